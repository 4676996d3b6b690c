//! The independent formulation of the spatial slider–crank of issue 31 in the crank angle φ
//! alone, the reference of `cargo xtask verify mbd.spatial.slider_crank` (the spatial
//! counterpart of [`crate::minimal_slider_crank`]). No clr code: closed-form loop kinematics,
//! Lagrange's equation, a fixed-step classical Runge–Kutta.
//!
//! The mechanism (own numbers, in the manner of Haug's spatial slider–crank, Haug 1989,
//! *Computer-Aided Kinematics and Dynamics of Mechanical Systems*, §11; SI units), the same as
//! `models/examples/spatial_slider_crank.toml`:
//! - crank: turns about the world x axis through O = (0, 0.06, 0.08) (revolute to ground); pin
//!   A = O + r(0, cos φ, sin φ), r = 0.1; 0.4 kg, centre of mass at O + (r/2)(0, cos φ, sin φ),
//!   moment of inertia about the axis at the centre of mass 4e-4 kg·m²;
//! - rod: spherical joint at A, universal joint at B, length L = 0.3; 1 kg, centre of mass at
//!   A + 0.12 e_w + 0.01 e_3, principal moments (1e-3, 7e-3, 7.5e-3) kg·m² about (e_w, e_h, e_3)
//!   (not axisymmetric, so its spin about its own axis enters the kinetic energy);
//! - slider: 0.5 kg on a prismatic joint along the world x axis, B = (s, 0, 0): a line out of
//!   the crank's plane x = 0 (it crosses the plane at right angles);
//! - universal joint at B: the cross's first pin is on the slider along world z, the second on
//!   the rod along e_h, perpendicular to the rod axis e_w = (B − A)/L;
//! - gravity (0, 0, −9.81) m/s²; no driver, no torque: the crank is started at φ₀ (A at the
//!   origin, on the slider line) with φ̇₀ = 30 rad/s and moves freely.
//!
//! Mobility (Grübler): 6·3 − 5 (revolute) − 3 (spherical) − 4 (universal) − 5 (prismatic) = 1.
//! The rod's spin about e_w is fixed by the universal joint: e_h must be perpendicular to both
//! e_w (a rod-fixed pin across the rod) and the slider's pin z, so e_h = (e_w × z)/|e_w × z|,
//! defined while e_w is not vertical (|A_z| ≤ 0.18 < L here); e_3 = e_w × e_h.
//!
//! Kinematics in closed form (loop closure |B − A| = L on the line B = s x̂):
//! s = A_x + √(L² − A_y² − A_z²) (the far root; the radicand ≥ L² − (|O| + r)² > 0, so the
//! crank turns fully). The rod's angular velocity in its own axes, per unit φ̇, is
//! Ω = (e_h′·e_3, e_3′·e_w, e_w′·e_h) (ė_i = ω × e_i), ′ = d/dφ.
//!
//! Dynamics (Lagrange's equation in φ): T = ½M(φ)φ̇², V(φ) = −g·Σmᵢcᵢ(φ),
//! M = J_crank + m₁|c₁′|² + m₂|c₂′|² + Σ_k I_k Ω_k² + m₃|c₃′|², and
//! M φ̈ + ½M′φ̇² + V′ = 0. The φ-derivatives up to the second are exact (to round-off): every
//! position is evaluated on second-order Taylor jets (value, d/dφ, d²/dφ²), so no finite
//! differences enter.

use std::f64::consts::PI;
use std::ops::{Add, Mul, Neg, Sub};

