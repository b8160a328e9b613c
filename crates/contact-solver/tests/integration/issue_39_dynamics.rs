//! Issue 39: nonsmooth contact dynamics, the library core ([`MoreauJean`] on a
//! [`DynamicModel`]).
//!
//! (a) Free vibration of a P2 cantilever (no contact: the obstacle is far) with `θ = 1/2`:
//!     the trapezoidal rule conserves `T + V` exactly, so the energy drifts by round-off only;
//!     with `θ = 1` the energy decays and the balance closes with the scheme's dissipation
//!     `D_θ = (θ − ½)(ΔvᵀMΔv + ΔuᵀKΔu)`.
//!     With one free dof (`m ü + k u = 0`), the trapezoidal rule is a rotation by
//!     `φ = 2 atan(ωh/2)` in the energy norm: from `(u0, 0)`, `u_n = u0 cos(nφ)` exactly
//!     (Hughes 1987 §9.3, the amplification of the θ-method).
//! (b) An elastic bar (plane stress, P2 strip, `ν = 0`: a 1D bar) hits a rigid wall at `v0`
//!     with `e = 0`, `θ = 1/2`. One-dimensional wave theory (Graff 1975 §2.1, "Wave motion in
//!     elastic solids"; Timoshenko & Goodier §143) gives the contact duration `2L/c`,
//!     `c = √(E/ρ)`, the contact force `ρ c A v0` while in contact and a rebound at `v0`.
//! (d) The same generic function, a free-flying body at uniform velocity (no load, no
//!     contact: `u = v0 t` exactly), on a 2D and a 3D model.
//!
//! Sketch (b):
//! ```text
//!   wall x = 0 |<- v0   [=============== bar L × b, E, ρ, ν = 0 ===============]
//! ```

#![cfg(feature = "fe")]

use contact_laws::Signorini;
use contact_solver::coupling::simulation::{EnergyBalance, MoreauJean};
use contact_solver::coupling::solid::RigidPlane;
use contact_solver::coupling::space::ContactSpace;
use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
use fem_core::dynamic::{DynamicModel, MassKind, Rayleigh};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::model::ModelSpace;
use fem_core::solid::generate::{box_mesh, lines};
use fem_core::solid::{SolidKind, SolidModel};
use fem_core::{Component, Dim, ElasticModel, ElementKind, Idealization, LinearElasticModel};
use fem_core::{Material, Structure, Supports};
use std::time::Instant;

/// A P2 cantilever 4 × 0.5 (8 × 2 cells), clamped on the left, moving with `v_y = 0.1 x/4`,
/// a rigid line 10 beyond its tip (never reached); `n` steps of `h = 0.05` at weight `theta`.
fn cantilever(theta: f64, n: usize) -> Vec<EnergyBalance> {
    cantilever_from(n, |body| {
        MoreauJean::new(theta)
            .unwrap()
            .with_velocity_field(body, |x| [0.0, 0.1 * x[0] / 4.0])
            .unwrap()
    })
}

/// The cantilever of [`cantilever`], the scheme (θ, initial state) made by `scheme`.
fn cantilever_from(
    n: usize,
    scheme: impl FnOnce(&DynamicModel<2>) -> MoreauJean,
) -> Vec<EnergyBalance> {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 4.0], [0.0, 0.5], 8, 2)
    };
    let mesh = rectangle(&spec).unwrap();
    let (left, right) = (
        mesh.node_set("left").unwrap().to_vec(),
        mesh.node_set("right").unwrap().to_vec(),
    );
    let mut supports = Supports::new();
    supports.fix(&left, Component::X).fix(&left, Component::Y);
    let m = Material::new(100.0, 0.3, 0.0)
        .unwrap()
        .with_density(1.0)
        .unwrap();
    let model =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], supports).unwrap();
    let body = DynamicModel::new(model, MassKind::Consistent, Rayleigh::default()).unwrap();
    let scheme = scheme(&body);
    let far = RigidLine::new([14.0, -1.0], [14.0, 2.0]).unwrap(); // normal −x
    let zone = ContactZone::rigid("far", right, far, Signorini, 0.1);
    let mut sim =
        ContactSimulation::with_scheme(body, vec![zone], SimulationSettings::default(), scheme)
            .unwrap();
    for _ in 0..n {
        let res = sim.advance(0.05).unwrap();
        assert_eq!(res.report.active_contacts, 0);
    }
    sim.scheme().energy_history().to_vec()
}

