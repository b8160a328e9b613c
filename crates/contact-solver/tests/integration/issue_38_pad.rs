//! Issue 38: the pad on its foundation, the family of `examples/solid_contact_scaling.rs
//! --slab m` (its ≥ 5 000-contact member is the scene where the active set beats dense), at a
//! size a debug build steps in a second.
//!
//! Quarter model: the slab `[0, 1]² × [0, h]`, `8 × 8 × 2` cells of six P1 tetrahedra
//! (`h = 0.25`), rollers on x = 0 and y = 0, its top lowered by `δ = h/100` (z only), its
//! bottom on the rigid plane z = 0: 81 contacts, all active. E = 1000, ν = 0.3.
//!
//! - `Auto` with a dense limit below the 81 active contacts picks the active set and says why
//!   (`PathReason::AboveDenseLimit`), as the default 3D limit (3000) does on the 5 329-contact
//!   member;
//! - its reactions are the dense path's to the solver's tolerance, with Coulomb friction;
//! - the reactions balance the supports' (z and x), and without friction the force is the
//!   uniaxial closed form `E δ/h` (P1 holds a uniform stress exactly).

#![cfg(feature = "fe")]

use contact_laws::{ContactLaw, Coulomb, Signorini};
use contact_solver::coupling::solid::{ContactZone3, RigidPlane, SolidContactSimulation};
use contact_solver::{FlexibilityMode, PathReason, SimulationSettings, SolvePath, StepReport};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidModel};
use fem_core::{Component, Material, Supports};

/// Cells per side and layers of the small pad.
const CELLS: usize = 8;
const LAYERS: usize = 2;

/// One step of the small pad with `law` on `mode`: the report, each contact's reaction and
/// the supports' total reaction in (x, z).
fn pad<L: ContactLaw + Clone>(
    law: L,
    mode: FlexibilityMode,
) -> (StepReport, Vec<[f64; 3]>, [f64; 2]) {
    pad_of(CELLS, LAYERS, law, mode)
}

/// [`pad`] with `cells` per side and `layers` (the thickness `layers / cells`).
fn pad_of<L: ContactLaw + Clone>(
    cells: usize,
    layers: usize,
    law: L,
    mode: FlexibilityMode,
) -> (StepReport, Vec<[f64; 3]>, [f64; 2]) {
    let mut sim = pad_simulation(cells, layers, law, mode);
    let res = sim.step(1.0, 1.0).unwrap();
    let reactions = res.contacts.iter().map(|c| c.force()).collect();
    (res.report, reactions, supports_xz(&sim))
}

/// The supports' total reaction in (x, z) after the simulation's last step (shared by the
/// issue-38 tests of the matrix-free path).
pub(crate) fn supports_xz<L: ContactLaw + Clone>(
    sim: &SolidContactSimulation<SolidModel, L>,
) -> [f64; 2] {
    let supports = sim
        .structure()
        .reactions(&sim.nodal_displacements(), 1.0)
        .unwrap();
    let total = |c: Component| -> f64 { supports.iter().filter(|r| r.0.1 == c).map(|r| r.1).sum() };
    [total(Component::X), total(Component::Z)]
}

/// The simulation of [`pad_of`], before its step.
fn pad_simulation<L: ContactLaw + Clone>(
    cells: usize,
    layers: usize,
    law: L,
    mode: FlexibilityMode,
) -> SolidContactSimulation<SolidModel, L> {
    let settings = SimulationSettings::for_dimension::<3>().with_flexibility(mode);
    pad_simulation_with(cells, layers, law, settings)
}

/// The pad of `cells × cells × layers` cells pressed on the rigid plane with `law`, under
/// `settings`, before its step (shared by the issue-38 tests of the matrix-free path).
pub(crate) fn pad_simulation_with<L: ContactLaw + Clone>(
    cells: usize,
    layers: usize,
    law: L,
    settings: SimulationSettings,
) -> SolidContactSimulation<SolidModel, L> {
    let h = layers as f64 / cells as f64;
    let mesh = box_mesh(
        &lines(0.0, 1.0, cells),
        &lines(0.0, 1.0, cells),
        &lines(0.0, h, layers),
        SolidKind::Tet4,
    )
    .unwrap();
    let mut s = Supports::new();
    s.fix(mesh.node_set("x0").unwrap(), Component::X)
        .fix(mesh.node_set("y0").unwrap(), Component::Y);
    s.prescribe(mesh.node_set("z1").unwrap(), Component::Z, -h / 100.0)
        .unwrap();
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let model = SolidModel::new(mesh, &[(0, Material::new(1000.0, 0.3, 0.0).unwrap())], s).unwrap();
    let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let zone = ContactZone3::rigid("base", nodes, floor, law, 0.1).with_areas(areas);
    SolidContactSimulation::new(model, vec![zone], settings).unwrap()
}

/// The largest relative imbalance of the contact reactions against the supports' (x, z).
fn imbalance(reactions: &[[f64; 3]], supports: [f64; 2]) -> f64 {
    let sum = |a: usize| -> f64 { reactions.iter().map(|r| r[a]).sum() };
    let force = sum(2);
    f64::max(
        (sum(0) + supports[0]).abs() / force,
        (sum(2) + supports[1]).abs() / force,
    )
}

