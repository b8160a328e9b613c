//! The primal active-set solve of a step (no `F*`): a semi-smooth Newton iteration on the
//! displacements, for contactor nodes against rigid obstacles or other bodies.
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
//! * the guess (`guess.rs`): closed iff `σ_n = r_n − c x_n > 0` (`c` the diagonal
//!   stiffness of the dof); a sticking node slides once `|r_t| > g`, in the direction of `r_t`;
//!   a sliding node keeps sliding while it moves against its friction force and sticks
//!   otherwise; a node that has just closed slides in the direction it moves;
//! * the reactions of the Dirichlet dofs are the contact forces, `r_D = (K̃ w̃)_D`.
//!
//! The matrix with the Dirichlet rows and columns replaced by their diagonal keeps the
//! pattern of `K`, so faer's symbolic Cholesky is done once. While the Dirichlet set differs
//! from the factorised one on at most [`max_low_rank_update`] dofs, the difference is a
//! low-rank (capacitance) correction costing one solve per changed dof, once per
//! factorisation; beyond, the matrix is refactored. Every iterate is in equilibrium (one exact
//! solve); the iteration stops when its natural-map residual (relative, as for the other paths,
//! with `ρ = c`) is below the tolerance.
//!
//! In 3D (two tangents) the sliding force's direction in the tangent plane is a lagged unknown
//! too, updated along `g s − c_t x_t` with a damped `c_t`. A node held along
//! one direction of its tangent plane (on a symmetry plane) gets a frame whose second tangent
//! is that direction, without a dof; with friction, its free slip there must be zero.
//!
//! Between two bodies (node pairs, node-to-segment, node-to-face) the jump is
//! `x = P (u_a − Σ_k w_k u_k)`: the contactor's dofs are renamed as the jump's components and
//! carry the targets' motion, `u = T v` with `u_a = Pᵀ x + Σ_k w_k u_k` and the identity
//! elsewhere, so that the jump is again one dof per component and `K̃ = Tᵀ K T` (whose
//! pattern couples a contactor with its targets' neighbours: its symbolic analysis is redone
//! when the active list changes). The reactions of those dofs are the contact forces, as the
//! generalised forces `Tᵀ f` of `+r` on the contactor and `−w_k r` on its targets.
//!
//! Scope: zones whose rows of `H` of a candidate are a rotation of its node's free dofs (with
//! the normal not along a prescribed component), minus a combination of other nodes' dofs
//! (a deformable target; then the contactor node has all its components free, and no
//! contactor is another candidate's target), non-adhesive laws with a friction coefficient (`Signorini`, `Coulomb`, RCCM once fully
//! debonded), one candidate per node, and a structure that exposes its stiffness
//! ([`Structure::stiffness_matrix`]). A step out of scope is refused with the reason
//! (`SolverError::Unsupported`). The lagged friction coupling converges for the friction
//! coefficients of engineering (μ = 1: 25 iterations on the stress suite's block), not for
//! μ = 10 with lift-off (`NotConverged`; `FlexibilityMode::Auto` then solves the step with a
//! dense `F*`).

use crate::error::SolverError;
use crate::local::contact_statuses;
use contact_laws::{ContactLaw, ContactStatus};
use faer::sparse::SymbolicSparseColMatRef;
use fem_core::SpdSolver;
use fem_core::Structure;

pub(crate) mod adhesive;
mod constrained;
mod frame;
mod guess;
mod inner;
mod transform;

pub(crate) use frame::{LocalFrame, frames};

use constrained::{Base, solve_constrained};
use guess::{Damping, Guess, Swing, guess_sets};
use inner::{Context, Iterate, window};

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

