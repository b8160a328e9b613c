//! The classical RCCM solver: contact and friction solved separately, with a fixed point on the
//! friction threshold (Raous, Latil: GYPTIS; the algorithm the seed compares the bipotential
//! with, Terfaya 2019 §5.6, tables 5.1–5.2). Selected by
//! [`Algorithm::ClassicRccm`](crate::Algorithm::ClassicRccm) in
//! [`UzawaSolver`](crate::UzawaSolver).
//!
//! On the reduced problem `x = W r + q` (normal first per contact, signs of
//! [`contact_laws`](contact_laws#sign-conventions)), with `μ̄_i` the coefficient of contact
//! `i`'s Coulomb cone ([`ContactLaw::friction_coefficient`]):
//!
//! ```text
//! outer iteration k (until the stopping rule below):
//!   1. Signorini at fixed r_t: projected SOR sweeps on the normal components
//!        r_n,i ← max(0, r_n,i − ω x_n,i / W_nn,i)
//!      until ‖Δr_n‖/‖r_n‖ ≤ tol over one sweep;
//!   2. threshold from the new r_n:   s_i = μ̄_i r_n,i;
//!   3. friction at fixed s (Tresca): projected SOR sweeps on the tangential components
//!        2D: r_t,i ← clamp(r_t,i − ω x_t,i / W_tt,i, −s_i, s_i)
//!        3D: r_t,i ← P_D(s_i)(r_t,i − ω x_t,i / λ_max(W_tt,i))     (both tangents at once)
//!      until ‖Δr_t‖/‖r_t‖ ≤ tol over one sweep.
//! ```
//! In 3D the two tangents of a contact share the disc `‖r_t‖ ≤ s_i`, so they move together,
//! with one step `ω/λ_max` of the contact's 2×2 tangential block: a scalar step, so that a
//! fixed point has `x_t` along `−r_t` as Coulomb's law wants (a diagonal step `W_tt⁻¹` per
//! component would not).
//! After every change of one component `x` is updated with that column of `W` (read as a row,
//! `W` is symmetric), as in the bipotential Gauss–Seidel sweep. A fixed point of the outer
//! iteration is a Signorini–Coulomb solution: `r_n ≥ 0, x_n ≥ 0, r_n x_n = 0`,
//! `|r_t| ≤ μ̄ r_n`, `x_t = 0` where `|r_t| < μ̄ r_n` and `r_t = −μ̄ r_n sign(x_t)` where
//! `x_t ≠ 0` — the zero of the natural map used by the stopping rule.
//! Step 3 is skipped entirely when every `μ̄_i = 0`, and then `r_t = 0` (a warm start's `r_t`
//! is dropped). The threshold is taken from the `r_n` just computed in step 1 rather than from
//! the `r_n` at the start of the outer iteration: on the problems measured below (ω = 1) that
//! takes 2–42 % fewer sweeps (e.g. 228 against 366 for random `n_c = 50`, seed 1, and 1157
//! against 1917 for the string with `n_c = 40`).
//!
//! # Stopping rule and what is counted
//! The rule is the bipotential solver's (see [layer docs](crate::local#stopping-rule)), tested
//! after each outer iteration: the relative change of the whole `r` over the outer iteration
//! and the natural-map residual `‖r − P_K(r + ρ⁰ v(W r + q))‖`, computed with the laws'
//! projection and the base `ρ⁰_i = 1/λ_max(W_ii)` exactly as for the bipotential sweeps, must
//! both be `≤ tol`. So both algorithms stop on equal terms. Like theirs, a second way to stop
//! is a long streak of residuals `≤ tol` (`residual_stop`), which this solver also checks every
//! `RESIDUAL_CHECK_EVERY` sweeps inside the sub-problems: their own rule waits for the change
//! of `r_n` (or `r_t`) over a sweep to vanish, which on a rank-deficient `W` (four corners of
//! a box carrying what three would) it need not do while the whole problem is solved to
//! `tol`.
//!
//! - [`UzawaReport::iterations`](crate::UzawaReport::iterations) counts **sweeps**: every
//!   normal sweep and every tangential sweep of every outer iteration. One sweep is one pass
//!   over the contacts, so it is the "contact iterations" count of the seed's tables 5.1–5.2
//!   (GYPTIS ≈ 132, bipotential ≈ 8) and compares with the bipotential Gauss–Seidel sweeps.
//!   A classic sweep touches one component per contact, a bipotential sweep both.
//! - [`UzawaReport::tangential_sweeps`](crate::UzawaReport::tangential_sweeps) counts the
//!   sweeps of step 3 (`iterations − tangential_sweeps` are Signorini sweeps);
//!   [`UzawaReport::outer_iterations`](crate::UzawaReport::outer_iterations) counts the outer
//!   iterations, and [`UzawaReport::history`](crate::UzawaReport::history) holds the natural
//!   residual after each of them.
//! - `max_iterations` caps the total number of sweeps; the sub-problems have no cap of their
//!   own (each is a convex QP on which projected SOR converges for `0 < ω < 2`).
//! - `rho_scale` is not used; the report's `rho_min`/`rho_max` give the range of `ρ⁰`.
//!
//! # Measured sweeps and the choice of ω
//! Tol 1e-10, sweeps to convergence (`iterations`, with the tangential ones in brackets) of
//! the classic solver for several ω, against the bipotential Gauss–Seidel sweeps (GS) on the
//! same problem. "random" is [`generate::random_problem`](crate::local::generate::random_problem)
//! (Coulomb, `μ ~ U(0, 1)`); "string" is a strongly coupled FE-like `W = K⁻¹` (two strings on
//! an elastic foundation pressed by a parabolic punch, see `examples/classic_omega.rs`, which
//! prints this table):
//!
//! ```text
//! problem                 GS   ω = 0.8      ω = 1        ω = 1.2      ω = 1.5      ω = 1.8
//! random n_c=10  seed 1   60   793 (299)    486 (162)    522 (258)   1051 (540)   3080 (1593)
//! random n_c=10  seed 2   54   367 (135)    179 (40)     307 (142)    637 (291)   1852 (846)
//! random n_c=10  seed 3   41   396 (162)    233 (87)     306 (145)    627 (313)   1843 (943)
//! random n_c=50  seed 1   51   369 (130)    228 (71)     281 (126)    557 (259)   1606 (755)
//! random n_c=50  seed 2   55   430 (178)    268 (104)    301 (139)    602 (289)   1747 (846)
//! random n_c=100 seed 3   58   601 (249)    393 (159)    445 (206)    845 (402)   2427 (1155)
//! string n_c=10 μ=0.3    128   382 (13)     256 (13)     230 (13)     361 (15)     974 (15)
//! string n_c=20 μ=0.3    189   743 (17)     556 (17)     554 (17)     863 (17)    2168 (17)
//! string n_c=20 μ=0.1    168   577 (13)     429 (13)     431 (13)     677 (15)    1727 (13)
//! string n_c=40 μ=0.5    271  1522 (481)   1157 (325)   1187 (233)   1756 (259)   4115 (695)
//! ```
//! ω = 1 (plain projected Gauss–Seidel) is the fastest on every random problem (7–42 % fewer
//! sweeps than ω = 1.2) and within 3 % of ω = 1.2 on the strings except the smallest (256
//! against 230); ω ≥ 1.5 is always slower. So the default `DEFAULT_OMEGA` is 1:
//! over-relaxation does not pay here because `W` is a flexibility (a dense, smoothing matrix),
//! not a stiffness. The outer iterations hardly depend on ω (15–29 on the random problems, 7–11
//! on the strings). The classic solver needs 3–8 times the bipotential's sweeps on the random
//! problems and 2–4 times on the strings; the seed's GYPTIS comparison points the same way
//! (≈ 132 contact iterations against 7–8, table 5.1, on an FE problem with adhesion). Both
//! reach the same `r` (within 3e-10 relative on the random problems, 2e-9 on the
//! worse-conditioned strings).
//!
//! # Examples
//! ```
//! use contact_solver::{Algorithm, ReducedProblem, UzawaSettings, UzawaSolver};
//! // One contact, W = I, q = (−1, 0.5), μ = 0.2: slip, r = (1, −0.2).
//! let p = ReducedProblem::new(vec![1.0, 0.0, 0.0, 1.0], vec![-1.0, 0.5], vec![0.2])?;
//! let settings = UzawaSettings::default().with_algorithm(Algorithm::ClassicRccm);
//! let sol = UzawaSolver::new(settings).solve(&p, &p.coulomb_laws())?;
//! assert!((sol.r[0] - 1.0).abs() < 1e-9 && (sol.r[1] + 0.2).abs() < 1e-9);
//! assert!(sol.report.tangential_sweeps > 0);
//! # Ok::<(), contact_solver::SolverError>(())
//! ```

