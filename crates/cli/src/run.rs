//! `bipo run`: steps a [`Study`] phase by phase with a progress bar, writes the CSV histories,
//! the VTK series, the plots and `summary.json`, and prints what work was done.

use crate::build::{Body, Custom, Library, LoadKind, Phase, PresetStudy, Study, function_value};
use crate::error::{CliError, CliResult};
use crate::plot;
use crate::scene::{CurveSpec, XAxis};
use contact_laws::ContactLaw;
use contact_solver::error::chain;
use contact_solver::{
    ContactRecord, ContactSimulation, Counters, InterfaceStatus, SolverError, StepResult,
};
use contact_solver::{HistoryWriter, InterfaceSeries, ReportWriter};
use fem_core::{Component, LinearElasticModel, Structure};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What steps the simulation: the scene-file driver or a library preset.
trait Driver {
    type Law: ContactLaw + Clone;
    fn sim(&self) -> &ContactSimulation<LinearElasticModel, Self::Law>;
    fn begin_phase(&mut self, phases: &[Phase], p: usize) -> CliResult<()>;
    fn step(
        &mut self,
        phases: &[Phase],
        p: usize,
        k: usize,
        t: f64,
    ) -> Result<StepResult, CliError>;
    fn end_phase(&mut self, phases: &[Phase], p: usize);
    /// Quantities only this driver knows (the pile's head load), at the last step.
    fn extras(&self) -> Extras {
        Extras::default()
    }
}

/// Quantities of the pile preset at the last step.
#[derive(Clone, Copy, Debug, Default)]
struct Extras {
    head_load: Option<f64>,
    head_displacement: Option<f64>,
}

struct CustomDriver<'a> {
    c: &'a mut Custom,
    last_loads: Option<Vec<f64>>,
}

fn fem_failed(what: &str, e: fem_core::FemError) -> CliError {
    CliError::failed(format!("{what}: {}", chain(&e)))
}

impl Driver for CustomDriver<'_> {
    type Law = contact_laws::StandardLaw;

    fn sim(&self) -> &ContactSimulation<LinearElasticModel, Self::Law> {
        &self.c.sim
    }

    fn begin_phase(&mut self, phases: &[Phase], p: usize) -> CliResult<()> {
        if p == 0 {
            return Ok(());
        }
        let c = &mut *self.c;
        let model = c.sim.structure_mut();
        let mut changed = false;
        for s in c
            .supports
            .iter()
            .filter(|s| s.phases[p - 1] && !s.phases[p])
        {
            for &comp in &s.components {
                model.release(&s.nodes, comp).map_err(|e| {
                    fem_failed(
                        &format!(
                            "phase `{}`: releasing the supports that end",
                            phases[p].name
                        ),
                        e,
                    )
                })?;
            }
            changed = true;
        }
        let t = phases[p].t0;
        for s in c
            .supports
            .iter()
            .filter(|s| s.phases[p] && (changed || !s.phases[p - 1]))
        {
            let v = s.value * function_value(&phases[p], &s.name, &s.function, &c.functions, t);
            for &comp in &s.components {
                model.set_prescribed(&s.nodes, comp, v).map_err(|e| {
                    fem_failed(
                        &format!("phase `{}`: applying the supports", phases[p].name),
                        e,
                    )
                })?;
            }
        }
        self.last_loads = None;
        Ok(())
    }

    fn step(
        &mut self,
        phases: &[Phase],
        p: usize,
        _k: usize,
        t: f64,
    ) -> Result<StepResult, CliError> {
        let c = &mut *self.c;
        let phase = &phases[p];
        let model = c.sim.structure_mut();
        for s in c.supports.iter().filter(|s| s.phases[p]) {
            let v = s.value * function_value(phase, &s.name, &s.function, &c.functions, t);
            for &comp in &s.components {
                model
                    .set_prescribed(&s.nodes, comp, v)
                    .map_err(|e| fem_failed("prescribed displacement", e))?;
            }
        }
        let factors: Vec<f64> = c
            .loads
            .iter()
            .map(|l| {
                if l.phases[p] {
                    function_value(phase, &l.name, &l.function, &c.functions, t)
                } else {
                    0.0
                }
            })
            .collect();
        if self.last_loads.as_ref() != Some(&factors) {
            model.clear_loads();
            for (l, &f) in c.loads.iter().zip(&factors) {
                if !l.phases[p] {
                    continue;
                }
                match &l.kind {
                    LoadKind::Traction(set, v) => {
                        let v = [v[0] * f, v[1] * f];
                        model.add_edge_traction(set, |_| v)
                    }
                    LoadKind::Nodal(nodes, v) => nodes
                        .iter()
                        .try_for_each(|&n| model.add_nodal_force(n, [v[0] * f, v[1] * f])),
                    LoadKind::Body(v) => {
                        let v = [v[0] * f, v[1] * f];
                        model.add_body_force(|_| v)
                    }
                    LoadKind::Gravity => model.add_self_weight(),
                }
                .map_err(|e| fem_failed("load", e))?;
            }
            self.last_loads = Some(factors);
        }
        c.sim.step(t, 1.0).map_err(|e| step_error(e, phase, t))
    }

    fn end_phase(&mut self, phases: &[Phase], p: usize) {
        if phases[p].reset_displacements {
            self.c.sim.reset_displacements();
        }
    }
}

