//! Supports (Dirichlet conditions) and the numbering of free and prescribed dofs.
//!
//! Constrained dofs are eliminated, so the reduced stiffness stays symmetric positive
//! definite; a prescribed value `ū` moves `−K_fp ū` to the right-hand side. Changing a
//! prescribed *value* between load steps needs no refactorisation; changing *which* dofs are
//! constrained changes the dof numbering (and so the pattern and the factorisation).

pub use crate::component::Component;
use crate::error::{FemError, finite};
use std::collections::BTreeMap;

/// The set of constrained dofs with their prescribed values (`0` for a fixed dof), and the
/// ties: sets of nodes that share one displacement component.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Supports {
    values: BTreeMap<(usize, Component), f64>,
    ties: Vec<(Component, Vec<usize>)>,
}

impl Supports {
    /// No supports.
    pub fn new() -> Self {
        Self::default()
    }

    /// Fixes `component` of every node in `nodes` (`u = 0`).
    pub fn fix(&mut self, nodes: &[usize], component: Component) -> &mut Self {
        for &n in nodes {
            self.values.insert((n, component), 0.0);
        }
        self
    }

    /// Prescribes `u = value` for `component` of every node in `nodes`. Prescribing a dof
    /// again with the same value is allowed; with another value it is an error (which one
    /// should win is not for the library to guess): use [`Supports::update`] to change a
    /// value on purpose, or [`Supports::release`] first.
    ///
    /// # Errors
    /// - [`FemError::InvalidParameter`] if `value` is NaN or infinite;
    /// - [`FemError::ConflictingPrescription`] if a dof of `nodes` already has another value
    ///   (nothing is changed then).
    ///
    /// # Examples
    /// ```
    /// use fem_core::{Component, FemError, Supports};
    /// let mut s = Supports::new();
    /// s.prescribe(&[0, 1], Component::Y, -0.01)?;
    /// s.prescribe(&[1], Component::Y, -0.01)?; // the same value again: fine
    /// let e = s.prescribe(&[1], Component::Y, 0.02).unwrap_err();
    /// assert!(matches!(e, FemError::ConflictingPrescription { node: 1, .. }));
    /// # Ok::<(), FemError>(())
    /// ```
    pub fn prescribe(
        &mut self,
        nodes: &[usize],
        component: Component,
        value: f64,
    ) -> Result<&mut Self, FemError> {
        let value = finite("prescribed displacement", value)?;
        for &n in nodes {
            match self.values.get(&(n, component)) {
                Some(&first) if first != value => {
                    return Err(FemError::ConflictingPrescription {
                        node: n,
                        component,
                        first,
                        second: value,
                    });
                }
                _ => {}
            }
        }
        self.update(nodes, component, value)
    }

