//! The contact simulation (seed 5.3–5.5): a [`Structure`], contact zones, and one
//! [`ContactSimulation::step`] per load increment ([`QuasiStatic`]) or per time step of another
//! [`TimeScheme`].
//!
//! # One step (`docs/theory.md` §13), stage by stage
//! [`ContactSimulation::step`] is the list of the stages; each takes what it reads and returns
//! what it makes, one file each: `detection` (the inputs, the renumbering, 1–2, the
//! penetration check), `path` and `flexibility` (3), `solve` and `floating` (4–5),
//! `equilibrium` (6, the acceptance and the report). The state they read and write is in three
//! parts (`parts`): the interface (zones, candidates, `H`), the accepted state carried between
//! steps, and the operator cache. What the time discretisation decides (the free response,
//! `q`, the acceptance) goes through the [`TimeScheme`] seam (`scheme`), quasi-static below;
//! `settings` and `report` hold the public data types; `newton` iterates these stages on the
//! tangent of a nonlinear structure ([`ContactSimulation::with_newton`]).
//!
//! ```text
//! check_step(time, force_factor, now)                        -> Result<()>
//! follow_structure()                                         -> stiffness version
//! free_response(clock)             [scheme: free response]   -> FreeResponse { y, jumps, mode_load }
//! Interface::initial_active_set(settings, accepted, jumps)   -> active
//! loop:
//!   solve_pass(active, free, dt, version)  [scheme: q]       -> Pass::Solved(Solved { active, r, x, … }) | Pass::Extend
//!   equilibrium(clock, free, solved)  [scheme: displacement] -> Equilibrium { solution, jumps }
//!   Interface::penetrating(solved.active, jumps)             -> penetrating candidates
//!   accept(clock, equilibrium, solved)  [scheme: accept]     -> StepResult (once none penetrates)
//! ```
//!
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

mod choice;
mod detection;
mod dispatch;
mod energy;
mod equilibrium;
mod flexibility;
mod floating;
mod last_problem;
mod moreau_jean;
mod newton;
mod newton_springs;
mod parts;
mod path;
mod report;
mod scheme;
mod settings;
mod solve;
mod tuning;
mod velocity_adhesion;

pub use choice::{PathChoice, PathReason, SolvePath};
pub use energy::EnergyBalance;
pub use moreau_jean::{AdhesionUpdate, MoreauJean};
pub use newton::{NEWTON_DENSE_LIMIT, NewtonSettings};
pub use report::{ContactRecord, Counters, InterfaceStatus, NewtonReport, StepReport, StepResult};
pub use scheme::{AcceptedContact, QuasiStatic, SchemeStep, TimeScheme, VelocitySprings};
pub use settings::{DEFAULT_DENSE_LIMIT, FlexibilityMode, SimulationSettings};
pub use tuning::{SimulationTuning, SkipRules};

use crate::coupling::force_factor::ForceFactorCheck;
use crate::coupling::space::ContactSpace;
use crate::coupling::zone::{Candidate, ContactZone};
use crate::error::SolverError;
use crate::local::adhesion::WarmStartPacing;
use crate::local::{ReducedProblem, UzawaSolver};
use contact_laws::ContactLaw;
use detection::FreeResponse;
use detection::check_step;
use equilibrium::Equilibrium;
use fem_core::{Dim, Structure};
use parts::{Accepted, Interface, OperatorCache};
use solve::{Pass, Solved};
use std::time::Instant;

