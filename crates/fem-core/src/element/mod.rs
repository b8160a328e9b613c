//! Elements: one isoparametric [`Element`] trait for 2D and 3D, and the built-in catalogue,
//! one file per element.
//!
//! | element | dim | nodes | stiffness rule | file |
//! |---|---|---|---|---|
//! | [`Tri3`] | 2 | 3 | centroid (3 points in axisymmetry) | `tri3.rs` |
//! | [`Tri6`] | 2 | 6 | 3 points (6 in axisymmetry) | `tri6.rs` |
//! | [`Quad4`] | 2 | 4 | full 2×2 Gauss | `quad4.rs` |
//! | [`Quad8`] | 2 | 8 (serendipity) | full 3×3 Gauss | `quad8.rs` |
//! | [`Quad9`] | 2 | 9 (Lagrange) | full 3×3 Gauss | `quad9.rs` |
//! | [`Tet4`] | 3 | 4 | centroid | `tet4.rs` |
//! | [`Tet10`] | 3 | 10 | 4 points (degree 3 when curved) | `tet10.rs` |
//! | [`Hex8`] | 3 | 8 | full 2×2×2 Gauss | `hex8.rs` |
//! | [`Hex20`] | 3 | 20 (serendipity) | full 3×3×3 Gauss | `hex20.rs` |
//!
//! An element supplies what is its own — reference shape functions and their derivatives,
//! quadrature rules and topology ([`Topology`]: sides or faces in local numbering, VTK cell
//! type, Gmsh element type) — and receives the kernels (stiffness, body force, initial-stress
//! force, stresses at the quadrature points, consistent and lumped mass) from one
//! implementation written once for any dimension ([`kernel`]). It may override any kernel.
//!
//! "Which dofs an element touches" lives in the mesh and the dof map; an element only computes
//! local arrays from its node coordinates, into buffers the caller reuses. Local dof order:
//! `(u_0, v_0[, w_0], u_1, …)`. The kinematic setting of a kernel is
//! [`Space::Setting`]: the [`crate::Idealization`] in 2D (plane strain, plane stress with its
//! thickness, axisymmetry with its `r` weight per radian and hoop strain `u_r / r`), `()` in 3D.
//!
//! # Examples
//! A user's element is any type that implements the trait; here a Quad4 with a reduced
//! one-point rule (hourglass-prone, for illustration), taking every kernel from the defaults:
//! ```
//! use fem_core::element::{Element, Quad4, QuadPoint, Topology};
//! use fem_core::{Idealization, Material};
//!
//! #[derive(Debug)]
//! struct OnePointQuad;
//! impl Element<2> for OnePointQuad {
//!     fn node_count(&self) -> usize { 4 }
//!     fn shape(&self, xi: [f64; 2], n: &mut [f64], dn: &mut [[f64; 2]]) {
//!         Quad4.shape(xi, n, dn)
//!     }
//!     fn stiffness_rule(&self, _: &Idealization, _: &[[f64; 2]]) -> &[QuadPoint<2>] {
//!         &[([0.0, 0.0], 4.0)]
//!     }
//!     fn load_rule(&self, s: &Idealization) -> &[QuadPoint<2>] { Quad4.load_rule(s) }
//!     fn topology(&self) -> Topology { Quad4.topology() }
//! }
//! let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
//! let material = Material::new(1.0, 0.25, 0.0)?;
//! let mut k_e = nalgebra::DMatrix::zeros(0, 0);
//! OnePointQuad.stiffness_into(0, &square, &material, &Idealization::PlaneStrain, &mut k_e)?;
//! assert_eq!(k_e.shape(), (8, 8));
//! # Ok::<(), fem_core::FemError>(())
//! ```

mod by_region;
pub mod hex20;
pub mod hex8;
pub(crate) use by_region::RegionElements;
pub mod kernel;
pub mod quad4;
pub mod quad8;
pub mod quad9;
pub mod tet10;
pub mod tet4;
pub mod tri3;
pub mod tri6;

#[cfg(test)]
mod tests;

pub use hex8::Hex8;
pub use hex20::Hex20;
pub use quad4::Quad4;
pub use quad8::Quad8;
pub use quad9::Quad9;
pub use tet4::Tet4;
pub use tet10::Tet10;
pub use tri3::Tri3;
pub use tri6::Tri6;

