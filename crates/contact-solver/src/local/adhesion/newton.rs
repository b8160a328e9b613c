//! Adhesion and contact solved together: one semi-smooth Newton iteration on the total
//! reactions, the states eliminated ([`AdhesionMethod::Newton`](super::AdhesionMethod)).
//!
//! The fixed point of the seed solves the contact problem for frozen states, updates the
//! states from the jumps and repeats. Here the state update is a closed form of the jump
//! (`ContactLaw::update_state`), so the states are functions of the unknowns and the whole
//! step is one nonsmooth equation. With the total reactions `r` as unknowns, `x = W r + q`,
//! the jumps `u = x + o` (`o` the tangential jump at the start of the step) and per contact
//!
//! ```text
//! s(x)   = update_state(s_start, u_start, (max(u_n, 0), u_t), Δt)     the state, eliminated
//! r̄(r,x) = r + A k(s) u                                               (r = r̄ + r_adh)
//! F(r)   = r̄ − P_K(s)(r̄ + ρ v_s(x))                                    the natural map
//! ```
//! (`A` the tributary area, `k(s)` the law's adhesive stiffness, `P_K(s)` its projection and
//! `v_s` its modified velocity, seed 5.26). `F` depends on contact `i`'s own `r_i` and
//! `x_i` only, so its generalised Jacobian is `J = A + B W` with `A_i = ∂F_i/∂r_i` and
//! `B_i = ∂F_i/∂x_i` block-diagonal; both come from central differences of the law's own
//! functions (any [`ContactLaw`] works, and a user's law needs no derivatives), by the chain
//! rule through `τ = r̄ + ρ v` so that the projection's step is on `τ`'s own scale
//! (`contact_blocks`). `ρ` is the contact's stiffness: the body's plus the start state's
//! springs (`docs/theory.md`, "The coupling solved by Newton"). A Newton
//! step factorises the dense `m × m` matrix `J` (no condensation of the springs per
//! iteration), with Armijo backtracking on `‖F‖²`. Before forming a new `J`, a chord step
//! solves with the factors kept from the last one (this solve's, or the previous solve's on
//! the same `W`: a load step's Jacobian differs little from the last step's), two triangular
//! solves against `2m³/3` flops; it is kept only if it divides `‖F‖` by 1.25, and it is tried
//! only from `m` = 256 on, where the factorisation dominates. One iteration (Newton or
//! chord) counts as one contact iteration *and* one adhesion iteration: it updates the
//! reactions and the states together, as the seed's "contact iterations" do.
//!
//! The iteration stops when the relative natural residual (the reduced layer's, with `r̄`)
//! is at most the solver's `tol`. When it cannot make progress (no descent, a singular
//! system or the iteration cap) it gives up and [`solve_adhesive`](super::solve_adhesive)
//! runs the fixed point from the start of the step instead.

use super::{AdhesiveSolution, AdhesiveStep, update_state};
use crate::error::SolverError;
use crate::local::dense::{KeptLu, dense_parallelism, fingerprint};
use crate::local::residual::contact_statuses;
use crate::local::settings::{Algorithm, UzawaReport, UzawaSettings};
use contact_laws::{ContactLaw, LocalVec2, LocalVec3};
use faer::Par;
use faer::dyn_stack::{MemBuffer, MemStack};

/// Newton steps (each with a new Jacobian) before the iteration gives up (it converges in
/// 2–6 on the seed's scenes).
const MAX_ITERATIONS: usize = 50;
/// Chord steps (with kept factors) in one solve at most; past them every step forms its
/// Jacobian.
const MAX_CHORDS: usize = 40;
/// A chord step is kept only if it multiplies the natural residual `‖F‖` by at most this;
/// otherwise the iterate's own Jacobian is formed and factorised. On the pile refined 4× and
/// 10× (`m` = 518 and 1286), 0.8 and 0.9 gave the same time, 0.5 a third more
/// (`docs/benchmarks.md`, "The pile with its interface refined").
const CHORD_CONTRACTION: f64 = 0.8;
/// Chord steps only from this many unknowns: below, a factorisation costs about what a chord
/// step does (`m` = 66 and 130 on the seed's scenes), and chords only add iterations (5.6.1:
/// 7 → 10 at the median, and slower).
const CHORD_MIN_SIZE: usize = 256;
/// Armijo's sufficient-decrease constant.
const ARMIJO: f64 = 1e-4;
/// Smallest backtracking step before the iteration gives up.
const MIN_STEP: f64 = 1.0 / 1_048_576.0;
/// Relative step of the central differences of the Jacobian's blocks.
const FD_STEP: f64 = 1e-7;
/// Smallest component, relative to the contact's force scale, a difference step is
/// relative to.
const FD_FLOOR: f64 = 1e-6;

