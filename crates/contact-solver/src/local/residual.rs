//! The toolbox every algorithm shares: per-contact access to flat vectors, norms, the base
//! penalty of a diagonal block, the natural-map residual and the contact statuses.
//!
//! ```text
//! residual(r, x) = ‖r − P_K(r + ρ⁰ v(x))‖        (zero exactly on solutions, seed 5.26)
//! ρ⁰_i = 1/λ_max(W_ii)                           (the largest non-expansive local step)
//! ```
//! Every per-contact helper is generic over the tangent dimension `DT` (1 in 2D, 2 in 3D):
//! contact `i`'s unknowns are `v[(DT+1) i ..][..DT+1]`, the normal first.
//!
//! The residual beside Siconos' error: [`siconos_error`].

use super::problem::ReducedProblem;
use contact_laws::{ContactLaw, ContactStatus, LocalVec};

/// Relative size of `‖P(τ) − τ‖/‖τ‖` under which a compressed contact is reported as stick.
pub(crate) const STATUS_TOL: f64 = 1e-8;

#[inline]
pub(crate) fn pick<T>(s: &[T], i: usize) -> &T {
    if s.len() == 1 { &s[0] } else { &s[i] }
}

/// Contact `i`'s part of a flat vector, normal first.
#[inline]
pub(crate) fn local<const DT: usize>(v: &[f64], i: usize) -> LocalVec<DT> {
    let b = (DT + 1) * i;
    let mut a = LocalVec::<DT>::zeros();
    a.n = v[b];
    for k in 0..DT {
        a.t[k] = v[b + 1 + k];
    }
    a
}

/// Writes contact `i`'s part of a flat vector.
#[inline]
pub(crate) fn set_local<const DT: usize>(v: &mut [f64], i: usize, a: &LocalVec<DT>) {
    let b = (DT + 1) * i;
    v[b] = a.n;
    for k in 0..DT {
        v[b + 1 + k] = a.t[k];
    }
}

/// The tangential part of `a` projected onto the disc of radius `g ≥ 0` (the segment
/// `[−g, g]` in 2D).
#[inline]
pub(crate) fn clamp_disc<const DT: usize>(a: &LocalVec<DT>, g: f64) -> LocalVec<DT> {
    let mut out = *a;
    if DT == 1 {
        out.t[0] = a.t[0].clamp(-g, g);
        return out;
    }
    let norm = a.t_norm();
    if norm > g {
        let f = if norm > 0.0 { g / norm } else { 0.0 };
        for k in 0..DT {
            out.t[k] = a.t[k] * f;
        }
    }
    out
}

pub(crate) fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// `1/λ_max` of the symmetric positive (semi)definite `d × d` block in the top-left corner of
/// `b` (`d` = 2 or 3); of its symmetric part `(b + bᵀ)/2` when it is not symmetric (a block of
/// a kept non-symmetric `W`: `λ_max` of the symmetric part bounds `uᵀ b u / uᵀ u`).
pub(crate) fn rho_of_block(b: &[[f64; 3]; 3], d: usize) -> f64 {
    let mut sym = *b;
    for i in 0..3 {
        for j in 0..i {
            if b[i][j] != b[j][i] {
                let a = 0.5 * b[i][j] + 0.5 * b[j][i];
                (sym[i][j], sym[j][i]) = (a, a);
            }
        }
    }
    let b = &sym;
    if d == 2 {
        let (a, c, e) = (b[0][0], b[0][1], b[1][1]);
        let h = 0.5 * (a - e);
        return 1.0 / (0.5 * (a + e) + (h * h + c * c).sqrt());
    }
    1.0 / lambda_max_3(b)
}

