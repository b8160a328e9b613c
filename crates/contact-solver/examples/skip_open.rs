//! The measurement behind `UzawaTuning::skip_open` (issue 14, "contacts that cannot close
//! leave the sweep"): the default solver with the restriction on and off, on problems whose
//! candidates are mostly open, timed in one run, alternated, median of `ROUNDS`.
//!
//! ```text
//! cargo run --release -p contact-solver --example skip_open -- [ROUNDS]
//! ```
//! `BIPO_QUICK=1`: one small half-space (16 cells across) and one small pile (5 × 5 × 3).
//! Problems: the 3D elastic half-space under a sphere (a Hertz patch of radius ≈ 0.45 in a
//! unit disc of nodes: ~20 % of the contacts close, ~40 % start with `q_n < 0`), dense, and
//! the same with a larger disc (radius 1.5: ~9 % close); shaken piles of rigid spheres
//! (rank-deficient `W`, contacts within the alert distance, many of them open), stored dense
//! and sparse (where the restriction is not tried: both columns then time the same solve). Every answer is
//! checked to agree with the unrestricted one (max |Δr| / max |r|).

#[path = "../tests/support/twins.rs"]
mod twins;
use contact_solver::local::generate::half_space::{HalfSpace, Indenter};
use contact_solver::local::generate::multibody::SpherePile;
use contact_solver::{Algorithm, ReducedProblem, UzawaSettings, UzawaSolver};
use std::error::Error;
use std::time::Instant;
use twins::sparse_twin;

fn problems() -> Result<Vec<(String, ReducedProblem)>, Box<dyn Error>> {
    let mut out = Vec::new();
    // quick (`BIPO_QUICK=1`, as CI runs it): one small problem of each kind
    let quick = std::env::var_os("BIPO_QUICK").is_some_and(|v| v != "0");
    let discs: &[(f64, usize)] = if quick {
        &[(1.0, 16)]
    } else {
        &[(1.0, 30), (1.0, 40), (1.5, 45)]
    };
    let piles: &[(usize, usize, u64)] = if quick {
        &[(5, 3, 3)]
    } else {
        &[(7, 5, 3), (10, 6, 4)]
    };
    for &(radius, cells) in discs {
        let hs = HalfSpace {
            radius,
            cells_across: cells,
            indenter: Indenter::Sphere { radius: 10.0 },
            ..HalfSpace::default()
        }
        .generate()?;
        let n = hs.problem.contact_count();
        out.push((format!("halfspace disc {radius} ({n}) dense"), hs.problem));
    }
    let shaken = SpherePile {
        jitter: 0.05,
        threshold: 0.2,
        initial_speed: 0.05,
        ..SpherePile::default()
    };
    for &(nx, layers, seed) in piles {
        let p = SpherePile {
            nx,
            ny: nx,
            layers,
            ..shaken
        }
        .generate(seed)?
        .problem;
        let n = p.contact_count();
        out.push((
            format!("pile {nx}x{nx}x{layers} ({n}) sparse"),
            sparse_twin(&p)?,
        ));
        out.push((format!("pile {nx}x{nx}x{layers} ({n}) dense"), p));
    }
    Ok(out)
}

fn main() -> Result<(), Box<dyn Error>> {
    let rounds: usize = std::env::args()
        .nth(1)
        .map_or(Ok(5), |a| a.parse())
        .map_err(|e| format!("ROUNDS: {e}"))?;
    faer::set_global_parallelism(faer::Par::Seq);
    let base = UzawaSettings::default()
        .with_tol(1e-8)
        .with_algorithm(Algorithm::Auto);
    println!(
        "| problem | may close (q_n < 0) | solved on | off: ms (algorithm) | on: ms (algorithm) | speed-up | max|Δr|/max|r| |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (name, p) in problems()? {
        let d = p.dimension();
        let may_close = p.q().iter().step_by(d).filter(|&&q| q < 0.0).count();
        let mut times = [Vec::new(), Vec::new()];
        let mut sols = [None, None];
        for _ in 0..rounds {
            for (k, skip) in [false, true].into_iter().enumerate() {
                let mut solver = UzawaSolver::new(base.with_skip_open(skip));
                let t0 = Instant::now();
                let sol = solver.solve(&p, &p.coulomb_laws())?;
                times[k].push(t0.elapsed().as_secs_f64() * 1e3);
                sols[k] = Some(sol);
            }
        }
        let (off, on) = (sols[0].take().ok_or("run")?, sols[1].take().ok_or("run")?);
        let r_max = off.r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        let diff = off
            .r
            .iter()
            .zip(&on.r)
            .fold(0.0_f64, |a, (x, y)| a.max((x - y).abs()));
        let med = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let (t_off, t_on) = (med(&mut times[0]), med(&mut times[1]));
        println!(
            "| {name} | {may_close} | {} | {t_off:.1} ({:?}) | {t_on:.1} ({:?}) | {:.2}× | {:.1e} |",
            on.report.solved_contacts,
            off.report.algorithm,
            on.report.algorithm,
            t_off / t_on,
            diff / r_max
        );
    }
    Ok(())
}
