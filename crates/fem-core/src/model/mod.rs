//! [`ElasticModel`]: a linear-elastic body on a mesh of either dimension, assembled and
//! factored once, that implements [`Structure`]: [`LinearElasticModel`] in the plane (plane
//! strain, plane stress or axisymmetry) and [`SolidModel`] in space are its two dimensions.
//! Loads are in `loads.rs`, recovery from a solution (stresses, strains, reactions, error
//! norms) in `post.rs`, floating bodies in `floating.rs`, users' elements in `elements.rs`,
//! the mass in `mass.rs`, the (trivial) state-dependent side in `nonlinear.rs`.

mod elements;
mod external;
mod floating;
mod loads;
mod mass;
mod nonlinear;
mod normals;
mod post;
mod tangent;

pub use external::ReducedSolver;
pub use normals::ModelSpace;

use crate::assembly::{Pattern, PrescribedCoupling, merge, scatter};
use crate::dirichlet::{Component, Dof, DofMap, Supports};
use crate::element::{RegionElements, Setting, VoigtStress};
use crate::error::FemError;
use crate::idealization::Idealization;
use crate::linear_solver::SpdSolver;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::ordering::{FillOrdering, nested_dissection};
use crate::rigid_modes::RigidBodyModes;
use crate::solid::SolidMesh;
use crate::space::{Dim, Space};
use crate::structure::{Floating, Mass, Nonlinear, Structure};
use faer::MatMut;
use nalgebra::DMatrix;
use std::collections::BTreeMap;
use std::sync::{Arc, OnceLock};

/// The linear-elastic model in the plane: [`ElasticModel`] with `D = 2`.
pub type LinearElasticModel = ElasticModel<2>;

/// The linear-elastic model in space: [`ElasticModel`] with `D = 3`.
pub type SolidModel = ElasticModel<3>;

/// A stress at a quadrature point: its position and the stress components
/// ([`Space::Stress`]).
pub type StressPoint<const D: usize = 2> = ([f64; D], VoigtStress<D>);

/// A support reaction: the constrained dof `(node, component)` and the force on it.
pub type Reaction = ((usize, Component), f64);

/// An initial stress field `σ₀(x)` (components as [`Space::Stress`]).
pub type StressField<const D: usize = 2> = Arc<dyn Fn([f64; D]) -> VoigtStress<D> + Send + Sync>;

/// The geostatic initial stress of seed eq. 6.1 for a ground surface at `z = z_surface`
/// (second coordinate upwards) and unit weight `gamma`:
/// `σ_zz = −γ (z_surface − z)` (compression negative), `σ_rr = σ_θθ = K0 σ_zz`, `σ_rz = 0`.
///
/// Returned in [`crate::Stress`] order `(rr, zz, rz, θθ)` — also valid in plane strain,
/// where the 4th component is `σ_zz` out of plane.
pub fn geostatic(gamma: f64, k0: f64, z_surface: f64) -> StressField {
    Arc::new(move |x: [f64; 2]| {
        let s_v = -gamma * (z_surface - x[1]).max(0.0);
        [k0 * s_v, s_v, 0.0, k0 * s_v]
    })
}

/// The geostatic initial stress in 3D for a ground surface at `z = z_surface` (`z` upwards)
/// and unit weight `gamma`: `σ_zz = −γ (z_surface − z)` (compression negative),
/// `σ_xx = σ_yy = K0 σ_zz`, no shear.
pub fn geostatic_3d(gamma: f64, k0: f64, z_surface: f64) -> StressField<3> {
    Arc::new(move |x: [f64; 3]| {
        let s_v = -gamma * (z_surface - x[2]).max(0.0);
        [k0 * s_v, k0 * s_v, s_v, 0.0, 0.0, 0.0]
    })
}

