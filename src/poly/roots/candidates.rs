//! Step 2: candidate roots — stable closed forms for degree ≤ 2, eigenvalues of the balanced
//! companion matrix above.

use num_complex::Complex64;

use super::companion;
use crate::error::{LtiError, Result};
use crate::poly::Poly;

/// Candidate roots (with repetition): closed forms for degree ≤ 2, companion eigenvalues above.
pub(crate) fn candidates(q: &Poly) -> Result<Vec<Complex64>> {
    let c = q.coeffs();
    let n = q.degree();
    match n {
        1 => Ok(vec![Complex64::new(-c[1] / c[0], 0.0)]),
        2 => Ok(quadratic(c[0], c[1], c[2])),
        _ => {
            let lead = c[0];
            let mut tail = Vec::with_capacity(n);
            for &cj in &c[1..] {
                let v = cj / lead;
                if !v.is_finite() {
                    return Err(LtiError::BadScaling {
                        what: "polynomial".into(),
                        ratio: -v,
                        leading: lead,
                    });
                }
                tail.push(v);
            }
            if let Some(ev) = companion::companion_eigenvalues(&tail) {
                return Ok(ev);
            }
            // The capped double-shift iteration did not converge: the general solver (with
            // its own cap and a retry after a similarity transformation).
            let mut a = nalgebra::DMatrix::<f64>::zeros(n, n);
            for (j, &v) in tail.iter().enumerate() {
                a[(0, j)] = -v;
            }
            for i in 1..n {
                a[(i, i - 1)] = 1.0;
            }
            crate::numeric::eigenvalues_checked(a)
        }
    }
}

/// Roots of a s² + b s + c without cancellation (a ≠ 0, c ≠ 0).
pub(super) fn quadratic(a: f64, b: f64, c: f64) -> Vec<Complex64> {
    // Scale to avoid overflow in b² and 4ac.
    let s = a.abs().max(b.abs()).max(c.abs());
    let (a, b, c) = (a / s, b / s, c / s);
    let disc = b.mul_add(b, -4.0 * a * c);
    if disc >= 0.0 {
        let sq = disc.sqrt();
        let qq = -0.5 * (b + sq.copysign(b));
        if qq == 0.0 {
            return vec![Complex64::new(0.0, 0.0); 2];
        }
        vec![Complex64::new(qq / a, 0.0), Complex64::new(c / qq, 0.0)]
    } else {
        let re = -b / (2.0 * a);
        let im = (-disc).sqrt() / (2.0 * a.abs());
        vec![Complex64::new(re, im), Complex64::new(re, -im)]
    }
}
