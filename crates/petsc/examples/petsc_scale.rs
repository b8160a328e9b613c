//! The measurements of issue 41 (docs/benchmarks.md, "Issue 41: scaling and the partition"),
//! one command per figure:
//!
//! ```text
//! mpirun -n N petsc_scale patch CELLS M [graph] [mumps] [batch|loop]
//!     the block (CELLS × CELLS × CELLS/2 Tet10 cells, [0, 1]² × [0, 0.5]) pressed by its top
//!     (−1e-3) on a rigid plane through an M × M patch of bottom nodes at its centre (M² Coulomb
//!     candidates, μ = 0.3), one step with a dense F*, the bulk solved by PETSc (CG + GAMG by
//!     default); each rank prints its setup, step, solve and peak-memory figures
//! petsc_scale direct CELLS M
//!     the same model and contacts on fem-core's direct SolidModel (serial, no mpirun)
//! petsc_scale partitions CELLS RANKS...
//!     interface nodes of the slab and the graph partitions of that block (no MPI needed)
//! petsc_scale interface CELLS
//!     the contact interface alone against its size: a P1 plate (CELLS × CELLS × 2 Tet4 cells,
//!     [0, 1]² × [0, 0.1]) whose whole bottom ((CELLS + 1)² candidates) is pressed on the
//!     plane, direct path: the step less its structure solves is the interface's own time
//!     (detection, F* from its columns, the local solve), and the peak memory it adds
//! ```
//! `setup` is the partition, the distributed assembly and the preconditioner's set-up (the
//! direct path: assembly and the Cholesky factorisation); `solve_s` is the time spent in the
//! structure's solves (`3 M² + 1` right-hand sides for a dense F* in 3D); `peak_rss_mib` is the
//! rank's `VmHWM`.

use bipotential_petsc::{LinearSolver, Partition, Partitioner, Petsc, PetscStructure};
use contact_laws::Coulomb;
use contact_solver::coupling::solid::{ContactZone3, RigidPlane, SolidContactSimulation};
use contact_solver::{FlexibilityMode, SimulationSettings};
use fem_core::faer::MatMut;
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidMesh, SolidModel};
use fem_core::{Component, DofMap, FemError, Material, Structure, Supports};
use std::cell::Cell;
use std::error::Error;
use std::time::Instant;

type Res<T> = Result<T, Box<dyn Error>>;

/// A structure whose solves are counted and timed, wall and CPU (every other call passed
/// through).
struct Timed<S> {
    inner: S,
    seconds: Cell<f64>,
    cpu: Cell<f64>,
    columns: Cell<usize>,
}

impl<S> Timed<S> {
    fn new(inner: S) -> Self {
        Self {
            inner,
            seconds: Cell::new(0.0),
            cpu: Cell::new(0.0),
            columns: Cell::new(0),
        }
    }

    fn time<T>(&self, columns: usize, f: impl FnOnce() -> T) -> T {
        let (start, cpu) = (Instant::now(), cpu_s());
        let out = f();
        self.seconds
            .set(self.seconds.get() + start.elapsed().as_secs_f64());
        self.cpu.set(self.cpu.get() + cpu_s() - cpu);
        self.columns.set(self.columns.get() + columns);
        out
    }
}

impl<S: Structure<3>> Structure<3> for Timed<S> {
    fn dof_count(&self) -> usize {
        self.inner.dof_count()
    }
    fn node_count(&self) -> usize {
        self.inner.node_count()
    }
    fn node_position(&self, node: usize) -> [f64; 3] {
        self.inner.node_position(node)
    }
    fn node_dofs(&self, node: usize) -> [Option<usize>; 3] {
        self.inner.node_dofs(node)
    }
    fn prescribed_displacement(&self, node: usize) -> [f64; 3] {
        self.inner.prescribed_displacement(node)
    }
    fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), FemError> {
        self.time(1, || self.inner.solve_in_place(rhs))
    }
    fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), FemError> {
        let columns = rhs.ncols();
        self.time(columns, || self.inner.solve_many_in_place(rhs))
    }
    fn free_response_into(&self, load_factor: f64, u: &mut [f64]) -> Result<(), FemError> {
        self.time(1, || self.inner.free_response_into(load_factor, u))
    }
    fn stiffness_version(&self) -> u64 {
        self.inner.stiffness_version()
    }
}

fn material() -> Material {
    Material::new(1000.0, 0.25, 0.0).expect("valid")
}

