//! Hertz contact of an elastic cylinder (plane strain) and sphere (axisymmetric) pressed on a
//! rigid flat, frictionless: contact half-width `a` and peak pressure `p0` against the closed
//! forms for the load `P` the simulation transmits.
//!
//! Source: H. Hertz (1882); K. L. Johnson, *Contact Mechanics*, Cambridge 1985, ch. 4:
//! `a = √(4PR/(πE*))`, `p0 = 2P/(πa)` (cylinder, `P` per unit length) and
//! `a = (3PR/(4E*))^(1/3)`, `p0 = 3P/(2πa²)` (sphere), `E* = E/(1 − ν²)` for a rigid flat.
//!
//! ```text
//!   y = H = 20 ─────────────── u_y = −δ
//!    u_x = 0   │    E = 1000  │
//!    (x = 0)   │    ν = 0.3   │ free        R = 100, L = H = 20, a ≈ 1 (L/a ≈ 20)
//!              ╰──___________─╯ arc y = R − √(R² − x²), contactor nodes
//!   ═══════════════════════════ rigid LINE y = 0 (Signorini)
//! ```
//! Half model with symmetry `u_x = 0` on `x = 0` (the axis in axisymmetry); one step. The scene,
//! the mesh (uniform fine zone `[0, 1.5]²` of `m × m` cells, geometric growth 1.5 beyond) and
//! the measurements (`a` from the second moment of the nodal reactions, `p0` from their L2
//! projection on the contact edge) are in `tests/support/hertz_scene.rs`.
//!
//! What is asserted, and why:
//! - P2, `m = 8` (`h = a/5.4`): `a` and `p0` within 2 % of Hertz in plane strain, `a` within
//!   2 % in axisymmetry; run with `--nocapture` for the numbers.
//! - Refinement `m = 4, 8, 16` (plane strain) and `m = 4, 8` (axisymmetric): both errors fall.
//!   The `a` error is not monotone in `h` for every `m`: it depends on where `a` falls
//!   between two contact nodes (`m = 3, 4, 8, 16`: −0.35 %, +1.1 %, −0.53 %, +0.004 %), so
//!   the sequence doubles `m`; the `p0` error falls monotonically, about as `h²` (5.5 %,
//!   1.1 %, 0.26 %).
//! - Global equilibrium: the top's support reactions balance the contact reactions.
//! - ρ robustness: `rho_scale = 1e-3` and `1e3` give the reactions of `rho_scale = 1`.
//!
//! The half-space idealisation costs little: with `m = 16` the `a` error is 4e-5 (plane
//! strain) and 1e-3 (axisymmetric).
//!
//! Cost (debug): one scene takes 0.25 s for `m = 4`, 0.9 s for `m = 8`, 1.9 s for `m = 16` on
//! one core; the file runs in about 3 s on 2 cores (5 s with `--test-threads=1`). Release
//! does `m = 8` in 10 ms. Most of the debug time is the sparse solves that build `F*`
//! (2 per active contact): faer's solves are generic, so they are compiled with the
//! workspace crates' opt-level 0, not with the dependencies' opt-level 3.

#![cfg(feature = "fe")]

use crate::support::hertz_scene::{HertzScene, Measured};
use contact_laws::Signorini;
use contact_solver::{ContactSimulation, SimulationSettings, StepResult};
use fem_core::{Component, ElementKind, Idealization, LinearElasticModel};
use std::time::Instant;

/// Builds, steps and measures the scene on P2 with `m × m` fine cells.
fn run(
    idealization: Idealization,
    m: usize,
    settings: SimulationSettings,
) -> (
    Measured,
    StepResult,
    ContactSimulation<LinearElasticModel, Signorini>,
) {
    let scene = HertzScene::new(idealization, ElementKind::Tri6, m);
    let start = Instant::now();
    let mut sim = scene.simulation(settings);
    let res = sim.step(1.0, 1.0).expect("the Hertz step converges");
    let measured = scene.measure(&sim, &res);
    eprintln!(
        "{idealization:?} P2 m = {m:2} (h = {:.4}, {} nodes): P = {:.5e}, a = {:.5} vs {:.5} \
         ({:+.2e}), p0 = {:.5} vs {:.5} ({:+.2e}); {} closed / {} active, {} sweeps, {:.2?}",
        scene.fine_extent / m as f64,
        sim.structure().mesh().node_count(),
        measured.p_total,
        measured.a_fe,
        measured.a_hertz,
        measured.a_error(),
        measured.p0_fe,
        measured.p0_hertz,
        measured.p0_error(),
        measured.closed,
        measured.active,
        res.report.contact_iterations,
        start.elapsed(),
    );
    (measured, res, sim)
}

