//! The singular values σ₁ ≥ σ₂ ≥ … of G(jω) (G(e^(jωT)) in discrete time) over a frequency
//! grid: the sigma plot of a MIMO model (for a SISO model, |G(jω)|).
//!
//! The automatic grid ([`sigma_grid`]) is the Bode grid of the model's poles (the
//! eigenvalues of A: two decades beyond the extreme corners, dense at lightly damped pairs)
//! with the certified H∞ peak frequency added, so that the peak is drawn at its height.

use serde::Serialize;

use super::gain::GainEvaluator;
use crate::analysis::Factored;
use crate::analysis::freq::check_frequencies;
use crate::error::Result;
use crate::lti::StateSpace;
use crate::poly::Root;

/// Singular values of the frequency response on a grid.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SigmaResponse {
    /// Frequencies, rad/s.
    pub w: Vec<f64>,
    /// `sigma[k][i]`: the i-th largest singular value at `w[k]` (min(inputs, outputs) each).
    pub sigma: Vec<Vec<f64>>,
}

/// The singular values of G at each frequency of `w` (rad/s, ≥ 0).
///
/// Errors: a negative or non-finite frequency; more frequencies × values than
/// [`crate::limits::MAX_CHANNEL_VALUES`] or frequencies × states² than
/// [`crate::limits::MAX_SIGMA_WORK`]; those of the Hessenberg reduction.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::norms::sigma_response;
/// // two decoupled lags 1/(s + 1) and 2/(s + 2): σ = {2/|jω + 2|, 1/|jω + 1|}
/// let ss = StateSpace::new(
///     DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]),
///     DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 2.0]),
///     DMatrix::identity(2, 2),
///     DMatrix::zeros(2, 2),
/// ).unwrap();
/// let r = sigma_response(&ss, &[0.0, 2.0]).unwrap();
/// assert!((r.sigma[0][0] - 1.0).abs() < 1e-15 && (r.sigma[0][1] - 1.0).abs() < 1e-15);
/// assert!((r.sigma[1][0] - 0.5f64.sqrt()).abs() < 1e-15);
/// assert!((r.sigma[1][1] - 0.2f64.sqrt()).abs() < 1e-15);
/// ```
pub fn sigma_response(ss: &StateSpace, w: &[f64]) -> Result<SigmaResponse> {
    check_frequencies(w)?;
    crate::limits::CHANNEL_VALUES.check(
        "frequencies × singular values",
        w.len() as u128 * ss.n_inputs().min(ss.n_outputs()).max(1) as u128,
    )?;
    let n = ss.order() as u128;
    crate::limits::SIGMA_WORK.check("frequencies × states²", w.len() as u128 * n * n)?;
    let eval = GainEvaluator::new(ss)?;
    let sigma = w.iter().map(|&x| eval.singular_values(x)).collect();
    Ok(SigmaResponse {
        w: w.to_vec(),
        sigma,
    })
}

/// The automatic frequency grid of a sigma plot (see the [module docs](self)): `points`
/// log-spaced frequencies plus the extras at lightly damped poles and the H∞ (L∞) peak when
/// it is finite and inside the range.
///
/// Errors: `points` < 2 or beyond [`crate::limits::MAX_POINTS`]; the eigenvalue solver's.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::norms::sigma_grid;
/// let ss = StateSpace::new(
///     DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, -0.02]),
///     DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
///     DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
///     DMatrix::zeros(1, 1),
/// ).unwrap();
/// let w = sigma_grid(&ss, 100).unwrap();
/// assert_eq!((w[0], *w.last().unwrap()), (0.01, 100.0));
/// assert!(w.iter().any(|&x| (x - (1.0f64 - 2e-4).sqrt()).abs() < 1e-6));
/// ```
pub fn sigma_grid(ss: &StateSpace, points: usize) -> Result<Vec<f64>> {
    crate::analysis::grid::check_points(points)?;
    let poles: Vec<Root> = if ss.order() == 0 {
        Vec::new()
    } else {
        let st = crate::numeric::linalg::eigen_structure(&ss.a)?;
        st.clusters
            .iter()
            .map(|c| Root::new(c.value, c.algebraic))
            .collect()
    };
    let f = Factored::from_zpk(&[], &poles, 1.0)?.with_domain(ss.domain);
    let mut w = crate::analysis::auto_frequency_grid(&f, points)?;
    let (lo, hi) = (w[0], w[w.len() - 1]);
    if let Ok(peak) = super::linf_norm(ss)
        && peak.infinite.is_none()
        && peak.w > lo
        && peak.w < hi
    {
        w.push(peak.w);
        w.sort_by(f64::total_cmp);
        w.dedup();
    }
    Ok(w)
}
