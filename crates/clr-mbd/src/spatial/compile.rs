//! Compile a [`SpatialDesc`] into a [`SpatialModel`]: validate every item (errors name the item
//! and its field), resolve names, build the joints from constraint primitives and size the
//! workspace.

use std::collections::HashMap;

use clr_contact::{ContactMemory, NormalLaw};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

use super::constraint::{Prim, PrimKind};
use super::desc::{
    ClearanceKind, DriverKind, End, JointKind, JournalClearanceDesc, Orientation, SpatialBody,
    SpatialClearance, SpatialDesc, SpatialForce, SpatialShape, SphericalClearance, VectorFrame,
};
use super::force::Force3;
use super::frame::{exp_map, perpendicular, quaternion_of, rotation};
use super::journal::Journal;
use super::kin::GROUND;
use super::model::{Inertia3, Owner, SpatialModel, Workspace};
use super::sphere::Sphere;
use crate::desc::laws::ContactFriction;
use crate::error::MbdError;
use crate::runtime::GROUND as GROUND_NAME;

fn invalid(path: impl Into<String>, message: impl Into<String>) -> MbdError {
    MbdError::Invalid {
        path: path.into(),
        message: message.into(),
    }
}

/// Initial pose of a body: centre of mass and rotation, and the centre of mass in its frame.
#[derive(Clone, Copy)]
struct Pose {
    r: Vector3<f64>,
    a: Matrix3<f64>,
    com: Vector3<f64>,
}

/// A resolved end: body index, point relative to the centre of mass (body frame), axis.
struct REnd {
    k: usize,
    s: Vector3<f64>,
    axis: Option<Vector3<f64>>,
}

struct Ctx {
    names: HashMap<String, usize>,
    poses: Vec<Pose>,
    known: String,
}

impl Ctx {
    fn pose(&self, k: usize) -> Pose {
        if k == GROUND {
            Pose {
                r: Vector3::zeros(),
                a: Matrix3::identity(),
                com: Vector3::zeros(),
            }
        } else {
            self.poses[k]
        }
    }

    fn end(&self, path: &str, e: &End) -> Result<REnd, MbdError> {
        let k = if e.body == GROUND_NAME {
            GROUND
        } else {
            *self
                .names
                .get(&e.body)
                .ok_or_else(|| MbdError::UnknownBody {
                    item: format!("{path}.body"),
                    body: e.body.clone(),
                    known: self.known.clone(),
                })?
        };
        let at = finite3(&format!("{path}.at"), e.at)?;
        let axis = match e.axis {
            Some(a) => Some(unit(&format!("{path}.axis"), a)?),
            None => None,
        };
        Ok(REnd {
            k,
            s: at - self.pose(k).com,
            axis,
        })
    }

    /// The world direction of a body vector at the initial pose, expressed in body `k`.
    fn carry(&self, from: usize, v: &Vector3<f64>, to: usize) -> Vector3<f64> {
        self.pose(to).a.transpose() * (self.pose(from).a * v)
    }
}

fn finite3(path: &str, v: [f64; 3]) -> Result<Vector3<f64>, MbdError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(Vector3::from(v))
    } else {
        Err(invalid(path, format!("{v:?} must be finite")))
    }
}

fn unit(path: &str, v: [f64; 3]) -> Result<Vector3<f64>, MbdError> {
    let u = finite3(path, v)?;
    let n = u.norm();
    if n > 0.0 {
        Ok(u / n)
    } else {
        Err(invalid(path, "an axis must not be the zero vector"))
    }
}

/// Inertia tensor of a body from `inertia` or `principal_inertia` (+ `principal_axes`).
fn inertia_of(path: &str, b: &SpatialBody) -> Result<Matrix3<f64>, MbdError> {
    let j = match (b.inertia, b.principal_inertia) {
        (Some(_), Some(_)) => {
            return Err(invalid(
                format!("{path}.principal_inertia"),
                "give either `inertia` (the tensor) or `principal_inertia`, not both",
            ))
        }
        (None, None) => {
            return Err(invalid(
                format!("{path}.inertia"),
                "missing: give `inertia` (3 × 3 tensor at the centre of mass, body frame, \
                 kg·m²) or `principal_inertia` = [I1, I2, I3] (kg·m², with `principal_axes`)",
            ))
        }
        (Some(t), None) => {
            if b.principal_axes.is_some() {
                return Err(invalid(
                    format!("{path}.principal_axes"),
                    "`principal_axes` goes with `principal_inertia`, not with the full tensor",
                ));
            }
            let m = Matrix3::from_row_slice(&t.concat());
            if (m - m.transpose()).abs().max() > 1e-9 * m.abs().max() {
                return Err(invalid(
                    format!("{path}.inertia"),
                    "the inertia tensor must be symmetric (I_xy = I_yx, …)",
                ));
            }
            m
        }
        (None, Some(p)) => {
            let axes = match b.principal_axes {
                Some(ax) => {
                    let r = Matrix3::from_row_slice(&ax.concat());
                    if (r * r.transpose() - Matrix3::identity()).abs().max() > 1e-6
                        || r.determinant() < 0.0
                    {
                        return Err(invalid(
                            format!("{path}.principal_axes"),
                            "the rows must be orthonormal unit vectors forming a right-handed \
                             set (to 1e-6)",
                        ));
                    }
                    r
                }
                None => Matrix3::identity(),
            };
            // J = Σ I_k e_k e_kᵀ with e_k the rows of `axes`
            axes.transpose() * Matrix3::from_diagonal(&Vector3::from(p)) * axes
        }
    };
    let eig = j.symmetric_eigenvalues();
    let (lo, hi) = (eig.min(), eig.max());
    let sum = eig.sum();
    if !(lo > 0.0 && lo.is_finite() && hi.is_finite()) {
        return Err(invalid(
            format!("{path}.inertia"),
            format!(
                "principal moments {eig:?} kg·m² must be positive (the tensor positive definite)"
            ),
        ));
    }
    // triangle inequality of principal moments: each ≤ the sum of the other two
    if 2.0 * hi > sum * (1.0 + 1e-9) {
        return Err(invalid(
            format!("{path}.inertia"),
            format!(
                "principal moments {:?} kg·m² break the triangle inequality (each must be at \
                 most the sum of the others): no real body has them; check the units and the axes",
                eig.as_slice()
            ),
        ));
    }
    Ok(j)
}

