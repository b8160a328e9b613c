//! The kernels of an isoparametric element, written once for any dimension `D`: the
//! element supplies shape functions and rules ([`Element`]), this module the integrals.
//!
//! ```text
//! x(ξ) = Σ N_i(ξ) x_i,   J = ∂x/∂ξ,   ∇N_i = J⁻ᵀ ∂N_i/∂ξ,   dΩ = det J · w_q · w(x)
//! K_e = Σ_q Bᵀ D B dΩ,   f_e = Σ_q Nᵀ b dΩ,   f_σ₀ = −Σ_q Bᵀ σ₀ dΩ,   M_e = Σ_q ρ NᵀN dΩ
//! ```
//! with `w(x)` the setting's weight (1, the thickness, or `r` in axisymmetry; 1 in 3D).
//!
//! The constitutive contraction has two arms: in the plane, `B` (rows `xx, yy, γ_xy[, θθ]`)
//! against the idealisation's matrix [`Material::elasticity`]; in 3D, the isotropic Lamé form
//! `K_ab[i][j] = λ g_a[i] g_b[j] + μ g_a[j] g_b[i] + μ δ_ij g_a·g_b`. Both are the same
//! `Bᵀ D B`; each keeps the floating-point order of the code it replaced, so that the
//! numbers of the triangles and tetrahedra did not move by one bit.

use super::{Element, MAX_NODES, QuadPoint, Setting, VoigtStress};
use crate::error::FemError;
use crate::idealization::Idealization;
use crate::material::Material;
use crate::space::{Dim, Space};
use nalgebra::DMatrix;

/// Kinematics at one quadrature point: shape values, Cartesian gradients, position, weight.
pub(crate) struct Point<const D: usize> {
    /// Shape values.
    pub(crate) n: [f64; MAX_NODES],
    /// Cartesian gradients `∇N_i`.
    pub(crate) grad: [[f64; D]; MAX_NODES],
    /// Position.
    pub(crate) x: [f64; D],
    /// Quadrature weight × det J × the setting's weight.
    pub(crate) weight: f64,
}

fn too_many(nodes: usize) -> FemError {
    FemError::Unsupported {
        what: format!(
            "an element of {nodes} nodes with the default kernels (at most {MAX_NODES}); \
             override the kernels of the element"
        ),
    }
}

/// The cofactor matrix of `J` (so that `J⁻ᵀ = cof / det J`) and `det J`.
#[inline]
fn cofactor<const D: usize>(j: &[[f64; D]; D]) -> ([[f64; D]; D], f64) {
    let mut cof = [[0.0; D]; D];
    match D {
        1 => cof[0][0] = 1.0,
        2 => {
            cof[0][0] = j[1][1];
            cof[0][1] = -j[1][0];
            cof[1][0] = -j[0][1];
            cof[1][1] = j[0][0];
        }
        _ => {
            // cof[i][k] = j[i+1][k+1] j[i+2][k+2] − j[i+1][k+2] j[i+2][k+1], indices mod 3
            for (i, row) in cof.iter_mut().enumerate() {
                let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
                for (k, c) in row.iter_mut().enumerate() {
                    let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
                    *c = j[i1][k1] * j[i2][k2] - j[i1][k2] * j[i2][k1];
                }
            }
        }
    }
    let det = if D == 2 {
        j[0][0] * j[1][1] - j[0][1] * j[1][0]
    } else {
        (0..D).map(|b| j[0][b] * cof[0][b]).fold(0.0, |s, v| s + v)
    };
    (cof, det)
}

/// The kinematics of `el` at the quadrature point `(ξ, w)`.
///
/// # Errors
/// [`FemError::InvertedElement`] if `det J` is not positive (or NaN).
pub(crate) fn point<const D: usize, E: Element<D> + ?Sized>(
    el: &E,
    element: usize,
    coords: &[[f64; D]],
    setting: &Setting<D>,
    (xi, w): QuadPoint<D>,
) -> Result<Point<D>, FemError>
where
    Dim<D>: Space,
{
    let nodes = el.node_count();
    if nodes > MAX_NODES {
        return Err(too_many(nodes));
    }
    let mut p = Point {
        n: [0.0; MAX_NODES],
        grad: [[0.0; D]; MAX_NODES],
        x: [0.0; D],
        weight: 0.0,
    };
    let mut dn = [[0.0; D]; MAX_NODES];
    el.shape(xi, &mut p.n[..nodes], &mut dn[..nodes]);
    // J[a][b] = ∂x_a/∂ξ_b
    let mut j = [[0.0; D]; D];
    for i in 0..nodes {
        for a in 0..D {
            p.x[a] += p.n[i] * coords[i][a];
            for b in 0..D {
                j[a][b] += coords[i][a] * dn[i][b];
            }
        }
    }
    let (cof, det) = cofactor(&j);
    if det.is_nan() || det <= 0.0 {
        return Err(FemError::InvertedElement {
            element,
            det_j: det,
        });
    }
    // ∇N = J⁻ᵀ ∂N/∂ξ, with (J⁻ᵀ)[a][b] = cof[a][b] / det
    for (g, d) in p.grad.iter_mut().zip(&dn).take(nodes) {
        for a in 0..D {
            let mut s = cof[a][0] * d[0];
            for b in 1..D {
                s += cof[a][b] * d[b];
            }
            g[a] = s / det;
        }
    }
    p.weight = match <Dim<D> as Space>::idealization(setting) {
        Some(ideal) => w * det * ideal.weight(p.x[0]),
        None => w * det,
    };
    Ok(p)
}

