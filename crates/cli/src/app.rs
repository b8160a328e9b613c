//! The `bipo` command line (the binary `src/main.rs` calls [`main`]).

use crate::app_dynamic as dynamic;
use crate::app_local::{AlgorithmArg, solve_local};
use crate::app_mpi as mpi;
use crate::app_plastic as plastic;
use crate::build::Built;
use crate::error::{CliError, CliResult};
use crate::{build, error, out, run, templates};
use clap::{Parser, Subcommand};
use fem_core::Dim;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const ABOUT: &str = "Contact mechanics with De Saxcé's bipotential, from TOML scene files.";

const EXAMPLES: &str = "\
Examples:
  bipo new block                      write block.toml, a commented Signorini scene
  bipo check block.toml               validate it (mesh, model, contact recognition)
  bipo run block.toml --out out/block run it: progress, summary, CSV, VTK, SVG
  bipo run examples/scenes/delamination.toml
  bipo solve-local problem.json       solve a reduced problem {dim (2 or 3), W, q, mu}

The scene format is documented in docs/guide.md, section \"Scene files and the bipo command\".";

#[derive(Parser)]
#[command(name = "bipo", version, about = ABOUT, after_help = EXAMPLES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene: steps every phase, writes summary.json, CSV histories, VTK series and plots.
    #[command(after_help = "\
Examples:
  bipo run examples/scenes/block.toml
  bipo run examples/scenes/hertz.toml --out /tmp/hertz
  bipo run examples/scenes/delamination.toml --quiet

Writes into the output directory (default: [output] dir, else out/<scene name>):
  summary.json    steps, counters, stages that ran, peak values per zone and curve
  steps.csv       one row per step (iterations, F* rebuilds, residual, wall time)
  contacts.csv    one row per (written step, contact candidate)
  interface.pvd   interface point clouds for ParaView (+ interface_NNNN.vtu)
  mesh.pvd        whole mesh with u and stress, if [output] mesh_vtk = true
  *.svg, curves.csv   the [[plots]] of the scene")]
    Run {
        /// The scene file (TOML).
        scene: PathBuf,
        /// Output directory (overrides the scene's `output.dir`).
        #[arg(long, short)]
        out: Option<PathBuf>,
        /// No progress bar and no per-phase lines (the final summary is still printed).
        #[arg(long, short)]
        quiet: bool,
        /// Threads of the factorisations and dense kernels (faer): 1 runs them sequentially,
        /// N on N threads; by default every core while the model is built, then sequential
        /// for models under 50 000 free dofs (measured: `docs/benchmarks.md`, "Threads").
        #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
        threads: Option<u16>,
    },
    /// Validate a scene without solving: parse, check every value, build the mesh and the
    /// model, and recognise the contact zones.
    #[command(after_help = "\
Examples:
  bipo check examples/scenes/hertz.toml

