//! Node sets of Gmsh physical curves (2D) and surfaces (3D) on genuine Gmsh meshes (issue 36).
//!
//! Source of the fixtures: Gmsh 4.15.2 (the Python SDK, `pip install gmsh`), the scripts
//! beside them in `tests/data/gmsh/` (`square_curves.py`, `box.py`). Gmsh numbers the points
//! first, then the nodes inside each curve, then the mid-side nodes, and orients the line
//! elements as the curve loops go, so a curve's nodes sorted by tag do not follow the curve.
//!
//! ```text
//!   (0,1) ─────── (1,1) ─────── (2,1)     square_curves: two surfaces sharing x = 1,
//!     │     left    │    right    │       unstructured, P1 and P2
//!   (0,0) ─────── (1,0) ─────── (2,0)     "bottom" (open), "outline" (closed), "middle"
//!                                         (inside), "tee" (branches), "ends" (two pieces)
//! ```
//! What is asserted, and why:
//! - a curve's node set runs along the curve: on a straight curve the coordinate along it is
//!   strictly monotone, so the polyline through the set in order has the curve's length (2 for
//!   "bottom", to 1e-12: sums of a few lengths of order 0.1, round-off only); sorted by tag it
//!   zig-zags (the old order: this fails on it);
//! - a closed curve lists each node once, clockwise (the body on the right, outward normal on
//!   the left), from its lowest node: its closed polyline has the perimeter 6 (1e-12);
//! - a branching curve and a curve of two pieces are not one curve ([`NotACurve`]);
//! - 3D: a physical surface's node set holds the surface's nodes, and its consistent nodal
//!   areas (from the faces, not from any order) sum to the surface's area (1e-12).

use fem_core::Mesh;
use fem_core::curve::{CurveOrder, NotACurve, chain_sides};
use fem_core::generate::{Grading, PileSpec, RectangleSpec, pile_in_soil, rectangle};
use fem_core::gmsh::read_msh;
use fem_core::solid::gmsh::read_msh_3d;
use std::path::PathBuf;

fn data(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/gmsh")
        .join(file)
}

/// The length of the polyline through `nodes` in order (closed: back to the first).
fn polyline_length(mesh: &Mesh, nodes: &[usize], closed: bool) -> f64 {
    let x = mesh.nodes();
    let d = |a: usize, b: usize| (x[a][0] - x[b][0]).hypot(x[a][1] - x[b][1]);
    let open: f64 = nodes.windows(2).map(|w| d(w[0], w[1])).sum();
    open + if closed {
        d(nodes[nodes.len() - 1], nodes[0])
    } else {
        0.0
    }
}

/// Needs only the API of the old code: fails there (the set sorted by tag zig-zags).
#[test]
fn issue_36_gmsh_curve_node_sets_follow_the_curve() {
    for order in [1, 2] {
        let mesh = read_msh(&data(&format!("square_curves_p{order}.msh"))).unwrap();
        let bottom = mesh.node_set("bottom").unwrap();
        let xs: Vec<f64> = bottom.iter().map(|&n| mesh.nodes()[n][0]).collect();
        assert!(
            xs.windows(2).all(|w| w[1] < w[0]),
            "P{order}: bottom not along the curve (right to left): {xs:?}"
        );
        // the polyline's length is the curve's (round-off on a few tens of segments)
        let length = polyline_length(&mesh, bottom, false);
        assert!((length - 2.0).abs() < 1e-12, "P{order}: length {length}");
        // the line x = 1 inside the square: along it, monotone in y
        let middle = mesh.node_set("middle").unwrap();
        let ys: Vec<f64> = middle.iter().map(|&n| mesh.nodes()[n][1]).collect();
        assert!(
            ys.windows(2).all(|w| w[1] < w[0]) || ys.windows(2).all(|w| w[1] > w[0]),
            "P{order}: middle {ys:?}"
        );
    }
}

