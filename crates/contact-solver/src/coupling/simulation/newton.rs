//! The global Newton around contact (issue 40): a quasi-static step for a structure whose
//! internal forces and tangent depend on its state ([`Structure::nonlinear`]), chosen with
//! [`ContactSimulation::with_newton`].
//!
//! Each iteration linearises the structure at the current `u_k` and solves the step's whole
//! contact problem on that tangent, with the stages of the linear step (detection, `F*` or the
//! primal active set, the local solve with its adhesion loop, the penetration check):
//!
//! ```text
//! R_k   = f_ext(λ) + Hᵀ r_k − f_int(u_k)              (equilibrium residual)
//! y     = u_k + K_t⁻¹ (f_ext(λ) − f_int(u_k))         (the free response on the tangent)
//! x     = W r + q,   W = H K_t⁻¹ Hᵀ,   q from the jumps of y and the step's start
//! u_k+1 = y + K_t⁻¹ Hᵀ r                              (r the total reactions)
//! ```
//! until `‖R‖∞ ≤ tol · max(‖f_ext‖∞, ‖f_int‖∞, ‖Hᵀ r‖∞)` after at least one correction. The
//! contact problem is solved whole in every iteration (to the reduced solver's tolerance, its
//! natural-map residual reported beside `R`), so the gaps and slips of `u_k+1` meet the law
//! with `r`, and `R = 0` makes `(u, r)` the solution of the nonlinear step: the Newton is on
//! the structure's smooth equilibrium, quadratic where the material is smooth. The jumps `q`
//! refers to are the step's start, as in a linear step: the slip increment and the adhesion's
//! state (`β`, updated inside each contact solve from the start state) are those of the whole
//! step, accepted once, with the structure's state ([`Nonlinear::commit`]), when it converges.
//!
//! For a linear-elastic structure `y` is the linear step's free response and one correction
//! solves the step (the residual after it is round-off).
//!
//! A step that does not converge in [`NewtonSettings::max_iterations`] (or whose contact
//! solve or tangent fails) is rolled back ([`Nonlinear::rollback`]); the first time, it is
//! tried again with springs on the closed contacts' normals (`newton_springs.rs`: a body at
//! its limit load has a tangent singular but for the contact), then halved, up to
//! [`NewtonSettings::max_cuts`] times in a call of
//! [`step`](ContactSimulation::step); the sub-steps interpolate the time and the force factor
//! from the last Newton step's (0 at the start), and the prescribed displacements from their
//! committed values to those set for the step ([`Nonlinear::interpolate_prescribed`]).

use super::report::{NewtonReport, StepReport, StepResult};
use super::scheme::{QuasiStatic, TimeScheme};
use super::settings::FlexibilityMode;
use super::solve::Solved;
use super::{Clock, ContactSimulation, check_step};
use crate::coupling::space::ContactSpace;
use crate::error::{NewtonFailure, SolverError};
use contact_laws::ContactLaw;
use fem_core::{Dim, Nonlinear, Structure};
use std::time::Instant;

/// Settings of the global Newton around contact ([`ContactSimulation::with_newton`]).
///
/// # Examples
/// ```
/// use contact_solver::NewtonSettings;
/// let s = NewtonSettings::default().with_tol(1e-10).with_max_cuts(4);
/// assert_eq!((s.tol, s.max_iterations, s.max_cuts), (1e-10, 12, 4));
/// assert_eq!(s.dense_limit, contact_solver::coupling::simulation::NEWTON_DENSE_LIMIT);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct NewtonSettings {
    /// Tolerance on the relative equilibrium residual
    /// ([`NewtonReport::residuals`]): `1e-9` by default, a thousand times the round-off of
    /// an assembled residual, where a quadratic Newton spends at most one more iteration.
    pub tol: f64,
    /// Newton corrections allowed per (sub-)step before it is cut: 12 by default.
    pub max_iterations: usize,
    /// Halvings of a step allowed in one call of [`step`](ContactSimulation::step): 8 by
    /// default (a sub-step of 1/256 of the step).
    pub max_cuts: usize,
    /// The largest active set solved with a dense `F*` in a Newton step when the settings'
    /// flexibility is [`FlexibilityMode::Auto`] and the structure exposes its tangent
    /// ([`Structure::stiffness_matrix`]); beyond, the primal active set. It replaces Auto's
    /// own limit there: `F*` is rebuilt at every new tangent, so the active set wins much
    /// earlier than between linear steps, which keep `F*` ([`NEWTON_DENSE_LIMIT`]).
    pub dense_limit: usize,
}

