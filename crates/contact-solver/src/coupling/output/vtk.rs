//! The interface of a step as a VTK point cloud ([`write_interface_vtu`] in 2D,
//! [`write_interface_vtu_3d`] in 3D, whose columns differ: the 3D file also carries the force
//! and the frame) and a time series of them ([`InterfaceSeries`]).

use crate::coupling::simulation::{ContactRecord, InterfaceStatus};
use crate::error::{Cause, SolverError};
use std::io::Write;
use std::path::{Path, PathBuf};
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, UnstructuredGridPiece, Version,
    VertexNumbers, Vtk,
};

/// The integer code of a status in the VTK output: 0 inactive, 1 open, 2 stick, 3 slip,
/// 4 closed (frictionless).
///
/// # Examples
/// ```
/// use contact_solver::InterfaceStatus;
/// use contact_solver::coupling::output::status_code;
/// assert_eq!(status_code(InterfaceStatus::Inactive), 0);
/// assert_eq!(status_code(InterfaceStatus::Slip), 3);
/// ```
pub fn status_code(status: InterfaceStatus) -> u8 {
    match status {
        InterfaceStatus::Inactive => 0,
        InterfaceStatus::Open => 1,
        InterfaceStatus::Stick => 2,
        InterfaceStatus::Slip => 3,
        InterfaceStatus::Closed => 4,
    }
}

/// Writes the contact candidates of one step as a VTK XML unstructured grid (`.vtu`): one
/// point and one `VTK_VERTEX` cell per record, in the order of `records`.
///
/// Points are at the reference `position` of each record, plus the displacement of its node
/// when `displacements` is given — nodal displacements indexed by
/// [`ContactRecord::node`], as [`ContactSimulation::nodal_displacements`](crate::ContactSimulation::nodal_displacements)
/// returns them. Point data (every float array `Float64`):
///
/// | name | type | content |
/// |---|---|---|
/// | `status` | `UInt8` | [`status_code`]: 0 inactive, 1 open, 2 stick, 3 slip, 4 closed |
/// | `zone`, `node` | `UInt64` | zone index, contactor node |
/// | `area`, `gap`, `u_t`, `slip_increment`, `beta` | scalar | as in [`ContactRecord`] |
/// | `r_local`, `r_bar_local`, `r_adh_local` | vector | local `[n, t, 0]` of `r`, `r̄`, `r_adh` |
/// | `u` | vector | `[u_x, u_y, 0]` of the node (only with `displacements`) |
///
/// # Errors
/// - [`SolverError::SizeMismatch`] if a record's node has no entry in `displacements`;
/// - [`SolverError::Io`] if the file cannot be written.
///
/// # Examples
/// ```
/// use contact_solver::coupling::output::write_interface_vtu;
/// use contact_solver::{ContactRecord, InterfaceStatus};
/// let mut c: ContactRecord = ContactRecord::default();
/// (c.node, c.position, c.area, c.status) = (1, [0.5, 0.0], 0.25, InterfaceStatus::Open);
/// (c.gap, c.normal, c.tangent) = (1e-3, [0.0, 1.0], [1.0, 0.0]);
/// let u = [[0.0, 0.0], [1e-4, -2e-4]];
/// let path = std::env::temp_dir().join("contact_solver_output_doc.vtu");
/// write_interface_vtu(&path, &[c], Some(&u))?;
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
pub fn write_interface_vtu(
    path: &Path,
    records: &[ContactRecord],
    displacements: Option<&[[f64; 2]]>,
) -> Result<(), SolverError> {
    write_vtk(path, interface_model(records, displacements)?)
}

/// Writes a VTK model as XML to `path`.
pub(crate) fn write_vtk(path: &Path, vtk: Vtk) -> Result<(), SolverError> {
    let io = |source: Cause| SolverError::Io {
        what: format!("cannot write `{}`", path.display()),
        source,
    };
    let file = std::fs::File::create(path).map_err(|e| io(Cause::new(e)))?;
    let mut writer = std::io::BufWriter::new(file);
    vtk.write_xml(&mut writer).map_err(|e| io(Cause::new(e)))?;
    writer.flush().map_err(|e| io(Cause::new(e)))
}

