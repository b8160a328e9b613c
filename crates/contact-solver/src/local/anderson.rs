//! Anderson acceleration of the bipotential fixed point (Anderson 1965; Walker, Ni 2011,
//! "Anderson acceleration for fixed-point iterations", SIAM J. Numer. Anal. 49, alg. AA),
//! with the safeguard of Peng et al. 2018 ("Anderson acceleration for geometry optimization
//! and physics simulation", ACM TOG 37): selected by
//! [`Algorithm::AndersonGaussSeidel`](crate::Algorithm::AndersonGaussSeidel) (the base map is
//! one projected Gauss–Seidel sweep) or
//! [`Algorithm::AndersonUzawa`](crate::Algorithm::AndersonUzawa) (one self-adaptive Uzawa
//! step) in [`UzawaSolver`](crate::UzawaSolver).
//!
//! With `G` the base map (`g_k = G(r_k)`, `f_k = g_k − r_k`) and a memory of the last
//! `d ≤` `ANDERSON_DEPTH` differences `Δf_j = f_{j+1} − f_j`, `Δg_j = g_{j+1} − g_j`:
//!
//! ```text
//! γ_k     = argmin_γ ‖f_k − ΔF γ‖                 (normal equations ΔFᵀΔF γ = ΔFᵀ f_k by
//!                                                   Cholesky, columns nearly dependent dropped)
//! r_{k+1} = g_k − ΔG γ_k
//! x_{k+1} = x(g_k) − ΔX γ_k                      (x = W r + q is affine: no product W r)
//! ```
//! `x` follows the mixing exactly (up to rounding) because `x` is affine in `r`, so an
//! accelerated iteration costs one base step plus `O(d m)`, not an extra product `W r`: the
//! Gram matrix `ΔFᵀΔF` is updated with the `d` products of each new column (a thin QR rebuilt
//! at each iteration, `O(d² m)`, doubled the cost of an iteration on `n_c ≤ 100`, where a
//! sweep costs only `4 n_c²`).
//! The mixed `r_{k+1}` need not lie in the cones; the next base step projects it.
//!
//! **Safeguard.** If the base step from an accelerated iterate gives a larger fixed-point
//! residual than the previous one (`‖f_{k+1}‖ > ‖f_k‖`), that iterate is rejected: the
//! iteration restarts from the plain step `g_k` with an empty memory (one base step wasted),
//! and after the `j`-th rejection the next `2^j` steps are plain. The back-off matters where
//! the plain map converges very slowly and the mixing keeps failing (a tipping block with
//! `μ = 10`, lift-off, slip and stick, from issue 8's stress suite: Gauss–Seidel needs 54 000
//! sweeps; without back-off the accelerated iteration cycled accept–reject and stalled at a
//! residual of 3e-4): the iteration then degrades to the plain map, with rare probes (on that
//! case 25 000 to 54 000 base steps depending on the starting state, never more than about the
//! plain sweep's; `tests/integration/local_algorithms.rs`, `issue_8_tipping_block_*`).
//!
//! **Stopping rule.** Each iteration is judged like a plain sweep: the change is that of
//! the base step, `‖g_k − r_k‖/‖g_k‖`, and the natural residual (with `ρ⁰`) is taken at
//! `g_k`, the projected point; `g_k` is what is returned (see
//! [layer docs](crate::local#stopping-rule)); or the residual alone after a long streak
//! `≤ tol` (`residual_stop`). [`UzawaReport::iterations`](crate::UzawaReport)
//! counts base steps (including rejected ones).
//!
//! # Examples
//! ```
//! use contact_solver::{Algorithm, UzawaSettings, UzawaSolver, local::generate::random_problem};
//! let p = random_problem(20, 1);
//! let settings = UzawaSettings::default().with_algorithm(Algorithm::AndersonGaussSeidel);
//! let sol = UzawaSolver::new(settings).solve(&p, &p.coulomb_laws())?;
//! assert!(sol.report.converged && sol.report.residual <= 1e-10);
//! # Ok::<(), contact_solver::SolverError>(())
//! ```

