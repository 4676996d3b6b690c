//! `[[measure]]` of a spatial model file: the position, velocity or acceleration of a point of a
//! body, in the world frame or in the frame of another body, and the distance between two
//! points with its rate.
//!
//! A spatial run records every body's centre of mass r, orientation quaternion (R: body →
//! world), velocity v, angular velocity ω (body frame), acceleration a and angular acceleration
//! α (body frame) at every row ([`super::output`]). A point's kinematics are exact functions of
//! those columns at the same row, so the measures are computed from them after the run (the
//! planar engine evaluates its measures while recording; a spatial model has no inputs that
//! could read them during the run). With d = R·(s − c) the point s of the body frame relative to
//! the centre of mass c (both body frame), ω_w = R·ω and α_w = R·α:
//!
//! - p = r + d, v_p = v + ω_w × d, a_p = a + α_w × d + ω_w × (ω_w × d)
//!   (rigid-body kinematics, e.g. Shabana, *Dynamics of Multibody Systems*, 4th ed., §2.6);
//! - in the frame of body F (origin o, rotation R_F, ω_F and α_F in F's frame), with u = p − o:
//!   x = R_Fᵀ u, ẋ = R_Fᵀ u̇ − ω_F × x, ẍ = R_Fᵀ ü − ω_F × (R_Fᵀ u̇) − α_F × x − ω_F × ẋ
//!   (what a sensor fixed to F reads: the time derivatives of the coordinates in F's frame);
//! - distance ‖p_b − p_a‖ and its rate (p_b − p_a)·(v_b − v_a)/‖p_b − p_a‖ (0 where the points
//!   coincide, as in the planar distance measure).
//!
//! Columns: `<name>.x .y .z` (m), `<name>.vx .vy .vz` (m/s), `<name>.ax .ay .az` (m/s²),
//! `<name>.distance` (m) and `<name>.distance_rate` (m/s).

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

use super::desc::{PointMeasure, SpatialDesc, SpatialMeasure};
use crate::error::MbdError;
use crate::runtime::GROUND;
use crate::Results;

/// Which derivative of a point's coordinates.
#[derive(Clone, Copy, PartialEq)]
enum Order {
    Position,
    Velocity,
    Acceleration,
}

/// Check the measures against the bodies and the columns the model writes (`columns`): names
/// given, columns new (not the run's nor an earlier measure's), bodies and frames defined,
/// points finite, no `axis`.
pub(crate) fn check(d: &SpatialDesc, columns: &[String]) -> Result<(), MbdError> {
    let body = |name: &str| name == GROUND || d.bodies.iter().any(|b| b.name == name);
    let bodies = || {
        let mut v: Vec<&str> = d.bodies.iter().map(|b| b.name.as_str()).collect();
        v.push(GROUND);
        v.join(", ")
    };
    for (k, m) in d.measures.iter().enumerate() {
        let at = |field: &str, message: String| MbdError::Invalid {
            path: format!("measure[{k}].{field}"),
            message,
        };
        if m.name().trim().is_empty() {
            return Err(at("name", "give the measure a name".into()));
        }
        // one name may serve several kinds (`tip.x` and `tip.vx`), as in planar files
        let earlier: Vec<String> = d.measures[..k]
            .iter()
            .flat_map(SpatialMeasure::columns)
            .collect();
        if let Some(c) = (m.columns().iter()).find(|c| columns.contains(c) || earlier.contains(c)) {
            return Err(at(
                "name",
                format!(
                    "its column `{c}` is one the run or an earlier measure writes already: \
                     choose another name"
                ),
            ));
        }
        for (field, end) in m.ends() {
            if !body(&end.body) {
                return Err(at(
                    &format!("{field}.body"),
                    format!("no body `{}`; bodies: {}", end.body, bodies()),
                ));
            }
            if end.axis.is_some() {
                return Err(at(
                    &format!("{field}.axis"),
                    "a measured point has no axis: remove `axis`".into(),
                ));
            }
            if end.at.iter().any(|x| !x.is_finite()) {
                return Err(at(
                    &format!("{field}.at"),
                    "a coordinate is not finite".into(),
                ));
            }
        }
        if let SpatialMeasure::Position(p)
        | SpatialMeasure::Velocity(p)
        | SpatialMeasure::Acceleration(p) = m
        {
            if let Some(f) = p.frame.as_deref().filter(|f| !body(f)) {
                return Err(at(
                    "frame",
                    format!("no body `{f}` to take the frame of; bodies: {}", bodies()),
                ));
            }
        }
    }
    Ok(())
}

/// The kinematics of a body at one row: centre of mass, rotation, and their derivatives.
struct Body {
    r: Vector3<f64>,
    rot: Matrix3<f64>,
    v: Vector3<f64>,
    w: Vector3<f64>,
    a: Vector3<f64>,
    alpha: Vector3<f64>,
    com: Vector3<f64>,
}

impl Body {
    /// The ground: the world frame at rest.
    fn ground() -> Self {
        let z = Vector3::zeros();
        Body {
            r: z,
            rot: Matrix3::identity(),
            v: z,
            w: z,
            a: z,
            alpha: z,
            com: z,
        }
    }

