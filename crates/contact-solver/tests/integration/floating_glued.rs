//! A floating block glued by an RCCM interface (issue 16): a block with **no support**, glued
//! to a rigid LINE (initial gap 0, `β₀ = 1`), pulled up by a force `F` on its top. The
//! adhesive springs alone hold it; the rigid-body amplitudes are solved with them (the
//! floating equilibrium's Jacobian by finite differences, as the springs resist motions the
//! contacts' statuses do not see).
//!
//! Source: the RCCM law in traction (Raous, Cangémi & Cocou 1999; seed ch. 3, eq. 3.5): per
//! unit area `σ = β² C_n u_n`, no damage while `½ C_n u_n² < w` (α = 0: rate-independent),
//! the peak `√(w C_n)` at `u₀ = √(w/C_n)`; statics: the springs carry `F`.
//!
//! ```text
//!            ↑ F (uniform traction on the top, F = 1)
//!   y = 1  ┌──────────────┐   E = 1e5, ν = 0: a stiff block, width 2
//!          │              │   no support at all
//!   y = 0  └──────────────┘   RCCM glue: C_n = C_t = 100, w = 0.01, μ = 0.2, β₀ = 1
//!   ═══════════════════════════ rigid LINE y = 0
//! ```
//! What is asserted, and why:
//! - `F = 1` (half the strength `2 √(w C_n) = 2`): `Σ r_n = −F` to `1e-8` relative (the
//!   floating equilibrium is solved to `1e-11` of the forces; the adhesion fixed point and
//!   the finite differences bring it to that of the reduced solves), an opening
//!   `u_n = F/(2 C_n) = 0.005` at every node to 1e-6 (the block's own stretch is
//!   `F/(2E) = 5e-6`, under the bound), `β = 1` (no damage below `u₀ = 0.01`);
//! - `F = 3`, above the strength: `SolverError::Unbalanced` along the vertical translation
//!   (the springs soften past their peak, so the equilibrium iteration stops making progress).

#![cfg(feature = "fe")]

use contact_laws::{BetaScheme, Rccm, RccmParams};
use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings, SolverError};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Idealization, LinearElasticModel, Material, RigidMotion, Supports};

fn glued(force: f64) -> ContactSimulation<LinearElasticModel, Rccm> {
    let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 6, 3)).unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut model = LinearElasticModel::floating(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1e5, 0.0, 0.0).unwrap())],
        Supports::new(),
    )
    .unwrap();
    model
        .add_edge_traction("top", |_| [0.0, force / 2.0])
        .unwrap();
    let law = Rccm::new(RccmParams {
        c_n: 100.0,
        c_t: 100.0,
        w: 0.01,
        alpha: 0.0,
        mu: 0.2,
        m: 1,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap();
    let base = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("glue", bottom, base, law, 1e-3);
    ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap()
}

#[test]
fn floating_glued_block_pulled_works() {
    let mut sim = glued(1.0);
    let res = sim.step(1.0, 1.0).expect("the glue holds the block");
    let total: f64 = res.contacts.iter().map(|c| c.r.n).sum();
    eprintln!(
        "Σ r_n = {total:.14}, gaps {:?}, β {:?}, α = {:?}, {} Newton iterations, {} solves",
        res.contacts.iter().map(|c| c.gap).collect::<Vec<_>>(),
        res.contacts.iter().map(|c| c.beta).collect::<Vec<_>>(),
        sim.rigid_body_amplitudes(),
        res.report.equilibrium_iterations,
        res.report.equilibrium_solves
    );
    assert!((total + 1.0).abs() <= 1e-8, "Σ r_n = {total}");
    for c in &res.contacts {
        assert!((c.gap - 0.005).abs() <= 1e-6, "gap {}", c.gap);
        assert!((c.beta - 1.0).abs() <= 1e-12, "β {}", c.beta);
    }
}

#[test]
fn floating_glued_block_pulled_beyond_its_strength_is_an_error() {
    let mut sim = glued(3.0);
    let err = sim.step(1.0, 1.0).unwrap_err();
    eprintln!("{err}");
    // the springs soften past their peak: no equilibrium along the vertical translation
    let SolverError::Unbalanced { motion, .. } = err else {
        panic!("expected Unbalanced, got {err:?}")
    };
    assert_eq!(
        motion,
        RigidMotion::Translation {
            direction: [0.0, 1.0]
        }
    );
}
