//! Siconos' `NumericsMatrix` in its text form (`NM_write_in_file`): a storage type, the sizes,
//! then the values.
//!
//! ```text
//! 0 (dense)          size0 size1, again "size0 size1", then size0·size1 values column by
//!                    column (Siconos stores column-major; each printed line is a column)
//! 1 (sparse blocks)  size0 size1, nbblocks, blocknumber0, blocknumber1,
//!                    blocksize0[blocknumber0], blocksize1[blocknumber1] (cumulative),
//!                    filled1 = blocknumber0 + 1, filled2 = nbblocks,
//!                    index1[filled1] (block-row pointers), index2[filled2] (block columns),
//!                    then for each block k: the line "k" and its values column by column
//! 2 (CSparse)        printed by cs_print with six digits: refused
//! ```

use super::tokens::{Tokens, error};
use crate::error::SolverError;
use crate::local::CsrMatrix;
use std::fmt::Write as _;

/// A matrix read from a `.dat` file.
pub(super) struct DatMatrix {
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// The values.
    pub values: Values,
}

/// The values of a [`DatMatrix`].
pub(super) enum Values {
    /// Row-major `rows × cols`.
    Dense(Vec<f64>),
    /// `(row, col, value)`, each position once (sparse-block storage).
    Triplets(Vec<(usize, usize, f64)>),
}

impl DatMatrix {
    /// The entries as triplets (the dense zeros left out).
    pub(super) fn entries(&self) -> Vec<(usize, usize, f64)> {
        match &self.values {
            Values::Triplets(t) => t.clone(),
            Values::Dense(a) => a
                .iter()
                .enumerate()
                .filter(|(_, v)| **v != 0.0)
                .map(|(k, &v)| (k / self.cols, k % self.cols, v))
                .collect(),
        }
    }
}

/// Reads a `NumericsMatrix` named `name` (`W`, `M`, `H`) at the cursor.
pub(super) fn read_matrix(t: &mut Tokens<'_>, name: &str) -> Result<DatMatrix, SolverError> {
    let line = t.line();
    let storage = t.count(&format!("the storage type of `{name}`"), 9)?;
    let left = t.remaining();
    let rows = t.count(&format!("the rows of `{name}`"), left)?;
    let cols = t.count(&format!("the columns of `{name}`"), left)?;
    match storage {
        0 => read_dense(t, name, rows, cols),
        1 => read_blocks(t, name, rows, cols),
        2 => Err(error(
            line,
            format!(
                "`{name}` has storage type 2 (CSparse, which Siconos prints with six digits): \
                 not supported; write it dense (0) or in sparse blocks (1)"
            ),
        )),
        s => Err(error(
            line,
            format!("`{name}` has storage type {s}: expected 0 (dense) or 1 (sparse blocks)"),
        )),
    }
}

fn read_dense(
    t: &mut Tokens<'_>,
    name: &str,
    rows: usize,
    cols: usize,
) -> Result<DatMatrix, SolverError> {
    let line = t.line();
    let left = t.remaining();
    let (r2, c2) = (
        t.count(&format!("the rows of `{name}` (repeated)"), left)?,
        t.count(&format!("the columns of `{name}` (repeated)"), left)?,
    );
    if (r2, c2) != (rows, cols) {
        return Err(error(
            line,
            format!("`{name}` is {rows} x {cols} but its dense header says {r2} x {c2}"),
        ));
    }
    let n = rows
        .checked_mul(cols)
        .ok_or_else(|| error(line, format!("`{name}` is {rows} x {cols}: too large")))?;
    let col_major = t.reals(&format!("`{name}`"), n)?;
    let mut a = vec![0.0; n];
    for (k, v) in col_major.into_iter().enumerate() {
        let (i, j) = (k % rows, k / rows);
        a[i * cols + j] = v;
    }
    Ok(DatMatrix {
        rows,
        cols,
        values: Values::Dense(a),
    })
}

/// Cumulative block sizes, strictly increasing and ending at `total`.
fn block_sizes(
    t: &mut Tokens<'_>,
    what: &str,
    count: usize,
    total: usize,
) -> Result<Vec<usize>, SolverError> {
    let line = t.line();
    let mut out = Vec::with_capacity(count.min(t.remaining()));
    let mut prev = 0;
    for k in 0..count {
        let v = t.count(&format!("{what}[{k}]"), total)?;
        if v <= prev {
            return Err(error(
                line,
                format!("{what}[{k}] = {v}: the cumulative block sizes must increase"),
            ));
        }
        prev = v;
        out.push(v);
    }
    if prev != total {
        return Err(error(
            line,
            format!("{what} ends at {prev}, not at the matrix size {total}"),
        ));
    }
    Ok(out)
}

