//! A parsed `.msh` file made into a [`Mesh<D>`](Mesh), once for both dimensions: the elements of
//! the mesh's dimension (one kind per file, with the region of their entity), the nodes they
//! use (in tag order), the connectivity in our node order and orientation, and the lower
//! elements of physical groups made into sets. What differs per dimension is a [`Reader`]:
//! the element-type table, the reordering, and how the physical groups become sets.

use super::{Names, Physical, check_elements, node_coordinates, region_of, unsupported_type};
use super::{physical_tags, with_tags};
use crate::error::FemError;
use crate::mesh::{Kind, Mesh};
use crate::space::{CellKind, Dim, Space};
use mshio::{ElementType, MshFile};
use std::collections::HashMap;

/// What the reader does per dimension.
pub(crate) struct Reader<const D: usize>
where
    Dim<D>: Space,
{
    /// The mesh kind of a Gmsh element type.
    pub(crate) kind_of: fn(ElementType) -> Option<Kind<D>>,
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
pub(crate) type Orient<const D: usize> = fn(Kind<D>, Vec<usize>, &[[f64; D]]) -> Vec<usize>;

/// The physical groups' elements made into sets of the mesh.
pub(crate) type Sets<const D: usize> = fn(
    &mut Mesh<D>,
    &[Lower],
    &HashMap<u64, usize>,
    &Names,
    &Physical,
    &str,
) -> Result<(), FemError>;

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
    pub(crate) fn groups(&self, names: &Names, physical: &Physical) -> Vec<String> {
        let dim = self.entity.0;
        let tags = physical.get(&self.entity).map_or(&[][..], Vec::as_slice);
        tags.iter()
            .map(|&p| {
                let name = names.get(&(dim, p)).cloned();
                name.unwrap_or_else(|| format!("{}_{p}", self.shape.prefix()))
            })
            .collect()
    }
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
    let mut kind: Option<Kind<D>> = None;
    let mut cells: Vec<&[u64]> = Vec::new();
    let mut cell_tags: Vec<u64> = Vec::new();
    let mut regions = Vec::new();
    let mut lower: Vec<Lower> = Vec::new();
    for block in &elements.element_blocks {
        let (dim, tag, t) = (block.entity_dim, block.entity_tag, block.element_type);
        if let Some(this) = (reader.kind_of)(t) {
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
    (reader.sets)(&mut mesh, &lower, &index, names, &physical, origin)?;
    Ok(mesh)
}
