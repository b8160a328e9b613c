//! `[analysis] dynamic = true`: the keys of a dynamic scene (issue 39), read and checked.
//!
//! ```text
//! [analysis]
//! type = "plane_stress"        # or plane_strain, axisymmetric, 3d
//! thickness = 1.0
//! dynamic = true               # a Moreau–Jean θ-scheme run (Jean 1999)
//! time_step = 0.005            # h > 0, at most end_time
//! end_time = 2.6
//! theta = 0.5                  # θ ∈ [1/2, 1] (default 1/2: no numerical dissipation)
//! mass = "consistent"          # or "lumped" (HRZ)
//! rayleigh_alpha = 0.0         # C = α M + β K (both ≥ 0, default 0)
//! rayleigh_beta = 0.0
//! ```
//! A static analysis refuses these keys, naming each.

use super::RawAnalysis;
use super::keys::only;
use crate::error::{CliResult, KeyPath, bail};
use serde::Deserialize;

/// `[analysis] mass`: which mass matrix the dynamic run integrates with.
#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum MassSpec {
    /// `∫ ρ Nᵀ N` (the default).
    #[default]
    Consistent,
    /// The HRZ lumped diagonal.
    Lumped,
}

impl MassSpec {
    /// The name in a scene file.
    pub fn name(self) -> &'static str {
        match self {
            MassSpec::Consistent => "consistent",
            MassSpec::Lumped => "lumped",
        }
    }
}

/// The most steps a dynamic scene may ask for (`end_time / time_step`): beyond, a typo in
/// `time_step` would start a run that never ends.
pub const MAX_DYNAMIC_STEPS: f64 = 10_000_000.0;

/// The time stepping of a dynamic scene, checked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicSpec {
    /// The step `h`.
    pub time_step: f64,
    /// The end of the run (it starts at 0).
    pub end_time: f64,
    /// The number of steps, `⌈end_time / h⌉`, each of `end_time / steps` (`h` itself when it
    /// divides the end time).
    pub steps: usize,
    /// `θ ∈ [1/2, 1]`.
    pub theta: f64,
    /// Consistent or lumped.
    pub mass: MassSpec,
    /// Rayleigh `α` (1/time).
    pub alpha: f64,
    /// Rayleigh `β` (time).
    pub beta: f64,
}

impl RawAnalysis {
    /// Whether the scene is dynamic (`dynamic = true`).
    pub fn is_dynamic(&self) -> bool {
        self.dynamic.unwrap_or(false)
    }

    /// The dynamic time stepping (`None` for a static analysis, which refuses the dynamic keys
    /// at their paths); `p` is `analysis`.
    pub fn dynamic(&self, p: &KeyPath) -> CliResult<Option<DynamicSpec>> {
        let present = [
            ("time_step", self.time_step.is_some()),
            ("end_time", self.end_time.is_some()),
            ("theta", self.theta.is_some()),
            ("mass", self.mass.is_some()),
            ("rayleigh_alpha", self.rayleigh_alpha.is_some()),
            ("rayleigh_beta", self.rayleigh_beta.is_some()),
        ];
        if !self.is_dynamic() {
            if let Some((k, _)) = present.iter().find(|(_, there)| *there) {
                let kp = p.key(k);
                bail!(
                    kp,
                    "`{kp}` is a key of a dynamic analysis (set `dynamic = true` in [analysis])"
                );
            }
            return Ok(None);
        }
        let all = "time_step end_time theta mass rayleigh_alpha rayleigh_beta";
        only(p, "a dynamic analysis", &present, all)?;
        let hp = p.key("time_step");
        let ep = p.key("end_time");
        let Some(h) = self.time_step else {
            bail!(
                p,
                "`{p}`: a dynamic analysis needs `time_step` (the step h > 0)"
            );
        };
        let Some(end) = self.end_time else {
            bail!(p, "`{p}`: a dynamic analysis needs `end_time` (> 0)");
        };
        if !(h.is_finite() && h > 0.0) {
            bail!(hp, "`{hp}` = {h:?}: expected a finite step > 0");
        }
        if !(end.is_finite() && end > 0.0) {
            bail!(ep, "`{ep}` = {end:?}: expected a finite end time > 0");
        }
        if h > end {
            bail!(
                hp,
                "`{hp}` = {h:?} is larger than `{ep}` = {end:?}: the run would not take one \
                     whole step (take a step at most the end time)"
            );
        }
        let count = (end / h * (1.0 - 1e-12)).ceil();
        if count > MAX_DYNAMIC_STEPS {
            bail!(
                hp,
                "`{hp}` = {h:?}: {count:.0} steps to reach `{ep}` = {end:?}, more than the \
                     {MAX_DYNAMIC_STEPS:.0} a run may take"
            );
        }
        let theta = self.theta.unwrap_or(0.5);
        if !(0.5..=1.0).contains(&theta) {
            let tp = p.key("theta");
            bail!(
                tp,
                "`{tp}` = {theta:?}: expected a weight in [1/2, 1] (1/2: the trapezoidal rule, \
                     no numerical dissipation; 1: backward Euler)"
            );
        }
        let mut rayleigh = [0.0; 2];
        for (out, (key, v)) in rayleigh.iter_mut().zip([
            ("rayleigh_alpha", self.rayleigh_alpha),
            ("rayleigh_beta", self.rayleigh_beta),
        ]) {
            let v = v.unwrap_or(0.0);
            if !(v.is_finite() && v >= 0.0) {
                let kp = p.key(key);
                bail!(kp, "`{kp}` = {v:?}: expected a finite coefficient ≥ 0");
            }
            *out = v;
        }
        Ok(Some(DynamicSpec {
            time_step: h,
            end_time: end,
            steps: (count as usize).max(1),
            theta,
            mass: self.mass.unwrap_or_default(),
            alpha: rayleigh[0],
            beta: rayleigh[1],
        }))
    }
}

