//! 3D reduced problems of an elastic half-space (`E`, `ν`) pressed by a rigid indenter: the
//! flexibility `W` of a disc of surface nodes from the closed-form point-load solutions of
//! Boussinesq (normal load) and Cerruti (tangential load), as in a boundary-element or
//! FE-condensed contact problem.
//!
//! Axes as in Johnson (1985, ch. 3): `z` points into the solid, `(x, y)` on the surface; per node
//! the frame is `[n, t₁, t₂] = [e_z, e_x, e_y]` (`n` is the indenter's outward normal, so
//! `r_n ≥ 0` presses the solid, as in `contact_laws`' crate docs). Between nodes `i ≠ j`,
//! `d = p_i − p_j`, `ρ = ‖d‖`, the displacement at `i` per unit force at `j` is
//!
//! ```text
//! normal–normal     (Boussinesq, Johnson §3.2, at z = 0):  (1 − ν²) / (π E ρ)
//! tangent–tangent   (Cerruti, Johnson ch. 3, concentrated tangential force, at z = 0):
//!                    W_xx = (1 + ν)/(π E ρ) · ((1 − ν) + ν d_x²/ρ²),   W_yy likewise,
//!                    W_xy = (1 + ν)/(π E ρ) · ν d_x d_y / ρ²
//! tangent–normal    (Boussinesq's radial displacement, Johnson §3.2, at z = 0,
//!                    u_r = −(1 − 2ν)(1 + ν) P / (2π E ρ), towards the load):
//!                    W_{x_i, z_j} = −c d_x/ρ²,   c = (1 − 2ν)(1 + ν)/(2π E)
//! normal–tangent    (Betti's reciprocity: W_{z_i, x_j} = W_{x_j, z_i}):  W_{z_i, x_j} = +c d_x/ρ²
//! ```
//! so `W` is symmetric by construction. The self terms (`ρ = 0`) are regularised by spreading
//! the unit load uniformly over a disc of the node's tributary area `h²` (grid spacing `h`),
//! radius `a_e = h/√π`, and taking the displacement at its centre: integrating the point-load
//! formulas over the disc,
//!
//! ```text
//! W_nn,ii = 2 (1 − ν²) / (π E a_e)          (Johnson eq. 3.25 at r = 0: u_z = 2(1 − ν²) p a/E)
//! W_tt,ii = (1 + ν)(2 − ν) / (π E a_e)      (Cerruti integrated: u_x = (2 − ν) q a/(2G))
//! W_nt,ii = 0                               (by symmetry)
//! ```
//! Nodes: the centres of an `n × n` grid of squares of side `h = 2a/n` covering `[−a, a]²`, kept
//! when inside the disc `ρ < a`. The indenter moves down by `δ` and sideways by `s`:
//!
//! ```text
//! q_n = g₀(ρ) − δ,  g₀ = 0 (flat punch of radius a) or ρ²/(2 R) (sphere of radius R)
//! q_t = −s          (the solid's displacement relative to the indenter, before the reactions)
//! ```
//! Check: a frictionless flat punch carries `P = 2 a E* δ`, `E* = E/(1 − ν²)` (the rigid
//! flat-ended punch, Johnson 1985 ch. 3; Sneddon 1946); `tests/integration/multibody_3d.rs`
//! compares the sum of `r_n` with it, and checks that `W` is symmetric and positive definite.

use crate::error::SolverError;
use crate::local::problem::ReducedProblem;
use std::f64::consts::PI;

/// The rigid indenter.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Indenter {
    /// A flat circular punch whose face covers the disc of nodes (initial gap 0).
    FlatPunch,
    /// A sphere of the given radius, touching the surface at the centre (gap `ρ²/(2R)`).
    Sphere {
        /// Radius `R` of the sphere.
        radius: f64,
    },
}

