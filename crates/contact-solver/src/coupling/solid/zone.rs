//! The 3D names of the contact zones, their targets and candidates: aliases of the generic
//! [`zone`](crate::coupling::zone) types at `D = 3` (tributary areas:
//! [`ContactZone::areas`](crate::ContactZone::areas)).

use crate::coupling::zone::{
    Candidate, ContactZone, PairNormals, Target, check_candidates, recognize, supported_contactors,
};
use crate::error::SolverError;
use fem_core::Structure;

/// The normals of a 3D node-pair zone: [`PairNormals<3>`].
pub type PairNormals3 = PairNormals<3>;
/// What the contactor nodes of a 3D zone face: [`Target<3>`].
pub type Target3 = Target<3>;
/// A 3D contact zone: [`ContactZone<L, 3>`].
pub type ContactZone3<L> = ContactZone<L, 3>;
/// A contactor node of a 3D zone, its frame and initial gap: [`Candidate<3>`].
pub type Candidate3 = Candidate<3>;

/// [`recognize`] followed by [`check_candidates`], the checks the 3D simulation runs: every
/// zone has a candidate, and none is held along its normal.
///
/// # Errors
/// As [`recognize`] and [`check_candidates`].
pub fn recognize_3d<S: Structure<3> + ?Sized, L>(
    structure: &S,
    zones: &[ContactZone3<L>],
) -> Result<Vec<Candidate3>, SolverError> {
    let out = recognize(structure, zones)?;
    check_candidates(structure, zones, &out)?;
    Ok(out)
}

/// [`supported_contactors`] on 3D zones (the same function).
///
/// # Errors
/// As [`recognize`].
pub fn supported_contactors_3d<S: Structure<3> + ?Sized, L>(
    structure: &S,
    zones: &[ContactZone3<L>],
) -> Result<Vec<(usize, usize)>, SolverError> {
    supported_contactors(structure, zones)
}
