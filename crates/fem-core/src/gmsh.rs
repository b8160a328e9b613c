//! Reading 2D triangle and quadrilateral meshes from Gmsh `.msh` files, format 4.1 (ASCII or
//! binary).
//!
//! The file is parsed by the [`mshio`] crate; this module turns it into a [`Mesh`]:
//!
//! - **Nodes.** Only the nodes used by triangles are kept, numbered `0..n` in increasing Gmsh
//!   tag order (an unused node would be a free, unloaded degree of freedom). The `z` coordinate
//!   is ignored: the mesh is projected onto the plane `z = 0`.
//! - **Triangles.** 3-node (Gmsh type 2) or 6-node (type 9) triangles, one kind per file.
//!   Clockwise triangles are reordered (corners 1 ↔ 2 and the mid-side nodes with them), so
//!   either orientation of the surface is accepted. The region of a triangle is the first
//!   physical tag of its surface entity, or 0 if it has none.
//! - **Quadrangles.** 4-node (type 3), 8-node (type 16) and 9-node (type 10) quadrangles, in
//!   the same node order as VTK's 9, 23 and 28; clockwise ones are reordered as triangles are.
//!   One element kind per file.
//! - **Physical curves** (dimension 1) become an edge set and a node set of the same name.
//!   Each line element (type 1 or 8) is matched to a triangle side by its two end nodes; where
//!   two triangles share that side (an interior curve), the one to the left of the line's
//!   direction is taken. The node set holds all the nodes of those sides, mid-side nodes
//!   included, **ordered along the curve** by chaining its sides ([`Mesh::add_curve_node_set`]:
//!   mid-side nodes between their corners, the body on the right so that the outward normal is
//!   on the left, a closed curve from its lowest node without repeating it), whatever order
//!   Gmsh numbers the nodes and lists the lines in. A curve that branches or is made of
//!   disjoint pieces keeps its nodes sorted, and [`Mesh::curve_order`] says why (a contact
//!   target refuses it).
//! - **Physical points** (dimension 0) become node sets (from the point elements, type 15).
//! - **Names** come from `$PhysicalNames`; an unnamed group is called `curve_<tag>` or
//!   `point_<tag>`. A curve group and a point group of the same name share one node set
//!   (sorted by index, as it is no longer one curve).
//!
//! Lines and points outside physical groups are ignored. Any other element type (tetrahedra, higher orders, …) is [`FemError::Unsupported`]; tetrahedral volume meshes are
//! read by [`crate::solid::gmsh`].

mod build;

use crate::error::FemError;
use crate::mesh::{ElementKind, Mesh, Side};
pub(crate) use build::{Lower, Reader, Shape, build};
use mshio::error::MshParserErrorKind;
use mshio::{ElementType, MshFile, MshParserError};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// Reads a Gmsh `.msh` 4.1 file holding a 2D triangle mesh (see the [module docs](self)).
///
/// # Errors
/// - [`FemError::Io`] if the file cannot be read or is not valid MSH 4.1 (with the line of
///   the first error where it is known);
/// - [`FemError::Unsupported`] for another format version, an element type other than
///   triangles, quadrangles, lines and points, mixed element kinds, a line in a physical
///   group that is not a triangle side, or a negative physical tag;
/// - the errors of [`Mesh::new`] (e.g. a degenerate triangle).
///
/// # Examples
/// ```no_run
/// let mesh = fem_core::gmsh::read_msh(std::path::Path::new("block.msh")).unwrap();
/// println!("{} triangles", mesh.element_count());
/// ```
pub fn read_msh(path: &Path) -> Result<Mesh, FemError> {
    let origin = path.display().to_string();
    let bytes =
        std::fs::read(path).map_err(|e| FemError::io(origin.clone(), "cannot read the file", e))?;
    parse(&bytes, &origin)
}

