//! Multibody reduced problems: rigid spheres piled in columns on a floor, inside a box, one time
//! step of a nonsmooth contact dynamics scheme (Moreau–Jean; Jean 1999, Acary–Brogliato 2008
//! for the reduced form `W = Hᵀ M⁻¹ H`).
//!
//! ```text
//! layout:   columns on an nx × ny grid of spacing s = 2R(1 + jitter); each sphere moved
//!           horizontally by jitter·R·U(−1, 1) per axis; layer 0 at z = R, layer k set on the
//!           sphere below it so they touch: z_k = z_{k−1} + √(4R² − d_h²)
//!           (d_h: their horizontal distance), so no two spheres overlap
//! contacts: every pair with gap d − 2R < threshold·R (normal from the lower-indexed sphere a to
//!           b), every sphere with the floor z = 0 and the four walls of the box
//!           [0, nx s] × [0, ny s] (normal into the box) with gap < threshold·R
//! frame:    n, t₁ = n × e / ‖n × e‖ (e: the axis least aligned with n), t₂ = n × t₁
//! unknowns: per sphere V = (v, ω) (6 dofs), M = diag(m I₃, I I₃), m = ρ 4/3 π R³, I = 2/5 m R²
//! local:    u = v_b + ω_b × (−R n) − v_a − ω_a × (R n),   x = (u·n, u·t₁, u·t₂) = Hᵀ V
//! reduced:  x = W r + q,   W = Hᵀ M⁻¹ H   (the Delassus operator, 3 n_c × 3 n_c)
//!           q = Hᵀ (V₀ + h M⁻¹ f_ext) + (max(gap, 0)/h) e_n,   f_ext = −m g e_z
//! ```
//! `r` is the impulse over the step on sphere `b` (and `−r` on `a`); `r_n ≥ 0` pushes them apart
//! (the signs of `contact_laws`' crate docs, with the reaction as an impulse and `x` a
//! velocity). `W` is positive semi-definite, of rank `rank(H) ≤ 6 n_b`: rank-deficient as soon as
//! `3 n_c > 6 n_b` (a hyperstatic pile), and then the impulses are not unique, only
//! `H r` (the generalized impulse, hence the velocities `V = V₀ + h M⁻¹ f_ext + M⁻¹ H r`) is.
//! The generator computes `rank(H)` (eigenvalues of the smaller of `GᵀG` and `GGᵀ`,
//! `G = M^{-1/2} H`, with faer).

#![allow(clippy::needless_range_loop)] // 6×3 blocks indexed by component read as the formulas

use super::SplitMix64;
use crate::error::SolverError;
use crate::local::problem::ReducedProblem;
use faer::{Mat, Side};

/// What a contact of a [`SpherePile`] touches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ContactKind {
    /// Two spheres: the impulse acts on `b`, its opposite on `a` (`a < b`).
    Spheres {
        /// The first sphere (the impulse on it is `−r`).
        a: usize,
        /// The second sphere (the impulse on it is `r`).
        b: usize,
    },
    /// A sphere and the floor `z = 0`.
    Floor {
        /// The sphere.
        body: usize,
    },
    /// A sphere and one of the box's four side walls (`wall` 0..4: `x = 0`, `x = L_x`, `y = 0`,
    /// `y = L_y`).
    Wall {
        /// The sphere.
        body: usize,
        /// Which wall.
        wall: usize,
    },
}

/// Side walls around the pile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Walls {
    /// Floor only.
    None,
    /// The floor and four side walls `[0, L_x] × [0, L_y]`.
    Box,
}

/// One contact: what it touches, its frame `[n, t₁, t₂]` and its gap at the start of the step.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct PileContact {
    /// What it touches.
    pub kind: ContactKind,
    /// `[n, t₁, t₂]`, orthonormal, `n` from `a` to `b` (or from the wall into the box).
    pub frame: [[f64; 3]; 3],
    /// The gap (distance between surfaces) at the start of the step.
    pub gap: f64,
}

