//! A state-space realisation built from zeros, poles and gain, without forming coefficients:
//! a cascade of real first- and second-order sections.
//!
//! Each real pole p is a section with A = \[p\]; each conjugate pair σ ± jω a section with the
//! real modal block A = \[\[σ, ω\], \[−ω, σ\]\] (perfectly conditioned, unlike a companion block).
//! Zeros are distributed over the sections so that each stays proper (a pair of zeros goes to
//! a pair of poles; two real poles are merged into one second-order section when a pair of
//! zeros needs a home), and the sections are connected in series. The state matrix is block
//! lower-triangular with the poles on its diagonal blocks, so the eigenvalues are the poles to
//! rounding, whatever their number and multiplicity.

use nalgebra::DMatrix;
use num_complex::Complex64;

use crate::error::{LtiError, Result};
use crate::lti::StateSpace;
use crate::poly::Root;

/// A section's poles: one real pole, a conjugate pair, or two real poles.
#[derive(Debug, Clone, Copy)]
enum Poles {
    Real(f64),
    Pair(Complex64),
    TwoReal(f64, f64),
}

/// A section's numerator in descending powers (degree ≤ the section's order).
#[derive(Debug, Clone)]
struct Section {
    poles: Poles,
    num: Vec<f64>,
}

impl Section {
    fn order(&self) -> usize {
        match self.poles {
            Poles::Real(_) => 1,
            _ => 2,
        }
    }

    /// Free numerator degree left.
    fn room(&self) -> usize {
        self.order() + 1 - self.num.len()
    }

    fn mul_num(&mut self, f: &[f64]) {
        let mut out = vec![0.0; self.num.len() + f.len() - 1];
        for (i, a) in self.num.iter().enumerate() {
            for (j, b) in f.iter().enumerate() {
                out[i + j] += a * b;
            }
        }
        self.num = out;
    }

    /// (A, B, C, D) of the section (B has one column, C one row).
    fn realise(&self) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>, f64) {
        let n = self.order();
        let mut num = vec![0.0; n + 1 - self.num.len()];
        num.extend_from_slice(&self.num);
        let d = num[0];
        match self.poles {
            Poles::Real(p) => {
                // (b0 s + b1)/(s − p) = b0 + (b1 + b0 p)/(s − p)
                let a = DMatrix::from_element(1, 1, p);
                let b = DMatrix::from_element(1, 1, 1.0);
                let c = DMatrix::from_element(1, 1, num[1] + d * p);
                (a, b, c, d)
            }
            Poles::Pair(z) => {
                let (s, w) = (z.re, z.im.abs());
                // den s² + a1 s + a2, strictly proper remainder r1 s + r0
                let (a1, a2) = (-2.0 * s, s * s + w * w);
                let (r1, r0) = (num[1] - d * a1, num[2] - d * a2);
                let a = DMatrix::from_row_slice(2, 2, &[s, w, -w, s]);
                let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
                // C (sI − A)⁻¹ B = (c1 ω + c2 (s − σ))/Δ
                let c2 = r1;
                let c1 = (r0 + c2 * s) / w;
                let c = DMatrix::from_row_slice(1, 2, &[c1, c2]);
                (a, b, c, d)
            }
            Poles::TwoReal(p, q) => {
                // lower-triangular [[p, 0], [1, q]] from 1/(s − p) then 1/(s − q)
                let (a1, a2) = (-(p + q), p * q);
                let (r1, r0) = (num[1] - d * a1, num[2] - d * a2);
                let a = DMatrix::from_row_slice(2, 2, &[p, 0.0, 1.0, q]);
                let b = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
                // x1 = u/(s−p), x2 = x1/(s−q): C x = (c1 (s − q) + c2)/((s−p)(s−q))
                let c1 = r1;
                let c2 = r0 + c1 * q;
                let c = DMatrix::from_row_slice(1, 2, &[c1, c2]);
                (a, b, c, d)
            }
        }
    }
}

