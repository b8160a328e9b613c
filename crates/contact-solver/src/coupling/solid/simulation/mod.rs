//! [`SolidContactSimulation`]: quasi-static contact of a 3D [`Structure<3>`] with rigid
//! obstacles and between bodies (node pairs, node-to-face), condensed on the contact unknowns
//! (`F* = H K⁻¹ Hᵀ`, dense) and solved with the local layer in 3D, one load step at a time.
//!
//! A step: the free response `u_free`; the active set (relative gap under `u_free` within the
//! zone's alert distance, in contact at the end of the last step, or adhesive, β > 0); `F*` on
//! it (rebuilt when the active set or the stiffness changes); the reduced problem
//! `x = F* r + q` with `q = (g₀ + n·u_rel, t₁·u_rel − u_t1,start, t₂·u_rel − u_t2,start)` per
//! contact (`u_rel` under `u_free`), solved by [`UzawaSolver`] (the same algorithms as in 2D,
//! `Auto` by default) or, when a law is adhesive, by the adhesion fixed point
//! [`solve_adhesive`] in 3D (the RCCM springs `β² C` on the normal and both tangential jumps,
//! condensed exactly); then `u = u_free + K⁻¹ Hᵀ r` and the penetration check of the inactive
//! candidates (added and solved again if one penetrates).
//!
//! Past `Auto`'s dense limit (or when asked), a step without adhesion is solved without `F*`:
//! by the primal active set on the factorised stiffness when every active contact faces a rigid
//! obstacle ([`crate::coupling::primal`]), matrix-free otherwise.
//!
//! What 3D does not have yet, refused with [`SolverError::Unsupported`] rather than answered
//! wrongly: floating structures.

use super::zone::{Candidate3, ContactZone3, recognize_3d};
use crate::coupling::flexibility::{Previous, build_dense};
use crate::coupling::force_factor::ForceFactorCheck;
use crate::coupling::primal::{LocalFrame, PrimalCache};
use crate::coupling::simulation::FlexibilityMode;
use crate::error::SolverError;
use crate::local::adhesion::{AdhesiveStep, WarmStartPacing, solve_adhesive};
use crate::local::{ReducedProblem, UzawaSolver};
use contact_laws::{ContactLaw, LocalVec};
use fem_core::Structure;

mod active_set;
mod matrix_free;
mod report;

pub use report::{DEFAULT_DENSE_LIMIT_3D, SolidContactRecord, SolidSettings, SolidStepResult};

