//! The same reduced problem with `W` stored sparse, shared by the tests (`crate::support`) and
//! examples (included with `#[path]`).

use contact_solver::{ReducedProblem, SolverError};

/// `p` with `W` stored sparse (its non-zero entries); a sparse `p` is returned as it is.
///
/// # Errors
/// Those of [`ReducedProblem::from_triplets`] (none for a valid `p`).
pub fn sparse_twin(p: &ReducedProblem) -> Result<ReducedProblem, SolverError> {
    let Some(w) = p.w_dense() else {
        return Ok(p.clone());
    };
    let m = p.size();
    let (mut i, mut j, mut v) = (Vec::new(), Vec::new(), Vec::new());
    for a in 0..m {
        for b in 0..m {
            if w[a * m + b] != 0.0 {
                i.push(a);
                j.push(b);
                v.push(w[a * m + b]);
            }
        }
    }
    ReducedProblem::from_triplets(p.dimension(), &i, &j, &v, p.q().to_vec(), p.mu().to_vec())
}
