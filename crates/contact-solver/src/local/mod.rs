//! The reduced-problem layer: `x = W r + q` with `r_i ∈ K_μi`, and every algorithm that solves
//! it (seed 5.26, 5.52). It depends on `contact-laws` and `faer` only (and `serde` for the JSON
//! form), so an FE code that condenses its own problem can use it without the FE coupling:
//! `contact-solver = { version = "0.1", default-features = false }` (see the crate docs).
//!
//! # Files
//! - [`problem`]: the validated problem [`ReducedProblem`]; `csr`: the sparse storage
//!   [`CsrMatrix`]; `delassus`: the row operations every algorithm uses on either storage
//!   (and the public view [`WView`]); `json` (feature `serde`) its JSON form; `fclib`
//!   (feature `fclib`) FCLIB's HDF5 files in and out; [`generate`]: seeded random problems,
//!   dense and sparse;
//! - `settings`: [`Algorithm`], [`UzawaSettings`], [`UzawaReport`], [`Solution`];
//!   `residual`: the natural map, norms, statuses, and [`stall`]: the stall detector (the
//!   toolbox every algorithm uses);
//! - one file per algorithm: `uzawa`, `gauss_seidel` (the base sweeps, on the shared `sweep`
//!   state), `plain` (their stopping loop), [`anderson`], [`newton`], [`classic`], and
//!   [`matrix_free`] (the sweep on an operator instead of a matrix) and
//!   [`matrix_free_anderson`] (the same with Anderson mixing, fewer products);
//! - `solver`: the dispatcher [`UzawaSolver`] (validates, runs the chosen algorithm, reports);
//! - [`adhesion`]: the adhesive springs condensed on `W` and the β fixed point around a solve.
//!
//! # 2D and 3D
//! A problem's [`ReducedProblem::dimension`] is 2 (per contact `(n, t)`) or 3 (`(n, t₁, t₂)`,
//! FCLIB's order). Every algorithm is generic over the tangent dimension `DT` (1 or 2) and the
//! dispatcher picks the instance once per solve, so the per-contact work stays on fixed-size
//! arrays in both.
//!
//! # Dense or sparse `W`
//! `W` is stored dense (row-major, [`ReducedProblem::new`]) or in compressed sparse rows
//! ([`ReducedProblem::from_triplets`], JSON triplets, sparse FCLIB files), for the Delassus
//! matrices of multibody codes (a few `d × d` blocks per block row: 3D, 7000 contacts is
//! 3.5 GB dense, 4 MB sparse). The sparse pattern is the block pattern, made symmetric
//! ([`CsrMatrix`]), so the `d` rows of a contact share one column list. Every algorithm reaches
//! `W` only through `delassus` (`dot_row`, `axpy_row`, `axpy_rows2/3`, `mul_into`,
//! `diagonal_block`), which matches the storage once per row: the dense loops are the zipped
//! slices they were, a sparse sweep costs `O(stored entries)`, and both storages of the same
//! `W` give the same bits (`tests/integration/sparse.rs`). Nothing densifies a sparse `W`: Newton
//! assembles its reduced system on the block pattern and factorises it with faer's sparse LU
//! ([`newton`]).
//!
//! Imports go one way: `csr` → `delassus` → `problem`; `stall` → `residual`/`settings` → the sweeps → `plain`/`anderson`/`newton`/
//! `classic` → `solver` → `adhesion`.
//!
//! # The iteration
//!
//! ```text
//! prediction (5.26a):  τ_i = r_i + ρ_i v_i(x),   v_i = law_i.modified_velocity(x_i)
//! correction (5.26b):  r_i ← law_i.project(τ_i)
//! ```
//! Six algorithms are offered ([`Algorithm`]), all stopping on the rule below. Two are the
//! plain bipotential sweeps:
//! - [`Algorithm::Uzawa`]: all contacts from the same `x` (a projected-gradient / Jacobi
//!   step), then `x = W r + q` once per iteration — the seed's algorithm, kept as the
//!   reference;
//! - [`Algorithm::GaussSeidel`]: contact by contact, each using the current `x`, which is
//!   updated right after with the columns of `W` that the contact touches (two in 2D, three
//!   in 3D) (De Saxcé–Feng's
//!   projected Gauss–Seidel). On seeded random SPD problems
//!   ([`generate::random_problem`], `n_c` = 10/100/300,
//!   release build) it takes 57–60 sweeps against 79–101 for Uzawa and is 1.5–9× faster
//!   (n_c = 300: 2.6 ms against 23 ms), because a sweep costs one pass over `W` while an
//!   Uzawa step costs one product `W r` per trial, and a few trials are redone.
//!
//! Two accelerate them ([`anderson`]): [`Algorithm::AndersonGaussSeidel`] —
//! **the default** — and [`Algorithm::AndersonUzawa`], safeguarded Anderson mixing of the last
//! 5 iterates of the sweep. [`Algorithm::Newton`] ([`newton`]) is a semi-smooth
//! Newton method on the same projection equation, for Coulomb-type laws. And
//! [`Algorithm::ClassicRccm`] is the classical solver the seed compares the bipotential with
//! (GYPTIS, seed §5.6): Signorini and friction solved separately, with a fixed point on the
//! friction threshold ([`classic`]).
//!
//! # Which algorithm
//! Measured by `examples/work_precision_local.rs` (`docs/benchmarks.md`, "Local solver:
//! work–precision"): time to reach a residual of 1e-10 on random problems (`n_c` = 10 to 5000)
//! and on FE reduced problems of the Hertz scene (21 and 141 contacts, frictionless and with
//! partial slip).
//! - Newton is the fastest on every FE problem (5–8× faster than Gauss–Seidel) and on random
//!   problems up to `n_c` ≈ 1000, but its dense factorisation grows as `n_c³` (at `n_c` = 5000
//!   it is 4–5× slower than the accelerated sweep) and it needs
//!   [`ContactLaw::friction_coefficient`](contact_laws::ContactLaw::friction_coefficient).
//! - The accelerated Gauss–Seidel sweep is 1.1–3× faster than Gauss–Seidel on every problem,
//!   needs nothing but `project` and `modified_velocity` (any law), and converges where
//!   Gauss–Seidel does not in 10 000 sweeps (issue 8's stress suite: a stiffness contrast of
//!   1e8, 40 sweeps). It is the default; choose Newton for Coulomb-type problems up to about a
//!   thousand contacts.
//! - [`Algorithm::Auto`] applies a rule per problem, re-measured on 2D and 3D problems of
//!   every kind with `W` dense and sparse (`examples/auto_rule.rs`, `docs/benchmarks.md`
//!   "Which algorithm, measured"): for Coulomb-type laws, Newton on a dense `W` with
//!   `n_c ≤` `AUTO_NEWTON_MAX_CONTACTS` (1000) — 2–3× faster than the sweep on FE problems,
//!   even with it on the 3D half-space and the sphere piles — and on a sparse `W` whose contact
//!   graph fills a factorisation by at most `AUTO_NEWTON_MAX_FILL` (10; geometric graphs:
//!   piles fill 3–5 and Newton is 1.3–1.9× faster) up to
//!   `AUTO_SPARSE_NEWTON_MAX_CONTACTS`; else the accelerated Gauss–Seidel sweep (random
//!   sparse couplings fill 27–87 and Newton is 3–20× slower). A dense `W` whose off-diagonal
//!   blocks are mostly exactly zero (`AUTO_MULTIBODY_ZERO_BLOCKS`: a multibody Delassus
//!   operator, never a condensed FE flexibility) gets the sweep too, and a Newton chosen by
//!   the rule hands over to the sweep on its second short Armijo step after the first
//!   (`AUTO_NEWTON_SHORT_STEP` = 2⁻⁵) or after `AUTO_NEWTON_BUDGET` (100) iterations (issue
//!   37: on semidefinite multibody stacks the Newton crept for thousands of iterations with
//!   steps `t ≤ 2⁻⁶` where the sweep converges in hundreds, while every converging run takes
//!   steps `t ≥ 2⁻⁴`; `docs/benchmarks.md` "Auto on multibody problems"). On a sparse `W`
//!   kept non-symmetric it runs instead until its residual stops halving over
//!   `AUTO_NEWTON_PROGRESS_WINDOW` (20) iterations, stops at the first residual `≤ tol`, and
//!   hands its iterate to the plain sweep (issue 37, Siconos' capsules: `newton/probe.rs`).
//!   On a dense `W` where the rule picks Newton and at least half the contacts are pressed
//!   (`AUTO_SWEEP_MIN_PRESSED`), `Auto` sweeps first (issue 37): 8 accelerated
//!   sweeps (`AUTO_SWEEP_PROBE`), and when their rate over the last four promises the tolerance
//!   within `AUTO_SWEEP_PREDICTED` (40) sweeps the sweep goes on from there and Newton never
//!   runs (random dense problems, well conditioned: 21–26 sweeps, where Newton was 1.7–3.5×
//!   slower); else Newton runs from the start as without the probe (FE problems: 54–74 sweeps,
//!   Newton 2–3× faster), the probe's sweeps its only cost. One contact with a friction
//!   coefficient is solved exactly by its case, with no iteration (`one_contact`: open, stick
//!   or slip, the 3D slip direction a root of a trigonometric quadratic; issue 37: Siconos'
//!   one-contact problems, where the set-up of an iteration was most of the time and a block
//!   `diag(1e4, 1, 1e-4)` cost the sweeps 272 iterations), the answer checked like an
//!   iterated one (else `Auto` iterates as before). In 2D `Auto`'s Gauss–Seidel sweeps solve
//!   each contact exactly ([`ContactSolve::Exact`], `exact_2d`; issue 37, ninth part: 99
//!   sweeps where the projected step takes 1 276 on Siconos' granular problems), and on a
//!   sparse 2D `W` that sweep runs in place of Newton (`solver/auto/sweep_2d.rs`).
//!   It is the default of `bipo solve-local`; the simulation's default stays the
//!   accelerated sweep, whose iteration counts the seed's tables and `docs/benchmarks.md`
//!   quote.
//!
//! # The penalty ρ
//! The base value is `ρ⁰_i = 1/λ_max(W_ii)`, where `W_ii` is contact `i`'s diagonal block
//! (2×2, or 3×3 in 3D, whose largest eigenvalue is computed in closed form):
//! the largest step for which the local map `r_i ↦ r_i − ρ W_ii r_i` is non-expansive, i.e. the
//! local step never overshoots, whatever the block's anisotropy (`1/W_nn` can exceed it when
//! `W_tt > W_nn`). The user may scale it by [`UzawaTuning::rho_scale`]. It is then adapted
//! (Khobotov 1987, Solodov–Tseng 1996): after a trial step `r → r'`,
//!
//! ```text
//! ratio = ‖ρ (v(x(r')) − v(x(r)))‖ / ‖r' − r‖
//! ratio > ν = 1.5   → ρ ← ρ/2 and redo the step
//! ratio < 0.3       → ρ ← 1.5 ρ for the next step
//! ```
//! We use `ν = 1.5` rather than the extragradient's `ν < 1`: this is a plain projected
//! step, which for the associated (frictionless) part converges for `ρ L < 2`; and with
//! `ν < 1` the exact local step `ρ = 1/λ` of an isotropic block (ratio exactly 1) would be
//! rejected. Measured on the random problems, `ν = 0.9` costs Gauss–Seidel 89–96 sweeps
//! against 57–60 with `ν = 1.5` (Uzawa: 83–103 against 79–101).
//!
//! `ρ⁰ = 1/W_nn` was measured too: within ±15 % of the sweeps of `1/λ_max` on these nearly
//! isotropic blocks; `1/λ_max` is kept because it stays safe on anisotropic ones.
//! For Uzawa the norms are global and one factor scales every `ρ_i`; for Gauss–Seidel each
//! contact adapts its own `ρ_i` with its local step (`x_i` changes by `W_ii Δr_i`). So a `ρ`
//! that is `10³` times too large or too small still converges.
//!
//! # Stopping rule
//! Both must hold at the same iterate (so the rule does not depend on the adapted ρ):
//!
//! ```text
//! change   = ‖r_{k+1} − r_k‖ / max(‖r_{k+1}‖, tiny)                          ≤ tol
//! residual = ‖r − P_K(r + ρ⁰ v(W r + q))‖ / max(‖r‖, max_i ρ⁰_i ‖q‖, tiny)   ≤ tol
//! ```
//! with `ρ⁰` the *base* penalty (not the adapted one, nor the user's scale) and
//! `tiny = f64::MIN_POSITIVE`. The residual is the natural map of the fixed point (zero
//! exactly on solutions); [`UzawaReport::history`] records it at every iteration.
//! Where the change does not vanish (a rank-deficient `W`: the solutions form a set, and the
//! iteration may move along it), the residual alone stops a run after a long streak `≤ tol`
//! (as long as the run before it, at least 100 iterations), and a run that ends at
//! `max_iterations` or stalled with a residual `≤ tol` on the exact `x` is converged (issue 37;
//! `residual_stop`). A run that fails leaves its best iterate in the error
//! ([`SolverError::best_iterate`](crate::SolverError::best_iterate)). How this residual
//! compares with Siconos' error: [`siconos_error`].

