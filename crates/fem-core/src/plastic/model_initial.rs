//! Initial stresses of a [`PlasticModel`]: a stress field per region set as the committed
//! stress of the points (zero strain), refused where it is outside the yield surface; the
//! geostatic K0 state as such a field.
//!
//! ```text
//! σ_v(x) = −Σ_i γ_i h_i(z)     σ_h = K0 σ_v     no shear      (compression negative)
//! ```
//! with `z` the last coordinate (upwards), `h_i(z)` the thickness of layer `i` between `z`
//! and the ground surface `z_s`, and `γ_i` the unit weight of its material (`−γ (z_s − z)⁺`
//! in one layer). It balances the self-weight (`div σ + b = 0` with `b = −γ e_z`) when the
//! sides are on rollers and the base fixed.

use super::model::PlasticModel;
use crate::element::VoigtStress;
use crate::error::{FemError, finite, non_negative};
use crate::model::{ModelSpace, StressField};
use crate::plastic::{PointState, Voigt};
use crate::space::{Dim, Space};
use std::sync::Arc;

/// A stress of dimension `D` ([`Space::Stress`]) as the 3D Voigt vector of a point
/// ([`crate::plastic`]): `(xx, yy, xy, zz)` → `[xx, yy, zz, xy, 0, 0]` in 2D (`(rr, zz, rz,
/// θθ)` → `[rr, zz, θθ, rz, 0, 0]` in axisymmetry), the identity in 3D.
pub(crate) fn to_voigt<const D: usize>(s: &VoigtStress<D>) -> Voigt
where
    Dim<D>: Space,
{
    match *s.as_ref() {
        [xx, yy, xy, zz] => [xx, yy, zz, xy, 0.0, 0.0],
        [a, b, c, d, e, f] => [a, b, c, d, e, f],
        _ => unreachable!("a Voigt stress has 4 or 6 components"),
    }
}

/// The inverse of [`to_voigt`] (the out-of-plane shears dropped in 2D).
pub(crate) fn from_voigt<const D: usize>(v: &Voigt) -> VoigtStress<D>
where
    Dim<D>: Space,
{
    let mut s = VoigtStress::<D>::default();
    let out = s.as_mut();
    if out.len() == 4 {
        out.copy_from_slice(&[v[0], v[1], v[3], v[2]]);
    } else {
        out.copy_from_slice(v);
    }
    s
}

