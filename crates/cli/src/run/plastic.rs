//! `bipo run` of a scene with a plastic material (issue 40), 2D or 3D: the phases' steps, each
//! solved by the global Newton around contact; a step that does not converge is halved (its
//! time, hence its supports' values and the loads' force factor) up to `[analysis.newton]
//! max_cuts` times, and the run stops at the last converged state when it still does not. The
//! run writes:
//!
//! - `steps.csv`: one row per step: time, force factor, Newton iterations (over the step's
//!   sub-steps), the final relative residual, the cuts, the contact iterations, the closed
//!   contacts, the largest equivalent plastic strain and the yielding points;
//! - `mesh.pvd` and `mesh_NNNN.vtu` (t = 0, every `output.every` steps, the last and the last
//!   converged state of a run that fails): `u` at the nodes; per element the mean
//!   `equivalent_plastic_strain`, `volumetric_plastic_strain` (`tr εᵖ`), `yielding` (the
//!   fraction of the element's points that yielded in the last step), `yield_state` (0
//!   elastic, 1 on the cone, 2 at its apex: the most plastic of the element's points) and
//!   `stress`;
//! - `curves.csv` and the SVGs of `[[plots]]` (e.g. a reaction against a displacement: the
//!   load–displacement curve);
//! - `summary.json` ([`PlasticSummary`]), with every step's Newton residuals.

