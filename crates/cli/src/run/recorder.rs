//! The recorder of a run: after each step it hands the result to each output's writer (the CSV
//! histories, the VTK series, the plotted curves, the summary's tally), computing once what
//! several of them need (the nodal displacements, the reactions, the contacts of the zones
//! asked for) and deciding which steps are written.

use super::csv::CsvWriter;
use super::driver::Extras;
use super::errors::{fem_failed, io};
use super::plots::Plots;
use super::pressure::{PressureRecorder, zone_mass};
use super::profiles::Profiles;
use super::rigid::{RigidMotionSummary, RigidWriter};
use super::summary::{CurveSummary, Tally, ZoneSummary};
use super::vtk::VtkWriter;
use crate::build::{Body, HertzShape, Study};
use crate::error::CliResult;
use crate::presets::ShaftPoint;
use contact_laws::ContactLaw;
use contact_solver::coupling::traction::TractionField;
use contact_solver::{ContactRecord, ContactSimulation, StepResult};
use fem_core::boundary_mass::BoundaryMass;
use fem_core::{Idealization, LinearElasticModel, Structure};
use std::path::{Path, PathBuf};

/// Which steps the CSV contact history and the VTK series write.
enum WriteSteps {
    Every(usize),
    List(Vec<usize>),
}

/// The writers of one run.
pub(super) struct Recorder {
    dir: PathBuf,
    csv: CsvWriter,
    vtk: VtkWriter,
    plots: Plots,
    pressure: PressureRecorder,
    /// The recovered traction goes into the interface VTK (`output.pressure`).
    vtk_pressure: bool,
    tally: Tally,
    write_steps: WriteSteps,
    zones_filter: Option<Vec<usize>>,
    files: Vec<String>,
    /// `rigid_motions.csv`, for a structure with rigid-body modes (floating bodies).
    rigid: Option<RigidWriter>,
    /// The pile's shaft profiles (the pile preset only).
    profiles: Option<Profiles>,
}

/// The names of the two axes: `r, z` in axisymmetry, `x, y` otherwise.
pub(super) fn axes(study: &Study) -> [&'static str; 2] {
    match study.model().idealization() {
        Idealization::Axisymmetric => ["r", "z"],
        _ => ["x", "y"],
    }
}

impl Recorder {
    /// Creates `dir` and the files written from the first step on.
    pub(super) fn new(study: &Study, dir: &Path) -> CliResult<Self> {
        std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
        let o = &study.output;
        let mut files = Vec::new();
        let csv = CsvWriter::new(
            dir,
            o.history,
            o.report,
            o.nodes.clone(),
            axes(study),
            &mut files,
        )?;
        let floating = study
            .model()
            .rigid_body_modes()
            .is_some_and(|m| !m.is_empty());
        let rigid = if floating {
            files.push("rigid_motions.csv".to_string());
            Some(RigidWriter::new(dir, axes(study))?)
        } else {
            None
        };
        let zones_filter = o.zones.as_ref().map(|zs| {
            zs.iter()
                .filter_map(|z| study.zone_names.iter().position(|n| n == z))
                .collect()
        });
        let plots = Plots::new(study);
        let pressure = pressure_recorder(study, dir, zones_filter.clone(), &mut files)?;
        let counts = study
            .candidates()
            .iter()
            .fold(vec![0; study.zone_names.len()], |mut v, c| {
                v[c.zone] += 1;
                v
            });
        Ok(Self {
            dir: dir.to_path_buf(),
            csv,
            vtk: VtkWriter::new(dir, o.vtk, o.writes_mesh_vtk()),
            plots,
            pressure,
            vtk_pressure: o.pressure,
            tally: Tally::new(&study.zone_names, &study.zone_laws, &counts),
            write_steps: match &o.steps {
                Some(l) => WriteSteps::List(l.clone()),
                None => WriteSteps::Every(o.every),
            },
            zones_filter,
            files,
            rigid,
            profiles: matches!(&study.body, Body::Preset(p) if p.kind == "pile")
                .then(Profiles::default),
        })
    }

    /// Steps recorded.
    pub(super) fn steps(&self) -> usize {
        self.plots.steps()
    }

    /// Steps with a tangential reaction, and steps with several penetration-check passes.
    pub(super) fn stage_counts(&self) -> (usize, usize) {
        (self.tally.tangential_steps, self.tally.detection_steps)
    }

