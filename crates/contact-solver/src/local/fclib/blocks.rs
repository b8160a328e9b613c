//! FCLIB's global problem condensed block by block: the sparse route.
//!
//! ```text
//! M = diag(M_1, …, M_B)          (after grouping the dofs into the connected components of
//!                                 M's graph: one block per rigid body, or per FE body)
//! X = M⁻¹ H:  X[b-dofs, a] = M_b⁻¹ H[b-dofs, a]   only for the columns a that touch block b
//! W = Hᵀ X:   column by column, a sparse product (Gustavson's), one triangle when M is symmetric
//! ```
//! The cost is one factorisation per block (a dense LU with partial pivoting up to
//! [`SMALL_BLOCK`] dofs, faer's sparse Cholesky or LU above), solves with only the columns of
//! `H` that touch each block, and `W`'s entries: no dense `n × m` right-hand side and, when
//! `W` is sparse (fewer than `m²/4` entries, the local reader's rule), no dense `W`. On `n`
//! rigid bodies in `n_c` contacts that is `O(n + n_c · k)` where the dense route was
//! `O(n · n_c)` (`k` the contacts per body).

use super::mass::{Condensed, CondensedW, solve_mass};
use super::sparse::zeroed;
use faer::Mat;

/// Blocks up to this many dofs are factorised densely by hand (a rigid body has 3 or 6); a
/// larger block (an FE body) by faer's sparse factorisation.
const SMALL_BLOCK: usize = 64;

/// The connected components of the graph of `M` (`n` dofs, entries `(row, col, value)`):
/// `block[k]` and `local[k]` give dof `k`'s block and its place in it, `dofs[b]` the dofs of
/// block `b`, increasing. Blocks are numbered by their first dof.
pub(super) struct Blocks {
    block: Vec<usize>,
    local: Vec<usize>,
    dofs: Vec<Vec<usize>>,
}

impl Blocks {
    /// The components of `M`'s graph, by union–find over its entries.
    pub(super) fn of(n: usize, entries: &[(usize, usize, f64)]) -> Self {
        let mut parent: Vec<usize> = (0..n).collect();
        fn root(parent: &mut [usize], mut k: usize) -> usize {
            while parent[k] != k {
                parent[k] = parent[parent[k]];
                k = parent[k];
            }
            k
        }
        for &(r, c, _) in entries {
            let (a, b) = (root(&mut parent, r), root(&mut parent, c));
            if a != b {
                parent[a.max(b)] = a.min(b);
            }
        }
        let (mut block, mut local) = (vec![0; n], vec![0; n]);
        let mut id = vec![usize::MAX; n];
        let mut dofs: Vec<Vec<usize>> = Vec::new();
        for k in 0..n {
            let r = root(&mut parent, k);
            if id[r] == usize::MAX {
                id[r] = dofs.len();
                dofs.push(Vec::new());
            }
            block[k] = id[r];
            local[k] = dofs[id[r]].len();
            dofs[id[r]].push(k);
        }
        Self { block, local, dofs }
    }

    /// The number of blocks.
    pub(super) fn count(&self) -> usize {
        self.dofs.len()
    }
}