/// Default [`NewtonSettings::dense_limit`], measured (`issue_40_measure_newton_paths`, guide
/// "Newton around contact"): per Newton iteration on a block sliding on a rigid line, the
/// dense `F*` and the primal active set cost the same at about 20–30 contacts (0.8 against
/// 1.0 ms at 17, 6.0 against 4.6 ms at 33), and the active set is 2.5× faster at 65 and 6×
/// at 257 contacts.
pub const NEWTON_DENSE_LIMIT: usize = 24;

impl Default for NewtonSettings {
    fn default() -> Self {
        Self {
            tol: 1e-9,
            max_iterations: 12,
            max_cuts: 8,
            dense_limit: NEWTON_DENSE_LIMIT,
        }
    }
}

impl NewtonSettings {
    /// With the residual tolerance `tol`.
    pub fn with_tol(mut self, tol: f64) -> Self {
        self.tol = tol;
        self
    }

    /// With at most `max_iterations` corrections per (sub-)step.
    pub fn with_max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// With at most `max_cuts` halvings per step.
    pub fn with_max_cuts(mut self, max_cuts: usize) -> Self {
        self.max_cuts = max_cuts;
        self
    }

    /// With at most `dense_limit` contacts on the dense path under `Auto`.
    pub fn with_dense_limit(mut self, dense_limit: usize) -> Self {
        self.dense_limit = dense_limit;
        self
    }

    /// # Errors
    /// [`SolverError::InvalidSetting`] naming `tol` (not finite and positive) or
    /// `max_iterations` (zero).
    fn check(&self) -> Result<(), SolverError> {
        if !(self.tol > 0.0 && self.tol.is_finite()) {
            return Err(SolverError::InvalidSetting {
                what: "NewtonSettings::tol",
                value: self.tol,
                expected: "a finite tolerance > 0",
            });
        }
        if self.max_iterations == 0 {
            return Err(SolverError::InvalidSetting {
                what: "NewtonSettings::max_iterations",
                value: 0.0,
                expected: "at least one correction per step",
            });
        }
        Ok(())
    }
}

/// What the Newton keeps between steps: its settings, the force factor of the last converged
/// step (where sub-steps start from) and its total reactions (the first residual's `Hᵀ r`).
pub(super) struct NewtonState<const D: usize> {
    settings: NewtonSettings,
    load_factor: f64,
    reactions: Vec<[f64; D]>,
    /// The springs on the closed contacts' normals (`newton_springs.rs`), per candidate,
    /// once a step has needed them (empty before): every later tangent carries them.
    pub(super) springs: Vec<f64>,
}

impl<const D: usize> NewtonState<D> {
    /// What a step starts from: the settings and the last converged force factor.
    pub(super) fn start(&self) -> (NewtonSettings, f64) {
        (self.settings, self.load_factor)
    }
}

