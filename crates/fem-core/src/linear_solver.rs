//! Sparse symmetric positive definite solves: a wrapper around faer's sparse Cholesky.
//!
//! The symbolic analysis (fill-reducing ordering, elimination tree) is done once per sparsity
//! pattern; the numeric factorisation is redone only when the values change; solves take one
//! or many right-hand sides.

use crate::error::FemError;
use faer::MatMut;
use faer::Side;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};

/// A sparse SPD solver for matrices given by their lower triangle in CSC form.
#[derive(Clone, Debug)]
pub struct SpdSolver {
    symbolic: SymbolicLlt<usize>,
    numeric: Option<Llt<usize, f64>>,
    dim: usize,
    factorizations: usize,
}

impl SpdSolver {
    /// Symbolic analysis of the pattern (lower triangle).
    ///
    /// # Errors
    /// [`FemError::LinearAlgebra`] if faer fails (allocation, index overflow).
    pub fn new(pattern: SymbolicSparseColMatRef<'_, usize>) -> Result<Self, FemError> {
        let symbolic = SymbolicLlt::try_new(pattern, Side::Lower)?;
        Ok(Self {
            symbolic,
            numeric: None,
            dim: pattern.nrows(),
            factorizations: 0,
        })
    }

    /// Numeric Cholesky factorisation of `matrix` (lower triangle, same pattern as given to
    /// [`SpdSolver::new`]).
    ///
    /// # Errors
    /// [`FemError::NotPositiveDefinite`] if a pivot is not positive (typically a rigid-body
    /// mode: missing supports), [`FemError::LinearAlgebra`] otherwise.
    pub fn factor(&mut self, matrix: SparseColMatRef<'_, usize, f64>) -> Result<(), FemError> {
        self.numeric = None;
        let llt = Llt::try_new_with_symbolic(self.symbolic.clone(), matrix, Side::Lower)?;
        self.numeric = Some(llt);
        self.factorizations += 1;
        Ok(())
    }

    /// Dimension of the system.
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
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
        self.numeric
            .as_ref()
            .expect("SpdSolver::factor must succeed before solving")
            .solve_in_place(rhs);
    }
}
