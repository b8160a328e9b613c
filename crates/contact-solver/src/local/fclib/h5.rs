//! Reading and writing FCLIB's datasets with the HDF5 library (`hdf5-metno`), every failure a
//! [`SolverError::Fclib`] naming the group or dataset. Sizes are checked against what the
//! problem expects *before* a dataset is read, so a hostile file cannot make us allocate more
//! than it declares consistently.

use super::sparse::{MAX_DENSE_ENTRIES, RawSparse, SparseForm};
use crate::error::{Cause, SolverError};
use hdf5::types::TypeDescriptor;
use hdf5::{Dataset, Group};

/// FCLIB stores every integer as a C `int`.
const INT_MAX: i64 = i32::MAX as i64;

/// The file being read or written, for the messages.
pub(super) struct H5File<'a> {
    /// The path as the user gave it.
    pub path: &'a str,
}

/// Which numbers a dataset must hold.
#[derive(Clone, Copy)]
enum Class {
    /// Signed or unsigned integers (indices, sizes).
    Integer,
    /// Floating-point numbers (integers are accepted and converted).
    Real,
}

impl H5File<'_> {
    /// The error with `reason` and no underlying cause.
    pub fn error(&self, reason: impl Into<String>) -> SolverError {
        SolverError::Fclib {
            path: self.path.to_owned(),
            reason: reason.into(),
            source: None,
        }
    }

    /// The error with `reason`, caused by the HDF5 library's `e`.
    pub fn h5_error(&self, reason: impl Into<String>, e: hdf5::Error) -> SolverError {
        SolverError::Fclib {
            path: self.path.to_owned(),
            reason: reason.into(),
            source: Some(Cause::new(e)),
        }
    }

    /// The group `name` of `parent` (whose path is `at`, `""` for the root).
    pub fn group(&self, parent: &Group, at: &str, name: &str) -> Result<Group, SolverError> {
        let full = join(at, name);
        if !parent.link_exists(name) {
            return Err(self.error(format!("missing group `{full}`")));
        }
        parent
            .group(name)
            .map_err(|e| self.h5_error(format!("`{full}` is not a group"), e))
    }

    fn dataset(&self, parent: &Group, at: &str, name: &str) -> Result<Dataset, SolverError> {
        let full = join(at, name);
        if !parent.link_exists(name) {
            return Err(self.error(format!("missing dataset `{full}`")));
        }
        parent
            .dataset(name)
            .map_err(|e| self.h5_error(format!("`{full}` is not a dataset"), e))
    }

    /// Checks the class and the number of entries of `ds` (`full` is its path).
    fn check(
        &self,
        ds: &Dataset,
        full: &str,
        class: Class,
        expected: usize,
    ) -> Result<(), SolverError> {
        let dtype = ds
            .dtype()
            .and_then(|t| t.to_descriptor())
            .map_err(|e| self.h5_error(format!("cannot read the type of `{full}`"), e))?;
        let ok = match class {
            Class::Integer => matches!(
                dtype,
                TypeDescriptor::Integer(_) | TypeDescriptor::Unsigned(_)
            ),
            Class::Real => matches!(
                dtype,
                TypeDescriptor::Float(_) | TypeDescriptor::Integer(_) | TypeDescriptor::Unsigned(_)
            ),
        };
        if !ok {
            let wanted = match class {
                Class::Integer => "integers",
                Class::Real => "numbers",
            };
            return Err(self.error(format!("`{full}` holds {dtype}, expected {wanted}")));
        }
        if ds.size() != expected {
            return Err(self.error(format!(
                "`{full}` has {} entries, expected {expected}",
                ds.size()
            )));
        }
        Ok(())
    }

    /// The `expected` integers of dataset `name` in `parent` (at `at`).
    pub fn ints(
        &self,
        parent: &Group,
        at: &str,
        name: &str,
        expected: usize,
    ) -> Result<Vec<i64>, SolverError> {
        let full = join(at, name);
        let ds = self.dataset(parent, at, name)?;
        self.check(&ds, &full, Class::Integer, expected)?;
        ds.read_raw::<i64>()
            .map_err(|e| self.h5_error(format!("cannot read `{full}`"), e))
    }

    /// The `expected` numbers of dataset `name`, each finite.
    pub fn reals(
        &self,
        parent: &Group,
        at: &str,
        name: &str,
        expected: usize,
    ) -> Result<Vec<f64>, SolverError> {
        let full = join(at, name);
        let ds = self.dataset(parent, at, name)?;
        self.check(&ds, &full, Class::Real, expected)?;
        let v = ds
            .read_raw::<f64>()
            .map_err(|e| self.h5_error(format!("cannot read `{full}`"), e))?;
        if let Some(k) = v.iter().position(|x| !x.is_finite()) {
            return Err(self.error(format!("`{full}[{k}]` = {} is not finite", v[k])));
        }
        Ok(v)
    }

    /// The one integer of dataset `name` (FCLIB writes a 1-D array of one entry; a scalar
    /// dataset is accepted too).
    pub fn int(&self, parent: &Group, at: &str, name: &str) -> Result<i64, SolverError> {
        let v = self.ints(parent, at, name, 1)?;
        Ok(v[0])
    }

    /// A size (`0 ≤ v ≤ i32::MAX`) from dataset `name`.
    pub fn size(&self, parent: &Group, at: &str, name: &str) -> Result<usize, SolverError> {
        let v = self.int(parent, at, name)?;
        usize::try_from(v)
            .ok()
            .filter(|_| v <= INT_MAX)
            .ok_or_else(|| {
                self.error(format!(
                    "`{}` = {v} is not a size (0 to 2^31 - 1)",
                    join(at, name)
                ))
            })
    }

    /// The sparse matrix of group `name` of `parent`, sizes and lengths checked (the indices are
    /// checked when it is decoded).
    pub fn matrix(&self, parent: &Group, at: &str, name: &str) -> Result<RawSparse, SolverError> {
        let full = join(at, name);
        let g = self.group(parent, at, name)?;
        let m = self.size(&g, &full, "m")?;
        let n = self.size(&g, &full, "n")?;
        let nz = self.int(&g, &full, "nz")?;
        let form = SparseForm::from_nz(nz).ok_or_else(|| {
            self.error(format!(
                "`{full}/nz` = {nz} is not a sparse form: -1 (compressed columns), -2 \
                 (compressed rows) or a number of triplets >= 0"
            ))
        })?;
        let cap = m.saturating_mul(n).clamp(1, MAX_DENSE_ENTRIES);
        let nzmax = if g.link_exists("nzmax") {
            Some(self.size(&g, &full, "nzmax")?)
        } else {
            None
        };
        let (p, count) = match form {
            SparseForm::Triplet => {
                let nz = nz as usize;
                if nz > cap {
                    return Err(self.error(format!(
                        "`{full}/nz` = {nz} triplets: more than the {cap} entries of a {m} x {n} \
                         matrix"
                    )));
                }
                (self.ints(&g, &full, "p", nz)?, nz)
            }
            SparseForm::CompressedColumn | SparseForm::CompressedRow => {
                let outer = if form == SparseForm::CompressedColumn {
                    n
                } else {
                    m
                };
                let p = self.ints(&g, &full, "p", outer + 1)?;
                let last = p[outer];
                let count = usize::try_from(last)
                    .ok()
                    .filter(|&c| c <= cap)
                    .ok_or_else(|| {
                        self.error(format!(
                            "`{full}/p[{outer}]` = {last} entries: not between 0 and the {cap} \
                             entries of a {m} x {n} matrix"
                        ))
                    })?;
                (p, count)
            }
        };
        let stored = match nzmax {
            Some(nzmax) if nzmax < count || nzmax > cap.max(count) => {
                return Err(self.error(format!(
                    "`{full}/nzmax` = {nzmax} is inconsistent: {count} entries are used, at most \
                     {cap} fit a {m} x {n} matrix"
                )));
            }
            Some(nzmax) => nzmax,
            None => count,
        };
        let i_len = if form == SparseForm::Triplet {
            count
        } else {
            stored
        };
        // FCLIB says `i` and `x` hold `nzmax` entries, but some versions of fclib.c write only
        // the `count` that are used (issue 37): either length is read, anything else refused.
        let i_len = self.used_or(&g, &full, "i", count, i_len)?;
        let x_len = self.used_or(&g, &full, "x", count, stored)?;
        let i = self.ints(&g, &full, "i", i_len)?;
        let x = self.reals(&g, &full, "x", x_len)?;
        Ok(RawSparse {
            m,
            n,
            form,
            p,
            i,
            x,
        })
    }

    /// `used` when dataset `name` holds exactly that many entries, `stored` otherwise (whose
    /// length the read then checks, naming the dataset).
    fn used_or(
        &self,
        g: &Group,
        at: &str,
        name: &str,
        used: usize,
        stored: usize,
    ) -> Result<usize, SolverError> {
        let ds = self.dataset(g, at, name)?;
        Ok(if ds.size() == used { used } else { stored })
    }

    /// Writes `v` as a 1-D dataset `name` of C `int`s (FCLIB's `H5LTmake_dataset_int`).
    pub fn write_ints(
        &self,
        g: &Group,
        at: &str,
        name: &str,
        v: &[i64],
    ) -> Result<(), SolverError> {
        let full = join(at, name);
        let ints = v
            .iter()
            .map(|&x| i32::try_from(x))
            .collect::<Result<Vec<i32>, _>>()
            .map_err(|_| self.error(format!("`{full}` does not fit FCLIB's 32-bit integers")))?;
        g.new_dataset_builder()
            .with_data(&ints[..])
            .create(name)
            .map(|_| ())
            .map_err(|e| self.h5_error(format!("cannot write `{full}`"), e))
    }

    /// Writes `v` as a 1-D dataset `name` of `double`s.
    pub fn write_reals(
        &self,
        g: &Group,
        at: &str,
        name: &str,
        v: &[f64],
    ) -> Result<(), SolverError> {
        g.new_dataset_builder()
            .with_data(v)
            .create(name)
            .map(|_| ())
            .map_err(|e| self.h5_error(format!("cannot write `{}`", join(at, name)), e))
    }

    /// Creates the group `name` of `parent`.
    pub fn create_group(&self, parent: &Group, at: &str, name: &str) -> Result<Group, SolverError> {
        parent
            .create_group(name)
            .map_err(|e| self.h5_error(format!("cannot create group `{}`", join(at, name)), e))
    }

    /// Writes `a` as the sparse matrix group `name` (FCLIB's `write_matrix`).
    pub fn write_matrix(
        &self,
        parent: &Group,
        at: &str,
        name: &str,
        a: &RawSparse,
    ) -> Result<(), SolverError> {
        let full = join(at, name);
        let g = self.create_group(parent, at, name)?;
        let size = |v: usize| v as i64;
        self.write_ints(&g, &full, "nzmax", &[size(a.x.len())])?;
        self.write_ints(&g, &full, "m", &[size(a.m)])?;
        self.write_ints(&g, &full, "n", &[size(a.n)])?;
        self.write_ints(&g, &full, "nz", &[a.nz()])?;
        self.write_ints(&g, &full, "p", &a.p)?;
        self.write_ints(&g, &full, "i", &a.i)?;
        self.write_reals(&g, &full, "x", &a.x)
    }
}

/// `at/name` (or `name` at the root).
pub(super) fn join(at: &str, name: &str) -> String {
    if at.is_empty() {
        name.to_owned()
    } else {
        format!("{at}/{name}")
    }
}
