//! Scale of one contact load step: a dense `F*`, the matrix-free iteration and the primal
//! active-set iteration (`FlexibilityMode::{Dense, MatrixFree, ActiveSet}`), with the number of
//! contact nodes `n_c` and the number of DOF varied independently (issue 8, "Scale").
//!
//! Scene: a P2 plane-strain rectangle `[0, W] × [0, H]` (default 2 × 1, E = 1000, ν = 0.3) of
//! `nx × ny` uniform cells, its top pressed down by a prescribed displacement
//! `(u_x, u_y) = (0.1 δ, −δ)`, `δ = 0.01 H`, onto a rigid LINE `y = −g₀ − s x` below its bottom
//! (`g₀ = 0.005 H`, `s = 0.01 H / W`: tilted, so the right part of the interface stays open).
//! The `n_c = 2 nx + 1` bottom nodes are contact candidates, all in the reduced problem (alert
//! distance `H`); `ny` sets the DOF, `2 (2 nx + 1) 2 ny` free DOF. One load step,
//! frictionless (`Signorini`) or Coulomb μ = 0.3, solver tolerance 1e-8.
//!
//! Commands (the sweeps run every configuration in its own process under
//! `/usr/bin/time -v timeout LIMIT`, for the peak resident memory, and append one CSV row each):
//!
//! ```text
//! cargo build --release --example contact_scaling
//! E=target/release/examples/contact_scaling
//! $E run --nx 50 --ny 250 --mode dense --law coulomb   # one configuration (dense | free |
//!                                                      # active), one CSV row; --steps N
//!                                                      # applies the load in N steps;
//!                                                      # --tol T (default 1e-8);
//!                                                      # --reactions FILE writes
//!                                                      # `node r_n r_t` per contact;
//!                                                      # --base block: on a deformable
//!                                                      # block (node-to-segment);
//!                                                      # --mf-window W: the Anderson
//!                                                      # window of matrix-free steps
//!                                                      # (0: momentum)
//! $E probe --nx 5000 --ny 25 --block 64                # build, time of 1 and 64 solves
//! $E sweep dof  --timeout 300    # n_c = 101, DOF 1e3 … 1e6  -> out/scale/dof.csv
//! $E sweep nc   --timeout 300    # DOF ≈ 1e5, n_c 51 … 4001  -> out/scale/nc.csv
//! $E sweep goal --timeout 600    # n_c = 10 001, DOF ≈ 1e6   -> out/scale/goal.csv
//! $E sweep nc --modes active     # one path only            -> out/scale/nc_active.csv
//! $E sweep goalcap --timeout 2400  # the same, 20 solver iterations -> out/scale/goalcap.csv
//! $E plot                        # out/scale/*.svg
//! ```
//!
//! In a sweep, once a configuration of a (law, mode) series times out, the larger ones of that
//! series are skipped (recorded as `skipped`): every cost grows along a sweep.

#[path = "common/mod.rs"]
mod common;
#[path = "scale/plot.rs"]
mod plot;

use bipotential::contact_laws::{ContactLaw, Coulomb, Signorini};
use bipotential::contact_solver::{
    Algorithm, ContactSimulation, ContactZone, FlexibilityMode, InterfaceStatus, RigidLine,
    SimulationSettings,
};
use bipotential::fem_core::generate::{RectangleSpec, rectangle};
use bipotential::fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Structure, Supports,
};
use std::collections::HashMap;
use std::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use plot::{loglog, table};

/// Solver tolerance of every timed run.
const TOL: f64 = 1e-8;
/// Young's modulus and Poisson's ratio of the block.
const YOUNG: f64 = 1000.0;
const POISSON: f64 = 0.3;
/// Friction coefficient of the Coulomb variant.
const MU: f64 = 0.3;

/// Columns of the CSV files (one row per configuration).
const HEADER: &str = "study,law,mode,nx,ny,n_c,dof,nnz_k,status,t_build,t_simulation,t_step,\
t_total,flexibility_columns,flexibility_builds,operator_applications,matrix_free_steps,\
iterations,residual,active,closed,sum_r_n,dense_f_bytes,algorithm,factorizations,\
active_set_solves,wall,peak_rss_mb";

