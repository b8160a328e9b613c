//! Settings, report and solution of the reduced-problem solvers, shared by every algorithm
//! (the stopping rule and the penalty ρ are described in the [layer docs](crate::local)).

use super::stall::DEFAULT_STALL_WINDOW;
use contact_laws::ContactStatus;

/// Threshold ν of the self-adaptive rule: a step whose ratio exceeds it is redone with ρ/2.
pub(crate) const ADAPT_SHRINK_ABOVE: f64 = 1.5;
/// A step whose ratio is below this grows ρ by `ADAPT_GROWTH` for the next step.
pub(crate) const ADAPT_GROW_BELOW: f64 = 0.3;
/// Growth factor of ρ after an easy step.
pub(crate) const ADAPT_GROWTH: f64 = 1.5;

/// Default over-relaxation factor of the classical solver's projected SOR sweeps (plain
/// Gauss–Seidel; see [`classic`](crate::local::classic)).
pub(crate) const DEFAULT_OMEGA: f64 = 1.0;

/// Which sweep the solver runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub enum Algorithm {
    /// Every contact from the same `x`, then `x = W r + q` (Jacobi / projected gradient).
    Uzawa,
    /// Contact by contact with the current `x` (projected Gauss–Seidel).
    GaussSeidel,
    /// The classical solver (seed §5.6, GYPTIS): contact and friction treated separately, by
    /// projected SOR sweeps on the normal then the tangential components, with a fixed point
    /// on the threshold `s_i = μ̄_i r_n,i`. Needs
    /// [`ContactLaw::friction_coefficient`](contact_laws::ContactLaw::friction_coefficient); see [`classic`](crate::local::classic).
    ClassicRccm,
    /// Anderson acceleration (memory 5, safeguarded) of the projected Gauss–Seidel sweep; see
    /// [`anderson`](crate::local::anderson).
    /// The default (chosen by measurement, see the [module docs](crate::local#which-algorithm)).
    #[default]
    AndersonGaussSeidel,
    /// Anderson acceleration (safeguarded) of the Uzawa step; see
    /// [`anderson`](crate::local::anderson).
    AndersonUzawa,
    /// Semi-smooth Newton on `r − P_K(r + ρ v(W r + q)) = 0` with an LU of the reduced
    /// Newton system (dense, or faer's sparse LU on a sparse `W`), a line search and
    /// Gauss–Seidel fallback. Needs
    /// [`ContactLaw::friction_coefficient`](contact_laws::ContactLaw::friction_coefficient); see [`newton`](crate::local::newton).
    Newton,
    /// Chosen per problem by the measured rule of the [layer docs](crate::local#which-algorithm):
    /// [`Newton`](Self::Newton) when every law has a friction coefficient and, for a dense `W`,
    /// there are at most 1000 contacts and fewer than half of its off-diagonal blocks are zero
    /// (not a multibody Delassus operator), for a sparse `W` at most 20 000 contacts whose
    /// graph fills a factorisation by at most 10 (`nnz(L)/nnz(tril)`); else
    /// [`AndersonGaussSeidel`](Self::AndersonGaussSeidel). A Newton chosen so that creeps
    /// (a second Armijo step of at most 2⁻⁵ after its first, or 100 iterations without
    /// converging) hands over to
    /// [`AndersonGaussSeidel`](Self::AndersonGaussSeidel) from the start (with or without
    /// [`fallback`](UzawaSettings::fallback); the report's
    /// [`fallback_from`](UzawaReport::fallback_from) says it happened).
    /// The report names the one that ran; it names `Auto` itself (one iteration) when a
    /// one-contact problem was solved exactly by its case (open, stick or slip) without
    /// iterating.
    Auto,
}

impl Algorithm {
    /// The variant's name (`"AndersonGaussSeidel"`), as errors carry it.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(contact_solver::Algorithm::Newton.name(), "Newton");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Self::Uzawa => "Uzawa",
            Self::GaussSeidel => "GaussSeidel",
            Self::ClassicRccm => "ClassicRccm",
            Self::AndersonGaussSeidel => "AndersonGaussSeidel",
            Self::AndersonUzawa => "AndersonUzawa",
            Self::Newton => "Newton",
            Self::Auto => "Auto",
        }
    }
}

