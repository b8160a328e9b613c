//! Stage 3 for a floating structure: the reduced problem with the rigid-body amplitudes `α` as
//! extra unknowns and the equilibrium of every body along its modes as their equation.
//!
//! With `R` the structure's modes ([`Floating::rigid_body_modes`](fem_core::Floating::rigid_body_modes)), `K⁺` its generalized
//! inverse and `f` the load, the displacement is `u = K⁺(f + Hᵀ r) + R α` and
//!
//! ```text
//! x = F r + G α + q,   G = H R,   F = H K⁺ Hᵀ,   q from u_free = K⁺ f
//! Gᵀ r = e,            e = −Rᵀ f          (the reactions balance the load along every mode)
//! ```
//! (the floating-subdomain form of FETI, Farhat & Roux 1991). Modes are few (at most 3 per
//! body in the plane, 6 in 3D), so the equation `Gᵀ r(α) = e` is solved by a semismooth Newton method on `α`, where
//! `r(α)` is the ordinary reduced problem with `q + G α`, solved by [`UzawaSolver`](crate::local::UzawaSolver) and warm
//! started. Its Jacobian comes from the contacts' statuses: with `E` the directions the
//! closed contacts' reactions may take (stick: `e_n`, `e_t`; slip: `e_n + (r_t/r_n) e_t`;
//! frictionless: `e_n`) and `P` the gaps they hold (stick: `x_n = x_t = 0`; slip or
//! frictionless: `x_n = 0`),
//!
//! ```text
//! dr/dα = −E (Pᵀ F E − C)⁻¹ Pᵀ G,    J = Gᵀ dr/dα
//! ```
//! where in 3D a slipping reaction also turns with its slip: across it (the unit tangent `p`
//! normal to `r_t`) it holds `p · x_t = C β` with the compliance `C = |s|/(κ r_n)` of
//! `r_t = κ r_n ŝ` (`floating/linearized.rs`; in the plane `C` has no row and the rows above
//! are all).
//! The step solves `J d = −(Gᵀ r − e)` on the directions `J` resists (a pseudo-inverse by
//! SVD), with a backtracking line search on `‖Gᵀ r − e‖`. Along a direction that no closed
//! contact resists (`J d = 0`: the body is free to move that way), the body moves rigidly
//! until the first open contact closes, and a little further (the penetration a lone contact
//! needs to carry the out-of-balance force). If no contact closes that way (or the closed
//! ones slip), contact cannot hold the body: [`SolverError::Unbalanced`] names the mode and
//! the force left over. In 3D the turning reactions resist every direction while the slips are
//! finite; whether the body slides off is decided by the slide's limit (`floating/slide.rs`). No penalty: the answer meets `Gᵀ r = e` to
//! [`SimulationTuning::equilibrium_tol`](super::SimulationTuning::equilibrium_tol).

use super::ContactSimulation;
use super::detection::FreeResponse;
use super::last_problem::AdhesiveInputs;
use super::report::StepReport;
use super::scheme::TimeScheme;
use super::solve::Pass;
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use crate::local::adhesion::{
    AdhesionOptions, AdhesiveSolution, AdhesiveStep, solve_adhesive_shared,
};
use crate::local::norm;
use contact_laws::ContactLaw;
use fem_core::{Dim, RigidMode, RigidMotion, Structure};

mod linearized;
mod slide;
use linearized::Linearized;

/// Singular values of `J` below this fraction of the largest count as directions no contact
/// resists.
const NULL_TOL: f64 = 1e-9;

/// The resisted directions balance to this fraction of the forces before the free ones are
/// examined (module docs).
const RAY_TOL: f64 = 1e-8;

/// Smallest line-search step.
const MIN_STEP: f64 = 1.0 / 1024.0;

/// Iterations without halving the equilibrium residual after which a floating solve that
/// runs out of iterations reports the load as unbalanced rather than not converged.
const STAGNATION: usize = 10;

/// Relative step of the finite-difference Jacobian with adhesive springs (about `√ε`).
const FD_STEP: f64 = 1.5e-8;

/// What the floating solve needs beyond the ordinary step.
struct Floating {
    /// Number of modes.
    nm: usize,
    /// `G` on the active rows, row-major `m × nm` (zero on decoupled tangential rows).
    g: Vec<f64>,
    /// `e = −Rᵀ f`.
    e: Vec<f64>,
    /// The modes' meaning.
    modes: Vec<RigidMode>,
}

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize, T: TimeScheme<S, D>>
    ContactSimulation<S, L, D, T>