/// An unstructured grid of one vertex per point (`points`: x, y, z of each) with point data.
pub(crate) fn vertex_cloud(points: Vec<f64>, data: Attributes) -> Vtk {
    let n = points.len() / 3;
    Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: points.into(),
            cells: Cells {
                cell_verts: VertexNumbers::XML {
                    connectivity: (0..n as u64).collect(),
                    offsets: (1..=n as u64).collect(),
                },
                types: vec![CellType::Vertex; n],
            },
            data,
        }),
    }
}

/// The VTK model of [`write_interface_vtu`].
pub(crate) fn interface_model(
    records: &[ContactRecord],
    displacements: Option<&[[f64; 2]]>,
) -> Result<Vtk, SolverError> {
    if let (Some(u), Some(max_node)) = (displacements, records.iter().map(|c| c.node).max())
        && max_node >= u.len()
    {
        return Err(SolverError::SizeMismatch {
            what: "displacements",
            expected: max_node + 1,
            found: u.len(),
        });
    }
    let points: Vec<f64> = records
        .iter()
        .flat_map(|c| {
            let [ux, uy] = displacements.map_or([0.0, 0.0], |u| u[c.node]);
            [c.position[0] + ux, c.position[1] + uy, 0.0]
        })
        .collect();
    let scalar = |name: &str, f: fn(&ContactRecord) -> f64| {
        Attribute::scalars(name, 1).with_data(records.iter().map(f).collect::<Vec<f64>>())
    };
    let local = |name: &str, f: fn(&ContactRecord) -> [f64; 2]| {
        Attribute::vectors(name).with_data(
            records
                .iter()
                .flat_map(|c| {
                    let [a, b] = f(c);
                    [a, b, 0.0]
                })
                .collect::<Vec<f64>>(),
        )
    };
    let mut data = Attributes::new();
    data.point = vec![
        Attribute::scalars("status", 1).with_data(
            records
                .iter()
                .map(|c| status_code(c.status))
                .collect::<Vec<u8>>(),
        ),
        Attribute::scalars("zone", 1)
            .with_data(records.iter().map(|c| c.zone as u64).collect::<Vec<u64>>()),
        Attribute::scalars("node", 1)
            .with_data(records.iter().map(|c| c.node as u64).collect::<Vec<u64>>()),
        scalar("area", |c| c.area),
        scalar("gap", |c| c.gap),
        scalar("u_t", |c| c.u_t),
        scalar("slip_increment", |c| c.slip_increment),
        scalar("beta", |c| c.beta),
        local("r_local", |c| [c.r.n, c.r.t[0]]),
        local("r_bar_local", |c| [c.r_bar.n, c.r_bar.t[0]]),
        local("r_adh_local", |c| [c.r_adh.n, c.r_adh.t[0]]),
    ];
    if let Some(u) = displacements {
        data.point.push(
            Attribute::vectors("u").with_data(
                records
                    .iter()
                    .flat_map(|c| [u[c.node][0], u[c.node][1], 0.0])
                    .collect::<Vec<f64>>(),
            ),
        );
    }
    Ok(vertex_cloud(points, data))
}

/// Writes the contact records of a 3D step as a VTK unstructured grid of vertices (`.vtu`,
/// ASCII XML). `positions[n]` is node `n`'s position, `displacements[n]` its displacement (the
/// points are then at the deformed positions, and `u` is written).
///
/// Point data:
///
/// | name | type | content |
/// |---|---|---|
/// | `active` | `UInt8` | 1 if the contact is closed ([`ContactRecord::is_closed`], as the CSV outputs) |
/// | `zone`, `node` | `UInt64` | zone index, contactor node |
/// | `area`, `gap`, `pressure`, `beta` | scalar | as in [`ContactRecord`] |
/// | `r_local` | vector | `[r_n, r_t1, r_t2]` |
/// | `slip` | vector | `[slip_t1, slip_t2, 0]`, the step's slip increment |
/// | `force` | vector | the contact force on the contactor node, global axes |
/// | `candidate` | `UInt8` | 1 if the contact was in the step's reduced problem |
/// | `normal`, `t1`, `t2` | vector | the contact's frame |
/// | `u` | vector | the node's displacement (only with `displacements`) |
///
/// # Errors
/// - [`SolverError::SizeMismatch`] if a record's node has no entry in `positions` or
///   `displacements`;
/// - [`SolverError::Io`] if the file cannot be written.
pub fn write_interface_vtu_3d(
    path: &Path,
    records: &[ContactRecord<3>],
    positions: &[[f64; 3]],
    displacements: Option<&[[f64; 3]]>,
) -> Result<(), SolverError> {
    write_vtk(path, interface_model_3d(records, positions, displacements)?)
}

