//! Newton's method on the equilibrium `f_int(u) = f_ext(λ)` of a [`Nonlinear`] structure
//! (no contact), along a load path `λ: start → end` in steps, with step cutting.
//!
//! ```text
//! for each step λ_n → λ_{n+1} = λ_n + Δλ:
//!   u ← u_n;  r = f_ext(λ_{n+1}) − f_int(u)
//!   while ‖r‖₂ > tol · max(‖f_ext(λ_{n+1})‖₂, ‖f_int(u)‖₂):
//!     K_t(u) Δu = r;  u ← u + Δu
//!   commit;  (no convergence within max_iterations: rollback, u ← u_n, Δλ ← Δλ / 2)
//! ```
//! The norm is the Euclidean norm over the free dofs, relative to the larger of the external
//! and internal forces (so that a state balancing a large initial stress under a small load
//! is measured on the forces that balance). After a cut step converges, the next step tries
//! twice its size again, up to the first size. The residual of every iteration of every step
//! tried is kept in the [`NewtonReport`]; with the consistent tangent of an associated law
//! they fall quadratically.

pub use crate::convergence::{NewtonReport, NewtonStep};
use crate::error::{FemError, finite, positive};
use crate::space::{Dim, Space};
use crate::structure::{Nonlinear, Structure};

/// The settings of [`solve`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonSettings {
    /// The number of equal load steps from `start` to `end` (before any cut); at least 1.
    pub steps: usize,
    /// The relative residual (module docs) at which an iterate is accepted; in `(0, 1)`.
    pub tolerance: f64,
    /// The most Newton iterations (solves) per step before it is cut; at least 1.
    pub max_iterations: usize,
    /// The most step halvings along the whole path before [`FemError::NotConverged`].
    pub max_cuts: usize,
}

impl Default for NewtonSettings {
    /// One step, tolerance `1e-10`, 20 iterations, 10 cuts.
    fn default() -> Self {
        Self {
            steps: 1,
            tolerance: 1e-10,
            max_iterations: 20,
            max_cuts: 10,
        }
    }
}

impl NewtonSettings {
    /// `steps` equal load steps, the other settings at their defaults.
    pub fn with_steps(steps: usize) -> Self {
        Self {
            steps,
            ..Self::default()
        }
    }
}

