//! The Newton system on a sparse `W`: assembled in compressed columns on the block pattern of
//! `W` restricted to the unknowns, and factorised by faer's sparse LU with partial pivoting
//! (the system `ρ⁻¹ Uᵀ S W U + diag` is not symmetric: `S` carries `μ̄ ŝ_x`).
//!
//! Unknown `jc` (contact `j`, direction `z`) couples only with the unknowns of the contacts in
//! block row `j` of `W`, so column `jc` of the system is `Σ_k z_k W[d j + k, :]` read on the
//! stored blocks of that row, dotted with the rows `l` of those contacts: `O(stored entries of
//! the row)` per unknown, never a dense `p × p`. The rows of a column come out ascending
//! (block columns ascending in each row of `W`, unknowns pushed contact by contact), so the
//! values are written straight into compressed columns.
//!
//! **Ordered once per pattern** (issue 37): the pattern depends only on how many unknowns each
//! contact has (the active set) and on `W`'s block pattern. The symbolic factorisation
//! (COLAMD ordering and elimination structure, a third of an LU on Siconos' capsules) is kept
//! with the pattern it was computed on and reused while the new pattern is the same: across
//! the proximal retries of one step (only `η` changes) and across steps whose active set did
//! not change. The same pattern gives the same ordering, so the factors and the iterates are
//! the same as with a fresh symbolic factorisation, bit for bit.

use super::NewtonScratch;
use crate::local::csr::CsrMatrix;
use faer::MatMut;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};

/// The sparse Newton matrix in compressed columns and the symbolic LU kept with its pattern.
#[derive(Clone, Debug, Default)]
pub(super) struct SparseNewton {
    /// The first unknown of each contact (`n_c + 1`).
    first: Vec<usize>,
    /// The pattern being assembled (compared with the kept one) and the values on it.
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
    /// The pattern of the kept symbolic factorisation, and the factorisation.
    kept: Option<(SymbolicSparseColMat<usize>, SymbolicLu<usize>)>,
    /// Symbolic factorisations computed so far (the count the reuse is tested on).
    symbolic_count: usize,
    /// Numeric factorisations computed so far.
    numeric_count: usize,
}

impl SparseNewton {
    /// The kept symbolic factorisation when the assembled pattern is the kept one; otherwise
    /// a fresh one on the assembled pattern, kept. `None` when faer refuses the pattern.
    fn symbolic(&mut self, p: usize) -> Option<SymbolicLu<usize>> {
        if let Some((pattern, symbolic)) = &self.kept
            && pattern.nrows() == p
            && pattern.col_ptr() == self.col_ptr.as_slice()
            && pattern.row_idx() == self.row_idx.as_slice()
        {
            return Some(symbolic.clone());
        }
        self.kept = None;
        let pattern = SymbolicSparseColMat::new_checked(
            p,
            p,
            self.col_ptr.clone(),
            None,
            self.row_idx.clone(),
        );
        self.symbolic_count += 1;
        let symbolic = SymbolicLu::try_new(pattern.as_ref()).ok()?;
        self.kept = Some((pattern, symbolic.clone()));
        Some(symbolic)
    }
}

impl NewtonScratch {
    /// Symbolic and numeric sparse LU factorisations computed by this scratch so far.
    #[cfg(test)]
    pub(crate) fn sparse_factorisations(&self) -> (usize, usize) {
        (self.sparse.symbolic_count, self.sparse.numeric_count)
    }

