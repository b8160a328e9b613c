//! `[preset]` as read (one flat table for the three presets) and its `installation`.

use super::keys::{need, only, present};
use crate::error::{CliResult, KeyPath};
use crate::spec::*;
use serde::Deserialize;

#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum PresetKind {
    /// Seed 5.6.1.
    Delamination,
    /// Seed 5.6.2.
    Shear,
    /// Seed ch. 6.
    Pile,
}

#[derive(Debug, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum InstallationKind {
    None,
    RadialDisplacement,
    NormalForceRatio,
}

/// `installation = {...}`.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct RawInstallation {
    #[serde(rename = "type")]
    kind: InstallationKind,
    value: Option<f64>,
}

/// `[preset]`.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct RawPreset {
    kind: PresetKind,
    length: Option<f64>,
    height: Option<f64>,
    young: Option<f64>,
    poisson: Option<f64>,
    nx: Option<usize>,
    ny: Option<usize>,
    element: Option<Element>,
    lift: Option<f64>,
    press: Option<f64>,
    push: Option<f64>,
    duration: Option<f64>,
    steps: Option<usize>,
    interface: Option<RccmOverride>,
    // pile
    site: Option<Site>,
    coulomb: Option<bool>,
    pile_young: Option<f64>,
    pile_poisson: Option<f64>,
    pile_unit_weight: Option<f64>,
    soil_young: Option<f64>,
    soil_poisson: Option<f64>,
    soil_unit_weight: Option<f64>,
    k0: Option<f64>,
    installation: Option<RawInstallation>,
    head_displacement: Option<f64>,
    head_force: Option<f64>,
    alert_distance: Option<f64>,
    mesh: Option<PileMeshOverride>,
    sectors: Option<usize>,
}

impl RawPreset {
    fn plate(&self) -> PlateOverride {
        PlateOverride {
            length: self.length,
            height: self.height,
            young: self.young,
            poisson: self.poisson,
            nx: self.nx,
            ny: self.ny,
            element: self.element,
            duration: self.duration,
            steps: self.steps,
            interface: self.interface,
        }
    }

    /// The preset.
    pub fn resolve(&self, p: &KeyPath) -> CliResult<Preset> {
        let present = present!(self; length, height, young, poisson, nx, ny, element, lift, press,
            push, duration, steps, interface, site, coulomb, pile_young, pile_poisson,
            pile_unit_weight, soil_young, soil_poisson, soil_unit_weight, k0, installation,
            head_displacement, head_force, alert_distance, mesh, sectors);
        const COMMON: &str = "length height young poisson nx ny element duration steps interface";
        Ok(match self.kind {
            PresetKind::Delamination => {
                only(
                    p,
                    "the delamination preset",
                    &present,
                    &format!("{COMMON} lift"),
                )?;
                Preset::Delamination {
                    plate: self.plate(),
                    lift: self.lift,
                }
            }
            PresetKind::Shear => {
                only(
                    p,
                    "the shear preset",
                    &present,
                    &format!("{COMMON} press push"),
                )?;
                Preset::Shear {
                    plate: self.plate(),
                    press: self.press,
                    push: self.push,
                }
            }
            PresetKind::Pile => {
                let keys = "site coulomb pile_young pile_poisson pile_unit_weight soil_young \
                            soil_poisson soil_unit_weight k0 installation head_displacement \
                            head_force steps alert_distance interface mesh sectors";
                only(p, "the pile preset", &present, keys)?;
                let installation = match self.installation {
                    None => None,
                    Some(i) => {
                        let ip = p.key("installation");
                        let what = "this installation";
                        Some(match i.kind {
                            InstallationKind::None => {
                                only(&ip, "installation \"none\"", &present!(i; value), "")?;
                                InstallationSpec::None {}
                            }
                            InstallationKind::RadialDisplacement => {
                                InstallationSpec::RadialDisplacement {
                                    value: need(&ip, &i.value, "value", what)?,
                                }
                            }
                            InstallationKind::NormalForceRatio => {
                                InstallationSpec::NormalForceRatio {
                                    value: need(&ip, &i.value, "value", what)?,
                                }
                            }
                        })
                    }
                };
                Preset::Pile(PileOverride {
                    site: self.site,
                    coulomb: self.coulomb.unwrap_or(false),
                    pile_young: self.pile_young,
                    pile_poisson: self.pile_poisson,
                    pile_unit_weight: self.pile_unit_weight,
                    soil_young: self.soil_young,
                    soil_poisson: self.soil_poisson,
                    soil_unit_weight: self.soil_unit_weight,
                    k0: self.k0,
                    installation,
                    head_displacement: self.head_displacement,
                    head_force: self.head_force,
                    steps: self.steps,
                    alert_distance: self.alert_distance,
                    interface: self.interface,
                    mesh: self.mesh,
                    sectors: self.sectors,
                })
            }
        })
    }
}