/// [`Algorithm::Auto`] picks Newton up to this many contacts: Newton is the fastest on every
/// FE problem measured and on random problems up to `n_c` ≈ 1000, beyond which its dense
/// factorisation (`n_c³`) loses to the accelerated sweep (4–5× slower at `n_c` = 5000,
/// `docs/benchmarks.md`, "Local solver: work–precision").
pub(crate) const AUTO_NEWTON_MAX_CONTACTS: usize = 1000;

/// [`Algorithm::Auto`] on a sparse `W` picks Newton (faer's sparse LU) when the contact graph
/// (a node per contact, an edge per stored block) fills its symbolic Cholesky factor by at
/// most this ratio `nnz(L)/nnz(tril)`. Measured (`examples/auto_rule.rs`, `docs/benchmarks.md`
/// "Which algorithm, measured"): shaken sphere piles fill 3.3 (425 contacts) and 4.7 (805),
/// and Newton is 1.3–1.9× faster than the accelerated sweep there; random block-sparse
/// problems fill 27 (1000 contacts), 47 (2D, 2000) and 87 (4000), and Newton is 3–20× slower.
pub(crate) const AUTO_NEWTON_MAX_FILL: f64 = 10.0;

/// [`Algorithm::Auto`] probes the fill of a sparse `W` (an AMD ordering and a symbolic
/// factorisation of the contact graph: 0.3–1.2 ms at 425–1000 contacts, 24 ms at 4000) only up
/// to this many contacts; beyond, it picks the accelerated sweep.
pub(crate) const AUTO_SPARSE_NEWTON_MAX_CONTACTS: usize = 20_000;

/// [`Algorithm::Auto`] solves a dense symmetric `W` stored sparse (and never runs the dense
/// Newton on it) when at least this fraction of its off-diagonal blocks is exactly zero: a
/// multibody Delassus operator `H M⁻¹ Hᵀ` (two contacts couple only through a body they
/// share); a condensed finite-element `F*` has none. Measured (`examples/auto_rule.rs`,
/// `docs/benchmarks.md` "Auto on multibody problems"): shaken sphere piles and towers have
/// 97.6–98.7 % zero blocks, and there every algorithm is faster on the sparse storage (the
/// sweep 2–4×, Newton 4–20×) while the dense Newton may not converge at all (a semi-definite
/// `W`: Armijo steps that shrink for thousands of iterations); the FE and random problems of
/// the table have none.
pub(crate) const AUTO_MULTIBODY_ZERO_BLOCKS: f64 = 0.5;

/// The iterations (sweeps and Newton steps) a Newton chosen by [`Algorithm::Auto`] may take
/// before the accelerated sweep takes over from the start, whatever its steps look like
/// (the probe, `AUTO_NEWTON_SHORT_STEPS`, usually decides sooner). Measured: Newton converges
/// in 7–9 iterations on the FE problems of `docs/benchmarks.md`, in 11–16 on the sphere piles
/// where it wins and in 53 on a tower of 50 spheres (where it is still 1.9× faster than the
/// sweep, with steps `t ≥ 2⁻⁴`); 100 is about twice the longest converging run.
pub(crate) const AUTO_NEWTON_BUDGET: usize = 100;

/// The iterations a Newton chosen by [`Algorithm::Auto`] may take where it runs without the
/// probe (a dense `W` kept non-symmetric, issue 37) before the accelerated sweep takes over
/// from Newton's iterate. Measured on Siconos' dense non-symmetric problems
/// (`docs/benchmarks.md`, "Auto over Siconos' whole collection", sixth part): Newton converges
/// in 7–18 iterations on the rovers and on `OneObject-i1028-138` / `-316`; on
/// `OneObject-i100000-499` it needs 95 (1.5× the sweep's time), and after 30 (about twice
/// the longest fast run) the sweep finishes from Newton's iterate in 380 sweeps (1 133 from
/// the start).
pub(crate) const AUTO_NEWTON_UNPROBED_BUDGET: usize = 30;

