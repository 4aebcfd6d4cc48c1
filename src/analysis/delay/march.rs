//! The delayed closed loop over long horizons: a Chebyshev collocation march of the delay
//! equation, interval by interval (the method of steps without the alternating sum).
//!
//! # Method
//! The loop L (proper, rational) is realised as (A, B, C, D) of dimension n (the cascade of
//! real sections of its reduced factors, [`StateSpace::from_zpk`]). In negative unity feedback
//! around the dead time T the loop's input is v(t) = e(t − T) = r(t − T) − y(t − T), so on the
//! interval \[kT, (k+1)T\] v is the control error of the previous interval, already known (0 on
//! the first): x′ = A x + B v, y = C x + D v, x continuous across the intervals.
//!
//! Each interval is cut into m equal sub-intervals of length h = T/m, and on each the state is
//! a polynomial of degree N at the N + 1 Chebyshev–Gauss–Lobatto nodes τᵢ, collocated in the
//! integration form X = x₀ + h·S(A X + B v) (S the Chebyshev integration matrix, ∫ from 0 to
//! τᵢ of the interpolant). The linear system (size n(N + 1)) is the same on every
//! sub-interval: it is solved once for the solution operators (x₀, v) ↦ (y at the nodes,
//! x at the end), and the march is then two matrix–vector products per sub-interval. The
//! nodes of a sub-interval shifted by T are the nodes of the same sub-interval one interval
//! later, so v needs no interpolation. Values at other times come from barycentric Lagrange
//! interpolation on the sub-interval's nodes; the kinks kT are sub-interval ends, so every
//! sub-interval holds a smooth piece.
//!
//! An impulse r = δ enters L at T and makes the state jump by B; for a bi-proper L the δ of
//! D·v in y returns one delay later: the jump at kT is (−D)^(k−1)·B (the δ terms of y are
//! excluded from the values, as in [`crate::analysis::delay::steps`]).
//!
//! # Accuracy
//! N = [`MARCH_DEGREE`]; m = ⌈ρT/[`MARCH_STEP`]⌉ with ρ the largest modulus of the reduced
//! poles of L and of the input's poles, so that ρh ≤ 8, where the Chebyshev coefficients of
//! e^(λτ) have fallen to ~1e-17 by degree 32 (stiff modes get as many sub-intervals as they
//! need). The estimated error (`estimated_error`) is the largest of the last two Chebyshev
//! coefficients of y over the sub-intervals (what degree N leaves unresolved) plus the rounding
//! 64·eps·max|y|. Measured (`tests/delay_march.rs`): the PI/FOPDT loop of the method of steps
//! agrees with its exact closed form to 1e-14 over 10 delays; K/(s + a) with T = 0.1 over 1000
//! delays within 1e-13 of the final value and the exact decay.
//!
//! # Limits
//! At most [`MAX_MARCH_INTERVALS`] intervals (⌊t_end/T⌋ + 1) and [`MAX_MARCH_NODES`] nodes
//! (intervals × m × (N + 1)): bounded time and memory (8 bytes a node).

use nalgebra::{DMatrix, DVector};

use crate::analysis::delay::checks::check_loop;
use crate::analysis::factored::Factored;
use crate::analysis::input::Input;
use crate::error::{LtiError, Result};
use crate::lti::StateSpace;

/// The polynomial degree N on each sub-interval (N + 1 Chebyshev–Gauss–Lobatto nodes).
pub const MARCH_DEGREE: usize = 32;
/// The largest ρh (ρ the fastest pole's modulus, h the sub-interval) a sub-interval takes.
pub const MARCH_STEP: f64 = 8.0;
/// The most intervals (delays within the horizon, plus the first) the march covers.
pub const MAX_MARCH_INTERVALS: usize = 100_000;
/// The most collocation nodes (intervals × sub-intervals × (N + 1)) the march stores.
pub const MAX_MARCH_NODES: usize = 4_000_000;
/// The largest collocation system n(N + 1) (n the order of L).
const MAX_SYSTEM: usize = 1_700;

