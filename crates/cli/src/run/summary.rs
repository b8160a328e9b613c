//! `summary.json`: what the run did (counters, stages, phases) and found (per-zone extremes and
//! final state, the plotted curves' extremes), and the tally of the zones kept step by step.
//!
//! One summary for both dimensions; the keys written are each dimension's (the file is a
//! contract): a 2D summary shows the library's [`Counters`] and the [`Stages`], a 3D one the
//! steps' reports summed ([`StepTotals`]) and the support reactions.

use super::errors::io;
use crate::build::{PhaseLaw, StudyDim};
use crate::error::{CliError, CliResult};
use crate::scene::Units;
use contact_laws::ContactLaw;
use contact_solver::{ContactSimulation, Counters, InterfaceStatus, StepResult};
use fem_core::{Dim, ElasticModel, Structure};
use serde::Serialize;
use serde::ser::{SerializeStruct, Serializer};
use std::path::Path;

/// A value with where it happened.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Peak {
    /// Value.
    pub value: f64,
    /// Global step.
    pub step: usize,
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

/// Per-zone results (2D: the tangential extremes and the statuses; 3D: the total force).
#[derive(Clone, Debug)]
pub struct ZoneSummary<const D: usize = 2> {
    /// Name.
    pub name: String,
    /// The law in force at the end of the run (`[[phases]] laws` may have changed it; `laws`
    /// lists them).
    pub law: String,
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
    /// Σ r_t at the end (the first tangential component).
    pub final_force_t: f64,
    /// Σ of the contact forces (global axes) at the end.
    pub final_force: [f64; D],
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

#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct StatusCount {
    /// Not in the reduced problem.
    pub inactive: usize,
    pub open: usize,
    pub stick: usize,
    pub slip: usize,
    /// Closed under a frictionless law (neither sticking nor slipping).
    pub closed: usize,
}

impl<const D: usize> Serialize for ZoneSummary<D> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_struct("ZoneSummary", 13)?;
        m.serialize_field("name", &self.name)?;
        m.serialize_field("law", &self.law)?;
        m.serialize_field("candidates", &self.candidates)?;
        m.serialize_field("max_force_n", &self.max_force_n)?;
        if D == 2 {
            m.serialize_field("min_force_n", &self.min_force_n)?;
            m.serialize_field("max_abs_force_t", &self.max_abs_force_t)?;
            m.serialize_field("min_beta", &self.min_beta)?;
        }
        m.serialize_field("final_force_n", &self.final_force_n)?;
        if D == 2 {
            m.serialize_field("final_force_t", &self.final_force_t)?;
            m.serialize_field("final_status", &self.final_status)?;
        } else {
            m.serialize_field("final_force", &self.final_force[..])?;
        }
        m.serialize_field("final_active", &self.final_active)?;
        m.serialize_field("final_within_alert", &self.final_within_alert)?;
        m.serialize_field("laws", &self.laws)?;
        m.end()
    }
}

/// The steps' reports summed (a 3D summary's `counters`; a preset's step may run several
/// solver steps, which the library's [`Counters`] count).
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct StepTotals {
    pub steps: usize,
    /// Contact (solver) iterations.
    pub contact_iterations: usize,
    /// Adhesion fixed-point iterations.
    pub adhesion_iterations: usize,
    /// Passes of the penetration check.
    pub passes: usize,
    /// Numeric factorisations of K (a support released, a stiffness change).
    pub stiffness_factorizations: usize,
    /// Steps solved matrix-free (no `F*`).
    pub matrix_free_steps: usize,
    /// Steps solved by the primal active-set iteration (no `F*`).
    pub active_set_steps: usize,
    /// Numeric factorisations of the constrained stiffness by the active-set iteration.
    pub active_set_factorizations: usize,
    /// The path of the last step and why (`summary.json`'s `path` and `path_reason`).
    #[serde(skip)]
    pub path: Option<contact_solver::PathChoice>,
}

impl StepTotals {
    /// Adds a step of report `r`, with `k` factorisations of K and `a` by the active set.
    pub(super) fn add(&mut self, r: &contact_solver::StepReport, k: usize, a: usize) {
        self.steps += 1;
        self.contact_iterations += r.contact_iterations;
        self.adhesion_iterations += r.adhesion_iterations;
        self.passes += r.detection_passes;
        self.stiffness_factorizations += k;
        self.matrix_free_steps += usize::from(r.matrix_free);
        self.active_set_steps += usize::from(r.active_set);
        self.active_set_factorizations += a;
        self.path = Some(r.path);
    }