/// Refuse an orientation angle beyond one turn: in a pose it is almost surely degrees given
/// for radians (30 → 0.5236 rad), which would otherwise give a valid but wrong orientation.
fn radians(path: &str, angle: f64) -> Result<(), MbdError> {
    if angle.abs() <= std::f64::consts::TAU {
        return Ok(());
    }
    Err(invalid(
        path,
        format!(
            "{angle} rad is more than one turn: angles are in rad (if {angle} is in degrees, \
             write {:.6})",
            angle.to_radians()
        ),
    ))
}

/// Largest ball or socket radius accepted, m: larger is almost surely millimetres given for
/// metres (a 10 mm socket written as 10), which would leave the ball never touching its socket.
const MAX_SPHERE_RADIUS: f64 = 1.0;

/// Rotation matrix of an orientation.
fn orientation(path: &str, o: &Orientation) -> Result<Matrix3<f64>, MbdError> {
    match o {
        Orientation::Quaternion { quaternion: q } => {
            let n = q.iter().map(|c| c * c).sum::<f64>().sqrt();
            if (n - 1.0).abs() > 1e-6 || n.is_nan() {
                return Err(invalid(
                    format!("{path}.quaternion"),
                    format!("norm {n} is not 1 (to 1e-6): give a unit quaternion [w, x, y, z]"),
                ));
            }
            Ok(rotation(q))
        }
        Orientation::Matrix { matrix } => {
            let a = Matrix3::from_row_slice(&matrix.concat());
            if (a * a.transpose() - Matrix3::identity()).abs().max() > 1e-6 || a.determinant() < 0.0
            {
                return Err(invalid(
                    format!("{path}.matrix"),
                    "must be a rotation: orthonormal rows to 1e-6, determinant +1",
                ));
            }
            Ok(rotation(&quaternion_of(&a)))
        }
        Orientation::AxisAngle { axis, angle } => {
            let u = unit(&format!("{path}.axis"), *axis)?;
            if !angle.is_finite() {
                return Err(invalid(format!("{path}.angle"), "must be finite (rad)"));
            }
            radians(&format!("{path}.angle"), *angle)?;
            Ok(exp_map(&(u * *angle)))
        }
        Orientation::Euler { euler, sequence } => {
            let seq: Vec<char> = sequence.to_ascii_lowercase().chars().collect();
            let ok = seq.len() == 3
                && seq.iter().all(|c| "xyz".contains(*c))
                && seq[0] != seq[1]
                && seq[1] != seq[2];
            if !ok {
                return Err(invalid(
                    format!("{path}.sequence"),
                    format!(
                        "`{sequence}`: three letters of x, y, z with no two neighbours equal \
                         (e.g. \"zyx\", \"zxz\"); the angles are about the moving axes"
                    ),
                ));
            }
            for (k, ang) in euler.iter().enumerate() {
                radians(&format!("{path}.euler[{k}]"), *ang)?;
            }
            let mut a = Matrix3::identity();
            for (c, ang) in seq.iter().zip(euler) {
                let ax = match c {
                    'x' => Vector3::x(),
                    'y' => Vector3::y(),
                    _ => Vector3::z(),
                };
                a *= exp_map(&(ax * *ang));
            }
            Ok(a)
        }
    }
}

/// The initial state of one body: (q = r, p; v = ṙ, ω_body), its pose and which of
/// (position, orientation, velocity, angular velocity) were given.
type BodyStart = ([f64; 7], [f64; 6], Pose, [bool; 4]);

/// The initial state of one body ([`BodyStart`]).
fn body_state(path: &str, b: &SpatialBody, com: Vector3<f64>) -> Result<BodyStart, MbdError> {
    let a = match &b.orientation {
        Some(o) => orientation(&format!("{path}.orientation"), o)?,
        None => Matrix3::identity(),
    };
    let origin = finite3(&format!("{path}.position"), b.position.unwrap_or_default())?;
    let r = origin + a * com;
    let frame = |v: Option<[f64; 3]>, f: Option<VectorFrame>, field: &str| match (v, f) {
        (None, Some(_)) => Err(invalid(
            format!("{path}.{field}_frame"),
            format!("given without `{field}`: remove it or give `{field}`"),
        )),
        (Some(_), None) => Err(invalid(
            format!("{path}.{field}_frame"),
            format!(
                "missing: name the frame `{field}` is given in, \"world\" or \"body\" (a \
                     guess would silently rotate it)"
            ),
        )),
        (None, None) => Ok(Vector3::zeros()),
        (Some(v), Some(f)) => {
            let v = finite3(&format!("{path}.{field}"), v)?;
            Ok(if f == VectorFrame::Body { a * v } else { v })
        }
    };
    let w_world = frame(
        b.angular_velocity,
        b.angular_velocity_frame,
        "angular_velocity",
    )?;
    let v_origin = frame(b.velocity, b.velocity_frame, "velocity")?;
    let v = v_origin + w_world.cross(&(a * com));
    let p = quaternion_of(&a);
    let wb = a.transpose() * w_world;
    let q = [r.x, r.y, r.z, p[0], p[1], p[2], p[3]];
    let vel = [v.x, v.y, v.z, wb.x, wb.y, wb.z];
    let given = [
        b.position.is_some(),
        b.orientation.is_some(),
        b.velocity.is_some(),
        b.angular_velocity.is_some(),
    ];
    Ok((q, vel, Pose { r, a, com }, given))
}

