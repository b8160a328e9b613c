//! [`Algorithm::Auto`] on a small sparse symmetric `W` (issue 37, seventh part): the
//! classical solver first, within a budget of sweeps, then `Auto`'s own choice.
//!
//! Measured on Siconos' small problems stored sparse (`docs/benchmarks.md`, "Auto on small
//! problems"): the classical solver (contact, then friction at a fixed threshold) solves the
//! weakly coupled ones in 2 outer iterations (6 sweeps) and was the fastest of ours on 9 of 11
//! problems of 3–107 contacts, where `Auto`'s Newton took 1.6–4.4× as long (its warm-up
//! sweeps, then a Jacobian and a factorisation). Where the classical solver is slow (the
//! rovers, `OneObject`: non-symmetric, not tried here; `Confeti-ex03`: 1 549 sweeps) the first
//! run stops within its budget and costs a fraction of what follows:
//!
//! ```text
//! k = stored(W) / m (entries of an average row)
//! sweeps ≤ clamp(k² / AUTO_CLASSIC_ENTRIES_SQUARED_PER_SWEEP,
//!                AUTO_CLASSIC_MIN_SWEEPS, AUTO_CLASSIC_PROBE)
//!   (redundant contacts, `auto/redundant.rs`: the accelerated sweep first, until it
//!    converges or stalls; then sweeps ≤ max_iterations)
//!   (a dense W kept non-symmetric of m ≥ 24 rows: sweeps ≤ ⌈3m/4⌉, no going on)
//! converged (and checked)                          → its answer
//! its outer residuals promise tol within
//!   AUTO_CLASSIC_PREDICTED outer iterations       → it goes on from its iterate
//! otherwise                                        → Auto's choice from the start
//! ```

use super::super::problem::ReducedProblem;
use super::super::settings::{
    AUTO_CLASSIC_ENTRIES_SQUARED_PER_SWEEP, AUTO_CLASSIC_MAX_CONTACTS, AUTO_CLASSIC_MIN_SWEEPS,
    AUTO_CLASSIC_PREDICTED, AUTO_CLASSIC_PROBE, Algorithm, Solution, UzawaSettings,
};
use super::UzawaSolver;
use super::auto::{promises_within, redundant_contacts, sweep_before_classic};
use crate::error::SolverError;
use contact_laws::ContactLaw;

/// What [`Algorithm::Auto`] runs first on a small sparse symmetric `W` ([module docs](self)).
#[derive(Clone, Copy, Debug)]
pub(super) struct ClassicProbe {
    /// The classical solver's first run, with its budget of sweeps.
    pub(super) classic: UzawaSettings,
    /// The accelerated sweep run before it, on redundant contacts
    /// ([`sweep_before_classic`]).
    pub(super) sweep: Option<UzawaSettings>,
}

/// The settings of the classical solver's first run where [`Algorithm::Auto`] tries it first
/// (a sparse symmetric `W` of 2 to `AUTO_CLASSIC_MAX_CONTACTS` contacts, with its budget of
/// sweeps `AUTO_CLASSIC_PROBE`, and on redundant contacts the accelerated sweep before it; a
/// dense `W` kept non-symmetric of as many contacts, with [`dense_sweeps`]); `None` elsewhere
/// (a symmetric dense `W` keeps the measured rule of `auto`: Newton, or the sweep first).
pub(super) fn classic_probe(st: UzawaSettings, problem: &ReducedProblem) -> Option<ClassicProbe> {
    let nc = problem.contact_count();
    if !(2..=AUTO_CLASSIC_MAX_CONTACTS).contains(&nc) {
        return None;
    }
    // issue 37, ninth part: a small dense W kept non-symmetric (`dense_sweeps`)
    let Some(a) = problem.w_sparse() else {
        let sweeps = dense_sweeps(problem)?;
        return Some(ClassicProbe {
            classic: UzawaSettings {
                algorithm: Algorithm::ClassicRccm,
                max_iterations: st.max_iterations.min(sweeps),
                ..st
            },
            sweep: None,
        });
    };
    if !problem.is_symmetric() {
        return None;
    }
    let per_row = a.stored() as f64 / problem.size() as f64;
    let sweeps = ((per_row * per_row / AUTO_CLASSIC_ENTRIES_SQUARED_PER_SWEEP) as usize)
        .clamp(AUTO_CLASSIC_MIN_SWEEPS, AUTO_CLASSIC_PROBE);
    // redundant contacts (`auto/redundant.rs`): the accelerated sweep first, then the
    // classical solver with its whole budget
    let redundant = redundant_contacts(problem);
    let sweeps = if redundant { st.max_iterations } else { sweeps };
    Some(ClassicProbe {
        classic: UzawaSettings {
            algorithm: Algorithm::ClassicRccm,
            max_iterations: st.max_iterations.min(sweeps),
            ..st
        },
        sweep: redundant.then(|| sweep_before_classic(st)),
    })
}

