//! `summary.json`: what the run did (counters, stages, phases) and found (per-zone extremes and
//! final state, the plotted curves' extremes), and the tally of the zones kept step by step.

use super::errors::io;
use crate::build::PhaseLaw;
use crate::error::{CliError, CliResult};
use crate::scene::Units;
use contact_laws::ContactLaw;
use contact_solver::{ContactSimulation, Counters, InterfaceStatus, StepResult};
use fem_core::{LinearElasticModel, Structure};
use serde::Serialize;
use std::path::Path;

/// A value with where it happened.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Peak {
    /// Value.
    pub value: f64,
    /// Global step.
    pub step: usize,
    /// Time.
    pub time: f64,
}

pub(super) fn keep(p: &mut Option<Peak>, value: f64, step: usize, time: f64, larger: bool) {
    if !value.is_finite() {
        return;
    }
    let better = match p {
        None => true,
        Some(q) => (larger && value > q.value) || (!larger && value < q.value),
    };
    if better {
        *p = Some(Peak { value, step, time });
    }
}

/// Per-zone results.
#[derive(Clone, Debug, Serialize)]
pub struct ZoneSummary {
    /// Name.
    pub name: String,
    /// The law in force at the end of the run (`[[phases]] laws` may have changed it; `laws`
    /// lists them).
    pub law: String,
    /// Candidates.
    pub candidates: usize,
    /// Largest Σ r_n (compression).
    pub max_force_n: Option<Peak>,
    /// Smallest Σ r_n (tension when negative).
    pub min_force_n: Option<Peak>,
    /// Largest |Σ r_t|.
    pub max_abs_force_t: Option<Peak>,
    /// Smallest β over the candidates.
    pub min_beta: Option<Peak>,
    /// Σ r_n at the end.
    pub final_force_n: f64,
    /// Σ r_t at the end.
    pub final_force_t: f64,
    /// Final statuses: inactive, open, stick, slip (laws with friction), closed
    /// (frictionless).
    pub final_status: StatusCount,
    /// Closed ("active") contacts at the end: the law's reaction is not zero (stick or slip).
    pub final_active: usize,
    /// Candidates of the reduced problem at the end (within the alert distance): closed or
    /// open.
    pub final_within_alert: usize,
    /// The law of each phase the run reached, with its global steps.
    pub laws: Vec<PhaseLaw>,
}

/// Status counts.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct StatusCount {
    /// Not in the reduced problem.
    pub inactive: usize,
    /// Open.
    pub open: usize,
    /// Stick.
    pub stick: usize,
    /// Slip.
    pub slip: usize,
    /// Closed under a frictionless law (neither sticking nor slipping).
    pub closed: usize,
}

/// Per-phase results.
#[derive(Clone, Debug, Serialize)]
pub struct PhaseSummary {
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
    /// Adhesion iterations.
    pub adhesion_iterations: usize,
    /// F* builds.
    pub flexibility_builds: usize,
    /// Stiffness changes.
    pub stiffness_changes: usize,
    /// Wall time.
    pub wall_time_s: f64,
}

/// Which stages of the step ran.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Stages {
    /// Zones whose law has adhesion.
    pub adhesive_zones: usize,
    /// Zones whose law has friction.
    pub friction_zones: usize,
    /// Adhesion fixed-point iterations (0: the adhesion loop was skipped).
    pub adhesion_iterations: usize,
    /// Steps whose contacts carried a tangential reaction.
    pub steps_with_tangential_reaction: usize,
    /// F* builds.
    pub flexibility_builds: usize,
    /// Refactorisations of K after the first (stiffness changes).
    pub stiffness_changes: usize,
    /// Contact iterations.
    pub contact_iterations: usize,
    /// Steps needing more than one penetration-check pass.
    pub steps_with_detection_passes: usize,
}

