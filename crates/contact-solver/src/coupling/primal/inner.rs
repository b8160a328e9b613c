//! Inner iterations on the correction columns: the guesses that differ from the last structure
//! solve only on dofs with a correction column are solved from it exactly by the capacitance
//! system ([`correct`]), without another structure solve.
//!
//! Near convergence a stick/slip or contact front moves by about one node per guess (the
//! traction concentrates at the front, so only the node next to it leaves its set). Each outer
//! iteration therefore also asks for the correction columns of a window of contacts around the
//! nodes whose guess changed since the last structure solve ([`window`]), solved in the same
//! block as its right-hand side; the inner iterations then move the fronts through the window,
//! each at the price of a small dense solve. A contact whose next guess would change a dof
//! without a column (or a sliding force there: the lagged thresholds `g = μ r_n` of the
//! contacts outside the window stay those of the last structure solve) keeps its guess until
//! the next outer iteration. Every inner iterate is in equilibrium, but its thresholds may lag
//! (a contact that has just closed slides with `g = 0` until its tangent gets a column or the
//! next outer iteration): an inner iterate that meets the tolerance ends the inner iterations,
//! and the answer is the next outer iterate that meets it, whose thresholds are those of the
//! iterate before it, as without inner iterations.

use super::constrained::{Base, correct, slot_forces};
use super::guess::{Guess, Swing, constraints, guess_sets, node_conditions, read_back};
use super::{PrimalCache, PrimalStep};
use crate::error::SolverError;
use crate::local::natural_residual;
use contact_laws::ContactLaw;
use faer::sparse::SymbolicSparseColMatRef;

/// Most inner iterations after one structure solve.
pub const MAX_INNER_ITERATIONS: usize = 64;

/// Most correction columns one outer iteration asks for ahead of a change (the window), and
/// how many steps along the interface's couplings the window reaches from a changed contact.
pub const WINDOW_COLUMNS: usize = 32;
pub const WINDOW_REACH: usize = 8;

/// What one primal solve reads and does not change.
pub(super) struct Context<'a, 'p, L: ContactLaw> {
    pub step: &'a PrimalStep<'p, L>,
    pub pattern: SymbolicSparseColMatRef<'a, usize>,
    pub contact_dofs: &'a [usize],
    /// The adhesive springs' load on each contact dof (as `contact_dofs`).
    pub contact_loads: &'a [f64],
    /// The complementarity constants (dof stiffnesses) and the natural map's `ρ` per contact.
    pub c: &'a [[f64; 3]],
    pub rho: &'a [f64],
    /// The residual's scale: `max(‖r‖, max ρ ‖q‖)`.
    pub scale_q: f64,
}

/// The current iterate of a primal solve and its buffers.
pub(super) struct Iterate {
    pub r: Vec<f64>,
    pub x: Vec<f64>,
    pub sets: Vec<Guess>,
    /// The Coulomb thresholds the guess was solved with.
    pub g: Vec<f64>,
    pub residual: f64,
    pub history: Vec<f64>,
    /// Iterates solved (outer and inner), and of them the inner ones.
    pub done: usize,
    pub inner: usize,
    pub mask: Vec<bool>,
    pub z: Vec<f64>,
    pub force: Vec<(usize, f64)>,
    pub w: Vec<f64>,
}

impl Iterate {
    /// The guess as constraints of the rotated system (`mask`, `z`, `force`).
    pub(super) fn constrain<L: ContactLaw>(&mut self, step: &PrimalStep<'_, L>) {
        let d = step.q.len() / step.active.len().max(1);
        constraints(
            step,
            d,
            &self.sets,
            &self.g,
            &mut self.mask,
            &mut self.z,
            &mut self.force,
        );
    }

    /// The relative natural-map residual of `(r, x)`.
    pub(super) fn residual_of<L: ContactLaw, const T: usize>(
        &self,
        ctx: &Context<'_, '_, L>,
    ) -> f64 {
        let rn = self.r.iter().map(|v| v * v).sum::<f64>().sqrt();
        let denom = rn.max(ctx.scale_q).max(f64::MIN_POSITIVE);
        natural_residual::<L, T>(ctx.step.laws, ctx.step.states, ctx.rho, &self.r, &self.x) / denom
    }

    /// Reads the reactions and jumps of the solve in `w` (exact on the probe dofs) back into
    /// the iterate, with its residual.
    pub(super) fn evaluate<L: ContactLaw, const T: usize>(
        &mut self,
        ctx: &Context<'_, '_, L>,
        cache: &PrimalCache,
    ) -> Result<(), SolverError> {
        if cache.probe.iter().any(|&i| !self.w[i].is_finite()) {
            return Err(SolverError::NotConverged {
                iterations: self.done + 1,
                residual: f64::NAN,
                history: std::mem::take(&mut self.history),
                best: None,
            });
        }
        // forces: reactions on Dirichlet dofs, the applied sliding force, zero elsewhere (the
        // rows of K̃ w at the contact dofs only, less the springs' load)
        for (&dof, &load) in ctx.contact_dofs.iter().zip(ctx.contact_loads) {
            self.z[dof] = cache.row_dot(ctx.pattern, dof, &self.w) - load;
        }
        read_back(
            ctx.step,
            T + 1,
            &self.sets,
            &self.mask,
            &self.z,
            &self.w,
            &mut self.r,
            &mut self.x,
        );
        self.residual = self.residual_of::<L, T>(ctx);
        self.history.push(self.residual);
        self.done += 1;
        Ok(())
    }
}

