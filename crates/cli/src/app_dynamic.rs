//! `bipo run` and `bipo check` of a dynamic scene (`[analysis] dynamic = true`, issue 39): the
//! header (mesh, time stepping, zones with their restitution), the run
//! ([`crate::run::run_dynamic`]) and its closing lines.

use crate::build::{self, DynamicStudy, StudyDim};
use crate::error::CliResult;
use crate::out;
use crate::run;
use fem_core::{Dim, Structure};
use std::path::PathBuf;

/// How `bipo run` chooses faer's parallelism from `--threads` and the dof count (the app's
/// rule, handed in so that the imports go one way).
pub(crate) type Parallelism = fn(Option<u16>, Option<usize>) -> faer::Par;

/// `bipo run` of a built dynamic study.
pub(crate) fn run_study<const D: usize>(
    study: DynamicStudy<D>,
    loaded: &build::Loaded,
    out: Option<PathBuf>,
    quiet: bool,
    (threads, parallelism): (Option<u16>, Parallelism),
) -> CliResult<()>
where
    Dim<D>: StudyDim<D>,
{
    let dofs = study.sim.structure().dof_count();
    faer::set_global_parallelism(parallelism(threads, Some(dofs)));
    let opts = run::RunOptions::new(out, study.output.dir.as_deref(), &loaded.path, quiet);
    header("run", loaded, &study);
    let s = run::run_dynamic(study, &opts)?;
    let e = &s.energy;
    out::outln!(
        "done: {} steps in {:.3} s (t = {}), {} contact iterations; energy: kinetic {:.6e}, \
         strain {:.6e}, work of the loads {:.6e}, dissipated by impact {:.6e}, friction \
         {:.6e}, damage {:.6e}, damping {:.6e}, scheme {:.6e}, in adhesive springs {:.6e}; \
         balance residual {:.1e} (relative, largest over the run)",
        s.steps,
        s.wall_time_s,
        s.time,
        s.contact_iterations,
        e.kinetic,
        e.strain,
        e.external_work,
        e.impact,
        e.friction,
        e.damage,
        e.damping,
        e.numerical,
        e.interface,
        s.max_residual_relative
    );
    for z in &s.zones {
        out::outln!(
            "  zone `{}`: peak normal force {:.6e}, {} steps in contact{}",
            z.name,
            z.peak_normal_force,
            z.contact_steps,
            match (z.first_contact_time, z.last_contact_time) {
                (Some(a), Some(b)) => format!(" (t {a} → {b})"),
                _ => String::new(),
            }
        );
    }
    out::outln!(
        "  outputs in {}: {}",
        opts.out_dir.display(),
        s.files.join(", ")
    );
    Ok(())
}

/// `bipo check` of a built dynamic study: its header; returns its steps and files.
pub(crate) fn check_study<const D: usize>(
    study: &DynamicStudy<D>,
    loaded: &build::Loaded,
) -> (usize, usize)
where
    Dim<D>: StudyDim<D>,
{
    header("check", loaded, study);
    (study.spec.steps, study.output_files())
}

/// The header: the scene, its mesh, the time stepping, the zones.
fn header<const D: usize>(cmd: &str, loaded: &build::Loaded, study: &DynamicStudy<D>)
where
    Dim<D>: StudyDim<D>,
{
    let body = study.sim.structure();
    let mesh = body.model().mesh();
    out::outln!(
        "bipo {cmd}: {} — {} (dynamic {}D scene)",
        loaded.path.display(),
        study.title,
        D
    );
    let setting = Dim::<D>::setting(body.model())
        .map(|s| format!("; {s}"))
        .unwrap_or_default();
    out::outln!(
        "  mesh: {} nodes, {} elements, {}{setting}; {} free dofs",
        mesh.node_count(),
        mesh.element_count(),
        build::kind_name(mesh.kind()),
        body.dof_count()
    );
    let s = &study.spec;
    out::outln!(
        "  Moreau–Jean: {} steps of h = {} to t = {}, θ = {}, {} mass, Rayleigh α = {}, β = {}",
        s.steps,
        s.time_step,
        s.end_time,
        s.theta,
        s.mass.name(),
        s.alpha,
        s.beta
    );
    for (z, name) in study.zone_names.iter().enumerate() {
        let c = study
            .sim
            .candidates()
            .iter()
            .filter(|c| c.zone == z)
            .count();
        out::outln!(
            "  zone `{name}` ({}, restitution {}): {c} candidates",
            study.zone_laws[z],
            study.restitution[z]
        );
    }
    for w in &study.warnings {
        out::outln!("warning: {w}");
    }
}
