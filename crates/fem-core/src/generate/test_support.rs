//! Checks shared by the generators' unit tests.

use crate::mesh::Mesh;

pub(super) fn corner_area(mesh: &Mesh, e: usize) -> f64 {
    let c = mesh.element(e);
    let [a, b, d] = [c[0], c[1], c[2]].map(|n| mesh.nodes()[n]);
    0.5 * ((b[0] - a[0]) * (d[1] - a[1]) - (d[0] - a[0]) * (b[1] - a[1]))
}

pub(super) fn total_area(mesh: &Mesh) -> f64 {
    (0..mesh.element_count())
        .map(|e| corner_area(mesh, e))
        .sum()
}

/// Every P2 mid-side node is the exact midpoint of its side's corners.
pub(super) fn assert_mid_nodes(mesh: &Mesh) {
    for e in 0..mesh.element_count() {
        let c = mesh.element(e);
        for (side, &[a, b, m]) in [[0, 1, 3], [1, 2, 4], [2, 0, 5]].iter().enumerate() {
            let [pa, pb, pm] = [c[a], c[b], c[m]].map(|n| mesh.nodes()[n]);
            for k in 0..2 {
                assert_eq!(pm[k], 0.5 * (pa[k] + pb[k]), "element {e} side {side}");
            }
        }
    }
}

/// Every node is used by some element.
pub(super) fn assert_all_nodes_used(mesh: &Mesh) {
    let mut used = vec![false; mesh.node_count()];
    for &n in mesh.connectivity() {
        used[n] = true;
    }
    assert!(used.iter().all(|&u| u));
}
