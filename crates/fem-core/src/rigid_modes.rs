//! Rigid-body modes left by the supports (floating bodies) and the dofs pinned to build a
//! generalized inverse `K⁺`.
//!
//! A body that its supports do not hold has a stiffness `K` (over the free dofs) with a kernel
//! spanned by rigid-body motions. In the plane they are the two translations and the rotation
//! `(−y, x)`; in axisymmetry only the axial translation (a radial translation strains the hoop
//! direction); in 3D the three translations and the three rotations `e_a × x`. Each connected
//! component of the mesh (nodes joined by elements) is a body of its own. The modes a body
//! keeps are those its prescribed dofs do not see and that move the nodes of a tie
//! ([`Supports::tie`](crate::Supports::tie)) alike: with `C` the matrix of the body's
//! candidate modes at its prescribed dofs, and of their differences between tied nodes
//! (`p × k`, `k ≤ 6`), they are `null(C)`.
//!
//! ```text
//! plane:        R_body = [ t_x  t_y  ω ],  t_x = (1, 0),  t_y = (0, 1),
//!               ω(x) = (−(y − c_y), x − c_x) / ρ     (c the centroid, ρ the largest distance to it)
//! axisymmetric: R_body = [ t_z ]
//! 3D:           R_body = [ t_x  t_y  t_z  ω_x  ω_y  ω_z ],  ω_a(x) = e_a × (x − c) / ρ
//! modes kept:   R_body N,   N a basis of null(C),   restricted to the free dofs
//! ```
//!
//! `K⁺` (Farhat & Roux 1991, the FETI "floating subdomain"; Farhat & Géradin 1998): pin as
//! many free dofs `P` as there are modes, chosen so that `R_P` (the modes at the pinned dofs)
//! is well conditioned, and invert the rest, `K⁺ = [K_SS⁻¹ 0; 0 0]`. For a balanced `b`
//! (`Rᵀ b = 0`), `K K⁺ b = b`: with `K R = 0`, `K_PS = −R_P⁻ᵀ R_Sᵀ K_SS`, so
//! `K_PS K_SS⁻¹ b_S = −R_P⁻ᵀ R_Sᵀ b_S = b_P`. The pinned dofs are picked greedily, each the
//! row of `R` farthest from the span of the rows already picked (a pivoted Gram–Schmidt on the
//! rows), which picks far-apart nodes.
//!
//! The zero-padded inverse vanishes at the pinned dofs, so a contact at a pinned node would
//! have no flexibility. [`LinearElasticModel`](crate::LinearElasticModel) therefore applies the
//! projected inverse `P K⁺ P`, `P = I − Q Qᵀ` (`Q` an orthonormal basis of the modes): still a
//! symmetric generalized inverse (`K P = K`, and `P b = b` for a balanced `b`), whose answers
//! are orthogonal to the modes and whose flexibility is positive at every node that is not
//! rigidly tied to the pins.

use crate::dirichlet::{Component, Dof, DofMap};
use crate::element::Setting;
use crate::error::FemError;
use crate::idealization::Idealization;
use crate::space::{Dim, Space};
use nalgebra::DMatrix;

/// The geometric meaning of a rigid-body mode (its nodal displacement field).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum RigidMotion {
    /// `u = d` at every node of the body, `d` a unit vector (`(1, 0)`: along x or r; `(0, 1)`:
    /// along y or z).
    Translation {
        /// The unit direction.
        direction: [f64; 2],
    },
    /// `u(x) = (−(y − c_y), x − c_x) / ρ`: a rotation about `centre`, scaled so that a node at
    /// distance `ρ` from the centre moves by 1. The generalized force along it is a moment
    /// divided by `ρ`.
    Rotation {
        /// Centre of rotation.
        centre: [f64; 2],
        /// The scale `ρ` (the body's size).
        radius: f64,
    },
    /// `u = d` at every node of a 3D body, `d` a unit vector in space (`(0, 0, 1)`: along z).
    /// The plane's translations are [`Translation`](Self::Translation).
    SpaceTranslation {
        /// The unit direction.
        direction: [f64; 3],
    },
    /// A mode given by a structure without a geometric description (in 3D: a rotation, or a
    /// mode that mixes rotation and translation).
    Other,
}

