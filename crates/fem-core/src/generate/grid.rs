//! The structured lattice shared by the generators: grid points, the two triangles of each
//! cell, boundary sides and named boundary lines.

use crate::error::FemError;
use crate::mesh::{ElementKind, Mesh, Side};

/// Checks that a generated coordinate list is strictly increasing.
pub(super) fn increasing(name: &'static str, points: &[f64]) -> Result<(), FemError> {
    match points.windows(2).find(|w| w[1] <= w[0]) {
        None => Ok(()),
        Some(w) => Err(FemError::InvalidParameter {
            name,
            value: w[1],
            expected: "coordinates increasing from the first to the last (and distinct)",
        }),
    }
}

/// The lattice lines of grid lines `c`: the lines themselves, plus their midpoints when the
/// elements are `quadratic` (2D grids and 3D boxes alike).
pub(crate) fn lattice_lines(c: &[f64], quadratic: bool) -> Vec<f64> {
    if !quadratic {
        return c.to_vec();
    }
    let mut out = Vec::with_capacity(2 * c.len() - 1);
    for w in c.windows(2) {
        out.extend([w[0], 0.5 * (w[0] + w[1])]);
    }
    out.push(c[c.len() - 1]);
    out
}

/// The lattice of a structured grid: the cell lines, plus the mid-lines for P2.
pub(super) struct Grid {
    pub(super) xs: Vec<f64>,
    pub(super) ys: Vec<f64>,
    /// Lattice steps per cell: 1 for P1, 2 for P2.
    pub(super) step: usize,
    kind: ElementKind,
}

impl Grid {
    pub(super) fn new(xs: &[f64], ys: &[f64], kind: ElementKind) -> Self {
        let step = if kind.is_quadratic() { 2 } else { 1 };
        Self {
            xs: lattice_lines(xs, kind.is_quadratic()),
            ys: lattice_lines(ys, kind.is_quadratic()),
            step,
            kind,
        }
    }

    /// Node id of lattice point `(i, j)`, numbered row by row.
    pub(super) fn id(&self, i: usize, j: usize) -> usize {
        j * self.xs.len() + i
    }

    pub(super) fn points(&self) -> Vec<[f64; 2]> {
        self.ys
            .iter()
            .flat_map(|&y| self.xs.iter().map(move |&x| [x, y]))
            .collect()
    }

    /// Connectivity and regions of the two triangles (or the quadrilateral) of every cell
    /// `(i, j)`. A Quad8 grid leaves the cell centres unused (see [`compact`]).
    pub(super) fn cells(&self, region: impl Fn(usize, usize) -> u32) -> (Vec<usize>, Vec<u32>) {
        let s = self.step;
        let (nx, ny) = ((self.xs.len() - 1) / s, (self.ys.len() - 1) / s);
        let mut connectivity = Vec::with_capacity(2 * nx * ny * self.kind.node_count());
        let mut regions = Vec::with_capacity(2 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (a, b) = ((s * i, s * j), (s * i + s, s * j));
                let (c, d) = ((s * i + s, s * j + s), (s * i, s * j + s));
                let mid = |(i0, j0): (usize, usize), (i1, j1): (usize, usize)| {
                    self.id((i0 + i1) / 2, (j0 + j1) / 2)
                };
                if self.kind.corner_count() == 4 {
                    connectivity.extend([a, b, c, d].map(|(i, j)| self.id(i, j)));
                    if self.kind.is_quadratic() {
                        connectivity.extend([mid(a, b), mid(b, c), mid(c, d), mid(d, a)]);
                    }
                    if self.kind == ElementKind::Quad9 {
                        connectivity.push(mid(a, c));
                    }
                    regions.push(region(i, j));
                    continue;
                }
                let triangles = match (i + j) % 2 {
                    0 => [[a, b, c], [a, c, d]],
                    _ => [[a, b, d], [b, c, d]],
                };
                for [p, q, r] in triangles {
                    connectivity.extend([p, q, r].map(|(i, j)| self.id(i, j)));
                    if self.kind == ElementKind::Tri6 {
                        connectivity.extend([mid(p, q), mid(q, r), mid(r, p)]);
                    }
                    regions.push(region(i, j));
                }
            }
        }
        (connectivity, regions)
    }
}

/// Drops the nodes no element uses (the cell centres of a Quad8 grid) and renumbers the
/// rest in order; returns the nodes and the map from old to new ids (`usize::MAX`: dropped).
pub(super) fn compact(
    points: Vec<[f64; 2]>,
    connectivity: &mut [usize],
) -> (Vec<[f64; 2]>, Vec<usize>) {
    let mut used = vec![false; points.len()];
    for &n in connectivity.iter() {
        used[n] = true;
    }
    let mut map = vec![usize::MAX; points.len()];
    let mut kept = Vec::with_capacity(points.len());
    for (old, p) in points.into_iter().enumerate() {
        if used[old] {
            map[old] = kept.len();
            kept.push(p);
        }
    }
    for n in connectivity.iter_mut() {
        *n = map[*n];
    }
    (kept, map)
}

/// A straight boundary line `x = c` or `y = c`, with a tolerance.
#[derive(Clone, Copy)]
pub(super) struct Line {
    axis: usize,
    value: f64,
    tol: f64,
}

impl Line {
    pub(super) fn x(value: f64, tol: f64) -> Self {
        Self {
            axis: 0,
            value,
            tol,
        }
    }

    pub(super) fn y(value: f64, tol: f64) -> Self {
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

/// The sides of `candidates` whose two corners lie on `line` and satisfy
/// `keep(point, region of the element)`, sorted along the line.
pub(super) fn select_sides(
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

pub(super) fn add_edge_and_node_set(
    mesh: &mut Mesh,
    name: &str,
    sides: Vec<Side>,
) -> Result<(), FemError> {
    mesh.add_edge_set(name, sides)?;
    let nodes = mesh.facet_set_nodes(name)?;
    mesh.add_node_set(name, nodes)
}
