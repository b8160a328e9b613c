//! The meridian section `(r, z)` that both scenes are built on: fem-core's pile-in-soil mesh
//! with the pile's tip detached from the soil below (module docs of `presets::pile`, "The
//! tip"). The axisymmetric scene meshes it as is, the 3D one revolves it.

use super::PulloutSpec;
use contact_solver::SolverError;
use fem_core::generate::{PILE, SOIL, pile_in_soil};
use fem_core::{FemError, Material, Mesh};

/// The meridian mesh and its interface nodes.
pub(super) struct Meridian {
    /// The mesh, tip detached (node sets of [`detach_tip`]).
    pub mesh: Mesh,
    /// The pile's shaft nodes (`interface_pile`), from the tip corner up.
    pub shaft_pile: Vec<usize>,
    /// The soil's shaft nodes (`interface_soil`), paired by index with `shaft_pile`.
    pub shaft_soil: Vec<usize>,
    /// The pile's tip nodes at `r < R` (copies), sorted by `r`.
    pub tip_pile: Vec<usize>,
    /// The soil's tip nodes, paired by index with `tip_pile`.
    pub tip_soil: Vec<usize>,
}

impl PulloutSpec {
    /// The meridian section of the scene (module docs).
    pub(super) fn meridian(&self) -> Result<Meridian, SolverError> {
        let generated = pile_in_soil(&self.mesh)?;
        let (mesh, tip_pile, tip_soil) = detach_tip(generated, self.radius(), self.mesh.length)?;
        Ok(Meridian {
            shaft_pile: mesh.node_set("interface_pile")?.to_vec(),
            shaft_soil: mesh.node_set("interface_soil")?.to_vec(),
            mesh,
            tip_pile,
            tip_soil,
        })
    }

    /// The materials by region: the soil's and the pile's.
    ///
    /// # Errors
    /// [`SolverError::Structure`] for an invalid Young's modulus, Poisson's ratio or unit
    /// weight.
    pub(super) fn materials(&self) -> Result<[(u32, Material); 2], SolverError> {
        Ok([
            (
                SOIL,
                Material::new(self.soil_young, self.soil_poisson, self.soil_unit_weight)?,
            ),
            (
                PILE,
                Material::new(self.pile_young, self.pile_poisson, self.pile_unit_weight)?,
            ),
        ])
    }
}

/// Duplicates the pile's tip nodes at `r < radius` (bonded to the soil by the generator) so the
/// tip can lift off: pile elements get new copies, the soil keeps the originals. Returns the
/// mesh (every set kept; `"axis"` gains the pile copy of the axis node; new node sets
/// `"tip_pile"` and `"tip_soil"`) and the paired tip nodes, pile copies then soil originals,
/// sorted by `r`.
pub(crate) fn detach_tip(
    mesh: Mesh,
    radius: f64,
    length: f64,
) -> Result<(Mesh, Vec<usize>, Vec<usize>), FemError> {
    let tol = 1e-9 * radius.max(length);
    let npe = mesh.kind().node_count();
    let mut on_tip: Vec<usize> = (0..mesh.node_count())
        .filter(|&n| {
            let p = mesh.nodes()[n];
            (p[1] + length).abs() <= tol && p[0] < radius - tol
        })
        .filter(|&n| {
            (0..mesh.element_count())
                .any(|e| mesh.regions()[e] == PILE && mesh.element(e).contains(&n))
        })
        .collect();
    on_tip.sort_by(|a, b| mesh.nodes()[*a][0].total_cmp(&mesh.nodes()[*b][0]));
    let mut nodes = mesh.nodes().to_vec();
    let mut copy = std::collections::HashMap::new();
    for &n in &on_tip {
        copy.insert(n, nodes.len());
        nodes.push(nodes[n]);
    }
    let mut connectivity = mesh.connectivity().to_vec();
    for (cell, &region) in connectivity.chunks_exact_mut(npe).zip(mesh.regions()) {
        if region == PILE {
            for node in cell.iter_mut() {
                if let Some(&c) = copy.get(node) {
                    *node = c;
                }
            }
        }
    }
    let mut out = Mesh::new(nodes, mesh.kind(), connectivity, mesh.regions().to_vec())?;
    for name in mesh.edge_set_names() {
        out.add_edge_set(name, mesh.edge_set(name)?.to_vec())?;
    }
    for name in mesh.node_set_names() {
        let mut set = mesh.node_set(name)?.to_vec();
        if name == "axis" {
            set.extend(
                set.iter()
                    .filter_map(|n| copy.get(n))
                    .copied()
                    .collect::<Vec<_>>(),
            );
        }
        out.add_node_set(name, set)?;
    }
    let tip_pile: Vec<usize> = on_tip.iter().map(|n| copy[n]).collect();
    out.add_node_set("tip_pile", tip_pile.clone())?;
    out.add_node_set("tip_soil", on_tip.clone())?;
    Ok((out, tip_pile, on_tip))
}

#[cfg(test)]
mod tests {
    use super::*;
    use fem_core::generate::PileSpec;

    #[test]
    fn detach_tip_works() {
        let spec = PileSpec {
            cells_shaft: 4,
            cells_soil_r: 3,
            cells_below_tip: 2,
            ..PileSpec::default()
        };
        let mesh = pile_in_soil(&spec).unwrap();
        let n0 = mesh.node_count();
        let (mesh, pile, soil) = detach_tip(mesh, 0.135, 13.0).unwrap();
        // P2, 2 cells across the pile: nodes at r = 0, R/4, R/2, 3R/4 (the corner is split).
        assert_eq!(pile.len(), 4);
        assert_eq!(mesh.node_count(), n0 + 4);
        for (p, s) in pile.iter().zip(&soil) {
            assert_eq!(mesh.nodes()[*p], mesh.nodes()[*s]);
            assert_ne!(p, s);
        }
        assert!(mesh.node_set("axis").unwrap().contains(&pile[0]));
        // no element uses both a pile copy and its soil original
        for e in 0..mesh.element_count() {
            let cell = mesh.element(e);
            for (p, s) in pile.iter().zip(&soil) {
                assert!(!(cell.contains(p) && cell.contains(s)));
            }
        }
    }
}
