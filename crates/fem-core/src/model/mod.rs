//! [`LinearElasticModel`]: a linear-elastic body on a triangle mesh, assembled and factored
//! once, that implements [`Structure`]. Recovery from a solution (stresses, strains, nodal
//! stresses, reactions) is in `post.rs`.

mod elements;
mod floating;
mod post;

use crate::assembly::{Pattern, PrescribedCoupling, merge, scatter};
use crate::dirichlet::{Component, Dof, DofMap, Supports};
use crate::element::{Element, RegionElements, Stress};
use crate::error::{FemError, finite};
use crate::idealization::Idealization;
use crate::linear_solver::SpdSolver;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::quadrature::GAUSS_3;
use crate::rigid_modes::RigidBodyModes;
use crate::structure::{Floating, Structure};
use faer::MatMut;
use nalgebra::DMatrix;
use std::collections::BTreeMap;
use std::sync::Arc;

/// A stress at a quadrature point: its position and the stress components.
pub type StressPoint = ([f64; 2], Stress);

/// A support reaction: the constrained dof `(node, component)` and the force on it.
pub type Reaction = ((usize, Component), f64);

/// An initial stress field `σ₀(x)` (components as [`Stress`]).
pub type StressField = Arc<dyn Fn([f64; 2]) -> Stress + Send + Sync>;

/// The geostatic initial stress of seed eq. 6.1 for a ground surface at `z = z_surface`
/// (second coordinate upwards) and unit weight `gamma`:
/// `σ_zz = −γ (z_surface − z)` (compression negative), `σ_rr = σ_θθ = K0 σ_zz`, `σ_rz = 0`.
///
/// Returned in [`Stress`] order `(rr, zz, rz, θθ)` — also valid in plane strain, where the 4th
/// component is `σ_zz` out of plane.
pub fn geostatic(gamma: f64, k0: f64, z_surface: f64) -> StressField {
    Arc::new(move |x: [f64; 2]| {
        let s_v = -gamma * (z_surface - x[1]).max(0.0);
        [k0 * s_v, s_v, 0.0, k0 * s_v]
    })
}

/// A linear-elastic body: mesh, idealisation, materials per region, supports and loads, with
/// its reduced stiffness assembled and factored.
///
/// Loads are kept as a reference load vector scaled by the load factor of
/// [`Structure::free_response_into`]; prescribed displacements and the initial stress are not
/// scaled. Changing a prescribed *value* ([`LinearElasticModel::set_prescribed`] on a
/// constrained dof) never refactors; constraining or releasing dofs does.
pub struct LinearElasticModel {
    mesh: Mesh,
    idealization: Idealization,
    materials: BTreeMap<u32, Material>,
    supports: Supports,
    dofs: DofMap,
    pattern: Pattern,
    values: Vec<f64>,
    coupling: PrescribedCoupling,
    solver: SpdSolver,
    /// Reference external loads per node component (`2 × node_count`).
    load: Vec<f64>,
    /// Internal forces of the initial stress per node component.
    initial_force: Vec<f64>,
    initial_stress: Option<StressField>,
    version: u64,
    /// Outward normals of the boundary nodes, computed at the first request.
    normals: std::sync::OnceLock<Vec<Option<[f64; 2]>>>,
    /// Whether the supports may leave rigid-body modes ([`LinearElasticModel::floating`]).
    may_float: bool,
    /// The rigid-body modes the supports leave (empty unless `may_float`).
    modes: RigidBodyModes,
    /// The free dofs pinned to factorise `K⁺` (one per mode).
    pinned: Vec<usize>,
    /// `K` with the pinned rows and columns decoupled (the matrix factorised when floating).
    pinned_values: Vec<f64>,
    /// Users' elements by region, in place of the mesh kind's ([`LinearElasticModel::with_element`]).
    elements: RegionElements<2>,
    /// An orthonormal basis of the modes (column-major), for the projection `P = I − Q Qᵀ`.
    mode_basis: Vec<f64>,
}

