//! [`Petsc`]: PETSc (and MPI) initialised for the life of the value, the rank and size of
//! `PETSC_COMM_WORLD`, and the end of every rank when one fails ([`Petsc::or_abort`]).

use crate::error::{PetscError, check};
use crate::ffi;
use std::ffi::{CString, c_char, c_int};
use std::fmt::Display;
use std::io::Write;
use std::ops::Deref;
use std::sync::Arc;

/// PETSc initialised (`PetscInitialize` with the program's arguments, so that PETSc's options
/// such as `-ksp_monitor` or `-pc_type` apply), finalised on drop. One per process; the
/// structures borrow it or share it ([`PetscHandle`]), so they are destroyed before PETSc is
/// finalised.
#[derive(Debug)]
pub struct Petsc {
    rank: usize,
    size: usize,
    /// The argument strings PETSc may keep pointers to.
    _args: Vec<CString>,
}

impl Petsc {
    /// Initialises MPI and PETSc with the program's command-line arguments.
    ///
    /// # Errors
    /// [`PetscError::Call`] if PETSc is already initialised or its initialisation fails.
    pub fn init() -> Result<Self, PetscError> {
        let mut flag = 0;
        // SAFETY: PetscInitialized only writes the flag
        check("PetscInitialized", unsafe {
            ffi::PetscInitialized(&mut flag)
        })?;
        if flag != 0 {
            return Err(PetscError::Call {
                function: "PetscInitialize (PETSc is already initialised: one `Petsc` per process)",
                code: -1,
            });
        }
        let args: Vec<CString> = std::env::args()
            .filter_map(|a| CString::new(a).ok())
            .collect();
        let mut ptrs: Vec<*mut c_char> = args.iter().map(|a| a.as_ptr().cast_mut()).collect();
        ptrs.push(std::ptr::null_mut());
        let mut argc = (ptrs.len() - 1) as c_int;
        let mut argv = ptrs.as_mut_ptr();
        // SAFETY: argc/argv describe NUL-terminated strings that outlive PETSc (kept in
        // `_args`; PETSc copies the option table at initialisation)
        check("PetscInitialize", unsafe {
            ffi::PetscInitialize(&mut argc, &mut argv, std::ptr::null(), std::ptr::null())
        })?;
        let (mut rank, mut size) = (0, 1);
        // SAFETY: PETSC_COMM_WORLD is valid after PetscInitialize
        unsafe {
            check(
                "MPI_Comm_rank",
                ffi::MPI_Comm_rank(ffi::PETSC_COMM_WORLD, &mut rank),
            )?;
            check(
                "MPI_Comm_size",
                ffi::MPI_Comm_size(ffi::PETSC_COMM_WORLD, &mut size),
            )?;
        }
        Ok(Self {
            rank: rank as usize,
            size: size as usize,
            _args: args,
        })
    }

    /// This process's rank in `PETSC_COMM_WORLD`.
    pub fn rank(&self) -> usize {
        self.rank
    }

    /// The number of ranks.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Waits for every rank (`MPI_Barrier`).
    ///
    /// # Errors
    /// [`PetscError::Call`] if MPI fails.
    pub fn barrier(&self) -> Result<(), PetscError> {
        // SAFETY: PETSc is initialised while `self` lives
        check("MPI_Barrier", unsafe {
            ffi::MPI_Barrier(ffi::PETSC_COMM_WORLD)
        })
    }

    /// Prints `error` on stderr with this rank's number and ends **every** rank
    /// (`MPI_Abort`): the others may be waiting in a collective call for this one, and would
    /// hang.
    pub fn abort(&self, error: &dyn Display) -> ! {
        eprintln!("rank {} of {}: error: {error}", self.rank, self.size);
        let _ = std::io::stderr().flush();
        // SAFETY: PETSc is initialised while `self` lives; MPI_Abort does not return
        unsafe {
            ffi::MPI_Abort(ffi::PETSC_COMM_WORLD, 1);
        }
        std::process::exit(1)
    }

    /// Runs `f`; its error, or its panic, ends every rank through [`Petsc::abort`]. The shape
    /// of a distributed program's body:
    ///
    /// ```no_run
    /// # #[cfg(feature = "petsc")] {
    /// use bipotential_petsc::Petsc;
    /// let petsc = Petsc::init().unwrap();
    /// let answer = petsc.or_abort(|| -> Result<f64, String> {
    ///     // build the PetscStructure, the contact simulation, step it ...
    ///     Ok(1.0)
    /// });
    /// # }
    /// ```
    pub fn or_abort<T, E: Display>(&self, f: impl FnOnce() -> Result<T, E>) -> T {
        match std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)) {
            Ok(Ok(value)) => value,
            Ok(Err(e)) => self.abort(&e),
            Err(panic) => {
                let message = panic
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "a panic".to_string());
                self.abort(&format!("panicked: {message}"))
            }
        }
    }
}

impl Drop for Petsc {
    fn drop(&mut self) {
        // SAFETY: initialised in `init`; every PETSc object borrows `self` and is gone
        let code = unsafe { ffi::PetscFinalize() };
        if code != 0 {
            eprintln!("PetscFinalize failed with error code {code}");
        }
    }
}

/// A structure's hold on [`Petsc`]: borrowed (`&'p Petsc`, the caller keeps it alive longer)
/// or shared (`Arc<Petsc>`: PETSc is finalised when its last holder, the caller's or a
/// structure's, is dropped, after the structure's PETSc objects). The constructors of
/// [`PetscStructure`](crate::PetscStructure) take either (`&petsc` or `Arc::clone(&petsc)`);
/// a shared one makes a `PetscStructure<'static>`, which a program can hand to an owner that
/// outlives its scope (`fem_core::ElasticModel::set_reduced_solver`).
#[derive(Debug, Clone)]
pub enum PetscHandle<'p> {
    /// Borrowed for `'p`.
    Borrowed(&'p Petsc),
    /// Shared ownership.
    Shared(Arc<Petsc>),
}

impl Deref for PetscHandle<'_> {
    type Target = Petsc;

    fn deref(&self) -> &Petsc {
        match self {
            PetscHandle::Borrowed(p) => p,
            PetscHandle::Shared(p) => p,
        }
    }
}

impl<'p> From<&'p Petsc> for PetscHandle<'p> {
    fn from(p: &'p Petsc) -> Self {
        PetscHandle::Borrowed(p)
    }
}

impl From<Arc<Petsc>> for PetscHandle<'static> {
    fn from(p: Arc<Petsc>) -> Self {
        PetscHandle::Shared(p)
    }
}
