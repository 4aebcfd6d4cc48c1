//! Grouping computed eigenvalues by distance: the candidates for one multiple eigenvalue
//! (the module docs of [`super`] give the radii). The components of the graph of links
//! shorter than the largest radius, each split at the longest link of its minimum spanning
//! tree (read off one tree per component: the cut property) until its diameter fits its
//! size; a group found not to be one eigenvalue is split again, at its longest link or, when
//! large, at its median. Only geometry here; whether a group *is* one eigenvalue is decided
//! in [`super`] (condition numbers, the reduced problem).

use num_complex::Complex64;

/// Largest cluster size whose radius grows with the size; larger clusters (semisimple ones
/// such as the identity's) are held to the radius of this size.
pub const MAX_DEFECTIVE_SIZE: usize = 6;

/// Growth factor K in the cluster radius ν·(K·n·ε)^(1/m).
pub(super) const RADIUS_GROWTH: f64 = 64.0;

/// Cluster radius for a cluster of m members (see the module docs of [`super`]).
pub(crate) fn radius(m: usize, n: usize, scale: f64) -> f64 {
    let m = m.clamp(1, MAX_DEFECTIVE_SIZE) as f64;
    scale * (RADIUS_GROWTH * n.max(1) as f64 * f64::EPSILON).powf(1.0 / m)
}

/// Clustering top-down: the connected components of the graph linking eigenvalues closer
/// than 2·r_6 (the largest radius), each split at the longest link of its minimum spanning
/// tree until its diameter is within 2·r_m for its size m.
///
/// Top-down, not closest-pairs-first: the m members of a defective eigenvalue lie on a circle
/// and are about equally far apart (a Jordan block of size 3 scatters into a near-equilateral
/// triangle), so no pair of them may satisfy the bound r_2 of a pair although the three
/// together satisfy r_3; a bottom-up merge would never form the triple.
pub(super) fn link_clusters(ev: &[Complex64], scale: f64) -> Vec<Vec<usize>> {
    let n = ev.len();
    let reach = 2.0 * radius(MAX_DEFECTIVE_SIZE, n, scale);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| ev[a].re.total_cmp(&ev[b].re));
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut k: usize) -> usize {
        while parent[k] != k {
            parent[k] = parent[parent[k]];
            k = parent[k];
        }
        k
    }
    for (ia, &a) in order.iter().enumerate() {
        for &b in &order[ia + 1..] {
            if ev[b].re - ev[a].re > reach {
                break;
            }
            if dist(ev[a], ev[b]) <= reach {
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                if ra != rb {
                    parent[rb] = ra;
                }
            }
        }
    }
    let mut components: Vec<Vec<usize>> = vec![Vec::new(); n];
    for k in 0..n {
        let r = root(&mut parent, k);
        components[r].push(k);
    }
    // Each component's minimum spanning tree once; a split at a tree's longest link leaves
    // two subtrees that are the minimum spanning trees of their members (the cut property),
    // so every later split is read off the same tree: O(m) per split instead of a new O(m²)
    // tree (a random matrix's spectrum is one component, peeled a member at a time).
    let mut work: Vec<(Vec<usize>, Vec<Link>)> = components
        .into_iter()
        .filter(|g| !g.is_empty())
        .map(|g| {
            let tree = spanning_tree(&g, ev);
            (g, tree)
        })
        .collect();
    let mut out = Vec::new();
    let mut owner = vec![usize::MAX; n];
    while let Some((g, tree)) = work.pop() {
        if g.len() > 1 && diameter_exceeds(&g, ev, 2.0 * radius(g.len(), n, scale)) {
            let [left, right] = cut_longest_link(g, tree, &mut owner);
            work.push(left);
            work.push(right);
        } else {
            out.push(g);
        }
    }
    for g in &mut out {
        g.sort_unstable();
    }
    out.sort_unstable_by_key(|g| g.first().copied().unwrap_or(0));
    out
}

/// A link of a spanning tree: its two members (indices into the eigenvalues) and length.
type Link = (usize, usize, f64);