/// The closed-loop response of a delayed loop as a piecewise polynomial: y at the
/// Chebyshev–Gauss–Lobatto nodes of every sub-interval of \[0, (K + 1)T\].
#[derive(Debug, Clone, PartialEq)]
pub struct DelayMarch {
    /// The dead time T (s).
    pub delay: f64,
    /// The intervals \[kT, (k+1)T\] covered, k = 0 … intervals − 1.
    pub intervals: usize,
    /// The sub-intervals per interval (m).
    pub sub: usize,
    /// The estimated error of the values (see the [module docs](self)).
    pub estimated_error: f64,
    /// The nodes on \[0, 1\] (τ₀ = 0 … τ_N = 1).
    nodes: Vec<f64>,
    /// The barycentric weights.
    weights: Vec<f64>,
    /// y at the nodes, sub-interval after sub-interval ((N + 1) values each).
    y: Vec<f64>,
    /// The estimated error of each sub-interval.
    tail: Vec<f64>,
}

/// Chebyshev–Gauss–Lobatto nodes on \[0, 1\], increasing.
fn cgl_nodes(n: usize) -> Vec<f64> {
    (0..=n)
        .map(|i| 0.5 * (1.0 - (std::f64::consts::PI * i as f64 / n as f64).cos()))
        .collect()
}

/// The matrix of node values → Chebyshev coefficients (on x = 2τ − 1, x_j = −cos(πj/N)).
fn coefficient_matrix(n: usize) -> DMatrix<f64> {
    let pi = std::f64::consts::PI;
    DMatrix::from_fn(n + 1, n + 1, |k, j| {
        // x_j = cos(π(N − j)/N): T_k(x_j) = cos(kπ(N − j)/N)
        let t = (pi * (k * (n - j)) as f64 / n as f64).cos();
        let cj = if j == 0 || j == n { 0.5 } else { 1.0 };
        let ck = if k == 0 || k == n { 0.5 } else { 1.0 };
        2.0 / n as f64 * cj * ck * t
    })
}

/// S: node values of f → ∫₀^τᵢ p(s) ds, p the interpolant on \[0, 1\].
fn integration_matrix(n: usize, nodes: &[f64]) -> DMatrix<f64> {
    let coef = coefficient_matrix(n);
    // antiderivative coefficients (degree n + 1) of Σ c_k T_k in x, then ×1/2 for τ
    let mut anti = DMatrix::<f64>::zeros(n + 2, n + 1);
    for k in 0..=n {
        match k {
            0 => anti[(1, 0)] += 1.0,
            1 => {
                // x²/2 = (T₂ + T₀)/4; constants cancel against F(−1)
                anti[(2, 1)] += 0.25;
            }
            _ => {
                anti[(k + 1, k)] += 1.0 / (2.0 * (k + 1) as f64);
                anti[(k - 1, k)] -= 1.0 / (2.0 * (k - 1) as f64);
            }
        }
    }
    let integ = anti * coef; // (n + 2) × (n + 1): coefficients of F
    let cheb = |x: f64, m: usize| -> Vec<f64> {
        let mut t = vec![0.0; m];
        t[0] = 1.0;
        if m > 1 {
            t[1] = x;
        }
        for k in 2..m {
            t[k] = 2.0 * x * t[k - 1] - t[k - 2];
        }
        t
    };
    let at_minus_one = cheb(-1.0, n + 2);
    DMatrix::from_fn(n + 1, n + 1, |i, j| {
        let x = 2.0 * nodes[i] - 1.0;
        let ti = cheb(x, n + 2);
        let s: f64 = (0..n + 2)
            .map(|k| (ti[k] - at_minus_one[k]) * integ[(k, j)])
            .sum();
        0.5 * s
    })
}

/// The solution operators of one sub-interval.
struct Operators {
    /// y at the nodes from x₀ ((N + 1) × n) and from v ((N + 1) × (N + 1)).
    py: DMatrix<f64>,
    qy: DMatrix<f64>,
    /// x at the end from x₀ (n × n) and from v (n × (N + 1)).
    pe: DMatrix<f64>,
    qe: DMatrix<f64>,
}

