//! Errors of the contact solver.
//!
//! Problems are validated once, when a [`ReducedProblem`](crate::ReducedProblem) is built;
//! the solver's loop then only fails by not converging.

#[cfg(feature = "fe")]
mod newton_failure;

use contact_laws::LawError;
#[cfg(feature = "fe")]
pub use newton_failure::NewtonFailure;
use std::error::Error;
use std::fmt;
use std::sync::Arc;

/// Error of `contact-solver`.
///
/// `Debug` is written out (not derived) so that the variants carrying an iteration history
/// ([`NotConverged`](Self::NotConverged), [`Stalled`](Self::Stalled),
/// [`AdhesionNotConverged`](Self::AdhesionNotConverged)) print its length and last
/// [`HISTORY_SHOWN`] values, not thousands of numbers: `main` returning
/// `Result<(), Box<dyn Error>>` prints its error with `Debug`. The whole history stays in the
/// field ([`history`](Self::history)).
#[derive(Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SolverError {
    /// An array does not have the length the problem needs.
    #[error("invalid size of `{what}`: expected {expected}, found {found}")]
    SizeMismatch {
        /// Which array (`"W"`, `"q"`, `"mu"`, `"laws"`, …).
        what: &'static str,
        /// The expected length.
        expected: usize,
        /// The length found.
        found: usize,
    },
    /// An entry is NaN or infinite.
    #[error("`{what}[{index}]` = {value} is not finite")]
    NonFinite {
        /// Which array.
        what: &'static str,
        /// Flat index of the entry.
        index: usize,
        /// The rejected value.
        value: f64,
    },
    /// An index of a sparse matrix given as triplets is out of range.
    #[error("`{what}[{index}]` = {value} is out of range: indices must be below {bound}")]
    IndexOutOfRange {
        /// Which array (`"rows"`, `"cols"`).
        what: &'static str,
        /// Position of the entry in that array (the triplet's number).
        index: usize,
        /// The rejected index.
        value: usize,
        /// The bound it must stay below (`m`).
        bound: usize,
    },
    /// The flexibility matrix `W` is not symmetric to the tolerance of its
    /// [`Asymmetry`](crate::Asymmetry) policy (`1e-6·max|W|` by default).
    #[error(
        "W is not symmetric: |W[{row}][{col}] - W[{col}][{row}]| = {difference:e} exceeds \
         {tolerance:e} (to solve it as given, build it with Asymmetry::Keep)"
    )]
    NotSymmetric {
        /// Row of the worst entry.
        row: usize,
        /// Column of the worst entry.
        col: usize,
        /// `|W_ij − W_ji|`.
        difference: f64,
        /// The tolerance it exceeds.
        tolerance: f64,
    },
    /// The algorithm asked for needs a symmetric `W` (its step is a projected gradient of the
    /// energy `½ rᵀ W r + qᵀ r`), and the problem keeps a non-symmetric one
    /// ([`Asymmetry::Keep`](crate::Asymmetry::Keep)).
    #[error(
        "the algorithm {algorithm} needs a symmetric W, and this problem keeps a W whose \
         asymmetry is {asymmetry:e} of its scale: use AndersonGaussSeidel, GaussSeidel, Newton, \
         ClassicRccm or Auto, which solve it as given"
    )]
    NeedsSymmetricW {
        /// The algorithm refused (`"Uzawa"`, `"AndersonUzawa"`).
        algorithm: &'static str,
        /// The relative asymmetry of the kept `W`
        /// ([`ReducedProblem::kept_asymmetry`](crate::ReducedProblem::kept_asymmetry)).
        asymmetry: f64,
    },
    /// A 2×2 diagonal block of `W` is not positive definite, so `W` is not SPD (a contact with
    /// no flexibility, or a rigid-body mode).
    #[error("the 2x2 diagonal block of W at contact {contact} is not positive definite")]
    NotPositiveDefinite {
        /// Index of the contact.
        contact: usize,
    },
    /// A friction coefficient was rejected by the local law (the law's error is the
    /// [`source`](std::error::Error::source)).
    #[error("invalid friction coefficient at contact {contact}")]
    InvalidLaw {
        /// Index of the contact.
        contact: usize,
        /// The law's own error.
        #[source]
        source: LawError,
    },
    /// The law at a contact has no friction coefficient
    /// ([`ContactLaw::friction_coefficient`](contact_laws::ContactLaw::friction_coefficient)
    /// returned `None`), which [`Algorithm::ClassicRccm`](crate::Algorithm::ClassicRccm)
    /// needs for its threshold `s = μ̄ r_n` and [`Algorithm::Newton`](crate::Algorithm::Newton)
    /// for its generalized Jacobian.
    #[error(
        "the law at contact {contact} has no friction coefficient: the classical RCCM solver and the Newton solver need a Coulomb-type law (use a bipotential sweep for this law)"
    )]
    NoFrictionCoefficient {
        /// Index of the contact.
        contact: usize,
    },
    /// The problem's friction coefficient at a contact disagrees with the law it is solved
    /// with. μ has one owner, the law: a [`ReducedProblem`](crate::ReducedProblem) solved with
    /// laws must carry their coefficients
    /// ([`ReducedProblem::with_friction_of`](crate::ReducedProblem::with_friction_of) builds
    /// it so), and a plain Coulomb problem is solved with
    /// [`solve_coulomb`](crate::solve_coulomb), whose laws are the problem's.
    #[error(
        "contact {contact}: the problem's friction coefficient mu = {problem} disagrees with its law's {law}; the law owns mu: build the problem with the laws' coefficients (ReducedProblem::with_friction_of) or solve it with its own Coulomb laws (solve_coulomb)"
    )]
    FrictionMismatch {
        /// Index of the contact.
        contact: usize,
        /// `μ_i` stored in the problem.
        problem: f64,
        /// The law's coefficient `μ̄_i` in its state.
        law: f64,
    },
    /// A local law was rejected (without a contact index; the law's error is the source).
    #[error("invalid contact law")]
    Law(#[from] LawError),
    /// The text is not JSON, or not JSON of the expected shape (the parser's error is the
    /// source).
    #[error("cannot read the reduced problem from JSON")]
    Json {
        /// The parser's error.
        #[source]
        source: Cause,
    },
    /// JSON that parses but does not describe a supported reduced problem (`dim ≠ 2`, rows of
    /// `W` of the wrong length).
    #[error("cannot read the reduced problem from JSON: {reason}")]
    Format {
        /// What is wrong, in the file's terms.
        reason: String,
    },
    /// An FCLIB HDF5 file (feature `fclib`, module `local::fclib`) that cannot
    /// be opened, read or written, or that does not hold a supported problem: the reason names
    /// the group or dataset (`fclib_local/W/i[4]`), the HDF5 library's error is the source when
    /// it is the cause.
    #[error("FCLIB file `{path}`: {reason}")]
    Fclib {
        /// The file.
        path: String,
        /// What is wrong, in the file's terms.
        reason: String,
        /// The HDF5 library's error, when it is the cause.
        #[source]
        source: Option<Cause>,
    },
    /// A Siconos `.dat` friction-contact file (module `local::siconos_dat`) that cannot be
    /// read, or that holds no supported problem: the line and what is wrong there.
    #[error("Siconos .dat problem, line {line}: {reason}")]
    SiconosDat {
        /// The line (from 1) of the token at fault; the last line when the file ends early.
        line: usize,
        /// What is wrong, in the file's terms.
        reason: String,
    },
    /// Writing an output file or stream failed (the I/O error is the source).
    #[error("I/O error: {what}")]
    Io {
        /// What could not be written (``cannot write `out/a.vtu` ``).
        what: String,
        /// The underlying error.
        #[source]
        source: Cause,
    },
    /// The iteration reached `max_iterations` before meeting the stopping rule.
    #[error(
        "the contact iteration did not converge in {iterations} iterations (residual {residual:e}; {})",
        tail_note("residuals", history)
    )]
    NotConverged {
        /// Iterations done.
        iterations: usize,
        /// Natural-map residual at the last iterate.
        residual: f64,
        /// Natural-map residual of every iteration.
        history: Vec<f64>,
        /// The best iterate the runs returned (see [`BestIterate`]), when the solver had one.
        best: Option<Box<BestIterate>>,
    },
    /// The [stall detector](crate::local::stall) stopped the iteration: its residual had not
    /// halved over the last [`stall_window`](crate::UzawaTuning::stall_window) iterations
    /// (nor over the second half of the run) — typically a problem with no solution (a
    /// rank-deficient `W` with incompatible `q`), or one the algorithm cannot solve.
    #[error(
        "the contact iteration stalled: {algorithm}{} made no progress, stopped after {iterations} iterations at residual {residual:e} (best {best_residual:e}; {}); the problem may have no solution",
        fallback_note(fallback_from),
        tail_note("residuals", history)
    )]
    Stalled {
        /// The algorithm that stalled (the fallback's when there was one), by the name of its
        /// [`Algorithm`](crate::Algorithm) variant ([`Algorithm::name`](crate::Algorithm::name)),
        /// or `MatrixFree` for
        /// [`solve_matrix_free`](crate::local::matrix_free::solve_matrix_free).
        algorithm: &'static str,
        /// The algorithm tried first, when the one that stalled was the fallback
        /// ([`UzawaSettings::fallback`](crate::UzawaSettings::fallback)).
        fallback_from: Option<&'static str>,
        /// Iterations done (of both runs with a fallback).
        iterations: usize,
        /// Natural-map residual at the last iterate.
        residual: f64,
        /// The smallest natural-map residual of the run that stalled.
        best_residual: f64,
        /// Natural-map residual of every iteration (of both runs with a fallback).
        history: Vec<f64>,
        /// The best iterate the runs returned (see [`BestIterate`]), when the solver had one.
        best: Option<Box<BestIterate>>,
    },
    /// A contact zone or obstacle whose geometry makes no sense (zero-length LINE, node out of
    /// range, empty node set, …).
    #[error("invalid contact geometry: {0}")]
    InvalidGeometry(String),
    /// The requested solution path does not apply to this step (e.g.
    /// `FlexibilityMode::ActiveSet` on a node-to-segment zone); the message says why.
    #[error("unsupported for this step: {0}")]
    Unsupported(String),
    /// A zone named by the caller does not exist.
    #[error("no contact zone is named `{name}` (the zones are: {known})")]
    UnknownZone {
        /// The name asked for.
        name: String,
        /// The zones' names, comma-separated.
        known: String,
    },
    /// An invalid setting (tolerance, alert distance, time step, …).
    #[error("invalid setting `{what}` = {value}: {expected}")]
    InvalidSetting {
        /// The setting.
        what: &'static str,
        /// Its value.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
    /// The structure failed (factorisation, solve, unknown node set); the structure's error is
    /// the source.
    #[cfg(feature = "fe")]
    #[error("structure")]
    Structure(#[from] fem_core::FemError),
    /// Contact cannot balance the load of a floating body along one of its rigid-body modes
    /// (the body would fly away or slide off): after the contact reactions did all they can,
    /// the generalized force along `motion` is still `imbalance` (a force for a translation, a
    /// moment about the mode's centre for a rotation), against the load's own `load` along it.
    #[cfg(feature = "fe")]
    #[error(
        "floating body {body}: contact cannot balance the load along its {motion}: out of balance \
         by {imbalance:e} (the load along it is {load:e}); add a support or a contact that holds it"
    )]
    Unbalanced {
        /// The body (connected component of the structure, as in
        /// [`RigidMode::body`](fem_core::RigidMode::body)).
        body: usize,
        /// The mode along which the load is not balanced.
        motion: fem_core::RigidMotion,
        /// The resultant force (translation) or moment (rotation) left unbalanced, load plus
        /// contact reactions.
        imbalance: f64,
        /// The load's own force or moment along the mode.
        load: f64,
    },
    /// The penetration check ran out: after the last detection pass allowed, candidates
    /// outside the solved reduced problem still penetrate their targets, so the step is not
    /// accepted (the answer would be a wrong one).
    #[error(
        "after {passes} detection passes, {count} contact candidate(s) outside the reduced problem still penetrate (the deepest: zone `{zone}`, contactor node {node}, gap {gap:e}); raise `{setting}` or refine the step"
    )]
    StillPenetrating {
        /// Detection passes done (each adds the penetrating candidates and solves again).
        passes: usize,
        /// Candidates still penetrating after the last pass.
        count: usize,
        /// The zone of the deepest one.
        zone: String,
        /// Its contactor node.
        node: usize,
        /// Its gap (negative).
        gap: f64,
        /// The setting that bounds the passes.
        setting: &'static str,
    },
    /// The global Newton around contact of a nonlinear structure did not converge after the
    /// step was cut as often as allowed; the last converged state is kept ([`NewtonFailure`]:
    /// the load reached and the residuals).
    #[cfg(feature = "fe")]
    #[error(transparent)]
    NewtonNotConverged(Box<NewtonFailure>),
    /// The fixed point between the contact solve and the adhesion update did not converge.
    #[error(
        "the adhesion fixed point did not converge in {iterations} iterations (last change of beta {change:e}; {})",
        tail_note("changes", history)
    )]
    AdhesionNotConverged {
        /// Fixed-point iterations done.
        iterations: usize,
        /// Largest change of the state in the last iteration.
        change: f64,
        /// The largest state change of every iteration.
        history: Vec<f64>,
    },
}

