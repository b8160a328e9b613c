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
