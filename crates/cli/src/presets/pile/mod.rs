//! Seed chapter 6: the pull-out of a driven steel pile (Plancoët and Cran), axisymmetric, P2,
//! with the shaft as node-to-node contact pairs carrying the RCCM law (or plain Coulomb
//! friction, fig. 6.5).
//!
//! Units: **kN, m, kPa** (kN/m²); unit weights and interface stiffnesses in kN/m³, `w` in kN/m
//! (kJ/m²). Forces of the axisymmetric model are per radian; every load this module reports
//! is a full-ring force (× 2π), in kN.
//!
//! # The three phases (seed §6.3)
//! 1. **Geostatic** ([`PulloutScene::geostatic`]): self-weight of pile and soil plus the initial
//!    stress of seed eq. 6.1. The soil has `σ_zz = γ_s z`, `σ_rr = σ_θθ = K0 σ_zz`
//!    (`z ≤ 0` down from the ground surface, tension positive). The pile gets the initial
//!    stress that balances its own weight with the soil's stress on its faces:
//!    ```text
//!    pile:  σ_rr = σ_θθ = K0 γ_s z,   σ_zz = −γ_s L_p + γ_p (z + L_p),   σ_rz = 0
//!    ```
//!    so the radial stress is continuous across the shaft, `σ_zz` is continuous across the tip,
//!    and the head, whose `u_z` is held, carries the excess weight
//!    `Q₀ = (γ_p − γ_s) π R² L_p`. Everything is in equilibrium at zero displacement: phase 1
//!    gives `u = 0` and shaft normal reactions `r_n = K0 γ_s |z| A` exactly (P2 consistent
//!    areas `A`, see below).
//! 2. **Installation** ([`PulloutScene::install`]): an imposed radial displacement `δ` of the
//!    soil's interface nodes, its stress kept and its displacement reset (the seed recovers "le
//!    nouveau champ de contrainte et les forces sur l'interface" and cancels the displacement
//!    field before the pull-out). The model is linear, so we solve the
//!    increment once, on the soil alone (the pile is a separate body, see the tip below), with
//!    `u_r = δ` on `interface_soil`: its stress `Δσ = D B u_δ` is self-balanced except at those
//!    nodes, where it leaves the reactions `R_δ`. Keeping `Δσ` while resetting `u_δ` is then
//!    exactly adding the nodal forces `−R_δ` to the soil's interface nodes: they press the soil
//!    onto the pile. `δ` is what the seed calibrates; see [`Installation`].
//! 3. **Pull-out** ([`PulloutScene::pull`]): the head `u_z = v₀ k / steps`, `k = 1 … steps`
//!    (seed: 15 mm for Plancoët, 6 mm for Cran, in 50 increments), each increment in
//!    [`PulloutSpec::substeps`] simulation steps.
//!
//! # Modelling choices the seed leaves open
//! - **Contactor and normal.** The pile's shaft nodes are the contactors, the soil's the
//!   targets, paired by index (`interface_pile[i]` ↔ `interface_soil[i]`); the normal points
//!   from the soil to the pile, `n = −e_r`, so `t = (n_z, −n_r) = +e_z`: `u_t > 0` is the pile
//!   moving up relative to the soil and the shaft friction on the pile during pull-out is
//!   `r_t < 0`.
//! - **Tributary areas** are P2-consistent (Simpson weights `h/6, 4h/6, h/6` per side, times the
//!   radius; `∫ N_i r ds` for P1), not the half-segment lumping: a linearly varying stress is
//!   then recovered exactly as `r / A` at every node, and the RCCM springs `C A_i` integrate the
//!   interface energy with Simpson's rule.
//! - **The tip.** fem-core's mesh bonds the pile tip to the soil below. A bonded tip would take
//!   tension during the pull-out and add to the head load without bound (a closed-ended pile's
//!   tip lifts off), so the tip nodes at `r < D/2` are duplicated and paired in a second,
//!   frictionless, non-adhesive zone (Signorini, normal `+e_z`). In phase 1 it carries the soil
//!   column `γ_s L_p` per area; it opens during the pull-out.
//! - **The tip corner** `(D/2, −L_p)` belongs to both faces. It stays the lowest shaft pair (65
//!   pairs, as in the seed) with the radial normal, in a zone of its own with plain Coulomb
//!   friction (same `μ`, no adhesion): in phase 1 it must carry, tangentially, the share of the
//!   tip's vertical pressure that falls on it (pile copy pushed down, soil copy up). Coulomb
//!   sticks rigidly as long as that share is below `μ r_n` (ratio `h_pile,r / (K0 h_shaft)`:
//!   0.39 with the default mesh), while an adhesive pair (β = 1, μ̄ = 0) would carry it on its
//!   spring `C A` alone, i.e. slip by millimetres in phase 1.
//! - **Supports.** `u_r = 0` on the axis (pile and soil) and on the outer side, `u_z = 0` at
//!   the base, and the pile head's `u_z` prescribed from the start (0 in phases 1–2): without
//!   contact the pile would float and `K` be singular.
//! - **Head load.** `Q = 2π Σ R_z` over the `pile_head` nodes, the force the jack applies on the
//!   pile ([`PulloutScene::head_load`]). The contact force on the head's corner node acts on a
//!   prescribed dof, so it is taken out of the support reaction `K u − f` there. At full slip,
//!   with the tip open, `Q = W_p + 2π Σ |r_t|` (seed eq. 1.2, `Q_t = Q_f + W`), with
//!   `W_p = γ_p π R² L_p`; at `v = 0`, `Q = Q₀ = W_p − γ_s π R² L_p` (the soil column under the
//!   tip carries the rest of the pile's weight). Field curves start at 0 (the soil carried the
//!   whole weight): compare them with `Q − Q₀` at small `v` and with `Q` at failure.
//! - **The β update (α = 0).** The plain fixed point of the seed (solve with frozen β, update β
//!   from the jumps, repeat) falls into a 2-cycle here as soon as a pair starts to debond: with
//!   `f(β) = 1 − β` a lower β makes the interface *stronger* (friction `μ(1 − β) σ_n` grows
//!   faster than the springs `C β² u` weaken), and the loop gain near the onset is about
//!   `2 μ σ_n / (k_s √(w/C))` ≈ 10 (`k_s` the soil's shear stiffness per area). The simulation's
//!   fixed point is therefore damped and Anderson-accelerated ([`contact_solver::local::adhesion`]), which
//!   converges: [`BetaCoupling::FixedPoint`] (the default) solves each of the seed's 50
//!   increments implicitly, about 15 β iterations per increment. [`BetaCoupling::Staggered`]
//!   (one solve with the β of the start of the step, then the update) is kept for comparison:
//!   it converges to the same curve at first order in the step (Plancoët, head load at 1.5 mm:
//!   166.57 kN with 4 steps per increment, 167.08 with 16, 167.45 implicit).
//! - **Units of `w`.** Table 6.3 gives `w = 3e-3 J/m²`. Read literally (3e-6 kN/m) the adhesive
//!   strength `√(wC)` would be 0.18 kPa and the debonding slip `√(w/C)` 17 µm, both invisible
//!   at the seed's increments (0.3 mm), and its parametric study of `w` (fig. 6.10) could not
//!   show anything. We take the table's number in the simulation's units, `w = 3e-3 kN/m`
//!   (3 J/m²): `√(wC)` = 5.6 kPa and `√(w/C)` = 0.53 mm for Plancoët.

