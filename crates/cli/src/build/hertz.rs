//! `[hertz]` checked against the study: the zone, the radius, the first point of contact, the
//! symmetry factor, the contact modulus `E*` and the SVG file ([`HertzPlan`]).

use super::checks::{finite, positive};
use crate::error::{CliResult, KeyPath, bail, err};
use crate::scene::Scene;

/// The Hertz reference of a run (drawn by `run`'s pressure plot).
#[derive(Clone, Debug, PartialEq)]
pub struct HertzPlan {
    /// The zone whose recovered pressure is drawn.
    pub zone: usize,
    /// Radius of the curved body.
    pub radius: f64,
    /// The first point of contact (2D: the first two entries).
    pub center: [f64; 3],
    /// The whole contact's force over the zone's `Σ r_n`.
    pub symmetry: f64,
    /// The contact modulus `E*`.
    pub e_star: f64,
    /// The SVG file, in the output directory.
    pub file: String,
}

/// The model behind the drawn ellipse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HertzShape {
    /// A cylinder on a flat (plane strain or plane stress): the force per unit length is the
    /// zone's `Σ r_n` times the symmetry factor, divided by `thickness`.
    Cylinder {
        /// Out-of-plane thickness of the reactions (1 in plane strain).
        thickness: f64,
    },
    /// A sphere on a flat (axisymmetry: `× 2π`, the reactions are per radian; 3D).
    Sphere {
        /// `2π` in axisymmetry, 1 in 3D.
        ring: f64,
    },
}

impl HertzShape {
    /// The contact radius (half-width) `a` and peak pressure `p0` for the zone's `Σ r_n`
    /// (Johnson 1985, § 4.2, eqs. 4.43 and 4.45 for the sphere; § 5.6 for the cylinder).
    ///
    /// ```text
    /// cylinder: P = s Σ r_n / thickness,  a = √(4 P R / (π E*)),  p0 = 2 P / (π a)
    /// sphere:   P = s ring Σ r_n,         a = (3 P R / (4 E*))^⅓, p0 = 3 P / (2 π a²)
    /// ```
    pub fn a_p0(self, plan: &HertzPlan, force_n: f64) -> (f64, f64) {
        use std::f64::consts::PI;
        let (r, e) = (plan.radius, plan.e_star);
        match self {
            HertzShape::Cylinder { thickness } => {
                let p = plan.symmetry * force_n / thickness;
                let a = (4.0 * p * r / (PI * e)).sqrt();
                (a, 2.0 * p / (PI * a))
            }
            HertzShape::Sphere { ring } => {
                let p = plan.symmetry * ring * force_n;
                let a = (3.0 * p * r / (4.0 * e)).cbrt();
                (a, 3.0 * p / (2.0 * PI * a * a))
            }
        }
    }
}

/// `[hertz]` of `scene` against the zones `zone_names` of a `dim`-dimensional study; `e_of`
/// turns one material's `(E, ν)` into `E*` (`E / (1 − ν²)`, or `E` in plane stress).
pub(super) fn check(
    scene: &Scene,
    zone_names: &[String],
    dim: usize,
    e_of: impl Fn(f64, f64) -> f64,
) -> CliResult<Option<HertzPlan>> {
    let Some(h) = &scene.hertz else {
        return Ok(None);
    };
    let p = KeyPath::root().key("hertz");
    let zone = match &h.zone {
        Some(name) => zone_names.iter().position(|z| z == name).ok_or_else(|| {
            let zp = p.key("zone");
            err!(
                zp,
                "`{zp}` = \"{name}\": no contact zone has that name (zones: {})",
                zone_names.join(", ")
            )
        })?,
        None if zone_names.len() == 1 => 0,
        None => {
            bail!(
                p.key("zone"),
                "`{}`: the scene has {} contact zones: say which one to compare with Hertz",
                p.key("zone"),
                zone_names.len()
            );
        }
    };
    let radius = positive(&p.key("radius"), h.radius)?;
    let mut center = [0.0; 3];
    if let Some(c) = &h.center {
        if c.len() != dim {
            bail!(
                p.key("center"),
                "`{}` has {} entries: expected {dim} coordinates",
                p.key("center"),
                c.len()
            );
        }
        for (k, v) in c.iter().enumerate() {
            center[k] = finite(&p.key("center").index(k), *v)?;
        }
    }
    let symmetry = match h.symmetry {
        Some(s) => positive(&p.key("symmetry"), s)?,
        None => 1.0,
    };
    let e_star = match (h.e_star, scene.materials.as_slice()) {
        (Some(e), _) => positive(&p.key("e_star"), e)?,
        (None, [m]) => e_of(m.young, m.poisson),
        (None, ms) => {
            bail!(
                p.key("e_star"),
                "`{}`: the scene has {} materials: give the contact modulus \
                     E* = 1 / ((1 − ν₁²)/E₁ + (1 − ν₂²)/E₂) of the two bodies",
                p.key("e_star"),
                ms.len()
            );
        }
    };
    let file = h.file.clone().unwrap_or_else(|| "pressure.svg".into());
    if !file.ends_with(".svg") || file.contains(['/', '\\']) {
        bail!(
            p.key("file"),
            "`{}` = \"{file}\": expected a file name ending in .svg (written in the output \
                 directory)",
            p.key("file")
        );
    }
    if scene.plots.iter().any(|pl| pl.file == file) {
        bail!(
            p.key("file"),
            "`{}` = \"{file}\" is also a plot's file",
            p.key("file")
        );
    }
    Ok(Some(HertzPlan {
        zone,
        radius,
        center,
        symmetry,
        e_star,
        file,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan() -> HertzPlan {
        HertzPlan {
            zone: 0,
            radius: 100.0,
            center: [0.0; 3],
            symmetry: 2.0,
            e_star: 1000.0 / 0.91,
            file: "pressure.svg".into(),
        }
    }

    #[test]
    fn a_p0_works() {
        // hertz.toml's header: Σ r_n = 4.468 (half model) gives a = 1.017 and p0 = 5.59
        let (a, p0) = HertzShape::Cylinder { thickness: 1.0 }.a_p0(&plan(), 4.468);
        assert!(
            (a - 1.017).abs() < 1e-3 && (p0 - 5.59).abs() < 1e-2,
            "{a} {p0}"
        );
        // sphere_3d.toml's header: P = 0.045788 on a quarter, R = 1 gives a = 0.05
        let mut q = plan();
        q.radius = 1.0;
        q.symmetry = 4.0;
        let (a, p0) = HertzShape::Sphere { ring: 1.0 }.a_p0(&q, 0.045788);
        assert!((a - 0.05).abs() < 1e-5, "{a}");
        // p0 = 3 P / (2 π a²) = 2 E* a / (π R)
        assert!((p0 - 2.0 * q.e_star * a / std::f64::consts::PI).abs() < 1e-3 * p0);
    }
}
