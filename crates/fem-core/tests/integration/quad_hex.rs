//! The quadrilaterals (Quad4, Quad8, Quad9) and hexahedra (Hex8, Hex20) of issue 35: element
//! properties, patch tests on distorted meshes, and the mass.
//!
//! Sources: the patch test — B. M. Irons, A. Razzaque, "Experience with the patch test for
//! convergence of finite elements" (1972); O. C. Zienkiewicz, R. L. Taylor, *The Finite
//! Element Method*, vol. 1, 6th ed., §9 (an isoparametric element reproduces every linear
//! displacement field exactly on any mesh, distorted ones included, when its rule integrates
//! `∇N det J` exactly: full Gauss rules do on straight-sided elements). HRZ lumping: E. Hinton,
//! T. Rock, O. C. Zienkiewicz, *Earthquake Eng. Struct. Dyn.* 4 (1976) 245–249.
//!
//! ```text
//!   y ^  u = A x + c prescribed on the boundary      3 × 2 cells on [0, 2] × [1, 2]
//!   2 +--+---+--+   interior corners moved by ±0.3 h   (r ∈ [1, 3] in axisymmetry:
//!     |  /   \  |   mid-side nodes at the middle of    u_r = a r, u_z = d z + e,
//!   1 +--+---+--+   their straight sides               the constant strains there)
//! ```
//! Checks: every node's displacement equals the linear field and every stress point carries
//! `D ε` to 1e-12 relative (round-off of a few dozen operations on O(1) numbers), in plane
//! strain, plane stress and axisymmetry; the same in 3D on a distorted 2 × 2 × 2 hexahedral
//! box with a general linear field.

use fem_core::element::{Element, Hex8, Hex20, Quad4, Quad8, Quad9, Tet10};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidMesh, SolidModel};
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, Supports,
};
use nalgebra::DMatrix;

use crate::common::Rng;

