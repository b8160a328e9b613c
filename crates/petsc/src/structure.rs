//! [`PetscStructure`]: a linear elastic body (3D, or 2D in plane strain, plane stress or
//! axisymmetry) whose stiffness is a distributed PETSc matrix, seen by the contact solver
//! through fem-core's [`Structure`] trait.
//!
//! ```text
//! every rank      holds the whole mesh, the dof map and the partition (computed alike)
//! rank p          assembles K_e of its elements into the MPIAIJ matrix (rows of other ranks
//!                 travel at MatAssembly) and keeps K_fp of its elements (prescribed columns)
//! a solve         rank 0's right-hand side -> distributed b (VecScatter from zero, reversed)
//!                 -> KSPSolve -> x gathered whole on every rank (VecScatter to all)
//! loads           f = factor · f_ext + f_σ₀ − K_fp ū: the nodal forces, body forces and
//!                 self-weight (f_ext, scaled) and the initial stress's forces (f_σ₀, not
//!                 scaled) integrated whole on every rank by fem-core's element kernels and
//!                 applied from rank 0; K_fp ū from each rank's own elements
//! ```
//! The contact solver runs on every rank with the same data: its inputs to the structure are
//! taken from rank 0 and its outputs are the same bits everywhere, so the interface (the
//! candidates, `F*`, the local solve) is rank 0's, broadcast. Every method that solves is
//! collective: every rank must call it, in the same order (what running the same program on
//! every rank gives).

use crate::assembly::{self, Body, Coupling};
use crate::error::PetscError;
use crate::ffi::PetscInt;
use crate::linalg::System;
use crate::partition::{Partition, Partitioner};
use crate::runtime::PetscHandle;
use crate::solver::LinearSolver;
use fem_core::element::{Element, Setting};
use fem_core::faer::MatMut;
use fem_core::model::ModelSpace;
use fem_core::solid::SolidMesh;
use fem_core::{
    Component, Dim, DofMap, FemError, Idealization, Material, Mesh, Space, StressField, Structure,
    Supports,
};
use std::cell::Cell;
use std::collections::{BTreeMap, BTreeSet};
use std::sync::OnceLock;

/// A linear elastic body solved by PETSc (module docs): the distributed counterpart of
/// fem-core's [`ElasticModel`](fem_core::ElasticModel) for a body held by its supports
/// (positive definite `K`), in 3D ([`PetscStructure::new`], the default `D`) or in the plane
/// ([`PetscStructure::plane`]: plane strain, plane stress, axisymmetry), with nodal forces,
/// body forces, self-weight, an initial stress and prescribed displacements as loads.
///
/// Its free-dof numbering is the [`DofMap`]'s, the same as an `ElasticModel` built from the
/// same mesh and supports, so the two give the same contact problem; its element matrices
/// and loads are fem-core's kernels, called as the `ElasticModel` calls them; its solves
/// agree with the direct path to the solver's tolerance ([`LinearSolver`]).
///
/// # Examples
/// Run under `mpirun -n 2` (or alone): `crates/petsc/examples/petsc_check.rs` builds the
/// block, steps Coulomb contact on it and compares with the direct path (and the seed's
/// pile, axisymmetric, in `examples/support/pile.rs`).
/// ```no_run
/// use bipotential_petsc::{LinearSolver, Petsc, PetscStructure};
/// use fem_core::solid::generate::{box_mesh, lines};
/// use fem_core::solid::SolidKind;
/// use fem_core::{Component, Material, Structure, Supports};
/// let petsc = Petsc::init().unwrap();
/// petsc.or_abort(|| -> Result<(), Box<dyn std::error::Error>> {
///     let mesh = box_mesh(&lines(0.0, 1.0, 2), &lines(0.0, 1.0, 2), &lines(0.0, 1.0, 2),
///         SolidKind::Tet10)?;
///     let mut s = Supports::new();
///     s.fix(mesh.node_set("z0")?, Component::Z).fix(mesh.node_set("x0")?, Component::X)
///         .fix(mesh.node_set("y0")?, Component::Y);
///     s.prescribe(mesh.node_set("z1")?, Component::Z, -1e-3)?;
///     let body = PetscStructure::new(&petsc, mesh, &[(0, Material::new(1e3, 0.3, 0.0)?)], s,
///         LinearSolver::default())?;
///     let mut u = vec![0.0; body.dof_count()];
///     body.free_response_into(1.0, &mut u)?; // the same u on every rank
///     Ok(())
/// });
/// ```
pub struct PetscStructure<'p, const D: usize = 3>
where
    Dim<D>: Space,
{
    mesh: Mesh<D>,
    setting: Setting<D>,
    materials: BTreeMap<u32, Material>,
    supports: Supports,
    dofs: DofMap<D>,
    partition: Partition,
    rank: usize,
    system: System,
    /// `K_fp` of this rank's elements.
    coupling: Vec<Coupling>,
    /// Reference external forces, `D × node_count` (rank 0's are the ones applied).
    load: Vec<f64>,
    /// The initial stress's internal forces, `D × node_count` (not scaled).
    initial_force: Vec<f64>,
    /// Outward normals of the boundary nodes, computed at the first request.
    normals: OnceLock<Vec<Option<[f64; D]>>>,
    solves: Cell<usize>,
    iterations: Cell<usize>,
    /// Whether [`Structure::solve_many_in_place`] solves its columns in blocks
    /// (`KSPMatSolve`) rather than one after the other.
    batched: bool,
    /// Whether the solver is direct (MUMPS), the one that may batch.
    direct: bool,
    /// Last: dropped after `system`'s PETSc objects (a shared handle may finalise PETSc).
    _petsc: PetscHandle<'p>,
}

