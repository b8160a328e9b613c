//! The impacting bar of `tests/integration/issue_39_dynamics.rs` (P2 strip `L = 1 × 0.1`,
//! plane stress, `E = ρ = 1`, `ν = 0`, consistent mass, `v0 = 0.1` onto a rigid wall,
//! Moreau–Jean `θ = 1/2`, `e = 0`), run and written out for the Siconos peer
//! (`tools/peers/siconos_bar.py`), which runs the same mesh, mass, step and `θ` in
//! `siconos.kernel` and compares the contact-force histories point by point.
//!
//! ```text
//! cargo build --release -p contact-solver --example moreau_jean_bar
//! /usr/bin/python3 tools/peers/siconos_bar.py        # runs the example, then Siconos
//! target/release/examples/moreau_jean_bar [OUT.json] [NX] [H] [STEPS] [REPEAT]
//! ```
//! `OUT.json` (default `out/moreau_jean_bar.json`): the free dofs' `M` and `K` as triplets
//! (`[row, col, value]`, the full symmetric matrices, exact zeros left out), the contact dofs
//! (the x dof of each node on `x = 0`, the wall's normal), `v0` on the free dofs, `h`, `θ`,
//! `e`, the step count, and our results: the contact force `Σ r_n / h` after each step, the
//! mean velocity `1ᵀ M v / m` along x after each step, and the in-process time of the run
//! (from the `DynamicModel` to the last step: factorisation, `F*`, every step), the median
//! of `REPEAT` runs (default 5).

use contact_laws::Signorini;
use contact_solver::coupling::simulation::MoreauJean;
use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
use fem_core::Supports;
use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{ElementKind, Idealization, LinearElasticModel, Material, Mesh, Structure};
use serde_json::json;
use std::time::Instant;

const V0: f64 = 0.1;

fn bar_mesh(nx: usize) -> Mesh {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 1.0], [0.0, 0.1], nx, 1)
    };
    rectangle(&spec).expect("a valid strip")
}

fn body(mesh: Mesh) -> DynamicModel<2> {
    let m = Material::new(1.0, 0.0, 0.0)
        .and_then(|m| m.with_density(1.0))
        .expect("valid material");
    let model = LinearElasticModel::floating(
        mesh,
        Idealization::PlaneStress { thickness: 1.0 },
        &[(0, m)],
        Supports::new(),
    )
    .expect("a floating strip");
    DynamicModel::new(model, MassKind::Consistent, Rayleigh::default()).expect("with a mass")
}

/// What one run gives: force and mean velocity after each step.
struct Run {
    force: Vec<f64>,
    velocity: Vec<f64>,
}

fn run(mesh: &Mesh, h: f64, steps: usize) -> Result<Run, Box<dyn std::error::Error>> {
    let left = mesh.node_set("left")?.to_vec();
    let body = body(mesh.clone());
    let scheme = MoreauJean::new(0.5)?.with_velocity_field(&body, |_| [-V0, 0.0])?;
    let wall = RigidLine::new([0.0, 1.0], [0.0, -1.0])?; // normal +x
    let zone = ContactZone::rigid("wall", left, wall, Signorini, 0.01);
    let mut sim =
        ContactSimulation::with_scheme(body, vec![zone], SimulationSettings::default(), scheme)?;
    let n = sim.structure().dof_count();
    let ones_x: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 1.0 } else { 0.0 }).collect();
    let mut m1 = vec![0.0; n];
    sim.structure().mass_mul_into(&ones_x, &mut m1);
    let total: f64 = m1.iter().zip(&ones_x).map(|(a, b)| a * b).sum();
    let (mut force, mut velocity) = (Vec::with_capacity(steps), Vec::with_capacity(steps));
    for _ in 0..steps {
        let res = sim.advance(h)?;
        force.push(res.contacts.iter().map(|c| c.r.n).sum::<f64>() / h);
        let v = sim.scheme().velocity();
        velocity.push(m1.iter().zip(v).map(|(a, b)| a * b).sum::<f64>() / total);
    }
    Ok(Run { force, velocity })
}

/// The full symmetric matrix of `mul` on `n` dofs as `[row, col, value]` triplets.
fn triplets(n: usize, mul: impl Fn(&[f64], &mut [f64])) -> Vec<(usize, usize, f64)> {
    let (mut e, mut y) = (vec![0.0; n], vec![0.0; n]);
    let mut out = Vec::new();
    for j in 0..n {
        e[j] = 1.0;
        mul(&e, &mut y);
        e[j] = 0.0;
        out.extend(
            y.iter()
                .enumerate()
                .filter(|(_, v)| **v != 0.0)
                .map(|(i, v)| (i, j, *v)),
        );
    }
    out
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or(default.to_string());
    let path = arg(1, "out/moreau_jean_bar.json");
    let nx: usize = arg(2, "100").parse()?;
    let h: f64 = arg(3, "0.005").parse()?;
    let steps: usize = arg(4, "520").parse()?;
    let repeat: usize = arg(5, "5").parse()?;
    if let Some(dir) = std::path::Path::new(&path).parent()
        && !dir.as_os_str().is_empty()
    {
        std::fs::create_dir_all(dir)?;
    }
    faer::set_global_parallelism(faer::Par::Seq);
    let mesh = bar_mesh(nx);

    let mut times = Vec::new();
    let mut result = None;
    for _ in 0..repeat.max(1) {
        let start = Instant::now();
        let r = run(&mesh, h, steps)?;
        times.push(start.elapsed().as_secs_f64() * 1e3);
        result = Some(r);
    }
    times.sort_by(f64::total_cmp);
    let ms = times[times.len() / 2];
    let ours = result.expect("one run at least");

    let body = body(mesh.clone());
    let n = body.dof_count();
    let mass = triplets(n, |x, y| body.mass_mul_into(x, y));
    let stiffness = triplets(n, |x, y| body.stiffness_mul_into(x, y));
    let contact_dofs: Vec<usize> = mesh
        .node_set("left")?
        .iter()
        .map(|&node| body.node_dofs(node)[0].expect("free"))
        .collect();
    let v0: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { -V0 } else { 0.0 }).collect();
    let out = json!({
        "n": n, "nx": nx, "h": h, "theta": 0.5, "e": 0.0, "steps": steps, "v0": v0,
        "mass": mass, "stiffness": stiffness, "contact_dofs": contact_dofs,
        "ours": { "force": ours.force, "velocity": ours.velocity, "ms": ms, "times_ms": times },
    });
    std::fs::write(&path, serde_json::to_string(&out)?)?;
    let peak = ours.force.iter().fold(0.0_f64, |m, f| m.max(*f));
    println!(
        "bar nx = {nx} ({n} dofs), h = {h}, {steps} steps: peak force {peak:.6e}, rebound \
         {:.6}, {ms:.2} ms (median of {}) -> {path}",
        ours.velocity.last().copied().unwrap_or(f64::NAN),
        times.len()
    );
    Ok(())
}
