//! The primal active-set solve of a step (no `F*`): a semi-smooth Newton iteration on the
//! displacements, for contactor nodes against rigid obstacles.
//!
//! A dense `F* = H K⁻¹ Hᵀ` costs `2 n_c` structure solves and `4 n_c²` values; the matrix-free
//! iteration costs one solve per iteration and its iteration count grows with the condition
//! number of `F*` (about `H/h` on a layer of thickness `H` meshed at `h`). Here the contact
//! conditions are imposed on the stiffness itself instead, as in the primal–dual active-set
//! methods of Hüeber & Wohlmuth: each iteration guesses which contacts are closed, sticking or
//! sliding, turns that guess into boundary conditions, and solves one linear system:
//!
//! * every candidate node is rotated into its local frame `(n, t)` (the rows of `H`), so that
//!   the local jump is `x = q + w̃` with `w̃` the rotated contact displacement `K̃⁻¹ r`;
//! * closed: `x_n = 0`, a Dirichlet condition on the rotated normal dof; sticking: also
//!   `x_t = 0` on the tangential dof; sliding: the tangential dof is loaded by the Coulomb
//!   force `r_t = ±g`, `g = μ r_n` of the previous iterate (the coupling is lagged by one
//!   iteration, so every system stays symmetric positive definite); open: `r = 0`;
//! * the guess: closed iff `σ_n = r_n − c x_n > 0` (`c` the diagonal stiffness of the dof); a
//!   sticking node slides once `|r_t| > g`, in the direction of `r_t`; a sliding node keeps
//!   sliding while it moves against its friction force and sticks otherwise (the semi-smooth
//!   Newton guess with `σ_t = r_t − c_t x_t` in the limit `c_t → 0⁺`: a large `c_t` flips its
//!   direction instead, which cycles between the two full-slip guesses when friction nearly
//!   balances the drive); a node that has just closed slides in the direction it moves;
//! * the reactions of the Dirichlet dofs are the contact forces, `r_D = (K̃ w̃)_D`.
//!
//! The matrix with the Dirichlet rows and columns replaced by their diagonal keeps the
//! pattern of `K`, so faer's symbolic Cholesky is done once. While the Dirichlet set differs
//! from the factorised one on at most [`max_low_rank_update`] dofs, the difference is a
//! low-rank (capacitance) correction costing one solve per changed dof, once per
//! factorisation; beyond, the matrix is refactored. The iteration stops when the guess repeats
//! (the iterate then solves its own boundary conditions exactly) and the natural-map residual
//! (relative, as for the other paths, with `ρ = c`), which then measures the friction lag, is
//! below the tolerance.
//!
//! Scope: rigid-obstacle zones (the two rows of `H` of a candidate form a rotation of its
//! node's two free dofs, or the normal row is a unit vector on the node's only free dof with
//! a frictionless law), non-adhesive laws with a friction coefficient (`Signorini`, `Coulomb`,
//! RCCM once fully debonded), one candidate per node, and a structure that exposes its
//! stiffness ([`Structure::stiffness_matrix`]). A step out of scope is refused with the
//! reason (`SolverError::Unsupported`). The lagged friction coupling converges for the
//! friction coefficients of engineering (μ = 1: 25 iterations on the stress suite's block),
//! not for μ = 10 with lift-off (`NotConverged`; `FlexibilityMode::Auto` then solves the step
//! with a dense `F*`).

use crate::error::SolverError;
use crate::local::{contact_statuses, natural_residual};
use contact_laws::{ContactLaw, ContactStatus};
use faer::Side;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use fem_core::Structure;

mod constrained;

use constrained::solve_constrained;

/// Most new corrections one iteration may add before the constrained stiffness is refactored
/// instead (a large change of the guess, typically in the first iterations).
pub const MAX_NEW_CORRECTIONS: usize = 24;

