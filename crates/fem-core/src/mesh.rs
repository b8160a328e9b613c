//! One mesh for both dimensions, [`Mesh<D>`](Mesh): node coordinates `[f64; D]`, one element
//! kind of the dimension ([`ElementKind`]: triangles and quadrilaterals in the plane,
//! tetrahedra and hexahedra in 3D), a flat connectivity, region ids, named node sets and named
//! *facet* sets (sides of 2D elements: edge sets; faces of 3D elements: face sets).
//!
//! What is written once over `D` lives here: construction and validation, the sets, joining,
//! the boundary facets. What is geometry stays per dimension: [`plane`] (outward normals, the
//! 2D names, curves in [`curve`]) and [`solid`] (nodal areas, `to_tet10`, the 3D names).
//! [`SolidMesh`] is `Mesh<3>`; `Mesh` alone is the 2D mesh.

pub mod curve;
mod kind;
pub mod plane;
pub mod solid;

pub use crate::element::tet10::TET_EDGES;
pub use kind::{ElementKind, SolidKind};
pub use solid::{MidpointFn, triangle_shape};
pub(crate) use solid::{dot, signed_volume};

use crate::element::Element;
use crate::error::FemError;
use crate::space::{Dim, Space};
use curve::CurveOrder;
use std::collections::{BTreeMap, HashMap};

/// A facet of an element: element index and local facet — a side of a 2D element (see
/// [`ElementKind::facet_nodes`]) or a face of a 3D one. The
/// local index is called `side` in both dimensions (a face is a 3D element's side), so that
/// 2D code reads `Side { element, side }` and 3D code `Face { element, side }`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Facet {
    /// Element index.
    pub element: usize,
    /// Local facet index in `0..facet_count()` of the kind.
    pub side: u8,
}

/// A side of a 2D element (a [`Facet`]).
pub type Side = Facet;

/// A face of a 3D element (a [`Facet`]).
pub type Face = Facet;

/// A 3D mesh of tetrahedra or hexahedra.
pub type SolidMesh = Mesh<3>;

/// A mesh of dimension `D` (see the [module docs](self)): node coordinates, connectivity,
/// region ids, named node sets and named facet sets.
///
/// Coordinates are `(x, y)` (`(r, z)` in axisymmetry) or `(x, y, z)`. Built with
/// [`Mesh::new`], which checks indices, finiteness and orientation, so every `Mesh` is valid.
///
/// # Examples
/// One function for both dimensions:
/// ```
/// use fem_core::generate::{RectangleSpec, rectangle};
/// use fem_core::solid::generate::{box_mesh, lines};
/// use fem_core::{Dim, ElementKind, Mesh, Space};
///
/// /// The boundary facets, and the facets of one element.
/// fn facets<const D: usize>(mesh: &Mesh<D>) -> (usize, usize)
/// where
///     Dim<D>: Space,
/// {
///     (mesh.boundary_facets().len(), mesh.kind().facet_count())
/// }
/// let square = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2))?;
/// let l = lines(0.0, 1.0, 1);
/// let cube = box_mesh(&l, &l, &l, ElementKind::Hex8)?;
/// assert_eq!((facets(&square), facets(&cube)), ((8, 3), (6, 6)));
/// # Ok::<(), fem_core::FemError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh<const D: usize = 2>
where
    Dim<D>: Space,
{
    nodes: Vec<[f64; D]>,
    kind: ElementKind,
    connectivity: Vec<usize>,
    regions: Vec<u32>,
    node_sets: BTreeMap<String, Vec<usize>>,
    facet_sets: BTreeMap<String, Vec<Facet>>,
    /// How the node sets made by [`Mesh::add_curve_node_set`] are ordered (2D).
    curves: BTreeMap<String, CurveOrder>,
}

