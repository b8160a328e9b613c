//! [`MoreauJean`]: the velocity-level θ-scheme of Moreau (1988) and Jean (1999) through the
//! [`TimeScheme`] seam, on a [`DynamicModel`] (whose solves are with `M̂`).
//!
//! ```text
//! M (v − v_k) + h C v_θ + h K u_θ = h f_θ + Hᵀ r          (r: the step's contact impulses)
//! v_θ = (1−θ) v_k + θ v,   u_θ = (1−θ) u_k + θ u,   u = u_k + h v_θ
//! ⇒  v = v_free + M̂⁻¹ Hᵀ r,   M̂ = M + hθC + h²θ²K,
//!    v_free = v_k + M̂⁻¹ h (f_θ − C v_k − K (u_k + hθ v_k)),   f_θ = f((1−θ) λ_k + θ λ)
//! ```
//! Per contact the reduced problem is `x = W r + q` with `W = H M̂⁻¹ Hᵀ` and, for Newton's
//! impact law with restitution `e`,
//!
//! ```text
//! x = (v_n + e v_n,k,  v_t),     q = (v_free,n + e v_n,k,  v_free,t)
//! ```
//! so that the contact laws act on velocities unchanged: Signorini `x_n ≥ 0 ⊥ r_n ≥ 0`,
//! Coulomb through De Saxcé's modified velocity `x_n + μ‖x_t‖` (Jean 1999 §3.3; Acary &
//! Brogliato 2008 §10.1.3). **Active** (Moreau's index set) is a contact whose gap predicted at
//! `u_k + h(1−θ) v_k`, `g_k + h(1−θ) v_n,k`, is `≤ 0`; every other candidate stays out of the
//! problem whatever its alert distance, and the end-of-step gap is not checked (the scheme
//! allows an `O(h)` interpenetration, which closes the next steps).
//!
//! The energy balance of each accepted step is kept in an [`EnergyBalance`] (`energy.rs`),
//! its contact dissipation split into impact, friction and damage.
//!
//! # Adhesion (RCCM) at velocity level
//! An adhesive law's springs `r_adh = −A k(β) u` (a force) enter the step as the impulse of
//! the springs of the state `β_k` at the start of the step, at `u_θ = (1−θ) u_k + θ u`:
//!
//! ```text
//! r_adh·h = −h A k(β_k) u_θ,   u = u_k + h((1−θ) v_k + θ v),   v_n = x_n − e v_n,k
//!         = −h²θ² A k(β_k) (x + o),   o = (u_k + hθ(1−θ) v_k − hθ² e v_n,k n) / (hθ²)
//! ```
//! so the springs are condensed into `x = W r + q` exactly as in a quasi-static step
//! ([`VelocitySprings`], `velocity_adhesion.rs`): `q̃ = (I + W B)⁻¹ (q − W B o)`. The law's
//! part `r̄` acts on the velocity `x` of the contacts in Moreau's index set (an open
//! adhesive contact has only its springs), and `β` is updated once per accepted step from
//! the step's displacement jumps `u_k → u`, by the law's update, as the quasi-static path
//! does (there within its fixed point, here once: `β` lags a step,
//! [`AdhesionUpdate::Lagged`]). [`AdhesionUpdate::Implicit`] iterates `β` within the step
//! (the springs are then the end state's); with it, `θ = 1` and a vanishing mass the step is
//! the quasi-static one.

use super::ContactSimulation;
use super::energy::{ContactTerms, EnergyBalance};
use super::report::StepResult;
use super::scheme::{AcceptedContact, SchemeStep, TimeScheme, VelocitySprings};
use crate::coupling::space::ContactSpace;
use crate::coupling::zone::Candidate;
use crate::error::SolverError;
use contact_laws::ContactLaw;
use fem_core::dynamic::DynamicModel;
use fem_core::model::ModelSpace;
use fem_core::{Dim, FemError, Structure};
use std::borrow::Cow;

/// How [`MoreauJean`] updates the states of adhesive laws (RCCM's `β`) in a step
/// (`docs/theory.md` §14, "Adhesion at velocity level").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum AdhesionUpdate {
    /// The springs of the state at the start of the step; the state updated once from the
    /// step's jumps (it lags a step: an `O(h)` error, no iteration).
    #[default]
    Lagged,
    /// The state iterated within the step (the quasi-static loop's plain fixed point, to
    /// [`SimulationSettings::adhesion_tol`](super::SimulationSettings)): the springs of the
    /// state at the end of the step, as a quasi-static step has them.
    Implicit,
}

