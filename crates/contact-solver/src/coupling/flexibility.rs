//! The dense flexibility `F* = H K⁻¹ Hᵀ` of a set of contact rows, built with chunks of
//! right-hand sides of a factorised structure: the toolbox below the 2D and 3D simulations.

use crate::error::SolverError;
use faer::Mat;
use fem_core::Structure;

/// Fills `w` (row-major `m × m`, `m = rows.len()`) at the rows and columns `solved` with
/// `w[i][j] = H_{rows[i]} · K⁻¹ H_{rows[j]}ᵀ`, where `h_rows[r]` holds row `r` of `H` as
/// `(free dof, coefficient)` pairs; `chunk` right-hand sides per solve. Entries outside
/// `solved` are left as they are.
pub(crate) fn flexibility_into<S: Structure<D> + ?Sized, const D: usize>(
    structure: &S,
    h_rows: &[Vec<(usize, f64)>],
    rows: &[usize],
    solved: &[usize],
    chunk: usize,
    w: &mut [f64],
) -> Result<(), SolverError> {
    let m = rows.len();
    let chunk = chunk.min(solved.len()).max(1);
    let mut x = Mat::<f64>::zeros(structure.dof_count(), chunk);
    for block in solved.chunks(chunk) {
        let nc = block.len();
        x.fill(0.0);
        for (c, &j) in block.iter().enumerate() {
            for &(dof, a) in &h_rows[rows[j]] {
                x[(dof, c)] += a;
            }
        }
        structure.solve_many_in_place(x.as_mut().subcols_mut(0, nc))?;
        for &i in solved {
            let row = &h_rows[rows[i]];
            for (c, &j) in block.iter().enumerate() {
                w[i * m + j] = row.iter().map(|&(dof, a)| a * x[(dof, c)]).sum();
            }
        }
    }
    Ok(())
}

/// The diagonal blocks of `F*` (`dim × dim`, row-major) of up to `max_samples` contacts spread
/// evenly over `active` (contact `i` owns rows `dim i .. dim i + dim` of `h_rows`), from one
/// multi-right-hand-side solve: returns the sampled positions in `active` and their blocks.
/// For the base penalties `ρ⁰` of the matrix-free iteration ([`from_nearest_sample`]).
pub(crate) fn sampled_diagonal_blocks<S: Structure<D> + ?Sized, const D: usize>(
    structure: &S,
    h_rows: &[Vec<(usize, f64)>],
    active: &[usize],
    dim: usize,
    max_samples: usize,
) -> Result<(Vec<usize>, Vec<Vec<f64>>), SolverError> {
    let na = active.len();
    let ns = na.min(max_samples);
    let samples: Vec<usize> = (0..ns).map(|k| (2 * k + 1) * na / (2 * ns)).collect();
    let mut x = Mat::<f64>::zeros(structure.dof_count(), dim * ns);
    for (c, &k) in samples.iter().enumerate() {
        let i = active[k];
        for d in 0..dim {
            for &(dof, a) in &h_rows[dim * i + d] {
                x[(dof, dim * c + d)] += a;
            }
        }
    }
    structure.solve_many_in_place(x.as_mut())?;
    let blocks = samples
        .iter()
        .enumerate()
        .map(|(c, &k)| {
            let i = active[k];
            (0..dim * dim)
                .map(|e| {
                    let (row, col) = (e / dim, e % dim);
                    h_rows[dim * i + row]
                        .iter()
                        .map(|&(dof, a)| a * x[(dof, dim * c + col)])
                        .sum()
                })
                .collect()
        })
        .collect();
    Ok((samples, blocks))
}

/// A value for each of `0..n` from the nearest of `samples` (positions, increasing) and their
/// `values`: contacts are listed in order along their interfaces, so neighbours in the list
/// are neighbours on the body.
pub(crate) fn from_nearest_sample(samples: &[usize], values: &[f64], n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| {
            let nearest = samples
                .iter()
                .enumerate()
                .min_by_key(|(_, s)| s.abs_diff(k))
                .map_or(0, |(c, _)| c);
            values[nearest]
        })
        .collect()
}
