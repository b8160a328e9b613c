//! The matrix-free iteration against the dense Gauss–Seidel solver on seeded random problems,
//! with the product `W r + q` as its only access to the problem.

#![cfg(feature = "fe")]

use contact_solver::local::generate::random_problem;
use contact_solver::local::matrix_free::solve_matrix_free;
use contact_solver::{UzawaSettings, UzawaSolver};

#[test]
fn matrix_free_agrees_with_gauss_seidel() {
    for (nc, seed) in [(10, 1), (50, 2), (200, 3)] {
        let p = random_problem(nc, seed);
        let laws = p.coulomb_laws();
        let settings = UzawaSettings::default();
        let dense = UzawaSolver::new(settings).solve(&p, &laws).unwrap();
        let rho0: Vec<f64> = (0..nc)
            .map(|i| {
                let [[a, b, _], [_, d, _], _] = p.diagonal_block(i);
                let h = 0.5 * (a - d);
                1.0 / (0.5 * (a + d) + (h * h + b * b).sqrt())
            })
            .collect();
        let states = vec![(); nc];
        let (mut r, mut x) = (vec![0.0; 2 * nc], vec![0.0; 2 * nc]);
        let report = solve_matrix_free(
            |r: &[f64], x: &mut [f64]| {
                p.displacement_into(r, x);
                Ok(())
            },
            &laws,
            &states,
            &rho0,
            &settings,
            &mut r,
            &mut x,
        )
        .unwrap();
        let scale = dense.r.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
        let diff = r
            .iter()
            .zip(&dense.r)
            .fold(0.0_f64, |a, (u, v)| a.max((u - v).abs()));
        eprintln!(
            "n_c {nc}: matrix-free {} iterations / {} products ({} restarts), GS {} sweeps; max |Δr| {diff:e}",
            report.iterations, report.applications, report.restarts, dense.report.iterations
        );
        assert!(report.converged);
        assert!(diff <= 1e-8 * scale, "n_c {nc}: {diff} vs {scale}");
    }
}

#[test]
fn matrix_free_reports_non_convergence_with_history() {
    let p = random_problem(20, 4);
    let laws = p.coulomb_laws();
    let settings = UzawaSettings::default().with_max_iterations(3);
    let (mut r, mut x) = (vec![0.0; 40], vec![0.0; 40]);
    let e = solve_matrix_free(
        |r: &[f64], x: &mut [f64]| {
            p.displacement_into(r, x);
            Ok(())
        },
        &laws,
        &[(); 20],
        &[0.1; 20],
        &settings,
        &mut r,
        &mut x,
    );
    match e {
        Err(contact_solver::SolverError::NotConverged {
            iterations,
            history,
            ..
        }) => {
            assert_eq!(iterations, 3);
            assert_eq!(history.len(), 3);
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
}

/// The same simulation dense and matrix-free (forced): a P2 block pressed on a LINE then pushed
/// sideways (Coulomb), so stick, slip and separation all occur.
#[test]
fn simulation_matrix_free_matches_dense() {
    use contact_laws::Coulomb;
    use contact_solver::{
        ContactSimulation, ContactZone, FlexibilityMode, RigidLine, SimulationSettings,
    };
    use fem_core::generate::{RectangleSpec, rectangle};
    use fem_core::{Component, ElementKind, Idealization, LinearElasticModel, Material, Supports};
    let run = |mode: FlexibilityMode| {
        let mut spec = RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 16, 8);
        spec.kind = ElementKind::Tri6;
        let mesh = rectangle(&spec).unwrap();
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
        // a LINE tilted slightly: the contact opens towards the right end
        let ground = RigidLine::new([-1.0, -0.01], [3.0, -0.03]).unwrap();
        let zone = ContactZone::rigid("base", bottom, ground, Coulomb::new(0.3).unwrap(), 0.1);
        let mut settings = SimulationSettings::default().with_flexibility(mode);
        settings.solver.tol = 1e-11;
        let mut sim = ContactSimulation::new(model, vec![zone], settings).unwrap();
        let mut out = Vec::new();
        for (k, (dy, dx)) in [(-0.02, 0.0), (-0.03, 0.002), (-0.03, 0.02)]
            .into_iter()
            .enumerate()
        {
            sim.structure_mut()
                .set_prescribed(&top, Component::Y, dy)
                .unwrap();
            sim.structure_mut()
                .set_prescribed(&top, Component::X, dx)
                .unwrap();
            out.push(sim.step(k as f64 + 1.0, 1.0).unwrap());
        }
        (out, sim.counters())
    };
    let (dense, cd) = run(FlexibilityMode::Dense);
    let (free, cf) = run(FlexibilityMode::MatrixFree);
    assert_eq!(cd.matrix_free_steps, 0);
    assert_eq!(cf.matrix_free_steps, 3);
    assert_eq!(cf.flexibility_builds, 0);
    let scale = dense
        .iter()
        .flat_map(|s| &s.contacts)
        .fold(0.0_f64, |a, c| a.max(c.r.n.abs()));
    let mut statuses = std::collections::HashSet::new();
    for (a, b) in dense.iter().zip(&free) {
        for (x, y) in a.contacts.iter().zip(&b.contacts) {
            for (xd, yd) in [(x.r.n, y.r.n), (x.r.t[0], y.r.t[0])] {
                assert!((xd - yd).abs() <= 1e-7 * scale, "{:?} vs {:?}", x.r, y.r);
            }
            if x.r.n > 1e-6 * scale {
                assert_eq!(x.status, y.status);
            }
            statuses.insert(x.status);
        }
    }
    eprintln!(
        "dense: {} F* columns; matrix-free: {} products, {} sampled columns",
        cd.flexibility_columns, cf.operator_applications, cf.flexibility_columns
    );
    assert!(statuses.len() >= 3, "{statuses:?}");
}
