//! Structured triangle meshes: graded 1D subdivisions, layered rectangles, and the
//! axisymmetric pile-in-soil domain of the seed's chapter 6.
//!
//! Every generator builds a tensor-product grid of points `x_i × y_j`, splits each cell into two
//! counter-clockwise triangles (the diagonal alternates from cell to cell, so the mesh has no
//! preferred direction) and, for P2, puts the mid-side nodes exactly at the middle of the
//! straight sides, shared by the neighbours. Grading is geometric:
//!
//! ```text
//! h_i = h_0 q^i,  i = 0 … n−1,   q = ratio^(1/(n−1)),   Σ h_i = b − a
//! ```
//!
//! Boundaries are named: edge sets hold the boundary [`Side`]s (sorted along the boundary) and
//! node sets of the same name hold all their nodes, mid-side nodes included.
//!
//! The pile mesh follows Terfaya (2019), ch. 6: axisymmetric `(r, z)` with `z` up and the
//! ground surface at `z = 0`, a pile of diameter `D = 0.27 m` and length `L_p = 13 m`, soil at
//! least `2 L_p` wide and `3.5 L_p` deep, and 65 interface node pairs on 6-node triangles.

use crate::error::{FemError, positive};
use crate::mesh::{ElementKind, Mesh, Side};
use std::collections::HashMap;

/// How the cells of a 1D subdivision grow from its start `a` to its end `b`.
///
/// Sizes follow a geometric progression; see the [module docs](self).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Grading {
    /// Equal cells.
    #[default]
    Uniform,
    /// Geometric progression with `ratio = h_last / h_first` (finite, `> 0`): `ratio > 1`
    /// refines toward the start `a`, `ratio < 1` toward the end `b`.
    Geometric {
        /// Last cell size over first cell size.
        ratio: f64,
    },
    /// Refined toward both ends, symmetrically: `ratio = h_middle / h_end` (finite, `> 0`,
    /// usually `> 1`). With fewer than three cells it is uniform.
    BothEnds {
        /// Middle cell size over end cell size.
        ratio: f64,
    },
}

impl Grading {
    /// Refined toward the start: the last cell is `ratio` times the first (`ratio ≥ 1` for a
    /// refinement).
    ///
    /// # Examples
    /// ```
    /// use fem_core::generate::{graded_points, Grading};
    /// let p = graded_points(0.0, 3.0, 2, Grading::fine_at_start(2.0)).unwrap();
    /// assert_eq!(p, vec![0.0, 1.0, 3.0]);
    /// ```
    pub fn fine_at_start(ratio: f64) -> Self {
        Grading::Geometric { ratio }
    }

    /// Refined toward the end: the first cell is `ratio` times the last (`ratio ≥ 1` for a
    /// refinement).
    ///
    /// # Examples
    /// ```
    /// use fem_core::generate::{graded_points, Grading};
    /// let p = graded_points(0.0, 3.0, 2, Grading::fine_at_end(2.0)).unwrap();
    /// assert_eq!(p, vec![0.0, 2.0, 3.0]);
    /// ```
    pub fn fine_at_end(ratio: f64) -> Self {
        Grading::Geometric { ratio: 1.0 / ratio }
    }

    /// The grading ratio (1 for uniform).
    fn ratio(self) -> f64 {
        match self {
            Grading::Uniform => 1.0,
            Grading::Geometric { ratio } | Grading::BothEnds { ratio } => ratio,
        }
    }

    /// Relative cell sizes, the largest being 1.
    fn weights(self, n: usize) -> Result<Vec<f64>, FemError> {
        let weights: Vec<f64> = match self {
            Grading::Uniform => vec![1.0; n],
            Grading::Geometric { ratio } => {
                let ratio = positive("ratio", ratio)?;
                let last = (n - 1).max(1) as f64;
                (0..n).map(|i| ratio.powf(i as f64 / last)).collect()
            }
            Grading::BothEnds { ratio } => {
                let ratio = positive("ratio", ratio)?;
                let k = (n - 1) / 2;
                (0..n)
                    .map(|i| match k {
                        0 => 1.0,
                        _ => ratio.powf(i.min(n - 1 - i) as f64 / k as f64),
                    })
                    .collect()
            }
        };
        let max = weights.iter().copied().fold(0.0, f64::max);
        let weights: Vec<f64> = weights.into_iter().map(|w| w / max).collect();
        if max.is_finite() && weights.iter().all(|&w| w > 0.0) {
            Ok(weights)
        } else {
            Err(FemError::InvalidParameter {
                name: "ratio",
                value: self.ratio(),
                expected: "a ratio whose powers stay finite and > 0 for this number of cells",
            })
        }
    }
}

