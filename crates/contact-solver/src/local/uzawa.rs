//! The Uzawa (Jacobi) step of the bipotential iteration, seed 5.26 / 5.52: every contact from
//! the same `x`, then `x = W r + q` once, with one global factor `θ` of the base penalties
//! adapted by the self-adaptive rule of the [layer docs](crate::local#the-penalty-ρ).
//!
//! ```text
//! τ_i = r_i + θ ρ⁰_i v_i(x),   r_i ← P_K(τ_i),   x ← W r + q
//! ```

use super::problem::ReducedProblem;
use super::residual::{local, pick, set_local};
use super::settings::{ADAPT_GROW_BELOW, ADAPT_GROWTH, ADAPT_SHRINK_ABOVE};
use super::sweep::{MAX_SHRINKS, Sweeps};
use contact_laws::ContactLaw;

impl Sweeps {
    /// One Jacobi step with the globally adapted factor `theta`; returns `‖Δr‖²`.
    /// `self.v` must hold `v(x)` on entry (it holds `v` of the new `x` on return).
    pub(crate) fn uzawa_step<L: ContactLaw, const DT: usize>(
        &mut self,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        r: &mut [f64],
        x: &mut [f64],
        theta: &mut f64,
    ) -> f64 {
        // `self.v` holds v(x) for the current iterate: set before the first step, then carried
        // over from the accepted trial below, so it is never evaluated twice.
        let nc = problem.contact_count();
        let mut shrinks = 0;
        loop {
            let mut dr2 = 0.0;
            for i in 0..nc {
                let (law, s) = (pick(laws, i), pick(states, i));
                let ri = local::<DT>(r, i);
                let tau = ri + local::<DT>(&self.v, i) * (*theta * self.rho0[i]);
                let rn = law.project(&tau, s);
                let d = rn - ri;
                dr2 += d.dot(&d);
                set_local(&mut self.r_trial, i, &rn);
            }
            if dr2 == 0.0 {
                return 0.0;
            }
            problem.displacement_into(&self.r_trial, &mut self.x_trial);
            let mut dv2 = 0.0;
            for i in 0..nc {
                let v = pick(laws, i)
                    .modified_velocity(&local::<DT>(&self.x_trial, i), pick(states, i));
                set_local(&mut self.v_trial, i, &v);
                let d = (v - local::<DT>(&self.v, i)) * (*theta * self.rho0[i]);
                dv2 += d.dot(&d);
            }
            let ratio = (dv2 / dr2).sqrt();
            if ratio > ADAPT_SHRINK_ABOVE && shrinks < MAX_SHRINKS {
                *theta *= 0.5;
                shrinks += 1;
                continue;
            }
            if ratio < ADAPT_GROW_BELOW {
                *theta *= ADAPT_GROWTH;
            }
            r.copy_from_slice(&self.r_trial);
            x.copy_from_slice(&self.x_trial);
            std::mem::swap(&mut self.v, &mut self.v_trial);
            return dr2;
        }
    }
}
