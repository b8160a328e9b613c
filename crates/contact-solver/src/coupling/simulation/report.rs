//! What a step reports: per contact ([`ContactRecord`]), per step ([`StepReport`]) and over the
//! whole simulation ([`Counters`]).

use super::choice::PathChoice;
use crate::coupling::space::ContactSpace;
use fem_core::Dim;
use std::time::Duration;

/// What a contact is doing at the end of a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub enum InterfaceStatus {
    /// Outside the alert distance: not in the reduced problem.
    Inactive,
    /// In the reduced problem, `r̄ = 0` (open; adhesive springs may still pull).
    Open,
    /// Compressed, sticking (a law with friction).
    Stick,
    /// Compressed, sliding (a law with friction).
    Slip,
    /// Compressed under a frictionless law (Signorini): neither sticking nor sliding, since
    /// nothing resists the tangential motion (issue 36: these were reported as `Stick`).
    Closed,
}

impl InterfaceStatus {
    /// A short lowercase name (`inactive`, `open`, `stick`, `slip`, `closed`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Inactive => "inactive",
            Self::Open => "open",
            Self::Stick => "stick",
            Self::Slip => "slip",
            Self::Closed => "closed",
        }
    }

    /// Whether the contact is closed: the law's reaction `r̄` is not zero (compressed, sticking,
    /// sliding, or closed without friction), what the outputs count as "active". `Inactive`
    /// (outside the alert distance) and `Open` (in the reduced problem, `r̄ = 0`) are not.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::InterfaceStatus;
    /// assert!(InterfaceStatus::Stick.is_closed() && InterfaceStatus::Slip.is_closed());
    /// assert!(InterfaceStatus::Closed.is_closed());
    /// assert!(!InterfaceStatus::Open.is_closed() && !InterfaceStatus::Inactive.is_closed());
    /// ```
    pub fn is_closed(self) -> bool {
        matches!(self, Self::Stick | Self::Slip | Self::Closed)
    }
}

/// One contact candidate at the end of a step. Local vectors have named components: `r.n` (normal,
/// `> 0` compression) and `r.t` (tangential). In 2D (the default `D`) the tangential
/// quantities are numbers and the local vectors [`LocalVec2`](contact_laws::LocalVec2); in 3D
/// they are pairs and [`LocalVec3`](contact_laws::LocalVec3) ([`ContactSpace`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ContactRecord<const D: usize = 2>
where
    Dim<D>: ContactSpace<D>,
{
    /// Zone index.
    pub zone: usize,
    /// Contactor node.
    pub node: usize,
    /// Reference position of the contactor node.
    pub position: [f64; D],
    /// Tributary area of the node: `r / area` is the interface stress.
    pub area: f64,
    /// Status.
    pub status: InterfaceStatus,
    /// Normal gap `x_n = g₀ + u_n` (`≥ 0`: open). For a glued interface (`g₀ = 0`) it is the
    /// normal jump `u_n` of the RCCM law.
    pub gap: f64,
    /// Total tangential relative displacement `u_t`.
    pub u_t: <Dim<D> as ContactSpace<D>>::Tangential,
    /// Tangential relative displacement of this step (the slip increment when sliding).
    pub slip_increment: <Dim<D> as ContactSpace<D>>::Tangential,
    /// Adhesion intensity β ([`ContactLaw::adhesion_intensity`](contact_laws::ContactLaw::adhesion_intensity), 0 without adhesion).
    pub beta: f64,
    /// Unit normal of the contact, global axes, from the target towards the contactor.
    pub normal: [f64; D],
    /// Unit tangent `t = (n_y, −n_x)` (2D; the two tangents of the frame in 3D), global
    /// axes: `r.t` is along it.
    pub tangent: <Dim<D> as ContactSpace<D>>::Tangents,
    /// Total reaction `r = r̄ + r_adh` on the contactor (`r_n > 0` compression).
    pub r: <Dim<D> as ContactSpace<D>>::Local,
    /// Reaction of the contact law proper, `r̄ ∈ K_μ̄`.
    pub r_bar: <Dim<D> as ContactSpace<D>>::Local,
    /// Adhesive reaction `r_adh`.
    pub r_adh: <Dim<D> as ContactSpace<D>>::Local,
}

