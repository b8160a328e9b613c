//! `contacts.csv` (one row per contact and written step) and `steps.csv` (one row per step),
//! through the library's [`HistoryWriter`] and [`ReportWriter`] (the CLI adds the zone and node
//! filters of `[output]` only).

use super::errors::{create, io};
use crate::error::CliResult;
use contact_solver::{ContactRecord, HistoryWriter, ReportWriter, StepReport};
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// The two CSV histories, each optional.
pub(super) struct CsvWriter {
    dir: PathBuf,
    history: Option<HistoryWriter<BufWriter<File>>>,
    report: Option<ReportWriter<BufWriter<File>>>,
    nodes_filter: Option<Vec<usize>>,
}

impl CsvWriter {
    /// Creates the files asked for, and lists them in `files`.
    pub(super) fn new(
        dir: &Path,
        history: bool,
        report: bool,
        nodes_filter: Option<Vec<usize>>,
        axes: [&str; 2],
        files: &mut Vec<String>,
    ) -> CliResult<Self> {
        let history = if history {
            files.push("contacts.csv".to_string());
            Some(
                HistoryWriter::with_axes(create(dir, "contacts.csv")?, axes)
                    .map_err(|e| io(&dir.join("contacts.csv"), e))?,
            )
        } else {
            None
        };
        let report = if report {
            files.push("steps.csv".to_string());
            Some(
                ReportWriter::new(create(dir, "steps.csv")?)
                    .map_err(|e| io(&dir.join("steps.csv"), e))?,
            )
        } else {
            None
        };
        Ok(Self {
            dir: dir.to_path_buf(),
            history,
            report,
            nodes_filter,
        })
    }

    /// One row of `steps.csv` (every step).
    pub(super) fn write_report(&mut self, rep: &StepReport) -> CliResult<()> {
        if let Some(r) = &mut self.report {
            r.write_report(rep)
                .map_err(|e| io(&self.dir.join("steps.csv"), e))?;
        }
        Ok(())
    }

    /// The rows of `contacts.csv` of a written step: the `selected` contacts (already filtered
    /// by zone) of the contactor nodes asked for.
    pub(super) fn write_contacts(
        &mut self,
        rep: &StepReport,
        selected: &[ContactRecord],
    ) -> CliResult<()> {
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
            h.write_contacts(rep.step, rep.time, rep.load_factor, &rows)
                .map_err(|e| io(&self.dir.join("contacts.csv"), e))?;
        }
        Ok(())
    }

    /// Flushes both files.
    pub(super) fn finish(&mut self) -> CliResult<()> {
        if let Some(h) = self.history.take() {
            h.finish()
                .map_err(|e| io(&self.dir.join("contacts.csv"), e))?;
        }
        if let Some(r) = self.report.take() {
            r.finish().map_err(|e| io(&self.dir.join("steps.csv"), e))?;
        }
        Ok(())
    }
}