/// ` (the fallback from X)`, or nothing.
fn fallback_note(from: &Option<&'static str>) -> String {
    from.map(|a| format!(" (the fallback after {a})"))
        .unwrap_or_default()
}

/// `last residuals: a, b, …` (the last [`HISTORY_SHOWN`] values of `history`), or `no history`.
pub(crate) fn tail_note(what: &str, history: &[f64]) -> String {
    if history.is_empty() {
        return "no history".to_string();
    }
    let shown = &history[history.len().saturating_sub(HISTORY_SHOWN)..];
    let values: Vec<String> = shown.iter().map(|v| format!("{v:.3e}")).collect();
    format!("last {what}: {}", values.join(", "))
}

/// How many of a history's last values [`SolverError`]'s `Debug` shows.
pub const HISTORY_SHOWN: usize = 5;

impl SolverError {
    /// The iteration history an error carries (the natural-map residual of every iteration
    /// for [`NotConverged`](Self::NotConverged) and [`Stalled`](Self::Stalled), the largest
    /// state change of every fixed-point iteration for
    /// [`AdhesionNotConverged`](Self::AdhesionNotConverged), the equilibrium residuals of the
    /// last attempt for [`NewtonNotConverged`](Self::NewtonNotConverged)), whole; `None` for
    /// the other variants.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::SolverError;
    /// let e = SolverError::NotConverged { iterations: 3, residual: 0.1, history: vec![1.0, 0.5, 0.1], best: None };
    /// assert_eq!(e.history(), Some(&[1.0, 0.5, 0.1][..]));
    /// ```
    pub fn history(&self) -> Option<&[f64]> {
        match self {
            Self::NotConverged { history, .. }
            | Self::Stalled { history, .. }
            | Self::AdhesionNotConverged { history, .. } => Some(history),
            #[cfg(feature = "fe")]
            Self::NewtonNotConverged(failure) => Some(&failure.history),
            _ => None,
        }
    }

