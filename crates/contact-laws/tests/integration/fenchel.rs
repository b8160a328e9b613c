//! Property tests of the Fenchel inequality of the bipotentials (seed 4.8–4.9, 4.69–4.71,
//! 4.79–4.81): `b(v, f) ≥ v·f` everywhere and `=` exactly on the pairs that obey the law.
//!
//! Cases: `b_c` (Coulomb, 4.28), the adhesive `b_c(−u̇, r̄)` with `μ̄ = μ f(β)` (4.63),
//! `b_β` (4.79) and the full `b = b_c + b_β` (4.81). Indicator functions are `+∞` and must
//! never produce NaN. Extremal pairs are built from each status: stick, slip and separation;
//! β damaging and β frozen. 10 000 cases each over magnitudes 1e-6..1e6.

use contact_laws::strategies::{beta, local_vec, magnitude, non_negative, rccm_params, signed};
use contact_laws::{
    ContactLaw, Coulomb, CoulombCone, LocalVec, Rccm, RccmState, adhesion_bipotential,
    contact_bipotential, contact_fenchel_gap, modified_velocity,
};
use nalgebra::SVector;
use proptest::prelude::*;

const TOL: f64 = 1e-12;

/// The status used to build an extremal pair.
#[derive(Clone, Copy, Debug)]
enum Status {
    Stick,
    Slip,
    Separation,
}

fn status() -> impl Strategy<Value = Status> {
    prop_oneof![
        Just(Status::Stick),
        Just(Status::Slip),
        Just(Status::Separation)
    ]
}

fn unit<const DT: usize>() -> impl Strategy<Value = SVector<f64, DT>> {
    proptest::array::uniform::<_, DT>(magnitude().prop_flat_map(|m| prop_oneof![Just(m), Just(-m)]))
        .prop_map(|d| {
            let d = SVector::<f64, DT>::from(d);
            d / d.norm()
        })
}

/// A pair `(u̇, r)` that obeys Signorini–Coulomb with friction `mu`, built from `status`.
fn extremal_pair<const DT: usize>(
    mu: f64,
    status: Status,
    a: f64,
    b: f64,
    s: f64,
    d: SVector<f64, DT>,
) -> (LocalVec<DT>, LocalVec<DT>) {
    match status {
        // u̇ = 0, r anywhere in K_μ.
        Status::Stick => (LocalVec::zeros(), LocalVec::new(a, d * (s * mu * a))),
        // r on the cone's surface, u̇_n = 0, u̇_t = −λ r_t/‖r_t‖ (λ = b).
        Status::Slip => (LocalVec::new(0.0, -d * b), LocalVec::new(a, d * (mu * a))),
        // r = 0, u̇_n ≥ 0, any u̇_t.
        Status::Separation => (LocalVec::new(a, d * b), LocalVec::zeros()),
    }
}

/// Magnitude scale of `u̇ · r` terms, for relative tolerances.
fn scale<const DT: usize>(mu: f64, du: &LocalVec<DT>, r: &LocalVec<DT>) -> f64 {
    (1.0 + mu) * du.norm() * r.norm()
}

fn check_contact_gap<const DT: usize>(
    cone: &CoulombCone,
    du: &LocalVec<DT>,
    r: &LocalVec<DT>,
) -> Result<(), TestCaseError> {
    let b = contact_bipotential(cone, du, r);
    let gap = contact_fenchel_gap(cone, du, r);
    prop_assert!(!b.is_nan() && !gap.is_nan(), "NaN: b = {b}, gap = {gap}");
    prop_assert!(
        b >= -du.dot(r) - TOL * scale(cone.mu(), du, r),
        "b_c < −u̇·r"
    );
    prop_assert!(gap >= -TOL * scale(cone.mu(), du, r), "negative gap {gap}");
    Ok(())
}

