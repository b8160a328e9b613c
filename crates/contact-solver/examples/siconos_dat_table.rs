//! Our algorithms on Siconos `.dat` problems, for the table of `docs/benchmarks.md` (issue 37):
//! `siconos_dat_table.py` runs this on each file, then Siconos' solvers on the same file, and
//! judges every answer with one residual computed outside both.
//!
//! ```text
//! cargo run --release -p contact-solver --example siconos_dat_table -- OUT FILE.dat [--tol 1e-8] [--repeat 3] [--only ALG]
//! cargo run --release -p contact-solver --example siconos_dat_table -- --export DIR
//! ```
//! The first form reads FILE (the read is timed apart), solves it with each algorithm
//! (fallback off, at most 5000 iterations, cold start) and with `Auto` (its defaults), each the
//! median of `--repeat` in-process runs (one when the first takes over 2 s; `Auto` with its
//! fallbacks on, and when it fails, the error's best iterate), and writes
//! `OUT/NAME.ours.json`: `source`, `read_ms`, and per run `algorithm`, `picked`, `ms`,
//! `iterations`, `outer` (Newton steps), `fallback_from`, `converged`, `residual` (ours)
//! and `r`. The second writes our own multibody
//! problems (sphere piles in a box, 3D, 64 to 1000 spheres) as `.dat` files into DIR.
//! `--only ALG` (an [`Algorithm`] as `Debug` spells it: `GaussSeidel`, `Auto`, …) runs that one
//! algorithm and writes `OUT/NAME.ALG.ours.json`, so that the script can cap each run's time by
//! killing its process.

