//! The mesh series of a distributed run (issue 41) as ParaView's parallel format: each rank
//! writes the elements of its part of the partition as one piece `mesh_NNNN_R.vtu` (its
//! elements, the nodes they use, the fields restricted to them), rank 0 writes `mesh_NNNN.pvtu`,
//! which names every piece and declares the arrays, and `mesh.pvd` lists the `.pvtu` files.
//!
//! ```text
//! mesh.pvd ── mesh_0000.pvtu ─┬─ mesh_0000_0.vtu   (rank 0's elements)
//!                             └─ mesh_0000_1.vtu   (rank 1's)
//! ```
//! A node on the border of two parts is in both pieces with the same values. Written once over
//! the dimension: a piece is a [`Mesh`] of the part's elements.

use super::errors::{fem_failed, io};
use crate::error::CliResult;
use fem_core::element::VoigtStress;
use fem_core::vtk::{Field, write_vtu};
use fem_core::{Dim, Mesh, Space};
use std::path::PathBuf;

/// This rank's part of the parallel mesh series.
#[derive(Clone, Debug)]
pub struct Pieces {
    rank: usize,
    /// The elements of each rank, by rank (every rank knows the whole partition).
    counts: Vec<usize>,
    /// This rank's elements.
    elements: Vec<usize>,
    /// Where the pieces and the `.pvtu` files go: the run's output directory (ranks other
    /// than 0 write their other files in a scratch directory).
    dir: PathBuf,
}

impl Pieces {
    /// The pieces of `rank` for the partition `element_rank` (each element's rank) over
    /// `size` ranks, written in `dir`.
    // made by the distributed run only, which the feature `petsc` builds
    #[cfg_attr(not(feature = "petsc"), allow(dead_code))]
    pub fn new(rank: usize, size: usize, element_rank: &[usize], dir: PathBuf) -> Self {
        let mut counts = vec![0; size];
        element_rank.iter().for_each(|&r| counts[r] += 1);
        let elements = (0..element_rank.len())
            .filter(|&e| element_rank[e] == rank)
            .collect();
        Self {
            rank,
            counts,
            elements,
            dir,
        }
    }