    /// The best-effort answer of a reduced solve that did not reach its tolerance
    /// ([`NotConverged`](Self::NotConverged) or [`Stalled`](Self::Stalled)): the iterate with
    /// the smallest natural-map residual among those the runs (the algorithm and its
    /// fallbacks) returned; `None` for the other variants and for errors built without one.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::{Algorithm, ReducedProblem, UzawaSettings, solve_coulomb};
    /// // two coupled contacts, both pressed: one Gauss–Seidel sweep does not solve them
    /// #[rustfmt::skip]
    /// let w = vec![2.0, 0.0, 1.0, 0.0,  0.0, 2.0, 0.0, 0.5,  1.0, 0.0, 2.0, 0.0,  0.0, 0.5, 0.0, 2.0];
    /// let p = ReducedProblem::new(w, vec![-1.0, 0.5, -1.0, -0.3], vec![0.3, 0.3])?;
    /// let st = UzawaSettings::default()
    ///     .with_algorithm(Algorithm::GaussSeidel)
    ///     .with_max_iterations(1)
    ///     .with_fallback(false);
    /// let e = solve_coulomb(&p, &st).unwrap_err();
    /// let best = e.best_iterate().expect("a best iterate");
    /// assert_eq!((best.r.len(), best.x.len()), (4, 4));
    /// assert!(best.residual > 1e-10);
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn best_iterate(&self) -> Option<&BestIterate> {
        match self {
            Self::NotConverged { best, .. } | Self::Stalled { best, .. } => best.as_deref(),
            _ => None,
        }
    }
}

