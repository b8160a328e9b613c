//! An elastic sphere dropped on a rigid plane (issue 39), shared by
//! `tests/integration/issue_39_hertz_impact.rs` and its finer `#[ignore]`d runs: the meridian
//! half-disk mesh (axisymmetric P2), its 3D quarter ([`fem_core::solid::revolve`], P2
//! tetrahedra), and one driver for both dimensions (Moreau–Jean, `θ = 1/2`, `e = 0`).
//!
//! The half-disk `r ≥ 0`, `r² + z² ≤ R²` is the image of the rectangle `[0, 1] × [−1, 1]` by
//! the elliptical map `r = R u √(1 − v²/2)`, `z = R v √(1 − u²/2)` (the sides `v = ±1` and
//! `u = 1` land on the circle, `u = 0` on the axis); the grid lines are graded towards the
//! south pole `(0, −R)`, where the sphere touches the plane `z = −R`. Only the rectangle's
//! corners `(1, ±1)` are distorted (their cells open to a flat angle), far from the contact.
//!
//! Closed form (Hertz impact; Johnson 1985, *Contact Mechanics*, §11.4, eqs. 11.23–11.24):
//! a sphere of mass `m` (here the whole sphere, `m = 4/3 π R³ ρ`, on an immovable plane)
//! obeys `m δ̈ = −(4/3) E* √R δ^{3/2}` with `E* = E/(1 − ν²)` (rigid plane), so
//! ```text
//! δ_max = (15 m v0² / (16 E* √R))^{2/5},      P_max = (4/3) E* √R δ_max^{3/2}
//! t_c   = 2 ∫₀¹ dx/√(1 − x^{5/2}) · δ_max/v0 = (4/5) B(2/5, 1/2) δ_max/v0 = 2.9432 δ_max/v0
//!       = 2.9432 (15/16)^{2/5} (m²/(R E*² v0))^{1/5} = 2.8682 (m²/(R E*² v0))^{1/5}
//! ```
//! (`∫₀¹ (1 − x^{5/2})^{−1/2} dx = (2/5) B(2/5, 1/2) = (2/5) Γ(2/5) Γ(1/2)/Γ(9/10) = 1.47164`.)
//! It holds while the contact radius `a = √(R δ)` is small against `R` and the impact slow
//! against the sphere's waves (`t_c` many times `R/c`).
#![allow(dead_code)]

use super::hertz_scene::graded_lines;
use contact_laws::Signorini;
use contact_solver::coupling::simulation::MoreauJean;
use contact_solver::coupling::solid::RigidPlane;
use contact_solver::coupling::space::ContactSpace;
use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::model::ModelSpace;
use fem_core::solid::{SolidModel, revolve};
use fem_core::{Component, Dim, ElementKind, Idealization, LinearElasticModel, Material, Mesh};
use fem_core::{Structure, Supports};
use std::f64::consts::{FRAC_PI_2, PI};

/// The sphere: `R = 1`, `E = 1`, `ν = 0.3`, `ρ = 1` (`c = √(E/ρ) = 1`: times in `R/c`).
pub const RADIUS: f64 = 1.0;
/// Young's modulus.
pub const YOUNG: f64 = 1.0;
/// Poisson's ratio.
pub const POISSON: f64 = 0.3;
/// Density.
pub const DENSITY: f64 = 1.0;

/// Hertz's closed form for the sphere above at `v0`: `(t_c, P_max, a_max)`.
pub fn hertz(v0: f64) -> (f64, f64, f64) {
    let e_star = YOUNG / (1.0 - POISSON * POISSON);
    let m = 4.0 / 3.0 * PI * RADIUS.powi(3) * DENSITY;
    let delta = (15.0 * m * v0 * v0 / (16.0 * e_star * RADIUS.sqrt())).powf(0.4);
    let p_max = 4.0 / 3.0 * e_star * RADIUS.sqrt() * delta.powf(1.5);
    let t_c = 2.8682 * (m * m / (RADIUS * e_star * e_star * v0)).powf(0.2);
    // the two forms of t_c agree (the constant's derivation in the module docs)
    debug_assert!((t_c / (2.9432 * delta / v0) - 1.0).abs() < 1e-4);
    (t_c, p_max, (RADIUS * delta).sqrt())
}