impl core::fmt::Display for RigidMotion {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            RigidMotion::Translation {
                direction: [1.0, 0.0],
            } => f.write_str("translation x"),
            RigidMotion::Translation {
                direction: [0.0, 1.0],
            } => f.write_str("translation y"),
            RigidMotion::Translation { direction } => {
                write!(
                    f,
                    "translation along ({:.3}, {:.3})",
                    direction[0], direction[1]
                )
            }
            RigidMotion::Rotation { centre, .. } => {
                write!(f, "rotation about ({:.4e}, {:.4e})", centre[0], centre[1])
            }
            RigidMotion::SpaceTranslation { direction } => match direction {
                [1.0, 0.0, 0.0] => f.write_str("translation x"),
                [0.0, 1.0, 0.0] => f.write_str("translation y"),
                [0.0, 0.0, 1.0] => f.write_str("translation z"),
                [x, y, z] => write!(f, "translation along ({x:.3}, {y:.3}, {z:.3})"),
            },
            RigidMotion::Other => f.write_str("rigid-body mode"),
        }
    }
}

/// One rigid-body mode: the body (connected component) it moves and its motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidMode {
    /// The body: index of the connected component (in order of its lowest node).
    pub body: usize,
    /// What it is.
    pub motion: RigidMotion,
}

/// The rigid-body modes of a structure over its free dofs: the columns of `R` (`K R = 0`) with
/// their meaning.
///
/// # Examples
/// ```
/// use fem_core::{RigidBodyModes, RigidMode, RigidMotion};
/// // two free dofs (one node), the x translation
/// let t_x = RigidMode { body: 0, motion: RigidMotion::Translation { direction: [1.0, 0.0] } };
/// let modes = RigidBodyModes::new(2, vec![1.0, 0.0], vec![t_x])?;
/// assert_eq!(modes.len(), 1);
/// assert_eq!(modes.column(0), &[1.0, 0.0]);
/// # Ok::<(), fem_core::FemError>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RigidBodyModes {
    dof_count: usize,
    /// Column-major `dof_count × modes.len()`.
    values: Vec<f64>,
    modes: Vec<RigidMode>,
}

impl RigidBodyModes {
    /// Modes given as the columns of `values` (column-major, `dof_count` rows) with their
    /// meaning.
    ///
    /// # Errors
    /// [`FemError::LengthMismatch`] if `values` does not hold `dof_count × modes.len()`
    /// entries; [`FemError::InvalidParameter`] for a non-finite entry.
    pub fn new(
        dof_count: usize,
        values: Vec<f64>,
        modes: Vec<RigidMode>,
    ) -> Result<Self, FemError> {
        if values.len() != dof_count * modes.len() {
            return Err(FemError::LengthMismatch {
                what: "rigid-body mode values",
                expected: dof_count * modes.len(),
                got: values.len(),
            });
        }
        if let Some(&value) = values.iter().find(|v| !v.is_finite()) {
            return Err(FemError::InvalidParameter {
                name: "rigid-body mode",
                value,
                expected: "finite values",
            });
        }
        Ok(Self {
            dof_count,
            values,
            modes,
        })
    }

    /// Number of modes.
    #[inline]
    pub fn len(&self) -> usize {
        self.modes.len()
    }

