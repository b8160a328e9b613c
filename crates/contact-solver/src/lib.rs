//! Contact solver of `bipotential`.
//!
//! For now this crate holds the **reduced-problem solver**: given the condensed problem of any
//! finite-element code (2D, `n_c` contacts, unknowns normal first per contact)
//!
//! ```text
//! x = W r + q,   W SPD (flexibility F* = H K⁻¹ Hᵀ), q = free gap
//! per contact:   r_i ∈ K_μi,   r_i = P_K(r_i + ρ_i v_i(x_i))    (De Saxcé, seed 5.26)
//! ```
//! it returns `r`, `x` and a report. Signs follow `docs/theory.md` §1 and
//! [`contact_laws`](contact_laws#sign-conventions): `r_n ≥ 0` is compression, `x_n ≥ 0` an
//! opening — the same as Siconos' `fc2d` (`u = W r + q`), so [`ReducedProblem::to_json`]
//! writes what `shared/peers/siconos_fc.py` reads. The local laws come through the
//! [`ContactLaw`](contact_laws::ContactLaw) trait (`docs/theory.md` §9); the iteration, the
//! self-adaptive ρ and the stopping rule are described in [`uzawa`].
//!
//! # Examples
//! ```
//! use contact_solver::{ReducedProblem, UzawaSettings, solve_coulomb};
//! let p = ReducedProblem::from_json(r#"{"dim": 2, "W": [2, 0, 0, 2], "q": [-1, 0.5], "mu": [0.2]}"#)?;
//! let sol = solve_coulomb(&p, &UzawaSettings::default())?;
//! assert!((sol.r[0] - 0.5).abs() < 1e-9);        // r_n = −q_n/f
//! assert!((sol.r[1] + 0.2 * sol.r[0]).abs() < 1e-9); // slip: r_t = −μ r_n
//! # Ok::<(), contact_solver::SolverError>(())
//! ```

#![warn(missing_docs)]

pub mod adhesion;
pub mod anderson;
pub mod classic;
pub mod error;
pub mod generate;
pub mod matrix_free;
pub mod newton;
pub mod obstacle;
pub mod output;
pub mod primal;
pub mod reduced;
pub mod scenes;
pub mod simulation;
pub mod uzawa;
pub mod zone;

pub use contact_laws;
pub use error::SolverError;
pub use obstacle::{ArcSide, Obstacle, ObstaclePoint, RigidArc, RigidLine};
pub use output::{HistoryWriter, InterfaceSeries, ReportWriter, write_interface_vtu};
pub use reduced::ReducedProblem;
pub use simulation::{
    ContactRecord, ContactSimulation, Counters, DEFAULT_DENSE_LIMIT, FlexibilityMode,
    InterfaceStatus, SimulationSettings, SkipRules, StepReport, StepResult,
};
pub use uzawa::{Algorithm, Solution, UzawaReport, UzawaSettings, UzawaSolver, solve_coulomb};
pub use zone::{Candidate, ContactZone, Target, recognize};