#[derive(Clone, Debug)]
struct Config {
    nx: usize,
    ny: usize,
    law: String,
    mode: String,
    width: f64,
    height: f64,
    /// Cap on the reduced solver's iterations; the step then returns unconverged (to time the
    /// parts of a step too long to finish).
    max_iterations: Option<usize>,
    /// Reduced solver of the dense path (`None`: the default).
    algorithm: Option<String>,
    /// Load steps (the top displacement in equal increments; 1: the whole load at once).
    steps: usize,
    /// Solver tolerance (`None`: [`TOL`]), and a file for the final contact reactions (one
    /// line `node r_n r_t` per candidate): to compare a run with a tighter one.
    tol: Option<f64>,
    reactions: Option<String>,
    /// What the block is pressed on: the tilted rigid `line` (default) or a deformable
    /// `block` below it (node-to-segment, non-matching meshes).
    base: String,
    /// Matrix-free steps: the Anderson window (`None`: the settings' default; 0: momentum).
    mf_window: Option<usize>,
}

impl Config {
    fn args(&self) -> Vec<String> {
        vec![
            "--nx".into(),
            self.nx.to_string(),
            "--ny".into(),
            self.ny.to_string(),
            "--law".into(),
            self.law.clone(),
            "--mode".into(),
            self.mode.clone(),
            "--width".into(),
            self.width.to_string(),
            "--height".into(),
            self.height.to_string(),
        ]
        .into_iter()
        .chain(
            self.max_iterations
                .into_iter()
                .flat_map(|n| ["--max-iterations".to_string(), n.to_string()]),
        )
        .chain(
            self.algorithm
                .iter()
                .flat_map(|a| ["--algorithm".to_string(), a.clone()]),
        )
        .chain(["--steps".to_string(), self.steps.to_string()])
        .chain(["--base".to_string(), self.base.clone()])
        .chain(
            self.tol
                .into_iter()
                .flat_map(|t| ["--tol".to_string(), t.to_string()]),
        )
        .chain(
            self.reactions
                .iter()
                .flat_map(|f| ["--reactions".to_string(), f.clone()]),
        )
        .chain(
            self.mf_window
                .into_iter()
                .flat_map(|w| ["--mf-window".to_string(), w.to_string()]),
        )
        .collect()
    }

    fn n_c(&self) -> usize {
        2 * self.nx + 1
    }

    /// Free DOF: every node but the top row, two components each.
    fn dof(&self) -> usize {
        2 * (2 * self.nx + 1) * (2 * self.ny)
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("run") => {
            let cfg = parse_config(&args[1..])?;
            let row = if cfg.law == "coulomb" {
                run(&cfg, Coulomb::new(MU)?)?
            } else {
                run(&cfg, Signorini)?
            };
            println!("ROW,{row}");
            Ok(())
        }
        Some("probe") => {
            let block = flag(&args, "--block").map_or(Ok(64), |s| s.parse())?;
            probe(&parse_config(&args[1..])?, block)
        }
        Some("sweep") => {
            let which = args.get(1).map_or("dof", String::as_str).to_string();
            let timeout = flag(&args, "--timeout").map_or(Ok(300), |s| s.parse())?;
            let modes = flag(&args, "--modes").map(String::from);
            let algorithm = flag(&args, "--algorithm").map(String::from);
            sweep(&which, timeout, modes, algorithm)
        }
        Some("plot") => plot(),
        _ => {
            eprintln!("usage: contact_scaling run|probe|sweep dof|nc|goal|plot [options]");
            Ok(())
        }
    }
}

fn flag<'a>(args: &'a [String], name: &str) -> Option<&'a str> {
    args.iter()
        .position(|a| a == name)
        .and_then(|k| args.get(k + 1))
        .map(String::as_str)
}

fn parse_config(args: &[String]) -> Result<Config, Box<dyn Error>> {
    let get = |name: &str, default: &str| flag(args, name).unwrap_or(default).to_string();
    Ok(Config {
        nx: get("--nx", "50").parse()?,
        ny: get("--ny", "50").parse()?,
        law: get("--law", "signorini"),
        mode: get("--mode", "dense"),
        width: get("--width", "2").parse()?,
        height: get("--height", "1").parse()?,
        max_iterations: flag(args, "--max-iterations").map(str::parse).transpose()?,
        algorithm: flag(args, "--algorithm").map(String::from),
        steps: get("--steps", "1").parse::<usize>()?.max(1),
        tol: flag(args, "--tol").map(str::parse).transpose()?,
        reactions: flag(args, "--reactions").map(String::from),
        base: get("--base", "line"),
        mf_window: flag(args, "--mf-window").map(str::parse).transpose()?,
    })
}

