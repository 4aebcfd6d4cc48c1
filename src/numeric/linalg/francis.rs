//! The Francis double-shift QR iteration on an upper Hessenberg matrix: real Schur form T,
//! optionally with the accumulated orthogonal transformation.
//!
//! # Method
//! The implicit double-shift QR algorithm as in LAPACK's `dlahqr` (Golub & Van Loan §7.5),
//! written from the published algorithm:
//! - **deflation** by the conservative criterion of Ahues & Tisseur (LAPACK Working Note 122):
//!   a subdiagonal entry is set to zero when it is negligible relative to its neighbours, not
//!   only to ‖H‖ — this keeps small eigenvalues accurate to high relative precision;
//! - **shifts**: the eigenvalues of the trailing 2×2 block (two real ones are replaced by the
//!   one closer to the corner, used twice); every 10th iteration without deflation an
//!   *exceptional shift* built from the subdiagonal (alternately at the bottom and at the top
//!   of the active block) breaks cycles such as the companion matrix of sⁿ ± c (DESIGN §5);
//! - the bulge starts at the lowest row where two consecutive small subdiagonal entries
//!   allow it;
//! - **2×2 blocks** are standardised by `lanv2`: a block with real eigenvalues is split
//!   (made upper triangular by a rotation), a complex pair has equal diagonal entries and
//!   off-diagonal entries of opposite signs, so eigenvalues are read without cancellation
//!   (nalgebra's Schur leaves blocks with real eigenvalues and a NaN imaginary part).
//!
//! The iteration is capped ([`MAX_ITER_PER_ROW`]·n sweeps in total); exhaustion is reported,
//! never looped on.

/// Sweeps allowed per row of the matrix (in total, not per eigenvalue). LAPACK allows 30 per
/// row per deflation; in practice 2–4 sweeps per eigenvalue suffice.
pub const MAX_ITER_PER_ROW: usize = 30;

/// Iterations without deflation between exceptional shifts (LAPACK's KEXSH).
const EXCEPTIONAL_EVERY: usize = 10;

/// Column-major n×n view.
struct Mat<'a> {
    d: &'a mut [f64],
    n: usize,
}

impl Mat<'_> {
    #[inline(always)]
    fn at(&self, i: usize, j: usize) -> f64 {
        self.d[i + j * self.n]
    }
    #[inline(always)]
    fn set(&mut self, i: usize, j: usize, x: f64) {
        self.d[i + j * self.n] = x;
    }
}

/// Runs the double-shift QR iteration on the upper Hessenberg `h` (n×n, column-major, finite).
///
/// With `want_t` the whole quasi-triangular T is kept up to date (needed for Schur vectors,
/// eigenvectors and multiplicities); without it only the diagonal blocks are correct (enough
/// for eigenvalues, ~2× faster). `z` (n×n column-major), when given, is multiplied on the
/// right by every transformation (pass Q of the Hessenberg reduction to get the Schur
/// vectors of the original matrix).
///
/// Returns `Err(sweeps)` when the iteration cap is reached.
pub(crate) fn hqr(
    h: &mut [f64],
    n: usize,
    want_t: bool,
    mut z: Option<&mut [f64]>,
) -> Result<usize, usize> {
    let mut m = Mat { d: h, n };
    if n == 0 {
        return Ok(0);
    }
    for j in 0..n.saturating_sub(2) {
        m.set(j + 2, j, 0.0);
        if j + 3 < n {
            m.set(j + 3, j, 0.0);
        }
    }
    let ulp = f64::EPSILON;
    let smlnum = f64::MIN_POSITIVE * (n as f64 / ulp);
    let cap = MAX_ITER_PER_ROW * n.max(10);
    let mut total = 0usize;
    let mut since_deflation = 0usize;
    // Active block is rows/columns l..=i; `hi` = i + 1 is the number of rows not yet deflated.
    let mut hi = n;
    let mut work = Vec::new();
    while hi > 0 {
        let i = hi - 1;
        let l = deflation_point(&mut m, i, ulp, smlnum);
        if l == i {
            hi -= 1;
            since_deflation = 0;
            continue;
        }
        if l + 1 == i {
            standardize_block(&mut m, i - 1, want_t, z.as_deref_mut());
            hi -= 2;
            since_deflation = 0;
            continue;
        }
        if total >= cap {
            return Err(total);
        }
        total += 1;
        since_deflation += 1;
        let shifts = pick_shifts(&m, l, i, since_deflation);
        let (start, v) = bulge_start(&m, l, i, shifts, ulp);
        chase(&mut m, l, i, start, v, want_t, z.as_deref_mut(), &mut work);
    }
    Ok(total)
}