    /// Sets `u = value` for `component` of every node in `nodes`, replacing any value they
    /// had (the prescribed displacement of the next step).
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] if `value` is NaN or infinite.
    pub fn update(
        &mut self,
        nodes: &[usize],
        component: Component,
        value: f64,
    ) -> Result<&mut Self, FemError> {
        let value = finite("prescribed displacement", value)?;
        for &n in nodes {
            self.values.insert((n, component), value);
        }
        Ok(self)
    }

    /// Removes the constraint on `component` of `nodes` (if any).
    pub fn release(&mut self, nodes: &[usize], component: Component) -> &mut Self {
        for &n in nodes {
            self.values.remove(&(n, component));
        }
        self
    }

    /// Ties `component` of every node in `nodes` to one shared displacement: a rigid cap (a
    /// "pilot node" in Abaqus or code_aster terms) that translates without rotating when
    /// both components of a set are tied. The set has one dof per tied component, so a force
    /// given at any one of its nodes ([`LinearElasticModel::add_nodal_force`]) is the cap's
    /// resultant, and prescribing the component on every node of the set controls the cap by
    /// displacement. A set that is otherwise free may float
    /// ([`LinearElasticModel::floating`]): its rigid-body modes are those that keep the tied
    /// components equal.
    ///
    /// [`LinearElasticModel::add_nodal_force`]: crate::LinearElasticModel::add_nodal_force
    /// [`LinearElasticModel::floating`]: crate::LinearElasticModel::floating
    ///
    /// # Errors
    /// [`FemError::InvalidTie`] for an empty set, or a node already tied along `component`
    /// (nothing is changed then).
    ///
    /// # Examples
    /// ```
    /// use fem_core::{Component, DofMap, FemError, Supports};
    /// let mut s = Supports::new();
    /// s.tie(&[0, 2], Component::Y)?;
    /// let map = DofMap::new(3, &s)?;
    /// assert_eq!(map.free_count(), 5); // six components, two of them shared
    /// assert_eq!(map.free_dofs(0)[1], map.free_dofs(2)[1]);
    /// assert!(s.tie(&[1, 2], Component::Y).is_err()); // node 2 is tied along y already
    /// # Ok::<(), FemError>(())
    /// ```
    pub fn tie(&mut self, nodes: &[usize], component: Component) -> Result<&mut Self, FemError> {
        if nodes.is_empty() {
            return Err(FemError::InvalidTie {
                component,
                node: None,
                reason: "the set is empty",
            });
        }
        // the nodes already tied along `component`, then those of this set as they come: one
        // pass, so that a cap of many nodes is not checked in quadratic time
        let mut seen: std::collections::BTreeSet<usize> = self
            .ties
            .iter()
            .filter(|(c, _)| *c == component)
            .flat_map(|(_, ns)| ns.iter().copied())
            .collect();
        for &n in nodes {
            if !seen.insert(n) {
                return Err(FemError::InvalidTie {
                    component,
                    node: Some(n),
                    reason: "the node is tied along this component already",
                });
            }
        }
        self.ties.push((component, nodes.to_vec()));
        Ok(self)
    }

    /// Whether `node` belongs to a tie along `component`.
    pub fn tied(&self, node: usize, component: Component) -> bool {
        self.ties
            .iter()
            .any(|(c, nodes)| *c == component && nodes.contains(&node))
    }

    /// The ties, in the order given: `(component, nodes)`.
    pub fn ties(&self) -> &[(Component, Vec<usize>)] {
        &self.ties
    }

    /// The prescribed value of a dof, `None` if it is free.
    pub fn value(&self, node: usize, component: Component) -> Option<f64> {
        self.values.get(&(node, component)).copied()
    }

    /// Iterates over `((node, component), value)` in node order.
    pub fn iter(&self) -> impl Iterator<Item = ((usize, Component), f64)> + '_ {
        self.values.iter().map(|(&k, &v)| (k, v))
    }

    /// Number of constrained dofs.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// `true` if no dof is constrained.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }
}

/// Where a dof of a node lives: in the free (unknown) vector or in the prescribed vector.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dof {
    /// Index in the reduced system.
    Free(usize),
    /// Index in the list of prescribed dofs.
    Prescribed(usize),
}

/// The numbering of the free and prescribed dofs of every node, in node order: `D = 2`
/// components per node (the default) or `D = 3`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DofMap<const D: usize = 2> {
    dofs: Vec<[Dof; D]>,
    free_count: usize,
    prescribed: Vec<(usize, Component)>,
}

impl DofMap {
    /// Numbers the dofs of a 2D model: [`DofMap::numbered`] with `D = 2`.
    ///
    /// # Errors
    /// As [`DofMap::numbered`].
    pub fn new(node_count: usize, supports: &Supports) -> Result<Self, FemError> {
        Self::numbered(node_count, supports)
    }
}

