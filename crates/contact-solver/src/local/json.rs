//! The JSON form of a reduced problem (feature `serde`): `{"dim": 2 or 3, "W": ..., "q": [...],
//! "mu": [...]}` — what `shared/peers/siconos_fc.py` reads and `bipo solve-local` takes. `W`
//! is a flat row-major list, a list of rows, or sparse triplets
//! `{"m": m, "i": [...], "j": [...], "v": [...]}` (0-based, duplicates summed), read into the
//! sparse storage ([`ReducedProblem::from_json`]).
//!
//! # Messages
//! Reading is strict and says what to fix in the file's terms: the key path of the mistake
//! (`` `W[1][0]` ``, `` `mu` ``, by `serde_path_to_error`), what was found and what is
//! expected (`W` must be "a flat list of m² numbers, a list of m rows, or triplets {"m", "i",
//! "j", "v"}"), and serde_json's line and column. Unknown keys are refused with the list of
//! keys there are (no writer of this project, `to_json`, the examples or `shared/peers/`, adds
//! any; a typo such as `"Mu"` would otherwise surface as a missing `mu` at best).
use super::asymmetry::Asymmetry;
use super::delassus::WView;
use super::problem::ReducedProblem;
use crate::error::{Cause, SolverError};
use serde::Serialize;
use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Unexpected, Visitor};
use std::fmt;

/// What a problem must be, for the messages.
const PROBLEM_EXPECTED: &str = "the problem as a JSON object {\"dim\", \"W\", \"q\", \"mu\"}";
/// What `W` must be, for the messages.
const W_EXPECTED: &str =
    "W as a flat list of m² numbers, a list of m rows, or triplets {\"m\", \"i\", \"j\", \"v\"}";

/// The JSON form as written: `{"dim": d, "W": flat row-major or triplets, "q": [...], "mu": [...]}`.
#[derive(Serialize)]
struct JsonOut<'a> {
    dim: usize,
    #[serde(rename = "W")]
    w: MatrixOut,
    q: &'a [f64],
    mu: &'a [f64],
}

#[derive(Serialize)]
#[serde(untagged)]
enum MatrixOut {
    Flat(Vec<f64>),
    Triplets {
        m: usize,
        i: Vec<usize>,
        j: Vec<usize>,
        v: Vec<f64>,
    },
}

/// The JSON form as read (only an object; every key known).
#[derive(serde::Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "the problem's keys \"dim\", \"W\", \"q\", \"mu\""
)]
struct JsonIn {
    #[serde(default)]
    dim: Option<Dim>,
    #[serde(rename = "W")]
    w: MatrixIn,
    q: Numbers,
    mu: Numbers,
}

/// `W` as read.
enum MatrixIn {
    Flat(Vec<f64>),
    Rows(Vec<Vec<f64>>),
    Triplets(TripletsIn),
}

/// A sparse `W` as triplets: `W[i[k]][j[k]] += v[k]`, `m × m`, 0-based.
#[derive(serde::Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "the keys of W as triplets \"m\", \"i\", \"j\", \"v\""
)]
struct TripletsIn {
    m: Index,
    i: Indices,
    j: Indices,
    v: Numbers,
}

/// A problem: an object only (serde's derive would also take a list of the fields in order).
struct Problem(JsonIn);

/// `dim`: 2 or 3.
struct Dim(usize);

/// A number (integer or floating point).
struct Num(f64);

/// A list of numbers.
struct Numbers(Vec<f64>);

/// An index or a size: an integer `≥ 0`.
struct Index(usize);

/// A list of indices.
struct Indices(Vec<usize>);

/// An entry of `W` given as a list: a number (flat `W`) or a row.
enum Entry {
    Number(f64),
    Row(Vec<f64>),
}

/// A visitor that only says what it expects (the `visit_*` are those of each use).
struct Expect<T>(&'static str, std::marker::PhantomData<T>);

fn expect<T>(what: &'static str) -> Expect<T> {
    Expect(what, std::marker::PhantomData)
}

impl<'de> Visitor<'de> for Expect<Problem> {
    type Value = Problem;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0)
    }
    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Problem, A::Error> {
        JsonIn::deserialize(de::value::MapAccessDeserializer::new(map)).map(Problem)
    }
}

impl<'de> Deserialize<'de> for Problem {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(expect::<Self>(PROBLEM_EXPECTED))
    }
}

