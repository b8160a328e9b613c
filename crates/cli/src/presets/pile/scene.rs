//! The pull-out scene once built: the three phases and the readings of a step (head load, shaft
//! profile, forces).

use super::PulloutSpec;
use contact_laws::Rccm;
use contact_solver::SolverError;
use contact_solver::coupling::simulation::{
    ContactRecord, ContactSimulation, InterfaceStatus, StepResult,
};
use fem_core::{Component, LinearElasticModel};
use std::f64::consts::PI;

/// Where a [`PulloutScene`] is in the seed's sequence.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Phase {
    Start,
    Geostatic,
    Installed,
}

/// One pull-out increment: the head displacement, the head load and the step's contacts.
#[derive(Clone, Debug, PartialEq)]
pub struct PulloutStep {
    /// Increment `k` (1-based).
    pub increment: usize,
    /// Head displacement `v` (m, upwards).
    pub head_displacement: f64,
    /// Head load `Q` (kN, full ring, upwards): see [`PulloutScene::head_load`].
    pub head_load: f64,
    /// The step.
    pub result: StepResult,
}

/// One shaft contact at the end of a step, in stresses (kPa) — for profiles along the shaft.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShaftPoint {
    /// Depth coordinate `z` (m, `≤ 0`).
    pub z: f64,
    /// Normal stress `σ_n = r_n / A` (kPa, compression positive).
    pub sigma_n: f64,
    /// Shear stress on the pile `τ = r_t / A` (kPa, along `+z`: negative while it resists the
    /// pull-out).
    pub tau: f64,
    /// Adhesion intensity β.
    pub beta: f64,
    /// Tangential jump `u_t` (m, pile up relative to the soil).
    pub u_t: f64,
    /// Status.
    pub status: InterfaceStatus,
}

/// The pull-out scene: the simulation and the bookkeeping of the three phases.
///
/// The result-reading methods ([`shaft_profile`](Self::shaft_profile),
/// [`shaft_normal_force`](Self::shaft_normal_force), …) take a [`StepResult`] of this scene.
///
/// # Panics
/// They panic if given a step of another simulation with fewer contact candidates.
///
/// # Examples
/// Plancoët on a coarse mesh, pulled 15 mm in 3 increments with plain Coulomb friction: at
/// full slip the head load is the pile's weight plus the shaft's `μ Σ r_n`.
/// ```
/// use contact_solver::SimulationSettings;
/// use bipo::presets::PulloutSpec;
/// let mut spec = PulloutSpec::plancoet().with_coulomb_interface();
/// (spec.mesh.cells_shaft, spec.mesh.cells_soil_r, spec.mesh.cells_below_tip) = (4, 4, 3);
/// spec.steps = 3;
/// let mut scene = spec.build(SimulationSettings::default())?;
/// let geo = scene.geostatic()?;
/// assert!((scene.head_load(&geo)? - spec.head_load_at_rest()).abs() < 1e-6); // Q₀
/// scene.install()?;
/// let last = (1..=3).map(|k| scene.pull(k)).last().unwrap()?;
/// let expected = scene.full_slip_load(&last.result);
/// assert!((last.head_load - expected).abs() < 1e-6 * expected);
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
pub struct PulloutScene {
    /// The simulation.
    pub simulation: ContactSimulation<LinearElasticModel, Rccm>,
    /// The spec it was built from.
    pub spec: PulloutSpec,
    /// The `pile_head` nodes (their `u_z` is the head displacement).
    pub head: Vec<usize>,
    /// Candidate indices of the shaft pairs, by increasing `z` (the tip corner first).
    pub shaft_candidates: Vec<usize>,
    /// Candidate indices of the tip pairs.
    pub tip_candidates: Vec<usize>,
    /// Installation nodal forces `(soil node, radial force per radian)` added in phase 2.
    pub installation_forces: Vec<(usize, f64)>,
    /// The installation displacement `δ` used (m).
    pub installation_displacement: f64,
    /// Tolerance of the contact solver (checked after each step).
    pub(super) tol: f64,
    pub(super) phase: Phase,
    /// Force control: the jack force applied so far (kN, full ring).
    pub(super) applied_force: f64,
}

impl PulloutScene {
    /// Phase 1: the geostatic step (self-weight and initial stress, head held at `u_z = 0`).
    ///
    /// # Errors
    /// As for [`ContactSimulation::step`]; [`SolverError::InvalidSetting`] if called twice.
    pub fn geostatic(&mut self) -> Result<StepResult, SolverError> {
        self.expect(Phase::Start, "geostatic")?;
        let res = self.checked_step(1.0)?;
        self.phase = Phase::Geostatic;
        Ok(res)
    }