/// A linear-elastic body in dimension `D`: mesh, kinematic setting (the [`Idealization`] in
/// 2D), materials per region, supports and loads, with its reduced stiffness assembled and
/// factored. Built with [`LinearElasticModel::new`] or [`SolidModel::new`] (or their
/// `floating` twins for a body that contact holds).
///
/// Loads are kept as a reference load vector scaled by the load factor of
/// [`Structure::free_response_into`]; prescribed displacements and the initial stress are not
/// scaled. Changing a prescribed *value* ([`ElasticModel::set_prescribed`] on a constrained
/// dof) never refactors; constraining or releasing dofs does.
pub struct ElasticModel<const D: usize>
where
    Dim<D>: ModelSpace<D>,
{
    mesh: Mesh<D>,
    setting: Setting<D>,
    materials: BTreeMap<u32, Material>,
    supports: Supports,
    dofs: DofMap<D>,
    pattern: Pattern,
    values: Vec<f64>,
    coupling: PrescribedCoupling,
    /// The Cholesky factorisation of `K` (its symbolic part made at the first factorisation);
    /// `None` for a model built for an external solver ([`ElasticModel::unfactored`]) or
    /// handed one.
    solver: Option<SpdSolver>,
    ordering: FillOrdering,
    /// Reference external loads per node component (`D × node_count`).
    load: Vec<f64>,
    /// Internal forces of the initial stress per node component.
    initial_force: Vec<f64>,
    /// The initial stress field of each region that has one.
    initial_stress: Vec<(u32, StressField<D>)>,
    version: u64,
    /// Outward normals of the boundary nodes, computed at the first request.
    normals: OnceLock<Vec<Option<[f64; D]>>>,
    /// Whether the supports may leave rigid-body modes (`floating` constructors).
    may_float: bool,
    /// The rigid-body modes the supports leave (empty unless `may_float`).
    modes: RigidBodyModes,
    /// The free dofs pinned to factorise `K⁺` (one per mode).
    pinned: Vec<usize>,
    /// `K` with the pinned rows and columns decoupled (the matrix factorised when floating).
    pinned_values: Vec<f64>,
    /// An orthonormal basis of the modes (column-major), for the projection `P = I − Q Qᵀ`.
    mode_basis: Vec<f64>,
    /// Users' elements by region, in place of the mesh kind's ([`ElasticModel::with_element`]).
    elements: RegionElements<D>,
    /// The mass, when every region's material has a density (reassembled with `K`).
    mass: Option<mass::MassValues>,
    /// The solver of `K x = b` in place of `solver` ([`ElasticModel::set_reduced_solver`]).
    external: Option<Box<dyn ReducedSolver>>,
}

impl<const D: usize> core::fmt::Debug for ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("ElasticModel")
            .field("dimension", &<Dim<D> as Space>::NAME)
            .field("nodes", &self.mesh.node_count())
            .field("elements", &self.mesh.element_count())
            .field("setting", &self.setting)
            .field("free_dofs", &self.dofs.free_count())
            .field("nnz", &self.pattern.nnz())
            .field("version", &self.version)
            .field("external_solver", &self.external.is_some())
            .finish()
    }
}

impl ElasticModel<2> {
    /// Builds the model: checks the data, numbers the dofs, builds the sparsity pattern,
    /// assembles and factors `K`.
    ///
    /// # Errors
    /// - [`FemError::MissingMaterial`] if a region has no material;
    /// - [`FemError::MissingDensity`] if some region's material has a density
    ///   ([`Material::with_density`]) and another's has none (the model has a mass,
    ///   [`Structure::mass`], when every region has one, and none when no region has);
    /// - [`FemError::NegativeRadius`] in axisymmetry for a node at `r < 0`;
    /// - [`FemError::InvertedElement`] for a (curved) element with a non-positive Jacobian;
    /// - [`FemError::UnknownNode`] for a support on a missing node;
    /// - [`FemError::InvalidParameter`] for a plane-stress thickness that is not finite and
    ///   positive;
    /// - [`FemError::NonFiniteStiffness`] for an element whose stiffness overflows;
    /// - [`FemError::NotPositiveDefinite`] if the supports leave a rigid-body mode (found from
    ///   the mesh and the supports, naming a dof the mode moves) or the stiffness is singular
    ///   otherwise (a node no element connects, a mechanism); a body that contact holds is
    ///   built with [`LinearElasticModel::floating`].
    pub fn new(
        mesh: Mesh,
        idealization: Idealization,
        materials: &[(u32, Material)],
        supports: Supports,
    ) -> Result<Self, FemError> {
        Self::build(
            mesh,
            idealization,
            materials,
            supports,
            false,
            FillOrdering::Amd,
        )
    }
}

