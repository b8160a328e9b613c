//! The sparse storage of `W`: compressed sparse rows (CSR) on a *block* pattern.
//!
//! ```text
//! row k:  columns col[row_ptr[k] .. row_ptr[k+1]]  (ascending),  values val[same range]
//! pattern: every d × d block (I, J) that holds an entry, and its transpose (J, I), and every
//!          diagonal block (I, I), stored whole (explicit zeros inside a touched block)
//! ```
//! Multibody Delassus operators `W = H M⁻¹ Hᵀ` couple contacts through bodies: their
//! non-zeros come in whole `d × d` blocks, a few per block row (Jean 1999; Acary, Brogliato
//! 2008, §13.4). Storing the block pattern (and its transpose) costs nothing on such matrices
//! and gives two properties the solvers use:
//! - the pattern is symmetric, so symmetrising round-off asymmetry is done in place;
//! - the `d` rows of a contact share one column list, so the Gauss–Seidel update
//!   `x += W[:, i] Δr_i` is one zipped pass over the contact's `d` rows, the same arithmetic
//!   as the dense loop on the stored columns: a sparse and a dense problem with the same `W`
//!   give the same bits.
//!
//! Column indices are `u32` (`m < 2³²`): 12 bytes per stored entry, plus `8 (m + 1)` for the
//! row pointers.

use crate::error::SolverError;

/// A square `m × m` matrix in compressed sparse rows on a *block* pattern: every `d × d` block
/// `(I, J)` that holds an entry, its transpose `(J, I)` and every diagonal block are stored
/// whole (explicit zeros inside a touched block); column indices (`u32`) ascending in each
/// row; the full symmetric pattern stored.
///
/// Why blocks: Delassus operators `H M⁻¹ Hᵀ` couple contacts by whole `d × d` blocks, so it
/// costs nothing on them, and it makes the pattern symmetric (round-off asymmetry is
/// symmetrised in place) and gives the `d` rows of a contact one shared column list, so the
/// Gauss–Seidel update `x += W[:, i] Δr_i` is one zipped pass with the dense loop's arithmetic:
/// sparse and dense storage of the same `W` give the same bits. Memory: 12 bytes per stored
/// entry plus `8 (m + 1)`.
///
/// Built by [`ReducedProblem::from_triplets`](crate::ReducedProblem::from_triplets); read
/// through [`ReducedProblem::w_sparse`](crate::ReducedProblem::w_sparse).
///
/// # Examples
/// ```
/// use contact_solver::ReducedProblem;
/// // two 2D contacts, W = 2 I with a coupling 0.5 between the normals
/// let p = ReducedProblem::from_triplets(
///     2,
///     &[0, 1, 2, 3, 0, 2],
///     &[0, 1, 2, 3, 2, 0],
///     &[2.0, 2.0, 2.0, 2.0, 0.5, 0.5],
///     vec![-1.0, 0.0, -1.0, 0.0],
///     vec![0.3, 0.3],
/// )?;
/// let w = p.w_sparse().expect("sparse");
/// assert_eq!((w.size(), w.stored()), (4, 16)); // 4 blocks of 2×2, stored whole
/// assert_eq!((w.get(0, 2), w.get(1, 3)), (0.5, 0.0));
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CsrMatrix {
    m: usize,
    row_ptr: Vec<usize>,
    col: Vec<u32>,
    val: Vec<f64>,
}

