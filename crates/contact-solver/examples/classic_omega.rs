//! Sweeps of the classical RCCM solver (`Algorithm::ClassicRccm`) for several over-relaxation
//! factors ω, against the bipotential Gauss–Seidel sweeps: the measurement behind
//! the default `UzawaTuning::omega` (1) (see the docs of `contact_solver::local::classic`).
//!
//! ```text
//! cargo run --release -p contact-solver --example classic_omega
//! ```
//! Problems: seeded random SPD problems (`generate::random_problem`, Coulomb, μ ~ U(0, 1)), and
//! a strongly coupled FE-like one: the flexibility `W = K⁻¹` of two strings (normal and
//! tangential) on an elastic foundation, `K = k_s I + k_b tridiag(−1, 2, −1)` per component
//! (`k_s, k_b` = 0.01, 1 normal and 0.02, 0.7 tangential, coupled by 0.005), pressed by a
//! parabolic punch `q_n = −1 + 6 ξ²` (ξ ∈ (−½, ½), the ends open) and pushed by
//! `q_t = 0.5 + 0.3 ξ`.

use contact_solver::local::generate::random_problem;
use contact_solver::{Algorithm, ReducedProblem, SolverError, UzawaSettings, UzawaSolver};

/// The string problem of the module docs, with `n_c` contacts and friction `mu`.
fn string_problem(nc: usize, mu: f64) -> Result<ReducedProblem, SolverError> {
    let m = 2 * nc;
    let mut k = vec![0.0; m * m];
    for (c, (k_s, k_b)) in [(0.01, 1.0), (0.02, 0.7)].into_iter().enumerate() {
        for i in 0..nc {
            let a = 2 * i + c;
            k[a * m + a] += k_s + 2.0 * k_b;
            if i + 1 < nc {
                let b = a + 2;
                k[a * m + b] -= k_b;
                k[b * m + a] -= k_b;
            }
        }
    }
    for i in 0..nc {
        k[2 * i * m + 2 * i + 1] += 0.005;
        k[(2 * i + 1) * m + 2 * i] += 0.005;
    }
    // W = K⁻¹ by Gauss–Jordan (K is SPD: no pivoting needed), then symmetrised.
    let mut w = vec![0.0; m * m];
    for i in 0..m {
        w[i * m + i] = 1.0;
    }
    for col in 0..m {
        let p = k[col * m + col];
        for j in 0..m {
            k[col * m + j] /= p;
            w[col * m + j] /= p;
        }
        for row in (0..m).filter(|&row| row != col) {
            let f = k[row * m + col];
            for j in 0..m {
                k[row * m + j] -= f * k[col * m + j];
                w[row * m + j] -= f * w[col * m + j];
            }
        }
    }
    for i in 0..m {
        for j in 0..i {
            let v = 0.5 * (w[i * m + j] + w[j * m + i]);
            w[i * m + j] = v;
            w[j * m + i] = v;
        }
    }
    let q = (0..m)
        .map(|a| {
            let xi = ((a / 2) as f64 + 0.5) / nc as f64 - 0.5;
            if a % 2 == 0 {
                -1.0 + 6.0 * xi * xi
            } else {
                0.5 + 0.3 * xi
            }
        })
        .collect();
    ReducedProblem::new(w, q, vec![mu; nc])
}

fn main() -> Result<(), SolverError> {
    let mut problems = Vec::new();
    for (nc, seed) in [(10, 1), (10, 2), (10, 3), (50, 1), (50, 2), (100, 3)] {
        problems.push((
            format!("random n_c={nc} seed={seed}"),
            random_problem(nc, seed),
        ));
    }
    for (nc, mu) in [(10, 0.3), (20, 0.3), (20, 0.1), (40, 0.5)] {
        problems.push((format!("string n_c={nc} mu={mu}"), string_problem(nc, mu)?));
    }
    let omegas = [0.8, 1.0, 1.2, 1.5, 1.8];
    print!("{:26} {:>6}", "problem", "GS");
    for omega in omegas {
        print!(" {:>16}", format!("classic w={omega}"));
    }
    println!("\n{:26} {:>6} {:>16}", "", "sweeps", "sweeps (tang.)");
    for (name, p) in &problems {
        let laws = p.coulomb_laws();
        let base = UzawaSettings::default().with_max_iterations(1_000_000);
        let gs = UzawaSolver::new(base).solve(p, &laws)?;
        print!("{name:26} {:6}", gs.report.iterations);
        for omega in omegas {
            let settings = base
                .with_algorithm(Algorithm::ClassicRccm)
                .with_omega(omega);
            let s = UzawaSolver::new(settings).solve(p, &laws)?;
            print!(
                " {:>16}",
                format!("{} ({})", s.report.iterations, s.report.tangential_sweeps)
            );
        }
        println!();
    }
    Ok(())
}
