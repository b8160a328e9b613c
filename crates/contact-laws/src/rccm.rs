//! The RCCM adhesive law (Raous–Cangémi–Cocou–Monerie) written with bipotentials.
//!
//! ```text
//! adhesion intensity       β ∈ [0, 1]   (1 = sound interface, 0 = fully debonded)
//! adhesive reaction        r_adh = −β² (C_n u_n, C_t u_t)                 (seed 4.31, sign: see below)
//! auxiliary reaction       r̄ = r − r_adh                                  (seed 4.30)
//! effective friction       μ̄ = μ f(β),  f(β) = 1 − β^m,  m ∈ {1, 2}       (seed 4.32–4.33)
//! r̄ obeys Signorini + Coulomb on K_μ̄, through b_c(−u̇, r̄)                 (seed 4.34, 4.63)
//! thermodynamic force      G_β = w − (C_n u_n² + C_t ‖u_t‖²) β              (seed 4.51)
//! evolution                α β̇ = −[G_β]⁻,  [x]⁻ = max(−x, 0)                (seed 3.25, 4.86)
//! adhesion bipotential     b_β(β̇, G) = α β̇²/2 + I_C⁻(β̇) + ([G]⁻)²/(2α)     (seed 4.79)
//! full bipotential         b = b_c(−u̇, r̄) + b_β(β̇, G_β)                   (seed 4.52, 4.81)
//! ```
//!
//! The seed writes `r_adh = +β²(C_n u_n, C_t u_t)` with the convention `u_n ≤ 0` for an
//! opening (3.26). This crate uses `u_n ≥ 0` for an opening and `r_n ≥ 0` for compression
//! (see the [crate conventions](crate#sign-conventions)), so the adhesive reaction, which
//! resists opening and slip, carries a minus sign: an opened, glued interface is in tension.
//!
//! Units (any consistent system): `C_n, C_t` stress per length (e.g. MPa/mm), `w` energy per
//! area (e.g. mJ/mm² = N/mm), `α` (N·s/mm in the seed: `α β̇` has the units of `w`), `μ`
//! dimensionless, `β` dimensionless.

use crate::cone::CoulombCone;
use crate::de_saxce::{contact_bipotential, modified_velocity};
use crate::error::{LawError, non_negative, unit_interval};
use crate::law::ContactLaw;
use crate::local::LocalVec;

/// Time integration of the adhesion evolution `α β̇ = −[G_β]⁻` over a step `Δt`.
///
/// Whatever the scheme, `α = 0` uses the rate-independent limit
/// `β = min(β_prev, w / (C_n u_n² + C_t ‖u_t‖²))` (the pile study of the seed, table 6.3).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum BetaScheme {
    /// Implicit (backward) Euler, seed 5.47–5.48, solved in closed form (no fixed point).
    ImplicitEuler,
    /// The θ-method of seed 5.44–5.45: `θ = 1` is implicit Euler, `θ = 0` explicit Euler,
    /// `θ = 1/2` Crank–Nicolson. Its explicit part uses the jumps at the start of the step.
    Theta(f64),
}

/// Parameters of the RCCM interface (seed 3.26–3.28, table 6.3), validated by [`Rccm::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RccmParams {
    /// Normal interface stiffness `C_n ≥ 0` (stress per length).
    pub c_n: f64,
    /// Tangential interface stiffness `C_t ≥ 0` (stress per length).
    pub c_t: f64,
    /// Dupré's energy `w ≥ 0` (energy per area): the work needed to debond a unit area.
    pub w: f64,
    /// Viscosity of the adhesion `α ≥ 0`; `0` gives the rate-independent law.
    pub alpha: f64,
    /// Coulomb friction coefficient `μ ≥ 0` of the debonded interface.
    pub mu: f64,
    /// Exponent `m ∈ {1, 2}` of `f(β) = 1 − β^m` (seed 4.33); the pile study uses `m = 1`.
    pub m: u32,
    /// Initial adhesion intensity `β₀ ∈ [0, 1]`: `1` for a sound interface, `0` for plain
    /// Coulomb friction (fig. 6.5 of the seed).
    pub beta_0: f64,
    /// Time integration of `β`.
    pub scheme: BetaScheme,
}