A contact zone whose contactor nodes are all outside its alert distance at the start is an
error, as is any unknown key, missing node set or region, NaN or out-of-range parameter.")]
    Check {
        /// The scene file (TOML).
        scene: PathBuf,
    },
    /// Solve a reduced contact problem x = W r + q with Coulomb friction, in 2D or 3D, read
    /// from JSON {"dim": 2 or 3, "W": [...], "q": [...], "mu": [...]} (the Siconos fc2d / fc3d
    /// export format), from Siconos' numerics text format (.dat, or any file that starts with a
    /// number), or from an FCLIB HDF5 file (.h5, .hdf5; bipo built with --features fclib).
    #[command(
        name = "solve-local",
        after_help = "\
Examples:
  bipo solve-local out/hertz_reduced.json
  bipo solve-local problem.json --tol 1e-12 --json > solution.json
  bipo solve-local problem.json --tol 1e-8 --write-best > best.json   (if it fails: the best iterate)
  bipo solve-local problem.hdf5     (FCLIB; needs a bipo built with --features fclib)
  bipo solve-local Capsules-i122-1617.dat   (Siconos' .dat, local or global, dense or blocks)

The problem, n_c contacts in dimension d = \"dim\" (2 or 3; 2 when the key is left out):
  2D (dim 2): per contact (normal, tangent); m = 2 n_c
  3D (dim 3): per contact (normal, tangent 1, tangent 2); m = 3 n_c
W is m x m (flat row-major, a list of rows, or sparse triplets {\"m\", \"i\", \"j\", \"v\"}),
q has m entries (normal first per contact), mu has n_c. The table printed has r_n, r_t (r_t1,
r_t2 in 3D), the gap and the slip of each contact and its status: Separation, Stick, Slip, or
Closed for a frictionless contact (mu = 0). Signs: r_n >= 0 is compression, x_n >= 0 an
opening. W symmetric to 1e-6 (relative) is symmetrised (--keep-asymmetric: kept as given and
solved by an algorithm that allows it; uzawa and anderson-uzawa refuse it); magnitudes beyond 1e+-100 are rescaled
internally; an algorithm that stalls or whose answer fails the Signorini-Coulomb check falls
back to rccm-classic (the output says so)."
    )]
    SolveLocal {
        /// The problem file (JSON, or FCLIB .h5/.hdf5).
        problem: PathBuf,
        /// Tolerance of the stopping rule.
        #[arg(long, default_value_t = 1e-10)]
        tol: f64,
        /// Maximum iterations.
        #[arg(long, default_value_t = 10_000)]
        max_iterations: usize,
        /// Algorithm.
        #[arg(long, value_enum, default_value_t = AlgorithmArg::Auto)]
        algorithm: AlgorithmArg,
        /// Print the solution as JSON {r, x, algorithm, fallback_from, iterations, residual,
        /// converged, asymmetry, rescaled}.
        #[arg(long)]
        json: bool,
        /// Keep a non-symmetric `W` of a JSON problem as given (multibody problems with joints)
        /// instead of symmetrising it up to 1e-6 and refusing it beyond; FCLIB files are always
        /// kept as given.
        #[arg(long)]
        keep_asymmetric: bool,
        /// When the tolerance is not reached, print the best iterate (the reactions with the
        /// smallest natural-map residual of the algorithm and its fallbacks) as JSON
        /// {r, x, residual, tol, converged: false}, then fail as without it (exit status 1).
        #[arg(long)]
        write_best: bool,
    },
    /// Write a commented template scene.
    #[command(after_help = "\
Examples:
  bipo new block                 -> block.toml
  bipo new hertz -o my_hertz.toml   (also writes hertz_cylinder.msh beside it)
  bipo new delamination
  bipo new pile                  -> pile.toml (seed ch. 6, Plancoët)
  bipo new sphere_3d             -> sphere_3d.toml (3D: a rigid sphere on a block)")]
    New {
        /// What to start from.
        #[arg(value_enum)]
        kind: templates::Kind,
        /// File to write (default: KIND.toml).
        #[arg(long, short)]
        output: Option<PathBuf>,
        /// Overwrite an existing file.
        #[arg(long)]
        force: bool,
    },
}