/// What one contact's natural map needs besides its unknowns.
struct ContactData<'a, L: ContactLaw, const D: usize> {
    law: &'a L,
    start: &'a L::State,
    u_start: &'a [f64; D],
    offset: [f64; D],
    area: f64,
    /// The natural map's `ρ`: the body's stiffness at the contact plus the start state's
    /// springs.
    rho: f64,
    dt: f64,
}

/// One contact's state, `r̄` and natural map at `(y, ξ) = (r_i, x_i)`.
struct Eval<S, const D: usize> {
    state: S,
    r_bar: [f64; D],
    f: [f64; D],
}

fn to_local<const D: usize>(a: &[f64; D]) -> ([f64; 3], bool) {
    let mut v = [0.0; 3];
    v[..D].copy_from_slice(a);
    (v, D == 3)
}

/// A map of local vectors (`LocalVec2` in 2D, `LocalVec3` in 3D) on `D` plain components.
fn through_local<const D: usize>(
    a: &[f64; D],
    two: impl FnOnce(&LocalVec2) -> LocalVec2,
    three: impl FnOnce(&LocalVec3) -> LocalVec3,
) -> [f64; D] {
    let (v, is_3d) = to_local(a);
    let mut o = [0.0; 3];
    if is_3d {
        let p = three(&LocalVec3::spatial(v[0], v[1], v[2]));
        o = [p.n, p.t[0], p.t[1]];
    } else {
        let p = two(&LocalVec2::planar(v[0], v[1]));
        o[0] = p.n;
        o[1] = p.t[0];
    }
    core::array::from_fn(|d| o[d])
}

fn project<L: ContactLaw, const D: usize>(law: &L, tau: &[f64; D], s: &L::State) -> [f64; D] {
    through_local(tau, |v| law.project(v, s), |v| law.project(v, s))
}

fn velocity<L: ContactLaw, const D: usize>(law: &L, x: &[f64; D], s: &L::State) -> [f64; D] {
    through_local(
        x,
        |v| law.modified_velocity(v, s),
        |v| law.modified_velocity(v, s),
    )
}

/// One contact's state, `r̄` and projection argument `τ = r̄ + ρ v` at `(y, ξ) = (r_i, x_i)`.
fn springs_and_tau<L: ContactLaw, const D: usize>(
    c: &ContactData<'_, L, D>,
    y: &[f64; D],
    xi: &[f64; D],
) -> (L::State, [f64; D], [f64; D]) {
    let u: [f64; D] = core::array::from_fn(|d| xi[d] + c.offset[d]);
    let mut u_state = u;
    u_state[0] = u_state[0].max(0.0);
    let state = update_state(c.law, c.start, c.u_start, &u_state, c.dt);
    let [kn, kt] = c.law.adhesive_stiffness(&state);
    let r_bar: [f64; D] =
        core::array::from_fn(|d| y[d] + c.area * if d == 0 { kn } else { kt } * u[d]);
    let v = velocity(c.law, xi, &state);
    let tau: [f64; D] = core::array::from_fn(|d| r_bar[d] + c.rho * v[d]);
    (state, r_bar, tau)
}

fn eval<L: ContactLaw, const D: usize>(
    c: &ContactData<'_, L, D>,
    y: &[f64; D],
    xi: &[f64; D],
) -> Eval<L::State, D> {
    let (state, r_bar, tau) = springs_and_tau(c, y, xi);
    let p = project(c.law, &tau, &state);
    let f = core::array::from_fn(|d| r_bar[d] - p[d]);
    Eval { state, r_bar, f }
}

