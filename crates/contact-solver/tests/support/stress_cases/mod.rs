//! The cases of the numerical-stability stress suite (issue 8, "Numerical stability under
//! stress"), shared by `tests/integration/stress.rs` (which asserts them) and
//! `examples/stress_table.rs` (which prints the table of `docs/validation.md`).
//!
//! Every case builds a small scene, steps it, and returns a [`Record`]: steps, solver sweeps,
//! adhesion iterations, the largest final residual of its steps and an [`Outcome`]. A case is
//! *converged* only if every step met the solver tolerance **and** the answer passed the
//! physics checks of the case (analytic values where there are some, equilibrium, gaps
//! `≥ −tol`, reactions in the cone, the RCCM update of β); a *typed error* is a
//! [`SolverError`] the case declares acceptable (e.g. the adhesion fixed point on a
//! snap-back); anything else is *wrong*.
//!
//! Groups (sketches with each builder):
//! - `contrast`: two stacked blocks with `E_up/E_low ∈ {1, 1e4, 1e8, 1e-8}`, node pairs and
//!   node-to-segment; a steel pile in soft soil (contrast 1e4 to 1e8);
//! - `rccm_c`: an RCCM-glued block, `C_n, C_t ∈ [1e-3, 1e12]`: pulled normally (peak
//!   `√(w C_n)`), pulled at an angle with `C_n ≠ C_t`, pressed then sheared (`r̄ ≠ 0`), and the
//!   recorded opening of one elastic step against `E d/(E + C h)`;
//! - `friction`: a block pressed then pushed a little (stick) or a lot (slip),
//!   `μ ∈ {0, 1e-8, 0.2, 1, 10}`, against the all-stick solution or `T = −μ N`;
//! - `rho`: the same block, `rho_scale ∈ [1e-3, 1e3]`, Gauss–Seidel and Uzawa;
//! - `load_steps`: a hanging block under a body force, steps from `1e-9` of the load to all
//!   of it at once (the solution is homogeneous of degree 1 in the load);
//! - `alpha`: the glued block with `α ∈ [0, 1e6]`, and `α → 0` against `α = 0`;
//! - `poisson`: P2 with `ν` up to 0.499 (pressed block, Hertz);
//! - `geometry`: nodes exactly on the obstacle, just beyond the alert distance (re-added when
//!   they end up penetrating), and on an ARC's endpoint.
#![allow(dead_code)] // the test and the example each take what they need

use super::hertz_scene::HertzScene;
use contact_laws::{BetaScheme, ContactLaw, Coulomb, LocalVec2, Rccm, RccmParams, Signorini};
use contact_solver::{
    Algorithm, ArcSide, ContactSimulation, ContactZone, InterfaceStatus, RigidArc, RigidLine,
    SimulationSettings, SolverError, StepResult,
};
use fem_core::generate::{PILE, PileSpec, RectangleSpec, SOIL, pile_in_soil, rectangle};
use fem_core::{
    Component, ElementKind, FemError, Idealization, LinearElasticModel, Material, Mesh, Structure,
    Supports,
};
use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt;
use std::time::{Duration, Instant};

// ---------------------------------------------------------------------------------------------
// Records

/// How a case ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// Every step converged to the tolerance and the physics checks passed.
    Converged,
    /// A typed error the case declares acceptable (its `Display`).
    TypedError(String),
    /// A wrong answer, a NaN, an unexpected error or a failed check.
    Wrong(String),
    /// The case panicked (only caught by the example).
    Panic(String),
}

/// One row of the table.
#[derive(Clone, Debug)]
pub struct Record {
    /// Group (`contrast`, `rccm_c`, …).
    pub group: &'static str,
    /// The case's parameters.
    pub case: String,
    /// Steps done (up to the error, if any).
    pub steps: usize,
    /// Solver sweeps summed over the steps.
    pub iterations: usize,
    /// Adhesion fixed-point iterations summed over the steps.
    pub adhesion_iterations: usize,
    /// Largest final (relative natural-map) residual over the steps.
    pub residual: f64,
    /// What the checks measured (the key numbers).
    pub note: String,
    /// How it ended.
    pub outcome: Outcome,
    /// Wall time.
    pub time: Duration,
}

