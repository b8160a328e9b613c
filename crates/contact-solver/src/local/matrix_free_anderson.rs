//! The matrix-free bipotential iteration accelerated by Anderson mixing instead of Nesterov
//! momentum (issue 38): fewer products `F* r` (structure solves) for the same answer.
//!
//! The base map is one projected step of De Saxcé's iteration (seed 5.26) with per-contact
//! `ρ_i = θ ρ⁰_i`, as in [`matrix_free`](super::matrix_free):
//!
//! ```text
//! G(r)_i  = P_Ki(r_i + θ ρ⁰_i v_i(x(r)))          x(r) = W r + q,  v = u̇ + μ‖u̇_t‖ n
//! g_k     = G(r_k),  f_k = g_k − r_k                (one product: x(g_k))
//! γ_k     = argmin_γ ‖f_k − ΔF γ‖                   (thin QR of the last `window` Δf)
//! r_{k+1} = g_k − ΔG γ_k,   x_{k+1} = x(g_k) − ΔX γ_k   (x is affine in r: no product)
//! ```
//! (Walker & Ni 2011, alg. AA). On the linear part of the problem (the sticking contacts of a
//! fixed status) Anderson mixing of depth `window` is GMRES(`window`) in disguise, so its count
//! of products grows as a Krylov method's, not as the momentum's `√κ` with restarts; the
//! projection makes the rest nonlinear and the mixing a quasi-Newton step on it.
//!
//! Each iteration costs one product `x(g_k)` (plus one per rejected step size). `θ` only
//! shrinks, by the Khobotov / Solodov–Tseng ratio rule of [`matrix_free`](super::matrix_free)
//! (halved when `‖θ ρ⁰ (v(x(g)) − v(x(r)))‖ > 1.5 ‖g − r‖`); the memory is emptied whenever
//! `θ` changes (the map changed). Growing `θ` as the momentum iteration does changed the map at
//! almost every step and emptied the memory (1 162 products on the 3D Hertz level 0, 11 002 on
//! the pad at 24 cells, against 114 and 252 without growth): the mixing, not the step, adapts to
//! the spectrum. **Safeguard** (after Peng et al. 2018, as in [`anderson`](super::anderson)): when the
//! base step from a mixed iterate has a fixed-point residual `‖f‖` above `RESTART_GROWTH` = 2 times
//! the best since the last restart, the iteration restarts from that best step with an empty
//! memory.
//!
//! The stopping rule, the stall detector and the check of problems without a solution are
//! those of [`matrix_free`](super::matrix_free); the answer is the projected `g_k` with its
//! exact product `x(g_k)`, so equilibrium holds to one solve's rounding.

use super::matrix_free::{MatrixFreeReport, check_sizes, conclude, no_solution};
use super::residual::{local, natural_residual, norm};
use super::settings::{ADAPT_SHRINK_ABOVE, UzawaSettings};
use super::stall::StallDetector;
use crate::error::SolverError;
use contact_laws::ContactLaw;

/// A column `Δf_j` whose distance to the span of the columns kept before it is below
/// `√DROP_TOL ‖Δf_j‖` is left out of the least-squares problem (nearly dependent).
const DROP_TOL: f64 = 1e-12;

/// A mixed iterate whose base step has a fixed-point residual `‖f‖` above this factor times
/// the best since the last restart is rejected. Measured on the 3D Hertz level 0 (window 10):
/// 1 rejects too much (Anderson's residual is not monotone; 311 products, with `2^j` plain steps
/// after the `j`-th rejection), 1.5, 2 and 4 give 119, 123 and 127 products, none 114 — but
/// without any, windows of 20 and 40 wander for hundreds of steps (884 and 2 939 products,
/// against 103 and 103 with 2). The pad at 24 cells: 252 products for 1.5, 2 and 4.
const RESTART_GROWTH: f64 = 2.0;

/// The depth of the Anderson memory measured best on the 3D Hertz level 0 and the pad of
/// `docs/benchmarks.md` ("Matrix-free preconditioned (issue 38)"): products for windows 5, 10
/// and 20: 120, 123, 103 (Hertz, 121 contacts) and 281, 263, 252 (pad, 1 369 contacts); the
/// memory holds `4 × window` vectors of `3 n_c` values.
pub const DEFAULT_MATRIX_FREE_WINDOW: usize = 20;