/// Sweeps of the classical first run on a dense `W` kept non-symmetric: `⌈m · 3/4⌉` for `m`
/// rows (`None` on a symmetric dense `W`, which keeps the sweep first). A sweep of a dense
/// `W` costs `m²`, Newton's dense LU `m³/3` a step, so the sweeps a Newton run buys grow with
/// `m`. Measured (issue 37, ninth part, `docs/benchmarks.md` "Tiny dense problems"): FCLIB's
/// `LMGC_GlobalFrictionContactProblem00046` (9 contacts, 27 rows: 21 sweeps allowed) converges
/// in 17 sweeps, 7.5 µs against Newton's 14.4; where the classical solver is slow (the rovers,
/// 107–3 069 sweeps; the slider cranks, 626–700; `OneObject`, over 5 000) the 3–57 sweeps
/// allowed cost a small fraction of the Newton that follows on `OneObject` but 20–30 % on the
/// rovers and slider cranks, hence `AUTO_CLASSIC_DENSE_MIN_ROWS`. Such a run never goes on past its
/// budget ([`UzawaSolver::solve_classic_first`]).
fn dense_sweeps(problem: &ReducedProblem) -> Option<usize> {
    (problem.w_dense().is_some()
        && !problem.is_symmetric()
        && problem.size() >= AUTO_CLASSIC_DENSE_MIN_ROWS)
        .then(|| (3 * problem.size()).div_ceil(4))
}

/// Rows below which a dense `W` kept non-symmetric runs Newton at once ([`dense_sweeps`]):
/// there Newton's whole solve takes 2–20 µs and a classical run that does not converge costs
/// 20–30 % of it in its set-up and check alone (measured on Siconos' slider cranks, 4 rows,
/// and rovers, 6–15 rows: 0.7–3.4 µs added with a budget of 3–12 sweeps).
const AUTO_CLASSIC_DENSE_MIN_ROWS: usize = 24;

/// What the classical solver's first run left when it did not solve the problem: its sweeps,
/// outer iterations and residual history, added to the report of the run that follows.
#[derive(Clone, Debug, Default)]
pub(super) struct Spent {
    iterations: usize,
    outer_iterations: usize,
    history: Vec<f64>,
}

impl Spent {
    /// Adds the spent work in front of `sol`'s report.
    pub(super) fn add_to(self, sol: &mut Solution) {
        let report = &mut sol.report;
        report.iterations += self.iterations;
        report.outer_iterations += self.outer_iterations;
        let mut history = self.history;
        history.append(&mut report.history);
        report.history = history;
    }

    fn add(&mut self, sol: &mut Solution) {
        self.iterations += sol.report.iterations;
        self.outer_iterations += sol.report.outer_iterations;
        self.history.append(&mut sol.report.history);
    }
}

