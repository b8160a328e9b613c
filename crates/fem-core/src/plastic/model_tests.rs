//! Unit tests of [`PlasticModel`] and [`newton`] with linear-elastic points (issue 40): the
//! plastic body must reproduce the elastic model, keep its history honestly, and carry a
//! geostatic state in equilibrium.

use super::newton::{self, NewtonSettings};
use super::{ConstitutivePoint, LinearElasticPoint, PlasticModel, PointState, Voigt, VoigtMatrix};
use crate::generate::{Grading, Layer, RectangleSpec, rectangle};
use crate::mesh::ElementKind;
use crate::model::ModelSpace;
use crate::solid::generate::{box_mesh, lines};
use crate::space::Dim;
use crate::{Component, ElasticModel, FemError, Idealization, Material, Nonlinear, Structure};
use crate::{LinearElasticModel, SolidModel, Supports};
use std::sync::Arc;

const YOUNG: f64 = 1000.0;
const POISSON: f64 = 0.3;

fn elastic_point() -> Arc<dyn ConstitutivePoint> {
    Arc::new(LinearElasticPoint::new(YOUNG, POISSON).unwrap())
}

fn material(unit_weight: f64) -> Material {
    Material::new(YOUNG, POISSON, unit_weight).unwrap()
}

/// A rectangle `[x0, x0 + 2] × [0, 1]` of `kind`, bottom fixed, the right side pulled by a
/// prescribed `u_x = 0.01`, self-weight and a nodal force at the top left.
fn plane(kind: ElementKind, idealization: Idealization, x0: f64) -> LinearElasticModel {
    let spec = RectangleSpec {
        kind,
        ..RectangleSpec::new([x0, x0 + 2.0], [0.0, 1.0], 4, 3)
    };
    let mesh = rectangle(&spec).unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let right: Vec<usize> = mesh.node_set("right").unwrap().to_vec();
    let right: Vec<usize> = right.into_iter().filter(|n| !bottom.contains(n)).collect();
    let top_left = mesh.node_set("top_left").unwrap()[0];
    let mut supports = Supports::new();
    supports
        .fix(&bottom, Component::X)
        .fix(&bottom, Component::Y);
    supports.prescribe(&right, Component::X, 0.01).unwrap();
    let mut model =
        LinearElasticModel::new(mesh, idealization, &[(0, material(20.0))], supports).unwrap();
    model.add_self_weight().unwrap();
    model.add_nodal_force(top_left, [3.0, -1.0]).unwrap();
    model
}

/// A box `[0, 2] × [0, 1] × [0, 1]` of `kind`, base fixed, `x1` pulled by `u_x = 0.01`,
/// self-weight.
fn solid(kind: ElementKind) -> SolidModel {
    let mesh = box_mesh(
        &lines(0.0, 2.0, 3),
        &lines(0.0, 1.0, 2),
        &lines(0.0, 1.0, 2),
        kind,
    )
    .unwrap();
    let base = mesh.node_set("z0").unwrap().to_vec();
    let x1: Vec<usize> = mesh.node_set("x1").unwrap().to_vec();
    let x1: Vec<usize> = x1.into_iter().filter(|n| !base.contains(n)).collect();
    let mut supports = Supports::new();
    for c in [Component::X, Component::Y, Component::Z] {
        supports.fix(&base, c);
    }
    supports.prescribe(&x1, Component::X, 0.01).unwrap();
    let mut model = SolidModel::new(mesh, &[(0, material(20.0))], supports).unwrap();
    model.add_self_weight().unwrap();
    model
}

/// The largest `|a − b|` over the largest `|b|`.
fn relative_difference<const D: usize>(a: &[[f64; D]], b: &[[f64; D]]) -> f64 {
    let scale = b.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    let diff = a
        .iter()
        .flatten()
        .zip(b.iter().flatten())
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale
}

