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
//! (`t* = 1/3`), `e = 0`, `θ = 1`, `h = 0.005`, lumped mass. `θ = 1` because the rigid limit
//! is wanted: the block's elastic modes have `ωh ≈ 5`, which backward Euler damps in a step;
//! with `θ = 1/2` the stiff block bounces off the plane on its own elasticity after the
//! impact (vz ≈ +0.13 for an impact at −0.32, measured), the right elastic answer but not the
//! rigid one.

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
    let scheme = MoreauJean::new(1.0)
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
    let mut mz = vec![0.0; n];
    sim.structure().mass_mul_into(&ones_z, &mut mz);
    let mean =
        |v: &[f64], m1: &[f64]| -> f64 { m1.iter().zip(v).map(|(a, b)| a * b).sum::<f64>() / mass };
    let t_star = V0 / (MU * G);
    let (mut t_stop, mut worst_mid, mut after) = (None, 0.0_f64, 0.0_f64);
    let mut first_contact: Option<usize> = None;
    for step in 1..=100 {
        let res = sim.advance(H).unwrap();
        let t = step as f64 * H;
        if first_contact.is_none() && res.contacts.iter().any(|c| c.r.n > 0.0) {
            first_contact = Some(step);
        }
        let v = sim.scheme().velocity().to_vec();
        let (vx, vz) = (mean(&v, &m1), mean(&v, &mz));
        // sliding, once the impact has settled (5 steps): v0 − μ g t, resting on the plane
        if first_contact.is_some_and(|s| step >= s + 5) && t < t_star {
            worst_mid = worst_mid.max((vx - (V0 - MU * G * t)).abs() / V0);
            assert!(vz.abs() < 1e-3 * V0, "t = {t}: vz = {vz}"); // e = 0: no bounce
        }
        if t_stop.is_none() && vx <= 0.0 {
            t_stop = Some(t);
        } else if t_stop.is_some() {
            after = after.max(vx.abs() / V0);
        }
    }
    let t_stop = t_stop.expect("the block stops");
    let energy = *sim.scheme().energy();
    eprintln!(
        "sliding block: stops at t = {t_stop:.4} (v0/(μg) = {t_star:.4}), worst |v − (v0 − μgt)| \
         = {:.1e} of v0, after the stop |v| < {after:.1e} v0, first contact in step {:?}, contact dissipation {:.4} (balance residual \
         {:.1e}), {:.2?}",
        worst_mid,
        first_contact,
        energy.contact_dissipation(),
        energy.residual(),
        start.elapsed()
    );
    // the mean velocity first reaches 0 in the step that contains t* (one step: 1.5 % of t*)
    assert!(t_stop - H < t_star && t_star <= t_stop, "t_stop = {t_stop}");
    // the deceleration is μ g to within the block's elastic vibration (measured 1.5e-4 v0)
    assert!(worst_mid < 1e-3, "{worst_mid}");
    // then it sticks: what is left is the elastic vibration the released friction strain
    // starts (measured 0.4 % of v0, decaying)
    assert!(after < 0.01, "{after}");
    // the balance closes with what friction and the impact dissipated
    assert!(energy.residual().abs() < 1e-9 * energy.scale());
    assert!(energy.contact_dissipation() > 0.0);
}
