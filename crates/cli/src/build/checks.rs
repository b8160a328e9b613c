//! The checks of single values (finite, positive, counts, Poisson's ratios), the names of the
//! element kinds, and the library errors turned into errors at a key path (with the whole
//! source chain).

use crate::error::{CliError, CliResult, KeyPath, bail, err};
use crate::spec::{Element, GradingSpec, Pair};
use contact_laws::LawError;
use contact_solver::SolverError;
use contact_solver::error::chain;
use fem_core::generate::Grading;
use fem_core::{Dim, ElementKind, FemError, Mesh, Space};
use std::collections::BTreeSet;

/// `value`, or the error "`path` = value: expected `expected`" when not `ok`.
pub(super) fn expect(path: &KeyPath, value: f64, ok: bool, expected: &str) -> CliResult<f64> {
    if ok {
        Ok(value)
    } else {
        bail!(path, "`{path}` = {value:?}: expected {expected}")
    }
}

/// A finite number > 0, and not subnormal (below 2.2e-308 a positive value has lost its
/// digits and its inverse overflows: no length, modulus, time or tolerance is that small).
pub(super) fn positive(path: &KeyPath, v: f64) -> CliResult<f64> {
    expect(path, v, v.is_finite() && v > 0.0, "a finite number > 0")?;
    expect(
        path,
        v,
        v.is_normal(),
        "a finite number > 0 that is not subnormal (at least 2.2e-308)",
    )
}

/// A finite number >= 0.
pub(super) fn non_negative(path: &KeyPath, v: f64) -> CliResult<f64> {
    expect(path, v, v.is_finite() && v >= 0.0, "a finite number >= 0")
}

pub(super) fn finite(path: &KeyPath, v: f64) -> CliResult<f64> {
    expect(path, v, v.is_finite(), "a finite number (not nan or inf)")
}

/// A Poisson's ratio, in (-1, 0.5).
pub(super) fn poisson(path: &KeyPath, v: f64) -> CliResult<f64> {
    expect(
        path,
        v,
        v > -1.0 && v < 0.5,
        "a Poisson's ratio in (-1, 0.5)",
    )
}

/// Two finite numbers (the error names the index).
pub(super) fn finite2(path: &KeyPath, v: Pair) -> CliResult<[f64; 2]> {
    finite_all(path, v.0)
}

/// `D` finite numbers (the error names the index).
pub(super) fn finite_all<const D: usize>(path: &KeyPath, v: [f64; D]) -> CliResult<[f64; D]> {
    for (k, x) in v.iter().enumerate() {
        finite(&path.index(k), *x)?;
    }
    Ok(v)
}

pub(super) fn at_least(path: &KeyPath, v: usize, min: usize) -> CliResult<usize> {
    if v >= min {
        Ok(v)
    } else {
        bail!(path, "`{path}` = {v}: expected an integer >= {min}")
    }
}

/// `set!(p, spec, field = value, check)`: `spec.field = check(p.field, v)?` when the scene
/// gives `value = Some(v)`.
macro_rules! set {
    ($p:expr, $spec:expr, $field:ident = $v:expr, $check:expr) => {
        if let Some(v) = $v {
            $spec.$field = $check(&$p.key(stringify!($field)), v)?;
        }
    };
}

pub(super) use set;

/// An integer >= 1 (a count of cells, steps).
pub(super) fn count(path: &KeyPath, v: usize) -> CliResult<usize> {
    at_least(path, v, 1)
}

/// The generator's grading (a ratio must be > 0).
pub(super) fn grading(path: &KeyPath, g: GradingSpec) -> CliResult<Grading> {
    Ok(match g {
        GradingSpec::Uniform {} => Grading::Uniform,
        GradingSpec::Geometric { ratio } => Grading::Geometric {
            ratio: positive(&path.key("ratio"), ratio)?,
        },
        GradingSpec::BothEnds { ratio } => Grading::BothEnds {
            ratio: positive(&path.key("ratio"), ratio)?,
        },
    })
}

/// The element kind of a scene's element name.
pub(super) fn kind(e: Element) -> ElementKind {
    match e {
        Element::P1 => ElementKind::Tri3,
        Element::P2 => ElementKind::Tri6,
    }
}

/// The tetrahedron of a scene's element name (the box generator's).
pub(super) fn solid_kind(e: Element) -> ElementKind {
    match e {
        Element::P1 => ElementKind::Tet4,
        Element::P2 => ElementKind::Tet10,
    }
}

/// Name of an element kind (2D or 3D) for messages.
pub fn kind_name(k: ElementKind) -> &'static str {
    match k {
        ElementKind::Tri3 => "P1 (3-node triangles)",
        ElementKind::Tri6 => "P2 (6-node triangles)",
        ElementKind::Quad4 => "P1 (4-node quadrilaterals)",
        ElementKind::Quad8 => "P2 (8-node serendipity quadrilaterals)",
        ElementKind::Quad9 => "P2 (9-node Lagrange quadrilaterals)",
        ElementKind::Tet4 => "P1 (4-node tetrahedra)",
        ElementKind::Tet10 => "P2 (10-node tetrahedra)",
        ElementKind::Hex8 => "P1 (8-node hexahedra)",
        ElementKind::Hex20 => "P2 (20-node serendipity hexahedra)",
        _ => "elements of a kind this version of bipo does not name",
    }
}

/// A `FemError` at `path`, with a hint for a singular stiffness.
pub(super) fn fem(path: &KeyPath, e: FemError) -> CliError {
    let hint = match e {
        FemError::NotPositiveDefinite { .. } => {
            " — add supports so that the body cannot move as a rigid body"
        }
        _ => "",
    };
    err!(path, "{}{hint}", chain(&e))
}

/// A `LawError` at the key of the offending parameter under `path`.
pub(super) fn law_error(path: &KeyPath, e: LawError) -> CliError {
    match e {
        LawError::InvalidParameter {
            name,
            value,
            expected,
        } => {
            let p = path.key(name);
            err!(p, "`{p}` = {value:?}: expected {expected}")
        }
        LawError::InvalidExponent { m } => {
            let p = path.key("m");
            err!(p, "`{p}` = {m}: expected 1 or 2")
        }
        other => CliError::at(path, chain(&other)),
    }
}

/// A `SolverError` at `path` (a structure error as [`fem`] does).
pub(super) fn solver_error(path: &KeyPath, e: SolverError) -> CliError {
    match e {
        SolverError::Structure(f) => fem(path, f),
        other => CliError::at(path, chain(&other)),
    }
}

/// "`a`, `b`" (or "none").
pub(super) fn list_names<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let v: Vec<String> = names.map(|n| format!("`{n}`")).collect();
    if v.is_empty() {
        "none".into()
    } else {
        v.join(", ")
    }
}

/// "1, 2, 3".
pub(super) fn join(s: &BTreeSet<u32>) -> String {
    s.iter()
        .map(|r| r.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The nodes of a node set of the mesh, or an error naming the sets there are.
pub(super) fn node_set<const D: usize>(
    path: &KeyPath,
    mesh: &Mesh<D>,
    name: &str,
) -> CliResult<Vec<usize>>
where
    Dim<D>: Space,
{
    mesh.node_set(name).map(|s| s.to_vec()).map_err(|_| {
        err!(
            path,
            "`{path}` = \"{name}\": the mesh has no node set of that name (node sets: {})",
            list_names(mesh.node_set_names())
        )
    })
}
