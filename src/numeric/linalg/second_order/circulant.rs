//! Symmetric circulant stiffness and damping (a periodic ring of identical masses and springs,
//! the seed's N-periodic lattice, §2.4.1.2 of the notes): their eigenvectors are the real
//! Fourier basis and their eigenvalues the discrete Fourier transform of the first column, so
//! the modes need no eigen solver, and every function of them (the blocks of e^(AT) and of
//! its integral) is again circulant: one column determines a block.
//!
//! # Recognition
//! A symmetric d×d matrix S (after the diagonal symmetrisation of [`super`]) is circulant when
//! every entry equals the first column's entry at the cyclic distance:
//! |s_ij − s_((i−j) mod d), 0| ≤ [`CIRCULANT_REL`]·max(|s_ij|, |s_((i−j) mod d), 0|) — exact up to
//! the rounding of the model's construction. The recognition in [`super::SecondOrder::detect`]
//! then checks the modes against the matrix itself: the residual ‖S·V − V·Λ‖ within
//! [`super::snap_tol`], as for the general eigen solver.
//!
//! # The modes
//! With c the first column, λ_p = Σₖ c_k·cos(2πkp/d), p = 0 … d − 1 (λ_p = λ_(d−p): the pairs
//! are degenerate), and the orthonormal real basis of the notes: 1/√d; √(2/d)·cos(2πpn/d) and
//! √(2/d)·sin(2πpn/d) for 0 < p < d/2; (−1)ⁿ/√d for p = d/2 when d is even (the Nyquist mode).

use nalgebra::{DMatrix, DMatrixViewMut};

/// Relative tolerance of the circulance test (the same as the symmetry test,
/// [`super::SYM_REL`]: the rounding of a model built in floating point).
pub const CIRCULANT_REL: f64 = super::SYM_REL;

/// True when the symmetric matrix `s` is circulant within [`CIRCULANT_REL`] (see the
/// [module docs](self)). Stops at the first entry that differs, so a non-circulant matrix
/// (a chain, a grid) is usually refused within its first two columns.
pub(super) fn is_circulant(s: &DMatrix<f64>) -> bool {
    let d = s.nrows();
    let close = |x: f64, y: f64| (x - y).abs() <= CIRCULANT_REL * x.abs().max(y.abs());
    let c = s.column(0);
    // column j is c rotated down by j: rows j.. hold c(0..d − j), rows ..j hold c(d − j..)
    (1..d).all(|j| {
        let col = s.column(j);
        (j..d).all(|i| close(col[i], c[i - j])) && (0..j).all(|i| close(col[i], c[i + d - j]))
    })
}

/// cos(2πm/d) and sin(2πm/d) for m = 0 … d − 1, each angle reflected into [0, π/4] before
/// the library functions are called (8m and d compared in integers: exact 0 and ±1 at the
/// quarter turns, the same rounding for the symmetric angles).
fn unit_roots(d: usize) -> (Vec<f64>, Vec<f64>) {
    let mut cs = vec![0.0; d];
    let mut sn = vec![0.0; d];
    // 2π·num/(8d): the angle (π/4)·(num/d)
    let eighth = |num: usize| 2.0 * std::f64::consts::PI * num as f64 / (8 * d) as f64;
    for m in 0..d {
        // θ = 2πm/d = (π/4)·(k + r/d): octant k, remainder r
        let (k, r) = ((8 * m) / d, (8 * m) % d);
        // (cos φ, sin φ) of φ = θ − (k/2)·(π/2), the angle within its quarter turn
        let (x, y) = if k % 2 == 0 {
            let a = eighth(r);
            (a.cos(), a.sin())
        } else {
            // φ = π/2 − (π/4)·(1 − r/d)
            let a = eighth(d - r);
            (a.sin(), a.cos())
        };
        let (c, s) = match k / 2 {
            0 => (x, y),
            1 => (-y, x),
            2 => (-x, -y),
            _ => (y, -x),
        };
        cs[m] = c;
        sn[m] = s;
    }
    (cs, sn)
}

/// The modes of the symmetric circulant stiffness `g` and damping `e` (both d×d): the
/// stiffness eigenvalues (ascending), the damping eigenvalues of the same modes, and the
/// orthonormal real Fourier basis (columns, in the same order) of the [module docs](self).
pub(super) fn fourier_modes(
    g: &DMatrix<f64>,
    e: &DMatrix<f64>,
) -> (Vec<f64>, Vec<f64>, DMatrix<f64>) {
    let d = g.nrows();
    let (cs, sn) = unit_roots(d);
    // Σₖ c_k·cos(2πkp/d), the index kp reduced mod d as it grows
    let spectrum = |s: &DMatrix<f64>, p: usize| -> f64 {
        let (mut sum, mut at) = (0.0, 0usize);
        for &ck in s.column(0).iter() {
            sum += ck * cs[at];
            at += p;
            if at >= d {
                at -= d;
            }
        }
        sum
    };
    // (stiffness, damping, frequency p, sine)
    let mut cols: Vec<(f64, f64, usize, bool)> = Vec::with_capacity(d);
    let mode = |p: usize| (spectrum(g, p), spectrum(e, p));
    let (l, y) = mode(0);
    cols.push((l, y, 0, false));
    for p in 1..d.div_ceil(2) {
        let (l, y) = mode(p);
        cols.push((l, y, p, false));
        cols.push((l, y, p, true));
    }
    if d % 2 == 0 {
        let (l, y) = mode(d / 2);
        cols.push((l, y, d / 2, false));
    }
    cols.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (one, two) = (1.0 / (d as f64).sqrt(), (2.0 / d as f64).sqrt());
    let mut v = DMatrix::<f64>::zeros(d, d);
    for (mut col, &(_, _, p, sine)) in v.column_iter_mut().zip(&cols) {
        // the mean and the Nyquist mode (cos(πn) = ±1) have norm √d, the pairs √(d/2)
        let (scale, table) = match (p == 0 || 2 * p == d, sine) {
            (true, _) => (one, &cs),
            (false, false) => (two, &cs),
            (false, true) => (two, &sn),
        };
        let mut at = 0usize;
        for x in col.iter_mut() {
            *x = scale * table[at];
            at += p;
            if at >= d {
                at -= d;
            }
        }
    }
    (
        cols.iter().map(|x| x.0).collect(),
        cols.iter().map(|x| x.1).collect(),
        v,
    )
}

