//! The dense flexibility `F* = H K⁻¹ Hᵀ` of a set of contact rows, built with chunks of
//! right-hand sides of a factorised structure: the toolbox below the 2D and 3D simulations.

use crate::error::SolverError;
use crate::local::symmetrize;
use faer::Mat;
use fem_core::Structure;

/// Fills `w` (row-major `m × m`, `m = rows.len()`) at the rows `solved` of the columns
/// `columns` (a subset of `solved`) with `w[i][j] = H_{rows[i]} · K⁻¹ H_{rows[j]}ᵀ`, where
/// `h_rows[r]` holds row `r` of `H` as `(free dof, coefficient)` pairs; `chunk` right-hand
/// sides per solve. Entries outside are left as they are.
pub(crate) fn flexibility_into<S: Structure<D> + ?Sized, const D: usize>(
    structure: &S,
    h_rows: &[Vec<(usize, f64)>],
    rows: &[usize],
    solved: &[usize],
    columns: &[usize],
    chunk: usize,
    w: &mut [f64],
) -> Result<(), SolverError> {
    let m = rows.len();
    let chunk = chunk.min(columns.len()).max(1);
    let mut x = Mat::<f64>::zeros(structure.dof_count(), chunk);
    for block in columns.chunks(chunk) {
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

/// A dense `F*` built before, on the contacts `active` (its entries are reused for the
/// contacts the new active set shares with it, while the stiffness is unchanged).
pub(crate) struct Previous<'a> {
    pub(crate) w: &'a [f64],
    pub(crate) active: &'a [usize],
}

/// The symmetric `F*` (row-major `m × m`, `m = dim · active.len()`) on `active`, contact `i`
/// owning rows `dim i .. dim i + dim` of `h_rows`, solving the columns for which
/// `solve(local row)` holds. With `previous`, the blocks between contacts it shares are copied
/// and only the new contacts' columns are solved (`F*` of a fixed stiffness does not depend
/// on the active set; the copied entries are the ones a rebuild would compute, to rounding).
/// Returns the matrix and the number of columns solved.
pub(crate) fn build_dense<S: Structure<D> + ?Sized, const D: usize>(
    structure: &S,
    h_rows: &[Vec<(usize, f64)>],
    active: &[usize],
    solve: impl Fn(usize) -> bool,
    previous: Option<Previous<'_>>,
    chunk: usize,
) -> Result<(Vec<f64>, usize), SolverError> {
    let na = active.len();
    let m = D * na;
    let mut w = vec![0.0; m * m];
    // the position in the previous active set of each contact kept
    let mut kept: Vec<Option<usize>> = vec![None; na];
    if let Some(p) = previous.filter(|p| p.w.len() == (D * p.active.len()).pow(2)) {
        let position: std::collections::HashMap<usize, usize> =
            p.active.iter().enumerate().map(|(k, &i)| (i, k)).collect();
        for (k, &i) in active.iter().enumerate() {
            kept[k] = position.get(&i).copied();
        }
        let mo = D * p.active.len();
        for (k, ko) in kept.iter().enumerate() {
            let Some(ko) = ko else { continue };
            for (l, lo) in kept.iter().enumerate() {
                let Some(lo) = lo else { continue };
                for a in 0..D {
                    for b in 0..D {
                        w[(D * k + a) * m + D * l + b] = p.w[(D * ko + a) * mo + D * lo + b];
                    }
                }
            }
        }
    }
    let solved: Vec<usize> = (0..m).filter(|&j| solve(j)).collect();
    let columns: Vec<usize> = solved
        .iter()
        .copied()
        .filter(|&j| kept[j / D].is_none())
        .collect();
    let rows: Vec<usize> = active
        .iter()
        .flat_map(|&i| (0..D).map(move |d| D * i + d))
        .collect();
    flexibility_into(structure, h_rows, &rows, &solved, &columns, chunk, &mut w)?;
    // the kept contacts' rows of the new columns, by symmetry
    for &j in &columns {
        for &i in &solved {
            if kept[i / D].is_some() {
                w[j * m + i] = w[i * m + j];
            }
        }
    }
    symmetrize(&mut w, m);
    Ok((w, columns.len()))
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
