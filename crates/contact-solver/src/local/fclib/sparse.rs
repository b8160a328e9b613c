//! FCLIB's sparse matrix (the CSparse `cs` struct, stored as datasets of one group): decoding
//! to a dense row-major array with every index checked, and encoding a dense array.
//!
//! ```text
//! nz = -1   compressed columns: p[n+1] column pointers, i[nzmax] row indices, x[nzmax]
//! nz = -2   compressed rows:    p[m+1] row pointers,    i[nzmax] column indices, x[nzmax]
//! nz >= 0   triplets (CSparse): i[nz] row indices,      p[nz] column indices,    x[nz..]
//! ```
//! Duplicates are summed (CSparse's `cs_compress`); `fclib.h` (FCLIB 3.0) and Siconos'
//! `fclib_interface.c` read and write the layout above.

use crate::local::csr::CsrMatrix;

/// Which of FCLIB's three sparse forms, as its `nz` dataset says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SparseForm {
    /// `nz = -1`: compressed columns.
    CompressedColumn,
    /// `nz = -2`: compressed rows.
    CompressedRow,
    /// `nz ≥ 0`: triplets (`i` rows, `p` columns, as CSparse).
    Triplet,
}

impl SparseForm {
    /// The form FCLIB's `nz` dataset names, or `None` for a value below `-2`.
    pub(super) fn from_nz(nz: i64) -> Option<Self> {
        match nz {
            -1 => Some(Self::CompressedColumn),
            -2 => Some(Self::CompressedRow),
            0.. => Some(Self::Triplet),
            _ => None,
        }
    }
}

/// A sparse matrix as read from (or written to) an FCLIB group, before any check.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct RawSparse {
    /// Rows.
    pub m: usize,
    /// Columns.
    pub n: usize,
    /// The form.
    pub form: SparseForm,
    /// Pointers (compressed) or column indices (triplets).
    pub p: Vec<i64>,
    /// Row (CSC, triplets) or column (CSR) indices.
    pub i: Vec<i64>,
    /// Values.
    pub x: Vec<f64>,
}

/// At most this many entries of a dense matrix are allocated when a file is decoded
/// (`2^30`, 8 GiB of `f64`: `m ≤ 32768` for a square `W`).
///
/// Public because it is a limit on the user's input: a file beyond it is refused with an
/// error, and a user converting a larger problem must know the bound.
pub const MAX_DENSE_ENTRIES: usize = 1 << 30;

/// A zeroed `rows × cols` buffer, refused (not aborted) when too large.
pub(super) fn zeroed(rows: usize, cols: usize, name: &str) -> Result<Vec<f64>, String> {
    let len = rows
        .checked_mul(cols)
        .filter(|&len| len <= MAX_DENSE_ENTRIES)
        .ok_or_else(|| {
            format!(
                "`{name}` is {rows} x {cols}: more than 2^30 entries once dense (the reduced \
                 problem is dense)"
            )
        })?;
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| format!("`{name}` is {rows} x {cols}: cannot allocate it dense"))?;
    v.resize(len, 0.0);
    Ok(v)
}

impl RawSparse {
    /// The entries `(row, col, value)`, every index and pointer checked (`name` is the group's
    /// path in the file, for the messages).
    pub fn entries(&self, name: &str) -> Result<Vec<(usize, usize, f64)>, String> {
        if let Some(k) = self.x.iter().position(|v| !v.is_finite()) {
            return Err(format!("`{name}/x[{k}]` = {} is not finite", self.x[k]));
        }
        match self.form {
            SparseForm::Triplet => self.triplet_entries(name),
            SparseForm::CompressedColumn => self.compressed_entries(name, self.n, self.m, true),
            SparseForm::CompressedRow => self.compressed_entries(name, self.m, self.n, false),
        }
    }