/// A quasi-static contact simulation: structure, zones, per-contact state and the cached `F*`.
///
/// # Examples
/// An elastic block (P1, plane strain) pressed on a rigid LINE by a prescribed displacement of
/// its top: the bottom nodes come into contact and the pressure is uniform.
/// ```
/// use contact_solver::{ContactSimulation, ContactZone, SimulationSettings};
/// use contact_solver::coupling::obstacle::RigidLine;
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
/// let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
/// assert!((total - 1.0).abs() < 1e-9);         // σ = E ε = 100 × 0.01 over a width of 1
/// assert!(res.contacts.iter().all(|c| c.gap.abs() < 1e-11)); // closed to 1e-9 of the 0.01 push
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// The same simulation solves 3D problems as `ContactSimulation<S, L, 3>` (a
/// [`Structure<3>`] and [`ContactZone<L, 3>`]): per contact the unknowns are `D` consecutive
/// components `(n, t…)`, and what differs by dimension comes from [`ContactSpace`].
///
/// The time discretisation is the type parameter `T`, a [`TimeScheme`]: [`QuasiStatic`] (load
/// steps) unless built by [`Self::with_scheme`].
///
/// # The state, in parts
/// Besides the structure and the settings, a simulation holds three parts, each written by the
/// stages that own it: `Interface` (zones, candidates, the rows of `H`), `Accepted` (what a
/// step carries to the next: law states, jumps, reactions, displacements, time) and
/// `OperatorCache` (the dense `F*`, the primal factorisations, their active set, the last
/// reduced problem).
pub struct ContactSimulation<S: Structure<D>, L: ContactLaw, const D: usize = 2, T = QuasiStatic>
where
    Dim<D>: ContactSpace<D>,
{
    structure: S,
    settings: SimulationSettings,
    scheme: T,
    interface: Interface<L, D>,
    accepted: Accepted<L::State, D>,
    cache: OperatorCache<L, D>,
    solver: UzawaSolver,
    /// When adhesive steps try Newton from the previous step's reactions.
    warm: WarmStartPacing,
    counters: Counters,
    /// The check of `step`'s force factor (until the structure shows applied forces).
    force_check: ForceFactorCheck,
    /// The global Newton of a nonlinear structure, when chosen ([`Self::with_newton`]).
    newton: Option<newton::NewtonState<D>>,
}

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize> ContactSimulation<S, L, D>
where
    Dim<D>: ContactSpace<D>,
{
    /// Recognises the candidates of `zones` on `structure` (reference configuration) and
    /// starts at time 0 with every law's initial state, stepping quasi-statically
    /// ([`QuasiStatic`]; another scheme: [`Self::with_scheme`]).
    ///
    /// # Errors
    /// As for [`recognize`](crate::coupling::zone::recognize); [`SolverError::InvalidSetting`] naming the setting for bad
    /// settings (a tolerance that is not finite and positive, a zero count);
    /// [`SolverError::InvalidGeometry`] if no zone has a candidate.
    pub fn new(
        structure: S,
        zones: Vec<ContactZone<L, D>>,
        settings: SimulationSettings,
    ) -> Result<Self, SolverError> {
        Self::with_scheme(structure, zones, settings, QuasiStatic)
    }
}

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize, T: TimeScheme<S, D>>
    ContactSimulation<S, L, D, T>