/// The start l of the unreduced block ending at row i: the largest k ≤ i with a negligible
/// subdiagonal entry h\[k, k−1\] (set to zero), or 0.
fn deflation_point(m: &mut Mat, i: usize, ulp: f64, smlnum: f64) -> usize {
    let mut k = i;
    while k > 0 {
        let sub = m.at(k, k - 1).abs();
        if sub <= smlnum {
            m.set(k, k - 1, 0.0);
            return k;
        }
        let mut tst = m.at(k - 1, k - 1).abs() + m.at(k, k).abs();
        if tst == 0.0 {
            if k >= 2 {
                tst += m.at(k - 1, k - 2).abs();
            }
            if k < i {
                tst += m.at(k + 1, k).abs();
            }
        }
        // Ahues & Tisseur: compare with the neighbours, conservatively.
        if sub <= ulp * tst {
            let up = m.at(k - 1, k).abs();
            let ab = sub.max(up);
            let ba = sub.min(up);
            let diff = (m.at(k - 1, k - 1) - m.at(k, k)).abs();
            let hkk = m.at(k, k).abs();
            let aa = hkk.max(diff);
            let bb = hkk.min(diff);
            let s = aa + ab;
            if ba * (ab / s) <= smlnum.max(ulp * (bb * (aa / s))) {
                m.set(k, k - 1, 0.0);
                return k;
            }
        }
        k -= 1;
    }
    0
}

/// The double shift as (re1, im1, re2, im2): eigenvalues of the trailing 2×2 block, or an
/// exceptional shift every [`EXCEPTIONAL_EVERY`] iterations without deflation.
fn pick_shifts(m: &Mat, l: usize, i: usize, its: usize) -> (f64, f64, f64, f64) {
    let (h11, h21, h12, h22) = if its % (2 * EXCEPTIONAL_EVERY) == 0 {
        let s = m.at(l + 1, l).abs() + m.at(l + 2, l + 1).abs();
        let h11 = 0.75 * s + m.at(l, l);
        (h11, s, -0.4375 * s, h11)
    } else if its % EXCEPTIONAL_EVERY == 0 {
        let s = m.at(i, i - 1).abs() + m.at(i - 1, i - 2).abs();
        let h11 = 0.75 * s + m.at(i, i);
        (h11, s, -0.4375 * s, h11)
    } else {
        (
            m.at(i - 1, i - 1),
            m.at(i, i - 1),
            m.at(i - 1, i),
            m.at(i, i),
        )
    };
    let s = h11.abs() + h12.abs() + h21.abs() + h22.abs();
    if s == 0.0 {
        return (0.0, 0.0, 0.0, 0.0);
    }
    let (h11, h21, h12, h22) = (h11 / s, h21 / s, h12 / s, h22 / s);
    let tr = 0.5 * (h11 + h22);
    let det = (h11 - tr) * (h22 - tr) - h12 * h21;
    let rtdisc = det.abs().sqrt();
    if det >= 0.0 {
        // Complex conjugate shifts.
        (tr * s, rtdisc * s, tr * s, -rtdisc * s)
    } else {
        // Two real shifts: use the one closer to h22 twice.
        let r1 = tr + rtdisc;
        let r2 = tr - rtdisc;
        let r = if (r1 - h22).abs() <= (r2 - h22).abs() {
            r1
        } else {
            r2
        };
        (r * s, 0.0, r * s, 0.0)
    }
}

