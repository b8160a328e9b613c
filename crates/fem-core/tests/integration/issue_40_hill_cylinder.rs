//! Hill's thick cylinder under internal pressure, plane strain, von Mises with perfect
//! plasticity (Hill 1950, *The Mathematical Theory of Plasticity*, ch. V §2; also Chakrabarty,
//! *Theory of Plasticity*, §5.3), with `PlasticModel` and `plastic::newton` (issue 40).
//!
//! Sketch: a quarter ring `a = 1 ≤ r ≤ b = 2` of P2 triangles (curved), symmetry planes on
//! rollers (`u_y = 0` on `y = 0`, `u_x = 0` on `x = 0`), the pressure `p` on `r = a`.
//! E = 1000, ν = 0.49 (nearly incompressible: Hill's solution takes the axial stress as the
//! mean of the in-plane ones, exact at ν = ½), shear yield stress `k = 1`
//! (`DruckerPrager::von_mises`). With the plastic zone `a ≤ r ≤ c`:
//!
//! ```text
//! p(c) = k (2 ln(c / a) + 1 − c² / b²)      first yield p = k (1 − a²/b²) = 0.75 k
//! limit pressure (c = b):  p_L = 2 k ln(b / a) = 1.3863 k
//! ```
//!
//! Checks: the elastic–plastic radius at three pressures within 1 % (the radius is read
//! between the outermost yielded quadrature point and the innermost elastic one, ~0.3 % of
//! `c` apart on this mesh); Newton converges in at most 8 iterations per load step with the
//! residual falling quadratically; the limit pressure within 1 % (the path stops converging
//! between 0.99 p_L and 1.01 p_L).

use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::plastic::newton::{self, NewtonReport, NewtonSettings};
use fem_core::plastic::{ConstitutivePoint, DruckerPrager, PlasticModel};
use fem_core::vtk::Field;
use fem_core::{
    Component, ElementKind, FemError, Idealization, LinearElasticModel, Material, Mesh, Structure,
    Supports,
};
use std::sync::Arc;

const A: f64 = 1.0;
const B: f64 = 2.0;
const K: f64 = 1.0;

/// The quarter ring: a rectangle in `(r, t)` mapped by `(r cos t, r sin t)`.
fn quarter_ring(radial: usize, around: usize) -> Mesh {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([A, B], [0.0, std::f64::consts::FRAC_PI_2], radial, around)
    };
    let flat = rectangle(&spec).unwrap();
    let nodes = flat
        .nodes()
        .iter()
        .map(|&[r, t]| [r * t.cos(), r * t.sin()])
        .collect();
    let mut mesh = Mesh::new(
        nodes,
        ElementKind::Tri6,
        flat.connectivity().to_vec(),
        flat.regions().to_vec(),
    )
    .unwrap();
    for name in ["left", "bottom", "top"] {
        mesh.add_node_set(name, flat.node_set(name).unwrap().to_vec())
            .unwrap();
    }
    mesh.add_edge_set("left", flat.edge_set("left").unwrap().to_vec())
        .unwrap();
    mesh
}

fn cylinder() -> PlasticModel<2> {
    let mesh = quarter_ring(100, 3);
    let (bottom, top) = (
        mesh.node_set("bottom").unwrap().to_vec(),
        mesh.node_set("top").unwrap().to_vec(),
    );
    let mut supports = Supports::new();
    supports.fix(&bottom, Component::Y).fix(&top, Component::X);
    let (young, poisson) = (1000.0, 0.49);
    let material = Material::new(young, poisson, 0.0).unwrap();
    let mut elastic =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, material)], supports)
            .unwrap();
    // the pressure pushes the inner surface outwards: t = p x / |x| (reference p = k)
    elastic
        .add_edge_traction("left", |[x, y]| {
            let r = x.hypot(y);
            [K * x / r, K * y / r]
        })
        .unwrap();
    let law: Arc<dyn ConstitutivePoint> =
        Arc::new(DruckerPrager::von_mises(young, poisson, K).unwrap());
    PlasticModel::new(elastic, &[(0, law)]).unwrap()
}

/// Hill's elastic–plastic radius at pressure `p` (bisection on `p(c)`, increasing in `c`).
fn hill_radius(p: f64) -> f64 {
    let pressure = |c: f64| K * (2.0 * (c / A).ln() + 1.0 - c * c / (B * B));
    let (mut lo, mut hi) = (A, B);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if pressure(mid) < p {
            lo = mid
        } else {
            hi = mid
        }
    }
    0.5 * (lo + hi)
}

