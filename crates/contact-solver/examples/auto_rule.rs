//! The measurement behind [`Algorithm::Auto`]'s rule (issue 14): Newton, the accelerated
//! Gauss–Seidel sweep (AGS) and the plain sweep (GS) on the kinds of problems users bring, in
//! 2D and 3D, with `W` dense and sparse, timed in one run with the algorithms alternated.
//!
//! ```text
//! cargo run --release -p contact-solver --example auto_rule -- [ROUNDS]
//! ```
//! Timing: cold start (`r = 0`), one thread (`faer::Par::Seq`), fallback off, tolerance 1e-8,
//! at most 5 000 iterations; `ROUNDS` (default 5) rounds, each timing every algorithm once on
//! every problem (alternated, so the machine's load falls on all alike), and the **median**
//! per (problem, algorithm). A round stops timing an algorithm on a problem once one run
//! took over 2 s (its count is then below `ROUNDS`).
//!
//! Problems: the 2D plane-strain Hertz scene (P2, `M × M` cells) frictionless and sliding
//! (`μ = 0.3`, `q_t + 10⁻⁴`), random dense problems ([`random_problem_in`]), the 3D elastic
//! half-space under a sliding sphere ([`half_space`]), shaken piles of rigid spheres
//! ([`multibody`], rank-deficient `W`) stored dense and sparse, among them (issue 37) towers
//! and piles in a box where Newton creeps for thousands of iterations, and random block-sparse
//! problems ([`random_sparse_problem`]).
//!
//!
//! `BIPO_QUICK=1` (as CI runs it, with `ROUNDS = 1`): the smallest problem of each kind (2D
//! Hertz 16 cells, random 200 and sparse random 2 000, half-space 12, random 100, the 5 × 5 × 5
//! pile, the tower and the 4 × 4 × 8 loose box, sparse random 1 000), every algorithm on each,
//! the same table; the full list took 33 s of CI's debug build, most of it in the largest
//! problems, where one run of the plain sweep can take seconds.
//!
//! [`half_space`]: contact_solver::local::generate::half_space
//! [`multibody`]: contact_solver::local::generate::multibody

#[path = "../tests/support/hertz_scene.rs"]
mod hertz_scene;
#[path = "../tests/support/twins.rs"]
mod twins;

use contact_solver::local::generate::half_space::{HalfSpace, Indenter};
use contact_solver::local::generate::multibody::SpherePile;
use contact_solver::local::generate::{random_problem_in, random_sparse_problem};
use contact_solver::{Algorithm, ReducedProblem, SimulationSettings, UzawaSettings, UzawaSolver};
use fem_core::{ElementKind, Idealization};
use hertz_scene::HertzScene;
use std::error::Error;
use std::time::Instant;
use twins::sparse_twin;

const ALGORITHMS: [Algorithm; 4] = [
    Algorithm::Newton,
    Algorithm::AndersonGaussSeidel,
    Algorithm::GaussSeidel,
    Algorithm::Auto,
];

fn hertz(cells: usize) -> Result<[(String, ReducedProblem); 2], Box<dyn Error>> {
    let scene = HertzScene::new(Idealization::PlaneStrain, ElementKind::Tri6, cells);
    let mut sim = scene.simulation(
        SimulationSettings::default().with_flexibility(contact_solver::FlexibilityMode::Dense),
    );
    sim.step(1.0, 1.0)?;
    let p = sim.last_reduced_problem().ok_or("no problem")?.clone();
    let q = (p.q().iter().enumerate())
        .map(|(k, &a)| if k % 2 == 1 { a + 1e-4 } else { a })
        .collect();
    let slide = ReducedProblem::new(
        p.w_dense().ok_or("dense")?.to_vec(),
        q,
        vec![0.3; p.contact_count()],
    )?;
    Ok([
        (format!("2D hertz_{cells}"), p),
        (format!("2D hertz_{cells}_slide"), slide),
    ])
}

