//! The quasi-static contact simulation (seed 5.3–5.5): a [`Structure`], contact zones, and one
//! [`ContactSimulation::step`] per load increment.
//!
//! # One step (`docs/theory.md` §13)
//! 1. Free response `u_free` of the structure to the current loads and prescribed values.
//! 2. Active set: candidates whose gap at the start of the step or under `u_free` is within
//!    their zone's alert distance, plus every adhesive candidate (β > 0).
//! 3. `F* = H K⁻¹ Hᵀ` on the active set, rebuilt only when the active set or the structure's
//!    [`stiffness_version`](Structure::stiffness_version) changed.
//! 4. Reduced problem `x = F* r + q` with `x = (x_n, Δu_t)` per contact: the normal part is the
//!    gap, the tangential part the slip increment of the step,
//!    `q = (g₀ + n·u_rel(u_free), t·u_rel(u_free) − u_t,start)`.
//! 5. Adhesion: the springs `r_adh = −(k_n u_n, k_t u_t)` of each law
//!    ([`ContactLaw::adhesive_stiffness`]) are condensed exactly,
//!    `x = W̃ r̄ + q̃`, `W̃ = (F*⁻¹ + B)⁻¹`, and the bipotential solver finds `r̄ ∈ K_μ̄`; then
//!    the state (β) is updated from the jump and the solve repeated until the largest state
//!    change is below [`SimulationSettings::adhesion_tol`] (seed 5.43–5.48). Skipped when no
//!    active law is adhesive.
//! 6. `u = u_free + K⁻¹ Hᵀ r` (one back-substitution, no refactorisation). Inactive candidates
//!    that ended up penetrating are added to the active set and the step is redone.

use crate::adhesion::{AdhesionOptions, AdhesiveStep, solve_adhesive};
use crate::error::SolverError;
use crate::matrix_free::solve_matrix_free;
use crate::primal::{LocalFrame, PrimalCache, PrimalStep, frames, solve_primal};
use crate::reduced::ReducedProblem;
use crate::uzawa::{UzawaSettings, UzawaSolver, contact_statuses};
use crate::zone::{Candidate, ContactZone, recognize};
use contact_laws::{ContactLaw, ContactStatus};
use faer::Mat;
use fem_core::Structure;
use std::time::{Duration, Instant};

/// Settings of a simulation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimulationSettings {
    /// The reduced solver (algorithm, tolerance, ρ scale, …).
    pub solver: UzawaSettings,
    /// Tolerance of the adhesion fixed point: largest [`ContactLaw::state_change`] (for RCCM,
    /// `|Δβ|`) between two iterations.
    pub adhesion_tol: f64,
    /// Maximum adhesion fixed-point iterations per step.
    pub max_adhesion_iterations: usize,
    /// Anderson window of the adhesion fixed point (`0`: the seed's plain fixed point); see
    /// [`AdhesionOptions::anderson_window`].
    pub adhesion_anderson_window: usize,
    /// Maximum passes of the penetration check per step (each adds the penetrating inactive
    /// candidates and redoes the step).
    pub max_detection_passes: usize,
    /// Right-hand sides per `solve_many_in_place` call when building `F*` (bounds the memory
    /// to `dof_count × columns` values).
    pub columns_per_solve: usize,
    /// What the simulation skips when a scene does not need it (all on by default; turn one
    /// off to measure what it saves).
    pub skip: SkipRules,
    /// Dense `F*` or the matrix-free iteration ([`crate::matrix_free`]).
    pub flexibility: FlexibilityMode,
}

/// How the reduced problem is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FlexibilityMode {
    /// Dense `F*` up to `dense_limit` active contacts; beyond, the primal active-set solve
    /// when the step is in its scope ([`crate::primal`]: rigid obstacles, no active adhesion, a
    /// structure that exposes its stiffness), else matrix-free (when no active law is adhesive:
    /// the exact condensation of the springs needs the dense `F*`). A step whose active-set
    /// iteration does not converge is solved again with a dense `F*` (up to 8000 contacts) or
    /// matrix-free (`Counters::active_set_fallbacks`).
    Auto {
        /// Largest active set solved with a dense `F*`.
        dense_limit: usize,
    },
    /// Always a dense `F*` (built with `2 n_c` structure solves, `4 n_c²` values).
    Dense,
    /// Never store `F*`: one structure solve per iteration. Adhesive laws are refused.
    MatrixFree,
    /// No `F*` at all: the semi-smooth Newton (primal–dual active-set) iteration on the
    /// factorised stiffness, one numeric factorisation per change of the closed/sticking set
    /// ([`crate::primal`]). Steps outside its scope are refused with the reason.
    ActiveSet,
}

/// Largest active set that `Auto` solves with a dense `F*` when its active-set iteration did
/// not converge (a dense `F*` of 8000 contacts takes 2 GiB); matrix-free beyond.
const FALLBACK_DENSE_LIMIT: usize = 8000;

/// Default [`FlexibilityMode::Auto`] limit, measured (`docs/benchmarks.md`, "Scale"): the
/// primal active set and the dense `F*` cost the same at about 100 contacts, and the active set
/// is 4–5× faster at 800 and 30–50× at 4000. The dense path is kept up to 500, where the two
/// are within a factor 2, because it also serves adhesion and every zone kind.
pub const DEFAULT_DENSE_LIMIT: usize = 500;

