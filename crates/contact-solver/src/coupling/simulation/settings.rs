//! Settings of a simulation: the knobs a user sets (the reduced solver, the adhesion loop's
//! tolerance and limit, the flexibility path, the right-hand sides per solve) and the
//! [`SimulationTuning`] beside them.

use super::tuning::{SimulationTuning, SkipRules, with_fields};
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use crate::local::UzawaSettings;
use fem_core::Dim;

/// Settings of a simulation: the knobs a user sets (the reduced solver's algorithm, tolerance
/// and iteration limit in [`solver`](Self::solver), the adhesion loop's tolerance and
/// iteration limit, how the reduced problem is held, the right-hand sides per solve), and the
/// rest in [`tuning`](Self::tuning) ([`SimulationTuning`]), whose defaults rarely need a
/// change. Build it with [`Default`] (2D) or [`for_dimension`](Self::for_dimension) and the
/// `with_*` methods.
///
/// # Examples
/// ```
/// use contact_solver::{FlexibilityMode, SimulationSettings};
/// let s = SimulationSettings::for_dimension::<3>()
///     .with_flexibility(FlexibilityMode::ActiveSet)
///     .with_max_detection_passes(8); // a tuning knob, through the same builder
/// assert_eq!(s.tuning.max_detection_passes, 8);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct SimulationSettings {
    /// The reduced solver (algorithm, tolerance, iteration limit, acceptance of non-converged
    /// results; its own tuning inside).
    pub solver: UzawaSettings,
    /// Tolerance of the adhesion loop: largest [`ContactLaw::state_change`](contact_laws::ContactLaw::state_change)
    /// (for RCCM, `|Δβ|`) between two iterations.
    pub adhesion_tol: f64,
    /// Maximum adhesion iterations per step.
    pub max_adhesion_iterations: usize,
    /// How the reduced problem is held: a dense `F*`, matrix-free, the primal active set, or
    /// `Auto` (the default) choosing by the size of the active set.
    pub flexibility: FlexibilityMode,
    /// Right-hand sides per `solve_many_in_place` call when building `F*` (bounds the memory
    /// to `dof_count × columns` values): 64 in 2D, 96 in 3D
    /// ([`for_dimension`](Self::for_dimension)).
    pub columns_per_solve: usize,
    /// What rarely needs a change: the adhesion loop's method and acceleration, the detection
    /// passes and penetration tolerance, the skip rules, the floating bodies' equilibrium.
    pub tuning: SimulationTuning,
}