/// Compile a description (see [`SpatialDesc::compile`](super::SpatialDesc::compile)).
pub(crate) fn compile(d: &SpatialDesc) -> Result<SpatialModel, MbdError> {
    let mut names = HashMap::new();
    let mut bodies = Vec::new();
    let mut poses = Vec::new();
    let mut fixed = Vec::new();
    let (mut yq, mut yv) = (Vec::new(), Vec::new());
    for (k, b) in d.bodies.iter().enumerate() {
        let path = b.name.clone();
        if b.name == GROUND_NAME || names.insert(b.name.clone(), k).is_some() {
            return Err(MbdError::DuplicateName {
                name: b.name.clone(),
                first: "body",
                second: "body",
            });
        }
        if !(b.mass > 0.0 && b.mass.is_finite()) {
            return Err(MbdError::InvalidInertia {
                body: b.name.clone(),
                what: "mass (kg)",
                value: b.mass,
            });
        }
        let j = inertia_of(&path, b)?;
        let com = finite3(&format!("{path}.centre_of_mass"), b.centre_of_mass)?;
        let (q, v, pose, given) = body_state(&path, b, com)?;
        bodies.push(Inertia3 {
            mass: b.mass,
            j,
            j_inv: j.try_inverse().unwrap_or_else(Matrix3::zeros),
        });
        poses.push(pose);
        fixed.push(given);
        yq.extend_from_slice(&q);
        yv.extend_from_slice(&v);
    }
    let known = d
        .bodies
        .iter()
        .map(|b| b.name.as_str())
        .collect::<Vec<_>>()
        .join(", ");
    let cx = Ctx {
        names,
        poses,
        known,
    };
    let mut prims = Vec::new();
    let mut owners = Vec::new();
    let mut row = 0;
    let mut joint_frames = HashMap::new();
    for j in &d.joints {
        let frames = joint(&cx, j, owners.len(), &mut prims)?;
        joint_frames.insert(j.name.clone(), (j.kind, frames));
        push_owner(&mut owners, &mut prims, &mut row, &j.name, false)?;
    }
    let mut motions = Vec::new();
    for dr in &d.drivers {
        driver(
            &cx,
            dr,
            &joint_frames,
            owners.len(),
            &mut prims,
            &mut motions,
        )?;
        push_owner(&mut owners, &mut prims, &mut row, &dr.name, true)?;
    }
    let forces = d
        .forces
        .iter()
        .map(|f| Ok((f.name().to_string(), force(&cx, f, &joint_frames)?)))
        .collect::<Result<Vec<_>, MbdError>>()?;
    let mut spheres = Vec::new();
    let mut journals = Vec::new();
    let mut n_bristle = 0;
    // memory slots: one per ball, then four per journal
    let n_spheres = d
        .clearances
        .iter()
        .filter(|c| matches!(c, SpatialClearance::Spherical(_)))
        .count();
    for c in &d.clearances {
        match c {
            SpatialClearance::Spherical(s) => {
                let sp = sphere(&cx, s, spheres.len(), &mut n_bristle)?;
                spheres.push(sp);
            }
            SpatialClearance::Journal(j) => {
                let slot = n_spheres + clr_contact::journal::GROUPS * journals.len();
                journals.push(journal(&cx, j, slot)?);
            }
            SpatialClearance::Contact(_) => {}
        }
    }
    // shape contacts: their slots after the joints'
    let first_slot = spheres.len() + clr_contact::journal::GROUPS * journals.len();
    let shape_contacts = super::shape_compile::contacts(
        &|path: &str, e: &End| cx.end(path, e).map(|r| (r.k, r.s, r.axis.is_some())),
        &|path: &str, o: &Orientation| orientation(path, o),
        d,
        first_slot,
    )?;
    let min_v = spheres
        .iter()
        .map(|s: &Sphere| s.law.min_impact_velocity())
        .chain(journals.iter().flat_map(|j: &Journal| {
            [
                j.radial.min_impact_velocity(),
                j.thrust.min_impact_velocity(),
            ]
        }))
        .chain(shape_contacts.iter().map(|c| c.law.min_impact_velocity()))
        .fold(f64::INFINITY, f64::min);
    let n_slots = first_slot
        + shape_contacts
            .iter()
            .map(|c| c.settings.max_points)
            .sum::<usize>();
    let memory = ContactMemory::new(n_slots, if min_v.is_finite() { min_v } else { 1e-4 })
        .map_err(|e| invalid("clearance", e.to_string()))?;
    let journal_points = journals
        .iter()
        .enumerate()
        .flat_map(|(k, j): (usize, &Journal)| (0..j.n_groups()).map(move |g| (k, g)))
        .collect();
    let gravity = finite3("model.gravity", d.model.gravity)?;
    let nb = bodies.len();
    let m = row;
    let mut ws = Workspace {
        phi: vec![0.0; m],
        g: vec![0.0; m * 6 * nb],
        phit: vec![0.0; m],
        gamma: vec![0.0; m],
        qf: vec![0.0; 6 * nb],
        y: vec![0.0; 6 * nb * m],
        lambda: vec![0.0; m],
        reports: vec![Default::default(); spheres.len()],
        journal_reports: vec![Default::default(); journals.len()],
        gap_state: Vec::new(),
        gap_cache: vec![None; journals.len()],
        shape_reports: vec![Default::default(); shape_contacts.len()],
        zdot: vec![0.0; n_bristle],
        ..Default::default()
    };
    ws.w.resize(m);
    let mut y_given = yq;
    y_given.extend(yv);
    y_given.extend([0.0; 2]);
    y_given.extend(vec![0.0; n_bristle]);
    Ok(SpatialModel {
        names: d.bodies.iter().map(|b| b.name.clone()).collect(),
        bodies,
        fixed,
        y_given,
        prims,
        owners,
        motions,
        forces,
        spheres,
        journals,
        journal_points,
        shape_contacts,
        memory,
        gravity,
        alpha: d.solver.baumgarte_alpha,
        beta: d.solver.baumgarte_beta,
        events_on: d.solver.contact_events,
        notes: Vec::new(),
        input_warnings: input_warnings(d),
        measure_points: measure_points(d, &cx.names),
        m,
        n_bristle,
        norm_rate: super::model::NORM_RATE,
        ws,
    })
}

