//! One Dormand–Prince step (the six new stages, the error estimate, the dense-output
//! coefficients), Hairer's starting step, and the step-size controller.

use super::options::Rk45Options;
use super::tableau::*;

/// The work vectors of one integration: the seven stages (k₁ is the FSAL stage), the stage
/// argument, the propagated solution and the five blocks of dense-output coefficients.
pub(super) struct Stepper {
    n: usize,
    pub k1: Vec<f64>,
    k2: Vec<f64>,
    k3: Vec<f64>,
    k4: Vec<f64>,
    k5: Vec<f64>,
    k6: Vec<f64>,
    pub k7: Vec<f64>,
    pub ytmp: Vec<f64>,
    pub y1: Vec<f64>,
    pub coef: Vec<f64>,
}

impl Stepper {
    pub fn new(n: usize) -> Stepper {
        Stepper {
            n,
            k1: vec![0.0; n],
            k2: vec![0.0; n],
            k3: vec![0.0; n],
            k4: vec![0.0; n],
            k5: vec![0.0; n],
            k6: vec![0.0; n],
            k7: vec![0.0; n],
            ytmp: vec![0.0; n],
            y1: vec![0.0; n],
            coef: vec![0.0; 5 * n],
        }
    }

    /// Stages 2–7 of a step of size `h` from (t, y), ending at `t_new` (t + h, or exactly
    /// t_end on the last step); the 5th-order solution goes to `y1`. Six evaluations of f.
    pub fn stages<F>(&mut self, f: &mut F, t: f64, y: &[f64], h: f64, t_new: f64)
    where
        F: FnMut(f64, &[f64], &mut [f64]),
    {
        let Stepper {
            n,
            k1,
            k2,
            k3,
            k4,
            k5,
            k6,
            k7,
            ytmp,
            y1,
            ..
        } = self;
        for i in 0..*n {
            ytmp[i] = y[i] + h * A21 * k1[i];
        }
        f(t + C2 * h, ytmp, k2);
        for i in 0..*n {
            ytmp[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i]);
        }
        f(t + C3 * h, ytmp, k3);
        for i in 0..*n {
            ytmp[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i]);
        }
        f(t + C4 * h, ytmp, k4);
        for i in 0..*n {
            ytmp[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i]);
        }
        f(t + C5 * h, ytmp, k5);
        for i in 0..*n {
            ytmp[i] =
                y[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i]);
        }
        f(t_new, ytmp, k6);
        for i in 0..*n {
            y1[i] =
                y[i] + h * (A71 * k1[i] + A73 * k3[i] + A74 * k4[i] + A75 * k5[i] + A76 * k6[i]);
        }
        f(t_new, y1, k7);
    }

    /// The local error estimate of the last step in the root-mean-square norm scaled by
    /// atol + rtol·max(|y|, |y1|); ∞ when the step left the finite numbers.
    #[allow(clippy::needless_range_loop)] // seven parallel stage vectors
    pub fn error_norm(&self, y: &[f64], h: f64, opts: &Rk45Options) -> f64 {
        let mut err = 0.0;
        for i in 0..self.n {
            let e = h
                * (E1 * self.k1[i]
                    + E3 * self.k3[i]
                    + E4 * self.k4[i]
                    + E5 * self.k5[i]
                    + E6 * self.k6[i]
                    + E7 * self.k7[i]);
            let sk = opts.atol + opts.rtol * y[i].abs().max(self.y1[i].abs());
            err += if sk > 0.0 {
                (e / sk) * (e / sk)
            } else if e == 0.0 {
                0.0
            } else {
                f64::INFINITY
            };
        }
        let err = if self.n > 0 {
            (err / self.n as f64).sqrt()
        } else {
            0.0
        };
        let finite = self.y1.iter().all(|v| v.is_finite()) && self.k7.iter().all(|v| v.is_finite());
        if finite && err.is_finite() {
            err
        } else {
            f64::INFINITY
        }
    }

    /// Fills the dense-output coefficients of the accepted step from y to y1.
    #[allow(clippy::needless_range_loop)] // seven parallel stage vectors
    pub fn dense_coefficients(&mut self, y: &[f64], h: f64) {
        let n = self.n;
        for i in 0..n {
            let ydiff = self.y1[i] - y[i];
            let bspl = h * self.k1[i] - ydiff;
            self.coef[i] = y[i];
            self.coef[n + i] = ydiff;
            self.coef[2 * n + i] = bspl;
            self.coef[3 * n + i] = ydiff - h * self.k7[i] - bspl;
            self.coef[4 * n + i] = h
                * (D1 * self.k1[i]
                    + D3 * self.k3[i]
                    + D4 * self.k4[i]
                    + D5 * self.k5[i]
                    + D6 * self.k6[i]
                    + D7 * self.k7[i]);
        }
    }

    /// Hairer's starting step: h such that an explicit Euler step changes x by about 1 % of
    /// the tolerance scale, refined with an estimate of the second derivative (one extra
    /// evaluation). Uses `k1` = f(t, y).
    pub fn initial_step<F>(
        &mut self,
        f: &mut F,
        t: f64,
        y: &[f64],
        hmax: f64,
        opts: &Rk45Options,
    ) -> f64
    where
        F: FnMut(f64, &[f64], &mut [f64]),
    {
        let n = self.n;
        let f0 = &self.k1;
        let sk: Vec<f64> = y
            .iter()
            .map(|v| (opts.atol + opts.rtol * v.abs()).max(f64::MIN_POSITIVE))
            .collect();
        let dnf: f64 = (0..n).map(|i| (f0[i] / sk[i]).powi(2)).sum();
        let dny: f64 = (0..n).map(|i| (y[i] / sk[i]).powi(2)).sum();
        let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
            1e-6
        } else {
            (dny / dnf).sqrt() * 0.01
        };
        h = h.min(hmax);
        for i in 0..n {
            self.ytmp[i] = y[i] + h * f0[i];
        }
        f(t + h, &self.ytmp, &mut self.k2);
        let der2: f64 = (0..n)
            .map(|i| ((self.k2[i] - self.k1[i]) / sk[i]).powi(2))
            .sum::<f64>()
            .sqrt()
            / h;
        let der12 = der2.max(dnf.sqrt());
        let h1 = if !der12.is_finite() {
            1e-6 * h
        } else if der12 <= 1e-15 {
            (h * 1e-3).max(1e-6)
        } else {
            (0.01 / der12).powf(0.2)
        };
        (100.0 * h).min(h1).min(hmax)
    }
}