/// A model with two node sets.
/// The model, its top and bottom nodes, and (`--base block`) the lower block's top surface.
type ModelWithSets = (LinearElasticModel, Vec<usize>, Vec<usize>, Vec<usize>);

/// The block, its top nodes, and its bottom (contactor) nodes.
fn model(cfg: &Config) -> Result<ModelWithSets, Box<dyn Error>> {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, cfg.width], [0.0, cfg.height], cfg.nx, cfg.ny)
    };
    let mut mesh = rectangle(&spec)?;
    let top = mesh.node_set("top")?.to_vec();
    let bottom = mesh.node_set("bottom")?.to_vec();
    let mut surface = Vec::new();
    let mut supports = Supports::new();
    if cfg.base == "block" {
        // a deformable base `[0, W] × [−H/2 − g₀, −g₀]` of `nx − 1` cells across (the meshes
        // do not match), clamped at its bottom
        let g0 = 0.005 * cfg.height;
        let low = rectangle(&RectangleSpec {
            kind: ElementKind::Tri6,
            ..RectangleSpec::new(
                [0.0, cfg.width],
                [-0.5 * cfg.height - g0, -g0],
                cfg.nx.saturating_sub(1).max(1),
                cfg.ny.div_ceil(2),
            )
        })?;
        let off = mesh.node_count();
        let mut nodes = mesh.nodes().to_vec();
        nodes.extend_from_slice(low.nodes());
        let mut conn = mesh.connectivity().to_vec();
        conn.extend(low.connectivity().iter().map(|n| n + off));
        let regions = vec![0; mesh.element_count() + low.element_count()];
        let mut by_x: Vec<usize> = low.node_set("top")?.iter().map(|n| n + off).collect();
        by_x.sort_by(|&a, &b| nodes[a][0].total_cmp(&nodes[b][0]));
        surface = by_x;
        let clamp: Vec<usize> = low.node_set("bottom")?.iter().map(|n| n + off).collect();
        supports.fix(&clamp, Component::X).fix(&clamp, Component::Y);
        mesh = bipotential::fem_core::Mesh::new(nodes, ElementKind::Tri6, conn, regions)?;
    } else if cfg.base != "line" {
        return Err(format!("unknown base `{}` (line | block)", cfg.base).into());
    }
    let delta = 0.01 * cfg.height;
    supports
        .prescribe(&top, Component::Y, -delta)?
        .prescribe(&top, Component::X, 0.1 * delta)?;
    let material = Material::new(YOUNG, POISSON, 0.0)?;
    let model =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, material)], supports)?;
    Ok((model, top, bottom, surface))
}

