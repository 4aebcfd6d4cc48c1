//! State-space models ẋ = A x + B u, y = C x + D u.

use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

use crate::error::{LtiError, Result};
use crate::lti::{Domain, TransferFunction};
use crate::numeric::eigenvalues;
use crate::poly::Poly;

/// A continuous-time state-space model (any number of inputs and outputs; conversions to a
/// transfer function need one input and one output).
#[derive(Debug, Clone, PartialEq)]
pub struct StateSpace {
    /// n × n state matrix.
    pub a: DMatrix<f64>,
    /// n × m input matrix.
    pub b: DMatrix<f64>,
    /// p × n output matrix.
    pub c: DMatrix<f64>,
    /// p × m feedthrough matrix.
    pub d: DMatrix<f64>,
    /// Continuous time (ẋ = Ax + Bu) or discrete time (x\[k+1\] = Ax\[k\] + Bu\[k\]) with its
    /// sampling period; [`StateSpace::new`] makes a continuous model,
    /// [`StateSpace::with_domain`] sets it.
    pub domain: Domain,
    /// Dead time (s) on each input (empty: none); the channel from input j to output i is
    /// delayed by `input_delays[j] + output_delays[i]` ([`StateSpace::with_delays`]).
    pub input_delays: Vec<f64>,
    /// Dead time (s) on each output (empty: none).
    pub output_delays: Vec<f64>,
}

impl StateSpace {
    /// Checks dimensions and finiteness.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::StateSpace;
    /// let ss = StateSpace::new(
    ///     DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -0.8]),
    ///     DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
    ///     DMatrix::from_row_slice(1, 2, &[4.0, 0.0]),
    ///     DMatrix::zeros(1, 1),
    /// ).unwrap();
    /// let g = ss.to_tf().unwrap();
    /// assert!((g.eval(num_complex::Complex64::new(0.0, 0.0)).re - 1.0).abs() < 1e-14);
    /// ```
    pub fn new(a: DMatrix<f64>, b: DMatrix<f64>, c: DMatrix<f64>, d: DMatrix<f64>) -> Result<Self> {
        let n = a.nrows();
        if a.ncols() != n {
            return Err(LtiError::invalid(format!(
                "A must be square, got {}×{}",
                a.nrows(),
                a.ncols()
            )));
        }
        if b.nrows() != n || c.ncols() != n || d.nrows() != c.nrows() || d.ncols() != b.ncols() {
            return Err(LtiError::invalid(format!(
                "inconsistent dimensions: A {}×{}, B {}×{}, C {}×{}, D {}×{}",
                a.nrows(),
                a.ncols(),
                b.nrows(),
                b.ncols(),
                c.nrows(),
                c.ncols(),
                d.nrows(),
                d.ncols()
            )));
        }
        for (m, name) in [(&a, "A"), (&b, "B"), (&c, "C"), (&d, "D")] {
            if let Some(x) = m.iter().find(|x| !x.is_finite()) {
                return Err(LtiError::NonFinite {
                    what: format!("an entry of {name}"),
                    value: *x,
                });
            }
        }
        Ok(StateSpace {
            a,
            b,
            c,
            d,
            domain: Domain::Continuous,
            input_delays: Vec::new(),
            output_delays: Vec::new(),
        })
    }

    /// The same matrices in `domain` (x\[k+1\] = A x\[k\] + B u\[k\] in discrete time).
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::{StateSpace, lti::Domain};
    /// let one = DMatrix::from_element(1, 1, 1.0);
    /// let ss = StateSpace::new(one.scale(0.5), one.clone(), one.clone(), one.scale(0.0))
    ///     .unwrap()
    ///     .with_domain(Domain::discrete(0.1).unwrap());
    /// assert_eq!(ss.domain.dt(), Some(0.1));
    /// ```
    pub fn with_domain(mut self, domain: Domain) -> Self {
        self.domain = domain;
        self
    }

