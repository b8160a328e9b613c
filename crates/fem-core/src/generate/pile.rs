//! The axisymmetric pile-in-soil domain of the seed's chapter 6: [`pile_in_soil`].

use super::grid::{Grid, Line, add_edge_and_node_set, increasing, select_sides};
use super::{Grading, graded_points};
use crate::error::{FemError, positive};
use crate::mesh::{ElementKind, Mesh};
use std::collections::HashMap;

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
/// `H ≤ L_p`, a zero cell count or a bad grading ratio; [`FemError::KindDimension`] for a 3D
/// kind.
///
/// # Examples
/// ```
/// use fem_core::generate::{pile_in_soil, PileSpec};
/// let mesh = pile_in_soil(&PileSpec::default()).unwrap();
/// assert_eq!(mesh.node_set("interface_pile").unwrap().len(), 65);
/// assert_eq!(mesh.node_set("interface_soil").unwrap().len(), 65);
/// ```
pub fn pile_in_soil(spec: &PileSpec) -> Result<Mesh, FemError> {
    if spec.kind == ElementKind::Quad8 {
        // the lattice's cell centres would be nodes of no element
        return Err(FemError::Unsupported {
            what: "the pile-in-soil generator with Quad8 elements (use Quad4 or Quad9)".into(),
        });
    }
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
    super::check_grid_size(
        spec.cells_pile_r.saturating_add(spec.cells_soil_r),
        spec.cells_below_tip.saturating_add(spec.cells_shaft),
        spec.kind,
    )?;
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
    let boundary = mesh.boundary_facets();
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
        let mut nodes = mesh.facet_set_nodes(name)?;
        if spec.tip_corner == TipCorner::Shared {
            let corner = grid.id(column, tip_row);
            nodes.retain(|&n| n != corner);
        }
        mesh.add_node_set(name, nodes)?;
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::test_support::*;
    use approx::assert_relative_eq;

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
        // But it ends the lowest interface side on both sides.
        for name in ["interface_pile", "interface_soil"] {
            assert!(!mesh.node_set(name).unwrap().contains(&corner[0]), "{name}");
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
