//! A rigid rough strip footing pushed into a weightless soil, plane strain, with
//! `PlasticModel` and `plastic::newton` (issue 40). Sources: Prandtl (1920) for `φ = 0`,
//! `q_u = (2 + π) c`; Reissner (1924) and Prandtl for `φ > 0`,
//!
//! ```text
//! q_u = c N_c     N_c = (N_q − 1) cot φ     N_q = e^{π tan φ} tan²(45° + φ/2)
//! φ = 0: N_c = 2 + π = 5.1416      φ = 20°: N_q = 6.3993, N_c = 14.835
//! ```
//! exact for associated Mohr–Coulomb in plane strain (the rough base changes the mechanism
//! under the footing, not the load, for a weightless soil). The Drucker–Prager cone is matched
//! with [`ConeMatch::PlaneStrain`] (`k_d = √6 / √(3 + 4 tan²φ)`): with associated flow in plane
//! strain its limit states are Mohr–Coulomb's, and at `φ = 0` it is von Mises with shear
//! yield stress `k = c`, Tresca's `c` in plane strain (the `Outer`/`Inner` matches would give
//! `k = 2c/√3`, 15 % more).
//!
//! Sketch: half model by symmetry, `0 ≤ x ≤ W`, `−H ≤ y ≤ 0`, footing half-width `b = 1` on
//! `y = 0, x ≤ b`; rollers on `x = 0` and `x = W`, the base fixed. The footing is a uniform
//! settlement `δ` of its nodes with `u_x = 0` (rough); the mean pressure is the reaction of
//! those nodes over `b`. P2 triangles (6 nodes: P1 triangles lock under the isochoric plastic
//! flow of `φ = 0`; Quad8 and Quad9 with their full 3 × 3 rule came out 10 % high where P2
//! triangles were 6 % high), straight-sided, on a grid graded towards the footing edge `(b, 0)`.
//!
//! The settlement goes in 20 equal steps, the first predicted by the elastic response to it,
//! the others from the last converged increment,
//! a step halved when its Newton needs more than 8 solves (and doubled back after). Measured
//! on the CI mesh (`docs/validation.md`, "Plastic bodies"): `φ = 0` +2.0 % in 28 steps,
//! `φ = 20°` +2.9 % in 22 steps; on the finer mesh +0.8 % and +1.2 %. The error is the mesh's
//! at the singular footing edge: it fell from +6 % with 6 : 1 grading as the edge cells
//! shrank.

use fem_core::generate::{Grading, RectangleSpec, graded_points, rectangle};
use fem_core::plastic::newton::{self, NewtonSettings};
use fem_core::plastic::{
    ConeMatch, ConstitutivePoint, DruckerPrager, DruckerPragerParameters, PlasticModel,
};
use fem_core::{
    Component, ElementKind, FemError, Idealization, LinearElasticModel, Material, Mesh, Nonlinear,
    Structure, Supports,
};
use std::sync::Arc;

/// Half-width of the footing.
pub(crate) const HALF_WIDTH: f64 = 1.0;
/// Cohesion.
pub(crate) const C: f64 = 1.0;

/// The mesh of the half model and its refinement.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FootingMesh {
    /// Extent along x.
    width: f64,
    /// Depth.
    depth: f64,
    /// Cells under the footing, along x.
    under: usize,
    /// Cells beside the footing, along x.
    beside: usize,
    /// Cells over the depth.
    down: usize,
    /// Ratio of the largest to the smallest cell along each graded line.
    ratio: f64,
    /// The element.
    kind: ElementKind,
}

impl FootingMesh {
    /// The CI mesh: 10 + 20 cells across, 14 down, graded 40 : 1 towards the footing edge,
    /// P2 triangles (840 elements, 1769 nodes).
    pub const CI: Self = Self {
        width: 10.0,
        depth: 6.0,
        under: 10,
        beside: 20,
        down: 14,
        ratio: 40.0,
        kind: ElementKind::Tri6,
    };
}

