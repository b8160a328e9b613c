//! A body built by a third-party finite-element crate, [fenris](https://crates.io/crates/fenris),
//! handed to bipotential's contact solver through fem-core's [`Structure`] trait.
//!
//! fenris (InteractiveComputerGraphics, MIT OR Apache-2.0) provides the mesh, the P2 triangle's
//! shape functions, the quadrature and the global assembly; this crate provides what fenris
//! leaves to its users — the elasticity operator ([`PlaneStrainElasticity`]) — and the few
//! lines that turn fenris's assembled matrix into a `Structure`: the supported dofs eliminated,
//! the lower triangle handed to fem-core's sparse Cholesky ([`SpdSolver`]) through the
//! re-exported [`fem_core::faer`], so this crate depends on no `faer` of its own.
//!
//! The contact solver then treats a [`FenrisBody`] like fem-core's own
//! [`LinearElasticModel`](fem_core::LinearElasticModel): the integration test
//! `block_on_line` solves a frictional block on a rigid line with both, on the same mesh and
//! material, and finds the same reactions to the solver's tolerance.
//!
//! ```no_run
//! use fem_core::{Component, Structure};
//! use fenris::connectivity::Tri6d2Connectivity;
//! use fenris::mesh::Tri6Mesh2d;
//! use fenris::nalgebra::Point2;
//! use fenris_body::{FenrisBody, PlaneStrainElasticity};
//!
//! // One P2 triangle, fixed along its bottom edge (nodes 0, 3, 1).
//! let vertices = vec![
//!     Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0),
//!     Point2::new(0.5, 0.0), Point2::new(0.5, 0.5), Point2::new(0.0, 0.5),
//! ];
//! let mesh = Tri6Mesh2d::from_vertices_and_connectivity(
//!     vertices, vec![Tri6d2Connectivity([0, 1, 2, 3, 4, 5])]);
//! let supports: Vec<_> = [0, 3, 1].iter()
//!     .flat_map(|&n| [(n, Component::X), (n, Component::Y)]).collect();
//! let body = FenrisBody::plane_strain(
//!     &mesh, PlaneStrainElasticity::new(1e3, 0.3)?, [0.0, -1.0], &supports)?
//!     .with_node_set("top", vec![2])?;
//! assert_eq!(body.dof_count(), 6);
//! let mut u = vec![0.0; body.dof_count()];
//! body.free_response_into(1.0, &mut u)?; // the body sags under its weight
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

mod elasticity;
mod error;

pub use elasticity::PlaneStrainElasticity;
pub use error::FenrisBodyError;

use elasticity::BodyForce;
use fem_core::faer::MatMut;
use fem_core::faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use fem_core::{Component, FemError, SpdSolver, Structure};
use fenris::assembly::global::{CsrAssembler, VectorAssembler};
use fenris::assembly::local::{
    ElementEllipticAssemblerBuilder, ElementSourceAssemblerBuilder, UniformQuadratureTable,
};
use fenris::mesh::Tri6Mesh2d;
use fenris::nalgebra::DVector;

/// A plane-strain body of P2 triangles assembled by fenris, with fixed (zero) supports and a
/// uniform body force: a [`Structure`] for the contact solver.
#[derive(Clone, Debug)]
pub struct FenrisBody {
    nodes: Vec<[f64; 2]>,
    dofs: Vec<[Option<usize>; 2]>,
    /// The stiffness over the free dofs, lower triangle (CSC, rows sorted).
    stiffness: SparseColMat<usize, f64>,
    solver: SpdSolver,
    /// The body-force load over the free dofs.
    load: Vec<f64>,
    sets: Vec<(String, Vec<usize>)>,
}