/// Runs `bipo` with the process arguments; the exit code is 0 on success, 2 for bad input
/// (arguments, scene or problem file), 1 when the computation fails.
pub fn main() -> ExitCode {
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        let at = info
            .location()
            .map(|l| format!(" ({}:{})", l.file(), l.line()))
            .unwrap_or_default();
        eprintln!("error: internal error in bipo, please report it: {msg}{at}");
    }));
    let cli = Cli::parse();
    let size = mpi::launch_quietly();
    let code = match cli.command {
        Command::Run {
            scene,
            out,
            quiet,
            threads,
        } => with_scene(&scene, |loaded| {
            let petsc = mpi::petsc_spec(loaded, size)?;
            faer::set_global_parallelism(parallelism(threads, None));
            match (build::build(loaded)?, petsc) {
                (Built::Plane(s), Some(spec)) => {
                    let prints = (print_header::<2> as _, print_summary::<2> as _);
                    mpi::run_study(*s, loaded, (out, quiet), spec, prints)
                }
                (Built::Solid(s), Some(spec)) => {
                    let prints = (print_header::<3> as _, print_summary::<3> as _);
                    mpi::run_study(*s, loaded, (out, quiet), spec, prints)
                }
                (built, Some(_)) => Err(mpi::refuse(&built)),
                (Built::Plane(study), None) => run_study(*study, loaded, out, quiet, threads),
                (Built::Solid(study), None) => run_study(*study, loaded, out, quiet, threads),
                (Built::PlaneDynamic(s), None) => {
                    dynamic::run_study(*s, loaded, out, quiet, (threads, parallelism))
                }
                (Built::SolidDynamic(s), None) => {
                    dynamic::run_study(*s, loaded, out, quiet, (threads, parallelism))
                }
                (Built::PlanePlastic(s), None) => {
                    plastic::run_study(*s, loaded, out, quiet, (threads, parallelism))
                }
                (Built::SolidPlastic(s), None) => {
                    plastic::run_study(*s, loaded, out, quiet, (threads, parallelism))
                }
            }
        }),
        Command::Check { scene } => with_scene(&scene, |loaded| {
            let (steps, files) = match build::build(loaded)? {
                Built::Plane(study) => check_study(&study, loaded),
                Built::Solid(study) => check_study(&study, loaded),
                Built::PlaneDynamic(s) => dynamic::check_study(&s, loaded),
                Built::SolidDynamic(s) => dynamic::check_study(&s, loaded),
                Built::PlanePlastic(s) => plastic::check_study(&s, loaded),
                Built::SolidPlastic(s) => plastic::check_study(&s, loaded),
            };
            out::outln!("ok: the scene is valid ({steps} steps to run, {files} files to write)");
            Ok(())
        }),
        Command::SolveLocal {
            problem,
            tol,
            max_iterations,
            algorithm,
            json,
            keep_asymmetric,
            write_best,
        } => finish(
            solve_local(
                &problem,
                tol,
                max_iterations,
                algorithm,
                (json, write_best),
                keep_asymmetric,
            ),
            None,
        ),
        Command::New {
            kind,
            output,
            force,
        } => finish(templates::write(kind, output, force), None),
    };
    ExitCode::from(code)
}

/// `bipo run` of a built study: its header, the run, its summary.
fn run_study<const D: usize>(
    study: build::Study<D>,
    loaded: &build::Loaded,
    out: Option<PathBuf>,
    quiet: bool,
    threads: Option<u16>,
) -> CliResult<()>
where
    Dim<D>: run::Drive<D>,
{
    use fem_core::Structure;
    faer::set_global_parallelism(parallelism(threads, Some(study.model().dof_count())));
    let opts = run::RunOptions::new(out, study.output.dir.as_deref(), &loaded.path, quiet);
    print_header("run", loaded, &study);
    let summary = run::run(study, &opts)?;
    print_summary(&summary, &opts.out_dir);
    Ok(())
}

/// `bipo check` of a built study: its header; returns its steps and files.
fn check_study<const D: usize>(study: &build::Study<D>, loaded: &build::Loaded) -> (usize, usize)
where
    Dim<D>: build::StudyDim<D>,
{
    print_header("check", loaded, study);
    (study.total_steps(), study.output_files())
}

/// Below this many free dofs `bipo run` runs faer sequentially by default: rayon's start-up
/// costs more than it saves on the seed's scenes and a 14k-dof 3D one, and both cores gain
/// 10–20 % on a 1e5-dof 3D one (`docs/benchmarks.md`, "Threads"). The library's sparse
/// factorisations and solves follow the same rule whatever `--threads` says
/// (`fem_core::linear_solver::SEQUENTIAL_BELOW_DOFS`).
pub const SEQUENTIAL_BELOW_DOFS: usize = fem_core::linear_solver::SEQUENTIAL_BELOW_DOFS;

