//! Work–precision of the local (reduced-problem) solvers: wall time against the final
//! natural-map residual for every [`Algorithm`], with the tolerance swept from 1e-4 to 1e-12,
//! on random problems (`n_c` = 10, 100, 1000, 5000) and on FE-like problems exported from the
//! Hertz scene of `tests/support/hertz_scene.rs`.
//!
//! ```text
//! cargo run --release -p contact-solver --example work_precision_local -- [OUT] [--max-nc N] [--budget S]
//! OPENBLAS_NUM_THREADS=1 /usr/bin/python3 crates/contact-solver/examples/work_precision_siconos.py [OUT]
//! cargo run --release -p contact-solver --example work_precision_local -- [OUT] --plot-only
//! ```
//! `OUT` defaults to `target/work_precision_local`. The first run writes
//! - `OUT/problems/NAME.{meta.json, W.f64, ref.json}`: `q`, `μ` and `W` (raw little-endian
//!   `f64`, row-major) of each problem, and the reference reaction `r_ref` (the solution with
//!   the smallest residual found); `OUT/problems/NAME.json` too for `n_c ≤ 1000`, in the
//!   format of `shared/peers/siconos_fc.py`;
//! - `OUT/ours.csv`: one row per (problem, algorithm, tolerance);
//! - `OUT/NAME.svg` (residual against time, log–log) and `OUT/summary.md` (time to reach a
//!   residual of 1e-10, best of ours against best of Siconos when `OUT/siconos.csv` exists).
//!
//! The Python script times Siconos' `fc2d` NSGS and Lemke and `fc3d` NSN-AC (2D embedded in
//! 3D) on the same problems and writes `OUT/siconos.csv` with *our* residual of *their*
//! reactions; `--plot-only` redraws the plots and the summary with both.
//!
//! Timing: cold start (`r = 0`), solver buffers reused, the **minimum** wall time over
//! repetitions (at least 3, more while the total stays under 0.3 s, at most 50; a single run
//! when one takes over 20 s), one
//! thread (`faer::Par::Seq`; Siconos with `OPENBLAS_NUM_THREADS=1`). The minimum is used
//! because the machine is shared with other builds: it is the least disturbed run. The
//! residual is [`UzawaReport::residual`](contact_solver::UzawaReport): relative natural map
//! with `ρ⁰_i = 1/λ_max(W_ii)` (`docs/theory.md` §13); "error" is `‖r − r_ref‖/‖r_ref‖`.
//! Per (problem, algorithm) the tolerance 1e-10 runs first, then the others while the time
//! spent stays under `--budget` seconds (default 120).
//!
//! Problems: `random_N` is [`random_problem`] (`n_c = N`; seeds 1, 3, 7, 11); `random_5000`
//! uses the same generator and stream with the product `A Aᵀ` computed by faer (the plain
//! triple loop of `random_problem` would take minutes), and is cached in `OUT/problems`.
//! `hertz_M` is the plane-strain Hertz scene (P2, `M × M` fine cells) after its step,
//! frictionless; `hertz_M_slide` is the same `W` and `q_n` with `μ = 0.3` and the flat shifted
//! tangentially, `q_t + 10⁻⁴` (partial slip: stick, slip and separation together).

#[path = "../tests/support/hertz_scene.rs"]
mod hertz_scene;

use contact_solver::local::generate::{SplitMix64, random_problem};
use contact_solver::{
    Algorithm, ReducedProblem, SimulationSettings, SolverError, UzawaSettings, UzawaSolver,
};
use fem_core::{ElementKind, Idealization};
use hertz_scene::HertzScene;
use plotters::prelude::*;
use std::collections::BTreeMap;
use std::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

const ALGORITHMS: [Algorithm; 6] = [
    Algorithm::Uzawa,
    Algorithm::GaussSeidel,
    Algorithm::ClassicRccm,
    Algorithm::AndersonGaussSeidel,
    Algorithm::AndersonUzawa,
    Algorithm::Newton,
];