impl<const D: usize> Default for ContactRecord<D>
where
    Dim<D>: ContactSpace<D>,
{
    /// An inactive record of zone 0, node 0: every number 0 (the frame too), to fill in field
    /// by field (the struct is `#[non_exhaustive]`).
    fn default() -> Self {
        let zero = <Dim<D> as ContactSpace<D>>::local_of(&[0.0; D]);
        let tangential = <Dim<D> as ContactSpace<D>>::tangential_of(&[0.0; D]);
        Self {
            zone: 0,
            node: 0,
            position: [0.0; D],
            area: 0.0,
            status: InterfaceStatus::Inactive,
            gap: 0.0,
            u_t: tangential,
            slip_increment: tangential,
            beta: 0.0,
            normal: [0.0; D],
            tangent: <Dim<D> as ContactSpace<D>>::tangents_of([[0.0; D]; D]),
            r: zero,
            r_bar: zero,
            r_adh: zero,
        }
    }
}

impl<const D: usize> ContactRecord<D>
where
    Dim<D>: ContactSpace<D>,
{
    /// The total reaction's local components `[r_n, r_t…]` (any dimension).
    pub fn reaction(&self) -> [f64; D] {
        <Dim<D> as ContactSpace<D>>::components(&self.r)
    }

    /// The contact frame `[n, t…]` in global axes: [`normal`](Self::normal), then the
    /// [`tangent`](Self::tangent)s.
    pub fn frame(&self) -> [[f64; D]; D] {
        <Dim<D> as ContactSpace<D>>::frame_of(self.normal, &self.tangent)
    }

    /// The total reaction on the contactor node in global axes, `r_n n + r_t t` (2D),
    /// `r_n n + r_t1 t1 + r_t2 t2` (3D); its target nodes carry the opposite, split by their
    /// weights.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::{ContactRecord, InterfaceStatus, contact_laws::LocalVec2};
    /// let mut c: ContactRecord = ContactRecord::default();
    /// (c.node, c.area, c.status) = (3, 1.0, InterfaceStatus::Slip);
    /// (c.normal, c.tangent) = ([0.0, 1.0], [1.0, 0.0]);
    /// (c.r, c.r_bar) = (LocalVec2::planar(2.0, -0.5), LocalVec2::planar(2.0, -0.5));
    /// assert_eq!(c.force(), [-0.5, 2.0]);
    /// assert_eq!(c.pressure(), 2.0);
    /// assert!(c.is_active() && c.is_closed());
    /// ```
    pub fn force(&self) -> [f64; D] {
        let (r, frame) = (self.reaction(), self.frame());
        core::array::from_fn(|a| (1..D).fold(r[0] * frame[0][a], |f, k| f + r[k] * frame[k][a]))
    }

    /// The contact pressure `r_n / area` (0 for a node without area).
    pub fn pressure(&self) -> f64 {
        if self.area > 0.0 {
            self.reaction()[0] / self.area
        } else {
            0.0
        }
    }

    /// Whether the contact was in the step's reduced problem (a candidate within its alert
    /// distance, maybe open): its status is not [`InterfaceStatus::Inactive`].
    pub fn is_active(&self) -> bool {
        self.status != InterfaceStatus::Inactive
    }

    /// Whether the contact is closed at the end of the step: the law's reaction `r̄` is not
    /// zero ([`InterfaceStatus::is_closed`]).
    pub fn is_closed(&self) -> bool {
        self.status.is_closed()
    }
}