impl UzawaSolver {
    /// The classical solver first ([module docs](self)): `Ok(Ok(answer))` when it solved the
    /// problem (its answer checked like every other), `Ok(Err(spent))` when `Auto`'s own
    /// choice must run from `r` (the work spent, for its report), `Ok(Err(Spent::default()))`
    /// where the rule does not try it.
    ///
    /// # Errors
    /// Those of the classical solver's run ([`SolverError::NoFrictionCoefficient`],
    /// [`SolverError::InvalidLaw`]).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn solve_classic_first<L: ContactLaw, const DT: usize>(
        &mut self,
        st: UzawaSettings,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        r: &[f64],
        mu: &[f64],
    ) -> Result<Result<Solution, Spent>, SolverError> {
        let mut spent = Spent::default();
        let Some(first) = classic_probe(st, problem) else {
            return Ok(Err(spent));
        };
        if let Some(sweep) = first.sweep {
            let mut sol = self.attempt::<L, DT>(sweep, problem, laws, states, r.to_vec())?;
            let mut best = None;
            self.accept_on_residual::<L, DT>(problem, laws, states, &mut sol, &mut best);
            self.check::<L, DT>(problem, laws, states, &mut sol, Some(mu));
            if sol.report.converged {
                sol.report.asymmetry = problem.asymmetry();
                return Ok(Ok(sol));
            }
            spent.add(&mut sol);
        }
        let probe = first.classic;
        let mut sol = self.attempt::<L, DT>(probe, problem, laws, states, r.to_vec())?;
        // a run that promises the tolerance goes on from its iterate, once
        let mut left = st.max_iterations.saturating_sub(sol.report.iterations);
        for round in 0..2 {
            let mut best = None;
            self.accept_on_residual::<L, DT>(problem, laws, states, &mut sol, &mut best);
            self.check::<L, DT>(problem, laws, states, &mut sol, Some(mu));
            if sol.report.converged {
                spent.add_to(&mut sol);
                sol.report.asymmetry = problem.asymmetry();
                return Ok(Ok(sol));
            }
            let promising = !sol.report.stalled
                && promises_within(&sol.report.history, st.tol, AUTO_CLASSIC_PREDICTED);
            let start = std::mem::take(&mut sol.r);
            spent.add(&mut sol);
            if round == 1 || !promising || left == 0 || dense_sweeps(problem).is_some() {
                break;
            }
            let rest = UzawaSettings {
                max_iterations: left,
                ..probe
            };
            sol = self.attempt::<L, DT>(rest, problem, laws, states, start)?;
            left = left.saturating_sub(sol.report.iterations);
        }
        Ok(Err(spent))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::Asymmetry;

    /// The rule's reach: a sparse symmetric `W` of 2 contacts is tried,
    /// one of 1 contact (the direct solve's) and a dense or non-symmetric one are not.
    #[test]
    fn classic_probe_works() {
        let (rows, cols) = (&[0, 1, 2, 3][..], &[0, 1, 2, 3][..]);
        let vals = [2.0, 2.0, 2.0, 2.0];
        let (q, mu) = (vec![-1.0, 0.5, -1.0, 0.5], vec![0.3; 2]);
        let sparse =
            ReducedProblem::from_triplets(2, rows, cols, &vals, q.clone(), mu.clone()).unwrap();
        let st = UzawaSettings::default();
        let probe = classic_probe(st, &sparse).unwrap();
        assert_eq!(probe.classic.algorithm, Algorithm::ClassicRccm);
        // one stored entry a row: the least budget; no redundant contacts, no sweep first
        assert_eq!(probe.classic.max_iterations, AUTO_CLASSIC_MIN_SWEEPS);
        assert!(probe.sweep.is_none());
        let one = ReducedProblem::from_triplets(
            2,
            &[0, 1],
            &[0, 1],
            &[2.0, 2.0],
            vec![-1.0, 0.0],
            vec![0.3],
        );
        assert!(classic_probe(st, &one.unwrap()).is_none());
        let mut w = vec![0.0; 16];
        (0..4).for_each(|k| w[5 * k] = 2.0);
        let dense = ReducedProblem::with_dimension(2, w, q.clone(), mu.clone()).unwrap();
        assert!(classic_probe(st, &dense).is_none());
        let kept = ReducedProblem::from_triplets_with_asymmetry(
            2,
            &[0, 0, 1, 2, 3],
            &[0, 1, 1, 2, 3],
            &[2.0, 0.5, 2.0, 2.0, 2.0],
            q,
            mu,
            Asymmetry::Keep,
        )
        .unwrap();
        assert!(classic_probe(st, &kept).is_none());
    }

    /// Issue 37, ninth part: on a small dense `W` kept non-symmetric whose contacts are weakly
    /// coupled (9 contacts, 27 rows, as FCLIB's `LMGC…00046`), `Auto` returns the classical solver's answer within
    /// `⌈3m/4⌉` = 21 sweeps, where main's rule ran Newton; the answer is the same as Newton's
    /// (to 1e-8 relative: both stop on a residual of at most 1e-8). A symmetric dense `W` is
    /// not tried, nor a 2D one of 4 rows.
    #[test]
    fn issue_37_auto_runs_the_classical_solver_first_on_a_tiny_dense_non_symmetric_w() {
        use crate::local::solver::UzawaSolver;
        use contact_laws::Coulomb;
        let (nc, m) = (9, 27);
        let mut w = vec![0.0; m * m];
        for i in 0..nc {
            for a in 0..3 {
                w[(3 * i + a) * m + 3 * i + a] = 2.0;
            }
            w[(3 * i) * m + 3 * i + 1] = 0.01; // a non-symmetric diagonal block
            w[(3 * i + 1) * m + 3 * i] = 0.005;
            if i + 1 < nc {
                // weak normal coupling to the next contact, off its mirror
                w[(3 * i) * m + 3 * (i + 1)] = 0.004;
                w[(3 * (i + 1)) * m + 3 * i] = 0.002;
            }
        }
        let q: Vec<f64> = (0..m)
            .map(|k| [-1.0, 0.1, -0.05][k % 3] * (1.0 + 0.1 * (k / 3) as f64))
            .collect();
        let mu = vec![0.3; nc];
        let kept =
            ReducedProblem::with_asymmetry(3, w.clone(), q.clone(), mu.clone(), Asymmetry::Keep)
                .unwrap();
        assert!(!kept.is_symmetric());
        let st = UzawaSettings::default();
        assert_eq!(classic_probe(st, &kept).unwrap().classic.max_iterations, 21);
        let laws = [Coulomb::new(0.3).unwrap()];
        let auto = UzawaSolver::new(st.with_algorithm(Algorithm::Auto))
            .solve(&kept, &laws)
            .unwrap();
        assert_eq!(auto.report.algorithm, Algorithm::ClassicRccm);
        assert!(auto.report.converged && auto.report.iterations <= 21);
        let newton = UzawaSolver::new(st.with_algorithm(Algorithm::Newton))
            .solve(&kept, &laws)
            .unwrap();
        let scale = newton.r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        for (a, b) in auto.r.iter().zip(&newton.r) {
            // both answers meet the natural-map residual 1e-8 (relative) of a W with
            // condition about 1.2: they agree to a few times that
            assert!((a - b).abs() <= 1e-7 * scale, "{a} against {b}");
        }
        // the same W symmetric: not tried; a 2D dense W kept non-symmetric of 4 rows: neither
        let sym =
            ReducedProblem::with_asymmetry(3, w, q, mu, Asymmetry::Symmetrise { tolerance: 1.0 })
                .unwrap();
        assert!(sym.is_symmetric() && classic_probe(st, &sym).is_none());
        let w2 = vec![
            2.0, 0.5, 0.1, 0.0, //
            0.3, 2.0, 0.0, 0.0, //
            0.1, 0.0, 2.0, 0.0, //
            0.0, 0.0, 0.0, 2.0,
        ];
        let two = ReducedProblem::with_asymmetry(
            2,
            w2,
            vec![-1.0, 0.2, -1.0, 0.1],
            vec![0.3; 2],
            Asymmetry::Keep,
        )
        .unwrap();
        assert!(classic_probe(st, &two).is_none());
    }
}
