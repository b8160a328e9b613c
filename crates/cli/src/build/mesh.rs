//! The mesh, in both dimensions: `[mesh]`'s values checked into a generator's spec (the
//! rectangle and the pile in 2D, the box in 3D: graded grid lines along x, y and z, Kuhn's six
//! tetrahedra per cell) or a Gmsh file to read, then the mesh generated ([`SceneDim`]'s
//! `generate`) or read, and the axisymmetric mesh checked to lie right of the axis.

use super::checks::{
    at_least, count, fem, finite, finite2, grading, kind, positive, set, solid_kind,
};
use super::dim::SceneDim;
use crate::error::{CliError, CliResult, KeyPath, bail};
use crate::spec::{
    BoxSpec, Element, MeshSpec, Pair, PileMeshOverride, PileMeshSpec, TipCornerSpec,
};
use fem_core::generate::{Grading, Layer, PileSpec, RectangleSpec, TipCorner, graded_points};
use fem_core::{Dim, ElementKind, FemError, Idealization, Mesh};
use std::path::{Path, PathBuf};

/// The most cells of a box (six tetrahedra each): 2e5 cells are 1.2e6 tetrahedra, beyond what a
/// scene run on a workstation solves in a useful time with a dense contact flexibility.
pub const MAX_BOX_CELLS: usize = 200_000;

/// A mesh to build, its values checked.
pub(crate) enum MeshPlan {
    /// `fem_core::generate::rectangle` (2D).
    Rectangle(RectangleSpec),
    /// `fem_core::generate::pile_in_soil` (2D), and whether its tip is detached
    /// ([`crate::presets::pile::detach_tip`]).
    Pile(PileSpec, bool),
    /// `fem_core::solid::generate::box_mesh` (3D): the grid lines and the element.
    Box([Vec<f64>; 3], ElementKind),
    /// An existing Gmsh file and the element order it must hold.
    Gmsh(GmshPlan),
}

/// A Gmsh file of `[mesh]` (in either dimension), which exists, and the element order it must
/// hold.
pub(crate) struct GmshPlan {
    /// As written in the scene (relative to the scene file).
    file: String,
    path: PathBuf,
    /// `mesh.element`, if given.
    element: Option<Element>,
}

impl GmshPlan {
    /// The file `file` of `[mesh]` (at `mp`), which must exist (`base_dir` is the scene file's
    /// folder), and `mesh.element`.
    pub(super) fn new(
        mp: &KeyPath,
        file: &str,
        element: Option<Element>,
        base_dir: &Path,
    ) -> CliResult<Self> {
        Ok(Self {
            file: file.to_owned(),
            path: gmsh_file(mp, file, base_dir)?,
            element,
        })
    }

    /// Reads the mesh and checks that its elements have the order `mesh.element` names.
    pub(super) fn read<const D: usize>(self, mp: &KeyPath) -> CliResult<Mesh<D>>
    where
        Dim<D>: SceneDim<D>,
    {
        let mesh = Dim::<D>::read_msh(&self.path).map_err(|e| fem(&mp.key("file"), e))?;
        if let Some(e) = self.element {
            let (order, name) = Dim::<D>::element_order(e, &mesh);
            if !order {
                bail!(
                    mp.key("element"),
                    "`mesh.element` = \"{e:?}\" but `{}` holds {name}",
                    self.file
                );
            }
        }
        Ok(mesh)
    }
}

/// Checks the values of `[mesh]` (at `mp`) and gives the generator's spec, or the file to read
/// (which must exist; `base_dir` is the scene file's folder). `idealization`: a 2D scene's.
pub(super) fn validate(
    mp: &KeyPath,
    spec: &MeshSpec,
    idealization: Option<Idealization>,
    base_dir: &Path,
) -> CliResult<MeshPlan> {
    match spec {
        MeshSpec::Rectangle { .. } => rectangle(mp, spec),
        MeshSpec::Pile(o) => pile(mp, o, idealization),
        MeshSpec::Box(b) => box_lines(mp, b),
        MeshSpec::Gmsh { file, element } => {
            Ok(MeshPlan::Gmsh(GmshPlan::new(mp, file, *element, base_dir)?))
        }
    }
}

/// The path of the Gmsh file `file` of `[mesh]` (at `mp`), which must exist (`base_dir` is the
/// scene file's folder).
fn gmsh_file(mp: &KeyPath, file: &str, base_dir: &Path) -> CliResult<PathBuf> {
    let path = base_dir.join(file);
    let fp = mp.key("file");
    let what = if file.trim().is_empty() {
        Some("expected the name of a Gmsh .msh file")
    } else if path.is_dir() {
        Some("is a directory, not a Gmsh .msh file")
    } else if !path.exists() {
        Some("no such file")
    } else {
        None
    };
    if let Some(what) = what {
        bail!(
            fp,
            "`{fp}` = \"{file}\": {what} ({}; paths are relative to the scene file)",
            path.display()
        );
    }
    Ok(path)
}

