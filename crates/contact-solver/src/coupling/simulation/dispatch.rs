//! What a step calls differently by dimension, in one place: the solvers whose number of
//! tangents `NT = D − 1` is a const parameter (not writable as `D - 1` on stable Rust) and the
//! base penalty of the matrix-free path. Each function branches on
//! [`ContactSpace::TANGENTS`]; both branches are compiled for every `D`, only the one of the
//! dimension runs.

use crate::coupling::primal::adhesive::{AdhesiveData, AdhesivePrimal, solve_primal_adhesive};
use crate::coupling::primal::{PrimalCache, PrimalSolution, PrimalStep, solve_primal};
use crate::coupling::space::ContactSpace;
use crate::error::SolverError;
use crate::local::UzawaSettings;
use crate::local::adhesion::AdhesionOptions;
use crate::local::contact_statuses;
use crate::local::matrix_free::{MatrixFreeReport, solve_matrix_free, solve_matrix_free_3d};
use crate::local::matrix_free_anderson::{
    solve_matrix_free_anderson, solve_matrix_free_anderson_3d,
};
use contact_laws::{ContactLaw, ContactStatus};
use fem_core::{Dim, Structure};

/// Whether `D` has two tangents (3D).
fn spatial<const D: usize>() -> bool
where
    Dim<D>: ContactSpace<D>,
{
    <Dim<D> as ContactSpace<D>>::TANGENTS == 2
}

/// The primal active-set solve ([`solve_primal`]) in dimension `D`.
pub(super) fn primal<S: Structure<D> + ?Sized, L: ContactLaw, const D: usize>(
    structure: &S,
    cache: &mut PrimalCache,
    step: &PrimalStep<'_, L>,
) -> Result<PrimalSolution, SolverError>
where
    Dim<D>: ContactSpace<D>,
{
    if spatial::<D>() {
        solve_primal::<_, D, _, 2>(structure, cache, step)
    } else {
        solve_primal::<_, D, _, 1>(structure, cache, step)
    }
}

/// The primal active set with the adhesion fixed point ([`solve_primal_adhesive`]).
pub(super) fn primal_adhesive<S: Structure<D> + ?Sized, L: ContactLaw, const D: usize>(
    structure: &S,
    cache: &mut PrimalCache,
    step: &PrimalStep<'_, L>,
    data: &AdhesiveData<'_, D>,
    options: &AdhesionOptions,
) -> Result<AdhesivePrimal<L::State>, SolverError>
where
    Dim<D>: ContactSpace<D>,
{
    if spatial::<D>() {
        solve_primal_adhesive::<_, D, _, 2, D>(structure, cache, step, data, options)
    } else {
        solve_primal_adhesive::<_, D, _, 1, D>(structure, cache, step, data, options)
    }
}

/// The matrix-free sweep ([`solve_matrix_free`], [`solve_matrix_free_3d`]), or with
/// `window > 0` its Anderson-accelerated twin ([`solve_matrix_free_anderson`],
/// [`solve_matrix_free_anderson_3d`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn matrix_free<L: ContactLaw, const D: usize>(
    apply: impl FnMut(&[f64], &mut [f64]) -> Result<(), SolverError>,
    laws: &[L],
    states: &[L::State],
    rho0: &[f64],
    window: usize,
    settings: &UzawaSettings,
    r: &mut [f64],
    x: &mut [f64],
) -> Result<MatrixFreeReport, SolverError>
where
    Dim<D>: ContactSpace<D>,
{
    if window > 0 {
        if spatial::<D>() {
            solve_matrix_free_anderson_3d(apply, laws, states, rho0, window, settings, r, x)
        } else {
            solve_matrix_free_anderson(apply, laws, states, rho0, window, settings, r, x)
        }
    } else if spatial::<D>() {
        solve_matrix_free_3d(apply, laws, states, rho0, settings, r, x)
    } else {
        solve_matrix_free(apply, laws, states, rho0, settings, r, x)
    }
}

/// The statuses of a solution ([`contact_statuses`]).
pub(super) fn statuses<L: ContactLaw, const D: usize>(
    laws: &[L],
    states: &[L::State],
    rho: &[f64],
    r: &[f64],
    x: &[f64],
) -> Vec<ContactStatus>
where
    Dim<D>: ContactSpace<D>,
{
    if spatial::<D>() {
        contact_statuses::<_, 2>(laws, states, rho, r, x)
    } else {
        contact_statuses::<_, 1>(laws, states, rho, r, x)
    }
}

/// The base penalty `ρ⁰` of a contact from its `D × D` diagonal block `w` of `F*`
/// (row-major): `1/λ_max` exactly in 2D, `1/‖w‖_∞` (a bound of `λ_max`) in 3D.
pub(super) fn rho0<const D: usize>(w: &[f64]) -> f64
where
    Dim<D>: ContactSpace<D>,
{
    if spatial::<D>() {
        let bound = (0..D)
            .map(|a| (0..D).map(|b| w[D * a + b].abs()).sum::<f64>())
            .fold(0.0_f64, f64::max);
        if bound > 0.0 && bound.is_finite() {
            1.0 / bound
        } else {
            1.0
        }
    } else {
        let (a, b, d) = (w[0], 0.5 * (w[1] + w[2]), w[3]);
        let h = 0.5 * (a - d);
        1.0 / (0.5 * (a + d) + (h * h + b * b).sqrt())
    }
}