fn run<L: ContactLaw + Clone + 'static>(cfg: &Config, law: L) -> Result<String, Box<dyn Error>> {
    let t0 = Instant::now();
    let (model, top, bottom, surface) = model(cfg)?;
    let t_build = t0.elapsed().as_secs_f64();
    let (dof, nnz) = (model.dof_count(), model.nnz());
    let (g0, slope) = (0.005 * cfg.height, 0.01 * cfg.height / cfg.width);
    let ground = RigidLine::new(
        [-cfg.width, -g0 + slope * cfg.width],
        [2.0 * cfg.width, -g0 - 2.0 * slope * cfg.width],
    )?;
    let zone = if surface.is_empty() {
        ContactZone::rigid("base", bottom, ground, law, cfg.height)
    } else {
        ContactZone::node_to_segment("base", bottom, surface, law, cfg.height)
    };
    let mut settings = SimulationSettings::default().with_flexibility(match cfg.mode.as_str() {
        "dense" => FlexibilityMode::Dense,
        "free" => FlexibilityMode::MatrixFree,
        "active" => FlexibilityMode::ActiveSet,
        other => return Err(format!("unknown mode `{other}` (dense | free | active)").into()),
    });
    settings.solver.tol = cfg.tol.unwrap_or(TOL);
    if let Some(w) = cfg.mf_window {
        settings = settings.with_matrix_free_window(w);
    }
    settings.solver.algorithm = match cfg.algorithm.as_deref() {
        None => Algorithm::default(),
        Some("gs") => Algorithm::GaussSeidel,
        Some("ags") => Algorithm::AndersonGaussSeidel,
        Some("uzawa") => Algorithm::Uzawa,
        Some("newton") => Algorithm::Newton,
        Some(other) => return Err(format!("unknown algorithm `{other}`").into()),
    };
    // the time limit of the sweep stops a run, not an iteration count
    settings.solver.max_iterations = 100_000_000;
    if let Some(n) = cfg.max_iterations {
        settings.solver.max_iterations = n;
        settings.solver.accept_non_converged = true;
    }
    let t = Instant::now();
    let mut sim = ContactSimulation::new(model, vec![zone], settings)?;
    let t_sim = t.elapsed().as_secs_f64();
    // the load in `steps` equal increments of the top displacement (the time, summed)
    let delta = 0.01 * cfg.height;
    let mut t_step = 0.0;
    let mut iterations = 0;
    let mut res = None;
    for k in 1..=cfg.steps {
        let f = k as f64 / cfg.steps as f64;
        if cfg.steps > 1 {
            sim.structure_mut()
                .set_prescribed(&top, Component::Y, -delta * f)?;
            sim.structure_mut()
                .set_prescribed(&top, Component::X, 0.1 * delta * f)?;
        }
        let t = Instant::now();
        let r = sim.step(k as f64, 1.0)?;
        let dt = t.elapsed().as_secs_f64();
        t_step += dt;
        iterations += r.report.contact_iterations;
        if cfg.steps > 1 {
            let c = sim.counters();
            eprintln!(
                "step {k}/{}: {dt:.2} s, {} iterations (so far: {} factorisations, {} solves)",
                cfg.steps,
                r.report.contact_iterations,
                c.active_set_factorizations,
                c.active_set_solves
            );
        }
        res = Some(r);
    }
    let res = res.ok_or("no step")?;
    let t_total = t0.elapsed().as_secs_f64();
    let c = sim.counters();
    let status = if res.report.converged { "ok" } else { "capped" };
    eprintln!(
        "{iterations} contact iterations ({} on the correction columns), {} factorisations, \
         {} solves",
        c.active_set_inner_iterations, c.active_set_factorizations, c.active_set_solves
    );
    let closed = res
        .contacts
        .iter()
        .filter(|r| matches!(r.status, InterfaceStatus::Stick | InterfaceStatus::Slip))
        .count();
    let sum_rn: f64 = res.contacts.iter().map(|r| r.r.n).sum();
    if let Some(path) = &cfg.reactions {
        let mut text = String::new();
        for c in &res.contacts {
            writeln!(text, "{} {:e} {:e}", c.node, c.r.n, c.r.t[0])?;
        }
        std::fs::write(path, text)?;
    }
    let n_c = sim.candidates().len();
    let dense_bytes = if res.report.matrix_free || res.report.active_set {
        0
    } else {
        8 * (2 * n_c) * (2 * n_c)
    };
    Ok(format!(
        "{},{},{},{},{n_c},{dof},{nnz},{status},{t_build},{t_sim},{t_step},{t_total},{},{},{},{},{},{},{},\
         {closed},{sum_rn},{dense_bytes},{:?},{},{}",
        cfg.law,
        cfg.mode,
        cfg.nx,
        cfg.ny,
        c.flexibility_columns,
        c.flexibility_builds,
        c.operator_applications,
        c.matrix_free_steps,
        iterations,
        res.report.residual,
        res.report.active_contacts,
        settings.solver.algorithm,
        c.active_set_factorizations,
        c.active_set_solves,
    ))
}

