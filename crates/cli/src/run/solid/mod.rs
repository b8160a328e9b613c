//! `bipo run` of a 3D scene: each phase's steps (supports set to their values at the step's
//! time, loads scaled by their functions), each step recorded ([`output`]), and `summary.json`.

mod output;

pub use output::SolidZoneSummary;

use super::RunOptions;
use super::driver::apply_step;
use super::errors::{fem_failed, io, step_error};
use super::progress::Progress;
use super::summary::{BTreeUnits, CurveSummary, MeshFacts, status};
use crate::build::{Phase, SolidStudy, released_at};
use crate::error::{CliError, CliResult};
use fem_core::Structure;
use output::{SolidRecorder, StepRow};
use serde::Serialize;
use std::time::Instant;

/// One phase of a 3D run.
#[derive(Clone, Debug, Serialize)]
pub struct SolidPhaseSummary {
    /// Name.
    pub name: String,
    /// Steps.
    pub steps: usize,
    /// Start time.
    pub t_start: f64,
    /// End time.
    pub t_end: f64,
    /// Contact iterations.
    pub contact_iterations: usize,
    /// Active-set passes.
    pub passes: usize,
    /// Adhesion fixed-point iterations.
    pub adhesion_iterations: usize,
    /// Numeric factorisations (of K, and of the active set's constrained stiffness).
    pub factorizations: usize,
    /// Wall time.
    pub wall_time_s: f64,
}

/// The work a 3D run did, named as 2D's `contact_solver::Counters` where the two share a
/// meaning.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct SolidCounters {
    /// Steps done.
    pub steps: usize,
    /// Contact (solver) iterations.
    pub contact_iterations: usize,
    /// Adhesion fixed-point iterations.
    pub adhesion_iterations: usize,
    /// Passes of the penetration check (2D: `detection_passes` summed).
    pub passes: usize,
    /// Refactorisations of K (a support released, a stiffness change).
    pub stiffness_factorizations: usize,
    /// Steps solved matrix-free (no `F*`).
    pub matrix_free_steps: usize,
    /// Steps solved by the primal active-set iteration (no `F*`).
    pub active_set_steps: usize,
    /// Numeric factorisations of the constrained stiffness by the active-set iteration.
    pub active_set_factorizations: usize,
}

/// `summary.json` of a 3D run.
#[derive(Clone, Debug, Serialize)]
pub struct SolidSummary {
    /// `bipo` version.
    pub bipo_version: &'static str,
    /// Scene file.
    pub scene: String,
    /// Title.
    pub title: String,
    /// Always 3.
    pub dimension: usize,
    /// Units note.
    pub units: BTreeUnits,
    /// `completed` or `failed`.
    pub status: String,
    /// The error when failed.
    pub error: Option<String>,
    /// Steps done.
    pub steps: usize,
    /// Final time.
    pub time: f64,
    /// Wall time of the run.
    pub wall_time_s: f64,
    /// Mesh facts.
    pub mesh: MeshFacts,
    /// Contact iterations over the run.
    pub contact_iterations: usize,
    /// Active-set passes over the run.
    pub passes: usize,
    /// Numeric factorisations over the run: of K and of the active set's constrained stiffness
    /// (`counters` splits them).
    pub factorizations: usize,
    /// The work done, counter by counter.
    pub counters: SolidCounters,
    /// Sum of the support reactions at the last step, global axes: with the applied loads and
    /// the contact forces on the body it balances.
    pub final_reaction: [f64; 3],
    /// Phases.
    pub phases: Vec<SolidPhaseSummary>,
    /// Zones.
    pub zones: Vec<SolidZoneSummary>,
    /// Files written (relative to the output directory).
    pub files: Vec<String>,
    /// The scene's warnings (e.g. contactor nodes held by a support, left out).
    pub warnings: Vec<String>,
    /// The `[[plots]]` curves: each one's least, largest and last value, as 2D's.
    pub curves: Vec<CurveSummary>,
}

