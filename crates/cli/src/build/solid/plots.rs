//! `[[plots]]` of a 3D scene: the plot files checked as in 2D, and each curve's quantity one
//! that a 3D run records (the step counters and the zones' sums); the rest (single nodes,
//! displacements, reactions, the pile's) is refused with its key path.

use super::super::outputs::{QUANTITIES, check_plot_file, zone_index};
use crate::error::{CliError, CliResult, KeyPath};
use crate::scene::{CurveSpec, PlotSpec};
use std::collections::BTreeSet;

/// The quantities a 3D run plots: the step's counters and, per zone, Σ r_n, the closed
/// contacts and β (mean, least).
const QUANTITIES_3D: &[&str] = &[
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

/// Checks the plots of a 3D scene with these zones; returns them.
pub(super) fn check(plots: &[PlotSpec], zone_names: &[String]) -> CliResult<Vec<PlotSpec>> {
    let mut files = BTreeSet::new();
    for (i, plot) in plots.iter().enumerate() {
        let pp = KeyPath::root().key("plots").index(i);
        check_plot_file(&pp, plot, &mut files)?;
        for (k, c) in plot.curves.iter().enumerate() {
            check_curve(&pp.key("curves").index(k), c, zone_names)?;
        }
        if let Some(c) = &plot.x_quantity {
            check_curve(&pp.key("x_quantity"), c, zone_names)?;
        }
    }
    Ok(plots.to_vec())
}

/// One curve: a 3D quantity, with its zone where the scene has several.
fn check_curve(p: &KeyPath, c: &CurveSpec, zone_names: &[String]) -> CliResult<()> {
    let q = p.key("quantity");
    if !QUANTITIES_3D.contains(&c.quantity.as_str()) {
        let what = if QUANTITIES.iter().any(|(n, _)| *n == c.quantity) {
            "not available in a 3D scene"
        } else {
            "unknown quantity"
        };
        return Err(CliError::at(
            &q,
            format!(
                "`{q}` = \"{}\": {what} (3D plots: {})",
                c.quantity,
                QUANTITIES_3D.join(", ")
            ),
        ));
    }
    for (key, given) in [("node", c.node.is_some()), ("set", c.set.is_some())] {
        if given {
            let k = p.key(key);
            return Err(CliError::at(
                &k,
                format!("`{k}`: a 3D plot's quantities are per step or per zone, not per {key}"),
            ));
        }
    }
    let zone = match &c.zone {
        Some(z) => Some(zone_index(&p.key("zone"), zone_names, z)?),
        None => None,
    };
    let per_zone = matches!(
        c.quantity.as_str(),
        "force_n" | "beta_mean" | "beta_min" | "closed"
    );
    if per_zone && zone.is_none() && zone_names.len() > 1 {
        return Err(CliError::at(
            p,
            format!(
                "`{p}`: quantity `{}` needs `zone` (the scene has several zones)",
                c.quantity
            ),
        ));
    }
    Ok(())
}
