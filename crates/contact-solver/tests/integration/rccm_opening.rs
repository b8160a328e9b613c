//! RCCM single-interface opening: a stiff block glued to a rigid base (initial gap 0), pulled
//! normally by its top face. Per unit area: `σ = β² C_n u_n`; with α = 0 the peak stress is
//! `√(w C_n)` at `u₀ = √(w/C_n)` and the work to decohesion is `w`; with α > 0 the peak rises
//! with the loading rate (seed figs 5.12–5.13).

#![cfg(feature = "fe")]

use contact_laws::{BetaScheme, Rccm, RccmParams};
use contact_solver::{
    ContactSimulation, ContactZone, InterfaceStatus, RigidLine, SimulationSettings,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};

const C_N: f64 = 100.0;
const W: f64 = 0.01;
const E: f64 = 1e5;
const WIDTH: f64 = 2.0;

fn glued_block(alpha: f64) -> (ContactSimulation<LinearElasticModel, Rccm>, Vec<usize>) {
    glued_block_with(alpha, SimulationSettings::default())
}

fn glued_block_with(
    alpha: f64,
    settings: SimulationSettings,
) -> (ContactSimulation<LinearElasticModel, Rccm>, Vec<usize>) {
    let mesh = rectangle(&RectangleSpec::new([0.0, WIDTH], [0.0, 1.0], 6, 3)).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0).unwrap();
    supports.fix(&top, Component::X);
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(E, 0.0, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let law = Rccm::new(RccmParams {
        c_n: C_N,
        c_t: C_N,
        w: W,
        alpha,
        mu: 0.2,
        m: 1,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap();
    let base = RigidLine::new([-1.0, 0.0], [WIDTH + 1.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("glue", bottom, base, law, 1e-3);
    let sim = ContactSimulation::new(model, vec![zone], settings).unwrap();
    (sim, top)
}

/// Pulls the top through `path` (top displacements) over `duration`; returns (u_n, σ) per step
/// with σ the mean tensile stress on the interface.
fn pull(alpha: f64, path: &[f64], duration: f64) -> Vec<(f64, f64)> {
    let (mut sim, top) = glued_block(alpha);
    let n = path.len() as f64;
    let mut out = Vec::new();
    for (k, &d) in path.iter().enumerate() {
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, d)
            .unwrap();
        let res = sim.step(duration * (k + 1) as f64 / n, 1.0).unwrap();
        let tension: f64 = -res.contacts.iter().map(|c| c.r.n).sum::<f64>() / WIDTH;
        let u_n = res.contacts.iter().map(|c| c.gap).sum::<f64>() / res.contacts.len() as f64;
        // the interface opens uniformly (ν = 0, uniaxial) and no r̄ acts in tension
        for c in &res.contacts {
            assert!(
                (c.gap - u_n).abs() <= 1e-9 * u_n.abs().max(1e-12),
                "{} vs {u_n}",
                c.gap
            );
            if u_n > 0.0 {
                assert_eq!(c.status, InterfaceStatus::Open);
                assert_eq!(c.r_bar, contact_laws::LocalVec2::zeros());
            }
        }
        out.push((u_n, tension));
    }
    out
}

/// Top displacements: through the exact peak `d₀ = u₀ + σ_peak h/E`, then geometric to 40 u₀.
fn path() -> Vec<f64> {
    let u0 = (W / C_N).sqrt();
    let d0 = u0 + (W * C_N).sqrt() / E;
    let mut p: Vec<f64> = (1..=20).map(|k| d0 * k as f64 / 20.0).collect();
    let mut d = d0;
    while d < 40.0 * u0 {
        d *= 1.02;
        p.push(d);
    }
    p
}

#[test]
fn rate_independent_peak_and_work() {
    let curve = pull(0.0, &path(), 1.0);
    let peak_exact = (W * C_N).sqrt();
    let peak = curve.iter().map(|c| c.1).fold(f64::MIN, f64::max);
    assert!(
        (peak - peak_exact).abs() <= 1e-6 * peak_exact,
        "peak {peak} vs √(wC) {peak_exact}"
    );
    // stress–opening curve follows σ = C u before the peak and w²/(C u³) after it
    for &(u, s) in &curve {
        let law = if u <= (W / C_N).sqrt() {
            C_N * u
        } else {
            W * W / (C_N * u.powi(3))
        };
        assert!(
            (s - law).abs() <= 1e-6 * peak_exact,
            "u {u}: σ {s} vs {law}"
        );
    }
    // work to decohesion: trapezoids, plus the analytic tail ∫_u^∞ w²/(C v³) dv = σ u / 2
    let mut work = 0.0;
    let mut prev = (0.0, 0.0);
    for &c in &curve {
        work += 0.5 * (c.1 + prev.1) * (c.0 - prev.0);
        prev = c;
    }
    work += 0.5 * prev.1 * prev.0;
    assert!((work - W).abs() <= 2e-3 * W, "work {work} vs w {W}");
    eprintln!("alpha = 0: peak {peak:.9} (√(wC) = {peak_exact}), work {work:.6e} (w = {W})");
}

#[test]
fn viscous_adhesion_peaks_higher_when_pulled_faster() {
    let p = path();
    let peak = |duration: f64| {
        pull(1.0, &p, duration)
            .iter()
            .map(|c| c.1)
            .fold(f64::MIN, f64::max)
    };
    let (slow, fast) = (peak(100.0), peak(10.0));
    let limit = (W * C_N).sqrt();
    eprintln!("alpha = 1: peak slow {slow:.6}, fast {fast:.6}, rate-independent {limit:.6}");
    assert!(
        slow > limit * 1.001,
        "viscosity delays damage: {slow} vs {limit}"
    );
    assert!(
        fast > slow * 1.01,
        "faster loading, higher peak: {fast} vs {slow}"
    );
}

/// The reduced problem a Newton step exports (formed on request from `F*` and the final
/// states) is the fixed point's, and its solution is the step's `r̄`.
#[test]
fn newton_steps_export_the_condensed_problem_they_solved() {
    use contact_solver::local::adhesion::AdhesionMethod;
    use contact_solver::{UzawaSettings, UzawaSolver};
    let exported = |method: AdhesionMethod| {
        let settings = SimulationSettings::default().with_adhesion_method(method);
        let (mut sim, top) = glued_block_with(0.0, settings);
        // pressed and sheared past the tangential springs' peak (½ C_t u_t² > w at
        // u_t > 0.014): r̄ in the cone, the springs damaged (β < 1), μ̄ = μ (1 − β) grown
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, -1e-5)
            .unwrap();
        sim.structure_mut()
            .set_prescribed(&top, Component::X, 0.02)
            .unwrap();
        let res = sim.step(1.0, 1.0).unwrap();
        assert!(res.contacts.iter().all(|c| c.beta > 0.1 && c.beta < 0.9));
        assert_eq!(sim.counters().adhesion_newton_fallbacks, 0);
        let r_bar: Vec<f64> = sim
            .last_active()
            .iter()
            .flat_map(|&i| [res.contacts[i].r_bar.n, res.contacts[i].r_bar.t[0]])
            .collect();
        let p = sim.last_reduced_problem().expect("a dense step").clone();
        (p, r_bar)
    };
    let (newton, r_newton) = exported(AdhesionMethod::Newton);
    let (fixed, _) = exported(AdhesionMethod::FixedPoint);
    let scale = |v: &[f64]| v.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
    // the two answers' states agree to the fixed point's tolerance (a β change of 1e-8)
    let (wn, wf) = (newton.w_dense().unwrap(), fixed.w_dense().unwrap());
    let dw = wn
        .iter()
        .zip(wf)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(dw <= 1e-6 * scale(wf), "W̃ differs by {dw:e}");
    let dq = newton
        .q()
        .iter()
        .zip(fixed.q())
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(dq <= 1e-6 * scale(fixed.q()), "q̃ differs by {dq:e}");
    // re-solved: the step's r̄ (both stop at a relative residual of 1e-10)
    let mut settings = UzawaSettings::default();
    settings.tol = 1e-12;
    let s = UzawaSolver::new(settings)
        .solve(&newton, &newton.coulomb_laws())
        .unwrap();
    let d =
        s.r.iter()
            .zip(&r_newton)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(scale(&r_newton) > 0.0);
    assert!(d <= 1e-7 * scale(&r_newton), "r̄ differs by {d:e}");
}

/// Newton from the previous step's reactions (the warm start, on by default) gives the answer
/// of Newton from the loose start on a sheared glued interface that damages over the steps.
#[test]
fn warm_started_newton_follows_the_same_path() {
    let run = |warm: bool| {
        let settings = SimulationSettings::default().with_adhesion_warm_start(warm);
        let (mut sim, top) = glued_block_with(0.0, settings);
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, -1e-5)
            .unwrap();
        let mut out = Vec::new();
        for k in 1..=30 {
            sim.structure_mut()
                .set_prescribed(&top, Component::X, 1e-3 * k as f64)
                .unwrap();
            let res = sim.step(k as f64, 1.0).unwrap();
            out.extend(res.contacts.iter().map(|c| (c.r.n, c.r.t[0], c.beta)));
        }
        (out, sim.counters())
    };
    let (warm, c_warm) = run(true);
    let (cold, c_cold) = run(false);
    assert!(c_warm.adhesion_warm_starts >= 15, "{c_warm:?}");
    assert_eq!(
        c_cold.adhesion_warm_starts + c_cold.adhesion_warm_start_failures,
        0
    );
    // the damage went on: β fell from 1 on every contact
    assert!(warm.iter().rev().take(7).all(|&(_, _, b)| b < 0.9));
    let scale = warm
        .iter()
        .fold(0.0_f64, |m, a| m.max(a.0.abs()).max(a.1.abs()));
    // both stop at Newton's tolerance (1e-10 relative): their answers agree far closer than
    // 1e-7 of the largest reaction; β to the fixed point's 1e-8
    for (a, b) in warm.iter().zip(&cold) {
        assert!((a.0 - b.0).abs() <= 1e-7 * scale, "{a:?} vs {b:?}");
        assert!((a.1 - b.1).abs() <= 1e-7 * scale, "{a:?} vs {b:?}");
        assert!((a.2 - b.2).abs() <= 1e-8, "{a:?} vs {b:?}");
    }
}
