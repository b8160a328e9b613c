//! The checks of `[output]` and `[[plots]]` against the built study: steps in range, zones and
//! contactor nodes that exist, plot files, and what each plotted quantity needs.

use super::checks::{at_least, list_names, node_set};
use super::study::{Body, Study, StudyDim};
use crate::error::{CliResult, KeyPath, bail, err};
use crate::scene::{CurveSpec, OutputSpec, PlotSpec, Scene};
use fem_core::Component;
use fem_core::Dim;
use std::collections::BTreeSet;

/// Quantities of the plots: (name, needs).
pub const QUANTITIES: &[(&str, &str)] = &[
    ("force_n", "zone"),
    ("force_t", "zone"),
    ("beta_mean", "zone"),
    ("beta_min", "zone"),
    ("closed", "zone"),
    ("gap", "node"),
    ("u_t", "node"),
    ("beta", "node"),
    ("r_n", "node"),
    ("r_t", "node"),
    ("u_x", "point"),
    ("u_y", "point"),
    ("reaction_x", "set"),
    ("reaction_y", "set"),
    ("contact_iterations", "step"),
    ("adhesion_iterations", "step"),
    ("active_contacts", "step"),
    ("candidates", "step"),
    ("residual", "step"),
    ("head_load", "pile"),
    ("head_displacement", "pile"),
];

/// The quantities a 3D run plots: the step's counters and, per zone, Σ r_n, the closed
/// contacts and β (mean, least).
pub(super) const QUANTITIES_3D: &[&str] = &[
    "force_n",
    "beta_mean",
    "beta_min",
    "closed",
    "contact_iterations",
    "adhesion_iterations",
    "active_contacts",
    "candidates",
    "residual",
];

/// Checks `[output]` and the plots of `scene` against `study`, and keeps the plots.
pub(super) fn check_outputs(scene: &Scene, study: &mut Study) -> CliResult<()> {
    let node_count = study.model().mesh().node_count();
    check_output_table(
        &study.output,
        study.total_steps(),
        &study.zone_names,
        &|n| study.candidates().iter().any(|c| c.node == n),
        node_count,
    )?;
    check_profile_steps(&study.output, study)?;
    let plane_stress = matches!(
        fem_core::Structure::idealization(study.model()),
        fem_core::Idealization::PlaneStress { .. }
    );
    study.hertz = super::hertz::check(scene, &study.zone_names, 2, |e, nu| {
        if plane_stress { e } else { e / (1.0 - nu * nu) }
    })?;
    study.plots = check_plots(&scene.plots, &study.zone_names, Some(study))?;
    check_file_count(study)
}

/// Checks `[[plots]]` (each file, then each curve's quantity and what it needs) of a scene with
/// these zones, and gives them. `study`: a 2D scene's, whose contactor nodes, node sets,
/// supports and preset the node, point, set and pile quantities need; without it (a 3D
/// scene), only [`QUANTITIES_3D`] are plotted (what a 3D run records).
pub(super) fn check_plots(
    plots: &[PlotSpec],
    zone_names: &[String],
    study: Option<&Study>,
) -> CliResult<Vec<PlotSpec>> {
    let mut files = BTreeSet::new();
    for (i, plot) in plots.iter().enumerate() {
        let pp = KeyPath::root().key("plots").index(i);
        check_plot_file(&pp, plot, &mut files)?;
        for (k, c) in plot.curves.iter().enumerate() {
            check_curve(&pp.key("curves").index(k), c, zone_names, study)?;
        }
        if let Some(c) = &plot.x_quantity {
            check_curve(&pp.key("x_quantity"), c, zone_names, study)?;
        }
    }
    Ok(plots.to_vec())
}

/// Checks plot `pp`'s file (an `.svg` name, not used twice: `files` holds those seen) and that
/// it has curves (2D and 3D scenes).
pub(super) fn check_plot_file(
    pp: &KeyPath,
    plot: &PlotSpec,
    files: &mut BTreeSet<String>,
) -> CliResult<()> {
    if !plot.file.ends_with(".svg") || plot.file.contains(['/', '\\']) {
        bail!(
            pp.key("file"),
            "`{}` = \"{}\": expected a file name ending in .svg (written in the output directory)",
            pp.key("file"),
            plot.file
        );
    }
    if !files.insert(plot.file.clone()) {
        bail!(pp.key("file"), "plot file `{}` is used twice", plot.file);
    }
    if plot.curves.is_empty() {
        bail!(pp.key("curves"), "a plot needs at least one curve");
    }
    Ok(())
}

