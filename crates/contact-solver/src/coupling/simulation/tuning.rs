//! The tuning of a simulation: what [`SimulationSettings`](super::SimulationSettings) holds
//! beside the knobs a user sets, with defaults measured per dimension where they differ
//! ([`ContactSpace`]).

use crate::coupling::space::ContactSpace;
use crate::local::adhesion::{AdhesionMethod, DEFAULT_ANDERSON_WINDOW};
use fem_core::Dim;

/// The `with_*` builders: these settings with one field (a path under `self`) replaced.
macro_rules! with_fields {
    ($($(#[$doc:meta])* fn $name:ident($($field:ident).+: $ty:ty);)*) => {$(
        $(#[$doc])*
        #[must_use]
        pub fn $name(mut self, value: $ty) -> Self {
            self.$($field).+ = value;
            self
        }
    )*};
}
pub(crate) use with_fields;

/// The tuning of a simulation ([`SimulationSettings::tuning`](super::SimulationSettings::tuning)):
/// the adhesion loop's method and acceleration, the penetration check, the skip rules and the
/// floating bodies' equilibrium. Its defaults rarely need a change; the `with_*` methods of
/// [`SimulationSettings`](super::SimulationSettings) set each field too.
///
/// # Examples
/// ```
/// use contact_solver::{SimulationSettings, SimulationTuning};
/// let mut tuning = SimulationTuning::for_dimension::<2>();
/// tuning.max_detection_passes = 10;
/// let s = SimulationSettings::default().with_tuning(tuning);
/// assert_eq!(s.tuning.max_detection_passes, 10);
/// assert_eq!(SimulationTuning::default(), SimulationSettings::default().tuning);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct SimulationTuning {
    /// How adhesion and contact are solved together: the seed's fixed point or Newton with
    /// the states eliminated (the default); see [`AdhesionMethod`].
    pub adhesion_method: AdhesionMethod,
    /// Anderson window of the adhesion fixed point (`0`: the seed's plain fixed point); see
    /// [`AdhesionOptions::anderson_window`](crate::local::adhesion::AdhesionOptions::anderson_window).
    pub adhesion_anderson_window: usize,
    /// Newton adhesion: try Newton from the previous step's reactions before the loose start
    /// ([`AdhesionOptions::warm_start`](crate::local::adhesion::AdhesionOptions::warm_start)),
    /// paced by [`WarmStartPacing`](crate::local::adhesion::WarmStartPacing).
    pub adhesion_warm_start: bool,
    /// Maximum passes of the penetration check per step (each adds the penetrating inactive
    /// candidates and redoes the step): 5 in 2D, 20 in 3D ([`ContactSpace::MAX_DETECTION_PASSES`]).
    pub max_detection_passes: usize,
    /// An inactive candidate penetrates when its gap is below `−penetration_tol × extent`
    /// (`extent`: the largest side of the box of the contactor nodes). `None` (the default):
    /// the dimension's [`ContactSpace::PENETRATION_TOL`], 0 in 2D and `1e-9` in 3D (round-off
    /// of the nodes' positions on curved faces).
    pub penetration_tol: Option<f64>,
    /// What the simulation skips when a scene does not need it (all on by default; turn one
    /// off to measure what it saves).
    pub skip: SkipRules,
    /// Floating structures ([`Structure::floating`](fem_core::Structure::floating)):
    /// the equilibrium of each body along its modes is met when the out-of-balance force
    /// along every mode is at most this fraction of the forces involved (load plus the absolute
    /// contact contributions). Default `1e-11`.
    pub equilibrium_tol: f64,
    /// Matrix-free steps: the depth of the Anderson memory that accelerates the iteration
    /// ([`solve_matrix_free_anderson`](crate::local::matrix_free_anderson::solve_matrix_free_anderson)),
    /// or `0`: Nesterov momentum ([`solve_matrix_free`](crate::local::matrix_free::solve_matrix_free),
    /// the iteration of earlier versions). Default: the dimension's
    /// [`ContactSpace::MATRIX_FREE_WINDOW`], 20 in 2D and 3D (measured: 7–20× fewer products
    /// than the momentum in 2D, 1.6–16× in 3D, `docs/benchmarks.md`).
    pub matrix_free_window: usize,
    /// Floating structures: the cap on the Newton iterations on the rigid-body amplitudes
    /// (each one reduced solve, plus line-search trials). Default 50.
    pub max_equilibrium_iterations: usize,
}

impl Default for SimulationTuning {
    /// The tuning of a 2D simulation ([`SimulationTuning::for_dimension`]`::<2>()`).
    fn default() -> Self {
        Self::for_dimension::<2>()
    }
}

impl SimulationTuning {
    /// The default tuning of dimension `D` (the detection passes measured for it, the rest
    /// alike).
    pub fn for_dimension<const D: usize>() -> Self
    where
        Dim<D>: ContactSpace<D>,
    {
        Self {
            adhesion_method: AdhesionMethod::Newton,
            adhesion_anderson_window: DEFAULT_ANDERSON_WINDOW,
            adhesion_warm_start: true,
            max_detection_passes: <Dim<D> as ContactSpace<D>>::MAX_DETECTION_PASSES,
            penetration_tol: None,
            skip: SkipRules::default(),
            equilibrium_tol: 1e-11,
            max_equilibrium_iterations: 50,
            matrix_free_window: <Dim<D> as ContactSpace<D>>::MATRIX_FREE_WINDOW,
        }
    }
}

/// "Skip what a scene does not need": each rule is on by default and only exists as a switch
/// so that its saving can be measured (`docs/benchmarks.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
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

impl SkipRules {
    /// Every rule off: the simulation does all the work a scene could need (to measure what
    /// the rules save).
    pub const fn none() -> Self {
        Self {
            reuse_flexibility: false,
            alert_distance: false,
            frictionless_normal_only: false,
            adhesion_loop_only_when_adhesive: false,
        }
    }

    with_fields! {
        /// These settings with [`reuse_flexibility`](Self::reuse_flexibility) replaced.
        fn with_reuse_flexibility(reuse_flexibility: bool);
        /// These settings with [`alert_distance`](Self::alert_distance) replaced.
        fn with_alert_distance(alert_distance: bool);
        /// These settings with [`frictionless_normal_only`](Self::frictionless_normal_only) replaced.
        fn with_frictionless_normal_only(frictionless_normal_only: bool);
        /// These settings with [`adhesion_loop_only_when_adhesive`](Self::adhesion_loop_only_when_adhesive) replaced.
        fn with_adhesion_loop_only_when_adhesive(adhesion_loop_only_when_adhesive: bool);
    }
}
