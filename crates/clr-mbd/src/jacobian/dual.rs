//! First-order forward-mode numbers for the analytic contact Jacobians.
//!
//! A [`D`] carries a value and its gradient over N seeded directions (the coordinates and
//! velocities an element depends on); arithmetic applies the chain rule, so a force written once
//! in these numbers gives its exact partial derivatives (to rounding), with no step size. The
//! contact laws enter through their own closed-form derivatives (clr-contact's
//! `force_with_derivatives`), see `contact::law_forces`. Fixed-size arrays: nothing allocates.

use std::ops::{Add, Div, Mul, Neg, Sub};

use nalgebra::Vector2;

/// A value and its gradient over N directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct D<const N: usize> {
    pub(crate) v: f64,
    pub(crate) g: [f64; N],
}

impl<const N: usize> D<N> {
    /// A constant (zero gradient).
    pub(crate) fn cst(v: f64) -> Self {
        Self { v, g: [0.0; N] }
    }

    /// The independent variable of direction `k`.
    pub(crate) fn var(v: f64, k: usize) -> Self {
        let mut g = [0.0; N];
        g[k] = 1.0;
        Self { v, g }
    }

    /// f(self) from the value f and the derivative f′ at `self.v` (the chain rule).
    pub(crate) fn chain(self, f: f64, df: f64) -> Self {
        Self {
            v: f,
            g: self.g.map(|x| df * x),
        }
    }

    pub(crate) fn sin_cos(self) -> (Self, Self) {
        let (s, c) = self.v.sin_cos();
        (self.chain(s, c), self.chain(c, -s))
    }

    pub(crate) fn sqrt(self) -> Self {
        let r = self.v.sqrt();
        self.chain(r, 0.5 / r)
    }

    /// Σ a_k x_k with constant coefficients a and variable x.
    pub(crate) fn dot(a: &[f64], x: &[Self]) -> Self {
        a.iter()
            .zip(x)
            .fold(Self::cst(0.0), |s, (a, x)| s + *x * *a)
    }
}

impl<const N: usize> Add for D<N> {
    type Output = Self;
    fn add(mut self, o: Self) -> Self {
        self.v += o.v;
        self.g.iter_mut().zip(o.g).for_each(|(a, b)| *a += b);
        self
    }
}

impl<const N: usize> Sub for D<N> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self + -o
    }
}

impl<const N: usize> Neg for D<N> {
    type Output = Self;
    fn neg(self) -> Self {
        self * -1.0
    }
}

impl<const N: usize> Mul for D<N> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let mut g = [0.0; N];
        for ((r, a), b) in g.iter_mut().zip(self.g).zip(o.g) {
            *r = a * o.v + self.v * b;
        }
        Self { v: self.v * o.v, g }
    }
}

impl<const N: usize> Mul<f64> for D<N> {
    type Output = Self;
    fn mul(self, k: f64) -> Self {
        Self {
            v: self.v * k,
            g: self.g.map(|x| x * k),
        }
    }
}

impl<const N: usize> Add<f64> for D<N> {
    type Output = Self;
    fn add(mut self, k: f64) -> Self {
        self.v += k;
        self
    }
}

impl<const N: usize> Div for D<N> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let inv = o.chain(1.0 / o.v, -1.0 / (o.v * o.v));
        self * inv
    }
}

/// The dual numbers as the scalar of clr-contact's spatial journal geometry
/// ([`clr_contact::journal::Real`]): the journal's deepest points, wetted regions, Gauss
/// points and thrust rings evaluated in `D` give the exact partial derivatives of its forces
/// and moments (the spatial Newton blocks, `spatial::jacobian`).
impl<const N: usize> clr_contact::journal::Real for D<N> {
    fn from_f64(v: f64) -> Self {
        Self::cst(v)
    }
    fn value(&self) -> f64 {
        self.v
    }
    fn chain(self, f: f64, df: f64) -> Self {
        D::chain(self, f, df)
    }
    fn chain2(a: Self, b: Self, f: f64, dfa: f64, dfb: f64) -> Self {
        let mut g = [0.0; N];
        for ((r, x), y) in g.iter_mut().zip(a.g).zip(b.g) {
            *r = dfa * x + dfb * y;
        }
        Self { v: f, g }
    }
}

/// A planar vector of [`D`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct V<const N: usize> {
    pub(crate) x: D<N>,
    pub(crate) y: D<N>,
}

impl<const N: usize> V<N> {
    pub(crate) fn new(x: D<N>, y: D<N>) -> Self {
        Self { x, y }
    }

