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

use crate::error::SolverError;
use contact_laws::{Coulomb, CoulombCone};

/// Asymmetry below which `W` is taken as given: `|W_ij − W_ji| ≤ 1e-12 · max|W|` (round-off
/// of a symmetric assembly).
pub const SYMMETRY_TOL: f64 = 1e-12;

/// Default relative asymmetry [`ReducedProblem::new`] repairs: up to
/// `|W_ij − W_ji| ≤ 1e-6 · max|W|` (round-off of the exporting code) `W` is replaced by
/// `(W + Wᵀ)/2` and [`ReducedProblem::asymmetry`] says by how much; beyond it, an error.
pub const DEFAULT_ASYMMETRY_TOL: f64 = 1e-6;

/// A validated reduced contact problem `x = W r + q` with friction coefficients `μ_i`, in
/// dimension `d` = 2 or 3 (the size of a contact's block: one normal and `d − 1` tangents).
///
/// Invariants (checked by [`new`](Self::new) and [`with_dimension`](Self::with_dimension)):
/// `W` is `m × m` (dense, row-major), `q` has `m` entries, `μ` has `n_c = m/d`; every entry
/// is finite; `W` is symmetric (to [`SYMMETRY_TOL`] as given, or symmetrised, see
/// [`new`](Self::new)); every `d × d` diagonal block of `W` is positive definite; `μ_i ≥ 0`.
/// Full positive definiteness of `W` is *not* checked (it would cost a factorisation, and
/// the Delassus operators of multibody codes are often only semidefinite).
#[derive(Clone, Debug, PartialEq)]
pub struct ReducedProblem {
    /// 2 or 3: unknowns per contact.
    dim: usize,
    w: Vec<f64>,
    q: Vec<f64>,
    mu: Vec<f64>,
    /// Relative asymmetry `max|W_ij − W_ji| / max|W|` removed by symmetrising (0 if none).
    asymmetry: f64,
}

impl ReducedProblem {
    /// Builds and validates a problem from `W` (dense, row-major, `m × m`), `q` (`m`) and `μ`
    /// (`n_c = m/2`).
    ///
    /// # Errors
    /// - [`SolverError::SizeMismatch`] if `q` has an odd length, or `W`, `μ` do not match it;
    /// - [`SolverError::NonFinite`] for a NaN or infinite entry;
    /// - [`SolverError::NotSymmetric`] if `|W_ij − W_ji| > 1e-6·max|W|`
    ///   ([`DEFAULT_ASYMMETRY_TOL`]); between [`SYMMETRY_TOL`] and that, `W` is replaced by
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
        Self::with_asymmetry_tolerance(2, w, q, mu, DEFAULT_ASYMMETRY_TOL)
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
        Self::with_asymmetry_tolerance(3, w, q, mu, DEFAULT_ASYMMETRY_TOL)
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
        Self::with_asymmetry_tolerance(dim, w, q, mu, DEFAULT_ASYMMETRY_TOL)
    }

    /// As [`with_dimension`](Self::with_dimension), repairing a relative asymmetry of `W` up
    /// to `tolerance` (`0`: only round-off below [`SYMMETRY_TOL`] is accepted).
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
    /// assert!((p.asymmetry() - 3e-7).abs() < 1e-12 && p.w()[1] == p.w()[2]);
    /// assert!(ReducedProblem::with_asymmetry_tolerance(2, w, vec![-1.0, 0.5], vec![0.3], 1e-9).is_err());
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn with_asymmetry_tolerance(
        dim: usize,
        mut w: Vec<f64>,
        q: Vec<f64>,
        mu: Vec<f64>,
        tolerance: f64,
    ) -> Result<Self, SolverError> {
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
        let nc = m / dim;
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
        if mu.len() != nc {
            return Err(SolverError::SizeMismatch {
                what: "mu",
                expected: nc,
                found: mu.len(),
            });
        }
        for (what, v) in [("W", &w), ("q", &q), ("mu", &mu)] {
            if let Some((index, &value)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(SolverError::NonFinite { what, index, value });
            }
        }
        for (contact, &m_i) in mu.iter().enumerate() {
            CoulombCone::new(m_i).map_err(|source| SolverError::InvalidLaw { contact, source })?;
        }
        let w_max = w.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        // the worst pair, compared scale-free (w_max may be near overflow or underflow)
        let (mut worst, mut row, mut col) = (0.0_f64, 0, 0);
        for i in 0..m {
            for j in (i + 1)..m {
                let difference = (w[i * m + j] / w_max - w[j * m + i] / w_max).abs();
                if difference > worst {
                    (worst, row, col) = (difference, i, j);
                }
            }
        }
        let mut asymmetry = 0.0;
        if worst > tolerance.max(SYMMETRY_TOL) {
            return Err(SolverError::NotSymmetric {
                row,
                col,
                difference: (w[row * m + col] - w[col * m + row]).abs(),
                tolerance: tolerance.max(SYMMETRY_TOL) * w_max,
            });
        } else if worst > SYMMETRY_TOL {
            asymmetry = worst;
            super::dense::symmetrize(&mut w, m);
        }
        let p = Self {
            dim,
            w,
            q,
            mu,
            asymmetry,
        };
        for contact in 0..nc {
            if !block_is_positive_definite(&p.diagonal_block(contact), dim) {
                return Err(SolverError::NotPositiveDefinite { contact });
            }
        }
        Ok(p)
    }

    /// Relative asymmetry `max|W_ij − W_ji| / max|W|` of the `W` given, removed by
    /// symmetrising it (0 when it was symmetric to [`SYMMETRY_TOL`]).
    pub fn asymmetry(&self) -> f64 {
        self.asymmetry
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

    /// The flexibility matrix `W`, dense row-major `m × m`.
    #[inline]
    pub fn w(&self) -> &[f64] {
        &self.w
    }

    /// The free gap / displacement `q`.
    #[inline]
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// The friction coefficients, one per contact.
    #[inline]
    pub fn mu(&self) -> &[f64] {
        &self.mu
    }

    /// The `d × d` diagonal block of contact `i` (normal first), in the top-left corner of a
    /// 3×3 array whose other entries are 0 in 2D.
    ///
    /// # Panics
    /// If `i >= contact_count()`.
    #[inline]
    #[track_caller]
    pub fn diagonal_block(&self, i: usize) -> [[f64; 3]; 3] {
        let (m, d) = (self.size(), self.dim);
        let a = d * i;
        let mut b = [[0.0; 3]; 3];
        for (k, row) in b.iter_mut().enumerate().take(d) {
            for (l, v) in row.iter_mut().enumerate().take(d) {
                *v = self.w[(a + k) * m + a + l];
            }
        }
        b
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
            let row = &self.w[i * m..(i + 1) * m];
            *xi = self.q[i] + row.iter().zip(r).map(|(a, b)| a * b).sum::<f64>();
        }
    }
}

/// Whether the `d × d` symmetric block `b` is positive definite, scale-free (blocks of 1e300 or
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
            let mut v = b[i][j] / s;
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
}