/// The VTK model of [`write_interface_vtu_3d`].
pub(crate) fn interface_model_3d(
    records: &[ContactRecord<3>],
    positions: &[[f64; 3]],
    displacements: Option<&[[f64; 3]]>,
) -> Result<Vtk, SolverError> {
    let max_node = records.iter().map(|c| c.node).max();
    for (what, len) in [
        ("positions", Some(positions.len())),
        ("displacements", displacements.map(<[_]>::len)),
    ] {
        if let (Some(len), Some(max_node)) = (len, max_node)
            && max_node >= len
        {
            return Err(SolverError::SizeMismatch {
                what,
                expected: max_node + 1,
                found: len,
            });
        }
    }
    let u = |node: usize| displacements.map_or([0.0; 3], |u| u[node]);
    let points: Vec<f64> = records
        .iter()
        .flat_map(|c| {
            let (x, d) = (positions[c.node], u(c.node));
            [x[0] + d[0], x[1] + d[1], x[2] + d[2]]
        })
        .collect();
    let scalar = |name: &str, f: &dyn Fn(&ContactRecord<3>) -> f64| {
        Attribute::scalars(name, 1).with_data(records.iter().map(f).collect::<Vec<f64>>())
    };
    let vector = |name: &str, f: &dyn Fn(&ContactRecord<3>) -> [f64; 3]| {
        Attribute::vectors(name).with_data(records.iter().flat_map(f).collect::<Vec<f64>>())
    };
    let flag = |name: &str, f: fn(&ContactRecord<3>) -> bool| {
        Attribute::scalars(name, 1)
            .with_data(records.iter().map(|c| u8::from(f(c))).collect::<Vec<u8>>())
    };
    let mut data = Attributes::new();
    data.point = vec![
        flag("active", ContactRecord::is_closed),
        Attribute::scalars("zone", 1)
            .with_data(records.iter().map(|c| c.zone as u64).collect::<Vec<u64>>()),
        Attribute::scalars("node", 1)
            .with_data(records.iter().map(|c| c.node as u64).collect::<Vec<u64>>()),
        scalar("area", &|c| c.area),
        scalar("gap", &|c| c.gap),
        scalar("pressure", &|c| c.pressure()),
        scalar("beta", &|c| c.beta),
        vector("r_local", &|c| c.reaction()),
        vector("slip", &|c| [c.slip_increment[0], c.slip_increment[1], 0.0]),
        vector("force", &|c| c.force()),
        flag("candidate", ContactRecord::is_active),
        vector("normal", &|c| c.normal),
        vector("t1", &|c| c.tangent[0]),
        vector("t2", &|c| c.tangent[1]),
    ];
    if displacements.is_some() {
        data.point.push(vector("u", &|c| u(c.node)));
    }
    Ok(vertex_cloud(points, data))
}

/// A time series of interface files for ParaView: `<stem>_<k>.vtu` (k = 0, 1, … on 4 digits)
/// in a directory, and `<stem>.pvd` listing them with their times, rewritten after every step
/// so that a run stopped half-way can still be opened.
///
/// # Examples
/// ```
/// use contact_solver::coupling::output::InterfaceSeries;
/// let dir = std::env::temp_dir().join("contact_solver_series_doc");
/// std::fs::create_dir_all(&dir).unwrap();
/// let mut series = InterfaceSeries::new(&dir, "interface");
/// let vtu = series.write_step(0.5, &[], None)?;
/// assert!(vtu.ends_with("interface_0000.vtu"));
/// assert!(series.pvd_path().exists());
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
#[derive(Clone, Debug)]
pub struct InterfaceSeries {
    dir: PathBuf,
    stem: String,
    entries: Vec<(f64, String)>,
}

impl InterfaceSeries {
    /// A series of files `<stem>_<k>.vtu` and `<stem>.pvd` in the existing directory `dir`.
    /// Nothing is written until [`InterfaceSeries::write_step`].
    ///
    /// # Examples
    /// ```
    /// use contact_solver::coupling::output::InterfaceSeries;
    /// let series = InterfaceSeries::new(std::env::temp_dir(), "contacts");
    /// assert!(series.pvd_path().ends_with("contacts.pvd"));
    /// ```
    pub fn new(dir: impl Into<PathBuf>, stem: impl Into<String>) -> Self {
        Self {
            dir: dir.into(),
            stem: stem.into(),
            entries: Vec::new(),
        }
    }

