//! Meshes of 3-node (P1) and 6-node (P2) triangles, with regions, node sets and edge sets.

pub mod curve;

use crate::element::{Element, Quad4, Quad8, Quad9, Tri3, Tri6};
use crate::error::FemError;
use curve::{CurveOrder, chain_sides};
use std::collections::BTreeMap;

/// The element family of a mesh.
///
/// Node order (Gmsh's and VTK's): triangles have corners `0, 1, 2` counter-clockwise, then for
/// P2 the mid-edge nodes `3` (edge 0–1), `4` (edge 1–2), `5` (edge 2–0); quadrilaterals have
/// corners `0..4` counter-clockwise, then for Quad8/Quad9 the mid-side nodes `4` (0–1),
/// `5` (1–2), `6` (2–3), `7` (3–0), and for Quad9 the centre `8`. The element of each kind is
/// [`ElementKind::element`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ElementKind {
    /// Linear 3-node triangle.
    Tri3,
    /// Quadratic 6-node isoparametric triangle.
    Tri6,
    /// Bilinear 4-node quadrilateral.
    Quad4,
    /// Quadratic 8-node serendipity quadrilateral.
    Quad8,
    /// Biquadratic 9-node Lagrange quadrilateral.
    Quad9,
}

impl ElementKind {
    /// Every kind, for tests and messages.
    pub const ALL: [ElementKind; 5] = [
        ElementKind::Tri3,
        ElementKind::Tri6,
        ElementKind::Quad4,
        ElementKind::Quad8,
        ElementKind::Quad9,
    ];

    /// The built-in element of this kind.
    #[inline]
    pub fn element(self) -> &'static dyn Element<2> {
        match self {
            ElementKind::Tri3 => &Tri3,
            ElementKind::Tri6 => &Tri6,
            ElementKind::Quad4 => &Quad4,
            ElementKind::Quad8 => &Quad8,
            ElementKind::Quad9 => &Quad9,
        }
    }

    /// Nodes per element: 3, 6, 4, 8 or 9.
    #[inline]
    pub fn node_count(self) -> usize {
        match self {
            ElementKind::Tri3 => 3,
            ElementKind::Tri6 => 6,
            ElementKind::Quad4 => 4,
            ElementKind::Quad8 => 8,
            ElementKind::Quad9 => 9,
        }
    }

    /// Corners per element: 3 or 4.
    #[inline]
    pub fn corner_count(self) -> usize {
        self.side_count()
    }

    /// Sides per element: 3 (triangles) or 4 (quadrilaterals).
    #[inline]
    pub fn side_count(self) -> usize {
        match self {
            ElementKind::Tri3 | ElementKind::Tri6 => 3,
            _ => 4,
        }
    }

    /// Whether the sides carry a mid-side node (3-node sides).
    #[inline]
    pub fn is_quadratic(self) -> bool {
        matches!(
            self,
            ElementKind::Tri6 | ElementKind::Quad8 | ElementKind::Quad9
        )
    }

    /// The local nodes of side `side ∈ 0..side_count()`, from its first corner to its second
    /// (the body on its left), with the mid-side node last for quadratic kinds (`[a, b]` or
    /// `[a, b, m]`).
    ///
    /// # Panics
    /// If `side >= self.side_count()`.
    #[inline]
    #[track_caller]
    pub fn side_nodes(self, side: usize) -> &'static [usize] {
        match self {
            ElementKind::Tri3 => crate::element::tri3::SIDES[side],
            ElementKind::Tri6 => crate::element::tri6::SIDES[side],
            ElementKind::Quad4 => crate::element::quad4::SIDES[side],
            ElementKind::Quad8 | ElementKind::Quad9 => crate::element::quad8::SIDES[side],
        }
    }
}

/// A side of an element: element index and local side `0, 1, 2` (see
/// [`ElementKind::side_nodes`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Side {
    /// Element index.
    pub element: usize,
    /// Local side index in `0..side_count()` of the element's kind.
    pub side: u8,
}

