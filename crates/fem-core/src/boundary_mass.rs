//! The consistent mass matrix of a boundary: sides of a triangle mesh (2D) or triangle faces
//! of a tetrahedral mesh (3D), P1 or P2, and its solves.
//!
//! ```text
//! M_ij = ∫_Γ N_i N_j w dΓ        (w: 1 in 3D; 1, the thickness or r in 2D: Idealization::weight)
//! f_i  = ∫_Γ N_i p w dΓ = (M p)_i   the consistent nodal forces of a field p = Σ N_j p_j
//! p    = M⁻¹ f                      the field whose consistent forces are f
//! ```
//!
//! The last line recovers a continuous boundary field from nodal forces (a contact pressure
//! from the nodal reactions, the "consistent" or `L²` recovery: it is the `L²` projection onto
//! the boundary's shape functions of the traction that the forces stand for). It is exact
//! for every field in the span of the shape functions: a uniform and a linear field on P1
//! sides, a quadratic one on P2 sides (Zienkiewicz & Taylor 2000, vol. 1, § 14.2, the
//! consistent mass; Hughes 2000, § 7.3).
//!
//! The integrals use 3 Gauss points per side (exact for `N_i N_j r` on straight P2 sides) and
//! the degree-4 triangle rule per face (exact for `N_i N_j` on flat P2 faces); curved sides and
//! faces are integrated on their isoparametric geometry.

use crate::error::FemError;
use crate::idealization::Idealization;
use crate::linear_solver::SpdSolver;
use crate::mesh::{Mesh, Side};
use crate::quadrature::GAUSS_3;
use crate::solid::{Face, SolidMesh};
use faer::sparse::{SparseColMat, Triplet};

/// A quadrature point of a boundary: position, weight (rule × Jacobian × idealisation weight)
/// and the shape values of its side's or face's nodes (global numbers).
#[derive(Clone, Copy, Debug)]
struct BoundaryPoint {
    x: [f64; 3],
    weight: f64,
    nodes: [usize; 6],
    n: [f64; 6],
    count: usize,
}

impl BoundaryPoint {
    fn new(x: [f64; 3], weight: f64, ids: &[usize], n: &[f64]) -> Self {
        let mut p = Self {
            x,
            weight,
            nodes: [0; 6],
            n: [0.0; 6],
            count: ids.len(),
        };
        p.nodes[..ids.len()].copy_from_slice(ids);
        p.n[..ids.len()].copy_from_slice(&n[..ids.len()]);
        p
    }
}

/// The consistent mass matrix of a boundary, factored (module docs): its nodes, sorted, and
/// the solves `M x = b` over them.
#[derive(Clone, Debug)]
pub struct BoundaryMass {
    nodes: Vec<usize>,
    /// The quadrature points of every side or face ([`BoundaryMass::integrate`]).
    points: Vec<BoundaryPoint>,
    /// Lower triangle, in the local numbering of `nodes`.
    matrix: SparseColMat<usize, f64>,
    solver: SpdSolver,
}

