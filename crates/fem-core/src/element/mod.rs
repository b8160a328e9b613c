//! Elements: the [`Element`] trait and the isoparametric triangles [`Tri3`] and [`Tri6`].
//!
//! "Which dofs an element touches" lives in the mesh and the dof map; an element only
//! computes local arrays from its node coordinates, into buffers the caller reuses.
//! Local dof order: `(u_0, v_0, u_1, v_1, …)`.

pub mod tri3;
pub mod tri6;

use crate::error::FemError;
use crate::idealization::Idealization;
use crate::material::Material;
use crate::quadrature::{TRI_1, TRI_3, TRI_6, TriPoint};
use nalgebra::{DMatrix, Matrix4};

/// Largest number of nodes of a built-in element (scratch arrays are sized by it).
pub const MAX_NODES: usize = 6;

/// Stress (or strain) components: `(xx, yy, xy, zz)` in the plane — `zz` is the out-of-plane
/// stress `ν(σ_xx + σ_yy)` in plane strain and 0 in plane stress — and `(rr, zz, rz, θθ)` in
/// axisymmetry.
pub type Stress = [f64; 4];

/// A finite element of linear elasticity, as the assembly consumes it.
pub trait Element {
    /// Number of nodes.
    fn node_count(&self) -> usize;

    /// The element stiffness `K_e = ∫ Bᵀ D B w dA` (`w` = 1, thickness or `r`), of size
    /// `2n × 2n`, written into `k_e` (resized if needed). `element` is only used in errors.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] if the Jacobian is not positive at a quadrature point.
    fn stiffness_into(
        &self,
        element: usize,
        coords: &[[f64; 2]],
        material: &Material,
        idealization: &Idealization,
        k_e: &mut DMatrix<f64>,
    ) -> Result<(), FemError>;

    /// Adds `f_e += ∫ Nᵀ b w dA` for a body force density `b(x)` (force per volume).
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] as for the stiffness.
    fn body_force_into(
        &self,
        element: usize,
        coords: &[[f64; 2]],
        idealization: &Idealization,
        b: &dyn Fn([f64; 2]) -> [f64; 2],
        f_e: &mut [f64],
    ) -> Result<(), FemError>;

    /// Adds the internal force of an initial stress field, `f_e −= ∫ Bᵀ σ₀ w dA`, so that
    /// the equilibrium `K u = f_ext + f_e` accounts for `σ₀(x)` (components as [`Stress`]).
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] as for the stiffness.
    fn initial_stress_force_into(
        &self,
        element: usize,
        coords: &[[f64; 2]],
        idealization: &Idealization,
        sigma_0: &dyn Fn([f64; 2]) -> Stress,
        f_e: &mut [f64],
    ) -> Result<(), FemError>;

    /// Stresses `σ = D B u_e` (plus nothing else: add `σ₀` yourself) at the quadrature points
    /// of the element's stiffness rule, with their positions; returns how many were written.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] as for the stiffness.
    fn stresses_into(
        &self,
        element: usize,
        coords: &[[f64; 2]],
        material: &Material,
        idealization: &Idealization,
        u_e: &[f64],
        out: &mut Vec<([f64; 2], Stress)>,
    ) -> Result<(), FemError>;
}

/// The 3-node linear triangle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tri3;

/// The 6-node quadratic isoparametric triangle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tri6;

type ShapeFn = fn([f64; 2], &mut [f64]);
type ShapeDerivFn = fn([f64; 2], &mut [[f64; 2]]);

/// Kinematics at one quadrature point: shape values, Cartesian gradients, position, weight.
struct Point {
    n: [f64; MAX_NODES],
    grad: [[f64; 2]; MAX_NODES],
    x: [f64; 2],
    /// Quadrature weight × det J × idealisation weight.
    weight: f64,
}

/// The isoparametric kinematics shared by [`Tri3`] and [`Tri6`].
#[derive(Clone, Copy)]
struct Iso {
    nodes: usize,
    shape: ShapeFn,
    dshape: ShapeDerivFn,
}

