//! [`DynamicModel`]: an [`ElasticModel`] whose solves are with the iteration matrix of a
//! θ-method on `M ü + C u̇ + K u = f`, for a velocity-level time scheme (Moreau–Jean; Jean
//! 1999 eq. 19, Acary & Brogliato 2008 §10.1).
//!
//! ```text
//! M̂ = M + hθ C + h²θ² K,     C = α M + β K              (Rayleigh damping)
//!   = (1 + hθα) M + (hθβ + h²θ²) K                      (on the pattern of K)
//! ```
//! `M` is the consistent mass or its HRZ lumped diagonal ([`MassKind`]). `M̂` is factorised
//! once per `(h, θ)` ([`DynamicModel::set_step`]): a new step size refactors (numeric
//! factorisation only; the symbolic one is per pattern) and changes
//! [`Structure::stiffness_version`], so a contact solver rebuilds its `F* = H M̂⁻¹ Hᵀ`.
//! `M̂` is positive definite whenever `M` is, so a body that only contact holds (built with
//! `floating`) is no longer floating here: its rigid motions have inertia.

use crate::assembly::lower_symmetric_mul_into;
use crate::error::FemError;
use crate::linear_solver::SpdSolver;
use crate::model::{ElasticModel, ModelSpace};
use crate::space::Dim;
use crate::structure::{Mass, Structure};
use crate::{Idealization, error::positive};
use core::sync::atomic::{AtomicUsize, Ordering};
use faer::MatMut;
use faer::sparse::SparseColMatRef;

/// The error of a model without mass.
const NO_MASS: FemError = FemError::MissingMethod {
    method: "mass",
    reason: "a dynamic model needs a density in every region's material",
};

/// Which mass a [`DynamicModel`] integrates with.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum MassKind {
    /// The consistent mass `∫ ρ Nᵀ N` (the default): no spurious dispersion at low
    /// frequencies, but oscillating contact forces under impact.
    #[default]
    Consistent,
    /// The HRZ lumped diagonal ([`Mass::lumped`]): the contact nodes' own inertia is their
    /// share of the element mass, which smooths impact forces.
    Lumped,
}

/// Rayleigh damping `C = α M + β K` (`alpha` per time, `beta` time; both `≥ 0`, the default
/// none).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rayleigh {
    /// The mass-proportional coefficient `α` (1/time).
    pub alpha: f64,
    /// The stiffness-proportional coefficient `β` (time).
    pub beta: f64,
}

/// An [`ElasticModel`] solved with `M̂ = M + hθC + h²θ²K` (module docs): the structure a
/// velocity-level contact scheme runs on. It answers [`Structure`] with `M̂` in place of `K`
/// ([`Structure::free_response_into`] is `M̂⁻¹ f`), is never floating, and offers the products
/// a scheme needs ([`Self::mass_mul_into`], [`Self::stiffness_mul_into`],
/// [`Self::damping_mul_into`], [`Self::load_into`]).
///
/// # Examples
/// A free P1 square of density 2: `M̂` solves a uniform force into a uniform acceleration
/// (`h = 0.1`, `θ = 1/2`: `M̂ v = M v` for a rigid translation, since `K v = 0`).
/// ```
/// use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
/// use fem_core::generate::{RectangleSpec, rectangle};
/// use fem_core::{Idealization, LinearElasticModel, Material, Structure, Supports};
/// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2))?;
/// let steel = Material::new(200.0, 0.3, 0.0)?.with_density(2.0)?;
/// let model = LinearElasticModel::floating(mesh, Idealization::PlaneStrain,
///     &[(0, steel)], Supports::new())?;
/// let mut dynamic = DynamicModel::new(model, MassKind::Lumped, Rayleigh::default())?;
/// dynamic.set_step(0.1, 0.5)?;
/// let n = dynamic.dof_count();
/// let t: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 1.0 } else { 0.0 }).collect();
/// let mut f = vec![0.0; n];
/// dynamic.mass_mul_into(&t, &mut f); // the force of a unit acceleration along x
/// dynamic.solve_in_place(&mut f)?;
/// assert!(f.iter().zip(&t).all(|(a, b)| (a - b).abs() < 1e-12));
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub struct DynamicModel<const D: usize = 2>
where
    Dim<D>: ModelSpace<D>,
{
    model: ElasticModel<D>,
    mass_kind: MassKind,
    damping: Rayleigh,
    /// `(h, θ)` of the factorised `M̂` (`None` before [`DynamicModel::set_step`]).
    step: Option<(f64, f64)>,
    /// The lower triangle of `M̂` on the pattern of `K`.
    values: Vec<f64>,
    /// The position of each diagonal entry in `values`.
    diagonal: Vec<usize>,
    solver: Option<SpdSolver>,
    /// The model's stiffness version `M̂` was formed with.
    model_version: u64,
    version: u64,
    /// Back-substitutions with `M̂` so far ([`DynamicModel::solve_count`]).
    solves: AtomicUsize,
}

