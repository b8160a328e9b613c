//! A semi-smooth Newton method on De Saxcé's projection equation, selected by
//! [`Algorithm::Newton`](crate::Algorithm::Newton) in [`UzawaSolver`](crate::UzawaSolver).
//!
//! The solutions of the reduced problem are the zeros of the natural map (seed 5.26; De Saxcé,
//! Feng 1998; the same map the stopping rule measures):
//!
//! ```text
//! F(r) = r − P_K(r + ρ v(W r + q)),    per contact  v = −(x_t + (x_n + μ̄|x_t|) n)
//! ```
//! with `ρ_i = ρ⁰_i · rho_scale` and `μ̄_i` the law's
//! [`friction_coefficient`](contact_laws::ContactLaw::friction_coefficient) (Coulomb-type laws
//! only; `None` is [`SolverError::NoFrictionCoefficient`](crate::SolverError)). `F` itself is
//! evaluated with the law's `project` and `modified_velocity`; `μ̄` only enters the
//! generalized Jacobian (Qi, Sun 1993; Alart, Curnier 1991 for the same construction on their
//! augmented Lagrangian):
//!
//! ```text
//! J = I − D_P + ρ D_P S W,       S_i = −∂v_i/∂x_i = [1  μ̄ s_x; 0  1],  s_x = sign(x_t)
//! D_P per case of the projection (seed 5.38, cone.rs):
//!   separation  D_P = 0
//!   stick       D_P = I
//!   slip        D_P = a aᵀ/(1 + μ̄²),   a = (1, μ̄ s_τ),  s_τ = sign(τ_t)
//! ```
//! (`sign(0) = 0` picks one element of the generalized Jacobian at the kink `x_t = 0`.)
//! The Newton system `J Δr = −F` is reduced before it is factorised: a separated contact has
//! `Δr_i = −F_i`; a slipping one has its component along `b = (−μ̄ s_τ, 1)` fixed,
//! `bᵀΔr_i = −bᵀF_i`, and one unknown along `a`; a sticking one keeps both. So the dense
//! system has `2·stick + slip` unknowns, rows `ρ_i⁻¹ (S_i W Δr)_i` (stick) and
//! `ρ_i⁻¹ âᵀ(S_i W Δr)_i` (slip), and is factorised by faer's partial-pivoting LU (by a
//! plain in-crate LU up to 32 unknowns, where faer's fixed cost dominates).
//!
//! **Globalisation.** Armijo backtracking on `φ = ‖F‖²`: the step `t ∈ {1, ½, ¼, …}` is
//! accepted when `φ(r + tΔr) ≤ (1 − 2σt) φ(r)`, `σ = 10⁻⁴`; `x` moves by `t W Δr` (one
//! product per Newton step, none per trial). If the direction is not finite (a singular
//! system) or no `t ≥ 2⁻²⁰` is accepted, one projected Gauss–Seidel sweep is done instead.
//!
//! **Warm-up.** [`WARMUP_SWEEPS`] = 2 projected Gauss–Seidel sweeps run before the first
//! Newton step: they find most of the active set, which saves Newton steps (each a dense
//! factorisation). Measured (release, one thread, cold start, tol 1e-10; problems of
//! `examples/work_precision_local.rs`), time per solve and Newton steps in brackets:
//!
//! ```text
//! warm-up sweeps    0             1             2             3             5
//! random_10         0.0025 ms (2) 0.0028 (2)    0.0022 (1)    0.0032 (1)    0.0028 (1)
//! random_100        0.257 ms (5)  0.185 (3)     0.231 (4)     0.243 (4)     0.217 (3)
//! random_1000       80.6 ms (6)   60.1 (4)      57.6 (4)      71.6 (5)      53.2 (3)
//! hertz_8           0.0102 ms (5) 0.0073 (3)    0.0051 (2)    0.0053 (2)    0.0061 (2)
//! hertz_8_slide     0.0284 ms (7) 0.0120 (5)    0.0083 (3)    0.0073 (2)    0.0079 (2)
//! hertz_64          0.633 ms (9)  0.383 (7)     0.372 (7)     0.340 (6)     0.374 (6)
//! hertz_64_slide    1.470 ms (9)  0.581 (6)     0.671 (7)     0.557 (6)     0.615 (6)
//! ```
//! Any warm-up helps (up to 3.4× on `hertz_8_slide`); between 1 and 5 sweeps the differences
//! are mostly within the noise of this shared machine, and 2 is never more than 20 % from the
//! best column.
//!
//! **Stopping rule.** The rule of the sweeps ([layer docs](crate::local#stopping-rule)), tested
//! after every Newton step or sweep. Once the natural residual (with `ρ⁰`) is `≤ tol`, the
//! iteration goes on with Gauss–Seidel sweeps (usually one) until the change of `r` is `≤ tol`
//! too, and both tests are made on the exact `x = W r + q`. (A Newton step's change is its
//! length, often still large when the residual has already dropped to rounding; and going back
//! to Newton at rounding level can cycle: when `r = 0` is the solution and `q` is rounding
//! noise, the sweep reaches `r = 0` exactly, the Newton step does not — issue 8's stress case
//! "nodes on the LINE, released to exactly 0".)
//! [`UzawaReport::iterations`](crate::UzawaReport) counts Newton steps and sweeps;
//! [`UzawaReport::outer_iterations`](crate::UzawaReport) the Newton steps (LU
//! factorisations).
//!
//! # Examples
//! ```
//! use contact_solver::{Algorithm, UzawaSettings, UzawaSolver, local::generate::random_problem};
//! let p = random_problem(20, 1);
//! let settings = UzawaSettings::default().with_algorithm(Algorithm::Newton);
//! let sol = UzawaSolver::new(settings).solve(&p, &p.coulomb_laws())?;
//! assert!(sol.report.converged && sol.report.outer_iterations < 20);
//! # Ok::<(), contact_solver::SolverError>(())
//! ```