impl Record {
    /// Converged, or a typed error.
    pub fn ok(&self) -> bool {
        matches!(self.outcome, Outcome::Converged | Outcome::TypedError(_))
    }

    /// The outcome as a short table cell.
    pub fn outcome_cell(&self) -> String {
        match &self.outcome {
            Outcome::Converged => "converged".into(),
            Outcome::TypedError(e) => format!("typed error: {e}"),
            Outcome::Wrong(e) => format!("**WRONG**: {e}"),
            Outcome::Panic(e) => format!("**PANIC**: {e}"),
        }
    }
}

impl fmt::Display for Record {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "[{}] {}: {} steps, {} sweeps, {} adhesion it., residual {:.1e}; {}; {}",
            self.group,
            self.case,
            self.steps,
            self.iterations,
            self.adhesion_iterations,
            self.residual,
            self.note,
            self.outcome_cell()
        )
    }
}

/// Why a case body stopped.
#[derive(Debug)]
pub enum Fail {
    /// The solver (or the structure) returned an error.
    Error(SolverError),
    /// A check failed.
    Wrong(String),
}

impl From<SolverError> for Fail {
    fn from(e: SolverError) -> Self {
        Self::Error(e)
    }
}

impl From<FemError> for Fail {
    fn from(e: FemError) -> Self {
        Self::Error(SolverError::Structure(e))
    }
}

impl From<contact_laws::LawError> for Fail {
    fn from(e: contact_laws::LawError) -> Self {
        Self::Error(SolverError::Law(e))
    }
}

/// `Err(Fail::Wrong(..))` unless `cond`. Conditions are written as what must hold
/// (`a <= tol`), so a NaN fails them.
macro_rules! ensure {
    ($cond:expr, $($arg:tt)+) => {
        let holds: bool = $cond;
        if !holds {
            return Err(Fail::Wrong(format!($($arg)+)));
        }
    };
}

/// The counters of a case, filled step by step.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    /// Steps.
    pub steps: usize,
    /// Sweeps.
    pub iterations: usize,
    /// Adhesion iterations.
    pub adhesion_iterations: usize,
    /// Largest final residual.
    pub residual: f64,
    /// Largest number of detection passes in a step.
    pub passes: usize,
}

impl Tally {
    /// Records a step and checks that it converged to `tol` and that every number is finite.
    fn add(&mut self, res: &StepResult, tol: f64) -> Result<(), Fail> {
        self.steps += 1;
        self.iterations += res.report.contact_iterations;
        self.adhesion_iterations += res.report.adhesion_iterations;
        self.residual = self.residual.max(res.report.residual);
        self.passes = self.passes.max(res.report.detection_passes);
        ensure!(
            res.report.converged && res.report.residual <= tol,
            "step {}: converged = {}, residual {:e} > tol {tol:e}",
            res.report.step,
            res.report.converged,
            res.report.residual
        );
        for c in &res.contacts {
            let values = [
                c.gap,
                c.u_t,
                c.slip_increment,
                c.beta,
                c.r.n,
                c.r.t[0],
                c.r_bar.n,
                c.r_bar.t[0],
                c.r_adh.n,
                c.r_adh.t[0],
            ];
            ensure!(
                values.iter().all(|v| v.is_finite()),
                "step {}: node {} has a non-finite value: {c:?}",
                res.report.step,
                c.node
            );
        }
        Ok(())
    }
}

/// A case to run: its group, name, and body.
pub struct Case {
    /// Group.
    pub group: &'static str,
    /// Parameters.
    pub name: String,
    /// `Some(reason)` for a known bug: the group test skips it, an ignored test runs it.
    pub bug: Option<&'static str>,
    run: Box<dyn Fn() -> Record + Send>,
}

