//! Closed forms as text: `1 - (1 + t) e^(-t)`, `1.1547 e^(-0.5 t) cos(0.866025 t - 0.523599)`.

use std::fmt;

use super::form::ClosedForm;
use super::term::ClosedFormTerm;
use super::words::{cos_of, product, signed_sum, var_power};
use crate::fmt::fmt_num;

impl ClosedForm {
    /// The right-hand side as text, e.g. `1 - (1 + t) e^(-t)`; `0` when empty.
    pub fn expression(&self) -> String {
        if let Some(s) = &self.sequence {
            return s.expression();
        }
        let scale = self
            .terms
            .iter()
            .flat_map(|t| match t {
                ClosedFormTerm::Impulse { coefficient, .. } => vec![coefficient.abs()],
                ClosedFormTerm::Real { coefficients, .. } => {
                    coefficients.iter().map(|c| c.abs()).collect()
                }
                ClosedFormTerm::Oscillatory { amplitudes, .. } => {
                    amplitudes.iter().map(|c| c.abs()).collect()
                }
            })
            .fold(0.0, f64::max);
        // Coefficients at rounding level relative to the largest one are not shown.
        let noise = 8.0 * f64::EPSILON * scale;
        let mut pieces: Vec<(bool, String)> = Vec::new(); // (negative, magnitude text)
        for t in &self.terms {
            pieces.extend(term_pieces(t, noise));
        }
        if pieces.is_empty() {
            return "0".into();
        }
        let mut out = String::new();
        for (i, (neg, body)) in pieces.iter().enumerate() {
            match (i, neg) {
                (0, true) => out.push_str(&format!("-{body}")),
                (0, false) => out.push_str(body),
                (_, true) => out.push_str(&format!(" - {body}")),
                (_, false) => out.push_str(&format!(" + {body}")),
            }
        }
        out
    }

    /// `lhs = expression`, e.g. `formula("y_ss(t)")`; for a sequence the argument `(t)` of
    /// `lhs` reads `[k]` (`y(t)` becomes `y[k]`).
    pub fn formula(&self, lhs: &str) -> String {
        if self.sequence.is_some() {
            return format!("{} = {}", lhs.replace("(t)", "[k]"), self.expression());
        }
        if self.delay != 0.0 {
            let d = fmt_num(self.delay);
            return format!(
                "{lhs} = f(t - {d})·1(t - {d}), f(t) = {}",
                self.expression()
            );
        }
        format!("{lhs} = {}", self.expression())
    }
}

impl fmt::Display for ClosedForm {
    /// `y(t) = …`, or `y[k] = …` for a sequence (see [`ClosedForm::expression`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.formula("y(t)"))
    }
}

/// `t`, `t^2`, … for the power k (empty for k = 0).
fn t_power(k: usize) -> String {
    var_power("t", k)
}

/// `e^(-0.5 t)`, `e^(-t)`, `e^(2 t)`; empty for rate 0.
fn exp_factor(rate: f64) -> String {
    if rate == 0.0 {
        return String::new();
    }
    let r = match fmt_num(rate).as_str() {
        "1" => String::new(),
        "-1" => "-".into(),
        x => format!("{x} "),
    };
    format!("e^({r}t)")
}

/// `cos(0.866025 t - 0.523599)`, `cos(t)`.
fn cos_factor(omega: f64, phase: f64) -> String {
    cos_of(omega, phase, "t")
}

/// Signed text pieces of one group; coefficients with |c| ≤ noise are left out.
fn term_pieces(t: &ClosedFormTerm, noise: f64) -> Vec<(bool, String)> {
    match t {
        ClosedFormTerm::Impulse {
            derivative,
            coefficient,
        } => {
            if coefficient.abs() <= noise {
                return vec![];
            }
            let d = match derivative {
                0 => "δ(t)".to_string(),
                1 => "δ'(t)".to_string(),
                2 => "δ''(t)".to_string(),
                k => format!("δ^({k})(t)"),
            };
            vec![(*coefficient < 0.0, product(coefficient.abs(), &[d]))]
        }
        ClosedFormTerm::Real { pole, coefficients } => {
            let nz: Vec<(usize, f64)> = coefficients
                .iter()
                .copied()
                .enumerate()
                .filter(|(_, c)| c.abs() > noise)
                .collect();
            let e = exp_factor(*pole);
            if e.is_empty() || nz.len() <= 1 {
                // A pole at 0 (a polynomial in t) or a single power: flat pieces.
                return nz
                    .iter()
                    .map(|&(k, c)| (c < 0.0, product(c.abs(), &[t_power(k), e.clone()])))
                    .collect();
            }
            // (c0 + c1 t + …) e^(pt), with the sign of the first coefficient taken out.
            let neg = nz[0].1 < 0.0;
            let inner = signed_sum(
                nz.iter()
                    .map(|&(k, c)| {
                        let c = if neg { -c } else { c };
                        (c < 0.0, product(c.abs(), &[t_power(k)]))
                    })
                    .collect(),
            );
            vec![(neg, format!("({inner}) {e}"))]
        }
        ClosedFormTerm::Oscillatory {
            sigma,
            omega,
            amplitudes,
            phases,
        } => {
            let nz: Vec<(usize, f64, f64)> = amplitudes
                .iter()
                .zip(phases)
                .enumerate()
                .filter(|(_, (a, _))| a.abs() > noise)
                .map(|(k, (a, p))| (k, *a, *p))
                .collect();
            let e = exp_factor(*sigma);
            if e.is_empty() || nz.len() <= 1 {
                // Undamped (σ = 0) or a single power: flat pieces.
                return nz
                    .iter()
                    .map(|&(k, a, p)| {
                        (
                            a < 0.0,
                            product(a.abs(), &[t_power(k), e.clone(), cos_factor(*omega, p)]),
                        )
                    })
                    .collect();
            }
            let neg = nz[0].1 < 0.0;
            let inner = signed_sum(
                nz.iter()
                    .map(|&(k, a, p)| {
                        let a = if neg { -a } else { a };
                        (
                            a < 0.0,
                            product(a.abs(), &[t_power(k), cos_factor(*omega, p)]),
                        )
                    })
                    .collect(),
            );
            vec![(neg, format!("{e} ({inner})"))]
        }
    }
}