/// Straight-sided grid: a uniform rectangle in cell indices mapped piecewise linearly onto
/// graded lines (the midside nodes land on the midpoints of the edges).
fn footing_mesh(m: &FootingMesh) -> Mesh {
    let mut xs = graded_points(0.0, HALF_WIDTH, m.under, Grading::fine_at_end(m.ratio)).unwrap();
    let outer = graded_points(
        HALF_WIDTH,
        m.width,
        m.beside,
        Grading::fine_at_start(m.ratio),
    );
    xs.extend_from_slice(&outer.unwrap()[1..]);
    let ys = graded_points(-m.depth, 0.0, m.down, Grading::fine_at_end(m.ratio)).unwrap();
    let (nx, ny) = (m.under + m.beside, m.down);
    let spec = RectangleSpec {
        kind: m.kind,
        ..RectangleSpec::new([0.0, nx as f64], [0.0, ny as f64], nx, ny)
    };
    let flat = rectangle(&spec).unwrap();
    let map = |lines: &[f64], s: f64| {
        let i = (s.floor() as usize).min(lines.len() - 2);
        lines[i] + (s - i as f64) * (lines[i + 1] - lines[i])
    };
    let nodes = flat
        .nodes()
        .iter()
        .map(|&[s, t]| [map(&xs, s), map(&ys, t)])
        .collect();
    let mut mesh = Mesh::new(
        nodes,
        m.kind,
        flat.connectivity().to_vec(),
        flat.regions().to_vec(),
    )
    .unwrap();
    for name in ["left", "right", "bottom", "top"] {
        mesh.add_node_set(name, flat.node_set(name).unwrap().to_vec())
            .unwrap();
    }
    mesh
}

/// The footing's nodes: the top nodes with `x ≤ b`.
fn footing_nodes(mesh: &Mesh) -> Vec<usize> {
    let top = mesh.node_set("top").unwrap();
    let nodes = mesh.nodes();
    top.iter()
        .copied()
        .filter(|&n| nodes[n][0] <= HALF_WIDTH * (1.0 + 1e-12))
        .collect()
}

/// The soil: `E = 10⁴ c`, `ν = 0.49` for `φ = 0` (nearly isochoric elastic part, as the
/// plastic flow), `ν = 0.3` otherwise.
pub(crate) fn soil(friction_angle: f64, dilatancy_angle: f64) -> Arc<dyn ConstitutivePoint> {
    let poisson = if friction_angle == 0.0 { 0.49 } else { 0.3 };
    Arc::new(
        DruckerPrager::new(DruckerPragerParameters {
            young: 1e4 * C,
            poisson,
            friction_angle,
            dilatancy_angle,
            cohesion: C,
            cone: ConeMatch::PlaneStrain,
        })
        .unwrap(),
    )
}

/// The body with its footing nodes (prescribed at 0 in both directions).
pub(crate) fn footing_body(
    m: &FootingMesh,
    law: Arc<dyn ConstitutivePoint>,
) -> (PlasticModel<2>, Vec<usize>) {
    let mesh = footing_mesh(m);
    let footing = footing_nodes(&mesh);
    let set = |name: &str| mesh.node_set(name).unwrap().to_vec();
    let mut supports = Supports::new();
    supports
        .fix(&set("left"), Component::X)
        .fix(&set("right"), Component::X)
        .fix(&set("bottom"), Component::X)
        .fix(&set("bottom"), Component::Y)
        .fix(&footing, Component::X)
        .fix(&footing, Component::Y);
    // the elastic model's material only gives loads (none: weightless soil)
    let material = Material::new(1e4 * C, 0.3, 0.0).unwrap();
    let elastic =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, material)], supports)
            .unwrap();
    (PlasticModel::new(elastic, &[(0, law)]).unwrap(), footing)
}

/// One point of the load–settlement curve.
#[derive(Clone, Debug)]
pub(crate) struct FootingStep {
    /// Settlement over half-width.
    pub(crate) settlement: f64,
    /// Mean pressure over cohesion.
    pub(crate) pressure: f64,
    /// The relative residuals of the converged Newton step.
    pub(crate) residuals: Vec<f64>,
}