use super::delassus::Delassus;
use super::problem::ReducedProblem;
use super::residual::{natural_residual, norm, pick, rho_of_block};
use super::residual_stop::{RESIDUAL_CHECK_EVERY, ResidualStop};
use super::settings::UzawaSettings;
use super::stall::StallDetector;
use crate::error::SolverError;
use contact_laws::{ContactLaw, LawError};

/// Scratch buffers of the classical solver, kept in the [`UzawaSolver`](crate::UzawaSolver)
/// and reused across solves.
#[derive(Clone, Debug, Default)]
pub(crate) struct ClassicScratch {
    /// `μ̄_i`, one per contact.
    mu_bar: Vec<f64>,
    /// The threshold `s_i = μ̄_i r_n,i`, one per contact.
    threshold: Vec<f64>,
    /// `1/W_kk`, one per unknown.
    inv_diag: Vec<f64>,
    /// 3D: `1/λ_max` of each contact's 2×2 tangential block.
    inv_lambda_t: Vec<f64>,
    /// `r` at the start of the outer iteration.
    r_prev: Vec<f64>,
}

/// What a classical solve did.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ClassicRun {
    /// Total sweeps (normal and tangential).
    pub iterations: usize,
    /// Outer iterations (threshold updates).
    pub outer_iterations: usize,
    /// Sweeps of the friction sub-problem.
    pub tangential_sweeps: usize,
    /// `true` when the stopping rule was met.
    pub converged: bool,
    /// `true` when the [stall detector](super::stall) stopped the run: on the natural
    /// residual of the outer iterations (counted in outer iterations, one per history entry),
    /// or on the change of a sub-problem's sweeps (counted in that sub-problem's sweeps: a
    /// sub-problem with no solution never meets its own rule).
    pub stalled: bool,
    /// Relative natural residual at the last outer iteration.
    pub residual: f64,
    /// Relative change of `r` over the last outer iteration.
    pub change: f64,
}