#[test]
fn issue_39_free_vibration_conserves_energy() {
    let start = Instant::now();
    let history = cantilever(0.5, 200);
    let e0 = history[0].initial;
    let drift = history
        .iter()
        .map(|e| (e.mechanical() - e0).abs() / e0)
        .fold(0.0, f64::max);
    let moved = history.iter().map(|e| e.strain / e0).fold(0.0, f64::max);
    eprintln!(
        "cantilever θ = 1/2, 200 steps: max |T + V − E0| / E0 = {drift:.2e}, max V/E0 = \
         {moved:.3}, {:.2?}",
        start.elapsed()
    );
    // the trapezoidal rule conserves T + V exactly; what is left is the round-off of
    // evaluating ½ uᵀ K u for a slender bending motion, ε ‖K‖ ‖u‖² / (uᵀ K u) ≈ 1e-12: it does
    // not accumulate (measured: max 5.9e-12 over 200 steps, 3.2e-12 at step 325 of 400)
    assert!(drift < 2e-11, "energy drift {drift:e}");
    // the energy does move between kinetic and strain (the test can fail)
    assert!(moved > 0.3, "strain share {moved}");
    let last = history.last().unwrap();
    assert_eq!(last.numerical, 0.0); // θ = 1/2: no numerical dissipation
    assert_eq!(last.contact_work, 0.0);
}

#[test]
fn issue_39_theta_one_balance_closes() {
    let history = cantilever(1.0, 100);
    let last = history.last().unwrap();
    let e0 = last.initial;
    // backward Euler dissipates (measured: 5 % of E0 in 100 steps of ωh ≈ 0.02 on the
    // first mode, more on the higher ones)
    assert!(last.numerical > 0.01 * e0, "{last:?}");
    // and every step's balance closes with D_θ (round-off, as above: measured 4e-12)
    for e in &history {
        assert!(e.residual().abs() < 2e-11 * e0, "{e:?}");
    }
    // monotone decay: D_θ ≥ 0 each step
    assert!(
        history
            .windows(2)
            .all(|w| w[1].mechanical() <= w[0].mechanical())
    );
}

#[test]
fn issue_39_initial_displacement_works() {
    // released from a bent shape u0 = (0, 0.01 (x/4)²) at rest: T0 = 0, V0 = ½ u0ᵀ K u0
    let mut v0 = 0.0;
    let history = cantilever_from(50, |body| {
        let mut u0 = vec![0.0; body.dof_count()];
        for node in 0..body.node_count() {
            let x = body.node_position(node);
            if let Some(i) = body.node_dofs(node)[1] {
                u0[i] = 0.01 * (x[0] / 4.0).powi(2);
            }
        }
        let mut ku = vec![0.0; u0.len()];
        body.stiffness_mul_into(&u0, &mut ku);
        v0 = 0.5 * u0.iter().zip(&ku).map(|(a, b)| a * b).sum::<f64>();
        MoreauJean::new(0.5).unwrap().with_displacement(u0).unwrap()
    });
    let first = &history[0];
    // the balance starts from the strain energy of u0 (same products: round-off)
    assert!(
        (first.initial - v0).abs() < 1e-14 * v0,
        "{} vs {v0}",
        first.initial
    );
    // released: energy moves into motion, and T + V stays V0 (as in the free vibration)
    let last = history.last().unwrap();
    assert!(last.kinetic > 0.01 * v0, "{last:?}");
    for e in &history {
        assert!((e.mechanical() - v0).abs() < 2e-11 * v0, "{e:?}");
    }
}

