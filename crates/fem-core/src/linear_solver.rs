//! Sparse symmetric positive definite solves: a wrapper around faer's sparse Cholesky.
//!
//! The symbolic analysis (fill-reducing ordering, elimination tree) is done once per sparsity
//! pattern; the numeric factorisation is redone only when the values change; solves take one
//! or many right-hand sides.
//!
//! The wrapper drives faer's low-level `SymbolicCholesky` (with the same default parameters
//! as faer's `SymbolicLlt`/`Llt`, so the numbers are the same) because only that level
//! exposes the fill-reducing permutation: a failed pivot is reported by faer in the permuted
//! order, and [`SpdSolver::factor`] maps it back to a row of the caller's matrix.

use crate::error::FemError;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltError;
use faer::sparse::linalg::cholesky::{
    LltRef, SymbolicCholesky, SymbolicCholeskyRaw, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Side};
use std::sync::Arc;

/// A sparse SPD solver for matrices given by their lower triangle in CSC form.
#[derive(Clone, Debug)]
pub struct SpdSolver {
    symbolic: Arc<SymbolicCholesky<usize>>,
    /// Numeric values of the factor `L` (valid when `factored`).
    values: Vec<f64>,
    factored: bool,
    /// Whether the values were freed by [`SpdSolver::release`] (not a failed factorisation).
    released: bool,
    dim: usize,
    factorizations: usize,
}

impl SpdSolver {
    /// Symbolic analysis of the pattern (lower triangle).
    ///
    /// # Errors
    /// [`FemError::LinearAlgebra`] if faer fails (allocation, index overflow).
    pub fn new(pattern: SymbolicSparseColMatRef<'_, usize>) -> Result<Self, FemError> {
        let symbolic = factorize_symbolic_cholesky(
            pattern,
            Side::Lower,
            Default::default(),
            params(pattern.ncols()),
        )?;
        Ok(Self::with_symbolic(symbolic))
    }

    /// Symbolic analysis of the pattern (lower triangle) with a given elimination order
    /// (`order[k]` the row/column eliminated `k`-th, e.g. from
    /// [`crate::ordering::nested_dissection`]) instead of faer's AMD.
    ///
    /// # Errors
    /// [`FemError::LengthMismatch`] if `order` is not a permutation of the pattern's
    /// dimension; [`FemError::LinearAlgebra`] if faer fails.
    pub fn with_order(
        pattern: SymbolicSparseColMatRef<'_, usize>,
        order: &[usize],
    ) -> Result<Self, FemError> {
        let n = pattern.ncols();
        let mut inverse = vec![usize::MAX; n];
        for (k, &v) in order.iter().enumerate() {
            if v >= n || inverse[v] != usize::MAX {
                return Err(FemError::LengthMismatch {
                    what: "elimination order (a permutation of the dofs)",
                    expected: n,
                    got: order.len(),
                });
            }
            inverse[v] = k;
        }
        if order.len() != n {
            return Err(FemError::LengthMismatch {
                what: "elimination order (a permutation of the dofs)",
                expected: n,
                got: order.len(),
            });
        }
        let perm = faer::perm::PermRef::new_checked(order, &inverse, n);
        let symbolic = factorize_symbolic_cholesky(
            pattern,
            Side::Lower,
            faer::sparse::linalg::cholesky::SymmetricOrdering::Custom(perm),
            params(n),
        )?;
        Ok(Self::with_symbolic(symbolic))
    }

    fn with_symbolic(symbolic: SymbolicCholesky<usize>) -> Self {
        Self {
            dim: symbolic.nrows(),
            symbolic: Arc::new(symbolic),
            values: Vec::new(),
            factored: false,
            released: false,
            factorizations: 0,
        }
    }

