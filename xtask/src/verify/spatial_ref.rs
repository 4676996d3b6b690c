//! Closed-form references for the spatial verify cases (issue 31). Standard library only.
//!
//! 1. Jacobi elliptic functions sn, cn, dn and the complete elliptic integral K by the
//!    arithmetic–geometric mean (descending Landen transformation), Abramowitz & Stegun,
//!    *Handbook of Mathematical Functions* (1964), 16.4 and 17.6; the incomplete integral
//!    F(φ|m) by Carlson's duplication algorithm (DLMF 19.25.5, 19.36.1; B. C. Carlson,
//!    "Numerical computation of real or complex elliptic integrals", Numer. Algorithms 10 (1995)).
//! 2. The torque-free asymmetric rigid body (Landau & Lifshitz, *Mechanics*, 3rd ed., §37).
//! 3. The heavy symmetric top on a fixed point (Goldstein, Poole & Safko, *Classical Mechanics*,
//!    3rd ed., §5.7).
//! 4. The rigid conical pendulum: the heavy top's steady precession without relative spin.
//!
//! Conventions: the parameter m = k² of the elliptic functions (A&S 16.1); angles in rad, times
//! in s, angular rates in rad/s, moments of inertia in kg·m², masses in kg, lengths in m,
//! g in m/s². Euler angles of the top: z-x-z (φ about the space vertical Z pointing up, θ about
//! the line of nodes, ψ about the body symmetry axis 3), θ measured from the upward vertical.

// `TorqueFreeBody::{flip_interval, regime, energy, momentum_sq}` are not used by the verify
// cases (kept with their unit tests for later cases).
#![allow(dead_code)]

use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt;

/// Invalid input to a reference function; the message says what to change.
#[derive(Debug, Clone, PartialEq)]
pub enum RefError {
    /// A physical constant that must be positive and finite is not.
    NotPositive {
        /// Name of the input.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// An input that must be finite is NaN or infinite.
    NotFinite {
        /// Name of the input.
        what: &'static str,
    },
    /// An angle lies outside the range where the reference is defined.
    AngleOutOfRange {
        /// Name of the angle.
        what: &'static str,
        /// The value given (rad).
        value: f64,
        /// The admissible range, in words.
        range: &'static str,
    },
    /// Steady precession needs I3²ω3² ≥ 4 I1 m g l cos θ (Goldstein 3rd ed. eq. 5.77).
    SpinTooSlow {
        /// The spin ω3 given (rad/s).
        omega3: f64,
        /// The smallest |ω3| with a steady precession at this θ (rad/s).
        min_omega3: f64,
    },
    /// A rigid conical rotation needs m g l / ((I1 − I3) cos θ) > 0.
    NoConicalMotion {
        /// (I1 − I3) cos θ_cone (kg·m²).
        denominator: f64,
    },
}

impl fmt::Display for RefError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotPositive { what, value } => {
                write!(f, "{what} = {value} must be positive and finite")
            }
            Self::NotFinite { what } => write!(f, "{what} must be finite"),
            Self::AngleOutOfRange { what, value, range } => {
                write!(f, "{what} = {value} rad must lie in {range}")
            }
            Self::SpinTooSlow { omega3, min_omega3 } => write!(
                f,
                "no steady precession for spin ω3 = {omega3} rad/s: raise |ω3| to at least \
                 {min_omega3} rad/s or lower the top below the horizontal"
            ),
            Self::NoConicalMotion { denominator } => write!(
                f,
                "no rigid conical rotation: (I1 − I3)·cos θ = {denominator} kg·m² must be > 0 \
                 (a prolate body I1 > I3 must hang below the pivot, an oblate one stand above it)"
            ),
        }
    }
}

impl std::error::Error for RefError {}

fn positive(what: &'static str, value: f64) -> Result<f64, RefError> {
    if value > 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(RefError::NotPositive { what, value })
    }
}

fn non_negative(what: &'static str, value: f64) -> Result<f64, RefError> {
    if value >= 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(RefError::NotPositive { what, value })
    }
}

fn finite(what: &'static str, value: f64) -> Result<f64, RefError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(RefError::NotFinite { what })
    }
}

// ---------------------------------------------------------------------------------------------
// 1. Elliptic functions
// ---------------------------------------------------------------------------------------------

/// Longest AGM ladder kept; the AGM converges quadratically, even 1 − m = 1e-300 needs < 20.
const AGM_MAX: usize = 40;

/// The descending Landen (AGM) scale of A&S 16.4.1–2 / 17.6.1: a₀ = 1, b₀ = √(1−m), c₀ = √m,
/// aₙ = (aₙ₋₁ + bₙ₋₁)/2, bₙ = √(aₙ₋₁bₙ₋₁), cₙ = (aₙ₋₁ − bₙ₋₁)/2, stopped at the first N with
/// c_N ≤ ε·a_N (then a_N equals the AGM to the last bit). Fixed arrays: no allocation.
struct AgmLadder {
    a: [f64; AGM_MAX + 1],
    c: [f64; AGM_MAX + 1],
    n: usize,
}

impl AgmLadder {
    /// Ladder for 0 ≤ m < 1.
    fn new(m: f64) -> Self {
        let mut a = [0.0; AGM_MAX + 1];
        let mut c = [0.0; AGM_MAX + 1];
        a[0] = 1.0;
        c[0] = m.sqrt();
        let mut b = (1.0 - m).sqrt();
        let mut n = 0;
        while c[n] > f64::EPSILON * a[n] && n < AGM_MAX {
            let (an, bn) = (a[n], b);
            a[n + 1] = 0.5 * (an + bn);
            c[n + 1] = 0.5 * (an - bn);
            b = (an * bn).sqrt();
            n += 1;
        }
        Self { a, c, n }
    }
}

/// Complete elliptic integral of the first kind K(m) = ∫₀^{π/2} dθ / √(1 − m sin²θ)
/// (dimensionless), by the AGM: K = π / (2 a_N) (A&S 17.6.3–4).
///
/// Domain 0 ≤ m ≤ 1; K(1) = +∞; NaN outside the domain or for NaN input.
pub fn ellip_k(m: f64) -> f64 {
    if !(0.0..=1.0).contains(&m) {
        return f64::NAN;
    }
    if m == 1.0 {
        return f64::INFINITY;
    }
    let l = AgmLadder::new(m);
    PI / (2.0 * l.a[l.n])
}

/// Values of the three Jacobi elliptic functions at one argument (dimensionless).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobi {
    /// sn(u|m) = sin am(u|m).
    pub sn: f64,
    /// cn(u|m) = cos am(u|m).
    pub cn: f64,
    /// dn(u|m) = √(1 − m sn²) > 0.
    pub dn: f64,
}

/// Jacobi elliptic functions sn, cn, dn of argument u (dimensionless) and parameter m = k²,
/// by the descending Landen transformation (A&S 16.4.3): φ_N = 2ᴺ a_N u,
/// φₙ₋₁ = ½ [φₙ + arcsin((cₙ/aₙ) sin φₙ)], sn = sin φ₀, cn = cos φ₀; dn from A&S 16.9.1 as
/// dn = √(m₁ + m cn²) with m₁ = 1 − m (sum of non-negative terms: absolute accuracy ~1e-16).
///
/// Limits: m = 0 gives (sin u, cos u, 1); m = 1 gives (tanh u, sech u, sech u) (A&S 16.6).
/// Domain 0 ≤ m ≤ 1 (NaN outside). The absolute error grows like 1e-16·|u| (argument
/// conditioning), so reduce u by multiples of 4K beforehand for |u| ≫ 1e3.
pub fn jacobi(u: f64, m: f64) -> Jacobi {
    if !(0.0..=1.0).contains(&m) || u.is_nan() {
        return Jacobi {
            sn: f64::NAN,
            cn: f64::NAN,
            dn: f64::NAN,
        };
    }
    if m == 1.0 {
        let sech = 1.0 / u.cosh();
        return Jacobi {
            sn: u.tanh(),
            cn: sech,
            dn: sech,
        };
    }
    let l = AgmLadder::new(m);
    let mut phi = (2.0_f64).powi(l.n as i32) * l.a[l.n] * u;
    for k in (1..=l.n).rev() {
        phi = 0.5 * (phi + (l.c[k] / l.a[k] * phi.sin()).asin());
    }
    let (sn, cn) = phi.sin_cos();
    Jacobi {
        sn,
        cn,
        dn: ((1.0 - m) + m * cn * cn).sqrt(),
    }
}

