//! Time: the piecewise linear functions of `[functions]` and the phases of load steps
//! (`[steps]` or `[[phases]]`), with the phase masks and function names of supports and loads,
//! and the law each zone has in each phase (`[[phases]] laws`), as the summaries report it.

use super::checks::{at_least, finite2, list_names, positive};
use crate::error::{CliResult, KeyPath, bail};
use crate::scene::Scene;
use crate::spec::Pair;
use contact_laws::StandardLaw;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};

/// A piecewise linear function of time, constant beyond its first and last points.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeFunction {
    points: Vec<[f64; 2]>,
}

impl TimeFunction {
    /// The function of `[time, value]` points (times increasing strictly: the caller's).
    pub(super) fn from_points(points: Vec<[f64; 2]>) -> Self {
        Self { points }
    }

    /// Value at `t`.
    pub fn eval(&self, t: f64) -> f64 {
        let p = &self.points;
        if t <= p[0][0] {
            return p[0][1];
        }
        for w in p.windows(2) {
            let ([t0, v0], [t1, v1]) = (w[0], w[1]);
            if t <= t1 {
                return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
            }
        }
        p[p.len() - 1][1]
    }
}

/// Checks `[functions]`: each table of points as a [`TimeFunction`], by name.
pub(super) fn time_functions(scene: &Scene) -> CliResult<BTreeMap<String, TimeFunction>> {
    let p = KeyPath::root().key("functions");
    (scene.functions.iter())
        .map(|(name, pts)| Ok((name.clone(), time_function(&p.key(name), pts)?)))
        .collect()
}

/// The function of the `[time, value]` points at `path` (times increasing strictly).
pub(super) fn time_function(path: &KeyPath, pts: &[Pair]) -> CliResult<TimeFunction> {
    let pts: Vec<[f64; 2]> = pts.iter().map(|p| p.0).collect();
    if pts.is_empty() {
        bail!(
            path,
            "`{path}` is empty: expected a table of [time, value] points"
        );
    }
    for (i, p) in pts.iter().enumerate() {
        finite2(&path.index(i), Pair(*p))?;
        if i > 0 && p[0] <= pts[i - 1][0] {
            let q = path.index(i).index(0);
            bail!(
                q,
                "`{q}` = {}: times must increase strictly (the previous point is at t = {})",
                p[0],
                pts[i - 1][0]
            );
        }
    }
    Ok(TimeFunction { points: pts })
}

/// One phase of load steps.
#[derive(Clone, Debug)]
pub struct Phase {
    /// Name.
    pub name: String,
    pub steps: usize,
    /// Start time.
    pub t0: f64,
    /// End time.
    pub t1: f64,
    /// Function overrides: load or support name → function name.
    pub overrides: BTreeMap<String, String>,
    /// Reset displacements at the end.
    pub reset_displacements: bool,
}

impl Phase {
    /// Time at the end of step `k` (1-based) of this phase.
    pub fn time(&self, k: usize) -> f64 {
        if k == self.steps {
            self.t1
        } else {
            self.t0 + (self.t1 - self.t0) * k as f64 / self.steps as f64
        }
    }
}

/// A phase without overrides.
pub(super) fn phase(name: &str, steps: usize, t0: f64, t1: f64) -> Phase {
    Phase {
        name: name.into(),
        steps,
        t0,
        t1,
        overrides: BTreeMap::new(),
        reset_displacements: false,
    }
}

/// The phases of the scene: `[steps]`, `[[phases]]`, or the preset's `total_default`.
pub(super) fn phases_of(
    scene: &Scene,
    total_default: Option<(usize, f64)>,
) -> CliResult<Vec<Phase>> {
    let mut out = Vec::new();
    match (&scene.steps, scene.phases.is_empty(), total_default) {
        (Some(_), false, _) => {
            bail!(
                KeyPath::root().key("phases"),
                "give either [steps] (one phase) or [[phases]], not both"
            );
        }
        (Some(s), true, _) => {
            let p = KeyPath::root().key("steps");
            let steps = at_least(&p.key("count"), s.count, 1)?;
            out.push(phase(
                "steps",
                steps,
                0.0,
                positive(&p.key("duration"), s.duration)?,
            ));
        }
        (None, false, _) => {
            let mut t = 0.0;
            let mut names = BTreeSet::new();
            for (i, ph) in scene.phases.iter().enumerate() {
                let p = KeyPath::root().key("phases").index(i);
                if !names.insert(ph.name.clone()) {
                    bail!(p.key("name"), "phase name `{}` is used twice", ph.name);
                }
                if ph.name.trim().is_empty() {
                    bail!(
                        p.key("name"),
                        "`{}` is empty: a phase needs a name",
                        p.key("name")
                    );
                }
                let d = positive(&p.key("duration"), ph.duration)?;
                if !(t + d).is_finite() || t + d <= t {
                    let dp = p.key("duration");
                    bail!(
                        dp,
                        "`{dp}` = {d:?}: the phase would end at t = {:?} after starting at \
                             t = {t:?} (the sum of the durations must stay finite, and each \
                             phase must move the time forward)",
                        t + d
                    );
                }
                out.push(Phase {
                    name: ph.name.clone(),
                    steps: at_least(&p.key("steps"), ph.steps, 1)?,
                    t0: t,
                    t1: t + d,
                    overrides: ph.functions.clone(),
                    reset_displacements: ph.reset_displacements,
                });
                t += d;
            }
        }
        (None, true, Some((steps, duration))) => out.push(phase("loading", steps, 0.0, duration)),
        (None, true, None) => {
            bail!(
                KeyPath::root(),
                "the scene has no load steps: add [steps] with `count` and `duration`, or [[phases]]"
            );
        }
    }
    let total = out
        .iter()
        .fold(0usize, |acc, phase| acc.saturating_add(phase.steps));
    if total > MAX_STEPS {
        let path = match &scene.steps {
            Some(_) => KeyPath::root().key("steps").key("count"),
            None => KeyPath::root().key("phases"),
        };
        bail!(
            path,
            "{total} load steps in all: more than the limit of {MAX_STEPS} (a run writes \
                 output every `output.every` steps and would not end in a useful time); \
                 use fewer steps"
        );
    }
    Ok(out)
}

