//! Two floating bodies (issue 16): two elastic blocks, one on the other, neither supported,
//! on a rigid LINE. Contact alone holds both: six rigid-body modes (three per connected
//! component of the mesh), solved for exactly.
//!
//! Source: statics of a stack of rigid bodies (e.g. J. L. Meriam, L. G. Kraige, *Engineering
//! Mechanics: Statics*, ch. 3 and 6): the interface carries the upper block's weight `W_up`
//! and the push `T` on it, the ground carries `W_up + W_low` and `T`; with Coulomb friction
//! `μ = 0.3` and `T = 0.2 W_up` both interfaces stick.
//!
//! ```text
//!      T →  ┌────────────┐ y = 2    upper block, E = 300, unit weight: W_up = 2
//!           ├────────────┤ y = 1    node pairs (Coulomb μ = 0.3), matching P1 meshes
//!           └────────────┘ y = 0    lower block, E = 100, unit weight: W_low = 2
//!   ═════════════════════════ rigid LINE y = 0 (Coulomb μ = 0.3)
//! ```
//! What is asserted, and why: the interface's `Σ r_n = W_up`, `Σ r_t = −T` and the ground's
//! `Σ r_n = W_up + W_low`, `Σ r_t = −T`, to `1e-10` relative (the equilibrium of each body is
//! solved to `equilibrium_tol = 1e-11` of the forces involved, plus round-off of the sums).

#![cfg(feature = "fe")]

use contact_laws::Coulomb;
use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{ElementKind, Idealization, LinearElasticModel, Material, Mesh};

#[test]
fn two_floating_blocks_stack_works() {
    let low = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 6, 3)).unwrap();
    let up = rectangle(&RectangleSpec::new([0.0, 2.0], [1.0, 2.0], 6, 3)).unwrap();
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
    let low_bottom = low.node_set("bottom").unwrap().to_vec();
    let up_bottom = shift(up.node_set("bottom").unwrap());
    let up_top_sides: Vec<_> = up
        .edge_set("top")
        .unwrap()
        .iter()
        .map(|s| fem_core::Side {
            element: s.element + low.element_count(),
            side: s.side,
        })
        .collect();
    mesh.add_edge_set("up_top", up_top_sides).unwrap();
    let mut model = LinearElasticModel::floating(
        mesh,
        Idealization::PlaneStrain,
        &[
            (0, Material::new(100.0, 0.3, 0.0).unwrap()),
            (1, Material::new(300.0, 0.3, 0.0).unwrap()),
        ],
        fem_core::Supports::new(),
    )
    .unwrap();
    let modes = model.rigid_body_modes().unwrap();
    let bodies: Vec<usize> = modes.modes().iter().map(|m| m.body).collect();
    assert_eq!(bodies, vec![0, 0, 0, 1, 1, 1]);
    let (w_low, w_up, push) = (2.0, 2.0, 0.4);
    model.add_body_force(|_| [0.0, -1.0]).unwrap();
    model
        .add_edge_traction("up_top", |_| [push / 2.0, 0.0])
        .unwrap();
    let law = Coulomb::new(0.3).unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
    let zones = vec![
        ContactZone::rigid("ground", low_bottom, ground, law, 0.01),
        ContactZone::node_pairs("interface", up_bottom, low_top, None, law, 0.1),
    ];
    let mut sim = ContactSimulation::new(model, zones, SimulationSettings::default()).unwrap();
    let res = sim.step(1.0, 1.0).expect("the stack rests");
    let sum = |zone: usize| {
        res.contacts
            .iter()
            .filter(|c| c.zone == zone)
            .fold((0.0, 0.0), |(n, t), c| (n + c.r.n, t + c.r.t[0]))
    };
    let (ground_n, ground_t) = sum(0);
    let (inter_n, inter_t) = sum(1);
    eprintln!(
        "ground Σ r = ({ground_n:.15}, {ground_t:.15}), interface Σ r = ({inter_n:.15}, \
         {inter_t:.15}); {} Newton iterations, {} solves, α = {:?}",
        res.report.equilibrium_iterations,
        res.report.equilibrium_solves,
        sim.rigid_body_amplitudes()
    );
    // each body's equilibrium to 1e-11 of its forces, plus round-off of the sums
    let total = w_low + w_up;
    assert!((ground_n - total).abs() <= 1e-10 * total, "{ground_n}");
    assert!((ground_t + push).abs() <= 1e-10 * total, "{ground_t}");
    // the interface reaction is on the upper block (the contactor)
    assert!((inter_n - w_up).abs() <= 1e-10 * total, "{inter_n}");
    assert!((inter_t + push).abs() <= 1e-10 * total, "{inter_t}");
}