fn check_extremal<const DT: usize>(
    mu: f64,
    status: Status,
    (a, b, s): (f64, f64, f64),
    d: SVector<f64, DT>,
) -> Result<(), TestCaseError> {
    let cone = CoulombCone::new(mu).unwrap();
    let (du, r) = extremal_pair(mu, status, a, b, s, d);
    let gap = contact_fenchel_gap(&cone, &du, &r);
    prop_assert!(
        gap.is_finite(),
        "{status:?}: infinite gap for ({du:?}, {r:?})"
    );
    prop_assert!(
        gap.abs() <= TOL * scale(mu, &du, &r),
        "{status:?}: gap {gap} ≠ 0"
    );
    // The pair is a fixed point of the Uzawa step: P(r + ρ v(u̇)) = r for any ρ > 0.
    let v = modified_velocity(&cone, &du);
    for rho in [1e-3, 1.0, 1e3] {
        let back = cone.project(&(r + v * rho));
        prop_assert!(
            (back - r).norm() <= 1e-10 * (r.norm() + rho * v.norm()),
            "{status:?}: P(r + ρv) = {back:?} ≠ r = {r:?} (ρ = {rho})"
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    #[test]
    fn contact_bipotential_satisfies_fenchel_2d(mu in non_negative(), du in local_vec::<1>(), r in local_vec::<1>()) {
        check_contact_gap(&CoulombCone::new(mu).unwrap(), &du, &r)?;
    }

    #[test]
    fn contact_bipotential_satisfies_fenchel_3d(mu in non_negative(), du in local_vec::<2>(), r in local_vec::<2>()) {
        check_contact_gap(&CoulombCone::new(mu).unwrap(), &du, &r)?;
    }

    #[test]
    fn contact_bipotential_satisfies_fenchel_on_its_domain(
        mu in non_negative(), un in non_negative(), ut in signed(), rn in non_negative(), s in -1.0f64..=1.0,
    ) {
        // Finite part: r ∈ K_μ and u̇_n ≥ 0, where only the coupling term μ r_n ‖u̇_t‖ acts.
        let cone = CoulombCone::new(mu).unwrap();
        let du = LocalVec::planar(un, ut);
        let r = LocalVec::planar(rn, s * mu * rn);
        prop_assert!(contact_bipotential(&cone, &du, &r).is_finite());
        check_contact_gap(&cone, &du, &r)?;
    }

    #[test]
    fn extremal_pairs_give_equality_2d(
        mu in non_negative(), status in status(), a in magnitude(), b in magnitude(), s in 0.0f64..=1.0, d in unit::<1>(),
    ) {
        check_extremal(mu, status, (a, b, s), d)?;
    }

    #[test]
    fn extremal_pairs_give_equality_3d(
        mu in non_negative(), status in status(), a in magnitude(), b in magnitude(), s in 0.0f64..=1.0, d in unit::<2>(),
    ) {
        check_extremal(mu, status, (a, b, s), d)?;
    }

    #[test]
    fn moreau_pairs_are_extremal(mu in non_negative(), tau in local_vec::<2>()) {
        // r = P_K(τ) and v = P_K*(τ) ∈ N_K(r); invert v = −(u̇_t + (u̇_n + μ‖u̇_t‖) n).
        // u̇_n ≥ 0 holds exactly; in floating point it is ≥ −ε‖τ‖, so it is clamped.
        let cone = CoulombCone::new(mu).unwrap();
        let r = cone.project(&tau);
        let v = cone.project_polar(&tau);
        let du_n = -v.n - mu * v.t_norm();
        prop_assert!(du_n >= -1e-12 * tau.norm());
        let du = LocalVec::new(du_n.max(0.0), -v.t);
        let gap = contact_fenchel_gap(&cone, &du, &r);
        prop_assert!(gap.is_finite());
        prop_assert!(gap.abs() <= 1e-11 * scale(mu, &du, &r) + 1e-11 * tau.norm() * tau.norm());
    }

    #[test]
    fn adhesive_contact_bipotential_satisfies_fenchel(
        p in rccm_params(), beta in beta(), du in local_vec::<1>(), r_bar in local_vec::<1>(),
    ) {
        let law = Rccm::new(p).unwrap();
        let state = RccmState::new(beta).unwrap();
        let gap = law.fenchel_gap(&du, &r_bar, &state);
        prop_assert!(!gap.is_nan());
        prop_assert!(gap >= -TOL * scale(p.mu, &du, &r_bar));
    }

    #[test]
    fn adhesive_contact_extremal_pairs_use_the_effective_friction(
        p in rccm_params(), beta in beta(), status in status(), a in magnitude(), b in magnitude(),
        s in 0.0f64..=1.0, d in unit::<1>(),
    ) {
        // Built with μ̄ = μ f(β): extremal for the RCCM law's b_c(−u̇, r̄) (4.63, 4.70).
        let law = Rccm::new(p).unwrap();
        let state = RccmState::new(beta).unwrap();
        let mu_bar = law.cone(&state).mu();
        prop_assert!((mu_bar - p.mu * law.friction_factor(beta)).abs() <= 1e-15 * p.mu);
        let (du, r_bar) = extremal_pair(mu_bar, status, a, b, s, d);
        let gap = law.fenchel_gap(&du, &r_bar, &state);
        prop_assert!(gap.abs() <= TOL * scale(mu_bar, &du, &r_bar), "{status:?}: gap {gap}");
    }

    #[test]
    fn adhesion_bipotential_satisfies_fenchel(alpha in non_negative(), beta_dot in signed(), g in signed()) {
        let b = adhesion_bipotential(alpha, beta_dot, g);
        prop_assert!(!b.is_nan());
        let s = beta_dot.abs() * g.abs();
        prop_assert!(b >= beta_dot * g - TOL * s, "b_β = {b} < β̇G = {}", beta_dot * g);
    }

    #[test]
    fn adhesion_extremal_pairs_give_equality(alpha in non_negative(), g in signed(), damaging in any::<bool>(), x in magnitude()) {
        // Damaging: G < 0, β̇ = G/α (α = 0: G = 0, any β̇ ≤ 0). Frozen: G ≥ 0, β̇ = 0.
        let (beta_dot, g) = if damaging {
            if alpha > 0.0 { let g = -g.abs(); (g / alpha, g) } else { (-x, 0.0) }
        } else {
            (0.0, g.abs())
        };
        let b = adhesion_bipotential(alpha, beta_dot, g);
        prop_assert!(b.is_finite());
        prop_assert!((b - beta_dot * g).abs() <= TOL * (beta_dot * g).abs(), "b_β = {b}, β̇G = {}", beta_dot * g);
    }

    #[test]
    fn full_bipotential_satisfies_fenchel(
        p in rccm_params(), beta in beta(), du in local_vec::<1>(), r_bar in local_vec::<1>(),
        u in local_vec::<1>(), beta_dot in signed(),
    ) {
        let law = Rccm::new(p).unwrap();
        let state = RccmState::new(beta).unwrap();
        let gap = law.fenchel_gap_full(&du, beta_dot, &r_bar, &u, &state);
        prop_assert!(!gap.is_nan());
        let g = law.g_beta(&u, beta);
        let s = scale(p.mu, &du, &r_bar) + (beta_dot * g).abs();
        prop_assert!(gap >= -TOL * s, "full gap {gap}");
    }

    #[test]
    fn full_bipotential_is_tight_on_extremal_pairs(
        p in rccm_params(), alpha in magnitude(), beta in beta(), status in status(), a in magnitude(),
        b in magnitude(), s in 0.0f64..=1.0, d in unit::<1>(), u in local_vec::<1>(),
    ) {
        // Contact pair extremal for μ̄, and β̇ = −[G_β]⁻/α (seed 4.83c): damaging if G_β < 0,
        // frozen otherwise.
        let law = Rccm::new(p.clone_with_alpha(alpha)).unwrap();
        let state = RccmState::new(beta).unwrap();
        let (du, r_bar) = extremal_pair(law.cone(&state).mu(), status, a, b, s, d);
        let g = law.g_beta(&u, beta);
        let beta_dot = g.min(0.0) / alpha;
        let gap = law.fenchel_gap_full(&du, beta_dot, &r_bar, &u, &state);
        let sc = scale(p.mu, &du, &r_bar) + (beta_dot * g).abs() + law.adhesion_bipotential(beta_dot, g);
        prop_assert!(gap.abs() <= TOL * sc, "{status:?}: full gap {gap}");
    }

    #[test]
    fn coulomb_law_and_free_functions_agree(mu in non_negative(), du in local_vec::<2>(), r in local_vec::<2>()) {
        let law = Coulomb::new(mu).unwrap();
        let cone = CoulombCone::new(mu).unwrap();
        prop_assert_eq!(law.bipotential(&du, &r, &()), contact_bipotential(&cone, &du, &r));
        prop_assert_eq!(law.modified_velocity(&du, &()), modified_velocity(&cone, &du));
    }
}

/// Helper: the same parameters with another viscosity.
trait WithAlpha {
    fn clone_with_alpha(&self, alpha: f64) -> Self;
}

impl WithAlpha for contact_laws::RccmParams {
    fn clone_with_alpha(&self, alpha: f64) -> Self {
        Self { alpha, ..*self }
    }
}
