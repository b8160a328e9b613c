//! What a scene reads differently in 2D and 3D, in one place: the trait [`SceneDim`], for
//! `Dim<2>` and `Dim<3>`. The passes are written once over the dimension `D` and ask it for
//! a load's vectors (two numbers or three; pressures in 3D), the boundary sets tractions name
//! (edge sets, face sets), the Gmsh reader and element names, the model's constructor (the 2D
//! idealisation and `floating`) and the geostatic stress.

use super::checks::{finite, finite2, kind_name, list_names};
use super::solid::solid_kind_name;
use super::study::LoadKind;
use crate::error::{CliError, CliResult, KeyPath};
use crate::raw::{RawLoad, triple};
use crate::spec::{Element, LoadSpec};
use crate::spec3::{Coords, LoadSpec3};
use fem_core::model::ModelSpace;
use fem_core::solid::{SolidKind, SolidMesh, SolidModel, geostatic_3d};
use fem_core::{Dim, ElasticModel, ElementKind, FemError, Idealization, LinearElasticModel};
use fem_core::{Material, Mesh, StressField, Supports};
use std::path::Path;

/// What a scene reads differently in each dimension (see the module docs).
pub(crate) trait SceneDim<const D: usize>: ModelSpace<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// What the model is built in besides its mesh, materials and supports.
    type Options;
    /// The 2D idealisation among the options (none in 3D).
    fn idealization(options: &Self::Options) -> Option<Idealization>;
    /// A load's set (where it has one) and kind (its set or node not yet looked up), its type,
    /// keys and values checked.
    fn load(l: &RawLoad, p: &KeyPath) -> CliResult<(Option<String>, LoadKind<D>)>;
    /// Checks that the boundary set a traction or pressure names exists.
    fn boundary_set(path: &KeyPath, mesh: &Mesh<D>, set: &str) -> CliResult<()>;
    /// The model.
    fn model(
        mesh: Mesh<D>,
        options: &Self::Options,
        materials: &[(u32, Material)],
        supports: Supports,
    ) -> Result<ElasticModel<D>, FemError>;
    /// The geostatic initial stress (`gamma`, `k0`, the surface's height).
    fn geostatic(gamma: f64, k0: f64, z: f64) -> StressField<D>;
    /// Reads a Gmsh 4.1 file of this dimension.
    fn read_msh(path: &Path) -> Result<Mesh<D>, FemError>;
    /// Whether `mesh`'s elements have the order `e` names (`mesh.element` of a Gmsh file names
    /// the order, the file the shape), and their name for messages.
    fn element_order(e: Element, mesh: &Mesh<D>) -> (bool, &'static str);
    /// Adds a uniform traction on the boundary set `set` (edges, faces) to the model's loads.
    ///
    /// # Errors
    /// The model's, for a set it does not have.
    fn traction(model: &mut ElasticModel<D>, set: &str, t: [f64; D]) -> Result<(), FemError>;
    /// Adds a pressure `p` (positive into the body) on the face set `set`.
    ///
    /// # Errors
    /// The model's, for a set it does not have; in 2D, always (a 2D scene has no pressure).
    fn pressure(model: &mut ElasticModel<D>, set: &str, p: f64) -> Result<(), FemError>;
}

impl SceneDim<2> for Dim<2> {
    /// The idealisation and `[analysis] floating`.
    type Options = (Idealization, bool);

    fn idealization(options: &Self::Options) -> Option<Idealization> {
        Some(options.0)
    }

    fn load(l: &RawLoad, p: &KeyPath) -> CliResult<(Option<String>, LoadKind<2>)> {
        let vp = p.key("value");
        Ok(match l.resolve(p)? {
            LoadSpec::Traction { set, value } => (
                Some(set),
                LoadKind::Traction(String::new(), finite2(&vp, value)?),
            ),
            LoadSpec::NodalForce { set, value } => {
                (Some(set), LoadKind::Nodal(Vec::new(), finite2(&vp, value)?))
            }
            LoadSpec::Resultant { set, value } => {
                (Some(set), LoadKind::Resultant(0, finite2(&vp, value)?))
            }
            LoadSpec::BodyForce { value } => (None, LoadKind::Body(finite2(&vp, value)?)),
            LoadSpec::Gravity => (None, LoadKind::Gravity),
        })
    }

    fn boundary_set(path: &KeyPath, mesh: &Mesh, set: &str) -> CliResult<()> {
        mesh.edge_set(set).map(|_| ()).map_err(|_| {
            CliError::at(
                path,
                format!(
                    "`{path}` = \"{set}\": the mesh has no edge set of that name (edge sets: {})",
                    list_names(mesh.edge_set_names())
                ),
            )
        })
    }

