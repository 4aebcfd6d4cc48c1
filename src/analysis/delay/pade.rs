//! The [n/n] Padé approximant of a dead time, e^(−sT) ≈ P(s)/Q(s): only the starting points
//! of the root search use it (the roots themselves are refined on the exact equation).

/// Numerator and denominator of the [n/n] Padé approximant of e^(−sT), descending powers of
/// s: Q(s) = Σ cₖ (sT)^k, P(s) = Q(−s), cₖ = (2n − k)!·n! / ((2n)!·k!·(n − k)!).
pub(super) fn pade_coefficients(delay: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut c = Vec::with_capacity(n + 1);
    let mut ck = 1.0_f64;
    let mut tk = 1.0_f64;
    for k in 0..=n {
        c.push(ck * tk);
        // c_{k+1} = c_k·(n − k)/((2n − k)(k + 1))
        if k < n {
            ck *= (n - k) as f64 / (((2 * n - k) * (k + 1)) as f64);
            tk *= delay;
        }
    }
    let den: Vec<f64> = c.iter().rev().copied().collect();
    let num: Vec<f64> = c
        .iter()
        .enumerate()
        .map(|(k, &v)| if k % 2 == 1 { -v } else { v })
        .rev()
        .collect();
    (num, den)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn second_order_pade() {
        // [2/2]: (1 − sT/2 + (sT)²/12)/(1 + sT/2 + (sT)²/12)
        let (num, den) = pade_coefficients(2.0, 2);
        assert_eq!(den, vec![4.0 / 12.0, 1.0, 1.0]);
        assert_eq!(num, vec![4.0 / 12.0, -1.0, 1.0]);
    }

    #[test]
    fn eighth_order_pade_matches_the_exponential() {
        let (num, den) = pade_coefficients(1.0, 8);
        let ev = |c: &[f64], x: f64| c.iter().fold(0.0, |a, &v| a * x + v);
        for x in [0.1, 0.5, 1.0, 1.5] {
            let r = ev(&num, x) / ev(&den, x);
            assert!((r - (-x).exp()).abs() < 1e-14, "x = {x}: {r}");
        }
    }
}
