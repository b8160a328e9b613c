//! A law written outside the crate through the `ContactLaw` trait: Tresca friction.
//!
//! Reference: Tresca's law (friction threshold `s` independent of the normal reaction) is a
//! standard (associated) law: `K = {r_n ≥ 0, ‖r_t‖ ≤ s}`, `v = −u̇ ∈ N_K(r)` and the
//! bipotential separates, `b(−u̇, r) = I_K(r) + I_ℝ⁻(−u̇_n) + s‖u̇_t‖` (Duvaut & Lions 1972;
//! De Saxcé & Feng 1991). The test checks the trait's default methods on it, then runs one
//! generic single-contact Uzawa loop — written only against `ContactLaw`, as the solver is —
//! for Signorini, Coulomb, RCCM and this Tresca law, against closed-form solutions.
//!
//! Single contact: gap `x = F r + x_free` with `F = f I` (flexibility, mm/N) and
//! `x_free = (−1, 0.5)` (penetrating, sliding), so `r_n = 1/f` and the tangential reaction is
//! stick `r_t = −0.5/f` when the threshold allows it, slip at the threshold otherwise.

use contact_laws::strategies::{local_vec, magnitude};
use contact_laws::{
    BetaScheme, ContactLaw, Coulomb, LocalVec, LocalVec2, Rccm, RccmParams, RccmState, Signorini,
};
use proptest::prelude::*;

/// Tresca friction with threshold `s ≥ 0` (force per area).
#[derive(Clone, Copy, Debug)]
struct Tresca {
    s: f64,
}

impl ContactLaw for Tresca {
    type State = ();

    fn has_friction(&self) -> bool {
        self.s > 0.0
    }

    fn project<const DT: usize>(&self, tau: &LocalVec<DT>, _: &()) -> LocalVec<DT> {
        // K is a product set: project each part.
        let tt = tau.t_norm();
        let t = if tt > self.s {
            tau.t * (self.s / tt)
        } else {
            tau.t
        };
        LocalVec::new(tau.n.max(0.0), t)
    }

    fn modified_velocity<const DT: usize>(&self, du: &LocalVec<DT>, _: &()) -> LocalVec<DT> {
        -*du // associated law: no De Saxcé correction
    }

    fn bipotential<const DT: usize>(&self, du: &LocalVec<DT>, r: &LocalVec<DT>, _: &()) -> f64 {
        let in_k = r.n >= 0.0 && r.t_norm() <= self.s * (1.0 + 1e-14);
        if !in_k || du.n < 0.0 {
            return f64::INFINITY;
        }
        self.s * du.t_norm()
    }
}

/// One contact, `x = f r + x_free`, solved by the bipotential Uzawa iteration of seed 5.26
/// with the step increment `x` in place of `u̇`. Generic over the law, like the solver.
fn solve_single_contact<L: ContactLaw>(law: &L, f: f64, x_free: LocalVec2) -> (LocalVec2, usize) {
    let state = law.initial_state();
    let rho = 0.5 / f;
    let mut r_bar = LocalVec2::zeros();
    for it in 1..=10_000 {
        let x = r_bar * f + x_free;
        let r_adh = law.adhesive_reaction(&x, &state);
        let next = law.project(&(r_bar + law.modified_velocity(&x, &state) * rho), &state);
        if (next - r_bar).norm() <= 1e-14 * next.norm().max(1e-300) {
            return (next + r_adh, it);
        }
        r_bar = next;
    }
    panic!("single-contact Uzawa did not converge");
}

#[test]
fn generic_uzawa_solves_a_single_contact_for_every_law() {
    let f = 2.0;
    let x_free = LocalVec2::planar(-1.0, 0.5);
    let close = |r: LocalVec2, n: f64, t: f64| {
        assert!(
            (r.n - n).abs() <= 1e-12 && (r.t[0] - t).abs() <= 1e-12,
            "r = {r:?}, expected ({n}, {t})"
        );
    };
    // Signorini: r = (1/f, 0).
    close(solve_single_contact(&Signorini, f, x_free).0, 0.5, 0.0);
    // Coulomb μ = 0.8 ≥ 0.5: stick, r_t = −0.5/f; μ = 0.2: slip, r_t = −μ r_n.
    close(
        solve_single_contact(&Coulomb::new(0.8).unwrap(), f, x_free).0,
        0.5,
        -0.25,
    );
    close(
        solve_single_contact(&Coulomb::new(0.2).unwrap(), f, x_free).0,
        0.5,
        -0.1,
    );
    // Tresca s = 1: stick; s = 0.05: slip at the threshold.
    close(
        solve_single_contact(&Tresca { s: 1.0 }, f, x_free).0,
        0.5,
        -0.25,
    );
    close(
        solve_single_contact(&Tresca { s: 0.05 }, f, x_free).0,
        0.5,
        -0.05,
    );
    // RCCM with β₀ = 0 is Coulomb.
    let rccm = Rccm::new(RccmParams {
        c_n: 1.0,
        c_t: 1.0,
        w: 1.0,
        alpha: 1.0,
        mu: 0.2,
        m: 1,
        beta_0: 0.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap();
    assert_eq!(rccm.initial_state(), RccmState::new(0.0).unwrap());
    close(solve_single_contact(&rccm, f, x_free).0, 0.5, -0.1);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    #[test]
    fn user_law_gets_a_sound_default_fenchel_gap(s in magnitude(), du in local_vec::<2>(), r in local_vec::<2>(), tau in local_vec::<2>()) {
        let law = Tresca { s };
        // Everywhere: gap ≥ 0 and never NaN.
        let gap = law.fenchel_gap(&du, &r, &());
        prop_assert!(gap >= -1e-12 * du.norm() * r.norm());
        // On Moreau pairs (r = P(τ), −u̇ = τ − P(τ)): gap = 0.
        let p = law.project(&tau, &());
        let du = p - tau;
        let gap = law.fenchel_gap(&du, &p, &());
        prop_assert!(gap.abs() <= 1e-12 * tau.norm() * tau.norm(), "gap {gap}");
        // Defaults: no adhesion, no state change.
        prop_assert!(!law.has_adhesion() && !law.adhesion_active(&()));
        prop_assert_eq!(law.adhesive_reaction(&du, &()), LocalVec::zeros());
    }
}
