//! The checks around the [`mshio`] parser, for both dimensions: the `$MeshFormat` header, the
//! node tags of an ASCII `$Nodes` section, the `$PhysicalNames` section (which `mshio` does not
//! read), a panic inside the parser, and its errors told with a line and a byte offset.

use super::build::Names;
use crate::error::FemError;
use mshio::error::MshParserErrorKind;
use mshio::{ElementType, MshFile, MshParserError};
use std::collections::HashMap;

/// Parses a `.msh` 4.1 file with `mshio`, behind the checks that guard it (header, node
/// tags, a panic inside the parser), and reads its `$PhysicalNames`.
pub(crate) fn parse_file(
    bytes: &[u8],
    origin: &str,
) -> Result<(MshFile<u64, i32, f64>, Names), FemError> {
    let io = |detail: String| FemError::invalid_file(origin, detail);
    check_header(bytes).map_err(|e| match e {
        HeaderError::Version(v) => FemError::Unsupported {
            what: format!(
                "MSH format version {v} in {origin}: only 4.1 is read (Gmsh option \
                 Mesh.MshFileVersion = 4.1)"
            ),
        },
        HeaderError::Invalid(detail) => io(detail),
    })?;
    let names = physical_names(bytes).map_err(io)?;
    check_ascii_node_tags(bytes).map_err(io)?;
    // `mshio` still has a few `unimplemented!` and unchecked subtractions on odd input (e.g.
    // an empty element block count); a panic there must not reach the caller.
    let parsed = std::panic::catch_unwind(|| mshio::parse_msh_bytes(bytes))
        .map_err(|_| io("the MSH parser failed on malformed data".to_string()))?;
    let file = parsed.map_err(|e| parser_error(&e, bytes, origin))?;
    Ok((file, names))
}

enum HeaderError {
    Version(String),
    Invalid(String),
}

/// Checks `$MeshFormat` before `mshio` sees it: its version and data size are read here.
fn check_header(bytes: &[u8]) -> Result<(), HeaderError> {
    let head = &bytes[..bytes.len().min(256)];
    let text = String::from_utf8_lossy(head);
    let mut lines = text.lines().map(str::trim).skip_while(|l| l.is_empty());
    if lines.next() != Some("$MeshFormat") {
        return Err(HeaderError::Invalid(
            "not a Gmsh .msh file: it does not start with $MeshFormat".to_string(),
        ));
    }
    let format = lines.next().unwrap_or("");
    let fields: Vec<&str> = format.split_whitespace().collect();
    let [version, file_type, data_size] = fields[..] else {
        return Err(HeaderError::Invalid(format!(
            "line 2: expected `version file-type data-size`, found `{format}`"
        )));
    };
    if version.parse::<f64>() != Ok(4.1) {
        return Err(HeaderError::Version(version.to_string()));
    }
    match (file_type, data_size) {
        // (`mshio` unwraps the data size's integer: a huge one panicked, found by fuzz/)
        ("0" | "1", "1" | "2" | "4" | "8" | "16") => Ok(()),
        _ => Err(HeaderError::Invalid(format!(
            "line 2: file type `{file_type}` (0 ASCII, 1 binary) with data size \
             `{data_size}` is not valid"
        ))),
    }
}

