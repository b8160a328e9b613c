//! The three paths of a 3D contact step against the number of contacts: dense `F*`,
//! matrix-free and the primal active set, on two scenes whose whole contact face is active.
//!
//! Run: `cargo run --release --example solid_contact_scaling -- 24 --dense` (`n`: cells per
//! side, default 24, 6 with `BIPO_QUICK=1`; `--dense`, `--matrix-free`, `--active-set` or
//! `--auto`; `--coulomb` for μ = 0.3; `--slab m` for the pad below, `m` layers of cells;
//! `--mf-window d`: the depth of the Anderson mixing of the matrix-free iteration, default the
//! settings' 20, 0 for the Nesterov momentum of earlier versions).
//!
//! The ball (default). Quarter model: block `[0, 1]² × [−0.5, 0]`, `n × n × n/2` cells of six
//! P1 tetrahedra, symmetry on x = 0 and y = 0, bottom pushed up by 0.03; ball R = 1 centred at
//! (0, 0, 1); E = 1000, ν = 0.3; the alert distance (1) makes all `(n + 1)²` top nodes active.
//!
//! The pad on its foundation (`--slab m`; issue 38's ≥ 5 000-contact scene is
//! `133 --slab 5 --coulomb --auto`: 303 644 DOF, 17 956 contacts, `docs/benchmarks.md`).
//! Quarter model:
//! the slab `[0, 1]² × [0, h]`, `h = m/n` (cubic cells), `n × n × m` cells of six P1
//! tetrahedra, rollers on x = 0 and y = 0, its top lowered by `δ = h/100` (z only), its bottom
//! resting on the rigid plane z = 0 (all `(n + 1)²` bottom nodes active); E = 1000, ν = 0.3.
//! Without friction the stress is uniaxial and P1 holds it exactly: total force `E δ/h` = 10.
//! With friction the foundation holds the bottom back, and the force is larger. Checked on
//! every run (the program fails otherwise): the contact reactions balance the top's and the
//! rollers' support reactions (`K u − f`) in z and x to 1e-9 of the force (the equilibrium of
//! the last exact solve: round-off), and without friction the total is 10 to 1e-6 (the reduced
//! problem's tolerance).

use bipotential::contact_laws::ContactLaw;
use bipotential::contact_laws::{Coulomb, Signorini};
use bipotential::contact_solver::coupling::solid::{
    ContactZone3, RigidPlane, RigidSphere, Side3, SolidContactSimulation, SolidStepResult,
};
use bipotential::contact_solver::{FlexibilityMode, SimulationSettings};
use bipotential::fem_core::solid::generate::{box_mesh, lines};
use bipotential::fem_core::solid::{SolidKind, SolidModel};
use bipotential::fem_core::{Component, Material, Structure, Supports};
use std::error::Error;
use std::time::Instant;

/// The relative tolerance of the pad's equilibrium check (round-off of one exact solve).
const BALANCE_TOL: f64 = 1e-9;
/// The relative tolerance of the frictionless pad's force against `E δ/h` (the reduced
/// problem is solved to 1e-8 relative).
const FORCE_TOL: f64 = 1e-6;

