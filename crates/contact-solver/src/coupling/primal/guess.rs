//! The guess of the primal active set: which contacts are open, sticking or sliding (with the
//! direction of their friction force), and the guess as constraints of the rotated system.

use super::PrimalStep;
use contact_laws::ContactLaw;

/// 3D: the scale of `c_t` in the sliding direction's update ([`guess_sets`]), relative to the
/// dof stiffness. It starts at [`Damping::START`] (measured: 1 and 0.5 cycle on a block in
/// partial slip, 0.3 converges there and on the frictional Hertz quarter in 19 iterations,
/// 0.1 in 58) and halves, down to [`Damping::MIN`], whenever [`Damping::PATIENCE`]
/// iterations pass without a new best residual (a stick/slip cycle).
pub(super) struct Damping {
    pub(super) factor: f64,
    best: f64,
    since_best: usize,
}

impl Damping {
    const START: f64 = 0.3;
    const MIN: f64 = 1e-3;
    const PATIENCE: usize = 20;

    pub(super) fn observe(&mut self, residual: f64) {
        if residual < self.best {
            self.best = residual;
            self.since_best = 0;
        } else {
            self.since_best += 1;
            if self.since_best >= Self::PATIENCE {
                self.factor = (self.factor * 0.5).max(Self::MIN);
                self.since_best = 0;
            }
        }
    }
}

impl Default for Damping {
    fn default() -> Self {
        Self {
            factor: Self::START,
            best: f64::INFINITY,
            since_best: 0,
        }
    }
}

/// 3D: one contact's own factor on its `c_t` in the sliding direction's update, and the last
/// turn of its direction. The global [`Damping`] scales every contact alike; a contact whose
/// direction swings back and forth (the diagonal stiffness `c_t` overestimates the stiffness
/// it meets, as at a node of a stiff pile sliding as a whole in soft soil: a 2-cycle at a
/// residual of 3e-7 on the 3D pile) halves its own factor each time it swings back, and
/// doubles it (up to 1) each time it turns on the same way.
#[derive(Clone, Copy, Debug)]
pub(super) struct Swing {
    scale: f64,
    last: [f64; 2],
}

impl Swing {
    const MIN: f64 = 1e-6;
}

impl Default for Swing {
    fn default() -> Self {
        Self {
            scale: 1.0,
            last: [0.0; 2],
        }
    }
}

/// The guess of one contact: open, sticking, or sliding with the unit direction of its friction
/// force in the tangent plane (`T` components used; zero for a frictionless or normal-only
/// contact, or before a direction is known).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Guess {
    kind: Kind,
    direction: [f64; 2],
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) enum Kind {
    #[default]
    Open,
    Stick,
    Slip,
}

impl Guess {
    const OPEN: Self = Self {
        kind: Kind::Open,
        direction: [0.0; 2],
    };
    const STICK: Self = Self {
        kind: Kind::Stick,
        direction: [0.0; 2],
    };

    fn slip(direction: [f64; 2]) -> Self {
        Self {
            kind: Kind::Slip,
            direction,
        }
    }

    /// Whether the contact is guessed open.
    pub(super) fn is_open(&self) -> bool {
        self.kind == Kind::Open
    }

    /// Whether two guesses hold the same kind (open, sticking, sliding).
    pub(super) fn same_kind(&self, other: &Self) -> bool {
        self.kind == other.kind
    }

    fn has_direction(&self) -> bool {
        self.direction != [0.0; 2]
    }
}

/// The unit direction of a tangential vector (`T` components): its sign in 2D (`+1` for zero,
/// as `f64::signum`), `v / |v|` in 3D (zero when `|v| <= tiny`: a direction of round-off).
fn direction<const T: usize>(v: [f64; 2], tiny: f64) -> [f64; 2] {
    if T == 1 {
        return [v[0].signum(), 0.0];
    }
    let norm = v[0].hypot(v[1]);
    if norm > tiny {
        [v[0] / norm, v[1] / norm]
    } else {
        [0.0; 2]
    }
}