/// Checks the node tags of an ASCII `$Nodes` section before `mshio` reads it: `mshio` trusts
/// the section's header, and when it announces contiguous tags (`max − min = n − 1`) it drops
/// the tags and numbers the nodes `min, min + 1, …` in file order, so a repeated or stray tag
/// would silently move a node. Each tag must appear once, within `[min, max]`, and, when the
/// header announces contiguous tags, in that order. Binary files are left to `mshio`.
fn check_ascii_node_tags(bytes: &[u8]) -> Result<(), String> {
    let ascii = String::from_utf8_lossy(&bytes[..bytes.len().min(256)])
        .lines()
        .nth(1)
        .and_then(|l| l.split_whitespace().nth(1).map(|f| f == "0"))
        .unwrap_or(false);
    const START: &[u8] = b"$Nodes";
    let Some(start) = bytes
        .windows(START.len() + 1)
        .position(|w| &w[..START.len()] == START && w[START.len()].is_ascii_whitespace())
        .filter(|&p| p == 0 || bytes[p - 1] == b'\n')
    else {
        return Ok(());
    };
    if !ascii {
        return Ok(());
    }
    let body = &bytes[start + START.len()..];
    let end = body
        .windows(9)
        .position(|w| w == b"$EndNodes")
        .unwrap_or(body.len());
    let text = String::from_utf8_lossy(&body[..end]);
    let mut tokens = text.split_whitespace();
    let mut next = |what: &str| -> Result<u64, String> {
        let token = tokens.next();
        if what == "a coordinate" {
            return Ok(0);
        }
        token
            .and_then(|s| s.parse::<u64>().ok())
            .ok_or_else(|| format!("$Nodes: expected {what}"))
    };
    let (blocks, count, min, max) = (
        next("the number of blocks")?,
        next("the number of nodes")?,
        next("the minimum tag")?,
        next("the maximum tag")?,
    );
    let contiguous = count > 0 && max.checked_sub(min) == Some(count - 1);
    let mut seen = std::collections::HashSet::new();
    let mut expected = min;
    for _ in 0..blocks {
        let (_dim, _entity, parametric, n) = (
            next("a block's dimension")?,
            next("a block's entity tag")?,
            next("a block's parametric flag")?,
            next("a block's node count")?,
        );
        for _ in 0..n {
            let tag = next("a node tag")?;
            if !(min..=max).contains(&tag) {
                return Err(format!(
                    "node tag {tag} is outside the range {min}…{max} announced by the $Nodes header"
                ));
            }
            if !seen.insert(tag) {
                return Err(format!("node tag {tag} is defined twice"));
            }
            if contiguous && tag != expected {
                return Err(format!(
                    "node tag {tag} where {expected} was expected: the $Nodes header announces \
                     the contiguous tags {min}…{max}"
                ));
            }
            expected += 1;
        }
        // the coordinates (3 per node, plus parametric ones, which `mshio` refuses anyway)
        if parametric != 0 {
            return Ok(());
        }
        for _ in 0..3 * n {
            next("a coordinate")?;
        }
    }
    Ok(())
}

/// The `$PhysicalNames` section (ASCII in both file types), by `(dimension, tag)`.
fn physical_names(bytes: &[u8]) -> Result<HashMap<(i32, i32), String>, String> {
    const START: &[u8] = b"$PhysicalNames";
    let Some(start) = bytes
        .windows(START.len())
        .position(|w| w == START)
        .filter(|&p| p == 0 || bytes[p - 1] == b'\n')
    else {
        return Ok(HashMap::new());
    };
    let line0 = bytes[..start].iter().filter(|&&b| b == b'\n').count() + 2;
    let body = &bytes[start + START.len()..];
    let text = String::from_utf8_lossy(&body[..body.len().min(1 << 20)]);
    let mut lines = text.lines().skip(1);
    let bad = |k: usize, what: &str| format!("$PhysicalNames, line {}: {what}", line0 + k);
    let count: usize = lines
        .next()
        .and_then(|l| l.trim().parse().ok())
        .ok_or_else(|| bad(0, "expected the number of names"))?;
    let mut names = HashMap::new();
    for k in 1..=count {
        let line = lines.next().ok_or_else(|| bad(k, "missing line"))?;
        let mut parts = line.trim().splitn(3, char::is_whitespace);
        let dim = parts.next().and_then(|s| s.parse::<i32>().ok());
        let tag = parts.next().and_then(|s| s.parse::<i32>().ok());
        let name = parts
            .next()
            .map(str::trim)
            .and_then(|s| s.strip_prefix('"'))
            .and_then(|s| s.strip_suffix('"'));
        match (dim, tag, name) {
            (Some(dim), Some(tag), Some(name)) => {
                names.insert((dim, tag), name.to_string());
            }
            _ => return Err(bad(k, "expected `dimension tag \"name\"`")),
        }
    }
    match lines.next().map(str::trim) {
        Some("$EndPhysicalNames") => Ok(names),
        _ => Err(bad(count + 1, "expected $EndPhysicalNames")),
    }
}

