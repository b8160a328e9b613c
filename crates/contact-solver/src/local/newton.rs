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
//! J = I − D_P + ρ D_P S W,       S_i = −∂v_i/∂x_i = [1  μ̄ ŝ_xᵀ; 0  I],  ŝ_x = x_t/‖x_t‖
//! D_P per case of the projection (seed 5.38, cone.rs), with γ = (τ_n + μ̄‖τ_t‖)/(1 + μ̄²):
//!   separation  D_P = 0
//!   stick       D_P = I
//!   slip        D_P = â âᵀ + κ e eᵀ,   â = (1, μ̄ ŝ_τ)/√(1 + μ̄²),  ŝ_τ = τ_t/‖τ_t‖,
//!               e = (0, ŝ_τ⊥),  κ = γ μ̄/‖τ_t‖ ∈ [0, 1)         (e, κ: 3D only)
//! ```
//! (`ŝ = 0` at 0 picks one element of the generalized Jacobian at the kink `x_t = 0`.) The slip
//! case in 3D is the derivative of `P(τ) = γ (1, μ̄ ŝ_τ)`: `â âᵀ` from `γ`, `κ e eᵀ` from the
//! turning of `ŝ_τ` (`∂ŝ/∂τ_t = (I − ŝŝᵀ)/‖τ_t‖`); `tests/integration/reduced_3d.rs` checks it
//! against finite differences of the law's own projection along random directions.
//!
//! The Newton system `J Δr = −F` is reduced before it is factorised, per contact in the
//! eigenvectors `u` of the symmetric `D_P` (eigenvalue `λ`):
//! - `λ = 0` (separation; the slip case's `b ⊥ â, e`): a known component, `uᵀΔr_i = −uᵀF_i`;
//! - `λ = 1` (stick; `â` in slip): one unknown `y_u` along `u` and the row
//!   `ρ_i⁻¹ uᵀ(S_i W Δr)_i = −ρ_i⁻¹ uᵀF_i`;
//! - `0 < λ < 1` (`e` in 3D slip): one unknown and the row
//!   `(1 − λ)/(ρ_i λ) y_u + uᵀ(S_i W Δr)_i = −uᵀF_i/(ρ_i λ)`.
//!
//! So the dense system has `d·stick + slip (+ slip with μ̄ > 0 in 3D)` unknowns and is
//! factorised by faer's partial-pivoting LU (by a plain in-crate LU up to 32 unknowns, where
//! faer's fixed cost dominates) when `W` is dense.
//!
//! **Sparse `W`.** The system is assembled on the block pattern of `W` restricted to the
//! unknowns (`O(stored entries)` per unknown) in faer's compressed columns and factorised by
//! faer's sparse LU with partial pivoting ([`sparse`](self#sparse-w)); nothing is densified, so
//! Newton runs on a sparse problem of any size (a 2000-contact 3D problem in
//! `tests/integration/sparse.rs`).
//!
//! **Globalisation.** Armijo backtracking on `φ = ‖F‖²`: the step `t ∈ {1, ½, ¼, …}` is
//! accepted when `φ(r + tΔr) ≤ (1 − 2σt) φ(r)`, `σ = 10⁻⁴`; `x` moves by `t W Δr` (one
//! product per Newton step, none per trial). If the direction is not finite (a singular
//! system) or no `t ≥ 2⁻²⁰` is accepted, the step is retried with a proximal regularisation
//! of the Jacobian, and when that fails too one projected Gauss–Seidel sweep is done instead.
//!
//! **Proximal regularisation** (issue 37; `src/local/newton/proximal.rs`). On a semidefinite
//! or rank-deficient `W` (redundant contacts of rigid bodies) the sticking rows `S W Δr` are
//! singular and the steps creep. The Jacobian is then taken with `W + ε_i I`, `ε_i = η/ρ_i`
//! (`F` keeps `W`): `η = 0` until a step fails or is short (`t ≤ 2⁻⁵`), then `η ← max(10 η,
//! 10⁻⁶)` up to 1, a failed step retried at once (at most 3 times); a full step divides `η`
//! by 10, to 0 below 10⁻⁶. A run without failed or short steps is the plain Newton's, bit for
//! bit. Measured in `docs/benchmarks.md` "Newton on semidefinite W (issue 37)". In `Auto`'s
//! last Newton, when the steps keep creeping (10 short or failed ones), `ρ` is raised tenfold,
//! up to `10³ ρ⁰` (`src/local/newton/rho_raise.rs`; `docs/benchmarks.md` "spheres in a box
//! (issue 37)").
//!
//! **Warm-up.** `WARMUP_SWEEPS` = 2 projected Gauss–Seidel sweeps run before the first
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
//! "nodes on the LINE, released to exactly 0".) The residual alone also stops it after a long
//! streak `≤ tol` (`residual_stop`).
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
use super::delassus::Delassus;
use super::problem::ReducedProblem;
use super::residual::{local, natural_residual, norm, pick, set_local};
use super::residual_stop::ResidualStop;
use super::settings::{AUTO_NEWTON_SHORT_STEPS, UzawaSettings};
use super::stall::StallDetector;
use super::sweep::Sweeps;
use crate::error::SolverError;
use contact_laws::ContactLaw;
use faer::linalg::solvers::Solve;
use faer::{MatMut, MatRef};

