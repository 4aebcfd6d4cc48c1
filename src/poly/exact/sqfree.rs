//! Square-free factorisation (Yun) and a coprime basis of several square-free polynomials.

use super::modular::gcd_cofactors;
use super::zpoly::ZPoly;

/// Yun's square-free factorisation of a primitive polynomial f of degree ≥ 1 with a positive
/// leading coefficient: f = Π fᵢ^i with every fᵢ square-free, primitive, of degree ≥ 1 and the
/// fᵢ pairwise coprime. Returned as (fᵢ, i), i increasing. `None` when a gcd is beyond the
/// exact budget.
pub(crate) fn square_free(f: &ZPoly) -> Option<Vec<(ZPoly, usize)>> {
    let (a0, mut b, c) = gcd_cofactors(f, &f.derivative())?;
    if a0.deg() == 0 {
        return Some(vec![(f.primitive(), 1)]);
    }
    let mut out = Vec::new();
    let mut d = c.sub(&b.derivative());
    let mut i = 1;
    while b.deg() > 0 {
        let (a, b2, c2) = gcd_cofactors(&b, &d)?;
        if a.deg() > 0 {
            out.push((a, i));
        }
        b = b2;
        d = c2.sub(&b.derivative());
        i += 1;
    }
    Some(out)
}

/// One element of a coprime basis with its multiplicities in the numerator and denominator.
#[derive(Debug, Clone)]
pub(crate) struct BasisElement {
    /// Square-free, primitive, positive leading coefficient, degree ≥ 1.
    pub poly: ZPoly,
    /// Multiplicity in the numerator.
    pub num: usize,
    /// Multiplicity in the denominator.
    pub den: usize,
}

/// Inserts the square-free polynomial `p` (multiplicities `num`, `den`) into a pairwise coprime
/// basis, splitting elements that share factors with it. Every polynomial inserted so far stays
/// a product of basis elements (each at most once), so the multiplicities add up.
pub(crate) fn insert(
    basis: &mut Vec<BasisElement>,
    p: &ZPoly,
    num: usize,
    den: usize,
) -> Option<()> {
    let mut p = p.primitive();
    let mut out = Vec::with_capacity(basis.len() + 1);
    for q in basis.drain(..) {
        if p.deg() == 0 {
            out.push(q);
            continue;
        }
        let (g, p2, q2) = gcd_cofactors(&p, &q.poly)?;
        if g.deg() == 0 {
            out.push(q);
            continue;
        }
        out.push(BasisElement {
            poly: g,
            num: q.num + num,
            den: q.den + den,
        });
        if q2.deg() > 0 {
            out.push(BasisElement {
                poly: q2.primitive(),
                num: q.num,
                den: q.den,
            });
        }
        p = p2.primitive();
    }
    if p.deg() > 0 {
        out.push(BasisElement { poly: p, num, den });
    }
    *basis = out;
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use dashu_int::IBig;

    fn z(c: &[i64]) -> ZPoly {
        ZPoly::new(c.iter().map(|&x| IBig::from(x)).collect())
    }

    #[test]
    fn yun_separates_multiplicities() {
        // (s + 1)³ (s − 2)² (s² + 1)
        let a = z(&[1, 1]);
        let b = z(&[-2, 1]);
        let c = z(&[1, 0, 1]);
        let f = a.pow(3).mul(&b.pow(2)).mul(&c);
        let sf = square_free(&f).unwrap();
        assert_eq!(sf, vec![(c.clone(), 1), (b.clone(), 2), (a.clone(), 3)]);
        // (2s + 3)^2: the factor stays primitive.
        let sf = square_free(&z(&[3, 2]).pow(2)).unwrap();
        assert_eq!(sf, vec![(z(&[3, 2]), 2)]);
    }

    #[test]
    fn basis_splits_common_factors() {
        let a = z(&[1, 1]);
        let b = z(&[-2, 1]);
        let c = z(&[3, 1]);
        let mut basis = Vec::new();
        insert(&mut basis, &a.mul(&b), 1, 0).unwrap();
        insert(&mut basis, &b.mul(&c), 0, 2).unwrap();
        let mut got: Vec<(ZPoly, usize, usize)> =
            basis.into_iter().map(|e| (e.poly, e.num, e.den)).collect();
        got.sort_by_key(|e| e.0.coeffs()[0].clone());
        assert_eq!(got, vec![(b, 1, 2), (a, 1, 0), (c, 0, 2)]);
    }
}
