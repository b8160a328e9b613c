//! A contact candidate: one contactor node of a zone with its target point, its frame
//! `[n, t…]`, its initial gap and the rows of `H` it owns (see the [zone](super) docs).

use super::{MAX_TARGETS, Projection};
use crate::coupling::space::{ContactSpace, dot};
use fem_core::{Dim, Structure};

/// A contact candidate in `D` dimensions (2 unless said): one contactor node with its target
/// point and frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate<const D: usize = 2> {
    /// Index of its zone.
    pub zone: usize,
    /// The contactor node.
    pub node: usize,
    /// Target nodes and weights (`None` for rigid obstacles and unused slots).
    pub targets: [Option<(usize, f64)>; MAX_TARGETS],
    /// Initial gap `g₀` (reference configuration).
    pub gap0: f64,
    /// The target point in the reference configuration.
    pub point: [f64; D],
    /// Tributary area of the contactor node (see [`ContactZone::areas`](super::ContactZone)).
    pub area: f64,
    /// `[n, t…]`: the unit normal from the target towards the contactor, then the tangents.
    frame: [[f64; D]; D],
}

impl<const D: usize> Candidate<D>
where
    Dim<D>: ContactSpace<D>,
{
    /// The candidate of contactor `node` of zone `zone` at its target `p`, with the frame of
    /// `p`'s normal ([`ContactSpace::frame`]).
    pub(crate) fn new(zone: usize, node: usize, p: Projection<D>, area: f64) -> Self {
        Self {
            zone,
            node,
            targets: p.targets,
            gap0: p.gap,
            point: p.point,
            area,
            frame: <Dim<D> as ContactSpace<D>>::frame(p.normal),
        }
    }

    /// The entries `(dof, coefficient)` of this candidate's `H` row along `dir`, on the
    /// structure's free dofs: `dir·u_contactor − Σ w_k dir·u_target,k`. In 2D every nonzero
    /// coefficient is kept, one entry per node and component; in 3D coefficients at or below
    /// [`ContactSpace::ROUND_OFF`] are dropped and the entries merged to one per dof (a node on
    /// both sides cancels).
    pub(crate) fn h_row<S: Structure<D> + ?Sized>(
        &self,
        s: &S,
        dir: [f64; D],
    ) -> Vec<(usize, f64)> {
        let round_off = <Dim<D> as ContactSpace<D>>::ROUND_OFF;
        let mut out = Vec::with_capacity(2 * D);
        let mut push = |node: usize, w: f64| {
            for (c, d) in s.node_dofs(node).into_iter().enumerate() {
                if let Some(i) = d {
                    let a = w * dir[c];
                    let keep = if round_off == 0.0 {
                        a != 0.0
                    } else {
                        a.abs() > round_off
                    };
                    if keep {
                        out.push((i, a));
                    }
                }
            }
        };
        push(self.node, 1.0);
        for &(node, w) in self.targets.iter().flatten() {
            push(node, -w);
        }
        if round_off == 0.0 {
            return out;
        }
        out.sort_unstable_by_key(|e| e.0);
        let mut merged: Vec<(usize, f64)> = Vec::with_capacity(out.len());
        for (dof, a) in out {
            match merged.last_mut() {
                Some(last) if last.0 == dof => last.1 += a,
                _ => merged.push((dof, a)),
            }
        }
        merged.retain(|e| e.1.abs() > round_off);
        merged
    }

    /// Whether the relative displacement along the normal is prescribed: the normal `H` row
    /// is empty, or its squared norm below [`ContactSpace::HELD`].
    pub(crate) fn held_along_normal<S: Structure<D> + ?Sized>(&self, s: &S) -> bool {
        let row = self.h_row(s, self.normal());
        row.is_empty()
            || row.iter().map(|(_, a)| a * a).sum::<f64>() < <Dim<D> as ContactSpace<D>>::HELD
    }

    /// The local components `[x_n, u_t…] = [g₀ + n·u_rel, t·u_rel…]` as the typed local
    /// vector of the dimension.
    pub fn local_vec(&self, u_rel: [f64; D]) -> <Dim<D> as ContactSpace<D>>::Local {
        <Dim<D> as ContactSpace<D>>::local_vec(self.local(u_rel))
    }
}

impl<const D: usize> Candidate<D> {
    /// The unit normal, from the target towards the contactor.
    #[inline]
    pub fn normal(&self) -> [f64; D] {
        self.frame[0]
    }

    /// The frame `[n, t…]`: the normal, then the tangents (`t = (n_y, −n_x)` in 2D; `t₁`,
    /// `t₂ = n × t₁` of [`tangent_frame`](crate::coupling::solid::tangent_frame) in 3D).
    #[inline]
    pub fn frame(&self) -> [[f64; D]; D] {
        self.frame
    }

    /// The relative displacement `u_rel` from a nodal displacement lookup.
    pub fn relative(&self, disp: impl Fn(usize) -> [f64; D]) -> [f64; D] {
        let mut u = disp(self.node);
        for &(node, w) in self.targets.iter().flatten() {
            let v = disp(node);
            for a in 0..D {
                u[a] -= w * v[a];
            }
        }
        u
    }

    /// `[x_n, u_t…] = [g₀ + n·u_rel, t·u_rel…]`.
    pub fn local(&self, u_rel: [f64; D]) -> [f64; D] {
        core::array::from_fn(|k| {
            let d = dot(self.frame[k], u_rel);
            if k == 0 { self.gap0 + d } else { d }
        })
    }
}

impl Candidate<2> {
    /// The unit tangent `t = (n_y, −n_x)`.
    #[inline]
    pub fn tangent(&self) -> [f64; 2] {
        self.frame[1]
    }
}