impl<const D: usize> core::fmt::Debug for DynamicModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("DynamicModel")
            .field("model", &self.model)
            .field("mass_kind", &self.mass_kind)
            .field("damping", &self.damping)
            .field("step", &self.step)
            .field("version", &self.version)
            .field("solves", &self.solve_count())
            .finish()
    }
}

impl<const D: usize> DynamicModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// Wraps `model` (2D or 3D) with its mass of kind `mass` and Rayleigh `damping`; `M̂` is
    /// formed by the first [`Self::set_step`].
    ///
    /// # Errors
    /// [`FemError::MissingMethod`] (`mass`) if the model has no mass (no region's material
    /// has a density: [`Material::with_density`](crate::Material::with_density));
    /// [`FemError::InvalidParameter`] naming `alpha` or `beta` if one is negative or not
    /// finite.
    pub fn new(
        model: ElasticModel<D>,
        mass: MassKind,
        damping: Rayleigh,
    ) -> Result<Self, FemError> {
        for (name, value) in [("alpha", damping.alpha), ("beta", damping.beta)] {
            crate::error::non_negative(name, value)?;
        }
        if model.mass().is_none() {
            return Err(NO_MASS);
        }
        let mut dynamic = Self {
            model,
            mass_kind: mass,
            damping,
            step: None,
            values: Vec::new(),
            diagonal: Vec::new(),
            solver: None,
            model_version: 0,
            version: 0,
            solves: AtomicUsize::new(0),
        };
        dynamic.follow_model()?;
        Ok(dynamic)
    }

    /// The wrapped model.
    pub fn model(&self) -> &ElasticModel<D> {
        &self.model
    }

    /// Changes the wrapped model through `change` (its loads, prescribed values, supports),
    /// then re-forms `M̂` if its stiffness or numbering changed.
    ///
    /// # Errors
    /// As [`Self::set_step`] when `M̂` is re-formed.
    pub fn update<R>(
        &mut self,
        change: impl FnOnce(&mut ElasticModel<D>) -> R,
    ) -> Result<R, FemError> {
        let out = change(&mut self.model);
        if self.model.stiffness_version() != self.model_version {
            self.follow_model()?;
            if let Some((h, theta)) = self.step.take() {
                self.set_step(h, theta)?;
            }
        }
        Ok(out)
    }

    /// The mass kind.
    pub fn mass_kind(&self) -> MassKind {
        self.mass_kind
    }

    /// The Rayleigh damping.
    pub fn damping(&self) -> Rayleigh {
        self.damping
    }

    /// The number of back-substitutions with `M̂` since construction: one per
    /// [`Structure::solve_in_place`], one per column of [`Structure::solve_many_in_place`]
    /// (a relaxed atomic counter, so the cost of a solve is unchanged). A velocity-level scheme
    /// needs two per step without contact changes (`v_free`, then `M̂⁻¹ Hᵀ r`); building
    /// `F* = H M̂⁻¹ Hᵀ` adds one per contact column, once per step size. A solver that
    /// factorises `M̂` itself (through [`Structure::stiffness_matrix`], as the contact
    /// solver's primal active set does) counts its own solves.
    ///
    /// # Examples
    /// ```
    /// use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
    /// use fem_core::generate::{RectangleSpec, rectangle};
    /// use fem_core::{Idealization, LinearElasticModel, Material, Structure, Supports};
    /// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2))?;
    /// let m = Material::new(200.0, 0.3, 0.0)?.with_density(2.0)?;
    /// let model = LinearElasticModel::floating(mesh, Idealization::PlaneStrain,
    ///     &[(0, m)], Supports::new())?;
    /// let mut dynamic = DynamicModel::new(model, MassKind::Lumped, Rayleigh::default())?;
    /// dynamic.set_step(0.1, 0.5)?;
    /// let mut b = vec![1.0; dynamic.dof_count()];
    /// dynamic.solve_in_place(&mut b)?;
    /// assert_eq!(dynamic.solve_count(), 1);
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    pub fn solve_count(&self) -> usize {
        self.solves.load(Ordering::Relaxed)
    }

    /// The `(h, θ)` that `M̂` is factorised for, `None` before the first [`Self::set_step`].
    pub fn step(&self) -> Option<(f64, f64)> {
        self.step
    }

    /// Forms and factorises `M̂` for the step `h` and the weight `θ`; nothing to do (no
    /// factorisation, same version) when they are the ones already factorised.
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] naming `h` (not finite and positive) or `theta` (not in
    /// `[1/2, 1]`); a factorisation error (a non-positive pivot: a node without mass and
    /// stiffness).
    pub fn set_step(&mut self, h: f64, theta: f64) -> Result<(), FemError> {
        positive("h", h)?;
        if !(0.5..=1.0).contains(&theta) {
            return Err(FemError::InvalidParameter {
                name: "theta",
                value: theta,
                expected: "a weight in [1/2, 1]",
            });
        }
        if self.step == Some((h, theta)) {
            return Ok(());
        }
        let (a, b) = self.coefficients(h, theta);
        let k = self.model.stiffness();
        let k_values = k.val();
        let mass = self.model.mass().ok_or(NO_MASS)?;
        match self.mass_kind {
            MassKind::Consistent => {
                let m = mass.matrix().ok_or(FemError::MissingMethod {
                    method: "Mass::matrix",
                    reason: "the consistent mass must be assembled on the stiffness pattern",
                })?;
                for ((v, m), k) in self.values.iter_mut().zip(m.val()).zip(k_values) {
                    *v = a * m + b * k;
                }
            }
            MassKind::Lumped => {
                for (v, k) in self.values.iter_mut().zip(k_values) {
                    *v = b * k;
                }
                for (&p, m) in self.diagonal.iter().zip(mass.lumped()) {
                    self.values[p] += a * m;
                }
            }
        }
        let view = SparseColMatRef::new(k.symbolic(), &self.values);
        let solver = self.solver.as_mut().expect("formed by follow_model");
        self.step = None;
        solver.factor(view)?;
        self.step = Some((h, theta));
        self.version += 1;
        Ok(())
    }

    /// `y = M x` with the mass of [`Self::mass_kind`], on the free dofs.
    ///
    /// # Panics
    /// If `x` or `y` is not [`Structure::dof_count`] long.
    #[track_caller]
    pub fn mass_mul_into(&self, x: &[f64], y: &mut [f64]) {
        let mass = self.model.mass().expect("checked by the constructor");
        match self.mass_kind {
            MassKind::Consistent => mass.mul_into(x, y),
            MassKind::Lumped => {
                assert!(
                    x.len() == y.len() && x.len() == mass.lumped().len(),
                    "lengths"
                );
                for ((y, x), m) in y.iter_mut().zip(x).zip(mass.lumped()) {
                    *y = m * x;
                }
            }
        }
    }

    /// `y = K x` on the free dofs.
    ///
    /// # Panics
    /// If `x` or `y` is not [`Structure::dof_count`] long.
    #[track_caller]
    pub fn stiffness_mul_into(&self, x: &[f64], y: &mut [f64]) {
        symmetric_mul_into(self.model.stiffness(), x, y);
    }

    /// `y = C x = α M x + β K x` on the free dofs (zero without damping).
    ///
    /// # Panics
    /// If `x` or `y` is not [`Structure::dof_count`] long.
    #[track_caller]
    pub fn damping_mul_into(&self, x: &[f64], y: &mut [f64]) {
        let Rayleigh { alpha, beta } = self.damping;
        y.fill(0.0);
        let mut t = vec![0.0; y.len()];
        if alpha != 0.0 {
            self.mass_mul_into(x, &mut t);
            y.iter_mut().zip(&t).for_each(|(y, t)| *y += alpha * t);
        }
        if beta != 0.0 {
            self.stiffness_mul_into(x, &mut t);
            y.iter_mut().zip(&t).for_each(|(y, t)| *y += beta * t);
        }
    }

    /// `y = M̂ x` with the factorised `M̂` on the free dofs.
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] naming `h` before the first [`Self::set_step`].
    ///
    /// # Panics
    /// If `x` or `y` is not [`Structure::dof_count`] long.
    #[track_caller]
    pub fn iteration_mul_into(&self, x: &[f64], y: &mut [f64]) -> Result<(), FemError> {
        self.factored()?;
        let view = SparseColMatRef::new(self.model.stiffness().symbolic(), &self.values);
        symmetric_mul_into(view, x, y);
        Ok(())
    }

    /// The load `f` at `load_factor` on the free dofs ([`ElasticModel::rhs_into`]: applied
    /// forces scaled, initial stresses and prescribed values at their values).
    ///
    /// # Errors
    /// [`FemError::NonFiniteSolve`] for a non-finite factor or load.
    pub fn load_into(&self, load_factor: f64, f: &mut [f64]) -> Result<(), FemError> {
        if !load_factor.is_finite() {
            return Err(FemError::NonFiniteSolve {
                what: "load factor",
                node: None,
                value: load_factor,
            });
        }
        self.model.rhs_into(load_factor, f);
        match f.iter().find(|v| !v.is_finite()) {
            Some(&value) => Err(FemError::NonFiniteSolve {
                what: "load",
                node: None,
                value,
            }),
            None => Ok(()),
        }
    }

    /// `(1 + hθα, hθβ + h²θ²)`: `M̂ = a M + b K`.
    fn coefficients(&self, h: f64, theta: f64) -> (f64, f64) {
        let c = h * theta;
        (1.0 + c * self.damping.alpha, c * self.damping.beta + c * c)
    }

    fn factored(&self) -> Result<&SpdSolver, FemError> {
        match (&self.solver, self.step) {
            (Some(solver), Some(_)) => Ok(solver),
            _ => Err(FemError::InvalidParameter {
                name: "h",
                value: f64::NAN,
                expected: "a step set by `DynamicModel::set_step` before solving",
            }),
        }
    }

    /// The pattern's diagonal positions and a fresh symbolic factorisation, for the model's
    /// current numbering (`M̂` to be formed again).
    fn follow_model(&mut self) -> Result<(), FemError> {
        let k = self.model.stiffness();
        let (col_ptr, row_idx) = (k.symbolic().col_ptr(), k.symbolic().row_idx());
        self.diagonal = (0..k.ncols())
            .map(|j| {
                (col_ptr[j]..col_ptr[j + 1])
                    .find(|&p| row_idx[p] == j)
                    .ok_or(FemError::MissingMethod {
                        method: "stiffness_matrix",
                        reason: "every diagonal entry of the stiffness must be stored",
                    })
            })
            .collect::<Result<_, _>>()?;
        self.values = vec![0.0; k.val().len()];
        self.solver = Some(SpdSolver::new(k.symbolic())?);
        self.model_version = self.model.stiffness_version();
        self.step = None;
        self.version += 1;
        Ok(())
    }
}