/// The guess of every contact; `sets` holds the previous one.
///
/// The guess is the semi-smooth Newton one with σ_n = r_n − c x_n and σ_t = r_t − c_t x_t in
/// the limit c_t → 0⁺ (any c > 0 has the same solutions): a sliding node keeps sliding while
/// it moves against its friction force (in 3D, the force turned against its new motion) and
/// sticks otherwise (a large c_t would flip its direction, which cycles between the two
/// full-slip guesses when friction nearly balances the drive); a sticking node slides once its
/// reaction leaves the Tresca disc, in the direction of its reaction.
///
/// In 3D the direction of a sliding node's force is a continuous unknown, lagged: the next one
/// is that of `g s − c_t x_t` (the natural map's argument with the dof stiffness `c_t`), not
/// `−x_t / |x_t|` (`c_t → ∞`), which swings wildly for the small slips near a stick zone
/// and does not converge. In 2D both are the sign of `s`. `c_t` is the dof stiffness times the
/// global damping `scale_ct` times the contact's own factor in `swings` ([`Swing`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn guess_sets<L: ContactLaw, const T: usize>(
    step: &PrimalStep<'_, L>,
    scale_ct: f64,
    c: &[[f64; 3]],
    r: &[f64],
    x: &[f64],
    g: &[f64],
    sets: &mut [Guess],
    swings: &mut [Swing],
) {
    debug_assert_eq!(sets.len(), swings.len());
    let d = T + 1;
    // a slip below this is round-off (of the free response), with no direction
    let tiny = 1e-12 * step.q.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
    for (kk, (guess, swing)) in sets.iter_mut().zip(swings.iter_mut()).enumerate() {
        let (rn, xn) = (r[d * kk], x[d * kk]);
        let sn = rn - c[kk][0] * xn;
        let prev = *guess;
        let frame = &step.frames[kk];
        let tangent = |v: &[f64]| -> [f64; 2] {
            core::array::from_fn(|a| if a < T { v[d * kk + 1 + a] } else { 0.0 })
        };
        let (rt, xt) = (tangent(r), tangent(x));
        let movable = frame.dofs[1..d].iter().any(Option::is_some);
        *guess = if sn <= 0.0 {
            Guess::OPEN
        } else if !step.tangent[kk] || !movable {
            Guess::slip([0.0; 2])
        } else if g[kk] == 0.0 {
            // no friction force yet: slide, against the direction the node moves
            Guess::slip(direction::<T>([-xt[0], -xt[1]], tiny))
        } else {
            let ct = c[kk][1].max(c[kk][2]) * scale_ct * swing.scale;
            let s = prev.direction;
            let v = [g[kk] * s[0] - ct * xt[0], g[kk] * s[1] - ct * xt[1]];
            match prev.kind {
                Kind::Slip if T == 2 && prev.has_direction() => {
                    // slides on while g s − c x_t leaves the disc without turning back
                    if v[0].hypot(v[1]) > g[kk] && dot(v, s) > 0.0 {
                        let next = direction::<T>(v, 0.0);
                        let turn = [next[0] - s[0], next[1] - s[1]];
                        let along = dot(turn, swing.last);
                        if along < 0.0 {
                            // the direction swings back: this contact's c_t is too stiff
                            // for the structure behind it (it overshoots)
                            swing.scale = (swing.scale * 0.5).max(Swing::MIN);
                        } else if along > 0.0 {
                            // it turns on the same way: let it take longer steps again
                            swing.scale = (swing.scale * 2.0).min(1.0);
                        }
                        swing.last = turn;
                        Guess::slip(next)
                    } else {
                        swing.last = [0.0; 2];
                        Guess::STICK
                    }
                }
                Kind::Slip if prev.has_direction() && dot(xt, s) < 0.0 => Guess::slip(s),
                Kind::Slip if prev.has_direction() => Guess::STICK,
                Kind::Stick if rt[0].hypot(rt[1]) > g[kk] => Guess::slip(direction::<T>(rt, 0.0)),
                _ => Guess::STICK,
            }
        };
    }
}