/// A disc of contact nodes on an elastic half-space under an indenter (see the
/// [module docs](self)); build with [`Default`] and [`generate`](Self::generate).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HalfSpace {
    /// Young's modulus `E`.
    pub young: f64,
    /// Poisson's ratio `ν` (in `[0, 0.5]`).
    pub poisson: f64,
    /// Radius `a` of the disc of nodes.
    pub radius: f64,
    /// Grid cells across the diameter (`n`; about `π n²/4` nodes).
    pub cells_across: usize,
    /// The indenter.
    pub indenter: Indenter,
    /// Indentation `δ` (downwards, into the solid).
    pub indentation: f64,
    /// Tangential displacement `s = (s_x, s_y)` of the indenter.
    pub push: [f64; 2],
    /// Friction coefficient of every node.
    pub mu: f64,
}

impl Default for HalfSpace {
    /// Steel-like units (`E = 210`, `ν = 0.3`), a unit disc on 20 cells across (316 nodes), a
    /// sphere of radius 10 pressed by `δ = 0.02` (contact radius `√(Rδ)` ≈ 0.45) and pushed by
    /// `s = (0.002, 0.001)`, `μ = 0.3`: stick, slip and open nodes together.
    fn default() -> Self {
        Self {
            young: 210.0,
            poisson: 0.3,
            radius: 1.0,
            cells_across: 20,
            indenter: Indenter::Sphere { radius: 10.0 },
            indentation: 0.02,
            push: [0.002, 0.001],
            mu: 0.3,
        }
    }
}

/// A generated half-space problem and its nodes.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct HalfSpaceProblem {
    /// The reduced problem `x = W r + q` (3D).
    pub problem: ReducedProblem,
    /// Node positions `(x, y)` on the surface.
    pub nodes: Vec<[f64; 2]>,
    /// Grid spacing `h` (each node stands for an area `h²`).
    pub spacing: f64,
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

impl HalfSpace {
    /// The nodes inside the disc and the spacing `h`.
    fn nodes(&self) -> (Vec<[f64; 2]>, f64) {
        let n = self.cells_across;
        let h = 2.0 * self.radius / n as f64;
        let mut nodes = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let p = [
                    (i as f64 + 0.5) * h - self.radius,
                    (j as f64 + 0.5) * h - self.radius,
                ];
                if p[0].hypot(p[1]) < self.radius {
                    nodes.push(p);
                }
            }
        }
        (nodes, h)
    }

    /// Builds the problem (deterministic: the grid has no randomness).
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] for a non-positive or non-finite `E`, radius, sphere
    /// radius or indentation, `ν` outside `[0, 0.5]`, fewer than 2 cells across, a negative
    /// `μ`, or a non-finite push.
    ///
    /// # Examples
    /// ```
    /// use contact_solver::local::generate::half_space::{HalfSpace, Indenter};
    /// let hs = HalfSpace { cells_across: 10, indenter: Indenter::FlatPunch, ..Default::default() };
    /// let p = hs.generate()?;
    /// assert_eq!(p.problem.contact_count(), p.nodes.len());
    /// assert_eq!(p.problem.q()[0], -hs.indentation); // flat punch: q_n = −δ
    /// assert!(HalfSpace { poisson: 0.7, ..hs }.generate().is_err());
    /// # Ok::<(), contact_solver::SolverError>(())
    /// ```
    pub fn generate(&self) -> Result<HalfSpaceProblem, SolverError> {
        check("young", self.young, self.young > 0.0, "finite and positive")?;
        let nu = self.poisson;
        check("poisson", nu, (0.0..=0.5).contains(&nu), "in [0, 0.5]")?;
        check(
            "radius",
            self.radius,
            self.radius > 0.0,
            "finite and positive",
        )?;
        let cells = self.cells_across as f64;
        check("cells_across", cells, self.cells_across >= 2, "at least 2")?;
        check(
            "indentation",
            self.indentation,
            self.indentation > 0.0,
            "finite and positive",
        )?;
        check("mu", self.mu, self.mu >= 0.0, "finite and >= 0")?;
        for s in self.push {
            check("push", s, true, "finite")?;
        }
        if let Indenter::Sphere { radius } = self.indenter {
            check(
                "indenter radius",
                radius,
                radius > 0.0,
                "finite and positive",
            )?;
        }
        let (nodes, h) = self.nodes();
        let nc = nodes.len();
        let m = 3 * nc;
        let e = self.young;
        let a_e = h / PI.sqrt();
        let c_nn = (1.0 - nu * nu) / (PI * e);
        let c_tt = (1.0 + nu) / (PI * e);
        let c_nt = (1.0 - 2.0 * nu) * (1.0 + nu) / (2.0 * PI * e);
        let mut w = vec![0.0; m * m];
        for (i, pi) in nodes.iter().enumerate() {
            for (j, pj) in nodes.iter().enumerate() {
                let blk = if i == j {
                    let (nn, tt) = (2.0 * c_nn / a_e, (1.0 + nu) * (2.0 - nu) / (PI * e * a_e));
                    [[nn, 0.0, 0.0], [0.0, tt, 0.0], [0.0, 0.0, tt]]
                } else {
                    let d = [pi[0] - pj[0], pi[1] - pj[1]];
                    let rho = d[0].hypot(d[1]);
                    let (ux, uy) = (d[0] / rho, d[1] / rho);
                    let t = c_tt / rho;
                    let nt = c_nt / rho;
                    [
                        [c_nn / rho, nt * ux, nt * uy],
                        [-nt * ux, t * ((1.0 - nu) + nu * ux * ux), t * nu * ux * uy],
                        [-nt * uy, t * nu * ux * uy, t * ((1.0 - nu) + nu * uy * uy)],
                    ]
                };
                for (a, row) in blk.iter().enumerate() {
                    w[(3 * i + a) * m + 3 * j..(3 * i + a) * m + 3 * j + 3].copy_from_slice(row);
                }
            }
        }
        let mut q = Vec::with_capacity(m);
        for p in &nodes {
            let gap = match self.indenter {
                Indenter::FlatPunch => 0.0,
                Indenter::Sphere { radius } => (p[0] * p[0] + p[1] * p[1]) / (2.0 * radius),
            };
            q.extend([gap - self.indentation, -self.push[0], -self.push[1]]);
        }
        Ok(HalfSpaceProblem {
            problem: ReducedProblem::new_3d(w, q, vec![self.mu; nc])?,
            nodes,
            spacing: h,
        })
    }
}

