//! [`Algorithm::Auto`]'s choice for a Coulomb-type problem (issues 14 and 37): which
//! algorithm runs first, on which storage of `W`, and how long a Newton it chose may run.
//! The measurements behind each constant are in `docs/benchmarks.md` ("Which algorithm,
//! measured" and "Auto on multibody problems").

use super::super::newton::{NewtonProbe, factor_fill};
use super::super::problem::ReducedProblem;
use super::super::settings::Algorithm;
use super::super::settings::{
    AUTO_CLASSIC_MAX_CONTACTS, AUTO_MULTIBODY_ZERO_BLOCKS, AUTO_NEWTON_BUDGET,
    AUTO_NEWTON_MAX_CONTACTS, AUTO_NEWTON_MAX_FILL, AUTO_NEWTON_UNPROBED_BUDGET,
    AUTO_SPARSE_NEWTON_MAX_CONTACTS, AUTO_SWEEP_MIN_PRESSED, AUTO_SWEEP_PREDICTED,
    AUTO_SWEEP_PROBE, UzawaSettings,
};

mod after_probe;
mod redundant;
mod sweep_2d;
pub(super) use redundant::{redundant_contacts, sweep_before_classic};
pub(super) use sweep_2d::{auto_contact_solve, exact_sweep_beats_newton};

/// [`Algorithm::Auto`]'s rule for a Coulomb-type problem (measured, see
/// `AUTO_NEWTON_MAX_FILL` and `AUTO_MULTIBODY_ZERO_BLOCKS`): Newton on a dense `W` up to
/// `AUTO_NEWTON_MAX_CONTACTS` contacts unless its blocks are mostly zero (a multibody
/// Delassus operator, [`mostly_zero_blocks`]: `Auto` solves it stored sparse,
/// [`sparse_twin_for_auto`]), on a sparse `W` up to
/// `AUTO_SPARSE_NEWTON_MAX_CONTACTS` contacts whose graph fills a factorisation by at most
/// `AUTO_NEWTON_MAX_FILL`. A dense `W` kept non-symmetric takes Newton whatever its blocks
/// (issue 37: Siconos' `OneObject` problems, a body with joints, 23–25 contacts and 70 % zero
/// blocks, were left to the sweep, 4 023 sweeps where Newton takes 13 iterations). Newton
/// chosen here runs within a budget ([`auto_newton_budget`]) and, on a symmetric or sparse
/// `W`, as a probe that gives up on its second short step ([`newton_probes`]). Above
/// `AUTO_CLASSIC_MAX_CONTACTS` contacts, a sparse `W` of redundant contacts
/// ([`redundant_contacts`]: Siconos' kapla tower, where one factorisation costs twice the whole
/// sweep) takes the sweep.
pub(super) fn newton_pays(problem: &ReducedProblem) -> bool {
    if exact_sweep_beats_newton(problem) {
        return false; // issue 37, ninth part: the exact 2D sweep (`sweep_2d`)
    }
    let nc = problem.contact_count();
    match problem.w_sparse() {
        None => {
            nc <= AUTO_NEWTON_MAX_CONTACTS
                && (!problem.is_symmetric() || !mostly_zero_blocks(problem))
        }
        // a small W (`AUTO_CLASSIC_MAX_CONTACTS`) is not measured: its fill costs little
        Some(a) => {
            nc <= AUTO_CLASSIC_MAX_CONTACTS
                || nc <= AUTO_SPARSE_NEWTON_MAX_CONTACTS
                    && !redundant_contacts(problem)
                    && factor_fill(a, problem.dimension())
                        .is_some_and(|f| f <= AUTO_NEWTON_MAX_FILL)
        }
    }
}

