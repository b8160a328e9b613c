//! `[mesh]` as read (one flat table for the four generators: rectangle and pile in 2D, box in
//! 3D, gmsh in both) and its gradings.

use super::keys::{need, only, present};
use crate::error::{CliResult, KeyPath, bail};
use crate::spec::*;
use serde::Deserialize;

#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum GradingKind {
    /// Equal cells.
    Uniform,
    Geometric,
    BothEnds,
}

/// `{ type = "geometric", ratio = 4.0 }`.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct RawGrading {
    #[serde(rename = "type")]
    kind: GradingKind,
    ratio: Option<f64>,
}

impl RawGrading {
    /// The grading.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<GradingSpec> {
        Ok(match self.kind {
            GradingKind::Uniform => {
                only(p, "a uniform grading", &present!(self; ratio), "")?;
                GradingSpec::Uniform {}
            }
            GradingKind::Geometric => GradingSpec::Geometric {
                ratio: need(p, &self.ratio, "ratio", "a geometric grading")?,
            },
            GradingKind::BothEnds => GradingSpec::BothEnds {
                ratio: need(p, &self.ratio, "ratio", "a both_ends grading")?,
            },
        })
    }
}

fn grading(p: &KeyPath, g: &Option<RawGrading>) -> CliResult<Option<GradingSpec>> {
    g.as_ref().map(|g| g.resolve(p)).transpose()
}

/// One layer.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawLayer {
    top: f64,
    ny: usize,
    grading: Option<RawGrading>,
    #[serde(default)]
    region: u32,
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Generator {
    /// `rectangle`.
    Rectangle,
    /// `pile`.
    Pile,
    /// `gmsh`.
    Gmsh,
    /// `box` (3D).
    Box,
}

/// `[mesh]`.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawMesh {
    generator: Generator,
    element: Option<Element>,
    // rectangle
    x: Option<Pair>,
    nx: Option<usize>,
    grading_x: Option<RawGrading>,
    y: Option<Pair>,
    ny: Option<usize>,
    grading_y: Option<RawGrading>,
    region: Option<u32>,
    y0: Option<f64>,
    layers: Option<Vec<RawLayer>>,
    // box
    z: Option<Pair>,
    nz: Option<usize>,
    grading_z: Option<RawGrading>,
    // pile
    diameter: Option<f64>,
    length: Option<f64>,
    width: Option<f64>,
    depth: Option<f64>,
    cells_pile_r: Option<usize>,
    cells_soil_r: Option<usize>,
    cells_shaft: Option<usize>,
    cells_below_tip: Option<usize>,
    grading_pile_r: Option<RawGrading>,
    grading_soil_r: Option<RawGrading>,
    grading_shaft: Option<RawGrading>,
    grading_below_tip: Option<RawGrading>,
    tip_corner: Option<TipCornerSpec>,
    detach_tip: Option<bool>,
    // gmsh
    file: Option<String>,
}

const RECTANGLE_KEYS: &str = "element x nx grading_x y ny grading_y region y0 layers";
const PILE_KEYS: &str = "element diameter length width depth cells_pile_r cells_soil_r cells_shaft \
                         cells_below_tip grading_pile_r grading_soil_r grading_shaft \
                         grading_below_tip tip_corner detach_tip";
const GMSH_KEYS: &str = "element file";
const BOX_KEYS: &str = "element x nx grading_x y ny grading_y z nz grading_z";

