//! Frequency response G(s) = C(sI − A)⁻¹B + D at many complex points, O(n²·min(m, p)) per
//! point after one O(n³) reduction.
//!
//! # Method
//! Once: balance A (exact diagonal similarity) and reduce it to Hessenberg form,
//! H = QᵀAQ, B̃ = QᵀB, C̃ = CQ (Laub 1981; ControlSystems.jl's `freqresp`). Per point s:
//! Gaussian elimination of the Hessenberg matrix M = sI − H with *adjacent-row pivoting*
//! (row k is eliminated against row k+1 only, the larger leading entry is the pivot; growth
//! is at most linear in n), fused with the solve Z·U = C̃ of the triangular factor: row k of
//! U is final after step k, so Z's column k and the running sums Σᵢ zᵢ·uᵢⱼ are updated at
//! once and U is never stored. The transformed right-hand side Y = E·B̃ comes out of the same
//! row operations, and G = Σₖ Z\[:, k\]·Y\[k, :\] + D. The two inner loops run over contiguous
//! real and imaginary arrays (vectorised; an AVX2 copy is selected at run time on x86-64).
//! With more outputs than inputs the dual system (Hᵀ reversed is again upper Hessenberg) is
//! used, so the work is n²·(1 + min(m, p)) complex multiply-adds.
//!
//! At an exact eigenvalue of A a zero pivot is replaced by ε·‖H‖ (the response there is
//! infinite; a huge finite value is returned instead of NaN).

use nalgebra::DMatrix;
use num_complex::Complex64;

use crate::error::{LtiError, Result};
use crate::numeric::balance::balance;

/// The Hessenberg form of a state-space system, ready for evaluation at any s.
#[derive(Clone, Debug)]
pub struct HessenbergResponse {
    n: usize,
    /// Outputs and inputs of the system evaluated (after the optional transposition).
    p: usize,
    m: usize,
    /// Row i of H from column max(i, 1) − 1 on, rows concatenated.
    rows: Vec<f64>,
    row_start: Vec<usize>,
    /// B̃ row-major (n×m).
    b: Vec<f64>,
    /// C̃ column-major (p×n): column k contiguous.
    c: Vec<f64>,
    /// D (p×m) of the evaluated system.
    d: DMatrix<f64>,
    /// The evaluated system is the dual: results are transposed back.
    dual: bool,
    /// ε·‖H‖: replaces an exactly zero pivot.
    tiny: f64,
}

/// Work arrays for one evaluation.
#[derive(Default)]
struct Work {
    cur_re: Vec<f64>,
    cur_im: Vec<f64>,
    acc_re: Vec<f64>,
    acc_im: Vec<f64>,
    y_re: Vec<f64>,
    y_im: Vec<f64>,
    g_re: Vec<f64>,
    g_im: Vec<f64>,
}

