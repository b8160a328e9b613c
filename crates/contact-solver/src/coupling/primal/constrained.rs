//! The linear solve of one guess of the primal active set: the rotated stiffness with the
//! guess's Dirichlet dofs, factorised once per mask and corrected by a low-rank (capacitance)
//! update while the mask changes on few dofs.

use super::{Correction, MAX_NEW_CORRECTIONS, PrimalCache, max_low_rank_update, position};
use crate::error::SolverError;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};

/// The last structure solve with the current factor, before its corrections: its values on the
/// probe dofs ([`PrimalCache`]) and the conditions it was solved for, by contact slot. Any
/// guess that differs from these conditions only on dofs with a correction column is solved
/// from it exactly by [`correct`], without another structure solve.
#[derive(Default)]
pub(super) struct Base {
    /// The uncorrected solution on the probe dofs.
    pub(super) w: Vec<f64>,
    /// Per slot: whether the dof was held (Dirichlet).
    pub(super) fixed: Vec<bool>,
    /// Per slot: the applied force (zero on a held dof).
    pub(super) force: Vec<f64>,
}

fn internal(what: &'static str) -> SolverError {
    SolverError::InvalidSetting {
        what: "flexibility",
        value: 0.0,
        expected: what,
    }
}

/// The applied force of every contact slot from the guess's force list.
pub(super) fn slot_forces(cache: &PrimalCache, force: &[(usize, f64)], out: &mut Vec<f64>) {
    out.clear();
    out.resize(cache.upper.len(), 0.0);
    for &(d, f) in force {
        if let Some(o) = cache.slot.get(d).and_then(|&s| out.get_mut(s)) {
            *o += f;
        }
    }
}

/// Solves the rotated system with Dirichlet conditions `w_d = z_d` on `mask` and the applied
/// `force` elsewhere, into `w` (exact on the probe dofs, [`PrimalCache`]); returns the number of
/// solves with the factor. `speculative` dofs get a correction column in the same block
/// solve even though their condition has not changed (the window around a moving front, see
/// the inner iteration of [`super::inner`]); `base` receives the uncorrected solve.
///
/// The factor `M₀` is of the mask `D₀` of its last factorisation. While the new mask differs
/// from `D₀` on at most [`max_low_rank_update`] dofs the difference is a low-rank correction
/// (capacitance matrix): a newly constrained dof `c` gets an unknown reaction along `e_c`, a
/// released one an unknown value with its column of `K̃` moved to the right-hand side, and a
/// small dense system enforces `w_c = z_c`, respectively `(K̃ w)_c = f_c`. Each changed dof
/// costs one solve, once per factorisation; beyond the limit the matrix is refactored.
#[allow(clippy::too_many_arguments)]
pub(super) fn solve_constrained(
    cache: &mut PrimalCache,
    pattern: SymbolicSparseColMatRef<'_, usize>,
    contact_dofs: &[usize],
    mask: &[bool],
    z: &[f64],
    force: &[(usize, f64)],
    speculative: &[usize],
    w: &mut [f64],
    base: &mut Base,
) -> Result<usize, SolverError> {
    let n = pattern.ncols();
    let diag = |values: &[f64], d: usize| values[position(pattern, d, d).unwrap_or(0)];
    let has_column = |cache: &PrimalCache, c: usize| cache.column_of[cache.slot[c]] != usize::MAX;
    let changed = match cache.factor {
        Some(_) => contact_dofs
            .iter()
            .filter(|&&d| mask[d] != cache.factor_mask[d])
            .count(),
        None => 0,
    };
    // the changed dofs without a correction column for this factor yet
    let mut missing: Vec<usize> = match cache.factor {
        Some(_) => contact_dofs
            .iter()
            .copied()
            .filter(|&d| mask[d] != cache.factor_mask[d] && !has_column(cache, d))
            .collect(),
        None => Vec::new(),
    };
    // refactor when the corrections would be too many in all, or too many new at once (a
    // large change of the guess: cheaper to refactor than to solve for its columns)
    if cache.factor.is_none()
        || changed > max_low_rank_update(n)
        || missing.len() > MAX_NEW_CORRECTIONS
    {
        refactor(cache, pattern, mask)?;
        missing.clear();
    }
    let ahead: Vec<usize> = speculative
        .iter()
        .copied()
        .filter(|&c| !has_column(cache, c) && !missing.contains(&c))
        .collect();
    missing.extend(ahead);
    base_rhs(cache, pattern, contact_dofs, mask, z, force, w);
    let d0 = &cache.factor_mask;
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let factor = cache
        .factor
        .as_ref()
        .ok_or_else(|| internal("a numeric factorisation (internal)"))?;
    // correction columns of the dofs not seen yet with this factor, solved in one block with
    // the base right-hand side (column 0)
    let mut fresh = Vec::with_capacity(missing.len());
    if missing.is_empty() {
        factor.solve_in_place(w);
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
                let on_probe = kc
                    .iter()
                    .map(|&(i, v)| (cache.probe_at[i], v))
                    .collect::<Vec<_>>();
                if on_probe.iter().any(|p| p.0 == usize::MAX) {
                    return Err(internal("a contact row on the probe dofs (internal)"));
                }
                rows.push(Some(on_probe));
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
            let col = block.col(b + 1);
            fresh.push(Correction {
                dof: c,
                at: cache.probe_at[c],
                column: cache.probe.iter().map(|&i| col[i]).collect(),
                row,
            });
        }
    }
    let solves = 1 + missing.len();
    for col in fresh {
        let s = cache.slot[col.dof];
        cache.column_of[s] = cache.columns.len();
        cache.columns.push(col);
    }
    // the uncorrected solve and its conditions
    base.w.clear();
    base.w.extend(cache.probe.iter().map(|&i| w[i]));
    base.fixed.clear();
    base.fixed.extend(contact_dofs.iter().map(|&d| mask[d]));
    slot_forces(cache, force, &mut base.force);
    correct(cache, mask, z, &base.force, base, w)?;
    Ok(solves)
}

