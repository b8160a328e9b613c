//! The files of a 2D run ([`RunDim`] for `Dim<2>`): `steps.csv` and `contacts.csv` through the
//! library's writers ([`super::csv`]), the interface and mesh series ([`super::vtk`]), the
//! rigid motions of floating bodies ([`super::rigid`]), and the pressure on the zones'
//! contactor edges (axisymmetric: rings).

use super::csv::CsvWriter;
use super::dim::{RunDim, Sim, StepRow, positions};
use super::errors::fem_failed;
use super::plots::Plots;
use super::pressure::PressureRecorder;
use super::rigid::{RigidMotionSummary, RigidWriter};
use super::summary::{CurveSummary, ZoneSummary};
use super::vtk::VtkWriter;
use crate::build::{HertzShape, Study};
use crate::error::CliResult;
use contact_laws::{ContactLaw, RccmState};
use contact_solver::coupling::traction::TractionField;
use contact_solver::{ContactRecord, StepResult};
use fem_core::boundary_mass::BoundaryMass;
use fem_core::{Dim, FemError, Idealization, LinearElasticModel, Structure};
use std::path::Path;

/// The writers of a 2D run.
pub(crate) struct PlaneWriters {
    csv: CsvWriter,
    vtk: VtkWriter,
    /// `rigid_motions.csv`, for a structure with rigid-body modes (floating bodies).
    rigid: Option<RigidWriter>,
}

/// The names of the two axes (`x, y`; `r, z` in axisymmetry).
fn axes(study: &Study) -> [&'static str; 2] {
    let a = Dim::<2>::axes(study.model());
    [a[0], a[1]]
}

impl RunDim<2> for Dim<2> {
    type Writers = PlaneWriters;

    fn writers(
        study: &Study,
        dir: &Path,
        pieces: Option<super::Pieces>,
        files: &mut Vec<String>,
    ) -> CliResult<PlaneWriters> {
        let o = &study.output;
        let csv = CsvWriter::new(
            dir,
            o.history,
            o.report,
            o.nodes.clone(),
            axes(study),
            files,
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
        Ok(PlaneWriters {
            csv,
            vtk: VtkWriter::new(dir, o.vtk, o.writes_mesh_vtk(), pieces),
            rigid,
        })
    }

    const SHEAR: &'static [&'static str] = &["t"];

    fn axes(model: &LinearElasticModel) -> &'static [&'static str] {
        match model.idealization() {
            Idealization::Axisymmetric => &["r", "z"],
            _ => &["x", "y"],
        }
    }

    fn surface_mass(model: &LinearElasticModel, nodes: &[usize]) -> Result<BoundaryMass, FemError> {
        BoundaryMass::on_nodes(model.mesh(), nodes, model.idealization())
    }

    fn hertz_shape(model: &LinearElasticModel) -> HertzShape {
        match model.idealization() {
            Idealization::Axisymmetric => HertzShape::Sphere {
                ring: std::f64::consts::TAU,
            },
            Idealization::PlaneStress { thickness } => HertzShape::Cylinder { thickness },
            _ => HertzShape::Cylinder { thickness: 1.0 },
        }
    }

    fn step<L: ContactLaw<State = RccmState> + Clone>(
        w: &mut PlaneWriters,
        plots: &mut Plots,
        sim: &Sim<L, 2>,
        (res, row, written): (&StepResult, &StepRow<'_>, bool),
        _: &[ZoneSummary],
    ) -> CliResult<Option<Vec<[f64; 2]>>> {
        let rep = &res.report;
        w.csv.write_report(rep)?;
        if let (Some(r), Some(modes)) = (&mut w.rigid, sim.structure().rigid_body_modes()) {
            r.write_step(row.step, rep.time, modes, sim.rigid_body_amplitudes())?;
        }
        let want_disp = plots.needs_displacements() || (written && w.vtk.is_active());
        let disp = want_disp.then(|| sim.nodal_displacements());
        let reactions = match (&disp, plots.needs_reactions()) {
            (Some(d), true) => Some(
                sim.structure()
                    .reactions(d, rep.load_factor)
                    .map_err(|e| fem_failed("reactions", e))?,
            ),
            _ => None,
        };
        let step = (res, row.extras, row.step);
        plots.record(step, disp.as_deref(), reactions.as_deref(), |c| c.u_t);
        Ok(disp)
    }

    fn contacts<L: ContactLaw<State = RccmState> + Clone>(
        w: &mut PlaneWriters,
        _: &Sim<L, 2>,
        (res, _): (&StepResult, &StepRow<'_>),
        selected: &[ContactRecord],
        _: &[ZoneSummary],
    ) -> CliResult<()> {
        w.csv.write_contacts(&res.report, selected)
    }

    fn vtk_active(w: &PlaneWriters) -> bool {
        w.vtk.is_active()
    }

    fn vtk(
        w: &mut PlaneWriters,
        model: &LinearElasticModel,
        (t, selected, disp): (f64, &[ContactRecord], Option<&[[f64; 2]]>),
        fields: &[TractionField],
    ) -> CliResult<()> {
        w.vtk.write_step(t, selected, disp, model, fields)
    }

    fn reaction(_: &PlaneWriters) -> Option<[f64; 2]> {
        None
    }

    fn finish(
        mut w: PlaneWriters,
        (plots, pressure): (&Plots, PressureRecorder),
        study: &Study,
        dir: &Path,
        files: &mut Vec<String>,
    ) -> CliResult<(Vec<CurveSummary>, Vec<RigidMotionSummary>)> {
        w.csv.finish()?;
        let rigid = match w.rigid.take() {
            Some(r) => r.finish()?,
            None => Vec::new(),
        };
        files.extend(w.vtk.files());
        let curves = plots.finish(&study.plots, dir, files)?;
        let positions = positions(study);
        pressure.finish(|n| positions[n], files)?;
        Ok((curves, rigid))
    }
}
