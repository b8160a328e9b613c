//! Settings of a simulation: the reduced solver, the adhesion loop, the flexibility path and the
//! skip rules.

use crate::local::UzawaSettings;

/// Settings of a simulation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimulationSettings {
    /// The reduced solver (algorithm, tolerance, ρ scale, …).
    pub solver: UzawaSettings,
    /// Tolerance of the adhesion fixed point: largest [`ContactLaw::state_change`](contact_laws::ContactLaw::state_change) (for RCCM,
    /// `|Δβ|`) between two iterations.
    pub adhesion_tol: f64,
    /// Maximum adhesion fixed-point iterations per step.
    pub max_adhesion_iterations: usize,
    /// Anderson window of the adhesion fixed point (`0`: the seed's plain fixed point); see
    /// [`AdhesionOptions::anderson_window`](crate::local::adhesion::AdhesionOptions::anderson_window).
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
    /// Dense `F*` or the matrix-free iteration ([`crate::local::matrix_free`]).
    pub flexibility: FlexibilityMode,
}

/// How the reduced problem is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FlexibilityMode {
    /// Dense `F*` up to `dense_limit` active contacts; beyond, the primal active-set solve
    /// when the step is in its scope ([`crate::coupling::primal`]: rigid obstacles, no active adhesion, a
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
    /// ([`crate::coupling::primal`]). Steps outside its scope are refused with the reason.
    ActiveSet,
}

/// Largest active set that `Auto` solves with a dense `F*` when its active-set iteration did
/// not converge (a dense `F*` of 8000 contacts takes 2 GiB); matrix-free beyond.
pub(super) const FALLBACK_DENSE_LIMIT: usize = 8000;

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
            adhesion_anderson_window: crate::local::adhesion::DEFAULT_ANDERSON_WINDOW,
            max_detection_passes: 5,
            columns_per_solve: 64,
            skip: SkipRules::default(),
            flexibility: FlexibilityMode::default(),
        }
    }
}
