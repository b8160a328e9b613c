//! Two elastic cylinders (issue 16): Hertz between two elastic bodies in both zone kinds
//! (node pairs, node-to-segment), and the Cattaneo–Mindlin partial slip of two identical
//! cylinders pressed by `P` then sheared by `Q`, with the Mindlin–Deresiewicz unloading.
//!
//! Sources: H. Hertz (1882); C. Cattaneo (1938); R. D. Mindlin (1949); R. D. Mindlin and
//! H. Deresiewicz (1953); all as in K. L. Johnson, *Contact Mechanics*, Cambridge 1985, §4.2
//! (two cylinders: `1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂`, `1/R = 1/R₁ + 1/R₂`,
//! `a = √(4PR/(πE*))`, `p0 = 2P/(πa)`) and §7.1–7.2 (`c/a = √(1 − Q/(μP))`, the Mindlin
//! traction, and the unloading from `Q*`: reversed slip on `c' < |x| < a`,
//! `c'/a = √(1 − (Q* − Q)/(2μP))`, and `q_unload(Q) = q(Q*) − 2 q((Q* − Q)/2)` so that the
//! tangential displacement obeys `δ_unload(Q) = δ(Q*) − 2 δ((Q* − Q)/2)`).
//!
//! Scene and measurements: `tests/support/cylinders.rs` (P2, fine zone `[0, 1.5]` of 16
//! cells, `h ≈ a/11`; the upper body floats, held by contact, loaded on a tied rigid cap).
//!
//! What is asserted, and why:
//! - Hertz (`R₁ = 100`, `E₁ = 1000`, `ν₁ = 0.3` on `R₂ = 150`, `E₂ = 3000`, `ν₂ = 0.25`,
//!   half model): `P` reproduced by the vertical reactions to `1e-10` (the floating body's
//!   equilibrium is solved to `1e-11` of the forces); `a` and `p0` within 1 % of Hertz (the
//!   one-body force-controlled Hertz on this mesh is within 0.5 %). `p0` is the mean
//!   pressure over `|x| < a/2` scaled by Hertz's shape there: with a non-matching or P1
//!   lower mesh the nodal forces oscillate from node to node by a few %, which a pointwise
//!   L2 projection at `x = 0` amplifies to 12–20 % (printed as `projected p0`);
//! - Cattaneo–Mindlin: no tangential reaction and no slip after pressing (β = 0: identical
//!   bodies); `c/a` within 5 % of `√(1 − Q/(μP))` for `Q/(μP)` = 0.2, 0.4, 0.6, 0.8; the
//!   tangential traction within 5 % of `μ p0` of Mindlin's, both lumped to the nodes the
//!   same way (`∫ q N_i dx / ∫ N_i dx`), at every node of the contact farther than 1.5 node
//!   spacings from `c` (the cusp of Mindlin's traction at `c` is not resolved within a node
//!   spacing: up to 9 % there); the meshes of the two bodies are exact mirror images, so
//!   β = 0 holds for the discrete problem too;
//! - unloading from `Q* = 0.8 μP` to `0.4 μP`: the outer contacts slip backwards, the inner
//!   ones do not (`c'/a = √0.8`, checked against the nodes' positions with one node of
//!   slack), and the cap's tangential displacement satisfies Mindlin–Deresiewicz's
//!   `δ(0.4 ↓) = δ(0.8) − 2 δ(0.2)` within 2 % of `δ(0.8)` (an exact consequence of the
//!   superposition that the discretisation keeps to its own error).

#![cfg(feature = "fe")]

use crate::support::cylinders::{Body, Cylinders, Pairing};
use contact_laws::{Coulomb, Signorini, StandardLaw};
use contact_solver::SimulationSettings;