/// Crank radius r (axis to pin A), m.
pub const CRANK: f64 = 0.1;
/// Rod length L (A to B), m.
pub const ROD: f64 = 0.3;
/// The crank's axis point O (world; the axis is world x), m.
pub const PIVOT: [f64; 3] = [0.0, 0.06, 0.08];
/// Crank mass, kg.
pub const M_CRANK: f64 = 0.4;
/// Crank moment of inertia about its axis direction at its centre of mass, kg·m².
pub const J_CRANK: f64 = 4.0e-4;
/// Rod mass, kg.
pub const M_ROD: f64 = 1.0;
/// Rod centre of mass: distance along e_w from A, m.
pub const ROD_COM_AXIAL: f64 = 0.12;
/// Rod centre of mass: offset along e_3, m.
pub const ROD_COM_OFFSET: f64 = 0.01;
/// Rod principal moments of inertia at its centre of mass about (e_w, e_h, e_3), kg·m².
pub const I_ROD: [f64; 3] = [1.0e-3, 7.0e-3, 7.5e-3];
/// Slider mass, kg.
pub const M_SLIDER: f64 = 0.5;
/// Gravity, m/s² (world).
pub const GRAVITY: [f64; 3] = [0.0, 0.0, -9.81];
/// Initial crank speed about +x, rad/s.
pub const OMEGA0: f64 = 30.0;

/// The initial crank angle φ₀: pin A at the world origin (A = O + r(0, −0.6, −0.8)), rad.
pub fn phi0() -> f64 {
    (-0.8f64).atan2(-0.6)
}

/// A second-order Taylor jet in φ: value, first and second derivative.
#[derive(Debug, Clone, Copy)]
struct Jet {
    v: f64,
    d: f64,
    dd: f64,
}

impl Jet {
    fn c(v: f64) -> Self {
        Self { v, d: 0.0, dd: 0.0 }
    }
    fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        Self {
            v: s,
            d: self.d / (2.0 * s),
            dd: self.dd / (2.0 * s) - self.d * self.d / (4.0 * s * s * s),
        }
    }
    fn recip(self) -> Self {
        let r = 1.0 / self.v;
        Self {
            v: r,
            d: -self.d * r * r,
            dd: (2.0 * self.d * self.d * r - self.dd) * r * r,
        }
    }
}

impl Add for Jet {
    type Output = Jet;
    fn add(self, o: Jet) -> Jet {
        Jet {
            v: self.v + o.v,
            d: self.d + o.d,
            dd: self.dd + o.dd,
        }
    }
}

impl Sub for Jet {
    type Output = Jet;
    fn sub(self, o: Jet) -> Jet {
        self + (-o)
    }
}

impl Neg for Jet {
    type Output = Jet;
    fn neg(self) -> Jet {
        Jet {
            v: -self.v,
            d: -self.d,
            dd: -self.dd,
        }
    }
}

impl Mul for Jet {
    type Output = Jet;
    fn mul(self, o: Jet) -> Jet {
        Jet {
            v: self.v * o.v,
            d: self.d * o.v + self.v * o.d,
            dd: self.dd * o.v + 2.0 * self.d * o.d + self.v * o.dd,
        }
    }
}

type V3 = [Jet; 3];

