//! The plotted curves: one value per step of each `[[plots]]` curve (and abscissa), written
//! at the end as `curves.csv` and one SVG per plot, with their extremes for the summary. The
//! curves are those of a 2D or a 3D run (the 3D scene lets through the quantities it has).

use super::driver::Extras;
use super::errors::io;
use super::summary::{CurveSummary, keep};
use crate::build::{Study, StudyDim};
use crate::error::CliResult;
use crate::plot;
use crate::scene::{CurveSpec, PlotSpec, XAxis};
use contact_solver::coupling::space::ContactSpace;
use contact_solver::{ContactRecord, StepResult};
use fem_core::{Component, Dim};
use std::path::Path;

/// One curve of a plot, with its values so far.
struct CurveRt {
    plot: usize,
    /// The abscissa of its plot rather than a curve.
    is_x: bool,
    label: String,
    spec: CurveSpec,
    zone: Option<usize>,
    set_nodes: Vec<usize>,
    values: Vec<f64>,
}

/// The curves of every plot and the three abscissae (time, step, load factor) of every step.
pub(crate) struct Plots {
    curves: Vec<CurveRt>,
    x_time: Vec<f64>,
    x_step: Vec<f64>,
    x_load: Vec<f64>,
}

impl Plots {
    /// The curves of the study's plots, with their labels, zones and node sets resolved.
    pub(super) fn new<const D: usize>(study: &Study<D>) -> Self
    where
        Dim<D>: StudyDim<D>,
    {
        Self::of(&study.plots, &study.zone_names, |s| {
            study.model().mesh().node_set(s).ok().map(|s| s.to_vec())
        })
    }

    /// The curves of `plots` for a run with these zones; `node_set` gives a set's nodes.
    pub(super) fn of(
        plots: &[PlotSpec],
        zone_names: &[String],
        node_set: impl Fn(&str) -> Option<Vec<usize>>,
    ) -> Self {
        let mut curves = Vec::new();
        for (i, p) in plots.iter().enumerate() {
            let all = p
                .curves
                .iter()
                .map(|c| (c, false))
                .chain(p.x_quantity.iter().map(|c| (c, true)));
            for (c, is_x) in all {
                let zone = c
                    .zone
                    .as_ref()
                    .and_then(|z| zone_names.iter().position(|n| n == z))
                    .or(if zone_names.len() == 1 { Some(0) } else { None });
                let set_nodes = c.set.as_deref().and_then(&node_set).unwrap_or_default();
                let label = c.label.clone().unwrap_or_else(|| {
                    let mut l = c.quantity.clone();
                    if let Some(z) = &c.zone {
                        l.push_str(&format!(" ({z})"));
                    }
                    if let Some(n) = c.node {
                        l.push_str(&format!(" node {n}"));
                    }
                    if let Some(s) = &c.set {
                        l.push_str(&format!(" [{s}]"));
                    }
                    l
                });
                curves.push(CurveRt {
                    plot: i,
                    is_x,
                    label,
                    spec: c.clone(),
                    zone,
                    set_nodes,
                    values: Vec::new(),
                });
            }
        }
        Self {
            curves,
            x_time: Vec::new(),
            x_step: Vec::new(),
            x_load: Vec::new(),
        }
    }

    /// Whether a curve needs the nodal displacements of every step.
    pub(super) fn needs_displacements(&self) -> bool {
        self.curves.iter().any(|c| {
            matches!(
                c.spec.quantity.as_str(),
                "u_x" | "u_y" | "u_z" | "reaction_x" | "reaction_y" | "reaction_z"
            )
        })
    }

    /// Whether a curve needs the support reactions of every step.
    pub(super) fn needs_reactions(&self) -> bool {
        self.curves
            .iter()
            .any(|c| c.spec.quantity.starts_with("reaction"))
    }

    pub(super) fn steps(&self) -> usize {
        self.x_time.len()
    }

    /// The values of global step `global` (`u_t`: a contact's tangential relative
    /// displacement along its first tangent).
    pub(super) fn record<const D: usize>(
        &mut self,
        (res, extras, global): (&StepResult<D>, Extras, usize),
        disp: Option<&[[f64; D]]>,
        reactions: Option<&[fem_core::Reaction]>,
        u_t: fn(&ContactRecord<D>) -> f64,
    ) where
        Dim<D>: ContactSpace<D>,
    {
        let (time, load) = (res.report.time, res.report.load_factor);
        self.record_with(time, load, global, |c| match c.spec.quantity.as_str() {
            "head_load" => extras.head_load.unwrap_or(f64::NAN),
            "head_displacement" => extras.head_displacement.unwrap_or(f64::NAN),
            _ => curve_value(c, res, (disp, reactions), u_t),
        });
    }

    /// Records global step `global`: `value(curve)` gives each curve's value.
    fn record_with(
        &mut self,
        time: f64,
        load_factor: f64,
        global: usize,
        value: impl Fn(&CurveRt) -> f64,
    ) {
        for i in 0..self.curves.len() {
            let v = value(&self.curves[i]);
            self.curves[i].values.push(v);
        }
        self.x_time.push(time);
        self.x_step.push(global as f64);
        self.x_load.push(load_factor);
    }