/// `W = Hᵀ M⁻¹ H` and `q = Hᵀ M⁻¹ f + w` block by block (see the [module docs](self)); `W`
/// sparse (triplets) when it has fewer than `m²/4` entries, else dense. `symmetric` says
/// whether `M` is: then one triangle of `W` is formed and mirrored, so that `W` is exactly
/// symmetric, as on the dense route. The error is the reason in the file's terms.
pub(super) fn condense(
    blocks: &Blocks,
    entries_m: &[(usize, usize, f64)],
    entries_h: &[(usize, usize, f64)],
    m: usize,
    f: &[f64],
    w: &[f64],
    symmetric: bool,
) -> Result<Condensed, String> {
    let n = blocks.block.len();
    let nb = blocks.count();
    // M's entries per block, in local indices
    let mut m_of: Vec<Vec<(usize, usize, f64)>> = vec![Vec::new(); nb];
    for &(r, c, v) in entries_m {
        m_of[blocks.block[r]].push((blocks.local[r], blocks.local[c], v));
    }
    // H by columns: (row, value) pairs of column a at start[a]..start[a + 1], file order
    let (start, by_col) = compress(m, entries_h.iter().map(|&(k, a, h)| (a, k, h)));
    // the columns touching each block, each listed once, increasing
    let mut cols_of: Vec<Vec<usize>> = vec![Vec::new(); nb];
    for a in 0..m {
        for &(k, _) in &by_col[start[a]..start[a + 1]] {
            let b = blocks.block[k];
            if cols_of[b].last() != Some(&a) {
                cols_of[b].push(a);
            }
        }
    }
    // X = M⁻¹ H by columns, as (dof, value) lists; y = M⁻¹ f
    let mut x_cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); m];
    let mut y = vec![0.0; n];
    for b in 0..nb {
        let dofs = &blocks.dofs[b];
        let cols = &cols_of[b];
        let mut rhs = Mat::<f64>::zeros(dofs.len(), cols.len() + 1);
        for (j, &a) in cols.iter().enumerate() {
            for &(k, h) in &by_col[start[a]..start[a + 1]] {
                if blocks.block[k] == b {
                    rhs[(blocks.local[k], j)] += h;
                }
            }
        }
        for (i, &k) in dofs.iter().enumerate() {
            rhs[(i, cols.len())] = f[k];
        }
        if dofs.len() <= SMALL_BLOCK {
            solve_small(dofs, &m_of[b], &mut rhs)?;
        } else {
            solve_mass(dofs.len(), &m_of[b], &mut rhs)?;
        }
        for (j, &a) in cols.iter().enumerate() {
            let col = rhs.col_as_slice(j);
            x_cols[a].extend(dofs.iter().zip(col).map(|(&k, &v)| (k, v)));
        }
        for (i, &k) in dofs.iter().enumerate() {
            y[k] = rhs[(i, cols.len())];
        }
    }
    let (rows, cols, vals) = products(n, entries_h, m, &x_cols, symmetric);
    // q_a = w_a + Σ h y_k, summed in the order of the file's entries
    let q: Vec<f64> = (0..m)
        .map(|a| {
            by_col[start[a]..start[a + 1]]
                .iter()
                .fold(w[a], |s, &(k, h)| s + h * y[k])
        })
        .collect();
    if let Some(k) = vals.iter().chain(&q).position(|v| !v.is_finite()) {
        return Err(format!(
            "`fclib_global/M` is singular: the condensed {} is not finite",
            if k < vals.len() { "W" } else { "q" }
        ));
    }
    let w = if (vals.len() as f64) < (m as f64) * (m as f64) / 4.0 {
        CondensedW::Triplets { rows, cols, vals }
    } else {
        let mut dense = zeroed(m, m, "fclib_global/H")?;
        for ((&r, &c), &v) in rows.iter().zip(&cols).zip(&vals) {
            dense[r * m + c] = v;
        }
        CondensedW::Dense(dense)
    };
    Ok(Condensed { w, q })
}

/// The entries `(outer, inner, value)` grouped by `outer` (`0..len`), in the order given:
/// `(start, pairs)` with the `(inner, value)` pairs of `o` at `start[o]..start[o + 1]`.
#[allow(clippy::type_complexity)]
fn compress(
    len: usize,
    entries: impl Iterator<Item = (usize, usize, f64)> + Clone,
) -> (Vec<usize>, Vec<(usize, f64)>) {
    let mut start = vec![0usize; len + 1];
    for (o, _, _) in entries.clone() {
        start[o + 1] += 1;
    }
    for o in 0..len {
        start[o + 1] += start[o];
    }
    let mut next = start.clone();
    let mut pairs = vec![(0usize, 0.0); start[len]];
    for (o, i, v) in entries {
        pairs[next[o]] = (i, v);
        next[o] += 1;
    }
    (start, pairs)
}

/// `W = Hᵀ X` as triplets, column by column (Gustavson): `W_ab = Σ_k H_ka X_kb` over the
/// stored `X_kb`, with `H` by rows. With `symmetric`, only `a ≥ b` is formed and mirrored.
/// Each column's rows are listed increasing, and every entry the pattern reaches is kept.
#[allow(clippy::type_complexity)]
fn products(
    n: usize,
    entries_h: &[(usize, usize, f64)],
    m: usize,
    x_cols: &[Vec<(usize, f64)>],
    symmetric: bool,
) -> (Vec<usize>, Vec<usize>, Vec<f64>) {
    let (row_start, by_row) = compress(n, entries_h.iter().copied());
    let mut acc = vec![0.0; m];
    let mut seen = vec![false; m];
    let mut touched = Vec::new();
    let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    for (b, xb) in x_cols.iter().enumerate() {
        let first = if symmetric { b } else { 0 };
        for &(k, x) in xb {
            for &(a, h) in &by_row[row_start[k]..row_start[k + 1]] {
                if a >= first {
                    if !seen[a] {
                        seen[a] = true;
                        touched.push(a);
                    }
                    acc[a] += h * x;
                }
            }
        }
        touched.sort_unstable();
        for &a in &touched {
            let v = std::mem::take(&mut acc[a]);
            seen[a] = false;
            rows.push(a);
            cols.push(b);
            vals.push(v);
            if symmetric && a != b {
                rows.push(b);
                cols.push(a);
                vals.push(v);
            }
        }
        touched.clear();
    }
    (rows, cols, vals)
}