/// [`solve_matrix_free`](super::matrix_free::solve_matrix_free) (2D: `r`, `x` with two
/// components per contact) with Anderson mixing of depth `window` (`window ≥ 1`).
///
/// # Errors
/// As [`solve_matrix_free`](super::matrix_free::solve_matrix_free), and
/// [`SolverError::InvalidSetting`] naming `matrix_free_window` when `window` is 0.
///
/// # Examples
/// ```
/// use contact_laws::Coulomb;
/// use contact_solver::local::matrix_free_anderson::solve_matrix_free_anderson;
/// use contact_solver::UzawaSettings;
/// // one contact, W = 2 I, pressed (q_n = −1) and pushed (q_t = 0.5), μ = 0.2: slip
/// let apply = |r: &[f64], x: &mut [f64]| {
///     x[0] = 2.0 * r[0] - 1.0;
///     x[1] = 2.0 * r[1] + 0.5;
///     Ok(())
/// };
/// let (mut r, mut x) = (vec![0.0; 2], vec![0.0; 2]);
/// let law = [Coulomb::new(0.2)?];
/// let s = UzawaSettings::default();
/// solve_matrix_free_anderson(apply, &law, &[()], &[0.5], 10, &s, &mut r, &mut x)?;
/// assert!((r[0] - 0.5).abs() < 1e-9 && (r[1] + 0.1).abs() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn solve_matrix_free_anderson<L: ContactLaw>(
    apply: impl FnMut(&[f64], &mut [f64]) -> Result<(), SolverError>,
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    window: usize,
    settings: &UzawaSettings,
    r: &mut [f64],
    x: &mut [f64],
) -> Result<MatrixFreeReport, SolverError> {
    solve::<L, 1>(apply, laws, states, rho0, window, settings, r, x)
}

/// [`solve_matrix_free_anderson`] in 3D: three components per contact, the normal first.
///
/// # Errors
/// As [`solve_matrix_free_anderson`].
///
/// # Examples
/// ```
/// use contact_laws::Coulomb;
/// use contact_solver::local::matrix_free_anderson::solve_matrix_free_anderson_3d;
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
/// let s = UzawaSettings::default();
/// solve_matrix_free_anderson_3d(apply, &law, &[()], &[0.5], 10, &s, &mut r, &mut x)?;
/// assert!((r[0] - 0.5).abs() < 1e-9 && (r[1] + 0.1).abs() < 1e-9 && r[2].abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn solve_matrix_free_anderson_3d<L: ContactLaw>(
    apply: impl FnMut(&[f64], &mut [f64]) -> Result<(), SolverError>,
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    window: usize,
    settings: &UzawaSettings,
    r: &mut [f64],
    x: &mut [f64],
) -> Result<MatrixFreeReport, SolverError> {
    solve::<L, 2>(apply, laws, states, rho0, window, settings, r, x)
}

/// The last `window` differences `Δf`, `Δg`, `Δx` (oldest first) and the least-squares scratch.
struct Memory {
    window: usize,
    df: Vec<Vec<f64>>,
    dg: Vec<Vec<f64>>,
    dx: Vec<Vec<f64>>,
    /// Orthonormal basis of the kept `Δf` (thin QR, modified Gram–Schmidt).
    basis: Vec<Vec<f64>>,
}

impl Memory {
    fn clear(&mut self) {
        self.df.clear();
        self.dg.clear();
        self.dx.clear();
    }

    /// Appends `a − b` for the three pairs, dropping the oldest past `window`.
    fn push(&mut self, f: (&[f64], &[f64]), g: (&[f64], &[f64]), x: (&[f64], &[f64])) {
        let diff = |(a, b): (&[f64], &[f64])| a.iter().zip(b).map(|(a, b)| a - b).collect();
        if self.df.len() == self.window {
            self.df.remove(0);
            self.dg.remove(0);
            self.dx.remove(0);
        }
        self.df.push(diff(f));
        self.dg.push(diff(g));
        self.dx.push(diff(x));
    }