/// The description's value findings (crate::desc::checks), on every clearance joint.
/// The bodies' points of the `[[measure]]` items (the ground's left out): (field, body index,
/// point relative to the centre of mass, m).
fn measure_points(
    d: &SpatialDesc,
    names: &HashMap<String, usize>,
) -> Vec<(String, usize, Vector3<f64>)> {
    let mut out = Vec::new();
    for m in &d.measures {
        for (field, end) in m.ends() {
            if let Some(&k) = names.get(&end.body) {
                let com = Vector3::from(d.bodies[k].centre_of_mass);
                out.push((
                    format!("{}.{field}", m.name()),
                    k,
                    Vector3::from(end.at) - com,
                ));
            }
        }
    }
    out
}

fn input_warnings(d: &SpatialDesc) -> Vec<crate::initial_data::Warning> {
    let mut out = Vec::new();
    for c in &d.clearances {
        match c {
            SpatialClearance::Spherical(s) => {
                crate::desc::checks::moduli_warnings(&s.name, s, &mut out);
            }
            SpatialClearance::Journal(j) => {
                crate::desc::checks::moduli_warnings(&j.name, j, &mut out);
            }
            SpatialClearance::Contact(_) => {}
        }
    }
    out
}

fn push_owner(
    owners: &mut Vec<Owner>,
    prims: &mut [Prim],
    row: &mut usize,
    name: &str,
    driver: bool,
) -> Result<(), MbdError> {
    let o = owners.len();
    if owners.iter().any(|w| w.name == name) {
        return Err(MbdError::DuplicateName {
            name: name.into(),
            first: "joint or driver",
            second: if driver { "driver" } else { "joint" },
        });
    }
    let first = *row;
    let mut ends = (GROUND, GROUND);
    for p in prims.iter_mut().filter(|p| p.owner == o) {
        p.row = *row;
        *row += p.rows();
        ends = (p.i, p.j);
    }
    let (i, j) = ends;
    owners.push(Owner {
        name: name.into(),
        driver,
        i,
        j,
        rows: (first, *row),
    });
    Ok(())
}

/// Joint frames kept for drivers and rotational springs: (x_i, y_i, z_i on i; x_j on j;
/// the points s_i, s_j), body frames.
#[derive(Clone, Copy)]
pub(crate) struct JointFrames {
    i: usize,
    j: usize,
    xi: Vector3<f64>,
    yi: Vector3<f64>,
    zi: Vector3<f64>,
    xj: Vector3<f64>,
    si: Vector3<f64>,
    sj: Vector3<f64>,
}

fn joint(
    cx: &Ctx,
    jd: &super::desc::SpatialJoint,
    owner: usize,
    prims: &mut Vec<Prim>,
) -> Result<JointFrames, MbdError> {
    let name = &jd.name;
    let a = cx.end(&format!("{name}.a"), &jd.a)?;
    let b = cx.end(&format!("{name}.b"), &jd.b)?;
    if a.k == b.k {
        return Err(MbdError::SameBody {
            item: name.clone(),
            body: jd.a.body.clone(),
        });
    }
    let needs_a = !matches!(jd.kind, JointKind::Spherical | JointKind::Fixed);
    let needs_b = jd.kind == JointKind::Universal;
    let allows_b = matches!(jd.kind, JointKind::Universal | JointKind::Revolute);
    match (needs_a, a.axis.is_some()) {
        (true, false) => {
            return Err(invalid(
                format!("{name}.a.axis"),
                format!("missing: a {:?} joint needs the axis on its a end", jd.kind)
                    .to_lowercase(),
            ))
        }
        (false, true) => {
            return Err(invalid(
                format!("{name}.a.axis"),
                "not used by this joint kind: remove it",
            ))
        }
        _ => {}
    }
    if needs_b && b.axis.is_none() {
        return Err(invalid(
            format!("{name}.b.axis"),
            "missing: a universal joint needs its second axis on the b end (perpendicular to a's)",
        ));
    }
    if !allows_b && b.axis.is_some() {
        return Err(invalid(
            format!("{name}.b.axis"),
            "not used by this joint kind: remove it (the axis is a's, carried to b at the \
             initial poses)",
        ));
    }
    let zi = a.axis.unwrap_or_else(Vector3::z);
    let xi = perpendicular(&zi);
    let yi = zi.cross(&xi);
    let zj = match (jd.kind, b.axis) {
        (JointKind::Revolute, Some(z)) => z,
        _ => cx.carry(a.k, &zi, b.k),
    };
    let xj = cx.carry(a.k, &xi, b.k);
    let yj = cx.carry(a.k, &yi, b.k);
    let mut push = |kind: PrimKind| {
        prims.push(Prim {
            owner,
            i: a.k,
            j: b.k,
            kind,
            row: 0,
        })
    };
    let coincide = PrimKind::Coincide { si: a.s, sj: b.s };
    let dot1 = |ai: Vector3<f64>, aj: Vector3<f64>| PrimKind::Dot1 { ai, aj };
    let dot2 = |ai: Vector3<f64>| PrimKind::Dot2 {
        ai,
        si: a.s,
        sj: b.s,
        offset: 0.0,
        motion: None,
    };
    match jd.kind {
        JointKind::Spherical => push(coincide),
        JointKind::Revolute => {
            push(coincide);
            push(dot1(xi, zj));
            push(dot1(yi, zj));
        }
        JointKind::Universal => {
            let zb = b.axis.unwrap_or_else(Vector3::z);
            let ca = cx.pose(a.k).a * zi;
            let cb = cx.pose(b.k).a * zb;
            if ca.dot(&cb).abs() > 1e-6 {
                return Err(invalid(
                    format!("{name}.b.axis"),
                    format!(
                        "the two axes of a universal joint must be perpendicular at the initial \
                         poses; their cosine is {:.3e}",
                        ca.dot(&cb)
                    ),
                ));
            }
            push(coincide);
            push(dot1(zi, zb));
        }
        JointKind::Cylindrical | JointKind::Prismatic => {
            push(dot1(xi, zj));
            push(dot1(yi, zj));
            push(dot2(xi));
            push(dot2(yi));
            if jd.kind == JointKind::Prismatic {
                push(dot1(xi, yj));
            }
        }
        JointKind::Planar => {
            push(dot1(xi, zj));
            push(dot1(yi, zj));
            push(dot2(zi));
        }
        JointKind::Fixed => {
            push(coincide);
            push(dot1(xi, yj));
            push(dot1(yi, zj));
            push(dot1(zi, xj));
        }
    }
    Ok(JointFrames {
        i: a.k,
        j: b.k,
        xi,
        yi,
        zi,
        xj,
        si: a.s,
        sj: b.s,
    })
}