    /// The body of columns `k` (of [`SUFFIXES`]) at row `row`.
    fn at_row(k: &[usize; 19], com: [f64; 3], row: &[f64]) -> Self {
        let v3 = |i: usize| Vector3::new(row[k[i]], row[k[i + 1]], row[k[i + 2]]);
        let q = nalgebra::Quaternion::new(row[k[3]], row[k[4]], row[k[5]], row[k[6]]);
        let rot = UnitQuaternion::from_quaternion(q)
            .to_rotation_matrix()
            .into_inner();
        Body {
            r: v3(0),
            rot,
            v: v3(7),
            w: rot * v3(10),
            a: v3(13),
            alpha: rot * v3(16),
            com: Vector3::from(com),
        }
    }

    /// Position, velocity and acceleration (world) of the point `s` of the body frame.
    fn point(&self, s: &[f64; 3]) -> [Vector3<f64>; 3] {
        let d = self.rot * (Vector3::from(*s) - self.com);
        let w = self.w;
        [
            self.r + d,
            self.v + w.cross(&d),
            self.a + self.alpha.cross(&d) + w.cross(&w.cross(&d)),
        ]
    }
}

/// The columns of a body a spatial run writes, in order ([`super::output`]).
const SUFFIXES: [&str; 19] = [
    "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz", "ax", "ay", "az",
    "alphax", "alphay", "alphaz",
];

/// A body's column indices in a result ([`SUFFIXES`]) and its centre of mass in its frame, m.
struct BodyColumns<'a> {
    name: &'a str,
    index: [usize; 19],
    com: [f64; 3],
}

/// The measures' columns for every row of `res` (name, values), in the order of
/// [`SpatialMeasure::columns`]; NaN throughout when `res` lacks a body's columns (a run that
/// failed before its first row).
pub fn evaluate(d: &SpatialDesc, res: &Results) -> Vec<(String, Vec<f64>)> {
    let names = d.measures.iter().flat_map(SpatialMeasure::columns);
    // per body: its column indices (looked up once) and centre of mass in its frame
    let index = |c: &str| res.columns.iter().position(|n| n == c);
    let bodies: Option<Vec<BodyColumns<'_>>> = (d.bodies.iter())
        .map(|b| {
            let k: Option<Vec<usize>> = SUFFIXES
                .iter()
                .map(|s| index(&format!("{}.{s}", b.name)))
                .collect();
            Some(BodyColumns {
                name: &b.name,
                index: <[usize; 19]>::try_from(k?).ok()?,
                com: b.centre_of_mass,
            })
        })
        .collect();
    let Some(bodies) = bodies else {
        return names.map(|c| (c, vec![f64::NAN; res.len()])).collect();
    };
    let mut out: Vec<(String, Vec<f64>)> =
        names.map(|c| (c, Vec::with_capacity(res.len()))).collect();
    for r in 0..res.len() {
        let row = res.row(r);
        let body = |name: &str| match bodies.iter().find(|b| b.name == name) {
            Some(b) => Body::at_row(&b.index, b.com, row),
            None => Body::ground(),
        };
        let mut k = 0;
        for m in &d.measures {
            let values = match m {
                SpatialMeasure::Position(p) => point_in(&body, p, Order::Position),
                SpatialMeasure::Velocity(p) => point_in(&body, p, Order::Velocity),
                SpatialMeasure::Acceleration(p) => point_in(&body, p, Order::Acceleration),
                SpatialMeasure::Distance(dm) => {
                    let [pa, va, _] = body(&dm.a.body).point(&dm.a.at);
                    let [pb, vb, _] = body(&dm.b.body).point(&dm.b.at);
                    let u = pb - pa;
                    let dist = u.norm();
                    // coincident points: rate 0, as the planar distance measure
                    let rate = if dist > 0.0 {
                        u.dot(&(vb - va)) / dist
                    } else {
                        0.0
                    };
                    vec![dist, rate]
                }
            };
            for v in values {
                out[k].1.push(v);
                k += 1;
            }
        }
    }
    out
}

/// The point's coordinates (or their derivative `order`) in the world or in `p.frame`.
fn point_in(body: &dyn Fn(&str) -> Body, p: &PointMeasure, order: Order) -> Vec<f64> {
    let [pos, vel, acc] = body(&p.at.body).point(&p.at.at);
    let world = match order {
        Order::Position => pos,
        Order::Velocity => vel,
        Order::Acceleration => acc,
    };
    let Some(f) = p.frame.as_deref().filter(|f| *f != GROUND) else {
        return world.iter().copied().collect();
    };
    let fb = body(f);
    // F's frame origin as a point of F: its body-frame coordinates are 0
    let [o, vo, ao] = fb.point(&[0.0; 3]);
    let rt = fb.rot.transpose();
    let (wf, af) = (rt * fb.w, rt * fb.alpha);
    let x = rt * (pos - o);
    let ud = rt * (vel - vo);
    let xd = ud - wf.cross(&x);
    let value = match order {
        Order::Position => x,
        Order::Velocity => xd,
        Order::Acceleration => rt * (acc - ao) - wf.cross(&ud) - af.cross(&x) - wf.cross(&xd),
    };
    value.iter().copied().collect()
}