use super::problem::ReducedProblem;
use super::residual::{natural_residual, norm};
use super::residual_stop::ResidualStop;
use super::settings::UzawaSettings;
use super::stall::StallDetector;
use super::sweep::Sweeps;
use contact_laws::ContactLaw;

/// Memory depth `d` of the Anderson mixing (the "window"): the last `d` differences.
pub(crate) const ANDERSON_DEPTH: usize = 5;

/// After the `k`-th rejected iterate the next `2^k` steps are plain (`k ≤ 16`).
const MAX_BACKOFF: u32 = 16;

/// A column `Δf_j` whose squared distance to the span of the columns kept before it is below
/// this fraction of `‖Δf_j‖²` is dropped from the least-squares problem (it is nearly a
/// combination of the others): the Cholesky pivot of the Gram matrix, so `ΔF` restricted to
/// the kept columns has a condition number below about `10⁶`.
const DROP_TOL: f64 = 1e-12;

/// Which map is accelerated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BaseMap {
    /// One projected Gauss–Seidel sweep with per-contact adapted `ρ_i`.
    GaussSeidel,
    /// One Uzawa (Jacobi) step with the globally adapted factor `θ`.
    Uzawa,
}

/// What an accelerated solve did.
#[derive(Clone, Copy, Debug)]
pub(crate) struct AndersonRun {
    /// Base steps done (including those from rejected iterates).
    pub iterations: usize,
    /// `true` when the stopping rule was met.
    pub converged: bool,
    /// `true` when the [stall detector](super::stall) stopped the run.
    pub stalled: bool,
    /// Relative natural residual at the last judged point.
    pub residual: f64,
    /// Relative change of the last base step.
    pub change: f64,
}

/// Scratch buffers of the accelerated iteration, kept in the
/// [`UzawaSolver`](crate::UzawaSolver) and reused across solves.
#[derive(Clone, Debug, Default)]
pub(crate) struct AndersonScratch {
    /// `g_k = G(r_k)` and `x(g_k)`.
    g: Vec<f64>,
    xg: Vec<f64>,
    /// `f_k = g_k − r_k`.
    f: Vec<f64>,
    /// The previous `g`, `x(g)`, `f`.
    g_prev: Vec<f64>,
    xg_prev: Vec<f64>,
    f_prev: Vec<f64>,
    /// Ring buffers of the differences `Δf`, `Δg`, `Δx` (each `ANDERSON_DEPTH` vectors).
    df: Vec<Vec<f64>>,
    dg: Vec<Vec<f64>>,
    dx: Vec<Vec<f64>>,
    /// The Gram matrix `Δf_iᵀ Δf_j` of the ring's slots.
    gram: [[f64; ANDERSON_DEPTH]; ANDERSON_DEPTH],
    /// Number of stored differences, and the slot the next one goes to.
    len: usize,
    next: usize,
}

impl AndersonScratch {
    fn resize(&mut self, m: usize) {
        for buf in [
            &mut self.g,
            &mut self.xg,
            &mut self.f,
            &mut self.g_prev,
            &mut self.xg_prev,
            &mut self.f_prev,
        ] {
            buf.clear();
            buf.resize(m, 0.0);
        }
        for ring in [&mut self.df, &mut self.dg, &mut self.dx] {
            ring.resize_with(ANDERSON_DEPTH, Vec::new);
            for v in ring.iter_mut() {
                v.clear();
                v.resize(m, 0.0);
            }
        }
        self.len = 0;
        self.next = 0;
    }

