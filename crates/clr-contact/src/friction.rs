//! Friction laws (contact-laws.md §2).
//!
//! Convention: v_T is the relative tangential (slip) velocity (m/s) of body j with respect to
//! body i along the tangent t; the returned friction force F_T (N) is the component along t of
//! the force on body j, so it opposes the slip: F_T·v_T ≤ 0. F_N (N) is the normal force; a
//! negative F_N is treated as 0.
//!
//! [`FrictionLaw`] holds the stateless laws; [`LuGre`] carries one bristle state z per contact,
//! which the caller integrates with [`LuGre::z_dot`].

use crate::error::positive;
use crate::error::ContactError;

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Coulomb {
        mu: f64,
        v_reg: f64,
    },
    Ambrosio {
        mu: f64,
        v0: f64,
        v1: f64,
        smooth: bool,
    },
    Threlfall {
        mu: f64,
        v0: f64,
    },
    Stribeck {
        mu_s: f64,
        mu_d: f64,
        v_s: f64,
        v_d: f64,
    },
}

/// A stateless friction law F_T = μ(v_T)·F_N, validated at construction.
///
/// Cheap to copy; [`force`](Self::force) allocates nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionLaw {
    kind: Kind,
}

fn coefficient(law: &'static str, name: &'static str, mu: f64) -> Result<f64, ContactError> {
    if mu >= 0.0 && mu.is_finite() {
        Ok(mu)
    } else {
        Err(ContactError::invalid(
            law,
            name,
            mu,
            "must be ≥ 0 and finite",
        ))
    }
}

fn ordered(
    law: &'static str,
    name: &'static str,
    lower: f64,
    upper: f64,
) -> Result<(), ContactError> {
    if lower < upper {
        Ok(())
    } else {
        Err(ContactError::invalid(
            law,
            name,
            upper,
            format!("must be greater than the lower velocity {lower:e} m/s"),
        ))
    }
}

/// Smoothstep s²(3 − 2s) of s ∈ [0, 1].
#[inline]
fn step3(s: f64) -> f64 {
    s * s * (3.0 - 2.0 * s)
}

impl FrictionLaw {
    /// Coulomb friction F_T = −μF_N sgn(v_T), regularized linearly below the stated velocity
    /// v_reg (m/s): F_T = −μF_N·clamp(v_T/v_reg, −1, 1), exact Coulomb for |v_T| ≥ v_reg.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for μ < 0 or v_reg ≤ 0.
    pub fn coulomb(mu: f64, v_reg: f64) -> Result<Self, ContactError> {
        const LAW: &str = "Coulomb friction";
        Ok(Self {
            kind: Kind::Coulomb {
                mu: coefficient(LAW, "friction coefficient μ (-)", mu)?,
                v_reg: positive(LAW, "regularization velocity (m/s)", v_reg)?,
            },
        })
    }

    /// Ambrósio's modified Coulomb law (J. Ambrósio, NATO ASI Virtual Nonlinear Multibody
    /// Systems II (2002) 15–33; Flores & Ambrósio 2004): F_T = −μ c_d(|v_T|) F_N sgn(v_T) with the
    /// dynamic correction coefficient c_d = 0 below v0, (|v_T| − v0)/(v1 − v0) between v0 and
    /// v1, 1 above v1. Friction is switched off near zero slip (not a stiction model).
    /// Typical v0 = 1e-4 m/s, v1 = 1e-3 m/s.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for μ < 0, v0 < 0 or v1 ≤ v0.
    pub fn ambrosio(mu: f64, v0: f64, v1: f64) -> Result<Self, ContactError> {
        Self::ambrosio_kind(mu, v0, v1, false)
    }

    /// C¹ variant of [`ambrosio`](Self::ambrosio) (an option of this crate, not Ambrósio's,
    /// contact-laws.md §2): c_d = s²(3 − 2s) with s = (|v_T| − v0)/(v1 − v0) clamped to [0, 1], so
    /// the force has a continuous derivative at v0 and v1, which helps implicit integrators.
    /// Equal to the linear ramp at v0, (v0 + v1)/2 and v1.
    ///
    /// # Errors
    /// As [`ambrosio`](Self::ambrosio).
    pub fn ambrosio_smooth(mu: f64, v0: f64, v1: f64) -> Result<Self, ContactError> {
        Self::ambrosio_kind(mu, v0, v1, true)
    }