use contact_laws::{BetaScheme, Rccm, RccmParams};
use contact_solver::SolverError;
use contact_solver::coupling::simulation::{ContactSimulation, SimulationSettings};
use contact_solver::coupling::zone::{ContactZone, PairNormals};
use fem_core::generate::{PileSpec, TipCorner};
use fem_core::{Dim, ElasticModel, Stress, StressField};
use std::f64::consts::PI;
use std::sync::Arc;

mod axisymmetric;
mod meridian;
mod plastic;
mod scene;
mod solid;

pub(crate) use meridian::detach_tip;
pub use plastic::PlasticPullout;
use scene::Phase;
pub use scene::{PileSpace, PulloutRun, PulloutScene, PulloutStep, ShaftPoint};

/// How the installation (phase 2) is modelled: the imposed radial displacement `δ` of the soil's
/// interface nodes, uniform along the shaft (seed §6.3, third method).
///
/// The seed chooses `δ` "to approach the measured limit of the shaft friction"; the field curves
/// are not in its text, so by default we calibrate `δ` to a lateral earth pressure instead:
/// [`Installation::NormalForceRatio`]`(2.0)` makes the total shaft normal force after
/// installation twice the geostatic one, `K_s = 2 K0` on average, the upper end of the range
/// usually quoted for large-displacement driven piles (`K_s / K0 = 1 … 2`, Kulhawy 1984). The
/// ultimate shaft friction is `μ` times that force, so a target friction maps to a ratio.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Installation {
    /// No installation: the pull-out starts from the geostatic state.
    None,
    /// The radial displacement `δ` (m, `> 0` pushes the soil away from the axis).
    RadialDisplacement(f64),
    /// `δ` such that the shaft normal force after installation is this multiple (`≥ 1`) of the
    /// geostatic one. The response is linear in `δ`, so one unit solve calibrates it.
    NormalForceRatio(f64),
}