    /// Stores `f − f_prev`, `g − g_prev`, `x(g) − x(g_prev)` in the ring.
    fn push_difference(&mut self) {
        let k = self.next;
        for (d, (a, b)) in self.df[k].iter_mut().zip(self.f.iter().zip(&self.f_prev)) {
            *d = a - b;
        }
        for (d, (a, b)) in self.dg[k].iter_mut().zip(self.g.iter().zip(&self.g_prev)) {
            *d = a - b;
        }
        for (d, (a, b)) in self.dx[k].iter_mut().zip(self.xg.iter().zip(&self.xg_prev)) {
            *d = a - b;
        }
        self.len = (self.len + 1).min(ANDERSON_DEPTH);
        for a in 0..self.len {
            let j = (k + ANDERSON_DEPTH - a) % ANDERSON_DEPTH;
            let g: f64 = self.df[k].iter().zip(&self.df[j]).map(|(u, v)| u * v).sum();
            self.gram[k][j] = g;
            self.gram[j][k] = g;
        }
        self.next = (self.next + 1) % ANDERSON_DEPTH;
    }

    /// `r = g − ΔG γ`, `x = x(g) − ΔX γ` with `γ = argmin ‖f − ΔF γ‖`; returns `false` (and
    /// leaves `r`, `x` untouched) when every column was dropped.
    fn mix(&mut self, r: &mut [f64], x: &mut [f64]) -> bool {
        // Cholesky L Lᵀ of the Gram matrix over the kept slots, newest first, so that a nearly
        // dependent older difference is the one dropped.
        const D: usize = ANDERSON_DEPTH;
        let mut lower = [[0.0_f64; D]; D];
        let mut kept = [0_usize; D];
        let mut n_kept = 0;
        for a in 0..self.len {
            let s = (self.next + D - 1 - a) % D;
            let mut row = [0.0_f64; D];
            for i in 0..n_kept {
                let dot: f64 = (0..i).map(|j| row[j] * lower[i][j]).sum();
                row[i] = (self.gram[s][kept[i]] - dot) / lower[i][i];
            }
            let pivot = self.gram[s][s] - row[..n_kept].iter().map(|v| v * v).sum::<f64>();
            if pivot > DROP_TOL * self.gram[s][s] && pivot > 0.0 {
                row[n_kept] = pivot.sqrt();
                lower[n_kept] = row;
                kept[n_kept] = s;
                n_kept += 1;
            }
        }
        if n_kept == 0 {
            return false;
        }
        // L Lᵀ γ = ΔFᵀ f.
        let mut gamma = [0.0_f64; D];
        for i in 0..n_kept {
            let b: f64 = self.df[kept[i]]
                .iter()
                .zip(&self.f)
                .map(|(u, v)| u * v)
                .sum();
            let dot: f64 = (0..i).map(|j| lower[i][j] * gamma[j]).sum();
            gamma[i] = (b - dot) / lower[i][i];
        }
        for i in (0..n_kept).rev() {
            let dot: f64 = ((i + 1)..n_kept).map(|j| lower[j][i] * gamma[j]).sum();
            gamma[i] = (gamma[i] - dot) / lower[i][i];
        }
        r.copy_from_slice(&self.g);
        x.copy_from_slice(&self.xg);
        for (&slot, &c) in kept.iter().zip(&gamma).take(n_kept) {
            r.iter_mut()
                .zip(&self.dg[slot])
                .for_each(|(a, b)| *a -= c * b);
            x.iter_mut()
                .zip(&self.dx[slot])
                .for_each(|(a, b)| *a -= c * b);
        }
        true
    }

