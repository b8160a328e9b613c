//! A block pressed on a rigid LINE, then pushed sideways by its top face (Coulomb, μ = 0.3):
//! below the threshold the base sticks; once sliding, the total tangential reaction is
//! `−μ ×` the total normal reaction (issue: 1e-8), and every base node slips the same way.

#![cfg(feature = "fe")]

use contact_laws::Coulomb;
use contact_solver::{
    ContactSimulation, ContactZone, InterfaceStatus, RigidLine, SimulationSettings, StepResult,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, ElementKind, Idealization, LinearElasticModel, Material, Supports};

const MU: f64 = 0.3;

fn totals(res: &StepResult) -> (f64, f64) {
    res.contacts
        .iter()
        .fold((0.0, 0.0), |(n, t), c| (n + c.r.n, t + c.r.t[0]))
}

#[test]
fn block_sticks_below_threshold_and_slides_at_mu() {
    for kind in [ElementKind::Tri3, ElementKind::Tri6] {
        let mut spec = RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 8, 4);
        spec.kind = kind;
        let mesh = rectangle(&spec).unwrap();
        let top = mesh.node_set("top").unwrap().to_vec();
        let bottom = mesh.node_set("bottom").unwrap().to_vec();
        let mut supports = Supports::new();
        supports.prescribe(&top, Component::Y, 0.0).unwrap();
        supports.prescribe(&top, Component::X, 0.0).unwrap();
        let model = LinearElasticModel::new(
            mesh,
            Idealization::PlaneStrain,
            &[(0, Material::new(1000.0, 0.0, 0.0).unwrap())],
            supports,
        )
        .unwrap();
        let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
        let zone = ContactZone::rigid("base", bottom, ground, Coulomb::new(MU).unwrap(), 0.1);
        let mut sim =
            ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap();

        // press: δ = 0.01 → N ≈ E' ε × 2
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, -0.01)
            .unwrap();
        let pressed = sim.step(1.0, 1.0).unwrap();
        let (n, t) = totals(&pressed);
        assert!(n > 0.0 && t.abs() <= 1e-9 * n, "{kind:?}: N {n}, T {t}");

        // small push: far below μN, the base sticks (no slip increment anywhere)
        sim.structure_mut()
            .set_prescribed(&top, Component::X, 1e-5)
            .unwrap();
        let small = sim.step(2.0, 1.0).unwrap();
        let (n, t) = totals(&small);
        assert!(
            t < 0.0 && t.abs() < 0.5 * MU * n,
            "{kind:?}: T {t} vs μN {}",
            MU * n
        );
        for c in small.contacts.iter().filter(|c| c.r.n > 1e-6 * n) {
            assert_eq!(
                c.status,
                InterfaceStatus::Stick,
                "{kind:?}: node {}",
                c.node
            );
            assert!(
                c.slip_increment.abs() <= 1e-9 * 0.01,
                "{kind:?}: slip {}",
                c.slip_increment
            );
        }

        // large push: the block slides; T = −μ N to 1e-8
        sim.structure_mut()
            .set_prescribed(&top, Component::X, 0.05)
            .unwrap();
        let slid = sim.step(3.0, 1.0).unwrap();
        let (n, t) = totals(&slid);
        assert!(
            (t + MU * n).abs() <= 1e-8 * MU * n,
            "{kind:?}: T {t} vs −μN {}",
            -MU * n
        );
        for c in slid.contacts.iter().filter(|c| c.r.n > 0.0) {
            assert_eq!(c.status, InterfaceStatus::Slip, "{kind:?}: node {}", c.node);
            assert!(c.slip_increment > 0.0);
            assert!((c.r.t[0] + MU * c.r.n).abs() <= 1e-8 * MU * n);
        }
        // the normal problem is unchanged by sliding on a rigid plane (ν = 0: no coupling)
        let (n_pressed, _) = totals(&pressed);
        assert!((n - n_pressed).abs() < 0.05 * n_pressed);
    }
}
