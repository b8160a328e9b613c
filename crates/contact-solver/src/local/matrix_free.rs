//! A matrix-free bipotential iteration for reduced problems too large to store `F*` densely.
//!
//! `F* = H K⁻¹ Hᵀ` costs `n_c²` memory and `2 n_c` structure solves to build; past a few
//! thousand contacts neither is affordable. This solver only needs the product
//! `x = F* r + q`, which costs one forward/back substitution with the factorised `K`
//! (`Hᵀ r`, solve, `H ·`). It is De Saxcé's projected iteration (seed 5.26) with
//!
//! - per-contact `ρ_i = θ ρ⁰_i`, `ρ⁰_i` from (estimated) diagonal blocks of `F*`, and the global
//!   factor `θ` adapted by the Khobotov / Solodov–Tseng ratio rule of the [layer docs](crate::local#the-penalty-ρ);
//! - Nesterov momentum on `r` with adaptive restart (O'Donoghue & Candès 2015): the momentum is
//!   dropped whenever the natural-map residual grows. Since `x` is affine in `r`, the
//!   extrapolated `x` is the same combination of the last two products: one structure solve per
//!   iteration (plus one per rejected trial).
//!
//! It stops on the same rule as the dense solvers: relative change of `r` and natural-map
//! residual with `ρ⁰`, both ≤ `tol` (in a simulation `ρ⁰` comes from diagonal blocks computed
//! exactly on 16 sampled contacts, so the residual's scaling differs slightly from the dense
//! solvers').
//!
//! **Cost.** Measured on a P2 block pressed and pushed on a LINE
//! (`tests/integration/matrix_free.rs` setup), the products per step grow about linearly with `n_c`
//! (the Delassus operator of a 2D elastic body has a condition number growing with `n_c`):
//! Signorini, tol 1e-8: 114 products for `n_c = 33`, 633 for 129; Coulomb: 194 and 2790. Building
//! `F*` costs `2 n_c` solves, so the dense path is faster whenever `F*` fits in memory; this solver
//! is for when it does not.

use super::residual::{local, natural_residual, norm, penetration};
use super::settings::{ADAPT_GROW_BELOW, ADAPT_GROWTH, ADAPT_SHRINK_ABOVE, UzawaSettings};
use super::solver::CHECK_FACTOR;
use super::stall::StallDetector;
use crate::error::SolverError;
use contact_laws::ContactLaw;

/// What the matrix-free solve did.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct MatrixFreeReport {
    /// Accepted iterations.
    pub iterations: usize,
    /// Operator applications (structure solves), including rejected trials.
    pub applications: usize,
    /// Whether the stopping rule was met.
    pub converged: bool,
    /// Whether the [stall detector](crate::local::stall) stopped the iteration (with
    /// `accept_non_converged`; otherwise a stall is [`SolverError::Stalled`]).
    pub stalled: bool,
    /// Final natural-map residual (relative).
    pub residual: f64,
    /// Residual of every iteration.
    pub history: Vec<f64>,
    /// Momentum restarts.
    pub restarts: usize,
    /// Final global factor `θ` of `ρ⁰`.
    pub theta: f64,
}

/// Solves `x = W r + q` given only `apply(r, x)`, which must write `W r + q` into `x`.
///
/// `rho0` holds `ρ⁰_i` per contact (e.g. `1/λ_max` of estimated diagonal blocks); `laws` and
/// `states` one per contact; `r` is the starting reaction on entry and the solution on return,
/// `x` the matching `W r + q`. Uses `settings.tol`, `max_iterations`, `rho_scale`,
/// `stall_window` and `accept_non_converged`.
///
/// # Errors
/// [`SolverError::SizeMismatch`] for inconsistent lengths; errors of `apply`;
/// [`SolverError::Stalled`] when the residual stops decreasing (the
/// [stall detector](crate::local::stall)) and [`SolverError::NotConverged`] when
/// `max_iterations` runs out, unless `accept_non_converged`.
///
/// # Examples
/// ```
/// use contact_laws::Coulomb;
/// use contact_solver::local::matrix_free::solve_matrix_free;
/// use contact_solver::UzawaSettings;
/// // one contact, W = 2 I, pressed (q_n = −1) and pushed (q_t = 0.5), μ = 0.2: slip
/// let apply = |r: &[f64], x: &mut [f64]| {
///     x[0] = 2.0 * r[0] - 1.0;
///     x[1] = 2.0 * r[1] + 0.5;
///     Ok(())
/// };
/// let (mut r, mut x) = (vec![0.0; 2], vec![0.0; 2]);
/// let law = [Coulomb::new(0.2)?];
/// solve_matrix_free(apply, &law, &[()], &[0.5], &UzawaSettings::default(), &mut r, &mut x)?;
/// assert!((r[0] - 0.5).abs() < 1e-9 && (r[1] + 0.1).abs() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn solve_matrix_free<L: ContactLaw>(
    apply: impl FnMut(&[f64], &mut [f64]) -> Result<(), SolverError>,
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    settings: &UzawaSettings,
    r: &mut [f64],
    x: &mut [f64],
) -> Result<MatrixFreeReport, SolverError> {
    solve::<L, 1>(apply, laws, states, rho0, settings, r, x)
}