fn hertz(pairing: Pairing, kind: fem_core::ElementKind, upper_cells: usize, lower_cells: usize) {
    let upper = Body {
        radius: 100.0,
        young: 1000.0,
        poisson: 0.3,
        fine_cells: upper_cells,
    };
    let lower = Body {
        radius: 150.0,
        young: 3000.0,
        poisson: 0.25,
        fine_cells: lower_cells,
    };
    let mut scene = Cylinders::new(upper, lower, true, pairing);
    scene.kind = kind;
    let mut sim = scene.simulation(Signorini.into(), SimulationSettings::default());
    // a ≈ 1: P = π a² E* / (4 R)
    let p = std::f64::consts::PI * scene.e_star() / (4.0 * scene.relative_radius());
    Cylinders::load(&mut sim, true, 0.0, p);
    let res = sim
        .step(1.0, 1.0)
        .expect("the two-cylinder Hertz step converges");
    let m = scene.measure(&sim, &res, 0.0);
    let (a, p0) = scene.hertz(p);
    eprintln!(
        "{pairing:?} {kind:?} {upper_cells}/{lower_cells}: P = {p} -> {:.12} ({:+.1e}), a = {:.5} vs {a:.5} ({:+.2e}), p0 = {:.5} vs \
         {p0:.5} ({:+.2e}); {} active, {} passes, {:.2?}",
        m.p_total,
        (m.p_total - p) / p,
        m.a,
        (m.a - a) / a,
        m.p0,
        (m.p0 - p0) / p0,
        res.report.active_contacts,
        res.report.detection_passes,
        res.report.wall_time
    );
    eprintln!(
        "   projected p0 {:.5} ({:+.2e})",
        m.p0_projected,
        (m.p0_projected - p0) / p0
    );
    assert!(((m.p_total - p) / p).abs() <= 1e-10, "P = {}", m.p_total);
    assert!(((m.a - a) / a).abs() < 0.01, "a = {} vs {a}", m.a);
    assert!(((m.p0 - p0) / p0).abs() < 0.01, "p0 = {} vs {p0}", m.p0);
    assert!(res.contacts.iter().all(|c| c.gap >= -1e-9));
}

#[test]
fn hertz_two_elastic_cylinders_node_pairs_works() {
    hertz(Pairing::NodePairs, fem_core::ElementKind::Tri6, 16, 16);
}

#[test]
fn hertz_two_elastic_cylinders_node_to_segment_works() {
    // a lower mesh that does not match the upper one
    hertz(Pairing::Segments, fem_core::ElementKind::Tri6, 16, 13);
    // P1, non-matching too
    hertz(Pairing::Segments, fem_core::ElementKind::Tri3, 32, 26);
}

/// Mindlin's tangential traction (magnitude, along the shear) at `x`.
fn mindlin(x: f64, a: f64, p0: f64, mu: f64, c: f64) -> f64 {
    let ellipse = |w: f64| {
        if x.abs() < w {
            (1.0 - x * x / (w * w)).sqrt()
        } else {
            0.0
        }
    };
    mu * p0 * ellipse(a) - mu * p0 * (c / a) * ellipse(c)
}

