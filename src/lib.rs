#![doc = include_str!("../README.md")]
#![warn(missing_docs)]

/// Local contact laws: Coulomb cone, projection onto `K_μ̄`, `b_c`, `b_β`, RCCM.
pub use contact_laws;
/// Contact solver: obstacle recognition, `F*`, Uzawa, adhesion coupling (in progress).
pub use contact_solver;
/// Finite-element core: P1/P2 triangles, idealizations, sparse assembly (in progress).
pub use fem_core;

/// The user guide (`docs/guide.md`), included here so that its examples are compiled and
/// run as doctests.
#[doc = include_str!("../docs/guide.md")]
pub mod guide {}