/// Collects `μ̄_i = law_i.friction_coefficient(state_i)` of the `nc` contacts into `mu_bar`
/// (cleared first), for the solvers that need a Coulomb cone (this one and
/// [`Algorithm::Newton`](crate::Algorithm::Newton)).
///
/// # Errors
/// [`SolverError::NoFrictionCoefficient`] / [`SolverError::InvalidLaw`] if a law's
/// `friction_coefficient` is `None` / not finite and `≥ 0`.
pub(crate) fn friction_coefficients_into<L: ContactLaw>(
    laws: &[L],
    states: &[L::State],
    nc: usize,
    mu_bar: &mut Vec<f64>,
) -> Result<(), SolverError> {
    mu_bar.clear();
    for contact in 0..nc {
        match pick(laws, contact).friction_coefficient(pick(states, contact)) {
            None => return Err(SolverError::NoFrictionCoefficient { contact }),
            Some(m) if m.is_finite() && m >= 0.0 => mu_bar.push(m),
            Some(value) => {
                return Err(SolverError::InvalidLaw {
                    contact,
                    source: LawError::InvalidParameter {
                        name: "mu_bar",
                        value,
                        expected: "a finite value >= 0",
                    },
                });
            }
        }
    }
    Ok(())
}

/// One projected SOR sweep on the unknowns `k = d i + component` (`d` unknowns per contact):
/// `r_k ← project(i, r_k − ω x_k / W_kk)`, then `x += W[:, k] Δr_k`. Returns the relative
/// change `‖Δr_c‖/‖r_c‖` of those unknowns over the sweep.
#[inline]
#[allow(clippy::too_many_arguments)]
fn sor_sweep(
    w: &Delassus,
    inv_diag: &[f64],
    omega: f64,
    d: usize,
    component: usize,
    r: &mut [f64],
    x: &mut [f64],
    project: impl Fn(usize, f64) -> f64,
) -> f64 {
    let m = r.len();
    let (mut d2, mut r2) = (0.0, 0.0);
    for i in 0..m / d {
        let k = d * i + component;
        let old = r[k];
        // x_k = 0 needs no step (and an infinite one would make 0 · ∞ = NaN)
        let step = if x[k] == 0.0 {
            0.0
        } else {
            omega * x[k] * inv_diag[k]
        };
        let new = project(i, old - step);
        r2 += new * new;
        let d = new - old;
        if d == 0.0 {
            continue;
        }
        d2 += d * d;
        r[k] = new;
        // x += W[:, k] Δr_k, read as row k of `columns`.
        w.axpy_row(k, d, x);
    }
    d2.sqrt() / r2.sqrt().max(f64::MIN_POSITIVE)
}

