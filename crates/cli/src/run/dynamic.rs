//! `bipo run` of a dynamic scene (issue 39), 2D or 3D: the Moreau–Jean steps from 0 to
//! `end_time` (all of one size, `end_time / steps`, so that `M̂` is factorised once), each load scaled by its time function at the step's θ-point, and what the run
//! writes against time:
//!
//! - `dynamics.csv`: one row per step (and t = 0): the energy balance of
//!   [`EnergyBalance`] (kinetic, strain, work of the loads, the contacts' work `−W_c` and its
//!   split into impact, friction and damage, the energy stored in adhesive springs, dissipated
//!   by the damping and by the scheme, the balance's residual, absolute and relative to its
//!   largest term), each zone's normal and tangential contact force resultants (impulse / h)
//!   and, for an RCCM zone, its mean adhesion intensity β, the bodies' mean velocity
//!   (momentum / mass) and each `output.velocity_sets` set's mean velocity;
//! - `mesh.pvd` and `mesh_NNNN.vtu` every `output.every` steps (and the last): displacement
//!   `u` and velocity `v` at the nodes;
//! - `energies.svg`, `contact_force.svg` (and `velocity.svg` with velocity sets);
//! - `summary.json` ([`DynamicSummary`]).

use super::RunOptions;
use super::driver::apply_step;
use super::errors::{create, fem_failed, io, step_error};
use super::progress::{Progress, path_name};
use crate::build::{DynamicSim, DynamicStudy, StudyDim};
use crate::error::{CliError, CliResult};
use crate::plot::write_svg;
use crate::scene::Units;
use contact_solver::StepResult;
use contact_solver::coupling::simulation::EnergyBalance;
use fem_core::{Dim, Structure};
use serde::Serialize;
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// The `summary.json` of a dynamic run.
#[derive(Debug, Serialize)]
pub struct DynamicSummary {
    pub bipo_version: &'static str,
    pub scene: String,
    pub title: String,
    pub units: Units,
    /// `completed` or `failed`.
    pub status: String,
    pub error: Option<String>,
    pub analysis: DynamicFacts,
    /// Steps done.
    pub steps: usize,
    /// The time reached.
    pub time: f64,
    pub wall_time_s: f64,
    /// The balance at the end.
    pub energy: EnergyFacts,
    /// The largest relative residual of the balance over the steps.
    pub max_residual_relative: f64,
    pub zones: Vec<DynamicZone>,
    /// The sets whose mean velocity `dynamics.csv` writes.
    pub velocity_sets: Vec<String>,
    /// Contact iterations over the run.
    pub contact_iterations: usize,
    pub files: Vec<String>,
    pub warnings: Vec<String>,
}

/// The time stepping of the run.
#[derive(Debug, Serialize)]
pub struct DynamicFacts {
    pub dynamic: bool,
    pub time_step: f64,
    pub end_time: f64,
    pub theta: f64,
    /// `consistent` or `lumped`.
    pub mass: &'static str,
    pub rayleigh_alpha: f64,
    pub rayleigh_beta: f64,
}

/// The energy balance (units of force × length).
#[derive(Debug, Serialize, Default)]
pub struct EnergyFacts {
    pub initial: f64,
    pub kinetic: f64,
    pub strain: f64,
    pub external_work: f64,
    pub contact_dissipation: f64,
    /// Dissipated by the normal impulses (impact).
    pub impact: f64,
    /// Dissipated by the tangential impulses (friction).
    pub friction: f64,
    /// Released by the adhesive springs as β dropped (damage).
    pub damage: f64,
    /// Stored in the adhesive springs now.
    pub interface: f64,
    pub damping: f64,
    pub numerical: f64,
    pub residual: f64,
    pub residual_relative: f64,
}

impl From<&EnergyBalance> for EnergyFacts {
    fn from(e: &EnergyBalance) -> Self {
        Self {
            initial: e.initial,
            kinetic: e.kinetic,
            strain: e.strain,
            external_work: e.external_work,
            contact_dissipation: e.contact_dissipation(),
            impact: e.impact,
            friction: e.friction,
            damage: e.damage,
            interface: e.interface,
            damping: e.damping,
            numerical: e.numerical,
            residual: e.residual(),
            residual_relative: relative(e),
        }
    }
}

