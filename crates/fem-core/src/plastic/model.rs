//! [`PlasticModel`]: a body whose material points follow a [`ConstitutivePoint`] with
//! history, behind the [`Nonlinear`] seam (issue 40).
//!
//! ```text
//! f_int(u) = Σ_e Σ_q Bᵀ σ_q(ε_q) w_q − K_fp ū        ε_q = B u_e  (u_e: free and prescribed)
//! K_t      = Σ_e Σ_q Bᵀ sym(C_t,q) B w_q               sym(C) = (C + Cᵀ) / 2
//! f_ext(λ) = λ f_ext,ref − K_fp ū                      (the elastic model's right-hand side)
//! ```
//! The elastic coupling `K_fp ū` of the prescribed values stands on both sides, so that
//! `f_ext` is the right-hand side of the elastic model the body is built on (the contract
//! of [`Nonlinear::external_force_into`]) and a linear-elastic point reproduces it exactly.
//! An initial stress is not a load: it is the committed stress of the points, so it enters
//! `f_int` (`Σ Bᵀ σ₀ w` at `u = 0`).
//!
//! The tangent is [`TangentKind::Symmetric`] (`sym(C_t)`, the elastic model's Cholesky) or
//! [`TangentKind::Exact`] (`C_t` itself in full storage, a sparse LU, `model_lu.rs`). For an
//! associated law (von Mises, Drucker–Prager with `θ = φ`) `C_t` is symmetric and both are
//! the consistent tangent; for a non-associated law only `Exact` is (quadratic Newton), the
//! symmetric part converges linearly and may be indefinite, so `Exact` is then the default.
//!
//! Everything linear — the dof map, the pattern and its symbolic factorisation, the loads,
//! the prescribed values, the mass — is the [`ElasticModel`]'s the body holds; the body
//! only replaces the internal forces and the tangent. Post-processing is in
//! `model_post.rs`, initial stresses in `model_initial.rs`.

use super::model_lu::{ExactTangent, TangentKind};
use super::{ConstitutivePoint, PointState, Voigt, VoigtMatrix};
use crate::dirichlet::Dof;
use crate::element::kernel::{self, Point};
use crate::error::FemError;
use crate::idealization::Idealization;
use crate::model::{ElasticModel, ModelSpace};
use crate::space::{Dim, Space};
use crate::structure::{Mass, Nonlinear, Structure};
use faer::MatMut;
use std::sync::Arc;

/// How a strain of the element becomes the 3D Voigt strain of the point (the table of
/// [`crate::plastic`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kinematics {
    /// `[ε_xx, ε_yy, 0, γ_xy, 0, 0]`.
    PlaneStrain,
    /// `[ε_rr, ε_zz, ε_θθ, γ_rz, 0, 0]`, `ε_θθ = u_r / r`.
    Axisymmetric,
    /// The full vector.
    Solid,
}

