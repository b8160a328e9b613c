//! A floating block (issue 16): an elastic block with **no support at all** resting under its
//! own weight on a rigid LINE. Contact alone holds it; the three rigid-body modes (x, y
//! translations and the rotation) are solved for exactly (`LinearElasticModel::floating`,
//! `contact_solver` stage `floating`), no penalty spring.
//!
//! Source: statics of a rigid body and Coulomb's law (Coulomb 1785; e.g. J. L. Meriam,
//! L. G. Kraige, *Engineering Mechanics: Statics*, ch. 6 "Friction"): the contact reactions
//! balance the load, `Σ r_n = W`, `Σ r_t = −T`; a block under a tangential force `T` sticks
//! while `T ≤ μ W` and slides off (no equilibrium) when `T > μ W`.
//!
//! ```text
//!        T →  ┌──────────────┐  y = 1         P2 (or P1), plane strain, E = 1000, ν = 0.3
//!             │  self-weight │                 unit weight γ = 1: W = 2 per unit thickness
//!             │      ↓ W     │                 T as a uniform traction on the top
//!             └──────────────┘  y = 0
//!   ══════════════════════════════════ rigid LINE y = 0 (Signorini or Coulomb μ = 0.3)
//!             x = 0          x = 2
//! ```
//! What is asserted, and why:
//! - frictionless and with friction, no `T`: `Σ r_n = W` to `1e-10` relative (the equilibrium
//!   is solved to `equilibrium_tol = 1e-12` of the forces involved; the rest is round-off of
//!   the sums), `Σ r_t = 0` to `1e-10 W`;
//! - `T = 0.2 W < μ W`: sticks, `Σ r_t = −T` and `Σ r_n = W` to `1e-10` relative;
//! - `T = 0.4 W > μ W = 0.3 W`: [`SolverError::Unbalanced`] on the x translation of body 0,
//!   out of balance by `T − μ W` (to `1e-9` relative: the slip reactions are exact);
//! - a load pulling the block off the line: [`SolverError::Unbalanced`] on the y translation;
//! - the matrix-free and active-set paths refuse a floating structure with a typed error.

#![cfg(feature = "fe")]

use contact_laws::{Coulomb, Signorini, StandardLaw};
use contact_solver::{
    ContactSimulation, ContactZone, FlexibilityMode, RigidLine, SimulationSettings, SolverError,
    StepResult,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{ElementKind, Idealization, LinearElasticModel, Material, RigidMotion, Supports};

const WEIGHT: f64 = 2.0;

/// The block with self-weight, a top traction `t_x` (total `2 t_x`) and a body force `b_y`
/// (weight `−2 b_y`).
fn block(
    kind: ElementKind,
    law: StandardLaw,
    traction: f64,
    body_force: f64,
    settings: SimulationSettings,
) -> ContactSimulation<LinearElasticModel, StandardLaw> {
    block_at(kind, law, traction, body_force, settings, 0.0)
}

/// [`block`] with its base at `y = lift` above the line.
fn block_at(
    kind: ElementKind,
    law: StandardLaw,
    traction: f64,
    body_force: f64,
    settings: SimulationSettings,
    lift: f64,
) -> ContactSimulation<LinearElasticModel, StandardLaw> {
    let spec = RectangleSpec {
        kind,
        ..RectangleSpec::new([0.0, 2.0], [lift, 1.0 + lift], 8, 4)
    };
    let mesh = rectangle(&spec).unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let material = Material::new(1000.0, 0.3, 0.0).unwrap();
    let mut model = LinearElasticModel::floating(
        mesh,
        Idealization::PlaneStrain,
        &[(0, material)],
        Supports::new(),
    )
    .unwrap();
    assert_eq!(model.rigid_body_modes().unwrap().len(), 3);
    model.add_body_force(|_| [0.0, body_force]).unwrap();
    model.add_edge_traction("top", |_| [traction, 0.0]).unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, law, 0.01);
    ContactSimulation::new(model, vec![zone], settings).unwrap()
}