/// The step-size controller of `DOPRI5`: Lund-stabilised (β = 0.04), growth limited to ×10
/// and shrinkage to ×0.2 per step, no growth right after a rejection.
pub(super) struct Controller {
    facold: f64,
    rejected_last: bool,
}

impl Controller {
    pub fn new() -> Controller {
        Controller {
            facold: 1e-4,
            rejected_last: false,
        }
    }

    /// The next step size after accepting a step of size `h` with error `err` ≤ 1.
    pub fn accept(&mut self, err: f64, h: f64, hmax: f64) -> f64 {
        let fac11 = err.powf(EXPO1);
        let fac = (fac11 / self.facold.powf(BETA) / SAFETY).clamp(1.0 / FAC_MAX, 1.0 / FAC_MIN);
        let mut h_new = (h / fac).min(hmax);
        if self.rejected_last {
            h_new = h_new.min(h);
        }
        self.facold = err.max(1e-4);
        self.rejected_last = false;
        h_new
    }

    /// The retried step size after rejecting a step of size `h` with error `err` > 1 (a
    /// non-finite error retreats by the largest shrinkage).
    pub fn reject(&mut self, err: f64, h: f64) -> f64 {
        self.rejected_last = true;
        if !err.is_finite() {
            return h * FAC_MIN;
        }
        h / (err.powf(EXPO1) / SAFETY).min(1.0 / FAC_MIN)
    }
}