/// The meridian half-disk (module docs), P2, with `fine` cells of size `size` (in `u` and
/// `v`) at the pole over `fine · size`, then cells growing by 1.5; node sets of the
/// rectangle: `bottom` (the lower arc from the pole, the contact candidates), `left` (the
/// axis), `right`, `top`.
pub fn meridian(fine: usize, size: f64) -> Mesh {
    let us = graded_lines(fine as f64 * size, fine, 1.5, 1.0);
    let vs: Vec<f64> = graded_lines(fine as f64 * size, fine, 1.5, 2.0)
        .iter()
        .map(|t| t - 1.0)
        .collect();
    let (nu, nv) = (us.len() - 1, vs.len() - 1);
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, nu as f64], [0.0, nv as f64], nu, nv)
    };
    let grid = rectangle(&spec).unwrap();
    let along = |lines: &[f64], s: f64| {
        let i = (s.floor() as usize).min(lines.len() - 2);
        lines[i] + (s - i as f64) * (lines[i + 1] - lines[i])
    };
    let nodes = grid
        .nodes()
        .iter()
        .map(|&[s, t]| {
            let (u, v) = (along(&us, s), along(&vs, t));
            [
                RADIUS * u * (1.0 - 0.5 * v * v).sqrt(),
                RADIUS * v * (1.0 - 0.5 * u * u).sqrt(),
            ]
        })
        .collect();
    let mut mesh = Mesh::new(
        nodes,
        grid.kind(),
        grid.connectivity().to_vec(),
        grid.regions().to_vec(),
    )
    .expect("the map keeps every element positive");
    for name in grid.node_set_names() {
        mesh.add_node_set(name, grid.node_set(name).unwrap().to_vec())
            .unwrap();
    }
    for name in grid.edge_set_names() {
        mesh.add_edge_set(name, grid.edge_set(name).unwrap().to_vec())
            .unwrap();
    }
    mesh
}

fn material() -> Material {
    Material::new(YOUNG, POISSON, 0.0)
        .unwrap()
        .with_density(DENSITY)
        .unwrap()
}

/// The axisymmetric sphere on `mesh` ([`meridian`]) with `u_r = 0` on the axis, and its
/// contact zone on the plane `z = −R` (touching the pole).
pub fn axisymmetric(mesh: Mesh, mass: MassKind) -> (DynamicModel<2>, ContactZone<Signorini, 2>) {
    let (axis, bottom) = (
        mesh.node_set("left").unwrap().to_vec(),
        mesh.node_set("bottom").unwrap().to_vec(),
    );
    let mut supports = Supports::new();
    supports.fix(&axis, Component::X);
    let model = LinearElasticModel::floating(
        mesh,
        Idealization::Axisymmetric,
        &[(0, material())],
        supports,
    )
    .unwrap();
    let body = DynamicModel::new(model, mass, Rayleigh::default()).unwrap();
    let plane = RigidLine::new([-1.0, -RADIUS], [2.0, -RADIUS]).unwrap(); // normal +z
    let zone = ContactZone::rigid("plane", bottom, plane, Signorini, 0.01);
    (body, zone)
}

/// The 3D quarter `x, y ≥ 0` of the sphere, `meridian` revolved through 90° in `sectors`
/// sectors (P2 tetrahedra), with the symmetry supports (`u_y = 0` on `θ = 0`, `u_x = 0` on
/// `θ = 90°`, both on the axis), and its contact zone (the revolved `bottom` faces, their
/// consistent areas) on the plane `z = −R`.
pub fn quarter(
    meridian: &Mesh,
    sectors: usize,
    mass: MassKind,
) -> (DynamicModel<3>, ContactZone<Signorini, 3>) {
    let mesh = revolve(meridian, FRAC_PI_2, sectors).unwrap().mesh;
    let mut s = Supports::new();
    s.fix(mesh.node_set("axis").unwrap(), Component::X)
        .fix(mesh.node_set("axis").unwrap(), Component::Y)
        .fix(mesh.node_set("theta0").unwrap(), Component::Y)
        .fix(mesh.node_set("theta1").unwrap(), Component::X);
    let (nodes, areas) = mesh.nodal_areas("bottom").unwrap();
    let model = SolidModel::floating(mesh, &[(0, material())], s).unwrap();
    let body = DynamicModel::new(model, mass, Rayleigh::default()).unwrap();
    let plane = RigidPlane::new([0.0, 0.0, -RADIUS], [0.0, 0.0, 1.0]).unwrap();
    let zone = ContactZone::<_, 3>::rigid("plane", nodes, plane, Signorini, 0.01).with_areas(areas);
    (body, zone)
}