impl<const D: usize> core::fmt::Debug for PetscStructure<'_, D>
where
    Dim<D>: Space,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PetscStructure")
            .field("dimension", &<Dim<D> as Space>::NAME)
            .field("setting", &self.setting)
            .field("nodes", &self.mesh.node_count())
            .field("free_dofs", &self.dofs.free_count())
            .field("rank", &self.rank)
            .field("offsets", &self.partition.offsets)
            .finish()
    }
}

impl<'p> PetscStructure<'p, 3> {
    /// Partitions the mesh over the ranks ([`Partition::slabs`]), assembles each rank's
    /// elements into the distributed stiffness and sets up the solver. Collective.
    ///
    /// # Errors
    /// - [`FemError::MissingMaterial`] for a region without a material, fem-core's element
    ///   errors ([`FemError::InvertedElement`], …), [`FemError::NonFiniteStiffness`];
    /// - [`PetscError::Unsupported`] for tied supports;
    /// - [`PetscError::InvalidSetting`] for a bad `solver`;
    /// - [`PetscError::Call`] if PETSc fails (then on every rank, or the failing rank
    ///   should end all through [`Petsc::or_abort`](crate::Petsc::or_abort)).
    pub fn new(
        petsc: impl Into<PetscHandle<'p>>,
        mesh: SolidMesh,
        materials: &[(u32, Material)],
        supports: Supports,
        solver: LinearSolver,
    ) -> Result<Self, PetscError> {
        Self::with_partitioner(petsc, mesh, materials, supports, solver, Partitioner::Slabs)
    }

    /// [`new`](Self::new) with the partition chosen ([`Partitioner::Graph`] cuts fewer nodes
    /// from three ranks on). Collective; the same errors as `new`.
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn with_partitioner(
        petsc: impl Into<PetscHandle<'p>>,
        mesh: SolidMesh,
        materials: &[(u32, Material)],
        supports: Supports,
        solver: LinearSolver,
        partitioner: Partitioner,
    ) -> Result<Self, PetscError> {
        Self::build(
            petsc.into(),
            mesh,
            (),
            materials,
            supports,
            (solver, partitioner),
        )
    }
}

