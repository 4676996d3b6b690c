//! Runtime primitives shared by the element runtime forms and the assembly: frames (where
//! coordinates of a body or beam node sit in q), body states, constraint primitives and force
//! elements, and the scatter helpers into Φ_q and Q. They depend on nothing else in the crate,
//! so elements and the assembly both build on them (description → elements → assembly →
//! integration).

use std::sync::Arc;

use clr_contact::BodyState;
use nalgebra::Vector2;

/// Name of the ground body (fixed at the origin, angle 0). It is always defined.
pub const GROUND: &str = "ground";

/// Index of the ground in resolved items (rigid bodies are numbered 0, 1, …).
pub(crate) const GROUND_ID: usize = usize::MAX;

/// A rigid body: mass, inertia about the centre of mass, initial pose and velocity.
///
/// The body reference point is its centre of mass; its coordinates are q = (x, y, θ) in m, m,
/// rad (θ counter-clockwise from the world x axis).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody {
    /// Mass, kg (> 0).
    pub mass: f64,
    /// Moment of inertia about the centre of mass, kg·m² (> 0).
    pub inertia: f64,
    /// Initial position of the centre of mass (x, y), m.
    pub position: [f64; 2],
    /// Initial angle, rad.
    pub angle: f64,
    /// Initial velocity of the centre of mass, m/s.
    pub velocity: [f64; 2],
    /// Initial angular velocity, rad/s.
    pub angular_velocity: f64,
}

impl RigidBody {
    /// A body of mass `mass` (kg) and centroidal inertia `inertia` (kg·m²) at rest at the origin.
    pub fn new(mass: f64, inertia: f64) -> Self {
        Self {
            mass,
            inertia,
            position: [0.0; 2],
            angle: 0.0,
            velocity: [0.0; 2],
            angular_velocity: 0.0,
        }
    }
    /// Initial pose: centre of mass at (x, y) m, angle θ rad.
    pub fn at(mut self, x: f64, y: f64, angle: f64) -> Self {
        self.position = [x, y];
        self.angle = angle;
        self
    }
    /// Initial velocity (v_x, v_y) m/s and angular velocity ω rad/s (made consistent with the
    /// constraints by [`Model::initial_state`]).
    pub fn moving(mut self, vx: f64, vy: f64, omega: f64) -> Self {
        self.velocity = [vx, vy];
        self.angular_velocity = omega;
        self
    }
}

/// An axial force of time (N), positive pushing apart (actuators).
pub(crate) type PushFn = Arc<dyn Fn(f64) -> f64 + Send + Sync>;

/// Applied force on a body: `f(t, state of the body) -> (F_x, F_y)` in N.
pub type ForceFn = Arc<dyn Fn(f64, &BodyState) -> Vector2<f64> + Send + Sync>;
/// Applied torque on a body: `f(t, state of the body) -> τ` in N·m.
pub type TorqueFn = Arc<dyn Fn(f64, &BodyState) -> f64 + Send + Sync>;
/// Torque between two bodies: `f(t, state of body i, state of body j) -> τ` in N·m, +τ on body
/// j and −τ on body i.
pub type PairTorqueFn = Arc<dyn Fn(f64, &BodyState, &BodyState) -> f64 + Send + Sync>;

#[derive(Debug, Clone, Copy)]
pub(crate) enum ConKind {
    /// r_i + A_i s_i − r_j − A_j s_j = 0 (2 rows).
    Coincide {
        i: usize,
        si: Vector2<f64>,
        j: usize,
        sj: Vector2<f64>,
    },
    /// θ_j − θ_i − c(t) = 0, c = offset or motion (1 row).
    Angle {
        i: usize,
        j: usize,
        offset: f64,
        motion: Option<usize>,
    },
    /// (A_i w)ᵀ (r_j + A_j s_j − r_i − A_i s_i) − c(t) = 0 (1 row).
    Project {
        i: usize,
        si: Vector2<f64>,
        j: usize,
        sj: Vector2<f64>,
        w: Vector2<f64>,
        motion: Option<usize>,
    },
    /// Node tie of floating body `f`: the node-frame coordinates (p, ψ) at columns
    /// `col..col + 3` equal R + A(ū₀ + Φ_N q_f) and θ + φ_θN·q_f (3 rows); `i` is the body's
    /// frame, `j` the node frame.
    FloatNode {
        f: usize,
        node: usize,
        col: usize,
        i: usize,
        j: usize,
    },
}