/// A zone's contact over the run.
#[derive(Debug, Serialize)]
pub struct DynamicZone {
    pub name: String,
    pub law: String,
    pub restitution: f64,
    /// The largest normal force resultant (impulse / h).
    pub peak_normal_force: f64,
    /// Steps with a normal impulse.
    pub contact_steps: usize,
    /// The end of the first and of the last step with a normal impulse.
    pub first_contact_time: Option<f64>,
    pub last_contact_time: Option<f64>,
    /// An RCCM zone: the mean adhesion intensity β over its contacts at the end.
    pub mean_beta: Option<f64>,
}

/// The balance's residual relative to its largest term (0 for a balance of zeros).
fn relative(e: &EnergyBalance) -> f64 {
    let s = e.scale();
    if s > 0.0 { e.residual() / s } else { 0.0 }
}

/// What the run keeps for the plots, per written row.
#[derive(Default)]
struct History {
    time: Vec<f64>,
    kinetic: Vec<f64>,
    strain: Vec<f64>,
    external: Vec<f64>,
    dissipated: Vec<f64>,
    /// Per zone, the normal force.
    normal: Vec<Vec<f64>>,
    /// Per velocity set, the mean velocity's last component (vertical).
    sets: Vec<Vec<f64>>,
}

/// The velocity `v` (free dofs) at every node, prescribed components 0.
fn nodal<const D: usize>(sim: &DynamicSim<D>, v: &[f64]) -> Vec<[f64; D]>
where
    Dim<D>: StudyDim<D>,
{
    let s = sim.structure();
    (0..s.node_count())
        .map(|n| {
            s.node_dofs(n)
                .map(|d| d.map_or(0.0, |i| v.get(i).copied().unwrap_or(0.0)))
        })
        .collect()
}

/// The mean of `v` over `nodes`.
fn mean<const D: usize>(v: &[[f64; D]], nodes: &[usize]) -> [f64; D] {
    let k = nodes.len().max(1) as f64;
    core::array::from_fn(|c| nodes.iter().map(|&n| v[n][c]).sum::<f64>() / k)
}

/// Per zone, the mean adhesion intensity β over its contacts (0 for a zone without any).
fn zone_betas<const D: usize>(res: &StepResult<D>, zones: usize) -> Vec<f64>
where
    Dim<D>: StudyDim<D>,
{
    let mut sum = vec![(0.0, 0_usize); zones];
    for c in &res.contacts {
        sum[c.zone].0 += c.beta;
        sum[c.zone].1 += 1;
    }
    sum.iter().map(|(b, n)| b / (*n).max(1) as f64).collect()
}

/// Per zone, the normal and tangential resultants of a step's impulses over `h`.
fn zone_forces<const D: usize>(res: &StepResult<D>, zones: usize, h: f64) -> Vec<(f64, f64)>
where
    Dim<D>: StudyDim<D>,
{
    let mut normal = vec![0.0; zones];
    let mut tangential = vec![[0.0; D]; zones];
    for c in &res.contacts {
        let r_n = c.reaction()[0];
        normal[c.zone] += r_n;
        let f = c.force();
        for a in 0..D {
            tangential[c.zone][a] += f[a] - r_n * c.normal[a];
        }
    }
    normal
        .iter()
        .zip(&tangential)
        .map(|(n, t)| (n / h, t.iter().map(|x| x * x).sum::<f64>().sqrt() / h))
        .collect()
}

