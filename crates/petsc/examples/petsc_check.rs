//! The distributed checks, run under `mpirun` (tests/mpi.sh; tests/mpi.rs spawns them):
//!
//! ```text
//! mpirun -n N petsc_check block [mumps]   3D block, Coulomb contact (μ = 0.3) on a rigid plane:
//!                                          pressed, then its top sheared until every contact slides
//! mpirun -n N petsc_check hertz [mumps]   rigid sphere on a block (the quarter Hertz model)
//!                                          (`block` and `hertz`: `batch` or `loop` sets
//!                                          how F*'s columns are solved, issue 41)
//! mpirun -n N petsc_check pile [mumps] [seed] [plane]
//!                                          the seed's pile pull-out, axisymmetric, RCCM
//!                                          interface (examples/support/pile.rs)
//! mpirun -n N petsc_check batches         70 right-hand sides, MUMPS batched and looped, CG looped:
//!                                          the direct path's solve to 1e-8 (issue 41)
//! mpirun -n N petsc_check errors          the 2D constructor and loads refuse bad data
//! mpirun -n N petsc_check fail            rank N−1 fails: every rank must end, with its message
//! mpirun -n N petsc_check scale CELLS     the block at CELLS³ Tet10 cells: times and peak RSS
//! mpirun -n N petsc_check partitions      the block on the slab and on the graph partition:
//!                                          the same answers to 1e-10 relative
//! ```
//! `block`, `hertz` and `pile` step the same scene with the [`PetscStructure`] and with
//! fem-core's direct `SolidModel` (`LinearElasticModel` for the pile) on rank 0 and print the largest difference of the reactions and the
//! contact nodes' displacements, relative to the largest value of each; above 1e-8 the program
//! fails (on every rank, through `Petsc::or_abort`).

use bipotential_petsc::{LinearSolver, Partitioner, Petsc, PetscError, PetscStructure};
use contact_laws::{ContactLaw, Coulomb, Signorini};
use contact_solver::SimulationSettings;
use contact_solver::coupling::solid::{
    ContactZone3, RigidPlane, RigidSphere, Side3, SolidContactSimulation,
};
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidMesh, SolidModel};
use fem_core::{Component, Material, Structure, Supports};
use std::error::Error;
use std::time::Instant;

#[path = "support/pile.rs"]
mod pile;

type Res<T> = Result<T, Box<dyn Error>>;

/// What one contact step gives: per contact `[r_n, r_t1, r_t2]` and the node's displacement.
#[derive(Debug, Default)]
struct Answer {
    reactions: Vec<[f64; 3]>,
    displacements: Vec<[f64; 3]>,
}

/// A scene: the mesh, its supports, the contact zone's builder, and what to change before
/// the second step (nodes, component, value).
struct Scene<L: ContactLaw> {
    mesh: SolidMesh,
    supports: Supports,
    zone: ContactZone3<L>,
    second: Vec<(Vec<usize>, Component, f64)>,
}

fn material() -> Material {
    Material::new(1000.0, 0.25, 0.0).expect("valid")
}

/// The sliding block of contact-solver's `solid_contact.rs`, refined: pressed by −1e-3 at
/// its top, then the top moved by 0.05 along (cos 0.6, sin 0.6).
fn block(cells: usize) -> Res<Scene<Coulomb>> {
    let mesh = box_mesh(
        &lines(0.0, 1.0, cells),
        &lines(0.0, 1.0, cells),
        &lines(0.0, 0.5, cells.div_ceil(2)),
        SolidKind::Tet10,
    )?;
    let top = mesh.node_set("z1")?.to_vec();
    let mut supports = Supports::new();
    supports
        .prescribe(&top, Component::Z, -1e-3)?
        .prescribe(&top, Component::X, 0.0)?
        .prescribe(&top, Component::Y, 0.0)?;
    let theta: f64 = 0.6;
    let second = vec![
        (top.clone(), Component::X, 0.05 * theta.cos()),
        (top, Component::Y, 0.05 * theta.sin()),
    ];
    let (nodes, areas) = mesh.nodal_areas("z0")?;
    let plane = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0])?;
    let zone = ContactZone3::rigid("base", nodes, plane, Coulomb::new(0.3)?, 0.1).with_areas(areas);
    Ok(Scene {
        mesh,
        supports,
        zone,
        second,
    })
}

