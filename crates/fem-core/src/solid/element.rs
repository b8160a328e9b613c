//! The isoparametric tetrahedra [`Tet4`] and [`Tet10`] of 3D linear elasticity.
//!
//! Local dof order `(u_0, v_0, w_0, u_1, …)`. Stresses and strains are Voigt vectors
//! [`Stress3`] `(xx, yy, zz, xy, yz, zx)`; strains carry the tensor shears (`ε_xy`, not `γ_xy`).

use super::quadrature::{TET_1, TET_4, TetPoint, conical_rule};
use crate::error::FemError;
use crate::material::Material;
use nalgebra::DMatrix;
use std::sync::OnceLock;

/// Largest number of nodes of a tetrahedron here.
pub const MAX_TET_NODES: usize = 10;

/// Stress (or strain) components `(xx, yy, zz, xy, yz, zx)`.
pub type Stress3 = [f64; 6];

/// A 3D finite element of linear elasticity, as the solid assembly consumes it.
pub trait SolidElement {
    /// Number of nodes.
    fn node_count(&self) -> usize;

    /// The element stiffness `K_e = ∫ Bᵀ D B dV`, `3n × 3n`, into `k_e` (resized if needed).
    /// `element` is only used in errors.
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] if the Jacobian is not positive at a quadrature point.
    fn stiffness_into(
        &self,
        element: usize,
        coords: &[[f64; 3]],
        material: &Material,
        k_e: &mut DMatrix<f64>,
    ) -> Result<(), FemError>;

    /// Adds `f_e += ∫ Nᵀ b dV` for a body force density `b(x)` (force per volume).
    ///
    /// # Errors
    /// As for the stiffness.
    fn body_force_into(
        &self,
        element: usize,
        coords: &[[f64; 3]],
        b: &dyn Fn([f64; 3]) -> [f64; 3],
        f_e: &mut [f64],
    ) -> Result<(), FemError>;

    /// Adds the internal force of an initial stress, `f_e −= ∫ Bᵀ σ₀ dV`.
    ///
    /// # Errors
    /// As for the stiffness.
    fn initial_stress_force_into(
        &self,
        element: usize,
        coords: &[[f64; 3]],
        sigma_0: &dyn Fn([f64; 3]) -> Stress3,
        f_e: &mut [f64],
    ) -> Result<(), FemError>;

    /// Stresses `σ = D ε(u_e)` at the quadrature points of the stiffness rule, with their
    /// positions, appended to `out`.
    ///
    /// # Errors
    /// As for the stiffness.
    fn stresses_into(
        &self,
        element: usize,
        coords: &[[f64; 3]],
        material: &Material,
        u_e: &[f64],
        out: &mut Vec<([f64; 3], Stress3)>,
    ) -> Result<(), FemError>;
}

/// The 4-node linear tetrahedron (one-point rule: its strain is constant).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tet4;

/// The 10-node quadratic isoparametric tetrahedron (four-point rule, exact for straight sides).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tet10;

/// Shape values and reference derivatives at `(ξ, η, ζ)`, for 4 or 10 nodes.
pub(crate) fn shape(nodes: usize, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let l = [1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]];
    const DL: [[f64; 3]; 4] = [
        [-1.0, -1.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    if nodes == 4 {
        n[..4].copy_from_slice(&l);
        dn[..4].copy_from_slice(&DL);
        return;
    }
    for i in 0..4 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
        dn[i] = DL[i].map(|d| (4.0 * l[i] - 1.0) * d);
    }
    for (k, [i, j]) in super::mesh::TET_EDGES.into_iter().enumerate() {
        n[4 + k] = 4.0 * l[i] * l[j];
        dn[4 + k] = core::array::from_fn(|c| 4.0 * (DL[i][c] * l[j] + l[i] * DL[j][c]));
    }
}

/// Kinematics at one quadrature point.
struct Point {
    n: [f64; MAX_TET_NODES],
    grad: [[f64; 3]; MAX_TET_NODES],
    x: [f64; 3],
    /// Quadrature weight × det J.
    weight: f64,
}