/// The best-effort answer a failed reduced solve carries ([`SolverError::best_iterate`]):
/// reactions, the displacements `x = W r + q` recomputed from them, and the relative
/// natural-map residual at that point (the definition of
/// [`UzawaReport::residual`](crate::UzawaReport::residual), above the tolerance asked for).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct BestIterate {
    /// Reactions, normal first per contact.
    pub r: Vec<f64>,
    /// `x = W r + q`.
    pub x: Vec<f64>,
    /// The relative natural-map residual at `(r, x)`.
    pub residual: f64,
}

impl BestIterate {
    /// A best iterate from its parts.
    pub fn new(r: Vec<f64>, x: Vec<f64>, residual: f64) -> Self {
        Self { r, x, residual }
    }
}

/// A history in `Debug`: its length and its last [`HISTORY_SHOWN`] values.
pub(crate) struct HistoryTail<'a>(pub(crate) &'a [f64]);

impl fmt::Debug for HistoryTail<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let h = self.0;
        if h.len() <= HISTORY_SHOWN {
            return f.debug_list().entries(h).finish();
        }
        write!(f, "[{} values, last {HISTORY_SHOWN}: ", h.len())?;
        for (k, v) in h[h.len() - HISTORY_SHOWN..].iter().enumerate() {
            if k > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{v:e}")?;
        }
        f.write_str("]")
    }
}

