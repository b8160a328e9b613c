//! Stage 2, the path: how this pass's active set is solved — a dense `F*` (with the adhesion
//! loop), the matrix-free iteration or the primal active set ([`crate::coupling::primal`]) —
//! and the fallback when `Auto`'s active-set iteration does not converge.

use super::ContactSimulation;
use super::choice::{DOF_RULE_FLOOR, PathChoice, PathReason, SolvePath, dense_contacts_for_dofs};
use super::detection::FreeResponse;
use super::report::StepReport;
use super::scheme::TimeScheme;
use super::settings::FlexibilityMode;
use super::solve::Pass;
use crate::coupling::primal::{LocalFrame, frames};
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use contact_laws::ContactLaw;
use fem_core::{Dim, Structure};

/// How one detection pass solves its active set.
#[derive(Debug, PartialEq)]
pub(super) enum Path {
    Dense,
    MatrixFree,
    ActiveSet(Vec<LocalFrame>),
}

impl Path {
    /// The reported name of this path.
    fn solve_path(&self) -> SolvePath {
        match self {
            Self::Dense => SolvePath::Dense,
            Self::MatrixFree => SolvePath::MatrixFree,
            Self::ActiveSet(_) => SolvePath::ActiveSet,
        }
    }
}

impl<S: Structure<D>, L: ContactLaw + Clone, const D: usize, T: TimeScheme<S, D>>
    ContactSimulation<S, L, D, T>
