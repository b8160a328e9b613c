//! The outputs of a 3D run: `steps.csv` (one row per step: time, closed ("active") contacts,
//! iterations, the total contact force and each zone's Σ r_n; then the candidates of the
//! reduced problem, the path's counters and the support reactions), `contacts.csv` (one row per
//! contact and written step, its frame appended), the body's `mesh_NNNN.vtu` series with `mesh.pvd` (displacement, contact force
//! and pressure at the nodes, the element-mean stress), the interface's `interface_NNNN.vtu`
//! series with `interface.pvd` (`output.vtk`: one point per contact at its deformed position,
//! [`write_interface_vtu_3d`]), `pressure.csv` and `pressure.svg` (the recovered pressure
//! field, [`super::super::pressure`]; the VTK files then carry it too), and the zones' tally
//! for the summary; the `[[plots]]` curves ([`super::super::plots`]: `curves.csv` and the SVGs).

use super::super::errors::{create, fem_failed, io};
use super::super::plots::Plots;
use super::super::pressure::{PressureRecorder, zone_mass};
use super::super::summary::{CurveSummary, Peak, keep};
use crate::error::{CliError, CliResult};
use contact_laws::{ContactLaw, RccmState, StandardLaw};
use contact_solver::coupling::output::InterfaceSeries;
use contact_solver::coupling::solid::{
    SolidContactRecord, SolidContactSimulation, SolidStepResult, write_interface_vtu_3d,
};
use contact_solver::coupling::traction::{TractionField, write_interface_vtu_3d_with_traction};
use fem_core::boundary_mass::BoundaryMass;
use fem_core::solid::SolidModel;
use fem_core::vtk::{Field3, write_pvd, write_vtu_3d};
use serde::Serialize;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Per-zone results of a 3D run.
#[derive(Clone, Debug, Serialize)]
pub struct SolidZoneSummary {
    /// Name.
    pub name: String,
    /// The law in force at the end of the run (`laws` lists each phase's).
    pub law: String,
    /// Candidates.
    pub candidates: usize,
    /// Largest Σ r_n.
    pub max_force_n: Option<Peak>,
    /// Σ r_n at the end.
    pub final_force_n: f64,
    /// Σ of the contact forces (global frame) at the end.
    pub final_force: [f64; 3],
    /// Closed contacts at the end (`r̄_n > 0`; 2D's stick and slip).
    pub final_active: usize,
    /// Candidates of the reduced problem at the end (within the alert distance): closed or
    /// open.
    pub final_within_alert: usize,
    /// The law of each phase the run reached, with its global steps.
    pub laws: Vec<crate::build::PhaseLaw>,
}

/// One step's row of `steps.csv`.
pub(super) struct StepRow<'a> {
    pub(super) step: usize,
    pub(super) phase: &'a str,
    pub(super) time: f64,
    pub(super) wall_time_s: f64,
    /// Numeric factorisations of this step (K refactored, and the active set's).
    pub(super) factorizations: usize,
}