    /// The dense row-major array of the matrix (duplicates summed). A single entry is copied,
    /// not added to `+0.0`, so that a stored `-0.0` comes back bit for bit.
    pub fn to_dense(&self, name: &str) -> Result<Vec<f64>, String> {
        let mut entries = self.entries(name)?;
        let mut a = zeroed(self.m, self.n, name)?;
        entries.sort_by_key(|&(r, c, _)| (r, c));
        for group in entries.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
            let (r, c, first) = group[0];
            a[r * self.n + c] = group[1..].iter().fold(first, |s, e| s + e.2);
        }
        Ok(a)
    }

    fn triplet_entries(&self, name: &str) -> Result<Vec<(usize, usize, f64)>, String> {
        let nz = self.i.len();
        if self.p.len() != nz || self.x.len() < nz {
            return Err(format!(
                "`{name}` holds {nz} triplets (`nz`) but `p` has {} and `x` {} entries",
                self.p.len(),
                self.x.len()
            ));
        }
        let mut out = Vec::with_capacity(nz);
        for k in 0..nz {
            let r = index(self.i[k], self.m, || format!("`{name}/i[{k}]`"), "rows")?;
            let c = index(self.p[k], self.n, || format!("`{name}/p[{k}]`"), "columns")?;
            out.push((r, c, self.x[k]));
        }
        Ok(out)
    }

    /// Compressed columns (`by_column`) or rows: `outer` pointers over `inner` indices.
    fn compressed_entries(
        &self,
        name: &str,
        outer: usize,
        inner: usize,
        by_column: bool,
    ) -> Result<Vec<(usize, usize, f64)>, String> {
        let (outer_name, inner_name) = if by_column {
            ("columns", "rows")
        } else {
            ("rows", "columns")
        };
        if self.p.len() != outer + 1 {
            return Err(format!(
                "`{name}/p` has {} entries, expected {} ({outer} {outer_name} + 1)",
                self.p.len(),
                outer + 1
            ));
        }
        if self.p[0] != 0 {
            return Err(format!("`{name}/p[0]` = {} must be 0", self.p[0]));
        }
        for k in 0..outer {
            if self.p[k + 1] < self.p[k] {
                return Err(format!(
                    "`{name}/p` decreases: p[{}] = {} < p[{k}] = {}",
                    k + 1,
                    self.p[k + 1],
                    self.p[k]
                ));
            }
        }
        let nnz = self.p[outer];
        if nnz > self.i.len().min(self.x.len()) as i64 {
            return Err(format!(
                "`{name}/p[{outer}]` = {nnz} entries, but `i` has {} and `x` {}",
                self.i.len(),
                self.x.len()
            ));
        }
        let mut out = Vec::with_capacity(nnz as usize);
        for a in 0..outer {
            for k in self.p[a] as usize..self.p[a + 1] as usize {
                let b = index(self.i[k], inner, || format!("`{name}/i[{k}]`"), inner_name)?;
                out.push(if by_column {
                    (b, a, self.x[k])
                } else {
                    (a, b, self.x[k])
                });
            }
        }
        Ok(out)
    }

    /// `a` (dense row-major `m × n`) in `form`, keeping every entry whose bits are not those
    /// of `+0.0` (so `-0.0` survives a round trip).
    pub fn from_dense(a: &[f64], m: usize, n: usize, form: SparseForm) -> Self {
        let kept = |v: f64| v.to_bits() != 0;
        let (mut p, mut i, mut x) = (Vec::new(), Vec::new(), Vec::new());
        let (outer, inner) = match form {
            SparseForm::CompressedColumn => (n, m),
            _ => (m, n),
        };
        if form != SparseForm::Triplet {
            p.push(0);
        }
        for a_ in 0..outer {
            for b in 0..inner {
                let (r, c) = match form {
                    SparseForm::CompressedColumn => (b, a_),
                    _ => (a_, b),
                };
                let v = a[r * n + c];
                if !kept(v) {
                    continue;
                }
                match form {
                    SparseForm::Triplet => {
                        i.push(r as i64);
                        p.push(c as i64);
                    }
                    SparseForm::CompressedColumn => i.push(r as i64),
                    SparseForm::CompressedRow => i.push(c as i64),
                }
                x.push(v);
            }
            if form != SparseForm::Triplet {
                p.push(x.len() as i64);
            }
        }
        Self {
            m,
            n,
            form,
            p,
            i,
            x,
        }
    }

    /// `a` (sparse, `m × m`) in `form`, keeping every stored entry whose bits are not those of
    /// `+0.0` (the entries [`from_dense`](Self::from_dense) keeps of the same `W`), without
    /// forming a dense matrix.
    pub fn from_csr(a: &CsrMatrix, form: SparseForm) -> Self {
        let m = a.size();
        let kept = |v: f64| v.to_bits() != 0;
        let (mut p, mut i, mut x) = (Vec::new(), Vec::new(), Vec::new());
        match form {
            SparseForm::Triplet | SparseForm::CompressedRow => {
                if form == SparseForm::CompressedRow {
                    p.push(0);
                }
                for k in 0..m {
                    let (cols, vals) = a.row(k);
                    for (&c, &v) in cols.iter().zip(vals).filter(|(_, v)| kept(**v)) {
                        if form == SparseForm::Triplet {
                            i.push(k as i64);
                            p.push(i64::from(c));
                        } else {
                            i.push(i64::from(c));
                        }
                        x.push(v);
                    }
                    if form == SparseForm::CompressedRow {
                        p.push(x.len() as i64);
                    }
                }
            }
            SparseForm::CompressedColumn => {
                // the transpose's rows, by a counting sort on the columns
                let mut count = vec![0usize; m + 1];
                for (_, c, v) in a.triplets() {
                    if kept(v) {
                        count[c + 1] += 1;
                    }
                }
                for c in 0..m {
                    count[c + 1] += count[c];
                }
                p = count.iter().map(|&c| c as i64).collect();
                let mut next = count;
                i = vec![0; next[m]];
                x = vec![0.0; next[m]];
                for (r, c, v) in a.triplets().filter(|t| kept(t.2)) {
                    i[next[c]] = r as i64;
                    x[next[c]] = v;
                    next[c] += 1;
                }
            }
        }
        Self {
            m,
            n: m,
            form,
            p,
            i,
            x,
        }
    }

    /// FCLIB's `nz`: `-1`, `-2` or the triplet count.
    pub fn nz(&self) -> i64 {
        match self.form {
            SparseForm::CompressedColumn => -1,
            SparseForm::CompressedRow => -2,
            SparseForm::Triplet => self.x.len() as i64,
        }
    }
}