mod lu;
mod probe;
mod proximal;
mod rho_raise;
mod sparse;
use lu::lu_solve_in_place;
pub(crate) use probe::NewtonProbe;
pub(crate) use sparse::factor_fill;

/// Armijo's constant `σ` of the line search.
const ARMIJO: f64 = 1e-4;
/// Projected Gauss–Seidel sweeps before the first Newton step (they find most of the active
/// set); measured in the [module docs](self).
pub(crate) const WARMUP_SWEEPS: usize = 2;
/// Halvings of the step before the line search gives up (`t ≥ 2⁻²⁰`).
const MAX_HALVINGS: usize = 20;
/// Newton systems up to this size are factorised by [`lu_solve_in_place`], larger ones by
/// faer. Measured (release, one thread, `examples/probe_lu` in the work–precision notes of
/// `docs/benchmarks.md`): faer's fixed cost dominates below about 40 unknowns
/// (p = 8: 1.0 µs against 0.2 µs; p = 32: 4.9 against 3.9 µs; p = 64: 16 against 21 µs).
const SMALL_SYSTEM: usize = 32;
/// On a sparse `W` of at most this many rows a Newton system of at most `SMALL_SYSTEM`
/// unknowns is assembled dense and solved by [`lu_solve_in_place`] (issue 37, seventh part):
/// faer's sparse LU orders and factorises symbolically at every step, which was most of
/// Newton's time on Siconos' small sparse problems (3–28 contacts, 3–4× the classical solver).
const SMALL_SPARSE_ROWS: usize = 512;

/// Case of the projection of contact `i` at the current iterate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
enum Case {
    #[default]
    Separation,
    Stick,
    Slip,
}

/// What the Jacobian needs of contact `i` at the current iterate (3-arrays, the last entry 0 in
/// 2D).
#[derive(Clone, Copy, Debug, Default)]
struct Local {
    case: Case,
    /// `ŝ_x = x_t/‖x_t‖` (0 at 0), in the tangent plane.
    s_x: [f64; 2],
    /// `ŝ_τ = τ_t/‖τ_t‖` (the first tangent at 0), in the tangent plane.
    s_tau: [f64; 2],
    /// `κ = γ μ̄/‖τ_t‖` of the slip case (3D).
    kappa: f64,
}

