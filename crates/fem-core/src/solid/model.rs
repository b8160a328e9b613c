//! [`SolidModel`]: a 3D linear-elastic body on a tetrahedral mesh, assembled and factored once,
//! and the [`Structure<3>`](crate::Structure) the contact solver sees.

use crate::element::kernel::{field_at3, hooke, lame};

#[path = "model_elements.rs"]
mod elements;
use super::mesh::SolidMesh;
use crate::assembly::{Pattern, PrescribedCoupling, merge, scatter};
use crate::dirichlet::{Component, Dof, DofMap, Supports};
use crate::element::{Element, RegionElements, Stress3};
use crate::error::{FemError, finite};
use crate::linear_solver::SpdSolver;
use crate::material::Material;
use crate::ordering::{FillOrdering, nested_dissection};
use crate::structure::Structure;
use faer::MatMut;
use nalgebra::DMatrix;
use std::collections::BTreeMap;
use std::sync::Arc;

/// An initial stress field `σ₀(x)` in 3D (components as [`Stress3`]).
pub type StressField3 = Arc<dyn Fn([f64; 3]) -> Stress3 + Send + Sync>;

/// A stress at a point: `(x, σ)`.
pub type StressPoint3 = ([f64; 3], Stress3);

/// The geostatic initial stress for a ground surface at `z = z_surface` (`z` upwards) and unit
/// weight `gamma`: `σ_zz = −γ (z_surface − z)` (compression negative),
/// `σ_xx = σ_yy = K0 σ_zz`, no shear.
pub fn geostatic_3d(gamma: f64, k0: f64, z_surface: f64) -> StressField3 {
    Arc::new(move |x: [f64; 3]| {
        let s_v = -gamma * (z_surface - x[2]).max(0.0);
        [k0 * s_v, k0 * s_v, s_v, 0.0, 0.0, 0.0]
    })
}

/// A linear-elastic 3D body: mesh, materials per region, supports and loads, with its reduced
/// stiffness assembled and factored.
///
/// Loads are a reference load vector scaled by the load factor of
/// [`Structure::free_response_into`]; prescribed displacements and the initial stress are not
/// scaled. Changing a prescribed *value* never refactors; constraining dofs does. The supports
/// must hold the body: a body left with a rigid-body mode is refused (floating 3D bodies are
/// not supported yet).
pub struct SolidModel {
    mesh: SolidMesh,
    materials: BTreeMap<u32, Material>,
    supports: Supports,
    dofs: DofMap<3>,
    pattern: Pattern,
    values: Vec<f64>,
    coupling: PrescribedCoupling,
    solver: SpdSolver,
    /// Reference external loads per node component (`3 × node_count`).
    load: Vec<f64>,
    /// Internal forces of the initial stress per node component.
    initial_force: Vec<f64>,
    version: u64,
    ordering: FillOrdering,
    /// Users' elements by region ([`SolidModel::with_element`]).
    elements: RegionElements<3>,
}

impl core::fmt::Debug for SolidModel {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SolidModel")
            .field("nodes", &self.mesh.node_count())
            .field("elements", &self.mesh.element_count())
            .field("kind", &self.mesh.kind())
            .field("free_dofs", &self.dofs.free_count())
            .field("nnz", &self.pattern.nnz())
            .field("version", &self.version)
            .finish()
    }
}

