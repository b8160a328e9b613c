//! What both routes of FCLIB's global condensation share: the condensed `(W, q)` and the
//! sparse solve with (a block of) `M`.

use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

/// The condensed `W`: dense row-major `m × m`, or sparse triplets (each `(row, col)` once).
pub(super) enum CondensedW {
    /// Row-major `m × m`.
    Dense(Vec<f64>),
    /// Triplets `(rows[k], cols[k], vals[k])`.
    Triplets {
        rows: Vec<usize>,
        cols: Vec<usize>,
        vals: Vec<f64>,
    },
}

/// `W` and `q` of the local problem.
pub(super) struct Condensed {
    pub w: CondensedW,
    pub q: Vec<f64>,
}

/// `rhs ← M⁻¹ rhs`: Cholesky of the lower triangle when `M` is symmetric, else (or when
/// Cholesky fails) LU.
pub(super) fn solve_mass(
    n: usize,
    entries: &[(usize, usize, f64)],
    rhs: &mut Mat<f64>,
) -> Result<(), String> {
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
pub(super) fn is_symmetric(entries: &[(usize, usize, f64)]) -> bool {
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
