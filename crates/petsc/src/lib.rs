//! The bulk of a contact model solved by PETSc under MPI, the contact interface kept whole.
//!
//! With the feature `petsc` (the system PETSc 3.18 and Open MPI: Debian's
//! `libpetsc-real-dev` and `libopenmpi-dev`), `PetscStructure` implements fem-core's
//! [`Structure`](fem_core::Structure) (3D, or 2D in plane strain, plane stress or
//! axisymmetry) with a stiffness assembled as a distributed PETSc MPIAIJ matrix from
//! fem-core's element kernels, each rank assembling its own elements of a [`Partition`]
//! (slabs or a recursive bisection of the element graph: [`Partitioner`]), and solved by CG with algebraic multigrid (or MUMPS: `LinearSolver`).
//! The contact solver (`contact-solver`) runs unchanged on every rank: the structure takes
//! its right-hand sides from rank 0 and returns the same solution to every rank, so
//! candidates, `F*` and the local solve are rank 0's, broadcast.
//!
//! A distributed program is the serial one, run by `mpirun -n N`, with three changes:
//! `Petsc::init` first, `PetscStructure::new` (or `PetscStructure::plane` in 2D) in place of
//! `SolidModel::new` (or `LinearElasticModel::new`), and the body inside `Petsc::or_abort` so
//! that a rank that fails ends every rank with its error instead of leaving the others
//! waiting. `examples/petsc_check.rs` is such a program.
//!
//! Without the feature the crate holds the partition only (pure Rust), so that the default
//! build and `cargo test --workspace` need neither MPI nor PETSc.
//!
//! The C functions used are bound by hand (`ffi`), the version checked at build time.

#![warn(missing_docs)]

pub mod partition;

pub use partition::{Partition, Partitioner};

#[cfg(feature = "petsc")]
mod assembly;
#[cfg(feature = "petsc")]
mod error;
#[cfg(feature = "petsc")]
mod ffi;
#[cfg(feature = "petsc")]
mod linalg;
#[cfg(feature = "petsc")]
mod runtime;
#[cfg(feature = "petsc")]
mod solver;
#[cfg(feature = "petsc")]
mod structure;

#[cfg(feature = "petsc")]
pub use error::PetscError;
#[cfg(feature = "petsc")]
pub use runtime::{Petsc, PetscHandle};
#[cfg(feature = "petsc")]
pub use solver::LinearSolver;
#[cfg(feature = "petsc")]
pub use structure::{BATCH_COLUMNS, PetscStructure};
