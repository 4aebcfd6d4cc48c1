//! Time responses in modal coordinates: with A = X·Λ·X⁻¹ block diagonal
//! ([`ModalForm`]), z = X⁻¹x advances block by block, zₖ(t + h) = e^(Λₖh)·zₖ(t) + Fₖ·u with
//! Fₖ = ∫₀ʰ e^(Λₖτ)dτ·B̂ₖ (exact for a constant input), and y = Re(Ĉz) + D·u: O(Σ nₖ²) per
//! step instead of a dense n×n product. Used for step, impulse and initial-state responses
//! of models of order ≥ [`MODAL_MIN_ORDER`] when the modal form is safe and the states are
//! not asked for; otherwise [`super::time`]'s dense march.
//!
//! Block maps: e^(λh) and h·φ₁(λh)·b̂ (φ₁(z) = (e^z − 1)/z with e^z − 1 formed without
//! cancellation) for 1×1 blocks; the exponential of the augmented block [[Λh, b̂h], [0, 0]]
//! (Taylor series after scaling, then squaring) for larger ones.

use nalgebra::DMatrix;
use num_complex::Complex64 as C;

use crate::error::{LtiError, Result};
use crate::numeric::linalg::modal::ModalForm;

/// Smallest order for which the step, impulse and initial responses go the modal way (below
/// it the dense march is as fast).
pub const MODAL_MIN_ORDER: usize = 32;

/// e^z − 1 without cancellation for small |z|.
fn expm1(z: C) -> C {
    let (x, y) = (z.re, z.im);
    let s = (0.5 * y).sin();
    C::new(x.exp_m1() * y.cos() - 2.0 * s * s, x.exp() * y.sin())
}

/// e^M of a small complex matrix: Taylor to 18 terms after scaling ‖M‖ below 1/2, then
/// squaring.
fn expm_small(m: &DMatrix<C>) -> Result<DMatrix<C>> {
    let n = m.nrows();
    let norm: f64 = m.iter().map(|z| z.norm()).sum();
    if !norm.is_finite() {
        return Err(LtiError::invalid("a modal block's exponential overflows"));
    }
    let sq = if norm > 0.5 {
        (norm / 0.5).log2().ceil().min(1100.0) as i32
    } else {
        0
    };
    let a = m.map(|z| z * 2f64.powi(-sq));
    let mut term = DMatrix::<C>::identity(n, n);
    let mut sum = term.clone();
    for k in 1..=18 {
        term = (&term * &a).map(|z| z / k as f64);
        sum += &term;
    }
    for _ in 0..sq {
        sum = &sum * &sum;
    }
    Ok(sum)
}

/// The maps of one block over a step h: E = e^(Λh) and F = ∫₀ʰ e^(Λτ)dτ·b (b zero for a free
/// response).
struct BlockMap {
    e: DMatrix<C>,
    f: Vec<C>,
}

fn block_map(lambda: &DMatrix<C>, b: &[C], h: f64) -> Result<BlockMap> {
    let k = lambda.nrows();
    if k == 1 {
        let z = lambda[(0, 0)] * h;
        let phi1 = if z.norm() == 0.0 {
            C::new(1.0, 0.0)
        } else {
            expm1(z) / z
        };
        return Ok(BlockMap {
            e: DMatrix::from_element(1, 1, z.exp()),
            f: vec![b[0] * phi1 * h],
        });
    }
    let mut m = DMatrix::<C>::zeros(k + 1, k + 1);
    for i in 0..k {
        for j in 0..k {
            m[(i, j)] = lambda[(i, j)] * h;
        }
        m[(i, k)] = b[i] * h;
    }
    let e = expm_small(&m)?;
    Ok(BlockMap {
        e: e.view((0, 0), (k, k)).into_owned(),
        f: (0..k).map(|i| e[(i, k)]).collect(),
    })
}