/// Pushes the footing down to `settlement · b` in `steps` equal increments (halved, up to
/// `max_cuts` times along the path, when a step does not converge within
/// `newton.max_iterations` solves to `newton.tolerance`, and doubled back after), and returns
/// the converged points.
pub(crate) fn push(
    body: &mut PlasticModel<2>,
    footing: &[usize],
    settlement: f64,
    steps: usize,
    newton: &NewtonSettings,
    max_cuts: usize,
) -> Result<Vec<FootingStep>, FemError> {
    let path = push_path(body, footing, settlement, steps, newton, max_cuts);
    match path.stop {
        None => Ok(path.curve),
        Some(e) => Err(e),
    }
}

/// A footing path as far as it went.
#[derive(Debug)]
pub(crate) struct FootingPath {
    /// The converged points.
    pub(crate) curve: Vec<FootingStep>,
    /// The free displacements of the last converged point.
    pub(crate) u: Vec<f64>,
    /// The last converged increment of `u`.
    pub(crate) du: Vec<f64>,
    /// The last converged increment of the settlement over `b`.
    pub(crate) last_increment: f64,
    /// Why the path stopped short of the settlement asked (`None`: it arrived).
    pub(crate) stop: Option<FemError>,
}

/// [`push`], keeping the last converged state and the error that stopped the path.
pub(crate) fn push_path(
    body: &mut PlasticModel<2>,
    footing: &[usize],
    settlement: f64,
    steps: usize,
    newton: &NewtonSettings,
    max_cuts: usize,
) -> FootingPath {
    let mut u = vec![0.0; body.dof_count()];
    // the last two converged states, for the predictor
    let (mut u_n, mut du_n) = (u.clone(), vec![0.0; u.len()]);
    let settings = NewtonSettings {
        steps: 1,
        max_cuts: 0,
        ..*newton
    };
    let first = settlement / steps as f64;
    let (mut done, mut step, mut last, mut cuts) = (0.0, first, first, 0);
    let mut out = Vec::new();
    let stop = loop {
        if done >= settlement * (1.0 - 1e-12) {
            break None;
        }
        let target = (done + step).min(settlement);
        if let Err(e) = body.set_prescribed(footing, Component::Y, -target * HALF_WIDTH) {
            break Some(e);
        }
        if out.is_empty() {
            // first step: the elastic response to the settlement (the tangent of the
            // committed, unstrained state), not the free dofs left at rest while the
            // footing's nodes move (which strains only the cells under the footing)
            let predicted = body
                .update_tangent()
                .and_then(|()| body.free_response_into(target, &mut u));
            if let Err(e) = predicted {
                break Some(e);
            }
        } else {
            // predictor: the last converged increment, scaled to this one
            let scale = (target - done) / last;
            for ((u, u_n), du) in u.iter_mut().zip(&u_n).zip(&du_n) {
                *u = u_n + scale * du;
            }
        }
        match newton::solve(body, &mut u, done, target, &settings) {
            Ok(report) => {
                let residuals = report.steps.last().unwrap().residuals.clone();
                let pressure = match body.reaction(footing, Component::Y) {
                    Ok(r) => -r / HALF_WIDTH / C,
                    Err(e) => break Some(e),
                };
                out.push(FootingStep {
                    settlement: target,
                    pressure,
                    residuals,
                });
                for ((du, u_n), u) in du_n.iter_mut().zip(u_n.iter_mut()).zip(&u) {
                    *du = u - *u_n;
                    *u_n = *u;
                }
                last = target - done;
                done = target;
                step = (2.0 * step).min(first);
            }
            Err(FemError::NotConverged { .. }) if cuts < max_cuts => {
                cuts += 1;
                step *= 0.5;
            }
            Err(e) => break Some(e),
        }
    };
    FootingPath {
        curve: out,
        u: u_n,
        du: du_n,
        last_increment: last,
        stop,
    }
}

/// Residuals in short scientific notation, for traces and messages.
pub(crate) fn short(residuals: &[f64]) -> String {
    let r: Vec<String> = residuals.iter().map(|r| format!("{r:.1e}")).collect();
    r.join(" ")
}

