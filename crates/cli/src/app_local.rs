//! `bipo solve-local`: read a reduced problem (JSON, Siconos `.dat`, FCLIB HDF5) and solve it.

use crate::error::{CliError, CliResult};
use crate::out;
use clap::ValueEnum;
use std::path::Path;

#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum AlgorithmArg {
    /// Newton up to 1000 contacts (the accelerated sweep when it creeps), else the
    /// Anderson-accelerated Gauss–Seidel sweep; a dense W of mostly zero blocks (multibody)
    /// is solved stored sparse (measured rule, docs/benchmarks.md).
    Auto,
    /// Semi-smooth Newton on De Saxcé's projection equation.
    Newton,
    /// Anderson-accelerated projected Gauss–Seidel bipotential sweeps (the simulation's
    /// default).
    Bipotential,
    /// Plain projected Gauss–Seidel bipotential sweeps.
    GaussSeidel,
    /// Jacobi (all contacts at once) bipotential sweeps.
    Uzawa,
    /// Anderson-accelerated Jacobi sweeps.
    AndersonUzawa,
    /// The classical RCCM solver (normal and tangential split).
    RccmClassic,
}

impl AlgorithmArg {
    pub(crate) fn algorithm(self) -> contact_solver::Algorithm {
        use contact_solver::Algorithm;
        match self {
            Self::Auto => Algorithm::Auto,
            Self::Newton => Algorithm::Newton,
            Self::Bipotential => Algorithm::AndersonGaussSeidel,
            Self::GaussSeidel => Algorithm::GaussSeidel,
            Self::Uzawa => Algorithm::Uzawa,
            Self::AndersonUzawa => Algorithm::AndersonUzawa,
            Self::RccmClassic => Algorithm::ClassicRccm,
        }
    }
}

/// The name of a contact's status in `solve-local`'s table, by what its law is: a closed
/// frictionless contact (`mu = 0`) is `Closed`, neither sticking nor slipping.
pub(crate) fn status_name(status: contact_laws::ContactStatus, mu: f64) -> &'static str {
    use contact_laws::ContactStatus;
    match status {
        ContactStatus::Separation => "Separation",
        _ if mu == 0.0 => "Closed",
        ContactStatus::Stick => "Stick",
        ContactStatus::Slip => "Slip",
    }
}

/// The reduced problem of `bipo solve-local`: FCLIB HDF5 for `.h5`/`.hdf5` (feature `fclib`),
/// Siconos' `.dat` for `.dat` or a text that starts with a digit, JSON otherwise.
fn read_local_problem(
    path: &Path,
    keep_asymmetric: bool,
) -> CliResult<contact_solver::ReducedProblem> {
    use contact_solver::error::chain;
    let hdf5 = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| matches!(e.to_ascii_lowercase().as_str(), "h5" | "hdf5"));
    if hdf5 {
        #[cfg(feature = "fclib")]
        return contact_solver::local::fclib::read_fclib(path)
            .map(|f| f.problem)
            .map_err(|e| match e {
                // the message names the file already
                contact_solver::SolverError::Fclib { .. } => CliError::input(chain(&e)),
                _ => CliError::input(format!("{}: {}", path.display(), chain(&e))),
            });
        #[cfg(not(feature = "fclib"))]
        return Err(CliError::input(format!(
            "{}: FCLIB HDF5 files need a bipo built with `--features fclib` (and the system \
             HDF5 library, Debian: libhdf5-dev); or export the problem as JSON",
            path.display()
        )));
    }
    let text = std::fs::read_to_string(path).map_err(|e| {
        CliError::input(format!(
            "{}: cannot read the problem file: {e}",
            path.display()
        ))
    })?;
    // a byte-order mark (some Windows editors write one) is not part of the JSON
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let dat = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("dat"));
    if dat || text.trim_start().starts_with(|c: char| c.is_ascii_digit()) {
        return contact_solver::local::siconos_dat::read_siconos_dat(text)
            .map(|d| d.problem)
            .map_err(|e| CliError::input(format!("{}: {}", path.display(), chain(&e))));
    }
    let read = if keep_asymmetric {
        contact_solver::ReducedProblem::from_json_with_asymmetry(
            text,
            contact_solver::Asymmetry::Keep,
        )
    } else {
        contact_solver::ReducedProblem::from_json(text)
    };
    read.map_err(|e| CliError::input(format!("{}: {}", path.display(), chain(&e))))
}

