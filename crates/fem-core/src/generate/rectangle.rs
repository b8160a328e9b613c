//! Layered rectangles: [`rectangle`] and its [`RectangleSpec`].

use super::grid::{Grid, Line, add_edge_and_node_set, compact, increasing, select_sides};
use super::{Grading, graded_points};
use crate::error::FemError;
use crate::mesh::{ElementKind, Mesh};

/// One horizontal layer of a [`RectangleSpec`]: from the top of the layer below (or `y0`)
/// up to `top`, with `ny` cells graded upward by `grading`, all in region `region`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layer {
    /// Upper edge of the layer.
    pub top: f64,
    /// Number of cells across the layer (`≥ 1`).
    pub ny: usize,
    /// Grading from the bottom of the layer to its top.
    pub grading: Grading,
    /// Region id of the layer's elements.
    pub region: u32,
}

/// A rectangle `[x0, x1] × [y0, top of the last layer]` made of horizontal layers.
///
/// Build it with [`RectangleSpec::new`] (one layer, region 0, uniform, P1) and adjust the
/// public fields.
#[derive(Clone, Debug, PartialEq)]
pub struct RectangleSpec {
    /// `[x0, x1]`, with `x0 < x1`.
    pub x: [f64; 2],
    /// Number of cells along x (`≥ 1`).
    pub nx: usize,
    /// Grading along x, from `x0` to `x1`.
    pub grading_x: Grading,
    /// Bottom edge.
    pub y0: f64,
    /// Layers from bottom to top (at least one), with increasing tops.
    pub layers: Vec<Layer>,
    /// P1 or P2 triangles.
    pub kind: ElementKind,
}

impl RectangleSpec {
    /// `[x0, x1] × [y0, y1]` with `nx × ny` uniform cells, one layer in region 0, P1.
    ///
    /// # Examples
    /// ```
    /// use fem_core::generate::{rectangle, RectangleSpec};
    /// use fem_core::ElementKind;
    /// let spec = RectangleSpec {
    ///     kind: ElementKind::Tri6,
    ///     ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2)
    /// };
    /// let mesh = rectangle(&spec).unwrap();
    /// assert_eq!(mesh.element_count(), 16);
    /// assert_eq!(mesh.node_count(), 9 * 5);
    /// ```
    pub fn new(x: [f64; 2], y: [f64; 2], nx: usize, ny: usize) -> Self {
        Self {
            x,
            nx,
            grading_x: Grading::Uniform,
            y0: y[0],
            layers: vec![Layer {
                top: y[1],
                ny,
                grading: Grading::Uniform,
                region: 0,
            }],
            kind: ElementKind::Tri3,
        }
    }
}

impl Default for RectangleSpec {
    /// The unit square as a single cell (two P1 triangles).
    fn default() -> Self {
        Self::new([0.0, 1.0], [0.0, 1.0], 1, 1)
    }
}

