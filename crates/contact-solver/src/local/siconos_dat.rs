//! Siconos' numerics text format for friction-contact problems (`.dat`), in and out: the files
//! of Siconos' test collection (`numerics/src/FrictionContact/test/data/`) and what
//! `frictionContact_printInFilename` writes.
//!
//! ```text
//! local (FrictionContactProblem):      dim, n_c, W (a NumericsMatrix), q (m values), mu (n_c)
//!                                      u = W r + q,  m = dim · n_c
//! global (GlobalFrictionContactProblem): dim, n_c, M (n × n), H (n × m), q (n), b (m), mu (n_c)
//!                                      M v = q + H r,  u = Hᵀ v + b
//!   condensed on reading:              W = Hᵀ M⁻¹ H,  q_loc = Hᵀ M⁻¹ q + b
//! ```
//! Per contact the unknowns are normal first, then the tangent(s): the order and signs of
//! [`ReducedProblem`] (`x = W r + q`, `r_n ≥ 0` in compression; see
//! [`contact_laws`](contact_laws#sign-conventions)). A matrix is written dense (storage 0,
//! column by column) or in sparse blocks (storage 1); the layout is in `matrix.rs`. A global
//! file is told from a local one by what follows the first matrix: exactly `m + n_c` values
//! (`q`, `mu`; local), else a storage type alone on its line (global). Siconos' older files end with one more integer (a
//! flag, `0` or `1`), which is skipped.
//!
//! Refused by name: the rolling-friction problems (`RFC3D`, `GRFC3D`: dimension 5, or a line
//! `mu_r` after `mu`), the CSparse storage (type 2, printed with six digits), a dimension
//! other than 2 or 3. A non-symmetric `W` (multibody codes write them) is kept as given
//! ([`Asymmetry::Keep`]).
//!
//! # Hostile files
//! Every count is checked against the tokens left before anything is allocated, every value
//! for finiteness, every block index against its bound: a bad file is a
//! [`SolverError::SiconosDat`] naming the line, never a panic.

mod condense;
mod matrix;
mod tokens;

use super::asymmetry::Asymmetry;
use super::problem::ReducedProblem;
use crate::error::SolverError;
use matrix::{DatMatrix, Values, read_matrix};
use tokens::{Tokens, error};

/// Where the problem of a `.dat` file came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum DatSource {
    /// A local problem (`FrictionContactProblem`), read as it is.
    Local,
    /// A global problem (`GlobalFrictionContactProblem`), condensed to `W = Hᵀ M⁻¹ H`.
    Global {
        /// The number of global unknowns `n` (rows of `M`).
        dofs: usize,
    },
}

/// A `.dat` file read by [`read_siconos_dat`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SiconosDat {
    /// The reduced problem `x = W r + q`.
    pub problem: ReducedProblem,
    /// Local, or global and condensed.
    pub source: DatSource,
}

/// Reads a Siconos `.dat` friction-contact problem (see the [module docs](self)).
///
/// # Errors
/// [`SolverError::SiconosDat`] naming the line for a file that ends early, a count or size
/// that does not match, a value that is not a finite number, a block out of range, a singular
/// `M`, or a problem of another kind (rolling friction, dimension other than 2 or 3); then
/// those of [`ReducedProblem::with_asymmetry`] with [`Asymmetry::Keep`] (a diagonal block
/// that is not positive definite, a negative `μ`).
///
/// # Examples
/// ```
/// use contact_solver::ReducedProblem;
/// use contact_solver::local::siconos_dat::{read_siconos_dat, write_siconos_dat};
/// let p = ReducedProblem::new(vec![2.0, 0.5, 0.5, 1.0], vec![-1.0, 0.2], vec![0.3])?;
/// let text = write_siconos_dat(&p);
/// assert_eq!(read_siconos_dat(&text)?.problem, p);
/// let bad = text.replace("3e-1", "NaN"); // μ = 0.3, written in the shortest form
/// assert!(read_siconos_dat(&bad).unwrap_err().to_string().contains("line"));
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
pub fn read_siconos_dat(text: &str) -> Result<SiconosDat, SolverError> {
    let mut t = Tokens::new(text);
    let line = t.line();
    let dim = t.count("the dimension", 99).map_err(|e| match e {
        // Siconos' test data holds other inputs beside the problems (ACinputs.dat: 1000 lines
        // of Alart–Curnier function arguments)
        SolverError::SiconosDat { line, reason } => error(
            line,
            format!("{reason}: not a friction-contact problem (its first line is the dimension)"),
        ),
        e => e,
    })?;
    match dim {
        2 | 3 => {}
        5 => {
            return Err(error(
                line,
                "dimension 5 is Siconos' rolling-friction problem (RFC3D, GRFC3D): not \
                 supported (only Coulomb friction in 2D or 3D)",
            ));
        }
        d => {
            return Err(error(
                line,
                format!(
                    "dimension {d}: expected 2 or 3 (not a friction-contact problem? Siconos' \
                     `.dat` files also hold lone matrices and other problem classes, MLCPs)"
                ),
            ));
        }
    }
    let nc = t.count("the number of contacts", t.remaining())?;
    let m = dim * nc;
    let first_line = t.line();
    let first = read_matrix(&mut t, "W")?;
    // A local file has exactly `q` and `mu` left (and maybe the old trailing flag); a global
    // one has `H`, `q`, `b` and `mu`, always more. The token count decides first: a local `q`
    // of integers, one to a line, looks like a storage type (Siconos' `FrictionContact3D_1c`).
    let left = t.remaining();
    let local_fits = (first.rows, first.cols) == (m, m) && (left == m + nc || left == m + nc + 1);
    let (problem, source) = if !local_fits && t.next_is_lone_integer() {
        global(&mut t, dim, nc, first)?
    } else {
        if (first.rows, first.cols) != (m, m) {
            return Err(error(
                first_line,
                format!(
                    "`W` is {} x {}, but {nc} contacts in dimension {dim} need {m} x {m}",
                    first.rows, first.cols
                ),
            ));
        }
        let q = t.reals("`q`", m)?;
        let mu = t.reals("`mu`", nc)?;
        (build(dim, first.values, m, q, mu)?, DatSource::Local)
    };
    trailing(&t)?;
    Ok(SiconosDat { problem, source })
}

