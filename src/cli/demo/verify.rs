//! The report's evidence: every check computed at run time, with its worst error.

use anyhow::Result;

use super::md::Md;
use crate::analysis::{Factored, Margins, StepInfo};
use crate::fmt::fmt_sig;

/// One verified quantity.
pub struct Check {
    pub group: &'static str,
    pub what: String,
    pub error: f64,
    pub tolerance: f64,
}

/// All checks of a demo run.
#[derive(Default)]
pub struct Checks {
    pub rows: Vec<Check>,
}

impl Checks {
    /// Records a check; `error` is a relative (or stated) error, `tolerance` its bound.
    pub fn add(
        &mut self,
        group: &'static str,
        what: impl Into<String>,
        error: f64,
        tolerance: f64,
    ) {
        self.rows.push(Check {
            group,
            what: what.into(),
            error,
            tolerance,
        });
    }

    pub fn passed(&self) -> usize {
        self.rows.iter().filter(|c| c.error <= c.tolerance).count()
    }

    pub fn all_pass(&self) -> bool {
        self.passed() == self.rows.len()
    }

    /// The worst error of each group, in first-seen order.
    pub fn groups(&self) -> Vec<(&'static str, usize, f64, f64, bool)> {
        let mut out: Vec<(&'static str, usize, f64, f64, bool)> = Vec::new();
        for c in &self.rows {
            let ok = c.error <= c.tolerance;
            match out.iter_mut().find(|g| g.0 == c.group) {
                Some(g) => {
                    g.1 += 1;
                    g.2 = g.2.max(c.error);
                    g.3 = g.3.max(c.tolerance);
                    g.4 &= ok;
                }
                None => out.push((c.group, 1, c.error, c.tolerance, ok)),
            }
        }
        out
    }

    /// The step metrics hold on the exactly simulated response: y(t₁₀) = 0.1 y∞,
    /// y(t₉₀) = 0.9 y∞, |y(t_s) − y∞| = 0.02|y∞|, y(t_peak) = peak.
    pub fn step_metrics(&mut self, name: &str, g: &Factored, si: &StepInfo) -> Result<()> {
        let yinf = si.steady_state;
        let (Some(t10), Some(t90), Some(ts)) = (si.rise_start, si.rise_end, si.settling_time)
        else {
            anyhow::bail!("{name}: step metrics not computed ({:?})", si.notes);
        };
        let mut t = vec![t10, t90, ts];
        let peak = match (si.peak_time, si.peak) {
            (Some(tp), Some(p)) if tp.is_finite() => Some((tp, p)),
            _ => None,
        };
        if let Some((tp, _)) = peak {
            t.push(tp);
        }
        let y = g.step_response(&t)?.y;
        let mut err = (y[0] - 0.1 * yinf).abs().max((y[1] - 0.9 * yinf).abs());
        err = err.max(((y[2] - yinf).abs() - 0.02 * yinf.abs()).abs());
        if let Some((_, p)) = peak {
            err = err.max((y[3].abs() - p).abs());
        }
        self.add(
            "step metrics on the exact response (relative to |y∞|)",
            name.to_string(),
            err / yinf.abs(),
            1e-8,
        );
        Ok(())
    }

    /// Margins hold on G(jω), evaluated independently of the frequency kernel (Horner on the
    /// coefficients): |G(jω_gc)| = 1, φ(ω_pc) ≡ −180°, |G(jω_bw)| = 10^(−3/20)|G(0)|.
    pub fn margins(&mut self, name: &str, g: &Factored, m: &Margins) -> Result<()> {
        let mut w = Vec::new();
        if let Some(x) = m.gain_crossover {
            w.push(x);
        }
        if let Some(x) = m.phase_crossover {
            w.push(x);
        }
        if let Some(x) = m.bandwidth {
            w.push(x);
        }
        if w.is_empty() {
            return Ok(());
        }
        let f: Vec<num_complex::Complex64> = w
            .iter()
            .map(|&x| g.eval(num_complex::Complex64::new(0.0, x)))
            .collect();
        let mut k = 0;
        let mut err: f64 = 0.0;
        if m.gain_crossover.is_some() {
            err = err.max((f[k].norm() - 1.0).abs());
            k += 1;
        }
        if m.phase_crossover.is_some() {
            let ph = f[k].arg().to_degrees() + 180.0;
            err = err.max((ph - 360.0 * (ph / 360.0).round()).abs() / 180.0);
            k += 1;
        }
        if m.bandwidth.is_some() {
            let dc = g.dc_gain().unwrap_or(f64::NAN).abs();
            err = err.max((f[k].norm() / dc - 10f64.powf(-3.0 / 20.0)).abs());
        }
        self.add(
            "margins and bandwidth on G(jω) (relative)",
            name.to_string(),
            err,
            1e-9,
        );
        Ok(())
    }

    /// The verification section.
    pub fn render(&self, md: &mut Md) {
        md.h2("Verification");
        md.p(&format!(
            "Everything below was recomputed while this report was generated: the checks of \
             this report's own numbers. {} of {} checks pass{}. What the library claims of the \
             models in general — exact Jacobians against central differences, closed-form \
             eigenvalues, periods and normal modes, the elliptic solution of the rigid body, the \
             lattice's modes and motion, the seed's analytic second-order responses — is checked \
             by `cargo test` (the tests cite their references).",
            self.passed(),
            self.rows.len(),
            if self.all_pass() {
                ""
            } else {
                " — the failing ones are marked ✗"
            }
        ));
        let rows: Vec<Vec<String>> = self
            .groups()
            .iter()
            .map(|(g, n, worst, tol, ok)| {
                vec![
                    g.to_string(),
                    n.to_string(),
                    fmt_sig(*worst, 3),
                    fmt_sig(*tol, 3),
                    if *ok { "✓".into() } else { "✗".into() },
                ]
            })
            .collect();
        md.table(&["check", "cases", "worst error", "tolerance", ""], &rows);
        md.h3("All cases");
        let rows: Vec<Vec<String>> = self
            .rows
            .iter()
            .map(|c| {
                vec![
                    c.group.to_string(),
                    c.what.clone(),
                    fmt_sig(c.error, 3),
                    if c.error <= c.tolerance {
                        "✓".into()
                    } else {
                        "✗".into()
                    },
                ]
            })
            .collect();
        md.table(&["check", "case", "error", ""], &rows);
    }
}
