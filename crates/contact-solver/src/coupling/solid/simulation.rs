//! [`SolidContactSimulation`]: quasi-static contact of a 3D [`Structure<3>`] with rigid
//! obstacles, condensed on the contact unknowns (`F* = H K⁻¹ Hᵀ`, dense) and solved with the
//! local layer in 3D, one load step at a time.
//!
//! A step: the free response `u_free`; the active set (gap under `u_free` within the zone's
//! alert distance, or in contact at the end of the last step); `F*` on it (rebuilt when the
//! active set or the stiffness changes); the reduced problem `x = F* r + q` with
//! `q = (g₀ + n·u_free, t₁·u_free − u_t1,start, t₂·u_free − u_t2,start)` per contact, solved
//! by [`UzawaSolver`] (the same algorithms as in 2D, `Auto` by default); then
//! `u = u_free + K⁻¹ Hᵀ r` and the penetration check of the inactive candidates (added and
//! solved again if one penetrates).
//!
//! What 3D does not have yet, refused with [`SolverError::Unsupported`] rather than answered
//! wrongly: adhesive laws (their springs are not condensed in 3D), floating structures, node
//! pairs and node-to-face zones, the matrix-free and active-set paths.

use super::zone::{Candidate3, ContactZone3, recognize_3d};
use crate::coupling::flexibility::flexibility_into;
use crate::error::SolverError;
use crate::local::{ReducedProblem, UzawaSettings, UzawaSolver, symmetrize};
use contact_laws::{ContactLaw, LocalVec};
use fem_core::Structure;

/// Settings of a [`SolidContactSimulation`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidSettings {
    /// The local solver's settings.
    pub solver: UzawaSettings,
    /// Right-hand sides per solve when building `F*`.
    pub columns_per_solve: usize,
    /// Largest number of active-set passes in a step (each adds the candidates that
    /// penetrated).
    pub max_passes: usize,
    /// A penetration below this fraction of the contact nodes' extent is not one.
    pub penetration_tol: f64,
}

impl Default for SolidSettings {
    fn default() -> Self {
        Self {
            solver: UzawaSettings::default(),
            columns_per_solve: 96,
            max_passes: 20,
            penetration_tol: 1e-9,
        }
    }
}

/// One contact at the end of a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidContactRecord {
    /// The candidate (zone, node, frame, area).
    pub candidate: Candidate3,
    /// Reaction `(r_n, r_t1, r_t2)` on the contactor node, in the frame: `r_n ≥ 0` is
    /// compression. The force on the node is `r_n n + r_t1 t₁ + r_t2 t₂`.
    pub r: [f64; 3],
    /// Gap at the end of the step.
    pub gap: f64,
    /// Tangential displacement increment of the step `(Δu_t1, Δu_t2)` (the slip of a sliding
    /// contact).
    pub slip: [f64; 2],
    /// Whether the contact was in the active set.
    pub active: bool,
}

impl SolidContactRecord {
    /// The reaction as a global force vector.
    pub fn force(&self) -> [f64; 3] {
        let [n, t1, t2] = self.candidate.frame();
        core::array::from_fn(|a| self.r[0] * n[a] + self.r[1] * t1[a] + self.r[2] * t2[a])
    }

    /// Contact pressure `r_n / area`.
    pub fn pressure(&self) -> f64 {
        if self.candidate.area > 0.0 {
            self.r[0] / self.candidate.area
        } else {
            0.0
        }
    }
}

/// The result of a step.
#[derive(Clone, Debug)]
pub struct SolidStepResult {
    /// Every candidate, in recognition order.
    pub contacts: Vec<SolidContactRecord>,
    /// Local-solver iterations summed over the passes.
    pub contact_iterations: usize,
    /// Active-set passes.
    pub passes: usize,
    /// The local solver's last residual.
    pub residual: f64,
    /// Number of active contacts.
    pub active: usize,
}

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
    /// Last reactions (warm start and "was in contact").
    r_last: Vec<[f64; 3]>,
    w_active: Vec<usize>,
    w: Vec<f64>,
    w_version: Option<u64>,
    u: Vec<f64>,
    time: f64,
    solver: UzawaSolver,
    scale: f64,
}