pub(crate) fn solve_local(
    path: &Path,
    tol: f64,
    max_iterations: usize,
    algorithm: AlgorithmArg,
    (json, write_best): (bool, bool),
    keep_asymmetric: bool,
) -> CliResult<()> {
    use contact_solver::error::chain;
    use contact_solver::{UzawaSettings, solve_coulomb};
    let problem = read_local_problem(path, keep_asymmetric)?;
    if problem.contact_count() == 0 {
        return Err(CliError::input(format!(
            "{}: the problem has no contact (`W`, `q` and `mu` are empty): nothing to solve",
            path.display()
        )));
    }
    if !(tol.is_finite() && tol > 0.0) {
        return Err(CliError::input(format!(
            "--tol {tol}: expected a finite tolerance > 0"
        )));
    }
    if max_iterations == 0 {
        return Err(CliError::input("--max-iterations 0: expected at least 1"));
    }
    let settings = UzawaSettings::default()
        .with_tol(tol)
        .with_max_iterations(max_iterations)
        .with_algorithm(algorithm.algorithm());
    let sol = solve_coulomb(&problem, &settings).map_err(|e| {
        if let (true, Some(best)) = (write_best, e.best_iterate()) {
            let v = serde_json::json!({
                "r": best.r, "x": best.x, "residual": best.residual, "tol": tol,
                "converged": false,
            });
            out::outln!("{}", serde_json::to_string_pretty(&v).unwrap_or_default());
        }
        CliError::failed(format!("{}: {}", path.display(), chain(&e)))
    })?;
    if json {
        let rep = &sol.report;
        let v = serde_json::json!({
            "r": sol.r,
            "x": sol.x,
            "algorithm": format!("{:?}", rep.algorithm),
            "fallback_from": rep.fallback_from.map(|a| format!("{a:?}")),
            "iterations": rep.iterations,
            "residual": rep.residual,
            "converged": rep.converged,
            "asymmetry": rep.asymmetry,
            "rescaled": rep.rescaled,
        });
        out::outln!("{}", serde_json::to_string_pretty(&v).unwrap_or_default());
        return Ok(());
    }
    let rep = &sol.report;
    out::outln!(
        "{} contacts, {:?} converged in {} iterations, residual {:.3e}",
        problem.contact_count(),
        rep.algorithm,
        rep.iterations,
        rep.residual
    );
    if let Some(first) = rep.fallback_from {
        out::outln!(
            "note: {first:?} did not converge (or failed the Signorini-Coulomb check); the answer \
             is {:?}'s",
            rep.algorithm
        );
    }
    if rep.asymmetry > 0.0 {
        out::outln!(
            "note: W was symmetric only to {:.1e} (relative) and was symmetrised",
            rep.asymmetry
        );
    }
    if rep.rescaled {
        out::outln!("note: W and q were rescaled internally (magnitudes beyond 1e+-100)");
    }
    let d = problem.dimension();
    if d == 2 {
        out::outln!(
            "contact      r_n             r_t             u_n (gap)       u_t         status"
        );
    } else {
        out::outln!(
            "contact      r_n             r_t1            r_t2            u_n (gap)       u_t1            u_t2        status"
        );
    }
    for i in 0..problem.contact_count() {
        let cell = |v: &[f64]| {
            v[d * i..d * (i + 1)]
                .iter()
                .map(|a| format!("{a:>14.6e}"))
                .collect::<Vec<_>>()
                .join("  ")
        };
        out::outln!(
            "{i:>7}  {}  {}  {}",
            cell(&sol.r),
            cell(&sol.x),
            status_name(sol.report.statuses[i], problem.mu()[i])
        );
    }
    Ok(())
}