/// Most dofs whose condition may differ from the factorised one before the constrained
/// stiffness is refactored, for `n` free dofs: `n / 10 000`, clamped to 24..=128. Each changed
/// dof costs one solve (once per factorisation) and one column of `n` values; a factorisation
/// costs more solves the larger the mesh (10 at 1e5 dofs, 13 at 1e6 on the scene of
/// `docs/benchmarks.md`, "Scale"), so more corrections pay before refactoring.
pub fn max_low_rank_update(n: usize) -> usize {
    (n / 10_000).clamp(24, 128)
}

/// Most iterations of one primal solve (also capped by the solver settings' `max_iterations`).
/// The count grows with how far the stick/slip and contact fronts must travel, in nodes, from
/// the first guess: 52 on 10 001 frictionless contacts, a few hundred with Coulomb friction
/// (`docs/benchmarks.md`, "Scale").
pub const PRIMAL_MAX_ITERATIONS: usize = 1000;

/// One active contact as the primal solve sees it: the dofs of its node that carry the local
/// normal and tangential components, and the rotation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LocalFrame {
    /// Global dof renamed as the local normal (`[0]`) and tangential (`[1]`) component
    /// (`[1]` is `None` for a node with one free dof).
    pub dofs: [Option<usize>; 2],
    /// `p[c][e]`: coefficient of original dof `dofs[e]` in local component `c`.
    pub p: [[f64; 2]; 2],
}

/// The frames of the active contacts, or why the primal solve does not apply.
pub(crate) fn frames(
    h_rows: &[Vec<(usize, f64)>],
    candidates: &[usize],
    frictional: &[bool],
    ndof: usize,
) -> Result<Vec<LocalFrame>, String> {
    let mut owner = vec![false; ndof];
    let mut out = Vec::with_capacity(candidates.len());
    for (k, &i) in candidates.iter().enumerate() {
        let (hn, ht) = (&h_rows[2 * i], &h_rows[2 * i + 1]);
        let mut dofs: Vec<usize> = hn.iter().chain(ht).map(|&(d, _)| d).collect();
        dofs.sort_unstable();
        dofs.dedup();
        let coef = |row: &[(usize, f64)], d: usize| -> f64 {
            row.iter().filter(|&&(e, _)| e == d).map(|&(_, a)| a).sum()
        };
        let frame = match *dofs.as_slice() {
            [a, b] => {
                let p = [[coef(hn, a), coef(hn, b)], [coef(ht, a), coef(ht, b)]];
                let orth = (p[0][0] * p[0][0] + p[0][1] * p[0][1] - 1.0).abs()
                    + (p[1][0] * p[1][0] + p[1][1] * p[1][1] - 1.0).abs()
                    + (p[0][0] * p[1][0] + p[0][1] * p[1][1]).abs();
                if orth > 1e-10 {
                    return Err(format!(
                        "candidate {i}: its jump is not a rotation of one node's displacement \
                         (node-pair or node-to-segment zone)"
                    ));
                }
                LocalFrame {
                    dofs: [Some(a), Some(b)],
                    p,
                }
            }
            [a] => {
                let (an, at) = (coef(hn, a), coef(ht, a));
                if (an.abs() - 1.0).abs() > 1e-10 || at.abs() > 1e-10 || frictional[k] {
                    return Err(format!(
                        "candidate {i}: one free dof, not aligned with the normal of a \
                         frictionless contact"
                    ));
                }
                LocalFrame {
                    dofs: [Some(a), None],
                    p: [[an, 0.0], [0.0, 0.0]],
                }
            }
            _ => {
                return Err(format!(
                    "candidate {i}: its jump involves {} dofs (node-pair or node-to-segment \
                     zone)",
                    dofs.len()
                ));
            }
        };
        for d in frame.dofs.into_iter().flatten() {
            if std::mem::replace(&mut owner[d], true) {
                return Err(format!("dof {d} belongs to two contact candidates"));
            }
        }
        out.push(frame);
    }
    Ok(out)
}

