//! Writing meshes and fields for ParaView: VTK XML unstructured grids (`.vtu`) through the
//! [`vtkio`] crate, and `.pvd` collections for time series.
//!
//! Points are written in 3D with `z = 0` (so `(r, z)` in axisymmetry appears as `(x, y)`).
//! P1 triangles are `VTK_TRIANGLE` (5), P2 triangles `VTK_QUADRATIC_TRIANGLE` (22), whose node
//! order is ours. Every array is `Float64`, base64-encoded inline; the element regions are
//! always written as the cell array `region` (`UInt32`).

use crate::error::FemError;
use crate::mesh::{ElementKind, Mesh};
use std::io::Write;
use std::path::Path;
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, UnstructuredGridPiece, Version,
    VertexNumbers, Vtk,
};

/// Values of one field, one entry per node (point data) or per element (cell data).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Field<'a> {
    /// A scalar.
    Scalar(&'a [f64]),
    /// An in-plane vector `(x, y)` (or `(r, z)`), written as a 3-vector with zero `z`.
    Vector(&'a [[f64; 2]]),
    /// A symmetric tensor `(xx, yy, xy, zz)` — the order of `element::Stress`, with `zz` the
    /// out-of-plane (or hoop) component — written as a full 3×3 tensor (9 components).
    SymTensor(&'a [[f64; 4]]),
}

impl Field<'_> {
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
            Field::Vector(v) => Attribute::vectors(name).with_data(
                v.iter()
                    .flat_map(|&[x, y]| [x, y, 0.0])
                    .collect::<Vec<f64>>(),
            ),
            Field::SymTensor(v) => Attribute::tensors(name).with_data(
                v.iter()
                    .flat_map(|&[xx, yy, xy, zz]| [xx, xy, 0.0, xy, yy, 0.0, 0.0, 0.0, zz])
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
pub fn write_vtu(
    path: &Path,
    mesh: &Mesh,
    point_data: &[(&str, Field<'_>)],
    cell_data: &[(&str, Field<'_>)],
) -> Result<(), FemError> {
    let vtk = model(mesh, point_data, cell_data)?;
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

fn model(
    mesh: &Mesh,
    point_data: &[(&str, Field<'_>)],
    cell_data: &[(&str, Field<'_>)],
) -> Result<Vtk, FemError> {
    for (fields, expected, what) in [
        (
            point_data,
            mesh.node_count(),
            "point field (one value per node)",
        ),
        (
            cell_data,
            mesh.element_count(),
            "cell field (one value per element)",
        ),
    ] {
        if let Some((_, f)) = fields.iter().find(|(_, f)| f.len() != expected) {
            return Err(FemError::LengthMismatch {
                what,
                expected,
                got: f.len(),
            });
        }
    }
    let points: Vec<f64> = mesh
        .nodes()
        .iter()
        .flat_map(|&[x, y]| [x, y, 0.0])
        .collect();
    let npe = mesh.kind().node_count();
    let cell_type = match mesh.kind() {
        ElementKind::Tri3 => CellType::Triangle,
        ElementKind::Tri6 => CellType::QuadraticTriangle,
    };
    let cells = Cells {
        cell_verts: VertexNumbers::XML {
            connectivity: mesh.connectivity().iter().map(|&n| n as u64).collect(),
            offsets: (1..=mesh.element_count())
                .map(|e| (e * npe) as u64)
                .collect(),
        },
        types: vec![cell_type; mesh.element_count()],
    };
    let mut data = Attributes::new();
    data.point = point_data.iter().map(|(n, f)| f.attribute(n)).collect();
    data.cell = cell_data.iter().map(|(n, f)| f.attribute(n)).collect();
    if !cell_data.iter().any(|(n, _)| *n == "region") {
        data.cell
            .push(Attribute::scalars("region", 1).with_data(mesh.regions().to_vec()));
    }
    Ok(Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: points.into(),
            cells,
            data,
        }),
    })
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
