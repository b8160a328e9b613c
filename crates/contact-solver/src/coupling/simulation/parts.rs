//! The simulation's state in three parts, each owned by the stages that write it:
//! [`Interface`] (what the interface is: zones, candidates, `H`), [`Accepted`] (what a step
//! carries to the next: law states, jumps, reactions, displacements, time) and
//! [`OperatorCache`] (the dense `F*`, the primal factorisations, the active set they are for,
//! and the last reduced problem).

use super::last_problem::LastProblem;
use super::settings::SimulationSettings;
use crate::coupling::primal::PrimalCache;
use crate::coupling::space::ContactSpace;
use crate::coupling::zone::{
    Candidate, ContactZone, check_candidates, check_rigid_targets, recognize,
};
use crate::error::SolverError;
use contact_laws::ContactLaw;
use fem_core::{Dim, Structure};

/// What the interface is: the zones, the candidates recognition found, and the rows of `H`
/// numbered for the structure's dofs.
pub(super) struct Interface<L, const D: usize>
where
    Dim<D>: ContactSpace<D>,
{
    pub(super) zones: Vec<ContactZone<L, D>>,
    pub(super) candidates: Vec<Candidate<D>>,
    /// H rows (n then the tangents per candidate) on free dofs: (dof, coefficient).
    pub(super) h_rows: Vec<Vec<(usize, f64)>>,
    /// Stiffness version the rows of `H` were numbered for (the last step's).
    pub(super) rows_version: u64,
    /// The penetration tolerance of the inactive candidates, a length
    /// ([`ContactSpace::PENETRATION_TOL`] × the contactors' extent).
    pub(super) penetration_tol: f64,
}

