//! Output of the interface (`contact_solver::coupling::output`): CSV histories read back bit-exactly and
//! `.vtu` files read back with vtkio.
//!
//! Scene (as `tests/integration/signorini_block.rs`): a 2 × 1 P1 block, plane strain, E = 200, ν =
//! 0.3, 8 × 4 cells, bottom 0.001 above a rigid LINE y = 0 (alert distance 0.5, so every bottom
//! node is a candidate in the reduced problem), left side fixed in x, top pushed down by
//! 0.0005 (step 1: still open) then 0.011 (step 2: pressed).

#![cfg(feature = "fe")]

use contact_laws::Signorini;
use contact_solver::coupling::output::{
    CONTACT_COLUMNS, HistoryWriter, InterfaceSeries, REPORT_COLUMNS, ReportWriter, status_code,
    write_interface_vtu,
};
use contact_solver::{
    ContactRecord, ContactSimulation, ContactZone, InterfaceStatus, RigidLine, SimulationSettings,
    SolverError, StepResult,
};
use fem_core::generate::{RectangleSpec, rectangle};
use fem_core::{Component, ElementKind, Idealization, LinearElasticModel, Material, Supports};
use std::path::PathBuf;
use vtkio::model::{Attribute, DataSet, Piece, Vtk};

const LIFT: f64 = 0.001;

fn block() -> ContactSimulation<LinearElasticModel, Signorini> {
    let mut spec = RectangleSpec::new([0.0, 2.0], [LIFT, 1.0 + LIFT], 8, 4);
    spec.kind = ElementKind::Tri3;
    let mesh = rectangle(&spec).unwrap();
    let bottom = mesh.node_set("bottom").unwrap().to_vec();
    let left = mesh.node_set("left").unwrap().to_vec();
    let top = mesh.node_set("top").unwrap().to_vec();
    let mut supports = Supports::new();
    supports.prescribe(&top, Component::Y, 0.0).unwrap();
    supports.fix(&left, Component::X);
    let model = LinearElasticModel::new(
        mesh,
        Idealization::PlaneStrain,
        &[(0, Material::new(200.0, 0.3, 0.0).unwrap())],
        supports,
    )
    .unwrap();
    let ground = RigidLine::new([-1.0, 0.0], [3.0, 0.0]).unwrap();
    let zone = ContactZone::rigid("base", bottom, ground, Signorini, 0.5);
    ContactSimulation::new(model, vec![zone], SimulationSettings::default()).unwrap()
}

/// Two steps of the block: open, then pressed.
fn run() -> (
    ContactSimulation<LinearElasticModel, Signorini>,
    Vec<StepResult>,
) {
    let mut sim = block();
    let top = sim.structure().mesh().node_set("top").unwrap().to_vec();
    let mut results = Vec::new();
    for (time, delta) in [(0.5, 0.5 * LIFT), (1.0, 0.011)] {
        sim.structure_mut()
            .set_prescribed(&top, Component::Y, -delta)
            .unwrap();
        results.push(sim.step(time, 1.0).unwrap());
    }
    (sim, results)
}

/// A fresh directory under the system's temp dir.
fn temp_dir(name: &str) -> PathBuf {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos();
    let dir = std::env::temp_dir().join(format!(
        "contact_solver_{name}_{}_{nanos}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn float(s: &str) -> f64 {
    s.parse()
        .unwrap_or_else(|e| panic!("`{s}` is not a float: {e}"))
}

#[test]
fn history_round_trips_exactly_works() {
    let (sim, results) = run();
    let candidates = sim.candidates().len();
    assert!(candidates > 0);
    // the pressed step has compressed contacts, so the history is not all zeros
    assert!(results[1].contacts.iter().any(|c| c.r.n > 0.0));
    let mut history = HistoryWriter::new(Vec::new()).unwrap();
    for res in &results {
        history.write_step(res).unwrap();
    }
    let text = String::from_utf8(history.finish().unwrap()).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), CONTACT_COLUMNS.join(","));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), results.len() * candidates);
    let records = results
        .iter()
        .flat_map(|res| res.contacts.iter().map(move |c| (&res.report, c)));
    for (row, (report, c)) in rows.iter().zip(records) {
        assert_eq!(row.len(), CONTACT_COLUMNS.len());
        assert_eq!(row[0].parse::<usize>().unwrap(), report.step);
        assert_eq!(float(row[1]), report.time);
        assert_eq!(float(row[2]), report.load_factor);
        assert_eq!(row[3].parse::<usize>().unwrap(), c.zone);
        assert_eq!(row[4].parse::<usize>().unwrap(), c.node);
        assert_eq!(row[7], c.status.name());
        let floats: Vec<f64> = row[5..7]
            .iter()
            .chain(&row[8..])
            .map(|s| float(s))
            .collect();
        #[rustfmt::skip]
        let expected = [
            c.position[0], c.position[1], c.gap, c.u_t, c.slip_increment, c.beta,
            c.r.n, c.r.t[0], c.r_bar.n, c.r_bar.t[0], c.r_adh.n, c.r_adh.t[0], c.area,
            c.force()[0], c.force()[1], c.normal[0], c.normal[1], c.tangent[0], c.tangent[1],
        ];
        // bit-exact: the writer uses round-trip formatting
        assert_eq!(floats, expected);
    }
}

