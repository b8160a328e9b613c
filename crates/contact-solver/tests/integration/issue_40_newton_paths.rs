//! Issue 40: the two contact paths inside the global Newton — a dense `F*` rebuilt on every
//! new tangent, and the primal active set on the tangent's matrix — give the same answer, and
//! what each costs per Newton iteration.
//!
//! The structure is a linear-elastic block whose tangent is declared new in every iteration
//! (`Retangent`: its stiffness version changes at each `update_tangent`, as a plastic body's
//! does), so each iteration pays what a plastic body's would for its contact path: `F*`'s
//! `2 n_c` solves, or the active set's factorisations of the constrained tangent (the body's
//! own refactorisation, the same for both paths, is not counted). Sketch: a block `L × 1`
//! (P1, plane strain, E = 1000, ν = 0.3) on a rigid line, pressed by `δ = 0.01` then pushed by
//! `0.004` (Coulomb, μ = 0.3: the base slides); `n_c = nx + 1` contacts.

#![cfg(feature = "fe")]

use contact_laws::Coulomb;
use contact_solver::coupling::simulation::NEWTON_DENSE_LIMIT;
use contact_solver::{
    ContactSimulation, ContactZone, FlexibilityMode, NewtonSettings, RigidLine, SimulationSettings,
};
use fem_core::faer::MatMut;
use fem_core::faer::sparse::SparseColMatRef;
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{
    Component, FemError, Idealization, LinearElasticModel, Material, Nonlinear, Structure, Supports,
};
use std::time::Duration;

/// A linear-elastic model whose tangent is new after every `update_tangent`.
struct Retangent {
    model: LinearElasticModel,
    tangents: u64,
}

impl Structure for Retangent {
    fn dof_count(&self) -> usize {
        self.model.dof_count()
    }
    fn node_count(&self) -> usize {
        self.model.node_count()
    }
    fn node_position(&self, node: usize) -> [f64; 2] {
        self.model.node_position(node)
    }
    fn node_dofs(&self, node: usize) -> [Option<usize>; 2] {
        self.model.node_dofs(node)
    }
    fn prescribed_displacement(&self, node: usize) -> [f64; 2] {
        self.model.prescribed_displacement(node)
    }
    fn outward_normal(&self, node: usize) -> Option<[f64; 2]> {
        self.model.outward_normal(node)
    }
    fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), FemError> {
        self.model.solve_in_place(rhs)
    }
    fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), FemError> {
        self.model.solve_many_in_place(rhs)
    }
    fn free_response_into(&self, factor: f64, u: &mut [f64]) -> Result<(), FemError> {
        self.model.free_response_into(factor, u)
    }
    fn stiffness_version(&self) -> u64 {
        (self.model.stiffness_version() << 32) + self.tangents
    }
    fn stiffness_matrix(&self) -> Option<SparseColMatRef<'_, usize, f64>> {
        self.model.stiffness_matrix()
    }
    fn nonlinear(&mut self) -> Option<&mut dyn Nonlinear> {
        Some(self)
    }
}

impl Nonlinear for Retangent {
    fn external_force_into(&self, factor: f64, f_ext: &mut [f64]) -> Result<(), FemError> {
        Nonlinear::external_force_into(&self.model, factor, f_ext)
    }
    fn internal_force_into(&mut self, u: &[f64], f_int: &mut [f64]) -> Result<(), FemError> {
        Nonlinear::internal_force_into(&mut self.model, u, f_int)
    }
    fn update_tangent(&mut self) -> Result<(), FemError> {
        self.tangents += 1;
        Ok(())
    }
    fn commit(&mut self) {}
    fn rollback(&mut self) {}
}

/// Presses and pushes a block of `nx` cells along its base through the Newton:
/// the final displacement and the wall time per Newton iteration.
fn run(nx: usize, flexibility: FlexibilityMode) -> (Vec<f64>, Duration) {
    let length = nx as f64 / 16.0;
    let mesh = rectangle(&RectangleSpec::new([0.0, length], [0.0, 1.0], nx, 16)).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0).unwrap();
    supports.prescribe(&top, Component::X, 0.0).unwrap();
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1000.0, 0.3, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [length + 1.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, Coulomb::new(0.3).unwrap(), 0.1);
    let settings = SimulationSettings::default().with_flexibility(flexibility);
    let body = Retangent { model, tangents: 0 };
    let mut sim = ContactSimulation::new(body, vec![zone], settings)
        .unwrap()
        .with_newton(NewtonSettings::default())
        .unwrap();
    let (mut time, mut iterations) = (Duration::ZERO, 0);
    for (k, (ux, uy)) in [(0.0, -0.01), (0.004, -0.01)].into_iter().enumerate() {
        let model = &mut sim.structure_mut().model;
        model.set_prescribed(&top, Component::X, ux).unwrap();
        model.set_prescribed(&top, Component::Y, uy).unwrap();
        let res = sim.step((k + 1) as f64, 1.0).unwrap();
        // Auto in the Newton: the active set past NEWTON_DENSE_LIMIT contacts
        let active_set = match flexibility {
            FlexibilityMode::Auto { .. } => nx + 1 > NEWTON_DENSE_LIMIT,
            mode => mode == FlexibilityMode::ActiveSet,
        };
        assert_eq!(res.report.active_set, active_set);
        time += res.report.wall_time;
        iterations += res.report.newton.as_ref().unwrap().iterations;
    }
    (sim.displacement().to_vec(), time / iterations as u32)
}

#[test]
fn issue_40_newton_dense_and_active_set_agree() {
    let (u_dense, _) = run(32, FlexibilityMode::Dense);
    let (u_active, _) = run(32, FlexibilityMode::ActiveSet);
    // the default (Auto) takes the active set at 33 contacts, the dense F* at 17
    let (u_auto, _) = run(32, FlexibilityMode::default());
    assert_eq!(u_auto, u_active);
    run(16, FlexibilityMode::default());
    // 1e-8 of the largest displacement: both solve the contact problem to the reduced
    // solver's 1e-10, on the same tangent
    let scale = u_dense.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (a, b) in u_dense.iter().zip(&u_active) {
        assert!((a - b).abs() <= 1e-8 * scale, "{a} vs {b}");
    }
}

/// The measurement behind the Newton's default path (`docs/guide.md`, "Newton around
/// contact"): `cargo test -p contact-solver --test integration issue_40_measure -- --ignored
/// --nocapture`.
#[test]
#[ignore = "a timing, printed"]
fn issue_40_measure_newton_paths() {
    for nx in [8, 16, 32, 64, 256] {
        // the best of 3 (a shared machine)
        let best = |mode| (0..3).map(|_| run(nx, mode).1).min().unwrap();
        let (dense, active) = (
            best(FlexibilityMode::Dense),
            best(FlexibilityMode::ActiveSet),
        );
        println!(
            "{} contacts: dense F* {:.2} ms, active set {:.2} ms per Newton iteration",
            nx + 1,
            dense.as_secs_f64() * 1e3,
            active.as_secs_f64() * 1e3
        );
    }
}