/// A curve's extremes.
#[derive(Clone, Debug, Serialize)]
pub struct CurveSummary {
    /// Plot file.
    pub plot: String,
    /// Label.
    pub label: String,
    /// Minimum.
    pub min: Option<Peak>,
    /// Maximum.
    pub max: Option<Peak>,
    /// Final value.
    pub last: Option<f64>,
}

/// `summary.json`.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// `bipo` version.
    pub bipo_version: &'static str,
    /// Scene file.
    pub scene: String,
    /// Title.
    pub title: String,
    /// Units note.
    pub units: BTreeUnits,
    /// `completed` or `failed`.
    pub status: String,
    /// The error when failed.
    pub error: Option<String>,
    /// Steps of the scene done (a preset's step may run several solver steps: see
    /// `counters.steps`).
    pub steps: usize,
    /// Final time.
    pub time: f64,
    /// Wall time of the run.
    pub wall_time_s: f64,
    /// Mesh facts.
    pub mesh: MeshFacts,
    /// The library's counters of the work done by this run (`contact_solver::Counters`).
    pub counters: Counters,
    /// Stages.
    pub stages: Stages,
    /// Phases.
    pub phases: Vec<PhaseSummary>,
    /// Zones.
    pub zones: Vec<ZoneSummary>,
    /// Plotted curves.
    pub curves: Vec<CurveSummary>,
    /// Files written (relative to the output directory).
    pub files: Vec<String>,
    /// Floating bodies: the rigid-body motion of each mode at the last step (as
    /// `rigid_motions.csv`); empty for supported bodies.
    pub rigid_motions: Vec<super::rigid::RigidMotionSummary>,
    /// The scene's warnings (e.g. contactor nodes held by a support, left out).
    pub warnings: Vec<String>,
}

/// Units note.
#[derive(Clone, Debug, Serialize, Default)]
pub struct BTreeUnits {
    /// Length.
    pub length: Option<String>,
    /// Force.
    pub force: Option<String>,
    /// Time.
    pub time: Option<String>,
    /// Stress.
    pub stress: Option<String>,
}

impl BTreeUnits {
    /// The scene's `[units]`.
    pub(super) fn of(u: &Units) -> Self {
        Self {
            length: u.length.clone(),
            force: u.force.clone(),
            time: u.time.clone(),
            stress: u.stress.clone(),
        }
    }
}

/// A run's status: "failed" when it stopped on `error`, else "completed".
pub(super) fn status(error: Option<&CliError>) -> String {
    if error.is_some() {
        "failed"
    } else {
        "completed"
    }
    .into()
}

/// Mesh facts.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct MeshFacts {
    /// Nodes.
    pub nodes: usize,
    /// Elements.
    pub elements: usize,
    /// Free dofs at the start.
    pub free_dofs: usize,
    /// Contact candidates.
    pub candidates: usize,
}

/// What the summary keeps of each step: the zones' extremes and final state, and how many
/// steps carried a tangential reaction or needed several penetration-check passes.
pub(super) struct Tally {
    /// Per-zone results so far.
    pub(super) zones: Vec<ZoneSummary>,
    /// Steps whose contacts carried a tangential reaction.
    pub(super) tangential_steps: usize,
    /// Steps needing more than one penetration-check pass.
    pub(super) detection_steps: usize,
}

impl Tally {
    /// No step yet: one empty summary per zone.
    pub(super) fn new(names: &[String], laws: &[String], candidates: &[usize]) -> Self {
        let zones = names
            .iter()
            .enumerate()
            .map(|(z, name)| ZoneSummary {
                name: name.clone(),
                law: laws[z].clone(),
                candidates: candidates[z],
                max_force_n: None,
                min_force_n: None,
                max_abs_force_t: None,
                min_beta: None,
                final_force_n: 0.0,
                final_force_t: 0.0,
                final_status: StatusCount::default(),
                final_active: 0,
                final_within_alert: 0,
                laws: Vec::new(),
            })
            .collect();
        Self {
            zones,
            tangential_steps: 0,
            detection_steps: 0,
        }
    }