impl<'p> PetscStructure<'p, 2> {
    /// The 2D body under `idealization` (plane strain, plane stress with its thickness,
    /// axisymmetry with `(r, z)` coordinates, forces per radian): as [`PetscStructure::new`].
    /// Collective.
    ///
    /// # Errors
    /// As [`PetscStructure::new`], and [`FemError::InvalidParameter`] for a plane-stress
    /// thickness that is not finite and positive, [`FemError::NegativeRadius`] in axisymmetry
    /// for a node at `r < 0`.
    ///
    /// # Examples
    /// A soil column under its weight and the geostatic stress it starts with (seed eq. 6.1),
    /// run under `mpirun` (the seed's pile: `examples/support/pile.rs`):
    /// ```no_run
    /// use bipotential_petsc::{LinearSolver, Petsc, PetscStructure};
    /// use fem_core::generate::{RectangleSpec, rectangle};
    /// use fem_core::{Component, Idealization, Material, Structure, Supports, geostatic};
    /// let petsc = Petsc::init().unwrap();
    /// petsc.or_abort(|| -> Result<(), Box<dyn std::error::Error>> {
    ///     let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [-4.0, 0.0], 2, 8))?;
    ///     let mut s = Supports::new();
    ///     s.fix(mesh.node_set("left")?, Component::X).fix(mesh.node_set("right")?, Component::X)
    ///         .fix(mesh.node_set("bottom")?, Component::Y);
    ///     let soil = Material::new(3e4, 0.33, 20.0)?; // E, ν, γ
    ///     let mut body = PetscStructure::plane(&petsc, mesh, Idealization::Axisymmetric,
    ///         &[(0, soil)], s, LinearSolver::Mumps)?;
    ///     body.add_self_weight()?;
    ///     body.set_initial_stress(geostatic(20.0, 0.43, 0.0))?;
    ///     let mut u = vec![0.0; body.dof_count()];
    ///     body.free_response_into(1.0, &mut u)?; // σ₀ balances the weight: u ≈ 0
    ///     Ok(())
    /// });
    /// ```
    pub fn plane(
        petsc: impl Into<PetscHandle<'p>>,
        mesh: Mesh<2>,
        idealization: Idealization,
        materials: &[(u32, Material)],
        supports: Supports,
        solver: LinearSolver,
    ) -> Result<Self, PetscError> {
        Self::with_setting(petsc, mesh, idealization, materials, supports, solver)
    }
}

