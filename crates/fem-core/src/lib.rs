//! Finite-element core of `bipotential`: linear elasticity on 2D and 3D meshes.
//!
//! What the crate holds:
//! - **Meshes** ([`mesh`]): one [`Mesh<D>`](Mesh) for 2D (triangles, quadrilaterals) and 3D
//!   ([`mesh::SolidMesh`]: tetrahedra, hexahedra) with regions, node sets and facet sets (edge
//!   or face sets); structured generators ([`generate`]: graded rectangles, the axisymmetric
//!   pile-in-soil domain); a Gmsh `.msh` 4.1 reader ([`gmsh`]); VTK `.vtu`/`.pvd` output for
//!   ParaView ([`vtk`]).
//! - **Elements** ([`element`]): one isoparametric [`Element`] trait for 2D and 3D with its
//!   kernels written once, and the catalogue — triangles [`Tri3`], [`Tri6`], quadrilaterals
//!   [`Quad4`], [`Quad8`], [`Quad9`] (plane strain, plane stress or axisymmetry,
//!   [`Idealization`]), tetrahedra and hexahedra ([`element::Tet4`], [`element::Tet10`],
//!   [`element::Hex8`], [`element::Hex20`]) — integrated with the rules of [`quadrature`], for
//!   an isotropic [`Material`].
//! - **Assembly and solution**: supports and the free/prescribed dof numbering
//!   ([`dirichlet`]), the sparsity pattern built once and refilled in place ([`assembly`]),
//!   and a sparse Cholesky solver whose symbolic analysis is done once per pattern
//!   ([`linear_solver`], [`SpdSolver`]).
//! - **The model** ([`model`]): one [`ElasticModel`] for both dimensions
//!   ([`LinearElasticModel`] in the plane, [`SolidModel`] in space) assembles and factors the
//!   reduced stiffness, applies loads, solves, and recovers stresses, strains and reactions.
//! - **Boundary fields** ([`boundary_mass`]): the consistent mass of a boundary's sides or
//!   faces, to recover a continuous traction from nodal forces.
//! - **The seam to the contact solver**: the [`Structure`] trait, implemented by
//!   [`ElasticModel`] and by users' own FE codes, with its optional capabilities
//!   [`Floating`] (rigid-body modes), [`Mass`] (inertia, for dynamics) and [`Nonlinear`]
//!   (internal forces and a state-dependent tangent, for nonlinear materials).
//! - **Dynamics** ([`dynamic`]): a model solved with `M̂ = M + hθC + h²θ²K`, for a
//!   velocity-level time scheme (the contact solver's Moreau–Jean).
//! - **Verification**: closed-form elasticity solutions ([`analytical`]).
//!
//! It knows nothing about contact. Errors are [`FemError`].

#![warn(missing_docs)]

pub mod analytical;
pub mod boundary_mass;
mod component;
mod convergence;
pub mod error;
pub mod generate;
pub mod gmsh;
pub mod idealization;
pub mod material;
pub mod mesh;
pub mod vtk;

pub use error::FemError;
pub use idealization::Idealization;
pub use material::{Material, MaterialParams};
pub use mesh::curve;
pub use mesh::{ElementKind, Facet, Mesh, Side};
pub mod element;
pub mod quadrature;
pub use element::{Element, Quad4, Quad8, Quad9, Stress, Tri3, Tri6};
pub mod assembly;
pub mod dirichlet;
pub mod dynamic;
pub mod linear_solver;
pub mod model;
pub mod ordering;
pub mod plastic;
pub mod rigid_modes;
pub mod solid;
pub mod space;
pub mod structure;
pub use dirichlet::{Component, DofMap, Supports};
pub use linear_solver::SpdSolver;
pub use model::{
    ElasticModel, LinearElasticModel, Reaction, SolidModel, StressField, StressPoint, geostatic,
    geostatic_3d,
};
pub use rigid_modes::{RigidBodyModes, RigidMode, RigidMotion};
pub use space::{Dim, Plane, Solid, Space};
pub use structure::{Floating, Mass, Nonlinear, Structure};

/// The `faer` this crate is built with (its sparse matrices and `MatMut` are in
/// [`Structure`]'s signatures): an implementer of [`Structure`] writes `fem_core::faer::…`
/// (or `bipotential::faer::…`) instead of adding `faer` to its own `Cargo.toml`, so the two
/// can never be different versions.
pub use faer;