impl HessenbergResponse {
    /// Reduces (A, B, C, D) once (A n×n, B n×m, C p×n, D p×m, finite).
    ///
    /// Errors: inconsistent dimensions (named), non-finite entries.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use num_complex::Complex64;
    /// use ltikit::numeric::linalg::HessenbergResponse;
    /// // G(s) = 4/(s² + 0.8s + 4)
    /// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -0.8]);
    /// let b = DMatrix::from_row_slice(2, 1, &[0.0, 4.0]);
    /// let c = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
    /// let d = DMatrix::zeros(1, 1);
    /// let g = HessenbergResponse::new(&a, &b, &c, &d).unwrap();
    /// let s = Complex64::new(0.0, 2.0);
    /// let exact = 4.0 / (s * s + 0.8 * s + 4.0);
    /// assert!((g.eval_siso(s) - exact).norm() < 1e-15);
    /// assert!((g.eval(s)[(0, 0)] - exact).norm() < 1e-15);
    /// ```
    pub fn new(
        a: &DMatrix<f64>,
        b: &DMatrix<f64>,
        c: &DMatrix<f64>,
        d: &DMatrix<f64>,
    ) -> Result<Self> {
        let (n, m, p) = super::checks::check_system(a, b, c, d)?;
        let mut h = a.clone();
        let mut bb = b.clone();
        let mut cc = c.clone();
        if n >= 2 {
            let mut hb = h.clone();
            let dg = balance(&mut hb);
            let bs = DMatrix::from_fn(n, m, |i, j| b[(i, j)] / dg[i]);
            let cs = DMatrix::from_fn(p, n, |i, j| c[(i, j)] * dg[j]);
            if bs.iter().chain(cs.iter()).all(|x| x.is_finite()) {
                (h, bb, cc) = (hb, bs, cs);
            }
        }
        for r in super::hessenberg::reduce_in_place(&mut h) {
            r.apply_left(&mut bb, 0..m);
            r.apply_right(&mut cc, 0..p);
        }
        let tiny = f64::EPSILON * super::norms::frobenius(h.iter()).max(f64::MIN_POSITIVE);
        if p > m {
            // Dual: Gᵀ = B̃ᵀ·(sI − Hᵀ)⁻¹·C̃ᵀ + Dᵀ; with J the reversal, J·Hᵀ·J is upper
            // Hessenberg: H_d = J·Hᵀ·J, B_d = J·C̃ᵀ, C_d = B̃ᵀ·J.
            let hd = DMatrix::from_fn(n, n, |i, j| h[(n - 1 - j, n - 1 - i)]);
            let bd = DMatrix::from_fn(n, p, |i, j| cc[(j, n - 1 - i)]);
            let cd = DMatrix::from_fn(m, n, |i, j| bb[(n - 1 - j, i)]);
            return Ok(Self::pack(&hd, &bd, &cd, d.transpose(), true, tiny));
        }
        Ok(Self::pack(&h, &bb, &cc, d.clone(), false, tiny))
    }

    fn pack(
        h: &DMatrix<f64>,
        b: &DMatrix<f64>,
        c: &DMatrix<f64>,
        d: DMatrix<f64>,
        dual: bool,
        tiny: f64,
    ) -> Self {
        let n = h.nrows();
        let mut rows = Vec::with_capacity(n * (n + 3) / 2);
        let mut row_start = Vec::with_capacity(n);
        for i in 0..n {
            row_start.push(rows.len());
            rows.extend((i.saturating_sub(1)..n).map(|j| h[(i, j)]));
        }
        let m = b.ncols();
        let p = c.nrows();
        let b_rm = (0..n)
            .flat_map(|i| (0..m).map(move |j| b[(i, j)]))
            .collect();
        HessenbergResponse {
            n,
            p,
            m,
            rows,
            row_start,
            b: b_rm,
            c: c.as_slice().to_vec(),
            d,
            dual,
            tiny,
        }
    }

    /// Number of states.
    pub fn order(&self) -> usize {
        self.n
    }

    /// G(s) (p×m).
    pub fn eval(&self, s: Complex64) -> DMatrix<Complex64> {
        let mut w = Work::default();
        self.eval_with(s, &mut w)
    }

    /// G at every point of `s`.
    pub fn eval_many(&self, s: &[Complex64]) -> Vec<DMatrix<Complex64>> {
        let mut w = Work::default();
        s.iter().map(|&x| self.eval_with(x, &mut w)).collect()
    }

    /// G(s) of a single-input single-output system (the (0, 0) entry otherwise).
    pub fn eval_siso(&self, s: Complex64) -> Complex64 {
        let mut w = Work::default();
        self.run(s, &mut w);
        Complex64::new(w.g_re[0], w.g_im[0]) + self.d.get((0, 0)).copied().unwrap_or(0.0)
    }

    /// G(s) of a single-input single-output system at every point (the (0, 0) entry otherwise).
    ///
    /// Errors when the system has no input or no output.
    pub fn eval_siso_many(&self, s: &[Complex64]) -> Result<Vec<Complex64>> {
        if self.m == 0 || self.p == 0 {
            return Err(LtiError::invalid("the system has no input or no output"));
        }
        let d = self.d[(0, 0)];
        let mut w = Work::default();
        Ok(s.iter()
            .map(|&x| {
                self.run(x, &mut w);
                Complex64::new(w.g_re[0] + d, w.g_im[0])
            })
            .collect())
    }

