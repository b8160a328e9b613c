//! [`PetscStructure`]: a 3D linear elastic body whose stiffness is a distributed PETSc
//! matrix, seen by the contact solver through fem-core's [`Structure`] trait.
//!
//! ```text
//! every rank      holds the whole mesh, the dof map and the partition (computed alike)
//! rank p          assembles K_e of its elements into the MPIAIJ matrix (rows of other ranks
//!                 travel at MatAssembly) and keeps K_fp of its elements (prescribed columns)
//! a solve         rank 0's right-hand side -> distributed b (VecScatter from zero, reversed)
//!                 -> KSPSolve -> x gathered whole on every rank (VecScatter to all)
//! ```
//! The contact solver runs on every rank with the same data: its inputs to the structure are
//! taken from rank 0 and its outputs are the same bits everywhere, so the interface (the
//! candidates, `F*`, the local solve) is rank 0's, broadcast. Every method that solves is
//! collective: every rank must call it, in the same order (what running the same program on
//! every rank gives).

use crate::error::PetscError;
use crate::ffi::PetscInt;
use crate::linalg::{System, int};
use crate::partition::{Partition, Partitioner};
use crate::runtime::Petsc;
use crate::solver::LinearSolver;
use fem_core::dirichlet::Dof;
use fem_core::faer::MatMut;
use fem_core::solid::SolidMesh;
use fem_core::{Component, DofMap, FemError, Material, Structure, Supports};
use std::cell::Cell;
use std::collections::BTreeMap;
use std::marker::PhantomData;

/// A 3D linear elastic body solved by PETSc (module docs): the distributed counterpart of
/// fem-core's [`SolidModel`](fem_core::solid::SolidModel) for a body held by its supports
/// (positive definite `K`), with nodal forces and prescribed displacements as loads.
///
/// Its free-dof numbering is the [`DofMap`]'s, the same as a `SolidModel` built from the
/// same mesh and supports, so the two give the same contact problem; its solves agree with
/// the direct path to the solver's tolerance ([`LinearSolver`]).
///
/// # Examples
/// Run under `mpirun -n 2` (or alone): `crates/petsc/examples/petsc_check.rs` builds the
/// block, steps Coulomb contact on it and compares with the direct path.
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
pub struct PetscStructure<'p> {
    mesh: SolidMesh,
    supports: Supports,
    dofs: DofMap<3>,
    partition: Partition,
    rank: usize,
    system: System,
    /// `K_fp` of this rank's elements: (distributed row, node, component, value).
    coupling: Vec<(PetscInt, usize, Component, f64)>,
    /// Reference nodal forces, `3 × node_count` (rank 0's are the ones applied).
    load: Vec<f64>,
    solves: Cell<usize>,
    iterations: Cell<usize>,
    _petsc: PhantomData<&'p Petsc>,
}

impl core::fmt::Debug for PetscStructure<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PetscStructure")
            .field("nodes", &self.mesh.node_count())
            .field("free_dofs", &self.dofs.free_count())
            .field("rank", &self.rank)
            .field("offsets", &self.partition.offsets)
            .finish()
    }
}

impl<'p> PetscStructure<'p> {
    /// Partitions the mesh over the ranks ([`Partition::slabs`]), assembles each rank's
    /// elements into the distributed stiffness and sets up the solver. Collective.
    ///
    /// # Errors
    /// - [`FemError::MissingMaterial`] for a region without a material, fem-core's element
    ///   errors ([`FemError::InvertedElement`], …), [`FemError::NonFiniteStiffness`];
    /// - [`PetscError::Unsupported`] for tied supports;
    /// - [`PetscError::InvalidSetting`] for a bad `solver`;
    /// - [`PetscError::Call`] if PETSc fails (then on every rank, or the failing rank
    ///   should end all through [`Petsc::or_abort`]).
    pub fn new(
        petsc: &'p Petsc,
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
        petsc: &'p Petsc,
        mesh: SolidMesh,
        materials: &[(u32, Material)],
        supports: Supports,
        solver: LinearSolver,
        partitioner: Partitioner,
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
        let dofs = DofMap::<3>::numbered(mesh.node_count(), &supports)?;
        let (rank, size) = (petsc.rank(), petsc.size());
        let partition = partitioner.partition(&mesh, &dofs, size);
        let (d_nnz, o_nnz) = preallocation(&mesh, &dofs, &partition, rank)?;
        let owned = partition.offsets[rank + 1] - partition.offsets[rank];
        let mut system = System::new(owned, dofs.free_count(), &d_nnz, &o_nnz)?;
        let coupling = assemble(&mesh, &materials, &dofs, &partition, rank, &system)?;
        if matches!(solver, LinearSolver::CgGamg { .. }) {
            let modes = rigid_modes(&mesh, &dofs, &partition);
            system.set_near_null_space(&modes, partition.offsets[rank])?;
        }
        system.assemble_and_set_up(solver)?;
        let load = vec![0.0; 3 * mesh.node_count()];
        Ok(Self {
            mesh,
            supports,
            dofs,
            partition,
            rank,
            system,
            coupling,
            load,
            solves: Cell::new(0),
            iterations: Cell::new(0),
            _petsc: PhantomData,
        })
    }

