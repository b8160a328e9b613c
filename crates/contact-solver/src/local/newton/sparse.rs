//! The Newton system on a sparse `W`: assembled in compressed columns on the block pattern of
//! `W` restricted to the unknowns, and factorised by faer's sparse LU with partial pivoting
//! (the system `ρ⁻¹ Uᵀ S W U + diag` is not symmetric: `S` carries `μ̄ ŝ_x`).
//!
//! Unknown `jc` (contact `j`, direction `z`) couples only with the unknowns of the contacts in
//! block row `j` of `W`, so column `jc` of the system is `Σ_k z_k W[d j + k, :]` read on the
//! stored blocks of that row, dotted with the rows `l` of those contacts: `O(stored entries of
//! the row)` per unknown, never a dense `p × p`. The pattern changes with the active set, so
//! the symbolic factorisation is redone at every Newton step (its cost is linear in the
//! non-zeros of the factors; measured in `docs/benchmarks.md`).

use super::NewtonScratch;
use crate::local::csr::CsrMatrix;
use faer::MatMut;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};

impl NewtonScratch {
    /// Assembles the Newton matrix of `self.rows`/`self.cols` on the sparse `w` and solves it
    /// in place of `self.b`; `false` when faer refuses the factorisation (a structurally
    /// singular system), the caller then takes a Gauss–Seidel sweep.
    #[allow(clippy::needless_range_loop)] // offsets blk d + l into a contact's block
    pub(super) fn sparse_solve<const DT: usize>(&mut self, w: &CsrMatrix) -> bool {
        let d = DT + 1;
        let (nc, p) = (self.cases.len(), self.cols.len());
        // unknowns of contact i: first[i] .. first[i + 1] (pushed contact by contact)
        self.first.clear();
        self.first.resize(nc + 1, 0);
        for &(i, _) in &self.cols {
            self.first[i + 1] += 1;
        }
        for i in 0..nc {
            self.first[i + 1] += self.first[i];
        }
        self.triplets.clear();
        for (jc, &(j, z)) in self.cols.iter().enumerate() {
            let (cols, rows) = w.block_rows(d * j, d);
            for (blk, chunk) in cols.chunks_exact(d).enumerate() {
                let i = chunk[0] as usize / d;
                let (lo, hi) = (self.first[i], self.first[i + 1]);
                if lo == hi {
                    continue;
                }
                // (W z) on contact i from the rows of `columns` (Wᵀ when W is kept
                // non-symmetric): Σ_k z_k C[d j + k, d i + l] = Σ_k W[d i + l, d j + k] z_k
                let mut wz = [0.0; 3];
                for (k, &zk) in z.iter().enumerate().take(d) {
                    if zk != 0.0 {
                        for l in 0..d {
                            wz[l] += rows[k][blk * d + l] * zk;
                        }
                    }
                }
                if i == j && self.eta > 0.0 {
                    // the proximal term of `W + ε_j I` (`proximal`)
                    let eps = self.eta / self.rho[j];
                    for l in 0..d {
                        wz[l] += eps * z[l];
                    }
                }
                for ir in lo..hi {
                    let (_, l, diagonal, _) = self.rows[ir];
                    let mut v = (0..d).map(|k| l[k] * wz[k]).sum::<f64>();
                    if ir == jc {
                        v += diagonal;
                    }
                    self.triplets.push(Triplet::new(ir, jc, v));
                }
            }
        }
        let Ok(a) = SparseColMat::<usize, f64>::try_new_from_triplets(p, p, &self.triplets) else {
            return false;
        };
        let Ok(lu) = a.sp_lu() else {
            return false;
        };
        lu.solve_in_place(MatMut::from_column_major_slice_mut(&mut self.b, p, 1));
        true
    }
}

/// The fill of a Newton factorisation on the sparse `w` (block size `d`): `nnz(L)` of the
/// symbolic Cholesky factor of the contact graph (one node per contact, an edge per stored
/// off-diagonal block; faer's default AMD ordering) over the graph's `nnz` in its lower
/// triangle, diagonal included. Geometric contact graphs (piles, FE interfaces) fill like
/// meshes; random couplings fill almost completely. `None` when faer refuses the pattern.
pub(crate) fn factor_fill(w: &CsrMatrix, d: usize) -> Option<f64> {
    use faer::sparse::SymbolicSparseColMatRef;
    use faer::sparse::linalg::cholesky::factorize_symbolic_cholesky;
    let nc = w.size() / d;
    // lower triangle of the contact graph in compressed columns (column J: blocks I ≥ J of
    // block row J, the pattern being symmetric)
    let mut col_ptr = Vec::with_capacity(nc + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0usize);
    for j in 0..nc {
        let (cols, _) = w.row(d * j);
        row_idx.extend(
            cols.iter()
                .step_by(d)
                .map(|&c| c as usize / d)
                .filter(|&i| i >= j),
        );
        col_ptr.push(row_idx.len());
    }
    let pattern = SymbolicSparseColMatRef::new_checked(nc, nc, &col_ptr, None, &row_idx);
    let symbolic = factorize_symbolic_cholesky(
        pattern,
        faer::Side::Lower,
        Default::default(),
        Default::default(),
    )
    .ok()?;
    Some(symbolic.len_val() as f64 / row_idx.len().max(1) as f64)
}
