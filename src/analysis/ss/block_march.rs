//! Blocks of a long run of equal steps under a constant input, for the dense march of
//! [`super::time`]: J samples for about the price of one.
//!
//! Stepping x ← Φx + g (Φ = e^(Ah), g = Γ₀u the held input's share) costs one n×n
//! matrix–vector product per sample. Over a block of J steps from x_b the outputs are
//! y_(b+j) = CΦʲ·x_b + fⱼ + Du with fⱼ = Σ_(i<j) CΦⁱg, and the state at the block's end is
//! Φᴶ·x_b + s_J with s_J = Σ_(i<J) Φⁱg. With W = \[C; CΦ; …; CΦ^(J−1)\] (Jp×n) precomputed, a
//! block costs one W·x_b (J·p·n) and one Φᴶ·x_b (n²): about p·n + n²/J per sample instead of
//! n². W, Φᴶ and s_J come from log₂J squarings by doubling (W's lower half is its upper half
//! times Φ^m, s_(2m) = s_m + Φ^m·s_m), matrix–matrix products that run at several times the
//! speed of the matrix–vector products they replace.
//!
//! The values are the same sums as the sample-by-sample march, grouped differently: the
//! rounding is of the same order (products of at most log₂J + 1 factors per term). The block
//! length is chosen by a cost model ([`block_len`]); short runs, small orders and marches that
//! record the states stay sample by sample.

use std::rc::Rc;

use nalgebra::{DMatrix, DVector};

use crate::error::{LtiError, Result};
use crate::numeric::linalg::matvec::{mat_vec, vec_mat};

/// Smallest order for which blocks are considered (below it a sample costs a few dozen
/// flops and the plain march is as fast).
pub(crate) const BLOCK_MIN_ORDER: usize = 16;

/// Largest W (J·p·n entries, 32 MB): the block length is capped so W stays below it.
const MAX_W_ENTRIES: usize = 1 << 22;

/// The cost of one flop of a matrix–matrix product relative to one of a matrix–vector product
/// (measured: a 256×256 product at ~50 Gflop/s against ~12 Gflop/s for the product with a
/// vector, one core with FMA; `examples/bench_ss_json.rs` times the march as a whole).
const GEMM_RELATIVE_COST: f64 = 0.25;

/// The block length J (a power of two, 2 ≤ J ≤ `run`) that minimises the estimated cost of a
/// run of `run` steps of an order-`n` model with `p` outputs, or `None` when blocks would not
/// save at least half of the plain march's n² per step.
pub(crate) fn block_len(n: usize, p: usize, run: usize) -> Option<usize> {
    if n < BLOCK_MIN_ORDER || run < 4 {
        return None;
    }
    let (nf, pf, rf) = (n as f64, p.max(1) as f64, run as f64);
    let plain = rf * nf * nf;
    let mut best: Option<(f64, usize)> = None;
    let mut j = 2usize;
    while j <= run && j * p.max(1) * n <= MAX_W_ENTRIES {
        let jf = j as f64;
        // squarings and W's doubling products, then per block Φᴶ·x and W·x
        let build = GEMM_RELATIVE_COST * (jf.log2() * nf * nf * nf + jf * pf * nf * nf);
        let march = (rf / jf).ceil() * nf * nf + rf * pf * nf;
        let cost = build + march;
        if best.is_none_or(|(c, _)| cost < c) {
            best = Some((cost, j));
        }
        j *= 2;
    }
    best.and_then(|(cost, j)| (cost < 0.5 * plain).then_some(j))
}

/// The maps of one block length J for a step map (Φ, g) and an output map C (+ D·u).
#[derive(Debug)]
pub(crate) struct BlockMap {
    /// J.
    len: usize,
    /// W = \[C; CΦ; …; CΦ^(J−1)\], row j·p + o for output o after j steps.
    w: DMatrix<f64>,
    /// fⱼ + D·u, same row order.
    f: DVector<f64>,
    /// Φᴶ.
    phi_len: DMatrix<f64>,
    /// s_J = Σ_(i<J) Φⁱg.
    s_len: DVector<f64>,
    /// Φ and g, to settle the state inside a block.
    phi: DMatrix<f64>,
    g: DVector<f64>,
}