impl<const D: usize> Mesh<D>
where
    Dim<D>: Space,
{
    /// Builds and validates a mesh. `connectivity` is flat, `kind.node_count()` entries per
    /// element; `regions` has one id per element (empty means all in region 0).
    ///
    /// # Errors
    /// - [`FemError::KindDimension`] for a kind of the other dimension (`Tet4` in 2D);
    /// - [`FemError::NonFiniteNode`] (2D) or [`FemError::NonFiniteNode3`] (3D) for a NaN or
    ///   infinite coordinate;
    /// - [`FemError::EmptyMesh`] for a connectivity without a single element;
    /// - [`FemError::BadConnectivity`], [`FemError::NodeOutOfRange`],
    ///   [`FemError::LengthMismatch`] (regions) for inconsistent arrays;
    /// - [`FemError::DegenerateElement`] (2D: area below `1e-12` of the squared longest side)
    ///   or [`FemError::DegenerateSolid`] (3D: corner volume below `1e-12` of the cubed
    ///   longest edge), and [`FemError::InvertedElement`] (clockwise corners, a left-handed
    ///   corner triad) with the element index.
    pub fn new(
        nodes: Vec<[f64; D]>,
        kind: ElementKind,
        connectivity: Vec<usize>,
        regions: Vec<u32>,
    ) -> Result<Self, FemError> {
        let kind = kind.of_dimension::<D>()?;
        for (node, p) in nodes.iter().enumerate() {
            if !p.iter().all(|v| v.is_finite()) {
                return Err(match *p.as_slice() {
                    [x, y] => FemError::NonFiniteNode { node, x, y },
                    _ => FemError::NonFiniteNode3 {
                        node,
                        coords: std::array::from_fn(|a| p.get(a).copied().unwrap_or(0.0)),
                    },
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
            facet_sets: BTreeMap::new(),
            curves: BTreeMap::new(),
        })
    }

    /// Adds (or replaces) a named node set (sorted, without repeats).
    ///
    /// # Errors
    /// [`FemError::UnknownNode`] for an unknown node.
    pub fn add_node_set(&mut self, name: &str, nodes: Vec<usize>) -> Result<(), FemError> {
        let nodes = checked_node_set(self.nodes.len(), nodes)?;
        self.node_sets.insert(name.to_string(), nodes);
        self.curves.remove(name);
        Ok(())
    }

    /// Adds (or replaces) a named facet set (an edge set in 2D, a face set in 3D; see
    /// [`Mesh::add_edge_set`] and [`Mesh::add_face_set`]).
    ///
    /// # Errors
    /// [`FemError::InvalidSide`] for a facet whose element or local index is out of range.
    pub fn add_facet_set(&mut self, name: &str, facets: Vec<Facet>) -> Result<(), FemError> {
        self.check_facets(&facets)?;
        self.facet_sets.insert(name.to_string(), facets);
        Ok(())
    }

    /// [`FemError::InvalidSide`] for the first facet whose element or local index is out of
    /// range.
    pub(crate) fn check_facets(&self, facets: &[Facet]) -> Result<(), FemError> {
        let bad = |f: &&Facet| {
            f.element >= self.element_count() || f.side as usize >= self.kind.facet_count()
        };
        match facets.iter().find(bad) {
            Some(f) => Err(FemError::InvalidSide {
                element: f.element,
                side: f.side,
                element_count: self.element_count(),
            }),
            None => Ok(()),
        }
    }

    /// Joins meshes into one with several bodies (e.g. two cylinders in contact): nodes,
    /// elements and regions in the order given, each part's node and facet sets renamed
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
    pub fn join(parts: &[(&str, &Self)]) -> Result<Self, FemError> {
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
            facet_sets: BTreeMap::new(),
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
            for (name, facets) in &part.facet_sets {
                let name = format!("{prefix}{name}");
                if out.facet_sets.contains_key(&name) {
                    return Err(clash(&name));
                }
                let facets = facets
                    .iter()
                    .map(|f| Facet {
                        element: f.element + elem_off,
                        side: f.side,
                    })
                    .collect();
                out.facet_sets.insert(name, facets);
            }
        }
        Ok(out)
    }

    /// The element family.
    #[inline]
    pub fn kind(&self) -> ElementKind {
        self.kind
    }

    /// The built-in element of the mesh's kind ([`ElementKind::element`]), for code generic
    /// over `D`.
    ///
    /// # Examples
    /// ```
    /// use fem_core::generate::{RectangleSpec, rectangle};
    /// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 1, 1))?;
    /// assert_eq!(mesh.built_in_element().node_count(), 3);
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    pub fn built_in_element(&self) -> &'static dyn Element<D> {
        match self.kind.element() {
            Ok(element) => element,
            Err(e) => unreachable!("Mesh::new checked the kind's dimension: {e}"),
        }
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
    pub fn nodes(&self) -> &[[f64; D]] {
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

    /// The coordinates of element `e`'s nodes, in its node order, into `coords` (cleared
    /// first; no allocation once `coords` holds an element's worth).
    ///
    /// # Panics
    /// If `e >= element_count()`.
    #[inline]
    #[track_caller]
    pub fn element_coords_into(&self, e: usize, coords: &mut Vec<[f64; D]>) {
        coords.clear();
        coords.extend(self.element(e).iter().map(|&n| self.nodes[n]));
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

    /// A named facet set (an edge set in 2D, a face set in 3D).
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] (of kind `"edge"` or `"face"`) if there is none of that name.
    pub fn facet_set(&self, name: &str) -> Result<&[Facet], FemError> {
        self.facet_sets
            .get(name)
            .map(Vec::as_slice)
            .ok_or_else(|| FemError::UnknownSet {
                kind: <Dim<D> as Space>::FACET,
                name: name.to_string(),
            })
    }

    /// Names of the node sets.
    pub fn node_set_names(&self) -> impl Iterator<Item = &str> {
        self.node_sets.keys().map(String::as_str)
    }

    /// Names of the facet sets.
    pub fn facet_set_names(&self) -> impl Iterator<Item = &str> {
        self.facet_sets.keys().map(String::as_str)
    }

    /// All node sets, by name.
    #[inline]
    pub fn node_sets(&self) -> &BTreeMap<String, Vec<usize>> {
        &self.node_sets
    }

    /// All facet sets, by name.
    #[inline]
    pub fn facet_sets(&self) -> &BTreeMap<String, Vec<Facet>> {
        &self.facet_sets
    }

    /// The global nodes of a facet, in the kind's facet order (corners first).
    ///
    /// # Panics
    /// If the facet does not exist.
    #[inline]
    #[track_caller]
    pub fn facet_nodes(&self, facet: Facet) -> impl Iterator<Item = usize> + '_ {
        let cell = self.element(facet.element);
        self.kind
            .facet_nodes(facet.side as usize)
            .iter()
            .map(move |&l| cell[l])
    }

    /// Nodes of the facets of a facet set, sorted by index, without duplicates.
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] if there is no facet set of that name.
    pub fn facet_set_nodes(&self, name: &str) -> Result<Vec<usize>, FemError> {
        let mut nodes: Vec<usize> = self
            .facet_set(name)?
            .iter()
            .flat_map(|&f| self.facet_nodes(f))
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        Ok(nodes)
    }

    /// The facets that belong to one element only (the boundary of the body, holes
    /// included), sorted; two facets are the same when their corners are.
    pub fn boundary_facets(&self) -> Vec<Facet> {
        let mut seen: HashMap<[usize; 4], (Facet, u32)> =
            HashMap::with_capacity(2 * self.element_count());
        for f in self.all_facets() {
            seen.entry(self.facet_key(f))
                .and_modify(|e| e.1 += 1)
                .or_insert((f, 1));
        }
        let mut out: Vec<Facet> = seen
            .into_values()
            .filter_map(|(f, n)| (n == 1).then_some(f))
            .collect();
        out.sort_unstable();
        out
    }
}