impl fmt::Debug for SolverError {
    // one arm per variant, as `#[derive(Debug)]` would write them, but with the histories cut
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::SizeMismatch {
                what,
                expected,
                found,
            } => f
                .debug_struct("SizeMismatch")
                .field("what", what)
                .field("expected", expected)
                .field("found", found)
                .finish(),
            Self::NonFinite { what, index, value } => f
                .debug_struct("NonFinite")
                .field("what", what)
                .field("index", index)
                .field("value", value)
                .finish(),
            Self::IndexOutOfRange {
                what,
                index,
                value,
                bound,
            } => f
                .debug_struct("IndexOutOfRange")
                .field("what", what)
                .field("index", index)
                .field("value", value)
                .field("bound", bound)
                .finish(),
            Self::NotSymmetric {
                row,
                col,
                difference,
                tolerance,
            } => f
                .debug_struct("NotSymmetric")
                .field("row", row)
                .field("col", col)
                .field("difference", difference)
                .field("tolerance", tolerance)
                .finish(),
            Self::NeedsSymmetricW {
                algorithm,
                asymmetry,
            } => f
                .debug_struct("NeedsSymmetricW")
                .field("algorithm", algorithm)
                .field("asymmetry", asymmetry)
                .finish(),
            Self::NotPositiveDefinite { contact } => f
                .debug_struct("NotPositiveDefinite")
                .field("contact", contact)
                .finish(),
            Self::InvalidLaw { contact, source } => f
                .debug_struct("InvalidLaw")
                .field("contact", contact)
                .field("source", source)
                .finish(),
            Self::NoFrictionCoefficient { contact } => f
                .debug_struct("NoFrictionCoefficient")
                .field("contact", contact)
                .finish(),
            Self::FrictionMismatch {
                contact,
                problem,
                law,
            } => f
                .debug_struct("FrictionMismatch")
                .field("contact", contact)
                .field("problem", problem)
                .field("law", law)
                .finish(),
            Self::Law(e) => f.debug_tuple("Law").field(e).finish(),
            Self::Json { source } => f.debug_struct("Json").field("source", source).finish(),
            Self::Format { reason } => f.debug_struct("Format").field("reason", reason).finish(),
            Self::Fclib {
                path,
                reason,
                source,
            } => f
                .debug_struct("Fclib")
                .field("path", path)
                .field("reason", reason)
                .field("source", source)
                .finish(),
            Self::SiconosDat { line, reason } => f
                .debug_struct("SiconosDat")
                .field("line", line)
                .field("reason", reason)
                .finish(),
            Self::Io { what, source } => f
                .debug_struct("Io")
                .field("what", what)
                .field("source", source)
                .finish(),
            Self::NotConverged {
                iterations,
                residual,
                history,
                best,
            } => {
                let mut d = f.debug_struct("NotConverged");
                d.field("iterations", iterations)
                    .field("residual", residual)
                    .field("history", &HistoryTail(history));
                if let Some(b) = best {
                    d.field("best_iterate_residual", &b.residual);
                }
                d.finish()
            }
            Self::Stalled {
                algorithm,
                fallback_from,
                iterations,
                residual,
                best_residual,
                history,
                best,
            } => {
                let mut d = f.debug_struct("Stalled");
                d.field("algorithm", algorithm)
                    .field("fallback_from", fallback_from)
                    .field("iterations", iterations)
                    .field("residual", residual)
                    .field("best_residual", best_residual)
                    .field("history", &HistoryTail(history));
                if let Some(b) = best {
                    d.field("best_iterate_residual", &b.residual);
                }
                d.finish()
            }
            Self::InvalidGeometry(s) => f.debug_tuple("InvalidGeometry").field(s).finish(),
            Self::Unsupported(s) => f.debug_tuple("Unsupported").field(s).finish(),
            Self::UnknownZone { name, known } => f
                .debug_struct("UnknownZone")
                .field("name", name)
                .field("known", known)
                .finish(),
            Self::InvalidSetting {
                what,
                value,
                expected,
            } => f
                .debug_struct("InvalidSetting")
                .field("what", what)
                .field("value", value)
                .field("expected", expected)
                .finish(),
            #[cfg(feature = "fe")]
            Self::Structure(e) => f.debug_tuple("Structure").field(e).finish(),
            #[cfg(feature = "fe")]
            Self::Unbalanced {
                body,
                motion,
                imbalance,
                load,
            } => f
                .debug_struct("Unbalanced")
                .field("body", body)
                .field("motion", motion)
                .field("imbalance", imbalance)
                .field("load", load)
                .finish(),
            Self::StillPenetrating {
                passes,
                count,
                zone,
                node,
                gap,
                setting,
            } => f
                .debug_struct("StillPenetrating")
                .field("passes", passes)
                .field("count", count)
                .field("zone", zone)
                .field("node", node)
                .field("gap", gap)
                .field("setting", setting)
                .finish(),
            #[cfg(feature = "fe")]
            Self::NewtonNotConverged(n) => f.debug_tuple("NewtonNotConverged").field(n).finish(),
            Self::AdhesionNotConverged {
                iterations,
                change,
                history,
            } => f
                .debug_struct("AdhesionNotConverged")
                .field("iterations", iterations)
                .field("change", change)
                .field("history", &HistoryTail(history))
                .finish(),
        }
    }
}

