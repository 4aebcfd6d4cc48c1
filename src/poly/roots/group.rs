//! Step 3: grouping of the candidates and acceptance of a group as one multiple root (or its
//! split at the longest minimum-spanning-tree edge).

use num_complex::Complex64;

use super::found::{Found, GROUP_REL};
use super::newton::{bound, confirm_complex, confirm_real, polish_complex, polish_real};
use crate::poly::Poly;

/// Factor on the predicted scatter radius within which every member of a group must lie for the
/// group to be accepted as one multiple root.
pub(super) const SCATTER_FACTOR: f64 = 100.0;

/// Full-plane root count a group of upper-half-plane candidates stands for.
pub(super) fn group_weight(g: &[Complex64]) -> usize {
    g.iter().map(|z| if z.im == 0.0 { 1 } else { 2 }).sum()
}

/// Connected components of the "closer than `rel` relative" graph.
pub(super) fn link_groups(pts: &[Complex64], rel: f64) -> Vec<Vec<Complex64>> {
    let n = pts.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for i in 0..n {
        for j in i + 1..n {
            let d = (pts[i] - pts[j]).norm();
            if d <= rel * pts[i].norm().max(pts[j].norm()) {
                let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                parent[a] = b;
            }
        }
    }
    let mut groups: Vec<Vec<Complex64>> = Vec::new();
    let mut root_of: Vec<Option<usize>> = vec![None; n];
    for (i, &pt) in pts.iter().enumerate() {
        let r = find(&mut parent, i);
        match root_of[r] {
            Some(g) => groups[g].push(pt),
            None => {
                root_of[r] = Some(groups.len());
                groups.push(vec![pt]);
            }
        }
    }
    groups
}

/// Accepts `group` as one root or splits it at the longest minimum-spanning-tree edge.
pub(super) fn resolve_group(
    q: &Poly,
    group: &[Complex64],
    all: &[Complex64],
    out: &mut Vec<Found>,
) {
    if let Some(f) = accept(q, group, all) {
        out.push(f);
        return;
    }
    let (a, b) = split_longest_edge(group);
    resolve_group(q, &a, all, out);
    resolve_group(q, &b, all, out);
}

/// Tries to accept `group` (points in the closed upper half plane) as a single root.
/// Singletons are always accepted (as a simple root, or as a real double root if the point is
/// one half of a conjugate pair that splits a double real root).
pub(super) fn accept(q: &Poly, group: &[Complex64], all: &[Complex64]) -> Option<Found> {
    let n_real = group.iter().filter(|z| z.im == 0.0).count();
    let n_up = group.len() - n_real;
    let mean = group.iter().sum::<Complex64>() / group.len() as f64;
    let max_im = group.iter().map(|z| z.im).fold(0.0, f64::max);
    let spread = group.iter().map(|z| (z - mean).norm()).fold(0.0, f64::max);
    // Neighbourhood used to guard Newton steps: never move farther than half the distance to
    // the nearest candidate outside the group (or a relative GROUP_REL if there is none).
    let outside = all
        .iter()
        .filter(|z| !group.contains(z))
        .flat_map(|z| [*z, z.conj()])
        .map(|z| (z - mean).norm())
        .fold(f64::INFINITY, f64::min);
    let reach = (0.5 * outside).min(GROUP_REL * mean.norm().max(f64::MIN_POSITIVE));
    let reach = reach.max(4.0 * spread);

    let near_axis = n_real > 0 || max_im <= GROUP_REL * mean.norm();
    if near_axis {
        let m = n_real + 2 * n_up;
        let center = (group
            .iter()
            .map(|z| if z.im == 0.0 { z.re } else { 2.0 * z.re })
            .sum::<f64>())
            / m as f64;
        if m == 1 {
            return Some(Found {
                value: Complex64::new(polish_real(q, center, reach), 0.0),
                multiplicity: 1,
            });
        }
        if let Some(c) = confirm_real(q, center, m, reach)
            && members_within_scatter(q, group, Complex64::new(c, 0.0), m)
        {
            return Some(Found {
                value: Complex64::new(c, 0.0),
                multiplicity: m,
            });
        }
        if n_real > 0 {
            return None;
        }
    }
    let m = n_up;
    if m == 1 {
        let z = polish_complex(q, mean, reach.min(0.5 * mean.im.abs()));
        return Some(Found {
            value: if z.im > 0.0 { z } else { mean },
            multiplicity: 1,
        });
    }
    confirm_complex(q, mean, m, reach)
        .filter(|&c| members_within_scatter(q, group, c, m))
        .map(|c| Found {
            value: c,
            multiplicity: m,
        })
}