/// The problems, all of them or (`quick`) the smallest of each kind (module docs).
fn problems(quick: bool) -> Result<Vec<(String, ReducedProblem)>, Box<dyn Error>> {
    // how many sizes of each kind: the first (smallest) alone when quick
    let sizes = if quick { 1 } else { usize::MAX };
    let mut out = Vec::new();
    for cells in [16, 32].into_iter().take(sizes) {
        out.extend(hertz(cells)?);
    }
    out.push(("2D random_200".into(), random_problem_in(2, 200, 5)));
    out.push((
        "2D sparse random_2000".into(),
        random_sparse_problem(2, 2000, 4, 6),
    ));
    for (name, cells) in [("3D halfspace_12", 12), ("3D halfspace_24", 24)]
        .into_iter()
        .take(sizes)
    {
        let hs = HalfSpace {
            cells_across: cells,
            indenter: Indenter::Sphere { radius: 2.5 },
            ..HalfSpace::default()
        };
        out.push((name.into(), hs.generate()?.problem));
    }
    out.push(("3D random_100".into(), random_problem_in(3, 100, 1)));
    if !quick {
        out.push(("3D random_500".into(), random_problem_in(3, 500, 3)));
    }
    let shaken = SpherePile {
        jitter: 0.05,
        threshold: 0.2,
        initial_speed: 0.05,
        ..SpherePile::default()
    };
    for (nx, layers, seed) in [(5, 5, 2), (7, 5, 3)].into_iter().take(sizes) {
        let p = SpherePile {
            nx,
            ny: nx,
            layers,
            ..shaken
        }
        .generate(seed)?
        .problem;
        let n = p.contact_count();
        out.push((format!("3D pile_{nx}x{nx}x{layers} ({n}) dense"), p.clone()));
        out.push((
            format!("3D pile_{nx}x{nx}x{layers} ({n}) sparse"),
            sparse_twin(&p)?,
        ));
    }
    // issue 37: the multibody families of `docs/benchmarks.md` "Auto on multibody problems"
    // (in a box: floor and four walls), where Newton converges and where it creeps
    for (name, pile, seed) in multibody_families()
        .into_iter()
        .filter(|f| !quick || f.0 == "tower_50" || f.0 == "box_4x4x8 loose")
    {
        let p = pile.generate(seed)?.problem;
        let n = p.contact_count();
        out.push((format!("3D {name} ({n}) dense"), p.clone()));
        out.push((format!("3D {name} ({n}) sparse"), sparse_twin(&p)?));
    }
    for (n, seed) in [(1000, 7), (4000, 8)].into_iter().take(sizes) {
        out.push((
            format!("3D sparse random_{n}"),
            random_sparse_problem(3, n, 4, seed),
        ));
    }
    Ok(out)
}

/// Sphere piles and towers in a box (issue 37), each with its seed: a tower of 50, columns
/// 3 × 3 × 16 and 4 × 4 × 8 shaken at two levels of disorder.
fn multibody_families() -> Vec<(String, SpherePile, u64)> {
    let base = SpherePile::default();
    let loose = SpherePile {
        jitter: 0.4,
        threshold: 0.5,
        initial_speed: 0.1,
        ..base
    };
    let shaken = SpherePile {
        jitter: 0.3,
        threshold: 0.5,
        initial_speed: 0.5,
        mu: 0.3,
        ..base
    };
    let tower = SpherePile {
        nx: 1,
        ny: 1,
        layers: 50,
        jitter: 0.1,
        threshold: 0.2,
        mu: 0.3,
        ..base
    };
    let (c16, c8) = ((3, 16), (4, 8));
    let grid = |p: SpherePile, (n, layers): (usize, usize)| SpherePile {
        nx: n,
        ny: n,
        layers,
        ..p
    };
    vec![
        ("tower_50".into(), tower, 1),
        ("box_3x3x16 shaken".into(), grid(shaken, c16), 2),
        ("box_3x3x16 loose".into(), grid(loose, c16), 1),
        ("box_4x4x8 loose".into(), grid(loose, c8), 1),
        ("box_4x4x8 loose s2".into(), grid(loose, c8), 2),
    ]
}

fn main() -> Result<(), Box<dyn Error>> {
    faer::set_global_parallelism(faer::Par::Seq);
    let rounds: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(5);
    let quick = std::env::var_os("BIPO_QUICK").is_some_and(|v| v != "0");
    let problems = problems(quick)?;
    let na = ALGORITHMS.len();
    let mut times = vec![vec![Vec::<f64>::new(); na]; problems.len()];
    let mut info = vec![vec![(0usize, false, Algorithm::Auto); na]; problems.len()];
    for _ in 0..rounds {
        for (k, (_, p)) in problems.iter().enumerate() {
            let laws = p.coulomb_laws();
            for (a, &algorithm) in ALGORITHMS.iter().enumerate() {
                if times[k][a].iter().any(|&t| t > 2000.0) {
                    continue;
                }
                let st = UzawaSettings::default()
                    .with_algorithm(algorithm)
                    .with_tol(1e-8)
                    .with_max_iterations(5_000)
                    .with_fallback(false)
                    .with_accept_non_converged(true);
                let t0 = Instant::now();
                let sol = UzawaSolver::new(st).solve(p, &laws)?;
                times[k][a].push(1e3 * t0.elapsed().as_secs_f64());
                info[k][a] = (
                    sol.report.iterations,
                    sol.report.converged,
                    sol.report.algorithm,
                );
            }
        }
    }
    println!("| problem | n_c | W | Newton | AGS | GS | Auto (picks) |");
    println!("|---|---|---|---|---|---|---|");
    for (k, (name, p)) in problems.iter().enumerate() {
        let mut cells = Vec::new();
        for a in 0..na {
            let t = &mut times[k][a];
            t.sort_by(f64::total_cmp);
            let (it, ok, picked) = info[k][a];
            let mark = if ok { "" } else { " not conv." };
            let pick = if ALGORITHMS[a] == Algorithm::Auto {
                format!(" {picked:?}")
            } else {
                String::new()
            };
            cells.push(format!(
                "{:.3} ({it}{mark}, ×{}){pick}",
                t[t.len() / 2],
                t.len()
            ));
        }
        println!(
            "| {name} | {} | {} | {} |",
            p.contact_count(),
            if p.is_sparse() { "sparse" } else { "dense" },
            cells.join(" | ")
        );
    }
    Ok(())
}