/// The probe of a Newton that [`Algorithm::Auto`] chose ([`NewtonProbe`]): on a symmetric
/// `W` the step probe (it gives up on its second short Armijo step,
/// `AUTO_NEWTON_SHORT_STEPS`); on a sparse one kept non-symmetric the progress probe (issue
/// 37, seventh part: Siconos' capsules, whose Newton takes short steps while its proximal `η`
/// rises and then converges in 29–40 iterations; `AUTO_NEWTON_PROGRESS_WINDOW`); on a dense
/// `W` kept non-symmetric none. Measured (issue 37, Siconos' rovers and `OneObject`
/// problems, dense, asymmetry 1e-5 to 1e-3 of the scale): Newton's Armijo steps shrink to
/// `t ≤ 2⁻⁵` early there and still converge within 7–18 iterations (95 on
/// `OneObject-i100000-499`), while the sweep that took over needed 4 023 sweeps (80× Newton's
/// time) on `OneObject-i1028-138`; the budget `AUTO_NEWTON_UNPROBED_BUDGET` bounds the run.
pub(super) fn newton_probe(problem: &ReducedProblem) -> NewtonProbe {
    match (problem.is_symmetric(), problem.w_dense().is_none()) {
        (true, _) => NewtonProbe::Steps,
        (false, true) => NewtonProbe::Progress,
        (false, false) => NewtonProbe::Off,
    }
}

/// Whether at least `AUTO_MULTIBODY_ZERO_BLOCKS` of the off-diagonal `d × d` blocks of a dense
/// `W` are exactly zero: the pattern of a multibody Delassus operator `H M⁻¹ Hᵀ` (two contacts
/// are coupled only through a body they share), never of a condensed finite-element
/// flexibility `F*` (every entry non-zero: an elastic body couples all its nodes). One pass
/// over `W` (the cost of one product `W r`), stopped as soon as the answer is known.
fn mostly_zero_blocks(problem: &ReducedProblem) -> bool {
    let Some(w) = problem.w_dense() else {
        return false;
    };
    let (nc, d, m) = (problem.contact_count(), problem.dimension(), problem.size());
    let pairs = nc * nc.saturating_sub(1);
    if pairs == 0 {
        return false;
    }
    let needed = (AUTO_MULTIBODY_ZERO_BLOCKS * pairs as f64).ceil() as usize;
    let (mut zero, mut seen) = (0usize, 0usize);
    for i in 0..nc {
        for j in (0..nc).filter(|&j| j != i) {
            seen += 1;
            let is_zero = (0..d).all(|a| {
                let row = &w[(d * i + a) * m + d * j..][..d];
                row.iter().all(|&v| v == 0.0)
            });
            zero += usize::from(is_zero);
            if zero >= needed {
                return true;
            }
            if zero + (pairs - seen) < needed {
                return false;
            }
        }
    }
    false
}

/// The same problem with `W` stored sparse, for [`Algorithm::Auto`] on a dense symmetric `W`
/// that is mostly zero blocks ([`mostly_zero_blocks`]): every algorithm is faster on the
/// sparse storage there (measured on sphere piles: the sweep 2–4×, Newton's sparse LU 4–20×
/// against the dense LU, `docs/benchmarks.md` "Auto on multibody problems"), and the sparse
/// rule of [`newton_pays`] applies. `None` when the problem is not such a one (or the copy
/// fails, which a valid problem does not).
pub(super) fn sparse_twin_for_auto(problem: &ReducedProblem) -> Option<ReducedProblem> {
    problem.w_dense()?;
    if !problem.is_symmetric() || !mostly_zero_blocks(problem) {
        return None;
    }
    problem.stored_sparse()?.ok()
}

/// The settings of the first run of a Newton that [`Algorithm::Auto`] chose: at most
/// `AUTO_NEWTON_BUDGET` iterations, after which the accelerated sweep takes over from the
/// start (whatever `fallback` says: the switch is part of `Auto`), so that a wrong first
/// choice costs a bounded fraction of the solve (issue 37: Newton ground for thousands of
/// iterations on multibody stacks that the sweep solves in hundreds). The run gives up
/// sooner as its probe says ([`newton_probe`]; the solver sets the Newton's `probe` for this
/// run): measured on symmetric `W`, the creeping runs give their second short step at
/// iteration 6–10, no converging run gives one, and a slow but converging Newton (a tower of
/// 50 spheres, 53 iterations, still 1.9× faster than the sweep) runs to the end.
///
/// A Newton that runs without the probe ([`NewtonProbe::Off`]: a dense `W` kept
/// non-symmetric) has the shorter budget `AUTO_NEWTON_UNPROBED_BUDGET`; it and the progress
/// probe's Newton hand their iterate to the sweep (the solver's hand-over).
pub(super) fn auto_newton_budget(st: UzawaSettings, problem: &ReducedProblem) -> UzawaSettings {
    let budget = if newton_probe(problem) != NewtonProbe::Off {
        AUTO_NEWTON_BUDGET
    } else {
        AUTO_NEWTON_UNPROBED_BUDGET
    };
    UzawaSettings {
        max_iterations: st.max_iterations.min(budget),
        ..st
    }
}