//!
//! # Problems as other codes export them
//! Before and after the chosen algorithm, the dispatcher ([`UzawaSolver`]) handles what a
//! problem from another code may bring (`tests/integration/real_world_inputs.rs`):
//! - **Round-off asymmetry.** [`ReducedProblem::new`] symmetrises `W` when
//!   `max|W_ij − W_ji| / max|W|` is between `SYMMETRY_TOL` (1e-12) and
//!   `DEFAULT_ASYMMETRY_TOL` (1e-6, or [`ReducedProblem::with_asymmetry_tolerance`]) and
//!   reports it ([`UzawaReport::asymmetry`]); beyond, a typed error gives the entry and the
//!   difference.
//! - **Asymmetry of the model.** With [`Asymmetry::Keep`]
//!   ([`ReducedProblem::with_asymmetry`], the FCLIB reader) a non-symmetric `W` is solved as
//!   given: the Gauss–Seidel sweeps (and Anderson on them), the classical split and Newton
//!   read its columns from a stored `Wᵀ`; the Uzawa variants refuse it
//!   ([`SolverError::NeedsSymmetricW`](crate::SolverError::NeedsSymmetricW)); the answer is
//!   checked by the natural residual recomputed from `x = W r + q` (see [`Asymmetry`]).
//! - **Every gap open.** With `r = 0` as the start and every `q_n ≥ 0` (Coulomb-type laws; for
//!   other laws, a natural residual of exactly 0 at `r = 0`), `r = 0` is the exact answer:
//!   returned with no iteration.
//! - **Contacts that stay open.** No bound is computed to take them out of the sweeps,
//!   because they already cost almost nothing there: a contact whose projection leaves
//!   `r_i = 0` unchanged touches no row of `W` (the Gauss–Seidel update is skipped when
//!   `Δr_i = 0`, and `W r` skips zero entries of `r`), so an open contact costs one projection
//!   of `d` numbers per sweep, against `O(stored entries of its row)` for a closed one; and
//!   Newton gives it no unknown (its equation is the known step `Δr_i = −F_i`).
//! - **Extreme magnitudes.** `W` or `q` with entries beyond `1e±100` (`RESCALE_ABOVE`) are
//!   solved on a copy scaled by powers of two (exact), when every law is
//!   [scale invariant](contact_laws::ContactLaw::is_scale_invariant) (the built-in laws are);
//!   for other laws, magnitudes beyond `1e±150` (where squares overflow) are refused with a
//!   typed error. [`UzawaReport::rescaled`] says when it happened.
//! - **A converged answer is checked.** For Coulomb-type laws the Signorini–Coulomb
//!   conditions are checked without the modified velocity (`r_n − max(0, r_n − ρ⁰ x_n)`,
//!   `r_t − clamp(r_t − ρ⁰ x_t, ±μ̄ r_n)`, relative like the residual) to `CHECK_FACTOR`
//!   × `tol`: with a huge `μ̄` the sum `x_n + μ̄|x_t|` can absorb a penetration and the
//!   bipotential residual reads 0 on a wrong answer (`μ = 1e100` did).
//! - **Fallback.** When the algorithm does not converge (it stalls, or reaches
//!   `max_iterations`) or fails the check, [`UzawaSettings::fallback`] (on by default) solves
//!   again with
//!   [`Algorithm::ClassicRccm`], which splits contact and friction and does not see
//!   `μ̄|x_t|`: one contact that sticks with `μ` from 100 to 1e100 is solved by every
//!   algorithm this way. Newton falls back first to the accelerated sweep (it solves what
//!   Newton solves without a Jacobian, e.g. where Newton's steps stay tiny at a kink of the
//!   projection), then to the classical split. [`UzawaReport::fallback_from`] names the algorithm that failed;
//!   the error, when all fail, carries every history.
//! - **Stalls** (issue 14: a positive semidefinite, rank-deficient `W` whose `q` admits no
//!   solution, or an algorithm that cannot solve the problem). The [`stall`] detector, shared
//!   by every algorithm loop, stops a run whose residual has not halved over the last
//!   `max(`[`UzawaTuning::stall_window`]`, k/2)` of its `k` iterations, so the fallback starts
//!   after a few windows instead of after `max_iterations`, and the error is
//!   [`SolverError::Stalled`](crate::SolverError::Stalled) (the residual it stalled at, the
//!   best one, the iterations, the history); with `accept_non_converged`,
//!   [`UzawaReport::stalled`] says so. The default window is far above the longest plateau of
//!   any converging run measured, so no converging run changes by one iteration.

pub mod adhesion;
pub mod anderson;
mod asymmetry;
pub mod classic;
mod csr;
mod delassus;
mod dense;
mod exact_2d;
#[cfg(feature = "fclib")]
pub mod fclib;
mod friction;
mod gauss_seidel;
pub mod generate;
#[cfg(feature = "serde")]
mod json;
pub mod matrix_free;
pub mod matrix_free_anderson;
pub mod newton;
mod one_contact;
mod plain;
pub mod problem;
mod residual;
mod residual_stop;
mod settings;
pub mod siconos_dat;
mod solver;
pub mod stall;
mod sweep;
mod uzawa;

pub use asymmetry::Asymmetry;
pub use csr::CsrMatrix;
pub use delassus::WView;
#[cfg(feature = "fe")]
pub(crate) use dense::symmetrize;
pub use problem::ReducedProblem;
pub use residual::siconos_error;
#[cfg(feature = "fe")]
pub(crate) use residual::{contact_statuses, natural_residual, norm};
pub use settings::{Algorithm, ContactSolve, Solution, UzawaReport, UzawaSettings, UzawaTuning};
pub use solver::{UzawaSolver, solve_coulomb};
