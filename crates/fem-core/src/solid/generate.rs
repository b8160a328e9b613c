//! Structured meshes: a graded box (tetrahedra or hexahedra) and the octant of a hollow sphere
//! (tetrahedra).

use super::mesh::{ElementKind, Face, SolidMesh, dot, signed_volume};
use crate::error::FemError;
use crate::generate::lattice_lines;

/// `n + 1` equally spaced values from `a` to `b` (grid lines for [`box_mesh`]).
pub fn lines(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}

/// Orders a tetrahedron's corners so that its volume is positive.
pub(super) fn oriented(nodes: &[[f64; 3]], mut t: [usize; 4]) -> [usize; 4] {
    if signed_volume(nodes[t[0]], nodes[t[1]], nodes[t[2]], nodes[t[3]]) < 0.0 {
        t.swap(2, 3);
    }
    t
}

fn check_lines(name: &'static str, v: &[f64]) -> Result<(), FemError> {
    if v.len() < 2 {
        return Err(FemError::InvalidParameter {
            name,
            value: v.len() as f64,
            expected: "at least two grid lines",
        });
    }
    if let Some(w) = v.windows(2).find(|w| {
        w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater)
            || !w[0].is_finite()
            || !w[1].is_finite()
    }) {
        return Err(FemError::InvalidParameter {
            name,
            value: w[1],
            expected: "finite, strictly increasing grid lines",
        });
    }
    Ok(())
}

/// Names the boundary faces that lie on planes: for each `(name, axis, value)`, the boundary
/// faces whose corners all have coordinate `axis` equal to `value` (to `1e-9` of the span).
fn name_planes(
    mesh: &mut SolidMesh,
    planes: &[(&str, usize, f64)],
    span: f64,
) -> Result<(), FemError> {
    let boundary = mesh.boundary_facets();
    for &(name, axis, value) in planes {
        let faces: Vec<Face> = boundary
            .iter()
            .copied()
            .filter(|f| {
                mesh.face_node_ids(*f)
                    .take(3)
                    .all(|n| (mesh.nodes()[n][axis] - value).abs() <= 1e-9 * span)
            })
            .collect();
        mesh.add_face_set(name, faces)?;
    }
    Ok(())
}

/// A box meshed on the grid `xs × ys × zs` (strictly increasing grid lines, graded as you
/// like), each cell cut into six tetrahedra around its diagonal (Kuhn's subdivision, conforming
/// across cells), or one hexahedron per cell for [`ElementKind::Hex8`] and [`ElementKind::Hex20`]
/// (mid-edge nodes at the middle of the edges). Face sets (and node sets) `x0, x1, y0, y1, z0, z1` name the six sides
/// (`x0` at `x = xs[0]`, …).
///
/// # Errors
/// [`FemError::InvalidParameter`] for fewer than two or non-increasing grid lines,
/// [`FemError::KindDimension`] for a 2D kind.
///
/// # Examples
/// ```
/// use fem_core::ElementKind;
/// use fem_core::solid::generate::{box_mesh, lines};
/// let m = box_mesh(&lines(0.0, 2.0, 2), &lines(0.0, 1.0, 1), &lines(0.0, 1.0, 1), ElementKind::Tet10)?;
/// assert_eq!(m.element_count(), 12);
/// assert_eq!(m.face_set("x1")?.len(), 2);
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub fn box_mesh(
    xs: &[f64],
    ys: &[f64],
    zs: &[f64],
    kind: ElementKind,
) -> Result<SolidMesh, FemError> {
    check_lines("xs", xs)?;
    check_lines("ys", ys)?;
    check_lines("zs", zs)?;
    let mut mesh = match kind.of_dimension::<3>()? {
        ElementKind::Hex8 | ElementKind::Hex20 => hex_box(xs, ys, zs, kind)?,
        _ => tet_box(xs, ys, zs)?, // Tet4, Tet10
    };
    let [x, y, z] = [xs, ys, zs].map(|v| (v[0], v[v.len() - 1]));
    let span = [x, y, z].iter().map(|(a, b)| b - a).fold(0.0, f64::max);
    let planes = [
        ("x0", 0, x.0),
        ("x1", 0, x.1),
        ("y0", 1, y.0),
        ("y1", 1, y.1),
        ("z0", 2, z.0),
        ("z1", 2, z.1),
    ];
    name_planes(&mut mesh, &planes, span)?;
    match kind {
        ElementKind::Tet10 => mesh.to_tet10(None),
        _ => Ok(mesh),
    }
}

