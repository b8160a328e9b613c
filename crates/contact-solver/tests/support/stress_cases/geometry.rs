//! Poisson's ratio up to 0.499 and geometric edge cases.

use super::*;

// ---------------------------------------------------------------------------------------------
// Poisson's ratio up to 0.499 with P2

/// A P2 block `[0, 2] × [0, 1]` (E = 200), left face `u_x = 0`, top `u_y = −δ`, frictionless
/// on a rigid LINE (gap 0): uniaxial stress in plane strain, `σ = E δ/(h (1 − ν²))` — in the P2
/// space for every ν, so any locking or conditioning blow-up shows.
pub(super) fn pressed_p2(nu: f64, tally: &mut Tally) -> Result<String, Fail> {
    const E: f64 = 200.0;
    const DELTA: f64 = 0.01;
    let mesh = rect([0.0, 2.0], [0.0, 1.0], 8, 4, ElementKind::Tri6);
    let top = set(&mesh, "top");
    let bottom = set(&mesh, "bottom");
    let left = set(&mesh, "left");
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, -DELTA)?;
    supports.fix(&left, Component::X);
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(E, nu, 0.0)?)],
        supports,
    )?;
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0])?;
    let zone = ContactZone::rigid("base", bottom, ground, Signorini, 0.1);
    let mut sim = ContactSimulation::new(model, vec![zone], settings())?;
    let res = sim.step(1.0, 1.0)?;
    tally.add(&res, TOL)?;
    let exact = 2.0 * E * DELTA / (1.0 - nu * nu);
    let (total, _) = totals(&res);
    let err = (total - exact) / exact;
    // the exact solution is in the space: the solve's tolerance and K's round-off (its
    // condition grows like 1/(1 − 2ν))
    ensure!(
        err.abs() <= 1e-8,
        "ν = {nu}: total {total:e} vs E'δ/h × 2 = {exact:e} ({err:+.1e})"
    );
    check_coulomb(&res, |_| 0.0, 1e-9 * exact, 1e-9 * DELTA)?;
    // the left face slides freely: the lateral expansion ν/(1 − ν) δ at x = 2
    let u = sim.nodal_displacements();
    let right = set(sim.structure().mesh(), "right");
    let expansion = 2.0 * nu / (1.0 - nu) * DELTA;
    let worst = right
        .iter()
        .map(|&n| (u[n][0] - expansion).abs())
        .fold(0.0, f64::max);
    ensure!(
        worst <= 1e-8 * DELTA,
        "ν = {nu}: lateral expansion off by {worst:e}"
    );
    Ok(format!(
        "Σr_n/(2E'δ/h) − 1 = {err:+.1e}; u_x(right) error {:.0e} δ",
        worst / DELTA
    ))
}

