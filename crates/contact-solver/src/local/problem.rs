//! The reduced (condensed) contact problem `x = W r + q`, in 2D or 3D.
//!
//! ```text
//! x = W r + q                       W = F* = H K⁻¹ Hᵀ (flexibility, SPD), q = free gap
//! per contact i:  r_i ∈ K_μi,  v_i = −(x_t + (x_n + μ_i‖x_t‖) n) ∈ N_K(r_i)   (seed 4.39, 5.52)
//! ```
//! Unknowns are ordered normal first per contact, then one tangent (2D) or two (3D):
//! `r = (r_n0, r_t0, r_n1, r_t1, …)` of size `m = 2 n_c`, or
//! `r = (r_n0, r_t0, r_s0, r_n1, …)` of size `m = 3 n_c`. Signs are those of
//! [`contact_laws`](contact_laws#sign-conventions): `r_n ≥ 0` is compression, `x_n ≥ 0` an
//! opening. This is also Siconos' `fc2d`/`fc3d` and FCLIB's form (`u = W r + q`, De Saxcé's
//! `û = u + μ‖u_t‖ n`), so `ReducedProblem::to_json` (feature `serde`) writes exactly what
//! `shared/peers/siconos_fc.py` reads.
//!
//! `W` is stored dense (row-major, [`ReducedProblem::new`]) or sparse (compressed rows on the
//! block pattern of [`CsrMatrix`], [`ReducedProblem::from_triplets`]); every algorithm works on
//! both through the crate's row operations, in `O(stored entries)` per sweep or product, and
//! nothing densifies a sparse `W`.

use super::asymmetry::{Asymmetry, SYMMETRY_TOL};
use super::csr::CsrMatrix;
use super::delassus::{Delassus, WView};
use crate::error::SolverError;
use contact_laws::{Coulomb, CoulombCone};
use std::sync::Arc;

mod shared;

/// A validated reduced contact problem `x = W r + q` with friction coefficients `μ_i`, in
/// dimension `d` = 2 or 3 (the size of a contact's block: one normal and `d − 1` tangents).
///
/// `W` is held dense (row-major `m × m`: [`new`](Self::new), [`new_3d`](Self::new_3d),
/// [`with_dimension`](Self::with_dimension)) or sparse ([`CsrMatrix`]:
/// [`from_triplets`](Self::from_triplets)); [`w`](Self::w) gives either, and the algorithms
/// run on both in `O(stored entries)` per sweep.
///
/// Invariants (checked by every constructor):
/// `W` is `m × m`, `q` has `m` entries, `μ` has `n_c = m/d`; every entry
/// is finite; `W` is symmetric (to `SYMMETRY_TOL` as given, or symmetrised, see
/// [`new`](Self::new)) unless kept non-symmetric ([`Asymmetry::Keep`],
/// [`is_symmetric`](Self::is_symmetric)); the symmetric part of every `d × d` diagonal block of
/// `W` is positive definite; `μ_i ≥ 0`.
/// Full positive definiteness of `W` is *not* checked (it would cost a factorisation, and
/// the Delassus operators of multibody codes are often only semidefinite).
#[derive(Clone, Debug, PartialEq)]
pub struct ReducedProblem {
    /// 2 or 3: unknowns per contact.
    dim: usize,
    w: Delassus,
    q: Vec<f64>,
    mu: Vec<f64>,
    /// Relative asymmetry `max|W_ij − W_ji| / max|W|` removed by symmetrising (0 if none).
    asymmetry: f64,
    /// `Wᵀ` in the storage of `W` when a non-symmetric `W` is kept ([`Asymmetry::Keep`]):
    /// its rows are the columns of `W` that the algorithms' updates read.
    columns: Option<Delassus>,
    /// Relative asymmetry of the `W` kept (0 when symmetric).
    kept_asymmetry: f64,
}