fn sums(res: &StepResult) -> (f64, f64) {
    res.contacts
        .iter()
        .fold((0.0, 0.0), |(n, t), c| (n + c.r.n, t + c.r.t[0]))
}

fn coulomb(mu: f64) -> StandardLaw {
    StandardLaw::from(Coulomb::new(mu).unwrap())
}

#[test]
fn floating_block_rests_on_its_weight_works() {
    for kind in [ElementKind::Tri3, ElementKind::Tri6] {
        for law in [StandardLaw::from(Signorini), coulomb(0.3)] {
            let mut sim = block(kind, law, 0.0, -1.0, SimulationSettings::default());
            let res = sim.step(1.0, 1.0).expect("the block rests");
            let (rn, rt) = sums(&res);
            eprintln!(
                "{kind:?} {law:?}: Σ r_n = {rn:.15}, Σ r_t = {rt:e}, {} Newton iterations, \
                 {} solves, α = {:?}, {:.2?}",
                res.report.equilibrium_iterations,
                res.report.equilibrium_solves,
                sim.rigid_body_amplitudes(),
                res.report.wall_time
            );
            // equilibrium solved to 1e-12 of the forces, plus round-off of the sum
            assert!(
                (rn - WEIGHT).abs() <= 1e-10 * WEIGHT,
                "{kind:?}: Σ r_n = {rn}"
            );
            assert!(rt.abs() <= 1e-10 * WEIGHT, "{kind:?}: Σ r_t = {rt}");
            // the block sits on the line: every bottom node closed, none penetrating
            assert!(res.contacts.iter().all(|c| c.gap.abs() < 1e-9));
            // the moment about the centre vanishes too: Σ r_n (x − 1) = 0 (symmetric load)
            let moment: f64 = res
                .contacts
                .iter()
                .map(|c| c.r.n * (c.position[0] - 1.0))
                .sum();
            assert!(moment.abs() <= 1e-10 * WEIGHT, "moment {moment:e}");
        }
    }
}

/// Lifted `0.05` above the line, beyond the alert distance `0.01`: no candidate is in the
/// first reduced problem; the free fall closes them (they are added and the pass redone) and
/// the block comes to rest on the line with the same reactions.
#[test]
fn floating_block_falls_onto_the_line_works() {
    let mut sim = block_at(
        ElementKind::Tri6,
        coulomb(0.3),
        0.0,
        -1.0,
        SimulationSettings::default(),
        0.05,
    );
    let res = sim.step(1.0, 1.0).expect("the block falls and rests");
    let (rn, rt) = sums(&res);
    eprintln!(
        "lifted: Σ r_n = {rn:.15}, Σ r_t = {rt:e}, {} passes, α = {:?}",
        res.report.detection_passes,
        sim.rigid_body_amplitudes()
    );
    // equilibrium to 1e-11 of the forces, plus round-off
    assert!((rn - WEIGHT).abs() <= 1e-10 * WEIGHT, "Σ r_n = {rn}");
    assert!(rt.abs() <= 1e-10 * WEIGHT, "Σ r_t = {rt}");
    assert!(res.report.detection_passes > 1);
    // it fell by the lift (plus its elastic settlement)
    assert!(sim.rigid_body_amplitudes()[1] < -0.05);
}

#[test]
fn floating_block_sticks_below_mu_w_works() {
    for kind in [ElementKind::Tri3, ElementKind::Tri6] {
        let push = 0.2 * WEIGHT; // T = 0.2 W < μ W = 0.6 W
        let mut sim = block(
            kind,
            coulomb(0.3),
            push / 2.0,
            -1.0,
            SimulationSettings::default(),
        );
        let res = sim.step(1.0, 1.0).expect("the block sticks");
        let (rn, rt) = sums(&res);
        eprintln!(
            "{kind:?} T = {push}: Σ r_n = {rn:.15}, Σ r_t = {rt:.15}, {} iterations, {} solves",
            res.report.equilibrium_iterations, res.report.equilibrium_solves
        );
        // equilibrium to 1e-12 of the forces involved, plus round-off
        assert!((rn - WEIGHT).abs() <= 1e-10 * WEIGHT, "Σ r_n = {rn}");
        assert!((rt + push).abs() <= 1e-10 * WEIGHT, "Σ r_t = {rt}");
        assert!(rt.abs() < 0.3 * rn);
    }
}

