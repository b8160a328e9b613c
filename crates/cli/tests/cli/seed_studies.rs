//! The qualitative facts of the seed's studies 5.6.1 and 5.6.2 on fast variants (fewer steps):
//! β decreases from the loaded end; faster loading delays damage; once debonded the adhesive
//! reaction vanishes and the contact reaction obeys Coulomb; damage never heals.

use bipo::presets::{DelaminationSpec, ShearSpec};
use contact_solver::local::adhesion::AdhesionMethod;
use contact_solver::{ContactRecord, InterfaceStatus, SimulationSettings, StepResult};

fn sorted(res: &StepResult) -> Vec<ContactRecord> {
    let mut v = res.contacts.clone();
    v.sort_by(|a, b| a.position[0].total_cmp(&b.position[0]));
    v
}

#[test]
fn delamination_beta_decreases_from_the_lifted_end() {
    let spec = DelaminationSpec {
        steps: 42,
        ..DelaminationSpec::default()
    };
    let mut scene = spec.build(SimulationSettings::default()).unwrap();
    let mut damaged_somewhere = false;
    for k in 1..=spec.steps {
        let res = scene.step(k).unwrap();
        let line = sorted(&res);
        // A lifts the right end: the damage is largest there, and across the damaged zone
        // (β < 0.9) β is non-increasing towards it. Ahead of the front the layer, a beam on an
        // elastic foundation, oscillates, so β may wiggle slightly (by 4e-5 at β = 0.988) there.
        let end = line.last().unwrap().beta;
        assert!(
            line.iter().all(|c| c.beta >= end),
            "step {k}: β at the end {end}"
        );
        for w in line.windows(2).filter(|w| w[0].beta < 0.9) {
            assert!(
                w[1].beta <= w[0].beta + 1e-12,
                "step {k}: β {} then {}",
                w[0].beta,
                w[1].beta
            );
        }
        damaged_somewhere |= end < 0.5;
    }
    assert!(damaged_somewhere);
}

#[test]
fn faster_loading_delays_damage() {
    let slow = DelaminationSpec {
        steps: 42,
        ..DelaminationSpec::default()
    };
    let fast = DelaminationSpec {
        duration: 1.0,
        ..slow.clone()
    };
    let (mut a, mut b) = (
        slow.build(SimulationSettings::default()).unwrap(),
        fast.build(SimulationSettings::default()).unwrap(),
    );
    let mut strictly = false;
    for k in 1..=slow.steps {
        let (ra, rb) = (sorted(&a.step(k).unwrap()), sorted(&b.step(k).unwrap()));
        // same imposed displacement at step k: the fast run keeps at least as much adhesion
        for (x, y) in ra.iter().zip(&rb) {
            assert!(
                y.beta >= x.beta - 1e-12,
                "step {k}, x = {}: fast β {} < slow β {}",
                x.position[0],
                y.beta,
                x.beta
            );
            strictly |= y.beta > x.beta + 1e-3;
        }
    }
    assert!(strictly);
}

#[test]
fn shear_debonded_contacts_obey_coulomb() {
    let spec = ShearSpec {
        steps: 30,
        ..ShearSpec::default()
    };
    let mu = spec.interface.mu;
    let mut scene = spec.build(SimulationSettings::default()).unwrap();
    let mut previous: Option<Vec<ContactRecord>> = None;
    let mut debonded_slipping = 0;
    for k in 1..=spec.steps {
        let line = sorted(&scene.step(k).unwrap());
        for c in &line {
            // the viscous law drives β to 0 only asymptotically (β → w/(C u²)): "debonded"
            // means β < 1e-4, where the adhesive reaction is negligible
            if c.beta < 1e-4 {
                let rb = c.r_bar.n.hypot(c.r_bar.t[0]);
                assert!(
                    c.r_adh.n.hypot(c.r_adh.t[0]) <= 1e-6 * rb.max(1e-12),
                    "r_adh {:?}",
                    c.r_adh
                );
                let mu_bar = mu * (1.0 - c.beta); // f(β) = 1 − β (m = 1)
                assert!(c.r_bar.t[0].abs() <= mu_bar * c.r_bar.n * (1.0 + 1e-9) + 1e-12);
                if c.status == InterfaceStatus::Slip {
                    debonded_slipping += 1;
                    assert!((c.r_bar.t[0].abs() - mu_bar * c.r_bar.n).abs() <= 1e-8 * rb);
                    assert!(c.r_bar.t[0] * c.slip_increment < 0.0); // friction opposes the slip
                }
            }
        }
        if let Some(prev) = &previous {
            for (p, c) in prev.iter().zip(&line) {
                assert!(c.beta <= p.beta + 1e-12, "β grew at x = {}", c.position[0]);
            }
        }
        previous = Some(line);
    }
    assert!(
        debonded_slipping > 0,
        "the block should slide once debonded"
    );
}