/// `visit_i64` of an unsigned target: a value `≥ 0` goes to `visit_u64`, a negative one is
/// refused with the visitor's expectation (shared by [`Dim`] and [`Index`]).
macro_rules! visit_signed_as_unsigned {
    () => {
        fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
            match u64::try_from(v) {
                Ok(v) => self.visit_u64(v),
                Err(_) => Err(E::invalid_value(Unexpected::Signed(v), &self)),
            }
        }
    };
}

impl Visitor<'_> for Expect<Dim> {
    type Value = Dim;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0)
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Dim, E> {
        match v {
            2 | 3 => Ok(Dim(v as usize)),
            _ => Err(E::invalid_value(Unexpected::Unsigned(v), &self)),
        }
    }
    visit_signed_as_unsigned!();
}

impl<'de> Deserialize<'de> for Dim {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_u64(expect::<Self>(
            "dim = 2 or 3 (unknowns per contact: a normal and 1 or 2 tangents)",
        ))
    }
}

/// The `visit_*` of a number, shared by [`Num`] and [`Entry`].
macro_rules! visit_number {
    ($out:expr) => {
        fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
            Ok($out(v))
        }
        fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
            Ok($out(v as f64))
        }
        fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
            Ok($out(v as f64))
        }
    };
}

impl Visitor<'_> for Expect<Num> {
    type Value = Num;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0)
    }
    visit_number!(Num);
}

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_f64(expect::<Self>("a number"))
    }
}

/// The elements of a list, each read as `T` and unwrapped by `f` (the capacity hint is capped:
/// a hostile length must not allocate before the elements are there).
fn list<'de, A: SeqAccess<'de>, T: Deserialize<'de>, U>(
    mut seq: A,
    f: impl Fn(T) -> U,
) -> Result<Vec<U>, A::Error> {
    let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(1 << 16));
    while let Some(v) = seq.next_element()? {
        out.push(f(v));
    }
    Ok(out)
}

/// The elements of a list of numbers.
fn numbers<'de, A: SeqAccess<'de>>(seq: A) -> Result<Vec<f64>, A::Error> {
    list(seq, |Num(v)| v)
}

impl<'de> Visitor<'de> for Expect<Numbers> {
    type Value = Numbers;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Numbers, A::Error> {
        numbers(seq).map(Numbers)
    }
}

impl<'de> Deserialize<'de> for Numbers {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_seq(expect::<Self>("a list of numbers"))
    }
}

impl Visitor<'_> for Expect<Index> {
    type Value = Index;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0)
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Index, E> {
        usize::try_from(v)
            .map(Index)
            .map_err(|_| E::invalid_value(Unexpected::Unsigned(v), &self))
    }
    visit_signed_as_unsigned!();
}

impl<'de> Deserialize<'de> for Index {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_u64(expect::<Self>(
            "an integer ≥ 0 (0-based index, or the size m)",
        ))
    }
}

impl<'de> Visitor<'de> for Expect<Indices> {
    type Value = Indices;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Indices, A::Error> {
        list(seq, |Index(v)| v).map(Indices)
    }
}

impl<'de> Deserialize<'de> for Indices {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_seq(expect::<Self>("a list of 0-based indices (integers ≥ 0)"))
    }
}

impl<'de> Visitor<'de> for Expect<Entry> {
    type Value = Entry;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0)
    }
    visit_number!(Entry::Number);
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Entry, A::Error> {
        numbers(seq).map(Entry::Row)
    }
}

impl<'de> Deserialize<'de> for Entry {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(expect::<Self>(
            "a number (W as a flat list) or a row of W (a list of numbers)",
        ))
    }
}

impl<'de> Visitor<'de> for Expect<MatrixIn> {
    type Value = MatrixIn;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<MatrixIn, A::Error> {
        let (mut flat, mut rows) = (Vec::new(), Vec::new());
        let mut k = 0;
        while let Some(entry) = seq.next_element()? {
            match entry {
                Entry::Number(v) if rows.is_empty() => flat.push(v),
                Entry::Row(r) if flat.is_empty() => rows.push(r),
                e => {
                    let (found, first) = match e {
                        Entry::Number(_) => ("a number", "a row"),
                        Entry::Row(_) => ("a row", "a number"),
                    };
                    return Err(de::Error::custom(format!(
                        "W mixes numbers and rows: W[{k}] is {found} but W[0] is \
                         {first}; expected {W_EXPECTED}"
                    )));
                }
            }
            k += 1;
        }
        Ok(if rows.is_empty() {
            MatrixIn::Flat(flat)
        } else {
            MatrixIn::Rows(rows)
        })
    }
    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<MatrixIn, A::Error> {
        TripletsIn::deserialize(de::value::MapAccessDeserializer::new(map)).map(MatrixIn::Triplets)
    }
}

