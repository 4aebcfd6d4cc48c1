//! One channel of a modal form as a sum of simple fractions, for fast evaluation at many
//! points.

use nalgebra::DMatrix;

use super::form::{C, ModalForm};

impl ModalForm {
    /// One channel (input → output, 0-based) as a sum of simple fractions, for fast evaluation
    /// at many points ([`ModalChannel::eval`]).
    pub fn channel(&self, input: usize, output: usize) -> ModalChannel {
        let mut simple = Vec::new();
        let mut pairs = Vec::new();
        let mut general = Vec::new();
        for (bi, blk) in self.blocks.iter().enumerate() {
            let i0 = blk.start;
            let (cr, bc) = (
                |i: usize| self.c[(output, i0 + i)],
                |i: usize| self.b[(i0 + i, input)],
            );
            match blk.lambda.nrows() {
                1 => simple.push((blk.lambda[(0, 0)], cr(0) * bc(0))),
                2 => {
                    let (a, b, t) = (blk.lambda[(0, 0)], blk.lambda[(1, 1)], blk.lambda[(0, 1)]);
                    pairs.push([a, b, cr(0) * bc(0), cr(1) * bc(1), cr(0) * t * bc(1)]);
                }
                _ => general.push(bi),
            }
        }
        ModalChannel {
            d: C::new(self.d[(output, input)], 0.0),
            simple,
            pairs,
            general: general
                .into_iter()
                .map(|bi| {
                    let blk = &self.blocks[bi];
                    let k = blk.lambda.nrows();
                    let i0 = blk.start;
                    (
                        blk.lambda.clone(),
                        (0..k).map(|i| self.c[(output, i0 + i)]).collect(),
                        (0..k).map(|i| self.b[(i0 + i, input)]).collect(),
                    )
                })
                .collect(),
        }
    }
}

/// One channel of a [`ModalForm`]: G(s) = d + Σ r/(s − λ) over the 1×1 blocks, the closed form
/// of each 2×2 block, and a back substitution for larger blocks.
#[derive(Clone, Debug)]
pub struct ModalChannel {
    d: C,
    /// (λ, r) of the 1×1 blocks.
    simple: Vec<(C, C)>,
    /// [a, b, r_a, r_b, r_ab] of the 2×2 blocks [a t; 0 b]: r_a/(s − a) + r_b/(s − b) +
    /// r_ab/((s − a)(s − b)).
    pairs: Vec<[C; 5]>,
    /// Larger blocks: (Λᵢ, Ĉᵢ row, B̂ᵢ column).
    general: Vec<(DMatrix<C>, Vec<C>, Vec<C>)>,
}

impl ModalChannel {
    /// G(s).
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::numeric::linalg::modal::ModalForm;
    /// // 1/(s + 1)² as a 2×2 Jordan block: ẋ₁ = −x₁ + x₂, ẋ₂ = −x₂ + u, y = x₁
    /// let a = DMatrix::from_row_slice(2, 2, &[-1.0, 1.0, 0.0, -1.0]);
    /// let m = ModalForm::new(&a, &DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
    ///     &DMatrix::from_row_slice(1, 2, &[1.0, 0.0]), &DMatrix::zeros(1, 1)).unwrap().unwrap();
    /// let s = num_complex::Complex64::new(0.0, 2.0);
    /// assert!((m.channel(0, 0).eval(s) - 1.0 / ((s + 1.0) * (s + 1.0))).norm() < 1e-15);
    /// ```
    pub fn eval(&self, s: C) -> C {
        let mut g = self.d;
        for &(l, r) in &self.simple {
            g += r / (s - l);
        }
        for &[a, b, ra, rb, rab] in &self.pairs {
            let (ia, ib) = (1.0 / (s - a), 1.0 / (s - b));
            g += ra * ia + rb * ib + rab * ia * ib;
        }
        for (lam, c, b) in &self.general {
            let k = lam.nrows();
            let mut v = vec![C::new(0.0, 0.0); k];
            for i in (0..k).rev() {
                let mut acc = b[i];
                for j in i + 1..k {
                    acc += lam[(i, j)] * v[j];
                }
                v[i] = acc / (s - lam[(i, i)]);
            }
            g += c.iter().zip(&v).map(|(x, y)| x * y).sum::<C>();
        }
        g
    }
}
