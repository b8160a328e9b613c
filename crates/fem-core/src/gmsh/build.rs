//! A parsed `.msh` file made into a [`Mesh<D>`](Mesh), once for both dimensions: the elements of
//! the mesh's dimension (one kind per file, with the region of their entity), the nodes they
//! use (in tag order), the connectivity in our node order and orientation, and the lower
//! elements of physical groups made into sets. What differs per dimension is a [`Reader`]:
//! the element-type table, the reordering, and how the physical groups become sets.

use super::file::unsupported_type;
use crate::error::FemError;
use crate::mesh::{ElementKind, Mesh};
use crate::space::{Dim, Space};
use mshio::{ElementType, MshFile};
use std::collections::HashMap;

/// What the reader does per dimension.
pub(crate) struct Reader<const D: usize>
where
    Dim<D>: Space,
{
    /// The element types read, for the error on any other.
    pub(crate) read: &'static str,
    /// What the file lacks when it holds no element of the dimension.
    pub(crate) none: &'static str,
    /// An element's nodes (0-based, in Gmsh's order) in our order and orientation.
    pub(crate) orient: Orient<D>,
    /// Adds the sets of the physical groups (`lower`; node tags by `index`).
    pub(crate) sets: Sets<D>,
}

/// An element's nodes (0-based, Gmsh's order) in our order and orientation, given the nodes.
pub(crate) type Orient<const D: usize> = fn(ElementKind, Vec<usize>, &[[f64; D]]) -> Vec<usize>;

/// The physical groups' elements made into sets of the mesh.
pub(crate) type Sets<const D: usize> = fn(&mut Mesh<D>, &Groups) -> Result<(), FemError>;

/// The elements of the physical groups of lower dimension, and what naming them needs.
pub(crate) struct Groups<'a> {
    pub(crate) lower: &'a [Lower],
    /// The mesh's node of each node tag.
    pub(crate) index: &'a HashMap<u64, usize>,
    pub(crate) names: &'a Names,
    pub(crate) physical: &'a Physical,
    /// The file, for messages.
    pub(crate) origin: &'a str,
}

/// The shapes of the elements of physical groups.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Shape {
    Triangle,
    Quadrangle,
    Line,
    Point,
}

impl Shape {
    fn of(t: ElementType) -> Option<Self> {
        match t {
            ElementType::Tri3 | ElementType::Tri6 => Some(Shape::Triangle),
            ElementType::Qua4 | ElementType::Qua8 | ElementType::Qua9 => Some(Shape::Quadrangle),
            ElementType::Lin2 | ElementType::Lin3 => Some(Shape::Line),
            ElementType::Pnt => Some(Shape::Point),
            _ => None,
        }
    }

    /// The prefix of an unnamed group's name.
    pub(crate) fn prefix(self) -> &'static str {
        match self {
            Shape::Triangle | Shape::Quadrangle => "surface",
            Shape::Line => "curve",
            Shape::Point => "point",
        }
    }
}

/// An element of a physical group of lower dimension than the mesh.
pub(crate) struct Lower {
    pub(crate) shape: Shape,
    /// The entity `(dimension, tag)`.
    pub(crate) entity: (i32, i32),
    pub(crate) element_tag: u64,
    pub(crate) nodes: Vec<u64>,
}

impl Lower {
    /// The names of the element's physical groups: from `$PhysicalNames`, else
    /// `surface_<tag>`, `curve_<tag>` or `point_<tag>`.
    pub(crate) fn groups(&self, of: &Groups) -> Vec<String> {
        let dim = self.entity.0;
        let tags = of.physical.get(&self.entity).map_or(&[][..], Vec::as_slice);
        tags.iter()
            .map(|&p| {
                let name = of.names.get(&(dim, p)).cloned();
                name.unwrap_or_else(|| format!("{}_{p}", self.shape.prefix()))
            })
            .collect()
    }
}

/// The mesh kind of dimension `D` of a Gmsh element type, from the catalogue's
/// [`Topology`](crate::element::Topology).
fn kind_of<const D: usize>(t: ElementType) -> Option<ElementKind> {
    ElementKind::ALL
        .into_iter()
        .find(|k| k.dimension() == D && k.topology().gmsh_type == t as u32)
}