use super::classic::friction_coefficients_into;
use super::problem::ReducedProblem;
use super::residual::{local, natural_residual, norm, pick, set_local};
use super::settings::UzawaSettings;
use super::sweep::Sweeps;
use crate::error::SolverError;
use contact_laws::ContactLaw;
use faer::linalg::solvers::Solve;
use faer::{MatMut, MatRef};

/// Armijo's constant `σ` of the line search.
const ARMIJO: f64 = 1e-4;
/// Projected Gauss–Seidel sweeps before the first Newton step (they find most of the active
/// set); measured in the [module docs](self).
pub const WARMUP_SWEEPS: usize = 2;
/// Halvings of the step before the line search gives up (`t ≥ 2⁻²⁰`).
const MAX_HALVINGS: usize = 20;
/// Newton systems up to this size are factorised by [`lu_solve_in_place`], larger ones by
/// faer. Measured (release, one thread, `examples/probe_lu` in the work–precision notes of
/// `docs/benchmarks.md`): faer's fixed cost dominates below about 40 unknowns
/// (p = 8: 1.0 µs against 0.2 µs; p = 32: 4.9 against 3.9 µs; p = 64: 16 against 21 µs).
const SMALL_SYSTEM: usize = 32;

/// Case of the projection of contact `i` at the current iterate, with the signs the
/// Jacobian needs.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
enum Case {
    #[default]
    Separation,
    Stick,
    Slip,
}

#[derive(Clone, Copy, Debug, Default)]
struct Local {
    case: Case,
    /// `sign(x_t)`, 0 at 0.
    s_x: f64,
    /// `sign(τ_t)`, 0 at 0.
    s_tau: f64,
}

#[inline]
fn sign0(a: f64) -> f64 {
    if a > 0.0 {
        1.0
    } else if a < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// What a Newton solve did.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NewtonRun {
    /// Newton steps plus Gauss–Seidel sweeps.
    pub iterations: usize,
    /// Newton steps (factorisations).
    pub newton_steps: usize,
    /// `true` when the stopping rule was met.
    pub converged: bool,
    /// Relative natural residual at the returned iterate.
    pub residual: f64,
    /// Relative change of the last iteration.
    pub change: f64,
}

/// Scratch buffers of the Newton sweeps, kept in the [`UzawaSolver`](crate::UzawaSolver) and
/// reused across solves.
#[derive(Clone, Debug, Default)]
pub(crate) struct NewtonScratch {
    mu_bar: Vec<f64>,
    /// `ρ_i = ρ⁰_i · rho_scale` of the map `F`.
    rho: Vec<f64>,
    f: Vec<f64>,
    f_try: Vec<f64>,
    cases: Vec<Local>,
    cases_try: Vec<Local>,
    dr: Vec<f64>,
    wdr: Vec<f64>,
    r_try: Vec<f64>,
    x_try: Vec<f64>,
    /// The known part `d` of `Δr` and `W d`.
    d: Vec<f64>,
    wd: Vec<f64>,
    /// Equations `(contact, l_n, l_t, rhs)`: `l · (W Δr)_i = rhs`.
    rows: Vec<(usize, f64, f64, f64)>,
    /// Unknowns `(contact, z_n, z_t)`: `Δr_j += y_u z`.
    cols: Vec<(usize, f64, f64)>,
    /// `W z` of one unknown.
    wcol: Vec<f64>,
    /// The Newton matrix, column-major `p × p`, and its right-hand side.
    a: Vec<f64>,
    b: Vec<f64>,
}

