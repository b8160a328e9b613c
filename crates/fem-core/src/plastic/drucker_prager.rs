//! Non-associated Drucker–Prager soil with perfect plasticity, written as an implicit standard
//! material (Terfaya 2019, §4.3, eqs. 4.12–4.17, after Berga and de Saxcé).
//!
//! Stresses are split into the mean stress `s_m = tr σ / 3` (**tension positive**) and the
//! deviator `s`; plastic strain rates into their trace `ė_m = tr ε̇ᵖ` and deviator `ė`. Norms
//! are tensor norms, `‖s‖ = √(s : s)`.
//!
//! ```text
//! K_σ = { ‖s‖ / k_d + s_m tan φ ≤ c }                      yield cone (4.12)
//! K_ε = { ė_m ≥ k_d tan θ ‖ė‖ }                             dilatancy cone (4.15)
//! b_p(ε̇ᵖ, σ) = I_Kε(ε̇ᵖ) + I_Kσ(σ) + c ė_m / tan φ
//!              + k_d (tan φ − tan θ)(c / tan φ − s_m) ‖ė‖   bipotential (4.16, sign mended)
//! ```
//!
//! On the smooth part of the cone the law is `ė = λ n / k_d`, `ė_m = λ tan θ` with
//! `n = s / ‖s‖`: the plastic flow is normal to the dilatancy cone of angle `θ ≤ φ`, not to the
//! yield cone (associated only when `θ = φ`). At the apex `(s_m = c / tan φ, s = 0)` any rate
//! of `K_ε` is admissible. The return mapping below is the discrete form of
//! `σ ∈ ∂_ε̇ᵖ b_p(ε̇ᵖ, σ)` with `σ = σ_trial − C Δεᵖ`, solved in closed form (`docs/theory.md`,
//! section "Drucker–Prager soil (issue 40)").

use super::{ConstitutivePoint, PointState, Voigt, VoigtMatrix, isotropic_tangent};
use crate::error::{FemError, non_negative, positive};

/// Relative round-off allowed by [`DruckerPrager::bipotential`] when it tests membership of
/// `K_σ` and `K_ε` (a stress returned onto the cone sits on it to a few ulps).
const MEMBERSHIP_TOLERANCE: f64 = 1e-12;

/// How the Drucker–Prager cone is fitted to the Mohr–Coulomb pyramid of the same `φ` and `c`.
///
/// Every match keeps the seed's form `‖s‖ / k_d + s_m tan φ ≤ c`; only `k_d` changes. At
/// `φ = 0` the cone is von Mises with shear yield stress `k = k_d c / √2`:
///
/// | match | `k_d` | `k` at `φ = 0` |
/// |---|---|---|
/// | [`PlaneStrain`](ConeMatch::PlaneStrain) | `√6 / √(3 + 4 tan²φ)` | `c` (Tresca in plane strain) |
/// | [`Outer`](ConeMatch::Outer) | `2√6 cos φ / (3 − sin φ)` | `2c / √3` |
/// | [`Inner`](ConeMatch::Inner) | `2√6 cos φ / (3 + sin φ)` | `2c / √3` |
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum ConeMatch {
    /// The seed's choice: with associated flow in plane strain (`ε̇ᵖ_zz = 0`) the cone gives
    /// Mohr–Coulomb's limit states exactly. It is also the cone inscribed in the pyramid
    /// (tangent to its faces, `k_d = √6 cos φ / √(3 + sin²φ)`, the same number): the seed's
    /// "cône tangentiel à l'intérieur de pyramide de Mohr–Coulomb".
    #[default]
    PlaneStrain,
    /// Through the compression meridians of the pyramid (triaxial compression,
    /// `σ₁ = σ₂ > σ₃`): the cone circumscribes the pyramid.
    Outer,
    /// Through the extension meridians of the pyramid (triaxial extension,
    /// `σ₁ > σ₂ = σ₃`); partly outside the pyramid between them.
    Inner,
}

impl ConeMatch {
    /// The constant `k_d` of (4.12) for a friction angle `phi_radians` (table on
    /// [`ConeMatch`]).
    pub fn k_d(self, phi_radians: f64) -> f64 {
        let phi = phi_radians;
        match self {
            Self::PlaneStrain => (6.0 / (3.0 + 4.0 * phi.tan().powi(2))).sqrt(),
            Self::Outer => 2.0 * 6f64.sqrt() * phi.cos() / (3.0 - phi.sin()),
            Self::Inner => 2.0 * 6f64.sqrt() * phi.cos() / (3.0 + phi.sin()),
        }
    }
}

