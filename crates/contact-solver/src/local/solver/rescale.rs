//! The internal rescaling of problems whose magnitudes would over- or underflow the norms.

use super::{RESCALE_ABOVE, UzawaSolver};
use crate::error::SolverError;
use crate::local::problem::ReducedProblem;
use crate::local::settings::Solution;
use contact_laws::ContactLaw;

impl UzawaSolver {
    /// Solves a problem whose `W` or `q` has magnitudes outside `[1e-100, 1e100]` on a copy
    /// rescaled by powers of two (exact: `W' = s_w W`, `q' = s_q q`, then `r = r' s_w / s_q`,
    /// `x = x' / s_q`), when every law is scale invariant; `None` when no rescaling is needed.
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] for magnitudes outside `[1e-150, 1e150]` (where the
    /// squares in the norms overflow) with a law that is not scale invariant; errors of the
    /// solve.
    pub(super) fn solve_rescaled<L: ContactLaw>(
        &mut self,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        r: &[f64],
    ) -> Result<Option<Solution>, SolverError> {
        let w_max = problem.delassus().max_abs();
        let q_max = problem.q().iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let outside = |v: f64, bound: f64| v != 0.0 && !(1.0 / bound..=bound).contains(&v);
        // the reactions are of the order of q/W: W ~ 1e74 with q ~ 1e-83 has r ~ 1e-157,
        // whose squares in the norms are subnormal (a residual of 0 and a "converged"
        // answer wrong by 1e-6 relative, found by tests/integration/finiteness.rs)
        let ratio = if w_max > 0.0 { q_max / w_max } else { 0.0 };
        if !outside(w_max, RESCALE_ABOVE)
            && !outside(q_max, RESCALE_ABOVE)
            && !outside(ratio, RESCALE_ABOVE)
        {
            return Ok(None);
        }
        if !laws.iter().all(ContactLaw::is_scale_invariant) {
            for (what, value) in [("W", w_max), ("q", q_max), ("q/W", ratio)] {
                if outside(value, 1e150) {
                    return Err(SolverError::InvalidSetting {
                        what,
                        value,
                        expected: "magnitudes within [1e-150, 1e150], or laws that are scale \
                                   invariant (ContactLaw::is_scale_invariant) so that W and q \
                                   can be rescaled",
                    });
                }
            }
            return Ok(None);
        }
        // powers of two: the rescaled problem has the same bits up to the exponents
        let power = |v: f64| {
            if v == 0.0 {
                1.0
            } else {
                2f64.powi(-(v.log2().round() as i32).clamp(-1020, 1020))
            }
        };
        let (sw, sq) = (power(w_max), power(q_max));
        // in the problem's own storage: a sparse W stays sparse
        let scaled = problem.rescaled(sw, sq)?;
        let r_scaled: Vec<f64> = r.iter().map(|v| v * sq / sw).collect();
        let start = r.iter().any(|&v| v != 0.0).then_some(r_scaled.as_slice());
        let mut sol = self.solve_with_states(&scaled, laws, states, start)?;
        sol.r.iter_mut().for_each(|v| *v = *v * sw / sq);
        sol.x.iter_mut().for_each(|v| *v /= sq);
        let report = &mut sol.report;
        report.rho_min *= sw;
        report.rho_max *= sw;
        report.rescaled = true;
        report.asymmetry = problem.asymmetry();
        Ok(Some(sol))
    }
}
