//! The [`ContactLaw`] trait: what the contact solver needs from a local law.

use crate::local::LocalVec;

/// A local contact law written with a bipotential, as the contact solver consumes it.
///
/// The solver (crate `contact-solver`) is generic over `L: ContactLaw`, so every call below
/// is monomorphised and inlined in its hot loop. Implementations must be pure, allocation
/// free and infallible: validate parameters in the constructor, not here. Every method is
/// generic over the dimension `DT` of the tangent plane (1 in 2D, 2 in 3D).
///
/// The solver's loop at one contact, per Uzawa iteration (seed 5.26a/b):
///
/// ```text
/// r_adh = law.adhesive_reaction(u, state)        (zero without adhesion)
/// v     = law.modified_velocity(du, state)       (De Saxcé's v, seed 4.39)
/// τ     = r̄ + ρ v                                 (prediction, 5.26a)
/// r̄     = law.project(τ, state)                   (correction, 5.26b)
/// r     = r̄ + r_adh
/// ```
/// and, per adhesion iteration, `state = law.update_state(start, u_start, u, dt)`.
///
/// # Writing your own law
/// Implement the four required methods; keep [`has_friction`](Self::has_friction) and
/// [`has_adhesion`](Self::has_adhesion) honest, because the solver uses them to skip the
/// tangential work and the adhesion loop. `project` must be the orthogonal projection onto a
/// closed convex set `K` and `modified_velocity(du)` must lie in the normal cone `N_K(r)`
/// exactly when `(du, r)` obeys your law; `bipotential` is then `≥ −du·r` with equality on
/// those pairs. See `docs/guide.md` and the test `tests/integration/user_law.rs` (a Tresca law).
pub trait ContactLaw {
    /// Per-contact internal state: `()` for Signorini and Coulomb, `RccmState` (β) for RCCM.
    type State: Copy + Default + core::fmt::Debug + PartialEq;

    /// The state at the start of the analysis. Defaults to `State::default()`.
    #[inline]
    fn initial_state(&self) -> Self::State {
        Self::State::default()
    }

    /// `true` when the law has a tangential response (a non-zero friction coefficient).
    /// When `false` the solver may skip the tangential components entirely.
    fn has_friction(&self) -> bool;

    /// `true` when the law carries adhesion (an internal variable that needs the adhesion
    /// fixed point). Defaults to `false`.
    #[inline]
    fn has_adhesion(&self) -> bool {
        false
    }

    /// `true` while this contact's adhesion is still active (for RCCM, `β > 0`); a contact
    /// whose adhesion is exhausted needs no state update. Defaults to `false`.
    #[inline]
    fn adhesion_active(&self, _state: &Self::State) -> bool {
        false
    }

    /// Correction step (seed 5.26b): the orthogonal projection of the augmented reaction
    /// `tau` onto the law's convex set (for Coulomb-type laws `K_μ̄`, seed 5.38).
    fn project<const DT: usize>(&self, tau: &LocalVec<DT>, state: &Self::State) -> LocalVec<DT>;

    /// The modified velocity `v` of the prediction step `τ = r̄ + ρ v` (seed 5.26a); for
    /// Coulomb-type laws `v = −(u̇_t + (u̇_n + μ̄‖u̇_t‖) n)` (seed 4.39).
    fn modified_velocity<const DT: usize>(
        &self,
        du: &LocalVec<DT>,
        state: &Self::State,
    ) -> LocalVec<DT>;

    /// The stiffnesses `[k_n, k_t]` of the adhesive springs in `state`: the adhesive reaction is
    /// `r_adh = −(k_n u_n, k_t u_t)` (for RCCM `k = β² (C_n, C_t)`, seed 4.31). The contact
    /// solver condenses these springs into the reduced problem exactly, so the adhesive part of
    /// a law must be linear in the jump `u` at fixed state. Defaults to `[0, 0]` (no adhesion).
    #[inline]
    fn adhesive_stiffness(&self, _state: &Self::State) -> [f64; 2] {
        [0.0, 0.0]
    }

