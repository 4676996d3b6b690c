//! The drawing of a spatial (3-D) model: what is drawn ([`SpatialScene`]: bodies through their
//! attachment points, joints with their axes, ball-and-socket clearance joints, a traced point),
//! what moves ([`SpatialFrames`], from the result columns) and the report page around it
//! ([`Report::spatial`]), drawn in the browser by three.js (`assets/report3d.js`, with the
//! vendored bundle `assets/three/three.bundle.min.js`).
//!
//! Result columns read (the spatial engine's contract): per body `B.x B.y B.z` (centre of mass,
//! world, m) and `B.qw B.qx B.qy B.qz` (unit quaternion of the body → world rotation, scalar
//! first); per ball-and-socket clearance joint `C.ex C.ey C.ez` (ball centre − socket centre,
//! world, m), `C.normal_force` (N, on the ball along −e/|e|), `C.ftx C.fty C.ftz` (friction force
//! on the ball, world, N) and `C.contact` (1 in contact, else 0). The ground is fixed at the
//! origin with the identity rotation. Missing contact columns are drawn as zero; a missing body
//! column is an error ([`SpatialError`]).

use serde::{Deserialize, Serialize};

use clr_mbd::Results;

use super::frames::{self, Plot};
use super::{Input, Limits, Report};

/// What a spatial report draws (all lengths in m).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpatialScene {
    /// Rigid bodies.
    pub bodies: Vec<BodyDraw>,
    /// Ideal joints.
    pub joints: Vec<JointDraw>,
    /// Ball-and-socket clearance joints.
    pub sockets: Vec<SocketDraw>,
    /// Journal-in-bearing (spatial revolute and cylindrical) clearance joints.
    #[serde(default)]
    pub journals: Vec<JournalDraw>,
    /// Contact shapes (`[[shape]]`), drawn as their triangulated surfaces on their bodies.
    #[serde(default)]
    pub shapes: Vec<ShapeDraw>,
    /// A point whose trajectory is drawn.
    pub trace: Option<TracePoint>,
}

/// A rigid body, drawn as tubes through its attachment points (a closed loop for three or
/// more) and a small sphere at its centre of mass; a body with one point is a small box there.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BodyDraw {
    /// Name (its result columns are `name.x`, …, `name.qz`).
    pub name: String,
    /// Attachment points in the body's centre-of-mass frame, m.
    pub points: Vec<[f64; 3]>,
}

/// An ideal joint, drawn at its place with its axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointDraw {
    /// Name.
    pub name: String,
    /// `revolute`, `spherical`, `universal`, `prismatic`, `cylindrical`, `planar` or `fixed`.
    pub kind: String,
    /// The body it is drawn on (`None`: the ground; then `at` and `axis` are world).
    pub body: Option<String>,
    /// Its place in that body's centre-of-mass frame, m.
    pub at: [f64; 3],
    /// Its axis (unit vector, that body's frame); for a planar joint the plane's normal.
    pub axis: Option<[f64; 3]>,
}

/// A contact shape: its surface as triangles, carried by its body (translucent on the ground).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShapeDraw {
    /// Name (the `[[shape]]`'s).
    pub name: String,
    /// The body it is on (`None`: the ground).
    pub body: Option<String>,
    /// Origin of the shape frame in that body's centre-of-mass frame, m.
    pub at: [f64; 3],
    /// Rotation shape frame → body frame, `[w, x, y, z]`.
    pub rotation: [f64; 4],
    /// Vertices in the shape frame, `[x, y, z]` flattened, m.
    pub vertices: Vec<f32>,
    /// Triangles, three vertex indices each, flattened (counter-clockwise seen from outside).
    pub triangles: Vec<u32>,
}

/// Segments around the curved shapes' axes in [`ShapeDraw`] (24: a ball of 10 mm is drawn
/// within 0.09 mm of its surface).
pub const SHAPE_SEGMENTS: u32 = 24;

/// A ball-and-socket clearance joint: the socket sphere on one body, the ball on the other.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SocketDraw {
    /// Name (its result columns are `name.ex`, …).
    pub name: String,
    /// Body of the socket (`None`: the ground).
    pub socket_body: Option<String>,
    /// Socket centre in that body's centre-of-mass frame, m.
    pub socket_at: [f64; 3],
    /// Body of the ball (`None`: the ground).
    pub ball_body: Option<String>,
    /// Ball centre in that body's centre-of-mass frame, m.
    pub ball_at: [f64; 3],
    /// Socket radius R, m.
    pub socket_radius: f64,
    /// Ball radius r < R, m (the clearance is R − r).
    pub ball_radius: f64,
}

