//! The element assembly of the distributed stiffness, in any dimension: each rank adds the
//! `K_e` of its elements (fem-core's element kernels, the same calls as the serial
//! [`ElasticModel`](fem_core::ElasticModel) makes) into the MPIAIJ matrix, keeps their
//! prescribed columns (`K_fp`), and gives the preallocation and GAMG's near-null space.
//!
//! ```text
//! K_e      element.stiffness_into(e, coords, material, setting)   setting: the Idealization
//!                                                                  in 2D, () in 3D
//! rows     the free dofs of the element's nodes, in the distributed numbering (Partition)
//! K_fp ū   kept as (row, node, component, K_e entry) for the prescribed dofs: each rank adds
//!          its own to b at every free response (the values ū may change, K_fp does not)
//! ```

use crate::error::PetscError;
use crate::ffi::PetscInt;
use crate::linalg::{System, int};
use crate::partition::Partition;
use fem_core::dirichlet::Dof;
use fem_core::element::Setting;
use fem_core::{Component, Dim, DofMap, FemError, Idealization, Material, Mesh, Space};
use std::collections::BTreeMap;

/// A `K_fp` entry of this rank's elements: (distributed row, node, component, value).
pub(crate) type Coupling = (PetscInt, usize, Component, f64);

/// The rigid-body motions on the free dofs, in the distributed numbering, orthonormalised
/// (modified Gram–Schmidt; a mode the supports make dependent on the others is dropped):
/// GAMG's near-null space, without which its coarse spaces miss the rotations and CG needs
/// several times the iterations.
///
/// ```text
/// 3D            three translations, three rotations ω × x about the centroid
/// plane         two translations, the in-plane rotation (−y, x)
/// axisymmetry   the two translations: u_z is a rigid motion; u_r = const is not (hoop
///               strain u_r / r) but is as smooth, which is what the coarse space wants
/// ```
pub(crate) fn rigid_modes<const D: usize>(
    mesh: &Mesh<D>,
    setting: &Setting<D>,
    dofs: &DofMap<D>,
    partition: &Partition,
) -> Vec<Vec<f64>>
where
    Dim<D>: Space,
{
    let n = dofs.free_count();
    let nodes = mesh.nodes();
    let mut centre = [0.0; D];
    for p in nodes {
        for a in 0..D {
            centre[a] += p[a] / nodes.len() as f64;
        }
    }
    let rotations = match <Dim<D> as Space>::idealization(setting) {
        None => 3,
        Some(Idealization::Axisymmetric) => 0,
        Some(_) => 1,
    };
    let mut modes: Vec<Vec<f64>> = Vec::new();
    for k in 0..D + rotations {
        let mut v = vec![0.0; n];
        for (node, p) in nodes.iter().enumerate() {
            let mut x = [0.0; 3];
            for a in 0..D {
                x[a] = p[a] - centre[a];
            }
            // translations e_k; rotations ω × x with ω = e_(k−D) (e_z in the plane)
            let u = match (D, k) {
                (_, k) if k < D => {
                    let mut e = [0.0; 3];
                    e[k] = 1.0;
                    e
                }
                (2, _) | (3, 5) => [-x[1], x[0], 0.0],
                (_, 3) => [0.0, -x[2], x[1]],
                _ => [x[2], 0.0, -x[0]],
            };
            for (c, d) in dofs.free_dofs(node).into_iter().enumerate() {
                if let Some(i) = d {
                    v[partition.row[i]] = u[c];
                }
            }
        }
        let before = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        for m in &modes {
            let dot: f64 = v.iter().zip(m).map(|(a, b)| a * b).sum();
            v.iter_mut().zip(m).for_each(|(a, b)| *a -= dot * b);
        }
        let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        if norm > 1e-8 * before {
            v.iter_mut().for_each(|a| *a /= norm);
            modes.push(v);
        }
    }
    modes
}

/// Nonzeros per owned row in the diagonal block (columns this rank owns) and off it: a row of
/// node `n` couples with every free dof of the nodes sharing an element with `n`.
pub(crate) fn preallocation<const D: usize>(
    mesh: &Mesh<D>,
    dofs: &DofMap<D>,
    partition: &Partition,
    rank: usize,
) -> Result<(Vec<PetscInt>, Vec<PetscInt>), PetscError>
where
    Dim<D>: Space,
{
    let owned = partition.offsets[rank + 1] - partition.offsets[rank];
    let (mut d_nnz, mut o_nnz) = (vec![0; owned], vec![0; owned]);
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); mesh.node_count()];
    for e in 0..mesh.element_count() {
        let cell = mesh.element(e);
        for &n in cell {
            if partition.node_rank[n] == rank {
                neighbours[n].extend_from_slice(cell);
            }
        }
    }
    for (n, list) in neighbours.iter_mut().enumerate() {
        if partition.node_rank[n] != rank {
            continue;
        }
        list.sort_unstable();
        list.dedup();
        let (mut d, mut o) = (0, 0);
        for &m in list.iter() {
            let free = dofs.free_dofs(m).into_iter().flatten().count();
            if partition.node_rank[m] == rank {
                d += free;
            } else {
                o += free;
            }
        }
        for i in dofs.free_dofs(n).into_iter().flatten() {
            let local = partition.row[i] - partition.offsets[rank];
            d_nnz[local] = int("nonzeros of a row", d)?;
            o_nnz[local] = int("nonzeros of a row", o)?;
        }
    }
    Ok((d_nnz, o_nnz))
}

