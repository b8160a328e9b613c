//! 3D linear elasticity on tetrahedral meshes: the mesh ([`SolidMesh`]), the P1 and P2
//! tetrahedra ([`Tet4`], [`Tet10`]), their quadrature, structured generators
//! ([`generate`]), a Gmsh `.msh` 4.1 reader ([`gmsh`]; VTK output is
//! [`crate::vtk::write_vtu_3d`]), and the name [`SolidModel`] of the one model
//! ([`crate::model::ElasticModel`]) in 3D, which implements [`Structure<3>`](crate::Structure).
//!
//! The pieces follow the 2D ones: the sparsity pattern and the fill-reducing ordering are
//! computed once per dof numbering ([`crate::assembly::Pattern`], [`crate::SpdSolver`]), the
//! values are refilled and refactored in place, and supports are the same [`crate::Supports`]
//! with [`crate::Component::Z`].

pub mod generate;
/// The Gmsh reader of both dimensions ([`gmsh::read_msh_3d`] reads a 3D mesh).
pub use crate::gmsh;
/// The mesh of both dimensions ([`SolidMesh`] is `Mesh<3>`).
pub use crate::mesh;
pub mod quadrature;
pub mod revolve;

pub use crate::element::{Stress3, Tet4, Tet10};
pub use crate::{SolidModel, geostatic_3d};
pub use mesh::{Face, SolidKind, SolidMesh, TET_EDGES, triangle_shape};

/// An initial stress field `σ₀(x)` in 3D: [`crate::StressField`] with `D = 3`.
pub type StressField3 = crate::StressField<3>;

/// A stress at a point in 3D: [`crate::StressPoint`] with `D = 3`.
pub type StressPoint3 = crate::StressPoint<3>;
pub use revolve::{Revolved, revolve};