#[test]
fn issue_36_gmsh_curves_open_closed_branching_and_pieces() {
    for order in [1, 2] {
        let mesh = read_msh(&data(&format!("square_curves_p{order}.msh"))).unwrap();
        assert_eq!(mesh.curve_order("bottom"), Some(&CurveOrder::Open));
        assert_eq!(mesh.curve_order("middle"), Some(&CurveOrder::Open));
        assert_eq!(mesh.curve_order("outline"), Some(&CurveOrder::Closed));
        let outline = mesh.node_set("outline").unwrap();
        // every node once, from the lowest, the perimeter 6 (round-off)
        let mut sorted = outline.to_vec();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), outline.len());
        assert_eq!(outline[0], sorted[0]);
        let perimeter = polyline_length(&mesh, outline, true);
        assert!((perimeter - 6.0).abs() < 1e-12, "P{order}: {perimeter}");
        // clockwise (body on the right): negative signed area −2 (the square's, round-off)
        let x = mesh.nodes();
        let n = outline.len();
        let area: f64 = (0..n)
            .map(|k| {
                let (a, b) = (x[outline[k]], x[outline[(k + 1) % n]]);
                0.5 * (a[0] * b[1] - b[0] * a[1])
            })
            .sum();
        assert!((area + 2.0).abs() < 1e-12, "P{order}: signed area {area}");
        // the outline and the middle line branch at (1, 0) and (1, 1)
        match mesh.curve_order("tee") {
            Some(CurveOrder::NotACurve(NotACurve::Branch { node, sides: 3 })) => {
                let p = x[*node];
                assert!(p[0] == 1.0 && (p[1] == 0.0 || p[1] == 1.0), "{p:?}");
            }
            other => panic!("tee: {other:?}"),
        }
        assert_eq!(
            mesh.curve_order("ends"),
            Some(&CurveOrder::NotACurve(NotACurve::Pieces { pieces: 2 }))
        );
        // a set that is not one curve keeps every node, sorted
        let ends = mesh.node_set("ends").unwrap();
        assert!(ends.windows(2).all(|w| w[0] < w[1]));
        assert!(ends.iter().all(|&k| x[k][0] == 0.0 || x[k][0] == 2.0));
    }
}

/// P2: each side's mid-side node lies between its corners in the set's order.
#[test]
fn issue_36_gmsh_p2_mid_side_nodes_between_corners() {
    let mesh = read_msh(&data("square_curves_p2.msh")).unwrap();
    let outline = mesh.node_set("outline").unwrap();
    let x = mesh.nodes();
    let n = outline.len();
    assert!(n.is_multiple_of(2));
    for k in (1..n).step_by(2) {
        let (a, m, b) = (x[outline[k - 1]], x[outline[k]], x[outline[(k + 1) % n]]);
        // the mid-side node of a straight P2 side is its midpoint (Gmsh's, to round-off)
        let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        assert!(
            (m[0] - mid[0]).abs() < 1e-12 && (m[1] - mid[1]).abs() < 1e-12,
            "node {} at {m:?} is not the middle of {a:?}–{b:?}",
            outline[k]
        );
    }
}

/// The generators keep their sets sorted by index; on every edge set but one that order
/// already runs along the curve (it is the chained order or its reverse), so chaining them
/// would change no number of the existing scenes but the direction. The exception is the
/// pile's `surface` (the soil's top, `z = 0`, from the pile's radius out): its node at the
/// pile's radius has a higher index than the rest, so sorted it jumps from one end to the
/// other. No scene or preset takes it as a contact set; `bipo` refuses it as a `segments`
/// target (it doubles back) and gives it, as a contactor, areas from its sides.
#[test]
fn issue_36_generator_sets_already_run_along_their_curves() {
    let mut off = Vec::new();
    for kind in [fem_core::ElementKind::Tri3, fem_core::ElementKind::Tri6] {
        let rect = rectangle(&RectangleSpec {
            kind,
            grading_x: Grading::Geometric { ratio: 4.0 },
            ..RectangleSpec::new([0.0, 3.0], [-1.0, 1.0], 5, 3)
        })
        .unwrap();
        let pile = pile_in_soil(&PileSpec {
            kind,
            ..PileSpec::default()
        })
        .unwrap();
        for (generator, mesh) in [("rectangle", &rect), ("pile", &pile)] {
            for name in mesh.edge_set_names() {
                let sorted = mesh.node_set(name).unwrap().to_vec();
                let curve = chain_sides(mesh, mesh.edge_set(name).unwrap())
                    .unwrap_or_else(|e| panic!("{generator} `{name}`: {e}"));
                let mut reversed = curve.nodes.clone();
                reversed.reverse();
                if curve.nodes != sorted && reversed != sorted {
                    off.push(format!("{generator} {kind:?} {name}"));
                }
            }
        }
    }
    assert_eq!(off, ["pile Tri3 surface", "pile Tri6 surface"]);
}

#[test]
fn issue_36_gmsh_surface_node_sets_and_areas() {
    for order in [1, 2] {
        let mesh = read_msh_3d(&data(&format!("box_p{order}.msh"))).unwrap();
        for (name, area) in [("top", 2.0), ("sides", 1.0)] {
            let (nodes, areas) = mesh.nodal_areas(name).unwrap();
            let sum: f64 = areas.iter().sum();
            // consistent ∫ N_i dA over flat faces: exact up to round-off
            assert!((sum - area).abs() < 1e-12, "P{order} {name}: {sum}");
            let set = mesh.node_set(name).unwrap();
            assert_eq!(set, &nodes[..], "P{order} {name}");
        }
        // the top's nodes are every node at z = 0.5, no other
        let top: Vec<usize> = (0..mesh.node_count())
            .filter(|&k| mesh.nodes()[k][2] == 0.5)
            .collect();
        assert_eq!(mesh.node_set("top").unwrap(), &top[..]);
    }
}