/// faer's parallelism for `bipo run`: `--threads`, else every core (while building, `dofs`
/// unknown, and for models of at least [`SEQUENTIAL_BELOW_DOFS`]) or sequential.
fn parallelism(threads: Option<u16>, dofs: Option<usize>) -> faer::Par {
    match (threads, dofs) {
        (Some(1), _) => faer::Par::Seq,
        (Some(n), _) => faer::Par::rayon(usize::from(n)),
        (None, Some(d)) if d < SEQUENTIAL_BELOW_DOFS => faer::Par::Seq,
        (None, _) => faer::Par::rayon(0),
    }
}

fn with_scene(path: &Path, f: impl FnOnce(&build::Loaded) -> CliResult<()>) -> u8 {
    let source = match std::fs::read_to_string(path) {
        Ok(s) => s,
        Err(e) => {
            return finish(
                Err(CliError::input(format!(
                    "cannot read the scene file: {}",
                    contact_solver::error::chain(&e)
                ))
                .in_file(path)),
                None,
            );
        }
    };
    let scene = match build::parse(&source) {
        Ok(s) => s,
        Err(e) => return finish(Err(e.in_file(path)), Some(&source)),
    };
    let loaded = build::Loaded {
        path: path.to_path_buf(),
        source,
        scene,
    };
    let result = f(&loaded).map_err(|e| {
        // errors about the scene's values point at the file; failures of the run do not
        if e.path.is_some() || e.span.is_some() {
            e.in_file(path)
        } else {
            e
        }
    });
    finish(result, Some(&loaded.source))
}

/// What [`check_scene`] learns of a valid scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CheckedScene {
    /// Load steps over all phases.
    pub steps: usize,
    /// Files a run writes.
    pub files: usize,
}

/// Parses and validates a scene's text as `bipo check` does: values, mesh (files relative to
/// `path`'s directory), model, contact zones; nothing is run or written. The error is the
/// message `bipo check` prints (with line and column when it is about a key). This is the
/// entry point of the scene fuzz target (`fuzz/`).
///
/// # Errors
/// The rendered message of any refusal.
pub fn check_scene(source: &str, path: &Path) -> Result<CheckedScene, String> {
    let render = |mut e: CliError| {
        if e.span.is_none()
            && let Some(p) = &e.path
        {
            e.span = error::locate(source, p);
        }
        e.in_file(path).render(Some(source))
    };
    let scene = build::parse(source).map_err(render)?;
    let loaded = build::Loaded {
        path: path.to_path_buf(),
        source: source.to_string(),
        scene,
    };
    let (steps, files) = match build::build(&loaded).map_err(render)? {
        Built::Plane(study) => (study.total_steps(), study.output_files()),
        Built::Solid(study) => (study.total_steps(), study.output_files()),
        Built::PlaneDynamic(s) => (s.spec.steps, s.output_files()),
        Built::SolidDynamic(s) => (s.spec.steps, s.output_files()),
        Built::PlanePlastic(s) => (s.total_steps(), s.output_files()),
        Built::SolidPlastic(s) => (s.total_steps(), s.output_files()),
    };
    Ok(CheckedScene { steps, files })
}

fn finish(result: CliResult<()>, source: Option<&str>) -> u8 {
    match result {
        Ok(()) => 0,
        Err(e) if out::is_silent() => e.code.clamp(1, 255) as u8,
        Err(mut e) => {
            if e.span.is_none()
                && let (Some(p), Some(src)) = (&e.path, source)
            {
                e.span = error::locate(src, p);
            }
            eprintln!("error: {}", e.render(source));
            e.code.clamp(1, 255) as u8
        }
    }
}

