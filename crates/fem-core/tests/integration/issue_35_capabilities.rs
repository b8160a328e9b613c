//! Issue 35, part 4: the optional capabilities of `Structure` — the mass ([`Mass`]) and the
//! state-dependent side ([`Nonlinear`]) — on fem-core's `ElasticModel`, against closed forms.
//!
//! - Total mass: a rigid translation `t` carries the whole mass, `tᵀ M t = ρ V |t|²`, with
//!   `V` the area (plane strain), thickness × area (plane stress), `∫ r dA` per radian
//!   (axisymmetry: the ring's mass is `2π` times), or the volume (3D); the HRZ lumped
//!   diagonal sums to the same per direction. Meshes: P1, P2 triangles, Quad4/8/9 (distorted),
//!   Tet4, Tet10, Hex8, Hex20 (distorted); no supports, so every dof is free.
//! - One element's consistent mass against its closed form (Tri3: `ρ A t / 12 [2 1 1; 1 2 1;
//!   1 1 2]` on each component; Zienkiewicz & Taylor, vol. 1, §16.2.3).
//! - `f_int(u) = K u`, and one Newton step from an arbitrary start solves the linear problem
//!   (loads, a prescribed displacement and an initial stress included), in 2D and 3D.
//! - Bad input: a region without density beside one with is an error naming the region.

use crate::quad_hex::{distorted_hexes, distorted_quads};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::solid::SolidKind;
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::{
    Component, ElementKind, FemError, Idealization, LinearElasticModel, Mass, Material, Mesh,
    SolidModel, Structure, Supports, geostatic,
};

const DENSITY: f64 = 2.5;

fn dense_material() -> Material {
    Material::new(100.0, 0.3, 0.0)
        .unwrap()
        .with_density(DENSITY)
        .unwrap()
}

/// `tᵀ M t` for the rigid translation `t` along `direction` and the lumped sum per
/// component, with the node components of every free dof.
fn translation_mass<const D: usize>(s: &impl Structure<D>, direction: [f64; D]) -> (f64, [f64; D]) {
    let mass: &dyn Mass = s.mass().expect("every region has a density");
    let n = s.dof_count();
    let mut t = vec![0.0; n];
    let mut lumped = [0.0; D];
    for node in 0..s.node_count() {
        for (c, dof) in s.node_dofs(node).into_iter().enumerate() {
            let i = dof.expect("no supports");
            t[i] = direction[c];
            lumped[c] += mass.lumped()[i];
        }
    }
    let mut mt = vec![0.0; n];
    mass.mul_into(&t, &mut mt);
    (t.iter().zip(&mt).map(|(a, b)| a * b).sum(), lumped)
}

fn check_total<const D: usize>(s: &impl Structure<D>, want: f64, what: &str) {
    // a rigid translation along an oblique direction: tᵀ M t = |t|² ρ V
    let direction: [f64; D] = core::array::from_fn(|d| [0.6, -0.8, 1.3][d]);
    let norm2: f64 = direction.iter().map(|v| v * v).sum();
    let (total, lumped) = translation_mass(s, direction);
    // round-off of the sums over the elements' quadrature points (a few hundred terms)
    let tol = 1e-12 * want;
    assert!(
        (total - norm2 * want).abs() < tol * norm2,
        "{what}: tᵀMt = {total}, want {}",
        norm2 * want
    );
    for (c, m) in lumped.iter().enumerate() {
        assert!(
            (m - want).abs() < tol,
            "{what}: lumped {c} = {m}, want {want}"
        );
    }
    let mass = s.mass().unwrap();
    assert!(
        mass.lumped().iter().all(|m| *m > 0.0),
        "{what}: HRZ positive"
    );
    assert_eq!(mass.matrix().map(|m| m.nrows()), Some(s.dof_count()));
}