impl<const D: usize> Mesh<D>
where
    Dim<D>: Space,
{
    /// Every facet of every element, in element order.
    pub(crate) fn all_facets(&self) -> impl Iterator<Item = Facet> + '_ {
        let count = self.kind.facet_count() as u8;
        (0..self.element_count())
            .flat_map(move |element| (0..count).map(move |side| Facet { element, side }))
    }

    /// The corner nodes of a facet, sorted, padded with `usize::MAX`: the same key for the
    /// two elements that share the facet.
    pub(crate) fn facet_key(&self, facet: Facet) -> [usize; 4] {
        let mut key = [usize::MAX; 4];
        let corners = self.facet_nodes(facet).take(self.kind.facet_corner_count());
        for (k, n) in key.iter_mut().zip(corners) {
            *k = n;
        }
        key.sort_unstable();
        key
    }
}

/// Checks the corners of one element: finite products, not degenerate, positively oriented.
/// A triangle or tetrahedron is tested whole, a quadrilateral or hexahedron on the simplex of
/// each corner and its neighbours ([`plane::corner_simplices`], [`solid::corner_simplices`]):
/// its signed area or volume against `1e-12` of its longest edge to the power `D`.
fn check_corners<const D: usize>(
    element: usize,
    nodes: &[[f64; D]],
    cell: &[usize],
) -> Result<(), FemError>
where
    Dim<D>: Space,
{
    let simplices = match D {
        2 => plane::corner_simplices(cell.len()),
        _ => solid::corner_simplices(cell.len()),
    };
    let (mut measure, mut l2) = (f64::INFINITY, 0.0_f64);
    for s in &simplices {
        let p: Vec<[f64; D]> = s[..=D].iter().map(|&k| nodes[cell[k]]).collect();
        let q = p.as_flattened();
        let m = match D {
            2 => plane::signed_area(*q.as_chunks().0.first_chunk().expect("3 points")),
            _ => match *q.as_chunks().0 {
                [a, b, c, d] => signed_volume(a, b, c, d),
                _ => f64::NAN,
            },
        };
        let mut lk = 0.0_f64;
        for (i, a) in p.iter().enumerate() {
            for b in &p[i + 1..] {
                lk = lk.max((0..D).map(|k| (a[k] - b[k]).powi(2)).sum());
            }
        }
        if !(m.is_finite() && lk.is_finite()) {
            // the coordinates are finite, but their products overflow
            let value = cell
                .iter()
                .flat_map(|&n| nodes[n].iter())
                .fold(0.0_f64, |m, v| m.max(v.abs()));
            return Err(FemError::InvalidParameter {
                name: "node coordinates",
                value,
                expected: match D {
                    2 => "magnitudes whose products stay finite (below about 1e150)",
                    _ => "magnitudes whose products stay finite (below about 1e100)",
                },
            });
        }
        measure = measure.min(m);
        l2 = l2.max(lk);
    }
    let small = if D == 2 {
        1e-12 * l2
    } else {
        1e-12 * l2 * l2.sqrt()
    };
    if measure.abs() <= small || l2 == 0.0 {
        return Err(match D {
            2 => FemError::DegenerateElement {
                element,
                area: measure,
            },
            _ => FemError::DegenerateSolid {
                element,
                volume: measure,
            },
        });
    }
    if measure < 0.0 {
        let det_j = if D == 2 { 2.0 } else { 6.0 } * measure;
        return Err(FemError::InvertedElement { element, det_j });
    }
    Ok(())
}