/// What [`assemble`] reads: the mesh, its setting, materials and dof map, and the partition.
pub(crate) struct Body<'a, const D: usize>
where
    Dim<D>: Space,
{
    pub(crate) mesh: &'a Mesh<D>,
    pub(crate) setting: &'a Setting<D>,
    pub(crate) materials: &'a BTreeMap<u32, Material>,
    pub(crate) dofs: &'a DofMap<D>,
    pub(crate) partition: &'a Partition,
}

/// Adds this rank's element stiffnesses into the matrix; returns their `K_fp` entries.
pub(crate) fn assemble<const D: usize>(
    body: &Body<'_, D>,
    rank: usize,
    system: &System,
) -> Result<Vec<Coupling>, PetscError>
where
    Dim<D>: Space,
{
    let Body {
        mesh,
        setting,
        materials,
        dofs,
        partition,
    } = *body;
    let element = mesh.built_in_element();
    let mut k_e = nalgebra::DMatrix::zeros(0, 0);
    let mut coords = Vec::new();
    let (mut rows, mut local, mut values) = (Vec::new(), Vec::new(), Vec::new());
    let mut coupling = Vec::new();
    for e in (0..mesh.element_count()).filter(|&e| partition.element_rank[e] == rank) {
        mesh.element_coords_into(e, &mut coords);
        let region = mesh.regions()[e];
        let material = &materials[&region];
        element.stiffness_into(e, &coords, material, setting, &mut k_e)?;
        if k_e.iter().any(|v| !v.is_finite()) {
            return Err(FemError::NonFiniteStiffness {
                element: e,
                region,
                young: material.young(),
            }
            .into());
        }
        rows.clear();
        local.clear();
        let cell = mesh.element(e);
        for (a, &n) in cell.iter().enumerate() {
            for (c, dof) in dofs.dofs(n).into_iter().enumerate() {
                if let Dof::Free(i) = dof {
                    rows.push(int("free dof", partition.row[i])?);
                    local.push(D * a + c);
                }
            }
        }
        values.clear();
        values.extend(
            local
                .iter()
                .flat_map(|&i| local.iter().map(move |&j| (i, j)))
                .map(|(i, j)| k_e[(i, j)]),
        );
        system.add_block(&rows, &values)?;
        for (&row, &i) in rows.iter().zip(&local) {
            for (b, &m) in cell.iter().enumerate() {
                for (c, dof) in dofs.dofs(m).into_iter().enumerate() {
                    let value = k_e[(i, D * b + c)];
                    if matches!(dof, Dof::Prescribed(_)) && value != 0.0 {
                        coupling.push((row, m, Component::all::<D>()[c], value));
                    }
                }
            }
        }
    }
    Ok(coupling)
}

#[cfg(test)]
mod tests {
    //! The parts of the assembly that need no MPI: GAMG's near-null space and the
    //! preallocation, against the serial element matrices (fem-core's kernels).
    use super::*;
    use fem_core::generate::{RectangleSpec, rectangle};
    use fem_core::{ElementKind, Supports};
    use nalgebra::DMatrix;

    fn plane_mesh() -> Mesh<2> {
        let mut spec = RectangleSpec::new([0.5, 2.0], [0.0, 1.0], 3, 2);
        spec.kind = ElementKind::Tri6;
        rectangle(&spec).unwrap()
    }

    /// The dense stiffness over the free dofs in the distributed numbering (one rank).
    fn dense<const D: usize>(
        mesh: &Mesh<D>,
        setting: &Setting<D>,
        dofs: &DofMap<D>,
        partition: &Partition,
    ) -> DMatrix<f64>
    where
        Dim<D>: Space,
    {
        let n = dofs.free_count();
        let mut k = DMatrix::zeros(n, n);
        let material = Material::new(100.0, 0.3, 0.0).unwrap();
        let (mut k_e, mut coords) = (DMatrix::zeros(0, 0), Vec::new());
        for e in 0..mesh.element_count() {
            mesh.element_coords_into(e, &mut coords);
            mesh.built_in_element()
                .stiffness_into(e, &coords, &material, setting, &mut k_e)
                .unwrap();
            let cell = mesh.element(e);
            for (a, &p) in cell.iter().enumerate() {
                for (b, &q) in cell.iter().enumerate() {
                    for (c, i) in dofs.free_dofs(p).into_iter().enumerate() {
                        for (d, j) in dofs.free_dofs(q).into_iter().enumerate() {
                            if let (Some(i), Some(j)) = (i, j) {
                                k[(partition.row[i], partition.row[j])] +=
                                    k_e[(D * a + c, D * b + d)];
                            }
                        }
                    }
                }
            }
        }
        k
    }