/// Runs a dynamic study; returns its summary (also written to `summary.json`).
pub fn run_dynamic<const D: usize>(
    mut study: DynamicStudy<D>,
    opts: &RunOptions,
) -> CliResult<DynamicSummary>
where
    Dim<D>: StudyDim<D>,
{
    let dir = &opts.out_dir;
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let start = Instant::now();
    let zones = study.zone_names.len();
    let axes = ["x", "y", "z"];
    let mut csv = create(dir, "dynamics.csv")?;
    let mut head = String::from(
        "step,time,kinetic,strain,external_work,contact_dissipation,impact,friction,damage,\
         interface,damping,numerical,balance_residual,balance_relative",
    );
    // the zones whose law has adhesion (β)
    let adhesive: Vec<bool> = study.zone_laws.iter().map(|l| l == "rccm").collect();
    for (z, a) in study.zone_names.iter().zip(&adhesive) {
        head += &format!(",normal_force_{z},tangential_force_{z}");
        if *a {
            head += &format!(",beta_{z}");
        }
    }
    for a in &axes[..D] {
        head += &format!(",v_body_{a}");
    }
    for (s, _) in &study.velocity_sets {
        for a in &axes[..D] {
            head += &format!(",v_{s}_{a}");
        }
    }
    let csv_path = dir.join("dynamics.csv");
    writeln!(csv, "{head}").map_err(|e| io(&csv_path, e))?;

    // the bodies' mean velocity: (1_a · M v) / (1_a · M 1_a) along each axis a
    let n = study.sim.structure().dof_count();
    let mut mass_axes = Vec::new();
    for a in 0..D {
        let mut ones = vec![0.0; n];
        for node in 0..study.sim.structure().node_count() {
            if let Some(i) = study.sim.structure().node_dofs(node)[a] {
                ones[i] = 1.0;
            }
        }
        let mut m1 = vec![0.0; n];
        study.sim.structure().mass_mul_into(&ones, &mut m1);
        let total: f64 = m1.iter().zip(&ones).map(|(x, y)| x * y).sum();
        mass_axes.push((m1, total));
    }

    let mut hist = History {
        normal: vec![Vec::new(); zones],
        sets: vec![Vec::new(); study.velocity_sets.len()],
        ..History::default()
    };
    let mut zone_facts: Vec<DynamicZone> = study
        .zone_names
        .iter()
        .zip(&study.zone_laws)
        .zip(&study.restitution)
        .map(|((name, law), &e)| DynamicZone {
            name: name.clone(),
            law: law.clone(),
            restitution: e,
            peak_normal_force: 0.0,
            contact_steps: 0,
            first_contact_time: None,
            last_contact_time: None,
            mean_beta: None,
        })
        .collect();

    // one CSV row (and the history) at time `t` with the balance `e` and the zone forces
    let velocity_sets = study.velocity_sets.clone();
    let mut write_row = |sim: &DynamicSim<D>,
                         step: usize,
                         t: f64,
                         e: &EnergyBalance,
                         forces: &[(f64, f64)],
                         betas: &[f64],
                         hist: &mut History|
     -> CliResult<()> {
        let v = sim.scheme().velocity();
        let mut line = format!(
            "{step},{t},{},{},{},{},{},{},{},{},{},{},{},{}",
            e.kinetic,
            e.strain,
            e.external_work,
            e.contact_dissipation() + 0.0, // −0 at rest is written 0
            e.impact,
            e.friction,
            e.damage,
            e.interface,
            e.damping,
            e.numerical,
            e.residual(),
            relative(e)
        );
        for (z, (fn_, ft)) in forces.iter().enumerate() {
            line += &format!(",{fn_},{ft}");
            if adhesive[z] {
                line += &format!(",{}", betas[z]);
            }
        }
        for (m1, total) in &mass_axes {
            let p: f64 = m1.iter().zip(v).map(|(x, y)| x * y).sum();
            let mean = if *total > 0.0 { p / total } else { 0.0 };
            line += &format!(",{mean}");
        }
        let nodal_v = nodal(sim, v);
        for (k, (_, nodes)) in velocity_sets.iter().enumerate() {
            let m = mean(&nodal_v, nodes);
            for x in m {
                line += &format!(",{x}");
            }
            hist.sets[k].push(m[D - 1]);
        }
        writeln!(csv, "{line}").map_err(|e| io(&csv_path, e))?;
        hist.time.push(t);
        hist.kinetic.push(e.kinetic);
        hist.strain.push(e.strain);
        hist.external.push(e.external_work);
        hist.dissipated
            .push(e.contact_dissipated() + e.damping + e.numerical);
        for (z, (fn_, _)) in forces.iter().enumerate() {
            hist.normal[z].push(*fn_);
        }
        Ok(())
    };

    // t = 0: the initial kinetic energy ½ v₀ᵀ M v₀ (at rest from the undeformed state)
    let v0 = study.sim.scheme().velocity().to_vec();
    let mut mv = vec![0.0; v0.len()];
    study.sim.structure().mass_mul_into(&v0, &mut mv);
    let t0 = 0.5 * v0.iter().zip(&mv).map(|(a, b)| a * b).sum::<f64>();
    let mut e0 = EnergyBalance::default();
    (e0.initial, e0.kinetic) = (t0, t0);
    let beta0 = study
        .sim
        .states()
        .iter()
        .zip(study.sim.candidates())
        .fold(vec![(0.0, 0_usize); zones], |mut acc, (s, c)| {
            acc[c.zone].0 +=
                contact_laws::ContactLaw::adhesion_intensity(&study.sim.zones()[c.zone].law, s);
            acc[c.zone].1 += 1;
            acc
        })
        .iter()
        .map(|(b, n)| b / (*n).max(1) as f64)
        .collect::<Vec<f64>>();
    let rest = vec![(0.0, 0.0); zones];
    write_row(&study.sim, 0, 0.0, &e0, &rest, &beta0, &mut hist)?;

    let mut vtk = Vec::new();
    if study.output.vtk {
        write_vtk(&study.sim, dir, 0.0, &mut vtk)?;
    }
    let progress = Progress::new(study.spec.steps, opts.quiet);
    progress.begin_phase("dynamic");
    let (mut steps, mut iterations, mut max_rel) = (0, 0, 0.0_f64);
    let mut last_loads = None;
    let mut error: Option<CliError> = None;
    let every = study.output.every.max(1);
    // one step size for the whole run: M̂ is factorised once
    let h = study.spec.end_time / study.spec.steps as f64;
    for k in 1..=study.spec.steps {
        let t_prev = study.sim.time();
        let t = t_prev + h;
        let t_theta = t_prev + study.spec.theta * h;
        let DynamicStudy {
            sim,
            supports,
            loads,
            functions,
            phase,
            ..
        } = &mut study;
        let applied = sim.structure_mut().update(|m| {
            apply_step(
                m,
                supports,
                loads,
                functions,
                (phase, 0),
                t_theta,
                &mut last_loads,
            )
        });
        let res = match applied {
            Err(e) => Err(fem_failed("loads", e)),
            Ok(Err(e)) => Err(e),
            Ok(Ok(())) => sim.advance(h).map_err(|e| step_error(e, phase, t)),
        };
        let res = match res {
            Ok(r) => r,
            Err(mut e) => {
                e.message = format!("step {k} ({})", e.message);
                error = Some(e);
                break;
            }
        };
        steps = k;
        iterations += res.report.contact_iterations;
        let forces = zone_forces(&res, zones, h);
        let betas = zone_betas(&res, zones);
        for (z, b) in betas.iter().enumerate() {
            zone_facts[z].mean_beta = adhesive[z].then_some(*b);
        }
        for (z, &(f, _)) in forces.iter().enumerate() {
            let facts = &mut zone_facts[z];
            facts.peak_normal_force = facts.peak_normal_force.max(f);
            if f > 0.0 {
                facts.contact_steps += 1;
                facts.first_contact_time.get_or_insert(t);
                facts.last_contact_time = Some(t);
            }
        }
        let e = *sim.scheme().energy();
        max_rel = max_rel.max(relative(&e).abs());
        if let Err(e) = write_row(sim, k, t, &e, &forces, &betas, &mut hist) {
            error = Some(e);
            break;
        }
        let written = k.is_multiple_of(every) || k == study.spec.steps;
        if study.output.vtk
            && written
            && let Err(e) = write_vtk(&study.sim, dir, t, &mut vtk)
        {
            error = Some(e);
            break;
        }
        progress.step(t, res.report.contact_iterations, path_name(&res.report));
    }
    progress.finish();
    csv.flush().map_err(|e| io(&csv_path, e))?;
    let mut files = vec!["summary.json".to_string(), "dynamics.csv".to_string()];
    files.extend(write_plots(dir, &study, &hist)?);
    if !vtk.is_empty() {
        files.push("mesh.pvd".into());
    }
    let spec = &study.spec;
    let summary = DynamicSummary {
        bipo_version: env!("CARGO_PKG_VERSION"),
        scene: opts.scene_file.display().to_string(),
        title: study.title.clone(),
        units: study.units.clone(),
        status: if error.is_some() {
            "failed"
        } else {
            "completed"
        }
        .into(),
        error: error.as_ref().map(|e| e.message.clone()),
        analysis: DynamicFacts {
            dynamic: true,
            time_step: spec.time_step,
            end_time: spec.end_time,
            theta: spec.theta,
            mass: spec.mass.name(),
            rayleigh_alpha: spec.alpha,
            rayleigh_beta: spec.beta,
        },
        steps,
        time: study.sim.time(),
        wall_time_s: start.elapsed().as_secs_f64(),
        energy: if steps > 0 {
            study.sim.scheme().energy().into()
        } else {
            (&e0).into()
        },
        max_residual_relative: max_rel,
        zones: zone_facts,
        velocity_sets: study.velocity_sets.iter().map(|(s, _)| s.clone()).collect(),
        contact_iterations: iterations,
        files,
        warnings: study.warnings.clone(),
    };
    let path = dir.join("summary.json");
    let text = serde_json::to_string_pretty(&summary).map_err(|e| io(&path, e))?;
    std::fs::write(&path, text + "\n").map_err(|e| io(&path, e))?;
    match error {
        Some(e) => Err(e),
        None => Ok(summary),
    }
}

