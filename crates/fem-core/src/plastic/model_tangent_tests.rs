//! Unit tests of the tangent of a [`PlasticModel`] (issue 40): the symmetric part against the
//! exact (non-symmetric) consistent tangent of a non-associated law, on a strip load.

use super::newton::{self, NewtonSettings};
use super::{ConstitutivePoint, PlasticModel, TangentKind};
use crate::generate::{RectangleSpec, rectangle};
use crate::mesh::ElementKind;
use crate::{Component, Idealization, LinearElasticModel, Material, Structure, Supports};
use std::sync::Arc;

const YOUNG: f64 = 1000.0;
const POISSON: f64 = 0.3;

fn material(unit_weight: f64) -> Material {
    Material::new(YOUNG, POISSON, unit_weight).unwrap()
}

/// A strip load `q` on `0 ≤ x ≤ 0.5` of a block `[0, 2] × [0, 1]` (P2 triangles, base fixed,
/// sides on rollers), Drucker–Prager `φ = 30°`, `c = 1`, `θ` given, loaded to `q = 5 c`
/// (past first yield near `q = 3.5 c`, well below collapse, `N_c ≈ 30`) in 5 steps.
fn footing(
    dilatancy_angle: f64,
    kind: Option<TangentKind>,
) -> (PlasticModel<2>, newton::NewtonReport) {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 8, 4)
    };
    let mesh = rectangle(&spec).unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let sides: Vec<usize> = ["left", "right"]
        .iter()
        .flat_map(|s| mesh.node_set(s).unwrap().to_vec())
        .collect();
    let mut supports = Supports::new();
    supports
        .fix(&bottom, Component::X)
        .fix(&bottom, Component::Y);
    supports.fix(&sides, Component::X);
    let mut elastic = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, material(0.0))],
        supports,
    )
    .unwrap();
    elastic
        .add_edge_traction(
            "top",
            |[x, _]| if x < 0.5 { [0.0, -1.0] } else { [0.0, 0.0] },
        )
        .unwrap();
    let law: Arc<dyn ConstitutivePoint> = Arc::new(
        super::DruckerPrager::new(super::DruckerPragerParameters {
            young: YOUNG,
            poisson: POISSON,
            friction_angle: 30.0,
            dilatancy_angle,
            cohesion: 1.0,
            cone: super::ConeMatch::PlaneStrain,
        })
        .unwrap(),
    );
    let mut body = PlasticModel::new(elastic, &[(0, law)]).unwrap();
    if let Some(kind) = kind {
        body.set_tangent_kind(kind).unwrap();
    }
    let mut u = vec![0.0; body.dof_count()];
    let settings = NewtonSettings {
        steps: 5,
        max_iterations: 60,
        ..NewtonSettings::default()
    };
    let report = newton::solve(&mut body, &mut u, 0.0, 5.0, &settings).unwrap();
    (body, report)
}

/// The symmetric part of the tangent (the solver is a Cholesky): exact for the associated
/// law (`θ = φ`), whose steps converge quadratically in a few solves; an approximation for the
/// non-associated one (`θ = 0`), which still converges to the same tolerance, linearly (here
/// 15 and 34 solves in the two plastic steps against 3 and 5).
#[test]
fn issue_40_non_associated_flow_converges_on_the_symmetric_part() {
    let solves = |report: &newton::NewtonReport| -> Vec<usize> {
        report.steps.iter().map(|s| s.residuals.len() - 1).collect()
    };
    let (associated, report) = footing(30.0, None);
    assert_eq!(report.cuts, 0);
    let yielded = |body: &PlasticModel<2>| {
        body.committed_states()
            .iter()
            .filter(|s| s.equivalent_plastic_strain > 0.0)
            .count()
    };
    assert!(yielded(&associated) > 0, "the load must reach plasticity");
    let associated_solves = solves(&report);
    assert!(
        associated_solves.iter().all(|&n| n <= 8),
        "{associated_solves:?}"
    );
    for step in &report.steps {
        let r = &step.residuals;
        for w in r.windows(2).skip(1) {
            // quadratic past the first solve, to the round-off floor (1e-10)
            assert!(w[1] <= 10.0 * w[0] * w[0] || w[1] < 1e-10, "{r:?}");
        }
    }
    let (non_associated, report) = footing(0.0, Some(TangentKind::Symmetric));
    assert!(report.steps.iter().all(|s| s.converged), "no cut needed");
    assert!(yielded(&non_associated) > 0);
    let non_associated_solves = solves(&report);
    let total = |v: &[usize]| v.iter().sum::<usize>();
    assert!(
        total(&non_associated_solves) > 2 * total(&associated_solves),
        "{non_associated_solves:?} against {associated_solves:?}"
    );
}

/// The solves of each step.
fn solves(report: &newton::NewtonReport) -> Vec<usize> {
    report.steps.iter().map(|s| s.residuals.len() - 1).collect()
}

