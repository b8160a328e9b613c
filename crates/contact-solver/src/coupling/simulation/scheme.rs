//! The time-scheme seam: what the time discretisation of a step decides, apart from the stages
//! every scheme shares (detection, the operator, the local solve, the penetration check).
//!
//! A step of [`ContactSimulation`](super::ContactSimulation) solves, on the active contacts,
//! the reduced problem
//!
//! ```text
//! y = y_free + A⁻¹ Hᵀ r,     x = W r + q,     W = H A⁻¹ Hᵀ
//! ```
//! where `y` is the scheme's unknown on the structure's free dofs and `A` what the structure
//! solves with ([`Structure::solve_in_place`]). The scheme says what `y_free` is (the free
//! response), what `q` is (from the free response and the accepted jumps), and what a solution
//! means once the step is accepted (the displacement, the contacts' jumps).
//!
//! | | [`QuasiStatic`] (today's) | a velocity-level scheme (Moreau–Jean θ) |
//! |---|---|---|
//! | `y` | displacement `u` | velocity `v` |
//! | `A` | stiffness `K` | `M̂ = M + hθC + h²θ²K` (a structure that solves with it) |
//! | `y_free` | `K⁻¹ f` at the force factor (`+ R α`) | `v_k + M̂⁻¹ h (f_θ − C v_k − K(u_k + hθ v_k))` |
//! | `x`, `q` | `(gap, slip increment)`, `(g_free, u_t,free − u_t,start)` | relative velocity, `H v_free` |
//! | accepted `u` | `y` | `u_k + h((1−θ) v_k + θ v)` |
//!
//! The operator `W` is not the scheme's: it is `H A⁻¹ Hᵀ` on the simulation's structure, so a
//! velocity-level scheme runs on a structure whose solves are with `M̂` (and whose
//! [`Structure::stiffness_version`] changes with `h`, which rebuilds the cached `F*`).

use crate::coupling::zone::Candidate;
use crate::error::SolverError;
use fem_core::Structure;
use std::borrow::Cow;

/// What a [`TimeScheme`] is told about the step it serves.
#[derive(Clone, Copy, Debug)]
#[non_exhaustive]
pub struct SchemeStep<'a> {
    /// The time at the end of the step.
    pub time: f64,
    /// The step's length `h`: `time` minus the time at the end of the last step (`≥ 0`; 0 for
    /// a load step at the same time).
    pub dt: f64,
    /// The factor on the structure's applied forces
    /// ([`ContactSimulation::step`](super::ContactSimulation::step)'s second argument).
    pub force_factor: f64,
    /// The accepted displacement at the end of the last step, on the structure's free dofs in
    /// the current numbering.
    pub displacement: &'a [f64],
    /// Floating structures ([`Structure::floating`]): the accepted amplitudes `α` of the
    /// rigid-body modes, one per mode (empty otherwise).
    pub rigid_body_amplitudes: &'a [f64],
}

impl<'a> SchemeStep<'a> {
    /// The step ending at `time` after `dt`, from the accepted `displacement` and amplitudes.
    pub(super) fn new(
        time: f64,
        dt: f64,
        force_factor: f64,
        displacement: &'a [f64],
        rigid_body_amplitudes: &'a [f64],
    ) -> Self {
        Self {
            time,
            dt,
            force_factor,
            displacement,
            rigid_body_amplitudes,
        }
    }
}

