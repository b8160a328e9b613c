//! The [`Structure`] trait: everything the contact solver may know about a body, and the
//! optional capability [`Floating`] of a body that only contact holds.

use crate::error::FemError;
use crate::idealization::Idealization;
use crate::rigid_modes::RigidBodyModes;
use faer::MatMut;
use faer::sparse::SparseColMatRef;

/// A linear(ised) structure seen from the contact solver, in dimension `D`: 2 (the default:
/// plane strain, plane stress or axisymmetry, e.g. [`LinearElasticModel`](crate::LinearElasticModel))
/// or 3 (e.g. [`SolidModel`](crate::solid::SolidModel)). Positions, dofs and displacements of a
/// node have `D` components.
///
/// The solver works on the **free dofs** only (prescribed dofs are eliminated). Contact forces
/// enter as external nodal forces on the contact nodes' free dofs: with `H` the map from free
/// dofs to the local contact frames, the displacement under contact reactions `r` is
/// `u = u_free + K⁻¹ Hᵀ r`, where `u_free` is the response to the current loads without
/// contact ([`Structure::free_response_into`]) and the flexibility `F* = H K⁻¹ Hᵀ` (seed 5.39)
/// is built from [`Structure::solve_many_in_place`]. Nothing else is needed, so any FE code
/// (or a hand-written model) can implement it; fem-core's
/// [`LinearElasticModel`](crate::model::LinearElasticModel) is one implementation.
///
/// # What to implement
/// The **required** methods are what every structure has: its dofs
/// ([`dof_count`](Self::dof_count)), its nodes ([`node_count`](Self::node_count),
/// [`node_position`](Self::node_position), [`node_dofs`](Self::node_dofs),
/// [`prescribed_displacement`](Self::prescribed_displacement)), solves with its factorised
/// stiffness ([`solve_many_in_place`](Self::solve_many_in_place)), its free response to the
/// loads ([`free_response_into`](Self::free_response_into)) and a version of its stiffness
/// ([`stiffness_version`](Self::stiffness_version)). Everything else is **provided**, with a
/// default that is the honest answer for a structure that does not override it:
///
/// | method | default | override when |
/// |---|---|---|
/// | [`solve_in_place`](Self::solve_in_place) | one column through `solve_many_in_place` | a single solve is cheaper alone |
/// | [`idealization`](Self::idealization) | plane strain (unit weight) | 2D plane stress or axisymmetry (never asked in 3D) |
/// | [`outward_normal`](Self::outward_normal) | `None` (not known) | the boundary normals are at hand |
/// | [`stiffness_matrix`](Self::stiffness_matrix) | `None` (not assembled) | `K` is assembled (the active-set path needs it) |
/// | [`floating`](Self::floating) | `None` (`K` positive definite) | supports leave rigid-body modes |
///
/// Named node sets (a contactor surface) are not asked by the solver: the zones name their
/// nodes by index, so a model keeps its sets itself (fem-core's models read them from their
/// mesh, `Mesh::node_set`).
///
/// # Floating bodies
/// A structure whose supports leave rigid-body modes (a body that only contact holds) returns
/// itself from [`Structure::floating`] as a [`Floating`]: its modes `R` (`K R = 0`) and the
/// load along them (`Rᵀ f`) come together, so a structure cannot offer one without the other.
/// Its solves then apply a **generalized inverse** `K⁺` (symmetric, `K K⁺ b = b` for every
/// balanced `b`, `Rᵀ b = 0`), and [`Structure::free_response_into`] returns `K⁺ f` whether `f`
/// is balanced or not: the contact solver adds the rigid motion `R α` and makes the contact
/// reactions balance `Rᵀ f`. A structure without modes (the default) keeps `K⁺ = K⁻¹`.
///
/// The pair is one capability, reached through one method, rather than two methods with
/// defaults, because that is what both sides need: a user's FE code implements the two
/// methods of [`Floating`] and one line here (`Some(self)`), and cannot return modes while
/// forgetting their load (a silent zero load would be a wrong answer); the solver asks one
/// question and gets both.
///
/// # Capabilities to come
/// The same shape will carry what a time scheme or a nonlinear material needs, each an
/// optional capability reached by one provided method with the default `None`, so that a
/// structure implements only what it has: the **mass** matrix (for dynamics, e.g. Moreau–Jean:
/// solves with `M + h² θ K` and products with `M`) and a **state-dependent tangent** with its
/// internal forces (plasticity, large strain: the tangent stiffness and `f_int(u)` at the
/// current state, after which [`stiffness_version`](Self::stiffness_version) changes). They are
/// not in the trait yet because no implementation backs them.
///
/// # Examples
/// A single spring `k` on one node along `x` (the `y` component supported): the smallest
/// structure, with the required methods only.
/// ```
/// use fem_core::{FemError, Structure};
/// use fem_core::faer::MatMut;
/// struct Spring { k: f64, f: f64 }
/// impl Structure for Spring {
///     fn dof_count(&self) -> usize { 1 }
///     fn node_count(&self) -> usize { 1 }
///     fn node_position(&self, _: usize) -> [f64; 2] { [0.0, 0.0] }
///     fn node_dofs(&self, _: usize) -> [Option<usize>; 2] { [Some(0), None] }
///     fn prescribed_displacement(&self, _: usize) -> [f64; 2] { [0.0, 0.0] }
///     fn solve_many_in_place(&self, mut rhs: MatMut<'_, f64>) -> Result<(), FemError> {
///         for c in 0..rhs.ncols() { rhs[(0, c)] /= self.k; }
///         Ok(())
///     }
///     fn free_response_into(&self, factor: f64, u: &mut [f64]) -> Result<(), FemError> {
///         u[0] = factor * self.f;
///         self.solve_in_place(u)
///     }
///     fn stiffness_version(&self) -> u64 { 0 }
/// }
/// let s = Spring { k: 4.0, f: 2.0 };
/// let mut u = [0.0];
/// s.free_response_into(1.0, &mut u)?;
/// assert_eq!(u, [0.5]); // f / k, through the provided `solve_in_place`
/// assert!(s.floating().is_none() && s.stiffness_matrix().is_none());
/// # Ok::<(), FemError>(())
/// ```
pub trait Structure<const D: usize = 2> {
    /// Number of free dofs (the size of `K`).
    fn dof_count(&self) -> usize;

