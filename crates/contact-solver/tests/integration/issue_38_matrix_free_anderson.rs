//! Issue 38: the matrix-free iteration accelerated by Anderson mixing
//! ([`SimulationTuning::matrix_free_window`](contact_solver::SimulationTuning)) gives the
//! dense path's answer with fewer products `F* r` (structure solves) than the momentum
//! iteration.
//!
//! The pad of `issue_38_pad.rs` (`examples/solid_contact_scaling.rs --slab m` at a size a
//! debug build steps in a second): the slab `[0, 1]² × [0, h]`, `8 × 8 × 2` cells of six P1
//! tetrahedra (`h = 0.25`), rollers on x = 0 and y = 0, its top lowered by `δ = h/100`, its
//! bottom on the rigid plane z = 0: 81 contacts, all closed. E = 1000, ν = 0.3.
//! - with Coulomb friction (μ = 0.3; the rim slips, the middle sticks): the reactions of both
//!   matrix-free variants are the dense path's to the solver's tolerance, and the accelerated
//!   one takes fewer products (a count, independent of the machine);
//! - without friction the force is the uniaxial closed form `E δ/h` (P1 holds it exactly);
//! - a window of 0 through the function itself is refused, naming the setting;
//! - on a problem with no solution (`stall.rs`'s opposed contacts) it stops with an error,
//!   never "converged".

#![cfg(feature = "fe")]

use crate::issue_38_pad::{pad_simulation_with, supports_xz};
use contact_laws::{ContactLaw, Coulomb, Signorini};
use contact_solver::local::matrix_free_anderson::{
    DEFAULT_MATRIX_FREE_WINDOW, solve_matrix_free_anderson_3d,
};
use contact_solver::{FlexibilityMode, SimulationSettings, SolverError, UzawaSettings};

/// Cells per side and layers of the small pad.
const CELLS: usize = 8;
const LAYERS: usize = 2;

/// What one step of the pad gives: each contact's reaction, the supports' total reaction in
/// (x, z), and the products `F* r` of the step.
struct Run {
    reactions: Vec<[f64; 3]>,
    supports: [f64; 2],
    products: usize,
    matrix_free: bool,
}

/// One step of the pad with `law` on `mode`, the matrix-free window `window`.
fn pad<L: ContactLaw + Clone>(law: L, mode: FlexibilityMode, window: usize) -> Run {
    let settings = SimulationSettings::for_dimension::<3>()
        .with_flexibility(mode)
        .with_matrix_free_window(window);
    let mut sim = pad_simulation_with(CELLS, LAYERS, law, settings);
    let res = sim.step(1.0, 1.0).unwrap();
    Run {
        reactions: res.contacts.iter().map(|c| c.force()).collect(),
        supports: supports_xz(&sim),
        products: sim.counters().operator_applications,
        matrix_free: res.report.matrix_free,
    }
}

/// The largest relative imbalance of the contact reactions against the supports' (x, z).
fn imbalance(run: &Run) -> f64 {
    let sum = |a: usize| -> f64 { run.reactions.iter().map(|r| r[a]).sum() };
    let force = sum(2);
    f64::max(
        (sum(0) + run.supports[0]).abs() / force,
        (sum(2) + run.supports[1]).abs() / force,
    )
}

#[test]
fn issue_38_anderson_matrix_free_gives_the_dense_answer_with_fewer_products() {
    let mu = Coulomb::new(0.3).unwrap();
    let dense = pad(mu, FlexibilityMode::Dense, 0);
    let momentum = pad(mu, FlexibilityMode::MatrixFree, 0);
    let anderson = pad(mu, FlexibilityMode::MatrixFree, DEFAULT_MATRIX_FREE_WINDOW);
    assert!(!dense.matrix_free && momentum.matrix_free && anderson.matrix_free);
    let scale = dense
        .reactions
        .iter()
        .fold(0.0_f64, |m, r| m.max(r[2].abs()));
    let t_max = dense
        .reactions
        .iter()
        .fold(0.0_f64, |m, r| m.max(r[0].abs()));
    assert!(
        t_max > 1e-3 * scale,
        "no friction at work: {t_max} of {scale}"
    );
    // the dense path's reactions to the solver's tolerance (1e-10 relative on the residual,
    // amplified by the stick/slip split and the sampled ρ⁰: 1e-7, as issue_38_pad.rs)
    for run in [&momentum, &anderson] {
        for (a, d) in run.reactions.iter().zip(&dense.reactions) {
            for k in 0..3 {
                assert!((a[k] - d[k]).abs() < 1e-7 * scale, "{a:?} against {d:?}");
            }
        }
        // one exact solve per answer: the supports balance to the round-off and the tolerance
        assert!(imbalance(run) < 1e-6, "{}", imbalance(run));
    }
    // the count, not a time: measured 443 against 116 products (`solid_contact_scaling 8
    // --slab 2 --coulomb --matrix-free --mf-window 0` / `20`, the same pad); the assertion
    // leaves room for rounding to shift a restart
    assert!(
        2 * anderson.products <= momentum.products,
        "Anderson {} products against the momentum's {}",
        anderson.products,
        momentum.products
    );
}

#[test]
fn issue_38_anderson_matrix_free_frictionless_pad_carries_the_uniaxial_force() {
    // E δ/h on the unit quarter: 1000 × 1/100
    let exact = 10.0;
    let run = pad(
        Signorini,
        FlexibilityMode::MatrixFree,
        DEFAULT_MATRIX_FREE_WINDOW,
    );
    let force: f64 = run.reactions.iter().map(|r| r[2]).sum();
    // P1 holds the uniform uniaxial stress exactly; the rest is the solver's tolerance
    assert!((force - exact).abs() < 1e-6 * exact, "{force}");
    assert!(imbalance(&run) < 1e-6, "{}", imbalance(&run));
}

#[test]
fn issue_38_anderson_matrix_free_rejects_a_zero_window() {
    let apply = |r: &[f64], x: &mut [f64]| {
        for (x, r) in x.iter_mut().zip(r) {
            *x = 2.0 * r - 1.0;
        }
        Ok(())
    };
    let (mut r, mut x) = (vec![0.0; 3], vec![0.0; 3]);
    let law = [Coulomb::new(0.2).unwrap()];
    let s = UzawaSettings::default();
    let e = solve_matrix_free_anderson_3d(apply, &law, &[()], &[0.5], 0, &s, &mut r, &mut x);
    assert!(
        matches!(
            e,
            Err(SolverError::InvalidSetting {
                what: "matrix_free_window",
                ..
            })
        ),
        "{e:?}"
    );
}

#[test]
fn issue_38_anderson_matrix_free_never_converges_on_the_unsolvable_problem() {
    let p = crate::stall::opposed_contacts();
    let apply = |r: &[f64], x: &mut [f64]| {
        p.displacement_into(r, x);
        Ok(())
    };
    let laws = [Coulomb::new(0.3).unwrap(), Coulomb::new(0.3).unwrap()];
    let st = UzawaSettings::default().with_max_iterations(100_000);
    let (mut r, mut x) = (vec![0.0; 4], vec![0.0; 4]);
    let e = contact_solver::local::matrix_free_anderson::solve_matrix_free_anderson(
        apply,
        &laws,
        &[(), ()],
        &[1.0, 1.0],
        DEFAULT_MATRIX_FREE_WINDOW,
        &st,
        &mut r,
        &mut x,
    );
    assert!(
        matches!(
            e,
            Err(SolverError::Stalled {
                algorithm: "MatrixFreeAnderson",
                ..
            } | SolverError::NotConverged { .. })
        ),
        "{e:?}"
    );
}
