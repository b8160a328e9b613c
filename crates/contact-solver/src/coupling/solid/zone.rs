//! The 3D names of the contact zones, their targets and candidates: aliases of the generic
//! [`zone`](crate::coupling::zone) types at `D = 3` (tributary areas:
//! [`ContactZone::areas`](crate::ContactZone::areas)).

use crate::coupling::zone::{Candidate, ContactZone, PairNormals, Target};

/// The normals of a 3D node-pair zone: [`PairNormals<3>`].
pub type PairNormals3 = PairNormals<3>;
/// What the contactor nodes of a 3D zone face: [`Target<3>`].
pub type Target3 = Target<3>;
/// A 3D contact zone: [`ContactZone<L, 3>`].
pub type ContactZone3<L> = ContactZone<L, 3>;
/// A contactor node of a 3D zone, its frame and initial gap: [`Candidate<3>`].
pub type Candidate3 = Candidate<3>;