/// A Newton step of [`Algorithm::Auto`]'s probe accepted with a step length at most this
/// (five halvings or more of the Armijo line search) is *short*. Measured (the residual and
/// the step of every Newton iteration on the rows of `docs/benchmarks.md` "Auto on multibody
/// problems"): after the first Newton step (which may need up to 16 halvings on a tower,
/// starting from the warm-up sweeps' active set), every run that converges takes steps
/// `t ≥ 2⁻⁴` (FE and random problems `t ≥ 2⁻²`), while the loose piles, where Newton creeps
/// for thousands of iterations, take `t ≤ 2⁻⁶` on most steps from their 4th–6th on.
pub(crate) const AUTO_NEWTON_SHORT_STEP: f64 = 1.0 / 32.0;

/// Short steps (`AUTO_NEWTON_SHORT_STEP`, or a failed line search) after its first step
/// after which a Newton chosen by [`Algorithm::Auto`] gives up and the accelerated sweep takes
/// over: two, so that one odd step does not decide (the loose piles give their second at
/// iteration 8–10, none of the converging runs gives one).
pub(crate) const AUTO_NEWTON_SHORT_STEPS: usize = 2;

/// The iterations over which a Newton chosen by [`Algorithm::Auto`] on a sparse `W` kept
/// non-symmetric must halve its residual, or give up (its progress probe, `newton/probe.rs`).
/// Measured on Siconos' capsules (`docs/benchmarks.md`, "Auto on large multibody problems"):
/// the converging runs halve it at least every 9 iterations (29–40 in all), the plateaus last
/// hundreds (`Capsules-i101-404`, `-i122-1617`); 20, about twice the longest halving.
pub(crate) const AUTO_NEWTON_PROGRESS_WINDOW: usize = 20;

/// Sweeps of the accelerated Gauss–Seidel that [`Algorithm::Auto`] runs first on a dense `W`
/// where it would pick Newton (issue 37, "sweep first"), to read the sweep's rate before
/// choosing: 8, a third of what the random dense problems need in all (21–26) and an eighth
/// of the FE problems' (54–74), whose Newton it delays.
pub(crate) const AUTO_SWEEP_PROBE: usize = 8;

/// The fraction of pressed contacts (`q_n < 0`) from which [`Algorithm::Auto`] sweeps first
/// on a dense `W`: Newton's step works on the closed contacts, so it is cheap beside a sweep
/// over the whole `W` when few are pressed (the 3D half-space under a sphere: Newton 2.7 ms
/// against the sweep's 23.6, `docs/benchmarks.md` "Sweep first") and costs a factorisation of
/// most of `W` when most are (random dense problems: 2/3 pressed, Newton 2–4× slower).
pub(crate) const AUTO_SWEEP_MIN_PRESSED: f64 = 0.5;

/// The sweeps (probe included) within which the probe's rate must promise the tolerance for
/// [`Algorithm::Auto`] to keep sweeping rather than run Newton: the sweep costs `O(m²)` a
/// sweep and Newton `O(m³)` an iteration on a dense `W`, and measured (`docs/benchmarks.md`,
/// "Sweep first") the sweep wins where it needs at most about 30 sweeps (random dense
/// problems: 21–26) and loses where it needs 54–74 (FE problems).
pub(crate) const AUTO_SWEEP_PREDICTED: f64 = 40.0;

/// Contacts up to which [`Algorithm::Auto`] runs the classical solver first on a sparse
/// symmetric `W` (issue 37, seventh part; `docs/benchmarks.md`, "Auto on small problems"):
/// on Siconos' small sparse problems (3–107 contacts) the classical solver was the fastest of
/// ours on 9 of 11 and Newton 1.4–4.4× slower; above (granular flows of 367–376 contacts) the
/// sweeps win.
pub(crate) const AUTO_CLASSIC_MAX_CONTACTS: usize = 128;

