//! Closed-form solutions of linear elasticity used to verify the finite elements.
//!
//! Every function is a plain evaluation of a textbook formula; signs follow the crate:
//! tension positive, the second coordinate (`y` or `z`) upwards, stresses in [`Stress`] order
//! `(xx|rr, yy|zz, xy|rz, zz|θθ)`.
//!
//! Sources:
//! - S. Timoshenko, J. N. Goodier, *Theory of Elasticity*, 3rd ed., McGraw-Hill, 1970 —
//!   §21 "Bending of a cantilever loaded at the end", §28 "Stress distribution symmetrical
//!   about an axis" (Lamé's thick-walled cylinder) and the displacements of that chapter.
//! - M. H. Sadd, *Elasticity: Theory, Applications and Numerics*, Academic Press — ch. 8,
//!   the end-loaded cantilever (polynomial solution) and the thick-walled cylinder under
//!   uniform boundary pressure.

use crate::element::Stress;
use crate::material::Material;

/// Axial condition of a thick-walled cylinder (what is assumed along its axis `z`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum CylinderEnds {
    /// `ε_zz = 0`: a long cylinder between rigid smooth walls. It is both the plane-strain
    /// model of a cross-section and the axisymmetric `(r, z)` model of a slice with `u_z = 0`
    /// on its top and bottom (both give the same `u_r`).
    PlaneStrain,
    /// `σ_zz = 0`: open ends (generalised plane stress; a thin ring, or a tube whose end
    /// caps are not carried by the wall).
    Open,
    /// Closed ends: the wall carries the end-cap force, `σ_zz = p a² / (b² − a²)` (uniform).
    Closed,
}

/// Lamé's solution at one radius: radial displacement and stresses.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct LameCylinder {
    /// Radial displacement `u_r`.
    pub u_r: f64,
    /// Radial stress `σ_rr`.
    pub sigma_rr: f64,
    /// Hoop stress `σ_θθ`.
    pub sigma_tt: f64,
    /// Axial stress `σ_zz`.
    pub sigma_zz: f64,
}

/// Lamé's thick-walled cylinder `a ≤ r ≤ b` under internal pressure `p` (outer surface free),
/// evaluated at radius `r` (Timoshenko & Goodier §28; Sadd ch. 8).
///
/// ```text
/// A = p a² / (b² − a²)
/// σ_rr = A (1 − b²/r²),   σ_θθ = A (1 + b²/r²)                 (independent of the ends)
/// σ_zz = 2νA (plane strain), 0 (open ends), A (closed ends)
/// u_r  = r ε_θθ = (r / E) [ (1 − ν) A − ν σ_zz + (1 + ν) A b²/r² ]
/// plane strain: u_r = (1 + ν) A / E · [ (1 − 2ν) r + b²/r ]
/// ```
///
/// # Panics
/// If `inner ≤ 0`, `outer ≤ inner` or `r ≤ 0` (or any is NaN).
///
/// # Examples
/// ```
/// use fem_core::analytical::{lame_cylinder, CylinderEnds};
/// use fem_core::Material;
/// let m = Material::new(1000.0, 0.3, 0.0).unwrap();
/// let s = lame_cylinder(1.0, 2.0, 3.0, &m, CylinderEnds::PlaneStrain, 1.0);
/// // The inner surface carries the pressure; the hoop stress there is p (b² + a²)/(b² − a²).
/// assert!((s.sigma_rr + 3.0).abs() < 1e-14);
/// assert!((s.sigma_tt - 5.0).abs() < 1e-14);
/// ```
#[track_caller]
pub fn lame_cylinder(
    inner: f64,
    outer: f64,
    pressure: f64,
    material: &Material,
    ends: CylinderEnds,
    r: f64,
) -> LameCylinder {
    assert!(
        inner > 0.0,
        "lame_cylinder: inner radius {inner} must be > 0"
    );
    assert!(
        outer > inner,
        "lame_cylinder: outer radius {outer} must exceed inner {inner}"
    );
    assert!(r > 0.0, "lame_cylinder: radius {r} must be > 0");
    let (e, nu) = (material.young(), material.poisson());
    let (a2, b2, r2) = (inner * inner, outer * outer, r * r);
    let big_a = pressure * a2 / (b2 - a2);
    let sigma_rr = big_a * (1.0 - b2 / r2);
    let sigma_tt = big_a * (1.0 + b2 / r2);
    let sigma_zz = match ends {
        CylinderEnds::PlaneStrain => 2.0 * nu * big_a,
        CylinderEnds::Open => 0.0,
        CylinderEnds::Closed => big_a,
    };
    let u_r = r / e * ((1.0 - nu) * big_a - nu * sigma_zz + (1.0 + nu) * big_a * b2 / r2);
    LameCylinder {
        u_r,
        sigma_rr,
        sigma_tt,
        sigma_zz,
    }
}

