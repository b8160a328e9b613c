//! Contacts that stay open leave the iteration ([`crate::UzawaTuning::skip_open`]).
//!
//! A sweep costs little for a contact that stays open (one projection), but every closed
//! contact's update moves `x` on all `m` rows of a dense `W`, and the accelerations and
//! products work on full vectors: a problem whose candidates are mostly open (a Hertz patch
//! among the nodes of a whole face, a granular problem inside the alert distance) pays for them
//! on every iteration. So the problem is solved on the contacts `A` that may close, then checked
//! on the others:
//!
//! ```text
//! A = { i : q_n,i < 0 or r_i ≠ 0 at the start }
//! repeat: solve x_A = W_AA r_A + q_A;  x = W [r_A, 0] + q   (one product)
//!         J = { i ∉ A : P_K(ρ⁰_i v_i(x_i)) ≠ 0 }   (r_i = 0 is not a solution at x_i)
//!         A = A ∪ J   until J is empty
//! ```
//! With `J` empty every contact left out has the exact residual 0 at `r_i = 0`, so the answer
//! is a solution of the whole problem to the same tolerance: no bound on the reactions is
//! needed. Each round costs one product with `W` (`O(m · m_A)` dense, `O(nnz)` sparse) and one
//! restriction of `W`; the rounds are few (a contact joins only if the answer presses it shut).
//! The sub-problem is solved as a Coulomb problem with the laws' own friction coefficients
//! (the laws are Coulomb-type: [`ContactLaw::friction_coefficient`]).

use super::super::problem::ReducedProblem;
use super::super::residual::{contact_statuses, local, pick};
use super::super::settings::{Solution, UzawaSettings};
use super::UzawaSolver;
use crate::error::SolverError;
use contact_laws::{ContactLaw, Coulomb};

/// The restriction is tried on a dense `W` only: on a sparse one an open contact already
/// costs next to nothing (its column is touched only when its reaction changes). The
/// algorithm is the one chosen for the whole problem (`Auto` choosing again for the smaller
/// one picked Newton on sphere piles, 10× slower there).
///
/// Below this many contacts the restriction is not tried (it costs a copy of `W_AA` and one
/// product per round, and the sweeps of a small problem are cheap).
pub(crate) const SKIP_OPEN_MIN_CONTACTS: usize = 64;

/// The restriction is tried when the contacts that may close are at most this fraction.
pub(crate) const SKIP_OPEN_MAX_FRACTION: f64 = 0.5;

/// Rounds of joining before the whole problem is solved instead.
const MAX_ROUNDS: usize = 8;

/// The contacts that may close: `q_n < 0` or a non-zero starting reaction.
fn may_close(problem: &ReducedProblem, r: &[f64]) -> Vec<bool> {
    let (d, q) = (problem.dimension(), problem.q());
    (0..problem.contact_count())
        .map(|i| q[d * i] < 0.0 || r[d * i..d * (i + 1)].iter().any(|&v| v != 0.0))
        .collect()
}

/// Whether the restriction is tried on `problem` from `r`: switched on, a dense `W` of at
/// least `SKIP_OPEN_MIN_CONTACTS` contacts, some but at most `SKIP_OPEN_MAX_FRACTION` of them
/// may close, and a cheap prediction says none of the others would join: each pressed contact
/// alone, `r_j ≈ −q_n,j / W_jj`, and only the couplings that close a gap (`W_ij < 0`: rigid
/// bodies pushed into others). Where some would, the rounds of joining cost more than the
/// smaller problem saves (measured on sphere piles: 0.56–0.70×): solve whole.
pub(super) fn restriction_pays(st: &UzawaSettings, problem: &ReducedProblem, r: &[f64]) -> bool {
    let nc = problem.contact_count();
    let Some(w) = problem.w_dense() else {
        return false;
    };
    if !st.tuning.skip_open || nc < SKIP_OPEN_MIN_CONTACTS {
        return false;
    }
    let keep = may_close(problem, r);
    let count = keep.iter().filter(|&&k| k).count();
    if count == 0 || count as f64 > SKIP_OPEN_MAX_FRACTION * nc as f64 {
        return false;
    }
    let (d, m, q) = (problem.dimension(), problem.size(), problem.q());
    let pressed: Vec<(usize, f64)> = (0..nc)
        .filter(|&j| keep[j] && q[d * j] < 0.0)
        .map(|j| (d * j, -q[d * j] / w[d * j * m + d * j]))
        .collect();
    !(0..nc).filter(|&i| !keep[i]).any(|i| {
        let row = &w[d * i * m..(d * i + 1) * m];
        let predicted: f64 = q[d * i]
            + pressed
                .iter()
                .map(|&(col, r)| row[col].min(0.0) * r)
                .sum::<f64>();
        predicted < 0.0
    })
}