/// `N_c` of Prandtl–Reissner for `φ` in degrees.
pub(crate) fn n_c(friction_angle: f64) -> f64 {
    if friction_angle == 0.0 {
        return 2.0 + std::f64::consts::PI;
    }
    let phi = friction_angle.to_radians();
    let n_q = (std::f64::consts::PI * phi.tan()).exp()
        * (std::f64::consts::FRAC_PI_4 + 0.5 * phi).tan().powi(2);
    (n_q - 1.0) / phi.tan()
}

/// Runs the footing on mesh `m` to `settlement` in 20 steps, each Newton step at most 8
/// solves to the relative residual `1e-10` (a step that needs more is halved).
fn collapse(m: &FootingMesh, friction_angle: f64, settlement: f64) -> Vec<FootingStep> {
    let (mut body, footing) = footing_body(m, soil(friction_angle, friction_angle));
    let newton = NewtonSettings {
        max_iterations: 8,
        ..NewtonSettings::default()
    };
    push(&mut body, &footing, settlement, 20, &newton, 30).unwrap()
}

/// The last pressure is on the plateau (the last two steps within 0.1 %), within `tolerance`
/// of `c N_c`, and every converged step ended superlinearly: where the residual before the
/// last solve is above 1e-8 (clear of the assembly's round-off floor, 1e-14 to 2e-11 here),
/// the last solve divides it by at least 100 (a tangent that is not the consistent one
/// converges linearly, by factors of 2–10 here).
fn check_collapse(curve: &[FootingStep], friction_angle: f64, tolerance: f64) {
    for step in curve {
        eprintln!(
            "φ = {friction_angle}: δ/b = {:.5}, q/c = {:.4}, residuals {}",
            step.settlement,
            step.pressure,
            short(&step.residuals)
        );
    }
    let n = curve.len();
    let worst = curve.iter().map(|s| s.residuals.len() - 1).max().unwrap();
    eprintln!(
        "φ = {friction_angle}: q/c = {:.4}, N_c = {:.4} ({:+.2} %), {n} steps, at most {worst} solves",
        curve[n - 1].pressure,
        n_c(friction_angle),
        100.0 * (curve[n - 1].pressure / n_c(friction_angle) - 1.0)
    );
    let (q, q_before) = (curve[n - 1].pressure, curve[n - 2].pressure);
    assert!(
        (q - q_before).abs() < 1e-3 * q,
        "not on the plateau: {q_before} → {q}"
    );
    let expected = n_c(friction_angle);
    assert!(
        (q - expected).abs() < tolerance * expected,
        "φ = {friction_angle}: q/c = {q}, N_c = {expected}"
    );
    for step in curve {
        let r = &step.residuals;
        if r.len() > 2 && r[r.len() - 2] > 1e-8 {
            assert!(
                r[r.len() - 1] <= 1e-2 * r[r.len() - 2],
                "δ/b = {}: {}",
                step.settlement,
                short(r)
            );
        }
    }
}

/// φ = 0: Prandtl's `(2 + π) c` within 3 % (measured +2.0 % on this mesh, +0.x % on the
/// finer one of `issue_40_strip_footing_fine`; the error is the P2 mesh's, shrinking with
/// the size of the cells at the footing edge).
#[test]
fn issue_40_strip_footing_prandtl_works() {
    let curve = collapse(&FootingMesh::CI, 0.0, 0.02);
    check_collapse(&curve, 0.0, 0.03);
}

/// φ = 20°, associated: Prandtl–Reissner's `N_c = 14.835` within 5 % (measured +2.9 %).
#[test]
fn issue_40_strip_footing_reissner_works() {
    let curve = collapse(&FootingMesh::CI, 20.0, 0.05);
    check_collapse(&curve, 20.0, 0.05);
}