/// Constrained (oedometric, P-wave) modulus `M = E (1 − ν) / ((1 + ν)(1 − 2ν))`: the ratio
/// `σ_zz / ε_zz` under uniaxial strain.
///
/// # Examples
/// ```
/// use fem_core::analytical::constrained_modulus;
/// use fem_core::Material;
/// let m = Material::new(1.0, 0.0, 0.0).unwrap();
/// assert_eq!(constrained_modulus(&m), 1.0);
/// ```
pub fn constrained_modulus(material: &Material) -> f64 {
    let (e, nu) = (material.young(), material.poisson());
    e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))
}

/// The at-rest coefficient of an elastic body under uniaxial strain, `K0 = ν / (1 − ν)`
/// (`σ_h = K0 σ_v` when the lateral strain is zero).
///
/// # Examples
/// ```
/// use fem_core::analytical::elastic_k0;
/// assert!((elastic_k0(0.25) - 1.0 / 3.0).abs() < 1e-15);
/// ```
pub fn elastic_k0(poisson: f64) -> f64 {
    poisson / (1.0 - poisson)
}

/// A laterally confined soil column at height `z`: vertical displacement and stress.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SoilColumn {
    /// Vertical displacement `u_z` (negative: settlement).
    pub u_z: f64,
    /// Stress in [`Stress`] order `(rr|xx, zz, rz, θθ|out-of-plane)`.
    pub sigma: Stress,
}

/// A column `0 ≤ z ≤ H` of the material of unit weight `γ` under its own weight, laterally
/// confined (`u_r = 0` or `u_x = 0` on its sides, so `ε_rr = ε_θθ = 0`), fixed at the base
/// `z = 0` and free at the top `z = H` — one-dimensional (oedometric) compression:
///
/// ```text
/// σ_zz(z) = −γ (H − z)                       (equilibrium, free top)
/// σ_rr = σ_θθ = K0 σ_zz,   K0 = ν / (1 − ν)  (zero lateral strain)
/// u_z(z)  = ∫₀ᶻ σ_zz / M = −γ (H² − (H − z)²) / (2M) = −γ z (2H − z) / (2M)
/// ```
///
/// with `M` the [`constrained_modulus`]; the top settles by `γ H² / (2M)`. The same stress
/// with any `K0` (not only the elastic one) is the geostatic state of
/// [`geostatic`](crate::model::geostatic): it balances gravity by itself, with no
/// displacement, whatever `K0` is.
///
/// # Panics
/// If `height ≤ 0` or is NaN.
///
/// # Examples
/// ```
/// use fem_core::analytical::{constrained_modulus, soil_column};
/// use fem_core::Material;
/// let m = Material::new(1.0e4, 0.3, 20.0).unwrap();
/// let top = soil_column(&m, 10.0, 10.0);
/// assert!((top.u_z + 20.0 * 100.0 / (2.0 * constrained_modulus(&m))).abs() < 1e-12);
/// assert_eq!(top.sigma[1], 0.0);
/// ```
#[track_caller]
pub fn soil_column(material: &Material, height: f64, z: f64) -> SoilColumn {
    assert!(height > 0.0, "soil_column: height {height} must be > 0");
    let gamma = material.unit_weight();
    let s_v = -gamma * (height - z);
    let s_h = elastic_k0(material.poisson()) * s_v;
    SoilColumn {
        u_z: -gamma * z * (2.0 * height - z) / (2.0 * constrained_modulus(material)),
        sigma: [s_h, s_v, 0.0, s_h],
    }
}