impl SolidModel {
    /// Builds the model: checks the data, numbers the dofs, builds the sparsity pattern (and
    /// the fill-reducing ordering, once), assembles and factors `K`.
    ///
    /// # Errors
    /// - [`FemError::MissingMaterial`] if a region has no material;
    /// - [`FemError::UnknownNode`] for a support on a missing node;
    /// - [`FemError::InvertedElement`] for a (curved) element with a non-positive Jacobian;
    /// - [`FemError::NonFiniteStiffness`] for an element whose stiffness overflows;
    /// - [`FemError::NotPositiveDefinite`] if the supports leave a rigid-body mode of some
    ///   body of the mesh (naming a dof the mode moves), or `K` is singular otherwise.
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
        let materials: BTreeMap<u32, Material> = materials.iter().copied().collect();
        for (element, region) in mesh.regions().iter().enumerate() {
            if !materials.contains_key(region) {
                return Err(FemError::MissingMaterial {
                    region: *region,
                    element,
                });
            }
        }
        let dofs = DofMap::<3>::numbered(mesh.node_count(), &supports)?;
        super::modes::refuse_rigid_modes(&mesh, &supports, &dofs)?;
        let pattern = Pattern::new(&dofs, (0..mesh.element_count()).map(|e| mesh.element(e)))?;
        let solver = solver_for(&mesh, &dofs, &pattern, ordering)?;
        let n3 = 3 * mesh.node_count();
        let mut model = Self {
            values: vec![0.0; pattern.nnz()],
            mesh,
            materials,
            supports,
            dofs,
            pattern,
            coupling: PrescribedCoupling::default(),
            solver,
            load: vec![0.0; n3],
            initial_force: vec![0.0; n3],
            version: 0,
            ordering,
            elements: RegionElements::default(),
        };
        model.assemble_and_factor()?;
        Ok(model)
    }

    fn assemble_and_factor(&mut self) -> Result<(), FemError> {
        self.values.fill(0.0);
        let kind = self.mesh.kind();
        let mut k_e = DMatrix::zeros(0, 0);
        let mut coords = Vec::with_capacity(10);
        let mut coupling = Vec::new();
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            coords.clear();
            coords.extend(cell.iter().map(|&n| self.mesh.nodes()[n]));
            let region = self.mesh.regions()[e];
            let material = &self.materials[&region];
            let element = self.elements.get(region, kind.element());
            element.stiffness_into(e, &coords, material, &(), &mut k_e)?;
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
        self.solver
            .factor(self.pattern.view(&self.values))
            .map_err(|e| match e {
                FemError::NonPositivePivot { row: Some(row) } => {
                    match self.dofs.free_dof_owner(row) {
                        Some((node, component)) => FemError::NotPositiveDefinite {
                            node,
                            component,
                            row,
                        },
                        None => e,
                    }
                }
                e => e,
            })?;
        self.version += 1;
        Ok(())
    }

    /// Reassembles and refactors `K` with the same pattern and ordering (what a change of
    /// material costs; the benchmarks time it).
    ///
    /// # Errors
    /// As [`SolidModel::new`].
    pub fn refactor(&mut self) -> Result<(), FemError> {
        self.assemble_and_factor()
    }

    /// The mesh.
    #[inline]
    pub fn mesh(&self) -> &SolidMesh {
        &self.mesh
    }

    /// The dof numbering.
    #[inline]
    pub fn dof_map(&self) -> &DofMap<3> {
        &self.dofs
    }

    /// The supports.
    #[inline]
    pub fn supports(&self) -> &Supports {
        &self.supports
    }

    /// Number of numeric factorisations so far.
    #[inline]
    pub fn factorizations(&self) -> usize {
        self.solver.factorizations()
    }

    /// Stored entries of the lower triangle of `K`.
    #[inline]
    pub fn nnz(&self) -> usize {
        self.pattern.nnz()
    }

    /// Stored entries of the Cholesky factor of `K` (its fill with the model's ordering).
    #[inline]
    pub fn factor_nnz(&self) -> usize {
        self.solver.factor_nnz()
    }

    /// The reduced stiffness (lower triangle, CSC).
    #[inline]
    pub fn stiffness(&self) -> faer::sparse::SparseColMatRef<'_, usize, f64> {
        self.pattern.view(&self.values)
    }

    /// Sets the prescribed value of `component` on `nodes`. If every such dof is already
    /// constrained only the value changes (no refactorisation); otherwise the dofs are
    /// constrained, renumbered, and `K` is reassembled and refactored.
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] for a non-finite value; [`FemError::UnknownNode`];
    /// factorisation errors.
    pub fn set_prescribed(
        &mut self,
        nodes: &[usize],
        component: Component,
        value: f64,
    ) -> Result<(), FemError> {
        if let Some(&node) = nodes.iter().find(|&&n| n >= self.mesh.node_count()) {
            return Err(FemError::UnknownNode {
                what: "a prescribed displacement",
                node,
                node_count: self.mesh.node_count(),
            });
        }
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
        if let Some(&node) = nodes.iter().find(|&&n| n >= self.mesh.node_count()) {
            return Err(FemError::UnknownNode {
                what: "a released support",
                node,
                node_count: self.mesh.node_count(),
            });
        }
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

    /// Numbers the dofs for the current supports, rebuilds the pattern and the solver, and
    /// reassembles and refactors; on failure the supports `before` are restored (and the
    /// model with them).
    fn renumber(&mut self, before: Supports) -> Result<(), FemError> {
        let rebuilt = self.rebuild_numbering();
        if rebuilt.is_err() {
            self.supports = before;
            self.rebuild_numbering()?;
        }
        rebuilt
    }

    fn rebuild_numbering(&mut self) -> Result<(), FemError> {
        self.dofs = DofMap::<3>::numbered(self.mesh.node_count(), &self.supports)?;
        let mesh = &self.mesh;
        self.pattern = Pattern::new(
            &self.dofs,
            (0..mesh.element_count()).map(|e| mesh.element(e)),
        )?;
        self.solver = solver_for(&self.mesh, &self.dofs, &self.pattern, self.ordering)?;
        self.values = vec![0.0; self.pattern.nnz()];
        self.assemble_and_factor()
    }

    /// Adds a reference nodal force `[f_x, f_y, f_z]`.
    ///
    /// # Errors
    /// [`FemError::UnknownNode`]; [`FemError::InvalidParameter`] for non-finite values.
    pub fn add_nodal_force(&mut self, node: usize, force: [f64; 3]) -> Result<(), FemError> {
        if node >= self.mesh.node_count() {
            return Err(FemError::UnknownNode {
                what: "a nodal force",
                node,
                node_count: self.mesh.node_count(),
            });
        }
        for f in force {
            finite("nodal force", f)?;
        }
        for (c, f) in force.into_iter().enumerate() {
            self.load[3 * node + c] += f;
        }
        Ok(())
    }

    /// Adds a reference traction `t(x, n)` (force per area, global frame; `n` the unit outward
    /// normal of the face at `x`) on the faces of a face set, integrated with a degree-4 rule
    /// on each face (exact for a uniform traction or pressure on P2 faces). A pressure `p` is
    /// `|_, n| [−p n_x, −p n_y, −p n_z]`.
    ///
    /// # Errors
    /// [`FemError::UnknownSet`]; [`FemError::InvalidParameter`] if `t` returns a non-finite
    /// value.
    pub fn add_face_traction(
        &mut self,
        face_set: &str,
        traction: impl Fn([f64; 3], [f64; 3]) -> [f64; 3],
    ) -> Result<(), FemError> {
        let faces = self.mesh.face_set(face_set)?;
        let mut load = self.load.clone();
        for &face in faces {
            self.mesh.face_points(face, |nodes, p| {
                let t = traction(p.x, p.normal);
                for v in t {
                    finite("traction", v)?;
                }
                for (i, node) in nodes.iter().enumerate() {
                    for (a, ta) in t.iter().enumerate() {
                        load[3 * node + a] += p.n[i] * ta * p.weight;
                    }
                }
                Ok(())
            })?;
        }
        self.load = load;
        Ok(())
    }

    /// Adds the self-weight of every region (unit weight of its material, along `−z`).
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] for a curved element with a non-positive Jacobian.
    pub fn add_self_weight(&mut self) -> Result<(), FemError> {
        let force = self.element_forces(|element, e, coords, f_e| {
            let gamma = self.materials[&self.mesh.regions()[e]].unit_weight();
            element.body_force_into(e, coords, &(), &|_| [0.0, 0.0, -gamma], f_e)
        })?;
        self.load.iter_mut().zip(force).for_each(|(l, f)| *l += f);
        Ok(())
    }

    /// Adds a body force `b(x)` (force per volume) over the whole mesh, integrated with a
    /// 64-point rule per element (degree 5).
    ///
    /// # Errors
    /// [`FemError::InvertedElement`]; [`FemError::InvalidParameter`] if `b` returns a
    /// non-finite value.
    pub fn add_body_force(&mut self, b: impl Fn([f64; 3]) -> [f64; 3]) -> Result<(), FemError> {
        let force = self.element_forces(|element, e, coords, f_e| {
            element.body_force_into(e, coords, &(), &b, f_e)
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

    /// Sets the initial stress field `σ₀` (replacing any previous one): its internal forces
    /// `−∫ Bᵀ σ₀ dV` enter every free response.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`]; [`FemError::InvalidParameter`] if `σ₀` is not finite.
    pub fn set_initial_stress(&mut self, sigma_0: StressField3) -> Result<(), FemError> {
        let force = self.element_forces(|element, e, coords, f_e| {
            element.initial_stress_force_into(e, coords, &(), &*sigma_0, f_e)
        })?;
        if let Some(&value) = force.iter().find(|v| !v.is_finite()) {
            return Err(FemError::InvalidParameter {
                name: "initial stress",
                value,
                expected: "a finite stress field",
            });
        }
        self.initial_force = force;
        Ok(())
    }

    /// Sets one initial stress field per region (replacing any previous one); elements of
    /// regions not listed start unstressed. For fields that jump across a curved interface
    /// between regions (a pile in soil), where a position test would misclassify the
    /// quadrature points of curved P2 elements near the interface.
    ///
    /// # Errors
    /// [`FemError::UnknownRegion`] for a region no element has; as
    /// [`SolidModel::set_initial_stress`].
    pub fn set_initial_stress_by_region(
        &mut self,
        fields: &[(u32, StressField3)],
    ) -> Result<(), FemError> {
        for (region, _) in fields {
            if !self.mesh.regions().contains(region) {
                return Err(FemError::UnknownRegion { region: *region });
            }
        }
        let regions = self.mesh.regions();
        let force = self.element_forces(|element, e, coords, f_e| {
            match fields.iter().find(|(r, _)| *r == regions[e]) {
                Some((_, sigma_0)) => {
                    element.initial_stress_force_into(e, coords, &(), &**sigma_0, f_e)
                }
                None => Ok(()),
            }
        })?;
        if let Some(&value) = force.iter().find(|v| !v.is_finite()) {
            return Err(FemError::InvalidParameter {
                name: "initial stress",
                value,
                expected: "a finite stress field",
            });
        }
        self.initial_force = force;
        Ok(())
    }

    /// Removes every reference load (nodal forces, tractions, body forces).
    pub fn clear_loads(&mut self) {
        self.load.fill(0.0);
    }

    fn element_forces(
        &self,
        integrate: impl Fn(&dyn Element<3>, usize, &[[f64; 3]], &mut [f64]) -> Result<(), FemError>,
    ) -> Result<Vec<f64>, FemError> {
        let mut force = vec![0.0; 3 * self.mesh.node_count()];
        let mut coords = Vec::with_capacity(10);
        let mut f_e = vec![0.0; 30];
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            coords.clear();
            coords.extend(cell.iter().map(|&n| self.mesh.nodes()[n]));
            f_e.resize(3 * cell.len(), 0.0);
            f_e.fill(0.0);
            integrate(self.element_at(e), e, &coords, &mut f_e)?;
            for (a, &n) in cell.iter().enumerate() {
                for c in 0..3 {
                    force[3 * n + c] += f_e[3 * a + c];
                }
            }
        }
        Ok(force)
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

    /// Nodal displacements `[u_x, u_y, u_z]` from the free-dof solution and the prescribed
    /// values.
    ///
    /// # Panics
    /// If `u_free.len() != dof_count()`.
    #[track_caller]
    pub fn nodal_displacements(&self, u_free: &[f64]) -> Vec<[f64; 3]> {
        assert_eq!(u_free.len(), self.dofs.free_count(), "solution length");
        self.dofs
            .expand(u_free, &self.dofs.prescribed_values(&self.supports))
    }

    /// Support reactions `R = K u − f` at every prescribed dof, for the displacements
    /// `displacements` (from [`SolidModel::solve`] or a contact simulation) at `load_factor`:
    /// `((node, component), reaction)`.
    ///
    /// # Errors
    /// [`FemError::LengthMismatch`] if `displacements` does not have one entry per node.
    pub fn reactions(
        &self,
        displacements: &[[f64; 3]],
        load_factor: f64,
    ) -> Result<Vec<crate::Reaction>, FemError> {
        if displacements.len() != self.mesh.node_count() {
            return Err(FemError::LengthMismatch {
                what: "nodal displacements",
                expected: self.mesh.node_count(),
                got: displacements.len(),
            });
        }
        Ok(self.coupling.reactions(
            &self.dofs,
            displacements,
            &self.load,
            &self.initial_force,
            load_factor,
        ))
    }

    /// Solves the free response at `load_factor` and returns the nodal displacements.
    ///
    /// # Errors
    /// As for [`Structure::free_response_into`].
    pub fn solve(&self, load_factor: f64) -> Result<Vec<[f64; 3]>, FemError> {
        let mut u = vec![0.0; self.dofs.free_count()];
        self.free_response_into(load_factor, &mut u)?;
        Ok(self.nodal_displacements(&u))
    }

    /// Stresses `D ε(u)` (without `σ₀`) at the quadrature points of every element, element
    /// by element.
    ///
    /// # Errors
    /// [`FemError::LengthMismatch`] if `displacements` has not one entry per node;
    /// [`FemError::InvertedElement`].
    pub fn stresses(&self, displacements: &[[f64; 3]]) -> Result<Vec<Vec<StressPoint3>>, FemError> {
        if displacements.len() != self.mesh.node_count() {
            return Err(FemError::LengthMismatch {
                what: "displacements",
                expected: self.mesh.node_count(),
                got: displacements.len(),
            });
        }
        let mut out = Vec::with_capacity(self.mesh.element_count());
        let mut coords = Vec::with_capacity(10);
        let mut u_e = Vec::with_capacity(30);
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            coords.clear();
            coords.extend(cell.iter().map(|&n| self.mesh.nodes()[n]));
            u_e.clear();
            u_e.extend(cell.iter().flat_map(|&n| displacements[n]));
            let material = &self.materials[&self.mesh.regions()[e]];
            let mut points = Vec::with_capacity(4);
            let element = self.element_at(e);
            element.stresses_into(e, &coords, material, &(), &u_e, &mut points)?;
            out.push(points);
        }
        Ok(out)
    }

    /// The errors of a displacement field against an exact one, `exact(x) = (u, ∇u)`
    /// (`∇u[i][j] = ∂u_i/∂x_j`), integrated with a 64-point rule per element:
    /// `(‖u − u*‖_L2, ‖u − u*‖_E)` with the energy norm `‖v‖_E² = ∫ ε(v) : C : ε(v) dV`.
    ///
    /// # Errors
    /// [`FemError::LengthMismatch`] if `displacements` has not one entry per node;
    /// [`FemError::InvertedElement`].
    pub fn error_norms(
        &self,
        displacements: &[[f64; 3]],
        exact: impl Fn([f64; 3]) -> ([f64; 3], [[f64; 3]; 3]),
    ) -> Result<(f64, f64), FemError> {
        if displacements.len() != self.mesh.node_count() {
            return Err(FemError::LengthMismatch {
                what: "displacements",
                expected: self.mesh.node_count(),
                got: displacements.len(),
            });
        }
        let (mut l2, mut energy) = (0.0, 0.0);
        let mut coords = Vec::with_capacity(10);
        let mut u_e = Vec::with_capacity(30);
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            coords.clear();
            coords.extend(cell.iter().map(|&n| self.mesh.nodes()[n]));
            u_e.clear();
            u_e.extend(cell.iter().flat_map(|&n| displacements[n]));
            let (lambda, mu) = lame(self.material(e));
            let element = self.element_at(e);
            for &q in element.load_rule(&()) {
                let (x, u, eps, w) = field_at3(element, e, &coords, &u_e, q)?;
                let (ue, g) = exact(x);
                let de: Stress3 = [
                    eps[0] - g[0][0],
                    eps[1] - g[1][1],
                    eps[2] - g[2][2],
                    eps[3] - 0.5 * (g[0][1] + g[1][0]),
                    eps[4] - 0.5 * (g[1][2] + g[2][1]),
                    eps[5] - 0.5 * (g[2][0] + g[0][2]),
                ];
                let s = hooke(lambda, mu, de);
                let inner = s[0] * de[0]
                    + s[1] * de[1]
                    + s[2] * de[2]
                    + 2.0 * (s[3] * de[3] + s[4] * de[4] + s[5] * de[5]);
                energy += w * inner;
                l2 += w * (0..3).map(|i| (u[i] - ue[i]).powi(2)).sum::<f64>();
            }
        }
        Ok((l2.sqrt(), energy.sqrt()))
    }

    /// The material of element `e`'s region.
    ///
    /// # Panics
    /// If `e >= element_count()`.
    #[track_caller]
    pub fn material(&self, e: usize) -> &Material {
        &self.materials[&self.mesh.regions()[e]]
    }
}