/// Carlson's symmetric integral R_F(x, y, z) = ½∫₀^∞ dt / √((t+x)(t+y)(t+z)) (DLMF 19.16.1)
/// by the duplication theorem (DLMF 19.26.18) and the fifth-order series of DLMF 19.36.1
/// (Carlson 1995, algorithm for R_F; relative error ~ tol⁶ with tol = 1e-3, i.e. < 1e-17).
/// x, y, z ≥ 0 with at most one zero.
fn carlson_rf(x: f64, y: f64, z: f64) -> f64 {
    const TOL: f64 = 1e-3;
    let (mut x, mut y, mut z) = (x, y, z);
    for _ in 0..100 {
        let mean = (x + y + z) / 3.0;
        let (dx, dy, dz) = (1.0 - x / mean, 1.0 - y / mean, 1.0 - z / mean);
        if dx.abs().max(dy.abs()).max(dz.abs()) < TOL {
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 + (e2 / 24.0 - 0.1 - 3.0 / 44.0 * e3) * e2 + e3 / 14.0) / mean.sqrt();
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
    f64::INFINITY
}

/// Incomplete elliptic integral of the first kind F(φ|m) = ∫₀^φ dθ / √(1 − m sin²θ)
/// (dimensionless; φ in rad), the inverse of the amplitude: sn(F(φ|m)|m) = sin φ.
///
/// F(φ|m) = sin φ · R_F(cos²φ, 1 − m sin²φ, 1) for |φ| ≤ π/2 (DLMF 19.25.5), extended by
/// F(φ + nπ|m) = F(φ|m) + 2nK(m) (A&S 17.4.3). Domain 0 ≤ m ≤ 1 (NaN outside).
pub fn ellip_f(phi: f64, m: f64) -> f64 {
    if !(0.0..=1.0).contains(&m) || !phi.is_finite() {
        return f64::NAN;
    }
    let n = (phi / PI).round();
    let r = phi - n * PI;
    let (s, c) = r.sin_cos();
    let base = s * carlson_rf(c * c, c * c + (1.0 - m) * s * s, 1.0);
    if n == 0.0 {
        base
    } else {
        base + 2.0 * n * ellip_k(m)
    }
}

// ---------------------------------------------------------------------------------------------
// 2. Torque-free asymmetric rigid body
// ---------------------------------------------------------------------------------------------

/// Which family of the torque-free motion (Landau & Lifshitz §37) the initial data select.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FreeRegime {
    /// L² > 2E·I_mid: ω circulates about the axis of largest moment, whose component keeps its
    /// sign (the dn component).
    AboutLargestAxis,
    /// L² < 2E·I_mid: ω circulates about the axis of smallest moment (the dn component).
    AboutSmallestAxis,
    /// L² = 2E·I_mid (m = 1): the separatrix; ω tends to the intermediate axis, period ∞.
    Separatrix,
    /// ω is constant: ω = 0, a spherical body, a rotation exactly about a principal axis of a
    /// degenerate eigenspace, or exactly about the intermediate axis (unstable equilibrium).
    Steady,
}

/// Closed-form body-frame angular velocity of a torque-free rigid body
/// (Landau & Lifshitz, *Mechanics*, §37, eqs. 37.8–37.10 and the M² < 2EI₂ case obtained by
/// exchanging the first and third axes).
///
/// Axis mapping: the moments are sorted internally, I_a, I_b, I_c with b the intermediate axis,
/// c the axis whose component keeps its sign (largest axis if L² > 2E·I_b, smallest if
/// L² < 2E·I_b) and a the remaining one. The solution is
/// ω_a = A cn τ, ω_b = B sn τ, ω_c = σ C dn τ, τ = λ t + τ₀, with
/// A² = (2EI_c − L²)/(I_a(I_c − I_a)), B² = (2EI_c − L²)/(I_b(I_c − I_b)),
/// C² = (L² − 2EI_a)/(I_c(I_c − I_a)), |λ| = √((I_c − I_b)(L² − 2EI_a)/(I_aI_bI_c)),
/// λ = ε σ sgn(I_c − I_b) |λ| (ε = +1 if (a, b, c) is a cyclic order of the caller's axes,
/// −1 otherwise; this sign follows from substituting into Euler's equations),
/// m = (I_b − I_a)(2EI_c − L²)/((I_c − I_b)(L² − 2EI_a)), σ = sign ω_c(0), and the phase τ₀
/// from am(τ₀) = atan2(ω_b(0)/B, ω_a(0)/A). These differences are evaluated as sums of
/// non-negative terms in ω₀ (no cancellation). All inputs and outputs use the caller's axis
/// order; the sorting is invisible to the caller.
#[derive(Debug, Clone, PartialEq)]
pub struct TorqueFreeBody {
    inertia: [f64; 3],
    omega0: [f64; 3],
    /// Caller's axis indices of (a, b, c).
    axes: [usize; 3],
    /// (A, B, C) in rad/s.
    amplitude: [f64; 3],
    sigma: f64,
    /// Signed rate of the elliptic argument, 1/s.
    lambda: f64,
    m: f64,
    tau0: f64,
    regime: FreeRegime,
}

impl TorqueFreeBody {
    /// Solution for principal moments `inertia` (kg·m², positive, any order) and the initial
    /// body angular velocity `omega0` (rad/s, components along the same principal axes).
    pub fn new(inertia: [f64; 3], omega0: [f64; 3]) -> Result<Self, RefError> {
        for (k, &i) in inertia.iter().enumerate() {
            positive(["inertia[0]", "inertia[1]", "inertia[2]"][k], i)?;
            finite(["omega0[0]", "omega0[1]", "omega0[2]"][k], omega0[k])?;
        }
        let mut s = [0, 1, 2];
        s.sort_by(|&p, &q| inertia[p].total_cmp(&inertia[q]));
        let (i1, i2, i3) = (inertia[s[0]], inertia[s[1]], inertia[s[2]]);
        let (w1, w3) = (omega0[s[0]], omega0[s[2]]);
        // 2E·I2 − L² (L&L §37): its sign picks the family.
        let d = i1 * (i2 - i1) * w1 * w1 - i3 * (i3 - i2) * w3 * w3;
        let axes = if d <= 0.0 {
            [s[0], s[1], s[2]]
        } else {
            [s[2], s[1], s[0]]
        };
        let mut body = Self {
            inertia,
            omega0,
            axes,
            amplitude: [0.0; 3],
            sigma: 1.0,
            lambda: 0.0,
            m: 0.0,
            tau0: 0.0,
            regime: FreeRegime::Steady,
        };
        body.solve(d);
        Ok(body)
    }