/// `t/‖t‖` of the first `DT` entries, or `zero` when `t = 0`.
#[inline]
fn unit<const DT: usize>(t: &[f64], zero: [f64; 2]) -> [f64; 2] {
    let n = if DT == 1 {
        t[0].abs()
    } else {
        t[0].hypot(t[1])
    };
    if n > 0.0 {
        if DT == 1 {
            [t[0] / n, 0.0]
        } else {
            [t[0] / n, t[1] / n]
        }
    } else {
        zero
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
    /// `true` when the [stall detector](super::stall) stopped the run.
    pub stalled: bool,
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
    /// Equations `(contact, l, diagonal, rhs)`: `l · (W Δr)_i + diagonal · y = rhs`, with `y`
    /// the unknown of the same index.
    rows: Vec<(usize, [f64; 3], f64, f64)>,
    /// Unknowns `(contact, z)`: `Δr_j += y z`.
    cols: Vec<(usize, [f64; 3])>,
    /// `W z` of one unknown.
    wcol: Vec<f64>,
    /// The Newton matrix, column-major `p × p` (dense `W`), and its right-hand side.
    a: Vec<f64>,
    b: Vec<f64>,
    /// Sparse `W`: the matrix in compressed columns and its kept symbolic LU.
    sparse: sparse::SparseNewton,
    /// Set by [`Algorithm::Auto`](super::settings::Algorithm::Auto) for the run of a Newton it
    /// chose: when the run gives up (neither converged nor stalled), so that the accelerated
    /// sweep takes over ([`probe`]).
    pub(crate) probe: NewtonProbe,
    /// Set by [`Algorithm::Auto`](super::settings::Algorithm::Auto) for its last Newton
    /// (after the sweep it switched to failed too): `ρ` is raised when the steps creep
    /// ([`rho_raise`]).
    pub(crate) raise_rho: bool,
    /// `η` of the [proximal regularisation](proximal) (`W + ε_i I`, `ε_i = η/ρ_i`, in the
    /// Jacobian); 0 off.
    eta: f64,
}

/// `F(r)` into `f` and the cases into `cases`; returns `‖F‖²`.
#[allow(clippy::too_many_arguments)]
fn eval<L: ContactLaw, const DT: usize>(
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
        let (ri, xi) = (local::<DT>(r, i), local::<DT>(x, i));
        let tau = ri + law.modified_velocity(&xi, s) * rho[i];
        let d = ri - law.project(&tau, s);
        set_local(f, i, &d);
        s2 += d.dot(&d);
        let (mu, tt) = (mu_bar[i], tau.t_norm());
        let case = if mu * tt <= -tau.n {
            Case::Separation
        } else if tt <= mu * tau.n && mu > 0.0 {
            // (With μ̄ = 0, P = (τ_n⁺, 0) has the Jacobian diag(1, 0) of the slip case even at
            // τ_t = 0, and the tangential unknowns drop out of the system.)
            Case::Stick
        } else {
            Case::Slip
        };
        let kappa = if case == Case::Slip && DT == 2 && tt > 0.0 {
            (tau.n + mu * tt) / (1.0 + mu * mu) * mu / tt
        } else {
            0.0
        };
        *c = Local {
            case,
            s_x: unit::<DT>(xi.t.as_slice(), [0.0; 2]),
            s_tau: unit::<DT>(tau.t.as_slice(), [1.0, 0.0]),
            kappa,
        };
    }
    s2
}

/// The relative natural residual of the stopping rule at `(r, x)`: `√φ` when `F` uses `ρ⁰`
/// itself, recomputed with `ρ⁰` otherwise.
#[allow(clippy::too_many_arguments)]
fn relative_residual<L: ContactLaw, const DT: usize>(
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
        natural_residual::<L, DT>(laws, states, sweeps.rho0(), r, x)
    };
    absolute / norm(r).max(denom_q).max(f64::MIN_POSITIVE)
}