/// What one attempt at a (sub-)step leaves when it fails: its error, residuals and
/// corrections.
struct Attempt {
    error: SolverError,
    history: Vec<f64>,
    iterations: usize,
}

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize> ContactSimulation<S, L, D, QuasiStatic>
where
    Dim<D>: ContactSpace<D>,
{
    /// Steps this simulation with the global Newton around contact (module docs of
    /// `newton`, `docs/guide.md` "Newton around contact"): every [`step`](Self::step) from
    /// now on iterates on the structure's equilibrium with its tangent
    /// ([`Structure::nonlinear`]), solving the contact problem on the current tangent in each
    /// iteration, and cuts the step on non-convergence. Linear structures need not: their
    /// step is one correction of it.
    ///
    /// The contact path follows [`SimulationSettings::flexibility`](crate::SimulationSettings::flexibility)
    /// as in a linear step: `F*` is rebuilt whenever the tangent changes (its
    /// [`Structure::stiffness_version`]); the primal active set factorises the structure's
    /// [`Structure::stiffness_matrix`], which a nonlinear structure returns as its current
    /// tangent. Under `Auto` (the default) the Newton's own
    /// [`dense_limit`](NewtonSettings::dense_limit) chooses between them, measured: beyond
    /// about 24 contacts the active set is the faster.
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] for bad settings; [`SolverError::Unsupported`] for a
    /// structure without [`Structure::nonlinear`] or a floating one.
    ///
    /// # Examples
    /// A linear-elastic block pressed on a rigid line through the Newton: one correction.
    /// ```
    /// use contact_solver::{ContactSimulation, ContactZone, NewtonSettings, SimulationSettings};
    /// use contact_solver::coupling::obstacle::RigidLine;
    /// use contact_laws::Signorini;
    /// use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};
    /// use fem_core::generate::{RectangleSpec, rectangle};
    ///
    /// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2))?;
    /// let (top, bottom) = (mesh.node_set("top")?.to_vec(), mesh.node_set("bottom")?.to_vec());
    /// let mut supports = Supports::new();
    /// supports.prescribe(&top, Component::Y, -0.01)?.fix(&top, Component::X);
    /// let model = LinearElasticModel::new(mesh, Idealization::PlaneStrain,
    ///     &[(0, Material::new(100.0, 0.0, 0.0)?)], supports)?;
    /// let ground = RigidLine::new([-1.0, 0.0], [2.0, 0.0])?;
    /// let zone = ContactZone::rigid("base", bottom, ground, Signorini, 0.1);
    /// let mut sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default())?
    ///     .with_newton(NewtonSettings::default())?;
    /// let res = sim.step(1.0, 1.0)?;
    /// let newton = res.report.newton.as_ref().expect("a Newton step");
    /// assert_eq!(newton.iterations, 1);
    /// assert!(newton.residuals.last().unwrap() <= &1e-9);
    /// let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
    /// assert!((total - 1.0).abs() < 1e-9); // E δ / H over a width of 1
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_newton(mut self, settings: NewtonSettings) -> Result<Self, SolverError> {
        settings.check()?;
        if self.structure.nonlinear().is_none() {
            return Err(SolverError::Unsupported(
                "with_newton: the structure has no state-dependent tangent \
                 (Structure::nonlinear is None); step it without the Newton"
                    .into(),
            ));
        }
        self.refuse_floating()?;
        self.newton = Some(NewtonState {
            settings,
            load_factor: 0.0,
            reactions: vec![[0.0; D]; self.interface.candidates.len()],
            springs: Vec::new(),
        });
        Ok(self)
    }
}

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize, T: TimeScheme<S, D>>
    ContactSimulation<S, L, D, T>