/// The `n + 1` points of a subdivision of `[a, b]` into `n` cells graded by `grading`,
/// from `a` to `b` exactly (strictly monotone; `b < a` is allowed and runs backwards).
///
/// # Errors
/// [`FemError::InvalidParameter`] if `a` or `b` is not finite, `a == b`, `n == 0`, or the
/// grading ratio is not finite and `> 0`.
///
/// # Examples
/// ```
/// use fem_core::generate::{graded_points, Grading};
/// let p = graded_points(0.0, 7.0, 3, Grading::Geometric { ratio: 4.0 }).unwrap();
/// // sizes 1, 2, 4
/// assert_eq!(p, vec![0.0, 1.0, 3.0, 7.0]);
/// ```
pub fn graded_points(a: f64, b: f64, n: usize, grading: Grading) -> Result<Vec<f64>, FemError> {
    for (name, value) in [("a", a), ("b", b)] {
        if !value.is_finite() {
            return Err(FemError::InvalidParameter {
                name,
                value,
                expected: "a finite value",
            });
        }
    }
    if a == b {
        return Err(FemError::InvalidParameter {
            name: "b",
            value: b,
            expected: "an end point different from a",
        });
    }
    if n == 0 {
        return Err(FemError::InvalidParameter {
            name: "n",
            value: 0.0,
            expected: "at least one cell",
        });
    }
    let weights = grading.weights(n)?;
    let total: f64 = weights.iter().sum();
    let mut points = Vec::with_capacity(n + 1);
    let mut acc = 0.0;
    points.push(a);
    for w in &weights[..n - 1] {
        acc += w;
        points.push(a + (b - a) * (acc / total));
    }
    points.push(b);
    if points.windows(2).all(|w| (w[1] - w[0]) * (b - a) > 0.0) {
        Ok(points)
    } else {
        Err(FemError::InvalidParameter {
            name: "ratio",
            value: grading.ratio(),
            expected: "a grading whose smallest cell does not vanish in round-off",
        })
    }
}

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
/// counts, no layer, or a bad grading ratio.
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
    let xs = graded_points(spec.x[0], spec.x[1], spec.nx, spec.grading_x)?;
    increasing("x", &xs)?;
    if spec.layers.is_empty() {
        return Err(FemError::InvalidParameter {
            name: "layers",
            value: 0.0,
            expected: "at least one layer",
        });
    }
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
    let (connectivity, regions) = grid.cells(|_, j| layer_of_row[j]);
    let corners = [
        ("bottom_left", grid.id(0, 0)),
        ("bottom_right", grid.id(grid.xs.len() - 1, 0)),
        ("top_left", grid.id(0, grid.ys.len() - 1)),
        ("top_right", grid.id(grid.xs.len() - 1, grid.ys.len() - 1)),
    ];
    let mut mesh = Mesh::new(grid.points(), spec.kind, connectivity, regions)?;
    let [x0, x1] = [xs[0], xs[spec.nx]];
    let [y0, y1] = [ys[0], ys[ys.len() - 1]];
    let tol = 1e-12 * (x1 - x0).max(y1 - y0);
    let boundary = boundary_sides(&mesh);
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

/// What happens at the pile's bottom corner `(r, z) = (D/2, −L_p)`, where the shaft
/// interface meets the pile tip.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TipCorner {
    /// The corner node is duplicated like the rest of the shaft and is the first interface
    /// pair, so `cells_shaft` P2 sides give `2 cells_shaft + 1` pairs (the seed's 65). The soil
    /// under the tip uses the soil copy: the pile tip stays bonded to the soil only at
    /// `r < D/2`.
    #[default]
    Split,
    /// The corner node stays a single node shared by pile and soil (the tip is bonded all
    /// along) and is left out of the interface node sets: `2 cells_shaft` pairs for P2. It
    /// still ends the lowest side of both interface edge sets.
    ///
    /// ```
    /// use fem_core::generate::{pile_in_soil, PileSpec, TipCorner};
    /// let spec = PileSpec { tip_corner: TipCorner::Shared, ..PileSpec::default() };
    /// let mesh = pile_in_soil(&spec).unwrap();
    /// assert_eq!(mesh.node_set("interface_soil").unwrap().len(), 64);
    /// ```
    Shared,
}

