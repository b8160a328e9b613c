//! `bipo run`: steps a [`Study`] (2D or 3D) phase by phase with a progress bar, writes the CSV
//! histories, the VTK series, the plots and `summary.json`, and prints what work was done.
//!
//! One file per output: [`csv`] (`contacts.csv`, `steps.csv` of a 2D run), [`vtk`] (its
//! interface and mesh series), [`plots`] (`curves.csv` and the SVGs), [`pressure`]
//! (`pressure.csv` and the Hertz plot of the recovered pressure field), [`summary`]
//! (`summary.json`) and [`progress`] (the bar and the phase lines); the [`recorder`] hands each
//! step to them, and a [`driver`] steps the study (a scene described key by key or a 2D library
//! preset). The run is written once over the dimension; the formats that differ by dimension
//! are [`dim::RunDim`]'s ([`plane`] and [`solid`]).

mod csv;
mod dim;
mod driver;
mod dynamic;
mod errors;
mod pieces;
mod plane;
mod plastic;
mod plots;
mod pressure;
mod profiles;
mod progress;
mod recorder;
mod rigid;
mod solid;
mod summary;
mod vtk;

pub use dynamic::run_dynamic;
pub use pieces::Pieces;
pub(crate) use plastic::PlasticRunDim;
pub use plastic::run_plastic;
pub use summary::{Peak, StepTotals, Summary};

use crate::build::{self, Body, Phase, Study, StudyDim, on_sim};
use crate::error::{CliError, CliResult};
use dim::{RunDim, StepRow};
use driver::{CustomDriver, Driver, PresetDriver};
use fem_core::Dim;
use progress::Progress;
use recorder::Recorder;
use std::path::PathBuf;
use std::time::Instant;
use summary::{PhaseSummary, Stages, facts, since, status};

pub struct RunOptions {
    /// Output directory.
    pub out_dir: PathBuf,
    /// No progress bar and no per-phase lines.
    pub quiet: bool,
    /// The scene file (for the summary).
    pub scene_file: PathBuf,
    /// A distributed run's parallel VTK pieces of this rank (`None`: one `.vtu` per step).
    pub pieces: Option<Pieces>,
}

impl RunOptions {
    /// The options of `bipo run` on `scene`: the output directory is `out` (the command line),
    /// else the scene's `[output] dir`, else `out/<scene stem>`.
    pub fn new(
        out: Option<PathBuf>,
        scene_dir: Option<&str>,
        scene: &std::path::Path,
        quiet: bool,
    ) -> Self {
        let out_dir = out
            .or_else(|| scene_dir.map(PathBuf::from))
            .unwrap_or_else(|| {
                let stem = scene.file_stem().map(|s| s.to_string_lossy().into_owned());
                PathBuf::from("out").join(stem.unwrap_or_else(|| "scene".into()))
            });
        Self {
            out_dir,
            quiet,
            scene_file: scene.to_path_buf(),
            pieces: None,
        }
    }
}

/// How a dimension's run steps its presets (2D: the library's seed studies, by their driver;
/// 3D has none).
pub(crate) trait Drive<const D: usize>: RunDim<D>
where
    Dim<D>: RunDim<D>,
{
    /// Steps every phase of a preset (see [`drive`]).
    fn drive_preset(
        p: &mut <Self as StudyDim<D>>::Preset,
        run: (&[Phase], usize, &RunOptions),
        rec: &mut Recorder<D>,
    ) -> (Vec<PhaseSummary<D>>, Option<CliError>, StepTotals);
}

impl Drive<2> for Dim<2> {
    fn drive_preset(
        p: &mut build::PresetStudy,
        run: (&[Phase], usize, &RunOptions),
        rec: &mut Recorder<2>,
    ) -> (Vec<PhaseSummary>, Option<CliError>, StepTotals) {
        drive(&mut PresetDriver::new(p), run, rec)
    }
}

impl Drive<3> for Dim<3> {
    fn drive_preset(
        p: &mut build::NoPreset,
        _: (&[Phase], usize, &RunOptions),
        _: &mut Recorder<3>,
    ) -> (Vec<PhaseSummary<3>>, Option<CliError>, StepTotals) {
        match *p {}
    }
}