where
    Dim<D>: ContactSpace<D>,
{
    /// The Newton's settings, when the simulation steps with it
    /// ([`ContactSimulation::with_newton`]).
    pub fn newton_settings(&self) -> Option<NewtonSettings> {
        self.newton.as_ref().map(|n| n.settings)
    }

    /// A floating structure is refused: its rigid-body amplitudes are solved on the linear
    /// path only.
    fn refuse_floating(&self) -> Result<(), SolverError> {
        if self.floats() {
            return Err(SolverError::Unsupported(
                "the global Newton does not solve for the rigid-body modes of a floating \
                 structure: support it, or step it without the Newton"
                    .into(),
            ));
        }
        Ok(())
    }

    /// [`Self::step`] with the Newton: sub-steps from the last converged state to `time` and
    /// `force_factor`, halved on failure (module docs).
    pub(super) fn newton_step(
        &mut self,
        time: f64,
        force_factor: f64,
        (settings, lambda_0): (NewtonSettings, f64),
    ) -> Result<StepResult<D>, SolverError> {
        let start = Instant::now();
        check_step(time, force_factor, self.accepted.time)?;
        self.refuse_floating()?;
        let time_0 = self.accepted.time;
        if force_factor != 1.0 {
            // issue 36's check, on the free response at the factor asked
            let mut y = vec![0.0; self.structure.dof_count()];
            self.structure.free_response_into(force_factor, &mut y)?;
            self.force_check.check(&self.structure, force_factor, &y)?;
        }
        let (mut done, mut fraction) = (0.0_f64, 1.0_f64);
        let (mut cuts, mut substeps, mut total) = (0, 0, 0);
        loop {
            let end = (done + fraction).min(1.0);
            let clock = if end >= 1.0 {
                Clock {
                    time,
                    dt: time - self.accepted.time,
                    force_factor,
                }
            } else {
                let t = time_0 + end * (time - time_0);
                Clock {
                    time: t,
                    dt: t - self.accepted.time,
                    force_factor: lambda_0 + end * (force_factor - lambda_0),
                }
            };
            // the prescribed displacements follow the sub-steps: `end` of the step from its
            // start is `(end − done) / (1 − done)` of what is left from the last commit
            body(&mut self.structure)?.interpolate_prescribed(if end >= 1.0 {
                1.0
            } else {
                (end - done) / (1.0 - done)
            })?;
            match self.newton_increment(clock, &settings, start) {
                Ok(mut result) => {
                    substeps += 1;
                    done = end;
                    if let Some(state) = self.newton.as_mut() {
                        state.load_factor = clock.force_factor;
                        for (r, c) in state.reactions.iter_mut().zip(&result.contacts) {
                            *r = c.reaction();
                        }
                    }
                    if let Some(newton) = result.report.newton.as_mut() {
                        total += newton.iterations;
                        (newton.cuts, newton.substeps) = (cuts, substeps);
                        newton.total_iterations = total;
                    }
                    if end >= 1.0 {
                        return Ok(result);
                    }
                }
                Err(attempt) => {
                    if let Some(body) = self.structure.nonlinear() {
                        body.rollback();
                    }
                    total += attempt.iterations;
                    if !can_cut(&attempt.error) {
                        return Err(attempt.error);
                    }
                    // a tangent singular but for the contact: the same sub-step again, with
                    // springs on the closed contacts (`newton_springs.rs`), before any cut,
                    // when a tangent failed (its factorisation, or a contact solve on it);
                    // not for a failure before the first correction (a material update that
                    // refuses the step's start: no tangent was used), nor for a Newton that
                    // ran out of iterations (a step too large: cut as before)
                    if attempt.iterations > 0
                        && !matches!(attempt.error, SolverError::NewtonNotConverged(_))
                        && self.start_springs()
                    {
                        continue;
                    }
                    if cuts >= settings.max_cuts {
                        let reached = self.newton.as_ref().map_or(0.0, |s| s.load_factor);
                        let cause = match attempt.error {
                            SolverError::NewtonNotConverged(_) => None,
                            e => Some(Box::new(e)),
                        };
                        return Err(SolverError::NewtonNotConverged(Box::new(NewtonFailure {
                            load_factor: reached,
                            time: self.accepted.time,
                            target_load_factor: force_factor,
                            target_time: time,
                            cuts,
                            iterations: attempt.iterations,
                            history: attempt.history,
                            cause,
                        })));
                    }
                    cuts += 1;
                    fraction *= 0.5;
                }
            }
        }
    }

    /// One (sub-)step of the Newton ending at `clock`, accepted (and committed) when it
    /// converges; otherwise the attempt's error (a bare `NewtonNotConverged` for the
    /// iteration budget or a residual that is not finite), residuals and corrections.
    fn newton_increment(
        &mut self,
        clock: Clock,
        settings: &NewtonSettings,
        start: Instant,
    ) -> Result<StepResult<D>, Attempt> {
        let mut history = Vec::new();
        let mut iterations = 0;
        let outcome = self.newton_iterations(clock, settings, start, &mut history, &mut iterations);
        outcome.map_err(|error| Attempt {
            error,
            history,
            iterations,
        })
    }

    /// The iterations of [`Self::newton_increment`], writing the residuals into `history` and
    /// counting the corrections in `iterations`.
    fn newton_iterations(
        &mut self,
        clock: Clock,
        settings: &NewtonSettings,
        start: Instant,
        history: &mut Vec<f64>,
        iterations: &mut usize,
    ) -> Result<StepResult<D>, SolverError> {
        let n = self.structure.dof_count();
        let mut f_ext = vec![0.0; n];
        body(&mut self.structure)?.external_force_into(clock.force_factor, &mut f_ext)?;
        let mut u = self.accepted.u.clone();
        let last = self.newton.as_ref().map(|s| s.reactions.clone());
        let mut contact =
            self.contact_force(last.iter().flatten().enumerate().map(|(i, r)| (i, &r[..])));
        let mut f_int = vec![0.0; n];
        let mut contact_residuals = Vec::new();
        let mut total = StepReport::start(self.counters.steps + 1, clock.time, clock.force_factor);
        let mut solution = None;
        let mut closed =
            self.closed_of(last.iter().flatten().enumerate().map(|(i, r)| (i, &r[..])));
        loop {
            body(&mut self.structure)?.internal_force_into(&u, &mut f_int)?;
            let residual = relative_residual(&f_ext, &f_int, &contact);
            history.push(residual);
            let not_converged = || {
                SolverError::NewtonNotConverged(Box::new(NewtonFailure {
                    load_factor: clock.force_factor,
                    time: clock.time,
                    target_load_factor: clock.force_factor,
                    target_time: clock.time,
                    cuts: 0,
                    iterations: *iterations,
                    history: history.clone(),
                    cause: None,
                }))
            };
            if !residual.is_finite() {
                return Err(not_converged());
            }
            if residual <= settings.tol
                && let Some((equilibrium, solved)) = solution.take()
            {
                body(&mut self.structure)?.commit();
                total.newton = Some(NewtonReport {
                    iterations: *iterations,
                    residuals: history.clone(),
                    contact_residuals,
                    cuts: 0,
                    substeps: 1,
                    total_iterations: *iterations,
                });
                return Ok(self.accept(clock, equilibrium, solved, total, start));
            }
            if *iterations >= settings.max_iterations {
                return Err(not_converged());
            }
            // the tangent at u, then the free response on it and the contact problem
            self.set_springs(&closed)?;
            body(&mut self.structure)?.update_tangent()?;
            let version = self.follow_structure()?;
            let mut y: Vec<f64> = f_ext.iter().zip(&f_int).map(|(e, i)| e - i).collect();
            self.structure.solve_in_place(&mut y)?;
            self.counters.structure_solves += 1;
            for (y, u) in y.iter_mut().zip(&u) {
                *y += u;
            }
            let free = self.free_of(y, Vec::new());
            let scheme = &self.scheme;
            let active = self.interface.initial_active_set(
                &self.settings,
                &self.accepted,
                &free.jumps,
                |i, start, free, alert, all| scheme.enters(i, start, free, alert, all),
            );
            let mut report = StepReport::start(total.step, clock.time, clock.force_factor);
            // Auto's limit is the Newton's while it runs (settings docs)
            let user = self.settings.flexibility;
            if matches!(user, FlexibilityMode::Auto { .. })
                && self.structure.stiffness_matrix().is_some()
            {
                self.settings.flexibility = FlexibilityMode::Auto {
                    dense_limit: settings.dense_limit,
                };
            }
            let outcome = self.passes(clock, &free, active, version, &mut report);
            self.settings.flexibility = user;
            let (equilibrium, solved) = outcome?;
            *iterations += 1;
            contact_residuals.push(report.residual);
            u.clear();
            u.extend_from_slice(equilibrium.displacement());
            contact = self.contact_force(solved_reactions::<_, D>(&solved));
            closed = self.closed_of(solved_reactions::<_, D>(&solved));
            merge(&mut total, report);
            solution = Some((equilibrium, solved));
        }
    }

    /// `Hᵀ r` on the free dofs from per-candidate reactions `(i, [r_n, r_t…])`.
    fn contact_force<'a>(&self, reactions: impl Iterator<Item = (usize, &'a [f64])>) -> Vec<f64> {
        let mut f = vec![0.0; self.structure.dof_count()];
        for (i, r) in reactions {
            for (d, &r) in r.iter().enumerate() {
                if r != 0.0 {
                    for &(dof, a) in &self.interface.h_rows[D * i + d] {
                        f[dof] += a * r;
                    }
                }
            }
        }
        f
    }
}