impl ReducedProblem {
    /// Builds and validates a problem from `W` (dense, row-major, `m × m`), `q` (`m`) and `μ`
    /// (`n_c = m/2`).
    ///
    /// # Errors
    /// - [`SolverError::SizeMismatch`] if `q` has an odd length, or `W`, `μ` do not match it;
    /// - [`SolverError::NonFinite`] for a NaN or infinite entry;
    /// - [`SolverError::NotSymmetric`] if `|W_ij − W_ji| > 1e-6·max|W|`
    ///   (`DEFAULT_ASYMMETRY_TOL`); between `SYMMETRY_TOL` and that, `W` is replaced by
    ///   `(W + Wᵀ)/2` and [`asymmetry`](Self::asymmetry) reports the relative asymmetry
    ///   removed (set the tolerance with
    ///   [`with_asymmetry_tolerance`](Self::with_asymmetry_tolerance));
    /// - [`SolverError::NotPositiveDefinite`] if a diagonal block of `W` (2×2; 3×3 for
    ///   [`new_3d`](Self::new_3d)) is not SPD —
    ///   except that a block `[W_nn 0; 0 0]` with `W_nn > 0` is accepted: it is a contact whose
    ///   tangential displacement is prescribed (a supported node), so `x_t = q_t` whatever `r`;
    /// - [`SolverError::InvalidLaw`] if some `μ_i < 0`.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::{ReducedProblem, SolverError};
    /// let p = ReducedProblem::new(vec![2.0, 0.0, 0.0, 2.0], vec![-1.0, 0.5], vec![0.3])?;
    /// assert_eq!(p.contact_count(), 1);
    /// assert!(ReducedProblem::new(vec![1.0], vec![-1.0, 0.5], vec![0.3]).is_err());
    /// # Ok::<(), SolverError>(())
    /// ```
    pub fn new(w: Vec<f64>, q: Vec<f64>, mu: Vec<f64>) -> Result<Self, SolverError> {
        Self::with_asymmetry(2, w, q, mu, Asymmetry::default())
    }

    /// A 3D problem: per contact the normal, then two tangents (`m = 3 n_c`); otherwise as
    /// [`new`](Self::new), with 3×3 diagonal blocks.
    ///
    /// # Errors
    /// As for [`new`](Self::new).
    ///
    /// # Examples
    /// ```
    /// use contact_solver::{ReducedProblem, UzawaSettings, solve_coulomb};
    /// // One contact, W = I, pressed by q_n = −1 and pushed by q_t = (0.3, 0.4), μ = 0.25:
    /// // it slips against the push, r_t = −μ r_n (0.6, 0.8).
    /// let w = vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    /// let p = ReducedProblem::new_3d(w, vec![-1.0, 0.3, 0.4], vec![0.25])?;
    /// let sol = solve_coulomb(&p, &UzawaSettings::default())?;
    /// assert!((sol.r[0] - 1.0).abs() < 1e-9);
    /// assert!((sol.r[1] + 0.15).abs() < 1e-9 && (sol.r[2] + 0.2).abs() < 1e-9);
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn new_3d(w: Vec<f64>, q: Vec<f64>, mu: Vec<f64>) -> Result<Self, SolverError> {
        Self::with_asymmetry(3, w, q, mu, Asymmetry::default())
    }

