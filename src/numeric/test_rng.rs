//! Seeded draws for the unit tests: Marsaglia's xorshift64 (shifts 13, 7, 17), the same doubles
//! on every run and every machine. The integration tests have theirs in `tests/common`.

/// The next state of the generator (the seed must not be 0).
pub(crate) fn next(seed: &mut u64) -> u64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    *seed
}

/// Uniform in [0, 1): the top 53 bits of the next state.
pub(crate) fn unit(seed: &mut u64) -> f64 {
    (next(seed) >> 11) as f64 / (1u64 << 53) as f64
}

/// Uniform in [−1, 1).
pub(crate) fn uniform(seed: &mut u64) -> f64 {
    unit(seed) * 2.0 - 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[allow(clippy::float_cmp)] // the same draw, scaled exactly
    fn draws_in_range_and_repeatable() {
        let (mut a, mut b) = (0x2545_F491_4F6C_DD1Du64, 0x2545_F491_4F6C_DD1Du64);
        for _ in 0..1000 {
            let (x, y) = (unit(&mut a), uniform(&mut b));
            assert!((0.0..1.0).contains(&x) && (-1.0..1.0).contains(&y));
            assert_eq!(y, x * 2.0 - 1.0);
        }
    }
}
