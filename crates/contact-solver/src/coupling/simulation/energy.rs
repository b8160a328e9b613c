//! [`EnergyBalance`]: the energy bookkeeping of a [`MoreauJean`](super::MoreauJean) run,
//! step by step.
//!
//! Dotting the step's equation (`moreau_jean.rs`) with `v_θ = (1−θ) v_k + θ v` (so that
//! `h v_θ = u − u_k`) gives, exactly (Acary & Brogliato 2008 §10.1; Acary 2016):
//!
//! ```text
//! ΔT + ΔV = W_ext + W_c − D_C − D_θ
//! T = ½ vᵀ M v,   V = ½ uᵀ K u,
//! W_ext = (u − u_k)·f_θ,   W_c = v_θ·Hᵀ r = v_θ·M̂ (v − v_free),
//! D_C = h v_θᵀ C v_θ,       D_θ = (θ − ½) (ΔvᵀMΔv + ΔuᵀKΔu) ≥ 0
//! ```
//! For `θ = 1/2` without damping or contact `T + V` changes only by the work of the loads.
//!
//! # The contacts' share, contact by contact
//! `W_c = Σ r·(H v_θ)` over the contacts, and `h H v_θ = Δu` is the step's jump increment, so
//! with the impulse `r = r̄ + r_adh` split into the law's part and the adhesive springs'
//! (`r_adh = −h A k(β_k) u_θ`, `velocity_adhesion.rs`):
//!
//! ```text
//! D_impact   = −Σ r̄_n Δu_n / h          (normal: Newton's impact law; 0 for e = 1, θ = ½)
//! D_friction = −Σ r̄_t·Δu_t / h          (tangential: Coulomb's cone, ≥ 0)
//! Σ r_adh·Δu / h = −(ΔE_adh + D_damage + D_θ,adh)
//! E_adh    = ½ Σ A (k_n u_n² + k_t |u_t|²)                 (the springs' stored energy)
//! D_damage = ½ Σ A ((k_n,k − k_n,k+1) u_n² + (k_t,k − k_t,k+1) |u_t|²)   (at the end jump u)
//! D_θ,adh  = (θ − ½) Σ A (k_n,k Δu_n² + k_t,k |Δu_t|²)
//! (with the states iterated within the step, AdhesionUpdate::Implicit, the springs are
//!  k_{k+1}: D_damage is taken at the start jump u_k and D_θ,adh with k_{k+1})
//! ⇒  ΔT + ΔV + ΔE_adh = W_ext − D_impact − D_friction − D_damage − D_C − D_θ − D_θ,adh
//! ```
//! The damage term is the energy the springs release at fixed jump when `β` drops: for the
//! RCCM law (`k = β² C`, `β = w/(C u²)` past the critical jump) it sums to `w` per unit area
//! over a full debonding, the law's fracture energy. [`EnergyBalance::residual`] closes this
//! balance; the global `W_c` is kept beside it ([`EnergyBalance::contact_work`]) as a check of
//! the split.

use fem_core::Dim;
use fem_core::dynamic::DynamicModel;
use fem_core::model::ModelSpace;

