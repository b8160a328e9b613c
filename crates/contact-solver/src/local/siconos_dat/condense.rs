//! A global problem of a `.dat` file condensed to the local one.
//!
//! ```text
//! Siconos' GlobalFrictionContactProblem:   M v = q + H r,   u = Hᵀ v + b
//! eliminating v = M⁻¹ (q + H r):           u = W r + q_loc,  W = Hᵀ M⁻¹ H,  q_loc = Hᵀ M⁻¹ q + b
//! ```
//! `M` is factorised once (sparse LU, faer), `M⁻¹ [H | q]` has `m + 1` dense columns.

use faer::Mat;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};

/// The most entries of the dense `M⁻¹ H` (`n · (m + 1)`) and of `W` (`m²`).
pub(super) const MAX_DENSE: usize = 1 << 28;

/// `(W row-major m × m, q_loc)` from the entries of `M` (`n × n`) and `H` (`n × m`); the
/// error is the reason in the file's terms.
pub(super) fn condense(
    n: usize,
    mass: &[(usize, usize, f64)],
    h: &[(usize, usize, f64)],
    m: usize,
    q: &[f64],
    b: &[f64],
) -> Result<(Vec<f64>, Vec<f64>), String> {
    let too_big = |r: usize, c: usize| r.checked_mul(c).is_none_or(|e| e > MAX_DENSE);
    if too_big(n, m + 1) || too_big(m, m) {
        return Err(format!(
            "the global problem ({n} dofs, {m} contact unknowns) is too large to condense densely"
        ));
    }
    let trips: Vec<_> = mass
        .iter()
        .map(|&(r, c, v)| Triplet::new(r, c, v))
        .collect();
    let mat = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &trips)
        .map_err(|e| format!("`M` cannot be assembled: {e:?}"))?;
    let lu = mat
        .sp_lu()
        .map_err(|e| format!("`M` is singular (sparse LU: {e:?})"))?;
    let mut rhs = Mat::<f64>::zeros(n, m + 1);
    for &(k, a, v) in h {
        rhs[(k, a)] += v;
    }
    for (k, &v) in q.iter().enumerate() {
        rhs[(k, m)] = v;
    }
    lu.solve_in_place(rhs.as_mut());
    let mut w = vec![0.0; m * m];
    let mut q_loc = b.to_vec();
    // W[a][c] = Σ_k H[k][a] X[k][c],  q_loc[a] += Σ_k H[k][a] y[k]
    for &(k, a, v) in h {
        let row = &mut w[a * m..(a + 1) * m];
        for (c, wc) in row.iter_mut().enumerate() {
            *wc += v * rhs[(k, c)];
        }
        q_loc[a] += v * rhs[(k, m)];
    }
    if w.iter().chain(&q_loc).any(|v| !v.is_finite()) {
        return Err("`M` is singular: the condensed W or q is not finite".into());
    }
    Ok((w, q_loc))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn condense_works() {
        // M = diag(2, 4), H = [1 0; 1 1] (2 dofs, m = 2): W = Hᵀ M⁻¹ H = [3/4 1/4; 1/4 1/4],
        // q_loc = Hᵀ M⁻¹ q + b with q = (2, 4), b = (1, 0): (1 + 1 + 1, 1) = (3, 1)
        let mass = [(0, 0, 2.0), (1, 1, 4.0)];
        let h = [(0, 0, 1.0), (1, 0, 1.0), (1, 1, 1.0)];
        let (w, q) = condense(2, &mass, &h, 2, &[2.0, 4.0], &[1.0, 0.0]).unwrap();
        // exact in binary: halves and quarters
        assert_eq!(w, vec![0.75, 0.25, 0.25, 0.25]);
        assert_eq!(q, vec![3.0, 1.0]);
    }

    #[test]
    fn condense_rejects_a_singular_mass() {
        let mass = [(0, 0, 1.0)];
        let h = [(0, 0, 1.0), (1, 1, 1.0)];
        let e = condense(2, &mass, &h, 2, &[0.0, 0.0], &[0.0, 0.0]).unwrap_err();
        assert!(e.contains("singular"), "{e}");
    }
}
