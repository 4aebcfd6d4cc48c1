//! Structure of a single-input single-output channel that the normwise rank decisions of the
//! system pencil cannot see: a first non-zero Markov parameter far below ε·‖A‖^k, which is
//! nonetheless exact because the realisation's zero entries keep it away from rounding.
//!
//! # Why
//! The pencil reduction ([`super::zeros`]) decides "D = 0" against (n + p)(n + m)·ε·‖[A B; C D]‖:
//! that is a statement about every system within that *normwise* distance, and a perturbation
//! of that size in an entry the model holds at exactly 0 can lower the relative degree. For a
//! damped lattice (force on particle 10, displacement of particle 20, viscous springs η = 0.01)
//! C·A^11·B = η¹⁰ = 1e-20 while ‖A‖ ~ 4: the reduction calls four more Markov parameters zero
//! and finds relative degree 16 with six spurious zeros, where the model has 12 and a 10-fold
//! zero at −1/η. Perturbations that keep the model's zeros at zero (entrywise relative ones,
//! the rounding of its entries) do not change C·A^k·B beyond k·n·ε·|C|·|A|^k·|B|, which is the
//! bound of its rounding error too (Higham, *Accuracy and Stability of Numerical Algorithms*,
//! §3.5, matrix–vector products). So:
//!
//! # Method
//! 1. [`componentwise_relative_degree`]: r is the first k with |C·A^(k−1)·B| above
//!    (n + 1)²·ε·|C|·|A|^(k−1)·|B| (the reduction's relative tolerance, applied to the
//!    magnitudes the parameter is a sum of); computed on the given realisation (the minimal
//!    one, formed by dense orthogonal similarities, has lost the zero entries: its C·A^k·B are
//!    rounding noise of ~1e-16 up to k = 14 for the lattice).
//! 2. [`refined_channel_zeros`]: the reduction forced to that r on the given realisation
//!    ([`super::zeros::siso_zeros_of_degree`]) gives its n − r invariant zeros. They include
//!    the modes removed by the minimal realisation (for a single channel
//!    det P(s) = det(sI − A)·G(s), so the invariant zeros are the transmission zeros and the
//!    removed modes); the computed zero nearest to each removed mode is dropped. A_f −
//!    B_f·D_f⁻¹·C_f is far from normal when D_f is that small, so each remaining zero is
//!    refined by Newton's method on G(s) of the minimal realisation (a Hessenberg solve for G
//!    and G′); a zero whose iteration reaches G's rounding level is simple and refined, the
//!    rest (a multiple zero, computed as a circle of ~ε^(1/m) relative radius, where Newton
//!    converges linearly at best) are grouped by proximity and reported as their mean with the
//!    group's size, which is accurate (the sum of a cluster's eigenvalues is a trace, perturbed
//!    to first order only).

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::freqresp::HessenbergResponse;
use crate::error::Result;
use crate::numeric::balance::{exponent, ldexp};

/// Newton steps allowed per zero.
const NEWTON_STEPS: usize = 40;
/// Members of a multiple zero are grouped when within this relative distance: an m-fold zero
/// is computed over a circle of radius ~|z|·(n·ε)^(1/m) (0.06 for m = 10, n = 128).
const GROUP_REL: f64 = 0.15;
/// Refined values within this relative distance are the same zero.
const SAME_REL: f64 = 1e-8;