/// A quasi-static 3D contact simulation (module docs).
///
/// # Examples
/// A P2 block pressed on a rigid floor with friction: the force is uniform and no contact
/// slips.
/// ```
/// use contact_laws::Coulomb;
/// use contact_solver::coupling::solid::{ContactZone3, RigidPlane, SolidContactSimulation, SolidSettings};
/// use fem_core::solid::{SolidKind, SolidModel, generate::{box_mesh, lines}};
/// use fem_core::{Component, Material, Supports};
///
/// let mesh = box_mesh(&lines(0.0, 1.0, 2), &lines(0.0, 1.0, 2), &lines(0.0, 0.5, 1), SolidKind::Tet10)?;
/// let top = mesh.node_set("z1")?.to_vec();
/// let mut s = Supports::new();
/// s.prescribe(&top, Component::Z, -1e-3)?.fix(&top, Component::X).fix(&top, Component::Y);
/// let (nodes, areas) = mesh.nodal_areas("z0")?;
/// let model = SolidModel::new(mesh, &[(0, Material::new(1000.0, 0.0, 0.0)?)], s)?;
/// let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0])?;
/// let zone = ContactZone3::rigid("base", nodes, floor, Coulomb::new(0.3)?, 0.1).with_areas(areas);
/// let mut sim = SolidContactSimulation::new(model, vec![zone], SolidSettings::default())?;
/// let res = sim.step(1.0, 1.0)?;
/// let total: f64 = res.contacts.iter().map(|c| c.r[0]).sum();
/// assert!((total - 2.0).abs() < 1e-8); // σ = E δ / H = 2 on a unit area (ν = 0)
/// assert!(res.contacts.iter().all(|c| c.slip[0].abs() < 1e-12 && c.slip[1].abs() < 1e-12));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct SolidContactSimulation<S: Structure<3>, L: ContactLaw> {
    structure: S,
    zones: Vec<ContactZone3<L>>,
    settings: SolidSettings,
    candidates: Vec<Candidate3>,
    /// `H` rows (n, t1, t2 per candidate) on free dofs.
    h_rows: Vec<Vec<(usize, f64)>>,
    states: Vec<L::State>,
    /// Accepted local displacement `(x_n, u_t1, u_t2)` at the end of the last step.
    jumps: Vec<[f64; 3]>,
    /// Last total reactions ("was in contact").
    r_last: Vec<[f64; 3]>,
    /// Last reactions of the laws, `r̄` (warm start).
    r_bar_last: Vec<[f64; 3]>,
    w_active: Vec<usize>,
    w: Vec<f64>,
    w_version: Option<u64>,
    warm: WarmStartPacing,
    u: Vec<f64>,
    /// Nodal displacements at the end of the last step (numbering-free).
    nodal_u: Vec<[f64; 3]>,
    /// Stiffness version the rows of `H` were numbered for.
    rows_version: u64,
    time: f64,
    steps: usize,
    solver: UzawaSolver,
    scale: f64,
    /// The active-set path's symbolic analysis and factorisation, kept between steps.
    primal: PrimalCache,
    /// The check of `step`'s force factor (until the structure shows applied forces).
    force_check: ForceFactorCheck,
}

