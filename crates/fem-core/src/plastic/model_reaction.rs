//! The reaction on prescribed dofs of a [`PlasticModel`]: with
//! [`PlasticModel::set_prescribed`], the force–displacement curve of a displacement control
//! (a rigid footing pushed into the soil, issue 40).
//!
//! ```text
//! R_c(nodes) = Σ_{a ∈ nodes} Σ_e Σ_q (Bᵀ σ_q w_q)_{a,c}      at the committed state
//! ```
//! is the force that whatever holds those dofs applies to the body: the resultant of the
//! internal forces there, which it balances when those nodes carry no load. A footing
//! pushing down on the soil gives `R_y < 0`.

use super::Voigt;
use super::model::{PlasticModel, strain_vectors};
use crate::component::Component;
use crate::error::FemError;
use crate::model::ModelSpace;
use crate::space::Dim;

impl<const D: usize> PlasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// The reaction `R_c` on `nodes` along `component` at the committed state (module
    /// docs); a node listed twice counts once.
    ///
    /// # Errors
    /// [`FemError::UnknownNode`].
    pub fn reaction(&self, nodes: &[usize], component: Component) -> Result<f64, FemError> {
        let count = self.elastic.mesh().node_count();
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
