//! Eigenvalues of a companion matrix without the general-purpose machinery: the companion
//! matrix is already upper Hessenberg, so the Householder reduction and the Schur vectors of
//! a general eigen-solver are wasted work. Balancing (Parlett–Reinsch, powers of two, exact)
//! keeps it Hessenberg; the Francis double-shift QR iteration (EISPACK `hqr`) then runs on it
//! in place with a hard iteration cap and exceptional shifts (which break the cycling of
//! sⁿ ± c, where nalgebra's uncapped iteration never ends). When the cap is reached the
//! caller falls back to [`crate::numeric::eigenvalues_checked`].
//!
//! Same backward stability as the general routine (orthogonal similarity transformations of
//! the balanced matrix); `Poly::roots` as a whole got 1.7–2× faster with it (degree 50:
//! 0.53 → 0.27 ms).

use num_complex::Complex64;

/// Iterations allowed per eigenvalue (EISPACK allows 30; exceptional shifts every 10).
const ITER_PER_EIGENVALUE: usize = 60;

/// Eigenvalues of the companion matrix of the monic polynomial sⁿ + a₁sⁿ⁻¹ + … + aₙ given
/// `tail` = [a₁, …, aₙ] (n ≥ 1, finite). Conjugate pairs are exact conjugates; real
/// eigenvalues have an imaginary part of exactly 0. `None` when the iteration does not
/// converge within the cap.
pub(super) fn companion_eigenvalues(tail: &[f64]) -> Option<Vec<Complex64>> {
    let n = tail.len();
    let mut a = companion_matrix(tail);
    balance(&mut a, n);
    hqr(&mut a, n)
}

/// The companion matrix of sⁿ + a₁sⁿ⁻¹ + … + aₙ, row-major upper Hessenberg: the first row
/// −a, ones on the subdiagonal.
fn companion_matrix(tail: &[f64]) -> Vec<f64> {
    let n = tail.len();
    let mut a = vec![0.0; n * n];
    for (j, &c) in tail.iter().enumerate() {
        a[j] = -c;
    }
    for i in 1..n {
        a[i * n + i - 1] = 1.0;
    }
    a
}

/// The companion matrix of sⁿ + a₁sⁿ⁻¹ + … + aₙ (`tail` = [a₁, …, aₙ], as
/// [`companion_eigenvalues`] builds it: the first row −a, ones below the diagonal) balanced,
/// D⁻¹·A·D (row-major), with D's diagonal, and its eigenvalues (`None` when the iteration
/// does not converge within the cap): one balancing for a caller that needs both the
/// eigenvalues and a well-scaled realisation (the ZOH of a transfer function).
pub(crate) fn balanced_companion(tail: &[f64]) -> (Vec<f64>, Vec<f64>, Option<Vec<Complex64>>) {
    let n = tail.len();
    let mut a = companion_matrix(tail);
    let d = balance(&mut a, n);
    let ev = hqr(&mut a.clone(), n);
    (a, d, ev)
}

/// Parlett–Reinsch balancing by powers of two (exact; keeps the Hessenberg form): A becomes
/// D⁻¹·A·D; returns D's diagonal.
fn balance(a: &mut [f64], n: usize) -> Vec<f64> {
    let mut d = vec![1.0; n];
    const RADIX: f64 = 2.0;
    const SQRDX: f64 = RADIX * RADIX;
    for _sweep in 0..200 {
        let mut done = true;
        for i in 0..n {
            let (mut c, mut r) = (0.0f64, 0.0f64);
            for j in 0..n {
                if j != i {
                    c += a[j * n + i].abs();
                    r += a[i * n + j].abs();
                }
            }
            if c == 0.0 || r == 0.0 {
                continue;
            }
            let s = c + r;
            let mut f = 1.0;
            let mut g = r / RADIX;
            while c < g && f < 1e300 {
                f *= RADIX;
                c *= SQRDX;
            }
            g = r * RADIX;
            while c > g && f > 1e-300 {
                f /= RADIX;
                c /= SQRDX;
            }
            if (c + r) / f < 0.95 * s {
                done = false;
                d[i] *= f;
                let gi = 1.0 / f;
                for j in 0..n {
                    a[i * n + j] *= gi;
                }
                for j in 0..n {
                    a[j * n + i] *= f;
                }
            }
        }
        if done {
            break;
        }
    }
    d
}

