//! The pull-out with a soil that may yield (issue 40): the preset's mesh, supports, loads,
//! geostatic stress and interface ([`PulloutSpec::build`], [`PulloutSpec::build_3d`]), the
//! soil a Drucker–Prager (or von Mises) [`PlasticModel`] region and the pile linear elastic,
//! stepped by the global Newton around contact
//! ([`ContactSimulation::with_newton`]).
//!
//! Two phases, as `examples/scenes/pile_dp.toml` (the 2D scene written key by key) and
//! contact-solver's `tests/support/pile_plastic.rs`: the geostatic step (self-weight and the
//! initial stress of seed eq. 6.1, which the plastic body takes over as its committed stress;
//! the head held at `u_z = 0`), then the head lifted by `v₀` in `steps` increments. The
//! installation of the elastic scene (an imposed radial displacement calibrated on the elastic
//! soil, added as nodal forces) is not served: [`Installation::None`] is required.
//!
//! The head load is the head's support reaction, as in the elastic scene:
//! ```text
//! Q = RING Σ_head (Bᵀσ − f − f_c)_z
//! ```
//! with `f` the head nodes' self-weight and `f_c` the contact forces acting on them.

use super::{Installation, Parts, PileSpace, PulloutSpec, PulloutStep};
use contact_laws::{ContactLaw, Rccm, StandardLaw};
use contact_solver::{
    ContactSimulation, NewtonSettings, SimulationSettings, SolverError, StepResult,
};
use fem_core::generate::{PILE, SOIL};
use fem_core::plastic::{ConstitutivePoint, DruckerPrager, LinearElasticPoint, PlasticModel};
use fem_core::{Component, Dim};
use std::sync::Arc;

/// The pull-out in a soil that may yield (module docs of `presets::pile::plastic`),
/// axisymmetric ([`PulloutSpec::build_plastic`]) or on a 3D quarter
/// ([`PulloutSpec::build_plastic_3d`]); its zones' law `L` ([`StandardLaw`] by default, as
/// `bipo`'s plastic scenes have it; [`Rccm`] works as well).
///
/// # Examples
/// The geostatic step in a Drucker–Prager sand, coarse mesh: the head carries
/// `Q₀ = (γ_p − γ_s) π R² L_p`, as in the elastic scene.
/// ```
/// use bipo::presets::{Installation, PulloutSpec};
/// use contact_solver::{NewtonSettings, SimulationSettings};
/// use fem_core::plastic::{ConeMatch, DruckerPrager, DruckerPragerParameters};
/// let mut spec = PulloutSpec::plancoet();
/// (spec.mesh.cells_shaft, spec.mesh.cells_soil_r, spec.mesh.cells_below_tip) = (4, 4, 3);
/// spec.installation = Installation::None;
/// let sand = DruckerPrager::new(DruckerPragerParameters {
///     young: spec.soil_young,
///     poisson: spec.soil_poisson,
///     friction_angle: 35.0,
///     dilatancy_angle: 35.0,
///     cohesion: 1.0,
///     cone: ConeMatch::PlaneStrain,
/// })?;
/// let settings = (SimulationSettings::default(), NewtonSettings::default());
/// let mut pile = spec.build_plastic::<contact_laws::StandardLaw>(Some(sand), settings)?;
/// let geo = pile.geostatic()?;
/// let q0 = spec.head_load_at_rest();
/// assert!((pile.head_load(&geo)? - q0).abs() < 1e-6 * q0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct PlasticPullout<const D: usize, L: ContactLaw = StandardLaw>
where
    Dim<D>: PileSpace<D>,
{
    /// The simulation (its structure the plastic body).
    pub simulation: ContactSimulation<PlasticModel<D>, L, D>,
    /// The spec it was built from.
    pub spec: PulloutSpec,
    /// The `pile_head` nodes, sorted (their `u_z` is the head displacement).
    pub head: Vec<usize>,
    /// Candidate indices of the shaft pairs, the tip corner's included.
    pub shaft_candidates: Vec<usize>,
    /// Candidate indices of the tip pairs.
    pub tip_candidates: Vec<usize>,
    /// `−Σ f_z` over the head nodes: their share of the self-weight (model units).
    head_weight: f64,
}