    pub(crate) fn cst(v: Vector2<f64>) -> Self {
        Self::new(D::cst(v.x), D::cst(v.y))
    }

    /// The value.
    pub(crate) fn val(&self) -> Vector2<f64> {
        Vector2::new(self.x.v, self.y.v)
    }

    pub(crate) fn dot(self, o: Self) -> D<N> {
        self.x * o.x + self.y * o.y
    }

    /// The planar cross product self × o (k̂ component).
    pub(crate) fn cross(self, o: Self) -> D<N> {
        self.x * o.y - self.y * o.x
    }

    /// k̂ × self = (−y, x).
    pub(crate) fn perp(self) -> Self {
        Self::new(-self.y, self.x)
    }

    pub(crate) fn norm(self) -> D<N> {
        self.dot(self).sqrt()
    }

    pub(crate) fn scale(self, k: D<N>) -> Self {
        Self::new(self.x * k, self.y * k)
    }

    /// A(θ) self: turned by the angle θ (rad).
    pub(crate) fn rot(self, th: D<N>) -> Self {
        let (s, c) = th.sin_cos();
        Self::new(c * self.x - s * self.y, s * self.x + c * self.y)
    }
}

impl<const N: usize> Add for V<N> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y)
    }
}

impl<const N: usize> Sub for V<N> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y)
    }
}

impl<const N: usize> Neg for V<N> {
    type Output = Self;
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y)
    }
}

impl<const N: usize> Mul<f64> for V<N> {
    type Output = Self;
    fn mul(self, k: f64) -> Self {
        Self::new(self.x * k, self.y * k)
    }
}

/// A planar frame (rigid body, beam node frame or floating-body frame) as duals: position,
/// angle, velocity and angular velocity.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DBody<const N: usize> {
    pub(crate) r: V<N>,
    pub(crate) th: D<N>,
    pub(crate) v: V<N>,
    pub(crate) w: D<N>,
}

impl<const N: usize> DBody<N> {
    /// The state `b` with its q seeded at directions `o..o + 3` and its q̇ at `o + 3..o + 6`
    /// (`None`: a constant frame, e.g. the ground).
    pub(crate) fn seed(b: &clr_contact::BodyState, o: Option<usize>) -> Self {
        let d = |v: f64, k: usize| match o {
            Some(o) => D::var(v, o + k),
            None => D::cst(v),
        };
        Self {
            r: V::new(d(b.position.x, 0), d(b.position.y, 1)),
            th: d(b.angle, 2),
            v: V::new(d(b.velocity.x, 3), d(b.velocity.y, 4)),
            w: d(b.angular_velocity, 5),
        }
    }

    /// World point of the body-fixed point with local coordinates `s`: r + A(θ) s.
    pub(crate) fn point(&self, s: Vector2<f64>) -> V<N> {
        self.r + V::cst(s).rot(self.th)
    }

