//! Errors of `bipo`: one message naming the file, the line and column and the key path of the
//! offending value, what it was and what was expected. Never a panic.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// One segment of a key path: `contact[1].law.mu` is `Key(contact) Index(1) Key(law) Key(mu)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Seg {
    Key(String),
    Index(usize),
}

/// A key path in a scene file.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct KeyPath(pub Vec<Seg>);

impl KeyPath {
    pub fn root() -> Self {
        Self(Vec::new())
    }

    fn with(&self, seg: Seg) -> Self {
        let mut v = self.0.clone();
        v.push(seg);
        Self(v)
    }

    /// This path extended by a key.
    pub fn key(&self, k: &str) -> Self {
        self.with(Seg::Key(k.to_string()))
    }

    /// This path without its last segment (the root stays the root).
    pub fn parent(&self) -> Self {
        let mut v = self.0.clone();
        v.pop();
        Self(v)
    }

    /// This path extended by an index.
    pub fn index(&self, i: usize) -> Self {
        self.with(Seg::Index(i))
    }
}

impl fmt::Display for KeyPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, s) in self.0.iter().enumerate() {
            match s {
                Seg::Key(k) if i == 0 => write!(f, "{k}")?,
                Seg::Key(k) => write!(f, ".{k}")?,
                Seg::Index(n) => write!(f, "[{n}]")?,
            }
        }
        Ok(())
    }
}

/// `bail!(path, "…", args)`: returns `Err(CliError::at(&path, format!("…", args)))`, a
/// bad-input error at a key path.
macro_rules! bail {
    ($path:expr, $($message:tt)+) => {
        return Err($crate::error::err!($path, $($message)+))
    };
}
pub(crate) use bail;

/// `err!(path, "…", args)`: `CliError::at(&path, format!("…", args))`.
macro_rules! err {
    ($path:expr, $($message:tt)+) => {
        $crate::error::CliError::at(&$path, format!($($message)+))
    };
}
pub(crate) use err;

/// An error with what `bipo` knows of where it comes from.
#[derive(Debug)]
pub struct CliError {
    /// The file it is about.
    pub file: Option<PathBuf>,
    /// Byte span in the file.
    pub span: Option<Range<usize>>,
    /// Key path in the scene.
    pub path: Option<KeyPath>,
    /// The sentence.
    pub message: String,
    /// Exit code (2: bad input, 1: the computation failed).
    pub code: i32,
}

impl CliError {
    fn new(path: Option<KeyPath>, message: impl Into<String>, code: i32) -> Self {
        let message = message.into();
        Self {
            file: None,
            span: None,
            path,
            message,
            code,
        }
    }

    /// A bad-input error at a key path.
    pub fn at(path: &KeyPath, message: impl Into<String>) -> Self {
        Self::new(Some(path.clone()), message, 2)
    }

    /// A bad-input error without location.
    pub fn input(message: impl Into<String>) -> Self {
        Self::new(None, message, 2)
    }

    /// A failure of the computation or of the output files.
    pub fn failed(message: impl Into<String>) -> Self {
        Self::new(None, message, 1)
    }

    /// Sets the file if none is set yet.
    pub fn in_file(mut self, file: &Path) -> Self {
        if self.file.is_none() {
            self.file = Some(file.to_path_buf());
        }
        self
    }

    /// Renders the message, with `file:line:column` and the source line when known.
    pub fn render(&self, source: Option<&str>) -> String {
        let mut head = String::new();
        if let Some(f) = &self.file {
            head.push_str(&f.display().to_string());
        }
        let mut snippet = String::new();
        if let (Some(span), Some(src)) = (&self.span, source) {
            let (line, col) = line_col(src, span.start);
            head.push_str(&format!(":{line}:{col}"));
            if let Some(text) = src.lines().nth(line - 1) {
                let gutter = format!("{line}");
                // `col` counts characters (1-based), not bytes: a line may hold multi-byte
                // characters before the span (a byte-order mark, found by fuzz/)
                let chars = text.chars().count();
                let width = (span.end.saturating_sub(span.start))
                    .clamp(1, chars.saturating_sub(col - 1).max(1));
                snippet = format!(
                    "\n {gutter} | {text}\n {} | {}{}",
                    " ".repeat(gutter.len()),
                    " ".repeat((col - 1).min(chars)),
                    "^".repeat(width.min(60))
                );
            }
        }
        if !head.is_empty() {
            head.push_str(": ");
        }
        let path = match &self.path {
            Some(p) if !p.0.is_empty() && !self.message.contains(&format!("`{p}`")) => {
                format!("`{p}`: ")
            }
            _ => String::new(),
        };
        shorten(&format!("{head}{path}{}{snippet}", self.message))
    }
}

/// The longest word (a run without spaces) an error prints whole.
const MAX_WORD: usize = 200;
/// The longest line an error prints whole.
const MAX_LINE: usize = 1000;