/// One primitive constraint (rows of Φ) belonging to a named joint or driver.
#[derive(Debug, Clone)]
pub(crate) struct Con {
    pub(crate) name: String,
    pub(crate) kind: ConKind,
    pub(crate) row: usize,
}

impl Con {
    pub(crate) fn coincide(
        name: &str,
        i: usize,
        si: Vector2<f64>,
        j: usize,
        sj: Vector2<f64>,
    ) -> Self {
        Con {
            name: name.into(),
            kind: ConKind::Coincide { i, si, j, sj },
            row: 0,
        }
    }
    pub(crate) fn angle(
        name: &str,
        i: usize,
        j: usize,
        offset: f64,
        motion: Option<usize>,
    ) -> Self {
        Con {
            name: name.into(),
            kind: ConKind::Angle {
                i,
                j,
                offset,
                motion,
            },
            row: 0,
        }
    }
    pub(crate) fn project(
        name: &str,
        i: usize,
        si: Vector2<f64>,
        j: usize,
        sj: Vector2<f64>,
        w: Vector2<f64>,
        motion: Option<usize>,
    ) -> Self {
        Con {
            name: name.into(),
            kind: ConKind::Project {
                i,
                si,
                j,
                sj,
                w,
                motion,
            },
            row: 0,
        }
    }
    pub(crate) fn rows(&self) -> usize {
        match self.kind {
            ConKind::Coincide { .. } => 2,
            ConKind::FloatNode { .. } => 3,
            _ => 1,
        }
    }
    pub(crate) fn bodies(&self) -> (usize, usize) {
        match self.kind {
            ConKind::Coincide { i, j, .. }
            | ConKind::Angle { i, j, .. }
            | ConKind::Project { i, j, .. }
            | ConKind::FloatNode { i, j, .. } => (i, j),
        }
    }
    pub(crate) fn label(&self, r: usize) -> String {
        let eq = match (self.kind, r) {
            (ConKind::Coincide { .. }, 0) => "x",
            (ConKind::Coincide { .. }, _) => "y",
            (ConKind::Angle { motion: None, .. }, _) => "relative angle",
            (ConKind::Angle { .. }, _) => "driven angle",
            (ConKind::Project { motion: None, .. }, _) => "normal offset",
            (ConKind::Project { .. }, _) => "driven displacement",
            (ConKind::FloatNode { .. }, 0) => "node x",
            (ConKind::FloatNode { .. }, 1) => "node y",
            (ConKind::FloatNode { .. }, _) => "node angle",
        };
        format!("{} ({eq})", self.name)
    }
}

pub(crate) enum ForceEl {
    Spring {
        name: String,
        i: usize,
        si: Vector2<f64>,
        j: usize,
        sj: Vector2<f64>,
        k: f64,
        c: f64,
        l0: f64,
        /// Axial pushing force of time (N; actuators), subtracted from the tension.
        push: Option<PushFn>,
    },
    RotSpring {
        name: String,
        i: usize,
        j: usize,
        k: f64,
        c: f64,
        angle0: f64,
    },
    Force {
        name: String,
        i: usize,
        si: Vector2<f64>,
        f: ForceFn,
        /// True when the load depends on time only (its Jacobian is then analytic).
        state_free: bool,
    },
    Torque {
        name: String,
        i: usize,
        f: TorqueFn,
        /// True when the load depends on time only (its Jacobian is then analytic).
        state_free: bool,
    },
    PairTorque {
        name: String,
        i: usize,
        j: usize,
        f: PairTorqueFn,
        /// True when the load depends on time only (its Jacobian is then analytic).
        state_free: bool,
    },
}