/// Parses the bytes of a Gmsh `.msh` 4.1 file (see [`read_msh`]). Errors about the data name
/// the file as `<msh>`.
///
/// # Errors
/// As [`read_msh`].
///
/// # Examples
/// ```
/// let msh = "$MeshFormat\n4.1 0 8\n$EndMeshFormat
/// $Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes
/// $Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n";
/// let mesh = fem_core::gmsh::parse_msh(msh.as_bytes()).unwrap();
/// assert_eq!(mesh.element_count(), 1);
/// assert_eq!(mesh.regions(), &[0]);
/// ```
pub fn parse_msh(bytes: &[u8]) -> Result<Mesh, FemError> {
    parse(bytes, "<msh>")
}

fn parse(bytes: &[u8], origin: &str) -> Result<Mesh, FemError> {
    let (file, names) = parse_file(bytes, origin)?;
    build(file, &names, origin, &PLANE)
}

/// The physical names (by `(dimension, tag)`) of a `.msh` file.
pub(crate) type Names = HashMap<(i32, i32), String>;

/// The physical tags of every entity `(dimension, tag)`.
pub(crate) type Physical = HashMap<(i32, i32), Vec<i32>>;

/// Parses a `.msh` 4.1 file with `mshio`, behind the checks that guard it (header, node
/// tags, a panic inside the parser), and reads its `$PhysicalNames`. Shared with the 3D
/// reader, [`crate::solid::gmsh`].
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

/// The `$PhysicalNames` section (ASCII in both file types), by `(dimension, tag)`.
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

/// Physical tags by entity `(dimension, tag)`, for points, curves, surfaces and volumes.
pub(crate) fn physical_tags(data: &mshio::MshData<u64, i32, f64>) -> Physical {
    let mut physical = HashMap::new();
    if let Some(entities) = &data.entities {
        for p in &entities.points {
            physical.insert((0, p.tag), p.physical_tags.clone());
        }
        for c in &entities.curves {
            physical.insert((1, c.tag), c.physical_tags.clone());
        }
        for s in &entities.surfaces {
            physical.insert((2, s.tag), s.physical_tags.clone());
        }
        for v in &entities.volumes {
            physical.insert((3, v.tag), v.physical_tags.clone());
        }
    }
    physical
}

/// The region of the elements of entity `(dim, tag)`: its first physical tag, or 0.
///
/// # Errors
/// [`FemError::Unsupported`] for a negative physical tag.
pub(crate) fn region_of(
    physical: &Physical,
    dim: i32,
    tag: i32,
    origin: &str,
) -> Result<u32, FemError> {
    let entity = ["point", "curve", "surface", "volume"]
        .get(dim as usize)
        .unwrap_or(&"entity");
    match physical.get(&(dim, tag)).and_then(|p| p.first()) {
        None => Ok(0),
        Some(&p) => u32::try_from(p).map_err(|_| FemError::Unsupported {
            what: format!("negative physical tag {p} on {entity} {tag} in {origin}"),
        }),
    }
}

/// The 2D reader's tables.
const PLANE: Reader<2> = Reader {
    kind_of,
    read: "triangles (types 2, 9), quadrangles (3, 16, 10), lines (1, 8) and points (15) \
           (volume meshes: `solid::gmsh`)",
    none: "triangles or quadrangles (Gmsh types 2, 9, 3, 16, 10)",
    orient,
    sets: add_physical_sets,
};