/// Tip deflection of a cantilever by Timoshenko beam theory with shear correction: a beam of
/// length `L`, rectangular section of height `h` and thickness `t` (plane stress), clamped at
/// one end and loaded by a transverse force `P` at the other:
///
/// ```text
/// δ = P L³ / (3 E I) + P L / (κ G A),   I = t h³ / 12,  A = t h,  G = E / (2(1 + ν)),  κ = 5/6
/// ```
///
/// `κ = 5/6` is the usual shear coefficient of a rectangle. The exact 2D solution
/// ([`cantilever_exact`]) gives the same bending term and a shear term that depends on how the
/// clamp is idealised: `κ = ∞` with [`Clamp::AxisHorizontal`], `κ = 2/3` with
/// [`Clamp::SectionVertical`]; `5/6` lies between and is closest to a fully clamped
/// finite-element end.
///
/// # Panics
/// If a length is not positive.
///
/// # Examples
/// ```
/// use fem_core::analytical::cantilever_tip_deflection;
/// use fem_core::Material;
/// let m = Material::new(12.0, 0.0, 0.0).unwrap();
/// // L = 1, h = t = 1: I = 1/12, so bending gives P L³/(3EI) = 1/3; shear adds 1/(5/6 · 6).
/// let d = cantilever_tip_deflection(1.0, 1.0, 1.0, 1.0, &m);
/// assert!((d - (1.0 / 3.0 + 0.2)).abs() < 1e-14);
/// ```
#[track_caller]
pub fn cantilever_tip_deflection(
    load: f64,
    length: f64,
    height: f64,
    thickness: f64,
    material: &Material,
) -> f64 {
    assert!(
        length > 0.0 && height > 0.0 && thickness > 0.0,
        "cantilever_tip_deflection: lengths must be > 0 (L = {length}, h = {height}, t = {thickness})"
    );
    let (e, nu) = (material.young(), material.poisson());
    let g = e / (2.0 * (1.0 + nu));
    let i = thickness * height.powi(3) / 12.0;
    let kappa = 5.0 / 6.0;
    load * length.powi(3) / (3.0 * e * i) + load * length / (kappa * g * thickness * height)
}

/// How the clamped end of [`cantilever_exact`] is held. The exact solution cannot fix every
/// point of the end section; it fixes the centroid and one rotation there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Clamp {
    /// The beam axis is horizontal at the clamp: `∂v/∂x = 0` at the centroid. Tip deflection
    /// `P L³ / (3EI)` (no shear term).
    AxisHorizontal,
    /// The section's vertical element at the centroid does not rotate: `∂u/∂y = 0` there.
    /// Tip deflection `P L³ / (3EI) + P L c² / (2 I G)` (shear term with `κ = 2/3`).
    SectionVertical,
}