#[test]
fn issue_35_total_mass_is_density_times_volume_in_the_plane() {
    // [1, 3] × [1, 2]: area 2, ∫ r dA = (3² − 1²)/2 = 4
    let meshes: Vec<(ElementKind, Mesh)> = [ElementKind::Tri3, ElementKind::Tri6]
        .into_iter()
        .map(|kind| {
            let spec = RectangleSpec {
                kind,
                ..RectangleSpec::new([1.0, 3.0], [1.0, 2.0], 4, 3)
            };
            (kind, rectangle(&spec).unwrap())
        })
        .chain(
            [ElementKind::Quad4, ElementKind::Quad8, ElementKind::Quad9]
                .into_iter()
                .map(|kind| (kind, distorted_quads(kind, 1.0, [3, 2], 17))),
        )
        .collect();
    for (kind, mesh) in meshes {
        for (ideal, volume) in [
            (Idealization::PlaneStrain, 2.0),
            (Idealization::PlaneStress { thickness: 0.7 }, 0.7 * 2.0),
            (Idealization::Axisymmetric, 4.0),
        ] {
            let model = LinearElasticModel::floating(
                mesh.clone(),
                ideal,
                &[(0, dense_material())],
                Supports::new(),
            )
            .unwrap();
            check_total(&model, DENSITY * volume, &format!("{kind:?} {ideal:?}"));
        }
    }
}

#[test]
fn issue_35_total_mass_is_density_times_volume_in_space() {
    let tets = |kind| {
        let mesh = box_mesh(
            &lines(0.0, 2.0, 3),
            &lines(0.0, 1.0, 2),
            &lines(0.0, 1.5, 2),
            kind,
        );
        (mesh.unwrap(), 3.0)
    };
    for (kind, (mesh, volume)) in [
        (SolidKind::Tet4, tets(SolidKind::Tet4)),
        (SolidKind::Tet10, tets(SolidKind::Tet10)),
        (
            SolidKind::Hex8,
            (distorted_hexes(SolidKind::Hex8, 2, 5), 1.0),
        ),
        (
            SolidKind::Hex20,
            (distorted_hexes(SolidKind::Hex20, 2, 5), 1.0),
        ),
    ] {
        let model = SolidModel::floating(mesh, &[(0, dense_material())], Supports::new()).unwrap();
        check_total(&model, DENSITY * volume, &format!("{kind:?}"));
    }
}

#[test]
fn issue_35_tri3_consistent_mass_matches_its_closed_form() {
    let nodes = vec![[0.5, 0.2], [2.0, 0.4], [1.1, 1.9]];
    let area = 0.5 * ((2.0 - 0.5) * (1.9 - 0.2) - (1.1 - 0.5) * (0.4 - 0.2));
    let mesh = Mesh::new(nodes, ElementKind::Tri3, vec![0, 1, 2], vec![0]).unwrap();
    let thickness = 0.3;
    let model = LinearElasticModel::floating(
        mesh,
        Idealization::PlaneStress { thickness },
        &[(0, dense_material())],
        Supports::new(),
    )
    .unwrap();
    let mass = model.mass().unwrap();
    let m = mass.matrix().unwrap().to_dense();
    let scale = DENSITY * area * thickness / 12.0;
    for a in 0..3 {
        for b in 0..=a {
            for c in 0..2 {
                let (i, j) = (
                    model.node_dofs(a)[c].unwrap(),
                    model.node_dofs(b)[c].unwrap(),
                );
                let (i, j) = (i.max(j), i.min(j)); // the lower triangle
                let want = scale * if a == b { 2.0 } else { 1.0 };
                // the 6-point rule is exact on N_a N_b; round-off only
                assert!((m[(i, j)] - want).abs() < 1e-14 * want, "{a} {b} {c}");
                let other = model.node_dofs(b)[1 - c].unwrap();
                let (k, l) = (i.max(other), i.min(other));
                if k != l || a != b {
                    assert_eq!(m[(k, l)], 0.0, "components do not couple");
                }
            }
        }
    }
    // HRZ on a Tri3: the diagonal 2/12 each, scaled to the element's mass → a third per node
    for v in mass.lumped() {
        assert!((v - 4.0 * scale).abs() < 1e-14 * scale);
    }
}

