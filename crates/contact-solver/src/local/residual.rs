//! The toolbox every algorithm shares: per-contact access to flat vectors, norms, the base
//! penalty of a diagonal block, the natural-map residual and the contact statuses.
//!
//! ```text
//! residual(r, x) = ‖r − P_K(r + ρ⁰ v(x))‖        (zero exactly on solutions, seed 5.26)
//! ρ⁰_i = 1/λ_max(W_ii)                           (the largest non-expansive local step)
//! ```

use contact_laws::{ContactLaw, ContactStatus, LocalVec2};

/// Relative size of `‖P(τ) − τ‖/‖τ‖` under which a compressed contact is reported as stick.
pub(crate) const STATUS_TOL: f64 = 1e-8;

#[inline]
pub(crate) fn pick<T>(s: &[T], i: usize) -> &T {
    if s.len() == 1 { &s[0] } else { &s[i] }
}

#[inline]
pub(crate) fn local(v: &[f64], i: usize) -> LocalVec2 {
    LocalVec2::planar(v[2 * i], v[2 * i + 1])
}

#[inline]
pub(crate) fn set_local(v: &mut [f64], i: usize, a: &LocalVec2) {
    v[2 * i] = a.n;
    v[2 * i + 1] = a.t[0];
}

pub(crate) fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// `1/λ_max` of the SPD block `[a b; b d]`.
pub(crate) fn rho_of_block([a, b, _, d]: [f64; 4]) -> f64 {
    let h = 0.5 * (a - d);
    1.0 / (0.5 * (a + d) + (h * h + b * b).sqrt())
}

/// The status of each contact at `(r, x)`, from the projection `P(r + ρ v(x))`: separation
/// when it is zero, stick when it leaves `τ` unchanged (to [`STATUS_TOL`]), slip otherwise.
/// `laws` and `states` may hold one entry for every contact.
pub(crate) fn contact_statuses<L: ContactLaw>(
    laws: &[L],
    states: &[L::State],
    rho: &[f64],
    r: &[f64],
    x: &[f64],
) -> Vec<ContactStatus> {
    (0..rho.len())
        .map(|i| {
            let (law, s) = (pick(laws, i), pick(states, i));
            let tau = local(r, i) + law.modified_velocity(&local(x, i), s) * rho[i];
            let p = law.project(&tau, s);
            if p.n == 0.0 && p.t[0] == 0.0 {
                ContactStatus::Separation
            } else if (p - tau).norm() <= STATUS_TOL * tau.norm() {
                ContactStatus::Stick
            } else {
                ContactStatus::Slip
            }
        })
        .collect()
}

/// `‖r − P(r + ρ⁰ v(x))‖` (absolute), the natural map of the fixed point with the base `ρ⁰`.
pub(crate) fn natural_residual<L: ContactLaw>(
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    r: &[f64],
    x: &[f64],
) -> f64 {
    let mut s2 = 0.0;
    for (i, &rho0) in rho0.iter().enumerate() {
        let (law, s) = (pick(laws, i), pick(states, i));
        let ri = local(r, i);
        let tau = ri + law.modified_velocity(&local(x, i), s) * rho0;
        let d = law.project(&tau, s) - ri;
        s2 += d.dot(&d);
    }
    s2.sqrt()
}

/// The friction coefficients `μ̄_i` of the laws in their states, if every law has one and it is
/// finite and `≥ 0` (Coulomb-type laws); `None` otherwise.
pub(crate) fn friction_coefficients<L: ContactLaw>(
    laws: &[L],
    states: &[L::State],
    nc: usize,
) -> Option<Vec<f64>> {
    (0..nc)
        .map(|i| {
            pick(laws, i)
                .friction_coefficient(pick(states, i))
                .filter(|m| m.is_finite() && *m >= 0.0)
        })
        .collect()
}

/// The Signorini–Coulomb conditions checked without De Saxcé's modified velocity:
/// `‖(r_n − max(0, r_n − ρ⁰ x_n), r_t − clamp(r_t − ρ⁰ x_t, ±μ̄ r_n⁺))‖` (absolute). Zero
/// exactly at a solution, like the natural residual, but the normal test sees `x_n` itself:
/// with a huge `μ̄` the modified velocity's `x_n + μ̄|x_t|` can absorb a penetration.
pub(crate) fn coulomb_residual(mu: &[f64], rho0: &[f64], r: &[f64], x: &[f64]) -> f64 {
    let mut s2 = 0.0;
    for (i, (&mu, &rho)) in mu.iter().zip(rho0).enumerate() {
        let (ri, xi) = (local(r, i), local(x, i));
        let dn = ri.n - (ri.n - rho * xi.n).max(0.0);
        let g = mu * ri.n.max(0.0);
        let dt = ri.t[0] - (ri.t[0] - rho * xi.t[0]).clamp(-g, g);
        s2 += dn * dn + dt * dt;
    }
    s2.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rho_of_block_works() {
        // λ_max of [2 0; 0 1] is 2; of [1 1; 1 1] is 2.
        assert_eq!(rho_of_block([2.0, 0.0, 0.0, 1.0]), 0.5);
        assert!((rho_of_block([1.0, 1.0, 1.0, 1.0]) - 0.5).abs() < 1e-15);
    }
}