fn get<const D: usize>(v: &[f64], k: usize) -> [f64; D] {
    core::array::from_fn(|d| v[D * k + d])
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// The iterate's states, `r̄` and natural map for every contact.
struct Iterate<S> {
    states: Vec<S>,
    r_bar: Vec<f64>,
    f: Vec<f64>,
    merit: f64,
}

fn eval_all<L: ContactLaw, const D: usize>(
    data: &[ContactData<'_, L, D>],
    r: &[f64],
    x: &[f64],
) -> Iterate<L::State> {
    let m = r.len();
    let mut it = Iterate {
        states: Vec::with_capacity(data.len()),
        r_bar: vec![0.0; m],
        f: vec![0.0; m],
        merit: 0.0,
    };
    for (k, c) in data.iter().enumerate() {
        let e = eval(c, &get(r, k), &get(x, k));
        it.states.push(e.state);
        it.r_bar[D * k..D * k + D].copy_from_slice(&e.r_bar);
        it.f[D * k..D * k + D].copy_from_slice(&e.f);
    }
    it.merit = it.f.iter().map(|a| a * a).sum();
    it
}

/// `x = W r + q` (row-major `W`; `q = 0` when `None`).
fn apply(w: &[f64], r: &[f64], q: Option<&[f64]>, x: &mut [f64]) {
    let m = r.len();
    for (i, xi) in x.iter_mut().enumerate() {
        *xi = q.map_or(0.0, |q| q[i]) + dot(&w[i * m..(i + 1) * m], r);
    }
}

/// `a · b` with four running sums (vectorised; the order of the sums is fixed).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (a4, b4) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = a4
        .remainder()
        .iter()
        .zip(b4.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in a4.zip(b4) {
        for l in 0..4 {
            acc[l] += x[l] * y[l];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// The relative natural residual: `‖F‖ / max(‖r‖, max ρ ‖q‖, tiny)`, with the total
/// reactions `r` where the reduced layer has `r̄`: away from the answer `r̄ = r + A k u` can
/// be all spring (a glued contact 1e7 times stiffer than the body, started from `r = 0`, has
/// `‖r̄‖` 1e7 times the force it transmits, and `‖F‖/‖r̄‖` would pass any tolerance there).
fn relative(it: &Iterate<impl Copy>, r: &[f64], rho_max: f64, q_norm: f64) -> f64 {
    it.merit.sqrt() / norm(r).max(rho_max * q_norm).max(f64::MIN_POSITIVE)
}

/// Below this relative residual a Newton iterate that cannot make further progress (its
/// merit at the rounding of the forces: 1.4e-10–3e-10 on four steps of 5.6.1) is close enough
/// for the fixed point to finish from its states and `r̄` in one or two iterations.
pub(super) const CLOSE: f64 = 1e-6;

/// What Newton gives back.
pub(super) enum Outcome<S> {
    /// Converged.
    Solved(Box<AdhesiveSolution<S>>),
    /// Could not make progress; the last iterate's `r̄` and states when its residual is below
    /// [`CLOSE`] (a start for the fixed point), `None` otherwise; the work done.
    Failed(Option<(Vec<f64>, Vec<S>)>, Work),
}

/// The work of one Newton solve.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Work {
    /// Iterations (Newton and chord steps).
    pub(super) iterations: usize,
    /// Jacobians formed and factorised.
    pub(super) factorizations: usize,
}

/// One contact's blocks of the generalised Jacobian: `A = ∂F/∂r` and `B = ∂F/∂x`
/// (`[row][column]`).
struct Blocks<const D: usize> {
    a: [[f64; D]; D],
    b: [[f64; D]; D],
}

/// The blocks of contact `c` at `(y0, x0)` (its state and `r̄` there given), by the chain
/// rule through the projection's argument `τ = r̄ + ρ v`:
///
/// ```text
/// F = r̄ − P(τ, s),   A = I − P_τ,   B = ∂r̄/∂x − P_τ ∂τ/∂x − ∂P/∂s ∂s/∂x
/// ```
///
/// Each factor is a central difference on its own scale. `P_τ` takes steps relative to `τ`'s
/// components: where the cone is thin (RCCM's `μ (1 − β)` with β ≈ 1: a half-width of
/// 1e-7 against reactions of order 1, the tangential force all carried by the spring), a step
/// relative to `r` or `x` would straddle the cone's edge and average the stick and slip
/// slopes, and Newton would stall there (5.6.1, issue 18). `∂r̄/∂x`, `∂τ/∂x` and the state's
/// effect `∂P/∂s ∂s/∂x` (at fixed `τ`) are smooth but for the damage threshold and
/// `|x_t|` in `v`, and take steps relative to `x` (with a floor from the contact's force
/// scale).
fn contact_blocks<L: ContactLaw, const D: usize>(
    c: &ContactData<'_, L, D>,
    y0: &[f64; D],
    x0: &[f64; D],
    state: &L::State,
    r_bar0: &[f64; D],
    q_norm: f64,
) -> Blocks<D> {
    let scale = y0
        .iter()
        .chain(r_bar0)
        .map(|a| a.abs())
        .fold(0.0, f64::max)
        .max(c.rho * x0.iter().map(|a| a.abs()).fold(0.0, f64::max));
    let scale = if scale > 0.0 {
        scale
    } else {
        c.rho * q_norm.max(f64::MIN_POSITIVE)
    };
    let floor = FD_FLOOR * scale;
    let v0 = velocity(c.law, x0, state);
    let tau0: [f64; D] = core::array::from_fn(|d| r_bar0[d] + c.rho * v0[d]);
    // P_τ, steps relative to τ's own components (floor from τ's size, else the force scale)
    let tau_size = tau0.iter().map(|a| a.abs()).fold(0.0, f64::max);
    let tau_floor = FD_FLOOR * if tau_size > 0.0 { tau_size } else { scale };
    let mut p_tau = [[0.0; D]; D];
    for j in 0..D {
        let h = FD_STEP * tau0[j].abs().max(tau_floor);
        let (mut tp, mut tm) = (tau0, tau0);
        tp[j] += h;
        tm[j] -= h;
        let (pp, pm) = (project(c.law, &tp, state), project(c.law, &tm, state));
        for i in 0..D {
            p_tau[i][j] = (pp[i] - pm[i]) / (2.0 * h);
        }
    }
    let mut blocks = Blocks {
        a: core::array::from_fn(|i| {
            core::array::from_fn(|j| if i == j { 1.0 } else { 0.0 } - p_tau[i][j])
        }),
        b: [[0.0; D]; D],
    };
    // what moves with x_j at fixed r: the state, r̄ (springs) and τ; P's own change with the
    // state at fixed τ
    let at = |xi: &[f64; D]| {
        let (s, rb, tau) = springs_and_tau(c, y0, xi);
        let p_state = project(c.law, &tau0, &s);
        (rb, tau, p_state)
    };
    for j in 0..D {
        let hx = FD_STEP * x0[j].abs().max(floor / c.rho);
        let (mut xp, mut xm) = (*x0, *x0);
        xp[j] += hx;
        xm[j] -= hx;
        let ((rbp, tp, psp), (rbm, tm, psm)) = (at(&xp), at(&xm));
        let dtau: [f64; D] = core::array::from_fn(|d| (tp[d] - tm[d]) / (2.0 * hx));
        for i in 0..D {
            let through_tau: f64 = (0..D).map(|l| p_tau[i][l] * dtau[l]).sum();
            blocks.b[i][j] =
                (rbp[i] - rbm[i]) / (2.0 * hx) - through_tau - (psp[i] - psm[i]) / (2.0 * hx);
        }
    }
    blocks
}

/// Solves the step by Newton, or says it could not (the caller then runs the fixed point).
/// `kept` holds the factors of the last Jacobian, reused by chord steps when they were built
/// for the same `W` (and left there for the next solve); `settings.max_iterations` caps the
/// Jacobians formed.
pub(super) fn solve<L: ContactLaw, const D: usize>(
    settings: &UzawaSettings,
    step: &AdhesiveStep<'_, L, D>,
    r_start: &[f64],
    offset: &[f64],
    kept: &mut KeptLu,
) -> Result<Outcome<L::State>, SolverError> {
    let m = step.q.len();
    let na = m / D;
    let w = step.w;
    // the body's stiffness at each contact, 1 / the largest diagonal entry of W_ii: the
    // scale of the relative residual
    let body_rho: Vec<f64> = (0..na)
        .map(|k| {
            let diag = (0..D)
                .map(|d| w[(D * k + d) * m + D * k + d])
                .fold(0.0_f64, f64::max);
            if diag > 0.0 && diag.is_finite() {
                1.0 / diag
            } else {
                1.0
            }
        })
        .collect();
    let data: Vec<ContactData<'_, L, D>> = (0..na)
        .map(|k| {
            // the natural map's ρ: the contact's stiffness, the body's plus the start state's
            // springs (a scale only: the zeros of F do not depend on it)
            let [kn, kt] = step.laws[k].adhesive_stiffness(&step.start_states[k]);
            let springs = step.areas[k] * kn.max(kt);
            ContactData {
                law: &step.laws[k],
                start: &step.start_states[k],
                u_start: &step.u_start[k],
                offset: get(offset, k),
                area: step.areas[k],
                rho: body_rho[k] + if springs.is_finite() { springs } else { 0.0 },
                dt: step.dt,
            }
        })
        .collect();
    let rho_max = body_rho.iter().copied().fold(0.0, f64::max);
    let q_norm = norm(step.q);
    let mut r = r_start.to_vec();
    let mut x = vec![0.0; m];
    apply(w, &r, Some(step.q), &mut x);
    let mut it = eval_all(&data, &r, &x);
    let max_newton = settings.max_iterations.min(MAX_ITERATIONS);
    let par = dense_parallelism(2 * m * m * m / 3);
    let chords_allowed = m >= CHORD_MIN_SIZE;
    let key = if chords_allowed { fingerprint(w) } else { 0 };
    let mut scratch = MemBuffer::new(KeptLu::scratch(m, par));
    let mut rhs = vec![0.0; m];
    let mut wdr = vec![0.0; m];
    let mut r_trial = vec![0.0; m];
    let mut x_trial = vec![0.0; m];
    let mut history = Vec::new();
    let mut iterations = 0;
    let mut factorizations = 0;
    let mut chords = 0;
    let mut change = 0.0;
    let failed = |it: Iterate<L::State>, residual: f64, iterations: usize, factorizations| {
        Ok(Outcome::Failed(
            (residual <= CLOSE).then_some((it.r_bar, it.states)),
            Work {
                iterations,
                factorizations,
            },
        ))
    };
    loop {
        let residual = relative(&it, &r, rho_max, q_norm);
        history.push(residual);
        if residual <= settings.tol {
            break;
        }
        // a chord step: the kept factors (this solve's last Jacobian, or the last solve's on
        // the same W), the full step kept only if it multiplies ‖F‖ by CHORD_CONTRACTION at most
        if chords_allowed && chords < MAX_CHORDS && kept.matches(m, key) {
            for (o, f) in rhs.iter_mut().zip(&it.f) {
                *o = -f;
            }
            kept.solve(&mut rhs, Par::Seq, MemStack::new(&mut scratch));
            if rhs.iter().all(|v| v.is_finite()) {
                apply(w, &rhs, None, &mut wdr);
                for i in 0..m {
                    r_trial[i] = r[i] + rhs[i];
                    x_trial[i] = x[i] + wdr[i];
                }
                let trial = eval_all(&data, &r_trial, &x_trial);
                if trial.merit <= CHORD_CONTRACTION * CHORD_CONTRACTION * it.merit {
                    change = norm(&rhs) / norm(&r_trial).max(f64::MIN_POSITIVE);
                    core::mem::swap(&mut r, &mut r_trial);
                    core::mem::swap(&mut x, &mut x_trial);
                    it = trial;
                    iterations += 1;
                    chords += 1;
                    continue;
                }
            }
        }
        if factorizations >= max_newton {
            return failed(it, residual, iterations, factorizations);
        }
        iterations += 1;
        factorizations += 1;
        // J = A + B W, row-major
        let jac = kept.start(m);
        for (k, c) in data.iter().enumerate() {
            let (y0, x0) = (get::<D>(&r, k), get::<D>(&x, k));
            let blocks = contact_blocks(c, &y0, &x0, &it.states[k], &get(&it.r_bar, k), q_norm);
            for j in 0..D {
                for i in 0..D {
                    jac[(D * k + i) * m + D * k + j] += blocks.a[i][j];
                }
                // B's column j times row D k + j of W
                let row = &w[(D * k + j) * m..(D * k + j + 1) * m];
                for i in 0..D {
                    let b = blocks.b[i][j];
                    if b != 0.0 {
                        let out = &mut jac[(D * k + i) * m..(D * k + i + 1) * m];
                        for (o, &wv) in out.iter_mut().zip(row) {
                            *o += b * wv;
                        }
                    }
                }
            }
        }
        // a row with no dependence at all (a component held by a support, W's row zero, in
        // stick): keep that reaction as it is
        for (i, row) in jac.chunks_exact_mut(m).enumerate() {
            if row.iter().all(|&v| v == 0.0) {
                row[i] = 1.0;
            }
        }
        for (o, f) in rhs.iter_mut().zip(&it.f) {
            *o = -f;
        }
        kept.factor(key, par, MemStack::new(&mut scratch));
        kept.solve(&mut rhs, par, MemStack::new(&mut scratch));
        if !rhs.iter().all(|v| v.is_finite()) {
            // singular: no chord step may reuse these factors
            kept.forget();
            return failed(it, residual, iterations, factorizations);
        }
        // W Δr, then Armijo backtracking on ‖F‖²
        apply(w, &rhs, None, &mut wdr);
        let mut t = 1.0;
        loop {
            for i in 0..m {
                r_trial[i] = r[i] + t * rhs[i];
                x_trial[i] = x[i] + t * wdr[i];
            }
            let trial = eval_all(&data, &r_trial, &x_trial);
            if trial.merit <= (1.0 - 2.0 * ARMIJO * t) * it.merit {
                change = t * norm(&rhs) / norm(&r_trial).max(f64::MIN_POSITIVE);
                core::mem::swap(&mut r, &mut r_trial);
                core::mem::swap(&mut x, &mut x_trial);
                it = trial;
                break;
            }
            t *= 0.5;
            if t < MIN_STEP {
                return failed(it, residual, iterations, factorizations);
            }
        }
    }
    // the answer: r̄ its projection (in the law's set exactly; it moves by |F| ≤ tol), r
    // consistent with it
    for (k, c) in data.iter().enumerate() {
        let s = &it.states[k];
        let xk = get::<D>(&x, k);
        let v = velocity(c.law, &xk, s);
        let rb = get::<D>(&it.r_bar, k);
        let tau: [f64; D] = core::array::from_fn(|d| rb[d] + c.rho * v[d]);
        let p = project(c.law, &tau, s);
        let [kn, kt] = c.law.adhesive_stiffness(s);
        for d in 0..D {
            let kd = c.area * if d == 0 { kn } else { kt };
            it.r_bar[D * k + d] = p[d];
            r[D * k + d] = p[d] - kd * (xk[d] + c.offset[d]);
        }
    }
    // (x stays the iterate's, the jumps the springs and the states were evaluated at)
    let rho: Vec<f64> = data.iter().map(|c| c.rho).collect();
    let statuses = if D == 3 {
        contact_statuses::<L, 2>(step.laws, &it.states, &rho, &it.r_bar, &x)
    } else {
        contact_statuses::<L, 1>(step.laws, &it.states, &rho, &it.r_bar, &x)
    };
    let report = UzawaReport {
        algorithm: Algorithm::Newton,
        iterations,
        outer_iterations: iterations,
        tangential_sweeps: 0,
        converged: true,
        stalled: false,
        residual: *history.last().unwrap_or(&0.0),
        change,
        history,
        rho_min: rho.iter().copied().fold(f64::INFINITY, f64::min),
        rho_max,
        statuses,
        fallback_from: None,
        asymmetry: 0.0,
        rescaled: false,
        solved_contacts: na,
    };
    Ok(Outcome::Solved(Box::new(AdhesiveSolution {
        r,
        r_bar: it.r_bar,
        x,
        states: it.states,
        adhesion_iterations: iterations,
        contact_iterations: iterations,
        jacobian_factorizations: factorizations,
        converged: true,
        newton_fallback: false,
        warm_started: false,
        warm_start_failed: false,
        report,
        condensed: None,
    })))
}

#[cfg(test)]
mod tests {
    use super::super::{AdhesionMethod, AdhesionOptions, AdhesiveStep, solve_adhesive};
    use crate::{UzawaSettings, UzawaSolver};
    use contact_laws::{BetaScheme, ContactLaw, Rccm, RccmParams};

    fn rccm(alpha: f64, mu: f64, w: f64) -> Rccm {
        Rccm::new(RccmParams {
            c_n: 100.0,
            c_t: 100.0,
            w,
            alpha,
            mu,
            m: 1,
            beta_0: 1.0,
            scheme: BetaScheme::ImplicitEuler,
        })
        .unwrap()
    }

    /// A coupled SPD `W` (`m × m`, row-major): `B Bᵀ/m + 0.5 I` scaled, deterministic.
    fn spd(m: usize, seed: u64) -> Vec<f64> {
        let mut state = seed;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        let b: Vec<f64> = (0..m * m).map(|_| next()).collect();
        let mut w = vec![0.0; m * m];
        for i in 0..m {
            for j in 0..m {
                let d: f64 = (0..m).map(|k| b[i * m + k] * b[j * m + k]).sum();
                w[i * m + j] = 1e-3 * (d / m as f64 + if i == j { 0.5 } else { 0.0 });
            }
        }
        w
    }

    /// Newton and the seed's fixed point on the same step: the same reactions and states.
    fn compare<const D: usize>(step: &AdhesiveStep<'_, Rccm, D>) -> usize {
        let mut solver = UzawaSolver::new(UzawaSettings::default());
        let options = AdhesionOptions::default();
        let newton = solve_adhesive(&mut solver, step, None, &options).unwrap();
        let fixed = AdhesionOptions {
            method: AdhesionMethod::FixedPoint,
            ..options
        };
        let reference = solve_adhesive(&mut solver, step, None, &fixed).unwrap();
        assert!(!newton.newton_fallback, "Newton fell back");
        let scale = reference.r.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
        // the fixed point stops on a state change of 1e-8: its answer is that close
        for (a, b) in newton.r.iter().zip(&reference.r) {
            assert!((a - b).abs() <= 1e-6 * scale, "r {a} vs {b}");
        }
        for (a, b) in newton.states.iter().zip(&reference.states) {
            assert!((a.beta() - b.beta()).abs() <= 1e-6, "β {a:?} vs {b:?}");
        }
        newton.adhesion_iterations
    }

    /// `nc` contacts in 2D, some pulled open, some pressed and sheared (a fraction `load` of
    /// the loading).
    fn interface(nc: usize, load: f64) -> (Vec<Rccm>, Vec<f64>) {
        let laws = (0..nc)
            .map(|k| rccm(0.0, 0.3, 1e-4 * (1 + k % 3) as f64))
            .collect();
        let q = (0..nc)
            .flat_map(|k| {
                let n = if k % 3 == 0 {
                    -0.004
                } else {
                    0.003 + 1e-3 * (k % 4) as f64
                };
                [load * n, load * 2e-3 * ((k % 5) as f64 - 2.0)]
            })
            .collect();
        (laws, q)
    }

    #[test]
    fn chord_steps_on_a_large_interface_keep_the_answer_and_reuse_the_factors() {
        // 150 contacts in 2D: m = 300, where chord steps are tried
        let nc = 150;
        assert!(2 * nc >= super::CHORD_MIN_SIZE);
        let (laws, q) = interface(nc, 1.0);
        let w = spd(2 * nc, 5);
        let starts: Vec<_> = laws.iter().map(|l| l.initial_state()).collect();
        let (areas, u) = (vec![1.0; nc], vec![[0.0; 2]; nc]);
        let step = AdhesiveStep {
            w: &w,
            q: &q,
            laws: &laws,
            start_states: &starts,
            u_start: &u,
            areas: &areas,
            dt: 0.1,
        };
        // against the fixed point, from a fresh solver
        compare(&step);
        // the next load on the same W: the second solve starts from the first one's factors
        let options = AdhesionOptions::default();
        let mut solver = UzawaSolver::new(UzawaSettings::default());
        solve_adhesive(&mut solver, &step, None, &options).unwrap();
        let (_, q_next) = interface(nc, 1.05);
        let next = AdhesiveStep { q: &q_next, ..step };
        let second = solve_adhesive(&mut solver, &next, None, &options).unwrap();
        let mut fresh = UzawaSolver::new(UzawaSettings::default());
        let alone = solve_adhesive(&mut fresh, &next, None, &options).unwrap();
        assert!(!second.newton_fallback && !alone.newton_fallback);
        assert!(
            second.jacobian_factorizations < alone.jacobian_factorizations,
            "kept factors: {} Jacobians, fresh: {}",
            second.jacobian_factorizations,
            alone.jacobian_factorizations
        );
        // both stop at the relative residual 1e-10: their reactions agree to far below 1e-8
        let scale = alone.r.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
        for (a, b) in second.r.iter().zip(&alone.r) {
            assert!((a - b).abs() <= 1e-8 * scale, "r {a} vs {b}");
        }
        // a different W (same size): the kept factors are not used for it
        let w_other = spd(2 * nc, 6);
        let other = AdhesiveStep {
            w: &w_other,
            ..next
        };
        let mut fresh = UzawaSolver::new(UzawaSettings::default());
        let reused = solve_adhesive(&mut solver, &other, None, &options).unwrap();
        let alone = solve_adhesive(&mut fresh, &other, None, &options).unwrap();
        assert_eq!(
            reused.jacobian_factorizations,
            alone.jacobian_factorizations
        );
        assert_eq!(reused.r, alone.r);
    }

    #[test]
    fn one_glued_contact_pulled_beyond_the_critical_opening() {
        let law = rccm(0.0, 0.2, 0.01);
        let step = AdhesiveStep {
            w: &[1e-3, 0.0, 0.0, 1e-3],
            q: &[0.02, 0.003],
            laws: &[law],
            start_states: &[law.initial_state()],
            u_start: &[[0.0, 0.0]],
            areas: &[1.0],
            dt: 1.0,
        };
        assert!(compare(&step) <= 5);
    }

    #[test]
    fn coupled_interfaces_in_2d_and_3d_agree_with_the_fixed_point() {
        // 12 contacts: some pulled open (damage), some pressed and sheared (friction with
        // μ̄ = μ (1 − β)); viscous and rate-independent β; every pair of contacts coupled
        for (alpha, seed) in [(0.0, 1), (0.5, 2), (0.0, 3)] {
            let nc = 12;
            let laws: Vec<Rccm> = (0..nc)
                .map(|k| rccm(alpha, 0.3, 1e-4 * (1 + k % 3) as f64))
                .collect();
            let starts: Vec<_> = laws.iter().map(|l| l.initial_state()).collect();
            let areas = vec![1.0; nc];
            let q2: Vec<f64> = (0..nc)
                .flat_map(|k| {
                    let n = if k % 3 == 0 {
                        -0.004
                    } else {
                        0.003 + 1e-3 * (k % 4) as f64
                    };
                    [n, 2e-3 * ((k % 5) as f64 - 2.0)]
                })
                .collect();
            let w2 = spd(2 * nc, seed);
            let u2 = vec![[0.0; 2]; nc];
            compare(&AdhesiveStep {
                w: &w2,
                q: &q2,
                laws: &laws,
                start_states: &starts,
                u_start: &u2,
                areas: &areas,
                dt: 0.1,
            });
            let q3: Vec<f64> = (0..nc)
                .flat_map(|k| [q2[2 * k], q2[2 * k + 1], -1e-3 * ((k % 3) as f64 - 1.0)])
                .collect();
            let w3 = spd(3 * nc, seed + 10);
            let u3 = vec![[0.0; 3]; nc];
            compare(&AdhesiveStep {
                w: &w3,
                q: &q3,
                laws: &laws,
                start_states: &starts,
                u_start: &u3,
                areas: &areas,
                dt: 0.1,
            });
        }
    }
}