    /// `true` without modes.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.modes.is_empty()
    }

    /// Number of rows (free dofs).
    #[inline]
    pub fn dof_count(&self) -> usize {
        self.dof_count
    }

    /// The meaning of every mode.
    #[inline]
    pub fn modes(&self) -> &[RigidMode] {
        &self.modes
    }

    /// Mode `j` over the free dofs.
    ///
    /// # Panics
    /// If `j >= len()`.
    #[inline]
    #[track_caller]
    pub fn column(&self, j: usize) -> &[f64] {
        &self.values[j * self.dof_count..(j + 1) * self.dof_count]
    }

    /// The generalized force along each mode, `out = Rᵀ f`.
    ///
    /// # Panics
    /// If `f.len() != dof_count()` or `out.len() != len()`.
    #[track_caller]
    pub fn project_into(&self, f: &[f64], out: &mut [f64]) {
        assert_eq!(f.len(), self.dof_count, "force length");
        assert_eq!(out.len(), self.len(), "output length");
        for (j, o) in out.iter_mut().enumerate() {
            *o = self.column(j).iter().zip(f).map(|(a, b)| a * b).sum();
        }
    }

    /// An orthonormal basis `Q` of the modes' span (modified Gram–Schmidt, twice), column-major
    /// `dof_count × len()`: what [`project_out`] takes.
    pub fn orthonormal_basis(&self) -> Vec<f64> {
        let n = self.dof_count;
        let mut q = self.values.clone();
        for j in 0..self.len() {
            for _ in 0..2 {
                for i in 0..j {
                    let (done, rest) = q.split_at_mut(j * n);
                    let qi = &done[i * n..(i + 1) * n];
                    let qj = &mut rest[..n];
                    let d: f64 = qi.iter().zip(qj.iter()).map(|(a, b)| a * b).sum();
                    qj.iter_mut().zip(qi).for_each(|(b, a)| *b -= d * a);
                }
            }
            let col = &mut q[j * n..(j + 1) * n];
            let norm = col.iter().map(|a| a * a).sum::<f64>().sqrt();
            if norm > 0.0 {
                col.iter_mut().for_each(|a| *a /= norm);
            }
        }
        q
    }

    /// `count` dofs to pin for a generalized inverse: per body, the rows of `R` picked by a
    /// pivoted Gram–Schmidt (each the row farthest from the span of those picked), so that
    /// `R` at the pinned dofs is invertible and well conditioned.
    pub fn pinned_dofs(&self) -> Vec<usize> {
        let mut pinned = Vec::with_capacity(self.len());
        let mut bodies: Vec<usize> = self.modes.iter().map(|m| m.body).collect();
        bodies.dedup();
        for body in bodies {
            let cols: Vec<usize> = (0..self.len())
                .filter(|&j| self.modes[j].body == body)
                .collect();
            let k = cols.len();
            let mut basis: Vec<Vec<f64>> = Vec::with_capacity(k);
            for _ in 0..k {
                // (squared norm, dof, row of R projected off the basis) of the farthest row
                let mut best: Option<(f64, usize, Vec<f64>)> = None;
                for i in 0..self.dof_count {
                    if pinned.contains(&i) {
                        continue;
                    }
                    let mut row: Vec<f64> = cols.iter().map(|&j| self.column(j)[i]).collect();
                    for q in &basis {
                        let d: f64 = q.iter().zip(&row).map(|(a, b)| a * b).sum();
                        row.iter_mut().zip(q).for_each(|(r, a)| *r -= d * a);
                    }
                    let norm = row.iter().map(|a| a * a).sum::<f64>();
                    if norm > best.as_ref().map_or(0.0, |b| b.0) {
                        best = Some((norm, i, row));
                    }
                }
                let Some((norm, i, mut row)) = best else {
                    break;
                };
                let norm = norm.sqrt();
                row.iter_mut().for_each(|r| *r /= norm);
                basis.push(row);
                pinned.push(i);
            }
        }
        pinned
    }
}

/// `b ← (I − Q Qᵀ) b`: removes from `b` its part along the modes (`q` from
/// [`RigidBodyModes::orthonormal_basis`], column-major with `b.len()` rows). Allocation-free.
///
/// # Panics
/// If `q.len()` is not a multiple of `b.len()`.
#[track_caller]
pub fn project_out(q: &[f64], b: &mut [f64]) {
    let n = b.len();
    if n == 0 {
        return;
    }
    assert_eq!(q.len() % n, 0, "basis length");
    for col in q.chunks_exact(n) {
        let d: f64 = col.iter().zip(b.iter()).map(|(a, c)| a * c).sum();
        if d != 0.0 {
            b.iter_mut().zip(col).for_each(|(c, a)| *c -= d * a);
        }
    }
}