    /// Adds a force on `node` to the reference load (scaled by the load factor).
    ///
    /// # Errors
    /// [`FemError::UnknownNode`] for a node outside the mesh, [`FemError::InvalidParameter`]
    /// for a non-finite force.
    pub fn add_nodal_force(&mut self, node: usize, force: [f64; 3]) -> Result<(), PetscError> {
        if node >= self.mesh.node_count() {
            return Err(FemError::UnknownNode {
                node,
                node_count: self.mesh.node_count(),
                what: "a nodal force",
            }
            .into());
        }
        for (c, f) in force.into_iter().enumerate() {
            if !f.is_finite() {
                return Err(FemError::InvalidParameter {
                    name: "nodal force",
                    value: f,
                    expected: "a finite number",
                }
                .into());
            }
            self.load[3 * node + c] += f;
        }
        Ok(())
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
    pub fn mesh(&self) -> &SolidMesh {
        &self.mesh
    }

    /// The partition of the mesh over the ranks.
    pub fn partition(&self) -> &Partition {
        &self.partition
    }

    /// The solves made so far (one per right-hand side) and their Krylov iterations in all.
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

/// The six rigid-body motions (three translations, three rotations about the centroid) on
/// the free dofs, in the distributed numbering, orthonormalised (modified Gram–Schmidt; a mode
/// the supports make dependent on the others is dropped): GAMG's near-null space, without
/// which its coarse spaces miss the rotations and CG needs several times the iterations.
fn rigid_modes(mesh: &SolidMesh, dofs: &DofMap<3>, partition: &Partition) -> Vec<Vec<f64>> {
    let n = dofs.free_count();
    let nodes = mesh.nodes();
    let mut centre = [0.0; 3];
    for p in nodes {
        for a in 0..3 {
            centre[a] += p[a] / nodes.len() as f64;
        }
    }
    let mut modes: Vec<Vec<f64>> = Vec::new();
    for k in 0..6 {
        let mut v = vec![0.0; n];
        for (node, p) in nodes.iter().enumerate() {
            let x = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
            // translations e_k; rotations ω × x with ω = e_(k−3)
            let u = match k {
                0..3 => {
                    let mut e = [0.0; 3];
                    e[k] = 1.0;
                    e
                }
                3 => [0.0, -x[2], x[1]],
                4 => [x[2], 0.0, -x[0]],
                _ => [-x[1], x[0], 0.0],
            };
            for (c, d) in dofs.free_dofs(node).into_iter().enumerate() {
                if let Some(i) = d {
                    v[partition.row[i]] = u[c];
                }
            }
        }
        let before = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        for m in &modes {
            let dot: f64 = v.iter().zip(m).map(|(a, b)| a * b).sum();
            v.iter_mut().zip(m).for_each(|(a, b)| *a -= dot * b);
        }
        let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        if norm > 1e-8 * before {
            v.iter_mut().for_each(|a| *a /= norm);
            modes.push(v);
        }
    }
    modes
}

/// Nonzeros per owned row in the diagonal block (columns this rank owns) and off it: a row of
/// node `n` couples with every free dof of the nodes sharing an element with `n`.
fn preallocation(
    mesh: &SolidMesh,
    dofs: &DofMap<3>,
    partition: &Partition,
    rank: usize,
) -> Result<(Vec<PetscInt>, Vec<PetscInt>), PetscError> {
    let owned = partition.offsets[rank + 1] - partition.offsets[rank];
    let (mut d_nnz, mut o_nnz) = (vec![0; owned], vec![0; owned]);
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); mesh.node_count()];
    for e in 0..mesh.element_count() {
        let cell = mesh.element(e);
        for &n in cell {
            if partition.node_rank[n] == rank {
                neighbours[n].extend_from_slice(cell);
            }
        }
    }
    for (n, list) in neighbours.iter_mut().enumerate() {
        if partition.node_rank[n] != rank {
            continue;
        }
        list.sort_unstable();
        list.dedup();
        let (mut d, mut o) = (0, 0);
        for &m in list.iter() {
            let free = dofs.free_dofs(m).into_iter().flatten().count();
            if partition.node_rank[m] == rank {
                d += free;
            } else {
                o += free;
            }
        }
        for i in dofs.free_dofs(n).into_iter().flatten() {
            let local = partition.row[i] - partition.offsets[rank];
            d_nnz[local] = int("nonzeros of a row", d)?;
            o_nnz[local] = int("nonzeros of a row", o)?;
        }
    }
    Ok((d_nnz, o_nnz))
}

