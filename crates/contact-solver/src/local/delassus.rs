//! `W` as the algorithms see it, dense or sparse: the few operations they need, each matching
//! the storage once per row (or per contact) so that the inner loops stay zipped slices.
//!
//! ```text
//! dot_row(k, r)          = Σ_j W_kj r_j                       (x_k = q_k + dot_row(k, r))
//! axpy_row(k, a, x)      x += a W[k, :]                        (= a W[:, k], W symmetric)
//! axpy_rows2/3(k, c, x)  x += c₀ W[k, :] + c₁ W[k+1, :] (+ c₂ W[k+2, :]),  one contact's rows
//! mul_into(v, out)       out = W v, skipping v_j = 0
//! ```
//! Each is `O(m)` per row on a dense `W` and `O(stored entries of the row)` on a sparse one,
//! with the same arithmetic in the same order on the stored columns (see [`super::csr`]).
//!
//! The algorithms' column updates (`x += W[:, k] Δr_k`, `W v`) call the row operations on
//! `ReducedProblem::columns`: `W` itself when it is symmetric, the stored `Wᵀ` when a
//! non-symmetric `W` is kept ([`Asymmetry::Keep`](super::Asymmetry::Keep)), whose rows are the
//! columns of `W`; `x = W r + q` always reads the rows of `W`.

use super::csr::CsrMatrix;
use std::sync::Arc;

/// The storage of `W` inside a [`ReducedProblem`](super::ReducedProblem).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Delassus {
    /// Row-major `m × m`, shared: the `F*` a simulation keeps and the problems it solves (and
    /// their clones) hold one copy (issue 38).
    Dense { m: usize, w: Arc<Vec<f64>> },
    /// Block-pattern CSR ([`CsrMatrix`]).
    Sparse(CsrMatrix),
}