#[test]
fn issue_35_supported_dofs_have_no_mass_and_a_model_without_density_has_none() {
    let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2)).unwrap();
    let left = mesh.node_set("left").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.fix(&left, Component::X);
    let model = LinearElasticModel::floating(
        mesh.clone(),
        Idealization::PlaneStrain,
        &[(0, dense_material())],
        supports.clone(),
    )
    .unwrap();
    let mass = model.mass().unwrap();
    assert_eq!(mass.lumped().len(), model.dof_count());
    // the y translation is intact: its mass is the whole body's
    let mut t = vec![0.0; model.dof_count()];
    for node in 0..model.node_count() {
        t[model.node_dofs(node)[1].unwrap()] = 1.0;
    }
    let mut mt = vec![0.0; t.len()];
    mass.mul_into(&t, &mut mt);
    let total: f64 = t.iter().zip(&mt).map(|(a, b)| a * b).sum();
    assert!((total - 2.0 * DENSITY).abs() < 1e-12 * 2.0 * DENSITY);
    // released, the left nodes' x dofs come back (renumbered) with their mass
    let mut model = model;
    let before = model.dof_count();
    model.release(&left, Component::X).unwrap();
    assert_eq!(model.dof_count(), before + left.len());
    let (total, lumped) = translation_mass(&model, [1.0, 0.0]);
    assert!((total - 2.0 * DENSITY).abs() < 1e-12 * 2.0 * DENSITY);
    assert!((lumped[0] - 2.0 * DENSITY).abs() < 1e-12 * 2.0 * DENSITY);
    let plain = Material::new(100.0, 0.3, 0.0).unwrap();
    let model =
        LinearElasticModel::floating(mesh, Idealization::PlaneStrain, &[(0, plain)], supports)
            .unwrap();
    assert!(model.mass().is_none());
}

#[test]
fn issue_35_missing_density_names_the_region() {
    let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2)).unwrap();
    let regions: Vec<u32> = (0..mesh.element_count())
        .map(|e| u32::from(e >= 5))
        .collect();
    let mesh = Mesh::new(
        mesh.nodes().to_vec(),
        ElementKind::Tri3,
        mesh.connectivity().to_vec(),
        regions,
    )
    .unwrap();
    let plain = Material::new(100.0, 0.3, 0.0).unwrap();
    let got = LinearElasticModel::floating(
        mesh,
        Idealization::PlaneStrain,
        &[(0, dense_material()), (7, plain), (1, plain)],
        Supports::new(),
    );
    match got {
        Err(FemError::MissingDensity { region, element }) => assert_eq!((region, element), (1, 5)),
        other => panic!("expected MissingDensity, got {other:?}"),
    }
    assert!(matches!(
        plain.with_density(-1.0),
        Err(FemError::InvalidParameter {
            name: "density",
            ..
        })
    ));
}