/// Per candidate, what a step keeps: the relative velocities `v_k` and `v_free` in the
/// candidate's frame, the shift of an initial displacement, and the restitution.
#[derive(Clone, Copy, Debug, Default)]
struct ContactVelocities {
    v_k: [f64; 3],
    v_free: [f64; 3],
    shift: [f64; 3],
    e: f64,
}

/// The Moreau–Jean θ-scheme (module docs): `θ ∈ [1/2, 1]`, Newton's impact law with a
/// restitution `e ∈ [0, 1]` (one for the scheme, or one per zone), the velocity `v_k` carried
/// between steps, and the energy balance of every accepted step.
///
/// Run it on a [`DynamicModel`] with [`ContactSimulation::with_scheme`] and step with
/// [`ContactSimulation::advance`] (which factorises `M̂` for the step size). The velocity
/// lives on the structure's free dofs, numbered as at the start: keep the supports of a
/// dynamic run (a change of the dof count is refused at the next step,
/// [`FemError::LengthMismatch`] naming `velocity`; following a renumbering is left to do).
/// The contact unknowns `r` of a step are impulses (force × time).
///
/// # Examples
/// A P1 block falling from rest onto a rigid line under its own weight (`g = 10`): before the
/// contact closes, `v = −g t` exactly (no elastic wave without a gradient of the load).
/// ```
/// use contact_solver::coupling::simulation::MoreauJean;
/// use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
/// use contact_laws::Signorini;
/// use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
/// use fem_core::generate::{RectangleSpec, rectangle};
/// use fem_core::{Idealization, LinearElasticModel, Material, Supports};
///
/// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.1, 1.1], 2, 2))?;
/// let bottom = mesh.node_set("bottom")?.to_vec();
/// let soft = Material::new(1e4, 0.0, 10.0)?.with_density(1.0)?; // unit weight ρ g
/// let mut model = LinearElasticModel::floating(mesh, Idealization::PlaneStrain,
///     &[(0, soft)], Supports::new())?;
/// model.add_self_weight()?;
/// let body = DynamicModel::new(model, MassKind::Lumped, Rayleigh::default())?;
/// let zone = ContactZone::rigid("ground", bottom, RigidLine::new([-1.0, 0.0], [2.0, 0.0])?,
///     Signorini, 0.5);
/// let mut sim = ContactSimulation::with_scheme(body, vec![zone],
///     SimulationSettings::default(), MoreauJean::new(0.5)?)?;
/// let res = sim.advance(0.01)?;
/// assert!(res.contacts.iter().all(|c| c.r.n == 0.0)); // 0.1 above the line: no contact
/// assert!(sim.scheme().velocity().iter().skip(1).step_by(2).all(|v| (v + 0.1).abs() < 1e-12));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct MoreauJean {
    theta: f64,
    restitution: f64,
    adhesion: AdhesionUpdate,
    /// Per zone (by index), a restitution in place of the scheme's.
    zone_restitution: Vec<Option<f64>>,
    /// `v_k` on the free dofs (empty: at rest).
    velocity: Vec<f64>,
    /// An initial displacement on the free dofs, until the first step is accepted.
    initial_displacement: Option<Vec<f64>>,
    /// The force factor of the last accepted step (`None` before the first).
    force_factor: Option<f64>,
    /// The step size `h` of the step in progress (the structure's).
    h: f64,
    /// This step: `u_k`, `v_free` and `f_θ` on the free dofs.
    u_start: Vec<f64>,
    v_free: Vec<f64>,
    load: Vec<f64>,
    /// The free dofs of every node, `D` per node.
    node_dofs: Vec<Option<usize>>,
    contacts: Vec<ContactVelocities>,
    accepted_steps: usize,
    /// The contacts' energy terms of the step being accepted.
    step_contacts: ContactTerms,
    energy: EnergyBalance,
    history: Vec<EnergyBalance>,
}

