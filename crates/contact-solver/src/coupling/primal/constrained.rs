//! The linear solve of one guess of the primal active set: the rotated stiffness with the
//! guess's Dirichlet dofs, factorised once per mask and corrected by a low-rank (capacitance)
//! update while the mask changes on few dofs.

use super::{Correction, MAX_NEW_CORRECTIONS, PrimalCache, max_low_rank_update, position};
use crate::error::SolverError;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};

/// Solves the rotated system with Dirichlet conditions `w_d = z_d` on `mask` and the applied
/// `force` elsewhere, into `w`; returns the number of solves with the factor.
///
/// The factor `M₀` is of the mask `D₀` of its last factorisation. While the new mask differs
/// from `D₀` on at most [`max_low_rank_update`] dofs the difference is a low-rank correction
/// (capacitance matrix): a newly constrained dof `c` gets an unknown reaction along `e_c`, a
/// released one an unknown value with its column of `K̃` moved to the right-hand side, and a
/// small dense system enforces `w_c = z_c`, respectively `(K̃ w)_c = f_c`. Each changed dof
/// costs one solve, once per factorisation; beyond the limit the matrix is refactored.
pub(super) fn solve_constrained(
    cache: &mut PrimalCache,
    pattern: SymbolicSparseColMatRef<'_, usize>,
    contact_dofs: &[usize],
    mask: &[bool],
    z: &[f64],
    force: &[(usize, f64)],
    w: &mut [f64],
) -> Result<usize, SolverError> {
    let n = pattern.ncols();
    let internal = |what: &'static str| SolverError::InvalidSetting {
        what: "flexibility",
        value: 0.0,
        expected: what,
    };
    let diag = |values: &[f64], d: usize| values[position(pattern, d, d).unwrap_or(0)];
    let mut changed: Vec<usize> = match cache.factor {
        Some(_) => contact_dofs
            .iter()
            .copied()
            .filter(|&d| mask[d] != cache.factor_mask[d])
            .collect(),
        None => Vec::new(),
    };
    // refactor when the corrections would be too many in all, or too many new at once (a
    // large change of the guess: cheaper to refactor than to solve for its columns)
    // the changed dofs without a correction column for this factor yet
    let mut missing: Vec<usize> = changed
        .iter()
        .copied()
        .filter(|c| !cache.columns.iter().any(|col| col.dof == *c))
        .collect();
    if cache.factor.is_none()
        || changed.len() > max_low_rank_update(n)
        || missing.len() > MAX_NEW_CORRECTIONS
    {
        refactor(cache, pattern, mask)?;
        changed.clear();
        missing.clear();
    }
    base_rhs(cache, pattern, contact_dofs, mask, z, force, w);
    let d0 = &cache.factor_mask;
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let factor = cache
        .factor
        .as_ref()
        .ok_or_else(|| internal("a numeric factorisation (internal)"))?;
    // correction columns of the dofs not seen yet with this factor, solved in one block with
    // the base right-hand side (column 0)
    if missing.is_empty() {
        factor.solve_in_place(w);
        if changed.is_empty() {
            return Ok(1);
        }
    } else {
        let mut block = faer::Mat::<f64>::zeros(n, 1 + missing.len());
        for (i, &v) in w.iter().enumerate() {
            block[(i, 0)] = v;
        }
        let mut rows = Vec::with_capacity(missing.len());
        for (b, &c) in missing.iter().enumerate() {
            let b = b + 1;
            if d0[c] {
                // released: unknown value y_c, its column of K̃ on the right-hand side
                let upper = cache
                    .slot
                    .get(c)
                    .and_then(|&k| cache.upper.get(k))
                    .ok_or_else(|| internal("a contact dof's row (internal)"))?;
                let kc: Vec<(usize, f64)> = (cp[c]..cp[c + 1])
                    .map(|p| (ri[p], cache.rotated[p]))
                    .chain(upper.iter().map(|&(j, p)| (j, cache.rotated[p])))
                    .collect();
                for &(i, v) in &kc {
                    if !d0[i] && i != c {
                        block[(i, b)] = -v;
                    }
                }
                block[(c, b)] = diag(&cache.rotated, c);
                rows.push(Some(kc));
            } else {
                // newly constrained: unknown reaction along e_c
                block[(c, b)] = 1.0;
                rows.push(None);
            }
        }
        factor.solve_many_in_place(block.as_mut());
        for (i, v) in w.iter_mut().enumerate() {
            *v = block[(i, 0)];
        }
        for ((b, &c), row) in missing.iter().enumerate().zip(rows) {
            cache.columns.push(Correction {
                dof: c,
                column: block.col(b + 1).iter().copied().collect(),
                row,
            });
        }
    }
    let solves = 1 + missing.len();
    let cols: Vec<&Correction> = changed
        .iter()
        .map(|c| cache.columns.iter().find(|col| col.dof == *c))
        .collect::<Option<_>>()
        .ok_or_else(|| internal("a correction column (internal)"))?;
    let k = cols.len();
    let apply = |col: &Correction, v: &[f64]| -> f64 {
        match &col.row {
            None => v[col.dof],
            Some(row) => row.iter().map(|&(i, a)| a * v[i]).sum(),
        }
    };
    let mut cap = faer::Mat::<f64>::zeros(k, k);
    let mut rhs = faer::Mat::<f64>::zeros(k, 1);
    for (a, ca) in cols.iter().enumerate() {
        for (b, cb) in cols.iter().enumerate() {
            cap[(a, b)] = apply(ca, &cb.column);
        }
        let target = match ca.row {
            None => z[ca.dof],
            Some(_) => force
                .iter()
                .filter(|f| f.0 == ca.dof)
                .map(|f| f.1)
                .sum::<f64>(),
        };
        rhs[(a, 0)] = target - apply(ca, w);
    }
    let y = cap.partial_piv_lu().solve(&rhs);
    for (b, cb) in cols.iter().enumerate() {
        let yb = y[(b, 0)];
        for (wi, ci) in w.iter_mut().zip(&cb.column) {
            *wi += yb * ci;
        }
    }
    Ok(solves)
}