impl<S: Structure<3>, L: ContactLaw + Clone> SolidContactSimulation<S, L> {
    /// Recognises the candidates of `zones` on `structure` and starts at time 0.
    ///
    /// # Errors
    /// As [`recognize_3d`]; [`SolverError::Unsupported`] for a floating structure;
    /// [`SolverError::InvalidSetting`] for zero `columns_per_solve` or `max_passes`, a
    /// `penetration_tol` that is not finite and positive, or an adhesive zone without areas.
    pub fn new(
        structure: S,
        zones: Vec<ContactZone3<L>>,
        settings: SolidSettings,
    ) -> Result<Self, SolverError> {
        check_settings(&settings)?;
        if structure.floating().is_some() {
            return Err(SolverError::Unsupported(
                "a floating 3D structure (rigid-body modes): hold it with supports".into(),
            ));
        }
        if let Some(z) = zones
            .iter()
            .find(|z| z.law.has_adhesion() && z.areas.is_none())
        {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{}`: an adhesive law needs the contactor nodes' tributary areas (its \
                 springs are a stiffness per unit area): give them with `with_areas`",
                z.name
            )));
        }
        let candidates = recognize_3d(&structure, &zones)?;
        let h_rows = candidates
            .iter()
            .flat_map(|c| c.frame().map(|dir| c.h_row(&structure, dir)))
            .collect();
        let states = candidates
            .iter()
            .map(|c| zones[c.zone].law.initial_state())
            .collect();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for c in &candidates {
            let x = structure.node_position(c.node);
            for a in 0..3 {
                lo[a] = lo[a].min(x[a]);
                hi[a] = hi[a].max(x[a]);
            }
        }
        let extent = (0..3).map(|a| hi[a] - lo[a]).fold(0.0, f64::max);
        let scale = if extent > 0.0 { extent } else { 1.0 };
        let n = candidates.len();
        Ok(Self {
            u: vec![0.0; structure.dof_count()],
            nodal_u: vec![[0.0; 3]; structure.node_count()],
            rows_version: structure.stiffness_version(),
            structure,
            zones,
            settings,
            h_rows,
            states,
            jumps: candidates.iter().map(|c| [c.gap0, 0.0, 0.0]).collect(),
            r_last: vec![[0.0; 3]; n],
            r_bar_last: vec![[0.0; 3]; n],
            candidates,
            w_active: Vec::new(),
            w: Vec::new(),
            w_version: None,
            warm: WarmStartPacing::default(),
            time: 0.0,
            steps: 0,
            solver: UzawaSolver::new(settings.solver),
            scale,
            primal: PrimalCache::default(),
            force_check: ForceFactorCheck::default(),
        })
    }

    /// The structure.
    pub fn structure(&self) -> &S {
        &self.structure
    }

    /// The candidates.
    pub fn candidates(&self) -> &[Candidate3] {
        &self.candidates
    }

    /// The zones.
    pub fn zones(&self) -> &[ContactZone3<L>] {
        &self.zones
    }

    /// Replaces the law of the zone named `zone` from the next step on (laws by phase: press
    /// without friction, then shear with it; other parameters). Every candidate's state (β)
    /// and accepted jump carry over.
    ///
    /// # Errors
    /// [`SolverError::UnknownZone`] naming the zones there are;
    /// [`SolverError::InvalidGeometry`] for an adhesive law on a zone without areas.
    pub fn set_law(&mut self, zone: &str, law: L) -> Result<(), SolverError> {
        let known = self
            .zones
            .iter()
            .map(|z| format!("`{}`", z.name))
            .collect::<Vec<_>>()
            .join(", ");
        let Some(z) = self.zones.iter_mut().find(|z| z.name == zone) else {
            return Err(SolverError::UnknownZone {
                name: zone.to_string(),
                known,
            });
        };
        if law.has_adhesion() && z.areas.is_none() {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{zone}`: an adhesive law needs the contactor nodes' tributary areas"
            )));
        }
        z.law = law;
        self.w_version = None;
        Ok(())
    }

    /// The settings.
    pub fn settings(&self) -> &SolidSettings {
        &self.settings
    }

    /// Replaces the settings from the next step on.
    ///
    /// # Errors
    /// As [`SolidContactSimulation::new`] for the settings.
    pub fn set_settings(&mut self, settings: SolidSettings) -> Result<(), SolverError> {
        check_settings(&settings)?;
        self.settings = settings;
        self.solver = UzawaSolver::new(settings.solver);
        Ok(())
    }

    /// Per-candidate law states at the end of the last step.
    pub fn states(&self) -> &[L::State] {
        &self.states
    }

    /// Resets the displacements and the tangential references to zero while keeping the law
    /// states (e.g. after an installation phase whose displacements are discarded).
    pub fn reset_displacements(&mut self) {
        self.u.fill(0.0);
        self.nodal_u.iter_mut().for_each(|v| *v = [0.0; 3]);
        for (j, c) in self.jumps.iter_mut().zip(&self.candidates) {
            *j = [c.gap0, 0.0, 0.0];
        }
        self.r_bar_last.iter_mut().for_each(|r| *r = [0.0; 3]);
    }

    /// The time at the end of the last step (0 before the first).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps solved so far.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// The free-dof displacement at the end of the last step, in the dof numbering of that
    /// step (a change of supports since renumbers the structure's dofs; the next step follows).
    pub fn displacement(&self) -> &[f64] {
        &self.u
    }

    /// The displacement of `node` at the end of the last step (prescribed components
    /// included).
    ///
    /// # Panics
    /// If `node >= node_count()`.
    #[track_caller]
    pub fn nodal_displacement(&self, node: usize) -> [f64; 3] {
        self.nodal_u[node]
    }

    /// Mutable access to the structure between steps (loads, prescribed values). A change of
    /// stiffness is noticed through [`Structure::stiffness_version`].
    pub fn structure_mut(&mut self) -> &mut S {
        &mut self.structure
    }

    /// One load step ending at `time` (`≥` the current time) with the applied forces scaled by
    /// `force_factor`, as [`ContactSimulation::step`](crate::ContactSimulation::step): the
    /// **prescribed displacements are not scaled** (ramp them through [`Self::structure_mut`]).
    ///
    /// # Errors
    /// Errors of the structure's solves and of the local solver;
    /// [`SolverError::StillPenetrating`] if candidates outside the reduced problem still
    /// penetrate after `max_passes` passes; [`SolverError::InvalidSetting`]
    /// for a `time` not finite or going backwards, or a `force_factor` not finite or other than
    /// 1 without applied forces to scale. On error the simulation keeps the previous state.
    pub fn step(&mut self, time: f64, force_factor: f64) -> Result<SolidStepResult, SolverError> {
        if !(time.is_finite() && time >= self.time) {
            return Err(SolverError::InvalidSetting {
                what: "time",
                value: time,
                expected: "a finite time >= the current time",
            });
        }
        if !force_factor.is_finite() {
            return Err(SolverError::InvalidSetting {
                what: "force_factor",
                value: force_factor,
                expected: "a finite force factor",
            });
        }
        let dt = time - self.time;
        self.follow_numbering()?;
        let ndof = self.structure.dof_count();
        let mut u_free = vec![0.0; ndof];
        self.structure
            .free_response_into(force_factor, &mut u_free)?;
        self.force_check
            .check(&self.structure, force_factor, &u_free)?;
        let free: Vec<[f64; 3]> = (0..self.candidates.len())
            .map(|i| self.local(i, &u_free))
            .collect();
        let mut active: Vec<usize> = (0..self.candidates.len())
            .filter(|&i| {
                let law = &self.zones[self.candidates[i].zone].law;
                free[i][0] <= self.zones[self.candidates[i].zone].alert_distance
                    || self.r_last[i][0] > 0.0
                    || (law.has_adhesion() && law.adhesion_active(&self.states[i]))
            })
            .collect();
        let tol = self.settings.penetration_tol * self.scale;
        let mut counts = Counts::default();
        let mut pass = 0;
        loop {
            pass += 1;
            let (sol, u) = if active.is_empty() {
                (None, u_free.clone())
            } else {
                let sol = self.solve_active(&active, &free, dt)?;
                counts.iterations += sol.iterations;
                counts.adhesion_iterations += sol.adhesion_iterations;
                counts.residual = sol.residual;
                counts.matrix_free = sol.matrix_free;
                counts.active_set = sol.active_set;
                counts.factorizations += sol.factorizations;
                let mut rhs = vec![0.0; ndof];
                for (k, &i) in active.iter().enumerate() {
                    for d in 0..3 {
                        for &(dof, a) in &self.h_rows[3 * i + d] {
                            rhs[dof] += a * sol.r[3 * k + d];
                        }
                    }
                }
                self.structure.solve_in_place(&mut rhs)?;
                let u: Vec<f64> = u_free.iter().zip(&rhs).map(|(a, b)| a + b).collect();
                (Some(sol), u)
            };
            let mut in_active = vec![false; self.candidates.len()];
            active.iter().for_each(|&i| in_active[i] = true);
            let penetrating: Vec<usize> = (0..self.candidates.len())
                .filter(|&i| !in_active[i] && self.local(i, &u)[0] < -tol)
                .collect();
            if penetrating.is_empty() {
                counts.passes = pass;
                return Ok(self.accept(&active, sol, u, dt, &counts));
            }
            if pass >= self.settings.max_passes {
                let deepest = penetrating
                    .iter()
                    .copied()
                    .min_by(|&a, &b| self.local(a, &u)[0].total_cmp(&self.local(b, &u)[0]))
                    .unwrap_or(penetrating[0]);
                let c = &self.candidates[deepest];
                return Err(SolverError::StillPenetrating {
                    passes: pass,
                    count: penetrating.len(),
                    zone: self.zones[c.zone].name.clone(),
                    node: c.node,
                    gap: self.local(deepest, &u)[0],
                    setting: "max_passes",
                });
            }
            active.extend(penetrating);
            active.sort_unstable();
        }
    }

    /// Follows a renumbering of the structure's dofs (supports added or released between
    /// steps change the numbering and the stiffness version): the rows of `H` are rebuilt from
    /// the candidates; `F*` is rebuilt with the new version.
    fn follow_numbering(&mut self) -> Result<(), SolverError> {
        let version = self.structure.stiffness_version();
        if version == self.rows_version {
            return Ok(());
        }
        self.h_rows = self
            .candidates
            .iter()
            .flat_map(|c| c.frame().map(|dir| c.h_row(&self.structure, dir)))
            .collect();
        if let Some(c) = self
            .candidates
            .iter()
            .enumerate()
            .find(|(i, _)| self.h_rows[3 * i].is_empty())
            .map(|(_, c)| c)
        {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{}`: node {} can no longer move along its contact normal relative to \
                 its target (every component along it is now prescribed)",
                self.zones[c.zone].name, c.node
            )));
        }
        self.w_version = None;
        self.rows_version = version;
        Ok(())
    }

    /// `(x_n, u_t1, u_t2)` of candidate `i` for a free-dof displacement `u`.
    fn local(&self, i: usize, u: &[f64]) -> [f64; 3] {
        let c = &self.candidates[i];
        c.local(c.relative(|node| node_displacement(&self.structure, u, node)))
    }

    fn tangent_needed(&self, i: usize) -> bool {
        let law = &self.zones[self.candidates[i].zone].law;
        law.has_friction() || law.has_adhesion()
    }

    /// `F* = H K⁻¹ Hᵀ` on `active` (frictionless contacts: their tangential block decoupled);
    /// while the stiffness is unchanged the columns of contacts already in it are kept.
    fn build_flexibility(&mut self, active: &[usize]) -> Result<(), SolverError> {
        let m = 3 * active.len();
        let version = self.structure.stiffness_version();
        let old = std::mem::take(&mut self.w);
        let previous = (self.w_version == Some(version)).then_some(Previous {
            w: &old,
            active: &self.w_active,
        });
        let (w, _) = build_dense(
            &self.structure,
            &self.h_rows,
            active,
            |j| {
                let i = active[j / 3];
                j % 3 == 0 || (self.tangent_needed(i) && !self.h_rows[3 * i + j % 3].is_empty())
            },
            previous,
            self.settings.columns_per_solve,
        )?;
        self.w = w;
        // a tangential direction the contact cannot move along (frictionless, or held on both
        // sides, e.g. across a symmetry plane) is decoupled: its row of `F*` is zero, and the
        // normal's flexibility on its diagonal keeps the problem definite with `r_t = 0` there
        for (k, &i) in active.iter().enumerate() {
            let wnn = self.w[3 * k * m + 3 * k];
            for d in 1..3 {
                if !self.tangent_needed(i) || self.h_rows[3 * i + d].is_empty() {
                    self.w[(3 * k + d) * m + 3 * k + d] = wnn;
                }
            }
        }
        self.w_active = active.to_vec();
        self.w_version = Some(version);
        Ok(())
    }

    fn solve_active(
        &mut self,
        active: &[usize],
        free: &[[f64; 3]],
        dt: f64,
    ) -> Result<Solved<L::State>, SolverError> {
        let adhesive = active
            .iter()
            .any(|&i| self.zones[self.candidates[i].zone].law.has_adhesion());
        let path = match self.settings.flexibility {
            FlexibilityMode::Dense => Path::Dense,
            FlexibilityMode::MatrixFree if adhesive => Path::Dense,
            FlexibilityMode::MatrixFree => Path::MatrixFree,
            FlexibilityMode::ActiveSet => Path::ActiveSet(
                self.active_set_frames(active)
                    .map_err(SolverError::Unsupported)?,
            ),
            FlexibilityMode::Auto { dense_limit } => {
                if adhesive || active.len() <= dense_limit {
                    Path::Dense
                } else if let Ok(f) = self.active_set_frames(active) {
                    Path::ActiveSet(f)
                } else {
                    Path::MatrixFree
                }
            }
        };
        let path = match path {
            Path::ActiveSet(frames) => match self.solve_active_set(active, &frames, free, dt) {
                Ok(solved) => return Ok(solved),
                // Auto chose this path: fall back to one that converges more surely (the
                // lagged friction coupling fails for large μ)
                Err(
                    SolverError::NotConverged { .. }
                    | SolverError::Stalled { .. }
                    | SolverError::Unsupported(_),
                ) if matches!(self.settings.flexibility, FlexibilityMode::Auto { .. }) => {
                    if active.len() <= DEFAULT_DENSE_LIMIT_3D {
                        Path::Dense
                    } else {
                        Path::MatrixFree
                    }
                }
                Err(e) => return Err(e),
            },
            other => other,
        };
        if matches!(path, Path::MatrixFree) {
            return self.solve_matrix_free(active, free);
        }
        if self.w_active != active || self.w_version != Some(self.structure.stiffness_version()) {
            self.build_flexibility(active)?;
        }
        let laws: Vec<L> = active
            .iter()
            .map(|&i| self.zones[self.candidates[i].zone].law.clone())
            .collect();
        let states: Vec<L::State> = active.iter().map(|&i| self.states[i]).collect();
        let mut q = vec![0.0; 3 * active.len()];
        for (k, &i) in active.iter().enumerate() {
            q[3 * k] = free[i][0];
            if self.tangent_needed(i) {
                q[3 * k + 1] = free[i][1] - self.jumps[i][1];
                q[3 * k + 2] = free[i][2] - self.jumps[i][2];
            }
        }
        let warm: Vec<f64> = active.iter().flat_map(|&i| self.r_bar_last[i]).collect();
        if laws.iter().any(|l| l.has_adhesion()) {
            let u_start: Vec<[f64; 3]> = active.iter().map(|&i| self.jumps[i]).collect();
            let areas: Vec<f64> = active.iter().map(|&i| self.candidates[i].area).collect();
            let step = AdhesiveStep {
                w: &self.w,
                q: &q,
                laws: &laws,
                start_states: &states,
                u_start: &u_start,
                areas: &areas,
                dt,
            };
            let mut options = self.adhesion_options();
            options.warm_start = options.warm_start && self.warm.enabled();
            let sol = solve_adhesive(&mut self.solver, &step, Some(&warm), &options)?;
            self.warm.record(&sol);
            return Ok(Solved {
                r: sol.r,
                r_bar: sol.r_bar,
                states: Some(sol.states),
                iterations: sol.contact_iterations,
                adhesion_iterations: sol.adhesion_iterations,
                residual: sol.report.residual,
                matrix_free: false,
                active_set: false,
                factorizations: 0,
            });
        }
        let mu: Vec<f64> = laws
            .iter()
            .zip(&states)
            .map(|(l, s)| l.friction_coefficient(s).unwrap_or(0.0))
            .collect();
        let problem = ReducedProblem::with_dimension(3, self.w.clone(), q, mu)?;
        let start = warm.iter().any(|v| *v != 0.0).then_some(warm.as_slice());
        let sol = self
            .solver
            .solve_with_states(&problem, &laws, &states, start)?;
        Ok(Solved {
            r_bar: sol.r.clone(),
            r: sol.r,
            states: None,
            iterations: sol.report.iterations,
            adhesion_iterations: 0,
            residual: sol.report.residual,
            matrix_free: false,
            active_set: false,
            factorizations: 0,
        })
    }

    fn accept(
        &mut self,
        active: &[usize],
        sol: Option<Solved<L::State>>,
        u: Vec<f64>,
        dt: f64,
        counts: &Counts,
    ) -> SolidStepResult {
        let n = self.candidates.len();
        let (mut reaction, mut law_reaction) = (vec![[0.0; 3]; n], vec![[0.0; 3]; n]);
        let mut solved_state: Vec<Option<L::State>> = vec![None; n];
        let mut in_active = vec![false; n];
        if let Some(sol) = &sol {
            for (k, &i) in active.iter().enumerate() {
                reaction[i] = core::array::from_fn(|d| sol.r[3 * k + d]);
                law_reaction[i] = core::array::from_fn(|d| sol.r_bar[3 * k + d]);
                solved_state[i] = sol.states.as_ref().map(|s| s[k]);
                in_active[i] = true;
            }
        }
        let mut contacts = Vec::with_capacity(n);
        for i in 0..n {
            let x = self.local(i, &u);
            let start = self.jumps[i];
            let law = &self.zones[self.candidates[i].zone].law;
            self.states[i] = solved_state[i].unwrap_or_else(|| {
                let u_start = LocalVec::<2>::spatial(start[0], start[1], start[2]);
                let u_now = LocalVec::<2>::spatial(x[0], x[1], x[2]);
                law.update_state(&self.states[i], &u_start, &u_now, dt)
            });
            contacts.push(SolidContactRecord {
                candidate: self.candidates[i],
                r: reaction[i],
                beta: law.adhesion_intensity(&self.states[i]),
                gap: x[0],
                slip: [x[1] - start[1], x[2] - start[2]],
                active: in_active[i],
                closed: in_active[i] && law_reaction[i][0] > 0.0,
            });
            self.jumps[i] = x;
            self.r_last[i] = reaction[i];
            self.r_bar_last[i] = law_reaction[i];
        }
        self.nodal_u = (0..self.structure.node_count())
            .map(|n| node_displacement(&self.structure, &u, n))
            .collect();
        self.u = u;
        self.time += dt;
        self.steps += 1;
        let closed = contacts.iter().filter(|c| c.closed).count();
        SolidStepResult {
            contacts,
            contact_iterations: counts.iterations,
            adhesion_iterations: counts.adhesion_iterations,
            passes: counts.passes,
            residual: counts.residual,
            active: active.len(),
            closed,
            matrix_free: counts.matrix_free,
            active_set: counts.active_set,
            factorizations: counts.factorizations,
        }
    }
}

/// A reduced solve's answer: total and law reactions, the states of an adhesive solve.
struct Solved<S> {
    r: Vec<f64>,
    r_bar: Vec<f64>,
    states: Option<Vec<S>>,
    iterations: usize,
    adhesion_iterations: usize,
    residual: f64,
    matrix_free: bool,
    active_set: bool,
    /// Numeric factorisations of the active-set path.
    factorizations: usize,
}

/// Iterations and passes of a step.
#[derive(Default)]
struct Counts {
    iterations: usize,
    adhesion_iterations: usize,
    passes: usize,
    residual: f64,
    matrix_free: bool,
    active_set: bool,
    factorizations: usize,
}

/// How one pass solves its active set.
enum Path {
    Dense,
    MatrixFree,
    ActiveSet(Vec<LocalFrame>),
}

/// The checks of [`SolidSettings`] (module docs of [`SolidContactSimulation::new`]).
fn check_settings(settings: &SolidSettings) -> Result<(), SolverError> {
    if settings.columns_per_solve == 0 || settings.max_passes == 0 {
        return Err(SolverError::InvalidSetting {
            what: "columns_per_solve / max_passes",
            value: 0.0,
            expected: "at least 1",
        });
    }
    if !(settings.penetration_tol > 0.0 && settings.penetration_tol.is_finite()) {
        return Err(SolverError::InvalidSetting {
            what: "penetration_tol",
            value: settings.penetration_tol,
            expected: "a finite tolerance > 0",
        });
    }
    Ok(())
}

/// The displacement of `node` from free-dof values `u` (prescribed components added).
fn node_displacement<S: Structure<3> + ?Sized>(s: &S, u: &[f64], node: usize) -> [f64; 3] {
    let dofs = s.node_dofs(node);
    let pre = s.prescribed_displacement(node);
    core::array::from_fn(|a| dofs[a].map_or(pre[a], |d| u[d]))
}
