//! "Skip what a scene does not need", one test per rule: the work is skipped (counters) and the
//! answer is the same as with the rule switched off.

#![cfg(feature = "fe")]

use contact_laws::{BetaScheme, Coulomb, Rccm, RccmParams, Signorini, StandardLaw};
use contact_solver::{
    ContactSimulation, ContactZone, RigidLine, SimulationSettings, SkipRules, StepResult,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, ElementKind, Idealization, LinearElasticModel, Material, Supports};

/// A block with its bottom 0.001 above a LINE, top pushed down in `steps` steps; the bottom's
/// left half faces the LINE, the right half is lifted by a step of 0.5 (out of reach).
fn run(
    law: StandardLaw,
    skip: SkipRules,
    steps: usize,
) -> (
    Vec<StepResult>,
    ContactSimulation<LinearElasticModel, StandardLaw>,
) {
    run_on(
        law,
        skip,
        steps,
        RigidLine::new([-1.0, 0.0], [1.0, 0.0]).unwrap(),
    )
}

/// [`run`] with the left half facing `near`.
fn run_on(
    law: StandardLaw,
    skip: SkipRules,
    steps: usize,
    near: RigidLine,
) -> (
    Vec<StepResult>,
    ContactSimulation<LinearElasticModel, StandardLaw>,
) {
    let mut spec = RectangleSpec::new([0.0, 2.0], [0.001, 1.001], 8, 4);
    spec.kind = ElementKind::Tri6;
    let mesh = rectangle(&spec).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0).unwrap();
    supports.fix(&top, Component::X);
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(200.0, 0.3, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let far = RigidLine::new([1.0, -0.5], [3.0, -0.5]).unwrap();
    let settings = SimulationSettings::default().with_skip(skip);
    let (l, r): (Vec<usize>, Vec<usize>) = bottom
        .iter()
        .partition(|&&n| model.mesh().nodes()[n][0] < 1.0);
    let zones = vec![
        ContactZone::rigid("near", l, near, law, 0.01),
        ContactZone::rigid("far", r, far, law, 0.01),
    ];
    let mut sim = ContactSimulation::new(model, zones, settings).unwrap();
    let mut out = Vec::new();
    for k in 1..=steps {
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, -0.004 * k as f64)
            .unwrap();
        out.push(sim.step(k as f64, 1.0).unwrap());
    }
    (out, sim)
}

fn same(a: &[StepResult], b: &[StepResult], tol: f64) {
    for (x, y) in a.iter().zip(b) {
        for (p, q) in x.contacts.iter().zip(&y.contacts) {
            for (pd, qd) in [(p.r.n, q.r.n), (p.r.t[0], q.r.t[0])] {
                assert!((pd - qd).abs() <= tol * 1.0, "{:?} vs {:?}", p.r, q.r);
            }
            assert!(
                (p.gap - q.gap).abs() <= 1e-9 * 0.004,
                "gap {} vs {}",
                p.gap,
                q.gap
            );
        }
    }
}

const ALL_OFF: SkipRules = SkipRules::none();

#[test]
fn frictionless_laws_skip_the_tangential_columns() {
    let law = StandardLaw::from(Signorini);
    let (on, sim_on) = run(law, SkipRules::default(), 3);
    let off_rule = SkipRules::default().with_frictionless_normal_only(false);
    let (off, sim_off) = run(law, off_rule, 3);
    same(&on, &off, 1e-9);
    let (c_on, c_off) = (sim_on.counters(), sim_off.counters());
    assert_eq!(c_on.flexibility_builds, c_off.flexibility_builds);
    assert_eq!(2 * c_on.flexibility_columns, c_off.flexibility_columns);
    assert!(on.iter().flat_map(|s| &s.contacts).all(|c| c.r.t[0] == 0.0));
}

#[test]
fn inactive_candidates_stay_out_and_f_star_is_reused() {
    let law = StandardLaw::from(Coulomb::new(0.3).unwrap());
    let (on, sim_on) = run(law, SkipRules::default(), 4);
    let (off, sim_off) = run(law, ALL_OFF, 4);
    same(&on, &off, 1e-9);
    let n = on[0].contacts.len();
    // the far half never enters; every candidate does when the rule is off
    assert!(on.iter().all(|s| s.report.active_contacts < n));
    assert!(off.iter().all(|s| s.report.active_contacts == n));
    // F* built once (active set constant after the first step), 4 times without reuse
    assert_eq!(sim_on.counters().flexibility_builds, 1);
    assert_eq!(sim_off.counters().flexibility_builds, 4);
    // no adhesion: no β loop, unless forced
    assert_eq!(sim_on.counters().adhesion_iterations, 0);
    assert!(sim_off.counters().adhesion_iterations > 0);
    // K never changes (only prescribed values): one factorisation for the whole run
    assert_eq!(sim_on.structure().factorizations(), 1);
    assert_eq!(sim_on.counters().stiffness_changes, 0);
}

#[test]
fn a_growing_active_set_solves_only_the_new_contacts_columns() {
    // the LINE falls away under the left half (gaps 0.001 to 0.021 against an alert distance
    // of 0.01): candidates enter the active set step by step while K stays the same, so each
    // rebuild of F* keeps the columns it has and solves the entering contacts' only
    let law = StandardLaw::from(Coulomb::new(0.3).unwrap());
    let line = || RigidLine::new([0.0, 0.0], [1.0, -0.02]).unwrap();
    let (on, sim_on) = run_on(law, SkipRules::default(), 5, line());
    let rebuild = SkipRules::default().with_reuse_flexibility(false);
    let (off, sim_off) = run_on(law, rebuild, 5, line());
    // the kept columns are the ones a rebuild computes (to the rounding of the solves)
    same(&on, &off, 1e-9);
    let active: Vec<usize> = on.iter().map(|s| s.report.active_contacts).collect();
    assert!(active.windows(2).any(|w| w[1] > w[0]), "{active:?}");
    let (c_on, c_off) = (sim_on.counters(), sim_off.counters());
    assert!(c_on.flexibility_builds > 1, "{c_on:?}");
    // two columns (friction) per contact that ever entered, once each
    let entered = *active.iter().max().unwrap();
    assert_eq!(c_on.flexibility_columns, 2 * entered, "{c_on:?}");
    assert_eq!(
        c_off.flexibility_columns,
        active.iter().map(|a| 2 * a).sum::<usize>(),
        "{c_off:?}"
    );
}

#[test]
fn no_adhesion_loop_when_every_beta_is_zero() {
    // RCCM with β₀ = 0 is plain Coulomb friction (seed fig. 6.5): no fixed point
    let law = StandardLaw::from(
        Rccm::new(RccmParams {
            c_n: 1e3,
            c_t: 1e3,
            w: 1e-3,
            alpha: 0.0,
            mu: 0.3,
            m: 1,
            beta_0: 0.0,
            scheme: BetaScheme::ImplicitEuler,
        })
        .unwrap(),
    );
    let (res, sim) = run(law, SkipRules::default(), 3);
    assert_eq!(sim.counters().adhesion_iterations, 0);
    let coulomb = StandardLaw::from(Coulomb::new(0.3).unwrap());
    let (reference, _) = run(coulomb, SkipRules::default(), 3);
    same(&res, &reference, 1e-9);
}