/// What a drop measured.
#[derive(Clone, Debug)]
pub struct Impact {
    /// The body's whole mass (the model's times `copies`).
    pub mass: f64,
    /// The whole contact force `copies · Σ r_n / h` after each step.
    pub force: Vec<f64>,
    /// The mean velocity along the drop axis (`1ᵀ M v / m`, upwards positive) after each
    /// step.
    pub velocity: Vec<f64>,
    /// Back-substitutions with `M̂` over the run ([`DynamicModel::solve_count`]).
    pub solves: usize,
}

/// Drops `body` at `v0` along `−axis` (the last coordinate) onto `zone`'s plane, `steps`
/// steps of `h` (Moreau–Jean, `θ = 1/2`, `e = 0`); `copies` is what the model is a part of
/// the whole (`2π` per radian, 4 for a quarter).
pub fn drop<const D: usize>(
    body: DynamicModel<D>,
    zone: ContactZone<Signorini, D>,
    v0: f64,
    h: f64,
    steps: usize,
    copies: f64,
) -> Impact
where
    Dim<D>: ModelSpace<D> + ContactSpace<D>,
{
    let scheme = MoreauJean::new(0.5)
        .unwrap()
        .with_velocity_field(&body, |_| {
            core::array::from_fn(|d| if d == D - 1 { -v0 } else { 0.0 })
        })
        .unwrap();
    let n = body.dof_count();
    let mut ones = vec![0.0; n];
    for node in 0..body.node_count() {
        if let Some(i) = body.node_dofs(node)[D - 1] {
            ones[i] = 1.0;
        }
    }
    let mut m1 = vec![0.0; n];
    body.mass_mul_into(&ones, &mut m1);
    let mass: f64 = m1.iter().zip(&ones).map(|(a, b)| a * b).sum();
    let settings = SimulationSettings::for_dimension::<D>();
    let mut sim = ContactSimulation::with_scheme(body, vec![zone], settings, scheme).unwrap();
    let (mut force, mut velocity) = (Vec::new(), Vec::new());
    for _ in 0..steps {
        let res = sim.advance(h).unwrap();
        force.push(
            copies
                * res
                    .contacts
                    .iter()
                    .map(|c| <Dim<D> as ContactSpace<D>>::components(&c.r)[0])
                    .sum::<f64>()
                / h,
        );
        let v = sim.scheme().velocity();
        velocity.push(m1.iter().zip(v).map(|(a, b)| a * b).sum::<f64>() / mass);
    }
    Impact {
        mass: copies * mass,
        force,
        velocity,
        solves: sim.structure().solve_count(),
    }
}

impl Impact {
    /// `(t_c, P_max)`: the time from the first to the last step with a force (whole steps,
    /// `± h`), and the largest force.
    pub fn duration_and_peak(&self, h: f64) -> (f64, f64) {
        let peak = self.force.iter().fold(0.0_f64, |m, f| m.max(*f));
        let on: Vec<usize> = (0..self.force.len())
            .filter(|&k| self.force[k] > 1e-6 * peak)
            .collect();
        let (first, last) = (on[0], *on.last().unwrap());
        ((last - first + 1) as f64 * h, peak)
    }

    /// The steps with a force, as runs `(first, last)` (more than one: a release and a
    /// re-impact).
    pub fn contact_runs(&self) -> Vec<(usize, usize)> {
        let peak = self.force.iter().fold(0.0_f64, |m, f| m.max(*f));
        let mut runs: Vec<(usize, usize)> = Vec::new();
        for (k, f) in self.force.iter().enumerate() {
            if *f > 1e-6 * peak {
                match runs.last_mut() {
                    Some((_, last)) if *last + 1 == k => *last = k,
                    _ => runs.push((k, k)),
                }
            }
        }
        runs
    }
}