impl<S: Structure<3>, L: ContactLaw + Clone> SolidContactSimulation<S, L> {
    /// Recognises the candidates of `zones` on `structure` and starts at time 0.
    ///
    /// # Errors
    /// As [`recognize_3d`]; [`SolverError::Unsupported`] for a floating structure or an
    /// adhesive law; [`SolverError::InvalidSetting`] for zero `columns_per_solve` or
    /// `max_passes`, or a `penetration_tol` that is not finite and positive.
    pub fn new(
        structure: S,
        zones: Vec<ContactZone3<L>>,
        settings: SolidSettings,
    ) -> Result<Self, SolverError> {
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
        if structure.rigid_body_modes().is_some_and(|m| !m.is_empty()) {
            return Err(SolverError::Unsupported(
                "a floating 3D structure (rigid-body modes): hold it with supports".into(),
            ));
        }
        if let Some(z) = zones.iter().find(|z| z.law.has_adhesion()) {
            return Err(SolverError::Unsupported(format!(
                "zone `{}`: adhesive laws are not supported in 3D yet",
                z.name
            )));
        }
        let candidates = recognize_3d(&structure, &zones)?;
        let mut h_rows = Vec::with_capacity(3 * candidates.len());
        for c in &candidates {
            let dofs = structure.node_dofs(c.node);
            for dir in c.frame() {
                h_rows.push(
                    (0..3)
                        .filter_map(|a| dofs[a].map(|d| (d, dir[a])))
                        .filter(|&(_, v)| v != 0.0)
                        .collect(),
                );
            }
        }
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
            structure,
            zones,
            settings,
            h_rows,
            states,
            jumps: candidates.iter().map(|c| [c.gap0, 0.0, 0.0]).collect(),
            r_last: vec![[0.0; 3]; n],
            candidates,
            w_active: Vec::new(),
            w: Vec::new(),
            w_version: None,
            time: 0.0,
            solver: UzawaSolver::new(settings.solver),
            scale,
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

    /// The free-dof displacement at the end of the last step.
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
        node_displacement(&self.structure, &self.u, node)
    }

    /// Mutable access to the structure between steps (loads, prescribed values). A change of
    /// stiffness is noticed through [`Structure::stiffness_version`].
    pub fn structure_mut(&mut self) -> &mut S {
        &mut self.structure
    }

    /// One load step to `load_factor`, of length `dt ≥ 0` (for the laws' state updates).
    ///
    /// # Errors
    /// Errors of the structure's solves; the local solver's errors
    /// ([`SolverError::NotConverged`] …); [`SolverError::NotConverged`] if the active set
    /// still grows after `max_passes` passes; [`SolverError::InvalidSetting`] for a negative
    /// or non-finite `dt`.
    pub fn step(&mut self, load_factor: f64, dt: f64) -> Result<SolidStepResult, SolverError> {
        if !(dt >= 0.0 && dt.is_finite()) {
            return Err(SolverError::InvalidSetting {
                what: "dt",
                value: dt,
                expected: "a finite step length >= 0",
            });
        }
        let ndof = self.structure.dof_count();
        let mut u_free = vec![0.0; ndof];
        self.structure
            .free_response_into(load_factor, &mut u_free)?;
        let free: Vec<[f64; 3]> = (0..self.candidates.len())
            .map(|i| self.local(i, &u_free))
            .collect();
        let mut active: Vec<usize> = (0..self.candidates.len())
            .filter(|&i| {
                free[i][0] <= self.zones[self.candidates[i].zone].alert || self.r_last[i][0] > 0.0
            })
            .collect();
        let tol = self.settings.penetration_tol * self.scale;
        let (mut iterations, mut residual) = (0, 0.0);
        for pass in 1..=self.settings.max_passes {
            let (r, u) = if active.is_empty() {
                (Vec::new(), u_free.clone())
            } else {
                let sol = self.solve_active(&active, &free)?;
                iterations += sol.report.iterations;
                residual = sol.report.residual;
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
                (sol.r, u)
            };
            let mut in_active = vec![false; self.candidates.len()];
            active.iter().for_each(|&i| in_active[i] = true);
            let penetrating: Vec<usize> = (0..self.candidates.len())
                .filter(|&i| !in_active[i] && self.local(i, &u)[0] < -tol)
                .collect();
            if penetrating.is_empty() {
                return Ok(self.accept(&active, &r, u, dt, iterations, pass, residual));
            }
            active.extend(penetrating);
            active.sort_unstable();
        }
        Err(SolverError::NotConverged {
            iterations: self.settings.max_passes,
            residual,
            history: Vec::new(),
        })
    }

    /// `(x_n, u_t1, u_t2)` of candidate `i` for a free-dof displacement `u`.
    fn local(&self, i: usize, u: &[f64]) -> [f64; 3] {
        let c = &self.candidates[i];
        let v = node_displacement(&self.structure, u, c.node);
        let [n, t1, t2] = c.frame();
        let d = super::obstacle::dot;
        [c.gap0 + d(n, v), d(t1, v), d(t2, v)]
    }

    fn tangent_needed(&self, i: usize) -> bool {
        self.zones[self.candidates[i].zone].law.has_friction()
    }

