//! Friction, ρ and load steps.

use super::*;

// ---------------------------------------------------------------------------------------------
// Friction and ρ

pub(super) const BLOCK_E: f64 = 1000.0;

/// A block `[0, 2] × [0, 1]` (E = 1000, ν = 0, P1, 8 × 4) on a rigid LINE (gap 0), Coulomb μ;
/// its top is prescribed: pressed by `δ = 0.01`, then pushed sideways.
pub(super) fn friction_block(
    mu: f64,
    settings: SimulationSettings,
) -> Result<(ContactSimulation<LinearElasticModel, Coulomb>, Vec<usize>), Fail> {
    let mesh = rect([0.0, 2.0], [0.0, 1.0], 8, 4, ElementKind::Tri3);
    let top = set(&mesh, "top");
    let bottom = set(&mesh, "bottom");
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0)?;
    supports.prescribe(&top, Component::X, 0.0)?;
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(BLOCK_E, 0.0, 0.0)?)],
        supports,
    )?;
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0])?;
    let zone = ContactZone::rigid("base", bottom, ground, Coulomb::new(mu)?, 0.1);
    Ok((ContactSimulation::new(model, vec![zone], settings)?, top))
}

/// The all-stick reference of [`friction_block`] after the push: the bottom fixed, the top at
/// `(push, −δ)`. Returns the bottom reactions `(r_n, r_t)` per bottom node.
pub(super) fn bonded_block(push: f64) -> Result<Vec<(usize, [f64; 2])>, Fail> {
    let mesh = rect([0.0, 2.0], [0.0, 1.0], 8, 4, ElementKind::Tri3);
    let top = set(&mesh, "top");
    let bottom = set(&mesh, "bottom");
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, -0.01)?;
    supports.prescribe(&top, Component::X, push)?;
    supports
        .fix(&bottom, Component::X)
        .fix(&bottom, Component::Y);
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(BLOCK_E, 0.0, 0.0)?)],
        supports,
    )?;
    let u = model.solve(1.0)?;
    let reactions = model.reactions(&u, 1.0)?;
    Ok(bottom
        .iter()
        .map(|&n| {
            let get = |c: Component| {
                reactions
                    .iter()
                    .find(|((m, d), _)| *m == n && *d == c)
                    .map(|(_, r)| *r)
                    .unwrap_or(0.0)
            };
            // on the base, n = +y and t = (n_y, −n_x) = +x
            (n, [get(Component::Y), get(Component::X)])
        })
        .collect())
}

/// The sideways push of the top that makes the friction block slide for μ ≤ 1.
pub(super) const PUSH: f64 = 0.05;

/// Presses the friction block (`δ = 0.01`, `t = 1`), then pushes its top to each of `pushes`
/// (`t = 2, 3, …`). Checks Signorini–Coulomb and the equilibrium of every step.
pub(super) fn press_and_push(
    mu: f64,
    settings: SimulationSettings,
    pushes: &[f64],
    tally: &mut Tally,
) -> Result<Vec<StepResult>, Fail> {
    let (mut sim, top) = friction_block(mu, settings)?;
    sim.structure_mut()
        .set_prescribed(&top, Component::Y, -0.01)?;
    let mut out = Vec::new();
    for k in 0..=pushes.len() {
        if k > 0 {
            sim.structure_mut()
                .set_prescribed(&top, Component::X, pushes[k - 1])?;
        }
        let res = sim.step(1.0 + k as f64, 1.0)?;
        tally.add(&res, settings.solver.tol)?;
        let (n, _) = totals(&res);
        // reactions to 1e-9 of N, gaps and slips to 1e-9 of δ: the solve's relative
        // tolerance 1e-10 on r and x, with room for the conditioning of W
        check_coulomb(&res, |_| mu, 1e-9 * n, 1e-9 * 0.01)?;
        let sum = equilibrium_sum(&sim, &res, 1.0)?;
        ensure!(
            sum[0].abs().max(sum[1].abs()) <= 1e-9 * n,
            "step {}: equilibrium defect {sum:?} (N = {n:e})",
            k + 1
        );
        out.push(res);
    }
    Ok(out)
}