impl StateSpace {
    /// A SISO realisation of the proper G(s) = gain·Π(s − zᵢ)^mᵢ / Π(s − pⱼ)^mⱼ as a cascade
    /// of real first- and second-order sections (see the [module docs](self)). Complex roots
    /// must come in conjugate pairs (the upper member is used).
    ///
    /// Errors: more zeros than poles (improper), a complex root without its conjugate.
    ///
    /// ```
    /// use ltikit::{Root, StateSpace};
    /// use num_complex::Complex64 as C;
    /// // 3 (s + 1) / ((s + 2)(s² + 2s + 5))
    /// let ss = StateSpace::from_zpk(
    ///     &[Root::new(C::new(-1.0, 0.0), 1)],
    ///     &[Root::new(C::new(-1.0, 2.0), 1), Root::new(C::new(-1.0, -2.0), 1), Root::new(C::new(-2.0, 0.0), 1)],
    ///     3.0,
    /// ).unwrap();
    /// let s = C::new(0.3, 0.7);
    /// let want = 3.0 * (s + 1.0) / ((s + 2.0) * (s * s + 2.0 * s + 5.0));
    /// assert!((ss.eval_siso(s) - want).norm() < 1e-14);
    /// ```
    pub fn from_zpk(zeros: &[Root], poles: &[Root], gain: f64) -> Result<StateSpace> {
        let nz: usize = zeros.iter().map(|r| r.multiplicity).sum();
        let np: usize = poles.iter().map(|r| r.multiplicity).sum();
        if nz > np {
            return Err(LtiError::Improper {
                operation: "a state-space realisation".into(),
                required: "proper".into(),
                num_degree: nz,
                den_degree: np,
                limit: np,
            });
        }
        let mut sections = pole_sections(poles)?;
        let (pairs, reals) = zero_factors(zeros)?;
        place_pairs(&mut sections, &pairs);
        for z in reals {
            match sections.iter_mut().find(|s| s.room() > 0) {
                Some(s) => s.mul_num(&[1.0, -z]),
                None => return Err(LtiError::invalid("no section left for a zero")),
            }
        }
        cascade(&sections, gain)
    }

    /// G(s) = C (sI − A)⁻¹ B + D of a single-input single-output model at a complex point
    /// (a dense solve: for checks and small models; NaN for a non-SISO model or a singular
    /// sI − A).
    pub fn eval_siso(&self, s: Complex64) -> Complex64 {
        let n = self.order();
        if self.b.ncols() != 1 || self.c.nrows() != 1 {
            return Complex64::new(f64::NAN, f64::NAN);
        }
        let m = DMatrix::from_fn(n, n, |i, j| {
            let a = Complex64::new(-self.a[(i, j)], 0.0);
            if i == j { a + s } else { a }
        });
        let b = DMatrix::from_fn(n, 1, |i, _| Complex64::new(self.b[(i, 0)], 0.0));
        let d = Complex64::new(self.d[(0, 0)], 0.0);
        if n == 0 {
            return d;
        }
        match m.lu().solve(&b) {
            Some(x) => {
                (0..n)
                    .map(|j| x[(j, 0)] * self.c[(0, j)])
                    .sum::<Complex64>()
                    + d
            }
            None => Complex64::new(f64::NAN, f64::NAN),
        }
    }
}

/// One section per real pole and per conjugate pair (multiplicities expanded).
fn pole_sections(poles: &[Root]) -> Result<Vec<Section>> {
    let mut out = Vec::new();
    for r in poles {
        let poles = if r.is_real() {
            Poles::Real(r.value.re)
        } else if r.value.im > 0.0 {
            if !poles.iter().any(|q| q.value == r.value.conj()) {
                return Err(LtiError::invalid(format!(
                    "pole {} + {}j has no conjugate partner",
                    r.value.re, r.value.im
                )));
            }
            Poles::Pair(r.value)
        } else {
            continue;
        };
        for _ in 0..r.multiplicity {
            out.push(Section {
                poles,
                num: vec![1.0],
            });
        }
    }
    Ok(out)
}

/// Quadratic factors [1, −2 Re z, |z|²] of the zero pairs and the real zeros.
fn zero_factors(zeros: &[Root]) -> Result<(Vec<[f64; 3]>, Vec<f64>)> {
    let mut pairs = Vec::new();
    let mut reals = Vec::new();
    for r in zeros {
        if r.is_real() {
            reals.extend(std::iter::repeat_n(r.value.re, r.multiplicity));
        } else if r.value.im > 0.0 {
            if !zeros.iter().any(|q| q.value == r.value.conj()) {
                return Err(LtiError::invalid(format!(
                    "zero {} + {}j has no conjugate partner",
                    r.value.re, r.value.im
                )));
            }
            let q = [1.0, -2.0 * r.value.re, r.value.norm_sqr()];
            pairs.extend(std::iter::repeat_n(q, r.multiplicity));
        }
    }
    Ok((pairs, reals))
}

