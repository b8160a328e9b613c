//! The few C functions of PETSc 3.18 (and of MPI) that this crate calls, bound by hand
//! (`petsc.h`, `mpi.h`). Object handles are opaque pointers; enums are `int`s with the values
//! of PETSc 3.18's headers. `build.rs` checks the version and the index width.

#![allow(
    non_camel_case_types,
    non_snake_case,
    missing_docs,
    clippy::upper_case_acronyms
)]

use std::ffi::{c_char, c_int, c_void};

/// `PetscInt`: 32 bits unless PETSc is built with 64-bit indices.
#[cfg(not(petsc_int64))]
pub type PetscInt = i32;
/// `PetscInt`: 32 bits unless PETSc is built with 64-bit indices.
#[cfg(petsc_int64)]
pub type PetscInt = i64;
pub type PetscErrorCode = c_int;
pub type PetscBool = c_int;
pub type MPI_Comm = *mut c_void;
pub type Mat = *mut c_void;
pub type Vec = *mut c_void;
pub type KSP = *mut c_void;
pub type PC = *mut c_void;
pub type VecScatter = *mut c_void;
pub type MatNullSpace = *mut c_void;

pub const PETSC_DEFAULT: PetscInt = -2;
pub const PETSC_DECIDE: PetscInt = -1;
pub const INSERT_VALUES: c_int = 1;
pub const ADD_VALUES: c_int = 2;
pub const SCATTER_FORWARD: c_int = 0;
pub const SCATTER_REVERSE: c_int = 1;
pub const MAT_FINAL_ASSEMBLY: c_int = 0;
pub const KSP_NORM_UNPRECONDITIONED: c_int = 2;

