//! Tests of the Drucker–Prager point (issue 40): closed-form strain paths, the apex, the
//! consistent tangent against finite differences, the bipotential inequality, objectivity.
//!
//! Closed forms: along a strain path whose deviator keeps one direction `n` (triaxial,
//! simple shear), perfect plasticity moves the stress in the `(s_m, ‖s‖)` plane on straight
//! lines: elastic until `f = 0` at `t_y`, then `λ(t) = (t − t_y) r / H` with `r = ∂f/∂t` of
//! the elastic path and `H = 2G / k_d² + K tan θ tan φ` (`docs/theory.md`). The return mapping
//! is exact on such paths whatever the step, so the tolerances are round-off (1e-10 relative
//! covers a few dozen operations on numbers of order the stress).

use super::drucker_prager::ConeMatch;
use super::{ConstitutivePoint, DruckerPrager, DruckerPragerParameters, PointState, Voigt};
use crate::FemError;
use proptest::prelude::*;

const YOUNG: f64 = 2e4;
const POISSON: f64 = 0.3;

fn point(phi: f64, theta: f64, c: f64, cone: ConeMatch) -> DruckerPrager {
    DruckerPrager::new(DruckerPragerParameters {
        young: YOUNG,
        poisson: POISSON,
        friction_angle: phi,
        dilatancy_angle: theta,
        cohesion: c,
        cone,
    })
    .unwrap()
}

fn isotropic(m: f64) -> Voigt {
    [m, m, m, 0.0, 0.0, 0.0]
}