/// [`solve_matrix_free`] in 3D: `r` and `x` have three components per contact, the normal
/// first, then the two tangential ones (`m = 3 n_c`).
///
/// # Errors
/// As [`solve_matrix_free`].
///
/// # Examples
/// ```
/// use contact_laws::Coulomb;
/// use contact_solver::local::matrix_free::solve_matrix_free_3d;
/// use contact_solver::UzawaSettings;
/// // one contact, W = 2 I, pressed (q_n = −1) and pushed along t₁ (q_t1 = 0.5), μ = 0.2: slip
/// let apply = |r: &[f64], x: &mut [f64]| {
///     x[0] = 2.0 * r[0] - 1.0;
///     x[1] = 2.0 * r[1] + 0.5;
///     x[2] = 2.0 * r[2];
///     Ok(())
/// };
/// let (mut r, mut x) = (vec![0.0; 3], vec![0.0; 3]);
/// let law = [Coulomb::new(0.2)?];
/// solve_matrix_free_3d(apply, &law, &[()], &[0.5], &UzawaSettings::default(), &mut r, &mut x)?;
/// assert!((r[0] - 0.5).abs() < 1e-9 && (r[1] + 0.1).abs() < 1e-9 && r[2].abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn solve_matrix_free_3d<L: ContactLaw>(
    apply: impl FnMut(&[f64], &mut [f64]) -> Result<(), SolverError>,
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    settings: &UzawaSettings,
    r: &mut [f64],
    x: &mut [f64],
) -> Result<MatrixFreeReport, SolverError> {
    solve::<L, 2>(apply, laws, states, rho0, settings, r, x)
}

/// The iteration with `DT` tangential components per contact.
fn solve<L: ContactLaw, const DT: usize>(
    mut apply: impl FnMut(&[f64], &mut [f64]) -> Result<(), SolverError>,
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    settings: &UzawaSettings,
    r: &mut [f64],
    x: &mut [f64],
) -> Result<MatrixFreeReport, SolverError> {
    let dim = DT + 1;
    check_sizes(dim, laws.len(), states.len(), rho0, r.len(), x.len())?;
    let nc = rho0.len();
    let m = dim * nc;
    let mut applications = 1;
    apply(r, x)?;
    // q = x − W r is not needed: the residual scale uses ‖x(0)‖ through the first product
    let mut r_prev = r.to_vec();
    let mut x_prev = x.to_vec();
    let mut y = r.to_vec();
    let mut xy = x.to_vec();
    let mut r_new = vec![0.0; m];
    let mut x_new = vec![0.0; m];
    let mut v = vec![0.0; m];
    let mut theta = settings.tuning.rho_scale;
    let mut t = 1.0_f64;
    let mut history = Vec::new();
    let mut restarts = 0;
    let rho_max = rho0.iter().fold(0.0_f64, |a, &b| a.max(b));
    let mut scale_q = 0.0_f64;
    let mut residual = f64::INFINITY;
    let mut last_residual = f64::INFINITY;
    let mut iterations = 0;
    let mut converged = false;
    let mut stalled = false;
    let mut stall = StallDetector::new(settings.tuning.stall_window);
    // cones `‖r_t‖ ≤ μ̄ r_n`, whose answers cannot penetrate
    let coulomb_type = laws
        .iter()
        .zip(states)
        .all(|(l, s)| l.friction_coefficient(s).is_some());
    while iterations < settings.max_iterations {
        iterations += 1;
        for i in 0..nc {
            let vi = laws[i].modified_velocity(&local::<DT>(&xy, i), &states[i]);
            v[dim * i] = vi.n;
            v[dim * i + 1..dim * (i + 1)].copy_from_slice(vi.t.as_slice());
        }
        let mut shrinks = 0;
        let dr2 = loop {
            let mut dr2 = 0.0;
            for i in 0..nc {
                let yi = local::<DT>(&y, i);
                let p = laws[i].project(&(yi + local(&v, i) * (theta * rho0[i])), &states[i]);
                r_new[dim * i] = p.n;
                r_new[dim * i + 1..dim * (i + 1)].copy_from_slice(p.t.as_slice());
                let d = p - yi;
                dr2 += d.dot(&d);
            }
            if dr2 == 0.0 {
                x_new.copy_from_slice(&xy);
                break 0.0;
            }
            apply(&r_new, &mut x_new)?;
            applications += 1;
            let mut dv2 = 0.0;
            for i in 0..nc {
                let vn = laws[i].modified_velocity(&local::<DT>(&x_new, i), &states[i]);
                let d = (vn - local(&v, i)) * (theta * rho0[i]);
                dv2 += d.dot(&d);
            }
            let ratio = (dv2 / dr2).sqrt();
            if ratio > ADAPT_SHRINK_ABOVE && shrinks < 60 {
                theta *= 0.5;
                shrinks += 1;
                continue;
            }
            if ratio < ADAPT_GROW_BELOW {
                theta *= ADAPT_GROWTH;
            }
            break dr2;
        };
        if scale_q == 0.0 {
            scale_q = rho_max * norm(x);
        }
        let change2: f64 = r_new
            .iter()
            .zip(r.iter())
            .map(|(a, b)| (a - b) * (a - b))
            .sum();
        let r_norm = norm(&r_new);
        let change = change2.sqrt() / r_norm.max(f64::MIN_POSITIVE);
        residual = natural_residual::<L, DT>(laws, states, rho0, &r_new, &x_new)
            / r_norm.max(scale_q).max(f64::MIN_POSITIVE);
        history.push(residual);
        // accept r_new
        r_prev.copy_from_slice(r);
        x_prev.copy_from_slice(x);
        r.copy_from_slice(&r_new);
        x.copy_from_slice(&x_new);
        if (change <= settings.tol && residual <= settings.tol) || dr2 == 0.0 {
            // a relative residual of 0 with reactions grown without bound (no solution)
            // leaves x_n < 0 at the scale of q: one more product gives q = x(r = 0)
            if coulomb_type && no_solution::<DT>(&mut apply, settings.tol, x, &mut applications)? {
                stalled = true;
                break;
            }
            converged = true;
            break;
        }
        if stall.stalled(iterations, residual) {
            stalled = true;
            break;
        }
        // momentum with adaptive restart
        let beta = if residual > last_residual {
            restarts += 1;
            t = 1.0;
            0.0
        } else {
            let t_next = 0.5 * (1.0 + (1.0 + 4.0 * t * t).sqrt());
            let b = (t - 1.0) / t_next;
            t = t_next;
            b
        };
        last_residual = residual;
        for k in 0..m {
            y[k] = r[k] + beta * (r[k] - r_prev[k]);
            xy[k] = x[k] + beta * (x[k] - x_prev[k]);
        }
    }
    conclude(
        "MatrixFree",
        MatrixFreeReport {
            iterations,
            applications,
            converged,
            stalled,
            residual,
            history,
            restarts,
            theta,
        },
        settings,
    )
}