/// The mesh of a parsed file (see the [module docs](self)).
pub(crate) fn build<const D: usize>(
    file: MshFile<u64, i32, f64>,
    names: &Names,
    origin: &str,
    reader: &Reader<D>,
) -> Result<Mesh<D>, FemError>
where
    Dim<D>: Space,
{
    let io = |detail: String| FemError::invalid_file(origin, detail);
    let data = file.data;
    let physical = physical_tags(&data);
    let nodes_section = data
        .nodes
        .ok_or_else(|| io("no $Nodes section".to_string()))?;
    let coords = node_coordinates(&nodes_section, &io)?;
    let elements = data
        .elements
        .ok_or_else(|| io("no $Elements section".to_string()))?;
    check_elements(&nodes_section, &elements, &coords).map_err(io)?;

    // The elements of the dimension (with their region) and the lower ones of physical groups.
    let mut kind: Option<ElementKind> = None;
    let mut cells: Vec<&[u64]> = Vec::new();
    let mut cell_tags: Vec<u64> = Vec::new();
    let mut regions = Vec::new();
    let mut lower: Vec<Lower> = Vec::new();
    for block in &elements.element_blocks {
        let (dim, tag, t) = (block.entity_dim, block.entity_tag, block.element_type);
        if let Some(this) = kind_of::<D>(t) {
            let first = *kind.get_or_insert(this);
            let n = this.node_count();
            if first != this {
                let entity = if D == 2 { "surface" } else { "volume" };
                return Err(FemError::Unsupported {
                    what: format!(
                        "mixed {}-node and {n}-node elements ({first:?} and {this:?}) in \
                         {origin} ({entity} {tag} holds {n}-node ones): one kind per file",
                        first.node_count(),
                    ),
                });
            }
            let region = region_of(&physical, dim, tag, origin)?;
            for e in &block.elements {
                if e.nodes.len() != n {
                    let (tag, got) = (e.element_tag, e.nodes.len());
                    return Err(io(format!("element {tag} has {got} nodes, not {n}")));
                }
                cells.push(&e.nodes);
                cell_tags.push(e.element_tag);
                regions.push(region);
            }
            continue;
        }
        let Some(shape) = Shape::of(t) else {
            return Err(unsupported_type(t, dim, tag, reader.read));
        };
        if physical.get(&(dim, tag)).is_none_or(Vec::is_empty) {
            continue;
        }
        lower.extend(block.elements.iter().map(|e| Lower {
            shape,
            entity: (dim, tag),
            element_tag: e.element_tag,
            nodes: e.nodes.clone(),
        }));
    }
    let Some(kind) = kind else {
        let none = reader.none;
        return Err(FemError::Unsupported {
            what: format!(
                "{origin} holds no {none}; note that once physical groups exist Gmsh saves \
                 only their elements (add a physical {})",
                if D == 2 { "surface" } else { "volume" }
            ),
        });
    };

    // Keep the nodes of the elements, in tag order (every tag is defined: `check_elements`
    // has seen to it; a 2D mesh drops `z`).
    let mut used: Vec<u64> = cells.iter().flat_map(|t| t.iter().copied()).collect();
    used.sort_unstable();
    used.dedup();
    let index: HashMap<u64, usize> = used.iter().enumerate().map(|(i, &t)| (t, i)).collect();
    let nodes: Vec<[f64; D]> = used
        .iter()
        .map(|t| std::array::from_fn(|a| coords[t][a]))
        .collect();
    let mut connectivity = Vec::with_capacity(kind.node_count() * cells.len());
    for t in &cells {
        let cell = t.iter().map(|tag| index[tag]).collect();
        connectivity.extend((reader.orient)(kind, cell, &nodes));
    }
    let mut mesh = Mesh::new(nodes, kind, connectivity, regions)
        .map_err(|e| with_tags(e, &used, &cell_tags, origin))?;
    let groups = Groups {
        lower: &lower,
        index: &index,
        names,
        physical: &physical,
        origin,
    };
    (reader.sets)(&mut mesh, &groups)?;
    Ok(mesh)
}

/// The physical names (by `(dimension, tag)`) of a `.msh` file.
pub(crate) type Names = HashMap<(i32, i32), String>;

/// The physical tags of every entity `(dimension, tag)`.
pub(crate) type Physical = HashMap<(i32, i32), Vec<i32>>;

/// Physical tags by entity `(dimension, tag)`, for points, curves, surfaces and volumes.
fn physical_tags(data: &mshio::MshData<u64, i32, f64>) -> Physical {
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
fn region_of(physical: &Physical, dim: i32, tag: i32, origin: &str) -> Result<u32, FemError> {
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

/// Checks the `$Elements` section against the `$Nodes` one before anything is built: the
/// counts the headers announce against what the blocks hold, each element tag used once, and
/// every node tag of every element defined in `$Nodes`.
fn check_elements(
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

/// An error of [`Mesh::new`] on the nodes and elements
/// read from a file, told with the file's own node and element tags instead of the mesh's
/// 0-based indices.
fn with_tags(e: FemError, node_tags: &[u64], element_tags: &[u64], origin: &str) -> FemError {
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
fn node_coordinates(
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