/// The plastic body with linear-elastic points against the elastic model it is built on:
/// one Newton solve, then the residual at round-off, and the same displacements to 1e-12
/// relative (both solve the same system with the same ordering; only the summation order of
/// the element matrices differs, and these small meshes have condition numbers ~1e3).
fn reproduces<const D: usize>(build: impl Fn() -> ElasticModel<D>)
where
    Dim<D>: ModelSpace<D>,
{
    let expected = build().solve(1.0).unwrap();
    let mut body = PlasticModel::new(build(), &[(0, elastic_point())]).unwrap();
    let mut u = vec![0.0; body.dof_count()];
    let report = newton::solve(&mut body, &mut u, 0.0, 1.0, &NewtonSettings::default()).unwrap();
    let residuals = &report.steps[0].residuals;
    assert_eq!(residuals.len(), 2, "one solve: {residuals:?}");
    assert!(residuals[1] < 1e-12, "{residuals:?}");
    let got = body.nodal_displacements(&u);
    let diff = relative_difference(&got, &expected);
    assert!(diff < 1e-12, "relative difference {diff:e}");
}

#[test]
fn issue_40_linear_elastic_points_reproduce_the_elastic_model_works() {
    reproduces(|| plane(ElementKind::Tri6, Idealization::PlaneStrain, 0.0));
    reproduces(|| plane(ElementKind::Tri3, Idealization::Axisymmetric, 0.5));
    reproduces(|| plane(ElementKind::Tri6, Idealization::Axisymmetric, 0.5));
    reproduces(|| plane(ElementKind::Quad4, Idealization::PlaneStrain, 0.0));
    reproduces(|| plane(ElementKind::Quad8, Idealization::Axisymmetric, 0.5));
    reproduces(|| solid(ElementKind::Tet4));
    reproduces(|| solid(ElementKind::Tet10));
    reproduces(|| solid(ElementKind::Hex8));
}

#[test]
fn commit_and_rollback_round_trip_works() {
    let mut body = PlasticModel::new(
        plane(ElementKind::Tri3, Idealization::PlaneStrain, 0.0),
        &[(0, elastic_point())],
    )
    .unwrap();
    let n = body.dof_count();
    let (u_1, u_2) = (vec![1e-3; n], vec![-2e-3; n]);
    let (mut f_1, mut f_2, mut f_again) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let version = body.stiffness_version();
    body.internal_force_into(&u_1, &mut f_1).unwrap();
    body.rollback();
    assert!(
        body.committed_states()
            .iter()
            .all(|s| *s == PointState::default()),
        "an evaluation leaves the committed state alone"
    );
    body.internal_force_into(&u_1, &mut f_1).unwrap();
    body.update_tangent().unwrap();
    assert!(
        body.stiffness_version() > version,
        "a new tangent, a new version"
    );
    body.commit();
    let committed = body.committed_states().to_vec();
    assert!(committed.iter().any(|s| s.strain != [0.0; 6]));
    body.internal_force_into(&u_2, &mut f_2).unwrap();
    body.rollback();
    assert_eq!(
        body.committed_states(),
        &committed[..],
        "rollback keeps the commit"
    );
    // from the committed state at u_1, u_1 again is a zero increment: σ = σ_c exactly
    body.internal_force_into(&u_1, &mut f_again).unwrap();
    assert_eq!(f_again, f_1);
    assert_ne!(f_2, f_1);
}

/// A rectangle `[0, 4] × [0, 2]` of `kind` (two layers, regions 0 and 1, the upper one from
/// `y = 1`), base fixed, sides on rollers, self-weight (γ = 20 below, `upper` above).
fn layered_ground(kind: ElementKind, idealization: Idealization, upper: f64) -> LinearElasticModel {
    let mut spec = RectangleSpec {
        kind,
        ..RectangleSpec::new([0.0, 4.0], [0.0, 1.0], 4, 2)
    };
    spec.layers.push(Layer {
        top: 2.0,
        ny: 2,
        grading: Grading::Uniform,
        region: 1,
    });
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
    let (lower, upper) = (material(20.0), material(upper));
    let mut model =
        LinearElasticModel::new(mesh, idealization, &[(0, lower), (1, upper)], supports).unwrap();
    model.add_self_weight().unwrap();
    model
}