/// True when every member of the group lies within SCATTER_FACTOR times the radius by which
/// rounding-level coefficient perturbations scatter an m-fold root at c:
/// ρ = (γ·eps·Σ|aᵢ||c|ⁱ · m! / |p^(m)(c)|)^(1/m). This keeps a distinct neighbour (a simple
/// pair at −10 ± j next to a double root at −10) from being absorbed into the multiple root.
pub(super) fn members_within_scatter(
    q: &Poly,
    group: &[Complex64],
    c: Complex64,
    m: usize,
) -> bool {
    let dm = q.nth_derivative(m).eval_complex(c).norm();
    let factorial: f64 = (1..=m).map(|k| k as f64).product();
    let pert = bound(q, c.norm()) * factorial;
    let rho = if dm > 0.0 {
        (pert / dm).powf(1.0 / m as f64)
    } else {
        f64::INFINITY
    };
    let radius = SCATTER_FACTOR * rho;
    group.iter().all(|z| {
        let d = (z - c).norm().min((z.conj() - c).norm());
        d <= radius
    })
}

/// Splits a group (≥ 2 points) in two at the longest edge of its minimum spanning tree.
pub(super) fn split_longest_edge(g: &[Complex64]) -> (Vec<Complex64>, Vec<Complex64>) {
    let n = g.len();
    // Prim's algorithm.
    let mut in_tree = vec![false; n];
    let mut best = vec![f64::INFINITY; n];
    let mut link = vec![0usize; n];
    let mut edges: Vec<(usize, usize, f64)> = Vec::with_capacity(n - 1);
    in_tree[0] = true;
    for j in 1..n {
        best[j] = (g[j] - g[0]).norm();
    }
    for _ in 1..n {
        let (k, _) = best
            .iter()
            .enumerate()
            .filter(|(i, _)| !in_tree[*i])
            .min_by(|a, b| a.1.total_cmp(b.1))
            .expect("a vertex outside the tree remains"); // ok: loop runs n-1 times
        in_tree[k] = true;
        edges.push((link[k], k, best[k]));
        for j in 0..n {
            if !in_tree[j] {
                let d = (g[j] - g[k]).norm();
                if d < best[j] {
                    best[j] = d;
                    link[j] = k;
                }
            }
        }
    }
    let (cut, _) = edges
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.2.total_cmp(&b.1.2))
        .expect("a group of two or more points has an edge"); // ok: n >= 2
    // Components of the tree without the cut edge.
    let mut adj = vec![Vec::new(); n];
    for (i, &(a, b, _)) in edges.iter().enumerate() {
        if i != cut {
            adj[a].push(b);
            adj[b].push(a);
        }
    }
    let mut side = vec![false; n];
    let mut stack = vec![edges[cut].0];
    side[edges[cut].0] = true;
    while let Some(v) = stack.pop() {
        for &w in &adj[v] {
            if !side[w] {
                side[w] = true;
                stack.push(w);
            }
        }
    }
    let a = (0..n).filter(|&i| side[i]).map(|i| g[i]).collect();
    let b = (0..n).filter(|&i| !side[i]).map(|i| g[i]).collect();
    (a, b)
}