    fn model(
        mesh: Mesh,
        &(idealization, floating): &Self::Options,
        materials: &[(u32, Material)],
        supports: Supports,
    ) -> Result<LinearElasticModel, FemError> {
        if floating {
            LinearElasticModel::floating(mesh, idealization, materials, supports)
        } else {
            LinearElasticModel::new(mesh, idealization, materials, supports)
        }
    }

    fn geostatic(gamma: f64, k0: f64, z: f64) -> StressField<2> {
        fem_core::geostatic(gamma, k0, z)
    }

    fn read_msh(path: &Path) -> Result<Mesh, FemError> {
        fem_core::gmsh::read_msh(path)
    }

    /// `P1`: linear triangles or quadrilaterals, `P2`: quadratic ones.
    fn element_order(e: Element, mesh: &Mesh) -> (bool, &'static str) {
        let k = mesh.kind();
        let order = match e {
            Element::P1 => matches!(k, ElementKind::Tri3 | ElementKind::Quad4),
            Element::P2 => matches!(
                k,
                ElementKind::Tri6 | ElementKind::Quad8 | ElementKind::Quad9
            ),
        };
        (order, kind_name(k))
    }

    fn traction(model: &mut LinearElasticModel, set: &str, t: [f64; 2]) -> Result<(), FemError> {
        model.add_edge_traction(set, |_| t)
    }

    /// Refused when a 2D scene is read: a pressure is a load of a 3D scene.
    fn pressure(_: &mut LinearElasticModel, _: &str, p: f64) -> Result<(), FemError> {
        Err(FemError::InvalidParameter {
            name: "pressure",
            value: p,
            expected: "no pressure in a 2D scene (a traction on an edge set)",
        })
    }
}

impl SceneDim<3> for Dim<3> {
    /// Nothing: a 3D scene has no idealisation and does not float yet.
    type Options = ();

    fn idealization(_: &()) -> Option<Idealization> {
        None
    }

    fn load(l: &RawLoad, p: &KeyPath) -> CliResult<(Option<String>, LoadKind<3>)> {
        let vp = p.key("value");
        let v3 = |c: &Coords| -> CliResult<[f64; 3]> {
            let v = triple(&vp, c)?;
            for (k, x) in v.iter().enumerate() {
                finite(&vp.index(k), *x)?;
            }
            Ok(v)
        };
        Ok(match l.resolve_3d(p)? {
            LoadSpec3::Traction { set, value } => {
                (Some(set), LoadKind::Traction(String::new(), v3(&value)?))
            }
            LoadSpec3::Pressure { set, value } => (
                Some(set),
                LoadKind::Pressure(String::new(), finite(&vp, value)?),
            ),
            LoadSpec3::NodalForce { set, value } => {
                (Some(set), LoadKind::Nodal(Vec::new(), v3(&value)?))
            }
            LoadSpec3::Resultant { set, value } => (Some(set), LoadKind::Resultant(0, v3(&value)?)),
            LoadSpec3::BodyForce { value } => (None, LoadKind::Body(v3(&value)?)),
            LoadSpec3::Gravity => (None, LoadKind::Gravity),
        })
    }

    fn boundary_set(path: &KeyPath, mesh: &SolidMesh, set: &str) -> CliResult<()> {
        mesh.face_set(set).map(|_| ()).map_err(|_| {
            CliError::at(
                path,
                format!(
                    "`{path}` = \"{set}\": the mesh has no face set of that name (face sets, the \
                     physical surfaces: {})",
                    list_names(mesh.facet_set_names())
                ),
            )
        })
    }

    fn model(
        mesh: SolidMesh,
        _: &(),
        materials: &[(u32, Material)],
        supports: Supports,
    ) -> Result<SolidModel, FemError> {
        SolidModel::new(mesh, materials, supports)
    }

    fn geostatic(gamma: f64, k0: f64, z: f64) -> StressField<3> {
        geostatic_3d(gamma, k0, z)
    }

    fn read_msh(path: &Path) -> Result<SolidMesh, FemError> {
        fem_core::solid::gmsh::read_msh_3d(path)
    }

    /// `P1`: Tet4 or Hex8, `P2`: Tet10 or Hex20.
    fn element_order(e: Element, mesh: &SolidMesh) -> (bool, &'static str) {
        let k = mesh.kind();
        let order = match e {
            Element::P1 => matches!(k, SolidKind::Tet4 | SolidKind::Hex8),
            Element::P2 => matches!(k, SolidKind::Tet10 | SolidKind::Hex20),
        };
        (order, solid_kind_name(k))
    }

    fn traction(model: &mut SolidModel, set: &str, t: [f64; 3]) -> Result<(), FemError> {
        model.add_face_traction(set, |_, _| t)
    }

    fn pressure(model: &mut SolidModel, set: &str, p: f64) -> Result<(), FemError> {
        model.add_face_traction(set, |_, n| n.map(|c| -p * c))
    }
}