/// [`layered_ground`] with γ = 20 in both layers.
fn ground(kind: ElementKind, idealization: Idealization) -> LinearElasticModel {
    layered_ground(kind, idealization, 20.0)
}

/// The K0 state balances the self-weight of a layered ground (γ = 20 below, 12 above: the
/// lower layer carries the upper one): the residual at `u = 0` is round-off (1e-12 relative:
/// the stress is linear in depth in each layer, the layers meet on element sides, and the
/// rules integrate `Bᵀ σ₀` and `Nᵀ γ` exactly) and Newton moves nothing beyond round-off of
/// the settlement the same weight would cause without it.
#[test]
fn issue_40_geostatic_state_is_in_equilibrium_works() {
    for (kind, idealization) in [
        (ElementKind::Tri3, Idealization::PlaneStrain),
        (ElementKind::Quad8, Idealization::PlaneStrain),
        (ElementKind::Tri6, Idealization::Axisymmetric),
    ] {
        let settlement = layered_ground(kind, idealization, 12.0).solve(1.0).unwrap();
        let scale = settlement
            .iter()
            .flatten()
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        let laws = [(0, elastic_point()), (1, elastic_point())];
        let mut body = PlasticModel::new(layered_ground(kind, idealization, 12.0), &laws).unwrap();
        body.set_geostatic(2.0, &[(0, 0.6), (1, 0.6)]).unwrap();
        let n = body.dof_count();
        let (mut f_ext, mut f_int) = (vec![0.0; n], vec![0.0; n]);
        body.external_force_into(1.0, &mut f_ext).unwrap();
        body.internal_force_into(&vec![0.0; n], &mut f_int).unwrap();
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let r: Vec<f64> = f_ext.iter().zip(&f_int).map(|(e, i)| e - i).collect();
        assert!(
            norm(&r) < 1e-12 * norm(&f_ext),
            "{kind:?}: {:e}",
            norm(&r) / norm(&f_ext)
        );
        body.update_tangent().unwrap();
        let mut du = r;
        body.solve_in_place(&mut du).unwrap();
        let moved = du.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!(
            moved < 1e-12 * scale,
            "{kind:?}: moved {moved:e} of {scale:e}"
        );
        let outputs = body.element_outputs();
        // the mean vertical stress of an element is −γ × its mean depth: negative
        assert!(outputs.stress.iter().all(|s| s[1] < 0.0));
        assert!(outputs.yielding.iter().all(|&y| y == 0.0));
    }
}

/// A test double with a yield surface `|σ_yy − σ_xx| / 2 ≤ c` (Tresca in the plane) and no
/// plastic flow: enough to test the admissibility check of an initial stress.
#[derive(Debug)]
struct CappedPoint {
    elastic: LinearElasticPoint,
    cohesion: f64,
}

impl ConstitutivePoint for CappedPoint {
    fn elastic_tangent(&self) -> VoigtMatrix {
        self.elastic.elastic_tangent()
    }

    fn update(
        &self,
        committed: &PointState,
        strain: &Voigt,
        trial: &mut PointState,
        tangent: &mut VoigtMatrix,
    ) -> Result<(), FemError> {
        self.elastic.update(committed, strain, trial, tangent)
    }

    fn yield_function(&self, stress: &Voigt) -> f64 {
        0.5 * (stress[1] - stress[0]).abs() - self.cohesion
    }
}