/// Checks `[output]` (`every`, `steps`, `zones`, `nodes`) for a run of `total` steps with
/// these zones; `is_contactor(n)` says whether node `n` is a contactor of some zone.
pub(super) fn check_output_table(
    o: &OutputSpec,
    total: usize,
    zone_names: &[String],
    is_contactor: &dyn Fn(usize) -> bool,
    node_count: usize,
) -> CliResult<()> {
    let op = KeyPath::root().key("output");
    at_least(&op.key("every"), o.every, 1)?;
    if o.steps.is_some() && o.every != 1 {
        let p = op.key("every");
        bail!(
            p,
            "`{p}` = {}: give `output.every` or `output.steps`, not both",
            o.every
        );
    }
    if let Some(steps) = &o.steps {
        for (i, s) in steps.iter().enumerate() {
            if *s < 1 || *s > total {
                let p = op.key("steps").index(i);
                bail!(p, "`{p}` = {s}: expected a step in 1..={total}");
            }
        }
    }
    if let Some(zs) = &o.zones {
        for (i, z) in zs.iter().enumerate() {
            zone_index(&op.key("zones").index(i), zone_names, z)?;
        }
    }
    if let Some(ns) = &o.nodes {
        for (i, n) in ns.iter().enumerate() {
            if !is_contactor(*n) {
                let p = op.key("nodes").index(i);
                bail!(
                    p,
                    "`{p}` = {n}: not a contactor node of any zone (the mesh has {node_count} nodes)"
                );
            }
        }
    }
    Ok(())
}

/// The most files a run may write (the VTK series dominate: one `.vtu` per written step).
pub const MAX_OUTPUT_FILES: usize = 100_000;

/// Refuses a run that would write more than [`MAX_OUTPUT_FILES`] files, at the key that
/// chooses the written steps.
pub(super) fn check_file_count<const D: usize>(study: &Study<D>) -> CliResult<()>
where
    Dim<D>: StudyDim<D>,
{
    let files = study.output_files();
    if files <= MAX_OUTPUT_FILES {
        return Ok(());
    }
    let o = &study.output;
    let op = KeyPath::root().key("output");
    let key = if o.steps.is_some() { "steps" } else { "every" };
    let p = op.key(key);
    bail!(
        p,
        "`{p}`: the run would write {files} files ({} written steps of {} steps, each with {} VTK \
             file(s)): more than the limit of {MAX_OUTPUT_FILES}; raise `output.every`, list \
             `output.steps`, or set `output.vtk` / `output.mesh_vtk` = false",
        study.written_steps(),
        study.total_steps(),
        usize::from(o.vtk) + usize::from(Dim::<D>::mesh_series(o))
    )
}

/// `output.profile_steps`: the pile preset's only, each a step of the run.
fn check_profile_steps(o: &OutputSpec, study: &Study) -> CliResult<()> {
    let Some(list) = &o.profile_steps else {
        return Ok(());
    };
    let p = KeyPath::root().key("output").key("profile_steps");
    if !matches!(&study.body, Body::Preset(b) if b.kind == "pile") {
        bail!(
            p,
            "`{p}`: shaft profiles are written by the pile preset only ([preset] kind = \"pile\")"
        );
    }
    let total = study.total_steps();
    if let Some(s) = list.iter().find(|&&s| s == 0 || s > total) {
        bail!(p, "`{p}`: step {s} is not a step of the run (1 to {total})");
    }
    Ok(())
}

pub fn zone_index(path: &KeyPath, names: &[String], name: &str) -> CliResult<usize> {
    names.iter().position(|n| n == name).ok_or_else(|| {
        err!(
            path,
            "`{path}` = \"{name}\": no such contact zone (zones: {})",
            list_names(names.iter().map(|s| s.as_str()))
        )
    })
}