/// The time discretisation of a [`ContactSimulation`](super::ContactSimulation) step: the
/// free response, the right-hand side `q` of the reduced problem, and the acceptance of a
/// step go through it (module docs). [`QuasiStatic`] is the default: load steps, each an
/// equilibrium.
///
/// # Contract
/// Per step the simulation calls, in this order: [`free_response`](Self::free_response)
/// once; [`free_jump`](Self::free_jump) once per candidate; [`enters`](Self::enters) once
/// per candidate (the initial active set); then per detection pass
/// [`rhs`](Self::rhs) per active contact (several times per pass for floating structures),
/// [`displacement`](Self::displacement) once, [`jump`](Self::jump) per active contact and
/// [`penetrates`](Self::penetrates) per inactive candidate; and [`accept`](Self::accept) once when the step is accepted (not on an error). Contacts are
/// named by their candidate index (stable over the simulation), local vectors are
/// `[n, t…]` in the candidate's frame ([`Candidate::frame`]), and *jumps* are always
/// displacement-level: `[gap, u_t…]` with the gap `g₀ + n·u_rel` (signs:
/// [`contact_laws`]). The reduced unknowns `x` and `q` are in the scheme's unit: lengths for
/// [`QuasiStatic`], velocities for a velocity-level scheme.
///
/// `S` is the structure type, so that a scheme may ask more of it than [`Structure`] (a mass,
/// a damping) through its own bounds.
///
/// The simulation's own check of the force factor (a factor other than 1 on a structure with
/// no applied force is refused, issue 36) compares the free response with the structure's
/// [`Structure::free_response_into`] at factor 1: a displacement-level check, which a scheme
/// of another unit meets by stepping with the factor 1.
///
/// # Examples
/// A scheme that counts the steps it accepts and is otherwise [`QuasiStatic`]:
/// ```
/// use contact_solver::coupling::simulation::{QuasiStatic, SchemeStep, TimeScheme};
/// use contact_solver::{Candidate, SolverError};
/// use std::borrow::Cow;
///
/// #[derive(Default)]
/// struct Counted { inner: QuasiStatic, accepted: usize }
///
/// impl<S: ?Sized, const D: usize> TimeScheme<S, D> for Counted
/// where QuasiStatic: TimeScheme<S, D> {
///     fn free_response(&mut self, s: &S, step: &SchemeStep<'_>, free: &mut [f64])
///         -> Result<(), SolverError> { self.inner.free_response(s, step, free) }
///     fn free_jump(&mut self, i: usize, c: &Candidate<D>, u_rel: [f64; D], start: &[f64; D])
///         -> [f64; D] { TimeScheme::<S, D>::free_jump(&mut self.inner, i, c, u_rel, start) }
///     fn rhs(&self, i: usize, free: &[f64; D], start: &[f64; D]) -> [f64; D] {
///         TimeScheme::<S, D>::rhs(&self.inner, i, free, start)
///     }
///     fn displacement<'y>(&self, step: &SchemeStep<'_>, y: &'y [f64]) -> Cow<'y, [f64]> {
///         TimeScheme::<S, D>::displacement(&self.inner, step, y)
///     }
///     fn jump(&self, i: usize, x: &[f64; D], start: &[f64; D]) -> [f64; D] {
///         TimeScheme::<S, D>::jump(&self.inner, i, x, start)
///     }
///     fn accept(&mut self, s: &S, step: &SchemeStep<'_>, y: &[f64], u: &[f64]) {
///         self.accepted += 1;
///         self.inner.accept(s, step, y, u)
///     }
/// }
///
/// // plugged into a simulation (a block pressed on a rigid line) with `with_scheme`
/// use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
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
/// let zone = ContactZone::rigid("base", bottom, RigidLine::new([-1.0, 0.0], [2.0, 0.0])?,
///     Signorini, 0.1);
/// let mut sim = ContactSimulation::with_scheme(model, vec![zone],
///     SimulationSettings::default(), Counted::default())?;
/// let res = sim.step(1.0, 1.0)?;
/// assert_eq!(sim.scheme().accepted, 1);
/// let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
/// assert!((total - 1.0).abs() < 1e-9); // E δ / H over a width of 1, as quasi-static
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub trait TimeScheme<S: ?Sized, const D: usize> {
    /// Writes the free response `y_free` (the response without contact) into `free`, on the
    /// structure's free dofs (`free` is zeroed, [`Structure::dof_count`] long), in the
    /// scheme's unknown: a displacement for [`QuasiStatic`], a velocity for a velocity-level
    /// scheme. The simulation counts it as one structure solve.
    ///
    /// # Errors
    /// [`SolverError::Structure`] (or another variant) if the structure's solve or load fails;
    /// the step then fails and the simulation keeps the last accepted state.
    fn free_response(
        &mut self,
        structure: &S,
        step: &SchemeStep<'_>,
        free: &mut [f64],
    ) -> Result<(), SolverError>;

    /// The jump `[gap, u_t…]` (lengths) the free response predicts for candidate `index`
    /// at the end of the step, from the relative value `u_rel` of the free response at its
    /// nodes (global axes, prescribed components included) and its accepted jump `start`.
    /// Detection compares its gap with the zone's alert distance. [`QuasiStatic`]:
    /// `candidate.local(u_rel)`. A scheme may keep what it computes per candidate (a
    /// velocity-level scheme keeps the relative velocities the step's `q` and jumps need).
    fn free_jump(
        &mut self,
        index: usize,
        candidate: &Candidate<D>,
        u_rel: [f64; D],
        start: &[f64; D],
    ) -> [f64; D];

    /// The right-hand side `q = [q_n, q_t…]` of contact `index` in `x = W r + q`, from its
    /// predicted jump `free` ([`free_jump`](Self::free_jump)) and its accepted jump `start`,
    /// in the unit of `x`. The simulation sets `q_t` to 0 on the tangential rows it decouples
    /// (frictionless laws under the skip rules, held 3D directions). [`QuasiStatic`]:
    /// `[free_n, free_t − start_t]` (the gap, and the slip increment of the step).
    fn rhs(&self, index: usize, free: &[f64; D], start: &[f64; D]) -> [f64; D];

    /// The displacement on the free dofs that the step's solution `solution` (`y_free + A⁻¹ Hᵀ
    /// r`, plus the rigid motion `R Δα` of a floating structure) stands for; the penetration
    /// check and, once accepted, the next step start from it; borrow `solution` when it is
    /// the displacement. Called once per detection pass: it must not change the scheme (a pass
    /// may be redone). [`QuasiStatic`]: `solution` itself.
    fn displacement<'y>(&self, step: &SchemeStep<'_>, solution: &'y [f64]) -> Cow<'y, [f64]>;

    /// The jump `[gap, u_t…]` (lengths) of active contact `index` at the end of the step, from
    /// its reduced solution `x` and its accepted jump `start`. The simulation keeps the normal
    /// component and the solved tangential ones (the others come from the displacement).
    /// [`QuasiStatic`]: `[x_n, start_t + x_t]`.
    fn jump(&self, index: usize, x: &[f64; D], start: &[f64; D]) -> [f64; D];

    /// Accepts the step: called once, after the last pass, with the `structure`, the step's
    /// `solution` and the `displacement` the simulation keeps (the place for a velocity-level
    /// scheme to keep its velocity and its energy balance). Not called when the step fails.
    /// [`QuasiStatic`]: nothing to keep.
    fn accept(
        &mut self,
        structure: &S,
        step: &SchemeStep<'_>,
        solution: &[f64],
        displacement: &[f64],
    );

    /// Whether candidate `index` enters the reduced problem at the start of the step, from
    /// its accepted jump `start`, the jump `free` the free response predicts
    /// ([`free_jump`](Self::free_jump)), its zone's alert distance, and `all` (`true` when
    /// the alert-distance skip rule is off, [`SkipRules`](super::SkipRules)). Adhesive
    /// candidates enter whatever it says. The default, the quasi-static rule: `all`, or
    /// either gap within the alert distance. A velocity-level scheme answers with its index
    /// set instead (a contact in the problem has its velocity constrained, open or not).
    #[inline]
    fn enters(
        &self,
        index: usize,
        start: &[f64; D],
        free: &[f64; D],
        alert_distance: f64,
        all: bool,
    ) -> bool {
        let _ = index;
        all || start[0] <= alert_distance || free[0] <= alert_distance
    }

    /// Whether inactive candidate `index`, whose jump at the end of the pass is `jump`,
    /// penetrates so that the step must be redone with it active. The default, the
    /// quasi-static check: `gap < −tolerance` (the simulation's penetration tolerance). A
    /// velocity-level scheme, whose index set is decided at the start of the step and which
    /// allows an `O(h)` interpenetration, answers `false`.
    #[inline]
    fn penetrates(&self, index: usize, jump: &[f64; D], tolerance: f64) -> bool {
        let _ = index;
        jump[0] < -tolerance
    }

    /// A velocity-level scheme: how the adhesive springs of contact `index`'s law (accepted
    /// jump `start`) enter its reduced problem, [`VelocitySprings`]; the simulation then
    /// solves an adhesive step with the states frozen at the start of the step and updates
    /// them once from the step's jumps. `None` (the default, [`QuasiStatic`]): the
    /// displacement-level adhesion loop, where `x` is the jump itself.
    #[inline]
    fn velocity_springs(&self, index: usize, start: &[f64; D]) -> Option<VelocitySprings<D>> {
        let _ = (index, start);
        None
    }

    /// Told, just before [`accept`](Self::accept), what every contact of the accepted
    /// reduced problem did (the place for a scheme's energy bookkeeping). The default
    /// ignores it.
    #[inline]
    fn accept_contacts(&mut self, contacts: &[AcceptedContact<D>]) {
        let _ = contacts;
    }
}

