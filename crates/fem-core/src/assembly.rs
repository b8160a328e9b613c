//! The sparsity pattern of the reduced stiffness (built once per mesh and dof map) and the
//! in-place refill of its values.
//!
//! Only the lower triangle of the reduced (free-dof) matrix is stored, in CSC form, as faer's
//! Cholesky reads it. Couplings between prescribed and other dofs are kept apart, as merged
//! triplets, for the right-hand side `−K_fp ū` and for support reactions.

use crate::dirichlet::{Dof, DofMap};
use crate::error::FemError;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use nalgebra::DMatrix;

/// Lower-triangular CSC pattern of the reduced stiffness.
#[derive(Clone, Debug)]
pub struct Pattern {
    symbolic: SymbolicSparseColMat<usize>,
}

impl Pattern {
    /// Builds the pattern from the node lists of the elements.
    ///
    /// # Errors
    /// [`FemError::LinearAlgebra`] if faer rejects the structure (index overflow).
    pub fn new<'a, const D: usize>(
        dofs: &DofMap<D>,
        elements: impl Iterator<Item = &'a [usize]>,
    ) -> Result<Self, FemError> {
        let n = dofs.free_count();
        // the node graph first (10 × 10 pairs for a P2 tetrahedron, not its 30 × 31 / 2 dof
        // pairs), each node's neighbours sorted and deduplicated once: the dof lists below are
        // then built without repeats, so that the pattern's transient memory stays near its
        // own (the 3D models' peak is the factor's; this keeps the assembly below it)
        let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); dofs.node_count()];
        for cell in elements {
            for &b in cell {
                neighbours[b].extend_from_slice(cell);
            }
        }
        for list in &mut neighbours {
            list.sort_unstable();
            list.dedup();
            list.shrink_to_fit();
        }
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (b, list) in neighbours.iter_mut().enumerate() {
            for j in dofs.free_dofs(b).into_iter().flatten() {
                for &a in list.iter() {
                    cols[j].extend(dofs.free_dofs(a).into_iter().flatten().filter(|&i| i >= j));
                }
            }
            *list = Vec::new();
        }
        // Every free dof gets its diagonal, even if no element touches it, so that a missing
        // connection shows up as a zero pivot (NotPositiveDefinite), not a structural error.
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for (j, col) in cols.iter_mut().enumerate() {
            col.push(j);
            col.sort_unstable();
            col.dedup();
            row_idx.extend_from_slice(col);
            col_ptr.push(row_idx.len());
            *col = Vec::new();
        }
        let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        Ok(Self { symbolic })
    }

    /// faer's symbolic matrix.
    #[inline]
    pub fn symbolic(&self) -> &SymbolicSparseColMat<usize> {
        &self.symbolic
    }

    /// Number of stored entries.
    #[inline]
    pub fn nnz(&self) -> usize {
        self.symbolic.row_idx().len()
    }

    /// Dimension.
    #[inline]
    pub fn dim(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Position of entry `(row, col)`, `row ≥ col`, in the values array.
    ///
    /// # Panics
    /// If the entry is not in the pattern (an internal invariant).
    #[inline]
    #[track_caller]
    pub fn position(&self, row: usize, col: usize) -> usize {
        let start = self.symbolic.col_ptr()[col];
        let end = self.symbolic.col_ptr()[col + 1];
        let rows = &self.symbolic.row_idx()[start..end];
        start
            + rows
                .binary_search(&row)
                .expect("entry outside the sparsity pattern")
    }

    /// `y = A x` for the symmetric matrix `A` whose lower triangle has these `values`.
    ///
    /// # Panics
    /// If `values.len() != nnz()` or `x`, `y` are not of length `dim()`.
    #[track_caller]
    pub(crate) fn symmetric_mul_into(&self, values: &[f64], x: &[f64], y: &mut [f64]) {
        let n = self.dim();
        assert_eq!(values.len(), self.nnz(), "one value per stored entry");
        assert!(
            x.len() == n && y.len() == n,
            "x and y of the matrix's dimension"
        );
        lower_symmetric_mul_into(
            self.symbolic.col_ptr(),
            self.symbolic.row_idx(),
            values,
            x,
            y,
        );
    }

    /// A faer view of the matrix with these `values`.
    ///
    /// # Panics
    /// If `values.len() != nnz()`.
    #[inline]
    #[track_caller]
    pub fn view<'a>(&'a self, values: &'a [f64]) -> SparseColMatRef<'a, usize, f64> {
        SparseColMatRef::new(self.symbolic.as_ref(), values)
    }
}

/// Couplings of the prescribed dofs with every dof: merged triplets `(p, dof, K_p,dof)`.
#[derive(Clone, Debug, Default)]
pub struct PrescribedCoupling {
    entries: Vec<(usize, Dof, f64)>,
}

impl PrescribedCoupling {
    /// The merged entries `(prescribed index, dof, value)`.
    #[inline]
    pub fn entries(&self) -> &[(usize, Dof, f64)] {
        &self.entries
    }