/// 1e-10 first (the goal), then the rest of the sweep.
const TOLERANCES: [f64; 9] = [1e-10, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-11, 1e-12];

/// The residual at which algorithms are compared in the summary.
const TARGET: f64 = 1e-10;

struct Options {
    out: PathBuf,
    max_nc: usize,
    budget: f64,
    plot_only: bool,
}

fn options() -> Result<Options, Box<dyn Error>> {
    let mut o = Options {
        out: PathBuf::from("target/work_precision_local"),
        max_nc: 5000,
        budget: 120.0,
        plot_only: false,
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--max-nc" => o.max_nc = args.next().ok_or("--max-nc N")?.parse()?,
            "--budget" => o.budget = args.next().ok_or("--budget SECONDS")?.parse()?,
            "--plot-only" => o.plot_only = true,
            _ if a.starts_with("--") => return Err(format!("unknown option {a}").into()),
            _ => o.out = PathBuf::from(a),
        }
    }
    Ok(o)
}

/// `random_problem(n_c, seed)` with the product `A Aᵀ` by faer (same stream, same problem up
/// to the rounding of the sums), for sizes where the triple loop is too slow.
fn random_problem_fast(n_c: usize, seed: u64) -> ReducedProblem {
    let m = 2 * n_c;
    let mut g = SplitMix64::new(seed);
    let s = 1.0 / (m as f64).sqrt();
    let a: Vec<f64> = (0..m * m).map(|_| s * g.uniform(-1.0, 1.0)).collect();
    // `a` is A row-major, i.e. Aᵀ column-major: W = (Aᵀ)ᵀ Aᵀ.
    let at = faer::MatRef::from_column_major_slice(&a, m, m);
    faer::set_global_parallelism(faer::Par::rayon(0));
    let product = at.transpose() * at;
    faer::set_global_parallelism(faer::Par::Seq);
    drop(a);
    let mut w = vec![0.0; m * m];
    for j in 0..m {
        for i in j..m {
            let v = product[(i, j)] + if i == j { 0.1 } else { 0.0 };
            w[i * m + j] = v;
            w[j * m + i] = v;
        }
    }
    drop(product);
    let q = (0..m)
        .map(|k| {
            if k % 2 == 0 {
                g.uniform(-1.0, 0.5)
            } else {
                g.uniform(-1.0, 1.0)
            }
        })
        .collect();
    let mu = (0..n_c).map(|_| g.uniform(0.0, 1.0)).collect();
    ReducedProblem::new(w, q, mu).expect("a generated problem is valid")
}

fn hertz_problems(cells: usize) -> Result<[(String, ReducedProblem); 2], Box<dyn Error>> {
    let scene = HertzScene::new(Idealization::PlaneStrain, ElementKind::Tri6, cells);
    // the reduced problem is exported, so the step must build a dense F*
    let mut sim = scene.simulation(
        SimulationSettings::default().with_flexibility(contact_solver::FlexibilityMode::Dense),
    );
    sim.step(1.0, 1.0)?;
    let p = sim
        .last_reduced_problem()
        .ok_or("no reduced problem")?
        .clone();
    let q = (p.q().iter().enumerate())
        .map(|(k, &a)| if k % 2 == 1 { a + 1e-4 } else { a })
        .collect();
    let slide = ReducedProblem::new(
        p.w_dense().unwrap().to_vec(),
        q,
        vec![0.3; p.contact_count()],
    )?;
    Ok([
        (format!("hertz_{cells}"), p),
        (format!("hertz_{cells}_slide"), slide),
    ])
}

fn write_raw(dir: &Path, name: &str, p: &ReducedProblem) -> Result<(), Box<dyn Error>> {
    let meta = serde_json::json!({ "n_c": p.contact_count(), "q": p.q(), "mu": p.mu() });
    std::fs::write(dir.join(format!("{name}.meta.json")), meta.to_string())?;
    let bytes: Vec<u8> = p
        .w_dense()
        .unwrap()
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    std::fs::write(dir.join(format!("{name}.W.f64")), bytes)?;
    if p.contact_count() <= 1000 {
        std::fs::write(dir.join(format!("{name}.json")), p.to_json()?)?;
    }
    Ok(())
}