/// Relative degree r and first non-zero Markov parameter C·A^(r−1)·B (D when r = 0) of a
/// single-input single-output realisation, decided componentwise (see the [module
/// docs](self)). `None` when every parameter up to k = n is zero to its bound (G ≡ 0) or the
/// system is not SISO.
pub(crate) fn componentwise_relative_degree(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
) -> Option<(usize, f64)> {
    let n = a.nrows();
    if b.ncols() != 1 || c.nrows() != 1 || d.shape() != (1, 1) {
        return None;
    }
    if d[(0, 0)] != 0.0 {
        return Some((0, d[(0, 0)]));
    }
    let rel = super::zeros::default_tol(n, 1, 1);
    let abs_a = a.abs();
    let abs_c = c.abs();
    let mut v = b.clone();
    let mut w = b.abs();
    // v and w carry the common factor 2^scale (kept in range, exactly)
    let mut scale: i32 = 0;
    for k in 1..=n {
        let m = (c * &v)[(0, 0)];
        let bound = (&abs_c * &w)[(0, 0)];
        if !(m.is_finite() && bound.is_finite()) {
            return None;
        }
        if bound > 0.0 && m.abs() > rel * bound {
            let gain = ldexp(m, scale);
            return gain.is_finite().then_some((k, gain));
        }
        v = a * v;
        w = &abs_a * w;
        let e = exponent(w.max())?;
        v.iter_mut().for_each(|x| *x = ldexp(*x, -e));
        w.iter_mut().for_each(|x| *x = ldexp(*x, -e));
        scale = scale.saturating_add(e);
    }
    None
}

/// The transmission zeros of a SISO channel of relative degree `r` (decided by
/// [`componentwise_relative_degree`] on (a, b, c)), with multiplicities: invariant zeros of
/// the given realisation, less the `removed` modes, refined on `response` (the minimal
/// realisation's G), see the [module docs](self). `None` when the forced reduction does not
/// apply or the count does not come out as `n_min − r`.
pub(crate) fn refined_channel_zeros(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    r: usize,
    removed: &[Complex64],
    response: &HessenbergResponse,
) -> Result<Option<Vec<(Complex64, usize)>>> {
    let Some(mut raw) = super::zeros::siso_zeros_of_degree(a, b, c, r)? else {
        return Ok(None);
    };
    let n_min = response.order();
    if n_min + removed.len() != a.nrows() || n_min < r {
        return Ok(None);
    }
    for &v in removed {
        let Some(k) =
            (0..raw.len()).min_by(|&i, &j| (raw[i] - v).norm().total_cmp(&(raw[j] - v).norm()))
        else {
            return Ok(None);
        };
        raw.swap_remove(k);
    }
    if raw.len() != n_min - r {
        return Ok(None);
    }
    let mut refined: Vec<Complex64> = Vec::new();
    let mut unresolved: Vec<Complex64> = Vec::new();
    for &z in &raw {
        match newton(response, z) {
            Some(v) => refined.push(v),
            None => unresolved.push(z),
        }
    }
    let mut out = group(&refined, SAME_REL);
    out.extend(group(&unresolved, GROUP_REL));
    Ok(Some(out))
}

/// Newton's method on G from `z0`: the point where G is at its rounding level (|G| ≤ 8ε·the
/// terms summed for it) or the step is below 4ε·|z|; `None` if neither within
/// [`NEWTON_STEPS`].
fn newton(response: &HessenbergResponse, z0: Complex64) -> Option<Complex64> {
    let mut z = z0;
    for _ in 0..NEWTON_STEPS {
        let (g, dg, terms) = response.eval_siso_with_derivative(z)?;
        if g.norm() <= 8.0 * f64::EPSILON * terms {
            return Some(z);
        }
        let step = g / dg;
        if !(step.re.is_finite() && step.im.is_finite()) {
            return None;
        }
        z -= step;
        if step.norm() <= 4.0 * f64::EPSILON * z.norm() {
            return Some(z);
        }
    }
    None
}