impl<const D: usize> DofMap<D> {
    /// Numbers the dofs of `node_count` nodes with the constraints of `supports`. The nodes
    /// of a free tie ([`Supports::tie`]) share the free dof numbered at the first of them in
    /// node order; a tie whose component is prescribed is prescribed node by node.
    ///
    /// # Errors
    /// [`FemError::UnknownNode`] if a support or a tie names a node that does not exist;
    /// [`FemError::InvalidTie`] for a tie whose component is prescribed at some of its nodes
    /// and free at others, or prescribed to different values;
    /// [`FemError::InvalidComponent`] for a support or tie along `Z` in 2D.
    pub fn numbered(node_count: usize, supports: &Supports) -> Result<Self, FemError> {
        if let Some(((node, _), _)) = supports.iter().find(|((n, _), _)| *n >= node_count) {
            return Err(FemError::UnknownNode {
                what: "a support",
                node,
                node_count,
            });
        }
        let outside = |c: Component| c as usize >= D;
        if let Some(((node, component), _)) = supports.iter().find(|((_, c), _)| outside(*c)) {
            return Err(FemError::InvalidComponent {
                what: "a support",
                node: Some(node),
                component,
                dimension: D,
            });
        }
        if let Some((component, nodes)) = supports.ties().iter().find(|(c, _)| outside(*c)) {
            return Err(FemError::InvalidComponent {
                what: "a tie",
                node: nodes.first().copied(),
                component: *component,
                dimension: D,
            });
        }
        // the tie group of every (node, component), for the free ties only
        let mut group = vec![[usize::MAX; D]; node_count];
        for (g, (component, nodes)) in supports.ties().iter().enumerate() {
            if let Some(&node) = nodes.iter().find(|&&n| n >= node_count) {
                return Err(FemError::UnknownNode {
                    what: "a tie",
                    node,
                    node_count,
                });
            }
            let values: Vec<Option<f64>> = nodes
                .iter()
                .map(|&n| supports.value(n, *component))
                .collect();
            match (
                values.iter().position(Option::is_some),
                values.iter().position(Option::is_none),
            ) {
                (Some(_), Some(free)) => {
                    return Err(FemError::InvalidTie {
                        component: *component,
                        node: Some(nodes[free]),
                        reason: "the tied component is prescribed at other nodes of the set: \
                                 prescribe it on the whole set or on none",
                    });
                }
                (Some(first), None) => {
                    if let Some(k) = values.iter().position(|v| *v != values[first]) {
                        return Err(FemError::InvalidTie {
                            component: *component,
                            node: Some(nodes[k]),
                            reason: "the tied component is prescribed to different values \
                                     within the set",
                        });
                    }
                }
                _ => {
                    for &n in nodes {
                        group[n][*component as usize] = g;
                    }
                }
            }
        }
        let mut shared = vec![usize::MAX; supports.ties().len()];
        let mut dofs = Vec::with_capacity(node_count);
        let mut free_count = 0;
        let mut prescribed = Vec::with_capacity(supports.len());
        for (node, groups) in group.iter().enumerate() {
            let mut d = [Dof::Free(0); D];
            for (c, comp) in Component::all::<D>().into_iter().enumerate() {
                d[c] = if supports.value(node, comp).is_some() {
                    prescribed.push((node, comp));
                    Dof::Prescribed(prescribed.len() - 1)
                } else if groups[c] != usize::MAX && shared[groups[c]] != usize::MAX {
                    Dof::Free(shared[groups[c]])
                } else {
                    free_count += 1;
                    if groups[c] != usize::MAX {
                        shared[groups[c]] = free_count - 1;
                    }
                    Dof::Free(free_count - 1)
                };
            }
            dofs.push(d);
        }
        Ok(Self {
            dofs,
            free_count,
            prescribed,
        })
    }

    /// Number of free dofs (the size of the reduced system).
    #[inline]
    pub fn free_count(&self) -> usize {
        self.free_count
    }

    /// Number of nodes.
    #[inline]
    pub fn node_count(&self) -> usize {
        self.dofs.len()
    }