/// `f_int(u) = K u` (against the dense product of the assembled `K`), and one Newton step
/// from `u_0` lands on the free response: `u_1 = u_0 + K⁻¹ (f_ext − f_int(u_0))`.
fn check_newton<const D: usize, S: Structure<D>>(model: &mut S, what: &str) {
    let n = model.dof_count();
    let u_0: Vec<f64> = (0..n).map(|i| ((i * 7 % 11) as f64 - 5.0) * 1e-3).collect();
    let k = model.stiffness_matrix().unwrap().to_dense();
    let k_u: Vec<f64> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| if i >= j { k[(i, j)] } else { k[(j, i)] } * u_0[j])
                .sum()
        })
        .collect();
    let (mut f_ext, mut f_int) = (vec![0.0; n], vec![0.0; n]);
    let body = model
        .nonlinear()
        .expect("the elastic model is nonlinear-capable");
    body.external_force_into(0.8, &mut f_ext).unwrap();
    body.internal_force_into(&u_0, &mut f_int).unwrap();
    let scale = k_u.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (a, b) in f_int.iter().zip(&k_u) {
        // two summation orders of the same products
        assert!(
            (a - b).abs() < 1e-12 * scale,
            "{what}: f_int {a} vs K u {b}"
        );
    }
    body.update_tangent().unwrap();
    let mut du: Vec<f64> = f_ext.iter().zip(&f_int).map(|(e, i)| e - i).collect();
    model.solve_in_place(&mut du).unwrap();
    let u_1: Vec<f64> = u_0.iter().zip(&du).map(|(u, d)| u + d).collect();
    let mut u_ref = vec![0.0; n];
    model.free_response_into(0.8, &mut u_ref).unwrap();
    let u_scale = u_ref.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(u_scale > 0.0);
    for (a, b) in u_1.iter().zip(&u_ref) {
        // the residual K u_0 − f_ext cancels in one back-substitution: round-off of the solve
        assert!((a - b).abs() < 1e-10 * u_scale, "{what}: u_1 {a} vs {b}");
    }
    let body = model.nonlinear().unwrap();
    body.internal_force_into(&u_1, &mut f_int).unwrap();
    body.commit();
    body.rollback();
    let f_scale = f_ext.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (a, b) in f_int.iter().zip(&f_ext) {
        // equilibrium at u_1, to the conditioning of K times round-off
        assert!((a - b).abs() < 1e-9 * f_scale, "{what}: residual {}", a - b);
    }
}

#[test]
fn issue_35_one_newton_step_with_the_tangent_solves_a_linear_body() {
    // 2D: self-weight, a prescribed settlement on the bottom and a geostatic initial stress
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 3)
    };
    let mesh = rectangle(&spec).unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let left = mesh.node_set("left").unwrap().to_vec();
    let mut supports = Supports::new();
    supports
        .prescribe(&bottom, Component::Y, -0.01)
        .unwrap()
        .fix(&left, Component::X);
    let soil = Material::new(100.0, 0.3, 2.0).unwrap();
    let mut model =
        LinearElasticModel::new(mesh, Idealization::Axisymmetric, &[(0, soil)], supports).unwrap();
    model.add_self_weight().unwrap();
    model.set_initial_stress(geostatic(2.0, 0.5, 1.0)).unwrap();
    check_newton(&mut model, "2D axisymmetric");
    // 3D: self-weight on a Hex20 box clamped at z = 0
    let l = lines(0.0, 1.0, 2);
    let mesh = box_mesh(&l, &l, &l, SolidKind::Hex20).unwrap();
    let base = mesh.node_set("z0").unwrap().to_vec();
    let mut supports = Supports::new();
    for c in [Component::X, Component::Y, Component::Z] {
        supports.fix(&base, c);
    }
    let mut model = SolidModel::new(mesh, &[(0, soil)], supports).unwrap();
    model.add_self_weight().unwrap();
    check_newton(&mut model, "3D Hex20");
}

/// A structure with none of the optional capabilities: the defaults answer `None`.
struct Spring;

impl Structure for Spring {
    fn dof_count(&self) -> usize {
        1
    }
    fn node_count(&self) -> usize {
        1
    }
    fn node_position(&self, _: usize) -> [f64; 2] {
        [0.0; 2]
    }
    fn node_dofs(&self, _: usize) -> [Option<usize>; 2] {
        [Some(0), None]
    }
    fn prescribed_displacement(&self, _: usize) -> [f64; 2] {
        [0.0; 2]
    }
    fn solve_many_in_place(&self, _: fem_core::faer::MatMut<'_, f64>) -> Result<(), FemError> {
        Ok(())
    }
    fn free_response_into(&self, _: f64, u: &mut [f64]) -> Result<(), FemError> {
        u[0] = 1.0;
        Ok(())
    }
    fn stiffness_version(&self) -> u64 {
        0
    }
}

#[test]
fn issue_35_a_structure_without_mass_or_tangent_answers_none() {
    let mut s = Spring;
    assert!(s.mass().is_none() && s.floating().is_none());
    assert!(s.nonlinear().is_none());
}