#[cfg(feature = "serde")]
impl From<serde_json::Error> for SolverError {
    fn from(e: serde_json::Error) -> Self {
        Self::Json {
            source: Cause::new(e),
        }
    }
}

/// The underlying error of a [`SolverError`] (I/O, JSON parser), shared so that the error stays
/// `Clone`. Its `Display` is the underlying error's; two causes are equal when their messages
/// are.
#[derive(Clone, Debug)]
pub struct Cause(Arc<dyn Error + Send + Sync + 'static>);

impl Cause {
    /// Wraps an error.
    pub fn new(e: impl Error + Send + Sync + 'static) -> Self {
        Self(Arc::new(e))
    }

    /// A cause that is only a message (an error reported as text by another layer).
    pub fn message(text: impl Into<String>) -> Self {
        Self(Arc::from(Box::<dyn Error + Send + Sync>::from(text.into())))
    }
}

impl fmt::Display for Cause {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl Error for Cause {
    fn source(&self) -> Option<&(dyn Error + 'static)> {
        self.0.source()
    }
}

impl PartialEq for Cause {
    fn eq(&self, other: &Self) -> bool {
        self.0.to_string() == other.0.to_string()
    }
}

/// `e` and its chain of sources, joined by `: ` (what `anyhow`'s `{:#}` prints): each error's
/// `Display` says what failed in its own words, the chain says why.
///
/// # Examples
/// ```
/// use contact_solver::error::chain;
/// let law = contact_laws::Coulomb::new(-1.0).unwrap_err();
/// let e = contact_solver::SolverError::from(law);
/// assert!(chain(&e).starts_with("invalid contact law: invalid parameter `mu`"));
/// ```
pub fn chain(e: &(dyn Error + 'static)) -> String {
    let mut text = e.to_string();
    let mut next = e.source();
    while let Some(s) = next {
        text.push_str(": ");
        text.push_str(&s.to_string());
        next = s.source();
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_display_a_sentence() {
        let e = SolverError::SizeMismatch {
            what: "q",
            expected: 4,
            found: 3,
        };
        assert_eq!(e.to_string(), "invalid size of `q`: expected 4, found 3");
        let law = contact_laws::Coulomb::new(-1.0).unwrap_err();
        let e: SolverError = law.into();
        // the law's message once: in the chain, not in the variant's own Display
        assert_eq!(e.to_string(), "invalid contact law");
        assert!(chain(&e).starts_with("invalid contact law: invalid parameter `mu`"));
        assert_eq!(chain(&e).matches("invalid parameter").count(), 1);
    }

    /// Issue 36: an error with a 10 000-entry history (the seed's `shear` example printed
    /// every value through `main`'s `Debug`) renders short, with the iterations, the residual
    /// and the last values, in `Display` and `Debug`; the whole history stays in the field.
    #[test]
    fn issue_36_history_errors_render_short() {
        let history: Vec<f64> = (0..10_000).map(|k| 1e-7 - 1e-12 * k as f64).collect();
        let last = history[9_999];
        let errors = [
            SolverError::NotConverged {
                iterations: 10_000,
                residual: 9.27e-8,
                history: history.clone(),
                best: None,
            },
            SolverError::Stalled {
                algorithm: "GaussSeidel",
                fallback_from: None,
                iterations: 10_000,
                residual: 9.27e-8,
                best_residual: 9.2e-8,
                history: history.clone(),
                best: None,
            },
            SolverError::AdhesionNotConverged {
                iterations: 10_000,
                change: 9.27e-8,
                history: history.clone(),
            },
        ];
        for e in &errors {
            let debug = format!("{e:?}");
            let display = e.to_string();
            // 500 characters: a few lines of a terminal; the full history printed 10 000
            // numbers (~200 000 characters)
            assert!(debug.len() < 500, "{} chars: {debug}", debug.len());
            assert!(display.len() < 500, "{display}");
            assert!(
                debug.contains("10000") && debug.contains("9.27e-8"),
                "{debug}"
            );
            assert!(
                display.contains("10000") && display.contains("9.27e-8"),
                "{display}"
            );
            assert!(display.contains(&format!("{last:.3e}")), "{display}");
            assert!(debug.contains(&format!("{last:e}")), "{debug}");
            assert!(debug.contains("10000 values, last 5"), "{debug}");
            assert_eq!(e.history(), Some(&history[..]));
            // through `Box<dyn Error>`, as `main` prints it
            let boxed: Box<dyn Error> = Box::new(e.clone());
            assert!(format!("{boxed:?}").len() < 500);
        }
        // a short history is printed whole, as the derived Debug did
        let e = SolverError::NotConverged {
            iterations: 2,
            residual: 0.5,
            history: vec![1.0, 0.5],
            best: None,
        };
        assert_eq!(
            format!("{e:?}"),
            "NotConverged { iterations: 2, residual: 0.5, history: [1.0, 0.5] }"
        );
    }
}