/// The coarse quarter Hertz model of contact-solver's `solid_contact.rs`: a rigid ball
/// (R = 10) on the block [0, 4]² × [−4, 0], its base pushed up by 0.04.
fn hertz() -> Res<Scene<Signorini>> {
    let graded = |l: f64, n_fine: usize, fine: f64, n_coarse: usize| -> Vec<f64> {
        let mut v = lines(0.0, fine, n_fine);
        let r = (l / fine).powf(1.0 / n_coarse as f64);
        v.extend((1..=n_coarse).map(|k| fine * r.powi(k as i32)));
        v
    };
    let xy = graded(4.0, 6, 0.9, 4);
    let mut z: Vec<f64> = graded(4.0, 4, 0.6, 4).iter().map(|v| -v).collect();
    z.reverse();
    let mesh = box_mesh(&xy, &xy, &z, SolidKind::Tet10)?;
    let mut supports = Supports::new();
    supports
        .fix(mesh.node_set("x0")?, Component::X)
        .fix(mesh.node_set("y0")?, Component::Y)
        .prescribe(mesh.node_set("z0")?, Component::Z, 0.04)?;
    let bottom = mesh.node_set("z0")?.to_vec();
    let (nodes, areas) = mesh.nodal_areas("z1")?;
    let ball = RigidSphere::new([0.0, 0.0, 10.0], 10.0, Side3::Outside)?;
    let zone = ContactZone3::rigid("top", nodes, ball, Signorini, 0.5).with_areas(areas);
    Ok(Scene {
        mesh,
        supports,
        zone,
        second: vec![(bottom, Component::Z, 0.06)],
    })
}

/// Steps the scene twice on `structure`; the answers of both steps.
fn run<S: Structure<3>, L: ContactLaw + Clone>(
    structure: S,
    zone: ContactZone3<L>,
    second: &[(Vec<usize>, Component, f64)],
    set: impl Fn(&mut S, &[usize], Component, f64) -> Res<()>,
) -> Res<Vec<Answer>> {
    let mut sim = SolidContactSimulation::new(
        structure,
        vec![zone],
        SimulationSettings::for_dimension::<3>(),
    )?;
    let mut answers = Vec::new();
    for step in 1..=2 {
        if step == 2 {
            for (nodes, c, v) in second {
                set(sim.structure_mut(), nodes, *c, *v)?;
            }
        }
        let res = sim.step(step as f64, 1.0)?;
        let mut a = Answer::default();
        for c in &res.contacts {
            a.reactions.push([c.r.n, c.r.t[0], c.r.t[1]]);
            a.displacements.push(sim.nodal_displacement(c.node));
        }
        answers.push(a);
    }
    Ok(answers)
}

/// The largest difference relative to the largest value, over every component.
fn relative(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    let scale = b.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    let diff = a
        .iter()
        .flatten()
        .zip(b.iter().flatten())
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale.max(f64::MIN_POSITIVE)
}

/// Issue 41: 70 right-hand sides (two blocks of `BATCH_COLUMNS`, the second partial) on the
/// block, solved by MUMPS batched and in the loop, and by CG in the loop (which refuses to
/// batch); each equals the direct path's solve to 1e-8 relative (CG stops at a residual of
/// 1e-12 relative), and MUMPS's two each other to 1e-12 (the same factors).
fn batches(petsc: &Petsc) -> Res<()> {
    use fem_core::faer::Mat;
    let scene = block(4)?;
    let direct = SolidModel::new(
        scene.mesh.clone(),
        &[(0, material())],
        scene.supports.clone(),
    )?;
    let n = direct.dof_count();
    let columns = 70;
    assert!(columns > bipotential_petsc::BATCH_COLUMNS);
    let rhs = Mat::from_fn(n, columns, |i, c| ((1 + i * (c + 3)) as f64 * 0.37).sin());
    let mut expected = rhs.clone();
    direct.solve_many_in_place(expected.as_mut())?;
    let largest = |f: &dyn Fn(usize, usize) -> f64| {
        (0..columns)
            .flat_map(|c| (0..n).map(move |i| (i, c)))
            .fold(0.0_f64, |m, (i, c)| m.max(f(i, c).abs()))
    };
    let scale = largest(&|i, c| expected[(i, c)]);
    let diff = |a: &Mat<f64>, b: &Mat<f64>| largest(&|i, c| a[(i, c)] - b[(i, c)]) / scale;
    for solver in [LinearSolver::default(), LinearSolver::Mumps] {
        let mut body = PetscStructure::new(
            petsc,
            scene.mesh.clone(),
            &[(0, material())],
            scene.supports.clone(),
            solver,
        )?;
        let mut answers = Vec::new();
        for on in [true, false] {
            if solver != LinearSolver::Mumps {
                // CG refuses to batch (it would report the last column's convergence alone)
                match body.set_batched_solves(on) {
                    Err(PetscError::Unsupported { .. }) if on => {
                        answers.push(None);
                        continue;
                    }
                    other => other?,
                }
            } else {
                body.set_batched_solves(on)?;
            }
            let mut x = rhs.clone();
            body.solve_many_in_place(x.as_mut())?;
            let error = diff(&x, &expected);
            if petsc.rank() == 0 {
                println!(
                    "batches {solver:?} batched={on} ({} ranks, {columns} columns): {error:.2e} relative to the direct path",
                    petsc.size()
                );
            }
            if error.is_nan() || error > 1e-8 {
                return Err(format!("batched={on}, {solver:?}: {error:.2e} > 1e-8").into());
            }
            answers.push(Some(x));
        }
        let solves = match (&answers[0], &answers[1]) {
            (Some(batched), Some(looped)) => {
                let between = diff(batched, looped);
                if between.is_nan() || between > 1e-12 {
                    return Err(
                        format!("{solver:?}: batch and loop differ by {between:.2e}").into(),
                    );
                }
                2 * columns
            }
            (None, Some(_)) => columns,
            _ => return Err(format!("{solver:?}: batched {}", answers[0].is_some()).into()),
        };
        if body.solve_counts().0 != solves {
            return Err(format!("{solver:?}: {:?} solves", body.solve_counts()).into());
        }
    }
    if petsc.rank() == 0 {
        println!("batches: OK");
    }
    Ok(())
}