/// The outputs (p × t.len()) from modal state `z0` under a unit step on `input` (or no input),
/// at the times `t` (finite, ≥ 0, any order).
pub(super) fn march(
    mf: &ModalForm,
    mut z: Vec<C>,
    input: Option<usize>,
    t: &[f64],
) -> Result<Vec<Vec<f64>>> {
    let p = mf.c.nrows();
    let mut order: Vec<usize> = (0..t.len()).collect();
    order.sort_by(|&i, &j| t[i].total_cmp(&t[j]));
    let mut y = vec![vec![0.0; t.len()]; p];
    let bcol = |i: usize| input.map_or(C::new(0.0, 0.0), |col| mf.b[(i, col)]);
    let mut maps: Vec<BlockMap> = Vec::new();
    let mut map_h = f64::NAN;
    let mut now = 0.0;
    let mut tmp = vec![C::new(0.0, 0.0); crate::numeric::linalg::modal::MAX_BLOCK];
    for &i in &order {
        let ti = t[i];
        let dt = ti - now;
        if dt > 0.0 {
            let tol = 8.0 * f64::EPSILON * ti.max(dt);
            // a new step length (NaN at the start compares false: no map yet)
            if map_h.is_nan() || (map_h - dt).abs() > tol {
                maps = mf
                    .blocks
                    .iter()
                    .map(|blk| {
                        let k = blk.lambda.nrows();
                        let b: Vec<C> = (0..k).map(|r| bcol(blk.start + r)).collect();
                        block_map(&blk.lambda, &b, dt)
                    })
                    .collect::<Result<_>>()?;
                map_h = dt;
            }
            for (blk, mp) in mf.blocks.iter().zip(&maps) {
                let (i0, k) = (blk.start, blk.lambda.nrows());
                for (r, slot) in tmp.iter_mut().enumerate().take(k) {
                    let mut acc = mp.f[r];
                    for c in 0..k {
                        acc += mp.e[(r, c)] * z[i0 + c];
                    }
                    *slot = acc;
                }
                z[i0..i0 + k].copy_from_slice(&tmp[..k]);
            }
            now = ti;
        }
        for (j, row) in y.iter_mut().enumerate() {
            let mut acc = input.map_or(0.0, |col| mf.d[(j, col)]);
            for (cz, zz) in mf.c.row(j).iter().zip(&z) {
                acc += (cz * zz).re;
            }
            if !acc.is_finite() {
                let norm = z.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
                return Err(LtiError::Diverged { t: ti, norm });
            }
            row[i] = acc;
        }
    }
    Ok(y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scalar_maps_are_exact_closed_forms() {
        // λ = −2, h = 0.1: E = e^(−0.2), F = (1 − e^(−0.2))/2
        let m = block_map(
            &DMatrix::from_element(1, 1, C::new(-2.0, 0.0)),
            &[C::new(1.0, 0.0)],
            0.1,
        )
        .unwrap();
        assert!((m.e[(0, 0)].re - (-0.2f64).exp()).abs() < 1e-16);
        assert!((m.f[0].re - (1.0 - (-0.2f64).exp()) / 2.0).abs() < 1e-16);
        // a 2×2 Jordan block [−1 1; 0 −1] with b = (0, 1): F = (1 − (1 + h)e^(−h), 1 − e^(−h))
        let lam = DMatrix::from_row_slice(
            2,
            2,
            &[
                C::new(-1.0, 0.0),
                C::new(1.0, 0.0),
                C::new(0.0, 0.0),
                C::new(-1.0, 0.0),
            ],
        );
        let h = 0.7f64;
        let m = block_map(&lam, &[C::new(0.0, 0.0), C::new(1.0, 0.0)], h).unwrap();
        assert!((m.f[0].re - (1.0 - (1.0 + h) * (-h).exp())).abs() < 1e-15);
        assert!((m.f[1].re - (1.0 - (-h).exp())).abs() < 1e-15);
        assert!((m.e[(0, 1)].re - h * (-h).exp()).abs() < 1e-15);
    }
}