/// How a step couples the contact solve with the β update of the RCCM law (see the
/// [module docs](self)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BetaCoupling {
    /// One solve with the β of the start of the step, then the β update (staggered, explicit):
    /// sets `max_adhesion_iterations = 1` and accepts the unconverged fixed point; the scene
    /// then checks the contact solver's residual itself. First order in the step.
    Staggered,
    /// The simulation's (damped, accelerated) fixed point, to `adhesion_tol` (the settings as
    /// given): implicit in β. The default.
    #[default]
    FixedPoint,
}

/// Seed chapter 6: the pull-out test, ready to build. [`Default`] is Plancoët with the RCCM
/// interface; see [`PulloutSpec::plancoet`], [`PulloutSpec::cran`] and
/// [`PulloutSpec::with_coulomb_interface`]. Units: kN, m, kPa (see the [module docs](self)).
#[derive(Clone, Debug, PartialEq)]
pub struct PulloutSpec {
    /// Geometry and mesh (fem-core's generator): `D = 0.27 m`, `L_p`, `W = 2 L_p`,
    /// `H = 3.5 L_p`, P2, 32 shaft cells (65 interface pairs). Must keep
    /// [`TipCorner::Split`].
    pub mesh: PileSpec,
    /// Young's modulus of the pile (3e7 kPa Plancoët, 3e6 kPa Cran).
    pub pile_young: f64,
    /// Poisson's ratio of the pile (0.3).
    pub pile_poisson: f64,
    /// Unit weight of the pile `γ_p` (78 kN/m³: the seed's solid cylinder has the unit weight
    /// of steel).
    pub pile_unit_weight: f64,
    /// Young's modulus of the soil (3e4 kPa).
    pub soil_young: f64,
    /// Poisson's ratio of the soil (0.33).
    pub soil_poisson: f64,
    /// Unit weight of the soil `γ_s` (20 kN/m³; total stresses, no water table in the seed).
    pub soil_unit_weight: f64,
    /// Coefficient of earth pressure at rest `K0` (0.43).
    pub k0: f64,
    /// Phase 2 (default: [`Installation::NormalForceRatio`]`(2.0)`, our calibration).
    pub installation: Installation,
    /// Final head displacement `v₀` (0.015 m Plancoët, 0.006 m Cran).
    pub head_displacement: f64,
    /// Force control (issue 16): `Some(Q)` makes the pile head a rigid cap (its nodes tied
    /// along `z`) that no support holds, loaded by the upward jack force `Q` (kN, full ring)
    /// ramped over the pull-out increments; the pile then floats, held by the interface (the
    /// adhesive shaft, the tip, the corner) through all three phases. `None` (the default,
    /// the seed's test): the head's `u_z` is prescribed, `0` in phases 1–2, then up to
    /// [`Self::head_displacement`].
    pub head_force: Option<f64>,
    /// Pull-out increments (50).
    pub steps: usize,
    /// Simulation steps per increment (1: the seed's 50 increments; more only for
    /// [`BetaCoupling::Staggered`]).
    pub substeps: usize,
    /// Coupling of the solve and the β update ([`BetaCoupling::FixedPoint`]).
    pub beta_coupling: BetaCoupling,
    /// The shaft interface (table 6.3): `C_n = C_t` (10500 kN/m³ Plancoët, 2500 Cran),
    /// `w = 3e-3` kN/m, `α = 0`, `μ = 0.46`, `m = 1`, `β₀ = 1`.
    pub interface: RccmParams,
    /// Alert distance of the zones (1 mm, our choice; the shaft pairs stay closed and adhesive
    /// pairs are always in the problem).
    pub alert_distance: f64,
}