/// The user's parameters of a [`DruckerPrager`] point (angles in **degrees**, as soil
/// reports give them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DruckerPragerParameters {
    /// Young's modulus `E > 0`.
    pub young: f64,
    /// Poisson's ratio `0 ≤ ν < 1/2`.
    pub poisson: f64,
    /// Friction angle `φ` in degrees, `0 ≤ φ < 90`.
    pub friction_angle: f64,
    /// Dilatancy angle `θ` in degrees, `0 ≤ θ ≤ φ` (`θ = φ`: associated flow).
    pub dilatancy_angle: f64,
    /// Cohesion `c ≥ 0` (`> 0` when `φ = 0`), in units of stress.
    pub cohesion: f64,
    /// How the cone matches Mohr–Coulomb.
    pub cone: ConeMatch,
}

/// Non-associated Drucker–Prager with perfect plasticity at one material point (module docs).
///
/// The accumulated equivalent plastic strain is `ε̄ᵖ = Σ √(2/3 Δεᵖ : Δεᵖ)` over the steps (the
/// full plastic strain increment, tensor norm): the uniaxial plastic strain for an isochoric
/// flow, as in von Mises plasticity.
///
/// # Examples
/// ```
/// use fem_core::plastic::{ConeMatch, ConstitutivePoint, DruckerPrager, DruckerPragerParameters, PointState};
/// let sand = DruckerPrager::new(DruckerPragerParameters {
///     young: 50e6, poisson: 0.3, friction_angle: 35.0, dilatancy_angle: 5.0,
///     cohesion: 1e3, cone: ConeMatch::PlaneStrain,
/// })?;
/// // simple shear far beyond yield from a confining pressure of 100 kPa
/// let committed = PointState::with_stress([-1e5, -1e5, -1e5, 0.0, 0.0, 0.0]);
/// let (mut trial, mut tangent) = (PointState::default(), [[0.0; 6]; 6]);
/// sand.update(&committed, &[0.0, 0.0, 0.0, 0.05, 0.0, 0.0], &mut trial, &mut tangent)?;
/// assert!(trial.yielding && sand.yield_function(&trial.stress).abs() < 1e-6);
/// # Ok::<(), fem_core::FemError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DruckerPrager {
    parameters: DruckerPragerParameters,
    /// Bulk modulus `K`.
    bulk: f64,
    /// Shear modulus `G`.
    shear: f64,
    k_d: f64,
    /// `1 / k_d`.
    inv_k_d: f64,
    /// Lamé's `λ = K − 2G/3`.
    lame: f64,
    tan_phi: f64,
    tan_theta: f64,
    /// `H = 2G / k_d² + K tan θ tan φ`, the denominator of the smooth return.
    plastic_modulus: f64,
    /// The elastic tangent `C`, kept (the hot loop starts every update from it).
    elastic: VoigtMatrix,
}

impl DruckerPrager {
    /// Checks `parameters` and builds the point.
    ///
    /// # Errors
    /// [`FemError::InvalidParameter`] naming `young`, `poisson` (outside `[0, 1/2)`),
    /// `friction_angle` (outside `[0, 90)` degrees), `dilatancy_angle` (negative or above
    /// `friction_angle`) or `cohesion` (negative, or zero with `φ = 0`); every value must be
    /// finite.
    pub fn new(parameters: DruckerPragerParameters) -> Result<Self, FemError> {
        let young = positive("young", parameters.young)?;
        let poisson = non_negative("poisson", parameters.poisson)?;
        if poisson >= 0.5 {
            return Err(FemError::InvalidParameter {
                name: "poisson",
                value: poisson,
                expected: "a value in [0, 0.5)",
            });
        }
        let phi = non_negative("friction_angle", parameters.friction_angle)?;
        if phi >= 90.0 {
            return Err(FemError::InvalidParameter {
                name: "friction_angle",
                value: phi,
                expected: "an angle in [0, 90) degrees",
            });
        }
        let theta = non_negative("dilatancy_angle", parameters.dilatancy_angle)?;
        if theta > phi {
            return Err(FemError::InvalidParameter {
                name: "dilatancy_angle",
                value: theta,
                expected: "an angle in [0, friction_angle] degrees (θ ≤ φ)",
            });
        }
        let cohesion = non_negative("cohesion", parameters.cohesion)?;
        if phi == 0.0 && cohesion == 0.0 {
            return Err(FemError::InvalidParameter {
                name: "cohesion",
                value: cohesion,
                expected: "a value > 0 when friction_angle is 0 (no strength otherwise)",
            });
        }
        let (phi, theta) = (phi.to_radians(), theta.to_radians());
        let (bulk, shear) = (
            young / (3.0 * (1.0 - 2.0 * poisson)),
            young / (2.0 * (1.0 + poisson)),
        );
        let (k_d, tan_phi, tan_theta) = (parameters.cone.k_d(phi), phi.tan(), theta.tan());
        Ok(Self {
            parameters,
            bulk,
            shear,
            k_d,
            inv_k_d: 1.0 / k_d,
            lame: bulk - 2.0 * shear / 3.0,
            tan_phi,
            tan_theta,
            plastic_modulus: 2.0 * shear / (k_d * k_d) + bulk * tan_theta * tan_phi,
            elastic: isotropic_tangent(young, poisson),
        })
    }