/// One projected sweep on the tangential pairs of a 3D problem (`k = 3i + 1, 3i + 2`):
/// `r_t,i ← P_D(s_i)(r_t,i − ω x_t,i / λ_max(W_tt,i))`, then `x += W[:, k] Δr_k`. Returns
/// the relative change `‖Δr_t‖/‖r_t‖` over the sweep.
fn disc_sweep(
    w: &Delassus,
    inv_lambda_t: &[f64],
    omega: f64,
    threshold: &[f64],
    r: &mut [f64],
    x: &mut [f64],
) -> f64 {
    let (mut d2, mut r2) = (0.0, 0.0);
    for (i, (&inv, &s)) in inv_lambda_t.iter().zip(threshold).enumerate() {
        let k = 3 * i + 1;
        let (old_t, old_s) = (r[k], r[k + 1]);
        let (mut new_t, mut new_s) = if inv.is_finite() {
            (old_t - omega * inv * x[k], old_s - omega * inv * x[k + 1])
        } else {
            // A tangentially supported contact (zero tangential block): an infinite step, so
            // r_t goes to the disc's edge against x_t (or stays, when x_t = 0).
            let n = x[k].hypot(x[k + 1]);
            if n > 0.0 {
                (-x[k] / n * s, -x[k + 1] / n * s)
            } else {
                (old_t, old_s)
            }
        };
        let norm = new_t.hypot(new_s);
        if norm > s {
            let f = if norm > 0.0 { s / norm } else { 0.0 };
            (new_t, new_s) = (new_t * f, new_s * f);
        }
        r2 += new_t * new_t + new_s * new_s;
        let (d_t, d_s) = (new_t - old_t, new_s - old_s);
        if d_t == 0.0 && d_s == 0.0 {
            continue;
        }
        d2 += d_t * d_t + d_s * d_s;
        (r[k], r[k + 1]) = (new_t, new_s);
        w.axpy_rows2(k, [d_t, d_s], x);
    }
    d2.sqrt() / r2.sqrt().max(f64::MIN_POSITIVE)
}