/// The axisymmetric pile-in-soil domain of the seed's chapter 6, in `(r, z)` with `z` up and
/// the ground surface at `z = 0`. [`Default`] gives the Plancoët pile: `D = 0.27 m`,
/// `L_p = 13 m`, `W = 2 L_p`, `H = 3.5 L_p` (the seed's minimum extents), P2, 65 interface
/// pairs.
///
/// Radial cells are counted and graded outward (from the axis), vertical cells upward. With
/// the defaults the shaft sides are `L_p / 32 ≈ 0.41 m` long, the first soil column
/// `≈ 0.098 m` wide and the first row below the tip `≈ 0.23 m` high. The grid is a tensor
/// product, so the shaft spacing runs out to `r = W` and the pile's radial spacing down to
/// `z = −H`: far-field triangles are elongated (right-angled, aspect ratio up to about 100
/// under the pile near the base).
///
/// # Examples
/// ```
/// use fem_core::generate::{pile_in_soil, PileSpec};
/// use fem_core::ElementKind;
/// // The Cran pile (L_p = 17 m) on P1 triangles.
/// let spec = PileSpec {
///     length: 17.0,
///     width: 34.0,
///     depth: 3.5 * 17.0,
///     kind: ElementKind::Tri3,
///     ..PileSpec::default()
/// };
/// let mesh = pile_in_soil(&spec).unwrap();
/// assert_eq!(mesh.node_set("interface_pile").unwrap().len(), 33);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PileSpec {
    /// Pile diameter `D`.
    pub diameter: f64,
    /// Embedded pile length `L_p`: the pile occupies `0 ≤ r ≤ D/2`, `−L_p ≤ z ≤ 0`.
    pub length: f64,
    /// Radial extent `W` of the soil block (the seed uses `W ≥ 2 L_p`).
    pub width: f64,
    /// Depth `H` of the soil block (the seed uses `H ≥ 3.5 L_p`).
    pub depth: f64,
    /// P1 or P2 triangles.
    pub kind: ElementKind,
    /// Cells across the pile radius, `0 ≤ r ≤ D/2`.
    pub cells_pile_r: usize,
    /// Grading across the pile radius (refine toward `r = D/2` with
    /// [`Grading::fine_at_end`]).
    pub grading_pile_r: Grading,
    /// Cells in the soil from `r = D/2` to `r = W`.
    pub cells_soil_r: usize,
    /// Grading of the soil cells from `r = D/2` outward.
    pub grading_soil_r: Grading,
    /// Cells along the shaft, `−L_p ≤ z ≤ 0`: element sides along the interface.
    pub cells_shaft: usize,
    /// Grading along the shaft, from the tip up.
    pub grading_shaft: Grading,
    /// Cells below the tip, `−H ≤ z ≤ −L_p`.
    pub cells_below_tip: usize,
    /// Grading below the tip, from the base up (refine toward the tip with
    /// [`Grading::fine_at_end`]).
    pub grading_below_tip: Grading,
    /// Whether the bottom corner of the interface is split or shared.
    pub tip_corner: TipCorner,
}

impl Default for PileSpec {
    fn default() -> Self {
        let length = 13.0;
        Self {
            diameter: 0.27,
            length,
            width: 2.0 * length,
            depth: 3.5 * length,
            kind: ElementKind::Tri6,
            cells_pile_r: 2,
            grading_pile_r: Grading::Uniform,
            cells_soil_r: 20,
            grading_soil_r: Grading::fine_at_start(50.0),
            cells_shaft: 32,
            grading_shaft: Grading::Uniform,
            cells_below_tip: 16,
            grading_below_tip: Grading::fine_at_end(30.0),
            tip_corner: TipCorner::Split,
        }
    }
}

/// Region id of the soil in [`pile_in_soil`].
pub const SOIL: u32 = 0;
/// Region id of the pile in [`pile_in_soil`].
pub const PILE: u32 = 1;

