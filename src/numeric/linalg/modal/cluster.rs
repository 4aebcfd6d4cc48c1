//! Single-linkage clustering of complex values: the blocks of the modal form, and the
//! eigenvalue clusters of a second-order model's modes.

use num_complex::Complex64 as C;

/// Cluster labels of `values` (single linkage: values closer than `tol`, |Δ| ≤ tol, share a
/// cluster, transitively), numbered in order of first appearance.
pub(crate) fn single_linkage(values: &[C], tol: f64) -> Vec<usize> {
    let n = values.len();
    let mut label: Vec<usize> = (0..n).collect();
    fn find(l: &mut [usize], i: usize) -> usize {
        let mut r = i;
        while l[r] != r {
            r = l[r];
        }
        let mut j = i;
        while l[j] != r {
            let next = l[j];
            l[j] = r;
            j = next;
        }
        r
    }
    // sort by real part to link neighbours cheaply: pairs within tol have |Δre| ≤ tol
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| values[a].re.total_cmp(&values[b].re));
    for (x, &i) in order.iter().enumerate() {
        for &j in &order[x + 1..] {
            if values[j].re - values[i].re > tol {
                break;
            }
            if (values[i] - values[j]).norm() <= tol {
                let (ri, rj) = (find(&mut label, i), find(&mut label, j));
                if ri != rj {
                    label[ri.max(rj)] = ri.min(rj);
                }
            }
        }
    }
    let roots: Vec<usize> = (0..n).map(|i| find(&mut label, i)).collect();
    let mut id = vec![usize::MAX; n];
    let mut next = 0;
    roots
        .iter()
        .map(|&r| {
            if id[r] == usize::MAX {
                id[r] = next;
                next += 1;
            }
            id[r]
        })
        .collect()
}
