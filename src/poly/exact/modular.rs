//! Modular greatest common divisors in ℤ\[s\] (Brown's algorithm): gcds modulo word-size primes,
//! Chinese remaindering, and a trial division that certifies the result.
//!
//! Why not Euclid over ℚ: the intermediate coefficients of the remainder sequence of two
//! degree-50 polynomials with 17-digit coefficients grow to tens of thousands of bits, while
//! the gcd itself is usually 1 — which one prime proves (for a prime that does not divide the
//! leading coefficients, deg gcd(a mod p, b mod p) ≥ deg gcd(a, b)).

use dashu_int::IBig;
use dashu_int::ops::{Gcd, UnsignedAbs};

use super::zpoly::ZPoly;

/// The 128 largest primes below 2³¹ (checked by the unit test below). Products of residues
/// stay below 2⁶², so all arithmetic modulo p is plain u64. Together they carry ~3960 bits: a
/// gcd whose coefficients need more is beyond the exact budget.
const PRIMES: [u64; 128] = [
    2147483647, 2147483629, 2147483587, 2147483579, 2147483563, 2147483549, 2147483543, 2147483497,
    2147483489, 2147483477, 2147483423, 2147483399, 2147483353, 2147483323, 2147483269, 2147483249,
    2147483237, 2147483179, 2147483171, 2147483137, 2147483123, 2147483077, 2147483069, 2147483059,
    2147483053, 2147483033, 2147483029, 2147482951, 2147482949, 2147482943, 2147482937, 2147482921,
    2147482877, 2147482873, 2147482867, 2147482859, 2147482819, 2147482817, 2147482811, 2147482801,
    2147482763, 2147482739, 2147482697, 2147482693, 2147482681, 2147482663, 2147482661, 2147482621,
    2147482591, 2147482583, 2147482577, 2147482507, 2147482501, 2147482481, 2147482417, 2147482409,
    2147482367, 2147482361, 2147482349, 2147482343, 2147482327, 2147482291, 2147482273, 2147482237,
    2147482231, 2147482223, 2147482121, 2147482093, 2147482091, 2147482081, 2147482063, 2147482021,
    2147481997, 2147481967, 2147481949, 2147481937, 2147481907, 2147481901, 2147481899, 2147481893,
    2147481883, 2147481863, 2147481827, 2147481811, 2147481797, 2147481793, 2147481673, 2147481629,
    2147481571, 2147481563, 2147481529, 2147481509, 2147481499, 2147481491, 2147481487, 2147481373,
    2147481367, 2147481359, 2147481353, 2147481337, 2147481317, 2147481311, 2147481283, 2147481269,
    2147481263, 2147481247, 2147481209, 2147481199, 2147481179, 2147481173, 2147481151, 2147481143,
    2147481139, 2147481071, 2147481053, 2147481031, 2147481019, 2147480989, 2147480971, 2147480969,
    2147480957, 2147480941, 2147480927, 2147480921, 2147480899, 2147480897, 2147480893, 2147480849,
];

/// Residue of x modulo p in [0, p).
fn residue(x: &IBig, p: u64) -> u64 {
    let r: u64 = x.unsigned_abs() % p;
    if *x < IBig::ZERO && r != 0 { p - r } else { r }
}

/// a^(−1) mod p for a ≢ 0 (Fermat).
fn inverse(a: u64, p: u64) -> u64 {
    let (mut base, mut e, mut r) = (a % p, p - 2, 1u64);
    while e > 0 {
        if e & 1 == 1 {
            r = r * base % p;
        }
        base = base * base % p;
        e >>= 1;
    }
    r
}

fn trim(v: &mut Vec<u64>) {
    while v.last() == Some(&0) {
        v.pop();
    }
}

/// a mod b in place (ascending, b non-zero with no high zeros).
fn rem_in_place(a: &mut Vec<u64>, b: &[u64], p: u64) {
    let m = b.len() - 1;
    let inv = inverse(b[m], p);
    while a.len() > m {
        let top = a.len() - 1;
        let f = a[top] * inv % p;
        if f != 0 {
            let base = top - m;
            for (j, &bj) in b.iter().enumerate() {
                a[base + j] = (a[base + j] + (p - f) * bj) % p;
            }
        }
        a.pop();
        trim(a);
    }
}

/// Monic gcd of two polynomials over 𝔽_p (ascending).
fn gcd_mod(mut a: Vec<u64>, mut b: Vec<u64>, p: u64) -> Vec<u64> {
    trim(&mut a);
    trim(&mut b);
    while !b.is_empty() {
        rem_in_place(&mut a, &b, p);
        std::mem::swap(&mut a, &mut b);
    }
    if let Some(&l) = a.last() {
        let inv = inverse(l, p);
        for x in a.iter_mut() {
            *x = *x * inv % p;
        }
    }
    a
}

