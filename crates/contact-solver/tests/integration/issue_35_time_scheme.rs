//! Issue 35: the time-scheme seam ([`TimeScheme`]) is pluggable.
//!
//! A scheme written here, [`Counted`], counts every call the simulation makes through the seam
//! and delegates to [`QuasiStatic`]. Plugged in with [`ContactSimulation::with_scheme`], it
//! must (a) be called as the seam's contract says, per step: one free response, one free jump
//! per candidate, one `q` per active contact and pass at least, one displacement and one jump
//! per active contact per pass, one acceptance; and (b) give the answer of the default
//! simulation (`ContactSimulation::new`, quasi-static). The two run the same floating-point
//! operations in the same order, so they agree to round-off: the tolerance `1e-14` relative
//! to each scene's largest reaction (resp. displacement) leaves room for nothing but a change
//! of operation order (measured: 0).
//!
//! Scenes, one per path of the pipeline that the seam touches: a block pressed then sheared on
//! a rigid line with Coulomb friction (tangential `q` and jumps, dense `F*`); a floating block
//! lifted above the line that falls onto it (the rigid motion `R α` in the free response,
//! extra detection passes); a block glued by RCCM and pulled off over several steps (the
//! adhesion loop with `dt`); the primal active-set and matrix-free paths on the sheared block.

#![cfg(feature = "fe")]

use contact_laws::{BetaScheme, ContactLaw, Coulomb, Rccm, RccmParams, StandardLaw};
use contact_solver::coupling::simulation::{QuasiStatic, SchemeStep, TimeScheme};
use contact_solver::{
    Candidate, ContactSimulation, ContactZone, FlexibilityMode, RigidLine, SimulationSettings,
    SolverError, StepResult,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, ElementKind, Idealization, LinearElasticModel, Material, Supports};
use std::borrow::Cow;
use std::cell::Cell;

/// Calls made through the seam.
#[derive(Clone, Debug, Default, PartialEq)]
struct Calls {
    free_response: usize,
    free_jump: usize,
    rhs: usize,
    displacement: usize,
    jump: usize,
    accept: usize,
}

/// [`QuasiStatic`], counting the calls.
#[derive(Default)]
struct Counted {
    inner: QuasiStatic,
    free_jump: Cell<usize>,
    rhs: Cell<usize>,
    displacement: Cell<usize>,
    jump: Cell<usize>,
    free_response: usize,
    accept: usize,
}

impl Counted {
    fn calls(&self) -> Calls {
        Calls {
            free_response: self.free_response,
            free_jump: self.free_jump.get(),
            rhs: self.rhs.get(),
            displacement: self.displacement.get(),
            jump: self.jump.get(),
            accept: self.accept,
        }
    }
}

fn bump(c: &Cell<usize>) {
    c.set(c.get() + 1);
}

impl<S: ?Sized, const D: usize> TimeScheme<S, D> for Counted
where
    QuasiStatic: TimeScheme<S, D>,
{
    fn free_response(
        &mut self,
        structure: &S,
        step: &SchemeStep<'_>,
        free: &mut [f64],
    ) -> Result<(), SolverError> {
        self.free_response += 1;
        assert!(step.dt >= 0.0 && step.time.is_finite());
        self.inner.free_response(structure, step, free)
    }

    fn free_jump(
        &mut self,
        index: usize,
        candidate: &Candidate<D>,
        u_rel: [f64; D],
        start: &[f64; D],
    ) -> [f64; D] {
        bump(&self.free_jump);
        TimeScheme::<S, D>::free_jump(&mut self.inner, index, candidate, u_rel, start)
    }

    fn rhs(&self, index: usize, free: &[f64; D], start: &[f64; D]) -> [f64; D] {
        bump(&self.rhs);
        TimeScheme::<S, D>::rhs(&self.inner, index, free, start)
    }

    fn displacement<'y>(&self, step: &SchemeStep<'_>, solution: &'y [f64]) -> Cow<'y, [f64]> {
        bump(&self.displacement);
        TimeScheme::<S, D>::displacement(&self.inner, step, solution)
    }

    fn jump(&self, index: usize, x: &[f64; D], start: &[f64; D]) -> [f64; D] {
        bump(&self.jump);
        TimeScheme::<S, D>::jump(&self.inner, index, x, start)
    }

    fn accept(
        &mut self,
        structure: &S,
        step: &SchemeStep<'_>,
        solution: &[f64],
        displacement: &[f64],
    ) {
        self.accept += 1;
        // quasi-static: the solution is the displacement
        assert_eq!(solution, displacement);
        self.inner.accept(structure, step, solution, displacement)
    }
}