    /// Phase 2: adds the installation forces and solves (head still at `u_z = 0`).
    ///
    /// # Errors
    /// As for [`ContactSimulation::step`]; [`SolverError::InvalidSetting`] unless phase 1 ran.
    pub fn install(&mut self) -> Result<StepResult, SolverError> {
        self.expect(Phase::Geostatic, "install")?;
        for &(node, f) in &self.installation_forces {
            self.simulation
                .structure_mut()
                .add_nodal_force(node, [f, 0.0])?;
        }
        let res = self.checked_step(2.0)?;
        self.phase = Phase::Installed;
        Ok(res)
    }

    /// Phase 3, increment `k` (1-based): head `u_z = v₀ k / steps`, reached in
    /// [`PulloutSpec::substeps`] equal steps from `v₀ (k − 1) / steps` (call the increments in
    /// order).
    ///
    /// # Errors
    /// As for [`ContactSimulation::step`]; [`SolverError::InvalidSetting`] unless phase 2 ran.
    pub fn pull(&mut self, k: usize) -> Result<PulloutStep, SolverError> {
        self.expect(Phase::Installed, "pull")?;
        if let Some(q) = self.spec.head_force {
            return self.pull_by_force(k, q);
        }
        let (steps, substeps) = (self.spec.steps as f64, self.spec.substeps);
        let v = self.spec.head_displacement * k as f64 / steps;
        let mut result = None;
        for j in 1..=substeps {
            let f = (k - 1) as f64 + j as f64 / substeps as f64;
            self.simulation.structure_mut().set_prescribed(
                &self.head,
                Component::Y,
                self.spec.head_displacement * f / steps,
            )?;
            result = Some(self.checked_step(2.0 + f)?);
        }
        let result = result.expect("at least one substep (checked by build)");
        Ok(PulloutStep {
            increment: k,
            head_displacement: v,
            head_load: self.head_load(&result)?,
            result,
        })
    }

    /// Phase 3 under force control ([`PulloutSpec::head_force`]): the jack force `Q k / steps`
    /// on the head's tied `u_z`, reached in [`PulloutSpec::substeps`] equal steps; the head
    /// displacement is the cap's.
    fn pull_by_force(&mut self, k: usize, q: f64) -> Result<PulloutStep, SolverError> {
        let (steps, substeps) = (self.spec.steps as f64, self.spec.substeps);
        let mut result = None;
        for j in 1..=substeps {
            let f = (k - 1) as f64 + j as f64 / substeps as f64;
            // the loads are cumulative: add this substep's share, per radian
            let share = q / (steps * substeps as f64) / (2.0 * PI);
            self.simulation
                .structure_mut()
                .add_nodal_force(self.head[0], [0.0, share])?;
            result = Some(self.checked_step(2.0 + f)?);
            self.applied_force = q * f / steps;
        }
        let result = result.expect("at least one substep (checked by build)");
        let v = self.simulation.nodal_displacements()[self.head[0]][1];
        Ok(PulloutStep {
            increment: k,
            head_displacement: v,
            head_load: self.head_load(&result)?,
            result,
        })
    }

    /// Runs the three phases: phase 1, phase 2, then every pull-out increment.
    ///
    /// # Errors
    /// As for the phases.
    pub fn run(&mut self) -> Result<PulloutRun, SolverError> {
        let geostatic = self.geostatic()?;
        let geostatic_head_load = self.head_load(&geostatic)?;
        let geostatic_max_displacement = self
            .simulation
            .nodal_displacements()
            .iter()
            .flatten()
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        let installed = self.install()?;
        let installed_head_load = self.head_load(&installed)?;
        let steps = (1..=self.spec.steps)
            .map(|k| self.pull(k))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(PulloutRun {
            geostatic,
            geostatic_max_displacement,
            geostatic_head_load,
            installed,
            installed_head_load,
            steps,
        })
    }

    /// One simulation step at `time`, with the contact solver's residual checked (the
    /// staggered coupling accepts unconverged results to cut the adhesion fixed point).
    fn checked_step(&mut self, time: f64) -> Result<StepResult, SolverError> {
        let res = self.simulation.step(time, 1.0)?;
        let r = &res.report;
        if r.active_contacts > 0 && (r.residual > self.tol || r.residual.is_nan()) {
            return Err(SolverError::NotConverged {
                iterations: r.contact_iterations,
                residual: r.residual,
                history: Vec::new(),
            });
        }
        Ok(res)
    }

    fn expect(&self, phase: Phase, what: &'static str) -> Result<(), SolverError> {
        if self.phase == phase {
            Ok(())
        } else {
            Err(SolverError::InvalidSetting {
                what,
                value: f64::NAN,
                expected: "the phases in order: geostatic, install, then pull(1 ..= steps)",
            })
        }
    }

