//! The PETSc objects of one distributed system `K x = b`, owned and destroyed together: the
//! MPIAIJ matrix, the KSP, the distributed vectors, and the two scatters that move a whole
//! vector from rank 0 into the distributed one (`VecScatterCreateToZero`, reversed) and the
//! distributed solution to every rank (`VecScatterCreateToAll`).

use crate::error::{PetscError, check};
use crate::ffi::{self, PetscInt};
use crate::solver::LinearSolver;
use std::ffi::c_int;

/// `value` as a `PetscInt`.
pub(crate) fn int(what: &'static str, value: usize) -> Result<PetscInt, PetscError> {
    PetscInt::try_from(value).map_err(|_| PetscError::TooLarge { what, value })
}

/// One distributed system (module docs).
pub(crate) struct System {
    pub(crate) mat: ffi::Mat,
    ksp: ffi::KSP,
    /// The right-hand side and the solution, distributed.
    pub(crate) b: ffi::Vec,
    x: ffi::Vec,
    to_zero: ffi::VecScatter,
    /// The whole vector on rank 0 (length 0 elsewhere).
    zero: ffi::Vec,
    to_all: ffi::VecScatter,
    /// The whole vector on every rank.
    all: ffi::Vec,
}

impl System {
    /// Creates the matrix with `owned` rows on this rank, `d_nnz`/`o_nnz` entries per owned
    /// row in the diagonal and off-diagonal blocks, ready for `MatSetValues`.
    pub(crate) fn new(
        owned: usize,
        global: usize,
        d_nnz: &[PetscInt],
        o_nnz: &[PetscInt],
    ) -> Result<Self, PetscError> {
        let (n, big_n) = (int("owned rows", owned)?, int("free dofs", global)?);
        let mut s = Self {
            mat: std::ptr::null_mut(),
            ksp: std::ptr::null_mut(),
            b: std::ptr::null_mut(),
            x: std::ptr::null_mut(),
            to_zero: std::ptr::null_mut(),
            zero: std::ptr::null_mut(),
            to_all: std::ptr::null_mut(),
            all: std::ptr::null_mut(),
        };
        // SAFETY: PETSc is initialised (the caller holds a `Petsc`); every handle written
        // here is destroyed once, in Drop (PETSc's destroy functions accept null handles)
        unsafe {
            let comm = ffi::PETSC_COMM_WORLD;
            check("MatCreate", ffi::MatCreate(comm, &mut s.mat))?;
            check("MatSetSizes", ffi::MatSetSizes(s.mat, n, n, big_n, big_n))?;
            check("MatSetType", ffi::MatSetType(s.mat, c"aij".as_ptr()))?;
            check(
                "MatSeqAIJSetPreallocation",
                ffi::MatSeqAIJSetPreallocation(s.mat, 0, d_nnz.as_ptr()),
            )?;
            check(
                "MatMPIAIJSetPreallocation",
                ffi::MatMPIAIJSetPreallocation(s.mat, 0, d_nnz.as_ptr(), 0, o_nnz.as_ptr()),
            )?;
            check("VecCreateMPI", ffi::VecCreateMPI(comm, n, big_n, &mut s.b))?;
            check("VecDuplicate", ffi::VecDuplicate(s.b, &mut s.x))?;
            check(
                "VecScatterCreateToZero",
                ffi::VecScatterCreateToZero(s.b, &mut s.to_zero, &mut s.zero),
            )?;
            check(
                "VecScatterCreateToAll",
                ffi::VecScatterCreateToAll(s.x, &mut s.to_all, &mut s.all),
            )?;
        }
        Ok(s)
    }

    /// Adds a dense block `values` (row-major, `rows.len() × rows.len()`) at `rows × rows`.
    pub(crate) fn add_block(&self, rows: &[PetscInt], values: &[f64]) -> Result<(), PetscError> {
        let n = rows.len() as PetscInt;
        // SAFETY: `values` holds n² entries (the caller's block)
        check("MatSetValues", unsafe {
            ffi::MatSetValues(
                self.mat,
                n,
                rows.as_ptr(),
                n,
                rows.as_ptr(),
                values.as_ptr(),
                ffi::ADD_VALUES,
            )
        })
    }

