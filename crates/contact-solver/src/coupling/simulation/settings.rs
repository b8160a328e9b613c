//! Settings of a simulation: the reduced solver, the adhesion loop, the flexibility path and the
//! skip rules.

use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use crate::local::UzawaSettings;
use fem_core::Dim;

/// Settings of a simulation.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
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
    /// How adhesion and contact are solved together: the seed's fixed point or Newton with
    /// the states eliminated (the default); see
    /// [`AdhesionMethod`](crate::local::adhesion::AdhesionMethod).
    pub adhesion_method: crate::local::adhesion::AdhesionMethod,
    /// Newton adhesion: try Newton from the previous step's reactions before the loose start
    /// ([`AdhesionOptions::warm_start`](crate::local::adhesion::AdhesionOptions::warm_start)),
    /// paced by [`WarmStartPacing`](crate::local::adhesion::WarmStartPacing).
    pub adhesion_warm_start: bool,
    /// Maximum passes of the penetration check per step (each adds the penetrating inactive
    /// candidates and redoes the step): 5 in 2D, 20 in 3D
    /// ([`for_dimension`](Self::for_dimension)).
    pub max_detection_passes: usize,
    /// An inactive candidate penetrates when its gap is below `−penetration_tol × extent`
    /// (`extent`: the largest side of the box of the contactor nodes). `None` (the default):
    /// the dimension's [`ContactSpace::PENETRATION_TOL`], 0 in 2D and `1e-9` in 3D (round-off
    /// of the nodes' positions on curved faces).
    pub penetration_tol: Option<f64>,
    /// Right-hand sides per `solve_many_in_place` call when building `F*` (bounds the memory
    /// to `dof_count × columns` values): 64 in 2D, 96 in 3D
    /// ([`for_dimension`](Self::for_dimension)).
    pub columns_per_solve: usize,
    /// What the simulation skips when a scene does not need it (all on by default; turn one
    /// off to measure what it saves).
    pub skip: SkipRules,
    /// Dense `F*` or the matrix-free iteration ([`crate::local::matrix_free`]).
    pub flexibility: FlexibilityMode,
    /// Floating structures ([`Structure::floating`](fem_core::Structure::floating)):
    /// the equilibrium of each body along its modes is met when the out-of-balance force
    /// along every mode is at most this fraction of the forces involved (load plus the absolute
    /// contact contributions). Default `1e-11`.
    pub equilibrium_tol: f64,
    /// Floating structures: the cap on the Newton iterations on the rigid-body amplitudes
    /// (each one reduced solve, plus line-search trials). Default 50.
    pub max_equilibrium_iterations: usize,
}

/// How the reduced problem is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum FlexibilityMode {
    /// Dense `F*` up to `dense_limit` active contacts; beyond, the primal active-set solve
    /// when the step is in its scope ([`crate::coupling::primal`]: rigid obstacles, node pairs
    /// and node-to-segment with every component of the contactors free, no active adhesion, a
    /// structure that exposes its stiffness), else matrix-free (when no active law is adhesive:
    /// the exact condensation of the springs needs the dense `F*`). A step whose active-set
    /// iteration does not converge is solved again with a dense `F*` (up to 8000 contacts in 2D,
    /// 3000 in 3D: `ContactSpace::FALLBACK_DENSE_LIMIT`) or
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

impl Default for SimulationSettings {
    /// The settings of a 2D simulation ([`SimulationSettings::for_dimension`]`::<2>()`).
    fn default() -> Self {
        Self::for_dimension::<2>()
    }
}

impl SimulationSettings {
    /// The default settings of dimension `D`: the defaults measured for that dimension
    /// ([`ContactSpace`]) of the `Auto` dense limit (500 contacts in 2D, 3000 in 3D), the
    /// right-hand sides per solve (64, 96) and the detection passes (5, 20); the rest alike.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::{FlexibilityMode, SimulationSettings};
    /// let s = SimulationSettings::for_dimension::<3>();
    /// assert_eq!(s.flexibility, FlexibilityMode::Auto { dense_limit: 3000 });
    /// assert_eq!(SimulationSettings::for_dimension::<2>(), SimulationSettings::default());
    /// ```
    pub fn for_dimension<const D: usize>() -> Self
    where
        Dim<D>: ContactSpace<D>,
    {
        Self {
            solver: UzawaSettings::default(),
            adhesion_tol: 1e-8,
            max_adhesion_iterations: 200,
            adhesion_anderson_window: crate::local::adhesion::DEFAULT_ANDERSON_WINDOW,
            adhesion_method: crate::local::adhesion::AdhesionMethod::Newton,
            adhesion_warm_start: true,
            max_detection_passes: <Dim<D> as ContactSpace<D>>::MAX_DETECTION_PASSES,
            penetration_tol: None,
            columns_per_solve: <Dim<D> as ContactSpace<D>>::COLUMNS_PER_SOLVE,
            skip: SkipRules::default(),
            flexibility: FlexibilityMode::Auto {
                dense_limit: <Dim<D> as ContactSpace<D>>::DENSE_LIMIT,
            },
            equilibrium_tol: 1e-11,
            max_equilibrium_iterations: 50,
        }
    }

