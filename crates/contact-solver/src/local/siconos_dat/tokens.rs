//! The whitespace-separated tokens of a `.dat` file, each with its line, read in order.

use crate::error::SolverError;

/// The tokens of a file and a cursor; every error names the line of the token it is about
/// (the last line for a file that ends too early).
pub(super) struct Tokens<'a> {
    items: Vec<(usize, &'a str)>,
    at: usize,
    last_line: usize,
}

/// The error at `line`.
pub(super) fn error(line: usize, reason: impl Into<String>) -> SolverError {
    SolverError::SiconosDat {
        line,
        reason: reason.into(),
    }
}

impl<'a> Tokens<'a> {
    /// Splits `text` (lines counted from 1).
    pub(super) fn new(text: &'a str) -> Self {
        let mut items = Vec::new();
        let mut last_line = 1;
        for (k, l) in text.lines().enumerate() {
            last_line = k + 1;
            items.extend(l.split_whitespace().map(|t| (k + 1, t)));
        }
        Self {
            items,
            at: 0,
            last_line,
        }
    }

    /// How many tokens are left.
    pub(super) fn remaining(&self) -> usize {
        self.items.len() - self.at
    }

    /// The line of the next token (the last line at the end).
    pub(super) fn line(&self) -> usize {
        self.items.get(self.at).map_or(self.last_line, |t| t.0)
    }

    /// Whether the next token is an integer alone on its line (a storage type or a flag).
    pub(super) fn next_is_lone_integer(&self) -> bool {
        let Some(&(line, t)) = self.items.get(self.at) else {
            return false;
        };
        let alone_before = self.at == 0 || self.items[self.at - 1].0 != line;
        let alone_after = self.items.get(self.at + 1).is_none_or(|n| n.0 != line);
        alone_before && alone_after && t.parse::<i64>().is_ok()
    }

    fn next(&mut self, what: &str) -> Result<(usize, &'a str), SolverError> {
        let t = self.items.get(self.at).copied().ok_or_else(|| {
            error(
                self.last_line,
                format!("the file ends where {what} was expected"),
            )
        })?;
        self.at += 1;
        Ok(t)
    }

    /// The next token as a count in `0..=max` (`what` names it in errors).
    pub(super) fn count(&mut self, what: &str, max: usize) -> Result<usize, SolverError> {
        let (line, t) = self.next(what)?;
        let v: i64 = t
            .parse()
            .map_err(|_| error(line, format!("{what}: `{t}` is not an integer")))?;
        if v < 0 || v as u64 > max as u64 {
            return Err(error(
                line,
                format!("{what} = {v} is out of range (0 to {max})"),
            ));
        }
        Ok(v as usize)
    }

    /// The next token as a finite real.
    pub(super) fn real(&mut self, what: &str) -> Result<f64, SolverError> {
        let (line, t) = self.next(what)?;
        let v: f64 = t
            .parse()
            .map_err(|_| error(line, format!("{what}: `{t}` is not a number")))?;
        if !v.is_finite() {
            return Err(error(line, format!("{what} = `{t}` is not finite")));
        }
        Ok(v)
    }

    /// `n` reals (after checking that `n` tokens are left, so that a wrong count fails
    /// before anything is allocated).
    pub(super) fn reals(&mut self, what: &str, n: usize) -> Result<Vec<f64>, SolverError> {
        if self.remaining() < n {
            return Err(error(
                self.line(),
                format!(
                    "{what} needs {n} values but only {} are left in the file",
                    self.remaining()
                ),
            ));
        }
        (0..n).map(|k| self.real(&format!("{what}[{k}]"))).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_work() {
        let mut t = Tokens::new("3\n1 2\n\n4.5e0\n7\n");
        assert!(t.next_is_lone_integer());
        assert_eq!(t.count("a", 9).unwrap(), 3);
        // `1` shares its line with `2`: not a lone integer
        assert!(!t.next_is_lone_integer());
        assert_eq!(t.reals("b", 2).unwrap(), vec![1.0, 2.0]);
        assert_eq!(t.line(), 4);
        assert_eq!(t.real("c").unwrap(), 4.5);
        assert!(t.next_is_lone_integer());
        assert_eq!(t.remaining(), 1);
    }

    #[test]
    fn tokens_reject_bad_values() {
        let line = |e: SolverError| match e {
            SolverError::SiconosDat { line, .. } => line,
            other => panic!("{other:?}"),
        };
        assert_eq!(line(Tokens::new("\n-1").count("n", 9).unwrap_err()), 2);
        assert_eq!(line(Tokens::new("10").count("n", 9).unwrap_err()), 1);
        assert_eq!(line(Tokens::new("1.5").count("n", 9).unwrap_err()), 1);
        assert_eq!(line(Tokens::new("inf").real("x").unwrap_err()), 1);
        assert_eq!(line(Tokens::new("1\n2").reals("x", 3).unwrap_err()), 1);
        // the end of the file is reported at its last line
        let mut t = Tokens::new("1\n2\n");
        t.count("a", 9).unwrap();
        t.count("b", 9).unwrap();
        assert_eq!(line(t.count("c", 9).unwrap_err()), 2);
    }
}