/// The row where the bulge starts and the first column of (H − σ₁)(H − σ₂) there (scaled).
fn bulge_start(
    m: &Mat,
    l: usize,
    i: usize,
    sh: (f64, f64, f64, f64),
    ulp: f64,
) -> (usize, [f64; 3]) {
    let (rt1r, rt1i, rt2r, rt2i) = sh;
    let mut k = i - 2;
    loop {
        let h21s = m.at(k + 1, k);
        let s = (m.at(k, k) - rt2r).abs() + rt2i.abs() + h21s.abs();
        let s = if s == 0.0 { 1.0 } else { s };
        let h21s = h21s / s;
        let mut v = [
            h21s * m.at(k, k + 1) + (m.at(k, k) - rt1r) * ((m.at(k, k) - rt2r) / s)
                - rt1i * (rt2i / s),
            h21s * (m.at(k, k) + m.at(k + 1, k + 1) - rt1r - rt2r),
            h21s * m.at(k + 2, k + 1),
        ];
        let s = v[0].abs() + v[1].abs() + v[2].abs();
        if s != 0.0 {
            for x in &mut v {
                *x /= s;
            }
        }
        if k == l {
            return (k, v);
        }
        let h00 = m.at(k, k - 1).abs() * (v[1].abs() + v[2].abs());
        let h01 =
            v[0].abs() * (m.at(k - 1, k - 1).abs() + m.at(k, k).abs() + m.at(k + 1, k + 1).abs());
        if h00 <= ulp * h01 {
            return (k, v);
        }
        k -= 1;
    }
}

/// Reflectors chased before the updates far from the bulge are applied (see [`chase`]).
const SEGMENT: usize = 24;

/// One 3-element (or 2-element, at the bottom) reflector of the chase: position k, length,
/// τ and v = (1, v₁, v₂).
#[derive(Clone, Copy)]
struct Refl3 {
    k: usize,
    nr: usize,
    tau: f64,
    v1: f64,
    v2: f64,
}

/// Chases the bulge from row `start` to the bottom of the active block l..=i.
///
/// The reflectors are applied at once only near the bulge (rows and columns of the current
/// segment of [`SEGMENT`] positions); the parts of T to the right and above, and Z, are
/// updated once per segment, column by column (left) or in row chunks that stay in cache
/// (right). Same operations as the textbook order, far less memory traffic.
#[allow(clippy::too_many_arguments)] // one sweep's state, passed once per bulge step
fn chase(
    m: &mut Mat,
    l: usize,
    i: usize,
    start: usize,
    v0: [f64; 3],
    want_t: bool,
    mut z: Option<&mut [f64]>,
    work: &mut Vec<f64>,
) {
    let n = m.n;
    let (col_end, row_start) = if want_t { (n, 0) } else { (i + 1, l) };
    let mut refl: Vec<Refl3> = Vec::with_capacity(SEGMENT);
    let mut k0 = start;
    while k0 < i {
        let k1 = (k0 + SEGMENT).min(i);
        let w_end = (k1 + 2).min(i + 1);
        refl.clear();
        for k in k0..k1 {
            let nr = 3.min(i - k + 1);
            let mut v = if k == start {
                v0
            } else {
                let mut t = [0.0; 3];
                for (r, x) in t.iter_mut().enumerate().take(nr) {
                    *x = m.at(k + r, k - 1);
                }
                t
            };
            let (beta, tau) = super::householder::make_reflector(&mut v[..nr]);
            if k > start {
                m.set(k, k - 1, beta);
                m.set(k + 1, k - 1, 0.0);
                if nr == 3 {
                    m.set(k + 2, k - 1, 0.0);
                }
            } else if start > l {
                // The bulge starts below a small (not negligible) subdiagonal entry: the
                // similarity scales it by (1 − τ) (this form avoids a sign error when v₂, v₃
                // underflow).
                let x = m.at(k, k - 1) * (1.0 - tau);
                m.set(k, k - 1, x);
            }
            if tau == 0.0 {
                continue;
            }
            let r = Refl3 {
                k,
                nr,
                tau,
                v1: v[1],
                v2: if nr == 3 { v[2] } else { 0.0 },
            };
            // Near the bulge: left on columns k..w_end, right on rows k0..min(k+4, i+1).
            for j in k..w_end.min(col_end) {
                apply_left_column(&mut m.d[j * n..j * n + n], &r);
            }
            let row_end = (k + 4).min(i + 1);
            apply_right3(m.d, n, &r, k0.max(row_start)..row_end);
            refl.push(r);
        }
        // Far from the bulge: right of the window, above it, and Z.
        if w_end < col_end {
            apply_left_far(m.d, n, &refl, k0..w_end, w_end..col_end, work);
        }
        if row_start < k0 {
            apply_right_chunked(m.d, n, &refl, row_start..k0);
        }
        if let Some(zz) = z.as_deref_mut() {
            apply_right_chunked(zz, n, &refl, 0..n);
        }
        k0 = k1;
    }
}