/// Relative size below which an eigenvalue of `CᵀC` counts as zero (a mode the supports leave).
const NULL_TOL: f64 = 1e-12;

/// The rigid-body modes that the supports of `dofs` leave on `mesh`, per connected component:
/// among the `D` translations and the `D(D−1)/2` rotations (the axial translation alone in
/// axisymmetry). In 3D the rotation `a` turns the plane `(a+1, a+2)` (mod 3), i.e. about the
/// axis `e_a`; a mode kept that is a pure translation is described as
/// [`RigidMotion::SpaceTranslation`] (its direction with a positive first non-zero component,
/// snapped onto an axis to round-off), any other as [`RigidMotion::Other`].
///
/// # Errors
/// [`FemError::NotPositiveDefinite`] for a node with a free dof that no element connects (its
/// kernel is not a rigid-body mode).
pub(crate) fn mesh_modes<'a, const D: usize>(
    nodes: &[[f64; D]],
    cells: impl IntoIterator<Item = &'a [usize]>,
    setting: Setting<D>,
    dofs: &DofMap<D>,
) -> Result<RigidBodyModes, FemError>
where
    Dim<D>: Space,
{
    let n = nodes.len();
    // connected components by union–find over the elements' nodes
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut used = vec![false; n];
    for cell in cells {
        for &node in cell {
            used[node] = true;
            let (a, b) = (root(&mut parent, cell[0]), root(&mut parent, node));
            if a != b {
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    if let Some(node) = (0..n).find(|&i| !used[i] && dofs.free_dofs(i).iter().any(Option::is_some))
    {
        let (c, row) = dofs
            .free_dofs(node)
            .iter()
            .enumerate()
            .find_map(|(c, d)| d.map(|r| (c, r)))
            .expect("a free dof");
        return Err(FemError::NotPositiveDefinite {
            node,
            component: Component::all::<D>()[c],
            row,
        });
    }
    let mut body_of = vec![usize::MAX; n];
    let mut bodies: Vec<Vec<usize>> = Vec::new();
    for i in 0..n {
        if !used[i] {
            continue;
        }
        let r = root(&mut parent, i);
        if body_of[r] == usize::MAX {
            body_of[r] = bodies.len();
            bodies.push(Vec::new());
        }
        let b = body_of[r];
        body_of[i] = b;
        bodies[b].push(i);
    }
    // ties: a free dof shared by several (node, component) must move them alike
    let ndof = dofs.free_count();
    let mut first_owner = vec![(usize::MAX, 0usize); ndof];
    let mut tie_pairs: Vec<Vec<[(usize, usize); 2]>> = vec![Vec::new(); bodies.len()];
    for node in 0..n {
        for (c, d) in dofs.free_dofs(node).into_iter().enumerate() {
            let Some(i) = d else { continue };
            let (first, fc) = first_owner[i];
            if first == usize::MAX {
                first_owner[i] = (node, c);
            } else if body_of[first] != body_of[node] {
                return Err(FemError::InvalidTie {
                    component: Component::all::<D>()[c],
                    node: Some(node),
                    reason: "the tie joins two bodies (parts of the mesh no element connects): \
                             tie nodes of one body only",
                });
            } else {
                tie_pairs[body_of[node]].push([(first, fc), (node, c)]);
            }
        }
    }
    let plane = !matches!(
        <Dim<D> as Space>::idealization(&setting),
        Some(Idealization::Axisymmetric)
    );
    let k = if plane { D + D * (D - 1) / 2 } else { 1 };
    let mut values = Vec::new();
    let mut modes = Vec::new();
    for (body, members) in bodies.iter().enumerate() {
        let count = members.len() as f64;
        let centre = members.iter().fold([0.0; D], |mut c, &i| {
            for a in 0..D {
                c[a] += nodes[i][a] / count;
            }
            c
        });
        let distance = |x: [f64; D]| match D {
            2 => (x[0] - centre[0]).hypot(x[1] - centre[1]),
            _ => (0..D)
                .map(|a| (x[a] - centre[a]).powi(2))
                .sum::<f64>()
                .sqrt(),
        };
        let radius = members
            .iter()
            .map(|&i| distance(nodes[i]))
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        // the candidate modes' value at (node, component): coefficients (t_x, t_y, ω) in the
        // plane, (t_x, t_y, t_z, ω_x, ω_y, ω_z) in 3D, (t_z) in axisymmetry
        let base = |node: usize, c: usize| -> [f64; 6] {
            let mut row = [0.0; 6];
            if !plane {
                row[0] = if c == 1 { 1.0 } else { 0.0 };
                return row;
            }
            row[c] = 1.0;
            let x = nodes[node];
            for r in 0..k - D {
                // rotation in the plane (i, j): u_i = −(x_j − c_j)/ρ, u_j = (x_i − c_i)/ρ
                let (i, j) = if D == 2 {
                    (0, 1)
                } else {
                    ((r + 1) % 3, (r + 2) % 3)
                };
                if c == i {
                    row[D + r] = -(x[j] - centre[j]) / radius;
                } else if c == j {
                    row[D + r] = (x[i] - centre[i]) / radius;
                }
            }
            row
        };
        let mut ctc = DMatrix::<f64>::zeros(k, k);
        let mut rows = 0usize;
        let mut add_row = |row: &[f64]| {
            rows += 1;
            for a in 0..k {
                for b in 0..k {
                    ctc[(a, b)] += row[a] * row[b];
                }
            }
        };
        for &node in members {
            for (c, d) in dofs.dofs(node).into_iter().enumerate() {
                if let Dof::Prescribed(_) = d {
                    add_row(&base(node, c));
                }
            }
        }
        for &[(a, ca), (b, cb)] in &tie_pairs[body] {
            let (ra, rb) = (base(a, ca), base(b, cb));
            let row: Vec<f64> = (0..k).map(|m| rb[m] - ra[m]).collect();
            if row.iter().any(|v| *v != 0.0) {
                add_row(&row);
            }
        }
        let null: Vec<Vec<f64>> = if rows == 0 {
            (0..k)
                .map(|a| (0..k).map(|b| f64::from(a == b)).collect())
                .collect()
        } else {
            let eig = ctc.symmetric_eigen();
            let top = eig.eigenvalues.iter().fold(0.0_f64, |m, &v| m.max(v));
            (0..k)
                .filter(|&a| eig.eigenvalues[a] <= NULL_TOL * top)
                .map(|a| eig.eigenvectors.column(a).iter().copied().collect())
                .collect()
        };
        let coefs: Vec<(Vec<f64>, RigidMotion)> = if D == 2 {
            canonical(&null, plane)
                .into_iter()
                .map(|coef| {
                    (
                        coef[..k].to_vec(),
                        plane_motion(coef, plane, centre, radius),
                    )
                })
                .collect()
        } else {
            null.into_iter().map(space_motion).collect()
        };
        for (coef, motion) in coefs {
            let start = values.len();
            values.resize(start + ndof, 0.0);
            for &node in members {
                for (c, d) in dofs.free_dofs(node).into_iter().enumerate() {
                    if let Some(i) = d {
                        let row = base(node, c);
                        values[start + i] = (0..k).map(|a| row[a] * coef[a]).sum();
                    }
                }
            }
            modes.push(RigidMode { body, motion });
        }
    }
    RigidBodyModes::new(ndof, values, modes)
}

/// The meaning of a plane mode with coefficients `coef` on `(t_x, t_y, ω)` (`centre` and
/// `radius` of the body's rotation; only the axial translation in axisymmetry).
fn plane_motion<const D: usize>(
    coef: [f64; 3],
    plane: bool,
    centre: [f64; D],
    radius: f64,
) -> RigidMotion {
    if !plane {
        RigidMotion::Translation {
            direction: [0.0, 1.0],
        }
    } else if coef[2] == 0.0 {
        RigidMotion::Translation {
            direction: [coef[0], coef[1]],
        }
    } else {
        // u = (a − θ(y − c_y)/ρ, b + θ(x − c_x)/ρ), θ = 1: a rotation about x₀
        RigidMotion::Rotation {
            centre: [centre[0] - coef[1] * radius, centre[1] + coef[0] * radius],
            radius,
        }
    }
}

/// The meaning of a 3D null vector `v` on `(t_x, t_y, t_z, ω_x, ω_y, ω_z)`: a translation when
/// its rotation part vanishes (to round-off), the vector then made the unit direction with a
/// positive first non-zero component, snapped onto an axis; otherwise [`RigidMotion::Other`]
/// and `v` unchanged.
fn space_motion(v: Vec<f64>) -> (Vec<f64>, RigidMotion) {
    let tiny = 1e-12;
    let norm = |w: &[f64]| w.iter().map(|x| x * x).sum::<f64>().sqrt();
    let (t, w) = v.split_at(3.min(v.len()));
    let size = norm(t);
    if v.len() != 6 || !(size > 0.0 && size.is_finite()) || norm(w) > tiny * size {
        return (v, RigidMotion::Other);
    }
    let mut d = [t[0] / size, t[1] / size, t[2] / size];
    if let Some(first) = d.iter().find(|x| x.abs() > tiny)
        && *first < 0.0
    {
        d = d.map(|x| -x);
    }
    if let Some(axis) = (0..3).find(|&a| (0..3).all(|b| b == a || d[b].abs() <= tiny)) {
        d = [0.0; 3];
        d[axis] = 1.0;
    }
    let coef = vec![d[0], d[1], d[2], 0.0, 0.0, 0.0];
    (coef, RigidMotion::SpaceTranslation { direction: d })
}

/// A unit direction with a positive first non-zero component, snapped onto an axis when it is
/// one to round-off.
fn unit_direction(a: f64, b: f64) -> [f64; 2] {
    let norm = a.hypot(b);
    let (mut a, mut b) = (a / norm, b / norm);
    if a < -1e-12 || (a.abs() <= 1e-12 && b < 0.0) {
        (a, b) = (-a, -b);
    }
    if a.abs() <= 1e-12 {
        [0.0, 1.0]
    } else if b.abs() <= 1e-12 {
        [1.0, 0.0]
    } else {
        [a, b]
    }
}

/// A readable basis of the null space (coefficients on `(t_x, t_y, ω)`): the translations it
/// holds first (unit directions, exactly `(1, 0)` and `(0, 1)` when both), then at most one
/// rotation normalised to `θ = 1`.
fn canonical(null: &[Vec<f64>], plane: bool) -> Vec<[f64; 3]> {
    if !plane {
        return null.iter().map(|_| [1.0, 0.0, 0.0]).collect();
    }
    let tiny = 1e-12;
    match null.len() {
        0 => Vec::new(),
        3 => vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        1 => {
            let v = &null[0];
            if v[2].abs() <= tiny * v[0].hypot(v[1]) {
                let d = unit_direction(v[0], v[1]);
                vec![[d[0], d[1], 0.0]]
            } else {
                vec![[v[0] / v[2], v[1] / v[2], 1.0]]
            }
        }
        _ => {
            let (a, b) = (&null[0], &null[1]);
            if a[2].abs() <= tiny && b[2].abs() <= tiny {
                // no rotation in the span (a tie holds it): both translations
                return vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
            }
            // the translation in the span: θ eliminated
            let t: Vec<f64> = (0..3).map(|i| b[2] * a[i] - a[2] * b[i]).collect();
            let dir = unit_direction(t[0], t[1]);
            // the other vector, orthogonal to the translation, made a rotation
            let w = if a[2].abs() >= b[2].abs() { a } else { b };
            let d = w[0] * dir[0] + w[1] * dir[1];
            let w = [w[0] - d * dir[0], w[1] - d * dir[1], w[2]];
            vec![[dir[0], dir[1], 0.0], [w[0] / w[2], w[1] / w[2], 1.0]]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dirichlet::Supports;
    use crate::generate::{RectangleSpec, rectangle};
    use crate::mesh::Mesh;

    fn mesh_modes(
        mesh: &Mesh,
        idealization: Idealization,
        dofs: &DofMap,
    ) -> Result<RigidBodyModes, FemError> {
        let cells = (0..mesh.element_count()).map(|e| mesh.element(e));
        super::mesh_modes(mesh.nodes(), cells, idealization, dofs)
    }

    #[test]
    fn rigid_modes_of_a_free_block_works() {
        let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2)).unwrap();
        let dofs = DofMap::new(mesh.node_count(), &Supports::new()).unwrap();
        let modes = mesh_modes(&mesh, Idealization::PlaneStrain, &dofs).unwrap();
        assert_eq!(modes.len(), 3);
        let RigidMotion::Rotation { centre, radius } = modes.modes()[2].motion else {
            panic!("{:?}", modes.modes());
        };
        // the centroid and the largest distance to it, to round-off of the node average
        assert!((centre[0] - 1.0).abs() < 1e-14 && (centre[1] - 0.5).abs() < 1e-14);
        assert!((radius - 1.25_f64.sqrt()).abs() < 1e-14);
        let pinned = modes.pinned_dofs();
        assert_eq!(pinned.len(), 3);
        let axi = mesh_modes(&mesh, Idealization::Axisymmetric, &dofs).unwrap();
        assert_eq!(axi.len(), 1);
        assert_eq!(axi.column(0)[1], 1.0);
        assert_eq!(axi.column(0)[0], 0.0);
    }

    #[test]
    fn rigid_modes_with_one_pin_works() {
        // y fixed at the bottom-left corner: the x translation and a rotation about a point
        // on the vertical through the corner
        let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2)).unwrap();
        let mut s = Supports::new();
        s.fix(&[0], Component::Y);
        let dofs = DofMap::new(mesh.node_count(), &s).unwrap();
        let modes = mesh_modes(&mesh, Idealization::PlaneStrain, &dofs).unwrap();
        assert_eq!(modes.len(), 2);
        assert_eq!(
            modes.modes()[0].motion,
            RigidMotion::Translation {
                direction: [1.0, 0.0]
            }
        );
        let RigidMotion::Rotation { centre, .. } = modes.modes()[1].motion else {
            panic!("{:?}", modes.modes());
        };
        let corner = mesh.nodes()[0];
        assert!((centre[0] - corner[0]).abs() < 1e-12, "{centre:?}");
    }

    #[test]
    fn rigid_modes_with_ties_works() {
        // a free block whose top nodes share u_y: the rotation would move them apart, so the
        // two translations remain; tying u_x of the top (one height) keeps all three
        let mesh = rectangle(&RectangleSpec::new([0.0, 2.0], [0.0, 1.0], 4, 2)).unwrap();
        let top = mesh.node_set("top").unwrap().to_vec();
        let mut s = Supports::new();
        s.tie(&top, Component::Y).unwrap();
        let dofs = DofMap::new(mesh.node_count(), &s).unwrap();
        let modes = mesh_modes(&mesh, Idealization::PlaneStrain, &dofs).unwrap();
        assert_eq!(modes.len(), 2, "{:?}", modes.modes());
        assert!(
            modes
                .modes()
                .iter()
                .all(|m| matches!(m.motion, RigidMotion::Translation { .. }))
        );
        let mut s = Supports::new();
        s.tie(&top, Component::X).unwrap();
        let dofs = DofMap::new(mesh.node_count(), &s).unwrap();
        assert_eq!(
            mesh_modes(&mesh, Idealization::PlaneStrain, &dofs)
                .unwrap()
                .len(),
            3
        );
    }

    #[test]
    fn a_tie_across_two_bodies_is_refused() {
        let a = rectangle(&RectangleSpec::new([0.0, 1.0], [0.0, 1.0], 1, 1)).unwrap();
        let b = rectangle(&RectangleSpec::new([2.0, 3.0], [0.0, 1.0], 1, 1)).unwrap();
        let mesh = Mesh::join(&[("a.", &a), ("b.", &b)]).unwrap();
        let mut s = Supports::new();
        s.tie(&[0, a.node_count()], Component::Y).unwrap();
        let dofs = DofMap::new(mesh.node_count(), &s).unwrap();
        assert!(matches!(
            mesh_modes(&mesh, Idealization::PlaneStrain, &dofs),
            Err(FemError::InvalidTie { .. })
        ));
    }
}