fn print_header<const D: usize>(cmd: &str, loaded: &build::Loaded, study: &build::Study<D>)
where
    Dim<D>: build::StudyDim<D>,
{
    use build::StudyDim;
    use fem_core::Structure;
    let model = study.model();
    let mesh = model.mesh();
    out::outln!(
        "bipo {cmd}: {} — {} ({})",
        loaded.path.display(),
        study.title,
        match &study.body {
            build::Body::Custom(_) if D == 3 => "3D scene".to_string(),
            build::Body::Custom(_) => "scene".to_string(),
            build::Body::Preset(p) => format!("preset {}", Dim::<D>::preset_kind(p)),
        }
    );
    let setting = Dim::<D>::setting(model)
        .map(|s| format!("; {s}"))
        .unwrap_or_default();
    out::outln!(
        "  mesh: {} nodes, {} elements, {}{setting}; {} free dofs",
        mesh.node_count(),
        mesh.element_count(),
        build::kind_name(mesh.kind()),
        model.dof_count()
    );
    let alert = study.alert_distances();
    for (z, name) in study.zone_names.iter().enumerate() {
        let c: Vec<_> = study.candidates().iter().filter(|c| c.zone == z).collect();
        let within = c.iter().filter(|c| c.gap0 <= alert[z]).count();
        let min_gap = c.iter().map(|c| c.gap0).fold(f64::INFINITY, f64::min);
        out::outln!(
            "  zone `{name}` ({}): {} candidates, {within} within the alert distance {} at the start (smallest gap {min_gap:.4e})",
            study.zone_laws[z],
            c.len(),
            alert[z]
        );
    }
    print_phases(&study.phases, &study.phase_law_names());
    print_warnings(&study.warnings);
}

/// The scene's warnings (e.g. contactor nodes left out), one line each.
fn print_warnings(warnings: &[String]) {
    for w in warnings {
        out::outln!("warning: {w}");
    }
}

/// The header's phase lines, with the laws a phase sets (`[[phases]] laws`).
fn print_phases(phases: &[build::Phase], set: &[Vec<(String, String)>]) {
    for (i, p) in phases.iter().enumerate() {
        let laws = set
            .get(i)
            .filter(|s| !s.is_empty())
            .map(|s| {
                let each: Vec<String> = s.iter().map(|(z, l)| format!("`{z}` {l}")).collect();
                format!("; laws from here: {}", each.join(", "))
            })
            .unwrap_or_default();
        out::outln!(
            "  phase `{}`: {} steps, t {} → {}{laws}",
            p.name,
            p.steps,
            p.t0,
            p.t1
        );
    }
}

/// The final lines of `bipo run`: the work done (each dimension's counters) and each zone's
/// results.
fn print_summary<const D: usize>(s: &run::Summary<D>, dir: &Path) {
    if D == 3 {
        print_solid_work(s);
    } else {
        print_plane_work(s);
    }
    if let Some(p) = s.totals.path {
        out::outln!("  path of the last step: {p}");
    }
    out::outln!("  outputs in {}: {}", dir.display(), s.files.join(", "));
}

