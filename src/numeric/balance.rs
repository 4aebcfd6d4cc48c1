//! Overflow-safe balancing and power-of-two scaling of real square matrices and of the system
//! matrix of a state-space model.
//!
//! nalgebra's `balance_parlett_reinsch` loops for ever when a squared row or column norm
//! overflows (an entry of 1e200 is enough: `inf / 2 == inf`). `balance` makes the same
//! decisions (the modified Parlett–Reinsch method with 2-norms of whole rows and columns,
//! James, Langou & Lowery 2014) but computes every norm with a power-of-two scale, so nothing
//! overflows; its radix loops and its sweeps are capped, and the diagonal factors stay within
//! 2^±[`MAX_SCALE_EXP`]. On matrices whose squared norms do not over- or underflow it gives
//! bitwise the same result as nalgebra's routine (power-of-two scaling commutes with rounding).
//!
//! `ldexp` and `exponent` scale by exact powers of two; eigenvalue solvers use them to
//! bring a matrix's entries into a range where no intermediate can overflow.

use nalgebra::DMatrix;

/// Sweeps allowed in `balance`. Balancing converges in a handful of sweeps in practice (each
/// accepted step lowers the sum of squared norms by ≥ 5 %); the cap only bounds the time.
pub const MAX_BALANCE_SWEEPS: usize = 100;

/// The diagonal factors of `balance` stay within 2^±`MAX_SCALE_EXP`, so that scaling the
/// input and output matrices of a state-space model by them cannot overflow either.
pub const MAX_SCALE_EXP: i32 = 512;

/// x · 2^e, exactly unless the result over- or underflows (then ±∞, or rounded to the
/// subnormal range / 0, like C's `ldexp`).
pub(crate) fn ldexp(x: f64, e: i32) -> f64 {
    // Steps of at most 2^±1000 keep each factor a normal number.
    let mut x = x;
    let mut e = e;
    while e > 1000 {
        x *= pow2(1000);
        e -= 1000;
        if !x.is_finite() || x == 0.0 {
            return x;
        }
    }
    while e < -1000 {
        x *= pow2(-1000);
        e += 1000;
        if x == 0.0 {
            return x;
        }
    }
    x * pow2(e)
}

/// 2^e for −1022 ≤ e ≤ 1023 (a normal number, built from its bits).
fn pow2(e: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&e));
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// The binary exponent e of |x| (2^e ≤ |x| < 2^(e+1)), for finite non-zero x; subnormals
/// included. `None` for 0 and non-finite values.
pub(crate) fn exponent(x: f64) -> Option<i32> {
    if x == 0.0 || !x.is_finite() {
        return None;
    }
    let bits = x.abs().to_bits();
    let biased = (bits >> 52) as i32;
    if biased > 0 {
        Some(biased - 1023)
    } else {
        // Subnormal: the position of the leading mantissa bit.
        let mant = bits & ((1u64 << 52) - 1);
        Some(-1074 + 63 - mant.leading_zeros() as i32)
    }
}

/// Smallest and largest binary exponents of the non-zero entries; `None` for a zero matrix.
/// Entries must be finite.
pub(crate) fn exponent_range(values: impl Iterator<Item = f64>) -> Option<(i32, i32)> {
    values.filter_map(exponent).fold(None, |acc, e| match acc {
        None => Some((e, e)),
        Some((lo, hi)) => Some((lo.min(e), hi.max(e))),
    })
}

/// 2-norm of the values without overflow or harmful underflow: scaled by the power of two just
/// above the largest magnitude, which is exact (bitwise the naive `sqrt(Σx²)` whenever that
/// neither overflows nor underflows). Returns (norm, largest magnitude, smallest non-zero
/// magnitude).
fn scaled_norm(values: impl Iterator<Item = f64> + Clone) -> (f64, f64, f64) {
    // One pass first: when every non-zero magnitude is within 2^±450 no square or partial
    // sum (at most 2^905 · count) over- or underflows, and the naive sum is bitwise the
    // scaled one (scaling by a power of two commutes with rounding).
    let (mut big, mut small, mut sum) = (0.0f64, f64::INFINITY, 0.0f64);
    for x in values.clone() {
        let a = x.abs();
        big = big.max(a);
        if a != 0.0 {
            small = small.min(a);
        }
        sum += x * x;
    }
    const SAFE_HI: f64 = 2.9e135; // < 2^450
    const SAFE_LO: f64 = 3.5e-136; // > 2^-450
    if big == 0.0 {
        return (0.0, 0.0, 0.0);
    }
    if big < SAFE_HI && small > SAFE_LO && sum.is_finite() {
        return (sum.sqrt(), big, small);
    }
    scaled_norm_slow(values)
}