    /// `‖K m‖ / ‖K‖` for each mode.
    fn energies(k: &DMatrix<f64>, modes: &[Vec<f64>]) -> Vec<f64> {
        modes
            .iter()
            .map(|m| (k * nalgebra::DVector::from_column_slice(m)).norm() / k.norm())
            .collect()
    }

    fn assert_orthonormal(modes: &[Vec<f64>]) {
        for (a, m) in modes.iter().enumerate() {
            for (b, l) in modes.iter().enumerate() {
                let dot: f64 = m.iter().zip(l).map(|(x, y)| x * y).sum();
                // modified Gram–Schmidt on a few hundred entries: round-off only
                assert!(
                    (dot - f64::from(u8::from(a == b))).abs() < 1e-12,
                    "{a} {b} {dot}"
                );
            }
        }
    }

    #[test]
    fn plane_strain_modes_are_the_rigid_motions_works() {
        let mesh = plane_mesh();
        let dofs = DofMap::<2>::numbered(mesh.node_count(), &Supports::new()).unwrap();
        let partition = Partition::slabs(&mesh, &dofs, 1);
        let setting = Idealization::PlaneStrain;
        let modes = rigid_modes(&mesh, &setting, &dofs, &partition);
        assert_eq!(modes.len(), 3, "two translations and the rotation");
        assert_orthonormal(&modes);
        let k = dense(&mesh, &setting, &dofs, &partition);
        for e in energies(&k, &modes) {
            // exact rigid motions: K m vanishes to round-off
            assert!(e < 1e-12, "{e}");
        }
    }

    #[test]
    fn axisymmetric_modes_are_the_two_translations_works() {
        let mesh = plane_mesh();
        let dofs = DofMap::<2>::numbered(mesh.node_count(), &Supports::new()).unwrap();
        let partition = Partition::slabs(&mesh, &dofs, 1);
        let setting = Idealization::Axisymmetric;
        let modes = rigid_modes(&mesh, &setting, &dofs, &partition);
        assert_eq!(modes.len(), 2, "u_r and u_z, no rotation");
        assert_orthonormal(&modes);
        let k = dense(&mesh, &setting, &dofs, &partition);
        let e = energies(&k, &modes);
        // u_z is rigid; u_r = const strains the hoop (u_r / r): not in the kernel
        assert!(e[1] < 1e-12 && e[0] > 1e-3, "{e:?}");
    }

    #[test]
    fn supports_drop_the_modes_they_remove_works() {
        let mesh = plane_mesh();
        let mut supports = Supports::new();
        // every x fixed: only the y dofs are free
        let all: Vec<usize> = (0..mesh.node_count()).collect();
        supports.fix(&all, Component::X);
        let dofs = DofMap::<2>::numbered(mesh.node_count(), &supports).unwrap();
        let partition = Partition::slabs(&mesh, &dofs, 1);
        let modes = rigid_modes(&mesh, &Idealization::PlaneStrain, &dofs, &partition);
        // the x translation vanishes (dropped); the y translation and the rotation's x·e_y
        // part stay
        assert_eq!(modes.len(), 2);
        assert_orthonormal(&modes);
    }

    #[test]
    fn preallocation_counts_every_coupled_dof_works() {
        let mesh = plane_mesh();
        let mut supports = Supports::new();
        supports.fix(mesh.node_set("bottom").unwrap(), Component::Y);
        let dofs = DofMap::<2>::numbered(mesh.node_count(), &supports).unwrap();
        for ranks in [1, 2] {
            let partition = Partition::slabs(&mesh, &dofs, ranks);
            let k = dense(&mesh, &Idealization::PlaneStrain, &dofs, &partition);
            for rank in 0..ranks {
                let (d, o) = preallocation(&mesh, &dofs, &partition, rank).unwrap();
                let (lo, hi) = (partition.offsets[rank], partition.offsets[rank + 1]);
                for row in lo..hi {
                    let nonzero = |cols: &mut dyn Iterator<Item = usize>| {
                        cols.filter(|&c| k[(row, c)] != 0.0).count() as PetscInt
                    };
                    let (in_d, in_o) = (
                        nonzero(&mut (lo..hi)),
                        nonzero(&mut (0..lo).chain(hi..k.ncols())),
                    );
                    // the pattern holds every nonzero (and the structural zeros of P2)
                    assert!(d[row - lo] >= in_d && o[row - lo] >= in_o, "row {row}");
                    assert!(d[row - lo] > 0, "row {row} couples with itself");
                }
                if ranks == 2 {
                    assert!(
                        o.iter().any(|&v| v > 0),
                        "rank {rank} couples with the other"
                    );
                }
            }
        }
    }
}