/// Checks a restitution `e` at `p`: in `[0, 1]`.
pub fn restitution(p: &KeyPath, e: f64) -> CliResult<f64> {
    if !(0.0..=1.0).contains(&e) {
        bail!(
            p,
            "`{p}` = {e:?}: expected a restitution coefficient in [0, 1] (0: no rebound, 1: \
                 elastic)"
        );
    }
    Ok(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn analysis(s: &str) -> RawAnalysis {
        toml::from_str(s).unwrap()
    }

    fn error(s: &str) -> String {
        let p = KeyPath::root().key("analysis");
        let e = analysis(s).dynamic(&p).unwrap_err();
        e.path.unwrap().to_string()
    }

    #[test]
    fn dynamic_keys_works() {
        let p = KeyPath::root().key("analysis");
        let a = analysis(
            "type = \"plane_strain\"\ndynamic = true\ntime_step = 0.3\nend_time = 1.0\n\
             mass = \"lumped\"\nrayleigh_beta = 0.1",
        );
        let d = a.dynamic(&p).unwrap().unwrap();
        // ⌈1 / 0.3⌉ = 4 steps (of 0.25)
        assert_eq!(d.steps, 4);
        assert_eq!(
            (d.theta, d.mass, d.alpha, d.beta),
            (0.5, MassSpec::Lumped, 0.0, 0.1)
        );
        // 1.0 / 0.1 is 10.000000000000002 in floating point: still 10 steps
        let a = analysis("type = \"3d\"\ndynamic = true\ntime_step = 0.1\nend_time = 1.0");
        assert_eq!(a.dynamic(&p).unwrap().unwrap().steps, 10);
        assert!(analysis("type = \"3d\"").dynamic(&p).unwrap().is_none());
    }

    #[test]
    fn dynamic_keys_rejects_bad_values() {
        let head = "type = \"plane_strain\"\ndynamic = true\n";
        for (body, key) in [
            ("time_step = 2.0\nend_time = 1.0", "analysis.time_step"),
            ("time_step = 0.0\nend_time = 1.0", "analysis.time_step"),
            ("time_step = -1.0\nend_time = 1.0", "analysis.time_step"),
            ("time_step = 0.1\nend_time = inf", "analysis.end_time"),
            (
                "time_step = 0.1\nend_time = 1.0\ntheta = 0.4",
                "analysis.theta",
            ),
            (
                "time_step = 0.1\nend_time = 1.0\ntheta = 1.5",
                "analysis.theta",
            ),
            (
                "time_step = 0.1\nend_time = 1.0\nrayleigh_alpha = -1",
                "analysis.rayleigh_alpha",
            ),
            ("end_time = 1.0", "analysis"),
        ] {
            assert_eq!(error(&format!("{head}{body}")), key, "{body}");
        }
        // a static analysis names the dynamic key it does not read
        assert_eq!(
            error("type = \"plane_strain\"\ntheta = 0.5"),
            "analysis.theta"
        );
        let p = KeyPath::root().key("e");
        assert!(restitution(&p, 1.5).is_err());
        assert!(restitution(&p, f64::NAN).is_err());
        assert_eq!(restitution(&p, 0.8).unwrap(), 0.8);
    }
}
