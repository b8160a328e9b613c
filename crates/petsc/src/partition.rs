//! A partition of a mesh over `ranks` processes, and the row ownership it gives the
//! distributed stiffness.
//!
//! ```text
//! slabs:    elements sorted by the centroid's coordinate along the longest side of the
//!           bounding box, cut into `ranks` runs of (almost) equal length (one level of
//!           recursive coordinate bisection, Berger & Bokhari 1987, generalised to `ranks`
//!           slabs): p − 1 cutting planes, each as large as the body's cross-section
//! graph:    recursive coordinate bisection of the element graph (Berger & Bokhari 1987;
//!           Simon 1991): the elements (vertices, at their centroids) of a part are split at
//!           the median along the longest side of their own bounding box, into halves sized
//!           ⌊k/2⌋ : ⌈k/2⌉ for k ranks, until each part is one rank's: parts of equal element
//!           count (to one element per level) that are nearly cubes, so the interface (the
//!           edges of the element graph cut) grows as p^(1/3) · N^(2/3) instead of p · N^(2/3)
//! nodes:    owned by the lowest rank among the elements that touch them
//! rows:     the free dofs ordered by (owner, serial free index): rank p owns the contiguous
//!           rows [offsets[p], offsets[p + 1]) of the distributed matrix
//! ```
//! Both are computed alike on every rank (ties broken by element index), from the replicated
//! mesh, with no communication. On the box-like block, Hertz and pile meshes at 2 ranks the
//! two coincide; beyond, `graph` cuts fewer nodes (docs/benchmarks.md, "Issue 41").
//! PETSc's own partitioners (PT-Scotch is the one Debian's PETSc 3.18 has) would need the
//! element graph distributed first; bisection needs nothing but the centroids.

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
        Self::from_element_ranks(mesh, dofs, element_rank, ranks)
    }

    /// Recursive coordinate bisection of the element graph, balanced by element count
    /// (module docs): on more than two ranks, parts that are nearly cubes where
    /// [`slabs`](Self::slabs) gives thin slices, so fewer nodes on the interface.
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
    /// let mesh = box_mesh(&lines(0.0, 1.0, 4), &lines(0.0, 1.0, 4), &lines(0.0, 1.0, 4),
    ///     SolidKind::Tet4).unwrap();
    /// let dofs = DofMap::<3>::numbered(mesh.node_count(), &Supports::new()).unwrap();
    /// let (graph, slabs) = (Partition::graph(&mesh, &dofs, 8), Partition::slabs(&mesh, &dofs, 8));
    /// // eight cubes of 2³ cells against eight slices of 4 × 4 × 1/2 cells
    /// assert!(graph.interface_nodes(&mesh) < slabs.interface_nodes(&mesh));
    /// ```
    #[track_caller]
    pub fn graph<const D: usize>(mesh: &Mesh<D>, dofs: &DofMap<D>, ranks: usize) -> Self
    where
        Dim<D>: Space,
    {
        assert!(ranks > 0, "at least one rank");
        assert_eq!(
            dofs.node_count(),
            mesh.node_count(),
            "dof map of another mesh"
        );
        let nodes = mesh.nodes();
        let centroids: Vec<[f64; D]> = (0..mesh.element_count())
            .map(|e| {
                let cell = mesh.element(e);
                let mut c = [0.0; D];
                for &n in cell {
                    for a in 0..D {
                        c[a] += nodes[n][a] / cell.len() as f64;
                    }
                }
                c
            })
            .collect();
        let mut element_rank = vec![0; centroids.len()];
        let mut elements: Vec<usize> = (0..centroids.len()).collect();
        bisect(&centroids, &mut elements, 0, ranks, &mut element_rank);
        Self::from_element_ranks(mesh, dofs, element_rank, ranks)
    }

    /// Node owners and the row numbering from the rank of each element (module docs).
    fn from_element_ranks<const D: usize>(
        mesh: &Mesh<D>,
        dofs: &DofMap<D>,
        element_rank: Vec<usize>,
        ranks: usize,
    ) -> Self
    where
        Dim<D>: Space,
    {
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

    /// The interface: nodes touched by elements of more than one rank (each one's dofs are
    /// rows that two or more ranks add to at assembly, and entries every Krylov product
    /// exchanges).
    ///
    /// # Panics
    /// If `mesh` is not the partitioned mesh (another element count).
    ///
    /// # Examples
    /// ```
    /// use bipotential_petsc::Partition;
    /// use fem_core::solid::generate::{box_mesh, lines};
    /// use fem_core::solid::SolidKind;
    /// use fem_core::{DofMap, Supports};
    /// let mesh = box_mesh(&lines(0.0, 2.0, 2), &lines(0.0, 1.0, 1), &lines(0.0, 1.0, 1),
    ///     SolidKind::Tet4).unwrap();
    /// let dofs = DofMap::<3>::numbered(mesh.node_count(), &Supports::new()).unwrap();
    /// // two cells along x, one per rank: the 4 nodes of the face x = 1 are shared
    /// assert_eq!(Partition::slabs(&mesh, &dofs, 2).interface_nodes(&mesh), 4);
    /// ```
    #[track_caller]
    pub fn interface_nodes<const D: usize>(&self, mesh: &Mesh<D>) -> usize
    where
        Dim<D>: Space,
    {
        assert_eq!(
            self.element_rank.len(),
            mesh.element_count(),
            "partition of another mesh"
        );
        let mut shared = vec![false; mesh.node_count()];
        for (e, &r) in self.element_rank.iter().enumerate() {
            for &n in mesh.element(e) {
                shared[n] |= self.node_rank[n] != r;
            }
        }
        shared.into_iter().filter(|&s| s).count()
    }
}

