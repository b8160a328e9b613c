//! The JSON form of a reduced problem (feature `serde`): `{"dim": 2 or 3, "W": ..., "q": [...],
//! "mu": [...]}` — what `shared/peers/siconos_fc.py` reads and `bipo solve-local` takes. `W`
//! is a flat row-major list, a list of rows, or sparse triplets
//! `{"m": m, "i": [...], "j": [...], "v": [...]}` (0-based, duplicates summed), read into the
//! sparse storage ([`ReducedProblem::from_triplets`]).

use super::delassus::WView;
use super::problem::ReducedProblem;
use crate::error::SolverError;
use serde::{Deserialize, Serialize};

/// The JSON form: `{"dim": 2 or 3, "W": flat row-major or list of rows, "q": [...], "mu": [...]}`.
#[derive(Serialize, Deserialize)]
struct JsonProblem {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    dim: Option<usize>,
    #[serde(rename = "W")]
    w: JsonMatrix,
    q: Vec<f64>,
    mu: Vec<f64>,
}

#[derive(Serialize, Deserialize)]
#[serde(untagged)]
enum JsonMatrix {
    Flat(Vec<f64>),
    Rows(Vec<Vec<f64>>),
    Triplets(JsonTriplets),
}

/// A sparse `W` as triplets: `W[i[k]][j[k]] += v[k]`, `m × m`, 0-based.
#[derive(Serialize, Deserialize)]
struct JsonTriplets {
    m: usize,
    i: Vec<usize>,
    j: Vec<usize>,
    v: Vec<f64>,
}

impl ReducedProblem {
    /// Reads a problem from JSON `{"dim": 3, "W": [...], "q": [...], "mu": [...]}`, the format
    /// of `shared/peers/siconos_fc.py`: `W` is a flat row-major list or a list of rows (stored
    /// dense), or triplets `{"m": m, "i": [...], "j": [...], "v": [...]}` (0-based, stored
    /// sparse); `dim` is 2 or 3 (unknowns per contact, the normal first), and 2 when left out.
    ///
    /// # Errors
    /// [`SolverError::Json`] for malformed JSON (a negative index included),
    /// [`SolverError::Format`] for ragged rows, triplets whose `m` is not the length of `q`, or
    /// a `dim` other than 2 or 3; otherwise those of
    /// [`with_dimension`](Self::with_dimension) or [`from_triplets`](Self::from_triplets).
    ///
    /// # Examples
    /// ```
    /// use contact_solver::ReducedProblem;
    /// let p = ReducedProblem::from_json(r#"{"W": [[1, 0], [0, 1]], "q": [-1, 0], "mu": [0.5]}"#)?;
    /// assert_eq!(p.w_dense(), Some(&[1.0, 0.0, 0.0, 1.0][..]));
    /// let s = ReducedProblem::from_json(
    ///     r#"{"W": {"m": 2, "i": [0, 1], "j": [0, 1], "v": [1, 1]}, "q": [-1, 0], "mu": [0.5]}"#,
    /// )?;
    /// assert!(s.is_sparse() && s.w_sparse().unwrap().get(1, 1) == 1.0);
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn from_json(text: &str) -> Result<Self, SolverError> {
        let j: JsonProblem = serde_json::from_str(text)?;
        let dim = j.dim.unwrap_or(2);
        if !(dim == 2 || dim == 3) {
            return Err(SolverError::Format {
                reason: format!(
                    "dim = {dim} is not supported: 2 or 3 (unknowns per contact: a normal and 1 \
                     or 2 tangents)"
                ),
            });
        }
        let w = match j.w {
            JsonMatrix::Triplets(t) => {
                if t.m != j.q.len() {
                    return Err(SolverError::Format {
                        reason: format!(
                            "W given as triplets: m = {} must be the length of q ({})",
                            t.m,
                            j.q.len()
                        ),
                    });
                }
                return Self::from_triplets(dim, &t.i, &t.j, &t.v, j.q, j.mu);
            }
            JsonMatrix::Flat(w) => w,
            JsonMatrix::Rows(rows) => {
                let m = j.q.len();
                if rows.iter().any(|r| r.len() != m) {
                    return Err(SolverError::Format {
                        reason: format!(
                            "W given as rows: every row must have {m} entries (the length of q)"
                        ),
                    });
                }
                rows.concat()
            }
        };
        Self::with_dimension(dim, w, j.q, j.mu)
    }