#[test]
fn cattaneo_mindlin_works() {
    let body = Body {
        radius: 100.0,
        young: 1000.0,
        poisson: 0.3,
        fine_cells: 16,
    };
    let mu = 0.3;
    let scene = Cylinders::new(body, body, false, Pairing::NodePairs);
    let law: StandardLaw = Coulomb::new(mu).unwrap().into();
    let mut sim = scene.simulation(law, SimulationSettings::default());
    let p = std::f64::consts::PI * scene.e_star() / (4.0 * scene.relative_radius());
    let (a, p0) = scene.hertz(p);
    let h = scene.fine_extent / body.fine_cells as f64 / 2.0; // P2 node spacing
    // 1. pressed by P: identical bodies (β = 0) take no tangential reaction and do not slip
    Cylinders::load(&mut sim, false, 0.0, p);
    let res = sim.step(1.0, 1.0).expect("pressing converges");
    let m = scene.measure(&sim, &res, mu);
    let t_max = res
        .contacts
        .iter()
        .map(|c| c.r.t[0].abs())
        .fold(0.0, f64::max);
    let n_max = res.contacts.iter().map(|c| c.r.n).fold(0.0, f64::max);
    eprintln!(
        "pressed: P = {:.10}, a = {:.5} vs {a:.5}, max |r_t| = {t_max:.2e} (max r_n {n_max:.3}), \
         statuses {:?}",
        m.p_total,
        m.a,
        res.contacts
            .iter()
            .filter(|c| c.r.n > 0.0)
            .map(|c| c.status.name())
            .collect::<std::collections::BTreeSet<_>>()
    );
    assert!(((m.p_total - p) / p).abs() < 1e-10);
    assert!(
        t_max <= 1e-8 * n_max,
        "tangential reaction {t_max:e} after pressing"
    );
    assert!(
        res.contacts
            .iter()
            .all(|c| c.slip_increment.abs() <= 1e-10 * a && c.status.name() != "slip")
    );
    // 2. sheared by Q = 0.2 … 0.8 μP
    let mut delta = vec![0.0];
    for (k, ratio) in [0.2, 0.4, 0.6, 0.8].into_iter().enumerate() {
        let q = ratio * mu * p;
        Cylinders::load(&mut sim, false, q, p);
        let res = sim.step(2.0 + k as f64, 1.0).expect("shearing converges");
        let m = scene.measure(&sim, &res, mu);
        let c_exact = (1.0 - ratio).sqrt();
        let c_fe = m.c / m.a;
        // the nodal tangential forces against Mindlin's traction lumped the same way
        // (∫ q N_i dx), as tractions (÷ ∫ N_i dx), at the nodes inside the contact, relative
        // to μ p0: `err` away from the stick–slip boundary (farther than 1.5 node spacings
        // from c, where the cusp of Mindlin's traction is not resolved), `err_all` everywhere
        let sign = m.q_total.signum(); // the friction on the upper body opposes Q
        let mesh = sim.structure().mesh();
        let (mut err, mut err_all) = (0.0_f64, 0.0_f64);
        for (node, x, q_i, w_i) in crate::support::cylinders::consistent(mesh, "up.bottom", |x| {
            mindlin(x, a, p0, mu, c_exact * a)
        }) {
            if x.abs() >= a {
                continue;
            }
            let f = res
                .contacts
                .iter()
                .find(|c| c.node == node)
                .map_or(0.0, |c| c.r.t[0]);
            let e = (sign * f - q_i).abs() / w_i / (mu * p0);
            err_all = err_all.max(e);
            if (x.abs() - c_exact * a).abs() > 1.5 * h {
                err = err.max(e);
            }
        }
        let slipping = res
            .contacts
            .iter()
            .filter(|c| c.status.name() == "slip")
            .count();
        delta.push(Cylinders::cap_displacement(&sim)[0]);
        eprintln!(
            "Q/μP = {ratio}: Q = {:.10} vs {q:.10}, c/a = {c_fe:.4} vs {c_exact:.4} ({:+.2e}), \
             traction error {err:.3} μp0 ({err_all:.3} next to c), {slipping} slipping, δ = {:.6e}",
            -m.q_total,
            (c_fe - c_exact) / c_exact,
            delta.last().unwrap()
        );
        assert!(((-m.q_total - q) / q).abs() < 1e-9, "Q = {}", -m.q_total);
        assert!(
            ((c_fe - c_exact) / c_exact).abs() < 0.05,
            "c/a = {c_fe} vs {c_exact}"
        );
        assert!(err < 0.05, "traction error {err} μ p0");
    }
    // 3. unloading from Q* = 0.8 μP to 0.4 μP: a reversed slip annulus c' < |x| < a
    let (q_star, q_back) = (0.8 * mu * p, 0.4 * mu * p);
    Cylinders::load(&mut sim, false, q_back, p);
    let res = sim.step(6.0, 1.0).expect("unloading converges");
    let m = scene.measure(&sim, &res, mu);
    let c_back = a * (1.0 - (q_star - q_back) / (2.0 * mu * p)).sqrt();
    let loading_sign = -1.0; // friction on the upper body opposed Q > 0 while loading
    let mut reversed = (0usize, 0usize);
    for c in res.contacts.iter().filter(|c| c.r.n > 0.0) {
        let x = c.position[0].abs();
        let backwards = c.status.name() == "slip" && c.r.t[0] * loading_sign < 0.0;
        if x > c_back + h {
            reversed.0 += 1;
            assert!(backwards, "x = {x}: {:?} r_t = {}", c.status, c.r.t[0]);
        } else if x < c_back - h {
            reversed.1 += usize::from(backwards);
        }
    }
    let d_back = Cylinders::cap_displacement(&sim)[0];
    let d_md = delta[4] - 2.0 * delta[1];
    eprintln!(
        "unloaded to 0.4 μP: Q = {:.10}, reversed slip at {} nodes beyond c' = {c_back:.4} \
         ({} inside), δ = {d_back:.6e} vs Mindlin–Deresiewicz {d_md:.6e} ({:+.2e} of δ(0.8))",
        -m.q_total,
        reversed.0,
        reversed.1,
        (d_back - d_md) / delta[4]
    );
    assert!(reversed.0 >= 2 && reversed.1 == 0);
    assert!(((d_back - d_md) / delta[4]).abs() < 0.02);
    assert!(
        d_back > delta[2],
        "hysteresis: unloading to 0.4 stays beyond loading to 0.4"
    );
}