#[test]
fn issue_40_geostatic_state_outside_the_yield_surface_is_refused_naming_the_region() {
    let weak: Arc<dyn ConstitutivePoint> = Arc::new(CappedPoint {
        elastic: LinearElasticPoint::new(YOUNG, POISSON).unwrap(),
        cohesion: 5.0,
    });
    let strong: Arc<dyn ConstitutivePoint> = Arc::new(CappedPoint {
        elastic: LinearElasticPoint::new(YOUNG, POISSON).unwrap(),
        cohesion: 1e3,
    });
    let build = |laws: &[(u32, Arc<dyn ConstitutivePoint>)]| {
        PlasticModel::new(ground(ElementKind::Tri3, Idealization::PlaneStrain), laws).unwrap()
    };
    // the upper layer (region 1, depth ≤ 1, |σ_v| ≤ 20) is weak: K0 = 0.6 keeps
    // |σ_v − σ_h| / 2 ≤ 4 < 5 there; K0 = 0.1 gives up to 9 > 5
    let mut body = build(&[(0, strong.clone()), (1, weak.clone())]);
    body.set_geostatic(2.0, &[(0, 0.1), (1, 0.6)]).unwrap();
    let err = body.set_geostatic(2.0, &[(0, 0.1), (1, 0.1)]).unwrap_err();
    let FemError::OutsideYieldSurface {
        region,
        element,
        yield_function,
        ..
    } = err
    else {
        panic!("{err:?}")
    };
    assert_eq!(region, 1);
    assert_eq!(body.elastic().mesh().regions()[element], 1);
    assert!(yield_function > 0.0);
    assert!(err.to_string().contains("region 1"), "{err}");
    // nothing changed: the admissible state set before stays
    assert!(body.committed_states().iter().any(|s| s.stress[1] < 0.0));
    assert!(matches!(
        body.set_geostatic(2.0, &[(7, 0.5)]),
        Err(FemError::UnknownRegion { region: 7 })
    ));
    assert!(matches!(
        body.set_geostatic(2.0, &[(0, -0.5)]),
        Err(FemError::InvalidParameter { name: "k0", .. })
    ));
}

#[test]
fn plastic_model_rejects_bad_input() {
    let stress = plane(
        ElementKind::Tri3,
        Idealization::PlaneStress { thickness: 1.0 },
        0.0,
    );
    assert!(matches!(
        PlasticModel::new(stress, &[(0, elastic_point())]),
        Err(FemError::Unsupported { .. })
    ));
    let strain = plane(ElementKind::Tri3, Idealization::PlaneStrain, 0.0);
    assert!(matches!(
        PlasticModel::new(strain, &[(3, elastic_point())]),
        Err(FemError::MissingMaterial { region: 0, .. })
    ));
    let mut body = PlasticModel::new(
        plane(ElementKind::Tri3, Idealization::PlaneStrain, 0.0),
        &[(0, elastic_point())],
    )
    .unwrap();
    let n = body.dof_count();
    let mut u = vec![f64::NAN; n];
    let mut f = vec![0.0; n];
    assert!(matches!(
        body.internal_force_into(&u, &mut f),
        Err(FemError::NonFiniteSolve {
            what: "displacement",
            ..
        })
    ));
    u.fill(0.0);
    let bad = NewtonSettings {
        tolerance: 0.0,
        ..NewtonSettings::default()
    };
    assert!(matches!(
        newton::solve(&mut body, &mut u, 0.0, 1.0, &bad),
        Err(FemError::InvalidParameter {
            name: "tolerance",
            ..
        })
    ));
    let loose = NewtonSettings {
        tolerance: 1.0,
        ..NewtonSettings::default()
    };
    assert!(matches!(
        newton::solve(&mut body, &mut u, 0.0, 1.0, &loose),
        Err(FemError::InvalidParameter {
            name: "tolerance",
            ..
        })
    ));
    assert!(matches!(
        newton::solve(&mut body, &mut u, 0.0, f64::NAN, &NewtonSettings::default()),
        Err(FemError::InvalidParameter { name: "end", .. })
    ));
}

/// A law whose update fails past a strain: every step beyond it fails, the path is cut
/// `max_cuts` times, and the error carries the history with the last converged state kept.
#[derive(Debug)]
struct BrittlePoint(LinearElasticPoint);

impl ConstitutivePoint for BrittlePoint {
    fn elastic_tangent(&self) -> VoigtMatrix {
        self.0.elastic_tangent()
    }