impl Default for FlexibilityMode {
    fn default() -> Self {
        Self::Auto {
            dense_limit: DEFAULT_DENSE_LIMIT,
        }
    }
}

/// "Skip what a scene does not need": each rule is on by default and only exists as a switch
/// so that its saving can be measured (`docs/benchmarks.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SkipRules {
    /// Reuse `F*` while the active set and the stiffness are unchanged (off: rebuild it every
    /// step).
    pub reuse_flexibility: bool,
    /// Leave candidates outside their alert distance out of the reduced problem (off: every
    /// candidate is active in every step).
    pub alert_distance: bool,
    /// For frictionless, non-adhesive laws, skip the tangential columns of `F*` (half the
    /// structure solves) and decouple the tangential unknowns (`r_t = 0` exactly).
    pub frictionless_normal_only: bool,
    /// Run no adhesion fixed point when no active law is adhesive (off: iterate anyway).
    pub adhesion_loop_only_when_adhesive: bool,
}

impl Default for SkipRules {
    fn default() -> Self {
        Self {
            reuse_flexibility: true,
            alert_distance: true,
            frictionless_normal_only: true,
            adhesion_loop_only_when_adhesive: true,
        }
    }
}

impl Default for SimulationSettings {
    fn default() -> Self {
        Self {
            solver: UzawaSettings::default(),
            adhesion_tol: 1e-8,
            max_adhesion_iterations: 200,
            adhesion_anderson_window: crate::adhesion::DEFAULT_ANDERSON_WINDOW,
            max_detection_passes: 5,
            columns_per_solve: 64,
            skip: SkipRules::default(),
            flexibility: FlexibilityMode::default(),
        }
    }
}

/// What a contact is doing at the end of a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum InterfaceStatus {
    /// Outside the alert distance: not in the reduced problem.
    Inactive,
    /// In the reduced problem, `r̄ = 0` (open; adhesive springs may still pull).
    Open,
    /// Compressed, sticking.
    Stick,
    /// Compressed, sliding.
    Slip,
}

impl InterfaceStatus {
    /// A short lowercase name (`inactive`, `open`, `stick`, `slip`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Inactive => "inactive",
            Self::Open => "open",
            Self::Stick => "stick",
            Self::Slip => "slip",
        }
    }
}

/// One contact candidate at the end of a step. Local components are `[normal, tangential]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactRecord {
    /// Zone index.
    pub zone: usize,
    /// Contactor node.
    pub node: usize,
    /// Reference position of the contactor node.
    pub position: [f64; 2],
    /// Tributary area of the node: `r / area` is the interface stress.
    pub area: f64,
    /// Status.
    pub status: InterfaceStatus,
    /// Normal gap `x_n = g₀ + u_n` (`≥ 0`: open). For a glued interface (`g₀ = 0`) it is the
    /// normal jump `u_n` of the RCCM law.
    pub gap: f64,
    /// Total tangential relative displacement `u_t`.
    pub u_t: f64,
    /// Tangential relative displacement of this step (the slip increment when sliding).
    pub slip_increment: f64,
    /// Adhesion intensity β ([`ContactLaw::adhesion_intensity`], 0 without adhesion).
    pub beta: f64,
    /// Total reaction `r = r̄ + r_adh` on the contactor (`r_n > 0` compression).
    pub r: [f64; 2],
    /// Reaction of the contact law proper, `r̄ ∈ K_μ̄`.
    pub r_bar: [f64; 2],
    /// Adhesive reaction `r_adh`.
    pub r_adh: [f64; 2],
}

/// Counters and timing of one step.
#[derive(Clone, Debug, PartialEq)]
pub struct StepReport {
    /// Step number (1-based).
    pub step: usize,
    /// Time at the end of the step.
    pub time: f64,
    /// Load factor of the step.
    pub load_factor: f64,
    /// Candidates in the reduced problem.
    pub active_contacts: usize,
    /// Adhesion fixed-point iterations (0 when the step had no adhesion).
    pub adhesion_iterations: usize,
    /// Contact iterations: solver sweeps summed over the adhesion iterations and passes.
    pub contact_iterations: usize,
    /// Passes of the penetration check (1 unless inactive candidates penetrated).
    pub detection_passes: usize,
    /// Whether `F*` was rebuilt in this step.
    pub flexibility_rebuilt: bool,
    /// Whether the step was solved matrix-free (no `F*`).
    pub matrix_free: bool,
    /// Whether the step was solved by the primal active-set iteration (no `F*`).
    pub active_set: bool,
    /// Natural-map residual of the last reduced solve.
    pub residual: f64,
    /// Whether every solve of the step met its tolerance (always `true` unless the settings
    /// accept non-converged results).
    pub converged: bool,
    /// Wall time of the step.
    pub wall_time: Duration,
}