where
    Dim<D>: ContactSpace<D>,
{
    /// Chooses the path of `active`, builds its operator (`F*` when dense and changed, kept in
    /// the operator cache with `active`) and solves the reduced problem (stage 3) on it, from
    /// the step's `free` response: the solution on `active`, or the candidates a floating
    /// body's rigid motion closes.
    pub(super) fn solve_pass(
        &mut self,
        active: &[usize],
        free: &FreeResponse<D>,
        dt: f64,
        version: u64,
        report: &mut StepReport,
    ) -> Result<Pass<L::State>, SolverError> {
        let (mut path, reason) = self.path(active)?;
        report.path = PathChoice::new(path.solve_path(), reason);
        if let Path::ActiveSet(frames) = &path {
            self.cache.without_dense(active);
            match self.solve_active_set(active, &free.jumps, frames, dt, report) {
                Ok(solved) => {
                    report.active_set = true;
                    return Ok(Pass::Solved(solved));
                }
                // Auto chose this path: fall back to one that converges more surely (the
                // lagged friction coupling of the active set fails for large μ)
                Err(
                    SolverError::NotConverged { .. }
                    | SolverError::Stalled { .. }
                    | SolverError::Unsupported(_),
                ) if matches!(self.settings.flexibility, FlexibilityMode::Auto { .. }) => {
                    self.counters.active_set_fallbacks += 1;
                    let limit = <Dim<D> as ContactSpace<D>>::FALLBACK_DENSE_LIMIT;
                    path = if active.len() <= limit {
                        Path::Dense
                    } else {
                        Path::MatrixFree
                    };
                    let active = active.len();
                    let reason = PathReason::ActiveSetFallback { active, limit };
                    report.path = PathChoice::new(path.solve_path(), reason);
                }
                Err(e) => return Err(e),
            }
        }
        if path == Path::MatrixFree {
            self.cache.without_dense(active);
            report.matrix_free = true;
            return self
                .solve_matrix_free_active(active, &free.jumps, report)
                .map(Pass::Solved);
        }
        let same_stiffness = self.cache.version == Some(version);
        if active != self.cache.active
            || !same_stiffness
            || (!self.settings.tuning.skip.reuse_flexibility && report.detection_passes == 1)
        {
            // the columns of contacts already in F* are kept while the stiffness is the same
            let reuse = same_stiffness && self.settings.tuning.skip.reuse_flexibility;
            self.build_flexibility(active, reuse)?;
            self.cache.version = Some(version);
            report.flexibility_rebuilt = true;
        }
        if self.floats() {
            return self.solve_floating(active, free, dt, report);
        }
        self.solve_active(active, &free.jumps, dt, report)
            .map(Pass::Solved)
    }

    /// How this step's active set is solved, and why.
    fn path(&self, active: &[usize]) -> Result<(Path, PathReason), SolverError> {
        let adhesive = active.iter().any(|&i| {
            let law = self.interface.law(i);
            law.has_adhesion() && law.adhesion_active(&self.accepted.states[i])
        });
        if self.floats() {
            // the rigid-body amplitudes are solved for on a dense F* only
            return match self.settings.flexibility {
                FlexibilityMode::Dense => Ok((Path::Dense, PathReason::Requested)),
                FlexibilityMode::Auto { .. } => Ok((Path::Dense, PathReason::Floating)),
                FlexibilityMode::MatrixFree | FlexibilityMode::ActiveSet => {
                    Err(SolverError::Unsupported(format!(
                        "the structure floats (it has rigid-body modes): \
                         SimulationSettings::flexibility = {:?} does not solve for them; use \
                         FlexibilityMode::Dense or Auto",
                        self.settings.flexibility
                    )))
                }
            };
        }
        let n = active.len();
        match self.settings.flexibility {
            FlexibilityMode::Dense => Ok((Path::Dense, PathReason::Requested)),
            FlexibilityMode::Auto { dense_limit: limit } => Ok(if adhesive {
                (Path::Dense, PathReason::Adhesive)
            } else if n <= limit {
                self.within_dense_limit(active, limit)
            } else if let Ok(f) = self.active_set_frames(active) {
                let reason = PathReason::AboveDenseLimit { active: n, limit };
                (Path::ActiveSet(f), reason)
            } else {
                let reason = PathReason::ActiveSetUnavailable { active: n, limit };
                (Path::MatrixFree, reason)
            }),
            FlexibilityMode::MatrixFree if adhesive => Err(SolverError::InvalidSetting {
                what: "flexibility",
                value: n as f64,
                expected: "Dense, ActiveSet or Auto for adhesive laws (MatrixFree has no place for the springs)",
            }),
            FlexibilityMode::MatrixFree | FlexibilityMode::ActiveSet if active.is_empty() => {
                Ok((Path::Dense, PathReason::NoActiveContacts))
            }
            FlexibilityMode::MatrixFree => Ok((Path::MatrixFree, PathReason::Requested)),
            FlexibilityMode::ActiveSet => self
                .active_set_frames(active)
                .map(|f| (Path::ActiveSet(f), PathReason::Requested))
                .map_err(SolverError::Unsupported),
        }
    }

    /// `Auto`'s path for `active` within its dense limit: dense, unless in 3D the contacts
    /// are above `max(500, 0.5 DOF^(2/3))`: then the active set where it applies, else
    /// matrix-free ([`super::choice`]).
    fn within_dense_limit(&self, active: &[usize], limit: usize) -> (Path, PathReason) {
        let n = active.len();
        let within = (
            Path::Dense,
            PathReason::WithinDenseLimit { active: n, limit },
        );
        if !<Dim<D> as ContactSpace<D>>::DENSE_BY_DOFS || n <= DOF_RULE_FLOOR {
            return within;
        }
        let dofs = self.structure.dof_count();
        let by_dofs = dense_contacts_for_dofs(dofs);
        if n <= by_dofs {
            let reason = PathReason::WithinDofRule {
                active: n,
                dofs,
                limit: by_dofs,
            };
            return (Path::Dense, reason);
        }
        match self.active_set_frames(active) {
            Ok(f) => {
                let reason = PathReason::AboveDofRule {
                    active: n,
                    dofs,
                    limit: by_dofs,
                };
                (Path::ActiveSet(f), reason)
            }
            // the active set does not apply: matrix-free, whose products cost less than the
            // dense columns on the same side of the rule (measured, issue 38)
            Err(_) => {
                let reason = PathReason::AboveDofRuleMatrixFree {
                    active: n,
                    dofs,
                    limit: by_dofs,
                };
                (Path::MatrixFree, reason)
            }
        }
    }

    /// Whether the structure has rigid-body modes (a floating body).
    pub(super) fn floats(&self) -> bool {
        self.structure.floating().is_some()
    }

    /// The local frames of the primal active-set path, or why it does not apply.
    fn active_set_frames(&self, active: &[usize]) -> Result<Vec<LocalFrame>, String> {
        if self.structure.stiffness_matrix().is_none() {
            return Err("the structure does not expose its stiffness matrix".into());
        }
        let interface = &self.interface;
        for &i in active {
            if interface
                .law(i)
                .friction_coefficient(&self.accepted.states[i])
                .is_none()
            {
                return Err(format!(
                    "zone `{}`: its law has no friction coefficient (not a Coulomb-cone law)",
                    interface.zones[interface.candidates[i].zone].name
                ));
            }
        }
        let node_of = |i: usize| interface.candidates[i].node;
        frames(&self.structure, &interface.h_rows, active, &node_of)
    }
}
