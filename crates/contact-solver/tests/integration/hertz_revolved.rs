//! Hertz in 3D against the axisymmetric model on the same meridian grid: the axisymmetric
//! scene of `hertz.rs` (P2, `m = 8` fine cells, `a ≈ 1`) revolved into a quarter of 3
//! sectors (`tests/support/hertz_revolved.rs`), the same `δ`. The 3D model differs from the
//! axisymmetric one only by its angular discretisation (P2 in θ, 30° sectors). Measured
//! (`cargo run --release -p contact-solver --example hertz_revolved -- 4 8 16`,
//! `docs/validation.md`): `P` −2.4 %, `a` −1.8 % at `m = 4` (a grid too coarse for the
//! contact: which nodes close differs between the two models, whatever the number of
//! sectors), −0.19 % and +0.11 % at `m = 8`, +0.04 % and −0.06 % at `m = 16`. Asserted at
//! `m = 8`: both within 0.5 % (the bound for mesh-converged answers), and `a` within
//! 2 % of Hertz (the grid's own error, as in `hertz.rs`).

#![cfg(feature = "fe")]

use crate::support::hertz_revolved::{Params, measure, quarter};
use crate::support::hertz_scene::HertzScene;
use contact_solver::SimulationSettings;
use fem_core::{ElementKind, Idealization};

#[test]
fn revolved_hertz_matches_the_axisymmetric_model() {
    let scene = HertzScene::new(Idealization::Axisymmetric, ElementKind::Tri6, 8);
    let mut axi = scene.simulation(SimulationSettings::default());
    let res2 = axi.step(1.0, 1.0).unwrap();
    let m2 = scene.measure(&axi, &res2);
    let params = Params {
        delta: scene.delta,
        young: scene.young,
        poisson: scene.poisson,
        alert: scene.alert,
    };
    let mut sim = quarter(&scene.mesh(), params, 3);
    let res3 = sim.step(1.0, 1.0).unwrap();
    let (p3, a3) = measure(&res3);
    let (a_hertz, _) = scene.hertz(p3);
    eprintln!(
        "axisymmetric: P = {:.5}, a = {:.5}; 3D quarter: P = {p3:.5} ({:+.2e}), a = {a3:.5} \
         ({:+.2e}); Hertz a for the 3D P: {a_hertz:.5}",
        m2.p_total,
        m2.a_fe,
        p3 / m2.p_total - 1.0,
        a3 / m2.a_fe - 1.0
    );
    assert!(
        (p3 / m2.p_total - 1.0).abs() < 5e-3,
        "P {p3} vs {}",
        m2.p_total
    );
    assert!((a3 / m2.a_fe - 1.0).abs() < 5e-3, "a {a3} vs {}", m2.a_fe);
    assert!(
        (a3 / a_hertz - 1.0).abs() < 0.02,
        "a {a3} vs Hertz {a_hertz}"
    );
}