/// `v` as an index below `len`, or the message naming `what` and the `bound` it exceeds.
fn index(v: i64, len: usize, what: impl Fn() -> String, bound: &str) -> Result<usize, String> {
    usize::try_from(v).ok().filter(|&u| u < len).ok_or_else(|| {
        format!(
            "{} = {v} is out of range: the matrix has {len} {bound}",
            what()
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[rustfmt::skip]
    const A: [f64; 6] = [
        1.0, 0.0, 2.0,
        0.0, -0.0, 3.0,
    ];

    #[test]
    fn from_csr_writes_what_from_dense_writes() {
        // 2D, two contacts, coupled; one explicit zero (1, 3) inside a stored block
        let rows = [0, 0, 1, 1, 2, 3, 2, 0];
        let cols = [0, 1, 0, 1, 2, 3, 0, 2];
        let vals = [2.0, 0.5, 0.5, 1.0, 3.0, 1.5, 0.25, 0.25];
        let a = CsrMatrix::from_triplets(2, 4, &rows, &cols, &vals).unwrap();
        let mut dense = vec![0.0; 16];
        for (r, c, v) in a.triplets() {
            dense[r * 4 + c] = v;
        }
        for form in [
            SparseForm::CompressedColumn,
            SparseForm::CompressedRow,
            SparseForm::Triplet,
        ] {
            assert_eq!(
                RawSparse::from_csr(&a, form),
                RawSparse::from_dense(&dense, 4, 4, form),
                "{form:?}"
            );
        }
    }

    #[test]
    fn from_dense_and_back_works_in_every_form() {
        for form in [
            SparseForm::CompressedColumn,
            SparseForm::CompressedRow,
            SparseForm::Triplet,
        ] {
            let s = RawSparse::from_dense(&A, 2, 3, form);
            assert_eq!(s.x.len(), 4, "{form:?}: -0.0 is kept, +0.0 is not");
            let back = s.to_dense("W").unwrap();
            assert!(
                back.iter().zip(&A).all(|(a, b)| a.to_bits() == b.to_bits()),
                "{form:?}"
            );
        }
        let csr = RawSparse::from_dense(&A, 2, 3, SparseForm::CompressedRow);
        assert_eq!(
            (&csr.p[..], &csr.i[..], csr.nz()),
            (&[0, 2, 4][..], &[0, 2, 1, 2][..], -2)
        );
    }

    #[test]
    fn entries_rejects_bad_indices_and_pointers() {
        let mut s = RawSparse::from_dense(&A, 2, 3, SparseForm::CompressedColumn);
        s.i[1] = 2;
        assert_eq!(
            s.entries("g/W").unwrap_err(),
            "`g/W/i[1]` = 2 is out of range: the matrix has 2 rows"
        );
        let mut s = RawSparse::from_dense(&A, 2, 3, SparseForm::CompressedRow);
        s.p[1] = 5;
        assert_eq!(
            s.entries("W").unwrap_err(),
            "`W/p` decreases: p[2] = 4 < p[1] = 5"
        );
        let mut s = RawSparse::from_dense(&A, 2, 3, SparseForm::Triplet);
        s.p[0] = -1;
        assert_eq!(
            s.entries("W").unwrap_err(),
            "`W/p[0]` = -1 is out of range: the matrix has 3 columns"
        );
    }
}