/// Iterations of the Newton that [`Algorithm::Auto`] runs again, unprobed, after its probe
/// switched to the accelerated sweep and the sweep did not converge either (issue 37:
/// FCLIB's `spheres-in-a-box-98`, where the sweep stalls at 1.5e-6 after 9 200 sweeps and
/// Newton with its raised `ρ` (`newton/rho_raise.rs`) converges in about 220 iterations;
/// the manufactured spheres in a box of the tests need up to 1 614). The budget bounds what a
/// problem with no solution costs on its way to the refusal.
const AUTO_LAST_NEWTON_BUDGET: usize = 2000;

/// The settings of that last Newton: `st`'s, Newton, at most `AUTO_LAST_NEWTON_BUDGET`
/// iterations, `ρ` raised when its steps creep (`newton/rho_raise.rs`). It starts from the
/// start of the solve (from the sweep's iterate it missed one of the manufactured spheres in
/// a box of `tests/integration/issue_37_spheres_box.rs` in 1 000 iterations, measured; from
/// the start every one, in at most 1 614).
pub(super) fn last_newton(st: UzawaSettings) -> UzawaSettings {
    UzawaSettings {
        algorithm: Algorithm::Newton,
        max_iterations: st.max_iterations.min(AUTO_LAST_NEWTON_BUDGET),
        ..st
    }
}

/// The sweep that goes on after a Newton run under `probe` ended without converging: the
/// accelerated sweep, except after the progress probe (a sparse `W` kept non-symmetric), where
/// the plain Gauss–Seidel sweep goes on from Newton's iterate. Measured (issue 37, seventh
/// part, `docs/benchmarks.md` "Auto on large multibody problems"): on Siconos'
/// `Capsules-i101-404`, after Newton's plateau at 5e-7, the plain sweep converges in 1 457
/// sweeps where the accelerated one takes 5 726; the plain sweep is our fastest algorithm on
/// both capsule files where Newton plateaus. After the progress probe it runs first as a
/// trial read by its rate (`auto/after_probe.rs`, issue 37, ninth part).
pub(super) fn sweep_after_newton(probe: NewtonProbe) -> Algorithm {
    match probe {
        NewtonProbe::Progress | NewtonProbe::Finish => Algorithm::GaussSeidel,
        NewtonProbe::Steps | NewtonProbe::Off => Algorithm::AndersonGaussSeidel,
    }
}

/// Whether `W` is dense and symmetric and at least `AUTO_SWEEP_MIN_PRESSED` of the contacts
/// are pressed (`q_n < 0`): there a Newton step factorises most of `W` (its closed set), and
/// `Auto` sweeps first ([`sweep_probe`]); where few are pressed (an indenter on a large FE
/// surface) Newton's steps are small beside a sweep over the whole `W`, and `Auto` keeps
/// Newton. A `W` kept non-symmetric runs Newton at once (issue 37, ninth part): its Newton is
/// unprobed, within `AUTO_NEWTON_UNPROBED_BUDGET`, and hands its iterate to the sweep, so the
/// sweep is what follows a wrong choice anyway; measured on Siconos' dense non-symmetric
/// problems (the rovers, 1–5 contacts; the slider crank, 2; `OneObject`, 23–25) the probe
/// never promised (the accelerated sweep needs 193–1 133 sweeps on `OneObject`, Newton
/// 11–14 iterations) and cost 25–40 % of `Auto`'s time on the rovers and 5–8 % on
/// `OneObject` (27–38 µs of 0.34–0.52 ms), where main kept it above 32 rows.
pub(super) fn pressed_most(problem: &ReducedProblem) -> bool {
    let (d, nc) = (problem.dimension(), problem.contact_count());
    let pressed = (0..nc).filter(|&i| problem.q()[d * i] < 0.0).count();
    problem.w_dense().is_some()
        && problem.is_symmetric()
        && nc > 0
        && pressed as f64 >= AUTO_SWEEP_MIN_PRESSED * nc as f64
}

