//! Output of the interface: CSV histories over the steps and VTK files for ParaView.
//!
//! - [`HistoryWriter`] writes one CSV row per (step, contact candidate), columns
//!   [`CONTACT_COLUMNS`]; [`ReportWriter`] one CSV row per step of the [`StepReport`]
//!   counters, columns [`REPORT_COLUMNS`]. Both write to any [`std::io::Write`].
//! - [`write_interface_vtu`] (2D) and [`write_interface_vtu_3d`] write the candidates of one
//!   step as a point cloud (one `VTK_VERTEX` cell per candidate) in a VTK XML unstructured
//!   grid (`.vtu`), through [`vtkio`]; [`InterfaceSeries`] writes one `.vtu` per step and keeps a `.pvd` collection
//!   of them up to date.
//!
//! Reactions are written in the local frame of each contact, `[n, t]` (the global components
//! are not known to a [`ContactRecord`]); signs are those of
//! [`contact_laws`](contact_laws#sign-conventions): `r_n ≥ 0` is compression, `gap ≥ 0` an
//! opening.
//!
//! Floats are written as the shortest text that parses back to the same number, so a history
//! read back with `str::parse::<f64>` is bit-exact. Each step is one `write_all`; wrap a file in
//! a [`std::io::BufWriter`] all the same when a step has few contacts.

use crate::coupling::simulation::{ContactRecord, StepReport, StepResult};
use crate::error::{Cause, SolverError};
use std::fmt::Write as _;
use std::io::Write;

mod vtk;

pub use vtk::{InterfaceSeries, status_code, write_interface_vtu, write_interface_vtu_3d};
pub(crate) use vtk::{interface_model, interface_model_3d, write_vtk};

/// Columns of [`HistoryWriter`], in order. `x, y` is the reference position of the contactor
/// node, `status` its [`InterfaceStatus::name`](crate::InterfaceStatus::name), `r_*_n, r_*_t`
/// the local components of `r`, `r̄` and `r_adh`, and `area` the tributary area
/// ([`ContactRecord::area`]); then, appended so that the other columns keep their places, the
/// total reaction in global axes `f_x, f_y` ([`ContactRecord::force`]) and the contact's frame,
/// its normal `n_x, n_y` and tangent `t_x, t_y`. [`HistoryWriter::with_axes`] renames the axes
/// (`r, z` in axisymmetry: `r, z, f_r, f_z, n_r, n_z, t_r, t_z`).
pub const CONTACT_COLUMNS: [&str; 25] = [
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
    "f_x",
    "f_y",
    "n_x",
    "n_y",
    "t_x",
    "t_y",
];

