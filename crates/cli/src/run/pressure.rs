//! The recovered contact traction of a run (2D and 3D): each zone's continuous pressure and
//! tangential traction on its contactor surface ([`TractionField`], the consistent boundary
//! mass of [`BoundaryMass`]) at every written step, into `pressure.csv` (one row per surface
//! node), to the interface VTK (the caller passes the fields on), and, with `[hertz]`, the
//! pressure of the last written step against the Hertz ellipse (`pressure.svg`).
//!
//! A zone's surface is the boundary sides (faces in 3D) whose nodes are all contactor nodes of
//! the zone; a zone without one (a lone node) has no field.

use super::errors::{create, io};
use crate::build::{HertzPlan, HertzShape};
use crate::error::{CliError, CliResult};
use crate::plot::{Mark, write_profile_svg};
use contact_solver::SolverError;
use contact_solver::coupling::traction::TractionField;
use contact_solver::error::chain;
use fem_core::FemError;
use fem_core::boundary_mass::BoundaryMass;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// A zone's surface mass, `None` for a zone without a surface; the error of any other
/// failure names the zone.
pub(super) fn zone_mass(
    zone: &str,
    mass: Result<BoundaryMass, FemError>,
) -> CliResult<Option<BoundaryMass>> {
    match mass {
        Ok(m) => Ok(Some(m)),
        Err(FemError::EmptyBoundary { .. }) => Ok(None),
        Err(e) => Err(CliError::failed(format!(
            "zone `{zone}`: the contact pressure cannot be recovered on its contactor surface \
             ({}); set `output.pressure = false` (and drop [hertz]) to run without it",
            chain(&e)
        ))),
    }
}

/// The field of the Hertz zone at the last written step.
struct Last {
    field: TractionField,
    force_n: f64,
    time: f64,
}

/// `pressure.csv`, the fields of each written step and the Hertz plot.
pub(crate) struct PressureRecorder {
    dir: PathBuf,
    csv: Option<BufWriter<File>>,
    masses: Vec<Option<BoundaryMass>>,
    zones_filter: Option<Vec<usize>>,
    hertz: Option<(HertzPlan, HertzShape)>,
    last: Option<Last>,
}

impl PressureRecorder {
    /// `pressure.csv` (when `csv`, listed in `files`) with the coordinate columns `coords`
    /// (`["x", "y"]`, `["r", "z"]` or `["x", "y", "z"]`) and the tangential ones `shear`.
    pub(super) fn new(
        dir: &Path,
        csv: bool,
        masses: Vec<Option<BoundaryMass>>,
        zones_filter: Option<Vec<usize>>,
        hertz: Option<(HertzPlan, HertzShape)>,
        columns: (&[&str], &[&str]),
        files: &mut Vec<String>,
    ) -> CliResult<Self> {
        let csv = if csv {
            let mut w = create(dir, "pressure.csv")?;
            let head = format!(
                "step,time,zone,node,{},p,{}",
                columns.0.join(","),
                columns.1.join(",")
            );
            writeln!(w, "{head}").map_err(|e| io(&dir.join("pressure.csv"), e))?;
            files.push("pressure.csv".into());
            Some(w)
        } else {
            None
        };
        Ok(Self {
            dir: dir.to_path_buf(),
            csv,
            masses,
            zones_filter,
            hertz,
            last: None,
        })
    }

    /// Whether a written step needs the fields (for the CSV or the plot).
    pub(super) fn is_active(&self) -> bool {
        self.csv.is_some() || self.hertz.is_some()
    }

