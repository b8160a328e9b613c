//! Issue 39: an adhesive (RCCM) interface pulled dynamically ([`MoreauJean`] on a
//! [`DynamicModel`], `moreau_jean.rs` "Adhesion at velocity level").
//!
//! A stiff block (`E = 1e5`, `ν = 0`, 2 × 1, P1 4 × 2) glued by the RCCM law (`C_n = C_t =
//! 100`, `w = 0.01`, `α = 0`, `μ = 0.2`; Raous, Cangémi & Cocu 1999) to a rigid base, its top
//! pulled up at a constant rate to `5 u₀` (`u₀ = √(w/C_n) = 0.01`, past the peak stress
//! `√(w C_n)`) in 100 steps of `h = 0.01`. Per unit area `σ = β² C_n u_n` with `β = w/(C_n
//! u_n²)` past `u₀` (seed figs 5.12–5.13), so the damage dissipates `w (1 − β_end)` per unit
//! area (the law's fracture energy, `energy.rs`).
//!
//! - As the density goes to 0 (`ρ = 1, 1e-2, 1e-4`: `c h / H = 3, 30, 300`) the dynamic force
//!   `−Σ r_n / h` tends to the quasi-static one (`ContactSimulation` on the same block and
//!   path): with `θ = 1` and `β` iterated within the step ([`AdhesionUpdate::Implicit`]) the
//!   limit step is the quasi-static step, and the errors shrink with `ρ` (tabulated in
//!   `docs/validation.md`). With `β` of the step's start ([`AdhesionUpdate::Lagged`]) they
//!   shrink to the lag's floor (`O(h)`: `β` a step late).
//! - The energy balance `ΔT + ΔV + ΔE_adh = W_ext − D_impact − D_friction − D_damage − D_θ`
//!   closes to 1e-8 relative at every step, and its split agrees with the global work of the
//!   impulses.

#![cfg(feature = "fe")]

use contact_laws::{BetaScheme, Rccm, RccmParams};
use contact_solver::coupling::simulation::{AdhesionUpdate, MoreauJean};
use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};

const C_N: f64 = 100.0;
const W: f64 = 0.01;
const WIDTH: f64 = 2.0;
const STEPS: usize = 100;
const H: f64 = 0.01;