fn driver(
    cx: &Ctx,
    dr: &super::desc::SpatialDriver,
    joints: &HashMap<String, (JointKind, JointFrames)>,
    owner: usize,
    prims: &mut Vec<Prim>,
    motions: &mut Vec<crate::TimeFn>,
) -> Result<(), MbdError> {
    let _ = cx;
    let name = &dr.name;
    let (kind, f) = *joints.get(&dr.joint).ok_or_else(|| {
        invalid(
            format!("{name}.joint"),
            format!(
                "unknown joint `{}`; {}",
                dr.joint,
                crate::field::suggestion(&dr.joint, joints.keys().map(String::as_str))
            ),
        )
    })?;
    dr.motion
        .validate(&format!("{name}.motion"))
        .map_err(|e| invalid(e.path, e.message))?;
    planar_inputs_only(&dr.motion, &format!("{name}.motion"))?;
    let ok = match dr.kind {
        DriverKind::RevoluteAngle => matches!(kind, JointKind::Revolute | JointKind::Cylindrical),
        DriverKind::PrismaticDisplacement => {
            matches!(kind, JointKind::Prismatic | JointKind::Cylindrical)
        }
    };
    if !ok {
        return Err(invalid(
            format!("{name}.joint"),
            format!(
                "`{}` is a {kind:?} joint; a {:?} driver needs a {} joint",
                dr.joint,
                dr.kind,
                if dr.kind == DriverKind::RevoluteAngle {
                    "revolute or cylindrical"
                } else {
                    "prismatic or cylindrical"
                }
            )
            .to_lowercase(),
        ));
    }
    motions.push(dr.motion.clone());
    let motion = motions.len() - 1;
    let kind = match dr.kind {
        DriverKind::RevoluteAngle => PrimKind::Angle {
            xi: f.xi,
            yi: f.yi,
            xj: f.xj,
            motion,
        },
        DriverKind::PrismaticDisplacement => {
            // zero at the initial poses: d₀ = z_i·(r_j + A_j s_j − r_i − A_i s_i) there
            let (pi, pj) = (cx.pose(f.i), cx.pose(f.j));
            let d = pj.r + pj.a * f.sj - pi.r - pi.a * f.si;
            PrimKind::Dot2 {
                ai: f.zi,
                si: f.si,
                sj: f.sj,
                offset: (pi.a * f.zi).dot(&d),
                motion: Some(motion),
            }
        }
    };
    prims.push(Prim {
        owner,
        i: f.i,
        j: f.j,
        kind,
        row: 0,
    });
    Ok(())
}

fn non_negative(path: &str, v: f64) -> Result<f64, MbdError> {
    if v >= 0.0 && v.is_finite() {
        Ok(v)
    } else {
        Err(invalid(
            path,
            format!("{v} must be finite and not negative"),
        ))
    }
}