#[test]
fn issue_39_moreau_jean_rejects_bad_input() {
    use contact_solver::SolverError;
    for theta in [0.49, 1.01, f64::NAN] {
        assert!(matches!(
            MoreauJean::new(theta),
            Err(SolverError::InvalidSetting { what: "theta", .. })
        ));
    }
    for e in [-0.1, 1.5, f64::NAN] {
        let s = MoreauJean::new(0.5).unwrap();
        assert!(matches!(
            s.with_restitution(e),
            Err(SolverError::InvalidSetting {
                what: "restitution",
                ..
            })
        ));
    }
    assert!(matches!(
        MoreauJean::new(0.5)
            .unwrap()
            .with_velocity(vec![0.0, f64::NAN]),
        Err(SolverError::NonFinite {
            what: "velocity",
            index: 1,
            ..
        })
    ));
    assert!(matches!(
        MoreauJean::new(0.5)
            .unwrap()
            .with_displacement(vec![f64::INFINITY]),
        Err(SolverError::NonFinite {
            what: "displacement",
            index: 0,
            ..
        })
    ));
}

#[test]
fn issue_39_one_dof_follows_the_trapezoidal_amplification() {
    // a P1 unit square (two triangles), every dof fixed but x at the top-right node
    let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 1, 1)).unwrap();
    let corner = (0..mesh.node_count())
        .find(|&n| mesh.nodes()[n] == [1.0, 1.0])
        .unwrap();
    let others: Vec<usize> = (0..mesh.node_count()).filter(|&n| n != corner).collect();
    let mut supports = Supports::new();
    supports
        .fix(&others, Component::X)
        .fix(&others, Component::Y)
        .fix(&[corner], Component::Y);
    let m = Material::new(100.0, 0.25, 0.0)
        .unwrap()
        .with_density(2.0)
        .unwrap();
    let model =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], supports).unwrap();
    let body = DynamicModel::new(model, MassKind::Consistent, Rayleigh::default()).unwrap();
    assert_eq!(body.dof_count(), 1);
    let (mut mass, mut stiffness) = ([0.0], [0.0]);
    body.mass_mul_into(&[1.0], &mut mass);
    body.stiffness_mul_into(&[1.0], &mut stiffness);
    let omega = (stiffness[0] / mass[0]).sqrt();
    let h = 1.0 / omega; // ωh = 1: φ = 0.927, a 7 % period error, far above the tolerance
    let u0 = 1e-3;
    let scheme = MoreauJean::new(0.5)
        .unwrap()
        .with_displacement(vec![u0])
        .unwrap();
    let far = RigidLine::new([9.0, -1.0], [9.0, 2.0]).unwrap(); // normal −x, 8 away
    let zone = ContactZone::rigid("far", vec![corner], far, Signorini, 0.1);
    let mut sim =
        ContactSimulation::with_scheme(body, vec![zone], SimulationSettings::default(), scheme)
            .unwrap();
    let phi = 2.0 * (omega * h / 2.0).atan();
    let mut worst = 0.0_f64;
    for n in 1..=50 {
        sim.advance(h).unwrap();
        let u = sim.displacement()[0];
        worst = worst.max((u - u0 * (n as f64 * phi).cos()).abs() / u0);
        // and not the exact cos(ωt) (the test can tell the scheme from the ODE)
        if n == 50 {
            assert!((u - u0 * (n as f64 * omega * h).cos()).abs() > 0.1 * u0);
        }
    }
    eprintln!("one dof, ωh = 1, 50 steps: max |u − u0 cos(nφ)| / u0 = {worst:.1e}");
    // the closed form of the discrete map; only round-off of 50 steps is left (measured 8e-15)
    assert!(worst < 1e-12, "{worst:e}");
}

/// The bar of (b): `L = 1`, width 0.1, thickness 1 (plane stress), `E = ρ = 1` (`c = 1`),
/// `ν = 0`, P2 with `nx` cells along its length and one across.
struct BarRun {
    /// Contact force `Σ r_n / h` at the end of every step.
    force: Vec<f64>,
    /// The mean velocity `(1ᵀ M v) / m` along x after each step.
    velocity: Vec<f64>,
    energy: EnergyBalance,
}

