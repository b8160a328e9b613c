//! FCLIB HDF5 files in and out (feature `fclib`): the frictional-contact interchange format of
//! Acary, Brémond, Koziara and Pérignon (INRIA RT-0444, 2014), read and written by Siconos.
//!
//! ```text
//! local problem (group fclib_local):       u = W r + q,   per contact α: r_α ∈ K_μα,
//!                                          û_α = u_α + μ_α ‖u_αT‖ n ∈ K*_μα,  û ⊥ r
//! global problem (group fclib_global):     M v = H r + f,   u = Hᵀ v + w
//!   condensed on reading:                  W = Hᵀ M⁻¹ H,    q = Hᵀ M⁻¹ f + w
//! ```
//! Per contact the local frame is normal first, then the tangent(s) (`spacedim` = 2 or 3
//! unknowns): the order and the signs of [`ReducedProblem`] (`x = W r + q`, `r_n ≥ 0` in
//! compression, `x_n ≥ 0` an opening; see [`contact_laws`](contact_laws#sign-conventions)).
//! `H` is `n × m` (`n` dofs, `m = spacedim · n_c`), as in `fclib.h` and Siconos'
//! `GlobalFrictionContactProblem` (whose `q` is FCLIB's `f` and `b` FCLIB's `w`).
//!
//! # Layout (as `fclib.c` writes it)
//! ```text
//! fclib_local/spacedim                     int[1], 2 or 3
//! fclib_local/W/{m, n, nz, nzmax}          int[1] each
//! fclib_local/W/{p, i}                     int[], see below
//! fclib_local/W/x                          double[nzmax]
//! fclib_local/vectors/{q, mu}              double[m], double[m / spacedim]
//! fclib_local/info/...                     optional strings (not read)
//! solution/{r, u}                          double[m] (and v, double[n], for a global problem)
//! guesses/number_of_guesses, guesses/1..k  as solution
//! ```
//! `nz = -1`: compressed columns (`p` column pointers, `i` row indices); `nz = -2`: compressed
//! rows (`p` row pointers, `i` column indices); `nz ≥ 0`: `nz` triplets, `i` rows and `p`
//! columns (CSparse's convention, which Siconos follows). Duplicates are summed. Indices are
//! read from any integer type (h5py writes 64-bit ones), values from any number type.
//!
//! A local `W` with fewer than `m²/4` entries is read into the sparse storage
//! ([`ReducedProblem::from_triplets`]), a denser one dense. A global problem whose `M` falls
//! into several diagonal blocks (rigid bodies, several FE bodies) is condensed block by block
//! at the cost of one factorisation per block, and its `W` stored by the same rule; one with a
//! single block (one FE body) is condensed dense. A sparse problem is written from its
//! compressed rows, never densified.
//!
//! We write `fclib_local` with `W` in compressed rows ([`write_fclib`]) or any form
//! ([`write_fclib_as`]), every entry that is not `+0.0` kept, integers as 32-bit C `int`s like
//! `fclib.c`. The mixed problems (`fclib_local/V`, `R`; `fclib_global/G`, `b`) are refused.
//!
//! # Hostile files
//! Every size is checked before a dataset is read, and against the sizes it depends on (`q`
//! has `W/m` entries, `mu` has `m / spacedim`, `p` has `n + 1` for compressed columns, …);
//! every index is checked against its bound and every value for finiteness: a bad file is a
//! [`SolverError::Fclib`] naming the dataset, never a panic. Dense matrices are limited to
//! [`MAX_DENSE_ENTRIES`].

mod blocks;
mod global;
mod h5;
mod mass;
mod sparse;

pub use sparse::{MAX_DENSE_ENTRIES, SparseForm};

use super::asymmetry::Asymmetry;
use super::delassus::WView;
use super::problem::ReducedProblem;
use crate::error::SolverError;
use h5::{H5File, join};
use hdf5::{File, Group};
use sparse::RawSparse;
use std::path::Path;

/// A solution or an initial guess stored in an FCLIB file.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct FclibSolution {
    /// The reactions `r` (`m` entries).
    pub r: Vec<f64>,
    /// The local velocities (or displacements) `u = W r + q`, when stored.
    pub u: Option<Vec<f64>>,
    /// The global velocities `v` (global problems), when stored.
    pub v: Option<Vec<f64>>,
}