/// Solves `a y = b` in place (`y` into `b`) by Gaussian elimination with partial pivoting;
/// `a` is column-major `p × p` and is overwritten by its LU factors. Returns `false` on a zero
/// pivot.
///
/// # Panics
/// If `a.len() != p²` or `b.len() != p`.
#[track_caller]
fn lu_solve_in_place(a: &mut [f64], b: &mut [f64]) -> bool {
    let p = b.len();
    assert_eq!(a.len(), p * p, "a must be p × p");
    for k in 0..p {
        let (mut pivot, mut best) = (k, a[k * p + k].abs());
        for i in k + 1..p {
            if a[k * p + i].abs() > best {
                (pivot, best) = (i, a[k * p + i].abs());
            }
        }
        if best == 0.0 || !best.is_finite() {
            return false;
        }
        if pivot != k {
            for j in 0..p {
                a.swap(j * p + k, j * p + pivot);
            }
            b.swap(k, pivot);
        }
        let inv = 1.0 / a[k * p + k];
        a[k * p + k + 1..(k + 1) * p]
            .iter_mut()
            .for_each(|l| *l *= inv);
        let (left, right) = a.split_at_mut((k + 1) * p);
        let col_k = &left[k * p..];
        for col in right.chunks_exact_mut(p) {
            let a_kj = col[k];
            if a_kj != 0.0 {
                for (c, l) in col[k + 1..].iter_mut().zip(&col_k[k + 1..]) {
                    *c -= l * a_kj;
                }
            }
        }
        let b_k = b[k];
        for (c, l) in b[k + 1..].iter_mut().zip(&col_k[k + 1..]) {
            *c -= l * b_k;
        }
    }
    for k in (0..p).rev() {
        b[k] /= a[k * p + k];
        let b_k = b[k];
        for (c, u) in b[..k].iter_mut().zip(&a[k * p..k * p + k]) {
            *c -= u * b_k;
        }
    }
    true
}

/// `F(r)` into `f` and the cases into `cases`; returns `‖F‖²`.
#[allow(clippy::too_many_arguments)]
fn eval<L: ContactLaw>(
    laws: &[L],
    states: &[L::State],
    rho: &[f64],
    mu_bar: &[f64],
    r: &[f64],
    x: &[f64],
    f: &mut [f64],
    cases: &mut [Local],
) -> f64 {
    let mut s2 = 0.0;
    for (i, c) in cases.iter_mut().enumerate() {
        let (law, s) = (pick(laws, i), pick(states, i));
        let (ri, xi) = (local(r, i), local(x, i));
        let tau = ri + law.modified_velocity(&xi, s) * rho[i];
        let d = ri - law.project(&tau, s);
        set_local(f, i, &d);
        s2 += d.dot(&d);
        let (mu, tt) = (mu_bar[i], tau.t[0].abs());
        let case = if mu * tt <= -tau.n {
            Case::Separation
        } else if tt <= mu * tau.n && mu > 0.0 {
            // (With μ̄ = 0, P = (τ_n⁺, 0) has the Jacobian diag(1, 0) of the slip case even at
            // τ_t = 0, and the tangential unknowns drop out of the system.)
            Case::Stick
        } else {
            Case::Slip
        };
        *c = Local {
            case,
            s_x: sign0(xi.t[0]),
            s_tau: sign0(tau.t[0]),
        };
    }
    s2
}

/// `out = W v`, skipping the zero entries of `v` (`W` symmetric: rows are columns).
fn product_into(w: &[f64], v: &[f64], out: &mut [f64]) {
    let m = v.len();
    out.iter_mut().for_each(|a| *a = 0.0);
    for (j, &vj) in v.iter().enumerate() {
        if vj != 0.0 {
            out.iter_mut()
                .zip(&w[j * m..(j + 1) * m])
                .for_each(|(a, b)| *a += b * vj);
        }
    }
}

