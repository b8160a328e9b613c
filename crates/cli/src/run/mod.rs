//! `bipo run`: steps a [`Study`] phase by phase with a progress bar, writes the CSV histories,
//! the VTK series, the plots and `summary.json`, and prints what work was done.
//!
//! One file per output: [`csv`] (`contacts.csv`, `steps.csv`), [`vtk`] (the interface and mesh
//! series), [`plots`] (`curves.csv` and the SVGs), [`pressure`] (`pressure.csv` and the Hertz
//! plot of the recovered pressure field), [`summary`] (`summary.json`) and
//! [`progress`] (the bar and the phase lines); the [`recorder`] hands each step to them, and a
//! [`driver`] steps the study (a scene described key by key or a library preset). A 3D study
//! runs through [`solid`] (its own driver and outputs; the bar and the error hints are shared).

mod csv;
mod driver;
mod errors;
mod plots;
mod pressure;
mod profiles;
mod progress;
mod recorder;
mod rigid;
mod solid;
mod summary;
mod vtk;

pub use solid::{SolidSummary, run_solid};
pub use summary::{Peak, Summary};

use crate::build::{self, Body, Phase, Study};
use crate::error::{CliError, CliResult};
use driver::{CustomDriver, Driver, PresetDriver};
use progress::Progress;
use recorder::Recorder;
use std::path::PathBuf;
use std::time::Instant;
use summary::{BTreeUnits, PhaseSummary, Stages, facts, since, status};

/// Options of `bipo run`.
pub struct RunOptions {
    /// Output directory.
    pub out_dir: PathBuf,
    /// No progress bar and no per-phase lines.
    pub quiet: bool,
    /// The scene file (for the summary).
    pub scene_file: PathBuf,
}

/// Runs the study; returns the summary (also written to `summary.json`).
pub fn run(mut study: Study, opts: &RunOptions) -> CliResult<Summary> {
    let mut recorder = Recorder::new(&study, &opts.out_dir)?;
    let start = Instant::now();
    let total = study.total_steps();
    let at_start = match &study.body {
        Body::Custom(c) => c.sim.counters(),
        Body::Preset(p) => p.sim().counters(),
    };
    let outcome = match &mut study.body {
        Body::Custom(c) => {
            let mut d = CustomDriver::new(c);
            drive(&mut d, &study.phases, total, &mut recorder, opts)
        }
        Body::Preset(p) => {
            let mut d = PresetDriver::new(p);
            drive(&mut d, &study.phases, total, &mut recorder, opts)
        }
    };
    let wall = start.elapsed().as_secs_f64();
    let (phases, error) = outcome;
    let (tangential, detection) = recorder.stage_counts();
    let steps_done = recorder.steps();
    let recorder::Finished {
        mut files,
        curves,
        mut zones,
        rigid,
    } = recorder.finish(&study)?;
    let set = match &study.body {
        Body::Custom(c) => build::phase_law_names(&c.phase_laws),
        Body::Preset(_) => Vec::new(),
    };
    let laws = build::laws_by_phase(
        &study.phases,
        &study.zone_names,
        &study.zone_laws,
        &set,
        steps_done,
        error.is_some(),
    );
    for (z, laws) in zones.iter_mut().zip(laws) {
        z.law = build::final_law(&laws, &z.law);
        z.laws = laws;
    }
    let (counters, time, facts) = match &study.body {
        Body::Custom(c) => (c.sim.counters(), c.sim.time(), facts(&c.sim)),
        Body::Preset(p) => (p.sim().counters(), p.sim().time(), facts(p.sim())),
    };
    files.insert(0, "summary.json".into());
    let counters = since(counters, at_start);
    let summary = Summary {
        bipo_version: env!("CARGO_PKG_VERSION"),
        scene: opts.scene_file.display().to_string(),
        title: study.title.clone(),
        units: BTreeUnits::of(&study.units),
        status: status(error.as_ref()),
        error: error.as_ref().map(|e| e.message.clone()),
        steps: steps_done,
        time,
        wall_time_s: wall,
        mesh: facts,
        counters,
        stages: Stages {
            adhesive_zones: study.adhesive_zones,
            friction_zones: study.friction_zones,
            adhesion_iterations: counters.adhesion_iterations,
            steps_with_tangential_reaction: tangential,
            flexibility_builds: counters.flexibility_builds,
            stiffness_changes: counters.stiffness_changes,
            contact_iterations: counters.contact_iterations,
            steps_with_detection_passes: detection,
        },
        phases,
        zones,
        curves,
        files,
        rigid_motions: rigid,
        warnings: study.warnings.clone(),
    };
    summary::write(&opts.out_dir.join("summary.json"), &summary)?;
    match error {
        Some(e) => Err(e),
        None => Ok(summary),
    }
}

/// Steps every phase of `phases` with `d`, recording each step; returns the phases done and the
/// error that stopped the run, if any.
fn drive<D: Driver>(
    d: &mut D,
    phases: &[Phase],
    total: usize,
    rec: &mut Recorder,
    opts: &RunOptions,
) -> (Vec<PhaseSummary>, Option<CliError>) {
    let progress = Progress::new(total, opts.quiet);
    let mut out: Vec<PhaseSummary> = Vec::new();
    let mut global = 0;
    for (pi, phase) in phases.iter().enumerate() {
        progress.begin_phase(&phase.name);
        let before = d.sim().counters();
        let t_phase = Instant::now();
        let fail = |out: &mut Vec<PhaseSummary>, e: CliError| {
            progress.finish();
            (std::mem::take(out), Some(e))
        };
        if let Err(e) = d.begin_phase(phases, pi) {
            return fail(&mut out, e);
        }
        for k in 1..=phase.steps {
            let t = phase.time(k);
            let res = match d.step(phases, pi, k, t) {
                Ok(r) => r,
                Err(mut e) => {
                    e.message = format!("step {} ({e_msg})", global + 1, e_msg = e.message);
                    return fail(&mut out, e);
                }
            };
            global += 1;
            if let Err(e) = rec.record(d.sim(), &res, d.extras(), global, k == phase.steps) {
                return fail(&mut out, e);
            }
            if let Some(points) = d.profile(&res) {
                let q = d.extras().head_load.unwrap_or(f64::NAN);
                rec.profile(global, t, pi, q, points);
            }
            progress.step(
                t,
                res.report.contact_iterations,
                progress::path_name(&res.report),
            );
        }
        d.end_phase(phases, pi);
        let after = d.sim().counters();
        let s = PhaseSummary {
            name: phase.name.clone(),
            steps: phase.steps,
            t_start: phase.t0,
            t_end: phase.t1,
            contact_iterations: after.contact_iterations - before.contact_iterations,
            adhesion_iterations: after.adhesion_iterations - before.adhesion_iterations,
            flexibility_builds: after.flexibility_builds - before.flexibility_builds,
            stiffness_changes: after.stiffness_changes - before.stiffness_changes,
            wall_time_s: t_phase.elapsed().as_secs_f64(),
        };
        progress.end_phase(&s);
        out.push(s);
    }
    progress.finish();
    (out, None)
}