/// The work of a 3D run, and each zone's force.
fn print_solid_work<const D: usize>(s: &run::Summary<D>) {
    let t = &s.totals;
    out::outln!(
        "done: {} steps in {:.3} s (t = {}), {} contact iterations, {} active-set passes, {} factorisations ({} of K, {} by the active set), {} adhesion iterations",
        s.steps,
        s.wall_time_s,
        s.time,
        s.phase_contact_iterations(),
        s.phase_passes(),
        t.factorizations(),
        t.stiffness_factorizations,
        t.active_set_factorizations,
        t.adhesion_iterations
    );
    let r = s.final_reaction.map(|r| r.to_vec()).unwrap_or_default();
    let e = |a: usize| r.get(a).copied().unwrap_or(0.0);
    out::outln!(
        "  steps: {} dense, {} active set, {} matrix-free; support reactions at the end [{:.6e}, {:.6e}, {:.6e}]",
        t.steps - t.active_set_steps - t.matrix_free_steps,
        t.active_set_steps,
        t.matrix_free_steps,
        e(0),
        e(1),
        e(2)
    );
    for z in &s.zones {
        let f = |a: usize| z.final_force.get(a).copied().unwrap_or(0.0);
        out::outln!(
            "  zone `{}` ({}, {} candidates): final Σr_n {:.6e} ({} active = closed, {} within the alert distance), force [{:.6e}, {:.6e}, {:.6e}], max Σr_n {}",
            z.name,
            build::describe_laws(&z.laws, &z.law),
            z.candidates,
            z.final_force_n,
            z.final_active,
            z.final_within_alert,
            f(0),
            f(1),
            f(2),
            z.max_force_n
                .map(|p| format!("{:.6e} at step {} (t = {})", p.value, p.step, p.time))
                .unwrap_or_else(|| "-".into())
        );
    }
}

/// The work of a 2D run (the stages that ran), each zone's extremes and the plotted curves'.
fn print_plane_work<const D: usize>(s: &run::Summary<D>) {
    let c = &s.counters;
    let solver_steps = if c.steps != s.steps {
        format!(" ({} solver steps)", c.steps)
    } else {
        String::new()
    };
    out::outln!(
        "done: {} steps{solver_steps} in {:.3} s (t = {}), {} contact iterations",
        s.steps,
        s.wall_time_s,
        s.time,
        c.contact_iterations
    );
    let st = &s.stages;
    let adhesion = if st.adhesive_zones == 0 {
        " (no adhesive zone: the adhesion loop never ran)".to_string()
    } else {
        String::new()
    };
    out::outln!("  stages that ran:");
    out::outln!(
        "    adhesion iterations   {}{adhesion}",
        st.adhesion_iterations
    );
    if c.adhesion_factorizations > 0 {
        out::outln!(
            "    Newton Jacobians      {} (dense LU factorisations of the adhesive Newton)",
            c.adhesion_factorizations
        );
    }
    out::outln!(
        "    F* rebuilds           {} ({} columns)",
        c.flexibility_builds,
        c.flexibility_columns
    );
    out::outln!(
        "    stiffness changes     {} (refactorisations of K after the first)",
        c.stiffness_changes
    );
    out::outln!("    contact iterations    {}", c.contact_iterations);
    out::outln!("    structure solves      {}", c.structure_solves);
    let friction = if st.friction_zones == 0 {
        " (no zone with friction)".to_string()
    } else {
        String::new()
    };
    out::outln!(
        "    tangential reactions  in {} of {} steps{friction}",
        st.steps_with_tangential_reaction,
        s.steps
    );
    for z in &s.zones {
        let peak = |p: &Option<run::Peak>| {
            p.map(|p| format!("{:.6e} at step {} (t = {})", p.value, p.step, p.time))
                .unwrap_or_else(|| "-".into())
        };
        out::outln!(
            "  zone `{}` ({}, {} candidates): {} active = closed, {} within the alert distance at the end; max Σr_n {}, min Σr_n {}, max |Σr_t| {}{}",
            z.name,
            build::describe_laws(&z.laws, &z.law),
            z.candidates,
            z.final_active,
            z.final_within_alert,
            peak(&z.max_force_n),
            peak(&z.min_force_n),
            peak(&z.max_abs_force_t),
            z.min_beta
                .map(|b| format!(", min β {:.4} at step {}", b.value, b.step))
                .unwrap_or_default()
        );
    }
    for cv in &s.curves {
        if let (Some(lo), Some(hi)) = (cv.min, cv.max) {
            out::outln!(
                "  {}: min {:.6e} (step {}), max {:.6e} (step {})",
                cv.label,
                lo.value,
                lo.step,
                hi.value,
                hi.step
            );
        }
    }
}