impl<L: ContactLaw, const D: usize> Interface<L, D>
where
    Dim<D>: ContactSpace<D>,
{
    /// Recognises the candidates of `zones` on `structure` (reference configuration) and
    /// numbers `H` for its dofs.
    ///
    /// # Errors
    /// As for [`recognize`]; [`SolverError::InvalidGeometry`] if no zone has a candidate, for
    /// a candidate whose normal motion is prescribed, or for a 3D adhesive zone without areas.
    pub(super) fn recognize<S: Structure<D>>(
        structure: &S,
        zones: Vec<ContactZone<L, D>>,
        relative_penetration_tol: f64,
    ) -> Result<Self, SolverError> {
        let candidates = recognize(structure, &zones)?;
        if D == 3 {
            // every zone has a candidate, none is held (2D refuses a held one in `h_rows_of`)
            check_candidates(structure, &zones, &candidates)?;
        }
        if candidates.is_empty() {
            return Err(SolverError::InvalidGeometry(
                "no contactor node projects on its target: the simulation has no contact candidate"
                    .into(),
            ));
        }
        check_rigid_targets(structure, &zones, &candidates)?;
        if let Some(z) = zones
            .iter()
            .find(|z| D == 3 && z.law.has_adhesion() && z.areas.is_none())
        {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{}`: an adhesive law needs the contactor nodes' tributary areas (its \
                 springs are a stiffness per unit area): give them with `with_areas`",
                z.name
            )));
        }
        let penetration_tol = relative_penetration_tol * extent(structure, &candidates);
        let h_rows = h_rows_of(structure, &zones, &candidates)?;
        Ok(Self {
            zones,
            candidates,
            h_rows,
            rows_version: structure.stiffness_version(),
            penetration_tol,
        })
    }

    /// Follows a renumbering of the structure's dofs (supports added or released between
    /// steps change the numbering and the stiffness version): the rows of `H` are rebuilt
    /// from the candidates. Returns whether the version changed.
    ///
    /// # Errors
    /// As [`h_rows_of`] (nothing changes then).
    pub(super) fn follow_numbering<S: Structure<D>>(
        &mut self,
        structure: &S,
    ) -> Result<bool, SolverError> {
        let version = structure.stiffness_version();
        if version == self.rows_version {
            return Ok(false);
        }
        self.h_rows = h_rows_of(structure, &self.zones, &self.candidates)?;
        self.rows_version = version;
        Ok(true)
    }

    /// Sets the penetration tolerance to `relative` × the contactors' extent.
    pub(super) fn set_relative_penetration_tol<S: Structure<D>>(
        &mut self,
        structure: &S,
        relative: f64,
    ) {
        self.penetration_tol = relative * extent(structure, &self.candidates);
    }

    /// The law of candidate `i`'s zone.
    #[inline]
    pub(super) fn law(&self, i: usize) -> &L {
        &self.zones[self.candidates[i].zone].law
    }

    /// The local jumps `[gap, u_t…]` of every candidate under the free-dof vector `u`.
    pub(super) fn local_jumps_of<S: Structure<D>>(
        &self,
        structure: &S,
        u: &[f64],
    ) -> Vec<[f64; D]> {
        self.candidates
            .iter()
            .map(|c| c.local(c.relative(|n| nodal(structure, u, n))))
            .collect()
    }

    /// Whether candidate `i`'s tangential unknown takes part (friction or adhesion), under the
    /// skip rules.
    pub(super) fn tangent_needed(&self, i: usize, settings: &SimulationSettings) -> bool {
        let law = self.law(i);
        !settings.tuning.skip.frictionless_normal_only || law.has_friction() || law.has_adhesion()
    }

    /// Whether the tangential component `d` (`1..D`) of candidate `i` is solved: its tangent
    /// is needed ([`Self::tangent_needed`]) and, in 3D
    /// ([`ContactSpace::DECOUPLE_HELD_TANGENTS`]), the contact can move along it.
    pub(super) fn tangent_solved(&self, i: usize, d: usize, settings: &SimulationSettings) -> bool {
        self.tangent_needed(i, settings)
            && !(<Dim<D> as ContactSpace<D>>::DECOUPLE_HELD_TANGENTS
                && self.h_rows[D * i + d].is_empty())
    }
}

/// What a step carries to the next: the accepted state at the end of the last step.
pub(super) struct Accepted<T, const D: usize> {
    /// Time at the end of the last step.
    pub(super) time: f64,
    /// Per-candidate law states.
    pub(super) states: Vec<T>,
    /// Per-candidate (gap, u_t…).
    pub(super) jumps: Vec<[f64; D]>,
    /// Per-candidate r̄ (the warm start of the next solve).
    pub(super) r_bar: Vec<[f64; D]>,
    /// Free-dof displacements, in the numbering of [`Interface::rows_version`].
    pub(super) u: Vec<f64>,
    /// Nodal displacements (numbering-free).
    pub(super) nodal_u: Vec<[f64; D]>,
    /// Floating structures: the rigid-body amplitudes `α` (one per mode).
    pub(super) alpha: Vec<f64>,
}

impl<T, const D: usize> Accepted<T, D>
where
    Dim<D>: ContactSpace<D>,
{
    /// Time 0, no displacement, every law's initial state.
    pub(super) fn start<S: Structure<D>, L: ContactLaw<State = T>>(
        structure: &S,
        interface: &Interface<L, D>,
    ) -> Self {
        let u = vec![0.0; structure.dof_count()];
        let n = interface.candidates.len();
        Self {
            time: 0.0,
            states: (0..n).map(|i| interface.law(i).initial_state()).collect(),
            jumps: interface.local_jumps_of(structure, &u),
            r_bar: vec![[0.0; D]; n],
            u,
            nodal_u: vec![[0.0; D]; structure.node_count()],
            alpha: Vec::new(),
        }
    }

    /// `u` in the structure's current numbering, from the nodal displacements.
    pub(super) fn renumber<S: Structure<D>>(&mut self, structure: &S) {
        self.u = vec![0.0; structure.dof_count()];
        for (n, v) in self.nodal_u.iter().enumerate() {
            for (c, d) in structure.node_dofs(n).into_iter().enumerate() {
                if let Some(i) = d {
                    self.u[i] = v[c];
                }
            }
        }
    }

    /// Zero displacement, rigid motion and reactions, the tangential reference from there;
    /// the law states kept.
    pub(super) fn reset_displacements<S: Structure<D>, L: ContactLaw>(
        &mut self,
        structure: &S,
        interface: &Interface<L, D>,
    ) {
        self.u.fill(0.0);
        self.nodal_u.iter_mut().for_each(|v| *v = [0.0; D]);
        self.alpha.fill(0.0);
        self.jumps = interface.local_jumps_of(structure, &self.u);
        self.r_bar.iter_mut().for_each(|r| *r = [0.0; D]);
    }
}

/// The operator cache: the dense `F*` of an active set, the primal factorisations, and the
/// reduced problem of the last solve.
pub(super) struct OperatorCache<L: ContactLaw, const D: usize> {
    /// Active set of the cached `F*` (and of the last solve).
    pub(super) active: Vec<usize>,
    /// `F*` on `active`, row-major (empty after a solve without it), shared with the reduced
    /// problems solved on it (and the last one, kept for export): one copy (issue 38).
    pub(super) w: std::sync::Arc<Vec<f64>>,
    /// Stiffness version `w` was built for.
    pub(super) version: Option<u64>,
    pub(super) primal: PrimalCache,
    pub(super) last_problem: LastProblem<L, D>,
}

impl<L: ContactLaw, const D: usize> OperatorCache<L, D> {
    /// Nothing cached.
    pub(super) fn new() -> Self {
        Self {
            active: Vec::new(),
            w: std::sync::Arc::default(),
            version: None,
            primal: PrimalCache::default(),
            last_problem: LastProblem::None,
        }
    }

    /// Forgets the operators (a law or the numbering changed): rebuilt at the next step.
    pub(super) fn invalidate(&mut self) {
        self.version = None;
        self.primal = PrimalCache::default();
    }

    /// A solve of `active` without a dense `F*` (matrix-free or active set).
    pub(super) fn without_dense(&mut self, active: &[usize]) {
        if active != self.active {
            self.active = active.to_vec();
        }
        // freed, not cleared: a cleared Vec kept the old F*'s allocation
        self.w = std::sync::Arc::default();
        self.version = None;
        self.last_problem = LastProblem::None;
    }
}

/// The rows of `H` (normal then tangent per candidate) on the structure's free dofs.
///
/// # Errors
/// [`SolverError::InvalidGeometry`] for a candidate whose normal relative displacement is fully
/// prescribed.
fn h_rows_of<S: Structure<D> + ?Sized, L, const D: usize>(
    structure: &S,
    zones: &[ContactZone<L, D>],
    candidates: &[Candidate<D>],
) -> Result<Vec<Vec<(usize, f64)>>, SolverError>
where
    Dim<D>: ContactSpace<D>,
{
    let mut h_rows = Vec::with_capacity(D * candidates.len());
    for c in candidates {
        for dir in c.frame() {
            h_rows.push(c.h_row(structure, dir));
        }
        if h_rows[h_rows.len() - D].is_empty() {
            return Err(SolverError::InvalidGeometry(format!(
                "zone `{}`: the normal displacement of contactor node {} relative to its \
                 target is fully prescribed, so it cannot take part in contact",
                zones[c.zone].name, c.node
            )));
        }
    }
    Ok(h_rows)
}

/// The largest side of the box of the candidates' contactor nodes (1 for a single point).
fn extent<S: Structure<D> + ?Sized, const D: usize>(s: &S, candidates: &[Candidate<D>]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; D], [f64::NEG_INFINITY; D]);
    for c in candidates {
        let x = s.node_position(c.node);
        for a in 0..D {
            lo[a] = lo[a].min(x[a]);
            hi[a] = hi[a].max(x[a]);
        }
    }
    let e = (0..D).map(|a| hi[a] - lo[a]).fold(0.0, f64::max);
    if e > 0.0 { e } else { 1.0 }
}

/// The displacement of `node` under the free-dof vector `u` (prescribed components at their
/// values).
pub(super) fn nodal<S: Structure<D> + ?Sized, const D: usize>(
    s: &S,
    u: &[f64],
    node: usize,
) -> [f64; D] {
    let mut v = s.prescribed_displacement(node);
    for (c, d) in s.node_dofs(node).into_iter().enumerate() {
        if let Some(i) = d {
            v[c] = u[i];
        }
    }
    v
}