fn cst(a: [f64; 3]) -> V3 {
    a.map(Jet::c)
}
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(a: V3, k: Jet) -> V3 {
    a.map(|x| x * k)
}
fn dot(a: V3, b: V3) -> Jet {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn unit(a: V3) -> V3 {
    scale(a, dot(a, a).sqrt().recip())
}

/// (a′·b, d/dφ(a′·b)) of two jet vectors.
fn rate(a: V3, b: V3) -> (f64, f64) {
    let mut r = (0.0, 0.0);
    for k in 0..3 {
        r.0 += a[k].d * b[k].v;
        r.1 += a[k].dd * b[k].v + a[k].d * b[k].d;
    }
    r
}

/// (|a′|², d/dφ|a′|² = 2a′·a″) of a jet vector.
fn speed_squared(a: V3) -> (f64, f64) {
    a.iter()
        .fold((0.0, 0.0), |r, x| (r.0 + x.d * x.d, r.1 + 2.0 * x.d * x.dd))
}

/// The loop's positions at φ (jets): centres of mass c₁ (crank), c₂ (rod), c₃ (slider, = B)
/// and the rod's axes (e_w, e_h, e_3).
struct Loop {
    c: [V3; 3],
    axes: [V3; 3],
}

impl Loop {
    fn at(phi: f64) -> Self {
        let (sp, cp) = phi.sin_cos();
        let radial = [
            Jet::c(0.0),
            Jet {
                v: cp,
                d: -sp,
                dd: -cp,
            },
            Jet {
                v: sp,
                d: cp,
                dd: -sp,
            },
        ];
        let o = cst(PIVOT);
        let a = add(o, scale(radial, Jet::c(CRANK)));
        let c1 = add(o, scale(radial, Jet::c(CRANK / 2.0)));
        let s = a[0] + (Jet::c(ROD * ROD) - a[1] * a[1] - a[2] * a[2]).sqrt();
        let b = [s, Jet::c(0.0), Jet::c(0.0)];
        let ew = scale(sub(b, a), Jet::c(1.0 / ROD));
        let eh = unit(cross(ew, cst([0.0, 0.0, 1.0])));
        let e3 = cross(ew, eh);
        let c2 = add(
            a,
            add(
                scale(ew, Jet::c(ROD_COM_AXIAL)),
                scale(e3, Jet::c(ROD_COM_OFFSET)),
            ),
        );
        Self {
            c: [c1, c2, b],
            axes: [ew, eh, e3],
        }
    }

    /// The rod's angular velocity per unit φ̇ about (e_w, e_h, e_3) and its φ-derivative.
    fn rod_rates(&self) -> [(f64, f64); 3] {
        let [ew, eh, e3] = self.axes;
        [rate(eh, e3), rate(e3, ew), rate(ew, eh)]
    }

    /// (M, dM/dφ, V, dV/dφ): generalized mass (kg·m²) and potential (J).
    fn energy_terms(&self) -> (f64, f64, f64, f64) {
        let masses = [M_CRANK, M_ROD, M_SLIDER];
        let (mut m, mut dm, mut v, mut dv) = (J_CRANK, 0.0, 0.0, 0.0);
        for (c, mass) in self.c.iter().zip(masses) {
            let (cc, dcc) = speed_squared(*c);
            m += mass * cc;
            dm += mass * dcc;
            for k in 0..3 {
                v -= mass * GRAVITY[k] * c[k].v;
                dv -= mass * GRAVITY[k] * c[k].d;
            }
        }
        for ((om, dom), i) in self.rod_rates().into_iter().zip(I_ROD) {
            m += i * om * om;
            dm += 2.0 * i * om * dom;
        }
        (m, dm, v, dv)
    }
}

/// Slider position s(φ) (world x of B), m.
pub fn slider_position(phi: f64) -> f64 {
    Loop::at(phi).c[2][0].v
}

/// φ̈ of Lagrange's equation M φ̈ + ½M′φ̇² + V′ = 0 at the state (φ, φ̇).
fn acceleration(y: [f64; 2]) -> f64 {
    let (m, dm, _, dv) = Loop::at(y[0]).energy_terms();
    -(dv + 0.5 * dm * y[1] * y[1]) / m
}

/// Total energy ½Mφ̇² + V at the state (φ, φ̇), J.
pub fn energy(y: [f64; 2]) -> f64 {
    let (m, _, v, _) = Loop::at(y[0]).energy_terms();
    0.5 * m * y[1] * y[1] + v
}

/// One classical Runge–Kutta step of size h.
fn rk4_step(y: [f64; 2], h: f64) -> [f64; 2] {
    let f = |y: [f64; 2]| [y[1], acceleration(y)];
    let at = |y: [f64; 2], k: [f64; 2], c: f64| [y[0] + c * k[0], y[1] + c * k[1]];
    let k1 = f(y);
    let k2 = f(at(y, k1, h / 2.0));
    let k3 = f(at(y, k2, h / 2.0));
    let k4 = f(at(y, k3, h));
    [
        y[0] + h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
        y[1] + h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
    ]
}

/// The states (φ, φ̇) at `times` (increasing, ≥ 0) from (φ₀, ω₀), classical RK4 with steps of at
/// most `h_max` s (each output interval cut into equal steps).
///
/// # Errors
/// Times not increasing or negative, or a non-positive step.
pub fn states(times: &[f64], h_max: f64) -> Result<Vec<[f64; 2]>, String> {
    if h_max.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(format!("step {h_max} s: must be positive"));
    }
    let mut y = [phi0(), OMEGA0];
    let mut t = 0.0;
    let mut out = Vec::with_capacity(times.len());
    for &t_out in times {
        if t_out.partial_cmp(&t) == Some(std::cmp::Ordering::Less) || !t_out.is_finite() {
            return Err(format!("output time {t_out} s: times must increase from 0"));
        }
        let n = ((t_out - t) / h_max).ceil().max(1.0);
        let h = (t_out - t) / n;
        for _ in 0..n as usize {
            y = rk4_step(y, h);
        }
        t = t_out;
        out.push(y);
    }
    Ok(out)
}