    /// The adhesive part `r_adh = −(k_n u_n, k_t u_t)` of the reaction at jump `u` (seed 4.31),
    /// from [`ContactLaw::adhesive_stiffness`]; the bipotential acts on `r̄ = r − r_adh`
    /// (seed 4.30).
    #[inline]
    fn adhesive_reaction<const DT: usize>(
        &self,
        u: &LocalVec<DT>,
        state: &Self::State,
    ) -> LocalVec<DT> {
        let [k_n, k_t] = self.adhesive_stiffness(state);
        LocalVec {
            n: -k_n * u.n,
            t: u.t * (-k_t),
        }
    }

    /// The adhesion intensity `β ∈ [0, 1]` of `state`, for reporting (`0` for laws without
    /// adhesion, the default).
    #[inline]
    fn adhesion_intensity(&self, _state: &Self::State) -> f64 {
        0.0
    }

    /// Whether [`project`](Self::project) and [`modified_velocity`](Self::modified_velocity)
    /// are positively homogeneous of degree 1 in their vector argument, in every state
    /// (`project(s τ) = s project(τ)` for `s > 0`): true for cones (Signorini, Coulomb, the
    /// RCCM law's `K_μ̄`), false for a law with a threshold of its own (Tresca). A
    /// reduced-problem solver may then rescale `W` and `q` by powers of two, exactly, to keep
    /// extreme magnitudes (1e-300 … 1e300) within range. Defaults to `false`.
    #[inline]
    fn is_scale_invariant(&self) -> bool {
        false
    }

    /// The friction coefficient `μ̄` of the law's cone in `state`, for Coulomb-type laws (a
    /// closed cone `‖r̄_t‖ ≤ μ̄ r̄_n`); `None` for laws that are not of this type. The classical
    /// RCCM solver (`contact_solver::Algorithm::ClassicRccm`) needs it; the bipotential
    /// solver does not.
    #[inline]
    fn friction_coefficient(&self, _state: &Self::State) -> Option<f64> {
        None
    }

    /// The contact bipotential `b_c(−u̇, r̄)` (seed 4.28, 4.63), `f64::INFINITY` where an
    /// indicator is active. For diagnostics and tests; the solver's loop never needs it.
    fn bipotential<const DT: usize>(
        &self,
        du: &LocalVec<DT>,
        r_bar: &LocalVec<DT>,
        state: &Self::State,
    ) -> f64;

    /// The Fenchel gap `b_c(−u̇, r̄) + u̇·r̄ ≥ 0` (seed 4.8): zero exactly on pairs that obey
    /// the law, `f64::INFINITY` where `b_c` is (never `∞ − ∞`).
    #[inline]
    fn fenchel_gap<const DT: usize>(
        &self,
        du: &LocalVec<DT>,
        r_bar: &LocalVec<DT>,
        state: &Self::State,
    ) -> f64 {
        let b = self.bipotential(du, r_bar, state);
        if b.is_infinite() {
            b
        } else {
            b + du.dot(r_bar)
        }
    }

    /// The internal-variable update at the end of an adhesion iteration: the state at the
    /// end of a step of length `dt ≥ 0`, from the state `start` and jump `u_start` at its
    /// start and the current jump `u` (seed 5.44–5.48). Defaults to `*start` (no state).
    #[inline]
    fn update_state<const DT: usize>(
        &self,
        start: &Self::State,
        _u_start: &LocalVec<DT>,
        _u: &LocalVec<DT>,
        _dt: f64,
    ) -> Self::State {
        *start
    }

    /// A non-negative distance between two states, for the adhesion fixed point's stopping
    /// test (for RCCM `|β_a − β_b|`). Defaults to `0`.
    #[inline]
    fn state_change(&self, _a: &Self::State, _b: &Self::State) -> f64 {
        0.0
    }
}
