//! Outputs of a [`PlasticModel`] per element for VTK: the mean over the element's points of
//! the equivalent plastic strain, of the yielding flag (the fraction of its points that
//! yielded in the last accepted update) and of the stress, at the committed state; and the
//! positions of the points.

use super::model::PlasticModel;
use super::model_initial::from_voigt;
use crate::element::VoigtStress;
use crate::error::FemError;
use crate::model::ModelSpace;
use crate::space::Dim;

/// Per-element means of the committed state ([`PlasticModel::element_outputs`]), one entry
/// per element, ready for [`crate::vtk::Field`] cell data.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct PlasticOutputs<const D: usize>
where
    Dim<D>: ModelSpace<D>,
{
    /// The mean equivalent plastic strain.
    pub equivalent_plastic_strain: Vec<f64>,
    /// The fraction of the element's points that yielded (`0` elastic, `1` all plastic).
    pub yielding: Vec<f64>,
    /// The mean stress, in the order of [`crate::Space::Stress`] (`(xx, yy, xy, zz)`,
    /// `(rr, zz, rz, θθ)` or `(xx, yy, zz, xy, yz, zx)`).
    pub stress: Vec<VoigtStress<D>>,
}

impl<const D: usize> PlasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// The per-element means of the committed state (module docs).
    pub fn element_outputs(&self) -> PlasticOutputs<D> {
        let elements = self.offsets.len() - 1;
        let mut out = PlasticOutputs {
            equivalent_plastic_strain: Vec::with_capacity(elements),
            yielding: Vec::with_capacity(elements),
            stress: Vec::with_capacity(elements),
        };
        for e in 0..elements {
            let points = &self.committed[self.element_points(e)];
            let w = 1.0 / points.len().max(1) as f64;
            let mut stress = [0.0; 6];
            let (mut eps_p, mut yielding) = (0.0, 0.0);
            for s in points {
                eps_p += w * s.equivalent_plastic_strain;
                yielding += if s.yielding { w } else { 0.0 };
                for (m, v) in stress.iter_mut().zip(&s.stress) {
                    *m += w * v;
                }
            }
            out.equivalent_plastic_strain.push(eps_p);
            out.yielding.push(yielding);
            out.stress.push(from_voigt::<D>(&stress));
        }
        out
    }

    /// The position of every quadrature point, in the order of
    /// [`PlasticModel::committed_states`].
    ///
    /// # Errors
    /// [`FemError::InvertedElement`] (not after a successful construction).
    pub fn point_positions(&self) -> Result<Vec<[f64; D]>, FemError> {
        let mut out = vec![[0.0; D]; self.committed.len()];
        self.for_each_point(|_, _, k, p| {
            out[k] = p.x;
            Ok(())
        })?;
        Ok(out)
    }
}
