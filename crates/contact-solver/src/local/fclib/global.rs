//! FCLIB's global problem condensed to the local one.
//!
//! ```text
//! global (fclib.h, Siconos' GlobalFrictionContactProblem):
//!   M v = H r + f,        u = Hᵀ v + w,        M: n × n SPD,  H: n × m,  m = d n_c
//! eliminating v = M⁻¹ (H r + f):
//!   u = W r + q,          W = Hᵀ M⁻¹ H,        q = Hᵀ M⁻¹ f + w
//! ```
//! (Siconos' `globalFrictionContact_reformulation_FrictionContact` does the same.) `M` is
//! factorised sparse with faer: Cholesky when it is symmetric, LU otherwise or when Cholesky
//! finds a non-positive pivot; `M⁻¹ H` is then `m` dense columns.

use super::sparse::zeroed;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

/// `(W, q)` of the local problem, `W` dense row-major `m × m` and exactly symmetric.
///
/// `entries_m`, `entries_h` are the checked entries of `M` (`n × n`) and `H` (`n × m`);
/// `f` has `n` entries and `w` has `m` (the caller checked the sizes). The error is the reason
/// in the file's terms.
pub(super) fn condense(
    n: usize,
    entries_m: &[(usize, usize, f64)],
    entries_h: &[(usize, usize, f64)],
    m: usize,
    f: &[f64],
    w: &[f64],
) -> Result<(Vec<f64>, Vec<f64>), String> {
    let mut wmat = zeroed(m, m, "fclib_global/H")?;
    zeroed(n, m + 1, "fclib_global/H")?; // the dense right-hand sides below, refused early
    // right-hand sides [H | f], n × (m + 1)
    let mut rhs = Mat::<f64>::zeros(n, m + 1);
    for &(k, a, h) in entries_h {
        rhs[(k, a)] += h;
    }
    for (k, &fk) in f.iter().enumerate() {
        rhs[(k, m)] = fk;
    }
    solve_mass(n, entries_m, &mut rhs)?;
    let q = lower_products(n, entries_h, m, &rhs, w, &mut wmat);
    if let Some(k) = wmat.iter().chain(&q).position(|v| !v.is_finite()) {
        return Err(format!(
            "`fclib_global/M` is singular: the condensed {} is not finite",
            if k < m * m { "W" } else { "q" }
        ));
    }
    Ok((wmat, q))
}

/// `W = Hᵀ X` (exactly symmetric: the lower triangle, mirrored) and `q = Hᵀ y + w` from
/// `[X | y] = M⁻¹ [H | f]` (`rhs`, column-major `n × (m + 1)`), `W` into `wmat` (row-major
/// `m × m`, zeroed). `H` is gathered by columns once, so that each entry `W_ab` is a sparse
/// dot product of column `a` of `H` with the contiguous column `b` of `X`: `nnz(H) · m / 2`
/// multiply-adds in all, reading `X` in order (the entry-by-entry product it replaces read
/// `X` across its rows, a cache miss per multiply-add, and computed both triangles).
fn lower_products(
    n: usize,
    entries_h: &[(usize, usize, f64)],
    m: usize,
    rhs: &Mat<f64>,
    w: &[f64],
    wmat: &mut [f64],
) -> Vec<f64> {
    // H by columns: start[a]..start[a + 1] indexes the (row, value) pairs of column a
    let mut start = vec![0usize; m + 1];
    for &(_, a, _) in entries_h {
        start[a + 1] += 1;
    }
    for a in 0..m {
        start[a + 1] += start[a];
    }
    let mut next = start.clone();
    let mut by_col = vec![(0usize, 0.0); entries_h.len()];
    for &(k, a, h) in entries_h {
        by_col[next[a]] = (k, h);
        next[a] += 1;
    }
    let column = |a: usize| &by_col[start[a]..start[a + 1]];
    let dot = |a: usize, xb: &[f64]| column(a).iter().map(|&(k, h)| h * xb[k]).sum::<f64>();
    for b in 0..m {
        let xb = &rhs.col_as_slice(b)[..n];
        for a in b..m {
            let v = dot(a, xb);
            wmat[a * m + b] = v;
            wmat[b * m + a] = v;
        }
    }
    let y = &rhs.col_as_slice(m)[..n];
    // q_a = w_a + Σ h y_k, summed in the order of the file's entries
    (0..m)
        .map(|a| column(a).iter().fold(w[a], |s, &(k, h)| s + h * y[k]))
        .collect()
}

/// `rhs ← M⁻¹ rhs`: Cholesky of the lower triangle when `M` is symmetric, else (or when
/// Cholesky fails) LU.
fn solve_mass(n: usize, entries: &[(usize, usize, f64)], rhs: &mut Mat<f64>) -> Result<(), String> {
    let trips: Vec<_> = entries
        .iter()
        .map(|&(r, c, v)| Triplet::new(r, c, v))
        .collect();
    let mass = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &trips)
        .map_err(|e| format!("`fclib_global/M` cannot be assembled: {e:?}"))?;
    if is_symmetric(entries)
        && let Ok(llt) = mass.sp_cholesky(Side::Lower)
    {
        llt.solve_in_place(rhs.as_mut());
        return Ok(());
    }
    let lu = mass
        .sp_lu()
        .map_err(|e| format!("`fclib_global/M` is singular (sparse LU: {e:?})"))?;
    lu.solve_in_place(rhs.as_mut());
    Ok(())
}

/// Whether the entries (duplicates summed) form a symmetric matrix to `1e-12 · max|M|`.
fn is_symmetric(entries: &[(usize, usize, f64)]) -> bool {
    let mut sums = std::collections::HashMap::with_capacity(entries.len());
    for &(r, c, v) in entries {
        *sums.entry((r, c)).or_insert(0.0) += v;
    }
    let scale = sums
        .values()
        .fold(0.0_f64, |a: f64, v: &f64| a.max(v.abs()));
    sums.iter().all(|(&(r, c), &v)| {
        let t = sums.get(&(c, r)).copied().unwrap_or(0.0);
        (v - t).abs() <= 1e-12 * scale
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::fclib::sparse::{RawSparse, SparseForm};

    #[test]
    fn condense_works_on_one_mass() {
        // M = diag(4, 16), H = I (one 2D contact), f = (1, 2), w = (0.5, 0):
        // W = M⁻¹ = diag(0.25, 0.0625), q = M⁻¹ f + w = (0.75, 0.125), all exact in binary
        let m_dense = [4.0, 0.0, 0.0, 16.0];
        let m_mat = RawSparse::from_dense(&m_dense, 2, 2, SparseForm::CompressedColumn);
        let em = m_mat.entries("M").unwrap();
        let eh = vec![(0, 0, 1.0), (1, 1, 1.0)];
        let (w, q) = condense(2, &em, &eh, 2, &[1.0, 2.0], &[0.5, 0.0]).unwrap();
        assert_eq!(w, vec![0.25, 0.0, 0.0, 0.0625]);
        assert_eq!(q, vec![0.75, 0.125]);
    }

    #[test]
    fn condense_rejects_a_singular_mass() {
        let m_dense = [1.0, 1.0, 1.0, 1.0];
        let m_mat = RawSparse::from_dense(&m_dense, 2, 2, SparseForm::CompressedColumn);
        let em = m_mat.entries("M").unwrap();
        let eh = vec![(0, 0, 1.0), (1, 1, 1.0)];
        let e = condense(2, &em, &eh, 2, &[1.0, 2.0], &[0.0, 0.0]).unwrap_err();
        assert!(e.starts_with("`fclib_global/M` is singular"), "{e}");
    }
}
