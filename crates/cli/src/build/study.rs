//! What a build gives: a [`Study`] ready to run, in 2D or 3D (`Study<3>`), its body (a scene
//! described key by key, with its supports, loads and time functions ready to apply, or a 2D
//! library preset) and its phases. What a study holds differently by dimension is
//! [`StudyDim`]'s.

use super::SceneDim;
use super::phases::{Phase, TimeFunction};
use crate::scene::{OutputSpec, PlotSpec, Units};
use contact_laws::{Rccm, StandardLaw};
use contact_solver::coupling::space::ContactSpace;
use contact_solver::{Candidate, ContactSimulation};
use fem_core::{Component, Dim, ElasticModel, Idealization, LinearElasticModel, Structure};
use std::collections::BTreeMap;

/// What a study holds and shows differently in 2D and 3D: its presets (2D only), the name of
/// its elements, the idealisation, and which `.vtu` series the body writes.
pub trait StudyDim<const D: usize>: SceneDim<D> + ContactSpace<D>
where
    Dim<D>: SceneDim<D> + ContactSpace<D>,
{
    /// A library preset of this dimension ([`PresetStudy`] in 2D; 3D has none: [`NoPreset`]).
    type Preset;
    /// The preset's simulation.
    fn preset_sim(p: &Self::Preset) -> &ContactSimulation<ElasticModel<D>, Rccm, D>;
    /// The preset's kind (`delamination`, `shear`, `pile`).
    fn preset_kind(p: &Self::Preset) -> &'static str;
    /// The idealisation, as the header names it (none in 3D).
    fn setting(model: &ElasticModel<D>) -> Option<String>;
    /// Whether the body's `mesh_NNNN.vtu` series is written: 2D with `output.mesh_vtk`, 3D also
    /// with `output.vtk` (its body series carries the contact forces).
    fn mesh_series(o: &OutputSpec) -> bool;
}

/// 3D has no preset: no value of this type exists.
pub enum NoPreset {}

impl StudyDim<2> for Dim<2> {
    type Preset = PresetStudy;

    fn preset_sim(p: &PresetStudy) -> &ContactSimulation<LinearElasticModel, Rccm> {
        p.sim()
    }

    fn preset_kind(p: &PresetStudy) -> &'static str {
        p.kind
    }

    fn setting(model: &LinearElasticModel) -> Option<String> {
        Some(match model.idealization() {
            Idealization::PlaneStrain => "plane strain".to_string(),
            Idealization::PlaneStress { thickness } => {
                format!("plane stress, thickness {thickness}")
            }
            Idealization::Axisymmetric => "axisymmetric".to_string(),
            _ => "other idealisation".to_string(),
        })
    }

    fn mesh_series(o: &OutputSpec) -> bool {
        o.writes_mesh_vtk()
    }
}

impl StudyDim<3> for Dim<3> {
    type Preset = NoPreset;

    fn preset_sim(p: &NoPreset) -> &ContactSimulation<ElasticModel<3>, Rccm, 3> {
        match *p {}
    }

    fn preset_kind(p: &NoPreset) -> &'static str {
        match *p {}
    }

    fn setting(_: &ElasticModel<3>) -> Option<String> {
        None
    }

    fn mesh_series(o: &OutputSpec) -> bool {
        o.vtk || o.writes_mesh_vtk()
    }
}

/// A support ready to apply.
#[derive(Clone, Debug)]
pub struct SupportRt {
    /// Name.
    pub name: Option<String>,
    pub nodes: Vec<usize>,
    pub components: Vec<Component>,
    /// Value.
    pub value: f64,
    pub function: Option<String>,
    pub phases: Vec<bool>,
}