    /// `F* = H K⁻¹ Hᵀ` on `active` (frictionless contacts: their tangential block decoupled).
    fn build_flexibility(&mut self, active: &[usize]) -> Result<(), SolverError> {
        let m = 3 * active.len();
        self.w.clear();
        self.w.resize(m * m, 0.0);
        let solved: Vec<usize> = (0..m)
            .filter(|&j| j % 3 == 0 || self.tangent_needed(active[j / 3]))
            .collect();
        let rows: Vec<usize> = active
            .iter()
            .flat_map(|&i| [3 * i, 3 * i + 1, 3 * i + 2])
            .collect();
        flexibility_into(
            &self.structure,
            &self.h_rows,
            &rows,
            &solved,
            self.settings.columns_per_solve,
            &mut self.w,
        )?;
        symmetrize(&mut self.w, m);
        for (k, &i) in active.iter().enumerate() {
            if !self.tangent_needed(i) {
                let wnn = self.w[3 * k * m + 3 * k];
                for d in 1..3 {
                    self.w[(3 * k + d) * m + 3 * k + d] = wnn;
                }
            }
        }
        self.w_active = active.to_vec();
        self.w_version = Some(self.structure.stiffness_version());
        Ok(())
    }

    fn solve_active(
        &mut self,
        active: &[usize],
        free: &[[f64; 3]],
    ) -> Result<crate::local::Solution, SolverError> {
        if self.w_active != active || self.w_version != Some(self.structure.stiffness_version()) {
            self.build_flexibility(active)?;
        }
        let laws: Vec<L> = active
            .iter()
            .map(|&i| self.zones[self.candidates[i].zone].law.clone())
            .collect();
        let states: Vec<L::State> = active.iter().map(|&i| self.states[i]).collect();
        let mu: Vec<f64> = laws
            .iter()
            .zip(&states)
            .map(|(l, s)| l.friction_coefficient(s).unwrap_or(0.0))
            .collect();
        let mut q = vec![0.0; 3 * active.len()];
        for (k, &i) in active.iter().enumerate() {
            q[3 * k] = free[i][0];
            if self.tangent_needed(i) {
                q[3 * k + 1] = free[i][1] - self.jumps[i][1];
                q[3 * k + 2] = free[i][2] - self.jumps[i][2];
            }
        }
        let warm: Vec<f64> = active.iter().flat_map(|&i| self.r_last[i]).collect();
        let problem = ReducedProblem::with_dimension(3, self.w.clone(), q, mu)?;
        let start = warm.iter().any(|v| *v != 0.0).then_some(warm.as_slice());
        self.solver
            .solve_with_states(&problem, &laws, &states, start)
    }

    #[allow(clippy::too_many_arguments)]
    fn accept(
        &mut self,
        active: &[usize],
        r: &[f64],
        u: Vec<f64>,
        dt: f64,
        contact_iterations: usize,
        passes: usize,
        residual: f64,
    ) -> SolidStepResult {
        let mut reaction = vec![[0.0; 3]; self.candidates.len()];
        let mut in_active = vec![false; self.candidates.len()];
        for (k, &i) in active.iter().enumerate() {
            reaction[i] = [r[3 * k], r[3 * k + 1], r[3 * k + 2]];
            in_active[i] = true;
        }
        let mut contacts = Vec::with_capacity(self.candidates.len());
        for i in 0..self.candidates.len() {
            let x = self.local(i, &u);
            let start = self.jumps[i];
            let law = &self.zones[self.candidates[i].zone].law;
            let u_start = LocalVec::<2>::spatial(start[0], start[1], start[2]);
            let u_now = LocalVec::<2>::spatial(x[0], x[1], x[2]);
            self.states[i] = law.update_state(&self.states[i], &u_start, &u_now, dt);
            contacts.push(SolidContactRecord {
                candidate: self.candidates[i],
                r: reaction[i],
                gap: x[0],
                slip: [x[1] - start[1], x[2] - start[2]],
                active: in_active[i],
            });
            self.jumps[i] = x;
            self.r_last[i] = reaction[i];
        }
        self.u = u;
        self.time += dt;
        SolidStepResult {
            contacts,
            contact_iterations,
            passes,
            residual,
            active: active.len(),
        }
    }
}

/// The displacement of `node` from free-dof values `u` (prescribed components added).
fn node_displacement<S: Structure<3> + ?Sized>(s: &S, u: &[f64], node: usize) -> [f64; 3] {
    let dofs = s.node_dofs(node);
    let pre = s.prescribed_displacement(node);
    core::array::from_fn(|a| dofs[a].map_or(pre[a], |d| u[d]))
}