/// The RCCM adhesive contact law with validated parameters; see the [module docs](self).
///
/// # Examples
/// ```
/// use contact_laws::{BetaScheme, ContactLaw, LocalVec2, Rccm, RccmParams};
/// let law = Rccm::new(RccmParams {
///     c_n: 2e5, c_t: 2e5, w: 1e-6, alpha: 1.0, mu: 0.2, m: 1, beta_0: 1.0,
///     scheme: BetaScheme::ImplicitEuler,
/// })?;
/// let state = law.initial_state();
/// // A glued interface opened by 1 µm pulls back: r_adh,n = −β² C_n u_n = −0.2.
/// let r_adh = law.adhesive_reaction(&LocalVec2::planar(1e-6, 0.0), &state);
/// assert!((r_adh.n + 0.2).abs() < 1e-12);
/// # Ok::<(), contact_laws::LawError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rccm {
    c_n: f64,
    c_t: f64,
    w: f64,
    alpha: f64,
    cone: CoulombCone,
    m: u32,
    beta_0: f64,
    scheme: BetaScheme,
}

/// Per-contact state of the RCCM law: the adhesion intensity `β ∈ [0, 1]`.
///
/// `Default` is the sound interface `β = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RccmState {
    beta: f64,
}

impl RccmState {
    /// The fully damaged interface `β = 0` (no adhesion).
    pub const ZERO: Self = Self { beta: 0.0 };

    /// Builds a state with adhesion intensity `beta`.
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] if `beta` is not in `[0, 1]` (or is NaN).
    pub fn new(beta: f64) -> Result<Self, LawError> {
        Ok(Self {
            beta: unit_interval("beta", beta)?,
        })
    }

    /// The adhesion intensity `β ∈ [0, 1]`.
    #[inline]
    pub fn beta(&self) -> f64 {
        self.beta
    }
}

impl Default for RccmState {
    fn default() -> Self {
        Self { beta: 1.0 }
    }
}

impl Rccm {
    /// Validates the parameters and builds the law.
    ///
    /// # Errors
    /// - [`LawError::InvalidParameter`] if `c_n`, `c_t`, `w`, `alpha` or `mu` is negative,
    ///   NaN or infinite, if `beta_0 ∉ [0, 1]`, or if a θ-scheme has `θ ∉ [0, 1]`;
    /// - [`LawError::InvalidExponent`] if `m ∉ {1, 2}`.
    pub fn new(p: RccmParams) -> Result<Self, LawError> {
        let c_n = non_negative("c_n", p.c_n)?;
        let c_t = non_negative("c_t", p.c_t)?;
        let w = non_negative("w", p.w)?;
        let alpha = non_negative("alpha", p.alpha)?;
        let cone = CoulombCone::new(p.mu)?;
        if p.m != 1 && p.m != 2 {
            return Err(LawError::InvalidExponent { m: p.m });
        }
        let beta_0 = unit_interval("beta_0", p.beta_0)?;
        if let BetaScheme::Theta(theta) = p.scheme {
            unit_interval("theta", theta)?;
        }
        Ok(Self {
            c_n,
            c_t,
            w,
            alpha,
            cone,
            m: p.m,
            beta_0,
            scheme: p.scheme,
        })
    }

    /// The validated parameters.
    pub fn params(&self) -> RccmParams {
        RccmParams {
            c_n: self.c_n,
            c_t: self.c_t,
            w: self.w,
            alpha: self.alpha,
            mu: self.cone.mu(),
            m: self.m,
            beta_0: self.beta_0,
            scheme: self.scheme,
        }
    }

    /// `f(β) = 1 − β^m` (seed 4.33), in `[0, 1]`.
    #[inline]
    pub fn friction_factor(&self, beta: f64) -> f64 {
        if self.m == 1 {
            1.0 - beta
        } else {
            1.0 - beta * beta
        }
    }

    /// The cone `K_μ̄` of the effective friction `μ̄ = μ f(β)` (seed 4.32–4.34).
    #[inline]
    pub fn cone(&self, state: &RccmState) -> CoulombCone {
        self.cone.scaled(self.friction_factor(state.beta))
    }

    /// `C_n u_n² + C_t ‖u_t‖²`: twice the energy per area stored in the undamaged interface
    /// springs at jump `u`; the energy release rate of the adhesion is `−G_β + w`.
    #[inline]
    pub fn jump_energy<const DT: usize>(&self, u: &LocalVec<DT>) -> f64 {
        self.c_n * u.n * u.n + self.c_t * u.t.norm_squared()
    }