fn compare<L: ContactLaw + Clone>(
    petsc: &Petsc,
    name: &str,
    scene: Scene<L>,
    solver: LinearSolver,
) -> Res<()> {
    let zone = scene.zone;
    let serial = if petsc.rank() == 0 {
        let model = SolidModel::new(
            scene.mesh.clone(),
            &[(0, material())],
            scene.supports.clone(),
        )?;
        Some(run(model, zone.clone(), &scene.second, |m, n, c, v| {
            Ok(m.set_prescribed(n, c, v)?)
        })?)
    } else {
        None
    };
    let start = Instant::now();
    let mut body = PetscStructure::new(
        petsc,
        scene.mesh,
        &[(0, material())],
        scene.supports,
        solver,
    )?;
    if let Some(&on) = BATCHED.get() {
        body.set_batched_solves(on)?;
    }
    let dofs = body.dof_count();
    let distributed = run(body, zone, &scene.second, |s, n, c, v| {
        Ok(s.set_prescribed(n, c, v)?)
    })?;
    let seconds = start.elapsed().as_secs_f64();
    if let Some(serial) = serial {
        for (step, (d, s)) in distributed.iter().zip(&serial).enumerate() {
            let closed = s.reactions.iter().filter(|r| r[0] > 0.0).count();
            if closed == 0 {
                return Err(format!(
                    "{name} step {}: no contact closed, nothing compared",
                    step + 1
                )
                .into());
            }
            let (er, eu) = (
                relative(&d.reactions, &s.reactions),
                relative(&d.displacements, &s.displacements),
            );
            println!(
                "{name} step {} ({} ranks, {dofs} dofs, {closed} closed): reactions {er:.2e}, displacements {eu:.2e} relative to the direct path",
                step + 1,
                petsc.size()
            );
            // the test's promise: the serial answer to 1e-8 relative
            if !(er <= 1e-8 && eu <= 1e-8) || d.reactions.len() != s.reactions.len() {
                return Err(format!(
                    "{name} step {}: differs from the direct path ({er:e}, {eu:e})",
                    step + 1
                )
                .into());
            }
        }
        println!("{name}: OK ({seconds:.2} s distributed)");
    }
    Ok(())
}

