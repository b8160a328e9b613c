//! Issue 39 (c): a stiff 3D block dropped on a rigid plane with Coulomb friction and a
//! tangential velocity stops sliding at `t* = v0 / (μ g)`.
//!
//! Source: the rigid block on a rough floor (Moreau 1988 §9; Acary & Brogliato 2008 §1.3).
//! Once the block rests, the normal impulse up to time `t` is `m g t` (what stops the fall at
//! the impact included), so friction removes `μ m g t` of tangential momentum while it slides,
//! whatever the drop height: the sliding stops at `t* = v0 / (μ g)` and the mean velocity is
//! `v0 − μ g t` before it. The block is stiff (`c = √(E/ρ)` ≈ 320 × its size per second) so
//! that its elastic vibration is a small perturbation of the rigid motion.
//!
//! Sketch: a unit cube of Hex8 (2 × 2 × 2 cells), density 1, `g = 10` along −z, starting
//! `d = 0.005` above the plane `z = 0` with `v = (v0, 0, 0)`, `v0 = 1`, `μ = 0.3`
//! (`t* = 1/3`), `e = 0`, `θ = 1/2`, `h = 0.005`.

#![cfg(feature = "fe")]

use contact_laws::Coulomb;
use contact_solver::coupling::simulation::MoreauJean;
use contact_solver::coupling::solid::RigidPlane;
use contact_solver::{ContactSimulation, ContactZone, SimulationSettings};
use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidModel};
use fem_core::{Material, Structure, Supports};
use std::time::Instant;

const G: f64 = 10.0;
const MU: f64 = 0.3;
const V0: f64 = 1.0;
const H: f64 = 0.005;
const DROP: f64 = 0.005;

#[test]
fn issue_39_sliding_block_stops_at_mu_g() {
    let start = Instant::now();
    let mesh = box_mesh(
        &lines(0.0, 1.0, 2),
        &lines(0.0, 1.0, 2),
        &lines(DROP, 1.0 + DROP, 2),
        SolidKind::Hex8,
    )
    .unwrap();
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let m = Material::new(1e5, 0.25, G)
        .unwrap()
        .with_density(1.0)
        .unwrap();
    let mut model = SolidModel::floating(mesh, &[(0, m)], Supports::new()).unwrap();
    model.add_self_weight().unwrap();
    let body = DynamicModel::new(model, MassKind::Lumped, Rayleigh::default()).unwrap();
    let scheme = MoreauJean::new(0.5)
        .unwrap()
        .with_velocity_field(&body, |_| [V0, 0.0, 0.0])
        .unwrap();
    let plane = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let law = Coulomb::new(MU).unwrap();
    let zone = ContactZone::<_, 3>::rigid("floor", nodes, plane, law, 0.1).with_areas(areas);
    let settings = SimulationSettings::for_dimension::<3>();
    let mut sim = ContactSimulation::with_scheme(body, vec![zone], settings, scheme).unwrap();
    let n = sim.structure().dof_count();
    let along = |axis: usize| -> Vec<f64> {
        (0..n)
            .map(|i| if i % 3 == axis { 1.0 } else { 0.0 })
            .collect()
    };
    let (ones_x, ones_z) = (along(0), along(2));
    let mut m1 = vec![0.0; n];
    sim.structure().mass_mul_into(&ones_x, &mut m1);
    let mass: f64 = m1.iter().zip(&ones_x).map(|(a, b)| a * b).sum();
    let mean = |v: &[f64], ones: &[f64]| -> f64 {
        let mut mv = vec![0.0; n];
        sim.structure().mass_mul_into(ones, &mut mv);
        mv.iter().zip(v).map(|(a, b)| a * b).sum::<f64>() / mass
    };
    let t_star = V0 / (MU * G);
    let (mut t_stop, mut worst_mid, mut first_contact) = (None, 0.0_f64, None);
    let mut step = 0;
    while step < 100 {
        step += 1;
        let res = sim.advance(H).unwrap();
        let t = step as f64 * H;
        if first_contact.is_none() && res.contacts.iter().any(|c| c.r.n > 0.0) {
            first_contact = Some(t);
        }
        let v = sim.scheme().velocity().to_vec();
        let (vx, vz) = (mean(&v, &ones_x), mean(&v, &ones_z));
        // while sliding, after the impact: v0 − μ g t
        if first_contact.is_some() && t < 0.9 * t_star {
            worst_mid = worst_mid.max((vx - (V0 - MU * G * t)).abs() / V0);
            // resting on the plane: no bounce (e = 0)
            assert!(vz.abs() < 0.01 * V0, "t = {t}: vz = {vz}");
        }
        if t_stop.is_none() && vx.abs() < 1e-3 * V0 {
            t_stop = Some(t);
        }
    }
    let t_stop = t_stop.expect("the block stops");
    let energy = *sim.scheme().energy();
    eprintln!(
        "sliding block: stops at t = {t_stop:.4} (v0/(μg) = {t_star:.4}), worst |v − (v0 − μgt)| \
         = {:.2} % of v0, first contact at {:?}, contact dissipation {:.4} (balance residual \
         {:.1e}), {:.2?}",
        100.0 * worst_mid,
        first_contact,
        energy.contact_dissipation(),
        energy.residual(),
        start.elapsed()
    );
    // the stop is seen at the end of a step: within one step of t* (1.5 % of t*)
    assert!((t_stop - t_star).abs() <= H + 1e-12, "t_stop = {t_stop}");
    // the deceleration is μ g to within the block's elastic vibration (a stiff block: 1 %)
    assert!(worst_mid < 0.01, "{worst_mid}");
    // the balance closes with what friction and the impact dissipated
    assert!(energy.residual().abs() < 1e-9 * energy.scale());
    assert!(energy.contact_dissipation() > 0.0);
}