/// The gcd of two non-zero polynomials with its cofactors: (g, a/g, b/g), g primitive with a
/// positive leading coefficient. `None` when the prime table is exhausted (coefficients of the
/// gcd beyond ~3900 bits): beyond the exact budget.
pub(crate) fn gcd_cofactors(a: &ZPoly, b: &ZPoly) -> Option<(ZPoly, ZPoly, ZPoly)> {
    if b.is_zero() {
        let g = a.primitive();
        let q = a.div_exact(&g)?;
        return Some((g, q, ZPoly::new(Vec::new())));
    }
    if a.is_zero() {
        let (g, q, z) = gcd_cofactors(b, a)?;
        return Some((g, z, q));
    }
    if a.deg() == 0 || b.deg() == 0 {
        return Some((ZPoly::one(), a.clone(), b.clone()));
    }
    let gamma = IBig::from((&a.lc()).gcd(&b.lc()));
    let (la, lb) = (a.lc(), b.lc());
    let mut best = usize::MAX;
    let mut acc: Option<(Vec<IBig>, IBig)> = None; // (symmetric residues, modulus)
    for &p in PRIMES.iter() {
        if residue(&la, p) == 0 || residue(&lb, p) == 0 {
            continue;
        }
        let am: Vec<u64> = a.coeffs().iter().map(|x| residue(x, p)).collect();
        let bm: Vec<u64> = b.coeffs().iter().map(|x| residue(x, p)).collect();
        let g = gcd_mod(am, bm, p);
        let d = g.len().saturating_sub(1);
        if d == 0 {
            return Some((ZPoly::one(), a.clone(), b.clone()));
        }
        if d > best {
            continue; // unlucky prime
        }
        if d < best {
            best = d;
            acc = None; // every earlier prime was unlucky
        }
        let gm = residue(&gamma, p);
        let scaled: Vec<u64> = g.iter().map(|&x| x * gm % p).collect();
        let stable = match acc.as_mut() {
            None => {
                let half = p / 2;
                let h = scaled
                    .iter()
                    .map(|&x| {
                        if x > half {
                            IBig::from(x) - IBig::from(p)
                        } else {
                            IBig::from(x)
                        }
                    })
                    .collect();
                acc = Some((h, IBig::from(p)));
                false
            }
            Some((h, m)) => crt_step(h, m, &scaled, p),
        };
        if stable {
            if let Some((h, _)) = &acc {
                let cand = ZPoly::new(h.clone()).primitive();
                if let (Some(qa), Some(qb)) = (a.div_exact(&cand), b.div_exact(&cand)) {
                    return Some((cand, qa, qb));
                }
            }
        }
    }
    None
}

/// Adds the residues `r` modulo `p` to the symmetric residues `h` modulo `m`; returns true
/// when no value changed (the reconstruction has stabilised).
fn crt_step(h: &mut [IBig], m: &mut IBig, r: &[u64], p: u64) -> bool {
    let inv = inverse(residue(m, p), p);
    let mp = &*m * IBig::from(p);
    let half = &mp / IBig::from(2u8);
    let mut unchanged = true;
    for (hi, &ri) in h.iter_mut().zip(r) {
        let t = (ri + p - residue(hi, p)) % p * inv % p;
        if t != 0 {
            unchanged = false;
            let mut v = &*hi + &*m * IBig::from(t);
            if v > half {
                v -= &mp;
            }
            *hi = v;
        }
    }
    *m = mp;
    unchanged
}

#[cfg(test)]
mod tests {
    use super::*;

    fn z(c: &[i64]) -> ZPoly {
        ZPoly::new(c.iter().map(|&x| IBig::from(x)).collect())
    }

    fn is_prime(n: u64) -> bool {
        n % 2 == 1
            && (3..)
                .step_by(2)
                .take_while(|d| d * d <= n)
                .all(|d| n % d != 0)
    }

    #[test]
    fn prime_table_is_the_largest_primes_below_2_31() {
        let mut expect = Vec::new();
        let mut n = (1u64 << 31) - 1;
        while expect.len() < PRIMES.len() {
            if is_prime(n) {
                expect.push(n);
            }
            n -= 1;
        }
        assert_eq!(PRIMES.to_vec(), expect);
    }

    #[test]
    fn gcd_with_cofactors() {
        // (s + 1)(2s + 3) and (s + 1)(s − 5): gcd s + 1.
        let a = z(&[1, 1]).mul(&z(&[3, 2]));
        let b = z(&[1, 1]).mul(&z(&[-5, 1])).scale(&IBig::from(6));
        let (g, qa, qb) = gcd_cofactors(&a, &b).unwrap();
        assert_eq!(g, z(&[1, 1]));
        assert_eq!(qa, z(&[3, 2]));
        assert_eq!(qb, z(&[-30, 6]));
        // Coprime.
        let (g, _, _) = gcd_cofactors(&z(&[1, 0, 1]), &z(&[2, 1])).unwrap();
        assert_eq!(g, ZPoly::one());
        // A gcd with large coefficients needs several primes: (10^30 s + 7)·(…).
        let big = ZPoly::new(vec![IBig::from(7), IBig::from(10u8).pow(30)]);
        let a = big.mul(&big).mul(&z(&[1, 3]));
        let b = big.mul(&z(&[5, 0, 1]));
        let (g, _, _) = gcd_cofactors(&a, &b).unwrap();
        assert_eq!(g, big);
        // Against a zero polynomial: the primitive part.
        let (g, q, _) = gcd_cofactors(&z(&[4, 6]), &ZPoly::new(vec![])).unwrap();
        assert_eq!((g, q), (z(&[2, 3]), z(&[2])));
    }
}