    fn ambrosio_kind(mu: f64, v0: f64, v1: f64, smooth: bool) -> Result<Self, ContactError> {
        const LAW: &str = "Ambrósio friction";
        let mu = coefficient(LAW, "friction coefficient μ (-)", mu)?;
        if !(v0 >= 0.0 && v0.is_finite()) {
            return Err(ContactError::invalid(
                LAW,
                "v0 (m/s)",
                v0,
                "must be ≥ 0 and finite",
            ));
        }
        positive(LAW, "v1 (m/s)", v1)?;
        ordered(LAW, "v1 (m/s)", v0, v1)?;
        Ok(Self {
            kind: Kind::Ambrosio { mu, v0, v1, smooth },
        })
    }

    /// Threlfall's law (D.C. Threlfall, Mech. Mach. Theory 13 (1978) 475–483):
    /// F_T = −μF_N(1 − e^{−3|v_T|/v0}) sgn(v_T); v0 (m/s) is where friction reaches 95 % of μF_N.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for μ < 0 or v0 ≤ 0.
    pub fn threlfall(mu: f64, v0: f64) -> Result<Self, ContactError> {
        const LAW: &str = "Threlfall friction";
        Ok(Self {
            kind: Kind::Threlfall {
                mu: coefficient(LAW, "friction coefficient μ (-)", mu)?,
                v0: positive(LAW, "v0 (m/s)", v0)?,
            },
        })
    }

    /// Bai & Zhao / ADAMS-STEP Stribeck-type law with static μ_s and dynamic μ_d coefficients and
    /// critical velocities v_s < v_d (m/s) (Bai & Zhao 2012, 2013; contact-laws.md §2). Signed
    /// μ(v), continuous at ±v_s and ±v_d:
    /// - |v| > v_d: μ = −μ_d sgn v;
    /// - v_s ≤ |v| ≤ v_d: μ = −[μ_d + (μ_s − μ_d)s²(3 − 2s)] sgn v, s = (|v| − v_d)/(v_s − v_d);
    /// - |v| < v_s: μ = μ_s − 2μ_s u²(3 − 2u), u = (v + v_s)/(2v_s).
    ///
    /// The spacecraft paper uses μ_s = 0.2, μ_d = 0.1, v_s = 0.01 m/s, v_d = 0.1 m/s.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for negative coefficients or v_d ≤ v_s ≤ 0.
    pub fn stribeck(mu_s: f64, mu_d: f64, v_s: f64, v_d: f64) -> Result<Self, ContactError> {
        const LAW: &str = "Bai/Stribeck friction";
        let mu_s = coefficient(LAW, "static coefficient μ_s (-)", mu_s)?;
        let mu_d = coefficient(LAW, "dynamic coefficient μ_d (-)", mu_d)?;
        positive(LAW, "static velocity v_s (m/s)", v_s)?;
        positive(LAW, "dynamic velocity v_d (m/s)", v_d)?;
        ordered(LAW, "dynamic velocity v_d (m/s)", v_s, v_d)?;
        Ok(Self {
            kind: Kind::Stribeck {
                mu_s,
                mu_d,
                v_s,
                v_d,
            },
        })
    }

    /// Signed friction coefficient μ(v_T) (–): F_T = μ(v_T)·F_N, with μ(v)·v ≤ 0.
    #[inline]
    pub fn signed_coefficient(&self, v_t: f64) -> f64 {
        if v_t.is_nan() {
            return 0.0;
        }
        let a = v_t.abs();
        let sgn = sign(v_t);
        match self.kind {
            Kind::Coulomb { mu, v_reg } => -mu * (v_t / v_reg).clamp(-1.0, 1.0),
            Kind::Ambrosio { mu, v0, v1, smooth } => {
                let ramp = ((a - v0) / (v1 - v0)).clamp(0.0, 1.0);
                let cd = if smooth { step3(ramp) } else { ramp };
                -mu * cd * sgn
            }
            Kind::Threlfall { mu, v0 } => -mu * (-(-3.0 * a / v0).exp_m1()) * sgn,
            Kind::Stribeck {
                mu_s,
                mu_d,
                v_s,
                v_d,
            } => {
                if a > v_d {
                    -mu_d * sgn
                } else if a >= v_s {
                    let s = (a - v_d) / (v_s - v_d);
                    -(mu_d + (mu_s - mu_d) * step3(s)) * sgn
                } else {
                    let u = (v_t + v_s) / (2.0 * v_s);
                    mu_s - 2.0 * mu_s * step3(u)
                }
            }
        }
    }