/// The energies and works of a dynamic run since its start (units of force × length), at the
/// end of a step; [`residual`](Self::residual) is what the balance leaves (round-off).
///
/// # Examples
/// ```
/// use contact_solver::coupling::simulation::EnergyBalance;
/// let e = EnergyBalance::default();
/// assert_eq!(e.residual(), 0.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct EnergyBalance {
    /// `T + V` at the start (initial velocity and displacement).
    pub initial: f64,
    /// The kinetic energy `½ vᵀ M v` now.
    pub kinetic: f64,
    /// The strain energy `½ uᵀ K u` now.
    pub strain: f64,
    /// The work of the loads `Σ (u − u_k)·f_θ`.
    pub external_work: f64,
    /// The work of the contact impulses `Σ v_θ·Hᵀ r` (`≤ 0`: impact and friction dissipate),
    /// from the global fields; equal (to round-off) to
    /// `−impact − friction − (interface − interface₀) − damage − D_θ,adh` (module docs).
    pub contact_work: f64,
    /// The energy the normal impulses dissipated, `−Σ r̄_n Δu_n / h` (impact).
    pub impact: f64,
    /// The energy the tangential impulses dissipated, `−Σ r̄_t·Δu_t / h` (friction).
    pub friction: f64,
    /// The energy the adhesive springs released as `β` dropped (damage).
    pub damage: f64,
    /// The energy stored in the adhesive springs now, `½ Σ A (k_n u_n² + k_t |u_t|²)`.
    pub interface: f64,
    /// The energy the Rayleigh damping dissipated, `Σ h v_θᵀ C v_θ`.
    pub damping: f64,
    /// The energy the scheme dissipated, `Σ (θ − ½)(ΔvᵀMΔv + ΔuᵀKΔu)` plus the adhesive
    /// springs' `D_θ,adh` (module docs; 0 for `θ = 1/2`).
    pub numerical: f64,
    /// `E_adh` at the start.
    interface_initial: f64,
    /// The adhesive springs' part `D_θ,adh` of `numerical`.
    adhesive_numerical: f64,
}

/// The contacts' terms of one step (module docs), summed over its contacts.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct ContactTerms {
    impact: f64,
    friction: f64,
    damage: f64,
    numerical: f64,
    /// `E_adh` at the start and at the end of the step.
    interface_start: f64,
    interface_end: f64,
}

impl ContactTerms {
    /// Adds a contact whose jump went from `start` to `end` under the impulses `r_bar` (the
    /// law's) in a step `h` at weight `theta`, with nodal springs `springs_start` (state at
    /// the start) and `springs_end`; the step's springs were the end state's if `implicit`
    /// (the damage is then counted at the start jump), the start state's otherwise (at the
    /// end jump).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn add<const D: usize>(
        &mut self,
        r_bar: &[f64; D],
        start: &[f64; D],
        end: &[f64; D],
        springs_start: [f64; 2],
        springs_end: [f64; 2],
        implicit: bool,
        h: f64,
        theta: f64,
    ) {
        let k = |s: [f64; 2], d: usize| if d == 0 { s[0] } else { s[1] };
        for d in 0..D {
            let du = end[d] - start[d];
            let work = -r_bar[d] * du / h;
            if d == 0 {
                self.impact += work;
            } else {
                self.friction += work;
            }
            let (k0, k1) = (k(springs_start, d), k(springs_end, d));
            let (at, used) = if implicit {
                (start[d], k1)
            } else {
                (end[d], k0)
            };
            self.damage += 0.5 * (k0 - k1) * at * at;
            self.numerical += (theta - 0.5) * used * du * du;
            self.interface_start += 0.5 * k0 * start[d] * start[d];
            self.interface_end += 0.5 * k1 * end[d] * end[d];
        }
    }
}

/// What one accepted step adds: its fields on the free dofs.
pub(super) struct StepFields<'a> {
    pub(super) h: f64,
    pub(super) theta: f64,
    pub(super) u_k: &'a [f64],
    pub(super) u: &'a [f64],
    pub(super) v_k: &'a [f64],
    pub(super) v: &'a [f64],
    pub(super) v_free: &'a [f64],
    pub(super) load: &'a [f64],
    pub(super) contacts: ContactTerms,
}

impl EnergyBalance {
    /// The mechanical energy `T + V` now.
    pub fn mechanical(&self) -> f64 {
        self.kinetic + self.strain
    }

    /// What the contacts dissipated, `−W_c`.
    pub fn contact_dissipation(&self) -> f64 {
        -self.contact_work
    }

    /// The energy the contacts dissipated by impact, friction and damage.
    pub fn contact_dissipated(&self) -> f64 {
        self.impact + self.friction + self.damage
    }

    /// `T + V + E_adh − (T + V + E_adh)₀ − W_ext + D_impact + D_friction + D_damage + D_C +
    /// D_θ`: zero but for round-off (module docs).
    pub fn residual(&self) -> f64 {
        self.mechanical() + self.interface - self.initial - self.external_work
            + self.impact
            + self.friction
            + self.damage
            + self.damping
            + self.numerical
    }

