//! [`SolidContactSimulation`]: the 3D names of [`ContactSimulation<S, L, 3>`] (issue 35: one
//! simulation for both dimensions). It holds the generic simulation and converts its settings
//! ([`SolidSettings`] to [`SimulationSettings`]) and its step results ([`StepResult<3>`] to
//! [`SolidStepResult`]), so that 3D code written against it keeps its names; new code may use
//! `ContactSimulation<_, _, 3>` directly (floating bodies, skip rules, counters and the last
//! reduced problem come with it).
//!
//! A step: the free response `u_free`; the active set (candidates within their zone's alert
//! distance at the start of the step or under `u_free`, or adhesive, β > 0); `F*` on it
//! (rebuilt when the active set or the stiffness changes); the reduced problem
//! `x = F* r + q` with `q = (g₀ + n·u_rel, t₁·u_rel − u_t1,start, t₂·u_rel − u_t2,start)` per
//! contact, solved by the adhesion fixed point (a single reduced solve when no law is
//! adhesive); then `u = u_free + K⁻¹ Hᵀ r` and the penetration check of the inactive
//! candidates (added and solved again if one penetrates beyond
//! [`SolidSettings::penetration_tol`] × the contactors' extent). Past `Auto`'s dense limit (or
//! when asked), a step without adhesion is solved without `F*`: by the primal active set
//! ([`crate::coupling::primal`]) when in its scope, matrix-free otherwise.

use super::zone::{Candidate3, ContactZone3};
use crate::coupling::simulation::{ContactSimulation, SimulationSettings, StepResult};
use crate::error::SolverError;
use contact_laws::ContactLaw;
use fem_core::Structure;

mod report;

pub use report::{DEFAULT_DENSE_LIMIT_3D, SolidContactRecord, SolidSettings, SolidStepResult};

/// A quasi-static 3D contact simulation (module docs).
///
/// # Examples
/// A P2 block pressed on a rigid floor with friction: the force is uniform and no contact
/// slips.
/// ```
/// use contact_laws::Coulomb;
/// use contact_solver::coupling::solid::{ContactZone3, RigidPlane, SolidContactSimulation, SolidSettings};
/// use fem_core::solid::{SolidKind, SolidModel, generate::{box_mesh, lines}};
/// use fem_core::{Component, Material, Supports};
///
/// let mesh = box_mesh(&lines(0.0, 1.0, 2), &lines(0.0, 1.0, 2), &lines(0.0, 0.5, 1), SolidKind::Tet10)?;
/// let top = mesh.node_set("z1")?.to_vec();
/// let mut s = Supports::new();
/// s.prescribe(&top, Component::Z, -1e-3)?.fix(&top, Component::X).fix(&top, Component::Y);
/// let (nodes, areas) = mesh.nodal_areas("z0")?;
/// let model = SolidModel::new(mesh, &[(0, Material::new(1000.0, 0.0, 0.0)?)], s)?;
/// let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0])?;
/// let zone = ContactZone3::rigid("base", nodes, floor, Coulomb::new(0.3)?, 0.1).with_areas(areas);
/// let mut sim = SolidContactSimulation::new(model, vec![zone], SolidSettings::default())?;
/// let res = sim.step(1.0, 1.0)?;
/// let total: f64 = res.contacts.iter().map(|c| c.r[0]).sum();
/// assert!((total - 2.0).abs() < 1e-8); // σ = E δ / H = 2 on a unit area (ν = 0)
/// assert!(res.contacts.iter().all(|c| c.slip[0].abs() < 1e-12 && c.slip[1].abs() < 1e-12));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct SolidContactSimulation<S: Structure<3>, L: ContactLaw> {
    sim: ContactSimulation<S, L, 3>,
    settings: SolidSettings,
}