/// The dofs released when phase `p > 0` starts: those of the supports that acted in phase
/// `p − 1` and not in `p`, less those a support of phase `p` prescribes. Those stay
/// constrained and only take their new value, so the body is never left without them in
/// between (a model that may not float refuses a release that leaves a rigid-body mode).
pub fn released_at(supports: &[SupportRt], p: usize) -> Vec<(Vec<usize>, Component)> {
    let held: std::collections::BTreeSet<(usize, Component)> = supports
        .iter()
        .filter(|s| s.phases[p])
        .flat_map(|s| {
            s.components
                .iter()
                .flat_map(|&c| s.nodes.iter().map(move |&n| (n, c)))
        })
        .collect();
    let mut out = Vec::new();
    for s in supports.iter().filter(|s| s.phases[p - 1] && !s.phases[p]) {
        for &c in &s.components {
            let nodes: Vec<usize> = s
                .nodes
                .iter()
                .copied()
                .filter(|&n| !held.contains(&(n, c)))
                .collect();
            if !nodes.is_empty() {
                out.push((nodes, c));
            }
        }
    }
    out
}

/// What a load is, in a scene of dimension `D` (2 or 3).
#[derive(Clone, Debug)]
pub enum LoadKind<const D: usize = 2> {
    /// Traction on a boundary set (an edge set in 2D, a face set in 3D).
    Traction(String, [f64; D]),
    /// Pressure on a face set, positive into the body (3D scenes only: a 2D scene refuses
    /// `type = "pressure"` when it is read).
    Pressure(String, f64),
    /// Force on each node.
    Nodal(Vec<usize>, [f64; D]),
    /// One force on a tied set, applied at this node of it.
    Resultant(usize, [f64; D]),
    Body([f64; D]),
    /// Self-weight (along −y in 2D, −z in 3D).
    Gravity,
}

/// A load ready to apply.
#[derive(Clone, Debug)]
pub struct LoadRt<const D: usize = 2> {
    /// Name.
    pub name: Option<String>,
    pub kind: LoadKind<D>,
    pub function: Option<String>,
    pub phases: Vec<bool>,
}

/// A scene described key by key.
pub struct Custom<const D: usize = 2>
where
    Dim<D>: StudyDim<D>,
{
    /// The simulation.
    pub sim: ContactSimulation<ElasticModel<D>, StandardLaw, D>,
    pub supports: Vec<SupportRt>,
    pub loads: Vec<LoadRt<D>>,
    pub functions: BTreeMap<String, TimeFunction>,
    /// Per phase, the laws it sets on zones at its start: `(zone, law)`.
    pub phase_laws: Vec<Vec<(String, StandardLaw)>>,
}

/// The library's scene of a preset.
pub enum Library {
    /// Delamination or shear (one loading phase).
    Seed(Box<crate::presets::Scene>),
    /// The pile pull-out (three phases).
    Pile(Box<crate::presets::PulloutScene>),
}

/// A seed study built by the library.
pub struct PresetStudy {
    /// `delamination`, `shear` or `pile`.
    pub kind: &'static str,
    pub scene: Library,
}

impl PresetStudy {
    /// The simulation.
    pub fn sim(&self) -> &ContactSimulation<LinearElasticModel, Rccm> {
        match &self.scene {
            Library::Seed(s) => &s.simulation,
            Library::Pile(p) => &p.simulation,
        }
    }
}

pub enum Body<const D: usize = 2>
where
    Dim<D>: StudyDim<D>,
{
    /// Key by key.
    Custom(Box<Custom<D>>),
    /// A preset (2D only).
    Preset(Box<<Dim<D> as StudyDim<D>>::Preset>),
}

/// `on_sim!(study, s => expr)`: `expr` with `s` the study's simulation, in both arms (a scene's
/// has the standard law, a preset's the RCCM law: two types). `D` is the caller's dimension.
macro_rules! on_sim {
    ($study:expr, $s:ident => $e:expr) => {
        match &$study.body {
            $crate::build::Body::Custom(c) => {
                let $s = &c.sim;
                $e
            }
            $crate::build::Body::Preset(p) => {
                let $s = <fem_core::Dim<D> as $crate::build::StudyDim<D>>::preset_sim(p);
                $e
            }
        }
    };
}
pub(crate) use on_sim;