impl NewtonScratch {
    /// `F` and the cases at `(r, x)` into `self.f`, `self.cases`; returns `‖F‖²`.
    fn refresh<L: ContactLaw, const DT: usize>(
        &mut self,
        laws: &[L],
        states: &[L::State],
        r: &[f64],
        x: &[f64],
    ) -> f64 {
        eval::<L, DT>(
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

    fn resize(&mut self, m: usize, nc: usize) {
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
        self.cases.resize(nc, Local::default());
        self.cases_try.clear();
        self.cases_try.resize(nc, Local::default());
    }

    /// The equations and unknowns of contact `i` (see the [module docs](self)) into
    /// `self.rows`, `self.cols`, and its known part into `self.d`.
    #[allow(clippy::needless_range_loop)] // offsets b + k into flat vectors
    fn contact_system<const DT: usize>(&mut self, i: usize, c: &Local, block: &[[f64; 3]; 3]) {
        let d = DT + 1;
        let b = d * i;
        let (rho, mu) = (self.rho[i], self.mu_bar[i]);
        let f = [
            self.f[b],
            self.f[b + 1],
            if DT == 2 { self.f[b + 2] } else { 0.0 },
        ];
        let dot = |u: &[f64; 3]| u[0] * f[0] + u[1] * f[1] + u[2] * f[2];
        // l = S_iᵀ u: the row of `uᵀ (S_i W Δr)_i`.
        let row = |u: &[f64; 3]| {
            [
                u[0],
                mu * c.s_x[0] * u[0] + u[1],
                mu * c.s_x[1] * u[0] + u[2],
            ]
        };
        let known = |u: &[f64; 3], d_out: &mut [f64]| {
            let beta = -dot(u);
            for k in 0..d {
                d_out[b + k] += beta * u[k];
            }
        };
        match c.case {
            Case::Separation => {
                for k in 0..d {
                    self.d[b + k] = -f[k];
                }
            }
            Case::Stick => {
                for k in 0..d {
                    let mut u = [0.0; 3];
                    u[k] = 1.0;
                    if k > 0 && block[k][k] == 0.0 {
                        // Tangentially supported contact (x_t = q_t fixed): no equation for
                        // Δr_t, which takes the fixed-point step.
                        self.d[b + k] = -f[k];
                    } else {
                        self.cols.push((i, u));
                        self.rows.push((i, row(&u), 0.0, -f[k] / rho));
                    }
                }
            }
            Case::Slip => {
                let k = 1.0 / (1.0 + mu * mu).sqrt();
                let [s1, s2] = c.s_tau;
                let a = [k, k * mu * s1, k * mu * s2];
                let bvec = [-k * mu, k * s1, k * s2];
                known(&bvec, &mut self.d);
                self.cols.push((i, a));
                self.rows.push((i, row(&a), 0.0, -dot(&a) / rho));
                if DT == 2 {
                    let e = [0.0, -s2, s1];
                    if c.kappa > 0.0 {
                        let kappa = c.kappa;
                        self.cols.push((i, e));
                        let diagonal = (1.0 - kappa) / (rho * kappa);
                        self.rows
                            .push((i, row(&e), diagonal, -dot(&e) / (rho * kappa)));
                    } else {
                        known(&e, &mut self.d);
                    }
                }
            }
        }
    }

    /// Assembles the dense `p × p` Newton matrix of `self.rows`/`self.cols` and solves it in
    /// place of `self.b`; `false` on a zero pivot of the small in-crate LU.
    fn dense_solve<const DT: usize>(&mut self, w: &Delassus) -> bool {
        let (d, p) = (DT + 1, self.cols.len());
        self.a.clear();
        self.a.resize(p * p, 0.0);
        for (jc, (&(j, z), col)) in self.cols.iter().zip(self.a.chunks_exact_mut(p)).enumerate() {
            // W z, read as rows d j + k of `columns`.
            let b = d * j;
            self.wcol.iter_mut().for_each(|o| *o = 0.0);
            for (k, &zk) in z.iter().enumerate().take(d) {
                if zk != 0.0 {
                    w.axpy_row(b + k, zk, &mut self.wcol);
                }
            }
            for (ir, (c, &(i, l, diagonal, _))) in col.iter_mut().zip(&self.rows).enumerate() {
                let bi = d * i;
                *c = (0..d).map(|k| l[k] * self.wcol[bi + k]).sum::<f64>();
                if i == j && self.eta > 0.0 {
                    *c += self.eta / self.rho[i] * (0..d).map(|k| l[k] * z[k]).sum::<f64>();
                }
                if ir == jc {
                    *c += diagonal;
                }
            }
        }
        if p <= SMALL_SYSTEM {
            lu_solve_in_place(&mut self.a, &mut self.b)
        } else {
            let a = MatRef::from_column_major_slice(&self.a, p, p);
            let rhs = MatMut::from_column_major_slice_mut(&mut self.b, p, 1);
            a.partial_piv_lu().solve_in_place(rhs);
            true
        }
    }

    /// The Newton direction `Δr` (into `self.dr`) from `self.f` and `self.cases`; `false` if
    /// it is not finite.
    #[allow(clippy::needless_range_loop)] // offsets d j + k into flat vectors
    fn direction<const DT: usize>(&mut self, problem: &ReducedProblem) -> bool {
        // rows of `columns` are the columns of W (W itself unless a non-symmetric W is kept)
        let (w, d) = (problem.columns(), DT + 1);
        self.rows.clear();
        self.cols.clear();
        self.d.iter_mut().for_each(|a| *a = 0.0);
        for i in 0..self.cases.len() {
            let c = self.cases[i];
            self.contact_system::<DT>(i, &c, &problem.diagonal_block(i));
        }
        self.dr.copy_from_slice(&self.d);
        let p = self.cols.len();
        if p > 0 {
            w.mul_into(&self.d, &mut self.wd);
            if self.eta > 0.0 {
                for (k, (o, dk)) in self.wd.iter_mut().zip(&self.d).enumerate() {
                    *o += self.eta / self.rho[k / d] * dk;
                }
            }
            self.b.clear();
            self.b.extend(self.rows.iter().map(|&(i, l, _, rhs)| {
                rhs - (0..d).map(|k| l[k] * self.wd[d * i + k]).sum::<f64>()
            }));
            let small = p <= SMALL_SYSTEM && problem.size() <= SMALL_SPARSE_ROWS;
            let solved = match w {
                Delassus::Sparse(a) if !small => self.sparse_solve::<DT>(a),
                _ => self.dense_solve::<DT>(w),
            };
            if !solved {
                return false;
            }
            for (&(j, z), &y) in self.cols.iter().zip(&self.b) {
                for k in 0..d {
                    self.dr[d * j + k] += y * z[k];
                }
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
    pub(crate) fn solve<L: ContactLaw, const DT: usize>(
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
        self.resize(m, nc);
        self.rho.clear();
        self.rho
            .extend(sweeps.rho0().iter().map(|a| a * settings.tuning.rho_scale));
        let mut exact_rho = settings.tuning.rho_scale == 1.0;
        let mut raise = rho_raise::RhoRaise::default();
        let tol = settings.tol;
        let mut run = NewtonRun {
            iterations: 0,
            newton_steps: 0,
            converged: false,
            stalled: false,
            residual: f64::INFINITY,
            change: f64::INFINITY,
        };
        let mut phi = self.refresh::<L, DT>(laws, states, r, x);
        // Once the residual is ≤ tol, sweeps polish r until the change is ≤ tol too.
        let mut polishing = false;
        let mut stall = StallDetector::new(settings.tuning.stall_window);
        let mut streak = ResidualStop::default();
        // Auto's probe: Newton steps so far, and the short ones after the first
        let (mut steps_tried, mut short_steps) = (0usize, 0usize);
        self.eta = 0.0;
        'outer: while run.iterations < settings.max_iterations {
            run.iterations += 1;
            let mut stepped = false;
            let warming_up = run.iterations <= WARMUP_SWEEPS;
            let mut t = 0.0;
            let mut attempt = 0;
            if !warming_up && !polishing {
                loop {
                    if self.direction::<DT>(problem) {
                        problem.columns().mul_into(&self.dr, &mut self.wdr);
                        t = 1.0;
                        for _ in 0..=MAX_HALVINGS {
                            for k in 0..m {
                                self.r_try[k] = r[k] + t * self.dr[k];
                                self.x_try[k] = x[k] + t * self.wdr[k];
                            }
                            let phi_try = eval::<L, DT>(
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
                        steps_tried += 1;
                        if steps_tried > 1 && self.probe.counts_short(stepped, t) {
                            short_steps += 1;
                            if short_steps >= AUTO_NEWTON_SHORT_STEPS {
                                // give up without a step (the iteration is not counted): the
                                // accelerated sweep takes over
                                run.iterations -= 1;
                                break 'outer;
                            }
                        }
                    }
                    // the proximal regularisation: a failed step is retried with a larger η
                    let retry;
                    (self.eta, retry) = proximal::next_eta(self.eta, stepped, t);
                    if stepped || !retry || attempt == proximal::RETRIES {
                        break;
                    }
                    attempt += 1;
                }
            }
            if stepped {
                run.newton_steps += 1;
                r.copy_from_slice(&self.r_try);
                x.copy_from_slice(&self.x_try);
                std::mem::swap(&mut self.f, &mut self.f_try);
                std::mem::swap(&mut self.cases, &mut self.cases_try);
                run.change = t * norm(&self.dr) / norm(r).max(f64::MIN_POSITIVE);
            }
            if !stepped {
                // Warm-up, polishing or fallback: one projected Gauss–Seidel sweep.
                let dr2 = sweeps.gauss_seidel_sweep::<L, DT>(problem, laws, states, r, x);
                run.change = dr2.sqrt() / norm(r).max(f64::MIN_POSITIVE);
                phi = self.refresh::<L, DT>(laws, states, r, x);
            }
            if self.raise_rho
                && !warming_up
                && !polishing
                && let Some(f) = raise.after(stepped, t)
            {
                self.rho.iter_mut().for_each(|a| *a *= f);
                exact_rho = false;
                phi = self.refresh::<L, DT>(laws, states, r, x);
            }
            run.residual =
                relative_residual::<L, DT>(sweeps, laws, states, exact_rho, phi, denom_q, r, x);
            // the second way to stop: a long streak of residuals ≤ tol (`residual_stop`)
            let on_residual = streak.met(run.iterations, run.residual, run.change, tol)
                || self.probe.stops_on_residual(run.residual, tol);
            if (run.residual <= tol && run.change <= tol) || on_residual {
                // x was updated incrementally: confirm on the exact x = W r + q.
                problem.displacement_into(r, x);
                phi = self.refresh::<L, DT>(laws, states, r, x);
                run.residual =
                    relative_residual::<L, DT>(sweeps, laws, states, exact_rho, phi, denom_q, r, x);
            }
            history.push(run.residual);
            if run.residual <= tol && (run.change <= tol || on_residual) {
                run.converged = true;
                break;
            }
            if on_residual {
                streak.reset();
            }
            if stall.stalled(run.iterations, run.residual) {
                run.stalled = true;
                break;
            }
            if self.probe.gives_up(history) {
                break;
            }
            polishing = run.residual <= tol;
        }
        Ok(run)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::generate::{SplitMix64, random_problem_in, random_sparse_problem};

    /// The Newton direction solves `J Δr = −F` with `J` the generalized Jacobian: checked
    /// against the directional derivative of `F` along `Δr` by central differences
    /// (`h = 1e-7 ‖r‖/‖Δr‖`, error `O(h²)` away from the kinks of the projection), at random
    /// points of random 2D and 3D problems where every case of the projection occurs. In 3D
    /// the slip case's curvature term `κ e eᵀ` is exercised (a wrong `κ` fails by O(1)).
    #[test]
    fn direction_solves_the_finite_difference_newton_system() {
        let mut cases_seen = [0usize; 3];
        for (dim, seed) in [(2, 1), (2, 2), (3, 3), (3, 4), (3, 5), (3, 6)] {
            let p = random_problem_in(dim, 6, seed);
            let (m, nc) = (p.size(), p.contact_count());
            let laws = p.coulomb_laws();
            let states = vec![(); nc];
            let mut sweeps = Sweeps::default();
            sweeps.reset(&p, 1.0);
            let mut nw = NewtonScratch::default();
            friction_coefficients_into(&laws, &states, nc, &mut nw.mu_bar).unwrap();
            nw.resize(m, nc);
            nw.rho = sweeps.rho0().to_vec();
            let mut g = SplitMix64::new(seed + 100);
            for _ in 0..20 {
                let r: Vec<f64> = (0..m).map(|_| g.uniform(-0.5, 1.5)).collect();
                let mut x = vec![0.0; m];
                p.displacement_into(&r, &mut x);
                let (rho, mu_bar) = (nw.rho.clone(), nw.mu_bar.clone());
                let f_of = |r: &[f64]| {
                    let mut x = vec![0.0; m];
                    p.displacement_into(r, &mut x);
                    let (mut f, mut c) = (vec![0.0; m], vec![Local::default(); nc]);
                    if dim == 3 {
                        eval::<_, 2>(&laws, &states, &rho, &mu_bar, r, &x, &mut f, &mut c);
                    } else {
                        eval::<_, 1>(&laws, &states, &rho, &mu_bar, r, &x, &mut f, &mut c);
                    }
                    f
                };
                let ok = if dim == 3 {
                    nw.refresh::<_, 2>(&laws, &states, &r, &x);
                    nw.direction::<2>(&p)
                } else {
                    nw.refresh::<_, 1>(&laws, &states, &r, &x);
                    nw.direction::<1>(&p)
                };
                assert!(ok);
                for c in &nw.cases {
                    cases_seen[c.case as usize] += 1;
                }
                let h = 1e-7 * norm(&r) / norm(&nw.dr);
                let plus: Vec<f64> = r.iter().zip(&nw.dr).map(|(a, b)| a + h * b).collect();
                let minus: Vec<f64> = r.iter().zip(&nw.dr).map(|(a, b)| a - h * b).collect();
                let (fp, fm) = (f_of(&plus), f_of(&minus));
                let err: f64 = (0..m)
                    .map(|k| ((fp[k] - fm[k]) / (2.0 * h) + nw.f[k]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                assert!(
                    err <= 1e-5 * norm(&nw.f),
                    "dim {dim}: ‖J Δr + F‖ = {err:e}, ‖F‖ = {:e}",
                    norm(&nw.f)
                );
            }
        }
        // every case of the projection was met
        assert!(cases_seen.iter().all(|&n| n > 10), "{cases_seen:?}");
    }

    /// The sparse assembly (faer's sparse LU) gives the dense assembly's Newton direction, to
    /// round-off (1e-10 relative: two LU factorisations of a well-conditioned system), at
    /// random points of random block-sparse 2D and 3D problems where every case occurs.
    #[test]
    fn sparse_direction_is_the_dense_direction() {
        for (dim, seed) in [(2, 21), (3, 22), (3, 23)] {
            let sparse = random_sparse_problem(dim, 40, 3, seed);
            let m = sparse.size();
            let mut w = vec![0.0; m * m];
            for (i, j, v) in sparse.w_sparse().unwrap().triplets() {
                w[i * m + j] = v;
            }
            let dense =
                ReducedProblem::with_dimension(dim, w, sparse.q().to_vec(), sparse.mu().to_vec())
                    .unwrap();
            let laws = sparse.coulomb_laws();
            let nc = sparse.contact_count();
            let states = vec![(); nc];
            let mut sweeps = Sweeps::default();
            sweeps.reset(&sparse, 1.0);
            let mut g = SplitMix64::new(seed);
            for _ in 0..10 {
                let r: Vec<f64> = (0..m).map(|_| g.uniform(-0.5, 1.5)).collect();
                let mut x = vec![0.0; m];
                dense.displacement_into(&r, &mut x);
                let mut dirs = Vec::new();
                for p in [&sparse, &dense] {
                    let mut nw = NewtonScratch::default();
                    friction_coefficients_into(&laws, &states, nc, &mut nw.mu_bar).unwrap();
                    nw.resize(m, nc);
                    nw.rho = sweeps.rho0().to_vec();
                    let ok = if dim == 3 {
                        nw.refresh::<_, 2>(&laws, &states, &r, &x);
                        nw.direction::<2>(p)
                    } else {
                        nw.refresh::<_, 1>(&laws, &states, &r, &x);
                        nw.direction::<1>(p)
                    };
                    assert!(ok && !nw.cols.is_empty());
                    dirs.push(nw.dr);
                }
                let diff: f64 = dirs[0]
                    .iter()
                    .zip(&dirs[1])
                    .map(|(a, b)| (a - b).powi(2))
                    .sum::<f64>()
                    .sqrt();
                assert!(diff <= 1e-10 * norm(&dirs[1]), "dim {dim}: {diff:e}");
            }
        }
    }
}