/// Sweeps of that first classical run: `k² / AUTO_CLASSIC_ENTRIES_SQUARED_PER_SWEEP` for `k`
/// stored entries in an average row of `W`, at least `AUTO_CLASSIC_MIN_SWEEPS` and at most
/// `AUTO_CLASSIC_PROBE`. A sweep costs `k` a row; Newton's elimination about `k²` a row (a
/// front of `k` rows), so the sweeps that a Newton step buys grow with `k`, and its steps with
/// the coupling. Fitted on Siconos' small sparse problems (`docs/benchmarks.md`, "Auto on
/// small problems"): the classical solver wins where it needs 5–6 sweeps (1–10 entries a
/// row) and on `Confeti-ex13-Fc3D-SBM` (172 sweeps, `k` = 56: 196 allowed); Newton wins on
/// `Confeti-ex03-Fc3D-SBM` (1 549 sweeps, `k` = 7.9) and `NESpheres_10_1` (187, `k` = 3.7),
/// where the first run stops after 16 sweeps; on the small semidefinite sphere piles of
/// `tests/integration/issue_37_semidefinite.rs` (Newton creeps, the sweep wins) it must cost
/// at most a few sweeps more than Newton's probe.
pub(crate) const AUTO_CLASSIC_PROBE: usize = 200;

/// See `AUTO_CLASSIC_PROBE`: 16, above the 6 sweeps (2 outer iterations) of the weakly
/// coupled problems.
pub(crate) const AUTO_CLASSIC_MIN_SWEEPS: usize = 16;

/// See `AUTO_CLASSIC_PROBE`: 16 (`Confeti-ex13-Fc3D-SBM`: 56²/16 = 196 sweeps).
pub(crate) const AUTO_CLASSIC_ENTRIES_SQUARED_PER_SWEEP: f64 = 16.0;

/// Outer iterations (first run included) within which the first classical run's rate must
/// promise the tolerance for [`Algorithm::Auto`] to let it go on rather than run its own
/// choice: 40, as for the sweep (`AUTO_SWEEP_PREDICTED`), below the 48 of
/// `Confeti-ex03-Fc3D-SBM` (where Newton and the sweep are 3× faster).
pub(crate) const AUTO_CLASSIC_PREDICTED: f64 = 40.0;

/// Settings of the reduced solver: the knobs a user sets (which algorithm, how accurate, how
/// long, what to do when it fails), with the tuning of the iteration beside them in
/// [`tuning`](Self::tuning). Build them from `Default` and the `with_*` setters (the struct is
/// `#[non_exhaustive]`, so new settings do not break callers); every tuning value has its
/// setter here too.
///
/// # Examples
/// ```
/// use contact_solver::{Algorithm, UzawaSettings};
/// let st = UzawaSettings::default().with_algorithm(Algorithm::Newton).with_tol(1e-12);
/// assert_eq!((st.algorithm, st.tol, st.max_iterations), (Algorithm::Newton, 1e-12, 10_000));
/// let tuned = st.with_rho_scale(1e-3);
/// assert_eq!((tuned.tuning.rho_scale, tuned.tuning.stall_window), (1e-3, 5000));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct UzawaSettings {
    /// Which sweep to run.
    pub algorithm: Algorithm,
    /// Tolerance of both tests of the stopping rule (see the [layer docs](crate::local)).
    pub tol: f64,
    /// Maximum number of iterations (sweeps).
    pub max_iterations: usize,
    /// Return `Ok` with `report.converged == false` instead of
    /// [`SolverError::NotConverged`](crate::SolverError::NotConverged).
    pub accept_non_converged: bool,
    /// When the chosen algorithm does not converge (stopped by the
    /// [stall detector](crate::local::stall), or `max_iterations` reached) or its answer
    /// fails the independent check of the Signorini–Coulomb conditions, solve again with
    /// [`Algorithm::ClassicRccm`] from the same start (after [`Algorithm::Newton`], first with
    /// [`Algorithm::AndersonGaussSeidel`], then the classical split if that fails too; laws
    /// with a
    /// [`friction_coefficient`](contact_laws::ContactLaw::friction_coefficient) only; not
    /// with `accept_non_converged`). The report's
    /// [`fallback_from`](UzawaReport::fallback_from) says it happened. Default `true`.
    pub fallback: bool,
    /// How the iteration runs: the penalty's scale, the relaxation of the classical solver,
    /// the stall window and the open-contact shortcut. The defaults are measured; most users
    /// never change them.
    #[cfg_attr(feature = "serde", serde(flatten))]
    pub tuning: UzawaTuning,
}