impl<'p, const D: usize> PetscStructure<'p, D>
where
    Dim<D>: ModelSpace<D>,
{
    /// [`PetscStructure::new`] (3D, `setting` = `()`) or [`PetscStructure::plane`] (2D,
    /// `setting` the idealisation), for code written once over the dimension (a model's
    /// `setting()`). Collective.
    ///
    /// # Errors
    /// As [`PetscStructure::plane`].
    pub fn with_setting(
        petsc: impl Into<PetscHandle<'p>>,
        mesh: Mesh<D>,
        setting: Setting<D>,
        materials: &[(u32, Material)],
        supports: Supports,
        solver: LinearSolver,
    ) -> Result<Self, PetscError> {
        match <Dim<D> as Space>::idealization(&setting).copied() {
            Some(Idealization::PlaneStress { thickness })
                if !(thickness.is_finite() && thickness > 0.0) =>
            {
                return Err(FemError::InvalidParameter {
                    name: "thickness",
                    value: thickness,
                    expected: "a finite value > 0",
                }
                .into());
            }
            Some(Idealization::Axisymmetric) => {
                if let Some((node, p)) = mesh.nodes().iter().enumerate().find(|(_, p)| p[0] < 0.0) {
                    return Err(FemError::NegativeRadius { node, r: p[0] }.into());
                }
            }
            _ => {}
        }
        Self::build(
            petsc.into(),
            mesh,
            setting,
            materials,
            supports,
            (solver, Partitioner::Slabs),
        )
    }

    fn build(
        petsc: PetscHandle<'p>,
        mesh: Mesh<D>,
        setting: Setting<D>,
        materials: &[(u32, Material)],
        supports: Supports,
        (solver, partitioner): (LinearSolver, Partitioner),
    ) -> Result<Self, PetscError> {
        solver.validate()?;
        if !supports.ties().is_empty() {
            return Err(PetscError::Unsupported {
                what: "tied supports (several nodes sharing a dof)",
            });
        }
        let materials: BTreeMap<u32, Material> = materials.iter().copied().collect();
        for (element, region) in mesh.regions().iter().enumerate() {
            if !materials.contains_key(region) {
                return Err(FemError::MissingMaterial {
                    region: *region,
                    element,
                }
                .into());
            }
        }
        let dofs = DofMap::<D>::numbered(mesh.node_count(), &supports)?;
        let (rank, size) = (petsc.rank(), petsc.size());
        let partition = partitioner.partition(&mesh, &dofs, size);
        let (d_nnz, o_nnz) = assembly::preallocation(&mesh, &dofs, &partition, rank)?;
        let owned = partition.offsets[rank + 1] - partition.offsets[rank];
        let mut system = System::new(owned, dofs.free_count(), &d_nnz, &o_nnz)?;
        let body = Body {
            mesh: &mesh,
            setting: &setting,
            materials: &materials,
            dofs: &dofs,
            partition: &partition,
        };
        let coupling = assembly::assemble(&body, rank, &system)?;
        if matches!(solver, LinearSolver::CgGamg { .. }) {
            let modes = assembly::rigid_modes(&mesh, &setting, &dofs, &partition);
            system.set_near_null_space(&modes, partition.offsets[rank])?;
        }
        system.assemble_and_set_up(solver)?;
        let n = D * mesh.node_count();
        Ok(Self {
            mesh,
            setting,
            materials,
            supports,
            dofs,
            partition,
            rank,
            system,
            coupling,
            load: vec![0.0; n],
            initial_force: vec![0.0; n],
            normals: OnceLock::new(),
            solves: Cell::new(0),
            iterations: Cell::new(0),
            batched: matches!(solver, LinearSolver::Mumps),
            direct: matches!(solver, LinearSolver::Mumps),
            _petsc: petsc,
        })
    }

    /// Adds a force on `node` (`D` components; in 2D per unit thickness, thickness, or
    /// radian as the idealisation says) to the reference load (scaled by the load factor).
    ///
    /// # Errors
    /// [`FemError::UnknownNode`] for a node outside the mesh, [`FemError::InvalidParameter`]
    /// for a non-finite force.
    pub fn add_nodal_force(&mut self, node: usize, force: [f64; D]) -> Result<(), PetscError> {
        if node >= self.mesh.node_count() {
            return Err(FemError::UnknownNode {
                node,
                node_count: self.mesh.node_count(),
                what: "a nodal force",
            }
            .into());
        }
        for f in force {
            finite("nodal force", f)?;
        }
        for (c, f) in force.into_iter().enumerate() {
            self.load[D * node + c] += f;
        }
        Ok(())
    }

    /// Adds the self-weight of every region (unit weight of its material, along the last
    /// coordinate downwards: `−y` in 2D, `−z` in 3D) to the reference load, as
    /// [`ElasticModel::add_self_weight`](fem_core::ElasticModel::add_self_weight) does.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] for a curved element with a non-positive Jacobian.
    pub fn add_self_weight(&mut self) -> Result<(), PetscError> {
        let force = self.element_forces(|element, e, coords, setting, f_e| {
            let gamma = self.materials[&self.mesh.regions()[e]].unit_weight();
            let mut g = [0.0; D];
            g[D - 1] = -gamma;
            element.body_force_into(e, coords, setting, &|_| g, f_e)
        })?;
        self.load.iter_mut().zip(force).for_each(|(l, f)| *l += f);
        Ok(())
    }

    /// Adds a body force `b(x)` (force per volume, global frame) over the whole mesh to the
    /// reference load, integrated with the element's load rule.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`]; [`FemError::InvalidParameter`] if `b` returns a
    /// non-finite value.
    pub fn add_body_force(&mut self, b: impl Fn([f64; D]) -> [f64; D]) -> Result<(), PetscError> {
        let force = self.element_forces(|element, e, coords, setting, f_e| {
            element.body_force_into(e, coords, setting, &b, f_e)
        })?;
        if let Some(&value) = force.iter().find(|v| !v.is_finite()) {
            finite("body force", value)?;
        }
        self.load.iter_mut().zip(force).for_each(|(l, f)| *l += f);
        Ok(())
    }

    /// Sets the initial stress field `σ₀` of every region (replacing any previous one): its
    /// internal forces `−∫ Bᵀ σ₀ w dV` enter every free response, unscaled, as in
    /// [`ElasticModel::set_initial_stress`](fem_core::ElasticModel::set_initial_stress).
    ///
    /// # Errors
    /// As [`PetscStructure::set_initial_stress_by_region`].
    pub fn set_initial_stress(&mut self, sigma_0: StressField<D>) -> Result<(), PetscError> {
        let regions: BTreeSet<u32> = self.mesh.regions().iter().copied().collect();
        let fields: Vec<_> = regions.into_iter().map(|r| (r, sigma_0.clone())).collect();
        self.set_initial_stress_by_region(&fields)
    }

    /// Sets one initial stress field per region (replacing any previous one); elements of
    /// regions not listed start unstressed (a geostatic soil around an unstressed pile).
    ///
    /// # Errors
    /// [`FemError::UnknownRegion`] for a region no element has; [`FemError::InvertedElement`];
    /// [`FemError::InvalidParameter`] if `σ₀` is not finite at a quadrature point.
    pub fn set_initial_stress_by_region(
        &mut self,
        fields: &[(u32, StressField<D>)],
    ) -> Result<(), PetscError> {
        let regions = self.mesh.regions();
        if let Some((region, _)) = fields.iter().find(|(r, _)| !regions.contains(r)) {
            return Err(FemError::UnknownRegion { region: *region }.into());
        }
        let force = self.element_forces(|element, e, coords, setting, f_e| {
            match fields.iter().find(|(r, _)| *r == regions[e]) {
                Some((_, sigma_0)) => {
                    element.initial_stress_force_into(e, coords, setting, &**sigma_0, f_e)
                }
                None => Ok(()),
            }
        })?;
        if let Some(&value) = force.iter().find(|v| !v.is_finite()) {
            finite("initial stress", value)?;
        }
        self.initial_force = force;
        Ok(())
    }

    /// Removes every reference load (nodal forces, body forces, self-weight); the initial
    /// stress stays.
    pub fn clear_loads(&mut self) {
        self.load.fill(0.0);
    }

    /// Integrates an element-level force over every element of the mesh (on every rank, so
    /// that rank 0 holds the whole vector it applies) and scatters it into nodal components
    /// (`D × node_count`); `f_e` is zeroed before each element.
    fn element_forces(
        &self,
        integrate: impl Fn(
            &dyn Element<D>,
            usize,
            &[[f64; D]],
            &Setting<D>,
            &mut [f64],
        ) -> Result<(), FemError>,
    ) -> Result<Vec<f64>, FemError> {
        let element = self.mesh.built_in_element();
        let mut force = vec![0.0; D * self.mesh.node_count()];
        let mut coords = Vec::with_capacity(element.node_count());
        let mut f_e = Vec::new();
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            self.mesh.element_coords_into(e, &mut coords);
            f_e.resize(D * cell.len(), 0.0);
            f_e.fill(0.0);
            integrate(element, e, &coords, &self.setting, &mut f_e)?;
            for (a, &n) in cell.iter().enumerate() {
                for c in 0..D {
                    force[D * n + c] += f_e[D * a + c];
                }
            }
        }
        Ok(force)
    }

    /// Changes the value of prescribed displacements (no reassembly). Constraining a free
    /// dof would renumber the system: refused.
    ///
    /// # Errors
    /// [`PetscError::Unsupported`] if a node's `component` is not prescribed;
    /// [`FemError::InvalidParameter`] for a non-finite value.
    pub fn set_prescribed(
        &mut self,
        nodes: &[usize],
        component: Component,
        value: f64,
    ) -> Result<(), PetscError> {
        if nodes
            .iter()
            .any(|&n| n >= self.mesh.node_count() || self.supports.value(n, component).is_none())
        {
            return Err(PetscError::Unsupported {
                what: "prescribing a free (or unknown) dof: build the structure with it prescribed",
            });
        }
        self.supports.update(nodes, component, value)?;
        Ok(())
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh<D> {
        &self.mesh
    }

    /// The kinematic setting: the [`Idealization`] in 2D, `()` in 3D.
    pub fn setting(&self) -> &Setting<D> {
        &self.setting
    }

    /// The partition of the mesh over the ranks.
    pub fn partition(&self) -> &Partition {
        &self.partition
    }

    /// Solves the many right-hand sides of `F*` ([`Structure::solve_many_in_place`]) in
    /// blocks of [`BATCH_COLUMNS`] columns through `KSPMatSolve` (`on`), or one after the
    /// other. Batched is the default with [`LinearSolver::Mumps`] (one multi-right-hand-side
    /// solve per block, about twice as fast: docs/benchmarks.md, "Issue 41"); CG + GAMG
    /// solves one after the other. Every rank must set the same.
    ///
    /// # Errors
    /// [`PetscError::Unsupported`] for `on` with CG + GAMG: PETSc would iterate the columns
    /// one by one, slower than the loop, and report only the last column's convergence.
    pub fn set_batched_solves(&mut self, on: bool) -> Result<(), PetscError> {
        if on && !self.direct {
            return Err(PetscError::Unsupported {
                what: "batched solves with CG + GAMG (use LinearSolver::Mumps)",
            });
        }
        self.batched = on;
        Ok(())
    }

    /// The solves made so far (one per right-hand side) and their Krylov iterations in all
    /// (MUMPS counts one a solve, batched or not).
    pub fn solve_counts(&self) -> (usize, usize) {
        (self.solves.get(), self.iterations.get())
    }

    /// Solves once with `b` filled by `fill` on rank 0 (distributed numbering) plus `extra`
    /// entries added on every rank, and writes the solution in the serial numbering.
    fn solve_with(
        &self,
        fill: impl FnOnce(&mut [f64]),
        extra: Option<(&[PetscInt], &[f64])>,
        out: &mut [f64],
    ) -> Result<(), PetscError> {
        self.system.load_from_rank_0(fill)?;
        if let Some((rows, values)) = extra {
            self.system.add_to_b(rows, values)?;
        }
        let row = &self.partition.row;
        let its = self.system.solve(|x| {
            for (o, &r) in out.iter_mut().zip(row) {
                *o = x[r];
            }
        })?;
        self.solves.set(self.solves.get() + 1);
        self.iterations.set(self.iterations.get() + its);
        Ok(())
    }
}

