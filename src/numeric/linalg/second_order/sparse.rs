//! The stiffness and damping blocks of a second-order A kept by columns when they are sparse
//! (a chain couples each mass to its two neighbours, a ring adds the two corners): products
//! with them cost O(nnz·d) instead of a d×d×d product. Used for the residual of the
//! stiffness eigenproblem ([`super::SecondOrder::detect`]) and for the lower blocks of the
//! exponential ([`super::SecondOrder::zoh`]).

use nalgebra::{DMatrix, DMatrixView, DMatrixViewMut};

/// A d×d matrix by columns: for column j, the (row, value) pairs of its non-zero entries.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ColumnSparse {
    cols: Vec<Vec<(usize, f64)>>,
}

impl ColumnSparse {
    /// The d×d matrix with entries `entry(i, j)`, or `None` when it has more than `max_nnz`
    /// non-zero entries (a dense product is then as fast).
    pub(crate) fn build(
        d: usize,
        max_nnz: usize,
        entry: impl Fn(usize, usize) -> f64,
    ) -> Option<ColumnSparse> {
        let mut cols = Vec::with_capacity(d);
        let mut nnz = 0usize;
        for j in 0..d {
            let mut col = Vec::new();
            for i in 0..d {
                let x = entry(i, j);
                if x != 0.0 {
                    nnz += 1;
                    if nnz > max_nnz {
                        return None;
                    }
                    col.push((i, x));
                }
            }
            cols.push(col);
        }
        Some(ColumnSparse { cols })
    }

    /// S·V (V with d rows): column j of the result is Σₖ V_kj · S(:, k).
    pub(crate) fn mul(&self, v: &DMatrix<f64>) -> DMatrix<f64> {
        let mut out = DMatrix::<f64>::zeros(self.cols.len(), v.ncols());
        for (j, mut o) in out.column_iter_mut().enumerate() {
            for (k, col) in self.cols.iter().enumerate() {
                let x = v[(k, j)];
                if x != 0.0 {
                    for &(i, s) in col {
                        o[i] += s * x;
                    }
                }
            }
        }
        out
    }

    /// out += α·X·S (X with d columns): column j gains α·Σ over the non-zero S_kj of
    /// S_kj · X(:, k) — contiguous columns of X.
    pub(crate) fn mul_left_add(
        &self,
        x: &DMatrixView<'_, f64>,
        out: &mut DMatrixViewMut<'_, f64>,
        alpha: f64,
    ) {
        for (j, col) in self.cols.iter().enumerate() {
            let mut o = out.column_mut(j);
            for &(k, s) in col {
                o.axpy(alpha * s, &x.column(k), 1.0);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_agree_with_the_dense_ones() {
        // a ring's stiffness (2 on the diagonal, −1 to the neighbours and across the corners)
        let d = 7;
        let dense = DMatrix::from_fn(d, d, |i, j| {
            if i == j {
                2.0
            } else if (i + 1) % d == j || (j + 1) % d == i {
                -1.0
            } else {
                0.0
            }
        });
        let s = ColumnSparse::build(d, 3 * d, |i, j| dense[(i, j)]).unwrap();
        let v = DMatrix::from_fn(d, 3, |i, j| (i as f64 + 1.0) * 0.37 - j as f64 * 1.3);
        assert!((s.mul(&v) - &dense * &v).amax() < 1e-14);
        let x = DMatrix::from_fn(4, d, |i, j| (j as f64 - 2.0) * 0.5 + i as f64);
        let mut out = DMatrix::from_element(4, d, 1.0);
        s.mul_left_add(
            &x.view((0, 0), (4, d)),
            &mut out.view_mut((0, 0), (4, d)),
            -2.0,
        );
        let want = DMatrix::from_element(4, d, 1.0) - &x * &dense * 2.0;
        assert!((out - want).amax() < 1e-14);
        // too many non-zeros: no sparse form
        assert!(ColumnSparse::build(d, 3 * d - 1, |i, j| dense[(i, j)]).is_none());
        assert_eq!(ColumnSparse::build(d, 0, |_, _| 0.0).unwrap().cols.len(), d);
    }
}