/// One column's rows r.k..r.k+nr times the reflector from the left.
#[inline(always)]
fn apply_left_column(col: &mut [f64], r: &Refl3) {
    let (t1, t2, t3) = (r.tau, r.tau * r.v1, r.tau * r.v2);
    if r.nr == 3 {
        let c = &mut col[r.k..r.k + 3];
        let s = c[0] + r.v1 * c[1] + r.v2 * c[2];
        c[0] -= s * t1;
        c[1] -= s * t2;
        c[2] -= s * t3;
    } else {
        let c = &mut col[r.k..r.k + 2];
        let s = c[0] + r.v1 * c[1];
        c[0] -= s * t1;
        c[1] -= s * t2;
    }
}

/// Columns in a block of the far-right update (the block, SEGMENT + 2 rows by this many
/// columns, stays in the L1 cache).
const FAR_COLS: usize = 96;

/// Rows `rows` × columns `cols` of a column-major matrix times the reflectors (in order) from
/// the left: the block is copied to a row-major buffer so that every reflector updates three
/// contiguous rows (vectorisable), then copied back.
fn apply_left_far(
    d: &mut [f64],
    n: usize,
    refl: &[Refl3],
    rows: std::ops::Range<usize>,
    cols: std::ops::Range<usize>,
    work: &mut Vec<f64>,
) {
    let h = rows.len();
    work.clear();
    work.resize(h * FAR_COLS, 0.0);
    let mut c0 = cols.start;
    while c0 < cols.end {
        let w = FAR_COLS.min(cols.end - c0);
        for c in 0..w {
            let col = &d[(c0 + c) * n + rows.start..(c0 + c) * n + rows.end];
            for (r, &x) in col.iter().enumerate() {
                work[r * FAR_COLS + c] = x;
            }
        }
        for rf in refl {
            let r = rf.k - rows.start;
            let (t1, t2, t3) = (rf.tau, rf.tau * rf.v1, rf.tau * rf.v2);
            let (v1, v2) = (rf.v1, rf.v2);
            let (a, rest) = work[r * FAR_COLS..].split_at_mut(FAR_COLS);
            let (b, rest) = rest.split_at_mut(FAR_COLS);
            let (a, b) = (&mut a[..w], &mut b[..w]);
            if rf.nr == 3 {
                let c = &mut rest[..w];
                for ((x, y), z) in a.iter_mut().zip(b.iter_mut()).zip(c.iter_mut()) {
                    let s = *x + v1 * *y + v2 * *z;
                    *x -= s * t1;
                    *y -= s * t2;
                    *z -= s * t3;
                }
            } else {
                for (x, y) in a.iter_mut().zip(b.iter_mut()) {
                    let s = *x + v1 * *y;
                    *x -= s * t1;
                    *y -= s * t2;
                }
            }
        }
        for c in 0..w {
            let col = &mut d[(c0 + c) * n + rows.start..(c0 + c) * n + rows.end];
            for (r, x) in col.iter_mut().enumerate() {
                *x = work[r * FAR_COLS + c];
            }
        }
        c0 += w;
    }
}

