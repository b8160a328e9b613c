//! What the 2D mesh has of its own: the names of its facets (sides, edge sets), curves
//! ([`Mesh::add_curve_node_set`]), outward normals and the corner check of its elements.

use super::curve::{CurveOrder, chain_sides};
use super::{Mesh, Side};
use crate::error::FemError;

impl Mesh<2> {
    /// Adds (or replaces) the node set of the edge set `name`, ordered along the curve its
    /// sides make ([`chain_sides`]); a set that is not one curve is sorted by index instead.
    /// Returns, and records for [`Mesh::curve_order`], which it is. The Gmsh reader makes the
    /// node sets of physical curves this way; the generators keep theirs sorted.
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
            Err(why) => (self.facet_set_nodes(name)?, CurveOrder::NotACurve(why)),
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

    /// Adds (or replaces) a named edge set ([`Mesh::add_facet_set`]).
    ///
    /// # Errors
    /// [`FemError::InvalidSide`] for a side whose element or local index is out of range.
    pub fn add_edge_set(&mut self, name: &str, sides: Vec<Side>) -> Result<(), FemError> {
        self.add_facet_set(name, sides)
    }

    /// A named edge set ([`Mesh::facet_set`]).
    ///
    /// # Errors
    /// [`FemError::UnknownSet`] if there is none of that name.
    pub fn edge_set(&self, name: &str) -> Result<&[Side], FemError> {
        self.facet_set(name)
    }

    /// Names of the edge sets.
    pub fn edge_set_names(&self) -> impl Iterator<Item = &str> {
        self.facet_set_names()
    }

    /// The global nodes of a side, from its first corner to its second, mid-side node last.
    #[inline]
    pub fn side_nodes(&self, side: Side) -> impl Iterator<Item = usize> + '_ {
        self.facet_nodes(side)
    }

    /// The unit outward normal of the boundary at every node (`None` inside the body): the
    /// sum of the outward normals `(Δy, −Δx)` of the boundary sides through the node (elements
    /// are counter-clockwise, so the body lies left of each side), weighted by their lengths,
    /// normalised. At a corner it bisects the two faces.
    pub fn outward_normals(&self) -> Vec<Option<[f64; 2]>> {
        let mut sum = vec![[0.0_f64; 2]; self.node_count()];
        let mut on_boundary = vec![false; self.node_count()];
        for side in self.boundary_facets() {
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
}

/// The corner triangles of a triangle (itself) or a quadrilateral (at each corner `k`, the
/// corners `k, k + 1, k − 1`), counter-clockwise when the element is: they test a
/// quadrilateral exactly for strict convexity, i.e. a positive Jacobian of its bilinear map
/// everywhere ([`Mesh::new`]).
pub(super) fn corner_simplices(corners: usize) -> Vec<[usize; 4]> {
    match corners {
        3 => vec![[0, 1, 2, 0]],
        c => (0..c)
            .map(|k| [k, (k + 1) % c, (k + c - 1) % c, 0])
            .collect(),
    }
}

/// The signed area of the triangle `(a, b, c)`, positive counter-clockwise.
pub(super) fn signed_area([a, b, c]: [[f64; 2]; 3]) -> f64 {
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::ElementKind;

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
        assert_eq!(m.boundary_facets().len(), 4);
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
        assert_eq!(m.facet_set_nodes("bottom").unwrap(), vec![0, 1]);
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