/// The load a rigid flat circular punch of radius `a` carries at indentation `δ`, frictionless:
/// `P = 2 a E* δ`, `E* = E/(1 − ν²)` (Johnson 1985 ch. 3, the flat-ended punch; Sneddon 1946).
///
/// # Examples
/// ```
/// use contact_solver::local::generate::half_space::flat_punch_load;
/// assert!((flat_punch_load(210.0, 0.0, 1.0, 0.01) - 4.2).abs() < 1e-12);
/// ```
pub fn flat_punch_load(young: f64, poisson: f64, radius: f64, indentation: f64) -> f64 {
    2.0 * radius * young / (1.0 - poisson * poisson) * indentation
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_space_rejects_bad_parameters() {
        let hs = HalfSpace::default();
        for bad in [
            HalfSpace { young: 0.0, ..hs },
            HalfSpace {
                poisson: -0.1,
                ..hs
            },
            HalfSpace {
                radius: f64::NAN,
                ..hs
            },
            HalfSpace {
                cells_across: 1,
                ..hs
            },
            HalfSpace {
                indentation: 0.0,
                ..hs
            },
            HalfSpace {
                indenter: Indenter::Sphere { radius: -1.0 },
                ..hs
            },
            HalfSpace {
                push: [f64::INFINITY, 0.0],
                ..hs
            },
        ] {
            assert!(matches!(
                bad.generate(),
                Err(SolverError::InvalidSetting { .. })
            ));
        }
    }

    #[test]
    fn half_space_self_terms_exceed_neighbours_works() {
        // the regularised self flexibility is larger than the point-load value at the nearest
        // neighbour (ρ = h), as a displacement field peaked under the load must be
        let p = HalfSpace::default().generate().unwrap();
        let w = p.problem.w_dense().unwrap();
        let m = p.problem.size();
        let nn_self = w[0];
        let h = p.spacing;
        let nn_next = (1.0 - 0.09) / (PI * 210.0 * h);
        assert!(nn_self > nn_next, "{nn_self} vs {nn_next}");
        assert!(w[1] == 0.0 && w[m] == 0.0);
    }
}