/// Slider positions s (m) at `times` (s), RK4 with steps of at most `h_max` s.
///
/// # Errors
/// As [`states`].
pub fn slider_positions(times: &[f64], h_max: f64) -> Result<Vec<f64>, String> {
    Ok(states(times, h_max)?
        .into_iter()
        .map(|y| slider_position(y[0]))
        .collect())
}

/// Crank turns made from φ₀ to the state `y_end` ((φ − φ₀)/2π): above 1 the run is a rotation,
/// not a swing.
pub fn turns(y_end: [f64; 2]) -> f64 {
    (y_end[0] - phi0()) / (2.0 * PI)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Energy conservation of the minimal model: ½Mφ̇² + V is a first integral of Lagrange's
    /// equation, so its drift measures the consistency of M′ and V′ with M and V (the jets)
    /// plus the RK4 error (O(h⁴)); over 1 s with h = 1e-4 s the drift is ~1e-13 J of ~1 J.
    #[test]
    fn energy_is_conserved() {
        let times: Vec<f64> = (1..=10).map(|k| 0.1 * k as f64).collect();
        let e0 = energy([phi0(), OMEGA0]);
        let ys = states(&times, 1e-4).unwrap();
        let drift = ys
            .iter()
            .map(|y| (energy(*y) - e0).abs())
            .fold(0.0, f64::max);
        assert!(drift < 1e-11 * e0.abs().max(1.0), "drift {drift:e} J");
        assert!(turns(ys[9]).abs() > 1.0, "the crank must turn over");
    }

    /// The rod's angular velocity from the jets against an independent one: the rotation matrix
    /// R = [e_w e_h e_3] differenced centrally in φ (step 1e-5, truncation ~1e-10),
    /// [Ω]× = Rᵀ dR/dφ; and slider speed ds/dφ against the central difference of s.
    #[test]
    fn rod_angular_velocity_matches_differenced_rotation() {
        let delta = 1e-5;
        for k in 0..12 {
            let phi = phi0() + k as f64 * PI / 6.0 + 0.1;
            let l = Loop::at(phi);
            let r = |p: f64| Loop::at(p).axes.map(|e| e.map(|x| x.v));
            let (rp, rm, r0) = (r(phi + delta), r(phi - delta), r(phi));
            let dr = |i: usize, j: usize| -> f64 {
                (0..3)
                    .map(|c| r0[i][c] * (rp[j][c] - rm[j][c]) / (2.0 * delta))
                    .sum()
            };
            // dr(i, j) = e_i·e_j′ (ė_j = ω × e_j): Ω_w = e_3·e_h′, Ω_h = e_w·e_3′, Ω_3 = e_h·e_w′.
            let fd = [dr(2, 1), dr(0, 2), dr(1, 0)];
            for (o, f) in l.rod_rates().iter().zip(fd) {
                assert!((o.0 - f).abs() < 1e-8, "Ω {} vs differenced {f}", o.0);
            }
            let ds = (slider_position(phi + delta) - slider_position(phi - delta)) / (2.0 * delta);
            assert!(
                (l.c[2][0].d - ds).abs() < 1e-9,
                "s′ {} vs {ds}",
                l.c[2][0].d
            );
        }
    }
}
