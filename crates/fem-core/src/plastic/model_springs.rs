//! Springs on the tangent of a [`PlasticModel`] ([`Nonlinear::set_tangent_springs`]):
//! `K_t + S`, the matrix of the Newton's solves where `K_t` alone is singular (issue 40: a
//! perfectly plastic body at its limit load, whose mechanism only the contact stops).
//!
//! ```text
//! S = Σ s_ij (e_i e_jᵀ + e_j e_iᵀ) (i > j),  + s_ii e_i e_iᵀ     on the tangent's pattern
//! ```
//! The springs are kept as positions in the lower values (and, for the exact tangent, in full
//! storage) and added after every assembly.
//!
//! [`Nonlinear::set_tangent_springs`]: crate::Nonlinear::set_tangent_springs

use super::PlasticModel;
use crate::error::FemError;
use crate::model::ModelSpace;
use crate::space::Dim;

impl<const D: usize> PlasticModel<D>
where
    Dim<D>: ModelSpace<D>,
{
    /// Checks `entries` and keeps them as `(lower position, value)`.
    ///
    /// # Errors
    /// As [`crate::Nonlinear::set_tangent_springs`].
    pub(super) fn set_springs(&mut self, entries: &[(usize, usize, f64)]) -> Result<(), FemError> {
        let pattern = self.elastic.pattern().symbolic();
        let n = pattern.ncols();
        let mut springs = Vec::with_capacity(entries.len());
        for &(row, col, value) in entries {
            if !value.is_finite() {
                return Err(FemError::InvalidParameter {
                    name: "springs",
                    value,
                    expected: "a finite spring stiffness",
                });
            }
            if row < col || row >= n {
                return Err(FemError::InvalidParameter {
                    name: "springs",
                    value: row as f64,
                    expected: "a row on the free dofs at or below the diagonal (row ≥ col)",
                });
            }
            let (start, end) = (pattern.col_ptr()[col], pattern.col_ptr()[col + 1]);
            let Ok(at) = pattern.row_idx()[start..end].binary_search(&row) else {
                return Err(FemError::Unsupported {
                    what: format!(
                        "a spring between free dofs {row} and {col}, which no element couples \
                         (outside the tangent's sparsity pattern)"
                    ),
                });
            };
            springs.push((start + at, value));
        }
        self.springs = springs;
        Ok(())
    }

    /// Adds the springs to the assembled values (both triangles of the exact tangent).
    pub(super) fn add_springs(&mut self) {
        for &(p, value) in &self.springs {
            self.values[p] += value;
            if let Some(exact) = &mut self.exact {
                let [lower, upper] = exact.lower_to_full[p];
                exact.values[lower] += value;
                if upper != lower {
                    exact.values[upper] += value;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::generate::{RectangleSpec, rectangle};
    use crate::plastic::{DruckerPrager, PlasticModel, TangentKind};
    use crate::{
        Component, FemError, Idealization, LinearElasticModel, Material, Nonlinear, Structure,
        Supports,
    };
    use std::sync::Arc;

    fn body() -> PlasticModel<2> {
        let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2)).unwrap();
        let bottom = mesh.node_set("bottom").unwrap().to_vec();
        let mut supports = Supports::new();
        supports
            .fix(&bottom, Component::X)
            .fix(&bottom, Component::Y);
        let m = Material::new(100.0, 0.3, 0.0).unwrap();
        let elastic =
            LinearElasticModel::new(mesh, Idealization::PlaneStrain, &[(0, m)], supports).unwrap();
        let point = Arc::new(DruckerPrager::von_mises(100.0, 0.3, 1.0).unwrap());
        PlasticModel::new(elastic, &[(0, point)]).unwrap()
    }

    fn entry(k: faer::sparse::SparseColMatRef<'_, usize, f64>, i: usize, j: usize) -> f64 {
        let (cp, ri) = (k.col_ptr(), k.row_idx());
        (cp[j]..cp[j + 1])
            .find(|&p| ri[p] == i)
            .map_or(0.0, |p| k.val()[p])
    }

    /// The springs enter the factorised tangent exactly (both kinds), and go when cleared.
    #[test]
    fn tangent_springs_works() {
        for kind in [TangentKind::Symmetric, TangentKind::Exact] {
            let mut b = body();
            b.set_tangent_kind(kind).unwrap();
            let k0 = b.stiffness_matrix().unwrap();
            let (d0, o0) = (entry(k0, 1, 1), entry(k0, 1, 0));
            b.set_tangent_springs(&[(1, 1, 5.0), (1, 0, 2.0), (1, 1, 1.0)])
                .unwrap();
            b.update_tangent().unwrap();
            let k1 = b.stiffness_matrix().unwrap();
            // exact sums: one addition each
            assert_eq!(entry(k1, 1, 1), d0 + 6.0);
            assert_eq!(entry(k1, 1, 0), o0 + 2.0);
            if let Some(full) = b.exact_tangent() {
                assert_eq!(entry(full, 0, 1), entry(full, 1, 0));
            }
            b.set_tangent_springs(&[]).unwrap();
            b.update_tangent().unwrap();
            assert_eq!(entry(b.stiffness_matrix().unwrap(), 1, 1), d0);
        }
    }

    #[test]
    fn tangent_springs_rejects_bad_entries() {
        let mut b = body();
        let n = b.dof_count();
        for (entries, name) in [
            (vec![(0, 1, 1.0)], "springs"),
            (vec![(n, 0, 1.0)], "springs"),
            (vec![(0, 0, f64::NAN)], "springs"),
        ] {
            match b.set_tangent_springs(&entries) {
                Err(FemError::InvalidParameter { name: got, .. }) => assert_eq!(got, name),
                other => panic!("{other:?}"),
            }
        }
        // the first and last free dofs are not coupled by an element (opposite corners)
        match b.set_tangent_springs(&[(n - 1, 0, 1.0)]) {
            Err(FemError::Unsupported { .. }) => {}
            other => panic!("{other:?}"),
        }
    }
}