    /// Numeric Cholesky factorisation of `matrix` (lower triangle, same pattern as given to
    /// [`SpdSolver::new`]).
    ///
    /// # Errors
    /// - [`FemError::NonPositivePivot`] if a pivot is not positive (typically a rigid-body
    ///   mode: missing supports), with `row: Some(r)`, `r` the row of `matrix` (not faer's
    ///   permuted index) whose pivot failed;
    /// - [`FemError::LinearAlgebra`] otherwise.
    pub fn factor(&mut self, matrix: SparseColMatRef<'_, usize, f64>) -> Result<(), FemError> {
        self.factored = false;
        self.released = false;
        let symbolic = &*self.symbolic;
        let len_val = symbolic.len_val();
        self.values.clear();
        self.values
            .try_reserve_exact(len_val)
            .map_err(|_| faer::sparse::FaerError::OutOfMemory)?;
        self.values.resize(len_val, 0.0);
        let par = parallelism(self.dim);
        let mut scratch = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        )
        .map_err(|_| faer::sparse::FaerError::OutOfMemory)?;
        let result = symbolic.factorize_numeric_llt::<f64>(
            &mut self.values,
            matrix,
            Side::Lower,
            Default::default(),
            par,
            MemStack::new(&mut scratch),
            Default::default(),
        );
        match result.map(|_| ()) {
            Ok(()) => {
                self.factored = true;
                self.factorizations += 1;
                Ok(())
            }
            Err(LltError::NonPositivePivot { index }) => Err(self.failed_row(index)),
        }
    }

    /// The row of the caller's matrix whose pivot failed, from faer's `index`.
    ///
    /// faer 0.24 reports `index` in the *permuted* matrix `P A Pᵀ`, and not with the same
    /// base on its two paths: the simplicial factorisation reports column `k` as `k + 1`,
    /// the supernodal one (a dense Cholesky per supernode) as `k`. Column `k` of `P A Pᵀ` is
    /// row `perm_fwd[k]` of `A` (faer's own solve gathers `x[k] = b[perm_fwd[k]]`). The
    /// unit tests `failed_pivot_row_works_*` pin both paths: a strongly negative diagonal
    /// entry in a positive definite matrix fails exactly at its own pivot.
    fn failed_row(&self, index: usize) -> FemError {
        let k = match self.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(_) => index.checked_sub(1),
            SymbolicCholeskyRaw::Supernodal(_) => Some(index),
        };
        let row = match (k, self.symbolic.perm()) {
            (Some(k), Some(perm)) => perm.arrays().0.get(k).copied(),
            (Some(k), None) => (k < self.dim).then_some(k),
            (None, _) => None,
        };
        match row {
            Some(row) => FemError::NonPositivePivot { row: Some(row) },
            None => FemError::LinearAlgebra {
                detail: format!(
                    "the Cholesky factorisation reported a non-positive pivot at index {index}, \
                     outside the matrix of dimension {}",
                    self.dim
                ),
            },
        }
    }

    /// Frees the numeric factor's values, keeping the symbolic analysis: the solver is then
    /// unfactored (as after a failed [`SpdSolver::factor`]) until the next factorisation,
    /// which allocates them again. What a body does to lend its factor's memory
    /// ([`crate::Structure::release_factor`]).
    pub fn release(&mut self) {
        self.factored = false;
        self.released = true;
        self.values = Vec::new();
    }

    /// Whether the factor was freed by [`SpdSolver::release`] and not redone since.
    #[inline]
    pub fn is_released(&self) -> bool {
        self.released
    }

    /// Whether the last [`SpdSolver::factor`] succeeded (a solve needs it).
    #[inline]
    pub fn is_factored(&self) -> bool {
        self.factored
    }

    /// Dimension of the system.
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Stored entries of the Cholesky factor `L` (the fill of faer's AMD ordering), known from
    /// the symbolic analysis.
    #[inline]
    pub fn factor_nnz(&self) -> usize {
        self.symbolic.len_val()
    }

    /// How many numeric factorisations this solver has done.
    #[inline]
    pub fn factorizations(&self) -> usize {
        self.factorizations
    }

    /// Solves `K x = b` in place (`rhs` holds `b` on entry and `x` on return).
    ///
    /// # Panics
    /// If `rhs.len() != dim()` or if [`SpdSolver::factor`] has not succeeded.
    #[track_caller]
    pub fn solve_in_place(&self, rhs: &mut [f64]) {
        let n = rhs.len();
        assert_eq!(n, self.dim, "right-hand side length");
        self.solve_many_in_place(MatMut::from_column_major_slice_mut(rhs, n, 1));
    }

    /// Solves `K X = B` in place for several right-hand sides (columns of `rhs`).
    ///
    /// # Panics
    /// If `rhs.nrows() != dim()` or if [`SpdSolver::factor`] has not succeeded.
    #[track_caller]
    pub fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) {
        assert_eq!(rhs.nrows(), self.dim, "right-hand side rows");
        assert!(
            self.factored,
            "SpdSolver::factor must succeed before solving"
        );
        self.solve_columns(rhs, parallelism(self.dim));
    }

    /// Solves the columns of `rhs` with `par`: split by columns between its threads (each
    /// share solved sequentially) when every thread gets [`MIN_COLUMNS_PER_THREAD`] of them.
    fn solve_columns(&self, rhs: MatMut<'_, f64>, par: faer::Par) {
        let threads = match par {
            faer::Par::Seq => 1,
            faer::Par::Rayon(n) => n.get(),
        };
        let groups = threads.min(rhs.ncols() / MIN_COLUMNS_PER_THREAD).max(1);
        if groups == 1 {
            self.solve_block(rhs, par);
            return;
        }
        // independent columns: each thread solves its share sequentially (faer's parallel
        // solve divides the work of every column, and costs more than it saves on the 60 000
        // dofs of the refined pile: `docs/benchmarks.md`, "Threads")
        let per = rhs.ncols().div_ceil(groups);
        std::thread::scope(|scope| {
            let mut rest = rhs;
            while rest.ncols() > per {
                let (block, tail) = rest.split_at_col_mut(per);
                scope.spawn(move || self.solve_block(block, faer::Par::Seq));
                rest = tail;
            }
            self.solve_block(rest, faer::Par::Seq);
        });
    }

    fn solve_block(&self, rhs: MatMut<'_, f64>, par: faer::Par) {
        let mut scratch = MemBuffer::new(
            self.symbolic
                .solve_in_place_scratch::<f64>(rhs.ncols(), par),
        );
        LltRef::<usize, f64>::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            par,
            MemStack::new(&mut scratch),
        );
    }
}