    /// The support reactions `R = K u − f` at the prescribed dofs of `dofs`, from the nodal
    /// `displacements`, the reference load and the initial-stress forces (per node component,
    /// `D` per node) at `load_factor`: `((node, component), reaction)`.
    pub(crate) fn reactions<const D: usize>(
        &self,
        dofs: &crate::dirichlet::DofMap<D>,
        displacements: &[[f64; D]],
        load: &[f64],
        initial_force: &[f64],
        load_factor: f64,
    ) -> Vec<((usize, crate::dirichlet::Component), f64)> {
        let prescribed = dofs.prescribed();
        let mut r: Vec<f64> = prescribed
            .iter()
            .map(|&(n, c)| {
                let g = D * n + c as usize;
                -(load_factor * load[g] + initial_force[g])
            })
            .collect();
        let mut free_value = vec![0.0; dofs.free_count()];
        for (n, u) in displacements.iter().enumerate() {
            for (c, d) in dofs.free_dofs(n).into_iter().enumerate() {
                if let Some(i) = d {
                    free_value[i] = u[c];
                }
            }
        }
        for &(p, dof, k) in &self.entries {
            let u = match dof {
                Dof::Free(i) => free_value[i],
                Dof::Prescribed(q) => {
                    let (n, c) = prescribed[q];
                    displacements[n][c as usize]
                }
            };
            r[p] += k * u;
        }
        prescribed.iter().copied().zip(r).collect()
    }

    /// `rhs −= K_fp ū` for the prescribed values `ū`.
    pub(crate) fn subtract_into(&self, prescribed: &[f64], rhs: &mut [f64]) {
        for &(p, dof, k) in &self.entries {
            if let Dof::Free(i) = dof {
                rhs[i] -= k * prescribed[p];
            }
        }
    }
}

/// Scatters an element matrix into the reduced values and the prescribed couplings.
pub(crate) fn scatter<const D: usize>(
    pattern: &Pattern,
    dofs: &DofMap<D>,
    cell: &[usize],
    k_e: &DMatrix<f64>,
    values: &mut [f64],
    coupling: &mut Vec<(usize, Dof, f64)>,
) {
    let nd = D * cell.len();
    let dof = |a: usize| dofs.dofs(cell[a / D])[a % D];
    for a in 0..nd {
        match dof(a) {
            Dof::Free(i) => {
                for b in 0..nd {
                    if let Dof::Free(j) = dof(b)
                        && i >= j
                    {
                        values[pattern.position(i, j)] += k_e[(a, b)];
                    }
                }
            }
            Dof::Prescribed(p) => {
                for b in 0..nd {
                    coupling.push((p, dof(b), k_e[(a, b)]));
                }
            }
        }
    }
}

/// Sorts and merges the coupling triplets.
pub(crate) fn merge(mut entries: Vec<(usize, Dof, f64)>) -> PrescribedCoupling {
    let key = |d: &Dof| match *d {
        Dof::Free(i) => (0, i),
        Dof::Prescribed(p) => (1, p),
    };
    entries.sort_unstable_by_key(|e| (e.0, key(&e.1)));
    let mut merged: Vec<(usize, Dof, f64)> = Vec::with_capacity(entries.len() / 2);
    for e in entries {
        match merged.last_mut() {
            Some(last) if last.0 == e.0 && last.1 == e.1 => last.2 += e.2,
            _ => merged.push(e),
        }
    }
    PrescribedCoupling { entries: merged }
}

/// `y = A x` for the symmetric `A` whose lower triangle is stored by columns (`col_ptr`,
/// `row_idx`, `values`); `x` and `y` of the matrix's dimension (checked by the callers).
pub(crate) fn lower_symmetric_mul_into(
    col_ptr: &[usize],
    row_idx: &[usize],
    values: &[f64],
    x: &[f64],
    y: &mut [f64],
) {
    y.fill(0.0);
    for (j, &x_j) in x.iter().enumerate() {
        let mut y_j = 0.0;
        for k in col_ptr[j]..col_ptr[j + 1] {
            let (i, a) = (row_idx[k], values[k]);
            y[i] += a * x_j;
            if i != j {
                y_j += a * x[i];
            }
        }
        y[j] += y_j;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Component, Supports};
    use std::collections::BTreeSet;

    /// The pattern built from the node graph is the set of dof pairs `i ≥ j` that share an
    /// element, plus every free dof's diagonal, also where a tie gives two nodes one dof and
    /// where a support leaves a node fewer dofs (brute force over the elements' dof pairs).
    #[test]
    fn issue_38_pattern_from_the_node_graph_is_the_elements_dof_pairs() {
        let mut supports = Supports::new();
        supports.fix(&[0], Component::X);
        supports.tie(&[4, 6], Component::Z).unwrap();
        // node 7 is in no element: its dofs get only their diagonal
        let dofs = DofMap::<3>::numbered(8, &supports).unwrap();
        let elements: [&[usize]; 3] = [&[0, 1, 2, 3], &[1, 2, 3, 4], &[5, 6, 3, 2]];
        let pattern = Pattern::new(&dofs, elements.iter().copied()).unwrap();
        let mut expected = BTreeSet::new();
        for cell in elements {
            let free: Vec<usize> = cell
                .iter()
                .flat_map(|&node| dofs.free_dofs(node))
                .flatten()
                .collect();
            for &i in &free {
                for &j in &free {
                    if i >= j {
                        expected.insert((j, i));
                    }
                }
            }
        }
        expected.extend((0..dofs.free_count()).map(|j| (j, j)));
        let s = pattern.symbolic();
        let mut got = Vec::new();
        for j in 0..dofs.free_count() {
            let rows = s.row_idx_of_col_raw(j);
            assert!(rows.windows(2).all(|w| w[0] < w[1]), "column {j}: {rows:?}");
            got.extend(rows.iter().map(|&i| (j, i)));
        }
        assert_eq!(got, expected.into_iter().collect::<Vec<_>>());
        assert_eq!(pattern.nnz(), got.len());
    }
}