/// A journal-in-bearing clearance joint: the bore (a translucent cylinder with its two rims) on
/// the bearing body, the journal (a solid cylinder) on the other; the page magnifies the
/// journal's radial offset and tilt in the bore by the clearance magnification, and marks each
/// radial region in contact at the journal's end on the side of that end's offset, each thrust
/// face in contact at the journal's end face.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JournalDraw {
    /// Name (its result columns are `name.radial_a.normal_force`, …).
    pub name: String,
    /// Body of the bearing (`None`: the ground).
    pub bearing_body: Option<String>,
    /// Bore centre (mid-length) in that body's centre-of-mass frame, m.
    pub bearing_at: [f64; 3],
    /// Bore axis in that body's frame (unit vector).
    pub bearing_axis: [f64; 3],
    /// Body of the journal (`None`: the ground).
    pub journal_body: Option<String>,
    /// Journal centre (mid-length) in that body's centre-of-mass frame, m.
    pub journal_at: [f64; 3],
    /// Journal axis in that body's frame (unit vector).
    pub journal_axis: [f64; 3],
    /// Bore radius R_b, m.
    pub bearing_radius: f64,
    /// Bore length L_b, m.
    pub bearing_length: f64,
    /// Journal radius R_j < R_b, m.
    pub journal_radius: f64,
    /// Journal length L_j, m.
    pub journal_length: f64,
}

/// Per journal and frame, the normal forces stored in [`SpatialFrames::journals`], N, in this
/// order (radial region A at the bore's low end, B at its high end, thrust faces − and +).
pub const JOURNAL_VALUES: [&str; 4] = [
    "radial_a.normal_force",
    "radial_b.normal_force",
    "thrust_minus.normal_force",
    "thrust_plus.normal_force",
];

/// The point whose trajectory is drawn.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TracePoint {
    /// Its body.
    pub body: String,
    /// Its place in the body's centre-of-mass frame, m.
    pub at: [f64; 3],
}

/// Per socket and frame, the values stored in [`SpatialFrames::sockets`], in this order.
pub const SOCKET_VALUES: [&str; 8] = [
    "ex",
    "ey",
    "ez",
    "normal_force",
    "ftx",
    "fty",
    "ftz",
    "contact",
];

/// The animation frames of a spatial model (numbers stored as `f32`, as the planar frames).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpatialFrames {
    /// Frame times, s.
    pub t: Vec<f64>,
    /// Per body: `[x, y, z, qw, qx, qy, qz]` per frame, flattened (m; unit quaternion).
    pub pose: Vec<Vec<f32>>,
    /// Per socket: the eight [`SOCKET_VALUES`] per frame, flattened (m, N, 1/0).
    pub sockets: Vec<Vec<f32>>,
    /// Per journal: the four [`JOURNAL_VALUES`] per frame, flattened, N (0 for a column the
    /// results lack, as the thrust faces of a cylindrical joint).
    #[serde(default)]
    pub journals: Vec<Vec<f32>>,
    /// The traced point's world place `[x, y, z]` per frame, flattened, m (empty without one).
    pub trace: Vec<f32>,
}

/// The scene with its frames, as the page carries it (`Report::spatial`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpatialView {
    /// What is drawn.
    pub scene: SpatialScene,
    /// What moves.
    pub frames: SpatialFrames,
}

/// Why a spatial scene cannot be drawn from the results.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpatialError {
    /// A body of the scene has no pose column.
    #[error("the results have no column `{column}`: body `{body}` of the drawing has no recorded pose (name the bodies of the drawing as the model does)")]
    MissingColumn {
        /// The body.
        body: String,
        /// The column.
        column: String,
    },
    /// A joint, socket or trace names a body the scene does not list.
    #[error("{item} names body `{body}`, which the drawing does not list in `bodies` (add it there or correct the name)")]
    UnknownBody {
        /// What names it.
        item: String,
        /// The name.
        body: String,
    },
}

/// Rotate `v` by the unit quaternion `q = [w, x, y, z]`: v + 2w(u×v) + 2u×(u×v) with u the
/// vector part (Kuipers, *Quaternions and Rotation Sequences*, 1999, eq. 5.13 expanded).
pub fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let u = [q[1], q[2], q[3]];
    let c = cross(u, v);
    let cc = cross(u, c);
    [0, 1, 2].map(|k| v[k] + 2.0 * (q[0] * c[k] + cc[k]))
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// A body's pose in one frame: centre of mass (world, m) and rotation (body → world).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Centre of mass, world, m.
    pub x: [f64; 3],
    /// Unit quaternion `[w, x, y, z]`, body → world.
    pub q: [f64; 4],
}