impl<const D: usize> PlasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// Sets one initial stress field per region as the committed stress of its points (at
    /// zero strain; replacing their state, plastic strains included); the points of regions
    /// not listed keep theirs. The tangent is not refactored (the next Newton iteration does
    /// it).
    ///
    /// # Errors
    /// - [`FemError::UnknownRegion`] for a region no element has;
    /// - [`FemError::InvalidParameter`] naming `initial stress` for a non-finite value;
    /// - [`FemError::OutsideYieldSurface`] naming the region, the element and the point where
    ///   the stress is outside the yield surface (`yield_function > 10⁻¹² ‖σ‖`: a state on
    ///   the surface up to round-off is admissible); nothing is changed then.
    pub fn set_initial_stress_by_region(
        &mut self,
        fields: &[(u32, StressField<D>)],
    ) -> Result<(), FemError> {
        let regions = self.elastic.mesh().regions();
        if let Some((region, _)) = fields.iter().find(|(r, _)| !regions.contains(r)) {
            return Err(FemError::UnknownRegion { region: *region });
        }
        let mut stresses = Vec::new();
        self.for_each_point(|e, q, k, p| {
            let region = regions[e];
            let Some((_, field)) = fields.iter().find(|(r, _)| *r == region) else {
                return Ok(());
            };
            let stress = to_voigt::<D>(&field(p.x));
            if let Some(&value) = stress.iter().find(|v| !v.is_finite()) {
                return Err(FemError::InvalidParameter {
                    name: "initial stress",
                    value,
                    expected: "a finite stress field",
                });
            }
            let yield_function = self.laws[self.law_of[e]].1.yield_function(&stress);
            let norm = stress.iter().map(|s| s * s).sum::<f64>().sqrt();
            if yield_function > 1e-12 * norm {
                return Err(FemError::OutsideYieldSurface {
                    region,
                    element: e,
                    point: q,
                    yield_function,
                });
            }
            stresses.push((k, stress));
            Ok(())
        })?;
        for (k, stress) in stresses {
            self.committed[k] = PointState::with_stress(stress);
        }
        self.trial.copy_from_slice(&self.committed);
        self.trial_current = false;
        Ok(())
    }

    /// Sets the geostatic K0 state (module docs) in each listed region, `(region, K0)`, for
    /// a ground surface at `surface` (last coordinate, upwards), with the unit weight of each
    /// region's material in the elastic model.
    ///
    /// The listed regions are horizontal layers when their height ranges (over their
    /// elements' nodes) do not overlap: the vertical stress at `z` then sums `γ h` over the
    /// layers between `z` and the surface (`σ_v = −Σ γ_i h_i`; a surface above the top layer
    /// adds no weight: a surcharge is a load). Listed regions side by side (overlapping
    /// heights, e.g. two soils across a vertical boundary) each take `σ_v = −γ (z_s − z)⁺` with
    /// their own `γ`. A region not listed keeps its state (a pile starts unstressed).
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] naming `surface` or `k0`; as
    /// [`PlasticModel::set_initial_stress_by_region`] (a `K0` so far from 1 that the state
    /// is outside the yield surface is refused naming the region and the point).
    pub fn set_geostatic(&mut self, surface: f64, k0: &[(u32, f64)]) -> Result<(), FemError> {
        let surface = finite("surface", surface)?;
        let mesh = self.elastic.mesh();
        let regions = mesh.regions();
        // (region, K0, γ, lowest and highest node of the region)
        let mut layers = Vec::with_capacity(k0.len());
        for &(region, k) in k0 {
            let k = non_negative("k0", k)?;
            let Some(e) = regions.iter().position(|r| *r == region) else {
                return Err(FemError::UnknownRegion { region });
            };
            let gamma = self.elastic.material(e).unit_weight();
            let heights = (0..mesh.element_count())
                .filter(|&e| regions[e] == region)
                .flat_map(|e| mesh.element(e).iter().map(|&n| mesh.nodes()[n][D - 1]));
            let (lo, hi) = heights.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), z| {
                (lo.min(z), hi.max(z))
            });
            layers.push((region, k, gamma, lo, hi));
        }
        let span = layers.iter().fold(0.0_f64, |m, l| m.max(l.4 - l.3));
        let layered = layers.iter().enumerate().all(|(i, a)| {
            layers[i + 1..]
                .iter()
                .all(|b| a.4.min(b.4) - a.3.max(b.3) <= 1e-9 * span)
        });
        let weights: Vec<(f64, f64, f64)> = layers.iter().map(|l| (l.2, l.3, l.4)).collect();
        let fields: Vec<(u32, StressField<D>)> = layers
            .iter()
            .map(|&(region, k, gamma, _, _)| {
                let weights = weights.clone();
                let field: StressField<D> = Arc::new(move |x: [f64; D]| {
                    let z = x[D - 1];
                    let s_v = if layered {
                        // −Σ γ_i |[z, z_s] ∩ [lo_i, hi_i]|
                        -weights
                            .iter()
                            .map(|&(g, lo, hi)| g * (surface.min(hi) - z.max(lo)).max(0.0))
                            .sum::<f64>()
                    } else {
                        -gamma * (surface - z).max(0.0)
                    };
                    let mut s = [k * s_v; 6];
                    s[D - 1] = s_v;
                    s[3..].fill(0.0);
                    from_voigt::<D>(&s)
                });
                (region, field)
            })
            .collect();
        self.set_initial_stress_by_region(&fields)
    }
}
