//! Issue 38: the 3D active set holds one factor of the stiffness's size at a time. Its solve
//! frees the structure's factor of `K` (`Structure::release_factor`) while it factorises the
//! constrained stiffness, drops its own after, and refactors `K`
//! (`Structure::restore_factor`). Checked on a block pressed onto a rigid floor and sheared
//! with Coulomb friction (two steps, as `solid_active_set.rs`'s partial slip):
//!
//! - one refactorisation of `K` per active-set step, none on the dense path;
//! - the restored factor is `K`'s: the structure's free response after the steps is bit for
//!   bit a fresh model's (same matrix, same symbolic analysis, same operations);
//! - the answer is the dense path's: reactions and displacements to the solver's tolerance.

#![cfg(feature = "fe")]

use contact_laws::Coulomb;
use contact_solver::coupling::solid::{ContactZone3, RigidPlane, SolidContactSimulation};
use contact_solver::{FlexibilityMode, SimulationSettings};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidModel};
use fem_core::{Component, Material, Structure, Supports};

/// The block `[0, 2] × [0, 1.5] × [0, 1]` (P2), rollers on `x = 0` and `y = 0`, its top
/// prescribed: `(0, 0, −1e-3)`, then with the shear `(dx, dy)`.
fn model(shear: [f64; 2]) -> (SolidModel, Vec<usize>, Vec<f64>, Vec<usize>) {
    let mesh = box_mesh(
        &lines(0.0, 2.0, 3),
        &lines(0.0, 1.5, 2),
        &lines(0.0, 1.0, 2),
        SolidKind::Tet10,
    )
    .unwrap();
    let top = mesh.node_set("z1").unwrap().to_vec();
    let mut s = Supports::new();
    s.fix(mesh.node_set("x0").unwrap(), Component::X)
        .fix(mesh.node_set("y0").unwrap(), Component::Y);
    s.prescribe(&top, Component::Z, -1e-3).unwrap();
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let mut model =
        SolidModel::new(mesh, &[(0, Material::new(1000.0, 0.3, 0.0).unwrap())], s).unwrap();
    if shear != [0.0; 2] {
        model.set_prescribed(&top, Component::X, shear[0]).unwrap();
        model.set_prescribed(&top, Component::Y, shear[1]).unwrap();
    }
    (model, nodes, areas, top)
}

/// The two steps on `mode`: the simulation after them, and each step's reactions.
fn run(
    mode: FlexibilityMode,
) -> (
    SolidContactSimulation<SolidModel, Coulomb>,
    Vec<Vec<[f64; 3]>>,
) {
    let (model, nodes, areas, top) = model([0.0; 2]);
    let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let zone = ContactZone3::rigid("base", nodes, floor, Coulomb::new(0.3).unwrap(), 0.1)
        .with_areas(areas);
    let settings = SimulationSettings::for_dimension::<3>().with_flexibility(mode);
    let mut sim = SolidContactSimulation::new(model, vec![zone], settings).unwrap();
    let mut reactions = Vec::new();
    let res = sim.step(1.0, 1.0).unwrap();
    reactions.push(res.contacts.iter().map(|c| c.reaction()).collect());
    for (c, v) in [(Component::X, 2e-4), (Component::Y, 1e-4)] {
        sim.structure_mut().set_prescribed(&top, c, v).unwrap();
    }
    let res = sim.step(2.0, 1.0).unwrap();
    assert_eq!(res.report.active_set, mode == FlexibilityMode::ActiveSet);
    reactions.push(res.contacts.iter().map(|c| c.reaction()).collect());
    (sim, reactions)
}

#[test]
fn issue_38_active_set_restores_the_structure_factor() {
    let (active, r_active) = run(FlexibilityMode::ActiveSet);
    let (dense, r_dense) = run(FlexibilityMode::Dense);
    assert_eq!(
        active.counters().structure_refactorizations,
        2,
        "one a step"
    );
    assert_eq!(dense.counters().structure_refactorizations, 0);
    // the restored factor solves as a fresh model's, bit for bit
    let (fresh, ..) = model([2e-4, 1e-4]);
    let n = fresh.dof_count();
    let (mut u_sim, mut u_fresh) = (vec![0.0; n], vec![0.0; n]);
    active
        .structure()
        .free_response_into(1.0, &mut u_sim)
        .unwrap();
    fresh.free_response_into(1.0, &mut u_fresh).unwrap();
    assert_eq!(u_sim, u_fresh);
    // the dense path's answer, to the solver's tolerance (1e-10 relative on the residual,
    // amplified by the conditioning of the stick/slip split: 1e-7, as solid_active_set.rs)
    let scale = r_dense
        .iter()
        .flatten()
        .fold(0.0_f64, |m, r| m.max(r[0].abs()));
    for (ra, rd) in r_active.iter().flatten().zip(r_dense.iter().flatten()) {
        for d in 0..3 {
            assert!(
                (ra[d] - rd[d]).abs() < 1e-7 * scale,
                "{ra:?} against {rd:?}"
            );
        }
    }
    let (ua, ud) = (active.displacement(), dense.displacement());
    let u_scale = ud.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (a, d) in ua.iter().zip(ud) {
        assert!((a - d).abs() < 1e-7 * u_scale, "{a} against {d}");
    }
}