    /// Velocity of the body's material point at the world point `p`: ṙ + ω k̂ × (p − r).
    pub(crate) fn point_velocity(&self, p: V<N>) -> V<N> {
        self.v + (p - self.r).perp().scale(self.w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The chain rule of the arithmetic against a hand-derived gradient:
    /// f(x, y) = sin(x)·y / √(x² + y²).
    #[test]
    fn gradient_of_a_composite_expression() {
        let (x, y) = (0.7, -1.3);
        let (dx, dy) = (D::<2>::var(x, 0), D::<2>::var(y, 1));
        let f = dx.sin_cos().0 * dy / (dx * dx + dy * dy).sqrt();
        let r = (x * x + y * y).sqrt();
        let fx = x.cos() * y / r - x.sin() * y * x / r.powi(3);
        let fy = x.sin() / r - x.sin() * y * y / r.powi(3);
        assert!((f.v - x.sin() * y / r).abs() < 1e-15);
        assert!((f.g[0] - fx).abs() < 1e-14 && (f.g[1] - fy).abs() < 1e-14);
    }

    /// The journal scalar's chain2 against the hand-derived gradient of
    /// f(a, b) = a²·b at a = x·y, b = x + y (∂f/∂a = 2ab, ∂f/∂b = a²).
    #[test]
    fn chain2_is_the_two_argument_chain_rule() {
        use clr_contact::journal::Real;
        let (x, y) = (D::<2>::var(0.4, 0), D::<2>::var(-1.1, 1));
        let (a, b) = (x * y, x + y);
        let f = <D<2> as Real>::chain2(a, b, a.v * a.v * b.v, 2.0 * a.v * b.v, a.v * a.v);
        // f = x²y²(x + y): ∂f/∂x = 2xy²(x + y) + x²y², ∂f/∂y = 2x²y(x + y) + x²y²
        let (xv, yv) = (0.4, -1.1);
        let fx = 2.0 * xv * yv * yv * (xv + yv) + xv * xv * yv * yv;
        let fy = 2.0 * xv * xv * yv * (xv + yv) + xv * xv * yv * yv;
        assert!((f.g[0] - fx).abs() < 1e-15 && (f.g[1] - fy).abs() < 1e-15);
    }

    /// The spatial journal film (clr_contact::journal_film) in these numbers: the gradient of the
    /// film force and journal moment of a tilted, squeezed, spinning journal over six state
    /// components against central differences (step 1e-7 relative), both closed forms, relative
    /// to the largest entry of the column. Long bearing 1e-6 (difference-quotient error). Short
    /// bearing 2e-3: its ψ rule is split at a state-dependent angle taken as a value, and with
    /// tilt the ψ-integrand has kinks where lines cavitate partly, so the difference quotient also
    /// differentiates the moving quadrature error (measured 4.5e-4 on the transverse moment, 1e-5
    /// level on the force): the duals give the exact derivative of the fixed-node quadrature.
    #[test]
    fn journal_film_gradient_matches_central_differences() {
        use clr_contact::journal::{JournalClearance, JournalState, V3};
        use clr_contact::journal_film::JournalFilm;
        use clr_contact::lubrication::{BearingModel, Transition};
        use nalgebra::Vector3;
        let joint = JournalClearance::cylindrical(10e-3, 10e-3, 9.95e-3, 12e-3).unwrap();
        let c = 50e-6;
        // x = (O_j.x, O_j.y, u_j.x, v_j.x, ω_j.y, ω_j.z)
        let x0 = [0.3 * c, -0.2 * c, 2e-3, 0.004, 0.3, 150.0];
        let state = |x: [D<6>; 6]| JournalState {
            bearing_centre: V3::zero(),
            bearing_axis: V3::constant(&Vector3::z()),
            bearing_velocity: V3::zero(),
            bearing_angular_velocity: V3::zero(),
            journal_centre: V3::new(x[0], x[1], D::cst(1e-4)),
            journal_axis: V3::new(x[2], D::cst(-1e-3), D::cst(1.0)),
            journal_velocity: V3::new(x[3], D::cst(-0.002), D::cst(0.01)),
            journal_angular_velocity: V3::new(D::cst(0.2), x[4], x[5]),
        };
        for model in [BearingModel::ShortBearing, BearingModel::LongBearing] {
            let film = JournalFilm::new(&joint, 0.04, model, Transition::new(0.5e-6, 0.0).unwrap())
                .unwrap();
            let tol = match model {
                BearingModel::ShortBearing => 2e-3,
                BearingModel::LongBearing => 1e-6,
            };
            let eval = |x: [f64; 6]| {
                let l = film.loads(&state(x.map(D::cst))).unwrap();
                let (f, m) = (l.force.value(), l.journal_moment.value());
                [f.x, f.y, f.z, m.x, m.y, m.z]
            };
            let seeded: [D<6>; 6] = std::array::from_fn(|k| D::var(x0[k], k));
            let l = film.loads(&state(seeded)).unwrap();
            let out = [
                l.force.0[0],
                l.force.0[1],
                l.force.0[2],
                l.journal_moment.0[0],
                l.journal_moment.0[1],
                l.journal_moment.0[2],
            ];
            for k in 0..6 {
                let h = 1e-7 * x0[k].abs();
                let (mut p, mut m) = (x0, x0);
                p[k] += h;
                m[k] -= h;
                let (fp, fm) = (eval(p), eval(m));
                let num: Vec<f64> = (0..6).map(|i| (fp[i] - fm[i]) / (2.0 * h)).collect();
                // forces and moments separately scaled
                for (range, what) in [(0..3, "force"), (3..6, "moment")] {
                    let scale = range
                        .clone()
                        .map(|i| num[i].abs().max(out[i].g[k].abs()))
                        .fold(0.0, f64::max);
                    for i in range {
                        assert!(
                            (out[i].g[k] - num[i]).abs() <= tol * scale,
                            "{model:?} {what} d{k} [{i}]: {} vs {}",
                            out[i].g[k],
                            num[i]
                        );
                    }
                }
            }
        }
    }
}