fn force(
    cx: &Ctx,
    f: &SpatialForce,
    joints: &HashMap<String, (JointKind, JointFrames)>,
) -> Result<Force3, MbdError> {
    let name = f.name();
    let no_axis = |e: &End, field: &str| match e.axis {
        Some(_) => Err(invalid(
            format!("{name}.{field}.axis"),
            "not used by a force element: remove it",
        )),
        None => Ok(()),
    };
    let two_ends = |a: &End, b: &End| -> Result<(REnd, REnd), MbdError> {
        no_axis(a, "a")?;
        no_axis(b, "b")?;
        Ok((
            cx.end(&format!("{name}.a"), a)?,
            cx.end(&format!("{name}.b"), b)?,
        ))
    };
    let fns = |fs: [&crate::TimeFn; 3], names: [&str; 3]| -> Result<[crate::TimeFn; 3], MbdError> {
        for (g, n) in fs.iter().zip(names) {
            g.validate(&format!("{name}.{n}"))
                .map_err(|e| invalid(e.path, e.message))?;
            planar_inputs_only(g, &format!("{name}.{n}"))?;
        }
        Ok([fs[0].clone(), fs[1].clone(), fs[2].clone()])
    };
    Ok(match f {
        SpatialForce::SpringDamper {
            a,
            b,
            stiffness,
            damping,
            free_length,
            ..
        } => {
            let (ea, eb) = two_ends(a, b)?;
            Force3::Line {
                i: ea.k,
                si: ea.s,
                j: eb.k,
                sj: eb.s,
                k: non_negative(&format!("{name}.stiffness"), *stiffness)?,
                c: non_negative(&format!("{name}.damping"), *damping)?,
                l0: non_negative(&format!("{name}.free_length"), *free_length)?,
                push: None,
            }
        }
        SpatialForce::Actuator { a, b, force, .. } => {
            no_axis(a, "a")?;
            no_axis(b, "b")?;
            force
                .validate(&format!("{name}.force"))
                .map_err(|e| invalid(e.path, e.message))?;
            planar_inputs_only(force, &format!("{name}.force"))?;
            let (ea, eb) = (
                cx.end(&format!("{name}.a"), a)?,
                cx.end(&format!("{name}.b"), b)?,
            );
            Force3::Line {
                i: ea.k,
                si: ea.s,
                j: eb.k,
                sj: eb.s,
                k: 0.0,
                c: 0.0,
                l0: 0.0,
                push: Some(force.clone()),
            }
        }
        SpatialForce::RotationalSpringDamper {
            joint,
            stiffness,
            damping,
            free_angle,
            ..
        } => {
            let (kind, fr) = joints.get(joint).copied().ok_or_else(|| {
                invalid(format!("{name}.joint"), format!("unknown joint `{joint}`"))
            })?;
            if !matches!(kind, JointKind::Revolute | JointKind::Cylindrical) {
                return Err(invalid(
                    format!("{name}.joint"),
                    "a rotational spring–damper acts about the axis of a revolute or \
                     cylindrical joint",
                ));
            }
            Force3::Rotational {
                i: fr.i,
                j: fr.j,
                xi: fr.xi,
                yi: fr.yi,
                xj: fr.xj,
                k: non_negative(&format!("{name}.stiffness"), *stiffness)?,
                c: non_negative(&format!("{name}.damping"), *damping)?,
                theta0: *free_angle,
            }
        }
        SpatialForce::Bushing {
            a,
            b,
            stiffness,
            damping,
            rotational_stiffness,
            rotational_damping,
            ..
        } => {
            let (ea, eb) = two_ends(a, b)?;
            let nn = |field: &str, v: [f64; 3]| -> Result<Vector3<f64>, MbdError> {
                for c in v {
                    non_negative(&format!("{name}.{field}"), c)?;
                }
                Ok(Vector3::from(v))
            };
            Force3::Bushing {
                i: ea.k,
                si: ea.s,
                j: eb.k,
                sj: eb.s,
                rel0: cx.pose(ea.k).a.transpose() * cx.pose(eb.k).a,
                kt: nn("stiffness", *stiffness)?,
                ct: nn("damping", *damping)?,
                kr: nn("rotational_stiffness", *rotational_stiffness)?,
                cr: nn("rotational_damping", *rotational_damping)?,
            }
        }
        SpatialForce::Force {
            at,
            frame,
            fx,
            fy,
            fz,
            ..
        } => {
            no_axis(at, "at")?;
            let e = cx.end(&format!("{name}.at"), at)?;
            if e.k == GROUND {
                return Err(invalid(
                    format!("{name}.at.body"),
                    "a load on the ground does nothing: name a body",
                ));
            }
            Force3::Point {
                i: e.k,
                si: e.s,
                body_frame: *frame == VectorFrame::Body,
                f: fns([fx, fy, fz], ["fx", "fy", "fz"])?,
            }
        }
        SpatialForce::Torque {
            body,
            frame,
            mx,
            my,
            mz,
            ..
        } => {
            let e = cx.end(
                name,
                &End {
                    body: body.clone(),
                    at: [0.0; 3],
                    axis: None,
                },
            )?;
            if e.k == GROUND {
                return Err(invalid(
                    format!("{name}.body"),
                    "a load on the ground does nothing: name a body",
                ));
            }
            Force3::Torque {
                i: e.k,
                body_frame: *frame == VectorFrame::Body,
                m: fns([mx, my, mz], ["mx", "my", "mz"])?,
            }
        }
    })
}