where
    Dim<D>: ContactSpace<D>,
{
    /// `G = H R` on every candidate row (row-major, `D n_candidates × n_modes`).
    pub(super) fn mode_rows(&self) -> Vec<f64> {
        let Some(modes) = self.structure.floating().map(|f| f.rigid_body_modes()) else {
            return Vec::new();
        };
        let nm = modes.len();
        let h_rows = &self.interface.h_rows;
        let mut g = vec![0.0; h_rows.len() * nm];
        for (row, h) in h_rows.iter().enumerate() {
            for j in 0..nm {
                let col = modes.column(j);
                g[row * nm + j] = h.iter().map(|&(dof, a)| a * col[dof]).sum();
            }
        }
        g
    }

    /// The candidates outside `active` that the rigid motion `d` (amplitudes) would close.
    fn closed_by(&self, active: &[usize], g_all: &[f64], d: &[f64]) -> Vec<usize> {
        let nm = d.len();
        (0..self.interface.candidates.len())
            .filter(|i| active.binary_search(i).is_err())
            .filter(|&i| (0..nm).map(|j| g_all[D * i * nm + j] * d[j]).sum::<f64>() < 0.0)
            .collect()
    }

    /// The reduced solve of a floating structure on `active`, the active set of the cached
    /// `F*` (module docs). Returns the solution with `alpha` set, or the candidates to add
    /// when a rigid motion would close a contact outside the active set.
    pub(super) fn solve_floating(
        &mut self,
        active: &[usize],
        free: &FreeResponse<D>,
        dt: f64,
        report: &mut StepReport,
    ) -> Result<Pass<L::State>, SolverError> {
        let na = active.len();
        let m = D * na;
        let g_all = self.mode_rows();
        let (nm, modes) = match self.structure.floating().map(|f| f.rigid_body_modes()) {
            Some(r) => (r.len(), r.modes().to_vec()),
            None => (0, Vec::new()),
        };
        // per active row: whether it is solved (normals, needed tangents)
        let this = &*self;
        let solved_rows: Vec<bool> = active
            .iter()
            .flat_map(|&i| (0..D).map(move |d| d == 0 || this.tangent_solved(i, d)))
            .collect();
        let tangent: Vec<bool> = active.iter().map(|&i| self.tangent_needed(i)).collect();
        let mut g = vec![0.0; m * nm];
        for (k, &i) in active.iter().enumerate() {
            for d in 0..D {
                let row = D * k + d;
                if !solved_rows[row] {
                    continue;
                }
                g[row * nm..(row + 1) * nm]
                    .copy_from_slice(&g_all[(D * i + d) * nm..(D * i + d + 1) * nm]);
            }
        }
        let fl = Floating {
            nm,
            g,
            e: free.mode_load.iter().map(|v| -v).collect(),
            modes,
        };
        let laws = self.laws_of(active);
        // adhesive springs resist the rigid motions too, which the statuses do not see: the
        // Jacobian is then taken by finite differences (one extra reduced solve per mode)
        let adhesive = (0..na).any(|k| laws[k].adhesion_active(&self.accepted.states[active[k]]));
        let start_states = self.states_of(active);
        let u_start = self.jumps_of(active);
        let areas = self.areas_of(active);
        let q0 = self.q_of(active, &free.jumps);
        let options = AdhesionOptions {
            tol: self.settings.adhesion_tol,
            max_iterations: self.settings.max_adhesion_iterations,
            accept_non_converged: self.settings.solver.accept_non_converged,
            always_iterate: false,
            anderson_window: self.settings.tuning.adhesion_anderson_window,
            method: self.settings.tuning.adhesion_method,
            warm_start: self.settings.tuning.adhesion_warm_start && self.warm.enabled(),
        };
        let mut r_warm = self.r_bar_of(active);
        let mut q = q0.clone();
        // one reduced solve at α, warm started from the last reactions
        let mut solve_at = |alpha: &[f64],
                            r_warm: &mut Vec<f64>,
                            report: &mut StepReport|
         -> Result<(AdhesiveSolution<L::State>, Vec<f64>), SolverError> {
            for (row, qi) in q.iter_mut().enumerate() {
                *qi = q0[row] + (0..nm).map(|j| fl.g[row * nm + j] * alpha[j]).sum::<f64>();
            }
            let step = AdhesiveStep {
                w: &self.cache.w,
                q: &q,
                laws: &laws,
                start_states: &start_states,
                u_start: &u_start,
                areas: &areas,
                dt,
            };
            let shared = Some(&self.cache.w);
            let sol =
                solve_adhesive_shared(&mut self.solver, &step, shared, Some(r_warm), &options)?;
            report.contact_iterations += sol.contact_iterations;
            // every reduced solve of the equilibrium iteration runs the adhesion loop (issue
            // 36: these were not counted, and a damaging floating pile reported 0)
            report.adhesion_iterations += sol.adhesion_iterations;
            self.counters.record_adhesive(&sol);
            report.equilibrium_solves += 1;
            r_warm.copy_from_slice(&sol.r_bar);
            let res = fl.residual(&sol.r);
            Ok((sol, res))
        };
        let mut alpha = vec![0.0; nm];
        let (mut sol, mut res) = solve_at(&alpha, &mut r_warm, report)?;
        let mut iterations = 0;
        let mut history = Vec::new();
        loop {
            let scale = fl.scale(&sol.r);
            let worst = res.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            history.push(if scale > 0.0 { worst / scale } else { 0.0 });
            if worst <= self.settings.tuning.equilibrium_tol * scale || scale == 0.0 {
                break;
            }
            if iterations >= self.settings.tuning.max_equilibrium_iterations {
                if self.settings.solver.accept_non_converged {
                    report.converged = false;
                    break;
                }
                // no progress over the last iterations: the contacts cannot carry the load
                // (adhesive springs past their peak soften: no equilibrium exists)
                let n = history.len();
                if n > STAGNATION
                    && history[n - STAGNATION..]
                        .iter()
                        .all(|&h| h >= 0.5 * history[n - 1 - STAGNATION])
                {
                    return Err(fl.unbalanced(&res, &res));
                }
                return Err(SolverError::NotConverged {
                    iterations,
                    residual: worst / scale,
                    history,
                    best: None,
                });
            }
            iterations += 1;
            let mut lin = Linearized::new::<_, D>(&self.cache.w, m, &fl, &sol, &tangent)?;
            if adhesive {
                // forward differences, step √ε of the amplitudes' scale
                let size = alpha
                    .iter()
                    .chain(&q0)
                    .fold(0.0_f64, |a, v| a.max(v.abs()))
                    .max(f64::MIN_POSITIVE);
                let h = FD_STEP * size;
                for j in 0..nm {
                    let mut shifted = alpha.clone();
                    shifted[j] += h;
                    let mut warm = r_warm.clone();
                    let (_, r_h) = solve_at(&shifted, &mut warm, report)?;
                    for i in 0..nm {
                        lin.jac[(i, j)] = (r_h[i] - res[i]) / h;
                    }
                }
            }
            let (newton, vs, free) = lin.directions(&res);
            let along = |r: &[f64]| -> f64 {
                (0..vs.ncols())
                    .map(|c| (0..nm).map(|i| vs[(i, c)] * r[i]).sum::<f64>().powi(2))
                    .sum::<f64>()
                    .sqrt()
            };
            let tol = self.settings.tuning.equilibrium_tol * scale;
            let merit = along(&res);
            // the free directions are examined once the resisted ones balance to this (the
            // reduced solves' own accuracy may not reach `tol` while a force is left over)
            let balanced = tol.max(RAY_TOL * scale);
            // in 3D a slipping reaction turns with its slip and no direction is free while the
            // body slides off: the slide's limit decides (`floating/slide.rs`)
            if lin.turns && !adhesive {
                let frozen = Linearized::frozen::<_, D>(&self.cache.w, m, &fl, &sol, &tangent)?;
                if let Some(d) = frozen.slide_off::<D>(&sol.r, &res, balanced, tol) {
                    let extend = self.closed_by(active, &g_all, &d);
                    if !extend.is_empty() {
                        return Ok(Pass::Extend(extend));
                    }
                    return Err(fl.unbalanced(&d, &d));
                }
            }
            if merit <= balanced && norm(&free) > tol {
                // the resisted directions balance: the force left is along free directions;
                // move rigidly that way until a contact closes (or stops slipping)
                // a piecewise-linear root search of the force along d̂ = free/‖free‖:
                // φ(t) = d̂ · res(α + t d), stepping to the next event (a contact closes or
                // sticks) or to the linear model's root, then Illinois within a bracket
                let d = free;
                let dn = norm(&d);
                let phi = |r: &[f64]| r.iter().zip(&d).map(|(a, b)| a * b).sum::<f64>() / dn;
                let base = alpha.clone();
                let (mut t_lo, mut phi_lo) = (0.0, phi(&res));
                let mut lin = lin;
                let mut bracket = None;
                for _ in 0..(4 * na + 16) {
                    let slope = (0..nm)
                        .map(|i| d[i] * (0..nm).map(|j| lin.jac[(i, j)] * d[j]).sum::<f64>())
                        .sum::<f64>()
                        / (dn * dn);
                    // a slope at round-off of J is no slope: the direction stays free
                    let mut j_max = 0.0_f64;
                    for c in lin.jac.col_iter() {
                        j_max = c.iter().fold(j_max, |m, v| m.max(v.abs()));
                    }
                    let t_root = if slope < -NULL_TOL * j_max {
                        phi_lo / -slope
                    } else {
                        f64::INFINITY
                    };
                    let t_event = lin
                        .ray_length::<D>(&d, &sol.x, &res, &self.cache.w, m)
                        .unwrap_or(f64::INFINITY);
                    let step = t_root.min(t_event);
                    if !step.is_finite() {
                        let extend = self.closed_by(active, &g_all, &d);
                        if !extend.is_empty() {
                            return Ok(Pass::Extend(extend));
                        }
                        return Err(fl.unbalanced(&res, &d));
                    }
                    let t = t_lo + step;
                    for j in 0..nm {
                        alpha[j] = base[j] + t * d[j];
                    }
                    (sol, res) = solve_at(&alpha, &mut r_warm, report)?;
                    let phi_t = phi(&res);
                    if phi_t.abs() <= tol {
                        break;
                    }
                    if phi_t < 0.0 {
                        bracket = Some(((t_lo, phi_lo), (t, phi_t)));
                        break;
                    }
                    (t_lo, phi_lo) = (t, phi_t);
                    lin = Linearized::new::<_, D>(&self.cache.w, m, &fl, &sol, &tangent)?;
                }
                if let Some(((mut ta, mut fa), (mut tb, mut fb))) = bracket {
                    // Illinois: regula falsi that halves the kept end's value
                    for _ in 0..100 {
                        let t = tb - fb * (tb - ta) / (fb - fa);
                        for j in 0..nm {
                            alpha[j] = base[j] + t * d[j];
                        }
                        (sol, res) = solve_at(&alpha, &mut r_warm, report)?;
                        let ft = phi(&res);
                        if ft.abs() <= tol || (tb - ta).abs() <= 1e-15 * t.abs() {
                            break;
                        }
                        if (ft < 0.0) == (fb < 0.0) {
                            fa *= 0.5;
                        } else {
                            (ta, fa) = (tb, fb);
                        }
                        (tb, fb) = (t, ft);
                    }
                }
                continue;
            }
            // Newton step on the resisted directions, backtracking on ‖V_Sᵀ (Gᵀ r − e)‖
            let mut lambda = 1.0;
            loop {
                let trial: Vec<f64> = alpha
                    .iter()
                    .zip(&newton)
                    .map(|(a, d)| a + lambda * d)
                    .collect();
                let mut warm = r_warm.clone();
                let (s, r) = solve_at(&trial, &mut warm, report)?;
                if along(&r) <= (1.0 - 1e-4 * lambda) * merit || lambda <= MIN_STEP {
                    alpha = trial;
                    r_warm = warm;
                    (sol, res) = (s, r);
                    break;
                }
                lambda *= 0.5;
            }
        }
        report.equilibrium_iterations += iterations;
        // (the last solve's: the trial solves of the line search are not counted)
        // the q of the accepted amplitudes
        let q: Vec<f64> = (0..m)
            .map(|row| q0[row] + (0..nm).map(|j| fl.g[row * nm + j] * alpha[j]).sum::<f64>())
            .collect();
        let inputs = AdhesiveInputs {
            q,
            laws,
            u_start,
            areas,
        };
        let solved = self.finish_adhesive(active, sol, alpha, inputs, report, true);
        Ok(Pass::Solved(solved))
    }
}