/// The minimum spanning tree of the members `g` (Prim's algorithm from `g[0]`):
/// `g.len() − 1` links, member i's link to its parent in the order of `g`.
fn spanning_tree(g: &[usize], ev: &[Complex64]) -> Vec<Link> {
    let m = g.len();
    let mut in_tree = vec![false; m];
    let mut best = vec![f64::INFINITY; m];
    let mut parent = vec![0usize; m];
    best[0] = 0.0;
    for _ in 0..m {
        let next = (0..m)
            .filter(|&i| !in_tree[i])
            .min_by(|&x, &y| best[x].total_cmp(&best[y]))
            .unwrap_or(0);
        in_tree[next] = true;
        for i in 0..m {
            if !in_tree[i] {
                let d = dist(ev[g[i]], ev[g[next]]);
                if d < best[i] {
                    best[i] = d;
                    parent[i] = next;
                }
            }
        }
    }
    (1..m).map(|i| (g[i], g[parent[i]], best[i])).collect()
}

/// Whether the largest distance between members of `g` exceeds `limit`: decided by the
/// bounding box when it can be (a side longer than `limit`, or a diagonal within it), by
/// all pairs otherwise.
fn diameter_exceeds(g: &[usize], ev: &[Complex64], limit: f64) -> bool {
    let (mut re0, mut re1, mut im0, mut im1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &k in g {
        re0 = re0.min(ev[k].re);
        re1 = re1.max(ev[k].re);
        im0 = im0.min(ev[k].im);
        im1 = im1.max(ev[k].im);
    }
    let (w, h) = (re1 - re0, im1 - im0);
    if w > limit || h > limit {
        return true;
    }
    if w.hypot(h) <= limit {
        return false;
    }
    g.iter()
        .enumerate()
        .any(|(i, &x)| g[i + 1..].iter().any(|&y| dist(ev[x], ev[y]) > limit))
}

/// The members and spanning tree split at the tree's longest link (the last of equal ones):
/// the two subtrees with their members, in the order of `g`.
/// `owner` is scratch space indexed by eigenvalue (any contents).
fn cut_longest_link(
    g: Vec<usize>,
    mut tree: Vec<Link>,
    owner: &mut [usize],
) -> [(Vec<usize>, Vec<Link>); 2] {
    let cut = (0..tree.len())
        .max_by(|&x, &y| tree[x].2.total_cmp(&tree[y].2))
        .unwrap_or(0);
    let (a, _, _) = tree.swap_remove(cut);
    // union-find over the remaining links
    for &k in &g {
        owner[k] = k;
    }
    fn root(owner: &mut [usize], mut k: usize) -> usize {
        while owner[k] != k {
            owner[k] = owner[owner[k]];
            k = owner[k];
        }
        k
    }
    for &(x, y, _) in &tree {
        let (rx, ry) = (root(owner, x), root(owner, y));
        if rx != ry {
            owner[ry] = rx;
        }
    }
    let ra = root(owner, a);
    let (mut below, mut rest) = (Vec::new(), Vec::new());
    for &k in &g {
        if root(owner, k) == ra {
            below.push(k);
        } else {
            rest.push(k);
        }
    }
    let (mut tb, mut tr) = (Vec::new(), Vec::new());
    for l in tree {
        if root(owner, l.0) == ra {
            tb.push(l);
        } else {
            tr.push(l);
        }
    }
    [(rest, tr), (below, tb)]
}

/// |a − b| without libm's `hypot` where the squares cannot overflow or underflow (the
/// clustering compares O(n²) distances: `hypot` was a sixth of a 256-state channel's
/// factorisation); `hypot` otherwise. Equal to it within an ulp.
pub(super) fn dist(a: Complex64, b: Complex64) -> f64 {
    let (dx, dy) = ((a.re - b.re).abs(), (a.im - b.im).abs());
    let m = dx.max(dy);
    if m > 1e-150 && m < 1e150 {
        (dx * dx + dy * dy).sqrt()
    } else {
        dx.hypot(dy)
    }
}

/// Splits a cluster in two at the longest link of its minimum spanning tree
/// ([`spanning_tree`], cut by [`cut_longest_link`]): (the rest, the subtree below the cut),
/// each in the order of `g`.
fn split_longest_link(g: &[usize], ev: &[Complex64]) -> (Vec<usize>, Vec<usize>) {
    if g.len() < 2 {
        return (g.to_vec(), Vec::new()); // no link to cut
    }
    let tree = spanning_tree(g, ev);
    let mut owner = vec![usize::MAX; ev.len()];
    let [(rest, _), (below, _)] = cut_longest_link(g.to_vec(), tree, &mut owner);
    (rest, below)
}

/// A group larger than this that is not one eigenvalue is split into halves (at the median
/// along its wider direction) instead of at its longest link, which in a tight cloud of
/// distinct eigenvalues peels one member at a time: log₂ m reduced problems deep, not m.
/// A multiple eigenvalue cut by such a split is missed (examined as smaller parts), never
/// invented; groups this large are far beyond the defective sizes the radii allow.
const BALANCED_SPLIT_ABOVE: usize = 32;

/// A group that is not one eigenvalue, in two: at its longest link, or in halves when large.
pub(super) fn split(g: &[usize], ev: &[Complex64]) -> [Vec<usize>; 2] {
    let (left, right) = if g.len() > BALANCED_SPLIT_ABOVE {
        split_in_halves(g, ev)
    } else {
        split_longest_link(g, ev)
    };
    [left, right]
}

/// `g` cut at the median of its members' real or imaginary parts, whichever spread more.
fn split_in_halves(g: &[usize], ev: &[Complex64]) -> (Vec<usize>, Vec<usize>) {
    let spread = |f: &dyn Fn(Complex64) -> f64| {
        let (lo, hi) = g
            .iter()
            .map(|&k| f(ev[k]))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
        hi - lo
    };
    let by_re = spread(&|z| z.re) >= spread(&|z| z.im);
    let mut sorted = g.to_vec();
    sorted.sort_by(|&a, &b| {
        if by_re {
            ev[a].re.total_cmp(&ev[b].re)
        } else {
            ev[a].im.total_cmp(&ev[b].im)
        }
    });
    let right = sorted.split_off(sorted.len() / 2);
    (sorted, right)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(re: f64, im: f64) -> Complex64 {
        Complex64::new(re, im)
    }

    /// A size-3 Jordan block scatters into a near-equilateral triangle of radius ~ε^(1/3):
    /// the three stay one group (no pair of them meets the pair radius r₂), a distant
    /// eigenvalue is a group of its own.
    #[test]
    fn a_scattered_triple_stays_together() {
        let (n, scale) = (4, 1.0);
        let rho = 0.4 * radius(3, n, scale);
        assert!(rho * 3f64.sqrt() > 2.0 * radius(2, n, scale)); // pairs too far for r₂
        let ev: Vec<Complex64> = (0..3)
            .map(|k| {
                let t = 2.0 * std::f64::consts::PI * k as f64 / 3.0;
                c(-1.0 + rho * t.cos(), rho * t.sin())
            })
            .chain([c(-3.0, 0.0)])
            .collect();
        assert_eq!(link_clusters(&ev, scale), vec![vec![0, 1, 2], vec![3]]);
    }

    /// The cut property: the two subtrees left by cutting a minimum spanning tree at its
    /// longest link are the minimum spanning trees of their members (same link lengths).
    #[test]
    fn a_cut_tree_gives_the_parts_spanning_trees() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut u = || crate::numeric::test_rng::unit(&mut seed);
        let ev: Vec<Complex64> = (0..40).map(|_| c(u(), u())).collect();
        let g: Vec<usize> = (0..40).collect();
        let tree = spanning_tree(&g, &ev);
        let mut owner = vec![usize::MAX; ev.len()];
        for (part, links) in cut_longest_link(g, tree, &mut owner) {
            let mut got: Vec<f64> = links.iter().map(|l| l.2).collect();
            let mut want: Vec<f64> = spanning_tree(&part, &ev).iter().map(|l| l.2).collect();
            got.sort_by(f64::total_cmp);
            want.sort_by(f64::total_cmp);
            assert_eq!(got.len() + 1, part.len());
            for (x, y) in got.iter().zip(&want) {
                assert!((x - y).abs() <= 1e-15, "{x} {y}");
            }
        }
    }

    /// A small group splits at its widest gap, a large one at its median.
    #[test]
    fn splits_at_the_gap_or_in_halves() {
        let ev = [c(0.0, 0.0), c(0.1, 0.0), c(5.0, 0.0)];
        assert_eq!(split(&[0, 1, 2], &ev), [vec![0, 1], vec![2]]);
        let ev: Vec<Complex64> = (0..40).map(|k| c(0.0, k as f64 * k as f64)).collect();
        let g: Vec<usize> = (0..40).collect();
        let [lo, hi] = split(&g, &ev);
        assert_eq!((lo.len(), hi.len()), (20, 20));
        assert!(lo.iter().all(|&k| k < 20) && hi.iter().all(|&k| k >= 20));
    }
}
