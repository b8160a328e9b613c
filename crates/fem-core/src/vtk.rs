//! Writing meshes and fields for ParaView: VTK XML unstructured grids (`.vtu`) through the
//! [`vtkio`] crate, and `.pvd` collections for time series.
//!
//! Each cell has its element's VTK type ([`Topology::vtk_cell`](crate::element::Topology::vtk_cell)),
//! whose node order is ours; 2D points are written with `z = 0` (so `(r, z)` in axisymmetry
//! appears as `(x, y)`). Every array is `Float64`, base64-encoded inline; the element regions
//! are always written as the cell array `region` (`UInt32`).

use crate::element::VoigtStress;
use crate::error::FemError;
use crate::mesh::{Mesh, SolidMesh};
use crate::space::{Dim, Space};
use std::io::Write;
use std::path::Path;
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, UnstructuredGridPiece, Version,
    VertexNumbers, Vtk,
};

/// Values of one field on a mesh of dimension `D`, one entry per node (point data) or per
/// element (cell data).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Field<'a, const D: usize = 2>
where
    Dim<D>: Space,
{
    /// A scalar.
    Scalar(&'a [f64]),
    /// A vector: in-plane `(x, y)` (or `(r, z)`), written as a 3-vector with zero `z`, or
    /// `(x, y, z)`, e.g. a displacement.
    Vector(&'a [[f64; D]]),
    /// A symmetric tensor in the order of [`Space::Stress`] — `(xx, yy, xy, zz)` in 2D (`zz`
    /// the out-of-plane or hoop component), `(xx, yy, zz, xy, yz, zx)` in 3D — written as a
    /// full 3×3 tensor (9 components).
    SymTensor(&'a [VoigtStress<D>]),
}

/// A field on a 3D mesh ([`write_vtu_3d`]).
pub type Field3<'a> = Field<'a, 3>;

/// A point `[f64; D]` as `(x, y, z)`, `z = 0` in 2D.
fn xyz<const D: usize>(p: &[f64; D]) -> [f64; 3] {
    std::array::from_fn(|a| p.get(a).copied().unwrap_or(0.0))
}

impl<const D: usize> Field<'_, D>
where
    Dim<D>: Space,
{
    fn len(&self) -> usize {
        match self {
            Field::Scalar(v) => v.len(),
            Field::Vector(v) => v.len(),
            Field::SymTensor(v) => v.len(),
        }
    }

    fn attribute(&self, name: &str) -> Attribute {
        match *self {
            Field::Scalar(v) => Attribute::scalars(name, 1).with_data(v.to_vec()),
            Field::Vector(v) => {
                Attribute::vectors(name).with_data(v.iter().flat_map(xyz).collect::<Vec<f64>>())
            }
            Field::SymTensor(v) => Attribute::tensors(name).with_data(
                v.iter()
                    .flat_map(|s| match *s.as_ref() {
                        [xx, yy, xy, zz] => [xx, xy, 0.0, xy, yy, 0.0, 0.0, 0.0, zz],
                        [xx, yy, zz, xy, yz, zx] => [xx, xy, zx, xy, yy, yz, zx, yz, zz],
                        _ => unreachable!("a Voigt stress has 4 or 6 components"),
                    })
                    .collect::<Vec<f64>>(),
            ),
        }
    }
}

/// Writes `mesh` with nodal fields `point_data` and element fields `cell_data` as a VTK XML
/// unstructured grid (give `path` the extension `.vtu` for ParaView). Non-finite values are
/// written as they are.
///
/// # Errors
/// - [`FemError::LengthMismatch`] if a point field does not have one entry per node or a cell
///   field one entry per element;
/// - [`FemError::Io`] if the file cannot be written.
///
/// # Examples
/// ```
/// use fem_core::generate::{rectangle, RectangleSpec};
/// use fem_core::vtk::{write_vtu, Field};
/// let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2)).unwrap();
/// let u: Vec<[f64; 2]> = mesh.nodes().iter().map(|p| [0.1 * p[1], 0.0]).collect();
/// let path = std::env::temp_dir().join("fem_core_vtk_doc.vtu");
/// write_vtu(&path, &mesh, &[("u", Field::Vector(&u))], &[]).unwrap();
/// ```
pub fn write_vtu<const D: usize>(
    path: &Path,
    mesh: &Mesh<D>,
    point_data: &[(&str, Field<'_, D>)],
    cell_data: &[(&str, Field<'_, D>)],
) -> Result<(), FemError>
where
    Dim<D>: Space,
{
    write_model(path, model(mesh, point_data, cell_data)?)
}

/// [`write_vtu`] on a 3D mesh, e.g. with the displacement as a [`Field::Vector`] and a stress
/// as a [`Field::SymTensor`].
///
/// # Errors
/// As [`write_vtu`].
///
/// # Examples
/// ```
/// use fem_core::ElementKind;
/// use fem_core::solid::generate::{box_mesh, lines};
/// use fem_core::vtk::{write_vtu_3d, Field3};
/// let l = lines(0.0, 1.0, 1);
/// let mesh = box_mesh(&l, &l, &l, ElementKind::Tet10)?;
/// let u: Vec<[f64; 3]> = mesh.nodes().iter().map(|p| [0.1 * p[2], 0.0, 0.0]).collect();
/// let path = std::env::temp_dir().join("fem_core_vtk_doc_3d.vtu");
/// write_vtu_3d(&path, &mesh, &[("u", Field3::Vector(&u))], &[])?;
/// # Ok::<(), fem_core::FemError>(())
/// ```
pub fn write_vtu_3d(
    path: &Path,
    mesh: &SolidMesh,
    point_data: &[(&str, Field3<'_>)],
    cell_data: &[(&str, Field3<'_>)],
) -> Result<(), FemError> {
    write_vtu(path, mesh, point_data, cell_data)
}

fn write_model(path: &Path, vtk: Vtk) -> Result<(), FemError> {
    let origin = path.display().to_string();
    let file = std::fs::File::create(path)
        .map_err(|e| FemError::io(origin.clone(), "cannot create the file", e))?;
    let mut writer = std::io::BufWriter::new(file);
    vtk.write_xml(&mut writer)
        .map_err(|e| FemError::io(origin.clone(), "cannot write the VTK XML", e))?;
    writer
        .flush()
        .map_err(|e| FemError::io(origin, "cannot write the file", e))
}

/// Checks that every point field has one entry per node and every cell field one per element.
fn check_lengths(
    point_lengths: &[usize],
    cell_lengths: &[usize],
    node_count: usize,
    element_count: usize,
) -> Result<(), FemError> {
    for (lengths, expected, what) in [
        (
            point_lengths,
            node_count,
            "point field (one value per node)",
        ),
        (
            cell_lengths,
            element_count,
            "cell field (one value per element)",
        ),
    ] {
        if let Some(&got) = lengths.iter().find(|&&n| n != expected) {
            return Err(FemError::LengthMismatch {
                what,
                expected,
                got,
            });
        }
    }
    Ok(())
}

fn model<const D: usize>(
    mesh: &Mesh<D>,
    point_data: &[(&str, Field<'_, D>)],
    cell_data: &[(&str, Field<'_, D>)],
) -> Result<Vtk, FemError>
where
    Dim<D>: Space,
{
    check_lengths(
        &point_data.iter().map(|(_, f)| f.len()).collect::<Vec<_>>(),
        &cell_data.iter().map(|(_, f)| f.len()).collect::<Vec<_>>(),
        mesh.node_count(),
        mesh.element_count(),
    )?;
    let points: Vec<f64> = mesh.nodes().iter().flat_map(xyz).collect();
    let element = mesh.built_in_element();
    let cell_type = match element.topology().vtk_cell {
        5 => CellType::Triangle,
        22 => CellType::QuadraticTriangle,
        9 => CellType::Quad,
        23 => CellType::QuadraticQuad,
        28 => CellType::BiquadraticQuad,
        10 => CellType::Tetra,
        24 => CellType::QuadraticTetra,
        12 => CellType::Hexahedron,
        _ => CellType::QuadraticHexahedron, // 25, the last built-in kind (they are sealed)
    };
    let mut data = Attributes::new();
    data.point = point_data.iter().map(|(n, f)| f.attribute(n)).collect();
    data.cell = cell_data.iter().map(|(n, f)| f.attribute(n)).collect();
    let cells = (mesh.connectivity(), element.node_count(), cell_type);
    Ok(grid(points, cells, mesh.regions(), data))
}

/// One unstructured-grid piece: flat points `(x, y, z)`, cells (flat connectivity, nodes per
/// cell, type), the regions (as the cell array `region` unless `data` has one) and `data`.
fn grid(
    points: Vec<f64>,
    (connectivity, npe, cell_type): (&[usize], usize, CellType),
    regions: &[u32],
    mut data: Attributes,
) -> Vtk {
    let element_count = connectivity.len() / npe;
    let cells = Cells {
        cell_verts: VertexNumbers::XML {
            connectivity: connectivity.iter().map(|&n| n as u64).collect(),
            offsets: (1..=element_count).map(|e| (e * npe) as u64).collect(),
        },
        types: vec![cell_type; element_count],
    };
    let has_region = data.cell.iter().any(|a| match a {
        Attribute::DataArray(d) => d.name == "region",
        Attribute::Field { name, .. } => name == "region",
    });
    if !has_region {
        data.cell
            .push(Attribute::scalars("region", 1).with_data(regions.to_vec()));
    }
    Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: points.into(),
            cells,
            data,
        }),
    }
}

/// Writes a ParaView collection (`.pvd`) of time steps: each entry is a time and the path of
/// its `.vtu` file, relative to the `.pvd` file.
///
/// # Errors
/// - [`FemError::InvalidParameter`] for a non-finite time;
/// - [`FemError::Io`] if the file cannot be written.
///
/// # Examples
/// ```
/// use fem_core::vtk::write_pvd;
/// let path = std::env::temp_dir().join("fem_core_vtk_doc.pvd");
/// write_pvd(&path, &[(0.0, "step_0.vtu"), (0.5, "step_1.vtu")]).unwrap();
/// ```
pub fn write_pvd(path: &Path, entries: &[(f64, &str)]) -> Result<(), FemError> {
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n\
         <VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  \
         <Collection>\n",
    );
    for &(time, file) in entries {
        if !time.is_finite() {
            return Err(FemError::InvalidParameter {
                name: "time",
                value: time,
                expected: "a finite time",
            });
        }
        xml.push_str(&format!(
            "    <DataSet timestep=\"{time}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
            escape(file)
        ));
    }
    xml.push_str("  </Collection>\n</VTKFile>\n");
    std::fs::write(path, xml)
        .map_err(|e| FemError::io(path.display().to_string(), "cannot write the file", e))
}

/// Escapes a string for an XML attribute value.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::ElementKind;

    #[test]
    fn escape_works() {
        assert_eq!(
            escape("a&b<c>\"d'.vtu"),
            "a&amp;b&lt;c&gt;&quot;d&apos;.vtu"
        );
    }

    #[test]
    fn model_rejects_length_mismatch() {
        let mesh = Mesh::new(
            vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            ElementKind::Tri3,
            vec![0, 1, 2],
            vec![],
        )
        .unwrap();
        let short = [1.0, 2.0];
        assert!(matches!(
            model(&mesh, &[("s", Field::Scalar(&short))], &[]),
            Err(FemError::LengthMismatch {
                expected: 3,
                got: 2,
                ..
            })
        ));
        assert!(matches!(
            model(&mesh, &[], &[("s", Field::Scalar(&short))]),
            Err(FemError::LengthMismatch {
                expected: 1,
                got: 2,
                ..
            })
        ));
        assert!(model(&mesh, &[], &[("s", Field::Scalar(&[7.0]))]).is_ok());
    }
}