    /// Writes `curves.csv` and the SVGs in `dir` (nothing without curves), adds them to `files`,
    /// and returns each curve's extremes.
    pub(super) fn finish(
        &self,
        plots: &[PlotSpec],
        dir: &Path,
        files: &mut Vec<String>,
    ) -> CliResult<Vec<CurveSummary>> {
        let mut summaries = Vec::new();
        if !self.curves.is_empty() {
            let mut csv = String::from("step,time,load_factor");
            for c in &self.curves {
                csv.push(',');
                csv.push_str(&c.label.replace(',', ";"));
            }
            csv.push('\n');
            for i in 0..self.x_time.len() {
                csv.push_str(&format!(
                    "{},{},{}",
                    self.x_step[i], self.x_time[i], self.x_load[i]
                ));
                for c in &self.curves {
                    csv.push_str(&format!(",{:?}", c.values[i]));
                }
                csv.push('\n');
            }
            let path = dir.join("curves.csv");
            std::fs::write(&path, csv).map_err(|e| io(&path, e))?;
            files.push("curves.csv".into());
            for (i, p) in plots.iter().enumerate() {
                let x_curve = self.curves.iter().find(|c| c.plot == i && c.is_x);
                let (xs, x_label) = match (x_curve, p.x) {
                    (Some(c), _) => (&c.values, c.label.as_str()),
                    (None, XAxis::Time) => (&self.x_time, "time"),
                    (None, XAxis::Step) => (&self.x_step, "step"),
                    (None, XAxis::LoadFactor) => (&self.x_load, "load factor"),
                };
                let series: Vec<(&str, &[f64])> = self
                    .curves
                    .iter()
                    .filter(|c| c.plot == i && !c.is_x)
                    .map(|c| (c.label.as_str(), c.values.as_slice()))
                    .collect();
                let path = dir.join(&p.file);
                plot::write_svg(
                    &path,
                    p.title.as_deref().unwrap_or(&p.file),
                    x_label,
                    xs,
                    &series,
                )
                .map_err(|e| io(&path, e))?;
                files.push(p.file.clone());
            }
            for c in &self.curves {
                let mut s = CurveSummary {
                    plot: plots[c.plot].file.clone(),
                    label: c.label.clone(),
                    min: None,
                    max: None,
                    last: c.values.last().copied(),
                };
                for (i, &v) in c.values.iter().enumerate() {
                    let (step, t) = (self.x_step[i] as usize, self.x_time[i]);
                    keep(&mut s.max, v, step, t, true);
                    keep(&mut s.min, v, step, t, false);
                }
                summaries.push(s);
            }
        }
        Ok(summaries)
    }
}

fn curve_value<const D: usize>(
    c: &CurveRt,
    res: &StepResult<D>,
    (disp, reactions): (Option<&[[f64; D]]>, Option<&[fem_core::Reaction]>),
    u_t: fn(&ContactRecord<D>) -> f64,
) -> f64
where
    Dim<D>: ContactSpace<D>,
{
    let q = c.spec.quantity.as_str();
    let in_zone = || (res.contacts.iter()).filter(|r| c.zone.is_none_or(|z| r.zone == z));
    let rep = &res.report;
    match q {
        "contact_iterations" => rep.contact_iterations as f64,
        "adhesion_iterations" => rep.adhesion_iterations as f64,
        // closed, as steps.csv's column; the reduced problem's size is `candidates`
        "active_contacts" => rep.closed_contacts as f64,
        "candidates" => rep.active_contacts as f64,
        "residual" => rep.residual,
        "force_n" => in_zone().map(|r| r.reaction()[0]).sum(),
        "force_t" => in_zone().map(|r| r.reaction()[1]).sum(),
        "closed" => in_zone().filter(|r| r.status.is_closed()).count() as f64,
        "beta_mean" | "beta_min" => {
            let b: Vec<f64> = in_zone().map(|r| r.beta).collect();
            if b.is_empty() {
                f64::NAN
            } else if q == "beta_min" {
                b.iter().copied().fold(f64::INFINITY, f64::min)
            } else {
                b.iter().sum::<f64>() / b.len() as f64
            }
        }
        "gap" | "u_t" | "beta" | "r_n" | "r_t" => {
            let node = c.spec.node.unwrap_or(usize::MAX);
            let zone_given = c.spec.zone.is_some();
            match res
                .contacts
                .iter()
                .find(|r| r.node == node && (!zone_given || c.zone == Some(r.zone)))
            {
                Some(r) => match q {
                    "gap" => r.gap,
                    "u_t" => u_t(r),
                    "beta" => r.beta,
                    "r_n" => r.reaction()[0],
                    _ => r.reaction()[1],
                },
                None => f64::NAN,
            }
        }
        "u_x" | "u_y" | "u_z" => {
            // the axis (z only in 3D: the check of the plots refuses it in 2D)
            let k = ["u_x", "u_y", "u_z"]
                .iter()
                .position(|a| *a == q)
                .unwrap_or(0);
            let Some(d) = disp else { return f64::NAN };
            if k >= D {
                return f64::NAN;
            }
            let nodes: Vec<usize> = match c.spec.node {
                Some(n) => vec![n],
                None => c.set_nodes.clone(),
            };
            if nodes.is_empty() {
                return f64::NAN;
            }
            nodes.iter().map(|&n| d[n][k]).sum::<f64>() / nodes.len() as f64
        }
        "reaction_x" | "reaction_y" | "reaction_z" => {
            let comp = match q {
                "reaction_x" => Component::X,
                "reaction_y" => Component::Y,
                _ => Component::Z,
            };
            reactions.map_or(f64::NAN, |r| {
                r.iter()
                    .filter(|((n, cc), _)| *cc == comp && c.set_nodes.contains(n))
                    .map(|(_, v)| v)
                    .sum()
            })
        }
        _ => f64::NAN,
    }
}