#[test]
fn report_log_round_trips_exactly_works() {
    let (_, results) = run();
    let mut log = ReportWriter::new(Vec::new()).unwrap();
    for res in &results {
        log.write_report(&res.report).unwrap();
    }
    let text = String::from_utf8(log.finish().unwrap()).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), REPORT_COLUMNS.join(","));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), results.len());
    for (row, res) in rows.iter().zip(&results) {
        let r = &res.report;
        assert_eq!(row.len(), REPORT_COLUMNS.len());
        let int = |i: usize| row[i].parse::<usize>().unwrap();
        assert_eq!(int(0), r.step);
        assert_eq!(float(row[1]), r.time);
        assert_eq!(float(row[2]), r.load_factor);
        assert_eq!(int(3), r.closed_contacts);
        assert_eq!(int(4), r.adhesion_iterations);
        assert_eq!(int(5), r.contact_iterations);
        assert_eq!(int(6), r.detection_passes);
        assert_eq!(int(7), usize::from(r.flexibility_rebuilt));
        assert_eq!(float(row[8]), r.residual);
        assert_eq!(int(9), usize::from(r.converged));
        assert_eq!(float(row[10]), r.wall_time.as_secs_f64());
        assert_eq!(int(11), usize::from(r.matrix_free));
        assert_eq!(int(12), usize::from(r.active_set));
        assert_eq!(int(13), r.active_contacts);
    }
    assert_eq!(rows[0][7], "1"); // F* built in the first step
}

/// The point data arrays of an imported single-piece `.vtu`, and its point coordinates.
fn read_vtu(path: &std::path::Path) -> (Vec<f64>, Vec<Attribute>) {
    let vtk = Vtk::import(path).unwrap();
    let DataSet::UnstructuredGrid { mut pieces, .. } = vtk.data else {
        panic!("not an unstructured grid");
    };
    assert_eq!(pieces.len(), 1);
    let Piece::Inline(piece) = pieces.remove(0) else {
        panic!("piece not inline");
    };
    let points = piece.points.cast_into::<f64>().unwrap();
    (points, piece.data.point)
}