impl BlockMap {
    /// The block maps of length `len` (≥ 2, a power of two) for x ← Φx + g, y = Cx + du.
    ///
    /// Errors: a non-finite power (Φᴶ overflows: the march diverges).
    pub(crate) fn new(
        phi: &DMatrix<f64>,
        g: &DVector<f64>,
        c: &DMatrix<f64>,
        du: &DVector<f64>,
        len: usize,
    ) -> Result<BlockMap> {
        let (n, p) = (phi.nrows(), c.nrows());
        let mut w = DMatrix::zeros(len * p, n);
        w.view_mut((0, 0), (p, n)).copy_from(c);
        let mut power = phi.clone(); // Φ^m
        let mut s = g.clone(); // s_m
        let mut m = 1;
        let mut scratch = DMatrix::zeros(n, n);
        let mut step = DVector::zeros(n);
        let mut row_out = vec![0.0; n];
        while m < len {
            // W[m..2m] = W[0..m]·Φ^m, s_2m = s_m + Φ^m·s_m, then Φ^2m
            if m * p >= 8 {
                let (top, mut bottom) = w.rows_range_pair_mut(0..m * p, m * p..2 * m * p);
                bottom.gemm(1.0, &top, &power, 0.0);
            } else {
                // a few rows: nalgebra's gemm would take its strided kernel
                for k in 0..m * p {
                    let row: Vec<f64> = w.row(k).iter().copied().collect();
                    vec_mat(&row, &power, &mut row_out);
                    for (j, v) in row_out.iter().enumerate() {
                        w[(m * p + k, j)] = *v;
                    }
                }
            }
            mat_vec(&power, s.as_slice(), step.as_mut_slice());
            s += &step;
            scratch.gemm(1.0, &power, &power, 0.0);
            std::mem::swap(&mut power, &mut scratch);
            m *= 2;
            if power.iter().any(|v| !v.is_finite()) {
                return Err(LtiError::Overflow {
                    what: format!("the state transition over {m} steps"),
                    reason: "the response diverges".into(),
                });
            }
        }
        // fⱼ = Σ_(i<j) CΦⁱg: prefix sums of W·g
        let mut wg = DVector::zeros(len * p);
        mat_vec(&w, g.as_slice(), wg.as_mut_slice());
        let mut f = DVector::zeros(len * p);
        for j in 1..len {
            for o in 0..p {
                f[j * p + o] = f[(j - 1) * p + o] + wg[(j - 1) * p + o];
            }
        }
        for j in 0..len {
            for o in 0..p {
                f[j * p + o] += du[o];
            }
        }
        Ok(BlockMap {
            len,
            w,
            f,
            phi_len: power,
            s_len: s,
            phi: phi.clone(),
            g: g.clone(),
        })
    }
}

/// The march's state: x itself, or (inside a run marched by blocks) the block's start x_b, the
/// steps taken since and the block's outputs; x = Φʲ·x_b + sⱼ is formed only when the run
/// ends ([`BlockState::settle`]).
#[derive(Debug)]
pub(crate) struct BlockState {
    x: DVector<f64>,
    block: Option<Block>,
    /// Room for the next state.
    next: DVector<f64>,
}

#[derive(Debug)]
struct Block {
    map: Rc<BlockMap>,
    steps: usize,
    y: DVector<f64>,
}

impl BlockState {
    /// The state x₀, outside any block.
    pub(crate) fn new(x: DVector<f64>) -> BlockState {
        let next = DVector::zeros(x.len());
        BlockState {
            x,
            block: None,
            next,
        }
    }

    /// Ends a block in progress: x = Φʲ·x_b + sⱼ by j plain steps (j < J).
    pub(crate) fn settle(&mut self) -> &mut DVector<f64> {
        if let Some(b) = self.block.take() {
            for _ in 0..b.steps {
                mat_vec(&b.map.phi, self.x.as_slice(), self.next.as_mut_slice());
                self.next += &b.map.g;
                std::mem::swap(&mut self.x, &mut self.next);
            }
        }
        &mut self.x
    }