    /// `W_c + D_impact + D_friction + D_damage + ΔE_adh + D_θ,adh`: how far the global work of
    /// the contact impulses is from the contacts' split, zero but for round-off.
    pub fn split_residual(&self) -> f64 {
        self.contact_work
            + self.impact
            + self.friction
            + self.damage
            + (self.interface - self.interface_initial)
            + self.adhesive_numerical
    }

    /// The scale the residual compares with: the largest term of the balance.
    pub fn scale(&self) -> f64 {
        [
            self.initial,
            self.kinetic,
            self.strain,
            self.external_work,
            self.contact_work,
            self.impact,
            self.friction,
            self.damage,
            self.interface,
            self.damping,
            self.numerical,
        ]
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()))
    }

    /// The balance at the start: `T₀ + V₀` from `u_0` and `v_0`, and the adhesive springs'
    /// `E_adh` at the start of the first step (`contacts`).
    pub(super) fn initial<const D: usize>(
        s: &DynamicModel<D>,
        u: &[f64],
        v: &[f64],
        contacts: &ContactTerms,
    ) -> Self
    where
        Dim<D>: ModelSpace<D>,
    {
        let (t, k) = (
            quadratic(u.len(), v, |x, y| s.mass_mul_into(x, y)),
            quadratic(u.len(), u, |x, y| s.stiffness_mul_into(x, y)),
        );
        let e = contacts.interface_start;
        Self {
            initial: t + k + e,
            kinetic: t,
            strain: k,
            interface: e,
            interface_initial: e,
            ..Self::default()
        }
    }

    /// Adds an accepted step.
    pub(super) fn add_step<const D: usize>(&mut self, s: &DynamicModel<D>, f: StepFields<'_>)
    where
        Dim<D>: ModelSpace<D>,
    {
        let n = f.v.len();
        let v_theta: Vec<f64> = f
            .v_k
            .iter()
            .zip(f.v)
            .map(|(a, b)| (1.0 - f.theta) * a + f.theta * b)
            .collect();
        let du: Vec<f64> = f.u.iter().zip(f.u_k).map(|(a, b)| a - b).collect();
        let dv: Vec<f64> = f.v.iter().zip(f.v_k).map(|(a, b)| a - b).collect();
        let mut buffer = vec![0.0; n];
        // W_c = v_θ·M̂ (v − v_free)
        let jump: Vec<f64> = f.v.iter().zip(f.v_free).map(|(a, b)| a - b).collect();
        let contact = match s.iteration_mul_into(&jump, &mut buffer) {
            Ok(()) => dot(&v_theta, &buffer),
            Err(_) => f64::NAN,
        };
        s.damping_mul_into(&v_theta, &mut buffer);
        let damping = f.h * dot(&v_theta, &buffer);
        let numerical = (f.theta - 0.5)
            * 2.0
            * (quadratic(n, &dv, |x, y| s.mass_mul_into(x, y))
                + quadratic(n, &du, |x, y| s.stiffness_mul_into(x, y)));
        self.kinetic = quadratic(n, f.v, |x, y| s.mass_mul_into(x, y));
        self.strain = quadratic(n, f.u, |x, y| s.stiffness_mul_into(x, y));
        self.external_work += dot(&du, f.load);
        self.contact_work += contact;
        self.damping += damping;
        let c = f.contacts;
        self.numerical += numerical + c.numerical;
        self.adhesive_numerical += c.numerical;
        self.impact += c.impact;
        self.friction += c.friction;
        self.damage += c.damage;
        self.interface += c.interface_end - c.interface_start;
    }
}

/// `½ xᵀ A x` through the product `mul`.
fn quadratic(n: usize, x: &[f64], mul: impl Fn(&[f64], &mut [f64])) -> f64 {
    let mut y = vec![0.0; n];
    mul(x, &mut y);
    0.5 * dot(x, &y)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