fn sphere(
    cx: &Ctx,
    s: &SphericalClearance,
    k: usize,
    n_bristle: &mut usize,
) -> Result<Sphere, MbdError> {
    let name = &s.name;
    let a = cx.end(&format!("{name}.socket"), &s.socket)?;
    let b = cx.end(&format!("{name}.ball"), &s.ball)?;
    for (e, f) in [(&a, "socket"), (&b, "ball")] {
        if e.axis.is_some() {
            return Err(invalid(
                format!("{name}.{f}.axis"),
                "a ball or socket has no axis: remove it",
            ));
        }
    }
    if a.k == b.k {
        return Err(MbdError::SameBody {
            item: name.clone(),
            body: s.ball.body.clone(),
        });
    }
    let (rs, rb) = (s.socket_radius, s.ball_radius);
    if rs > MAX_SPHERE_RADIUS {
        return Err(invalid(
            format!("{name}.socket_radius"),
            format!(
                "{rs} m is larger than {MAX_SPHERE_RADIUS} m: lengths are in m (a radius in mm, \
                 {rs} mm, is {:e} m)",
                rs * 1e-3
            ),
        ));
    }
    if !(rs > 0.0 && rs.is_finite()) {
        return Err(invalid(
            format!("{name}.socket_radius"),
            format!("{rs} m must be positive"),
        ));
    }
    if !(rb > 0.0 && rb < rs) {
        return Err(invalid(
            format!("{name}.ball_radius"),
            format!(
                "{rb} m must be positive and smaller than socket_radius = {rs} m (equal radii \
                 are the ideal spherical joint: use a [[joint]] of type \"spherical\")"
            ),
        ));
    }
    let path = format!("{name}.normal");
    let law_name = s.normal.law.trim().to_ascii_lowercase().replace('_', "-");
    let normal = match law_name.as_str() {
        "hertz" | "power" | "linear" => s.normal.build(&path, None),
        // Hertz for a sphere in a concave sphere: the same K = (4/3)E*√(R_sR_b/(R_s − R_b))
        // as clr-contact's internal-cylinder law, which is that sphere formula
        "hertz-internal-sphere" => {
            let mut d = s.normal.clone();
            d.law = "hertz-internal-cylinder".into();
            d.build(&path, Some((rs, rb)))
        }
        other => {
            return Err(invalid(
                format!("{path}.law"),
                format!(
                    "`{other}` is not available for a ball in a socket: the line-contact laws \
                     (liu, bai-zhao, johnson, pereira, presets with length, flores-line, area) \
                     are for cylinders; use hertz-internal-sphere (from the materials), hertz, \
                     power or linear"
                ),
            ))
        }
    }
    .map_err(|e| invalid(e.path, e.message))?;
    let friction = match &s.friction {
        None => None,
        Some(f) => match f
            .build_contact(&format!("{name}.friction"))
            .map_err(|e| invalid(e.path, e.message))?
        {
            ContactFriction::Static(l) if l.mu_max() == 0.0 => None,
            other => Some(other),
        },
    };
    let bristle = match friction {
        Some(ContactFriction::LuGre(_)) => {
            *n_bristle += 3;
            Some(*n_bristle - 3)
        }
        _ => None,
    };
    Ok(Sphere {
        name: name.clone(),
        i: a.k,
        si: a.s,
        j: b.k,
        sj: b.s,
        r_socket: rs,
        r_ball: rb,
        law: normal,
        friction,
        memory: k,
        bristle,
    })
}

/// Compile a revolute or cylindrical clearance joint; `slot` is its first contact-memory slot.
fn journal(cx: &Ctx, d: &JournalClearanceDesc, slot: usize) -> Result<Journal, MbdError> {
    let name = &d.name;
    let a = cx.end(&format!("{name}.bearing"), &d.bearing)?;
    let b = cx.end(&format!("{name}.journal"), &d.journal)?;
    if a.k == b.k {
        return Err(MbdError::SameBody {
            item: name.clone(),
            body: d.journal.body.clone(),
        });
    }
    let axis = |e: &REnd, f: &str| {
        e.axis.ok_or_else(|| {
            invalid(
                format!("{name}.{f}.axis"),
                "give the axis of the bore or journal in its body frame, e.g. axis = [0, 0, 1]",
            )
        })
    };
    let (ui, uj) = (axis(&a, "bearing")?, axis(&b, "journal")?);
    let joint = journal_geometry(d)?;
    let (radial, thrust, friction) = journal_laws(d, &joint)?;
    let laws = clr_contact::JournalLaws::new(
        radial,
        thrust,
        match friction {
            Some(f) => clr_contact::journal::JournalFriction::Law(f),
            None => clr_contact::journal::JournalFriction::None,
        },
    )
    .map_err(|e| invalid(format!("{name}.friction"), e.to_string()))?;
    let film = journal_film(d, &joint)?;
    Ok(Journal {
        name: name.clone(),
        i: a.k,
        si: a.s,
        ui,
        j: b.k,
        sj: b.s,
        uj,
        joint,
        laws,
        radial,
        thrust,
        friction,
        film,
        memory: slot,
    })
}

/// The oil film of a lubricated journal joint, validated at `lubrication.<field>`.
fn journal_film(
    d: &JournalClearanceDesc,
    joint: &clr_contact::JournalClearance,
) -> Result<Option<clr_contact::journal_film::JournalFilm>, MbdError> {
    use crate::element::revolute_clearance::LubricationModel;
    use clr_contact::lubrication::{BearingModel, Transition};
    let Some(l) = &d.lubrication else {
        return Ok(None);
    };
    let path = format!("{}.lubrication", d.name);
    if l.length.is_some() {
        return Err(invalid(
            format!("{path}.length"),
            "the film length of a spatial journal is the overlap of journal and bore (from              bearing_length, journal_length and the pose): remove `length`",
        ));
    }
    let model = match l.model {
        LubricationModel::ShortBearing => BearingModel::ShortBearing,
        LubricationModel::LongBearing => BearingModel::LongBearing,
    };
    let at = |e: clr_contact::ContactError| invalid(path.clone(), e.to_string());
    let transition = Transition::new(l.film_threshold, l.dry_threshold).map_err(at)?;
    clr_contact::journal_film::JournalFilm::new(joint, l.viscosity, model, transition)
        .map(Some)
        .map_err(at)
}