    /// Derivative dμ/dv_T (s/m) of the [signed coefficient](Self::signed_coefficient), for
    /// Jacobians of implicit integrators (dF_T/dv_T = F_N·dμ/dv_T). Where the law has a kink
    /// (Coulomb at ±v_reg, the linear Ambrósio ramp at v0 and v1) the value of the branch with the
    /// larger |v_T| is returned.
    #[inline]
    pub fn coefficient_derivative(&self, v_t: f64) -> f64 {
        if v_t.is_nan() {
            return 0.0;
        }
        let a = v_t.abs();
        match self.kind {
            Kind::Coulomb { mu, v_reg } => {
                if a < v_reg {
                    -mu / v_reg
                } else {
                    0.0
                }
            }
            Kind::Ambrosio { mu, v0, v1, smooth } => {
                if a < v0 || a >= v1 {
                    0.0
                } else if smooth {
                    let s = (a - v0) / (v1 - v0);
                    -mu * 6.0 * s * (1.0 - s) / (v1 - v0)
                } else {
                    -mu / (v1 - v0)
                }
            }
            Kind::Threlfall { mu, v0 } => -mu * 3.0 / v0 * (-3.0 * a / v0).exp(),
            Kind::Stribeck {
                mu_s,
                mu_d,
                v_s,
                v_d,
            } => {
                if a > v_d {
                    0.0
                } else if a >= v_s {
                    let s = (a - v_d) / (v_s - v_d);
                    -(mu_s - mu_d) * 6.0 * s * (1.0 - s) / (v_s - v_d)
                } else {
                    let u = (v_t + v_s) / (2.0 * v_s);
                    -6.0 * mu_s * u * (1.0 - u) / v_s
                }
            }
        }
    }

    /// Friction force F_T (N) along t on body j for slip v_T (m/s) and normal force F_N (N):
    /// opposes v_T, |F_T| ≤ μ_max·F_N; 0 for F_N ≤ 0.
    #[inline]
    pub fn force(&self, v_t: f64, f_n: f64) -> f64 {
        if f_n.is_nan() || f_n <= 0.0 {
            return 0.0;
        }
        self.signed_coefficient(v_t) * f_n
    }

    /// [`force`](Self::force) with its partial derivatives, for Jacobians of implicit
    /// integrators: (F_T (N), ∂F_T/∂v_T (N·s/m), ∂F_T/∂F_N (–)).
    ///
    /// F_T is computed exactly as [`force`](Self::force) computes it (bit for bit). With the
    /// [signed coefficient](Self::signed_coefficient) μ(v_T), F_T = μ(v_T)·F_N, so
    ///
    /// ∂F_T/∂v_T = F_N·μ'(v_T),  ∂F_T/∂F_N = μ(v_T),
    ///
    /// where μ' = dμ/dv_T ([`coefficient_derivative`](Self::coefficient_derivative)) is, with
    /// a = |v_T|:
    /// - Coulomb, regularized: −μ/v_reg for a < v_reg, 0 above (contact-laws.md §2);
    /// - Ambrósio (J. Ambrósio, NATO ASI Virtual Nonlinear Multibody Systems II (2002) 15–33):
    ///   −μ/(v1 − v0) for v0 ≤ a < v1, 0 otherwise; the C¹ variant −6μs(1 − s)/(v1 − v0) with
    ///   s = (a − v0)/(v1 − v0) ∈ [0, 1];
    /// - Threlfall (Mech. Mach. Theory 13 (1978) 475–483): −(3μ/v0)e^{−3a/v0};
    /// - Bai & Zhao / STEP Stribeck (Int. J. Mech. Sci. 54 (2012) 190–205): 0 for a > v_d,
    ///   −6(μ_s − μ_d)s(1 − s)/(v_s − v_d) with s = (a − v_d)/(v_s − v_d) for v_s ≤ a ≤ v_d,
    ///   −6μ_s u(1 − u)/v_s with u = (v_T + v_s)/(2v_s) for a < v_s.
    ///
    /// Non-smooth points: the regularized Coulomb law has kinks at ±v_reg and the linear Ambrósio
    /// ramp at ±v0 and ±v1, where the derivative of the branch with the larger |v_T| is returned;
    /// the C¹ Ambrósio variant, Threlfall (at v_T = 0) and Stribeck (at ±v_s, ±v_d) have a
    /// continuous first derivative. For F_N ≤ 0 or NaN the force is clamped to 0 and all three
    /// components are 0 (the derivative from above at F_N = 0 would be ∂F_T/∂F_N = μ(v_T)).
    /// Allocates nothing.
    #[inline]
    pub fn force_with_derivatives(&self, v_t: f64, f_n: f64) -> (f64, f64, f64) {
        if f_n.is_nan() || f_n <= 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let mu = self.signed_coefficient(v_t);
        (mu * f_n, self.coefficient_derivative(v_t) * f_n, mu)
    }