impl<S: Structure<3>, L: ContactLaw + Clone> SolidContactSimulation<S, L> {
    /// Recognises the candidates of `zones` on `structure` and starts at time 0.
    ///
    /// # Errors
    /// As [`ContactSimulation::new`] (with the 3D checks of the candidates);
    /// [`SolverError::Unsupported`] for a floating structure (use `ContactSimulation<_, _, 3>`,
    /// which solves for the rigid-body amplitudes); [`SolverError::InvalidSetting`] for zero
    /// `columns_per_solve` or `max_passes`, or a `penetration_tol` that is not finite and
    /// positive; [`SolverError::InvalidGeometry`] for an adhesive zone without areas.
    pub fn new(
        structure: S,
        zones: Vec<ContactZone3<L>>,
        settings: SolidSettings,
    ) -> Result<Self, SolverError> {
        check_settings(&settings)?;
        if structure.floating().is_some() {
            return Err(SolverError::Unsupported(
                "a floating 3D structure (rigid-body modes) in SolidContactSimulation: hold it \
                 with supports, or use ContactSimulation<_, _, 3>"
                    .into(),
            ));
        }
        let mut sim = ContactSimulation::new(structure, zones, simulation_settings(&settings))?;
        sim.set_relative_penetration_tol(settings.penetration_tol);
        Ok(Self { sim, settings })
    }

    /// The generic simulation this one names.
    pub fn simulation(&self) -> &ContactSimulation<S, L, 3> {
        &self.sim
    }

    /// The structure.
    pub fn structure(&self) -> &S {
        self.sim.structure()
    }

    /// The candidates.
    pub fn candidates(&self) -> &[Candidate3] {
        self.sim.candidates()
    }

    /// The zones.
    pub fn zones(&self) -> &[ContactZone3<L>] {
        self.sim.zones()
    }

    /// Replaces the law of the zone named `zone` from the next step on (laws by phase: press
    /// without friction, then shear with it; other parameters). Every candidate's state (β)
    /// and accepted jump carry over.
    ///
    /// # Errors
    /// [`SolverError::UnknownZone`] naming the zones there are;
    /// [`SolverError::InvalidGeometry`] for an adhesive law on a zone without areas.
    pub fn set_law(&mut self, zone: &str, law: L) -> Result<(), SolverError> {
        self.sim.set_law(zone, law)
    }

    /// The settings.
    pub fn settings(&self) -> &SolidSettings {
        &self.settings
    }

    /// Replaces the settings from the next step on.
    ///
    /// # Errors
    /// As [`SolidContactSimulation::new`] for the settings.
    pub fn set_settings(&mut self, settings: SolidSettings) -> Result<(), SolverError> {
        check_settings(&settings)?;
        self.sim.set_settings(simulation_settings(&settings));
        self.sim
            .set_relative_penetration_tol(settings.penetration_tol);
        self.settings = settings;
        Ok(())
    }

    /// Per-candidate law states at the end of the last step.
    pub fn states(&self) -> &[L::State] {
        self.sim.states()
    }

    /// Resets the displacements and the tangential references to zero while keeping the law
    /// states (e.g. after an installation phase whose displacements are discarded).
    pub fn reset_displacements(&mut self) {
        self.sim.reset_displacements();
    }

    /// The time at the end of the last step (0 before the first).
    pub fn time(&self) -> f64 {
        self.sim.time()
    }

    /// Steps solved so far.
    pub fn steps(&self) -> usize {
        self.sim.counters().steps
    }

    /// The free-dof displacement at the end of the last step, in the dof numbering of that
    /// step (a change of supports since renumbers the structure's dofs; the next step follows).
    pub fn displacement(&self) -> &[f64] {
        self.sim.displacement()
    }

    /// The displacement of `node` at the end of the last step (prescribed components
    /// included).
    ///
    /// # Panics
    /// If `node >= node_count()`.
    #[track_caller]
    pub fn nodal_displacement(&self, node: usize) -> [f64; 3] {
        self.sim.nodal_displacement(node)
    }

