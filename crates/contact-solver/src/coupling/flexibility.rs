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
