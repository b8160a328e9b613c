//! [`Algorithm::Auto`](crate::Algorithm::Auto) in 2D (issue 37, ninth part): its Gauss–Seidel
//! sweeps solve each contact exactly ([`ContactSolve::Exact`], `local/exact_2d.rs`), and on a
//! sparse `W` that sweep runs in place of Newton.
//!
//! Measured (`docs/benchmarks.md`, "The 2D sweep with exact contacts (issue 37, ninth
//! part)"; the accelerated sweep alone, dev profile at `opt-level = 3`, cold start, 1e-8):
//!
//! ```text
//! problem (2D)                   n_c  W       projected AGS     exact AGS       Newton
//! Siconos FrictionContact…00727  367  sparse  1 276 sw 27.6 ms    99 sw 1.22 ms   68 it 25 ms
//! Siconos FrictionContact…00237  376  sparse    157 sw  3.5 ms    51 sw 0.74 ms   43 it 14 ms
//! Siconos FrictionContact…00071   89  sparse     70 sw  0.32 ms   22 sw 0.07 ms   13 it 0.37 ms
//! random block-sparse            2000 sparse     45 sw  6.5 ms    12 sw 1.6 ms     7 it 24 ms
//! random dense                    200 dense      26 sw  1.15 ms   17 sw 0.89 ms    8 it 3.3 ms
//! plane-strain Hertz (FE, F*)      40 dense      54 sw  0.15 ms   54 sw 0.12 ms    8 it 0.09 ms
//! ```
//! The exact sweep never took more sweeps than the projected one; on a sparse `W` it beat
//! Newton 5–15×, on the dense FE flexibility Newton stays ahead (its rule is kept there).

use crate::local::problem::ReducedProblem;
use crate::local::settings::{ContactSolve, UzawaSettings};

/// `st` for [`Algorithm::Auto`](crate::Algorithm::Auto)'s runs on `problem`: in 2D, the
/// sweeps solve each contact exactly.
pub(in crate::local::solver) fn auto_contact_solve(
    st: UzawaSettings,
    problem: &ReducedProblem,
) -> UzawaSettings {
    if problem.dimension() == 2 {
        st.with_contact_solve(ContactSolve::Exact)
    } else {
        st
    }
}

/// Whether the exact 2D sweep is [`Algorithm::Auto`](crate::Algorithm::Auto)'s choice over
/// Newton: a 2D problem with `W` stored sparse (see the module docs).
pub(in crate::local::solver) fn exact_sweep_beats_newton(problem: &ReducedProblem) -> bool {
    problem.dimension() == 2 && problem.w_sparse().is_some()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::generate::{random_problem_in, random_sparse_problem};

    /// 2D gets the exact contacts, 3D keeps the projected step; only a 2D sparse `W` takes
    /// the sweep over Newton.
    #[test]
    fn auto_contact_solve_works() {
        let st = UzawaSettings::default();
        let (dense_2d, dense_3d) = (random_problem_in(2, 5, 1), random_problem_in(3, 5, 1));
        let sparse_2d = random_sparse_problem(2, 50, 0, 2);
        let sparse_3d = random_sparse_problem(3, 50, 0, 2);
        let solve = |p: &ReducedProblem| auto_contact_solve(st, p).tuning.contact_solve;
        assert_eq!(solve(&dense_2d), ContactSolve::Exact);
        assert_eq!(solve(&sparse_2d), ContactSolve::Exact);
        assert_eq!(solve(&dense_3d), ContactSolve::Projected);
        assert!(exact_sweep_beats_newton(&sparse_2d));
        assert!(!exact_sweep_beats_newton(&dense_2d));
        assert!(!exact_sweep_beats_newton(&sparse_3d));
    }

    /// Issue 37, ninth part: `Auto` on a generated 2D block-sparse problem runs the
    /// accelerated sweep with exact contacts, no Newton first, in at most half the sweeps of
    /// the projected accelerated sweep that main's rule ran there (measured: 12 against 45 at
    /// 2 000 contacts), converged.
    #[test]
    fn issue_37_auto_runs_the_exact_sweep_on_a_sparse_2d_w() {
        use crate::{Algorithm, UzawaSolver};
        let p = random_sparse_problem(2, 400, 2, 11);
        let laws = p.coulomb_laws();
        let auto = UzawaSolver::new(st_auto()).solve(&p, &laws).unwrap();
        let ags = UzawaSettings::default().with_algorithm(Algorithm::AndersonGaussSeidel);
        let projected = UzawaSolver::new(ags).solve(&p, &laws).unwrap();
        let rep = &auto.report;
        assert_eq!(rep.algorithm, Algorithm::AndersonGaussSeidel);
        assert_eq!(rep.fallback_from, None);
        assert!(rep.converged);
        let n_p = projected.report.iterations;
        assert!(
            2 * rep.iterations <= n_p,
            "Auto {} sweeps, projected {n_p}",
            rep.iterations
        );
    }

    fn st_auto() -> UzawaSettings {
        UzawaSettings::default().with_algorithm(crate::Algorithm::Auto)
    }
}
