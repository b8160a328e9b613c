//! Work–precision of the local solvers on 3D problems of three kinds (issue 14): piles of rigid
//! spheres ([`multibody`]), an elastic half-space under a sliding sphere ([`half_space`]) and
//! seeded random problems ([`random_problem_in`]), for the side-by-side run with Siconos' fc3d
//! solvers (`compare_siconos_3d.py`).
//!
//! ```text
//! cargo run --release -p contact-solver --example work_precision_3d -- [OUT] [--only NAME]
//! OPENBLAS_NUM_THREADS=1 /usr/bin/python3 crates/contact-solver/examples/compare_siconos_3d.py OUT
//! ```
//! `OUT` defaults to `target/work_precision_3d`. It writes, per problem `NAME`,
//! - `OUT/NAME.json`: the problem ([`ReducedProblem::to_json`], `{"dim":3,"W":[flat],…}`);
//! - `OUT/NAME.ours.json`: our reaction `r` (the answer with the smallest residual found);
//!
//! and `OUT/ours.csv` (one row per problem, algorithm and tolerance) and `OUT/problems.txt`
//! (one line per problem: name, contacts, bodies, rank deficiency). With `--only NAME` it
//! times that problem alone and prints its rows (the Python script calls it so, between
//! Siconos' runs, to alternate ours and theirs). `BIPO_QUICK=1` (without `--only`) takes the
//! smallest problem of each kind: `pile_rest_3x3x3`, `halfspace_12`, `random_100`.
//!
//! Timing: cold start (`r = 0`), one thread (`faer::Par::Seq`), fallback off, the **median** of
//! 5 runs (1 run when the first takes over 2 s; the count is in the table), tolerances 1e-8
//! and 1e-10 (the latter only when 1e-8 converged), at most 5 000 iterations.
//!
//! [`multibody`]: contact_solver::local::generate::multibody
//! [`half_space`]: contact_solver::local::generate::half_space

use contact_solver::local::generate::half_space::{HalfSpace, Indenter};
use contact_solver::local::generate::multibody::SpherePile;
use contact_solver::local::generate::random_problem_in;
use contact_solver::{Algorithm, ReducedProblem, UzawaSettings, UzawaSolver};
use std::error::Error;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

const ALGORITHMS: [Algorithm; 6] = [
    Algorithm::Newton,
    Algorithm::AndersonGaussSeidel,
    Algorithm::GaussSeidel,
    Algorithm::ClassicRccm,
    Algorithm::AndersonUzawa,
    Algorithm::Uzawa,
];

struct Problem {
    name: String,
    problem: ReducedProblem,
    bodies: usize,
    deficiency: usize,
}

fn pile(name: &str, s: SpherePile, seed: u64) -> Result<Problem, Box<dyn Error>> {
    let p = s.generate(seed)?;
    Ok(Problem {
        name: name.into(),
        bodies: p.body_count(),
        deficiency: p.rank_deficiency,
        problem: p.problem,
    })
}

fn half(name: &str, cells_across: usize) -> Result<Problem, Box<dyn Error>> {
    let hs = HalfSpace {
        cells_across,
        indenter: Indenter::Sphere { radius: 2.5 },
        ..HalfSpace::default()
    };
    Ok(Problem {
        name: name.into(),
        problem: hs.generate()?.problem,
        bodies: 1,
        deficiency: 0,
    })
}

/// The problems, by name (`only`: just that one).
fn problems(only: Option<&str>) -> Result<Vec<Problem>, Box<dyn Error>> {
    let resting = SpherePile {
        nx: 3,
        ny: 3,
        layers: 3,
        ..SpherePile::default()
    };
    let shaken = SpherePile {
        jitter: 0.05,
        threshold: 0.2,
        initial_speed: 0.05,
        ..SpherePile::default()
    };
    let mut out = Vec::new();
    type Make = Box<dyn Fn() -> Result<Problem, Box<dyn Error>>>;
    let makers: Vec<(&str, Make)> = vec![
        (
            "pile_rest_3x3x3",
            Box::new(move || pile("pile_rest_3x3x3", resting, 1)),
        ),
        (
            "pile_shaken_5x5x5",
            Box::new(move || {
                let s = SpherePile {
                    nx: 5,
                    ny: 5,
                    layers: 5,
                    ..shaken
                };
                pile("pile_shaken_5x5x5", s, 2)
            }),
        ),
        (
            "pile_shaken_7x7x5",
            Box::new(move || {
                let s = SpherePile {
                    nx: 7,
                    ny: 7,
                    layers: 5,
                    ..shaken
                };
                pile("pile_shaken_7x7x5", s, 3)
            }),
        ),
        ("halfspace_12", Box::new(|| half("halfspace_12", 12))),
        ("halfspace_24", Box::new(|| half("halfspace_24", 24))),
        ("halfspace_36", Box::new(|| half("halfspace_36", 36))),
        (
            "random_100",
            Box::new(|| {
                Ok(Problem {
                    name: "random_100".into(),
                    problem: random_problem_in(3, 100, 1),
                    bodies: 0,
                    deficiency: 0,
                })
            }),
        ),
        (
            "random_500",
            Box::new(|| {
                Ok(Problem {
                    name: "random_500".into(),
                    problem: random_problem_in(3, 500, 3),
                    bodies: 0,
                    deficiency: 0,
                })
            }),
        ),
    ];
    // quick (`BIPO_QUICK=1`, as CI runs it): the smallest problem of each kind
    let quick = std::env::var_os("BIPO_QUICK").is_some_and(|v| v != "0");
    let small = ["pile_rest_3x3x3", "halfspace_12", "random_100"];
    for (name, make) in makers {
        let wanted = match only {
            Some(o) => o == name,
            None => !quick || small.contains(&name),
        };
        if wanted {
            out.push(make()?);
        }
    }
    if out.is_empty() {
        return Err(format!("no problem named {only:?}").into());
    }
    Ok(out)
}

