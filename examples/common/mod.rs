//! Shared helpers of the seed-study examples: CSV tables and SVG line plots (plotters), the
//! quick mode (`BIPO_QUICK=1`, as CI runs the examples) and the checks of their figures.

#![allow(dead_code)]

use bipotential::contact_solver::StepResult;
use plotters::prelude::*;
use std::error::Error;
use std::fmt::Write as _;
use std::path::Path;

/// One named curve.
pub struct Series {
    /// Legend.
    pub name: String,
    /// Points `(x, y)`.
    pub points: Vec<(f64, f64)>,
}

impl Series {
    /// A named curve.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            points,
        }
    }
}

/// Writes `header` and `rows` as CSV (full round-trip precision).
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<f64>]) -> Result<(), Box<dyn Error>> {
    let mut s = header.join(",");
    s.push('\n');
    for r in rows {
        let line: Vec<String> = r.iter().map(|v| format!("{v}")).collect();
        writeln!(s, "{}", line.join(","))?;
    }
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(path, s)?;
    Ok(())
}

/// Writes the curves of `series` as one CSV with columns `series,x,y`.
pub fn write_series_csv(
    path: &Path,
    x: &str,
    y: &str,
    series: &[Series],
) -> Result<(), Box<dyn Error>> {
    let mut s = format!("series,{x},{y}\n");
    for c in series {
        for (a, b) in &c.points {
            writeln!(s, "{},{a},{b}", c.name)?;
        }
    }
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(path, s)?;
    Ok(())
}

/// An SVG line plot of `series`.
pub fn line_plot(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), Box<dyn Error>> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let pts = series.iter().flat_map(|s| s.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if x0 >= x1 {
        x1 = x0 + 1.0;
    }
    if y0 >= y1 {
        y1 = y0 + 1.0;
    }
    let pad = 0.05 * (y1 - y0);
    let root = SVGBackend::new(path, (720, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .draw()?;
    for (k, s) in series.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        chart
            .draw_series(LineSeries::new(
                s.points.iter().copied(),
                color.stroke_width(2),
            ))?
            .label(s.name.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

/// `true` when the environment variable `BIPO_QUICK` is set (and not `0`): the examples then
/// run a small version of their study (fewer steps, sizes or repeats, the same code), as CI
/// does (`.ci/run`). Arguments given on the command line still win.
pub fn quick() -> bool {
    std::env::var_os("BIPO_QUICK").is_some_and(|v| v != "0")
}

/// The largest difference of two runs of the same scene over every step and contact: the
/// reactions `|Δr_n|`, `|Δr_t|` relative to the largest `|r|` of `b`, and `|Δβ|`.
pub fn max_difference(a: &[StepResult], b: &[StepResult]) -> (f64, f64) {
    let scale = b
        .iter()
        .flat_map(|s| s.contacts.iter().map(|c| c.r.n.abs().max(c.r.t[0].abs())))
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let (mut dr, mut db) = (0.0_f64, 0.0_f64);
    for (x, y) in a.iter().zip(b) {
        for (p, q) in x.contacts.iter().zip(&y.contacts) {
            dr = dr
                .max((p.r.n - q.r.n).abs())
                .max((p.r.t[0] - q.r.t[0]).abs());
            db = db.max((p.beta - q.beta).abs());
        }
    }
    (dr / scale, db)
}

/// An error naming `what` when `value` exceeds `tolerance` (or is NaN): the examples' check of
/// a figure against its reference, so that a miss stops them with a non-zero exit.
pub fn check(what: &str, value: f64, tolerance: f64) -> Result<(), Box<dyn Error>> {
    if value <= tolerance {
        Ok(())
    } else {
        Err(format!("{what} = {value:e} exceeds its tolerance {tolerance:e}").into())
    }
}