    /// The `D` dofs of `node`.
    ///
    /// # Panics
    /// If `node >= node_count()`.
    #[inline]
    #[track_caller]
    pub fn dofs(&self, node: usize) -> [Dof; D] {
        self.dofs[node]
    }

    /// The free-dof indices of `node` (`None` for a prescribed component).
    ///
    /// # Panics
    /// If `node >= node_count()`.
    #[inline]
    #[track_caller]
    pub fn free_dofs(&self, node: usize) -> [Option<usize>; D] {
        self.dofs[node].map(|d| match d {
            Dof::Free(i) => Some(i),
            Dof::Prescribed(_) => None,
        })
    }

    /// The prescribed dofs, in the order of their indices.
    #[inline]
    pub fn prescribed(&self) -> &[(usize, Component)] {
        &self.prescribed
    }

    /// The prescribed value of every prescribed dof, in [`DofMap::prescribed`] order.
    pub(crate) fn prescribed_values(&self, supports: &Supports) -> Vec<f64> {
        self.prescribed
            .iter()
            .map(|&(n, c)| supports.value(n, c).unwrap_or(0.0))
            .collect()
    }

    /// `rhs = factor · load + initial` on the free dofs, from per-node-component vectors
    /// (`D` entries per node; the nodes of a tie add into their shared dof).
    pub(crate) fn gather_into(&self, factor: f64, load: &[f64], initial: &[f64], rhs: &mut [f64]) {
        rhs.fill(0.0);
        for (node, d) in self.dofs.iter().enumerate() {
            for (c, d) in d.iter().enumerate() {
                if let Dof::Free(i) = d {
                    rhs[*i] += factor * load[D * node + c] + initial[D * node + c];
                }
            }
        }
    }

    /// Nodal values from the free-dof values `u_free` and the prescribed ones.
    pub(crate) fn expand(&self, u_free: &[f64], prescribed: &[f64]) -> Vec<[f64; D]> {
        self.dofs
            .iter()
            .map(|d| {
                d.map(|d| match d {
                    Dof::Free(i) => u_free[i],
                    Dof::Prescribed(p) => prescribed[p],
                })
            })
            .collect()
    }

    /// The node and component of free dof `dof` (a row of the reduced system; the first node
    /// of a tie), `None` if `dof >= free_count()`. A linear search: meant for error reports, not for loops.
    pub fn free_dof_owner(&self, dof: usize) -> Option<(usize, Component)> {
        self.dofs.iter().enumerate().find_map(|(node, d)| {
            Component::all::<D>()
                .into_iter()
                .zip(d)
                .find_map(|(c, d)| (*d == Dof::Free(dof)).then_some((node, c)))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dof_map_works() {
        let mut s = Supports::new();
        s.fix(&[0], Component::X)
            .prescribe(&[2], Component::Y, 0.5)
            .unwrap();
        let map = DofMap::new(3, &s).unwrap();
        assert_eq!(map.free_count(), 4);
        assert_eq!(map.dofs(0), [Dof::Prescribed(0), Dof::Free(0)]);
        assert_eq!(map.dofs(2), [Dof::Free(3), Dof::Prescribed(1)]);
        assert_eq!(map.free_dofs(1), [Some(1), Some(2)]);
        assert_eq!(map.prescribed(), &[(0, Component::X), (2, Component::Y)]);
        assert_eq!(map.free_dof_owner(0), Some((0, Component::Y)));
        assert_eq!(map.free_dof_owner(3), Some((2, Component::X)));
        assert_eq!(map.free_dof_owner(4), None);
    }

    #[test]
    fn supports_rejects_nan_and_unknown_nodes() {
        let mut s = Supports::new();
        assert!(s.prescribe(&[0], Component::X, f64::NAN).is_err());
        s.fix(&[5], Component::Y);
        assert!(matches!(
            DofMap::new(3, &s),
            Err(FemError::UnknownNode { node: 5, .. })
        ));
    }
}