impl MoreauJean {
    /// The scheme with weight `theta` (`1/2`: no numerical dissipation, the trapezoidal rule;
    /// `1`: backward Euler), restitution 0, starting at rest from the undeformed state.
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] naming `theta` outside `[1/2, 1]`.
    pub fn new(theta: f64) -> Result<Self, SolverError> {
        if !(0.5..=1.0).contains(&theta) {
            return Err(SolverError::InvalidSetting {
                what: "theta",
                value: theta,
                expected: "a weight in [1/2, 1]",
            });
        }
        Ok(Self {
            theta,
            restitution: 0.0,
            adhesion: AdhesionUpdate::Lagged,
            zone_restitution: Vec::new(),
            velocity: Vec::new(),
            initial_displacement: None,
            force_factor: None,
            h: f64::NAN,
            u_start: Vec::new(),
            v_free: Vec::new(),
            load: Vec::new(),
            node_dofs: Vec::new(),
            contacts: Vec::new(),
            accepted_steps: 0,
            step_contacts: ContactTerms::default(),
            energy: EnergyBalance::default(),
            history: Vec::new(),
        })
    }

    /// The scheme's restitution `e` (Newton's law `v_n = −e v_n,k` at an impact), for every
    /// zone without its own ([`Self::with_zone_restitution`]).
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] naming `restitution` outside `[0, 1]`.
    pub fn with_restitution(mut self, e: f64) -> Result<Self, SolverError> {
        self.restitution = check_restitution(e)?;
        Ok(self)
    }

    /// How the states of adhesive laws are updated in a step (default
    /// [`AdhesionUpdate::Lagged`]).
    ///
    /// # Examples
    /// A block glued to a rigid line by the RCCM law, its top pulled up: the glue holds it
    /// in tension, and the energy balance (the springs' energy and the damage included)
    /// closes.
    /// ```
    /// use contact_solver::coupling::simulation::{AdhesionUpdate, MoreauJean};
    /// use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
    /// use contact_laws::{BetaScheme, Rccm, RccmParams};
    /// use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
    /// use fem_core::generate::{RectangleSpec, rectangle};
    /// use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};
    ///
    /// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2))?;
    /// let (top, bottom) = (mesh.node_set("top")?.to_vec(), mesh.node_set("bottom")?.to_vec());
    /// let mut supports = Supports::new();
    /// supports.prescribe(&top, Component::Y, 0.005)?.fix(&top, Component::X);
    /// let m = Material::new(1e4, 0.0, 0.0)?.with_density(1.0)?;
    /// let model = LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], supports)?;
    /// let body = DynamicModel::new(model, MassKind::Lumped, Rayleigh::default())?;
    /// let glue = Rccm::new(RccmParams { c_n: 100.0, c_t: 100.0, w: 0.01, alpha: 0.0, mu: 0.2,
    ///     m: 1, beta_0: 1.0, scheme: BetaScheme::ImplicitEuler })?;
    /// let zone = ContactZone::rigid("glue", bottom, RigidLine::new([-1.0, 0.0], [2.0, 0.0])?,
    ///     glue, 1e-3);
    /// let scheme = MoreauJean::new(1.0)?.with_adhesion_update(AdhesionUpdate::Implicit);
    /// let mut sim = ContactSimulation::with_scheme(body, vec![zone],
    ///     SimulationSettings::default(), scheme)?;
    /// let res = sim.advance(0.01)?;
    /// assert!(res.contacts.iter().map(|c| c.r.n).sum::<f64>() < 0.0); // the glue pulls
    /// let e = sim.scheme().energy();
    /// assert!(e.interface > 0.0 && e.residual().abs() < 1e-10 * e.scale());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn with_adhesion_update(mut self, update: AdhesionUpdate) -> Self {
        self.adhesion = update;
        self
    }

    /// The restitution of the zone of index `zone` (in the simulation's zone list).
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] naming `restitution` outside `[0, 1]`.
    pub fn with_zone_restitution(mut self, zone: usize, e: f64) -> Result<Self, SolverError> {
        if self.zone_restitution.len() <= zone {
            self.zone_restitution.resize(zone + 1, None);
        }
        self.zone_restitution[zone] = Some(check_restitution(e)?);
        Ok(self)
    }

    /// The initial velocity `v_0` on the structure's free dofs (checked against the
    /// structure's dof count at the first step).
    ///
    /// # Errors
    /// [`SolverError::NonFinite`] naming `velocity`; [`SolverError::InvalidSetting`] naming
    /// `velocity` once a step has been accepted.
    pub fn with_velocity(mut self, velocity: Vec<f64>) -> Result<Self, SolverError> {
        self.before_first_step("velocity")?;
        check_finite("velocity", &velocity)?;
        self.velocity = velocity;
        Ok(self)
    }

    /// The initial velocity from a field `v(x)` at the nodes' reference positions, written
    /// on `structure`'s free dofs (prescribed components have none).
    ///
    /// # Errors
    /// As [`Self::with_velocity`].
    pub fn with_velocity_field<S: Structure<D> + ?Sized, const D: usize>(
        self,
        structure: &S,
        v: impl Fn([f64; D]) -> [f64; D],
    ) -> Result<Self, SolverError> {
        let mut velocity = vec![0.0; structure.dof_count()];
        for node in 0..structure.node_count() {
            let value = v(structure.node_position(node));
            for (c, dof) in structure.node_dofs(node).into_iter().enumerate() {
                if let Some(i) = dof {
                    velocity[i] = value[c];
                }
            }
        }
        self.with_velocity(velocity)
    }

    /// The initial displacement `u_0` on the structure's free dofs (the gaps of the first
    /// step start from it; its strain energy is in the balance's initial energy).
    ///
    /// # Errors
    /// As [`Self::with_velocity`], naming `displacement`.
    pub fn with_displacement(mut self, displacement: Vec<f64>) -> Result<Self, SolverError> {
        self.before_first_step("displacement")?;
        check_finite("displacement", &displacement)?;
        self.initial_displacement = Some(displacement);
        Ok(self)
    }

    /// The weight `θ`.
    pub fn theta(&self) -> f64 {
        self.theta
    }

    /// The velocity `v` on the free dofs at the end of the last accepted step (the initial
    /// velocity before the first; empty for a start at rest).
    pub fn velocity(&self) -> &[f64] {
        &self.velocity
    }

    /// The energy balance since the start, at the end of the last accepted step.
    pub fn energy(&self) -> &EnergyBalance {
        &self.energy
    }

    /// The energy balance at the end of every accepted step, in order.
    pub fn energy_history(&self) -> &[EnergyBalance] {
        &self.history
    }

    fn before_first_step(&self, what: &'static str) -> Result<(), SolverError> {
        if self.accepted_steps > 0 {
            return Err(SolverError::InvalidSetting {
                what,
                value: self.accepted_steps as f64,
                expected: "an initial value, set before the first step",
            });
        }
        Ok(())
    }

    /// The relative value of the free-dof field `y` at `candidate` in its frame (prescribed
    /// components count 0: they do not move).
    fn local_of<const D: usize>(&self, candidate: &Candidate<D>, y: &[f64]) -> [f64; 3] {
        let rel = candidate.relative(|node| {
            core::array::from_fn(|c| self.node_dofs[D * node + c].map_or(0.0, |i| y[i]))
        });
        let frame = candidate.frame();
        core::array::from_fn(|k| {
            if k < D {
                (0..D).map(|a| frame[k][a] * rel[a]).sum()
            } else {
                0.0
            }
        })
    }
}