/// Turns a `mshio` error into ours, without its unbounded hex dump.
fn parser_error(e: &MshParserError<&[u8]>, bytes: &[u8], origin: &str) -> FemError {
    let trace = e.filtered_backtrace();
    if let Some((_, MshParserErrorKind::UnknownElement)) = trace.first() {
        let value = trace
            .iter()
            .find_map(|(_, k)| k.context().and_then(|c| c.strip_prefix("value ")))
            .unwrap_or("?");
        return FemError::Unsupported {
            what: format!("Gmsh element type {value} (unknown to the reader) in {origin}"),
        };
    }
    let Some((rest, kind)) = trace.first() else {
        return FemError::invalid_file(origin, "invalid MSH 4.1 data");
    };
    let offset = bytes.len().saturating_sub(rest.len());
    let line = bytes[..offset].iter().filter(|&&b| b == b'\n').count() + 1;
    let mut context: Vec<&str> = trace
        .iter()
        .rev()
        .filter_map(|(_, k)| k.context())
        .collect();
    let what = match kind.context() {
        Some(c) => {
            context.pop();
            format!("expected {c}")
        }
        None => kind.to_string(),
    };
    FemError::invalid_file(
        origin,
        format!(
            "invalid MSH 4.1 data near line {line}, byte {offset} (in {}): {what}",
            context.join(" > ")
        ),
    )
}

/// `MSH_QUA_4`-style name of a Gmsh element type (as in Gmsh's `GmshDefines.h`).
fn gmsh_type_name(t: ElementType) -> String {
    // `Tri15i` → `MSH_TRI_15I`, `PntSub` → `MSH_PNT_SUB`, `Pnt` → `MSH_PNT`.
    let short = format!("{t:?}");
    let split = short
        .char_indices()
        .skip(1)
        .find(|(_, c)| !c.is_ascii_lowercase())
        .map_or(short.len(), |(i, _)| i);
    let (family, rest) = short.split_at(split);
    match rest {
        "" => format!("MSH_{}", family.to_uppercase()),
        _ => format!("MSH_{}_{}", family.to_uppercase(), rest.to_uppercase()),
    }
}

/// An element type the reader does not take; `read` says what it does take.
pub(crate) fn unsupported_type(t: ElementType, dim: i32, tag: i32, read: &str) -> FemError {
    FemError::Unsupported {
        what: format!(
            "Gmsh element type {} ({}) on entity ({dim}, {tag}): only {read} are read",
            t as i32,
            gmsh_type_name(t)
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gmsh_type_name_works() {
        assert_eq!(gmsh_type_name(ElementType::Qua4), "MSH_QUA_4");
        assert_eq!(gmsh_type_name(ElementType::Tri6), "MSH_TRI_6");
        assert_eq!(gmsh_type_name(ElementType::Pnt), "MSH_PNT");
        assert_eq!(gmsh_type_name(ElementType::Tet10), "MSH_TET_10");
        assert_eq!(gmsh_type_name(ElementType::Tri15i), "MSH_TRI_15I");
        assert_eq!(gmsh_type_name(ElementType::PntSub), "MSH_PNT_SUB");
        assert_eq!(gmsh_type_name(ElementType::Trih4), "MSH_TRIH_4");
    }

    #[test]
    fn check_header_rejects_bad_headers() {
        assert!(check_header(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n").is_ok());
        assert!(check_header(b"\n  $MeshFormat\r\n4.1 1 8\r\n").is_ok());
        assert!(check_header(b"$MeshFormat\n4.10 0 8\n").is_ok());
        assert!(matches!(
            check_header(b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"),
            Err(HeaderError::Version(v)) if v == "2.2"
        ));
        assert!(matches!(
            check_header(b"$MeshFormat\n4.1 1 3\n"),
            Err(HeaderError::Invalid(_))
        ));
        assert!(matches!(
            check_header(b"$MeshFormat\n4.1\n"),
            Err(HeaderError::Invalid(_))
        ));
        assert!(matches!(
            check_header(b"hello"),
            Err(HeaderError::Invalid(_))
        ));
        assert!(matches!(check_header(b""), Err(HeaderError::Invalid(_))));
    }

    #[test]
    fn physical_names_works() {
        let text = b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n\
                     1 3 \"bottom edge\"\n2 7 \"soil\"\n$EndPhysicalNames\n";
        let names = physical_names(text).unwrap();
        assert_eq!(names[&(1, 3)], "bottom edge");
        assert_eq!(names[&(2, 7)], "soil");
        assert!(physical_names(b"$MeshFormat\n").unwrap().is_empty());
        let bad = b"$PhysicalNames\n2\n1 3 \"a\"\n$EndPhysicalNames\n";
        assert!(physical_names(bad).unwrap_err().contains("line 4"));
        assert!(physical_names(b"$PhysicalNames\n1\n1 x \"a\"\n$EndPhysicalNames\n").is_err());
    }
}