/// Sets the laws phase `p` gives its zones (the interface states carry over), then releases the
/// supports that end with the phase before.
fn begin_phase(study: &mut SolidStudy, p: usize) -> CliResult<()> {
    for (zone, law) in study.phase_laws.get(p).into_iter().flatten() {
        study.sim.set_law(zone, *law).map_err(|e| {
            CliError::failed(format!(
                "phase `{}`: setting the law of zone `{zone}`: {e}",
                study.phases[p].name
            ))
        })?;
    }
    release_ending(study, p)
}

/// Releases, when phase `p > 0` starts, the supports that acted in the phase before and not in
/// this one ([`released_at`]; the simulation follows the new dof numbering at its next step).
fn release_ending(study: &mut SolidStudy, p: usize) -> CliResult<()> {
    if p == 0 {
        return Ok(());
    }
    let model = study.sim.structure_mut();
    for (nodes, c) in released_at(&study.supports, p) {
        model.release(&nodes, c).map_err(|e| {
            fem_failed(
                &format!(
                    "phase `{}`: releasing the supports that end",
                    study.phases[p].name
                ),
                e,
            )
        })?;
    }
    Ok(())
}

/// Whether global step `global` (the last of its phase when `last`) is written.
fn written(study: &SolidStudy, global: usize, last: bool) -> bool {
    match &study.output.steps {
        Some(list) => list.contains(&global),
        None => global.is_multiple_of(study.output.every.max(1)) || last,
    }
}

/// Steps every phase, recording each step; returns the phases done and the error that stopped
/// the run, if any.
fn drive(
    study: &mut SolidStudy,
    rec: &mut SolidRecorder,
    progress: &Progress,
    time: &mut f64,
    global: &mut usize,
    counters: &mut SolidCounters,
) -> (Vec<SolidPhaseSummary>, Option<CliError>) {
    let mut out = Vec::new();
    let mut last_loads = None;
    for p in 0..study.phases.len() {
        let phase: Phase = study.phases[p].clone();
        progress.begin_phase(&phase.name);
        if let Err(e) = begin_phase(study, p) {
            return (out, Some(e));
        }
        let t_phase = Instant::now();
        let (mut iterations, mut passes, mut adhesion, mut factorizations) = (0, 0, 0, 0);
        for k in 1..=phase.steps {
            let t = phase.time(k);
            let t_step = Instant::now();
            let k0 = study.sim.structure().factorizations();
            let a0 = study.sim.counters().active_set_factorizations;
            let model = study.sim.structure_mut();
            let (supports, loads, functions) = (&study.supports, &study.loads, &study.functions);
            let res = apply_step(
                model,
                supports,
                loads,
                functions,
                (&phase, p),
                t,
                &mut last_loads,
            );
            let res = res.and_then(|()| {
                let at = t.max(study.sim.time());
                study
                    .sim
                    .step(at, 1.0)
                    .map_err(|e| step_error(e, &phase, t))
            });
            let res = match res {
                Ok(r) => r,
                Err(mut e) => {
                    e.message = format!("step {} ({})", *global + 1, e.message);
                    return (out, Some(e));
                }
            };
            *global += 1;
            *time = t;
            let r = &res.report;
            iterations += r.contact_iterations;
            passes += r.detection_passes;
            adhesion += r.adhesion_iterations;
            let k_step = study.sim.structure().factorizations() - k0;
            let a_step = study.sim.counters().active_set_factorizations - a0;
            factorizations += k_step + a_step;
            counters.steps += 1;
            counters.contact_iterations += r.contact_iterations;
            counters.adhesion_iterations += r.adhesion_iterations;
            counters.passes += r.detection_passes;
            counters.stiffness_factorizations += k_step;
            counters.matrix_free_steps += usize::from(r.matrix_free);
            counters.active_set_steps += usize::from(r.active_set);
            counters.active_set_factorizations += a_step;
            let row = StepRow {
                step: *global,
                phase: &phase.name,
                time: t,
                wall_time_s: t_step.elapsed().as_secs_f64(),
                factorizations: k_step + a_step,
            };
            let write = written(study, *global, k == phase.steps);
            if let Err(e) = rec.record(&study.sim, &res, &row, write) {
                return (out, Some(e));
            }
            progress.step(t, res.report.contact_iterations, path_name(&res));
        }
        if phase.reset_displacements {
            study.sim.reset_displacements();
        }
        let s = SolidPhaseSummary {
            name: phase.name.clone(),
            steps: phase.steps,
            t_start: phase.t0,
            t_end: phase.t1,
            contact_iterations: iterations,
            passes,
            adhesion_iterations: adhesion,
            factorizations,
            wall_time_s: t_phase.elapsed().as_secs_f64(),
        };
        progress.line(&format!(
            "phase `{}`: {} steps, t {} → {}: {} contact iterations, {} adhesion iterations, {} \
             active-set passes, {} factorisations, {:.3} s",
            s.name,
            s.steps,
            s.t_start,
            s.t_end,
            s.contact_iterations,
            s.adhesion_iterations,
            s.passes,
            s.factorizations,
            s.wall_time_s
        ));
        out.push(s);
    }
    (out, None)
}