/// The pile-in-soil mesh: region [`SOIL`] (0) and region [`PILE`] (1), disconnected along the
/// shaft `r = D/2, −L_p ≤ z ≤ 0` by duplicated nodes.
///
/// Named sets (each an edge set of boundary sides sorted along the line, and a node set of
/// all their nodes):
/// - `"axis"` (`r = 0`, pile and soil), `"outer"` (`r = W`), `"base"` (`z = −H`),
///   `"surface"` (`z = 0`, soil only), `"pile_head"` (`z = 0`, pile only);
/// - `"interface_pile"` and `"interface_soil"`: the shaft, as sides of pile elements and of
///   soil elements. Their node sets are coincident pairs: entry `i` of one lies at the same
///   point as entry `i` of the other, sorted by increasing `z`, and the two never share a
///   node. The bottom corner is paired or shared according to [`PileSpec::tip_corner`].
///
/// Nodes are numbered row by row from the bottom of the lattice; the soil copies of the
/// interface nodes come last.
///
/// # Errors
/// [`FemError::InvalidParameter`] for a non-positive or non-finite size, `W ≤ D/2`,
/// `H ≤ L_p`, a zero cell count or a bad grading ratio.
///
/// # Examples
/// ```
/// use fem_core::generate::{pile_in_soil, PileSpec};
/// let mesh = pile_in_soil(&PileSpec::default()).unwrap();
/// assert_eq!(mesh.node_set("interface_pile").unwrap().len(), 65);
/// assert_eq!(mesh.node_set("interface_soil").unwrap().len(), 65);
/// ```
pub fn pile_in_soil(spec: &PileSpec) -> Result<Mesh, FemError> {
    let diameter = positive("diameter", spec.diameter)?;
    let length = positive("length", spec.length)?;
    let radius = 0.5 * diameter;
    let width = positive("width", spec.width)?;
    let depth = positive("depth", spec.depth)?;
    if width <= radius {
        return Err(FemError::InvalidParameter {
            name: "width",
            value: width,
            expected: "a soil width W > D/2",
        });
    }
    if depth <= length {
        return Err(FemError::InvalidParameter {
            name: "depth",
            value: depth,
            expected: "a soil depth H > L_p",
        });
    }
    let mut rs = graded_points(0.0, radius, spec.cells_pile_r, spec.grading_pile_r)?;
    rs.extend_from_slice(
        &graded_points(radius, width, spec.cells_soil_r, spec.grading_soil_r)?[1..],
    );
    let mut zs = graded_points(
        -depth,
        -length,
        spec.cells_below_tip,
        spec.grading_below_tip,
    )?;
    zs.extend_from_slice(&graded_points(-length, 0.0, spec.cells_shaft, spec.grading_shaft)?[1..]);
    increasing("r", &rs)?;
    increasing("z", &zs)?;

    let grid = Grid::new(&rs, &zs, spec.kind);
    let (n_pile_r, n_tip) = (spec.cells_pile_r, spec.cells_below_tip);
    let (mut connectivity, regions) = grid.cells(|i, j| {
        if i < n_pile_r && j >= n_tip {
            PILE
        } else {
            SOIL
        }
    });

    // Duplicate the lattice column r = D/2 from the tip (or just above it) to the surface.
    let mut nodes = grid.points();
    let column = grid.step * n_pile_r;
    let tip_row = grid.step * n_tip;
    let first_row = match spec.tip_corner {
        TipCorner::Split => tip_row,
        TipCorner::Shared => tip_row + 1,
    };
    let mut soil_copy = HashMap::new();
    for row in first_row..grid.ys.len() {
        let id = grid.id(column, row);
        soil_copy.insert(id, nodes.len());
        nodes.push(nodes[id]);
    }
    let npe = spec.kind.node_count();
    for (cell, &region) in connectivity.chunks_exact_mut(npe).zip(&regions) {
        if region == SOIL {
            for node in cell.iter_mut() {
                if let Some(&copy) = soil_copy.get(node) {
                    *node = copy;
                }
            }
        }
    }

    let mut mesh = Mesh::new(nodes, spec.kind, connectivity, regions)?;
    let tol = 1e-12 * width.max(depth);
    let boundary = boundary_sides(&mesh);
    let named = [
        ("axis", Line::x(0.0, tol), None),
        ("outer", Line::x(width, tol), None),
        ("base", Line::y(-depth, tol), None),
        ("surface", Line::y(0.0, tol), Some(SOIL)),
        ("pile_head", Line::y(0.0, tol), Some(PILE)),
    ];
    for (name, line, only) in named {
        let sides = select_sides(&mesh, &boundary, line, |_, region| {
            only.is_none_or(|r| r == region)
        });
        add_edge_and_node_set(&mut mesh, name, sides)?;
    }
    let shaft = Line::x(radius, tol);
    for (name, side_region) in [("interface_pile", PILE), ("interface_soil", SOIL)] {
        let sides = select_sides(&mesh, &boundary, shaft, |p, region| {
            p[1] >= -length - tol && region == side_region
        });
        mesh.add_edge_set(name, sides)?;
        let mut nodes = mesh.edge_set_nodes(name)?;
        if spec.tip_corner == TipCorner::Shared {
            let corner = grid.id(column, tip_row);
            nodes.retain(|&n| n != corner);
        }
        mesh.add_node_set(name, nodes)?;
    }
    Ok(mesh)
}

/// Checks that a generated coordinate list is strictly increasing.
fn increasing(name: &'static str, points: &[f64]) -> Result<(), FemError> {
    match points.windows(2).find(|w| w[1] <= w[0]) {
        None => Ok(()),
        Some(w) => Err(FemError::InvalidParameter {
            name,
            value: w[1],
            expected: "coordinates increasing from the first to the last (and distinct)",
        }),
    }
}

/// The lattice of a structured grid: the cell lines, plus the mid-lines for P2.
struct Grid {
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// Lattice steps per cell: 1 for P1, 2 for P2.
    step: usize,
    kind: ElementKind,
}

impl Grid {
    fn new(xs: &[f64], ys: &[f64], kind: ElementKind) -> Self {
        let refine = |c: &[f64]| match kind {
            ElementKind::Tri3 => c.to_vec(),
            ElementKind::Tri6 => {
                let mut out = Vec::with_capacity(2 * c.len() - 1);
                for w in c.windows(2) {
                    out.extend([w[0], 0.5 * (w[0] + w[1])]);
                }
                out.push(c[c.len() - 1]);
                out
            }
        };
        let step = match kind {
            ElementKind::Tri3 => 1,
            ElementKind::Tri6 => 2,
        };
        Self {
            xs: refine(xs),
            ys: refine(ys),
            step,
            kind,
        }
    }