    /// The head load `Q` (kN, full ring, upwards) at the end of `result`, which must be the
    /// step just solved (the reactions come from the simulation's current displacements):
    /// `2π Σ R_z` over the head nodes, `R = K u − f` minus the contact forces that act on the
    /// head's prescribed `u_z` (the shaft pair at the head's corner).
    ///
    /// # Errors
    /// [`SolverError::Structure`] if the displacements do not match the model.
    pub fn head_load(&self, result: &StepResult) -> Result<f64, SolverError> {
        if let Some(q) = self.spec.head_force {
            // force control: the jack force applied so far (the cap's load along z)
            let _ = (q, result);
            return Ok(self.applied_force);
        }
        let model = self.simulation.structure();
        let u = self.simulation.nodal_displacements();
        let reactions = model.reactions(&u, 1.0)?;
        let mut q: f64 = reactions
            .iter()
            .filter(|((n, c), _)| *c == Component::Y && self.head.binary_search(n).is_ok())
            .map(|(_, r)| r)
            .sum();
        let candidates = self.simulation.candidates();
        for (c, rec) in candidates.iter().zip(&result.contacts) {
            // global force on the contactor, −w times it on each target
            let f_z = rec.r.n * c.normal()[1] + rec.r.t[0] * c.tangent()[1];
            if self.head.binary_search(&c.node).is_ok() {
                q -= f_z;
            }
            for &(t, w) in c.targets.iter().flatten() {
                if self.head.binary_search(&t).is_ok() {
                    q += w * f_z;
                }
            }
        }
        Ok(2.0 * PI * q)
    }

    /// The shaft at the end of `result`, from the tip corner up, in stresses.
    pub fn shaft_profile(&self, result: &StepResult) -> Vec<ShaftPoint> {
        self.shaft_candidates
            .iter()
            .map(|&i| {
                let c: &ContactRecord = &result.contacts[i];
                let a = c.area;
                let per_area = |f: f64| if a > 0.0 { f / a } else { 0.0 };
                ShaftPoint {
                    z: c.position[1],
                    sigma_n: per_area(c.r.n),
                    tau: per_area(c.r.t[0]),
                    beta: c.beta,
                    u_t: c.u_t,
                    status: c.status,
                }
            })
            .collect()
    }

    /// The shaft normal force `2π Σ r_n` (kN) at the end of `result`.
    pub fn shaft_normal_force(&self, result: &StepResult) -> f64 {
        2.0 * PI
            * self
                .shaft_candidates
                .iter()
                .map(|&i| result.contacts[i].r.n)
                .sum::<f64>()
    }

    /// The shaft friction `−2π Σ r_t` (kN, positive when it resists the pull-out).
    pub fn shaft_friction(&self, result: &StepResult) -> f64 {
        -2.0 * PI
            * self
                .shaft_candidates
                .iter()
                .map(|&i| result.contacts[i].r.t[0])
                .sum::<f64>()
    }

    /// The tip's normal force `2π Σ r_n` (kN, compression).
    pub fn tip_force(&self, result: &StepResult) -> f64 {
        2.0 * PI
            * self
                .tip_candidates
                .iter()
                .map(|&i| result.contacts[i].r.n)
                .sum::<f64>()
    }

    /// The full-slip load predicted from the interface's own normal reactions,
    /// `W_p + 2π Σ μ r_n` (kN): the pile's weight plus `π D ∫ μ σ_n dz` over the shaft (seed
    /// eqs. 1.2–1.4 with `τ = μ σ_n`), the tip being open.
    pub fn full_slip_load(&self, result: &StepResult) -> f64 {
        self.spec.pile_weight() + self.spec.interface.mu * self.shaft_normal_force(result)
    }
}

/// The three phases of a pull-out run.
#[derive(Clone, Debug, PartialEq)]
pub struct PulloutRun {
    /// Phase 1.
    pub geostatic: StepResult,
    /// Largest nodal displacement component after phase 1 (m; round-off for an equilibrium
    /// at rest).
    pub geostatic_max_displacement: f64,
    /// Head load after phase 1 (kN): `Q₀` ([`PulloutSpec::head_load_at_rest`]).
    pub geostatic_head_load: f64,
    /// Phase 2.
    pub installed: StepResult,
    /// Head load after phase 2 (kN), the start `v = 0` of the load–displacement curve.
    pub installed_head_load: f64,
    /// Phase 3, one entry per increment.
    pub steps: Vec<PulloutStep>,
}

impl PulloutRun {
    /// The load–displacement curve `(v, Q)` (m, kN), from `(0, Q after installation)` through
    /// every pull-out increment; see [`PulloutScene::head_load`].
    pub fn curve(&self) -> Vec<(f64, f64)> {
        std::iter::once((0.0, self.installed_head_load))
            .chain(
                self.steps
                    .iter()
                    .map(|s| (s.head_displacement, s.head_load)),
            )
            .collect()
    }

    /// The largest head load of phase 3 (kN).
    pub fn peak_load(&self) -> f64 {
        self.steps
            .iter()
            .map(|s| s.head_load)
            .fold(f64::NEG_INFINITY, f64::max)
    }
}