/// One step of the simulation of `model` and `zone`: the step, the active set's
/// factorisations and, when `balance` (the pad), the largest relative imbalance of the
/// support and contact reactions in z and x.
fn step<L: ContactLaw + Clone>(
    model: SolidModel,
    zone: ContactZone3<L>,
    settings: SimulationSettings,
    balance: bool,
) -> Result<(SolidStepResult, usize, f64, usize), Box<dyn Error>> {
    let mut sim = SolidContactSimulation::new(model, vec![zone], settings)?;
    let res = sim.step(1.0, 1.0)?;
    let mut imbalance = 0.0;
    if balance {
        let supports = sim.structure().reactions(&sim.nodal_displacements(), 1.0)?;
        for (c, a) in [(Component::Z, 2), (Component::X, 0)] {
            let support: f64 = supports.iter().filter(|r| r.0.1 == c).map(|r| r.1).sum();
            let contact: f64 = res.contacts.iter().map(|k| k.force()[a]).sum();
            let force: f64 = res.contacts.iter().map(|k| k.r.n).sum();
            imbalance = f64::max(imbalance, (support + contact).abs() / force);
        }
    }
    let c = sim.counters();
    Ok((
        res,
        c.active_set_factorizations,
        imbalance,
        c.operator_applications,
    ))
}

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| args.iter().position(|a| a == flag).map(|i| i + 1);
    let slab: Option<usize> = match value("--slab") {
        Some(i) => Some(args.get(i).ok_or("--slab needs a layer count")?.parse()?),
        None => None,
    };
    let n: usize = args
        .iter()
        .enumerate()
        .find(|(i, a)| {
            !a.starts_with("--") && Some(*i) != value("--slab") && Some(*i) != value("--mf-window")
        })
        .map_or(
            Ok(
                if std::env::var_os("BIPO_QUICK").is_some_and(|v| v != "0") {
                    6
                } else {
                    24
                },
            ),
            |(_, a)| a.parse(),
        )?;
    let flexibility = if args.iter().any(|a| a == "--matrix-free") {
        FlexibilityMode::MatrixFree
    } else if args.iter().any(|a| a == "--active-set") {
        FlexibilityMode::ActiveSet
    } else if args.iter().any(|a| a == "--auto") {
        SimulationSettings::for_dimension::<3>().flexibility
    } else {
        FlexibilityMode::Dense
    };
    let window: usize = match value("--mf-window") {
        Some(i) => args.get(i).ok_or("--mf-window needs a depth")?.parse()?,
        None => {
            SimulationSettings::for_dimension::<3>()
                .tuning
                .matrix_free_window
        }
    };
    let settings = SimulationSettings::for_dimension::<3>()
        .with_flexibility(flexibility)
        .with_matrix_free_window(window);
    let coulomb = args.iter().any(|a| a == "--coulomb");
    let start = Instant::now();
    let (z, alert) = match slab {
        Some(m) if m > 0 => (lines(0.0, m as f64 / n as f64, m), 0.1),
        Some(_) => return Err("--slab needs at least one layer".into()),
        None => (lines(-0.5, 0.0, n.div_ceil(2)), 1.0),
    };
    let mesh = box_mesh(
        &lines(0.0, 1.0, n),
        &lines(0.0, 1.0, n),
        &z,
        SolidKind::Tet4,
    )?;
    let h = z[z.len() - 1] - z[0];
    let mut s = Supports::new();
    s.fix(mesh.node_set("x0")?, Component::X)
        .fix(mesh.node_set("y0")?, Component::Y);
    let face = if slab.is_some() {
        s.prescribe(mesh.node_set("z1")?, Component::Z, -h / 100.0)?;
        "z0"
    } else {
        s.prescribe(mesh.node_set("z0")?, Component::Z, 0.03)?;
        "z1"
    };
    let (nodes, areas) = mesh.nodal_areas(face)?;
    let model = SolidModel::new(mesh, &[(0, Material::new(1000.0, 0.3, 0.0)?)], s)?;
    let dofs = model.dof_count();
    let t_build = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let balance = slab.is_some();
    let (res, factorizations, imbalance, products) = match (slab, coulomb) {
        (Some(_), true) => {
            let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0])?;
            let zone = ContactZone3::rigid("base", nodes, floor, Coulomb::new(0.3)?, alert);
            step(model, zone.with_areas(areas), settings, balance)?
        }
        (Some(_), false) => {
            let floor = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0])?;
            let zone = ContactZone3::rigid("base", nodes, floor, Signorini, alert);
            step(model, zone.with_areas(areas), settings, balance)?
        }
        (None, true) => {
            let ball = RigidSphere::new([0.0, 0.0, 1.0], 1.0, Side3::Outside)?;
            let zone = ContactZone3::rigid("top", nodes, ball, Coulomb::new(0.3)?, alert);
            step(model, zone.with_areas(areas), settings, balance)?
        }
        (None, false) => {
            let ball = RigidSphere::new([0.0, 0.0, 1.0], 1.0, Side3::Outside)?;
            let zone = ContactZone3::rigid("top", nodes, ball, Signorini, alert);
            step(model, zone.with_areas(areas), settings, balance)?
        }
    };
    let t_step = start.elapsed().as_secs_f64();
    let force: f64 = res.contacts.iter().map(|c| c.r.n).sum();
    let closed = res.contacts.iter().filter(|c| c.r.n > 0.0).count();
    println!(
        "| {n} | {dofs} | {} | {closed} | {:?} | {force:.6} | {t_build:.2} | {t_step:.2} | {} | {} |",
        res.report.active_contacts,
        settings.flexibility,
        res.report.contact_iterations,
        factorizations
    );
    println!("path: {}", res.report.path);
    if res.report.matrix_free {
        println!("matrix-free: {products} products F* r (window {window})");
    }
    if balance {
        println!("equilibrium: support + contact reactions = {imbalance:.2e} of the force");
        if imbalance.is_nan() || imbalance > BALANCE_TOL {
            return Err(format!("the reactions do not balance: {imbalance:.3e}").into());
        }
        // uniaxial stress E δ/h on the unit quarter, exact for P1 without friction
        let exact = 1000.0 / 100.0;
        let error = (force - exact).abs();
        if !coulomb && (error.is_nan() || error > FORCE_TOL * exact) {
            return Err(format!("frictionless force {force} is not E δ/h = {exact}").into());
        }
    }
    Ok(())
}