fn operators(ss: &StateSpace, h: f64, s: &DMatrix<f64>) -> Result<Operators> {
    let n = ss.a.nrows();
    let np = s.nrows();
    let dim = n * np;
    let mut m = DMatrix::<f64>::identity(dim, dim);
    let mut rhs = DMatrix::<f64>::zeros(dim, n + np);
    for i in 0..np {
        for a in 0..n {
            rhs[(i * n + a, a)] = 1.0;
        }
        for j in 0..np {
            let sij = h * s[(i, j)];
            if sij == 0.0 {
                continue;
            }
            for a in 0..n {
                for b in 0..n {
                    m[(i * n + a, j * n + b)] -= sij * ss.a[(a, b)];
                }
                rhs[(i * n + a, n + j)] += sij * ss.b[(a, 0)];
            }
        }
    }
    let z = m.lu().solve(&rhs).ok_or_else(|| LtiError::Undefined {
        what: "the collocation march of the delayed loop".into(),
        reason: "its collocation system is singular".into(),
    })?;
    let d = ss.d[(0, 0)];
    let mut py = DMatrix::zeros(np, n);
    let mut qy = DMatrix::zeros(np, np);
    for i in 0..np {
        for a in 0..n {
            let c = ss.c[(0, a)];
            if c == 0.0 {
                continue;
            }
            for b in 0..n {
                py[(i, b)] += c * z[(i * n + a, b)];
            }
            for j in 0..np {
                qy[(i, j)] += c * z[(i * n + a, n + j)];
            }
        }
        qy[(i, i)] += d;
    }
    let last = (np - 1) * n;
    let pe = z.view((last, 0), (n, n)).into_owned();
    let qe = z.view((last, n), (n, np)).into_owned();
    Ok(Operators { py, qy, pe, qe })
}