/// The writers of a 3D run.
pub(super) struct SolidRecorder {
    dir: PathBuf,
    steps: Option<BufWriter<File>>,
    contacts: Option<BufWriter<File>>,
    vtk: Option<Vec<(f64, String)>>,
    interface: Option<InterfaceSeries>,
    zones_filter: Option<Vec<usize>>,
    nodes_filter: Option<Vec<usize>>,
    pressure: PressureRecorder,
    /// The recovered traction goes into the VTK files (`output.pressure`).
    vtk_pressure: bool,
    pub(super) zones: Vec<SolidZoneSummary>,
    pub(super) files: Vec<String>,
    /// The `[[plots]]` curves.
    plots: Plots,
    /// The plots' specs.
    plot_specs: Vec<crate::scene::PlotSpec>,
    /// The support reactions `Σ R` (global axes) of the last step.
    pub(super) reaction: [f64; 3],
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

impl SolidRecorder {
    /// Creates `dir` and the CSV files asked for.
    pub(super) fn new(dir: &Path, study: &crate::build::SolidStudy) -> CliResult<Self> {
        std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
        let o = &study.output;
        let mut files = Vec::new();
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
        let zones_filter: Option<Vec<usize>> = o.zones.as_ref().map(|zs| {
            zs.iter()
                .filter_map(|z| study.zone_names.iter().position(|n| n == z))
                .collect()
        });
        let masses = if o.pressure || study.hertz.is_some() {
            let mesh = study.sim.structure().mesh();
            study
                .sim
                .zones()
                .iter()
                .map(|z| zone_mass(&z.name, BoundaryMass::on_nodes_3d(mesh, &z.contactor)))
                .collect::<CliResult<Vec<_>>>()?
        } else {
            vec![None; study.zone_names.len()]
        };
        let hertz = study
            .hertz
            .clone()
            .map(|h| (h, crate::build::HertzShape::Sphere { ring: 1.0 }));
        let pressure = PressureRecorder::new(
            dir,
            o.pressure,
            masses,
            zones_filter.clone(),
            hertz,
            (&["x", "y", "z"][..], &["t1", "t2"][..]),
            &mut files,
        )?;
        let candidates = study.sim.candidates();
        let zones = study
            .zone_names
            .iter()
            .enumerate()
            .map(|(z, name)| SolidZoneSummary {
                name: name.clone(),
                law: study.zone_laws[z].clone(),
                candidates: candidates.iter().filter(|c| c.zone == z).count(),
                max_force_n: None,
                final_force_n: 0.0,
                final_force: [0.0; 3],
                final_active: 0,
                final_within_alert: 0,
                laws: Vec::new(),
            })
            .collect();
        Ok(Self {
            dir: dir.to_path_buf(),
            steps,
            contacts,
            vtk: study.writes_vtk().then(Vec::new),
            interface: o.vtk.then(|| InterfaceSeries::new(dir, "interface")),
            zones_filter,
            nodes_filter: o.nodes.clone(),
            pressure,
            vtk_pressure: o.pressure,
            zones,
            files,
            plots: Plots::of(&study.plots, &study.zone_names, |_| None),
            plot_specs: study.plots.clone(),
            reaction: [0.0; 3],
        })
    }

