//! Patch tests of the P1 and P2 triangles in plane strain, plane stress and axisymmetry.
//!
//! Source: B. M. Irons, A. Razzaque, "Experience with the patch test for convergence of finite
//! elements" (1972); O. C. Zienkiewicz, R. L. Taylor, J. Z. Zhu, *The Finite Element Method:
//! Its Basis and Fundamentals*, 7th ed., §9.3 (patch tests A, B and C).
//!
//! ```text
//!   y,z                                     Dirichlet patch (test "B"): every boundary node gets
//!    ^  +------+------+------+------+        the exact linear field u = a + B x (plane) or
//!    |  |  \  /    \    /   \   /   |        u_r = c r, u_z = d z + e (axisymmetric); interior
//!    |  +---*-------*--------*------+        nodes * are moved at random (P2: mid-side nodes at
//!    |  |  /  \    /  \     /  \    |        the middle of the straight sides, or — one case —
//!    |  +------+------+------+------+        moved too, curving the interior sides).
//!    +-------------------------------> x,r   Traction patch (test "C"): σ n on every side,
//!                                            3 supports against rigid motion (plane stress).
//! ```
//!
//! Parameters: E = 210, ν = 0.3 (plane stress thickness 0.5). Plane domain [0, 2] × [0, 1],
//! axisymmetric domain [0, 2] × [−1, 1] (its left side is the axis r = 0), 5 × 4 cells. The
//! linear field must come back at every interior node to 1e-12 relative, with the matching
//! constant stress at every quadrature point.

use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, Stress, Supports,
};

use crate::common;

/// `nx × ny` cells on `[x0, x1] × [y0, y1]` (see [`common::grid`]).
fn grid(
    kind: ElementKind,
    [x0, x1]: [f64; 2],
    [y0, y1]: [f64; 2],
    n: [usize; 2],
    distort: f64,
    curve: f64,
    seed: u64,
) -> Mesh {
    common::grid(kind, n, distort, curve, seed, |[s, t]| {
        [x0 + (x1 - x0) * s, y0 + (y1 - y0) * t]
    })
}

// ---------------------------------------------------------------------------------------------

/// Round-off allowance of every patch: the solve of a few hundred well-conditioned unknowns
/// (κ(K) ≲ 1e4 on these meshes) loses about 4 digits from 1e-16.
const PATCH_TOL: f64 = 1e-12;

fn material() -> Material {
    Material::new(210.0, 0.3, 0.0).unwrap()
}

/// `D ε` with the crate's out-of-plane conventions (plane strain: σ_zz = ν (σ_xx + σ_yy)).
fn stress_of(strain: [f64; 4], idealization: &Idealization) -> Stress {
    let d = material().elasticity(idealization);
    let m = idealization.strain_size();
    let mut s = [0.0; 4];
    for (r, sr) in s.iter_mut().enumerate().take(m) {
        *sr = (0..m).map(|k| d[(r, k)] * strain[k]).sum();
    }
    if let Idealization::PlaneStrain = idealization {
        s[3] = 0.3 * (s[0] + s[1]);
    }
    s
}

/// Imposes `exact` on the boundary nodes, solves, and checks interior nodes and stresses.
fn dirichlet_patch(mesh: Mesh, idealization: Idealization, exact: impl Fn([f64; 2]) -> [f64; 2]) {
    let strain_scale = 4e-3;
    let mut supports = Supports::new();
    for &n in mesh.node_set("boundary").unwrap() {
        let u = exact(mesh.nodes()[n]);
        supports.prescribe(&[n], Component::X, u[0]).unwrap();
        supports.prescribe(&[n], Component::Y, u[1]).unwrap();
    }
    let interior = mesh.node_set("interior").unwrap().to_vec();
    assert!(!interior.is_empty());
    let model = LinearElasticModel::new(mesh, idealization, &[(0, material())], supports).unwrap();
    let u = model.solve(0.0).unwrap();
    let scale = u.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    for &n in &interior {
        let x = model.mesh().nodes()[n];
        let e = exact(x);
        for c in 0..2 {
            assert!(
                (u[n][c] - e[c]).abs() <= PATCH_TOL * scale,
                "{idealization:?} {:?}: node {n} at {x:?}: u = {:?}, exact {e:?}",
                model.mesh().kind(),
                u[n]
            );
        }
    }
    // Strain of the exact field by central differences (exact for a linear field up to
    // round-off ~1e-16/1e-3 relative).
    let h = 1e-3;
    let x = [1.0, 0.3];
    let g = |a: usize, b: usize| {
        let (mut xp, mut xm) = (x, x);
        xp[b] += h;
        xm[b] -= h;
        (exact(xp)[a] - exact(xm)[a]) / (2.0 * h)
    };
    let hoop = if let Idealization::Axisymmetric = idealization {
        exact(x)[0] / x[0]
    } else {
        0.0
    };
    let expected = stress_of([g(0, 0), g(1, 1), g(0, 1) + g(1, 0), hoop], &idealization);
    let s_scale = expected.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(s_scale > 0.1 * 210.0 * strain_scale);
    for pts in model.stresses(&u).unwrap() {
        for (p, s) in pts {
            for k in 0..4 {
                // The reference stress itself carries ~1e-13 relative from the differences.
                assert!(
                    (s[k] - expected[k]).abs() <= 1e-11 * s_scale,
                    "{idealization:?}: σ at {p:?} = {s:?}, expected {expected:?}"
                );
            }
        }
    }
}

/// A general affine field: translation plus a non-symmetric gradient (stretch, shear, rotation).
fn affine(x: [f64; 2]) -> [f64; 2] {
    let a = [1e-3, -2e-3];
    let b = [[2e-3, 1e-3], [-3e-3, -1.5e-3]];
    [
        a[0] + b[0][0] * x[0] + b[0][1] * x[1],
        a[1] + b[1][0] * x[0] + b[1][1] * x[1],
    ]
}