/// A pile of rigid spheres in columns (see the [module docs](self)); build one with
/// [`Default`] and [`generate`](Self::generate) it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpherePile {
    /// Columns along x.
    pub nx: usize,
    /// Columns along y.
    pub ny: usize,
    /// Spheres per column.
    pub layers: usize,
    /// Radius of every sphere.
    pub radius: f64,
    /// Mass density.
    pub density: f64,
    /// Horizontal disorder, as a fraction of `R` (in `[0, 0.5]`): 0 stacks perfect columns.
    pub jitter: f64,
    /// Contacts are kept when their gap is below `threshold·R`.
    pub threshold: f64,
    /// Friction coefficient of every contact.
    pub mu: f64,
    /// Time step `h`.
    pub time_step: f64,
    /// Gravity `g` (along `−z`).
    pub gravity: f64,
    /// Largest initial speed of a sphere (each gets a seeded random translation and rotation
    /// velocity with components in `[−v, v]`, rotations scaled by `1/R`); 0: at rest.
    pub initial_speed: f64,
    /// Side walls or not.
    pub walls: Walls,
}

impl Default for SpherePile {
    /// A 4 × 4 × 4 pile of unit spheres (density 1) in a box, `μ = 0.5`, `h = 0.01`,
    /// `g = 9.81`, no jitter, at rest, threshold `0.1 R`.
    fn default() -> Self {
        Self {
            nx: 4,
            ny: 4,
            layers: 4,
            radius: 1.0,
            density: 1.0,
            jitter: 0.0,
            threshold: 0.1,
            mu: 0.5,
            time_step: 0.01,
            gravity: 9.81,
            initial_speed: 0.0,
            walls: Walls::Box,
        }
    }
}

/// A generated multibody problem and what it was built from.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct PileProblem {
    /// The reduced problem `x = W r + q` (3D, `μ` per contact).
    pub problem: ReducedProblem,
    /// Sphere centres.
    pub centers: Vec<[f64; 3]>,
    /// The contacts, in the problem's order.
    pub contacts: Vec<PileContact>,
    /// Mass of one sphere.
    pub mass: f64,
    /// Rank of `H` (and of `W`).
    pub rank: usize,
    /// `3 n_c − rank`: the dimension of the impulses that `W` does not see.
    pub rank_deficiency: usize,
    /// The radius (for the lever arms).
    radius: f64,
}

impl PileProblem {
    /// Number of spheres.
    pub fn body_count(&self) -> usize {
        self.centers.len()
    }

    /// The generalized impulse `H r` (per sphere: force then moment about its centre, 6 entries).
    ///
    /// # Examples
    /// ```
    /// use contact_solver::local::generate::multibody::{SpherePile, Walls};
    /// use contact_solver::{UzawaSettings, solve_coulomb};
    /// // one sphere on the floor: the floor's impulse cancels the weight's, h m g
    /// let s = SpherePile { nx: 1, ny: 1, layers: 1, walls: Walls::None, ..Default::default() };
    /// let pile = s.generate(0)?;
    /// let sol = solve_coulomb(&pile.problem, &UzawaSettings::default())?;
    /// let hr = pile.generalized_impulse(&sol.r);
    /// assert!((hr[2] - s.time_step * pile.mass * s.gravity).abs() < 1e-9);
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    ///
    /// # Panics
    /// If `r.len() != 3 n_c`.
    #[track_caller]
    pub fn generalized_impulse(&self, r: &[f64]) -> Vec<f64> {
        assert_eq!(
            r.len(),
            3 * self.contacts.len(),
            "r has 3 entries per contact"
        );
        let mut out = vec![0.0; 6 * self.centers.len()];
        for (k, c) in self.contacts.iter().enumerate() {
            let f: [f64; 3] =
                std::array::from_fn(|d| (0..3).map(|a| r[3 * k + a] * c.frame[a][d]).sum());
            for (body, sign, lever) in ends(self.radius, c) {
                let m = cross(lever, f);
                for d in 0..3 {
                    out[6 * body + d] += sign * f[d];
                    out[6 * body + 3 + d] += sign * m[d];
                }
            }
        }
        out
    }
}

