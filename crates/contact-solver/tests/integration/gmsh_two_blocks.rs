//! A block pressed on a block, then pulled, through an RCCM interface (issue 36): the mesh made
//! by Gmsh against the same geometry from the library's generator.
//!
//! Source of the fixtures: Gmsh 4.15.2 (the Python SDK), `tests/data/gmsh/two_blocks.py`:
//! two separate transfinite blocks, 4 × 2 cells each, every cell cut along the diagonal the
//! `rectangle` generator uses ("AlternateLeft"), P1 and P2, so the Gmsh mesh has the
//! generator's nodes and triangles, numbered otherwise (Gmsh: points, then curves, then
//! surfaces) with the interface curves oriented as Gmsh's loops go.
//!
//! ```text
//!   y = 1   ┌───────────────┐  upper_top: u_x = 0, u_y = d(t) = −0.01, −0.005, 0.001, 0.002
//!           │ upper (reg 2) │  E = 100, ν = 0.3
//!   y = 0   ├───────────────┤  contactor upper_bottom → segments lower_top, RCCM
//!           │ lower (reg 1) │  C_n = C_t = 100, w = 0.01, α = 1, μ = 0.2, β₀ = 1
//!   y = −1  └───────────────┘  lower_bottom fixed
//! ```
//! What is asserted, and why:
//! - the contactor's tributary areas (lumped along the set's order) sum to the interface's
//!   length 2, to 1e-12 (round-off). On the set sorted by tag (the old order) the P2 set
//!   zig-zags and they sum to about 8.9: this fails on the old code;
//! - every step agrees with the generator's mesh node by node (matched by position): `r_n`,
//!   `r_t`, the gap and β, to 1e-8 of the largest reaction. Same triangles, the same nodes
//!   (Gmsh's transfinite points lie within 1.3e-12 of the generator's, so nodes are matched
//!   to 1e-10 and the areas agree to 1e-10): only the numbering and that round-off differ,
//!   and the solver's tolerance (1e-10 relative by default) separates the answers.

#![cfg(feature = "fe")]

use crate::support::hertz_scene::with_region;
use contact_laws::{BetaScheme, Rccm, RccmParams};
use contact_solver::{ContactSimulation, ContactZone, SimulationSettings, StepResult};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::gmsh::read_msh;
use fem_core::{
    Component, ElementKind, Idealization, LinearElasticModel, Material, Mesh, Supports,
};
use std::path::PathBuf;

const PATH: [f64; 4] = [-0.01, -0.005, 0.001, 0.002];

fn gmsh_mesh(order: usize) -> Mesh {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join(format!("tests/data/gmsh/two_blocks_p{order}.msh"));
    read_msh(&file).unwrap()
}

fn generated_mesh(order: usize) -> Mesh {
    let kind = if order == 1 {
        ElementKind::Tri3
    } else {
        ElementKind::Tri6
    };
    let block = |y| {
        rectangle(&RectangleSpec {
            kind,
            ..RectangleSpec::new([0.0, 2.0], y, 4, 2)
        })
        .unwrap()
    };
    let lower = with_region(&block([-1.0, 0.0]), 1);
    let upper = with_region(&block([0.0, 1.0]), 2);
    Mesh::join(&[("lower_", &lower), ("upper_", &upper)]).unwrap()
}

/// The simulation on `mesh` (sets named as the Gmsh file's: the generator's `lower_top` is
/// the lower block's `top`, …).
fn simulation(mesh: Mesh) -> (ContactSimulation<LinearElasticModel, Rccm>, Vec<usize>) {
    let set = |name: &str| mesh.node_set(name).unwrap().to_vec();
    let (contactor, surface) = (set("upper_bottom"), set("lower_top"));
    let (top, base) = (set("upper_top"), set("lower_bottom"));
    let mut supports = Supports::new();
    supports.fix(&base, Component::X).fix(&base, Component::Y);
    supports.fix(&top, Component::X);
    supports.prescribe(&top, Component::Y, 0.0).unwrap();
    let material = Material::new(100.0, 0.3, 0.0).unwrap();
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(1, material), (2, material)],
        supports,
    )
    .unwrap();
    let law = Rccm::new(RccmParams {
        c_n: 100.0,
        c_t: 100.0,
        w: 0.01,
        alpha: 1.0,
        mu: 0.2,
        m: 1,
        beta_0: 1.0,
        scheme: BetaScheme::ImplicitEuler,
    })
    .unwrap();
    let zone = ContactZone::node_to_segment("interface", contactor, surface, law, 0.05);
    let sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap();
    (sim, top)
}

fn run(mesh: Mesh) -> (Vec<StepResult>, f64) {
    let (mut sim, top) = simulation(mesh);
    let areas: f64 = sim.candidates().iter().map(|c| c.area).sum();
    let mut out = Vec::new();
    for (k, &d) in PATH.iter().enumerate() {
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, d)
            .unwrap();
        out.push(sim.step((k + 1) as f64, 1.0).unwrap());
    }
    (out, areas)
}