/// The tetrahedral (Tet4) box of [`box_mesh`], before its sides are named.
fn tet_box(xs: &[f64], ys: &[f64], zs: &[f64]) -> Result<SolidMesh, FemError> {
    let (nx, ny, nz) = (xs.len(), ys.len(), zs.len());
    let id = |i: usize, j: usize, k: usize| i + nx * (j + ny * k);
    let mut nodes = Vec::with_capacity(nx * ny * nz);
    for &z in zs {
        for &y in ys {
            for &x in xs {
                nodes.push([x, y, z]);
            }
        }
    }
    const PERMS: [[usize; 3]; 6] = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    let mut connectivity = Vec::with_capacity(24 * (nx - 1) * (ny - 1) * (nz - 1));
    for k in 0..nz - 1 {
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                for p in PERMS {
                    let mut at = [i, j, k];
                    let mut t = [id(i, j, k); 4];
                    for (s, &axis) in p.iter().enumerate() {
                        at[axis] += 1;
                        t[s + 1] = id(at[0], at[1], at[2]);
                    }
                    connectivity.extend(oriented(&nodes, t));
                }
            }
        }
    }
    SolidMesh::new(nodes, ElementKind::Tet4, connectivity, Vec::new())
}

/// The hexahedral box of [`box_mesh`] (before its sides are named): a lattice of the grid lines (and their midpoints for
/// Hex20, whose nodes are the lattice points with at most one odd index).
fn hex_box(xs: &[f64], ys: &[f64], zs: &[f64], kind: ElementKind) -> Result<SolidMesh, FemError> {
    use crate::element::hex8::CORNERS;
    use crate::element::hex20::EDGES;
    let quadratic = kind == ElementKind::Hex20;
    let [lx, ly, lz] = [xs, ys, zs].map(|c| lattice_lines(c, quadratic));
    let step = if quadratic { 2 } else { 1 };
    let (mx, my) = (lx.len(), ly.len());
    let lattice = |i: usize, j: usize, k: usize| i + mx * (j + my * k);
    // number the used lattice points in order
    let mut id = vec![usize::MAX; mx * my * lz.len()];
    let mut nodes = Vec::new();
    for (k, &z) in lz.iter().enumerate() {
        for (j, &y) in ly.iter().enumerate() {
            for (i, &x) in lx.iter().enumerate() {
                if (i % 2 + j % 2 + k % 2) <= 1 || !quadratic {
                    id[lattice(i, j, k)] = nodes.len();
                    nodes.push([x, y, z]);
                }
            }
        }
    }
    let cells = (xs.len() - 1) * (ys.len() - 1) * (zs.len() - 1);
    let mut connectivity = Vec::with_capacity(kind.node_count() * cells);
    for ck in 0..zs.len() - 1 {
        for cj in 0..ys.len() - 1 {
            for ci in 0..xs.len() - 1 {
                // lattice index of a reference point (−1, 0, 1 per axis) of the cell
                let at = |c: [f64; 3]| {
                    let o = |a: usize, v: f64| step * a + ((v + 1.0) * step as f64 / 2.0) as usize;
                    id[lattice(o(ci, c[0]), o(cj, c[1]), o(ck, c[2]))]
                };
                connectivity.extend(CORNERS.iter().map(|&c| at(c)));
                if quadratic {
                    connectivity.extend(EDGES.iter().map(|&[a, b]| {
                        at(core::array::from_fn(|d| {
                            0.5 * (CORNERS[a][d] + CORNERS[b][d])
                        }))
                    }));
                }
            }
        }
    }
    SolidMesh::new(nodes, kind, connectivity, Vec::new())
}