/// A body of dimension `D` whose material points follow a [`ConstitutivePoint`] per region,
/// with its history per quadrature point (committed and trial), built on an
/// [`ElasticModel`] that brings the mesh, the idealisation (plane strain or axisymmetry in
/// 2D; plane stress is not served), the supports and the loads. It implements
/// [`Structure`] and is its own [`Nonlinear`] side; [`crate::plastic::newton`] solves its
/// equilibrium.
///
/// The elastic model's materials give the loads (unit weights) and nothing else: the
/// stiffness is the points' tangent. An initial stress set on the elastic model
/// ([`ElasticModel::set_initial_stress`]) becomes the committed stress of the points.
///
/// # Examples
/// With linear-elastic points the body answers the elastic model's displacements in one
/// Newton step:
/// ```
/// use fem_core::generate::{RectangleSpec, rectangle};
/// use fem_core::plastic::{LinearElasticPoint, PlasticModel, newton};
/// use fem_core::{Component, Idealization, LinearElasticModel, Material, Structure, Supports};
/// use std::sync::Arc;
/// let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2))?;
/// let left = mesh.node_set("left")?.to_vec();
/// let mut supports = Supports::new();
/// supports.fix(&left, Component::X).fix(&left, Component::Y);
/// let mut elastic = LinearElasticModel::new(mesh, Idealization::PlaneStrain,
///     &[(0, Material::new(100.0, 0.3, 1.0)?)], supports)?;
/// elastic.add_self_weight()?;
/// let expected = elastic.solve(1.0)?;
/// let point = Arc::new(LinearElasticPoint::new(100.0, 0.3)?);
/// let mut body = PlasticModel::new(elastic, &[(0, point)])?;
/// let mut u = vec![0.0; body.dof_count()];
/// let report = newton::solve(&mut body, &mut u, 0.0, 1.0, &newton::NewtonSettings::default())?;
/// assert_eq!(report.steps[0].residuals.len(), 2); // one solve, then converged
/// let got = body.nodal_displacements(&u);
/// let scale = expected.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
/// let close = got.iter().flatten().zip(expected.iter().flatten());
/// assert!(close.into_iter().all(|(a, b)| (a - b).abs() < 1e-12 * scale));
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub struct PlasticModel<const D: usize>
where
    Dim<D>: ModelSpace<D>,
{
    pub(super) elastic: ElasticModel<D>,
    pub(super) kinematics: Kinematics,
    /// The laws, with their regions.
    pub(super) laws: Vec<(u32, Arc<dyn ConstitutivePoint>)>,
    /// The law of each element (index into `laws`).
    pub(super) law_of: Vec<usize>,
    /// Element `e`'s points are `offsets[e]..offsets[e + 1]` of the state arrays.
    pub(super) offsets: Vec<usize>,
    pub(super) committed: Vec<PointState>,
    pub(super) trial: Vec<PointState>,
    /// The consistent tangent of each point at its trial state.
    pub(super) tangents: Vec<VoigtMatrix>,
    /// Whether `trial` and `tangents` come from an evaluation since the last rollback.
    pub(super) trial_current: bool,
    /// The tangent's values on the elastic model's pattern (the symmetric part).
    pub(super) values: Vec<f64>,
    /// The full tangent and its LU, when the kind is [`TangentKind::Exact`].
    pub(super) exact: Option<ExactTangent>,
    /// The successful LU factorisations, over every kind change (part of the version).
    lu_updates: u64,
    /// The prescribed values in use, in the dof map's order (the elastic model's).
    prescribed: Vec<f64>,
    /// The prescribed values set for the coming step ([`PlasticModel::set_prescribed`]) and
    /// those of the last commit: the ends of [`Nonlinear::interpolate_prescribed`].
    prescribed_target: Vec<f64>,
    prescribed_committed: Vec<f64>,
    /// Springs added to every assembled tangent, `(lower position, value)`
    /// ([`Nonlinear::set_tangent_springs`], `model_springs.rs`).
    pub(super) springs: Vec<(usize, f64)>,
    scratch: Scratch<D>,
}

/// Buffers of the element loops, reused across calls.
struct Scratch<const D: usize> {
    coords: Vec<[f64; D]>,
    u_e: Vec<f64>,
    f_e: Vec<f64>,
    /// `b[a]`: the Voigt strain of a unit value of local dof `a`.
    b: Vec<Voigt>,
    /// `C b[a]`.
    cb: Vec<Voigt>,
    /// The element tangent, row-major `nd × nd`.
    k_e: Vec<f64>,
}

impl<const D: usize> core::fmt::Debug for PlasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PlasticModel")
            .field("elastic", &self.elastic)
            .field("kinematics", &self.kinematics)
            .field("laws", &self.laws)
            .field("points", &self.committed.len())
            .finish()
    }
}

