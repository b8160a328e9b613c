//! Output of the interface: CSV histories over the steps and VTK files for ParaView.
//!
//! - [`HistoryWriter`] writes one CSV row per (step, contact candidate), columns
//!   [`CONTACT_COLUMNS`]; [`ReportWriter`] one CSV row per step of the [`StepReport`]
//!   counters, columns [`REPORT_COLUMNS`]. Both write to any [`std::io::Write`].
//! - [`write_interface_vtu`] writes the candidates of one step as a point cloud (one
//!   `VTK_VERTEX` cell per candidate) in a VTK XML unstructured grid (`.vtu`), through
//!   [`vtkio`]; [`InterfaceSeries`] writes one `.vtu` per step and keeps a `.pvd` collection
//!   of them up to date.
//!
//! Reactions are written in the local frame of each contact, `[n, t]` (the global components
//! are not known to a [`ContactRecord`]); signs are those of
//! [`contact_laws`](contact_laws#sign-conventions): `r_n ≥ 0` is compression, `gap ≥ 0` an
//! opening.
//!
//! Floats are written with Rust's `Display` for `f64`, the shortest text that parses back to
//! the same number, so a history read back with `str::parse::<f64>` is bit-exact (`NaN` and
//! `inf` are written as such). Rows are built in a buffer reused across steps and handed to the
//! writer with one `write_all` per step; wrap a file in a [`std::io::BufWriter`] all the same
//! when a step has few contacts.

use crate::coupling::simulation::{ContactRecord, InterfaceStatus, StepReport, StepResult};
use crate::error::{Cause, SolverError};
use std::fmt::Write as _;
use std::io::Write;
use std::path::{Path, PathBuf};
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, UnstructuredGridPiece, Version,
    VertexNumbers, Vtk,
};

/// Columns of [`HistoryWriter`], in order. `x, y` is the reference position of the contactor
/// node, `status` its [`InterfaceStatus::name`], `r_*_n, r_*_t` the local components of
/// `r`, `r̄` and `r_adh`, and `area` the tributary area ([`ContactRecord::area`], last so that
/// the other columns keep their places).
pub const CONTACT_COLUMNS: [&str; 19] = [
    "step",
    "time",
    "load_factor",
    "zone",
    "node",
    "x",
    "y",
    "status",
    "gap",
    "u_t",
    "slip_increment",
    "beta",
    "r_n",
    "r_t",
    "r_bar_n",
    "r_bar_t",
    "r_adh_n",
    "r_adh_t",
    "area",
];

/// Columns of [`ReportWriter`], in order. The flags `flexibility_rebuilt`, `converged`,
/// `matrix_free` and `active_set` are written `0` / `1` (so every column is numeric),
/// `wall_time_s` in seconds.
pub const REPORT_COLUMNS: [&str; 13] = [
    "step",
    "time",
    "load_factor",
    "active_contacts",
    "adhesion_iterations",
    "contact_iterations",
    "detection_passes",
    "flexibility_rebuilt",
    "residual",
    "converged",
    "wall_time_s",
    "matrix_free",
    "active_set",
];

/// The integer code of a status in the VTK output: 0 inactive, 1 open, 2 stick, 3 slip.
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
    }
}

/// CSV history of the interface: one row per (step, contact candidate), columns
/// [`CONTACT_COLUMNS`].
///
/// The header is written by [`HistoryWriter::new`]. Call [`HistoryWriter::write_step`] after
/// each [`ContactSimulation::step`](crate::ContactSimulation::step), then
/// [`HistoryWriter::finish`] to flush and get the writer back (dropping the writer does not
/// flush it).
///
/// # Examples
/// ```
/// use contact_solver::coupling::output::HistoryWriter;
/// use contact_solver::{ContactRecord, InterfaceStatus, contact_laws::LocalVec2};
/// let c = ContactRecord {
///     zone: 0, node: 7, position: [0.5, 0.0], area: 0.25, status: InterfaceStatus::Stick,
///     gap: 0.0, u_t: 1e-3, slip_increment: 0.0, beta: 1.0,
///     r: LocalVec2::planar(2.0, -0.1), r_bar: LocalVec2::planar(2.0, -0.1),
///     r_adh: LocalVec2::zeros(),
/// };
/// let mut history = HistoryWriter::new(Vec::new())?;
/// history.write_contacts(1, 0.5, 1.0, &[c])?;
/// let text = String::from_utf8(history.finish()?).unwrap();
/// assert_eq!(
///     text.lines().nth(1),
///     Some("1,0.5,1,0,7,0.5,0,stick,0,0.001,0,1,2,-0.1,2,-0.1,0,0,0.25")
/// );
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
#[derive(Debug)]
pub struct HistoryWriter<W: Write> {
    out: W,
    line: String,
}