    /// Largest |μ| the law can produce (–).
    pub fn mu_max(&self) -> f64 {
        match self.kind {
            Kind::Coulomb { mu, .. } | Kind::Ambrosio { mu, .. } | Kind::Threlfall { mu, .. } => mu,
            Kind::Stribeck { mu_s, mu_d, .. } => mu_s.max(mu_d),
        }
    }
}

/// The LuGre friction model (C. Canudas de Wit, H. Olsson, K.J. Åström, P. Lischinsky, IEEE
/// Trans. Autom. Control 40 (1995) 419–425), in friction-coefficient form:
///
/// μ = σ₀z + σ₁ż + σ₂v,  ż = v − σ₀|v|z/g(v),  g(v) = μ_c + (μ_s − μ_c)e^{−(v/v_s)²},
/// F_T = −μ F_N.
///
/// z is the mean bristle deflection (m), one state per contact that the caller integrates.
/// σ₀ in 1/m, σ₁ and σ₂ in s/m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LuGre {
    sigma0: f64,
    sigma1: f64,
    sigma2: f64,
    mu_s: f64,
    mu_c: f64,
    v_s: f64,
}

impl LuGre {
    /// A validated LuGre model: bristle stiffness σ₀ (1/m), bristle damping σ₁ (s/m), viscous
    /// coefficient σ₂ (s/m), static μ_s and Coulomb μ_c coefficients, Stribeck velocity v_s
    /// (m/s).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for σ₀ ≤ 0, σ₁ or σ₂ < 0, μ_c ≤ 0, μ_s ≤ 0 or v_s ≤ 0.
    pub fn new(
        sigma0: f64,
        sigma1: f64,
        sigma2: f64,
        mu_s: f64,
        mu_c: f64,
        v_s: f64,
    ) -> Result<Self, ContactError> {
        const LAW: &str = "LuGre friction";
        Ok(Self {
            sigma0: positive(LAW, "bristle stiffness σ0 (1/m)", sigma0)?,
            sigma1: coefficient(LAW, "bristle damping σ1 (s/m)", sigma1)?,
            sigma2: coefficient(LAW, "viscous coefficient σ2 (s/m)", sigma2)?,
            // μ_s > 0 keeps g(v) > 0: g(0) = μ_s divides in ż (a zero would give 0/0 at rest)
            mu_s: positive(LAW, "static coefficient μ_s (-)", mu_s)?,
            mu_c: positive(LAW, "Coulomb coefficient μ_c (-)", mu_c)?,
            v_s: positive(LAW, "Stribeck velocity v_s (m/s)", v_s)?,
        })
    }

    /// Stribeck curve g(v) = μ_c + (μ_s − μ_c)e^{−(v/v_s)²} (–).
    #[inline]
    pub fn g(&self, v: f64) -> f64 {
        let r = v / self.v_s;
        self.mu_c + (self.mu_s - self.mu_c) * (-r * r).exp()
    }

    /// Bristle rate ż = v − σ₀|v|z/g(v) (m/s) for slip v (m/s) and state z (m).
    #[inline]
    pub fn z_dot(&self, v: f64, z: f64) -> f64 {
        v - self.sigma0 * v.abs() * z / self.g(v)
    }

    /// Derivative of the Stribeck curve, g'(v) = −2(μ_s − μ_c)(v/v_s²)e^{−(v/v_s)²} (s/m).
    #[inline]
    pub fn g_derivative(&self, v: f64) -> f64 {
        let r = v / self.v_s;
        -2.0 * (self.mu_s - self.mu_c) * r / self.v_s * (-r * r).exp()
    }

    /// [`z_dot`](Self::z_dot) with its partial derivatives, for Jacobians of implicit
    /// integrators that carry z as a state: (ż (m/s), ∂ż/∂v (–), ∂ż/∂z (1/s)).
    ///
    /// ż is computed exactly as [`z_dot`](Self::z_dot) computes it (bit for bit). From
    /// ż = v − σ₀|v|z/g(v) (Canudas de Wit, Olsson, Åström, Lischinsky, IEEE Trans. Autom.
    /// Control 40 (1995) 419–425):
    ///
    /// ∂ż/∂v = 1 − σ₀z·[sgn(v)·g(v) − |v|·g'(v)]/g(v)²,  ∂ż/∂z = −σ₀|v|/g(v),
    ///
    /// with g' from [`g_derivative`](Self::g_derivative).
    ///
    /// Non-smooth point: |v| makes ż a kink at v = 0 for z ≠ 0; the one-sided derivatives there are
    /// 1 ∓ σ₀z/g(0), and at v = 0 exactly sgn(0) = 0 gives ∂ż/∂v = 1, their mean. Allocates
    /// nothing.
    #[inline]
    pub fn z_dot_derivatives(&self, v: f64, z: f64) -> (f64, f64, f64) {
        let g = self.g(v);
        let a = v.abs();
        let z_dot = v - self.sigma0 * a * z / g;
        let dg = self.g_derivative(v);
        let d_v = 1.0 - self.sigma0 * z * (sign(v) * g - a * dg) / (g * g);
        let d_z = -self.sigma0 * a / g;
        (z_dot, d_v, d_z)
    }