    /// Von Mises plasticity (`φ = θ = 0`) with shear yield stress `k = shear_yield`
    /// (uniaxial yield stress `√3 k`): the plane-strain match, whose `k_d = √2` makes `k = c`.
    ///
    /// # Errors
    /// As [`DruckerPrager::new`]; a non-positive `shear_yield` is named `cohesion`.
    pub fn von_mises(young: f64, poisson: f64, shear_yield: f64) -> Result<Self, FemError> {
        Self::new(DruckerPragerParameters {
            young,
            poisson,
            friction_angle: 0.0,
            dilatancy_angle: 0.0,
            cohesion: shear_yield,
            cone: ConeMatch::PlaneStrain,
        })
    }

    /// The parameters it was built from.
    pub fn parameters(&self) -> &DruckerPragerParameters {
        &self.parameters
    }

    /// The constant `k_d` of the cone (4.12), set by [`ConeMatch`].
    pub fn k_d(&self) -> f64 {
        self.k_d
    }

    /// The bulk modulus `K = E / (3 (1 − 2ν))`.
    pub fn bulk_modulus(&self) -> f64 {
        self.bulk
    }

    /// The shear modulus `G = E / (2 (1 + ν))`.
    pub fn shear_modulus(&self) -> f64 {
        self.shear
    }

    /// The mean stress of the apex, `c / tan φ`; `None` for `φ = 0` (a cylinder, no apex).
    pub fn apex_mean_stress(&self) -> Option<f64> {
        (self.tan_phi > 0.0).then(|| self.parameters.cohesion / self.tan_phi)
    }

    /// The bipotential `b_p(ε̇ᵖ, σ)` (4.16, with the sign of its last factor mended:
    /// `docs/theory.md`) of a plastic strain rate (engineering shears) and a stress.
    ///
    /// `+∞` when `σ ∉ K_σ` or `ε̇ᵖ ∉ K_ε` (to a relative round-off of `1e-12`), and, for
    /// `φ = 0`, when `ė_m > 0` (a von Mises material cannot dilate); `+∞` for non-finite
    /// input. `b_p(ε̇ᵖ, σ) ≥ ε̇ᵖ : σ` always, with equality on the law's pairs.
    ///
    /// # Examples
    /// ```
    /// use fem_core::plastic::{ConeMatch, DruckerPrager, DruckerPragerParameters};
    /// let soil = DruckerPrager::new(DruckerPragerParameters {
    ///     young: 1e4, poisson: 0.3, friction_angle: 30.0, dilatancy_angle: 0.0,
    ///     cohesion: 2.0, cone: ConeMatch::Outer,
    /// })?;
    /// // at the apex σ = (c / tan φ) 1, a purely volumetric rate is one of the law's pairs
    /// let apex = soil.apex_mean_stress().unwrap();
    /// let (stress, rate) = ([apex, apex, apex, 0.0, 0.0, 0.0], [1e-3, 1e-3, 1e-3, 0.0, 0.0, 0.0]);
    /// let power = 3.0 * apex * 1e-3;
    /// assert!((soil.bipotential(&rate, &stress) - power).abs() < 1e-12 * power);
    /// // a compacting rate is outside the dilatancy cone K_ε
    /// assert_eq!(soil.bipotential(&[-1e-3, 0.0, 0.0, 0.0, 0.0, 0.0], &stress), f64::INFINITY);
    /// # Ok::<(), fem_core::FemError>(())
    /// ```
    pub fn bipotential(&self, plastic_rate: &Voigt, stress: &Voigt) -> f64 {
        if plastic_rate.iter().chain(stress).any(|v| !v.is_finite()) {
            return f64::INFINITY;
        }
        let c = self.parameters.cohesion;
        let (s_m, s) = split(stress);
        let s_norm = stress_norm(&s);
        let scale_s = c + s_m.abs() * self.tan_phi + s_norm / self.k_d;
        if self.yield_function(stress) > MEMBERSHIP_TOLERANCE * scale_s {
            return f64::INFINITY;
        }
        let (e_m, e_norm) = strain_split_norm(plastic_rate);
        // ė_m − k_d tan θ ‖ė‖ ≥ 0 on K_ε
        let excess = e_m - self.k_d * self.tan_theta * e_norm;
        let scale_e = e_m.abs() + self.k_d * e_norm;
        if excess < -MEMBERSHIP_TOLERANCE * scale_e {
            return f64::INFINITY;
        }
        // b_p = (c / tan φ) (ė_m − k_d tan θ ‖ė‖) + k_d c ‖ė‖ − k_d (tan φ − tan θ) s_m ‖ė‖,
        // the form of (4.16) that stays finite at φ = 0 on the rates with ė_m = 0
        let cohesive = if self.tan_phi > 0.0 {
            c * excess / self.tan_phi
        } else if excess <= MEMBERSHIP_TOLERANCE * scale_e || c == 0.0 {
            0.0
        } else {
            return f64::INFINITY;
        };
        cohesive + self.k_d * e_norm * (c - (self.tan_phi - self.tan_theta) * s_m)
    }