#[test]
fn anderson_acceleration_changes_the_work_not_the_answer() {
    let spec = DelaminationSpec {
        steps: 42,
        ..DelaminationSpec::default()
    };
    let run = |window: usize| {
        let settings = SimulationSettings::default()
            .with_adhesion_method(AdhesionMethod::FixedPoint)
            .with_adhesion_anderson_window(window);
        let mut scene = spec.build(settings).unwrap();
        let results: Vec<StepResult> = (1..=spec.steps).map(|k| scene.step(k).unwrap()).collect();
        (results, scene.simulation.counters().adhesion_iterations)
    };
    let (plain, n_plain) = run(0);
    let (fast, n_fast) = run(1);
    for (a, b) in plain.iter().zip(&fast) {
        for (x, y) in a.contacts.iter().zip(&b.contacts) {
            assert!(
                (x.beta - y.beta).abs() <= 1e-6,
                "β {} vs {}",
                x.beta,
                y.beta
            );
        }
    }
    assert!(n_fast < n_plain, "Anderson {n_fast} vs plain {n_plain}");
}

/// Newton with β eliminated against the seed's fixed point on 5.6.1 and 5.6.2 (42 of the 210
/// steps each): the same answer to the fixed point's tolerance (a state change of 1e-8 per
/// iteration, so 1e-6 leaves room for its accumulated error over the steps), and at most 10
/// contact iterations per step at the median (the seed's table 5.1: 7–8 with 210 steps; these
/// steps are 5 times larger: 9 on 5.6.1, and 6 at 210 steps, `examples/seed_tables.rs`).
#[test]
fn newton_on_the_seed_scenes_gives_the_fixed_points_answer_in_few_iterations() {
    let methods = [AdhesionMethod::Newton, AdhesionMethod::FixedPoint];
    for scene in ["5.6.1", "5.6.2"] {
        let mut runs = Vec::new();
        let mut fallbacks = 0;
        for method in methods {
            let settings = SimulationSettings::default().with_adhesion_method(method);
            let (mut s, n) = if scene == "5.6.1" {
                let spec = DelaminationSpec {
                    steps: 42,
                    ..DelaminationSpec::default()
                };
                (spec.build(settings).unwrap(), spec.steps)
            } else {
                let spec = ShearSpec {
                    steps: 42,
                    ..ShearSpec::default()
                };
                (spec.build(settings).unwrap(), spec.steps)
            };
            let results: Vec<StepResult> = (1..=n).map(|k| s.step(k).unwrap()).collect();
            fallbacks += s.simulation.counters().adhesion_newton_fallbacks;
            runs.push(results);
        }
        let scale = runs[1]
            .iter()
            .flat_map(|s| s.contacts.iter().map(|c| c.r.n.abs().max(c.r.t[0].abs())))
            .fold(0.0, f64::max);
        for (a, b) in runs[0].iter().zip(&runs[1]) {
            for (x, y) in a.contacts.iter().zip(&b.contacts) {
                assert!(
                    (x.beta - y.beta).abs() <= 1e-6,
                    "{scene}: β {} vs {}",
                    x.beta,
                    y.beta
                );
                let dr = (x.r.n - y.r.n).abs().max((x.r.t[0] - y.r.t[0]).abs());
                assert!(dr <= 1e-6 * scale, "{scene}: |Δr| {dr} (scale {scale})");
            }
        }
        let mut per_step: Vec<usize> = runs[0]
            .iter()
            .map(|s| s.report.contact_iterations)
            .collect();
        per_step.sort_unstable();
        let median = per_step[per_step.len() / 2];
        let fixed: usize = runs[1].iter().map(|s| s.report.contact_iterations).sum();
        let newton: usize = per_step.iter().sum();
        eprintln!(
            "{scene}: Newton {newton} contact iterations (median {median}/step, {fallbacks} \
             fallbacks to the fixed point), fixed point {fixed}"
        );
        assert!(
            median <= 10,
            "{scene}: median {median} contact iterations per step"
        );
        assert!(
            newton < fixed,
            "{scene}: Newton {newton} vs fixed point {fixed}"
        );
    }
}