impl<'de> Deserialize<'de> for MatrixIn {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(expect::<Self>(W_EXPECTED))
    }
}

/// Reads the JSON form; the error names the key path of the mistake (`` `W[1][0]`: `` before
/// serde_json's message and position) unless it is at the top level.
fn read(text: &str) -> Result<JsonIn, SolverError> {
    let mut de = serde_json::Deserializer::from_str(text);
    let problem: Result<Problem, _> = serde_path_to_error::deserialize(&mut de);
    let wrap = |e: serde_path_to_error::Error<serde_json::Error>| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        // a literal beyond f64 (`1e400`) is a syntax error to serde_json, but the user's
        // mistake is a value: name its key
        let out_of_range = inner.is_syntax() && inner.to_string().starts_with("number out of");
        let trivial = path == "." || path.is_empty();
        let source = if out_of_range && !trivial {
            Cause::message(format!(
                "`{path}`: {inner} (a number beyond the largest finite f64, ±1.8e308)"
            ))
        } else if trivial || inner.is_syntax() || inner.is_eof() {
            Cause::new(inner)
        } else {
            Cause::message(format!("`{path}`: {inner}"))
        };
        SolverError::Json { source }
    };
    let Problem(j) = problem.map_err(wrap)?;
    de.end()?;
    Ok(j)
}