impl FenrisBody {
    /// Assembles with fenris the stiffness of `mesh` for `material` and the load of the body
    /// force `body_force` (force per unit volume, uniform), eliminates the components listed
    /// in `supports` (fixed at zero) and factorises the rest.
    ///
    /// fenris's nodal dof numbering (`2 node + component`) is kept with the supported dofs
    /// left out. Both integrals use fenris's triangle rule of strength 2, exact for P2 on
    /// straight-sided triangles (the stiffness's integrand is constant over each, the load's
    /// quadratic).
    ///
    /// # Errors
    /// [`FenrisBodyError::InvalidParameter`] for a non-finite body force;
    /// [`FenrisBodyError::UnknownNode`] or [`FenrisBodyError::BadComponent`] for a bad
    /// support; [`FenrisBodyError::RigidBodyMotion`] if the supports leave a rigid-body motion
    /// free (this body returns no rigid-body modes); [`FenrisBodyError::Fenris`] if fenris's
    /// assembly fails; [`FenrisBodyError::Fem`] if the stiffness cannot be factorised
    /// otherwise (a mechanism).
    pub fn plane_strain(
        mesh: &Tri6Mesh2d<f64>,
        material: PlaneStrainElasticity,
        body_force: [f64; 2],
        supports: &[(usize, Component)],
    ) -> Result<Self, FenrisBodyError> {
        for (k, b) in body_force.iter().enumerate() {
            if !b.is_finite() {
                return Err(FenrisBodyError::InvalidParameter {
                    name: ["body_force[0]", "body_force[1]"][k],
                    value: *b,
                    reason: "must be finite",
                });
            }
        }
        let count = mesh.vertices().len();
        let mut fixed = vec![[false; 2]; count];
        for &(node, component) in supports {
            let c = component as usize;
            if node >= count {
                return Err(FenrisBodyError::UnknownNode {
                    what: "supports".into(),
                    node,
                    count,
                });
            }
            if c > 1 {
                return Err(FenrisBodyError::BadComponent { node, component });
            }
            fixed[node][c] = true;
        }
        check_rigid_motions(mesh, &fixed)?;
        let mut free = 0;
        let dofs: Vec<[Option<usize>; 2]> = fixed
            .iter()
            .map(|f| {
                f.map(|is_fixed| {
                    (!is_fixed).then(|| {
                        free += 1;
                        free - 1
                    })
                })
            })
            .collect();

        // fenris: quadrature, stiffness and load over every dof (2 node + component).
        let (weights, points) = fenris::quadrature::total_order::triangle::<f64>(2)
            .map_err(|e| FenrisBodyError::Fenris(format!("triangle rule: {e:?}")))?;
        let qtable = UniformQuadratureTable::from_points_and_weights(points, weights);
        let u = DVector::<f64>::zeros(2 * count);
        let elliptic = ElementEllipticAssemblerBuilder::new()
            .with_finite_element_space(mesh)
            .with_operator(&material)
            .with_quadrature_table(&qtable)
            .with_u(&u)
            .build();
        let k = CsrAssembler::default()
            .assemble(&elliptic)
            .map_err(|e| FenrisBodyError::Fenris(format!("stiffness: {e}")))?;
        let source = BodyForce(body_force);
        let loads = ElementSourceAssemblerBuilder::new()
            .with_finite_element_space(mesh)
            .with_quadrature_table(&qtable)
            .with_source(&source)
            .build();
        let f = VectorAssembler::default()
            .assemble_vector(&loads)
            .map_err(|e| FenrisBodyError::Fenris(format!("load: {e}")))?;

        // The free rows and columns, lower triangle, into faer's CSC.
        let free_dof = |global: usize| dofs[global / 2][global % 2];
        let mut triplets = Vec::with_capacity(k.nnz() / 2 + free);
        for (row, col, &value) in k.triplet_iter() {
            if let (Some(i), Some(j)) = (free_dof(row), free_dof(col))
                && i >= j
            {
                triplets.push(Triplet::new(i, j, value));
            }
        }
        let stiffness = SparseColMat::try_new_from_triplets(free, free, &triplets)
            .map_err(|e| FenrisBodyError::Fenris(format!("free stiffness: {e:?}")))?;
        let mut solver = SpdSolver::new(stiffness.symbolic())?;
        solver.factor(stiffness.as_ref())?;
        let mut load = vec![0.0; free];
        for (global, value) in f.iter().enumerate() {
            if let Some(i) = free_dof(global) {
                load[i] = *value;
            }
        }
        Ok(Self {
            nodes: mesh.vertices().iter().map(|p| [p.x, p.y]).collect(),
            dofs,
            stiffness,
            solver,
            load,
            sets: Vec::new(),
        })
    }

