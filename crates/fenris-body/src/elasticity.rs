//! Isotropic linear elasticity in plane strain as a fenris operator: what fenris asks of a
//! user to assemble a stiffness (it ships the Laplace operator only).

use fenris::Symmetry;
use fenris::assembly::local::SourceFunction;
use fenris::assembly::operators::{EllipticContraction, EllipticOperator, Operator};
use fenris::nalgebra::{Matrix2, Point2, U2, Vector2};

use crate::error::FenrisBodyError;

/// Plane-strain isotropic linear elasticity (Lamé constants from `E` and `ν`), the elliptic
/// operator `σ(∇u)` and its contraction for fenris's assemblers.
///
/// The stiffness block between nodes `I` and `J` (shape-function gradients `a = ∇φ_I`,
/// `b = ∇φ_J`) is
/// ```text
/// K_IJ[i][j] = λ a_i b_j + μ a_j b_i + μ (a · b) δ_ij
/// ```
/// (`ε(φ_I e_i) : C : ε(φ_J e_j)`), the same bilinear form as fem-core's plane-strain
/// triangles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneStrainElasticity {
    lambda: f64,
    mu: f64,
}

impl PlaneStrainElasticity {
    /// From Young's modulus `young > 0` and Poisson's ratio `-1 < poisson < 0.5`.
    ///
    /// # Errors
    /// [`FenrisBodyError::InvalidParameter`] naming `young` or `poisson` when it is out of
    /// range or not finite.
    pub fn new(young: f64, poisson: f64) -> Result<Self, FenrisBodyError> {
        if !(young.is_finite() && young > 0.0) {
            return Err(FenrisBodyError::InvalidParameter {
                name: "young",
                value: young,
                reason: "must be finite and > 0",
            });
        }
        if !(poisson.is_finite() && poisson > -1.0 && poisson < 0.5) {
            return Err(FenrisBodyError::InvalidParameter {
                name: "poisson",
                value: poisson,
                reason: "must lie in (-1, 0.5)",
            });
        }
        Ok(Self {
            lambda: young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)),
            mu: young / (2.0 * (1.0 + poisson)),
        })
    }
}

impl Operator<f64, U2> for PlaneStrainElasticity {
    type SolutionDim = U2;
    type Parameters = ();
}

impl EllipticOperator<f64, U2> for PlaneStrainElasticity {
    /// `σ = λ tr(ε) I + 2 μ ε` with `ε = sym(∇u)` (fenris's gradient is `G[k][i] = ∂u_i/∂x_k`;
    /// `σ` is symmetric, so its layout does not matter).
    fn compute_elliptic_operator(&self, gradient: &Matrix2<f64>, _parameters: &()) -> Matrix2<f64> {
        let eps = (gradient + gradient.transpose()) * 0.5;
        Matrix2::identity() * (self.lambda * eps.trace()) + eps * (2.0 * self.mu)
    }
}

impl EllipticContraction<f64, U2> for PlaneStrainElasticity {
    fn contract(
        &self,
        _gradient: &Matrix2<f64>,
        a: &Vector2<f64>,
        b: &Vector2<f64>,
        _parameters: &(),
    ) -> Matrix2<f64> {
        a * b.transpose() * self.lambda
            + b * a.transpose() * self.mu
            + Matrix2::identity() * (self.mu * a.dot(b))
    }

    fn symmetry(&self) -> Symmetry {
        Symmetry::Symmetric
    }
}

/// A uniform body force (force per unit volume), fenris's source term `∫ b · φ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BodyForce(pub(crate) [f64; 2]);

impl Operator<f64, U2> for BodyForce {
    type SolutionDim = U2;
    type Parameters = ();
}

impl SourceFunction<f64, U2> for BodyForce {
    fn evaluate(&self, _coords: &Point2<f64>, _data: &()) -> Vector2<f64> {
        Vector2::new(self.0[0], self.0[1])
    }
}