    /// The thermodynamic force `G_β = w − (C_n u_n² + C_t ‖u_t‖²) β` (seed 4.51), energy per
    /// area. Damage progresses (`β̇ < 0`) only where `G_β < 0`.
    #[inline]
    pub fn g_beta<const DT: usize>(&self, u: &LocalVec<DT>, beta: f64) -> f64 {
        self.w - self.jump_energy(u) * beta
    }

    /// The adhesion bipotential `b_β(β̇, G) = α β̇²/2 + I_C⁻(β̇) + ([G]⁻)²/(2α)` (seed 4.79),
    /// with `C⁻ = {β̇ ≤ 0}` and `[G]⁻ = max(−G, 0)`.
    ///
    /// For `α = 0` it is the limit `I_C⁻(β̇) + I_ℝ⁺(G)`: `β̇ ≤ 0`, `G ≥ 0`, `β̇ G = 0` on
    /// extremal pairs. Returns `f64::INFINITY` where an indicator is active.
    #[inline]
    pub fn adhesion_bipotential(&self, beta_dot: f64, g: f64) -> f64 {
        adhesion_bipotential(self.alpha, beta_dot, g)
    }

    /// The full bipotential `b(−u̇, β̇, r̄, G_β) = b_c(−u̇, r̄) + b_β(β̇, G_β)` (seed 4.81), with
    /// `G_β` evaluated at the jump `u` and the state's `β`.
    ///
    /// Fenchel: `b ≥ −u̇·r̄ + β̇ G_β` (see [`Rccm::fenchel_gap_full`]).
    #[inline]
    pub fn bipotential_full<const DT: usize>(
        &self,
        du: &LocalVec<DT>,
        beta_dot: f64,
        r_bar: &LocalVec<DT>,
        u: &LocalVec<DT>,
        state: &RccmState,
    ) -> f64 {
        let b_c = contact_bipotential(&self.cone(state), du, r_bar);
        if b_c.is_infinite() {
            return b_c;
        }
        b_c + self.adhesion_bipotential(beta_dot, self.g_beta(u, state.beta))
    }

    /// The Fenchel gap of the full bipotential, `b − (−u̇·r̄ + β̇ G_β) ≥ 0`; `0` on pairs that
    /// obey the law, `f64::INFINITY` where `b` is infinite, never NaN for finite arguments.
    #[inline]
    pub fn fenchel_gap_full<const DT: usize>(
        &self,
        du: &LocalVec<DT>,
        beta_dot: f64,
        r_bar: &LocalVec<DT>,
        u: &LocalVec<DT>,
        state: &RccmState,
    ) -> f64 {
        let b = self.bipotential_full(du, beta_dot, r_bar, u, state);
        if b.is_infinite() {
            return b;
        }
        b + du.dot(r_bar) - beta_dot * self.g_beta(u, state.beta)
    }

    /// The adhesion intensity at the end of a step of length `dt`, from `beta_start` at its
    /// start, the jumps `u_start` at its start and `u` at its end (the current iterate of the
    /// adhesion fixed point, seed 5.44–5.48), with the law's [`BetaScheme`]. `α = 0` uses
    /// the rate-independent update. The result lies in `[0, beta_start]`.
    ///
    /// # Panics
    /// Debug builds panic if `dt` is negative or not finite (a caller invariant: the solver
    /// validates its time steps).
    #[inline]
    #[track_caller]
    pub fn update_beta<const DT: usize>(
        &self,
        beta_start: f64,
        u_start: &LocalVec<DT>,
        u: &LocalVec<DT>,
        dt: f64,
    ) -> f64 {
        debug_assert!(
            dt.is_finite() && dt >= 0.0,
            "time step dt = {dt} must be finite and >= 0"
        );
        let energy = self.jump_energy(u);
        if self.alpha == 0.0 {
            return beta_rate_independent(beta_start, energy, self.w);
        }
        match self.scheme {
            BetaScheme::ImplicitEuler => {
                beta_implicit_euler(beta_start, energy, self.w, self.alpha, dt)
            }
            BetaScheme::Theta(theta) => beta_theta(
                beta_start,
                self.jump_energy(u_start),
                energy,
                self.w,
                self.alpha,
                dt,
                theta,
            ),
        }
    }
}

