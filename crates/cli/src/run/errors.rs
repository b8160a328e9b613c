//! The failures of a run: an output file that cannot be written, a structure operation or a
//! step that fails. Each prints the library error's whole chain (`contact_solver::error::chain`).

use crate::build::Phase;
use crate::error::{CliError, CliResult};
use contact_solver::SolverError;
use contact_solver::error::chain;
use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

/// "cannot write `what`: " and the whole error chain (a `String` from the plotter is one link).
pub(super) fn io(what: &Path, e: impl Into<Box<dyn std::error::Error + Send + Sync>>) -> CliError {
    let e: Box<dyn std::error::Error + Send + Sync> = e.into();
    CliError::failed(format!("cannot write {}: {}", what.display(), chain(&*e)))
}

/// Creates `dir/name` for buffered writing.
pub(super) fn create(dir: &Path, name: &str) -> CliResult<BufWriter<File>> {
    let path = dir.join(name);
    File::create(&path)
        .map(BufWriter::new)
        .map_err(|e| io(&path, e))
}

/// A structure operation (supports, loads, reactions, stresses) that failed.
pub(super) fn fem_failed(what: &str, e: fem_core::FemError) -> CliError {
    CliError::failed(format!("{what}: {}", chain(&e)))
}

/// A step that failed, with a hint when raising a limit may help.
pub(super) fn step_error(e: SolverError, phase: &Phase, t: f64) -> CliError {
    let hint = match &e {
        SolverError::NotConverged { .. } => {
            " — raise [solver] max_iterations or tol, or set accept_non_converged = true"
        }
        SolverError::Stalled { .. } => {
            " — check the contact setup (a rigid-body mode, contacts that fight each other), or \
             set accept_non_converged = true"
        }
        SolverError::Unbalanced { .. } => {
            " (the body floats, [analysis] floating = true, so only its contacts hold it; a \
             smaller load may also balance)"
        }
        SolverError::AdhesionNotConverged { .. } => {
            " — raise [solver] max_adhesion_iterations or adhesion_tol, or take smaller steps"
        }
        _ => "",
    };
    CliError::failed(format!(
        "phase `{}` at t = {t}: {}{hint}",
        phase.name,
        chain(&e)
    ))
}