/// The solution on the probe dofs, into `w`, for the Dirichlet set `mask` (values `z`) and the
/// slot forces `forces`, from the uncorrected solve `base`: exact when the conditions differ
/// from `base`'s only on dofs with a correction column. The dofs whose condition differs from
/// the factor's mask `D₀` are the unknowns of the capacitance system; a force that differs
/// from `base`'s on a free dof with a column is a known load along that column.
pub(super) fn correct(
    cache: &PrimalCache,
    mask: &[bool],
    z: &[f64],
    forces: &[f64],
    base: &Base,
    w: &mut [f64],
) -> Result<(), SolverError> {
    let d0 = &cache.factor_mask;
    let mut wp = base.w.clone();
    // the unknowns: a held dof's value condition or a released dof's row condition
    let mut unknown: Vec<&Correction> = Vec::new();
    for col in &cache.columns {
        let (c, s) = (col.dof, cache.slot[col.dof]);
        if mask[c] {
            // held: by M₀ itself only if it was held in D₀ and in `base` (whose right-hand
            // side then carries its value)
            if !(d0[c] && base.fixed[s]) {
                unknown.push(col);
            }
        } else if d0[c] {
            unknown.push(col);
        } else {
            let load = forces[s] - base.force[s];
            if load != 0.0 {
                for (wi, ci) in wp.iter_mut().zip(&col.column) {
                    *wi += load * ci;
                }
            }
        }
    }
    let k = unknown.len();
    if k > 0 {
        let apply = |col: &Correction, v: &[f64]| -> f64 {
            match (&col.row, mask[col.dof]) {
                (Some(row), false) => row.iter().map(|&(i, a)| a * v[i]).sum(),
                _ => v[col.at],
            }
        };
        let mut cap = faer::Mat::<f64>::zeros(k, k);
        let mut rhs = faer::Mat::<f64>::zeros(k, 1);
        for (a, ca) in unknown.iter().enumerate() {
            for (b, cb) in unknown.iter().enumerate() {
                cap[(a, b)] = apply(ca, &cb.column);
            }
            let target = if mask[ca.dof] {
                z[ca.dof]
            } else {
                forces[cache.slot[ca.dof]]
            };
            rhs[(a, 0)] = target - apply(ca, &wp);
        }
        let y = cap.partial_piv_lu().solve(&rhs);
        for (b, cb) in unknown.iter().enumerate() {
            let yb = y[(b, 0)];
            for (wi, ci) in wp.iter_mut().zip(&cb.column) {
                *wi += yb * ci;
            }
        }
    }
    for (&i, &v) in cache.probe.iter().zip(&wp) {
        w[i] = v;
    }
    Ok(())
}

/// Factorises the rotated matrix with the Dirichlet rows and columns of `mask` decoupled (kept
/// diagonal) and forgets the correction columns of the previous factor.
fn refactor(
    cache: &mut PrimalCache,
    pattern: SymbolicSparseColMatRef<'_, usize>,
    mask: &[bool],
) -> Result<(), SolverError> {
    let n = pattern.ncols();
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
        .map(|s| s.2.clone())
        .ok_or_else(|| internal("a symbolic factorisation (internal)"))?;
    cache.factor = None;
    cache.columns.clear();
    cache.column_of.fill(usize::MAX);
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