/// The relative natural residual of the stopping rule at `(r, x)`: `√φ` when `F` uses `ρ⁰`
/// itself, recomputed with `ρ⁰` otherwise.
#[allow(clippy::too_many_arguments)]
fn relative_residual<L: ContactLaw>(
    sweeps: &Sweeps,
    laws: &[L],
    states: &[L::State],
    exact_rho: bool,
    phi: f64,
    denom_q: f64,
    r: &[f64],
    x: &[f64],
) -> f64 {
    let absolute = if exact_rho {
        phi.sqrt()
    } else {
        natural_residual(laws, states, sweeps.rho0(), r, x)
    };
    absolute / norm(r).max(denom_q).max(f64::MIN_POSITIVE)
}

impl NewtonScratch {
    /// `F` and the cases at `(r, x)` into `self.f`, `self.cases`; returns `‖F‖²`.
    fn refresh<L: ContactLaw>(
        &mut self,
        laws: &[L],
        states: &[L::State],
        r: &[f64],
        x: &[f64],
    ) -> f64 {
        eval(
            laws,
            states,
            &self.rho,
            &self.mu_bar,
            r,
            x,
            &mut self.f,
            &mut self.cases,
        )
    }

    fn resize(&mut self, m: usize) {
        for buf in [
            &mut self.f,
            &mut self.f_try,
            &mut self.dr,
            &mut self.wdr,
            &mut self.r_try,
            &mut self.x_try,
            &mut self.d,
            &mut self.wd,
            &mut self.wcol,
        ] {
            buf.clear();
            buf.resize(m, 0.0);
        }
        self.cases.clear();
        self.cases.resize(m / 2, Local::default());
        self.cases_try.clear();
        self.cases_try.resize(m / 2, Local::default());
    }

    /// The Newton direction `Δr` (into `self.dr`) from `self.f` and `self.cases`; `false` if
    /// it is not finite.
    fn direction(&mut self, problem: &ReducedProblem) -> bool {
        let (m, w) = (problem.size(), problem.w());
        self.rows.clear();
        self.cols.clear();
        self.d.iter_mut().for_each(|a| *a = 0.0);
        for (i, c) in self.cases.iter().enumerate() {
            let (f_n, f_t) = (self.f[2 * i], self.f[2 * i + 1]);
            let (rho, mu) = (self.rho[i], self.mu_bar[i]);
            match c.case {
                Case::Separation => {
                    self.d[2 * i] = -f_n;
                    self.d[2 * i + 1] = -f_t;
                }
                Case::Stick => {
                    self.cols.push((i, 1.0, 0.0));
                    self.rows.push((i, 1.0, mu * c.s_x, -f_n / rho));
                    if w[(2 * i + 1) * m + 2 * i + 1] == 0.0 {
                        // Tangentially supported contact (x_t = q_t fixed): no equation for
                        // Δr_t, which takes the fixed-point step.
                        self.d[2 * i + 1] = -f_t;
                    } else {
                        self.cols.push((i, 0.0, 1.0));
                        self.rows.push((i, 0.0, 1.0, -f_t / rho));
                    }
                }
                Case::Slip => {
                    let k = 1.0 / (1.0 + mu * mu).sqrt();
                    let (a_n, a_t) = (k, k * mu * c.s_tau);
                    let (b_n, b_t) = (-k * mu * c.s_tau, k);
                    let beta = -(b_n * f_n + b_t * f_t);
                    self.d[2 * i] = beta * b_n;
                    self.d[2 * i + 1] = beta * b_t;
                    self.cols.push((i, a_n, a_t));
                    let rhs = -(a_n * f_n + a_t * f_t) / rho;
                    self.rows.push((i, a_n, a_n * mu * c.s_x + a_t, rhs));
                }
            }
        }
        self.dr.copy_from_slice(&self.d);
        let p = self.cols.len();
        if p > 0 {
            product_into(w, &self.d, &mut self.wd);
            self.a.clear();
            self.a.resize(p * p, 0.0);
            for (&(j, z_n, z_t), col) in self.cols.iter().zip(self.a.chunks_exact_mut(p)) {
                // W z, read as rows 2j, 2j+1 (W symmetric).
                let (row_n, row_t) = (&w[2 * j * m..(2 * j + 1) * m], &w[(2 * j + 1) * m..]);
                for ((o, a), b) in self.wcol.iter_mut().zip(row_n).zip(row_t) {
                    *o = z_n * a + z_t * b;
                }
                for (c, &(i, l_n, l_t, _)) in col.iter_mut().zip(&self.rows) {
                    *c = l_n * self.wcol[2 * i] + l_t * self.wcol[2 * i + 1];
                }
            }
            self.b.clear();
            self.b.extend(
                self.rows
                    .iter()
                    .map(|&(i, l_n, l_t, b)| b - (l_n * self.wd[2 * i] + l_t * self.wd[2 * i + 1])),
            );
            if p <= SMALL_SYSTEM {
                if !lu_solve_in_place(&mut self.a, &mut self.b) {
                    return false;
                }
            } else {
                let a = MatRef::from_column_major_slice(&self.a, p, p);
                let rhs = MatMut::from_column_major_slice_mut(&mut self.b, p, 1);
                a.partial_piv_lu().solve_in_place(rhs);
            }
            for (&(j, z_n, z_t), &y) in self.cols.iter().zip(&self.b) {
                self.dr[2 * j] += y * z_n;
                self.dr[2 * j + 1] += y * z_t;
            }
        }
        self.dr.iter().all(|a| a.is_finite())
    }