use crate::error::FemError;
use crate::material::Material;
use crate::space::{Dim, Space};
use nalgebra::DMatrix;
use std::fmt::Debug;

/// Largest number of nodes an element may have for the default kernels (their scratch
/// arrays are sized by it; a 27-node hexahedron fits).
pub const MAX_NODES: usize = 27;

/// Stress (or strain) components in 2D: `(xx, yy, xy, zz)` in the plane — `zz` is the
/// out-of-plane stress `ν(σ_xx + σ_yy)` in plane strain and 0 in plane stress — and
/// `(rr, zz, rz, θθ)` in axisymmetry.
pub type Stress = [f64; 4];

/// Stress (or strain) components in 3D: `(xx, yy, zz, xy, yz, zx)` (strains with tensor
/// shears `ε_xy`, not `γ_xy`).
pub type Stress3 = [f64; 6];

/// A quadrature point `ξ` of the reference element and its weight.
pub type QuadPoint<const D: usize> = ([f64; D], f64);

/// The kinematic setting of dimension `D` ([`Space::Setting`]).
pub type Setting<const D: usize> = <Dim<D> as Space>::Setting;

/// The Voigt stress of dimension `D` ([`Space::Stress`]).
pub type VoigtStress<const D: usize> = <Dim<D> as Space>::Stress;

/// The topology of an element: what the mesh, the readers and the writers need.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Topology {
    /// Number of corner (vertex) nodes; they come first in the local numbering.
    pub corners: usize,
    /// The sides (2D) or faces (3D) in local numbering. A 2D side runs from its first corner to
    /// its second with the body on its left, mid-side node last (`[a, b]` or `[a, b, m]`). A
    /// 3D face lists its corners counter-clockwise seen from outside, then its mid-edge nodes
    /// for the edges (c0–c1, c1–c2, …): the node order of a 3/6-node triangle or a 4/8-node
    /// quadrilateral.
    pub sides: &'static [&'static [usize]],
    /// The VTK cell type (5 triangle, 22 quadratic triangle, 9 quad, 23 quadratic quad,
    /// 28 biquadratic quad, 10 tetra, 24 quadratic tetra, 12 hexahedron, 25 quadratic
    /// hexahedron).
    pub vtk_cell: u8,
    /// The Gmsh element type (2, 9, 3, 16, 10, 4, 11, 5, 17).
    pub gmsh_type: u32,
}

