//! Seed chapter 6: pull-out of the Plancoët and Cran piles (axisymmetric P2, 65 shaft pairs),
//! with the RCCM interface of table 6.3 and with plain Coulomb friction (fig. 6.5), plus the
//! parametric study of §6.5 (C, w and μ each varied, figs 6.9–6.11) on Plancoët.
//!
//! Units: kN, m, kPa; loads are full-ring forces. The head load `Q` is the force the jack
//! applies on the pile (it holds the pile's excess weight `Q₀ = (γ_p − γ_s) π R² L_p` at
//! `v = 0`; at full slip `Q = W_p + Q_f`). Modelling choices: `bipo::presets::pile`
//! and `docs/validation.md` ("Pile pull-out").
//!
//! Writes under `out/pile/`: `load_displacement.csv` and one SVG per site (RCCM vs Coulomb),
//! `steps_<site>_<interface>.csv` (every increment: loads, shaft friction, tip force),
//! `shaft_<site>.csv` and SVGs of the shear stress, β and normal stress along the shaft at
//! increments 5, 10, 25 and 50, and `param_{C,w,mu}.{csv,svg}`.
//!
//! `cargo run --release --example pile_pullout` (`BIPO_QUICK=1`: 5 increments on a coarse mesh,
//! 8 shaft cells).

#[path = "common/mod.rs"]
mod common;

use bipo::presets::{PulloutRun, PulloutScene, PulloutSpec};
use bipotential::contact_laws::RccmParams;
use bipotential::contact_solver::SimulationSettings;
use common::{Series, line_plot, write_csv, write_series_csv};
use std::error::Error;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A finished run: the scene (for its bookkeeping) and its results.
struct Done {
    scene: PulloutScene,
    run: PulloutRun,
    seconds: f64,
}

/// `spec`, or with `BIPO_QUICK=1` its quick version: 5 increments on the coarse mesh of
/// `pile_3d --coarse` (8 shaft cells).
fn sized(mut spec: PulloutSpec) -> PulloutSpec {
    if common::quick() {
        spec.steps = 5;
        (
            spec.mesh.cells_shaft,
            spec.mesh.cells_soil_r,
            spec.mesh.cells_below_tip,
        ) = (8, 6, 4);
    }
    spec
}

