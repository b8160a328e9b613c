//! The exact (non-symmetric) consistent tangent of a [`super::PlasticModel`] and its sparse
//! LU (issue 40): [`TangentKind`] and the full-storage matrix behind
//! [`TangentKind::Exact`].
//!
//! The full pattern is the elastic model's lower pattern mirrored (both triangles, sorted
//! rows per column); the symbolic LU (faer's COLAMD ordering) is done once when the body is
//! built, the numeric one at every tangent update.

use crate::assembly::Pattern;
use crate::error::FemError;
use faer::linalg::solvers::SolveCore;
use faer::sparse::linalg::LuError;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut};

/// Which tangent a [`super::PlasticModel`] assembles and factorises.
///
/// The default of a body ([`super::PlasticModel::new`]) is chosen by measurement
/// (`docs/validation.md`, "Plastic bodies"): [`TangentKind::Exact`] when some region's law
/// is non-associated ([`super::ConstitutivePoint::symmetric_tangent`] is `false`),
/// [`TangentKind::Symmetric`] otherwise, where both are the same matrix and the Cholesky is
/// the cheaper exact solve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TangentKind {
    /// `Σ Bᵀ sym(C_t) B w`, `sym(C) = (C + Cᵀ)/2`, factorised with the elastic model's
    /// sparse Cholesky: the consistent tangent of an associated law, an approximation
    /// (linear Newton, possibly indefinite) for a non-associated one.
    Symmetric,
    /// `Σ Bᵀ C_t B w` in full storage, factorised with a sparse LU: the consistent tangent
    /// of any law (quadratic Newton).
    Exact,
}

/// The full-storage tangent and its LU.
pub(super) struct ExactTangent {
    full: SymbolicSparseColMat<usize>,
    /// The values on `full`.
    pub(super) values: Vec<f64>,
    /// For lower position `p` (entry `(i, j)`, `i ≥ j`) of the elastic pattern: the
    /// positions of `(i, j)` and `(j, i)` in `full`.
    pub(super) lower_to_full: Vec<[usize; 2]>,
    symbolic: SymbolicLu<usize>,
    lu: Option<Lu<usize, f64>>,
}

impl core::fmt::Debug for ExactTangent {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("ExactTangent")
            .field("nnz", &self.values.len())
            .finish()
    }
}

impl ExactTangent {
    /// Mirrors the lower `pattern` and analyses it (symbolic LU).
    ///
    /// # Errors
    /// [`FemError::LinearAlgebra`] if faer fails (allocation, index overflow).
    pub(super) fn new(pattern: &Pattern) -> Result<Self, FemError> {
        let lower = pattern.symbolic();
        let n = lower.ncols();
        let (col_ptr, row_idx) = (lower.col_ptr(), lower.row_idx());
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); n];
        for j in 0..n {
            for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
                cols[j].push(i);
                if i != j {
                    cols[i].push(j);
                }
            }
        }
        let mut full_ptr = Vec::with_capacity(n + 1);
        let mut full_idx = Vec::with_capacity(2 * row_idx.len());
        full_ptr.push(0);
        for col in &mut cols {
            col.sort_unstable();
            full_idx.extend_from_slice(col);
            full_ptr.push(full_idx.len());
        }
        let full = SymbolicSparseColMat::new_checked(n, n, full_ptr, None, full_idx);
        let position = |row: usize, col: usize| {
            let (s, e) = (full.col_ptr()[col], full.col_ptr()[col + 1]);
            // every mirrored entry is in `full` by construction
            s + full.row_idx()[s..e].binary_search(&row).unwrap_or(0)
        };
        let mut lower_to_full = Vec::with_capacity(row_idx.len());
        for j in 0..n {
            for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
                lower_to_full.push([position(i, j), position(j, i)]);
            }
        }
        let symbolic = SymbolicLu::try_new(full.as_ref())?;
        Ok(Self {
            values: vec![0.0; full.row_idx().len()],
            full,
            lower_to_full,
            symbolic,
            lu: None,
        })
    }

    /// The matrix with the current values.
    pub(super) fn matrix(&self) -> SparseColMatRef<'_, usize, f64> {
        SparseColMatRef::new(self.full.as_ref(), &self.values)
    }

    /// Numeric LU of the current values.
    ///
    /// # Errors
    /// [`FemError::LinearAlgebra`] if the matrix is singular (no pivot at some step) or
    /// faer fails.
    pub(super) fn factor(&mut self) -> Result<(), FemError> {
        self.lu = None;
        let lu =
            Lu::try_new_with_symbolic(self.symbolic.clone(), self.matrix()).map_err(
                |e| match e {
                    LuError::SymbolicSingular { index } => FemError::LinearAlgebra {
                        detail: format!(
                            "the exact plastic tangent is singular (the sparse LU found no pivot \
                         at step {index}): a mechanism of the body"
                        ),
                    },
                    LuError::Generic(e) => e.into(),
                },
            )?;
        self.lu = Some(lu);
        Ok(())
    }

    /// Solves `K X = B` in place.
    ///
    /// # Errors
    /// [`FemError::LinearAlgebra`] if no factorisation has succeeded since the last failure,
    /// or if the solution is not finite (a numerically singular matrix).
    pub(super) fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), FemError> {
        let Some(lu) = &self.lu else {
            return Err(FemError::LinearAlgebra {
                detail: "a solve with the exact plastic tangent after its factorisation failed"
                    .into(),
            });
        };
        let mut rhs = rhs;
        lu.solve_in_place_with_conj(Conj::No, rhs.as_mut());
        // a numerically singular matrix (a zero pivot) leaves infinities or NaN
        for j in 0..rhs.ncols() {
            for i in 0..rhs.nrows() {
                if !rhs[(i, j)].is_finite() {
                    return Err(FemError::LinearAlgebra {
                        detail: format!(
                            "the exact plastic tangent is numerically singular (the LU solve \
                             gave {} at row {i})",
                            rhs[(i, j)]
                        ),
                    });
                }
            }
        }
        Ok(())
    }
}