/// What the primal solve keeps between steps: the symbolic analysis of `K`'s pattern, the
/// rotated stiffness and the last numeric factorisation with its Dirichlet set.
#[derive(Default)]
pub(crate) struct PrimalCache {
    /// The symbolic analysis of `K̃`'s pattern, for a stiffness version and, when the pattern
    /// is `expanded`, the active list.
    symbolic: Option<(u64, Option<Vec<usize>>, SpdSolver)>,
    /// The pattern of `K̃` when a contact has a deformable target (`None`: `K`'s).
    expanded: Option<std::sync::Arc<faer::sparse::SymbolicSparseColMat<usize>>>,
    /// Stiffness version and active list the rotated values were built for.
    rotated_for: Option<(u64, Vec<usize>)>,
    rotated: Vec<f64>,
    factor: Option<SpdSolver>,
    /// Dirichlet mask (by dof) of `factor`.
    factor_mask: Vec<bool>,
    /// Low-rank corrections of `factor` for dofs whose condition changed since it was
    /// computed, or may change soon (a window around a moving front): `M₀⁻¹ u_c` on the probe
    /// dofs, and for a released dof its row of `K̃`.
    columns: Vec<Correction>,
    /// Per slot: the index of its correction column in `columns` (`usize::MAX`: none).
    column_of: Vec<usize>,
    /// Slot of each contact dof (`usize::MAX` elsewhere) and, per slot, the entries of its row
    /// left of the diagonal (column, position): with its column, the full row of `K̃`.
    slot: Vec<usize>,
    upper: Vec<Vec<(usize, usize)>>,
    /// The probe dofs: the contact dofs and every dof their rows of `K̃` touch (sorted), the
    /// only values of a solve the contact conditions read; `probe_at[dof]` its position there
    /// (`usize::MAX` elsewhere).
    probe: Vec<usize>,
    probe_at: Vec<usize>,
    /// Per slot, the active contact it belongs to; per active contact, the others its dofs
    /// couple with in `K̃` (the neighbours along the interface).
    node_of_slot: Vec<usize>,
    adjacent: Vec<Vec<usize>>,
    /// The adhesive springs added to the diagonal of `rotated`: (position, stiffness), and
    /// as the last step passed them (per component of its active list, `rotated_for`'s).
    sprung: Vec<(usize, f64)>,
    springs_passed: Vec<f64>,
    /// The guess of the last converged solve on `rotated_for` (a warm start for the next,
    /// [`PrimalStep::x0`]; empty after a new rotation).
    last_sets: Vec<Guess>,
    /// Numeric factorisations done.
    pub factorizations: usize,
}

/// The low-rank correction of a dof whose condition differs from the factorised one.
struct Correction {
    dof: usize,
    /// Position of `dof` among the probe dofs.
    at: usize,
    /// `M₀⁻¹ u_c` on the probe dofs.
    column: Vec<f64>,
    /// A released dof's row of `K̃` on the probe dofs (position, value): its condition is
    /// `(K̃ w)_c = f_c`; `None` for a newly constrained one (`w_c = z_c`).
    row: Option<Vec<(usize, f64)>>,
}

/// The result of a primal solve, on the active list.
pub(crate) struct PrimalSolution {
    pub r: Vec<f64>,
    pub x: Vec<f64>,
    pub statuses: Vec<ContactStatus>,
    /// Iterates solved, outer and inner (on the correction columns, [`inner`]).
    pub iterations: usize,
    pub inner_iterations: usize,
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
    /// Local jumps of the free response, `x = q + H w` (`T + 1` per contact, see
    /// [`solve_primal`]).
    pub q: &'a [f64],
    /// Starting reactions (as `q`).
    pub r0: &'a [f64],
    /// Starting jumps (as `q`; empty: `q`). When given, the first guess also starts from the
    /// last solve's guess if it was on as many contacts (a sequence of solves of one step,
    /// as the adhesion fixed point's).
    pub x0: &'a [f64],
    /// Adhesive springs on the jumps (as `q`, or empty: none): the nodal stiffness `b` of
    /// each component, equal on the tangents of a contact (an isotropic law), added to the
    /// diagonal of its dof; the reactions are then the contact law's `r̄`, the springs' force
    /// `−b (x + o)` being the rest of the total reaction ([`adhesive`]).
    pub springs: &'a [f64],
    /// The springs' load at `w = 0`, `−b (q + o)` (as `springs`).
    pub spring_load: &'a [f64],
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
    /// Puts the step's adhesive springs on the diagonal of the rotated stiffness (forgetting
    /// the factor when they change).
    fn set_springs<L: ContactLaw>(
        &mut self,
        pattern: SymbolicSparseColMatRef<'_, usize>,
        step: &PrimalStep<'_, L>,
        d: usize,
    ) -> Result<(), SolverError> {
        let mut now = Vec::new();
        if !step.springs.is_empty() {
            for (kk, f) in step.frames.iter().enumerate() {
                for (c, dof) in f.dofs.iter().enumerate().take(d) {
                    let b = step.springs[d * kk + c];
                    if let (Some(dof), true) = (*dof, b != 0.0) {
                        let p = position(pattern, dof, dof).ok_or(SolverError::Unsupported(
                            "a stiffness without a diagonal entry at a contact dof".into(),
                        ))?;
                        now.push((p, b));
                    }
                }
            }
        }
        self.springs_passed.clear();
        self.springs_passed.extend_from_slice(step.springs);
        if now != self.sprung {
            for &(p, b) in &self.sprung {
                self.rotated[p] -= b;
            }
            for &(p, b) in &now {
                self.rotated[p] += b;
            }
            self.sprung = now;
            self.factor = None;
        }
        Ok(())
    }