/// The radius between the outermost yielded point and the innermost elastic one beyond it.
fn plastic_radius(body: &PlasticModel<2>) -> f64 {
    let positions = body.point_positions().unwrap();
    let states = body.committed_states();
    let radius = |k: usize| positions[k][0].hypot(positions[k][1]);
    let yielded = (0..states.len()).filter(|&k| states[k].equivalent_plastic_strain > 0.0);
    let outer = yielded.map(radius).fold(A, f64::max);
    let elastic = (0..states.len()).filter(|&k| states[k].equivalent_plastic_strain == 0.0);
    let inner = elastic.map(radius).filter(|&r| r > outer).fold(B, f64::min);
    0.5 * (outer + inner)
}

/// Every converged step took at most 8 solves, and past its largest residual (the first
/// solve of a step is with the tangent of the last converged state, which may raise it),
/// where the residual is below 1e-2, it falls quadratically, `r_{k+1} ≤ 10 r_k²` (relative residuals; the factor 10 absorbs the constant
/// of the rate), down to the round-off floor of the assembly: the purely elastic steps land
/// at 2–4e-11 after their one solve, so a residual below 1e-10 is at the floor.
fn check_quadratic(report: &NewtonReport) {
    for step in report.converged_steps() {
        let r = &step.residuals;
        assert!(r.len() - 1 <= 8, "λ = {}: {r:?}", step.load_factor);
        let peak = (0..r.len()).fold(0, |m, k| if r[k] > r[m] { k } else { m });
        for w in r[peak..].windows(2) {
            if w[0] < 1e-2 {
                let quadratic = w[1] <= 10.0 * w[0] * w[0] || w[1] < 1e-10;
                assert!(quadratic, "λ = {}: {r:?}", step.load_factor);
            }
        }
    }
}

#[test]
fn issue_40_hill_thick_cylinder_works() {
    let mut body = cylinder();
    let mut u = vec![0.0; body.dof_count()];
    let mut lambda = 0.0;
    for p in [0.9, 1.1, 1.3] {
        let settings = NewtonSettings::with_steps(4);
        let report = newton::solve(&mut body, &mut u, lambda, p, &settings).unwrap();
        lambda = p;
        check_quadratic(&report);
        let (c, expected) = (plastic_radius(&body), hill_radius(p * K));
        assert!(
            (c - expected).abs() < 0.01 * expected,
            "p = {p}: c = {c}, Hill {expected}"
        );
    }
    // per-element outputs at p = 1.3 (c = 1.6): the innermost elements have yielded
    // throughout, the outermost not at all; they go to VTK as cell data
    let out = body.element_outputs();
    let mesh = body.elastic().mesh();
    let mean_radius = |e: usize| {
        let nodes = mesh.element(e);
        let sum: f64 = nodes
            .iter()
            .map(|&n| mesh.nodes()[n][0].hypot(mesh.nodes()[n][1]))
            .sum();
        sum / nodes.len() as f64
    };
    for e in 0..mesh.element_count() {
        let r = mean_radius(e);
        if r < 1.5 {
            assert_eq!(out.yielding[e], 1.0, "element {e} at r = {r}");
            assert!(out.equivalent_plastic_strain[e] > 0.0);
        } else if r > 1.7 {
            assert_eq!(out.yielding[e], 0.0, "element {e} at r = {r}");
            assert_eq!(out.equivalent_plastic_strain[e], 0.0);
        }
    }
    let path =
        std::env::temp_dir().join(format!("fem_core_issue_40_hill_{}.vtu", std::process::id()));
    let displacements = body.nodal_displacements(&u);
    fem_core::vtk::write_vtu(
        &path,
        mesh,
        &[("u", Field::Vector(&displacements))],
        &[
            (
                "equivalent_plastic_strain",
                Field::Scalar(&out.equivalent_plastic_strain),
            ),
            ("yielding", Field::Scalar(&out.yielding)),
            ("stress", Field::SymTensor(&out.stress)),
        ],
    )
    .unwrap();
    std::fs::remove_file(&path).unwrap();
    // on to 1.01 p_L: the path must stop converging between 0.99 p_L and 1.01 p_L
    let limit = 2.0 * K * (B / A).ln();
    let settings = NewtonSettings {
        steps: 4,
        max_cuts: 8,
        max_iterations: 12,
        ..NewtonSettings::default()
    };
    let err = newton::solve(&mut body, &mut u, lambda, 1.01 * limit, &settings).unwrap_err();
    let FemError::NotConverged {
        converged_load_factor,
        report,
        ..
    } = err
    else {
        panic!("{err:?}")
    };
    check_quadratic(&report);
    assert!(
        converged_load_factor > 0.99 * limit,
        "converged only to {converged_load_factor}, p_L = {limit}"
    );
}