/// The rectangle generator: one layer (`y`, `ny`, …) or `y0` and `layers`.
fn rectangle(mp: &KeyPath, spec: &MeshSpec) -> CliResult<MeshPlan> {
    let MeshSpec::Rectangle {
        element,
        x,
        nx,
        grading_x,
        y,
        ny,
        grading_y,
        region,
        y0,
        layers,
    } = spec
    else {
        unreachable!("called for the rectangle generator")
    };
    let xs = interval(&mp.key("x"), *x, "x")?;
    let mut spec = RectangleSpec::new(xs, [0.0, 1.0], at_least(&mp.key("nx"), *nx, 1)?, 1);
    spec.grading_x = grading(&mp.key("grading_x"), *grading_x)?;
    graded(
        &mp.key("x"),
        &mp.key("grading_x"),
        xs,
        spec.nx,
        spec.grading_x,
    )?;
    spec.kind = kind(*element);
    match (y, layers) {
        (Some(y), None) => {
            if y0.is_some() {
                bail!(
                    mp.key("y0"),
                    "`y0` goes with `layers`; with `y = [y0, y1]` leave it out"
                );
            }
            let ys = interval(&mp.key("y"), *y, "y")?;
            let ny = ny.ok_or_else(|| CliError::at(mp, "`mesh.ny` is missing (cells along y)"))?;
            spec.y0 = ys[0];
            let layer = Layer {
                top: ys[1],
                ny: at_least(&mp.key("ny"), ny, 1)?,
                grading: grading(&mp.key("grading_y"), grading_y.unwrap_or_default())?,
                region: region.unwrap_or(0),
            };
            graded(
                &mp.key("y"),
                &mp.key("grading_y"),
                ys,
                layer.ny,
                layer.grading,
            )?;
            spec.layers = vec![layer];
        }
        (None, Some(layers)) => {
            for (k, key) in [
                (ny.is_some(), "ny"),
                (grading_y.is_some(), "grading_y"),
                (region.is_some(), "region"),
            ] {
                if k {
                    bail!(
                        mp.key(key),
                        "`mesh.{key}` goes with `y = [y0, y1]`; with `layers` give it per layer"
                    );
                }
            }
            spec.y0 = finite(&mp.key("y0"), y0.unwrap_or(0.0))?;
            if layers.is_empty() {
                bail!(mp.key("layers"), "`mesh.layers` is empty");
            }
            let mut below = spec.y0;
            spec.layers = Vec::new();
            for (i, l) in layers.iter().enumerate() {
                let lp = mp.key("layers").index(i);
                let top = finite(&lp.key("top"), l.top)?;
                if top <= below {
                    bail!(
                        lp.key("top"),
                        "`{}` = {top}: layers go upward, expected a top above {below}",
                        lp.key("top")
                    );
                }
                let layer = Layer {
                    top,
                    ny: at_least(&lp.key("ny"), l.ny, 1)?,
                    grading: grading(&lp.key("grading"), l.grading)?,
                    region: l.region,
                };
                graded(
                    &lp.key("top"),
                    &lp.key("grading"),
                    [below, top],
                    layer.ny,
                    layer.grading,
                )?;
                below = top;
                spec.layers.push(layer);
            }
        }
        (Some(_), Some(_)) => {
            bail!(
                mp.key("layers"),
                "give `y = [y0, y1]` or `layers`, not both"
            );
        }
        (None, None) => {
            bail!(
                mp,
                "the rectangle needs `y = [y0, y1]` and `ny`, or `y0` and `layers`"
            );
        }
    }
    Ok(MeshPlan::Rectangle(spec))
}

/// `[a, b]` at `path`: two finite numbers, `a < b`, whose difference does not overflow.
pub(super) fn interval(path: &KeyPath, pair: Pair, axis: &str) -> CliResult<[f64; 2]> {
    let [a, b] = finite2(path, pair)?;
    if a >= b {
        bail!(
            path,
            "`{path}` = [{a:?}, {b:?}]: expected {axis}0 < {axis}1"
        );
    }
    if !(b - a).is_finite() {
        bail!(
            path,
            "`{path}` = [{a:?}, {b:?}]: the length {axis}1 - {axis}0 overflows (expected \
                 coordinates whose differences stay finite)"
        );
    }
    Ok([a, b])
}

/// Checks the grading of `n` cells over `[a, b]` before the generator runs, so that a ratio
/// whose smallest cell vanishes is blamed on the grading (at `grading_path`), not on a
/// degenerate element. Lines of more than a million cells are left to the generator's limits
/// (nothing is allocated for them here).
fn graded(
    path: &KeyPath,
    grading_path: &KeyPath,
    [a, b]: [f64; 2],
    n: usize,
    g: Grading,
) -> CliResult<()> {
    if n > 1_000_000 {
        return Ok(());
    }
    match fem_core::generate::graded_points(a, b, n, g) {
        Ok(_) => Ok(()),
        Err(e @ FemError::InvalidParameter { name: "ratio", .. }) => {
            Err(fem(&grading_path.key("ratio"), e))
        }
        Err(e) => Err(fem(path, e)),
    }
}