/// The axial component (`z`): the last one.
fn axial<const D: usize>() -> Component {
    Component::all::<D>()[D - 1]
}

impl PulloutSpec {
    /// The axisymmetric pull-out in a soil of law `soil` (module docs of
    /// `presets::pile::plastic`; `None`: linear elastic, the same body stepped by the same
    /// Newton), with the contact solver's and the Newton's `settings`.
    ///
    /// # Errors
    /// [`PulloutSpec::build`]'s; [`SolverError::Unsupported`] for an installation other than
    /// [`Installation::None`] or for force control; [`SolverError::InvalidSetting`] when the
    /// law's elastic constants are not [`Self::soil_young`] and [`Self::soil_poisson`]; a
    /// geostatic state outside the yield surface ([`fem_core::FemError::OutsideYieldSurface`]
    /// in [`SolverError::Structure`]).
    pub fn build_plastic<L: ContactLaw + Clone + From<Rccm>>(
        &self,
        soil: Option<DruckerPrager>,
        settings: (SimulationSettings, NewtonSettings),
    ) -> Result<PlasticPullout<2, L>, SolverError> {
        self.check_plastic(soil.as_ref())?;
        let parts = self.axisymmetric_parts()?;
        self.plastic(parts, soil, settings)
    }

    /// [`Self::build_plastic`] on the 3D quarter of `sectors` sectors
    /// ([`PulloutSpec::build_3d`]'s mesh, supports and zones; the contact settings those of
    /// [`SimulationSettings::for_dimension`]`::<3>()` unless tuned).
    ///
    /// # Errors
    /// As [`Self::build_plastic`]; [`SolverError::InvalidSetting`] for zero sectors.
    pub fn build_plastic_3d<L: ContactLaw + Clone + From<Rccm>>(
        &self,
        sectors: usize,
        soil: Option<DruckerPrager>,
        settings: (SimulationSettings, NewtonSettings),
    ) -> Result<PlasticPullout<3, L>, SolverError> {
        self.check_plastic(soil.as_ref())?;
        if sectors == 0 {
            return Err(SolverError::InvalidSetting {
                what: "sectors",
                value: 0.0,
                expected: "at least one sector",
            });
        }
        let parts = self.quarter_parts(sectors, false)?;
        self.plastic(parts, soil, settings)
    }

    /// What the plastic pull-out refuses, on top of [`Self::check`].
    fn check_plastic(&self, soil: Option<&DruckerPrager>) -> Result<(), SolverError> {
        self.check()?;
        if self.installation != Installation::None {
            return Err(SolverError::Unsupported(
                "the installation phase in a soil that may yield (its radial displacement is \
                 calibrated on the elastic soil): take Installation::None"
                    .into(),
            ));
        }
        if self.head_force.is_some() {
            return Err(SolverError::Unsupported(
                "force control of the pile head in a soil that may yield (a floating pile: the \
                 global Newton needs supports that hold the body)"
                    .into(),
            ));
        }
        let Some(p) = soil.map(DruckerPrager::parameters) else {
            return Ok(());
        };
        for (what, law, spec) in [
            ("soil law's young", p.young, self.soil_young),
            ("soil law's poisson", p.poisson, self.soil_poisson),
        ] {
            if law != spec {
                return Err(SolverError::InvalidSetting {
                    what,
                    value: law,
                    expected: "the spec's soil_young and soil_poisson (one soil)",
                });
            }
        }
        Ok(())
    }

