//! The delamination scene of seed 5.6.1 (coarse in time): the bipotential solver and the
//! classical RCCM solver agree, and the bipotential needs fewer contact iterations (seed
//! table 5.1: about 8 per step against about 132).

use bipo::presets::DelaminationSpec;
use contact_solver::{Algorithm, InterfaceStatus, SimulationSettings, StepResult};

fn run(algorithm: Algorithm, steps: usize) -> (Vec<StepResult>, usize, usize) {
    let mut settings = SimulationSettings::default();
    settings.solver.algorithm = algorithm;
    let spec = DelaminationSpec {
        steps,
        ..DelaminationSpec::default()
    };
    let mut scene = spec.build(settings).unwrap();
    let results: Vec<StepResult> = (1..=steps).map(|k| scene.step(k).unwrap()).collect();
    let c = scene.simulation.counters();
    (results, c.contact_iterations, c.adhesion_iterations)
}

#[test]
fn bipotential_and_classic_agree_and_bipotential_iterates_less() {
    let steps = 21;
    let (bip, bip_iters, bip_adh) = run(Algorithm::GaussSeidel, steps);
    let (cla, cla_iters, cla_adh) = run(Algorithm::ClassicRccm, steps);
    let scale = bip
        .iter()
        .flat_map(|s| s.contacts.iter().map(|c| c.r.n.abs().max(c.r.t[0].abs())))
        .fold(0.0, f64::max);
    let mut worst = 0.0_f64;
    for (a, b) in bip.iter().zip(&cla) {
        for (x, y) in a.contacts.iter().zip(&b.contacts) {
            worst = worst
                .max((x.r.n - y.r.n).abs())
                .max((x.r.t[0] - y.r.t[0]).abs());
            assert!(
                (x.beta - y.beta).abs() <= 1e-6,
                "β {} vs {}",
                x.beta,
                y.beta
            );
        }
    }
    eprintln!(
        "delamination, {steps} steps: bipotential {bip_iters} contact / {bip_adh} adhesion iterations, \
         classic {cla_iters} / {cla_adh}; max |Δr| = {worst:e} (scale {scale:e})"
    );
    assert!(worst <= 1e-6 * scale, "max |Δr| {worst} vs scale {scale}");
    assert!(
        bip_iters < cla_iters,
        "bipotential {bip_iters} vs classic {cla_iters}"
    );
    // the layer debonds from the lifted end: β falls there and stays 1 at the far end
    let last = bip.last().unwrap();
    let right = last
        .contacts
        .iter()
        .max_by(|a, b| a.position[0].total_cmp(&b.position[0]))
        .unwrap();
    let left = last
        .contacts
        .iter()
        .min_by(|a, b| a.position[0].total_cmp(&b.position[0]))
        .unwrap();
    assert!(
        right.beta < 0.5 && right.gap > 0.0,
        "β at A's end {}",
        right.beta
    );
    assert!(left.beta > 0.99 && left.status != InterfaceStatus::Inactive);
}