impl core::fmt::Debug for LinearElasticModel {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("LinearElasticModel")
            .field("nodes", &self.mesh.node_count())
            .field("elements", &self.mesh.element_count())
            .field("idealization", &self.idealization)
            .field("free_dofs", &self.dofs.free_count())
            .field("nnz", &self.pattern.nnz())
            .field("version", &self.version)
            .finish()
    }
}

impl LinearElasticModel {
    /// Builds the model: checks the data, numbers the dofs, builds the sparsity pattern,
    /// assembles and factors `K`.
    ///
    /// # Errors
    /// - [`FemError::MissingMaterial`] if a region has no material;
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
        Self::build(mesh, idealization, materials, supports, false)
    }

    fn build(
        mesh: Mesh,
        idealization: Idealization,
        materials: &[(u32, Material)],
        supports: Supports,
        may_float: bool,
    ) -> Result<Self, FemError> {
        if let Idealization::PlaneStress { thickness } = idealization {
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
        if let Idealization::Axisymmetric = idealization
            && let Some((node, p)) = mesh.nodes().iter().enumerate().find(|(_, p)| p[0] < 0.0)
        {
            return Err(FemError::NegativeRadius { node, r: p[0] });
        }
        let dofs = DofMap::new(mesh.node_count(), &supports)?;
        let pattern = Pattern::new(&dofs, (0..mesh.element_count()).map(|e| mesh.element(e)))?;
        let solver = SpdSolver::new(pattern.symbolic().as_ref())?;
        let n2 = 2 * mesh.node_count();
        let mut model = Self {
            values: vec![0.0; pattern.nnz()],
            mesh,
            idealization,
            materials,
            supports,
            dofs,
            pattern,
            coupling: PrescribedCoupling::default(),
            solver,
            load: vec![0.0; n2],
            initial_force: vec![0.0; n2],
            initial_stress: None,
            version: 0,
            normals: std::sync::OnceLock::new(),
            may_float,
            modes: RigidBodyModes::default(),
            pinned: Vec::new(),
            pinned_values: Vec::new(),
            mode_basis: Vec::new(),
            elements: RegionElements::default(),
        };
        model.find_modes()?;
        model.assemble_and_factor()?;
        Ok(model)
    }

    fn assemble_and_factor(&mut self) -> Result<(), FemError> {
        self.values.fill(0.0);
        let kind = self.mesh.kind();
        let mut k_e = DMatrix::zeros(0, 0);
        let mut coords = Vec::with_capacity(6);
        let mut coupling = Vec::new();
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            coords.clear();
            coords.extend(cell.iter().map(|&n| self.mesh.nodes()[n]));
            let region = self.mesh.regions()[e];
            let material = &self.materials[&region];
            let element = self.elements.get(region, kind.element());
            element.stiffness_into(e, &coords, material, &self.idealization, &mut k_e)?;
            if k_e.iter().any(|v| !v.is_finite()) {
                return Err(FemError::NonFiniteStiffness {
                    element: e,
                    region: self.mesh.regions()[e],
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
        let values = if self.pinned.is_empty() {
            &self.values
        } else {
            self.pin_values();
            &self.pinned_values
        };
        self.solver
            .factor(self.pattern.view(values))
            .map_err(|e| self.name_failed_dof(e))?;
        self.version += 1;
        Ok(())
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

    /// The mesh.
    #[inline]
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The dof numbering.
    #[inline]
    pub fn dof_map(&self) -> &DofMap {
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

    /// The reduced stiffness `K` (lower triangle, free dofs), as a faer view.
    #[inline]
    pub fn stiffness(&self) -> faer::sparse::SparseColMatRef<'_, usize, f64> {
        self.pattern.view(&self.values)
    }

    /// Sets the prescribed value of `component` on `nodes`. If every such dof is already
    /// constrained only the value changes (no refactorisation); otherwise the dofs are
    /// constrained, renumbered, and `K` is reassembled and refactored.
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] for a non-finite value; factorisation errors.
    pub fn set_prescribed(
        &mut self,
        nodes: &[usize],
        component: Component,
        value: f64,
    ) -> Result<(), FemError> {
        let renumber = nodes
            .iter()
            .any(|&n| self.supports.value(n, component).is_none());
        self.supports.update(nodes, component, value)?;
        if renumber {
            self.rebuild()?;
        }
        Ok(())
    }

    /// Removes the supports of `component` on `nodes`, then renumbers and refactors.
    ///
    /// # Errors
    /// [`FemError::NotPositiveDefinite`] if the body is left without enough supports.
    pub fn release(&mut self, nodes: &[usize], component: Component) -> Result<(), FemError> {
        self.supports.release(nodes, component);
        self.rebuild()
    }

    fn rebuild(&mut self) -> Result<(), FemError> {
        self.dofs = DofMap::new(self.mesh.node_count(), &self.supports)?;
        let mesh = &self.mesh;
        self.pattern = Pattern::new(
            &self.dofs,
            (0..mesh.element_count()).map(|e| mesh.element(e)),
        )?;
        self.solver = SpdSolver::new(self.pattern.symbolic().as_ref())?;
        self.values = vec![0.0; self.pattern.nnz()];
        self.find_modes()?;
        self.assemble_and_factor()
    }

    /// Adds a reference nodal force `[f_x, f_y]` (per unit thickness, thickness, or radian as
    /// the idealisation says).
    ///
    /// # Errors
    /// [`FemError::UnknownNode`] or [`FemError::InvalidParameter`] for non-finite values.
    pub fn add_nodal_force(&mut self, node: usize, force: [f64; 2]) -> Result<(), FemError> {
        if node >= self.mesh.node_count() {
            return Err(FemError::UnknownNode {
                what: "a nodal force",
                node,
                node_count: self.mesh.node_count(),
            });
        }
        finite("nodal force", force[0])?;
        finite("nodal force", force[1])?;
        self.load[2 * node] += force[0];
        self.load[2 * node + 1] += force[1];
        Ok(())
    }

    /// Adds a reference traction `t(x)` (force per area, global frame) on the sides of an edge
    /// set, integrated with 3 Gauss points per side (exact for P2 sides in axisymmetry).
    ///
    /// # Errors
    /// [`FemError::UnknownSet`]; [`FemError::InvalidParameter`] if `t` returns a non-finite
    /// value.
    pub fn add_edge_traction(
        &mut self,
        edge_set: &str,
        traction: impl Fn([f64; 2]) -> [f64; 2],
    ) -> Result<(), FemError> {
        let sides = self.mesh.edge_set(edge_set)?.to_vec();
        for side in sides {
            let nodes: Vec<usize> = self.mesh.side_nodes(side).collect();
            let xs: Vec<[f64; 2]> = nodes.iter().map(|&n| self.mesh.nodes()[n]).collect();
            for &(s, w) in &GAUSS_3 {
                // 1D shapes on [−1, 1]: P1 (a, b); P2 (a, b, mid).
                let (n, dn): (Vec<f64>, Vec<f64>) = if nodes.len() == 2 {
                    (vec![(1.0 - s) / 2.0, (1.0 + s) / 2.0], vec![-0.5, 0.5])
                } else {
                    (
                        vec![s * (s - 1.0) / 2.0, s * (s + 1.0) / 2.0, 1.0 - s * s],
                        vec![s - 0.5, s + 0.5, -2.0 * s],
                    )
                };
                let mut x = [0.0; 2];
                let mut dx = [0.0; 2];
                for i in 0..nodes.len() {
                    for a in 0..2 {
                        x[a] += n[i] * xs[i][a];
                        dx[a] += dn[i] * xs[i][a];
                    }
                }
                let jac = dx[0].hypot(dx[1]);
                let t = traction(x);
                finite("traction", t[0])?;
                finite("traction", t[1])?;
                let wt = w * jac * self.idealization.weight(x[0]);
                for i in 0..nodes.len() {
                    self.load[2 * nodes[i]] += n[i] * t[0] * wt;
                    self.load[2 * nodes[i] + 1] += n[i] * t[1] * wt;
                }
            }
        }
        Ok(())
    }

    /// Adds the self-weight of every region (unit weight of its material, along `−y`/`−z`) to
    /// the reference loads.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] for a curved element with a non-positive Jacobian.
    pub fn add_self_weight(&mut self) -> Result<(), FemError> {
        let force = self.element_forces(|element, e, coords, idealization, f_e| {
            let gamma = self.materials[&self.mesh.regions()[e]].unit_weight();
            element.body_force_into(e, coords, idealization, &|_| [0.0, -gamma], f_e)
        })?;
        self.load.iter_mut().zip(force).for_each(|(l, f)| *l += f);
        Ok(())
    }

    /// Integrates an element-level force over every element and scatters it into a vector of
    /// nodal components (`2 × node_count`); `f_e` is zeroed before each element.
    fn element_forces(
        &self,
        integrate: impl Fn(
            &dyn Element<2>,
            usize,
            &[[f64; 2]],
            &Idealization,
            &mut [f64],
        ) -> Result<(), FemError>,
    ) -> Result<Vec<f64>, FemError> {
        let mut force = vec![0.0; 2 * self.mesh.node_count()];
        let mut coords = Vec::with_capacity(6);
        let mut f_e = vec![0.0; 12];
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            coords.clear();
            coords.extend(cell.iter().map(|&n| self.mesh.nodes()[n]));
            f_e.resize(2 * cell.len(), 0.0);
            f_e.fill(0.0);
            integrate(self.element_at(e), e, &coords, &self.idealization, &mut f_e)?;
            for (a, &n) in cell.iter().enumerate() {
                force[2 * n] += f_e[2 * a];
                force[2 * n + 1] += f_e[2 * a + 1];
            }
        }
        Ok(force)
    }

    /// Adds a body force `b(x)` (force per volume, global frame) over the whole mesh to the
    /// reference loads, integrated with the element's load rule (degree 2 for P1, 4 for P2).
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] for a curved element with a non-positive Jacobian;
    /// [`FemError::InvalidParameter`] if `b` returns a non-finite value.
    pub fn add_body_force(&mut self, b: impl Fn([f64; 2]) -> [f64; 2]) -> Result<(), FemError> {
        let force = self.element_forces(|element, e, coords, idealization, f_e| {
            element.body_force_into(e, coords, idealization, &b, f_e)
        })?;
        if let Some(&value) = force.iter().find(|v| !v.is_finite()) {
            return Err(FemError::InvalidParameter {
                name: "body force",
                value,
                expected: "a finite body force",
            });
        }
        self.load.iter_mut().zip(force).for_each(|(l, f)| *l += f);
        Ok(())
    }

    /// Sets the initial stress field `σ₀` (replacing any previous one) and its internal forces
    /// `−∫ Bᵀ σ₀ w dA`, which enter every free response.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`]; [`FemError::InvalidParameter`] if `σ₀` is not finite at
    /// a quadrature point.
    pub fn set_initial_stress(&mut self, sigma_0: StressField) -> Result<(), FemError> {
        let force = self.element_forces(|element, e, coords, idealization, f_e| {
            element.initial_stress_force_into(e, coords, idealization, &*sigma_0, f_e)
        })?;
        if let Some(&value) = force.iter().find(|v| !v.is_finite()) {
            return Err(FemError::InvalidParameter {
                name: "initial stress",
                value,
                expected: "a finite stress field",
            });
        }
        self.initial_force = force;
        self.initial_stress = Some(sigma_0);
        Ok(())
    }

    /// Removes every reference load (nodal forces, tractions, self-weight).
    pub fn clear_loads(&mut self) {
        self.load.fill(0.0);
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

    /// Nodal displacements `[u_x, u_y]` from the free-dof solution `u_free` and the prescribed
    /// values.
    ///
    /// # Panics
    /// If `u_free.len() != dof_count()`.
    #[track_caller]
    pub fn nodal_displacements(&self, u_free: &[f64]) -> Vec<[f64; 2]> {
        assert_eq!(u_free.len(), self.dofs.free_count(), "solution length");
        self.dofs
            .expand(u_free, &self.dofs.prescribed_values(&self.supports))
    }

    /// Solves the free response at `load_factor` and returns the nodal displacements.
    ///
    /// # Errors
    /// As for [`Structure::free_response_into`].
    pub fn solve(&self, load_factor: f64) -> Result<Vec<[f64; 2]>, FemError> {
        let mut u = vec![0.0; self.dofs.free_count()];
        self.free_response_into(load_factor, &mut u)?;
        Ok(self.nodal_displacements(&u))
    }
}

impl Structure for LinearElasticModel {
    fn outward_normal(&self, node: usize) -> Option<[f64; 2]> {
        self.normals.get_or_init(|| self.mesh.outward_normals())[node]
    }

    fn dof_count(&self) -> usize {
        self.dofs.free_count()
    }

    fn node_count(&self) -> usize {
        self.mesh.node_count()
    }

    fn node_position(&self, node: usize) -> [f64; 2] {
        self.mesh.nodes()[node]
    }

    fn node_dofs(&self, node: usize) -> [Option<usize>; 2] {
        self.dofs.free_dofs(node)
    }

    fn prescribed_displacement(&self, node: usize) -> [f64; 2] {
        let d = self.dofs.dofs(node);
        [Component::X, Component::Y].map(|c| match d[c as usize] {
            Dof::Prescribed(_) => self.supports.value(node, c).unwrap_or(0.0),
            Dof::Free(_) => 0.0,
        })
    }

    fn idealization(&self) -> Idealization {
        self.idealization
    }

    fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), FemError> {
        if self.pinned.is_empty() {
            self.solver.solve_in_place(rhs);
        } else {
            // x = P K⁺ P b (crate::rigid_modes)
            self.project(rhs, true);
            self.solver.solve_in_place(rhs);
            self.project(rhs, false);
        }
        Ok(())
    }

    fn solve_many_in_place(&self, mut rhs: MatMut<'_, f64>) -> Result<(), FemError> {
        if self.pinned.is_empty() {
            self.solver.solve_many_in_place(rhs);
        } else {
            for c in 0..rhs.ncols() {
                self.project_column(rhs.as_mut().col_mut(c), true);
            }
            self.solver.solve_many_in_place(rhs.as_mut());
            for c in 0..rhs.ncols() {
                self.project_column(rhs.as_mut().col_mut(c), false);
            }
        }
        Ok(())
    }

    fn free_response_into(&self, load_factor: f64, u: &mut [f64]) -> Result<(), FemError> {
        if !load_factor.is_finite() {
            return Err(FemError::NonFiniteSolve {
                what: "load factor",
                node: None,
                value: load_factor,
            });
        }
        self.rhs_into(load_factor, u);
        self.check_finite("right-hand side", u)?;
        self.solve_in_place(u)?;
        self.check_finite("displacement", u)
    }

    fn floating(&self) -> Option<&dyn Floating> {
        (!self.modes.is_empty()).then_some(self)
    }

    fn stiffness_version(&self) -> u64 {
        self.version
    }

    fn stiffness_matrix(&self) -> Option<faer::sparse::SparseColMatRef<'_, usize, f64>> {
        Some(self.stiffness())
    }
}

/// Asked only through [`Structure::floating`], which offers the model when its supports leave
/// modes ([`LinearElasticModel::floating`]).
impl Floating for LinearElasticModel {
    fn rigid_body_modes(&self) -> &RigidBodyModes {
        &self.modes
    }

    fn rigid_body_load_into(&self, load_factor: f64, out: &mut [f64]) -> Result<(), FemError> {
        self.mode_load_into(load_factor, out)
    }
}

impl LinearElasticModel {
    /// The rigid-body modes the supports leave, or `None` when `K` is positive definite: the
    /// modes of [`Structure::floating`].
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

#[cfg(test)]
mod tests;