/// `reaction` against a closed form: a linear-elastic block `2 × 1` (P2) confined laterally
/// (`u_x = 0` on both sides, `u_y = 0` at the base), its top pushed down by `d`. The state is
/// uniform, `ε_yy = −d`, `σ_yy = (λ + 2G) ε_yy`, `σ_xx = λ ε_yy`, so the top carries
/// `R_y = 2 σ_yy` and the left side `R_x = −σ_xx` (the support pushes inwards). Tolerance
/// 1e-12 relative: the solve and the sums are exact up to round-off.
#[test]
fn issue_40_reaction_works() {
    use fem_core::plastic::LinearElasticPoint;
    let spec = RectangleSpec {
        kind: ElementKind::Tri6,
        ..RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2)
    };
    let mesh = rectangle(&spec).unwrap();
    let set = |name: &str| mesh.node_set(name).unwrap().to_vec();
    let (top, left, right, bottom) = (set("top"), set("left"), set("right"), set("bottom"));
    let mut supports = Supports::new();
    supports
        .fix(&left, Component::X)
        .fix(&right, Component::X)
        .fix(&bottom, Component::Y)
        .fix(&top, Component::Y);
    let (young, poisson) = (100.0, 0.3);
    let material = Material::new(young, poisson, 0.0).unwrap();
    let elastic =
        LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, material)], supports)
            .unwrap();
    let point: Arc<dyn ConstitutivePoint> =
        Arc::new(LinearElasticPoint::new(young, poisson).unwrap());
    let mut body = PlasticModel::new(elastic, &[(0, point)]).unwrap();
    let d = 1e-3;
    body.set_prescribed(&top, Component::Y, -d).unwrap();
    let mut u = vec![0.0; body.dof_count()];
    newton::solve(&mut body, &mut u, 0.0, 1.0, &NewtonSettings::default()).unwrap();
    let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    let g = young / (2.0 * (1.0 + poisson));
    let (sigma_yy, sigma_xx) = (-(lambda + 2.0 * g) * d, -lambda * d);
    let r_y = body.reaction(&top, Component::Y).unwrap();
    let r_x = body.reaction(&left, Component::X).unwrap();
    assert!(
        (r_y - 2.0 * sigma_yy).abs() < 1e-12 * sigma_yy.abs(),
        "{r_y}"
    );
    assert!((r_x + sigma_xx).abs() < 1e-12 * sigma_xx.abs(), "{r_x}");
    // a node listed twice counts once
    let twice: Vec<usize> = top.iter().chain(&top).copied().collect();
    assert_eq!(body.reaction(&twice, Component::Y).unwrap(), r_y);
}

/// Displacement control refuses a free dof and an unknown node, by name.
#[test]
fn issue_40_footing_loading_captures_errors() {
    let (mut body, footing) = footing_body(&FootingMesh::CI, soil(0.0, 0.0));
    let free = body.node_count() / 2;
    let err = body
        .set_prescribed(&[free], Component::Y, -0.1)
        .unwrap_err();
    assert!(matches!(err, FemError::Unsupported { .. }), "{err}");
    let beyond = body.node_count();
    assert!(matches!(
        body.set_prescribed(&[beyond], Component::Y, -0.1),
        Err(FemError::UnknownNode { .. })
    ));
    assert!(
        body.set_prescribed(&footing, Component::Y, f64::NAN)
            .is_err()
    );
    assert!(matches!(
        body.reaction(&[beyond], Component::Y),
        Err(FemError::UnknownNode { .. })
    ));
    // at rest, nothing pushes
    assert_eq!(body.reaction(&footing, Component::Y).unwrap(), 0.0);
}

/// The finer run recorded in `docs/validation.md` (20 + 40 cells across, 28 down, graded
/// 60 : 1; about 10 s each in a debug build): the same checks.
#[test]
#[ignore]
fn issue_40_strip_footing_fine() {
    let fine = FootingMesh {
        under: 20,
        beside: 40,
        down: 28,
        ratio: 60.0,
        ..FootingMesh::CI
    };
    for (phi, settlement, tolerance) in [(0.0, 0.02, 0.03), (20.0, 0.05, 0.05)] {
        let curve = collapse(&fine, phi, settlement);
        let last = curve.last().unwrap();
        let worst = curve.iter().map(|s| s.residuals.len() - 1).max().unwrap();
        eprintln!(
            "φ = {phi}: q/c = {:.4}, N_c = {:.4} ({:+.2} %), {} steps, at most {worst} solves",
            last.pressure,
            n_c(phi),
            100.0 * (last.pressure / n_c(phi) - 1.0),
            curve.len()
        );
        check_collapse(&curve, phi, tolerance);
    }
}