    /// Mutable access to the structure between steps (loads, prescribed values). A change of
    /// stiffness is noticed through [`Structure::stiffness_version`].
    pub fn structure_mut(&mut self) -> &mut S {
        self.sim.structure_mut()
    }

    /// One load step ending at `time` (`≥` the current time) with the applied forces scaled by
    /// `force_factor`, as [`ContactSimulation::step`]: the **prescribed displacements are not
    /// scaled** (ramp them through [`Self::structure_mut`]).
    ///
    /// # Errors
    /// As [`ContactSimulation::step`]; [`SolverError::StillPenetrating`] names `max_passes`
    /// when candidates outside the reduced problem still penetrate after that many passes. On
    /// error the simulation keeps the previous state.
    pub fn step(&mut self, time: f64, force_factor: f64) -> Result<SolidStepResult, SolverError> {
        let before = self.sim.counters().active_set_factorizations;
        let res = self.sim.step(time, force_factor).map_err(|e| match e {
            SolverError::StillPenetrating {
                passes,
                count,
                zone,
                node,
                gap,
                ..
            } => SolverError::StillPenetrating {
                passes,
                count,
                zone,
                node,
                gap,
                setting: "max_passes",
            },
            e => e,
        })?;
        let factorizations = self.sim.counters().active_set_factorizations - before;
        Ok(self.result(res, factorizations))
    }

    /// The 3D step result of the generic one.
    fn result(&self, res: StepResult<3>, factorizations: usize) -> SolidStepResult {
        let contacts: Vec<SolidContactRecord> = res
            .contacts
            .iter()
            .zip(self.sim.candidates())
            .map(|(c, candidate)| SolidContactRecord {
                candidate: *candidate,
                r: c.reaction(),
                beta: c.beta,
                gap: c.gap,
                slip: c.slip_increment,
                active: c.status != crate::coupling::simulation::InterfaceStatus::Inactive,
                closed: c.status.is_closed(),
            })
            .collect();
        let r = &res.report;
        SolidStepResult {
            contacts,
            contact_iterations: r.contact_iterations,
            adhesion_iterations: r.adhesion_iterations,
            passes: r.detection_passes,
            residual: r.residual,
            active: r.active_contacts,
            closed: r.closed_contacts,
            matrix_free: r.matrix_free,
            active_set: r.active_set,
            factorizations,
        }
    }
}

/// The generic settings of 3D ones: `max_passes` is `max_detection_passes`, the adhesion
/// options their fields (non-converged results are accepted when either asks).
fn simulation_settings(s: &SolidSettings) -> SimulationSettings {
    let mut solver = s.solver;
    solver.accept_non_converged |= s.adhesion.accept_non_converged;
    SimulationSettings::for_dimension::<3>()
        .with_solver(solver)
        .with_columns_per_solve(s.columns_per_solve)
        .with_max_detection_passes(s.max_passes)
        .with_adhesion_tol(s.adhesion.tol)
        .with_max_adhesion_iterations(s.adhesion.max_iterations)
        .with_adhesion_anderson_window(s.adhesion.anderson_window)
        .with_adhesion_method(s.adhesion.method)
        .with_adhesion_warm_start(s.adhesion.warm_start)
        .with_flexibility(s.flexibility)
}

/// The checks of [`SolidSettings`] (the errors of [`SolidContactSimulation::new`]).
fn check_settings(settings: &SolidSettings) -> Result<(), SolverError> {
    if settings.columns_per_solve == 0 || settings.max_passes == 0 {
        return Err(SolverError::InvalidSetting {
            what: "columns_per_solve / max_passes",
            value: 0.0,
            expected: "at least 1",
        });
    }
    if !(settings.penetration_tol > 0.0 && settings.penetration_tol.is_finite()) {
        return Err(SolverError::InvalidSetting {
            what: "penetration_tol",
            value: settings.penetration_tol,
            expected: "a finite tolerance > 0",
        });
    }
    Ok(())
}
