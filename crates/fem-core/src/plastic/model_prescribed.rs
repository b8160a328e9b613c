//! Displacement-controlled loading of a [`PlasticModel`]: new values of dofs that are
//! prescribed already, and the reaction they carry (a rigid footing pushed into the soil,
//! issue 40).
//!
//! ```text
//! R_c(nodes) = Σ_{a ∈ nodes} Σ_e Σ_q (Bᵀ σ_q w_q)_{a,c}      at the committed state
//! ```
//! is the force the body exerts back on whatever holds those dofs (the resultant of the
//! internal forces there): with no load on those nodes it is minus the force the support
//! applies.

use super::Voigt;
use super::model::{PlasticModel, strain_vectors};
use crate::component::Component;
use crate::error::FemError;
use crate::model::ModelSpace;
use crate::space::Dim;
use crate::structure::Structure;

impl<const D: usize> PlasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// Sets the value of `component` on `nodes`, dofs that are prescribed already, for the
    /// next Newton steps: the committed state is kept, so a load path of prescribed
    /// displacements is a sequence of `set_prescribed` and [`crate::plastic::newton::solve`]
    /// calls (no renumbering, no refactorisation).
    ///
    /// # Errors
    /// [`FemError::UnknownNode`]; [`FemError::InvalidParameter`] for a non-finite value;
    /// [`FemError::Unsupported`] if one of the dofs is free (constraining it would renumber
    /// the body's dofs).
    pub fn set_prescribed(
        &mut self,
        nodes: &[usize],
        component: Component,
        value: f64,
    ) -> Result<(), FemError> {
        let count = self.elastic.node_count();
        if let Some(&node) = nodes.iter().find(|&&n| n >= count) {
            return Err(FemError::UnknownNode {
                node,
                node_count: count,
                what: "a prescribed displacement",
            });
        }
        if let Some(&node) = nodes
            .iter()
            .find(|&&n| self.elastic.node_dofs(n)[component as usize].is_some())
        {
            return Err(FemError::Unsupported {
                what: format!(
                    "a new prescribed value on the free {component:?} dof of node {node} of \
                     a plastic body (prescribe it, at any value, before building the body)"
                ),
            });
        }
        self.elastic.set_prescribed(nodes, component, value)?;
        self.prescribed = self.elastic.prescribed_values();
        Ok(())
    }

    /// The reaction `R_c` on `nodes` along `component` at the committed state (module
    /// docs); a node listed twice counts once.
    ///
    /// # Errors
    /// [`FemError::UnknownNode`].
    pub fn reaction(&self, nodes: &[usize], component: Component) -> Result<f64, FemError> {
        let count = self.elastic.node_count();
        let mut member = vec![false; count];
        for &node in nodes {
            if node >= count {
                return Err(FemError::UnknownNode {
                    node,
                    node_count: count,
                    what: "a reaction",
                });
            }
            member[node] = true;
        }
        let c = component as usize;
        let mesh = self.elastic.mesh();
        let mut b: Vec<Voigt> = Vec::new();
        let mut total = 0.0;
        self.for_each_point(|e, _, k, p| {
            let cell = mesh.element(e);
            b.resize(D * cell.len(), [0.0; 6]);
            strain_vectors(p, cell.len(), self.kinematics, &mut b);
            let stress = &self.committed[k].stress;
            for (a, &node) in cell.iter().enumerate() {
                if member[node] {
                    total += p.weight
                        * b[D * a + c]
                            .iter()
                            .zip(stress)
                            .map(|(x, y)| x * y)
                            .sum::<f64>();
                }
            }
            Ok(())
        })?;
        Ok(total)
    }
}