/// Runs the study; returns the summary (also written to `summary.json`).
pub fn run<const D: usize>(mut study: Study<D>, opts: &RunOptions) -> CliResult<Summary<D>>
where
    Dim<D>: Drive<D>,
{
    let mut recorder = Recorder::new(&study, &opts.out_dir, opts.pieces.clone())?;
    let start = Instant::now();
    let total = study.total_steps();
    let at_start = on_sim!(study, s => s.counters());
    let run = (&study.phases[..], total, opts);
    let (phases, error, totals) = match &mut study.body {
        Body::Custom(c) => drive(&mut CustomDriver::new(c), run, &mut recorder),
        Body::Preset(p) => Dim::<D>::drive_preset(p, run, &mut recorder),
    };
    let wall = start.elapsed().as_secs_f64();
    let (tangential, detection) = recorder.stage_counts();
    let steps_done = recorder.steps();
    let final_reaction = recorder.reaction();
    let recorder::Finished {
        mut files,
        curves,
        mut zones,
        rigid,
    } = recorder.finish(&study)?;
    let laws = build::laws_by_phase(
        &study.phases,
        &study.zone_names,
        &study.zone_laws,
        &study.phase_law_names(),
        steps_done,
        error.is_some(),
    );
    for (z, laws) in zones.iter_mut().zip(laws) {
        z.law = build::final_law(&laws, &z.law);
        z.laws = laws;
    }
    let (counters, time, facts) = on_sim!(study, s => (s.counters(), s.time(), facts(s)));
    files.insert(0, "summary.json".into());
    let counters = since(counters, at_start);
    let summary = Summary {
        bipo_version: env!("CARGO_PKG_VERSION"),
        scene: opts.scene_file.display().to_string(),
        title: study.title.clone(),
        units: study.units.clone(),
        status: status(error.as_ref()),
        error: error.as_ref().map(|e| e.message.clone()),
        steps: steps_done,
        time,
        wall_time_s: wall,
        mesh: facts,
        counters,
        totals,
        final_reaction,
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

/// Steps every phase of `phases` with `d`, recording each step; returns the phases done, the
/// error that stopped the run, if any, and the steps' reports summed.
fn drive<const D: usize, Dr: Driver<D>>(
    d: &mut Dr,
    (phases, total, opts): (&[Phase], usize, &RunOptions),
    rec: &mut Recorder<D>,
) -> (Vec<PhaseSummary<D>>, Option<CliError>, StepTotals)
where
    Dim<D>: RunDim<D>,
{
    let progress = Progress::new(total, opts.quiet);
    let mut out: Vec<PhaseSummary<D>> = Vec::new();
    let mut totals = StepTotals::default();
    let mut global = 0;
    for (pi, phase) in phases.iter().enumerate() {
        progress.begin_phase(&phase.name);
        let (before, mut phase_totals) = (d.sim().counters(), StepTotals::default());
        let t_phase = Instant::now();
        let fail = |out: &mut Vec<PhaseSummary<D>>, e: CliError, totals: StepTotals| {
            progress.finish();
            (std::mem::take(out), Some(e), totals)
        };
        if let Err(e) = d.begin_phase(phases, pi) {
            return fail(&mut out, e, totals);
        }
        for k in 1..=phase.steps {
            let t = phase.time(k);
            let t_step = Instant::now();
            // K's factorisations: its changes, and its refactorisations after a 3D active
            // set freed its factor (`Counters::structure_refactorizations`)
            let k_of = |d: &Dr| {
                d.sim().structure().factorizations() + d.sim().counters().structure_refactorizations
            };
            let k0 = k_of(d);
            let a0 = d.sim().counters().active_set_factorizations;
            let res = match d.step(phases, pi, k, t) {
                Ok(r) => r,
                Err(mut e) => {
                    e.message = format!("step {} ({e_msg})", global + 1, e_msg = e.message);
                    return fail(&mut out, e, totals);
                }
            };
            global += 1;
            let k_step = k_of(d) - k0;
            let a_step = d.sim().counters().active_set_factorizations - a0;
            totals.add(&res.report, k_step, a_step);
            phase_totals.add(&res.report, k_step, a_step);
            let row = StepRow {
                step: global,
                phase: &phase.name,
                time: t,
                wall_time_s: t_step.elapsed().as_secs_f64(),
                factorizations: k_step + a_step,
                extras: d.extras(),
            };
            if let Err(e) = rec.record(d.sim(), &res, &row, k == phase.steps) {
                return fail(&mut out, e, totals);
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
        let s = PhaseSummary {
            name: phase.name.clone(),
            steps: phase.steps,
            t_start: phase.t0,
            t_end: phase.t1,
            counters: since(d.sim().counters(), before),
            totals: phase_totals,
            wall_time_s: t_phase.elapsed().as_secs_f64(),
        };
        progress.end_phase(&s);
        out.push(s);
    }
    progress.finish();
    (out, None, totals)
}