/// Which partition a distributed structure uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Partitioner {
    /// [`Partition::slabs`]: slices along the longest side (the default; as good as `Graph`
    /// on two ranks).
    #[default]
    Slabs,
    /// [`Partition::graph`]: recursive bisection, nearly cubic parts (fewer interface nodes
    /// from three ranks on).
    Graph,
}

impl Partitioner {
    /// The partition of `mesh` over `ranks`.
    ///
    /// # Panics
    /// As [`Partition::slabs`].
    ///
    /// # Examples
    /// ```
    /// use bipotential_petsc::{Partition, Partitioner};
    /// use fem_core::solid::generate::{box_mesh, lines};
    /// use fem_core::solid::SolidKind;
    /// use fem_core::{DofMap, Supports};
    /// let mesh = box_mesh(&lines(0.0, 1.0, 2), &lines(0.0, 1.0, 2), &lines(0.0, 1.0, 2),
    ///     SolidKind::Tet4).unwrap();
    /// let dofs = DofMap::<3>::numbered(mesh.node_count(), &Supports::new()).unwrap();
    /// assert_eq!(Partitioner::Graph.partition(&mesh, &dofs, 4), Partition::graph(&mesh, &dofs, 4));
    /// ```
    #[track_caller]
    pub fn partition<const D: usize>(
        self,
        mesh: &Mesh<D>,
        dofs: &DofMap<D>,
        ranks: usize,
    ) -> Partition
    where
        Dim<D>: Space,
    {
        match self {
            Self::Slabs => Partition::slabs(mesh, dofs, ranks),
            Self::Graph => Partition::graph(mesh, dofs, ranks),
        }
    }
}

