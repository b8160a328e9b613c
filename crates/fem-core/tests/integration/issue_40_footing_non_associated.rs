//! The rigid rough strip footing of `issue_40_strip_footing` with **non-associated** flow
//! (`φ = 20°`, `θ = 10°` and `0`), issue 40. Sources: Davis (1968), "Theories of plasticity
//! and the failure of soil masses" (the equivalent associated soil); Drescher & Detournay
//! (1993); Krabbenhøft, Karim, Lyamin & Sloan (2012), "Associated computational plasticity
//! schemes for nonassociated frictional materials", IJNME 90; Loukidis & Salgado (2009) and
//! Frydman & Burd (1997), who report non-associated `N_c` 10–25 % below the associated one
//! for `θ = 0`.
//!
//! **Why the direct Newton stalls** (measured by `issue_40_strip_footing_non_associated_diagnosis`,
//! `docs/validation.md`): the footing is already displacement-controlled (prescribed
//! settlement, `q` from the reaction), and the global exact tangent matches central
//! differences of the internal forces to 1e-9 (relative) along every Newton direction, so
//! neither the control nor the tangent is at fault. What does not settle is the set of
//! yielding points: 40 to 190 of the 2520 points switch between elastic and plastic at every
//! iteration, with no fall of the residual (1e-1 after 15 iterations), where the associated
//! footing's set settles in 2–3 iterations. The cause is the law itself: with `θ < φ` and
//! perfect plasticity, Rudnicki & Rice's (1975) critical hardening modulus is positive in
//! plane strain (at `θ = 0`, `s_zz = 0` at flow and `h_crit / G = (1 + ν)² μ² / (18 (1 − ν)) >
//! 0`), so the acoustic tensor of the continuum tangent loses definiteness as soon as a point
//! yields: the incremental problem is no longer monotone and may have several solutions,
//! and Newton (exact or symmetrised tangent, with or without a line search on the residual)
//! cycles between them. Smaller steps do not help (halved 12 times, the step still
//! cycles); a backtracking line search on `‖r‖` advances, with 10–60 solves per step, to
//! `q ≈ 14.2c` at `θ = 10°` and then creeps.
//!
//! **What the test runs instead**: Davis's equivalent associated soil. In plane strain the
//! cone with dilatancy `θ` flows with `ε̇ᵖ_zz = 0`, which fixes `s_zz = −k_d tan θ ‖s‖ / 3` and
//! turns the cone into a Mohr–Coulomb envelope `(φ_ps, c_ps)` with a dilatancy angle `ψ_ps`
//! in the plane (`davis_equivalent`); Davis's soil is then associated with
//!
//! ```text
//! β = cos ψ_ps cos φ_ps / (1 − sin ψ_ps sin φ_ps),   c* = β c_ps,   tan φ* = β tan φ_ps
//! φ = 20°: θ = 10° → φ* = 19.57°, c* = 0.9765 c, c* N_c(φ*) = 14.10 c (−5.0 %)
//!          θ =  0° → φ* = 18.55°, c* = 0.9219 c, c* N_c(φ*) = 12.49 c (−15.8 %)
//! ```
//!
//! an associated law, so its Newton is the quadratic one of the associated footing (at most
//! 8 solves per step). The direct non-associated Newton is run beside it as far as it
//! converges within 8 solves per step: its states are true equilibria of the
//! non-associated law, so they bound its collapse load from below.

use super::issue_40_strip_footing::{
    C, FootingMesh, FootingStep, HALF_WIDTH, footing_body, n_c, push, short, soil,
};
use fem_core::plastic::newton::NewtonSettings;
use fem_core::plastic::{
    ConeMatch, ConstitutivePoint, DruckerPrager, DruckerPragerParameters, PlasticModel,
    PointState, Voigt, VoigtMatrix,
};
use fem_core::{Component, FemError, Nonlinear, Structure};
use std::sync::{Arc, Mutex};

/// Davis's equivalent associated soil of the plane-strain cone (`ConeMatch::PlaneStrain`)
/// with friction `φ` and dilatancy `θ` (degrees): `(φ*, c* / c)`, module docs.
///
/// With `t` the in-plane radius and `p` the in-plane mean stress, the flow rule with
/// `ε̇ᵖ_zz = 0` gives `‖s‖ = √2 t / √(1 − k_d² tan²θ / 6)` and `s_m = p − k_d tan θ ‖s‖ / 6`,
/// so that the cone reads `A t + p tan φ = c`, i.e. `sin φ_ps = tan φ / A`,
/// `c_ps = c / (A cos φ_ps)`, and the in-plane flow `sin ψ_ps = k_d tan θ / √(2 − k_d² tan²θ / 3)`.
/// At `θ = φ` it returns `(φ, 1)`.
fn davis_equivalent(friction_angle: f64, dilatancy_angle: f64) -> (f64, f64) {
    let (phi, theta) = (friction_angle.to_radians(), dilatancy_angle.to_radians());
    let (tan_phi, tan_theta) = (phi.tan(), theta.tan());
    let k_d = ConeMatch::PlaneStrain.k_d(phi);
    let shrink = 1.0 - k_d * k_d * tan_theta * tan_theta / 6.0;
    let a = 2f64.sqrt() * (1.0 / k_d - k_d * tan_theta * tan_phi / 6.0) / shrink.sqrt();
    let phi_ps = (tan_phi / a).asin();
    let c_ps = 1.0 / (a * phi_ps.cos());
    let sin_psi = k_d * tan_theta / (2.0 - k_d * k_d * tan_theta * tan_theta / 3.0).sqrt();
    let beta = (1.0 - sin_psi * sin_psi).sqrt() * phi_ps.cos() / (1.0 - sin_psi * phi_ps.sin());
    ((beta * phi_ps.tan()).atan().to_degrees(), beta * c_ps)
}