/// The block of CELLS × CELLS × CELLS/2 Tet10 cells, its top pressed, and the zone of the
/// `side × side` bottom nodes nearest the centre (`side` odd).
fn patch_model(cells: usize, side: usize) -> Res<(SolidMesh, Supports, ContactZone3<Coulomb>)> {
    if side.is_multiple_of(2) || side > 2 * cells + 1 {
        return Err(format!("M = {side}: odd, at most 2 CELLS + 1").into());
    }
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
    let (nodes, areas) = mesh.nodal_areas("z0")?;
    // Tet10 bottom nodes lie on a grid of spacing 1/(2 CELLS): keep |x − ½|, |y − ½| ≤ h
    let h = (side / 2) as f64 / (2 * cells) as f64 + 0.25 / (2 * cells) as f64;
    let (nodes, areas): (Vec<usize>, Vec<f64>) = nodes
        .into_iter()
        .zip(areas)
        .filter(|&(n, _)| {
            let p = mesh.nodes()[n];
            (p[0] - 0.5).abs() <= h && (p[1] - 0.5).abs() <= h
        })
        .unzip();
    assert_eq!(nodes.len(), side * side, "the patch");
    let plane = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0])?;
    let zone =
        ContactZone3::rigid("patch", nodes, plane, Coulomb::new(0.3)?, 0.1).with_areas(areas);
    Ok((mesh, supports, zone))
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

/// CPU time (user + system) of this process so far, in seconds (`/proc/self/stat`, clock
/// ticks of 1/100 s): on the shared machine the figure the load changes least.
fn cpu_s() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // the fields after the command's closing parenthesis: utime is the 12th, stime the 13th
            let rest = s.rsplit_once(')')?.1;
            let f: Vec<&str> = rest.split_whitespace().collect();
            Some(f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?)
        })
        .map_or(f64::NAN, |ticks| ticks / 100.0)
}

/// One dense-F* step on `structure`; prints the figures with `head` before them and `tail`'s
/// (of the structure after the step) after.
fn step<S: Structure<3>>(
    head: &str,
    structure: S,
    zone: ContactZone3<Coulomb>,
    setup: (f64, f64),
    tail: impl Fn(&S) -> String,
) -> Res<()> {
    let settings =
        SimulationSettings::for_dimension::<3>().with_flexibility(FlexibilityMode::Dense);
    let (start, cpu) = (Instant::now(), cpu_s());
    let mut sim = SolidContactSimulation::new(Timed::new(structure), vec![zone], settings)?;
    let res = sim.step(1.0, 1.0)?;
    let (step, step_cpu) = (start.elapsed().as_secs_f64(), cpu_s() - cpu);
    let timed = sim.structure();
    let (solve, solve_cpu, columns) = (timed.seconds.get(), timed.cpu.get(), timed.columns.get());
    let force: f64 = res.contacts.iter().map(|c| c.r.n).sum();
    println!(
        "{head} candidates={} closed={} setup_s={:.2} setup_cpu_s={:.2} step_s={step:.2} \
         step_cpu_s={step_cpu:.2} solve_s={solve:.2} solve_cpu_s={solve_cpu:.2} columns={columns} \
         per_solve_cpu_s={:.4} interface_s={:.2} interface_cpu_s={:.2} force={force:.9e} \
         peak_rss_mib={:.0}{}",
        res.report.active_contacts,
        res.report.closed_contacts,
        setup.0,
        setup.1,
        solve_cpu / columns.max(1) as f64,
        step - solve,
        step_cpu - solve_cpu,
        peak_rss_mib(),
        tail(&timed.inner)
    );
    Ok(())
}

fn patch(petsc: &Petsc, args: &[String]) -> Res<()> {
    let cells: usize = args.first().ok_or("patch CELLS M")?.parse()?;
    let side: usize = args.get(1).ok_or("patch CELLS M")?.parse()?;
    let partitioner = if args.iter().any(|a| a == "graph") {
        Partitioner::Graph
    } else {
        Partitioner::Slabs
    };
    let solver = if args.iter().any(|a| a == "mumps") {
        LinearSolver::Mumps
    } else {
        LinearSolver::default()
    };
    let (mesh, supports, zone) = patch_model(cells, side)?;
    petsc.barrier()?;
    let (start, cpu) = (Instant::now(), cpu_s());
    let mut body = PetscStructure::with_partitioner(
        petsc,
        mesh,
        &[(0, material())],
        supports,
        solver,
        partitioner,
    )?;
    // issue 41: `batch` or `loop` sets how F*'s columns are solved (default: the solver's)
    if args.iter().any(|a| a == "batch") {
        body.set_batched_solves(true)?;
    } else if args.iter().any(|a| a == "loop") {
        body.set_batched_solves(false)?;
    }
    let setup = (start.elapsed().as_secs_f64(), cpu_s() - cpu);
    let interface = body.partition().interface_nodes(body.mesh());
    let head = format!(
        "patch cells={cells} dofs={} ranks={} rank={} partition={partitioner:?} interface_nodes={interface}",
        body.dof_count(),
        petsc.size(),
        petsc.rank()
    );
    step(&head, body, zone, setup, |body| {
        let (solves, its) = body.solve_counts();
        format!(
            " krylov_iterations={its} per_solve={:.1}",
            its as f64 / solves.max(1) as f64
        )
    })?;
    petsc.barrier()?;
    Ok(())
}