/// Gives `elements` (centroids `centroids`) to ranks `first..first + ranks`: split at the
/// median along the longest side of their centroids' box, `⌊ranks/2⌋ : ⌈ranks/2⌉` by count.
fn bisect<const D: usize>(
    centroids: &[[f64; D]],
    elements: &mut [usize],
    first: usize,
    ranks: usize,
    element_rank: &mut [usize],
) {
    if ranks == 1 || elements.len() <= 1 {
        elements.iter().for_each(|&e| element_rank[e] = first);
        return;
    }
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    for &e in elements.iter() {
        for a in 0..D {
            lo[a] = lo[a].min(centroids[e][a]);
            hi[a] = hi[a].max(centroids[e][a]);
        }
    }
    let axis = (0..D)
        .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
        .unwrap_or(0);
    let left = ranks / 2;
    let cut = elements.len() * left / ranks;
    // ties broken by index: every rank computes the same partition
    elements.sort_unstable_by(|&a, &b| {
        centroids[a][axis]
            .total_cmp(&centroids[b][axis])
            .then(a.cmp(&b))
    });
    let (low, high) = elements.split_at_mut(cut);
    bisect(centroids, low, first, left, element_rank);
    bisect(centroids, high, first + left, ranks - left, element_rank);
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

    /// Every element owned by exactly one rank in range, every rank given
    /// `ne / ranks` elements to one per bisection level, and every row numbered once.
    #[test]
    fn issue_41_graph_owns_every_element_once_works() {
        let (mesh, dofs) = block();
        let ne = mesh.element_count();
        for ranks in 1..=9 {
            let p = Partition::graph(&mesh, &dofs, ranks);
            assert_eq!(p.element_rank.len(), ne);
            let mut count = vec![0usize; ranks];
            for &r in &p.element_rank {
                count[r] += 1; // panics if a rank is out of range
            }
            assert_eq!(count.iter().sum::<usize>(), ne);
            // each level's floor loses under one element: ⌈log2 ranks⌉ in all
            let levels = usize::BITS - (ranks - 1).leading_zeros();
            let (min, max) = (count.iter().min().unwrap(), count.iter().max().unwrap());
            assert!(
                *min + 1 >= ne / ranks && *max <= ne / ranks + levels as usize + 1,
                "{ranks} ranks: {count:?}"
            );
            let mut rows = p.row.clone();
            rows.sort_unstable();
            assert_eq!(rows, (0..dofs.free_count()).collect::<Vec<_>>());
            assert_eq!(p.offsets[ranks], dofs.free_count());
            for (i, &r) in p.row.iter().enumerate() {
                let (node, _) = dofs.free_dof_owner(i).unwrap();
                assert_eq!(p.row_rank(r), p.node_rank[node]);
            }
        }
    }

    /// On a cube of 8³ cells: 2 ranks cut one plane either way; 8 ranks give 8 cubes
    /// (3 internal planes) against 7 slab planes, and the node counts are exact.
    #[test]
    fn issue_41_graph_cuts_fewer_nodes_than_slabs_works() {
        let mesh = box_mesh(
            &lines(0.0, 1.0, 8),
            &lines(0.0, 1.0, 8),
            &lines(0.0, 1.0, 8),
            SolidKind::Tet4,
        )
        .unwrap();
        let dofs = DofMap::<3>::numbered(mesh.node_count(), &Supports::new()).unwrap();
        let (g2, s2) = (
            Partition::graph(&mesh, &dofs, 2),
            Partition::slabs(&mesh, &dofs, 2),
        );
        // one plane of 9 × 9 nodes
        assert_eq!(g2.interface_nodes(&mesh), 81);
        assert_eq!(s2.interface_nodes(&mesh), 81);
        // slabs: 7 planes of 81; cubes: 3 planes of 81 less the 2 · 9 + 2 · 9 − ... union:
        // x = 0.5, y = 0.5, z = 0.5 planes, 3 · 81 − 3 · 9 + 1 nodes
        assert_eq!(
            Partition::slabs(&mesh, &dofs, 8).interface_nodes(&mesh),
            7 * 81
        );
        assert_eq!(
            Partition::graph(&mesh, &dofs, 8).interface_nodes(&mesh),
            3 * 81 - 3 * 9 + 1
        );
        assert_eq!(Partition::graph(&mesh, &dofs, 1).interface_nodes(&mesh), 0);
    }
}
