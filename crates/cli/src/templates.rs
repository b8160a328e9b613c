//! `bipo new KIND`: the commented template scenes. They are the scene files of
//! `examples/scenes/` (so every template is run by the tests), read through the symbolic links
//! in `crates/cli/templates/`, which `cargo package` turns into files: the published crate
//! carries its templates.

use crate::error::{CliError, CliResult};
use clap::ValueEnum;
use std::path::PathBuf;

/// Template kinds.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum Kind {
    /// An elastic block pressed on a rigid LINE, frictionless (Signorini), P1.
    Block,
    /// A half cylinder (P2, Gmsh mesh) pressed on a rigid LINE: Hertz contact.
    Hertz,
    /// Seed 5.6.1: delamination of a thin layer (library preset, RCCM).
    Delamination,
    /// Seed 5.6.2: shear of a compressed block (library preset, RCCM).
    Shear,
    /// Seed chapter 6: pull-out of the Plancoët pile (library preset, three phases).
    Pile,
    /// 3D: a rigid sphere pressed into a P2 block (Hertz, quarter model).
    #[value(name = "sphere_3d")]
    Sphere3d,
}

const BLOCK: &str = include_str!("../templates/block.toml");
const HERTZ: &str = include_str!("../templates/hertz.toml");
const HERTZ_MSH: &str = include_str!("../templates/hertz_cylinder.msh");
const DELAMINATION: &str = include_str!("../templates/delamination.toml");
const SHEAR: &str = include_str!("../templates/shear.toml");
const PILE: &str = include_str!("../templates/pile.toml");
const SPHERE_3D: &str = include_str!("../templates/sphere_3d.toml");

impl Kind {
    /// The template text.
    pub fn text(self) -> &'static str {
        match self {
            Kind::Block => BLOCK,
            Kind::Hertz => HERTZ,
            Kind::Delamination => DELAMINATION,
            Kind::Shear => SHEAR,
            Kind::Pile => PILE,
            Kind::Sphere3d => SPHERE_3D,
        }
    }

    /// Extra files the template refers to: (name, content).
    fn extra(self) -> &'static [(&'static str, &'static str)] {
        match self {
            Kind::Hertz => &[("hertz_cylinder.msh", HERTZ_MSH)],
            _ => &[],
        }
    }
}

/// Writes the template (and its extra files beside it).
pub fn write(kind: Kind, output: Option<PathBuf>, force: bool) -> CliResult<()> {
    let path = output.unwrap_or_else(|| {
        // the name on the command line: `block`, …, `sphere_3d`
        let name = kind.to_possible_value().map(|v| v.get_name().to_owned());
        PathBuf::from(format!("{}.toml", name.unwrap_or_default()))
    });
    let dir = path.parent().map(PathBuf::from).unwrap_or_default();
    let mut files = vec![(path.clone(), kind.text())];
    for (name, text) in kind.extra() {
        files.push((dir.join(name), *text));
    }
    for (p, _) in &files {
        if p.exists() && !force {
            return Err(CliError::input(format!(
                "{} exists already (use --force to overwrite it)",
                p.display()
            )));
        }
    }
    for (p, text) in &files {
        std::fs::write(p, text)
            .map_err(|e| CliError::failed(format!("cannot write {}: {e}", p.display())))?;
        crate::out::outln!("wrote {}", p.display());
    }
    crate::out::outln!("next: bipo check {0} && bipo run {0}", path.display());
    Ok(())
}
