//! The [`Structure`] trait: everything the contact solver may know about a body, and its
//! optional capabilities, one file each: [`Floating`] (a body that only contact holds),
//! [`Mass`] (inertia, for a dynamic scheme) and [`Nonlinear`] (internal forces and a tangent
//! that depend on the state, for a nonlinear material).

mod floating;
mod mass;
mod nonlinear;

pub use floating::Floating;
pub use mass::Mass;
pub use nonlinear::Nonlinear;

use crate::error::FemError;
use crate::idealization::Idealization;
use faer::MatMut;
use faer::sparse::SparseColMatRef;

/// A linear(ised) structure seen from the contact solver, in dimension `D`: 2 (the default:
/// plane strain, plane stress or axisymmetry) or 3. Positions, dofs and displacements of a node
/// have `D` components; fem-core's [`LinearElasticModel`](crate::LinearElasticModel) and
/// [`SolidModel`](crate::solid::SolidModel) are implementations, and so can be any FE code.
///
/// The solver works on the **free dofs** only (prescribed dofs are eliminated). With `H` the
/// map from free dofs to the local contact frames, the displacement under contact reactions `r`
/// is `u = u_free + K⁻¹ Hᵀ r`, `u_free` the response to the loads without contact
/// ([`Structure::free_response_into`]) and `F* = H K⁻¹ Hᵀ` (seed 5.39) built from
/// [`Structure::solve_many_in_place`].
///
/// # What to implement
/// The **required** methods are what every structure has and the solver calls on every scene
/// (so they are one trait, not three): geometry and dofs, a solve with the factorised stiffness
/// (with [`stiffness_version`](Self::stiffness_version) saying when `K` changed) and the free
/// response to the load. The rest is **provided**, with a default that is the honest answer
/// for a structure that does not override it; the last three are **capabilities**, a trait
/// each reached by one method, so that a structure implements only what it has:
///
/// | method | default | override when |
/// |---|---|---|
/// | [`solve_in_place`](Self::solve_in_place) | one column through `solve_many_in_place` | a single solve is cheaper alone |
/// | [`idealization`](Self::idealization) | plane strain (unit weight) | 2D plane stress or axisymmetry (never asked in 3D) |
/// | [`outward_normal`](Self::outward_normal) | `None` (not known) | the boundary normals are at hand |
/// | [`stiffness_matrix`](Self::stiffness_matrix) | `None` (not assembled) | `K` is assembled (the active-set path needs it) |
/// | [`release_factor`](Self::release_factor), [`restore_factor`](Self::restore_factor) | keep the factor | the factor of `K` may be freed while the 3D active set holds its own |
/// | [`floating`](Self::floating) → [`Floating`] | `None` (`K` positive definite) | supports leave rigid-body modes |
/// | [`mass`](Self::mass) → [`Mass`] | `None` (no inertia) | a dynamic scheme runs on it |
/// | [`nonlinear`](Self::nonlinear) → [`Nonlinear`] | `None` (linear: `f_int = K u`) | the tangent and internal forces depend on the state |
///
/// Named node sets are not asked: the zones name their nodes by index.
///
/// # Floating bodies
/// A floating structure's solves apply a **generalized inverse** `K⁺` (symmetric, `K K⁺ b = b`
/// for every balanced `b`, `Rᵀ b = 0`), and [`Structure::free_response_into`] returns `K⁺ f`
/// whether `f` is balanced or not: the contact solver adds the rigid motion `R α` and makes the
/// reactions balance `Rᵀ f`. The modes and their load are one capability ([`Floating`]) so that
/// a structure cannot return modes while forgetting their load (a silent zero load would be a
/// wrong answer).
///
/// [`Mass`] (for a dynamic scheme such as Moreau–Jean) and [`Nonlinear`] (plasticity, large
/// strain) take the same shape; fem-core's [`ElasticModel`](crate::ElasticModel) has both, its
/// mass when every region's material has a density
/// ([`Material::with_density`](crate::Material::with_density)).
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
/// assert!(s.floating().is_none() && s.stiffness_matrix().is_none() && s.mass().is_none());
/// let mut s = s;
/// assert!(!s.release_factor()); // the default keeps the factor
/// s.restore_factor()?;
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

    /// The 2D idealisation: the contact zones weigh the lumped areas of axisymmetric contact
    /// nodes by `2πr`. Only asked in 2D; the default, [`Idealization::PlaneStrain`], is the
    /// unit weight.
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

    /// Solves `K x = b` in place (`x = K⁺ b` for a floating structure, see the trait docs), by
    /// default as the one column of [`solve_many_in_place`](Self::solve_many_in_place).
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
    /// The dense and matrix-free contact paths only solve with `K`; the primal active-set path
    /// (`FlexibilityMode::ActiveSet`, the default past a few hundred contacts) factorises `K`
    /// with the contact conditions imposed as boundary conditions. The pattern must couple all
    /// dofs of a node with every dof the node is coupled to (true of any assembled stiffness).
    fn stiffness_matrix(&self) -> Option<SparseColMatRef<'_, usize, f64>> {
        None
    }

    /// Frees the numeric factorisation of `K` (keeping what
    /// [`restore_factor`](Self::restore_factor) needs to redo it) and returns whether it did.
    ///
    /// The primal active-set path in 3D factorises the constrained stiffness itself, a factor
    /// of the same fill as `K`'s; it calls this before and
    /// [`restore_factor`](Self::restore_factor) after its solve, dropping its own factor first,
    /// so that one factor of that size is held at a time (`docs/benchmarks.md`, issue 38).
    /// Between the two calls it asks for no solve. The default keeps the factor and returns
    /// `false` (then `restore_factor` is not called): right for a structure whose solves do
    /// not hold a factor, or that cannot refactor.
    fn release_factor(&mut self) -> bool {
        false
    }

    /// Refactorises `K` after [`release_factor`](Self::release_factor) returned `true`: the
    /// same matrix, so every later solve gives the numbers it gave before the release, and
    /// [`stiffness_version`](Self::stiffness_version) does not change. The default does
    /// nothing.
    ///
    /// # Errors
    /// A factorisation error (as the structure's first factorisation of `K` could give).
    fn restore_factor(&mut self) -> Result<(), FemError> {
        Ok(())
    }

    /// The structure as a floating body (its rigid-body modes and the load along them), or
    /// `None` when `K` is positive definite. With `Some`, the solves apply `K⁺` (trait docs)
    /// and there is at least one mode.
    fn floating(&self) -> Option<&dyn Floating> {
        None
    }

    /// The structure's mass, or `None` without inertia: a quasi-static scheme never asks, a
    /// dynamic one refuses a structure without it.
    fn mass(&self) -> Option<&dyn Mass> {
        None
    }

    /// The structure as a state-dependent body, or `None` for a linear structure, whose
    /// internal forces are `K u` with the `K` it solves with.
    fn nonlinear(&mut self) -> Option<&mut dyn Nonlinear> {
        None
    }
}