    /// `γ = argmin ‖f − ΔF γ‖` (nearly dependent columns get `γ_j = 0`), then
    /// `r −= ΔG γ`, `x −= ΔX γ`.
    fn mix(&mut self, f: &[f64], r: &mut [f64], x: &mut [f64]) {
        let d = self.df.len();
        let mut rr = vec![vec![0.0; d]; d];
        let mut kept = Vec::with_capacity(d);
        self.basis.resize_with(d, Vec::new);
        for j in 0..d {
            let mut v = self.df[j].clone();
            let n0 = norm(&v);
            for (k, row) in rr.iter_mut().enumerate().take(kept.len()) {
                let qk: &Vec<f64> = &self.basis[k];
                let c: f64 = qk.iter().zip(&v).map(|(a, b)| a * b).sum();
                row[j] = c;
                v.iter_mut().zip(qk).for_each(|(a, b)| *a -= c * b);
            }
            let nv = norm(&v);
            if n0 == 0.0 || nv * nv <= DROP_TOL * n0 * n0 {
                continue;
            }
            v.iter_mut().for_each(|a| *a /= nv);
            let k = kept.len();
            rr[k][j] = nv;
            self.basis[k] = v;
            kept.push(j);
        }
        // R γ_kept = Qᵀ f, back substitution over the kept columns
        let nk = kept.len();
        let mut c: Vec<f64> = (0..nk)
            .map(|k| self.basis[k].iter().zip(f).map(|(a, b)| a * b).sum())
            .collect();
        let mut gamma = vec![0.0; d];
        for k in (0..nk).rev() {
            let mut s = c[k];
            for l in k + 1..nk {
                s -= rr[k][kept[l]] * gamma[kept[l]];
            }
            gamma[kept[k]] = s / rr[k][kept[k]];
            c[k] = s;
        }
        for (j, &gj) in gamma.iter().enumerate() {
            if gj != 0.0 {
                r.iter_mut()
                    .zip(&self.dg[j])
                    .for_each(|(a, b)| *a -= gj * b);
                x.iter_mut()
                    .zip(&self.dx[j])
                    .for_each(|(a, b)| *a -= gj * b);
            }
        }
    }
}

/// One projected step `g = P(r + θ ρ⁰ v(x))`; returns `‖g − r‖²`.
fn base_step<L: ContactLaw, const DT: usize>(
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    theta: f64,
    (r, x): (&[f64], &[f64]),
    g: &mut [f64],
) -> f64 {
    let dim = DT + 1;
    let mut d2 = 0.0;
    for (i, (law, s)) in laws.iter().zip(states).enumerate() {
        let ri = local::<DT>(r, i);
        let v = law.modified_velocity(&local::<DT>(x, i), s);
        let p = law.project(&(ri + v * (theta * rho0[i])), s);
        g[dim * i] = p.n;
        g[dim * i + 1..dim * (i + 1)].copy_from_slice(p.t.as_slice());
        let d = p - ri;
        d2 += d.dot(&d);
    }
    d2
}

/// `‖θ ρ⁰ (v(x_a) − v(x_b))‖²`, the numerator of the step-size ratio.
fn velocity_change2<L: ContactLaw, const DT: usize>(
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    theta: f64,
    xa: &[f64],
    xb: &[f64],
) -> f64 {
    let mut s = 0.0;
    for (i, (law, st)) in laws.iter().zip(states).enumerate() {
        let va = law.modified_velocity(&local::<DT>(xa, i), st);
        let vb = law.modified_velocity(&local::<DT>(xb, i), st);
        let d = (va - vb) * (theta * rho0[i]);
        s += d.dot(&d);
    }
    s
}