    /// Number of nodes.
    fn node_count(&self) -> usize;

    /// Coordinates of a node in the reference configuration: `(x, y)` or `(r, z)` in 2D,
    /// `(x, y, z)` in 3D.
    ///
    /// # Panics
    /// If `node >= node_count()`.
    fn node_position(&self, node: usize) -> [f64; D];

    /// The free-dof indices of a node's `D` components; `None` for a component eliminated by
    /// a support. Several nodes may share a dof (the nodes of a tie, `Supports::tie`); the
    /// contact solver sums what they contribute.
    ///
    /// # Panics
    /// If `node >= node_count()`.
    fn node_dofs(&self, node: usize) -> [Option<usize>; D];

    /// The imposed displacement (`[u_x, u_y]` or `[u_x, u_y, u_z]`) of `node`'s prescribed components, `0` for its
    /// free components (whose values come from a solution vector). The contact solver adds it
    /// to the gap of contact nodes that are partly supported (e.g. on an axis of symmetry).
    ///
    /// # Panics
    /// If `node >= node_count()`.
    fn prescribed_displacement(&self, node: usize) -> [f64; D];

    /// The 2D idealisation (plane strain, plane stress or axisymmetry): the contact zones weigh
    /// the lumped areas of axisymmetric contact nodes by `2πr`. Only asked in 2D; a 3D
    /// structure has none and keeps the default, [`Idealization::PlaneStrain`] (the unit
    /// weight), as does a 2D structure in plane strain or plane stress.
    fn idealization(&self) -> Idealization {
        Idealization::PlaneStrain
    }

    /// The unit outward normal of the body's boundary at `node`, or `None` for a node inside
    /// the body or a structure that does not know it (the default). The contact coupling uses
    /// it to refuse a rigid target that faces away from the body touching it.
    ///
    /// # Panics
    /// If `node >= node_count()`.
    fn outward_normal(&self, node: usize) -> Option<[f64; D]> {
        let _ = node;
        None
    }