    /// Frees the numeric factorisation and its correction columns (the next solve
    /// refactorises); the rotated stiffness and the symbolic analysis stay.
    pub(crate) fn drop_factor(&mut self) {
        self.factor = None;
        self.columns.clear();
        self.column_of.fill(usize::MAX);
    }

    /// The springs the last solve passed, if it was on `active` (empty otherwise).
    pub(crate) fn springs_for(&self, active: &[usize]) -> &[f64] {
        match &self.rotated_for {
            Some((_, a)) if a == active => &self.springs_passed,
            _ => &[],
        }
    }

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
}

/// The symbolic analysis of the stiffness's pattern: faer's AMD in 2D, nested dissection on the
/// dofs' node positions in 3D (the orderings `LinearElasticModel` and `SolidModel` use, chosen
/// by measurement: `docs/benchmarks.md`; with AMD a 3D factorisation of 1e5 dofs takes 3× as
/// long).
fn symbolic_of<S: Structure<N> + ?Sized, const N: usize>(
    structure: &S,
    pattern: SymbolicSparseColMatRef<'_, usize>,
) -> Result<SpdSolver, SolverError> {
    if N < 3 {
        return Ok(SpdSolver::new(pattern)?);
    }
    let mut coords = vec![[0.0; 3]; pattern.ncols()];
    for node in 0..structure.node_count() {
        let x = structure.node_position(node);
        for dof in structure.node_dofs(node).into_iter().flatten() {
            if let Some(c) = coords.get_mut(dof) {
                for (a, v) in x.iter().enumerate().take(3) {
                    c[a] = *v;
                }
            }
        }
    }
    let order = fem_core::ordering::nested_dissection(pattern, &coords);
    Ok(SpdSolver::with_order(pattern, &order)?)
}

/// The semi-smooth Newton (primal–dual active-set) solve of one step, see the module docs.
/// `T` is the number of tangential components (1 in 2D, 2 in 3D): `step`'s vectors hold
/// `T + 1` values per contact.
pub(crate) fn solve_primal<
    S: Structure<N> + ?Sized,
    const N: usize,
    L: ContactLaw,
    const T: usize,
>(
    structure: &S,
    cache: &mut PrimalCache,
    step: &PrimalStep<'_, L>,
) -> Result<PrimalSolution, SolverError> {
    let d = T + 1;
    // the frames' tangents (turned in the tangent plane, 3D)
    let turned = |v: &[f64], back: bool| -> Vec<f64> {
        let mut out = v.to_vec();
        if T == 2 {
            for (kk, f) in step.frames.iter().enumerate() {
                let g = f.turn;
                let (a, b) = (v[d * kk + 1], v[d * kk + 2]);
                (out[d * kk + 1], out[d * kk + 2]) = if back {
                    (g[0][0] * a + g[1][0] * b, g[0][1] * a + g[1][1] * b)
                } else {
                    (g[0][0] * a + g[0][1] * b, g[1][0] * a + g[1][1] * b)
                };
            }
        }
        out
    };
    let q_turned = turned(step.q, false);
    let r0_turned = turned(step.r0, false);
    let turned_or_empty = |v: &[f64]| {
        if v.is_empty() {
            Vec::new()
        } else {
            turned(v, false)
        }
    };
    let load_turned = turned_or_empty(step.spring_load);
    let x0_turned = turned_or_empty(step.x0);
    let step = &PrimalStep {
        q: &q_turned,
        r0: &r0_turned,
        x0: &x0_turned,
        spring_load: &load_turned,
        ..*step
    };
    let mut sol = solve_turned::<S, N, L, T>(structure, cache, step)?;
    sol.r = turned(&sol.r, true);
    sol.x = turned(&sol.x, true);
    Ok(sol)
}