    /// Numeric factorisations, of K and by the active set.
    pub fn factorizations(&self) -> usize {
        self.stiffness_factorizations + self.active_set_factorizations
    }
}

/// Per-phase results: the library's counters over the phase (2D's keys) and the steps'
/// reports summed (3D's).
#[derive(Clone, Debug)]
pub struct PhaseSummary<const D: usize = 2> {
    /// Name.
    pub name: String,
    pub steps: usize,
    pub t_start: f64,
    pub t_end: f64,
    /// The library's counters over the phase.
    pub counters: Counters,
    /// The phase's steps' reports summed.
    pub totals: StepTotals,
    pub wall_time_s: f64,
}

impl<const D: usize> Serialize for PhaseSummary<D> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_struct("PhaseSummary", 9)?;
        m.serialize_field("name", &self.name)?;
        m.serialize_field("steps", &self.steps)?;
        m.serialize_field("t_start", &self.t_start)?;
        m.serialize_field("t_end", &self.t_end)?;
        if D == 2 {
            let c = &self.counters;
            m.serialize_field("contact_iterations", &c.contact_iterations)?;
            m.serialize_field("adhesion_iterations", &c.adhesion_iterations)?;
            m.serialize_field("flexibility_builds", &c.flexibility_builds)?;
            m.serialize_field("stiffness_changes", &c.stiffness_changes)?;
        } else {
            let t = &self.totals;
            m.serialize_field("contact_iterations", &t.contact_iterations)?;
            m.serialize_field("passes", &t.passes)?;
            m.serialize_field("adhesion_iterations", &t.adhesion_iterations)?;
            m.serialize_field("factorizations", &t.factorizations())?;
        }
        m.serialize_field("wall_time_s", &self.wall_time_s)?;
        m.end()
    }
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
    pub contact_iterations: usize,
    /// Steps needing more than one penetration-check pass.
    pub steps_with_detection_passes: usize,
}

/// A curve's extremes.
#[derive(Clone, Debug, Serialize)]
pub struct CurveSummary {
    pub plot: String,
    pub label: String,
    /// Minimum.
    pub min: Option<Peak>,
    /// Maximum.
    pub max: Option<Peak>,
    /// Final value.
    pub last: Option<f64>,
}

#[derive(Clone, Debug)]
pub struct Summary<const D: usize = 2> {
    pub bipo_version: &'static str,
    pub scene: String,
    pub title: String,
    pub units: Units,
    /// `completed` or `failed`.
    pub status: String,
    /// The error when failed.
    pub error: Option<String>,
    /// Steps of the scene done (a preset's step may run several solver steps: see
    /// `counters.steps`).
    pub steps: usize,
    pub time: f64,
    pub wall_time_s: f64,
    pub mesh: MeshFacts,
    /// The library's counters of the work done by this run (`contact_solver::Counters`).
    pub counters: Counters,
    /// The steps' reports summed.
    pub totals: StepTotals,
    /// The sum of the support reactions at the last step (global axes), where the run keeps
    /// it (3D: `steps.csv` has it per step).
    pub final_reaction: Option<[f64; D]>,
    pub stages: Stages,
    pub phases: Vec<PhaseSummary<D>>,
    pub zones: Vec<ZoneSummary<D>>,
    pub curves: Vec<CurveSummary>,
    /// Files written (relative to the output directory).
    pub files: Vec<String>,
    /// Floating bodies: the rigid-body motion of each mode at the last step (as
    /// `rigid_motions.csv`); empty for supported bodies.
    pub rigid_motions: Vec<super::rigid::RigidMotionSummary>,
    /// The scene's warnings (e.g. contactor nodes held by a support, left out).
    pub warnings: Vec<String>,
}

impl<const D: usize> Summary<D> {
    pub fn phase_contact_iterations(&self) -> usize {
        self.phases
            .iter()
            .map(|p| p.totals.contact_iterations)
            .sum()
    }

    /// Penetration-check passes of the phases done.
    pub fn phase_passes(&self) -> usize {
        self.phases.iter().map(|p| p.totals.passes).sum()
    }
}