    fn update(
        &self,
        committed: &PointState,
        strain: &Voigt,
        trial: &mut PointState,
        tangent: &mut VoigtMatrix,
    ) -> Result<(), FemError> {
        if strain.iter().any(|e| e.abs() > 0.011) {
            return Err(FemError::InvalidParameter {
                name: "strain",
                value: 0.011,
                expected: "a strain the test law can carry",
            });
        }
        self.0.update(committed, strain, trial, tangent)
    }

    fn yield_function(&self, _: &Voigt) -> f64 {
        f64::NEG_INFINITY
    }
}

#[test]
fn issue_40_newton_cuts_steps_and_keeps_the_last_converged_state() {
    // a bar [0, 1] × [0, 0.1] pulled at its right end by a force: ε_xx = 0.02 λ, which the
    // law carries up to λ = 0.55
    let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 0.1], 4, 1)).unwrap();
    let left = mesh.node_set("left").unwrap().to_vec();
    let right = mesh.node_set("right").unwrap().to_vec();
    let bottom_left = mesh.node_set("bottom_left").unwrap().to_vec();
    let mut supports = Supports::new();
    supports
        .fix(&left, Component::X)
        .fix(&bottom_left, Component::Y);
    let mut elastic = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, material(0.0))],
        supports,
    )
    .unwrap();
    // E A ε = F with A = 0.1 (ν = 0): half the force on each right node
    for &node in &right {
        elastic
            .add_nodal_force(node, [0.5 * YOUNG * 0.1 * 0.02, 0.0])
            .unwrap();
    }
    let law: Arc<dyn ConstitutivePoint> =
        Arc::new(BrittlePoint(LinearElasticPoint::new(YOUNG, 0.0).unwrap()));
    let tip = right[0];
    let mut body = PlasticModel::new(elastic, &[(0, law)]).unwrap();
    let mut u = vec![0.0; body.dof_count()];
    let settings = NewtonSettings {
        steps: 4,
        max_cuts: 3,
        ..NewtonSettings::default()
    };
    let err = newton::solve(&mut body, &mut u, 0.0, 1.0, &settings).unwrap_err();
    let FemError::NotConverged {
        converged_load_factor,
        cuts,
        report,
        ..
    } = err
    else {
        panic!("{err:?}")
    };
    assert_eq!(cuts, 3);
    // steps of 0.25 to 0.5, then 0.75 fails and is cut to 0.625 (fails), 0.5625 (fails),
    // 0.53125 (converges), then 0.59375 (the step doubled again) fails with no cut left
    assert_eq!(converged_load_factor, 0.53125);
    assert_eq!(report.load_factor, 0.53125);
    assert!(report.steps.iter().filter(|s| !s.converged).count() == 4);
    // the structure and u are at the last converged state: the strain 0.02 × 0.53125
    let ux = body.nodal_displacements(&u)[tip][0];
    assert!((ux - 0.02 * 0.53125).abs() < 1e-12, "{ux}");
    let strain = body.committed_states()[0].strain[0];
    assert!((strain - 0.02 * 0.53125).abs() < 1e-12, "{strain}");
}