/// `b_β(β̇, G)` of seed 4.79 for viscosity `alpha ≥ 0`; see [`Rccm::adhesion_bipotential`].
#[inline]
pub fn adhesion_bipotential(alpha: f64, beta_dot: f64, g: f64) -> f64 {
    if beta_dot > 0.0 {
        return f64::INFINITY; // I_C⁻(β̇)
    }
    let g_minus = (-g).max(0.0);
    if alpha == 0.0 {
        // Limit α → 0: ([G]⁻)²/(2α) → I_ℝ⁺(G), α β̇²/2 → 0.
        return if g_minus > 0.0 { f64::INFINITY } else { 0.0 };
    }
    0.5 * alpha * beta_dot * beta_dot + g_minus * g_minus / (2.0 * alpha)
}

/// Rate-independent adhesion update (`α = 0`): `β = min(β_prev, w / E)` with
/// `E = C_n u_n² + C_t ‖u_t‖² ≥ 0`, in `[0, β_prev]`.
///
/// `w / E` is the largest `β` with `G_β ≥ 0`; β never increases.
#[inline]
pub fn beta_rate_independent(beta_prev: f64, energy: f64, w: f64) -> f64 {
    if energy * beta_prev <= w {
        beta_prev
    } else {
        // Here E > 0 since E β_prev > w ≥ 0.
        (w / energy).min(beta_prev)
    }
}

/// Implicit-Euler adhesion update (seed 5.47–5.48) in closed form.
///
/// ```text
/// β = β_prev + (Δt/α) min(G_β(β), 0),   G_β(β) = w − E β
/// E β_prev ≤ w  →  β = β_prev                      (no damage: G ≥ 0)
/// otherwise     →  β = (α β_prev + Δt w) / (α + Δt E)   (then G(β) < 0, consistent)
/// ```
/// As `α → 0` this tends to [`beta_rate_independent`]. `alpha = 0` delegates to it.
#[inline]
pub fn beta_implicit_euler(beta_prev: f64, energy: f64, w: f64, alpha: f64, dt: f64) -> f64 {
    if energy * beta_prev <= w {
        return beta_prev;
    }
    if alpha == 0.0 {
        return beta_rate_independent(beta_prev, energy, w);
    }
    if dt == 0.0 {
        return beta_prev;
    }
    // A quotient of sums of non-negative terms: accurate to a few ulps even when
    // Δt E ≫ α (a decrement form would cancel); `min` keeps rounding from raising β.
    ((alpha * beta_prev + dt * w) / (alpha + dt * energy)).min(beta_prev)
}

/// θ-method adhesion update (seed 5.44–5.45) in closed form.
///
/// ```text
/// y(β, E) = min(w − E β, 0) / α
/// β = β_prev + Δt [θ y(β, E) + (1 − θ) y(β_prev, E_prev)]
/// ```
/// with `E_prev`, `E` the jump energies at the start and end of the step. The map
/// `β ↦ β − θΔt y(β, E)` is increasing, so the equation has one root, found in two cases;
/// the result is clamped to `[0, β_prev]` (the explicit part can overshoot when
/// `Δt E_prev > α`). `theta = 1` is [`beta_implicit_euler`]. `alpha = 0` delegates to
/// [`beta_rate_independent`]; note that for `θ < 1` the `α → 0` limit is not that update
/// (the explicit part blows up and β drops to 0): use `θ = 1` or `α = 0` for stiff cases.
#[inline]
pub fn beta_theta(
    beta_prev: f64,
    energy_prev: f64,
    energy: f64,
    w: f64,
    alpha: f64,
    dt: f64,
    theta: f64,
) -> f64 {
    if alpha == 0.0 {
        return beta_rate_independent(beta_prev, energy, w);
    }
    let explicit = (1.0 - theta) * dt * (w - energy_prev * beta_prev).min(0.0) / alpha;
    let c = beta_prev + explicit;
    let h = theta * dt;
    let beta = if energy * c <= w || h == 0.0 {
        c
    } else {
        // Here c > 0 (E c > w ≥ 0): a quotient of non-negative terms, as in implicit Euler.
        (alpha * c + h * w) / (alpha + h * energy)
    };
    beta.clamp(0.0, beta_prev)
}

impl ContactLaw for Rccm {
    type State = RccmState;

    #[inline]
    fn initial_state(&self) -> RccmState {
        RccmState { beta: self.beta_0 }
    }

    #[inline]
    fn has_friction(&self) -> bool {
        self.cone.mu() > 0.0
    }

    #[inline]
    fn has_adhesion(&self) -> bool {
        self.beta_0 > 0.0
    }

    #[inline]
    fn adhesion_active(&self, state: &RccmState) -> bool {
        state.beta > 0.0
    }

    #[inline]
    fn project<const DT: usize>(&self, tau: &LocalVec<DT>, state: &RccmState) -> LocalVec<DT> {
        self.cone(state).project(tau)
    }