/// An isoparametric finite element of linear elasticity in dimension `D` (2 or 3).
///
/// Required: the node count, the reference shape functions and their derivatives, the
/// quadrature rules and the topology. Every kernel has a default written once for any `D` in
/// [`kernel`]; an element may override one (e.g. a B-bar stiffness).
///
/// Coordinates and rules are in reference coordinates `ξ ∈ ℝ^D`; the element's node order is
/// that of its [`Topology`].
pub trait Element<const D: usize>: Debug + Send + Sync
where
    Dim<D>: Space,
{
    /// Number of nodes (at most [`MAX_NODES`] for the default kernels).
    fn node_count(&self) -> usize;

    /// Shape values `n[i] = N_i(ξ)` and reference derivatives `dn[i][a] = ∂N_i/∂ξ_a` at `ξ`
    /// (the first `node_count()` entries of each).
    fn shape(&self, xi: [f64; D], n: &mut [f64], dn: &mut [[f64; D]]);

    /// The rule of the stiffness (and, unless [`Element::stress_rule`] says otherwise, of the
    /// stresses); it may depend on the setting and on the node coordinates (a curved element).
    fn stiffness_rule(&self, setting: &Setting<D>, coords: &[[f64; D]]) -> &[QuadPoint<D>];

    /// A rule for loads (exact for `N` times the setting's weight on straight elements).
    fn load_rule(&self, setting: &Setting<D>) -> &[QuadPoint<D>];

    /// The rule at whose points [`Element::stresses_into`] reports; the stiffness rule by
    /// default.
    fn stress_rule(&self, setting: &Setting<D>, coords: &[[f64; D]]) -> &[QuadPoint<D>] {
        self.stiffness_rule(setting, coords)
    }

    /// A rule for the mass `∫ ρ NᵀN`; the load rule by default.
    fn mass_rule(&self, setting: &Setting<D>) -> &[QuadPoint<D>] {
        self.load_rule(setting)
    }

    /// Sides or faces, VTK and Gmsh types.
    fn topology(&self) -> Topology;

    /// The element stiffness `K_e = ∫ Bᵀ D B w dΩ` (`w` = 1, the thickness or `r`), of size
    /// `Dn × Dn`, written into `k_e` (resized if needed). `element` is only used in errors.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] if the Jacobian is not positive at a quadrature point;
    /// [`FemError::Unsupported`] for more than [`MAX_NODES`] nodes.
    fn stiffness_into(
        &self,
        element: usize,
        coords: &[[f64; D]],
        material: &Material,
        setting: &Setting<D>,
        k_e: &mut DMatrix<f64>,
    ) -> Result<(), FemError> {
        kernel::stiffness_into(self, element, coords, material, setting, k_e)
    }

    /// Adds `f_e += ∫ Nᵀ b w dΩ` for a body force density `b(x)` (force per volume).
    ///
    /// # Errors
    /// As for the stiffness.
    fn body_force_into(
        &self,
        element: usize,
        coords: &[[f64; D]],
        setting: &Setting<D>,
        b: &dyn Fn([f64; D]) -> [f64; D],
        f_e: &mut [f64],
    ) -> Result<(), FemError> {
        kernel::body_force_into(self, element, coords, setting, b, f_e)
    }

    /// Adds the internal force of an initial stress field, `f_e −= ∫ Bᵀ σ₀ w dΩ`, so that the
    /// equilibrium `K u = f_ext + f_e` accounts for `σ₀(x)` (components as [`VoigtStress`]).
    ///
    /// # Errors
    /// As for the stiffness.
    fn initial_stress_force_into(
        &self,
        element: usize,
        coords: &[[f64; D]],
        setting: &Setting<D>,
        sigma_0: &dyn Fn([f64; D]) -> VoigtStress<D>,
        f_e: &mut [f64],
    ) -> Result<(), FemError> {
        kernel::initial_stress_force_into(self, element, coords, setting, sigma_0, f_e)
    }

    /// Appends the stresses `σ = D ε(u_e)` (add `σ₀` yourself) at the points of
    /// [`Element::stress_rule`], with their positions.
    ///
    /// # Errors
    /// As for the stiffness.
    fn stresses_into(
        &self,
        element: usize,
        coords: &[[f64; D]],
        material: &Material,
        setting: &Setting<D>,
        u_e: &[f64],
        out: &mut Vec<([f64; D], VoigtStress<D>)>,
    ) -> Result<(), FemError> {
        kernel::stresses_into(self, element, coords, material, setting, u_e, out)
    }

    /// The consistent mass `M_e = ∫ ρ NᵀN w dΩ` (`Dn × Dn`, the same block on every
    /// component) into `m_e` (resized if needed), with the mass density `density`.
    ///
    /// # Errors
    /// As for the stiffness.
    fn mass_into(
        &self,
        element: usize,
        coords: &[[f64; D]],
        density: f64,
        setting: &Setting<D>,
        m_e: &mut DMatrix<f64>,
    ) -> Result<(), FemError> {
        kernel::mass_into(self, element, coords, density, setting, m_e)
    }

    /// A lumped (diagonal) mass, one entry per dof, by HRZ diagonal scaling (Hinton, Rock
    /// & Zienkiewicz 1976): the diagonal of the consistent mass scaled so that it sums to the
    /// element's mass. Row sums are not used because they vanish or turn negative at the
    /// corners of quadratic elements (Tri6: 0, Tet10 and Quad8/Hex20: negative); HRZ is positive
    /// for every element and keeps the total mass exact.
    ///
    /// # Errors
    /// As for the stiffness.
    ///
    /// # Panics
    /// If `m_e.len() != D · node_count()`.
    #[track_caller]
    fn lumped_mass_into(
        &self,
        element: usize,
        coords: &[[f64; D]],
        density: f64,
        setting: &Setting<D>,
        m_e: &mut [f64],
    ) -> Result<(), FemError> {
        kernel::lumped_mass_into(self, element, coords, density, setting, m_e)
    }
}
