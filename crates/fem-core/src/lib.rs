//! Finite-element core of `bipotential`: 3-node (P1) and 6-node (P2) triangles, plane
//! strain, plane stress and axisymmetry, sparse assembly and Cholesky factorisation.
//!
//! It knows nothing about contact. The contact solver sees a body only through the
//! `Structure` trait (in progress, issue 4).

#![warn(missing_docs)]

pub mod analytical;
pub mod error;
pub mod generate;
pub mod gmsh;
pub mod idealization;
pub mod material;
pub mod mesh;
pub mod vtk;

pub use error::FemError;
pub use idealization::Idealization;
pub use material::Material;
pub use mesh::{ElementKind, Mesh, Side};
pub mod element;
pub mod quadrature;
pub use element::{Element, Stress, Tri3, Tri6};
pub mod assembly;
pub mod dirichlet;
pub mod linear_solver;
pub mod model;
pub mod structure;
pub use dirichlet::{Component, DofMap, Supports};
pub use linear_solver::SpdSolver;
pub use model::{LinearElasticModel, Reaction, StressField, StressPoint, geostatic};
pub use structure::Structure;
