//! `bipo`: run contact studies of `bipotential` from TOML scene files.
//!
//! ```text
//! bipo run SCENE [--out DIR]     step the scene, write CSV / VTK / SVG and summary.json
//! bipo check SCENE               validate, build the model and recognise the contacts
//! bipo solve-local PROBLEM.json  solve a reduced problem {dim, W, q, mu}
//! bipo new KIND [-o FILE]        write a commented template scene
//! ```
//! The scene format is documented in `docs/guide.md` ("Scene files and the `bipo` command").

fn main() -> std::process::ExitCode {
    bipo::app::main()
}