/// `y = A x` for the symmetric `A` given by its lower triangle.
#[track_caller]
fn symmetric_mul_into(a: SparseColMatRef<'_, usize, f64>, x: &[f64], y: &mut [f64]) {
    let n = a.ncols();
    assert!(
        x.len() == n && y.len() == n,
        "x and y of the matrix's dimension"
    );
    let symbolic = a.symbolic();
    lower_symmetric_mul_into(symbolic.col_ptr(), symbolic.row_idx(), a.val(), x, y);
}

/// `K` replaced by `M̂` in every solve; the geometry and dofs are the model's.
impl<const D: usize> Structure<D> for DynamicModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    fn dof_count(&self) -> usize {
        self.model.dof_count()
    }

    fn node_count(&self) -> usize {
        self.model.node_count()
    }

    fn node_position(&self, node: usize) -> [f64; D] {
        self.model.node_position(node)
    }

    fn node_dofs(&self, node: usize) -> [Option<usize>; D] {
        self.model.node_dofs(node)
    }

    fn prescribed_displacement(&self, node: usize) -> [f64; D] {
        self.model.prescribed_displacement(node)
    }

    fn idealization(&self) -> Idealization {
        self.model.idealization()
    }

    fn outward_normal(&self, node: usize) -> Option<[f64; D]> {
        self.model.outward_normal(node)
    }

    /// Solves `M̂ x = b`.
    fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), FemError> {
        self.factored()?.solve_in_place(rhs);
        self.solves.fetch_add(1, Ordering::Relaxed);
        Ok(())
    }

    /// Solves `M̂ X = B`.
    fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), FemError> {
        let columns = rhs.ncols();
        self.factored()?.solve_many_in_place(rhs);
        self.solves.fetch_add(columns, Ordering::Relaxed);
        Ok(())
    }

    /// `M̂⁻¹ f` at `load_factor` (the response of one step from rest to the load over `h`,
    /// up to the factor `h`; a velocity-level scheme forms its own free response).
    fn free_response_into(&self, load_factor: f64, u: &mut [f64]) -> Result<(), FemError> {
        self.load_into(load_factor, u)?;
        self.solve_in_place(u)
    }

    fn stiffness_version(&self) -> u64 {
        self.version
    }

    /// `M̂` (lower triangle, on the pattern of `K`): the matrix the solves are with.
    fn stiffness_matrix(&self) -> Option<SparseColMatRef<'_, usize, f64>> {
        self.step?;
        Some(SparseColMatRef::new(
            self.model.stiffness().symbolic(),
            &self.values,
        ))
    }

    fn mass(&self) -> Option<&dyn Mass> {
        self.model.mass()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{RectangleSpec, rectangle};
    use crate::{LinearElasticModel, Material, Supports};

    fn square() -> LinearElasticModel {
        let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2)).unwrap();
        let m = Material::new(100.0, 0.3, 0.0)
            .unwrap()
            .with_density(3.0)
            .unwrap();
        LinearElasticModel::floating(mesh, Idealization::PlaneStrain, &[(0, m)], Supports::new())
            .unwrap()
    }

    #[test]
    fn iteration_matrix_works() {
        // M̂ x = (1 + hθα) M x + (hθβ + h²θ²) K x for a random-ish x (round-off only)
        let damping = Rayleigh {
            alpha: 0.3,
            beta: 0.01,
        };
        for kind in [MassKind::Consistent, MassKind::Lumped] {
            let mut d = DynamicModel::new(square(), kind, damping).unwrap();
            d.set_step(0.2, 0.75).unwrap();
            let n = d.dof_count();
            let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin()).collect();
            let (mut mx, mut kx, mut hx) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            d.mass_mul_into(&x, &mut mx);
            d.stiffness_mul_into(&x, &mut kx);
            d.iteration_mul_into(&x, &mut hx).unwrap();
            let c = 0.2 * 0.75;
            for i in 0..n {
                let expected = (1.0 + c * 0.3) * mx[i] + (c * 0.01 + c * c) * kx[i];
                assert!((hx[i] - expected).abs() < 1e-12 * (1.0 + expected.abs()));
            }
            // the solve inverts the product
            d.solve_in_place(&mut hx).unwrap();
            assert!(hx.iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-10));
        }
    }

    #[test]
    fn set_step_refactors_only_on_change() {
        let mut d = DynamicModel::new(square(), MassKind::Consistent, Rayleigh::default()).unwrap();
        d.set_step(0.1, 0.5).unwrap();
        let v = d.stiffness_version();
        d.set_step(0.1, 0.5).unwrap();
        assert_eq!(d.stiffness_version(), v);
        d.set_step(0.05, 0.5).unwrap();
        assert_eq!(d.stiffness_version(), v + 1);
    }

    #[test]
    fn solve_count_works() {
        // one per single solve, one per column of a many-solve; a failed solve (no step) none
        let mut d = DynamicModel::new(square(), MassKind::Lumped, Rayleigh::default()).unwrap();
        let n = d.dof_count();
        assert!(d.solve_in_place(&mut vec![1.0; n]).is_err());
        assert_eq!(d.solve_count(), 0);
        d.set_step(0.1, 0.5).unwrap();
        d.solve_in_place(&mut vec![1.0; n]).unwrap();
        let mut many = faer::Mat::<f64>::zeros(n, 3);
        d.solve_many_in_place(many.as_mut()).unwrap();
        assert_eq!(d.solve_count(), 4);
    }

    #[test]
    fn dynamic_model_rejects_bad_input() {
        let mut d = DynamicModel::new(square(), MassKind::Lumped, Rayleigh::default()).unwrap();
        let mut b = vec![1.0; d.dof_count()];
        assert!(matches!(
            d.solve_in_place(&mut b),
            Err(FemError::InvalidParameter { name: "h", .. })
        ));
        for theta in [0.4, 1.1, f64::NAN] {
            assert!(matches!(
                d.set_step(0.1, theta),
                Err(FemError::InvalidParameter { name: "theta", .. })
            ));
        }
        assert!(matches!(
            d.set_step(0.0, 0.5),
            Err(FemError::InvalidParameter { name: "h", .. })
        ));
        let bad = Rayleigh {
            alpha: -1.0,
            beta: 0.0,
        };
        assert!(matches!(
            DynamicModel::new(square(), MassKind::Lumped, bad),
            Err(FemError::InvalidParameter { name: "alpha", .. })
        ));
        let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 1, 1)).unwrap();
        let m = Material::new(100.0, 0.3, 0.0).unwrap();
        let massless = LinearElasticModel::floating(
            mesh,
            Idealization::PlaneStrain,
            &[(0, m)],
            Supports::new(),
        )
        .unwrap();
        assert!(matches!(
            DynamicModel::new(massless, MassKind::Lumped, Rayleigh::default()),
            Err(FemError::MissingMethod { method: "mass", .. })
        ));
    }
}
