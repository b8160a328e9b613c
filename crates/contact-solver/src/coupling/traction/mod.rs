//! A continuous contact traction recovered from the nodal reactions of a zone: the pressure
//! `p` and the tangential traction `(t₁, t₂)` (one component in 2D) at every node of the
//! contactor's surface.
//!
//! The contact reactions are nodal forces; on P2 sides and faces they are the consistent
//! forces `r_i = ∫ N_i p dΓ` of a traction, so that `r_n / A_i` (the per-node pressure of the
//! reports) is `0 / 0` at a P2 corner in 3D (the corners of a 6-node triangle carry no force
//! of a uniform pressure) and oscillates in 2D. The recovery solves the consistent boundary
//! mass instead ([`BoundaryMass`], Zienkiewicz & Taylor 2000, § 14.2):
//!
//! ```text
//! M_Γ p = r_n,    M_Γ t_k = r_tk   (k = 1, 2),    M_Γ,ij = ∫_Γ N_i N_j w dΓ
//! ```
//!
//! over the whole contactor surface (its nodes that are no candidate, or whose candidate is
//! open, carry `r = 0`). The field is exact for any traction in the span of the surface's
//! shape functions (uniform and linear on P1, quadratic on P2) and is its `L²` projection
//! otherwise. The tangential components are taken in each node's own frame (the candidates'
//! `t` in 2D, `t₁, t₂` in 3D), so they add up as a field only where the frames agree (a flat
//! or gently curved target). Signs: `p > 0` is compression ([`contact_laws`]'s convention).

mod vtk;

pub use vtk::{write_interface_vtu_3d_with_traction, write_interface_vtu_with_traction};

use crate::coupling::simulation::ContactRecord;
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use fem_core::boundary_mass::BoundaryMass;

/// The traction recovered on one zone's contactor surface (module docs).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct TractionField {
    /// The zone.
    pub zone: usize,
    /// The surface's nodes (global numbers, sorted; [`BoundaryMass::nodes`]).
    pub nodes: Vec<usize>,
    /// Contact pressure at each node (`> 0` compression).
    pub pressure: Vec<f64>,
    /// Tangential traction at each node, in its candidate's frame (`[t, 0]` in 2D, `[t₁, t₂]`
    /// in 3D; `0` at a node that is no candidate).
    pub shear: Vec<[f64; 2]>,
}

impl TractionField {
    /// The field from the local nodal reactions `(node, [r_n, r_t1, r_t2])` of the zone's
    /// candidates (a node listed twice adds up); the other surface nodes carry none.
    ///
    /// # Errors
    /// [`SolverError::InvalidGeometry`] if a node is not on the surface of `mass` (the zone's
    /// contactor nodes are not the nodes of the sides or faces given), or
    /// [`SolverError::NonFinite`] if a reaction is NaN or infinite.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::coupling::traction::TractionField;
    /// use fem_core::boundary_mass::BoundaryMass;
    /// use fem_core::{ElementKind, Idealization, Mesh, Side};
    /// let mesh = Mesh::new(vec![[0.0, 0.0], [2.0, 0.0], [0.0, 1.0]], ElementKind::Tri3,
    ///     vec![0, 1, 2], vec![])?;
    /// let side = Side { element: 0, side: 0 };
    /// let mass = BoundaryMass::from_sides(&mesh, &[side], Idealization::PlaneStrain)?;
    /// // a pressure 3 on the side of length 2: 3 at each node
    /// let f = TractionField::recover(&mass, 0, [(0, [3.0, 0.0, 0.0]), (1, [3.0, 0.0, 0.0])])?;
    /// assert!(f.pressure.iter().all(|p| (p - 3.0).abs() < 1e-14));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn recover(
        mass: &BoundaryMass,
        zone: usize,
        reactions: impl IntoIterator<Item = (usize, [f64; 3])>,
    ) -> Result<Self, SolverError> {
        let n = mass.nodes().len();
        let mut rhs = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        for (index, (node, r)) in reactions.into_iter().enumerate() {
            let Some(i) = mass.index_of(node) else {
                return Err(SolverError::InvalidGeometry(format!(
                    "zone {zone}: contact node {node} is not on the surface whose pressure is \
                     recovered (the sides or faces given are not the contactor's)"
                )));
            };
            if let Some(&value) = r.iter().find(|v| !v.is_finite()) {
                return Err(SolverError::NonFinite {
                    what: "contact reaction",
                    index,
                    value,
                });
            }
            for k in 0..3 {
                rhs[k][i] += r[k];
            }
        }
        let [p, t1, t2] = rhs.map(|b| {
            if b.iter().all(|v| *v == 0.0) {
                b
            } else {
                mass.solve(&b)
            }
        });
        Ok(Self {
            zone,
            nodes: mass.nodes().to_vec(),
            pressure: p,
            shear: t1.into_iter().zip(t2).map(|(a, b)| [a, b]).collect(),
        })
    }

    /// The field of zone `zone` from a step's records, 2D or 3D (those of other zones are
    /// skipped; in 2D the second tangential component is 0).
    ///
    /// # Errors
    /// As [`TractionField::recover`].
    pub fn from_records<const D: usize>(
        mass: &BoundaryMass,
        zone: usize,
        records: &[ContactRecord<D>],
    ) -> Result<Self, SolverError>
    where
        fem_core::Dim<D>: ContactSpace<D>,
    {
        let mine = records.iter().filter(|c| c.zone == zone).map(|c| {
            let mut r = [0.0; 3];
            r[..D].copy_from_slice(&c.reaction());
            (c.node, r)
        });
        Self::recover(mass, zone, mine)
    }

    /// `(p, [t₁, t₂])` at global node `node`, if it is on the surface.
    pub fn at(&self, node: usize) -> Option<(f64, [f64; 2])> {
        let i = self.nodes.binary_search(&node).ok()?;
        Some((self.pressure[i], self.shear[i]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fem_core::generate::{RectangleSpec, rectangle};
    use fem_core::{ElementKind, Idealization};

    #[test]
    fn recover_rejects_foreign_nodes_and_nan() {
        let mut spec = RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 2, 1);
        spec.kind = ElementKind::Tri6;
        let mesh = rectangle(&spec).unwrap();
        let sides = mesh.edge_set("bottom").unwrap();
        let mass = BoundaryMass::from_sides(&mesh, sides, Idealization::PlaneStrain).unwrap();
        let top = mesh.node_set("top").unwrap()[0];
        assert!(matches!(
            TractionField::recover(&mass, 0, [(top, [1.0, 0.0, 0.0])]),
            Err(SolverError::InvalidGeometry(m)) if m.contains(&format!("node {top}"))
        ));
        let bottom = mass.nodes()[0];
        assert!(matches!(
            TractionField::recover(&mass, 0, [(bottom, [f64::NAN, 0.0, 0.0])]),
            Err(SolverError::NonFinite { .. })
        ));
        // no reaction: a zero field
        let f = TractionField::recover(&mass, 0, []).unwrap();
        assert!(f.pressure.iter().all(|p| *p == 0.0));
        assert_eq!(f.at(bottom), Some((0.0, [0.0, 0.0])));
        assert_eq!(f.at(top), None);
    }
}