/// Where the problem of an FCLIB file came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum FclibSource {
    /// The group `fclib_local`, read as it is.
    Local,
    /// The group `fclib_global`, condensed to `W = Hᵀ M⁻¹ H`, `q = Hᵀ M⁻¹ f + w`.
    Global {
        /// The number of global unknowns `n` (rows of `M`).
        dofs: usize,
    },
}

/// An FCLIB file read by [`read_fclib`]: the reduced problem and what else the file holds.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct FclibProblem {
    /// The reduced problem `x = W r + q`.
    pub problem: ReducedProblem,
    /// FCLIB's `spacedim`: unknowns per contact (2 or 3).
    pub spacedim: usize,
    /// Local, or global and condensed.
    pub source: FclibSource,
    /// The group `solution`, when present.
    pub solution: Option<FclibSolution>,
    /// The groups `guesses/1` … `guesses/k`.
    pub guesses: Vec<FclibSolution>,
}

/// Reads an FCLIB file: its local problem, or its global problem condensed (see the
/// [module docs](self) for the layout and the formulas), with the stored solution and guesses.
///
/// # Errors
/// [`SolverError::Fclib`] naming the group or dataset for a file that cannot be opened, a
/// missing group or dataset, a `spacedim` other than 2 or 3, inconsistent sizes, an index out
/// of range, a value that is not finite, a singular `M`, or a mixed problem; then those of
/// [`ReducedProblem::with_asymmetry`] with [`Asymmetry::Keep`] (a diagonal block that is not
/// positive definite, a negative `μ`): a non-symmetric `W`, as multibody codes write them, is
/// kept as given (not symmetrised: [`ReducedProblem::is_symmetric`] says which), so the
/// answer is the one of the problem in the file.
///
/// # Examples
/// ```
/// use contact_solver::ReducedProblem;
/// use contact_solver::local::fclib::{read_fclib, write_fclib};
/// let p = ReducedProblem::new(vec![2.0, 0.0, 0.0, 1.0], vec![-1.0, 0.5], vec![0.3])?;
/// let path = std::env::temp_dir().join("fclib_doc_example.hdf5");
/// write_fclib(&path, &p, None)?;
/// let back = read_fclib(&path)?;
/// assert_eq!(back.problem, p);
/// assert_eq!(back.spacedim, 2);
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
pub fn read_fclib(path: impl AsRef<Path>) -> Result<FclibProblem, SolverError> {
    let path = path.as_ref();
    let shown = path.display().to_string();
    let f = H5File { path: &shown };
    let file = File::open(path).map_err(|e| f.h5_error("cannot open it as an HDF5 file", e))?;
    let (problem, spacedim, source) = if file.link_exists("fclib_local") {
        read_local(&f, &file)?
    } else if file.link_exists("fclib_global") {
        read_global(&f, &file)?
    } else {
        return Err(f.error("neither group `fclib_local` nor `fclib_global` is present"));
    };
    let m = problem.size();
    let dofs = match source {
        FclibSource::Local => 0,
        FclibSource::Global { dofs } => dofs,
    };
    let solution = if file.link_exists("solution") {
        let g = f.group(&file, "", "solution")?;
        Some(read_solution(&f, &g, "solution", m, dofs)?)
    } else {
        None
    };
    let guesses = if file.link_exists("guesses") {
        read_guesses(&f, &file, m, dofs)?
    } else {
        Vec::new()
    };
    Ok(FclibProblem {
        problem,
        spacedim,
        source,
        solution,
        guesses,
    })
}

/// `spacedim` of group `at`, 2 or 3.
fn read_spacedim(f: &H5File<'_>, g: &Group, at: &str) -> Result<usize, SolverError> {
    let d = f.int(g, at, "spacedim")?;
    match d {
        2 | 3 => Ok(d as usize),
        _ => Err(f.error(format!(
            "`{at}/spacedim` = {d}: the space dimension must be 2 or 3"
        ))),
    }
}

/// Checks that `m` (named `what`) is a multiple of `spacedim`; returns `n_c`.
fn contacts(f: &H5File<'_>, what: &str, m: usize, spacedim: usize) -> Result<usize, SolverError> {
    if !m.is_multiple_of(spacedim) {
        return Err(f.error(format!(
            "`{what}` = {m} is not a multiple of spacedim = {spacedim}"
        )));
    }
    Ok(m / spacedim)
}

