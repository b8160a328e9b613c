//! [`PetscError`]: what the distributed structure reports.

use fem_core::FemError;

/// An error of the PETSc structure or of PETSc itself.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PetscError {
    /// A PETSc (or MPI) function returned an error code; PETSc printed its trace to stderr.
    #[error("PETSc's `{function}` failed with error code {code} (PETSc's trace is on stderr)")]
    Call {
        /// The C function.
        function: &'static str,
        /// Its error code (`PetscErrorCode`).
        code: i32,
    },
    /// The Krylov solver stopped without reaching its tolerance.
    #[error(
        "the PETSc solver did not converge: KSPConvergedReason {reason} after {iterations} \
         iterations (negative reasons: PETSc's `KSPConvergedReason` list; raise `max_iterations` \
         or use `LinearSolver::Mumps`)"
    )]
    NotConverged {
        /// PETSc's `KSPConvergedReason` (negative: diverged).
        reason: i32,
        /// The iterations made.
        iterations: i64,
    },
    /// A size does not fit PETSc's index type (`PetscInt`).
    #[error("{what} = {value} does not fit PETSc's index type (rebuild PETSc with 64-bit indices)")]
    TooLarge {
        /// What is counted.
        what: &'static str,
        /// The count.
        value: usize,
    },
    /// Something the distributed structure does not do (yet).
    #[error("not supported by the PETSc structure: {what}")]
    Unsupported {
        /// What.
        what: &'static str,
    },
    /// A solver setting is out of its range.
    #[error("invalid PETSc solver setting `{name}` = {value:?}: expected {expected}")]
    InvalidSetting {
        /// The setting.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The admissible range.
        expected: &'static str,
    },
    /// The finite element data (mesh, materials, supports) is invalid.
    #[error(transparent)]
    Fem(#[from] FemError),
}

impl From<PetscError> for FemError {
    /// The contact solver sees fem-core's error: PETSc's failures as
    /// [`FemError::LinearAlgebra`] with the sentence, the model's errors unchanged.
    fn from(e: PetscError) -> Self {
        match e {
            PetscError::Fem(e) => e,
            e => FemError::LinearAlgebra {
                detail: e.to_string(),
            },
        }
    }
}

/// `Ok` for a zero code, else [`PetscError::Call`] naming `function`.
pub(crate) fn check(function: &'static str, code: i32) -> Result<(), PetscError> {
    if code == 0 {
        Ok(())
    } else {
        Err(PetscError::Call { function, code })
    }
}