struct PresetDriver<'a> {
    p: &'a mut PresetStudy,
    extras: Extras,
}

impl Driver for PresetDriver<'_> {
    type Law = contact_laws::Rccm;

    fn sim(&self) -> &ContactSimulation<LinearElasticModel, Self::Law> {
        self.p.sim()
    }

    fn begin_phase(&mut self, _: &[Phase], _: usize) -> CliResult<()> {
        Ok(())
    }

    fn step(
        &mut self,
        phases: &[Phase],
        p: usize,
        k: usize,
        t: f64,
    ) -> Result<StepResult, CliError> {
        let err = |e| step_error(e, &phases[p], t);
        match &mut self.p.scene {
            Library::Seed(s) => s.step(k).map_err(err),
            Library::Pile(s) => {
                let (res, v) = match p {
                    0 => (s.geostatic().map_err(err)?, 0.0),
                    1 => (s.install().map_err(err)?, 0.0),
                    _ => {
                        let r = s.pull(k).map_err(err)?;
                        (r.result, r.head_displacement)
                    }
                };
                self.extras = Extras {
                    head_load: Some(s.head_load(&res).map_err(err)?),
                    head_displacement: Some(v),
                };
                Ok(res)
            }
        }
    }

    fn end_phase(&mut self, _: &[Phase], _: usize) {}

    fn extras(&self) -> Extras {
        self.extras
    }
}

fn step_error(e: SolverError, phase: &Phase, t: f64) -> CliError {
    let hint = match &e {
        SolverError::NotConverged { .. } => {
            " — raise [solver] max_iterations or tol, or set accept_non_converged = true"
        }
        SolverError::AdhesionNotConverged { .. } => {
            " — raise [solver] max_adhesion_iterations or adhesion_tol, or take smaller steps"
        }
        _ => "",
    };
    CliError::failed(format!(
        "phase `{}` at t = {t}: {}{hint}",
        phase.name,
        chain(&e)
    ))
}

/// Options of `bipo run`.
pub struct RunOptions {
    /// Output directory.
    pub out_dir: PathBuf,
    /// No progress bar and no per-phase lines.
    pub quiet: bool,
    /// The scene file (for the summary).
    pub scene_file: PathBuf,
}

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

