//! The mass of an [`ElasticModel`] ([`Mass`]): the consistent mass on the stiffness pattern
//! and the HRZ lumped diagonal, assembled from each element's
//! [`Element::mass_into`](crate::Element::mass_into) and
//! [`Element::lumped_mass_into`](crate::Element::lumped_mass_into) with the density of its
//! region, whenever the stiffness is assembled (a model has a mass only if its materials
//! have densities, so a quasi-static model pays nothing).
//!
//! ```text
//! M = Σ_e Aᵀ_e (∫ ρ Nᵀ N w dΩ) A_e,    m = Σ_e Aᵀ_e m_e^HRZ     (free dofs only)
//! ```

use super::{ElasticModel, ModelSpace};
use crate::assembly::scatter;
use crate::dirichlet::Dof;
use crate::error::FemError;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::space::Dim;
use crate::structure::Mass;
use faer::sparse::SparseColMatRef;
use nalgebra::DMatrix;
use std::collections::BTreeMap;

/// The assembled mass: consistent values on the stiffness pattern and the lumped diagonal.
#[derive(Clone, Debug, Default)]
pub(super) struct MassValues {
    /// The lower triangle of `M`, on the pattern of `K`.
    values: Vec<f64>,
    /// The HRZ lumped mass per free dof.
    lumped: Vec<f64>,
}

/// Whether the model has a mass: `true` if every region of the mesh has a material with a
/// density, `false` if none has.
///
/// # Errors
/// [`FemError::MissingDensity`] for the first region without a density when another has one.
pub(super) fn has_mass<const D: usize>(
    mesh: &Mesh<D>,
    materials: &BTreeMap<u32, Material>,
) -> Result<bool, FemError>
where
    Dim<D>: ModelSpace<D>,
{
    let regions = mesh.regions();
    if !regions.iter().any(|r| materials[r].density().is_some()) {
        return Ok(false);
    }
    match regions
        .iter()
        .position(|r| materials[r].density().is_none())
    {
        Some(element) => Err(FemError::MissingDensity {
            region: regions[element],
            element,
        }),
        None => Ok(true),
    }
}

impl<const D: usize> ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// Assembles `M` and its lumped diagonal for the current dof numbering (a no-op for a
    /// model without mass).
    ///
    /// # Errors
    /// As the element kernels (an inverted element), and [`FemError::NonFiniteSolve`] for a
    /// mass that overflows.
    pub(super) fn assemble_mass(&mut self) -> Result<(), FemError> {
        let Some(mass) = self.mass.as_mut() else {
            return Ok(());
        };
        mass.values.clear();
        mass.values.resize(self.pattern.nnz(), 0.0);
        mass.lumped.clear();
        mass.lumped.resize(self.dofs.free_count(), 0.0);
        let built_in = self.mesh.built_in_element();
        let (mut m_e, mut lumped_e) = (DMatrix::zeros(0, 0), Vec::new());
        let (mut coords, mut coupling) = (Vec::new(), Vec::new());
        for e in 0..self.mesh.element_count() {
            let cell = self.mesh.element(e);
            self.mesh.element_coords_into(e, &mut coords);
            let region = self.mesh.regions()[e];
            // every region has a density: checked by `has_mass` when the model was built
            let density = self.materials[&region].density().unwrap_or(0.0);
            let element = self.elements.get(region, built_in);
            element.mass_into(e, &coords, density, &self.setting, &mut m_e)?;
            lumped_e.clear();
            lumped_e.resize(D * cell.len(), 0.0);
            element.lumped_mass_into(e, &coords, density, &self.setting, &mut lumped_e)?;
            if let Some(value) = m_e.iter().chain(&lumped_e).find(|v| !v.is_finite()) {
                return Err(FemError::NonFiniteSolve {
                    what: "mass",
                    node: None,
                    value: *value,
                });
            }
            coupling.clear();
            scatter(
                &self.pattern,
                &self.dofs,
                cell,
                &m_e,
                &mut mass.values,
                &mut coupling,
            );
            for (a, m) in lumped_e.iter().enumerate() {
                if let Dof::Free(i) = self.dofs.dofs(cell[a / D])[a % D] {
                    mass.lumped[i] += m;
                }
            }
        }
        Ok(())
    }
}

/// Asked through [`Structure::mass`](crate::Structure::mass), which offers the model when its
/// materials have densities.
///
/// # Panics
/// Called directly on a model without mass (no region's material has a density), every
/// method but [`matrix`](Mass::matrix) (which answers `None`): the caller skipped the
/// question `mass()` asks.
impl<const D: usize> Mass for ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    #[track_caller]
    fn mul_into(&self, x: &[f64], y: &mut [f64]) {
        self.pattern
            .symmetric_mul_into(&self.mass_values().values, x, y);
    }

    #[track_caller]
    fn lumped(&self) -> &[f64] {
        &self.mass_values().lumped
    }

    fn matrix(&self) -> Option<SparseColMatRef<'_, usize, f64>> {
        self.mass.as_ref().map(|m| self.pattern.view(&m.values))
    }
}

impl<const D: usize> ElasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    #[track_caller]
    fn mass_values(&self) -> &MassValues {
        self.mass.as_ref().expect(
            "the model has no mass (no region's material has a density): ask `Structure::mass`",
        )
    }
}