    /// Records a step (its contacts and VTK file when `write`).
    pub(super) fn record(
        &mut self,
        sim: &SolidContactSimulation<SolidModel, StandardLaw>,
        res: &SolidStepResult,
        row: &StepRow<'_>,
        write: bool,
    ) -> CliResult<()> {
        let (t, step) = (row.time, row.step);
        let mut total_n = 0.0;
        let mut total = [0.0; 3];
        for (z, zs) in self.zones.iter_mut().enumerate() {
            let mine = res.contacts.iter().filter(|c| c.candidate.zone == z);
            let (mut f_n, mut f, mut closed, mut within) = (0.0, [0.0; 3], 0, 0);
            for c in mine {
                f_n += c.r[0];
                let g = c.force();
                (0..3).for_each(|a| f[a] += g[a]);
                closed += usize::from(c.closed);
                within += usize::from(c.active);
            }
            keep(&mut zs.max_force_n, f_n, step, t, true);
            zs.final_force_n = f_n;
            zs.final_force = f;
            zs.final_active = closed;
            zs.final_within_alert = within;
            total_n += f_n;
            (0..3).for_each(|a| total[a] += f[a]);
        }
        self.plots
            .record_3d(t, 1.0, step, |q, zone| plot_value(res, q, zone));
        // the nodal displacements, for the reactions and the VTK series
        let mesh = sim.structure().mesh();
        let u: Vec<[f64; 3]> = (0..mesh.node_count())
            .map(|n| sim.nodal_displacement(n))
            .collect();
        self.reaction = support_reaction(sim.structure(), &u)?;
        if let Some(w) = &mut self.steps {
            let mut text = format!(
                "{step},{},{t},1,{},{},{},{:e},{:e},{total_n:e},{:e},{:e},{:e}",
                field(row.phase),
                res.closed,
                res.contact_iterations,
                res.passes,
                res.residual,
                row.wall_time_s,
                total[0],
                total[1],
                total[2]
            );
            for z in &self.zones {
                text.push_str(&format!(",{:e}", z.final_force_n));
            }
            let r = self.reaction;
            text.push_str(&format!(
                ",{},{},{},{},{},{:e},{:e},{:e}",
                res.active,
                res.adhesion_iterations,
                u8::from(res.matrix_free),
                u8::from(res.active_set),
                row.factorizations,
                r[0],
                r[1],
                r[2]
            ));
            line(w, &self.dir, "steps.csv", &text)?;
        }
        if !write {
            return Ok(());
        }
        let selected: Vec<&SolidContactRecord> = res
            .contacts
            .iter()
            .filter(|c| {
                self.zones_filter
                    .as_ref()
                    .is_none_or(|z| z.contains(&c.candidate.zone))
            })
            .collect();
        if let Some(w) = &mut self.contacts {
            let model = sim.structure();
            let model_zones = sim.zones();
            for c in &selected {
                let cand = &c.candidate;
                if self
                    .nodes_filter
                    .as_ref()
                    .is_some_and(|n| !n.contains(&cand.node))
                {
                    continue;
                }
                let x = model.mesh().nodes()[cand.node];
                let f = c.force();
                let mut text = format!(
                    "{step},{t},{},{},{},{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{}",
                    field(&self.zones[cand.zone].name),
                    cand.node,
                    x[0],
                    x[1],
                    x[2],
                    u8::from(c.closed),
                    c.gap,
                    c.r[0],
                    c.r[1],
                    c.r[2],
                    cand.area,
                    c.pressure(),
                    c.slip[0],
                    c.slip[1],
                    f[0],
                    f[1],
                    f[2],
                    c.beta
                );
                text.push_str(&format!(",{}", u8::from(c.active)));
                for v in cand.frame().iter().flatten() {
                    text.push_str(&format!(",{v:e}"));
                }
                text.push_str(&format!(",{}", status(&model_zones[cand.zone].law, c)));
                line(w, &self.dir, "contacts.csv", &text)?;
            }
        }
        let vtk_any = self.vtk.is_some() || self.interface.is_some();
        let fields = if self.pressure.is_active() || (self.vtk_pressure && vtk_any) {
            self.pressure.record(
                step,
                t,
                |mass, zone| TractionField::from_records_3d(mass, zone, &res.contacts),
                |zone| {
                    res.contacts
                        .iter()
                        .filter(|c| c.candidate.zone == zone)
                        .map(|c| c.r[0])
                        .sum()
                },
                |node| mesh.nodes()[node].to_vec(),
                2,
            )?
        } else {
            Vec::new()
        };
        let fields = if self.vtk_pressure { &fields[..] } else { &[] };
        if !vtk_any {
            return Ok(());
        }
        if self.vtk.is_some() {
            self.write_vtk(sim, &selected, &u, t, fields)?;
        }
        if let Some(series) = &mut self.interface {
            let records: Vec<SolidContactRecord> = selected.iter().map(|c| **c).collect();
            series
                .write_step_with(t, |path| {
                    if fields.is_empty() {
                        write_interface_vtu_3d(path, &records, mesh.nodes(), Some(&u))
                    } else {
                        write_interface_vtu_3d_with_traction(
                            path,
                            &records,
                            mesh.nodes(),
                            Some(&u),
                            fields,
                        )
                    }
                })
                .map_err(|e| CliError::failed(format!("writing the interface VTK: {e}")))?;
        }
        Ok(())
    }

