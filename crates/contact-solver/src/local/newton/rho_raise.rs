//! Raising the penalty `ρ` of Newton's map when the steps creep (issue 37, spheres in a box).
//!
//! The zeros of `F(r) = r − P_K(r + ρ v(W r + q))` do not depend on `ρ > 0`, but Newton's
//! path does: `ρ` sets where the map's kinks (stick/slip/separation) lie, so it decides
//! which active set each step's Jacobian sees. `ρ⁰_i = 1/λ_max(W_ii)` is the largest step
//! a Gauss–Seidel sweep may take, sized for one contact alone; on a multibody `W` whose global
//! spectrum is far below its diagonal blocks' (FCLIB's `spheres-in-a-box-98`: blocks of
//! `7·10³ … 6.6·10⁵`, global eigenvalues down to `2·10⁻⁵` plus a null space of 201) the map
//! with `ρ⁰` decides the cases almost on `r` alone, the Jacobian's active set is wrong step
//! after step and the line search cuts every step to `t ≤ 2⁻⁵` (5 000 steps, not solved).
//! With `ρ = 10 ρ⁰ … 3·10⁴ ρ⁰` the same Newton converges in 65–853 steps (measured in
//! `docs/benchmarks.md` "spheres in a box (issue 37)"); Siconos' `NSN_AC` takes `ρ = 1`
//! absolute here, `3·10⁴ … 6.6·10⁵ ρ⁰`.
//!
//! The rule, in the last Newton of [`Algorithm::Auto`](crate::Algorithm::Auto) only (after
//! its probe switched to the sweep and the sweep failed too): every `CREEPING_STEPS` creeping
//! iterations (a failed line search or a step `t ≤ SHORT_STEP`, counted since the last raise)
//! `ρ ← FACTOR ρ`, at most `MAX_RAISES` times (`ρ ≤ 10³ ρ⁰`). The stopping rule keeps
//! measuring the residual with `ρ⁰`. Not in every Newton run: there it lost issue 8's tipping
//! block and `random_sparse_problem(2, 1001, 2, 3)`, which converge with `ρ⁰` after long slow
//! stretches (`tests/integration/local_algorithms.rs`, `sparse.rs`). A user's Newton reaches
//! the same answers with [`UzawaTuning::rho_scale`](crate::UzawaTuning::rho_scale) (10 to
//! `3·10⁴` on FCLIB's file).

use super::proximal::SHORT_STEP;

/// Creeping iterations (since the last raise) that raise `ρ`.
pub(super) const CREEPING_STEPS: usize = 10;
/// The factor of one raise.
pub(super) const FACTOR: f64 = 10.0;
/// At most this many raises (`ρ ≤ FACTOR^MAX_RAISES ρ⁰ = 10³ ρ⁰`). Measured (FCLIB's
/// `spheres-in-a-box-98`, Newton alone): at most 1 raise, not converged in 5 000
/// iterations; 2, 3 064 iterations; 3, 223; 4, 219. On manufactured spheres in a box
/// (`tests/integration/issue_37_spheres_box.rs`) 4 raises lost two problems that 3 solve.
pub(super) const MAX_RAISES: u32 = 3;

/// The count behind the rule of the [module docs](self).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct RhoRaise {
    creeping: usize,
    raises: u32,
}

impl RhoRaise {
    /// Records one Newton iteration (`stepped = false`: no step accepted; `t` its length) and
    /// returns the factor by which `ρ` is to be multiplied now, if any.
    pub(super) fn after(&mut self, stepped: bool, t: f64) -> Option<f64> {
        if stepped && t > SHORT_STEP {
            return None;
        }
        self.creeping += 1;
        if self.creeping >= CREEPING_STEPS && self.raises < MAX_RAISES {
            self.creeping = 0;
            self.raises += 1;
            Some(FACTOR)
        } else {
            None
        }
    }

    /// How many times `ρ` was raised.
    #[cfg(test)]
    fn raises(&self) -> u32 {
        self.raises
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Good steps never raise; every `CREEPING_STEPS`-th creeping one does, `MAX_RAISES`
    /// times at most.
    #[test]
    fn rho_rises_only_after_creeping_steps() {
        let mut r = RhoRaise::default();
        for _ in 0..1000 {
            assert_eq!(r.after(true, 1.0), None);
            assert_eq!(r.after(true, 0.25), None);
        }
        let mut raised = 0;
        for k in 1..=10 * CREEPING_STEPS {
            let stepped = k % 2 == 0;
            if let Some(f) = r.after(stepped, 1.0 / 64.0) {
                assert_eq!((f, k % CREEPING_STEPS), (FACTOR, 0));
                raised += 1;
            }
        }
        assert_eq!((raised, r.raises()), (MAX_RAISES, MAX_RAISES));
    }
}