/// Runs `steps` (end time, force factor) on the default simulation and on one with
/// [`Counted`] (both built by `build`, the structure changed by `change(structure, k)` before
/// step `k`), checks the calls of every step and that the two agree to 1e-14 (module docs).
fn same_answer<L: ContactLaw + Clone>(
    name: &str,
    build: impl Fn() -> (LinearElasticModel, Vec<ContactZone<L>>, SimulationSettings),
    steps: &[(f64, f64)],
    change: impl Fn(&mut LinearElasticModel, usize),
) {
    let (model, zones, settings) = build();
    let mut plain = ContactSimulation::new(model, zones, settings).unwrap();
    let (model, zones, settings) = build();
    let mut counted =
        ContactSimulation::with_scheme(model, zones, settings, Counted::default()).unwrap();
    let candidates = plain.candidates().len();
    for (k, (time, factor)) in steps.iter().enumerate() {
        change(plain.structure_mut(), k);
        change(counted.structure_mut(), k);
        let before = counted.scheme().calls();
        let a = plain.step(*time, *factor).unwrap();
        let b = counted.step(*time, *factor).unwrap();
        let calls = counted.scheme().calls();
        let passes = b.report.detection_passes;
        let active = b.report.active_contacts;
        // the contract, per step
        assert_eq!(calls.free_response - before.free_response, 1, "{name} {k}");
        assert_eq!(calls.accept - before.accept, 1, "{name} {k}");
        assert_eq!(calls.free_jump - before.free_jump, candidates, "{name} {k}");
        assert!(
            calls.displacement - before.displacement <= passes,
            "{name} {k}"
        );
        assert!(calls.displacement > before.displacement, "{name} {k}");
        assert!(calls.rhs - before.rhs >= active, "{name} {k}");
        assert!(calls.jump - before.jump >= active, "{name} {k}");
        compare(name, k, &a, &b);
        assert_eq!(a.report.contact_iterations, b.report.contact_iterations);
        assert_eq!(a.report.detection_passes, b.report.detection_passes);
        let (ua, ub) = (plain.nodal_displacements(), counted.nodal_displacements());
        let size = ua.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (p, q) in ua.iter().flatten().zip(ub.iter().flatten()) {
            assert!((p - q).abs() <= 1e-14 * size, "{name} {k}: u {p} vs {q}");
        }
        for (p, q) in plain
            .rigid_body_amplitudes()
            .iter()
            .zip(counted.rigid_body_amplitudes())
        {
            assert!((p - q).abs() <= 1e-14 * p.abs().max(size), "{name} {k}: α");
        }
    }
    assert_eq!(plain.counters(), counted.counters(), "{name}");
    eprintln!("{name}: {:?}", counted.scheme().calls());
}

/// The records of two steps agree to 1e-14 of the largest reaction (gaps and slips to 1e-14
/// of the largest of them).
fn compare(name: &str, k: usize, a: &StepResult, b: &StepResult) {
    let force = a
        .contacts
        .iter()
        .flat_map(|c| c.reaction())
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    let length = a
        .contacts
        .iter()
        .flat_map(|c| [c.gap, c.u_t, c.slip_increment])
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    for (p, q) in a.contacts.iter().zip(&b.contacts) {
        assert_eq!(p.status, q.status, "{name} {k}: node {}", p.node);
        for (x, y) in p.reaction().iter().zip(q.reaction()) {
            assert!((x - y).abs() <= 1e-14 * force, "{name} {k}: r {x} vs {y}");
        }
        for (x, y) in [
            (p.gap, q.gap),
            (p.u_t, q.u_t),
            (p.slip_increment, q.slip_increment),
            (p.beta, q.beta),
        ] {
            assert!(
                (x - y).abs() <= 1e-14 * length.max(1.0e-300),
                "{name} {k}: {x} vs {y}"
            );
        }
    }
}