impl Iso {
    fn point(
        &self,
        element: usize,
        coords: &[[f64; 2]],
        idealization: &Idealization,
        (xi, w): TriPoint,
    ) -> Result<Point, FemError> {
        let mut p = Point {
            n: [0.0; MAX_NODES],
            grad: [[0.0; 2]; MAX_NODES],
            x: [0.0; 2],
            weight: 0.0,
        };
        let mut dn = [[0.0; 2]; MAX_NODES];
        (self.shape)(xi, &mut p.n[..self.nodes]);
        (self.dshape)(xi, &mut dn[..self.nodes]);
        // J = [∂x/∂ξ ∂x/∂η; ∂y/∂ξ ∂y/∂η]
        let mut j = [[0.0; 2]; 2];
        for i in 0..self.nodes {
            for a in 0..2 {
                p.x[a] += p.n[i] * coords[i][a];
                for b in 0..2 {
                    j[a][b] += coords[i][a] * dn[i][b];
                }
            }
        }
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det.is_nan() || det <= 0.0 {
            return Err(FemError::InvertedElement {
                element,
                det_j: det,
            });
        }
        // ∇N = J⁻ᵀ ∂N/∂ξ
        for (g, &[dxi, deta]) in p.grad.iter_mut().zip(&dn).take(self.nodes) {
            *g = [
                (j[1][1] * dxi - j[1][0] * deta) / det,
                (-j[0][1] * dxi + j[0][0] * deta) / det,
            ];
        }
        p.weight = w * det * idealization.weight(p.x[0]);
        Ok(p)
    }

    /// Strain–displacement matrix `B` (rows: xx, yy, xy[, θθ]) at a point.
    fn b_matrix(&self, p: &Point, idealization: &Idealization) -> [[f64; 2 * MAX_NODES]; 4] {
        let mut b = [[0.0; 2 * MAX_NODES]; 4];
        let axi = matches!(idealization, Idealization::Axisymmetric);
        for i in 0..self.nodes {
            let [gx, gy] = p.grad[i];
            b[0][2 * i] = gx;
            b[1][2 * i + 1] = gy;
            b[2][2 * i] = gy;
            b[2][2 * i + 1] = gx;
            if axi {
                b[3][2 * i] = p.n[i] / p.x[0];
            }
        }
        b
    }

