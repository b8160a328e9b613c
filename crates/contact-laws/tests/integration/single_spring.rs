//! RCCM single spring pulled open (seed 3.29 and §6.5; Raous, Cangémi & Cocou 1999).
//!
//! Sketch: one interface point, normal jump `u_n` imposed from 0 and increased monotonically
//! to full decohesion, `u_t = 0`, no contact (`r̄ = 0`), so the whole reaction is adhesive:
//! `σ = −r_n = C_n u_n β²`.
//!
//! Closed form with `α = 0`: `β = 1` until `u_0 = √(w/C_n)`, where the stress peaks at
//! `σ_0 = √(w C_n)`; then `β = w/(C_n u²)` and `σ = w²/(C_n u³)`. The work done to full
//! decohesion is `∫ σ du = w/2 + w/2 = w` (Dupré's energy), all of it dissipated.
//! With viscosity `α > 0` the peak rises with the opening rate and tends to `σ_0` as the
//! rate vanishes.
//!
//! Parameters: the seed's delamination interface (5.6.1), `C_n = 2e5 MPa/mm`,
//! `w = 1e-6 mJ/mm²`, in N, mm, s; and a unit-free case `C_n = w = 1`.

use contact_laws::{BetaScheme, ContactLaw, LocalVec2, Rccm, RccmParams};

fn law(c_n: f64, w: f64, alpha: f64) -> Rccm {
    Rccm::new(RccmParams {
        c_n,
        c_t: c_n,
        w,
        alpha,
        mu: 0.2,
        m: 1,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap()
}

/// Opening history: uniform on [0, u_0] (with u_0 a grid point), geometric beyond, up to
/// `u_max`, with `n` points on each part.
fn openings(u_0: f64, u_max: f64, n: usize) -> Vec<f64> {
    let mut u: Vec<f64> = (0..=n).map(|i| u_0 * i as f64 / n as f64).collect();
    let ratio = (u_max / u_0).powf(1.0 / n as f64);
    u.extend((1..=n).map(|i| u_0 * ratio.powi(i as i32)));
    u
}

/// Pulls the spring along `history` at opening rate `rate` through the `ContactLaw` API;
/// returns (u, σ) samples and the final β.
fn pull(law: &Rccm, history: &[f64], rate: f64) -> (Vec<(f64, f64)>, f64) {
    let mut state = law.initial_state();
    let mut u_prev = LocalVec2::zeros();
    let mut curve = Vec::with_capacity(history.len());
    for &u_n in history {
        let u = LocalVec2::planar(u_n, 0.0);
        let dt = (u_n - u_prev.n) / rate;
        state = law.update_state(&state, &u_prev, &u, dt);
        let r_adh = law.adhesive_reaction(&u, &state);
        assert!(r_adh.n <= 0.0, "an opened glued spring is in tension");
        curve.push((u_n, -r_adh.n));
        u_prev = u;
    }
    (curve, state.beta())
}

fn trapezoid(curve: &[(f64, f64)]) -> f64 {
    curve
        .windows(2)
        .map(|p| 0.5 * (p[1].0 - p[0].0) * (p[1].1 + p[0].1))
        .sum()
}

#[test]
fn rate_independent_spring_peaks_at_sqrt_w_c_works() {
    for (c_n, w) in [(2e5_f64, 1e-6_f64), (1.0, 1.0), (10500.0, 3e-3)] {
        let u_0 = (w / c_n).sqrt();
        let sigma_0 = (w * c_n).sqrt();
        let (curve, _) = pull(&law(c_n, w, 0.0), &openings(u_0, 1e3 * u_0, 2000), 1.0);
        let (u_peak, peak) = curve
            .iter()
            .copied()
            .fold((0.0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
        assert!(
            (peak - sigma_0).abs() <= 1e-12 * sigma_0,
            "peak {peak} vs √(wC) {sigma_0}"
        );
        assert!(
            (u_peak - u_0).abs() <= 1e-12 * u_0,
            "peak at {u_peak}, u_0 = {u_0}"
        );
        // Beyond the peak the closed form σ = w²/(C u³) holds at every sample.
        for &(u, s) in curve.iter().filter(|p| p.0 > u_0) {
            let exact = w * w / (c_n * u * u * u);
            assert!(
                (s - exact).abs() <= 1e-12 * exact,
                "σ({u}) = {s}, exact {exact}"
            );
        }
    }
}

#[test]
fn rate_independent_spring_dissipates_w_works() {
    // Trapezoidal work up to 1e3 u_0, plus the exact tail w²/(2 C u_max²) = w·5e-7.
    for (c_n, w) in [(2e5_f64, 1e-6_f64), (1.0, 1.0)] {
        let u_0 = (w / c_n).sqrt();
        let u_max = 1e3 * u_0;
        let (curve, beta_end) = pull(&law(c_n, w, 0.0), &openings(u_0, u_max, 20_000), 1.0);
        let tail = w * w / (2.0 * c_n * u_max * u_max);
        let work = trapezoid(&curve) + tail;
        // Energy still stored in the spring at u_max: ½ C u² β², which the tail releases.
        assert!(beta_end < 1e-5, "not fully debonded: β = {beta_end}");
        assert!((work - w).abs() <= 1e-6 * w, "work {work} vs w = {w}");
    }
}

#[test]
fn viscous_spring_peak_rises_with_rate_and_tends_to_sqrt_w_c() {
    // Unit-free case C = w = α = 1 (u_0 = 1, σ_0 = 1), opened to 50 u_0 at rates 10..1e-4.
    let sigma_0 = 1.0;
    let history = openings(1.0, 50.0, 20_000);
    let mut last_peak = f64::INFINITY;
    for rate in [10.0, 1.0, 0.1, 1e-2, 1e-3, 1e-4] {
        let (curve, _) = pull(&law(1.0, 1.0, 1.0), &history, rate);
        let peak = curve.iter().map(|p| p.1).fold(0.0, f64::max);
        assert!(
            peak >= sigma_0 * (1.0 - 1e-12),
            "viscous peak {peak} below √(wC)"
        );
        assert!(peak < last_peak, "peak must fall as the rate falls");
        last_peak = peak;
    }
    assert!(
        (last_peak - sigma_0) / sigma_0 < 1e-2,
        "slow peak {last_peak}"
    );
}