/// Adds this rank's element stiffnesses into the matrix; returns their `K_fp` entries.
fn assemble(
    mesh: &SolidMesh,
    materials: &BTreeMap<u32, Material>,
    dofs: &DofMap<3>,
    partition: &Partition,
    rank: usize,
    system: &System,
) -> Result<Vec<(PetscInt, usize, Component, f64)>, PetscError> {
    let element = mesh.built_in_element();
    let mut k_e = nalgebra::DMatrix::zeros(0, 0);
    let mut coords = Vec::new();
    let (mut rows, mut local, mut values) = (Vec::new(), Vec::new(), Vec::new());
    let mut coupling = Vec::new();
    for e in (0..mesh.element_count()).filter(|&e| partition.element_rank[e] == rank) {
        mesh.element_coords_into(e, &mut coords);
        let region = mesh.regions()[e];
        let material = &materials[&region];
        element.stiffness_into(e, &coords, material, &(), &mut k_e)?;
        if k_e.iter().any(|v| !v.is_finite()) {
            return Err(FemError::NonFiniteStiffness {
                element: e,
                region,
                young: material.young(),
            }
            .into());
        }
        rows.clear();
        local.clear();
        let cell = mesh.element(e);
        for (a, &n) in cell.iter().enumerate() {
            for (c, dof) in dofs.dofs(n).into_iter().enumerate() {
                if let Dof::Free(i) = dof {
                    rows.push(int("free dof", partition.row[i])?);
                    local.push(3 * a + c);
                }
            }
        }
        values.clear();
        values.extend(
            local
                .iter()
                .flat_map(|&i| local.iter().map(move |&j| (i, j)))
                .map(|(i, j)| k_e[(i, j)]),
        );
        system.add_block(&rows, &values)?;
        for (&row, &i) in rows.iter().zip(&local) {
            for (b, &m) in cell.iter().enumerate() {
                for (c, dof) in dofs.dofs(m).into_iter().enumerate() {
                    let value = k_e[(i, 3 * b + c)];
                    if matches!(dof, Dof::Prescribed(_)) && value != 0.0 {
                        coupling.push((row, m, Component::all::<3>()[c], value));
                    }
                }
            }
        }
    }
    Ok(coupling)
}

impl Structure<3> for PetscStructure<'_> {
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
        Component::all::<3>().map(|c| self.supports.value(node, c).unwrap_or(0.0))
    }

    /// Solves the columns one after the other with the one KSP (its preconditioner built
    /// once).
    fn solve_many_in_place(&self, mut rhs: MatMut<'_, f64>) -> Result<(), FemError> {
        assert_eq!(rhs.nrows(), self.dof_count(), "rhs rows");
        let row = &self.partition.row;
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

    /// `f = factor · f_ext − K_fp ū`: the forces from rank 0, `K_fp ū` from each rank's
    /// elements.
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
                        whole[self.partition.row[i]] += load_factor * self.load[3 * n + c];
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
