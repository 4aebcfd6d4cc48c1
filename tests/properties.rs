//! Property tests: partial fractions recompose G(s); tf → ss → tf keeps G(jω).

use ltikit::analysis::partial_fractions;
use ltikit::{Poly, StateSpace, TransferFunction};
use num_complex::Complex64;
use proptest::prelude::*;

/// A pole site: a real pole or a conjugate pair, with a multiplicity.
#[derive(Debug, Clone, Copy)]
struct Site {
    re: f64,
    im: f64,
    mult: usize,
}

fn site() -> impl Strategy<Value = Site> {
    (
        -4.0..4.0f64,
        prop_oneof![Just(0.0), 0.3..4.0f64],
        1..=3usize,
    )
        .prop_map(|(re, im, mult)| Site {
            // Quarter units keep the sites representable and apart; an offset breaks symmetry.
            re: (re * 4.0).round() / 4.0 + 0.0625,
            im: (im * 4.0).round() / 4.0,
            mult,
        })
}

fn roots_of(sites: &[Site]) -> Vec<Complex64> {
    let mut r = Vec::new();
    for s in sites {
        for _ in 0..s.mult {
            r.push(Complex64::new(s.re, s.im));
            if s.im != 0.0 {
                r.push(Complex64::new(s.re, -s.im));
            }
        }
    }
    r
}

fn well_separated(roots: &[Complex64], gap: f64) -> bool {
    for (i, a) in roots.iter().enumerate() {
        for b in &roots[i + 1..] {
            if a != b && (a - b).norm() < gap {
                return false;
            }
        }
    }
    true
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn partial_fractions_recompose(
        sites in prop::collection::vec(site(), 1..=4),
        num in prop::collection::vec(-3.0..3.0f64, 1..=8),
    ) {
        let roots = roots_of(&sites);
        prop_assume!(roots.len() <= 10);
        prop_assume!(well_separated(&roots, 0.5));
        let den = Poly::from_roots(&roots).unwrap();
        let num = Poly::from_descending(&num).unwrap();
        prop_assume!(!num.is_zero());
        let pf = partial_fractions(&num, &den).unwrap();
        // Every power from 1 to the multiplicity, per pole.
        let mut k = 0;
        while k < pf.terms.len() {
            let p = pf.terms[k].pole;
            let mut power = 1;
            while k < pf.terms.len() && pf.terms[k].pole == p {
                prop_assert_eq!(pf.terms[k].power, power);
                power += 1;
                k += 1;
            }
        }
        for s in [
            Complex64::new(0.1, 5.3), Complex64::new(-6.0, 0.7), Complex64::new(6.5, -2.0),
            Complex64::new(0.0, 0.0), Complex64::new(-2.2, 4.9), Complex64::new(1.7, 0.2),
        ] {
            if roots.iter().any(|r| (s - r).norm() < 0.4) {
                continue;
            }
            let g = num.eval_complex(s) / den.eval_complex(s);
            let size: f64 = pf.terms.iter()
                .map(|t| t.residue.norm() / (s - t.pole).norm().powi(t.power as i32))
                .sum::<f64>()
                + pf.direct_poly().eval_complex(s).norm();
            // The reference N/D by Horner carries its own rounding error, up to
            // 2n·eps·Σ|aₖ||s|ᵏ/|D(s)| relative (large next to a multiple root, where D
            // cancels); the expansion must agree within that plus 1e-12 of the terms.
            let n = den.degree() as f64;
            let horner = 2.0 * n * f64::EPSILON
                * (den.eval_abs(s.norm()) / den.eval_complex(s).norm()
                    + num.eval_abs(s.norm()) / num.eval_complex(s).norm());
            let err = (pf.eval(s) - g).norm();
            let tol = 1e-12 * size.max(g.norm()) + horner * g.norm();
            prop_assert!(err <= tol, "s = {}: {:e} > {:e} (|G| = {:e})", s, err, tol, g.norm());
        }
    }

    #[test]
    fn tf_ss_tf_keeps_the_frequency_response(
        sites in prop::collection::vec(site(), 1..=4),
        num in prop::collection::vec(-3.0..3.0f64, 1..=9),
    ) {
        let roots = roots_of(&sites);
        prop_assume!(roots.len() <= 8);
        let den = Poly::from_roots(&roots).unwrap();
        prop_assume!(num.len() <= roots.len() + 1);
        let g = TransferFunction::new(Poly::from_descending(&num).unwrap(), den).unwrap();
        let h = StateSpace::from_tf(&g).unwrap().balanced().to_tf().unwrap();
        for w in [0.05, 0.5, 1.3, 4.0, 20.0] {
            let s = Complex64::new(0.0, w);
            // Scale of the rounding: (Σ|bₖ|ωᵏ + Σ|aₖ|ωᵏ)/|D(jω)| (D monic). The realisation
            // and its characteristic polynomials perturb the coefficients at rounding level
            // relative to both polynomials, so G = s⁷/D(s) at ω = 0.05 (|G| ~ 1e-13) is only
            // kept to that absolute level.
            let scale = (g.num().eval_abs(w) + g.den().eval_abs(w)) / g.den().eval_complex(s).norm();
            let err = (g.eval(s) - h.eval(s)).norm();
            prop_assert!(err <= 1e-9 * scale, "ω = {}: {:e} vs scale {:e}", w, err, scale);
        }
    }
}