/// What the primal solve keeps between steps: the symbolic analysis of `K`'s pattern, the
/// rotated stiffness and the last numeric factorisation with its Dirichlet set.
#[derive(Default)]
pub(crate) struct PrimalCache {
    symbolic: Option<(u64, SymbolicLlt<usize>)>,
    /// Stiffness version and active list the rotated values were built for.
    rotated_for: Option<(u64, Vec<usize>)>,
    rotated: Vec<f64>,
    factor: Option<Llt<usize, f64>>,
    /// Dirichlet mask (by dof) of `factor`.
    factor_mask: Vec<bool>,
    /// Low-rank corrections of `factor` for dofs whose condition changed since it was
    /// computed: `M₀⁻¹ u_c`, and for a released dof its row of `K̃`.
    columns: Vec<Correction>,
    /// Slot of each contact dof (`usize::MAX` elsewhere) and, per slot, the entries of its row
    /// left of the diagonal (column, position): with its column, the full row of `K̃`.
    slot: Vec<usize>,
    upper: Vec<Vec<(usize, usize)>>,
    /// Numeric factorisations done.
    pub factorizations: usize,
}

/// The low-rank correction of a dof whose condition differs from the factorised one.
struct Correction {
    dof: usize,
    /// `M₀⁻¹ u_c`.
    column: Vec<f64>,
    /// A released dof's row of `K̃` (its condition is `(K̃ w)_c = f_c`); `None` for a newly
    /// constrained one (`w_c = z_c`).
    row: Option<Vec<(usize, f64)>>,
}

/// The result of a primal solve, on the active list.
pub(crate) struct PrimalSolution {
    pub r: Vec<f64>,
    pub x: Vec<f64>,
    pub statuses: Vec<ContactStatus>,
    pub iterations: usize,
    pub residual: f64,
    pub converged: bool,
    pub solves: usize,
}

/// The problem of one step for [`solve_primal`].
pub(crate) struct PrimalStep<'a, L: ContactLaw> {
    pub active: &'a [usize],
    pub frames: &'a [LocalFrame],
    pub laws: &'a [L],
    pub states: &'a [L::State],
    /// Friction coefficient of each active contact (0: frictionless).
    pub mu: &'a [f64],
    /// Whether the tangential component takes part (else `x_t = r_t = 0`).
    pub tangent: &'a [bool],
    /// Local jumps of the free response, `x = q + H w`.
    pub q: &'a [f64],
    /// Starting reactions.
    pub r0: &'a [f64],
    pub tol: f64,
    pub max_iterations: usize,
    pub accept_non_converged: bool,
}

fn position(k: SymbolicSparseColMatRef<'_, usize>, row: usize, col: usize) -> Option<usize> {
    let start = k.col_ptr()[col];
    let rows = &k.row_idx()[start..k.col_ptr()[col + 1]];
    rows.binary_search(&row).ok().map(|p| start + p)
}

impl PrimalCache {
    /// `(K̃ v)_c` for a contact dof `c`: its column below the diagonal and its row left of it.
    fn row_dot(&self, pattern: SymbolicSparseColMatRef<'_, usize>, c: usize, v: &[f64]) -> f64 {
        let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
        let lower: f64 = (cp[c]..cp[c + 1]).map(|p| self.rotated[p] * v[ri[p]]).sum();
        let upper: f64 = self.upper[self.slot[c]]
            .iter()
            .map(|&(j, p)| self.rotated[p] * v[j])
            .sum();
        lower + upper
    }