/// The validated geometry of a journal joint (errors name the field).
fn journal_geometry(d: &JournalClearanceDesc) -> Result<clr_contact::JournalClearance, MbdError> {
    let name = &d.name;
    for (f, v) in [
        ("bearing_radius", d.bearing_radius),
        ("bearing_length", d.bearing_length),
        ("journal_radius", d.journal_radius),
        ("journal_length", d.journal_length),
    ] {
        if v > MAX_SPHERE_RADIUS {
            return Err(invalid(
                format!("{name}.{f}"),
                format!(
                    "{v} m is larger than {MAX_SPHERE_RADIUS} m: lengths are in m (a length in \
                     mm, {v} mm, is {:e} m)",
                    v * 1e-3
                ),
            ));
        }
        if !(v > 0.0 && v.is_finite()) {
            return Err(invalid(
                format!("{name}.{f}"),
                format!("{v} m must be positive"),
            ));
        }
    }
    let (rb, rj) = (d.bearing_radius, d.journal_radius);
    if rj >= rb {
        return Err(invalid(
            format!("{name}.journal_radius"),
            format!(
                "{rj} m must be smaller than bearing_radius = {rb} m (equal radii are the ideal \
                 joint: use a [[joint]] of the same type)"
            ),
        ));
    }
    let geometry = match d.kind {
        ClearanceKind::Revolute => {
            let Some(ca) = d.axial_clearance else {
                return Err(invalid(
                    format!("{name}.axial_clearance"),
                    "a revolute clearance joint needs its total axial end play in m (the \
                     cylindrical kind has no thrust faces)",
                ));
            };
            if !(ca > 0.0 && ca <= MAX_SPHERE_RADIUS) {
                return Err(invalid(
                    format!("{name}.axial_clearance"),
                    format!("{ca} m must be positive and at most {MAX_SPHERE_RADIUS} m (in m)"),
                ));
            }
            if let Some(rt) = d.thrust_radius {
                if !(rt > 0.0 && rt <= MAX_SPHERE_RADIUS) {
                    return Err(invalid(
                        format!("{name}.thrust_radius"),
                        format!("{rt} m must be positive and at most {MAX_SPHERE_RADIUS} m"),
                    ));
                }
            }
            clr_contact::JournalClearance::revolute(
                rb,
                d.bearing_length,
                rj,
                d.journal_length,
                ca,
                d.thrust_radius,
            )
        }
        _ => {
            for (f, given) in [
                ("axial_clearance", d.axial_clearance.is_some()),
                ("thrust_radius", d.thrust_radius.is_some()),
                ("thrust_normal", d.thrust_normal.is_some()),
            ] {
                if given {
                    return Err(invalid(
                        format!("{name}.{f}"),
                        "a cylindrical clearance joint has no thrust faces: remove it, or use \
                         type = \"revolute\"",
                    ));
                }
            }
            clr_contact::JournalClearance::cylindrical(rb, d.bearing_length, rj, d.journal_length)
        }
    }
    .map_err(|e| invalid(name.clone(), e.to_string()))?;
    match d.quadrature_order {
        Some(n) => geometry
            .with_quadrature_order(n)
            .map_err(|e| invalid(format!("{name}.quadrature_order"), e.to_string())),
        None => Ok(geometry),
    }
}

/// The radial law (line laws with their length L_c = min(L_b, L_j)), the thrust law (default:
/// the radial law object) and the stateless friction law of a journal joint.
fn journal_laws(
    d: &JournalClearanceDesc,
    joint: &clr_contact::JournalClearance,
) -> Result<(NormalLaw, NormalLaw, Option<clr_contact::FrictionLaw>), MbdError> {
    let name = &d.name;
    let path = format!("{name}.normal");
    if d.normal.length.is_some() {
        return Err(invalid(
            format!("{path}.length"),
            "the line laws' length is the joint's contact length min(bearing_length, \
             journal_length): remove it",
        ));
    }
    let mut normal = d.normal.clone();
    if normal.takes_length() {
        normal.length = Some(joint.contact_length());
    }
    let radii = Some((d.bearing_radius, d.journal_radius));
    let radial = normal
        .build(&path, radii)
        .map_err(|e| invalid(e.path, e.message))?;
    let thrust = match &d.thrust_normal {
        Some(t) => t
            .build(&format!("{name}.thrust_normal"), None)
            .map_err(|e| invalid(e.path, e.message))?,
        None => radial,
    };
    let friction = super::shape_compile::stateless_friction(
        name,
        d.friction.as_ref(),
        "a journal joint",
        "Gauss point",
    )?;
    Ok((radial, thrust, friction))
}

/// The drawn surface of a `[[shape]]` ([`SpatialShape::surface`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeSurface {
    /// Rotation shape frame → body frame, `[w, x, y, z]` (unit quaternion).
    pub rotation: [f64; 4],
    /// Vertices in the shape frame, m.
    pub vertices: Vec<[f64; 3]>,
    /// Triangles as indices into `vertices` (counter-clockwise seen from outside).
    pub triangles: Vec<[u32; 3]>,
}

impl SpatialShape {
    /// The shape's surface as triangles, for drawing (report pages and animations): its
    /// orientation resolved and its geometry tessellated by clr-contact
    /// ([`clr_contact::shapes3d::ContactShape3::surface`], `segments` around curved kinds).
    ///
    /// # Errors
    /// The orientation or the geometry is invalid (the error a run would give, at its field).
    pub fn surface(&self, segments: u32) -> Result<ShapeSurface, MbdError> {
        let name = &self.name;
        let rotation = match &self.orientation {
            Some(o) => UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
                orientation(&format!("{name}.orientation"), o)?,
            )),
            None => UnitQuaternion::identity(),
        };
        let path = format!("{name}.geometry");
        let desc = super::shape_compile::to_shape3(&orientation, &path, &self.geometry)?;
        let shape = clr_contact::shapes3d::ContactShape3::new(desc)
            .map_err(|source| MbdError::Contact { item: path, source })?;
        let (vertices, triangles) = shape.surface(segments);
        let q = rotation.quaternion();
        Ok(ShapeSurface {
            rotation: [q.w, q.i, q.j, q.k],
            vertices,
            triangles,
        })
    }
}

/// `[[input]]` is read in planar models only so far: a spatial function naming one is refused
/// (unbound, it would evaluate to NaN).
fn planar_inputs_only(f: &crate::TimeFn, path: &str) -> Result<(), MbdError> {
    if f.has_input() {
        return Err(invalid(
            path.to_string(),
            "`type = \"input\"` is available in planar models only in this version; give a \
             function of time"
                .to_string(),
        ));
    }
    Ok(())
}