/// The most load steps a scene may ask for, over all its phases: a step is at least one
/// structure solve and one contact solve, so 1e6 steps is already hours; `steps = 1e12` ran
/// without end and filled the disk with output files.
pub(super) const MAX_STEPS: usize = 1_000_000;

/// Which phases a support or load acts in (all without a list).
pub(super) fn phase_mask(
    path: &KeyPath,
    list: &Option<Vec<String>>,
    phases: &[Phase],
) -> CliResult<Vec<bool>> {
    match list {
        None => Ok(vec![true; phases.len()]),
        Some(names) if names.is_empty() => bail!(
            path,
            "`{path}` is empty: it would act in no phase (name at least one, or leave \
                 `phases` out to act in every phase)"
        ),
        Some(names) => {
            let mut mask = vec![false; phases.len()];
            for (i, n) in names.iter().enumerate() {
                match phases.iter().position(|p| &p.name == n) {
                    Some(k) => mask[k] = true,
                    None => {
                        let p = path.index(i);
                        bail!(
                            p,
                            "`{p}` = \"{n}\": no such phase (phases: {})",
                            list_names(phases.iter().map(|p| p.name.as_str()))
                        );
                    }
                }
            }
            Ok(mask)
        }
    }
}

/// Checks that a function name exists in `[functions]`.
pub(super) fn check_function(
    path: &KeyPath,
    name: &Option<String>,
    f: &BTreeMap<String, TimeFunction>,
) -> CliResult<()> {
    if let Some(n) = name
        && !f.contains_key(n)
    {
        bail!(
            path,
            "`{path}` = \"{n}\": no such function in [functions] (functions: {})",
            list_names(f.keys().map(|k| k.as_str()))
        );
    }
    Ok(())
}

/// The value of the time function of a support or load at `t` in `phase` (with the phase's
/// override by name); 1 without a function.
pub fn function_value(
    phase: &Phase,
    name: &Option<String>,
    function: &Option<String>,
    functions: &BTreeMap<String, TimeFunction>,
    t: f64,
) -> f64 {
    let f = name
        .as_ref()
        .and_then(|n| phase.overrides.get(n))
        .or(function.as_ref());
    f.and_then(|f| functions.get(f)).map_or(1.0, |f| f.eval(t))
}

/// The scene's name of a law (`signorini`, `coulomb`, `rccm`), as `law = { kind = ... }`
/// spells it.
pub fn law_name(law: &StandardLaw) -> &'static str {
    match law {
        StandardLaw::Signorini(_) => "signorini",
        StandardLaw::Coulomb(_) => "coulomb",
        StandardLaw::Rccm(_) => "rccm",
    }
}

/// The law names that `[[phases]] laws` sets, per phase: `(zone, law)`.
pub fn phase_law_names(phase_laws: &[Vec<(String, StandardLaw)>]) -> Vec<Vec<(String, String)>> {
    phase_laws
        .iter()
        .map(|set| {
            set.iter()
                .map(|(zone, law)| (zone.clone(), law_name(law).to_string()))
                .collect()
        })
        .collect()
}

/// The law of a zone during one phase of a run (`summary.json`: `zones[].laws`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PhaseLaw {
    pub phase: String,
    /// The law in force during it (`signorini`, `coulomb`, `rccm`).
    pub law: String,
    /// Its first global step (1-based).
    pub first_step: usize,
    /// Its last global step done (`first_step − 1` when the run stopped at its first step).
    pub last_step: usize,
}

