//! The state the bipotential sweeps share: the base penalties `ρ⁰_i = 1/λ_max(W_ii)`, the
//! adapted `ρ_i`, and the trial buffers of the Uzawa step. The sweeps themselves live one per
//! file ([`uzawa`](super::uzawa), [`gauss_seidel`](super::gauss_seidel)); the accelerated and
//! Newton solvers drive them through this type.

use super::exact_2d::ExactBlocks;
use super::problem::ReducedProblem;
use super::residual::{local, pick, rho_of_block, set_local};
use contact_laws::ContactLaw;

/// Maximum number of halvings of ρ within one step (`2⁻⁶⁰ ≈ 10⁻¹⁸`).
pub(crate) const MAX_SHRINKS: usize = 60;

/// Buffers and penalties of the bipotential sweeps, reused across solves.
#[derive(Clone, Debug, Default)]
pub(crate) struct Sweeps {
    pub(crate) r_trial: Vec<f64>,
    pub(crate) x_trial: Vec<f64>,
    pub(crate) v: Vec<f64>,
    pub(crate) v_trial: Vec<f64>,
    pub(crate) rho0: Vec<f64>,
    pub(crate) rho: Vec<f64>,
    /// The diagonal blocks `W_ii` of the problem of the last [`reset`](Self::reset), read
    /// once: on a sparse `W` each read is a search of the row (issue 37, ninth part: 22 % of
    /// the accelerated sweep's time on Siconos' 2D granular problems).
    pub(crate) blocks: Vec<[[f64; 3]; 3]>,
    /// The contacts' blocks when the Gauss–Seidel sweep solves each 2D contact exactly
    /// ([`ContactSolve::Exact`](super::ContactSolve::Exact), `exact_2d`).
    pub(crate) exact: Option<ExactBlocks>,
    /// How many times [`reset`](Self::reset) computed `ρ⁰` (one eigenvalue problem a
    /// contact), a work count for the tests (issue 37: `Auto` computed it once per run).
    pub(crate) rho0_computed: usize,
}

impl Sweeps {
    /// Sizes the buffers for `problem` and sets `ρ⁰_i = 1/λ_max(W_ii)`, `ρ_i = rho_scale·ρ⁰_i`.
    pub(crate) fn reset(&mut self, problem: &ReducedProblem, rho_scale: f64) {
        let m = problem.size();
        for buf in [
            &mut self.r_trial,
            &mut self.x_trial,
            &mut self.v,
            &mut self.v_trial,
        ] {
            buf.clear();
            buf.resize(m, 0.0);
        }
        self.rho0_computed += 1;
        self.rho0.clear();
        let d = problem.dimension();
        self.blocks.clear();
        self.blocks
            .extend((0..problem.contact_count()).map(|i| problem.diagonal_block(i)));
        self.rho0
            .extend(self.blocks.iter().map(|block| rho_of_block(block, d)));
        self.rho.clear();
        self.rho.extend(self.rho0.iter().map(|a| a * rho_scale));
        // the exact solve is set per run, after the reset (`exact_contacts`)
        self.exact = None;
    }

    /// [`reset`](Self::reset) for a run on the problem the sweeps were last reset for: the
    /// buffers zeroed and `ρ_i = rho_scale·ρ⁰_i`, the `ρ⁰` kept (it depends on `W`'s diagonal
    /// blocks only). Issue 37, ninth part: each run of a solve computed `ρ⁰` again (`Auto`'s
    /// classical first run, then Newton: three times), 5–10 % of `Auto`'s time on Siconos'
    /// `NESpheres_10_1`. A problem of another size is reset in full.
    pub(crate) fn restart(&mut self, problem: &ReducedProblem, rho_scale: f64) {
        let m = problem.size();
        if self.rho0.len() != problem.contact_count() || self.r_trial.len() != m {
            self.reset(problem, rho_scale);
            return;
        }
        for buf in [
            &mut self.r_trial,
            &mut self.x_trial,
            &mut self.v,
            &mut self.v_trial,
        ] {
            buf.fill(0.0);
        }
        self.rho.clear();
        self.rho.extend(self.rho0.iter().map(|a| a * rho_scale));
    }

    /// The base penalties `ρ⁰_i = 1/λ_max(W_ii)` of the current solve.
    pub(crate) fn rho0(&self) -> &[f64] {
        &self.rho0
    }

    /// `self.v = v(x)`, the precondition of [`uzawa_step`](super::uzawa).
    pub(crate) fn set_velocity<L: ContactLaw, const DT: usize>(
        &mut self,
        laws: &[L],
        states: &[L::State],
        x: &[f64],
    ) {
        for i in 0..self.rho0.len() {
            let v = pick(laws, i).modified_velocity(&local::<DT>(x, i), pick(states, i));
            set_local(&mut self.v, i, &v);
        }
    }
}