/// Counters over the whole simulation: what work was done (and skipped).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Steps done.
    pub steps: usize,
    /// `F*` builds.
    pub flexibility_builds: usize,
    /// Right-hand sides solved to build `F*`.
    pub flexibility_columns: usize,
    /// Structure solves outside `F*` (free response and final displacement).
    pub structure_solves: usize,
    /// Adhesion fixed-point iterations.
    pub adhesion_iterations: usize,
    /// Contact (solver) iterations.
    pub contact_iterations: usize,
    /// Steps where the structure's stiffness version changed.
    pub stiffness_changes: usize,
    /// Steps solved matrix-free.
    pub matrix_free_steps: usize,
    /// Products `F* r` done matrix-free (one structure solve each).
    pub operator_applications: usize,
    /// Steps solved by the primal active-set iteration.
    pub active_set_steps: usize,
    /// Numeric factorisations of the constrained stiffness by the active-set iteration.
    pub active_set_factorizations: usize,
    /// Solves with the constrained stiffness by the active-set iteration.
    pub active_set_solves: usize,
    /// Steps where `Auto`'s active-set iteration did not converge and the step was solved
    /// again with a dense `F*` (up to 8000 contacts) or matrix-free.
    pub active_set_fallbacks: usize,
}

/// The result of one step.
#[derive(Clone, Debug, PartialEq)]
pub struct StepResult {
    /// Counters and timing.
    pub report: StepReport,
    /// Every candidate, in recognition order.
    pub contacts: Vec<ContactRecord>,
}

/// A quasi-static contact simulation: structure, zones, per-contact state and the cached `F*`.
///
/// # Examples
/// An elastic block (P1, plane strain) pressed on a rigid LINE by a prescribed displacement of
/// its top: the bottom nodes come into contact and the pressure is uniform.
/// ```
/// use contact_solver::{ContactSimulation, ContactZone, SimulationSettings};
/// use contact_solver::obstacle::RigidLine;
/// use contact_laws::Signorini;
/// use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};
/// use fem_core::generate::{RectangleSpec, rectangle};
///
/// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 4, 4))?; // P1
/// let (top, bottom) = (mesh.node_set("top")?.to_vec(), mesh.node_set("bottom")?.to_vec());
/// let mut supports = Supports::new();
/// supports.prescribe(&top, Component::Y, -0.01)?.fix(&top, Component::X);
/// let model = LinearElasticModel::new(mesh, Idealization::PlaneStrain,
///     &[(0, Material::new(100.0, 0.0, 0.0)?)], supports)?;
/// let ground = RigidLine::new([-1.0, 0.0], [2.0, 0.0])?;
/// let zone = ContactZone::rigid("base", bottom, ground, Signorini, 0.1);
/// let mut sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default())?;
/// let res = sim.step(1.0, 1.0)?;
/// let total: f64 = res.contacts.iter().map(|c| c.r[0]).sum();
/// assert!((total - 1.0).abs() < 1e-9);         // σ = E ε = 100 × 0.01 over a width of 1
/// assert!(res.contacts.iter().all(|c| c.gap.abs() < 1e-11)); // closed to 1e-9 of the 0.01 push
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct ContactSimulation<S: Structure, L: ContactLaw> {
    structure: S,
    zones: Vec<ContactZone<L>>,
    settings: SimulationSettings,
    candidates: Vec<Candidate>,
    /// H rows (n then t per candidate) on free dofs: (dof, coefficient).
    h_rows: Vec<Vec<(usize, f64)>>,
    /// Accepted state at the end of the last step.
    states: Vec<L::State>,
    /// Accepted (gap, u_t) at the end of the last step.
    jumps: Vec<[f64; 2]>,
    /// Last accepted r̄ (warm start).
    r_bar: Vec<[f64; 2]>,
    /// Active set of the cached W.
    w_active: Vec<usize>,
    w: Vec<f64>,
    w_version: Option<u64>,
    u: Vec<f64>,
    time: f64,
    solver: UzawaSolver,
    counters: Counters,
    last_problem: Option<ReducedProblem>,
    last_version: u64,
    primal: PrimalCache,
}

impl<S: Structure, L: ContactLaw + Clone> ContactSimulation<S, L> {
    /// Recognises the candidates of `zones` on `structure` (reference configuration) and
    /// starts at time 0 with every law's initial state.
    ///
    /// # Errors
    /// As for [`recognize`]; [`SolverError::InvalidSetting`] for bad settings;
    /// [`SolverError::InvalidGeometry`] if no zone has a candidate.
    pub fn new(
        structure: S,
        zones: Vec<ContactZone<L>>,
        settings: SimulationSettings,
    ) -> Result<Self, SolverError> {
        if !(settings.adhesion_tol > 0.0 && settings.adhesion_tol.is_finite()) {
            return Err(SolverError::InvalidSetting {
                what: "adhesion_tol",
                value: settings.adhesion_tol,
                expected: "a finite tolerance > 0",
            });
        }
        if settings.columns_per_solve == 0 {
            return Err(SolverError::InvalidSetting {
                what: "columns_per_solve",
                value: 0.0,
                expected: "at least 1",
            });
        }
        let candidates = recognize(&structure, &zones)?;
        if candidates.is_empty() {
            return Err(SolverError::InvalidGeometry(
                "no contactor node projects on its target: the simulation has no contact candidate"
                    .into(),
            ));
        }
        let mut h_rows = Vec::with_capacity(2 * candidates.len());
        for c in &candidates {
            for dir in [c.normal, c.tangent] {
                let mut row = Vec::with_capacity(6);
                c.h_row(&structure, dir, &mut row);
                h_rows.push(row);
            }
            if h_rows[h_rows.len() - 2].is_empty() {
                return Err(SolverError::InvalidGeometry(format!(
                    "zone `{}`: the normal displacement of contactor node {} relative to its \
                     target is fully prescribed, so it cannot take part in contact",
                    zones[c.zone].name, c.node
                )));
            }
        }
        let states = candidates
            .iter()
            .map(|c| zones[c.zone].law.initial_state())
            .collect();
        let mut sim = Self {
            u: vec![0.0; structure.dof_count()],
            last_version: structure.stiffness_version(),
            structure,
            zones,
            settings,
            h_rows,
            states,
            jumps: vec![[0.0; 2]; candidates.len()],
            r_bar: vec![[0.0; 2]; candidates.len()],
            candidates,
            w_active: Vec::new(),
            w: Vec::new(),
            w_version: None,
            time: 0.0,
            solver: UzawaSolver::new(settings.solver),
            counters: Counters::default(),
            last_problem: None,
            primal: PrimalCache::default(),
        };
        sim.jumps = sim.local_jumps_of(&sim.u);
        Ok(sim)
    }

