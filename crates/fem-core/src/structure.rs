//! The [`Structure`] trait: everything the contact solver may know about a body.

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
/// # Floating bodies
/// A structure whose supports leave rigid-body modes (a body that only contact holds) returns
/// them from [`Structure::rigid_body_modes`] (`R`, `K R = 0`) and the load along them from
/// [`Structure::rigid_body_load_into`] (`Rᵀ f`). Its solves then apply a **generalized
/// inverse** `K⁺` (symmetric, `K K⁺ b = b` for every balanced `b`, `Rᵀ b = 0`), and
/// [`Structure::free_response_into`] returns `K⁺ f` whether `f` is balanced or not: the contact
/// solver adds the rigid motion `R α` and makes the contact reactions balance `Rᵀ f`. A
/// structure without modes (the default) keeps `K⁺ = K⁻¹`.
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

    /// The 2D idealisation (plane strain, plane stress or axisymmetry). A 3D structure has
    /// none and returns [`Idealization::PlaneStrain`], the unit weight.
    fn idealization(&self) -> Idealization;

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

    /// A named set of nodes (e.g. a contactor surface).
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] if the structure has no such set.
    fn boundary_nodes(&self, name: &str) -> Result<&[usize], FemError>;

    /// Solves `K x = b` in place (`x = K⁺ b` for a floating structure, see the trait docs).
    ///
    /// # Errors
    /// A factorisation error if `K` could not be factored.
    ///
    /// # Panics
    /// If `rhs.len() != dof_count()`.
    fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), FemError>;

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

    /// The rigid-body modes the supports leave (the kernel of `K` over the free dofs), or
    /// `None` (the default) when `K` is positive definite. When it returns modes, the solves
    /// apply a generalized inverse `K⁺` (trait docs) and
    /// [`Structure::rigid_body_load_into`] must be implemented.
    fn rigid_body_modes(&self) -> Option<&RigidBodyModes> {
        None
    }

    /// The generalized load along each rigid-body mode, `Rᵀ f` (`f` the right-hand side of
    /// [`Structure::free_response_into`] at `load_factor`), written into `out` (one entry per
    /// mode). Contact must balance it.
    ///
    /// # Errors
    /// The default: nothing to do without modes; [`FemError::MissingMethod`] for a structure
    /// that returns modes but does not implement this method (a silent zero would be a wrong
    /// answer).
    ///
    /// # Panics
    /// If `out.len()` is not the number of modes.
    fn rigid_body_load_into(&self, load_factor: f64, out: &mut [f64]) -> Result<(), FemError> {
        let _ = load_factor;
        match self.rigid_body_modes() {
            Some(m) if !m.is_empty() => Err(FemError::MissingMethod {
                method: "rigid_body_load_into",
                reason: "the structure returns rigid-body modes",
            }),
            _ => {
                assert!(out.is_empty(), "one entry per rigid-body mode");
                Ok(())
            }
        }
    }
}