/// Gives each pair of zeros a second-order section with room for it, merging two first-order
/// sections into one when none is left.
fn place_pairs(sections: &mut Vec<Section>, pairs: &[[f64; 3]]) {
    for q in pairs {
        if let Some(s) = sections
            .iter_mut()
            .find(|s| s.order() == 2 && s.num.len() == 1)
        {
            s.mul_num(q);
            continue;
        }
        // merge two first-order sections with no zeros yet
        let firsts: Vec<usize> = sections
            .iter()
            .enumerate()
            .filter(|(_, s)| s.order() == 1 && s.num.len() == 1)
            .map(|(i, _)| i)
            .take(2)
            .collect();
        if let [i, j] = firsts[..] {
            let (Poles::Real(p), Poles::Real(r)) = (sections[i].poles, sections[j].poles) else {
                continue;
            };
            sections.remove(j);
            sections[i] = Section {
                poles: Poles::TwoReal(p, r),
                num: q.to_vec(),
            };
        }
    }
}

/// The series connection of the sections, the gain applied to the last output.
fn cascade(sections: &[Section], gain: f64) -> Result<StateSpace> {
    let n: usize = sections.iter().map(Section::order).sum();
    let mut a = DMatrix::zeros(n, n);
    let mut b = DMatrix::zeros(n, 1);
    // the running output of the cascade so far: y = c·x + d·u
    let mut c = DMatrix::zeros(1, n);
    let mut d = 1.0;
    let mut at = 0;
    for s in sections {
        let (sa, sb, sc, sd) = s.realise();
        let k = s.order();
        // section input = previous output: ẋ_s = A_s x_s + B_s (c x + d u)
        a.view_mut((at, at), (k, k)).copy_from(&sa);
        for i in 0..k {
            for j in 0..at {
                a[(at + i, j)] = sb[(i, 0)] * c[(0, j)];
            }
            b[(at + i, 0)] = sb[(i, 0)] * d;
        }
        // new output = C_s x_s + D_s (c x + d u)
        for j in 0..at {
            c[(0, j)] *= sd;
        }
        for j in 0..k {
            c[(0, at + j)] = sc[(0, j)];
        }
        d *= sd;
        at += k;
    }
    let c = c * gain;
    StateSpace::new(a, b, c, DMatrix::from_element(1, 1, gain * d))
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64 as C;

    fn r(re: f64, im: f64, m: usize) -> Root {
        Root::new(C::new(re, im), m)
    }

    #[test]
    fn cascade_matches_the_factors() {
        let cases: Vec<(Vec<Root>, Vec<Root>, f64)> = vec![
            (vec![], vec![r(-1.0, 0.0, 3)], 2.0),
            (
                vec![r(0.5, 1.0, 1), r(0.5, -1.0, 1)],
                vec![r(-1.0, 0.0, 1), r(-3.0, 0.0, 1)],
                -1.5,
            ),
            (
                vec![
                    r(-2.0, 0.0, 1),
                    r(0.0, 0.0, 1),
                    r(-1.0, 3.0, 1),
                    r(-1.0, -3.0, 1),
                ],
                vec![r(-0.1, 2.0, 2), r(-0.1, -2.0, 2)],
                4.0,
            ),
            (
                vec![r(1.0, 0.0, 2)],
                vec![r(-1.0, 0.0, 1), r(-2.0, 0.0, 1)],
                1.0,
            ),
        ];
        for (z, p, k) in cases {
            let ss = StateSpace::from_zpk(&z, &p, k).unwrap();
            for s in [C::new(0.3, 0.7), C::new(-0.5, 5.0), C::new(2.0, 0.0)] {
                let mut want = C::new(k, 0.0);
                for x in &z {
                    want *= (s - x.value).powu(x.multiplicity as u32);
                }
                for x in &p {
                    want /= (s - x.value).powu(x.multiplicity as u32);
                }
                let got = ss.eval_siso(s);
                assert!(
                    (got - want).norm() <= 1e-13 * want.norm().max(1.0),
                    "{got} {want}"
                );
            }
        }
    }

    #[test]
    fn improper_is_refused() {
        assert!(StateSpace::from_zpk(&[r(-1.0, 0.0, 2)], &[r(-2.0, 0.0, 1)], 1.0).is_err());
    }
}