/// The symbolic factorisation of `pattern` with `ordering` (nested dissection on the position
/// of each free dof's first node).
fn solver_for(
    mesh: &SolidMesh,
    dofs: &DofMap<3>,
    pattern: &Pattern,
    ordering: FillOrdering,
) -> Result<SpdSolver, FemError> {
    match ordering {
        FillOrdering::Amd => SpdSolver::new(pattern.symbolic().as_ref()),
        FillOrdering::NestedDissection => {
            let mut coords = vec![[f64::NAN; 3]; dofs.free_count()];
            for node in (0..mesh.node_count()).rev() {
                for d in dofs.free_dofs(node).into_iter().flatten() {
                    coords[d] = mesh.nodes()[node];
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

impl Structure<3> for SolidModel {
    fn dof_count(&self) -> usize {
        self.dofs.free_count()
    }

    fn node_count(&self) -> usize {
        self.mesh.node_count()
    }

    fn node_position(&self, node: usize) -> [f64; 3] {
        self.mesh.nodes()[node]
    }

    fn node_dofs(&self, node: usize) -> [Option<usize>; 3] {
        self.dofs.free_dofs(node)
    }

    fn prescribed_displacement(&self, node: usize) -> [f64; 3] {
        let d = self.dofs.dofs(node);
        Component::all::<3>().map(|c| match d[c as usize] {
            Dof::Prescribed(_) => self.supports.value(node, c).unwrap_or(0.0),
            Dof::Free(_) => 0.0,
        })
    }

    fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), FemError> {
        self.solver.solve_in_place(rhs);
        Ok(())
    }

    fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), FemError> {
        self.solver.solve_many_in_place(rhs);
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
        let check = |what, v: &[f64]| match v.iter().position(|x| !x.is_finite()) {
            None => Ok(()),
            Some(i) => Err(FemError::NonFiniteSolve {
                what,
                node: self.dofs.free_dof_owner(i),
                value: v[i],
            }),
        };
        check("right-hand side", u)?;
        self.solver.solve_in_place(u);
        check("displacement", u)
    }

    fn stiffness_version(&self) -> u64 {
        self.version
    }

    fn stiffness_matrix(&self) -> Option<faer::sparse::SparseColMatRef<'_, usize, f64>> {
        Some(self.stiffness())
    }
}