impl<const D: usize> PlasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// Builds the body on `elastic` with one law per region, takes the elastic model's
    /// initial stress (if any) as the committed stress, and assembles and factorises the
    /// tangent at the committed state.
    ///
    /// # Errors
    /// - [`FemError::MissingMaterial`] if a region of the mesh has no law;
    /// - [`FemError::Unsupported`] in plane stress, or for a floating elastic model;
    /// - [`FemError::OutsideYieldSurface`] if the initial stress is not admissible;
    /// - the factorisation's ([`FemError::NotPositiveDefinite`] for the Cholesky,
    ///   [`FemError::LinearAlgebra`] for the LU).
    ///
    /// The tangent is [`TangentKind::Exact`] when some law's
    /// [`ConstitutivePoint::symmetric_tangent`] is `false`, [`TangentKind::Symmetric`]
    /// otherwise ([`PlasticModel::set_tangent_kind`] changes it).
    pub fn new(
        mut elastic: ElasticModel<D>,
        laws: &[(u32, Arc<dyn ConstitutivePoint>)],
    ) -> Result<Self, FemError> {
        let kinematics = match <Dim<D> as Space>::idealization(elastic.setting()) {
            None => Kinematics::Solid,
            Some(Idealization::PlaneStrain) => Kinematics::PlaneStrain,
            Some(Idealization::Axisymmetric) => Kinematics::Axisymmetric,
            Some(Idealization::PlaneStress { .. }) => {
                return Err(FemError::Unsupported {
                    what: "a plastic body in plane stress (the plastic seam serves plane \
                           strain, axisymmetry and 3D)"
                        .into(),
                });
            }
        };
        if elastic.floating().is_some() {
            return Err(FemError::Unsupported {
                what: "a plastic body on a floating elastic model (its supports leave \
                       rigid-body modes)"
                    .into(),
            });
        }
        let mesh = elastic.mesh();
        let mut law_of = Vec::with_capacity(mesh.element_count());
        let mut offsets = Vec::with_capacity(mesh.element_count() + 1);
        offsets.push(0);
        let mut coords = Vec::new();
        for (e, region) in mesh.regions().iter().enumerate() {
            let Some(law) = laws.iter().position(|(r, _)| r == region) else {
                return Err(FemError::MissingMaterial {
                    region: *region,
                    element: e,
                });
            };
            law_of.push(law);
            mesh.element_coords_into(e, &mut coords);
            let rule = elastic
                .element_at(e)
                .stiffness_rule(elastic.setting(), &coords);
            offsets.push(offsets[e] + rule.len());
        }
        let points = offsets[mesh.element_count()];
        let nodes = mesh.built_in_element().node_count();
        let nd = D * nodes;
        let initial = elastic.take_initial_stress();
        let exact = if laws.iter().all(|(_, law)| law.symmetric_tangent()) {
            None
        } else {
            Some(ExactTangent::new(elastic.pattern())?)
        };
        let mut body = Self {
            exact,
            lu_updates: 0,
            values: vec![0.0; elastic.pattern().nnz()],
            prescribed: elastic.prescribed_values(),
            prescribed_target: elastic.prescribed_values(),
            prescribed_committed: elastic.prescribed_values(),
            springs: Vec::new(),
            kinematics,
            laws: laws.to_vec(),
            law_of,
            offsets,
            committed: vec![PointState::default(); points],
            trial: vec![PointState::default(); points],
            tangents: vec![[[0.0; 6]; 6]; points],
            trial_current: false,
            scratch: Scratch {
                coords: Vec::with_capacity(nodes),
                u_e: vec![0.0; nd],
                f_e: vec![0.0; nd],
                b: vec![[0.0; 6]; nd],
                cb: vec![[0.0; 6]; nd],
                k_e: vec![0.0; nd * nd],
            },
            elastic,
        };
        if !initial.is_empty() {
            body.set_initial_stress_by_region(&initial)?;
        }
        body.update_tangent()?;
        Ok(body)
    }

    /// The tangent the body assembles and factorises.
    #[inline]
    pub fn tangent_kind(&self) -> TangentKind {
        if self.exact.is_some() {
            TangentKind::Exact
        } else {
            TangentKind::Symmetric
        }
    }

    /// Changes the tangent the body assembles and factorises, and refactorises it (at the
    /// trial state of the last evaluation, else at the committed state).
    ///
    /// # Errors
    /// The factorisation's, as [`PlasticModel::new`].
    pub fn set_tangent_kind(&mut self, kind: TangentKind) -> Result<(), FemError> {
        if kind == self.tangent_kind() {
            return Ok(());
        }
        self.exact = match kind {
            TangentKind::Symmetric => None,
            TangentKind::Exact => Some(ExactTangent::new(self.elastic.pattern())?),
        };
        self.update_tangent()
    }

    /// The exact tangent of the last [`Nonlinear::update_tangent`] in full storage (both
    /// triangles), when the kind is [`TangentKind::Exact`].
    pub fn exact_tangent(&self) -> Option<faer::sparse::SparseColMatRef<'_, usize, f64>> {
        self.exact.as_ref().map(ExactTangent::matrix)
    }

    /// The elastic model the body is built on (mesh, supports, loads).
    #[inline]
    pub fn elastic(&self) -> &ElasticModel<D> {
        &self.elastic
    }

    /// The committed state of every quadrature point, element by element
    /// ([`PlasticModel::element_points`]).
    #[inline]
    pub fn committed_states(&self) -> &[PointState] {
        &self.committed
    }

    /// The indices of element `e`'s points in [`PlasticModel::committed_states`] (in the
    /// order of the element's stiffness rule).
    ///
    /// # Panics
    /// If `e` is not an element of the mesh.
    #[track_caller]
    pub fn element_points(&self, e: usize) -> core::ops::Range<usize> {
        self.offsets[e]..self.offsets[e + 1]
    }

    /// Changes the prescribed value of `component` on `nodes`, all of them already
    /// constrained along it (the dof numbering of a plastic body is fixed): a displacement
    /// control, the target of the coming step (a cut step reaches it in sub-steps,
    /// [`Nonlinear::interpolate_prescribed`]). The next [`Nonlinear::internal_force_into`]
    /// sees the new values; run
    /// [`crate::plastic::newton::solve`] with `start == end` for the equilibrium at the same
    /// load factor.
    ///
    /// # Errors
    /// [`FemError::Unsupported`] for a node not yet constrained along `component`;
    /// [`FemError::UnknownNode`], [`FemError::InvalidParameter`] for a non-finite value (as
    /// [`ElasticModel::set_prescribed`]).
    pub fn set_prescribed(
        &mut self,
        nodes: &[usize],
        component: crate::Component,
        value: f64,
    ) -> Result<(), FemError> {
        let supports = self.elastic.supports();
        let node_count = self.elastic.mesh().node_count();
        if let Some(&node) = nodes
            .iter()
            .find(|&&n| n < node_count && supports.value(n, component).is_none())
        {
            return Err(FemError::Unsupported {
                what: format!(
                    "a new support on node {node} ({component:?}) of a plastic body: its dof \
                     numbering is fixed, constrain the dof before building it"
                ),
            });
        }
        // from the targets, not from values a failed cut step left
        self.elastic
            .set_prescribed_values(&self.prescribed_target)?;
        self.elastic.set_prescribed(nodes, component, value)?;
        self.prescribed = self.elastic.prescribed_values();
        self.prescribed_target.clone_from(&self.prescribed);
        Ok(())
    }

    /// Nodal displacements (`D` components per node) from the free-dof solution `u_free`
    /// and the prescribed values ([`ElasticModel::nodal_displacements`]).
    ///
    /// # Panics
    /// If `u_free.len()` is not [`Structure::dof_count`].
    #[track_caller]
    pub fn nodal_displacements(&self, u_free: &[f64]) -> Vec<[f64; D]> {
        self.elastic.nodal_displacements(u_free)
    }

    /// Runs `visit(e, q, k, point)` for every quadrature point `k` (point `q` of element
    /// `e`) with its kinematics (not in the hot loops: it allocates its coordinates).
    pub(super) fn for_each_point(
        &self,
        mut visit: impl FnMut(usize, usize, usize, &Point<D>) -> Result<(), FemError>,
    ) -> Result<(), FemError> {
        let mesh = self.elastic.mesh();
        let setting = self.elastic.setting();
        let mut coords = Vec::new();
        for e in 0..mesh.element_count() {
            mesh.element_coords_into(e, &mut coords);
            let element = self.elastic.element_at(e);
            let rule = element.stiffness_rule(setting, &coords);
            for (q, &qp) in rule.iter().enumerate() {
                let p = kernel::point(element, e, &coords, setting, qp)?;
                visit(e, q, self.offsets[e] + q, &p)?;
            }
        }
        Ok(())
    }

    /// The element loop of the internal forces (`u` given) or of the tangent (`u` is
    /// `None`: the points' tangents at their trial states are assembled into `values`).
    fn element_loop(&mut self, u: Option<&[f64]>, f_int: &mut [f64]) -> Result<(), FemError> {
        let Self {
            elastic,
            kinematics,
            laws,
            law_of,
            offsets,
            committed,
            trial,
            tangents,
            values,
            exact,
            prescribed,
            scratch,
            ..
        } = self;
        let mesh = elastic.mesh();
        let dofs = elastic.dof_map();
        let setting = elastic.setting();
        let pattern = elastic.pattern();
        let Scratch {
            coords,
            u_e,
            f_e,
            b,
            cb,
            k_e,
        } = scratch;
        for e in 0..mesh.element_count() {
            let cell = mesh.element(e);
            let nd = D * cell.len();
            mesh.element_coords_into(e, coords);
            let element = elastic.element_at(e);
            let rule = element.stiffness_rule(setting, coords);
            if let Some(u) = u {
                for (a, &node) in cell.iter().enumerate() {
                    for (c, d) in dofs.dofs(node).iter().enumerate() {
                        u_e[D * a + c] = match *d {
                            Dof::Free(i) => u[i],
                            Dof::Prescribed(p) => prescribed[p],
                        };
                    }
                }
                f_e[..nd].fill(0.0);
            } else {
                k_e[..nd * nd].fill(0.0);
            }
            let law = &*laws[law_of[e]].1;
            for (q, &qp) in rule.iter().enumerate() {
                let k = offsets[e] + q;
                let p = kernel::point(element, e, coords, setting, qp)?;
                strain_vectors(&p, cell.len(), *kinematics, b);
                if u.is_some() {
                    let mut strain = [0.0; 6];
                    for (b_a, u_a) in b.iter().zip(&u_e[..nd]) {
                        for (s, b_ai) in strain.iter_mut().zip(b_a) {
                            *s += b_ai * u_a;
                        }
                    }
                    law.update(&committed[k], &strain, &mut trial[k], &mut tangents[k])?;
                    let stress = &trial[k].stress;
                    for (f, b_a) in f_e.iter_mut().zip(&b[..nd]) {
                        *f += p.weight * dot(b_a, stress);
                    }
                } else if exact.is_some() {
                    // k_e[a][b] = b_a · C b_b: the full element tangent
                    let c = &tangents[k];
                    for (cb_a, b_a) in cb.iter_mut().zip(&b[..nd]) {
                        for (out, row) in cb_a.iter_mut().zip(c) {
                            *out = dot(row, b_a);
                        }
                    }
                    for a in 0..nd {
                        for bb in 0..nd {
                            k_e[a * nd + bb] += p.weight * dot(&b[a], &cb[bb]);
                        }
                    }
                } else {
                    let c = &tangents[k];
                    // sym(C) = (C + Cᵀ) / 2: C itself for an associated law
                    let c_sym: VoigtMatrix =
                        std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (c[i][j] + c[j][i])));
                    for (cb_a, b_a) in cb.iter_mut().zip(&b[..nd]) {
                        for (out, row) in cb_a.iter_mut().zip(&c_sym) {
                            *out = dot(row, b_a);
                        }
                    }
                    for a in 0..nd {
                        for bb in 0..=a {
                            k_e[a * nd + bb] += p.weight * dot(&b[a], &cb[bb]);
                        }
                    }
                }
            }
            let dof = |a: usize| dofs.dofs(cell[a / D])[a % D];
            if u.is_some() {
                for (a, f) in f_e[..nd].iter().enumerate() {
                    if let Dof::Free(i) = dof(a) {
                        f_int[i] += f;
                    }
                }
            } else if let Some(exact) = exact.as_mut() {
                for a in 0..nd {
                    let Dof::Free(i) = dof(a) else { continue };
                    for bb in 0..nd {
                        let Dof::Free(j) = dof(bb) else { continue };
                        if i >= j {
                            let pos = pattern.position(i, j);
                            let (k_ab, k_ba) = (k_e[a * nd + bb], k_e[bb * nd + a]);
                            values[pos] += 0.5 * (k_ab + k_ba);
                            let [ij, ji] = exact.lower_to_full[pos];
                            exact.values[ij] += k_ab;
                            if i != j {
                                exact.values[ji] += k_ba;
                            }
                        }
                    }
                }
            } else {
                for a in 0..nd {
                    let Dof::Free(i) = dof(a) else { continue };
                    for bb in 0..nd {
                        let Dof::Free(j) = dof(bb) else { continue };
                        if i >= j {
                            let k_ab = k_e[a.max(bb) * nd + a.min(bb)];
                            values[pattern.position(i, j)] += k_ab;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// The tangents of the points at their committed states (the trial state made equal to
    /// the committed one): what `update_tangent` assembles when no trial was evaluated.
    fn refresh_from_committed(&mut self) -> Result<(), FemError> {
        for (e, &law) in self.law_of.iter().enumerate() {
            let law = &*self.laws[law].1;
            for k in self.offsets[e]..self.offsets[e + 1] {
                let c = &self.committed[k];
                law.update(c, &c.strain, &mut self.trial[k], &mut self.tangents[k])?;
            }
        }
        self.trial_current = true;
        Ok(())
    }
}

/// `a · b` over the 6 Voigt components.
#[inline]
fn dot(a: &Voigt, b: &Voigt) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `b[D i + c]`: the Voigt strain (engineering shears) of a unit displacement of node `i`
/// along `c`, at the point `p` of an element of `nodes` nodes.
pub(super) fn strain_vectors<const D: usize>(
    p: &Point<D>,
    nodes: usize,
    kinematics: Kinematics,
    b: &mut [Voigt],
) {
    for i in 0..nodes {
        let mut g = [0.0; 3];
        g[..D].copy_from_slice(&p.grad[i]);
        let [gx, gy, gz] = g;
        match kinematics {
            Kinematics::Solid => {
                // [xx, yy, zz, xy, yz, zx]: γ_xy = u,y + v,x; γ_yz = v,z + w,y; γ_zx = w,x + u,z
                b[3 * i] = [gx, 0.0, 0.0, gy, 0.0, gz];
                b[3 * i + 1] = [0.0, gy, 0.0, gx, gz, 0.0];
                b[3 * i + 2] = [0.0, 0.0, gz, 0.0, gy, gx];
            }
            Kinematics::PlaneStrain => {
                b[2 * i] = [gx, 0.0, 0.0, gy, 0.0, 0.0];
                b[2 * i + 1] = [0.0, gy, 0.0, gx, 0.0, 0.0];
            }
            Kinematics::Axisymmetric => {
                // ε_θθ = u_r / r
                b[2 * i] = [gx, 0.0, p.n[i] / p.x[0], gy, 0.0, 0.0];
                b[2 * i + 1] = [0.0, gy, 0.0, gx, 0.0, 0.0];
            }
        }
    }
}

impl<const D: usize> Nonlinear for PlasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// `λ f_ext,ref − K_fp ū`: the elastic model's right-hand side without initial stress
    /// (module docs).
    fn external_force_into(&self, load_factor: f64, f_ext: &mut [f64]) -> Result<(), FemError> {
        self.elastic.external_force_into(load_factor, f_ext)
    }

    #[track_caller]
    fn internal_force_into(&mut self, u: &[f64], f_int: &mut [f64]) -> Result<(), FemError> {
        let n = self.elastic.dof_count();
        assert_eq!(u.len(), n, "displacement length");
        assert_eq!(f_int.len(), n, "internal force length");
        if let Some(i) = u.iter().position(|v| !v.is_finite()) {
            return Err(FemError::NonFiniteSolve {
                what: "displacement",
                node: self.elastic.dof_map().free_dof_owner(i),
                value: u[i],
            });
        }
        f_int.fill(0.0);
        self.trial_current = false;
        self.element_loop(Some(u), f_int)?;
        self.trial_current = true;
        self.elastic
            .subtract_prescribed_coupling(&self.prescribed, f_int);
        Ok(())
    }

    /// Assembles `Σ Bᵀ sym(C_t) B w` on the elastic model's pattern and refactors it
    /// (numeric only) — or, for [`TangentKind::Exact`], `Σ Bᵀ C_t B w` in full storage and
    /// its LU; the stiffness version changes.
    fn update_tangent(&mut self) -> Result<(), FemError> {
        if !self.trial_current {
            self.refresh_from_committed()?;
        }
        self.values.fill(0.0);
        if let Some(exact) = &mut self.exact {
            exact.values.fill(0.0);
        }
        self.element_loop(None, &mut [])?;
        self.add_springs();
        match &mut self.exact {
            Some(exact) => {
                exact.factor()?;
                self.lu_updates += 1;
                Ok(())
            }
            None => self.elastic.factor_values(&self.values),
        }
    }

    fn commit(&mut self) {
        if self.trial_current {
            self.committed.copy_from_slice(&self.trial);
            self.prescribed_committed.clone_from(&self.prescribed);
        }
    }

    fn rollback(&mut self) {
        self.trial.copy_from_slice(&self.committed);
        self.trial_current = false;
    }

    fn set_tangent_springs(&mut self, entries: &[(usize, usize, f64)]) -> Result<(), FemError> {
        self.set_springs(entries)
    }

    /// `ū = ū_c + fraction (ū_s − ū_c)` on every prescribed dof, into the elastic model
    /// too (its `f_ext` couples them, its nodes report them).
    fn interpolate_prescribed(&mut self, fraction: f64) -> Result<(), FemError> {
        if !(0.0..=1.0).contains(&fraction) {
            return Err(FemError::InvalidParameter {
                name: "fraction",
                value: fraction,
                expected: "a fraction of the step in [0, 1]",
            });
        }
        for ((p, c), s) in self
            .prescribed
            .iter_mut()
            .zip(&self.prescribed_committed)
            .zip(&self.prescribed_target)
        {
            *p = if fraction == 1.0 {
                *s
            } else {
                c + fraction * (s - c)
            };
        }
        self.elastic.set_prescribed_values(&self.prescribed)
    }
}

/// The solves are with the tangent of the last [`Nonlinear::update_tangent`] (the elastic
/// tangent of the committed state after construction).
impl<const D: usize> Structure<D> for PlasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    fn outward_normal(&self, node: usize) -> Option<[f64; D]> {
        self.elastic.outward_normal(node)
    }

    fn dof_count(&self) -> usize {
        self.elastic.dof_count()
    }

    fn node_count(&self) -> usize {
        self.elastic.node_count()
    }

    fn node_position(&self, node: usize) -> [f64; D] {
        self.elastic.node_position(node)
    }

    fn node_dofs(&self, node: usize) -> [Option<usize>; D] {
        self.elastic.node_dofs(node)
    }

    fn prescribed_displacement(&self, node: usize) -> [f64; D] {
        self.elastic.prescribed_displacement(node)
    }

    fn idealization(&self) -> Idealization {
        self.elastic.idealization()
    }

    fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), FemError> {
        match &self.exact {
            Some(exact) => {
                let n = rhs.len();
                exact.solve_many_in_place(MatMut::from_column_major_slice_mut(rhs, n, 1))
            }
            None => self.elastic.solve_in_place(rhs),
        }
    }

    fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), FemError> {
        match &self.exact {
            Some(exact) => exact.solve_many_in_place(rhs),
            None => self.elastic.solve_many_in_place(rhs),
        }
    }

    /// The linear response `K_t⁻¹ f_ext(λ)` with the current tangent, from the reference
    /// configuration (the initial stress, in `f_int`, is not in it); the equilibrium of
    /// the body is [`crate::plastic::newton`]'s.
    fn free_response_into(&self, load_factor: f64, u: &mut [f64]) -> Result<(), FemError> {
        if self.exact.is_none() {
            return self.elastic.free_response_into(load_factor, u);
        }
        self.elastic.external_force_into(load_factor, u)?;
        self.solve_in_place(u)?;
        match u.iter().position(|v| !v.is_finite()) {
            None => Ok(()),
            Some(i) => Err(FemError::NonFiniteSolve {
                what: "displacement",
                node: self.elastic.dof_map().free_dof_owner(i),
                value: u[i],
            }),
        }
    }

    /// The elastic model's version plus the LU factorisations of the exact tangent: it
    /// changes at every tangent update of either kind.
    fn stiffness_version(&self) -> u64 {
        self.elastic.stiffness_version() + self.lu_updates
    }

    /// The symmetric part of the tangent of the last [`Nonlinear::update_tangent`] (lower
    /// triangle; the exact tangent itself is [`PlasticModel::exact_tangent`]).
    fn stiffness_matrix(&self) -> Option<faer::sparse::SparseColMatRef<'_, usize, f64>> {
        Some(self.elastic.pattern().view(&self.values))
    }

    fn mass(&self) -> Option<&dyn Mass> {
        self.elastic.mass()
    }

    fn nonlinear(&mut self) -> Option<&mut dyn Nonlinear> {
        Some(self)
    }
}
