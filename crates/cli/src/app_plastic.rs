//! `bipo run` and `bipo check` of a scene with a plastic material (issue 40): the header
//! (mesh, materials, the Newton's settings, zones), the run ([`crate::run::run_plastic`]) and
//! its closing lines.

use crate::app_dynamic::Parallelism;
use crate::build::{self, PlasticStudy, StudyDim};
use crate::error::CliResult;
use crate::out;
use crate::run::{self, PlasticRunDim};
use fem_core::{Dim, Structure};
use std::path::PathBuf;

/// `bipo run` of a built plastic study.
pub(crate) fn run_study<const D: usize>(
    study: PlasticStudy<D>,
    loaded: &build::Loaded,
    out: Option<PathBuf>,
    quiet: bool,
    (threads, parallelism): (Option<u16>, Parallelism),
) -> CliResult<()>
where
    Dim<D>: PlasticRunDim<D>,
{
    let dofs = study.sim.structure().dof_count();
    faer::set_global_parallelism(parallelism(threads, Some(dofs)));
    let opts = run::RunOptions::new(out, study.output.dir.as_deref(), &loaded.path, quiet);
    header("run", loaded, &study);
    let s = run::run_plastic(study, &opts)?;
    out::outln!(
        "done: {} steps in {:.3} s (t = {}), {} Newton iterations (at most {} in one solve of a \
         step or sub-step), {} cut(s), {} contact iterations",
        s.steps,
        s.wall_time_s,
        s.time,
        s.newton_iterations,
        s.max_newton_iterations,
        s.cuts,
        s.contact_iterations
    );
    out::outln!(
        "  plastic: {} of {} points yielding in the last step ({} at the apex), largest \
         equivalent plastic strain {:.6e}",
        s.yielding_points,
        s.points,
        s.apex_points,
        s.max_equivalent_plastic_strain
    );
    for c in &s.curves {
        if let Some(last) = c.last {
            out::outln!("  curve `{}` ({}): last {last:.6e}", c.label, c.plot);
        }
    }
    out::outln!(
        "  outputs in {}: {}",
        opts.out_dir.display(),
        s.files.join(", ")
    );
    Ok(())
}

/// `bipo check` of a built plastic study: its header; returns its steps and files.
pub(crate) fn check_study<const D: usize>(
    study: &PlasticStudy<D>,
    loaded: &build::Loaded,
) -> (usize, usize)
where
    Dim<D>: StudyDim<D>,
{
    header("check", loaded, study);
    (study.total_steps(), study.output_files())
}

/// The header: the scene, its mesh, the materials, the Newton, the zones.
fn header<const D: usize>(cmd: &str, loaded: &build::Loaded, study: &PlasticStudy<D>)
where
    Dim<D>: StudyDim<D>,
{
    let body = study.sim.structure();
    let mesh = body.elastic().mesh();
    out::outln!(
        "bipo {cmd}: {} — {} (plastic {}D scene)",
        loaded.path.display(),
        study.title,
        D
    );
    let setting = Dim::<D>::setting(body.elastic())
        .map(|s| format!("; {s}"))
        .unwrap_or_default();
    out::outln!(
        "  mesh: {} nodes, {} elements, {}{setting}; {} free dofs, {} material points",
        mesh.node_count(),
        mesh.element_count(),
        build::kind_name(mesh.kind()),
        body.dof_count(),
        body.committed_states().len()
    );
    let materials: Vec<String> = study
        .materials
        .iter()
        .map(|(r, k)| format!("region {r} {k}"))
        .collect();
    let n = &study.newton;
    out::outln!(
        "  materials: {}; Newton: tol {:e}, at most {} iterations per step, {} cut(s)",
        materials.join(", "),
        n.tol,
        n.max_iterations,
        n.max_cuts
    );
    for (z, name) in study.zone_names.iter().enumerate() {
        let c = study
            .sim
            .candidates()
            .iter()
            .filter(|c| c.zone == z)
            .count();
        out::outln!("  zone `{name}` ({}): {c} candidates", study.zone_laws[z]);
    }
    for w in &study.warnings {
        out::outln!("warning: {w}");
    }
}