impl<W: Write> HistoryWriter<W> {
    /// Starts a history on `out` and writes the header line.
    ///
    /// # Errors
    /// [`SolverError::Io`] if `out` fails.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::coupling::output::{CONTACT_COLUMNS, HistoryWriter};
    /// let text = HistoryWriter::new(Vec::new())?.finish()?;
    /// assert_eq!(String::from_utf8(text).unwrap().trim_end(), CONTACT_COLUMNS.join(","));
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn new(out: W) -> Result<Self, SolverError> {
        let mut w = Self {
            out,
            line: String::new(),
        };
        w.line.push_str(&CONTACT_COLUMNS.join(","));
        w.line.push('\n');
        w.flush_line()?;
        Ok(w)
    }

    /// Writes the rows of one step: one per entry of `result.contacts`, with the step number,
    /// time and load factor of `result.report`.
    ///
    /// # Errors
    /// [`SolverError::Io`] if the writer fails.
    ///
    /// # Examples
    /// See [`HistoryWriter`] and `tests/integration/output.rs` (a whole simulation).
    /// ```
    /// # use contact_solver::coupling::output::HistoryWriter;
    /// # fn log(sim_step: &contact_solver::StepResult) -> Result<(), contact_solver::SolverError> {
    /// let mut history = HistoryWriter::new(Vec::new())?;
    /// history.write_step(sim_step)?;
    /// # Ok(()) }
    /// ```
    pub fn write_step(&mut self, result: &StepResult) -> Result<(), SolverError> {
        let r = &result.report;
        self.write_contacts(r.step, r.time, r.load_factor, &result.contacts)
    }

    /// Writes one row per record of `contacts`, with the given step number, time and load
    /// factor (for records that do not come with a [`StepReport`]).
    ///
    /// # Errors
    /// [`SolverError::Io`] if the writer fails.
    ///
    /// # Examples
    /// See [`HistoryWriter`].
    /// ```
    /// # use contact_solver::coupling::output::HistoryWriter;
    /// let mut history = HistoryWriter::new(Vec::new())?;
    /// history.write_contacts(1, 1.0, 1.0, &[])?; // no candidates: no row
    /// assert_eq!(history.finish()?.iter().filter(|&&b| b == b'\n').count(), 1);
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn write_contacts(
        &mut self,
        step: usize,
        time: f64,
        load_factor: f64,
        contacts: &[ContactRecord],
    ) -> Result<(), SolverError> {
        for c in contacts {
            let line = &mut self.line;
            // Writing into a String cannot fail.
            let _ = write!(line, "{step}");
            push_float(line, time);
            push_float(line, load_factor);
            let _ = write!(line, ",{},{}", c.zone, c.node);
            push_float(line, c.position[0]);
            push_float(line, c.position[1]);
            line.push(',');
            line.push_str(c.status.name());
            for x in [c.gap, c.u_t, c.slip_increment, c.beta] {
                push_float(line, x);
            }
            for x in [c.r, c.r_bar, c.r_adh]
                .into_iter()
                .flat_map(|v| [v.n, v.t[0]])
            {
                push_float(line, x);
            }
            push_float(line, c.area);
            line.push('\n');
        }
        self.flush_line()
    }

    /// Flushes the writer and returns it.
    ///
    /// # Errors
    /// [`SolverError::Io`] if the flush fails.
    ///
    /// # Examples
    /// See [`HistoryWriter`].
    /// ```
    /// # use contact_solver::coupling::output::HistoryWriter;
    /// let bytes: Vec<u8> = HistoryWriter::new(Vec::new())?.finish()?;
    /// assert!(bytes.starts_with(b"step,time,load_factor,zone,node,"));
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn finish(mut self) -> Result<W, SolverError> {
        self.out
            .flush()
            .map_err(|e| io_error("contact history", e))?;
        Ok(self.out)
    }