/// A scene ready to run, in 2D or 3D (`[analysis] type = "3d"`).
pub struct Study<const D: usize = 2>
where
    Dim<D>: StudyDim<D>,
{
    pub title: String,
    pub units: Units,
    pub body: Body<D>,
    pub phases: Vec<Phase>,
    pub output: OutputSpec,
    /// Plots (validated).
    pub plots: Vec<PlotSpec>,
    pub zone_names: Vec<String>,
    pub zone_laws: Vec<String>,
    pub adhesive_zones: usize,
    pub friction_zones: usize,
    /// What the scene's checks let pass but the user should know (e.g. contactor nodes held
    /// by a support, left out): printed by `bipo check` and `bipo run`, and in `summary.json`.
    pub warnings: Vec<String>,
    /// `[hertz]`: the pressure plot against Hertz.
    pub hertz: Option<super::HertzPlan>,
}

impl<const D: usize> Study<D>
where
    Dim<D>: StudyDim<D>,
{
    pub fn candidates(&self) -> &[Candidate<D>] {
        on_sim!(self, s => s.candidates())
    }

    pub fn model(&self) -> &ElasticModel<D> {
        on_sim!(self, s => s.structure())
    }

    pub fn alert_distances(&self) -> Vec<f64> {
        on_sim!(self, s => s.zones().iter().map(|z| z.alert_distance).collect())
    }

    /// Each zone's name and contactor nodes.
    pub fn contactors(&self) -> Vec<(String, Vec<usize>)> {
        on_sim!(self, s => {
            s.zones().iter().map(|z| (z.name.clone(), z.contactor.clone())).collect()
        })
    }

    /// The laws each phase sets on zones at its start (`[[phases]] laws`; none for a preset),
    /// by name.
    pub fn phase_law_names(&self) -> Vec<Vec<(String, String)>> {
        match &self.body {
            Body::Custom(c) => super::phase_law_names(&c.phase_laws),
            Body::Preset(_) => Vec::new(),
        }
    }

    pub fn total_steps(&self) -> usize {
        self.phases.iter().map(|p| p.steps).sum()
    }

    /// The steps whose contacts and VTK files are written: every `output.every`-th global
    /// step and the last of each phase, or the listed `output.steps`. Counted without
    /// iterating over the steps.
    pub fn written_steps(&self) -> usize {
        written_steps(&self.output, &self.phases)
    }

    /// The files a run writes: one `.vtu` per written step and series (interface, mesh),
    /// their `.pvd`, the CSV histories, the plots, `curves.csv` and `summary.json`.
    pub fn output_files(&self) -> usize {
        let o = &self.output;
        let series = usize::from(o.vtk) + usize::from(Dim::<D>::mesh_series(o));
        let fixed = 1
            + usize::from(o.history)
            + usize::from(o.report)
            + usize::from(o.pressure)
            + usize::from(self.hertz.is_some());
        let plots = if self.plots.is_empty() {
            0
        } else {
            self.plots.len() + 1
        };
        self.written_steps()
            .saturating_add(1)
            .saturating_mul(series)
            .saturating_add(fixed + plots)
    }
}

/// The steps whose contacts and VTK files are written (see [`Study::written_steps`]).
pub fn written_steps(o: &OutputSpec, phases: &[Phase]) -> usize {
    if let Some(list) = &o.steps {
        let total: usize = phases.iter().map(|p| p.steps).sum();
        let set: std::collections::BTreeSet<_> =
            list.iter().filter(|s| (1..=total).contains(*s)).collect();
        return set.len();
    }
    let k = o.every.max(1);
    let mut start = 0usize;
    let mut n = 0usize;
    for p in phases {
        let end = start.saturating_add(p.steps);
        n = n.saturating_add(end / k - start / k);
        if !end.is_multiple_of(k) {
            n = n.saturating_add(1);
        }
        start = end;
    }
    n
}