    /// The same model with a dead time on each input and each output (s; an empty list is
    /// no delay): y_i = Σ_j G_ij(s)·e^(−s(τ_in,j + τ_out,i))·u_j (continuous time).
    ///
    /// Errors: a list of the wrong length, a bad delay
    /// ([`check_delay`](crate::lti::delay::check_delay)), a discrete-time model (its delays
    /// are whole samples, part of its matrices).
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::StateSpace;
    /// let one = DMatrix::from_element(1, 1, 1.0);
    /// let ss = StateSpace::new(-one.clone(), one.clone(), one.clone(), one.scale(0.0)).unwrap()
    ///     .with_delays(vec![0.5], vec![0.25]).unwrap();
    /// assert_eq!(ss.channel_delay(0, 0), 0.75);
    /// assert!(ss.clone().with_delays(vec![0.5, 1.0], vec![]).is_err());
    /// ```
    pub fn with_delays(mut self, input: Vec<f64>, output: Vec<f64>) -> Result<Self> {
        for (v, n, what) in [
            (&input, self.b.ncols(), "input"),
            (&output, self.c.nrows(), "output"),
        ] {
            if !v.is_empty() && v.len() != n {
                return Err(LtiError::invalid(format!(
                    "`{what}_delays` has {} values, the model has {n} {what}s",
                    v.len()
                )));
            }
            for &t in v {
                crate::lti::delay::check_delay(t)?;
            }
        }
        let any = input.iter().chain(&output).any(|&t| t > 0.0);
        if any {
            self.domain.require_continuous(
                "a dead time on the inputs or outputs of a state-space model (a discrete model \
                 delays by whole samples in its matrices)",
            )?;
        }
        self.input_delays = if input.iter().any(|&t| t > 0.0) {
            input
        } else {
            Vec::new()
        };
        self.output_delays = if output.iter().any(|&t| t > 0.0) {
            output
        } else {
            Vec::new()
        };
        Ok(self)
    }

    /// The dead time of the channel from `input` to `output` (0-based): its input's delay
    /// plus its output's (0 without delays or for an index out of range).
    pub fn channel_delay(&self, input: usize, output: usize) -> f64 {
        self.input_delays.get(input).copied().unwrap_or(0.0)
            + self.output_delays.get(output).copied().unwrap_or(0.0)
    }

    /// True when some input or output has a dead time.
    pub fn has_delays(&self) -> bool {
        !self.input_delays.is_empty() || !self.output_delays.is_empty()
    }

    /// Errors when the model has dead times: `operation` takes the rational model only.
    pub fn require_no_delays(&self, operation: &str) -> Result<()> {
        if !self.has_delays() {
            return Ok(());
        }
        Err(LtiError::invalid(format!(
            "{operation} of a state-space model with input or output dead times is not \
             available; analyse one channel (it carries its delay), or replace the delays by \
             Padé approximants (`pade`)"
        )))
    }

    /// Number of states.
    pub fn order(&self) -> usize {
        self.a.nrows()
    }

    /// Controllable canonical realisation of a proper transfer function (MATLAB's `tf2ss`
    /// form): A is the companion matrix of the monic denominator, B = e₁.
    ///
    /// ```
    /// use ltikit::{StateSpace, TransferFunction};
    /// let g = TransferFunction::from_descending(&[1.0, 3.0], &[1.0, 3.0, 2.0]).unwrap();
    /// let ss = StateSpace::from_tf(&g).unwrap();
    /// assert_eq!(ss.a.as_slice(), &[-3.0, 1.0, -2.0, 0.0]); // column-major
    /// ```
    pub fn from_tf(g: &TransferFunction) -> Result<Self> {
        g.require_proper("a state-space realisation", false)?;
        let n = g.order();
        let lead = g.den().leading();
        let den: Vec<f64> = g.den().coeffs().iter().map(|a| a / lead).collect();
        // Numerator padded to degree n, divided by the denominator's leading coefficient.
        let mut num = vec![0.0; n + 1];
        let nc = g.num().coeffs();
        for (i, &b) in nc.iter().enumerate() {
            num[n + 1 - nc.len() + i] = b / lead;
        }
        if g.num().is_zero() {
            num = vec![0.0; n + 1];
        }
        let d = num[0];
        let mut a = DMatrix::zeros(n, n);
        let mut b = DMatrix::zeros(n, 1);
        let mut c = DMatrix::zeros(1, n);
        for j in 0..n {
            a[(0, j)] = -den[j + 1];
            c[(0, j)] = num[j + 1] - den[j + 1] * d;
        }
        for i in 1..n {
            a[(i, i - 1)] = 1.0;
        }
        if n > 0 {
            b[(0, 0)] = 1.0;
        }
        Ok(StateSpace::new(a, b, c, DMatrix::from_element(1, 1, d))?.with_domain(g.domain()))
    }