    /// The plastic body on the parts' elastic model (the soil `soil`, the pile linear
    /// elastic), the head's weight read off it, the simulation with the Newton.
    fn plastic<L: ContactLaw + Clone, const D: usize>(
        &self,
        parts: Parts<D, L>,
        soil: Option<DruckerPrager>,
        (settings, newton): (SimulationSettings, NewtonSettings),
    ) -> Result<PlasticPullout<D, L>, SolverError>
    where
        Dim<D>: PileSpace<D>,
    {
        let soil: Arc<dyn ConstitutivePoint> = match soil {
            Some(law) => Arc::new(law),
            None => Arc::new(LinearElasticPoint::new(self.soil_young, self.soil_poisson)?),
        };
        let laws: [(u32, Arc<dyn ConstitutivePoint>); 2] = [
            (SOIL, soil),
            (
                PILE,
                Arc::new(LinearElasticPoint::new(self.pile_young, self.pile_poisson)?),
            ),
        ];
        // the plastic body takes the model's initial stress over as its committed stress
        let body = PlasticModel::new(parts.model, &laws)?;
        // −f at the head's prescribed u_z: `K 0 − f` of the elastic model, which no longer
        // holds the initial stress
        let elastic = body.elastic();
        let zero = vec![[0.0; D]; elastic.mesh().node_count()];
        let axial = axial::<D>();
        let head_weight = elastic
            .reactions(&zero, 1.0)?
            .iter()
            .filter(|((n, c), _)| *c == axial && parts.head.binary_search(n).is_ok())
            .map(|(_, r)| r)
            .sum();
        let simulation =
            ContactSimulation::new(body, parts.zones, settings)?.with_newton(newton)?;
        Ok(PlasticPullout {
            simulation,
            spec: self.clone(),
            head: parts.head,
            shaft_candidates: parts.shaft_candidates,
            tip_candidates: parts.tip_candidates,
            head_weight,
        })
    }
}

impl<const D: usize, L: ContactLaw + Clone> PlasticPullout<D, L>
where
    Dim<D>: PileSpace<D>,
{
    /// Phase 1, the geostatic step (to time 1).
    ///
    /// # Errors
    /// The step's (a Newton that does not converge after its cuts, say).
    pub fn geostatic(&mut self) -> Result<StepResult<D>, SolverError> {
        self.simulation.step(1.0, 1.0)
    }

    /// Pull-out increment `k` (1-based, to time `1 + k`): the head at `u_z = v₀ k / steps`.
    ///
    /// # Errors
    /// The step's; [`SolverError::Structure`] if the head's support cannot be set.
    pub fn pull(&mut self, k: usize) -> Result<PulloutStep<D>, SolverError> {
        let v = self.spec.head_displacement * k as f64 / self.spec.steps as f64;
        self.simulation
            .structure_mut()
            .set_prescribed(&self.head, axial::<D>(), v)?;
        let result = self.simulation.step(1.0 + k as f64, 1.0)?;
        Ok(PulloutStep {
            increment: k,
            head_displacement: v,
            head_load: self.head_load(&result)?,
            result,
        })
    }

    /// The head load `Q` (kN, full ring, upwards) at the end of `result`, the step just
    /// solved (module docs of `presets::pile::plastic`).
    ///
    /// # Errors
    /// [`SolverError::Structure`] for a head node outside the mesh (not with a built scene).
    pub fn head_load(&self, result: &StepResult<D>) -> Result<f64, SolverError> {
        let body = self.simulation.structure();
        let mut q = body.reaction(&self.head, axial::<D>())? + self.head_weight;
        for (c, rec) in self.simulation.candidates().iter().zip(&result.contacts) {
            // global force on the contactor, −w times it on each target
            let f_z = rec.force()[D - 1];
            if self.head.binary_search(&c.node).is_ok() {
                q -= f_z;
            }
            for &(t, w) in c.targets.iter().flatten() {
                if self.head.binary_search(&t).is_ok() {
                    q += w * f_z;
                }
            }
        }
        Ok(<Dim<D> as PileSpace<D>>::RING * q)
    }

    /// The material points that yielded in the last converged step.
    pub fn yielding_points(&self) -> usize {
        let states = self.simulation.structure().committed_states();
        states.iter().filter(|s| s.yielding).count()
    }
}