/// The μ cases.
pub fn friction_cases() -> Vec<Case> {
    let max = SimulationSettings::default().solver.max_iterations;
    let ok = no_error as Allowed;
    let mut runs: Vec<(f64, f64, usize, Allowed, String)> = Vec::new();
    // a small push: stick wherever μ r_n carries it
    for mu in [0.0, 1e-8, 0.2, 1.0, 10.0] {
        runs.push((mu, 1e-4, max, ok, format!("μ = {mu:e}")));
    }
    for mu in [0.0, 1e-8, 0.2, 1.0] {
        runs.push((mu, PUSH, max, ok, format!("μ = {mu:e}")));
    }
    // μ = 10 and the large push: the block tips, the left third lifts off, two nodes slip and
    // four stick; the sweeps need ~54 000 iterations, so the default cap ends in NotConverged
    let label = "μ = 1e1 (lift-off, slip and stick)".to_string();
    runs.push((10.0, PUSH, max, is_not_converged, label));
    runs.push((
        10.0,
        PUSH,
        100_000,
        ok,
        "  same, max_iterations = 100 000".into(),
    ));
    let mut v = Vec::new();
    for (mu, push, max_iterations, allowed, label) in runs {
        v.push(Case::new(
            "friction",
            format!("block pressed (δ = 0.01) then pushed by {push:e}, {label}"),
            allowed,
            move |tally| {
                let mut s = settings();
                s.solver.max_iterations = max_iterations;
                let steps = press_and_push(mu, s, &[push], tally)?;
                let pushed = &steps[1];
                let (n, t) = totals(pushed);
                // the all-stick solution (bottom fixed) is the answer whenever it lies in
                // the cone at every node
                let bonded = bonded_block(push)?;
                let (n_b, t_b) = bonded
                    .iter()
                    .fold((0.0, 0.0), |a, (_, r)| (a.0 + r[0], a.1 + r[1]));
                let sticks = bonded.iter().all(|(_, r)| r[1].abs() <= mu * r[0]);
                let compressed = pushed.contacts.iter().filter(|c| c.r.n > 1e-9 * n);
                if sticks {
                    let r_max = bonded
                        .iter()
                        .map(|(_, r)| r[0].abs().max(r[1].abs()))
                        .fold(0.0, f64::max);
                    for (c, (node, r)) in pushed.contacts.iter().zip(&bonded) {
                        ensure!(c.node == *node, "node order");
                        // two solves of the same problem: the solver's tolerance (1e-10),
                        // conditioning aside
                        ensure!(
                            (c.r.n - r[0]).abs().max((c.r.t[0] - r[1]).abs()) <= 1e-8 * r_max,
                            "node {}: r {:?} but the all-stick solution is {r:?}",
                            c.node,
                            c.r
                        );
                    }
                    for c in compressed {
                        ensure!(
                            c.status == InterfaceStatus::Stick && c.slip_increment.abs() <= 1e-11,
                            "node {} is {:?} (slip {:e}), expected stick",
                            c.node,
                            c.status,
                            c.slip_increment
                        );
                    }
                    Ok(format!(
                        "stick: T/N = {:.4}, all-stick T/N = {:.4}",
                        t / n,
                        t_b / n_b
                    ))
                } else if mu * n_b < t_b.abs() {
                    // full slip: T = −μ N, to the solver's tolerance relative to ‖r‖ (1e-9 N)
                    ensure!(
                        (t + mu * n).abs() <= 1e-9 * n,
                        "sliding: T {t:e} vs −μN {:e} (difference {:e})",
                        -mu * n,
                        t + mu * n
                    );
                    for c in compressed {
                        ensure!(
                            mu == 0.0 || c.status == InterfaceStatus::Slip,
                            "node {} is {:?}, expected slip",
                            c.node,
                            c.status
                        );
                        ensure!(
                            c.slip_increment > 0.0,
                            "node {} slip {:e}",
                            c.node,
                            c.slip_increment
                        );
                    }
                    Ok(format!("slip: (T + μN)/N = {:+.1e}", (t + mu * n) / n))
                } else {
                    Ok(format!("partial slip: T/(μN) = {:.4}", t / (mu * n)))
                }
            },
        ));
    }
    v
}

/// The ρ cases: μ = 0.3, press, push 1e-4 (stick), push 0.05 (slip); every reaction against
/// Gauss–Seidel with `rho_scale = 1`.
pub fn rho_cases() -> Vec<Case> {
    let mut v = Vec::new();
    let runs = [
        (
            Algorithm::GaussSeidel,
            vec![1e-3, 1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3],
        ),
        (Algorithm::Uzawa, vec![1e-3, 1.0, 1e3]),
    ];
    for (algorithm, scales) in runs {
        for scale in scales {
            v.push(Case::new(
                "rho",
                format!("block μ = 0.3 pressed, stuck, slid; {algorithm:?}, rho_scale = {scale:e}"),
                no_error,
                move |tally| {
                    let mut s = settings();
                    s.solver.algorithm = algorithm;
                    s.solver.tuning.rho_scale = scale;
                    let steps = press_and_push(0.3, s, &[1e-4, PUSH], tally)?;
                    let mut reference_tally = Tally::default();
                    let reference =
                        press_and_push(0.3, settings(), &[1e-4, PUSH], &mut reference_tally)?;
                    let mut worst = 0.0_f64;
                    for (a, b) in steps.iter().zip(&reference) {
                        let r_max = max_abs_r(b);
                        for (ca, cb) in a.contacts.iter().zip(&b.contacts) {
                            let d = (ca.r.n - cb.r.n).abs().max((ca.r.t[0] - cb.r.t[0]).abs());
                            worst = worst.max(d / r_max);
                        }
                    }
                    // two solves to a relative residual of 1e-10 each, conditioning aside
                    ensure!(
                        worst <= 1e-8,
                        "reactions differ from rho_scale = 1 by {worst:e} of the largest"
                    );
                    Ok(format!("max |r − r_ref|/max|r_ref| = {worst:.0e}"))
                },
            ));
        }
    }
    v
}