/// The most columns one batched solve holds (`F*`'s right-hand sides): bounds the dense
/// blocks, `3 × BATCH_COLUMNS` whole vectors a rank at most.
pub const BATCH_COLUMNS: usize = 64;

/// [`FemError::InvalidParameter`] unless `value` is finite.
fn finite(name: &'static str, value: f64) -> Result<f64, FemError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(FemError::InvalidParameter {
            name,
            value,
            expected: "a finite number",
        })
    }
}

impl<const D: usize> Structure<D> for PetscStructure<'_, D>
where
    Dim<D>: ModelSpace<D>,
{
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
        Component::all::<D>().map(|c| self.supports.value(node, c).unwrap_or(0.0))
    }

    fn idealization(&self) -> Idealization {
        <Dim<D> as Space>::idealization(&self.setting)
            .copied()
            .unwrap_or(Idealization::PlaneStrain)
    }

    fn outward_normal(&self, node: usize) -> Option<[f64; D]> {
        self.normals
            .get_or_init(|| <Dim<D> as ModelSpace<D>>::outward_normals(&self.mesh))[node]
    }

    /// Solves the columns with the one KSP (its preconditioner built once): in blocks of
    /// [`BATCH_COLUMNS`] through `KSPMatSolve` if batched
    /// ([`set_batched_solves`](PetscStructure::set_batched_solves)), else one after the other.
    fn solve_many_in_place(&self, mut rhs: MatMut<'_, f64>) -> Result<(), FemError> {
        assert_eq!(rhs.nrows(), self.dof_count(), "rhs rows");
        let row = &self.partition.row;
        if self.batched {
            let mut block = Vec::new();
            for first in (0..rhs.ncols()).step_by(BATCH_COLUMNS) {
                let k = BATCH_COLUMNS.min(rhs.ncols() - first);
                block.clear();
                block.resize(k * row.len(), 0.0);
                for (i, &r) in row.iter().enumerate() {
                    for c in 0..k {
                        block[k * r + c] = rhs[(i, first + c)];
                    }
                }
                let its = self.system.solve_block(
                    k,
                    |whole| whole.copy_from_slice(&block),
                    |whole| {
                        for (i, &r) in row.iter().enumerate() {
                            for c in 0..k {
                                rhs[(i, first + c)] = whole[k * r + c];
                            }
                        }
                    },
                )?;
                self.solves.set(self.solves.get() + k);
                self.iterations.set(self.iterations.get() + k * its);
            }
            return Ok(());
        }
        let mut column = vec![0.0; rhs.nrows()];
        for c in 0..rhs.ncols() {
            for (i, v) in column.iter_mut().enumerate() {
                *v = rhs[(i, c)];
            }
            let mut out = vec![0.0; column.len()];
            self.solve_with(
                |whole| {
                    for (&r, &v) in row.iter().zip(&column) {
                        whole[r] = v;
                    }
                },
                None,
                &mut out,
            )?;
            for (i, v) in out.into_iter().enumerate() {
                rhs[(i, c)] = v;
            }
        }
        Ok(())
    }

    /// `f = factor · f_ext + f_σ₀ − K_fp ū`: the forces from rank 0, `K_fp ū` from each
    /// rank's elements.
    fn free_response_into(&self, load_factor: f64, u: &mut [f64]) -> Result<(), FemError> {
        assert_eq!(u.len(), self.dof_count(), "u length");
        if !load_factor.is_finite() {
            return Err(FemError::NonFiniteSolve {
                what: "load factor",
                node: None,
                value: load_factor,
            });
        }
        let (rows, values): (Vec<PetscInt>, Vec<f64>) = self
            .coupling
            .iter()
            .map(|&(r, n, c, k)| (r, -k * self.supports.value(n, c).unwrap_or(0.0)))
            .unzip();
        let fill = |whole: &mut [f64]| {
            for n in 0..self.mesh.node_count() {
                for (c, d) in self.dofs.free_dofs(n).into_iter().enumerate() {
                    if let Some(i) = d {
                        let k = D * n + c;
                        whole[self.partition.row[i]] +=
                            load_factor * self.load[k] + self.initial_force[k];
                    }
                }
            }
        };
        self.solve_with(fill, Some((&rows, &values)), u)?;
        match u.iter().position(|x| !x.is_finite()) {
            None => Ok(()),
            Some(i) => Err(FemError::NonFiniteSolve {
                what: "displacement",
                node: self.dofs.free_dof_owner(i),
                value: u[i],
            }),
        }
    }

    /// The stiffness never changes (no renumbering is offered).
    fn stiffness_version(&self) -> u64 {
        0
    }
}