    /// Runs the Newton iteration from `(r, x)` (`x = W r + q`); on return `(r, x)` is the last
    /// iterate. `denom_q = max_i ρ⁰_i ‖q‖`.
    ///
    /// # Errors
    /// [`SolverError::NoFrictionCoefficient`] / [`SolverError::InvalidLaw`] if a law's
    /// `friction_coefficient` is `None` / not finite and `≥ 0`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn solve<L: ContactLaw>(
        &mut self,
        sweeps: &mut Sweeps,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        settings: &UzawaSettings,
        denom_q: f64,
        r: &mut [f64],
        x: &mut [f64],
        history: &mut Vec<f64>,
    ) -> Result<NewtonRun, SolverError> {
        let (nc, m) = (problem.contact_count(), problem.size());
        friction_coefficients_into(laws, states, nc, &mut self.mu_bar)?;
        self.resize(m);
        self.rho.clear();
        self.rho
            .extend(sweeps.rho0().iter().map(|a| a * settings.rho_scale));
        let exact_rho = settings.rho_scale == 1.0;
        let tol = settings.tol;
        let mut run = NewtonRun {
            iterations: 0,
            newton_steps: 0,
            converged: false,
            residual: f64::INFINITY,
            change: f64::INFINITY,
        };
        let mut phi = self.refresh(laws, states, r, x);
        // Once the residual is ≤ tol, sweeps polish r until the change is ≤ tol too.
        let mut polishing = false;
        while run.iterations < settings.max_iterations {
            run.iterations += 1;
            let mut stepped = false;
            let warming_up = run.iterations <= WARMUP_SWEEPS;
            if !warming_up && !polishing && self.direction(problem) {
                product_into(problem.w(), &self.dr, &mut self.wdr);
                let mut t = 1.0;
                for _ in 0..=MAX_HALVINGS {
                    for k in 0..m {
                        self.r_try[k] = r[k] + t * self.dr[k];
                        self.x_try[k] = x[k] + t * self.wdr[k];
                    }
                    let phi_try = eval(
                        laws,
                        states,
                        &self.rho,
                        &self.mu_bar,
                        &self.r_try,
                        &self.x_try,
                        &mut self.f_try,
                        &mut self.cases_try,
                    );
                    if phi_try <= (1.0 - 2.0 * ARMIJO * t) * phi {
                        stepped = true;
                        phi = phi_try;
                        break;
                    }
                    t *= 0.5;
                }
                if stepped {
                    run.newton_steps += 1;
                    r.copy_from_slice(&self.r_try);
                    x.copy_from_slice(&self.x_try);
                    std::mem::swap(&mut self.f, &mut self.f_try);
                    std::mem::swap(&mut self.cases, &mut self.cases_try);
                    run.change = t * norm(&self.dr) / norm(r).max(f64::MIN_POSITIVE);
                }
            }
            if !stepped {
                // Warm-up, polishing or fallback: one projected Gauss–Seidel sweep.
                let dr2 = sweeps.gauss_seidel_sweep(problem, laws, states, r, x);
                run.change = dr2.sqrt() / norm(r).max(f64::MIN_POSITIVE);
                phi = self.refresh(laws, states, r, x);
            }
            run.residual = relative_residual(sweeps, laws, states, exact_rho, phi, denom_q, r, x);
            if run.residual <= tol && run.change <= tol {
                // x was updated incrementally: confirm on the exact x = W r + q.
                problem.displacement_into(r, x);
                phi = self.refresh(laws, states, r, x);
                run.residual =
                    relative_residual(sweeps, laws, states, exact_rho, phi, denom_q, r, x);
            }
            history.push(run.residual);
            if run.residual <= tol && run.change <= tol {
                run.converged = true;
                break;
            }
            polishing = run.residual <= tol;
        }
        Ok(run)
    }
}