/// The sum of the top's support reactions along y plus the sum of the contact reactions.
fn equilibrium_defect(
    sim: &ContactSimulation<LinearElasticModel, Signorini>,
    res: &StepResult,
) -> (f64, f64) {
    let model = sim.structure();
    let reactions = model.reactions(&sim.nodal_displacements(), 1.0).unwrap();
    let support: f64 = reactions
        .iter()
        .filter(|((_, c), _)| *c == Component::Y)
        .map(|(_, r)| r)
        .sum();
    let contact: f64 = res.contacts.iter().map(|c| c.r.n).sum();
    (support + contact, contact)
}

#[test]
fn plane_strain_p2_converges_to_hertz() {
    let settings = SimulationSettings::default();
    let errors: Vec<(f64, f64)> = [4, 8, 16]
        .into_iter()
        .map(|m| {
            let (measured, res, sim) = run(Idealization::PlaneStrain, m, settings);
            let (defect, total) = equilibrium_defect(&sim, &res);
            eprintln!(
                "  equilibrium: (Σ R_top + Σ r_n) / Σ r_n = {:.1e}",
                defect / total
            );
            // u = u_free + K⁻¹ Hᵀ r balances any r exactly: what is left is the round-off of
            // the sparse solves, far below 1e-9
            assert!(
                defect.abs() <= 1e-9 * total,
                "m = {m}: equilibrium defect {defect:e}"
            );
            if m == 8 {
                // the moderate mesh: 2 % is the brief's target; measured 0.5 % (a), 1.1 % (p0)
                assert!(
                    measured.a_error().abs() < 0.02,
                    "a error {:e}",
                    measured.a_error()
                );
                assert!(
                    measured.p0_error().abs() < 0.02,
                    "p0 error {:e}",
                    measured.p0_error()
                );
            }
            (measured.a_error().abs(), measured.p0_error().abs())
        })
        .collect();
    for w in errors.windows(2) {
        assert!(w[1].0 < w[0].0, "a error does not fall: {errors:?}");
        assert!(w[1].1 < w[0].1, "p0 error does not fall: {errors:?}");
    }
}

#[test]
fn axisymmetric_p2_converges_to_hertz() {
    let settings = SimulationSettings::default();
    let errors: Vec<(f64, f64)> = [4, 8]
        .into_iter()
        .map(|m| {
            let (measured, res, sim) = run(Idealization::Axisymmetric, m, settings);
            let (defect, total) = equilibrium_defect(&sim, &res);
            eprintln!(
                "  equilibrium: (Σ R_top + Σ r_n) / Σ r_n = {:.1e}",
                defect / total
            );
            // per radian on both sides: the same balance (and bound) as in plane strain
            assert!(
                defect.abs() <= 1e-9 * total,
                "m = {m}: equilibrium defect {defect:e}"
            );
            if m == 8 {
                // 2 % is the brief's target; measured 0.55 % (p0 is 2.7 % off here, 0.75 % at
                // m = 16: the r-weighted projection converges more slowly at the axis)
                assert!(
                    measured.a_error().abs() < 0.02,
                    "a error {:e}",
                    measured.a_error()
                );
            }
            (measured.a_error().abs(), measured.p0_error().abs())
        })
        .collect();
    assert!(
        errors[1].0 < errors[0].0,
        "a error does not fall: {errors:?}"
    );
    assert!(
        errors[1].1 < errors[0].1,
        "p0 error does not fall: {errors:?}"
    );
}

#[test]
fn rho_scale_does_not_change_the_hertz_reactions() {
    let mut settings = SimulationSettings::default();
    // two digits beyond the 1e-8 asked of the comparison
    settings.solver.tol = 1e-12;
    let reactions = |rho_scale: f64| {
        let mut s = settings;
        s.solver.tuning.rho_scale = rho_scale;
        let (_, res, _) = run(Idealization::PlaneStrain, 4, s);
        eprintln!(
            "  rho_scale = {rho_scale:e}: {} sweeps",
            res.report.contact_iterations
        );
        assert!(res.report.converged);
        res.contacts.iter().map(|c| c.r.n).collect::<Vec<f64>>()
    };
    let reference = reactions(1.0);
    let largest = reference.iter().fold(0.0_f64, |a, r| a.max(r.abs()));
    for rho_scale in [1e-3, 1e3] {
        let r = reactions(rho_scale);
        let diff = r
            .iter()
            .zip(&reference)
            .fold(0.0_f64, |a, (x, y)| a.max((x - y).abs()))
            / largest;
        eprintln!("  rho_scale = {rho_scale:e}: max |Δr| / max |r| = {diff:.1e}");
        // the brief's 1e-8; both runs stop at a 1e-12 natural-map residual
        assert!(diff <= 1e-8, "rho_scale = {rho_scale:e}: {diff:e}");
    }
}