/// The circulant d×d block with first column `col` into `out` (d×d): entry (i, j) is
/// col((i − j) mod d); each column of `out` is `col` rotated, two contiguous copies.
pub(super) fn fill(col: &[f64], out: &mut DMatrixViewMut<'_, f64>) {
    let d = col.len();
    for j in 0..d {
        let mut o = out.column_mut(j);
        o.rows_mut(j, d - j).copy_from_slice(&col[..d - j]);
        o.rows_mut(0, j).copy_from_slice(&col[d - j..]);
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // exact values at the quarter turns and the zero mode
    use super::*;

    fn circulant(c: &[f64]) -> DMatrix<f64> {
        let d = c.len();
        DMatrix::from_fn(d, d, |i, j| c[(i + d - j) % d])
    }

    #[test]
    fn unit_roots_are_accurate_and_exact_at_quarter_turns() {
        for d in [1, 2, 3, 4, 7, 8, 12, 128, 129] {
            let (cs, sn) = unit_roots(d);
            for m in 0..d {
                let a = 2.0 * std::f64::consts::PI * m as f64 / d as f64;
                assert!((cs[m] - a.cos()).abs() < 1e-15, "d={d} m={m}");
                assert!((sn[m] - a.sin()).abs() < 1e-15, "d={d} m={m}");
                if (4 * m) % d == 0 {
                    assert!(
                        cs[m] == cs[m].round() && sn[m] == sn[m].round(),
                        "d={d} m={m}"
                    );
                }
            }
        }
    }

    #[test]
    fn fourier_modes_diagonalise_symmetric_circulants() {
        // odd and even orders (the Nyquist mode), with and without a zero eigenvalue
        for c in [
            vec![2.0, -1.0, 0.0, 0.0, -1.0],
            vec![2.0, -1.0, 0.0, 0.0, 0.0, -1.0],
            vec![3.5, -1.0, 0.25, 0.7, 0.25, -1.0],
            vec![1.0],
            vec![2.0, -2.0],
        ] {
            let s = circulant(&c);
            assert!(is_circulant(&s));
            let (lam, gam, v) = fourier_modes(&s, &s);
            assert_eq!(lam, gam);
            let d = c.len();
            assert!(lam.windows(2).all(|w| w[0] <= w[1]));
            let r =
                &s * &v - &v * DMatrix::from_diagonal(&nalgebra::DVector::from_vec(lam.clone()));
            assert!(r.amax() < 1e-14, "{c:?}: residual {:.1e}", r.amax());
            let o = v.transpose() * &v - DMatrix::identity(d, d);
            assert!(o.amax() < 1e-15, "{c:?}: orthogonality {:.1e}", o.amax());
        }
        // the ring: λ = 4·sin²(πp/d), the translation exactly 0
        let ring = circulant(&[2.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]);
        let (lam, gam, _) = fourier_modes(&ring, &DMatrix::zeros(8, 8));
        assert!(gam.iter().all(|&y| y == 0.0));
        assert_eq!(lam[0], 0.0);
        assert!((lam[7] - 4.0).abs() < 1e-15);
    }

    #[test]
    fn non_circulants_are_refused() {
        // a chain (fixed ends): symmetric Toeplitz, not circulant
        let d = 6;
        let chain = DMatrix::from_fn(d, d, |i, j| match i.abs_diff(j) {
            0 => 2.0,
            1 => -1.0,
            _ => 0.0,
        });
        assert!(!is_circulant(&chain));
        // one spring perturbed by more than rounding
        let mut ring = circulant(&[2.0, -1.0, 0.0, 0.0, 0.0, -1.0]);
        ring[(2, 3)] = -1.0 - 1e-12;
        ring[(3, 2)] = -1.0 - 1e-12;
        assert!(!is_circulant(&ring));
        // within rounding it is accepted
        ring[(2, 3)] = -1.0 - 2.0 * f64::EPSILON;
        ring[(3, 2)] = -1.0 - 2.0 * f64::EPSILON;
        assert!(is_circulant(&ring));
    }

    #[test]
    fn fill_rotates_the_column() {
        let col = [1.0, 2.0, 3.0, 4.0];
        let mut m = DMatrix::zeros(4, 4);
        fill(&col, &mut m.view_mut((0, 0), (4, 4)));
        assert_eq!(m, circulant(&col));
    }
}