    /// Names a node set (e.g. a contactor surface), read back by
    /// [`node_set`](Self::node_set); a set of the same name is replaced.
    ///
    /// # Errors
    /// [`FenrisBodyError::UnknownNode`] naming the set if a node is not in the mesh.
    pub fn with_node_set(mut self, name: &str, nodes: Vec<usize>) -> Result<Self, FenrisBodyError> {
        let count = self.nodes.len();
        if let Some(&node) = nodes.iter().find(|&&n| n >= count) {
            return Err(FenrisBodyError::UnknownNode {
                what: format!("node set `{name}`"),
                node,
                count,
            });
        }
        self.sets.retain(|(n, _)| n != name);
        self.sets.push((name.to_string(), nodes));
        Ok(self)
    }

    /// The nodes of a set named by [`with_node_set`](Self::with_node_set).
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] if the body has no such set.
    pub fn node_set(&self, name: &str) -> Result<&[usize], FemError> {
        self.sets
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, nodes)| nodes.as_slice())
            .ok_or_else(|| FemError::UnknownSet {
                kind: "node",
                name: name.to_string(),
            })
    }

    /// The body-force load over the free dofs (fenris's `∫ b · φ`).
    pub fn load(&self) -> &[f64] {
        &self.load
    }
}

/// Refuses supports that leave a rigid-body motion of the plane free: the three motions
/// (translations along x and y, rotation about the centroid) restricted to the supported
/// components must be independent (Gram–Schmidt in that order; the first that is not names
/// the error). A singular `K` would otherwise factorise with a round-off pivot and give
/// displacements of `1e12` without a word.
fn check_rigid_motions(mesh: &Tri6Mesh2d<f64>, fixed: &[[bool; 2]]) -> Result<(), FenrisBodyError> {
    let vertices = mesh.vertices();
    let count = vertices.len().max(1) as f64;
    let (xc, yc) = vertices
        .iter()
        .fold((0.0, 0.0), |(x, y), p| (x + p.x / count, y + p.y / count));
    let supported: Vec<(usize, usize)> = fixed
        .iter()
        .enumerate()
        .flat_map(|(n, f)| (0..2).filter(move |&c| f[c]).map(move |c| (n, c)))
        .collect();
    let motion = |which: usize| -> Vec<f64> {
        supported
            .iter()
            .map(|&(n, c)| match (which, c) {
                (0, 0) | (1, 1) => 1.0,
                (2, 0) => -(vertices[n].y - yc),
                (2, 1) => vertices[n].x - xc,
                _ => 0.0,
            })
            .collect()
    };
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for (which, name) in ["translation along x", "translation along y", "rotation"]
        .into_iter()
        .enumerate()
    {
        let r = motion(which);
        let norm_r = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        let mut v = r.clone();
        for q in &basis {
            let dot: f64 = r.iter().zip(q).map(|(a, b)| a * b).sum();
            v.iter_mut().zip(q).for_each(|(v, q)| *v -= dot * q);
        }
        let norm_v = v.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm_r == 0.0 || norm_v <= 1e-9 * norm_r {
            return Err(FenrisBodyError::RigidBodyMotion { motion: name });
        }
        basis.push(v.into_iter().map(|v| v / norm_v).collect());
    }
    Ok(())
}

impl Structure for FenrisBody {
    fn dof_count(&self) -> usize {
        self.load.len()
    }

    fn node_count(&self) -> usize {
        self.nodes.len()
    }

    fn node_position(&self, node: usize) -> [f64; 2] {
        self.nodes[node]
    }

    fn node_dofs(&self, node: usize) -> [Option<usize>; 2] {
        self.dofs[node]
    }

    fn prescribed_displacement(&self, node: usize) -> [f64; 2] {
        assert!(node < self.nodes.len(), "node {node} out of range");
        [0.0, 0.0] // every support of this body is fixed at zero
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
        for (u, f) in u.iter_mut().zip(&self.load) {
            *u = load_factor * f;
        }
        self.solver.solve_in_place(u);
        Ok(())
    }

    fn stiffness_version(&self) -> u64 {
        0 // assembled once, never changed
    }

    fn stiffness_matrix(&self) -> Option<SparseColMatRef<'_, usize, f64>> {
        Some(self.stiffness.as_ref())
    }
}
