//! A model's elements by region: the built-in element of the mesh's kind, or a user's element
//! in its place for a region (`ElasticModel::with_element`).

use super::Element;
use crate::error::FemError;
use crate::space::{Dim, Space};
use std::collections::BTreeMap;
use std::sync::Arc;

/// Users' elements by region, in place of the built-in one of the mesh's kind.
#[derive(Clone, Default)]
pub(crate) struct RegionElements<const D: usize>
where
    Dim<D>: Space,
{
    users: BTreeMap<u32, Arc<dyn Element<D>>>,
}

impl<const D: usize> RegionElements<D>
where
    Dim<D>: Space,
{
    /// Puts `element` in place of the built-in one for `region`.
    ///
    /// # Errors
    /// [`FemError::MissingMaterial`] (element `usize::MAX`) if no element of the mesh is in
    /// `region` (`regions`: one per element); [`FemError::LengthMismatch`] if the element's
    /// node count is not `nodes`, the mesh kind's.
    pub(crate) fn insert(
        &mut self,
        region: u32,
        element: Arc<dyn Element<D>>,
        regions: &[u32],
        nodes: usize,
    ) -> Result<(), FemError> {
        if !regions.contains(&region) {
            return Err(FemError::MissingMaterial {
                region,
                element: usize::MAX,
            });
        }
        if element.node_count() != nodes {
            return Err(FemError::LengthMismatch {
                what: "nodes of the region's element (the mesh kind's node count)",
                expected: nodes,
                got: element.node_count(),
            });
        }
        self.users.insert(region, element);
        Ok(())
    }

    /// The element of `region`: the user's, else `built_in`.
    pub(crate) fn get<'a>(
        &'a self,
        region: u32,
        built_in: &'a dyn Element<D>,
    ) -> &'a dyn Element<D> {
        self.users.get(&region).map_or(built_in, |a| &**a)
    }
}