impl Case {
    fn new(
        group: &'static str,
        name: impl Into<String>,
        allowed: Allowed,
        body: impl Fn(&mut Tally) -> Result<String, Fail> + Send + 'static,
    ) -> Self {
        let name = name.into();
        let case = name.clone();
        Self {
            group,
            name,
            bug: None,
            run: Box::new(move || {
                let start = Instant::now();
                let mut tally = Tally::default();
                let result = body(&mut tally);
                if let Err(Fail::Error(SolverError::NotConverged {
                    iterations,
                    residual,
                    ..
                })) = &result
                {
                    tally.iterations += iterations;
                    tally.residual = tally.residual.max(*residual);
                }
                let (note, outcome) = match result {
                    Ok(note) => (note, Outcome::Converged),
                    Err(Fail::Error(e)) if allowed(&e) => {
                        (String::new(), Outcome::TypedError(short_error(&e)))
                    }
                    Err(Fail::Error(e)) => (
                        String::new(),
                        Outcome::Wrong(format!("unexpected error: {}", short_error(&e))),
                    ),
                    Err(Fail::Wrong(msg)) => (String::new(), Outcome::Wrong(msg)),
                };
                Record {
                    group,
                    case: case.clone(),
                    steps: tally.steps,
                    iterations: tally.iterations,
                    adhesion_iterations: tally.adhesion_iterations,
                    residual: tally.residual,
                    note,
                    outcome,
                    time: start.elapsed(),
                }
            }),
        }
    }

    fn bug(mut self, reason: &'static str) -> Self {
        self.bug = Some(reason);
        self
    }

    /// Runs the case.
    pub fn run(&self) -> Record {
        (self.run)()
    }
}

/// The error's message without its (long) history.
fn short_error(e: &SolverError) -> String {
    match e {
        SolverError::NotConverged {
            iterations,
            residual,
            ..
        } => format!("NotConverged {{ iterations: {iterations}, residual: {residual:.1e} }}"),
        SolverError::Stalled {
            iterations,
            residual,
            ..
        } => format!("Stalled {{ iterations: {iterations}, residual: {residual:.1e} }}"),
        SolverError::AdhesionNotConverged {
            iterations, change, ..
        } => format!("AdhesionNotConverged {{ iterations: {iterations}, change: {change:.1e} }}"),
        other => other.to_string(),
    }
}

/// The known bug of the stiff contactor on soft segments (see `docs/validation.md`).
pub const STIFF_CONTACTOR_BUG: &str = "bug: NotConverged although the natural-map residual \
     stays below tol (6.7e-11): r drifts along the near-null space of W (stiff contactor on soft \
     segments, contrast 1e8), so the relative-change test never passes";

/// Which errors a case accepts as its typed outcome.
type Allowed = fn(&SolverError) -> bool;

fn no_error(_: &SolverError) -> bool {
    false
}

/// Every case, group by group.
pub fn all_cases() -> Vec<Case> {
    let mut v = Vec::new();
    v.extend(contrast_cases());
    v.extend(rccm_c_cases());
    v.extend(friction_cases());
    v.extend(rho_cases());
    v.extend(load_step_cases());
    v.extend(alpha_cases());
    v.extend(poisson_cases());
    v.extend(geometry_cases());
    v
}

// ---------------------------------------------------------------------------------------------
// Shared checks

/// The tolerance every case asks of the solver (the default).
pub const TOL: f64 = 1e-10;