impl ForceEl {
    pub(crate) fn name(&self) -> &str {
        match self {
            ForceEl::Spring { name, .. }
            | ForceEl::RotSpring { name, .. }
            | ForceEl::Force { name, .. }
            | ForceEl::Torque { name, .. }
            | ForceEl::PairTorque { name, .. } => name,
        }
    }
}

impl ForceEl {
    /// Add this element's generalized forces at (t, q, q̇) into `qf`; returns (the power it
    /// dissipates, the power it puts into the system), W. Spring and damper terms go to the
    /// elastic energy and the dissipation; applied loads (forces, torques, an actuator's push
    /// F(t), bushings and custom loads, whose energy is not otherwise accounted) report their
    /// power F·v of the application point, τ·ω, τ·(ω_j − ω_i), which is exactly q̇ᵀ of the
    /// generalized force they add.
    pub(crate) fn eval(
        &self,
        frames: &[Frame],
        t: f64,
        q: &[f64],
        qd: &[f64],
        qf: &mut [f64],
    ) -> (f64, f64) {
        let (mut p_diss, mut p_in) = (0.0, 0.0);
        match self {
            ForceEl::Spring {
                i,
                si,
                j,
                sj,
                k,
                c,
                l0,
                push,
                ..
            } => {
                let bi = body_state(frames, *i, q, qd);
                let bj = body_state(frames, *j, q, qd);
                let (ai, aj) = (bi.rotate(*si), bj.rotate(*sj));
                let d = bj.position + aj - bi.position - ai;
                let l = d.norm();
                if l <= f64::MIN_POSITIVE {
                    return (0.0, 0.0);
                }
                let u = d / l;
                let vrel = bj.velocity + bj.angular_velocity * perp(aj)
                    - bi.velocity
                    - bi.angular_velocity * perp(ai);
                let ldot = u.dot(&vrel);
                let pushing = push.as_ref().map_or(0.0, |f| f(t));
                let tension = k * (l - l0) + c * ldot - pushing;
                p_diss += c * ldot * ldot;
                // the push lowers the tension: force +F·u on j and −F·u on i, power F·l̇
                p_in += pushing * ldot;
                add_force(frames, qf, *i, ai, tension * u);
                add_force(frames, qf, *j, aj, -tension * u);
            }
            ForceEl::RotSpring {
                i, j, k, c, angle0, ..
            } => {
                let bi = body_state(frames, *i, q, qd);
                let bj = body_state(frames, *j, q, qd);
                let wrel = bj.angular_velocity - bi.angular_velocity;
                let tau = -k * (bj.angle - bi.angle - angle0) - c * wrel;
                p_diss += c * wrel * wrel;
                add_torque(frames, qf, *j, tau);
                add_torque(frames, qf, *i, -tau);
            }
            ForceEl::Force { i, si, f, .. } => {
                let bi = body_state(frames, *i, q, qd);
                let force = f(t, &bi);
                let arm = bi.rotate(*si);
                // F·(v + ω × arm): the generalized force (F, arm × F) times the frame's rates
                p_in += force.dot(&bi.velocity) + cross(arm, force) * bi.angular_velocity;
                add_force(frames, qf, *i, arm, force);
            }
            ForceEl::Torque { i, f, .. } => {
                let bi = body_state(frames, *i, q, qd);
                let tau = f(t, &bi);
                p_in += tau * bi.angular_velocity;
                add_torque(frames, qf, *i, tau);
            }
            ForceEl::PairTorque { i, j, f, .. } => {
                let bi = body_state(frames, *i, q, qd);
                let bj = body_state(frames, *j, q, qd);
                let tau = f(t, &bi, &bj);
                p_in += tau * (bj.angular_velocity - bi.angular_velocity);
                add_torque(frames, qf, *j, tau);
                add_torque(frames, qf, *i, -tau);
            }
        }
        (p_diss, p_in)
    }
}