impl ElasticModel<3> {
    /// Builds the 3D model: checks the data, numbers the dofs, builds the sparsity pattern
    /// (and the fill-reducing ordering, once), assembles and factors `K`.
    ///
    /// # Errors
    /// As [`LinearElasticModel::new`], but for the 2D idealisation's (a floating body is built
    /// with [`SolidModel::floating`]).
    pub fn new(
        mesh: SolidMesh,
        materials: &[(u32, Material)],
        supports: Supports,
    ) -> Result<Self, FemError> {
        Self::with_ordering(mesh, materials, supports, FillOrdering::default())
    }

    /// As [`SolidModel::new`], with the fill-reducing ordering of the factorisation chosen
    /// (the default, nested dissection, leaves less fill on 3D meshes: `docs/benchmarks.md`).
    ///
    /// # Errors
    /// As [`SolidModel::new`].
    pub fn with_ordering(
        mesh: SolidMesh,
        materials: &[(u32, Material)],
        supports: Supports,
        ordering: FillOrdering,
    ) -> Result<Self, FemError> {
        Self::build(mesh, (), materials, supports, false, ordering)
    }
}

impl<const D: usize> ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    fn build(
        mesh: Mesh<D>,
        setting: Setting<D>,
        materials: &[(u32, Material)],
        supports: Supports,
        may_float: bool,
        ordering: FillOrdering,
    ) -> Result<Self, FemError> {
        let mut model = Self::assembled(mesh, setting, materials, supports, may_float, ordering)?;
        model.factor()?;
        Ok(model)
    }

    /// The model with `K` assembled (and the modes found), not factorised: what
    /// [`Self::build`] factorises and [`ElasticModel::unfactored`] leaves for an external
    /// solver.
    fn assembled(
        mesh: Mesh<D>,
        setting: Setting<D>,
        materials: &[(u32, Material)],
        supports: Supports,
        may_float: bool,
        ordering: FillOrdering,
    ) -> Result<Self, FemError> {
        let idealization = <Dim<D> as Space>::idealization(&setting).copied();
        if let Some(Idealization::PlaneStress { thickness }) = idealization {
            crate::error::positive("thickness", thickness)?;
        }
        let materials: BTreeMap<u32, Material> = materials.iter().copied().collect();
        for (element, region) in mesh.regions().iter().enumerate() {
            if !materials.contains_key(region) {
                return Err(FemError::MissingMaterial {
                    region: *region,
                    element,
                });
            }
        }
        if let Some(Idealization::Axisymmetric) = idealization
            && let Some((node, p)) = mesh.nodes().iter().enumerate().find(|(_, p)| p[0] < 0.0)
        {
            return Err(FemError::NegativeRadius { node, r: p[0] });
        }
        let with_mass = mass::has_mass(&mesh, &materials)?;
        let dofs = DofMap::<D>::numbered(mesh.node_count(), &supports)?;
        let pattern = Pattern::new(&dofs, (0..mesh.element_count()).map(|e| mesh.element(e)))?;
        let n = D * mesh.node_count();
        let mut model = Self {
            values: vec![0.0; pattern.nnz()],
            mesh,
            setting,
            materials,
            supports,
            dofs,
            pattern,
            coupling: PrescribedCoupling::default(),
            solver: None,
            ordering,
            load: vec![0.0; n],
            initial_force: vec![0.0; n],
            initial_stress: Vec::new(),
            version: 0,
            normals: OnceLock::new(),
            may_float,
            modes: RigidBodyModes::default(),
            pinned: Vec::new(),
            pinned_values: Vec::new(),
            mode_basis: Vec::new(),
            elements: RegionElements::default(),
            mass: with_mass.then(mass::MassValues::default),
            external: None,
        };
        model.find_modes()?;
        model.assemble()?;
        Ok(model)
    }

    fn assemble_and_factor(&mut self) -> Result<(), FemError> {
        self.refuse_with_external("reassembling K")?;
        self.assemble()?;
        self.factor()
    }

    /// Assembles `K` (and the mass) into the pattern's values.
    fn assemble(&mut self) -> Result<(), FemError> {
        self.values.fill(0.0);
        let built_in = self.mesh.built_in_element();
        let mut k_e = DMatrix::zeros(0, 0);
        let mut coords = Vec::with_capacity(built_in.node_count());
        let mut coupling = Vec::new();
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            self.mesh.element_coords_into(e, &mut coords);
            let region = self.mesh.regions()[e];
            let material = &self.materials[&region];
            let element = self.elements.get(region, built_in);
            element.stiffness_into(e, &coords, material, &self.setting, &mut k_e)?;
            if k_e.iter().any(|v| !v.is_finite()) {
                return Err(FemError::NonFiniteStiffness {
                    element: e,
                    region,
                    young: material.young(),
                });
            }
            scatter(
                &self.pattern,
                &self.dofs,
                cell,
                &k_e,
                &mut self.values,
                &mut coupling,
            );
        }
        self.coupling = merge(coupling);
        self.assemble_mass()
    }

    /// Factorises the assembled `K` (pinned when floating), its symbolic part made first
    /// when the model has none.
    fn factor(&mut self) -> Result<(), FemError> {
        let values = if self.pinned.is_empty() {
            &self.values
        } else {
            self.pin_values();
            &self.pinned_values
        };
        let solver = match &mut self.solver {
            Some(solver) => solver,
            None => self.solver.insert(solver_for(
                &self.mesh,
                &self.dofs,
                &self.pattern,
                self.ordering,
            )?),
        };
        solver
            .factor(self.pattern.view(values))
            .map_err(|e| self.name_failed_dof(e))?;
        self.version += 1;
        Ok(())
    }

    /// [`Self::rhs_into`] for a load factor that must be finite, the result checked finite:
    /// the right-hand side of [`Structure::free_response_into`] and the external force of
    /// [`crate::structure::Nonlinear`].
    fn checked_rhs_into(&self, load_factor: f64, rhs: &mut [f64]) -> Result<(), FemError> {
        if !load_factor.is_finite() {
            return Err(FemError::NonFiniteSolve {
                what: "load factor",
                node: None,
                value: load_factor,
            });
        }
        self.rhs_into(load_factor, rhs);
        self.check_finite("right-hand side", rhs)
    }

    /// [`FemError::NonFiniteSolve`] at the first non-finite entry of a free-dof vector.
    fn check_finite(&self, what: &'static str, v: &[f64]) -> Result<(), FemError> {
        match v.iter().position(|x| !x.is_finite()) {
            None => Ok(()),
            Some(i) => Err(FemError::NonFiniteSolve {
                what,
                node: self.dofs.free_dof_owner(i),
                value: v[i],
            }),
        }
    }

    /// [`FemError::LinearAlgebra`] when the stiffness (or a nonlinear model's tangent held
    /// here) has no factorisation: the last one failed.
    fn check_factored(&self) -> Result<&SpdSolver, FemError> {
        match &self.solver {
            Some(solver) if solver.is_factored() => Ok(solver),
            Some(solver) if solver.is_released() => Err(FemError::LinearAlgebra {
                detail: "a solve with a stiffness whose factor was released (call \
                         Structure::restore_factor first)"
                    .into(),
            }),
            Some(_) => Err(FemError::LinearAlgebra {
                detail: "a solve with a stiffness whose last factorisation failed (factorise a \
                         positive definite stiffness or tangent first)"
                    .into(),
            }),
            None => Err(FemError::LinearAlgebra {
                detail: "a solve with a model built without a factorisation \
                         (`ElasticModel::unfactored`): set its solver \
                         (`set_reduced_solver`) or factorise it (`refactor`) first"
                    .into(),
            }),
        }
    }

    /// Names the node and component of a failed pivot: the solver reports a row of the
    /// reduced system, which the dof map turns into `(node, component)`.
    fn name_failed_dof(&self, e: FemError) -> FemError {
        match e {
            FemError::NonPositivePivot { row: Some(row) } => match self.dofs.free_dof_owner(row) {
                Some((node, component)) => FemError::NotPositiveDefinite {
                    node,
                    component,
                    row,
                },
                None => e,
            },
            e => e,
        }
    }

    /// Reassembles and refactors `K` with the same pattern and ordering (what a change of
    /// material costs; the benchmarks time it).
    ///
    /// # Errors
    /// As the constructors.
    pub fn refactor(&mut self) -> Result<(), FemError> {
        self.assemble_and_factor()
    }

    /// The mesh.
    #[inline]
    pub fn mesh(&self) -> &Mesh<D> {
        &self.mesh
    }

    /// The kinematic setting: the [`Idealization`] in 2D, `()` in 3D.
    #[inline]
    pub fn setting(&self) -> &Setting<D> {
        &self.setting
    }

    /// The dof numbering.
    #[inline]
    pub fn dof_map(&self) -> &DofMap<D> {
        &self.dofs
    }

    /// The supports.
    #[inline]
    pub fn supports(&self) -> &Supports {
        &self.supports
    }

    /// Number of numeric factorisations done so far (for "skip what is not needed" checks).
    #[inline]
    pub fn factorizations(&self) -> usize {
        self.version as usize
    }

    /// Number of stored entries of the lower triangle of `K`.
    #[inline]
    pub fn nnz(&self) -> usize {
        self.pattern.nnz()
    }

    /// Stored entries of the Cholesky factor of `K` (its fill with the model's ordering); 0
    /// for a model without one (built [`unfactored`](ElasticModel::unfactored) or handed a
    /// [`ReducedSolver`]).
    #[inline]
    pub fn factor_nnz(&self) -> usize {
        self.solver.as_ref().map_or(0, SpdSolver::factor_nnz)
    }

    /// The reduced stiffness `K` (lower triangle, free dofs), as a faer view.
    #[inline]
    pub fn stiffness(&self) -> faer::sparse::SparseColMatRef<'_, usize, f64> {
        self.pattern.view(&self.values)
    }

    /// The material of element `e`'s region.
    ///
    /// # Panics
    /// If `e` is not an element of the mesh.
    #[track_caller]
    pub fn material(&self, e: usize) -> &Material {
        &self.materials[&self.mesh.regions()[e]]
    }

    /// Sets the prescribed value of `component` on `nodes`. If every such dof is already
    /// constrained only the value changes (no refactorisation); otherwise the dofs are
    /// constrained, renumbered, and `K` is reassembled and refactored.
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] for a non-finite value; [`FemError::UnknownNode`];
    /// factorisation errors (the supports are then restored).
    pub fn set_prescribed(
        &mut self,
        nodes: &[usize],
        component: Component,
        value: f64,
    ) -> Result<(), FemError> {
        self.check_nodes(nodes, "a prescribed displacement")?;
        let renumber = nodes
            .iter()
            .any(|&n| self.supports.value(n, component).is_none());
        let before = self.supports.clone();
        self.supports.update(nodes, component, value)?;
        if renumber {
            self.renumber(before)?;
        }
        Ok(())
    }

    /// Removes the supports of `component` on `nodes` (those nodes move freely along it from
    /// the next solve on), then renumbers and refactors. A contact simulation holding the
    /// model follows the new numbering at its next step.
    ///
    /// # Errors
    /// [`FemError::UnknownNode`]; [`FemError::NotPositiveDefinite`] if the body is left
    /// without enough supports (the supports are then restored).
    pub fn release(&mut self, nodes: &[usize], component: Component) -> Result<(), FemError> {
        self.check_nodes(nodes, "a released support")?;
        if nodes
            .iter()
            .all(|&n| self.supports.value(n, component).is_none())
        {
            return Ok(());
        }
        let before = self.supports.clone();
        self.supports.release(nodes, component);
        self.renumber(before)
    }

    fn check_nodes(&self, nodes: &[usize], what: &'static str) -> Result<(), FemError> {
        let node_count = self.mesh.node_count();
        match nodes.iter().find(|&&n| n >= node_count) {
            Some(&node) => Err(FemError::UnknownNode {
                what,
                node,
                node_count,
            }),
            None => Ok(()),
        }
    }

    /// Numbers the dofs for the current supports, rebuilds the pattern, the solver and the
    /// modes, and reassembles and refactors; on failure the supports `before` are restored
    /// (and the model with them).
    fn renumber(&mut self, before: Supports) -> Result<(), FemError> {
        if let Err(e) = self.refuse_with_external("constraining or releasing a dof") {
            self.supports = before;
            return Err(e);
        }
        let rebuilt = self.rebuild_numbering();
        if rebuilt.is_err() {
            self.supports = before;
            self.rebuild_numbering()?;
        }
        rebuilt
    }

    fn rebuild_numbering(&mut self) -> Result<(), FemError> {
        self.dofs = DofMap::<D>::numbered(self.mesh.node_count(), &self.supports)?;
        let mesh = &self.mesh;
        self.pattern = Pattern::new(
            &self.dofs,
            (0..mesh.element_count()).map(|e| mesh.element(e)),
        )?;
        self.solver = None;
        self.values = vec![0.0; self.pattern.nnz()];
        self.find_modes()?;
        self.assemble_and_factor()
    }

    /// The right-hand side of the reduced system at `load_factor`:
    /// `f = factor · f_ext + f_σ₀ − K_fp ū`, on the free dofs.
    ///
    /// # Panics
    /// If `rhs.len() != dof_count()`.
    #[track_caller]
    pub fn rhs_into(&self, load_factor: f64, rhs: &mut [f64]) {
        assert_eq!(rhs.len(), self.dofs.free_count(), "rhs length");
        // += : the nodes of a tie share one dof, which takes their sum
        self.dofs
            .gather_into(load_factor, &self.load, &self.initial_force, rhs);
        self.coupling
            .subtract_into(&self.dofs.prescribed_values(&self.supports), rhs);
    }

    /// Nodal displacements (`D` components per node) from the free-dof solution `u_free` and
    /// the prescribed values.
    ///
    /// # Panics
    /// If `u_free.len() != dof_count()`.
    #[track_caller]
    pub fn nodal_displacements(&self, u_free: &[f64]) -> Vec<[f64; D]> {
        assert_eq!(u_free.len(), self.dofs.free_count(), "solution length");
        self.dofs
            .expand(u_free, &self.dofs.prescribed_values(&self.supports))
    }

    /// Solves the free response at `load_factor` and returns the nodal displacements.
    ///
    /// # Errors
    /// As for [`Structure::free_response_into`].
    pub fn solve(&self, load_factor: f64) -> Result<Vec<[f64; D]>, FemError> {
        let mut u = vec![0.0; self.dofs.free_count()];
        self.free_response_into(load_factor, &mut u)?;
        Ok(self.nodal_displacements(&u))
    }

    /// The rigid-body modes the supports leave ([`Structure::floating`]), or `None` when `K`
    /// is positive definite.
    pub fn rigid_body_modes(&self) -> Option<&RigidBodyModes> {
        self.floating().map(Floating::rigid_body_modes)
    }

    /// The load along each rigid-body mode, `Rᵀ f` at `load_factor`, written into `out`
    /// ([`Floating::rigid_body_load_into`]; nothing to write without modes).
    ///
    /// # Errors
    /// [`FemError::NonFiniteSolve`] if the load is not finite.
    ///
    /// # Panics
    /// If `out.len()` is not the number of modes.
    #[track_caller]
    pub fn rigid_body_load_into(&self, load_factor: f64, out: &mut [f64]) -> Result<(), FemError> {
        self.mode_load_into(load_factor, out)
    }
}

