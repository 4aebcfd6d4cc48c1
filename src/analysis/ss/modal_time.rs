//! Time responses in modal coordinates: with A = X·Λ·X⁻¹ block diagonal
//! ([`ModalForm`]), z = X⁻¹x advances block by block, zₖ(t + h) = e^(Λₖh)·zₖ(t) + Fₖ·u with
//! Fₖ = ∫₀ʰ e^(Λₖτ)dτ·B̂ₖ (exact for a constant input), and y = Re(Ĉz) + D·u: O(Σ nₖ²) per
//! step instead of a dense n×n product. Used for step, impulse and initial-state responses
//! of models of order ≥ [`MODAL_MIN_ORDER`] when the modal form is safe and the states are
//! not asked for; otherwise [`super::time`]'s dense march.
//!
//! 1×1 blocks are marched as scalar *tracks*: blocks of equal λ share one free and one forced
//! track, and a conjugate pair with exactly conjugate data is one track counted twice — the
//! lattice's 256 states are 65 tracks for one channel.
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

/// A scalar track of the march: w(t) of one 1×1 block value λ — free (w(0) = 1, ẇ = λw) or
/// forced by the unit input (w(0) = 0, ẇ = λw + 1) — and what each output sees of it.
/// 1×1 blocks with the same λ share their tracks (their contributions are multiples of the
/// same two functions of t), and a track whose coefficients are exactly the conjugates of
/// another's is dropped, its partner counted twice (the outputs are real).
struct Track {
    lambda: C,
    forced: bool,
    /// Output coefficients (p), already doubled for a track that stands for a conjugate pair.
    coef: Vec<C>,
}

/// The tracks of the 1×1 blocks, and the indices of the larger blocks.
fn tracks(mf: &ModalForm, z0: &[C], input: Option<usize>) -> (Vec<Track>, Vec<usize>) {
    let p = mf.c.nrows();
    let mut out: Vec<Track> = Vec::new();
    let mut general = Vec::new();
    // group 1×1 blocks by their exact value (blocks of equal value are adjacent in the
    // second-order form; a map keeps the general case linear too)
    let mut index: std::collections::HashMap<(u64, u64, bool), usize> =
        std::collections::HashMap::new();
    for (bi, blk) in mf.blocks.iter().enumerate() {
        if blk.lambda.nrows() != 1 {
            general.push(bi);
            continue;
        }
        let (i, l) = (blk.start, blk.lambda[(0, 0)]);
        let parts = [
            (false, z0[i]),
            (true, input.map_or(C::new(0.0, 0.0), |col| mf.b[(i, col)])),
        ];
        for (forced, w) in parts {
            if w == C::new(0.0, 0.0) {
                continue;
            }
            let key = (l.re.to_bits(), l.im.to_bits(), forced);
            let k = *index.entry(key).or_insert_with(|| {
                out.push(Track {
                    lambda: l,
                    forced,
                    coef: vec![C::new(0.0, 0.0); p],
                });
                out.len() - 1
            });
            for (j, c) in out[k].coef.iter_mut().enumerate() {
                *c += mf.c[(j, i)] * w;
            }
        }
    }
    // conjugate partners: keep the upper track, twice
    let mut keep = vec![true; out.len()];
    for k in 0..out.len() {
        if !keep[k] || out[k].lambda.im <= 0.0 {
            continue;
        }
        let l = out[k].lambda.conj();
        let key = (l.re.to_bits(), l.im.to_bits(), out[k].forced);
        if let Some(&m) = index.get(&key)
            && keep[m]
            && out[m]
                .coef
                .iter()
                .zip(&out[k].coef)
                .all(|(a, b)| *a == b.conj())
        {
            keep[m] = false;
            out[k].coef.iter_mut().for_each(|c| *c *= 2.0);
        }
    }
    let tracks = out
        .into_iter()
        .zip(keep)
        .filter_map(|(t, k)| (k && t.coef.iter().any(|c| *c != C::new(0.0, 0.0))).then_some(t))
        .collect();
    (tracks, general)
}

/// The outputs (p × t.len()) from modal state `z0` under a unit step on `input` (or no input),
/// at the times `t` (finite, ≥ 0, any order).
pub(super) fn march(
    mf: &ModalForm,
    z0: Vec<C>,
    input: Option<usize>,
    t: &[f64],
) -> Result<Vec<Vec<f64>>> {
    let p = mf.c.nrows();
    let mut y = vec![vec![0.0; t.len()]; p];
    let bcol = |i: usize| input.map_or(C::new(0.0, 0.0), |col| mf.b[(i, col)]);
    let (tracks, general) = tracks(mf, &z0, input);
    // the state: the tracks' values and the general blocks' modal coordinates
    let w: Vec<C> = tracks
        .iter()
        .map(|tr| C::new(if tr.forced { 0.0 } else { 1.0 }, 0.0))
        .collect();
    let mut state = (w, z0);
    // coefficients by output, track-major for the inner loop
    let coef: Vec<Vec<C>> = (0..p)
        .map(|j| tracks.iter().map(|tr| tr.coef[j]).collect())
        .collect();
    let mut tmp = vec![C::new(0.0, 0.0); crate::numeric::linalg::modal::MAX_BLOCK];
    crate::numeric::march::march(
        t,
        &mut state,
        // the tracks' factors e^(λh) and (e^(λh) − 1)/λ, and the general blocks' maps
        |dt, _, _| {
            let mut e = Vec::with_capacity(tracks.len());
            let mut f = Vec::with_capacity(tracks.len());
            for tr in &tracks {
                let zz = tr.lambda * dt;
                e.push(zz.exp());
                f.push(if !tr.forced {
                    C::new(0.0, 0.0)
                } else if zz.norm() == 0.0 {
                    C::new(dt, 0.0)
                } else {
                    expm1(zz) / zz * dt
                });
            }
            let maps = general
                .iter()
                .map(|&bi| {
                    let blk = &mf.blocks[bi];
                    let k = blk.lambda.nrows();
                    let b: Vec<C> = (0..k).map(|r| bcol(blk.start + r)).collect();
                    block_map(&blk.lambda, &b, dt)
                })
                .collect::<Result<Vec<BlockMap>>>()?;
            Ok((e, f, maps))
        },
        |(e, f, maps), (w, z), _, _| {
            for ((wk, ek), fk) in w.iter_mut().zip(e).zip(f) {
                *wk = *ek * *wk + *fk;
            }
            for (&bi, mp) in general.iter().zip(maps) {
                let blk = &mf.blocks[bi];
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
            Ok(())
        },
        |i, ti, (w, z)| {
            for (j, row) in y.iter_mut().enumerate() {
                let mut acc = input.map_or(0.0, |col| mf.d[(j, col)]);
                for (c, wk) in coef[j].iter().zip(w) {
                    acc += c.re * wk.re - c.im * wk.im;
                }
                for &bi in &general {
                    let blk = &mf.blocks[bi];
                    let rows = blk.start..blk.start + blk.lambda.nrows();
                    for (r, zr) in rows.clone().zip(&z[rows]) {
                        acc += (mf.c[(j, r)] * zr).re;
                    }
                }
                if !acc.is_finite() {
                    let norm = w
                        .iter()
                        .chain(z.iter())
                        .map(|v| v.norm_sqr())
                        .sum::<f64>()
                        .sqrt();
                    return Err(LtiError::Diverged { t: ti, norm });
                }
                row[i] = acc;
            }
            Ok(())
        },
    )?;
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