impl ClassicScratch {
    /// Runs the classical solver from `r` (with `x = W r + q`), pushing the natural residual of
    /// every outer iteration to `history`. `rho0` holds the base `ρ⁰_i`.
    ///
    /// # Errors
    /// [`SolverError::NoFrictionCoefficient`] / [`SolverError::InvalidLaw`] if a law's
    /// `friction_coefficient` is `None` / not finite and `≥ 0`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn solve<L: ContactLaw, const DT: usize>(
        &mut self,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        rho0: &[f64],
        settings: &UzawaSettings,
        r: &mut [f64],
        x: &mut [f64],
        history: &mut Vec<f64>,
    ) -> Result<ClassicRun, SolverError> {
        let nc = problem.contact_count();
        let m = problem.size();
        let d = DT + 1;
        // rows of `columns` are the columns of W (W itself unless a non-symmetric W is kept)
        let w = problem.columns();
        friction_coefficients_into(laws, states, nc, &mut self.mu_bar)?;
        let frictional = self.mu_bar.iter().any(|&mu_bar| mu_bar > 0.0);
        let tangential = |k: &usize| !k.is_multiple_of(d);
        if !frictional && (0..m).filter(tangential).any(|k| r[k] != 0.0) {
            // Frictionless: r_t = 0 exactly (drop a warm start's r_t).
            (0..m).filter(tangential).for_each(|k| r[k] = 0.0);
            problem.displacement_into(r, x);
        }
        self.inv_diag.clear();
        self.inv_diag.extend((0..m).map(|k| {
            let w_kk = problem.diagonal_block(k / d)[k % d][k % d];
            // A supported component (a prescribed slip: its row of W is zero) takes an infinite
            // step, so that it goes to its bound against x. The zero may be −0.0 (the spring
            // condensation writes one), and 1/−0.0 = −∞ sent it to the wrong bound: the 5.6.2
            // shear stalled at its corner node (issue 36).
            if w_kk > 0.0 {
                1.0 / w_kk
            } else {
                f64::INFINITY
            }
        }));
        self.inv_lambda_t.clear();
        if DT == 2 {
            self.inv_lambda_t.extend((0..nc).map(|i| {
                let b = problem.diagonal_block(i);
                let t = [[b[1][1], b[1][2], 0.0], [b[2][1], b[2][2], 0.0], [0.0; 3]];
                rho_of_block(&t, 2)
            }));
        }
        self.threshold.clear();
        self.threshold.resize(nc, 0.0);
        self.r_prev.clear();
        self.r_prev.resize(m, 0.0);

        let (tol, omega, max) = (settings.tol, settings.tuning.omega, settings.max_iterations);
        let denom_q = rho0.iter().fold(0.0_f64, |a, &b| a.max(b)) * norm(problem.q());
        let mut run = ClassicRun {
            iterations: 0,
            outer_iterations: 0,
            tangential_sweeps: 0,
            converged: false,
            stalled: false,
            residual: f64::INFINITY,
            change: f64::INFINITY,
        };
        let window = settings.tuning.stall_window;
        let mut stall = StallDetector::new(window);
        // the second way to stop, on the residual alone (`residual_stop`), checked also inside
        // the sub-problems, whose own rule waits for a change that a rank-deficient W need not
        // give
        let mut streak = ResidualStop::default();
        let mut on_residual = false;
        let relative = |r: &[f64], x: &[f64]| {
            let denom = norm(r).max(denom_q).max(f64::MIN_POSITIVE);
            natural_residual::<L, DT>(laws, states, rho0, r, x) / denom
        };
        while run.iterations < max {
            self.r_prev.copy_from_slice(r);
            // 1. Signorini at fixed r_t.
            let mut inner = StallDetector::new(window);
            let mut sweeps = 0;
            while run.iterations < max {
                run.iterations += 1;
                sweeps += 1;
                let change_n =
                    sor_sweep(w, &self.inv_diag, omega, d, 0, r, x, |_, r_n| r_n.max(0.0));
                if change_n <= tol {
                    break;
                }
                if inner.stalled(sweeps, change_n) {
                    run.stalled = true;
                    break;
                }
                if sweeps % RESIDUAL_CHECK_EVERY == 0
                    && streak.met(run.iterations, relative(r, x), change_n, tol)
                {
                    on_residual = true;
                    break;
                }
            }
            if frictional && !on_residual {
                // 2. Threshold from the new r_n.
                for ((s, mu_bar), r_n) in self
                    .threshold
                    .iter_mut()
                    .zip(&self.mu_bar)
                    .zip(r.iter().step_by(d))
                {
                    *s = mu_bar * r_n;
                }
                // 3. Friction at fixed threshold.
                let s = &self.threshold;
                let mut inner = StallDetector::new(window);
                let mut sweeps = 0;
                while run.iterations < max && !run.stalled {
                    run.iterations += 1;
                    sweeps += 1;
                    run.tangential_sweeps += 1;
                    let change_t = if DT == 1 {
                        sor_sweep(w, &self.inv_diag, omega, 2, 1, r, x, |i, r_t| {
                            r_t.max(-s[i]).min(s[i])
                        })
                    } else {
                        disc_sweep(w, &self.inv_lambda_t, omega, s, r, x)
                    };
                    if change_t <= tol {
                        break;
                    }
                    if inner.stalled(sweeps, change_t) {
                        run.stalled = true;
                        break;
                    }
                    if sweeps % RESIDUAL_CHECK_EVERY == 0
                        && streak.met(run.iterations, relative(r, x), change_t, tol)
                    {
                        on_residual = true;
                        break;
                    }
                }
            }
            run.outer_iterations += 1;
            let dr2: f64 = r
                .iter()
                .zip(&self.r_prev)
                .map(|(a, b)| (a - b) * (a - b))
                .sum();
            let r_norm = norm(r);
            run.change = dr2.sqrt() / r_norm.max(f64::MIN_POSITIVE);
            let denom = r_norm.max(denom_q).max(f64::MIN_POSITIVE);
            run.residual = natural_residual::<L, DT>(laws, states, rho0, r, x) / denom;
            on_residual |= streak.met(run.iterations, run.residual, run.change, tol);
            if (run.change <= tol && run.residual <= tol) || on_residual {
                // x was updated incrementally: confirm on the exact x = W r + q.
                problem.displacement_into(r, x);
                run.residual = natural_residual::<L, DT>(laws, states, rho0, r, x) / denom;
            }
            history.push(run.residual);
            if run.residual <= tol && (run.change <= tol || on_residual) {
                run.converged = true;
                break;
            }
            if on_residual {
                streak.reset();
                on_residual = false;
            }
            run.stalled |= stall.stalled(run.outer_iterations, run.residual);
            if run.stalled {
                break;
            }
        }
        Ok(run)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sor_sweep_works() {
        // W = [2 1; 1 2] (one contact), q = (−2, 1), r = 0 so x = q.
        let w = Delassus::Dense {
            m: 2,
            w: std::sync::Arc::new(vec![2.0, 1.0, 1.0, 2.0]),
        };
        let inv_diag = [0.5, 0.5];
        let (mut r, mut x) = ([0.0, 0.0], [-2.0, 1.0]);
        // Normal: r_n = max(0, 0 − 1·(−2)/2) = 1, then x += W[:, 0]·1 = (0, 2).
        let change = sor_sweep(&w, &inv_diag, 1.0, 2, 0, &mut r, &mut x, |_, v| v.max(0.0));
        assert_eq!((r, x, change), ([1.0, 0.0], [0.0, 2.0], 1.0));
        // Tangential with s = 0.4 and ω = 1.5: r_t = clamp(0 − 1.5·2/2, −0.4, 0.4) = −0.4.
        let change = sor_sweep(&w, &inv_diag, 1.5, 2, 1, &mut r, &mut x, |_, v| {
            v.clamp(-0.4, 0.4)
        });
        assert_eq!((r, change), ([1.0, -0.4], 1.0));
        assert!((x[0] + 0.4).abs() < 1e-15 && (x[1] - 1.2).abs() < 1e-15);
        // Nothing moves: zero change, x untouched.
        let change = sor_sweep(&w, &inv_diag, 1.0, 2, 1, &mut r, &mut x, |_, v| {
            v.clamp(-0.4, 0.4)
        });
        assert_eq!((r[1], change), (-0.4, 0.0));
    }

    /// Issue 36: a contact whose slip is prescribed (its tangential row and column of `W` are
    /// zero, the diagonal entry written `−0.0`, as the spring condensation of the seed's 5.6.2
    /// shear writes it) slides: `r_t = −μ r_n sign(x_t)`. With `1/W_tt = 1/−0.0 = −∞` the sweep
    /// sent `r_t` to the wrong edge of the cone and the solver never converged (10 000
    /// iterations at a constant residual).
    #[test]
    fn issue_36_classic_slides_a_contact_with_a_prescribed_slip() {
        use crate::{Algorithm, UzawaSolver};
        // contact 0: W_nn = 1, W_tt = −0.0; pressed (q_n = −1), sliding (q_t = 0.5 fixed);
        // contact 1 an ordinary one coupled to contact 0's normal
        #[rustfmt::skip]
        let w = vec![
            1.0, 0.0, 0.2, 0.0,
            0.0, -0.0, 0.0, 0.0,
            0.2, 0.0, 1.0, 0.1,
            0.0, 0.0, 0.1, 0.5,
        ];
        let problem = ReducedProblem::new(w, vec![-1.0, 0.5, -0.5, 0.2], vec![0.3, 0.3]).unwrap();
        let laws = problem.coulomb_laws();
        let settings = UzawaSettings::default()
            .with_algorithm(Algorithm::ClassicRccm)
            .with_fallback(false);
        let sol = UzawaSolver::new(settings).solve(&problem, &laws).unwrap();
        let (r_n, r_t) = (sol.r[0], sol.r[1]);
        // tol 1e-10 on the natural map: the answer to about that, relative to |r| ~ 1
        assert!(
            r_n > 0.5 && sol.x[0].abs() < 1e-8,
            "r_n {r_n}, x_n {}",
            sol.x[0]
        );
        assert!((r_t + 0.3 * r_n).abs() < 1e-8, "r_t {r_t} against −μ r_n");
        // the bipotential sweep gives the same answer
        let gs = UzawaSolver::new(settings.with_algorithm(Algorithm::GaussSeidel))
            .solve(&problem, &laws)
            .unwrap();
        for (a, b) in sol.r.iter().zip(&gs.r) {
            assert!(
                (a - b).abs() < 1e-8,
                "classic {:?} against GS {:?}",
                sol.r,
                gs.r
            );
        }
    }
}