    /// One step with the block map `map`: a new block starts when none of this map is in
    /// progress (the block outputs W·x_b + f), the state jumps by Φᴶ at a block's end.
    pub(crate) fn advance(&mut self, map: &Rc<BlockMap>) {
        let same = self.block.as_ref().is_some_and(|b| Rc::ptr_eq(&b.map, map));
        if !same {
            self.settle();
            let mut y = DVector::zeros(map.f.len());
            mat_vec(&map.w, self.x.as_slice(), y.as_mut_slice());
            y += &map.f;
            self.block = Some(Block {
                map: Rc::clone(map),
                steps: 0,
                y,
            });
        }
        if let Some(b) = self.block.as_mut() {
            b.steps += 1;
            if b.steps == b.map.len {
                mat_vec(&b.map.phi_len, self.x.as_slice(), self.next.as_mut_slice());
                self.next += &b.map.s_len;
                std::mem::swap(&mut self.x, &mut self.next);
                mat_vec(&b.map.w, self.x.as_slice(), b.y.as_mut_slice());
                b.y += &b.map.f;
                b.steps = 0;
            }
        }
    }

    /// The outputs now: from the block's buffer inside a block (D·u included), else `None`.
    pub(crate) fn outputs(&self) -> Option<&[f64]> {
        self.block.as_ref().map(|b| {
            let p = b.y.len() / b.map.len;
            &b.y.as_slice()[b.steps * p..(b.steps + 1) * p]
        })
    }

    /// The state x (outside a block) or the current block's start (inside one): for the norm
    /// in a divergence message.
    pub(crate) fn anchor(&self) -> &DVector<f64> {
        &self.x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_only_where_they_pay() {
        assert_eq!(block_len(8, 1, 10_000), None, "small order");
        assert_eq!(block_len(256, 1, 10), None, "short run");
        // the dense 64-state closed-form test of tests/ss_time.rs takes blocks
        assert!(block_len(64, 2, 5000).is_some());
        let j = block_len(256, 1, 10_000).unwrap();
        assert!(j.is_power_of_two() && (16..=256).contains(&j), "{j}");
        // W bounded: 256 outputs of 2048 states leave J ≤ 8
        assert!(block_len(2048, 256, 1_000_000).is_none_or(|j| j * 256 * 2048 <= MAX_W_ENTRIES));
    }

    #[test]
    fn blocks_reproduce_the_plain_march() {
        // a 20-state rotation-and-decay chain (|λ| ≤ √(0.9² + 0.4²) < 1); 1000 steps by blocks
        // of 8 against x ← Φx + g, relative to the largest output
        let n = 20;
        let phi = DMatrix::from_fn(n, n, |i, j| {
            if i == j {
                0.9
            } else if j == i + 1 {
                0.2
            } else if i == j + 1 {
                -0.2
            } else {
                0.0
            }
        });
        let g = DVector::from_fn(n, |i, _| 1.0 / (1.0 + i as f64));
        let c = DMatrix::from_fn(2, n, |o, j| ((o + 1) * (j + 1)) as f64 / n as f64);
        let du = DVector::from_vec(vec![0.5, -0.25]);
        let map = Rc::new(BlockMap::new(&phi, &g, &c, &du, 8).unwrap());
        let mut st = BlockState::new(DVector::zeros(n));
        let mut x = DVector::zeros(n);
        let (mut worst, mut scale) = (0.0f64, 0.0f64);
        for _ in 0..1000 {
            st.advance(&map);
            x = &phi * &x + &g;
            let y = &c * &x + &du;
            let yb = st.outputs().unwrap();
            for o in 0..2 {
                worst = worst.max((yb[o] - y[o]).abs());
                scale = scale.max(y[o].abs());
            }
        }
        assert!(worst < 1e-13 * scale, "{worst:e} of {scale:e}");
        // leaving the block mid-way gives back the state
        let xs = st.settle().clone();
        assert!(
            (&xs - &x).norm() < 1e-13 * x.norm(),
            "{}",
            (&xs - &x).norm()
        );
    }
}
