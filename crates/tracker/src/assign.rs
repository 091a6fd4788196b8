//! Global nearest-neighbour assignment over gated pairs, cluster by cluster.
//!
//! Rows (tracks or initiators) and columns (plots) joined by a gated pair form a
//! bipartite graph; each connected component (cluster) is solved on its own with the
//! optimal 2-D assignment of the [`lsap`] crate (SciPy's shortest-augmenting-path
//! Jonker–Volgenant, `f64` costs, rectangular). A row may also stay unassigned at its
//! `miss` cost: the cluster's matrix is `rows × (columns + rows)` with row `i`'s own
//! dummy column at `miss[i]` and every non-gated entry at a prohibitive finite cost
//! (lsap rejects infinities). The work is linear in the number of clusters and cubic
//! only in a cluster's size.

/// A gated pair: row, column, cost.
pub(crate) type Edge = (usize, usize, f64);

/// Union-find with path halving.
fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Solves the assignment; returns for each row the column given to it, if any.
/// `miss[r]` is row `r`'s cost of staying unassigned; gated edges should cost less.
pub(crate) fn gnn(rows: usize, cols: usize, edges: &[Edge], miss: &[f64]) -> Vec<Option<usize>> {
    let mut out = vec![None; rows];
    if edges.is_empty() {
        return out;
    }
    let mut parent: Vec<usize> = (0..rows + cols).collect();
    for &(r, c, _) in edges {
        let (a, b) = (find(&mut parent, r), find(&mut parent, rows + c));
        if a != b {
            parent[a] = b;
        }
    }
    // Clusters of one edge (most of them when targets are apart) are settled at once;
    // the other edges are grouped by their cluster's root, which needs a sort.
    let mut count = vec![0_u32; rows + cols];
    let roots: Vec<usize> = edges
        .iter()
        .map(|&(r, _, _)| {
            let root = find(&mut parent, r);
            count[root] += 1;
            root
        })
        .collect();
    for (&root, &(r, c, cost)) in roots.iter().zip(edges) {
        if count[root] == 1 && cost < miss[r] {
            out[r] = Some(c);
        }
    }
    let by_root = group_by_root(&roots, &count, |n| n > 1);
    let mut start = 0;
    let mut row_ids = Vec::new();
    let mut col_ids = Vec::new();
    while start < by_root.len() {
        let root = by_root[start].0;
        let end = start + by_root[start..].partition_point(|e| e.0 == root);
        let cluster = &by_root[start..end];
        start = end;
        if let [(_, k)] = cluster {
            let (r, c, cost) = edges[*k];
            if cost < miss[r] {
                out[r] = Some(c);
            }
            continue;
        }
        row_ids.clear();
        col_ids.clear();
        for &(_, k) in cluster {
            row_ids.push(edges[k].0);
            col_ids.push(edges[k].1);
        }
        row_ids.sort_unstable();
        row_ids.dedup();
        col_ids.sort_unstable();
        col_ids.dedup();
        if row_ids.len() > MAX_OPTIMAL_ROWS {
            greedy(cluster, edges, miss, &mut out);
            continue;
        }
        let (nr, nc) = (row_ids.len(), col_ids.len());
        let width = nc + nr;
        let big = 1e6
            * (1.0
                + cluster
                    .iter()
                    .map(|&(_, k)| edges[k].2.abs())
                    .chain(row_ids.iter().map(|&r| miss[r].abs()))
                    .fold(0.0, f64::max));
        let mut cost = vec![big; nr * width];
        for (i, &r) in row_ids.iter().enumerate() {
            cost[i * width + nc + i] = miss[r];
        }
        for &(_, k) in cluster {
            let (r, c, w) = edges[k];
            let (Ok(i), Ok(j)) = (row_ids.binary_search(&r), col_ids.binary_search(&c)) else {
                continue;
            };
            cost[i * width + j] = cost[i * width + j].min(w);
        }
        if let Ok((ri, ci)) = lsap::solve(nr, width, &cost, false) {
            for (i, j) in ri.into_iter().zip(ci) {
                if j < nc && cost[i * width + j] < big {
                    out[row_ids[i]] = Some(col_ids[j]);
                }
            }
        }
    }
    out
}

/// Groups edges `(row, col)` into the connected components of the bipartite graph:
/// each group lists edge indices.
pub(crate) fn clusters(rows: usize, cols: usize, edges: &[(usize, usize)]) -> Vec<Vec<usize>> {
    let mut parent: Vec<usize> = (0..rows + cols).collect();
    for &(r, c) in edges {
        let (a, b) = (find(&mut parent, r), find(&mut parent, rows + c));
        if a != b {
            parent[a] = b;
        }
    }
    let mut count = vec![0_u32; rows + cols];
    let roots: Vec<usize> = edges
        .iter()
        .map(|&(r, _)| {
            let root = find(&mut parent, r);
            count[root] += 1;
            root
        })
        .collect();
    let by_root = group_by_root(&roots, &count, |_| true);
    let mut out: Vec<Vec<usize>> = Vec::new();
    let mut last = usize::MAX;
    for (root, k) in by_root {
        if root != last {
            out.push(Vec::new());
            last = root;
        }
        if let Some(g) = out.last_mut() {
            g.push(k);
        }
    }
    out
}

