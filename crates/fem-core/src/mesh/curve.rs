//! The nodes of a set of element sides ordered along the curve they make.
//!
//! A mesh file lists a curve's line elements in any order and orientation, and numbers its
//! nodes as it likes (Gmsh: the end points first, then the nodes inside the curve, then the
//! mid-side nodes), so a node set sorted by index does not follow the curve. [`chain_sides`]
//! chains the sides by their shared corners instead:
//!
//! - **Order.** From one end to the other, each side's mid-side node (P2) between its two
//!   corners: `a, m_ab, b, m_bc, c, …`.
//! - **Direction.** Each side is walked against its element's counter-clockwise order, so the
//!   element lies on the right and the body's outward normal on the left (`n = (−t_y, t_x)`):
//!   the convention of a contact target, which has its contactor on its left. Where the sides
//!   disagree (a curve inside a body, whose sides may come from either side), the direction
//!   most of them agree with wins.
//! - **Open and closed curves.** An open curve runs between its two ends (the one it leaves
//!   from is set by the direction). A closed curve starts at its lowest node index and lists
//!   every node once: the start node is *not* repeated at the end ([`CurveOrder::Closed`];
//!   whoever walks the segments adds the closing one, from the last node back to the first).
//! - **Not a curve.** A corner on three or more sides (a branch) or sides in several disjoint
//!   pieces make no single order: [`NotACurve`] says which.

use crate::mesh::{Mesh, Side};
use std::collections::BTreeMap;

/// How the nodes of a node set made from a curve are ordered
/// ([`Mesh::curve_order`](crate::Mesh::curve_order)).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CurveOrder {
    /// Along an open curve, from one end to the other, outward normal on the left.
    Open,
    /// Along a closed curve, outward normal on the left, from its lowest node index; every
    /// node once (the closing segment runs from the last node back to the first).
    Closed,
    /// Not one curve: the nodes are sorted by index.
    NotACurve(NotACurve),
}

/// Why a set of sides is not one curve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NotACurve {
    /// The set has no side.
    Empty,
    /// The corner `node` lies on `sides` (3 or more) sides of the set.
    Branch {
        /// The branching node (0-based index of the mesh).
        node: usize,
        /// How many sides of the set meet there.
        sides: usize,
    },
    /// The sides make `pieces` (2 or more) disjoint curves.
    Pieces {
        /// How many disjoint pieces.
        pieces: usize,
    },
}

impl std::fmt::Display for NotACurve {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NotACurve::Empty => write!(f, "it has no side"),
            NotACurve::Branch { node, sides } => write!(
                f,
                "it branches at node {node} ({sides} of its sides meet there)"
            ),
            NotACurve::Pieces { pieces } => write!(
                f,
                "it is made of {pieces} disjoint pieces (a polyline through it would bridge \
                 the gaps)"
            ),
        }
    }
}

/// A chained curve: its nodes in order and whether it closes on itself.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Curve {
    /// The nodes along the curve (see the [module docs](self)).
    pub nodes: Vec<usize>,
    /// `true` for a closed curve (the first node is not repeated at the end).
    pub closed: bool,
}

