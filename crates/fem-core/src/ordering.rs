//! A geometric nested-dissection ordering of a sparse symmetric pattern, for the Cholesky
//! factorisation of 3D stiffness matrices.
//!
//! faer's default fill-reducing ordering is approximate minimum degree (AMD), which is close to
//! the best on 2D meshes but leaves much more fill on 3D ones, where nested dissection has the
//! optimal `O(n^{4/3})` factor and `O(n²)` work (George 1973; Lipton, Rose, Tarjan 1979). With
//! node coordinates a separator is cheap to find: cut the vertex set at the median of one
//! coordinate, and take as separator the vertices of one side that have a neighbour on the
//! other (the side with fewer of them); of the three coordinates, the one whose separator is
//! smallest (on graded meshes the longest extent is not it: issue 38 in `docs/benchmarks.md`,
//! 17 % less fill on the 1e5-DOF Hertz block). Both halves are ordered first, recursively,
//! then the separator; small sets (below [`LEAF`]) keep their order.
//!
//! ```text
//! order(S):  |S| ≤ LEAF → S
//!            for each axis a:  m = median of x_a over S
//!              L = {v ∈ S : x_a(v) < m} (or ≤ m if that is empty),  R = S \ L
//!              C = {v ∈ L : v has a neighbour in R}  or  {v ∈ R : neighbour in L}, the smaller
//!            keep the axis of the smallest C (the longest extent on a tie)
//!            order(L \ C), order(R \ C), C
//! ```
//!
//! Measured in `docs/benchmarks.md` (3D pipeline): it is what
//! [`SolidModel`](crate::solid::SolidModel) uses.

use faer::sparse::SymbolicSparseColMatRef;

/// The fill-reducing ordering of a sparse Cholesky factorisation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum FillOrdering {
    /// faer's approximate minimum degree (the 2D models' choice).
    Amd,
    /// [`nested_dissection`] on the node coordinates (the 3D default: measured in
    /// `docs/benchmarks.md`).
    #[default]
    NestedDissection,
}

/// Sets at most this large are not split further.
pub const LEAF: usize = 64;

/// The nested-dissection elimination order of the vertices of a symmetric pattern (either
/// triangle, or both, in CSC form), one position per vertex: `order[k]` is the vertex
/// eliminated `k`-th. `coords[v]` is vertex `v`'s position (for a stiffness matrix: the node of
/// the dof).
///
/// # Panics
/// If `coords.len()` is not the pattern's dimension.
#[track_caller]
pub fn nested_dissection(
    pattern: SymbolicSparseColMatRef<'_, usize>,
    coords: &[[f64; 3]],
) -> Vec<usize> {
    let n = pattern.ncols();
    assert_eq!(coords.len(), n, "one position per vertex");
    // symmetric adjacency without the diagonal
    let mut degree = vec![0usize; n];
    for j in 0..n {
        for &i in pattern.row_idx_of_col_raw(j) {
            if i != j {
                degree[i] += 1;
                degree[j] += 1;
            }
        }
    }
    let mut start = Vec::with_capacity(n + 1);
    start.push(0);
    for d in &degree {
        start.push(start.last().copied().unwrap_or(0) + d);
    }
    let mut fill = start.clone();
    let mut adj = vec![0usize; start[n]];
    for j in 0..n {
        for &i in pattern.row_idx_of_col_raw(j) {
            if i != j {
                adj[fill[i]] = j;
                fill[i] += 1;
                adj[fill[j]] = i;
                fill[j] += 1;
            }
        }
    }
    let neighbours = |v: usize| &adj[start[v]..start[v + 1]];

    let mut order = Vec::with_capacity(n);
    // side[v]: 0 outside the set being split, 1 left, 2 right
    let mut side = vec![0u8; n];
    // work stack: a set to split, or a separator to emit once both halves are done
    enum Task {
        Split(Vec<usize>),
        Emit(Vec<usize>),
    }
    let mut stack = vec![Task::Split((0..n).collect())];
    while let Some(task) = stack.pop() {
        let mut set = match task {
            Task::Emit(sep) => {
                order.extend(sep);
                continue;
            }
            Task::Split(set) if set.len() <= LEAF => {
                order.extend(set);
                continue;
            }
            Task::Split(set) => set,
        };
        // cut across each axis with some extent, at the median; keep the smallest separator
        // (the longest axis first, so that a tie keeps it)
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &v in &set {
            for a in 0..3 {
                lo[a] = lo[a].min(coords[v][a]);
                hi[a] = hi[a].max(coords[v][a]);
            }
        }
        let mut axes = [0, 1, 2];
        axes.sort_by(|&a, &b| (hi[b] - lo[b]).total_cmp(&(hi[a] - lo[a])).then(b.cmp(&a)));
        let mut best: Option<(Vec<usize>, usize, Vec<usize>)> = None;
        for (k, &axis) in axes.iter().enumerate() {
            if k > 0 && hi[axis] <= lo[axis] {
                continue;
            }
            let mut sorted = set.clone();
            let (half, sep) = median_cut(&mut sorted, axis, coords, &mut side, &neighbours);
            if best.as_ref().is_none_or(|b| sep.len() < b.2.len()) {
                best = Some((sorted, half, sep));
            }
        }
        let Some((sorted, half, sep)) = best else {
            continue;
        };
        set = sorted;
        for &v in &set {
            side[v] = 0;
        }
        // mark the separator to drop it from its half
        for &v in &sep {
            side[v] = 3;
        }
        let (l, r): (Vec<usize>, Vec<usize>) = (
            set[..half]
                .iter()
                .copied()
                .filter(|&v| side[v] != 3)
                .collect(),
            set[half..]
                .iter()
                .copied()
                .filter(|&v| side[v] != 3)
                .collect(),
        );
        for &v in &sep {
            side[v] = 0;
        }
        if sep.is_empty() && (l.is_empty() || r.is_empty()) {
            // nothing to gain (all points at one position): keep the order
            order.extend(l.into_iter().chain(r));
            continue;
        }
        stack.push(Task::Emit(sep));
        stack.push(Task::Split(r));
        stack.push(Task::Split(l));
    }
    order
}