impl Pose {
    /// The ground: at the origin, not turned.
    pub const GROUND: Pose = Pose {
        x: [0.0; 3],
        q: [1.0, 0.0, 0.0, 0.0],
    };

    /// The world place of the body point `p` (m).
    pub fn point(&self, p: [f64; 3]) -> [f64; 3] {
        let r = rotate(self.q, p);
        [0, 1, 2].map(|k| self.x[k] + r[k])
    }

    /// The world direction of the body direction `d`.
    pub fn direction(&self, d: [f64; 3]) -> [f64; 3] {
        rotate(self.q, d)
    }
}

impl SpatialScene {
    /// Index of body `name` in [`Self::bodies`] (`None` for the ground).
    ///
    /// # Errors
    /// [`SpatialError::UnknownBody`] when the scene does not list it.
    fn body_index(&self, item: &str, name: Option<&str>) -> Result<Option<usize>, SpatialError> {
        let Some(name) = name else { return Ok(None) };
        match self.bodies.iter().position(|b| b.name == name) {
            Some(k) => Ok(Some(k)),
            None => Err(SpatialError::UnknownBody {
                item: item.to_string(),
                body: name.to_string(),
            }),
        }
    }

    /// Check that every body named by a joint, socket or the trace is listed.
    ///
    /// # Errors
    /// The first [`SpatialError::UnknownBody`].
    pub fn check(&self) -> Result<(), SpatialError> {
        for j in &self.joints {
            self.body_index(&format!("joint `{}`", j.name), j.body.as_deref())?;
        }
        for s in &self.sockets {
            let item = format!("socket `{}`", s.name);
            self.body_index(&item, s.socket_body.as_deref())?;
            self.body_index(&item, s.ball_body.as_deref())?;
        }
        for j in &self.journals {
            let item = format!("journal `{}`", j.name);
            self.body_index(&item, j.bearing_body.as_deref())?;
            self.body_index(&item, j.journal_body.as_deref())?;
        }
        if let Some(tr) = &self.trace {
            self.body_index("the trace", Some(&tr.body))?;
        }
        Ok(())
    }
}

impl SpatialFrames {
    /// The frames of `results` at `rows` for `scene`.
    ///
    /// # Errors
    /// [`SpatialError`] when a body has no pose column or an item names an unlisted body.
    pub fn new(
        scene: &SpatialScene,
        results: &Results,
        rows: &[usize],
    ) -> Result<Self, SpatialError> {
        scene.check()?;
        let t = results
            .column("t")
            .unwrap_or_else(|| vec![0.0; results.len()]);
        let mut pose = Vec::with_capacity(scene.bodies.len());
        for b in &scene.bodies {
            let mut cols = Vec::with_capacity(7);
            for c in ["x", "y", "z", "qw", "qx", "qy", "qz"] {
                let column = format!("{}.{c}", b.name);
                cols.push(results.column(&column).ok_or(SpatialError::MissingColumn {
                    body: b.name.clone(),
                    column,
                })?);
            }
            pose.push(
                rows.iter()
                    .flat_map(|&r| cols.iter().map(move |c| c[r] as f32))
                    .collect(),
            );
        }
        let sockets = scene
            .sockets
            .iter()
            .map(|s| values_at(results, &s.name, &SOCKET_VALUES, rows))
            .collect();
        let journals = scene
            .journals
            .iter()
            .map(|j| values_at(results, &j.name, &JOURNAL_VALUES, rows))
            .collect();
        let mut frames = SpatialFrames {
            t: rows.iter().map(|&r| t[r]).collect(),
            pose,
            sockets,
            journals,
            trace: Vec::new(),
        };
        if let Some(tr) = &scene.trace {
            let k = scene.body_index("the trace", Some(&tr.body))?;
            frames.trace = (0..frames.t.len())
                .flat_map(|f| frames.pose_of(k, f).point(tr.at).map(|v| v as f32))
                .collect();
        }
        Ok(frames)
    }

    /// The pose of body `k` (`None`: the ground) in frame `f`.
    pub fn pose_of(&self, k: Option<usize>, f: usize) -> Pose {
        let Some(p) = k
            .and_then(|k| self.pose.get(k))
            .and_then(|p| p.get(7 * f..7 * f + 7))
        else {
            return Pose::GROUND;
        };
        let v = |i: usize| f64::from(p[i]);
        Pose {
            x: [v(0), v(1), v(2)],
            q: [v(3), v(4), v(5), v(6)],
        }
    }

