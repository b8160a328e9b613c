//! The recorder of a run: after each step it hands the result to each output's writer (the CSV
//! histories, the VTK series, the plotted curves, the summary's tally), computing once what
//! several of them need (the nodal displacements, the reactions, the contacts of the zones
//! asked for) and deciding which steps are written.

use super::csv::CsvWriter;
use super::driver::Extras;
use super::errors::{fem_failed, io};
use super::plots::Plots;
use super::summary::{CurveSummary, Tally, ZoneSummary};
use super::vtk::VtkWriter;
use crate::build::Study;
use crate::error::CliResult;
use contact_laws::ContactLaw;
use contact_solver::{ContactRecord, ContactSimulation, StepResult};
use fem_core::LinearElasticModel;
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
    tally: Tally,
    write_steps: WriteSteps,
    zones_filter: Option<Vec<usize>>,
    files: Vec<String>,
}

impl Recorder {
    /// Creates `dir` and the files written from the first step on.
    pub(super) fn new(study: &Study, dir: &Path) -> CliResult<Self> {
        std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
        let o = &study.output;
        let mut files = Vec::new();
        let csv = CsvWriter::new(dir, o.history, o.report, o.nodes.clone(), &mut files)?;
        let zones_filter = o.zones.as_ref().map(|zs| {
            zs.iter()
                .filter_map(|z| study.zone_names.iter().position(|n| n == z))
                .collect()
        });
        let plots = Plots::new(study);
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
            vtk: VtkWriter::new(dir, o.vtk, o.mesh_vtk),
            plots,
            tally: Tally::new(&study.zone_names, &study.zone_laws, &counts),
            write_steps: match &o.steps {
                Some(l) => WriteSteps::List(l.clone()),
                None => WriteSteps::Every(o.every),
            },
            zones_filter,
            files,
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
        self.vtk
            .write_step(rep.time, &selected, disp.as_deref(), model)
    }

    /// Closes the files, writes the curves and the plots; returns the files written (but
    /// `summary.json`), the curves' and the zones' summaries.
    pub(super) fn finish(
        mut self,
        study: &Study,
    ) -> CliResult<(Vec<String>, Vec<CurveSummary>, Vec<ZoneSummary>)> {
        self.csv.finish()?;
        let mut files = self.files.clone();
        files.extend(self.vtk.files());
        let summaries = self.plots.finish(study, &self.dir, &mut files)?;
        Ok((files, summaries, self.tally.zones))
    }
}