/// A triangle mesh: node coordinates, connectivity, region ids, named node sets and named
/// edge sets.
///
/// Coordinates are `(x, y)`, or `(r, z)` in axisymmetry. Built with [`Mesh::new`], which checks
/// indices, finiteness and orientation (corner area > 0), so every `Mesh` is valid.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    nodes: Vec<[f64; 2]>,
    kind: ElementKind,
    connectivity: Vec<usize>,
    regions: Vec<u32>,
    node_sets: BTreeMap<String, Vec<usize>>,
    edge_sets: BTreeMap<String, Vec<Side>>,
    /// How the node sets made by [`Mesh::add_curve_node_set`] are ordered.
    curves: BTreeMap<String, CurveOrder>,
}

impl Mesh {
    /// Builds and validates a mesh. `connectivity` is flat, `kind.node_count()` entries per
    /// element; `regions` has one id per element (empty means all in region 0).
    ///
    /// # Errors
    /// - [`FemError::NonFiniteNode`] for a NaN or infinite coordinate;
    /// - [`FemError::EmptyMesh`] for a connectivity without a single element;
    /// - [`FemError::BadConnectivity`], [`FemError::NodeOutOfRange`],
    ///   [`FemError::LengthMismatch`] (regions) for inconsistent arrays;
    /// - [`FemError::DegenerateElement`] (area below `1e-12` of the squared longest side) and
    ///   [`FemError::InvertedElement`] (clockwise corners) with the element index.
    pub fn new(
        nodes: Vec<[f64; 2]>,
        kind: ElementKind,
        connectivity: Vec<usize>,
        regions: Vec<u32>,
    ) -> Result<Self, FemError> {
        for (node, p) in nodes.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(FemError::NonFiniteNode {
                    node,
                    x: p[0],
                    y: p[1],
                });
            }
        }
        let npe = kind.node_count();
        let regions = checked_cells(nodes.len(), npe, &connectivity, regions)?;
        for (element, cell) in connectivity.chunks_exact(npe).enumerate() {
            check_corners(element, &nodes, &cell[..kind.corner_count()])?;
        }
        Ok(Self {
            nodes,
            kind,
            connectivity,
            regions,
            node_sets: BTreeMap::new(),
            edge_sets: BTreeMap::new(),
            curves: BTreeMap::new(),
        })
    }

    /// Adds (or replaces) a named node set.
    ///
    /// # Errors
    /// [`FemError::UnknownNode`] for an unknown node.
    pub fn add_node_set(&mut self, name: &str, nodes: Vec<usize>) -> Result<(), FemError> {
        let nodes = checked_node_set(self.nodes.len(), nodes)?;
        self.node_sets.insert(name.to_string(), nodes);
        self.curves.remove(name);
        Ok(())
    }

    /// Adds (or replaces) the node set of the edge set `name`, ordered along the curve its
    /// sides make ([`chain_sides`]: mid-side nodes between their corners, the outward normal
    /// on the left, a closed curve's first node not repeated); a set that is not one curve
    /// (branches, disjoint pieces) is sorted by index instead. Returns, and records for
    /// [`Mesh::curve_order`], which it is. The Gmsh reader makes the node sets of physical
    /// curves this way; the generators keep their sets sorted (along their straight lines).
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] if there is no edge set of that name.
    ///
    /// # Examples
    /// ```
    /// use fem_core::curve::CurveOrder;
    /// use fem_core::generate::{RectangleSpec, rectangle};
    /// let mut mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 2, 1))?;
    /// assert_eq!(mesh.add_curve_node_set("top")?, CurveOrder::Open);
    /// assert_eq!(mesh.node_set("top")?, &[3, 4, 5]); // left to right: the body below
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    pub fn add_curve_node_set(&mut self, name: &str) -> Result<CurveOrder, FemError> {
        let (nodes, order) = match chain_sides(self, self.edge_set(name)?) {
            Ok(c) if c.closed => (c.nodes, CurveOrder::Closed),
            Ok(c) => (c.nodes, CurveOrder::Open),
            Err(why) => (self.edge_set_nodes(name)?, CurveOrder::NotACurve(why)),
        };
        self.node_sets.insert(name.to_string(), nodes);
        self.curves.insert(name.to_string(), order.clone());
        Ok(order)
    }

    /// How the node set `name` is ordered when it was made from a curve
    /// ([`Mesh::add_curve_node_set`]), `None` for other sets (sorted by index).
    pub fn curve_order(&self, name: &str) -> Option<&CurveOrder> {
        self.curves.get(name)
    }

    /// Adds (or replaces) a named edge set.
    ///
    /// # Errors
    /// [`FemError::InvalidSide`] for a side whose element or local index is out of range.
    pub fn add_edge_set(&mut self, name: &str, sides: Vec<Side>) -> Result<(), FemError> {
        if let Some(s) = sides.iter().find(|s| {
            s.element >= self.element_count() || s.side as usize >= self.kind.side_count()
        }) {
            return Err(FemError::InvalidSide {
                element: s.element,
                side: s.side,
                element_count: self.element_count(),
            });
        }
        self.edge_sets.insert(name.to_string(), sides);
        Ok(())
    }

    /// Joins meshes into one with several bodies (e.g. two cylinders in contact): nodes,
    /// elements and regions in the order given, each part's node and edge sets renamed
    /// `"{prefix}{name}"` with the part's prefix. The parts stay unconnected (no node is
    /// merged); contact zones or ties join them.
    ///
    /// # Errors
    /// [`FemError::Unsupported`] for an empty list, parts of different element kinds, or two
    /// sets that end up with the same name.
    ///
    /// # Examples
    /// ```
    /// use fem_core::Mesh;
    /// use fem_core::generate::{RectangleSpec, rectangle};
    /// let low = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2))?;
    /// let up = rectangle(&RectangleSpec::new([0.0, 1.0], [1.0, 2.0], 2, 2))?;
    /// let both = Mesh::join(&[("low.", &low), ("up.", &up)])?;
    /// assert_eq!(both.node_count(), 18);
    /// assert_eq!(both.node_set("up.bottom")?[0], 9); // the second part's nodes come after
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    pub fn join(parts: &[(&str, &Mesh)]) -> Result<Self, FemError> {
        let Some((_, first)) = parts.first() else {
            return Err(FemError::Unsupported {
                what: "joining an empty list of meshes".into(),
            });
        };
        let kind = first.kind;
        let mut out = Self {
            nodes: Vec::new(),
            kind,
            connectivity: Vec::new(),
            regions: Vec::new(),
            node_sets: BTreeMap::new(),
            edge_sets: BTreeMap::new(),
            curves: BTreeMap::new(),
        };
        for (prefix, part) in parts {
            if part.kind != kind {
                return Err(FemError::Unsupported {
                    what: format!(
                        "joining meshes of different element kinds ({:?} and {:?}, part `{prefix}`)",
                        kind, part.kind
                    ),
                });
            }
            let (node_off, elem_off) = (out.nodes.len(), out.element_count());
            out.nodes.extend_from_slice(&part.nodes);
            out.connectivity
                .extend(part.connectivity.iter().map(|n| n + node_off));
            out.regions.extend_from_slice(&part.regions);
            let clash = |name: &str| FemError::Unsupported {
                what: format!(
                    "joining meshes: two sets are named `{name}`; give the parts other prefixes"
                ),
            };
            for (name, nodes) in &part.node_sets {
                let name = format!("{prefix}{name}");
                if out.node_sets.contains_key(&name) {
                    return Err(clash(&name));
                }
                out.node_sets
                    .insert(name, nodes.iter().map(|n| n + node_off).collect());
            }
            for (name, order) in &part.curves {
                out.curves.insert(format!("{prefix}{name}"), order.clone());
            }
            for (name, sides) in &part.edge_sets {
                let name = format!("{prefix}{name}");
                if out.edge_sets.contains_key(&name) {
                    return Err(clash(&name));
                }
                let sides = sides
                    .iter()
                    .map(|s| Side {
                        element: s.element + elem_off,
                        side: s.side,
                    })
                    .collect();
                out.edge_sets.insert(name, sides);
            }
        }
        Ok(out)
    }

    /// The element family.
    #[inline]
    pub fn kind(&self) -> ElementKind {
        self.kind
    }

    /// Number of nodes.
    #[inline]
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Number of elements.
    #[inline]
    pub fn element_count(&self) -> usize {
        self.connectivity.len() / self.kind.node_count()
    }

    /// Node coordinates.
    #[inline]
    pub fn nodes(&self) -> &[[f64; 2]] {
        &self.nodes
    }

    /// The nodes of element `e`.
    ///
    /// # Panics
    /// If `e >= element_count()`.
    #[inline]
    #[track_caller]
    pub fn element(&self, e: usize) -> &[usize] {
        let npe = self.kind.node_count();
        &self.connectivity[e * npe..(e + 1) * npe]
    }

    /// The flat connectivity array.
    #[inline]
    pub fn connectivity(&self) -> &[usize] {
        &self.connectivity
    }

    /// Region id of every element.
    #[inline]
    pub fn regions(&self) -> &[u32] {
        &self.regions
    }

    /// A named node set.
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] if there is none of that name.
    pub fn node_set(&self, name: &str) -> Result<&[usize], FemError> {
        self.node_sets
            .get(name)
            .map(Vec::as_slice)
            .ok_or_else(|| FemError::UnknownSet {
                kind: "node",
                name: name.to_string(),
            })
    }

    /// A named edge set.
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] if there is none of that name.
    pub fn edge_set(&self, name: &str) -> Result<&[Side], FemError> {
        self.edge_sets
            .get(name)
            .map(Vec::as_slice)
            .ok_or_else(|| FemError::UnknownSet {
                kind: "edge",
                name: name.to_string(),
            })
    }

    /// Names of the node sets.
    pub fn node_set_names(&self) -> impl Iterator<Item = &str> {
        self.node_sets.keys().map(String::as_str)
    }

    /// Names of the edge sets.
    pub fn edge_set_names(&self) -> impl Iterator<Item = &str> {
        self.edge_sets.keys().map(String::as_str)
    }

    /// The global nodes of a side, from its first corner to its second, mid-side node last.
    #[inline]
    pub fn side_nodes(&self, side: Side) -> impl Iterator<Item = usize> + '_ {
        let cell = self.element(side.element);
        self.kind
            .side_nodes(side.side as usize)
            .iter()
            .map(move |&l| cell[l])
    }

    /// The sides that belong to one element only (the boundary of the body, holes included),
    /// sorted.
    pub fn boundary_sides(&self) -> Vec<Side> {
        let mut count: BTreeMap<[usize; 2], (usize, Side)> = BTreeMap::new();
        for element in 0..self.element_count() {
            let cell = self.element(element);
            for side in 0..self.kind.side_count() as u8 {
                let local = self.kind.side_nodes(side as usize);
                let (a, b) = (cell[local[0]], cell[local[1]]);
                count
                    .entry([a.min(b), a.max(b)])
                    .or_insert((0, Side { element, side }))
                    .0 += 1;
            }
        }
        let mut sides: Vec<Side> = count
            .into_values()
            .filter_map(|(n, side)| (n == 1).then_some(side))
            .collect();
        sides.sort_unstable();
        sides
    }

    /// The unit outward normal of the boundary at every node (`None` inside the body): the
    /// sum of the outward normals `(Δy, −Δx)` of the boundary sides through the node (elements
    /// are counter-clockwise, so the body lies left of each side), weighted by their lengths,
    /// normalised. At a corner it bisects the two faces.
    pub fn outward_normals(&self) -> Vec<Option<[f64; 2]>> {
        let mut sum = vec![[0.0_f64; 2]; self.node_count()];
        let mut on_boundary = vec![false; self.node_count()];
        for side in self.boundary_sides() {
            let nodes: Vec<usize> = self.side_nodes(side).collect();
            let (a, b) = (self.nodes[nodes[0]], self.nodes[nodes[1]]);
            let n = [b[1] - a[1], a[0] - b[0]];
            for &node in &nodes {
                sum[node][0] += n[0];
                sum[node][1] += n[1];
                on_boundary[node] = true;
            }
        }
        sum.iter()
            .zip(on_boundary)
            .map(|(s, on)| {
                let len = s[0].hypot(s[1]);
                (on && len > 0.0 && len.is_finite()).then(|| [s[0] / len, s[1] / len])
            })
            .collect()
    }

    /// Nodes of the sides of an edge set (sorted by index, without duplicates; see
    /// [`Mesh::add_curve_node_set`] for the order along the curve).
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] if there is no edge set of that name.
    pub fn edge_set_nodes(&self, name: &str) -> Result<Vec<usize>, FemError> {
        let mut nodes: Vec<usize> = self
            .edge_set(name)?
            .iter()
            .flat_map(|&s| self.side_nodes(s))
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        Ok(nodes)
    }
}