fn law() -> Rccm {
    Rccm::new(RccmParams {
        c_n: C_N,
        c_t: C_N,
        w: W,
        alpha: 0.0,
        mu: 0.2,
        m: 1,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap()
}

/// The top displacement at step `k` (1-based): `5 u₀ k / 100`.
fn pulled(k: usize) -> f64 {
    5.0 * (W / C_N).sqrt() * k as f64 / STEPS as f64
}

/// The glued block of density `density`; its top nodes and its glued zone.
fn block(density: f64) -> (LinearElasticModel, Vec<usize>, ContactZone<Rccm>) {
    let mesh = rectangle(&RectangleSpec::new([0.0, WIDTH], [0.0, 1.0], 4, 2)).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0).unwrap();
    supports.fix(&top, Component::X);
    let m = Material::new(1e5, 0.0, 0.0)
        .unwrap()
        .with_density(density)
        .unwrap();
    let model =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], supports).unwrap();
    let base = RigidLine::new([-1.0, 0.0], [WIDTH + 1.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("glue", bottom, base, law(), 1e-3);
    (model, top, zone)
}

/// The quasi-static tension `−Σ r_n` per step.
fn quasi_static() -> Vec<f64> {
    let (model, top, zone) = block(1.0);
    let mut sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap();
    (1..=STEPS)
        .map(|k| {
            sim.structure_mut()
                .set_prescribed(&top, Component::Y, pulled(k))
                .unwrap();
            let res = sim.step(H * k as f64, 1.0).unwrap();
            -res.contacts.iter().map(|c| c.r.n).sum::<f64>()
        })
        .collect()
}

/// What a dynamic pull measured.
struct Pull {
    /// The tension `−Σ r_n / h` per step.
    tension: Vec<f64>,
    /// Largest `|residual| / scale` of the balance and of its split over the steps.
    balance: f64,
    split: f64,
    /// The damage dissipated, and `w A (1 − β)` summed over the contacts at the end.
    damage: f64,
    fracture: f64,
}

fn dynamic(density: f64, update: AdhesionUpdate) -> Pull {
    let (model, top, zone) = block(density);
    let body = DynamicModel::new(model, MassKind::Consistent, Rayleigh::default()).unwrap();
    let scheme = MoreauJean::new(1.0).unwrap().with_adhesion_update(update);
    let mut sim =
        ContactSimulation::with_scheme(body, vec![zone], SimulationSettings::default(), scheme)
            .unwrap();
    let (mut tension, mut balance, mut split) = (Vec::new(), 0.0_f64, 0.0_f64);
    let mut fracture = 0.0;
    for k in 1..=STEPS {
        sim.structure_mut()
            .update(|m| m.set_prescribed(&top, Component::Y, pulled(k)).map(|_| ()))
            .unwrap()
            .unwrap();
        let res = sim.advance(H).unwrap();
        tension.push(-res.contacts.iter().map(|c| c.r.n).sum::<f64>() / H);
        let e = sim.scheme().energy();
        balance = balance.max(e.residual().abs() / e.scale());
        split = split.max(e.split_residual().abs() / e.scale());
        fracture = res
            .contacts
            .iter()
            .map(|c| W * c.area * (1.0 - c.beta))
            .sum();
    }
    Pull {
        tension,
        balance,
        split,
        damage: sim.scheme().energy().damage,
        fracture,
    }
}

/// `max |a − b| / max |b|`.
fn error(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

#[test]
fn issue_39_rccm_pull_tends_to_quasi_static() {
    let reference = quasi_static();
    let peak = reference.iter().fold(0.0_f64, |m, v| m.max(*v));
    // the quasi-static curve itself: the peak √(w C_n) × width, within the path's resolution
    let exact = (W * C_N).sqrt() * WIDTH;
    assert!((peak - exact).abs() < 0.02 * exact, "{peak} vs {exact}");
    let mut errors = Vec::new();
    for density in [1.0, 1e-2, 1e-4] {
        let implicit = dynamic(density, AdhesionUpdate::Implicit);
        let lagged = dynamic(density, AdhesionUpdate::Lagged);
        let (e_i, e_l) = (
            error(&implicit.tension, &reference),
            error(&lagged.tension, &reference),
        );
        eprintln!(
            "ρ = {density:e}: error implicit {e_i:.2e}, lagged {e_l:.2e}; balance {:.1e} / {:.1e}, \
             split {:.1e} / {:.1e}; damage {:.5} (lagged {:.5}) vs w A (1 − β) {:.5}",
            implicit.balance,
            lagged.balance,
            implicit.split,
            lagged.split,
            implicit.damage,
            lagged.damage,
            implicit.fracture
        );
        for p in [&implicit, &lagged] {
            // the balance, damage included, closes to 1e-8 (issue 39), measured near 1e-14
            assert!(
                p.balance < 1e-8 && p.split < 1e-8,
                "{} {}",
                p.balance,
                p.split
            );
            // the damage dissipation is the fracture energy w A (1 − β) of what broke, up to
            // the path's resolution (Δu = u₀/20: a 5 % step at the peak), measured below 3 %
            assert!(
                (p.damage - p.fracture).abs() < 0.05 * p.fracture,
                "{} vs {}",
                p.damage,
                p.fracture
            );
        }
        errors.push(e_i);
    }
    // the errors shrink with the density, and the lightest block is on the quasi-static curve
    assert!(errors[1] < errors[0] && errors[2] < errors[1], "{errors:?}");
    assert!(errors[2] < 1e-2, "{errors:?}");
}