    /// Gives GAMG the near-null space of the operator: `modes`, whole orthonormal vectors in
    /// the distributed numbering (the same on every rank), of which this rank sets the rows
    /// `first..first + owned`.
    pub(crate) fn set_near_null_space(
        &self,
        modes: &[Vec<f64>],
        first: usize,
    ) -> Result<(), PetscError> {
        let mut vecs = vec![std::ptr::null_mut(); modes.len()];
        // SAFETY: `b` exists; each duplicate's local array holds this rank's rows; the null
        // space keeps its own references, so the vectors are destroyed here
        unsafe {
            let mut r = Ok(());
            for (v, mode) in vecs.iter_mut().zip(modes) {
                r = r.and_then(|()| check("VecDuplicate", ffi::VecDuplicate(self.b, v)));
                let mut len: PetscInt = 0;
                r = r.and_then(|()| check("VecGetLocalSize", ffi::VecGetLocalSize(*v, &mut len)));
                let mut a = std::ptr::null_mut();
                r = r.and_then(|()| check("VecGetArray", ffi::VecGetArray(*v, &mut a)));
                if r.is_ok() && len > 0 {
                    std::slice::from_raw_parts_mut(a, len as usize)
                        .copy_from_slice(&mode[first..first + len as usize]);
                }
                r = r.and_then(|()| check("VecRestoreArray", ffi::VecRestoreArray(*v, &mut a)));
            }
            let mut space = std::ptr::null_mut();
            r = r.and_then(|()| {
                check(
                    "MatNullSpaceCreate",
                    ffi::MatNullSpaceCreate(
                        ffi::PETSC_COMM_WORLD,
                        0,
                        vecs.len() as PetscInt,
                        vecs.as_ptr(),
                        &mut space,
                    ),
                )
            });
            r = r.and_then(|()| {
                check(
                    "MatSetNearNullSpace",
                    ffi::MatSetNearNullSpace(self.mat, space),
                )
            });
            ffi::MatNullSpaceDestroy(&mut space);
            for v in &mut vecs {
                ffi::VecDestroy(v);
            }
            r
        }
    }

    /// Ends the assembly (communicates the entries set on other ranks' rows) and sets up the
    /// KSP and its preconditioner (GAMG's hierarchy or MUMPS's factorisation), once.
    pub(crate) fn assemble_and_set_up(&mut self, solver: LinearSolver) -> Result<(), PetscError> {
        // SAFETY: handles created in `new`
        unsafe {
            check(
                "MatAssemblyBegin",
                ffi::MatAssemblyBegin(self.mat, ffi::MAT_FINAL_ASSEMBLY),
            )?;
            check(
                "MatAssemblyEnd",
                ffi::MatAssemblyEnd(self.mat, ffi::MAT_FINAL_ASSEMBLY),
            )?;
            check(
                "KSPCreate",
                ffi::KSPCreate(ffi::PETSC_COMM_WORLD, &mut self.ksp),
            )?;
            check(
                "KSPSetOperators",
                ffi::KSPSetOperators(self.ksp, self.mat, self.mat),
            )?;
            let mut pc = std::ptr::null_mut();
            check("KSPGetPC", ffi::KSPGetPC(self.ksp, &mut pc))?;
            match solver {
                LinearSolver::CgGamg {
                    rtol,
                    max_iterations,
                } => {
                    check("KSPSetType", ffi::KSPSetType(self.ksp, c"cg".as_ptr()))?;
                    check("PCSetType", ffi::PCSetType(pc, c"gamg".as_ptr()))?;
                    check(
                        "KSPSetNormType",
                        ffi::KSPSetNormType(self.ksp, ffi::KSP_NORM_UNPRECONDITIONED),
                    )?;
                    // abstol 0: the relative test alone (a zero right-hand side converges
                    // at once on its zero residual)
                    check(
                        "KSPSetTolerances",
                        ffi::KSPSetTolerances(
                            self.ksp,
                            rtol,
                            0.0,
                            ffi::PETSC_DEFAULT as f64,
                            int("max_iterations", max_iterations)?,
                        ),
                    )?;
                }
                LinearSolver::Mumps => {
                    check("KSPSetType", ffi::KSPSetType(self.ksp, c"preonly".as_ptr()))?;
                    check("PCSetType", ffi::PCSetType(pc, c"lu".as_ptr()))?;
                    check(
                        "PCFactorSetMatSolverType",
                        ffi::PCFactorSetMatSolverType(pc, c"mumps".as_ptr()),
                    )?;
                }
            }
            check("KSPSetFromOptions", ffi::KSPSetFromOptions(self.ksp))?;
            check("KSPSetUp", ffi::KSPSetUp(self.ksp))?;
        }
        Ok(())
    }