impl BoundaryMass {
    /// The mass of the sides `sides` of `mesh` (a 2D boundary: line elements of 2 or 3 nodes),
    /// weighted by `idealization` (the thickness in plane stress, `r` per radian in
    /// axisymmetry).
    ///
    /// # Errors
    /// - [`FemError::EmptyBoundary`] if `sides` is empty;
    /// - [`FemError::InvalidSide`] for a side that does not exist;
    /// - [`FemError::SingularBoundaryMass`] with the node whose sides carry no weight (a side
    ///   along the axis `r = 0` in axisymmetry).
    ///
    /// # Examples
    /// ```
    /// use fem_core::boundary_mass::BoundaryMass;
    /// use fem_core::{ElementKind, Idealization, Mesh, Side};
    /// // one triangle, its side 0 from (0, 0) to (2, 0): M = (2 / 6) [[2, 1], [1, 2]]
    /// let mesh = Mesh::new(vec![[0.0, 0.0], [2.0, 0.0], [0.0, 1.0]], ElementKind::Tri3,
    ///     vec![0, 1, 2], vec![])?;
    /// let side = Side { element: 0, side: 0 };
    /// let m = BoundaryMass::from_sides(&mesh, &[side], Idealization::PlaneStrain)?;
    /// assert_eq!(m.nodes(), &[0, 1]);
    /// let f = m.apply(&[1.0, 1.0]); // a uniform unit pressure: half the length at each node
    /// assert!((f[0] - 1.0).abs() < 1e-14 && (f[1] - 1.0).abs() < 1e-14);
    /// let p = m.solve(&f);
    /// assert!((p[0] - 1.0).abs() < 1e-14 && (p[1] - 1.0).abs() < 1e-14);
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    pub fn from_sides(
        mesh: &Mesh,
        sides: &[Side],
        idealization: Idealization,
    ) -> Result<Self, FemError> {
        if sides.is_empty() {
            return Err(FemError::EmptyBoundary {
                what: "the sides of a 2D boundary",
            });
        }
        mesh.check_facets(sides)?;
        let mut blocks = Vec::with_capacity(sides.len());
        let mut points = Vec::with_capacity(3 * sides.len());
        for &side in sides {
            let nodes: Vec<usize> = mesh.side_nodes(side).collect();
            let xs: Vec<[f64; 2]> = nodes.iter().map(|&n| mesh.nodes()[n]).collect();
            let k = nodes.len();
            let mut m_e = [[0.0; 3]; 3];
            for &(s, w) in &GAUSS_3 {
                // 1D shapes on [−1, 1]: P1 (a, b); P2 (a, b, mid)
                let (n, dn) = if k == 2 {
                    ([(1.0 - s) / 2.0, (1.0 + s) / 2.0, 0.0], [-0.5, 0.5, 0.0])
                } else {
                    (
                        [s * (s - 1.0) / 2.0, s * (s + 1.0) / 2.0, 1.0 - s * s],
                        [s - 0.5, s + 0.5, -2.0 * s],
                    )
                };
                let (mut x, mut dx) = ([0.0; 2], [0.0; 2]);
                for i in 0..k {
                    for a in 0..2 {
                        x[a] += n[i] * xs[i][a];
                        dx[a] += dn[i] * xs[i][a];
                    }
                }
                let wt = w * dx[0].hypot(dx[1]) * idealization.weight(x[0]);
                points.push(BoundaryPoint::new([x[0], x[1], 0.0], wt, &nodes, &n));
                for i in 0..k {
                    for j in 0..k {
                        m_e[i][j] += n[i] * n[j] * wt;
                    }
                }
            }
            blocks.push((nodes, m_e.iter().flat_map(|r| r[..k].to_vec()).collect()));
        }
        Self::assemble(blocks, points)
    }

    /// The mass of the faces `faces` of `mesh` (3- or 6-node triangles, curved P2 faces
    /// included).
    ///
    /// # Errors
    /// - [`FemError::EmptyBoundary`] if `faces` is empty;
    /// - [`FemError::InvalidSide`] for a face that does not exist;
    /// - [`FemError::SingularBoundaryMass`] (not met on a valid mesh: every face has an area).
    ///
    /// # Examples
    /// ```
    /// use fem_core::boundary_mass::BoundaryMass;
    /// use fem_core::ElementKind;
    /// use fem_core::solid::{Face, SolidMesh};
    /// let nodes = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    /// let mesh = SolidMesh::new(nodes, ElementKind::Tet4, vec![0, 1, 2, 3], vec![])?;
    /// let m = BoundaryMass::from_faces(&mesh, &[Face { element: 0, side: 0 }])?;
    /// // a uniform unit pressure on the face z = 0 (area 1/2): a third of it at each corner
    /// let f = m.apply(&[1.0; 3]);
    /// assert!(f.iter().all(|v| (v - 1.0 / 6.0).abs() < 1e-15));
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    pub fn from_faces(mesh: &SolidMesh, faces: &[Face]) -> Result<Self, FemError> {
        if faces.is_empty() {
            return Err(FemError::EmptyBoundary {
                what: "the faces of a 3D boundary",
            });
        }
        mesh.check_facets(faces)?;
        let mut blocks = Vec::with_capacity(faces.len());
        let mut points = Vec::with_capacity(6 * faces.len());
        for &face in faces {
            let mut block: Option<(Vec<usize>, Vec<f64>)> = None;
            mesh.face_points(face, |nodes, p| {
                let k = nodes.len();
                let b = block.get_or_insert_with(|| (nodes.to_vec(), vec![0.0; k * k]));
                for i in 0..k {
                    for j in 0..k {
                        b.1[i * k + j] += p.n[i] * p.n[j] * p.weight;
                    }
                }
                points.push(BoundaryPoint::new(p.x, p.weight, nodes, &p.n));
                Ok(())
            })?;
            blocks.extend(block);
        }
        Self::assemble(blocks, points)
    }