    /// Records global step `global` (the last of its phase when `last_of_phase`).
    pub(super) fn record<L: ContactLaw + Clone>(
        &mut self,
        sim: &ContactSimulation<LinearElasticModel, L>,
        res: &StepResult,
        extras: Extras,
        global: usize,
        last_of_phase: bool,
    ) -> CliResult<()> {
        let rep = &res.report;
        self.csv.write_report(rep)?;
        self.tally.record(res, global);
        if let (Some(w), Some(modes)) = (&mut self.rigid, sim.structure().rigid_body_modes()) {
            w.write_step(global, rep.time, modes, sim.rigid_body_amplitudes())?;
        }
        let write = match &self.write_steps {
            WriteSteps::Every(k) => global.is_multiple_of(*k) || last_of_phase,
            WriteSteps::List(l) => l.contains(&global),
        };
        let want_disp = self.plots.needs_displacements() || (write && self.vtk.is_active());
        let disp = want_disp.then(|| sim.nodal_displacements());
        let model = sim.structure();
        let reactions = if self.plots.needs_reactions() {
            let d = disp.as_ref().expect("computed above");
            Some(
                model
                    .reactions(d, rep.load_factor)
                    .map_err(|e| fem_failed("reactions", e))?,
            )
        } else {
            None
        };
        self.plots
            .record(res, extras, disp.as_deref(), reactions.as_deref(), global);
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
        self.csv.write_contacts(rep, &selected)?;
        let fields = if self.pressure.is_active() || (self.vtk_pressure && self.vtk.is_active()) {
            let nodes = model.mesh().nodes();
            self.pressure.record(
                global,
                rep.time,
                |mass, zone| TractionField::from_records(mass, zone, &res.contacts),
                |zone| {
                    res.contacts
                        .iter()
                        .filter(|c| c.zone == zone)
                        .map(|c| c.r.n)
                        .sum()
                },
                |node| nodes[node].to_vec(),
                1,
            )?
        } else {
            Vec::new()
        };
        let fields = if self.vtk_pressure { &fields[..] } else { &[] };
        self.vtk
            .write_step(rep.time, &selected, disp.as_deref(), model, fields)
    }

    /// Keeps the pile's shaft at global step `global` (time `t`, phase `phase`, head load `q`).
    pub(super) fn profile(
        &mut self,
        global: usize,
        t: f64,
        phase: usize,
        q: f64,
        points: Vec<ShaftPoint>,
    ) {
        if let Some(p) = &mut self.profiles {
            p.record(global, t, phase, q, points);
        }
    }

    /// Closes the files, writes the curves, the plots and the pile's profiles; returns the files written (but
    /// `summary.json`), the curves', the zones' summaries and the floating bodies' last rigid
    /// motions.
    pub(super) fn finish(mut self, study: &Study) -> CliResult<Finished> {
        self.csv.finish()?;
        let rigid = match self.rigid.take() {
            Some(w) => w.finish()?,
            None => Vec::new(),
        };
        let mut files = self.files.clone();
        files.extend(self.vtk.files());
        let summaries = self.plots.finish(&study.plots, &self.dir, &mut files)?;
        let nodes = study.model().mesh().nodes();
        self.pressure
            .finish(|n| [nodes[n][0], nodes[n][1], 0.0], &mut files)?;
        if let Some(p) = &self.profiles {
            p.finish(&self.dir, study.output.profile_steps.as_deref(), &mut files)?;
        }
        Ok(Finished {
            files,
            curves: summaries,
            zones: self.tally.zones,
            rigid,
        })
    }
}

/// What the recorder hands the summary at the end of a run.
pub(super) struct Finished {
    pub(super) files: Vec<String>,
    pub(super) curves: Vec<CurveSummary>,
    pub(super) zones: Vec<ZoneSummary>,
    pub(super) rigid: Vec<RigidMotionSummary>,
}

/// The masses of the zones' contactor surfaces (when `output.pressure` or `[hertz]` asks for
/// them) and the writer of `pressure.csv`.
fn pressure_recorder(
    study: &Study,
    dir: &Path,
    zones_filter: Option<Vec<usize>>,
    files: &mut Vec<String>,
) -> CliResult<PressureRecorder> {
    fn masses<L: ContactLaw + Clone>(
        sim: &ContactSimulation<LinearElasticModel, L>,
    ) -> CliResult<Vec<Option<BoundaryMass>>> {
        let model = sim.structure();
        sim.zones()
            .iter()
            .map(|z| {
                let m = BoundaryMass::on_nodes(model.mesh(), &z.contactor, model.idealization());
                zone_mass(&z.name, m)
            })
            .collect()
    }
    let wanted = study.output.pressure || study.hertz.is_some();
    let masses = match (&study.body, wanted) {
        (_, false) => vec![None; study.zone_names.len()],
        (Body::Custom(c), true) => masses(&c.sim)?,
        (Body::Preset(p), true) => masses(p.sim())?,
    };
    let ideal = study.model().idealization();
    let shape = match ideal {
        Idealization::Axisymmetric => HertzShape::Sphere {
            ring: std::f64::consts::TAU,
        },
        Idealization::PlaneStress { thickness } => HertzShape::Cylinder { thickness },
        _ => HertzShape::Cylinder { thickness: 1.0 },
    };
    let coords: &[&str] = if ideal == Idealization::Axisymmetric {
        &["r", "z"]
    } else {
        &["x", "y"]
    };
    PressureRecorder::new(
        dir,
        study.output.pressure,
        masses,
        zones_filter,
        study.hertz.clone().map(|h| (h, shape)),
        (coords, &["t"][..]),
        files,
    )
}