/// A block (2 × 1, E = 1000, ν = 0) on a rigid line, its top prescribed.
fn sheared_block(
    settings: SimulationSettings,
) -> (
    LinearElasticModel,
    Vec<ContactZone<Coulomb>>,
    SimulationSettings,
) {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 8, 4)
    };
    let mesh = rectangle(&spec).unwrap();
    let top = mesh.node_set("top").unwrap().to_vec();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0).unwrap();
    supports.prescribe(&top, Component::X, 0.0).unwrap();
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(1000.0, 0.0, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, Coulomb::new(0.3).unwrap(), 0.1);
    (model, vec![zone], settings)
}

fn top_of(model: &LinearElasticModel) -> Vec<usize> {
    model.mesh().node_set("top").unwrap().to_vec()
}

fn press_then_shear(model: &mut LinearElasticModel, k: usize) {
    let top = top_of(model);
    let (dy, dx) = [(-0.01, 0.0), (-0.01, 1e-5), (-0.01, 0.05), (-0.005, 0.06)][k];
    model.set_prescribed(&top, Component::Y, dy).unwrap();
    model.set_prescribed(&top, Component::X, dx).unwrap();
}

#[test]
fn issue_35_time_scheme_sheared_block_works() {
    for flexibility in [
        FlexibilityMode::Dense,
        FlexibilityMode::ActiveSet,
        FlexibilityMode::MatrixFree,
    ] {
        let settings = SimulationSettings::default().with_flexibility(flexibility);
        same_answer(
            &format!("sheared {flexibility:?}"),
            || sheared_block(settings),
            &[(1.0, 1.0), (2.0, 1.0), (3.0, 1.0), (4.0, 1.0)],
            press_then_shear,
        );
    }
}

#[test]
fn issue_35_time_scheme_floating_block_works() {
    let build = || {
        let spec = RectangleSpec {
            kind: ElementKind::Tri6,
            ..RectangleSpec::new([0.0, 2.0], [0.05, 1.05], 8, 4)
        };
        let mesh = rectangle(&spec).unwrap();
        let bottom = mesh.node_set("bottom").unwrap().to_vec();
        let material = Material::new(1000.0, 0.3, 0.0).unwrap();
        let mut model = LinearElasticModel::floating(
            mesh,
            Idealization::PlaneStrain,
            &[(0, material)],
            Supports::new(),
        )
        .unwrap();
        model.add_body_force(|_| [0.0, -1.0]).unwrap();
        model.add_edge_traction("top", |_| [0.1, 0.0]).unwrap();
        let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
        let law = StandardLaw::from(Coulomb::new(0.3).unwrap());
        let zone = ContactZone::rigid("base", bottom, ground, law, 0.01);
        (model, vec![zone], SimulationSettings::default())
    };
    // falls onto the line (passes > 1), then rests under 1.5 and 2 times the load (α ≠ 0 in
    // the free response)
    same_answer(
        "floating",
        build,
        &[(1.0, 1.0), (2.0, 1.5), (3.0, 2.0)],
        |_, _| {},
    );
}

#[test]
fn issue_35_time_scheme_glued_block_works() {
    let build = || {
        let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 6, 3)).unwrap();
        let top = mesh.node_set("top").unwrap().to_vec();
        let bottom = mesh.node_set("bottom").unwrap().to_vec();
        let mut supports = Supports::new();
        supports.prescribe(&top, Component::Y, 0.0).unwrap();
        supports.fix(&top, Component::X);
        let model = LinearElasticModel::new(
            mesh,
            Idealization::PlaneStrain,
            &[(0, Material::new(1e5, 0.0, 0.0).unwrap())],
            supports,
        )
        .unwrap();
        let law = Rccm::new(RccmParams {
            c_n: 100.0,
            c_t: 100.0,
            w: 0.01,
            alpha: 0.1,
            mu: 0.2,
            m: 1,
            beta_0: 1.0,
            scheme: BetaScheme::ImplicitEuler,
        })
        .unwrap();
        let base = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
        let zone = ContactZone::rigid("glue", bottom, base, law, 1e-3);
        (model, vec![zone], SimulationSettings::default())
    };
    // pulled through the peak (u₀ = √(w/C_n) = 0.01) to 3 u₀, one step per 0.002, at
    // 0.1 s per step (the viscosity α = 0.1 makes dt matter)
    let steps: Vec<(f64, f64)> = (1..=15).map(|k| (0.1 * k as f64, 1.0)).collect();
    same_answer("glued", build, &steps, |m, k| {
        let top = top_of(m);
        m.set_prescribed(&top, Component::Y, 0.002 * (k + 1) as f64)
            .unwrap();
    });
}