/// The symbolic factorisation of `pattern` with `ordering` (nested dissection on the position
/// of each free dof's first node).
fn solver_for<const D: usize>(
    mesh: &Mesh<D>,
    dofs: &DofMap<D>,
    pattern: &Pattern,
    ordering: FillOrdering,
) -> Result<SpdSolver, FemError>
where
    Dim<D>: ModelSpace<D>,
{
    match ordering {
        FillOrdering::Amd => SpdSolver::new(pattern.symbolic().as_ref()),
        FillOrdering::NestedDissection => {
            let mut coords = vec![[f64::NAN; 3]; dofs.free_count()];
            for node in (0..mesh.node_count()).rev() {
                for d in dofs.free_dofs(node).into_iter().flatten() {
                    coords[d] = [0.0; 3];
                    coords[d][..D].copy_from_slice(&mesh.nodes()[node]);
                }
            }
            // a dof no node owns cannot happen (numbered from the nodes); keep it finite
            coords
                .iter_mut()
                .filter(|c| c[0].is_nan())
                .for_each(|c| *c = [0.0; 3]);
            let order = nested_dissection(pattern.symbolic().as_ref(), &coords);
            SpdSolver::with_order(pattern.symbolic().as_ref(), &order)
        }
    }
}

impl<const D: usize> Structure<D> for ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    fn outward_normal(&self, node: usize) -> Option<[f64; D]> {
        self.normals
            .get_or_init(|| <Dim<D> as ModelSpace<D>>::outward_normals(&self.mesh))[node]
    }

    fn dof_count(&self) -> usize {
        self.dofs.free_count()
    }

    fn node_count(&self) -> usize {
        self.mesh.node_count()
    }

    fn node_position(&self, node: usize) -> [f64; D] {
        self.mesh.nodes()[node]
    }

    fn node_dofs(&self, node: usize) -> [Option<usize>; D] {
        self.dofs.free_dofs(node)
    }

    fn prescribed_displacement(&self, node: usize) -> [f64; D] {
        let d = self.dofs.dofs(node);
        Component::all::<D>().map(|c| match d[c as usize] {
            Dof::Prescribed(_) => self.supports.value(node, c).unwrap_or(0.0),
            Dof::Free(_) => 0.0,
        })
    }

    fn idealization(&self) -> Idealization {
        <Dim<D> as Space>::idealization(&self.setting)
            .copied()
            .unwrap_or(Idealization::PlaneStrain)
    }

    fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), FemError> {
        if let Some(external) = &self.external {
            let n = rhs.len();
            return external.solve_many_in_place(MatMut::from_column_major_slice_mut(rhs, n, 1));
        }
        let solver = self.check_factored()?;
        if self.pinned.is_empty() {
            solver.solve_in_place(rhs);
        } else {
            // x = P K⁺ P b (crate::rigid_modes)
            self.project(rhs, true);
            solver.solve_in_place(rhs);
            self.project(rhs, false);
        }
        Ok(())
    }

    fn solve_many_in_place(&self, mut rhs: MatMut<'_, f64>) -> Result<(), FemError> {
        if let Some(external) = &self.external {
            return external.solve_many_in_place(rhs);
        }
        let solver = self.check_factored()?;
        if self.pinned.is_empty() {
            solver.solve_many_in_place(rhs);
        } else {
            for c in 0..rhs.ncols() {
                self.project_column(rhs.as_mut().col_mut(c), true);
            }
            solver.solve_many_in_place(rhs.as_mut());
            for c in 0..rhs.ncols() {
                self.project_column(rhs.as_mut().col_mut(c), false);
            }
        }
        Ok(())
    }

    fn free_response_into(&self, load_factor: f64, u: &mut [f64]) -> Result<(), FemError> {
        self.checked_rhs_into(load_factor, u)?;
        self.solve_in_place(u)?;
        self.check_finite("displacement", u)
    }

    fn floating(&self) -> Option<&dyn Floating> {
        (!self.modes.is_empty()).then_some(self)
    }

    fn release_factor(&mut self) -> bool {
        self.release_own_factor()
    }

    fn restore_factor(&mut self) -> Result<(), FemError> {
        self.restore_own_factor()
    }

    fn stiffness_version(&self) -> u64 {
        self.version
    }

    fn stiffness_matrix(&self) -> Option<faer::sparse::SparseColMatRef<'_, usize, f64>> {
        Some(self.stiffness())
    }

    fn mass(&self) -> Option<&dyn Mass> {
        self.mass.is_some().then_some(self)
    }

    fn nonlinear(&mut self) -> Option<&mut dyn Nonlinear> {
        Some(self)
    }
}

/// Asked only through [`Structure::floating`], which offers the model when its supports leave
/// modes (the `floating` constructors).
impl<const D: usize> Floating for ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    fn rigid_body_modes(&self) -> &RigidBodyModes {
        &self.modes
    }

    fn rigid_body_load_into(&self, load_factor: f64, out: &mut [f64]) -> Result<(), FemError> {
        self.mode_load_into(load_factor, out)
    }
}

#[cfg(test)]
mod tests;