/// Quadratic convergence past the first solve of each step, `r_{k+1} ≤ 10 r_k²` (the
/// relative residuals are below 1, so a linear rate fails it), down to the round-off floor
/// (1e-10).
fn assert_quadratic(report: &newton::NewtonReport) {
    for step in &report.steps {
        let r = &step.residuals;
        for w in r.windows(2).skip(1) {
            assert!(w[1] <= 10.0 * w[0] * w[0] || w[1] < 1e-10, "{r:?}");
        }
    }
}

/// The exact tangent (sparse LU) is the default of a non-associated law, and its Newton on
/// the strip load with `θ = 0` is quadratic: at most 8 solves per step (measured 3 and 5 in
/// the plastic steps) where the symmetric part took 15 and 34. For the associated law the default is the Cholesky, and the LU of
/// the same (symmetric) matrix takes the same solves.
#[test]
fn issue_40_exact_tangent_converges_quadratically_for_non_associated_flow() {
    let time = std::time::Instant::now();
    let (body, report) = footing(0.0, None);
    let exact_time = time.elapsed();
    assert_eq!(body.tangent_kind(), TangentKind::Exact);
    assert_eq!(report.cuts, 0);
    assert!(report.steps.iter().all(|s| s.converged));
    let exact = solves(&report);
    assert!(exact.iter().all(|&n| n <= 8), "{exact:?}");
    assert_quadratic(&report);
    let time = std::time::Instant::now();
    let (_, report) = footing(0.0, Some(TangentKind::Symmetric));
    let symmetric_time = time.elapsed();
    let symmetric = solves(&report);
    eprintln!(
        "θ = 0: exact {exact:?} in {exact_time:?}, symmetric part {symmetric:?} in \
         {symmetric_time:?}"
    );

    let time = std::time::Instant::now();
    let (body, report) = footing(30.0, None);
    let cholesky_time = time.elapsed();
    assert_eq!(body.tangent_kind(), TangentKind::Symmetric);
    let cholesky = solves(&report);
    let time = std::time::Instant::now();
    let (_, report) = footing(30.0, Some(TangentKind::Exact));
    let lu_time = time.elapsed();
    assert_quadratic(&report);
    assert_eq!(
        solves(&report),
        cholesky,
        "the same matrix, the same Newton"
    );
    eprintln!("θ = φ: Cholesky {cholesky:?} in {cholesky_time:?}, LU in {lu_time:?}");
}

/// The LU solve of the exact tangent (non-symmetric after the plastic steps of `θ = 0`)
/// against a dense partial-pivoting LU of the same matrix (1e-12 relative: both are
/// backward stable and the strip's tangent is well conditioned at this load); the symmetric
/// part the body reports is `(K + Kᵀ)/2` of it.
#[test]
fn issue_40_exact_tangent_solve_matches_a_dense_lu() {
    let (mut body, _) = footing(0.0, None);
    crate::Nonlinear::update_tangent(&mut body).unwrap();
    let k = body.exact_tangent().unwrap().to_dense();
    let n = k.nrows();
    let asymmetry = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .fold(0.0_f64, |m, (i, j)| m.max((k[(i, j)] - k[(j, i)]).abs()));
    let scale = (0..n).fold(0.0_f64, |m, i| m.max(k[(i, i)].abs()));
    assert!(asymmetry > 1e-3 * scale, "{asymmetry} against {scale}");
    let lower = body.stiffness_matrix().unwrap().to_dense();
    for j in 0..n {
        for i in j..n {
            let sym = 0.5 * (k[(i, j)] + k[(j, i)]);
            assert!((lower[(i, j)] - sym).abs() <= 1e-12 * scale, "({i}, {j})");
        }
    }
    let b: Vec<f64> = (0..n)
        .map(|i| ((i * 37 % 101) as f64 - 50.0) / 50.0)
        .collect();
    let mut x = b.clone();
    body.solve_in_place(&mut x).unwrap();
    let dense =
        faer::linalg::solvers::Solve::solve(&k.partial_piv_lu(), faer::ColRef::from_slice(&b));
    let norm = dense.norm_l2();
    let error = (0..n)
        .map(|i| (x[i] - dense[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!(error <= 1e-12 * norm, "{error} against {norm}");
    // the stiffness version keeps rising across a change of kind (caches keyed on it)
    let version = body.stiffness_version();
    body.set_tangent_kind(TangentKind::Symmetric).unwrap();
    assert!(body.exact_tangent().is_none());
    assert!(body.stiffness_version() > version);
}

/// A singular exact tangent (here all zero) is an error naming the LU, never a NaN
/// displacement: either the factorisation or the solve refuses it.
#[test]
fn issue_40_singular_exact_tangent_is_an_error() {
    let (body, _) = footing(0.0, None);
    let mut exact = super::model_lu::ExactTangent::new(body.elastic().pattern()).unwrap();
    let n = body.dof_count();
    let mut b = vec![1.0; n];
    let result = exact.factor().and_then(|()| {
        exact.solve_many_in_place(faer::MatMut::from_column_major_slice_mut(&mut b, n, 1))
    });
    assert!(
        matches!(result, Err(crate::FemError::LinearAlgebra { .. })),
        "{result:?}"
    );
}