fn point(
    nodes: usize,
    element: usize,
    coords: &[[f64; 3]],
    (xi, w): TetPoint,
) -> Result<Point, FemError> {
    let mut p = Point {
        n: [0.0; MAX_TET_NODES],
        grad: [[0.0; 3]; MAX_TET_NODES],
        x: [0.0; 3],
        weight: 0.0,
    };
    let mut dn = [[0.0; 3]; MAX_TET_NODES];
    shape(nodes, xi, &mut p.n, &mut dn);
    // J[a][b] = ∂x_a/∂ξ_b
    let mut j = [[0.0; 3]; 3];
    for i in 0..nodes {
        for a in 0..3 {
            p.x[a] += p.n[i] * coords[i][a];
            for b in 0..3 {
                j[a][b] += coords[i][a] * dn[i][b];
            }
        }
    }
    let cof = [
        [
            j[1][1] * j[2][2] - j[1][2] * j[2][1],
            j[1][2] * j[2][0] - j[1][0] * j[2][2],
            j[1][0] * j[2][1] - j[1][1] * j[2][0],
        ],
        [
            j[0][2] * j[2][1] - j[0][1] * j[2][2],
            j[0][0] * j[2][2] - j[0][2] * j[2][0],
            j[0][1] * j[2][0] - j[0][0] * j[2][1],
        ],
        [
            j[0][1] * j[1][2] - j[0][2] * j[1][1],
            j[0][2] * j[1][0] - j[0][0] * j[1][2],
            j[0][0] * j[1][1] - j[0][1] * j[1][0],
        ],
    ];
    let det = j[0][0] * cof[0][0] + j[0][1] * cof[0][1] + j[0][2] * cof[0][2];
    if det.is_nan() || det <= 0.0 {
        return Err(FemError::InvertedElement {
            element,
            det_j: det,
        });
    }
    // ∇N = J⁻ᵀ ∂N/∂ξ, with J⁻¹ = cofᵀ / det, so (J⁻ᵀ)[a][b] = cof[a][b] / det
    for (g, d) in p.grad.iter_mut().zip(&dn).take(nodes) {
        *g = core::array::from_fn(|a| {
            (cof[a][0] * d[0] + cof[a][1] * d[1] + cof[a][2] * d[2]) / det
        });
    }
    p.weight = w * det;
    Ok(p)
}

/// Lamé's constants `(λ, μ)` of a material.
#[inline]
pub(crate) fn lame(material: &Material) -> (f64, f64) {
    let (e, nu) = (material.young(), material.poisson());
    (
        e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
        e / (2.0 * (1.0 + nu)),
    )
}

/// `σ = λ tr(ε) I + 2 μ ε` for a Voigt strain with tensor shears.
#[inline]
pub(crate) fn hooke(lambda: f64, mu: f64, e: Stress3) -> Stress3 {
    let tr = e[0] + e[1] + e[2];
    [
        lambda * tr + 2.0 * mu * e[0],
        lambda * tr + 2.0 * mu * e[1],
        lambda * tr + 2.0 * mu * e[2],
        2.0 * mu * e[3],
        2.0 * mu * e[4],
        2.0 * mu * e[5],
    ]
}

/// The 64-point conical rule (degree 5) for loads and error norms, built once.
pub(crate) fn load_rule() -> &'static [TetPoint] {
    static RULE: OnceLock<Vec<TetPoint>> = OnceLock::new();
    RULE.get_or_init(|| conical_rule(4))
}

/// The shared isoparametric implementation.
#[derive(Clone, Copy)]
struct Iso {
    nodes: usize,
    rule: &'static [TetPoint],
}