    /// The structure.
    pub fn structure(&self) -> &S {
        &self.structure
    }

    /// The structure, to change loads or prescribed values between steps.
    pub fn structure_mut(&mut self) -> &mut S {
        &mut self.structure
    }

    /// The zones.
    pub fn zones(&self) -> &[ContactZone<L>] {
        &self.zones
    }

    /// The candidates found by recognition.
    pub fn candidates(&self) -> &[Candidate] {
        &self.candidates
    }

    /// The settings.
    pub fn settings(&self) -> &SimulationSettings {
        &self.settings
    }

    /// Replaces the settings (e.g. to switch algorithm between steps).
    pub fn set_settings(&mut self, settings: SimulationSettings) {
        self.settings = settings;
        self.solver = UzawaSolver::new(settings.solver);
    }

    /// Current time.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Per-candidate law states at the end of the last step.
    pub fn states(&self) -> &[L::State] {
        &self.states
    }

    /// Counters since the start.
    pub fn counters(&self) -> Counters {
        self.counters
    }

    /// The free-dof displacements at the end of the last step.
    pub fn displacement(&self) -> &[f64] {
        &self.u
    }

    /// Nodal displacements `[u_x, u_y]` at the end of the last step (prescribed components
    /// included).
    pub fn nodal_displacements(&self) -> Vec<[f64; 2]> {
        (0..self.structure.node_count())
            .map(|n| nodal(&self.structure, &self.u, n))
            .collect()
    }

    /// The reduced problem of the last solve — after condensation of the adhesive springs,
    /// with `μ̄` per contact — on the active contacts (see [`Self::last_active`]); export it
    /// with [`ReducedProblem::to_json`] to re-solve it elsewhere (e.g. Siconos). `None` when the
    /// last step was solved without a dense `F*` (matrix-free or active set; force
    /// `FlexibilityMode::Dense` to export a large step).
    pub fn last_reduced_problem(&self) -> Option<&ReducedProblem> {
        self.last_problem.as_ref()
    }

    /// Candidate indices of the contacts of the last reduced problem, in its order.
    pub fn last_active(&self) -> &[usize] {
        &self.w_active
    }

    /// Resets the displacement and the tangential reference to zero while keeping the law
    /// states (e.g. after an installation phase whose displacements are discarded).
    pub fn reset_displacements(&mut self) {
        self.u.fill(0.0);
        self.jumps = self.local_jumps_of(&self.u);
        self.r_bar.iter_mut().for_each(|r| *r = [0.0; 2]);
    }

    fn local_jumps_of(&self, u: &[f64]) -> Vec<[f64; 2]> {
        self.candidates
            .iter()
            .map(|c| c.local(c.relative(|n| nodal(&self.structure, u, n))))
            .collect()
    }