    /// G(s) and its derivative G′(s) = −C̃(sI − H)⁻²B̃ of a single-input single-output
    /// system (the (0, 0) entry otherwise): two O(n²) Hessenberg solves with partial pivoting
    /// on one factorisation of sI − H. What the margins refine their crossings on (the
    /// slope of ln|G(jω)| is Re(j·G′/G)), and the size of the terms summed for G,
    /// Σ|c̃ₖ·xₖ| + |D| with x = (sI − H)⁻¹B̃: G lost about log₁₀(terms/|G|) digits to
    /// cancellation. `None` without an input or an output.
    pub(crate) fn eval_siso_with_derivative(
        &self,
        s: Complex64,
    ) -> Option<(Complex64, Complex64, f64)> {
        if self.m == 0 || self.p == 0 {
            return None;
        }
        let n = self.n;
        let (m, p) = (self.m, self.p);
        let d = self.d[(0, 0)];
        // the (0, 0) entry of the evaluated system (its transpose when dual)
        let bcol: Vec<Complex64> = (0..n).map(|i| Complex64::new(self.b[i * m], 0.0)).collect();
        let crow: Vec<Complex64> = (0..n).map(|k| Complex64::new(self.c[k * p], 0.0)).collect();
        if n == 0 {
            return Some((Complex64::new(d, 0.0), Complex64::new(0.0, 0.0), d.abs()));
        }
        // sI − H, dense row-major
        let mut u = vec![Complex64::new(0.0, 0.0); n * n];
        for i in 0..n {
            let j0 = i.saturating_sub(1);
            for (j, &h) in (j0..n).zip(&self.rows[self.row_start[i]..]) {
                u[i * n + j] = Complex64::new(-h, 0.0);
            }
            u[i * n + i] += s;
        }
        // LU of the Hessenberg matrix: one multiplier and one row swap per column
        let mut ops = Vec::with_capacity(n);
        for k in 0..n.saturating_sub(1) {
            let swap = u[(k + 1) * n + k].norm() > u[k * n + k].norm();
            if swap {
                for j in k..n {
                    u.swap(k * n + j, (k + 1) * n + j);
                }
            }
            let mut piv = u[k * n + k];
            if piv.norm() == 0.0 {
                piv = Complex64::new(self.tiny, 0.0);
                u[k * n + k] = piv;
            }
            let l = u[(k + 1) * n + k] / piv;
            for j in k..n {
                let t = u[k * n + j];
                u[(k + 1) * n + j] -= l * t;
            }
            ops.push((swap, l));
        }
        if u[n * n - 1].norm() == 0.0 {
            u[n * n - 1] = Complex64::new(self.tiny, 0.0);
        }
        let solve = |rhs: &mut [Complex64]| {
            for (k, &(swap, l)) in ops.iter().enumerate() {
                if swap {
                    rhs.swap(k, k + 1);
                }
                let t = rhs[k];
                rhs[k + 1] -= l * t;
            }
            for i in (0..n).rev() {
                let mut acc = rhs[i];
                for j in i + 1..n {
                    acc -= u[i * n + j] * rhs[j];
                }
                rhs[i] = acc / u[i * n + i];
            }
        };
        let mut x = bcol;
        solve(&mut x);
        let g = crow.iter().zip(&x).map(|(c, x)| c * x).sum::<Complex64>() + d;
        let terms = crow
            .iter()
            .zip(&x)
            .map(|(c, x)| (c * x).norm())
            .sum::<f64>()
            + d.abs();
        let mut y = x;
        solve(&mut y);
        let dg = -crow.iter().zip(&y).map(|(c, y)| c * y).sum::<Complex64>();
        Some((g, dg, terms))
    }