    /// Fills amplitudes, rate, parameter and phase (L&L §37) for the chosen axis labelling.
    fn solve(&mut self, d: f64) {
        let [a, b, c] = self.axes;
        let (ia, ib, ic) = (self.inertia[a], self.inertia[b], self.inertia[c]);
        let (wa, wb, wc) = (self.omega0[a], self.omega0[b], self.omega0[c]);
        // P = 2EI_c − L², Q = L² − 2EI_a, each a sum of terms of one sign.
        let p = ia * (ic - ia) * wa * wa + ib * (ic - ib) * wb * wb;
        let q = ib * (ib - ia) * wb * wb + ic * (ic - ia) * wc * wc;
        let lambda2 = (ic - ib) * q / (ia * ib * ic);
        if lambda2 <= 0.0 || (wa == 0.0 && wc == 0.0) {
            return; // Steady: ω constant.
        }
        self.sigma = if wc < 0.0 { -1.0 } else { 1.0 };
        // Sign of λ from I_a ω̇_a = ε(I_b − I_c)ω_bω_c, ε = +1 if (a, b, c) is a cyclic order of
        // the caller's axes: λ = ε σ sgn(I_c − I_b) |λ|.
        let cyclic = if (b + 3 - a) % 3 == 1 { 1.0 } else { -1.0 };
        let turn = if ic > ib { 1.0 } else { -1.0 };
        self.lambda = cyclic * turn * self.sigma * lambda2.sqrt();
        self.m = if d == 0.0 {
            1.0
        } else {
            ((ib - ia) * p / ((ic - ib) * q)).clamp(0.0, 1.0)
        };
        self.amplitude = [
            (wa * wa + ib * (ic - ib) / (ia * (ic - ia)) * wb * wb).sqrt(),
            (ia * (ic - ia) / (ib * (ic - ib)) * wa * wa + wb * wb).sqrt(),
            (wc * wc + ib * (ib - ia) / (ic * (ic - ia)) * wb * wb).sqrt(),
        ];
        let [amp_a, amp_b, _] = self.amplitude;
        let am0 = if amp_a > 0.0 {
            (wb / amp_b).atan2(wa / amp_a)
        } else {
            0.0
        };
        self.tau0 = ellip_f(am0, self.m);
        self.regime = if self.m == 1.0 || d == 0.0 {
            FreeRegime::Separatrix
        } else if self.inertia[c] > self.inertia[a] {
            FreeRegime::AboutLargestAxis
        } else {
            FreeRegime::AboutSmallestAxis
        };
    }

    /// Body-frame angular velocity ω(t) (rad/s) at time t (s), components in the caller's axis
    /// order. Does not allocate.
    pub fn omega(&self, t: f64) -> [f64; 3] {
        if self.regime == FreeRegime::Steady {
            return self.omega0;
        }
        let j = jacobi(self.tau0 + self.lambda * t, self.m);
        let [a, b, c] = self.axes;
        let mut w = [0.0; 3];
        w[a] = self.amplitude[0] * j.cn;
        w[b] = self.amplitude[1] * j.sn;
        w[c] = self.sigma * self.amplitude[2] * j.dn;
        w
    }

    /// Full period T (s) of the body-frame angular velocity: the smallest T > 0 with
    /// ω(t + T) = ω(t), T = 4K(m)/|λ| (L&L §37, cn and sn have period 4K). +∞ on the
    /// separatrix and in the `Steady` regime with λ = 0. For a rotation exactly about the
    /// largest or smallest axis ω is constant and T is the linearised wobble period 2π/|λ|.
    pub fn period(&self) -> f64 {
        if self.lambda == 0.0 || self.m >= 1.0 {
            return f64::INFINITY;
        }
        4.0 * ellip_k(self.m) / self.lambda.abs()
    }

    /// Time between flips T/2 (s): after T/2 the two components ω_a, ω_b change sign and ω_c
    /// returns, ω(t + T/2) = (−ω_a, −ω_b, ω_c)(t); this is the interval between the reversals
    /// of the intermediate-axis component (the "Dzhanibekov flip").
    pub fn flip_interval(&self) -> f64 {
        0.5 * self.period()
    }

    /// The elliptic parameter m = k² of the solution (dimensionless, 0 ≤ m ≤ 1).
    pub fn parameter(&self) -> f64 {
        self.m
    }

    /// The family of the motion selected by the initial data.
    pub fn regime(&self) -> FreeRegime {
        self.regime
    }

    /// Caller's axis indices (a, b, c): ω_a ∝ cn, ω_b ∝ sn (intermediate axis), ω_c ∝ dn.
    pub fn axes(&self) -> [usize; 3] {
        self.axes
    }

    /// Kinetic energy E = ½ Σ Iᵢωᵢ² (J) of a body angular velocity `w` (rad/s).
    pub fn energy(&self, w: [f64; 3]) -> f64 {
        0.5 * (0..3).map(|k| self.inertia[k] * w[k] * w[k]).sum::<f64>()
    }

    /// Squared angular momentum L² = Σ (Iᵢωᵢ)² (kg²·m⁴/s²) of a body angular velocity `w`.
    pub fn momentum_sq(&self, w: [f64; 3]) -> f64 {
        (0..3).map(|k| (self.inertia[k] * w[k]).powi(2)).sum()
    }
}

// ---------------------------------------------------------------------------------------------
// 3. Heavy symmetric top
// ---------------------------------------------------------------------------------------------

/// A heavy symmetric top with its tip on a fixed frictionless pivot (Goldstein 3rd ed. §5.7).
/// Body axis 3 is the symmetry axis from the pivot through the centre of mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeavyTop {
    /// Mass m (kg).
    pub mass: f64,
    /// Distance l from the pivot to the centre of mass along the symmetry axis (m).
    pub com_distance: f64,
    /// Gravitational acceleration g (m/s², acting along −Z).
    pub gravity: f64,
    /// Transverse moment of inertia I1 about the pivot (kg·m²), I1 = I1,cm + m l².
    pub i1: f64,
    /// Axial moment of inertia I3 (kg·m², zero allowed for a point mass on a massless rod).
    pub i3: f64,
}

/// Initial state of the top in z-x-z Euler angles; φ and ψ are cyclic and not needed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TopState {
    /// Nutation angle θ (rad) of the symmetry axis from the upward vertical, 0 < θ < π.
    pub theta: f64,
    /// Precession rate φ̇ (rad/s) about the space vertical Z.
    pub phi_dot: f64,
    /// Nutation rate θ̇ (rad/s).
    pub theta_dot: f64,
    /// Spin rate ψ̇ (rad/s) about the symmetry axis relative to the line of nodes.
    pub psi_dot: f64,
}

/// Bounds and period of the nutation of a heavy symmetric top.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nutation {
    /// Smallest nutation angle reached (rad), the upper turning point u₂ = cos θ_min.
    pub theta_min: f64,
    /// Largest nutation angle reached (rad), the lower turning point u₁ = cos θ_max.
    pub theta_max: f64,
    /// The three roots u₁ ≤ u₂ ≤ u₃ of f(u) (u₃ ≥ 1 unphysical; +∞ when g = 0).
    pub roots: [f64; 3],
    /// Nutation period (s): time for θ to go θ_min → θ_max → θ_min,
    /// T = 4K(k²)/√(β(u₃ − u₁)), k² = (u₂ − u₁)/(u₃ − u₁) (Byrd & Friedman 233.00).
    /// For a double root (steady precession) it is the period of small nutations.
    pub period: f64,
}

/// The two steady-precession rates at one nutation angle and spin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyPrecession {
    /// Slow precession rate φ̇ (rad/s), the root of smaller magnitude.
    pub slow: f64,
    /// Fast precession rate φ̇ (rad/s); `None` at θ = π/2 where the quadratic is linear.
    pub fast: Option<f64>,
}

impl HeavyTop {
    /// A top; `mass`, `i1` must be positive, `com_distance`, `gravity`, `i3` non-negative.
    pub fn new(
        mass: f64,
        com_distance: f64,
        gravity: f64,
        i1: f64,
        i3: f64,
    ) -> Result<Self, RefError> {
        Ok(Self {
            mass: positive("mass", mass)?,
            com_distance: non_negative("com_distance", com_distance)?,
            gravity: non_negative("gravity", gravity)?,
            i1: positive("i1", i1)?,
            i3: non_negative("i3", i3)?,
        })
    }