/// The accelerated iteration with `DT` tangential components per contact.
#[allow(clippy::too_many_arguments)]
fn solve<L: ContactLaw, const DT: usize>(
    mut apply: impl FnMut(&[f64], &mut [f64]) -> Result<(), SolverError>,
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    window: usize,
    settings: &UzawaSettings,
    r: &mut [f64],
    x: &mut [f64],
) -> Result<MatrixFreeReport, SolverError> {
    let dim = DT + 1;
    check_sizes(dim, laws.len(), states.len(), rho0, r.len(), x.len())?;
    if window == 0 {
        return Err(SolverError::InvalidSetting {
            what: "matrix_free_window",
            value: 0.0,
            expected: "a window ≥ 1 (the depth of the Anderson memory)",
        });
    }
    let m = dim * rho0.len();
    apply(r, x)?;
    let mut applications = 1;
    let mut memory = Memory {
        window,
        df: Vec::new(),
        dg: Vec::new(),
        dx: Vec::new(),
        basis: Vec::new(),
    };
    let (mut g, mut xg, mut f) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
    let (mut g_prev, mut xg_prev, mut f_prev) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
    let mut have_prev = false;
    let mut last_mixed = false;
    let (mut g_best, mut xg_best, mut f_best) = (vec![0.0; m], vec![0.0; m], f64::INFINITY);
    let mut theta = settings.tuning.rho_scale;
    let rho_max = rho0.iter().fold(0.0_f64, |a, &b| a.max(b));
    let scale_q = rho_max * norm(x);
    let (mut history, mut rejections) = (Vec::new(), 0);
    let (mut iterations, mut converged, mut stalled) = (0, false, false);
    let mut residual = f64::INFINITY;
    let mut stall = StallDetector::new(settings.tuning.stall_window);
    let coulomb_type = laws
        .iter()
        .zip(states)
        .all(|(l, s)| l.friction_coefficient(s).is_some());
    while iterations < settings.max_iterations {
        iterations += 1;
        // the base step, θ adapted on its ratio (a shrink redoes it: one more product)
        let mut shrinks = 0;
        let dr2 = loop {
            let dr2 = base_step::<L, DT>(laws, states, rho0, theta, (r, x), &mut g);
            if dr2 == 0.0 {
                xg.copy_from_slice(x);
                break 0.0;
            }
            apply(&g, &mut xg)?;
            applications += 1;
            let ratio = (velocity_change2::<L, DT>(laws, states, rho0, theta, &xg, x) / dr2).sqrt();
            if ratio > ADAPT_SHRINK_ABOVE && shrinks < 60 {
                theta *= 0.5;
                shrinks += 1;
                continue;
            }
            break dr2;
        };
        if shrinks > 0 {
            memory.clear();
            have_prev = false;
            f_best = f64::INFINITY;
        }
        let g_norm = norm(&g);
        let change = dr2.sqrt() / g_norm.max(f64::MIN_POSITIVE);
        residual = natural_residual::<L, DT>(laws, states, rho0, &g, &xg)
            / g_norm.max(scale_q).max(f64::MIN_POSITIVE);
        history.push(residual);
        if (change <= settings.tol && residual <= settings.tol) || dr2 == 0.0 {
            r.copy_from_slice(&g);
            x.copy_from_slice(&xg);
            if coulomb_type && no_solution::<DT>(&mut apply, settings.tol, x, &mut applications)? {
                stalled = true;
                break;
            }
            converged = true;
            break;
        }
        if stall.stalled(iterations, residual) {
            r.copy_from_slice(&g);
            x.copy_from_slice(&xg);
            stalled = true;
            break;
        }
        for k in 0..m {
            f[k] = g[k] - r[k];
        }
        let f_norm = dr2.sqrt();
        if f_norm > RESTART_GROWTH * f_best && last_mixed {
            // the mixed iterates made things worse: restart from the best step
            rejections += 1;
            memory.clear();
            have_prev = false;
            f_best = f64::INFINITY;
            r.copy_from_slice(&g_best);
            x.copy_from_slice(&xg_best);
            last_mixed = false;
            continue;
        }
        if f_norm < f_best {
            f_best = f_norm;
            g_best.copy_from_slice(&g);
            xg_best.copy_from_slice(&xg);
        }
        if have_prev {
            memory.push((&f, &f_prev), (&g, &g_prev), (&xg, &xg_prev));
        }
        g_prev.copy_from_slice(&g);
        xg_prev.copy_from_slice(&xg);
        f_prev.copy_from_slice(&f);
        have_prev = true;
        r.copy_from_slice(&g);
        x.copy_from_slice(&xg);
        last_mixed = !memory.df.is_empty();
        if last_mixed {
            memory.mix(&f, r, x);
        }
    }
    conclude(
        "MatrixFreeAnderson",
        MatrixFreeReport {
            iterations,
            applications,
            converged,
            stalled,
            residual,
            history,
            restarts: rejections,
            theta,
        },
        settings,
    )
}