    /// Writes this rank's piece `{stem}_{rank}.vtu` of `mesh` (no file for a rank without
    /// elements) with the fields (given on the whole mesh: one value per node, per element),
    /// and on rank 0 `{stem}.pvtu`; returns the `.pvtu`'s name, for the `.pvd`.
    pub(super) fn write<const D: usize>(
        &self,
        stem: &str,
        mesh: &Mesh<D>,
        point: &[(&str, Field<'_, D>)],
        cell: &[(&str, Field<'_, D>)],
    ) -> CliResult<String>
    where
        Dim<D>: Space,
    {
        let piece = |r: usize| format!("{stem}_{r}.vtu");
        // rank 0 makes the directory too, but a rank may get here first
        std::fs::create_dir_all(&self.dir).map_err(|e| io(&self.dir, e))?;
        if !self.elements.is_empty() {
            // the part's nodes, numbered in the order met
            let mut local = vec![usize::MAX; mesh.node_count()];
            let mut nodes = Vec::new();
            let mut connectivity = Vec::new();
            for &e in &self.elements {
                for &n in mesh.element(e) {
                    if local[n] == usize::MAX {
                        local[n] = nodes.len();
                        nodes.push(n);
                    }
                    connectivity.push(local[n]);
                }
            }
            let regions = self.elements.iter().map(|&e| mesh.regions()[e]).collect();
            let coords = nodes.iter().map(|&n| mesh.nodes()[n]).collect();
            let part = Mesh::<D>::new(coords, mesh.kind(), connectivity, regions)
                .map_err(|e| fem_failed("the mesh piece of this rank", e))?;
            let point: Vec<(&str, Owned<D>)> = point
                .iter()
                .map(|(n, f)| (*n, restrict(f, &nodes)))
                .collect();
            let cell: Vec<(&str, Owned<D>)> = cell
                .iter()
                .map(|(n, f)| (*n, restrict(f, &self.elements)))
                .collect();
            let path = self.dir.join(piece(self.rank));
            write_vtu(
                &path,
                &part,
                &point
                    .iter()
                    .map(|(n, f)| (*n, f.field()))
                    .collect::<Vec<_>>(),
                &cell
                    .iter()
                    .map(|(n, f)| (*n, f.field()))
                    .collect::<Vec<_>>(),
            )
            .map_err(|e| io(&path, e))?;
        }
        let name = format!("{stem}.pvtu");
        if self.rank == 0 {
            let path = self.dir.join(&name);
            let sources: Vec<String> = (0..self.counts.len())
                .filter(|&r| self.counts[r] > 0)
                .map(piece)
                .collect();
            std::fs::write(&path, pvtu(point, cell, &sources)).map_err(|e| io(&path, e))?;
        }
        Ok(name)
    }
}

/// A field restricted to a part, owned.
enum Owned<const D: usize>
where
    Dim<D>: Space,
{
    Scalar(Vec<f64>),
    Vector(Vec<[f64; D]>),
    SymTensor(Vec<VoigtStress<D>>),
}

impl<const D: usize> Owned<D>
where
    Dim<D>: Space,
{
    fn field(&self) -> Field<'_, D> {
        match self {
            Owned::Scalar(v) => Field::Scalar(v),
            Owned::Vector(v) => Field::Vector(v),
            Owned::SymTensor(v) => Field::SymTensor(v),
        }
    }
}

/// `f` at the entries `ids`.
fn restrict<const D: usize>(f: &Field<'_, D>, ids: &[usize]) -> Owned<D>
where
    Dim<D>: Space,
{
    match f {
        Field::Scalar(v) => Owned::Scalar(ids.iter().map(|&i| v[i]).collect()),
        Field::Vector(v) => Owned::Vector(ids.iter().map(|&i| v[i]).collect()),
        Field::SymTensor(v) => Owned::SymTensor(ids.iter().map(|&i| v[i]).collect()),
    }
}

/// The components a field is written with (fem-core's VTK: vectors as 3, tensors as 3×3).
fn components<const D: usize>(f: &Field<'_, D>) -> usize
where
    Dim<D>: Space,
{
    match f {
        Field::Scalar(_) => 1,
        Field::Vector(_) => 3,
        Field::SymTensor(_) => 9,
    }
}

/// The `.pvtu` file: the arrays of the pieces (as fem-core's VTK writes them: `Float64`, the
/// cell array `region` as `UInt32`) and the pieces' files.
fn pvtu<const D: usize>(
    point: &[(&str, Field<'_, D>)],
    cell: &[(&str, Field<'_, D>)],
    sources: &[String],
) -> String
where
    Dim<D>: Space,
{
    let array = |name: &str, kind: &str, n: usize| {
        format!("      <PDataArray type=\"{kind}\" Name=\"{name}\" NumberOfComponents=\"{n}\"/>\n")
    };
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" \
         byte_order=\"LittleEndian\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n    <PPointData>\n",
    );
    for (name, f) in point {
        xml.push_str(&array(name, "Float64", components(f)));
    }
    xml.push_str("    </PPointData>\n    <PCellData>\n");
    for (name, f) in cell {
        xml.push_str(&array(name, "Float64", components(f)));
    }
    xml.push_str(&array("region", "UInt32", 1));
    xml.push_str(
        "    </PCellData>\n    <PPoints>\n      <PDataArray type=\"Float64\" \
         NumberOfComponents=\"3\"/>\n    </PPoints>\n",
    );
    for s in sources {
        xml.push_str(&format!("    <Piece Source=\"{s}\"/>\n"));
    }
    xml.push_str("  </PUnstructuredGrid>\n</VTKFile>\n");
    xml
}

#[cfg(test)]
mod tests {
    use super::*;
    use fem_core::solid::SolidKind;
    use fem_core::solid::generate::{box_mesh, lines};

    #[test]
    fn issue_41_pieces_cover_the_mesh_once_works() {
        let l = lines(0.0, 1.0, 2);
        let mesh = box_mesh(&l, &l, &l, SolidKind::Tet4).unwrap();
        let dir = std::env::temp_dir().join(format!("bipo_pieces_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // two parts: the elements by parity
        let ranks: Vec<usize> = (0..mesh.element_count()).map(|e| e % 2).collect();
        let u: Vec<[f64; 3]> = mesh.nodes().iter().map(|p| [p[2], 0.0, 0.0]).collect();
        let s = vec![[1.0; 6]; mesh.element_count()];
        let point = [("u", Field::Vector(&u[..]))];
        let cell = [("stress", Field::SymTensor(&s[..]))];
        let mut total = 0;
        for rank in [1, 0] {
            let p = Pieces::new(rank, 2, &ranks, dir.clone());
            assert_eq!(p.write("m", &mesh, &point, &cell).unwrap(), "m.pvtu");
            total += p.elements.len();
        }
        // every element in exactly one piece
        assert_eq!(total, mesh.element_count());
        let xml = std::fs::read_to_string(dir.join("m.pvtu")).unwrap();
        assert!(xml.contains("<Piece Source=\"m_0.vtu\"/>"));
        assert!(xml.contains("<Piece Source=\"m_1.vtu\"/>"));
        assert!(xml.contains("Name=\"u\" NumberOfComponents=\"3\""));
        assert!(xml.contains("Name=\"stress\" NumberOfComponents=\"9\""));
        for r in 0..2 {
            let piece = std::fs::read_to_string(dir.join(format!("m_{r}.vtu"))).unwrap();
            assert!(piece.contains("Name=\"u\"") && piece.contains("Name=\"region\""));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