/// The octant `x, y, z ≥ 0` of a hollow sphere of radii `inner < outer`: the spherical
/// triangle cut into `n_t²` triangles (a lattice on the plane `x + y + z = 1` projected on the
/// sphere), extruded over `n_r` layers in radius into prisms, each cut into three tetrahedra
/// (diagonals chosen by node index, so the cut conforms). P2 mid-edge nodes lie on the spheres
/// and on the radial lines. Face sets `inner`, `outer` and the symmetry planes `x0`, `y0`, `z0`.
///
/// # Errors
/// [`FemError::InvalidParameter`] for radii that are not `0 < inner < outer` or a zero count,
/// [`FemError::KindDimension`] for a 2D kind, [`FemError::Unsupported`] for hexahedra.
pub fn sphere_shell_octant(
    inner: f64,
    outer: f64,
    n_t: usize,
    n_r: usize,
    kind: ElementKind,
) -> Result<SolidMesh, FemError> {
    kind.of_dimension::<3>()?;
    if !(inner > 0.0 && outer > inner && outer.is_finite()) {
        return Err(FemError::InvalidParameter {
            name: "inner radius",
            value: inner,
            expected: "0 < inner < outer (finite)",
        });
    }
    if n_t == 0 || n_r == 0 {
        return Err(FemError::InvalidParameter {
            name: "divisions",
            value: 0.0,
            expected: "at least one division in each direction",
        });
    }
    // lattice point (i, j): barycentric (i/n, j/n, 1 − (i + j)/n) on e_x, e_y, e_z
    let mut lattice = Vec::new();
    let mut lid = vec![vec![usize::MAX; n_t + 1]; n_t + 1];
    for (i, row) in lid.iter_mut().enumerate() {
        for (j, id) in row.iter_mut().enumerate().take(n_t - i + 1) {
            *id = lattice.len();
            let (a, b) = (i as f64 / n_t as f64, j as f64 / n_t as f64);
            lattice.push([a, b, 1.0 - a - b]);
        }
    }
    let mut tris = Vec::new();
    for i in 0..n_t {
        for j in 0..n_t - i {
            tris.push([lid[i][j], lid[i + 1][j], lid[i][j + 1]]);
            if i + j + 1 < n_t {
                tris.push([lid[i + 1][j], lid[i + 1][j + 1], lid[i][j + 1]]);
            }
        }
    }
    let radii = lines(inner, outer, n_r);
    let per_layer = lattice.len();
    let mut nodes = Vec::with_capacity(per_layer * (n_r + 1));
    for &r in &radii {
        for p in &lattice {
            let len = dot(*p, *p).sqrt();
            nodes.push(p.map(|v| r * v / len));
        }
    }
    let mut connectivity = Vec::new();
    for layer in 0..n_r {
        for t in &tris {
            let mut t = *t;
            t.sort_unstable();
            let [a, b, c] = t.map(|v| v + layer * per_layer);
            let [a2, b2, c2] = t.map(|v| v + (layer + 1) * per_layer);
            // a < b < c globally, so each quad's diagonal runs from its lower-index bottom
            // node to its higher-index top node: both neighbours cut it alike
            for tet in [[a, b, c, c2], [a, b, b2, c2], [a, a2, b2, c2]] {
                connectivity.extend(oriented(&nodes, tet));
            }
        }
    }
    let mut mesh = SolidMesh::new(nodes, ElementKind::Tet4, connectivity, Vec::new())?;
    let boundary = mesh.boundary_facets();
    let tol = 1e-9 * outer;
    let on = |mesh: &SolidMesh, f: &Face, test: &dyn Fn([f64; 3]) -> bool| {
        mesh.face_node_ids(*f)
            .take(3)
            .all(|n| test(mesh.nodes()[n]))
    };
    let radius = |p: [f64; 3]| dot(p, p).sqrt();
    type OnSurface = Box<dyn Fn([f64; 3]) -> bool>;
    let sets: [(&str, OnSurface); 5] = [
        ("inner", Box::new(move |p| (radius(p) - inner).abs() <= tol)),
        ("outer", Box::new(move |p| (radius(p) - outer).abs() <= tol)),
        ("x0", Box::new(move |p: [f64; 3]| p[0].abs() <= tol)),
        ("y0", Box::new(move |p: [f64; 3]| p[1].abs() <= tol)),
        ("z0", Box::new(move |p: [f64; 3]| p[2].abs() <= tol)),
    ];
    for (name, test) in &sets {
        let faces: Vec<Face> = boundary
            .iter()
            .copied()
            .filter(|f| on(&mesh, f, &**test))
            .collect();
        mesh.add_face_set(name, faces)?;
    }
    match kind {
        ElementKind::Tet4 => Ok(mesh),
        ElementKind::Tet10 => {
            // the parametric midpoint: radius and lattice position averaged, then projected
            let flat = |p: [f64; 3]| {
                let s = p[0] + p[1] + p[2];
                (radius(p), p.map(|v| v / s))
            };
            let mid = move |a: [f64; 3], b: [f64; 3]| {
                let ((ra, fa), (rb, fb)) = (flat(a), flat(b));
                let f: [f64; 3] = core::array::from_fn(|k| 0.5 * (fa[k] + fb[k]));
                let r = 0.5 * (ra + rb);
                let len = dot(f, f).sqrt();
                f.map(|v| r * v / len)
            };
            mesh.to_tet10(Some(&mid))
        }
        other => Err(FemError::Unsupported {
            what: format!("sphere_shell_octant of {other:?} elements (it makes tetrahedra)"),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn volume(m: &SolidMesh) -> f64 {
        (0..m.element_count())
            .map(|e| {
                let c = m.element(e);
                let x = m.nodes();
                signed_volume(x[c[0]], x[c[1]], x[c[2]], x[c[3]])
            })
            .sum()
    }

    #[test]
    fn box_mesh_is_conforming_and_fills_the_box_works() {
        let m = box_mesh(
            &lines(0.0, 2.0, 3),
            &[0.0, 0.2, 1.0],
            &lines(-1.0, 0.5, 2),
            ElementKind::Tet4,
        )
        .unwrap();
        assert_eq!(m.element_count(), 6 * 3 * 2 * 2);
        assert!((volume(&m) - 2.0 * 1.0 * 1.5).abs() < 1e-13);
        // boundary faces: 2 per cell face on the six sides (conforming: no inner face counted)
        let cells_on_sides = 2 * (3 * 2 + 3 * 2 + 2 * 2);
        assert_eq!(m.boundary_facets().len(), 2 * cells_on_sides);
        let named: usize = ["x0", "x1", "y0", "y1", "z0", "z1"]
            .iter()
            .map(|s| m.face_set(s).unwrap().len())
            .sum();
        assert_eq!(named, m.boundary_facets().len());
        let p2 = box_mesh(
            &lines(0.0, 1.0, 2),
            &lines(0.0, 1.0, 2),
            &lines(0.0, 1.0, 2),
            ElementKind::Tet10,
        )
        .unwrap();
        assert_eq!(p2.node_count(), 5 * 5 * 5);
        assert!(p2.node_set("z1").unwrap().len() == 25);
    }

    #[test]
    fn sphere_shell_octant_is_conforming_works() {
        let m = sphere_shell_octant(1.0, 2.0, 4, 3, ElementKind::Tet10).unwrap();
        let inner: Vec<usize> = m.node_set("inner").unwrap().to_vec();
        for n in inner {
            let p = m.nodes()[n];
            assert!((dot(p, p).sqrt() - 1.0).abs() < 1e-12);
        }
        let named: usize = ["inner", "outer", "x0", "y0", "z0"]
            .iter()
            .map(|s| m.face_set(s).unwrap().len())
            .sum();
        assert_eq!(
            named,
            m.boundary_facets().len(),
            "every boundary face is named once"
        );
        assert_eq!(m.face_set("inner").unwrap().len(), 16);
        assert!(sphere_shell_octant(2.0, 1.0, 1, 1, ElementKind::Tet4).is_err());
    }
}