/// Counters and timing of one step.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct StepReport {
    /// Step number (1-based).
    pub step: usize,
    /// Time at the end of the step.
    pub time: f64,
    /// The step's force factor ([`ContactSimulation::step`](crate::ContactSimulation::step)'s
    /// second argument: it scales the applied forces, not prescribed displacements).
    pub load_factor: f64,
    /// Candidates in the reduced problem (within the alert distance, in contact at the last
    /// step, or adhesive): the `candidates` column of
    /// [`ReportWriter`](crate::coupling::output::ReportWriter).
    pub active_contacts: usize,
    /// Contacts closed at the end of the step ([`InterfaceStatus::is_closed`]): the
    /// `active_contacts` column of [`ReportWriter`](crate::coupling::output::ReportWriter).
    pub closed_contacts: usize,
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
    /// The path of the step's last pass and why it was taken (the settings, or `Auto`'s rule
    /// and its numbers): see [`PathChoice`].
    pub path: PathChoice,
    /// Floating structures: Newton iterations on the rigid-body amplitudes (0 otherwise).
    pub equilibrium_iterations: usize,
    /// Floating structures: reduced solves of those iterations, line-search trials included.
    pub equilibrium_solves: usize,
    /// Natural-map residual of the last reduced solve.
    pub residual: f64,
    /// Whether every solve of the step met its tolerance (always `true` unless the settings
    /// accept non-converged results).
    pub converged: bool,
    /// Wall time of the step.
    pub wall_time: Duration,
    /// The global Newton of a nonlinear structure
    /// ([`ContactSimulation::with_newton`](crate::ContactSimulation::with_newton)): its
    /// iterations and residuals; `None` on the linear path.
    pub newton: Option<NewtonReport>,
}

/// What the global Newton around contact did in one
/// [`step`](crate::ContactSimulation::step) ([`ContactSimulation::with_newton`](crate::ContactSimulation::with_newton)).
///
/// A step that was cut ran as several accepted sub-steps; `iterations` and the residuals are
/// those of the last one, which ends at the step's time and force factor.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct NewtonReport {
    /// Newton corrections of the last sub-step (one contact solve on the current tangent
    /// each): 1 for a linear-elastic structure.
    pub iterations: usize,
    /// The relative equilibrium residual `‖f_ext + Hᵀ r − f_int(u)‖∞ / scale` of the last
    /// sub-step at every evaluation: at its start (the last step's `u` and `r` under the new
    /// load), then after each correction; the last is below
    /// [`NewtonSettings::tol`](crate::NewtonSettings::tol). The scale is the largest of
    /// `‖f_ext‖∞`, `‖f_int(u)‖∞` and `‖Hᵀ r‖∞`.
    pub residuals: Vec<f64>,
    /// The natural-map residual of the contact problem solved in each correction (the
    /// reduced solver's own, below its tolerance unless the settings accept non-converged
    /// solves).
    pub contact_residuals: Vec<f64>,
    /// Halvings of the step after a sub-step that did not converge.
    pub cuts: usize,
    /// Sub-steps accepted (1 when the step was not cut); each is counted in
    /// [`Counters::steps`].
    pub substeps: usize,
    /// Newton corrections over the whole step, the attempts that were cut included.
    pub total_iterations: usize,
}