    /// Solves one load step ending at `time` (`≥` the current time) with the structure's loads
    /// scaled by `load_factor` (and its current prescribed values).
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] if `time` is not finite or goes backwards;
    /// [`SolverError::Structure`] if a structure solve fails; [`SolverError::NotConverged`] or
    /// [`SolverError::AdhesionNotConverged`] unless the settings accept non-converged results.
    /// On error the simulation keeps the state of the previous step.
    pub fn step(&mut self, time: f64, load_factor: f64) -> Result<StepResult, SolverError> {
        let start = Instant::now();
        if !(time.is_finite() && time >= self.time) {
            return Err(SolverError::InvalidSetting {
                what: "time",
                value: time,
                expected: "a finite time not before the current time",
            });
        }
        if !load_factor.is_finite() {
            return Err(SolverError::InvalidSetting {
                what: "load_factor",
                value: load_factor,
                expected: "a finite number",
            });
        }
        let dt = time - self.time;
        let version = self.structure.stiffness_version();
        if version != self.last_version {
            self.counters.stiffness_changes += 1;
            self.last_version = version;
        }
        let ndof = self.structure.dof_count();
        let mut u_free = vec![0.0; ndof];
        self.structure
            .free_response_into(load_factor, &mut u_free)?;
        self.counters.structure_solves += 1;
        let free = self.local_jumps_of(&u_free);

        let all = !self.settings.skip.alert_distance;
        let mut active: Vec<usize> = (0..self.candidates.len())
            .filter(|&i| {
                let c = &self.candidates[i];
                let zone = &self.zones[c.zone];
                all || zone.law.adhesion_active(&self.states[i])
                    || self.jumps[i][0] <= zone.alert_distance
                    || free[i][0] <= zone.alert_distance
            })
            .collect();

        let mut report = StepReport {
            step: self.counters.steps + 1,
            time,
            load_factor,
            active_contacts: 0,
            adhesion_iterations: 0,
            contact_iterations: 0,
            detection_passes: 0,
            flexibility_rebuilt: false,
            matrix_free: false,
            active_set: false,
            residual: 0.0,
            converged: true,
            wall_time: Duration::ZERO,
        };
        let mut u = vec![0.0; ndof];
        loop {
            report.detection_passes += 1;
            let mut path = self.path(&active)?;
            let mut primal = None;
            if let Path::ActiveSet(frames) = &path {
                self.w_active.clone_from(&active);
                self.w.clear();
                self.w_version = None;
                self.last_problem = None;
                match self.solve_active_set(&free, frames, &mut report) {
                    Ok(solved) => {
                        report.active_set = true;
                        primal = Some(solved);
                    }
                    // Auto chose this path: fall back to one that converges more surely (the
                    // lagged friction coupling of the active set fails for large μ)
                    Err(SolverError::NotConverged { .. })
                        if matches!(self.settings.flexibility, FlexibilityMode::Auto { .. }) =>
                    {
                        self.counters.active_set_fallbacks += 1;
                        path = if active.len() <= FALLBACK_DENSE_LIMIT {
                            Path::Dense
                        } else {
                            Path::MatrixFree
                        };
                    }
                    Err(e) => return Err(e),
                }
            }
            let solved = if let Some(solved) = primal {
                solved
            } else if path == Path::MatrixFree {
                if active != self.w_active {
                    self.w_active.clone_from(&active);
                }
                self.w.clear();
                self.w_version = None;
                self.last_problem = None;
                report.matrix_free = true;
                self.solve_matrix_free_active(&free, &mut report)?
            } else {
                if active != self.w_active
                    || self.w_version != Some(version)
                    || (!self.settings.skip.reuse_flexibility && report.detection_passes == 1)
                {
                    self.build_flexibility(&active)?;
                    self.w_version = Some(version);
                    report.flexibility_rebuilt = true;
                }
                self.solve_active(&free, dt, &mut report)?
            };
            // u = u_free + K⁻¹ Hᵀ r
            u.fill(0.0);
            for (k, &i) in self.w_active.iter().enumerate() {
                for d in 0..2 {
                    let r = solved.r[2 * k + d];
                    for &(dof, a) in &self.h_rows[2 * i + d] {
                        u[dof] += a * r;
                    }
                }
            }
            self.structure.solve_in_place(&mut u)?;
            self.counters.structure_solves += 1;
            for (a, b) in u.iter_mut().zip(&u_free) {
                *a += b;
            }
            let mut jumps = self.local_jumps_of(&u);
            // active contacts: the reduced solution's own jumps. Recomputing them from `u` adds
            // the rounding of `u` (an ulp of the load) times the stiffness contrast, which is
            // large for stiff glue (C h / E ≫ 1); the next step starts from these jumps.
            for (k, &i) in self.w_active.iter().enumerate() {
                jumps[i][0] = solved.x[2 * k];
                if self.tangent_needed(i) {
                    jumps[i][1] = self.jumps[i][1] + solved.x[2 * k + 1];
                }
            }
            let penetrating: Vec<usize> = (0..self.candidates.len())
                .filter(|i| self.w_active.binary_search(i).is_err() && jumps[*i][0] < 0.0)
                .collect();
            if penetrating.is_empty()
                || report.detection_passes >= self.settings.max_detection_passes
            {
                return Ok(self.accept(time, u, jumps, solved, report, start));
            }
            active.extend(penetrating);
            active.sort_unstable();
        }
    }

    /// How this step's active set is solved.
    fn path(&self, active: &[usize]) -> Result<Path, SolverError> {
        let adhesive = active.iter().any(|&i| {
            let law = &self.zones[self.candidates[i].zone].law;
            law.has_adhesion() && law.adhesion_active(&self.states[i])
        });
        match self.settings.flexibility {
            FlexibilityMode::Dense => Ok(Path::Dense),
            FlexibilityMode::Auto { dense_limit } => {
                if adhesive || active.len() <= dense_limit {
                    Ok(Path::Dense)
                } else if let Ok(f) = self.active_set_frames(active) {
                    Ok(Path::ActiveSet(f))
                } else {
                    Ok(Path::MatrixFree)
                }
            }
            FlexibilityMode::MatrixFree | FlexibilityMode::ActiveSet if adhesive => {
                Err(SolverError::InvalidSetting {
                    what: "flexibility",
                    value: active.len() as f64,
                    expected: "Dense or Auto for adhesive laws (the springs are condensed on a dense F*)",
                })
            }
            FlexibilityMode::MatrixFree if active.is_empty() => Ok(Path::Dense),
            FlexibilityMode::MatrixFree => Ok(Path::MatrixFree),
            FlexibilityMode::ActiveSet if active.is_empty() => Ok(Path::Dense),
            FlexibilityMode::ActiveSet => self
                .active_set_frames(active)
                .map(Path::ActiveSet)
                .map_err(SolverError::Unsupported),
        }
    }

    /// The local frames of the primal active-set path, or why it does not apply.
    fn active_set_frames(&self, active: &[usize]) -> Result<Vec<LocalFrame>, String> {
        if self.structure.stiffness_matrix().is_none() {
            return Err("the structure does not expose its stiffness matrix".into());
        }
        let mut frictional = Vec::with_capacity(active.len());
        for &i in active {
            let law = &self.zones[self.candidates[i].zone].law;
            if law.friction_coefficient(&self.states[i]).is_none() {
                return Err(format!(
                    "zone `{}`: its law has no friction coefficient (not a Coulomb-cone law)",
                    self.zones[self.candidates[i].zone].name
                ));
            }
            frictional.push(self.tangent_needed(i));
        }
        frames(
            &self.h_rows,
            active,
            &frictional,
            self.structure.dof_count(),
        )
    }

    /// The primal active-set solve of the step (no `F*`).
    fn solve_active_set(
        &mut self,
        free: &[[f64; 2]],
        frames: &[LocalFrame],
        report: &mut StepReport,
    ) -> Result<Solved<L::State>, SolverError> {
        let active = self.w_active.clone();
        let laws: Vec<L> = active
            .iter()
            .map(|&i| self.zones[self.candidates[i].zone].law.clone())
            .collect();
        let states: Vec<L::State> = active.iter().map(|&i| self.states[i]).collect();
        let tangent: Vec<bool> = active.iter().map(|&i| self.tangent_needed(i)).collect();
        let mu: Vec<f64> = laws
            .iter()
            .zip(&states)
            .map(|(l, s)| l.friction_coefficient(s).unwrap_or(0.0))
            .collect();
        let mut q = vec![0.0; 2 * active.len()];
        for (k, &i) in active.iter().enumerate() {
            q[2 * k] = free[i][0];
            if tangent[k] {
                q[2 * k + 1] = free[i][1] - self.jumps[i][1];
            }
        }
        let r0: Vec<f64> = active.iter().flat_map(|&i| self.r_bar[i]).collect();
        let step = PrimalStep {
            active: &active,
            frames,
            laws: &laws,
            states: &states,
            mu: &mu,
            tangent: &tangent,
            q: &q,
            r0: &r0,
            tol: self.settings.solver.tol,
            max_iterations: self
                .settings
                .solver
                .max_iterations
                .min(crate::primal::PRIMAL_MAX_ITERATIONS),
            accept_non_converged: self.settings.solver.accept_non_converged,
        };
        let before = self.primal.factorizations;
        let sol = solve_primal(&self.structure, &mut self.primal, &step)?;
        self.counters.active_set_steps += 1;
        self.counters.active_set_factorizations += self.primal.factorizations - before;
        self.counters.active_set_solves += sol.solves;
        report.contact_iterations += sol.iterations;
        report.residual = sol.residual;
        report.converged &= sol.converged;
        Ok(Solved {
            r: sol.r.clone(),
            r_bar: sol.r,
            x: sol.x,
            statuses: sol.statuses,
            states,
        })
    }

    /// `ρ⁰_i = 1/λ_max` of the diagonal blocks of `F*`, computed exactly on up to
    /// [`RHO_SAMPLES`] contacts spread over the active list and carried to the others from the
    /// nearest sample in that order (interfaces are listed in order along them).
    fn estimate_rho0(&mut self, active: &[usize]) -> Result<Vec<f64>, SolverError> {
        let na = active.len();
        let ns = na.min(RHO_SAMPLES);
        let samples: Vec<usize> = (0..ns).map(|k| (2 * k + 1) * na / (2 * ns)).collect();
        let ndof = self.structure.dof_count();
        let mut x = Mat::<f64>::zeros(ndof, 2 * ns);
        for (c, &k) in samples.iter().enumerate() {
            let i = active[k];
            for d in 0..2 {
                for &(dof, a) in &self.h_rows[2 * i + d] {
                    x[(dof, 2 * c + d)] += a;
                }
            }
        }
        self.structure.solve_many_in_place(x.as_mut())?;
        self.counters.flexibility_columns += 2 * ns;
        let rho: Vec<f64> = samples
            .iter()
            .enumerate()
            .map(|(c, &k)| {
                let i = active[k];
                let w = |row: usize, col: usize| -> f64 {
                    self.h_rows[2 * i + row]
                        .iter()
                        .map(|&(dof, a)| a * x[(dof, 2 * c + col)])
                        .sum()
                };
                let (a, b, d) = (w(0, 0), 0.5 * (w(0, 1) + w(1, 0)), w(1, 1));
                let h = 0.5 * (a - d);
                1.0 / (0.5 * (a + d) + (h * h + b * b).sqrt())
            })
            .collect();
        Ok((0..na)
            .map(|k| {
                let nearest = samples
                    .iter()
                    .enumerate()
                    .min_by_key(|(_, s)| s.abs_diff(k))
                    .map_or(0, |(c, _)| c);
                rho[nearest]
            })
            .collect())
    }

    /// The reduced solve without `F*`: one structure solve per product `F* r`.
    fn solve_matrix_free_active(
        &mut self,
        free: &[[f64; 2]],
        report: &mut StepReport,
    ) -> Result<Solved<L::State>, SolverError> {
        let active = self.w_active.clone();
        let na = active.len();
        let m = 2 * na;
        let laws: Vec<L> = active
            .iter()
            .map(|&i| self.zones[self.candidates[i].zone].law.clone())
            .collect();
        let states: Vec<L::State> = active.iter().map(|&i| self.states[i]).collect();
        let mut q = vec![0.0; m];
        for (k, &i) in active.iter().enumerate() {
            q[2 * k] = free[i][0];
            if self.tangent_needed(i) {
                q[2 * k + 1] = free[i][1] - self.jumps[i][1];
            }
        }
        let rho0 = self.estimate_rho0(&active)?;
        let mut r: Vec<f64> = active.iter().flat_map(|&i| self.r_bar[i]).collect();
        let mut x = vec![0.0; m];
        let rows: Vec<usize> = active.iter().flat_map(|&i| [2 * i, 2 * i + 1]).collect();
        let (structure, h_rows) = (&self.structure, &self.h_rows);
        let mut scratch = vec![0.0; structure.dof_count()];
        let mut applications = 0;
        let apply = |r: &[f64], x: &mut [f64]| -> Result<(), SolverError> {
            scratch.fill(0.0);
            for (j, &row) in rows.iter().enumerate() {
                if r[j] != 0.0 {
                    for &(dof, a) in &h_rows[row] {
                        scratch[dof] += a * r[j];
                    }
                }
            }
            structure.solve_in_place(&mut scratch)?;
            applications += 1;
            for (j, &row) in rows.iter().enumerate() {
                x[j] = q[j]
                    + h_rows[row]
                        .iter()
                        .map(|&(dof, a)| a * scratch[dof])
                        .sum::<f64>();
            }
            Ok(())
        };
        let mf = solve_matrix_free(
            apply,
            &laws,
            &states,
            &rho0,
            &self.settings.solver,
            &mut r,
            &mut x,
        )?;
        self.counters.operator_applications += applications;
        self.counters.structure_solves += applications;
        self.counters.matrix_free_steps += 1;
        report.contact_iterations += mf.iterations;
        report.residual = mf.residual;
        report.converged &= mf.converged;
        let statuses = contact_statuses(&laws, &states, &rho0, &r, &x);
        Ok(Solved {
            r: r.clone(),
            r_bar: r,
            x,
            statuses,
            states,
        })
    }

    /// `F* = H K⁻¹ Hᵀ` on `active`, in chunks of right-hand sides.
    fn build_flexibility(&mut self, active: &[usize]) -> Result<(), SolverError> {
        let m = 2 * active.len();
        let ndof = self.structure.dof_count();
        self.w.clear();
        self.w.resize(m * m, 0.0);
        // local rows of W (index into 0..m) whose columns are solved for
        let solved: Vec<usize> = (0..m)
            .filter(|&j| j % 2 == 0 || self.tangent_needed(active[j / 2]))
            .collect();
        let chunk = self.settings.columns_per_solve.min(solved.len().max(1));
        let mut x = Mat::<f64>::zeros(ndof, chunk);
        let rows: Vec<usize> = active.iter().flat_map(|&i| [2 * i, 2 * i + 1]).collect();
        for block in solved.chunks(chunk) {
            let nc = block.len();
            x.fill(0.0);
            for (c, &j) in block.iter().enumerate() {
                for &(dof, a) in &self.h_rows[rows[j]] {
                    x[(dof, c)] += a;
                }
            }
            self.structure
                .solve_many_in_place(x.as_mut().subcols_mut(0, nc))?;
            for &i in &solved {
                let row = &self.h_rows[rows[i]];
                for (c, &j) in block.iter().enumerate() {
                    let mut s = 0.0;
                    for &(dof, a) in row {
                        s += a * x[(dof, c)];
                    }
                    self.w[i * m + j] = s;
                }
            }
        }
        symmetrize(&mut self.w, m);
        // decoupled tangential unknowns of frictionless contacts: W_tt = W_nn, nothing else
        for (k, &i) in active.iter().enumerate() {
            if !self.tangent_needed(i) {
                self.w[(2 * k + 1) * m + 2 * k + 1] = self.w[2 * k * m + 2 * k];
            }
        }
        self.w_active.clear();
        self.w_active.extend_from_slice(active);
        self.counters.flexibility_builds += 1;
        self.counters.flexibility_columns += solved.len();
        Ok(())
    }

    /// Whether candidate `i`'s tangential unknown takes part (friction or adhesion), under the
    /// skip rules.
    fn tangent_needed(&self, i: usize) -> bool {
        let law = &self.zones[self.candidates[i].zone].law;
        !self.settings.skip.frictionless_normal_only || law.has_friction() || law.has_adhesion()
    }

    /// The adhesion fixed point around the reduced solve, on the cached active set.
    fn solve_active(
        &mut self,
        free: &[[f64; 2]],
        dt: f64,
        report: &mut StepReport,
    ) -> Result<Solved<L::State>, SolverError> {
        let active = &self.w_active;
        let m = 2 * active.len();
        let laws: Vec<L> = active
            .iter()
            .map(|&i| self.zones[self.candidates[i].zone].law.clone())
            .collect();
        let start_states: Vec<L::State> = active.iter().map(|&i| self.states[i]).collect();
        let u_start: Vec<[f64; 2]> = active.iter().map(|&i| self.jumps[i]).collect();
        let areas: Vec<f64> = active.iter().map(|&i| self.candidates[i].area).collect();
        // q = (g₀ + n·u_rel(u_free), t·u_rel(u_free) − u_t,start)
        let mut q = vec![0.0; m];
        for (k, &i) in active.iter().enumerate() {
            q[2 * k] = free[i][0];
            if self.tangent_needed(i) {
                q[2 * k + 1] = free[i][1] - self.jumps[i][1];
            }
        }
        let r_bar: Vec<f64> = active.iter().flat_map(|&i| self.r_bar[i]).collect();
        let step = AdhesiveStep {
            w: &self.w,
            q: &q,
            laws: &laws,
            start_states: &start_states,
            u_start: &u_start,
            areas: &areas,
            dt,
        };
        let options = AdhesionOptions {
            tol: self.settings.adhesion_tol,
            max_iterations: self.settings.max_adhesion_iterations,
            accept_non_converged: self.settings.solver.accept_non_converged,
            always_iterate: !self.settings.skip.adhesion_loop_only_when_adhesive,
            anderson_window: self.settings.adhesion_anderson_window,
        };
        let sol = solve_adhesive(&mut self.solver, &step, Some(&r_bar), &options)?;
        report.contact_iterations += sol.contact_iterations;
        report.adhesion_iterations += sol.adhesion_iterations;
        report.residual = sol.report.residual;
        report.converged &= sol.converged;
        self.last_problem = Some(sol.condensed);
        Ok(Solved {
            r: sol.r,
            r_bar: sol.r_bar,
            x: sol.x,
            statuses: sol.report.statuses,
            states: sol.states,
        })
    }

    fn accept(
        &mut self,
        time: f64,
        u: Vec<f64>,
        jumps: Vec<[f64; 2]>,
        solved: Solved<L::State>,
        mut report: StepReport,
        start: Instant,
    ) -> StepResult {
        let mut records: Vec<ContactRecord> = self
            .candidates
            .iter()
            .enumerate()
            .map(|(i, c)| ContactRecord {
                zone: c.zone,
                node: c.node,
                position: self.structure.node_position(c.node),
                area: c.area,
                status: InterfaceStatus::Inactive,
                gap: jumps[i][0],
                u_t: jumps[i][1],
                slip_increment: jumps[i][1] - self.jumps[i][1],
                beta: self.zones[c.zone].law.adhesion_intensity(&self.states[i]),
                r: [0.0; 2],
                r_bar: [0.0; 2],
                r_adh: [0.0; 2],
            })
            .collect();
        for r in self.r_bar.iter_mut() {
            *r = [0.0; 2];
        }
        for (k, &i) in self.w_active.iter().enumerate() {
            let law = &self.zones[self.candidates[i].zone].law;
            self.states[i] = solved.states[k];
            let rb = [solved.r_bar[2 * k], solved.r_bar[2 * k + 1]];
            self.r_bar[i] = rb;
            let rec = &mut records[i];
            rec.beta = law.adhesion_intensity(&self.states[i]);
            rec.r_bar = rb;
            rec.r = [solved.r[2 * k], solved.r[2 * k + 1]];
            rec.r_adh = [rec.r[0] - rb[0], rec.r[1] - rb[1]];
            rec.status = match solved.statuses[k] {
                ContactStatus::Separation => InterfaceStatus::Open,
                ContactStatus::Stick => InterfaceStatus::Stick,
                ContactStatus::Slip => InterfaceStatus::Slip,
            };
        }
        self.jumps = jumps;
        self.u = u;
        self.time = time;
        self.counters.steps += 1;
        self.counters.adhesion_iterations += report.adhesion_iterations;
        self.counters.contact_iterations += report.contact_iterations;
        report.active_contacts = self.w_active.len();
        report.wall_time = start.elapsed();
        StepResult {
            report,
            contacts: records,
        }
    }
}

/// How one detection pass solves its active set.
#[derive(Debug, PartialEq)]
enum Path {
    Dense,
    MatrixFree,
    ActiveSet(Vec<LocalFrame>),
}

/// Contacts whose diagonal block of `F*` is computed exactly to set `ρ⁰` in matrix-free steps.
const RHO_SAMPLES: usize = 16;

/// The solution of the reduced problem of a step, on the active set.
struct Solved<T> {
    r: Vec<f64>,
    r_bar: Vec<f64>,
    /// `x = (gap, slip increment)` of the reduced solution.
    x: Vec<f64>,
    statuses: Vec<ContactStatus>,
    states: Vec<T>,
}

fn nodal<S: Structure + ?Sized>(s: &S, u: &[f64], node: usize) -> [f64; 2] {
    let mut v = s.prescribed_displacement(node);
    for (c, d) in s.node_dofs(node).into_iter().enumerate() {
        if let Some(i) = d {
            v[c] = u[i];
        }
    }
    v
}

pub(crate) fn symmetrize(w: &mut [f64], m: usize) {
    for i in 0..m {
        for j in 0..i {
            let a = 0.5 * (w[i * m + j] + w[j * m + i]);
            w[i * m + j] = a;
            w[j * m + i] = a;
        }
    }
}