/// Columns of [`ReportWriter`], in order. `active_contacts` counts the contacts closed at the
/// end of the step ([`StepReport::closed_contacts`]), `candidates` (appended) those of the
/// reduced problem, within the alert distance ([`StepReport::active_contacts`]). The flags
/// `flexibility_rebuilt`, `converged`, `matrix_free` and `active_set` are written `0` / `1` (so
/// every column is numeric), `wall_time_s` in seconds.
pub const REPORT_COLUMNS: [&str; 14] = [
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
    "candidates",
];

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
/// let mut c: ContactRecord = ContactRecord::default();
/// (c.node, c.position, c.area, c.status) = (7, [0.5, 0.0], 0.25, InterfaceStatus::Stick);
/// (c.u_t, c.beta, c.normal, c.tangent) = (1e-3, 1.0, [0.0, 1.0], [1.0, 0.0]);
/// (c.r, c.r_bar) = (LocalVec2::planar(2.0, -0.1), LocalVec2::planar(2.0, -0.1));
/// let mut history = HistoryWriter::new(Vec::new())?;
/// history.write_contacts(1, 0.5, 1.0, &[c])?;
/// let text = String::from_utf8(history.finish()?).unwrap();
/// assert_eq!(
///     text.lines().nth(1),
///     Some("1,0.5,1,0,7,0.5,0,stick,0,0.001,0,1,2,-0.1,2,-0.1,0,0,0.25,-0.1,2,0,1,1,0")
/// );
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
#[derive(Debug)]
pub struct HistoryWriter<W: Write>(Csv<W>);

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
        Self::with_axes(out, ["x", "y"])
    }

    /// Starts a history on `out` whose axis columns are named `axes` rather than `x, y`
    /// (`["r", "z"]` in axisymmetry): `x, y`, `f_x, f_y`, `n_x, n_y` and `t_x, t_y` become
    /// `r, z`, `f_r, f_z`, `n_r, n_z` and `t_r, t_z`; the rows are the same.
    ///
    /// # Errors
    /// [`SolverError::Io`] if `out` fails.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::coupling::output::HistoryWriter;
    /// let text = HistoryWriter::with_axes(Vec::new(), ["r", "z"])?.finish()?;
    /// let head = String::from_utf8(text).unwrap();
    /// assert!(head.starts_with("step,time,load_factor,zone,node,r,z,status,"));
    /// assert!(head.trim_end().ends_with(",area,f_r,f_z,n_r,n_z,t_r,t_z"));
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn with_axes(out: W, axes: [&str; 2]) -> Result<Self, SolverError> {
        let head: Vec<String> = CONTACT_COLUMNS
            .iter()
            .map(|&c| match c {
                "x" => axes[0].to_string(),
                "y" => axes[1].to_string(),
                "f_x" | "n_x" | "t_x" => format!("{}{}", &c[..2], axes[0]),
                "f_y" | "n_y" | "t_y" => format!("{}{}", &c[..2], axes[1]),
                _ => c.to_string(),
            })
            .collect();
        Csv::new(out, "contact history", &head.join(",")).map(Self)
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
            let line = &mut self.0.line;
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
            for x in c.force().into_iter().chain(c.normal).chain(c.tangent) {
                push_float(line, x);
            }
            line.push('\n');
        }
        self.0.flush_line()
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
    pub fn finish(self) -> Result<W, SolverError> {
        self.0.finish()
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
/// // step 1 at t = 0.5, load factor 1, 3 closed contacts, no adhesion iteration, …
/// assert!(text.lines().nth(1).unwrap().starts_with("1,0.5,1,3,0,"));
/// # Ok::<(), contact_solver::SolverError>(())
/// ```
#[derive(Debug)]
pub struct ReportWriter<W: Write>(Csv<W>);

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
        Csv::new(out, "step log", &REPORT_COLUMNS.join(",")).map(Self)
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
        let line = &mut self.0.line;
        let _ = write!(line, "{}", r.step);
        push_float(line, r.time);
        push_float(line, r.load_factor);
        let _ = write!(
            line,
            ",{},{},{},{},{}",
            r.closed_contacts,
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
            ",{},{},{}",
            u8::from(r.matrix_free),
            u8::from(r.active_set),
            r.active_contacts
        );
        line.push('\n');
        self.0.flush_line()
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
    pub fn finish(self) -> Result<W, SolverError> {
        self.0.finish()
    }
}

/// A CSV sink: rows are built in `line`, reused across steps, and handed to `out` in one
/// `write_all`; `what` names it in I/O errors.
#[derive(Debug)]
struct Csv<W: Write> {
    out: W,
    line: String,
    what: &'static str,
}

impl<W: Write> Csv<W> {
    /// Starts on `out` and writes the header line `head`.
    fn new(out: W, what: &'static str, head: &str) -> Result<Self, SolverError> {
        let line = format!("{head}\n");
        let mut csv = Self { out, line, what };
        csv.flush_line()?;
        Ok(csv)
    }

    /// Writes the buffered rows and clears the buffer.
    fn flush_line(&mut self) -> Result<(), SolverError> {
        let res = self.out.write_all(self.line.as_bytes());
        self.line.clear();
        res.map_err(|e| self.io_error(e))
    }

    fn finish(mut self) -> Result<W, SolverError> {
        self.out.flush().map_err(|e| self.io_error(e))?;
        Ok(self.out)
    }

    fn io_error(&self, e: std::io::Error) -> SolverError {
        SolverError::Io {
            what: format!("cannot write the {}", self.what),
            source: Cause::new(e),
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coupling::simulation::InterfaceStatus;
    use contact_laws::LocalVec2;

    pub(super) fn record(node: usize, status: InterfaceStatus) -> ContactRecord {
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
            normal: [0.0, 1.0],
            tangent: [1.0, 0.0],
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
}
