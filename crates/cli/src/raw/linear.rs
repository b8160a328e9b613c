//! `[analysis] linear_solver` and `[analysis.petsc]` (issue 41): how the bulk's `K x = b` is
//! solved. `"direct"` (the default) is the model's own sparse Cholesky factorisation;
//! `"petsc"` is PETSc's distributed solver under MPI (`mpirun -n N bipo run scene.toml`, with a
//! `bipo` built with the feature `petsc`):
//!
//! ```toml
//! [analysis]
//! type = "3d"
//! linear_solver = "petsc"
//! [analysis.petsc]
//! method = "cg_gamg"        # conjugate gradients with algebraic multigrid (default), or "mumps"
//! rtol = 1e-12              # cg_gamg: relative residual (default 1e-12)
//! max_iterations = 10000    # cg_gamg: per solve (default 10000)
//! ```
//! The key is not `[solver]`'s: that table is the contact (reduced) solver's.

use super::RawAnalysis;
use super::keys::{only, present};
use crate::error::{CliResult, KeyPath, bail};
use serde::Deserialize;

/// `[analysis] linear_solver`.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum LinearSolverKind {
    /// The model's sparse Cholesky factorisation, in this process.
    #[default]
    Direct,
    /// PETSc under MPI.
    Petsc,
}

/// `[analysis.petsc] method`.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum PetscMethod {
    /// Conjugate gradients preconditioned by algebraic multigrid (GAMG).
    CgGamg,
    /// MUMPS's distributed direct factorisation.
    Mumps,
}

/// `[analysis.petsc]`, as read.
#[derive(Debug, Deserialize, Clone, Copy, Default)]
#[serde(deny_unknown_fields)]
pub struct RawPetsc {
    method: Option<PetscMethod>,
    rtol: Option<f64>,
    max_iterations: Option<usize>,
}

/// The linear solver a scene asks for, checked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LinearSolverSpec {
    /// The model's factorisation.
    Direct,
    /// PETSc under MPI.
    Petsc(PetscSpec),
}

/// `[analysis.petsc]`, checked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PetscSpec {
    /// CG + GAMG, stopped at `‖b − K x‖ ≤ rtol ‖b‖`.
    CgGamg {
        /// The relative residual.
        rtol: f64,
        /// Iterations per solve.
        max_iterations: usize,
    },
    /// MUMPS.
    Mumps,
}

/// The default `rtol`: the error of `x` is at most `κ(K) rtol`, and `1e-12` keeps the contact
/// answer to 1e-8 of the direct path on meshes with `κ ≲ 1e4` (bipotential-petsc's
/// `LinearSolver`).
const RTOL: f64 = 1e-12;
/// The default iterations per solve.
const MAX_ITERATIONS: usize = 10_000;

impl RawAnalysis {
    /// `linear_solver` and `[analysis.petsc]`, checked (`p` is `analysis`): an `rtol` in
    /// `(0, 1)`, iterations in `[1, 2³¹)`, no `[analysis.petsc]` without
    /// `linear_solver = "petsc"`, no CG keys with MUMPS.
    pub fn linear_solver(&self, p: &KeyPath) -> CliResult<LinearSolverSpec> {
        let pp = p.key("petsc");
        match (self.linear_solver.unwrap_or_default(), &self.petsc) {
            (LinearSolverKind::Direct, None) => Ok(LinearSolverSpec::Direct),
            (LinearSolverKind::Direct, Some(_)) => bail!(
                pp,
                "`{pp}` sets PETSc's solver, but `{}` is not \"petsc\"",
                p.key("linear_solver")
            ),
            (LinearSolverKind::Petsc, raw) => {
                let raw = raw.unwrap_or_default();
                let spec = match raw.method.unwrap_or(PetscMethod::CgGamg) {
                    PetscMethod::Mumps => {
                        let present = present!(raw; rtol, max_iterations);
                        only(&pp, "PETSc's MUMPS (a direct solver)", &present, "method")?;
                        PetscSpec::Mumps
                    }
                    PetscMethod::CgGamg => {
                        let rtol = raw.rtol.unwrap_or(RTOL);
                        if !(rtol > 0.0 && rtol < 1.0) {
                            let k = pp.key("rtol");
                            bail!(k, "`{k}` = {rtol:?}: expected a number in (0, 1)");
                        }
                        let max_iterations = raw.max_iterations.unwrap_or(MAX_ITERATIONS);
                        if max_iterations == 0 || i32::try_from(max_iterations).is_err() {
                            let k = pp.key("max_iterations");
                            bail!(
                                k,
                                "`{k}` = {max_iterations}: expected an integer in [1, 2^31)"
                            );
                        }
                        PetscSpec::CgGamg {
                            rtol,
                            max_iterations,
                        }
                    }
                };
                Ok(LinearSolverSpec::Petsc(spec))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn analysis(s: &str) -> RawAnalysis {
        toml::from_str(&format!("type = \"3d\"\n{s}")).unwrap()
    }

    #[test]
    fn issue_41_linear_solver_works() {
        let p = KeyPath::root().key("analysis");
        assert_eq!(
            analysis("").linear_solver(&p).unwrap(),
            LinearSolverSpec::Direct
        );
        assert_eq!(
            analysis("linear_solver = \"petsc\"")
                .linear_solver(&p)
                .unwrap(),
            LinearSolverSpec::Petsc(PetscSpec::CgGamg {
                rtol: RTOL,
                max_iterations: MAX_ITERATIONS
            })
        );
        assert_eq!(
            analysis("linear_solver = \"petsc\"\npetsc = { method = \"mumps\" }")
                .linear_solver(&p)
                .unwrap(),
            LinearSolverSpec::Petsc(PetscSpec::Mumps)
        );
    }

    #[test]
    fn issue_41_linear_solver_rejects_bad_keys() {
        let p = KeyPath::root().key("analysis");
        for (s, key) in [
            ("petsc = { rtol = 1e-10 }", "analysis.petsc"),
            (
                "linear_solver = \"petsc\"\npetsc = { rtol = 0.0 }",
                "analysis.petsc.rtol",
            ),
            (
                "linear_solver = \"petsc\"\npetsc = { rtol = nan }",
                "analysis.petsc.rtol",
            ),
            (
                "linear_solver = \"petsc\"\npetsc = { max_iterations = 0 }",
                "analysis.petsc.max_iterations",
            ),
            (
                "linear_solver = \"petsc\"\npetsc = { method = \"mumps\", rtol = 1e-9 }",
                "analysis.petsc.rtol",
            ),
        ] {
            let e = analysis(s).linear_solver(&p).unwrap_err();
            assert_eq!(
                e.path.as_ref().map(|k| k.to_string()).as_deref(),
                Some(key),
                "{s}"
            );
        }
    }
}