/// The bodies a contact touches: (body, sign of the impulse on it, lever arm).
fn ends(radius: f64, c: &PileContact) -> Vec<(usize, f64, [f64; 3])> {
    let n = c.frame[0];
    let rn = [radius * n[0], radius * n[1], radius * n[2]];
    let neg = [-rn[0], -rn[1], -rn[2]];
    match c.kind {
        ContactKind::Spheres { a, b } => vec![(a, -1.0, rn), (b, 1.0, neg)],
        ContactKind::Floor { body } | ContactKind::Wall { body, .. } => vec![(body, 1.0, neg)],
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// `[n, t₁, t₂]` with `t₁ = n × e/‖n × e‖`, `e` the axis least aligned with `n`.
fn frame(n: [f64; 3]) -> [[f64; 3]; 3] {
    let mut axis = 0;
    for d in 1..3 {
        if n[d].abs() < n[axis].abs() {
            axis = d;
        }
    }
    let mut e = [0.0; 3];
    e[axis] = 1.0;
    let t1 = normalize(cross(n, e));
    [n, t1, cross(n, t1)]
}

fn check(
    what: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<(), SolverError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(SolverError::InvalidSetting {
            what,
            value,
            expected,
        })
    }
}

impl SpherePile {
    fn validate(&self) -> Result<(), SolverError> {
        for (what, n) in [("nx", self.nx), ("ny", self.ny), ("layers", self.layers)] {
            check(what, n as f64, n > 0, "at least 1")?;
        }
        check(
            "radius",
            self.radius,
            self.radius > 0.0,
            "finite and positive",
        )?;
        check(
            "density",
            self.density,
            self.density > 0.0,
            "finite and positive",
        )?;
        check(
            "jitter",
            self.jitter,
            (0.0..=0.5).contains(&self.jitter),
            "in [0, 0.5]",
        )?;
        check(
            "threshold",
            self.threshold,
            self.threshold >= 0.0,
            "finite and >= 0",
        )?;
        check("mu", self.mu, self.mu >= 0.0, "finite and >= 0")?;
        check(
            "time_step",
            self.time_step,
            self.time_step > 0.0,
            "finite and positive",
        )?;
        check("gravity", self.gravity, true, "finite")?;
        check(
            "initial_speed",
            self.initial_speed,
            self.initial_speed >= 0.0,
            "finite and >= 0",
        )
    }

    /// The sphere centres (see the [module docs](self)).
    fn centers(&self, g: &mut SplitMix64) -> Vec<[f64; 3]> {
        let r = self.radius;
        let s = 2.0 * r * (1.0 + self.jitter);
        let mut centers = Vec::with_capacity(self.nx * self.ny * self.layers);
        for i in 0..self.nx {
            for j in 0..self.ny {
                let mut below: Option<[f64; 3]> = None;
                for _ in 0..self.layers {
                    let x = s * (i as f64 + 0.5) + self.jitter * r * g.uniform(-1.0, 1.0);
                    let y = s * (j as f64 + 0.5) + self.jitter * r * g.uniform(-1.0, 1.0);
                    let z = match below {
                        None => r,
                        Some(c) => {
                            let dh2 = (x - c[0]).powi(2) + (y - c[1]).powi(2);
                            c[2] + (4.0 * r * r - dh2).sqrt()
                        }
                    };
                    below = Some([x, y, z]);
                    centers.push([x, y, z]);
                }
            }
        }
        centers
    }

    /// Builds the problem with the seed `seed` (jitter and initial velocities).
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] for a zero count, a non-positive or non-finite radius,
    /// density or time step, a jitter outside `[0, 0.5]`, a negative threshold, `μ` or initial
    /// speed, or a NaN anywhere; [`SolverError::InvalidGeometry`] when no contact is found.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::local::generate::multibody::SpherePile;
    /// // 2 × 2 columns of 3 unit spheres, no side walls: 4 floor contacts, 8 in the columns,
    /// // 12 between neighbouring columns (touching, not pressed).
    /// let pile = SpherePile { nx: 2, ny: 2, layers: 3, walls: contact_solver::local::generate::multibody::Walls::None, ..Default::default() };
    /// let p = pile.generate(1)?;
    /// assert_eq!((p.body_count(), p.problem.contact_count()), (12, 24));
    /// assert_eq!(p.rank + p.rank_deficiency, 72);
    /// assert!(SpherePile { radius: -1.0, ..pile }.generate(1).is_err());
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn generate(&self, seed: u64) -> Result<PileProblem, SolverError> {
        self.validate()?;
        let mut g = SplitMix64::new(seed);
        let centers = self.centers(&mut g);
        let r = self.radius;
        let nb = centers.len();
        let mass = self.density * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
        let inertia = 0.4 * mass * r * r;
        // V after the free step: V₀ + h M⁻¹ f_ext
        let v = self.initial_speed;
        let free: Vec<[f64; 6]> = (0..nb)
            .map(|_| {
                std::array::from_fn(|d| {
                    let u = v * g.uniform(-1.0, 1.0);
                    match d {
                        0..=1 => u,
                        2 => u - self.time_step * self.gravity,
                        _ => u / r,
                    }
                })
            })
            .collect();
        let contacts = self.contacts(&centers);
        if contacts.is_empty() {
            return Err(SolverError::InvalidGeometry(
                "the sphere pile has no contact below the threshold".into(),
            ));
        }
        // J[k]: per end (body, 6×3 block of H: rows (v, ω), columns (n, t₁, t₂)).
        let jac: Vec<Vec<(usize, [[f64; 3]; 6])>> = contacts
            .iter()
            .map(|c| {
                ends(r, c)
                    .into_iter()
                    .map(|(body, sign, lever)| {
                        let mut blk = [[0.0; 3]; 6];
                        for a in 0..3 {
                            let e = c.frame[a];
                            let m = cross(lever, e);
                            for d in 0..3 {
                                blk[d][a] = sign * e[d];
                                blk[3 + d][a] = sign * m[d];
                            }
                        }
                        (body, blk)
                    })
                    .collect()
            })
            .collect();
        let nc = contacts.len();
        let m = 3 * nc;
        let inv = [1.0 / mass, 1.0 / inertia];
        // contacts of each body
        let mut of_body: Vec<Vec<(usize, usize)>> = vec![Vec::new(); nb];
        for (k, ends) in jac.iter().enumerate() {
            for (e, &(body, _)) in ends.iter().enumerate() {
                of_body[body].push((k, e));
            }
        }
        let mut w = vec![0.0; m * m];
        for list in &of_body {
            for &(k, ek) in list {
                let bk = &jac[k][ek].1;
                for &(l, el) in list {
                    let bl = &jac[l][el].1;
                    for a in 0..3 {
                        for b in 0..3 {
                            let s: f64 = (0..6).map(|d| inv[d / 3] * bk[d][a] * bl[d][b]).sum();
                            w[(3 * k + a) * m + 3 * l + b] += s;
                        }
                    }
                }
            }
        }
        let mut q = vec![0.0; m];
        for (k, ends) in jac.iter().enumerate() {
            for &(body, ref blk) in ends {
                for a in 0..3 {
                    q[3 * k + a] += (0..6).map(|d| blk[d][a] * free[body][d]).sum::<f64>();
                }
            }
            q[3 * k] += contacts[k].gap.max(0.0) / self.time_step;
        }
        // rank(H) = rank(G), G = M^{-1/2} H: from the smaller Gram matrix
        let rank = if m <= 6 * nb {
            rank_of(&Mat::from_fn(m, m, |i, j| w[i * m + j]))
        } else {
            let mut ggt = Mat::<f64>::zeros(6 * nb, 6 * nb);
            for ends in &jac {
                for &(bi, ref bk) in ends {
                    for &(bj, ref bl) in ends {
                        for d in 0..6 {
                            for e in 0..6 {
                                let s: f64 = (0..3).map(|a| bk[d][a] * bl[e][a]).sum();
                                ggt[(6 * bi + d, 6 * bj + e)] +=
                                    (inv[d / 3] * inv[e / 3]).sqrt() * s;
                            }
                        }
                    }
                }
            }
            rank_of(&ggt)
        };
        Ok(PileProblem {
            problem: ReducedProblem::new_3d(w, q, vec![self.mu; nc])?,
            centers,
            contacts,
            mass,
            rank,
            rank_deficiency: m - rank,
            radius: r,
        })
    }

    /// Every pair, floor and wall contact with a gap below `threshold·R`.
    fn contacts(&self, centers: &[[f64; 3]]) -> Vec<PileContact> {
        let r = self.radius;
        let cut = self.threshold * r;
        let s = 2.0 * r * (1.0 + self.jitter);
        let (lx, ly) = (s * self.nx as f64, s * self.ny as f64);
        let mut out = Vec::new();
        for (b, c) in centers.iter().enumerate() {
            if c[2] - r < cut {
                out.push(PileContact {
                    kind: ContactKind::Floor { body: b },
                    frame: frame([0.0, 0.0, 1.0]),
                    gap: c[2] - r,
                });
            }
            if self.walls == Walls::Box {
                let walls = [
                    (c[0] - r, [1.0, 0.0, 0.0]),
                    (lx - c[0] - r, [-1.0, 0.0, 0.0]),
                    (c[1] - r, [0.0, 1.0, 0.0]),
                    (ly - c[1] - r, [0.0, -1.0, 0.0]),
                ];
                for (wall, (gap, n)) in walls.into_iter().enumerate() {
                    if gap < cut {
                        out.push(PileContact {
                            kind: ContactKind::Wall { body: b, wall },
                            frame: frame(n),
                            gap,
                        });
                    }
                }
            }
            for (a, ca) in centers[..b].iter().enumerate() {
                let d = [c[0] - ca[0], c[1] - ca[1], c[2] - ca[2]];
                let dist = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                if dist - 2.0 * r < cut {
                    out.push(PileContact {
                        kind: ContactKind::Spheres { a, b },
                        frame: frame([d[0] / dist, d[1] / dist, d[2] / dist]),
                        gap: dist - 2.0 * r,
                    });
                }
            }
        }
        out
    }
}