    /// Zeroes `b` and fills it from rank 0's whole vector: `fill(whole)` runs on rank 0 only,
    /// on the vector in the distributed numbering (the others' data is not read: rank 0's is
    /// broadcast, so every rank solves the same system).
    pub(crate) fn load_from_rank_0(&self, fill: impl FnOnce(&mut [f64])) -> Result<(), PetscError> {
        // SAFETY: handles created in `new`; the array is restored before the scatter
        unsafe {
            let mut len: PetscInt = 0;
            check("VecGetLocalSize", ffi::VecGetLocalSize(self.zero, &mut len))?;
            if len > 0 {
                let mut a = std::ptr::null_mut();
                check("VecGetArray", ffi::VecGetArray(self.zero, &mut a))?;
                let whole = std::slice::from_raw_parts_mut(a, len as usize);
                // the vector keeps the previous right-hand side: `fill` starts from zero
                whole.fill(0.0);
                fill(whole);
                check("VecRestoreArray", ffi::VecRestoreArray(self.zero, &mut a))?;
            }
            check("VecSet", ffi::VecSet(self.b, 0.0))?;
            self.scatter(self.to_zero, self.zero, self.b, ffi::SCATTER_REVERSE)
        }
    }

    /// Adds `values` at `rows` of `b` (any rank's rows) and ends the vector's assembly
    /// (collective: every rank calls it, with its own entries).
    pub(crate) fn add_to_b(&self, rows: &[PetscInt], values: &[f64]) -> Result<(), PetscError> {
        // SAFETY: rows and values have the same length
        unsafe {
            check(
                "VecSetValues",
                ffi::VecSetValues(
                    self.b,
                    rows.len() as PetscInt,
                    rows.as_ptr(),
                    values.as_ptr(),
                    ffi::ADD_VALUES,
                ),
            )?;
            check("VecAssemblyBegin", ffi::VecAssemblyBegin(self.b))?;
            check("VecAssemblyEnd", ffi::VecAssemblyEnd(self.b))
        }
    }

    /// Solves `K x = b`, then gives the whole `x` (distributed numbering) to `read` on every
    /// rank. Returns the iterations.
    pub(crate) fn solve(&self, read: impl FnOnce(&[f64])) -> Result<usize, PetscError> {
        // SAFETY: handles created in `new`, the KSP set up in `assemble_and_set_up`
        unsafe {
            check("KSPSolve", ffi::KSPSolve(self.ksp, self.b, self.x))?;
        }
        let its = self.converged()?;
        // SAFETY: `to_all` scatters `x` into `all`, both created in `new`
        unsafe {
            self.scatter(self.to_all, self.x, self.all, ffi::SCATTER_FORWARD)?;
            with_array(self.all, |whole| read(whole))?;
        }
        Ok(its)
    }