    /// The rotated stiffness `K̃ = P K Pᵀ` (lower triangle, `K`'s pattern).
    fn rotate(
        &mut self,
        k: SparseColMatRef<'_, usize, f64>,
        frames: &[LocalFrame],
    ) -> Result<(), SolverError> {
        let pattern = k.symbolic();
        let n = pattern.ncols();
        let values = k.val();
        // members[d]: the rotated dofs original dof d contributes to, with the coefficients
        let mut members: Vec<[(usize, f64); 2]> = Vec::new();
        let mut slot = vec![usize::MAX; n];
        for f in frames {
            for (e, d) in f.dofs.iter().enumerate() {
                if let Some(d) = *d {
                    slot[d] = members.len();
                    let mut m = [(usize::MAX, 0.0); 2];
                    for (c, dc) in f.dofs.iter().enumerate() {
                        if let Some(dc) = *dc {
                            m[c] = (dc, f.p[c][e]);
                        }
                    }
                    members.push(m);
                }
            }
        }
        let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
        self.upper = vec![Vec::new(); members.len()];
        for j in 0..n {
            for (off, &i) in ri[cp[j]..cp[j + 1]].iter().enumerate() {
                if i != j && slot[i] != usize::MAX {
                    self.upper[slot[i]].push((j, cp[j] + off));
                }
            }
        }
        self.slot.clone_from(&slot);
        let out = &mut self.rotated;
        out.clear();
        out.resize(values.len(), 0.0);
        let missing = || SolverError::InvalidSetting {
            what: "flexibility",
            value: 0.0,
            expected: "a stiffness pattern that couples both dofs of every contact node (ActiveSet)",
        };
        let add = |i: usize, j: usize, v: f64, out: &mut Vec<f64>| -> Result<(), SolverError> {
            if i >= j {
                let pos = position(pattern, i, j).ok_or_else(missing)?;
                out[pos] += v;
            }
            Ok(())
        };
        let identity = |d: usize| [(d, 1.0), (usize::MAX, 0.0)];
        for q in 0..n {
            for p in cp[q]..cp[q + 1] {
                let (row, v) = (ri[p], values[p]);
                if slot[row] == usize::MAX && slot[q] == usize::MAX {
                    out[p] += v;
                    continue;
                }
                let mp = if slot[row] == usize::MAX {
                    identity(row)
                } else {
                    members[slot[row]]
                };
                let mq = if slot[q] == usize::MAX {
                    identity(q)
                } else {
                    members[slot[q]]
                };
                for &(i, a) in mp.iter().filter(|m| m.0 != usize::MAX) {
                    for &(j, b) in mq.iter().filter(|m| m.0 != usize::MAX) {
                        // ordered entry (row, q) → K̃[i, j]; its mirror (q, row) → K̃[j, i]
                        add(i, j, a * v * b, out)?;
                        if row != q {
                            add(j, i, a * v * b, out)?;
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

/// The semi-smooth Newton (primal–dual active-set) solve of one step, see the module docs.
pub(crate) fn solve_primal<S: Structure + ?Sized, L: ContactLaw>(
    structure: &S,
    cache: &mut PrimalCache,
    step: &PrimalStep<'_, L>,
) -> Result<PrimalSolution, SolverError> {
    let k = structure
        .stiffness_matrix()
        .ok_or(SolverError::InvalidSetting {
            what: "flexibility",
            value: 0.0,
            expected: "a structure that exposes its stiffness matrix (ActiveSet)",
        })?;
    let pattern = k.symbolic();
    let n = pattern.ncols();
    let na = step.active.len();
    let version = structure.stiffness_version();
    if cache.symbolic.as_ref().map(|s| s.0) != Some(version) {
        let sym = SymbolicLlt::try_new(pattern, Side::Lower).map_err(fem_core::FemError::from)?;
        cache.symbolic = Some((version, sym));
        cache.factor = None;
    }
    let rotated_for = Some((version, step.active.to_vec()));
    if cache.rotated_for != rotated_for {
        cache.rotate(k, step.frames)?;
        cache.rotated_for = rotated_for;
        cache.factor = None;
    }
    // diagonal of K̃ at the local dofs: the complementarity constants c
    let diag = |d: usize| cache.rotated[position(pattern, d, d).unwrap_or(0)];
    let c: Vec<[f64; 2]> = step
        .frames
        .iter()
        .map(|f| {
            let cn = f.dofs[0].map_or(1.0, diag);
            [cn, f.dofs[1].map_or(cn, diag)]
        })
        .collect();
    // ρ of the natural-map residual and of the statuses: the dof stiffness, the scale of the
    // dense path's ρ⁰ = 1/λ_max(F*_ii)
    let rho: Vec<f64> = c.iter().map(|c| c[0].max(c[1])).collect();
    let denom = {
        let qn = step.q.iter().map(|v| v * v).sum::<f64>().sqrt();
        let rq = rho.iter().fold(0.0_f64, |m, &r| m.max(r)) * qn;
        move |r: &[f64]| {
            let rn = r.iter().map(|v| v * v).sum::<f64>().sqrt();
            rn.max(rq).max(f64::MIN_POSITIVE)
        }
    };

    let mut r = step.r0.to_vec();
    let mut x = step.q.to_vec();
    for (kk, &t) in step.tangent.iter().enumerate() {
        if !t {
            r[2 * kk + 1] = 0.0;
            x[2 * kk + 1] = 0.0;
        }
    }
    let mut mask = vec![false; n];
    let mut w = vec![0.0; n];
    let mut z = vec![0.0; n];
    let mut force: Vec<(usize, f64)> = Vec::new();
    let contact_dofs: Vec<usize> = step.frames.iter().flat_map(|f| f.dofs).flatten().collect();
    // per contact: 0 open, 1 stick, 2 slip (with sign)
    let mut sets: Vec<(u8, f64)> = vec![(0, 0.0); na];
    let mut last_sets = sets.clone();
    let mut history = Vec::new();
    let mut solves = 0;
    let mut residual = natural_residual::<L, 1>(step.laws, step.states, &rho, &r, &x) / denom(&r);
    let mut g: Vec<f64> = (0..na).map(|kk| step.mu[kk] * r[2 * kk].max(0.0)).collect();
    for iteration in 0..=step.max_iterations {
        // the semi-smooth Newton guess from the current iterate
        if iteration > 0 {
            // Coulomb thresholds from the current normal reactions (the friction coupling is
            // lagged by one iteration: the linear systems stay symmetric)
            for kk in 0..na {
                g[kk] = step.mu[kk] * r[2 * kk].max(0.0);
            }
        }
        last_sets.clone_from(&sets);
        guess_sets(step, &c, &r, &x, &g, &mut sets);
        if iteration > 0 && sets == last_sets && residual <= step.tol {
            // the iterate solves its own guess exactly: converged once the friction lag is
            // below the tolerance too
            return Ok(finish(step, &rho, r, x, iteration, residual, true, solves));
        }
        if iteration == step.max_iterations {
            break;
        }
        constraints(step, &sets, &g, &mut mask, &mut z, &mut force);
        solves += solve_constrained(cache, pattern, &contact_dofs, &mask, &z, &force, &mut w)?;
        if w.iter().any(|v| !v.is_finite()) {
            return Err(SolverError::NotConverged {
                iterations: iteration + 1,
                residual: f64::NAN,
                history,
            });
        }
        // forces: reactions on Dirichlet dofs, the applied sliding force, zero elsewhere (the
        // rows of K̃ w at the contact dofs only)
        for &d in &contact_dofs {
            z[d] = cache.row_dot(pattern, d, &w);
        }
        read_back(step, &sets, &mask, &z, &w, &mut r, &mut x);
        residual = natural_residual::<L, 1>(step.laws, step.states, &rho, &r, &x) / denom(&r);
        history.push(residual);
    }
    if step.accept_non_converged {
        return Ok(finish(
            step,
            &rho,
            r,
            x,
            step.max_iterations,
            residual,
            false,
            solves,
        ));
    }
    Err(SolverError::NotConverged {
        iterations: step.max_iterations,
        residual,
        history,
    })
}

/// Per contact: `(0, 0)` open, `(1, 0)` stick, `(2, ±1)` slip with the sign of the friction
/// force (`(2, 0)` for a frictionless or normal-only contact); `sets` holds the previous guess.
///
/// The guess is the semi-smooth Newton one with σ_n = r_n − c x_n and σ_t = r_t − c_t x_t in
/// the limit c_t → 0⁺ (any c > 0 has the same solutions): a sliding node keeps sliding while
/// it moves against its friction force and sticks otherwise (a large c_t would flip its
/// direction, which cycles between the two full-slip guesses when friction nearly balances
/// the drive); a sticking node slides once its reaction leaves the Tresca disc.
fn guess_sets<L: ContactLaw>(
    step: &PrimalStep<'_, L>,
    c: &[[f64; 2]],
    r: &[f64],
    x: &[f64],
    g: &[f64],
    sets: &mut [(u8, f64)],
) {
    let na = sets.len();
    for kk in 0..na {
        let (rn, xn) = (r[2 * kk], x[2 * kk]);
        let sn = rn - c[kk][0] * xn;
        let prev = sets[kk];
        sets[kk] = if sn <= 0.0 {
            (0, 0.0)
        } else if !step.tangent[kk] || step.frames[kk].dofs[1].is_none() {
            (2, 0.0)
        } else if g[kk] == 0.0 {
            // no friction force yet: slide, in the direction the node moves
            (2, -x[2 * kk + 1].signum())
        } else {
            let (rt, xt) = (r[2 * kk + 1], x[2 * kk + 1]);
            match prev {
                (2, s) if s != 0.0 && xt * s < 0.0 => (2, s),
                (2, s) if s != 0.0 => (1, 0.0),
                (1, _) if rt.abs() > g[kk] => (2, rt.signum()),
                _ => (1, 0.0),
            }
        };
    }
}

/// The guess `sets` as constraints of the rotated system: the Dirichlet set `mask` with its values
/// `z` (closed normals, sticking tangents) and the sliding forces `g · s` on the free
/// tangential dofs.
fn constraints<L: ContactLaw>(
    step: &PrimalStep<'_, L>,
    sets: &[(u8, f64)],
    g: &[f64],
    mask: &mut [bool],
    z: &mut [f64],
    force: &mut Vec<(usize, f64)>,
) {
    // the Dirichlet set and its values
    mask.fill(false);
    z.fill(0.0);
    for (kk, f) in step.frames.iter().enumerate() {
        if sets[kk].0 >= 1
            && let Some(d) = f.dofs[0]
        {
            mask[d] = true;
            z[d] = -step.q[2 * kk];
        }
        if sets[kk].0 == 1
            && let Some(d) = f.dofs[1]
        {
            mask[d] = true;
            z[d] = -step.q[2 * kk + 1];
        }
    }
    // sliding forces on the free tangential dofs
    force.clear();
    for (kk, f) in step.frames.iter().enumerate() {
        if sets[kk].0 == 2
            && sets[kk].1 != 0.0
            && let Some(d) = f.dofs[1]
        {
            force.push((d, g[kk] * sets[kk].1));
        }
    }
}

/// The local jumps `x = q + w` and reactions `r` of a solve: the reaction `z` on a Dirichlet dof or
/// a sliding tangent, zero elsewhere; the constrained components of `x` exactly zero.
fn read_back<L: ContactLaw>(
    step: &PrimalStep<'_, L>,
    sets: &[(u8, f64)],
    mask: &[bool],
    z: &[f64],
    w: &[f64],
    r: &mut [f64],
    x: &mut [f64],
) {
    for (kk, f) in step.frames.iter().enumerate() {
        for comp in 0..2 {
            let j = 2 * kk + comp;
            match f.dofs[comp] {
                Some(d) => {
                    x[j] = step.q[j] + w[d];
                    r[j] = if mask[d] || (comp == 1 && sets[kk].0 == 2) {
                        z[d]
                    } else {
                        0.0
                    };
                }
                None => {
                    x[j] = 0.0;
                    r[j] = 0.0;
                }
            }
        }
        if !step.tangent[kk] {
            x[2 * kk + 1] = 0.0;
            r[2 * kk + 1] = 0.0;
        }
        if sets[kk].0 >= 1 {
            x[2 * kk] = 0.0;
        }
        if sets[kk].0 == 1 {
            x[2 * kk + 1] = 0.0;
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn finish<L: ContactLaw>(
    step: &PrimalStep<'_, L>,
    rho: &[f64],
    r: Vec<f64>,
    x: Vec<f64>,
    iterations: usize,
    residual: f64,
    converged: bool,
    solves: usize,
) -> PrimalSolution {
    let statuses = contact_statuses::<L, 1>(step.laws, step.states, rho, &r, &x);
    PrimalSolution {
        r,
        x,
        statuses,
        iterations,
        residual,
        converged,
        solves,
    }
}
