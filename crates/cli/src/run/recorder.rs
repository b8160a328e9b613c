//! The recorder of a run, in either dimension: after each step it hands the result to each
//! output's writer (the CSV histories, the VTK series, the plotted curves, the pressure, the
//! summary's tally), computing once what several of them need (the nodal displacements, the
//! contacts of the zones asked for) and deciding which steps are written. The formats that
//! differ by dimension are [`RunDim`]'s.

use super::dim::{RunDim, Sim, StepRow};
use super::errors::io;
use super::plots::Plots;
use super::pressure::{PressureRecorder, zone_mass};
use super::profiles::Profiles;
use super::rigid::RigidMotionSummary;
use super::summary::{CurveSummary, Tally, ZoneSummary};
use crate::build::{Body, Study, StudyDim};
use crate::error::CliResult;
use crate::presets::ShaftPoint;
use contact_laws::{ContactLaw, RccmState};
use contact_solver::coupling::traction::TractionField;
use contact_solver::{ContactRecord, StepResult};
use fem_core::Dim;
use std::path::{Path, PathBuf};

/// Which steps the CSV contact history and the VTK series write.
enum WriteSteps {
    Every(usize),
    List(Vec<usize>),
}

/// The writers of one run.
pub(crate) struct Recorder<const D: usize>
where
    Dim<D>: RunDim<D>,
{
    dir: PathBuf,
    /// This dimension's CSV and VTK writers.
    writers: <Dim<D> as RunDim<D>>::Writers,
    plots: Plots,
    pressure: PressureRecorder,
    /// The recovered traction goes into the VTK files (`output.pressure`).
    vtk_pressure: bool,
    tally: Tally<D>,
    write_steps: WriteSteps,
    zones_filter: Option<Vec<usize>>,
    files: Vec<String>,
    /// The pile's shaft profiles (the pile preset only).
    profiles: Option<Profiles>,
}