    /// Writes the buffered rows and clears the buffer.
    fn flush_line(&mut self) -> Result<(), SolverError> {
        let res = self.out.write_all(self.line.as_bytes());
        self.line.clear();
        res.map_err(|e| io_error("contact history", e))
    }
}

/// CSV log of the steps: one row per [`StepReport`], columns [`REPORT_COLUMNS`].
///
/// The header is written by [`ReportWriter::new`]; [`ReportWriter::finish`] flushes and gives
/// the writer back.
///
/// # Examples
/// ```
/// use contact_solver::coupling::output::ReportWriter;
/// # use contact_solver::{ContactSimulation, ContactZone, RigidLine, SimulationSettings};
/// # use fem_core::{Component, Idealization, LinearElasticModel, Material, Supports};
/// # use fem_core::generate::{RectangleSpec, rectangle};
/// # let mesh = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 2, 2))?;
/// # let (top, bottom) = (mesh.node_set("top")?.to_vec(), mesh.node_set("bottom")?.to_vec());
/// # let mut supports = Supports::new();
/// # supports.prescribe(&top, Component::Y, -0.01)?.fix(&top, Component::X);
/// # let model = LinearElasticModel::new(mesh, Idealization::PlaneStrain,
/// #     &[(0, Material::new(100.0, 0.0, 0.0)?)], supports)?;
/// # let ground = RigidLine::new([-1.0, 0.0], [2.0, 0.0])?;
/// # let zone = ContactZone::rigid("base", bottom, ground, contact_laws::Signorini, 0.1);
/// # let mut sim = ContactSimulation::new(model, vec![zone], SimulationSettings::default())?;
/// let report = sim.step(0.5, 1.0)?.report; // a simulation's step (a block pressed on a LINE)
/// let mut log = ReportWriter::new(Vec::new())?;
/// log.write_report(&report)?;
/// let text = String::from_utf8(log.finish()?).unwrap();
/// // step 1 at t = 0.5, load factor 1, 3 active contacts, no adhesion iteration, …
/// assert!(text.lines().nth(1).unwrap().starts_with("1,0.5,1,3,0,"));
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
#[derive(Debug)]
pub struct ReportWriter<W: Write> {
    out: W,
    line: String,
}

impl<W: Write> ReportWriter<W> {
    /// Starts a log on `out` and writes the header line.
    ///
    /// # Errors
    /// [`SolverError::Io`] if `out` fails.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::coupling::output::{REPORT_COLUMNS, ReportWriter};
    /// let text = ReportWriter::new(Vec::new())?.finish()?;
    /// assert_eq!(String::from_utf8(text).unwrap().trim_end(), REPORT_COLUMNS.join(","));
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn new(out: W) -> Result<Self, SolverError> {
        let mut w = Self {
            out,
            line: String::new(),
        };
        w.line.push_str(&REPORT_COLUMNS.join(","));
        w.line.push('\n');
        w.flush_line()?;
        Ok(w)
    }

    /// Writes the row of one step.
    ///
    /// # Errors
    /// [`SolverError::Io`] if the writer fails.
    ///
    /// # Examples
    /// See [`ReportWriter`].
    /// ```
    /// # use contact_solver::coupling::output::ReportWriter;
    /// # fn log(result: &contact_solver::StepResult) -> Result<(), contact_solver::SolverError> {
    /// let mut log = ReportWriter::new(Vec::new())?;
    /// log.write_report(&result.report)?;
    /// # Ok(()) }
    /// ```
    pub fn write_report(&mut self, r: &StepReport) -> Result<(), SolverError> {
        let line = &mut self.line;
        let _ = write!(line, "{}", r.step);
        push_float(line, r.time);
        push_float(line, r.load_factor);
        let _ = write!(
            line,
            ",{},{},{},{},{}",
            r.active_contacts,
            r.adhesion_iterations,
            r.contact_iterations,
            r.detection_passes,
            u8::from(r.flexibility_rebuilt),
        );
        push_float(line, r.residual);
        let _ = write!(line, ",{}", u8::from(r.converged));
        push_float(line, r.wall_time.as_secs_f64());
        let _ = write!(
            line,
            ",{},{}",
            u8::from(r.matrix_free),
            u8::from(r.active_set)
        );
        line.push('\n');
        self.flush_line()
    }