/// The largest eigenvalue of a symmetric 3×3 matrix (closed form, Smith 1961), computed on the
/// matrix scaled by its largest entry so that no square overflows or underflows.
fn lambda_max_3(b: &[[f64; 3]; 3]) -> f64 {
    let s = b.iter().flatten().fold(0.0_f64, |a, v| a.max(v.abs()));
    if s == 0.0 {
        return 0.0;
    }
    let a = |i: usize, j: usize| b[i][j] / s;
    let p1 = a(0, 1).powi(2) + a(0, 2).powi(2) + a(1, 2).powi(2);
    let q = (a(0, 0) + a(1, 1) + a(2, 2)) / 3.0;
    let p2 = (a(0, 0) - q).powi(2) + (a(1, 1) - q).powi(2) + (a(2, 2) - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    if p == 0.0 {
        return q * s;
    }
    let c = |i: usize, j: usize| (a(i, j) - if i == j { q } else { 0.0 }) / p;
    let det = c(0, 0) * (c(1, 1) * c(2, 2) - c(1, 2) * c(2, 1))
        - c(0, 1) * (c(1, 0) * c(2, 2) - c(1, 2) * c(2, 0))
        + c(0, 2) * (c(1, 0) * c(2, 1) - c(1, 1) * c(2, 0));
    let phi = (0.5 * det).clamp(-1.0, 1.0).acos() / 3.0;
    (q + 2.0 * p * phi.cos()) * s
}

/// The status of each contact at `(r, x)`, from the projection `P(r + ρ v(x))`: separation
/// when it is zero, stick when it leaves `τ` unchanged (to [`STATUS_TOL`]), slip otherwise.
/// `laws` and `states` may hold one entry for every contact.
pub(crate) fn contact_statuses<L: ContactLaw, const DT: usize>(
    laws: &[L],
    states: &[L::State],
    rho: &[f64],
    r: &[f64],
    x: &[f64],
) -> Vec<ContactStatus> {
    (0..rho.len())
        .map(|i| {
            let (law, s) = (pick(laws, i), pick(states, i));
            let tau = local::<DT>(r, i) + law.modified_velocity(&local::<DT>(x, i), s) * rho[i];
            let p = law.project(&tau, s);
            if p.n == 0.0 && p.t.iter().all(|&t| t == 0.0) {
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
pub(crate) fn natural_residual<L: ContactLaw, const DT: usize>(
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    r: &[f64],
    x: &[f64],
) -> f64 {
    let mut s2 = 0.0;
    for (i, &rho0) in rho0.iter().enumerate() {
        let (law, s) = (pick(laws, i), pick(states, i));
        let ri = local::<DT>(r, i);
        let tau = ri + law.modified_velocity(&local::<DT>(x, i), s) * rho0;
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
/// `‖(r_n − max(0, r_n − ρ⁰ x_n), r_t − P_D(r_t − ρ⁰ x_t))‖` (absolute), `P_D` the projection
/// on the disc (segment in 2D) of radius `μ̄ r_n⁺`. Zero
/// exactly at a solution, like the natural residual, but the normal test sees `x_n` itself:
/// with a huge `μ̄` the modified velocity's `x_n + μ̄|x_t|` can absorb a penetration.
pub(crate) fn coulomb_residual<const DT: usize>(
    mu: &[f64],
    rho0: &[f64],
    r: &[f64],
    x: &[f64],
) -> f64 {
    let mut s2 = 0.0;
    for (i, (&mu, &rho)) in mu.iter().zip(rho0).enumerate() {
        let (ri, xi) = (local::<DT>(r, i), local::<DT>(x, i));
        let dn = ri.n - (ri.n - rho * xi.n).max(0.0);
        let g = mu * ri.n.max(0.0);
        let dt = ri.t - clamp_disc(&(ri - xi * rho), g).t;
        s2 += dn * dn + dt.norm_squared();
    }
    s2.sqrt()
}

/// The largest penetration `max_i (−x_n,i)⁺` of an answer and the scale of the
/// displacements it is compared with, `max(‖q‖∞, ‖x − q‖∞)` (`x − q = W r`). An iteration
/// whose reactions grow without bound (a problem with no solution) can bring the *relative*
/// residual `‖·‖/‖r‖` to 0 while `x_n` stays negative at the scale of `q`: this catches it.
pub(crate) fn penetration<const DT: usize>(q: &[f64], x: &[f64]) -> (f64, f64) {
    let (mut pen, mut scale) = (0.0_f64, 0.0_f64);
    for (k, (&x, &q)) in x.iter().zip(q).enumerate() {
        scale = scale.max(q.abs()).max((x - q).abs());
        if k % (DT + 1) == 0 {
            pen = pen.max(-x);
        }
    }
    (pen, scale)
}

/// Siconos' error of the reactions `r` of a Coulomb `problem`: `u = W r + q`, then
/// `‖r − P_K(r − (u + μ‖u_t‖ n))‖ / ‖q‖` (absolute when `q = 0`), what Siconos'
/// `fc3d_compute_error` returns for the same `(r, u)`, in 2D and 3D.
///
/// # Our tolerance beside Siconos'
/// The `tol` of [`UzawaSettings`](crate::UzawaSettings) bounds the *relative* natural residual
/// that [`UzawaReport::residual`](crate::UzawaReport::residual) reports (the
/// [stopping rule](crate::local#stopping-rule)); for a Coulomb law the modified velocity is
/// De Saxcé's, `v(x) = −(x_t + (x_n + μ‖x_t‖) n)`, so per contact it is Siconos' map:
///
/// ```text
/// ours     ‖r − P_K(r − ρ⁰_i (x + μ‖x_t‖ n))‖ / max(‖r‖, max_i ρ⁰_i ‖q‖),   ρ⁰_i = 1/λ_max(W_ii)
/// Siconos  ‖r − P_K(r − ρ (u + μ‖u_T‖ e_n))‖ / ‖q‖,   ρ = 1,   u = W r + q
/// ```
/// (Siconos numerics, `fc3d_compute_error` and `fc3d_unitary_compute_and_add_error`: the
/// absolute error is divided by the `norm` its caller passes, "norm of a vector (problem->q)
/// for relative error"; the sources of 2016 divided by `1 + ‖q‖`.) The two differ by the step (`ρ⁰_i` is the largest non-expansive local step;
/// Siconos' `ρ = 1` makes its error carry the units of `r` and of `x` mixed) and by the scale
/// (ours is relative to the reactions, Siconos' to the free velocities), so on a problem whose
/// `W` is far from unit size the same number means different accuracies. This function
/// computes Siconos' for an answer of ours, to compare like with like.
///
/// # Panics
/// If `r.len() != problem.size()`.
///
/// # Examples
/// ```
/// use contact_solver::{ReducedProblem, solve_coulomb, UzawaSettings};
/// use contact_solver::local::siconos_error;
/// let p = ReducedProblem::new(vec![4.0, 0.0, 0.0, 4.0], vec![-1.0, 0.5], vec![0.2])?;
/// let sol = solve_coulomb(&p, &UzawaSettings::default())?;
/// assert!(siconos_error(&p, &sol.r) < 1e-9);
/// // r = 0 leaves the whole penetration: ‖(0 − P(1 − 0.1, −0.5))‖/‖q‖ is of order one
/// assert!(siconos_error(&p, &[0.0, 0.0]) > 0.5);
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
#[track_caller]
pub fn siconos_error(problem: &ReducedProblem, r: &[f64]) -> f64 {
    let m = problem.size();
    assert_eq!(r.len(), m, "r must have problem.size() entries");
    let mut u = vec![0.0; m];
    problem.displacement_into(r, &mut u);
    let laws = problem.coulomb_laws();
    let rho = vec![1.0; problem.contact_count()];
    let absolute = match problem.dimension() {
        3 => natural_residual::<_, 2>(&laws, &[()], &rho, r, &u),
        _ => natural_residual::<_, 1>(&laws, &[()], &rho, r, &u),
    };
    let q = norm(problem.q());
    if q > 0.0 { absolute / q } else { absolute }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rho_of_block_works() {
        // λ_max of [2 0; 0 1] is 2; of [1 1; 1 1] is 2.
        let b2 = |a, b, d| [[a, b, 0.0], [b, d, 0.0], [0.0; 3]];
        assert_eq!(rho_of_block(&b2(2.0, 0.0, 1.0), 2), 0.5);
        assert!((rho_of_block(&b2(1.0, 1.0, 1.0), 2) - 0.5).abs() < 1e-15);
        // 3×3: diag(1, 3, 2) → 3; [[2 1 0] [1 2 1] [0 1 2]] → 2 + √2; 1e300 scale; zero.
        let d = [[1.0, 0.0, 0.0], [0.0, 3.0, 0.0], [0.0, 0.0, 2.0]];
        assert!((rho_of_block(&d, 3) - 1.0 / 3.0).abs() < 1e-15);
        let t = [[2.0, 1.0, 0.0], [1.0, 2.0, 1.0], [0.0, 1.0, 2.0]];
        assert!((1.0 / rho_of_block(&t, 3) - (2.0 + 2f64.sqrt())).abs() < 1e-14);
        let big = t.map(|row| row.map(|v| v * 1e300));
        assert!((1.0 / rho_of_block(&big, 3) / 1e300 - (2.0 + 2f64.sqrt())).abs() < 1e-14);
        assert_eq!(lambda_max_3(&[[0.0; 3]; 3]), 0.0);
    }
}
