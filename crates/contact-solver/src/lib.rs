//! Contact solver of `bipotential`, in two layers.
//!
//! - [`local`] — **the reduced problem and its solvers**, for any code that can condense its
//!   contact problem (2D, `n_c` contacts, unknowns normal first per contact):
//!
//!   ```text
//!   x = W r + q,   W SPD (flexibility F* = H K⁻¹ Hᵀ), q = free gap
//!   per contact:   r_i ∈ K_μi,   r_i = P_K(r_i + ρ_i v_i(x_i))    (De Saxcé, seed 5.26)
//!   ```
//!   Uzawa, Gauss–Seidel, their Anderson-accelerated forms, semi-smooth Newton, the classical
//!   RCCM split and the matrix-free sweep, plus the adhesive condensation around them. This
//!   layer depends on `contact-laws` and `faer` only: with `default-features = false` the crate
//!   compiles without `fem-core`, `vtkio` or any FE coupling (feature `serde` adds the JSON
//!   form of a problem).
//! - [`coupling`] (feature `fe`, on by default) — **the FE coupling**: obstacles, contact zones
//!   and recognition on a [`fem_core::Structure`], the flexibility `F*` (dense, matrix-free or
//!   the primal active set), load stepping ([`ContactSimulation`]) as a pipeline of stages, and
//!   the CSV/VTK writers.
//!
//! Signs follow `docs/theory.md` §1 and [`contact_laws`](contact_laws#sign-conventions):
//! `r_n ≥ 0` is compression, `x_n ≥ 0` an opening — the same as Siconos' `fc2d`
//! (`u = W r + q`), so `ReducedProblem::to_json` writes what `shared/peers/siconos_fc.py`
//! reads. The local laws come through the [`ContactLaw`](contact_laws::ContactLaw) trait
//! (`docs/theory.md` §9); the iteration, the self-adaptive ρ and the stopping rule are
//! described in [`local`].
//!
//! # Features
//! - `fe` (default): the FE coupling ([`coupling`]); pulls `fem-core` and `vtkio`.
//! - `serde` (default): `ReducedProblem::{from_json, to_json}` and `Serialize` on the report
//!   types.
//!
//! # Examples
//! ```
//! use contact_solver::{ReducedProblem, UzawaSettings, solve_coulomb};
//! let p = ReducedProblem::new(vec![2.0, 0.0, 0.0, 2.0], vec![-1.0, 0.5], vec![0.2])?;
//! let sol = solve_coulomb(&p, &UzawaSettings::default())?;
//! assert!((sol.r[0] - 0.5).abs() < 1e-9);        // r_n = −q_n/f
//! assert!((sol.r[1] + 0.2 * sol.r[0]).abs() < 1e-9); // slip: r_t = −μ r_n
//! # Ok::<(), contact_solver::SolverError>(())
//! ```

#![warn(missing_docs)]

#[cfg(feature = "fe")]
pub mod coupling;
pub mod error;
pub mod local;

pub use contact_laws;
#[cfg(feature = "fe")]
pub use error::NewtonFailure;
pub use error::{BestIterate, SolverError};
pub use local::{
    Algorithm, Asymmetry, ContactSolve, CsrMatrix, ReducedProblem, Solution, UzawaReport,
    UzawaSettings, UzawaSolver, UzawaTuning, WView, solve_coulomb,
};

#[cfg(feature = "fe")]
pub use coupling::obstacle::{ArcSide, Obstacle, ObstaclePoint, ObstacleSide, RigidArc, RigidLine};
#[cfg(feature = "fe")]
pub use coupling::output::{HistoryWriter, InterfaceSeries, ReportWriter, write_interface_vtu};
#[cfg(feature = "fe")]
pub use coupling::simulation::{
    ContactRecord, ContactSimulation, Counters, DEFAULT_DENSE_LIMIT, FlexibilityMode,
    InterfaceStatus, PathChoice, PathReason, SimulationSettings, SimulationTuning, SkipRules,
    SolvePath, StepReport, StepResult,
};
#[cfg(feature = "fe")]
pub use coupling::simulation::{EnergyBalance, MoreauJean, QuasiStatic, SchemeStep, TimeScheme};
#[cfg(feature = "fe")]
pub use coupling::simulation::{NewtonReport, NewtonSettings};
#[cfg(feature = "fe")]
pub use coupling::zone::{
    Candidate, ContactZone, PairNormals, Polyline, Target, check_rigid_targets, recognize,
    supported_contactors,
};