/// How a step was solved, for the progress lines.
fn path_name(res: &contact_solver::coupling::solid::SolidStepResult) -> &'static str {
    if res.report.active_set {
        "active set"
    } else if res.report.matrix_free {
        "matrix-free"
    } else {
        "dense"
    }
}

/// Runs a 3D study; returns the summary (also written to `summary.json`).
pub fn run_solid(mut study: SolidStudy, opts: &RunOptions) -> CliResult<SolidSummary> {
    let mut rec = SolidRecorder::new(&opts.out_dir, &study)?;
    let start = Instant::now();
    let progress = Progress::new(study.total_steps(), opts.quiet);
    let (mut time, mut steps) = (0.0, 0);
    let mut counters = SolidCounters::default();
    let (phases, error) = drive(
        &mut study,
        &mut rec,
        &progress,
        &mut time,
        &mut steps,
        &mut counters,
    );
    progress.finish();
    let final_reaction = rec.reaction;
    let (mut files, mut zones, curves) = rec.finish(study.sim.structure().mesh().nodes())?;
    let laws = crate::build::laws_by_phase(
        &study.phases,
        &study.zone_names,
        &study.zone_laws,
        &crate::build::phase_law_names(&study.phase_laws),
        steps,
        error.is_some(),
    );
    for (z, laws) in zones.iter_mut().zip(laws) {
        z.law = crate::build::final_law(&laws, &z.law);
        z.laws = laws;
    }
    files.insert(0, "summary.json".into());
    let model = study.sim.structure();
    let summary = SolidSummary {
        bipo_version: env!("CARGO_PKG_VERSION"),
        scene: opts.scene_file.display().to_string(),
        title: study.title.clone(),
        dimension: 3,
        units: BTreeUnits::of(&study.units),
        status: status(error.as_ref()),
        error: error.as_ref().map(|e| e.message.clone()),
        steps,
        time,
        wall_time_s: start.elapsed().as_secs_f64(),
        mesh: MeshFacts {
            nodes: model.mesh().node_count(),
            elements: model.mesh().element_count(),
            free_dofs: model.dof_count(),
            candidates: study.sim.candidates().len(),
        },
        contact_iterations: phases.iter().map(|p| p.contact_iterations).sum(),
        passes: phases.iter().map(|p| p.passes).sum(),
        factorizations: counters.stiffness_factorizations + counters.active_set_factorizations,
        counters,
        final_reaction,
        phases,
        zones,
        files,
        warnings: study.warnings.clone(),
        curves,
    };
    let path = opts.out_dir.join("summary.json");
    let text = serde_json::to_string_pretty(&summary).map_err(|e| io(&path, e))?;
    std::fs::write(&path, text + "\n").map_err(|e| io(&path, e))?;
    match error {
        Some(e) => Err(e),
        None => Ok(summary),
    }
}