/// equilibrium, then a step at the same load factor: the elastic model's answer with the new
/// value (1e-12 relative, as the reproduction test); a new support is refused.
#[test]
fn issue_40_displacement_control_works() {
    let build = || plane(ElementKind::Quad4, Idealization::PlaneStrain, 0.0);
    let mut body = PlasticModel::new(build(), &[(0, elastic_point())]).unwrap();
    let mut u = vec![0.0; body.dof_count()];
    let settings = NewtonSettings::default();
    newton::solve(&mut body, &mut u, 0.0, 1.0, &settings).unwrap();
    let right: Vec<usize> = {
        let mesh = body.elastic().mesh();
        let bottom = mesh.node_set("bottom").unwrap();
        let right = mesh.node_set("right").unwrap();
        right
            .iter()
            .copied()
            .filter(|n| !bottom.contains(n))
            .collect()
    };
    body.set_prescribed(&right, Component::X, 0.03).unwrap();
    let report = newton::solve(&mut body, &mut u, 1.0, 1.0, &settings).unwrap();
    assert_eq!(report.steps.len(), 1);
    assert!(report.steps[0].converged);
    let mut elastic = build();
    elastic.set_prescribed(&right, Component::X, 0.03).unwrap();
    let expected = elastic.solve(1.0).unwrap();
    let diff = relative_difference(&body.nodal_displacements(&u), &expected);
    assert!(diff < 1e-12, "relative difference {diff:e}");
    let top_left = body.elastic().mesh().node_set("top_left").unwrap().to_vec();
    assert!(matches!(
        body.set_prescribed(&top_left, Component::Y, 0.1),
        Err(FemError::Unsupported { .. })
    ));
}

/// A cut step's prescribed values: `interpolate_prescribed` moves them from their values at
/// the last commit to the targets of `set_prescribed`, and refuses a fraction outside [0, 1].
#[test]
fn issue_40_interpolate_prescribed_works() {
    let build = plane(ElementKind::Tri3, Idealization::PlaneStrain, 0.0);
    let mut body = PlasticModel::new(build, &[(0, elastic_point())]).unwrap();
    // the right side is held at u_x = 0.01, the bottom at 0
    let right: Vec<usize> = (0..body.node_count())
        .filter(|&n| body.prescribed_displacement(n)[0] != 0.0)
        .collect();
    assert!(!right.is_empty());
    let (u, mut f) = (vec![0.0; body.dof_count()], vec![0.0; body.dof_count()]);
    body.internal_force_into(&u, &mut f).unwrap();
    body.commit();
    body.set_prescribed(&right, Component::X, 0.03).unwrap();
    let at = |body: &PlasticModel<2>| body.prescribed_displacement(right[0])[0];
    assert_eq!(at(&body), 0.03);
    // a quarter of the way from 0.01; exact to round-off of values of order 1e-2
    body.interpolate_prescribed(0.25).unwrap();
    assert!((at(&body) - 0.015).abs() < 1e-16);
    // committed there, the rest starts from 0.015
    body.internal_force_into(&u, &mut f).unwrap();
    body.commit();
    body.interpolate_prescribed(0.5).unwrap();
    assert!((at(&body) - 0.0225).abs() < 1e-16);
    body.interpolate_prescribed(1.0).unwrap();
    assert_eq!(at(&body), 0.03);
    for bad in [1.5, -0.1, f64::NAN] {
        assert!(matches!(
            body.interpolate_prescribed(bad),
            Err(FemError::InvalidParameter {
                name: "fraction",
                ..
            })
        ));
    }
}

/// Uniaxial compression under displacement control past yield, von Mises (`k = 1`, uniaxial
/// yield stress `√3 k`), in 3D (one Hex8 on rollers) and in axisymmetry (a ring of Quad4,
/// free radially): the homogeneous state is exact for these elements, so every point carries
/// `σ_zz = −√3 k` once yielded and no other stress (1e-10: the return mapping's round-off
/// on stresses of order 1 and strains of order 1e-3).
#[test]
fn issue_40_uniaxial_yield_in_3d_and_axisymmetry_works() {
    let law = || -> Arc<dyn ConstitutivePoint> {
        Arc::new(super::DruckerPrager::von_mises(YOUNG, POISSON, 1.0).unwrap())
    };
    let yield_stress = 3f64.sqrt();
    // 3D
    let mesh = box_mesh(&[0.0, 1.0], &[0.0, 1.0], &[0.0, 1.0], ElementKind::Hex8).unwrap();
    let mut supports = Supports::new();
    for (set, c) in [
        ("x0", Component::X),
        ("y0", Component::Y),
        ("z0", Component::Z),
    ] {
        supports.fix(mesh.node_set(set).unwrap(), c);
    }
    let top = mesh.node_set("z1").unwrap().to_vec();
    supports.fix(&top, Component::Z);
    let elastic = SolidModel::new(mesh, &[(0, material(0.0))], supports).unwrap();
    let mut body = PlasticModel::new(elastic, &[(0, law())]).unwrap();
    check_uniaxial(&mut body, &top, Component::Z, 2, yield_stress);
    // axisymmetry: (r, z) in [1, 2] × [0, 1]
    let spec = RectangleSpec {
        kind: ElementKind::Quad4,
        ..RectangleSpec::new([1.0, 2.0], [0.0, 1.0], 2, 2)
    };
    let mesh = rectangle(&spec).unwrap();
    let mut supports = Supports::new();
    supports.fix(mesh.node_set("bottom").unwrap(), Component::Y);
    let top = mesh.node_set("top").unwrap().to_vec();
    supports.fix(&top, Component::Y);
    let elastic = LinearElasticModel::new(
        mesh,
        Idealization::Axisymmetric,
        &[(0, material(0.0))],
        supports,
    )
    .unwrap();
    let mut body = PlasticModel::new(elastic, &[(0, law())]).unwrap();
    check_uniaxial(&mut body, &top, Component::Y, 1, yield_stress);
}