/// The conditions one contact's guess puts on its dofs (`T + 1` components, `None` for a
/// component without a dof): held at `z` (`true`, the value) or loaded by a force (`false`,
/// the force: `g · s` on a sliding tangent, zero elsewhere, plus the adhesive springs' load).
pub(super) fn node_conditions<L: ContactLaw>(
    step: &PrimalStep<'_, L>,
    d: usize,
    kk: usize,
    guess: Guess,
    g: f64,
) -> [Option<(usize, bool, f64)>; 3] {
    let f = &step.frames[kk];
    let mut out = [None; 3];
    for (comp, o) in out.iter_mut().enumerate().take(d) {
        let Some(dof) = f.dofs[comp] else { continue };
        let held = match comp {
            0 => guess.kind != Kind::Open,
            _ => guess.kind == Kind::Stick,
        };
        // the adhesive springs' load, on a dof that is not held
        let load = step.spring_load.get(d * kk + comp).copied().unwrap_or(0.0);
        *o = Some(if held {
            (dof, true, -step.q[d * kk + comp])
        } else if comp >= 1 && guess.kind == Kind::Slip && guess.has_direction() {
            (dof, false, g * guess.direction[comp - 1] + load)
        } else {
            (dof, false, load)
        });
    }
    out
}

/// The guess `sets` as constraints of the rotated system: the Dirichlet set `mask` with its values
/// `z` (closed normals, sticking tangents) and the sliding forces `g · s` on the free
/// tangential dofs.
pub(super) fn constraints<L: ContactLaw>(
    step: &PrimalStep<'_, L>,
    d: usize,
    sets: &[Guess],
    g: &[f64],
    mask: &mut [bool],
    z: &mut [f64],
    force: &mut Vec<(usize, f64)>,
) {
    // only the contact dofs are ever set (here, and the reactions read back into `z`): clear
    // those, not all `n` (the inner iterations build a guess per small dense solve)
    for &dof in step.frames.iter().flat_map(|f| f.dofs.iter().flatten()) {
        mask[dof] = false;
        z[dof] = 0.0;
    }
    force.clear();
    for (kk, &guess) in sets.iter().enumerate() {
        for (dof, held, v) in node_conditions(step, d, kk, guess, g[kk])
            .into_iter()
            .flatten()
        {
            if held {
                mask[dof] = true;
                z[dof] = v;
            } else if v != 0.0 {
                force.push((dof, v));
            }
        }
    }
}

/// The local jumps `x = q + w` and reactions `r` of a solve: the reaction `z` on a Dirichlet dof or
/// a sliding tangent, zero elsewhere; the constrained components of `x` exactly zero.
#[allow(clippy::too_many_arguments)]
pub(super) fn read_back<L: ContactLaw>(
    step: &PrimalStep<'_, L>,
    d: usize,
    sets: &[Guess],
    mask: &[bool],
    z: &[f64],
    w: &[f64],
    r: &mut [f64],
    x: &mut [f64],
) {
    for (kk, f) in step.frames.iter().enumerate() {
        let kind = sets[kk].kind;
        for comp in 0..d {
            let j = d * kk + comp;
            match f.dofs[comp] {
                Some(dof) => {
                    x[j] = step.q[j] + w[dof];
                    r[j] = if mask[dof] || (comp >= 1 && kind == Kind::Slip) {
                        z[dof]
                    } else {
                        0.0
                    };
                }
                None => {
                    x[j] = 0.0;
                    r[j] = 0.0;
                }
            }
            let held = match comp {
                0 => kind != Kind::Open,
                _ => kind == Kind::Stick,
            };
            if held || (comp >= 1 && !step.tangent[kk]) {
                x[j] = 0.0;
            }
            if comp >= 1 && !step.tangent[kk] {
                r[j] = 0.0;
            }
        }
    }
}
