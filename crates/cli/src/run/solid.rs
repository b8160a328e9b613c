//! The files of a 3D run ([`RunDim`] for `Dim<3>`): `steps.csv` (one row per step: time,
//! closed ("active") contacts, iterations, the total contact force and each zone's Σ r_n; then
//! the candidates of the reduced problem, the path's counters and the support reactions),
//! `contacts.csv` (one row per contact and written step, its frame appended), the body's
//! `mesh_NNNN.vtu` series with `mesh.pvd` (displacement, contact force and pressure at the
//! nodes, the element-mean stress), the interface's `interface_NNNN.vtu` series with
//! `interface.pvd` (`output.vtk`: one point per contact at its deformed position,
//! [`write_interface_vtu_3d`]), and the pressure on the zones' contactor faces.

use super::dim::{RunDim, Sim, StepRow, positions};
use super::errors::{create, fem_failed, io};
use super::pieces::Pieces;
use super::plots::Plots;
use super::pressure::PressureRecorder;
use super::rigid::RigidMotionSummary;
use super::summary::{CurveSummary, ZoneSummary};
use super::vtk::push_pvd;
use crate::build::{HertzShape, Study, StudyDim};
use crate::error::{CliError, CliResult};
use contact_laws::{ContactLaw, RccmState};
use contact_solver::coupling::output::InterfaceSeries;
use contact_solver::coupling::solid::write_interface_vtu_3d;
use contact_solver::coupling::traction::{TractionField, write_interface_vtu_3d_with_traction};
use contact_solver::{ContactRecord, StepResult};
use fem_core::boundary_mass::BoundaryMass;
use fem_core::vtk::{Field3, write_vtu_3d};
use fem_core::{Dim, ElasticModel, FemError};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The writers of a 3D run.
pub(crate) struct SolidWriters {
    dir: PathBuf,
    steps: Option<BufWriter<File>>,
    contacts: Option<BufWriter<File>>,
    vtk: Option<Vec<(f64, String)>>,
    interface: Option<InterfaceSeries>,
    nodes_filter: Option<Vec<usize>>,
    /// A distributed run's pieces of the mesh series (`mesh_NNNN.pvtu` in `mesh.pvd`).
    pieces: Option<Pieces>,
    /// The support reactions `Σ R` (global axes) of the last step.
    reaction: [f64; 3],
}

/// A text field of a CSV row, quoted when it holds a comma, a quote or a line break (RFC 4180).
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

fn line(w: &mut BufWriter<File>, dir: &Path, name: &str, text: &str) -> CliResult<()> {
    writeln!(w, "{text}").map_err(|e| io(&dir.join(name), e))
}

impl RunDim<3> for Dim<3> {
    type Writers = SolidWriters;

    fn writers(
        study: &Study<3>,
        dir: &Path,
        pieces: Option<Pieces>,
        files: &mut Vec<String>,
    ) -> CliResult<SolidWriters> {
        let o = &study.output;
        let steps = if o.report {
            let mut w = create(dir, "steps.csv")?;
            let mut head = String::from(
                "step,phase,time,load_factor,active_contacts,contact_iterations,passes,residual,\
                 wall_time_s,force_n,force_x,force_y,force_z",
            );
            for z in &study.zone_names {
                head.push_str(&format!(",{}", field(&format!("force_n:{z}"))));
            }
            head.push_str(
                ",candidates,adhesion_iterations,matrix_free,active_set,factorizations,\
                 reaction_x,reaction_y,reaction_z",
            );
            line(&mut w, dir, "steps.csv", &head)?;
            files.push("steps.csv".to_string());
            Some(w)
        } else {
            None
        };
        let contacts = if o.history {
            let mut w = create(dir, "contacts.csv")?;
            line(
                &mut w,
                dir,
                "contacts.csv",
                "step,time,zone,node,x,y,z,active,gap,r_n,r_t1,r_t2,area,pressure,slip_t1,\
                 slip_t2,f_x,f_y,f_z,beta,candidate,n_x,n_y,n_z,t1_x,t1_y,t1_z,t2_x,t2_y,t2_z,status",
            )?;
            files.push("contacts.csv".to_string());
            Some(w)
        } else {
            None
        };
        Ok(SolidWriters {
            dir: dir.to_path_buf(),
            steps,
            contacts,
            vtk: Dim::<3>::mesh_series(o).then(Vec::new),
            interface: o.vtk.then(|| InterfaceSeries::new(dir, "interface")),
            nodes_filter: o.nodes.clone(),
            pieces,
            reaction: [0.0; 3],
        })
    }