struct Row {
    algorithm: Algorithm,
    tol: f64,
    converged: bool,
    iterations: usize,
    runs: usize,
    ms: f64,
    residual: f64,
    norm_r: f64,
    r: Vec<f64>,
}

fn time(p: &ReducedProblem, algorithm: Algorithm, tol: f64) -> Result<Row, Box<dyn Error>> {
    let st = UzawaSettings::default()
        .with_algorithm(algorithm)
        .with_tol(tol)
        .with_max_iterations(5_000)
        .with_fallback(false)
        .with_accept_non_converged(true);
    let mut solver = UzawaSolver::new(st);
    let laws = p.coulomb_laws();
    let mut times = Vec::new();
    let mut last = None;
    while times.len() < 5 {
        let t0 = Instant::now();
        let sol = solver.solve(p, &laws)?;
        times.push(t0.elapsed().as_secs_f64());
        last = Some(sol);
        if times[0] > 2.0 {
            break;
        }
    }
    let sol = last.ok_or("no run")?;
    times.sort_by(f64::total_cmp);
    Ok(Row {
        algorithm,
        tol,
        converged: sol.report.converged,
        iterations: sol.report.iterations,
        runs: times.len(),
        ms: 1e3 * times[times.len() / 2],
        residual: sol.report.residual,
        norm_r: sol.r.iter().map(|v| v * v).sum::<f64>().sqrt(),
        r: sol.r,
    })
}

fn main() -> Result<(), Box<dyn Error>> {
    faer::set_global_parallelism(faer::Par::Seq);
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut out = PathBuf::from("target/work_precision_3d");
    let mut only = None;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--only" => only = Some(it.next().ok_or("--only needs a name")?.clone()),
            _ => out = PathBuf::from(a),
        }
    }
    std::fs::create_dir_all(&out)?;
    let mut csv = String::from(
        "problem,contacts,algorithm,tol,converged,iterations,runs,ms,residual,norm_r\n",
    );
    let mut listing = String::new();
    for pb in problems(only.as_deref())? {
        let p = &pb.problem;
        if only.is_none() {
            std::fs::write(out.join(format!("{}.json", pb.name)), p.to_json()?)?;
        }
        writeln!(
            listing,
            "{} {} {} {}",
            pb.name,
            p.contact_count(),
            pb.bodies,
            pb.deficiency
        )?;
        eprintln!(
            "# {}: n_c = {}, bodies {}, rank deficiency {}",
            pb.name,
            p.contact_count(),
            pb.bodies,
            pb.deficiency
        );
        let mut best: Option<Row> = None;
        for algorithm in ALGORITHMS {
            for tol in [1e-8, 1e-10] {
                let row = time(p, algorithm, tol)?;
                let line = format!(
                    "{},{},{:?},{:e},{},{},{},{:.3},{:.3e},{:.9e}",
                    pb.name,
                    p.contact_count(),
                    row.algorithm,
                    row.tol,
                    row.converged,
                    row.iterations,
                    row.runs,
                    row.ms,
                    row.residual,
                    row.norm_r
                );
                println!("{line}");
                writeln!(csv, "{line}")?;
                let converged = row.converged;
                if best.as_ref().is_none_or(|b| row.residual < b.residual) {
                    best = Some(row);
                }
                if !converged {
                    break;
                }
            }
        }
        if let Some(b) = best
            && only.is_none()
        {
            let r: Vec<String> = b.r.iter().map(|v| format!("{v:e}")).collect();
            std::fs::write(
                out.join(format!("{}.ours.json", pb.name)),
                format!(
                    "{{\"algorithm\":\"{:?}\",\"tol\":{:e},\"residual\":{:e},\"r\":[{}]}}",
                    b.algorithm,
                    b.tol,
                    b.residual,
                    r.join(",")
                ),
            )?;
        }
    }
    if only.is_none() {
        std::fs::write(out.join("ours.csv"), csv)?;
        std::fs::write(out.join("problems.txt"), listing)?;
    }
    Ok(())
}