/// Checks the corners of one element: finite products, not degenerate, counter-clockwise. A
/// triangle's area is tested; a quadrilateral is tested at each corner (the triangle of the
/// corner and its two neighbours), which accepts exactly the strictly convex quadrilaterals —
/// those whose bilinear map has a positive Jacobian everywhere.
fn check_corners(element: usize, nodes: &[[f64; 2]], cell: &[usize]) -> Result<(), FemError> {
    let c = cell.len();
    let corner_triangles = if c == 3 { 1 } else { c };
    let (mut area, mut l2) = (f64::INFINITY, 0.0_f64);
    for k in 0..corner_triangles {
        // for a triangle: (0, 1, 2); for a quadrilateral: (k, k + 1, k − 1)
        let [a, b, cc] = if c == 3 {
            [nodes[cell[0]], nodes[cell[1]], nodes[cell[2]]]
        } else {
            [
                nodes[cell[k]],
                nodes[cell[(k + 1) % c]],
                nodes[cell[(k + c - 1) % c]],
            ]
        };
        let ak = 0.5 * ((b[0] - a[0]) * (cc[1] - a[1]) - (cc[0] - a[0]) * (b[1] - a[1]));
        let lk = [(a, b), (b, cc), (cc, a)]
            .iter()
            .map(|(p, q)| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2))
            .fold(0.0, f64::max);
        if !(ak.is_finite() && lk.is_finite()) {
            // the coordinates are finite, but their products overflow
            let value = cell
                .iter()
                .flat_map(|&n| nodes[n].iter())
                .fold(0.0_f64, |m, v| m.max(v.abs()));
            return Err(FemError::InvalidParameter {
                name: "node coordinates",
                value,
                expected: "magnitudes whose products stay finite (below about 1e150)",
            });
        }
        area = area.min(ak);
        l2 = l2.max(lk);
    }
    if area.abs() <= 1e-12 * l2 || l2 == 0.0 {
        return Err(FemError::DegenerateElement { element, area });
    }
    if area < 0.0 {
        return Err(FemError::InvertedElement {
            element,
            det_j: 2.0 * area,
        });
    }
    Ok(())
}