/// `rhs ← M_b⁻¹ rhs` for a small block (`dofs` its global dofs, `entries` its entries in
/// local indices): dense LU with partial pivoting. A zero pivot is a singular `M`, named by
/// the block's first dof.
fn solve_small(
    dofs: &[usize],
    entries: &[(usize, usize, f64)],
    rhs: &mut Mat<f64>,
) -> Result<(), String> {
    let k = dofs.len();
    let mut a = vec![0.0; k * k];
    for &(r, c, v) in entries {
        a[r * k + c] += v;
    }
    let mut perm: Vec<usize> = (0..k).collect();
    for j in 0..k {
        let p = (j..k)
            .max_by(|&s, &t| a[s * k + j].abs().total_cmp(&a[t * k + j].abs()))
            .unwrap_or(j);
        if a[p * k + j] == 0.0 {
            return Err(format!(
                "`fclib_global/M` is singular: its diagonal block of {k} dofs from dof {} has \
                 a zero pivot",
                dofs[0]
            ));
        }
        if p != j {
            for c in 0..k {
                a.swap(j * k + c, p * k + c);
            }
            perm.swap(j, p);
        }
        for i in j + 1..k {
            let l = a[i * k + j] / a[j * k + j];
            a[i * k + j] = l;
            for c in j + 1..k {
                a[i * k + c] -= l * a[j * k + c];
            }
        }
    }
    let mut z = vec![0.0; k];
    for col in 0..rhs.ncols() {
        let x = rhs.col_as_slice_mut(col);
        for (i, &p) in perm.iter().enumerate() {
            z[i] = x[p];
        }
        for i in 0..k {
            let s: f64 = (0..i).map(|c| a[i * k + c] * z[c]).sum();
            z[i] -= s;
        }
        for i in (0..k).rev() {
            let s: f64 = (i + 1..k).map(|c| a[i * k + c] * z[c]).sum();
            z[i] = (z[i] - s) / a[i * k + i];
        }
        x.copy_from_slice(&z);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::global::condense_dense;
    use super::super::global::tests::{dense, rigid_bodies};
    use super::*;
    use crate::local::generate::SplitMix64;

    /// `M` of `bodies` rigid bodies of 6 dofs each: a positive diagonal, the 3 × 3 rotational
    /// block coupled by `c` above the diagonal and `c · skew` below it (`skew = 1`: symmetric,
    /// and positive definite for `|c| ≤ 0.3`, the diagonal being ≥ 1).
    fn body_masses(bodies: usize, c: f64, skew: f64) -> Vec<(usize, usize, f64)> {
        let mut g = SplitMix64::new(5);
        let mut em = Vec::new();
        for body in 0..bodies {
            let d = 6 * body;
            em.extend((d..d + 6).map(|k| (k, k, g.uniform(1.0, 2.0))));
            for (i, j) in [(3, 4), (3, 5), (4, 5)] {
                em.push((d + i, d + j, c));
                em.push((d + j, d + i, c * skew));
            }
        }
        em
    }

    /// The block route against the dense route on the same problem: `W` to `1e-13 · max|W|`
    /// and `q` to `1e-13 · max|q|` (both factorise the same blocks; they differ in the order of
    /// the sums only, a few ulps of sums of at most 12 · 6 products), and whether `W` came out
    /// sparse.
    fn compare(n: usize, em: &[(usize, usize, f64)], eh: &[(usize, usize, f64)], m: usize) -> bool {
        let mut g = SplitMix64::new(6);
        let f: Vec<f64> = (0..n).map(|_| g.uniform(-1.0, 1.0)).collect();
        let w: Vec<f64> = (0..m).map(|_| g.uniform(-1.0, 1.0)).collect();
        let symmetric = em.iter().all(|&(r, c, v)| {
            let t: f64 = em
                .iter()
                .filter(|e| (e.0, e.1) == (c, r))
                .map(|e| e.2)
                .sum();
            r == c || v == t
        });
        let parts = Blocks::of(n, em);
        assert!(parts.count() > 1);
        let by_blocks = condense(&parts, em, eh, m, &f, &w, symmetric).unwrap();
        let sparse = matches!(by_blocks.w, CondensedW::Triplets { .. });
        let (w_ref, q_ref) = condense_dense(n, em, eh, m, &f, &w, symmetric).unwrap();
        let w_new = dense(by_blocks.w, m);
        let max = |v: &[f64]| v.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let (sw, sq) = (max(&w_ref), max(&q_ref));
        for (a, b) in w_ref.iter().zip(&w_new) {
            assert!((a - b).abs() <= 1e-13 * sw, "W: {a} against {b}");
        }
        for (a, b) in q_ref.iter().zip(&by_blocks.q) {
            assert!((a - b).abs() <= 1e-13 * sq, "q: {a} against {b}");
        }
        let asymmetric = (0..m).any(|a| (0..m).any(|b| w_new[a * m + b] != w_new[b * m + a]));
        assert_eq!(asymmetric, !symmetric, "W is symmetric exactly when M is");
        sparse
    }

    #[test]
    fn issue_37_block_route_matches_the_dense_route() {
        // 60 bodies, 20 contacts: few contacts per body, so W is sparse
        let (n, _, eh, m) = rigid_bodies(60, 20);
        assert!(compare(n, &body_masses(60, 0.2, 1.0), &eh, m));
        // 6 bodies, 20 contacts: W is dense
        let (n, _, eh, m) = rigid_bodies(6, 20);
        assert!(!compare(n, &body_masses(6, 0.2, 1.0), &eh, m));
        // a non-symmetric M (c below the diagonal, −c/2 above): both triangles of W
        let (n, _, eh, m) = rigid_bodies(60, 20);
        compare(n, &body_masses(60, 0.2, -0.5), &eh, m);
    }

    #[test]
    fn issue_37_block_route_factorises_a_large_block_sparse() {
        // rigid bodies 0..10 and one FE-like body of 90 dofs (above SMALL_BLOCK): a chain
        // stiffness 2 on the diagonal, −1 beside it, +1 at its ends (SPD), contacts between
        // the bodies and the chain
        let bodies = 10;
        let mut em = body_masses(bodies, 0.1, 1.0);
        let first = 6 * bodies;
        let chain = 90;
        for k in first..first + chain {
            em.push((
                k,
                k,
                if k == first || k == first + chain - 1 {
                    3.0
                } else {
                    2.0
                },
            ));
            if k + 1 < first + chain {
                em.push((k, k + 1, -1.0));
                em.push((k + 1, k, -1.0));
            }
        }
        let n = first + chain;
        let mut g = SplitMix64::new(7);
        let mut eh = Vec::new();
        for col in 0..30 {
            let body = col % bodies;
            for k in 6 * body..6 * body + 6 {
                eh.push((k, col, g.uniform(-1.0, 1.0)));
            }
            let node = first + (g.uniform(0.0, (chain - 1) as f64) as usize);
            eh.push((node, col, g.uniform(-1.0, 1.0)));
        }
        // per body three translations alone and one rotational 3 × 3 block; then the chain
        assert_eq!(Blocks::of(n, &em).count(), 4 * bodies + 1);
        compare(n, &em, &eh, 30);
    }

    #[test]
    fn issue_37_block_route_names_a_singular_block() {
        // two 2-dof blocks, the second [1 1; 1 1]
        let em = [
            (0, 0, 1.0),
            (1, 1, 1.0),
            (0, 1, 0.5),
            (1, 0, 0.5),
            (2, 2, 1.0),
            (3, 3, 1.0),
            (2, 3, 1.0),
            (3, 2, 1.0),
        ];
        let eh = [(0, 0, 1.0), (1, 1, 1.0), (2, 0, 1.0), (3, 1, 1.0)];
        let parts = Blocks::of(4, &em);
        assert_eq!(parts.count(), 2);
        let e = condense(&parts, &em, &eh, 2, &[0.0; 4], &[0.0; 2], true)
            .err()
            .unwrap();
        assert_eq!(
            e,
            "`fclib_global/M` is singular: its diagonal block of 2 dofs from dof 2 has a zero \
             pivot"
        );
    }

    #[test]
    fn blocks_are_the_components_of_the_graph() {
        // 0–3 coupled, 1 alone, 2–4 coupled (through an entry below the diagonal only)
        let em = [(0, 3, 1.0), (1, 1, 1.0), (4, 2, 1.0), (0, 0, 1.0)];
        let b = Blocks::of(5, &em);
        assert_eq!(b.dofs, vec![vec![0, 3], vec![1], vec![2, 4]]);
        assert_eq!(b.block, vec![0, 1, 2, 0, 2]);
        assert_eq!(b.local, vec![0, 0, 0, 1, 1]);
    }
}