    /// m g l (N·m): the gravity torque at θ = π/2.
    pub fn mgl(&self) -> f64 {
        self.mass * self.gravity * self.com_distance
    }

    /// Nutation turning points and period for an initial state (Goldstein 3rd ed. §5.7,
    /// eqs. 5.62–5.66): with u = cos θ, a = I3ω3/I1, b = p_φ/I1, β = 2mgl/I1 and
    /// α = 2E′/I1 = θ̇² + φ̇² sin²θ + βu (at t = 0), u̇² = f(u) = (1 − u²)(α − βu) − (b − au)².
    /// f(±1) ≤ 0 ≤ f(u₀) = sin²θ₀ θ̇₀², so the turning points u₁ ≤ u₀ ≤ u₂ are found by bisection
    /// on [−1, u₀] and [u₀, 1] to the last bit (a double root, i.e. steady precession, is
    /// resolved only to ~1e-8, the square root of the rounding of f).
    pub fn nutation(&self, s: TopState) -> Result<Nutation, RefError> {
        let c = self.constants(s)?;
        let u0 = s.theta.cos();
        let u1 = bisect(|u| c.f(u), -1.0, u0);
        let u2 = bisect(|u| -c.f(u), u0, 1.0);
        // Vieta: u₁ + u₂ + u₃ = (α + a²)/β; written without dividing by β (g = 0 allowed).
        let spread = c.alpha + c.a * c.a - c.beta * (2.0 * u1 + u2); // β(u₃ − u₁)
        let u3 = if c.beta > 0.0 {
            u1 + spread / c.beta
        } else {
            f64::INFINITY
        };
        let period = 4.0 * ellip_k((c.beta * (u2 - u1) / spread).clamp(0.0, 1.0)) / spread.sqrt();
        Ok(Nutation {
            theta_min: u2.clamp(-1.0, 1.0).acos(),
            theta_max: u1.clamp(-1.0, 1.0).acos(),
            roots: [u1, u2, u3],
            period,
        })
    }

    /// The constants a, b, α, β of Goldstein eqs. 5.62–5.65 for the state `s`.
    fn constants(&self, s: TopState) -> Result<TopConstants, RefError> {
        if !(s.theta > 0.0 && s.theta < PI) {
            return Err(RefError::AngleOutOfRange {
                what: "theta",
                value: s.theta,
                range: "(0, π) (Euler angles are singular on the vertical)",
            });
        }
        finite("phi_dot", s.phi_dot)?;
        finite("theta_dot", s.theta_dot)?;
        finite("psi_dot", s.psi_dot)?;
        let (sin, cos) = s.theta.sin_cos();
        let omega3 = s.psi_dot + s.phi_dot * cos;
        let a = self.i3 * omega3 / self.i1;
        let beta = 2.0 * self.mgl() / self.i1;
        Ok(TopConstants {
            a,
            b: s.phi_dot * sin * sin + a * cos,
            alpha: s.theta_dot * s.theta_dot + (s.phi_dot * sin).powi(2) + beta * cos,
            beta,
        })
    }

    /// The two steady-precession rates φ̇ at nutation angle `theta` (rad, 0 < θ < π) and spin
    /// ω3 = ψ̇ + φ̇ cos θ (rad/s): the roots of I1 cos θ φ̇² − I3ω3 φ̇ + mgl = 0 (Goldstein
    /// 3rd ed. eq. 5.76, from θ̈ = 0 in the θ Lagrange equation), computed in the
    /// cancellation-free form q = ½(I3ω3 + sgn(ω3)√D), slow = mgl/q, fast = q/(I1 cos θ),
    /// D = I3²ω3² − 4 I1 mgl cos θ.
    pub fn steady_precession(&self, theta: f64, omega3: f64) -> Result<SteadyPrecession, RefError> {
        if !(theta > 0.0 && theta < PI) {
            return Err(RefError::AngleOutOfRange {
                what: "theta",
                value: theta,
                range: "(0, π)",
            });
        }
        finite("omega3", omega3)?;
        let quad = self.i1 * theta.cos();
        let lin = self.i3 * omega3;
        let disc = lin * lin - 4.0 * quad * self.mgl();
        if disc < 0.0 {
            return Err(RefError::SpinTooSlow {
                omega3,
                min_omega3: (4.0 * quad * self.mgl()).sqrt() / self.i3,
            });
        }
        let root = if omega3 < 0.0 {
            -disc.sqrt()
        } else {
            disc.sqrt()
        };
        let q = 0.5 * (lin + root);
        if q == 0.0 {
            return Ok(SteadyPrecession {
                slow: 0.0,
                fast: Some(0.0),
            });
        }
        Ok(SteadyPrecession {
            slow: self.mgl() / q,
            fast: (quad != 0.0).then(|| q / quad),
        })
    }
}

/// Goldstein's constants of the heavy top (eqs. 5.62–5.65), all per I1.
struct TopConstants {
    /// a = I3ω3/I1 (rad/s).
    a: f64,
    /// b = p_φ/I1 (rad/s).
    b: f64,
    /// α = 2E′/I1 (1/s²).
    alpha: f64,
    /// β = 2mgl/I1 (1/s²).
    beta: f64,
}

impl TopConstants {
    /// f(u) = (1 − u²)(α − βu) − (b − au)² = u̇² (1/s², Goldstein eq. 5.66).
    fn f(&self, u: f64) -> f64 {
        (1.0 - u) * (1.0 + u) * (self.alpha - self.beta * u) - (self.b - self.a * u).powi(2)
    }
}