/// A layered rectangle of triangles with named boundaries.
///
/// Edge sets and node sets `"bottom"`, `"top"`, `"left"`, `"right"`; single-node sets
/// `"bottom_left"`, `"bottom_right"`, `"top_left"`, `"top_right"`. Nodes are numbered row by
/// row from the bottom left.
///
/// # Errors
/// [`FemError::InvalidParameter`] for non-finite or non-increasing coordinates, zero cell
/// counts, no layer, or a bad grading ratio; [`FemError::KindDimension`] for a 3D kind.
///
/// # Examples
/// ```
/// use fem_core::generate::{rectangle, Grading, Layer, RectangleSpec};
/// let mut spec = RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2);
/// spec.layers.push(Layer { top: 1.5, ny: 1, grading: Grading::Uniform, region: 7 });
/// let mesh = rectangle(&spec).unwrap();
/// assert_eq!(mesh.regions().iter().filter(|&&r| r == 7).count(), 4);
/// assert_eq!(mesh.node_set("top_right").unwrap(), &[mesh.node_count() - 1]);
/// ```
pub fn rectangle(spec: &RectangleSpec) -> Result<Mesh, FemError> {
    if spec.layers.is_empty() {
        return Err(FemError::InvalidParameter {
            name: "layers",
            value: 0.0,
            expected: "at least one layer",
        });
    }
    let rows = spec
        .layers
        .iter()
        .fold(0usize, |acc, l| acc.saturating_add(l.ny));
    super::check_grid_size(spec.nx, rows, spec.kind)?;
    let xs = graded_points(spec.x[0], spec.x[1], spec.nx, spec.grading_x)?;
    increasing("x", &xs)?;
    let mut ys = vec![spec.y0];
    let mut layer_of_row = Vec::new();
    for layer in &spec.layers {
        let bottom = *ys.last().unwrap_or(&spec.y0);
        let points = graded_points(bottom, layer.top, layer.ny, layer.grading)?;
        increasing("layer top", &points)?;
        ys.extend_from_slice(&points[1..]);
        layer_of_row.extend(std::iter::repeat_n(layer.region, layer.ny));
    }
    let grid = Grid::new(&xs, &ys, spec.kind);
    let (mut connectivity, regions) = grid.cells(|_, j| layer_of_row[j]);
    let (points, map) = compact(grid.points(), &mut connectivity);
    let corners = [
        ("bottom_left", map[grid.id(0, 0)]),
        ("bottom_right", map[grid.id(grid.xs.len() - 1, 0)]),
        ("top_left", map[grid.id(0, grid.ys.len() - 1)]),
        (
            "top_right",
            map[grid.id(grid.xs.len() - 1, grid.ys.len() - 1)],
        ),
    ];
    let mut mesh = Mesh::new(points, spec.kind, connectivity, regions)?;
    let [x0, x1] = [xs[0], xs[spec.nx]];
    let [y0, y1] = [ys[0], ys[ys.len() - 1]];
    let tol = 1e-12 * (x1 - x0).max(y1 - y0);
    let boundary = mesh.boundary_facets();
    let named = [
        ("bottom", Line::y(y0, tol)),
        ("top", Line::y(y1, tol)),
        ("left", Line::x(x0, tol)),
        ("right", Line::x(x1, tol)),
    ];
    for (name, line) in named {
        let sides = select_sides(&mesh, &boundary, line, |_, _| true);
        add_edge_and_node_set(&mut mesh, name, sides)?;
    }
    for (name, node) in corners {
        mesh.add_node_set(name, vec![node])?;
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::test_support::*;
    use approx::assert_relative_eq;

    #[test]
    fn rectangle_p1_works() {
        let spec = RectangleSpec {
            grading_x: Grading::fine_at_start(3.0),
            ..RectangleSpec::new([1.0, 4.0], [-1.0, 1.0], 3, 2)
        };
        let mesh = rectangle(&spec).unwrap();
        assert_eq!(mesh.node_count(), 4 * 3);
        assert_eq!(mesh.element_count(), 12);
        assert_relative_eq!(total_area(&mesh), 6.0, max_relative = 1e-14);
        assert_all_nodes_used(&mesh);
        assert_eq!(mesh.node_set("bottom").unwrap(), &[0, 1, 2, 3]);
        assert_eq!(mesh.node_set("top").unwrap(), &[8, 9, 10, 11]);
        assert_eq!(mesh.node_set("left").unwrap(), &[0, 4, 8]);
        assert_eq!(mesh.node_set("right").unwrap(), &[3, 7, 11]);
        assert_eq!(mesh.node_set("bottom_left").unwrap(), &[0]);
        assert_eq!(mesh.node_set("bottom_right").unwrap(), &[3]);
        assert_eq!(mesh.node_set("top_left").unwrap(), &[8]);
        assert_eq!(mesh.node_set("top_right").unwrap(), &[11]);
        for (name, count) in [("bottom", 3), ("top", 3), ("left", 2), ("right", 2)] {
            assert_eq!(mesh.edge_set(name).unwrap().len(), count, "{name}");
        }
        // Bottom sides run along x, in order, from left to right (counter-clockwise).
        let sides = |name| -> Vec<Vec<usize>> {
            let set = mesh.edge_set(name).unwrap();
            set.iter().map(|&s| mesh.side_nodes(s).collect()).collect()
        };
        assert_eq!(sides("bottom"), vec![vec![0, 1], vec![1, 2], vec![2, 3]]);
        assert_eq!(sides("left"), vec![vec![4, 0], vec![8, 4]]);
    }

    #[test]
    fn rectangle_p2_layers_work() {
        let spec = RectangleSpec {
            x: [0.0, 2.0],
            nx: 3,
            grading_x: Grading::BothEnds { ratio: 2.0 },
            y0: -1.0,
            layers: vec![
                Layer {
                    top: 0.0,
                    ny: 2,
                    grading: Grading::fine_at_end(3.0),
                    region: 4,
                },
                Layer {
                    top: 0.5,
                    ny: 1,
                    grading: Grading::Uniform,
                    region: 2,
                },
            ],
            kind: ElementKind::Tri6,
        };
        let mesh = rectangle(&spec).unwrap();
        assert_eq!(mesh.kind(), ElementKind::Tri6);
        assert_eq!(mesh.node_count(), 7 * 7);
        assert_eq!(mesh.element_count(), 18);
        assert_relative_eq!(total_area(&mesh), 3.0, max_relative = 1e-14);
        assert_mid_nodes(&mesh);
        assert_all_nodes_used(&mesh);
        for e in 0..mesh.element_count() {
            let c = mesh.element(e);
            let y = (0..3).map(|k| mesh.nodes()[c[k]][1]).sum::<f64>() / 3.0;
            let expected = if y < 0.0 { 4 } else { 2 };
            assert_eq!(mesh.regions()[e], expected);
        }
        // The interface between the layers is a grid line.
        assert_eq!(
            mesh.nodes().iter().filter(|p| p[1] == 0.0).count(),
            7,
            "y = 0 is a lattice row"
        );
        for (name, sides, nodes) in [
            ("bottom", 3, 7),
            ("top", 3, 7),
            ("left", 3, 7),
            ("right", 3, 7),
        ] {
            assert_eq!(mesh.edge_set(name).unwrap().len(), sides);
            assert_eq!(mesh.node_set(name).unwrap().len(), nodes);
        }
        for &n in mesh.node_set("right").unwrap() {
            assert_eq!(mesh.nodes()[n][0], 2.0);
        }
        assert_eq!(mesh.node_set("top_right").unwrap(), &[48]);
        assert_eq!(mesh.nodes()[48], [2.0, 0.5]);
    }

    #[test]
    fn rectangle_rejects_bad_spec() {
        let bad = |spec: RectangleSpec| {
            matches!(rectangle(&spec), Err(FemError::InvalidParameter { .. }))
        };
        assert!(bad(RectangleSpec::new([1.0, 0.0], [0.0, 1.0], 2, 2)));
        assert!(bad(RectangleSpec::new([0.0, 1.0], [1.0, 0.0], 2, 2)));
        assert!(bad(RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 0, 2)));
        assert!(bad(RectangleSpec::new([0.0, 1.0], [0.0, f64::NAN], 2, 2)));
        let mut spec = RectangleSpec::default();
        spec.layers.clear();
        assert!(bad(spec));
        let mut spec = RectangleSpec::default();
        spec.layers.push(Layer {
            top: 0.5,
            ny: 1,
            grading: Grading::Uniform,
            region: 1,
        });
        assert!(bad(spec));
    }
}