    /// Node id of lattice point `(i, j)`, numbered row by row.
    fn id(&self, i: usize, j: usize) -> usize {
        j * self.xs.len() + i
    }

    fn points(&self) -> Vec<[f64; 2]> {
        self.ys
            .iter()
            .flat_map(|&y| self.xs.iter().map(move |&x| [x, y]))
            .collect()
    }

    /// Connectivity and regions of the two triangles of every cell `(i, j)`.
    fn cells(&self, region: impl Fn(usize, usize) -> u32) -> (Vec<usize>, Vec<u32>) {
        let s = self.step;
        let (nx, ny) = ((self.xs.len() - 1) / s, (self.ys.len() - 1) / s);
        let mut connectivity = Vec::with_capacity(2 * nx * ny * self.kind.node_count());
        let mut regions = Vec::with_capacity(2 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (a, b) = ((s * i, s * j), (s * i + s, s * j));
                let (c, d) = ((s * i + s, s * j + s), (s * i, s * j + s));
                let triangles = match (i + j) % 2 {
                    0 => [[a, b, c], [a, c, d]],
                    _ => [[a, b, d], [b, c, d]],
                };
                for [p, q, r] in triangles {
                    connectivity.extend([p, q, r].map(|(i, j)| self.id(i, j)));
                    if self.kind == ElementKind::Tri6 {
                        let mid = |(i0, j0): (usize, usize), (i1, j1): (usize, usize)| {
                            self.id((i0 + i1) / 2, (j0 + j1) / 2)
                        };
                        connectivity.extend([mid(p, q), mid(q, r), mid(r, p)]);
                    }
                    regions.push(region(i, j));
                }
            }
        }
        (connectivity, regions)
    }
}

/// A straight boundary line `x = c` or `y = c`, with a tolerance.
#[derive(Clone, Copy)]
struct Line {
    axis: usize,
    value: f64,
    tol: f64,
}

impl Line {
    fn x(value: f64, tol: f64) -> Self {
        Self {
            axis: 0,
            value,
            tol,
        }
    }

    fn y(value: f64, tol: f64) -> Self {
        Self {
            axis: 1,
            value,
            tol,
        }
    }

    fn contains(&self, p: [f64; 2]) -> bool {
        (p[self.axis] - self.value).abs() <= self.tol
    }

    /// The coordinate along the line.
    fn along(&self, p: [f64; 2]) -> f64 {
        p[1 - self.axis]
    }
}

/// Sides whose pair of corner nodes belongs to a single element.
fn boundary_sides(mesh: &Mesh) -> Vec<Side> {
    let kind = mesh.kind();
    let mut count: HashMap<[usize; 2], (usize, Side)> = HashMap::new();
    for element in 0..mesh.element_count() {
        let cell = mesh.element(element);
        for side in 0..3 {
            let [a, b] = [
                cell[kind.side_nodes(side)[0]],
                cell[kind.side_nodes(side)[1]],
            ];
            let entry = count.entry([a.min(b), a.max(b)]).or_insert((
                0,
                Side {
                    element,
                    side: side as u8,
                },
            ));
            entry.0 += 1;
        }
    }
    let mut sides: Vec<Side> = count
        .into_values()
        .filter_map(|(n, side)| (n == 1).then_some(side))
        .collect();
    sides.sort_unstable();
    sides
}

/// The sides of `candidates` whose two corners lie on `line` and satisfy
/// `keep(point, region of the element)`, sorted along the line.
fn select_sides(
    mesh: &Mesh,
    candidates: &[Side],
    line: Line,
    keep: impl Fn([f64; 2], u32) -> bool,
) -> Vec<Side> {
    let on = |p: [f64; 2], region: u32| line.contains(p) && keep(p, region);
    let nodes = mesh.nodes();
    let corners = |s: Side| {
        let mut it = mesh.side_nodes(s);
        let a = it.next().map_or([f64::NAN; 2], |n| nodes[n]);
        let b = it.next().map_or([f64::NAN; 2], |n| nodes[n]);
        (a, b)
    };
    let mut keyed: Vec<(f64, Side)> = candidates
        .iter()
        .filter(|&&s| {
            let region = mesh.regions()[s.element];
            let (a, b) = corners(s);
            on(a, region) && on(b, region)
        })
        .map(|&s| {
            let (a, b) = corners(s);
            (0.5 * (line.along(a) + line.along(b)), s)
        })
        .collect();
    keyed.sort_by(|x, y| x.0.total_cmp(&y.0));
    keyed.into_iter().map(|(_, s)| s).collect()
}