/// Rows `rows` of a column-major matrix times the reflectors (in order) from the right, in
/// chunks of rows small enough to stay in the L1 cache across the reflectors.
fn apply_right_chunked(d: &mut [f64], n: usize, refl: &[Refl3], rows: std::ops::Range<usize>) {
    const CHUNK: usize = 64;
    let mut r0 = rows.start;
    while r0 < rows.end {
        let r1 = (r0 + CHUNK).min(rows.end);
        for r in refl {
            apply_right3(d, n, r, r0..r1);
        }
        r0 = r1;
    }
}

/// Columns k..k+nr of a column-major matrix times the reflector, on the given rows.
#[inline(always)]
fn apply_right3(d: &mut [f64], n: usize, r: &Refl3, rows: std::ops::Range<usize>) {
    if rows.is_empty() {
        return;
    }
    let (t1, t2, t3) = (r.tau, r.tau * r.v1, r.tau * r.v2);
    let (v1, v2, k) = (r.v1, r.v2, r.k);
    let (left, right) = d.split_at_mut((k + 1) * n);
    let c0 = &mut left[k * n + rows.start..k * n + rows.end];
    if r.nr == 3 {
        let (mid, last) = right.split_at_mut(n);
        let c1 = &mut mid[rows.start..rows.end];
        let c2 = &mut last[rows.start..rows.end];
        for ((a, b), c) in c0.iter_mut().zip(c1.iter_mut()).zip(c2.iter_mut()) {
            let s = *a + v1 * *b + v2 * *c;
            *a -= s * t1;
            *b -= s * t2;
            *c -= s * t3;
        }
    } else {
        let c1 = &mut right[rows.start..rows.end];
        for (a, b) in c0.iter_mut().zip(c1.iter_mut()) {
            let s = *a + v1 * *b;
            *a -= s * t1;
            *b -= s * t2;
        }
    }
}

/// Standardises the 2×2 block at rows/columns k, k+1 with `lanv2` and applies the rotation to
/// the rest of T (if `want_t`) and to z.
fn standardize_block(m: &mut Mat, k: usize, want_t: bool, z: Option<&mut [f64]>) {
    let n = m.n;
    let blk = lanv2(
        m.at(k, k),
        m.at(k, k + 1),
        m.at(k + 1, k),
        m.at(k + 1, k + 1),
    );
    m.set(k, k, blk.a);
    m.set(k, k + 1, blk.b);
    m.set(k + 1, k, blk.c);
    m.set(k + 1, k + 1, blk.d);
    let (cs, sn) = (blk.cs, blk.sn);
    if want_t {
        for j in k + 2..n {
            let (x, y) = (m.at(k, j), m.at(k + 1, j));
            m.set(k, j, cs * x + sn * y);
            m.set(k + 1, j, cs * y - sn * x);
        }
        rotate_columns(m.d, n, k, 0..k, cs, sn);
    }
    if let Some(zz) = z {
        rotate_columns(zz, n, k, 0..n, cs, sn);
    }
}

/// Columns k, k+1 ← (cs·x + sn·y, cs·y − sn·x) on the given rows.
pub(crate) fn rotate_columns(
    d: &mut [f64],
    n: usize,
    k: usize,
    rows: std::ops::Range<usize>,
    cs: f64,
    sn: f64,
) {
    let (left, right) = d.split_at_mut((k + 1) * n);
    let x = &mut left[k * n + rows.start..k * n + rows.end];
    let y = &mut right[rows.start..rows.end];
    for (a, b) in x.iter_mut().zip(y.iter_mut()) {
        let (p, q) = (*a, *b);
        *a = cs * p + sn * q;
        *b = cs * q - sn * p;
    }
}

/// A standardised 2×2 block [a b; c d] = Gᵀ·[a₀ b₀; c₀ d₀]·G, G = [cs −sn; sn cs].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Block2 {
    /// Top-left entry.
    pub a: f64,
    /// Top-right entry.
    pub b: f64,
    /// Bottom-left entry: 0 for two real eigenvalues.
    pub c: f64,
    /// Bottom-right entry (= `a` for a complex pair).
    pub d: f64,
    /// Cosine of the rotation.
    pub cs: f64,
    /// Sine of the rotation.
    pub sn: f64,
}