/// Root of `g` in [lo, hi] assuming g(lo) ≤ 0 ≤ g(hi), by bisection to adjacent doubles.
fn bisect(g: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if g(mid) >= 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

// ---------------------------------------------------------------------------------------------
// 4. Rigid conical pendulum
// ---------------------------------------------------------------------------------------------

/// Angular velocity Ω (rad/s, > 0; −Ω is the same motion in the other sense) of a symmetric
/// body on a spherical pivot turning rigidly about the vertical at a constant cone angle
/// `theta_cone` (rad) measured from the DOWNWARD vertical:
/// Ω² = m g l / ((I1 − I3) cos θ_cone), I1 transverse and I3 axial moments about the pivot.
///
/// This is the heavy top's steady precession (Goldstein eq. 5.76) with no spin relative to the
/// precessing frame, ψ̇ = 0: with θ_top = π − θ_cone and ω3 = Ω cos θ_top, the condition
/// I1 cos θ_top Ω² − I3 ω3 Ω + mgl = 0 becomes (I1 − I3) cos θ_top Ω² + mgl = 0. For a point mass
/// on a massless rod (I1 = m l², I3 = 0) it reduces to the textbook Ω² = g/(l cos θ_cone).
/// Requires (I1 − I3) cos θ_cone > 0 and m g l > 0.
pub fn conical_pendulum_rate(top: &HeavyTop, theta_cone: f64) -> Result<f64, RefError> {
    if !(theta_cone > 0.0 && theta_cone < PI) || theta_cone == FRAC_PI_2 {
        return Err(RefError::AngleOutOfRange {
            what: "theta_cone",
            value: theta_cone,
            range: "(0, π) without π/2",
        });
    }
    let denominator = (top.i1 - top.i3) * theta_cone.cos();
    positive("m g l", top.mgl())?;
    if denominator <= 0.0 {
        return Err(RefError::NoConicalMotion { denominator });
    }
    Ok((top.mgl() / denominator).sqrt())
}

// ---------------------------------------------------------------------------------------------
// Tests: every closed form against an independent formulation (RK4 of the equations of motion,
// quadrature, textbook special values).
// ---------------------------------------------------------------------------------------------

#[cfg(test)]
mod tests {
    use super::*;

    /// One classical RK4 step of y' = f(y) (autonomous).
    fn rk4<const N: usize>(f: &impl Fn(&[f64; N]) -> [f64; N], y: &[f64; N], h: f64) -> [f64; N] {
        let add = |y: &[f64; N], k: &[f64; N], s: f64| -> [f64; N] {
            let mut r = *y;
            for i in 0..N {
                r[i] += s * k[i];
            }
            r
        };
        let k1 = f(y);
        let k2 = f(&add(y, &k1, 0.5 * h));
        let k3 = f(&add(y, &k2, 0.5 * h));
        let k4 = f(&add(y, &k3, h));
        let mut r = *y;
        for i in 0..N {
            r[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        r
    }

    fn close(x: f64, y: f64, tol: f64, what: &str) {
        assert!(
            (x - y).abs() <= tol,
            "{what}: {x} vs {y}, |Δ| = {:e} > {tol:e}",
            (x - y).abs()
        );
    }

    // ---- 1. elliptic functions ----

    /// Independent K: trapezoidal rule on the periodic integrand over a full period (exponentially
    /// convergent, Trefethen & Weideman, SIAM Review 56 (2014) 385), 4000 nodes.
    fn k_trapezoid(m: f64) -> f64 {
        let n = 4000;
        let h = 2.0 * PI / n as f64;
        let s: f64 = (0..n)
            .map(|i| 1.0 / (1.0 - m * (i as f64 * h).sin().powi(2)).sqrt())
            .sum();
        0.25 * s * h
    }

    #[test]
    fn k_matches_gamma_closed_form_table_and_quadrature() {
        // Lemniscatic case K(1/2) = Γ(1/4)²/(4√π) (Whittaker & Watson §22.8),
        // Γ(1/4) = 3.6256099082219083119.
        let gamma_quarter = 3.625_609_908_221_908_f64;
        let k_half = gamma_quarter * gamma_quarter / (4.0 * PI.sqrt());
        close(ellip_k(0.5), k_half, 4e-16, "K(1/2)");
        close(ellip_k(0.0), FRAC_PI_2, 0.0, "K(0)");
        assert_eq!(ellip_k(1.0), f64::INFINITY);
        assert!(ellip_k(1.5).is_nan() && ellip_k(-0.1).is_nan());
        // A&S Table 17.1 (15 digits).
        for (m, k) in [(0.1, 1.612_441_348_720_219), (0.9, 2.578_092_113_348_173)] {
            close(ellip_k(m), k, 2e-15, "K table 17.1");
        }
        for m in [0.1, 0.3, 0.5, 0.7, 0.9, 0.99] {
            // Tolerance: rounding of the 4000-term sum (~1e-14 relative).
            close(
                ellip_k(m),
                k_trapezoid(m),
                3e-14 * ellip_k(m),
                "K vs trapezoid",
            );
        }
        // Two algorithms (AGM and Carlson R_F) agree: F(π/2|m) = K(m). Tolerance adds the
        // conditioning dF/dφ = 1/k′ times the 6e-17 error of the double nearest π/2.
        for m in [0.0, 0.2, 0.5, 0.9, 0.999_999] {
            let tol = 4e-15 * ellip_k(m) + 1.2e-16 / (1.0 - m).sqrt();
            close(ellip_f(FRAC_PI_2, m), ellip_k(m), tol, "F(π/2) = K");
        }
        // Near m = 1: K = ln(4/k′) + O(k′² ln k′) (A&S 17.3.26); k′ = 2⁻²⁰ so that m = 1 − 2⁻⁴⁰
        // is exact in binary.
        let kp = (2.0f64).powi(-20);
        close(ellip_k(1.0 - kp * kp), (4.0 / kp).ln(), 1e-10, "K near 1");
    }

    #[test]
    fn jacobi_matches_published_values() {
        // Mathematica JacobiSN/CN/DN[u, 1/2], 16 digits, as tabulated by J. Burkardt,
        // test_values (jacobi_sn_values, jacobi_cn_values, jacobi_dn_values), after A&S ch. 16.
        let table = [
            (
                0.1,
                0.099_750_685_474_624_84,
                0.995_012_462_609_058_2,
                0.997_509_348_514_424_3,
            ),
            (
                0.2,
                0.198_021_742_981_970_4,
                0.980_197_627_678_409_8,
                0.990_148_319_522_48,
            ),
            (
                0.5,
                0.470_750_473_655_657_3,
                0.882_266_394_890_440_3,
                0.942_972_425_777_385_7,
            ),
            (
                1.0,
                0.803_001_824_895_643_9,
                0.595_976_567_672_140_7,
                0.823_161_001_631_596_3,
            ),
            (
                2.0,
                0.994_662_325_358_017_7,
                -0.103_183_615_527_761_8,
                0.710_861_047_784_087_3,
            ),
        ];
        for (u, sn, cn, dn) in table {
            let j = jacobi(u, 0.5);
            close(j.sn, sn, 1e-15, "sn table");
            close(j.cn, cn, 1e-15, "cn table");
            close(j.dn, dn, 1e-15, "dn table");
        }
    }

    #[test]
    fn jacobi_limits_and_quarter_period_values() {
        for &u in &[-3.0, -0.4, 0.0, 0.7, 2.5, 11.0] {
            let j = jacobi(u, 0.0);
            close(j.sn, f64::sin(u), 1e-15, "sn(u|0) = sin");
            close(j.cn, f64::cos(u), 1e-15, "cn(u|0) = cos");
            close(j.dn, 1.0, 0.0, "dn(u|0) = 1");
            let j = jacobi(u, 1.0);
            close(j.sn, f64::tanh(u), 0.0, "sn(u|1) = tanh");
            close(j.cn, 1.0 / f64::cosh(u), 0.0, "cn(u|1) = sech");
            // A&S 16.15.1–3: first order in m₁ near m = 1 (non-uniform in u: |u| ≤ 3 only),
            // m₁ = 2⁻³³ ≈ 1.2e-10 (exact in binary), neglected O((m₁ sinh u cosh u)²) < 1e-16.
            if u.abs() > 3.0 {
                continue;
            }
            let m1 = (2.0f64).powi(-33);
            let j = jacobi(u, 1.0 - m1);
            let (sh, ch) = (f64::sinh(u), f64::cosh(u));
            let corr = sh * ch - u;
            close(
                j.sn,
                u.tanh() + 0.25 * m1 * corr / (ch * ch),
                2e-15,
                "sn near m = 1",
            );
            close(
                j.cn,
                1.0 / ch - 0.25 * m1 * corr * u.tanh() / ch,
                2e-15,
                "cn near m = 1",
            );
            close(
                j.dn,
                1.0 / ch + 0.25 * m1 * (sh * ch + u) * u.tanh() / ch,
                2e-15,
                "dn near 1",
            );
        }
        // A&S 16.5: sn(K) = 1, cn(K) = 0, dn(K) = k′; sn(K/2) = 1/√(1+k′), cn(K/2) = √(k′/(1+k′)),
        // dn(K/2) = √k′. Tolerance 2e-15: the rounding of K (~ε·K) enters through the argument.
        for m in [0.1, 0.5, 0.8, 0.99, 0.999_999] {
            let (k, kp) = (ellip_k(m), (1.0 - m).sqrt());
            let j = jacobi(k, m);
            close(j.sn, 1.0, 1e-15, "sn(K)");
            close(j.cn, 0.0, 2e-15, "cn(K)");
            close(j.dn, kp, 2e-15, "dn(K)");
            let j = jacobi(0.5 * k, m);
            close(j.sn, 1.0 / (1.0 + kp).sqrt(), 1e-15, "sn(K/2)");
            close(j.cn, (kp / (1.0 + kp)).sqrt(), 2e-15, "cn(K/2)");
            close(j.dn, kp.sqrt(), 2e-15, "dn(K/2)");
            let j = jacobi(4.0 * k + 0.3, m);
            let j0 = jacobi(0.3, m);
            close(j.sn, j0.sn, 1e-14, "period 4K");
            close(j.cn, j0.cn, 1e-14, "period 4K");
        }
    }

    #[test]
    fn jacobi_identities_addition_theorem_and_ode() {
        // sn² + cn² = 1 and the addition theorem A&S 16.17.1–3 on a grid.
        for m in [0.05, 0.5, 0.9, 0.9999] {
            for iu in -6..=6 {
                for iv in -3..=3 {
                    let (u, v) = (0.37 * iu as f64, 0.53 * iv as f64);
                    let (a, b, s) = (jacobi(u, m), jacobi(v, m), jacobi(u + v, m));
                    close(a.sn * a.sn + a.cn * a.cn, 1.0, 3e-16, "sn² + cn²");
                    let den = 1.0 - m * a.sn * a.sn * b.sn * b.sn;
                    close(
                        s.sn,
                        (a.sn * b.cn * b.dn + b.sn * a.cn * a.dn) / den,
                        3e-15,
                        "sn(u+v)",
                    );
                    close(
                        s.cn,
                        (a.cn * b.cn - a.sn * a.dn * b.sn * b.dn) / den,
                        3e-15,
                        "cn(u+v)",
                    );
                    let dn = (a.dn * b.dn - m * a.sn * a.cn * b.sn * b.cn) / den;
                    close(s.dn, dn, 3e-15, "dn(u+v)");
                }
            }
        }
        // Derivatives A&S 16.16.1–3 integrated by RK4 from (0, 1, 1), h = 1e-3 to u = 10.
        let m = 0.7;
        let f = |y: &[f64; 3]| [y[1] * y[2], -y[0] * y[2], -m * y[0] * y[1]];
        let mut y = [0.0, 1.0, 1.0];
        let h = 1e-3;
        for i in 1..=10_000 {
            y = rk4(&f, &y, h);
            if i % 1000 == 0 {
                let j = jacobi(i as f64 * h, m);
                close(y[0], j.sn, 1e-12, "sn vs ODE");
                close(y[1], j.cn, 1e-12, "cn vs ODE");
                close(y[2], j.dn, 1e-12, "dn vs ODE");
            }
        }
    }

    #[test]
    fn incomplete_integral_inverts_amplitude() {
        // Tolerance 5e-14: F reaches ~30 here and sn, cn carry the argument error ~1e-16·|F|/k′.
        for m in [0.0, 0.3, 0.95, 1.0 - (2.0f64).powi(-33)] {
            for i in -40..=40 {
                let phi = 0.23 * i as f64;
                if m > 0.99 && phi.cos().abs() < 0.1 {
                    continue; // F is huge there; covered by the K tests.
                }
                let j = jacobi(ellip_f(phi, m), m);
                close(j.sn, phi.sin(), 5e-14, "sn(F(φ))");
                close(j.cn, phi.cos(), 5e-14, "cn(F(φ))");
            }
        }
        assert!(ellip_f(0.3, 1.2).is_nan());
    }

    // ---- 2. torque-free body ----

    /// Euler's equations I₁ω̇₁ = (I₂ − I₃)ω₂ω₃ (cyclic), Goldstein eq. 5.39, in the caller's axes.
    fn euler(i: [f64; 3]) -> impl Fn(&[f64; 3]) -> [f64; 3] {
        move |w: &[f64; 3]| {
            let mut d = [0.0; 3];
            for k in 0..3 {
                let (p, q) = ((k + 1) % 3, (k + 2) % 3);
                d[k] = (i[p] - i[q]) / i[k] * w[p] * w[q];
            }
            d
        }
    }

    /// Integrates Euler's equations by RK4 (h = 1e-4 s) and returns the worst deviation of the
    /// closed form over `checks` checkpoints up to t_end, relative to |ω₀|.
    fn worst_vs_rk4(body: &TorqueFreeBody, t_end: f64, checks: usize) -> f64 {
        let f = euler(body.inertia);
        let steps = (t_end / 1e-4).round() as usize;
        let h = t_end / steps as f64;
        let scale = body.omega0.iter().map(|w| w * w).sum::<f64>().sqrt();
        let mut w = body.omega0;
        let mut worst: f64 = 0.0;
        for s in 1..=steps {
            w = rk4(&f, &w, h);
            if s % (steps / checks) == 0 || s == steps {
                let e = body.omega(s as f64 * h);
                for k in 0..3 {
                    worst = worst.max((w[k] - e[k]).abs() / scale);
                }
            }
        }
        worst
    }

    #[test]
    fn torque_free_matches_rk4_in_both_families() {
        // Unsorted moments, mixed signs; L² > 2E·I_mid (largest axis is caller's axis 2).
        let cases = [
            (
                [2.0, 1.0, 3.0],
                [0.4, -0.7, 1.1],
                FreeRegime::AboutLargestAxis,
            ),
            (
                [2.0, 1.0, 3.0],
                [0.4, 0.7, -1.1],
                FreeRegime::AboutLargestAxis,
            ),
            (
                [3.0, 1.0, 2.0],
                [-0.3, 1.2, 0.5],
                FreeRegime::AboutSmallestAxis,
            ),
            (
                [3.0, 1.0, 2.0],
                [0.3, -1.2, -0.5],
                FreeRegime::AboutSmallestAxis,
            ),
            // Near the intermediate axis (Dzhanibekov), m = 1 − O(1e-4) on both sides.
            (
                [1.0, 2.0, 3.0],
                [0.01, 1.0, 0.012],
                FreeRegime::AboutLargestAxis,
            ),
            (
                [1.0, 2.0, 3.0],
                [-0.02, 1.0, 0.01],
                FreeRegime::AboutSmallestAxis,
            ),
        ];
        for (inertia, w0, regime) in cases {
            let body = TorqueFreeBody::new(inertia, w0).unwrap();
            assert_eq!(body.regime(), regime, "{inertia:?} {w0:?}");
            let t = body.period();
            assert!(t.is_finite() && t > 0.0);
            // ω at t = 0 reproduces ω₀ (phase and signs); near the separatrix the phase
            // τ₀ = F(am₀|m) is conditioned by 1/k′ ~ 1e2, hence 1e-14.
            let e = body.omega(0.0);
            for k in 0..3 {
                close(e[k], w0[k], 1e-14, "ω(0)");
            }
            let worst = worst_vs_rk4(&body, 1.5 * t, 30);
            assert!(worst < 1e-9, "{inertia:?} {w0:?}: RK4 deviation {worst:e}");
            // One full period returns ω₀, half a period flips ω_a, ω_b (closed form itself).
            let (wt, wh) = (body.omega(t), body.omega(0.5 * t));
            let [a, b, c] = body.axes();
            close(wt[a], w0[a], 1e-12, "ω_a(T)");
            close(wt[b], w0[b], 1e-12, "ω_b(T)");
            close(wh[a], -w0[a], 1e-12, "ω_a(T/2)");
            close(wh[b], -w0[b], 1e-12, "ω_b(T/2)");
            close(wh[c], w0[c], 1e-12, "ω_c(T/2)");
        }
    }

    #[test]
    fn torque_free_separatrix_matches_rk4() {
        // I = (1, 5, 9), ω₁ = 3ω₃ makes 2E·I₂ − L² = 4ω₁² − 36ω₃² exactly 0 in binary: m = 1,
        // ω_a ∝ sech, ω_b ∝ tanh (L&L §37 limit). The saddle amplifies the RK4 error like e^{λt}
        // (λ ≈ 0.92/s), so 8 s keep it below 1e-9.
        let body = TorqueFreeBody::new([1.0, 5.0, 9.0], [0.75, -0.5, 0.25]).unwrap();
        assert_eq!(body.regime(), FreeRegime::Separatrix);
        assert_eq!(body.period(), f64::INFINITY);
        let worst = worst_vs_rk4(&body, 8.0, 40);
        assert!(worst < 1e-9, "separatrix RK4 deviation {worst:e}");
        // ω tends to the intermediate axis:
        // |ω_b| → B = √(I_a(I_c − I_a)/(I_b(I_c − I_b)) ω_a² + ω_b²).
        let b_amp = (1.0 * 8.0 / (5.0 * 4.0) * 0.75f64.powi(2) + 0.25).sqrt();
        let w = body.omega(40.0);
        close(w[1].abs(), b_amp, 1e-14, "separatrix limit");
        close(w[0], 0.0, 1e-14, "separatrix ω_a → 0");
    }

    #[test]
    fn torque_free_conserves_energy_and_momentum() {
        let body = TorqueFreeBody::new([1.5, 4.0, 2.5], [1.3, -0.2, 0.9]).unwrap();
        let (e0, l0) = (body.energy(body.omega0), body.momentum_sq(body.omega0));
        for i in 0..200 {
            let w = body.omega(0.173 * i as f64);
            close(body.energy(w), e0, 1e-14 * e0, "E");
            close(body.momentum_sq(w), l0, 1e-14 * l0, "L²");
        }
    }

    #[test]
    fn torque_free_symmetric_and_steady_limits() {
        // Symmetric body I1 = I2: the transverse ω turns at Ω = (I3 − I1)ω3/I1 (Goldstein 5.6).
        let (i1, i3, w3) = (2.0, 5.0, 1.7);
        let body = TorqueFreeBody::new([i1, i3, i1], [0.4, w3, 0.0]).unwrap();
        let rate = (i3 - i1) * w3 / i1;
        close(body.period(), 2.0 * PI / rate, 1e-14, "symmetric period");
        for i in 0..50 {
            let t = 0.37 * i as f64;
            let w = body.omega(t);
            // Euler: ω̇₀ = (I₁ − I₂)/I₀ ω₁ω₂ = rate·ω₂, ω̇₂ = −rate·ω₀
            // → ω₀ = 0.4 cos(rate t), ω₂ = −0.4 sin(rate t).
            close(w[0], 0.4 * (rate * t).cos(), 1e-14, "ω₀ symmetric");
            close(w[2], -0.4 * (rate * t).sin(), 1e-14, "ω₂ symmetric");
            close(w[1], w3, 1e-15, "ω₃ symmetric");
        }
        // Exactly about the intermediate axis, a sphere, rest: ω stays constant.
        for (i, w) in [
            ([1.0, 2.0, 3.0], [0.0, 2.0, 0.0]),
            ([2.0, 2.0, 2.0], [0.3, 2.0, -1.0]),
            ([1.0, 2.0, 3.0], [0.0, 0.0, 0.0]),
        ] {
            let body = TorqueFreeBody::new(i, w).unwrap();
            assert_eq!(body.regime(), FreeRegime::Steady);
            assert_eq!(body.omega(7.3), w);
        }
        // Exactly about the largest axis: constant ω, period = linearised wobble period
        // 2π/(ω3 √((I3 − I1)(I3 − I2)/(I1 I2))) (Goldstein §5.6 small-oscillation analysis).
        let body = TorqueFreeBody::new([1.0, 2.0, 3.0], [0.0, 0.0, 1.5]).unwrap();
        assert_eq!(body.omega(3.1), [0.0, 0.0, 1.5]);
        close(
            body.period(),
            2.0 * PI / (1.5 * (2.0f64 * 1.0 / 2.0).sqrt()),
            1e-14,
            "wobble",
        );
        assert!(TorqueFreeBody::new([1.0, -2.0, 3.0], [0.0; 3]).is_err());
        assert!(TorqueFreeBody::new([1.0, 2.0, 3.0], [f64::NAN, 0.0, 0.0]).is_err());
    }

    // ---- 3. heavy top ----

    /// Lagrange equations of the heavy symmetric top in z-x-z Euler angles, state
    /// (θ, φ, ψ, θ̇, φ̇, ψ̇), from L = ½I1(θ̇² + φ̇² sin²θ) + ½I3(ψ̇ + φ̇ cos θ)² − mgl cos θ
    /// (Goldstein eq. 5.59) differentiated directly (no use of the first integrals).
    fn top_rhs(top: HeavyTop) -> impl Fn(&[f64; 6]) -> [f64; 6] {
        move |y: &[f64; 6]| {
            let [th, _, _, thd, phd, psd] = *y;
            let (s, c) = th.sin_cos();
            let w3 = psd + phd * c;
            let thdd = phd * phd * s * c - top.i3 / top.i1 * w3 * phd * s + top.mgl() / top.i1 * s;
            // d/dt p_φ = 0: I1(φ̈ s² + 2φ̇θ̇ s c) − I3 ω3 θ̇ s = 0 (ω̇3 = 0 from the ψ equation).
            let phdd = (top.i3 * w3 * thd - 2.0 * top.i1 * phd * thd * c) / (top.i1 * s);
            // d/dt ω3 = 0: ψ̈ = −φ̈ cos θ + φ̇ θ̇ sin θ.
            let psdd = -phdd * c + phd * thd * s;
            [thd, phd, psd, thdd, phdd, psdd]
        }
    }

    /// RK4 of the top for `t_end` s, h = 1e-4 s; returns the θ extremes located at the sign
    /// changes of θ̇ by cubic Hermite interpolation, the times of those turning points and the
    /// whole-run min/max of θ (for the steady cases).
    struct TopRun {
        turning: Vec<(f64, f64)>,
        min: f64,
        max: f64,
    }

    /// Cubic Hermite interpolant on s ∈ [0, 1] with end values p0, p1 and end slopes m0, m1
    /// (per unit s); returns the value and its s-derivative.
    fn hermite(s: f64, p0: f64, m0: f64, p1: f64, m1: f64) -> (f64, f64) {
        let (s2, s3) = (s * s, s * s * s);
        let v = (2.0 * s3 - 3.0 * s2 + 1.0) * p0
            + (s3 - 2.0 * s2 + s) * m0
            + (-2.0 * s3 + 3.0 * s2) * p1
            + (s3 - s2) * m1;
        let d = (6.0 * s2 - 6.0 * s) * p0
            + (3.0 * s2 - 4.0 * s + 1.0) * m0
            + (-6.0 * s2 + 6.0 * s) * p1
            + (3.0 * s2 - 2.0 * s) * m1;
        (v, d)
    }

    fn run_top(top: HeavyTop, s: TopState, t_end: f64) -> TopRun {
        let f = top_rhs(top);
        let h = 1e-4;
        let mut y = [s.theta, 0.0, 0.0, s.theta_dot, s.phi_dot, s.psi_dot];
        let mut run = TopRun {
            turning: Vec::new(),
            min: s.theta,
            max: s.theta,
        };
        let steps = (t_end / h) as usize;
        for i in 0..steps {
            let yn = rk4(&f, &y, h);
            let (d0, d1) = (y[3], yn[3]);
            if d0 != 0.0 && d0.signum() != d1.signum() {
                // θ̇ as a cubic Hermite in s ∈ [0, 1] (slopes h·θ̈), zero by Newton; θ there
                // from the cubic Hermite of θ (slopes h·θ̇).
                let (a0, a1) = (f(&y)[3], f(&yn)[3]);
                let mut s_ = d0 / (d0 - d1);
                for _ in 0..4 {
                    let (v, dv) = hermite(s_, d0, h * a0, d1, h * a1);
                    s_ -= v / dv;
                }
                let (th, _) = hermite(s_, y[0], h * d0, yn[0], h * d1);
                run.turning.push(((i as f64 + s_) * h, th));
            }
            y = yn;
            run.min = run.min.min(y[0]);
            run.max = run.max.max(y[0]);
        }
        run
    }

    #[test]
    fn nutation_bounds_and_period_match_rk4() {
        let top = HeavyTop::new(1.0, 0.5, 9.81, 0.5, 0.2).unwrap();
        let states = [
            // Released with spin only: starts at θ_min (cusps, Goldstein Fig. 5.9c).
            TopState {
                theta: 0.5,
                phi_dot: 0.0,
                theta_dot: 0.0,
                psi_dot: 20.0,
            },
            // General initial rates: both turning points away from θ₀ (Fig. 5.9a/b).
            TopState {
                theta: 1.0,
                phi_dot: 1.5,
                theta_dot: -0.8,
                psi_dot: 12.0,
            },
            // Below the horizontal, retrograde precession.
            TopState {
                theta: 2.2,
                phi_dot: -2.0,
                theta_dot: 1.1,
                psi_dot: 8.0,
            },
        ];
        for s in states {
            let n = top.nutation(s).unwrap();
            assert!(n.theta_min <= s.theta && s.theta <= n.theta_max);
            let run = run_top(top, s, 3.2 * n.period);
            assert!(
                run.turning.len() >= 5,
                "{s:?}: {} turning points",
                run.turning.len()
            );
            for &(_, th) in &run.turning {
                let near = if (th - n.theta_min).abs() < (th - n.theta_max).abs() {
                    n.theta_min
                } else {
                    n.theta_max
                };
                close(th, near, 1e-9, "turning point vs RK4");
            }
            // Same kind of turning point recurs after one nutation period.
            let (t_a, t_b) = (run.turning[1].0, run.turning[3].0);
            close(t_b - t_a, n.period, 1e-8, "nutation period vs RK4");
        }
        // g = 0: the figure axis cones about L at L/I1 (Goldstein §5.6), so θ (from an
        // arbitrary vertical) has period 2π I1/L, L² = I1²(θ̇² + φ̇² sin²θ) + I3²ω3².
        let free = HeavyTop::new(1.0, 0.5, 0.0, 0.5, 0.2).unwrap();
        let s = states[1];
        let w3 = s.psi_dot + s.phi_dot * s.theta.cos();
        let l = (free.i1.powi(2) * (s.theta_dot.powi(2) + (s.phi_dot * s.theta.sin()).powi(2))
            + (free.i3 * w3).powi(2))
        .sqrt();
        let n = free.nutation(s).unwrap();
        close(
            n.period,
            2.0 * PI * free.i1 / l,
            1e-14,
            "free nutation period",
        );
        assert_eq!(n.roots[2], f64::INFINITY);
        // Bad input is an error, not a panic.
        let bad = TopState {
            theta: 0.0,
            phi_dot: 0.0,
            theta_dot: 0.0,
            psi_dot: 1.0,
        };
        assert!(top.nutation(bad).is_err());
        assert!(HeavyTop::new(1.0, 0.5, 9.81, 0.0, 0.2).is_err());
    }

    #[test]
    fn steady_precession_rates_keep_theta_constant() {
        let top = HeavyTop::new(1.0, 0.5, 9.81, 0.5, 0.2).unwrap();
        for (theta, omega3) in [(0.8, 15.0), (0.8, -15.0), (2.0, 6.0), (FRAC_PI_2, 10.0)] {
            let p = top.steady_precession(theta, omega3).unwrap();
            // At θ = π/2 in floating point cos θ = 6e-17 and the fast root is ~1e17 rad/s.
            let rates = [Some(p.slow), p.fast.filter(|f| f.abs() < 1e3)];
            for phi_dot in rates.into_iter().flatten() {
                // Residual of Goldstein eq. 5.76.
                let res = top.i1 * theta.cos() * phi_dot * phi_dot - top.i3 * omega3 * phi_dot
                    + top.mgl();
                close(
                    res,
                    0.0,
                    1e-12 * top.mgl().max(top.i1 * phi_dot * phi_dot),
                    "eq. 5.76",
                );
                let s = TopState {
                    theta,
                    phi_dot,
                    theta_dot: 0.0,
                    psi_dot: omega3 - phi_dot * theta.cos(),
                };
                let run = run_top(top, s, 3.0);
                close(run.min, theta, 1e-10, "steady θ min (RK4)");
                close(run.max, theta, 1e-10, "steady θ max (RK4)");
                let n = top.nutation(s).unwrap();
                close(n.theta_min, theta, 1e-7, "double root θ_min");
                close(n.theta_max, theta, 1e-7, "double root θ_max");
            }
        }
        // Slow top above the horizontal: no steady precession, error names the spin needed.
        let e = top.steady_precession(0.5, 1.0).unwrap_err();
        assert!(matches!(e, RefError::SpinTooSlow { .. }), "{e}");
    }

    // ---- 4. conical pendulum ----

    #[test]
    fn conical_pendulum_limits_and_consistency() {
        let (m, l, g) = (2.0, 0.7, 9.81);
        for theta_c in [0.2, 0.6, 1.2] {
            // Point mass on a massless rod: Ω² = g/(l cos θ) (e.g. Goldstein §5.7 limit).
            let point = HeavyTop::new(m, l, g, m * l * l, 0.0).unwrap();
            let om = conical_pendulum_rate(&point, theta_c).unwrap();
            close(
                om,
                (g / (l * theta_c.cos())).sqrt(),
                1e-14 * om,
                "point mass",
            );
            // Uniform slender rod of length L hung by its end: Ω² = 3g/(2L cos θ).
            let rod_len = 2.0 * l;
            let rod = HeavyTop::new(m, l, g, m * rod_len * rod_len / 3.0, 0.0).unwrap();
            let om = conical_pendulum_rate(&rod, theta_c).unwrap();
            close(
                om,
                (1.5 * g / (rod_len * theta_c.cos())).sqrt(),
                1e-14 * om,
                "rod",
            );
            // A prolate body with spin-free rigid rotation: one root of the steady-precession
            // quadratic of item 3 at θ_top = π − θ_cone, ω3 = Ω cos θ_top.
            let body = HeavyTop::new(m, l, g, 1.3, 0.4).unwrap();
            let om = conical_pendulum_rate(&body, theta_c).unwrap();
            let th = PI - theta_c;
            let p = body.steady_precession(th, om * th.cos()).unwrap();
            let hit = (p.slow - om).abs().min((p.fast.unwrap() - om).abs());
            assert!(hit < 1e-13 * om, "Ω = {om} not among {p:?}");
            // RK4 of the Lagrange equations: θ stays, ψ̇ stays 0.
            let s = TopState {
                theta: th,
                phi_dot: om,
                theta_dot: 0.0,
                psi_dot: 0.0,
            };
            let run = run_top(body, s, 3.0);
            close(run.min, th, 1e-10, "conical θ min (RK4)");
            close(run.max, th, 1e-10, "conical θ max (RK4)");
        }
        // Oblate body above the pivot turns rigidly too; prolate above it does not.
        let oblate = HeavyTop::new(m, 0.05, g, 0.3, 0.5).unwrap();
        assert!(conical_pendulum_rate(&oblate, 2.5).is_ok());
        let prolate = HeavyTop::new(m, l, g, 1.3, 0.4).unwrap();
        assert!(matches!(
            conical_pendulum_rate(&prolate, 2.5),
            Err(RefError::NoConicalMotion { .. })
        ));
    }
}