/// Model build, then the time of one structure solve and of one block of `block` right-hand
/// sides (`F*` is built in blocks of `columns_per_solve`, default 64): the unit costs of both
/// modes.
fn probe(cfg: &Config, block_size: usize) -> Result<(), Box<dyn Error>> {
    let t = Instant::now();
    let (model, _, bottom, _) = model(cfg)?;
    let t_build = t.elapsed().as_secs_f64();
    let n = model.dof_count();
    let mut rhs: Vec<f64> = (0..n).map(|i| ((i * 7919) % 1000) as f64 * 1e-3).collect();
    let t = Instant::now();
    model.solve_in_place(&mut rhs)?;
    let t1 = t.elapsed().as_secs_f64();
    let mut block = faer::Mat::<f64>::zeros(n, block_size);
    for (c, &node) in bottom.iter().cycle().take(block_size).enumerate() {
        if let Some(d) = model.node_dofs(node)[1] {
            block[(d, c)] = 1.0;
        }
    }
    let t = Instant::now();
    model.solve_many_in_place(block.as_mut())?;
    let t_block = t.elapsed().as_secs_f64();
    let k = model.stiffness();
    let t = Instant::now();
    let mut spd = bipotential::fem_core::SpdSolver::new(k.symbolic())?;
    let t_sym = t.elapsed().as_secs_f64();
    let t = Instant::now();
    spd.factor(k)?;
    let t_num = t.elapsed().as_secs_f64();
    println!("symbolic {t_sym:.3} s, numeric {t_num:.3} s");
    println!(
        "nx {} ny {}: n_c {}, dof {n}, nnz(K) {}, build {t_build:.3} s, one solve {t1:.4} s, \
         {block_size} solves {t_block:.4} s ({:.4} s per column)",
        cfg.nx,
        cfg.ny,
        cfg.n_c(),
        model.nnz(),
        t_block / block_size as f64
    );
    Ok(())
}

/// `ny` for a target number of free DOF at a given `nx`.
fn ny_for(nx: usize, dof: f64) -> usize {
    ((dof / (4.0 * (2 * nx + 1) as f64)).round() as usize).max(1)
}

/// Runs the configurations of sweep `which` (only `modes` if given, with the dense path's
/// `algorithm` if given) into `out/scale/{which}[_{modes}][_{algorithm}].csv`.
fn sweep(
    which: &str,
    timeout: u64,
    modes: Option<String>,
    algorithm: Option<String>,
) -> Result<(), Box<dyn Error>> {
    let exe = std::env::current_exe()?;
    let base = |nx, ny, law: &str, mode: &str| Config {
        nx,
        ny,
        law: law.into(),
        mode: mode.into(),
        width: 2.0,
        height: 1.0,
        max_iterations: None,
        algorithm: algorithm.clone(),
        steps: 1,
        tol: None,
        reactions: None,
        base: "line".into(),
        mf_window: None,
    };
    // (series key, configurations in increasing cost)
    let mut plan: Vec<Config> = Vec::new();
    for law in ["signorini", "coulomb"] {
        for mode in ["dense", "free", "active"] {
            if modes.as_deref().is_some_and(|m| m != mode) {
                continue;
            }
            match which {
                "dof" => {
                    for dof in [1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6] {
                        plan.push(base(50, ny_for(50, dof), law, mode));
                    }
                }
                "nc" => {
                    for nx in [25, 50, 100, 200, 400, 800, 1200, 2000] {
                        plan.push(base(nx, ny_for(nx, 1e5), law, mode));
                    }
                }
                "goal" => plan.push(base(5000, 25, law, mode)),
                // the goal scene with the reduced solver capped at 20 iterations: the time of
                // F* (or of 20 products) and the memory at full size (Coulomb's dense F* is
                // the frictionless one with twice the columns: not run)
                "goalcap" if !(law == "coulomb" && mode == "dense") && mode != "active" => plan
                    .push(Config {
                        max_iterations: Some(20),
                        ..base(5000, 25, law, mode)
                    }),
                "goalcap" => {}
                other => {
                    return Err(
                        format!("unknown sweep `{other}` (dof | nc | goal | goalcap)").into(),
                    );
                }
            }
        }
    }
    let mut name = which.to_string();
    for suffix in [&modes, &algorithm].into_iter().flatten() {
        name = format!("{name}_{suffix}");
    }
    let path = PathBuf::from(format!("out/scale/{name}.csv"));
    std::fs::create_dir_all("out/scale")?;
    let mut csv = format!("{HEADER}\n");
    std::fs::write(&path, &csv)?;
    let mut failed: HashMap<(String, String), String> = HashMap::new();
    for cfg in plan {
        let key = (cfg.law.clone(), cfg.mode.clone());
        let line = if let Some(why) = failed.get(&key) {
            format!(
                "{which},{},{},{},{},{},{},,skipped after {why},,,,,,,,,,,,,,,,,",
                cfg.law,
                cfg.mode,
                cfg.nx,
                cfg.ny,
                cfg.n_c(),
                cfg.dof()
            )
        } else {
            let start = Instant::now();
            let out = Command::new("/usr/bin/time")
                .arg("-v")
                .arg("timeout")
                .arg(timeout.to_string())
                .arg(&exe)
                .arg("run")
                .args(cfg.args())
                .output()?;
            let wall = start.elapsed().as_secs_f64();
            let stdout = String::from_utf8_lossy(&out.stdout);
            let stderr = String::from_utf8_lossy(&out.stderr);
            let rss_mb = stderr
                .lines()
                .find_map(|l| l.trim().strip_prefix("Maximum resident set size (kbytes):"))
                .and_then(|v| v.trim().parse::<f64>().ok())
                .map_or(f64::NAN, |kb| kb / 1024.0);
            match stdout.lines().find_map(|l| l.strip_prefix("ROW,")) {
                Some(row) => format!("{which},{row},{wall:.3},{rss_mb:.1}"),
                None => {
                    let status = match out.status.code() {
                        Some(124) => format!("timeout {timeout} s"),
                        Some(c) => {
                            let why = stderr
                                .lines()
                                .find(|l| l.starts_with("Error"))
                                .unwrap_or("")
                                .replace(',', ";");
                            format!("exit {c} {why}")
                        }
                        None => "killed".to_string(),
                    };
                    failed.insert(key, status.clone());
                    format!(
                        "{which},{},{},{},{},{},{},,{status},,,,,,,,,,,,,,,,{wall:.3},{rss_mb:.1}",
                        cfg.law,
                        cfg.mode,
                        cfg.nx,
                        cfg.ny,
                        cfg.n_c(),
                        cfg.dof()
                    )
                }
            }
        };
        eprintln!("{line}");
        csv.push_str(&line);
        csv.push('\n');
        std::fs::write(&path, &csv)?;
    }
    Ok(())
}

