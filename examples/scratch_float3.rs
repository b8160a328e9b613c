use bipotential::contact_laws::Signorini;
use bipotential::contact_solver::coupling::solid::RigidPlane;
use bipotential::contact_solver::{ContactSimulation, ContactZone, SimulationSettings};
use bipotential::fem_core::solid::generate::{box_mesh, lines};
use bipotential::fem_core::solid::{SolidKind, SolidModel};
use bipotential::fem_core::{Component, Material, Structure, Supports};

fn main() {
    let p = 2.0;
    let mesh = box_mesh(
        &lines(0.0, 2.0, 3),
        &lines(0.0, 1.5, 2),
        &lines(0.0, 1.0, 2),
        SolidKind::Tet10,
    )
    .unwrap();
    let mut s = Supports::new();
    s.fix(mesh.node_set("x0").unwrap(), Component::X)
        .fix(mesh.node_set("y0").unwrap(), Component::Y);
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let mut model =
        SolidModel::floating(mesh, &[(0, Material::new(1000.0, 0.3, 0.0).unwrap())], s).unwrap();
    model
        .add_face_traction("z1", |_, _| [0.0, 0.0, -p])
        .unwrap();
    println!(
        "modes: {:?}",
        model.floating().map(|f| f.rigid_body_modes().len())
    );
    let plane = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let zone = ContactZone::<_, 3>::rigid("base", nodes, plane, Signorini, 0.1).with_areas(areas);
    let mut sim =
        ContactSimulation::new(model, vec![zone], SimulationSettings::for_dimension::<3>())
            .unwrap();
    let res = sim.step(1.0, 1.0).unwrap();
    let total: f64 = res.contacts.iter().map(|c| c.reaction()[0]).sum();
    println!(
        "total reaction {total} vs {} rel {:e}",
        p * 3.0,
        (total - p * 3.0) / (p * 3.0)
    );
    let max_gap = res.contacts.iter().map(|c| c.gap.abs()).fold(0.0, f64::max);
    println!("max |gap| {max_gap:e}");
}