impl<const D: usize> Serialize for Summary<D> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let plane = D == 2;
        let mut m = s.serialize_struct("Summary", 23)?;
        m.serialize_field("bipo_version", self.bipo_version)?;
        m.serialize_field("scene", &self.scene)?;
        m.serialize_field("title", &self.title)?;
        if !plane {
            m.serialize_field("dimension", &D)?;
        }
        m.serialize_field("units", &self.units)?;
        m.serialize_field("status", &self.status)?;
        m.serialize_field("error", &self.error)?;
        m.serialize_field("steps", &self.steps)?;
        m.serialize_field("time", &self.time)?;
        m.serialize_field("wall_time_s", &self.wall_time_s)?;
        m.serialize_field("mesh", &self.mesh)?;
        if plane {
            m.serialize_field("counters", &self.counters)?;
            m.serialize_field("stages", &self.stages)?;
        } else {
            m.serialize_field("contact_iterations", &self.phase_contact_iterations())?;
            m.serialize_field("passes", &self.phase_passes())?;
            m.serialize_field("factorizations", &self.totals.factorizations())?;
            m.serialize_field("counters", &self.totals)?;
            m.serialize_field(
                "final_reaction",
                &self.final_reaction.as_ref().map(|r| &r[..]),
            )?;
        }
        m.serialize_field("phases", &self.phases)?;
        m.serialize_field("zones", &self.zones)?;
        if plane {
            m.serialize_field("curves", &self.curves)?;
            m.serialize_field("files", &self.files)?;
            m.serialize_field("rigid_motions", &self.rigid_motions)?;
        } else {
            m.serialize_field("files", &self.files)?;
        }
        m.serialize_field("warnings", &self.warnings)?;
        if !plane {
            m.serialize_field("curves", &self.curves)?;
        }
        // issue 38: the path of the last step and why (the settings, or auto's rule), last so
        // that the keys before keep their order
        let path = self.totals.path;
        m.serialize_field("path", &path.map(|p| p.path.name()))?;
        m.serialize_field("path_reason", &path.map(|p| p.reason.to_string()))?;
        m.end()
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

#[derive(Clone, Copy, Debug, Serialize)]
pub struct MeshFacts {
    pub nodes: usize,
    pub elements: usize,
    /// Free dofs at the start.
    pub free_dofs: usize,
    pub candidates: usize,
}

/// What the summary keeps of each step: the zones' extremes and final state, and how many
/// steps carried a tangential reaction or needed several penetration-check passes.
pub(super) struct Tally<const D: usize> {
    /// Per-zone results so far.
    pub(super) zones: Vec<ZoneSummary<D>>,
    /// Steps whose contacts carried a tangential reaction.
    pub(super) tangential_steps: usize,
    /// Steps needing more than one penetration-check pass.
    pub(super) detection_steps: usize,
}

impl<const D: usize> Tally<D>
where
    Dim<D>: StudyDim<D>,
{
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
                final_force: [0.0; D],
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
    pub(super) fn record(&mut self, res: &StepResult<D>, global: usize) {
        let rep = &res.report;
        let t = rep.time;
        if res
            .contacts
            .iter()
            .any(|c| c.reaction()[1..].iter().any(|&r| r != 0.0))
        {
            self.tangential_steps += 1;
        }
        if rep.detection_passes > 1 {
            self.detection_steps += 1;
        }
        for (z, zs) in self.zones.iter_mut().enumerate() {
            let mine = res.contacts.iter().filter(|c| c.zone == z);
            let (mut fn_, mut ft, mut bmin) = (0.0, 0.0, f64::INFINITY);
            let mut force = [0.0; D];
            let mut st = StatusCount::default();
            let (mut closed, mut within) = (0, 0);
            for c in mine {
                closed += usize::from(c.is_closed());
                within += usize::from(c.is_active());
                let (r, f) = (c.reaction(), c.force());
                fn_ += r[0];
                ft += r[1];
                (0..D).for_each(|a| force[a] += f[a]);
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
            zs.final_force = force;
            zs.final_status = st;
            zs.final_active = closed;
            zs.final_within_alert = within;
        }
    }
}

/// Writes `summary.json` (pretty-printed, with a final newline).
pub(super) fn write<const D: usize>(path: &Path, summary: &Summary<D>) -> CliResult<()> {
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
    d.structure_refactorizations -= start.structure_refactorizations;
    d
}

pub(super) fn facts<const D: usize, L: ContactLaw + Clone>(
    sim: &ContactSimulation<ElasticModel<D>, L, D>,
) -> MeshFacts
where
    Dim<D>: StudyDim<D>,
{
    let m = sim.structure();
    MeshFacts {
        nodes: m.mesh().node_count(),
        elements: m.mesh().element_count(),
        free_dofs: m.dof_count(),
        candidates: sim.candidates().len(),
    }
}