    /// The checks of [`ContactSimulation::new`](crate::ContactSimulation::new) and
    /// [`set_settings`](crate::ContactSimulation::set_settings).
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] naming the setting: an `adhesion_tol` that is not
    /// finite and positive, a zero `columns_per_solve` or `max_detection_passes`, a
    /// `penetration_tol` that is not finite and non-negative.
    pub(crate) fn check(&self) -> Result<(), SolverError> {
        if !(self.adhesion_tol > 0.0 && self.adhesion_tol.is_finite()) {
            return Err(SolverError::InvalidSetting {
                what: "adhesion_tol",
                value: self.adhesion_tol,
                expected: "a finite tolerance > 0",
            });
        }
        for (what, n) in [
            ("columns_per_solve", self.columns_per_solve),
            ("max_detection_passes", self.max_detection_passes),
        ] {
            if n == 0 {
                return Err(SolverError::InvalidSetting {
                    what,
                    value: 0.0,
                    expected: "at least 1",
                });
            }
        }
        if let Some(tol) = self.penetration_tol
            && !(tol >= 0.0 && tol.is_finite())
        {
            return Err(SolverError::InvalidSetting {
                what: "penetration_tol",
                value: tol,
                expected: "a finite tolerance >= 0",
            });
        }
        Ok(())
    }

    /// The relative penetration tolerance in dimension `D`: [`Self::penetration_tol`] or the
    /// dimension's default.
    pub(crate) fn relative_penetration_tol<const D: usize>(&self) -> f64
    where
        Dim<D>: ContactSpace<D>,
    {
        self.penetration_tol
            .unwrap_or(<Dim<D> as ContactSpace<D>>::PENETRATION_TOL)
    }

    /// These settings with [`solver`](Self::solver) replaced.
    #[must_use]
    pub fn with_solver(mut self, solver: UzawaSettings) -> Self {
        self.solver = solver;
        self
    }

    /// These settings with [`adhesion_tol`](Self::adhesion_tol) replaced.
    #[must_use]
    pub fn with_adhesion_tol(mut self, adhesion_tol: f64) -> Self {
        self.adhesion_tol = adhesion_tol;
        self
    }

    /// These settings with [`max_adhesion_iterations`](Self::max_adhesion_iterations) replaced.
    #[must_use]
    pub fn with_max_adhesion_iterations(mut self, max_adhesion_iterations: usize) -> Self {
        self.max_adhesion_iterations = max_adhesion_iterations;
        self
    }

    /// These settings with [`adhesion_anderson_window`](Self::adhesion_anderson_window) replaced.
    #[must_use]
    pub fn with_adhesion_anderson_window(mut self, adhesion_anderson_window: usize) -> Self {
        self.adhesion_anderson_window = adhesion_anderson_window;
        self
    }

    /// These settings with [`adhesion_warm_start`](Self::adhesion_warm_start) replaced.
    #[must_use]
    pub fn with_adhesion_warm_start(mut self, warm_start: bool) -> Self {
        self.adhesion_warm_start = warm_start;
        self
    }

    /// These settings with [`adhesion_method`](Self::adhesion_method) replaced.
    #[must_use]
    pub fn with_adhesion_method(
        mut self,
        adhesion_method: crate::local::adhesion::AdhesionMethod,
    ) -> Self {
        self.adhesion_method = adhesion_method;
        self
    }

    /// These settings with [`max_detection_passes`](Self::max_detection_passes) replaced.
    #[must_use]
    pub fn with_max_detection_passes(mut self, max_detection_passes: usize) -> Self {
        self.max_detection_passes = max_detection_passes;
        self
    }

    /// These settings with [`penetration_tol`](Self::penetration_tol) set to `relative`.
    #[must_use]
    pub fn with_penetration_tol(mut self, relative: f64) -> Self {
        self.penetration_tol = Some(relative);
        self
    }

    /// These settings with [`columns_per_solve`](Self::columns_per_solve) replaced.
    #[must_use]
    pub fn with_columns_per_solve(mut self, columns_per_solve: usize) -> Self {
        self.columns_per_solve = columns_per_solve;
        self
    }

    /// These settings with [`equilibrium_tol`](Self::equilibrium_tol) replaced.
    #[must_use]
    pub fn with_equilibrium_tol(mut self, equilibrium_tol: f64) -> Self {
        self.equilibrium_tol = equilibrium_tol;
        self
    }

    /// These settings with [`max_equilibrium_iterations`](Self::max_equilibrium_iterations)
    /// replaced.
    #[must_use]
    pub fn with_max_equilibrium_iterations(mut self, max_equilibrium_iterations: usize) -> Self {
        self.max_equilibrium_iterations = max_equilibrium_iterations;
        self
    }

    /// These settings with [`skip`](Self::skip) replaced.
    #[must_use]
    pub fn with_skip(mut self, skip: SkipRules) -> Self {
        self.skip = skip;
        self
    }

    /// These settings with [`flexibility`](Self::flexibility) replaced.
    #[must_use]
    pub fn with_flexibility(mut self, flexibility: FlexibilityMode) -> Self {
        self.flexibility = flexibility;
        self
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

    /// These settings with [`reuse_flexibility`](Self::reuse_flexibility) replaced.
    #[must_use]
    pub fn with_reuse_flexibility(mut self, reuse_flexibility: bool) -> Self {
        self.reuse_flexibility = reuse_flexibility;
        self
    }

    /// These settings with [`alert_distance`](Self::alert_distance) replaced.
    #[must_use]
    pub fn with_alert_distance(mut self, alert_distance: bool) -> Self {
        self.alert_distance = alert_distance;
        self
    }

    /// These settings with [`frictionless_normal_only`](Self::frictionless_normal_only) replaced.
    #[must_use]
    pub fn with_frictionless_normal_only(mut self, frictionless_normal_only: bool) -> Self {
        self.frictionless_normal_only = frictionless_normal_only;
        self
    }

    /// These settings with [`adhesion_loop_only_when_adhesive`](Self::adhesion_loop_only_when_adhesive) replaced.
    #[must_use]
    pub fn with_adhesion_loop_only_when_adhesive(
        mut self,
        adhesion_loop_only_when_adhesive: bool,
    ) -> Self {
        self.adhesion_loop_only_when_adhesive = adhesion_loop_only_when_adhesive;
        self
    }
}