/// The dofs, without a correction column yet, of the contacts within [`WINDOW_REACH`]
/// couplings of a contact whose kind (open, sticking, sliding) differs between `before` and
/// `now`, nearest first, at most [`WINDOW_COLUMNS`]: the normal dofs only around a contact that
/// opened or closed, the tangential ones of frictional contacts. None when many contacts
/// changed (the fronts are not placed yet: the next factorisation is near).
pub(super) fn window<L: ContactLaw>(
    cache: &PrimalCache,
    step: &PrimalStep<'_, L>,
    before: &[Guess],
    now: &[Guess],
) -> Vec<usize> {
    let na = now.len();
    let seeds: Vec<usize> = (0..na)
        .filter(|&kk| !before[kk].same_kind(&now[kk]))
        .collect();
    let mut out = Vec::new();
    if seeds.is_empty() || seeds.len() > WINDOW_COLUMNS / 2 || cache.adjacent.len() != na {
        return out;
    }
    let d = step.q.len() / na.max(1);
    // reach per contact (usize::MAX: not reached) and whether its normal dof is wanted
    let mut reach = vec![usize::MAX; na];
    let mut normal = vec![false; na];
    let mut queue = std::collections::VecDeque::new();
    for &kk in &seeds {
        reach[kk] = 0;
        normal[kk] = before[kk].is_open() != now[kk].is_open();
        queue.push_back(kk);
    }
    while let Some(kk) = queue.pop_front() {
        let frame = &step.frames[kk];
        let frictional = step.tangent[kk] && step.mu[kk] > 0.0;
        for (comp, dof) in frame.dofs.iter().enumerate().take(d) {
            let Some(dof) = *dof else { continue };
            let wanted = if comp == 0 { normal[kk] } else { frictional };
            if wanted && cache.column_of[cache.slot[dof]] == usize::MAX {
                if out.len() == WINDOW_COLUMNS {
                    return out;
                }
                out.push(dof);
            }
        }
        if reach[kk] == WINDOW_REACH {
            continue;
        }
        for &o in &cache.adjacent[kk] {
            if reach[o] == usize::MAX {
                reach[o] = reach[kk] + 1;
                normal[o] = normal[kk];
                queue.push_back(o);
            }
        }
    }
    out
}

/// Whether the conditions of contact `kk` under `guess` and threshold `g` can be solved from
/// `base`: each of its dofs keeps `base`'s condition or has a correction column.
fn representable<L: ContactLaw>(
    ctx: &Context<'_, '_, L>,
    cache: &PrimalCache,
    base: &Base,
    kk: usize,
    guess: Guess,
    g: f64,
) -> bool {
    let d = ctx.step.q.len() / ctx.step.active.len().max(1);
    node_conditions(ctx.step, d, kk, guess, g)
        .into_iter()
        .flatten()
        .all(|(dof, held, v)| {
            let s = cache.slot[dof];
            let same = base.fixed[s] == held && (held || base.force[s] == v);
            same || cache.column_of[s] != usize::MAX
        })
}

/// The inner iterations after a structure solve (see the module docs): while the next guess
/// changes some contact whose new conditions the correction columns can solve, solve it from
/// `base` and read it back. Stops at a guess with nothing to change, at the tolerance, or at
/// the iteration cap.
pub(super) fn iterate<L: ContactLaw, const T: usize>(
    ctx: &Context<'_, '_, L>,
    cache: &PrimalCache,
    base: &Base,
    damping: f64,
    it: &mut Iterate,
) -> Result<(), SolverError> {
    if cache.columns.is_empty() {
        return Ok(());
    }
    let step = ctx.step;
    let d = T + 1;
    let na = it.sets.len();
    let mut trial = it.sets.clone();
    let mut g_try = it.g.clone();
    let mut forces = Vec::new();
    let mut two_back = Vec::new();
    let mut swings = vec![Swing::default(); na];
    for _ in 0..MAX_INNER_ITERATIONS {
        if it.residual <= step.tol || it.done >= step.max_iterations {
            break;
        }
        for (kk, g) in g_try.iter_mut().enumerate() {
            *g = step.mu[kk] * it.r[d * kk].max(0.0);
        }
        trial.clone_from(&it.sets);
        // (2D only: no sliding direction to damp)
        guess_sets::<L, T>(
            step,
            damping,
            ctx.c,
            &it.r,
            &it.x,
            &g_try,
            &mut trial,
            &mut swings,
        );
        // a new guess somewhere the columns reach; the thresholds of the contacts outside stay
        // the outer iteration's
        let mut any = false;
        for kk in 0..na {
            if trial[kk] == it.sets[kk] && g_try[kk] == it.g[kk] {
                continue;
            }
            let same = node_conditions(step, d, kk, trial[kk], g_try[kk])
                == node_conditions(step, d, kk, it.sets[kk], it.g[kk]);
            if !same && representable(ctx, cache, base, kk, trial[kk], g_try[kk]) {
                any |= trial[kk] != it.sets[kk];
            } else {
                trial[kk] = it.sets[kk];
                g_try[kk] = it.g[kk];
            }
        }
        // a guess seen two iterations ago: a cycle the columns do not settle
        if !any || trial == two_back {
            break;
        }
        two_back.clone_from(&it.sets);
        std::mem::swap(&mut it.sets, &mut trial);
        it.g.clone_from(&g_try);
        it.constrain(step);
        slot_forces(cache, &it.force, &mut forces);
        correct(cache, &it.mask, &it.z, &forces, base, &mut it.w)?;
        it.evaluate::<L, T>(ctx, cache)?;
        it.inner += 1;
    }
    Ok(())
}