/// Laws by phase (issue 16): the same two cylinders pressed *without* friction, then sheared
/// with Coulomb friction after `ContactSimulation::set_law` — the usual way to set up a
/// Cattaneo–Mindlin test in codes that cannot press with friction. With β = 0 pressing
/// creates no tangential traction either way, so the sheared state must be the one of
/// pressing with friction: the same reactions to `1e-9` of `P` and the same cap
/// displacement to `1e-9` relative (both runs solve to `tol = 1e-10`).
#[test]
fn laws_by_phase_works() {
    let body = Body {
        radius: 100.0,
        young: 1000.0,
        poisson: 0.3,
        fine_cells: 12,
    };
    let mu = 0.3;
    let scene = Cylinders::new(body, body, false, Pairing::NodePairs);
    let coulomb: StandardLaw = Coulomb::new(mu).unwrap().into();
    let p = std::f64::consts::PI * scene.e_star() / (4.0 * scene.relative_radius());
    let q = 0.5 * mu * p;
    let run = |press: StandardLaw| {
        let mut sim = scene.simulation(press, SimulationSettings::default());
        Cylinders::load(&mut sim, false, 0.0, p);
        sim.step(1.0, 1.0).expect("pressing converges");
        let err = sim.set_law("interfaces", coulomb).unwrap_err();
        assert!(err.to_string().contains("`interface`"), "{err}");
        sim.set_law("interface", coulomb).unwrap();
        Cylinders::load(&mut sim, false, q, p);
        let res = sim.step(2.0, 1.0).expect("shearing converges");
        (res, Cylinders::cap_displacement(&sim))
    };
    let (with, d_with) = run(coulomb);
    let (without, d_without) = run(Signorini.into());
    let gap = with
        .contacts
        .iter()
        .zip(&without.contacts)
        .map(|(a, b)| (a.r.n - b.r.n).abs().max((a.r.t[0] - b.r.t[0]).abs()))
        .fold(0.0, f64::max);
    eprintln!(
        "pressed with / without friction, then sheared: reactions differ by {gap:.2e} (P = {p:.3}), \
         cap u_x {:.9e} vs {:.9e}",
        d_with[0], d_without[0]
    );
    assert!(gap <= 1e-9 * p);
    assert!((d_with[0] - d_without[0]).abs() <= 1e-9 * d_with[0].abs());
}