impl Block2 {
    /// The two eigenvalues as (re₁, im₁, re₂, im₂); a complex pair has im₁ > 0 = −im₂.
    pub(crate) fn eigenvalues(&self) -> (f64, f64, f64, f64) {
        if self.c == 0.0 {
            (self.a, 0.0, self.d, 0.0)
        } else {
            let im = self.b.abs().sqrt() * self.c.abs().sqrt();
            (self.a, im, self.d, -im)
        }
    }
}

/// Schur factorisation of a real 2×2 matrix in standard form (the method of LAPACK's
/// `dlanv2`, Bai & Demmel 1993): either c = 0 (real eigenvalues a, d) or a = d and b·c < 0
/// (eigenvalues a ± i√(−bc)), computed without cancellation for nearly equal eigenvalues.
pub(crate) fn lanv2(a: f64, b: f64, c: f64, d: f64) -> Block2 {
    let eps = f64::EPSILON;
    let sgn = |x: f64, y: f64| if y >= 0.0 { x.abs() } else { -x.abs() };
    if c == 0.0 {
        return Block2 {
            a,
            b,
            c,
            d,
            cs: 1.0,
            sn: 0.0,
        };
    }
    if b == 0.0 {
        // Swap rows and columns.
        return Block2 {
            a: d,
            b: -c,
            c: 0.0,
            d: a,
            cs: 0.0,
            sn: 1.0,
        };
    }
    if a - d == 0.0 && (b >= 0.0) != (c >= 0.0) {
        return Block2 {
            a,
            b,
            c,
            d,
            cs: 1.0,
            sn: 0.0,
        };
    }
    let temp = a - d;
    let p = 0.5 * temp;
    let bcmax = b.abs().max(c.abs());
    let bcmis = b.abs().min(c.abs()) * sgn(1.0, b) * sgn(1.0, c);
    let scale = p.abs().max(bcmax);
    let zz = (p / scale) * p + (bcmax / scale) * bcmis;
    if zz >= 4.0 * eps {
        // Real eigenvalues: compute a and d from the larger root without cancellation.
        let zr = p + sgn(scale.sqrt() * zz.sqrt(), p);
        let a1 = d + zr;
        let d1 = d - (bcmax / zr) * bcmis;
        let tau = c.hypot(zr);
        return Block2 {
            a: a1,
            b: b - c,
            c: 0.0,
            d: d1,
            cs: zr / tau,
            sn: c / tau,
        };
    }
    // Complex or nearly equal real eigenvalues: make the diagonal entries equal.
    let sigma = b + c;
    let tau = sigma.hypot(temp);
    let mut cs = (0.5 * (1.0 + sigma.abs() / tau)).sqrt();
    let mut sn = -(p / (tau * cs)) * sgn(1.0, sigma);
    // [aa bb; cc dd] = [a b; c d]·[cs −sn; sn cs]
    let (aa, bb) = (a * cs + b * sn, -a * sn + b * cs);
    let (cc, dd) = (c * cs + d * sn, -c * sn + d * cs);
    // [a b; c d] = [cs sn; −sn cs]·[aa bb; cc dd]
    let mut b1 = bb * cs + dd * sn;
    let mut c1 = -aa * sn + cc * cs;
    let temp = 0.5 * ((aa * cs + cc * sn) + (-bb * sn + dd * cs));
    let (mut a1, mut d1) = (temp, temp);
    if c1 != 0.0 && b1 != 0.0 && (b1 >= 0.0) == (c1 >= 0.0) {
        // Real eigenvalues: reduce to upper triangular form.
        let sab = b1.abs().sqrt();
        let sac = c1.abs().sqrt();
        let pp = sgn(sab * sac, c1);
        let tau = 1.0 / (b1 + c1).abs().sqrt();
        a1 = temp + pp;
        d1 = temp - pp;
        b1 -= c1;
        c1 = 0.0;
        let cs1 = sab * tau;
        let sn1 = sac * tau;
        let t = cs * cs1 - sn * sn1;
        sn = cs * sn1 + sn * cs1;
        cs = t;
    } else if c1 != 0.0 && b1 == 0.0 {
        b1 = -c1;
        c1 = 0.0;
        let t = cs;
        cs = -sn;
        sn = t;
    }
    Block2 {
        a: a1,
        b: b1,
        c: c1,
        d: d1,
        cs,
        sn,
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // these tests expect exact zeros and exact values

    /// `lanv2` on a worked example (an internal kernel: a unit test, not a doctest).
    #[test]
    #[allow(clippy::float_cmp)] // exact values are meant
    fn lanv2_example() {
        use crate::numeric::linalg::francis::lanv2;
        // Two real eigenvalues 1 and 3 from a non-triangular block.
        let blk = lanv2(2.0, 1.0, 1.0, 2.0);
        assert_eq!(blk.c, 0.0);
        let (r1, _, r2, _) = blk.eigenvalues();
        assert!((r1.max(r2) - 3.0).abs() < 1e-15 && (r1.min(r2) - 1.0).abs() < 1e-15);
        // A rotation block: ±2i.
        let (re, im, _, _) = lanv2(0.0, 2.0, -2.0, 0.0).eigenvalues();
        assert!(re == 0.0 && (im - 2.0).abs() < 1e-15);
    }
    use super::*;

    fn check_block(a: f64, b: f64, c: f64, d: f64) {
        let blk = lanv2(a, b, c, d);
        let g = nalgebra::Matrix2::new(blk.cs, -blk.sn, blk.sn, blk.cs);
        let orig = nalgebra::Matrix2::new(a, b, c, d);
        let std = nalgebra::Matrix2::new(blk.a, blk.b, blk.c, blk.d);
        let back = g * std * g.transpose();
        let scale = orig.norm().max(1e-300);
        assert!(
            (back - orig).norm() <= 4e-16 * scale,
            "{a} {b} {c} {d}: {back} vs {orig}"
        );
        assert!(
            blk.c == 0.0 || (blk.a == blk.d && blk.b * blk.c < 0.0),
            "{blk:?}"
        );
        // Trace and determinant preserved.
        let (r1, i1, r2, i2) = blk.eigenvalues();
        assert!(((r1 + r2) - (a + d)).abs() <= 4e-16 * scale * 4.0);
        let det = r1 * r2 - i1 * i2;
        assert!((det - (a * d - b * c)).abs() <= 1e-15 * scale * scale + 1e-300);
    }

    #[test]
    fn standard_forms() {
        check_block(1.0, 2.0, 3.0, 4.0);
        check_block(1.0, -2.0, 3.0, 4.0);
        check_block(0.0, 1.0, -1.0, 0.0);
        check_block(5.0, 0.0, 2.0, 1.0);
        check_block(1.0, 1e-9, 1e-9, 1.0);
        check_block(1.0, 1.0, 1e-20, 1.0);
        check_block(1.0, 1e300, -1e-300, 1.0);
        check_block(-3.0, 7.0, -0.5, 2.0);
    }

    #[test]
    fn nearly_double_real_eigenvalue_is_split() {
        // (x − 1)² − 1e-20: eigenvalues 1 ± 1e-10, nalgebra returns NaN imaginary parts here.
        let blk = lanv2(1.0, 1.0, 1e-20, 1.0);
        assert_eq!(blk.c, 0.0);
        let (r1, i1, r2, i2) = blk.eigenvalues();
        assert!(i1 == 0.0 && i2 == 0.0);
        // Near 1 an f64 is resolved to ε = 2.2e-16 (one ulp), so each eigenvalue is exact to
        // about ε/2 at best and their distance to about ε: the split is 2e-10 to that.
        assert!(
            ((r1 - r2).abs() - 2e-10).abs() <= 2.0 * f64::EPSILON,
            "{r1} {r2}"
        );
    }
}