/// The plane strain–displacement matrix `B` (rows `xx, yy, γ_xy, θθ`; the first `2 n`
/// columns are set, the rest is zero).
type PlaneB = [[f64; 2 * MAX_NODES]; 4];

/// `B` at a point of an element of `nodes` nodes; the hoop row only in axisymmetry.
#[inline]
fn plane_b<const D: usize>(p: &Point<D>, nodes: usize, axi: bool) -> PlaneB {
    let mut b = [[0.0; 2 * MAX_NODES]; 4];
    for i in 0..nodes {
        let (gx, gy) = (p.grad[i][0], p.grad[i][1]);
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

/// Lamé's constants `(λ, μ)` of a material.
#[inline]
pub(crate) fn lame(material: &Material) -> (f64, f64) {
    let (e, nu) = (material.young(), material.poisson());
    (
        e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
        e / (2.0 * (1.0 + nu)),
    )
}

/// `σ = λ tr(ε) I + 2 μ ε` for a 3D Voigt strain with tensor shears.
#[inline]
pub(crate) fn hooke(lambda: f64, mu: f64, e: [f64; 6]) -> [f64; 6] {
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

/// The 3D strain (tensor shears) at a point from the element displacements.
fn strain3<const D: usize>(p: &Point<D>, nodes: usize, u_e: &[f64]) -> [f64; 6] {
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

fn resize_zero(m: &mut DMatrix<f64>, nd: usize) {
    if m.shape() != (nd, nd) {
        *m = DMatrix::zeros(nd, nd);
    } else {
        m.fill(0.0);
    }
}

#[track_caller]
fn check_coords<const D: usize>(nodes: usize, coords: &[[f64; D]]) {
    assert_eq!(coords.len(), nodes, "one coordinate per element node");
}

/// The default [`Element::stiffness_into`].
///
/// # Errors
/// As [`Element::stiffness_into`].
pub fn stiffness_into<const D: usize, E: Element<D> + ?Sized>(
    el: &E,
    element: usize,
    coords: &[[f64; D]],
    material: &Material,
    setting: &Setting<D>,
    k_e: &mut DMatrix<f64>,
) -> Result<(), FemError>
where
    Dim<D>: Space,
{
    let nodes = el.node_count();
    check_coords(nodes, coords);
    let nd = D * nodes;
    resize_zero(k_e, nd);
    match <Dim<D> as Space>::idealization(setting) {
        Some(ideal) => plane_stiffness(el, element, coords, material, ideal, setting, k_e),
        None => solid_stiffness(el, element, coords, material, setting, k_e),
    }
}

fn plane_stiffness<const D: usize, E: Element<D> + ?Sized>(
    el: &E,
    element: usize,
    coords: &[[f64; D]],
    material: &Material,
    ideal: &Idealization,
    setting: &Setting<D>,
    k_e: &mut DMatrix<f64>,
) -> Result<(), FemError>
where
    Dim<D>: Space,
{
    let nd = D * el.node_count();
    let d = material.elasticity(ideal);
    let m = ideal.strain_size();
    let axi = matches!(ideal, Idealization::Axisymmetric);
    for &q in el.stiffness_rule(setting, coords) {
        let p = point(el, element, coords, setting, q)?;
        let b = plane_b(&p, el.node_count(), axi);
        // DB = D B (m × nd) column by column, then K += Bᵀ (DB) w
        for c in 0..nd {
            let mut db = [0.0; 4];
            for (r, v) in db.iter_mut().enumerate().take(m) {
                *v = (0..m).map(|k| d[(r, k)] * b[k][c]).sum();
            }
            for a in 0..=c {
                let v: f64 = (0..m).map(|k| b[k][a] * db[k]).sum::<f64>() * p.weight;
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

fn solid_stiffness<const D: usize, E: Element<D> + ?Sized>(
    el: &E,
    element: usize,
    coords: &[[f64; D]],
    material: &Material,
    setting: &Setting<D>,
    k_e: &mut DMatrix<f64>,
) -> Result<(), FemError>
where
    Dim<D>: Space,
{
    let nodes = el.node_count();
    let nd = D * nodes;
    let (lambda, mu) = lame(material);
    for &q in el.stiffness_rule(setting, coords) {
        let p = point(el, element, coords, setting, q)?;
        // K_ab[i][j] = w (λ g_a[i] g_b[j] + μ g_a[j] g_b[i] + μ δ_ij g_a·g_b)
        for a in 0..nodes {
            let ga = p.grad[a];
            for b in 0..=a {
                let gb = p.grad[b];
                let mut dot = ga[0] * gb[0];
                for c in 1..D {
                    dot += ga[c] * gb[c];
                }
                for i in 0..D {
                    for j in 0..D {
                        let mut v = lambda * ga[i] * gb[j] + mu * ga[j] * gb[i];
                        if i == j {
                            v += mu * dot;
                        }
                        k_e[(D * a + i, D * b + j)] += p.weight * v;
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

/// The default [`Element::body_force_into`].
///
/// # Errors
/// As [`Element::body_force_into`].
pub fn body_force_into<const D: usize, E: Element<D> + ?Sized>(
    el: &E,
    element: usize,
    coords: &[[f64; D]],
    setting: &Setting<D>,
    b: &dyn Fn([f64; D]) -> [f64; D],
    f_e: &mut [f64],
) -> Result<(), FemError>
where
    Dim<D>: Space,
{
    let nodes = el.node_count();
    check_coords(nodes, coords);
    let plane = <Dim<D> as Space>::idealization(setting).is_some();
    for &q in el.load_rule(setting) {
        let p = point(el, element, coords, setting, q)?;
        let bx = b(p.x);
        for a in 0..nodes {
            for i in 0..D {
                f_e[D * a + i] += if plane {
                    p.n[a] * bx[i] * p.weight
                } else {
                    p.weight * p.n[a] * bx[i]
                };
            }
        }
    }
    Ok(())
}

/// The default [`Element::initial_stress_force_into`].
///
/// # Errors
/// As [`Element::initial_stress_force_into`].
pub fn initial_stress_force_into<const D: usize, E: Element<D> + ?Sized>(
    el: &E,
    element: usize,
    coords: &[[f64; D]],
    setting: &Setting<D>,
    sigma_0: &dyn Fn([f64; D]) -> VoigtStress<D>,
    f_e: &mut [f64],
) -> Result<(), FemError>
where
    Dim<D>: Space,
{
    let nodes = el.node_count();
    check_coords(nodes, coords);
    let ideal = <Dim<D> as Space>::idealization(setting);
    for &q in el.load_rule(setting) {
        let p = point(el, element, coords, setting, q)?;
        let s0 = sigma_0(p.x);
        let s = s0.as_ref();
        match ideal {
            Some(ideal) => {
                let m = ideal.strain_size();
                let axi = matches!(ideal, Idealization::Axisymmetric);
                let b = plane_b(&p, nodes, axi);
                // σ in B's row order: (xx, yy, xy, θθ)
                for (a, f) in f_e.iter_mut().enumerate().take(D * nodes) {
                    let v: f64 = (0..m).map(|k| b[k][a] * s[k]).sum();
                    *f -= v * p.weight;
                }
            }
            None => {
                // σ as a tensor: rows (xx xy zx), (xy yy yz), (zx yz zz)
                let t = [[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]];
                for a in 0..nodes {
                    let g = p.grad[a];
                    for (i, row) in t.iter().enumerate() {
                        f_e[D * a + i] -=
                            p.weight * (row[0] * g[0] + row[1] * g[1] + row[2] * g[2]);
                    }
                }
            }
        }
    }
    Ok(())
}

/// The default [`Element::stresses_into`].
///
/// # Errors
/// As [`Element::stresses_into`].
pub fn stresses_into<const D: usize, E: Element<D> + ?Sized>(
    el: &E,
    element: usize,
    coords: &[[f64; D]],
    material: &Material,
    setting: &Setting<D>,
    u_e: &[f64],
    out: &mut Vec<([f64; D], VoigtStress<D>)>,
) -> Result<(), FemError>
where
    Dim<D>: Space,
{
    let nodes = el.node_count();
    check_coords(nodes, coords);
    let ideal = <Dim<D> as Space>::idealization(setting);
    for &q in el.stress_rule(setting, coords) {
        let p = point(el, element, coords, setting, q)?;
        let mut stress = VoigtStress::<D>::default();
        let s = stress.as_mut();
        match ideal {
            Some(ideal) => {
                let d = material.elasticity(ideal);
                let m = ideal.strain_size();
                let axi = matches!(ideal, Idealization::Axisymmetric);
                let b = plane_b(&p, nodes, axi);
                let mut eps = [0.0; 4];
                for (k, e) in eps.iter_mut().enumerate().take(m) {
                    *e = (0..D * nodes).map(|a| b[k][a] * u_e[a]).sum();
                }
                for (r, sr) in s.iter_mut().enumerate().take(m) {
                    *sr = (0..m).map(|k| d[(r, k)] * eps[k]).sum();
                }
                if let Idealization::PlaneStrain = ideal {
                    s[3] = material.poisson() * (s[0] + s[1]);
                }
            }
            None => {
                let (lambda, mu) = lame(material);
                s.copy_from_slice(&hooke(lambda, mu, strain3(&p, nodes, u_e)));
            }
        }
        out.push((p.x, stress));
    }
    Ok(())
}

/// The default [`Element::mass_into`].
///
/// # Errors
/// As [`Element::mass_into`].
pub fn mass_into<const D: usize, E: Element<D> + ?Sized>(
    el: &E,
    element: usize,
    coords: &[[f64; D]],
    density: f64,
    setting: &Setting<D>,
    m_e: &mut DMatrix<f64>,
) -> Result<(), FemError>
where
    Dim<D>: Space,
{
    let nodes = el.node_count();
    check_coords(nodes, coords);
    resize_zero(m_e, D * nodes);
    for &q in el.mass_rule(setting) {
        let p = point(el, element, coords, setting, q)?;
        for a in 0..nodes {
            for b in 0..=a {
                let v = density * p.n[a] * p.n[b] * p.weight;
                for i in 0..D {
                    m_e[(D * a + i, D * b + i)] += v;
                }
            }
        }
    }
    for a in 0..D * nodes {
        for b in (a + 1)..D * nodes {
            m_e[(a, b)] = m_e[(b, a)];
        }
    }
    Ok(())
}

/// The default [`Element::lumped_mass_into`] (HRZ diagonal scaling).
///
/// # Errors
/// As [`Element::lumped_mass_into`].
///
/// # Panics
/// If `m_e.len() != D · node_count()`.
#[track_caller]
pub fn lumped_mass_into<const D: usize, E: Element<D> + ?Sized>(
    el: &E,
    element: usize,
    coords: &[[f64; D]],
    density: f64,
    setting: &Setting<D>,
    m_e: &mut [f64],
) -> Result<(), FemError>
where
    Dim<D>: Space,
{
    let nodes = el.node_count();
    check_coords(nodes, coords);
    assert_eq!(m_e.len(), D * nodes, "one lumped mass per element dof");
    let (mut total, mut diag) = (0.0, [0.0; MAX_NODES]);
    for &q in el.mass_rule(setting) {
        let p = point(el, element, coords, setting, q)?;
        total += density * p.weight;
        for (d, n) in diag.iter_mut().zip(&p.n).take(nodes) {
            *d += density * n * n * p.weight;
        }
    }
    let sum: f64 = diag[..nodes].iter().sum();
    for a in 0..nodes {
        let m = if sum > 0.0 {
            diag[a] * total / sum
        } else {
            0.0
        };
        m_e[D * a..D * a + D].fill(m);
    }
    Ok(())
}

/// Position, displacement, strain (3D Voigt, tensor shears) and weight at a point.
pub(crate) type Field3 = ([f64; 3], [f64; 3], [f64; 6], f64);

/// Position, displacement, strain (3D Voigt, tensor shears) and weight at one quadrature
/// point of a 3D element, for error norms.
pub(crate) fn field_at3<E: Element<3> + ?Sized>(
    el: &E,
    element: usize,
    coords: &[[f64; 3]],
    u_e: &[f64],
    q: QuadPoint<3>,
) -> Result<Field3, FemError> {
    let nodes = el.node_count();
    let p = point(el, element, coords, &(), q)?;
    let mut u = [0.0; 3];
    for a in 0..nodes {
        for (i, ui) in u.iter_mut().enumerate() {
            *ui += p.n[a] * u_e[3 * a + i];
        }
    }
    Ok((p.x, u, strain3(&p, nodes, u_e), p.weight))
}