impl Default for PulloutSpec {
    fn default() -> Self {
        Self::plancoet()
    }
}

impl PulloutSpec {
    /// Plancoët: `L_p = 13 m`, `E_p = 3e4 MPa`, `C = 10500 kN/m³`, `v₀ = 15 mm`.
    ///
    /// # Examples
    /// ```
    /// use bipo::presets::PulloutSpec;
    /// let spec = PulloutSpec::plancoet();
    /// assert_eq!(spec.mesh.length, 13.0);
    /// assert_eq!(spec.interface.c_t, 10500.0);
    /// ```
    pub fn plancoet() -> Self {
        Self::site(13.0, 3e7, 10500.0, 0.015)
    }

    /// Cran: `L_p = 17 m`, `E_p = 3e3 MPa`, `C = 2500 kN/m³`, `v₀ = 6 mm`; the domain scales
    /// with `L_p` (`W = 2 L_p`, `H = 3.5 L_p`).
    ///
    /// # Examples
    /// ```
    /// use bipo::presets::PulloutSpec;
    /// let spec = PulloutSpec::cran();
    /// assert_eq!((spec.mesh.width, spec.mesh.depth), (34.0, 59.5));
    /// ```
    pub fn cran() -> Self {
        Self::site(17.0, 3e6, 2500.0, 0.006)
    }

    fn site(length: f64, pile_young: f64, c: f64, head_displacement: f64) -> Self {
        Self {
            mesh: PileSpec {
                length,
                width: 2.0 * length,
                depth: 3.5 * length,
                ..PileSpec::default()
            },
            pile_young,
            pile_poisson: 0.3,
            pile_unit_weight: 78.0,
            soil_young: 3e4,
            soil_poisson: 0.33,
            soil_unit_weight: 20.0,
            k0: 0.43,
            installation: Installation::NormalForceRatio(2.0),
            head_displacement,
            head_force: None,
            steps: 50,
            substeps: 1,
            beta_coupling: BetaCoupling::FixedPoint,
            interface: RccmParams {
                c_n: c,
                c_t: c,
                w: 3e-3,
                alpha: 0.0,
                mu: 0.46,
                m: 1,
                beta_0: 1.0,
                scheme: BetaScheme::ImplicitEuler,
            },
            alert_distance: 1e-3,
        }
    }

    /// The same test with the plain Coulomb interface of seed fig. 6.5: `β₀ = 0` (no adhesion,
    /// friction `μ` from the start, rigid while sticking).
    ///
    /// # Examples
    /// ```
    /// use bipo::presets::PulloutSpec;
    /// assert_eq!(PulloutSpec::cran().with_coulomb_interface().interface.beta_0, 0.0);
    /// ```
    pub fn with_coulomb_interface(mut self) -> Self {
        self.interface.beta_0 = 0.0;
        self
    }

    /// Pile radius `R = D/2`.
    pub fn radius(&self) -> f64 {
        0.5 * self.mesh.diameter
    }

    /// The pile's weight `W_p = γ_p π R² L_p` (kN).
    pub fn pile_weight(&self) -> f64 {
        self.pile_unit_weight * PI * self.radius().powi(2) * self.mesh.length
    }

