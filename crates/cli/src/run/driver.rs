//! What steps a study: the scene-file driver of either dimension (supports released and applied
//! per phase, loads scaled by their time functions, [`apply_step`]) or a 2D library preset (its
//! own step functions).

use super::errors::{fem_failed, step_error};
use crate::build::{
    Custom, Library, LoadRt, Phase, PresetStudy, SceneDim, StudyDim, SupportRt, TimeFunction,
    add_load, function_value, released_at,
};
use crate::error::{CliError, CliResult};
use crate::presets::ShaftPoint;
use contact_laws::{ContactLaw, RccmState};
use contact_solver::{ContactSimulation, StepResult};
use fem_core::{Dim, ElasticModel, LinearElasticModel};
use std::collections::BTreeMap;

/// What steps the simulation: the scene-file driver or a library preset.
pub(super) trait Driver<const D: usize>
where
    Dim<D>: StudyDim<D>,
{
    type Law: ContactLaw<State = RccmState> + Clone;
    fn sim(&self) -> &ContactSimulation<ElasticModel<D>, Self::Law, D>;
    fn begin_phase(&mut self, phases: &[Phase], p: usize) -> CliResult<()>;
    fn step(
        &mut self,
        phases: &[Phase],
        p: usize,
        k: usize,
        t: f64,
    ) -> Result<StepResult<D>, CliError>;
    fn end_phase(&mut self, phases: &[Phase], p: usize);
    /// Quantities only this driver knows (the pile's head load), at the last step.
    fn extras(&self) -> Extras {
        Extras::default()
    }
    /// The pile's shaft at the end of `res` (a step of this driver), for the profiles.
    fn profile(&self, _res: &StepResult<D>) -> Option<Vec<ShaftPoint>> {
        None
    }
}

/// Quantities of the pile preset at the last step.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Extras {
    pub(super) head_load: Option<f64>,
    pub(super) head_displacement: Option<f64>,
}

/// Steps a scene described key by key.
pub(super) struct CustomDriver<'a, const D: usize>
where
    Dim<D>: StudyDim<D>,
{
    c: &'a mut Custom<D>,
    last_loads: Option<Vec<f64>>,
}

impl<'a, const D: usize> CustomDriver<'a, D>
where
    Dim<D>: StudyDim<D>,
{
    /// The driver of `c`, before its first phase.
    pub(super) fn new(c: &'a mut Custom<D>) -> Self {
        Self {
            c,
            last_loads: None,
        }
    }
}

impl<const D: usize> Driver<D> for CustomDriver<'_, D>
where
    Dim<D>: StudyDim<D>,
{
    type Law = contact_laws::StandardLaw;

    fn sim(&self) -> &ContactSimulation<ElasticModel<D>, Self::Law, D> {
        &self.c.sim
    }

    fn begin_phase(&mut self, phases: &[Phase], p: usize) -> CliResult<()> {
        let c = &mut *self.c;
        // the laws this phase sets (the interface states carry over)
        for (zone, law) in c.phase_laws.get(p).into_iter().flatten() {
            c.sim.set_law(zone, *law).map_err(|e| {
                CliError::failed(format!(
                    "phase `{}`: setting the law of zone `{zone}`: {e}",
                    phases[p].name
                ))
            })?;
        }
        if p == 0 {
            return Ok(());
        }
        let model = c.sim.structure_mut();
        let changed = c.supports.iter().any(|s| s.phases[p - 1] && !s.phases[p]);
        for (nodes, comp) in released_at(&c.supports, p) {
            model.release(&nodes, comp).map_err(|e| {
                fem_failed(
                    &format!(
                        "phase `{}`: releasing the supports that end",
                        phases[p].name
                    ),
                    e,
                )
            })?;
        }
        let t = phases[p].t0;
        for s in c
            .supports
            .iter()
            .filter(|s| s.phases[p] && (changed || !s.phases[p - 1]))
        {
            let v = s.value * function_value(&phases[p], &s.name, &s.function, &c.functions, t);
            for &comp in &s.components {
                model.set_prescribed(&s.nodes, comp, v).map_err(|e| {
                    fem_failed(
                        &format!("phase `{}`: applying the supports", phases[p].name),
                        e,
                    )
                })?;
            }
        }
        self.last_loads = None;
        Ok(())
    }

    fn step(
        &mut self,
        phases: &[Phase],
        p: usize,
        _k: usize,
        t: f64,
    ) -> Result<StepResult<D>, CliError> {
        let c = &mut *self.c;
        let phase = &phases[p];
        apply_step(
            c.sim.structure_mut(),
            &c.supports,
            &c.loads,
            &c.functions,
            (phase, p),
            t,
            &mut self.last_loads,
        )?;
        let at = t.max(c.sim.time());
        c.sim.step(at, 1.0).map_err(|e| step_error(e, phase, t))
    }

    fn end_phase(&mut self, phases: &[Phase], p: usize) {
        if phases[p].reset_displacements {
            self.c.sim.reset_displacements();
        }
    }
}