/// The box generator: its grid lines along x, y and z, graded, at most [`MAX_BOX_CELLS`] cells.
fn box_lines(mp: &KeyPath, b: &BoxSpec) -> CliResult<MeshPlan> {
    let mut lines: [Vec<f64>; 3] = Default::default();
    let mut cells = 1usize;
    for (a, axis) in ["x", "y", "z"].into_iter().enumerate() {
        let range = interval(&mp.key(axis), b.ranges[a], axis)?;
        let np = mp.key(&format!("n{axis}"));
        let n = at_least(&np, b.cells[a], 1)?;
        cells = cells.saturating_mul(n);
        if cells > MAX_BOX_CELLS {
            bail!(
                np,
                "`{np}` = {n}: the box would have more than {MAX_BOX_CELLS} cells \
                     (nx·ny·nz, six tetrahedra each); use fewer cells or a graded grid"
            );
        }
        let gp = mp.key(&format!("grading_{axis}"));
        let g = grading(&gp, b.gradings[a])?;
        lines[a] = graded_points(range[0], range[1], n, g).map_err(|e| match e {
            FemError::InvalidParameter { name: "ratio", .. } => fem(&gp.key("ratio"), e),
            e => fem(&mp.key(axis), e),
        })?;
    }
    Ok(MeshPlan::Box(lines, solid_kind(b.element)))
}

/// The pile generator: the seed's pile with optional overrides (axisymmetric only).
fn pile(mp: &KeyPath, o: &PileMeshSpec, idealization: Option<Idealization>) -> CliResult<MeshPlan> {
    if !matches!(idealization, Some(Idealization::Axisymmetric)) {
        bail!(
            KeyPath::root().key("analysis"),
            "the pile generator builds an axisymmetric (r, z) mesh: it needs \
             [analysis] type = \"axisymmetric\""
        );
    }
    let mut s = PileSpec::default();
    let sizes = &o.sizes;
    if sizes.length.is_some() && sizes.width.is_none() && sizes.depth.is_none() {
        // keep the seed's proportions W = 2 L_p, H = 3.5 L_p
        let l = positive(&mp.key("length"), sizes.length.unwrap_or(13.0))?;
        s.width = 2.0 * l;
        s.depth = 3.5 * l;
    }
    pile_sizes(mp, &mut s, sizes)?;
    set!(mp, s, grading_pile_r = o.grading_pile_r, grading);
    set!(mp, s, grading_soil_r = o.grading_soil_r, grading);
    set!(mp, s, grading_shaft = o.grading_shaft, grading);
    set!(mp, s, grading_below_tip = o.grading_below_tip, grading);
    if let Some(t) = o.tip_corner {
        s.tip_corner = match t {
            TipCornerSpec::Split => TipCorner::Split,
            TipCornerSpec::Shared => TipCorner::Shared,
        };
    }
    Ok(MeshPlan::Pile(s, o.detach_tip))
}

/// The pile's element, sizes and cell counts of `m` (at `mp`: `[mesh]` or `[preset] mesh`).
pub(super) fn pile_sizes(mp: &KeyPath, s: &mut PileSpec, m: &PileMeshOverride) -> CliResult<()> {
    if let Some(e) = m.element {
        s.kind = kind(e);
    }
    set!(mp, s, diameter = m.diameter, positive);
    set!(mp, s, length = m.length, positive);
    set!(mp, s, width = m.width, positive);
    set!(mp, s, depth = m.depth, positive);
    set!(mp, s, cells_pile_r = m.cells_pile_r, count);
    set!(mp, s, cells_soil_r = m.cells_soil_r, count);
    set!(mp, s, cells_shaft = m.cells_shaft, count);
    set!(mp, s, cells_below_tip = m.cells_below_tip, count);
    Ok(())
}

/// Generates or reads the mesh of `plan` (`[mesh]` at `mp`) in dimension `D`; an axisymmetric
/// mesh (`idealization`: a 2D scene's) must lie at x >= 0.
pub(super) fn build<const D: usize>(
    mp: &KeyPath,
    plan: MeshPlan,
    idealization: Option<Idealization>,
) -> CliResult<Mesh<D>>
where
    Dim<D>: SceneDim<D>,
{
    let mesh = match plan {
        MeshPlan::Gmsh(g) => g.read(mp)?,
        plan => Dim::<D>::generate(mp, plan)?,
    };
    if let Some(Idealization::Axisymmetric) = idealization
        && let Some((node, p)) = mesh.nodes().iter().enumerate().find(|(_, p)| p[0] < 0.0)
    {
        bail!(
            KeyPath::root().key("analysis"),
            "axisymmetric analysis needs every node at r = x >= 0, but node {node} is at x = {} \
                 (the mesh must lie right of the axis x = 0)",
            p[0]
        );
    }
    Ok(mesh)
}