/// The active contacts' total reactions of a solve, as `(candidate, [r_n, r_t…])`.
fn solved_reactions<T, const D: usize>(
    solved: &Solved<T>,
) -> impl Iterator<Item = (usize, &[f64])> {
    solved.active.iter().copied().zip(solved.r.chunks_exact(D))
}

/// The structure's [`Nonlinear`] side (checked when the Newton was chosen).
fn body<S: Structure<D>, const D: usize>(
    structure: &mut S,
) -> Result<&mut dyn Nonlinear, SolverError> {
    structure.nonlinear().ok_or_else(|| {
        SolverError::Unsupported("the structure no longer has a state-dependent tangent".into())
    })
}

/// `‖f_ext + Hᵀ r − f_int‖∞ / max(‖f_ext‖∞, ‖f_int‖∞, ‖Hᵀ r‖∞)` (0 when all three are 0).
fn relative_residual(f_ext: &[f64], f_int: &[f64], contact: &[f64]) -> f64 {
    let norm = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let scale = norm(f_ext).max(norm(f_int)).max(norm(contact));
    let residual = f_ext
        .iter()
        .zip(f_int)
        .zip(contact)
        .fold(0.0_f64, |m, ((e, i), c)| m.max((e + c - i).abs()));
    if scale > 0.0 {
        residual / scale
    } else {
        residual
    }
}

/// Whether a failed attempt is worth a smaller step: what a step too large causes (the
/// Newton's budget, a contact solve that does not converge, a penetration the passes did not
/// catch, a tangent that lost definiteness or a material update that failed), not bad input.
fn can_cut(error: &SolverError) -> bool {
    matches!(
        error,
        SolverError::NewtonNotConverged(_)
            | SolverError::NotConverged { .. }
            | SolverError::Stalled { .. }
            | SolverError::AdhesionNotConverged { .. }
            | SolverError::StillPenetrating { .. }
            | SolverError::Structure(_)
    )
}

/// Adds a correction's work (`report`) to the step's `total`; the flags and the residual
/// are the last correction's.
fn merge(total: &mut StepReport, report: StepReport) {
    total.adhesion_iterations += report.adhesion_iterations;
    total.contact_iterations += report.contact_iterations;
    total.detection_passes += report.detection_passes;
    total.flexibility_rebuilt |= report.flexibility_rebuilt;
    total.matrix_free = report.matrix_free;
    total.active_set = report.active_set;
    total.path = report.path;
    total.residual = report.residual;
    total.converged &= report.converged;
}