fn read_raw(dir: &Path, name: &str) -> Option<ReducedProblem> {
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join(format!("{name}.meta.json"))).ok()?)
            .ok()?;
    let vec =
        |k: &str| -> Option<Vec<f64>> { meta[k].as_array()?.iter().map(|v| v.as_f64()).collect() };
    let bytes = std::fs::read(dir.join(format!("{name}.W.f64"))).ok()?;
    let w = bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
    ReducedProblem::new(w, vec("q")?, vec("mu")?).ok()
}

fn problems(o: &Options, dir: &Path) -> Result<Vec<(String, ReducedProblem)>, Box<dyn Error>> {
    let mut out = Vec::new();
    for (nc, seed) in [(10, 1), (100, 3), (1000, 7), (5000, 11)] {
        if nc > o.max_nc {
            continue;
        }
        let name = format!("random_{nc}");
        let t = Instant::now();
        let p = if nc <= 1000 {
            random_problem(nc, seed)
        } else if let Some(p) = read_raw(dir, &name) {
            p
        } else {
            random_problem_fast(nc, seed)
        };
        eprintln!("{name}: built in {:.1?}", t.elapsed());
        out.push((name, p));
    }
    for cells in [8, 64] {
        out.extend(hertz_problems(cells)?);
    }
    Ok(out)
}

/// One measured point.
struct Row {
    problem: String,
    n_c: usize,
    solver: String,
    tol: f64,
    time_ms: f64,
    median_ms: f64,
    residual: f64,
    error: f64,
    iterations: usize,
    converged: bool,
}

const HEADER: &str =
    "source,problem,n_c,solver,tol,time_ms,median_ms,residual,error,iterations,converged";

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

fn run(o: &Options) -> Result<(), Box<dyn Error>> {
    let dir = o.out.join("problems");
    std::fs::create_dir_all(&dir)?;
    let mut csv = format!("{HEADER}\n");
    for (name, p) in problems(o, &dir)? {
        write_raw(&dir, &name, &p)?;
        let laws = p.coulomb_laws();
        let mut rows: Vec<(Row, Vec<f64>)> = Vec::new();
        for algorithm in ALGORITHMS {
            let mut spent = 0.0;
            for tol in TOLERANCES {
                if spent > o.budget {
                    eprintln!("{name} {algorithm:?}: budget spent, tol {tol:e} skipped");
                    continue;
                }
                let mut solver = UzawaSolver::new(
                    UzawaSettings::default()
                        .with_algorithm(algorithm)
                        .with_tol(tol)
                        .with_max_iterations(1_000_000)
                        .with_accept_non_converged(true),
                );
                let mut times = Vec::new();
                let mut last = None;
                let start = Instant::now();
                // At least 3 runs (1 when a run takes over 20 s), more while under 0.3 s, at
                // most 50.
                loop {
                    let elapsed = start.elapsed().as_secs_f64();
                    let n = times.len();
                    if n >= 50 || (n >= 3 && elapsed >= 0.3) || (n >= 1 && elapsed > 20.0) {
                        break;
                    }
                    let t = Instant::now();
                    let s = solver.solve(&p, &laws);
                    times.push(t.elapsed().as_secs_f64() * 1e3);
                    last = Some(s);
                }
                spent += start.elapsed().as_secs_f64();
                times.sort_by(f64::total_cmp);
                let sol = match last {
                    Some(Ok(s)) => s,
                    Some(Err(e)) => return Err(e.into()),
                    None => {
                        return Err(SolverError::Format {
                            reason: "no run".into(),
                        }
                        .into());
                    }
                };
                let row = Row {
                    problem: name.clone(),
                    n_c: p.contact_count(),
                    solver: format!("{algorithm:?}"),
                    tol,
                    time_ms: times[0],
                    median_ms: times[times.len() / 2],
                    residual: sol.report.residual,
                    error: f64::NAN,
                    iterations: sol.report.iterations,
                    converged: sol.report.converged,
                };
                eprintln!(
                    "{name:18} {algorithm:20?} tol {tol:7.0e}: {:10.4} ms (median {:10.4}, {} runs) \
                     residual {:8.2e}, {} it{}",
                    row.time_ms,
                    row.median_ms,
                    times.len(),
                    row.residual,
                    row.iterations,
                    if row.converged { "" } else { " NOT CONVERGED" }
                );
                rows.push((row, sol.r));
            }
        }
        // Reference: the reaction with the smallest residual found.
        let best = rows
            .iter()
            .min_by(|a, b| a.0.residual.total_cmp(&b.0.residual))
            .map(|(_, r)| r.clone())
            .ok_or("no rows")?;
        let best_norm = norm(&best).max(f64::MIN_POSITIVE);
        std::fs::write(
            dir.join(format!("{name}.ref.json")),
            serde_json::json!({ "r": best }).to_string(),
        )?;
        for (row, r) in &mut rows {
            let d: Vec<f64> = r.iter().zip(&best).map(|(a, b)| a - b).collect();
            row.error = norm(&d) / best_norm;
            writeln!(
                csv,
                "ours,{},{},{},{:e},{},{},{:e},{:e},{},{}",
                row.problem,
                row.n_c,
                row.solver,
                row.tol,
                row.time_ms,
                row.median_ms,
                row.residual,
                row.error,
                row.iterations,
                row.converged
            )?;
        }
        // Written after every problem, so a long run keeps what it measured.
        std::fs::write(o.out.join("ours.csv"), &csv)?;
    }
    Ok(())
}

