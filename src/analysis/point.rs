//! A transfer function at one complex point: G(s₀) (G(z₀) in discrete time) of a SISO plant
//! or of every channel of a MIMO one, each through its factored form (the same engine as the
//! frequency response: a state-space channel is evaluated on its minimal realisation, so a mode
//! the channel does not see is no pole of it), the dead time e^(−s₀T) included.
//!
//! At a pole of G in lowest terms the value is infinite: an error names the pole. A point is at
//! a pole when |s₀ − p| ≤ 1e-9·max(1, |p|) (the poles are computed to about that accuracy or
//! better; a simple pole's digits are those of the roots).
//!
//! ```
//! use ltikit::TransferFunction;
//! use ltikit::analysis::point::value_at;
//! use num_complex::Complex64;
//! let f = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap().factored().unwrap();
//! let g = value_at(&f, Complex64::new(-1.0, 2.0)).unwrap();   // 1/(2j) = −0.5j
//! assert!((g - Complex64::new(0.0, -0.5)).norm() < 1e-15);
//! let e = value_at(&f, Complex64::new(-1.0, 0.0)).unwrap_err().to_string();
//! assert!(e.contains("pole -1"), "{e}");
//! ```

use num_complex::Complex64;

use crate::analysis::factored::Factored;
use crate::error::{LtiError, Result};
use crate::fmt::fmt_sig;
use crate::lti::{Model, StateSpace};

/// Relative distance within which a point is taken to be a pole.
pub const POLE_TOLERANCE: f64 = 1e-9;

/// G(s) of `f` at `s` (the dead time included).
///
/// Errors: `s` not finite; `s` at a pole of G in lowest terms (naming it).
pub fn value_at(f: &Factored, s: Complex64) -> Result<Complex64> {
    if !(s.re.is_finite() && s.im.is_finite()) {
        return Err(LtiError::invalid(format!(
            "the point {} is not finite",
            complex_text(s)
        )));
    }
    let var = f.domain().variable();
    if let Some(p) = f
        .reduced_poles()
        .iter()
        .find(|p| (s - p.value).norm() <= POLE_TOLERANCE * p.value.norm().max(1.0))
    {
        return Err(LtiError::invalid(format!(
            "{var} = {} is at the pole {} of G: G({var}) is infinite there",
            complex_text(s),
            complex_text(p.value)
        )));
    }
    let g = f.eval_delayed(s);
    if !(g.re.is_finite() && g.im.is_finite()) {
        return Err(LtiError::invalid(format!(
            "G({var}) overflows at {var} = {}",
            complex_text(s)
        )));
    }
    Ok(g)
}

/// G(s) of every channel of `model`: `values[output][input]` (a transfer function has one).
///
/// Errors: those of [`value_at`], naming the channel of a MIMO model; the factored core's.
///
/// ```
/// use ltikit::lti::Model;
/// use ltikit::StateSpace;
/// use ltikit::analysis::point::transfer_matrix;
/// use nalgebra::DMatrix;
/// use num_complex::Complex64;
/// // ẋ = −x + u, y = [x; 2x + u]: G = [1/(s+1); 2/(s+1) + 1]
/// let ss = StateSpace::new(DMatrix::from_element(1, 1, -1.0), DMatrix::from_element(1, 1, 1.0),
///     DMatrix::from_row_slice(2, 1, &[1.0, 2.0]), DMatrix::from_row_slice(2, 1, &[0.0, 1.0]))
///     .unwrap();
/// let g = transfer_matrix(&Model::Ss(ss), Complex64::new(1.0, 0.0)).unwrap();
/// assert!((g[1][0].re - 2.0).abs() < 1e-15);
/// ```
pub fn transfer_matrix(model: &Model, s: Complex64) -> Result<Vec<Vec<Complex64>>> {
    match model {
        Model::Tf(g) => Ok(vec![vec![value_at(&g.factored()?, s)?]]),
        Model::Ss(ss) => {
            let (m, p) = (ss.n_inputs(), ss.n_outputs());
            (0..p)
                .map(|o| {
                    (0..m)
                        .map(|i| {
                            let f = channel(ss, i, o)?;
                            value_at(&f, s).map_err(|e| in_channel(e, i, o, m, p))
                        })
                        .collect()
                })
                .collect()
        }
    }
}

/// A complex number as `-1+2j` (10 significant digits; `-1` when real).
///
/// ```
/// use ltikit::analysis::point::complex_text;
/// use num_complex::Complex64;
/// assert_eq!(complex_text(Complex64::new(-1.0, 2.0)), "-1+2j");
/// assert_eq!(complex_text(Complex64::new(0.5, -0.25)), "0.5-0.25j");
/// assert_eq!(complex_text(Complex64::new(3.0, 0.0)), "3");
/// ```
pub fn complex_text(z: Complex64) -> String {
    if z.im == 0.0 {
        return fmt_sig(z.re, 10);
    }
    let sign = if z.im < 0.0 { '-' } else { '+' };
    format!("{}{sign}{}j", fmt_sig(z.re, 10), fmt_sig(z.im.abs(), 10))
}

fn channel(ss: &StateSpace, input: usize, output: usize) -> Result<Factored> {
    Factored::from_state_space(&ss.channel(input, output)?)
}

/// An error of one channel of a MIMO model, the channel named.
fn in_channel(e: LtiError, i: usize, o: usize, m: usize, p: usize) -> LtiError {
    if m == 1 && p == 1 {
        return e;
    }
    LtiError::invalid(format!("channel input {} → output {}: {e}", i + 1, o + 1))
}