// ---------------------------------------------------------------------------------------------
// Load steps

/// A block `[0, 2] × [0, 1]` (E = 1000, ν = 0.3, P1) hanging from its fixed top, its bottom on
/// a rigid LINE (gap 0, Coulomb μ = 0.3), under a body force `(0.2, −1)` scaled by the load
/// factor. Proportional loading from zero: the solution is homogeneous of degree 1 in the
/// load, `r(λ) = λ r(1)`, whatever the steps.
pub(super) fn hanging_block() -> Result<ContactSimulation<LinearElasticModel, Coulomb>, Fail> {
    let mesh = rect([0.0, 2.0], [0.0, 1.0], 8, 4, ElementKind::Tri3);
    let top = set(&mesh, "top");
    let bottom = set(&mesh, "bottom");
    let mut supports = Supports::new();
    supports.fix(&top, Component::X).fix(&top, Component::Y);
    let mut model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(BLOCK_E, 0.3, 0.0)?)],
        supports,
    )?;
    model.add_body_force(|_| [0.2, -1.0])?;
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0])?;
    let zone = ContactZone::rigid("base", bottom, ground, Coulomb::new(0.3)?, 0.1);
    Ok(ContactSimulation::new(model, vec![zone], settings())?)
}

/// Steps the hanging block through the load factors `path`; returns `r(λ)/λ` of every step.
pub(super) fn hang(path: &[f64], tally: &mut Tally) -> Result<Vec<Vec<[f64; 2]>>, Fail> {
    let mut sim = hanging_block()?;
    let mut out = Vec::new();
    for (k, &lambda) in path.iter().enumerate() {
        let res = sim.step(k as f64 + 1.0, lambda)?;
        tally.add(&res, TOL)?;
        let (n, _) = totals(&res);
        ensure!(n > 0.0, "λ = {lambda:e}: no contact force");
        // scale-free tolerances: relative to this step's N and to its displacements (~λ/E)
        check_coulomb(&res, |_| 0.3, 1e-9 * n, 1e-9 * lambda / BLOCK_E)?;
        // external load: the body force over the area 2
        let sum = equilibrium_sum(&sim, &res, lambda)?;
        let defect = [sum[0] + 0.4 * lambda, sum[1] - 2.0 * lambda];
        ensure!(
            defect[0].abs().max(defect[1].abs()) <= 1e-9 * n,
            "λ = {lambda:e}: equilibrium defect {defect:?} (N = {n:e})"
        );
        out.push(
            res.contacts
                .iter()
                .map(|c| [c.r.n / lambda, c.r.t[0] / lambda])
                .collect(),
        );
    }
    Ok(out)
}

/// The load-step cases.
pub fn load_step_cases() -> Vec<Case> {
    let paths: Vec<(&str, Vec<f64>)> = vec![
        ("whole load in one step", vec![1.0]),
        (
            "1e-9 of the load, then the rest in one step",
            vec![1e-9, 1.0],
        ),
        (
            "10 steps of 1e-9, then the rest",
            (1..=10).map(|k| k as f64 * 1e-9).chain([1.0]).collect(),
        ),
        (
            "geometric 1e-9, 1e-8, …, 1 (10 steps)",
            (0..=9).map(|k| 10f64.powi(k - 9)).collect(),
        ),
        ("1 − 1e-9, then 1", vec![1.0 - 1e-9, 1.0]),
    ];
    paths
        .into_iter()
        .map(|(name, path)| {
            Case::new(
                "load_steps",
                format!("hanging block, μ = 0.3: {name}"),
                no_error,
                move |tally| {
                    let mut reference_tally = Tally::default();
                    let reference = hang(&[1.0], &mut reference_tally)?.remove(0);
                    let r_max = reference
                        .iter()
                        .map(|r| r[0].abs().max(r[1].abs()))
                        .fold(0.0, f64::max);
                    let mut worst = 0.0_f64;
                    for (k, scaled) in hang(&path, tally)?.iter().enumerate() {
                        for (a, b) in scaled.iter().zip(&reference) {
                            let d = (a[0] - b[0]).abs().max((a[1] - b[1]).abs()) / r_max;
                            worst = worst.max(d);
                            // homogeneity, to the solver's tolerance (two solves at 1e-10)
                            ensure!(
                                d <= 1e-8,
                                "step {} (λ = {:e}): r/λ {a:?} vs r(1) {b:?}",
                                k + 1,
                                path[k]
                            );
                        }
                    }
                    let (n, t) = reference
                        .iter()
                        .fold((0.0, 0.0), |s, r| (s.0 + r[0], s.1 + r[1]));
                    Ok(format!(
                        "max |r/λ − r(1)|/max|r(1)| = {worst:.0e}; T/N = {:.4}",
                        t / n
                    ))
                },
            )
        })
        .collect()
}
