//! The proximal regularisation of the Newton system on a semidefinite or rank-deficient `W`
//! (issue 37): the Jacobian is taken with `W + ε_i I` in place of `W` (`F` keeps the true
//! `W`, so the zeros are the same), with `ε_i = η / ρ_i` (`1/ρ⁰_i` is the largest eigenvalue
//! of contact `i`'s diagonal block: `η` is relative to the block's scale), Levenberg–Marquardt
//! fashion:
//!
//! - `η = 0` until a Newton step fails (a direction that is not finite, or no step accepted by
//!   the line search) or is short (`t ≤ SHORT_STEP`): on a well-posed problem the iteration is
//!   the plain semi-smooth Newton, step for step;
//! - on such a step `η ← max(10 η, ETA_MIN)` (at most `ETA_MAX`) and the step is retried at
//!   once with the new `η` (at most `RETRIES` times per iteration) before the iteration falls
//!   back to a Gauss–Seidel sweep;
//! - on a full step (`t = 1`) `η ← η / 10`, and `0` below `ETA_MIN`, so that the last steps
//!   are plain Newton steps and converge superlinearly.
//!
//! On a singular `S W` restricted to the sticking unknowns (a rank-deficient `W`: redundant
//! contacts of a rigid body) the plain system has no solution, or a huge one the line search
//! cuts to nothing; `W + εI` is positive definite there, and its step is a damped Newton step
//! (a proximal-point step of size `1/ε` along the null space of `W`).

/// The smallest non-zero `η`.
pub(super) const ETA_MIN: f64 = 1e-6;
/// The largest `η` (`ε_i` = the block's largest eigenvalue: a step of the size of a Jacobi
/// step).
pub(super) const ETA_MAX: f64 = 1.0;
/// Retries of a failed or short step with a larger `η` in one iteration.
pub(super) const RETRIES: usize = 3;
/// A step `t` at most this short raises `η` (the creeping steps of a semidefinite `W`,
/// `docs/benchmarks.md` "Auto's Newton as a probe": converging runs take `t ≥ 2⁻⁴`).
pub(super) const SHORT_STEP: f64 = 1.0 / 32.0;

/// `η` after a step of length `t` (`stepped = false`: none accepted) taken with `eta`, and
/// whether the step is to be retried with it (a failed step, while `η` can still rise).
pub(super) fn next_eta(eta: f64, stepped: bool, t: f64) -> (f64, bool) {
    if stepped && t > SHORT_STEP {
        let down = if t >= 1.0 { eta / 10.0 } else { eta };
        (if down < ETA_MIN { 0.0 } else { down }, false)
    } else {
        let up = (eta * 10.0).clamp(ETA_MIN, ETA_MAX);
        (up, up > eta)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `η` stays 0 on good steps, rises by 10 on failed or short ones up to `ETA_MAX` (and
    /// asks for a retry only while it rises), falls by 10 on full steps back to 0.
    #[test]
    fn eta_rises_on_bad_steps_and_falls_on_full_ones() {
        assert_eq!(next_eta(0.0, true, 1.0), (0.0, false));
        assert_eq!(next_eta(0.0, true, 0.25), (0.0, false));
        assert_eq!(next_eta(0.0, false, 1e-6), (ETA_MIN, true));
        assert_eq!(next_eta(0.0, true, 1.0 / 64.0), (ETA_MIN, true));
        let (e, retry) = next_eta(1e-3, false, 0.0);
        assert!((e - 1e-2).abs() < 1e-15 && retry);
        assert_eq!(next_eta(ETA_MAX, false, 0.0), (ETA_MAX, false));
        let (e, retry) = next_eta(1e-3, true, 1.0);
        assert!((e - 1e-4).abs() < 1e-16 && !retry);
        assert_eq!(next_eta(1e-3, true, 0.5), (1e-3, false));
        assert_eq!(next_eta(ETA_MIN, true, 1.0), (0.0, false));
    }
}