impl<const D: usize> Recorder<D>
where
    Dim<D>: RunDim<D>,
{
    /// Creates `dir` and the files written from the first step on (the mesh series as this
    /// rank's `pieces` in a distributed run).
    pub(super) fn new(
        study: &Study<D>,
        dir: &Path,
        pieces: Option<super::Pieces>,
    ) -> CliResult<Self> {
        std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
        let o = &study.output;
        let mut files = Vec::new();
        let writers = Dim::<D>::writers(study, dir, pieces, &mut files)?;
        let zones_filter: Option<Vec<usize>> = o.zones.as_ref().map(|zs| {
            zs.iter()
                .filter_map(|z| study.zone_names.iter().position(|n| n == z))
                .collect()
        });
        let pressure = pressure_recorder(study, dir, zones_filter.clone(), &mut files)?;
        let counts = study
            .candidates()
            .iter()
            .fold(vec![0; study.zone_names.len()], |mut v, c| {
                v[c.zone] += 1;
                v
            });
        let pile = match &study.body {
            Body::Preset(p) => Dim::<D>::preset_kind(p) == "pile",
            Body::Custom(_) => false,
        };
        Ok(Self {
            dir: dir.to_path_buf(),
            writers,
            plots: Plots::new(study),
            pressure,
            vtk_pressure: o.pressure,
            tally: Tally::new(&study.zone_names, &study.zone_laws, &counts),
            write_steps: match &o.steps {
                Some(l) => WriteSteps::List(l.clone()),
                None => WriteSteps::Every(o.every.max(1)),
            },
            zones_filter,
            files,
            profiles: pile.then(Profiles::default),
        })
    }

    pub(super) fn steps(&self) -> usize {
        self.plots.steps()
    }

    /// Steps with a tangential reaction, and steps with several penetration-check passes.
    pub(super) fn stage_counts(&self) -> (usize, usize) {
        (self.tally.tangential_steps, self.tally.detection_steps)
    }

    /// The support reactions' sum at the last step, where the dimension keeps it.
    pub(super) fn reaction(&self) -> Option<[f64; D]> {
        Dim::<D>::reaction(&self.writers)
    }

    /// Records `row`'s step (the last of its phase when `last_of_phase`).
    pub(super) fn record<L: ContactLaw<State = RccmState> + Clone>(
        &mut self,
        sim: &Sim<L, D>,
        res: &StepResult<D>,
        row: &StepRow<'_>,
        last_of_phase: bool,
    ) -> CliResult<()> {
        let global = row.step;
        let write = match &self.write_steps {
            WriteSteps::Every(k) => global.is_multiple_of(*k) || last_of_phase,
            WriteSteps::List(l) => l.contains(&global),
        };
        self.tally.record(res, global);
        let zones = &self.tally.zones;
        let step = (res, row, write);
        let disp = Dim::<D>::step(&mut self.writers, &mut self.plots, sim, step, zones)?;
        if !write {
            return Ok(());
        }
        let selected: Vec<ContactRecord<D>> = res
            .contacts
            .iter()
            .filter(|c| {
                self.zones_filter
                    .as_ref()
                    .is_none_or(|z| z.contains(&c.zone))
            })
            .copied()
            .collect();
        Dim::<D>::contacts(&mut self.writers, sim, (res, row), &selected, zones)?;
        let vtk = Dim::<D>::vtk_active(&self.writers);
        let fields = if self.pressure.is_active() || (self.vtk_pressure && vtk) {
            let nodes = sim.structure().mesh().nodes();
            self.pressure.record(
                global,
                res.report.time,
                |mass, zone| TractionField::from_records(mass, zone, &res.contacts),
                |zone| {
                    res.contacts
                        .iter()
                        .filter(|c| c.zone == zone)
                        .map(|c| c.reaction()[0])
                        .sum()
                },
                |node| nodes[node].to_vec(),
                D - 1,
            )?
        } else {
            Vec::new()
        };
        let fields = if self.vtk_pressure { &fields[..] } else { &[] };
        if !vtk {
            return Ok(());
        }
        let written = (res.report.time, &selected[..], disp.as_deref());
        Dim::<D>::vtk(&mut self.writers, sim.structure(), written, fields)
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

    /// Closes the files, writes the curves, the plots and the pile's profiles; returns the
    /// files written (but `summary.json`), the curves', the zones' summaries and the floating
    /// bodies' last rigid motions.
    pub(super) fn finish(self, study: &Study<D>) -> CliResult<Finished<D>> {
        let mut files = self.files;
        let (curves, rigid) = Dim::<D>::finish(
            self.writers,
            (&self.plots, self.pressure),
            study,
            &self.dir,
            &mut files,
        )?;
        if let Some(p) = &self.profiles {
            p.finish(&self.dir, study.output.profile_steps.as_deref(), &mut files)?;
        }
        Ok(Finished {
            files,
            curves,
            zones: self.tally.zones,
            rigid,
        })
    }
}

/// What the recorder hands the summary at the end of a run.
pub(super) struct Finished<const D: usize> {
    pub(super) files: Vec<String>,
    pub(super) curves: Vec<CurveSummary>,
    pub(super) zones: Vec<ZoneSummary<D>>,
    pub(super) rigid: Vec<RigidMotionSummary>,
}

/// The masses of the zones' contactor surfaces (when `output.pressure` or `[hertz]` asks for
/// them) and the writer of `pressure.csv`.
fn pressure_recorder<const D: usize>(
    study: &Study<D>,
    dir: &Path,
    zones_filter: Option<Vec<usize>>,
    files: &mut Vec<String>,
) -> CliResult<PressureRecorder>
where
    Dim<D>: RunDim<D>,
{
    let model = study.model();
    let masses = if study.output.pressure || study.hertz.is_some() {
        study
            .contactors()
            .iter()
            .map(|(name, nodes)| zone_mass(name, Dim::<D>::surface_mass(model, nodes)))
            .collect::<CliResult<Vec<_>>>()?
    } else {
        vec![None; study.zone_names.len()]
    };
    let hertz = study.hertz.clone();
    PressureRecorder::new(
        dir,
        study.output.pressure,
        masses,
        zones_filter,
        hertz.map(|h| (h, Dim::<D>::hertz_shape(model))),
        (Dim::<D>::axes(model), Dim::<D>::SHEAR),
        files,
    )
}