/// The ν cases.
pub fn poisson_cases() -> Vec<Case> {
    let mut v = Vec::new();
    for nu in [0.3, 0.45, 0.49, 0.499] {
        v.push(Case::new(
            "poisson",
            format!("P2 block pressed, plane strain, ν = {nu}"),
            no_error,
            move |tally| pressed_p2(nu, tally),
        ));
    }
    let hertz = [
        (Idealization::PlaneStrain, 0.3),
        (Idealization::PlaneStrain, 0.49),
        (Idealization::PlaneStrain, 0.499),
        (Idealization::Axisymmetric, 0.3),
        (Idealization::Axisymmetric, 0.499),
    ];
    for (idealization, nu) in hertz {
        v.push(Case::new(
            "poisson",
            format!("Hertz P2 m = 8, {idealization:?}, ν = {nu}"),
            no_error,
            move |tally| {
                let mut scene = HertzScene::new(idealization, ElementKind::Tri6, 8);
                scene.poisson = nu;
                let mut sim = scene.simulation(settings());
                let res = sim.step(1.0, 1.0)?;
                tally.add(&res, TOL)?;
                let m = scene.measure(&sim, &res);
                let (n, _) = totals(&res);
                check_coulomb(&res, |_| 0.0, 1e-9 * n, 1e-9 * scene.delta)?;
                // the axial resultant (the radial one goes into the hoop in axisymmetry); the
                // round-off of R = K u − f grows with the condition of K, ∝ 1/(1 − 2ν)
                let sum = equilibrium_sum(&sim, &res, 1.0)?;
                ensure!(
                    sum[1].abs() <= 1e-11 * n / (1.0 - 2.0 * nu),
                    "equilibrium defect {:e} of Σr_n = {n:e}",
                    sum[1]
                );
                // Hertz with E* = E/(1 − ν²) holds for every ν; at ν = 0.3 the m = 8 errors are
                // −0.5 % (a) and −1.1 % / −2.7 % (p0, plane strain / axisymmetric), see
                // tests/integration/hertz.rs. Locking would stiffen the body and shrink a.
                ensure!(m.a_error().abs() <= 2e-2, "a {:.5} vs Hertz {:.5}", m.a_fe, m.a_hertz);
                ensure!(m.p0_error().abs() <= 4e-2, "p0 {:.5} vs Hertz {:.5}", m.p0_fe, m.p0_hertz);
                Ok(format!(
                    "a {:+.2} %, p0 {:+.2} % vs Hertz (E* = E/(1 − ν²)); P = {:.4e}; equilibrium {:.0e}",
                    100.0 * m.a_error(),
                    100.0 * m.p0_error(),
                    m.p_total,
                    sum[1] / n
                ))
            },
        ));
    }
    v
}

// ---------------------------------------------------------------------------------------------
// Geometry: on the obstacle, beyond the alert distance, on an ARC's end

/// A block `[x0, x0 + 2] × [y0, y0 + 1]` (E = 1000, ν, P1, 8 × 4) with its top prescribed
/// `(0, 0)` and its bottom facing the rigid LINE `y = 0` (Signorini).
pub(super) fn resting_block(
    x0: f64,
    y0: f64,
    nu: f64,
    top_x_free: bool,
) -> Result<(LinearElasticModel, Vec<usize>, Vec<usize>), Fail> {
    let mesh = rect([x0, x0 + 2.0], [y0, y0 + 1.0], 8, 4, ElementKind::Tri3);
    let top = set(&mesh, "top");
    let bottom = set(&mesh, "bottom");
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0)?;
    if top_x_free {
        supports.fix(&set(&mesh, "left"), Component::X);
    } else {
        supports.prescribe(&top, Component::X, 0.0)?;
    }
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(BLOCK_E, nu, 0.0)?)],
        supports,
    )?;
    Ok((model, top, bottom))
}

pub(super) fn ground() -> RigidLine {
    RigidLine::new([-3.0, 0.0], [5.0, 0.0]).unwrap()
}