impl CsrMatrix {
    /// Builds the block pattern of `(rows, cols)` (block size `dim`) and sums `vals` into it
    /// (duplicates summed, in the order given).
    ///
    /// # Errors
    /// [`SolverError::SizeMismatch`] if `cols` or `vals` is not as long as `rows`, or if
    /// `m ≥ 2³²`; [`SolverError::IndexOutOfRange`] for an index `≥ m`;
    /// [`SolverError::NonFinite`] for a value that is not finite (each naming the triplet).
    pub(crate) fn from_triplets(
        dim: usize,
        m: usize,
        rows: &[usize],
        cols: &[usize],
        vals: &[f64],
    ) -> Result<Self, SolverError> {
        let n = rows.len();
        for (what, len) in [("cols", cols.len()), ("vals", vals.len())] {
            if len != n {
                return Err(SolverError::SizeMismatch {
                    what,
                    expected: n,
                    found: len,
                });
            }
        }
        if m > u32::MAX as usize {
            return Err(SolverError::SizeMismatch {
                what: "W",
                expected: u32::MAX as usize,
                found: m,
            });
        }
        for (what, idx) in [("rows", rows), ("cols", cols)] {
            if let Some((index, &value)) = idx.iter().enumerate().find(|(_, v)| **v >= m) {
                return Err(SolverError::IndexOutOfRange {
                    what,
                    index,
                    value,
                    bound: m,
                });
            }
        }
        if let Some((index, &value)) = vals.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(SolverError::NonFinite {
                what: "vals",
                index,
                value,
            });
        }
        // block pattern: (I, J), (J, I) of every triplet and every (I, I)
        let nb = m / dim;
        let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(2 * n + nb);
        for (&r, &c) in rows.iter().zip(cols) {
            let (bi, bj) = ((r / dim) as u32, (c / dim) as u32);
            pairs.push((bi, bj));
            pairs.push((bj, bi));
        }
        pairs.extend((0..nb as u32).map(|b| (b, b)));
        pairs.sort_unstable();
        pairs.dedup();
        let mut block_ptr = vec![0usize; nb + 1];
        for &(bi, _) in &pairs {
            block_ptr[bi as usize + 1] += 1;
        }
        for b in 0..nb {
            block_ptr[b + 1] += block_ptr[b];
        }
        let stored = pairs.len() * dim * dim;
        let mut row_ptr = Vec::with_capacity(m + 1);
        let mut col = Vec::with_capacity(stored);
        row_ptr.push(0);
        for k in 0..m {
            let b = k / dim;
            for &(_, bj) in &pairs[block_ptr[b]..block_ptr[b + 1]] {
                let first = bj * dim as u32;
                col.extend(first..first + dim as u32);
            }
            row_ptr.push(col.len());
        }
        let mut a = Self {
            m,
            row_ptr,
            col,
            val: vec![0.0; stored],
        };
        for ((&r, &c), &v) in rows.iter().zip(cols).zip(vals) {
            let p = a
                .position(r, c)
                .unwrap_or_else(|| unreachable!("({r}, {c}) is in the block pattern"));
            a.val[p] += v;
        }
        Ok(a)
    }

    /// The block-sparse copy of a dense row-major `m × m` matrix `w` (block size `dim`):
    /// every block `(I, J)` with a non-zero entry in it or in `(J, I)`, and every diagonal
    /// block, with `w`'s values — what [`from_triplets`](Self::from_triplets) builds from
    /// `w`'s non-zero entries, without sorting them (issue 37: `Auto`'s sparse copy of a
    /// multibody `W` stored dense, 0.65 ms from triplets on 60 contacts against the whole
    /// sweep's 1 ms).
    ///
    /// # Panics
    /// If `w.len() != m * m`, `dim` does not divide `m`, or `m ≥ 2³²` (the caller's
    /// invariants: a validated dense `W`).
    #[track_caller]
    pub(crate) fn from_dense(dim: usize, m: usize, w: &[f64]) -> Self {
        assert!(w.len() == m * m && dim > 0 && m.is_multiple_of(dim) && m <= u32::MAX as usize);
        let nb = m / dim;
        let block_zero = |bi: usize, bj: usize| {
            (0..dim).all(|a| {
                w[(dim * bi + a) * m + dim * bj..][..dim]
                    .iter()
                    .all(|&v| v == 0.0)
            })
        };
        // the block columns of each block row, increasing
        let mut blocks: Vec<Vec<u32>> = vec![Vec::new(); nb];
        for (bi, row) in blocks.iter_mut().enumerate() {
            for bj in 0..nb {
                if bi == bj || !block_zero(bi, bj) || !block_zero(bj, bi) {
                    row.push(bj as u32);
                }
            }
        }
        let stored: usize = blocks.iter().map(|b| b.len()).sum::<usize>() * dim * dim;
        let (mut row_ptr, mut col, mut val) = (
            Vec::with_capacity(m + 1),
            Vec::with_capacity(stored),
            Vec::with_capacity(stored),
        );
        row_ptr.push(0);
        for k in 0..m {
            for &bj in &blocks[k / dim] {
                let first = bj as usize * dim;
                col.extend(first as u32..(first + dim) as u32);
                val.extend_from_slice(&w[k * m + first..][..dim]);
            }
            row_ptr.push(col.len());
        }
        Self {
            m,
            row_ptr,
            col,
            val,
        }
    }

    /// The principal sub-matrix on the blocks `keep` (block size `dim`; increasing, distinct),
    /// renumbered in that order: the block pattern and the order of the stored columns stay.
    pub(crate) fn restricted(&self, dim: usize, keep: &[usize]) -> Self {
        let mut new_block = vec![u32::MAX; self.m / dim];
        for (k, &b) in keep.iter().enumerate() {
            new_block[b] = k as u32;
        }
        let m = dim * keep.len();
        let (mut row_ptr, mut col, mut val) = (Vec::with_capacity(m + 1), Vec::new(), Vec::new());
        row_ptr.push(0);
        let d = dim as u32;
        for &b in keep {
            for k in 0..dim {
                let (cols, vals) = self.row(dim * b + k);
                for (&c, &v) in cols.iter().zip(vals) {
                    let nb = new_block[(c / d) as usize];
                    if nb != u32::MAX {
                        col.push(nb * d + c % d);
                        val.push(v);
                    }
                }
                row_ptr.push(col.len());
            }
        }
        Self {
            m,
            row_ptr,
            col,
            val,
        }
    }

    /// The size `m` (the matrix is `m × m`).
    #[inline]
    pub fn size(&self) -> usize {
        self.m
    }

    /// Number of stored entries (explicit zeros inside a stored block included).
    #[inline]
    pub fn stored(&self) -> usize {
        self.val.len()
    }

    /// Bytes held by the three arrays: `12 · stored + 8 (m + 1)`.
    pub fn storage_bytes(&self) -> usize {
        self.val.len() * size_of::<f64>()
            + self.col.len() * size_of::<u32>()
            + self.row_ptr.len() * size_of::<usize>()
    }

    /// The row pointers (`m + 1` entries): row `k` is `row_ptr[k]..row_ptr[k + 1]`.
    #[inline]
    pub fn row_pointers(&self) -> &[usize] {
        &self.row_ptr
    }

    /// The column indices of the stored entries, ascending within a row.
    #[inline]
    pub fn column_indices(&self) -> &[u32] {
        &self.col
    }

    /// The stored values.
    #[inline]
    pub fn values(&self) -> &[f64] {
        &self.val
    }

    /// Row `k`: its column indices and values.
    ///
    /// # Panics
    /// If `k >= size()`.
    #[inline]
    #[track_caller]
    pub fn row(&self, k: usize) -> (&[u32], &[f64]) {
        let range = self.row_ptr[k]..self.row_ptr[k + 1];
        (&self.col[range.clone()], &self.val[range])
    }

    /// The entry `W_ij` (0 outside the pattern).
    ///
    /// # Panics
    /// If `i >= size()`.
    #[track_caller]
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.position(i, j).map_or(0.0, |p| self.val[p])
    }

    /// The index in `values()` of `W_ij`, if stored.
    #[inline]
    pub(crate) fn position(&self, i: usize, j: usize) -> Option<usize> {
        let (cols, _) = self.row(i);
        let j = u32::try_from(j).ok()?;
        cols.binary_search(&j).ok().map(|p| self.row_ptr[i] + p)
    }

    /// `max |W_ij|`.
    pub(crate) fn max_abs(&self) -> f64 {
        self.val.iter().fold(0.0_f64, |a, x| a.max(x.abs()))
    }

    /// The worst relative asymmetry `max |W_ij/s − W_ji/s|` over the pattern and where
    /// (`(worst, i, j, |W_ij − W_ji|)`), with `s = w_max`.
    pub(crate) fn worst_asymmetry(&self, w_max: f64) -> (f64, usize, usize, f64) {
        let (mut worst, mut row, mut col, mut diff) = (0.0_f64, 0, 0, 0.0);
        for i in 0..self.m {
            for p in self.row_ptr[i]..self.row_ptr[i + 1] {
                let j = self.col[p] as usize;
                if j <= i {
                    continue;
                }
                let a = self.val[p];
                let b = self.get(j, i);
                let difference = (a / w_max - b / w_max).abs();
                if difference > worst {
                    (worst, row, col, diff) = (difference, i, j, (a - b).abs());
                }
            }
        }
        (worst, row, col, diff)
    }

    /// `Wᵀ` on the same pattern (the pattern is symmetric, so only the values move).
    pub(crate) fn transposed(&self) -> Self {
        let mut t = self.clone();
        for i in 0..self.m {
            for p in self.row_ptr[i]..self.row_ptr[i + 1] {
                let j = self.col[p] as usize;
                let q = self
                    .position(j, i)
                    .unwrap_or_else(|| unreachable!("the pattern is symmetric"));
                t.val[q] = self.val[p];
            }
        }
        t
    }

    /// Replaces `W` by `(W + Wᵀ)/2`, in place (the pattern is symmetric).
    pub(crate) fn symmetrize(&mut self) {
        for i in 0..self.m {
            for p in self.row_ptr[i]..self.row_ptr[i + 1] {
                let j = self.col[p] as usize;
                if j <= i {
                    continue;
                }
                let q = self
                    .position(j, i)
                    .unwrap_or_else(|| unreachable!("the pattern is symmetric"));
                // halves first: the same bits as the dense `symmetrize`
                let a = 0.5 * self.val[q] + 0.5 * self.val[p];
                self.val[p] = a;
                self.val[q] = a;
            }
        }
    }

    /// The `d × d` diagonal block of contact `i` (normal first), top-left of a 3×3 array.
    ///
    /// # Panics
    /// If `i >= m/d`.
    #[track_caller]
    pub(crate) fn diagonal_block(&self, i: usize, d: usize) -> [[f64; 3]; 3] {
        let a = d * i;
        let first = self
            .position(a, a)
            .unwrap_or_else(|| unreachable!("diagonal blocks are in the pattern"));
        let offset = first - self.row_ptr[a];
        let mut b = [[0.0; 3]; 3];
        for (k, row) in b.iter_mut().enumerate().take(d) {
            let start = self.row_ptr[a + k] + offset;
            row[..d].copy_from_slice(&self.val[start..start + d]);
        }
        b
    }

    /// A copy with every value multiplied by `s`.
    pub(crate) fn scaled(&self, s: f64) -> Self {
        Self {
            m: self.m,
            row_ptr: self.row_ptr.clone(),
            col: self.col.clone(),
            val: self.val.iter().map(|v| v * s).collect(),
        }
    }

    /// The stored entries `(i, j, W_ij)`, row by row, columns ascending.
    pub fn triplets(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        (0..self.m).flat_map(move |i| {
            let (cols, vals) = self.row(i);
            cols.iter()
                .zip(vals)
                .map(move |(&j, &v)| (i, j as usize, v))
        })
    }

    /// The rows `k..k + n` (`n` ≤ 3, one contact's rows): the shared column list and the `n`
    /// value slices.
    #[inline]
    pub(crate) fn block_rows(&self, k: usize, n: usize) -> (&[u32], [&[f64]; 3]) {
        let (lo, hi) = (self.row_ptr[k], self.row_ptr[k + 1]);
        let len = hi - lo;
        let at = |r: usize| {
            let s = self.row_ptr[k + r];
            &self.val[s..s + len]
        };
        let empty: &[f64] = &[];
        (
            &self.col[lo..hi],
            [
                at(0),
                if n > 1 { at(1) } else { empty },
                if n > 2 { at(2) } else { empty },
            ],
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_triplets_works() {
        // 3D, two contacts, one coupling entry (0, 4): blocks (0,0), (0,1), (1,0), (1,1)
        let a = CsrMatrix::from_triplets(3, 6, &[0, 0, 0, 4], &[0, 0, 4, 4], &[1.0, 2.0, 0.5, 7.0])
            .unwrap();
        assert_eq!(a.stored(), 36);
        assert_eq!(
            (a.get(0, 0), a.get(0, 4), a.get(4, 0), a.get(4, 4)),
            (3.0, 0.5, 0.0, 7.0)
        );
        let (cols, rows) = a.block_rows(3, 3);
        assert_eq!(cols, &[0, 1, 2, 3, 4, 5]);
        assert_eq!(rows[1][4], 7.0);
        assert_eq!(a.diagonal_block(1, 3)[1][1], 7.0);
        // the pattern is symmetric, so symmetrising is in place
        let mut b = a.clone();
        b.symmetrize();
        assert_eq!((b.get(0, 4), b.get(4, 0)), (0.25, 0.25));
        let (worst, i, j, diff) = a.worst_asymmetry(a.max_abs());
        assert_eq!((i, j, diff), (0, 4, 0.5));
        assert!((worst - 0.5 / 7.0).abs() < 1e-15);
        // a block-diagonal pattern: one block per contact
        let c = CsrMatrix::from_triplets(2, 4, &[0, 3], &[0, 3], &[1.0, 1.0]).unwrap();
        assert_eq!(c.stored(), 8);
        assert_eq!(c.get(0, 2), 0.0);
        assert_eq!(c.storage_bytes(), 8 * 12 + 5 * 8);
    }

    #[test]
    fn from_triplets_rejects_bad_triplets() {
        let e = CsrMatrix::from_triplets(2, 4, &[0, 5], &[0, 1], &[1.0, 1.0]);
        assert_eq!(
            e,
            Err(SolverError::IndexOutOfRange {
                what: "rows",
                index: 1,
                value: 5,
                bound: 4
            })
        );
        let e = CsrMatrix::from_triplets(2, 4, &[0], &[0, 1], &[1.0]);
        assert!(matches!(
            e,
            Err(SolverError::SizeMismatch { what: "cols", .. })
        ));
        let e = CsrMatrix::from_triplets(2, 4, &[0, 1], &[0, 1], &[1.0, f64::NAN]);
        assert!(matches!(
            e,
            Err(SolverError::NonFinite {
                what: "vals",
                index: 1,
                ..
            })
        ));
    }
}