/// [`scaled_norm`] with the power-of-two scaling (entries near the ends of the f64 range).
fn scaled_norm_slow(values: impl Iterator<Item = f64> + Clone) -> (f64, f64, f64) {
    let big = values.clone().fold(0.0f64, |m, x| m.max(x.abs()));
    let small = values
        .clone()
        .filter(|x| *x != 0.0)
        .fold(f64::INFINITY, |m, x| m.min(x.abs()));
    let Some(e) = exponent(big) else {
        return (0.0, 0.0, 0.0);
    };
    let sum: f64 = values
        .map(|x| {
            let y = ldexp(x, -e);
            y * y
        })
        .sum();
    (ldexp(sum.sqrt(), e), big, small)
}

/// Balances `m` in place by a diagonal similarity with powers of two, m ← D⁻¹·m·D (exact: no
/// rounding — a step that would push an entry into the subnormal range or overflow is not
/// taken), and returns the diagonal of D. See the [module docs](self).
///
/// The input must be square and finite; the result is finite.
pub(crate) fn balance(m: &mut DMatrix<f64>) -> Vec<f64> {
    let n = m.nrows();
    if n != m.ncols() || n < 2 {
        return vec![1.0; n];
    }
    balance_leading(m, n)
}

/// Balances the system matrix S = \[A B; C 0\] of a state-space model by a diagonal
/// similarity of the states only, (D⁻¹AD, D⁻¹B, CD) with powers of two (exact), so that each
/// state's row of \[A B\] and column of \[A; C\] have comparable norms (SLICOT `TB01ID`,
/// which `TB01PD` runs before its staircases). Returns the diagonal of D. Rank decisions
/// made relative to a norm (staircases, pencil reductions) then see every state at its own
/// scale: an input entry of 5e8 feeding a state whose coupling to the others is 1e-18 no
/// longer hides that coupling below the rounding of ‖\[A B\]‖.
///
/// The inputs must be finite with consistent sizes; the results are finite.
pub(crate) fn balance_system(
    a: &mut DMatrix<f64>,
    b: &mut DMatrix<f64>,
    c: &mut DMatrix<f64>,
) -> Vec<f64> {
    let n = a.nrows();
    let (m, p) = (b.ncols(), c.nrows());
    if n == 0 || a.ncols() != n || b.nrows() != n || c.ncols() != n {
        return vec![1.0; n];
    }
    let mut s = DMatrix::<f64>::zeros(n + p, n + m);
    s.view_mut((0, 0), (n, n)).copy_from(a);
    s.view_mut((0, n), (n, m)).copy_from(b);
    s.view_mut((n, 0), (p, n)).copy_from(c);
    let d = balance_leading(&mut s, n);
    a.copy_from(&s.view((0, 0), (n, n)));
    b.copy_from(&s.view((0, n), (n, m)));
    c.copy_from(&s.view((n, 0), (p, n)));
    d
}