    /// One `mesh_NNNN.vtu` and the `.pvd` listing the series so far.
    fn write_vtk(
        &mut self,
        sim: &SolidContactSimulation<SolidModel, StandardLaw>,
        selected: &[&SolidContactRecord],
        u: &[[f64; 3]],
        t: f64,
        fields: &[TractionField],
    ) -> CliResult<()> {
        let model = sim.structure();
        let mesh = model.mesh();
        let mut force = vec![[0.0; 3]; mesh.node_count()];
        let mut pressure = vec![0.0; mesh.node_count()];
        for c in selected {
            let n = c.candidate.node;
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
        let Some(entries) = self.vtk.as_mut() else {
            return Ok(());
        };
        let name = format!("mesh_{:04}.vtu", entries.len());
        let path = self.dir.join(&name);
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
        write_vtu_3d(
            &path,
            mesh,
            &point,
            &[("stress", Field3::SymTensor(&stress))],
        )
        .map_err(|e| io(&path, e))?;
        entries.push((t, name));
        let list: Vec<(f64, &str)> = entries.iter().map(|(t, f)| (*t, f.as_str())).collect();
        let pvd = self.dir.join("mesh.pvd");
        write_pvd(&pvd, &list).map_err(|e| io(&pvd, e))
    }

    /// Flushes the CSV files and draws the Hertz plot; returns the files written (but
    /// `summary.json`).
    pub(super) fn finish(
        mut self,
        positions: &[[f64; 3]],
    ) -> CliResult<(Vec<String>, Vec<SolidZoneSummary>, Vec<CurveSummary>)> {
        self.pressure.finish(|n| positions[n], &mut self.files)?;
        let curves = self
            .plots
            .finish(&self.plot_specs, &self.dir, &mut self.files)?;
        for (w, name) in [
            (&mut self.steps, "steps.csv"),
            (&mut self.contacts, "contacts.csv"),
        ] {
            if let Some(w) = w {
                w.flush().map_err(|e| io(&self.dir.join(name), e))?;
            }
        }
        if self.vtk.as_ref().is_some_and(|e| !e.is_empty()) {
            self.files.push("mesh.pvd".into());
        }
        if self
            .interface
            .as_ref()
            .is_some_and(|s| s.pvd_path().exists())
        {
            self.files.push("interface.pvd".into());
        }
        Ok((self.files, self.zones, curves))
    }
}

/// The value of a 3D plot's `quantity` at this step, over `zone` (all zones: `None`); the
/// quantities are those [`crate::build`] lets through for 3D.
fn plot_value(res: &SolidStepResult, quantity: &str, zone: Option<usize>) -> f64 {
    let mine = || {
        res.contacts
            .iter()
            .filter(move |c| zone.is_none_or(|z| c.candidate.zone == z))
    };
    match quantity {
        "contact_iterations" => res.contact_iterations as f64,
        "adhesion_iterations" => res.adhesion_iterations as f64,
        // closed, as steps.csv's column; the reduced problem's size is `candidates`
        "active_contacts" => res.closed as f64,
        "candidates" => res.active as f64,
        "residual" => res.residual,
        "force_n" => mine().map(|c| c.r[0]).sum(),
        "closed" => mine().filter(|c| c.closed).count() as f64,
        "beta_mean" | "beta_min" => {
            let b: Vec<f64> = mine().map(|c| c.beta).collect();
            if b.is_empty() {
                f64::NAN
            } else if quantity == "beta_min" {
                b.iter().copied().fold(f64::INFINITY, f64::min)
            } else {
                b.iter().sum::<f64>() / b.len() as f64
            }
        }
        _ => f64::NAN,
    }
}

/// The status of a 3D contact, named as 2D's `InterfaceStatus`: `inactive` (outside the
/// reduced problem), `open` (`r̄ = 0`), `closed` (compressed under a frictionless law),
/// `stick` or `slip` (compressed under a law with friction: `slip` when the tangential reaction
/// is on the Coulomb cone `|r_t| = μ r_n`, to a relative 1e-6). With adhesion the reaction is
/// the total one (`r̄` plus the springs') and the cone the law's `μ f(β)`.
fn status(law: &StandardLaw, c: &SolidContactRecord) -> &'static str {
    if !c.active {
        return "inactive";
    }
    if !c.closed {
        return "open";
    }
    if !law.has_friction() {
        return "closed";
    }
    let state = RccmState::new(c.beta.clamp(0.0, 1.0)).unwrap_or(RccmState::ZERO);
    let mu = law.friction_coefficient(&state).unwrap_or(0.0);
    let r_t = c.r[1].hypot(c.r[2]);
    if r_t >= (1.0 - 1e-6) * mu * c.r[0] {
        "slip"
    } else {
        "stick"
    }
}

/// The sum of the support reactions `R = K u − f` over every prescribed dof, global axes: with
/// the applied loads and the contact forces it balances (the whole body's equilibrium).
fn support_reaction(model: &SolidModel, u: &[[f64; 3]]) -> CliResult<[f64; 3]> {
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
