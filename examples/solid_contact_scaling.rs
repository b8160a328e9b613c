//! The three paths of a 3D contact step against the number of contacts: dense `F*`,
//! matrix-free and the primal active set, on a P1 block whose whole top is a contact zone
//! (every top node active), indented by a rigid ball.
//!
//! Run: `cargo run --release --example solid_contact_scaling -- 24 --dense` (`n`: cells per
//! side of the top, default 24, 6 with `BIPO_QUICK=1`; `--dense`, `--matrix-free` or
//! `--active-set`; `--coulomb` for μ = 0.3).
//!
//! Quarter model: block `[0, 1]² × [−0.5, 0]`, `n × n × n/2` cells of six P1 tetrahedra,
//! symmetry on x = 0 and y = 0, bottom pushed up by 0.03; ball R = 1 centred at (0, 0, 1);
//! E = 1000, ν = 0.3; the alert distance (1) makes all `(n + 1)²` top nodes active.

use bipotential::contact_laws::ContactLaw;
use bipotential::contact_laws::{Coulomb, Signorini};
use bipotential::contact_solver::coupling::solid::{
    ContactZone3, RigidSphere, Side3, SolidContactSimulation, SolidStepResult,
};
use bipotential::contact_solver::{FlexibilityMode, SimulationSettings};
use bipotential::fem_core::solid::generate::{box_mesh, lines};
use bipotential::fem_core::solid::{SolidKind, SolidModel};
use bipotential::fem_core::{Component, Material, Structure, Supports};
use std::error::Error;
use std::time::Instant;

/// One step of the simulation of `model` and `zone`; the step and the active set's
/// factorisations.
fn step<L: ContactLaw + Clone>(
    model: SolidModel,
    zone: ContactZone3<L>,
    settings: SimulationSettings,
) -> Result<(SolidStepResult, usize), Box<dyn Error>> {
    let mut sim = SolidContactSimulation::new(model, vec![zone], settings)?;
    let res = sim.step(1.0, 1.0)?;
    Ok((res, sim.counters().active_set_factorizations))
}
fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = args.iter().find(|a| !a.starts_with("--")).map_or(
        Ok(
            if std::env::var_os("BIPO_QUICK").is_some_and(|v| v != "0") {
                6
            } else {
                24
            },
        ),
        |a| a.parse(),
    )?;
    let flexibility = if args.iter().any(|a| a == "--matrix-free") {
        FlexibilityMode::MatrixFree
    } else if args.iter().any(|a| a == "--active-set") {
        FlexibilityMode::ActiveSet
    } else {
        FlexibilityMode::Dense
    };
    let settings = SimulationSettings::for_dimension::<3>().with_flexibility(flexibility);
    let coulomb = args.iter().any(|a| a == "--coulomb");
    let start = Instant::now();
    let mesh = box_mesh(
        &lines(0.0, 1.0, n),
        &lines(0.0, 1.0, n),
        &lines(-0.5, 0.0, n.div_ceil(2)),
        SolidKind::Tet4,
    )?;
    let mut s = Supports::new();
    s.fix(mesh.node_set("x0")?, Component::X)
        .fix(mesh.node_set("y0")?, Component::Y)
        .prescribe(mesh.node_set("z0")?, Component::Z, 0.03)?;
    let (nodes, areas) = mesh.nodal_areas("z1")?;
    let model = SolidModel::new(mesh, &[(0, Material::new(1000.0, 0.3, 0.0)?)], s)?;
    let dofs = model.dof_count();
    let ball = RigidSphere::new([0.0, 0.0, 1.0], 1.0, Side3::Outside)?;
    let t_build = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let (res, factorizations) = if coulomb {
        let zone =
            ContactZone3::rigid("top", nodes, ball, Coulomb::new(0.3)?, 1.0).with_areas(areas);
        step(model, zone, settings)?
    } else {
        let zone = ContactZone3::rigid("top", nodes, ball, Signorini, 1.0).with_areas(areas);
        step(model, zone, settings)?
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
    Ok(())
}
