//! The quasi-static contact simulation (seed 5.3–5.5): a [`Structure`], contact zones, and one
//! [`ContactSimulation::step`] per load increment.
//!
//! # One step (`docs/theory.md` §13), stage by stage
//! [`ContactSimulation::step`] is the list of the stages, one file each: `detection` (1–2 and
//! the penetration check), `path` and `flexibility` (3), `solve` (4–5), `equilibrium` (6 and
//! the report); `settings` and `report` hold the public data types.
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

mod detection;
mod dispatch;
mod equilibrium;
mod flexibility;
mod floating;
mod last_problem;
mod path;
mod report;
mod settings;
mod solve;
mod tuning;

pub use report::{ContactRecord, Counters, InterfaceStatus, StepReport, StepResult};
pub use settings::{DEFAULT_DENSE_LIMIT, FlexibilityMode, SimulationSettings};
pub use tuning::{SimulationTuning, SkipRules};

use crate::coupling::force_factor::ForceFactorCheck;
use crate::coupling::primal::PrimalCache;
use crate::coupling::space::ContactSpace;
use crate::coupling::zone::{
    Candidate, ContactZone, check_candidates, check_rigid_targets, recognize,
};
use crate::error::SolverError;
use crate::local::adhesion::WarmStartPacing;
use crate::local::{ReducedProblem, UzawaSolver};
use contact_laws::ContactLaw;
use fem_core::{Dim, Structure};
use last_problem::LastProblem;
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
pub struct ContactSimulation<S: Structure<D>, L: ContactLaw, const D: usize = 2>
where
    Dim<D>: ContactSpace<D>,
{
    structure: S,
    zones: Vec<ContactZone<L, D>>,
    settings: SimulationSettings,
    candidates: Vec<Candidate<D>>,
    /// H rows (n then the tangents per candidate) on free dofs: (dof, coefficient).
    h_rows: Vec<Vec<(usize, f64)>>,
    /// Accepted state at the end of the last step.
    states: Vec<L::State>,
    /// Accepted (gap, u_t…) at the end of the last step.
    jumps: Vec<[f64; D]>,
    /// Last accepted r̄ (warm start).
    r_bar: Vec<[f64; D]>,
    /// Active set of the cached W.
    w_active: Vec<usize>,
    w: Vec<f64>,
    w_version: Option<u64>,
    u: Vec<f64>,
    /// Nodal displacements at the end of the last step (numbering-free).
    nodal_u: Vec<[f64; D]>,
    /// Stiffness version the rows of `H` (and `u`) were numbered for.
    rows_version: u64,
    time: f64,
    solver: UzawaSolver,
    counters: Counters,
    last_problem: LastProblem<L, D>,
    last_version: u64,
    primal: PrimalCache,
    /// When adhesive steps try Newton from the previous step's reactions.
    warm: WarmStartPacing,
    /// Floating structures: the accepted rigid-body amplitudes `α` (one per mode).
    alpha: Vec<f64>,
    /// Floating structures: the load along every mode at this step's load factor, `Rᵀ f`.
    mode_load: Vec<f64>,
    /// The check of `step`'s force factor (until the structure shows applied forces).
    force_check: ForceFactorCheck,
    /// The penetration tolerance of the inactive candidates, a length
    /// ([`SimulationTuning::penetration_tol`] × the contactors' extent).
    penetration_tol: f64,
}

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize> ContactSimulation<S, L, D>
where
    Dim<D>: ContactSpace<D>,
{
    /// Recognises the candidates of `zones` on `structure` (reference configuration) and
    /// starts at time 0 with every law's initial state.
    ///
    /// # Errors
    /// As for [`recognize`]; [`SolverError::InvalidSetting`] naming the setting for bad
    /// settings (a tolerance that is not finite and positive, a zero count);
    /// [`SolverError::InvalidGeometry`] if no zone has a candidate.
    pub fn new(
        structure: S,
        zones: Vec<ContactZone<L, D>>,
        settings: SimulationSettings,
    ) -> Result<Self, SolverError> {
        settings.check()?;
        let candidates = recognize(&structure, &zones)?;
        if D == 3 {
            // the stricter checks 3D always ran (every zone has a candidate, none is held)
            check_candidates(&structure, &zones, &candidates)?;
        }
        if candidates.is_empty() {
            return Err(SolverError::InvalidGeometry(
                "no contactor node projects on its target: the simulation has no contact candidate"
                    .into(),
            ));
        }
        check_rigid_targets(&structure, &zones, &candidates)?;
        if let Some(z) = zones
            .iter()
            .find(|z| D == 3 && z.law.has_adhesion() && z.areas.is_none())
        {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{}`: an adhesive law needs the contactor nodes' tributary areas (its \
                 springs are a stiffness per unit area): give them with `with_areas`",
                z.name
            )));
        }
        let penetration_tol =
            settings.relative_penetration_tol::<D>() * extent(&structure, &candidates);
        let h_rows = h_rows_of(&structure, &zones, &candidates)?;
        let states = candidates
            .iter()
            .map(|c| zones[c.zone].law.initial_state())
            .collect();
        let mut sim = Self {
            u: vec![0.0; structure.dof_count()],
            nodal_u: vec![[0.0; D]; structure.node_count()],
            rows_version: structure.stiffness_version(),
            last_version: structure.stiffness_version(),
            structure,
            zones,
            settings,
            h_rows,
            states,
            jumps: vec![[0.0; D]; candidates.len()],
            r_bar: vec![[0.0; D]; candidates.len()],
            candidates,
            w_active: Vec::new(),
            w: Vec::new(),
            w_version: None,
            time: 0.0,
            solver: UzawaSolver::new(settings.solver),
            counters: Counters::default(),
            last_problem: LastProblem::None,
            primal: PrimalCache::default(),
            warm: WarmStartPacing::default(),
            alpha: Vec::new(),
            mode_load: Vec::new(),
            force_check: ForceFactorCheck::default(),
            penetration_tol,
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
    pub fn zones(&self) -> &[ContactZone<L, D>] {
        &self.zones
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
        let Some(z) = self.zones.iter_mut().find(|z| z.name == zone) else {
            return Err(SolverError::UnknownZone {
                name: zone.to_string(),
                known: self
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
        self.w_version = None;
        self.primal = PrimalCache::default();
        Ok(())
    }

    /// The candidates found by recognition.
    pub fn candidates(&self) -> &[Candidate<D>] {
        &self.candidates
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
        self.penetration_tol =
            settings.relative_penetration_tol::<D>() * extent(&self.structure, &self.candidates);
        Ok(())
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

    /// The free-dof displacements at the end of the last step, in the dof numbering of that
    /// step (a change of supports since renumbers the structure's dofs; the next step follows).
    pub fn displacement(&self) -> &[f64] {
        &self.u
    }

    /// Nodal displacements `[u_x, u_y]` (`[u_x, u_y, u_z]` in 3D) at the end of the last
    /// step (prescribed components included).
    pub fn nodal_displacements(&self) -> Vec<[f64; D]> {
        self.nodal_u.clone()
    }

    /// The displacement of `node` at the end of the last step (prescribed components
    /// included).
    ///
    /// # Panics
    /// If `node >= node_count()`.
    #[track_caller]
    pub fn nodal_displacement(&self, node: usize) -> [f64; D] {
        self.nodal_u[node]
    }

    /// The reduced problem of the last solve — after condensation of the adhesive springs,
    /// with `μ̄` per contact — on the active contacts (see [`Self::last_active`]); export it
    /// with [`ReducedProblem::to_json`] to re-solve it elsewhere (e.g. Siconos). `None` when the
    /// last step was solved without a dense `F*` (matrix-free or active set; force
    /// `FlexibilityMode::Dense` to export a large step).
    pub fn last_reduced_problem(&self) -> Option<&ReducedProblem> {
        self.last_problem.get(&self.w)
    }

    /// Candidate indices of the contacts of the last reduced problem, in its order.
    pub fn last_active(&self) -> &[usize] {
        &self.w_active
    }

    /// Floating structures ([`Structure::floating`]): the amplitudes `α` of the
    /// rigid-body modes in the displacement `u = K⁺(f + Hᵀ r) + R α` at the end of the last
    /// step, one per mode (empty for a supported structure).
    pub fn rigid_body_amplitudes(&self) -> &[f64] {
        &self.alpha
    }

    /// Resets the displacement and the tangential reference to zero while keeping the law
    /// states (e.g. after an installation phase whose displacements are discarded).
    pub fn reset_displacements(&mut self) {
        self.u.fill(0.0);
        self.nodal_u.iter_mut().for_each(|v| *v = [0.0; D]);
        self.alpha.fill(0.0);
        self.jumps = self.local_jumps_of(&self.u);
        self.r_bar.iter_mut().for_each(|r| *r = [0.0; D]);
    }

    /// Follows a renumbering of the structure's dofs (supports added or released between
    /// steps change the numbering and the stiffness version): the rows of `H` are rebuilt
    /// from the candidates and `u` from the nodal displacements of the last step; the caches
    /// keyed on the version rebuild themselves.
    pub(super) fn follow_numbering(&mut self) -> Result<(), SolverError> {
        let version = self.structure.stiffness_version();
        if version == self.rows_version {
            return Ok(());
        }
        self.h_rows = h_rows_of(&self.structure, &self.zones, &self.candidates)?;
        self.u = vec![0.0; self.structure.dof_count()];
        for (n, v) in self.nodal_u.iter().enumerate() {
            for (c, d) in self.structure.node_dofs(n).into_iter().enumerate() {
                if let Some(i) = d {
                    self.u[i] = v[c];
                }
            }
        }
        self.primal = PrimalCache::default();
        self.w_version = None;
        self.rows_version = version;
        Ok(())
    }

    /// The nodal displacements of the free-dof vector `u` under the current numbering.
    pub(super) fn nodal_of(&self, u: &[f64]) -> Vec<[f64; D]> {
        (0..self.structure.node_count())
            .map(|n| nodal(&self.structure, u, n))
            .collect()
    }

    fn local_jumps_of(&self, u: &[f64]) -> Vec<[f64; D]> {
        self.candidates
            .iter()
            .map(|c| c.local(c.relative(|n| nodal(&self.structure, u, n))))
            .collect()
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
    /// previous step.
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
        let start = Instant::now();
        let version = self.begin_step(time, force_factor)?;
        let dt = time - self.time;
        // 1. detection: the free response and the active set
        let (u_free, free) = self.free_response(force_factor)?;
        self.force_check
            .check(&self.structure, force_factor, &u_free)?;
        let mut active = self.initial_active_set(&free);
        let mut report = StepReport::start(self.counters.steps + 1, time, force_factor);
        loop {
            report.detection_passes += 1;
            // 2–3. the path and its operator, then the local solve (with the adhesion loop)
            let solved = self.solve_pass(&active, &free, dt, version, &mut report)?;
            if !solved.extend.is_empty() {
                // a rigid motion of a floating body closes candidates outside the set
                active.extend(solved.extend);
                active.sort_unstable();
                active.dedup();
                continue;
            }
            // 4. equilibrium, then the penetration check and the report
            let (u, jumps) = self.equilibrium(&u_free, &solved)?;
            let penetrating = self.penetrating(&jumps);
            if penetrating.is_empty() {
                return Ok(self.accept(time, u, jumps, solved, report, start));
            }
            if report.detection_passes >= self.settings.tuning.max_detection_passes {
                // issue 35: accepting the step would return contacts that penetrate
                let deepest = penetrating
                    .iter()
                    .copied()
                    .min_by(|&a, &b| jumps[a][0].total_cmp(&jumps[b][0]))
                    .unwrap_or(penetrating[0]);
                let c = &self.candidates[deepest];
                return Err(SolverError::StillPenetrating {
                    passes: report.detection_passes,
                    count: penetrating.len(),
                    zone: self.zones[c.zone].name.clone(),
                    node: c.node,
                    gap: jumps[deepest][0],
                    setting: "max_detection_passes",
                });
            }
            active.extend(penetrating);
            active.sort_unstable();
        }
    }

    /// Whether candidate `i`'s tangential unknown takes part (friction or adhesion), under the
    /// skip rules.
    fn tangent_needed(&self, i: usize) -> bool {
        let law = &self.zones[self.candidates[i].zone].law;
        !self.settings.tuning.skip.frictionless_normal_only
            || law.has_friction()
            || law.has_adhesion()
    }

    /// Whether the tangential component `d` (`1..D`) of candidate `i` is solved: its tangent
    /// is needed ([`Self::tangent_needed`]) and, in 3D
    /// ([`ContactSpace::DECOUPLE_HELD_TANGENTS`]), the contact can move along it.
    pub(super) fn tangent_solved(&self, i: usize, d: usize) -> bool {
        self.tangent_needed(i)
            && !(<Dim<D> as ContactSpace<D>>::DECOUPLE_HELD_TANGENTS
                && self.h_rows[D * i + d].is_empty())
    }
}

/// The rows of `H` (normal then tangent per candidate) on the structure's free dofs.
///
/// # Errors
/// [`SolverError::InvalidGeometry`] for a candidate whose normal relative displacement is fully
/// prescribed.
fn h_rows_of<S: Structure<D> + ?Sized, L, const D: usize>(
    structure: &S,
    zones: &[ContactZone<L, D>],
    candidates: &[Candidate<D>],
) -> Result<Vec<Vec<(usize, f64)>>, SolverError>
where
    Dim<D>: ContactSpace<D>,
{
    let mut h_rows = Vec::with_capacity(D * candidates.len());
    for c in candidates {
        for dir in c.frame() {
            h_rows.push(c.h_row(structure, dir));
        }
        if h_rows[h_rows.len() - D].is_empty() {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{}`: the normal displacement of contactor node {} relative to its \
                 target is fully prescribed, so it cannot take part in contact",
                zones[c.zone].name, c.node
            )));
        }
    }
    Ok(h_rows)
}

/// The largest side of the box of the candidates' contactor nodes (1 for a single point).
fn extent<S: Structure<D> + ?Sized, const D: usize>(s: &S, candidates: &[Candidate<D>]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; D], [f64::NEG_INFINITY; D]);
    for c in candidates {
        let x = s.node_position(c.node);
        for a in 0..D {
            lo[a] = lo[a].min(x[a]);
            hi[a] = hi[a].max(x[a]);
        }
    }
    let e = (0..D).map(|a| hi[a] - lo[a]).fold(0.0, f64::max);
    if e > 0.0 { e } else { 1.0 }
}

fn nodal<S: Structure<D> + ?Sized, const D: usize>(s: &S, u: &[f64], node: usize) -> [f64; D] {
    let mut v = s.prescribed_displacement(node);
    for (c, d) in s.node_dofs(node).into_iter().enumerate() {
        if let Some(i) = d {
            v[c] = u[i];
        }
    }
    v
}