/// One piece of the VTK series (`mesh_NNNN.vtu`: `u` and `v` at the nodes) at time `t`, and
/// `mesh.pvd` rewritten with every piece so far (`entries`).
fn write_vtk<const D: usize>(
    sim: &DynamicSim<D>,
    dir: &Path,
    t: f64,
    entries: &mut Vec<(f64, String)>,
) -> CliResult<()>
where
    Dim<D>: StudyDim<D>,
{
    use super::vtk::push_pvd;
    use fem_core::vtk::{Field, write_vtu};
    let u = sim.nodal_displacements();
    let v = nodal(sim, sim.scheme().velocity());
    let name = format!("mesh_{:04}.vtu", entries.len());
    let path = dir.join(&name);
    write_vtu(
        &path,
        sim.structure().model().mesh(),
        &[("u", Field::Vector(&u)), ("v", Field::Vector(&v))],
        &[],
    )
    .map_err(|e| io(&path, e))?;
    push_pvd(dir, entries, t, name)
}

/// `energies.svg`, `contact_force.svg` and, with velocity sets, `velocity.svg`; returns their
/// names.
fn write_plots<const D: usize>(
    dir: &Path,
    study: &DynamicStudy<D>,
    h: &History,
) -> CliResult<Vec<String>>
where
    Dim<D>: StudyDim<D>,
{
    let svg = |name: &str, title: &str, series: &[(&str, &[f64])]| -> CliResult<String> {
        let path = dir.join(name);
        write_svg(&path, title, "time", &h.time, series).map_err(|e| io(&path, e))?;
        Ok(name.to_string())
    };
    let mut files = vec![svg(
        "energies.svg",
        "Energies",
        &[
            ("kinetic", &h.kinetic),
            ("strain", &h.strain),
            ("work of the loads", &h.external),
            ("dissipated", &h.dissipated),
        ],
    )?];
    let normal: Vec<(&str, &[f64])> = study
        .zone_names
        .iter()
        .zip(&h.normal)
        .map(|(z, f)| (z.as_str(), f.as_slice()))
        .collect();
    files.push(svg("contact_force.svg", "Normal contact force", &normal)?);
    if !study.velocity_sets.is_empty() {
        let sets: Vec<(&str, &[f64])> = study
            .velocity_sets
            .iter()
            .zip(&h.sets)
            .map(|((s, _), v)| (s.as_str(), v.as_slice()))
            .collect();
        let axis = if D == 3 { "z" } else { "y" };
        files.push(svg(
            "velocity.svg",
            &format!("Mean velocity along {axis}"),
            &sets,
        )?);
    }
    Ok(files)
}
