//! The seed's pile pull-out (chapter 6, Plancoët, RCCM interface) in 3D against the
//! axisymmetric model: the same meridian mesh revolved into a quarter of `S` sectors
//! (`bipo::presets::PulloutSpec::build_3d`), the same installation displacement `δ` (the
//! axisymmetric calibration), the same 50 increments. Prints both head load–displacement
//! curves and their largest relative difference, the sizes and the times.
//!
//! ```text
//! cargo run --release --example pile_3d -- [S] [--coarse] [--steps N] [--active-set]
//! ```
//! Defaults: `S = 2`, the seed's mesh (32 shaft cells), 50 increments. `--coarse` takes 8 shaft
//! cells (a quick look); `--active-set` solves the 3D model with the primal active set (the
//! springs on the stiffness, no `F*`) instead of the dense `F*`. `BIPO_QUICK=1`: `--coarse`
//! and 5 increments. Ends in an error when the curves differ by more than 3 % of the peak.

use bipo::presets::{Installation, PulloutSpec};
use bipotential::contact_solver::{FlexibilityMode, SimulationSettings};
use std::error::Error;
use std::time::Instant;

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    // the first number that is not the value of `--steps`
    let sectors: usize = args
        .iter()
        .enumerate()
        .find(|(i, a)| {
            !a.starts_with("--")
                && a.parse::<usize>().is_ok()
                && (*i == 0 || args[i - 1] != "--steps")
        })
        .map_or(Ok(2), |(_, s)| s.parse())?;
    let quick = std::env::var_os("BIPO_QUICK").is_some_and(|v| v != "0");
    let mut spec = PulloutSpec::plancoet();
    if quick {
        spec.steps = 5;
    }
    if quick || args.iter().any(|a| a == "--coarse") {
        (
            spec.mesh.cells_shaft,
            spec.mesh.cells_soil_r,
            spec.mesh.cells_below_tip,
        ) = (8, 6, 4);
    }
    if let Some(i) = args.iter().position(|a| a == "--steps") {
        spec.steps = args.get(i + 1).ok_or("--steps N")?.parse()?;
    }
    let t = Instant::now();
    let mut axi = spec.build(SimulationSettings::default())?;
    let run2 = axi.run()?;
    let t2 = t.elapsed().as_secs_f64();
    let curve2 = run2.curve();
    let dofs2 = 2 * axi.simulation.structure().mesh().node_count();
    spec.installation = Installation::RadialDisplacement(axi.installation_displacement);
    let t = Instant::now();
    let mut settings = SimulationSettings::for_dimension::<3>();
    if args.iter().any(|a| a == "--active-set") {
        settings.flexibility = FlexibilityMode::ActiveSet;
    }
    let mut solid = spec.build_3d(sectors, settings)?;
    let curve3 = solid.run()?.curve();
    let t3 = t.elapsed().as_secs_f64();
    let dofs3 = 3 * solid.simulation.structure().mesh().node_count();
    println!(
        "Plancoët, δ = {:.4e} m; axisymmetric: {dofs2} DOF, {} pairs, {t2:.2} s; 3D quarter, \
         {sectors} sectors: {dofs3} DOF, {} pairs, {t3:.1} s",
        axi.installation_displacement,
        axi.simulation.candidates().len(),
        solid.simulation.candidates().len()
    );
    println!("| v (mm) | Q axisymmetric (kN) | Q 3D (kN) | difference |");
    println!("|---|---|---|---|");
    let mut worst = 0.0_f64;
    let peak = curve2.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    for ((v, q2), (_, q3)) in curve2.iter().zip(&curve3) {
        let d = (q3 - q2) / peak;
        worst = worst.max(d.abs());
        println!(
            "| {:.2} | {q2:.2} | {q3:.2} | {:+.2} % |",
            1e3 * v,
            100.0 * d
        );
    }
    println!(
        "largest difference, relative to the peak load {peak:.2} kN: {:.2} %",
        100.0 * worst
    );
    // the same meridian mesh and installation: the 3D model differs by its sectors' faceting
    // (measured 0.55 % with 5 sectors on the coarse mesh); 3 % flags a real disagreement
    if worst.is_nan() || worst > 0.03 {
        return Err(format!(
            "the 3D curve is {:.2} % of the peak off the axisymmetric one (tolerance 3 %)",
            100.0 * worst
        )
        .into());
    }
    Ok(())
}