/// The block stepped on the slab and on the graph partition: the answers agree to 1e-10
/// relative (the partition changes GAMG's aggregates and the sums' order, not the problem;
/// CG stops at 1e-12 relative).
fn partitions(petsc: &Petsc, solver: LinearSolver) -> Res<()> {
    let mut answers = Vec::new();
    let mut ranks = Vec::new();
    for partitioner in [Partitioner::Slabs, Partitioner::Graph] {
        let scene = block(4)?;
        let body = PetscStructure::with_partitioner(
            petsc,
            scene.mesh,
            &[(0, material())],
            scene.supports,
            solver,
            partitioner,
        )?;
        let interface = body.partition().interface_nodes(body.mesh());
        ranks.push(body.partition().element_rank.clone());
        if petsc.rank() == 0 {
            println!(
                "partitions {partitioner:?} ({} ranks): {interface} interface nodes",
                petsc.size()
            );
        }
        answers.push(run(body, scene.zone, &scene.second, |s, n, c, v| {
            Ok(s.set_prescribed(n, c, v)?)
        })?);
    }
    if petsc.size() > 2 && ranks[0] == ranks[1] {
        return Err("the two partitions coincide: nothing compared".into());
    }
    for (step, (g, s)) in answers[1].iter().zip(&answers[0]).enumerate() {
        let (er, eu) = (
            relative(&g.reactions, &s.reactions),
            relative(&g.displacements, &s.displacements),
        );
        if petsc.rank() == 0 {
            println!(
                "partitions step {}: graph against slabs: reactions {er:.2e}, displacements {eu:.2e}",
                step + 1
            );
        }
        // the promise: the partition does not change the answer (beyond the solver's 1e-12)
        if !(er <= 1e-10 && eu <= 1e-10) || g.reactions.len() != s.reactions.len() {
            return Err(format!("partitions step {}: {er:e}, {eu:e}", step + 1).into());
        }
    }
    if petsc.rank() == 0 {
        println!("partitions: OK");
    }
    Ok(())
}

/// Peak resident memory of this process (`VmHWM`), in MiB.
fn peak_rss_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kib| kib / 1024.0)
}

fn scale(petsc: &Petsc, cells: usize, solver: LinearSolver) -> Res<()> {
    let scene = block(cells)?;
    let zone = scene.zone;
    let contacts = scene.mesh.node_set("z0")?.len();
    petsc.barrier()?;
    let t0 = Instant::now();
    let mut body = PetscStructure::new(
        petsc,
        scene.mesh,
        &[(0, material())],
        scene.supports,
        solver,
    )?;
    if let Some(&on) = BATCHED.get() {
        body.set_batched_solves(on)?;
    }
    let setup = t0.elapsed().as_secs_f64();
    let dofs = body.dof_count();
    let t1 = Instant::now();
    let mut sim =
        SolidContactSimulation::new(body, vec![zone], SimulationSettings::for_dimension::<3>())?;
    sim.step(1.0, 1.0)?;
    let step = t1.elapsed().as_secs_f64();
    let (solves, its) = sim.structure().solve_counts();
    petsc.barrier()?;
    println!(
        "scale cells={cells} dofs={dofs} contacts={contacts} ranks={} rank={} setup_s={setup:.2} step_s={step:.2} solves={solves} iterations={its} peak_rss_mib={:.0}",
        petsc.size(),
        petsc.rank(),
        peak_rss_mib()
    );
    Ok(())
}

/// `batch` or `loop` on the command line: how `F*`'s columns are solved (default: the
/// solver's, `PetscStructure::set_batched_solves`).
static BATCHED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();

fn main() {
    let petsc = match Petsc::init() {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    if let Some(on) = args.iter().find_map(|a| match a.as_str() {
        "batch" => Some(true),
        "loop" => Some(false),
        _ => None,
    }) {
        BATCHED.get_or_init(|| on);
    }
    let solver = if args.iter().any(|a| a == "mumps") {
        LinearSolver::Mumps
    } else {
        LinearSolver::default()
    };
    petsc.or_abort(|| -> Res<()> {
        match args.first().map(String::as_str) {
            Some("block") => compare(&petsc, "block", block(4)?, solver),
            Some("hertz") => compare(&petsc, "hertz", hertz()?, solver),
            Some("batches") => batches(&petsc),
            Some("pile") => {
                let has = |word: &str| args.iter().any(|a| a == word);
                pile::compare(&petsc, has("seed"), has("plane"), solver)
            }
            Some("errors") => pile::errors(&petsc),
            Some("partitions") => partitions(&petsc, solver),
            Some("fail") => {
                if petsc.rank() + 1 == petsc.size() {
                    return Err(format!("a deliberate failure on rank {}", petsc.rank()).into());
                }
                // the others wait in a collective call that the failed rank never makes
                petsc.barrier()?;
                Err("the barrier returned without the failed rank".into())
            }
            Some("scale") => {
                let cells = args
                    .get(1)
                    .and_then(|c| c.parse().ok())
                    .ok_or("scale CELLS")?;
                scale(&petsc, cells, solver)
            }
            _ => Err(
                "usage: petsc_check block|hertz|batches|pile|errors|partitions|fail|scale CELLS [mumps] [batch|loop] [seed] [plane]"
                    .into(),
            ),
        }
    });
}
