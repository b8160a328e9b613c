//! Property tests of the adhesion update (seed 3.25, 4.86, 5.44–5.48).
//!
//! Reference: the evolution `α β̇ = −[w − (C_n u_n² + C_t ‖u_t‖²) β]⁻` (Raous, Cangémi &
//! Cocou 1999; seed 4.86) integrated over a step `Δt` by implicit Euler (5.47–5.48, here in
//! closed form), the θ-method (5.44–5.45) and its rate-independent limit `α = 0` (pile study,
//! table 6.3). Properties: β never increases and stays in `[0, 1]`, each closed form solves
//! its own discrete equation, `α → 0` of implicit Euler is the `α = 0` update, `β = 0` is
//! Coulomb. 10 000 cases each over magnitudes 1e-6..1e6.

use contact_laws::strategies::{beta, local_vec, magnitude, non_negative, rccm_params};
use contact_laws::{
    BetaScheme, ContactLaw, Coulomb, LocalVec2, Rccm, RccmParams, RccmState, beta_implicit_euler,
    beta_rate_independent, beta_theta,
};
use proptest::prelude::*;

const TOL: f64 = 1e-12;

fn dt() -> impl Strategy<Value = f64> {
    non_negative()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    #[test]
    fn update_is_monotone_and_bounded(
        p in rccm_params(), beta_start in beta(), u0 in local_vec::<1>(), u in local_vec::<1>(), dt in dt(),
    ) {
        let law = Rccm::new(p).unwrap();
        let start = RccmState::new(beta_start).unwrap();
        let end = law.update_state(&start, &u0, &u, dt);
        prop_assert!(end.beta().is_finite());
        prop_assert!((0.0..=beta_start).contains(&end.beta()), "β: {beta_start} → {}", end.beta());
        prop_assert!(law.state_change(&start, &end) == beta_start - end.beta());
    }

    #[test]
    fn beta_is_non_increasing_along_a_loading_history(
        p in rccm_params(), history in proptest::collection::vec((local_vec::<1>(), dt()), 1..40),
    ) {
        let law = Rccm::new(p).unwrap();
        let mut state = law.initial_state();
        let mut u_prev = LocalVec2::zeros();
        for (u, dt) in history {
            let next = law.update_state(&state, &u_prev, &u, dt);
            prop_assert!(next.beta() <= state.beta() && next.beta() >= 0.0);
            state = next;
            u_prev = u;
        }
    }

    #[test]
    fn implicit_euler_solves_its_discrete_equation(
        beta_prev in beta(), e in non_negative(), w in non_negative(), alpha in magnitude(), dt in dt(),
    ) {
        // β = β_prev + (Δt/α) min(w − E β, 0)  (5.47), and G(β) < 0 ⇔ E β_prev > w.
        // Checked multiplied through by α, the well-conditioned form of the equation.
        let b = beta_implicit_euler(beta_prev, e, w, alpha, dt);
        let lhs = alpha * (b - beta_prev);
        let rhs = dt * (w - e * b).min(0.0);
        let scale = alpha * beta_prev + dt * (w + e * b);
        prop_assert!((lhs - rhs).abs() <= TOL * scale, "α(β − β_prev) = {lhs}, Δt min(G, 0) = {rhs}");
        if e * beta_prev <= w || dt == 0.0 {
            prop_assert_eq!(b, beta_prev); // frozen, exactly
        } else {
            prop_assert!(w - e * b <= TOL * (w + e * b), "damaging but G(β) = {} > 0", w - e * b);
        }
    }

    #[test]
    fn theta_method_solves_its_discrete_equation(
        beta_prev in beta(), e0 in non_negative(), e in non_negative(), w in non_negative(),
        alpha in magnitude(), dt in dt(), theta in 0.0f64..=1.0,
    ) {
        // β = β_prev + Δt [θ y(β, E) + (1 − θ) y(β_prev, E_prev)],  y = min(w − E β, 0)/α
        // (5.44–5.45), unless clamped to [0, β_prev].
        let b = beta_theta(beta_prev, e0, e, w, alpha, dt, theta);
        prop_assert!((0.0..=beta_prev).contains(&b));
        if b > 0.0 && b < beta_prev {
            // Multiplied through by α, as for implicit Euler.
            let y = |beta: f64, en: f64| (w - en * beta).min(0.0);
            let lhs = alpha * (b - beta_prev);
            let rhs = dt * (theta * y(b, e) + (1.0 - theta) * y(beta_prev, e0));
            let scale = alpha * beta_prev + dt * (w + e * b + e0 * beta_prev);
            prop_assert!((lhs - rhs).abs() <= TOL * scale, "α(β − β_prev) = {lhs}, rhs = {rhs}");
        }
        // θ = 1 is implicit Euler.
        prop_assert_eq!(beta_theta(beta_prev, e0, e, w, alpha, dt, 1.0), beta_implicit_euler(beta_prev, e, w, alpha, dt));
    }

    #[test]
    fn rate_independent_update_restores_admissibility(beta_prev in beta(), e in non_negative(), w in non_negative()) {
        // After the update G_β = w − E β ≥ 0: damage stops exactly at the threshold.
        let b = beta_rate_independent(beta_prev, e, w);
        prop_assert!((0.0..=beta_prev).contains(&b));
        prop_assert!(w - e * b >= -TOL * w, "G = {} < 0", w - e * b);
        // and β is the largest admissible value not above β_prev.
        if b < beta_prev {
            prop_assert!((e * b - w).abs() <= TOL * w);
        }
    }

    #[test]
    fn vanishing_viscosity_tends_to_the_rate_independent_update(
        beta_prev in beta(), e in magnitude(), w in non_negative(), dt in magnitude(), k in 0i32..10,
    ) {
        // |β_α − β_0| ≤ α β_prev / (Δt E): first order in α.
        let alpha = 10f64.powi(-k) * dt * e * 1e-2;
        let limit = beta_rate_independent(beta_prev, e, w);
        let b = beta_implicit_euler(beta_prev, e, w, alpha, dt);
        prop_assert!(b >= limit - TOL);
        prop_assert!(b - limit <= alpha * beta_prev / (dt * e) * (1.0 + 1e-9) + TOL, "β_α = {b}, β_0 = {limit}");
    }

    #[test]
    fn alpha_zero_is_rate_independent_for_every_scheme(
        p in rccm_params(), beta_start in beta(), u0 in local_vec::<1>(), u in local_vec::<1>(), dt in dt(),
    ) {
        let law = Rccm::new(RccmParams { alpha: 0.0, ..p }).unwrap();
        let end = law.update_beta(beta_start, &u0, &u, dt);
        prop_assert_eq!(end, beta_rate_independent(beta_start, law.jump_energy(&u), p.w));
    }

    #[test]
    fn beta_zero_reduces_rccm_to_coulomb(p in rccm_params(), tau in local_vec::<1>(), u in local_vec::<1>(), du in local_vec::<1>(), dt in dt()) {
        let rccm = Rccm::new(p).unwrap();
        let coulomb = Coulomb::new(p.mu).unwrap();
        let zero = RccmState::new(0.0).unwrap();
        prop_assert_eq!(rccm.project(&tau, &zero), coulomb.project(&tau, &()));
        prop_assert_eq!(rccm.modified_velocity(&du, &zero), coulomb.modified_velocity(&du, &()));
        prop_assert_eq!(rccm.bipotential(&du, &tau, &zero), coulomb.bipotential(&du, &tau, &()));
        prop_assert_eq!(rccm.adhesive_reaction(&u, &zero), LocalVec2::zeros());
        prop_assert_eq!(rccm.update_state(&zero, &u, &u, dt), zero);
        prop_assert!(!rccm.adhesion_active(&zero));
    }
}

#[test]
fn beta_one_is_frictionless_whatever_mu() {
    let law = Rccm::new(RccmParams {
        c_n: 1.0,
        c_t: 1.0,
        w: 1.0,
        alpha: 1.0,
        mu: 0.5,
        m: 2,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap();
    let s = law.initial_state();
    assert_eq!(law.cone(&s).mu(), 0.0);
    assert_eq!(
        law.project(&LocalVec2::planar(2.0, 3.0), &s),
        LocalVec2::planar(2.0, 0.0)
    );
}