    /// Writes the consistent tangent of the smooth return (`docs/theory.md`, section 15),
    /// `C − a ⊗ b / H − β (P − n ⊗ n)`, into `tangent`.
    fn smooth_tangent_into(
        &self,
        n: &Voigt,
        dlambda: f64,
        s_trial_norm: f64,
        tangent: &mut VoigtMatrix,
    ) {
        let (g, k) = (self.shear, self.bulk);
        let two_g_k_d = 2.0 * g * self.inv_k_d;
        // a = 2G n / k_d + K tan θ δ (flow), b = (2G n / k_d + K tan φ δ) / H (yield normal)
        let inv_h = 1.0 / self.plastic_modulus;
        let mut a = [0.0; 6];
        let mut b = [0.0; 6];
        for i in 0..6 {
            a[i] = two_g_k_d * n[i];
            b[i] = a[i] * inv_h;
        }
        for i in 0..3 {
            a[i] += k * self.tan_theta;
            b[i] += k * self.tan_phi * inv_h;
        }
        let beta = 2.0 * g * two_g_k_d * dlambda / s_trial_norm;
        *tangent = self.elastic;
        for (i, row) in tangent.iter_mut().enumerate() {
            for (j, entry) in row.iter_mut().enumerate() {
                *entry -= a[i] * b[j] - beta * n[i] * n[j];
            }
        }
        // − β P, P mapping engineering strains to the tensor deviator
        for (i, row) in tangent.iter_mut().enumerate().take(3) {
            for (j, entry) in row.iter_mut().enumerate().take(3) {
                *entry -= beta * (f64::from(u8::from(i == j)) - 1.0 / 3.0);
            }
        }
        for (i, row) in tangent.iter_mut().enumerate().skip(3) {
            row[i] -= 0.5 * beta;
        }
    }
}

/// `(s_m, s)`: the mean stress and the deviator (tensor shears) of a Voigt stress.
#[inline]
fn split(stress: &Voigt) -> (f64, Voigt) {
    let s_m = (stress[0] + stress[1] + stress[2]) / 3.0;
    let mut s = *stress;
    for v in &mut s[..3] {
        *v -= s_m;
    }
    (s_m, s)
}

/// `‖s‖ = √(s : s)` of a Voigt stress-like vector (tensor shears).
#[inline]
fn stress_norm(s: &Voigt) -> f64 {
    (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]))
        .sqrt()
}

/// `(tr ε, ‖dev ε‖)` of a Voigt strain with engineering shears (tensor norm).
#[inline]
fn strain_split_norm(strain: &Voigt) -> (f64, f64) {
    let tr = strain[0] + strain[1] + strain[2];
    let (a, b, c) = (
        strain[0] - tr / 3.0,
        strain[1] - tr / 3.0,
        strain[2] - tr / 3.0,
    );
    let shear = strain[3] * strain[3] + strain[4] * strain[4] + strain[5] * strain[5];
    (tr, (a * a + b * b + c * c + 0.5 * shear).sqrt())
}

/// `√(ε : ε)` of a Voigt strain with engineering shears.
#[inline]
fn strain_norm(strain: &Voigt) -> f64 {
    let normal = strain[0] * strain[0] + strain[1] * strain[1] + strain[2] * strain[2];
    let shear = strain[3] * strain[3] + strain[4] * strain[4] + strain[5] * strain[5];
    (normal + 0.5 * shear).sqrt()
}

impl ConstitutivePoint for DruckerPrager {
    fn elastic_tangent(&self) -> VoigtMatrix {
        self.elastic
    }