    #[inline]
    fn modified_velocity<const DT: usize>(
        &self,
        du: &LocalVec<DT>,
        state: &RccmState,
    ) -> LocalVec<DT> {
        modified_velocity(&self.cone(state), du)
    }

    /// `k = β² (C_n, C_t)`: `r_adh = −β² (C_n u_n, C_t u_t)` (seed 4.31 with this crate's signs).
    #[inline]
    fn adhesive_stiffness(&self, state: &RccmState) -> [f64; 2] {
        let b2 = state.beta * state.beta;
        [b2 * self.c_n, b2 * self.c_t]
    }

    #[inline]
    fn adhesion_intensity(&self, state: &RccmState) -> f64 {
        state.beta
    }

    #[inline]
    fn is_scale_invariant(&self) -> bool {
        true
    }

    #[inline]
    fn friction_coefficient(&self, state: &RccmState) -> Option<f64> {
        Some(self.cone(state).mu())
    }

    #[inline]
    fn bipotential<const DT: usize>(
        &self,
        du: &LocalVec<DT>,
        r_bar: &LocalVec<DT>,
        state: &RccmState,
    ) -> f64 {
        contact_bipotential(&self.cone(state), du, r_bar)
    }

    #[inline]
    fn update_state<const DT: usize>(
        &self,
        start: &RccmState,
        u_start: &LocalVec<DT>,
        u: &LocalVec<DT>,
        dt: f64,
    ) -> RccmState {
        RccmState {
            beta: self.update_beta(start.beta, u_start, u, dt),
        }
    }