/// The associated plane-strain soil with friction angle `phi` (degrees) and cohesion
/// `cohesion`, otherwise as `soil`.
fn associated_soil(phi: f64, cohesion: f64) -> Arc<dyn ConstitutivePoint> {
    Arc::new(
        DruckerPrager::new(DruckerPragerParameters {
            young: 1e4 * C,
            poisson: 0.3,
            friction_angle: phi,
            dilatancy_angle: phi,
            cohesion,
            cone: ConeMatch::PlaneStrain,
        })
        .unwrap(),
    )
}

/// At most 8 solves per step to `1e-10`, as the associated footing.
fn eight_solves() -> NewtonSettings {
    NewtonSettings {
        max_iterations: 8,
        ..NewtonSettings::default()
    }
}

/// The direct non-associated run: the last converged `(δ/b, q/c)` of [`push`] with at most
/// 8 solves per step and `max_cuts` halvings, whether it arrived at `settlement` or stalled.
fn direct(theta: f64, settlement: f64, max_cuts: usize) -> (f64, f64) {
    let (mut body, footing) = footing_body(&FootingMesh::CI, soil(20.0, theta));
    match push(&mut body, &footing, settlement, 20, &eight_solves(), max_cuts) {
        Ok(curve) => {
            let last = curve.last().unwrap();
            (last.settlement, last.pressure)
        }
        Err(FemError::NotConverged {
            converged_load_factor,
            ..
        }) => {
            let q = -body.reaction(&footing, Component::Y).unwrap() / HALF_WIDTH / C;
            (converged_load_factor, q)
        }
        Err(e) => panic!("θ = {theta}: {e}"),
    }
}

/// The plateau (the last two steps within 0.1 %) and the superlinear end of every step:
/// where the residual before the last solve is above 1e-8, the last solve divides it by
/// at least 100 (as `check_collapse` of the associated footing).
fn check_plateau_and_rate(curve: &[FootingStep], what: &str) {
    let n = curve.len();
    let (q, q_before) = (curve[n - 1].pressure, curve[n - 2].pressure);
    assert!(
        (q - q_before).abs() < 1e-3 * q,
        "{what}: not on the plateau: {q_before} → {q}"
    );
    for step in curve {
        let r = &step.residuals;
        assert!(r.len() <= 9, "{what}: {} solves", r.len() - 1);
        if r.len() > 2 && r[r.len() - 2] > 1e-8 {
            assert!(
                r[r.len() - 1] <= 1e-2 * r[r.len() - 2],
                "{what}, δ/b = {}: {}",
                step.settlement,
                short(r)
            );
        }
    }
}

/// `φ = 20°`, `θ = 10°` and `0`: Davis's equivalent soil on the CI mesh reaches a plateau with
/// at most 8 solves per step, converging quadratically (residuals printed), within 5 % of its
/// closed form `c* N_c(φ*)` (the associated footing's tolerance: measured +2.9 % there, the
/// P2 mesh's error at the footing edge). Against the literature: below the associated
/// `N_c = 14.835` and above `0.75 N_c` for `θ = 0` (Loukidis & Salgado, Frydman & Burd:
/// 10–25 % lower), within `[0.9, 1)·N_c` for `θ = 10°` (half the dilatancy: a reduction
/// between 0 and the 10 % at the low end of `θ = 0`'s band). The direct non-associated
/// Newton, as far as it converges, stays below the equivalent collapse load (its states
/// are equilibria of the law, a lower bound of its collapse load).
#[test]
fn issue_40_strip_footing_non_associated_works() {
    let associated = n_c(20.0);
    for (theta, low, high) in [(10.0, 0.90, 1.0), (0.0, 0.75, 0.90)] {
        let (phi_star, c_star) = davis_equivalent(20.0, theta);
        let expected = c_star * n_c(phi_star);
        let (mut body, footing) = footing_body(&FootingMesh::CI, associated_soil(phi_star, c_star));
        let curve = push(&mut body, &footing, 0.05, 20, &eight_solves(), 30).unwrap();
        for step in &curve {
            eprintln!(
                "θ = {theta} (Davis φ* = {phi_star:.3}°, c* = {c_star:.4} c): δ/b = {:.5}, \
                 q/c = {:.4}, residuals {}",
                step.settlement,
                step.pressure,
                short(&step.residuals)
            );
        }
        check_plateau_and_rate(&curve, &format!("θ = {theta}"));
        let q = curve.last().unwrap().pressure;
        eprintln!(
            "θ = {theta}: q/c = {q:.4}, c* N_c(φ*) = {expected:.4} ({:+.2} %), \
             q / N_c(20°) = {:.4}",
            100.0 * (q / expected - 1.0),
            q / associated
        );
        assert!(
            (q - expected).abs() < 0.05 * expected,
            "θ = {theta}: q/c = {q}, c* N_c(φ*) = {expected}"
        );
        assert!(
            q > low * associated && q < high * associated,
            "θ = {theta}: q / N_c = {} outside [{low}, {high}]",
            q / associated
        );
        // the direct law, 8 solves per step, 10 halvings: converged states below the plateau
        let (reached, q_direct) = direct(theta, 0.05, 10);
        eprintln!("θ = {theta}, direct: q/c = {q_direct:.4} at δ/b = {reached:.5}");
        assert!(reached > 0.0, "θ = {theta}: the direct Newton converged no step");
        assert!(
            q_direct < q,
            "θ = {theta}: direct q/c = {q_direct} above the equivalent {q}"
        );
    }
}