    /// The mass of the boundary sides of `mesh` whose nodes all lie in `nodes` (e.g. a contact
    /// zone's contactor nodes: the surface they make).
    ///
    /// # Errors
    /// [`FemError::EmptyBoundary`] if no boundary side has all its nodes in `nodes`; as
    /// [`BoundaryMass::from_sides`] otherwise. A P2 side whose mid-side node and one corner are
    /// in `nodes` is taken too (a contactor that ends at a corner belonging to another zone:
    /// that corner then carries no reaction of this one).
    pub fn on_nodes(
        mesh: &Mesh,
        nodes: &[usize],
        idealization: Idealization,
    ) -> Result<Self, FemError> {
        let set: std::collections::BTreeSet<usize> = nodes.iter().copied().collect();
        let sides: Vec<Side> = mesh
            .boundary_facets()
            .into_iter()
            .filter(|&s| {
                // all the side's nodes in the set, or (P2) the mid-side node and one corner: a
                // contactor that stops at a corner held by another zone keeps that side
                let (inside, all) = mesh.side_nodes(s).fold((0, 0), |(i, a), n| {
                    (i + usize::from(set.contains(&n)), a + 1)
                });
                inside == all
                    || (all == 3
                        && inside == 2
                        && mesh.side_nodes(s).nth(2).is_some_and(|m| set.contains(&m)))
            })
            .collect();
        if sides.is_empty() {
            return Err(FemError::EmptyBoundary {
                what: "the boundary sides within a node set",
            });
        }
        Self::from_sides(mesh, &sides, idealization)
    }

    /// The mass of the boundary faces of `mesh` whose nodes all lie in `nodes` (e.g. a contact
    /// zone's contactor nodes: the surface they make).
    ///
    /// # Errors
    /// [`FemError::EmptyBoundary`] if no boundary face has all its nodes in `nodes`; as
    /// [`BoundaryMass::from_faces`] otherwise.
    pub fn on_nodes_3d(mesh: &SolidMesh, nodes: &[usize]) -> Result<Self, FemError> {
        let set: std::collections::BTreeSet<usize> = nodes.iter().copied().collect();
        let faces: Vec<Face> = mesh
            .boundary_facets()
            .into_iter()
            .filter(|&f| mesh.face_node_ids(f).all(|n| set.contains(&n)))
            .collect();
        if faces.is_empty() {
            return Err(FemError::EmptyBoundary {
                what: "the boundary faces within a node set",
            });
        }
        Self::from_faces(mesh, &faces)
    }