where
    Dim<D>: ContactSpace<D>,
{
    /// As [`ContactSimulation::new`], stepping with the time scheme `scheme` (the example of
    /// [`TimeScheme`] plugs one).
    ///
    /// # Errors
    /// As [`ContactSimulation::new`].
    pub fn with_scheme(
        structure: S,
        zones: Vec<ContactZone<L, D>>,
        settings: SimulationSettings,
        scheme: T,
    ) -> Result<Self, SolverError> {
        settings.check()?;
        let interface =
            Interface::recognize(&structure, zones, settings.relative_penetration_tol::<D>())?;
        let accepted = Accepted::start(&structure, &interface);
        Ok(Self {
            structure,
            settings,
            scheme,
            interface,
            accepted,
            cache: OperatorCache::new(),
            solver: UzawaSolver::new(settings.solver),
            warm: WarmStartPacing::default(),
            counters: Counters::default(),
            force_check: ForceFactorCheck::default(),
            newton: None,
        })
    }

    /// The time scheme.
    pub fn scheme(&self) -> &T {
        &self.scheme
    }

    /// The time scheme, to change its parameters between steps.
    pub fn scheme_mut(&mut self) -> &mut T {
        &mut self.scheme
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
    pub fn zones(&self) -> &[ContactZone<L, D>] {
        &self.interface.zones
    }

    /// Replaces the law of the zone named `zone` from the next step on: laws and parameters
    /// by phase (press without friction, then shear with it; another `μ`; other RCCM
    /// parameters). Every candidate's state (`β`) and its accepted jump (the gap and the
    /// tangential reference of the slip) carry over unchanged: the next step starts from the
    /// last accepted one, under the new law. The cached `F*` is rebuilt at the next step,
    /// since whether a contact's tangential unknown takes part depends on the law.
    ///
    /// # Errors
    /// [`SolverError::UnknownZone`] if no zone has that name (nothing changes then).
    ///
    /// # Examples
    /// ```
    /// use contact_solver::{ContactSimulation, ContactZone, SimulationSettings};
    /// use contact_solver::coupling::obstacle::RigidLine;
    /// use contact_laws::{Coulomb, Signorini, StandardLaw};
    /// use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};
    /// use fem_core::generate::{RectangleSpec, rectangle};
    ///
    /// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2))?;
    /// let (top, bottom) = (mesh.node_set("top")?.to_vec(), mesh.node_set("bottom")?.to_vec());
    /// let mut supports = Supports::new();
    /// supports.prescribe(&top, Component::Y, -0.01)?.fix(&top, Component::X);
    /// let model = LinearElasticModel::new(mesh, Idealization::PlaneStrain,
    ///     &[(0, Material::new(100.0, 0.3, 0.0)?)], supports)?;
    /// let ground = RigidLine::new([-1.0, 0.0], [2.0, 0.0])?;
    /// let zone = ContactZone::rigid("base", bottom, ground, StandardLaw::from(Signorini), 0.1);
    /// let mut sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default())?;
    /// sim.step(1.0, 1.0)?; // pressed without friction
    /// sim.set_law("base", Coulomb::new(0.3)?.into())?; // then with friction
    /// assert!(sim.set_law("basis", Signorini.into()).is_err()); // names the zones it has
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn set_law(&mut self, zone: &str, law: L) -> Result<(), SolverError> {
        let Some(z) = self.interface.zones.iter_mut().find(|z| z.name == zone) else {
            return Err(SolverError::UnknownZone {
                name: zone.to_string(),
                known: self
                    .interface
                    .zones
                    .iter()
                    .map(|z| format!("`{}`", z.name))
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        };
        if D == 3 && law.has_adhesion() && z.areas.is_none() {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{zone}`: an adhesive law needs the contactor nodes' tributary areas"
            )));
        }
        z.law = law;
        self.cache.invalidate();
        Ok(())
    }

    /// The candidates found by recognition.
    pub fn candidates(&self) -> &[Candidate<D>] {
        &self.interface.candidates
    }

    /// The settings.
    pub fn settings(&self) -> &SimulationSettings {
        &self.settings
    }

    /// Replaces the settings from the next step on (e.g. to switch algorithm between steps).
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] as [`Self::new`] (nothing changes then).
    pub fn set_settings(&mut self, settings: SimulationSettings) -> Result<(), SolverError> {
        settings.check()?;
        self.settings = settings;
        self.solver = UzawaSolver::new(settings.solver);
        self.interface.set_relative_penetration_tol(
            &self.structure,
            settings.relative_penetration_tol::<D>(),
        );
        Ok(())
    }

    /// Current time.
    pub fn time(&self) -> f64 {
        self.accepted.time
    }

    /// Per-candidate law states at the end of the last step.
    pub fn states(&self) -> &[L::State] {
        &self.accepted.states
    }

    /// Counters since the start.
    pub fn counters(&self) -> Counters {
        self.counters
    }

    /// The free-dof displacements at the end of the last step, in the dof numbering of that
    /// step (a change of supports since renumbers the structure's dofs; the next step follows).
    pub fn displacement(&self) -> &[f64] {
        &self.accepted.u
    }

    /// Nodal displacements `[u_x, u_y]` (`[u_x, u_y, u_z]` in 3D) at the end of the last
    /// step (prescribed components included).
    pub fn nodal_displacements(&self) -> Vec<[f64; D]> {
        self.accepted.nodal_u.clone()
    }

    /// The displacement of `node` at the end of the last step (prescribed components
    /// included).
    ///
    /// # Panics
    /// If `node >= node_count()`.
    #[track_caller]
    pub fn nodal_displacement(&self, node: usize) -> [f64; D] {
        self.accepted.nodal_u[node]
    }

    /// The reduced problem of the last solve — after condensation of the adhesive springs,
    /// with `μ̄` per contact — on the active contacts (see [`Self::last_active`]); export it
    /// with [`ReducedProblem::to_json`] to re-solve it elsewhere (e.g. Siconos). `None` when the
    /// last step was solved without a dense `F*` (matrix-free or active set; force
    /// `FlexibilityMode::Dense` to export a large step).
    pub fn last_reduced_problem(&self) -> Option<&ReducedProblem> {
        self.cache.last_problem.get(&self.cache.w)
    }

    /// Candidate indices of the contacts of the last reduced problem, in its order.
    pub fn last_active(&self) -> &[usize] {
        &self.cache.active
    }

    /// Floating structures ([`Structure::floating`]): the amplitudes `α` of the
    /// rigid-body modes in the displacement `u = K⁺(f + Hᵀ r) + R α` at the end of the last
    /// step, one per mode (empty for a supported structure).
    pub fn rigid_body_amplitudes(&self) -> &[f64] {
        &self.accepted.alpha
    }

    /// Resets the displacement and the tangential reference to zero while keeping the law
    /// states (e.g. after an installation phase whose displacements are discarded).
    pub fn reset_displacements(&mut self) {
        self.accepted
            .reset_displacements(&self.structure, &self.interface);
    }

    /// Solves one load step ending at `time` (`≥` the current time) with the structure's
    /// applied forces scaled by `force_factor`.
    ///
    /// `force_factor` scales the applied forces only (point loads, tractions, body forces:
    /// [`Structure::free_response_into`]): **prescribed displacements are not scaled** and
    /// enter at their current values, as do initial stresses. To ramp a prescribed
    /// displacement, set its value before each step through [`Self::structure_mut`] (`bipo`'s
    /// time tables do that) and step with the factor 1. A factor other than 1 on a structure
    /// without applied forces would change nothing and is refused.
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] if `time` is not finite or goes backwards, if
    /// `force_factor` is not finite, or if it is not 1 while the structure has no applied force
    /// for it to scale; [`SolverError::Structure`] if a structure solve fails;
    /// [`SolverError::NotConverged`] or [`SolverError::AdhesionNotConverged`] unless the
    /// settings accept non-converged results; [`SolverError::StillPenetrating`] if candidates
    /// outside the reduced problem still penetrate after
    /// [`max_detection_passes`](SimulationTuning::max_detection_passes) passes. On error the simulation keeps the state of the
    /// previous step. With the global Newton ([`Self::with_newton`]) the step is cut on
    /// those failures, and [`SolverError::NewtonNotConverged`] reports the load reached
    /// (the simulation keeping the last converged sub-step).
    ///
    /// # Examples
    /// A block pressed by a prescribed displacement of its top: the displacement is ramped
    /// through the structure, not by the factor.
    /// ```
    /// use contact_solver::{ContactSimulation, ContactZone, SimulationSettings};
    /// use contact_solver::coupling::obstacle::RigidLine;
    /// use contact_laws::Signorini;
    /// use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};
    /// use fem_core::generate::{RectangleSpec, rectangle};
    ///
    /// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2))?;
    /// let (top, bottom) = (mesh.node_set("top")?.to_vec(), mesh.node_set("bottom")?.to_vec());
    /// let mut supports = Supports::new();
    /// supports.prescribe(&top, Component::Y, 0.0)?.fix(&top, Component::X);
    /// let model = LinearElasticModel::new(mesh, Idealization::PlaneStrain,
    ///     &[(0, Material::new(100.0, 0.0, 0.0)?)], supports)?;
    /// let ground = RigidLine::new([-1.0, 0.0], [2.0, 0.0])?;
    /// let zone = ContactZone::rigid("base", bottom, ground, Signorini, 0.1);
    /// let mut sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default())?;
    /// for k in 1..=2 {
    ///     sim.structure_mut().set_prescribed(&top, Component::Y, -0.005 * k as f64)?;
    ///     let res = sim.step(k as f64, 1.0)?;
    ///     let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
    ///     assert!((total - 0.5 * k as f64).abs() < 1e-9); // E × 0.005 k over a width of 1
    /// }
    /// // the factor scales forces only: on this structure (no force) 0.5 is refused
    /// assert!(sim.step(3.0, 0.5).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn step(&mut self, time: f64, force_factor: f64) -> Result<StepResult<D>, SolverError> {
        if let Some(from) = self.newton.as_ref().map(newton::NewtonState::start) {
            return self.newton_step(time, force_factor, from);
        }
        let start = Instant::now();
        check_step(time, force_factor, self.accepted.time)?;
        let version = self.follow_structure()?;
        let clock = Clock {
            time,
            dt: time - self.accepted.time,
            force_factor,
        };
        // 1. detection: the free response (the scheme's) and the active set
        let free = self.free_response(clock)?;
        self.force_check
            .check(&self.structure, force_factor, &free.y)?;
        let scheme = &self.scheme;
        let active = self.interface.initial_active_set(
            &self.settings,
            &self.accepted,
            &free.jumps,
            |i, start, free, alert, all| scheme.enters(i, start, free, alert, all),
        );
        let mut report = StepReport::start(self.counters.steps + 1, time, force_factor);
        let (equilibrium, solved) = self.passes(clock, &free, active, version, &mut report)?;
        // 5. acceptance (the scheme's, then the carried state) and the report
        Ok(self.accept(clock, equilibrium, solved, report, start))
    }

    /// Stages 2–4 of a step from its `free` response and initial `active` set: the detection
    /// passes (path, operator, local solve, equilibrium, penetration check) until no inactive
    /// candidate penetrates; the last pass's equilibrium and reduced solution, not accepted.
    ///
    /// # Errors
    /// As [`Self::step`].
    fn passes(
        &mut self,
        clock: Clock,
        free: &FreeResponse<D>,
        mut active: Vec<usize>,
        version: u64,
        report: &mut StepReport,
    ) -> Result<(Equilibrium<D>, Solved<L::State>), SolverError> {
        loop {
            report.detection_passes += 1;
            // 2–3. the path and its operator, then the local solve (with the adhesion loop)
            let solved = match self.solve_pass(&active, free, clock.dt, version, report)? {
                Pass::Solved(solved) => solved,
                Pass::Extend(more) => {
                    // a rigid motion of a floating body closes candidates outside the set
                    active.extend(more);
                    active.sort_unstable();
                    active.dedup();
                    continue;
                }
            };
            // 4. equilibrium (the scheme's displacement), then the penetration check
            let equilibrium = self.equilibrium(clock, free, &solved)?;
            let scheme = &self.scheme;
            let penetrating =
                self.interface
                    .penetrating(&solved.active, &equilibrium.jumps, |i, jump, tol| {
                        scheme.penetrates(i, jump, tol)
                    });
            if penetrating.is_empty() {
                return Ok((equilibrium, solved));
            }
            if report.detection_passes >= self.settings.tuning.max_detection_passes {
                // issue 35: accepting the step would return contacts that penetrate
                return Err(self.interface.still_penetrating(
                    &penetrating,
                    &equilibrium.jumps,
                    report.detection_passes,
                ));
            }
            active.extend(penetrating);
            active.sort_unstable();
        }
    }

    /// Whether candidate `i`'s tangential unknown takes part (friction or adhesion), under the
    /// skip rules ([`Interface::tangent_needed`]).
    pub(super) fn tangent_needed(&self, i: usize) -> bool {
        self.interface.tangent_needed(i, &self.settings)
    }

    /// Whether the tangential component `d` (`1..D`) of candidate `i` is solved
    /// ([`Interface::tangent_solved`]).
    pub(super) fn tangent_solved(&self, i: usize, d: usize) -> bool {
        self.interface.tangent_solved(i, d, &self.settings)
    }
}

/// The step's times and force factor, as the stages pass them on.
#[derive(Clone, Copy, Debug)]
struct Clock {
    /// Time at the end of the step.
    time: f64,
    /// Length of the step.
    dt: f64,
    /// Factor on the applied forces.
    force_factor: f64,
}

impl Clock {
    /// What the time scheme is told, with the accepted state `accepted` of the last step.
    fn scheme_step<'a, T, const D: usize>(self, accepted: &'a Accepted<T, D>) -> SchemeStep<'a> {
        SchemeStep::new(
            self.time,
            self.dt,
            self.force_factor,
            &accepted.u,
            &accepted.alpha,
        )
    }
}