/// One CSV file as rows of named fields.
fn read_rows(path: &Path) -> Vec<HashMap<String, String>> {
    let Ok(text) = std::fs::read_to_string(path) else {
        return Vec::new();
    };
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .unwrap_or("")
        .split(',')
        .map(String::from)
        .collect();
    lines
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect()
}

fn num(row: &HashMap<String, String>, key: &str) -> f64 {
    row.get(key)
        .and_then(|v| v.parse().ok())
        .unwrap_or(f64::NAN)
}

/// The rows of every `out/scale/{study}*.csv` (the sweeps split by mode or algorithm).
fn read_study(dir: &Path, study: &str) -> Vec<HashMap<String, String>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.ends_with(".csv")
                && (name == format!("{study}.csv") || name.starts_with(&format!("{study}_")))
        })
        .collect();
    files.sort();
    files.iter().flat_map(|f| read_rows(f)).collect()
}

/// The curve label of a row: law, mode, and the reduced solver of the dense path.
fn label(r: &HashMap<String, String>) -> String {
    if r["mode"] == "free" {
        return format!("{}, matrix-free", r["law"]);
    }
    if r["mode"] == "active" {
        return format!("{}, active set (no F*)", r["law"]);
    }
    let algorithm = match r.get("algorithm").map_or("", String::as_str) {
        "GaussSeidel" => "GS",
        "AndersonGaussSeidel" => "Anderson GS",
        other => other,
    };
    format!("{}, dense F* ({algorithm})", r["law"])
}

/// Curves `y(x)` of the finished runs, one per label, in order of first appearance.
fn curves(rows: &[HashMap<String, String>], x: &str, y: &str) -> Vec<common::Series> {
    let mut out: Vec<common::Series> = Vec::new();
    for r in rows.iter().filter(|r| r["status"] == "ok") {
        let p = (num(r, x), num(r, y));
        if !(p.0 > 0.0 && p.1 > 0.0) {
            continue;
        }
        let name = label(r);
        match out.iter_mut().find(|s| s.name == name) {
            Some(s) => s.points.push(p),
            None => out.push(common::Series::new(name, vec![p])),
        }
    }
    out.sort_by(|a, b| a.name.cmp(&b.name));
    out
}