    /// Assembles element blocks `(global nodes, row-major k × k matrix)` and factors.
    fn assemble(
        blocks: Vec<(Vec<usize>, Vec<f64>)>,
        points: Vec<BoundaryPoint>,
    ) -> Result<Self, FemError> {
        let mut nodes: Vec<usize> = blocks.iter().flat_map(|b| b.0.iter().copied()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        let local = |g: usize| nodes.binary_search(&g).expect("collected above");
        let mut triplets = Vec::new();
        for (ids, m_e) in &blocks {
            let k = ids.len();
            for i in 0..k {
                for j in 0..k {
                    let (r, c) = (local(ids[i]), local(ids[j]));
                    if r >= c {
                        triplets.push(Triplet::new(r, c, m_e[i * k + j]));
                    }
                }
            }
        }
        let n = nodes.len();
        let matrix = SparseColMat::try_new_from_triplets(n, n, &triplets).map_err(|e| {
            FemError::LinearAlgebra {
                detail: format!("boundary mass pattern: {e:?}"),
            }
        })?;
        let mut solver = SpdSolver::new(matrix.symbolic())?;
        solver.factor(matrix.as_ref()).map_err(|e| match e {
            FemError::NonPositivePivot { row: Some(r) } => {
                FemError::SingularBoundaryMass { node: nodes[r] }
            }
            other => other,
        })?;
        Ok(Self {
            nodes,
            points,
            matrix,
            solver,
        })
    }

    /// The boundary's nodes (global numbers, sorted): the order of every vector of this type.
    #[inline]
    pub fn nodes(&self) -> &[usize] {
        &self.nodes
    }

    /// The position of global node `node` in [`BoundaryMass::nodes`], if it is on the boundary.
    #[inline]
    pub fn index_of(&self, node: usize) -> Option<usize> {
        self.nodes.binary_search(&node).ok()
    }

    /// `M v`: the consistent nodal forces of the field of nodal values `v`.
    ///
    /// # Panics
    /// If `v.len() != nodes().len()`.
    #[track_caller]
    pub fn apply(&self, v: &[f64]) -> Vec<f64> {
        assert_eq!(v.len(), self.nodes.len(), "one value per boundary node");
        let mut out = vec![0.0; v.len()];
        let m = self.matrix.as_ref();
        for c in 0..m.ncols() {
            for (r, &a) in m.row_idx_of_col(c).zip(m.val_of_col(c)) {
                out[r] += a * v[c];
                if r != c {
                    out[c] += a * v[r];
                }
            }
        }
        out
    }

    /// `M⁻¹ f`: the nodal values of the field whose consistent nodal forces are `f`.
    ///
    /// # Panics
    /// If `f.len() != nodes().len()`.
    #[track_caller]
    pub fn solve(&self, f: &[f64]) -> Vec<f64> {
        assert_eq!(f.len(), self.nodes.len(), "one force per boundary node");
        let mut x = f.to_vec();
        self.solver.solve_in_place(&mut x);
        x
    }

    /// `∫_Γ g(x, v(x)) w dΓ` with the same rule as the mass, where `v = Σ N_i v_i` is the
    /// field of nodal values `values` (in [`BoundaryMass::nodes`] order) and `x` the point
    /// (`[x, y, 0]` in 2D): e.g. an `L²` distance to a closed form.
    ///
    /// # Panics
    /// If `values.len() != nodes().len()`.
    ///
    /// # Examples
    /// ```
    /// use fem_core::boundary_mass::BoundaryMass;
    /// use fem_core::{ElementKind, Idealization, Mesh, Side};
    /// let mesh = Mesh::new(vec![[0.0, 0.0], [2.0, 0.0], [0.0, 1.0]], ElementKind::Tri3,
    ///     vec![0, 1, 2], vec![])?;
    /// let m = BoundaryMass::from_sides(&mesh, &[Side { element: 0, side: 0 }],
    ///     Idealization::PlaneStrain)?;
    /// // v = x / 2 on [0, 2]: ∫ v² dx = 2 / 3
    /// let i = m.integrate(&[0.0, 1.0], |_, v| v * v);
    /// assert!((i - 2.0 / 3.0).abs() < 1e-14);
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    #[track_caller]
    pub fn integrate(&self, values: &[f64], g: impl Fn([f64; 3], f64) -> f64) -> f64 {
        assert_eq!(
            values.len(),
            self.nodes.len(),
            "one value per boundary node"
        );
        self.points
            .iter()
            .map(|p| {
                let v: f64 = (0..p.count)
                    .map(|i| {
                        let k = self.index_of(p.nodes[i]).expect("a node of the boundary");
                        p.n[i] * values[k]
                    })
                    .sum();
                g(p.x, v) * p.weight
            })
            .sum()
    }

    /// `∫ N_i w dΓ` of each node (the row sums of `M`): the consistent nodal areas.
    pub fn areas(&self) -> Vec<f64> {
        self.apply(&vec![1.0; self.nodes.len()])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::ElementKind;

    /// A strip `[0, 3] × [1, 2]` (P1, or P2 with straight sides), its bottom sides `y = 1`.
    fn strip(kind: ElementKind) -> (Mesh, Vec<Side>) {
        let mut spec = crate::generate::RectangleSpec::new([0.0, 3.0], [1.0, 2.0], 3, 1);
        spec.kind = kind;
        let mesh = crate::generate::rectangle(&spec).unwrap();
        let sides = mesh.edge_set("bottom").unwrap().to_vec();
        (mesh, sides)
    }

    #[test]
    fn apply_then_solve_works_on_every_2d_idealization() {
        for kind in [ElementKind::Tri3, ElementKind::Tri6] {
            let (mesh, sides) = strip(kind);
            for ideal in [
                Idealization::PlaneStrain,
                Idealization::PlaneStress { thickness: 0.1 },
                Idealization::Axisymmetric,
            ] {
                let m = BoundaryMass::from_sides(&mesh, &sides, ideal).unwrap();
                // the areas of a unit pressure sum to the side's measure: 3, 0.3, ∫ r dx = 4.5
                let total: f64 = m.areas().iter().sum();
                let expected = match ideal {
                    Idealization::PlaneStrain => 3.0,
                    Idealization::PlaneStress { .. } => 0.3,
                    _ => 4.5,
                };
                // a few round-offs of sums of order 1
                assert!(
                    (total - expected).abs() < 1e-13,
                    "{kind:?} {ideal:?}: {total}"
                );
                let v: Vec<f64> = (0..m.nodes().len()).map(|i| (i as f64).sin()).collect();
                let back = m.solve(&m.apply(&v));
                for (a, b) in v.iter().zip(&back) {
                    // a small SPD system (condition number below 10³ here)
                    assert!((a - b).abs() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn from_sides_rejects_empty_missing_and_axis_sides() {
        let (mesh, _) = strip(ElementKind::Tri3);
        assert!(matches!(
            BoundaryMass::from_sides(&mesh, &[], Idealization::PlaneStrain),
            Err(FemError::EmptyBoundary { .. })
        ));
        let bad = Side {
            element: 99,
            side: 0,
        };
        assert!(matches!(
            BoundaryMass::from_sides(&mesh, &[bad], Idealization::PlaneStrain),
            Err(FemError::InvalidSide { element: 99, .. })
        ));
        // the left side lies on the axis r = 0: no weight in axisymmetry
        let axis = mesh.edge_set("left").unwrap();
        assert!(matches!(
            BoundaryMass::from_sides(&mesh, axis, Idealization::Axisymmetric),
            Err(FemError::SingularBoundaryMass { .. })
        ));
    }

    #[test]
    fn on_nodes_finds_the_surface_of_a_node_set_works() {
        let (mesh, sides) = strip(ElementKind::Tri6);
        let bottom = mesh.node_set("bottom").unwrap();
        let a = BoundaryMass::on_nodes(&mesh, bottom, Idealization::PlaneStrain).unwrap();
        let b = BoundaryMass::from_sides(&mesh, &sides, Idealization::PlaneStrain).unwrap();
        assert_eq!(a.nodes(), b.nodes());
        for (x, y) in a.areas().iter().zip(b.areas()) {
            // the same integrals summed in another order
            assert!((x - y).abs() < 1e-15);
        }
        // a single node makes no side
        assert!(matches!(
            BoundaryMass::on_nodes(&mesh, &bottom[..1], Idealization::PlaneStrain),
            Err(FemError::EmptyBoundary { .. })
        ));
        let solid = crate::solid::generate::box_mesh(
            &[0.0, 1.0],
            &[0.0, 1.0],
            &[0.0, 1.0],
            ElementKind::Tet10,
        )
        .unwrap();
        let top = solid.node_set("z1").unwrap();
        let m = BoundaryMass::on_nodes_3d(&solid, top).unwrap();
        let f = BoundaryMass::from_faces(&solid, solid.face_set("z1").unwrap()).unwrap();
        assert_eq!(m.nodes(), f.nodes());
        // the face's area, 1, to round-off
        assert!((m.areas().iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn from_faces_works_and_rejects_bad_faces() {
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let mesh = SolidMesh::new(nodes, ElementKind::Tet4, vec![0, 1, 2, 3], vec![]).unwrap();
        let p2 = mesh.to_tet10(None).unwrap();
        let face = Face {
            element: 0,
            side: 0,
        };
        let m = BoundaryMass::from_faces(&p2, &[face]).unwrap();
        assert_eq!(m.nodes().len(), 6);
        let areas = m.areas();
        // the P2 triangle: ∫ N = 0 at the corners, A / 3 at the mid-edge nodes
        for (k, n) in m.nodes().iter().enumerate() {
            let expected = if *n < 4 { 0.0 } else { 0.5 / 3.0 };
            assert!((areas[k] - expected).abs() < 1e-15);
        }
        assert!(matches!(
            BoundaryMass::from_faces(&mesh, &[]),
            Err(FemError::EmptyBoundary { .. })
        ));
        assert!(matches!(
            BoundaryMass::from_faces(
                &mesh,
                &[Face {
                    element: 0,
                    side: 4
                }]
            ),
            Err(FemError::InvalidSide { side: 4, .. })
        ));
    }
}