/// `(root, edge)` for the edges whose cluster size `count[root]` passes `keep`, grouped
/// by root in increasing root order and, within a root, increasing edge index: the order
/// of sorting the pairs, got by a counting sort over the roots (`O(edges + nodes)`).
fn group_by_root(
    roots: &[usize],
    count: &[u32],
    keep: impl Fn(u32) -> bool,
) -> Vec<(usize, usize)> {
    let mut next = vec![0_usize; count.len() + 1];
    for (root, &n) in count.iter().enumerate() {
        next[root + 1] = next[root] + if keep(n) { n as usize } else { 0 };
    }
    let mut out = vec![(0, 0); next[count.len()]];
    for (k, &root) in roots.iter().enumerate() {
        if keep(count[root]) {
            out[next[root]] = (root, k);
            next[root] += 1;
        }
    }
    out
}

/// Clusters with more rows than this are assigned greedily (the dense solver is cubic in
/// the cluster size; such clusters arise from chains of initiation gates in dense clutter).
pub(crate) const MAX_OPTIMAL_ROWS: usize = 64;

/// Greedy assignment of one cluster: pairs in increasing cost, each row and column once,
/// only pairs cheaper than the row's miss cost.
fn greedy(cluster: &[(usize, usize)], edges: &[Edge], miss: &[f64], out: &mut [Option<usize>]) {
    let mut order: Vec<usize> = cluster.iter().map(|&(_, k)| k).collect();
    order.sort_unstable_by(|&a, &b| edges[a].2.total_cmp(&edges[b].2));
    let mut col_used = std::collections::HashSet::new();
    for k in order {
        let (r, c, w) = edges[k];
        if out[r].is_some() || w >= miss[r] || !col_used.insert(c) {
            continue;
        }
        out[r] = Some(c);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        #[test]
        fn grouping_by_root_equals_sorting(roots in proptest::collection::vec(0usize..12, 0..80)) {
            let mut count = vec![0_u32; 12];
            for &r in &roots {
                count[r] += 1;
            }
            for min in [1, 2] {
                let mut sorted: Vec<(usize, usize)> = roots
                    .iter()
                    .enumerate()
                    .filter(|&(_, &r)| count[r] >= min)
                    .map(|(k, &r)| (r, k))
                    .collect();
                sorted.sort_unstable();
                proptest::prop_assert_eq!(group_by_root(&roots, &count, |n| n >= min), sorted);
            }
        }
    }

    #[test]
    fn optimal_not_greedy_and_misses() {
        // Rows 0, 1 compete for columns 0, 1 (miss 10 each): r0c0 = 1, r0c1 = 2,
        // r1c0 = 0.5, r1c1 = 1.2. Greedy (smallest first) takes r1c0, then r0c1: 2.5.
        // Optimal: r0c0 + r1c1 = 2.2.
        let edges = [(0, 0, 1.0), (0, 1, 2.0), (1, 0, 0.5), (1, 1, 1.2)];
        let out = gnn(2, 2, &edges, &[10.0, 10.0]);
        assert_eq!(out, vec![Some(0), Some(1)]);
        // Row 2 alone in its cluster with column 2; row 3 with no edge stays unassigned.
        let edges = [(0, 0, 1.0), (1, 0, 0.5), (2, 2, 3.0)];
        let out = gnn(4, 3, &edges, &[10.0, 10.0, 10.0, 10.0]);
        // Rows 0 and 1 share column 0: row 1 (0.5) takes it, row 0 misses at 10.
        assert_eq!(out, vec![None, Some(0), Some(2), None]);
        // A miss cheaper than the pair: left unassigned.
        let out = gnn(1, 1, &[(0, 0, 5.0)], &[4.0]);
        assert_eq!(out, vec![None]);
    }

    #[test]
    fn large_clusters_are_paired_greedily() {
        // A chain of 70 rows (> MAX_OPTIMAL_ROWS): row r gates column r (cost 1) and
        // column r + 1 (cost 0.5). Greedy takes every 0.5 pair first: row r → column r + 1.
        let rows = MAX_OPTIMAL_ROWS + 6;
        let mut edges = Vec::new();
        for r in 0..rows {
            edges.push((r, r, 1.0));
            edges.push((r, r + 1, 0.5));
        }
        let out = gnn(rows, rows + 1, &edges, &vec![10.0; rows]);
        for (r, c) in out.iter().enumerate() {
            assert_eq!(*c, Some(r + 1));
        }
    }
}