    /// Solves `K X = B` for `k` columns at once: `KSPMatSolve` on MPI dense matrices (MUMPS
    /// applies one multi-right-hand-side solve). For the direct solver only: a Krylov method
    /// would iterate column by column inside PETSc and report the last column's convergence
    /// alone. `fill(whole)` runs on rank 0 only, on `B` whole and row-major in the
    /// distributed numbering (`whole[k·r + c]`, zeroed first), which one scatter moves to the
    /// ranks; one scatter gathers `X`, laid out alike, whole on every rank for `read`.
    /// Returns the iterations of the last column.
    pub(crate) fn solve_block(
        &self,
        k: usize,
        fill: impl FnOnce(&mut [f64]),
        read: impl FnOnce(&[f64]),
    ) -> Result<usize, PetscError> {
        let mut t = Block::default();
        // SAFETY: handles created in `new`, the KSP set up; every handle of `t` is destroyed
        // once, in its Drop; each array is restored before its object is used again
        unsafe {
            let comm = ffi::PETSC_COMM_WORLD;
            let (mut n, mut big_n): (PetscInt, PetscInt) = (0, 0);
            check("VecGetLocalSize", ffi::VecGetLocalSize(self.b, &mut n))?;
            check(
                "VecGetLocalSize",
                ffi::VecGetLocalSize(self.all, &mut big_n),
            )?;
            let (n, big_n) = (n as usize, big_n as usize);
            let columns = int("columns", k)?;
            let local = int("block entries", n * k)?;
            let global = int("block entries", big_n * k)?;
            check(
                "VecCreateMPI",
                ffi::VecCreateMPI(comm, local, global, &mut t.big),
            )?;
            check(
                "VecScatterCreateToZero",
                ffi::VecScatterCreateToZero(t.big, &mut t.to_zero, &mut t.zero),
            )?;
            let mut fill = Some(fill);
            with_array(t.zero, |whole| {
                if !whole.is_empty() {
                    whole.fill(0.0);
                    (fill.take().expect("filled once"))(whole);
                }
            })?;
            self.scatter(t.to_zero, t.zero, t.big, ffi::SCATTER_REVERSE)?;
            for m in [&mut t.b, &mut t.x] {
                check(
                    "MatCreateDense",
                    ffi::MatCreateDense(
                        comm,
                        n as PetscInt,
                        ffi::PETSC_DECIDE,
                        big_n as PetscInt,
                        columns,
                        std::ptr::null_mut(),
                        m,
                    ),
                )?;
            }
            let mut lda: PetscInt = 0;
            check("MatDenseGetLDA", ffi::MatDenseGetLDA(t.b, &mut lda))?;
            let lda = lda as usize;
            with_array(t.big, |rows| {
                with_dense(t.b, lda * k, |m| {
                    for (i, row) in rows.chunks_exact(k).enumerate() {
                        for (c, &v) in row.iter().enumerate() {
                            m[c * lda + i] = v;
                        }
                    }
                })
            })??;
            for m in [t.b, t.x] {
                check(
                    "MatAssemblyBegin",
                    ffi::MatAssemblyBegin(m, ffi::MAT_FINAL_ASSEMBLY),
                )?;
                check(
                    "MatAssemblyEnd",
                    ffi::MatAssemblyEnd(m, ffi::MAT_FINAL_ASSEMBLY),
                )?;
            }
            check("KSPMatSolve", ffi::KSPMatSolve(self.ksp, t.b, t.x))?;
            let its = self.converged()?;
            let mut lda: PetscInt = 0;
            check("MatDenseGetLDA", ffi::MatDenseGetLDA(t.x, &mut lda))?;
            let lda = lda as usize;
            with_array(t.big, |rows| {
                with_dense(t.x, lda * k, |m| {
                    for (i, row) in rows.chunks_exact_mut(k).enumerate() {
                        for (c, v) in row.iter_mut().enumerate() {
                            *v = m[c * lda + i];
                        }
                    }
                })
            })??;
            check(
                "VecScatterCreateToAll",
                ffi::VecScatterCreateToAll(t.big, &mut t.to_all, &mut t.all),
            )?;
            self.scatter(t.to_all, t.big, t.all, ffi::SCATTER_FORWARD)?;
            let mut read = Some(read);
            with_array(t.all, |whole| (read.take().expect("read once"))(whole))?;
            Ok(its)
        }
    }

    /// The iterations of the last solve, or [`PetscError::NotConverged`].
    fn converged(&self) -> Result<usize, PetscError> {
        let mut reason: c_int = 0;
        let mut its: PetscInt = 0;
        // SAFETY: the KSP exists
        unsafe {
            check(
                "KSPGetConvergedReason",
                ffi::KSPGetConvergedReason(self.ksp, &mut reason),
            )?;
            check(
                "KSPGetIterationNumber",
                ffi::KSPGetIterationNumber(self.ksp, &mut its),
            )?;
        }
        if reason < 0 {
            return Err(PetscError::NotConverged {
                reason,
                iterations: its as i64,
            });
        }
        Ok(its as usize)
    }

