//! A geometric partition of a mesh over `ranks` processes, and the row ownership it gives the
//! distributed stiffness.
//!
//! ```text
//! elements: sorted by the centroid's coordinate along the longest side of the bounding box,
//!           cut into `ranks` runs of (almost) equal length (one level of recursive coordinate
//!           bisection, Berger & Bokhari 1987, generalised to `ranks` slabs)
//! nodes:    owned by the lowest rank among the elements that touch them
//! rows:     the free dofs ordered by (owner, serial free index): rank p owns the contiguous
//!           rows [offsets[p], offsets[p + 1]) of the distributed matrix
//! ```
//! Slabs keep each rank's interface to its neighbours to one or two planes, which is what a
//! graph partition would also find on the block, Hertz and pile meshes (all box-like); a graph
//! partition (ParMETIS through PETSc's `MatPartitioning`) is the next step for general meshes.

use fem_core::{Dim, DofMap, Mesh, Space};

/// Which rank assembles each element, which rank owns each node and row, and the
/// permutation from the serial free-dof numbering (the [`DofMap`]'s, what the contact solver
/// sees) to the distributed row numbering.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Partition {
    /// The rank of each element.
    pub element_rank: Vec<usize>,
    /// The rank of each node (lowest rank of the elements touching it; 0 for a free node).
    pub node_rank: Vec<usize>,
    /// `row[i]`: the distributed row of the serial free dof `i`.
    pub row: Vec<usize>,
    /// Rank `p` owns rows `offsets[p]..offsets[p + 1]`.
    pub offsets: Vec<usize>,
}

impl Partition {
    /// Slabs along the longest side of the mesh's bounding box (module docs).
    ///
    /// # Panics
    /// If `ranks == 0` or `dofs` was numbered for another node count.
    ///
    /// # Examples
    /// ```
    /// use bipotential_petsc::Partition;
    /// use fem_core::solid::generate::{box_mesh, lines};
    /// use fem_core::solid::SolidKind;
    /// use fem_core::{DofMap, Supports};
    /// let mesh = box_mesh(&lines(0.0, 4.0, 4), &lines(0.0, 1.0, 1), &lines(0.0, 1.0, 1),
    ///     SolidKind::Tet4).unwrap();
    /// let dofs = DofMap::<3>::numbered(mesh.node_count(), &Supports::new()).unwrap();
    /// let p = Partition::slabs(&mesh, &dofs, 2);
    /// assert_eq!(p.offsets.len(), 3);
    /// assert_eq!(p.offsets[2], dofs.free_count());
    /// ```
    #[track_caller]
    pub fn slabs<const D: usize>(mesh: &Mesh<D>, dofs: &DofMap<D>, ranks: usize) -> Self
    where
        Dim<D>: Space,
    {
        assert!(ranks > 0, "at least one rank");
        assert_eq!(
            dofs.node_count(),
            mesh.node_count(),
            "dof map of another mesh"
        );
        let ne = mesh.element_count();
        let nodes = mesh.nodes();
        let mut lo = [f64::INFINITY; D];
        let mut hi = [f64::NEG_INFINITY; D];
        for p in nodes {
            for a in 0..D {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        let axis = (0..D)
            .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
            .unwrap_or(0);
        let centroid = |e: usize| {
            let cell = mesh.element(e);
            cell.iter().map(|&n| nodes[n][axis]).sum::<f64>() / cell.len() as f64
        };
        let mut order: Vec<usize> = (0..ne).collect();
        // ties broken by index: every rank computes the same partition
        order.sort_by(|&a, &b| centroid(a).total_cmp(&centroid(b)).then(a.cmp(&b)));
        let mut element_rank = vec![0; ne];
        for (k, &e) in order.iter().enumerate() {
            element_rank[e] = k * ranks / ne.max(1);
        }
        let mut node_rank = vec![usize::MAX; mesh.node_count()];
        for (e, &r) in element_rank.iter().enumerate() {
            for &n in mesh.element(e) {
                node_rank[n] = node_rank[n].min(r);
            }
        }
        node_rank
            .iter_mut()
            .filter(|r| **r == usize::MAX)
            .for_each(|r| *r = 0);
        let nf = dofs.free_count();
        let mut dof_rank = vec![0; nf];
        for (n, &r) in node_rank.iter().enumerate() {
            for d in dofs.free_dofs(n).into_iter().flatten() {
                dof_rank[d] = r;
            }
        }
        let mut offsets = vec![0; ranks + 1];
        for &r in &dof_rank {
            offsets[r + 1] += 1;
        }
        for p in 0..ranks {
            offsets[p + 1] += offsets[p];
        }
        let mut next = offsets.clone();
        let row = dof_rank
            .iter()
            .map(|&r| {
                next[r] += 1;
                next[r] - 1
            })
            .collect();
        Self {
            element_rank,
            node_rank,
            row,
            offsets,
        }
    }

    /// The number of ranks.
    pub fn ranks(&self) -> usize {
        self.offsets.len() - 1
    }

    /// The rank owning distributed row `row`.
    ///
    /// # Panics
    /// If `row` is not a row of the partition.
    #[track_caller]
    pub fn row_rank(&self, row: usize) -> usize {
        assert!(
            row < *self.offsets.last().unwrap_or(&0),
            "row {row} out of range"
        );
        self.offsets.partition_point(|&o| o <= row) - 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fem_core::solid::SolidKind;
    use fem_core::solid::generate::{box_mesh, lines};
    use fem_core::{Component, Supports};

    fn block() -> (fem_core::solid::SolidMesh, DofMap<3>) {
        let mesh = box_mesh(
            &lines(0.0, 1.0, 2),
            &lines(0.0, 1.0, 2),
            &lines(0.0, 3.0, 6),
            SolidKind::Tet10,
        )
        .unwrap();
        let mut s = Supports::new();
        s.fix(mesh.node_set("z0").unwrap(), Component::Z);
        let dofs = DofMap::<3>::numbered(mesh.node_count(), &s).unwrap();
        (mesh, dofs)
    }

    #[test]
    fn slabs_number_every_row_once_works() {
        let (mesh, dofs) = block();
        for ranks in 1..=4 {
            let p = Partition::slabs(&mesh, &dofs, ranks);
            let mut rows = p.row.clone();
            rows.sort_unstable();
            assert_eq!(rows, (0..dofs.free_count()).collect::<Vec<_>>());
            // balanced to one slab of elements: each rank has rows
            assert!(p.offsets.windows(2).all(|w| w[1] > w[0]), "{:?}", p.offsets);
            for (i, &r) in p.row.iter().enumerate() {
                let (node, _) = dofs.free_dof_owner(i).unwrap();
                assert_eq!(p.row_rank(r), p.node_rank[node]);
            }
        }
    }

    #[test]
    fn slabs_cut_along_the_longest_side_works() {
        let (mesh, dofs) = block();
        let p = Partition::slabs(&mesh, &dofs, 2);
        // z is the long side (3 against 1): the lower half of the elements is rank 0
        for e in 0..mesh.element_count() {
            let z = mesh
                .element(e)
                .iter()
                .map(|&n| mesh.nodes()[n][2])
                .sum::<f64>()
                / 10.0;
            assert_eq!(
                p.element_rank[e],
                usize::from(z > 1.5),
                "element {e} at z {z}"
            );
        }
        // one rank: the serial numbering unchanged
        let one = Partition::slabs(&mesh, &dofs, 1);
        assert_eq!(one.row, (0..dofs.free_count()).collect::<Vec<_>>());
    }
}