    #[inline]
    fn state_change(&self, a: &RccmState, b: &RccmState) -> f64 {
        (a.beta - b.beta).abs()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::LocalVec2;
    use approx::assert_relative_eq;

    fn params() -> RccmParams {
        RccmParams {
            c_n: 2e5,
            c_t: 1e5,
            w: 1e-6,
            alpha: 1.0,
            mu: 0.2,
            m: 1,
            beta_0: 1.0,
            scheme: BetaScheme::ImplicitEuler,
        }
    }

    #[test]
    fn new_rejects_invalid_parameters() {
        type Edit = fn(&mut RccmParams);
        let cases: [(&str, Edit); 8] = [
            ("c_n", |p| p.c_n = -1.0),
            ("c_t", |p| p.c_t = f64::NAN),
            ("w", |p| p.w = -1e-9),
            ("alpha", |p| p.alpha = f64::INFINITY),
            ("mu", |p| p.mu = -0.2),
            ("beta_0", |p| p.beta_0 = 1.5),
            ("theta", |p| p.scheme = BetaScheme::Theta(-0.5)),
            ("theta", |p| p.scheme = BetaScheme::Theta(f64::NAN)),
        ];
        for (name, edit) in cases {
            let mut p = params();
            edit(&mut p);
            match Rccm::new(p) {
                Err(LawError::InvalidParameter { name: n, .. }) => assert_eq!(n, name),
                other => panic!("{name}: expected InvalidParameter, got {other:?}"),
            }
        }
        for m in [0, 3] {
            let p = RccmParams { m, ..params() };
            assert_eq!(Rccm::new(p), Err(LawError::InvalidExponent { m }));
        }
        assert!(RccmState::new(-0.1).is_err());
        assert!(RccmState::new(0.5).is_ok());
    }

    #[test]
    fn friction_factor_and_effective_cone_work() {
        let law = Rccm::new(params()).unwrap();
        assert_relative_eq!(law.friction_factor(0.25), 0.75);
        let law2 = Rccm::new(RccmParams { m: 2, ..params() }).unwrap();
        assert_relative_eq!(law2.friction_factor(0.5), 0.75);
        // β = 1: frictionless; β = 0: Coulomb with μ.
        assert_eq!(law.cone(&RccmState::new(1.0).unwrap()).mu(), 0.0);
        assert_eq!(law.cone(&RccmState::new(0.0).unwrap()).mu(), 0.2);
    }

    #[test]
    fn adhesive_reaction_resists_opening_and_slip() {
        let law = Rccm::new(params()).unwrap();
        let s = RccmState::new(0.5).unwrap();
        let r = law.adhesive_reaction(&LocalVec2::planar(2e-6, -1e-6), &s);
        assert_relative_eq!(r.n, -0.25 * 2e5 * 2e-6); // tension when opened
        assert_relative_eq!(r.t[0], 0.25 * 1e5 * 1e-6); // opposite to the slip
    }

    #[test]
    fn g_beta_works() {
        let law = Rccm::new(params()).unwrap();
        let u = LocalVec2::planar(1e-6, 2e-6);
        // w − (C_n u_n² + C_t u_t²) β = 1e-6 − (2e-7 + 4e-7)·0.5
        assert_relative_eq!(law.g_beta(&u, 0.5), 1e-6 - 3e-7, epsilon = 1e-20);
    }

    #[test]
    fn implicit_euler_solves_its_equation() {
        // β = β_p + (Δt/α) min(w − E β, 0) must hold for the returned β.
        for (bp, e, w, a, dt) in [
            (1.0, 3.0, 1.0, 2.0, 0.5),
            (0.7, 10.0, 0.1, 1e-3, 1.0),
            (0.2, 1.0, 0.5, 1.0, 1.0),
        ] {
            let b = beta_implicit_euler(bp, e, w, a, dt);
            // The residual is amplified by Δt E/α: scale the tolerance with the terms.
            let scale = bp + dt / a * (w + e * b);
            assert_relative_eq!(
                b,
                bp + dt / a * (w - e * b).min(0.0),
                epsilon = 1e-14 * scale
            );
            assert!((0.0..=bp).contains(&b));
        }
    }

    #[test]
    fn theta_one_is_implicit_euler_and_theta_zero_is_explicit() {
        let (bp, ep, e, w, a, dt) = (0.9, 2.0, 3.0, 1.0, 2.0, 0.5);
        assert_relative_eq!(
            beta_theta(bp, ep, e, w, a, dt, 1.0),
            beta_implicit_euler(bp, e, w, a, dt),
            epsilon = 1e-15
        );
        // Explicit: β = β_p + Δt min(w − E_p β_p, 0)/α = 0.9 + 0.25·(1 − 1.8) = 0.7.
        assert_relative_eq!(beta_theta(bp, ep, e, w, a, dt, 0.0), 0.7, epsilon = 1e-15);
        // Crank–Nicolson satisfies its own equation.
        let b = beta_theta(bp, ep, e, w, a, dt, 0.5);
        let rhs = bp + dt * (0.5 * (w - e * b).min(0.0) + 0.5 * (w - ep * bp).min(0.0)) / a;
        assert_relative_eq!(b, rhs, epsilon = 1e-14);
    }

    #[test]
    fn implicit_euler_tends_to_rate_independent_as_alpha_vanishes() {
        let (bp, e, w, dt) = (1.0, 4.0, 1.0, 0.1);
        let limit = beta_rate_independent(bp, e, w);
        assert_relative_eq!(limit, 0.25);
        let mut prev_err = f64::INFINITY;
        for k in 1..=12 {
            let alpha = 10f64.powi(-k);
            let err = (beta_implicit_euler(bp, e, w, alpha, dt) - limit).abs();
            assert!(err < prev_err, "error must decrease as α → 0");
            // |β_α − β_0| = α (β_p − w/E) / (α + Δt E) ≤ α β_p / (Δt E)
            assert!(err <= alpha * bp / (dt * e) * (1.0 + 1e-12));
            prev_err = err;
        }
        assert!(prev_err < 1e-11);
        // And α = 0 itself is the rate-independent update, through the law too.
        let law = Rccm::new(RccmParams {
            alpha: 0.0,
            w,
            c_n: e,
            ..params()
        })
        .unwrap();
        let u = LocalVec2::planar(1.0, 0.0);
        assert_eq!(law.update_beta(bp, &u, &u, dt), limit);
    }

    #[test]
    fn adhesion_bipotential_works() {
        // Damaging pair: G < 0, β̇ = G/α → b_β = G²/α = β̇ G.
        assert_relative_eq!(adhesion_bipotential(2.0, -1.5, -3.0), 4.5);
        // Frozen: G ≥ 0, β̇ = 0 → 0.
        assert_eq!(adhesion_bipotential(2.0, 0.0, 3.0), 0.0);
        // β̇ > 0 is forbidden.
        assert_eq!(adhesion_bipotential(2.0, 1e-9, 3.0), f64::INFINITY);
        // α = 0: indicator of G ≥ 0.
        assert_eq!(adhesion_bipotential(0.0, -1.0, 0.0), 0.0);
        assert_eq!(adhesion_bipotential(0.0, -1.0, -1e-12), f64::INFINITY);
    }
}