/// Numerical rank of a symmetric positive semi-definite matrix: eigenvalues above
/// `1e-10 · λ_max` (the Gram matrices here have entries of one scale, so round-off eigenvalues
/// sit near `1e-16 λ_max`).
fn rank_of(a: &Mat<f64>) -> usize {
    match a.self_adjoint_eigenvalues(Side::Lower) {
        Ok(ev) => {
            let top = ev.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            ev.iter().filter(|&&v| v > 1e-10 * top).count()
        }
        // an eigen solver that fails is reported as full rank, the bound `min(3 n_c, 6 n_b)`
        Err(_) => a.nrows(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pile_rejects_bad_parameters() {
        let p = SpherePile::default();
        for bad in [
            SpherePile { nx: 0, ..p },
            SpherePile { radius: 0.0, ..p },
            SpherePile {
                density: f64::NAN,
                ..p
            },
            SpherePile { jitter: 0.7, ..p },
            SpherePile {
                time_step: -1.0,
                ..p
            },
            SpherePile { mu: -0.1, ..p },
        ] {
            assert!(matches!(
                bad.generate(0),
                Err(SolverError::InvalidSetting { .. })
            ));
        }
    }

    #[test]
    fn pile_is_deterministic_and_frames_orthonormal_works() {
        let pile = SpherePile {
            jitter: 0.2,
            initial_speed: 0.1,
            ..SpherePile::default()
        };
        let (a, b) = (pile.generate(5).unwrap(), pile.generate(5).unwrap());
        assert_eq!(a.problem.w_dense(), b.problem.w_dense());
        assert_eq!(a.problem.q(), b.problem.q());
        for c in &a.contacts {
            assert!(c.gap > -1e-12, "no overlap: {}", c.gap);
            for i in 0..3 {
                for j in 0..3 {
                    let d: f64 = (0..3).map(|k| c.frame[i][k] * c.frame[j][k]).sum();
                    assert!((d - f64::from(u8::from(i == j))).abs() < 1e-14);
                }
            }
        }
    }
}