/// Factorises the rotated matrix with the Dirichlet rows and columns of `mask` decoupled (kept
/// diagonal) and forgets the correction columns of the previous factor.
fn refactor(
    cache: &mut PrimalCache,
    pattern: SymbolicSparseColMatRef<'_, usize>,
    mask: &[bool],
) -> Result<(), SolverError> {
    let n = pattern.ncols();
    let internal = |what: &'static str| SolverError::InvalidSetting {
        what: "flexibility",
        value: 0.0,
        expected: what,
    };
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let mut m = cache.rotated.clone();
    for j in 0..n {
        for p in cp[j]..cp[j + 1] {
            let i = ri[p];
            if i != j && (mask[i] || mask[j]) {
                m[p] = 0.0;
            }
        }
    }
    let mut solver = cache
        .symbolic
        .as_ref()
        .map(|s| s.1.clone())
        .ok_or_else(|| internal("a symbolic factorisation (internal)"))?;
    cache.factor = None;
    cache.columns.clear();
    solver.factor(SparseColMatRef::new(pattern, &m))?;
    cache.factor = Some(solver);
    cache.factor_mask.clear();
    cache.factor_mask.extend_from_slice(mask);
    cache.factorizations += 1;
    Ok(())
}

/// The right-hand side of a solve with the current factor (of the mask `D₀`) into `w`: the values
/// kept from `D₀`, the forces elsewhere, and `−K̃_{·D} z_D` from the columns of the kept
/// Dirichlet dofs (contact dofs only).
fn base_rhs(
    cache: &PrimalCache,
    pattern: SymbolicSparseColMatRef<'_, usize>,
    contact_dofs: &[usize],
    mask: &[bool],
    z: &[f64],
    force: &[(usize, f64)],
    w: &mut [f64],
) {
    let d0 = &cache.factor_mask;
    let diag = |values: &[f64], d: usize| values[position(pattern, d, d).unwrap_or(0)];
    // base right-hand side: the values kept from D₀, the forces elsewhere; −K̃_{·D} z_D from
    // the columns of the kept Dirichlet dofs (contact dofs only)
    w.fill(0.0);
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    for &d in contact_dofs {
        if mask[d] && d0[d] {
            let v = z[d];
            for p in cp[d]..cp[d + 1] {
                w[ri[p]] -= cache.rotated[p] * v;
            }
            for &(j, p) in &cache.upper[cache.slot[d]] {
                w[j] -= cache.rotated[p] * v;
            }
        }
    }
    for &d in contact_dofs {
        if d0[d] {
            w[d] = if mask[d] {
                diag(&cache.rotated, d) * z[d]
            } else {
                0.0
            };
        }
    }
    for &(d, f) in force {
        if !d0[d] {
            w[d] += f;
        }
    }
}