fn bar(nx: usize, h: f64, steps: usize, v0: f64, mass: MassKind) -> BarRun {
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 1.0], [0.0, 0.1], nx, 1)
    };
    let mesh = rectangle(&spec).unwrap();
    let left = mesh.node_set("left").unwrap().to_vec();
    let m = Material::new(1.0, 0.0, 0.0)
        .unwrap()
        .with_density(1.0)
        .unwrap();
    let model = LinearElasticModel::floating(
        mesh,
        Idealization::PlaneStress { thickness: 1.0 },
        &[(0, m)],
        Supports::new(),
    )
    .unwrap();
    let body = DynamicModel::new(model, mass, Rayleigh::default()).unwrap();
    let scheme = MoreauJean::new(0.5)
        .unwrap()
        .with_velocity_field(&body, |_| [-v0, 0.0])
        .unwrap();
    let wall = RigidLine::new([0.0, 1.0], [0.0, -1.0]).unwrap(); // normal +x
    let zone = ContactZone::rigid("wall", left, wall, Signorini, 0.01);
    let mut sim =
        ContactSimulation::with_scheme(body, vec![zone], SimulationSettings::default(), scheme)
            .unwrap();
    let n = sim.structure().dof_count();
    let ones_x: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 1.0 } else { 0.0 }).collect();
    let mut m1 = vec![0.0; n];
    sim.structure().mass_mul_into(&ones_x, &mut m1);
    let total: f64 = m1.iter().zip(&ones_x).map(|(a, b)| a * b).sum();
    let (mut force, mut velocity) = (Vec::new(), Vec::new());
    for _ in 0..steps {
        let res = sim.advance(h).unwrap();
        force.push(res.contacts.iter().map(|c| c.r.n).sum::<f64>() / h);
        let v = sim.scheme().velocity();
        velocity.push(m1.iter().zip(v).map(|(a, b)| a * b).sum::<f64>() / total);
    }
    BarRun {
        force,
        velocity,
        energy: *sim.scheme().energy(),
    }
}

#[test]
fn issue_39_bar_impact_matches_wave_theory() {
    let start = Instant::now();
    // 100 P2 cells along L (node spacing L/200), h = L/(200 c) (half a cell per step), the
    // consistent mass. Measured (rebound / duration): consistent h = 0.01: 1.7 % / 1.0 %;
    // h = 0.005: 1.05 % / 0.5 %; h = 0.0025 (nx = 400): 0.66 % / 0.4 %. The HRZ-lumped P2
    // strip rebounds 2.7 % slow whatever the mesh and step (0.0972–0.0974 for nx = 100–200,
    // h = 0.005–0.01): it smears the returning front, so the contact unloads over ~15 steps
    // and leaves 5 % of the energy in vibration; the consistent mass does not, and its
    // plateau oscillation (Gibbs at the front) averages out.
    let (nx, h, v0) = (100, 0.005, 0.1);
    let run = bar(nx, h, 520, v0, MassKind::Consistent);
    let (duration_exact, force_exact) = (2.0, 1.0 * 1.0 * 0.1 * v0); // 2L/c, ρ c A v0
    let in_contact: Vec<usize> = (0..run.force.len())
        .filter(|&k| run.force[k] > 1e-6 * force_exact)
        .collect();
    let (first, last) = (in_contact[0], *in_contact.last().unwrap());
    // the contact is one interval (no release and re-impact)
    assert_eq!(in_contact.len(), last - first + 1, "{:?}", in_contact);
    let duration = (last - first + 1) as f64 * h;
    // the plateau: the middle 80 % of the contact
    let (a, b) = (first + (last - first) / 10, last - (last - first) / 10);
    let plateau = &run.force[a..=b];
    let mean = plateau.iter().sum::<f64>() / plateau.len() as f64;
    let spread = plateau.iter().fold(0.0_f64, |m, f| m.max((f - mean).abs())) / mean;
    let rebound = *run.velocity.last().unwrap();
    eprintln!(
        "bar P2 nx = {nx}, h = {h}: duration {duration:.4} (2L/c = {duration_exact}), \
         plateau force {mean:.6e} (ρcAv0 = {force_exact:.6e}, spread ±{:.1} %), rebound \
         {rebound:.5} (v0 = {v0}), contact dissipation {:.3e} of T0 = {:.3e}, balance \
         residual {:.1e}, {:.2?}",
        100.0 * spread,
        run.energy.contact_dissipation(),
        run.energy.initial,
        run.energy.residual(),
        start.elapsed()
    );
    // each within 2 % (the issue's bound; measured 0.5 %, 0.003 %, 1.05 %): the duration is
    // counted in whole steps (1 step = 0.25 % of 2L/c), the rebound converges as h^0.7
    assert!((duration - duration_exact).abs() < 0.02 * duration_exact);
    assert!((mean - force_exact).abs() < 0.02 * force_exact);
    assert!((rebound - v0).abs() < 0.02 * v0);
    // the balance closes with the contact's dissipation (round-off of 260 steps)
    assert!(run.energy.residual().abs() < 1e-10 * run.energy.initial); // measured 5e-17 / 5e-4
    assert!(run.energy.contact_dissipation() >= 0.0);
}