    /// The fields of a written step (the zones of `output.zones` with a surface), written to
    /// `pressure.csv`; `recover(mass, zone)` makes a zone's field, `force_n(zone)` its `Σ r_n`,
    /// `position(node)` a node's reference position, `shear` the tangential components written.
    pub(super) fn record(
        &mut self,
        step: usize,
        time: f64,
        recover: impl Fn(&BoundaryMass, usize) -> Result<TractionField, SolverError>,
        force_n: impl Fn(usize) -> f64,
        position: impl Fn(usize) -> Vec<f64>,
        shear: usize,
    ) -> CliResult<Vec<TractionField>> {
        let mut fields = Vec::new();
        let hertz_zone = self.hertz.as_ref().map(|h| h.0.zone);
        for (zone, mass) in self.masses.iter().enumerate() {
            let Some(mass) = mass else { continue };
            let listed = self.zones_filter.as_ref().is_none_or(|z| z.contains(&zone));
            if !listed && hertz_zone != Some(zone) {
                continue;
            }
            let field = recover(mass, zone).map_err(|e| {
                CliError::failed(format!("recovering the contact pressure: {}", chain(&e)))
            })?;
            if hertz_zone == Some(zone) {
                self.last = Some(Last {
                    field: field.clone(),
                    force_n: force_n(zone),
                    time,
                });
            }
            if listed {
                fields.push(field);
            }
        }
        if let Some(w) = &mut self.csv {
            let path = self.dir.join("pressure.csv");
            for f in &fields {
                for (k, &node) in f.nodes.iter().enumerate() {
                    let mut line = format!("{step},{time},{},{node}", f.zone);
                    for c in position(node) {
                        line.push_str(&format!(",{c}"));
                    }
                    line.push_str(&format!(",{:e}", f.pressure[k]));
                    for t in &f.shear[k][..shear] {
                        line.push_str(&format!(",{t:e}"));
                    }
                    writeln!(w, "{line}").map_err(|e| io(&path, e))?;
                }
            }
        }
        Ok(fields)
    }

    /// Flushes `pressure.csv` and draws the Hertz plot (listed in `files`); `position(node)`
    /// is a node's reference position (`[x, y, 0]` in 2D).
    pub(super) fn finish(
        mut self,
        position: impl Fn(usize) -> [f64; 3],
        files: &mut Vec<String>,
    ) -> CliResult<()> {
        if let Some(w) = &mut self.csv {
            w.flush()
                .map_err(|e| io(&self.dir.join("pressure.csv"), e))?;
        }
        let (Some((plan, shape)), Some(last)) = (&self.hertz, &self.last) else {
            return Ok(());
        };
        let mass = self.masses[plan.zone].as_ref().expect("recorded above");
        let path = self.dir.join(&plan.file);
        draw_hertz(&path, plan, *shape, last, mass, &position)?;
        files.push(plan.file.clone());
        Ok(())
    }
}

/// The pressure at the last written step against Hertz (module docs), with `p(0)/p0` and the
/// relative `L²` distance over the contact disc in the title.
fn draw_hertz(
    path: &Path,
    plan: &HertzPlan,
    shape: HertzShape,
    last: &Last,
    mass: &BoundaryMass,
    position: &impl Fn(usize) -> [f64; 3],
) -> CliResult<()> {
    let (a, p0) = shape.a_p0(plan, last.force_n);
    let distance = |x: [f64; 3]| {
        let d: f64 = (0..3).map(|k| (x[k] - plan.center[k]).powi(2)).sum();
        d.sqrt()
    };
    let hertz = |d: f64| {
        if d < a {
            p0 * (1.0 - d * d / (a * a)).sqrt()
        } else {
            0.0
        }
    };
    let f = &last.field;
    let mut fe: Vec<(f64, f64)> = f
        .nodes
        .iter()
        .zip(&f.pressure)
        .map(|(&n, &p)| (distance(position(n)), p))
        .filter(|(d, _)| *d <= 2.0 * a)
        .collect();
    fe.sort_by(|u, v| u.0.total_cmp(&v.0));
    let centre = fe.first().map_or(f64::NAN, |p| p.1 / p0);
    let in_disc = |x: [f64; 3]| distance(x) < a;
    let err = mass.integrate(&f.pressure, |x, p| {
        if in_disc(x) {
            (p - hertz(distance(x))).powi(2)
        } else {
            0.0
        }
    });
    let norm = mass.integrate(&f.pressure, |x, _| {
        if in_disc(x) {
            hertz(distance(x)).powi(2)
        } else {
            0.0
        }
    });
    let l2 = (err / norm).sqrt();
    let curve: Vec<(f64, f64)> = (0..=200)
        .map(|k| {
            let d = 2.0 * a * f64::from(k) / 200.0;
            (d, hertz(d))
        })
        .collect();
    let title = format!(
        "t = {}: p(0)/p0 = {centre:.4}, L2 distance over r < a: {:.2} %",
        last.time,
        100.0 * l2
    );
    let hertz_label = format!("Hertz: a = {a:.4}, p0 = {p0:.4}");
    write_profile_svg(
        path,
        &title,
        "distance from the first point of contact",
        "contact pressure",
        &[
            ("recovered pressure (nodes)", &fe, Mark::Dots),
            (&hertz_label, &curve, Mark::Line),
        ],
    )
    .map_err(|e| io(path, e))
}
