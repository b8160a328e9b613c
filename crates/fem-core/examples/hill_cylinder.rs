//! Hill's thick cylinder (plane strain, von Mises, perfect plasticity) on the mesh of
//! `tests/integration/issue_40_hill_cylinder.rs`, timed, written as JSON for the GetFEM peer
//! `tools/peers/getfem_hill.py` (issue 40): the mesh (nodes, P2 triangles in GetFEM's node
//! order, the symmetry node sets, the inner edge), the material, the load levels, and our
//! answers at each level (inner-radius displacement, elastic–plastic radius, Newton
//! iterations, wall time).
//!
//! ```text
//! cargo run -p fem-core --example hill_cylinder -- hill.json
//! /usr/bin/python3 tools/peers/getfem_hill.py hill.json
//! ```

use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::plastic::newton::{self, NewtonSettings};
use fem_core::plastic::{ConstitutivePoint, DruckerPrager, PlasticModel};
use fem_core::{
    Component, ElementKind, FemError, Idealization, LinearElasticModel, Material, Mesh, Structure,
    Supports,
};
use std::sync::Arc;
use std::time::Instant;

const A: f64 = 1.0;
const B: f64 = 2.0;
const K: f64 = 1.0;
const YOUNG: f64 = 1000.0;
const POISSON: f64 = 0.49;
const RADIAL: usize = 100;
const AROUND: usize = 3;
const LEVELS: [f64; 3] = [0.9, 1.1, 1.3];
const STEPS_PER_LEVEL: usize = 4;

/// The quarter ring `a ≤ r ≤ b`: a rectangle in `(r, t)` mapped by `(r cos t, r sin t)`.
fn quarter_ring() -> Result<Mesh, FemError> {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([A, B], [0.0, std::f64::consts::FRAC_PI_2], RADIAL, AROUND)
    };
    let flat = rectangle(&spec)?;
    let nodes = flat
        .nodes()
        .iter()
        .map(|&[r, t]| [r * t.cos(), r * t.sin()])
        .collect();
    let mut mesh = Mesh::new(
        nodes,
        ElementKind::Tri6,
        flat.connectivity().to_vec(),
        flat.regions().to_vec(),
    )?;
    for name in ["left", "bottom", "top"] {
        mesh.add_node_set(name, flat.node_set(name)?.to_vec())?;
    }
    mesh.add_edge_set("left", flat.edge_set("left")?.to_vec())?;
    Ok(mesh)
}

/// The elastic–plastic radius: between the outermost yielded point and the innermost
/// elastic one beyond it.
fn plastic_radius(body: &PlasticModel<2>) -> Result<f64, FemError> {
    let positions = body.point_positions()?;
    let states = body.committed_states();
    let radius = |k: usize| positions[k][0].hypot(positions[k][1]);
    let yielded = (0..states.len()).filter(|&k| states[k].equivalent_plastic_strain > 0.0);
    let outer = yielded.map(radius).fold(A, f64::max);
    let elastic = (0..states.len()).filter(|&k| states[k].equivalent_plastic_strain == 0.0);
    let inner = elastic.map(radius).filter(|&r| r > outer).fold(B, f64::min);
    Ok(0.5 * (outer + inner))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "hill.json".into());
    let mesh = quarter_ring()?;
    let set = |name: &str| mesh.node_set(name).map(<[usize]>::to_vec);
    let (bottom, top, left) = (set("bottom")?, set("top")?, set("left")?);
    // GetFEM's P2 triangle lists v0, m01, v1, m02, m12, v2; ours v0, v1, v2, m01, m12, m20
    let triangles: Vec<Vec<usize>> = (0..mesh.element_count())
        .map(|e| {
            let c = mesh.element(e);
            vec![c[0], c[3], c[1], c[5], c[4], c[2]]
        })
        .collect();
    let nodes = mesh.nodes().to_vec();
    // the inner node on the x axis
    let probe = bottom
        .iter()
        .copied()
        .find(|&n| (nodes[n][0] - A).abs() < 1e-12)
        .ok_or("no node at (a, 0)")?;

    let start = Instant::now();
    let mut supports = Supports::new();
    supports.fix(&bottom, Component::Y).fix(&top, Component::X);
    let material = Material::new(YOUNG, POISSON, 0.0)?;
    let mut elastic =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, material)], supports)?;
    elastic.add_edge_traction("left", |[x, y]| {
        let r = x.hypot(y);
        [K * x / r, K * y / r]
    })?;
    let law: Arc<dyn ConstitutivePoint> = Arc::new(DruckerPrager::von_mises(YOUNG, POISSON, K)?);
    let mut body = PlasticModel::new(elastic, &[(0, law)])?;
    let built = start.elapsed().as_secs_f64();
    let mut u = vec![0.0; body.dof_count()];
    let mut lambda = 0.0;
    let mut levels = Vec::new();
    for p in LEVELS {
        let t = Instant::now();
        let settings = NewtonSettings::with_steps(STEPS_PER_LEVEL);
        let report = newton::solve(&mut body, &mut u, lambda, p, &settings)?;
        let seconds = t.elapsed().as_secs_f64();
        lambda = p;
        let iterations: Vec<usize> = report
            .converged_steps()
            .map(|s| s.residuals.len() - 1)
            .collect();
        let u_inner = body.nodal_displacements(&u)[probe][0];
        levels.push(serde_json::json!({
            "pressure": p,
            "u_inner": u_inner,
            "plastic_radius": plastic_radius(&body)?,
            "iterations": iterations,
            "seconds": seconds,
        }));
    }
    let total = start.elapsed().as_secs_f64();
    let out = serde_json::json!({
        "a": A, "b": B, "k": K, "young": YOUNG, "poisson": POISSON,
        "steps_per_level": STEPS_PER_LEVEL,
        "nodes": nodes,
        "triangles": triangles,
        "bottom": bottom, "top": top, "inner": left, "probe": probe,
        "ours": { "levels": levels, "build_seconds": built, "total_seconds": total },
    });
    std::fs::write(&path, serde_json::to_string(&out)?)?;
    println!("{}", serde_json::to_string_pretty(&out["ours"])?);
    Ok(())
}
