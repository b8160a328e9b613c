//! `rigid_motions.csv`: the rigid-body motions of the floating bodies (`[analysis] floating`),
//! one row per step and rigid-body mode: its kind (`translation`, `rotation`), the mode's amplitude `α` in the displacement
//! `u = K⁺(f + Hᵀ r) + R α` and what it means in global axes (a translation's displacement, a
//! rotation's angle `α / ρ` about its centre); the last step's go to `summary.json`.

use super::errors::{create, io};
use crate::error::CliResult;
use fem_core::{RigidBodyModes, RigidMotion};
use serde::Serialize;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// One rigid-body mode at the end of the run.
#[derive(Clone, Debug, Serialize)]
pub struct RigidMotionSummary {
    /// The body (connected component, in order of its lowest node).
    pub body: usize,
    /// The mode's index among the structure's rigid-body modes.
    pub mode: usize,
    /// What it is (`translation x`, `rotation about (…)`).
    pub motion: String,
    /// Its amplitude `α` at the end.
    pub amplitude: f64,
    /// The displacement of a translation `α d` (zero for a rotation), global axes.
    pub translation: [f64; 2],
    /// The angle of a rotation `α / ρ` in radians, counter-clockwise (zero for a translation).
    pub rotation: f64,
}

/// The file, the modes' meanings, and the last step's motions.
pub(super) struct RigidWriter {
    path: PathBuf,
    out: BufWriter<File>,
    pub(super) last: Vec<RigidMotionSummary>,
}

/// A translation's displacement and a rotation's angle for amplitude `a`.
fn meaning(motion: &RigidMotion, a: f64) -> ([f64; 2], f64) {
    match *motion {
        // `+ 0.0`: a negative amplitude times a zero component is 0, not −0
        RigidMotion::Translation { direction } => {
            ([a * direction[0] + 0.0, a * direction[1] + 0.0], 0.0)
        }
        RigidMotion::Rotation { radius, .. } => ([0.0; 2], a / radius),
        _ => ([0.0; 2], 0.0),
    }
}

/// The `motion` column: `translation` or `rotation` (`other` for a mode without a geometric
/// meaning); no comma, whatever the centre.
fn kind(motion: &RigidMotion) -> &'static str {
    match motion {
        RigidMotion::Translation { .. } => "translation",
        RigidMotion::Rotation { .. } => "rotation",
        _ => "other",
    }
}

impl RigidWriter {
    /// Creates `dir/rigid_motions.csv` with its header (axes named `axes`: `x, y` or `r, z`).
    pub(super) fn new(dir: &Path, axes: [&str; 2]) -> CliResult<Self> {
        let path = dir.join("rigid_motions.csv");
        let mut out = create(dir, "rigid_motions.csv")?;
        writeln!(
            out,
            "step,time,body,mode,motion,amplitude,u_{},u_{},rotation",
            axes[0], axes[1]
        )
        .map_err(|e| io(&path, e))?;
        Ok(Self {
            path,
            out,
            last: Vec::new(),
        })
    }

    /// The rows of step `step` at `time`: the amplitudes `alpha` of `modes`.
    pub(super) fn write_step(
        &mut self,
        step: usize,
        time: f64,
        modes: &RigidBodyModes,
        alpha: &[f64],
    ) -> CliResult<()> {
        self.last.clear();
        for (j, (m, &a)) in modes.modes().iter().zip(alpha).enumerate() {
            let (u, theta) = meaning(&m.motion, a);
            writeln!(
                self.out,
                "{step},{time},{},{j},{},{a:e},{:e},{:e},{theta:e}",
                m.body,
                kind(&m.motion),
                u[0],
                u[1]
            )
            .map_err(|e| io(&self.path, e))?;
            self.last.push(RigidMotionSummary {
                body: m.body,
                mode: j,
                motion: m.motion.to_string(),
                amplitude: a,
                translation: u,
                rotation: theta,
            });
        }
        Ok(())
    }

    /// Flushes the file; returns the last step's motions.
    pub(super) fn finish(mut self) -> CliResult<Vec<RigidMotionSummary>> {
        self.out.flush().map_err(|e| io(&self.path, e))?;
        Ok(self.last)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn meaning_of_translation_and_rotation_works() {
        let t = RigidMotion::Translation {
            direction: [0.0, 1.0],
        };
        assert_eq!(meaning(&t, 2.0), ([0.0, 2.0], 0.0));
        let r = RigidMotion::Rotation {
            centre: [0.0; 2],
            radius: 4.0,
        };
        assert_eq!(meaning(&r, 2.0), ([0.0; 2], 0.5));
    }
}