    /// The closed-form return of the module docs: elastic predictor, then the smooth return
    /// `Δλ = f_trial / H` with `H = 2G / k_d² + K tan θ tan φ` when it leaves `‖s‖ > 0`, else
    /// the apex (`σ = (c / tan φ) 1`, tangent zero). No allocation.
    fn update(
        &self,
        committed: &PointState,
        strain: &Voigt,
        trial: &mut PointState,
        tangent: &mut VoigtMatrix,
    ) -> Result<(), FemError> {
        super::check_strain(strain)?;
        let (g, k) = (self.shear, self.bulk);
        let lambda = self.lame;
        let mut d = [0.0; 6];
        for (i, v) in d.iter_mut().enumerate() {
            *v = strain[i] - committed.strain[i];
        }
        let tr = d[0] + d[1] + d[2];
        let mut stress_trial = committed.stress;
        for i in 0..3 {
            stress_trial[i] += lambda * tr + 2.0 * g * d[i];
        }
        for i in 3..6 {
            stress_trial[i] += g * d[i];
        }
        *trial = *committed;
        trial.strain = *strain;
        let (m_trial, s_trial) = split(&stress_trial);
        let a_trial = stress_norm(&s_trial);
        let c = self.parameters.cohesion;
        let inv_k_d = self.inv_k_d;
        let f_trial = a_trial * inv_k_d + m_trial * self.tan_phi - c;
        if !f_trial.is_finite() {
            // a finite strain (or committed stress) whose elastic trial stress overflows
            return Err(FemError::InvalidParameter {
                name: "strain",
                value: strain.iter().fold(0.0, |m, v| m.max(v.abs())),
                expected: "a strain increment whose elastic trial stress is finite",
            });
        }
        if f_trial <= 0.0 {
            trial.stress = stress_trial;
            trial.yielding = false;
            *tangent = self.elastic_tangent();
            return Ok(());
        }
        let dlambda = f_trial / self.plastic_modulus;
        let a_new = a_trial - 2.0 * g * dlambda * inv_k_d;
        let mut dp = [0.0; 6];
        // at φ = 0, a_new = k_d c > 0 (no apex) up to a round-off that a tiny c could expose
        if a_new > 0.0 || self.tan_phi == 0.0 {
            let a_new = a_new.max(0.0);
            // smooth return along n = s_trial / ‖s_trial‖, which it keeps
            let inv_a = 1.0 / a_trial;
            let n = s_trial.map(|v| v * inv_a);
            let m_new = m_trial - k * dlambda * self.tan_theta;
            // Δεᵖ = Δλ (n / k_d + tan θ / 3 · 1), shears engineering
            let (flow, dilation) = (dlambda * inv_k_d, dlambda * self.tan_theta / 3.0);
            for i in 0..3 {
                trial.stress[i] = m_new + a_new * n[i];
                dp[i] = flow * n[i] + dilation;
            }
            for i in 3..6 {
                trial.stress[i] = a_new * n[i];
                dp[i] = 2.0 * flow * n[i];
            }
            self.smooth_tangent_into(&n, dlambda, a_trial, tangent);
        } else {
            // apex: a_new ≤ 0 needs tan φ > 0 (at φ = 0, a_new = k_d c > 0); Δεᵖ = C⁻¹(σ_trial −
            // σ_apex) lies in K_ε exactly when the smooth return fails (docs/theory.md)
            let apex = c / self.tan_phi;
            let volumetric = (m_trial - apex) / (3.0 * k);
            for i in 0..6 {
                if i < 3 {
                    trial.stress[i] = apex;
                    dp[i] = s_trial[i] / (2.0 * g) + volumetric;
                } else {
                    trial.stress[i] = 0.0;
                    dp[i] = s_trial[i] / g;
                }
            }
            *tangent = [[0.0; 6]; 6];
        }
        for (total, increment) in trial.plastic_strain.iter_mut().zip(dp) {
            *total += increment;
        }
        trial.equivalent_plastic_strain += (2.0f64 / 3.0).sqrt() * strain_norm(&dp);
        trial.yielding = true;
        Ok(())
    }

    /// `f(σ) = ‖s‖ / k_d + s_m tan φ − c` (4.12), in units of stress.
    fn yield_function(&self, stress: &Voigt) -> f64 {
        let (s_m, s) = split(stress);
        stress_norm(&s) / self.k_d + s_m * self.tan_phi - self.parameters.cohesion
    }

    /// Associated (`θ = φ`): the consistent tangent is symmetric.
    fn symmetric_tangent(&self) -> bool {
        self.parameters.dilatancy_angle == self.parameters.friction_angle
    }
}