/// A message with its absurdly long parts cut: a word longer than [`MAX_WORD`] characters (a
/// 200 kB string value echoed back, a source line quoted) keeps its first 80 and says how long
/// it was; a line still longer than [`MAX_LINE`] is cut the same way.
pub fn shorten(message: &str) -> String {
    let cut = |s: &str, keep: usize| -> String {
        let n = s.chars().count();
        let head: String = s.chars().take(keep).collect();
        // the closing quote and colon of a quoted value stay
        let tail: String = s
            .chars()
            .rev()
            .take(3)
            .take_while(|c| c.is_ascii_punctuation())
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        format!("{head}…[{n} characters]{tail}")
    };
    message
        .split('\n')
        .map(|line| {
            let line = line
                .split(' ')
                .map(|w| {
                    if w.chars().count() > MAX_WORD {
                        cut(w, 80)
                    } else {
                        w.to_string()
                    }
                })
                .collect::<Vec<_>>()
                .join(" ");
            if line.chars().count() > MAX_LINE {
                cut(&line, MAX_LINE)
            } else {
                line
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.render(None))
    }
}

/// 1-based line and column (in characters) of a byte offset.
pub fn line_col(src: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(src.len());
    let before = &src[..floor_char_boundary(src, offset)];
    let line = before.matches('\n').count() + 1;
    let col = before
        .rsplit('\n')
        .next()
        .map(|l| l.chars().count())
        .unwrap_or(0)
        + 1;
    (line, col)
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// The byte span of the value at `path` in the TOML text (the deepest existing prefix).
pub fn locate(src: &str, path: &KeyPath) -> Option<Range<usize>> {
    let root = toml::de::DeTable::parse(src).ok()?;
    let mut span = None;
    let mut table: Option<&toml::de::DeTable<'_>> = Some(root.get_ref());
    let mut value: Option<&toml::de::DeValue<'_>> = None;
    for seg in &path.0 {
        let next = match (seg, table, value) {
            (Seg::Key(k), Some(t), _) => t.get(k.as_str()),
            (Seg::Key(k), None, Some(v)) => v.get(k.as_str()),
            (Seg::Index(i), _, Some(v)) => v.get(*i),
            _ => None,
        };
        match next {
            Some(v) => {
                span = Some(v.span());
                value = Some(v.get_ref());
                table = None;
            }
            None => break,
        }
    }
    span
}

pub type CliResult<T> = Result<T, CliError>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shorten_cuts_huge_words_and_lines_works() {
        let huge = "a".repeat(200_000);
        let s = shorten(&format!("`title` = \"{huge}\": expected a short text"));
        assert!(s.len() < 200, "{s}");
        assert!(
            s.ends_with("…[200003 characters]\": expected a short text"),
            "{s}"
        );
        let spaced = "ab ".repeat(100_000);
        assert!(shorten(&spaced).chars().count() < MAX_LINE + 40);
        assert_eq!(shorten("short\nlines"), "short\nlines");
    }

    #[test]
    fn key_paths_display_like_toml_works() {
        let p = KeyPath::root().key("contact").index(1).key("law").key("mu");
        assert_eq!(p.to_string(), "contact[1].law.mu");
    }

    #[test]
    fn render_points_under_multibyte_characters_works() {
        // a byte-order mark and a Greek letter before the value: the caret goes under it (the
        // old code sliced the line at a character column as if it were a byte index: a panic)
        let src = "\u{feff}x = \"ββ\" ; 1\n";
        let mut e = CliError::input("bad");
        e.span = Some(src.find('1').unwrap()..src.len() - 1);
        let text = e.render(Some(src));
        let lines: Vec<&str> = text.lines().collect();
        let (quoted, caret) = (lines[1], lines[2]);
        let at = |l: &str, c: char| {
            l.chars().count() - 1 - l.chars().rev().position(|x| x == c).unwrap()
        };
        assert_eq!(at(quoted, '1'), at(caret, '^'), "{text}");
    }

    #[test]
    fn line_col_counts_characters_works() {
        let src = "a = 1\nβ = 2\n";
        assert_eq!(line_col(src, 0), (1, 1));
        assert_eq!(line_col(src, src.find('2').unwrap()), (2, 5));
    }

    #[test]
    fn locate_finds_nested_values_works() {
        let src = "[[contact]]\nname = \"a\"\nlaw = { type = \"coulomb\", mu = -1 }\n";
        let p = KeyPath::root().key("contact").index(0).key("law").key("mu");
        let span = locate(src, &p).unwrap();
        assert_eq!(&src[span], "-1");
        // a missing key: the deepest existing prefix
        let q = KeyPath::root().key("contact").index(0).key("target");
        assert_eq!(&src[locate(src, &q).unwrap()][..11], "[[contact]]");
    }
}