/// The geometry cases.
pub fn geometry_cases() -> Vec<Case> {
    let mut v = Vec::new();
    v.push(Case::new(
        "geometry",
        "nodes on the LINE (gap 0), no load; then pulled off; then pressed and released",
        no_error,
        |tally| {
            let (model, top, _) = resting_block(0.0, 0.0, 0.0, false)?;
            let zone = ContactZone::rigid(
                "base",
                set(model.mesh(), "bottom"),
                ground(),
                Coulomb::new(0.3)?,
                0.1,
            );
            let mut sim = ContactSimulation::new(model, vec![zone], settings())?;
            // nothing at all: r = 0, gap = 0, every candidate active and open
            let res = sim.step(1.0, 1.0)?;
            tally.add(&res, TOL)?;
            ensure!(
                res.report.active_contacts == res.contacts.len(),
                "not all active at gap 0"
            );
            for c in &res.contacts {
                ensure!(
                    c.r == LocalVec2::zeros() && c.gap == 0.0 && c.status == InterfaceStatus::Open,
                    "unloaded: {c:?}"
                );
            }
            // pulled off by 0.01 (ν = 0: a rigid lift)
            sim.structure_mut()
                .set_prescribed(&top, Component::Y, 0.01)?;
            let res = sim.step(2.0, 1.0)?;
            tally.add(&res, TOL)?;
            for c in &res.contacts {
                ensure!(
                    c.r == LocalVec2::zeros() && (c.gap - 0.01).abs() <= 1e-14,
                    "lifted: {c:?}"
                );
            }
            // pressed by 0.01, then released to exactly 0
            sim.structure_mut()
                .set_prescribed(&top, Component::Y, -0.01)?;
            let res = sim.step(3.0, 1.0)?;
            tally.add(&res, TOL)?;
            let (n, _) = totals(&res);
            ensure!(
                (n - 2.0 * BLOCK_E * 0.01).abs() <= 1e-9 * n,
                "pressed: N = {n:e}"
            );
            check_coulomb(&res, |_| 0.3, 1e-9 * n, 1e-11)?;
            sim.structure_mut()
                .set_prescribed(&top, Component::Y, 0.0)?;
            let res = sim.step(4.0, 1.0)?;
            tally.add(&res, TOL)?;
            for c in &res.contacts {
                ensure!(
                    c.r.n.abs() <= 1e-12 * n && c.r.t[0].abs() <= 1e-12 * n && c.gap.abs() <= 1e-14,
                    "released: {c:?}"
                );
            }
            Ok(format!(
                "unloaded r = 0 exactly; pressed N/(2Eδ) − 1 = {:+.0e}",
                n / (2.0 * BLOCK_E * 0.01) - 1.0
            ))
        },
    ));
    v.push(Case::new(
        "geometry",
        "gap = Δx (1 + 1e-9) just beyond the alert distance Δx = 1e-3: unloaded, then pressed",
        no_error,
        |tally| {
            let alert = 1e-3;
            let g = alert * (1.0 + 1e-9);
            let (model, top, bottom) = resting_block(0.0, g, 0.0, false)?;
            let zone = ContactZone::rigid("base", bottom, ground(), Signorini, alert);
            let mut sim = ContactSimulation::new(model, vec![zone], settings())?;
            let res = sim.step(1.0, 1.0)?;
            tally.add(&res, TOL)?;
            ensure!(
                res.report.active_contacts == 0,
                "{} active beyond Δx",
                res.report.active_contacts
            );
            ensure!(
                sim.counters().flexibility_columns == 0,
                "F* built for nothing"
            );
            for c in &res.contacts {
                ensure!(
                    c.status == InterfaceStatus::Inactive
                        && c.r == LocalVec2::zeros()
                        && c.gap == g,
                    "{c:?}"
                );
            }
            // one step from open to pressed by 0.01 after closing
            sim.structure_mut()
                .set_prescribed(&top, Component::Y, -(g + 0.01))?;
            let res = sim.step(2.0, 1.0)?;
            tally.add(&res, TOL)?;
            let (n, _) = totals(&res);
            let exact = 2.0 * BLOCK_E * 0.01;
            ensure!((n - exact).abs() <= 1e-8 * exact, "N = {n:e} vs {exact:e}");
            check_coulomb(&res, |_| 0.0, 1e-9 * n, 1e-11)?;
            Ok(format!(
                "inactive while open; pressed N/(2Eδ) − 1 = {:+.0e}",
                n / exact - 1.0
            ))
        },
    ));
    v.push(Case::new(
        "geometry",
        "gap = Δx = 1e-3 exactly (active: the test is ≤), unloaded",
        no_error,
        |tally| {
            let alert = 1e-3;
            let (model, _, bottom) = resting_block(0.0, alert, 0.0, false)?;
            let zone = ContactZone::rigid("base", bottom, ground(), Signorini, alert);
            let mut sim = ContactSimulation::new(model, vec![zone], settings())?;
            let res = sim.step(1.0, 1.0)?;
            tally.add(&res, TOL)?;
            ensure!(
                res.report.active_contacts == res.contacts.len(),
                "{} active at gap = Δx",
                res.report.active_contacts
            );
            for c in &res.contacts {
                ensure!(
                    c.status == InterfaceStatus::Open
                        && c.r == LocalVec2::zeros()
                        && c.gap == alert,
                    "{c:?}"
                );
            }
            Ok(format!(
                "{} active, open, r = 0",
                res.report.active_contacts
            ))
        },
    ));
    v.push(Case::new(
        "geometry",
        "wall at Δx (1 + 1e-9) beyond the alert distance, reached by the Poisson expansion (re-added)",
        no_error,
        |tally| {
            // block [0,2]×[0,1], ν = 0.3, left u_x = 0, top u_y = −δ (u_x free), frictionless base
            // and a frictionless wall x = 2 + g: the free response (a rigid translation) keeps
            // the wall inactive; the contact solution expands into it. Final state uniform:
            // ε_xx = g/2, ε_yy = −δ.
            let (alert, delta, nu) = (1e-3, 0.01, 0.3);
            let g = alert * (1.0 + 1e-9);
            let (model, top, bottom) = resting_block(0.0, 0.0, nu, true)?;
            let right = set(model.mesh(), "right");
            let wall = RigidLine::new([2.0 + g, -1.0], [2.0 + g, 2.0])?; // going up: contactor at −x
            let zones = vec![
                ContactZone::rigid("base", bottom, ground(), Signorini, alert),
                ContactZone::rigid("wall", right.clone(), wall, Signorini, alert),
            ];
            let mut sim = ContactSimulation::new(model, zones, settings())?;
            sim.structure_mut().set_prescribed(&top, Component::Y, -delta)?;
            let res = sim.step(1.0, 1.0)?;
            tally.add(&res, TOL)?;
            ensure!(res.report.detection_passes >= 2, "the wall was active from the start");
            let (lambda, mu2) = (BLOCK_E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), BLOCK_E / (1.0 + nu));
            let (exx, eyy) = (g / 2.0, -delta);
            let sxx = (lambda + mu2) * exx + lambda * eyy;
            let syy = lambda * exx + (lambda + mu2) * eyy;
            let base: f64 = res.contacts.iter().filter(|c| c.zone == 0).map(|c| c.r.n).sum();
            let side: f64 = res.contacts.iter().filter(|c| c.zone == 1).map(|c| c.r.n).sum();
            let scale = -2.0 * syy;
            check_coulomb(&res, |_| 0.0, 1e-9 * scale, 1e-9 * delta)?;
            // uniform strain: exact in P1
            ensure!((base + 2.0 * syy).abs() <= 1e-8 * scale, "base {base:e} vs −2σ_yy {:e}", -2.0 * syy);
            ensure!((side + sxx).abs() <= 1e-8 * scale, "wall {side:e} vs −σ_xx {:e}", -sxx);
            Ok(format!(
                "{} passes; base/(−2σ_yy) − 1 = {:+.0e}, wall/(−σ_xx) − 1 = {:+.0e}",
                res.report.detection_passes,
                base / (-2.0 * syy) - 1.0,
                side / (-sxx) - 1.0
            ))
        },
    ));
    // ARC endpoint cases: block [−1, 1] × [0, 1] over a rigid cylinder R = 10 centred at (0, −10)
    v.push(Case::new(
        "geometry",
        "ARC starting exactly at a node on it (gap 0; start π/2, sweep π/2: x ≤ 0), pressed",
        no_error,
        |tally| arc_case(FRAC_PI_2, FRAC_PI_2, ArcSpan::Left, 0.02, tally),
    ));
    v.push(Case::new(
        "geometry",
        "ARC ending exactly at a node on it (gap 0; start −0.3 wraps to 2π − 0.3, sweep π/2 + 0.3: x ≥ 0), pressed",
        no_error,
        |tally| arc_case(-0.3, FRAC_PI_2 + 0.3, ArcSpan::Right, 0.02, tally),
    ));
    v.push(Case::new(
        "geometry",
        "ARC whose ends are exactly under the nodes x = ±0.5 (sweep = π − 2θ), pressed",
        no_error,
        |tally| {
            let theta = 10f64.atan2(0.5);
            arc_case(theta, PI - 2.0 * theta, ArcSpan::Within(0.5), 0.05, tally)
        },
    ));
    v
}

