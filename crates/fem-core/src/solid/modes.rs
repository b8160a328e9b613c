//! Refusing a 3D body that its supports do not hold.
//!
//! Each connected component of the mesh (nodes joined by elements) is a body. Its six
//! candidate rigid-body modes are the translations and the rotations about its centroid,
//! scaled by its size `ρ`:
//!
//! ```text
//! R = [ t_x  t_y  t_z  ω_x  ω_y  ω_z ],   ω_a(x) = e_a × (x − c) / ρ
//! ```
//!
//! With `C` the modes at the body's prescribed dofs and their differences between tied nodes,
//! a mode survives when `C N = 0`: an eigenvector of `CᵀC` whose eigenvalue is below `1e-10`
//! of the largest (or all six for an unsupported body). A 3D `SolidModel` does not float yet,
//! so a surviving mode is an error that names the dof it moves most.

use super::mesh::SolidMesh;
use crate::dirichlet::{Component, Dof, DofMap, Supports};
use crate::error::FemError;
use nalgebra::{Matrix6, Vector6};

fn find(parent: &mut [usize], mut a: usize) -> usize {
    while parent[a] != a {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    a
}

/// The six modes at one dof of node position `x` (component `c`), for centroid `c0` and size
/// `rho`.
fn mode_row(x: [f64; 3], c: usize, c0: [f64; 3], rho: f64) -> Vector6<f64> {
    let d = [
        (x[0] - c0[0]) / rho,
        (x[1] - c0[1]) / rho,
        (x[2] - c0[2]) / rho,
    ];
    let mut row = Vector6::zeros();
    row[c] = 1.0;
    // ω_a = e_a × d: component c of e_a × d
    for a in 0..3 {
        let mut e = [0.0; 3];
        e[a] = 1.0;
        let w = [
            e[1] * d[2] - e[2] * d[1],
            e[2] * d[0] - e[0] * d[2],
            e[0] * d[1] - e[1] * d[0],
        ];
        row[3 + a] = w[c];
    }
    row
}

/// [`FemError::NotPositiveDefinite`] if the supports and ties leave some body of `mesh` with a
/// rigid-body mode.
pub(crate) fn refuse_rigid_modes(
    mesh: &SolidMesh,
    supports: &Supports,
    dofs: &DofMap<3>,
) -> Result<(), FemError> {
    let n = mesh.node_count();
    let mut parent: Vec<usize> = (0..n).collect();
    let mut used = vec![false; n];
    for e in 0..mesh.element_count() {
        let cell = mesh.element(e);
        for &a in cell {
            used[a] = true;
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, cell[0]));
            if ra != rb {
                parent[ra] = rb;
            }
        }
    }
    let mut bodies: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for node in (0..n).filter(|&k| used[k]) {
        let root = find(&mut parent, node);
        bodies.entry(root).or_default().push(node);
    }
    let x = mesh.nodes();
    for nodes in bodies.values() {
        let mut c0 = [0.0; 3];
        for &k in nodes {
            for a in 0..3 {
                c0[a] += x[k][a] / nodes.len() as f64;
            }
        }
        let rho = nodes
            .iter()
            .map(|&k| {
                let d = super::mesh::sub(x[k], c0);
                super::mesh::dot(d, d).sqrt()
            })
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        let mut gram = Matrix6::zeros();
        for &k in nodes {
            for c in Component::all::<3>() {
                if supports.value(k, c).is_some() {
                    let r = mode_row(x[k], c as usize, c0, rho);
                    gram += r * r.transpose();
                }
            }
        }
        let root = find(&mut parent, nodes[0]);
        for (c, tied) in supports.ties() {
            let mut tied = tied
                .iter()
                .filter(|&&k| k < n && used[k] && find(&mut parent, k) == root);
            if let Some(&first) = tied.next() {
                let r0 = mode_row(x[first], *c as usize, c0, rho);
                for &k in tied {
                    let r = mode_row(x[k], *c as usize, c0, rho) - r0;
                    gram += r * r.transpose();
                }
            }
        }
        let eig = gram.symmetric_eigen();
        let top = eig.eigenvalues.max();
        let Some(j) = (0..6).find(|&j| eig.eigenvalues[j] <= 1e-10 * top || top == 0.0) else {
            continue;
        };
        let mode = eig.eigenvectors.column(j).into_owned();
        // the free dof that the mode moves most
        let mut best: Option<(f64, usize, Component, usize)> = None;
        for &k in nodes {
            for (c, d) in Component::all::<3>().into_iter().zip(dofs.dofs(k)) {
                if let Dof::Free(row) = d {
                    let v = mode_row(x[k], c as usize, c0, rho).dot(&mode).abs();
                    if best.is_none_or(|b| v > b.0 * (1.0 + 1e-9)) {
                        best = Some((v, k, c, row));
                    }
                }
            }
        }
        if let Some((_, node, component, row)) = best {
            return Err(FemError::NotPositiveDefinite {
                node,
                component,
                row,
            });
        }
    }
    Ok(())
}