fn check_restitution(e: f64) -> Result<f64, SolverError> {
    if (0.0..=1.0).contains(&e) {
        Ok(e)
    } else {
        Err(SolverError::InvalidSetting {
            what: "restitution",
            value: e,
            expected: "a coefficient in [0, 1]",
        })
    }
}

fn check_finite(what: &'static str, v: &[f64]) -> Result<(), SolverError> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(SolverError::NonFinite {
            what,
            index,
            value: v[index],
        }),
        None => Ok(()),
    }
}

fn length(what: &'static str, expected: usize, got: usize) -> Result<(), SolverError> {
    if expected == got {
        Ok(())
    } else {
        Err(FemError::LengthMismatch {
            what,
            expected,
            got,
        }
        .into())
    }
}

impl<const D: usize> TimeScheme<DynamicModel<D>, D> for MoreauJean
where
    Dim<D>: ModelSpace<D>,
{
    /// `v_free = v_k + M̂⁻¹ h (f_θ − C v_k − K (u_k + hθ v_k))` (module docs).
    fn free_response(
        &mut self,
        structure: &DynamicModel<D>,
        step: &SchemeStep<'_>,
        free: &mut [f64],
    ) -> Result<(), SolverError> {
        let Some((h, theta)) = structure.step() else {
            return Err(FemError::InvalidParameter {
                name: "h",
                value: step.dt,
                expected: "a step set on the structure: `ContactSimulation::advance` sets it",
            }
            .into());
        };
        if (step.dt - h).abs() > 1e-9 * h {
            return Err(SolverError::InvalidSetting {
                what: "dt",
                value: step.dt,
                expected: "the step `h` the structure's M̂ is factorised for \
                           (`ContactSimulation::advance` sets both)",
            });
        }
        if theta != self.theta {
            return Err(SolverError::InvalidSetting {
                what: "theta",
                value: theta,
                expected: "the scheme's θ in the structure's M̂ (`advance` sets both)",
            });
        }
        let n = structure.dof_count();
        if self.velocity.is_empty() {
            self.velocity = vec![0.0; n];
        }
        length("velocity", n, self.velocity.len())?;
        self.u_start = match &self.initial_displacement {
            Some(u0) => u0.clone(),
            None => step.displacement.to_vec(),
        };
        length("displacement", n, self.u_start.len())?;
        self.h = h;
        let lambda = (1.0 - theta) * self.force_factor.unwrap_or(step.force_factor)
            + theta * step.force_factor;
        self.load.resize(n, 0.0);
        structure.load_into(lambda, &mut self.load)?;
        // h (f_θ − C v_k − K (u_k + hθ v_k))
        let predictor: Vec<f64> = self
            .u_start
            .iter()
            .zip(&self.velocity)
            .map(|(u, v)| u + h * theta * v)
            .collect();
        let (mut kx, mut cv) = (vec![0.0; n], vec![0.0; n]);
        structure.stiffness_mul_into(&predictor, &mut kx);
        structure.damping_mul_into(&self.velocity, &mut cv);
        for (((y, f), c), k) in free.iter_mut().zip(&self.load).zip(&cv).zip(&kx) {
            *y = h * (f - c - k);
        }
        structure.solve_in_place(free)?;
        for (f, v) in free.iter_mut().zip(&self.velocity) {
            *f += v;
        }
        self.v_free.clear();
        self.v_free.extend_from_slice(free);
        self.node_dofs = (0..structure.node_count())
            .flat_map(|node| structure.node_dofs(node))
            .collect();
        Ok(())
    }

    /// Keeps the candidate's relative velocities and returns the jump predicted at
    /// `u_k + h(1−θ) v_k`: `[g_k + h(1−θ) v_n,k, u_t,k + h(1−θ) v_t,k]`.
    fn free_jump(
        &mut self,
        index: usize,
        candidate: &Candidate<D>,
        _u_rel: [f64; D],
        start: &[f64; D],
    ) -> [f64; D] {
        if self.contacts.len() <= index {
            self.contacts
                .resize(index + 1, ContactVelocities::default());
        }
        let shift = match &self.initial_displacement {
            Some(u0) => self.local_of(candidate, u0),
            None => [0.0; 3],
        };
        let e = self
            .zone_restitution
            .get(candidate.zone)
            .copied()
            .flatten()
            .unwrap_or(self.restitution);
        let contact = ContactVelocities {
            v_k: self.local_of(candidate, &self.velocity),
            v_free: self.local_of(candidate, &self.v_free),
            shift,
            e,
        };
        self.contacts[index] = contact;
        let weight = self.h * (1.0 - self.theta);
        core::array::from_fn(|d| start[d] + contact.shift[d] + weight * contact.v_k[d])
    }

    /// `[v_free,n + e v_n,k, v_free,t…]`.
    fn rhs(&self, index: usize, _free: &[f64; D], _start: &[f64; D]) -> [f64; D] {
        let c = &self.contacts[index];
        core::array::from_fn(|d| {
            if d == 0 {
                c.v_free[0] + c.e * c.v_k[0]
            } else {
                c.v_free[d]
            }
        })
    }

    /// `u = u_k + h((1−θ) v_k + θ v)`.
    fn displacement<'y>(&self, _step: &SchemeStep<'_>, solution: &'y [f64]) -> Cow<'y, [f64]> {
        let (h, theta) = (self.h, self.theta);
        Cow::Owned(
            self.u_start
                .iter()
                .zip(&self.velocity)
                .zip(solution)
                .map(|((u, v_k), v)| u + h * ((1.0 - theta) * v_k + theta * v))
                .collect(),
        )
    }

    /// `v_n = x_n − e v_n,k`, `v_t = x_t`, and the jump `start + h((1−θ) v_k + θ v)`.
    fn jump(&self, index: usize, x: &[f64; D], start: &[f64; D]) -> [f64; D] {
        let c = &self.contacts[index];
        let (h, theta) = (self.h, self.theta);
        core::array::from_fn(|d| {
            let v = if d == 0 { x[0] - c.e * c.v_k[0] } else { x[d] };
            start[d] + c.shift[d] + h * ((1.0 - theta) * c.v_k[d] + theta * v)
        })
    }

    /// Keeps `v`, and adds the step's terms to the energy balance.
    fn accept(
        &mut self,
        structure: &DynamicModel<D>,
        step: &SchemeStep<'_>,
        solution: &[f64],
        displacement: &[f64],
    ) {
        let contacts = std::mem::take(&mut self.step_contacts);
        if self.accepted_steps == 0 {
            self.energy =
                EnergyBalance::initial(structure, &self.u_start, &self.velocity, &contacts);
        }
        self.energy.add_step(
            structure,
            super::energy::StepFields {
                h: self.h,
                theta: self.theta,
                u_k: &self.u_start,
                u: displacement,
                v_k: &self.velocity,
                v: solution,
                v_free: &self.v_free,
                load: &self.load,
                contacts,
            },
        );
        self.history.push(self.energy);
        self.velocity.clear();
        self.velocity.extend_from_slice(solution);
        self.initial_displacement = None;
        self.force_factor = Some(step.force_factor);
        self.accepted_steps += 1;
    }

    /// Moreau's index set: the gap predicted at `u_k + h(1−θ) v_k` is closed (`≤ 0`); the
    /// alert distance and the skip rule do not widen it.
    fn enters(
        &self,
        _index: usize,
        _start: &[f64; D],
        free: &[f64; D],
        _alert_distance: f64,
        _all: bool,
    ) -> bool {
        free[0] <= 0.0
    }

    /// Never: the index set is the start of the step's (module docs).
    fn penetrates(&self, _index: usize, _jump: &[f64; D], _tolerance: f64) -> bool {
        false
    }

    /// The springs' impulse at `u_θ`: scale `h²θ²`, offset
    /// `(u_k + hθ(1−θ) v_k − hθ² e v_n,k n) / (hθ²)`; constrained in Moreau's index set
    /// (module docs).
    fn velocity_springs(&self, index: usize, start: &[f64; D]) -> Option<VelocitySprings<D>> {
        let c = &self.contacts[index];
        let (h, theta) = (self.h, self.theta);
        let slope = h * theta * theta;
        let offset = core::array::from_fn(|d| {
            let u_k = start[d] + c.shift[d];
            let restitution = if d == 0 { slope * c.e * c.v_k[0] } else { 0.0 };
            (u_k + h * theta * (1.0 - theta) * c.v_k[d] - restitution) / slope
        });
        let free_gap = start[0] + c.shift[0] + h * (1.0 - theta) * c.v_k[0];
        let implicit = self.adhesion == AdhesionUpdate::Implicit;
        Some(VelocitySprings::new(
            h * slope,
            offset,
            free_gap <= 0.0,
            implicit,
        ))
    }

    /// Keeps the contacts' impact, friction and damage terms for [`accept`](Self::accept).
    fn accept_contacts(&mut self, contacts: &[AcceptedContact<D>]) {
        let mut terms = ContactTerms::default();
        for a in contacts {
            let shift = self.contacts[a.index].shift;
            let start: [f64; D] = core::array::from_fn(|d| a.start[d] + shift[d]);
            terms.add(
                &a.r_bar,
                &start,
                &a.jump,
                a.springs_start,
                a.springs_end,
                self.adhesion == AdhesionUpdate::Implicit,
                self.h,
                self.theta,
            );
        }
        self.step_contacts = terms;
    }
}

impl<L: ContactLaw + Clone, const D: usize> ContactSimulation<DynamicModel<D>, L, D, MoreauJean>
where
    Dim<D>: ContactSpace<D> + ModelSpace<D>,
{
    /// One Moreau–Jean step of length `dt` at the force factor 1: factorises `M̂` for
    /// `(dt, θ)` if the structure's is for another step, then
    /// [`step`](ContactSimulation::step)s to `time() + dt`.
    ///
    /// # Errors
    /// [`SolverError::Structure`] naming `h` for a `dt` that is not finite and positive (or a
    /// failed factorisation); as [`ContactSimulation::step`] otherwise.
    pub fn advance(&mut self, dt: f64) -> Result<StepResult<D>, SolverError> {
        let theta = self.scheme().theta();
        self.structure_mut().set_step(dt, theta)?;
        let time = self.time() + dt;
        self.step(time, 1.0)
    }
}