/// The admissible linear field of axisymmetry: u_r = c r, u_z = d z + e.
fn radial(x: [f64; 2]) -> [f64; 2] {
    [2e-3 * x[0], -1e-3 * x[1] + 5e-4]
}

const PLANE: [Idealization; 2] = [
    Idealization::PlaneStrain,
    Idealization::PlaneStress { thickness: 0.5 },
];

#[test]
fn dirichlet_patch_p1_works() {
    for ideal in PLANE {
        let mesh = grid(
            ElementKind::Tri3,
            [0.0, 2.0],
            [0.0, 1.0],
            [5, 4],
            0.25,
            0.0,
            7,
        );
        dirichlet_patch(mesh, ideal, affine);
    }
    let mesh = grid(
        ElementKind::Tri3,
        [0.0, 2.0],
        [-1.0, 1.0],
        [5, 4],
        0.25,
        0.0,
        11,
    );
    dirichlet_patch(mesh, Idealization::Axisymmetric, radial);
}

#[test]
fn dirichlet_patch_p2_works() {
    for ideal in PLANE {
        let mesh = grid(
            ElementKind::Tri6,
            [0.0, 2.0],
            [0.0, 1.0],
            [5, 4],
            0.25,
            0.0,
            7,
        );
        dirichlet_patch(mesh, ideal, affine);
    }
    let mesh = grid(
        ElementKind::Tri6,
        [0.0, 2.0],
        [-1.0, 1.0],
        [5, 4],
        0.25,
        0.0,
        11,
    );
    dirichlet_patch(mesh, Idealization::Axisymmetric, radial);
}

/// Curved interior P2 sides: the isoparametric map still reproduces linear fields exactly,
/// and the rules integrate `∫ ∇N_i dA` (degree 2 in ξ) and its axisymmetric analogue (degree
/// 4) exactly, so the patch passes to round-off.
#[test]
fn dirichlet_patch_p2_curved_works() {
    for ideal in PLANE {
        let mesh = grid(
            ElementKind::Tri6,
            [0.0, 2.0],
            [0.0, 1.0],
            [5, 4],
            0.2,
            0.12,
            3,
        );
        dirichlet_patch(mesh, ideal, affine);
    }
    let mesh = grid(
        ElementKind::Tri6,
        [0.0, 2.0],
        [-1.0, 1.0],
        [5, 4],
        0.2,
        0.12,
        5,
    );
    dirichlet_patch(mesh, Idealization::Axisymmetric, radial);
}

/// Test "C": the boundary carries the tractions σ n of a constant stress; three supports
/// remove the rigid motions; the whole displacement field is then determined.
#[test]
fn traction_patch_plane_stress_works() {
    let t = 0.5;
    let ideal = Idealization::PlaneStress { thickness: t };
    let m = material();
    let (e, nu) = (m.young(), m.poisson());
    let sigma = [3.0, -1.0, 0.7];
    let strain = [
        (sigma[0] - nu * sigma[1]) / e,
        (sigma[1] - nu * sigma[0]) / e,
        sigma[2] * 2.0 * (1.0 + nu) / e,
    ];
    // u(0, 0) = 0, v(2, 0) = 0: u = ε_xx x + γ y, v = ε_yy y.
    let exact = |x: [f64; 2]| [strain[0] * x[0] + strain[2] * x[1], strain[1] * x[1]];
    for kind in [ElementKind::Tri3, ElementKind::Tri6] {
        let mesh = grid(kind, [0.0, 2.0], [0.0, 1.0], [5, 4], 0.25, 0.0, 13);
        let corner = |x: [f64; 2]| {
            mesh.nodes()
                .iter()
                .position(|p| (p[0] - x[0]).hypot(p[1] - x[1]) < 1e-12)
                .unwrap()
        };
        let (bl, br) = (corner([0.0, 0.0]), corner([2.0, 0.0]));
        let mut supports = Supports::new();
        supports
            .fix(&[bl], Component::X)
            .fix(&[bl], Component::Y)
            .fix(&[br], Component::Y);
        let mut model = LinearElasticModel::new(mesh, ideal, &[(0, m)], supports).unwrap();
        let [sxx, syy, sxy] = sigma;
        model.add_edge_traction("bottom", |_| [-sxy, -syy]).unwrap();
        model.add_edge_traction("right", |_| [sxx, sxy]).unwrap();
        model.add_edge_traction("top", |_| [sxy, syy]).unwrap();
        model.add_edge_traction("left", |_| [-sxx, -sxy]).unwrap();
        let u = model.solve(1.0).unwrap();
        let scale = u.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for (n, x) in model.mesh().nodes().iter().enumerate() {
            let ex = exact(*x);
            for c in 0..2 {
                assert!(
                    (u[n][c] - ex[c]).abs() <= PATCH_TOL * scale,
                    "{kind:?}: node {n} at {x:?}: {:?} vs {ex:?}",
                    u[n]
                );
            }
        }
        for pts in model.stresses(&u).unwrap() {
            for (_, s) in pts {
                for k in 0..3 {
                    // Relative to the largest stress component, |σ_xx| = 3.
                    assert!(
                        (s[k] - sigma[k]).abs() <= PATCH_TOL * 3.0,
                        "{kind:?}: {s:?}"
                    );
                }
                assert_eq!(s[3], 0.0);
            }
        }
        // The reactions vanish: the tractions are self-equilibrated (round-off of Σ|f| ≈ 10).
        for (_, r) in model.reactions(&u, 1.0).unwrap() {
            assert!(r.abs() < 1e-12 * 10.0, "{kind:?}: reaction {r}");
        }
    }
}