/// The settings of the sweep [`Algorithm::Auto`] runs first on a dense `W` where it would
/// pick Newton: the accelerated sweep for at most `AUTO_SWEEP_PROBE` sweeps.
pub(super) fn sweep_probe(st: UzawaSettings) -> UzawaSettings {
    UzawaSettings {
        algorithm: Algorithm::AndersonGaussSeidel,
        max_iterations: st.max_iterations.min(AUTO_SWEEP_PROBE),
        ..st
    }
}

/// Whether the sweep whose relative residuals are `history` (one a sweep) promises `tol`
/// within `AUTO_SWEEP_PREDICTED` sweeps in all, at the rate of its last four sweeps:
///
/// ```text
/// ρ = (h_k / h_{k−4})^{1/4},   k + ln(tol / h_k) / ln ρ ≤ AUTO_SWEEP_PREDICTED
/// ```
/// A history already at `tol` promises it; one shorter than five sweeps, or not contracting
/// (`ρ ≥ 1`, a NaN), does not.
pub(super) fn sweep_promises(history: &[f64], tol: f64) -> bool {
    promises_within(history, tol, AUTO_SWEEP_PREDICTED)
}

/// [`sweep_promises`] with `within` iterations in all in place of `AUTO_SWEEP_PREDICTED`.
pub(super) fn promises_within(history: &[f64], tol: f64, within: f64) -> bool {
    let k = history.len();
    let Some(&last) = history.last() else {
        return false;
    };
    if last <= tol {
        return true;
    }
    if k < 5 {
        return false;
    }
    let rate = (last / history[k - 5]).powf(0.25);
    if rate.is_nan() || rate >= 1.0 || rate <= 0.0 {
        return false;
    }
    k as f64 + (tol / last).ln() / rate.ln() <= within
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::Asymmetry;

    /// A block-diagonal `W` (two bodies, no shared contact) is mostly zero blocks; a full one
    /// (every entry non-zero, like a condensed FE flexibility) is not; one contact has no
    /// off-diagonal block; a sparse `W` is left to the fill rule.
    #[test]
    fn mostly_zero_blocks_works() {
        let diag = ReducedProblem::new(
            vec![
                2.0, 0.5, 0.0, 0.0, //
                0.5, 2.0, 0.0, 0.0, //
                0.0, 0.0, 2.0, 0.0, //
                0.0, 0.0, 0.0, 2.0,
            ],
            vec![-1.0; 4],
            vec![0.3; 2],
        )
        .unwrap();
        assert!(mostly_zero_blocks(&diag));
        let full = crate::local::generate::random_problem_in(3, 20, 1);
        assert!(!mostly_zero_blocks(&full));
        let one = ReducedProblem::new(vec![1.0, 0.0, 0.0, 1.0], vec![-1.0, 0.0], vec![0.3]);
        assert!(!mostly_zero_blocks(&one.unwrap()));
        let sparse = crate::local::generate::random_sparse_problem(3, 50, 0, 2);
        assert!(!mostly_zero_blocks(&sparse));
    }

    /// Issue 37, sixth part: a dense `W` kept non-symmetric runs Newton without the probe and
    /// within `AUTO_NEWTON_UNPROBED_BUDGET`, whatever its zero blocks (`newton_pays`); the
    /// same `W` symmetric keeps the step probe, kept non-symmetric but stored sparse it takes the
    /// progress probe, both with
    /// `AUTO_NEWTON_BUDGET` (the progress probe, seventh part), and a symmetric block-diagonal
    /// one is left to the sparse twin.
    #[test]
    fn issue_37_dense_non_symmetric_w_runs_newton_unprobed() {
        // two uncoupled contacts (every off-diagonal block zero), one block non-symmetric
        let w = vec![
            2.0, 0.5, 0.0, 0.0, //
            0.1, 2.0, 0.0, 0.0, //
            0.0, 0.0, 2.0, 0.0, //
            0.0, 0.0, 0.0, 2.0,
        ];
        let (q, mu) = (vec![-1.0; 4], vec![0.3; 2]);
        let kept =
            ReducedProblem::with_asymmetry(2, w.clone(), q.clone(), mu.clone(), Asymmetry::Keep)
                .unwrap();
        assert!(!kept.is_symmetric() && mostly_zero_blocks(&kept));
        assert!(newton_pays(&kept) && newton_probe(&kept) == NewtonProbe::Off);
        assert!(sparse_twin_for_auto(&kept).is_none());
        let st = UzawaSettings::default();
        let budget = auto_newton_budget(st, &kept).max_iterations;
        assert_eq!(budget, AUTO_NEWTON_UNPROBED_BUDGET);
        // symmetrised (the default policy): the multibody rule as before
        let sym =
            ReducedProblem::with_asymmetry(2, w, q, mu, Asymmetry::Symmetrise { tolerance: 1.0 })
                .unwrap();
        assert!(sym.is_symmetric() && !newton_pays(&sym));
        assert_eq!(newton_probe(&sym), NewtonProbe::Steps);
        assert!(sparse_twin_for_auto(&sym).is_some());
        assert_eq!(
            auto_newton_budget(st, &sym).max_iterations,
            AUTO_NEWTON_BUDGET
        );
        // kept non-symmetric, stored sparse: the probe stays
        let sparse = ReducedProblem::from_triplets_with_asymmetry(
            2,
            &[0, 0, 1, 1, 2, 3],
            &[0, 1, 0, 1, 2, 3],
            &[2.0, 0.5, 0.1, 2.0, 2.0, 2.0],
            vec![-1.0; 4],
            vec![0.3; 2],
            Asymmetry::Keep,
        )
        .unwrap();
        assert!(!sparse.is_symmetric());
        assert_eq!(newton_probe(&sparse), NewtonProbe::Progress);
        assert_eq!(
            auto_newton_budget(st, &sparse).max_iterations,
            AUTO_NEWTON_BUDGET
        );
    }

    /// Issue 37, ninth part: a dense `W` kept non-symmetric runs Newton at once at every size
    /// (main swept first above 32 rows: Siconos' `OneObject` problems, 69–75 rows, where the
    /// probe never promised and cost 5–8 % of `Auto`'s time); the same `W` symmetrised keeps
    /// the sweep first.
    #[test]
    fn issue_37_no_sweep_first_on_a_dense_non_symmetric_w() {
        let random = crate::local::generate::random_problem_in(3, 20, 3);
        let m = random.size();
        let w = random.w_dense().unwrap().to_vec();
        // every contact pressed
        let q: Vec<f64> = (0..m)
            .map(|k| if k % 3 == 0 { -1.0 } else { 0.2 })
            .collect();
        let mu = random.mu().to_vec();
        let sym = ReducedProblem::with_dimension(3, w.clone(), q.clone(), mu.clone()).unwrap();
        let mut w = w;
        w[1] += 0.1 * w[0]; // one entry off its mirror: kept non-symmetric
        let kept = ReducedProblem::with_asymmetry(3, w, q, mu, Asymmetry::Keep).unwrap();
        assert!(!kept.is_symmetric() && m > 32);
        assert!(
            pressed_most(&sym),
            "the symmetric problem is mostly pressed"
        );
        assert!(!pressed_most(&kept));
        assert!(newton_pays(&kept));
    }

    /// A sweep contracting by 0.5 a sweep from 1 reaches 1e-8 near sweep 27 (promised at 8
    /// sweeps); by 0.8, near sweep 83 (not promised); a rising or short history promises
    /// nothing; a history at the tolerance promises it.
    #[test]
    fn sweep_promises_works() {
        let geometric = |rate: f64| (0..8).map(|k| rate.powi(k)).collect::<Vec<_>>();
        assert!(sweep_promises(&geometric(0.5), 1e-8));
        assert!(!sweep_promises(&geometric(0.8), 1e-8));
        assert!(!sweep_promises(&geometric(1.1), 1e-8));
        assert!(!sweep_promises(&[1.0, 0.1, 0.01], 1e-8));
        assert!(sweep_promises(&[1.0, 1e-9], 1e-8));
        assert!(!sweep_promises(&[], 1e-8));
        assert!(!sweep_promises(
            &[1.0, 0.5, 0.25, 0.1, 0.05, f64::NAN],
            1e-8
        ));
    }
}
