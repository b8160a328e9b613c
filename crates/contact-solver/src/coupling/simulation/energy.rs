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
//! For `θ = 1/2` without damping or contact `T + V` changes only by the work of the loads;
//! `−W_c ≥ 0` is what the contacts dissipate (impact and friction: with `e = 0` and
//! `θ = 1/2` a closed contact has `v_n = 0`, so `r_n v_n,θ = ½ r_n v_n,k ≤ 0` at an impact).

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
    /// The work of the contact impulses `Σ v_θ·Hᵀ r` (`≤ 0`: impact and friction dissipate).
    pub contact_work: f64,
    /// The energy the Rayleigh damping dissipated, `Σ h v_θᵀ C v_θ`.
    pub damping: f64,
    /// The energy the scheme dissipated, `Σ (θ − ½)(ΔvᵀMΔv + ΔuᵀKΔu)` (0 for `θ = 1/2`).
    pub numerical: f64,
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

    /// `T + V − (T + V)₀ − W_ext − W_c + D_C + D_θ`: zero but for round-off.
    pub fn residual(&self) -> f64 {
        self.mechanical() - self.initial - self.external_work - self.contact_work
            + self.damping
            + self.numerical
    }

    /// The scale the residual compares with: the largest term of the balance.
    pub fn scale(&self) -> f64 {
        [
            self.initial,
            self.kinetic,
            self.strain,
            self.external_work,
            self.contact_work,
            self.damping,
            self.numerical,
        ]
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()))
    }

    /// The balance at the start: `T₀ + V₀` from `u_0` and `v_0`.
    pub(super) fn initial<const D: usize>(s: &DynamicModel<D>, u: &[f64], v: &[f64]) -> Self
    where
        Dim<D>: ModelSpace<D>,
    {
        let (t, k) = (
            quadratic(u.len(), v, |x, y| s.mass_mul_into(x, y)),
            quadratic(u.len(), u, |x, y| s.stiffness_mul_into(x, y)),
        );
        Self {
            initial: t + k,
            kinetic: t,
            strain: k,
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
        self.numerical += numerical;
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
