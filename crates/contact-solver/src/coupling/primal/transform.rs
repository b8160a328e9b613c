//! The transformed stiffness of the primal active set: the contactor dofs renamed as the local
//! jumps, and its pattern when a contact has a deformable target.

use super::frame::LocalFrame;
use super::{PrimalCache, position};
use crate::error::SolverError;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};

impl PrimalCache {
    /// The transformed stiffness `K̃ = Tᵀ K T` (lower triangle) with `u = T v`: the identity
    /// but at the contactor dofs, `u_a = Pᵀ x + Σ_k w_k u_k` ([`LocalFrame`]). Against rigid
    /// obstacles `T` is a rotation per node and `K̃` keeps `K`'s pattern; against deformable
    /// targets a contactor dof couples with its targets' neighbours too, and `K̃` gets the
    /// pattern of `Tᵀ K T` (`expanded`).
    pub(super) fn rotate(
        &mut self,
        k: SparseColMatRef<'_, usize, f64>,
        frames: &[LocalFrame],
    ) -> Result<(), SolverError> {
        let kpat = k.symbolic();
        let n = kpat.ncols();
        let values = k.val();
        // members[slot of d]: the new dofs original dof d is a combination of, with the
        // coefficients
        let mut members: Vec<Vec<(usize, f64)>> = Vec::new();
        let mut slot = vec![usize::MAX; n];
        for f in frames {
            for (e, d) in f.dofs.iter().enumerate() {
                if let Some(d) = *d {
                    slot[d] = members.len();
                    let mut m: Vec<(usize, f64)> = f
                        .dofs
                        .iter()
                        .enumerate()
                        .filter_map(|(c, dc)| dc.map(|dc| (dc, f.p[c][e])))
                        .collect();
                    m.extend(f.carry.iter().filter(|c| c.0 == e).map(|&(_, j, w)| (j, w)));
                    members.push(m);
                }
            }
        }
        self.expanded = frames
            .iter()
            .any(|f| !f.carry.is_empty())
            .then(|| std::sync::Arc::new(expand(kpat, &slot, &members)));
        let expanded = self.expanded.clone();
        let pattern = expanded.as_deref().map_or(kpat, |p| p.as_ref());
        let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
        self.upper = vec![Vec::new(); members.len()];
        for j in 0..n {
            for (off, &i) in ri[cp[j]..cp[j + 1]].iter().enumerate() {
                if i != j && slot[i] != usize::MAX {
                    self.upper[slot[i]].push((j, cp[j] + off));
                }
            }
        }
        self.slot.clone_from(&slot);
        self.node_of_slot = frames
            .iter()
            .enumerate()
            .flat_map(|(kk, f)| f.dofs.iter().flatten().map(move |_| kk))
            .collect();
        self.column_of = vec![usize::MAX; members.len()];
        self.columns.clear();
        let mut probe_at = vec![usize::MAX; n];
        let mut adjacent = vec![Vec::new(); frames.len()];
        for (kk, f) in frames.iter().enumerate() {
            for &c in f.dofs.iter().flatten() {
                let row = ri[cp[c]..cp[c + 1]]
                    .iter()
                    .copied()
                    .chain(self.upper[slot[c]].iter().map(|&(j, _)| j));
                for j in std::iter::once(c).chain(row) {
                    probe_at[j] = 0;
                    if let Some(&o) = self.node_of_slot.get(slot[j])
                        && o != kk
                        && !adjacent[kk].contains(&o)
                    {
                        adjacent[kk].push(o);
                    }
                }
            }
        }
        self.probe = (0..n).filter(|&i| probe_at[i] == 0).collect();
        for (k, &i) in self.probe.iter().enumerate() {
            probe_at[i] = k;
        }
        self.probe_at = probe_at;
        self.adjacent = adjacent;
        let out = &mut self.rotated;
        out.clear();
        out.resize(ri.len(), 0.0);
        let missing = || SolverError::InvalidSetting {
            what: "flexibility",
            value: 0.0,
            expected: "a stiffness pattern that couples the dofs of every contact node (ActiveSet)",
        };
        let add = |i: usize, j: usize, v: f64, out: &mut Vec<f64>| -> Result<(), SolverError> {
            if i >= j {
                let pos = position(pattern, i, j).ok_or_else(missing)?;
                out[pos] += v;
            }
            Ok(())
        };
        let (kcp, kri) = (kpat.col_ptr(), kpat.row_idx());
        for q in 0..n {
            for p in kcp[q]..kcp[q + 1] {
                let (row, v) = (kri[p], values[p]);
                if slot[row] == usize::MAX && slot[q] == usize::MAX && expanded.is_none() {
                    out[p] += v;
                    continue;
                }
                let own_row = [(row, 1.0)];
                let own_q = [(q, 1.0)];
                let mp: &[(usize, f64)] = match slot[row] {
                    usize::MAX => &own_row,
                    s => &members[s],
                };
                let mq: &[(usize, f64)] = match slot[q] {
                    usize::MAX => &own_q,
                    s => &members[s],
                };
                for &(i, a) in mp {
                    for &(j, b) in mq {
                        // ordered entry (row, q) → K̃[i, j]; its mirror (q, row) → K̃[j, i]
                        add(i, j, a * v * b, out)?;
                        if row != q {
                            add(j, i, a * v * b, out)?;
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

/// The lower pattern of `Tᵀ K T` (see [`PrimalCache::rotate`]): every pair of new dofs that two
/// coupled original dofs are combinations of.
fn expand(
    k: SymbolicSparseColMatRef<'_, usize>,
    slot: &[usize],
    members: &[Vec<(usize, f64)>],
) -> SymbolicSparseColMat<usize> {
    let n = k.ncols();
    let (cp, ri) = (k.col_ptr(), k.row_idx());
    let mut cols: Vec<Vec<usize>> = (0..n).map(|q| ri[cp[q]..cp[q + 1]].to_vec()).collect();
    let of = |d: usize| -> Vec<usize> {
        match slot[d] {
            usize::MAX => vec![d],
            s => members[s].iter().map(|m| m.0).collect(),
        }
    };
    for q in 0..n {
        for &row in &ri[cp[q]..cp[q + 1]] {
            if slot[row] == usize::MAX && slot[q] == usize::MAX {
                continue;
            }
            for i in of(row) {
                for j in of(q) {
                    cols[i.min(j)].push(i.max(j));
                }
            }
        }
    }
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0);
    for mut c in cols {
        c.sort_unstable();
        c.dedup();
        row_idx.extend(c);
        col_ptr.push(row_idx.len());
    }
    SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx)
}