/// Below this many right-hand sides per thread a multi-column solve is not split between
/// threads by columns.
pub const MIN_COLUMNS_PER_THREAD: usize = 8;

/// Below this many unknowns factorisations and solves run sequentially whatever faer's global
/// parallelism: handing them to rayon's threads costs more than it saves. Measured with
/// `bipo run` (`docs/benchmarks.md`, "Threads"): the seed's pile (8 623 dofs) 1.09 s
/// sequential against 1.45 s on both cores, the delamination 0.29 s against 0.51 s, a 14k-dof
/// 3D sphere 0.46 s against 0.52 s; a 1e5-dof 3D model gains 10–20 % on both cores.
pub const SEQUENTIAL_BELOW_DOFS: usize = 50_000;

/// faer's parallelism for a factorisation or solve of `dim` unknowns: sequential below
/// [`SEQUENTIAL_BELOW_DOFS`], faer's global setting above.
pub fn parallelism(dim: usize) -> faer::Par {
    if dim < SEQUENTIAL_BELOW_DOFS {
        faer::Par::Seq
    } else {
        faer::get_global_parallelism()
    }
}

/// From this many unknowns the factorisation is supernodal whatever faer's flop-ratio rule
/// picks: the supernodal solves run the many right-hand sides of `F*` as dense blocks. On the
/// seed's pile (8 623 dofs, 397 columns of `F*` and 104 single solves) faer's rule picks the
/// simplicial one and the run takes 0.384 s against 0.335 s supernodal (medians of five,
/// alternating); below, on the 2 900-dof seed scenes and Hertz, the two are within the noise.
pub const SUPERNODAL_FROM_DOFS: usize = 4000;