    fn rule(&self, idealization: &Idealization) -> &'static [TriPoint] {
        match (self.nodes, idealization) {
            (3, Idealization::Axisymmetric) => &TRI_3,
            (3, _) => &TRI_1,
            (_, Idealization::Axisymmetric) => &TRI_6,
            _ => &TRI_3,
        }
    }

    /// A rule exact for `N` times the idealisation weight (loads).
    fn load_rule(&self, idealization: &Idealization) -> &'static [TriPoint] {
        match (self.nodes, idealization) {
            (3, Idealization::Axisymmetric) => &TRI_3,
            (3, _) => &TRI_3,
            _ => &TRI_6,
        }
    }

    fn stiffness_into(
        &self,
        element: usize,
        coords: &[[f64; 2]],
        material: &Material,
        idealization: &Idealization,
        k_e: &mut DMatrix<f64>,
    ) -> Result<(), FemError> {
        let nd = 2 * self.nodes;
        if k_e.nrows() != nd || k_e.ncols() != nd {
            *k_e = DMatrix::zeros(nd, nd);
        } else {
            k_e.fill(0.0);
        }
        let d: Matrix4<f64> = material.elasticity(idealization);
        let m = idealization.strain_size();
        for &q in self.rule(idealization) {
            let p = self.point(element, coords, idealization, q)?;
            let b = self.b_matrix(&p, idealization);
            // DB = D B (m × nd), then K += Bᵀ (DB) w
            let mut db = [[0.0; 2 * MAX_NODES]; 4];
            for r in 0..m {
                for c in 0..nd {
                    db[r][c] = (0..m).map(|k| d[(r, k)] * b[k][c]).sum();
                }
            }
            for a in 0..nd {
                for c in a..nd {
                    let v: f64 = (0..m).map(|k| b[k][a] * db[k][c]).sum::<f64>() * p.weight;
                    k_e[(a, c)] += v;
                }
            }
        }
        for a in 0..nd {
            for c in 0..a {
                k_e[(a, c)] = k_e[(c, a)];
            }
        }
        Ok(())
    }

    fn body_force_into(
        &self,
        element: usize,
        coords: &[[f64; 2]],
        idealization: &Idealization,
        b: &dyn Fn([f64; 2]) -> [f64; 2],
        f_e: &mut [f64],
    ) -> Result<(), FemError> {
        for &q in self.load_rule(idealization) {
            let p = self.point(element, coords, idealization, q)?;
            let bx = b(p.x);
            for i in 0..self.nodes {
                f_e[2 * i] += p.n[i] * bx[0] * p.weight;
                f_e[2 * i + 1] += p.n[i] * bx[1] * p.weight;
            }
        }
        Ok(())
    }

    fn initial_stress_force_into(
        &self,
        element: usize,
        coords: &[[f64; 2]],
        idealization: &Idealization,
        sigma_0: &dyn Fn([f64; 2]) -> Stress,
        f_e: &mut [f64],
    ) -> Result<(), FemError> {
        let m = idealization.strain_size();
        for &q in self.load_rule(idealization) {
            let p = self.point(element, coords, idealization, q)?;
            let b = self.b_matrix(&p, idealization);
            let s = sigma_0(p.x);
            // Stress vector in B's row order: (xx, yy, xy, θθ); Stress is (xx, yy, xy, zz/θθ).
            for (a, f) in f_e.iter_mut().enumerate().take(2 * self.nodes) {
                let v: f64 = (0..m).map(|k| b[k][a] * s[k]).sum();
                *f -= v * p.weight;
            }
        }
        Ok(())
    }

    fn stresses_into(
        &self,
        element: usize,
        coords: &[[f64; 2]],
        material: &Material,
        idealization: &Idealization,
        u_e: &[f64],
        out: &mut Vec<([f64; 2], Stress)>,
    ) -> Result<(), FemError> {
        let d = material.elasticity(idealization);
        let m = idealization.strain_size();
        for &q in self.rule(idealization) {
            let p = self.point(element, coords, idealization, q)?;
            let b = self.b_matrix(&p, idealization);
            let mut eps = [0.0; 4];
            for (k, e) in eps.iter_mut().enumerate().take(m) {
                *e = (0..2 * self.nodes).map(|a| b[k][a] * u_e[a]).sum();
            }
            let mut s = [0.0; 4];
            for (r, sr) in s.iter_mut().enumerate().take(m) {
                *sr = (0..m).map(|k| d[(r, k)] * eps[k]).sum();
            }
            if let Idealization::PlaneStrain = idealization {
                s[3] = material.poisson() * (s[0] + s[1]);
            }
            out.push((p.x, s));
        }
        Ok(())
    }
}

const TRI3: Iso = Iso {
    nodes: 3,
    shape: tri3::shape,
    dshape: tri3::shape_derivatives,
};
const TRI6: Iso = Iso {
    nodes: 6,
    shape: tri6::shape,
    dshape: tri6::shape_derivatives,
};

macro_rules! impl_element {
    ($t:ty, $iso:expr) => {
        impl Element for $t {
            #[inline]
            fn node_count(&self) -> usize {
                $iso.nodes
            }
            fn stiffness_into(
                &self,
                element: usize,
                coords: &[[f64; 2]],
                material: &Material,
                idealization: &Idealization,
                k_e: &mut DMatrix<f64>,
            ) -> Result<(), FemError> {
                $iso.stiffness_into(element, coords, material, idealization, k_e)
            }
            fn body_force_into(
                &self,
                element: usize,
                coords: &[[f64; 2]],
                idealization: &Idealization,
                b: &dyn Fn([f64; 2]) -> [f64; 2],
                f_e: &mut [f64],
            ) -> Result<(), FemError> {
                $iso.body_force_into(element, coords, idealization, b, f_e)
            }
            fn initial_stress_force_into(
                &self,
                element: usize,
                coords: &[[f64; 2]],
                idealization: &Idealization,
                sigma_0: &dyn Fn([f64; 2]) -> Stress,
                f_e: &mut [f64],
            ) -> Result<(), FemError> {
                $iso.initial_stress_force_into(element, coords, idealization, sigma_0, f_e)
            }
            fn stresses_into(
                &self,
                element: usize,
                coords: &[[f64; 2]],
                material: &Material,
                idealization: &Idealization,
                u_e: &[f64],
                out: &mut Vec<([f64; 2], Stress)>,
            ) -> Result<(), FemError> {
                $iso.stresses_into(element, coords, material, idealization, u_e, out)
            }
        }
    };
}

