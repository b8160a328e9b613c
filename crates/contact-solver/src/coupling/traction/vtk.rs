//! The interface files with the recovered traction: the point clouds of
//! [`write_interface_vtu`](crate::coupling::output::write_interface_vtu) (2D) and
//! [`write_interface_vtu_3d`](crate::coupling::output::write_interface_vtu_3d) (3D), each
//! point also carrying the [`TractionField`] of its zone at its node:
//!
//! | name | type | content |
//! |---|---|---|
//! | `pressure_field` | scalar | the recovered contact pressure `p` (`NaN`: no field for the zone) |
//! | `shear_field` | vector | the recovered tangential traction `[t₁, t₂, 0]` (`[t, 0, 0]` in 2D), local frame |

use super::TractionField;
use crate::coupling::output::{interface_model, interface_model_3d, write_vtk};
use crate::coupling::simulation::ContactRecord;
use crate::error::SolverError;
use std::path::Path;
use vtkio::model::{Attribute, DataSet, Piece, Vtk};

/// `(p, [t₁, t₂])` of `(zone, node)` from the fields (`NaN` when none covers it).
fn lookup(fields: &[TractionField], zone: usize, node: usize) -> (f64, [f64; 2]) {
    fields
        .iter()
        .find(|f| f.zone == zone)
        .and_then(|f| f.at(node))
        .unwrap_or((f64::NAN, [f64::NAN; 2]))
}

/// Appends `pressure_field` and `shear_field` of the points `(zone, node)` to the model.
fn push_fields(vtk: &mut Vtk, fields: &[TractionField], points: &[(usize, usize)]) {
    let values: Vec<(f64, [f64; 2])> = points.iter().map(|&(z, n)| lookup(fields, z, n)).collect();
    let p = Attribute::scalars("pressure_field", 1)
        .with_data(values.iter().map(|v| v.0).collect::<Vec<f64>>());
    let t = Attribute::vectors("shear_field").with_data(
        values
            .iter()
            .flat_map(|v| [v.1[0], v.1[1], 0.0])
            .collect::<Vec<f64>>(),
    );
    if let DataSet::UnstructuredGrid { pieces, .. } = &mut vtk.data {
        for piece in pieces {
            if let Piece::Inline(grid) = piece {
                grid.data.point.push(p.clone());
                grid.data.point.push(t.clone());
            }
        }
    }
}

/// [`write_interface_vtu`](crate::coupling::output::write_interface_vtu) with the recovered
/// traction of each record's zone (module docs).
///
/// # Errors
/// As [`write_interface_vtu`](crate::coupling::output::write_interface_vtu).
pub fn write_interface_vtu_with_traction(
    path: &Path,
    records: &[ContactRecord],
    displacements: Option<&[[f64; 2]]>,
    fields: &[TractionField],
) -> Result<(), SolverError> {
    let mut vtk = interface_model(records, displacements)?;
    let points: Vec<(usize, usize)> = records.iter().map(|c| (c.zone, c.node)).collect();
    push_fields(&mut vtk, fields, &points);
    write_vtk(path, vtk)
}

/// [`write_interface_vtu_3d`](crate::coupling::output::write_interface_vtu_3d) with the
/// recovered traction of each record's zone (module docs).
///
/// # Errors
/// As [`write_interface_vtu_3d`](crate::coupling::output::write_interface_vtu_3d).
pub fn write_interface_vtu_3d_with_traction(
    path: &Path,
    records: &[ContactRecord<3>],
    positions: &[[f64; 3]],
    displacements: Option<&[[f64; 3]]>,
    fields: &[TractionField],
) -> Result<(), SolverError> {
    let mut vtk = interface_model_3d(records, positions, displacements)?;
    let points: Vec<(usize, usize)> = records.iter().map(|c| (c.zone, c.node)).collect();
    push_fields(&mut vtk, fields, &points);
    write_vtk(path, vtk)
}