/// How a velocity-level scheme takes a contact's adhesive springs (nodal stiffnesses
/// `A k(β)`, [`ContactLaw::adhesive_stiffness`](contact_laws::ContactLaw::adhesive_stiffness)
/// at the start state) into the reduced problem `x = W r + q`: the springs add
/// `r_adh = −scale · A k(β) (x + offset)` to the contact's unknown, which is condensed
/// exactly ([`crate::local::adhesion::condense`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct VelocitySprings<const D: usize> {
    /// The factor on the nodal springs: `h²θ²` for Moreau–Jean (an impulse `h r_adh` of the
    /// springs at `u_θ`, which is `hθ²` times `x` plus a known part).
    pub scale: f64,
    /// The offset `o` of `x` the springs act on.
    pub offset: [f64; D],
    /// Whether the contact's velocity is constrained by its law (Moreau's index set):
    /// `false` leaves only the springs acting (`r̄ = 0`).
    pub constrained: bool,
    /// Whether the states are iterated within the step to the end state (a fixed point, as
    /// the quasi-static loop: the springs are those of the end state), or frozen at the start
    /// state and updated once from the step's jumps (`false`).
    pub implicit: bool,
}

impl<const D: usize> VelocitySprings<D> {
    /// Springs `scale · A k(β)` acting on `x + offset`; `constrained` and `implicit` as the
    /// fields.
    pub fn new(scale: f64, offset: [f64; D], constrained: bool, implicit: bool) -> Self {
        Self {
            scale,
            offset,
            constrained,
            implicit,
        }
    }
}