impl ReducedProblem {
    /// Reads a problem from JSON `{"dim": 3, "W": [...], "q": [...], "mu": [...]}`, the format
    /// of `shared/peers/siconos_fc.py`: `W` is a flat row-major list or a list of rows (stored
    /// dense), or triplets `{"m": m, "i": [...], "j": [...], "v": [...]}` (0-based, stored
    /// sparse); `dim` is 2 or 3 (unknowns per contact, the normal first), and 2 when left out.
    ///
    /// # Errors
    /// [`SolverError::Json`] for malformed JSON or JSON of the wrong shape (a value of the
    /// wrong type, a negative index, a `dim` other than 2 or 3, an unknown or missing key; the
    /// message names the key path),
    /// [`SolverError::Format`] for a `W` whose size does not match `q` (flat, rows, or
    /// triplets whose `m` is not the length of `q`) or triplets with lists `i`, `j`, `v` of
    /// different lengths; otherwise those of
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
        Self::from_json_with_asymmetry(text, Asymmetry::default())
    }

    /// As [`from_json`](Self::from_json), with the [`Asymmetry`] policy `asymmetry`
    /// ([`Asymmetry::Keep`]: a non-symmetric `W`, as a multibody code exports it, is solved as
    /// given; see [`with_asymmetry`](Self::with_asymmetry)).
    ///
    /// # Errors
    /// As for [`from_json`](Self::from_json), the policy's as for
    /// [`with_asymmetry`](Self::with_asymmetry).
    ///
    /// # Examples
    /// ```
    /// use contact_solver::{Asymmetry, ReducedProblem};
    /// let text = r#"{"W": [[1, 0], [0.5, 1]], "q": [-1, 0], "mu": [0.3]}"#;
    /// assert!(ReducedProblem::from_json(text).is_err());
    /// let p = ReducedProblem::from_json_with_asymmetry(text, Asymmetry::Keep)?;
    /// assert!(!p.is_symmetric() && p.w_dense() == Some(&[1.0, 0.0, 0.5, 1.0][..]));
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn from_json_with_asymmetry(text: &str, asymmetry: Asymmetry) -> Result<Self, SolverError> {
        let j = read(text)?;
        let dim = j.dim.map_or(2, |d| d.0);
        let (q, mu) = (j.q.0, j.mu.0);
        let w = match j.w {
            MatrixIn::Triplets(t) => {
                let (m, i, jj, v) = (t.m.0, t.i.0, t.j.0, t.v.0);
                if m != q.len() {
                    return Err(SolverError::Format {
                        reason: format!(
                            "W given as triplets: m = {m} must be the length of q ({})",
                            q.len()
                        ),
                    });
                }
                if i.len() != v.len() || jj.len() != v.len() {
                    return Err(SolverError::Format {
                        reason: format!(
                            "W given as triplets: i, j and v must have one entry per stored \
                             value, found {} indices i, {} indices j and {} values v",
                            i.len(),
                            jj.len(),
                            v.len()
                        ),
                    });
                }
                return Self::from_triplets_with_asymmetry(dim, &i, &jj, &v, q, mu, asymmetry);
            }
            MatrixIn::Flat(w) => {
                let m = q.len();
                if w.len() != m * m {
                    return Err(SolverError::Format {
                        reason: format!(
                            "W given as a flat list has {} numbers: expected m² = {} (m = {m}, \
                             the length of q), row after row",
                            w.len(),
                            m * m
                        ),
                    });
                }
                w
            }
            MatrixIn::Rows(rows) => {
                let m = q.len();
                if rows.len() != m {
                    return Err(SolverError::Format {
                        reason: format!(
                            "W given as rows has {} rows: expected m = {m} (the length of q)",
                            rows.len()
                        ),
                    });
                }
                if let Some((k, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != m) {
                    return Err(SolverError::Format {
                        reason: format!(
                            "W given as rows: row {k} has {} entries, every row must have m = \
                             {m} (the length of q)",
                            r.len()
                        ),
                    });
                }
                rows.concat()
            }
        };
        Self::with_asymmetry(dim, w, q, mu, asymmetry)
    }

    /// Writes the problem as JSON `{"dim": d, "W": ..., "q": [...], "mu": [...]}`, `W` flat
    /// row-major when dense, as triplets `{"m", "i", "j", "v"}` of every stored entry when
    /// sparse (so the block pattern, explicit zeros included, survives a round trip).
    ///
    /// # Errors
    /// [`SolverError::Json`] if serialisation fails (it does not for a validated problem).
    pub fn to_json(&self) -> Result<String, SolverError> {
        Ok(serde_json::to_string(&JsonOut {
            dim: self.dimension(),
            w: match self.w() {
                WView::Dense(w) => MatrixOut::Flat(w.to_vec()),
                WView::Sparse(a) => {
                    let n = a.stored();
                    let (mut i, mut j, mut v) = (
                        Vec::with_capacity(n),
                        Vec::with_capacity(n),
                        Vec::with_capacity(n),
                    );
                    for (a, b, c) in a.triplets() {
                        i.push(a);
                        j.push(b);
                        v.push(c);
                    }
                    MatrixOut::Triplets {
                        m: a.size(),
                        i,
                        j,
                        v,
                    }
                }
            },
            q: self.q(),
            mu: self.mu(),
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
        let text = crate::error::chain(&e.unwrap_err());
        assert!(text.contains("`dim`: invalid value: integer `4`, expected dim = 2 or 3"));
        // an unknown key is named with the keys there are; a null problem says what it must be
        let e = ReducedProblem::from_json(r#"{"W":[1,0,0,1],"q":[0,0],"Mu":[0]}"#);
        let text = crate::error::chain(&e.unwrap_err());
        assert!(text.contains("unknown field `Mu`, expected one of `dim`, `W`, `q`, `mu`"));
        let text = crate::error::chain(&ReducedProblem::from_json("null").unwrap_err());
        assert!(text.contains(
            "invalid type: null, expected the problem as a JSON object {\"dim\", \"W\", \"q\", \"mu\"}"
        ));
        // dim 3 with 2 unknowns: q is not 3 n_c
        let e = ReducedProblem::from_json(r#"{"dim":3,"W":[1,0,0,1],"q":[0,0],"mu":[0]}"#);
        assert!(matches!(
            e,
            Err(SolverError::SizeMismatch { what: "q", .. })
        ));
        let e = ReducedProblem::from_json(r#"{"W":[[1,0],[0]],"q":[0,0],"mu":[0]}"#);
        assert!(matches!(e, Err(SolverError::Format { .. })));
        let e = ReducedProblem::from_json(r#"{"W":[[1,0],["a",1]],"q":[0,0],"mu":[0]}"#);
        let text = crate::error::chain(&e.unwrap_err());
        assert!(text.contains("`W[1][0]`: invalid type: string \"a\", expected a number"));
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