/// Counters over the whole simulation: what work was done (and skipped).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
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
    /// Refactorisations of the structure's `K` after a 3D active-set solve that freed its
    /// factor (one factor held at a time: [`Structure::release_factor`](fem_core::Structure::release_factor)).
    pub structure_refactorizations: usize,
    /// Solves with the constrained stiffness by the active-set iteration.
    pub active_set_solves: usize,
    /// Active-set iterations solved on the correction columns of a window around the moving
    /// fronts, without a solve with the stiffness (counted in `contact_iterations` too).
    pub active_set_inner_iterations: usize,
    /// Steps where `Auto`'s active-set iteration did not converge and the step was solved
    /// again with a dense `F*` (up to 8000 contacts) or matrix-free.
    pub active_set_fallbacks: usize,
    /// Floating structures: Newton iterations on the rigid-body amplitudes.
    pub equilibrium_iterations: usize,
    /// Floating structures: reduced solves of those iterations.
    pub equilibrium_solves: usize,
    /// Adhesive solves where [`AdhesionMethod::Newton`](crate::local::adhesion::AdhesionMethod)
    /// could not make progress and the fixed point gave the answer.
    pub adhesion_newton_fallbacks: usize,
    /// Adhesive solves that Newton solved from the previous step's reactions, without the
    /// loose start and its condensation
    /// ([`AdhesionOptions::warm_start`](crate::local::adhesion::AdhesionOptions::warm_start)).
    pub adhesion_warm_starts: usize,
    /// Warm starts that did not converge within their cap or whose answer the state-change
    /// guard dropped (the step went on from the loose start).
    pub adhesion_warm_start_failures: usize,
    /// Jacobians the adhesive Newton formed and factorised (its other iterations were chord
    /// steps with kept factors).
    pub adhesion_factorizations: usize,
}

impl Counters {
    /// Adds an adhesive solve's Newton outcomes.
    pub(crate) fn record_adhesive<S>(&mut self, sol: &crate::local::adhesion::AdhesiveSolution<S>) {
        self.adhesion_newton_fallbacks += usize::from(sol.newton_fallback);
        self.adhesion_warm_starts += usize::from(sol.warm_started);
        self.adhesion_warm_start_failures += usize::from(sol.warm_start_failed);
        self.adhesion_factorizations += sol.jacobian_factorizations;
    }
}

/// The result of one step.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct StepResult<const D: usize = 2>
where
    Dim<D>: ContactSpace<D>,
{
    /// Counters and timing.
    pub report: StepReport,
    /// Every candidate, in recognition order.
    pub contacts: Vec<ContactRecord<D>>,
}

impl StepReport {
    /// The report of a step before any work: one pass, converged, nothing counted yet.
    pub(super) fn start(step: usize, time: f64, load_factor: f64) -> Self {
        Self {
            step,
            time,
            load_factor,
            active_contacts: 0,
            closed_contacts: 0,
            adhesion_iterations: 0,
            contact_iterations: 0,
            detection_passes: 0,
            flexibility_rebuilt: false,
            matrix_free: false,
            active_set: false,
            path: PathChoice::default(),
            equilibrium_iterations: 0,
            equilibrium_solves: 0,
            residual: 0.0,
            converged: true,
            wall_time: Duration::ZERO,
            newton: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn issue_35_record_force_is_one_formula_in_both_dimensions() {
        // 3D: a frame turned about z by 90°, n = e_z, t1 = e_y, t2 = −e_x; r = (2, 0.5, −0.25)
        let c = ContactRecord::<3> {
            normal: [0.0, 0.0, 1.0],
            tangent: [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]],
            r: <Dim<3> as ContactSpace<3>>::local_of(&[2.0, 0.5, -0.25]),
            area: 0.5,
            status: InterfaceStatus::Slip,
            ..Default::default()
        };
        assert_eq!(
            c.frame(),
            [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]
        );
        assert_eq!(c.force(), [0.25, 0.5, 2.0]);
        assert_eq!(c.pressure(), 4.0);
        assert!(c.is_active() && c.is_closed());
        // 2D: n = e_y, t = e_x; r = (3, −1)
        let p = ContactRecord::<2> {
            normal: [0.0, 1.0],
            tangent: [1.0, 0.0],
            r: <Dim<2> as ContactSpace<2>>::local_of(&[3.0, -1.0]),
            status: InterfaceStatus::Open,
            ..Default::default()
        };
        assert_eq!(p.force(), [-1.0, 3.0]);
        assert_eq!(p.pressure(), 0.0); // no area
        assert!(p.is_active() && !p.is_closed());
        assert!(!ContactRecord::<3>::default().is_active());
    }
}