/// Values linked (single linkage) when within `rel`·max(|zᵢ|, |zⱼ|, 1)·… of each other,
/// each group as its mean (real when the group is closed under conjugation) and size.
fn group(values: &[Complex64], rel: f64) -> Vec<(Complex64, usize)> {
    let n = values.len();
    let mut label: Vec<usize> = (0..n).collect();
    fn root(label: &mut [usize], mut k: usize) -> usize {
        while label[k] != k {
            label[k] = label[label[k]];
            k = label[k];
        }
        k
    }
    for i in 0..n {
        for j in i + 1..n {
            let size = values[i]
                .norm()
                .max(values[j].norm())
                .max(f64::MIN_POSITIVE);
            if (values[i] - values[j]).norm() <= rel * size {
                let (ri, rj) = (root(&mut label, i), root(&mut label, j));
                label[ri] = rj;
            }
        }
    }
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut slot = vec![usize::MAX; n];
    for k in 0..n {
        let r = root(&mut label, k);
        if slot[r] == usize::MAX {
            slot[r] = groups.len();
            groups.push(Vec::new());
        }
        groups[slot[r]].push(k);
    }
    groups
        .iter()
        .map(|g| {
            let sum: Complex64 = g.iter().map(|&k| values[k]).sum();
            let mean = sum / g.len() as f64;
            let self_conjugate = g.len() > 1
                && g.iter().all(|&k| {
                    g.iter().any(|&j| {
                        (values[j] - values[k].conj()).norm() <= f64::EPSILON * values[k].norm()
                    })
                });
            let mean = if self_conjugate {
                Complex64::new(mean.re, 0.0)
            } else {
                mean
            };
            (mean, g.len())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_markov_parameter_far_below_the_norm_is_seen() {
        // A chain x₁ → x₂ → x₃ with the middle link 1e-20 and a large decoupled entry:
        // C·B = 0, C·A·B = 0, C·A²·B = 1e-20 exactly (the path's product), ‖A‖ = 1e3.
        let mut a = DMatrix::zeros(4, 4);
        a[(1, 0)] = 1.0;
        a[(2, 1)] = 1e-20;
        a[(3, 3)] = -1e3;
        a[(0, 3)] = 5.0;
        let b = DMatrix::from_column_slice(4, 1, &[1.0, 0.0, 0.0, 0.0]);
        let c = DMatrix::from_row_slice(1, 4, &[0.0, 0.0, 1.0, 0.0]);
        let d = DMatrix::zeros(1, 1);
        let (r, g) = componentwise_relative_degree(&a, &b, &c, &d).unwrap();
        assert_eq!(r, 3);
        assert!((g - 1e-20).abs() <= f64::EPSILON * 1e-20, "{g:e}");
        // the normwise reduction cannot see it
        let rd = super::super::relative_degree(&a, &b, &c, &d, None).unwrap();
        assert_ne!(rd.r, Some(3));
    }

    #[test]
    fn rounding_noise_is_not_a_markov_parameter() {
        // G = 1/(s + 1)² behind a dense orthogonal similarity: C·B is rounding noise
        // (~1e-17 of |C|·|B|), the relative degree is 2 and the gain 1.
        let a0 = DMatrix::from_row_slice(2, 2, &[-1.0, 1.0, 0.0, -1.0]);
        let (s, co) = (0.6f64, 0.8f64);
        let q = DMatrix::from_row_slice(2, 2, &[co, -s, s, co]);
        let a = q.transpose() * a0 * &q;
        let b = q.transpose() * DMatrix::from_column_slice(2, 1, &[0.0, 1.0]);
        let c = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]) * &q;
        let (r, g) = componentwise_relative_degree(&a, &b, &c, &DMatrix::zeros(1, 1)).unwrap();
        assert_eq!(r, 2);
        assert!((g - 1.0).abs() < 1e-15);
        assert!(
            componentwise_relative_degree(&a, &b, &DMatrix::zeros(1, 2), &DMatrix::zeros(1, 1))
                .is_none()
        );
    }

    #[test]
    fn grouping_takes_means_and_keeps_conjugate_groups_real() {
        let v = [
            Complex64::new(-1.0, 0.05),
            Complex64::new(-1.0, -0.05),
            Complex64::new(5.0, 0.0),
        ];
        let g = group(&v, 0.15);
        assert_eq!(
            g,
            vec![
                (Complex64::new(-1.0, 0.0), 2),
                (Complex64::new(5.0, 0.0), 1)
            ]
        );
    }
}