/// Checks a flat connectivity of `npe` nodes per element against `node_count` nodes and returns
/// the region of every element (`regions` empty: all in region 0).
pub(crate) fn checked_cells(
    node_count: usize,
    npe: usize,
    connectivity: &[usize],
    regions: Vec<u32>,
) -> Result<Vec<u32>, FemError> {
    if !connectivity.len().is_multiple_of(npe) {
        return Err(FemError::BadConnectivity {
            len: connectivity.len(),
            nodes_per_element: npe,
        });
    }
    let n_elem = connectivity.len() / npe;
    if n_elem == 0 {
        return Err(FemError::EmptyMesh { node_count });
    }
    let regions = if regions.is_empty() {
        vec![0; n_elem]
    } else if regions.len() != n_elem {
        return Err(FemError::LengthMismatch {
            what: "regions",
            expected: n_elem,
            got: regions.len(),
        });
    } else {
        regions
    };
    for (element, cell) in connectivity.chunks_exact(npe).enumerate() {
        if let Some(&node) = cell.iter().find(|&&n| n >= node_count) {
            return Err(FemError::NodeOutOfRange {
                element,
                node,
                node_count,
            });
        }
    }
    Ok(regions)
}

/// A node set checked against `node_count` nodes, sorted, without repeats.
pub(crate) fn checked_node_set(
    node_count: usize,
    mut nodes: Vec<usize>,
) -> Result<Vec<usize>, FemError> {
    if let Some(&node) = nodes.iter().find(|&&n| n >= node_count) {
        return Err(FemError::UnknownNode {
            what: "a node set",
            node,
            node_count,
        });
    }
    nodes.sort_unstable();
    nodes.dedup();
    Ok(nodes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Vec<[f64; 2]> {
        vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    }

    #[test]
    fn boundary_sides_and_outward_normals_work() {
        // a square of two triangles plus a centre node: 4 triangles around (0.5, 0.5)
        let mut nodes = square();
        nodes.push([0.5, 0.5]);
        let m = Mesh::new(
            nodes,
            ElementKind::Tri3,
            vec![0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4],
            vec![],
        )
        .unwrap();
        assert_eq!(m.boundary_sides().len(), 4);
        let n = m.outward_normals();
        let h = std::f64::consts::FRAC_1_SQRT_2;
        // corners bisect their two faces; the centre is inside
        for (node, expected) in [(0, [-h, -h]), (1, [h, -h]), (2, [h, h]), (3, [-h, h])] {
            let got = n[node].unwrap();
            assert!((got[0] - expected[0]).abs() < 1e-15 && (got[1] - expected[1]).abs() < 1e-15);
        }
        assert_eq!(n[4], None);
    }

    #[test]
    fn new_works() {
        let mut m = Mesh::new(square(), ElementKind::Tri3, vec![0, 1, 2, 0, 2, 3], vec![]).unwrap();
        assert_eq!(m.element_count(), 2);
        assert_eq!(m.regions(), &[0, 0]);
        m.add_node_set("left", vec![3, 0, 0]).unwrap();
        assert_eq!(m.node_set("left").unwrap(), &[0, 3]);
        m.add_edge_set(
            "bottom",
            vec![Side {
                element: 0,
                side: 0,
            }],
        )
        .unwrap();
        assert_eq!(m.edge_set_nodes("bottom").unwrap(), vec![0, 1]);
        assert!(matches!(
            m.node_set("top"),
            Err(FemError::UnknownSet { .. })
        ));
    }

    #[test]
    fn new_rejects_inverted_degenerate_and_bad_indices() {
        assert!(matches!(
            Mesh::new(square(), ElementKind::Tri3, vec![0, 2, 1], vec![]),
            Err(FemError::InvertedElement { element: 0, .. })
        ));
        let mut nodes = square();
        nodes.push([2.0, 0.0]);
        assert!(matches!(
            Mesh::new(nodes, ElementKind::Tri3, vec![0, 1, 2, 0, 1, 4], vec![]),
            Err(FemError::DegenerateElement { element: 1, .. })
        ));
        assert!(matches!(
            Mesh::new(square(), ElementKind::Tri3, vec![0, 1, 7], vec![]),
            Err(FemError::NodeOutOfRange {
                element: 0,
                node: 7,
                ..
            })
        ));
        assert!(matches!(
            Mesh::new(square(), ElementKind::Tri3, vec![0, 1], vec![]),
            Err(FemError::BadConnectivity { .. })
        ));
        let mut nodes = square();
        nodes[2][1] = f64::NAN;
        assert!(matches!(
            Mesh::new(nodes, ElementKind::Tri3, vec![0, 1, 2], vec![]),
            Err(FemError::NonFiniteNode { node: 2, .. })
        ));
    }
}