#[test]
fn floating_block_slides_off_above_mu_w_captures_errors() {
    let push = 0.4 * WEIGHT; // T = 0.4 W > μ W = 0.3 W
    let mut sim = block(
        ElementKind::Tri6,
        coulomb(0.15),
        push / 2.0,
        -1.0,
        SimulationSettings::default(),
    );
    let err = sim.step(1.0, 1.0).unwrap_err();
    eprintln!("{err}");
    let SolverError::Unbalanced {
        body,
        motion,
        imbalance,
        load,
    } = err
    else {
        panic!("expected Unbalanced, got {err:?}");
    };
    assert_eq!(body, 0);
    assert_eq!(
        motion,
        RigidMotion::Translation {
            direction: [1.0, 0.0]
        }
    );
    // out of balance by T − μ W (slip reactions μ r_n exactly; Σ r_n = W)
    let expected = push - 0.15 * WEIGHT;
    assert!(
        (imbalance - expected).abs() <= 1e-9 * WEIGHT,
        "imbalance {imbalance} vs {expected}"
    );
    assert!((load - push).abs() <= 1e-12 * WEIGHT);
    // the simulation keeps the previous state: a step with no push succeeds
    assert_eq!(sim.counters().steps, 0);
}

/// Issue 16 regression: far beyond `μ W` (`T = 1.0 = 1.67 μ W`, P1) the force reported was the
/// whole load `T` instead of `T − μ W = 0.4`: a round-off slope (−3e-23) of the force along
/// the free direction sent the block 1e22 away, off the line. Slopes below the null tolerance
/// of `J` now count as zero.
#[test]
fn issue_16_unbalanced_far_beyond_mu_w_reports_t_minus_mu_w() {
    for (push, expected) in [(0.7, 0.1), (0.8, 0.2), (1.0, 0.4), (2.0, 1.4)] {
        let mut sim = block(
            ElementKind::Tri3,
            coulomb(0.3),
            push / 2.0,
            -1.0,
            SimulationSettings::default(),
        );
        let err = sim.step(1.0, 1.0).unwrap_err();
        let SolverError::Unbalanced {
            motion, imbalance, ..
        } = err
        else {
            panic!("expected Unbalanced, got {err:?}");
        };
        assert_eq!(
            motion,
            RigidMotion::Translation {
                direction: [1.0, 0.0]
            }
        );
        // 1e-9: as the slide-off test
        assert!(
            (imbalance - expected).abs() <= 1e-9,
            "T = {push}: {imbalance}"
        );
    }
}

#[test]
fn floating_block_pulled_off_captures_errors() {
    let mut sim = block(
        ElementKind::Tri3,
        StandardLaw::from(Signorini),
        0.0,
        1.0, // upwards
        SimulationSettings::default(),
    );
    let err = sim.step(1.0, 1.0).unwrap_err();
    eprintln!("{err}");
    assert!(
        matches!(
            err,
            SolverError::Unbalanced {
                body: 0,
                motion: RigidMotion::Translation {
                    direction: [0.0, 1.0]
                },
                ..
            }
        ),
        "{err:?}"
    );
}

#[test]
fn floating_block_other_paths_captures_errors() {
    for mode in [FlexibilityMode::MatrixFree, FlexibilityMode::ActiveSet] {
        let settings = SimulationSettings::default().with_flexibility(mode);
        let mut sim = block(ElementKind::Tri3, coulomb(0.3), 0.0, -1.0, settings);
        let err = sim.step(1.0, 1.0).unwrap_err();
        assert!(
            matches!(&err, SolverError::Unsupported(m) if m.contains("rigid-body modes")),
            "{err:?}"
        );
    }
}