    /// The four [`JOURNAL_VALUES`] of journal `j` in frame `f`, N (zeros when absent).
    pub fn journal(&self, j: usize, f: usize) -> [f64; 4] {
        let v = self.journals.get(j).and_then(|a| a.get(4 * f..4 * f + 4));
        std::array::from_fn(|i| v.map_or(0.0, |v| f64::from(v[i])))
    }

    /// The eight [`SOCKET_VALUES`] of socket `s` in frame `f` (zeros when absent).
    pub fn socket(&self, s: usize, f: usize) -> [f64; 8] {
        let v = self.sockets.get(s).and_then(|a| a.get(8 * f..8 * f + 8));
        std::array::from_fn(|i| v.map_or(0.0, |v| f64::from(v[i])))
    }
}

impl SpatialView {
    /// The scene with its frames at `rows` of `results`.
    ///
    /// # Errors
    /// As [`SpatialFrames::new`].
    pub fn new(
        scene: SpatialScene,
        results: &Results,
        rows: &[usize],
    ) -> Result<Self, SpatialError> {
        let frames = SpatialFrames::new(&scene, results, rows)?;
        Ok(SpatialView { scene, frames })
    }

    /// Index of body `name` (`None`: the ground, or a name the scene does not list, which
    /// [`SpatialScene::check`] has ruled out).
    pub fn body(&self, name: Option<&str>) -> Option<usize> {
        name.and_then(|n| self.scene.bodies.iter().position(|b| b.name == n))
    }
}

/// The figures of a spatial run: the normal force of every socket and the energy balance, each
/// decimated to about `max` points per line.
pub fn plots(scene: &SpatialScene, results: &Results, max: usize) -> Vec<Plot> {
    let Some(t) = results.column("t") else {
        return Vec::new();
    };
    let mut forces = frames::time_plot("contact forces", "normal force F_N [N]");
    for s in &scene.sockets {
        if let Some(f) = results.column(&format!("{}.normal_force", s.name)) {
            forces.lines.push(frames::time_line(&s.name, &t, &f, max));
        }
    }
    for j in &scene.journals {
        for v in JOURNAL_VALUES {
            let Some(f) = results.column(&format!("{}.{v}", j.name)) else {
                continue;
            };
            // a group that never touches adds nothing but a flat line at zero
            if f.iter().any(|&x| x != 0.0) {
                let group = v.trim_end_matches(".normal_force");
                let label = format!("{}.{group}", j.name);
                forces.lines.push(frames::time_line(&label, &t, &f, max));
            }
        }
    }
    let mut out = Vec::new();
    if !forces.lines.is_empty() {
        out.push(forces);
    }
    out.extend(frames::energy_plot(results, &t, max));
    out
}

impl Report {
    /// The report of a spatial run (`kind = "run"`) or initial state (`"view"`): the page of
    /// [`Report::new`] (metrics, impacts, figures, notes) with the 3-D drawing of `scene` in
    /// place of the planar one. `input.desc` is not read (a spatial model has no planar
    /// description).
    ///
    /// # Errors
    /// [`SpatialError`] when the scene does not fit the results.
    pub fn spatial(
        kind: &'static str,
        input: &Input<'_>,
        scene: SpatialScene,
        limits: Limits,
    ) -> Result<Self, SpatialError> {
        let t = input.results.column("t").unwrap_or_default();
        let rows = frames::select(&t, limits.frames);
        let plots = plots(&scene, input.results, limits.points);
        let view = SpatialView::new(scene, input.results, &rows)?;
        let planar = Input {
            desc: Err(String::new()),
            model: input.model,
            source: input.source,
            description: input.description,
            results: input.results,
            metrics: input.metrics,
            notes: input.notes,
            error: input.error,
        };
        let mut report = Report::new(kind, &planar, limits);
        report.scene_note = None;
        report.plots = plots;
        report.spatial = Some(view);
        Ok(report)
    }
}

/// Extra style of a spatial page.
pub(super) const CSS: &str = include_str!("assets/report3d.css");

/// The scripts a spatial page carries before `report.js`: the three.js bundle (classic script
/// defining the global `THREE`: see `assets/three/README.md`) and the 3-D stage.
pub(super) fn scripts() -> String {
    format!(
        "<script>\n{three}\n</script>\n<script>\n{stage}\n</script>\n",
        three = include_str!("assets/three/three.bundle.min.js"),
        stage = include_str!("assets/report3d.js"),
    )
}