    /// A problem of dimension `dim` (2 or 3): [`new`](Self::new) or [`new_3d`](Self::new_3d).
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] if `dim` is neither 2 nor 3; as for [`new`](Self::new).
    pub fn with_dimension(
        dim: usize,
        w: Vec<f64>,
        q: Vec<f64>,
        mu: Vec<f64>,
    ) -> Result<Self, SolverError> {
        Self::with_asymmetry(dim, w, q, mu, Asymmetry::default())
    }

    /// As [`with_dimension`](Self::with_dimension), repairing a relative asymmetry of `W` up
    /// to `tolerance` (`0`: only round-off below `SYMMETRY_TOL` is accepted).
    ///
    /// # Errors
    /// As for [`new`](Self::new); [`SolverError::InvalidSetting`] if `tolerance` is negative or
    /// not finite, or `dim` is neither 2 nor 3.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::ReducedProblem;
    /// // W symmetric to 3e-7 relative: repaired by default, refused with a tolerance of 1e-9.
    /// let w = vec![2.0, 0.3, 0.3 + 6e-7, 1.0];
    /// let p = ReducedProblem::new(w.clone(), vec![-1.0, 0.5], vec![0.3])?;
    /// assert!((p.asymmetry() - 3e-7).abs() < 1e-12 && p.w_dense().unwrap()[1] == p.w_dense().unwrap()[2]);
    /// assert!(ReducedProblem::with_asymmetry_tolerance(2, w, vec![-1.0, 0.5], vec![0.3], 1e-9).is_err());
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn with_asymmetry_tolerance(
        dim: usize,
        w: Vec<f64>,
        q: Vec<f64>,
        mu: Vec<f64>,
        tolerance: f64,
    ) -> Result<Self, SolverError> {
        Self::with_asymmetry(dim, w, q, mu, Asymmetry::Symmetrise { tolerance })
    }

    /// As [`with_dimension`](Self::with_dimension), with the [`Asymmetry`] policy `asymmetry`:
    /// [`Asymmetry::Keep`] keeps a non-symmetric `W` as given (the algorithms that need
    /// symmetry then refuse the problem, `Auto` avoids them).
    ///
    /// # Errors
    /// As for [`with_asymmetry_tolerance`](Self::with_asymmetry_tolerance); with
    /// [`Asymmetry::Keep`], never [`SolverError::NotSymmetric`], and
    /// [`SolverError::NotPositiveDefinite`] when the symmetric part of a diagonal block is not
    /// positive definite.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::{Asymmetry, ReducedProblem, UzawaSettings, solve_coulomb};
    /// // one contact pressed (q_n = −1) with a skew coupling W_tn = 0.5 ≠ W_nt = 0: frictionless,
    /// // r_n = 1 and x_t = q_t + W_tn r_n = 0.5 on the real W
    /// let w = vec![1.0, 0.0, 0.5, 1.0];
    /// let p = ReducedProblem::with_asymmetry(2, w, vec![-1.0, 0.0], vec![0.0], Asymmetry::Keep)?;
    /// let sol = solve_coulomb(&p, &UzawaSettings::default())?;
    /// assert!((sol.r[0] - 1.0).abs() < 1e-9 && (sol.x[1] - 0.5).abs() < 1e-9);
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn with_asymmetry(
        dim: usize,
        w: Vec<f64>,
        q: Vec<f64>,
        mu: Vec<f64>,
        asymmetry: Asymmetry,
    ) -> Result<Self, SolverError> {
        Self::dense_validated(dim, Arc::new(w), q, mu, asymmetry)
    }

    /// [`with_asymmetry`](Self::with_asymmetry) on a shared `W`: kept as given (no copy)
    /// unless it has to be symmetrised ([`from_shared`](Self::from_shared)).
    pub(super) fn dense_validated(
        dim: usize,
        w: Arc<Vec<f64>>,
        q: Vec<f64>,
        mu: Vec<f64>,
        asymmetry: Asymmetry,
    ) -> Result<Self, SolverError> {
        let m = check_setup(dim, asymmetry, &q)?;
        if m.checked_mul(m).is_none() {
            return Err(SolverError::SizeMismatch {
                what: "W",
                expected: usize::MAX,
                found: w.len(),
            });
        }
        if w.len() != m * m {
            return Err(SolverError::SizeMismatch {
                what: "W",
                expected: m * m,
                found: w.len(),
            });
        }
        if let Some((index, &value)) = w.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(SolverError::NonFinite {
                what: "W",
                index,
                value,
            });
        }
        check_vectors(m / dim, &q, &mu)?;
        Self::validated(dim, Delassus::Dense { m, w }, q, mu, asymmetry)
    }

    /// The symmetry (refused, symmetrised or kept by `policy`) and diagonal-block checks
    /// shared by every constructor, on `W` whose sizes and entries were checked.
    fn validated(
        dim: usize,
        mut w: Delassus,
        q: Vec<f64>,
        mu: Vec<f64>,
        policy: Asymmetry,
    ) -> Result<Self, SolverError> {
        let w_max = w.max_abs();
        // the worst pair, compared scale-free (w_max may be near overflow or underflow)
        let (worst, row, col, difference) = match &w {
            Delassus::Dense { m, w } => {
                let m = *m;
                let (mut worst, mut row, mut col) = (0.0_f64, 0, 0);
                if w_max < 0.5 * f64::MAX {
                    // |a − b| ≤ 2 w_max cannot overflow: one division, not two per pair
                    for i in 0..m {
                        for j in (i + 1)..m {
                            let difference = (w[i * m + j] - w[j * m + i]).abs();
                            if difference > worst {
                                (worst, row, col) = (difference, i, j);
                            }
                        }
                    }
                    if worst > 0.0 {
                        worst /= w_max;
                    }
                } else {
                    for i in 0..m {
                        for j in (i + 1)..m {
                            let difference = (w[i * m + j] / w_max - w[j * m + i] / w_max).abs();
                            if difference > worst {
                                (worst, row, col) = (difference, i, j);
                            }
                        }
                    }
                }
                // (an empty W has no pair: worst stays 0, no entry is read)
                let difference = if worst > 0.0 {
                    (w[row * m + col] - w[col * m + row]).abs()
                } else {
                    0.0
                };
                (worst, row, col, difference)
            }
            Delassus::Sparse(a) => a.worst_asymmetry(w_max),
        };
        let (mut asymmetry, mut columns, mut kept_asymmetry) = (0.0, None, 0.0);
        match policy.symmetrise_up_to() {
            Some(tolerance) if worst > tolerance.max(SYMMETRY_TOL) => {
                return Err(SolverError::NotSymmetric {
                    row,
                    col,
                    difference,
                    tolerance: tolerance.max(SYMMETRY_TOL) * w_max,
                });
            }
            Some(_) if worst > SYMMETRY_TOL => {
                asymmetry = worst;
                match &mut w {
                    Delassus::Dense { m, w } => {
                        super::dense::symmetrize(Arc::make_mut(w).as_mut_slice(), *m)
                    }
                    Delassus::Sparse(a) => a.symmetrize(),
                }
            }
            None if worst > SYMMETRY_TOL => {
                kept_asymmetry = worst;
                columns = Some(w.transposed());
            }
            _ => {}
        }
        let p = Self {
            dim,
            w,
            q,
            mu,
            asymmetry,
            columns,
            kept_asymmetry,
        };
        for contact in 0..p.contact_count() {
            if !block_is_positive_definite(&p.diagonal_block(contact), dim) {
                return Err(SolverError::NotPositiveDefinite { contact });
            }
        }
        Ok(p)
    }

    /// A problem with a sparse `W` given as triplets `W[rows[k]][cols[k]] += vals[k]`
    /// (0-based; duplicates summed; `m = q.len()`), stored in compressed rows on the block
    /// pattern of [`CsrMatrix`] (whole `d × d` blocks, the pattern made symmetric). Validated
    /// as [`with_dimension`](Self::with_dimension), without forming a dense `W`.
    ///
    /// # Errors
    /// - [`SolverError::InvalidSetting`] if `dim` is neither 2 nor 3;
    /// - [`SolverError::SizeMismatch`] if `q` is not `dim · n_c` long, `μ` does not have
    ///   `n_c` entries, or `cols`, `vals` are not as long as `rows`;
    /// - [`SolverError::IndexOutOfRange`] for an index `≥ m` (naming the triplet);
    /// - [`SolverError::NonFinite`] for a value (`"vals"`, naming the triplet), `q` or `μ` that
    ///   is not finite;
    /// - [`SolverError::NotSymmetric`], [`SolverError::NotPositiveDefinite`],
    ///   [`SolverError::InvalidLaw`] as for [`new`](Self::new) (asymmetry up to
    ///   `DEFAULT_ASYMMETRY_TOL` is symmetrised and reported by
    ///   [`asymmetry`](Self::asymmetry)).
    ///
    /// # Examples
    /// ```
    /// use contact_solver::{ReducedProblem, UzawaSettings, solve_coulomb};
    /// // one 3D contact, W = I: entries (0,0), (1,1), (2,2)
    /// let p = ReducedProblem::from_triplets(
    ///     3, &[0, 1, 2], &[0, 1, 2], &[1.0; 3], vec![-1.0, 0.3, 0.4], vec![0.25],
    /// )?;
    /// assert!(p.w_sparse().is_some() && p.w_dense().is_none());
    /// let sol = solve_coulomb(&p, &UzawaSettings::default())?;
    /// assert!((sol.r[0] - 1.0).abs() < 1e-9 && (sol.r[1] + 0.15).abs() < 1e-9);
    /// // a row index out of range is named
    /// let e = ReducedProblem::from_triplets(3, &[0, 9], &[0, 1], &[1.0; 2], vec![0.0; 3], vec![0.2]);
    /// assert!(matches!(e, Err(contact_solver::SolverError::IndexOutOfRange { index: 1, .. })));
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn from_triplets(
        dim: usize,
        rows: &[usize],
        cols: &[usize],
        vals: &[f64],
        q: Vec<f64>,
        mu: Vec<f64>,
    ) -> Result<Self, SolverError> {
        Self::from_triplets_with_asymmetry(dim, rows, cols, vals, q, mu, Asymmetry::default())
    }

    /// As [`from_triplets`](Self::from_triplets), repairing a relative asymmetry of `W` up to
    /// `tolerance` (as [`with_asymmetry_tolerance`](Self::with_asymmetry_tolerance)).
    ///
    /// # Errors
    /// As for [`from_triplets`](Self::from_triplets); [`SolverError::InvalidSetting`] if
    /// `tolerance` is negative or not finite.
    pub fn from_triplets_with_tolerance(
        dim: usize,
        rows: &[usize],
        cols: &[usize],
        vals: &[f64],
        q: Vec<f64>,
        mu: Vec<f64>,
        tolerance: f64,
    ) -> Result<Self, SolverError> {
        let policy = Asymmetry::Symmetrise { tolerance };
        Self::from_triplets_with_asymmetry(dim, rows, cols, vals, q, mu, policy)
    }

    /// As [`from_triplets`](Self::from_triplets), with the [`Asymmetry`] policy `asymmetry`
    /// (as [`with_asymmetry`](Self::with_asymmetry)).
    ///
    /// # Errors
    /// As for [`from_triplets`](Self::from_triplets) and
    /// [`with_asymmetry`](Self::with_asymmetry).
    pub fn from_triplets_with_asymmetry(
        dim: usize,
        rows: &[usize],
        cols: &[usize],
        vals: &[f64],
        q: Vec<f64>,
        mu: Vec<f64>,
        asymmetry: Asymmetry,
    ) -> Result<Self, SolverError> {
        let m = check_setup(dim, asymmetry, &q)?;
        check_vectors(m / dim, &q, &mu)?;
        let w = CsrMatrix::from_triplets(dim, m, rows, cols, vals)?;
        Self::validated(dim, Delassus::Sparse(w), q, mu, asymmetry)
    }

    /// The same problem with `W` scaled by `s_w` and `q` by `s_q` (powers of two in the
    /// dispatcher's rescaling: exact), in the same storage, validated again.
    pub(crate) fn rescaled(&self, s_w: f64, s_q: f64) -> Result<Self, SolverError> {
        let q = self.q.iter().map(|v| v * s_q).collect();
        let policy = if self.columns.is_some() {
            Asymmetry::Keep
        } else {
            Asymmetry::Refuse
        };
        Self::validated(self.dim, self.w.scaled(s_w), q, self.mu.clone(), policy)
    }

    /// The problem on the contacts `keep` (increasing, distinct, each `< n_c`): `W` restricted
    /// to their rows and columns in the same storage, `q` and `μ` likewise. A principal
    /// sub-matrix of a valid `W` is valid (symmetric, the same diagonal blocks), so nothing is
    /// checked again; a kept non-symmetric `W` keeps its `Wᵀ` restricted alike.
    pub(crate) fn restricted(&self, keep: &[usize]) -> Self {
        let d = self.dim;
        let rows: Vec<usize> = keep
            .iter()
            .flat_map(|&i| (0..d).map(move |k| d * i + k))
            .collect();
        let restrict = |w: &Delassus| match w {
            Delassus::Dense { m, w } => {
                let mut out = Vec::with_capacity(rows.len() * rows.len());
                for &r in &rows {
                    let row = &w[r * m..(r + 1) * m];
                    out.extend(rows.iter().map(|&c| row[c]));
                }
                Delassus::Dense {
                    m: rows.len(),
                    w: Arc::new(out),
                }
            }
            Delassus::Sparse(a) => Delassus::Sparse(a.restricted(d, keep)),
        };
        Self {
            dim: d,
            w: restrict(&self.w),
            q: rows.iter().map(|&r| self.q[r]).collect(),
            mu: keep.iter().map(|&i| self.mu[i]).collect(),
            asymmetry: 0.0,
            columns: self.columns.as_ref().map(restrict),
            kept_asymmetry: self.kept_asymmetry,
        }
    }

    /// Relative asymmetry `max|W_ij − W_ji| / max|W|` of the `W` given, removed by
    /// symmetrising it (0 when it was symmetric to `SYMMETRY_TOL`).
    pub fn asymmetry(&self) -> f64 {
        self.asymmetry
    }

    /// Whether `W` is symmetric (as given to round-off, or symmetrised): `false` only when a
    /// non-symmetric `W` was kept ([`Asymmetry::Keep`]).
    #[inline]
    pub fn is_symmetric(&self) -> bool {
        self.columns.is_none()
    }

    /// Relative asymmetry `max|W_ij − W_ji| / max|W|` of a `W` kept non-symmetric
    /// ([`Asymmetry::Keep`]); 0 when `W` is symmetric.
    pub fn kept_asymmetry(&self) -> f64 {
        self.kept_asymmetry
    }

    /// The dimension `d` (2 or 3): unknowns per contact, the normal first.
    #[inline]
    pub fn dimension(&self) -> usize {
        self.dim
    }

    /// Number of contacts `n_c`.
    #[inline]
    pub fn contact_count(&self) -> usize {
        self.mu.len()
    }

    /// Number of unknowns `m = d n_c`.
    #[inline]
    pub fn size(&self) -> usize {
        self.q.len()
    }

    /// The flexibility matrix `W`, dense or sparse.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::{ReducedProblem, WView};
    /// let p = ReducedProblem::new(vec![2.0, 0.0, 0.0, 1.0], vec![-1.0, 0.5], vec![0.3])?;
    /// assert!(matches!(p.w(), WView::Dense(w) if w == [2.0, 0.0, 0.0, 1.0]));
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    #[inline]
    pub fn w(&self) -> WView<'_> {
        self.w.view()
    }

    /// `W` dense row-major `m × m`, or `None` when it is stored sparse.
    #[inline]
    pub fn w_dense(&self) -> Option<&[f64]> {
        match &self.w {
            Delassus::Dense { w, .. } => Some(w.as_slice()),
            Delassus::Sparse(_) => None,
        }
    }

    /// `W` in compressed sparse rows, or `None` when it is stored dense.
    #[inline]
    pub fn w_sparse(&self) -> Option<&CsrMatrix> {
        match &self.w {
            Delassus::Dense { .. } => None,
            Delassus::Sparse(a) => Some(a),
        }
    }

    /// Whether `W` is stored sparse.
    #[inline]
    pub fn is_sparse(&self) -> bool {
        matches!(self.w, Delassus::Sparse(_))
    }

    /// Bytes held by the storage of `W`: `8 m²` dense; `12 · stored + 8 (m + 1)` sparse.
    pub fn w_storage_bytes(&self) -> usize {
        self.w.storage_bytes()
    }

    /// The storage, for the algorithms' row operations.
    #[inline]
    pub(crate) fn delassus(&self) -> &Delassus {
        &self.w
    }

    /// The storage whose rows are the columns of `W`, for the algorithms' updates
    /// `x += W[:, k] Δr_k` and products `W v`: `W` when symmetric, the kept `Wᵀ` otherwise.
    #[inline]
    pub(crate) fn columns(&self) -> &Delassus {
        self.columns.as_ref().unwrap_or(&self.w)
    }

    /// The free gap / displacement `q`.
    #[inline]
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// The friction coefficients, one per contact: the laws of
    /// [`coulomb_laws`](Self::coulomb_laws) and [`solve_coulomb`](crate::solve_coulomb);
    /// a solve with other laws takes μ from them and refuses a problem that disagrees
    /// ([`with_friction_of`](Self::with_friction_of)).
    #[inline]
    pub fn mu(&self) -> &[f64] {
        &self.mu
    }

    /// The friction coefficients to replace (`crate::local::friction`).
    pub(crate) fn mu_mut(&mut self) -> &mut [f64] {
        &mut self.mu
    }

    /// The `d × d` diagonal block of contact `i` (normal first), in the top-left corner of a
    /// 3×3 array whose other entries are 0 in 2D.
    ///
    /// # Panics
    /// If `i >= contact_count()`.
    #[inline]
    #[track_caller]
    pub fn diagonal_block(&self, i: usize) -> [[f64; 3]; 3] {
        self.w.diagonal_block(i, self.dim)
    }

    /// One Coulomb law per contact, `Coulomb::new(μ_i)` (infallible: `μ` was validated).
    pub fn coulomb_laws(&self) -> Vec<Coulomb> {
        self.mu
            .iter()
            .map(|&m| Coulomb::new(m).unwrap_or_else(|_| unreachable!("mu validated in new")))
            .collect()
    }

    /// `x = W r + q` into `x`.
    ///
    /// # Panics
    /// If `r` or `x` does not have `size()` entries.
    #[track_caller]
    pub fn displacement_into(&self, r: &[f64], x: &mut [f64]) {
        let m = self.size();
        assert!(r.len() == m && x.len() == m, "r and x must have m entries");
        for (i, xi) in x.iter_mut().enumerate() {
            *xi = self.q[i] + self.w.dot_row(i, r);
        }
    }
}