    /// Friction coefficient μ = σ₀z + σ₁ż + σ₂v (–), positive along the slip.
    #[inline]
    pub fn coefficient(&self, v: f64, z: f64, z_dot: f64) -> f64 {
        self.sigma0 * z + self.sigma1 * z_dot + self.sigma2 * v
    }

    /// Friction force F_T = −μF_N (N) along t for slip v (m/s), state z (m), its rate ż (m/s)
    /// and normal force F_N (N); 0 for F_N ≤ 0.
    #[inline]
    pub fn force(&self, v: f64, z: f64, z_dot: f64, f_n: f64) -> f64 {
        if f_n.is_nan() || f_n <= 0.0 {
            return 0.0;
        }
        -self.coefficient(v, z, z_dot) * f_n
    }

    /// [`force`](Self::force) with its partial derivatives with respect to its four arguments,
    /// for Jacobians of implicit integrators: (F_T (N), ∂F_T/∂v (N·s/m), ∂F_T/∂z (N/m),
    /// ∂F_T/∂ż (N·s/m), ∂F_T/∂F_N (–)).
    ///
    /// F_T is computed exactly as [`force`](Self::force) computes it (bit for bit). From
    /// F_T = −(σ₀z + σ₁ż + σ₂v)F_N (Canudas de Wit et al., IEEE Trans. Autom. Control 40 (1995)
    /// 419–425, friction-coefficient form):
    ///
    /// ∂F_T/∂v = −σ₂F_N, ∂F_T/∂z = −σ₀F_N, ∂F_T/∂ż = −σ₁F_N, ∂F_T/∂F_N = −μ.
    ///
    /// ż is an argument here, held fixed in ∂F_T/∂v and ∂F_T/∂z. When ż = ż(v, z) from
    /// [`z_dot`](Self::z_dot), the total derivatives follow with
    /// [`z_dot_derivatives`](Self::z_dot_derivatives): dF_T/dv = ∂F_T/∂v + ∂F_T/∂ż·∂ż/∂v and
    /// dF_T/dz = ∂F_T/∂z + ∂F_T/∂ż·∂ż/∂z.
    ///
    /// Non-smooth point: for F_N ≤ 0 or NaN the force is clamped to 0 and all five components are
    /// 0 (the derivative from above at F_N = 0 would be ∂F_T/∂F_N = −μ). Allocates nothing.
    #[inline]
    pub fn force_with_derivatives(
        &self,
        v: f64,
        z: f64,
        z_dot: f64,
        f_n: f64,
    ) -> (f64, f64, f64, f64, f64) {
        if f_n.is_nan() || f_n <= 0.0 {
            return (0.0, 0.0, 0.0, 0.0, 0.0);
        }
        let mu = self.coefficient(v, z, z_dot);
        (
            -mu * f_n,
            -self.sigma2 * f_n,
            -self.sigma0 * f_n,
            -self.sigma1 * f_n,
            -mu,
        )
    }

    /// Steady-state bristle deflection z_ss = g(v) sgn(v)/σ₀ (m).
    pub fn steady_state_z(&self, v: f64) -> f64 {
        self.g(v) * sign(v) / self.sigma0
    }

    /// Steady-state coefficient μ_ss = g(v) sgn(v) + σ₂v (–).
    pub fn steady_state_coefficient(&self, v: f64) -> f64 {
        self.g(v) * sign(v) + self.sigma2 * v
    }

    /// Largest steady-state |μ| for slips up to |v| (–): max(μ_s, μ_c) + σ₂|v|.
    pub fn mu_max(&self, v: f64) -> f64 {
        self.mu_s.max(self.mu_c) + self.sigma2 * v.abs()
    }

    /// Bound of the bristle deflection z_max = max(μ_s, μ_c)/σ₀ (m): every steady-state
    /// deflection satisfies |z_ss(v)| ≤ z_max, and |z| stays below it when it starts below it
    /// (Canudas de Wit et al. 1995, Property 1). The natural scale of z, e.g. for an
    /// integrator's absolute tolerance.
    pub fn z_max(&self) -> f64 {
        self.mu_s.max(self.mu_c) / self.sigma0
    }
}

fn sign(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}