/// Sorts `set` along `axis` and cuts it at the median value (every vertex at that coordinate
/// on the same side, so that a cut through a plane of nodes takes that plane as its
/// separator): returns the size of the left part and the separator, the vertices of one side
/// with a neighbour on the other (the smaller such side). `side` is all 0 on entry and return.
fn median_cut<'a>(
    set: &mut [usize],
    axis: usize,
    coords: &[[f64; 3]],
    side: &mut [u8],
    neighbours: &impl Fn(usize) -> &'a [usize],
) -> (usize, Vec<usize>) {
    set.sort_unstable_by(|&u, &v| coords[u][axis].total_cmp(&coords[v][axis]).then(u.cmp(&v)));
    let m = coords[set[set.len() / 2]][axis];
    let mut half = set.partition_point(|&v| coords[v][axis] < m);
    if half == 0 {
        half = set.partition_point(|&v| coords[v][axis] <= m);
    }
    let (left, right) = set.split_at(half);
    for &v in left {
        side[v] = 1;
    }
    for &v in right {
        side[v] = 2;
    }
    let touches = |v: usize, other: u8| neighbours(v).iter().any(|&w| side[w] == other);
    let cut_left: Vec<usize> = left.iter().copied().filter(|&v| touches(v, 2)).collect();
    let cut_right: Vec<usize> = right.iter().copied().filter(|&v| touches(v, 1)).collect();
    for &v in set.iter() {
        side[v] = 0;
    }
    let sep = if cut_left.len() <= cut_right.len() {
        cut_left
    } else {
        cut_right
    };
    (half, sep)
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::SymbolicSparseColMat;

    #[test]
    fn nested_dissection_is_a_permutation_with_separators_last_works() {
        // a 20 × 20 grid graph (5-point stencil), lower triangle
        let m = 20;
        let id = |i: usize, j: usize| i + m * j;
        let mut col_ptr = vec![0];
        let mut rows = Vec::new();
        let mut coords = Vec::new();
        for j in 0..m {
            for i in 0..m {
                coords.push([i as f64, j as f64, 0.0]);
                let v = id(i, j);
                rows.push(v);
                if i + 1 < m {
                    rows.push(id(i + 1, j));
                }
                if j + 1 < m {
                    rows.push(id(i, j + 1));
                }
                rows[col_ptr[col_ptr.len() - 1]..].sort_unstable();
                col_ptr.push(rows.len());
            }
        }
        let n = m * m;
        let p = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, rows);
        let order = nested_dissection(p.as_ref(), &coords);
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..n).collect::<Vec<_>>());
        // the last vertices are the first separator: one grid line (x or y constant)
        let last = &order[n - m..];
        let on_line = |a: usize| last.iter().all(|&v| coords[v][a] == coords[last[0]][a]);
        assert!(on_line(0) || on_line(1), "{last:?}");
    }

    /// A 4 × 30 grid graph whose x extent (3 × 10) is a little longer than its y extent
    /// (29 × 1): the cut across x (the longest extent) has a separator of 30 vertices, the one
    /// across y of 4, and the first separator (the last vertices eliminated) is the 4, one
    /// grid line of constant y; across the longest extent it would have been a line of constant
    /// x.
    #[test]
    fn issue_38_nested_dissection_cuts_across_the_smallest_separator() {
        let (nx, ny) = (4, 30);
        let id = |i: usize, j: usize| i + nx * j;
        let mut col_ptr = vec![0];
        let mut rows = Vec::new();
        let mut coords = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                coords.push([10.0 * i as f64, j as f64, 0.0]);
                rows.push(id(i, j));
                if i + 1 < nx {
                    rows.push(id(i + 1, j));
                }
                if j + 1 < ny {
                    rows.push(id(i, j + 1));
                }
                rows[col_ptr[col_ptr.len() - 1]..].sort_unstable();
                col_ptr.push(rows.len());
            }
        }
        let n = nx * ny;
        let p = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, rows);
        let order = nested_dissection(p.as_ref(), &coords);
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..n).collect::<Vec<_>>());
        let last = &order[n - nx..];
        assert!(
            last.iter().all(|&v| coords[v][1] == coords[last[0]][1]),
            "{:?}",
            last.iter().map(|&v| coords[v]).collect::<Vec<_>>()
        );
    }
}