fn keep(p: &mut Option<Peak>, value: f64, step: usize, time: f64, larger: bool) {
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
    /// Law.
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
    /// Final statuses: inactive, open, stick, slip.
    pub final_status: StatusCount,
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

struct CurveRt {
    plot: usize,
    /// The abscissa of its plot rather than a curve.
    is_x: bool,
    label: String,
    spec: CurveSpec,
    zone: Option<usize>,
    set_nodes: Vec<usize>,
    values: Vec<f64>,
}

struct Recorder {
    dir: PathBuf,
    history: Option<HistoryWriter<BufWriter<File>>>,
    report: Option<ReportWriter<BufWriter<File>>>,
    interface: Option<InterfaceSeries>,
    mesh_entries: Option<Vec<(f64, String)>>,
    write_steps: WriteSteps,
    zones_filter: Option<Vec<usize>>,
    nodes_filter: Option<Vec<usize>>,
    curves: Vec<CurveRt>,
    x_time: Vec<f64>,
    x_step: Vec<f64>,
    x_load: Vec<f64>,
    zones: Vec<ZoneSummary>,
    tangential_steps: usize,
    detection_steps: usize,
    files: Vec<String>,
}

enum WriteSteps {
    Every(usize),
    List(Vec<usize>),
}

/// "cannot write `what`: " and the whole error chain (a `String` from the plotter is one link).
fn io(what: &Path, e: impl Into<Box<dyn std::error::Error + Send + Sync>>) -> CliError {
    let e: Box<dyn std::error::Error + Send + Sync> = e.into();
    CliError::failed(format!("cannot write {}: {}", what.display(), chain(&*e)))
}

fn create(dir: &Path, name: &str) -> CliResult<BufWriter<File>> {
    let path = dir.join(name);
    File::create(&path)
        .map(BufWriter::new)
        .map_err(|e| io(&path, e))
}

impl Recorder {
    fn new(study: &Study, dir: &Path) -> CliResult<Self> {
        std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
        let o = &study.output;
        let mut files = Vec::new();
        let history = if o.history {
            files.push("contacts.csv".to_string());
            Some(
                HistoryWriter::new(create(dir, "contacts.csv")?)
                    .map_err(|e| io(&dir.join("contacts.csv"), e))?,
            )
        } else {
            None
        };
        let report = if o.report {
            files.push("steps.csv".to_string());
            Some(
                ReportWriter::new(create(dir, "steps.csv")?)
                    .map_err(|e| io(&dir.join("steps.csv"), e))?,
            )
        } else {
            None
        };
        let zones_filter = o.zones.as_ref().map(|zs| {
            zs.iter()
                .filter_map(|z| study.zone_names.iter().position(|n| n == z))
                .collect()
        });
        let mut curves = Vec::new();
        for (i, p) in study.plots.iter().enumerate() {
            let all = p
                .curves
                .iter()
                .map(|c| (c, false))
                .chain(p.x_quantity.iter().map(|c| (c, true)));
            for (c, is_x) in all {
                let zone = c
                    .zone
                    .as_ref()
                    .and_then(|z| study.zone_names.iter().position(|n| n == z))
                    .or(if study.zone_names.len() == 1 {
                        Some(0)
                    } else {
                        None
                    });
                let set_nodes = c
                    .set
                    .as_ref()
                    .and_then(|s| study.model().mesh().node_set(s).ok())
                    .map(|s| s.to_vec())
                    .unwrap_or_default();
                let label = c.label.clone().unwrap_or_else(|| {
                    let mut l = c.quantity.clone();
                    if let Some(z) = &c.zone {
                        l.push_str(&format!(" ({z})"));
                    }
                    if let Some(n) = c.node {
                        l.push_str(&format!(" node {n}"));
                    }
                    if let Some(s) = &c.set {
                        l.push_str(&format!(" [{s}]"));
                    }
                    l
                });
                curves.push(CurveRt {
                    plot: i,
                    is_x,
                    label,
                    spec: c.clone(),
                    zone,
                    set_nodes,
                    values: Vec::new(),
                });
            }
        }
        let counts = study
            .candidates()
            .iter()
            .fold(vec![0; study.zone_names.len()], |mut v, c| {
                v[c.zone] += 1;
                v
            });
        let zones = study
            .zone_names
            .iter()
            .enumerate()
            .map(|(z, name)| ZoneSummary {
                name: name.clone(),
                law: study.zone_laws[z].clone(),
                candidates: counts[z],
                max_force_n: None,
                min_force_n: None,
                max_abs_force_t: None,
                min_beta: None,
                final_force_n: 0.0,
                final_force_t: 0.0,
                final_status: StatusCount::default(),
            })
            .collect();
        Ok(Self {
            dir: dir.to_path_buf(),
            history,
            report,
            interface: o.vtk.then(|| InterfaceSeries::new(dir, "interface")),
            mesh_entries: o.mesh_vtk.then(Vec::new),
            write_steps: match &o.steps {
                Some(l) => WriteSteps::List(l.clone()),
                None => WriteSteps::Every(o.every),
            },
            zones_filter,
            nodes_filter: o.nodes.clone(),
            curves,
            x_time: Vec::new(),
            x_step: Vec::new(),
            x_load: Vec::new(),
            zones,
            tangential_steps: 0,
            detection_steps: 0,
            files,
        })
    }

    fn record<L: ContactLaw + Clone>(
        &mut self,
        sim: &ContactSimulation<LinearElasticModel, L>,
        res: &StepResult,
        extras: Extras,
        global: usize,
        last_of_phase: bool,
    ) -> CliResult<()> {
        let rep = &res.report;
        let t = rep.time;
        if let Some(r) = &mut self.report {
            r.write_report(rep)
                .map_err(|e| io(&self.dir.join("steps.csv"), e))?;
        }
        if res.contacts.iter().any(|c| c.r.t[0] != 0.0) {
            self.tangential_steps += 1;
        }
        if rep.detection_passes > 1 {
            self.detection_steps += 1;
        }
        // zone summaries
        for (z, zs) in self.zones.iter_mut().enumerate() {
            let mine = res.contacts.iter().filter(|c| c.zone == z);
            let (mut fn_, mut ft, mut bmin) = (0.0, 0.0, f64::INFINITY);
            let mut st = StatusCount::default();
            for c in mine {
                fn_ += c.r.n;
                ft += c.r.t[0];
                bmin = bmin.min(c.beta);
                match c.status {
                    InterfaceStatus::Inactive => st.inactive += 1,
                    InterfaceStatus::Open => st.open += 1,
                    InterfaceStatus::Stick => st.stick += 1,
                    InterfaceStatus::Slip => st.slip += 1,
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
        }
        // curves
        let needs_disp = self.curves.iter().any(|c| {
            matches!(
                c.spec.quantity.as_str(),
                "u_x" | "u_y" | "reaction_x" | "reaction_y"
            )
        });
        let write = match &self.write_steps {
            WriteSteps::Every(k) => global.is_multiple_of(*k) || last_of_phase,
            WriteSteps::List(l) => l.contains(&global),
        };
        let want_disp =
            needs_disp || (write && (self.interface.is_some() || self.mesh_entries.is_some()));
        let disp = want_disp.then(|| sim.nodal_displacements());
        let model = sim.structure();
        let reactions = if self
            .curves
            .iter()
            .any(|c| c.spec.quantity.starts_with("reaction"))
        {
            let d = disp.as_ref().expect("computed above");
            Some(
                model
                    .reactions(d, rep.load_factor)
                    .map_err(|e| fem_failed("reactions", e))?,
            )
        } else {
            None
        };
        for c in &mut self.curves {
            let v = match c.spec.quantity.as_str() {
                "head_load" => extras.head_load.unwrap_or(f64::NAN),
                "head_displacement" => extras.head_displacement.unwrap_or(f64::NAN),
                _ => curve_value(c, res, disp.as_deref(), reactions.as_deref()),
            };
            c.values.push(v);
        }
        self.x_time.push(t);
        self.x_step.push(global as f64);
        self.x_load.push(rep.load_factor);

        if !write {
            return Ok(());
        }
        let selected: Vec<ContactRecord> = res
            .contacts
            .iter()
            .filter(|c| {
                self.zones_filter
                    .as_ref()
                    .is_none_or(|z| z.contains(&c.zone))
            })
            .copied()
            .collect();
        if let Some(h) = &mut self.history {
            let rows: Vec<ContactRecord> = selected
                .iter()
                .filter(|c| {
                    self.nodes_filter
                        .as_ref()
                        .is_none_or(|n| n.contains(&c.node))
                })
                .copied()
                .collect();
            h.write_contacts(rep.step, t, rep.load_factor, &rows)
                .map_err(|e| io(&self.dir.join("contacts.csv"), e))?;
        }
        if let Some(s) = &mut self.interface {
            s.write_step(t, &selected, disp.as_deref())
                .map_err(|e| io(&self.dir, e))?;
        }
        if let Some(entries) = &mut self.mesh_entries {
            let d = disp.as_ref().expect("computed above");
            let stress = model
                .nodal_stresses(d)
                .map_err(|e| fem_failed("nodal stresses", e))?;
            let name = format!("mesh_{:04}.vtu", entries.len());
            let path = self.dir.join(&name);
            fem_core::vtk::write_vtu(
                &path,
                model.mesh(),
                &[
                    ("u", fem_core::vtk::Field::Vector(d)),
                    ("stress", fem_core::vtk::Field::SymTensor(&stress)),
                ],
                &[],
            )
            .map_err(|e| io(&path, e))?;
            entries.push((t, name));
            let list: Vec<(f64, &str)> = entries.iter().map(|(t, f)| (*t, f.as_str())).collect();
            let pvd = self.dir.join("mesh.pvd");
            fem_core::vtk::write_pvd(&pvd, &list).map_err(|e| io(&pvd, e))?;
        }
        Ok(())
    }

    fn finish(
        mut self,
        study: &Study,
    ) -> CliResult<(Vec<String>, Vec<CurveSummary>, Vec<ZoneSummary>)> {
        if let Some(h) = self.history.take() {
            h.finish()
                .map_err(|e| io(&self.dir.join("contacts.csv"), e))?;
        }
        if let Some(r) = self.report.take() {
            r.finish().map_err(|e| io(&self.dir.join("steps.csv"), e))?;
        }
        let mut files = self.files.clone();
        if let Some(s) = &self.interface
            && s.pvd_path().exists()
        {
            files.push("interface.pvd".into());
        }
        if self.mesh_entries.as_ref().is_some_and(|e| !e.is_empty()) {
            files.push("mesh.pvd".into());
        }
        // curves.csv and the plots
        let mut summaries = Vec::new();
        if !self.curves.is_empty() {
            let mut csv = String::from("step,time,load_factor");
            for c in &self.curves {
                csv.push(',');
                csv.push_str(&c.label.replace(',', ";"));
            }
            csv.push('\n');
            for i in 0..self.x_time.len() {
                csv.push_str(&format!(
                    "{},{},{}",
                    self.x_step[i], self.x_time[i], self.x_load[i]
                ));
                for c in &self.curves {
                    csv.push_str(&format!(",{:?}", c.values[i]));
                }
                csv.push('\n');
            }
            let path = self.dir.join("curves.csv");
            std::fs::write(&path, csv).map_err(|e| io(&path, e))?;
            files.push("curves.csv".into());
            for (i, p) in study.plots.iter().enumerate() {
                let x_curve = self.curves.iter().find(|c| c.plot == i && c.is_x);
                let xs = match (x_curve, p.x) {
                    (Some(c), _) => &c.values,
                    (None, XAxis::Time) => &self.x_time,
                    (None, XAxis::Step) => &self.x_step,
                    (None, XAxis::LoadFactor) => &self.x_load,
                };
                let series: Vec<(&str, &[f64])> = self
                    .curves
                    .iter()
                    .filter(|c| c.plot == i && !c.is_x)
                    .map(|c| (c.label.as_str(), c.values.as_slice()))
                    .collect();
                let path = self.dir.join(&p.file);
                let x_label = match (x_curve, p.x) {
                    (Some(c), _) => c.label.as_str(),
                    (None, XAxis::Time) => "time",
                    (None, XAxis::Step) => "step",
                    (None, XAxis::LoadFactor) => "load factor",
                };
                plot::write_svg(
                    &path,
                    p.title.as_deref().unwrap_or(&p.file),
                    x_label,
                    xs,
                    &series,
                )
                .map_err(|e| io(&path, e))?;
                files.push(p.file.clone());
            }
            for c in &self.curves {
                let mut s = CurveSummary {
                    plot: study.plots[c.plot].file.clone(),
                    label: c.label.clone(),
                    min: None,
                    max: None,
                    last: c.values.last().copied(),
                };
                for (i, &v) in c.values.iter().enumerate() {
                    keep(&mut s.max, v, self.x_step[i] as usize, self.x_time[i], true);
                    keep(
                        &mut s.min,
                        v,
                        self.x_step[i] as usize,
                        self.x_time[i],
                        false,
                    );
                }
                summaries.push(s);
            }
        }
        Ok((files, summaries, self.zones))
    }
}

fn curve_value(
    c: &CurveRt,
    res: &StepResult,
    disp: Option<&[[f64; 2]]>,
    reactions: Option<&[fem_core::Reaction]>,
) -> f64 {
    let q = c.spec.quantity.as_str();
    let in_zone = |r: &&ContactRecord| c.zone.is_none_or(|z| r.zone == z);
    let rep = &res.report;
    match q {
        "contact_iterations" => rep.contact_iterations as f64,
        "adhesion_iterations" => rep.adhesion_iterations as f64,
        "active_contacts" => rep.active_contacts as f64,
        "residual" => rep.residual,
        "force_n" => res.contacts.iter().filter(in_zone).map(|r| r.r.n).sum(),
        "force_t" => res.contacts.iter().filter(in_zone).map(|r| r.r.t[0]).sum(),
        "closed" => res
            .contacts
            .iter()
            .filter(in_zone)
            .filter(|r| matches!(r.status, InterfaceStatus::Stick | InterfaceStatus::Slip))
            .count() as f64,
        "beta_mean" | "beta_min" => {
            let b: Vec<f64> = res
                .contacts
                .iter()
                .filter(in_zone)
                .map(|r| r.beta)
                .collect();
            if b.is_empty() {
                f64::NAN
            } else if q == "beta_min" {
                b.iter().copied().fold(f64::INFINITY, f64::min)
            } else {
                b.iter().sum::<f64>() / b.len() as f64
            }
        }
        "gap" | "u_t" | "beta" | "r_n" | "r_t" => {
            let node = c.spec.node.unwrap_or(usize::MAX);
            let zone_given = c.spec.zone.is_some();
            match res
                .contacts
                .iter()
                .find(|r| r.node == node && (!zone_given || c.zone == Some(r.zone)))
            {
                Some(r) => match q {
                    "gap" => r.gap,
                    "u_t" => r.u_t,
                    "beta" => r.beta,
                    "r_n" => r.r.n,
                    _ => r.r.t[0],
                },
                None => f64::NAN,
            }
        }
        "u_x" | "u_y" => {
            let k = usize::from(q == "u_y");
            let Some(d) = disp else { return f64::NAN };
            let nodes: Vec<usize> = match c.spec.node {
                Some(n) => vec![n],
                None => c.set_nodes.clone(),
            };
            if nodes.is_empty() {
                return f64::NAN;
            }
            nodes.iter().map(|&n| d[n][k]).sum::<f64>() / nodes.len() as f64
        }
        "reaction_x" | "reaction_y" => {
            let comp = if q == "reaction_x" {
                Component::X
            } else {
                Component::Y
            };
            reactions.map_or(f64::NAN, |r| {
                r.iter()
                    .filter(|((n, cc), _)| *cc == comp && c.set_nodes.contains(n))
                    .map(|(_, v)| v)
                    .sum()
            })
        }
        _ => f64::NAN,
    }
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
            let mut d = CustomDriver {
                c,
                last_loads: None,
            };
            drive(&mut d, &study.phases, total, &mut recorder, opts)
        }
        Body::Preset(p) => {
            let mut d = PresetDriver {
                p,
                extras: Extras::default(),
            };
            drive(&mut d, &study.phases, total, &mut recorder, opts)
        }
    };
    let wall = start.elapsed().as_secs_f64();
    let (phases, error) = outcome;
    let (tangential, detection) = (recorder.tangential_steps, recorder.detection_steps);
    let steps_done = recorder.x_time.len();
    let (mut files, curves, zones) = recorder.finish(&study)?;
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
        units: BTreeUnits {
            length: study.units.length.clone(),
            force: study.units.force.clone(),
            time: study.units.time.clone(),
            stress: study.units.stress.clone(),
        },
        status: if error.is_some() {
            "failed"
        } else {
            "completed"
        }
        .into(),
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
    };
    let path = opts.out_dir.join("summary.json");
    let text = serde_json::to_string_pretty(&summary).map_err(|e| io(&path, e))?;
    std::fs::write(&path, text + "\n").map_err(|e| io(&path, e))?;
    match error {
        Some(e) => Err(e),
        None => Ok(summary),
    }
}