/// Steps a library preset.
pub(super) struct PresetDriver<'a> {
    p: &'a mut PresetStudy,
    extras: Extras,
}

impl<'a> PresetDriver<'a> {
    /// The driver of `p`, before its first step.
    pub(super) fn new(p: &'a mut PresetStudy) -> Self {
        Self {
            p,
            extras: Extras::default(),
        }
    }
}

impl Driver<2> for PresetDriver<'_> {
    type Law = contact_laws::Rccm;

    fn sim(&self) -> &ContactSimulation<LinearElasticModel, Self::Law> {
        self.p.sim()
    }

    fn begin_phase(&mut self, _: &[Phase], _: usize) -> CliResult<()> {
        Ok(())
    }

    fn step(
        &mut self,
        phases: &[Phase],
        p: usize,
        k: usize,
        t: f64,
    ) -> Result<StepResult<2>, CliError> {
        let err = |e| step_error(e, &phases[p], t);
        match &mut self.p.scene {
            Library::Seed(s) => s.step(k).map_err(err),
            Library::Pile(s) => {
                let (res, v) = match p {
                    0 => (s.geostatic().map_err(err)?, 0.0),
                    1 => (s.install().map_err(err)?, 0.0),
                    _ => {
                        let r = s.pull(k).map_err(err)?;
                        (r.result, r.head_displacement)
                    }
                };
                self.extras = Extras {
                    head_load: Some(s.head_load(&res).map_err(err)?),
                    head_displacement: Some(v),
                };
                Ok(res)
            }
        }
    }

    fn end_phase(&mut self, _: &[Phase], _: usize) {}

    fn extras(&self) -> Extras {
        self.extras
    }

    fn profile(&self, res: &StepResult) -> Option<Vec<ShaftPoint>> {
        match &self.p.scene {
            Library::Pile(s) => Some(s.shaft_profile(res)),
            Library::Seed(_) => None,
        }
    }
}

/// The supports and loads of phase `p` (`phase`) at time `t`, on the model of either
/// dimension: each load scaled by its function, the loads rebuilt only when a factor changed
/// since `last` (the factors last applied; none: rebuild them).
pub(super) fn apply_step<const D: usize>(
    model: &mut ElasticModel<D>,
    supports: &[SupportRt],
    loads: &[LoadRt<D>],
    functions: &BTreeMap<String, TimeFunction>,
    (phase, p): (&Phase, usize),
    t: f64,
    last: &mut Option<Vec<f64>>,
) -> CliResult<()>
where
    Dim<D>: SceneDim<D>,
{
    for s in supports.iter().filter(|s| s.phases[p]) {
        let v = s.value * function_value(phase, &s.name, &s.function, functions, t);
        for &c in &s.components {
            model
                .set_prescribed(&s.nodes, c, v)
                .map_err(|e| fem_failed("prescribed displacement", e))?;
        }
    }
    let factors: Vec<f64> = loads
        .iter()
        .map(|l| {
            if l.phases[p] {
                function_value(phase, &l.name, &l.function, functions, t)
            } else {
                0.0
            }
        })
        .collect();
    if last.as_ref() == Some(&factors) {
        return Ok(());
    }
    model.clear_loads();
    for (l, &f) in loads.iter().zip(&factors) {
        if !l.phases[p] {
            continue;
        }
        add_load(model, &l.kind, f).map_err(|e| fem_failed("load", e))?;
    }
    *last = Some(factors);
    Ok(())
}
