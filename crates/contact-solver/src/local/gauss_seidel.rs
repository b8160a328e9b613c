//! The projected Gauss–Seidel sweep of the bipotential iteration (De Saxcé–Feng): contact by
//! contact with the current `x`, which is updated right after with the columns of `W` that
//! the contact touches (two in 2D, three in 3D); each contact adapts its own `ρ_i` with its local step (`x_i` moves by
//! `W_ii Δr_i`), see the [layer docs](crate::local#the-penalty-ρ).
//!
//! ```text
//! τ_i = r_i + ρ_i v_i(x_i),   Δr_i = P_K(τ_i) − r_i,   x ← x + W[:, i] Δr_i
//! ```

use super::problem::ReducedProblem;
use super::residual::{local, pick, set_local};
use super::settings::{ADAPT_GROW_BELOW, ADAPT_GROWTH, ADAPT_SHRINK_ABOVE};
use super::sweep::{MAX_SHRINKS, Sweeps};
use contact_laws::{ContactLaw, LocalVec};

impl Sweeps {
    /// One projected Gauss–Seidel sweep with per-contact adapted `ρ_i`; returns `‖Δr‖²`.
    pub(crate) fn gauss_seidel_sweep<L: ContactLaw, const DT: usize>(
        &mut self,
        problem: &ReducedProblem,
        laws: &[L],
        states: &[L::State],
        r: &mut [f64],
        x: &mut [f64],
    ) -> f64 {
        // 2D contacts solved exactly (`exact_2d`, set per run for this problem)
        if DT == 1
            && let Some(exact) = self
                .exact
                .take_if(|e| e.blocks.len() == problem.contact_count())
        {
            let dr2 = self.exact_sweep_2d(&exact, problem, laws, states, r, x);
            self.exact = Some(exact);
            return dr2;
        }
        // rows of `columns` are the columns of W (W itself unless a non-symmetric W is kept)
        let w = problem.columns();
        // the blocks read at the reset, when it was for this problem (its size)
        let cached = self.blocks.len() == problem.contact_count();
        let mut dr2 = 0.0;
        for i in 0..problem.contact_count() {
            let (law, s) = (pick(laws, i), pick(states, i));
            let block = if cached {
                self.blocks[i]
            } else {
                problem.diagonal_block(i)
            };
            let ri = local::<DT>(r, i);
            let xi = local::<DT>(x, i);
            let d = self.projected_step::<L, DT>(i, law, s, ri, xi, &block);
            if d.n == 0.0 && d.t.iter().all(|&t| t == 0.0) {
                continue;
            }
            dr2 += d.dot(&d);
            set_local(r, i, &(ri + d));
            // x += W[:, d i + k] Δr_k, read as rows of `columns`.
            let b = (DT + 1) * i;
            if DT == 1 {
                w.axpy_rows2(b, [d.n, d.t[0]], x);
            } else {
                w.axpy_rows3(b, [d.n, d.t[0], d.t[1]], x);
            }
        }
        dr2
    }

    /// The projected step of contact `i` with the others held, `Δr_i = P_K(r_i + ρ_i v_i) − r_i`,
    /// adapting its `ρ_i` on its local step (`x_i` moves by `W_ii Δr_i`, `block`).
    #[inline]
    pub(crate) fn projected_step<L: ContactLaw, const DT: usize>(
        &mut self,
        i: usize,
        law: &L,
        s: &L::State,
        ri: LocalVec<DT>,
        xi: LocalVec<DT>,
        block: &[[f64; 3]; 3],
    ) -> LocalVec<DT> {
        let v = law.modified_velocity(&xi, s);
        let mut shrinks = 0;
        loop {
            let rho = self.rho[i];
            let d = law.project(&(ri + v * rho), s) - ri;
            let dd = d.dot(&d);
            if dd == 0.0 {
                return d;
            }
            // x_i moves by W_ii Δr_i when only r_i changes.
            let mut xn = xi;
            xn.n += block[0][0] * d.n;
            for k in 0..DT {
                xn.n += block[0][k + 1] * d.t[k];
                xn.t[k] += block[k + 1][0] * d.n;
                for l in 0..DT {
                    xn.t[k] += block[k + 1][l + 1] * d.t[l];
                }
            }
            let dv = law.modified_velocity(&xn, s) - v;
            let ratio = rho * (dv.dot(&dv) / dd).sqrt();
            if ratio > ADAPT_SHRINK_ABOVE && shrinks < MAX_SHRINKS {
                self.rho[i] *= 0.5;
                shrinks += 1;
                continue;
            }
            if ratio < ADAPT_GROW_BELOW {
                self.rho[i] *= ADAPT_GROWTH;
            }
            return d;
        }
    }
}