    /// The head load at rest `Q₀ = (γ_p − γ_s) π R² L_p` (kN): the pile's weight less the soil
    /// column the tip stands on.
    pub fn head_load_at_rest(&self) -> f64 {
        (self.pile_unit_weight - self.soil_unit_weight)
            * PI
            * self.radius().powi(2)
            * self.mesh.length
    }

    /// The initial stress of phase 1 (see the [module docs](self)) of the axisymmetric model,
    /// in [`Stress`] order `(rr, zz, rz, θθ)`, tension positive.
    pub fn initial_stress(&self) -> StressField {
        let (radius, length) = (self.radius(), self.mesh.length);
        let stress = self.geostatic_stress();
        Arc::new(move |x: [f64; 2]| -> Stress {
            let (s_rr, s_zz) = stress(x[1], x[0] < radius && x[1] > -length);
            [s_rr, s_zz, 0.0, s_rr]
        })
    }

    /// Phase 1's stresses `(σ_rr = σ_θθ, σ_zz)` at the height `z` (taken as `min(z, 0)`), in
    /// the pile (`in_pile`) or in the soil (module docs), tension positive, no shear: one
    /// formula for both dimensions.
    fn geostatic_stress(&self) -> impl Fn(f64, bool) -> (f64, f64) + Copy + Send + Sync + 'static {
        let length = self.mesh.length;
        let (gamma_s, gamma_p, k0) = (self.soil_unit_weight, self.pile_unit_weight, self.k0);
        move |z: f64, in_pile: bool| {
            let z = z.min(0.0);
            let s_rr = k0 * gamma_s * z;
            if in_pile {
                (s_rr, -gamma_s * length + gamma_p * (z + length))
            } else {
                (s_rr, gamma_s * z)
            }
        }
    }

    /// The shaft normal force of phase 1, `Σ K0 γ_s |z| A` over the shaft's `(z, A)`.
    fn shaft_normal_at_rest(&self, shaft: impl IntoIterator<Item = (f64, f64)>) -> f64 {
        shaft
            .into_iter()
            .map(|(z, a)| self.k0 * self.soil_unit_weight * (-z).max(0.0) * a)
            .sum()
    }

    /// Finishes a scene from what a dimension's builder made: the coupling's settings, the
    /// simulation, and `δ` for the requested installation from the geostatic shaft normal
    /// force and the unit installation's (both in the model's units).
    fn assemble<const D: usize>(
        &self,
        parts: Parts<D>,
        mut settings: SimulationSettings,
    ) -> Result<PulloutScene<D>, SolverError>
    where
        Dim<D>: PileSpace<D>,
    {
        let tol = settings.solver.tol;
        if self.beta_coupling == BetaCoupling::Staggered {
            settings.max_adhesion_iterations = 1;
            settings.solver.accept_non_converged = true;
        }
        let simulation = ContactSimulation::new(parts.model, parts.zones, settings)?;
        let unit_normal = parts.unit_normal;
        if !(unit_normal > 0.0 && unit_normal.is_finite()) {
            return Err(SolverError::InvalidGeometry(format!(
                "the installation's unit radial displacement gives a shaft normal force of \
                 {unit_normal}, not a compression"
            )));
        }
        let delta = match self.installation {
            Installation::None => 0.0,
            Installation::RadialDisplacement(d) => d,
            Installation::NormalForceRatio(k) => (k - 1.0) * parts.geostatic_normal / unit_normal,
        };
        Ok(PulloutScene {
            simulation,
            spec: self.clone(),
            head: parts.head,
            shaft_candidates: parts.shaft_candidates,
            tip_candidates: parts.tip_candidates,
            installation_forces: parts
                .unit_forces
                .into_iter()
                .map(|(n, f)| (n, f.map(|v| -v * delta)))
                .collect(),
            installation_displacement: delta,
            tol,
            phase: Phase::Start,
            applied_force: 0.0,
        })
    }

    /// The three zones (module docs) from their pairs: the shaft's RCCM interface, the tip
    /// corner's plain Coulomb friction (no adhesion), the tip's frictionless contact.
    ///
    /// # Errors
    /// [`SolverError::Law`] for invalid interface parameters.
    fn zones<L: From<Rccm>, const D: usize>(
        &self,
        [shaft, corner, tip]: [ZonePairs<D>; 3],
    ) -> Result<Vec<ContactZone<L, D>>, SolverError>
    where
        Dim<D>: PileSpace<D>,
    {
        let shaft_law = Rccm::new(self.interface)?;
        let corner_law = Rccm::new(RccmParams {
            beta_0: 0.0,
            ..self.interface
        })?;
        let tip_law = Rccm::new(RccmParams {
            mu: 0.0,
            beta_0: 0.0,
            ..self.interface
        })?;
        let zones = [
            ("shaft", shaft, shaft_law),
            ("tip_corner", corner, corner_law),
            ("tip", tip, tip_law),
        ];
        Ok(zones
            .into_iter()
            .map(|(name, p, law)| {
                ContactZone::node_pairs(
                    name,
                    p.pile,
                    p.soil,
                    p.normals,
                    L::from(law),
                    self.alert_distance,
                )
                .with_areas(p.areas)
            })
            .collect())
    }

    fn check(&self) -> Result<(), SolverError> {
        let bad = |what: &'static str, value: f64, expected: &'static str| {
            Err(SolverError::InvalidSetting {
                what,
                value,
                expected,
            })
        };
        if self.mesh.tip_corner != TipCorner::Split {
            return bad(
                "mesh.tip_corner",
                1.0,
                "TipCorner::Split (a shared corner would bond the pile to the soil)",
            );
        }
        if !(self.k0.is_finite() && self.k0 >= 0.0) {
            return bad("k0", self.k0, "a finite K0 >= 0");
        }
        if let Some(q) = self.head_force
            && !q.is_finite()
        {
            return bad("head_force", q, "a finite force (kN, full ring, upwards)");
        }
        if !self.head_displacement.is_finite() {
            return bad(
                "head_displacement",
                self.head_displacement,
                "a finite displacement",
            );
        }
        if self.steps == 0 {
            return bad("steps", 0.0, "at least one pull-out increment");
        }
        if self.substeps == 0 {
            return bad("substeps", 0.0, "at least one step per increment");
        }
        if !(self.alert_distance.is_finite() && self.alert_distance >= 0.0) {
            return bad(
                "alert_distance",
                self.alert_distance,
                "a finite distance >= 0",
            );
        }
        match self.installation {
            Installation::RadialDisplacement(d) if !d.is_finite() => {
                bad("installation", d, "a finite radial displacement")
            }
            Installation::NormalForceRatio(k) if !(k.is_finite() && k >= 1.0) => {
                bad("installation", k, "a finite normal-force ratio >= 1")
            }
            _ => Ok(()),
        }
    }
}