unsafe extern "C" {
    pub static mut PETSC_COMM_WORLD: MPI_Comm;

    pub fn PetscInitialize(
        argc: *mut c_int,
        argv: *mut *mut *mut c_char,
        file: *const c_char,
        help: *const c_char,
    ) -> PetscErrorCode;
    pub fn PetscInitialized(flag: *mut PetscBool) -> PetscErrorCode;
    pub fn PetscFinalize() -> PetscErrorCode;

    pub fn MPI_Comm_rank(comm: MPI_Comm, rank: *mut c_int) -> c_int;
    pub fn MPI_Comm_size(comm: MPI_Comm, size: *mut c_int) -> c_int;
    pub fn MPI_Abort(comm: MPI_Comm, code: c_int) -> c_int;
    pub fn MPI_Barrier(comm: MPI_Comm) -> c_int;

    pub fn MatCreate(comm: MPI_Comm, mat: *mut Mat) -> PetscErrorCode;
    pub fn MatSetSizes(
        mat: Mat,
        m: PetscInt,
        n: PetscInt,
        big_m: PetscInt,
        big_n: PetscInt,
    ) -> PetscErrorCode;
    pub fn MatSetType(mat: Mat, kind: *const c_char) -> PetscErrorCode;
    pub fn MatSeqAIJSetPreallocation(
        mat: Mat,
        nz: PetscInt,
        nnz: *const PetscInt,
    ) -> PetscErrorCode;
    pub fn MatMPIAIJSetPreallocation(
        mat: Mat,
        d_nz: PetscInt,
        d_nnz: *const PetscInt,
        o_nz: PetscInt,
        o_nnz: *const PetscInt,
    ) -> PetscErrorCode;
    pub fn MatSetValues(
        mat: Mat,
        m: PetscInt,
        rows: *const PetscInt,
        n: PetscInt,
        cols: *const PetscInt,
        values: *const f64,
        mode: c_int,
    ) -> PetscErrorCode;
    pub fn MatAssemblyBegin(mat: Mat, kind: c_int) -> PetscErrorCode;
    pub fn MatAssemblyEnd(mat: Mat, kind: c_int) -> PetscErrorCode;
    pub fn MatDestroy(mat: *mut Mat) -> PetscErrorCode;
    pub fn MatCreateDense(
        comm: MPI_Comm,
        m: PetscInt,
        n: PetscInt,
        big_m: PetscInt,
        big_n: PetscInt,
        data: *mut f64,
        mat: *mut Mat,
    ) -> PetscErrorCode;
    pub fn MatDenseGetArray(mat: Mat, a: *mut *mut f64) -> PetscErrorCode;
    pub fn MatDenseRestoreArray(mat: Mat, a: *mut *mut f64) -> PetscErrorCode;
    pub fn MatDenseGetLDA(mat: Mat, lda: *mut PetscInt) -> PetscErrorCode;
    pub fn MatNullSpaceCreate(
        comm: MPI_Comm,
        has_constant: PetscBool,
        n: PetscInt,
        vecs: *const Vec,
        space: *mut MatNullSpace,
    ) -> PetscErrorCode;
    pub fn MatSetNearNullSpace(mat: Mat, space: MatNullSpace) -> PetscErrorCode;
    pub fn MatNullSpaceDestroy(space: *mut MatNullSpace) -> PetscErrorCode;

    pub fn VecCreateMPI(
        comm: MPI_Comm,
        n: PetscInt,
        big_n: PetscInt,
        v: *mut Vec,
    ) -> PetscErrorCode;
    pub fn VecDuplicate(v: Vec, new: *mut Vec) -> PetscErrorCode;
    pub fn VecSet(v: Vec, value: f64) -> PetscErrorCode;
    pub fn VecSetValues(
        v: Vec,
        n: PetscInt,
        ix: *const PetscInt,
        y: *const f64,
        mode: c_int,
    ) -> PetscErrorCode;
    pub fn VecAssemblyBegin(v: Vec) -> PetscErrorCode;
    pub fn VecAssemblyEnd(v: Vec) -> PetscErrorCode;
    pub fn VecGetArray(v: Vec, a: *mut *mut f64) -> PetscErrorCode;
    pub fn VecRestoreArray(v: Vec, a: *mut *mut f64) -> PetscErrorCode;
    pub fn VecGetLocalSize(v: Vec, n: *mut PetscInt) -> PetscErrorCode;
    pub fn VecDestroy(v: *mut Vec) -> PetscErrorCode;
    pub fn VecScatterCreateToZero(v: Vec, ctx: *mut VecScatter, out: *mut Vec) -> PetscErrorCode;
    pub fn VecScatterCreateToAll(v: Vec, ctx: *mut VecScatter, out: *mut Vec) -> PetscErrorCode;
    pub fn VecScatterBegin(
        ctx: VecScatter,
        x: Vec,
        y: Vec,
        mode: c_int,
        dir: c_int,
    ) -> PetscErrorCode;
    pub fn VecScatterEnd(
        ctx: VecScatter,
        x: Vec,
        y: Vec,
        mode: c_int,
        dir: c_int,
    ) -> PetscErrorCode;
    pub fn VecScatterDestroy(ctx: *mut VecScatter) -> PetscErrorCode;

    pub fn KSPCreate(comm: MPI_Comm, ksp: *mut KSP) -> PetscErrorCode;
    pub fn KSPSetOperators(ksp: KSP, a: Mat, p: Mat) -> PetscErrorCode;
    pub fn KSPSetType(ksp: KSP, kind: *const c_char) -> PetscErrorCode;
    pub fn KSPGetPC(ksp: KSP, pc: *mut PC) -> PetscErrorCode;
    pub fn PCSetType(pc: PC, kind: *const c_char) -> PetscErrorCode;
    pub fn PCFactorSetMatSolverType(pc: PC, kind: *const c_char) -> PetscErrorCode;
    pub fn KSPSetTolerances(
        ksp: KSP,
        rtol: f64,
        abstol: f64,
        dtol: f64,
        maxits: PetscInt,
    ) -> PetscErrorCode;
    pub fn KSPSetNormType(ksp: KSP, norm: c_int) -> PetscErrorCode;
    pub fn KSPSetFromOptions(ksp: KSP) -> PetscErrorCode;
    pub fn KSPSetUp(ksp: KSP) -> PetscErrorCode;
    pub fn KSPSolve(ksp: KSP, b: Vec, x: Vec) -> PetscErrorCode;
    pub fn KSPMatSolve(ksp: KSP, b: Mat, x: Mat) -> PetscErrorCode;
    pub fn KSPGetConvergedReason(ksp: KSP, reason: *mut c_int) -> PetscErrorCode;
    pub fn KSPGetIterationNumber(ksp: KSP, its: *mut PetscInt) -> PetscErrorCode;
    pub fn KSPDestroy(ksp: *mut KSP) -> PetscErrorCode;
}