/// A read-only view of `W`, dense or sparse ([`ReducedProblem::w`](super::ReducedProblem::w)).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum WView<'a> {
    /// Dense row-major `m × m`.
    Dense(&'a [f64]),
    /// Compressed sparse rows.
    Sparse(&'a CsrMatrix),
}

impl Delassus {
    /// The public view.
    pub(crate) fn view(&self) -> WView<'_> {
        match self {
            Self::Dense { w, .. } => WView::Dense(w.as_slice()),
            Self::Sparse(a) => WView::Sparse(a),
        }
    }

    /// Bytes held by the storage of `W`.
    pub(crate) fn storage_bytes(&self) -> usize {
        match self {
            Self::Dense { w, .. } => w.len() * size_of::<f64>(),
            Self::Sparse(a) => a.storage_bytes(),
        }
    }

    /// `max |W_ij|`.
    pub(crate) fn max_abs(&self) -> f64 {
        match self {
            Self::Dense { w, .. } => w.iter().fold(0.0_f64, |a, x| a.max(x.abs())),
            Self::Sparse(a) => a.max_abs(),
        }
    }

    /// A copy of `W` multiplied by `s`.
    pub(crate) fn scaled(&self, s: f64) -> Self {
        match self {
            Self::Dense { m, w } => Self::Dense {
                m: *m,
                w: Arc::new(w.iter().map(|v| v * s).collect()),
            },
            Self::Sparse(a) => Self::Sparse(a.scaled(s)),
        }
    }

    /// `Wᵀ` in the same storage (the columns of a `W` kept non-symmetric, read as rows).
    pub(crate) fn transposed(&self) -> Self {
        match self {
            Self::Dense { m, w } => {
                let m = *m;
                let mut t = vec![0.0; w.len()];
                for i in 0..m {
                    for j in 0..m {
                        t[j * m + i] = w[i * m + j];
                    }
                }
                Self::Dense { m, w: Arc::new(t) }
            }
            Self::Sparse(a) => Self::Sparse(a.transposed()),
        }
    }

    /// The `d × d` diagonal block of contact `i`, top-left of a 3×3 array.
    #[inline]
    pub(crate) fn diagonal_block(&self, i: usize, d: usize) -> [[f64; 3]; 3] {
        match self {
            Self::Dense { m, w } => {
                let a = d * i;
                let mut b = [[0.0; 3]; 3];
                for (k, row) in b.iter_mut().enumerate().take(d) {
                    for (l, v) in row.iter_mut().enumerate().take(d) {
                        *v = w[(a + k) * m + a + l];
                    }
                }
                b
            }
            Self::Sparse(a) => a.diagonal_block(i, d),
        }
    }

    /// `Σ_j W_kj r_j`.
    #[inline]
    pub(crate) fn dot_row(&self, k: usize, r: &[f64]) -> f64 {
        match self {
            Self::Dense { m, w } => {
                let row = &w[k * m..(k + 1) * m];
                row.iter().zip(r).map(|(a, b)| a * b).sum::<f64>()
            }
            Self::Sparse(s) => {
                let (cols, vals) = s.row(k);
                cols.iter()
                    .zip(vals)
                    .map(|(&j, a)| a * r[j as usize])
                    .sum::<f64>()
            }
        }
    }

    /// `x += a W[k, :]`.
    #[inline]
    pub(crate) fn axpy_row(&self, k: usize, a: f64, x: &mut [f64]) {
        match self {
            Self::Dense { m, w } => {
                for (xj, b) in x.iter_mut().zip(&w[k * m..(k + 1) * m]) {
                    *xj += b * a;
                }
            }
            Self::Sparse(s) => {
                let (cols, vals) = s.row(k);
                for (&j, b) in cols.iter().zip(vals) {
                    x[j as usize] += b * a;
                }
            }
        }
    }

    /// `x += c₀ W[k, :] + c₁ W[k+1, :]` (rows of one contact).
    #[inline]
    pub(crate) fn axpy_rows2(&self, k: usize, c: [f64; 2], x: &mut [f64]) {
        match self {
            Self::Dense { m, w } => {
                let row_0 = &w[k * m..(k + 1) * m];
                let row_1 = &w[(k + 1) * m..(k + 2) * m];
                for ((xj, a), b) in x.iter_mut().zip(row_0).zip(row_1) {
                    *xj += a * c[0] + b * c[1];
                }
            }
            Self::Sparse(s) => {
                let (cols, [row_0, row_1, _]) = s.block_rows(k, 2);
                for ((&j, a), b) in cols.iter().zip(row_0).zip(row_1) {
                    x[j as usize] += a * c[0] + b * c[1];
                }
            }
        }
    }

    /// `x += c₀ W[k, :] + c₁ W[k+1, :] + c₂ W[k+2, :]` (rows of one 3D contact).
    #[inline]
    pub(crate) fn axpy_rows3(&self, k: usize, c: [f64; 3], x: &mut [f64]) {
        match self {
            Self::Dense { m, w } => {
                let row_0 = &w[k * m..(k + 1) * m];
                let row_1 = &w[(k + 1) * m..(k + 2) * m];
                let row_2 = &w[(k + 2) * m..(k + 3) * m];
                for (((xj, a), b), e) in x.iter_mut().zip(row_0).zip(row_1).zip(row_2) {
                    *xj += a * c[0] + b * c[1] + e * c[2];
                }
            }
            Self::Sparse(s) => {
                let (cols, [row_0, row_1, row_2]) = s.block_rows(k, 3);
                for (((&j, a), b), e) in cols.iter().zip(row_0).zip(row_1).zip(row_2) {
                    x[j as usize] += a * c[0] + b * c[1] + e * c[2];
                }
            }
        }
    }

    /// `out = Σ_j v_j (row j)`: `W v` when the rows are the columns of `W` (`W` symmetric, or
    /// the kept `Wᵀ`), skipping the zero entries of `v`.
    pub(crate) fn mul_into(&self, v: &[f64], out: &mut [f64]) {
        out.iter_mut().for_each(|a| *a = 0.0);
        for (j, &vj) in v.iter().enumerate() {
            if vj != 0.0 {
                self.axpy_row(j, vj, out);
            }
        }
    }
}