    /// Runs the accelerated iteration from `(r, x)` (`x = W r + q`); on return `(r, x)` is
    /// the last judged point. `theta` is Uzawa's global factor of `ρ⁰` (not used by
    /// [`BaseMap::GaussSeidel`]); `denom_q = max_i ρ⁰_i ‖q‖`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn solve<L: ContactLaw, const DT: usize>(
        &mut self,
        sweeps: &mut Sweeps,
        base: BaseMap,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        settings: &UzawaSettings,
        denom_q: f64,
        theta: &mut f64,
        r: &mut [f64],
        x: &mut [f64],
        history: &mut Vec<f64>,
    ) -> AndersonRun {
        let m = problem.size();
        self.resize(m);
        let tol = settings.tol;
        let mut run = AndersonRun {
            iterations: 0,
            converged: false,
            stalled: false,
            residual: f64::INFINITY,
            change: f64::INFINITY,
        };
        let mut have_prev = false;
        let mut accelerated = false;
        let mut f_prev_norm = f64::INFINITY;
        // Plain steps still to do before mixing again, and the rejections so far.
        let (mut plain_left, mut rejections) = (0_usize, 0_u32);
        let mut stall = StallDetector::new(settings.tuning.stall_window);
        let mut streak = ResidualStop::default();
        while run.iterations < settings.max_iterations {
            run.iterations += 1;
            self.g.copy_from_slice(r);
            self.xg.copy_from_slice(x);
            let dr2 = match base {
                BaseMap::GaussSeidel => sweeps.gauss_seidel_sweep::<L, DT>(
                    problem,
                    laws,
                    states,
                    &mut self.g,
                    &mut self.xg,
                ),
                BaseMap::Uzawa => {
                    sweeps.set_velocity::<L, DT>(laws, states, x);
                    sweeps.uzawa_step::<L, DT>(
                        problem,
                        laws,
                        states,
                        &mut self.g,
                        &mut self.xg,
                        theta,
                    )
                }
            };
            for ((f, g), a) in self.f.iter_mut().zip(&self.g).zip(r.iter()) {
                *f = g - a;
            }
            let f_norm = dr2.sqrt();
            let g_norm = norm(&self.g);
            run.change = f_norm / g_norm.max(f64::MIN_POSITIVE);
            let denom = g_norm.max(denom_q).max(f64::MIN_POSITIVE);
            let rho0 = sweeps.rho0();
            run.residual = natural_residual::<L, DT>(laws, states, rho0, &self.g, &self.xg) / denom;
            // the second way to stop: a long streak of residuals ≤ tol (`residual_stop`)
            let on_residual = streak.met(run.iterations, run.residual, run.change, tol);
            if (run.change <= tol && run.residual <= tol) || on_residual {
                // x(g) was built incrementally: confirm on the exact x = W g + q.
                problem.displacement_into(&self.g, &mut self.xg);
                run.residual =
                    natural_residual::<L, DT>(laws, states, rho0, &self.g, &self.xg) / denom;
            }
            history.push(run.residual);
            if run.residual <= tol && (run.change <= tol || on_residual) {
                r.copy_from_slice(&self.g);
                x.copy_from_slice(&self.xg);
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
            if accelerated && f_norm > f_prev_norm {
                // Safeguard: back to the plain step g_prev, memory emptied, and the next
                // 2^rejections steps plain.
                r.copy_from_slice(&self.g_prev);
                x.copy_from_slice(&self.xg_prev);
                self.len = 0;
                have_prev = false;
                accelerated = false;
                f_prev_norm = f64::INFINITY;
                rejections = (rejections + 1).min(MAX_BACKOFF);
                plain_left = 1 << rejections;
                continue;
            }
            if have_prev {
                self.push_difference();
            }
            accelerated = plain_left == 0 && self.len > 0 && self.mix(r, x);
            plain_left = plain_left.saturating_sub(1);
            if !accelerated {
                r.copy_from_slice(&self.g);
                x.copy_from_slice(&self.xg);
            }
            self.f_prev.copy_from_slice(&self.f);
            self.g_prev.copy_from_slice(&self.g);
            self.xg_prev.copy_from_slice(&self.xg);
            have_prev = true;
            f_prev_norm = f_norm;
        }
        if !run.converged {
            // Return the last projected point, not a mixed one that may leave the cones.
            r.copy_from_slice(&self.g);
            x.copy_from_slice(&self.xg);
        }
        run
    }
}