impl Iso {
    /// The stiffness rule: `rule` for a straight-sided element; for a curved P2 element
    /// (a mid-edge node off its edge's midpoint) a degree-3 rule, the lowest that integrates
    /// `∇N detJ` exactly, so that curved meshes pass the patch test.
    fn rule_for(&self, coords: &[[f64; 3]]) -> &'static [TetPoint] {
        if self.nodes == 4 || !is_curved(coords) {
            self.rule
        } else {
            static CURVED: OnceLock<Vec<TetPoint>> = OnceLock::new();
            CURVED.get_or_init(|| conical_rule(3))
        }
    }

    fn check(&self, coords: &[[f64; 3]]) {
        assert_eq!(coords.len(), self.nodes, "one coordinate per element node");
    }

    fn stiffness_into(
        &self,
        element: usize,
        coords: &[[f64; 3]],
        material: &Material,
        k_e: &mut DMatrix<f64>,
    ) -> Result<(), FemError> {
        self.check(coords);
        let nd = 3 * self.nodes;
        if k_e.shape() != (nd, nd) {
            *k_e = DMatrix::zeros(nd, nd);
        } else {
            k_e.fill(0.0);
        }
        let (lambda, mu) = lame(material);
        for &q in self.rule_for(coords) {
            let p = point(self.nodes, element, coords, q)?;
            // K_ab[i][j] = w (λ g_a[i] g_b[j] + μ g_a[j] g_b[i] + μ δ_ij g_a·g_b)
            for a in 0..self.nodes {
                let ga = p.grad[a];
                for b in 0..=a {
                    let gb = p.grad[b];
                    let dot = ga[0] * gb[0] + ga[1] * gb[1] + ga[2] * gb[2];
                    for i in 0..3 {
                        for j in 0..3 {
                            let mut v = lambda * ga[i] * gb[j] + mu * ga[j] * gb[i];
                            if i == j {
                                v += mu * dot;
                            }
                            k_e[(3 * a + i, 3 * b + j)] += p.weight * v;
                        }
                    }
                }
            }
        }
        for a in 0..nd {
            for b in (a + 1)..nd {
                k_e[(a, b)] = k_e[(b, a)];
            }
        }
        Ok(())
    }

    fn body_force_into(
        &self,
        element: usize,
        coords: &[[f64; 3]],
        b: &dyn Fn([f64; 3]) -> [f64; 3],
        f_e: &mut [f64],
    ) -> Result<(), FemError> {
        self.check(coords);
        for &q in load_rule() {
            let p = point(self.nodes, element, coords, q)?;
            let bx = b(p.x);
            for a in 0..self.nodes {
                for i in 0..3 {
                    f_e[3 * a + i] += p.weight * p.n[a] * bx[i];
                }
            }
        }
        Ok(())
    }

    fn initial_stress_force_into(
        &self,
        element: usize,
        coords: &[[f64; 3]],
        sigma_0: &dyn Fn([f64; 3]) -> Stress3,
        f_e: &mut [f64],
    ) -> Result<(), FemError> {
        self.check(coords);
        for &q in load_rule() {
            let p = point(self.nodes, element, coords, q)?;
            let s = sigma_0(p.x);
            // σ as a tensor: rows (xx xy zx), (xy yy yz), (zx yz zz)
            let t = [[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]];
            for a in 0..self.nodes {
                let g = p.grad[a];
                for i in 0..3 {
                    f_e[3 * a + i] -= p.weight * (t[i][0] * g[0] + t[i][1] * g[1] + t[i][2] * g[2]);
                }
            }
        }
        Ok(())
    }

    fn stresses_into(
        &self,
        element: usize,
        coords: &[[f64; 3]],
        material: &Material,
        u_e: &[f64],
        out: &mut Vec<([f64; 3], Stress3)>,
    ) -> Result<(), FemError> {
        self.check(coords);
        let (lambda, mu) = lame(material);
        for &q in self.rule {
            let p = point(self.nodes, element, coords, q)?;
            let e = strain(&p, self.nodes, u_e);
            out.push((p.x, hooke(lambda, mu, e)));
        }
        Ok(())
    }
}

/// Whether a 10-node element has a mid-edge node off the midpoint of its edge (by more than
/// `1e-12` of the edge's length).
fn is_curved(coords: &[[f64; 3]]) -> bool {
    super::mesh::TET_EDGES
        .iter()
        .enumerate()
        .any(|(k, &[i, j])| {
            let (a, b, m) = (coords[i], coords[j], coords[4 + k]);
            let d = super::mesh::sub(b, a);
            let off: [f64; 3] = core::array::from_fn(|c| m[c] - 0.5 * (a[c] + b[c]));
            super::mesh::dot(off, off) > 1e-24 * super::mesh::dot(d, d)
        })
}