/// Per zone, the law of each phase the run reached: the zone's own law (`zone_laws`) until a
/// phase's `laws` (`set`, per phase `(zone, law name)`) gives it another, which then holds
/// until the next. The phases listed are those with a step done (`steps_done` global steps)
/// and, for a run that `failed`, the one it stopped in.
pub fn laws_by_phase(
    phases: &[Phase],
    zone_names: &[String],
    zone_laws: &[String],
    set: &[Vec<(String, String)>],
    steps_done: usize,
    failed: bool,
) -> Vec<Vec<PhaseLaw>> {
    let mut current: Vec<String> = zone_laws.to_vec();
    let mut out = vec![Vec::new(); zone_names.len()];
    let mut before = 0;
    for (p, phase) in phases.iter().enumerate() {
        let first = before + 1;
        let reached = first <= steps_done || (failed && first == steps_done + 1);
        if !reached {
            break;
        }
        for (zone, law) in set.get(p).into_iter().flatten() {
            if let Some(z) = zone_names.iter().position(|n| n == zone) {
                current[z] = law.clone();
            }
        }
        let last = (before + phase.steps).min(steps_done);
        for (z, laws) in out.iter_mut().enumerate() {
            laws.push(PhaseLaw {
                phase: phase.name.clone(),
                law: current[z].clone(),
                first_step: first,
                last_step: last,
            });
        }
        before += phase.steps;
    }
    out
}

/// The law in force at the end of a run (the last phase's of `laws`, else `initial`).
pub fn final_law(laws: &[PhaseLaw], initial: &str) -> String {
    laws.last().map_or(initial, |l| l.law.as_str()).to_string()
}

/// The laws of a zone in words: its one law, or each law with its phases and steps when a
/// phase changed it (`signorini in `press` (steps 1–2), coulomb in `shear` (steps 3–6)`).
pub fn describe_laws(laws: &[PhaseLaw], initial: &str) -> String {
    if laws.iter().all(|l| l.law == initial) {
        return initial.to_string();
    }
    laws.iter()
        .map(|l| {
            let steps = if l.last_step < l.first_step {
                format!("stopped at step {}", l.first_step)
            } else if l.last_step == l.first_step {
                format!("step {}", l.first_step)
            } else {
                format!("steps {}–{}", l.first_step, l.last_step)
            };
            format!("{} in `{}` ({steps})", l.law, l.phase)
        })
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn laws_by_phase_follows_the_switches_works() {
        let phases = [phase("press", 2, 0.0, 1.0), phase("shear", 4, 1.0, 2.0)];
        let names = ["base".to_string(), "side".to_string()];
        let own = ["signorini".to_string(), "signorini".to_string()];
        let set = vec![
            Vec::new(),
            vec![("base".to_string(), "coulomb".to_string())],
        ];
        let laws = laws_by_phase(&phases, &names, &own, &set, 6, false);
        let base: Vec<_> = laws[0]
            .iter()
            .map(|l| (l.law.as_str(), l.first_step, l.last_step))
            .collect();
        assert_eq!(base, [("signorini", 1, 2), ("coulomb", 3, 6)]);
        assert_eq!(final_law(&laws[0], "signorini"), "coulomb");
        assert_eq!(final_law(&laws[1], "signorini"), "signorini");
        assert_eq!(
            describe_laws(&laws[0], "signorini"),
            "signorini in `press` (steps 1–2), coulomb in `shear` (steps 3–6)"
        );
        assert_eq!(describe_laws(&laws[1], "signorini"), "signorini");
        // a run that failed at the first step of `shear`: that phase is listed, no step done
        let failed = laws_by_phase(&phases, &names, &own, &set, 2, true);
        assert_eq!(failed[0].len(), 2);
        assert_eq!((failed[0][1].first_step, failed[0][1].last_step), (3, 2));
        // a run that stopped at step 2 without failing lists only `press`
        assert_eq!(
            laws_by_phase(&phases, &names, &own, &set, 2, false)[0].len(),
            1
        );
    }

    #[test]
    fn time_functions_interpolate_and_hold_works() {
        let p = KeyPath::root().key("functions").key("f");
        let f = time_function(&p, &[Pair([0.0, 0.0]), Pair([1.0, 2.0]), Pair([3.0, 2.0])]).unwrap();
        assert_eq!(f.eval(-1.0), 0.0);
        assert_eq!(f.eval(0.5), 1.0);
        assert_eq!(f.eval(2.0), 2.0);
        assert_eq!(f.eval(10.0), 2.0);
    }

    #[test]
    fn time_functions_rejects_non_increasing_times() {
        let p = KeyPath::root().key("functions").key("f");
        let e = time_function(&p, &[Pair([0.0, 0.0]), Pair([0.0, 1.0])]).unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "functions.f[1][0]");
        assert!(time_function(&p, &[]).is_err());
    }

    #[test]
    fn phase_times_end_exactly_works() {
        let ph = phase("p", 3, 2.0, 2.3);
        assert_eq!(ph.time(3), 2.3);
        assert!((ph.time(1) - 2.1).abs() < 1e-15);
    }
}