#[inline]
pub(crate) fn perp(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v.y, v.x)
}

#[inline]
pub(crate) fn rot(th: f64, s: Vector2<f64>) -> Vector2<f64> {
    let (sn, c) = th.sin_cos();
    Vector2::new(c * s.x - sn * s.y, sn * s.x + c * s.y)
}

#[inline]
pub(crate) fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// A frame that joints and forces attach to: a rigid body (columns 3k..3k+3 of q) or a beam
/// node (its free DOF columns; a constrained DOF stays 0), with the reference position `base`
/// added to the displacement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Frame {
    pub(crate) cols: [Option<usize>; 3],
    pub(crate) base: Vector2<f64>,
}

impl Frame {
    pub(crate) fn rigid(k: usize) -> Self {
        Frame {
            cols: [Some(3 * k), Some(3 * k + 1), Some(3 * k + 2)],
            base: Vector2::zeros(),
        }
    }
}

/// Position of frame k's reference point from the coordinates `q`, m (the ground at 0).
#[inline]
pub(crate) fn frame_position(frames: &[Frame], k: usize, q: &[f64]) -> Vector2<f64> {
    if k == GROUND_ID {
        return Vector2::zeros();
    }
    let f = &frames[k];
    let v = |d: usize| f.cols[d].map_or(0.0, |c| q[c]);
    f.base + Vector2::new(v(0), v(1))
}

/// Position, angle, velocity and angular velocity of frame k (the ground is fixed at 0). For a
/// beam node the angle is the node rotation (small-rotation frame).
#[inline]
pub(crate) fn body_state(frames: &[Frame], k: usize, q: &[f64], qd: &[f64]) -> BodyState {
    if k == GROUND_ID {
        return BodyState::default();
    }
    let f = &frames[k];
    let v = |x: &[f64], d: usize| f.cols[d].map_or(0.0, |c| x[c]);
    BodyState::new(
        f.base + Vector2::new(v(q, 0), v(q, 1)),
        v(q, 2),
        Vector2::new(v(qd, 0), v(qd, 1)),
        v(qd, 2),
    )
}

/// (d²r/dt², d²θ/dt²) of frame `k` from the accelerations `qdd` (zero for the ground and
/// constrained node directions).
pub(crate) fn frame_rates(frames: &[Frame], k: usize, qdd: &[f64]) -> (Vector2<f64>, f64) {
    if k == GROUND_ID {
        return (Vector2::zeros(), 0.0);
    }
    let v = |d: usize| frames[k].cols[d].map_or(0.0, |c| qdd[c]);
    (Vector2::new(v(0), v(1)), v(2))
}

#[inline]
pub(crate) fn put(frames: &[Frame], phiq: &mut [f64], n: usize, r: usize, k: usize, v: [f64; 3]) {
    if k != GROUND_ID {
        for (c, vd) in frames[k].cols.iter().zip(v) {
            if let Some(c) = c {
                phiq[r * n + c] += vd;
            }
        }
    }
}

#[inline]
pub(crate) fn add_force(
    frames: &[Frame],
    qf: &mut [f64],
    k: usize,
    arm: Vector2<f64>,
    f: Vector2<f64>,
) {
    add_gen(frames, qf, k, [f.x, f.y, cross(arm, f)]);
}

#[inline]
pub(crate) fn add_torque(frames: &[Frame], qf: &mut [f64], k: usize, tau: f64) {
    add_gen(frames, qf, k, [0.0, 0.0, tau]);
}

#[inline]
pub(crate) fn add_gen(frames: &[Frame], qf: &mut [f64], k: usize, g: [f64; 3]) {
    if k != GROUND_ID {
        for (c, gd) in frames[k].cols.iter().zip(g) {
            if let Some(c) = c {
                qf[*c] += gd;
            }
        }
    }
}