/// The strain (tensor shears) at a point from the element displacements.
fn strain(p: &Point, nodes: usize, u_e: &[f64]) -> Stress3 {
    let mut du = [[0.0; 3]; 3]; // du[i][j] = ∂u_i/∂x_j
    for (a, g) in p.grad.iter().enumerate().take(nodes) {
        for (i, row) in du.iter_mut().enumerate() {
            for (d, gj) in row.iter_mut().zip(g) {
                *d += u_e[3 * a + i] * gj;
            }
        }
    }
    [
        du[0][0],
        du[1][1],
        du[2][2],
        0.5 * (du[0][1] + du[1][0]),
        0.5 * (du[1][2] + du[2][1]),
        0.5 * (du[2][0] + du[0][2]),
    ]
}

/// Displacement and its gradient at reference point `xi` of an element (for error norms):
/// `(x, u, ∇u, det J · w)` for each point of `rule`.
pub(crate) fn field_at(
    nodes: usize,
    element: usize,
    coords: &[[f64; 3]],
    u_e: &[f64],
    q: TetPoint,
) -> Result<([f64; 3], [f64; 3], Stress3, f64), FemError> {
    let p = point(nodes, element, coords, q)?;
    let mut u = [0.0; 3];
    for a in 0..nodes {
        for i in 0..3 {
            u[i] += p.n[a] * u_e[3 * a + i];
        }
    }
    Ok((p.x, u, strain(&p, nodes, u_e), p.weight))
}

macro_rules! delegate {
    ($t:ty, $nodes:expr, $rule:expr) => {
        impl $t {
            const ISO: Iso = Iso {
                nodes: $nodes,
                rule: $rule,
            };
        }

        impl SolidElement for $t {
            fn node_count(&self) -> usize {
                $nodes
            }
            fn stiffness_into(
                &self,
                element: usize,
                coords: &[[f64; 3]],
                material: &Material,
                k_e: &mut DMatrix<f64>,
            ) -> Result<(), FemError> {
                Self::ISO.stiffness_into(element, coords, material, k_e)
            }
            fn body_force_into(
                &self,
                element: usize,
                coords: &[[f64; 3]],
                b: &dyn Fn([f64; 3]) -> [f64; 3],
                f_e: &mut [f64],
            ) -> Result<(), FemError> {
                Self::ISO.body_force_into(element, coords, b, f_e)
            }
            fn initial_stress_force_into(
                &self,
                element: usize,
                coords: &[[f64; 3]],
                sigma_0: &dyn Fn([f64; 3]) -> Stress3,
                f_e: &mut [f64],
            ) -> Result<(), FemError> {
                Self::ISO.initial_stress_force_into(element, coords, sigma_0, f_e)
            }
            fn stresses_into(
                &self,
                element: usize,
                coords: &[[f64; 3]],
                material: &Material,
                u_e: &[f64],
                out: &mut Vec<([f64; 3], Stress3)>,
            ) -> Result<(), FemError> {
                Self::ISO.stresses_into(element, coords, material, u_e, out)
            }
        }
    };
}