    fn eval_with(&self, s: Complex64, w: &mut Work) -> DMatrix<Complex64> {
        self.run(s, w);
        let (p, m) = (self.p, self.m);
        let g = DMatrix::from_fn(p, m, |i, j| {
            Complex64::new(w.g_re[i * m + j], w.g_im[i * m + j]) + self.d[(i, j)]
        });
        if self.dual { g.transpose() } else { g }
    }

    /// Fills w.g_{re,im} (p×m row-major) with C̃(sI − H)⁻¹B̃.
    fn run(&self, s: Complex64, w: &mut Work) {
        #[cfg(all(ltikit_simd, target_arch = "x86_64"))]
        {
            if is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above).
                unsafe { self.run_avx2(s, w) };
                return;
            }
        }
        self.run_portable(s, w);
    }

    #[cfg(all(ltikit_simd, target_arch = "x86_64"))]
    #[target_feature(enable = "avx2")]
    #[allow(clippy::incompatible_msrv)]
    fn run_avx2(&self, s: Complex64, w: &mut Work) {
        self.run_portable(s, w);
    }

    #[inline(always)]
    fn run_portable(&self, s: Complex64, w: &mut Work) {
        let (n, p, m) = (self.n, self.p, self.m);
        w.g_re.clear();
        w.g_re.resize(p * m, 0.0);
        w.g_im.clear();
        w.g_im.resize(p * m, 0.0);
        if n == 0 || p == 0 || m == 0 {
            return;
        }
        // Current pivot-row candidate: row 0 of sI − H.
        let row0 = &self.rows[..n];
        w.cur_re.clear();
        w.cur_re.extend(row0.iter().map(|h| -h));
        w.cur_im.clear();
        w.cur_im.resize(n, 0.0);
        w.cur_re[0] += s.re;
        w.cur_im[0] += s.im;
        w.acc_re.clear();
        w.acc_re.resize(p * n, 0.0);
        w.acc_im.clear();
        w.acc_im.resize(p * n, 0.0);
        w.y_re.clear();
        w.y_re.extend_from_slice(&self.b[..m]);
        w.y_im.clear();
        w.y_im.resize(m, 0.0);
        let mut z = vec![Complex64::new(0.0, 0.0); p];
        let mut yk = vec![Complex64::new(0.0, 0.0); m];
        for k in 0..n {
            let ck = Complex64::new(w.cur_re[k], w.cur_im[k]);
            let (next, sub) = if k + 1 < n {
                let r = &self.rows[self.row_start[k + 1]..self.row_start[k + 1] + (n - k)];
                (r, r[0])
            } else {
                (&self.rows[..0], 0.0)
            };
            let swap = sub.abs() > ck.re.abs() + ck.im.abs();
            let mut ukk = if swap { Complex64::new(-sub, 0.0) } else { ck };
            if ukk.re == 0.0 && ukk.im == 0.0 {
                ukk = Complex64::new(self.tiny, 0.0);
            }
            // z_k = (C̃[:, k] − acc[:, k]) / u_kk and y_k.
            for (q, zq) in z.iter_mut().enumerate() {
                let a = Complex64::new(w.acc_re[q * n + k], w.acc_im[q * n + k]);
                *zq = (Complex64::new(self.c[k * p + q], 0.0) - a) / ukk;
            }
            let brow = |i: usize| &self.b[i * m..(i + 1) * m];
            if swap {
                for (t, &x) in yk.iter_mut().zip(brow(k + 1)) {
                    *t = Complex64::new(x, 0.0);
                }
            } else {
                for (t, (&re, &im)) in yk.iter_mut().zip(w.y_re.iter().zip(&w.y_im)) {
                    *t = Complex64::new(re, im);
                }
            }
            for (q, zq) in z.iter().enumerate() {
                for (j, yj) in yk.iter().enumerate() {
                    let g = zq * yj;
                    w.g_re[q * m + j] += g.re;
                    w.g_im[q * m + j] += g.im;
                }
            }
            if k + 1 == n {
                break;
            }
            let l = if swap {
                ck / ukk
            } else {
                Complex64::new(-sub, 0.0) / ukk
            };
            // Column k+1 (holds s) by hand, the rest in the vector loops.
            let mk1 = Complex64::new(s.re - next[1], s.im);
            let old = Complex64::new(w.cur_re[k + 1], w.cur_im[k + 1]);
            let (u1, new1) = if swap {
                (mk1, old - l * mk1)
            } else {
                (old, mk1 - l * old)
            };
            for (q, zq) in z.iter().enumerate() {
                let a = zq * u1;
                w.acc_re[q * n + k + 1] += a.re;
                w.acc_im[q * n + k + 1] += a.im;
            }
            w.cur_re[k + 1] = new1.re;
            w.cur_im[k + 1] = new1.im;
            let tail = &next[2..];
            let (cre, cim) = (&mut w.cur_re[k + 2..], &mut w.cur_im[k + 2..]);
            for (q, zq) in z.iter().enumerate() {
                let are = &mut w.acc_re[q * n + k + 2..(q + 1) * n];
                let aim = &mut w.acc_im[q * n + k + 2..(q + 1) * n];
                if swap {
                    acc_update_real(are, aim, *zq, tail);
                } else {
                    acc_update(are, aim, *zq, cre, cim);
                }
            }
            if swap {
                eliminate_swapped(cre, cim, l, tail);
                for (i, &x) in brow(k + 1).iter().enumerate() {
                    let t = Complex64::new(w.y_re[i], w.y_im[i]) - l * x;
                    w.y_re[i] = t.re;
                    w.y_im[i] = t.im;
                }
            } else {
                eliminate(cre, cim, l, tail);
                for (i, &x) in brow(k + 1).iter().enumerate() {
                    let t = Complex64::new(x, 0.0) - l * Complex64::new(w.y_re[i], w.y_im[i]);
                    w.y_re[i] = t.re;
                    w.y_im[i] = t.im;
                }
            }
        }
    }
}