/// Refuses the groups of FCLIB's mixed problems (equality constraints).
fn refuse_mixed(f: &H5File<'_>, g: &Group, at: &str, names: &[&str]) -> Result<(), SolverError> {
    match names.iter().find(|n| g.link_exists(n)) {
        Some(n) => Err(f.error(format!(
            "`{at}/{n}` is present: FCLIB's mixed problems (with equality constraints) are not \
             supported"
        ))),
        None => Ok(()),
    }
}

fn read_local(
    f: &H5File<'_>,
    file: &File,
) -> Result<(ReducedProblem, usize, FclibSource), SolverError> {
    let at = "fclib_local";
    let g = f.group(file, "", at)?;
    let spacedim = read_spacedim(f, &g, at)?;
    refuse_mixed(f, &g, at, &["V", "R"])?;
    let w_raw = f.matrix(&g, at, "W")?;
    if w_raw.m != w_raw.n {
        return Err(f.error(format!(
            "`{at}/W` is {} x {}: it must be square",
            w_raw.m, w_raw.n
        )));
    }
    let m = w_raw.m;
    let nc = contacts(f, "fclib_local/W/m", m, spacedim)?;
    let v = f.group(&g, at, "vectors")?;
    let q = f.reals(&v, "fclib_local/vectors", "q", m)?;
    let mu = f.reals(&v, "fclib_local/vectors", "mu", nc)?;
    // sparse enough (fewer than m²/4 entries): straight into the sparse storage
    let problem = if (w_raw.x.len() as f64) < (m as f64) * (m as f64) / 4.0 {
        let entries = w_raw.entries("fclib_local/W").map_err(|r| f.error(r))?;
        let n = entries.len();
        let (mut rows, mut cols, mut vals) = (
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
        );
        for (r, c, v) in entries {
            rows.push(r);
            cols.push(c);
            vals.push(v);
        }
        let keep = Asymmetry::Keep;
        ReducedProblem::from_triplets_with_asymmetry(spacedim, &rows, &cols, &vals, q, mu, keep)?
    } else {
        let w = w_raw.to_dense("fclib_local/W").map_err(|r| f.error(r))?;
        build_problem(f, spacedim, w, q, mu)?
    };
    Ok((problem, spacedim, FclibSource::Local))
}

fn read_global(
    f: &H5File<'_>,
    file: &File,
) -> Result<(ReducedProblem, usize, FclibSource), SolverError> {
    let at = "fclib_global";
    let g = f.group(file, "", at)?;
    let spacedim = read_spacedim(f, &g, at)?;
    refuse_mixed(f, &g, at, &["G"])?;
    let mass = f.matrix(&g, at, "M")?;
    let h = f.matrix(&g, at, "H")?;
    let n = mass.m;
    if mass.n != n || h.m != n {
        return Err(f.error(format!(
            "`{at}/M` is {} x {} and `{at}/H` is {} x {}: M must be square with as many rows as H",
            mass.m, mass.n, h.m, h.n
        )));
    }
    let m = h.n;
    let nc = contacts(f, "fclib_global/H/n", m, spacedim)?;
    let v = f.group(&g, at, "vectors")?;
    let vec_at = "fclib_global/vectors";
    let rhs = f.reals(&v, vec_at, "f", n)?;
    let w = f.reals(&v, vec_at, "w", m)?;
    let mu = f.reals(&v, vec_at, "mu", nc)?;
    let entries_m = mass.entries("fclib_global/M").map_err(|r| f.error(r))?;
    let entries_h = h.entries("fclib_global/H").map_err(|r| f.error(r))?;
    let condensed =
        global::condense(n, &entries_m, &entries_h, m, &rhs, &w).map_err(|r| f.error(r))?;
    let q = condensed.q;
    let problem = match condensed.w {
        mass::CondensedW::Dense(wmat) => build_problem(f, spacedim, wmat, q, mu)?,
        mass::CondensedW::Triplets { rows, cols, vals } => {
            let keep = Asymmetry::Keep;
            ReducedProblem::from_triplets_with_asymmetry(
                spacedim, &rows, &cols, &vals, q, mu, keep,
            )?
        }
    };
    Ok((problem, spacedim, FclibSource::Global { dofs: n }))
}

/// The problem of dimension `spacedim` (2 or 3, checked by [`read_spacedim`]).
fn build_problem(
    _f: &H5File<'_>,
    spacedim: usize,
    w: Vec<f64>,
    q: Vec<f64>,
    mu: Vec<f64>,
) -> Result<ReducedProblem, SolverError> {
    ReducedProblem::with_asymmetry(spacedim, w, q, mu, Asymmetry::Keep)
}