/// The columns `name.<value>` of `results` at `rows`, interleaved per row (0 for a missing
/// column).
fn values_at(results: &Results, name: &str, values: &[&str], rows: &[usize]) -> Vec<f32> {
    let cols: Vec<Option<Vec<f64>>> = values
        .iter()
        .map(|c| results.column(&format!("{name}.{c}")))
        .collect();
    rows.iter()
        .flat_map(|&r| {
            cols.iter()
                .map(move |c| c.as_ref().map_or(0.0, |c| c[r] as f32))
        })
        .collect()
}

/// Synthetic spatial results for tests (here and in `clr animate`): a top (body `top`) on a
/// spherical joint at the world origin spinning at ω = 2π rad/s about its axis
/// a = (sin 30°, cos 30°, 0), its centre of mass at 0.3·a; a ball-and-socket clearance joint
/// `cup` (socket on the ground at (0.5, 0, 0), R = 20 mm, r = 19 mm) whose ball runs on a
/// circle of radius 0.8 mm in the socket's x-y plane, once per second, pressed with 100 N and
/// rubbed with 20 N of friction. `rows` rows over t = 0 … 1 s. Returns the scene and results.
#[doc(hidden)]
pub fn spinning_top(rows: usize) -> (SpatialScene, Results) {
    let a = spin_axis();
    let mut columns: Vec<String> = vec!["t".into()];
    for c in ["x", "y", "z", "qw", "qx", "qy", "qz"] {
        columns.push(format!("top.{c}"));
    }
    for c in SOCKET_VALUES {
        columns.push(format!("cup.{c}"));
    }
    let mut data = Vec::with_capacity(rows * columns.len());
    for k in 0..rows {
        let t = k as f64 / (rows.max(2) - 1) as f64;
        let (s, c) = (std::f64::consts::PI * t).sin_cos();
        let (ex, ey) = (0.8e-3 * (2.0 * s * c), 0.8e-3 * (s * s - c * c));
        data.push(t);
        data.extend([
            0.3 * a[0],
            0.3 * a[1],
            0.3 * a[2],
            c,
            s * a[0],
            s * a[1],
            s * a[2],
        ]);
        data.extend([
            ex,
            ey,
            0.0,
            100.0,
            -20.0 * ey / 0.8e-3,
            20.0 * ex / 0.8e-3,
            0.0,
            1.0,
        ]);
    }
    let scene = SpatialScene {
        bodies: vec![BodyDraw {
            name: "top".into(),
            points: vec![
                [-0.3 * a[0], -0.3 * a[1], 0.0],
                [0.1, 0.0, 0.1],
                [-0.1, 0.0, -0.1],
            ],
        }],
        joints: vec![JointDraw {
            name: "pivot".into(),
            kind: "spherical".into(),
            body: None,
            at: [0.0; 3],
            axis: None,
        }],
        journals: Vec::new(),
        shapes: Vec::new(),
        sockets: vec![SocketDraw {
            name: "cup".into(),
            socket_body: None,
            socket_at: [0.5, 0.0, 0.0],
            ball_body: Some("top".into()),
            ball_at: [0.1, 0.0, 0.1],
            socket_radius: 0.020,
            ball_radius: 0.019,
        }],
        trace: Some(TracePoint {
            body: "top".into(),
            at: [0.1, 0.0, 0.1],
        }),
    };
    let results = Results {
        columns,
        data,
        ..Results::default()
    };
    (scene, results)
}

/// The spin axis of [`spinning_top`], (sin 30°, cos 30°, 0).
fn spin_axis() -> [f64; 3] {
    let b = 30f64.to_radians();
    [b.sin(), b.cos(), 0.0]
}

