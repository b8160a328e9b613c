//! [`LinearSolver`]: how PETSc solves `K x = b` (Krylov with algebraic multigrid, or a direct
//! factorisation by MUMPS).

use crate::error::PetscError;

/// The distributed linear solver. Every choice can be overridden at run time by PETSc's own
/// options (`-ksp_type`, `-pc_type`, `-ksp_rtol`, …, read by `KSPSetFromOptions`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum LinearSolver {
    /// Conjugate gradients (`KSPCG`) preconditioned by smoothed-aggregation algebraic
    /// multigrid (`PCGAMG`), stopped when the **unpreconditioned** residual
    /// `‖b − K x‖ ≤ rtol ‖b‖`. The error of `x` is at most `κ(K) · rtol` relative, so `rtol`
    /// must be tighter than the contact tolerance by the condition number: the default
    /// `1e-12` keeps the contact answers to 1e-8 of the direct path on the tests' meshes
    /// (`κ ≲ 1e4`).
    CgGamg {
        /// Relative tolerance on the unpreconditioned residual.
        rtol: f64,
        /// Most iterations per solve.
        max_iterations: usize,
    },
    /// A direct factorisation by MUMPS (`-ksp_type preonly -pc_type lu
    /// -pc_factor_mat_solver_type mumps`): exact to rounding, memory as a direct solver.
    Mumps,
}

impl Default for LinearSolver {
    fn default() -> Self {
        Self::CgGamg {
            rtol: 1e-12,
            max_iterations: 10_000,
        }
    }
}

impl LinearSolver {
    /// Checks the settings.
    ///
    /// # Errors
    /// [`PetscError::InvalidSetting`] for an `rtol` outside `(0, 1)` or no iterations.
    pub fn validate(&self) -> Result<(), PetscError> {
        if let Self::CgGamg {
            rtol,
            max_iterations,
        } = *self
        {
            if !(rtol > 0.0 && rtol < 1.0) {
                return Err(PetscError::InvalidSetting {
                    name: "rtol",
                    value: rtol,
                    expected: "a number in (0, 1)",
                });
            }
            if max_iterations == 0 || i32::try_from(max_iterations).is_err() {
                return Err(PetscError::InvalidSetting {
                    name: "max_iterations",
                    value: max_iterations as f64,
                    expected: "an integer in [1, 2^31)",
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solver_validate_rejects_bad_settings() {
        assert!(LinearSolver::default().validate().is_ok());
        assert!(LinearSolver::Mumps.validate().is_ok());
        for (rtol, its) in [(0.0, 10), (1.0, 10), (f64::NAN, 10), (1e-10, 0)] {
            let s = LinearSolver::CgGamg {
                rtol,
                max_iterations: its,
            };
            assert!(
                matches!(s.validate(), Err(PetscError::InvalidSetting { .. })),
                "{s:?}"
            );
        }
    }
}
