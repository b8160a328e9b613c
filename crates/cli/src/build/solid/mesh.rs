//! The mesh of a 3D scene: the box generator (graded grid lines along x, y and z, Kuhn's six
//! tetrahedra per cell) or a Gmsh 4.1 volume file (physical volumes as regions, physical
//! surfaces as face and node sets).

use super::super::checks::{at_least, fem, grading};
use super::super::mesh::{GmshPlan, interval};
use crate::error::{CliError, CliResult, KeyPath};
use crate::spec::Element;
use crate::spec3::MeshSpec3;
use fem_core::FemError;
use fem_core::generate::graded_points;
use fem_core::solid::generate::box_mesh;
use fem_core::solid::{SolidKind, SolidMesh};
use std::path::Path;

/// The most cells of a box (six tetrahedra each): 2e5 cells are 1.2e6 tetrahedra, beyond what a
/// scene run on a workstation solves in a useful time with a dense contact flexibility.
pub const MAX_BOX_CELLS: usize = 200_000;

/// A 3D mesh to build, its values checked.
pub(super) enum MeshPlan3 {
    /// The grid lines of a box and its element.
    Box([Vec<f64>; 3], SolidKind),
    /// A Gmsh file and the element order it must hold.
    Gmsh(GmshPlan),
}

/// The tetrahedron of a scene's element name.
pub(super) fn solid_kind(e: Element) -> SolidKind {
    match e {
        Element::P1 => SolidKind::Tet4,
        Element::P2 => SolidKind::Tet10,
    }
}

/// Name of a 3D element kind for messages.
pub fn solid_kind_name(k: SolidKind) -> &'static str {
    match k {
        SolidKind::Tet4 => "P1 (4-node tetrahedra)",
        SolidKind::Tet10 => "P2 (10-node tetrahedra)",
        SolidKind::Hex8 => "P1 (8-node hexahedra)",
        SolidKind::Hex20 => "P2 (20-node serendipity hexahedra)",
        _ => "elements of a kind this version of bipo does not name",
    }
}

/// Checks `[mesh]` (at `mp`) of a 3D scene.
pub(super) fn validate(mp: &KeyPath, spec: &MeshSpec3, base_dir: &Path) -> CliResult<MeshPlan3> {
    match spec {
        MeshSpec3::Box(b) => {
            let mut lines: [Vec<f64>; 3] = Default::default();
            let mut cells = 1usize;
            for (a, axis) in ["x", "y", "z"].into_iter().enumerate() {
                let range = interval(&mp.key(axis), b.ranges[a], axis)?;
                let np = mp.key(&format!("n{axis}"));
                let n = at_least(&np, b.cells[a], 1)?;
                cells = cells.saturating_mul(n);
                if cells > MAX_BOX_CELLS {
                    return Err(CliError::at(
                        &np,
                        format!(
                            "`{np}` = {n}: the box would have more than {MAX_BOX_CELLS} cells \
                             (nx·ny·nz, six tetrahedra each); use fewer cells or a graded grid"
                        ),
                    ));
                }
                let gp = mp.key(&format!("grading_{axis}"));
                let g = grading(&gp, b.gradings[a])?;
                lines[a] = graded_points(range[0], range[1], n, g).map_err(|e| match e {
                    FemError::InvalidParameter { name: "ratio", .. } => fem(&gp.key("ratio"), e),
                    e => fem(&mp.key(axis), e),
                })?;
            }
            Ok(MeshPlan3::Box(lines, solid_kind(b.element)))
        }
        MeshSpec3::Gmsh { file, element } => Ok(MeshPlan3::Gmsh(GmshPlan::new(
            mp, file, *element, base_dir,
        )?)),
    }
}

/// Generates or reads the mesh of `plan`.
pub(super) fn build(mp: &KeyPath, plan: MeshPlan3) -> CliResult<SolidMesh> {
    match plan {
        MeshPlan3::Box([xs, ys, zs], kind) => box_mesh(&xs, &ys, &zs, kind).map_err(|e| fem(mp, e)),
        MeshPlan3::Gmsh(g) => g.read(mp),
    }
}
