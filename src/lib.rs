#![doc = include_str!("../README.md")]
#![warn(missing_docs)]

/// Local contact laws: Coulomb cone, projection onto `K_μ̄`, `b_c`, `b_β`, RCCM.
pub use contact_laws;
/// Contact solver: the reduced problem `x = W r + q` and its algorithms (`local`), and the FE
/// coupling (`coupling`): obstacles, zones, `F*` or the active set, adhesion, load stepping.
pub use contact_solver;
/// Finite-element core: meshes, P1/P2 triangles, idealizations, sparse assembly, the
/// `Structure` trait.
pub use fem_core;
/// The `faer` that fem-core and contact-solver are built with (dense and sparse matrices in
/// the [`Structure`](fem_core::Structure) trait): use it to implement the trait, so that your
/// code and the library share one version.
pub use fem_core::faer;

/// The user guide (`docs/guide.md`), included here so that its examples are compiled and
/// run as doctests.
#[doc = include_str!("../docs/guide.md")]
pub mod guide {}