impl SpatialScene {
    /// The drawing of a spatial model description: every body through the points its joints,
    /// forces and sockets attach to (centre-of-mass frame), the joints with their axes, the
    /// sockets and journals, and the trace of the first ball (else of the first journal's
    /// centre, else of the last body's centre of mass).
    pub fn from_desc(d: &clr_mbd::spatial::SpatialDesc) -> Self {
        use clr_mbd::spatial::{End, SpatialForce};
        let com = |body: &str| {
            d.bodies
                .iter()
                .find(|b| b.name == body)
                .map(|b| b.centre_of_mass)
        };
        let local = |e: &End| match com(&e.body) {
            Some(c) => (Some(e.body.clone()), sub(e.at, c)),
            None => (None, e.at),
        };
        let mut bodies: Vec<BodyDraw> = d
            .bodies
            .iter()
            .map(|b| BodyDraw {
                name: b.name.clone(),
                points: Vec::new(),
            })
            .collect();
        let mut attach = |e: &End| {
            if let (Some(b), p) = local(e) {
                if let Some(bd) = bodies.iter_mut().find(|x| x.name == b) {
                    if !bd.points.contains(&p) {
                        bd.points.push(p);
                    }
                }
            }
        };
        let mut joints = Vec::new();
        for j in &d.joints {
            attach(&j.a);
            attach(&j.b);
            let (body, at) = local(&j.a);
            let kind = serde_json::to_value(j.kind)
                .ok()
                .and_then(|v| v.as_str().map(String::from))
                .unwrap_or_default();
            joints.push(JointDraw {
                name: j.name.clone(),
                kind,
                body,
                at,
                axis: j.a.axis,
            });
        }
        for f in &d.forces {
            match f {
                SpatialForce::SpringDamper { a, b, .. }
                | SpatialForce::Actuator { a, b, .. }
                | SpatialForce::Bushing { a, b, .. } => {
                    attach(a);
                    attach(b);
                }
                SpatialForce::Force { at, .. } => attach(at),
                _ => {}
            }
        }
        let mut shapes = Vec::new();
        for s in &d.shapes {
            attach(&s.at);
            // an invalid shape is refused by the run at its field; the drawing leaves it out
            if let Ok(surface) = s.surface(SHAPE_SEGMENTS) {
                let (body, at) = local(&s.at);
                shapes.push(ShapeDraw {
                    name: s.name.clone(),
                    body,
                    at,
                    rotation: surface.rotation,
                    vertices: surface
                        .vertices
                        .iter()
                        .flatten()
                        .map(|&x| x as f32)
                        .collect(),
                    triangles: surface.triangles.into_iter().flatten().collect(),
                });
            }
        }
        let mut sockets = Vec::new();
        let mut journals = Vec::new();
        for c in &d.clearances {
            let c = match c {
                clr_mbd::spatial::SpatialClearance::Spherical(c) => c,
                clr_mbd::spatial::SpatialClearance::Journal(j) => {
                    attach(&j.bearing);
                    attach(&j.journal);
                    let (bearing_body, bearing_at) = local(&j.bearing);
                    let (journal_body, journal_at) = local(&j.journal);
                    journals.push(JournalDraw {
                        name: j.name.clone(),
                        bearing_body,
                        bearing_at,
                        bearing_axis: unit(j.bearing.axis.unwrap_or([0.0, 0.0, 1.0])),
                        journal_body,
                        journal_at,
                        journal_axis: unit(j.journal.axis.unwrap_or([0.0, 0.0, 1.0])),
                        bearing_radius: j.bearing_radius,
                        bearing_length: j.bearing_length,
                        journal_radius: j.journal_radius,
                        journal_length: j.journal_length,
                    });
                    continue;
                }
                clr_mbd::spatial::SpatialClearance::Contact(_) => continue,
            };
            attach(&c.socket);
            attach(&c.ball);
            let (socket_body, socket_at) = local(&c.socket);
            let (ball_body, ball_at) = local(&c.ball);
            sockets.push(SocketDraw {
                name: c.name.clone(),
                socket_body,
                socket_at,
                ball_body,
                ball_at,
                socket_radius: c.socket_radius,
                ball_radius: c.ball_radius,
            });
        }
        let trace = match sockets.first() {
            Some(SocketDraw {
                ball_body: Some(b),
                ball_at,
                ..
            }) => Some(TracePoint {
                body: b.clone(),
                at: *ball_at,
            }),
            _ => match journals.first() {
                Some(JournalDraw {
                    journal_body: Some(b),
                    journal_at,
                    ..
                }) => Some(TracePoint {
                    body: b.clone(),
                    at: *journal_at,
                }),
                _ => d.bodies.last().map(|b| TracePoint {
                    body: b.name.clone(),
                    at: [0.0; 3],
                }),
            },
        };
        Self {
            bodies,
            joints,
            sockets,
            journals,
            shapes,
            trace,
        }
    }
}