impl RawMesh {
    fn present(&self) -> [(&'static str, bool); 28] {
        present!(self; element, x, nx, grading_x, y, ny, grading_y, region, y0, layers, diameter,
            length, width, depth, cells_pile_r, cells_soil_r, cells_shaft, cells_below_tip,
            grading_pile_r, grading_soil_r, grading_shaft, grading_below_tip, tip_corner, detach_tip, file, z,
            nz, grading_z)
    }

    /// The mesh spec of a scene of dimension `D`: the generators of the other dimension are
    /// refused at `generator`.
    pub fn resolve<const D: usize>(&self, p: &KeyPath) -> CliResult<MeshSpec> {
        let present = self.present();
        let gp = p.key("generator");
        if D == 2 && self.generator == Generator::Box {
            bail!(
                gp,
                "`{gp}` = \"box\" builds a 3D mesh: it needs [analysis] type = \"3d\" \
                     (a 2D scene takes rectangle, pile or gmsh)"
            );
        }
        if D == 3 && matches!(self.generator, Generator::Rectangle | Generator::Pile) {
            bail!(
                gp,
                "`{gp}` = \"{}\" builds a 2D mesh; a 3D scene ([analysis] type = \
                     \"3d\") takes generator = \"box\" or \"gmsh\"",
                if self.generator == Generator::Pile {
                    "pile"
                } else {
                    "rectangle"
                }
            );
        }
        Ok(match self.generator {
            Generator::Rectangle => {
                only(p, "the rectangle generator", &present, RECTANGLE_KEYS)?;
                let what = "the rectangle generator";
                let layers = match &self.layers {
                    None => None,
                    Some(ls) => Some(
                        ls.iter()
                            .enumerate()
                            .map(|(i, l)| {
                                Ok(LayerSpec {
                                    top: l.top,
                                    ny: l.ny,
                                    grading: grading(
                                        &p.key("layers").index(i).key("grading"),
                                        &l.grading,
                                    )?
                                    .unwrap_or_default(),
                                    region: l.region,
                                })
                            })
                            .collect::<CliResult<Vec<_>>>()?,
                    ),
                };
                MeshSpec::Rectangle {
                    element: need(p, &self.element, "element", what)?,
                    x: need(p, &self.x, "x", what)?,
                    nx: need(p, &self.nx, "nx", what)?,
                    grading_x: grading(&p.key("grading_x"), &self.grading_x)?.unwrap_or_default(),
                    y: self.y,
                    ny: self.ny,
                    grading_y: grading(&p.key("grading_y"), &self.grading_y)?,
                    region: self.region,
                    y0: self.y0,
                    layers,
                }
            }
            Generator::Pile => {
                only(p, "the pile generator", &present, PILE_KEYS)?;
                MeshSpec::Pile(PileMeshSpec {
                    sizes: PileMeshOverride {
                        element: self.element,
                        diameter: self.diameter,
                        length: self.length,
                        width: self.width,
                        depth: self.depth,
                        cells_pile_r: self.cells_pile_r,
                        cells_soil_r: self.cells_soil_r,
                        cells_shaft: self.cells_shaft,
                        cells_below_tip: self.cells_below_tip,
                    },
                    grading_pile_r: grading(&p.key("grading_pile_r"), &self.grading_pile_r)?,
                    grading_soil_r: grading(&p.key("grading_soil_r"), &self.grading_soil_r)?,
                    grading_shaft: grading(&p.key("grading_shaft"), &self.grading_shaft)?,
                    grading_below_tip: grading(
                        &p.key("grading_below_tip"),
                        &self.grading_below_tip,
                    )?,
                    tip_corner: self.tip_corner,
                    detach_tip: self.detach_tip.unwrap_or(false),
                })
            }
            Generator::Gmsh => {
                only(p, "a gmsh mesh", &present, GMSH_KEYS)?;
                MeshSpec::Gmsh {
                    file: need(p, &self.file, "file", "a gmsh mesh")?,
                    element: self.element,
                }
            }
            Generator::Box => {
                let what = "the box generator";
                only(p, what, &present, BOX_KEYS)?;
                let g = |key: &str, v: &Option<RawGrading>| -> CliResult<GradingSpec> {
                    Ok(grading(&p.key(key), v)?.unwrap_or_default())
                };
                MeshSpec::Box(BoxSpec {
                    element: need(p, &self.element, "element", what)?,
                    ranges: [
                        need(p, &self.x, "x", what)?,
                        need(p, &self.y, "y", what)?,
                        need(p, &self.z, "z", what)?,
                    ],
                    cells: [
                        need(p, &self.nx, "nx", what)?,
                        need(p, &self.ny, "ny", what)?,
                        need(p, &self.nz, "nz", what)?,
                    ],
                    gradings: [
                        g("grading_x", &self.grading_x)?,
                        g("grading_y", &self.grading_y)?,
                        g("grading_z", &self.grading_z)?,
                    ],
                })
            }
        })
    }
}