/// Checks a flat connectivity of `npe` nodes per element against `node_count` nodes and returns
/// the region of every element (`regions` empty: all in region 0).
fn checked_cells(
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
fn checked_node_set(node_count: usize, mut nodes: Vec<usize>) -> Result<Vec<usize>, FemError> {
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

    fn square() -> Mesh {
        let nodes = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        Mesh::new(nodes, ElementKind::Tri3, vec![0, 1, 2, 0, 2, 3], vec![]).unwrap()
    }

    fn tetrahedron() -> SolidMesh {
        let nodes = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        SolidMesh::new(nodes, ElementKind::Tet4, vec![0, 1, 2, 3], vec![]).unwrap()
    }

    /// One generic function on a mesh of either dimension: its boundary facets, the node count
    /// of its built-in element, and the error of an unknown facet set.
    fn summary<const D: usize>(mesh: &Mesh<D>) -> (usize, usize, FemError)
    where
        Dim<D>: Space,
    {
        let boundary = mesh.boundary_facets().len();
        (
            boundary,
            mesh.built_in_element().node_count(),
            mesh.facet_set("top").unwrap_err(),
        )
    }

    #[test]
    fn issue_35_one_generic_function_serves_both_dimensions() {
        // two triangles share the diagonal: 4 boundary sides; a tetrahedron has 4 faces
        let unknown = |kind| FemError::UnknownSet {
            kind,
            name: "top".to_string(),
        };
        assert_eq!(summary(&square()), (4, 3, unknown("edge")));
        assert_eq!(summary(&tetrahedron()), (4, 4, unknown("face")));
    }

    #[test]
    fn issue_35_the_built_in_element_of_every_kind_works() {
        fn check<const D: usize>(kind: ElementKind)
        where
            Dim<D>: Space,
        {
            let element = kind.element::<D>().unwrap();
            let topology = element.topology();
            assert_eq!(topology, kind.topology(), "{kind:?}");
            assert_eq!(element.node_count(), kind.node_count(), "{kind:?}");
            assert_eq!(topology.corners, kind.corner_count(), "{kind:?}");
            assert_eq!(topology.sides.len(), kind.facet_count(), "{kind:?}");
            for f in 0..kind.facet_count() {
                let corners = &kind.facet_nodes(f)[..kind.facet_corner_count()];
                assert!(
                    corners.iter().all(|&c| c < topology.corners),
                    "{kind:?} {f}"
                );
            }
        }
        let (plane, solid) = ElementKind::ALL.split_at(5);
        assert!(plane.iter().all(|k| k.dimension() == 2));
        assert!(solid.iter().all(|k| k.dimension() == 3));
        plane.iter().copied().for_each(check::<2>);
        solid.iter().copied().for_each(check::<3>);
    }

    #[test]
    fn issue_35_join_works_in_3d() {
        let mut a = tetrahedron();
        a.add_face_set(
            "base",
            vec![Face {
                element: 0,
                side: 0,
            }],
        )
        .unwrap();
        let both = SolidMesh::join(&[("a.", &a), ("b.", &a)]).unwrap();
        assert_eq!((both.node_count(), both.element_count()), (8, 2));
        assert_eq!(
            both.face_set("b.base").unwrap(),
            &[Face {
                element: 1,
                side: 0
            }]
        );
        // the face set's node set came along, shifted to the second part's nodes
        assert_eq!(both.node_set("b.base").unwrap(), &[4, 5, 6]);
        assert!(matches!(
            SolidMesh::join(&[("a.", &a), ("a.", &a)]),
            Err(FemError::Unsupported { .. })
        ));
    }

    #[test]
    fn new_rejects_non_finite_nodes_in_both_dimensions() {
        let mut nodes = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        nodes[3][2] = f64::INFINITY;
        assert!(matches!(
            SolidMesh::new(nodes, ElementKind::Tet4, vec![0, 1, 2, 3], vec![]),
            Err(FemError::NonFiniteNode3 { node: 3, coords }) if coords[2] == f64::INFINITY
        ));
        assert!(matches!(
            SolidMesh::new(vec![[0.0; 3]], ElementKind::Tet4, vec![0, 0, 0, 9], vec![]),
            Err(FemError::NodeOutOfRange { node: 9, .. })
        ));
    }
}