    /// Adds global step `global`.
    pub(super) fn record(&mut self, res: &StepResult, global: usize) {
        let rep = &res.report;
        let t = rep.time;
        if res.contacts.iter().any(|c| c.r.t[0] != 0.0) {
            self.tangential_steps += 1;
        }
        if rep.detection_passes > 1 {
            self.detection_steps += 1;
        }
        for (z, zs) in self.zones.iter_mut().enumerate() {
            let mine = res.contacts.iter().filter(|c| c.zone == z);
            let (mut fn_, mut ft, mut bmin) = (0.0, 0.0, f64::INFINITY);
            let mut st = StatusCount::default();
            let (mut closed, mut within) = (0, 0);
            for c in mine {
                closed += usize::from(c.status.is_closed());
                within += usize::from(c.status != InterfaceStatus::Inactive);
                fn_ += c.r.n;
                ft += c.r.t[0];
                bmin = bmin.min(c.beta);
                match c.status {
                    InterfaceStatus::Inactive => st.inactive += 1,
                    InterfaceStatus::Open => st.open += 1,
                    InterfaceStatus::Stick => st.stick += 1,
                    InterfaceStatus::Slip => st.slip += 1,
                    InterfaceStatus::Closed => st.closed += 1,
                    // a status the library adds later has no column yet
                    _ => {}
                }
            }
            keep(&mut zs.max_force_n, fn_, global, t, true);
            keep(&mut zs.min_force_n, fn_, global, t, false);
            keep(&mut zs.max_abs_force_t, ft.abs(), global, t, true);
            if zs.law == "rccm" {
                keep(&mut zs.min_beta, bmin, global, t, false);
            }
            zs.final_force_n = fn_;
            zs.final_force_t = ft;
            zs.final_status = st;
            zs.final_active = closed;
            zs.final_within_alert = within;
        }
    }
}

/// Writes `summary.json` (pretty-printed, with a final newline).
pub(super) fn write(path: &Path, summary: &Summary) -> CliResult<()> {
    let text = serde_json::to_string_pretty(summary).map_err(|e| io(path, e))?;
    std::fs::write(path, text + "\n").map_err(|e| io(path, e))
}

/// The work done since `start` (a preset's builder may have stepped already, e.g. to calibrate).
///
/// `Counters` is `#[non_exhaustive]`, so it cannot be built here with a struct expression, and
/// the library has no difference of two counters: the difference is taken field by field on a
/// copy of `now` (its fields are public). A field the library adds later must be added here,
/// or it is reported since the start of the simulation rather than of the run.
pub(super) fn since(now: Counters, start: Counters) -> Counters {
    let mut d = now;
    d.steps -= start.steps;
    d.flexibility_builds -= start.flexibility_builds;
    d.flexibility_columns -= start.flexibility_columns;
    d.structure_solves -= start.structure_solves;
    d.adhesion_iterations -= start.adhesion_iterations;
    d.contact_iterations -= start.contact_iterations;
    d.stiffness_changes -= start.stiffness_changes;
    d.matrix_free_steps -= start.matrix_free_steps;
    d.operator_applications -= start.operator_applications;
    d.active_set_steps -= start.active_set_steps;
    d.active_set_factorizations -= start.active_set_factorizations;
    d.active_set_solves -= start.active_set_solves;
    d.active_set_inner_iterations -= start.active_set_inner_iterations;
    d.active_set_fallbacks -= start.active_set_fallbacks;
    d
}

pub(super) fn facts<L: ContactLaw + Clone>(
    sim: &ContactSimulation<LinearElasticModel, L>,
) -> MeshFacts {
    let m = sim.structure();
    MeshFacts {
        nodes: m.mesh().node_count(),
        elements: m.mesh().element_count(),
        free_dofs: m.dof_count(),
        candidates: sim.candidates().len(),
    }
}