/// Checks the asymmetry policy's tolerance, `dim` (2 or 3) and that `q` has `dim · n_c`
/// entries; returns `m`.
fn check_setup(dim: usize, policy: Asymmetry, q: &[f64]) -> Result<usize, SolverError> {
    let tolerance = policy.symmetrise_up_to().unwrap_or(0.0);
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(SolverError::InvalidSetting {
            what: "asymmetry tolerance",
            value: tolerance,
            expected: "a finite relative tolerance >= 0",
        });
    }
    if !(dim == 2 || dim == 3) {
        return Err(SolverError::InvalidSetting {
            what: "dim",
            value: dim as f64,
            expected: "2 or 3 (unknowns per contact: a normal and 1 or 2 tangents)",
        });
    }
    let m = q.len();
    if !m.is_multiple_of(dim) {
        return Err(SolverError::SizeMismatch {
            what: "q",
            expected: m.next_multiple_of(dim),
            found: m,
        });
    }
    Ok(m)
}

/// Checks that `μ` has `nc` entries, `q` and `μ` are finite and every `μ_i ≥ 0`.
fn check_vectors(nc: usize, q: &[f64], mu: &[f64]) -> Result<(), SolverError> {
    if mu.len() != nc {
        return Err(SolverError::SizeMismatch {
            what: "mu",
            expected: nc,
            found: mu.len(),
        });
    }
    for (what, v) in [("q", q), ("mu", mu)] {
        if let Some((index, &value)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(SolverError::NonFinite { what, index, value });
        }
    }
    for (contact, &m_i) in mu.iter().enumerate() {
        CoulombCone::new(m_i).map_err(|source| SolverError::InvalidLaw { contact, source })?;
    }
    Ok(())
}