    /// Writes the problem as JSON `{"dim": d, "W": ..., "q": [...], "mu": [...]}`, `W` flat
    /// row-major when dense, as triplets `{"m", "i", "j", "v"}` of every stored entry when
    /// sparse (so the block pattern, explicit zeros included, survives a round trip).
    ///
    /// # Errors
    /// [`SolverError::Json`] if serialisation fails (it does not for a validated problem).
    pub fn to_json(&self) -> Result<String, SolverError> {
        Ok(serde_json::to_string(&JsonProblem {
            dim: Some(self.dimension()),
            w: match self.w() {
                WView::Dense(w) => JsonMatrix::Flat(w.to_vec()),
                WView::Sparse(a) => {
                    let n = a.stored();
                    let mut t = JsonTriplets {
                        m: a.size(),
                        i: Vec::with_capacity(n),
                        j: Vec::with_capacity(n),
                        v: Vec::with_capacity(n),
                    };
                    for (i, j, v) in a.triplets() {
                        t.i.push(i);
                        t.j.push(j);
                        t.v.push(v);
                    }
                    JsonMatrix::Triplets(t)
                }
            },
            q: self.q().to_vec(),
            mu: self.mu().to_vec(),
        })?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_json_reads_dim_3_and_rejects_dim_4_and_ragged_rows() {
        let p = ReducedProblem::from_json(
            r#"{"dim":3,"W":[[2,0,0],[0,1,0],[0,0,1]],"q":[-1,0,0],"mu":[0.5]}"#,
        )
        .unwrap();
        assert_eq!((p.dimension(), p.contact_count()), (3, 1));
        assert_eq!(ReducedProblem::from_json(&p.to_json().unwrap()).unwrap(), p);
        let e = ReducedProblem::from_json(r#"{"dim":4,"W":[1,0,0,1],"q":[0,0],"mu":[0]}"#);
        assert!(matches!(e, Err(SolverError::Format { .. })));
        // dim 3 with 2 unknowns: q is not 3 n_c
        let e = ReducedProblem::from_json(r#"{"dim":3,"W":[1,0,0,1],"q":[0,0],"mu":[0]}"#);
        assert!(matches!(
            e,
            Err(SolverError::SizeMismatch { what: "q", .. })
        ));
        let e = ReducedProblem::from_json(r#"{"W":[[1,0],[0]],"q":[0,0],"mu":[0]}"#);
        assert!(matches!(e, Err(SolverError::Format { .. })));
        // triplets: m must be the length of q; a negative index is a parse error
        let e = ReducedProblem::from_json(
            r#"{"W":{"m":3,"i":[0],"j":[0],"v":[1]},"q":[0,0],"mu":[0]}"#,
        );
        assert!(matches!(e, Err(SolverError::Format { .. })));
        let e = ReducedProblem::from_json(
            r#"{"W":{"m":2,"i":[-1],"j":[0],"v":[1]},"q":[0,0],"mu":[0]}"#,
        );
        assert!(matches!(e, Err(SolverError::Json { .. })));
        let e = ReducedProblem::from_json(
            r#"{"W":{"m":2,"i":[0,2],"j":[0,1],"v":[1,1]},"q":[0,0],"mu":[0]}"#,
        );
        assert!(matches!(
            e,
            Err(SolverError::IndexOutOfRange {
                what: "rows",
                index: 1,
                ..
            })
        ));
        let e = ReducedProblem::from_json("{").unwrap_err();
        assert!(matches!(e, SolverError::Json { .. }));
        // the parser's message once, in the chain
        assert_eq!(e.to_string(), "cannot read the reduced problem from JSON");
        assert!(
            crate::error::chain(&e).contains("EOF"),
            "{}",
            crate::error::chain(&e)
        );
    }
}