/// Exact plane-stress solution of a cantilever with a parabolic end shear (Timoshenko &
/// Goodier §21; Sadd ch. 8), in the crate's frame: the beam occupies `0 ≤ x ≤ L`,
/// `−c ≤ y ≤ c` (`c = h/2`), thickness `t`, clamped at `x = 0`, and the end `x = L` carries
/// the traction `t_y = −P (c² − y²) / (2I)` (resultant `P` downwards). With `I = t h³ / 12`:
///
/// ```text
/// σ_xx = P (L − x) y / I,   σ_yy = 0,   σ_xy = −P (c² − y²) / (2I)
/// u = P (L x − x²/2) y / (EI) − ν P y³ / (6EI) + P y³ / (6IG) + d₂ y
/// v = −ν P (L − x) y² / (2EI) − P (L x²/2 − x³/6) / (EI) + d₁ x
/// d₁ + d₂ = −P c² / (2IG);  AxisHorizontal: d₁ = 0;  SectionVertical: d₂ = 0
/// ```
///
/// The end tractions at `x = 0` (the reaction) are `σ_xx = P L y / I` and the parabolic shear;
/// `u(0, 0) = v(0, 0) = 0`. Returns the displacement `[u, v]` and the stress at `p = [x, y]`.
///
/// # Panics
/// If a length is not positive.
///
/// # Examples
/// ```
/// use fem_core::analytical::{cantilever_exact, Clamp};
/// use fem_core::Material;
/// let m = Material::new(12.0, 0.25, 0.0).unwrap();
/// let (u, s) = cantilever_exact(1.0, 2.0, 1.0, 1.0, &m, Clamp::AxisHorizontal, [2.0, 0.0]);
/// // δ = P L³/(3EI) = 8 / (3 · 12 · 1/12) = 8/3, downwards.
/// assert!((u[1] + 8.0 / 3.0).abs() < 1e-13);
/// assert!(s[0].abs() < 1e-15);
/// ```
#[track_caller]
pub fn cantilever_exact(
    load: f64,
    length: f64,
    height: f64,
    thickness: f64,
    material: &Material,
    clamp: Clamp,
    p: [f64; 2],
) -> ([f64; 2], Stress) {
    assert!(
        length > 0.0 && height > 0.0 && thickness > 0.0,
        "cantilever_exact: lengths must be > 0 (L = {length}, h = {height}, t = {thickness})"
    );
    let (e, nu) = (material.young(), material.poisson());
    let g = e / (2.0 * (1.0 + nu));
    let i = thickness * height.powi(3) / 12.0;
    let c = height / 2.0;
    let (pl, l) = (load, length);
    let [x, y] = p;
    let shear = -pl * c * c / (2.0 * i * g);
    let (d1, d2) = match clamp {
        Clamp::AxisHorizontal => (0.0, shear),
        Clamp::SectionVertical => (shear, 0.0),
    };
    let u = pl * (l * x - x * x / 2.0) * y / (e * i) - nu * pl * y.powi(3) / (6.0 * e * i)
        + pl * y.powi(3) / (6.0 * i * g)
        + d2 * y;
    let v = -nu * pl * (l - x) * y * y / (2.0 * e * i)
        - pl * (l * x * x / 2.0 - x.powi(3) / 6.0) / (e * i)
        + d1 * x;
    let stress = [
        pl * (l - x) * y / i,
        0.0,
        -pl * (c * c - y * y) / (2.0 * i),
        0.0,
    ];
    ([u, v], stress)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central differences of the displacement of `f` at `p`: `[[∂u/∂x, ∂u/∂y], [∂v/∂x, ∂v/∂y]]`.
    fn gradient(f: &dyn Fn([f64; 2]) -> [f64; 2], p: [f64; 2], h: f64) -> [[f64; 2]; 2] {
        let mut g = [[0.0; 2]; 2];
        for b in 0..2 {
            let (mut xp, mut xm) = (p, p);
            xp[b] += h;
            xm[b] -= h;
            let (fp, fm) = (f(xp), f(xm));
            for a in 0..2 {
                g[a][b] = (fp[a] - fm[a]) / (2.0 * h);
            }
        }
        g
    }

    #[test]
    fn cantilever_exact_is_compatible_with_its_stress_works() {
        let m = Material::new(200.0, 0.3, 0.0).unwrap();
        let (l, h, t, load) = (5.0, 1.0, 0.5, 2.0);
        let ps = m.elasticity(&crate::Idealization::PlaneStress { thickness: t });
        for clamp in [Clamp::AxisHorizontal, Clamp::SectionVertical] {
            let disp = |p: [f64; 2]| cantilever_exact(load, l, h, t, &m, clamp, p).0;
            for p in [[0.3, 0.2], [4.0, -0.45], [2.5, 0.0]] {
                let g = gradient(&disp, p, 1e-5);
                let eps = [g[0][0], g[1][1], g[0][1] + g[1][0]];
                let s = cantilever_exact(load, l, h, t, &m, clamp, p).1;
                for r in 0..3 {
                    let s_r: f64 = (0..3).map(|k| ps[(r, k)] * eps[k]).sum();
                    // Central differences of a cubic: truncation h²/6·|u'''| ≈ 1e-11, round-off
                    // ε|u|/h ≈ 1e-10 in the gradient, ×E = 200 in the stress (|σ| ≲ 120).
                    assert!((s_r - s[r]).abs() < 1e-6, "{clamp:?} {p:?} {r}");
                }
            }
            // Centroid of the clamp is fixed; the chosen rotation vanishes there.
            let g = gradient(&disp, [0.0, 0.0], 1e-5);
            assert!(disp([0.0, 0.0]).iter().all(|v| v.abs() < 1e-15));
            let rot = match clamp {
                Clamp::AxisHorizontal => g[1][0],
                Clamp::SectionVertical => g[0][1],
            };
            assert!(rot.abs() < 1e-8, "{clamp:?}: {rot}");
        }
        // Resultant of the end shear is −P: ∫ σ_xy t dy, with Simpson (exact for the parabola).
        let sxy = |y: f64| cantilever_exact(load, l, h, t, &m, Clamp::AxisHorizontal, [l, y]).1[2];
        let resultant = t * h / 6.0 * (sxy(-h / 2.0) + 4.0 * sxy(0.0) + sxy(h / 2.0));
        assert!((resultant + load).abs() < 1e-13);
        // SectionVertical's tip deflection matches Timoshenko beam theory with κ = 2/3.
        let d = -cantilever_exact(load, l, h, t, &m, Clamp::SectionVertical, [l, 0.0]).0[1];
        let g = 200.0 / 2.6;
        let beam = load * l.powi(3) / (3.0 * 200.0 * t / 12.0) + load * l / (2.0 / 3.0 * g * t * h);
        assert!((d - beam).abs() < 1e-12 * beam);
    }

    #[test]
    fn lame_cylinder_satisfies_equilibrium_and_boundary_conditions_works() {
        let m = Material::new(1000.0, 0.3, 0.0).unwrap();
        let (a, b, p) = (1.0, 3.0, 7.0);
        for ends in [
            CylinderEnds::PlaneStrain,
            CylinderEnds::Open,
            CylinderEnds::Closed,
        ] {
            let f = |r: f64| lame_cylinder(a, b, p, &m, ends, r);
            assert!((f(a).sigma_rr + p).abs() < 1e-13);
            assert!(f(b).sigma_rr.abs() < 1e-13);
            // dσ_rr/dr + (σ_rr − σ_θθ)/r = 0
            for r in [1.2, 2.0, 2.9] {
                let h = 1e-5;
                let ds = (f(r + h).sigma_rr - f(r - h).sigma_rr) / (2.0 * h);
                let s = f(r);
                assert!((ds + (s.sigma_rr - s.sigma_tt) / r).abs() < 1e-8);
                // Hooke: ε_θθ = u_r / r and ε_rr = du_r/dr with a uniform ε_zz.
                let (e, nu) = (1000.0, 0.3);
                let e_tt = (s.sigma_tt - nu * (s.sigma_rr + s.sigma_zz)) / e;
                let e_rr = (s.sigma_rr - nu * (s.sigma_tt + s.sigma_zz)) / e;
                assert!((s.u_r / r - e_tt).abs() < 1e-15);
                let du = (f(r + h).u_r - f(r - h).u_r) / (2.0 * h);
                assert!((du - e_rr).abs() < 1e-10);
                if ends == CylinderEnds::PlaneStrain {
                    let e_zz = (s.sigma_zz - nu * (s.sigma_rr + s.sigma_tt)) / e;
                    assert!(e_zz.abs() < 1e-16);
                }
            }
        }
    }

    #[test]
    fn soil_column_works() {
        let m = Material::new(5.0e4, 0.25, 18.0).unwrap();
        let hgt = 8.0;
        let base = soil_column(&m, hgt, 0.0);
        assert_eq!(base.u_z, 0.0);
        assert!((base.sigma[1] + 18.0 * 8.0).abs() < 1e-12);
        assert!((base.sigma[0] - base.sigma[1] / 3.0).abs() < 1e-12);
        // σ_zz = M du_z/dz.
        let h = 1e-4;
        let z = 3.0;
        let du = (soil_column(&m, hgt, z + h).u_z - soil_column(&m, hgt, z - h).u_z) / (2.0 * h);
        assert!((constrained_modulus(&m) * du - soil_column(&m, hgt, z).sigma[1]).abs() < 1e-8);
    }
}
