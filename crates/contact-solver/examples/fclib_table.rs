//! Our algorithms on FCLIB files (local and global), for the table "Siconos' FCLIB files
//! (issue 37)" of `docs/benchmarks.md`: `fclib_table.py` runs this once per file and algorithm
//! (so that a per-problem time cap can end it), then Siconos' solvers, and judges every answer
//! with one residual computed outside both.
//!
//! ```text
//! cargo run --release -p contact-solver --features fclib --example fclib_table -- \
//!     OUT FILE.hdf5 ALGORITHM [--tol 1e-8] [--repeat 3] [--max-iterations 5000]
//! ```
//! Reads FILE with [`read_fclib`] (local, or global condensed to `W = Hᵀ M⁻¹ H`; the read and
//! condensation timed apart, median of `--repeat`), solves it with ALGORITHM (a name of
//! [`Algorithm`], e.g. `AndersonGaussSeidel`, `Auto`; fallback off and at most 5000 iterations
//! (`--max-iterations`; `--stall-window N` sets the stall detector's window, 0 off;
//! `--rho-scale S` multiplies the base penalty)
//! except for `Auto`, which runs with its defaults; cold start), the median of `--repeat`
//! in-process runs (one when the first takes over 2 s), and writes
//! `OUT/STEM.ALGORITHM.json`: `source`, `dofs`, `dim`, `contacts`, `sparse`, `read_ms`,
//! `algorithm`, `picked`, `ms`, `iterations`, `converged`, `residual` (ours) and `r`, or
//! `error`.

use contact_solver::local::fclib::{FclibSource, read_fclib};
use contact_solver::{Algorithm, UzawaSettings, UzawaSolver};
use std::fmt::Write as _;
use std::time::Instant;

const ALGORITHMS: [Algorithm; 7] = [
    Algorithm::Uzawa,
    Algorithm::GaussSeidel,
    Algorithm::ClassicRccm,
    Algorithm::AndersonGaussSeidel,
    Algorithm::AndersonUzawa,
    Algorithm::Newton,
    Algorithm::Auto,
];

fn main() {
    if let Err(e) = run() {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

/// The median of `times` (not empty).
fn median(times: &mut [f64]) -> f64 {
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |name: &str, default: f64| -> f64 {
        args.iter()
            .position(|a| a == name)
            .and_then(|k| args.get(k + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let usage = "usage: fclib_table OUT FILE.hdf5 ALGORITHM [--tol 1e-8] [--repeat 3] \
                 [--max-iterations 5000]";
    let (out, file, name) = match &args[..] {
        [o, f, a, ..] => (o, f, a),
        _ => return Err(usage.into()),
    };
    let algorithm = ALGORITHMS
        .into_iter()
        .find(|a| format!("{a:?}") == *name)
        .ok_or_else(|| format!("unknown algorithm `{name}`; {usage}"))?;
    let tol = flag("--tol", 1e-8);
    let repeat = (flag("--repeat", 3.0) as usize).max(1);
    let max_iterations = flag("--max-iterations", 5000.0) as usize;
    let stall_window = flag("--stall-window", f64::NAN);
    let mut read_times = Vec::new();
    let mut read = None;
    for _ in 0..repeat {
        let t0 = Instant::now();
        let f = read_fclib(file)?;
        read_times.push(1e3 * t0.elapsed().as_secs_f64());
        read = Some(f);
    }
    let read_ms = median(&mut read_times);
    let f = read.ok_or("no read")?;
    let p = &f.problem;
    let laws = p.coulomb_laws();
    let (source, dofs) = match f.source {
        FclibSource::Global { dofs } => ("global", dofs),
        _ => ("local", 0),
    };
    let mut json = format!(
        "{{\"source\": \"{source}\", \"dofs\": {dofs}, \"read_ms\": {read_ms:e}, \"dim\": {}, \
         \"contacts\": {}, \"sparse\": {}, \"algorithm\": \"{algorithm:?}\"",
        p.dimension(),
        p.contact_count(),
        p.is_sparse()
    );
    let st = UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_tol(tol)
        .with_accept_non_converged(true);
    let st = if algorithm == Algorithm::Auto {
        st
    } else {
        st.with_fallback(false).with_max_iterations(max_iterations)
    };
    // `--stall-window 0` switches the stall detector off (a diagnostic)
    let st = if stall_window.is_nan() {
        st
    } else {
        st.with_tuning(st.tuning.with_stall_window(stall_window as usize))
    };
    // `--rho-scale S` multiplies the base penalty `ρ⁰_i` (a diagnostic)
    let rho_scale = flag("--rho-scale", f64::NAN);
    let st = if rho_scale.is_nan() {
        st
    } else {
        st.with_tuning(st.tuning.with_rho_scale(rho_scale))
    };
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..repeat {
        let t = Instant::now();
        let sol = UzawaSolver::new(st).solve(p, &laws);
        times.push(1e3 * t.elapsed().as_secs_f64());
        last = Some(sol);
        if times[0] > 2000.0 {
            break;
        }
    }
    let ms = median(&mut times);
    match last.ok_or("no run")? {
        Ok(sol) => {
            let r: Vec<String> = sol.r.iter().map(|v| format!("{v:e}")).collect();
            let _ = write!(
                json,
                ", \"picked\": \"{:?}\", \"ms\": {ms:e}, \"iterations\": {}, \"converged\": {}, \
                 \"residual\": {:e}, \"r\": [{}]}}",
                sol.report.algorithm,
                sol.report.iterations,
                sol.report.converged,
                sol.report.residual,
                r.join(", ")
            );
        }
        Err(e) => {
            let msg = e.to_string().replace('"', "'");
            let _ = write!(json, ", \"ms\": {ms:e}, \"error\": \"{msg}\"}}");
        }
    }
    json.push('\n');
    let stem = std::path::Path::new(file)
        .file_stem()
        .and_then(|s| s.to_str())
        .ok_or("file name")?;
    std::fs::create_dir_all(out)?;
    std::fs::write(format!("{out}/{stem}.{algorithm:?}.json"), json)?;
    Ok(())
}