/// The solution group `g` (at `at`): `r` (required), `u` and `v` (optional).
fn read_solution(
    f: &H5File<'_>,
    g: &Group,
    at: &str,
    m: usize,
    dofs: usize,
) -> Result<FclibSolution, SolverError> {
    let r = f.reals(g, at, "r", m)?;
    let u = if g.link_exists("u") {
        Some(f.reals(g, at, "u", m)?)
    } else {
        None
    };
    let v = if dofs > 0 && g.link_exists("v") {
        Some(f.reals(g, at, "v", dofs)?)
    } else {
        None
    };
    Ok(FclibSolution { r, u, v })
}

/// `guesses/number_of_guesses` and the groups `guesses/1` … `guesses/k`.
fn read_guesses(
    f: &H5File<'_>,
    file: &File,
    m: usize,
    dofs: usize,
) -> Result<Vec<FclibSolution>, SolverError> {
    let g = f.group(file, "", "guesses")?;
    let count = f.size(&g, "guesses", "number_of_guesses")?;
    let mut out = Vec::new();
    for k in 1..=count {
        let name = k.to_string();
        let at = join("guesses", &name);
        let gk = f.group(&g, "guesses", &name)?;
        out.push(read_solution(f, &gk, &at, m, dofs)?);
    }
    Ok(out)
}

/// Writes `problem` as an FCLIB local problem, `W` in compressed rows, and `solution` (the
/// reactions `r`, with `u = W r + q`) when given. The file is created, or truncated.
///
/// # Errors
/// [`SolverError::SizeMismatch`] if `solution` does not have `m` entries;
/// [`SolverError::Fclib`] if the file cannot be created or written.
///
/// # Examples
/// ```
/// use contact_solver::{ReducedProblem, UzawaSettings, solve_coulomb};
/// use contact_solver::local::fclib::{read_fclib, write_fclib};
/// let p = ReducedProblem::new(vec![2.0, 0.5, 0.5, 1.0], vec![-1.0, 0.2], vec![0.3])?;
/// let sol = solve_coulomb(&p, &UzawaSettings::default())?;
/// let path = std::env::temp_dir().join("fclib_doc_write.hdf5");
/// write_fclib(&path, &p, Some(&sol.r))?;
/// assert_eq!(read_fclib(&path)?.solution.map(|s| s.r), Some(sol.r));
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
pub fn write_fclib(
    path: impl AsRef<Path>,
    problem: &ReducedProblem,
    solution: Option<&[f64]>,
) -> Result<(), SolverError> {
    write_fclib_as(path, problem, solution, SparseForm::CompressedRow)
}

/// As [`write_fclib`], with `W` stored in `form`.
///
/// # Errors
/// As for [`write_fclib`].
pub fn write_fclib_as(
    path: impl AsRef<Path>,
    problem: &ReducedProblem,
    solution: Option<&[f64]>,
    form: SparseForm,
) -> Result<(), SolverError> {
    let m = problem.size();
    if let Some(r) = solution
        && r.len() != m
    {
        return Err(SolverError::SizeMismatch {
            what: "solution",
            expected: m,
            found: r.len(),
        });
    }
    let path = path.as_ref();
    let shown = path.display().to_string();
    let f = H5File { path: &shown };
    let file = File::create(path).map_err(|e| f.h5_error("cannot create it", e))?;
    let at = "fclib_local";
    let g = f.create_group(&file, "", at)?;
    let spacedim = problem.dimension() as i64;
    f.write_ints(&g, at, "spacedim", &[spacedim])?;
    let w = match problem.w() {
        WView::Dense(w) => RawSparse::from_dense(w, m, m, form),
        WView::Sparse(a) => RawSparse::from_csr(a, form),
    };
    f.write_matrix(&g, at, "W", &w)?;
    let v = f.create_group(&g, at, "vectors")?;
    f.write_reals(&v, "fclib_local/vectors", "q", problem.q())?;
    f.write_reals(&v, "fclib_local/vectors", "mu", problem.mu())?;
    if let Some(r) = solution {
        let s = f.create_group(&file, "", "solution")?;
        let mut u = vec![0.0; m];
        problem.displacement_into(r, &mut u);
        f.write_reals(&s, "solution", "u", &u)?;
        f.write_reals(&s, "solution", "r", r)?;
    }
    file.close().map_err(|e| f.h5_error("cannot close it", e))
}
