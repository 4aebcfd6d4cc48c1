//! One accepted step with its continuous extension (Hairer's quartic interpolant).

/// One accepted step [t₀, t₁] with its continuous extension, handed to the observer of
/// [`integrate`](super::integrate()).
#[derive(Debug, Clone, Copy)]
pub struct DenseStep<'a> {
    pub(super) t0: f64,
    pub(super) t1: f64,
    pub(super) h: f64,
    pub(super) n: usize,
    /// Five blocks of n coefficients of the quartic interpolant.
    pub(super) coef: &'a [f64],
    pub(super) x1: &'a [f64],
}

impl DenseStep<'_> {
    /// Start of the step.
    pub fn t_start(&self) -> f64 {
        self.t0
    }

    /// End of the step.
    pub fn t_end(&self) -> f64 {
        self.t1
    }

    /// State at the start of the step.
    pub fn state_start(&self) -> &[f64] {
        &self.coef[..self.n]
    }

    /// State at the end of the step (the propagated 5th-order solution).
    pub fn state_end(&self) -> &[f64] {
        self.x1
    }

    fn theta(&self, t: f64) -> f64 {
        (t - self.t0) / self.h
    }

    /// Component `i` of the interpolated state at `t` (meant for t in the step; outside it the
    /// quartic is extrapolated). Panics if `i` is out of range, like slice indexing.
    pub fn eval_component(&self, t: f64, i: usize) -> f64 {
        let n = self.n;
        let th = self.theta(t);
        let th1 = 1.0 - th;
        let c = self.coef;
        c[i] + th * (c[n + i] + th1 * (c[2 * n + i] + th * (c[3 * n + i] + th1 * c[4 * n + i])))
    }

    /// The interpolated state at `t`, written into `out` (length = state dimension).
    pub fn eval(&self, t: f64, out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate().take(self.n) {
            *o = self.eval_component(t, i);
        }
    }
}