    const SHEAR: &'static [&'static str] = &["t1", "t2"];

    fn axes(_: &ElasticModel<3>) -> &'static [&'static str] {
        &["x", "y", "z"]
    }

    fn surface_mass(model: &ElasticModel<3>, nodes: &[usize]) -> Result<BoundaryMass, FemError> {
        BoundaryMass::on_nodes_3d(model.mesh(), nodes)
    }

    fn hertz_shape(_: &ElasticModel<3>) -> HertzShape {
        HertzShape::Sphere { ring: 1.0 }
    }

    fn step<L: ContactLaw<State = RccmState> + Clone>(
        w: &mut SolidWriters,
        plots: &mut Plots,
        sim: &Sim<L, 3>,
        (res, row, _): (&StepResult<3>, &StepRow<'_>, bool),
        zones: &[ZoneSummary<3>],
    ) -> CliResult<Option<Vec<[f64; 3]>>> {
        let (t, step) = (row.time, row.step);
        let mut total_n = 0.0;
        let mut total = [0.0; 3];
        for z in zones {
            total_n += z.final_force_n;
            (0..3).for_each(|a| total[a] += z.final_force[a]);
        }
        // the nodal displacements, for the reactions, the plots and the VTK series
        let mesh = sim.structure().mesh();
        let u: Vec<[f64; 3]> = (0..mesh.node_count())
            .map(|n| sim.nodal_displacement(n))
            .collect();
        plots.record((res, row.extras, step), Some(&u), None, |c| c.u_t[0]);
        w.reaction = support_reaction(sim.structure(), &u)?;
        if let Some(out) = &mut w.steps {
            let mut text = format!(
                "{step},{},{t},1,{},{},{},{:e},{:e},{total_n:e},{:e},{:e},{:e}",
                field(row.phase),
                res.report.closed_contacts,
                res.report.contact_iterations,
                res.report.detection_passes,
                res.report.residual,
                row.wall_time_s,
                total[0],
                total[1],
                total[2]
            );
            for z in zones {
                text.push_str(&format!(",{:e}", z.final_force_n));
            }
            let r = w.reaction;
            text.push_str(&format!(
                ",{},{},{},{},{},{:e},{:e},{:e}",
                res.report.active_contacts,
                res.report.adhesion_iterations,
                u8::from(res.report.matrix_free),
                u8::from(res.report.active_set),
                row.factorizations,
                r[0],
                r[1],
                r[2]
            ));
            line(out, &w.dir, "steps.csv", &text)?;
        }
        Ok(Some(u))
    }

    fn contacts<L: ContactLaw<State = RccmState> + Clone>(
        w: &mut SolidWriters,
        sim: &Sim<L, 3>,
        (_, row): (&StepResult<3>, &StepRow<'_>),
        selected: &[ContactRecord<3>],
        zones: &[ZoneSummary<3>],
    ) -> CliResult<()> {
        let Some(out) = &mut w.contacts else {
            return Ok(());
        };
        let (t, step) = (row.time, row.step);
        let model = sim.structure();
        let model_zones = sim.zones();
        for c in selected {
            if w.nodes_filter
                .as_ref()
                .is_some_and(|n| !n.contains(&c.node))
            {
                continue;
            }
            let x = model.mesh().nodes()[c.node];
            let f = c.force();
            let mut text = format!(
                "{step},{t},{},{},{},{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{}",
                field(&zones[c.zone].name),
                c.node,
                x[0],
                x[1],
                x[2],
                u8::from(c.is_closed()),
                c.gap,
                c.r.n,
                c.r.t[0],
                c.r.t[1],
                c.area,
                c.pressure(),
                c.slip_increment[0],
                c.slip_increment[1],
                f[0],
                f[1],
                f[2],
                c.beta
            );
            text.push_str(&format!(",{}", u8::from(c.is_active())));
            for v in c.frame().iter().flatten() {
                text.push_str(&format!(",{v:e}"));
            }
            text.push_str(&format!(",{}", status(&model_zones[c.zone].law, c)));
            line(out, &w.dir, "contacts.csv", &text)?;
        }
        Ok(())
    }

    fn vtk_active(w: &SolidWriters) -> bool {
        w.vtk.is_some() || w.interface.is_some()
    }

    fn vtk(
        w: &mut SolidWriters,
        model: &ElasticModel<3>,
        (t, selected, disp): (f64, &[ContactRecord<3>], Option<&[[f64; 3]]>),
        fields: &[TractionField],
    ) -> CliResult<()> {
        let u = disp.unwrap_or_default();
        if w.vtk.is_some() {
            write_vtk(w, model, selected, u, t, fields)?;
        }
        if let Some(series) = &mut w.interface {
            let nodes = model.mesh().nodes();
            series
                .write_step_with(t, |path| {
                    if fields.is_empty() {
                        write_interface_vtu_3d(path, selected, nodes, Some(u))
                    } else {
                        write_interface_vtu_3d_with_traction(path, selected, nodes, Some(u), fields)
                    }
                })
                .map_err(|e| CliError::failed(format!("writing the interface VTK: {e}")))?;
        }
        Ok(())
    }

    fn reaction(w: &SolidWriters) -> Option<[f64; 3]> {
        Some(w.reaction)
    }

    fn finish(
        mut w: SolidWriters,
        (plots, pressure): (&Plots, PressureRecorder),
        study: &Study<3>,
        dir: &Path,
        files: &mut Vec<String>,
    ) -> CliResult<(Vec<CurveSummary>, Vec<RigidMotionSummary>)> {
        let positions = positions(study);
        pressure.finish(|n| positions[n], files)?;
        let curves = plots.finish(&study.plots, dir, files)?;
        for (out, name) in [
            (&mut w.steps, "steps.csv"),
            (&mut w.contacts, "contacts.csv"),
        ] {
            if let Some(out) = out {
                out.flush().map_err(|e| io(&dir.join(name), e))?;
            }
        }
        if w.vtk.as_ref().is_some_and(|e| !e.is_empty()) {
            files.push("mesh.pvd".into());
        }
        if w.interface.as_ref().is_some_and(|s| s.pvd_path().exists()) {
            files.push("interface.pvd".into());
        }
        Ok((curves, Vec::new()))
    }
}

/// One `mesh_NNNN.vtu` and the `.pvd` listing the series so far.
fn write_vtk(
    w: &mut SolidWriters,
    model: &ElasticModel<3>,
    selected: &[ContactRecord<3>],
    u: &[[f64; 3]],
    t: f64,
    fields: &[TractionField],
) -> CliResult<()> {
    let mesh = model.mesh();
    let mut force = vec![[0.0; 3]; mesh.node_count()];
    let mut pressure = vec![0.0; mesh.node_count()];
    for c in selected {
        let n = c.node;
        let f = c.force();
        (0..3).for_each(|a| force[n][a] += f[a]);
        pressure[n] += c.pressure();
    }
    let stress: Vec<[f64; 6]> = model
        .elastic_stresses(u)
        .map_err(|e| fem_failed("stresses", e))?
        .iter()
        .map(|points| {
            let mut mean = [0.0; 6];
            for (_, s) in points {
                (0..6).for_each(|k| mean[k] += s[k] / points.len() as f64);
            }
            mean
        })
        .collect();
    let Some(entries) = w.vtk.as_mut() else {
        return Ok(());
    };
    let stem = format!("mesh_{:04}", entries.len());
    // the recovered pressure on the contactor surfaces (0 elsewhere)
    let mut field = vec![0.0; mesh.node_count()];
    for f in fields {
        for (&n, &p) in f.nodes.iter().zip(&f.pressure) {
            field[n] += p;
        }
    }
    let mut point = vec![
        ("u", Field3::Vector(u)),
        ("contact_force", Field3::Vector(&force)),
        ("contact_pressure", Field3::Scalar(&pressure)),
    ];
    if !fields.is_empty() {
        point.push(("pressure_field", Field3::Scalar(&field)));
    }
    let cell = [("stress", Field3::SymTensor(&stress))];
    let name = match &w.pieces {
        Some(pieces) => pieces.write(&stem, mesh, &point, &cell)?,
        None => {
            let name = format!("{stem}.vtu");
            let path = w.dir.join(&name);
            write_vtu_3d(&path, mesh, &point, &cell).map_err(|e| io(&path, e))?;
            name
        }
    };
    push_pvd(&w.dir, entries, t, name)
}

/// The status of a 3D contact, named as 2D's `InterfaceStatus`: `inactive` (outside the
/// reduced problem), `open` (`r̄ = 0`), `closed` (compressed under a frictionless law),
/// `stick` or `slip` (compressed under a law with friction: `slip` when the tangential reaction
/// is on the Coulomb cone `|r_t| = μ r_n`, to a relative 1e-6). With adhesion the reaction is
/// the total one (`r̄` plus the springs') and the cone the law's `μ f(β)`.
fn status<L: ContactLaw<State = RccmState>>(law: &L, c: &ContactRecord<3>) -> &'static str {
    if !c.is_active() {
        return "inactive";
    }
    if !c.is_closed() {
        return "open";
    }
    if !law.has_friction() {
        return "closed";
    }
    let state = RccmState::new(c.beta.clamp(0.0, 1.0)).unwrap_or(RccmState::ZERO);
    let mu = law.friction_coefficient(&state).unwrap_or(0.0);
    let r_t = c.r.t[0].hypot(c.r.t[1]);
    if r_t >= (1.0 - 1e-6) * mu * c.r.n {
        "slip"
    } else {
        "stick"
    }
}

/// The sum of the support reactions `R = K u − f` over every prescribed dof, global axes: with
/// the applied loads and the contact forces it balances (the whole body's equilibrium).
fn support_reaction(model: &ElasticModel<3>, u: &[[f64; 3]]) -> CliResult<[f64; 3]> {
    let mut total = [0.0; 3];
    for ((_, c), r) in model
        .reactions(u, 1.0)
        .map_err(|e| fem_failed("support reactions", e))?
    {
        total[c as usize] += r;
    }
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn field_quotes_commas_and_quotes_works() {
        assert_eq!(field("floor"), "floor");
        assert_eq!(field("a,b"), "\"a,b\"");
        assert_eq!(field("say \"hi\""), "\"say \"\"hi\"\"\"");
    }
}
