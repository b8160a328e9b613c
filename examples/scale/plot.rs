//! The table and the log–log plots of `contact_scaling`'s studies.

use crate::common;
use crate::{label, num};
use plotters::prelude::*;
use std::collections::HashMap;
use std::error::Error;
use std::fmt::Write as _;
use std::path::Path;

/// A markdown table of the main columns.
pub fn table(rows: &[HashMap<String, String>]) -> String {
    let mut s = String::from(
        "| law, path (solver) | n_c | free DOF | build (s) | step (s) | F* columns | products F* r | \
         factorisations / solves | iterations | closed | peak RSS (MiB) |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let f = |k: &str, p: usize| {
            let v = num(r, k);
            if v.is_finite() {
                format!("{v:.p$}")
            } else {
                "—".into()
            }
        };
        let step = if r["status"] == "ok" {
            f("t_step", 3)
        } else {
            r["status"].clone()
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {step} | {} | {} | {} | {} | {} | {} |",
            label(r),
            r["n_c"],
            r["dof"],
            f("t_build", 2),
            f("flexibility_columns", 0),
            f("operator_applications", 0),
            if r["mode"] == "active" {
                format!("{} / {}", f("factorizations", 0), f("active_set_solves", 0))
            } else {
                "—".into()
            },
            f("iterations", 0),
            f("closed", 0),
            f("peak_rss_mb", 0),
        );
    }
    s
}

/// Colour, dashing and markers of a curve, from its name: one colour per path (solver), dashed
/// for Coulomb, no markers on the model lines.
fn style(name: &str) -> (RGBColor, bool, bool) {
    let colour = if name.contains("active set") {
        RGBColor(214, 39, 40)
    } else if name.contains("matrix-free") || name.contains("products") {
        RGBColor(31, 119, 180)
    } else if name.contains("Newton") {
        RGBColor(44, 160, 44)
    } else if name.contains("Anderson") || name.contains("F* columns") {
        RGBColor(255, 127, 14)
    } else if name.contains("(GS)") {
        RGBColor(148, 103, 189)
    } else if name.contains("build") {
        RGBColor(127, 127, 127)
    } else {
        RGBColor(0, 0, 0)
    };
    let model = name.contains("bytes") || name.contains("budget");
    (colour, name.starts_with("coulomb"), !model)
}

/// A log–log SVG plot, a marker on every measured point; room is left above the curves for
/// the legend.
pub fn loglog(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[common::Series],
) -> Result<(), Box<dyn Error>> {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, 0.0_f64, f64::MAX, 0.0_f64);
    for &(x, y) in series.iter().flat_map(|s| s.points.iter()) {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if x1 <= 0.0 {
        return Ok(());
    }
    let decades = (y1 / y0).log10().max(1.0);
    let top = y1 * 10f64.powf(0.05 * decades * series.len() as f64);
    let root = SVGBackend::new(path, (820, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(
            (x0 / 1.3..x1 * 1.3).log_scale(),
            (y0 / 1.5..top).log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .draw()?;
    for s in series {
        let (colour, dashed, markers) = style(&s.name);
        let line = colour.stroke_width(2);
        let points = s.points.iter().copied();
        let drawn = if dashed {
            chart.draw_series(DashedLineSeries::new(points, 8, 5, line))?
        } else {
            chart.draw_series(LineSeries::new(points, line))?
        };
        drawn.label(s.name.as_str()).legend(move |(x, y)| {
            PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
        });
        if markers {
            chart.draw_series(s.points.iter().map(|&p| Circle::new(p, 3, colour.filled())))?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