/// The tuning of the reduced solver's iteration ([`UzawaSettings::tuning`]): values whose
/// defaults were measured over the test suite and the benchmarks, for a user who studies one
/// hard problem.
///
/// # Examples
/// ```
/// use contact_solver::{UzawaSettings, UzawaTuning};
/// let tuning = UzawaTuning::default().with_stall_window(0).with_skip_open(false);
/// let st = UzawaSettings::default().with_tuning(tuning);
/// assert_eq!((st.tuning.stall_window, st.tuning.skip_open), (0, false));
/// assert_eq!(st.tuning.rho_scale, 1.0); // the rest keeps its default
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct UzawaTuning {
    /// Factor applied to the base `ρ⁰_i = 1/λ_max(W_ii)` at the start (adapted afterwards).
    /// Not used by [`Algorithm::ClassicRccm`]. Default 1.
    pub rho_scale: f64,
    /// Over-relaxation factor `ω ∈ (0, 2)` of the projected SOR sweeps of
    /// [`Algorithm::ClassicRccm`] (default 1, plain Gauss–Seidel); not used by the
    /// bipotential sweeps.
    pub omega: f64,
    /// Window of the [stall detector](crate::local::stall): the run stops as stalled when
    /// its residual has not halved over the last `max(stall_window, k/2)` of its `k`
    /// iterations. `0` switches the detector off; otherwise at least
    /// [`MIN_STALL_WINDOW`](crate::local::stall::MIN_STALL_WINDOW). Default 5000 (measured:
    /// twice the longest plateau of any converging run, [`stall`](crate::local::stall)).
    pub stall_window: usize,
    /// Solve only on the contacts that may close (Coulomb-type laws): the iteration starts
    /// on the contacts with `q_n < 0` (or a non-zero starting reaction), and a contact left
    /// out joins when the answer would make it penetrate; the answer is exact (every contact
    /// left out is checked at the end to be a solution with `r_i = 0`). Tried on a dense `W`
    /// (a sparse one gains nothing, measured) of at least 64 contacts when at most half of
    /// them may close. Default `true`.
    pub skip_open: bool,
    /// How a Gauss–Seidel sweep solves each contact ([`ContactSolve`]): one projected step
    /// (the default), or, in 2D with Coulomb-type laws, exactly (issue 37, ninth part).
    /// [`Algorithm::Auto`] sets [`ContactSolve::Exact`] in 2D.
    pub contact_solve: ContactSolve,
}

/// How a Gauss–Seidel sweep ([`Algorithm::GaussSeidel`], [`Algorithm::AndersonGaussSeidel`])
/// solves each contact with the others held ([`UzawaTuning::contact_solve`]).
///
/// # Examples
/// ```
/// use contact_solver::{ContactSolve, UzawaSettings, UzawaSolver, local::generate::random_problem};
/// let p = random_problem(30, 2); // 2D
/// let exact = UzawaSettings::default().with_contact_solve(ContactSolve::Exact);
/// let sol = UzawaSolver::new(exact).solve(&p, &p.coulomb_laws())?;
/// assert!(sol.report.converged);
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub enum ContactSolve {
    /// One step of the bipotential iteration per contact, `r_i ← P_K(r_i + ρ_i v_i(x_i))`
    /// with its adapted `ρ_i` (De Saxcé–Feng), in 2D and 3D: the default of the explicit
    /// algorithms.
    #[default]
    Projected,
    /// In 2D, with Coulomb-type laws (a
    /// [`friction_coefficient`](contact_laws::ContactLaw::friction_coefficient)), each contact
    /// solved exactly by its case (open, stick, slip) on its `2 × 2` block: the non-smooth
    /// block Gauss–Seidel (NSGS) of Siconos' `fc2d` (`exact_2d`); in 3D, or with other laws,
    /// [`Projected`](Self::Projected). Measured on Siconos' 2D granular problems: 99 sweeps
    /// of the accelerated sweep where the projected one takes 1 276.
    Exact,
}