/// A distorted quadrilateral mesh of `[x0, x0 + 2] × [1, 2]` with `n[0] × n[1]` cells:
/// interior corners moved by up to `0.3` cell sizes, mid-side nodes (and Quad9 centres) put
/// back at the middle of their straight sides (centre: the mean of the corners).
pub(crate) fn distorted_quads(kind: ElementKind, x0: f64, n: [usize; 2], seed: u64) -> Mesh {
    let spec = RectangleSpec {
        kind,
        ..RectangleSpec::new([x0, x0 + 2.0], [1.0, 2.0], n[0], n[1])
    };
    let mesh = rectangle(&spec).unwrap();
    let h = [2.0 / n[0] as f64, 1.0 / n[1] as f64];
    let mut nodes = mesh.nodes().to_vec();
    let mut rng = Rng(seed);
    let inside = |p: [f64; 2]| {
        p[0] > x0 + 1e-9 && p[0] < x0 + 2.0 - 1e-9 && p[1] > 1.0 + 1e-9 && p[1] < 2.0 - 1e-9
    };
    let mut is_corner = vec![false; nodes.len()];
    for e in 0..mesh.element_count() {
        for &c in &mesh.element(e)[..4] {
            is_corner[c] = true;
        }
    }
    for (p, corner) in nodes.iter_mut().zip(&is_corner) {
        if *corner && inside(*p) {
            p[0] += 0.3 * h[0] * rng.next();
            p[1] += 0.3 * h[1] * rng.next();
        }
    }
    for e in 0..mesh.element_count() {
        let cell = mesh.element(e);
        let mid = |a: [f64; 2], b: [f64; 2]| [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        if cell.len() >= 8 {
            for k in 0..4 {
                nodes[cell[4 + k]] = mid(nodes[cell[k]], nodes[cell[(k + 1) % 4]]);
            }
        }
        if cell.len() == 9 {
            let c: [f64; 2] =
                core::array::from_fn(|a| cell[..4].iter().map(|&i| nodes[i][a]).sum::<f64>() / 4.0);
            nodes[cell[8]] = c;
        }
    }
    Mesh::new(
        nodes,
        kind,
        mesh.connectivity().to_vec(),
        mesh.regions().to_vec(),
    )
    .unwrap()
}

/// A distorted hexahedral box `[0, 1]³` of `n³` cells (interior corners moved by up to 0.25
/// cell sizes, mid-edge nodes back at the middle of their edges).
pub(crate) fn distorted_hexes(kind: SolidKind, n: usize, seed: u64) -> SolidMesh {
    let l = lines(0.0, 1.0, n);
    let mesh = box_mesh(&l, &l, &l, kind).unwrap();
    let h = 1.0 / n as f64;
    let mut nodes = mesh.nodes().to_vec();
    let mut rng = Rng(seed);
    let mut is_corner = vec![false; nodes.len()];
    for e in 0..mesh.element_count() {
        for &c in &mesh.element(e)[..8] {
            is_corner[c] = true;
        }
    }
    for (p, corner) in nodes.iter_mut().zip(&is_corner) {
        if *corner && p.iter().all(|v| *v > 1e-9 && *v < 1.0 - 1e-9) {
            for v in p.iter_mut() {
                *v += 0.25 * h * rng.next();
            }
        }
    }
    if kind == SolidKind::Hex20 {
        for e in 0..mesh.element_count() {
            let cell = mesh.element(e);
            for (k, [a, b]) in fem_core::element::hex20::EDGES.iter().enumerate() {
                let (pa, pb) = (nodes[cell[*a]], nodes[cell[*b]]);
                nodes[cell[8 + k]] = core::array::from_fn(|d| 0.5 * (pa[d] + pb[d]));
            }
        }
    }
    SolidMesh::new(nodes, kind, mesh.connectivity().to_vec(), vec![]).unwrap()
}

fn on_box_boundary(p: [f64; 2], x0: f64) -> bool {
    (p[0] - x0).abs() < 1e-9
        || (p[0] - x0 - 2.0).abs() < 1e-9
        || (p[1] - 1.0).abs() < 1e-9
        || (p[1] - 2.0).abs() < 1e-9
}

#[test]
fn issue_35_quadrilateral_patch_tests_works() {
    let material = Material::new(100.0, 0.3, 0.0).unwrap();
    for kind in [ElementKind::Quad4, ElementKind::Quad8, ElementKind::Quad9] {
        for ideal in [
            Idealization::PlaneStrain,
            Idealization::PlaneStress { thickness: 0.7 },
            Idealization::Axisymmetric,
        ] {
            let axi = ideal == Idealization::Axisymmetric;
            let x0 = if axi { 1.0 } else { 0.0 };
            let mesh = distorted_quads(kind, x0, [3, 2], 7);
            // constant strain: any linear field in the plane; u_r = a r, u_z = d z + e in
            // axisymmetry (the linear fields with constant strain that satisfy equilibrium)
            let exact = |p: [f64; 2]| -> [f64; 2] {
                if axi {
                    [1e-3 * p[0], -2e-3 * p[1] + 1e-4]
                } else {
                    [
                        1e-3 * p[0] + 4e-4 * p[1] + 1e-4,
                        -3e-4 * p[0] - 2e-3 * p[1] - 2e-4,
                    ]
                }
            };
            let mut supports = Supports::new();
            for (node, &p) in mesh.nodes().iter().enumerate() {
                if on_box_boundary(p, x0) {
                    let u = exact(p);
                    supports.prescribe(&[node], Component::X, u[0]).unwrap();
                    supports.prescribe(&[node], Component::Y, u[1]).unwrap();
                }
            }
            let model =
                LinearElasticModel::new(mesh.clone(), ideal, &[(0, material)], supports).unwrap();
            let u = model.solve(1.0).unwrap();
            for (node, &p) in mesh.nodes().iter().enumerate() {
                let want = exact(p);
                for c in 0..2 {
                    // round-off of the solve on O(1e-3) values
                    assert!(
                        (u[node][c] - want[c]).abs() < 1e-12 * 1e-2,
                        "{kind:?} {ideal:?} node {node}: {:?} vs {want:?}",
                        u[node]
                    );
                }
            }
            // the stress of the constant strain, at every stress point
            let eps = if axi {
                [1e-3, -2e-3, 0.0, 1e-3]
            } else {
                [1e-3, -2e-3, 4e-4 - 3e-4, 0.0]
            };
            let d = material.elasticity(&ideal);
            let m = ideal.strain_size();
            let want: Vec<f64> = (0..m)
                .map(|r| (0..m).map(|k| d[(r, k)] * eps[k]).sum())
                .collect();
            for points in model.stresses(&u).unwrap() {
                for (_, s) in points {
                    for r in 0..3 {
                        assert!(
                            (s[r] - want[r]).abs() < 1e-12 * 1.0,
                            "{kind:?} {ideal:?}: σ {s:?} vs {want:?}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn issue_35_hexahedron_patch_tests_works() {
    let material = Material::new(100.0, 0.3, 0.0).unwrap();
    let g = [[1e-3, 2e-4, -3e-4], [5e-4, -2e-3, 1e-4], [0.0, 7e-4, 4e-4]];
    let exact = |p: [f64; 3]| -> [f64; 3] {
        core::array::from_fn(|i| g[i][0] * p[0] + g[i][1] * p[1] + g[i][2] * p[2] + 1e-4)
    };
    for kind in [SolidKind::Hex8, SolidKind::Hex20] {
        let mesh = distorted_hexes(kind, 2, 11);
        let mut supports = Supports::new();
        for (node, &p) in mesh.nodes().iter().enumerate() {
            if p.iter().any(|v| v.abs() < 1e-9 || (v - 1.0).abs() < 1e-9) {
                let u = exact(p);
                for (c, comp) in Component::all::<3>().into_iter().enumerate() {
                    supports.prescribe(&[node], comp, u[c]).unwrap();
                }
            }
        }
        let model = SolidModel::new(mesh.clone(), &[(0, material)], supports).unwrap();
        let u = model.solve(1.0).unwrap();
        for (node, &p) in mesh.nodes().iter().enumerate() {
            let want = exact(p);
            for c in 0..3 {
                // round-off of the solve on O(1e-3) values
                assert!(
                    (u[node][c] - want[c]).abs() < 1e-12 * 1e-2,
                    "{kind:?} node {node}"
                );
            }
        }
        let (lambda, mu) = (100.0 * 0.3 / (1.3 * 0.4), 100.0 / 2.6);
        let e = [
            g[0][0],
            g[1][1],
            g[2][2],
            0.5 * (g[0][1] + g[1][0]),
            0.5 * (g[1][2] + g[2][1]),
            0.5 * (g[2][0] + g[0][2]),
        ];
        let tr = e[0] + e[1] + e[2];
        let want: [f64; 6] = core::array::from_fn(|k| {
            if k < 3 {
                lambda * tr + 2.0 * mu * e[k]
            } else {
                2.0 * mu * e[k]
            }
        });
        for points in model.stresses(&u).unwrap() {
            for (_, s) in points {
                for k in 0..6 {
                    assert!(
                        (s[k] - want[k]).abs() < 1e-12,
                        "{kind:?}: {s:?} vs {want:?}"
                    );
                }
            }
        }
    }
}

fn reference_nodes_2d(el: &dyn Element<2>) -> Vec<[f64; 2]> {
    let corners = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
    let mut out = corners.to_vec();
    if el.node_count() >= 8 {
        for k in 0..4 {
            let (a, b) = (corners[k], corners[(k + 1) % 4]);
            out.push([0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]);
        }
    }
    if el.node_count() == 9 {
        out.push([0.0, 0.0]);
    }
    out
}

fn reference_nodes_3d(el: &dyn Element<3>) -> Vec<[f64; 3]> {
    let c = [
        [-1.0, -1.0, -1.0],
        [1.0, -1.0, -1.0],
        [1.0, 1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
        [1.0, -1.0, 1.0],
        [1.0, 1.0, 1.0],
        [-1.0, 1.0, 1.0],
    ];
    let mut out = c.to_vec();
    if el.node_count() == 20 {
        for [a, b] in fem_core::element::hex20::EDGES {
            out.push(core::array::from_fn(|d| 0.5 * (c[a][d] + c[b][d])));
        }
    }
    out
}

/// Kronecker property `N_i(x_j) = δ_ij`, partition of unity, and the derivatives against
/// central differences (step 1e-6: truncation `h² |N'''| / 6 ≈ 1e-12`, round-off ≈ 1e-10).
#[test]
fn issue_35_shape_functions_works() {
    let quads: [&dyn Element<2>; 3] = [&Quad4, &Quad8, &Quad9];
    for el in quads {
        let n = el.node_count();
        let (mut v, mut dv) = (vec![0.0; n], vec![[0.0; 2]; n]);
        for (j, xj) in reference_nodes_2d(el).into_iter().enumerate() {
            el.shape(xj, &mut v, &mut dv);
            for (i, vi) in v.iter().enumerate() {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((vi - want).abs() < 1e-14, "{el:?} N_{i}(x_{j}) = {vi}");
            }
        }
        let xi = [0.31, -0.57];
        el.shape(xi, &mut v, &mut dv);
        assert!((v.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        for a in 0..2 {
            let (mut p, mut m) = (xi, xi);
            p[a] += 1e-6;
            m[a] -= 1e-6;
            let (mut vp, mut vm, mut d) = (vec![0.0; n], vec![0.0; n], vec![[0.0; 2]; n]);
            el.shape(p, &mut vp, &mut d);
            el.shape(m, &mut vm, &mut d);
            for i in 0..n {
                assert!(
                    ((vp[i] - vm[i]) / 2e-6 - dv[i][a]).abs() < 1e-8,
                    "{el:?} {i} {a}"
                );
            }
        }
    }
    let hexes: [&dyn Element<3>; 2] = [&Hex8, &Hex20];
    for el in hexes {
        let n = el.node_count();
        let (mut v, mut dv) = (vec![0.0; n], vec![[0.0; 3]; n]);
        for (j, xj) in reference_nodes_3d(el).into_iter().enumerate() {
            el.shape(xj, &mut v, &mut dv);
            for (i, vi) in v.iter().enumerate() {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((vi - want).abs() < 1e-14, "{el:?} N_{i}(x_{j}) = {vi}");
            }
        }
        let xi = [0.31, -0.57, 0.2];
        el.shape(xi, &mut v, &mut dv);
        assert!((v.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        for a in 0..3 {
            let (mut p, mut m) = (xi, xi);
            p[a] += 1e-6;
            m[a] -= 1e-6;
            let (mut vp, mut vm, mut d) = (vec![0.0; n], vec![0.0; n], vec![[0.0; 3]; n]);
            el.shape(p, &mut vp, &mut d);
            el.shape(m, &mut vm, &mut d);
            for i in 0..n {
                assert!(
                    ((vp[i] - vm[i]) / 2e-6 - dv[i][a]).abs() < 1e-8,
                    "{el:?} {i} {a}"
                );
            }
        }
    }
}

/// Full integration: the stiffness is symmetric, positive semi-definite, and its kernel is
/// exactly the rigid modes (3 in the plane, 6 in space; no hourglass mode).
#[test]
fn issue_35_stiffness_kernel_is_the_rigid_modes_works() {
    let material = Material::new(210.0, 0.3, 0.0).unwrap();
    let mut k = DMatrix::zeros(0, 0);
    for kind in [ElementKind::Quad4, ElementKind::Quad8, ElementKind::Quad9] {
        let mesh = distorted_quads(kind, 0.0, [1, 1], 3);
        let coords: Vec<[f64; 2]> = mesh.element(0).iter().map(|&n| mesh.nodes()[n]).collect();
        kind.element::<2>()
            .unwrap()
            .stiffness_into(0, &coords, &material, &Idealization::PlaneStrain, &mut k)
            .unwrap();
        assert!((&k - k.transpose()).amax() < 1e-12 * k.amax());
        let eig = k.clone().symmetric_eigen().eigenvalues;
        let zero = eig.iter().filter(|v| v.abs() < 1e-9 * k.amax()).count();
        assert_eq!(zero, 3, "{kind:?}: {eig}");
        assert!(eig.iter().all(|v| *v > -1e-9 * k.amax()));
    }
    for kind in [SolidKind::Hex8, SolidKind::Hex20] {
        let mesh = distorted_hexes(kind, 1, 3);
        let mut nodes = mesh.nodes().to_vec();
        // a skewed single element (the box corners are on the boundary and stay put)
        for p in &mut nodes {
            p[0] += 0.2 * p[1] * p[2];
        }
        let coords: Vec<[f64; 3]> = mesh.element(0).iter().map(|&n| nodes[n]).collect();
        kind.element::<3>()
            .unwrap()
            .stiffness_into(0, &coords, &material, &(), &mut k)
            .unwrap();
        assert!((&k - k.transpose()).amax() < 1e-12 * k.amax());
        let eig = k.clone().symmetric_eigen().eigenvalues;
        let zero = eig.iter().filter(|v| v.abs() < 1e-9 * k.amax()).count();
        assert_eq!(zero, 6, "{kind:?}");
        assert!(eig.iter().all(|v| *v > -1e-9 * k.amax()));
    }
}

/// `∫ r dA` of a polygon (straight sides), by the shoelace formula for its first moment.
fn polygon_first_moment(p: &[[f64; 2]]) -> (f64, f64) {
    let (mut area, mut moment) = (0.0, 0.0);
    for k in 0..p.len() {
        let (a, b) = (p[k], p[(k + 1) % p.len()]);
        let cross = a[0] * b[1] - b[0] * a[1];
        area += 0.5 * cross;
        moment += cross * (a[0] + b[0]) / 6.0;
    }
    (area, moment)
}

/// The consistent mass: symmetric, positive definite, total `ρ V` (or `ρ t A`, or the
/// axisymmetric `∫ ρ r dA` per radian, i.e. `2π ∫ ρ r dA` for the ring); HRZ lumping positive
/// with the same total.
#[test]
fn issue_35_mass_totals_and_definiteness_works() {
    let density = 2.5;
    for kind in [
        ElementKind::Tri3,
        ElementKind::Tri6,
        ElementKind::Quad4,
        ElementKind::Quad8,
        ElementKind::Quad9,
    ] {
        let mesh = if matches!(kind, ElementKind::Tri3 | ElementKind::Tri6) {
            let spec = RectangleSpec {
                kind,
                ..RectangleSpec::new([1.0, 3.0], [1.0, 2.0], 1, 1)
            };
            rectangle(&spec).unwrap()
        } else {
            distorted_quads(kind, 1.0, [2, 1], 5)
        };
        for ideal in [
            Idealization::PlaneStrain,
            Idealization::PlaneStress { thickness: 0.7 },
            Idealization::Axisymmetric,
        ] {
            for e in 0..mesh.element_count() {
                let cell = mesh.element(e);
                let coords: Vec<[f64; 2]> = cell.iter().map(|&n| mesh.nodes()[n]).collect();
                let el = kind.element::<2>().unwrap();
                let mut m = DMatrix::zeros(0, 0);
                el.mass_into(e, &coords, density, &ideal, &mut m).unwrap();
                let corners = &coords[..kind.corner_count()];
                let (area, moment) = polygon_first_moment(corners);
                let want = density
                    * match ideal {
                        Idealization::PlaneStrain => area,
                        Idealization::PlaneStress { thickness } => thickness * area,
                        _ => moment,
                    };
                // one component's block sums to the mass (Σ N_i = 1)
                let total: f64 = (0..cell.len())
                    .flat_map(|a| (0..cell.len()).map(move |b| (a, b)))
                    .map(|(a, b)| m[(2 * a, 2 * b)])
                    .sum();
                // round-off of the rule's sums
                assert!((total - want).abs() < 1e-13 * want, "{kind:?} {ideal:?}");
                assert!((&m - m.transpose()).amax() < 1e-15 * m.amax());
                assert!(
                    m.clone().cholesky().is_some(),
                    "{kind:?} {ideal:?}: not SPD"
                );
                let mut lumped = vec![0.0; 2 * cell.len()];
                el.lumped_mass_into(e, &coords, density, &ideal, &mut lumped)
                    .unwrap();
                assert!(lumped.iter().all(|v| *v > 0.0), "{kind:?}: {lumped:?}");
                let sum: f64 = lumped.iter().step_by(2).sum();
                assert!((sum - want).abs() < 1e-13 * want);
            }
        }
    }
    let tet10: [[f64; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 3.0, 0.0],
        [0.0, 0.0, 1.5],
    ];
    let mut c10 = tet10.to_vec();
    for [a, b] in fem_core::solid::TET_EDGES {
        c10.push(core::array::from_fn(|d| 0.5 * (tet10[a][d] + tet10[b][d])));
    }
    let hex = distorted_hexes(SolidKind::Hex20, 2, 9);
    let hex8 = distorted_hexes(SolidKind::Hex8, 2, 9);
    let mut total_hex = [0.0; 2];
    for (slot, mesh) in [&hex8, &hex].into_iter().enumerate() {
        for e in 0..mesh.element_count() {
            let coords: Vec<[f64; 3]> = mesh.element(e).iter().map(|&n| mesh.nodes()[n]).collect();
            let el = mesh.kind().element::<3>().unwrap();
            let mut m = DMatrix::zeros(0, 0);
            el.mass_into(e, &coords, density, &(), &mut m).unwrap();
            let n = coords.len();
            total_hex[slot] += (0..n)
                .flat_map(|a| (0..n).map(move |b| (a, b)))
                .map(|(a, b)| m[(3 * a, 3 * b)])
                .sum::<f64>();
            assert!(m.clone().cholesky().is_some());
            let mut lumped = vec![0.0; 3 * n];
            el.lumped_mass_into(e, &coords, density, &(), &mut lumped)
                .unwrap();
            assert!(lumped.iter().all(|v| *v > 0.0));
        }
        // the unit box's volume whatever the interior distortion; round-off over 8 elements
        assert!((total_hex[slot] - density).abs() < 1e-13);
    }
    let cases: [(&dyn Element<3>, Vec<[f64; 3]>, f64); 1] = [(&Tet10, c10, 1.5)];
    for (el, coords, volume) in cases {
        let mut m = DMatrix::zeros(0, 0);
        el.mass_into(0, &coords, density, &(), &mut m).unwrap();
        let n = coords.len();
        let total: f64 = (0..n)
            .flat_map(|a| (0..n).map(move |b| (a, b)))
            .map(|(a, b)| m[(3 * a, 3 * b)])
            .sum();
        assert!((total - density * volume).abs() < 1e-13 * density * volume);
        assert!(m.clone().cholesky().is_some());
        // HRZ keeps Tet10's corners positive where row sums are negative
        let row0: f64 = (0..n).map(|b| m[(0, 3 * b)]).sum();
        assert!(
            row0 < 0.0,
            "the row sum of a Tet10 corner is negative: {row0}"
        );
        let mut lumped = vec![0.0; 3 * n];
        el.lumped_mass_into(0, &coords, density, &(), &mut lumped)
            .unwrap();
        assert!(lumped.iter().all(|v| *v > 0.0));
    }
}
