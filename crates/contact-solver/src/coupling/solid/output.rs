//! The interface of a 3D step for ParaView: one VTK point per contact candidate, at its node's
//! deformed position, with the record's local reactions, gap, slip and β
//! ([`write_interface_vtu_3d`]); a time series of them goes through
//! [`InterfaceSeries::write_step_with`](crate::coupling::output::InterfaceSeries::write_step_with).

use super::simulation::SolidContactRecord;
use crate::coupling::output::{vertex_cloud, write_vtk};
use crate::error::SolverError;
use std::path::Path;
use vtkio::model::{Attribute, Attributes, Vtk};

/// Writes the contact records of a 3D step as a VTK unstructured grid of vertices (`.vtu`,
/// ASCII XML). `positions[n]` is node `n`'s position, `displacements[n]` its displacement (the
/// points are then at the deformed positions, and `u` is written).
///
/// Point data:
///
/// | name | type | content |
/// |---|---|---|
/// | `active` | `UInt8` | 1 if the contact is closed ([`SolidContactRecord::closed`], as the CSV outputs) |
/// | `zone`, `node` | `UInt64` | zone index, contactor node |
/// | `area`, `gap`, `pressure`, `beta` | scalar | as in [`SolidContactRecord`] |
/// | `r_local` | vector | `[r_n, r_t1, r_t2]` |
/// | `slip` | vector | `[slip_t1, slip_t2, 0]`, the step's slip increment |
/// | `force` | vector | the contact force on the contactor node, global axes |
/// | `candidate` | `UInt8` | 1 if the contact was in the step's reduced problem |
/// | `normal`, `t1`, `t2` | vector | the contact's frame |
/// | `u` | vector | the node's displacement (only with `displacements`) |
///
/// # Errors
/// - [`SolverError::SizeMismatch`] if a record's node has no entry in `positions` or
///   `displacements`;
/// - [`SolverError::Io`] if the file cannot be written.
pub fn write_interface_vtu_3d(
    path: &Path,
    records: &[SolidContactRecord],
    positions: &[[f64; 3]],
    displacements: Option<&[[f64; 3]]>,
) -> Result<(), SolverError> {
    write_vtk(path, interface_model_3d(records, positions, displacements)?)
}

/// The VTK model of [`write_interface_vtu_3d`].
pub(crate) fn interface_model_3d(
    records: &[SolidContactRecord],
    positions: &[[f64; 3]],
    displacements: Option<&[[f64; 3]]>,
) -> Result<Vtk, SolverError> {
    let max_node = records.iter().map(|c| c.candidate.node).max();
    for (what, len) in [
        ("positions", Some(positions.len())),
        ("displacements", displacements.map(<[_]>::len)),
    ] {
        if let (Some(len), Some(max_node)) = (len, max_node)
            && max_node >= len
        {
            return Err(SolverError::SizeMismatch {
                what,
                expected: max_node + 1,
                found: len,
            });
        }
    }
    let u = |node: usize| displacements.map_or([0.0; 3], |u| u[node]);
    let points: Vec<f64> = records
        .iter()
        .flat_map(|c| {
            let (x, d) = (positions[c.candidate.node], u(c.candidate.node));
            [x[0] + d[0], x[1] + d[1], x[2] + d[2]]
        })
        .collect();
    let scalar = |name: &str, f: &dyn Fn(&SolidContactRecord) -> f64| {
        Attribute::scalars(name, 1).with_data(records.iter().map(f).collect::<Vec<f64>>())
    };
    let vector = |name: &str, f: &dyn Fn(&SolidContactRecord) -> [f64; 3]| {
        Attribute::vectors(name).with_data(records.iter().flat_map(f).collect::<Vec<f64>>())
    };
    let mut data = Attributes::new();
    data.point = vec![
        Attribute::scalars("active", 1).with_data(
            records
                .iter()
                .map(|c| u8::from(c.closed))
                .collect::<Vec<u8>>(),
        ),
        Attribute::scalars("zone", 1).with_data(
            records
                .iter()
                .map(|c| c.candidate.zone as u64)
                .collect::<Vec<u64>>(),
        ),
        Attribute::scalars("node", 1).with_data(
            records
                .iter()
                .map(|c| c.candidate.node as u64)
                .collect::<Vec<u64>>(),
        ),
        scalar("area", &|c| c.candidate.area),
        scalar("gap", &|c| c.gap),
        scalar("pressure", &|c| c.pressure()),
        scalar("beta", &|c| c.beta),
        vector("r_local", &|c| c.r),
        vector("slip", &|c| [c.slip[0], c.slip[1], 0.0]),
        vector("force", &|c| c.force()),
        Attribute::scalars("candidate", 1).with_data(
            records
                .iter()
                .map(|c| u8::from(c.active))
                .collect::<Vec<u8>>(),
        ),
        vector("normal", &|c| c.candidate.normal()),
        vector("t1", &|c| c.candidate.frame()[1]),
        vector("t2", &|c| c.candidate.frame()[2]),
    ];
    if displacements.is_some() {
        data.point.push(vector("u", &|c| u(c.candidate.node)));
    }
    Ok(vertex_cloud(points, data))
}