    /// `VecScatterBegin` + `VecScatterEnd` with `INSERT_VALUES`.
    unsafe fn scatter(
        &self,
        ctx: ffi::VecScatter,
        from: ffi::Vec,
        to: ffi::Vec,
        dir: c_int,
    ) -> Result<(), PetscError> {
        // SAFETY: the caller passes handles of this system
        unsafe {
            check(
                "VecScatterBegin",
                ffi::VecScatterBegin(ctx, from, to, ffi::INSERT_VALUES, dir),
            )?;
            check(
                "VecScatterEnd",
                ffi::VecScatterEnd(ctx, from, to, ffi::INSERT_VALUES, dir),
            )
        }
    }
}

impl Drop for System {
    fn drop(&mut self) {
        // SAFETY: each handle is null or owned by `self`; the destroy functions null them
        unsafe {
            ffi::KSPDestroy(&mut self.ksp);
            ffi::VecScatterDestroy(&mut self.to_zero);
            ffi::VecScatterDestroy(&mut self.to_all);
            ffi::VecDestroy(&mut self.zero);
            ffi::VecDestroy(&mut self.all);
            ffi::VecDestroy(&mut self.b);
            ffi::VecDestroy(&mut self.x);
            ffi::MatDestroy(&mut self.mat);
        }
    }
}

/// The temporary PETSc objects of one [`System::solve_block`], destroyed together.
struct Block {
    /// `B`, then `X`, row-major and distributed as the rows are.
    big: ffi::Vec,
    to_zero: ffi::VecScatter,
    zero: ffi::Vec,
    to_all: ffi::VecScatter,
    all: ffi::Vec,
    b: ffi::Mat,
    x: ffi::Mat,
}

impl Default for Block {
    fn default() -> Self {
        let null = std::ptr::null_mut();
        Self {
            big: null,
            to_zero: null,
            zero: null,
            to_all: null,
            all: null,
            b: null,
            x: null,
        }
    }
}

impl Drop for Block {
    fn drop(&mut self) {
        // SAFETY: each handle is null or owned by `self`; the destroy functions null them
        unsafe {
            ffi::VecScatterDestroy(&mut self.to_zero);
            ffi::VecScatterDestroy(&mut self.to_all);
            ffi::VecDestroy(&mut self.zero);
            ffi::VecDestroy(&mut self.all);
            ffi::VecDestroy(&mut self.big);
            ffi::MatDestroy(&mut self.b);
            ffi::MatDestroy(&mut self.x);
        }
    }
}

/// Runs `f` on the local array of `v` (empty where the rank holds none), then restores it.
///
/// # Safety
/// `v` is a live vector.
unsafe fn with_array<R>(v: ffi::Vec, f: impl FnOnce(&mut [f64]) -> R) -> Result<R, PetscError> {
    // SAFETY: the caller's vector; the slice lives until the array is restored
    unsafe {
        let mut len: PetscInt = 0;
        check("VecGetLocalSize", ffi::VecGetLocalSize(v, &mut len))?;
        let mut a = std::ptr::null_mut();
        check("VecGetArray", ffi::VecGetArray(v, &mut a))?;
        let r = if len > 0 {
            f(std::slice::from_raw_parts_mut(a, len as usize))
        } else {
            f(&mut [])
        };
        check("VecRestoreArray", ffi::VecRestoreArray(v, &mut a))?;
        Ok(r)
    }
}

/// Runs `f` on the local column-major array of the dense `m` (`len` = lda × columns
/// entries), then restores it.
///
/// # Safety
/// `m` is a live dense matrix whose local array holds `len` entries.
unsafe fn with_dense<R>(
    m: ffi::Mat,
    len: usize,
    f: impl FnOnce(&mut [f64]) -> R,
) -> Result<R, PetscError> {
    // SAFETY: the caller's matrix and length
    unsafe {
        let mut a = std::ptr::null_mut();
        check("MatDenseGetArray", ffi::MatDenseGetArray(m, &mut a))?;
        let r = if len > 0 {
            f(std::slice::from_raw_parts_mut(a, len))
        } else {
            f(&mut [])
        };
        check("MatDenseRestoreArray", ffi::MatDenseRestoreArray(m, &mut a))?;
        Ok(r)
    }
}