/// Whether an answer whose relative residual met the tolerance is that of a problem without a
/// solution: with some `x_n < 0`, one more product gives `q = x(r = 0)` (counted in
/// `applications`) and the penetration is judged at the scale of `q`.
pub(super) fn no_solution<const DT: usize>(
    apply: &mut impl FnMut(&[f64], &mut [f64]) -> Result<(), SolverError>,
    tol: f64,
    x: &[f64],
    applications: &mut usize,
) -> Result<bool, SolverError> {
    if !x.iter().step_by(DT + 1).any(|&v| v < 0.0) {
        return Ok(false);
    }
    let zero = vec![0.0; x.len()];
    let mut q = vec![0.0; x.len()];
    apply(&zero, &mut q)?;
    *applications += 1;
    let (pen, scale) = penetration::<DT>(&q, x);
    Ok(pen > CHECK_FACTOR * tol * scale)
}

/// The report of a finished matrix-free solve, or the error of a stalled or non-converged one
/// (unless `accept_non_converged`).
pub(super) fn conclude(
    algorithm: &'static str,
    report: MatrixFreeReport,
    settings: &UzawaSettings,
) -> Result<MatrixFreeReport, SolverError> {
    let MatrixFreeReport {
        iterations,
        residual,
        history,
        stalled,
        converged,
        ..
    } = &report;
    let (iterations, residual) = (*iterations, *residual);
    if *stalled && !settings.accept_non_converged {
        let best_residual = history.iter().copied().fold(f64::INFINITY, f64::min);
        return Err(SolverError::Stalled {
            algorithm,
            fallback_from: None,
            iterations,
            residual,
            best_residual,
            history: report.history,
            best: None,
        });
    }
    if !*converged && !settings.accept_non_converged {
        return Err(SolverError::NotConverged {
            iterations,
            residual,
            history: report.history,
            best: None,
        });
    }
    Ok(report)
}

/// The sizes of a matrix-free solve (`n_c` laws and states, `dim n_c` reactions and jumps)
/// and its base penalties (finite, positive).
pub(super) fn check_sizes(
    dim: usize,
    n_laws: usize,
    n_states: usize,
    rho0: &[f64],
    n_r: usize,
    n_x: usize,
) -> Result<(), SolverError> {
    let nc = rho0.len();
    let m = dim * nc;
    for (what, len, expected) in [
        ("laws", n_laws, nc),
        ("states", n_states, nc),
        ("r", n_r, m),
        ("x", n_x, m),
    ] {
        if len != expected {
            return Err(SolverError::SizeMismatch {
                what,
                expected,
                found: len,
            });
        }
    }
    if let Some((index, &value)) = rho0
        .iter()
        .enumerate()
        .find(|(_, a)| !(a.is_finite() && **a > 0.0))
    {
        return Err(SolverError::NonFinite {
            what: "rho0",
            index,
            value,
        });
    }
    Ok(())
}