impl Floating {
    /// `Gᵀ r − e`: the out-of-balance generalized force along every mode.
    fn residual(&self, r: &[f64]) -> Vec<f64> {
        let nm = self.nm;
        let mut res: Vec<f64> = self.e.iter().map(|v| -v).collect();
        for (row, &ri) in r.iter().enumerate() {
            for (rj, gj) in res.iter_mut().zip(&self.g[row * nm..(row + 1) * nm]) {
                *rj += gj * ri;
            }
        }
        res
    }

    /// The size of the forces involved: `max_j (|e_j| + Σ |G_ij r_i|)`.
    fn scale(&self, r: &[f64]) -> f64 {
        let nm = self.nm;
        (0..nm)
            .map(|j| {
                self.e[j].abs()
                    + r.iter()
                        .enumerate()
                        .map(|(row, ri)| (self.g[row * nm + j] * ri).abs())
                        .sum::<f64>()
            })
            .fold(0.0, f64::max)
    }

    /// The error for an out-of-balance force `res` along the free direction `d`: the mode
    /// that `d` moves most, or, when that is a translation, the direction (in the plane or in
    /// space) along which the body's translations move (a block sliding down an incline moves
    /// along the slope, not along x).
    fn unbalanced(&self, res: &[f64], d: &[f64]) -> SolverError {
        let j = (0..self.nm)
            .max_by(|&a, &b| d[a].abs().total_cmp(&d[b].abs()))
            .unwrap_or(0);
        let mode = self.modes[j];
        if translation(mode.motion).is_some()
            && let Some(e) = self.unbalanced_translation(mode.body, res, d)
        {
            return e;
        }
        // the generalized force along a rotation mode scaled by 1/ρ is a moment / ρ
        let to_physical = match mode.motion {
            RigidMotion::Rotation { radius, .. } => radius,
            _ => 1.0,
        };
        SolverError::Unbalanced {
            body: mode.body,
            motion: mode.motion,
            imbalance: res[j] * to_physical,
            load: -self.e[j] * to_physical,
        }
    }
}

