//! The two checks every flat table makes once its `type` is known: the keys it needs, and no
//! key it does not read.

use crate::error::{CliResult, KeyPath, bail, err};

/// `present!(self; a, b)`: `[("a", self.a.is_some()), ("b", self.b.is_some())]`, the keys a
/// flat table has, for [`only`].
macro_rules! present {
    ($s:ident; $($k:ident),* $(,)?) => { [$((stringify!($k), $s.$k.is_some())),*] };
}
pub(super) use present;

/// `need(path, &opt, "key", "what")`: the value, or the error "`path`: what needs `key`".
pub(super) fn need<T: Clone>(path: &KeyPath, v: &Option<T>, key: &str, what: &str) -> CliResult<T> {
    v.clone()
        .ok_or_else(|| err!(path, "`{path}`: {what} needs `{key}`"))
}

/// Refuses the keys present that `what` does not read (`accepted`: the keys it reads, separated
/// by spaces).
pub(super) fn only(
    path: &KeyPath,
    what: &str,
    present: &[(&str, bool)],
    accepted: &str,
) -> CliResult<()> {
    let accepted: Vec<&str> = accepted.split_whitespace().collect();
    if let Some((k, _)) = present.iter().find(|(k, p)| *p && !accepted.contains(k)) {
        let p = path.key(k);
        let keys = if accepted.is_empty() {
            "none".to_string()
        } else {
            let quoted: Vec<String> = accepted.iter().map(|a| format!("`{a}`")).collect();
            quoted.join(", ")
        };
        bail!(p, "`{p}` is not a key of {what} (its keys: {keys})");
    }
    Ok(())
}
