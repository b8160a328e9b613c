//! The pull-out scene once built, in either dimension: the three phases and the readings of a
//! step (head load, shaft forces), written once over `D`; what differs is the factor from the
//! model's forces to the full ring ([`PileSpace::RING`]) and, in the plane only, the shaft
//! profile in stresses.

use super::PulloutSpec;
use contact_laws::Rccm;
use contact_solver::SolverError;
use contact_solver::coupling::simulation::{
    ContactRecord, ContactSimulation, InterfaceStatus, StepResult,
};
use contact_solver::coupling::space::ContactSpace;
use fem_core::model::ModelSpace;
use fem_core::{Component, Dim, ElasticModel, Space};
use std::f64::consts::PI;

/// The dimensions a pull-out scene is built in: the axisymmetric meridian ([`Dim<2>`], forces
/// per radian) and a 3D quarter ([`Dim<3>`]).
pub trait PileSpace<const D: usize>: ContactSpace<D> + ModelSpace<D>
where
    Dim<D>: Space,
{
    /// The factor from the model's forces to the full ring: `2π` (per radian) in the plane,
    /// `4` (a quarter) in 3D.
    const RING: f64;
}

impl PileSpace<2> for Dim<2> {
    const RING: f64 = 2.0 * PI;
}

impl PileSpace<3> for Dim<3> {
    const RING: f64 = 4.0;
}

/// Where a [`PulloutScene`] is in the seed's sequence.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Phase {
    Start,
    Geostatic,
    Installed,
}

/// One pull-out increment: the head displacement, the head load and the step's contacts.
#[derive(Clone, Debug, PartialEq)]
pub struct PulloutStep<const D: usize = 2>
where
    Dim<D>: ContactSpace<D>,
{
    /// Increment `k` (1-based).
    pub increment: usize,
    /// Head displacement `v` (m, upwards).
    pub head_displacement: f64,
    /// Head load `Q` (kN, full ring, upwards): see [`PulloutScene::head_load`].
    pub head_load: f64,
    /// The step.
    pub result: StepResult<D>,
}

/// One shaft contact at the end of a step of the axisymmetric scene, in stresses (kPa) — for
/// profiles along the shaft.
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

/// The pull-out scene: the simulation and the bookkeeping of the three phases, axisymmetric
/// (`D = 2`, [`PulloutSpec::build`]) or on a 3D quarter (`D = 3`, [`PulloutSpec::build_3d`]).
///
/// The result-reading methods ([`head_load`](Self::head_load),
/// [`shaft_friction`](Self::shaft_friction), …) take a [`StepResult`] of this scene.
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
pub struct PulloutScene<const D: usize = 2>
where
    Dim<D>: PileSpace<D>,
{
    /// The simulation.
    pub simulation: ContactSimulation<ElasticModel<D>, Rccm, D>,
    /// The spec it was built from.
    pub spec: PulloutSpec,
    /// The `pile_head` nodes, sorted (their `u_z` is the head displacement).
    pub head: Vec<usize>,
    /// Candidate indices of the shaft pairs, the tip corner's included (in the plane by
    /// increasing `z`, the tip corner first).
    pub shaft_candidates: Vec<usize>,
    /// Candidate indices of the tip pairs.
    pub tip_candidates: Vec<usize>,
    /// Installation nodal forces `(soil node, force)` added in phase 2 (per radian in the
    /// plane).
    pub installation_forces: Vec<(usize, [f64; D])>,
    /// The installation displacement `δ` used (m).
    pub installation_displacement: f64,
    /// Tolerance of the contact solver (checked after each step).
    pub(super) tol: f64,
    pub(super) phase: Phase,
    /// Force control: the jack force applied so far (kN, full ring).
    pub(super) applied_force: f64,
}

/// The axial component (`z`): the last one.
fn axial<const D: usize>() -> Component {
    Component::all::<D>()[D - 1]
}