impl DelayMarch {
    /// March the closed loop of `l` (continuous, proper) with dead time `delay` > 0 for the
    /// `input` over 0 ≤ t ≤ `horizon` (see the [module docs](self)).
    ///
    /// Errors: a discrete-time or improper loop, a delay that is not a finite number > 0, a
    /// horizon that is not finite or negative, an invalid input, more than
    /// [`MAX_MARCH_INTERVALS`] intervals or [`MAX_MARCH_NODES`] nodes
    /// ([`LtiError::LimitExceeded`]), values that overflow (an unstable loop).
    ///
    /// ```
    /// use ltikit::analysis::{Factored, Input, delay::DelayMarch};
    /// use ltikit::Root;
    /// use num_complex::Complex64 as C;
    /// // L = 1/(s + 1), T = 1: y = 1 − e^(−(t − 1)) on [1, 2].
    /// let l = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 1)], 1.0).unwrap();
    /// let m = DelayMarch::new(&l, 1.0, &Input::Step, 1.5).unwrap();
    /// assert_eq!(m.eval(0.5), 0.0);
    /// assert!((m.eval(1.5) - (1.0 - (-0.5f64).exp())).abs() < 1e-14);
    /// assert!(m.estimated_error < 1e-13);
    /// ```
    pub fn new(l: &Factored, delay: f64, input: &Input, horizon: f64) -> Result<DelayMarch> {
        check_loop(l, delay, input, horizon)?;
        let ratio = (horizon / delay).floor();
        if ratio.is_nan() || ratio >= MAX_MARCH_INTERVALS as f64 {
            return Err(limit(
                format!(
                    "the intervals of the delay march (the horizon {} s over the delay {} s)",
                    crate::fmt::fmt_sig(horizon, 6),
                    crate::fmt::fmt_sig(delay, 6)
                ),
                if ratio.is_finite() {
                    ratio as u128 + 1
                } else {
                    u128::MAX
                },
                MAX_MARCH_INTERVALS,
                "intervals",
                "MAX_MARCH_INTERVALS",
            ));
        }
        // ratio in [0, MAX_MARCH_INTERVALS)
        let intervals = interval_index(horizon.max(0.0), delay, ratio.max(0.0) as usize) + 1;
        let rho = l
            .reduced_poles()
            .iter()
            .map(|p| p.value.norm())
            .chain(input.poles().iter().map(|p| p.0.norm()))
            .fold(0.0, f64::max);
        let sub_f = (rho * delay / MARCH_STEP).ceil().max(1.0);
        let nn = MARCH_DEGREE + 1;
        let nodes_needed = sub_f * intervals as f64 * nn as f64;
        if nodes_needed.is_nan() || nodes_needed > MAX_MARCH_NODES as f64 {
            return Err(limit(
                format!(
                    "the nodes of the delay march ({intervals} intervals × {} sub-intervals \
                     (fastest pole {} rad/s against the delay {} s) × {nn}; shorten the \
                     horizon)",
                    sub_f,
                    crate::fmt::fmt_sig(rho, 3),
                    crate::fmt::fmt_sig(delay, 6)
                ),
                if nodes_needed.is_finite() {
                    nodes_needed as u128
                } else {
                    u128::MAX
                },
                MAX_MARCH_NODES,
                "nodes",
                "MAX_MARCH_NODES",
            ));
        }
        // sub_f ≤ MAX_MARCH_NODES
        let sub = sub_f as usize;
        let ss = StateSpace::from_zpk(l.reduced_zeros(), l.reduced_poles(), l.gain())?;
        let n = ss.a.nrows();
        if n * nn > MAX_SYSTEM {
            return Err(limit(
                format!("the collocation system of the delay march (order {n} × {nn} nodes)"),
                (n * nn) as u128,
                MAX_SYSTEM,
                "unknowns",
                "the march's system size",
            ));
        }
        let nodes = cgl_nodes(MARCH_DEGREE);
        let mut weights: Vec<f64> = (0..nn)
            .map(|i| if i % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        weights[0] *= 0.5;
        weights[MARCH_DEGREE] *= 0.5;
        let h = delay / sub as f64;
        let s = integration_matrix(MARCH_DEGREE, &nodes);
        let op = operators(&ss, h, &s)?;
        let coef = coefficient_matrix(MARCH_DEGREE);
        let tail_rows = [
            coef.row(MARCH_DEGREE - 1).into_owned(),
            coef.row(MARCH_DEGREE).into_owned(),
        ];
        let d = ss.d[(0, 0)];
        let total = intervals * sub;
        let mut y = vec![0.0; total * nn];
        let mut tail = vec![0.0; total];
        let mut x = DVector::<f64>::zeros(n);
        let mut v = DVector::<f64>::zeros(nn);
        let mut jump_weight = 1.0f64;
        let mut ymax = 0.0f64;
        for k in 0..intervals {
            if k >= 1 && *input == Input::Impulse {
                for a in 0..n {
                    x[a] += jump_weight * ss.b[(a, 0)];
                }
                jump_weight *= -d;
            }
            for j in 0..sub {
                let g = k * sub + j;
                if k == 0 {
                    v.fill(0.0);
                } else {
                    // e on the same sub-interval one interval earlier
                    let gp = g - sub;
                    let (a, b) = sub_bounds(delay, sub, k - 1, j);
                    for i in 0..nn {
                        let t = a + (b - a) * nodes[i];
                        v[i] = input.eval(t) - y[gp * nn + i];
                    }
                }
                let yv = &op.py * &x + &op.qy * &v;
                x = &op.pe * &x + &op.qe * &v;
                let slot = &mut y[g * nn..(g + 1) * nn];
                slot.copy_from_slice(yv.as_slice());
                let mut local = 0.0f64;
                for &val in slot.iter() {
                    local = local.max(val.abs());
                }
                if !local.is_finite() || x.iter().any(|v| !v.is_finite()) {
                    return Err(LtiError::Overflow {
                        what: format!(
                            "the delayed closed loop's response at t = {} s",
                            crate::fmt::fmt_sig(k as f64 * delay, 6)
                        ),
                        reason: " (the loop is unstable at this delay; shorten the horizon)".into(),
                    });
                }
                ymax = ymax.max(local);
                tail[g] = tail_rows
                    .iter()
                    .map(|r| (r * &yv)[(0, 0)].abs())
                    .fold(0.0, f64::max)
                    + 64.0 * f64::EPSILON * local;
            }
        }
        let estimated_error = tail.iter().copied().fold(0.0, f64::max) + 64.0 * f64::EPSILON * ymax;
        Ok(DelayMarch {
            delay,
            intervals,
            sub,
            estimated_error,
            nodes,
            weights,
            y,
            tail,
        })
    }

    /// The end of the validity: (intervals)·T.
    pub fn valid_until(&self) -> f64 {
        self.intervals as f64 * self.delay
    }

    /// The bounds \[a, b\] of sub-interval g.
    pub(crate) fn bounds(&self, g: usize) -> (f64, f64) {
        sub_bounds(self.delay, self.sub, g / self.sub, g % self.sub)
    }

    /// The sub-interval holding t ≥ 0 (the last one for t at or beyond the end).
    pub(crate) fn piece_of(&self, t: f64) -> usize {
        let guess = (t / self.delay).floor();
        let g = if guess.is_nan() || guess < 0.0 {
            0
        } else if guess > self.intervals as f64 {
            self.intervals
        } else {
            guess as usize
        };
        let k = interval_index(t.max(0.0), self.delay, g).min(self.intervals - 1);
        let (a, _) = sub_bounds(self.delay, self.sub, k, 0);
        let h = self.delay / self.sub as f64;
        let mut j = (((t - a) / h).floor().max(0.0) as usize).min(self.sub - 1);
        while j > 0 && sub_bounds(self.delay, self.sub, k, j).0 > t {
            j -= 1;
        }
        while j + 1 < self.sub && sub_bounds(self.delay, self.sub, k, j + 1).0 <= t {
            j += 1;
        }
        k * self.sub + j
    }

    /// y on sub-interval g at t (the interpolant, extended to its closed ends).
    pub(crate) fn value_in(&self, g: usize, t: f64) -> f64 {
        let nn = self.nodes.len();
        let (a, b) = self.bounds(g);
        let s = ((t - a) / (b - a)).clamp(0.0, 1.0);
        barycentric(&self.nodes, &self.weights, &self.y[g * nn..(g + 1) * nn], s)
    }

    /// y′ at the nodes of sub-interval g.
    pub(crate) fn node_derivatives(&self, g: usize) -> Vec<f64> {
        let nn = self.nodes.len();
        let (a, b) = self.bounds(g);
        let vals = &self.y[g * nn..(g + 1) * nn];
        let w = &self.weights;
        let x = &self.nodes;
        (0..nn)
            .map(|i| {
                let mut sum = 0.0;
                for j in 0..nn {
                    if j != i {
                        let dij = w[j] / w[i] / (x[i] - x[j]);
                        sum += dij * (vals[j] - vals[i]);
                    }
                }
                sum / (b - a)
            })
            .collect()
    }

    /// The interpolant of the derivative on sub-interval g from its node values.
    pub(crate) fn derivative_in(&self, g: usize, dnodes: &[f64], t: f64) -> f64 {
        let (a, b) = self.bounds(g);
        let s = ((t - a) / (b - a)).clamp(0.0, 1.0);
        barycentric(&self.nodes, &self.weights, dnodes, s)
    }

    /// y(t) for 0 ≤ t < (intervals)·T (at a kink the value just after it); 0 for t < 0; NaN for
    /// NaN and beyond.
    pub fn eval(&self, t: f64) -> f64 {
        if t.is_nan() || t >= self.valid_until() {
            return f64::NAN;
        }
        if t < 0.0 {
            return 0.0;
        }
        self.value_in(self.piece_of(t), t)
    }

    /// The estimated error at t (that of its sub-interval).
    pub fn error_at(&self, t: f64) -> f64 {
        if t.is_nan() {
            return f64::NAN;
        }
        if t < 0.0 {
            return 0.0;
        }
        self.tail[self.piece_of(t)]
    }
}

/// \[a, b\] of sub-interval j of interval k (the interval's ends exactly kT and (k + 1)T).
fn sub_bounds(delay: f64, sub: usize, k: usize, j: usize) -> (f64, f64) {
    let start = k as f64 * delay;
    let end = (k + 1) as f64 * delay;
    let h = (end - start) / sub as f64;
    let a = if j == 0 { start } else { start + j as f64 * h };
    let b = if j + 1 == sub {
        end
    } else {
        start + (j + 1) as f64 * h
    };
    (a, b)
}

/// The barycentric interpolant (second form) at s.
fn barycentric(x: &[f64], w: &[f64], f: &[f64], s: f64) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..x.len() {
        let d = s - x[i];
        if d == 0.0 {
            return f[i];
        }
        let c = w[i] / d;
        num += c * f[i];
        den += c;
    }
    num / den
}

/// The k with kT ≤ t < (k + 1)T from a guess within one of it.
pub(crate) fn interval_index(t: f64, delay: f64, guess: usize) -> usize {
    let mut k = guess;
    while k > 0 && k as f64 * delay > t {
        k -= 1;
    }
    while (k + 1) as f64 * delay <= t {
        k += 1;
    }
    k
}

fn limit(field: String, value: u128, max: usize, unit: &str, name: &str) -> LtiError {
    LtiError::LimitExceeded {
        field,
        value,
        max: max as u64,
        unit: unit.into(),
        limit: name.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integration_matrix_integrates_polynomials() {
        let n = MARCH_DEGREE;
        let x = cgl_nodes(n);
        let s = integration_matrix(n, &x);
        for p in 0..=n {
            let f = DVector::from_iterator(n + 1, x.iter().map(|&t| t.powi(p as i32)));
            let got = &s * f;
            for i in 0..=n {
                let want = x[i].powi(p as i32 + 1) / (p + 1) as f64;
                assert!((got[i] - want).abs() < 1e-13, "p = {p}, i = {i}");
            }
        }
    }
}
