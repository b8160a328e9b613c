//! A stack of rigid boxes, each resting on the one below (the first on the floor) by its four
//! bottom corners: one time step of Moreau–Jean nonsmooth contact dynamics (Jean 1999;
//! Acary–Brogliato 2008 for the reduced form `W = Hᵀ M⁻¹ H`), the kind of problem Siconos'
//! `BoxesStack` exports (issue 37).
//!
//! ```text
//! box k (k = 0..n):  half sizes (a, b, c), centre (s_x k, s_y k, (2k + 1) c), at rest
//! contacts:          the four bottom corners p = centre + (±a, ±b, −c) of box k on the top face
//!                    of box k − 1 (of the floor for k = 0), gap 0, frame n = e_z, t₁ = e_x,
//!                    t₂ = e_y (so the impulse r acts on box k, −r on box k − 1)
//! unknowns:          V = (v, ω) per box, M = diag(m I₃, J), m = 8 ρ a b c,
//!                    J = m/3 diag(b² + c², a² + c², a² + b²)
//! local velocity:    u = v_k + ω_k × (p − c_k) − v_{k−1} − ω_{k−1} × (p − c_{k−1}),  x = Hᵀ V
//! reduced:           x = W r + q,  W = Hᵀ M⁻¹ H,  q = Hᵀ h M⁻¹ f_ext,
//!                    f_ext = −m g e_z on every box, + F e_x at the top box's centre
//! ```
//! `W` is `12 n × 12 n` of rank at most `6 n`: half of it is a null space (four corners carry
//! what three would). The answer is known: with `|F| < μ` times the weight above every
//! interface and the offsets small, every box stays at rest, so `x = 0` and the
//! generalized impulse is `H r = −h f_ext`: the normal impulses of interface `k` sum to
//! `h m g (n − k)`, the tangential ones to `−h F` along `e_x` (what the top box is pushed
//! with) — while how they split among the four corners is not unique.

/// The stack's parameters.
#[derive(Clone, Copy, Debug)]
pub struct BoxStack {
    /// Number of boxes.
    pub boxes: usize,
    /// Half sizes `(a, b, c)`.
    pub half: [f64; 3],
    /// Horizontal offset of each box from the one below (`s_x`, `s_y`), smaller than the
    /// half sizes so that every corner rests on the box below.
    pub offset: [f64; 2],
    /// Friction coefficient of every contact.
    pub mu: f64,
    /// Lateral force on the top box, along `e_x`.
    pub push: f64,
    /// Time step `h`, gravity `g` and mass density.
    pub time_step: f64,
    /// Gravity `g`.
    pub gravity: f64,
    /// Mass density.
    pub density: f64,
}

impl Default for BoxStack {
    /// Ten unit-density boxes of `1 × 0.6 × 0.4`, offset by `(0.05, −0.03)`, `μ = 0.5`, no push,
    /// `h = 0.01`, `g = 9.81`.
    fn default() -> Self {
        Self {
            boxes: 10,
            half: [0.5, 0.3, 0.2],
            offset: [0.05, -0.03],
            mu: 0.5,
            push: 0.0,
            time_step: 0.01,
            gravity: 9.81,
            density: 1.0,
        }
    }
}

/// A generated stack: the reduced problem's data and what checks its answer.
#[derive(Clone, Debug)]
pub struct BoxStackProblem {
    /// `W`, row-major `12 n × 12 n`.
    pub w: Vec<f64>,
    /// `q`, `12 n`.
    pub q: Vec<f64>,
    /// `μ` per contact (`4 n`).
    pub mu: Vec<f64>,
    /// The mass of each box.
    pub mass: f64,
}

impl BoxStack {
    /// The centre of box `k`.
    fn centre(&self, k: usize) -> [f64; 3] {
        let [a, b, c] = [self.offset[0], self.offset[1], self.half[2]];
        [a * k as f64, b * k as f64, (2 * k + 1) as f64 * c]
    }

    /// The reduced problem (see the [module docs](self)).
    pub fn generate(&self) -> BoxStackProblem {
        let n = self.boxes;
        let [a, b, c] = self.half;
        let mass = 8.0 * self.density * a * b * c;
        let inertia = [
            mass / 3.0 * (b * b + c * c),
            mass / 3.0 * (a * a + c * c),
            mass / 3.0 * (a * a + b * b),
        ];
        // M^{-1/2} per dof of a box
        let inv_sqrt: [f64; 6] = [
            1.0 / mass.sqrt(),
            1.0 / mass.sqrt(),
            1.0 / mass.sqrt(),
            1.0 / inertia[0].sqrt(),
            1.0 / inertia[1].sqrt(),
            1.0 / inertia[2].sqrt(),
        ];
        let (nc, dofs) = (4 * n, 6 * n);
        let m = 3 * nc;
        // Hᵀ, m × dofs: row 3j + a is e_aᵀ (v_k + ω_k × ρ_k) − (same for box k − 1)
        let mut ht = vec![0.0; m * dofs];
        for k in 0..n {
            let ck = self.centre(k);
            for (corner, (sx, sy)) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .into_iter()
                .enumerate()
            {
                let j = 4 * k + corner;
                let p = [ck[0] + sx * a, ck[1] + sy * b, ck[2] - c];
                // frame rows: e_z (normal), e_x, e_y
                for (row, e) in [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
                    .into_iter()
                    .enumerate()
                {
                    let i = 3 * j + row;
                    let mut put = |body: usize, sign: f64, centre: [f64; 3]| {
                        let arm = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
                        // eᵀ(ω × arm) = (arm × e)ᵀ ω
                        let moment = [
                            arm[1] * e[2] - arm[2] * e[1],
                            arm[2] * e[0] - arm[0] * e[2],
                            arm[0] * e[1] - arm[1] * e[0],
                        ];
                        for d in 0..3 {
                            ht[i * dofs + 6 * body + d] += sign * e[d];
                            ht[i * dofs + 6 * body + 3 + d] += sign * moment[d];
                        }
                    };
                    put(k, 1.0, ck);
                    if k > 0 {
                        put(k - 1, -1.0, self.centre(k - 1));
                    }
                }
            }
        }
        // G = Hᵀ M^{-1/2}, W = G Gᵀ (exactly symmetric: the same products in the same order)
        let g: Vec<f64> = (0..m * dofs)
            .map(|e| ht[e] * inv_sqrt[(e % dofs) % 6])
            .collect();
        let mut w = vec![0.0; m * m];
        for i in 0..m {
            for j in 0..m {
                w[i * m + j] = (0..dofs).map(|d| g[i * dofs + d] * g[j * dofs + d]).sum();
            }
        }
        // q = Hᵀ h M⁻¹ f_ext
        let mut v_free = vec![0.0; dofs];
        for k in 0..n {
            v_free[6 * k + 2] = -self.time_step * self.gravity;
        }
        v_free[6 * (n - 1)] += self.time_step * self.push / mass;
        let q = (0..m)
            .map(|i| (0..dofs).map(|d| ht[i * dofs + d] * v_free[d]).sum())
            .collect();
        BoxStackProblem {
            w,
            q,
            mu: vec![self.mu; nc],
            mass,
        }
    }
}

impl BoxStackProblem {
    /// `(Σ r_n, Σ r_t1, Σ r_t2)` of interface `k` (below box `k`).
    pub fn interface_impulse(&self, r: &[f64], k: usize) -> [f64; 3] {
        let mut s = [0.0; 3];
        for j in 4 * k..4 * k + 4 {
            for a in 0..3 {
                s[a] += r[3 * j + a];
            }
        }
        s
    }
}