    /// Assembles the Newton matrix of `self.rows`/`self.cols` on the sparse `w` and solves it
    /// in place of `self.b`; `false` when faer refuses the factorisation (a structurally
    /// singular system), the caller then takes a Gauss–Seidel sweep.
    #[allow(clippy::needless_range_loop)] // offsets blk d + l into a contact's block
    pub(super) fn sparse_solve<const DT: usize>(&mut self, w: &CsrMatrix) -> bool {
        let d = DT + 1;
        let (nc, p) = (self.cases.len(), self.cols.len());
        let sp = &mut self.sparse;
        // unknowns of contact i: first[i] .. first[i + 1] (pushed contact by contact)
        sp.first.clear();
        sp.first.resize(nc + 1, 0);
        for &(i, _) in &self.cols {
            sp.first[i + 1] += 1;
        }
        for i in 0..nc {
            sp.first[i + 1] += sp.first[i];
        }
        sp.col_ptr.clear();
        sp.row_idx.clear();
        sp.values.clear();
        sp.col_ptr.push(0);
        for (jc, &(j, z)) in self.cols.iter().enumerate() {
            let (cols, rows) = w.block_rows(d * j, d);
            for (blk, chunk) in cols.chunks_exact(d).enumerate() {
                let i = chunk[0] as usize / d;
                let (lo, hi) = (sp.first[i], sp.first[i + 1]);
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
                    sp.row_idx.push(ir);
                    sp.values.push(v);
                }
            }
            sp.col_ptr.push(sp.row_idx.len());
        }
        let Some(symbolic) = sp.symbolic(p) else {
            return false;
        };
        let Some((pattern, _)) = &sp.kept else {
            return false;
        };
        sp.numeric_count += 1;
        let a = SparseColMatRef::new(pattern.as_ref(), &sp.values);
        let Ok(lu) = Lu::try_new_with_symbolic(symbolic, a) else {
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

#[cfg(test)]
mod tests {
    use super::super::NewtonScratch;
    use crate::local::classic::friction_coefficients_into;
    use crate::local::generate::multibody::SpherePile;
    use crate::local::residual::norm;
    use crate::local::settings::{Algorithm, UzawaSettings};
    use crate::local::sweep::Sweeps;

    /// A hyperstatic pile of spheres (`W = Hᵀ M⁻¹ H` rank-deficient, stored sparse): Newton's
    /// system is singular on its sticking contacts, so steps fail and the proximal retries
    /// refactorise with a larger `η` on the same pattern. The symbolic LU is computed once
    /// per pattern: far fewer times than the numeric one (without the reuse the two counts
    /// are equal, and this test fails). Measured: 285 numeric LUs for 113 Newton steps in
    /// 200 iterations, 15 symbolic.
    #[test]
    fn issue_37_sparse_newton_orders_once_per_pattern() {
        let pile = SpherePile {
            nx: 4,
            ny: 4,
            layers: 8,
            jitter: 0.4,
            threshold: 0.5,
            initial_speed: 0.1,
            ..SpherePile::default()
        }
        .generate(1)
        .unwrap();
        let dense = &pile.problem;
        let (m, nc) = (dense.size(), dense.contact_count());
        // the same storage as `ReducedProblem::from_triplets` on W's non-zero entries
        let p = dense.stored_sparse().unwrap().unwrap();
        assert!(p.is_sparse() && pile.rank_deficiency > 0);
        let laws = p.coulomb_laws();
        let states = vec![(); nc];
        let settings = UzawaSettings {
            algorithm: Algorithm::Newton,
            max_iterations: 200,
            ..UzawaSettings::default()
        };
        let mut sweeps = Sweeps::default();
        sweeps.reset(&p, 1.0);
        let denom_q = sweeps.rho0().iter().fold(0.0_f64, |a, &b| a.max(b)) * norm(p.q());
        let mut nw = NewtonScratch::default();
        friction_coefficients_into(&laws, &states, nc, &mut nw.mu_bar).unwrap();
        let (mut r, mut x, mut history) = (vec![0.0; m], p.q().to_vec(), Vec::new());
        let run = nw
            .solve::<_, 2>(
                &mut sweeps,
                &p,
                &laws,
                &states,
                &settings,
                denom_q,
                &mut r,
                &mut x,
                &mut history,
            )
            .unwrap();
        let (symbolic, numeric) = nw.sparse_factorisations();
        // retries happened: more factorisations than Newton iterations that factorised
        assert!(numeric > run.newton_steps, "{numeric} LUs, {run:?}");
        // at most one symbolic LU per two numeric ones (measured: one per 19); without the
        // reuse the two counts are equal
        assert!(
            symbolic >= 1 && 2 * symbolic <= numeric,
            "{symbolic} of {numeric}"
        );
    }
}
