//! Force-controlled Hertz contact (issue 16): the elastic cylinder (plane strain) and sphere
//! (axisymmetric) of `tests/integration/hertz.rs`, pressed on the rigid flat by a **force** `P` (a
//! uniform traction on the flat top, no support there) instead of a prescribed displacement. The
//! body floats along `y` (the symmetry support `u_x = 0` on the axis holds the other modes) and
//! contact alone holds it: the rigid-body amplitude is solved for exactly with the body's
//! equilibrium `Σ r_n = P` (`LinearElasticModel::floating`, `contact_solver`'s floating stage).
//!
//! Source: H. Hertz (1882); K. L. Johnson, *Contact Mechanics*, Cambridge 1985, ch. 4:
//! `a = √(4PR/(πE*))`, `p0 = 2P/(πa)` (cylinder, `P` per unit length) and
//! `a = (3PR/(4E*))^(1/3)`, `p0 = 3P/(2πa²)` (sphere), `E* = E/(1 − ν²)` for a rigid flat.
//!
//! ```text
//!   y = H = 20 ─────────────── traction P/(2L) (plane strain) or P/(πL²) (per radian)
//!    u_x = 0   │    E = 1000  │
//!    (x = 0)   │    ν = 0.3   │ free        R = 100, L = H = 20, a ≈ 1
//!              ╰──___________─╯ arc y = R − √(R² − x²), contactor nodes
//!   ═══════════════════════════ rigid LINE y = 0 (Signorini)
//! ```
//! Mesh and measurements as `tests/integration/hertz.rs` (`tests/support/hertz_scene.rs`): P2,
//! uniform fine zone `[0, 1.5]²` of `16 × 16` cells (`h = a/11`), geometric growth 1.5 beyond.
//!
//! What is asserted, and why:
//! - `P` reproduced by the reactions to `1e-10` relative: the body's equilibrium is solved
//!   to `equilibrium_tol = 1e-11` of the forces involved;
//! - `a` and `p0` within 1 % of Hertz for the load `P` given (the displacement-controlled
//!   scene on this mesh is within 0.6 %; the uniform traction on a top at `H = 20 a` differs
//!   from the half-space by less than that);
//! - the contact stays on the same side of the line: no penetration beyond round-off.

#![cfg(feature = "fe")]

use crate::support::hertz_scene::HertzScene;
use contact_solver::SimulationSettings;
use fem_core::{ElementKind, Idealization};

fn check(idealization: Idealization, p_total: f64) {
    let scene = HertzScene::new(idealization, ElementKind::Tri6, 16);
    let mut sim = scene.force_simulation(p_total, SimulationSettings::default());
    let res = sim
        .step(1.0, 1.0)
        .expect("the force-controlled Hertz step converges");
    let m = scene.measure(&sim, &res);
    eprintln!(
        "{idealization:?} P2 m = 16: P = {p_total} -> {:.15} ({:+.2e}), a = {:.5} vs {:.5} \
         ({:+.2e}), p0 = {:.5} vs {:.5} ({:+.2e}); {} closed / {} active, {} passes, \
         {} Newton iterations, {} solves, α = {:?}, {:.2?}",
        m.p_total,
        (m.p_total - p_total) / p_total,
        m.a_fe,
        m.a_hertz,
        m.a_error(),
        m.p0_fe,
        m.p0_hertz,
        m.p0_error(),
        m.closed,
        m.active,
        res.report.detection_passes,
        res.report.equilibrium_iterations,
        res.report.equilibrium_solves,
        sim.rigid_body_amplitudes(),
        res.report.wall_time,
    );
    // equilibrium solved to 1e-11 of the forces; the sum adds round-off
    assert!(
        ((m.p_total - p_total) / p_total).abs() <= 1e-10,
        "P = {}",
        m.p_total
    );
    // discretisation error on this mesh (module docs)
    assert!(m.a_error().abs() < 0.01, "a error {:e}", m.a_error());
    assert!(m.p0_error().abs() < 0.01, "p0 error {:e}", m.p0_error());
    let scale = res.contacts.iter().map(|c| c.gap.abs()).fold(0.0, f64::max);
    assert!(
        res.contacts
            .iter()
            .all(|c| c.gap >= -1e-9 * scale.max(1e-3))
    );
}

#[test]
fn hertz_force_plane_strain_works() {
    // a ≈ 0.96 for R = 100, E* = 1099
    check(Idealization::PlaneStrain, 8.0);
}

#[test]
fn hertz_force_axisymmetric_works() {
    // a ≈ 0.98
    check(Idealization::Axisymmetric, 14.0);
}