delegate!(Tet4, 4, &TET_1);
delegate!(Tet10, 10, &TET_4);

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_tet() -> Vec<[f64; 3]> {
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ]
    }

    fn tet10(c: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let mut out = c.to_vec();
        for [i, j] in super::super::mesh::TET_EDGES {
            out.push(core::array::from_fn(|a| 0.5 * (c[i][a] + c[j][a])));
        }
        out
    }

    #[test]
    fn shape_functions_partition_unity_and_match_finite_differences_works() {
        let xi = [0.21, 0.17, 0.33];
        for nodes in [4, 10] {
            let (mut n, mut dn) = ([0.0; 10], [[0.0; 3]; 10]);
            shape(nodes, xi, &mut n, &mut dn);
            assert!((n[..nodes].iter().sum::<f64>() - 1.0).abs() < 1e-15);
            for c in 0..3 {
                let h = 1e-6;
                let (mut np, mut nm, mut d) = ([0.0; 10], [0.0; 10], [[0.0; 3]; 10]);
                let mut xp = xi;
                xp[c] += h;
                shape(nodes, xp, &mut np, &mut d);
                let mut xm = xi;
                xm[c] -= h;
                shape(nodes, xm, &mut nm, &mut d);
                for i in 0..nodes {
                    let fd = (np[i] - nm[i]) / (2.0 * h);
                    // central differences of a quadratic are exact up to round-off / h
                    assert!((fd - dn[i][c]).abs() < 1e-9, "node {i} dir {c}");
                }
            }
        }
    }

    #[test]
    fn stiffness_is_symmetric_with_six_rigid_modes_works() {
        let m = Material::new(210.0, 0.3, 0.0).unwrap();
        let c4 = vec![
            [0.1, 0.0, 0.2],
            [1.3, 0.1, 0.0],
            [0.2, 1.1, 0.1],
            [0.3, 0.2, 0.9],
        ];
        for coords in [c4.clone(), tet10(&c4)] {
            let n = coords.len();
            let mut k = DMatrix::zeros(0, 0);
            let el: &dyn SolidElement = if n == 4 { &Tet4 } else { &Tet10 };
            el.stiffness_into(0, &coords, &m, &mut k).unwrap();
            assert!((&k - k.transpose()).amax() < 1e-12 * k.amax());
            let eig = k.clone().symmetric_eigen().eigenvalues;
            let zero = eig.iter().filter(|v| v.abs() < 1e-9 * k.amax()).count();
            assert_eq!(zero, 6, "three translations and three rotations");
            assert!(eig.iter().all(|v| *v > -1e-9 * k.amax()));
            // a rotation about z is a zero-energy mode
            let u: Vec<f64> = coords.iter().flat_map(|p| [-p[1], p[0], 0.0]).collect();
            let f = &k * nalgebra::DVector::from_vec(u);
            assert!(f.amax() < 1e-12 * k.amax());
        }
    }

    #[test]
    fn uniform_strain_gives_hooke_stress_works() {
        let m = Material::new(100.0, 0.25, 0.0).unwrap();
        let (lambda, mu) = lame(&m);
        let grad = [[1e-3, 2e-4, -3e-4], [5e-4, -2e-3, 1e-4], [0.0, 7e-4, 4e-4]];
        let c4 = unit_tet();
        for coords in [c4.clone(), tet10(&c4)] {
            let u: Vec<f64> = coords
                .iter()
                .flat_map(|p| {
                    let g = &grad;
                    core::array::from_fn::<f64, 3, _>(|i| {
                        g[i][0] * p[0] + g[i][1] * p[1] + g[i][2] * p[2]
                    })
                })
                .collect();
            let mut out = Vec::new();
            let el: &dyn SolidElement = if coords.len() == 4 { &Tet4 } else { &Tet10 };
            el.stresses_into(0, &coords, &m, &u, &mut out).unwrap();
            let e = [
                grad[0][0],
                grad[1][1],
                grad[2][2],
                0.5 * (grad[0][1] + grad[1][0]),
                0.5 * (grad[1][2] + grad[2][1]),
                0.5 * (grad[2][0] + grad[0][2]),
            ];
            let want = hooke(lambda, mu, e);
            for (_, s) in out {
                for k in 0..6 {
                    assert!((s[k] - want[k]).abs() < 1e-12 * 100.0, "{k}");
                }
            }
        }
    }

    #[test]
    fn self_weight_sums_to_the_weight_works() {
        let c4 = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 3.0, 0.0],
            [0.0, 0.0, 1.5],
        ];
        let volume = 2.0 * 3.0 * 1.5 / 6.0;
        for coords in [c4.clone(), tet10(&c4)] {
            let mut f = vec![0.0; 3 * coords.len()];
            let el: &dyn SolidElement = if coords.len() == 4 { &Tet4 } else { &Tet10 };
            el.body_force_into(0, &coords, &|_| [0.0, 0.0, -2.0], &mut f)
                .unwrap();
            let fz: f64 = f.iter().skip(2).step_by(3).sum();
            assert!((fz + 2.0 * volume).abs() < 1e-13);
        }
    }

    #[test]
    fn inverted_element_captures_errors() {
        let m = Material::new(1.0, 0.3, 0.0).unwrap();
        let mut c = unit_tet();
        c.swap(1, 2);
        let mut k = DMatrix::zeros(0, 0);
        assert!(matches!(
            Tet4.stiffness_into(7, &c, &m, &mut k),
            Err(FemError::InvertedElement { element: 7, .. })
        ));
    }
}