/// (d) A free flight at uniform velocity `v0` (no load; `zone` is never reached) for 20 steps
/// of `h = 0.1`, on a model of either dimension: returns the largest error of `u = v0 t` over
/// the free dofs and of `T` against `T0`, relative.
fn free_flight<const D: usize>(
    model: ElasticModel<D>,
    zone: ContactZone<Signorini, D>,
    v0: [f64; D],
) -> (f64, f64)
where
    Dim<D>: ModelSpace<D> + ContactSpace<D>,
{
    let body = DynamicModel::new(model, MassKind::Consistent, Rayleigh::default()).unwrap();
    let scheme = MoreauJean::new(0.5)
        .unwrap()
        .with_velocity_field(&body, |_| v0)
        .unwrap();
    let settings = SimulationSettings::for_dimension::<D>();
    let mut sim = ContactSimulation::with_scheme(body, vec![zone], settings, scheme).unwrap();
    let (mut u_err, mut t_err) = (0.0_f64, 0.0_f64);
    let speed = v0.iter().map(|v| v * v).sum::<f64>().sqrt();
    for k in 1..=20 {
        sim.advance(0.1).unwrap();
        let t = 0.1 * k as f64;
        for node in 0..sim.structure().node_count() {
            let u = sim.nodal_displacement(node);
            for d in 0..D {
                u_err = u_err.max((u[d] - v0[d] * t).abs() / (speed * t));
            }
        }
        let e = sim.scheme().energy();
        t_err = t_err.max((e.kinetic - e.initial).abs() / e.initial);
    }
    (u_err, t_err)
}

#[test]
fn issue_39_free_flight_works_in_2d_and_3d() {
    let mesh = rectangle(&RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2)
    })
    .unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let m = Material::new(10.0, 0.3, 0.0)
        .unwrap()
        .with_density(2.0)
        .unwrap();
    let plane =
        LinearElasticModel::floating(mesh, Idealization::PlaneStrain, &[(0, m)], Supports::new())
            .unwrap();
    let far = RigidLine::new([-9.0, -5.0], [9.0, -5.0]).unwrap();
    let zone = ContactZone::rigid("far", bottom, far, Signorini, 0.1);
    let (u2, t2) = free_flight(plane, zone, [0.3, 0.4]);

    let mesh = box_mesh(
        &lines(0.0, 1.0, 2),
        &lines(0.0, 1.0, 2),
        &lines(0.0, 1.0, 2),
        SolidKind::Hex8,
    )
    .unwrap();
    let (nodes, areas) = mesh.nodal_areas("z0").unwrap();
    let solid = SolidModel::floating(mesh, &[(0, m)], Supports::new()).unwrap();
    let far = RigidPlane::new([0.0, 0.0, -5.0], [0.0, 0.0, 1.0]).unwrap();
    let zone = ContactZone::<_, 3>::rigid("far", nodes, far, Signorini, 0.1).with_areas(areas);
    let (u3, t3) = free_flight(solid, zone, [0.3, 0.4, 0.5]);
    eprintln!("free flight: 2D |u − v0 t| {u2:.1e}, |ΔT| {t2:.1e}; 3D {u3:.1e}, {t3:.1e}");
    // a rigid translation is in the kernel of K: the scheme is exact to round-off (20 steps)
    for err in [u2, t2, u3, t3] {
        assert!(err < 1e-12, "{err:e}");
    }
}