/// Which bottom nodes an ARC of [`arc_case`] spans.
#[derive(Clone, Copy, Debug)]
pub(super) enum ArcSpan {
    /// `x ≤ 0`, the node `x = 0` at its start.
    Left,
    /// `x ≥ 0`, the node `x = 0` at its end.
    Right,
    /// `|x| ≤ x_end`, its ends under the nodes `±x_end`.
    Within(f64),
}

/// A block `[−1, 1] × [0, 1]` (E = 1000, ν = 0.3, P1, 8 × 4), top prescribed `(0, −δ)`, over
/// the rigid ARC (Outside, Signorini) of radius 10 centred at `(0, −10)` from `start` over
/// `sweep`, which spans `span`: exactly those bottom nodes are candidates, with the radial
/// normal and gap; after the step the end nodes carry load.
pub(super) fn arc_case(
    start: f64,
    sweep: f64,
    span: ArcSpan,
    delta: f64,
    tally: &mut Tally,
) -> Result<String, Fail> {
    const R: f64 = 10.0;
    let mesh = rect([-1.0, 1.0], [0.0, 1.0], 8, 4, ElementKind::Tri3);
    let top = set(&mesh, "top");
    let bottom = set(&mesh, "bottom");
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, -delta)?;
    supports.prescribe(&top, Component::X, 0.0)?;
    let xs: Vec<f64> = bottom.iter().map(|&n| mesh.nodes()[n][0]).collect();
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(BLOCK_E, 0.3, 0.0)?)],
        supports,
    )?;
    let arc = RigidArc::new([0.0, -R], R, start, sweep, ArcSide::Outside)?;
    let zone = ContactZone::rigid("arc", bottom.clone(), arc, Signorini, 0.1);
    let mut sim = ContactSimulation::new(model, vec![zone], settings())?;
    let on_arc = |x: f64| match span {
        ArcSpan::Left => x <= 0.0,
        ArcSpan::Right => x >= 0.0,
        ArcSpan::Within(x_end) => x.abs() <= x_end,
    };
    let expected: Vec<usize> = bottom
        .iter()
        .zip(&xs)
        .filter(|(_, x)| on_arc(**x))
        .map(|(n, _)| *n)
        .collect();
    let found: Vec<usize> = sim.candidates().iter().map(|c| c.node).collect();
    ensure!(
        found == expected,
        "candidates {found:?}, expected {expected:?}"
    );
    let ends: Vec<usize> = match span {
        ArcSpan::Left => vec![*expected.last().unwrap()],
        ArcSpan::Right => vec![expected[0]],
        ArcSpan::Within(_) => vec![expected[0], *expected.last().unwrap()],
    };
    for c in sim.candidates() {
        let x = sim.structure().node_position(c.node);
        let d = [x[0], x[1] + R];
        let l = d[0].hypot(d[1]);
        ensure!(
            (c.normal()[0] - d[0] / l).abs() <= 1e-15 && (c.normal()[1] - d[1] / l).abs() <= 1e-15,
            "node {}: normal {:?}",
            c.node,
            c.normal()
        );
        ensure!(
            (c.gap0 - (l - R)).abs() <= 1e-14,
            "node {}: gap0 {:e}",
            c.node,
            c.gap0
        );
    }
    let res = sim.step(1.0, 1.0)?;
    tally.add(&res, TOL)?;
    let (n, _) = totals(&res);
    check_coulomb(&res, |_| 0.0, 1e-9 * n, 1e-9 * delta)?;
    let sum = equilibrium_sum(&sim, &res, 1.0)?;
    ensure!(
        sum[0].abs().max(sum[1].abs()) <= 1e-9 * n,
        "equilibrium defect {sum:?} (N = {n:e})"
    );
    let end_forces: Vec<f64> = res
        .contacts
        .iter()
        .filter(|c| ends.contains(&c.node))
        .map(|c| c.r.n)
        .collect();
    ensure!(
        end_forces.iter().all(|&f| f > 0.0),
        "the end nodes carry {end_forces:?}"
    );
    Ok(format!(
        "{} candidates, end node(s) r_n/N = {:?}",
        expected.len(),
        end_forces
            .iter()
            .map(|f| format!("{:.3}", f / n))
            .collect::<Vec<_>>()
    ))
}