fn add_edge_and_node_set(mesh: &mut Mesh, name: &str, sides: Vec<Side>) -> Result<(), FemError> {
    mesh.add_edge_set(name, sides)?;
    let nodes = mesh.edge_set_nodes(name)?;
    mesh.add_node_set(name, nodes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn corner_area(mesh: &Mesh, e: usize) -> f64 {
        let c = mesh.element(e);
        let [a, b, d] = [c[0], c[1], c[2]].map(|n| mesh.nodes()[n]);
        0.5 * ((b[0] - a[0]) * (d[1] - a[1]) - (d[0] - a[0]) * (b[1] - a[1]))
    }

    fn total_area(mesh: &Mesh) -> f64 {
        (0..mesh.element_count())
            .map(|e| corner_area(mesh, e))
            .sum()
    }

    /// Every P2 mid-side node is the exact midpoint of its side's corners.
    fn assert_mid_nodes(mesh: &Mesh) {
        for e in 0..mesh.element_count() {
            let c = mesh.element(e);
            for (side, &[a, b, m]) in [[0, 1, 3], [1, 2, 4], [2, 0, 5]].iter().enumerate() {
                let [pa, pb, pm] = [c[a], c[b], c[m]].map(|n| mesh.nodes()[n]);
                for k in 0..2 {
                    assert_eq!(pm[k], 0.5 * (pa[k] + pb[k]), "element {e} side {side}");
                }
            }
        }
    }

    /// Every node is used by some element.
    fn assert_all_nodes_used(mesh: &Mesh) {
        let mut used = vec![false; mesh.node_count()];
        for &n in mesh.connectivity() {
            used[n] = true;
        }
        assert!(used.iter().all(|&u| u));
    }

    #[test]
    fn graded_points_works() {
        let p = graded_points(1.0, 2.0, 4, Grading::Uniform).unwrap();
        assert_eq!(p, vec![1.0, 1.25, 1.5, 1.75, 2.0]);
        let p = graded_points(0.0, 10.0, 5, Grading::Geometric { ratio: 16.0 }).unwrap();
        let h: Vec<f64> = p.windows(2).map(|w| w[1] - w[0]).collect();
        // Round-off of a sum of five terms.
        assert_relative_eq!(h[4] / h[0], 16.0, max_relative = 1e-12);
        for w in h.windows(2) {
            assert_relative_eq!(w[1] / w[0], 2.0, max_relative = 1e-12);
        }
        let p = graded_points(0.0, 1.0, 5, Grading::fine_at_end(16.0)).unwrap();
        assert_relative_eq!((p[1] - p[0]) / (p[5] - p[4]), 16.0, max_relative = 1e-12);
        let p = graded_points(0.0, 1.0, 5, Grading::BothEnds { ratio: 4.0 }).unwrap();
        let h: Vec<f64> = p.windows(2).map(|w| w[1] - w[0]).collect();
        assert_relative_eq!(h[0], h[4], max_relative = 1e-12);
        assert_relative_eq!(h[1], h[3], max_relative = 1e-12);
        assert_relative_eq!(h[2] / h[0], 4.0, max_relative = 1e-12);
        assert_eq!(p[5], 1.0);
        // Backwards, and a single cell ignores the ratio.
        assert_eq!(
            graded_points(1.0, 0.0, 2, Grading::Uniform).unwrap(),
            [1.0, 0.5, 0.0]
        );
        assert_eq!(
            graded_points(0.0, 1.0, 1, Grading::Geometric { ratio: 9.0 }).unwrap(),
            [0.0, 1.0]
        );
        assert_eq!(
            graded_points(0.0, 1.0, 2, Grading::BothEnds { ratio: 9.0 }).unwrap(),
            [0.0, 0.5, 1.0]
        );
    }

    #[test]
    fn graded_points_rejects_bad_input() {
        let bad = |r| matches!(r, Err(FemError::InvalidParameter { .. }));
        assert!(bad(graded_points(0.0, 1.0, 0, Grading::Uniform)));
        assert!(bad(graded_points(0.0, 0.0, 3, Grading::Uniform)));
        assert!(bad(graded_points(f64::NAN, 1.0, 3, Grading::Uniform)));
        assert!(bad(graded_points(0.0, f64::INFINITY, 3, Grading::Uniform)));
        assert!(bad(graded_points(
            0.0,
            1.0,
            3,
            Grading::Geometric { ratio: 0.0 }
        )));
        assert!(bad(graded_points(0.0, 1.0, 3, Grading::fine_at_end(0.0))));
        assert!(bad(graded_points(
            0.0,
            1.0,
            3,
            Grading::BothEnds { ratio: -1.0 }
        )));
        assert!(bad(graded_points(
            0.0,
            1.0,
            3,
            Grading::BothEnds { ratio: f64::NAN }
        )));
        // Finite weights, but the smallest cells vanish next to the largest.
        assert!(bad(graded_points(
            1.0,
            2.0,
            1000,
            Grading::Geometric { ratio: 1e300 }
        )));
        assert!(graded_points(0.0, 1.0, 50, Grading::Geometric { ratio: 1e12 }).is_ok());
    }

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
        let bottom: Vec<Vec<usize>> = mesh
            .edge_set("bottom")
            .unwrap()
            .iter()
            .map(|&s| mesh.side_nodes(s).collect())
            .collect();
        assert_eq!(bottom, vec![vec![0, 1], vec![1, 2], vec![2, 3]]);
        let left: Vec<Vec<usize>> = mesh
            .edge_set("left")
            .unwrap()
            .iter()
            .map(|&s| mesh.side_nodes(s).collect())
            .collect();
        assert_eq!(left, vec![vec![4, 0], vec![8, 4]]);
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

    fn small_pile(kind: ElementKind, tip_corner: TipCorner) -> PileSpec {
        PileSpec {
            diameter: 0.5,
            length: 2.0,
            width: 4.0,
            depth: 7.0,
            kind,
            cells_pile_r: 2,
            grading_pile_r: Grading::fine_at_end(2.0),
            cells_soil_r: 3,
            grading_soil_r: Grading::fine_at_start(4.0),
            cells_shaft: 4,
            grading_shaft: Grading::fine_at_start(2.0),
            cells_below_tip: 2,
            grading_below_tip: Grading::fine_at_end(3.0),
            tip_corner,
        }
    }

    /// Checks the interface pairs: coincident, sorted by z, pile nodes only in pile
    /// elements and soil nodes only in soil elements.
    fn assert_interface(mesh: &Mesh, spec: &PileSpec, pairs: usize) {
        let pile = mesh.node_set("interface_pile").unwrap();
        let soil = mesh.node_set("interface_soil").unwrap();
        assert_eq!(pile.len(), pairs);
        assert_eq!(soil.len(), pairs);
        let mut in_region = vec![[false; 2]; mesh.node_count()];
        for e in 0..mesh.element_count() {
            for &n in mesh.element(e) {
                in_region[n][mesh.regions()[e] as usize] = true;
            }
        }
        for (i, (&p, &s)) in pile.iter().zip(soil).enumerate() {
            assert_ne!(p, s);
            assert_eq!(mesh.nodes()[p], mesh.nodes()[s]);
            assert_eq!(mesh.nodes()[p][0], 0.5 * spec.diameter);
            assert_eq!(in_region[p], [false, true], "pile node {p}");
            assert_eq!(in_region[s], [true, false], "soil node {s}");
            if i > 0 {
                assert!(mesh.nodes()[p][1] > mesh.nodes()[pile[i - 1]][1]);
            }
        }
        assert_eq!(mesh.nodes()[pile[pairs - 1]][1], 0.0);
        let sides_per_set = spec.cells_shaft;
        for (name, region) in [("interface_pile", PILE), ("interface_soil", SOIL)] {
            let sides = mesh.edge_set(name).unwrap();
            assert_eq!(sides.len(), sides_per_set);
            let mut z_prev = f64::NEG_INFINITY;
            for &s in sides {
                assert_eq!(mesh.regions()[s.element], region);
                let z: Vec<f64> = mesh.side_nodes(s).map(|n| mesh.nodes()[n][1]).collect();
                assert!(z[0].min(z[1]) >= z_prev);
                z_prev = z[0].max(z[1]);
            }
            assert_eq!(z_prev, 0.0);
        }
    }

    fn assert_pile_sets(mesh: &Mesh, spec: &PileSpec) {
        let r_pile = 0.5 * spec.diameter;
        let on = |name: &str, f: &dyn Fn([f64; 2]) -> bool| {
            let nodes = mesh.node_set(name).unwrap();
            assert!(!nodes.is_empty());
            for &n in nodes {
                assert!(
                    f(mesh.nodes()[n]),
                    "{name}: node {n} at {:?}",
                    mesh.nodes()[n]
                );
            }
        };
        on("axis", &|p| p[0] == 0.0);
        on("outer", &|p| p[0] == spec.width);
        on("base", &|p| p[1] == -spec.depth);
        on("surface", &|p| p[1] == 0.0 && p[0] >= r_pile);
        on("pile_head", &|p| p[1] == 0.0 && p[0] <= r_pile);
        let step = mesh.kind().node_count() / 3;
        let rows = step * (spec.cells_shaft + spec.cells_below_tip) + 1;
        let cols = step * (spec.cells_pile_r + spec.cells_soil_r) + 1;
        assert_eq!(mesh.node_set("axis").unwrap().len(), rows);
        assert_eq!(mesh.node_set("outer").unwrap().len(), rows);
        assert_eq!(mesh.node_set("base").unwrap().len(), cols);
        assert_eq!(
            mesh.node_set("pile_head").unwrap().len(),
            step * spec.cells_pile_r + 1
        );
        assert_eq!(
            mesh.node_set("surface").unwrap().len(),
            step * spec.cells_soil_r + 1
        );
        let head = mesh.node_set("pile_head").unwrap();
        let surface = mesh.node_set("surface").unwrap();
        assert!(head.iter().all(|n| !surface.contains(n)));
        for (name, count) in [
            ("axis", spec.cells_shaft + spec.cells_below_tip),
            ("outer", spec.cells_shaft + spec.cells_below_tip),
            ("base", spec.cells_pile_r + spec.cells_soil_r),
            ("surface", spec.cells_soil_r),
            ("pile_head", spec.cells_pile_r),
        ] {
            assert_eq!(mesh.edge_set(name).unwrap().len(), count, "{name}");
        }
        for &s in mesh.edge_set("pile_head").unwrap() {
            assert_eq!(mesh.regions()[s.element], PILE);
        }
    }

    #[test]
    fn pile_in_soil_p2_split_works() {
        let spec = small_pile(ElementKind::Tri6, TipCorner::Split);
        let mesh = pile_in_soil(&spec).unwrap();
        let lattice = (2 * 5 + 1) * (2 * 6 + 1);
        let pairs = 2 * spec.cells_shaft + 1;
        assert_eq!(mesh.node_count(), lattice + pairs);
        assert_eq!(mesh.element_count(), 2 * 5 * 6);
        // Straight sides: the corner areas are the exact areas.
        assert_relative_eq!(total_area(&mesh), 4.0 * 7.0, max_relative = 1e-13);
        let pile_area: f64 = (0..mesh.element_count())
            .filter(|&e| mesh.regions()[e] == PILE)
            .map(|e| corner_area(&mesh, e))
            .sum();
        assert_relative_eq!(pile_area, 0.25 * 2.0, max_relative = 1e-13);
        assert_mid_nodes(&mesh);
        assert_all_nodes_used(&mesh);
        assert_interface(&mesh, &spec, pairs);
        assert_pile_sets(&mesh, &spec);
        // The first pair is the tip corner.
        let first = mesh.node_set("interface_pile").unwrap()[0];
        assert_eq!(mesh.nodes()[first], [0.25, -2.0]);
    }

    #[test]
    fn pile_in_soil_p1_shared_works() {
        let spec = small_pile(ElementKind::Tri3, TipCorner::Shared);
        let mesh = pile_in_soil(&spec).unwrap();
        let lattice = 6 * 7;
        let pairs = spec.cells_shaft;
        assert_eq!(mesh.node_count(), lattice + pairs);
        assert_eq!(mesh.element_count(), 2 * 5 * 6);
        assert_relative_eq!(total_area(&mesh), 28.0, max_relative = 1e-13);
        assert_all_nodes_used(&mesh);
        assert_interface(&mesh, &spec, pairs);
        assert_pile_sets(&mesh, &spec);
        // The tip corner is one node, in both regions, and in no pair.
        let corner: Vec<usize> = (0..mesh.node_count())
            .filter(|&n| mesh.nodes()[n] == [0.25, -2.0])
            .collect();
        assert_eq!(corner.len(), 1);
        assert!(
            !mesh
                .node_set("interface_pile")
                .unwrap()
                .contains(&corner[0])
        );
        assert!(
            !mesh
                .node_set("interface_soil")
                .unwrap()
                .contains(&corner[0])
        );
        // But it ends the lowest interface side on both sides.
        for name in ["interface_pile", "interface_soil"] {
            let lowest = mesh.edge_set(name).unwrap()[0];
            assert!(mesh.side_nodes(lowest).any(|n| n == corner[0]));
        }
    }

    #[test]
    fn pile_in_soil_default_matches_the_seed() {
        let spec = PileSpec::default();
        let mesh = pile_in_soil(&spec).unwrap();
        assert_eq!(mesh.kind(), ElementKind::Tri6);
        assert_interface(&mesh, &spec, 65);
        assert_pile_sets(&mesh, &spec);
        assert_mid_nodes(&mesh);
        let (w, h) = (26.0, 45.5);
        // Sum of 2000-odd element areas.
        assert_relative_eq!(total_area(&mesh), w * h, max_relative = 1e-12);
        let pile = mesh.regions().iter().filter(|&&r| r == PILE).count();
        assert_eq!(pile, 2 * 2 * 32);
    }

    #[test]
    fn pile_in_soil_rejects_bad_spec() {
        let bad =
            |spec: PileSpec| matches!(pile_in_soil(&spec), Err(FemError::InvalidParameter { .. }));
        let base = small_pile(ElementKind::Tri3, TipCorner::Split);
        assert!(bad(PileSpec {
            diameter: 0.0,
            ..base
        }));
        assert!(bad(PileSpec {
            length: f64::NAN,
            ..base
        }));
        assert!(bad(PileSpec { width: 0.2, ..base }));
        assert!(bad(PileSpec { depth: 2.0, ..base }));
        assert!(bad(PileSpec {
            cells_shaft: 0,
            ..base
        }));
        assert!(bad(PileSpec {
            grading_soil_r: Grading::Geometric { ratio: -2.0 },
            ..base
        }));
    }
}