    /// The path of the `.pvd` collection.
    ///
    /// # Examples
    /// See [`InterfaceSeries::new`].
    /// ```
    /// # use contact_solver::coupling::output::InterfaceSeries;
    /// let series = InterfaceSeries::new("out", "contacts");
    /// assert_eq!(series.pvd_path(), std::path::Path::new("out/contacts.pvd"));
    /// ```
    pub fn pvd_path(&self) -> PathBuf {
        self.dir.join(format!("{}.pvd", self.stem))
    }

    /// Writes the records of one step at `time` with [`write_interface_vtu`], then rewrites
    /// the `.pvd` collection; returns the path of the `.vtu` file.
    ///
    /// # Errors
    /// - [`SolverError::NonFinite`] if `time` is NaN or infinite (nothing is written);
    /// - the errors of [`write_interface_vtu`];
    /// - [`SolverError::Io`] if the `.pvd` file cannot be written.
    ///
    /// # Examples
    /// See [`InterfaceSeries`].
    /// ```
    /// # use contact_solver::coupling::output::InterfaceSeries;
    /// # use contact_solver::SolverError;
    /// let mut series = InterfaceSeries::new(std::env::temp_dir(), "contacts_doc");
    /// assert!(matches!(series.write_step(f64::NAN, &[], None), Err(SolverError::NonFinite { .. })));
    /// ```
    pub fn write_step(
        &mut self,
        time: f64,
        records: &[ContactRecord],
        displacements: Option<&[[f64; 2]]>,
    ) -> Result<PathBuf, SolverError> {
        self.write_step_with(time, |path| {
            write_interface_vtu(path, records, displacements)
        })
    }

    /// Writes the next file of the series at `time` with `write` (given its path, e.g.
    /// [`write_interface_vtu_3d`] for a 3D step), then rewrites the `.pvd` collection; returns the path of the `.vtu` file.
    ///
    /// # Errors
    /// As [`InterfaceSeries::write_step`], with `write`'s errors.
    pub fn write_step_with(
        &mut self,
        time: f64,
        write: impl FnOnce(&Path) -> Result<(), SolverError>,
    ) -> Result<PathBuf, SolverError> {
        if !time.is_finite() {
            return Err(SolverError::NonFinite {
                what: "time",
                index: self.entries.len(),
                value: time,
            });
        }
        let file = format!("{}_{:04}.vtu", self.stem, self.entries.len());
        let path = self.dir.join(&file);
        write(&path)?;
        self.entries.push((time, file));
        let entries: Vec<(f64, &str)> =
            self.entries.iter().map(|(t, f)| (*t, f.as_str())).collect();
        let pvd = self.pvd_path();
        fem_core::vtk::write_pvd(&pvd, &entries).map_err(|e| match e {
            fem_core::FemError::Io {
                path,
                detail,
                source,
            } => SolverError::Io {
                what: format!("cannot write `{path}`"),
                source: source.map_or_else(|| Cause::message(detail), Cause::new),
            },
            other => SolverError::Structure(other),
        })?;
        Ok(path)
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::record;
    use super::*;

    #[test]
    fn interface_model_rejects_short_displacements() {
        let records = [
            record(0, InterfaceStatus::Open),
            record(3, InterfaceStatus::Stick),
        ];
        let u = [[0.0; 2]; 3];
        assert_eq!(
            interface_model(&records, Some(&u)).unwrap_err(),
            SolverError::SizeMismatch {
                what: "displacements",
                expected: 4,
                found: 3
            }
        );
        assert!(interface_model(&records, Some(&[[0.0; 2]; 4])).is_ok());
        assert!(interface_model(&records, None).is_ok());
    }

    #[test]
    fn status_code_works() {
        let codes = [
            InterfaceStatus::Inactive,
            InterfaceStatus::Open,
            InterfaceStatus::Stick,
            InterfaceStatus::Slip,
            InterfaceStatus::Closed,
        ]
        .map(status_code);
        assert_eq!(codes, [0, 1, 2, 3, 4]);
    }
}
