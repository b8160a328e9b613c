//! Issue 38, the follow-up "let the default be whatever wins the measurement"
//! (`docs/benchmarks.md`, "Matrix-free preconditioned (issue 38)"):
//! - the default Anderson window of matrix-free steps is 20 in 2D and 3D (measured against
//!   the momentum iteration, window 0, and a window of 10);
//! - `Auto` in 3D, within the dense limit but above `max(500, 0.5 DOF^(2/3))`, goes
//!   matrix-free where the active set does not apply (it stayed dense before), and says why.
//!
//! The pad of `issue_38_pad.rs` at 24 × 24 × 5 cells of six P1 tetrahedra (the member of
//! `examples/solid_contact_scaling.rs --slab 5` measured in `docs/benchmarks.md`: 625
//! contacts, 10 325 free DOF), its top lowered by 1 % of its thickness onto the rigid plane
//! z = 0, Coulomb μ = 0.3 through a wrapper that hides its cone from the active set.

#![cfg(feature = "fe")]

use crate::issue_38_pad::{pad_simulation_with, supports_xz};
use contact_laws::{ContactLaw, Coulomb, LocalVec};
use contact_solver::local::matrix_free_anderson::DEFAULT_MATRIX_FREE_WINDOW;
use contact_solver::{PathReason, SimulationSettings, SimulationTuning, SolvePath, StepReport};

/// Coulomb's law without its friction coefficient: the same answers, but the primal active set
/// (which needs a Coulomb cone) does not apply to it.
#[derive(Clone, Copy, Debug)]
struct HiddenCone(Coulomb);

impl ContactLaw for HiddenCone {
    type State = ();

    fn has_friction(&self) -> bool {
        true
    }

    fn project<const DT: usize>(&self, tau: &LocalVec<DT>, s: &()) -> LocalVec<DT> {
        self.0.project(tau, s)
    }

    fn modified_velocity<const DT: usize>(&self, du: &LocalVec<DT>, s: &()) -> LocalVec<DT> {
        self.0.modified_velocity(du, s)
    }

    fn bipotential<const DT: usize>(&self, du: &LocalVec<DT>, r: &LocalVec<DT>, s: &()) -> f64 {
        self.0.bipotential(du, r, s)
    }
}

/// One step of the `cells × cells × layers` pad with `law` under the default 3D `Auto`: the
/// report, the total contact force (x, z) and the supports' (x, z).
fn pad<L: ContactLaw + Clone>(
    cells: usize,
    layers: usize,
    law: L,
) -> (StepReport, [f64; 2], [f64; 2]) {
    let settings = SimulationSettings::for_dimension::<3>();
    let mut sim = pad_simulation_with(cells, layers, law, settings);
    let res = sim.step(1.0, 1.0).unwrap();
    let force = |a: usize| -> f64 { res.contacts.iter().map(|c| c.force()[a]).sum() };
    (res.report, [force(0), force(2)], supports_xz(&sim))
}

#[test]
fn issue_38_default_matrix_free_window_per_dimension() {
    // 20 measured best in both dimensions (0 is the momentum iteration of earlier versions)
    assert_eq!(DEFAULT_MATRIX_FREE_WINDOW, 20);
    let two = SimulationSettings::for_dimension::<2>()
        .tuning
        .matrix_free_window;
    let three = SimulationSettings::for_dimension::<3>()
        .tuning
        .matrix_free_window;
    assert_eq!((two, three), (20, 20));
    assert_eq!(SimulationSettings::default().tuning.matrix_free_window, 20);
    assert_eq!(SimulationTuning::default().matrix_free_window, 20);
    // the momentum iteration stays one setting away
    let momentum = SimulationSettings::for_dimension::<3>().with_matrix_free_window(0);
    assert_eq!(momentum.tuning.matrix_free_window, 0);
}

#[test]
fn issue_38_auto_goes_matrix_free_above_the_dof_rule_without_the_active_set() {
    let mu = Coulomb::new(0.3).unwrap();
    // 625 contacts > max(500, 0.5 · 10 325^(2/3) = 237), within the dense limit (3000): the
    // active set does not apply to the hidden cone, so matrix-free (dense before; measured
    // 3.2× slower than matrix-free on this pad)
    let (report, force, supports) = pad(24, 5, HiddenCone(mu));
    assert_eq!(report.active_contacts, 625);
    assert_eq!(report.path.path, SolvePath::MatrixFree, "{}", report.path);
    assert!(report.matrix_free && !report.active_set);
    assert_eq!(
        report.path.reason,
        PathReason::AboveDofRuleMatrixFree {
            active: 625,
            dofs: 10_325,
            limit: 500
        }
    );
    assert!(
        report
            .path
            .to_string()
            .starts_with("matrix-free (auto: 625 active contacts > 500 = max(500, 0.5 DOF^(2/3))"),
        "{}",
        report.path
    );
    // the answer: the supports balance the contact force (the exact product of the last
    // step, round-off), and it is the active set's on the plain Coulomb law to the solver's
    // tolerance (1e-8 relative on the residual; 1e-6 on the force leaves room for W's scale)
    for a in 0..2 {
        assert!(
            (force[a] + supports[a]).abs() < 1e-9 * force[1],
            "{force:?} {supports:?}"
        );
    }
    let (plain, plain_force, _) = pad(24, 5, mu);
    assert_eq!(plain.path.path, SolvePath::ActiveSet, "{}", plain.path);
    assert!(
        (force[1] - plain_force[1]).abs() < 1e-6 * plain_force[1],
        "{force:?} against {plain_force:?}"
    );
    // below the rule's floor the path stays dense, as before: the 8 × 8 × 2 pad, 81 contacts
    let (small, ..) = pad(8, 2, HiddenCone(mu));
    assert_eq!(small.path.path, SolvePath::Dense, "{}", small.path);
}