/// Whether the symmetric part `(b + bᵀ)/2` of the `d × d` block `b` is positive definite
/// (`b` itself when symmetric, the case of every `W` but a kept non-symmetric one), scale-free (blocks of 1e300 or
/// 1e-300 neither overflow nor underflow) — except that a tangent whose row and column are
/// exactly zero is allowed: it is a contact whose tangential displacement is prescribed (a
/// supported node), so `x_t = q_t` whatever `r`.
#[allow(clippy::needless_range_loop)] // a textbook Cholesky on 3×3 arrays
fn block_is_positive_definite(b: &[[f64; 3]; 3], d: usize) -> bool {
    let s = (0..d).fold(0.0_f64, |a, k| a.max(b[k][k].abs()));
    if s.is_nan() || s <= 0.0 {
        return false;
    }
    let kept: Vec<usize> = (0..d)
        .filter(|&k| k == 0 || (0..d).any(|l| b[k][l] != 0.0 || b[l][k] != 0.0))
        .collect();
    // Cholesky of the kept principal block, scaled by s.
    let mut l = [[0.0_f64; 3]; 3];
    for (a, &i) in kept.iter().enumerate() {
        for (c, &j) in kept.iter().enumerate().take(a + 1) {
            // the symmetric part's entry; b[i][j] itself (the same bits) when symmetric
            let b_ij = if b[i][j] == b[j][i] {
                b[i][j]
            } else {
                0.5 * b[i][j] + 0.5 * b[j][i]
            };
            let mut v = b_ij / s;
            for k in 0..c {
                v -= l[a][k] * l[c][k];
            }
            if a == c {
                if v.is_nan() || v <= 0.0 {
                    return false;
                }
                l[a][a] = v.sqrt();
            } else {
                l[a][c] = v / l[c][c];
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_works() {
        let p = ReducedProblem::new(vec![2.0, 0.5, 0.5, 1.0], vec![-1.0, 0.0], vec![0.2]).unwrap();
        assert_eq!(
            p.diagonal_block(0),
            [[2.0, 0.5, 0.0], [0.5, 1.0, 0.0], [0.0, 0.0, 0.0]]
        );
        let mut x = [0.0; 2];
        p.displacement_into(&[1.0, 2.0], &mut x);
        assert_eq!(x, [2.0, 2.5]);
    }

    #[test]
    fn new_rejects_singular_block() {
        let e = ReducedProblem::new(vec![1.0, 1.0, 1.0, 1.0], vec![-1.0, 0.0], vec![0.2]);
        assert_eq!(e, Err(SolverError::NotPositiveDefinite { contact: 0 }));
        let e = ReducedProblem::new(vec![0.0, 0.0, 0.0, 1.0], vec![-1.0, 0.0], vec![0.2]);
        assert_eq!(e, Err(SolverError::NotPositiveDefinite { contact: 0 }));
        // tangentially supported contact: [W_nn 0; 0 0]
        assert!(ReducedProblem::new(vec![1.0, 0.0, 0.0, 0.0], vec![-1.0, 0.0], vec![0.2]).is_ok());
    }

    #[test]
    fn new_3d_checks_blocks_and_sizes() {
        let eye = |d: usize| -> Vec<f64> {
            (0..d * d)
                .map(|k| if k % (d + 1) == 0 { 1.0 } else { 0.0 })
                .collect()
        };
        let p = ReducedProblem::new_3d(eye(6), vec![-1.0, 0.0, 0.0, 1.0, 0.0, 0.0], vec![0.1, 0.2])
            .unwrap();
        assert_eq!((p.dimension(), p.contact_count(), p.size()), (3, 2, 6));
        assert_eq!(
            p.diagonal_block(1),
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
        );
        // q of 4 entries is not 3 n_c
        let e = ReducedProblem::new_3d(eye(4), vec![0.0; 4], vec![0.1]);
        assert!(matches!(
            e,
            Err(SolverError::SizeMismatch { what: "q", .. })
        ));
        // a singular 3×3 block: the two tangents equal
        let w = vec![1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0];
        let e = ReducedProblem::new_3d(w, vec![-1.0, 0.0, 0.0], vec![0.1]);
        assert_eq!(e, Err(SolverError::NotPositiveDefinite { contact: 0 }));
        // both tangents supported: only the normal is kept
        let w = vec![2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        assert!(ReducedProblem::new_3d(w, vec![-1.0, 0.0, 0.0], vec![0.1]).is_ok());
        let e = ReducedProblem::with_dimension(4, eye(4), vec![0.0; 4], vec![0.1]);
        assert!(matches!(
            e,
            Err(SolverError::InvalidSetting { what: "dim", .. })
        ));
    }

    #[test]
    fn asymmetry_keep_works() {
        // a block [1 3; −3 1]: skew off-diagonal, symmetric part I (positive definite)
        let w = vec![1.0, 3.0, -3.0, 1.0];
        let p = ReducedProblem::with_asymmetry(
            2,
            w.clone(),
            vec![-1.0, 0.0],
            vec![0.2],
            Asymmetry::Keep,
        )
        .unwrap();
        assert!(!p.is_symmetric() && p.kept_asymmetry() == 2.0 && p.asymmetry() == 0.0);
        assert_eq!(p.w_dense(), Some(&w[..]));
        // the columns' storage is Wᵀ: its row 0 is W's column 0
        let mut x = [0.0; 2];
        p.columns().axpy_row(0, 1.0, &mut x);
        assert_eq!(x, [1.0, -3.0]);
        // x = W r + q reads the rows of W
        p.displacement_into(&[1.0, 0.0], &mut x);
        assert_eq!(x, [0.0, -3.0]);
        // a restricted and a rescaled copy keep it
        assert!(!p.restricted(&[0]).is_symmetric());
        assert!(!p.rescaled(2.0, 0.5).unwrap().is_symmetric());
        // refused by the other policies, naming the pair
        for policy in [Asymmetry::Refuse, Asymmetry::default()] {
            let e =
                ReducedProblem::with_asymmetry(2, w.clone(), vec![-1.0, 0.0], vec![0.2], policy);
            assert!(matches!(
                e,
                Err(SolverError::NotSymmetric { row: 0, col: 1, .. })
            ));
        }
    }

    #[test]
    fn asymmetry_keep_rejects_indefinite_symmetric_part() {
        // [1 3; 1 1]: its symmetric part [1 2; 2 1] is indefinite
        let w = vec![1.0, 3.0, 1.0, 1.0];
        let e = ReducedProblem::with_asymmetry(2, w, vec![-1.0, 0.0], vec![0.2], Asymmetry::Keep);
        assert_eq!(e, Err(SolverError::NotPositiveDefinite { contact: 0 }));
        let e = ReducedProblem::with_asymmetry(
            2,
            vec![1.0, 0.0, 0.0, 1.0],
            vec![-1.0, 0.0],
            vec![0.2],
            Asymmetry::Symmetrise { tolerance: -1.0 },
        );
        assert!(matches!(e, Err(SolverError::InvalidSetting { .. })));
    }
}