impl_element!(Tri3, TRI3);
impl_element!(Tri6, TRI6);

#[cfg(test)]
mod tests {
    use super::*;

    fn p2_coords(c: [[f64; 2]; 3]) -> Vec<[f64; 2]> {
        let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        vec![
            c[0],
            c[1],
            c[2],
            mid(c[0], c[1]),
            mid(c[1], c[2]),
            mid(c[2], c[0]),
        ]
    }

    #[test]
    fn shape_functions_partition_unity_and_gradients_sum_to_zero_works() {
        for xi in [[0.2, 0.3], [0.0, 0.0], [0.7, 0.1]] {
            let mut n = [0.0; 6];
            let mut dn = [[0.0; 2]; 6];
            tri6::shape(xi, &mut n);
            tri6::shape_derivatives(xi, &mut dn);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            for a in 0..2 {
                assert!(dn.iter().map(|g| g[a]).sum::<f64>().abs() < 1e-14);
            }
            // Finite-difference check of the derivatives.
            let h = 1e-7;
            for a in 0..2 {
                let mut xp = xi;
                let mut xm = xi;
                xp[a] += h;
                xm[a] -= h;
                let (mut np, mut nm) = ([0.0; 6], [0.0; 6]);
                tri6::shape(xp, &mut np);
                tri6::shape(xm, &mut nm);
                for i in 0..6 {
                    assert!(((np[i] - nm[i]) / (2.0 * h) - dn[i][a]).abs() < 1e-8);
                }
            }
        }
    }

    #[test]
    fn stiffness_is_symmetric_with_rigid_modes_in_kernel_works() {
        let m = Material::new(200.0, 0.3, 0.0).unwrap();
        let c3 = vec![[0.1, 0.0], [1.3, 0.2], [0.4, 0.9]];
        let c6 = p2_coords([[0.1, 0.0], [1.3, 0.2], [0.4, 0.9]]);
        let mut k = DMatrix::zeros(0, 0);
        for ideal in [
            Idealization::PlaneStrain,
            Idealization::PlaneStress { thickness: 2.0 },
        ] {
            for (el, coords) in [(&Tri3 as &dyn Element, &c3), (&Tri6, &c6)] {
                el.stiffness_into(0, coords, &m, &ideal, &mut k).unwrap();
                assert!((&k - k.transpose()).norm() < 1e-12 * k.norm());
                // Translations and the infinitesimal rotation produce no force.
                let n = coords.len();
                let modes = [
                    (0..n).flat_map(|_| [1.0, 0.0]).collect::<Vec<_>>(),
                    (0..n).flat_map(|_| [0.0, 1.0]).collect(),
                    coords.iter().flat_map(|p| [-p[1], p[0]]).collect(),
                ];
                for mode in modes {
                    let f = &k * nalgebra::DVector::from_vec(mode);
                    assert!(f.norm() < 1e-12 * k.norm(), "rigid mode not in kernel");
                }
                assert!(k.clone().symmetric_eigenvalues().min() > -1e-10 * k.norm());
            }
        }
        // Axisymmetric: only the axial translation is a rigid mode.
        Tri6.stiffness_into(0, &c6, &m, &Idealization::Axisymmetric, &mut k)
            .unwrap();
        let f = &k * nalgebra::DVector::from_vec((0..6).flat_map(|_| [0.0, 1.0]).collect());
        assert!(f.norm() < 1e-12 * k.norm());
    }

    #[test]
    fn stiffness_rejects_inverted_element() {
        let m = Material::new(1.0, 0.3, 0.0).unwrap();
        let mut k = DMatrix::zeros(0, 0);
        let err = Tri3
            .stiffness_into(
                7,
                &[[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]],
                &m,
                &Idealization::PlaneStrain,
                &mut k,
            )
            .unwrap_err();
        assert!(matches!(err, FemError::InvertedElement { element: 7, .. }));
    }
}