    /// A diagonally similar realisation (D⁻¹AD, D⁻¹B, CD) with row and column norms of A
    /// balanced (Parlett–Reinsch, powers of two: exact). Improves the accuracy of `exp(A t)`
    /// for companion matrices with coefficients of very different sizes. Overflow-safe and
    /// bounded (at most [`MAX_BALANCE_SWEEPS`](crate::numeric::balance::MAX_BALANCE_SWEEPS)
    /// sweeps, exponents clamped): an entry of 1e200 is balanced like any other.
    ///
    /// ```
    /// use ltikit::{StateSpace, TransferFunction};
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1e200, 0.0]).unwrap();
    /// let b = StateSpace::from_tf(&g).unwrap().balanced();
    /// assert!(b.a.iter().chain(b.b.iter()).chain(b.c.iter()).all(|x| x.is_finite()));
    /// ```
    pub fn balanced(&self) -> StateSpace {
        let mut a = self.a.clone();
        let d = crate::numeric::balance::balance(&mut a);
        let mut b = self.b.clone();
        let mut c = self.c.clone();
        for (i, &di) in d.iter().enumerate() {
            b.row_mut(i).scale_mut(1.0 / di);
            c.column_mut(i).scale_mut(di);
        }
        if b.iter().chain(c.iter()).any(|x| !x.is_finite()) {
            // B or C would overflow with these factors (entries near f64::MAX): keep A as is.
            return self.clone();
        }
        StateSpace {
            a,
            b,
            c,
            d: self.d.clone(),
            domain: self.domain,
            input_delays: self.input_delays.clone(),
            output_delays: self.output_delays.clone(),
        }
    }

    /// Transfer function of a single-input single-output model, from the identity
    /// C·adj(sI − A)·B = det(sI − A + BC) − det(sI − A):
    /// G(s) = [det(sI − A + BC) + (D − 1)·det(sI − A)] / det(sI − A). Characteristic
    /// polynomials come from the eigenvalues (conjugate pairs exact, so the coefficients are
    /// real).
    pub fn to_tf(&self) -> Result<TransferFunction> {
        self.to_tf_in_s()?
            .with_domain(self.domain)
            .with_delay(self.channel_delay(0, 0))
    }

    fn to_tf_in_s(&self) -> Result<TransferFunction> {
        if self.b.ncols() != 1 || self.c.nrows() != 1 {
            return Err(LtiError::invalid(format!(
                "a transfer function needs one input and one output, the model has {} and {}",
                self.b.ncols(),
                self.c.nrows()
            )));
        }
        let d = self.d[(0, 0)];
        let n = self.order();
        let den = charpoly(&self.a)?;
        if d != 0.0 || n == 0 {
            let closed = &self.a - &self.b * &self.c;
            let num = &charpoly(&closed)? + &den.scale(d - 1.0);
            return TransferFunction::new(num, den);
        }
        // D = 0: the numerator has degree n − r where r is the relative degree, the index of
        // the first non-zero Markov parameter C·A^(r−1)·B, which is also its leading
        // coefficient. The difference of characteristic polynomials below carries rounding
        // residue in the structurally zero coefficients above that degree; drop it.
        let Some((r, h)) = self.first_markov_parameter() else {
            return TransferFunction::new(Poly::zero(), den);
        };
        let closed = &self.a - &self.b * &self.c;
        let diff = &charpoly(&closed)? - &den;
        let asc = diff.ascending();
        let mut coeffs: Vec<f64> = (0..=n - r)
            .map(|k| asc.get(k).copied().unwrap_or(0.0))
            .collect();
        coeffs[n - r] = h;
        coeffs.reverse();
        let num = Poly::trimmed(coeffs);
        TransferFunction::new(num, den)
    }

    /// The first Markov parameter C·A^(k−1)·B that is not zero to rounding level, with its
    /// index k (the relative degree), for a SISO model with D = 0. None when all n vanish
    /// (the transfer function is zero).
    fn first_markov_parameter(&self) -> Option<(usize, f64)> {
        // The rounding error of C·A^(k−1)·B is bounded componentwise by
        // ~(k + n)·eps·|C|·|A|^(k−1)·|B|; a parameter above a margin of that bound is not zero.
        // (Norms instead of the componentwise bound took 1 for zero when ‖A‖ = 1e200.)
        let n = self.order();
        let abs_a = self.a.abs();
        let mut v = self.b.column(0).into_owned();
        let mut va = v.abs();
        let abs_c = self.c.abs();
        for k in 1..=n {
            let h = (&self.c * &v)[(0, 0)];
            let bound = (&abs_c * &va)[(0, 0)];
            let tol = 1e3 * ((k + n) as f64) * f64::EPSILON * bound;
            if h.abs() > tol {
                return Some((k, h));
            }
            v = &self.a * v;
            va = &abs_a * va;
        }
        None
    }

    /// Output at time t of the free response from x(0): C e^{At} x₀.
    pub fn free_response(&self, x0: &DVector<f64>, t: f64) -> Result<DVector<f64>> {
        let e = crate::numeric::expm(&(&self.a * t))?;
        Ok(&self.c * (e * x0))
    }

    /// Eigenvalues of A.
    pub fn eigenvalues(&self) -> Result<Vec<Complex64>> {
        eigenvalues(&self.a)
    }

    /// The p×m dc-gain matrix D − C·A⁻¹·B (discrete time: D + C·(I − A)⁻¹·B) by one LU
    /// solve, when every eigenvalue of A is clearly away from 0 (from 1 in discrete time): by
    /// more than 1e-6·(‖A‖_F + 1), far outside the cluster radius within which the
    /// whole-model analysis makes an eigenvalue exactly 0 (1) and a gain infinite. `None`
    /// otherwise (an integrator, or one only nearly cancelled): the analysis then decides
    /// channel by channel, through each channel's minimal realisation — a cancelled
    /// integrator leaves a finite gain. Dead times do not change the dc gain.
    ///
    /// Errors: those of the eigenvalue computation.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::StateSpace;
    /// // ẋ = −2x + u, y = (3x, x): gains 3/2 and 1/2
    /// let ss = StateSpace::new(
    ///     DMatrix::from_element(1, 1, -2.0),
    ///     DMatrix::from_element(1, 1, 1.0),
    ///     DMatrix::from_column_slice(2, 1, &[3.0, 1.0]),
    ///     DMatrix::zeros(2, 1),
    /// )
    /// .unwrap();
    /// let g = ss.dc_gain_direct().unwrap().unwrap();
    /// assert_eq!((g[(0, 0)], g[(1, 0)]), (1.5, 0.5));
    /// // an integrator: no direct answer
    /// let i = StateSpace::new(
    ///     DMatrix::zeros(1, 1),
    ///     DMatrix::from_element(1, 1, 1.0),
    ///     DMatrix::from_element(1, 1, 1.0),
    ///     DMatrix::zeros(1, 1),
    /// )
    /// .unwrap();
    /// assert!(i.dc_gain_direct().unwrap().is_none());
    /// ```
    pub fn dc_gain_direct(&self) -> Result<Option<DMatrix<f64>>> {
        let n = self.order();
        let discrete = self.domain.is_discrete();
        if n > 0 {
            let scale = self.a.norm() + 1.0;
            let at = Complex64::new(if discrete { 1.0 } else { 0.0 }, 0.0);
            if self
                .eigenvalues()?
                .iter()
                .any(|l| (l - at).norm() <= 1e-6 * scale)
            {
                return Ok(None);
            }
        }
        let m = if discrete {
            DMatrix::identity(n, n) - &self.a
        } else {
            -&self.a
        };
        let Some(x) = m.lu().solve(&self.b) else {
            return Ok(None);
        };
        let g = &self.d + &self.c * x;
        Ok(g.iter().all(|v| v.is_finite()).then_some(g))
    }
}