/// acc += z·u for complex u (the old current row).
#[inline(always)]
fn acc_update(are: &mut [f64], aim: &mut [f64], z: Complex64, ure: &[f64], uim: &[f64]) {
    for (((ar, ai), &ur), &ui) in are.iter_mut().zip(aim.iter_mut()).zip(ure).zip(uim) {
        *ar += z.re * ur - z.im * ui;
        *ai += z.re * ui + z.im * ur;
    }
}

/// acc += z·u for u = −h (a row of −H, real).
#[inline(always)]
fn acc_update_real(are: &mut [f64], aim: &mut [f64], z: Complex64, h: &[f64]) {
    for ((ar, ai), &hj) in are.iter_mut().zip(aim.iter_mut()).zip(h) {
        *ar -= z.re * hj;
        *ai -= z.im * hj;
    }
}

/// cur ← −h − l·cur (row k+1 of sI − H minus l times the pivot row).
#[inline(always)]
fn eliminate(cre: &mut [f64], cim: &mut [f64], l: Complex64, h: &[f64]) {
    for ((cr, ci), &hj) in cre.iter_mut().zip(cim.iter_mut()).zip(h) {
        let (r, i) = (*cr, *ci);
        *cr = -hj - (l.re * r - l.im * i);
        *ci = -(l.re * i + l.im * r);
    }
}