/// Chains `sides` of `mesh` into one curve (see the [module docs](self)). Sides with the same
/// two corners count once.
///
/// # Errors
/// [`NotACurve`] for an empty set, a branch or disjoint pieces.
///
/// # Examples
/// ```
/// use fem_core::curve::chain_sides;
/// use fem_core::generate::{RectangleSpec, rectangle};
/// let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 2, 1))?;
/// let curve = chain_sides(&mesh, mesh.edge_set("bottom")?).unwrap();
/// // the body (above) on the right: the bottom is walked from x = 2 to x = 0
/// assert_eq!(curve.nodes, vec![2, 1, 0]);
/// assert!(!curve.closed);
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub fn chain_sides(mesh: &Mesh, sides: &[Side]) -> Result<Curve, NotACurve> {
    // Each side once, as (first corner, second corner, mid-side node), in its element's order.
    let mut edges: Vec<(usize, usize, Option<usize>)> = Vec::with_capacity(sides.len());
    let mut seen = std::collections::BTreeSet::new();
    for &s in sides {
        let mut it = mesh.side_nodes(s);
        let (Some(a), Some(b)) = (it.next(), it.next()) else {
            continue;
        };
        if seen.insert([a.min(b), a.max(b)]) {
            edges.push((a, b, it.next()));
        }
    }
    if edges.is_empty() {
        return Err(NotACurve::Empty);
    }
    let mut at: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (k, &(a, b, _)) in edges.iter().enumerate() {
        at.entry(a).or_default().push(k);
        at.entry(b).or_default().push(k);
    }
    if let Some((&node, list)) = at.iter().find(|(_, l)| l.len() > 2) {
        return Err(NotACurve::Branch {
            node,
            sides: list.len(),
        });
    }
    // One piece: walk from an end (or, closed, from the lowest node) and count the sides
    // walked.
    let ends: Vec<usize> = at
        .iter()
        .filter(|(_, l)| l.len() == 1)
        .map(|(&n, _)| n)
        .collect();
    let closed = ends.is_empty();
    let start = ends
        .first()
        .copied()
        .unwrap_or_else(|| *at.keys().next().expect("non-empty"));
    let mut nodes = vec![start];
    let mut used = vec![false; edges.len()];
    let mut agree = 0usize; // sides walked from their second corner to their first
    let mut node = start;
    while let Some(&k) = at[&node].iter().find(|&&k| !used[k]) {
        used[k] = true;
        let (a, b, m) = edges[k];
        let next = if a == node { b } else { a };
        agree += usize::from(node == b);
        nodes.extend(m);
        if next != start {
            nodes.push(next);
        }
        node = next;
    }
    let walked = used.iter().filter(|&&u| u).count();
    if walked < edges.len() {
        let mut pieces = 1;
        let mut left: Vec<usize> = (0..edges.len()).filter(|&k| !used[k]).collect();
        while let Some(k0) = left.pop() {
            pieces += 1;
            let mut stack = vec![k0];
            used[k0] = true;
            while let Some(k) = stack.pop() {
                for c in [edges[k].0, edges[k].1] {
                    for &j in &at[&c] {
                        if !used[j] {
                            used[j] = true;
                            stack.push(j);
                        }
                    }
                }
            }
            left.retain(|&k| !used[k]);
        }
        return Err(NotACurve::Pieces { pieces });
    }
    if 2 * agree < edges.len() {
        // most sides were walked along their element's order: walk the other way
        if closed {
            nodes[1..].reverse();
        } else {
            nodes.reverse();
        }
    }
    Ok(Curve { nodes, closed })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::ElementKind;

    /// A strip of `n` P1 squares along x, two triangles each, with the bottom sides.
    fn strip(n: usize) -> (Mesh, Vec<Side>) {
        let mut nodes = Vec::new();
        for i in 0..=n {
            nodes.push([i as f64, 0.0]);
            nodes.push([i as f64, 1.0]);
        }
        let mut conn = Vec::new();
        for i in 0..n {
            let (a, b, c, d) = (2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1);
            conn.extend([a, b, c, a, c, d]);
        }
        let mesh = Mesh::new(nodes, ElementKind::Tri3, conn, vec![]).unwrap();
        let bottom = (0..n)
            .map(|i| Side {
                element: 2 * i,
                side: 0,
            })
            .collect();
        (mesh, bottom)
    }

    #[test]
    fn chain_sides_works_on_open_curves_in_any_order() {
        let (mesh, mut bottom) = strip(3);
        bottom.reverse();
        let c = chain_sides(&mesh, &bottom).unwrap();
        // body above the bottom: walked from x = 3 to x = 0
        assert_eq!(c.nodes, vec![6, 4, 2, 0]);
        assert!(!c.closed);
    }

    #[test]
    fn chain_sides_works_on_closed_curves() {
        let (mesh, _) = strip(2);
        let boundary = mesh.boundary_facets();
        let c = chain_sides(&mesh, &boundary).unwrap();
        assert!(c.closed);
        assert_eq!(c.nodes.len(), 6);
        // from the lowest node, clockwise (body on the right): 0 → 1 (up the left side)
        assert_eq!(c.nodes[..2], [0, 1]);
    }

    #[test]
    fn chain_sides_rejects_branches_and_pieces() {
        let (mesh, bottom) = strip(3);
        let two = vec![bottom[0], bottom[2]];
        assert_eq!(
            chain_sides(&mesh, &two),
            Err(NotACurve::Pieces { pieces: 2 })
        );
        // the bottom and the inner vertical side x = 1: element 2 is (2, 4, 5), its side 2
        // runs 5 → 2, down to the bottom's node 2
        let mut tee = bottom.clone();
        tee.push(Side {
            element: 2,
            side: 2,
        });
        assert_eq!(
            chain_sides(&mesh, &tee),
            Err(NotACurve::Branch { node: 2, sides: 3 })
        );
        assert_eq!(chain_sides(&mesh, &[]), Err(NotACurve::Empty));
    }
}
