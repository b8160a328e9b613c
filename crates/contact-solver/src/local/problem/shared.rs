//! A reduced problem on a dense `W` shared with its owner (issue 38): a simulation keeps one
//! `F*` and the problems it solves (their clones, the last one kept for export) hold the same
//! allocation, where each held its own copy before.
//!
//! ```text
//! peak of the dense path ≈ factor of K + F* (once) + the solver's vectors (O(m))
//! ```
//! Nothing is copied unless `W` must be symmetrised (an asymmetry between round-off and the
//! tolerance): then the problem takes its own symmetrised copy and the owner's is untouched.

use super::{Delassus, ReducedProblem};
use crate::error::SolverError;
use crate::local::Asymmetry;
use crate::local::csr::CsrMatrix;
use std::sync::Arc;

impl ReducedProblem {
    /// As [`with_dimension`](Self::with_dimension), on a dense row-major `W` held shared:
    /// the problem keeps `w` itself (a reference count, no copy), unless `W` has to be
    /// symmetrised, which is done on a copy of its own.
    ///
    /// # Errors
    /// As for [`with_dimension`](Self::with_dimension).
    ///
    /// # Examples
    /// ```
    /// use contact_solver::ReducedProblem;
    /// use std::sync::Arc;
    /// let w = Arc::new(vec![2.0, 0.5, 0.5, 1.0]);
    /// let p = ReducedProblem::from_shared(2, Arc::clone(&w), vec![-1.0, 0.5], vec![0.3])?;
    /// // the problem holds the caller's allocation, not a copy
    /// assert!(Arc::ptr_eq(p.w_shared().unwrap(), &w) && Arc::strong_count(&w) == 2);
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn from_shared(
        dim: usize,
        w: Arc<Vec<f64>>,
        q: Vec<f64>,
        mu: Vec<f64>,
    ) -> Result<Self, SolverError> {
        Self::dense_validated(dim, w, q, mu, Asymmetry::default())
    }

    /// The same problem with `W` stored sparse ([`CsrMatrix::from_dense`]): the problem
    /// [`from_triplets`](Self::from_triplets) builds from the non-zero entries of `W`,
    /// validated alike, without sorting them. `None` when `W` is stored sparse or kept
    /// non-symmetric.
    pub(crate) fn stored_sparse(&self) -> Option<Result<Self, SolverError>> {
        let Delassus::Dense { m, w } = &self.w else {
            return None;
        };
        if self.columns.is_some() {
            return None;
        }
        let a = CsrMatrix::from_dense(self.dim, *m, w);
        let (q, mu) = (self.q.clone(), self.mu.clone());
        Some(Self::validated(
            self.dim,
            Delassus::Sparse(a),
            q,
            mu,
            Asymmetry::default(),
        ))
    }

    /// The dense `W` as held (shared with whoever else holds it), or `None` when `W` is
    /// stored sparse.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::ReducedProblem;
    /// let p = ReducedProblem::new(vec![2.0, 0.0, 0.0, 1.0], vec![-1.0, 0.5], vec![0.3])?;
    /// // a clone of the problem shares W
    /// let c = p.clone();
    /// assert!(std::sync::Arc::ptr_eq(p.w_shared().unwrap(), c.w_shared().unwrap()));
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn w_shared(&self) -> Option<&Arc<Vec<f64>>> {
        match &self.w {
            Delassus::Dense { w, .. } => Some(w),
            Delassus::Sparse(_) => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 37: the sparse copy is the problem built from `W`'s non-zero entries as
    /// triplets, exactly (pattern, values, checks), on a `W` with zero and non-zero blocks.
    #[test]
    fn issue_37_stored_sparse_matches_triplets() {
        let p = crate::local::generate::random_problem_in(3, 12, 4);
        let m = p.size();
        let mut w = p.w_dense().unwrap().to_vec();
        for (k, v) in w.iter_mut().enumerate() {
            let (bi, bj) = (k / m / 3, k % m / 3);
            if bi != bj && (bi + bj) % 3 != 0 {
                *v = 0.0;
            }
        }
        // one zero entry inside a kept block
        w[1] = 0.0;
        w[m] = 0.0;
        let dense = ReducedProblem::with_dimension(3, w.clone(), p.q().to_vec(), p.mu().to_vec());
        let sparse = dense.unwrap().stored_sparse().unwrap().unwrap();
        let (mut rows, mut cols, mut vals) = (vec![], vec![], vec![]);
        for (k, &v) in w.iter().enumerate().filter(|(_, v)| **v != 0.0) {
            rows.push(k / m);
            cols.push(k % m);
            vals.push(v);
        }
        let (q, mu) = (p.q().to_vec(), p.mu().to_vec());
        let triplets = ReducedProblem::from_triplets(3, &rows, &cols, &vals, q, mu).unwrap();
        assert_eq!(sparse, triplets);
        assert!(triplets.stored_sparse().is_none());
    }

    #[test]
    fn issue_38_from_shared_keeps_the_allocation() {
        let w = Arc::new(vec![2.0, 0.5, 0.5, 1.0]);
        let p = ReducedProblem::from_shared(2, Arc::clone(&w), vec![-1.0, 0.5], vec![0.3]).unwrap();
        assert!(Arc::ptr_eq(p.w_shared().unwrap(), &w));
        // the same problem as from an owned copy
        let owned = ReducedProblem::new(w.to_vec(), vec![-1.0, 0.5], vec![0.3]).unwrap();
        assert_eq!(p, owned);
    }

    #[test]
    fn issue_38_from_shared_symmetrises_a_copy() {
        // asymmetric by 3e-7 relative: symmetrised, on a copy; the owner's W is untouched
        let w = Arc::new(vec![2.0, 0.3, 0.3 + 6e-7, 1.0]);
        let p = ReducedProblem::from_shared(2, Arc::clone(&w), vec![-1.0, 0.5], vec![0.3]).unwrap();
        assert!(!Arc::ptr_eq(p.w_shared().unwrap(), &w));
        assert_eq!(w[2], 0.3 + 6e-7);
        let d = p.w_dense().unwrap();
        assert_eq!(d[1], d[2]);
        // the validation errors of `with_dimension`
        let e = ReducedProblem::from_shared(2, Arc::new(vec![1.0]), vec![-1.0, 0.5], vec![0.3]);
        assert!(matches!(
            e,
            Err(SolverError::SizeMismatch { what: "W", .. })
        ));
    }
}