/// The work done since `start` (a preset's builder may have stepped already, e.g. to calibrate).
///
/// `Counters` is `#[non_exhaustive]`, so it cannot be built here with a struct expression, and
/// the library has no difference of two counters: the difference is taken field by field on a
/// copy of `now` (its fields are public). A field the library adds later must be added here,
/// or it is reported since the start of the simulation rather than of the run.
fn since(now: Counters, start: Counters) -> Counters {
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
    d.active_set_fallbacks -= start.active_set_fallbacks;
    d
}

fn facts<L: ContactLaw + Clone>(sim: &ContactSimulation<LinearElasticModel, L>) -> MeshFacts {
    let m = sim.structure();
    MeshFacts {
        nodes: m.mesh().node_count(),
        elements: m.mesh().element_count(),
        free_dofs: m.dof_count(),
        candidates: sim.candidates().len(),
    }
}

fn drive<D: Driver>(
    d: &mut D,
    phases: &[Phase],
    total: usize,
    rec: &mut Recorder,
    opts: &RunOptions,
) -> (Vec<PhaseSummary>, Option<CliError>) {
    let total = total as u64;
    let pb = if opts.quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr())
    };
    pb.set_style(
        ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} steps, {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    let mut out: Vec<PhaseSummary> = Vec::new();
    let mut global = 0;
    for (pi, phase) in phases.iter().enumerate() {
        pb.set_prefix(format!("phase `{}`", phase.name));
        let before = d.sim().counters();
        let t_phase = Instant::now();
        let fail = |out: &mut Vec<PhaseSummary>, e: CliError| {
            pb.finish_and_clear();
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
            pb.set_message(format!(
                "t = {t:.4}, {} iterations",
                res.report.contact_iterations
            ));
            pb.inc(1);
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
        let line = format!(
            "phase `{}`: {} steps, t {} → {}: {} contact iterations, {} adhesion iterations, {} F* builds, {} stiffness changes, {:.3} s",
            s.name,
            s.steps,
            s.t_start,
            s.t_end,
            s.contact_iterations,
            s.adhesion_iterations,
            s.flexibility_builds,
            s.stiffness_changes,
            s.wall_time_s
        );
        if !opts.quiet {
            pb.suspend(|| println!("{line}"));
        }
        out.push(s);
    }
    pb.finish_and_clear();
    (out, None)
}
