//! Criterion benches of the local laws: the projection onto K_μ (2D and 3D), the contact
//! bipotential b_c, the RCCM correction (projection onto K_μ̄ with μ̄ = μ f(β)) and the β
//! updates. Each bench runs over a batch of 1024 precomputed inputs mixing the three cases
//! of seed 5.38, so branch prediction sees a realistic pattern; the time per call is the
//! batch time divided by 1024 (criterion prints it as throughput in elements/s).
//!
//! Run: `cargo bench -p contact-laws --bench laws`

use contact_laws::{
    BetaScheme, ContactLaw, CoulombCone, LocalVec, LocalVec2, LocalVec3, Rccm, RccmParams,
    RccmState, beta_implicit_euler, beta_rate_independent, contact_bipotential,
};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;

const N: usize = 1024;

/// A deterministic pseudo-random sequence in [-1, 1] (xorshift), to avoid a rand dependency.
fn noise(seed: u64) -> impl FnMut() -> f64 {
    let mut x = seed;
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

fn inputs2() -> Vec<LocalVec2> {
    let mut r = noise(42);
    (0..N).map(|_| LocalVec2::planar(r(), r())).collect()
}

fn inputs3() -> Vec<LocalVec3> {
    let mut r = noise(7);
    (0..N).map(|_| LocalVec3::spatial(r(), r(), r())).collect()
}

fn bench_projection(c: &mut Criterion) {
    let cone = CoulombCone::new(0.3).unwrap();
    let mut g = c.benchmark_group("projection");
    g.throughput(Throughput::Elements(N as u64));
    let taus2 = inputs2();
    let mut out2 = vec![LocalVec2::zeros(); N];
    g.bench_function("k_mu_2d", |b| {
        b.iter(|| {
            for (o, t) in out2.iter_mut().zip(black_box(&taus2)) {
                *o = cone.project(t);
            }
            black_box(&out2);
        })
    });
    let taus3 = inputs3();
    let mut out3 = vec![LocalVec3::zeros(); N];
    g.bench_function("k_mu_3d", |b| {
        b.iter(|| {
            for (o, t) in out3.iter_mut().zip(black_box(&taus3)) {
                *o = cone.project(t);
            }
            black_box(&out3);
        })
    });
    // The RCCM correction: μ̄ = μ (1 − β) per contact, then the projection.
    let law = Rccm::new(RccmParams {
        c_n: 2e5,
        c_t: 2e5,
        w: 1e-6,
        alpha: 1.0,
        mu: 0.2,
        m: 1,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap();
    let mut r = noise(3);
    let states: Vec<RccmState> = (0..N)
        .map(|_| RccmState::new(0.5 * (r() + 1.0)).unwrap())
        .collect();
    g.bench_function("rccm_k_mu_bar_2d", |b| {
        b.iter(|| {
            for ((o, t), s) in out2.iter_mut().zip(black_box(&taus2)).zip(&states) {
                *o = law.project(t, s);
            }
            black_box(&out2);
        })
    });
    g.finish();
}

fn bench_bipotential(c: &mut Criterion) {
    let cone = CoulombCone::new(0.3).unwrap();
    let mut g = c.benchmark_group("bipotential");
    g.throughput(Throughput::Elements(N as u64));
    // Pairs on the domain (r ∈ K, u̇_n ≥ 0), so the coupling term is evaluated.
    let rs: Vec<LocalVec2> = inputs2().iter().map(|t| cone.project(t)).collect();
    let dus: Vec<LocalVec2> = inputs2()
        .iter()
        .rev()
        .map(|v| LocalVec::planar(v.n.abs(), v.t[0]))
        .collect();
    g.bench_function("b_c_2d", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for (du, r) in black_box(&dus).iter().zip(black_box(&rs)) {
                s += contact_bipotential(&cone, du, r);
            }
            black_box(s)
        })
    });
    g.finish();
}

fn bench_beta(c: &mut Criterion) {
    let mut g = c.benchmark_group("beta_update");
    g.throughput(Throughput::Elements(N as u64));
    let mut r = noise(11);
    // (β_prev, E) with about half the contacts damaging (E β_prev > w = 1).
    let data: Vec<(f64, f64)> = (0..N)
        .map(|_| (0.5 * (r() + 1.0), 2.0 * (r() + 1.0)))
        .collect();
    let mut out = vec![0.0; N];
    g.bench_function("implicit_euler", |b| {
        b.iter(|| {
            for (o, &(bp, e)) in out.iter_mut().zip(black_box(&data)) {
                *o = beta_implicit_euler(bp, e, 1.0, 1.0, 0.05);
            }
            black_box(&out);
        })
    });
    g.bench_function("rate_independent", |b| {
        b.iter(|| {
            for (o, &(bp, e)) in out.iter_mut().zip(black_box(&data)) {
                *o = beta_rate_independent(bp, e, 1.0);
            }
            black_box(&out);
        })
    });
    g.finish();
}

criterion_group!(benches, bench_projection, bench_bipotential, bench_beta);
criterion_main!(benches);