/// How the reduced problem is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
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
            flexibility: FlexibilityMode::Auto {
                dense_limit: <Dim<D> as ContactSpace<D>>::DENSE_LIMIT,
            },
            columns_per_solve: <Dim<D> as ContactSpace<D>>::COLUMNS_PER_SOLVE,
            tuning: SimulationTuning::for_dimension::<D>(),
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
            ("max_detection_passes", self.tuning.max_detection_passes),
        ] {
            if n == 0 {
                return Err(SolverError::InvalidSetting {
                    what,
                    value: 0.0,
                    expected: "at least 1",
                });
            }
        }
        if let Some(tol) = self.tuning.penetration_tol
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

    /// The relative penetration tolerance in dimension `D`:
    /// [`SimulationTuning::penetration_tol`] or the dimension's default.
    pub(crate) fn relative_penetration_tol<const D: usize>(&self) -> f64
    where
        Dim<D>: ContactSpace<D>,
    {
        self.tuning
            .penetration_tol
            .unwrap_or(<Dim<D> as ContactSpace<D>>::PENETRATION_TOL)
    }

    /// These settings with [`tuning.penetration_tol`](SimulationTuning::penetration_tol) set to
    /// `relative`.
    #[must_use]
    pub fn with_penetration_tol(mut self, relative: f64) -> Self {
        self.tuning.penetration_tol = Some(relative);
        self
    }

    with_fields! {
        /// These settings with [`solver`](Self::solver) replaced.
        fn with_solver(solver: UzawaSettings);
        /// These settings with [`adhesion_tol`](Self::adhesion_tol) replaced.
        fn with_adhesion_tol(adhesion_tol: f64);
        /// These settings with [`max_adhesion_iterations`](Self::max_adhesion_iterations) replaced.
        fn with_max_adhesion_iterations(max_adhesion_iterations: usize);
        /// These settings with [`tuning.adhesion_anderson_window`](SimulationTuning::adhesion_anderson_window) replaced.
        fn with_adhesion_anderson_window(tuning.adhesion_anderson_window: usize);
        /// These settings with [`tuning.matrix_free_window`](SimulationTuning::matrix_free_window) replaced.
        fn with_matrix_free_window(tuning.matrix_free_window: usize);
        /// These settings with [`tuning.adhesion_warm_start`](SimulationTuning::adhesion_warm_start) replaced.
        fn with_adhesion_warm_start(tuning.adhesion_warm_start: bool);
        /// These settings with [`tuning.adhesion_method`](SimulationTuning::adhesion_method) replaced.
        fn with_adhesion_method(tuning.adhesion_method: crate::local::adhesion::AdhesionMethod);
        /// These settings with [`tuning.max_detection_passes`](SimulationTuning::max_detection_passes) replaced.
        fn with_max_detection_passes(tuning.max_detection_passes: usize);
        /// These settings with [`columns_per_solve`](Self::columns_per_solve) replaced.
        fn with_columns_per_solve(columns_per_solve: usize);
        /// These settings with [`tuning.equilibrium_tol`](SimulationTuning::equilibrium_tol) replaced.
        fn with_equilibrium_tol(tuning.equilibrium_tol: f64);
        /// These settings with [`tuning.max_equilibrium_iterations`](SimulationTuning::max_equilibrium_iterations) replaced.
        fn with_max_equilibrium_iterations(tuning.max_equilibrium_iterations: usize);
        /// These settings with [`tuning.skip`](SimulationTuning::skip) replaced.
        fn with_skip(tuning.skip: SkipRules);
        /// These settings with [`tuning`](Self::tuning) replaced.
        fn with_tuning(tuning: SimulationTuning);
        /// These settings with [`flexibility`](Self::flexibility) replaced.
        fn with_flexibility(flexibility: FlexibilityMode);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn issue_35_for_dimension_keeps_each_dimensions_defaults() {
        // the values the 2D settings and the former 3D `SolidSettings` had
        let plane = SimulationSettings::default();
        assert_eq!(plane, SimulationSettings::for_dimension::<2>());
        assert_eq!(
            plane.flexibility,
            FlexibilityMode::Auto { dense_limit: 500 }
        );
        assert_eq!(
            (plane.columns_per_solve, plane.tuning.max_detection_passes),
            (64, 5)
        );
        assert_eq!(plane.relative_penetration_tol::<2>(), 0.0);
        let solid = SimulationSettings::for_dimension::<3>();
        assert_eq!(
            solid.flexibility,
            FlexibilityMode::Auto { dense_limit: 3000 }
        );
        assert_eq!(
            (solid.columns_per_solve, solid.tuning.max_detection_passes),
            (96, 20)
        );
        assert_eq!(solid.relative_penetration_tol::<3>(), 1e-9);
        // the rest alike
        assert_eq!(solid.solver, plane.solver);
        assert_eq!(solid.tuning.skip, plane.tuning.skip);
        assert_eq!(
            (solid.adhesion_tol, solid.max_adhesion_iterations),
            (plane.adhesion_tol, plane.max_adhesion_iterations)
        );
        // a tolerance given holds in both dimensions
        let given = plane.with_penetration_tol(1e-6);
        assert_eq!(given.relative_penetration_tol::<2>(), 1e-6);
        assert_eq!(given.relative_penetration_tol::<3>(), 1e-6);
    }

    #[test]
    fn check_rejects_each_bad_setting_by_name() {
        let ok = SimulationSettings::default();
        assert_eq!(ok.check(), Ok(()));
        let bad = [
            ("adhesion_tol", ok.with_adhesion_tol(f64::NAN)),
            ("adhesion_tol", ok.with_adhesion_tol(0.0)),
            ("columns_per_solve", ok.with_columns_per_solve(0)),
            ("max_detection_passes", ok.with_max_detection_passes(0)),
            ("penetration_tol", ok.with_penetration_tol(-1e-9)),
            ("penetration_tol", ok.with_penetration_tol(f64::INFINITY)),
        ];
        for (name, s) in bad {
            match s.check() {
                Err(SolverError::InvalidSetting { what, .. }) => assert_eq!(what, name),
                other => panic!("{name}: {other:?}"),
            }
        }
        // 0 is 2D's own tolerance
        assert_eq!(ok.with_penetration_tol(0.0).check(), Ok(()));
    }

    #[test]
    fn builders_set_the_tuning_fields() {
        let s = SimulationSettings::default()
            .with_adhesion_anderson_window(3)
            .with_adhesion_warm_start(false)
            .with_adhesion_method(crate::local::adhesion::AdhesionMethod::FixedPoint)
            .with_max_detection_passes(7)
            .with_equilibrium_tol(1e-9)
            .with_max_equilibrium_iterations(9)
            .with_skip(SkipRules::none());
        let t = s.tuning;
        assert_eq!(t.adhesion_anderson_window, 3);
        assert!(!t.adhesion_warm_start);
        assert_eq!(
            t.adhesion_method,
            crate::local::adhesion::AdhesionMethod::FixedPoint
        );
        assert_eq!(
            (t.max_detection_passes, t.max_equilibrium_iterations),
            (7, 9)
        );
        assert_eq!(t.equilibrium_tol, 1e-9);
        assert_eq!(t.skip, SkipRules::none());
        assert_eq!(SimulationSettings::default().with_tuning(t).tuning, t);
    }
}
