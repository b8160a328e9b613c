//! What a run writes differently in 2D and 3D, in one place: the trait [`RunDim`], for
//! `Dim<2>` ([`super::plane`]) and `Dim<3>` ([`super::solid`]). The [`Recorder`](super::recorder)
//! is written once and asks it for the formats that are each dimension's contract:
//! `steps.csv` and `contacts.csv` (2D: the library's writers; 3D: the frame and the support
//! reactions appended), the VTK series, the rigid motions of floating bodies (2D), the
//! coordinates of `pressure.csv` and the order in which the files are listed.

use super::driver::Extras;
use super::plots::Plots;
use super::pressure::PressureRecorder;
use super::rigid::RigidMotionSummary;
use super::summary::{CurveSummary, ZoneSummary};
use crate::build::{HertzShape, Study, StudyDim};
use crate::error::CliResult;
use contact_laws::{ContactLaw, RccmState};
use contact_solver::coupling::traction::TractionField;
use contact_solver::{ContactRecord, ContactSimulation, StepResult};
use fem_core::boundary_mass::BoundaryMass;
use fem_core::{Dim, ElasticModel, FemError};
use std::path::Path;

/// A simulation the run steps: a scene's (`StandardLaw`) or a preset's (`Rccm`).
pub(crate) type Sim<L, const D: usize> = ContactSimulation<ElasticModel<D>, L, D>;

/// One step as the driver hands it to the recorder.
pub(crate) struct StepRow<'a> {
    /// Global step.
    pub(super) step: usize,
    /// Its phase's name.
    pub(super) phase: &'a str,
    pub(super) time: f64,
    pub(super) wall_time_s: f64,
    /// Numeric factorisations of this step (K refactored, and the active set's).
    pub(super) factorizations: usize,
    /// Quantities only the driver knows (the pile's head load).
    pub(super) extras: Extras,
}

/// What a run writes differently in each dimension (see the module docs).
pub(crate) trait RunDim<const D: usize>: StudyDim<D>
where
    Dim<D>: RunDim<D>,
{
    /// The writers of this dimension's CSV and VTK files.
    type Writers;

    /// Creates the files written from the first step on, listed in `files`; `pieces`: the
    /// mesh series as this rank's parallel pieces (a distributed run).
    ///
    /// # Errors
    /// A file that cannot be created.
    fn writers(
        study: &Study<D>,
        dir: &Path,
        pieces: Option<super::Pieces>,
        files: &mut Vec<String>,
    ) -> CliResult<Self::Writers>;

    /// The tangential columns of `pressure.csv` (`t`; `t1`, `t2`).
    const SHEAR: &'static [&'static str];

    /// The names of the axes (`x, y`, or `r, z` in axisymmetry; `x, y, z`).
    fn axes(model: &ElasticModel<D>) -> &'static [&'static str];

    /// The consistent mass of the boundary facets whose nodes are all in `nodes` (a zone's
    /// contactor surface, for the pressure recovery).
    ///
    /// # Errors
    /// The model's, for nodes without such a facet among others.
    fn surface_mass(model: &ElasticModel<D>, nodes: &[usize]) -> Result<BoundaryMass, FemError>;

    /// The shape `[hertz]` compares the pressure with (the plane or axisymmetric setting).
    fn hertz_shape(model: &ElasticModel<D>) -> HertzShape;

    /// Every step: its row of `steps.csv` (`zones` tallied already), the rigid motions, the
    /// plotted values; returns the nodal displacements when the step is `written` and its VTK
    /// files need them.
    fn step<L: ContactLaw<State = RccmState> + Clone>(
        w: &mut Self::Writers,
        plots: &mut Plots,
        sim: &Sim<L, D>,
        step: (&StepResult<D>, &StepRow<'_>, bool),
        zones: &[ZoneSummary<D>],
    ) -> CliResult<Option<Vec<[f64; D]>>>;

    /// A written step's rows of `contacts.csv` (`selected`: the contacts of `output.zones`).
    fn contacts<L: ContactLaw<State = RccmState> + Clone>(
        w: &mut Self::Writers,
        sim: &Sim<L, D>,
        step: (&StepResult<D>, &StepRow<'_>),
        selected: &[ContactRecord<D>],
        zones: &[ZoneSummary<D>],
    ) -> CliResult<()>;

    /// Whether a VTK series is written.
    fn vtk_active(w: &Self::Writers) -> bool;

    /// A written step's VTK files at time `t` (`fields`: the recovered traction, if the VTK
    /// files carry it).
    fn vtk(
        w: &mut Self::Writers,
        model: &ElasticModel<D>,
        written: (f64, &[ContactRecord<D>], Option<&[[f64; D]]>),
        fields: &[TractionField],
    ) -> CliResult<()>;

    /// The support reactions' sum at the last step, where this dimension keeps it.
    fn reaction(w: &Self::Writers) -> Option<[f64; D]>;

    /// Closes the files, writes the plots and the Hertz plot, listing them in `files` (in
    /// this dimension's order); returns the curves' extremes and the rigid motions.
    fn finish(
        w: Self::Writers,
        outputs: (&Plots, PressureRecorder),
        study: &Study<D>,
        dir: &Path,
        files: &mut Vec<String>,
    ) -> CliResult<(Vec<CurveSummary>, Vec<RigidMotionSummary>)>;
}

/// The reference positions of `study`'s nodes in 3D coordinates (`z = 0` in 2D).
pub(super) fn positions<const D: usize>(study: &Study<D>) -> Vec<[f64; 3]>
where
    Dim<D>: StudyDim<D>,
{
    study
        .model()
        .mesh()
        .nodes()
        .iter()
        .map(|x| std::array::from_fn(|a| if a < D { x[a] } else { 0.0 }))
        .collect()
}