impl Default for UzawaSettings {
    fn default() -> Self {
        Self {
            algorithm: Algorithm::default(),
            tol: 1e-10,
            max_iterations: 10_000,
            accept_non_converged: false,
            fallback: true,
            tuning: UzawaTuning::default(),
        }
    }
}

impl Default for UzawaTuning {
    fn default() -> Self {
        Self {
            rho_scale: 1.0,
            omega: DEFAULT_OMEGA,
            stall_window: DEFAULT_STALL_WINDOW,
            skip_open: true,
            contact_solve: ContactSolve::Projected,
        }
    }
}

/// What the solver did.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct UzawaReport {
    /// The algorithm that ran.
    pub algorithm: Algorithm,
    /// Iterations (sweeps) done: for [`Algorithm::ClassicRccm`], every normal and tangential
    /// sweep of every outer iteration (see [`classic`](crate::local::classic)); for the Anderson
    /// variants, base steps (rejected ones included); for [`Algorithm::Newton`], Newton steps
    /// plus Gauss–Seidel sweeps.
    pub iterations: usize,
    /// Outer iterations: threshold updates of [`Algorithm::ClassicRccm`], Newton steps (dense
    /// factorisations) of [`Algorithm::Newton`]; equal to `iterations` for the sweeps.
    pub outer_iterations: usize,
    /// Sweeps of the friction sub-problem of [`Algorithm::ClassicRccm`] (so
    /// `iterations − tangential_sweeps` are Signorini sweeps); 0 for the bipotential sweeps,
    /// which treat both components of a contact together.
    pub tangential_sweeps: usize,
    /// `true` when the stopping rule was met.
    pub converged: bool,
    /// `true` when the last run was stopped by the [stall detector](crate::local::stall)
    /// (its residual stopped decreasing) rather than by `max_iterations`; `converged` is then
    /// `false`.
    pub stalled: bool,
    /// Natural-map residual at the returned iterate (relative, see the [layer docs](crate::local)).
    pub residual: f64,
    /// Relative change `‖r_{k+1} − r_k‖/‖r_{k+1}‖` of the last iteration.
    pub change: f64,
    /// The natural-map residual of every iteration (of every outer iteration for
    /// [`Algorithm::ClassicRccm`]).
    pub history: Vec<f64>,
    /// Smallest adapted `ρ_i` at the end (the base `ρ⁰_i` for [`Algorithm::ClassicRccm`]).
    pub rho_min: f64,
    /// Largest adapted `ρ_i` at the end (the base `ρ⁰_i` for [`Algorithm::ClassicRccm`]).
    pub rho_max: f64,
    /// Status of each contact at the returned iterate (case of the projection with `ρ⁰`).
    pub statuses: Vec<ContactStatus>,
    /// The algorithm that was tried first and failed, when the answer comes from the fallback
    /// ([`UzawaSettings::fallback`]); `iterations`, `outer_iterations` and `history` then
    /// count both runs.
    pub fallback_from: Option<Algorithm>,
    /// Relative asymmetry of the problem's `W`, removed by symmetrising it
    /// ([`ReducedProblem::asymmetry`](crate::ReducedProblem::asymmetry)).
    pub asymmetry: f64,
    /// Whether `W` and `q` were rescaled internally (by powers of two, exactly) because their
    /// magnitudes were outside `[1e-100, 1e100]`.
    pub rescaled: bool,
    /// Contacts the algorithm iterated on: `n_c`, or fewer when
    /// [`skip_open`](UzawaTuning::skip_open) left out contacts that stay open; 0 when
    /// `r = 0` was the answer with no iteration.
    pub solved_contacts: usize,
}

/// The solution of a reduced problem.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Solution {
    /// Reactions, normal first per contact (`r_n ≥ 0` is compression).
    pub r: Vec<f64>,
    /// Displacements / gaps `x = W r + q` (`x_n ≥ 0` is an opening).
    pub x: Vec<f64>,
    /// How the solver got there.
    pub report: UzawaReport,
}