    /// Flushes the writer and returns it.
    ///
    /// # Errors
    /// [`SolverError::Io`] if the flush fails.
    ///
    /// # Examples
    /// See [`ReportWriter`].
    /// ```
    /// # use contact_solver::coupling::output::ReportWriter;
    /// let bytes: Vec<u8> = ReportWriter::new(Vec::new())?.finish()?;
    /// assert!(bytes.starts_with(b"step,time,"));
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn finish(mut self) -> Result<W, SolverError> {
        self.out.flush().map_err(|e| io_error("step log", e))?;
        Ok(self.out)
    }

    fn flush_line(&mut self) -> Result<(), SolverError> {
        let res = self.out.write_all(self.line.as_bytes());
        self.line.clear();
        res.map_err(|e| io_error("step log", e))
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
/// | `status` | `UInt8` | [`status_code`]: 0 inactive, 1 open, 2 stick, 3 slip |
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
/// use contact_solver::{ContactRecord, InterfaceStatus, contact_laws::LocalVec2};
/// let c = ContactRecord {
///     zone: 0, node: 1, position: [0.5, 0.0], area: 0.25, status: InterfaceStatus::Open,
///     gap: 1e-3, u_t: 0.0, slip_increment: 0.0, beta: 0.0,
///     r: LocalVec2::zeros(), r_bar: LocalVec2::zeros(), r_adh: LocalVec2::zeros(),
/// };
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
    /// [`write_interface_vtu_3d`](crate::coupling::solid::write_interface_vtu_3d) for a 3D
    /// step), then rewrites the `.pvd` collection; returns the path of the `.vtu` file.
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

/// Appends `,x` with the shortest digits that parse back to `x`: plain decimals for
/// `1e-5 ≤ |x| < 1e16` and zero, scientific notation otherwise (Rust's `Display` would spell
/// out every zero of `1e-300`).
fn push_float(line: &mut String, x: f64) {
    let a = x.abs();
    let _ = if a == 0.0 || (1e-5..1e16).contains(&a) || !x.is_finite() {
        write!(line, ",{x}")
    } else {
        write!(line, ",{x:e}")
    };
}

/// An I/O error while writing `what`.
fn io_error(what: &str, e: std::io::Error) -> SolverError {
    SolverError::Io {
        what: format!("cannot write the {what}"),
        source: Cause::new(e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use contact_laws::LocalVec2;

    fn record(node: usize, status: InterfaceStatus) -> ContactRecord {
        ContactRecord {
            zone: 0,
            node,
            position: [node as f64, 0.0],
            area: 1.0,
            status,
            gap: 0.1 * node as f64,
            u_t: 0.0,
            slip_increment: 0.0,
            beta: 0.0,
            r: LocalVec2::planar(1.0, 0.0),
            r_bar: LocalVec2::planar(1.0, 0.0),
            r_adh: LocalVec2::zeros(),
        }
    }

    /// A writer that always fails.
    #[derive(Debug)]
    struct Broken;
    impl Write for Broken {
        fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
            Err(std::io::Error::other("disk full"))
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Err(std::io::Error::other("disk full"))
        }
    }

    #[test]
    fn writers_capture_errors() {
        let e = HistoryWriter::new(Broken).unwrap_err();
        assert_eq!(
            e,
            SolverError::Io {
                what: "cannot write the contact history".into(),
                source: Cause::message("disk full")
            }
        );
        assert!(matches!(
            ReportWriter::new(Broken),
            Err(SolverError::Io { .. })
        ));
    }

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
    fn push_float_round_trips_works() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -0.1,
            1.0 / 3.0,
            1e-5,
            9.999e-6,
            1e-300,
            5e-324,
            1e16,
            1.5e300,
            f64::MAX,
            f64::MIN_POSITIVE,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for x in values {
            let mut line = String::new();
            push_float(&mut line, x);
            let back: f64 = line[1..].parse().unwrap();
            assert_eq!(back.to_bits(), x.to_bits(), "{x} written {line}");
            assert!(line.len() < 30, "{line}");
        }
        let mut line = String::new();
        push_float(&mut line, f64::NAN);
        assert!(line[1..].parse::<f64>().unwrap().is_nan());
    }

    #[test]
    fn status_code_works() {
        let codes = [
            InterfaceStatus::Inactive,
            InterfaceStatus::Open,
            InterfaceStatus::Stick,
            InterfaceStatus::Slip,
        ]
        .map(status_code);
        assert_eq!(codes, [0, 1, 2, 3]);
    }
}