/// Characteristic polynomial det(sI − M) from the eigenvalues of M.
pub fn charpoly(m: &DMatrix<f64>) -> Result<Poly> {
    let ev = eigenvalues(m)?;
    Poly::from_roots(&ev)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // these tests expect exact values
    use super::*;

    #[test]
    fn tf_ss_tf_round_trip() {
        let g = TransferFunction::from_descending(&[2.0, 1.0, 5.0], &[3.0, 1.0, 4.0, 2.0]).unwrap();
        let h = StateSpace::from_tf(&g).unwrap().to_tf().unwrap();
        for w in [0.0, 0.3, 1.0, 7.0] {
            let s = Complex64::new(0.0, w);
            assert!((g.eval(s) - h.eval(s)).norm() <= 1e-12 * g.eval(s).norm());
        }
    }

    #[test]
    fn relative_degree_is_kept() {
        // 1/(s² + s + 1): the numerator must come back as the constant 1, no spurious zeros.
        let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0, 1.0]).unwrap();
        let h = StateSpace::from_tf(&g).unwrap().to_tf().unwrap();
        assert_eq!(h.num().degree(), 0);
        assert!((h.num().leading() - 1.0).abs() < 1e-15);
        let g = TransferFunction::from_descending(&[2.0, 0.0], &[1.0, 4.0, 6.0, 4.0]).unwrap();
        let h = StateSpace::from_tf(&g).unwrap().to_tf().unwrap();
        assert_eq!(h.num().degree(), 1);
        assert!(h.num().coeff(0).abs() < 1e-14);
    }

    #[test]
    fn biproper_feedthrough() {
        let g = TransferFunction::from_descending(&[2.0, 3.0], &[1.0, 1.0]).unwrap();
        let ss = StateSpace::from_tf(&g).unwrap();
        assert_eq!(ss.d[(0, 0)], 2.0);
        assert_eq!(ss.c[(0, 0)], 1.0);
        let h = ss.to_tf().unwrap();
        assert!((h.eval(Complex64::new(0.0, 0.0)).re - 3.0).abs() < 1e-14);
    }

    #[test]
    fn rejects_improper_and_bad_dims() {
        let g = TransferFunction::from_descending(&[1.0, 0.0, 0.0], &[1.0, 1.0]).unwrap();
        assert!(StateSpace::from_tf(&g).is_err());
        let e = StateSpace::new(
            DMatrix::zeros(2, 2),
            DMatrix::zeros(3, 1),
            DMatrix::zeros(1, 2),
            DMatrix::zeros(1, 1),
        );
        assert!(e.is_err());
    }

    #[test]
    fn balancing_preserves_transfer_function() {
        let g = TransferFunction::from_descending(&[1e6], &[1.0, 2e3, 1e6]).unwrap();
        let ss = StateSpace::from_tf(&g).unwrap();
        let b = ss.balanced();
        let h = b.to_tf().unwrap();
        let s = Complex64::new(0.0, 500.0);
        assert!((g.eval(s) - h.eval(s)).norm() <= 1e-12 * g.eval(s).norm());
    }
}