/// After `mu`: nothing, or Siconos' flag (one integer).
fn trailing(t: &Tokens<'_>) -> Result<(), SolverError> {
    let left = t.remaining();
    if left == 0 || (left == 1 && t.next_is_lone_integer()) {
        return Ok(());
    }
    Err(error(
        t.line(),
        format!(
            "{left} more values after `mu`: Siconos' rolling-friction problems store `mu_r` \
             there (not supported), else the contact count is wrong"
        ),
    ))
}

/// The rest of a global problem, `M` read; condensed.
fn global(
    t: &mut Tokens<'_>,
    dim: usize,
    nc: usize,
    mass: DatMatrix,
) -> Result<(ReducedProblem, DatSource), SolverError> {
    let m = dim * nc;
    let line = t.line();
    let h = read_matrix(t, "H")?;
    let n = mass.rows;
    if mass.cols != n || h.rows != n || h.cols != m {
        return Err(error(
            line,
            format!(
                "global problem: `M` is {} x {} and `H` is {} x {}; expected M square and H \
                 {n} x {m} ({nc} contacts in dimension {dim})",
                mass.rows, mass.cols, h.rows, h.cols
            ),
        ));
    }
    let q = t.reals("`q` (global)", n)?;
    let b = t.reals("`b`", m)?;
    let mu_line = t.line();
    let mu = t.reals("`mu`", nc)?;
    let (w, q_loc) = condense::condense(n, &mass.entries(), &h.entries(), m, &q, &b)
        .map_err(|r| error(mu_line, r))?;
    let problem = build(dim, Values::Dense(w), m, q_loc, mu)?;
    Ok((problem, DatSource::Global { dofs: n }))
}

/// The problem: sparse when `W` has fewer than `m²/4` nonzero entries, else dense.
fn build(
    dim: usize,
    w: Values,
    m: usize,
    q: Vec<f64>,
    mu: Vec<f64>,
) -> Result<ReducedProblem, SolverError> {
    let keep = Asymmetry::Keep;
    let sparse_enough = |nnz: usize| (nnz as f64) < (m as f64) * (m as f64) / 4.0;
    match w {
        Values::Dense(a) if !sparse_enough(a.iter().filter(|v| **v != 0.0).count()) => {
            ReducedProblem::with_asymmetry(dim, a, q, mu, keep)
        }
        Values::Triplets(e) if !sparse_enough(e.len()) => {
            let mut a = vec![0.0; m * m];
            for (i, j, v) in e {
                a[i * m + j] = v;
            }
            ReducedProblem::with_asymmetry(dim, a, q, mu, keep)
        }
        w => {
            let e = DatMatrix {
                rows: m,
                cols: m,
                values: w,
            }
            .entries();
            let rows: Vec<usize> = e.iter().map(|x| x.0).collect();
            let cols: Vec<usize> = e.iter().map(|x| x.1).collect();
            let vals: Vec<f64> = e.iter().map(|x| x.2).collect();
            ReducedProblem::from_triplets_with_asymmetry(dim, &rows, &cols, &vals, q, mu, keep)
        }
    }
}

/// Writes `problem` as a Siconos local `.dat` problem: `W` dense (storage 0) when it is stored
/// dense, in `dim × dim` sparse blocks (storage 1) when sparse. Numbers are written in the
/// shortest form that reads back to the same `f64`, so [`read_siconos_dat`] gives back the same
/// problem (Siconos' `frictionContact_new_from_filename` reads it too).
///
/// # Examples
/// ```
/// use contact_solver::ReducedProblem;
/// use contact_solver::local::siconos_dat::write_siconos_dat;
/// let p = ReducedProblem::new(vec![2.0, 0.0, 0.0, 1.0], vec![-1.0, 0.5], vec![0.3])?;
/// assert!(write_siconos_dat(&p).starts_with("2\n1\n0\n2\n2\n"));
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
pub fn write_siconos_dat(problem: &ReducedProblem) -> String {
    let dim = problem.dimension();
    let m = problem.size();
    let mut out = format!("{dim}\n{}\n", problem.contact_count());
    match (problem.w_dense(), problem.w_sparse()) {
        (Some(a), _) => matrix::write_dense(&mut out, m, m, a),
        (None, Some(w)) => matrix::write_blocks(&mut out, dim, w),
        (None, None) => unreachable!("W is stored dense or sparse"),
    }
    for v in [problem.q(), problem.mu()] {
        let line: Vec<String> = v.iter().map(|x| format!("{x:e}")).collect();
        out.push_str(&line.join(" "));
        out.push('\n');
    }
    out
}