/// What a dimension's builder makes ([`PulloutSpec::build`], [`PulloutSpec::build_3d`]) for
/// [`PulloutSpec::assemble`] (or the plastic pull-out's builder) to finish, its zones' law `L`.
struct Parts<const D: usize, L = Rccm>
where
    Dim<D>: PileSpace<D>,
{
    /// The model with its self-weight and initial stress.
    model: ElasticModel<D>,
    /// Shaft, tip corner, tip.
    zones: Vec<ContactZone<L, D>>,
    /// The `pile_head` nodes, sorted.
    head: Vec<usize>,
    shaft_candidates: Vec<usize>,
    tip_candidates: Vec<usize>,
    /// The shaft normal force of phase 1, `Σ K0 γ_s |z| A`.
    geostatic_normal: f64,
    /// The soil's interface forces per unit `δ` (the unit installation's reactions, divided by
    /// its `δ₁`), and their resultant along `e_r`.
    unit_forces: Vec<(usize, [f64; D])>,
    unit_normal: f64,
}

/// The node pairs of one zone: the pile's nodes (contactors), the soil's (targets), their
/// normals (from the soil to the pile) and tributary areas.
struct ZonePairs<const D: usize>
where
    Dim<D>: PileSpace<D>,
{
    pile: Vec<usize>,
    soil: Vec<usize>,
    normals: PairNormals<D>,
    areas: Vec<f64>,
}