use contact_solver::local::generate::multibody::SpherePile;
use contact_solver::local::siconos_dat::{DatSource, read_siconos_dat, write_siconos_dat};
use contact_solver::{Algorithm, Asymmetry, ReducedProblem, UzawaSettings, UzawaSolver};
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

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |name: &str, default: f64| -> f64 {
        args.iter()
            .position(|a| a == name)
            .and_then(|k| args.get(k + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    if args.first().map(String::as_str) == Some("--export") {
        let dir = args.get(1).ok_or("--export DIR")?;
        std::fs::create_dir_all(dir)?;
        for (n, layers) in [(4, 4), (6, 5), (8, 8), (10, 10)] {
            let pile = SpherePile {
                nx: n,
                ny: n,
                layers,
                jitter: 0.2,
                ..SpherePile::default()
            }
            .generate(37)?;
            // stored sparse, so that it is written in sparse blocks as multibody codes write it
            let p = &pile.problem;
            let (m, a) = (p.size(), p.w_dense().ok_or("dense W")?);
            let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
            for (k, &v) in a.iter().enumerate().filter(|(_, v)| **v != 0.0) {
                rows.push(k / m);
                cols.push(k % m);
                vals.push(v);
            }
            let sparse = ReducedProblem::from_triplets_with_asymmetry(
                3,
                &rows,
                &cols,
                &vals,
                p.q().to_vec(),
                p.mu().to_vec(),
                Asymmetry::Keep,
            )?;
            let name = format!("{dir}/pile_{}.dat", n * n * layers);
            std::fs::write(&name, write_siconos_dat(&sparse))?;
            println!("{name}: {} contacts", pile.problem.contact_count());
        }
        return Ok(());
    }
    let (out, file) = (args.first().ok_or("OUT FILE")?, args.get(1).ok_or("FILE")?);
    let tol = flag("--tol", 1e-8);
    let repeat = flag("--repeat", 3.0) as usize;
    let only = args
        .iter()
        .position(|a| a == "--only")
        .map(|k| args.get(k + 1).ok_or("--only ALG"))
        .transpose()?;
    let algorithms: Vec<Algorithm> = match only {
        None => ALGORITHMS.to_vec(),
        Some(name) => vec![
            *ALGORITHMS
                .iter()
                .find(|a| format!("{a:?}") == *name)
                .ok_or_else(|| format!("--only {name}: not one of {ALGORITHMS:?}"))?,
        ],
    };
    let text = std::fs::read_to_string(file)?;
    let t0 = Instant::now();
    let dat = read_siconos_dat(&text)?;
    let read_ms = 1e3 * t0.elapsed().as_secs_f64();
    let p = &dat.problem;
    let laws = p.coulomb_laws();
    let source = match dat.source {
        DatSource::Global { dofs } => format!("global {dofs} dofs"),
        _ => "local".to_string(),
    };
    let mut json = format!(
        "{{\"source\": \"{source}\", \"read_ms\": {read_ms:e}, \"dim\": {}, \"contacts\": {}, \
         \"sparse\": {}, \"runs\": [",
        p.dimension(),
        p.contact_count(),
        p.is_sparse()
    );
    for (k, &algorithm) in algorithms.iter().enumerate() {
        // Auto as a user gets it (its fallbacks on: accepting a non-converged answer would
        // switch them off); a failure is reported with the error's best iterate
        let st = UzawaSettings::default()
            .with_algorithm(algorithm)
            .with_tol(tol);
        let st = if algorithm == Algorithm::Auto {
            st
        } else {
            st.with_accept_non_converged(true)
                .with_fallback(false)
                .with_max_iterations(5000)
        };
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..repeat.max(1) {
            let t = Instant::now();
            let sol = UzawaSolver::new(st).solve(p, &laws);
            times.push(1e3 * t.elapsed().as_secs_f64());
            let slow = times[0] > 2000.0;
            last = Some(sol);
            if slow {
                break;
            }
        }
        times.sort_by(f64::total_cmp);
        let ms = times[times.len() / 2];
        let sep = if k == 0 { "" } else { ", " };
        match last.expect("one run") {
            Ok(sol) => {
                let r: Vec<String> = sol.r.iter().map(|v| format!("{v:e}")).collect();
                let _ = write!(
                    json,
                    "{sep}{{\"algorithm\": \"{algorithm:?}\", \"picked\": \"{:?}\", \"ms\": {ms:e}, \
                     \"iterations\": {}, \"outer\": {}, \"fallback_from\": \"{:?}\", \"converged\": {}, \
                     \"residual\": {:e}, \"r\": [{}]}}",
                    sol.report.algorithm,
                    sol.report.iterations,
                    sol.report.outer_iterations,
                    sol.report.fallback_from,
                    sol.report.converged,
                    sol.report.residual,
                    r.join(", ")
                );
            }
            Err(e) if e.best_iterate().is_some() => {
                let best = e.best_iterate().expect("checked");
                let r: Vec<String> = best.r.iter().map(|v| format!("{v:e}")).collect();
                let msg = e.to_string().replace('"', "'");
                let msg = msg.lines().next().unwrap_or("");
                let _ = write!(
                    json,
                    "{sep}{{\"algorithm\": \"{algorithm:?}\", \"picked\": \"failed: {msg}\", \
                     \"ms\": {ms:e}, \"iterations\": 0, \"converged\": false, \
                     \"residual\": {:e}, \"r\": [{}]}}",
                    best.residual,
                    r.join(", ")
                );
            }
            Err(e) => {
                let msg = e.to_string().replace('"', "'");
                let _ = write!(
                    json,
                    "{sep}{{\"algorithm\": \"{algorithm:?}\", \"ms\": {ms:e}, \"error\": \"{msg}\"}}"
                );
            }
        }
    }
    json.push_str("]}\n");
    let stem = std::path::Path::new(file)
        .file_stem()
        .and_then(|s| s.to_str())
        .ok_or("file name")?;
    std::fs::create_dir_all(out)?;
    let name = match only {
        Some(alg) => format!("{out}/{stem}.{alg}.ours.json"),
        None => format!("{out}/{stem}.ours.json"),
    };
    std::fs::write(name, json)?;
    Ok(())
}