fn plot() -> Result<(), Box<dyn Error>> {
    let dir = Path::new("out/scale");
    let dof = read_study(dir, "dof");
    let nc = read_study(dir, "nc");
    if !dof.is_empty() {
        let mut time = curves(&dof, "dof", "t_step");
        let mut builds: Vec<(f64, f64)> = dof
            .iter()
            .filter(|r| r["status"] == "ok" && r["law"] == "signorini" && r["mode"] == "free")
            .map(|r| (num(r, "dof"), num(r, "t_build")))
            .collect();
        builds.sort_by(|a, b| a.0.total_cmp(&b.0));
        time.push(common::Series::new("model build (K + Cholesky)", builds));
        loglog(
            &dir.join("dof_time.svg"),
            "One load step, n_c = 101, tol 1e-8",
            "free DOF",
            "step time (s)",
            &time,
        )?;
        loglog(
            &dir.join("dof_memory.svg"),
            "Peak resident memory, n_c = 101",
            "free DOF",
            "peak RSS (MiB)",
            &curves(&dof, "dof", "peak_rss_mb")
                .into_iter()
                .filter(|s| !s.name.contains("(GS)"))
                .collect::<Vec<_>>(),
        )?;
    }
    if !nc.is_empty() {
        loglog(
            &dir.join("nc_time.svg"),
            "One load step, DOF ≈ 1e5, tol 1e-8",
            "contact nodes n_c",
            "step time (s)",
            &curves(&nc, "n_c", "t_step"),
        )?;
        // the dense memory hardly depends on the solver: the default's and Newton's (its LU)
        let mut mem = curves(&nc, "n_c", "peak_rss_mb");
        mem.retain(|s| !s.name.contains("(GS)"));
        let ncs: Vec<f64> = nc
            .iter()
            .map(|r| num(r, "n_c"))
            .filter(|v| v.is_finite())
            .collect();
        let (lo, hi) = ncs
            .iter()
            .fold((f64::MAX, 0.0_f64), |(a, b), &v| (a.min(v), b.max(v)));
        let f_line: Vec<(f64, f64)> = (0..=20)
            .map(|k| lo * (hi / lo).powf(k as f64 / 20.0))
            .map(|n| (n, 64.0 * n * n / (1024.0 * 1024.0)))
            .collect();
        mem.push(common::Series::new(
            "F* and its copy in the reduced problem: 64 n_c² bytes",
            f_line,
        ));
        loglog(
            &dir.join("nc_memory.svg"),
            "Peak resident memory, DOF ≈ 1e5",
            "contact nodes n_c",
            "peak RSS (MiB)",
            &mem,
        )?;
        let mut work = Vec::new();
        for law in ["signorini", "coulomb"] {
            let pick = |mode: &str, key: &str| -> Vec<(f64, f64)> {
                // one point per n_c (the dense runs of every algorithm build the same F*)
                let points: std::collections::BTreeMap<u64, f64> = nc
                    .iter()
                    .filter(|r| r["law"] == law && r["mode"] == mode && r["status"] == "ok")
                    .map(|r| (num(r, "n_c") as u64, num(r, key)))
                    .collect();
                points.into_iter().map(|(n, v)| (n as f64, v)).collect()
            };
            work.push(common::Series::new(
                format!("{law}: F* columns (dense)"),
                pick("dense", "flexibility_columns"),
            ));
            work.push(common::Series::new(
                format!("{law}: products F* r (matrix-free)"),
                pick("free", "operator_applications"),
            ));
            work.push(common::Series::new(
                format!("{law}: solves (active set)"),
                pick("active", "active_set_solves"),
            ));
            work.push(common::Series::new(
                format!("{law}: factorisations (active set)"),
                pick("active", "factorizations"),
            ));
        }
        work.retain(|s| !s.points.is_empty());
        loglog(
            &dir.join("nc_solves.svg"),
            "Structure solves per step, DOF ≈ 1e5, tol 1e-8",
            "contact nodes n_c",
            "solves with the factorised K",
            &work,
        )?;
        loglog(
            &dir.join("nc_iterations.svg"),
            "Reduced-solver iterations, DOF ≈ 1e5, tol 1e-8",
            "contact nodes n_c",
            "iterations (sweeps, Newton steps or products)",
            &curves(&nc, "n_c", "iterations"),
        )?;
    }
    // the table of every CSV, for the docs
    for name in ["dof", "nc", "goal", "goalcap"] {
        let rows = read_study(dir, name);
        if !rows.is_empty() {
            println!("\n{name}:\n{}", table(&rows));
        }
    }
    Ok(())
}