impl UzawaSolver {
    /// The answer from the contacts that may close, or `None` when the restriction does not
    /// apply (too few contacts, too many may close, or the rounds ran out).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn solve_skipping_open<L: ContactLaw, const DT: usize>(
        &mut self,
        st: UzawaSettings,
        auto: bool,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        r: &[f64],
        mu: &[f64],
    ) -> Result<Option<Solution>, SolverError> {
        let d = DT + 1;
        let nc = problem.contact_count();
        if !restriction_pays(&st, problem, r) {
            return Ok(None);
        }
        let mut keep = may_close(problem, r);
        // ρ⁰ of the whole problem (`solve_checked` reset the sweeps for it; the check below
        // and the statuses use it)
        let rho0 = self.sweeps.rho0.clone();
        let sub_settings = st.with_skip_open(false);
        // the start, then each round's answer: a round starts where the last one ended
        let mut r_full = r.to_vec();
        let mut x_full = vec![0.0; problem.size()];
        let (mut iterations, mut outer, mut tangential) = (0, 0, 0);
        let mut history = Vec::new();
        for _ in 0..MAX_ROUNDS {
            let idx: Vec<usize> = (0..nc).filter(|&i| keep[i]).collect();
            let sub = problem.restricted(&idx);
            // the laws' coefficients (which the problem's agree with, friction.rs)
            let mu_sub: Vec<f64> = idx.iter().map(|&i| mu[i]).collect();
            let laws_sub: Vec<Coulomb> = idx
                .iter()
                .map(|&i| {
                    Coulomb::new(mu[i])
                        .map_err(|source| SolverError::InvalidLaw { contact: i, source })
                })
                .collect::<Result<_, _>>()?;
            let r_sub: Vec<f64> = idx
                .iter()
                .flat_map(|&i| r_full[d * i..d * (i + 1)].iter().copied())
                .collect();
            let sol = self
                .solve_checked::<Coulomb, DT>(
                    sub_settings,
                    auto,
                    &sub,
                    &laws_sub,
                    &[()],
                    r_sub,
                    Some(&mu_sub),
                )
                .map_err(drop_best)?;
            let report = &sol.report;
            iterations += report.iterations;
            outer += report.outer_iterations;
            tangential += report.tangential_sweeps;
            history.extend_from_slice(&report.history);
            r_full.fill(0.0);
            for (k, &i) in idx.iter().enumerate() {
                r_full[d * i..d * (i + 1)].copy_from_slice(&sol.r[d * k..d * (k + 1)]);
            }
            problem.displacement_into(&r_full, &mut x_full);
            let mut joined = false;
            for i in 0..nc {
                if keep[i] {
                    continue;
                }
                let (law, s) = (pick(laws, i), pick(states, i));
                let tau = law.modified_velocity(&local::<DT>(&x_full, i), s) * rho0[i];
                let p = law.project(&tau, s);
                if p.n != 0.0 || p.t.iter().any(|&t| t != 0.0) {
                    keep[i] = true;
                    joined = true;
                }
            }
            if !joined {
                let mut report = sol.report;
                report.iterations = iterations;
                report.outer_iterations = outer;
                report.tangential_sweeps = tangential;
                report.history = history;
                report.solved_contacts = idx.len();
                report.asymmetry = problem.asymmetry();
                report.statuses = contact_statuses::<L, DT>(laws, states, &rho0, &r_full, &x_full);
                self.sweeps.reset(problem, st.tuning.rho_scale);
                return Ok(Some(Solution {
                    r: r_full,
                    x: x_full,
                    report,
                }));
            }
        }
        Ok(None)
    }
}

/// The error of a solve on the contacts that may close, without its best iterate (which has
/// the sub-problem's size, not the problem's).
fn drop_best(mut e: SolverError) -> SolverError {
    if let SolverError::NotConverged { best, .. } | SolverError::Stalled { best, .. } = &mut e {
        *best = None;
    }
    e
}
