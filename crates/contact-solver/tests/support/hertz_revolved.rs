//! The axisymmetric Hertz scene of [`super::hertz_scene`] revolved into a 3D quarter
//! ([`fem_core::solid::revolve`]): the same meridian grid, `sectors` sectors of `90°/sectors`,
//! the same body, load and rigid flat, so that the 3D model and the axisymmetric one can be
//! compared on equal terms (`tests/integration/hertz_revolved.rs`,
//! `examples/hertz_revolved.rs`).
//!
//! Supports: the top `u_z = −δ`; the axis `u_x = u_y = 0`; the symmetry planes `θ = 0`
//! (`u_y = 0`) and `θ = 90°` (`u_x = 0`). Contact: the bottom nodes against the rigid plane
//! `z = 0`, frictionless, with the consistent areas of the bottom faces. Measured as in the
//! axisymmetric scene: `P = 4 Σ f_i` (quarter) and `a² = 5/2 Σ f_i r_i² / Σ f_i`
//! (`r = √(x² + y²)`).
#![allow(dead_code)]

use contact_laws::Signorini;
use contact_solver::SimulationSettings;
use contact_solver::coupling::solid::{
    ContactZone3, RigidPlane, SolidContactSimulation, SolidStepResult,
};
use fem_core::solid::{SolidModel, revolve};
use fem_core::{Component, Material, Mesh, Supports};
use std::f64::consts::FRAC_PI_2;

/// The axisymmetric scene's parameters that the quarter needs.
#[derive(Clone, Copy, Debug)]
pub struct Params {
    /// Prescribed downward displacement of the top.
    pub delta: f64,
    /// Young's modulus.
    pub young: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// Alert distance.
    pub alert: f64,
}

/// The 3D quarter of the axisymmetric scene's meridian `mesh` in `sectors` sectors.
pub fn quarter(
    meridian: &Mesh,
    scene: Params,
    sectors: usize,
) -> SolidContactSimulation<SolidModel, Signorini> {
    let rev = revolve(meridian, FRAC_PI_2, sectors).expect("a meridian mesh");
    let mesh = rev.mesh;
    let mut s = Supports::new();
    s.prescribe(mesh.node_set("top").unwrap(), Component::Z, -scene.delta)
        .unwrap()
        .fix(mesh.node_set("axis").unwrap(), Component::X)
        .fix(mesh.node_set("axis").unwrap(), Component::Y)
        .fix(mesh.node_set("theta0").unwrap(), Component::Y)
        .fix(mesh.node_set("theta1").unwrap(), Component::X);
    let (nodes, areas) = mesh.nodal_areas("bottom").unwrap();
    let material = Material::new(scene.young, scene.poisson, 0.0).unwrap();
    let model = SolidModel::new(mesh, &[(0, material)], s).expect("a supported quarter");
    let ground = RigidPlane::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let zone = ContactZone3::rigid("arc", nodes, ground, Signorini, scene.alert).with_areas(areas);
    SolidContactSimulation::new(model, vec![zone], SimulationSettings::for_dimension::<3>())
        .expect("valid scene")
}

/// `(P, a)` of a step of the quarter: the total force and the second-moment contact radius.
pub fn measure(res: &SolidStepResult) -> (f64, f64) {
    let (mut s0, mut s2) = (0.0, 0.0);
    for c in &res.contacts {
        let p = c.position; // on the plane z = 0: the target point's x, y
        s0 += c.r.n;
        s2 += c.r.n * (p[0] * p[0] + p[1] * p[1]);
    }
    (4.0 * s0, (2.5 * s2 / s0).sqrt())
}