/// Checks one curve (or abscissa) of a plot: its quantity and what that quantity needs (see
/// [`check_plots`] for `study`).
fn check_curve(
    p: &KeyPath,
    c: &CurveSpec,
    zone_names: &[String],
    study: Option<&Study>,
) -> CliResult<()> {
    let known = QUANTITIES.iter().find(|(q, _)| *q == c.quantity);
    if study.is_none() {
        check_curve_3d(p, c, known.is_some())?;
    }
    let Some((_, needs)) = known else {
        let q = p.key("quantity");
        bail!(
            q,
            "`{q}` = \"{}\": unknown quantity (expected one of {})",
            c.quantity,
            QUANTITIES
                .iter()
                .map(|(q, _)| *q)
                .collect::<Vec<_>>()
                .join(", ")
        );
    };
    let zone = match &c.zone {
        Some(z) => Some(zone_index(&p.key("zone"), zone_names, z)?),
        None => None,
    };
    if *needs == "zone" && zone.is_none() && zone_names.len() > 1 {
        bail!(
            p,
            "`{p}`: quantity `{}` needs `zone` (the scene has several zones)",
            c.quantity
        );
    }
    let Some(study) = study else {
        return Ok(());
    };
    let mesh = study.model().mesh();
    match *needs {
        "node" => {
            let Some(n) = c.node else {
                bail!(
                    p,
                    "`{p}`: quantity `{}` needs `node` (a contactor node)",
                    c.quantity
                );
            };
            if !study
                .candidates()
                .iter()
                .any(|k| k.node == n && zone.is_none_or(|z| z == k.zone))
            {
                let q = p.key("node");
                bail!(
                    q,
                    "`{q}` = {n}: not a contactor node{} (the mesh has {} nodes)",
                    zone.map(|z| format!(" of zone `{}`", study.zone_names[z]))
                        .unwrap_or_default(),
                    mesh.node_count()
                );
            }
        }
        "point" => match (c.node, &c.set) {
            (Some(n), None) => {
                if n >= mesh.node_count() {
                    let q = p.key("node");
                    bail!(
                        q,
                        "`{q}` = {n}: the mesh has {} nodes (0..{})",
                        mesh.node_count(),
                        mesh.node_count()
                    );
                }
            }
            (None, Some(s)) => {
                node_set(&p.key("set"), mesh, s)?;
            }
            _ => {
                bail!(
                    p,
                    "`{p}`: quantity `{}` needs `node` or `set` (one of them)",
                    c.quantity
                );
            }
        },
        "pile" if !matches!(&study.body, Body::Preset(p) if p.kind == "pile") => {
            bail!(
                p.key("quantity"),
                "`{}` = \"{}\": only the pile preset has this quantity",
                p.key("quantity"),
                c.quantity
            );
        }
        "set" => {
            let Some(s) = &c.set else {
                bail!(
                    p,
                    "`{p}`: quantity `{}` needs `set` (a supported node set)",
                    c.quantity
                );
            };
            let nodes = node_set(&p.key("set"), mesh, s)?;
            let comp = if c.quantity == "reaction_x" {
                Component::X
            } else {
                Component::Y
            };
            let supports = study.model().supports();
            let any = nodes.iter().any(|&n| supports.value(n, comp).is_some())
                || matches!(&study.body, Body::Custom(cu) if cu.supports.iter().any(|s| s.components.contains(&comp) && s.nodes.iter().any(|n| nodes.contains(n))));
            if !any {
                let q = p.key("set");
                bail!(
                    q,
                    "`{q}` = \"{s}\": no node of this set has a support on {comp:?}, so it has no reaction"
                );
            }
        }
        _ => {}
    }
    Ok(())
}

/// What a 3D scene refuses of a curve: a quantity a 3D run does not record (`known`: one of
/// [`QUANTITIES`]), a node or a set.
fn check_curve_3d(p: &KeyPath, c: &CurveSpec, known: bool) -> CliResult<()> {
    if !QUANTITIES_3D.contains(&c.quantity.as_str()) {
        let q = p.key("quantity");
        let what = if known {
            "not available in a 3D scene"
        } else {
            "unknown quantity"
        };
        bail!(
            q,
            "`{q}` = \"{}\": {what} (3D plots: {})",
            c.quantity,
            QUANTITIES_3D.join(", ")
        );
    }
    for (key, given) in [("node", c.node.is_some()), ("set", c.set.is_some())] {
        if given {
            let k = p.key(key);
            bail!(
                k,
                "`{k}`: a 3D plot's quantities are per step or per zone, not per {key}"
            );
        }
    }
    Ok(())
}