/// A translation's unit direction in space (a plane one with `z = 0`) and whether it is a
/// plane one; `None` for any other motion.
fn translation(motion: RigidMotion) -> Option<([f64; 3], bool)> {
    match motion {
        RigidMotion::Translation { direction: [x, y] } => Some(([x, y, 0.0], true)),
        RigidMotion::SpaceTranslation { direction } => Some((direction, false)),
        _ => None,
    }
}

impl Floating {
    /// [`SolverError::Unbalanced`] along the translation `Σ d_k e_k` of `body`'s translation
    /// modes `e_k` (orthonormal, in the plane or in space), oriented so that the force left
    /// over pushes along it: that force `Σ res_k (e_k · dir)` and the load's own
    /// `Σ −e_k (e_k · dir)`. `None` (the mode is reported as it is) when the direction is one
    /// of the modes' own, when the body's translation directions are not orthonormal (a user's
    /// modes), or when `d` has no translation part.
    fn unbalanced_translation(&self, body: usize, res: &[f64], d: &[f64]) -> Option<SolverError> {
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let mut plane = true;
        let translations: Vec<(usize, [f64; 3])> = self
            .modes
            .iter()
            .enumerate()
            .filter(|(_, m)| m.body == body)
            .filter_map(|(k, m)| {
                let (e, in_plane) = translation(m.motion)?;
                plane &= in_plane;
                Some((k, e))
            })
            .collect();
        for (a, &(_, ea)) in translations.iter().enumerate() {
            for &(_, eb) in &translations[a..] {
                let expected = if ea == eb { 1.0 } else { 0.0 };
                if (dot(ea, eb) - expected).abs() > 1e-12 {
                    return None;
                }
            }
        }
        let mut dir = [0.0; 3];
        for &(k, e) in &translations {
            for (da, ea) in dir.iter_mut().zip(e) {
                *da += d[k] * ea;
            }
        }
        let length = if plane {
            dir[0].hypot(dir[1])
        } else {
            dot(dir, dir).sqrt()
        };
        if !(length > 0.0 && length.is_finite()) {
            return None;
        }
        dir = dir.map(|v| v / length);
        // an axis direction (to round-off) is the mode itself, reported as it is
        if translations
            .iter()
            .any(|&(_, e)| dot(e, dir).abs() >= 1.0 - 1e-9)
        {
            return None;
        }
        let along = |v: &dyn Fn(usize) -> f64| -> f64 {
            translations.iter().map(|&(k, e)| v(k) * dot(e, dir)).sum()
        };
        let (mut imbalance, mut load) = (along(&|k| res[k]), along(&|k| -self.e[k]));
        if imbalance < 0.0 {
            dir = dir.map(|v| -v);
            imbalance = -imbalance;
            load = -load;
        }
        let motion = if plane {
            RigidMotion::Translation {
                direction: [dir[0], dir[1]],
            }
        } else {
            RigidMotion::SpaceTranslation { direction: dir }
        };
        Some(SolverError::Unbalanced {
            body,
            motion,
            imbalance,
            load,
        })
    }
}