/// Eigenvalues of an upper Hessenberg matrix (row-major, destroyed) by the Francis
/// double-shift QR iteration (EISPACK `hqr`).
///
/// Longer than our ~120-line rule on purpose: it is the classical algorithm in one piece, so
/// that it can be checked line by line against EISPACK's `hqr` (deflation test, exceptional
/// shifts, the double-shift sweep share its loop state).
#[allow(clippy::many_single_char_names)] // the classical algorithm's names
fn hqr(a: &mut [f64], n: usize) -> Option<Vec<Complex64>> {
    let idx = |i: usize, j: usize| i * n + j;
    let mut wr = vec![0.0; n];
    let mut wi = vec![0.0; n];
    let mut anorm = 0.0;
    for i in 0..n {
        for j in i.saturating_sub(1)..n {
            anorm += a[idx(i, j)].abs();
        }
    }
    let eps = f64::EPSILON;
    let mut t = 0.0; // accumulated exceptional shifts
    let mut nn = n as isize - 1;
    let mut its = 0usize;
    let mut total = 0usize;
    let cap = ITER_PER_EIGENVALUE * n.max(1);
    while nn >= 0 {
        let nu = nn as usize;
        // Look for a single small subdiagonal element.
        let mut l = nu;
        while l > 0 {
            let mut s = a[idx(l - 1, l - 1)].abs() + a[idx(l, l)].abs();
            if s == 0.0 {
                s = anorm;
            }
            if a[idx(l, l - 1)].abs() <= eps * s {
                a[idx(l, l - 1)] = 0.0;
                break;
            }
            l -= 1;
        }
        let mut x = a[idx(nu, nu)];
        if l == nu {
            // one root found
            wr[nu] = x + t;
            wi[nu] = 0.0;
            nn -= 1;
            its = 0;
            continue;
        }
        let mut y = a[idx(nu - 1, nu - 1)];
        let mut w = a[idx(nu, nu - 1)] * a[idx(nu - 1, nu)];
        if l == nu - 1 {
            // two roots found
            let p = 0.5 * (y - x);
            let q = p * p + w;
            let z = q.abs().sqrt();
            x += t;
            if q >= 0.0 {
                let z = p + z.copysign(p);
                wr[nu - 1] = x + z;
                wr[nu] = if z != 0.0 { x - w / z } else { x + z };
                wi[nu - 1] = 0.0;
                wi[nu] = 0.0;
            } else {
                wr[nu - 1] = x + p;
                wr[nu] = x + p;
                wi[nu - 1] = z;
                wi[nu] = -z;
            }
            nn -= 2;
            its = 0;
            continue;
        }
        // no root found yet: iterate
        if total >= cap {
            return None;
        }
        if its > 0 && its % 10 == 0 {
            // exceptional shift
            t += x;
            for i in 0..=nu {
                a[idx(i, i)] -= x;
            }
            let s = a[idx(nu, nu - 1)].abs() + a[idx(nu - 1, nu - 2)].abs();
            x = 0.75 * s;
            y = x;
            w = -0.4375 * s * s;
        }
        its += 1;
        total += 1;
        // Form the shift and look for two consecutive small subdiagonal elements.
        let mut m = nu - 2;
        let (mut p, mut q, mut r);
        loop {
            let z = a[idx(m, m)];
            let rr = x - z;
            let ss = y - z;
            p = (rr * ss - w) / a[idx(m + 1, m)] + a[idx(m, m + 1)];
            q = a[idx(m + 1, m + 1)] - z - rr - ss;
            r = a[idx(m + 2, m + 1)];
            let s = p.abs() + q.abs() + r.abs();
            p /= s;
            q /= s;
            r /= s;
            if m == l {
                break;
            }
            let u = a[idx(m, m - 1)].abs() * (q.abs() + r.abs());
            let v = p.abs() * (a[idx(m - 1, m - 1)].abs() + z.abs() + a[idx(m + 1, m + 1)].abs());
            if u <= eps * v {
                break;
            }
            m -= 1;
        }
        if !(p.is_finite() && q.is_finite() && r.is_finite()) {
            return None;
        }
        for i in m + 2..=nu {
            a[idx(i, i - 2)] = 0.0;
            if i != m + 2 {
                a[idx(i, i - 3)] = 0.0;
            }
        }
        // Double QR step on rows l..nn and columns m..nn.
        let mut k = m;
        while k < nu {
            if k != m {
                p = a[idx(k, k - 1)];
                q = a[idx(k + 1, k - 1)];
                r = if k != nu - 1 {
                    a[idx(k + 2, k - 1)]
                } else {
                    0.0
                };
                x = p.abs() + q.abs() + r.abs();
                if x != 0.0 {
                    p /= x;
                    q /= x;
                    r /= x;
                }
            }
            let s = (p * p + q * q + r * r).sqrt().copysign(p);
            if s != 0.0 {
                if k == m {
                    if l != m {
                        a[idx(k, k - 1)] = -a[idx(k, k - 1)];
                    }
                } else {
                    a[idx(k, k - 1)] = -s * x;
                }
                p += s;
                x = p / s;
                y = q / s;
                let z = r / s;
                q /= p;
                r /= p;
                // row modification (rows k, k+1 and k+2, columns k..=nn), on row slices
                let (head, rest) = a[k * n..].split_at_mut(n);
                let (row1, rest) = rest.split_at_mut(n);
                let row0 = &mut head[k..=nu];
                let row1 = &mut row1[k..=nu];
                if k != nu - 1 {
                    let row2 = &mut rest[k..=nu];
                    for ((a0, a1), a2) in row0.iter_mut().zip(row1.iter_mut()).zip(row2) {
                        let pp = *a0 + q * *a1 + r * *a2;
                        *a2 -= pp * z;
                        *a1 -= pp * y;
                        *a0 -= pp * x;
                    }
                } else {
                    for (a0, a1) in row0.iter_mut().zip(row1.iter_mut()) {
                        let pp = *a0 + q * *a1;
                        *a1 -= pp * y;
                        *a0 -= pp * x;
                    }
                }
                // column modification (columns k, k+1 and k+2, rows l..=min(nn, k+3))
                let mmin = if nu < k + 3 { nu } else { k + 3 };
                let three = k != nu - 1;
                for i in l..=mmin {
                    let row = &mut a[i * n + k..i * n + k + if three { 3 } else { 2 }];
                    let mut pp = x * row[0] + y * row[1];
                    if three {
                        pp += z * row[2];
                        row[2] -= pp * r;
                    }
                    row[1] -= pp * q;
                    row[0] -= pp;
                }
            }
            k += 1;
        }
    }
    let out: Vec<Complex64> = wr
        .iter()
        .zip(&wi)
        .map(|(&re, &im)| Complex64::new(re, im))
        .collect();
    out.iter()
        .all(|z| z.re.is_finite() && z.im.is_finite())
        .then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sorted(mut v: Vec<Complex64>) -> Vec<Complex64> {
        v.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
        v
    }

    #[test]
    fn balanced_companion_is_the_similarity_it_reports() {
        // coefficients over 14 decades: the balancing moves them; D⁻¹·A·D rebuilt from the
        // returned diagonal is the returned matrix bit for bit (powers of two), and the
        // eigenvalues are companion_eigenvalues' own
        let tail = [1e3, 2e6, 3.5e7, 1e10, 4e11, 1e14, 2e14];
        let n = tail.len();
        let (a, d, ev) = balanced_companion(&tail);
        // powers of two, not all 1
        assert!(d.iter().all(|x| x.to_bits() & ((1u64 << 52) - 1) == 0));
        assert!(d.iter().any(|&x| x.to_bits() != 1f64.to_bits()));
        for i in 0..n {
            for j in 0..n {
                let raw = if i == 0 {
                    -tail[j]
                } else if j + 1 == i {
                    1.0
                } else {
                    0.0
                };
                assert_eq!(
                    a[i * n + j].to_bits(),
                    (raw / d[i] * d[j]).to_bits(),
                    "({i}, {j})"
                );
            }
        }
        assert_eq!(
            sorted(ev.unwrap()),
            sorted(companion_eigenvalues(&tail).unwrap())
        );
    }

    #[test]
    fn simple_cubic() {
        // (s + 1)(s + 2)(s + 3) = s³ + 6s² + 11s + 6
        let ev = sorted(companion_eigenvalues(&[6.0, 11.0, 6.0]).unwrap());
        for (z, want) in ev.iter().zip([-3.0, -2.0, -1.0]) {
            assert!((z.re - want).abs() < 1e-13 && z.im == 0.0, "{z}");
        }
    }

    #[test]
    #[allow(clippy::float_cmp)] // exact conjugates are the contract
    fn cyclic_companions_converge() {
        // sⁿ ± 1: nalgebra's uncapped Schur iteration never ends on these; the exceptional
        // shifts break the cycle. Every eigenvalue lies on the unit circle, pairs exact.
        for n in 2..=24 {
            for c in [1.0, -1.0] {
                let mut tail = vec![0.0; n];
                tail[n - 1] = c;
                let ev = companion_eigenvalues(&tail).unwrap_or_else(|| panic!("s^{n} + {c}"));
                assert_eq!(ev.len(), n);
                for z in &ev {
                    assert!((z.norm() - 1.0).abs() < 1e-12, "s^{n} + {c}: {z}");
                    if z.im != 0.0 {
                        assert!(ev.iter().any(|w| w.re == z.re && w.im == -z.im));
                    }
                }
            }
        }
    }

    #[test]
    fn matches_the_general_solver() {
        // A badly scaled order-8 plant denominator (coefficients 1 … 1e4).
        let tail = [
            20.4, 226.84, 1224.56, 4753.8, 8420.0, 15580.0, 8400.0, 10000.0,
        ];
        let ours = sorted(companion_eigenvalues(&tail).unwrap());
        let mut m = nalgebra::DMatrix::<f64>::zeros(8, 8);
        for (j, c) in tail.iter().enumerate() {
            m[(0, j)] = -c;
        }
        for i in 1..8 {
            m[(i, i - 1)] = 1.0;
        }
        let theirs = sorted(crate::numeric::eigenvalues(&m).unwrap());
        for (a, b) in ours.iter().zip(&theirs) {
            assert!((a - b).norm() < 1e-12 * b.norm(), "{a} vs {b}");
        }
    }
}