use super::RunOptions;
use super::driver::Extras;
use super::errors::{create, fem_failed, io, step_error};
use super::plots::Plots;
use super::progress::Progress;
use super::summary::CurveSummary;
use crate::build::{PlasticSim, PlasticStudy, StudyDim, function_value};
use crate::error::{CliError, CliResult};
use crate::scene::Units;
use contact_solver::{ContactRecord, SolverError, StepResult};
use fem_core::plastic::PlasticModel;
use fem_core::{Component, Dim, Nonlinear, Reaction};
use serde::Serialize;
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// The `summary.json` of a plastic run.
#[derive(Debug, Serialize)]
pub struct PlasticSummary {
    pub bipo_version: &'static str,
    pub scene: String,
    pub title: String,
    pub units: Units,
    /// `completed` or `failed`.
    pub status: String,
    /// The error that stopped the run (the outputs hold its last converged state).
    pub error: Option<String>,
    pub dimension: usize,
    /// Each region's material type.
    pub materials: Vec<(u32, &'static str)>,
    /// The Newton's settings.
    pub newton: NewtonFacts,
    /// Steps done (converged).
    pub steps: usize,
    /// The time of the last converged state.
    pub time: f64,
    pub wall_time_s: f64,
    /// Newton iterations over the run (every attempt, cut ones included), and the most in
    /// one converged solve of a step or sub-step.
    pub newton_iterations: usize,
    pub max_newton_iterations: usize,
    /// Step halvings over the run.
    pub cuts: usize,
    pub contact_iterations: usize,
    /// The last converged state: the largest equivalent plastic strain, the points that
    /// yielded in its step (at the apex among them), of all points.
    pub max_equivalent_plastic_strain: f64,
    pub yielding_points: usize,
    pub apex_points: usize,
    pub points: usize,
    /// Every step's Newton report.
    pub step_reports: Vec<StepFacts>,
    pub curves: Vec<CurveSummary>,
    pub files: Vec<String>,
    pub warnings: Vec<String>,
}

/// `[analysis.newton]` as run.
#[derive(Debug, Serialize)]
pub struct NewtonFacts {
    pub tol: f64,
    pub max_iterations: usize,
    pub max_cuts: usize,
}

/// One step's Newton: its sub-steps' iterations summed, its cuts, the residuals of its last
/// sub-step.
#[derive(Debug, Serialize)]
pub struct StepFacts {
    pub step: usize,
    pub time: f64,
    pub load_factor: f64,
    pub iterations: usize,
    pub cuts: usize,
    pub residuals: Vec<f64>,
}

/// The tangential slip a plot of `u_t` shows, by dimension.
pub(crate) trait PlasticRunDim<const D: usize>: StudyDim<D>
where
    Dim<D>: StudyDim<D>,
{
    /// A contact's tangential relative displacement (along its first tangent in 3D).
    fn u_t(c: &ContactRecord<D>) -> f64;
}

impl PlasticRunDim<2> for Dim<2> {
    fn u_t(c: &ContactRecord<2>) -> f64 {
        c.u_t
    }
}

impl PlasticRunDim<3> for Dim<3> {
    fn u_t(c: &ContactRecord<3>) -> f64 {
        c.u_t[0]
    }
}

/// Sets every moving support of `study` at time `t` of phase `p`, and returns the loads'
/// force factor there.
fn apply<const D: usize>(study: &mut PlasticStudy<D>, p: usize, t: f64) -> CliResult<f64>
where
    Dim<D>: StudyDim<D>,
{
    let phase = &study.phases[p];
    let body = study.sim.structure_mut();
    for s in study.supports.iter().filter(|s| s.value != 0.0) {
        let v = s.value * function_value(phase, &s.name, &s.function, &study.functions, t);
        for &c in &s.components {
            body.set_prescribed(&s.nodes, c, v)
                .map_err(|e| fem_failed("prescribed displacement", e))?;
        }
    }
    let (function, name) = &study.load_function;
    Ok(function_value(phase, name, function, &study.functions, t))
}

/// Yield state of an element for the VTK files and the counts: per element the most plastic
/// state of its points (0 elastic, 1 cone, 2 apex) and the mean `tr εᵖ`; the number of
/// yielding points and of those at the apex.
fn plastic_fields<const D: usize>(body: &PlasticModel<D>) -> (Vec<f64>, Vec<f64>, usize, usize)
where
    Dim<D>: StudyDim<D>,
{
    let states = body.committed_states();
    let elements = body.elastic().mesh().element_count();
    let (mut state, mut volumetric) = (vec![0.0_f64; elements], vec![0.0; elements]);
    let (mut yielding, mut apex) = (0, 0);
    for e in 0..elements {
        let points = &states[body.element_points(e)];
        let w = 1.0 / points.len().max(1) as f64;
        for s in points {
            let ep = &s.plastic_strain;
            volumetric[e] += w * (ep[0] + ep[1] + ep[2]);
            if !s.yielding {
                continue;
            }
            yielding += 1;
            // at the apex the deviator vanishes (to the return mapping's round-off)
            let m = (s.stress[0] + s.stress[1] + s.stress[2]) / 3.0;
            let dev: f64 = (0..3).map(|i| (s.stress[i] - m).powi(2)).sum::<f64>()
                + 2.0 * (3..6).map(|i| s.stress[i].powi(2)).sum::<f64>();
            let norm: f64 = s.stress.iter().map(|x| x * x).sum::<f64>();
            let at_apex = dev.sqrt() <= 1e-8 * norm.sqrt();
            apex += usize::from(at_apex);
            state[e] = state[e].max(if at_apex { 2.0 } else { 1.0 });
        }
    }
    (state, volumetric, yielding, apex)
}

/// One piece of the mesh's VTK series at time `t`, and `mesh.pvd` rewritten.
fn write_vtk<const D: usize>(
    sim: &PlasticSim<D>,
    dir: &Path,
    t: f64,
    entries: &mut Vec<(f64, String)>,
) -> CliResult<()>
where
    Dim<D>: StudyDim<D>,
{
    use super::vtk::push_pvd;
    use fem_core::vtk::{Field, write_vtu};
    let body = sim.structure();
    let u = sim.nodal_displacements();
    let out = body.element_outputs();
    let (state, volumetric, _, _) = plastic_fields(body);
    let name = format!("mesh_{:04}.vtu", entries.len());
    let path = dir.join(&name);
    write_vtu(
        &path,
        body.elastic().mesh(),
        &[("u", Field::Vector(&u))],
        &[
            (
                "equivalent_plastic_strain",
                Field::Scalar(&out.equivalent_plastic_strain),
            ),
            ("volumetric_plastic_strain", Field::Scalar(&volumetric)),
            ("yielding", Field::Scalar(&out.yielding)),
            ("yield_state", Field::Scalar(&state)),
            ("stress", Field::SymTensor(&out.stress)),
        ],
    )
    .map_err(|e| io(&path, e))?;
    push_pvd(dir, entries, t, name)
}

/// The reactions on the nodes of the plots' `reaction_*` sets, node by node, after step
/// `res`: at a prescribed dof the force its support applies, `Bᵀσ − f − f_c` (the loads `f` at
/// the step's force factor, the self-weight on a pile's head say, and the contact forces `f_c`
/// on the node taken off); elsewhere `Bᵀσ`.
fn reactions<const D: usize>(
    sim: &PlasticSim<D>,
    res: &StepResult<D>,
    sets: &[Vec<usize>],
) -> CliResult<Vec<Reaction>>
where
    Dim<D>: StudyDim<D>,
{
    let mut out = Vec::new();
    if sets.iter().all(Vec::is_empty) {
        return Ok(out);
    }
    let body = sim.structure();
    // `K 0 − λ f = −λ f` at every prescribed dof (the plastic body holds the initial stress,
    // the elastic model none)
    let elastic = body.elastic();
    let zero = vec![[0.0; D]; elastic.mesh().node_count()];
    let loads = elastic
        .reactions(&zero, res.report.load_factor)
        .map_err(|e| fem_failed("reaction", e))?;
    // the contact forces on the nodes: on the contactor, `−w` times it on each target
    let mut contact = vec![[0.0; D]; elastic.mesh().node_count()];
    for (c, rec) in sim.candidates().iter().zip(&res.contacts) {
        let f = rec.force();
        for a in 0..D {
            contact[c.node][a] += f[a];
        }
        for &(t, w) in c.targets.iter().flatten() {
            for a in 0..D {
                contact[t][a] -= w * f[a];
            }
        }
    }
    for &n in sets.iter().flatten() {
        for c in Component::all::<D>() {
            let r = body
                .reaction(&[n], c)
                .map_err(|e| fem_failed("reaction", e))?;
            let held = loads.iter().find(|((m, k), _)| *m == n && *k == c);
            let r = match held {
                Some((_, minus_f)) => r + minus_f - contact[n][c as usize],
                None => r,
            };
            out.push(((n, c), r));
        }
    }
    Ok(out)
}

/// A step to time `t_end` of phase `p`, halved while its Newton does not converge (up to
/// `max_cuts` times): the last sub-step's result, with the iterations and cuts of all.
fn step<const D: usize>(
    study: &mut PlasticStudy<D>,
    p: usize,
    t_end: f64,
) -> Result<(StepResult<D>, usize, usize), CliError>
where
    Dim<D>: StudyDim<D>,
{
    let t_start = study.sim.time();
    let (mut cuts, mut iterations) = (0, 0);
    let mut fraction = 1.0_f64;
    let mut done = 0.0_f64;
    loop {
        let end = (done + fraction).min(1.0);
        let t = if end >= 1.0 {
            t_end
        } else {
            t_start + end * (t_end - t_start)
        };
        let factor = apply(study, p, t)?;
        match study.sim.step(t, factor) {
            Ok(res) => {
                iterations += res.report.newton.as_ref().map_or(0, |n| n.total_iterations);
                done = end;
                if end >= 1.0 {
                    return Ok((res, iterations, cuts));
                }
                fraction = (2.0 * fraction).min(1.0 - done);
            }
            Err(SolverError::NewtonNotConverged(f)) if cuts < study.newton.max_cuts => {
                iterations += f.iterations;
                cuts += 1;
                fraction *= 0.5;
                // a factorisation that failed in the attempt is not left behind: the tangent
                // at the committed state again (the next attempt's first solve uses it)
                if f.cause.is_some() {
                    study
                        .sim
                        .structure_mut()
                        .update_tangent()
                        .map_err(|e| fem_failed("the tangent at the last converged state", e))?;
                }
            }
            Err(e) => {
                // the supports back at the last converged state, which the outputs show
                let reached = study.sim.time();
                apply(study, p, reached)?;
                let mut err = step_error(e, &study.phases[p], t);
                err.message = format!(
                    "{} (after {cuts} cut(s) of the step to t = {t_end}; the outputs hold the \
                     last converged state, t = {reached}; raise [analysis.newton] \
                     `max_iterations` or `max_cuts`, or take more steps)",
                    err.message
                );
                return Err(err);
            }
        }
    }
}

/// Runs a plastic study; returns its summary (also written to `summary.json`).
pub fn run_plastic<const D: usize>(
    mut study: PlasticStudy<D>,
    opts: &RunOptions,
) -> CliResult<PlasticSummary>
where
    Dim<D>: PlasticRunDim<D>,
{
    let dir = &opts.out_dir;
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let start = Instant::now();
    let mut csv = create(dir, "steps.csv")?;
    let csv_path = dir.join("steps.csv");
    writeln!(
        csv,
        "step,phase,time,load_factor,newton_iterations,residual,cuts,contact_iterations,\
         closed_contacts,max_equivalent_plastic_strain,yielding_points,wall_time_s"
    )
    .map_err(|e| io(&csv_path, e))?;
    let mesh = study.model().mesh();
    let mut plots = Plots::of(&study.plots, &study.zone_names, |s| {
        mesh.node_set(s).ok().map(|s| s.to_vec())
    });
    let reaction_sets: Vec<Vec<usize>> = study
        .plots
        .iter()
        .flat_map(|p| p.curves.iter().chain(&p.x_quantity))
        .filter(|c| c.quantity.starts_with("reaction_"))
        .filter_map(|c| c.set.as_deref().and_then(|s| mesh.node_set(s).ok()))
        .map(<[usize]>::to_vec)
        .collect();
    let mut vtk = Vec::new();
    if study.output.vtk {
        write_vtk(&study.sim, dir, 0.0, &mut vtk)?;
    }
    let progress = Progress::new(study.total_steps(), opts.quiet);
    let every = study.output.every.max(1);
    let total = study.total_steps();
    let (mut global, mut contact_iterations, mut newton_total, mut max_newton) = (0, 0, 0, 0);
    let mut cuts_total = 0;
    let mut reports = Vec::new();
    let mut error: Option<CliError> = None;
    'phases: for p in 0..study.phases.len() {
        progress.begin_phase(&study.phases[p].name);
        for k in 1..=study.phases[p].steps {
            let t = study.phases[p].time(k);
            let step_start = Instant::now();
            let (res, iterations, cuts) = match step(&mut study, p, t) {
                Ok(r) => r,
                Err(mut e) => {
                    e.message = format!("step {} ({})", global + 1, e.message);
                    error = Some(e);
                    break 'phases;
                }
            };
            global += 1;
            let newton = res.report.newton.as_ref();
            let residuals = newton.map(|n| n.residuals.clone()).unwrap_or_default();
            max_newton = max_newton.max(newton.map_or(0, |n| n.iterations));
            newton_total += iterations;
            cuts_total += cuts;
            contact_iterations += res.report.contact_iterations;
            let body = study.sim.structure();
            let eps = body.element_outputs().equivalent_plastic_strain;
            let max_eps = eps.iter().copied().fold(0.0, f64::max);
            let (_, _, yielding, _) = plastic_fields(body);
            writeln!(
                csv,
                "{global},{},{},{},{iterations},{:?},{cuts},{},{},{max_eps:?},{yielding},{}",
                study.phases[p].name,
                res.report.time,
                res.report.load_factor,
                residuals.last().copied().unwrap_or(0.0),
                res.report.contact_iterations,
                res.report.closed_contacts,
                step_start.elapsed().as_secs_f64()
            )
            .map_err(|e| io(&csv_path, e))?;
            // a row per step as it comes (a long plastic run is watched through it)
            csv.flush().map_err(|e| io(&csv_path, e))?;
            let disp = study.sim.nodal_displacements();
            let r = reactions(&study.sim, &res, &reaction_sets)?;
            plots.record(
                (&res, Extras::default(), global),
                Some(&disp),
                Some(&r),
                Dim::<D>::u_t,
            );
            reports.push(StepFacts {
                step: global,
                time: res.report.time,
                load_factor: res.report.load_factor,
                iterations,
                cuts,
                residuals,
            });
            if study.output.vtk && (global.is_multiple_of(every) || global == total) {
                write_vtk(&study.sim, dir, res.report.time, &mut vtk)?;
            }
            progress.step(res.report.time, iterations, "newton");
        }
    }
    progress.finish();
    if error.is_some() && study.output.vtk && global > 0 {
        // the last converged state, if the series does not end there already
        let t = study.sim.time();
        if vtk.last().is_none_or(|(tv, _)| *tv != t) {
            write_vtk(&study.sim, dir, t, &mut vtk)?;
        }
    }
    csv.flush().map_err(|e| io(&csv_path, e))?;
    let mut files = vec!["summary.json".to_string(), "steps.csv".to_string()];
    let curves = plots.finish(&study.plots, dir, &mut files)?;
    if !vtk.is_empty() {
        files.push("mesh.pvd".into());
    }
    let body = study.sim.structure();
    let eps = body.element_outputs().equivalent_plastic_strain;
    let (_, _, yielding, apex) = plastic_fields(body);
    let summary = PlasticSummary {
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
        dimension: D,
        materials: study.materials.clone(),
        newton: NewtonFacts {
            tol: study.newton.tol,
            max_iterations: study.newton.max_iterations,
            max_cuts: study.newton.max_cuts,
        },
        steps: global,
        time: study.sim.time(),
        wall_time_s: start.elapsed().as_secs_f64(),
        newton_iterations: newton_total,
        max_newton_iterations: max_newton,
        cuts: cuts_total,
        contact_iterations,
        max_equivalent_plastic_strain: eps.iter().copied().fold(0.0, f64::max),
        yielding_points: yielding,
        apex_points: apex,
        points: body.committed_states().len(),
        step_reports: reports,
        curves,
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