impl<const D: usize> PulloutScene<D>
where
    Dim<D>: PileSpace<D>,
{
    /// Phase 1: the geostatic step (self-weight and initial stress, head held at `u_z = 0`).
    ///
    /// # Errors
    /// As for [`ContactSimulation::step`]; [`SolverError::InvalidSetting`] if called twice.
    pub fn geostatic(&mut self) -> Result<StepResult<D>, SolverError> {
        self.expect(Phase::Start, "geostatic")?;
        let res = self.checked_step(1.0)?;
        self.phase = Phase::Geostatic;
        Ok(res)
    }

    /// Phase 2: adds the installation forces and solves (head still at `u_z = 0`).
    ///
    /// # Errors
    /// As for [`ContactSimulation::step`]; [`SolverError::InvalidSetting`] unless phase 1 ran.
    pub fn install(&mut self) -> Result<StepResult<D>, SolverError> {
        self.expect(Phase::Geostatic, "install")?;
        for &(node, f) in &self.installation_forces {
            self.simulation.structure_mut().add_nodal_force(node, f)?;
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
    pub fn pull(&mut self, k: usize) -> Result<PulloutStep<D>, SolverError> {
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
                axial::<D>(),
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
    fn pull_by_force(&mut self, k: usize, q: f64) -> Result<PulloutStep<D>, SolverError> {
        let (steps, substeps) = (self.spec.steps as f64, self.spec.substeps);
        let mut result = None;
        for j in 1..=substeps {
            let f = (k - 1) as f64 + j as f64 / substeps as f64;
            // the loads are cumulative: add this substep's share, per radian in the plane
            let mut share = [0.0; D];
            share[D - 1] = q / (steps * substeps as f64) / <Dim<D> as PileSpace<D>>::RING;
            self.simulation
                .structure_mut()
                .add_nodal_force(self.head[0], share)?;
            result = Some(self.checked_step(2.0 + f)?);
            self.applied_force = q * f / steps;
        }
        let result = result.expect("at least one substep (checked by build)");
        let v = self.simulation.nodal_displacement(self.head[0])[D - 1];
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
    pub fn run(&mut self) -> Result<PulloutRun<D>, SolverError> {
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
    fn checked_step(&mut self, time: f64) -> Result<StepResult<D>, SolverError> {
        let res = self.simulation.step(time, 1.0)?;
        let r = &res.report;
        if r.active_contacts > 0 && (r.residual > self.tol || r.residual.is_nan()) {
            return Err(SolverError::NotConverged {
                iterations: r.contact_iterations,
                residual: r.residual,
                history: Vec::new(),
                best: None,
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
    /// [`RING`](PileSpace::RING)` Σ R_z` over the head nodes, `R = K u − f` minus the contact
    /// forces that act on the head's prescribed `u_z` (the shaft pairs at the head's corner).
    /// Under force control, the jack force applied so far.
    ///
    /// # Errors
    /// [`SolverError::Structure`] if the displacements do not match the model.
    pub fn head_load(&self, result: &StepResult<D>) -> Result<f64, SolverError> {
        if self.spec.head_force.is_some() {
            // force control: the jack force applied so far (the cap's load along z)
            return Ok(self.applied_force);
        }
        let model = self.simulation.structure();
        let u = self.simulation.nodal_displacements();
        let axial = axial::<D>();
        let mut q: f64 = model
            .reactions(&u, 1.0)?
            .iter()
            .filter(|((n, c), _)| *c == axial && self.head.binary_search(n).is_ok())
            .map(|(_, r)| r)
            .sum();
        for (c, rec) in self.simulation.candidates().iter().zip(&result.contacts) {
            // global force on the contactor, −w times it on each target
            let f_z = rec.force()[D - 1];
            if self.head.binary_search(&c.node).is_ok() {
                q -= f_z;
            }
            for &(t, w) in c.targets.iter().flatten() {
                if self.head.binary_search(&t).is_ok() {
                    q += w * f_z;
                }
            }
        }
        Ok(<Dim<D> as PileSpace<D>>::RING * q)
    }

    /// `RING Σ value(record)` over the `candidates` of `result` (kN).
    fn ring_sum(
        candidates: &[usize],
        result: &StepResult<D>,
        value: impl Fn(&ContactRecord<D>) -> f64,
    ) -> f64 {
        <Dim<D> as PileSpace<D>>::RING
            * candidates
                .iter()
                .map(|&i| value(&result.contacts[i]))
                .sum::<f64>()
    }

    /// The shaft normal force `RING Σ r_n` (kN) at the end of `result`.
    pub fn shaft_normal_force(&self, result: &StepResult<D>) -> f64 {
        Self::ring_sum(&self.shaft_candidates, result, |c| c.reaction()[0])
    }

    /// The shaft friction `−RING Σ r·e_z` (kN, positive when it resists the pull-out; in the
    /// plane `r·e_z = r_t`, the tangent being `+e_z`).
    pub fn shaft_friction(&self, result: &StepResult<D>) -> f64 {
        -Self::ring_sum(&self.shaft_candidates, result, |c| c.force()[D - 1])
    }

    /// The tip's normal force `RING Σ r_n` (kN, compression).
    pub fn tip_force(&self, result: &StepResult<D>) -> f64 {
        Self::ring_sum(&self.tip_candidates, result, |c| c.reaction()[0])
    }

    /// The full-slip load predicted from the interface's own normal reactions,
    /// `W_p + μ RING Σ r_n` (kN): the pile's weight plus `π D ∫ μ σ_n dz` over the shaft (seed
    /// eqs. 1.2–1.4 with `τ = μ σ_n`), the tip being open.
    pub fn full_slip_load(&self, result: &StepResult<D>) -> f64 {
        self.spec.pile_weight() + self.spec.interface.mu * self.shaft_normal_force(result)
    }
}

impl PulloutScene<2> {
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
}

/// The three phases of a pull-out run.
#[derive(Clone, Debug, PartialEq)]
pub struct PulloutRun<const D: usize = 2>
where
    Dim<D>: ContactSpace<D>,
{
    /// Phase 1.
    pub geostatic: StepResult<D>,
    /// Largest nodal displacement component after phase 1 (m; round-off for an equilibrium
    /// at rest).
    pub geostatic_max_displacement: f64,
    /// Head load after phase 1 (kN): `Q₀` ([`PulloutSpec::head_load_at_rest`]).
    pub geostatic_head_load: f64,
    /// Phase 2.
    pub installed: StepResult<D>,
    /// Head load after phase 2 (kN), the start `v = 0` of the load–displacement curve.
    pub installed_head_load: f64,
    /// Phase 3, one entry per increment.
    pub steps: Vec<PulloutStep<D>>,
}

impl<const D: usize> PulloutRun<D>
where
    Dim<D>: ContactSpace<D>,
{
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