/// A 2D element counter-clockwise: the shoelace area of the corners; a clockwise element is
/// mirrored: triangles 1 ↔ 2 (mid-sides 3 ↔ 5), quadrangles 1 ↔ 3 (mid-sides 4 ↔ 7, 5 ↔ 6;
/// the centre stays).
fn orient(kind: ElementKind, mut cell: Vec<usize>, nodes: &[[f64; 2]]) -> Vec<usize> {
    let nc = kind.corner_count();
    let area: f64 = (0..nc)
        .map(|k| {
            let (p, q) = (nodes[cell[k]], nodes[cell[(k + 1) % nc]]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum();
    if area < 0.0 {
        let swaps: &[(usize, usize)] = match (nc, kind.is_quadratic()) {
            (3, false) => &[(1, 2)],
            (3, true) => &[(1, 2), (3, 5)],
            (_, false) => &[(1, 3)],
            (_, true) => &[(1, 3), (4, 7), (5, 6)],
        };
        swaps.iter().for_each(|&(a, b)| cell.swap(a, b));
    }
    cell
}

/// The physical curves and points as edge and node sets of `mesh`: line elements matched to
/// triangle sides (directed corner pairs), point elements to nodes; named by `names` or
/// `curve_N` / `point_N`.
fn add_physical_sets(
    mesh: &mut Mesh,
    lower: &[Lower],
    index: &HashMap<u64, usize>,
    names: &Names,
    physical: &Physical,
    origin: &str,
) -> Result<(), FemError> {
    let of = |shape: Shape| lower.iter().filter(move |l| l.shape == shape);
    // Physical curves: match lines to triangle sides (directed corner pairs).
    let mut sides: HashMap<(usize, usize), Side> = HashMap::new();
    for side in mesh.all_facets() {
        let mut it = mesh.side_nodes(side);
        if let (Some(a), Some(b)) = (it.next(), it.next()) {
            sides.insert((a, b), side);
        }
    }
    let mut edge_sets: BTreeMap<String, Vec<Side>> = BTreeMap::new();
    for line in of(Shape::Line) {
        let side = match_side(mesh, &sides, index, line).ok_or_else(|| FemError::Unsupported {
            what: format!(
                "a line element of curve {} (nodes {:?}) in {origin} is not a triangle side",
                line.entity.1, line.nodes
            ),
        })?;
        for name in line.groups(names, physical) {
            let set = edge_sets.entry(name).or_default();
            if !set.contains(&side) {
                set.push(side);
            }
        }
    }
    let curves: Vec<String> = edge_sets.keys().cloned().collect();
    for (name, set) in edge_sets {
        mesh.add_edge_set(&name, set)?;
    }
    let mut node_sets: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for point in of(Shape::Point) {
        let node = point
            .nodes
            .first()
            .and_then(|t| index.get(t))
            .copied()
            .ok_or_else(|| FemError::Unsupported {
                what: format!(
                    "physical point entity {} (nodes {:?}) in {origin} is not a node of a triangle",
                    point.entity.1, point.nodes
                ),
            })?;
        for name in point.groups(names, physical) {
            node_sets.entry(name).or_default().push(node);
        }
    }
    for name in &curves {
        match node_sets.remove(name) {
            // a point group of the same name: one sorted set of both
            Some(points) => {
                let mut all = mesh.facet_set_nodes(name)?;
                all.extend(points);
                mesh.add_node_set(name, all)?;
            }
            None => {
                mesh.add_curve_node_set(name)?;
            }
        }
    }
    for (name, set) in node_sets {
        mesh.add_node_set(&name, set)?;
    }
    Ok(())
}

/// Checks the `$Elements` section against the `$Nodes` one before anything is built: the
/// counts the headers announce against what the blocks hold, each element tag used once, and
/// every node tag of every element defined in `$Nodes`.
pub(crate) fn check_elements(
    nodes_section: &mshio::Nodes<u64, i32, f64>,
    elements: &mshio::Elements<u64, i32>,
    coords: &HashMap<u64, [f64; 3]>,
) -> Result<(), String> {
    if nodes_section.num_nodes != coords.len() as u64 {
        return Err(format!(
            "the $Nodes header announces {} nodes, but its blocks define {}",
            nodes_section.num_nodes,
            coords.len()
        ));
    }
    let held: usize = elements
        .element_blocks
        .iter()
        .map(|b| b.elements.len())
        .sum();
    if elements.num_elements != held as u64 {
        return Err(format!(
            "the $Elements header announces {} elements, but its blocks hold {held}",
            elements.num_elements
        ));
    }
    let mut seen = std::collections::HashSet::new();
    for e in elements.element_blocks.iter().flat_map(|b| &b.elements) {
        if !seen.insert(e.element_tag) {
            return Err(format!("element tag {} is used twice", e.element_tag));
        }
        if let Some(t) = e.nodes.iter().find(|t| !coords.contains_key(t)) {
            return Err(format!(
                "element {} refers to node tag {t}, which $Nodes never defines",
                e.element_tag
            ));
        }
    }
    Ok(())
}

/// An error of [`Mesh::new`] (or [`crate::solid::SolidMesh::new`]) on the nodes and elements
/// read from a file, told with the file's own node and element tags instead of the mesh's
/// 0-based indices.
pub(crate) fn with_tags(
    e: FemError,
    node_tags: &[u64],
    element_tags: &[u64],
    origin: &str,
) -> FemError {
    let node = |i: usize| node_tags.get(i).copied().unwrap_or(i as u64);
    let element = |i: usize| element_tags.get(i).copied().unwrap_or(i as u64);
    let detail = match e {
        FemError::NonFiniteNode { node: n, x, y } => {
            format!(
                "node {} has a non-finite coordinate ({x:?}, {y:?})",
                node(n)
            )
        }
        FemError::NonFiniteNode3 { node: n, coords } => {
            format!("node {} has a non-finite coordinate {coords:?}", node(n))
        }
        FemError::DegenerateElement { element: k, area } => {
            format!("element {} is degenerate: signed area {area:e}", element(k))
        }
        FemError::DegenerateSolid { element: k, volume } => {
            format!("element {} is degenerate: volume {volume:e}", element(k))
        }
        FemError::InvertedElement { element: k, det_j } => format!(
            "element {} is inverted: Jacobian determinant {det_j:e} at a quadrature point",
            element(k)
        ),
        other => return other,
    };
    FemError::invalid_file(origin, detail)
}

/// Node coordinates `(x, y, z)` by tag. Sparse blocks carry their tags; for contiguous tags `mshio` keeps
/// none, and they run from the minimum tag in file order (as Gmsh writes them).
///
/// # Errors
/// A tag defined twice, in two blocks or within one (where `mshio`'s map of tags would keep
/// only one of them).
pub(crate) fn node_coordinates(
    nodes_section: &mshio::Nodes<u64, i32, f64>,
    io: &dyn Fn(String) -> FemError,
) -> Result<HashMap<u64, [f64; 3]>, FemError> {
    let mut coords: HashMap<u64, [f64; 3]> = HashMap::new();
    let mut next_tag = nodes_section.min_node_tag;
    for block in &nodes_section.node_blocks {
        let tagged: Vec<(u64, usize)> = match &block.node_tags {
            Some(map) => {
                if map.len() != block.nodes.len() {
                    return Err(io(format!(
                        "a $Nodes block of entity {} lists {} nodes but only {} distinct tags: \
                         a node tag is repeated",
                        block.entity_tag,
                        block.nodes.len(),
                        map.len()
                    )));
                }
                map.iter().map(|(&tag, &i)| (tag, i)).collect()
            }
            None => (0..block.nodes.len())
                .map(|i| (next_tag + i as u64, i))
                .collect(),
        };
        next_tag += block.nodes.len() as u64;
        for (tag, i) in tagged {
            let n = &block.nodes[i];
            if coords.insert(tag, [n.x, n.y, n.z]).is_some() {
                return Err(io(format!("node tag {tag} is defined twice")));
            }
        }
    }
    Ok(coords)
}

/// The mesh kind of a Gmsh element type, from the catalogue's [`crate::element::Topology`].
fn kind_of(t: ElementType) -> Option<ElementKind> {
    ElementKind::ALL
        .into_iter()
        .find(|k| k.element().topology().gmsh_type == t as u32)
}

/// The triangle side of a line element: to the left of the line if two triangles share it.
/// For a 3-node line in a P2 mesh the middle node must be the side's.
fn match_side(
    mesh: &Mesh,
    sides: &HashMap<(usize, usize), Side>,
    index: &HashMap<u64, usize>,
    line: &Lower,
) -> Option<Side> {
    let a = *index.get(line.nodes.first()?)?;
    let b = *index.get(line.nodes.get(1)?)?;
    let side = sides.get(&(a, b)).or_else(|| sides.get(&(b, a))).copied()?;
    match (line.nodes.get(2), mesh.kind().is_quadratic()) {
        (Some(mid), true) => {
            let m = *index.get(mid)?;
            (mesh.side_nodes(side).nth(2) == Some(m)).then_some(side)
        }
        _ => Some(side),
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