/// [`solve_primal`] in the frames' tangents.
fn solve_turned<S: Structure<N> + ?Sized, const N: usize, L: ContactLaw, const T: usize>(
    structure: &S,
    cache: &mut PrimalCache,
    step: &PrimalStep<'_, L>,
) -> Result<PrimalSolution, SolverError> {
    let d = T + 1;
    let k = structure
        .stiffness_matrix()
        .ok_or(SolverError::InvalidSetting {
            what: "flexibility",
            value: 0.0,
            expected: "a structure that exposes its stiffness matrix (ActiveSet)",
        })?;
    let version = structure.stiffness_version();
    let rotated_for = Some((version, step.active.to_vec()));
    if cache.rotated_for != rotated_for {
        cache.rotate(k, step.frames)?;
        cache.rotated_for = rotated_for;
        cache.sprung.clear();
        cache.last_sets.clear();
        cache.factor = None;
    }
    let expanded = cache.expanded.clone();
    let pattern = expanded.as_deref().map_or(k.symbolic(), |p| p.as_ref());
    let symbolic_for = (version, expanded.as_ref().map(|_| step.active.to_vec()));
    if cache.symbolic.as_ref().map(|s| (s.0, &s.1)) != Some((symbolic_for.0, &symbolic_for.1)) {
        let solver = symbolic_of(structure, pattern)?;
        cache.symbolic = Some((symbolic_for.0, symbolic_for.1, solver));
        cache.factor = None;
    }
    let n = pattern.ncols();
    let na = step.active.len();
    cache.set_springs(pattern, step, d)?;
    // a frictional contact that cannot move along one of its tangents (every component along
    // it prescribed) is solved with that slip zero: exact only when its free slip is zero (a
    // symmetry plane), which is checked here
    let qmax = step.q.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (kk, f) in step.frames.iter().enumerate() {
        for c in 1..d {
            if f.dofs[c].is_none() && step.tangent[kk] && step.q[d * kk + c].abs() > 1e-12 * qmax {
                return Err(SolverError::Unsupported(format!(
                    "contact {}: it cannot move along its tangent {c} but its free slip \
                     there is {:e} (a frictional contact held across its tangent)",
                    step.active[kk],
                    step.q[d * kk + c]
                )));
            }
        }
    }
    // diagonal of K̃ at the local dofs: the complementarity constants c
    let diag = |dof: usize| cache.rotated[position(pattern, dof, dof).unwrap_or(0)];
    let c: Vec<[f64; 3]> = step
        .frames
        .iter()
        .map(|f| {
            let cn = f.dofs[0].map_or(1.0, diag);
            [cn, f.dofs[1].map_or(cn, diag), f.dofs[2].map_or(cn, diag)]
        })
        .collect();
    // ρ of the natural-map residual and of the statuses: the dof stiffness, the scale of the
    // dense path's ρ⁰ = 1/λ_max(F*_ii)
    let rho: Vec<f64> = c
        .iter()
        .map(|c| c[..d].iter().fold(0.0_f64, |m, &v| m.max(v)))
        .collect();
    let scale_q = {
        let qn = step.q.iter().map(|v| v * v).sum::<f64>().sqrt();
        rho.iter().fold(0.0_f64, |m, &r| m.max(r)) * qn
    };
    let contact_dofs: Vec<usize> = step.frames.iter().flat_map(|f| f.dofs).flatten().collect();
    // the springs' load on each contact dof (as `contact_dofs`)
    let contact_loads: Vec<f64> = step
        .frames
        .iter()
        .enumerate()
        .flat_map(|(kk, f)| {
            (0..3).filter_map(move |c| f.dofs[c].map(|_| step.spring_load.get(d * kk + c)))
        })
        .map(|v| v.copied().unwrap_or(0.0))
        .collect();
    let ctx = Context {
        step,
        pattern,
        contact_dofs: &contact_dofs,
        contact_loads: &contact_loads,
        c: &c,
        rho: &rho,
        scale_q,
    };
    let warm = step.x0.len() == step.q.len() && cache.last_sets.len() == na;
    let mut it = Iterate {
        r: step.r0.to_vec(),
        x: if step.x0.len() == step.q.len() {
            step.x0.to_vec()
        } else {
            step.q.to_vec()
        },
        sets: if warm {
            cache.last_sets.clone()
        } else {
            vec![Guess::default(); na]
        },
        g: Vec::new(),
        residual: 0.0,
        history: Vec::new(),
        done: 0,
        inner: 0,
        mask: vec![false; n],
        z: vec![0.0; n],
        force: Vec::new(),
        w: vec![0.0; n],
    };
    for (kk, &t) in step.tangent.iter().enumerate() {
        if !t {
            for j in d * kk + 1..d * (kk + 1) {
                it.r[j] = 0.0;
                it.x[j] = 0.0;
            }
        }
    }
    let mut solves = 0;
    it.residual = it.residual_of::<L, T>(&ctx);
    it.g = (0..na)
        .map(|kk| step.mu[kk] * it.r[d * kk].max(0.0))
        .collect();
    let mut damping = Damping::default();
    let mut swings = vec![Swing::default(); na];
    let mut base = Base::default();
    // the guess of the last structure solve
    let mut before = it.sets.clone();
    // whether the last iterate came from a structure solve (the answer must: [`inner`])
    let mut outer_last = false;
    loop {
        damping.observe(it.residual);
        // the semi-smooth Newton guess from the current iterate
        if it.done > 0 {
            // Coulomb thresholds from the current normal reactions (the friction coupling is
            // lagged by one iteration: the linear systems stay symmetric)
            for kk in 0..na {
                it.g[kk] = step.mu[kk] * it.r[d * kk].max(0.0);
            }
        }
        guess_sets::<L, T>(
            step,
            damping.factor,
            &c,
            &it.r,
            &it.x,
            &it.g,
            &mut it.sets,
            &mut swings,
        );
        if it.done > 0 && it.residual <= step.tol && outer_last {
            // the last iterate is in equilibrium (one exact solve) and meets the law to the
            // tolerance; the guess need not repeat (a P2 corner node with no force flips
            // between open and closed on round-off)
            cache.last_sets.clone_from(&it.sets);
            return Ok(finish::<L, T>(step, &rho, it, true, solves));
        }
        if it.done >= step.max_iterations {
            break;
        }
        it.constrain(step);
        // the inner iterations are 2D only: in 3D every sliding contact's direction changes
        // at every iteration, and on the sheared block they did not converge
        let ahead = if T == 1 && it.done > 0 {
            window(cache, step, &before, &it.sets)
        } else {
            Vec::new()
        };
        before.clone_from(&it.sets);
        solves += solve_constrained(
            cache,
            pattern,
            &contact_dofs,
            &it.mask,
            &it.z,
            &it.force,
            &ahead,
            &mut it.w,
            &mut base,
        )?;
        it.evaluate::<L, T>(&ctx, cache)?;
        let inner_before = it.inner;
        if T == 1 {
            inner::iterate::<L, T>(&ctx, cache, &base, damping.factor, &mut it)?;
        }
        outer_last = it.inner == inner_before;
    }
    if step.accept_non_converged {
        return Ok(finish::<L, T>(step, &rho, it, false, solves));
    }
    Err(SolverError::NotConverged {
        iterations: it.done,
        residual: it.residual,
        history: it.history,
        best: None,
    })
}

fn finish<L: ContactLaw, const T: usize>(
    step: &PrimalStep<'_, L>,
    rho: &[f64],
    it: Iterate,
    converged: bool,
    solves: usize,
) -> PrimalSolution {
    let statuses = contact_statuses::<L, T>(step.laws, step.states, rho, &it.r, &it.x);
    PrimalSolution {
        r: it.r,
        x: it.x,
        statuses,
        iterations: it.done,
        inner_iterations: it.inner,
        residual: it.residual,
        converged,
        solves,
    }
}