fn array<T: vtkio::model::Scalar>(data: &[Attribute], name: &str) -> Vec<T> {
    let a = data
        .iter()
        .find_map(|a| match a {
            Attribute::DataArray(d) if d.name == name => Some(d),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no array `{name}`"));
    // `into_vec` checks the stored type too (UInt8 status, UInt64 ids, Float64 fields)
    a.data
        .clone()
        .into_vec::<T>()
        .unwrap_or_else(|| panic!("`{name}` has another type"))
}

#[test]
fn interface_vtu_reads_back_works() {
    let (sim, results) = run();
    let dir = temp_dir("vtu");
    let contacts: &[ContactRecord] = &results[1].contacts;
    let u = sim.nodal_displacements();
    let path = dir.join("interface.vtu");
    write_interface_vtu(&path, contacts, Some(&u)).unwrap();
    let (points, data) = read_vtu(&path);
    assert_eq!(points.len(), 3 * contacts.len());
    for (p, c) in points.chunks(3).zip(contacts) {
        let d = u[c.node];
        assert_eq!(p, [c.position[0] + d[0], c.position[1] + d[1], 0.0]);
    }
    // Float64 arrays are written base64-encoded in binary: exact
    assert_eq!(
        array::<f64>(&data, "gap"),
        contacts.iter().map(|c| c.gap).collect::<Vec<_>>()
    );
    let r_local = array::<f64>(&data, "r_local");
    assert_eq!(
        r_local,
        contacts
            .iter()
            .flat_map(|c| [c.r.n, c.r.t[0], 0.0])
            .collect::<Vec<_>>()
    );
    let status = array::<u8>(&data, "status");
    assert_eq!(
        status,
        contacts
            .iter()
            .map(|c| status_code(c.status))
            .collect::<Vec<_>>()
    );
    assert!(
        status
            .iter()
            .all(|&s| s != status_code(InterfaceStatus::Open))
    );
    assert_eq!(
        array::<u64>(&data, "node"),
        contacts.iter().map(|c| c.node as u64).collect::<Vec<_>>()
    );
    array::<u64>(&data, "zone");
    for name in [
        "area",
        "u_t",
        "slip_increment",
        "beta",
        "r_bar_local",
        "r_adh_local",
        "u",
    ] {
        array::<f64>(&data, name);
    }

    // without displacements: reference positions, no `u`
    write_interface_vtu(&path, contacts, None).unwrap();
    let (points, data) = read_vtu(&path);
    assert_eq!(points[0..2], contacts[0].position);
    assert!(
        !data
            .iter()
            .any(|a| matches!(a, Attribute::DataArray(d) if d.name == "u"))
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn interface_series_works() {
    let (sim, results) = run();
    let dir = temp_dir("series");
    let mut series = InterfaceSeries::new(&dir, "interface");
    let u = sim.nodal_displacements();
    for res in &results {
        series
            .write_step(res.report.time, &res.contacts, Some(&u))
            .unwrap();
    }
    for k in 0..results.len() {
        assert!(dir.join(format!("interface_{k:04}.vtu")).exists());
    }
    let pvd = std::fs::read_to_string(series.pvd_path()).unwrap();
    assert!(pvd.contains(r#"timestep="0.5" group="" part="0" file="interface_0000.vtu""#));
    assert!(pvd.contains(r#"timestep="1" group="" part="0" file="interface_0001.vtu""#));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn output_captures_errors() {
    let (_, results) = run();
    let missing = std::env::temp_dir()
        .join(format!("contact_solver_no_such_dir_{}", std::process::id()))
        .join("sub");
    let e = write_interface_vtu(&missing.join("a.vtu"), &results[1].contacts, None).unwrap_err();
    let SolverError::Io { what, .. } = &e else {
        panic!("expected SolverError::Io, got {e:?}");
    };
    assert!(what.contains("a.vtu"), "{what}");
    assert!(e.to_string().starts_with("I/O error: cannot write"), "{e}");
    // the OS error once, as the source
    let full = contact_solver::error::chain(&e);
    assert_eq!(full.matches("No such file").count(), 1, "{full}");

    let mut series = InterfaceSeries::new(&missing, "interface");
    assert!(matches!(
        series.write_step(0.5, &results[0].contacts, None),
        Err(SolverError::Io { .. })
    ));

    // displacements with too few nodes: an error, not an out-of-bounds panic
    assert!(matches!(
        write_interface_vtu(
            &missing.join("a.vtu"),
            &results[1].contacts,
            Some(&[[0.0; 2]])
        ),
        Err(SolverError::SizeMismatch {
            what: "displacements",
            ..
        })
    ));

    // a writer that fails
    struct Full;
    impl std::io::Write for Full {
        fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
            Err(std::io::Error::new(
                std::io::ErrorKind::StorageFull,
                "no space",
            ))
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    assert!(matches!(
        HistoryWriter::new(Full),
        Err(SolverError::Io { .. })
    ));
    assert!(matches!(
        ReportWriter::new(Full),
        Err(SolverError::Io { .. })
    ));
    // a file opened read-only: writing the header fails
    let dir = temp_dir("readonly");
    let path = dir.join("h.csv");
    std::fs::write(&path, "").unwrap();
    let file = std::fs::File::open(&path).unwrap();
    assert!(matches!(
        HistoryWriter::new(file),
        Err(SolverError::Io { .. })
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}