#[test]
fn issue_38_auto_picks_the_active_set_on_the_pad() {
    let limit = 40;
    let auto = FlexibilityMode::Auto { dense_limit: limit };
    let mu = Coulomb::new(0.3).unwrap();
    let (report, r_auto, s_auto) = pad(mu, auto);
    assert_eq!(report.active_contacts, (CELLS + 1) * (CELLS + 1));
    assert!(report.active_set, "{}", report.path);
    assert_eq!(report.path.path, SolvePath::ActiveSet);
    assert_eq!(
        report.path.reason,
        PathReason::AboveDenseLimit { active: 81, limit }
    );
    let (dense, r_dense, s_dense) = pad(mu, FlexibilityMode::Dense);
    assert_eq!(dense.path.path, SolvePath::Dense);
    // friction holds part of the bottom: some contacts slip at the rim, the tangential
    // reactions are not all zero
    let t_max = r_dense.iter().fold(0.0_f64, |m, r| m.max(r[0].abs()));
    let scale = r_dense.iter().fold(0.0_f64, |m, r| m.max(r[2].abs()));
    assert!(
        t_max > 1e-3 * scale,
        "no friction at work: {t_max} of {scale}"
    );
    // the dense path's reactions to the solver's tolerance (1e-10 relative on the residual,
    // amplified by the stick/slip split: 1e-7, as issue_38_one_factor.rs)
    for (a, d) in r_auto.iter().zip(&r_dense) {
        for k in 0..3 {
            assert!((a[k] - d[k]).abs() < 1e-7 * scale, "{a:?} against {d:?}");
        }
    }
    // equilibrium with the supports on both paths: K u − f at the supports is exact up to the
    // solve's round-off (1e-12) and the reduced problem's tolerance (1e-8 relative)
    assert!(
        imbalance(&r_auto, s_auto) < 1e-6,
        "{}",
        imbalance(&r_auto, s_auto)
    );
    assert!(
        imbalance(&r_dense, s_dense) < 1e-6,
        "{}",
        imbalance(&r_dense, s_dense)
    );
}

#[test]
fn issue_38_frictionless_pad_carries_the_uniaxial_force() {
    // E δ/h on the unit quarter: 1000 × 1/100
    let exact = 10.0;
    for mode in [
        FlexibilityMode::Auto { dense_limit: 40 },
        FlexibilityMode::Dense,
    ] {
        let (report, r, s) = pad(Signorini, mode);
        let force: f64 = r.iter().map(|r| r[2]).sum();
        // P1 holds the uniform uniaxial stress exactly; the rest is the solver's tolerance
        assert!((force - exact).abs() < 1e-6 * exact, "{mode:?}: {force}");
        assert!(imbalance(&r, s) < 1e-6, "{mode:?}: {}", imbalance(&r, s));
        assert_eq!(report.active_set, mode != FlexibilityMode::Dense);
    }
}

#[test]
fn issue_38_auto_weighs_contacts_against_dofs() {
    // The default 3D `Auto` (dense limit 3000). The small pad, 81 contacts: below the rule's
    // floor (500), dense as before.
    let auto = SimulationSettings::for_dimension::<3>().flexibility;
    let (small, ..) = pad(Signorini, auto);
    assert_eq!(small.path.path, SolvePath::Dense);
    assert_eq!(
        small.path.reason,
        PathReason::WithinDenseLimit {
            active: 81,
            limit: 3000
        }
    );
    // The 24 × 24 × 5 pad of `docs/benchmarks.md` (625 contacts, 10 325 free DOF): within the
    // dense limit, above max(500, 0.5 · 10 325^(2/3) = 237), so the active set (measured 7×
    // faster than dense there), and the report says why.
    let mu = Coulomb::new(0.3).unwrap();
    let (report, r, s) = pad_of(24, 5, mu, auto);
    assert_eq!(report.active_contacts, 625);
    assert_eq!(report.path.path, SolvePath::ActiveSet, "{}", report.path);
    assert_eq!(
        report.path.reason,
        PathReason::AboveDofRule {
            active: 625,
            dofs: 10_325,
            limit: 500
        }
    );
    // its answer balances the supports (as the small pad's: 1e-6 of the force)
    assert!(imbalance(&r, s) < 1e-6, "{}", imbalance(&r, s));
}

#[test]
fn issue_38_dense_step_holds_f_star_once() {
    // A dense step without springs solves on the simulation's own F*: the reduced problem kept
    // for export shares its allocation with the simulation's operator cache (two holders of
    // one W, where each held its own copy before), and a clone of it shares it too.
    let mut sim = pad_simulation(CELLS, LAYERS, Signorini, FlexibilityMode::Dense);
    sim.step(1.0, 1.0).unwrap();
    let p = sim.last_reduced_problem().unwrap();
    let w = p.w_shared().unwrap();
    assert_eq!(p.size(), 3 * 81);
    assert_eq!(std::sync::Arc::strong_count(w), 2);
    let c = p.clone();
    assert!(std::sync::Arc::ptr_eq(w, c.w_shared().unwrap()));
    assert_eq!(std::sync::Arc::strong_count(w), 3);
}