impl UzawaSettings {
    /// These settings with [`algorithm`](Self::algorithm) replaced.
    #[must_use]
    pub fn with_algorithm(mut self, algorithm: Algorithm) -> Self {
        self.algorithm = algorithm;
        self
    }

    /// These settings with [`fallback`](Self::fallback) replaced.
    #[must_use]
    pub fn with_fallback(mut self, fallback: bool) -> Self {
        self.fallback = fallback;
        self
    }

    /// These settings with [`tol`](Self::tol) replaced.
    #[must_use]
    pub fn with_tol(mut self, tol: f64) -> Self {
        self.tol = tol;
        self
    }

    /// These settings with [`max_iterations`](Self::max_iterations) replaced.
    #[must_use]
    pub fn with_max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// These settings with [`accept_non_converged`](Self::accept_non_converged) replaced.
    #[must_use]
    pub fn with_accept_non_converged(mut self, accept_non_converged: bool) -> Self {
        self.accept_non_converged = accept_non_converged;
        self
    }

    /// These settings with [`tuning`](Self::tuning) replaced.
    #[must_use]
    pub fn with_tuning(mut self, tuning: UzawaTuning) -> Self {
        self.tuning = tuning;
        self
    }

    /// These settings with [`UzawaTuning::rho_scale`] replaced.
    #[must_use]
    pub fn with_rho_scale(mut self, rho_scale: f64) -> Self {
        self.tuning.rho_scale = rho_scale;
        self
    }

    /// These settings with [`UzawaTuning::omega`] replaced.
    #[must_use]
    pub fn with_omega(mut self, omega: f64) -> Self {
        self.tuning.omega = omega;
        self
    }

    /// These settings with [`UzawaTuning::stall_window`] replaced.
    #[must_use]
    pub fn with_stall_window(mut self, stall_window: usize) -> Self {
        self.tuning.stall_window = stall_window;
        self
    }

    /// These settings with [`UzawaTuning::skip_open`] replaced.
    #[must_use]
    pub fn with_skip_open(mut self, skip_open: bool) -> Self {
        self.tuning.skip_open = skip_open;
        self
    }

    /// These settings with [`UzawaTuning::contact_solve`] replaced.
    #[must_use]
    pub fn with_contact_solve(mut self, contact_solve: ContactSolve) -> Self {
        self.tuning.contact_solve = contact_solve;
        self
    }
}

impl UzawaTuning {
    /// This tuning with [`rho_scale`](Self::rho_scale) replaced.
    #[must_use]
    pub fn with_rho_scale(mut self, rho_scale: f64) -> Self {
        self.rho_scale = rho_scale;
        self
    }

    /// This tuning with [`omega`](Self::omega) replaced.
    #[must_use]
    pub fn with_omega(mut self, omega: f64) -> Self {
        self.omega = omega;
        self
    }

    /// This tuning with [`stall_window`](Self::stall_window) replaced.
    #[must_use]
    pub fn with_stall_window(mut self, stall_window: usize) -> Self {
        self.stall_window = stall_window;
        self
    }

    /// This tuning with [`skip_open`](Self::skip_open) replaced.
    #[must_use]
    pub fn with_skip_open(mut self, skip_open: bool) -> Self {
        self.skip_open = skip_open;
        self
    }

    /// This tuning with [`contact_solve`](Self::contact_solve) replaced.
    #[must_use]
    pub fn with_contact_solve(mut self, contact_solve: ContactSolve) -> Self {
        self.contact_solve = contact_solve;
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn issue_35_defaults_are_kept_by_the_split() {
        // the values before the split into settings and tuning (issue 35)
        let st = UzawaSettings::default();
        assert_eq!(st.algorithm, Algorithm::AndersonGaussSeidel);
        assert_eq!((st.tol, st.max_iterations), (1e-10, 10_000));
        assert!(!st.accept_non_converged && st.fallback);
        let t = st.tuning;
        assert_eq!((t.rho_scale, t.omega, t.stall_window), (1.0, 1.0, 5000));
        assert!(t.skip_open);
        assert_eq!(t.contact_solve, ContactSolve::Projected);
    }
}