/// cur ← cur − l·(−h) (the pivot row is row k+1 of sI − H).
#[inline(always)]
fn eliminate_swapped(cre: &mut [f64], cim: &mut [f64], l: Complex64, h: &[f64]) {
    for ((cr, ci), &hj) in cre.iter_mut().zip(cim.iter_mut()).zip(h) {
        *cr += l.re * hj;
        *ci += l.im * hj;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dense(
        a: &DMatrix<f64>,
        b: &DMatrix<f64>,
        c: &DMatrix<f64>,
        d: &DMatrix<f64>,
        s: Complex64,
    ) -> DMatrix<Complex64> {
        let n = a.nrows();
        let m = DMatrix::from_fn(n, n, |i, j| {
            let e = if i == j { s } else { Complex64::new(0.0, 0.0) };
            e - a[(i, j)]
        });
        let bc = b.map(|x| Complex64::new(x, 0.0));
        let x = m.lu().solve(&bc).unwrap();
        c.map(|x| Complex64::new(x, 0.0)) * x + d.map(|x| Complex64::new(x, 0.0))
    }

    #[test]
    fn mimo_against_dense_solve() {
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for &(n, m, p) in &[(6, 2, 3), (7, 3, 2), (1, 1, 1), (5, 1, 4)] {
            let a = DMatrix::from_fn(n, n, |_, _| rnd());
            let b = DMatrix::from_fn(n, m, |_, _| rnd());
            let c = DMatrix::from_fn(p, n, |_, _| rnd());
            let d = DMatrix::from_fn(p, m, |_, _| rnd());
            let g = HessenbergResponse::new(&a, &b, &c, &d).unwrap();
            for &s in &[
                Complex64::new(0.0, 0.3),
                Complex64::new(-0.2, 5.0),
                Complex64::new(1.0, 0.0),
            ] {
                let want = dense(&a, &b, &c, &d, s);
                let got = g.eval(s);
                assert_eq!(got.shape(), (p, m));
                let err = (&got - &want).norm() / want.norm();
                assert!(err < 1e-13, "n={n} m={m} p={p}: {err:e}");
            }
        }
    }

    #[test]
    fn empty_and_bad_dimensions() {
        let a = DMatrix::<f64>::zeros(0, 0);
        let g = HessenbergResponse::new(
            &a,
            &DMatrix::zeros(0, 1),
            &DMatrix::zeros(1, 0),
            &DMatrix::from_element(1, 1, 2.5),
        )
        .unwrap();
        assert_eq!(
            g.eval_siso(Complex64::new(0.0, 1.0)),
            Complex64::new(2.5, 0.0)
        );
        let a = DMatrix::<f64>::zeros(2, 2);
        let err = HessenbergResponse::new(
            &a,
            &DMatrix::zeros(3, 1),
            &DMatrix::zeros(1, 2),
            &DMatrix::zeros(1, 1),
        )
        .unwrap_err();
        assert!(err.to_string().contains("B must be"), "{err}");
    }

    #[test]
    fn derivative_against_the_closed_form() {
        // G(s) = 4/(s² + 0.8s + 4) in a dense realisation: G′ = −4(2s + 0.8)/(s² + 0.8s + 4)²
        let a = DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.3, -4.0, -0.8, 0.1, 0.0, 0.0, -5.0]);
        let b = DMatrix::from_row_slice(3, 1, &[0.0, 4.0, 0.0]);
        let c = DMatrix::from_row_slice(1, 3, &[1.0, 0.0, 0.7]);
        let d = DMatrix::from_element(1, 1, 0.25);
        let h = HessenbergResponse::new(&a, &b, &c, &d).unwrap();
        for s in [
            Complex64::new(0.0, 2.0),
            Complex64::new(-0.3, 0.7),
            Complex64::new(1.0, -3.0),
        ] {
            let q = s * s + 0.8 * s + 4.0;
            let (g, dg, terms) = h.eval_siso_with_derivative(s).unwrap();
            assert!(terms >= g.norm() * (1.0 - 1e-15));
            assert!((g - (4.0 / q + 0.25)).norm() < 1e-14 * g.norm());
            let exact = -4.0 * (2.0 * s + 0.8) / (q * q);
            assert!(
                (dg - exact).norm() < 1e-13 * exact.norm(),
                "{dg} vs {exact}"
            );
            assert!((g - h.eval_siso(s)).norm() < 1e-14 * g.norm());
        }
    }

    #[test]
    fn at_a_pole_the_value_is_huge_not_nan() {
        let a = DMatrix::from_row_slice(1, 1, &[-1.0]);
        let one = DMatrix::from_element(1, 1, 1.0);
        let g = HessenbergResponse::new(&a, &one, &one, &DMatrix::zeros(1, 1)).unwrap();
        let v = g.eval_siso(Complex64::new(-1.0, 0.0));
        assert!(v.re.is_finite() && v.re.abs() > 1e14);
    }
}
