//! Issue 40: a displacement-controlled step that the global Newton cuts reaches its
//! prescribed displacement in sub-steps, and lands where the same sub-steps taken one by one
//! land (`Nonlinear::interpolate_prescribed`).
//!
//! Sketch: the von Mises block of `issue_40_newton_plastic` (plane strain, E = 1000,
//! ν = 0.3, shear yield k = 1) on a frictionless rigid line, one row of 4 P1 cells, its top
//! lowered by `δ = 4e-3` (beyond the first yield at `1.77e-3`). Its points refuse a
//! vertical strain increment above `1.5e-3` in one update (a material update that fails,
//! which the Newton cuts), so the step is cut twice and made in four quarters. Before the
//! seam, every sub-step applied the whole `δ` and no cut could help.

#![cfg(feature = "fe")]

use contact_laws::Signorini;
use contact_solver::{
    ContactSimulation, ContactZone, NewtonSettings, RigidLine, SimulationSettings, StepResult,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::plastic::{
    ConstitutivePoint, DruckerPrager, PlasticModel, PointState, Voigt, VoigtMatrix,
};
use fem_core::{Component, FemError, Idealization, LinearElasticModel, Material, Supports};
use std::sync::Arc;

const E: f64 = 1000.0;
const NU: f64 = 0.3;
const DELTA: f64 = 4e-3;
/// The largest vertical strain increment a point accepts in one update.
const LIMIT: f64 = 1.5e-3;

/// Von Mises, refusing a vertical strain increment above [`LIMIT`] from the committed state.
#[derive(Debug)]
struct Cautious(DruckerPrager);

impl ConstitutivePoint for Cautious {
    fn elastic_tangent(&self) -> VoigtMatrix {
        self.0.elastic_tangent()
    }

    fn update(
        &self,
        committed: &PointState,
        strain: &Voigt,
        trial: &mut PointState,
        tangent: &mut VoigtMatrix,
    ) -> Result<(), FemError> {
        let increment = (strain[1] - committed.strain[1]).abs();
        if increment > LIMIT {
            return Err(FemError::InvalidParameter {
                name: "strain",
                value: increment,
                expected: "a vertical strain increment of at most 1.5e-3",
            });
        }
        self.0.update(committed, strain, trial, tangent)
    }

    fn yield_function(&self, stress: &Voigt) -> f64 {
        self.0.yield_function(stress)
    }
}

type Simulation = ContactSimulation<PlasticModel<2>, Signorini, 2>;

fn block() -> (Simulation, Vec<usize>) {
    let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 4, 1)).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let left = mesh.node_set("left").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0).unwrap();
    supports.fix(&left, Component::X);
    let elastic = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(E, NU, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let point = Arc::new(Cautious(DruckerPrager::von_mises(E, NU, 1.0).unwrap()));
    let body = PlasticModel::new(elastic, &[(0, point)]).unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [2.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, Signorini, 0.1);
    let sim = ContactSimulation::new(body, vec![zone], SimulationSettings::default())
        .unwrap()
        .with_newton(NewtonSettings::default().with_tol(1e-12))
        .unwrap();
    (sim, top)
}

fn force(res: &StepResult<2>) -> f64 {
    res.contacts.iter().map(|c| c.r.n).sum()
}

#[test]
fn issue_40_a_cut_step_follows_its_prescribed_displacement() {
    let (mut cut, top) = block();
    cut.structure_mut()
        .set_prescribed(&top, Component::Y, -DELTA)
        .unwrap();
    let res = cut.step(1.0, 1.0).unwrap();
    let newton = res.report.newton.as_ref().unwrap();
    // 4e-3 and 2e-3 are refused, 1e-3 is not: two cuts, four quarters
    assert_eq!((newton.cuts, newton.substeps), (2, 4), "{newton:?}");

    let (mut steps, top) = block();
    let mut last = None;
    for k in 1..=4 {
        steps
            .structure_mut()
            .set_prescribed(&top, Component::Y, -DELTA * k as f64 / 4.0)
            .unwrap();
        let res = steps.step(k as f64 / 4.0, 1.0).unwrap();
        assert_eq!(res.report.newton.as_ref().unwrap().cuts, 0);
        last = Some(res);
    }
    let last = last.unwrap();
    // the same sub-steps: equal up to the round-off of the interpolated values and the
    // Newton's 1e-12 (1e-10 of the force, which is O(1))
    let (f_cut, f_steps) = (force(&res), force(&last));
    assert!(f_cut > 1.9, "plastic: {f_cut}");
    assert!(
        (f_cut - f_steps).abs() <= 1e-10 * f_steps,
        "{f_cut} vs {f_steps}"
    );
    let (a, b) = (cut.structure(), steps.structure());
    for (p, q) in a.committed_states().iter().zip(b.committed_states()) {
        for (s, t) in p.stress.iter().zip(&q.stress) {
            assert!((s - t).abs() <= 1e-10, "{:?} vs {:?}", p.stress, q.stress);
        }
        assert_eq!(p.yielding, q.yielding);
    }
    // the top ends where it was sent
    for &n in &top {
        assert_eq!(cut.nodal_displacement(n)[1], -DELTA);
    }
}