/// `v` scaled to unit length (unchanged when zero: the reader refuses a zero axis).
fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if n > 0.0 {
        [v[0] / n, v[1] / n, v[2] / n]
    } else {
        v
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rodrigues' rotation formula (Rodrigues 1840; e.g. Shabana, *Computational Dynamics*,
    /// 3rd ed., eq. 7.24): R v = v cos φ + (a × v) sin φ + a (a·v)(1 − cos φ), an independent
    /// form of the quaternion rotation.
    fn rodrigues(a: [f64; 3], phi: f64, v: [f64; 3]) -> [f64; 3] {
        let (s, c) = phi.sin_cos();
        let av = cross(a, v);
        let d = a[0] * v[0] + a[1] * v[1] + a[2] * v[2];
        [0, 1, 2].map(|k| v[k] * c + av[k] * s + a[k] * d * (1.0 - c))
    }

    fn input<'a>(results: &'a Results) -> Input<'a> {
        Input {
            model: "top",
            source: "test",
            description: "a spinning top and a ball in a socket",
            desc: Err("spatial".into()),
            results,
            metrics: &[],
            notes: &[],
            error: None,
        }
    }

    #[test]
    fn the_traced_point_turns_about_the_tilted_axis_as_rodrigues_says() {
        let (scene, results) = spinning_top(101);
        let rows: Vec<usize> = (0..101).collect();
        let fr = SpatialFrames::new(&scene, &results, &rows).unwrap();
        let a = spin_axis();
        let p = [0.1, 0.0, 0.1];
        for (f, &t) in fr.t.iter().enumerate() {
            let r = rodrigues(a, 2.0 * std::f64::consts::PI * t, p);
            let want = [0, 1, 2].map(|k| 0.3 * a[k] + r[k]);
            // f32 storage: 7 digits of 0.4 m, 1e-6 m is ample and far below a pixel
            for (k, w) in want.iter().enumerate() {
                let got = f64::from(fr.trace[3 * f + k]);
                assert!((got - w).abs() < 1e-6, "t {t} axis {k}: {got} vs {w}");
            }
            // the pivot (body point −0.3·a) stays at the origin: the spherical joint holds
            let pivot = fr.pose_of(Some(0), f).point(a.map(|v| -0.3 * v));
            assert!(pivot.iter().all(|v| v.abs() < 1e-6), "{pivot:?}");
        }
        // the socket values come through in their order (t = 0.5 s: e = (0, 0.8 mm, 0))
        let s = fr.socket(0, 50);
        assert!((s[1] - 0.8e-3).abs() < 1e-9 && s[0].abs() < 1e-9, "{s:?}");
        assert_eq!((s[3], s[7]), (100.0, 1.0));
    }

    #[test]
    fn a_missing_pose_column_or_body_is_an_error_that_names_it() {
        let (mut scene, results) = spinning_top(3);
        scene.bodies[0].name = "spinner".into();
        scene.trace = None;
        scene.sockets.clear();
        let err = SpatialFrames::new(&scene, &results, &[0]).unwrap_err();
        assert!(err.to_string().contains("`spinner.x`"), "{err}");
        let (mut scene, results) = spinning_top(3);
        scene.joints[0].body = Some("lid".into());
        let err = SpatialFrames::new(&scene, &results, &[0]).unwrap_err();
        assert!(
            err.to_string().contains("joint `pivot` names body `lid`"),
            "{err}"
        );
    }

    /// The page data between `<script id="clr-data" …>` and `</script>`.
    fn page_data(html: &str) -> serde_json::Value {
        let open = "type=\"application/json\">";
        let start = html.find(open).unwrap() + open.len();
        let end = start + html[start..].find("</script>").unwrap();
        serde_json::from_str(&html[start..end].replace("<\\/", "</")).unwrap()
    }

    /// Every `http://` or `https://` in the page, except the XML namespace names three.js
    /// passes to `createElementNS` (names, never fetched).
    fn urls(html: &str) -> Vec<String> {
        const NAMESPACES: [&str; 2] =
            ["http://www.w3.org/1999/xhtml", "http://www.w3.org/2000/svg"];
        let mut out = Vec::new();
        for (i, _) in html.match_indices("http") {
            let rest = &html[i..];
            let is_url = rest.starts_with("http://") || rest.starts_with("https://");
            if is_url && !NAMESPACES.iter().any(|n| rest.starts_with(n)) {
                out.push(rest.chars().take(60).collect());
            }
        }
        out
    }

    #[test]
    fn the_spatial_page_is_self_contained_and_carries_scene_and_three_js() {
        let (scene, results) = spinning_top(201);
        let limits = Limits {
            frames: 50,
            points: 100,
        };
        let report = Report::spatial("run", &input(&results), scene.clone(), limits).unwrap();
        let html = report.html();
        assert_eq!(urls(&html), Vec::<String>::new());
        let data = page_data(&html);
        let view: SpatialView = serde_json::from_value(data["spatial"].clone()).unwrap();
        assert_eq!(view.scene, scene);
        assert_eq!(view.frames.t.len(), 50);
        assert_eq!(view.frames.pose[0].len(), 50 * 7);
        assert_eq!(view.frames.trace.len(), 50 * 3);
        assert!(data["scene"].is_null() && data["scene_note"].is_null());
        let titles: Vec<&str> = (data["plots"].as_array().unwrap().iter())
            .map(|p| p["title"].as_str().unwrap())
            .collect();
        assert_eq!(titles, ["contact forces"]);
        assert!(html.contains("var THREE=") && html.contains("OrbitControls"));
        assert!(html.contains("window.clrSpatialStage = function"));
        // the classic scripts stay closed where they should: no "</script" inside them
        assert_eq!(html.matches("</script>").count(), 4);
    }

    /// A journal joint of a model file is drawn with its bodies, centres and unit axes (in the
    /// centre-of-mass frames), and its frames carry the four group forces of the results.
    #[test]
    fn a_journal_joint_is_drawn_from_its_description_with_its_group_forces() {
        let text = include_str!("../../models/examples/spatial_revolute_clearance.toml");
        let d = clr_mbd::spatial::SpatialDesc::from_toml_table(text.parse().unwrap()).unwrap();
        let scene = SpatialScene::from_desc(&d);
        let [j] = scene.journals.as_slice() else {
            panic!("{:?}", scene.journals)
        };
        assert_eq!(j.bearing_body, None);
        assert_eq!(j.journal_body.as_deref(), Some("pendulum"));
        // the journal at the frame origin, the centre of mass 0.1 m along x
        assert_eq!(j.journal_at, [-0.1, 0.0, 0.0]);
        let n = j.bearing_axis.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!((n - 1.0).abs() < 1e-15, "{n}");
        assert_eq!(scene.trace.as_ref().map(|t| t.at), Some([-0.1, 0.0, 0.0]));
        let mut columns: Vec<String> = ["t", "pendulum.x", "pendulum.y", "pendulum.z"]
            .map(String::from)
            .to_vec();
        columns.extend(["qw", "qx", "qy", "qz"].map(|c| format!("pendulum.{c}")));
        columns.extend(JOURNAL_VALUES.map(|v| format!("pin.{v}")));
        let row = [0.0, 0.1, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.5, 2.5, 0.0, 4.0];
        let results = Results {
            columns,
            data: [row, row].concat(),
            ..Results::default()
        };
        let frames = SpatialFrames::new(&scene, &results, &[0, 1]).unwrap();
        assert_eq!(
            frames.journals,
            vec![vec![1.5, 2.5, 0.0, 4.0, 1.5, 2.5, 0.0, 4.0]]
        );
        let titles: Vec<String> = plots(&scene, &results, 10)[0]
            .lines
            .iter()
            .map(|l| l.label.clone())
            .collect();
        assert_eq!(titles, ["pin.radial_a", "pin.radial_b", "pin.thrust_plus"]);
    }

    /// The slider-in-guide example's shapes: the guide on the ground as its four plates (8
    /// corners and 12 triangles each), the slider on its block, both at their places.
    #[test]
    fn contact_shapes_are_in_the_scene_with_their_surfaces() {
        let text = include_str!("../../models/examples/spatial_slider_in_guide.toml");
        let d = clr_mbd::spatial::SpatialDesc::from_toml_table(text.parse().unwrap()).unwrap();
        let scene = SpatialScene::from_desc(&d);
        let [guide, slider] = scene.shapes.as_slice() else {
            panic!("{:?}", scene.shapes.len())
        };
        assert_eq!(
            (guide.name.as_str(), guide.body.as_deref()),
            ("guide", None)
        );
        assert_eq!(
            (guide.vertices.len(), guide.triangles.len()),
            (4 * 8 * 3, 4 * 12 * 3)
        );
        assert_eq!(slider.body.as_deref(), Some("block"));
        assert_eq!(
            (slider.vertices.len(), slider.triangles.len()),
            (8 * 3, 12 * 3)
        );
        assert_eq!(slider.rotation, [1.0, 0.0, 0.0, 0.0]);
        let top = guide
            .vertices
            .chunks_exact(3)
            .map(|v| v[2])
            .fold(f32::MIN, f32::max);
        assert!((top - 0.0155).abs() < 1e-7, "{top}");
    }

    #[test]
    fn a_planar_page_carries_neither_three_js_nor_spatial_data() {
        let (_, results) = spinning_top(3);
        let report = Report::new("run", &input(&results), Limits::default());
        let html = report.html();
        assert!(!html.contains("var THREE=") && !html.contains("clrSpatialStage = function"));
        assert!(page_data(&html).get("spatial").is_none());
        assert_eq!(html.matches("</script>").count(), 2);
    }
}