/// The balancing loop on the leading k rows and columns of `m` (k ≤ its sizes): row i is
/// divided and column i multiplied by the same power of two, for i < k only.
fn balance_leading(m: &mut DMatrix<f64>, n: usize) -> Vec<f64> {
    let mut d = vec![1.0; n];
    let mut d_exp = vec![0i32; n];
    if n > m.nrows().min(m.ncols()) {
        return d;
    }
    for _sweep in 0..MAX_BALANCE_SWEEPS {
        let mut converged = true;
        #[allow(clippy::needless_range_loop)] // i indexes the matrix, d_exp and the row at once
        for i in 0..n {
            let (n_col, col_max, col_min) = scaled_norm(m.column(i).iter().copied());
            let (n_row, row_max, row_min) = scaled_norm(m.row(i).iter().copied());
            if n_col == 0.0 || n_row == 0.0 {
                continue;
            }
            // Work with the norms scaled by a common power of two: the squares below can then
            // neither overflow nor (for the larger one) underflow.
            let Some(e) = exponent(n_col.max(n_row)) else {
                continue;
            };
            let mut c = ldexp(n_col, -e);
            let mut r = ldexp(n_row, -e);
            let s = c * c + r * r;
            let mut k = 0i32;
            // At most ~1100 halvings separate two finite norms; the caps are never binding.
            for _ in 0..1100 {
                if c >= r / 2.0 {
                    break;
                }
                c *= 2.0;
                r /= 2.0;
                k += 1;
            }
            for _ in 0..1100 {
                if c < r * 2.0 {
                    break;
                }
                c /= 2.0;
                r *= 2.0;
                k -= 1;
            }
            if k == 0 || c * c + r * r >= 0.95 * s {
                continue;
            }
            let new_exp = d_exp[i] + k;
            // Keep the similarity exact: no entry may overflow or lose bits to underflow.
            if new_exp.abs() > MAX_SCALE_EXP
                || !ldexp(col_max, k).is_finite()
                || !ldexp(row_max, -k).is_finite()
                || (k < 0 && ldexp(col_min, k) < f64::MIN_POSITIVE)
                || (k > 0 && ldexp(row_min, -k) < f64::MIN_POSITIVE)
            {
                continue;
            }
            converged = false;
            d_exp[i] = new_exp;
            m.column_mut(i).apply(|x| *x = ldexp(*x, k));
            m.row_mut(i).apply(|x| *x = ldexp(*x, -k));
        }
        if converged {
            break;
        }
    }
    for (di, &e) in d.iter_mut().zip(&d_exp) {
        *di = ldexp(1.0, e);
    }
    d
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // exact powers of two are the contract
    use super::*;

    /// `balance` on a worked example (an internal kernel: a unit test, not a doctest).
    #[test]
    #[allow(clippy::float_cmp)] // exact values are meant
    fn balance_example() {
        use crate::numeric::balance::balance;
        use nalgebra::DMatrix;
        // nalgebra's own balancing never returns on this matrix (its squared norm overflows).
        let mut m = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -1e200]);
        let d = balance(&mut m);
        assert_eq!(d.len(), 2);
        assert!(m.iter().all(|x| x.is_finite()));
    }

    /// `exponent` on a worked example (an internal kernel: a unit test, not a doctest).
    #[test]
    #[allow(clippy::float_cmp)] // exact values are meant
    fn exponent_example() {
        use crate::numeric::balance::exponent;
        assert_eq!(exponent(1.0), Some(0));
        assert_eq!(exponent(-0.75), Some(-1));
        assert_eq!(exponent(f64::MIN_POSITIVE / 4.0), Some(-1024));
        assert_eq!(exponent(0.0), None);
    }

    /// `ldexp` on a worked example (an internal kernel: a unit test, not a doctest).
    #[test]
    #[allow(clippy::float_cmp)] // exact values are meant
    fn ldexp_example() {
        use crate::numeric::balance::ldexp;
        assert_eq!(ldexp(3.0, 4), 48.0);
        assert_eq!(ldexp(1.0, -1074), f64::from_bits(1));
        assert_eq!(ldexp(1e300, 100), f64::INFINITY);
    }

    #[test]
    fn same_as_nalgebra_on_ordinary_matrices() {
        // A badly scaled companion matrix and a random-looking one: bitwise nalgebra's result.
        let tail = [20.4, 226.84, 1224.56, 4753.8, 8420.0, 15580.0, 8400.0, 1e4];
        let mut a = DMatrix::<f64>::zeros(8, 8);
        for (j, c) in tail.iter().enumerate() {
            a[(0, j)] = -c;
        }
        for i in 1..8 {
            a[(i, i - 1)] = 1.0;
        }
        let b = DMatrix::from_fn(5, 5, |i, j| {
            ((i * 7 + j * 3) % 11) as f64 * 10f64.powi(i as i32 - j as i32)
        });
        for m in [a, b] {
            let mut ours = m.clone();
            let mut theirs = m.clone();
            let d = balance(&mut ours);
            let dn = nalgebra::linalg::balancing::balance_parlett_reinsch(&mut theirs);
            assert_eq!(ours, theirs);
            assert_eq!(d.as_slice(), dn.as_slice());
        }
    }

    #[test]
    fn overflowing_norms_terminate_and_stay_exact() {
        for big in [1e200, 1e300, f64::MAX] {
            let m0 =
                DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.0, 0.0, 0.0, 1.0, -1.0, -big, -big]);
            let mut m = m0.clone();
            let d = balance(&mut m);
            assert!(m.iter().all(|x| x.is_finite()));
            // m = D⁻¹ m0 D exactly.
            for i in 0..3 {
                for j in 0..3 {
                    assert_eq!(m[(i, j)], m0[(i, j)] / d[i] * d[j]);
                }
            }
        }
    }

    #[test]
    fn ldexp_and_exponent_round_trip() {
        for &x in &[1.0, 3.5, 1e-310, 1e300, -7e-200] {
            let e = exponent(x).unwrap();
            let m = ldexp(x, -e);
            assert!((1.0..2.0).contains(&m.abs()), "{x}: {m}");
            assert_eq!(ldexp(m, e), x);
        }
        assert_eq!(ldexp(1.0, 2000), f64::INFINITY);
        assert_eq!(ldexp(1.0, -2000), 0.0);
    }
}