/// Reads the rows of a CSV written by this example or by the Siconos script.
fn read_rows(path: &Path) -> Result<Vec<(String, Row)>, Box<dyn Error>> {
    let Ok(text) = std::fs::read_to_string(path) else {
        return Ok(Vec::new());
    };
    let mut out = Vec::new();
    for line in text.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split(',').collect();
        if f.len() < 11 {
            return Err(format!("{}: short line {line}", path.display()).into());
        }
        out.push((
            f[0].to_string(),
            Row {
                problem: f[1].to_string(),
                n_c: f[2].parse()?,
                solver: f[3].to_string(),
                tol: f[4].parse()?,
                time_ms: f[5].parse()?,
                median_ms: f[6].parse()?,
                residual: f[7].parse()?,
                error: f[8].parse().unwrap_or(f64::NAN),
                iterations: f[9].parse()?,
                converged: matches!(f[10].trim(), "true" | "True" | "1"),
            },
        ));
    }
    Ok(out)
}

/// Log–log plot of residual against time, one line per solver through its tolerance sweep.
fn plot(
    path: &Path,
    title: &str,
    series: &[(String, Vec<(f64, f64)>)],
) -> Result<(), Box<dyn Error>> {
    let floor = 1e-17; // residuals of exactly 0 are drawn at the floor
    let pts = series.iter().flat_map(|s| s.1.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y.max(floor));
        y1 = y1.max(y.max(floor));
    }
    let root = SVGBackend::new(path, (760, 500)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(
            (x0 / 1.5..x1 * 1.5).log_scale(),
            (y0 / 5.0..y1 * 5.0).log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc("wall time per solve (ms)")
        .y_desc("final relative natural residual (ours, on every solver's r)")
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()?;
    // The target residual.
    chart.draw_series(LineSeries::new(
        [(x0 / 1.5, TARGET), (x1 * 1.5, TARGET)],
        BLACK.mix(0.3),
    ))?;
    for (k, (name, points)) in series.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        let pts: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x, y.max(floor))).collect();
        // Ours: thick lines and dots; Siconos: thin lines and triangles.
        let peer = name.starts_with("siconos");
        let width = if peer { 1 } else { 2 };
        chart
            .draw_series(LineSeries::new(
                pts.iter().copied(),
                color.stroke_width(width),
            ))?
            .label(name.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(width))
            });
        if peer {
            chart.draw_series(
                pts.iter()
                    .map(|&p| TriangleMarker::new(p, 5, color.filled())),
            )?;
        } else {
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

fn report(o: &Options) -> Result<(), Box<dyn Error>> {
    let mut rows = read_rows(&o.out.join("ours.csv"))?;
    rows.extend(read_rows(&o.out.join("siconos.csv"))?);
    // problem → solver → points
    let mut by_problem: BTreeMap<(usize, String), BTreeMap<String, Vec<&Row>>> = BTreeMap::new();
    for (source, row) in &rows {
        let solver = if source == "ours" {
            row.solver.clone()
        } else {
            format!("siconos {}", row.solver)
        };
        by_problem
            .entry((row.n_c, row.problem.clone()))
            .or_default()
            .entry(solver)
            .or_default()
            .push(row);
    }
    let mut md = String::from(
        "Time (ms) to reach a relative natural residual ≤ 1e-10 (the fastest point of each \
         tolerance sweep whose final residual is ≤ 1e-10; — when none is):\n\n",
    );
    let mut names: Vec<String> = ALGORITHMS.iter().map(|a| format!("{a:?}")).collect();
    for solvers in by_problem.values() {
        for s in solvers.keys() {
            if !names.contains(s) {
                names.push(s.clone());
            }
        }
    }
    writeln!(
        md,
        "| problem | n_c | {} | best ours | best Siconos | ratio |",
        names.join(" | ")
    )?;
    writeln!(md, "|---|---|{}---|---|---|", "---|".repeat(names.len()))?;
    for ((n_c, problem), solvers) in &by_problem {
        let mut series = Vec::new();
        let mut cells = Vec::new();
        let (mut best_ours, mut best_siconos) = (
            (f64::INFINITY, String::new()),
            (f64::INFINITY, String::new()),
        );
        for name in &names {
            let Some(points) = solvers.get(name) else {
                cells.push(String::from(" "));
                continue;
            };
            let mut pts: Vec<&Row> = points.clone();
            pts.sort_by(|a, b| b.tol.total_cmp(&a.tol));
            series.push((
                name.clone(),
                pts.iter()
                    .map(|r| (r.time_ms, r.residual))
                    .collect::<Vec<_>>(),
            ));
            let t = pts
                .iter()
                .filter(|r| r.residual <= TARGET)
                .map(|r| r.time_ms)
                .fold(f64::INFINITY, f64::min);
            cells.push(if t.is_finite() {
                format!("{t:.4}")
            } else {
                "—".to_string()
            });
            let best = if name.starts_with("siconos") {
                &mut best_siconos
            } else {
                &mut best_ours
            };
            if t < best.0 {
                *best = (t, name.clone());
            }
        }
        let ratio = if best_ours.0.is_finite() && best_siconos.0.is_finite() {
            format!("{:.2}", best_siconos.0 / best_ours.0)
        } else {
            "—".to_string()
        };
        writeln!(
            md,
            "| {problem} | {n_c} | {} | {} ({:.4}) | {} ({:.4}) | {ratio} |",
            cells.join(" | "),
            best_ours.1,
            best_ours.0,
            best_siconos.1,
            best_siconos.0
        )?;
        plot(
            &o.out.join(format!("{problem}.svg")),
            &format!("{problem} (n_c = {n_c}): residual against time"),
            &series,
        )?;
    }
    md.push_str("\nratio = best Siconos time / best of ours (> 1: ours is faster).\n");
    std::fs::write(o.out.join("summary.md"), &md)?;
    println!("{md}");
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    faer::set_global_parallelism(faer::Par::Seq);
    let o = options()?;
    std::fs::create_dir_all(&o.out)?;
    if !o.plot_only {
        run(&o)?;
    }
    report(&o)
}