/// Solves the equilibrium of `structure` from load factor `start` to `end` (module docs),
/// starting from the free displacements `u` in equilibrium with the committed state at
/// `start` (zero for a fresh body), and leaves in `u` the displacements at `end` with the
/// structure committed there. With `start == end` it makes one step at that load factor:
/// the equilibrium after a change of prescribed values (a displacement control; a step that
/// does not converge then cannot be cut smaller, it is retried as it is).
///
/// # Errors
/// - [`FemError::InvalidParameter`] naming `start`, `end`, `steps`, `tolerance` or
///   `max_iterations`;
/// - [`FemError::Unsupported`] for a structure without a [`Nonlinear`] side;
/// - [`FemError::NotConverged`] when a step does not converge after `max_cuts` halvings
///   (a failed factorisation or material update counts as a step that does not converge),
///   with the report; `u` and the structure are then at the last converged state.
///
/// # Panics
/// If `u.len()` is not the structure's `dof_count()`.
#[track_caller]
pub fn solve<const D: usize, S>(
    structure: &mut S,
    u: &mut [f64],
    start: f64,
    end: f64,
    settings: &NewtonSettings,
) -> Result<NewtonReport, FemError>
where
    Dim<D>: Space,
    S: Structure<D> + ?Sized,
{
    let n = structure.dof_count();
    assert_eq!(u.len(), n, "displacement length");
    let (start, end) = (finite("start", start)?, finite("end", end)?);
    let tolerance = positive("tolerance", settings.tolerance)?;
    for (name, value) in [
        ("steps", settings.steps),
        ("max_iterations", settings.max_iterations),
    ] {
        if value == 0 {
            return Err(FemError::InvalidParameter {
                name,
                value: 0.0,
                expected: "at least 1",
            });
        }
    }
    if structure.nonlinear().is_none() {
        return Err(FemError::Unsupported {
            what: "a Newton load path on a structure without a Nonlinear side".into(),
        });
    }
    let first = (end - start) / settings.steps as f64;
    let mut report = NewtonReport {
        load_factor: start,
        ..NewtonReport::default()
    };
    let mut buffers = Buffers {
        f_ext: vec![0.0; n],
        f_int: vec![0.0; n],
        u_converged: u.to_vec(),
    };
    let mut step = first;
    // a step counts as arrived within round-off of `end`
    let arrived = |lambda: f64| (end - lambda).abs() <= 1e-12 * (end - start).abs();
    // `start == end`: one step at that load factor (after a change of prescribed values),
    // pending until it converges
    let mut pending = start == end;
    while pending || !arrived(report.load_factor) {
        let target = if (end - report.load_factor).abs() <= step.abs() * (1.0 + 1e-12) {
            end
        } else {
            report.load_factor + step
        };
        let mut residuals = Vec::with_capacity(settings.max_iterations + 1);
        let converged = iterate(
            structure,
            u,
            target,
            tolerance,
            settings,
            &mut buffers,
            &mut residuals,
        )
        .unwrap_or(false);
        report.steps.push(NewtonStep {
            load_factor: target,
            residuals,
            converged,
        });
        let body = structure.nonlinear().expect("checked above");
        if converged {
            pending = false;
            body.commit();
            report.load_factor = target;
            buffers.u_converged.copy_from_slice(u);
            step = if step.abs() < first.abs() {
                2.0 * step
            } else {
                first
            };
        } else {
            body.rollback();
            u.copy_from_slice(&buffers.u_converged);
            if report.cuts == settings.max_cuts {
                return Err(FemError::NotConverged {
                    load_factor: target,
                    converged_load_factor: report.load_factor,
                    cuts: report.cuts,
                    report: Box::new(report),
                });
            }
            report.cuts += 1;
            step *= 0.5;
        }
    }
    Ok(report)
}

/// The vectors of the iterations, allocated once per path.
struct Buffers {
    f_ext: Vec<f64>,
    f_int: Vec<f64>,
    u_converged: Vec<f64>,
}

/// The Newton iterations of one step to `load_factor`, the relative residuals pushed onto
/// `residuals`: whether the last met the tolerance.
fn iterate<const D: usize, S>(
    structure: &mut S,
    u: &mut [f64],
    load_factor: f64,
    tolerance: f64,
    settings: &NewtonSettings,
    b: &mut Buffers,
    residuals: &mut Vec<f64>,
) -> Result<bool, FemError>
where
    Dim<D>: Space,
    S: Structure<D> + ?Sized,
{
    for iteration in 0..=settings.max_iterations {
        let body: &mut dyn Nonlinear = structure.nonlinear().expect("checked by solve");
        body.external_force_into(load_factor, &mut b.f_ext)?;
        body.internal_force_into(u, &mut b.f_int)?;
        let scale = norm(&b.f_ext).max(norm(&b.f_int));
        // r = f_ext − f_int, into f_ext
        b.f_ext.iter_mut().zip(&b.f_int).for_each(|(e, i)| *e -= i);
        let r = norm(&b.f_ext);
        let relative = if scale > 0.0 { r / scale } else { 0.0 };
        residuals.push(relative);
        if !relative.is_finite() {
            return Ok(false);
        }
        if relative <= tolerance {
            return Ok(true);
        }
        if iteration == settings.max_iterations {
            break;
        }
        body.update_tangent()?;
        structure.solve_in_place(&mut b.f_ext)?;
        u.iter_mut().zip(&b.f_ext).for_each(|(u, du)| *u += du);
    }
    Ok(false)
}

/// The Euclidean norm.
fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}