fn dot(a: &Voigt, b: &Voigt) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn max_abs(a: &Voigt) -> f64 {
    a.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// One update from `committed` to `strain`; returns the trial state and the tangent.
fn step(point: &DruckerPrager, committed: &PointState, strain: &Voigt) -> (PointState, [Voigt; 6]) {
    let (mut trial, mut tangent) = (PointState::default(), [[0.0; 6]; 6]);
    point
        .update(committed, strain, &mut trial, &mut tangent)
        .unwrap();
    (trial, tangent)
}

/// `(tr ε, dev ε)` of a strain without shear.
fn volumetric_deviatoric(d: &Voigt) -> (f64, Voigt) {
    let tr = d[0] + d[1] + d[2];
    let mut dev = *d;
    for v in &mut dev[..3] {
        *v -= tr / 3.0;
    }
    (tr, dev)
}

/// The closed-form response along `ε(t) = t d` (no shear in `d`) from the confinement
/// `−p0 1`: the stress and the plastic strain at `t`.
fn closed_form_normal_path(dp: &DruckerPrager, p0: f64, d: &Voigt, t: f64) -> (Voigt, Voigt) {
    let params = dp.parameters();
    let (tan_phi, tan_theta) = (
        params.friction_angle.to_radians().tan(),
        params.dilatancy_angle.to_radians().tan(),
    );
    let (g, k, k_d) = (dp.shear_modulus(), dp.bulk_modulus(), dp.k_d());
    let (tr, dev) = volumetric_deviatoric(d);
    let dev_norm = dev[..3].iter().map(|v| v * v).sum::<f64>().sqrt();
    let n: Voigt = core::array::from_fn(|i| dev[i] / dev_norm);
    let r = 2.0 * g * dev_norm / k_d + k * tr * tan_phi;
    let t_y = (params.cohesion + p0 * tan_phi) / r;
    let h = 2.0 * g / (k_d * k_d) + k * tan_theta * tan_phi;
    let lambda = if t > t_y { (t - t_y) * r / h } else { 0.0 };
    let a = 2.0 * g * t * dev_norm - 2.0 * g * lambda / k_d;
    let m = -p0 + k * t * tr - k * lambda * tan_theta;
    let stress = core::array::from_fn(|i| if i < 3 { m + a * n[i] } else { 0.0 });
    let plastic = core::array::from_fn(|i| {
        if i < 3 {
            lambda * (n[i] / k_d + tan_theta / 3.0)
        } else {
            0.0
        }
    });
    (stress, plastic)
}

/// Walks `ε(t) = t d` over `times` (committing each step) and checks the closed form, the
/// flow direction, the dilatancy ratio and Mohr–Coulomb on the meridian `(major, minor)`
/// (indices of `σ₁`, `σ₃`), to 1e-10 relative (module docs).
fn check_normal_path(dp: &DruckerPrager, p0: f64, d: &Voigt, times: &[f64], mc: (usize, usize)) {
    let params = *dp.parameters();
    let (phi, theta) = (
        params.friction_angle.to_radians(),
        params.dilatancy_angle.to_radians(),
    );
    let mut committed = PointState::with_stress(isotropic(-p0));
    let mut plastic_steps = 0;
    for &t in times {
        let strain = d.map(|v| v * t);
        let (trial, _) = step(dp, &committed, &strain);
        let (stress, plastic) = closed_form_normal_path(dp, p0, d, t);
        let scale = max_abs(&stress);
        for i in 0..6 {
            assert!(
                (trial.stress[i] - stress[i]).abs() <= 1e-10 * scale,
                "t = {t}, σ[{i}] = {} vs {}",
                trial.stress[i],
                stress[i]
            );
            assert!(
                (trial.plastic_strain[i] - plastic[i]).abs()
                    <= 1e-10 * max_abs(&plastic).max(1e-300),
                "t = {t}, εᵖ[{i}] = {} vs {}",
                trial.plastic_strain[i],
                plastic[i]
            );
        }
        if trial.yielding {
            plastic_steps += 1;
            // the plastic increment: volumetric / deviatoric = k_d tan θ, deviator along s
            let increment: Voigt =
                core::array::from_fn(|i| trial.plastic_strain[i] - committed.plastic_strain[i]);
            let (tr, dev) = volumetric_deviatoric(&increment);
            let dev_norm = dev[..3].iter().map(|v| v * v).sum::<f64>().sqrt();
            let ratio = tr / dev_norm;
            assert!(
                (ratio - dp.k_d() * theta.tan()).abs() <= 1e-10 * (1.0 + ratio.abs()),
                "dilatancy ratio {ratio} vs k_d tan θ = {}",
                dp.k_d() * theta.tan()
            );
            let (_, s) = volumetric_deviatoric(&trial.stress);
            let s_norm = s[..3].iter().map(|v| v * v).sum::<f64>().sqrt();
            for i in 0..3 {
                assert!((dev[i] / dev_norm - s[i] / s_norm).abs() < 1e-10);
            }
            // Mohr–Coulomb on this meridian: (σ₁ − σ₃) + (σ₁ + σ₃) sin φ = 2c cos φ
            let (s1, s3) = (trial.stress[mc.0], trial.stress[mc.1]);
            let mohr_coulomb =
                (s1 - s3) + (s1 + s3) * phi.sin() - 2.0 * params.cohesion * phi.cos();
            assert!(
                mohr_coulomb.abs() <= 1e-10 * scale,
                "MC residual {mohr_coulomb}"
            );
        }
        committed = trial;
    }
    assert!(
        plastic_steps >= 3,
        "the path must yield ({plastic_steps} plastic steps)"
    );
}

/// Triaxial compression `ε = t (0.2, 0.2, −1) 1e-3` from 100 of confinement, on the outer
/// cone (which passes through Mohr–Coulomb's compression meridian): closed form, θ's flow and
/// Mohr–Coulomb at every plastic step, associated and not.
#[test]
fn issue_40_triaxial_compression_matches_the_closed_form() {
    let d = [0.2e-3, 0.2e-3, -1e-3, 0.0, 0.0, 0.0];
    // yield at t ≈ 21.8 (2 % axial strain) for θ = 0
    let times = [5.0, 15.0, 21.0, 30.0, 45.0, 70.0, 120.0];
    for theta in [0.0, 10.0, 30.0] {
        let dp = point(30.0, theta, 10.0, ConeMatch::Outer);
        check_normal_path(&dp, 100.0, &d, &times, (0, 2));
    }
}

/// Triaxial extension `ε = t (−0.5, −0.5, 1) 1e-3` (isochoric) from 100 of confinement on
/// the inner cone (through the extension meridian): as the compression test, with σ₁ = σ_zz.
#[test]
fn issue_40_triaxial_extension_matches_the_closed_form() {
    let d = [-0.5e-3, -0.5e-3, 1e-3, 0.0, 0.0, 0.0];
    // yield at t ≈ 3.55
    let times = [0.5, 1.7, 3.0, 4.0, 5.5, 7.5, 12.0];
    for theta in [0.0, 15.0, 25.0] {
        let dp = point(25.0, theta, 5.0, ConeMatch::Inner);
        check_normal_path(&dp, 100.0, &d, &times, (2, 0));
    }
}

/// Simple shear `γ_xy = t` from 50 of confinement (plane strain): `τ = G γ` until
/// `√2 τ / k_d − p0 tan φ = c`, then `τ̇ = G − √2 G λ̇ / k_d`, `ṡ_m = −K λ̇ tan θ`,
/// `γ̇ᵖ = √2 λ̇ / k_d`, `ε̇ᵖ_v = λ̇ tan θ` with `λ̇ = √2 G / (k_d H)`; for θ = 0 the shear stress
/// stays at its yield value; `ε̄ᵖ = √(2/3) ‖εᵖ‖` (parallel increments). Tolerance 1e-10
/// relative (module docs).
#[test]
fn issue_40_simple_shear_matches_the_closed_form() {
    let p0 = 50.0;
    for (theta, cone) in [
        (0.0, ConeMatch::PlaneStrain),
        (20.0, ConeMatch::PlaneStrain),
        (35.0, ConeMatch::Outer),
    ] {
        let dp = point(35.0, theta, 8.0, cone);
        let (g, k, k_d) = (dp.shear_modulus(), dp.bulk_modulus(), dp.k_d());
        let (tan_phi, tan_theta) = (35f64.to_radians().tan(), f64::to_radians(theta).tan());
        let h = 2.0 * g / (k_d * k_d) + k * tan_theta * tan_phi;
        let rate = 2f64.sqrt() * g / k_d;
        let t_y = (8.0 + p0 * tan_phi) / rate;
        let mut committed = PointState::with_stress(isotropic(-p0));
        for t in [0.3, 0.9, 1.4, 2.0, 3.3, 5.0].map(|f| f * t_y) {
            let (trial, _) = step(&dp, &committed, &[0.0, 0.0, 0.0, t, 0.0, 0.0]);
            let lambda = if t > t_y { (t - t_y) * rate / h } else { 0.0 };
            let tau = g * t - 2f64.sqrt() * g * lambda / k_d;
            let m = -p0 - k * lambda * tan_theta;
            let expected = [m, m, m, tau, 0.0, 0.0];
            let plastic_v = lambda * tan_theta;
            let expected_plastic = [
                plastic_v / 3.0,
                plastic_v / 3.0,
                plastic_v / 3.0,
                2f64.sqrt() * lambda / k_d,
                0.0,
                0.0,
            ];
            for i in 0..6 {
                assert!(
                    (trial.stress[i] - expected[i]).abs() <= 1e-10 * p0,
                    "θ = {theta}, t = {t}, σ[{i}]"
                );
                assert!(
                    (trial.plastic_strain[i] - expected_plastic[i]).abs() <= 1e-10 * t,
                    "εᵖ[{i}]"
                );
            }
            if theta == 0.0 && t > t_y {
                let tau_y = k_d * (8.0 + p0 * tan_phi) / 2f64.sqrt();
                assert!(
                    (trial.stress[3] - tau_y).abs() <= 1e-10 * tau_y,
                    "stationary τ"
                );
            }
            // the increments are parallel: ε̄ᵖ = √(2/3) ‖εᵖ‖, ‖εᵖ‖² = ε_v²/3 + γᵖ²/2
            let gamma_p = expected_plastic[3];
            let equivalent =
                (2.0 / 3.0 * (plastic_v * plastic_v / 3.0 + 0.5 * gamma_p * gamma_p)).sqrt();
            assert!(
                (trial.equivalent_plastic_strain - equivalent).abs() <= 1e-10 * t,
                "ε̄ᵖ = {} vs {equivalent}",
                trial.equivalent_plastic_strain
            );
            committed = trial;
        }
    }
}

/// The plane-strain match (the seed's `k_d`): for in-plane principal stresses on Mohr–Coulomb,
/// the most favourable out-of-plane stress (where `∂f/∂σ_zz = 0`, i.e. `ε̇ᵖ_zz = 0` for
/// associated flow) puts the point exactly on the cone; tolerance 1e-12 of the stress (the
/// minimum is found by golden section to 1e-9 in σ_zz, and `f` is quadratic there).
#[test]
fn issue_40_plane_strain_cone_reproduces_mohr_coulomb() {
    for phi_deg in [0.0f64, 10.0, 20.0, 35.0, 50.0] {
        let (phi, c) = (phi_deg.to_radians(), 7.0);
        let dp = point(phi_deg, 0.0, c, ConeMatch::PlaneStrain);
        // the same number as the cone inscribed in the pyramid (tangent to its faces)
        let inscribed = 6f64.sqrt() * phi.cos() / (3.0 + phi.sin().powi(2)).sqrt();
        assert!(
            (dp.k_d() - inscribed).abs() < 1e-14,
            "k_d = {} vs {inscribed}",
            dp.k_d()
        );
        for center in [-40.0, -5.0, 0.0] {
            // σ₁,₃ = p ± R on MC: R = c cos φ − p sin φ
            let radius = c * phi.cos() - center * phi.sin();
            let f =
                |zz: f64| dp.yield_function(&[center + radius, center - radius, zz, 0.0, 0.0, 0.0]);
            let (mut lo, mut hi) = (center - 3.0 * radius, center + 3.0 * radius);
            for _ in 0..200 {
                let (x1, x2) = (lo + 0.382 * (hi - lo), hi - 0.382 * (hi - lo));
                if f(x1) < f(x2) { hi = x2 } else { lo = x1 }
            }
            let min = f(0.5 * (lo + hi));
            assert!(
                min.abs() < 1e-12 * (c + center.abs()),
                "φ = {phi_deg}, p = {center}: min f = {min}"
            );
        }
    }
}

/// Hydrostatic tension beyond the apex returns to `σ = (c / tan φ) 1` with a purely
/// volumetric plastic strain `(s_m,trial − c / tan φ) / K` and a zero tangent; with a little
/// shear the apex still holds while `Δεᵖ = C⁻¹(σ_trial − σ_apex)` lies in the dilatancy cone.
/// Tolerance 1e-12 relative (one division).
#[test]
fn issue_40_apex_return_works() {
    let dp = point(30.0, 10.0, 10.0, ConeMatch::PlaneStrain);
    let apex = dp.apex_mean_stress().unwrap();
    let k = dp.bulk_modulus();
    let committed = PointState::default();
    let (trial, tangent) = step(&dp, &committed, &isotropic(1e-2));
    for i in 0..6 {
        let expected = if i < 3 { apex } else { 0.0 };
        assert!((trial.stress[i] - expected).abs() <= 1e-12 * apex);
        let plastic = if i < 3 {
            (3.0 * k * 1e-2 - apex) / (3.0 * k)
        } else {
            0.0
        };
        assert!((trial.plastic_strain[i] - plastic).abs() <= 1e-12 * 1e-2);
    }
    assert!(tangent.iter().flatten().all(|v| *v == 0.0) && trial.yielding);
    let (sheared, _) = step(&dp, &committed, &[1e-2, 1e-2, 1e-2, 1e-3, 0.0, 0.0]);
    assert_eq!(sheared.stress, isotropic(apex), "deep in the apex region");
    assert!(
        dp.bipotential(&sheared.plastic_strain, &sheared.stress)
            .is_finite(),
        "Δεᵖ ∈ K_ε"
    );
    assert!(
        dp.apex_mean_stress().is_some()
            && point(0.0, 0.0, 1.0, ConeMatch::Outer)
                .apex_mean_stress()
                .is_none()
    );
}

/// Von Mises at φ = 0: simple shear gives `τ = min(G γ, k)` with `k = c` (plane-strain match)
/// and `k = 2c / √3` (outer and inner), and uniaxial strain `ε_xx = t` gives
/// `σ_xx − σ_yy = √3 k` after yield with `s_m = K t` (plastic flow isochoric). 1e-12 relative.
#[test]
fn issue_40_von_mises_is_the_frictionless_case() {
    for (cone, k_expected) in [
        (ConeMatch::PlaneStrain, 3.0),
        (ConeMatch::Outer, 6.0 / 3f64.sqrt()),
        (ConeMatch::Inner, 6.0 / 3f64.sqrt()),
    ] {
        let dp = point(0.0, 0.0, 3.0, cone);
        let g = dp.shear_modulus();
        for gamma in [1e-4, 5e-4, 1e-3, 1e-2] {
            let (trial, _) = step(
                &dp,
                &PointState::default(),
                &[0.0, 0.0, 0.0, gamma, 0.0, 0.0],
            );
            let tau = (g * gamma).min(k_expected);
            assert!(
                (trial.stress[3] - tau).abs() <= 1e-12 * k_expected,
                "{cone:?}: τ"
            );
            assert!(trial.stress[..3].iter().all(|v| v.abs() < 1e-12));
        }
        let (trial, _) = step(
            &dp,
            &PointState::default(),
            &[1e-2, 0.0, 0.0, 0.0, 0.0, 0.0],
        );
        let q = trial.stress[0] - trial.stress[1];
        assert!(
            (q - 3f64.sqrt() * k_expected).abs() <= 1e-12 * k_expected,
            "{cone:?}: q = {q}"
        );
        let mean = trial.stress[..3].iter().sum::<f64>() / 3.0;
        assert!((mean - dp.bulk_modulus() * 1e-2).abs() <= 1e-12 * mean);
        let volumetric: f64 = trial.plastic_strain[..3].iter().sum();
        assert!(volumetric.abs() < 1e-15, "von Mises flow is isochoric");
    }
    let vm = DruckerPrager::von_mises(YOUNG, POISSON, 3.0).unwrap();
    assert_eq!(vm, point(0.0, 0.0, 3.0, ConeMatch::PlaneStrain));
}

/// Central finite differences of `update` against its consistent tangent, relative 1e-6 of the
/// elastic stiffness (step 1e-8 on strains of 1e-3: truncation ~1e-10, round-off ~1e-11),
/// in the elastic, smooth (associated, not, φ = 0) and apex regimes, from a committed state
/// with prestress and earlier plastic strain. The smooth tangent is non-symmetric exactly when
/// θ ≠ φ.
#[test]
fn issue_40_consistent_tangent_matches_finite_differences() {
    let cases = [
        (30.0, 30.0, [1e-3, -2e-3, 0.5e-3, 2e-3, -1e-3, 0.7e-3], true),
        (30.0, 5.0, [1e-3, -2e-3, 0.5e-3, 2e-3, -1e-3, 0.7e-3], true),
        (0.0, 0.0, [1e-3, -2e-3, 0.5e-3, 2e-3, -1e-3, 0.7e-3], true),
        (
            40.0,
            0.0,
            [-0.4e-3, 1e-3, -0.6e-3, 1.5e-3, 0.0, -2e-3],
            true,
        ),
        (30.0, 10.0, [3e-3, 3e-3, 3e-3, 1e-4, 0.0, 0.0], true),
        (30.0, 10.0, [1e-5, 0.0, -1e-5, 1e-5, 0.0, 0.0], false),
    ];
    for (phi, theta, strain, must_yield) in cases {
        let dp = point(phi, theta, 5.0, ConeMatch::PlaneStrain);
        // an earlier plastic step, committed
        let start = PointState::with_stress([-20.0, -30.0, -25.0, 2.0, -1.0, 0.5]);
        let (committed, _) = step(&dp, &start, &[0.0, 0.0, 0.0, 1e-3, 0.0, 0.0]);
        let (trial, tangent) = step(&dp, &committed, &strain);
        assert_eq!(trial.yielding, must_yield, "φ = {phi}, θ = {theta}");
        let scale = dp
            .elastic_tangent()
            .iter()
            .flatten()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let h = 1e-8;
        for j in 0..6 {
            let (mut plus, mut minus) = (strain, strain);
            plus[j] += h;
            minus[j] -= h;
            let (sp, _) = step(&dp, &committed, &plus);
            let (sm, _) = step(&dp, &committed, &minus);
            for (i, row) in tangent.iter().enumerate() {
                let fd = (sp.stress[i] - sm.stress[i]) / (2.0 * h);
                assert!(
                    (fd - row[j]).abs() <= 1e-6 * scale,
                    "φ = {phi}, θ = {theta}: D[{i}][{j}] = {} vs fd {fd}",
                    row[j]
                );
            }
        }
        let asymmetry = (0..6)
            .flat_map(|i| (0..6).map(move |j| (i, j)))
            .fold(0.0f64, |m, (i, j)| {
                m.max((tangent[i][j] - tangent[j][i]).abs())
            });
        let smooth = must_yield && trial.stress[3..].iter().any(|v| *v != 0.0);
        if phi == theta || !smooth {
            assert!(asymmetry <= 1e-12 * scale, "symmetric: {asymmetry}");
        } else {
            assert!(
                asymmetry > 1e-3 * scale,
                "non-associated: non-symmetric ({asymmetry})"
            );
        }
    }
}

/// Rotating the strain path (and the initial stress) rotates the stresses and plastic strains
/// and leaves ε̄ᵖ unchanged: the law is isotropic. 1e-12 relative (a rotation costs a few ulps).
#[test]
fn issue_40_update_is_objective() {
    let rotation = nalgebra::Rotation3::from_euler_angles(0.3, -1.1, 2.0);
    let rotate = |v: &Voigt, engineering: bool| -> Voigt {
        let f = if engineering { 0.5 } else { 1.0 };
        let t = nalgebra::Matrix3::new(
            v[0],
            f * v[3],
            f * v[5],
            f * v[3],
            v[1],
            f * v[4],
            f * v[5],
            f * v[4],
            v[2],
        );
        let r = rotation.matrix() * t * rotation.matrix().transpose();
        [
            r[(0, 0)],
            r[(1, 1)],
            r[(2, 2)],
            r[(0, 1)] / f,
            r[(1, 2)] / f,
            r[(2, 0)] / f,
        ]
    };
    let dp = point(30.0, 8.0, 5.0, ConeMatch::Outer);
    let prestress = [-20.0, -30.0, -25.0, 2.0, -1.0, 0.5];
    let path = [
        [1e-3, -2e-3, 0.5e-3, 2e-3, -1e-3, 0.7e-3],
        [2e-3, -3e-3, 0.0, 5e-3, -1e-3, 0.0],
        [2e-2, 2e-2, 2.5e-2, 5e-3, -1e-3, 0.0],
    ];
    let (mut a, mut b) = (
        PointState::with_stress(prestress),
        PointState::with_stress(rotate(&prestress, false)),
    );
    for strain in path {
        (a, _) = step(&dp, &a, &strain);
        (b, _) = step(&dp, &b, &rotate(&strain, true));
        let (sigma, plastic) = (rotate(&a.stress, false), rotate(&a.plastic_strain, true));
        for i in 0..6 {
            assert!((sigma[i] - b.stress[i]).abs() <= 1e-12 * max_abs(&sigma));
            assert!((plastic[i] - b.plastic_strain[i]).abs() <= 1e-12 * max_abs(&plastic));
        }
        let equivalent = a.equivalent_plastic_strain;
        assert!((equivalent - b.equivalent_plastic_strain).abs() <= 1e-12 * equivalent);
        assert!(a.yielding && b.yielding);
    }
}

/// Each bad parameter is named.
#[test]
fn issue_40_drucker_prager_rejects_bad_parameters() {
    let good = DruckerPragerParameters {
        young: YOUNG,
        poisson: POISSON,
        friction_angle: 30.0,
        dilatancy_angle: 10.0,
        cohesion: 1.0,
        cone: ConeMatch::default(),
    };
    let named = |p: DruckerPragerParameters| match DruckerPrager::new(p) {
        Err(FemError::InvalidParameter { name, .. }) => name,
        other => panic!("expected an invalid parameter, got {other:?}"),
    };
    assert_eq!(
        named(DruckerPragerParameters {
            dilatancy_angle: 31.0,
            ..good
        }),
        "dilatancy_angle"
    );
    assert_eq!(
        named(DruckerPragerParameters {
            dilatancy_angle: -1.0,
            ..good
        }),
        "dilatancy_angle"
    );
    assert_eq!(
        named(DruckerPragerParameters {
            friction_angle: 90.0,
            ..good
        }),
        "friction_angle"
    );
    assert_eq!(
        named(DruckerPragerParameters {
            friction_angle: -5.0,
            ..good
        }),
        "friction_angle"
    );
    assert_eq!(
        named(DruckerPragerParameters {
            friction_angle: f64::NAN,
            ..good
        }),
        "friction_angle"
    );
    assert_eq!(
        named(DruckerPragerParameters {
            cohesion: -1.0,
            ..good
        }),
        "cohesion"
    );
    assert_eq!(
        named(DruckerPragerParameters {
            cohesion: f64::INFINITY,
            ..good
        }),
        "cohesion"
    );
    assert_eq!(
        named(DruckerPragerParameters {
            friction_angle: 0.0,
            dilatancy_angle: 0.0,
            cohesion: 0.0,
            ..good
        }),
        "cohesion"
    );
    assert_eq!(
        named(DruckerPragerParameters {
            poisson: 0.5,
            ..good
        }),
        "poisson"
    );
    assert_eq!(
        named(DruckerPragerParameters {
            poisson: -0.1,
            ..good
        }),
        "poisson"
    );
    assert_eq!(
        named(DruckerPragerParameters { young: 0.0, ..good }),
        "young"
    );
    assert!(
        DruckerPrager::new(DruckerPragerParameters {
            dilatancy_angle: 30.0,
            cohesion: 0.0,
            ..good
        })
        .is_ok()
    );
    let dp = DruckerPrager::new(good).unwrap();
    let (mut trial, mut tangent) = (PointState::default(), [[0.0; 6]; 6]);
    let err = dp.update(
        &PointState::default(),
        &[0.0, f64::NAN, 0.0, 0.0, 0.0, 0.0],
        &mut trial,
        &mut tangent,
    );
    assert!(matches!(
        err,
        Err(FemError::InvalidParameter { name: "strain", .. })
    ));
    let err = dp.update(
        &PointState::default(),
        &[1e300, -1e300, 0.0, 0.0, 0.0, 0.0],
        &mut trial,
        &mut tangent,
    );
    assert!(
        matches!(err, Err(FemError::InvalidParameter { name: "strain", .. })),
        "overflow"
    );
    // φ = 0 with a cohesion tiny beside the trial stress: no apex, no NaN
    let tiny = point(0.0, 0.0, 1e-30, ConeMatch::PlaneStrain);
    let (state, _) = step(
        &tiny,
        &PointState::default(),
        &[1e-2, 0.0, 0.0, 1e-2, 0.0, 0.0],
    );
    assert!(state.stress.iter().all(|v| v.is_finite()) && state.yielding);
    assert_eq!(
        dp.bipotential(&[f64::NAN; 6], &isotropic(0.0)),
        f64::INFINITY
    );
}

/// A stress inside `K_σ` from raw numbers: the mean stress clipped below the apex, the
/// deviator scaled to a fraction `rho` of the cone's radius there.
fn admissible_stress(dp: &DruckerPrager, raw: &Voigt, rho: f64) -> Voigt {
    let c = dp.parameters().cohesion;
    let tan_phi = dp.parameters().friction_angle.to_radians().tan();
    let (tr, dev) = volumetric_deviatoric(raw);
    let m = dp
        .apex_mean_stress()
        .map_or(tr / 3.0, |apex| (tr / 3.0).min(apex));
    let norm = (dev[0] * dev[0]
        + dev[1] * dev[1]
        + dev[2] * dev[2]
        + 2.0 * (dev[3] * dev[3] + dev[4] * dev[4] + dev[5] * dev[5]))
        .sqrt();
    let radius = rho * dp.k_d() * (c - m * tan_phi);
    core::array::from_fn(|i| {
        let s = if norm > 0.0 {
            dev[i] * radius / norm
        } else {
            0.0
        };
        if i < 3 { m + s } else { s }
    })
}

fn law() -> impl Strategy<Value = DruckerPrager> {
    (0.0..50.0f64, 0.0..=1.0f64, 0.5..20.0f64, 0..3usize).prop_map(|(phi, frac, c, cone)| {
        let cone = [ConeMatch::PlaneStrain, ConeMatch::Outer, ConeMatch::Inner][cone];
        point(phi, phi * frac, c, cone)
    })
}

fn voigt(range: f64) -> impl Strategy<Value = Voigt> {
    prop::array::uniform6(-range..range)
}

proptest! {
    /// Fenchel's inequality of the bipotential, `b_p(ε̇ᵖ, σ) ≥ ε̇ᵖ : σ`, on arbitrary pairs and
    /// on admissible ones (σ ∈ K_σ, ε̇ᵖ ∈ K_ε, half of them on the cone's boundary), to
    /// round-off (1e-12 of `|σ| |ε̇ᵖ|`).
    #[test]
    fn issue_40_bipotential_bounds_the_power(
        dp in law(), raw_s in voigt(100.0), raw_e in voigt(1.0), rho in 0.0..=1.0f64, extra in -1.0..1.0f64,
    ) {
        prop_assert!(dp.bipotential(&raw_e, &raw_s) >= dot(&raw_e, &raw_s) - 1e-12 * max_abs(&raw_s) * max_abs(&raw_e));
        let sigma = admissible_stress(&dp, &raw_s, rho);
        let (_, dev) = volumetric_deviatoric(&raw_e);
        let dev_norm = (dev[..3].iter().map(|v| v * v).sum::<f64>() + 0.5 * dev[3..].iter().map(|v| v * v).sum::<f64>()).sqrt();
        let tan_theta = dp.parameters().dilatancy_angle.to_radians().tan();
        let e_m = dp.k_d() * tan_theta * dev_norm + extra.max(0.0);
        let rate: Voigt = core::array::from_fn(|i| if i < 3 { dev[i] + e_m / 3.0 } else { dev[i] });
        let b = dp.bipotential(&rate, &sigma);
        let power = dot(&rate, &sigma);
        prop_assert!(b >= power - 1e-12 * max_abs(&sigma).max(dp.parameters().cohesion) * max_abs(&rate), "b = {b}, power = {power}");
        if dp.parameters().friction_angle > 0.0 || extra <= 0.0 {
            prop_assert!(b.is_finite(), "admissible pair: finite b_p");
        }
    }

    /// On the law's pairs (σ from an update, ε̇ᵖ its plastic strain increment) the bipotential
    /// equals the power, `b_p = Δεᵖ : σ`, to 1e-10 of `|σ| |Δεᵖ|`; after every update
    /// `f(σ) ≤ 1e-10 (c + |s_m| tan φ)`.
    #[test]
    fn issue_40_law_pairs_are_extremal(
        dp in law(), raw_s in voigt(100.0), rho in 0.0..=1.0f64, strain in voigt(2e-2),
    ) {
        let committed = PointState::with_stress(admissible_stress(&dp, &raw_s, rho));
        let (trial, _) = step(&dp, &committed, &strain);
        let tan_phi = dp.parameters().friction_angle.to_radians().tan();
        let mean = trial.stress[..3].iter().sum::<f64>() / 3.0;
        let f = dp.yield_function(&trial.stress);
        prop_assert!(f <= 1e-10 * (dp.parameters().cohesion + mean.abs() * tan_phi), "f = {f}");
        let increment: Voigt = core::array::from_fn(|i| trial.plastic_strain[i] - committed.plastic_strain[i]);
        let b = dp.bipotential(&increment, &trial.stress);
        let power = dot(&increment, &trial.stress);
        prop_assert!((b - power).abs() <= 1e-10 * max_abs(&trial.stress).max(dp.parameters().cohesion) * max_abs(&increment), "b = {b}, power = {power}");
        prop_assert_eq!(trial.yielding, max_abs(&increment) > 0.0);
    }
}

/// 0 elastic, 1 smooth return, 2 apex.
fn regime(state: &PointState) -> u8 {
    let (_, s) = volumetric_deviatoric(&state.stress);
    match (state.yielding, max_abs(&s) > 0.0) {
        (false, _) => 0,
        (true, true) => 1,
        (true, false) => 2,
    }
}

proptest! {
    /// The consistent tangent along a random direction against central differences of
    /// `update` (GetFEM's habit), for random laws, committed stresses and strains, where the
    /// three updates share a regime and the deviator is not tiny (the curvature of `n` scales
    /// as `1/‖s‖`): step 1e-9 on strains of 1e-2, truncation `(1e-9 / 1e-5)²` at worst,
    /// round-off `1e-16 · 1e3 / 1e-9`; tolerance 1e-6 of `C`.
    #[test]
    fn issue_40_tangent_matches_finite_differences_along_random_directions(
        dp in law(), raw_s in voigt(100.0), rho in 0.0..=1.0f64, strain in voigt(2e-2),
        direction in voigt(1.0),
    ) {
        let committed = PointState::with_stress(admissible_stress(&dp, &raw_s, rho));
        let (trial, tangent) = step(&dp, &committed, &strain);
        let h = 1e-9;
        let plus: Voigt = core::array::from_fn(|i| strain[i] + h * direction[i]);
        let minus: Voigt = core::array::from_fn(|i| strain[i] - h * direction[i]);
        let ((sp, _), (sm, _)) = (step(&dp, &committed, &plus), step(&dp, &committed, &minus));
        let (_, s) = volumetric_deviatoric(&trial.stress);
        prop_assume!(regime(&sp) == regime(&trial) && regime(&sm) == regime(&trial));
        prop_assume!(regime(&trial) != 1 || max_abs(&s) > 1e-5 * dp.shear_modulus());
        let scale = dp.elastic_tangent().iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for (i, row) in tangent.iter().enumerate() {
            let fd = (sp.stress[i] - sm.stress[i]) / (2.0 * h);
            let exact = dot(row, &direction);
            prop_assert!((fd - exact).abs() <= 1e-6 * scale, "row {i}: D·d = {exact}, fd {fd}");
        }
    }
}