#[test]
fn issue_36_gmsh_rccm_areas_sum_to_the_interface_length() {
    for order in [1, 2] {
        let (sim, _) = simulation(gmsh_mesh(order));
        let areas: f64 = sim.candidates().iter().map(|c| c.area).sum();
        assert_eq!(sim.candidates().len(), 4 * order + 1);
        // the lumped areas of the nodes along the line y = 0: round-off on 2
        assert!((areas - 2.0).abs() < 1e-12, "P{order}: Σ areas = {areas}");
    }
}

#[test]
fn issue_36_gmsh_two_blocks_agree_with_the_generator() {
    for order in [1, 2] {
        let (gmsh, gmsh_areas) = run(gmsh_mesh(order));
        let (generated, generated_areas) = run(generated_mesh(order));
        assert!((gmsh_areas - 2.0).abs() < 1e-12 && (generated_areas - 2.0).abs() < 1e-12);
        for (step, (a, b)) in gmsh.iter().zip(&generated).enumerate() {
            let scale = b
                .contacts
                .iter()
                .map(|c| c.r.n.abs().max(c.r.t[0].abs()))
                .fold(0.0, f64::max);
            assert!(scale > 0.0);
            let total = |r: &StepResult| r.contacts.iter().map(|c| c.r.n).sum::<f64>();
            eprintln!(
                "P{order} step {step}: Σ r_n Gmsh {:.12}, generator {:.12}",
                total(a),
                total(b)
            );
            assert_eq!(a.contacts.len(), b.contacts.len());
            for c in &a.contacts {
                let d = b
                    .contacts
                    .iter()
                    .find(|d| {
                        // Gmsh's transfinite nodes are within 1.3e-12 of the generator's
                        (d.position[0] - c.position[0]).abs() < 1e-10
                            && (d.position[1] - c.position[1]).abs() < 1e-10
                    })
                    .unwrap_or_else(|| panic!("no generator node at {:?}", c.position));
                // same nodes, triangles and areas: round-off and the solver's tolerance
                let tol = 1e-8 * scale;
                assert!(
                    (c.r.n - d.r.n).abs() < tol
                        && (c.r.t[0] - d.r.t[0]).abs() < tol
                        && (c.gap - d.gap).abs() < 1e-8 * 0.01
                        && (c.beta - d.beta).abs() < 1e-8
                        && (c.area - d.area).abs() < 1e-10,
                    "P{order} step {step} at {:?}: Gmsh {c:?} vs generator {d:?}",
                    c.position
                );
            }
        }
    }
}

/// A closed curve's areas (the closing segment included) and those of a curve of two pieces
/// (from its sides) on the square of `fem-core/tests/data/gmsh/square_curves_p2.msh`: the
/// perimeter 6 and the two sides' lengths 2, to 1e-12 (round-off on a few tens of segments).
/// Without the closing segment the outline's areas fall short by its length; lumped along the
/// two pieces' sorted nodes they bridge the gap between the pieces.
#[test]
fn issue_36_closed_and_pieces_areas() {
    use contact_solver::coupling::zone::{lumped_areas, segment_areas};
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../fem-core/tests/data/gmsh/square_curves_p2.msh");
    let mesh = read_msh(&file).unwrap();
    let outline = mesh.node_set("outline").unwrap().to_vec();
    let ends = mesh.node_set("ends").unwrap().to_vec();
    let mut segments = Vec::new();
    for &side in mesh.edge_set("ends").unwrap() {
        let s: Vec<usize> = mesh.side_nodes(side).collect();
        segments.extend([[s[0], s[2]], [s[2], s[1]]]);
    }
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports
        .fix(&bottom, Component::X)
        .fix(&bottom, Component::Y);
    let material = Material::new(100.0, 0.3, 0.0).unwrap();
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(1, material), (2, material)],
        supports,
    )
    .unwrap();
    let closed: f64 = lumped_areas(&model, &outline, true).iter().sum();
    assert!((closed - 6.0).abs() < 1e-12, "closed: {closed}");
    let open: f64 = lumped_areas(&model, &outline, false).iter().sum();
    assert!(open < 6.0 - 1e-3, "without the closing segment: {open}");
    let pieces = segment_areas(&model, &ends, &segments).unwrap();
    let sum: f64 = pieces.iter().sum();
    assert!((sum - 2.0).abs() < 1e-12, "pieces: {sum}");
    // sorted by index, a polyline through the two pieces would bridge them: more than 2
    let bridged: f64 = lumped_areas(&model, &ends, false).iter().sum();
    assert!(bridged > 2.5, "bridged: {bridged}");
}