fn run(spec: &PulloutSpec) -> Result<Done, Box<dyn Error>> {
    let start = Instant::now();
    let mut scene = spec.build(SimulationSettings::default())?;
    let run = scene.run()?;
    Ok(Done {
        scene,
        run,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// `(v in mm, Q in kN)`, starting from the state after installation at `v = 0`.
fn curve(d: &Done) -> Vec<(f64, f64)> {
    d.run
        .curve()
        .into_iter()
        .map(|(v, q)| (1e3 * v, q))
        .collect()
}

fn write_steps(path: &Path, d: &Done) -> Result<(), Box<dyn Error>> {
    let s = &d.scene;
    let rows: Vec<Vec<f64>> = d
        .run
        .steps
        .iter()
        .map(|p| {
            let r = &p.result;
            let beta_mean = s
                .shaft_candidates
                .iter()
                .map(|&i| r.contacts[i].beta)
                .sum::<f64>()
                / s.shaft_candidates.len() as f64;
            vec![
                p.increment as f64,
                1e3 * p.head_displacement,
                p.head_load,
                p.head_load - s.spec.pile_weight(),
                s.shaft_friction(r),
                s.tip_force(r),
                s.shaft_normal_force(r),
                s.full_slip_load(r),
                beta_mean,
            ]
        })
        .collect();
    write_csv(
        path,
        &[
            "increment",
            "v_mm",
            "Q_kN",
            "Q_minus_Wp_kN",
            "shaft_friction_kN",
            "tip_force_kN",
            "shaft_normal_force_kN",
            "full_slip_load_kN",
            "beta_mean",
        ],
        &rows,
    )
}

fn main() -> Result<(), Box<dyn Error>> {
    let total = Instant::now();
    let out = PathBuf::from("out/pile");
    std::fs::create_dir_all(&out)?;

    let sites = [
        ("plancoet", sized(PulloutSpec::plancoet())),
        ("cran", sized(PulloutSpec::cran())),
    ];
    let mut main_runs = Vec::new();
    for (name, spec) in &sites {
        let rccm = run(spec)?;
        let coulomb = run(&spec.clone().with_coulomb_interface())?;
        main_runs.push((*name, rccm, coulomb));
    }

    // Phase checks and summary.
    println!(
        "Pile pull-out (seed ch. 6), units kN, m; Q = jack force on the pile head (full ring)"
    );
    for (name, rccm, coulomb) in &main_runs {
        let s = &rccm.scene;
        let spec = &s.spec;
        let geo = &rccm.run.geostatic;
        let n_geo = s.shaft_normal_force(geo);
        let n_inst = s.shaft_normal_force(&rccm.run.installed);
        let u_max = rccm.run.geostatic_max_displacement;
        println!(
            "\n{name}: L_p = {} m, E_p = {:.0} MPa, C = {} kN/m³, δ = {:.3} mm, W_p = {:.1} kN, Q₀ = {:.1} kN",
            spec.mesh.length,
            spec.pile_young / 1e3,
            spec.interface.c_t,
            1e3 * s.installation_displacement,
            spec.pile_weight(),
            spec.head_load_at_rest(),
        );
        println!(
            "  phase 1: max |u| = {u_max:.1e} m, shaft normal force {n_geo:.1} kN (K0 γ π D L_p²/2 = {:.1}), \
             tip {:.1} kN; phase 2: shaft normal force {n_inst:.1} kN (× {:.3})",
            spec.k0
                * spec.soil_unit_weight
                * std::f64::consts::PI
                * spec.mesh.diameter
                * spec.mesh.length.powi(2)
                / 2.0,
            s.tip_force(geo),
            n_inst / n_geo,
        );
        for (label, d) in [("RCCM", rccm), ("Coulomb", coulomb)] {
            let last = d.run.steps.last().expect("steps");
            println!(
                "  {label:8}: Q(v₀ = {:.0} mm) = {:.1} kN, peak {:.1} kN, W_p + 2π Σ μ r_n = {:.1} kN, tip {:.2} kN; \
                 {} steps in {:.2} s ({} contact iterations)",
                1e3 * last.head_displacement,
                last.head_load,
                d.run.peak_load(),
                d.scene.full_slip_load(&last.result),
                d.scene.tip_force(&last.result),
                d.scene.simulation.counters().steps,
                d.seconds,
                d.scene.simulation.counters().contact_iterations,
            );
        }
    }

    // The head load–displacement table.
    let (p, c) = (&main_runs[0], &main_runs[1]);
    println!("\n  k | v Plancoët | Q RCCM  | Q Coulomb || v Cran | Q RCCM  | Q Coulomb");
    println!("    |    (mm)    |  (kN)   |   (kN)    ||  (mm)  |  (kN)   |   (kN)");
    for k in 0..p.1.run.steps.len() {
        let (a, b) = (&p.1.run.steps[k], &p.2.run.steps[k]);
        let (e, f) = (&c.1.run.steps[k], &c.2.run.steps[k]);
        println!(
            "{:3} | {:10.2} | {:7.1} | {:9.1} || {:6.2} | {:7.1} | {:9.1}",
            k + 1,
            1e3 * a.head_displacement,
            a.head_load,
            b.head_load,
            1e3 * e.head_displacement,
            e.head_load,
            f.head_load
        );
    }

    // CSV and plots of the main runs.
    let mut all = Vec::new();
    for (name, rccm, coulomb) in &main_runs {
        let series = vec![
            Series::new(format!("{name} RCCM"), curve(rccm)),
            Series::new(format!("{name} Coulomb (β₀ = 0)"), curve(coulomb)),
        ];
        line_plot(
            &out.join(format!("load_displacement_{name}.svg")),
            &format!("Pull-out, {name} (figs 6.5, 6.7–6.8)"),
            "head displacement v (mm)",
            "head load Q (kN)",
            &series,
        )?;
        all.extend(series);
        write_steps(&out.join(format!("steps_{name}_rccm.csv")), rccm)?;
        write_steps(&out.join(format!("steps_{name}_coulomb.csv")), coulomb)?;
        shaft_profiles(&out, name, rccm)?;
    }
    write_series_csv(&out.join("load_displacement.csv"), "v_mm", "Q_kN", &all)?;

    // Parametric study on Plancoët (§6.5): one parameter varied at a time.
    let base = sized(PulloutSpec::plancoet());
    type Set = fn(&mut RccmParams, f64);
    let studies: [(&str, &str, &[f64], Set); 3] = [
        (
            "C",
            "C_n = C_t (kN/m³)",
            &[2500.0, 10500.0, 42000.0],
            |p, v| {
                p.c_n = v;
                p.c_t = v;
            },
        ),
        ("w", "w (kN/m)", &[1e-3, 3e-3, 3e-2, 3e-1], |p, v| p.w = v),
        ("mu", "μ", &[0.3, 0.46, 0.6], |p, v| p.mu = v),
    ];
    let baseline = &main_runs[0].1;
    for (file, label, values, set) in studies {
        let mut series = Vec::new();
        for &v in values {
            let mut spec = base.clone();
            set(&mut spec.interface, v);
            let pts = if spec == base {
                curve(baseline)
            } else {
                curve(&run(&spec)?)
            };
            series.push(Series::new(format!("{label} = {v}"), pts));
        }
        write_series_csv(
            &out.join(format!("param_{file}.csv")),
            "v_mm",
            "Q_kN",
            &series,
        )?;
        line_plot(
            &out.join(format!("param_{file}.svg")),
            &format!("Plancoët, influence of {label} (§6.5)"),
            "head displacement v (mm)",
            "head load Q (kN)",
            &series,
        )?;
    }
    println!(
        "\nwrote {}; total {:.2} s",
        out.display(),
        total.elapsed().as_secs_f64()
    );
    Ok(())
}

fn shaft_profiles(out: &Path, name: &str, d: &Done) -> Result<(), Box<dyn Error>> {
    let mut tau = Vec::new();
    let mut beta = Vec::new();
    let mut sigma = Vec::new();
    for k in [5usize, 10, 25, 50] {
        let Some(step) = d.run.steps.get(k - 1) else {
            continue;
        };
        let profile = d.scene.shaft_profile(&step.result);
        let v = 1e3 * step.head_displacement;
        let tag = format!("k = {k}, v = {v:.2} mm");
        // friction resisting the pull-out, −τ, against depth
        tau.push(Series::new(
            &tag,
            profile.iter().map(|p| (-p.tau, p.z)).collect(),
        ));
        beta.push(Series::new(
            &tag,
            profile.iter().map(|p| (p.beta, p.z)).collect(),
        ));
        sigma.push(Series::new(
            &tag,
            profile.iter().map(|p| (p.sigma_n, p.z)).collect(),
        ));
    }
    write_series_csv(
        &out.join(format!("shaft_{name}_shear.csv")),
        "minus_tau_kPa",
        "z_m",
        &tau,
    )?;
    write_series_csv(
        &out.join(format!("shaft_{name}_beta.csv")),
        "beta",
        "z_m",
        &beta,
    )?;
    write_series_csv(
        &out.join(format!("shaft_{name}_normal.csv")),
        "sigma_n_kPa",
        "z_m",
        &sigma,
    )?;
    line_plot(
        &out.join(format!("shaft_{name}_shear.svg")),
        &format!("{name}: shaft friction −r_t/A along the pile (RCCM)"),
        "−τ (kPa)",
        "z (m)",
        &tau,
    )?;
    line_plot(
        &out.join(format!("shaft_{name}_beta.svg")),
        &format!("{name}: adhesion intensity β along the pile"),
        "β",
        "z (m)",
        &beta,
    )?;
    line_plot(
        &out.join(format!("shaft_{name}_normal.svg")),
        &format!("{name}: normal stress r_n/A along the pile"),
        "σ_n (kPa)",
        "z (m)",
        &sigma,
    )?;
    Ok(())
}
