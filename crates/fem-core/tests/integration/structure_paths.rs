//! The contact solver's input is the same whichever path built the structure.
//!
//! Sketch: a 4 × 2 block of P1 triangles (plane strain, E = 1000, ν = 0.3), fixed at its left
//! side, loaded on the right by a traction, with three "contact" nodes on its bottom side and
//! their local frames (n = (0, 1), t = (1, 0)). Path A is fem-core's `LinearElasticModel`
//! (sparse assembly, faer Cholesky). Path B is a user-written `Structure`: the same elements
//! through the public `Element` trait, assembled densely and factored with nalgebra's
//! Cholesky — as a downstream FE code would plug in. A generic function written only against
//! `Structure` computes what the contact solver needs, `x_free = H u_free` and
//! `F* = H K⁻¹ Hᵀ` (seed 5.39, 5.56–5.59); both paths must agree to 1e-12 relative.

use faer::Mat;
use fem_core::{
    Component, Element, ElementKind, FemError, Idealization, LinearElasticModel, Material, Mesh,
    Side, Structure, Supports, Tri3,
};
use nalgebra::{DMatrix, DVector};

fn block() -> Mesh {
    let (nx, ny) = (4, 2);
    let mut nodes = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            nodes.push([i as f64, j as f64 * 0.5]);
        }
    }
    let id = |i: usize, j: usize| j * (nx + 1) + i;
    let mut conn = Vec::new();
    let mut right = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            conn.extend([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            if i == nx - 1 {
                right.push(Side {
                    element: conn.len() / 3 - 1,
                    side: 1,
                });
            }
            conn.extend([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let mut mesh = Mesh::new(nodes, ElementKind::Tri3, conn, vec![]).unwrap();
    mesh.add_node_set("left", (0..=ny).map(|j| id(0, j)).collect())
        .unwrap();
    mesh.add_node_set("contact", vec![id(1, 0), id(2, 0), id(3, 0)])
        .unwrap();
    mesh.add_edge_set("right", right).unwrap();
    mesh
}

/// Path B: a user's structure built from the public `Element` trait, dense algebra.
struct DenseStructure {
    mesh: Mesh,
    dofs: Vec<[Option<usize>; 2]>,
    chol: nalgebra::Cholesky<f64, nalgebra::Dyn>,
    load: DVector<f64>,
}

impl DenseStructure {
    fn new(mesh: Mesh, material: &Material, fixed: &[usize], traction: [f64; 2]) -> Self {
        let mut dofs = vec![[None, None]; mesh.node_count()];
        let mut n = 0;
        for (node, d) in dofs.iter_mut().enumerate() {
            if !fixed.contains(&node) {
                *d = [Some(n), Some(n + 1)];
                n += 2;
            }
        }
        let mut k = DMatrix::zeros(n, n);
        let mut k_e = DMatrix::zeros(6, 6);
        for e in 0..mesh.element_count() {
            let cell = mesh.element(e);
            let coords: Vec<[f64; 2]> = cell.iter().map(|&i| mesh.nodes()[i]).collect();
            Tri3.stiffness_into(e, &coords, material, &Idealization::PlaneStrain, &mut k_e)
                .unwrap();
            for a in 0..6 {
                for b in 0..6 {
                    if let (Some(i), Some(j)) = (dofs[cell[a / 2]][a % 2], dofs[cell[b / 2]][b % 2])
                    {
                        k[(i, j)] += k_e[(a, b)];
                    }
                }
            }
        }
        // Uniform traction on the right side: half the side force to each end node.
        let mut load = DVector::zeros(n);
        for side in mesh.edge_set("right").unwrap() {
            let ends: Vec<usize> = mesh.side_nodes(*side).collect();
            let (p, q) = (mesh.nodes()[ends[0]], mesh.nodes()[ends[1]]);
            let len = (p[0] - q[0]).hypot(p[1] - q[1]);
            for &node in &ends {
                for c in 0..2 {
                    if let Some(i) = dofs[node][c] {
                        load[i] += traction[c] * len / 2.0;
                    }
                }
            }
        }
        let chol = k.cholesky().expect("SPD");
        Self {
            mesh,
            dofs,
            chol,
            load,
        }
    }
}

impl Structure for DenseStructure {
    fn dof_count(&self) -> usize {
        self.load.len()
    }
    fn node_count(&self) -> usize {
        self.mesh.node_count()
    }
    fn node_position(&self, node: usize) -> [f64; 2] {
        self.mesh.nodes()[node]
    }
    fn node_dofs(&self, node: usize) -> [Option<usize>; 2] {
        self.dofs[node]
    }
    fn prescribed_displacement(&self, _node: usize) -> [f64; 2] {
        [0.0, 0.0] // every support of this structure is a fixed (zero) displacement
    }
    fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), FemError> {
        let x = self.chol.solve(&DVector::from_column_slice(rhs));
        rhs.copy_from_slice(x.as_slice());
        Ok(())
    }
    fn solve_many_in_place(&self, mut rhs: faer::MatMut<'_, f64>) -> Result<(), FemError> {
        for j in 0..rhs.ncols() {
            let b = DVector::from_iterator(rhs.nrows(), (0..rhs.nrows()).map(|i| rhs[(i, j)]));
            let x = self.chol.solve(&b);
            for i in 0..rhs.nrows() {
                rhs[(i, j)] = x[i];
            }
        }
        Ok(())
    }
    fn free_response_into(&self, load_factor: f64, u: &mut [f64]) -> Result<(), FemError> {
        let x = self.chol.solve(&(&self.load * load_factor));
        u.copy_from_slice(x.as_slice());
        Ok(())
    }
    fn stiffness_version(&self) -> u64 {
        1
    }
}

/// What the contact solver computes from any structure: `x_free = H u_free` and
/// `F* = H K⁻¹ Hᵀ`, with rows (n, t) per contact node, frame n = (0, 1), t = (1, 0).
fn contact_input<S: Structure>(s: &S, nodes: &[usize]) -> (Vec<f64>, Vec<f64>) {
    let frame = [[0.0, 1.0], [1.0, 0.0]]; // rows: n, t
    let m = 2 * nodes.len();
    let mut h_t = Mat::<f64>::zeros(s.dof_count(), m);
    for (k, &node) in nodes.iter().enumerate() {
        let d = s.node_dofs(node);
        for (row, dir) in frame.iter().enumerate() {
            for c in 0..2 {
                if let Some(i) = d[c] {
                    h_t[(i, 2 * k + row)] = dir[c];
                }
            }
        }
    }
    let mut u = vec![0.0; s.dof_count()];
    s.free_response_into(1.0, &mut u).unwrap();
    let mut k_inv_h_t = h_t.clone();
    s.solve_many_in_place(k_inv_h_t.as_mut()).unwrap();
    let x_free: Vec<f64> = (0..m)
        .map(|r| (0..s.dof_count()).map(|i| h_t[(i, r)] * u[i]).sum())
        .collect();
    let mut flex = vec![0.0; m * m];
    for a in 0..m {
        for b in 0..m {
            flex[a * m + b] = (0..s.dof_count())
                .map(|i| h_t[(i, a)] * k_inv_h_t[(i, b)])
                .sum();
        }
    }
    (x_free, flex)
}

#[test]
fn contact_input_is_the_same_through_both_paths_works() {
    let material = Material::new(1000.0, 0.3, 0.0).unwrap();
    let mesh = block();
    let left = mesh.node_set("left").unwrap().to_vec();
    let contact = mesh.node_set("contact").unwrap().to_vec();
    let traction = [0.0, -2.0];

    let mut supports = Supports::new();
    supports.fix(&left, Component::X).fix(&left, Component::Y);
    let mut model = LinearElasticModel::new(
        mesh.clone(),
        Idealization::PlaneStrain,
        &[(0, material)],
        supports,
    )
    .unwrap();
    model.add_edge_traction("right", |_| traction).unwrap();
    let dense = DenseStructure::new(mesh, &material, &left, traction);

    let (xa, fa) = contact_input(&model, &contact);
    let (xb, fb) = contact_input(&dense, &contact);
    let rel = |a: &[f64], b: &[f64]| {
        let num: f64 = a
            .iter()
            .zip(b)
            .map(|(x, y)| (x - y).powi(2))
            .sum::<f64>()
            .sqrt();
        let den: f64 = a.iter().map(|x| x * x).sum::<f64>().sqrt();
        num / den
    };
    assert!(rel(&xa, &xb) < 1e-12, "x_free differs: {xa:?} vs {xb:?}");
    assert!(rel(&fa, &fb) < 1e-12, "F* differs");
    // F* is symmetric positive definite (a flexibility).
    let m = 2 * contact.len();
    let f = DMatrix::from_row_slice(m, m, &fa);
    assert!((&f - f.transpose()).norm() < 1e-12 * f.norm());
    assert!(f.symmetric_eigenvalues().min() > 0.0);
    // The bottom of a cantilever loaded downwards moves down.
    assert!(xa.iter().step_by(2).all(|&x_n| x_n < 0.0));
}
