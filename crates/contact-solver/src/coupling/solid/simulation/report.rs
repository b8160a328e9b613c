//! The public data of a 3D simulation: its settings and what a step returns.

use super::super::zone::Candidate3;
use crate::coupling::simulation::FlexibilityMode;
use crate::local::UzawaSettings;
use crate::local::adhesion::AdhesionOptions;

/// Settings of a [`SolidContactSimulation`](super::SolidContactSimulation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidSettings {
    /// The local solver's settings.
    pub solver: UzawaSettings,
    /// Right-hand sides per solve when building `F*`.
    pub columns_per_solve: usize,
    /// Largest number of active-set passes in a step (each adds the candidates that
    /// penetrated).
    pub max_passes: usize,
    /// A penetration below this fraction of the contact nodes' extent is not one.
    pub penetration_tol: f64,
    /// The adhesion fixed point (tolerance on β, cap, Anderson window), for adhesive laws.
    pub adhesion: AdhesionOptions,
    /// How the reduced problem is held: `Dense` (`F*` built with `3 n_c` solves), `MatrixFree`
    /// (one solve per iteration, no `F*`; adhesive steps still build `F*`, whose exact
    /// condensation of the springs needs it), `ActiveSet` (the primal active set: rigid
    /// obstacles, node pairs and node-to-face, adhesive laws by the fixed point on the states;
    /// a step out of its scope is refused with the reason), or
    /// `Auto { dense_limit }` (the default, [`DEFAULT_DENSE_LIMIT_3D`]): dense up to that many
    /// active contacts; beyond, the active set when the step is in its scope, else
    /// matrix-free, and a step whose active-set iteration fails is solved again dense (up to
    /// the limit's default) or matrix-free.
    pub flexibility: FlexibilityMode,
}

/// Default `Auto` limit of 3D steps: a dense `F*` of 3000 contacts holds 81e6 values (648 MB)
/// and is faster to build than the matrix-free iterations are to converge
/// (`docs/benchmarks.md`, "3D: dense against matrix-free").
pub const DEFAULT_DENSE_LIMIT_3D: usize = 3000;

impl Default for SolidSettings {
    fn default() -> Self {
        Self {
            solver: UzawaSettings::default(),
            columns_per_solve: 96,
            max_passes: 20,
            penetration_tol: 1e-9,
            adhesion: AdhesionOptions::default(),
            flexibility: FlexibilityMode::Auto {
                dense_limit: DEFAULT_DENSE_LIMIT_3D,
            },
        }
    }
}

/// One contact at the end of a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidContactRecord {
    /// The candidate (zone, node, frame, area).
    pub candidate: Candidate3,
    /// Reaction `(r_n, r_t1, r_t2)` on the contactor node, in the frame: `r_n ≥ 0` is
    /// compression. The force on the node is `r_n n + r_t1 t₁ + r_t2 t₂` (its target nodes
    /// carry the opposite, split by their weights). With adhesion this is the total reaction,
    /// the law's `r̄` plus the springs' `−β² C (u_n, u_t)` times the area.
    pub r: [f64; 3],
    /// The adhesion intensity `β` at the end of the step (0 for laws without adhesion).
    pub beta: f64,
    /// Gap at the end of the step.
    pub gap: f64,
    /// Tangential displacement increment of the step `(Δu_t1, Δu_t2)` (the slip of a sliding
    /// contact).
    pub slip: [f64; 2],
    /// Whether the contact was in the step's reduced problem (a candidate, maybe open).
    pub active: bool,
    /// Whether it is closed (`r̄_n > 0`, 2D's [`crate::InterfaceStatus::is_closed`]).
    pub closed: bool,
}

impl SolidContactRecord {
    /// The reaction as a global force vector.
    pub fn force(&self) -> [f64; 3] {
        let [n, t1, t2] = self.candidate.frame();
        core::array::from_fn(|a| self.r[0] * n[a] + self.r[1] * t1[a] + self.r[2] * t2[a])
    }

    /// Contact pressure `r_n / area`.
    pub fn pressure(&self) -> f64 {
        if self.candidate.area > 0.0 {
            self.r[0] / self.candidate.area
        } else {
            0.0
        }
    }
}

/// The result of a step.
#[derive(Clone, Debug)]
pub struct SolidStepResult {
    /// Every candidate, in recognition order.
    pub contacts: Vec<SolidContactRecord>,
    /// Local-solver iterations summed over the passes (and the adhesion iterations).
    pub contact_iterations: usize,
    /// Adhesion fixed-point iterations summed over the passes (0 without adhesion).
    pub adhesion_iterations: usize,
    /// Active-set passes.
    pub passes: usize,
    /// The local solver's last residual.
    pub residual: f64,
    /// Contacts in the reduced problem (candidates within the alert distance).
    pub active: usize,
    /// Contacts closed at the end of the step ([`SolidContactRecord::closed`]).
    pub closed: usize,
    /// Whether the last pass was solved matrix-free (no `F*`).
    pub matrix_free: bool,
    /// Whether the last pass was solved by the primal active set (no `F*`).
    pub active_set: bool,
    /// Numeric factorisations of the active set's constrained stiffness in this step.
    pub factorizations: usize,
}
