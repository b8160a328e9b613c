//! The VTK series: the interface (`interface_*.vtu` + `interface.pvd`, through the library's
//! [`InterfaceSeries`]) and the whole mesh (`mesh_*.vtu` + `mesh.pvd`: displacement and nodal
//! stress; a distributed run's as parallel pieces, `mesh_*.pvtu`, through [`Pieces`]).

use super::errors::{fem_failed, io};
use super::pieces::Pieces;
use crate::error::CliResult;
use contact_solver::coupling::traction::{TractionField, write_interface_vtu_with_traction};
use contact_solver::{ContactRecord, InterfaceSeries};
use fem_core::LinearElasticModel;
use std::path::{Path, PathBuf};

/// The two series, each optional.
pub(super) struct VtkWriter {
    dir: PathBuf,
    interface: Option<InterfaceSeries>,
    mesh_entries: Option<Vec<(f64, String)>>,
    /// A distributed run's pieces of the mesh series (`mesh_NNNN.pvtu` in `mesh.pvd`).
    pieces: Option<Pieces>,
}

impl VtkWriter {
    /// The series asked for (nothing is written before the first step); the mesh series as
    /// this rank's `pieces` in a distributed run.
    pub(super) fn new(dir: &Path, interface: bool, mesh: bool, pieces: Option<Pieces>) -> Self {
        Self {
            dir: dir.to_path_buf(),
            interface: interface.then(|| InterfaceSeries::new(dir, "interface")),
            mesh_entries: mesh.then(Vec::new),
            pieces,
        }
    }

    /// Whether a written step needs the nodal displacements.
    pub(super) fn is_active(&self) -> bool {
        self.interface.is_some() || self.mesh_entries.is_some()
    }

    /// One written step at time `t`; `disp` is given whenever [`is_active`](Self::is_active);
    /// the interface carries the recovered traction `fields` when there are some.
    pub(super) fn write_step(
        &mut self,
        t: f64,
        selected: &[ContactRecord],
        disp: Option<&[[f64; 2]]>,
        model: &LinearElasticModel,
        fields: &[TractionField],
    ) -> CliResult<()> {
        if let Some(s) = &mut self.interface {
            if fields.is_empty() {
                s.write_step(t, selected, disp)
            } else {
                s.write_step_with(t, |path| {
                    write_interface_vtu_with_traction(path, selected, disp, fields)
                })
            }
            .map_err(|e| io(&self.dir, e))?;
        }
        if let Some(entries) = &mut self.mesh_entries {
            let d = disp.expect("computed by the recorder");
            let stress = model
                .nodal_stresses(d)
                .map_err(|e| fem_failed("nodal stresses", e))?;
            let stem = format!("mesh_{:04}", entries.len());
            let point = [
                ("u", fem_core::vtk::Field::Vector(d)),
                ("stress", fem_core::vtk::Field::SymTensor(&stress)),
            ];
            let name = match &self.pieces {
                Some(pieces) => pieces.write(&stem, model.mesh(), &point, &[])?,
                None => {
                    let name = format!("{stem}.vtu");
                    let path = self.dir.join(&name);
                    fem_core::vtk::write_vtu(&path, model.mesh(), &point, &[])
                        .map_err(|e| io(&path, e))?;
                    name
                }
            };
            // each rank's own directory (rank 0's is the run's)
            push_pvd(&self.dir, entries, t, name)?;
        }
        Ok(())
    }

    /// The `.pvd` files written, for the list of outputs.
    pub(super) fn files(&self) -> Vec<String> {
        let mut files = Vec::new();
        if let Some(s) = &self.interface
            && s.pvd_path().exists()
        {
            files.push("interface.pvd".into());
        }
        if self.mesh_entries.as_ref().is_some_and(|e| !e.is_empty()) {
            files.push("mesh.pvd".into());
        }
        files
    }
}

/// Appends the step `(t, name)` to a `mesh.pvd` series in `dir` and rewrites the series.
pub(super) fn push_pvd(
    dir: &Path,
    entries: &mut Vec<(f64, String)>,
    t: f64,
    name: String,
) -> CliResult<()> {
    entries.push((t, name));
    let list: Vec<(f64, &str)> = entries.iter().map(|(t, f)| (*t, f.as_str())).collect();
    let pvd = dir.join("mesh.pvd");
    fem_core::vtk::write_pvd(&pvd, &list).map_err(|e| io(&pvd, e))
}