fn direct(args: &[String]) -> Res<()> {
    let cells: usize = args.first().ok_or("direct CELLS M")?.parse()?;
    let side: usize = args.get(1).ok_or("direct CELLS M")?.parse()?;
    let (mesh, supports, zone) = patch_model(cells, side)?;
    let (start, cpu) = (Instant::now(), cpu_s());
    let model = SolidModel::new(mesh, &[(0, material())], supports)?;
    let setup = (start.elapsed().as_secs_f64(), cpu_s() - cpu);
    let head = format!("direct cells={cells} dofs={}", model.dof_count());
    step(&head, model, zone, setup, |_| String::new())?;
    Ok(())
}

fn partitions(args: &[String]) -> Res<()> {
    let cells: usize = args.first().ok_or("partitions CELLS RANKS...")?.parse()?;
    let (mesh, supports, _) = patch_model(cells, 1)?;
    let dofs = DofMap::<3>::numbered(mesh.node_count(), &supports)?;
    for ranks in &args[1..] {
        let ranks: usize = ranks.parse()?;
        let (s, g) = (
            Partition::slabs(&mesh, &dofs, ranks),
            Partition::graph(&mesh, &dofs, ranks),
        );
        let rows = |p: &Partition| {
            let w: Vec<usize> = p.offsets.windows(2).map(|w| w[1] - w[0]).collect();
            (w.iter().min().copied(), w.iter().max().copied())
        };
        println!(
            "partitions cells={cells} dofs={} nodes={} ranks={ranks} slabs_interface={} graph_interface={} slabs_rows={:?} graph_rows={:?}",
            dofs.free_count(),
            mesh.node_count(),
            s.interface_nodes(&mesh),
            g.interface_nodes(&mesh),
            rows(&s),
            rows(&g)
        );
    }
    Ok(())
}

fn interface(args: &[String]) -> Res<()> {
    let cells: usize = args.first().ok_or("interface CELLS")?.parse()?;
    let mesh = box_mesh(
        &lines(0.0, 1.0, cells),
        &lines(0.0, 1.0, cells),
        &lines(0.0, 0.1, 2),
        SolidKind::Tet4,
    )?;
    let top = mesh.node_set("z1")?.to_vec();
    let mut supports = Supports::new();
    supports
        .prescribe(&top, Component::Z, -1e-3)?
        .prescribe(&top, Component::X, 0.0)?
        .prescribe(&top, Component::Y, 0.0)?;
    let (nodes, areas) = mesh.nodal_areas("z0")?;
    let plane = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0])?;
    let zone = ContactZone3::rigid("base", nodes, plane, Coulomb::new(0.3)?, 0.1).with_areas(areas);
    let (start, cpu) = (Instant::now(), cpu_s());
    let model = SolidModel::new(mesh, &[(0, material())], supports)?;
    let setup = (start.elapsed().as_secs_f64(), cpu_s() - cpu);
    let before = peak_rss_mib();
    let head = format!(
        "interface cells={cells} dofs={} rss_before_step_mib={before:.0}",
        model.dof_count()
    );
    step(&head, model, zone, setup, |_| String::new())?;
    Ok(())
}

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
    petsc.or_abort(|| -> Res<()> {
        let rest = args.get(1..).unwrap_or_default();
        match args.first().map(String::as_str) {
            Some("patch") => patch(&petsc, rest),
            Some("direct") => direct(rest),
            Some("partitions") => partitions(rest),
            Some("interface") => interface(rest),
            _ => Err(
                "usage: petsc_scale patch CELLS M [graph] [mumps] [batch|loop] | direct CELLS M | \
                 partitions CELLS RANKS... | interface CELLS"
                    .into(),
            ),
        }
    });
}