fn params(dim: usize) -> faer::sparse::linalg::cholesky::CholeskySymbolicParams<'static> {
    let mut p = faer::sparse::linalg::cholesky::CholeskySymbolicParams::default();
    if dim >= SUPERNODAL_FROM_DOFS {
        p.supernodal_flop_ratio_threshold =
            faer::sparse::linalg::SupernodalThreshold::FORCE_SUPERNODAL;
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::linalg::SupernodalThreshold;
    use faer::sparse::linalg::cholesky::CholeskySymbolicParams;
    use faer::sparse::{SparseColMat, Triplet};

    /// Lower triangle of the 5-point Laplacian on an `m × m` grid (SPD), plus `shift` on
    /// the diagonal of `row`.
    fn laplacian(m: usize, row: usize, shift: f64) -> SparseColMat<usize, f64> {
        let n = m * m;
        let mut t = Vec::new();
        for j in 0..m {
            for i in 0..m {
                let k = j * m + i;
                t.push(Triplet::new(k, k, 4.0 + if k == row { shift } else { 0.0 }));
                if i + 1 < m {
                    t.push(Triplet::new(k + 1, k, -1.0));
                }
                if j + 1 < m {
                    t.push(Triplet::new(k + m, k, -1.0));
                }
            }
        }
        SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
    }

    fn solver(a: &SparseColMat<usize, f64>, threshold: SupernodalThreshold) -> SpdSolver {
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: threshold,
            ..Default::default()
        };
        let symbolic =
            factorize_symbolic_cholesky(a.symbolic(), Side::Lower, Default::default(), params)
                .unwrap();
        SpdSolver::with_symbolic(symbolic)
    }

    /// A strongly negative diagonal entry in an SPD matrix fails at its own pivot: every
    /// leading block of `P A Pᵀ` before it is a principal submatrix of the SPD Laplacian, and
    /// its own pivot is `a_rr − (≥ 0) < 0`. So the reported row must be `row`, whatever the
    /// ordering; the permutation is checked to move `row`, so that an unmapped (or
    /// off-by-one) index would be caught.
    fn check(threshold: SupernodalThreshold, supernodal: bool) {
        for row in [0, 37, 200, 399] {
            let a = laplacian(20, row, -1e3);
            let mut s = solver(&a, threshold);
            assert_eq!(
                matches!(s.symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)),
                supernodal
            );
            let perm = s.symbolic.perm().expect("AMD ordering").arrays().0.to_vec();
            assert_ne!(perm[row], row, "the ordering moves row {row}");
            assert_eq!(
                s.factor(a.as_ref()),
                Err(FemError::NonPositivePivot { row: Some(row) })
            );
            assert_eq!(s.factorizations(), 0);
        }
        // Without the negative entry it factors and solves.
        let a = laplacian(20, 0, 0.0);
        let mut s = solver(&a, threshold);
        s.factor(a.as_ref()).unwrap();
        let mut b = vec![1.0; 400];
        s.solve_in_place(&mut b);
        assert!(b.iter().all(|x| x.is_finite() && *x > 0.0));
    }

    /// Released, the solver is unfactored; refactored, it solves bit for bit as before (same
    /// symbolic analysis, same values, same order of operations).
    #[test]
    fn issue_38_release_then_refactor_solves_the_same() {
        let a = laplacian(20, 0, 0.0);
        let mut s = solver(&a, SupernodalThreshold::FORCE_SUPERNODAL);
        s.factor(a.as_ref()).unwrap();
        let b: Vec<f64> = (0..400).map(|i| ((i * 7) % 13) as f64 - 6.0).collect();
        let mut before = b.clone();
        s.solve_in_place(&mut before);
        s.release();
        assert!(!s.is_factored() && s.is_released());
        s.factor(a.as_ref()).unwrap();
        assert!(s.is_factored() && !s.is_released());
        let mut after = b;
        s.solve_in_place(&mut after);
        assert_eq!(before, after);
    }

    #[test]
    fn columns_split_between_threads_solve_like_one_block() {
        let a = laplacian(20, 0, 0.0);
        let mut s = solver(&a, SupernodalThreshold::FORCE_SUPERNODAL);
        s.factor(a.as_ref()).unwrap();
        let n = 400;
        let b = faer::Mat::<f64>::from_fn(n, 43, |i, j| ((i * 7 + j * 13) % 17) as f64 - 8.0);
        let mut one = b.clone();
        s.solve_block(one.as_mut(), faer::Par::Seq);
        // 43 columns on 3 threads: shares of 15, 15 and 13; on 8 threads only 5 shares of 8+
        for threads in [2, 3, 8] {
            let mut split = b.clone();
            s.solve_columns(split.as_mut(), faer::Par::rayon(threads));
            for j in 0..43 {
                for i in 0..n {
                    // the same arithmetic per column: equal to rounding
                    let (x, y) = (split[(i, j)], one[(i, j)]);
                    assert!((x - y).abs() <= 1e-13 * y.abs().max(1.0), "{x} vs {y}");
                }
            }
        }
        // and the solution solves K x = b (residual of the 5-point stencil)
        for j in [0, 42] {
            for k in 0..n {
                let (i, jj) = (k % 20, k / 20);
                let mut kx = 4.0 * one[(k, j)];
                if i > 0 {
                    kx -= one[(k - 1, j)];
                }
                if i + 1 < 20 {
                    kx -= one[(k + 1, j)];
                }
                if jj > 0 {
                    kx -= one[(k - 20, j)];
                }
                if jj + 1 < 20 {
                    kx -= one[(k + 20, j)];
                }
                assert!(
                    (kx - b[(k, j)]).abs() < 1e-10,
                    "row {k}: {kx} vs {}",
                    b[(k, j)]
                );
            }
        }
    }

    #[test]
    fn failed_pivot_row_works_simplicial() {
        check(SupernodalThreshold::FORCE_SIMPLICIAL, false);
    }

    #[test]
    fn failed_pivot_row_works_supernodal() {
        check(SupernodalThreshold::FORCE_SUPERNODAL, true);
    }
}