thread_local! {
    /// Whether the cases run on this thread force the primal active-set path
    /// (`tests/integration/stress_active_set.rs`). Per thread, not per process: the stress
    /// tests with the default path (`stress.rs`) run in the same test binary, each test on a
    /// thread of its own.
    static ACTIVE_SET: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Makes every case run afterwards on the calling thread (a test's own thread) solve its steps
/// with `FlexibilityMode::ActiveSet` instead of the default (a dense `F*` at these sizes).
#[allow(dead_code)]
pub fn force_active_set() {
    ACTIVE_SET.with(|a| a.set(true));
}

fn settings() -> SimulationSettings {
    let mut s = SimulationSettings::default();
    s.solver.tol = TOL;
    if ACTIVE_SET.with(|a| a.get()) {
        s.flexibility = contact_solver::FlexibilityMode::ActiveSet;
    }
    s
}

fn rect(x: [f64; 2], y: [f64; 2], nx: usize, ny: usize, kind: ElementKind) -> Mesh {
    let mut spec = RectangleSpec::new(x, y, nx, ny);
    spec.kind = kind;
    rectangle(&spec).expect("valid rectangle")
}

fn set(mesh: &Mesh, name: &str) -> Vec<usize> {
    mesh.node_set(name).expect("named set").to_vec()
}

/// Checks Signorini–Coulomb on every candidate of a non-adhesive step: gaps `≥ −tol_gap`
/// (inactive candidates included), `r_n ≥ −tol_r`, complementarity, `|r_t| ≤ μ r_n`, and on a
/// slipping contact `|r_t| = μ r_n` with `r_t` opposing the slip. `mu(zone)` gives μ.
fn check_coulomb(
    res: &StepResult,
    mu: impl Fn(usize) -> f64,
    tol_r: f64,
    tol_gap: f64,
) -> Result<(), Fail> {
    let k = res.report.step;
    for c in &res.contacts {
        let m = mu(c.zone);
        // the residual controls x_n through De Saxcé's x_n + μ|x_t| and, on a sliding contact,
        // through the cone's generatrix (a factor 1/√(1 + μ²)): the gap is known ~μ² times less
        // well (μ = 10, residual 1e-10: gaps to 1.1e-10 = 1.1e-8 δ)
        let tol_gap = tol_gap * (1.0 + m) * (1.0 + m);
        let (rn, rt) = (c.r.n, c.r.t[0]);
        ensure!(
            c.gap >= -tol_gap,
            "step {k}: node {} penetrates: gap {:e}",
            c.node,
            c.gap
        );
        ensure!(
            rn >= -tol_r,
            "step {k}: node {} in tension: r_n {rn:e}",
            c.node
        );
        ensure!(
            rn <= tol_r || c.gap.abs() <= tol_gap,
            "step {k}: node {} pressed (r_n {rn:e}) but open (gap {:e})",
            c.node,
            c.gap
        );
        ensure!(
            rt.abs() <= m * rn.max(0.0) * (1.0 + 1e-12) + tol_r,
            "step {k}: node {} outside the cone: |r_t| {:e} > μ r_n {:e}",
            c.node,
            rt.abs(),
            m * rn
        );
        if rn > tol_r && c.slip_increment.abs() > tol_gap {
            ensure!(
                rt.abs() >= m * rn - tol_r && rt * c.slip_increment <= tol_r * tol_gap,
                "step {k}: node {} slips by {:e} with r_t {rt:e} (μ r_n {:e})",
                c.node,
                c.slip_increment,
                m * rn
            );
        }
        if c.status == InterfaceStatus::Inactive {
            ensure!(
                c.r == LocalVec2::zeros(),
                "step {k}: inactive node {} carries {:?}",
                c.node,
                c.r
            );
        }
    }
    Ok(())
}

/// `Σ R + Σ (contact forces on free dofs)`, by component: zero for a body without external
/// loads, up to the round-off of the solves. Contact forces are `r_n n + r_t t` on the
/// contactor and `−w_k` times that on target nodes.
fn equilibrium_sum(
    sim: &ContactSimulation<LinearElasticModel, impl ContactLaw + Clone>,
    res: &StepResult,
    load_factor: f64,
) -> Result<[f64; 2], Fail> {
    let model = sim.structure();
    let mut sum = [0.0; 2];
    for ((_, c), r) in model.reactions(&sim.nodal_displacements(), load_factor)? {
        sum[c as usize] += r;
    }
    for (cand, rec) in sim.candidates().iter().zip(&res.contacts) {
        let f = [
            rec.r.n * cand.normal()[0] + rec.r.t[0] * cand.tangent()[0],
            rec.r.n * cand.normal()[1] + rec.r.t[0] * cand.tangent()[1],
        ];
        let mut add = |node: usize, w: f64| {
            for (c, d) in model.node_dofs(node).into_iter().enumerate() {
                if d.is_some() {
                    sum[c] += w * f[c];
                }
            }
        };
        add(cand.node, 1.0);
        for &(node, w) in cand.targets.iter().flatten() {
            add(node, -w);
        }
    }
    Ok(sum)
}

fn totals(res: &StepResult) -> (f64, f64) {
    res.contacts
        .iter()
        .fold((0.0, 0.0), |(n, t), c| (n + c.r.n, t + c.r.t[0]))
}

fn max_abs_r(res: &StepResult) -> f64 {
    res.contacts
        .iter()
        .map(|c| c.r.n.abs().max(c.r.t[0].abs()))
        .fold(0.0, f64::max)
}

// ---------------------------------------------------------------------------------------------
// Stiffness contrast

// The groups (declared after `ensure!`, which they use).
mod contrast;
mod friction;
mod geometry;
mod glue;

pub use contrast::*;
pub use friction::*;
pub use geometry::*;
pub use glue::*;