/// One contact of an accepted step's reduced problem, as [`TimeScheme::accept_contacts`] is
/// told it: local vectors `[n, t…]` in the candidate's frame (signs: [`contact_laws`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct AcceptedContact<const D: usize> {
    /// The candidate's index.
    pub index: usize,
    /// The total reaction `r = r̄ + r_adh` (impulses for a velocity-level scheme).
    pub r: [f64; D],
    /// The law's part `r̄`.
    pub r_bar: [f64; D],
    /// The accepted jump `[gap, u_t…]` at the start of the step.
    pub start: [f64; D],
    /// The jump at the end of the step.
    pub jump: [f64; D],
    /// The nodal adhesive springs `A [k_n, k_t]` in the state at the start of the step.
    pub springs_start: [f64; 2],
    /// The same in the state at the end of the step.
    pub springs_end: [f64; 2],
}

/// Today's scheme: load steps, each an equilibrium `K u = f + Hᵀ r` at the step's force
/// factor and prescribed values ([`TimeScheme`]); time only orders the steps (and rates the
/// laws whose state evolves with it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuasiStatic;

impl<S: Structure<D> + ?Sized, const D: usize> TimeScheme<S, D> for QuasiStatic {
    /// `u_free = K⁻¹ f` at the step's force factor (prescribed displacements at their values),
    /// plus `R α` of the last step for a floating structure (`K⁺ f + R α`).
    fn free_response(
        &mut self,
        structure: &S,
        step: &SchemeStep<'_>,
        free: &mut [f64],
    ) -> Result<(), SolverError> {
        structure.free_response_into(step.force_factor, free)?;
        if let Some(floating) = structure.floating() {
            let modes = floating.rigid_body_modes();
            for (j, &a) in step.rigid_body_amplitudes.iter().enumerate() {
                if a != 0.0 {
                    for (u, r) in free.iter_mut().zip(modes.column(j)) {
                        *u += a * r;
                    }
                }
            }
        }
        Ok(())
    }

    #[inline]
    fn free_jump(
        &mut self,
        _index: usize,
        candidate: &Candidate<D>,
        u_rel: [f64; D],
        _start: &[f64; D],
    ) -> [f64; D] {
        candidate.local(u_rel)
    }

    #[inline]
    fn rhs(&self, _index: usize, free: &[f64; D], start: &[f64; D]) -> [f64; D] {
        core::array::from_fn(|d| if d == 0 { free[0] } else { free[d] - start[d] })
    }

    #[inline]
    fn displacement<'y>(&self, _step: &SchemeStep<'_>, solution: &'y [f64]) -> Cow<'y, [f64]> {
        Cow::Borrowed(solution)
    }

    #[inline]
    fn jump(&self, _index: usize, x: &[f64; D], start: &[f64; D]) -> [f64; D] {
        core::array::from_fn(|d| if d == 0 { x[0] } else { start[d] + x[d] })
    }

    #[inline]
    fn accept(
        &mut self,
        _structure: &S,
        _step: &SchemeStep<'_>,
        _solution: &[f64],
        _displacement: &[f64],
    ) {
    }
}
