//! The pile's shaft profiles against depth: at chosen steps (`[output] profile_steps`; by
//! default the first pull-out step, the step of the peak head load and the last step), the
//! normal stress `σ_n`, the shaft friction `τ`, the adhesion β and the slip `u_t` of every shaft
//! contact, written as `profiles.csv` and one SVG per quantity against depth.

use super::errors::{create, io};
use crate::error::CliResult;
use crate::plot;
use crate::presets::ShaftPoint;
use std::io::Write;
use std::path::Path;

/// One step's shaft.
struct Profile {
    step: usize,
    time: f64,
    phase: usize,
    head_load: f64,
    points: Vec<ShaftPoint>,
}

/// The shaft of every step of a pile run (a few dozen contacts a step), until the steps to
/// write are known.
#[derive(Default)]
pub(super) struct Profiles {
    steps: Vec<Profile>,
}

/// The quantities plotted: file, title, label, value.
type Quantity = (&'static str, &'static str, fn(&ShaftPoint) -> f64);
const QUANTITIES: [Quantity; 4] = [
    (
        "profile_sigma_n.svg",
        "Normal stress on the shaft σ_n (kPa)",
        |p| p.sigma_n,
    ),
    (
        "profile_tau.svg",
        "Shaft friction τ (kPa, along +z)",
        |p| p.tau,
    ),
    ("profile_beta.svg", "Adhesion β", |p| p.beta),
    (
        "profile_slip.svg",
        "Slip u_t (m, pile up relative to the soil)",
        |p| p.u_t,
    ),
];

impl Profiles {
    /// Keeps global step `step` of phase `phase`.
    pub(super) fn record(
        &mut self,
        step: usize,
        time: f64,
        phase: usize,
        head_load: f64,
        points: Vec<ShaftPoint>,
    ) {
        self.steps.push(Profile {
            step,
            time,
            phase,
            head_load,
            points,
        });
    }

    /// The steps to write: `chosen`, or the first step of the last phase (the pull-out), the
    /// step of its largest head load and the last step; in order, once each.
    fn selected(&self, chosen: Option<&[usize]>) -> Vec<&Profile> {
        let mut steps: Vec<usize> = match chosen {
            Some(list) => list.to_vec(),
            None => {
                let Some(last) = self.steps.last() else {
                    return Vec::new();
                };
                let pull = self.steps.iter().filter(|p| p.phase == last.phase);
                let first = self
                    .steps
                    .iter()
                    .find(|p| p.phase == last.phase)
                    .map_or(last.step, |p| p.step);
                let peak = pull
                    .max_by(|a, b| a.head_load.total_cmp(&b.head_load))
                    .map_or(last.step, |p| p.step);
                vec![first, peak, last.step]
            }
        };
        steps.sort_unstable();
        steps.dedup();
        self.steps
            .iter()
            .filter(|p| steps.contains(&p.step))
            .collect()
    }

    /// Writes `profiles.csv` and the SVGs of the steps chosen (see [`Profiles::selected`]) into
    /// `dir`, listing them in `files`.
    pub(super) fn finish(
        &self,
        dir: &Path,
        chosen: Option<&[usize]>,
        files: &mut Vec<String>,
    ) -> CliResult<()> {
        let sel = self.selected(chosen);
        if sel.is_empty() {
            return Ok(());
        }
        let path = dir.join("profiles.csv");
        let mut w = create(dir, "profiles.csv")?;
        let mut text = String::from("step,time,head_load,z,depth,sigma_n,tau,beta,u_t,status\n");
        for p in &sel {
            for q in &p.points {
                text.push_str(&format!(
                    "{},{},{:e},{},{},{:e},{:e},{},{:e},{}\n",
                    p.step,
                    p.time,
                    p.head_load,
                    q.z,
                    -q.z + 0.0,
                    q.sigma_n,
                    q.tau,
                    q.beta,
                    q.u_t,
                    q.status.name()
                ));
            }
        }
        w.write_all(text.as_bytes())
            .and_then(|()| w.flush())
            .map_err(|e| io(&path, e))?;
        files.push("profiles.csv".into());
        // every step has the same shaft contacts, in the same order: one abscissa
        let depth: Vec<f64> = sel[0].points.iter().map(|q| -q.z + 0.0).collect();
        let labels: Vec<String> = sel
            .iter()
            .map(|p| format!("step {} (t = {}, Q = {:.4e})", p.step, p.time, p.head_load))
            .collect();
        for (file, title, value) in QUANTITIES {
            let values: Vec<Vec<f64>> = sel
                .iter()
                .map(|p| p.points.iter().map(value).collect())
                .collect();
            let series: Vec<(&str, &[f64])> = labels
                .iter()
                .zip(&values)
                .map(|(l, v)| (l.as_str(), v.as_slice()))
                .collect();
            let path = dir.join(file);
            plot::write_svg(&path, title, "depth (m)", &depth, &series)
                .map_err(|e| io(&path, e))?;
            files.push(file.into());
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use contact_solver::InterfaceStatus;

    fn shaft(z: f64) -> ShaftPoint {
        ShaftPoint {
            z,
            sigma_n: 1.0,
            tau: -0.5,
            beta: 1.0,
            u_t: 0.0,
            status: InterfaceStatus::Stick,
        }
    }

    #[test]
    fn default_steps_are_first_peak_and_last_of_the_pullout_works() {
        let mut p = Profiles::default();
        for (step, phase, q) in [
            (1, 0, 9.0),
            (2, 1, 9.0),
            (3, 2, 1.0),
            (4, 2, 5.0),
            (5, 2, 2.0),
        ] {
            p.record(step, step as f64, phase, q, vec![shaft(-1.0)]);
        }
        let steps = |s: Vec<&Profile>| s.iter().map(|p| p.step).collect::<Vec<_>>();
        assert_eq!(steps(p.selected(None)), [3, 4, 5]);
        assert_eq!(steps(p.selected(Some(&[5, 1, 5]))), [1, 5]);
        assert!(Profiles::default().selected(None).is_empty());
    }
}