    /// Solves `K x = b` in place (`x = K⁺ b` for a floating structure, see the trait docs).
    /// The default solves `b` as the one column of
    /// [`solve_many_in_place`](Self::solve_many_in_place).
    ///
    /// # Errors
    /// A factorisation error if `K` could not be factored.
    ///
    /// # Panics
    /// If `rhs.len() != dof_count()`.
    fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), FemError> {
        let n = rhs.len();
        self.solve_many_in_place(MatMut::from_column_major_slice_mut(rhs, n, 1))
    }

    /// Solves `K X = B` in place for the columns of `rhs` (`X = K⁺ B` for a floating
    /// structure).
    ///
    /// # Errors
    /// A factorisation error if `K` could not be factored.
    ///
    /// # Panics
    /// If `rhs.nrows() != dof_count()`.
    fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), FemError>;

    /// The free response `u_free` (no contact) to the current loads at `load_factor`,
    /// including prescribed displacements and initial stresses, written into `u`.
    ///
    /// # Errors
    /// As for [`Structure::solve_in_place`].
    ///
    /// # Panics
    /// If `u.len() != dof_count()`.
    fn free_response_into(&self, load_factor: f64, u: &mut [f64]) -> Result<(), FemError>;

    /// A counter that changes whenever `K` (or its dof numbering) changes: the solver rebuilds
    /// `F*` only when it does.
    fn stiffness_version(&self) -> u64;

    /// The stiffness over the free dofs as its lower triangle in CSC form (row indices sorted
    /// in each column, every diagonal entry stored), if the structure has it assembled.
    ///
    /// Optional: the dense and matrix-free contact paths only solve with `K`. The primal
    /// active-set path (contact-solver's `FlexibilityMode::ActiveSet`, the default past a few
    /// hundred contacts) needs the matrix itself, because it factorises `K` with the contact
    /// conditions imposed as boundary conditions. Its pattern must couple both dofs of a node
    /// with every dof the node is coupled to (true of any assembled FE stiffness).
    fn stiffness_matrix(&self) -> Option<SparseColMatRef<'_, usize, f64>> {
        None
    }

    /// The structure as a floating body ([`Floating`]: its rigid-body modes and the load along
    /// them), or `None` (the default) when the supports leave no rigid-body mode and `K` is
    /// positive definite. A structure that returns `Some` applies a generalized inverse `K⁺`
    /// in its solves (trait docs) and returns at least one mode.
    fn floating(&self) -> Option<&dyn Floating> {
        None
    }
}

/// The capability of a [`Structure`] that only contact holds: the rigid-body modes its
/// supports leave and the load along them, reached through [`Structure::floating`] (the trait
/// docs say how the solves treat such a body and why the pair is one capability).
///
/// The modes live on the free dofs, so the trait is the same in 2D and 3D.
///
/// # Examples
/// A block with no support at all floats with three modes (two translations, one rotation):
/// ```
/// use fem_core::generate::{RectangleSpec, rectangle};
/// use fem_core::{Idealization, LinearElasticModel, Material, Structure, Supports};
/// let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 2, 1))?;
/// let model = LinearElasticModel::floating(mesh, Idealization::PlaneStrain,
///     &[(0, Material::new(100.0, 0.3, 0.0)?)], Supports::new())?;
/// let floating = model.floating().expect("no support: rigid-body modes");
/// let mut load = vec![1.0; floating.rigid_body_modes().len()];
/// floating.rigid_body_load_into(1.0, &mut load)?;
/// assert_eq!(load, [0.0; 3]); // no load: nothing for contact to balance
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub trait Floating {
    /// The rigid-body modes the supports leave (the kernel of `K` over the free dofs), at least
    /// one.
    fn rigid_body_modes(&self) -> &RigidBodyModes;

    /// The generalized load along each rigid-body mode, `Rᵀ f` (`f` the right-hand side of
    /// [`Structure::free_response_into`] at `load_factor`), written into `out` (one entry per
    /// mode). Contact must balance it.
    ///
    /// # Errors
    /// As the structure's own load assembly (e.g. a non-finite load).
    ///
    /// # Panics
    /// If `out.len()` is not the number of modes.
    fn rigid_body_load_into(&self, load_factor: f64, out: &mut [f64]) -> Result<(), FemError>;
}