fn read_blocks(
    t: &mut Tokens<'_>,
    name: &str,
    rows: usize,
    cols: usize,
) -> Result<DatMatrix, SolverError> {
    let left = t.remaining();
    let nb = t.count(&format!("the block count of `{name}`"), left)?;
    let bn0 = t.count(&format!("the block rows of `{name}`"), rows)?;
    let bn1 = t.count(&format!("the block columns of `{name}`"), cols)?;
    let bs0 = block_sizes(t, &format!("`{name}` blocksize0"), bn0, rows)?;
    let bs1 = block_sizes(t, &format!("`{name}` blocksize1"), bn1, cols)?;
    let line = t.line();
    let filled1 = t.count(&format!("`{name}` filled1"), t.remaining())?;
    let filled2 = t.count(&format!("`{name}` filled2"), t.remaining())?;
    if filled1 != bn0 + 1 || filled2 != nb {
        return Err(error(
            line,
            format!(
                "`{name}` has filled1 = {filled1} and filled2 = {filled2}: expected {} (block \
                 rows + 1) and {nb} (blocks)",
                bn0 + 1
            ),
        ));
    }
    let mut index1 = Vec::with_capacity(filled1);
    for k in 0..filled1 {
        let line = t.line();
        let v = t.count(&format!("`{name}` index1[{k}]"), nb)?;
        let expected_first = k > 0 || v == 0;
        if !expected_first || index1.last().is_some_and(|&p| v < p) {
            return Err(error(
                line,
                format!(
                    "`{name}` index1[{k}] = {v}: block-row pointers start at 0 and never decrease"
                ),
            ));
        }
        index1.push(v);
    }
    if index1.last() != Some(&nb) {
        return Err(error(
            t.line(),
            format!(
                "`{name}` index1 ends at {:?}, not at the block count {nb}",
                index1.last()
            ),
        ));
    }
    let mut index2 = Vec::with_capacity(filled2);
    for k in 0..filled2 {
        index2.push(t.count(&format!("`{name}` index2[{k}]"), bn1.saturating_sub(1))?);
    }
    let mut entries = Vec::new();
    for br in 0..bn0 {
        let (r0, r1) = (if br == 0 { 0 } else { bs0[br - 1] }, bs0[br]);
        for (k, &bc) in index2
            .iter()
            .enumerate()
            .take(index1[br + 1])
            .skip(index1[br])
        {
            let (c0, c1) = (if bc == 0 { 0 } else { bs1[bc - 1] }, bs1[bc]);
            let line = t.line();
            let label = t.count(&format!("the label of block {k} of `{name}`"), nb)?;
            if label != k {
                return Err(error(
                    line,
                    format!("block {k} of `{name}` is labelled {label}"),
                ));
            }
            let (h, w) = (r1 - r0, c1 - c0);
            let vals = t.reals(&format!("`{name}` block {k}"), h * w)?;
            for (j, col) in vals.chunks(h).enumerate() {
                // the zeros of a dense block are not entries (as in a dense matrix)
                for (i, &v) in col.iter().enumerate().filter(|(_, v)| **v != 0.0) {
                    entries.push((r0 + i, c0 + j, v));
                }
            }
        }
    }
    // a block given twice would be summed by the solver's triplet assembly: refuse it
    let mut seen: Vec<(usize, usize)> = Vec::with_capacity(nb);
    for br in 0..bn0 {
        seen.clear();
        seen.extend((index1[br]..index1[br + 1]).map(|k| (index2[k], k)));
        seen.sort_unstable();
        if let Some(p) = seen.windows(2).find(|p| p[0].0 == p[1].0) {
            return Err(error(
                line,
                format!(
                    "`{name}` gives block ({br}, {}) twice (blocks {} and {})",
                    p[0].0, p[0].1, p[1].1
                ),
            ));
        }
    }
    Ok(DatMatrix {
        rows,
        cols,
        values: Values::Triplets(entries),
    })
}

/// One number as `.dat` files hold it: the shortest form that reads back to the same `f64`.
fn push_real(out: &mut String, v: f64) {
    let _ = write!(out, " {v:e}");
}

/// Writes a dense row-major `rows × cols` matrix (storage 0).
pub(super) fn write_dense(out: &mut String, rows: usize, cols: usize, a: &[f64]) {
    let _ = writeln!(out, "0\n{rows}\n{cols}\n{rows}\t{cols}");
    for j in 0..cols {
        for i in 0..rows {
            push_real(out, a[i * cols + j]);
        }
        out.push('\n');
    }
}

/// Writes a square sparse matrix in `dim × dim` blocks (storage 1); a block is written when
/// any of its entries is stored.
pub(super) fn write_blocks(out: &mut String, dim: usize, w: &CsrMatrix) {
    let m = w.size();
    let nbr = m / dim;
    // block columns present in each block row, sorted
    let mut present: Vec<Vec<usize>> = vec![Vec::new(); nbr];
    for (i, cols) in present.iter_mut().enumerate() {
        for r in i * dim..(i + 1) * dim {
            cols.extend(w.row(r).0.iter().map(|&c| c as usize / dim));
        }
        cols.sort_unstable();
        cols.dedup();
    }
    let nb: usize = present.iter().map(Vec::len).sum();
    let _ = writeln!(out, "1\n{m}\n{m}\n{nb}\n{nbr}\n{nbr}");
    for _ in 0..2 {
        for i in 1..=nbr {
            let _ = write!(out, "{}\t", i * dim);
        }
        out.push('\n');
    }
    let _ = writeln!(out, "{}\n{nb}", nbr + 1);
    let mut p = 0;
    let _ = write!(out, "0\t");
    for cols in &present {
        p += cols.len();
        let _ = write!(out, "{p}\t");
    }
    out.push('\n');
    for c in present.iter().flatten() {
        let _ = write!(out, "{c}\t");
    }
    out.push('\n');
    let mut k = 0;
    for (bi, cols) in present.iter().enumerate() {
        for &bj in cols {
            let _ = writeln!(out, "{k}");
            for j in bj * dim..(bj + 1) * dim {
                for i in bi * dim..(bi + 1) * dim {
                    let _ = writeln!(out, "{:e}", w.get(i, j));
                }
            }
            k += 1;
        }
    }
}