/// Pulls `top` down along `c` in three strains (elastic, twice plastic) and checks the stress
/// of every point: component `axis` (Voigt index of the axial stress) `E ε` then `−σ_y`.
fn check_uniaxial<const D: usize>(
    body: &mut PlasticModel<D>,
    top: &[usize],
    c: Component,
    axis: usize,
    yield_stress: f64,
) where
    Dim<D>: ModelSpace<D>,
{
    let mut u = vec![0.0; body.dof_count()];
    for strain in [-1e-3, -3e-3, -5e-3] {
        body.set_prescribed(top, c, strain).unwrap();
        let report = newton::solve(body, &mut u, 0.0, 0.0, &NewtonSettings::default()).unwrap();
        assert!(report.steps.iter().all(|s| s.residuals.len() <= 9));
        let expected = (YOUNG * strain).max(-yield_stress);
        for s in body.committed_states() {
            for (i, &v) in s.stress.iter().enumerate() {
                let want = if i == axis { expected } else { 0.0 };
                assert!((v - want).abs() < 1e-10, "ε = {strain}: σ = {:?}", s.stress);
            }
            assert_eq!(s.equivalent_plastic_strain > 0.0, strain < -2e-3, "{s:?}");
        }
    }
}

/// An initial stress set on the elastic model is taken over as the committed stress (and
/// leaves the external force): the same state as `set_geostatic` (to round-off of the two
/// evaluations of `−γ (z_s − z)`: 1e-12 relative).
#[test]
fn issue_40_initial_stress_of_the_elastic_model_is_taken_over() {
    let laws = [(0, elastic_point()), (1, elastic_point())];
    let mut elastic = ground(ElementKind::Tri3, Idealization::PlaneStrain);
    elastic
        .set_initial_stress(crate::model::geostatic(20.0, 0.6, 2.0))
        .unwrap();
    let taken = PlasticModel::new(elastic, &laws).unwrap();
    let mut set =
        PlasticModel::new(ground(ElementKind::Tri3, Idealization::PlaneStrain), &laws).unwrap();
    set.set_geostatic(2.0, &[(0, 0.6), (1, 0.6)]).unwrap();
    for (a, b) in taken.committed_states().iter().zip(set.committed_states()) {
        for (x, y) in a.stress.iter().zip(&b.stress) {
            assert!((x - y).abs() <= 1e-12 * y.abs().max(1.0), "{a:?} vs {b:?}");
        }
    }
    let n = taken.dof_count();
    let (mut f_a, mut f_b) = (vec![0.0; n], vec![0.0; n]);
    taken.external_force_into(1.0, &mut f_a).unwrap();
    set.external_force_into(1.0, &mut f_b).unwrap();
    assert_eq!(
        f_a, f_b,
        "the initial stress is not a load of the plastic body"
    );
}
