//! Deformable–deformable contact: two stacked blocks, the upper one pressed onto the lower one
//! (frictionless, ν = 0, uniaxial). Matching meshes through node pairs reproduce the exact
//! series-spring solution `σ = δ / (h_u/E_u + h_l/E_l)`; non-matching meshes through
//! node-to-segment carry the same total force with the contactor nodes closed.

#![cfg(feature = "fe")]

use contact_laws::Signorini;
use contact_solver::{ContactSimulation, ContactZone, SimulationSettings};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, Supports,
};

const E_LOW: f64 = 100.0;
const E_UP: f64 = 300.0;
const DELTA: f64 = 0.01;

/// Lower block [0,2]×[0,1] (region 0, `nx_low`), upper block [0,2]×[1,2] (region 1, `nx_up`),
/// the interface nodes coincident where the meshes match. Returns the simulation's parts.
fn stacked(nx_low: usize, nx_up: usize) -> (LinearElasticModel, Vec<usize>, Vec<usize>) {
    let low = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], nx_low, 2)).unwrap();
    let up = rectangle(&RectangleSpec::new([0.0, 2.0], [1.0, 2.0], nx_up, 2)).unwrap();
    let off = low.node_count();
    let mut nodes = low.nodes().to_vec();
    nodes.extend_from_slice(up.nodes());
    let mut conn = low.connectivity().to_vec();
    conn.extend(up.connectivity().iter().map(|n| n + off));
    let mut regions = vec![0; low.element_count()];
    regions.extend(vec![1; up.element_count()]);
    let mut mesh = Mesh::new(nodes, ElementKind::Tri3, conn, regions).unwrap();
    let shift = |v: &[usize]| v.iter().map(|n| n + off).collect::<Vec<_>>();
    let low_top = low.node_set("top").unwrap().to_vec();
    let up_bottom = shift(up.node_set("bottom").unwrap());
    let up_top = shift(up.node_set("top").unwrap());
    mesh.add_node_set("up_top", up_top.clone()).unwrap();
    mesh.add_node_set("bottom", low.node_set("bottom").unwrap().to_vec())
        .unwrap();
    let mut supports = Supports::new();
    supports
        .fix(low.node_set("bottom").unwrap(), Component::X)
        .fix(low.node_set("bottom").unwrap(), Component::Y)
        .fix(&up_top, Component::X);
    supports.prescribe(&up_top, Component::Y, -DELTA).unwrap();
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[
            (0, Material::new(E_LOW, 0.0, 0.0).unwrap()),
            (1, Material::new(E_UP, 0.0, 0.0).unwrap()),
        ],
        supports,
    )
    .unwrap();
    (model, up_bottom, low_top)
}

fn sigma_exact() -> f64 {
    DELTA / (1.0 / E_UP + 1.0 / E_LOW)
}

#[test]
fn node_pairs_give_the_series_solution() {
    let (model, contactor, target) = stacked(6, 6);
    let zone = ContactZone::node_pairs("interface", contactor, target, None, Signorini, 0.1);
    let mut settings = SimulationSettings::default();
    settings.solver.tol = 1e-12;
    let mut sim = ContactSimulation::new(model, vec![zone], settings).unwrap();
    for c in sim.candidates() {
        assert_eq!(c.normal(), [0.0, 1.0]); // from the lower body to the upper one
        assert_eq!(c.gap0, 0.0);
    }
    let res = sim.step(1.0, 1.0).unwrap();
    let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
    let exact = 2.0 * sigma_exact();
    assert!((total - exact).abs() <= 1e-10 * exact, "{total} vs {exact}");
    for c in &res.contacts {
        assert!(c.gap.abs() <= 1e-10 * DELTA, "gap {}", c.gap);
        // the consistent nodal force of a uniform pressure: h/2 at the ends, h inside
        let h = 2.0 / 6.0;
        let weight = if c.position[0] == 0.0 || c.position[0] == 2.0 {
            h / 2.0
        } else {
            h
        };
        assert!((c.r.n - sigma_exact() * weight).abs() <= 1e-9 * exact);
    }
}

#[test]
fn node_to_segment_carries_the_load_on_non_matching_meshes() {
    let (model, contactor, target) = stacked(8, 5);
    let zone = ContactZone::node_to_segment("interface", contactor.clone(), target, Signorini, 0.1);
    let mut sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap();
    assert_eq!(sim.candidates().len(), contactor.len()); // ends project on the end segments
    let res = sim.step(1.0, 1.0).unwrap();
    let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
    let exact = 2.0 * sigma_exact();
    eprintln!(
        "node-to-segment: total {total}, exact {exact}, error {:.2e}",
        (total - exact) / exact
    );
    // node-to-segment does not pass the patch test exactly: the total within 2 %
    assert!((total - exact).abs() <= 2e-2 * exact, "{total} vs {exact}");
    for c in &res.contacts {
        assert!(c.gap.abs() <= 1e-9 * DELTA, "gap {}", c.gap);
        assert!(c.r.n > 0.0);
    }
    // action = reaction: the lower block's bottom reactions balance the contact force
    let u = sim.nodal_displacements();
    let model = sim.structure();
    let bottom = model.mesh().node_set("bottom").unwrap().to_vec();
    let reactions = model.reactions(&u, 1.0).unwrap();
    let lower: f64 = reactions
        .iter()
        .filter(|((n, c), _)| bottom.contains(n) && *c == Component::Y)
        .map(|(_, r)| r)
        .sum();
    assert!((lower - total).abs() <= 1e-8 * exact, "{lower} vs {total}");
}
