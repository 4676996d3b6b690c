//! The drawing of a mechanism, from its plain description (`clr_mbd::ModelDesc`): the parts
//! (rigid bodies and the floating frames of flexible bodies) with the points where elements
//! attach, the beams with their undeformed nodes, and every element with its anchors resolved
//! to a part or a beam node. Element kinds are read generically through their serde form, so a
//! new kind is drawn (as links between its anchors) without a change here; the renderer
//! (`assets/report.js`) gives the known kinds their own symbols. Contact shapes (`[[shape]]`)
//! are drawn as their outlines, taken from the clr-contact [`Shape`] of each geometry.

use std::collections::BTreeMap;

use clr_contact::Shape;
use clr_mbd::desc::SectionDesc;
use clr_mbd::element::shape::ShapeDesc;
use clr_mbd::ModelDesc;
use serde::Serialize;
use serde_json::Value;

/// Fields of an element that hold an anchor (a point name, `{body, at}` or `{beam, node}`).
const ANCHOR_FIELDS: &[&str] = &["a", "b", "at", "bearing", "journal", "guide", "slider"];
/// Fields of an element that name a body.
const BODY_FIELDS: &[&str] = &["body", "body_i", "body_j", "beam"];
/// Points on a full circle of a ball or a capsule's ends (chord sagitta 0.2 % of the radius).
const CIRCLE_POINTS: usize = 48;
/// Most outline points of one shape: longer outlines are thinned evenly (a 1000-point
/// polyline is kept whole; an involute gear of more than about 75 teeth, at about 52 points
/// per tooth, loses flank points).
pub const MAX_SHAPE_POINTS: usize = 4000;

/// Where an element attaches, resolved: a point of a part (index into [`Scene::parts`], `-1`
/// for the ground) in that part's frame (m), or a node of a beam (index into [`Scene::beams`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum At {
    /// A point (m) in the frame of part `part` (`-1`: the world frame).
    Part {
        /// Part index, `-1` for the ground.
        part: i64,
        /// Local coordinates, m.
        at: [f64; 2],
    },
    /// A node of a beam.
    Node {
        /// Beam index.
        beam: usize,
        /// Node index (0 at the beam's start).
        node: usize,
    },
}

/// A moving frame: a rigid body or the floating frame of a flexible body.
#[derive(Debug, Clone, Serialize)]
pub struct Part {
    /// Name (its result columns are `name.x`, `name.y`, `name.theta`).
    pub name: String,
    /// `rigid` or `flexible`.
    pub kind: &'static str,
    /// Centre of mass in the part frame, m (the columns `x`, `y` are those of this point).
    pub com: [f64; 2],
    /// Initial pose [x, y, θ] of the frame origin as given (m, rad; missing entries 0).
    pub pose0: [f64; 3],
    /// Every point where something attaches (the origins of contact shapes included), in the
    /// part frame (m): the outline is drawn through them.
    pub points: Vec<[f64; 2]>,
}

/// A beam: ground-fixed (`part == -1`, nodes in world coordinates) or the mesh of a flexible
/// body (nodes in its frame).
#[derive(Debug, Clone, Serialize)]
pub struct Beam {
    /// Name.
    pub name: String,
    /// `-1` for a ground-fixed beam, else the part index of the flexible body's frame.
    pub part: i64,
    /// Undeformed node positions, m.
    pub nodes: Vec<[f64; 2]>,
    /// Section depth in the bending plane, m (drawn width).
    pub depth: f64,
}

/// One element of the description: its section (`joint`, `driver`, `force`, `clearance`),
/// kind, name, resolved anchors, the bodies it names and its numeric parameters (radii, sizes,
/// angles, axis).
#[derive(Debug, Clone, Serialize)]
pub struct Item {
    /// Section of the model file.
    pub section: &'static str,
    /// Kind (`type` in the file).
    pub kind: String,
    /// Name.
    pub name: String,
    /// Anchor field → where it attaches.
    pub anchors: BTreeMap<String, At>,
    /// Body field → part index (`-1` ground), or beam index for `beam`.
    pub bodies: BTreeMap<String, i64>,
    /// Numeric fields and 2-vectors (SI units of the model file).
    pub params: BTreeMap<String, Value>,
    /// The shapes it puts in contact, indices into [`Scene::shapes`] in the file's order (A, B
    /// of a `contact` clearance); empty for other kinds (and then not written).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub shapes: Vec<usize>,
}

/// One closed or open line of a shape's outline, in the shape frame (m).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Outline {
    /// Vertices, m; a closed outline is counter-clockwise and does not repeat its first point.
    pub points: Vec<[f64; 2]>,
    /// True for a polygon (filled), false for an open chain (a polyline shape).
    pub closed: bool,
}

/// A contact shape (`[[shape]]`), drawn with the part it is attached to.
#[derive(Debug, Clone, Serialize)]
pub struct ShapeItem {
    /// Name.
    pub name: String,
    /// Origin of the shape frame: a point of a part (`part` −1: the ground, world m) or a beam
    /// node (the shape moves with the node; node rotations are not drawn); none for a beam face
    /// (`beam_face`: it follows its beam, which is drawn as such, and has no outline here).
    pub at: Option<At>,
    /// Angle of the shape frame from the part's x axis, rad.
    pub angle: f64,
    /// Geometry kind (`type` in the file: `ball`, `cuboid`, `involute_gear`, …).
    pub kind: String,
    /// The outline in the shape frame, m: one polygon for a ball (48 points), capsule
    /// (stadium), cuboid or convex polygon, an open chain for a polyline, and for a compound
    /// the outline of every part placed by its pose, or, when the parts are a disc and convex
    /// polygons each crossing its circle once (an involute gear: core and teeth), the one
    /// outline of their union. At most [`MAX_SHAPE_POINTS`] points in all.
    pub outlines: Vec<Outline>,
}

/// The drawable mechanism.
#[derive(Debug, Clone, Serialize)]
pub struct Scene {
    /// Moving frames.
    pub parts: Vec<Part>,
    /// Ground points where something attaches (world, m); not the origins of contact shapes
    /// (no ground symbol is drawn under a shape).
    pub ground: Vec<[f64; 2]>,
    /// Beams.
    pub beams: Vec<Beam>,
    /// Joints, drivers, forces and clearances.
    pub items: Vec<Item>,
    /// Contact shapes.
    pub shapes: Vec<ShapeItem>,
    /// Gravity [g_x, g_y], m/s².
    pub gravity: [f64; 2],
}

/// Section depth (m) in the bending plane.
fn depth(s: &SectionDesc) -> f64 {
    match s {
        SectionDesc::Rectangular { depth, .. } | SectionDesc::General { depth, .. } => *depth,
        SectionDesc::Circular { diameter } => *diameter,
        SectionDesc::Tube { outer_diameter, .. } => *outer_diameter,
    }
}

/// Equally spaced nodes from `start` to `end` (m).
fn mesh(start: [f64; 2], end: [f64; 2], elements: usize) -> Vec<[f64; 2]> {
    let n = elements.max(1);
    (0..=n)
        .map(|k| {
            let s = k as f64 / n as f64;
            [
                start[0] + s * (end[0] - start[0]),
                start[1] + s * (end[1] - start[1]),
            ]
        })
        .collect()
}

impl Scene {
    /// The scene of a description. Anchors that name nothing known (the description was
    /// checked, so only by a bug) are left out of their item.
    pub fn from_desc(desc: &ModelDesc) -> Self {
        let mut s = Scene {
            parts: Vec::new(),
            ground: Vec::new(),
            beams: Vec::new(),
            items: Vec::new(),
            shapes: Vec::new(),
            gravity: desc.model.gravity,
        };
        for b in &desc.bodies {
            // The pose as the description gives it or computes it (`between`); a body the
            // reader refuses is drawn from its given fields (the run reports the error).
            let (position, angle) = match b.resolve() {
                Ok(r) => (r.position, r.angle),
                Err(_) => (b.position, b.angle),
            };
            s.parts.push(Part {
                name: b.name.clone(),
                kind: "rigid",
                com: b.centre_of_mass,
                pose0: [
                    position.map_or(0.0, |p| p[0]),
                    position.map_or(0.0, |p| p[1]),
                    angle.unwrap_or(0.0),
                ],
                points: vec![b.centre_of_mass],
            });
        }
        for b in &desc.beams {
            s.beams.push(Beam {
                name: b.name.clone(),
                part: -1,
                nodes: mesh(b.start, b.end, b.elements),
                depth: depth(&b.section),
            });
        }
        for f in &desc.flexible_bodies {
            s.parts.push(Part {
                name: f.name.clone(),
                kind: "flexible",
                com: [0.0, 0.0],
                pose0: f.pose.unwrap_or_default(),
                points: Vec::new(),
            });
            s.beams.push(Beam {
                name: f.name.clone(),
                part: (s.parts.len() - 1) as i64,
                nodes: mesh(f.beam.start, f.beam.end, f.beam.elements),
                depth: depth(&f.beam.section),
            });
        }
        let points: BTreeMap<String, Value> = desc
            .points
            .iter()
            .filter_map(|p| Some((p.name.clone(), serde_json::to_value(p).ok()?)))
            .collect();
        for shape in &desc.shapes {
            if let Some(item) = s.shape(shape, &points) {
                // the part's outline reaches the shape (a stop tab at a flap's tip); the
                // ground gets no symbol under a shape
                if let Some(At::Part { part, at }) = item.at {
                    if part >= 0 {
                        s.parts[part as usize].points.push(at);
                    }
                }
                s.shapes.push(item);
            }
        }
        let sections: [(&'static str, Vec<Value>); 4] = [
            ("joint", values(&desc.joints)),
            ("driver", values(&desc.drivers)),
            ("force", values(&desc.forces)),
            ("clearance", values(&desc.clearances)),
        ];
        for (section, items) in sections {
            for v in items {
                if let Some(item) = s.item(section, &v, &points) {
                    s.items.push(item);
                }
            }
        }
        s
    }

    /// Part index of a body name (`-1` for the ground).
    fn part(&self, name: &str) -> Option<i64> {
        if name == "ground" {
            return Some(-1);
        }
        self.parts
            .iter()
            .position(|p| p.name == name)
            .map(|i| i as i64)
    }

    fn beam(&self, name: &str) -> Option<usize> {
        self.beams.iter().position(|b| b.name == name)
    }

    /// Resolve an anchor value.
    fn resolve(&self, v: &Value, points: &BTreeMap<String, Value>) -> Option<At> {
        match v {
            Value::String(p) => self.resolve(points.get(p)?, points),
            Value::Object(o) => {
                if let (Some(beam), Some(node)) = (o.get("beam"), o.get("node")) {
                    let beam = self.beam(beam.as_str()?)?;
                    return Some(At::Node {
                        beam,
                        node: node.as_u64()? as usize,
                    });
                }
                let part = self.part(o.get("body")?.as_str()?)?;
                let at = o
                    .get("at")
                    .and_then(|a| Some([a.get(0)?.as_f64()?, a.get(1)?.as_f64()?]));
                Some(At::Part {
                    part,
                    at: at.unwrap_or([0.0, 0.0]),
                })
            }
            _ => None,
        }
    }

    /// Resolve an anchor value and remember the point on its part's outline (or as a ground
    /// point).
    fn anchor(&mut self, v: &Value, points: &BTreeMap<String, Value>) -> Option<At> {
        let at = self.resolve(v, points)?;
        if let At::Part { part, at: local } = at {
            if part < 0 {
                self.ground.push(local);
            } else {
                self.parts[part as usize].points.push(local);
            }
        }
        Some(at)
    }

    /// The drawing of a shape: its frame resolved and its outline. A beam face has no
    /// frame nor outline of its own (its beam is drawn). A shape whose anchor names nothing
    /// known or whose rigid geometry clr-contact refuses (the description was checked, so only
    /// by a bug) is left out.
    fn shape(&self, d: &ShapeDesc, points: &BTreeMap<String, Value>) -> Option<ShapeItem> {
        let kind = serde_json::to_value(&d.geometry)
            .ok()
            .and_then(|g| Some(g.get("type")?.as_str()?.to_string()))
            .unwrap_or_default();
        let at = match &d.at {
            Some(a) => Some(self.resolve(&serde_json::to_value(a).ok()?, points)?),
            None => None,
        };
        let outlines = if kind == "beam_face" {
            Vec::new()
        } else {
            thin(outlines(&d.geometry.to_shape().ok()?), MAX_SHAPE_POINTS)
        };
        Some(ShapeItem {
            name: d.name.clone(),
            at,
            angle: d.angle,
            kind,
            outlines,
        })
    }

    fn item(
        &mut self,
        section: &'static str,
        v: &Value,
        points: &BTreeMap<String, Value>,
    ) -> Option<Item> {
        let o = v.as_object()?;
        let mut item = Item {
            section,
            kind: o.get("type")?.as_str()?.to_string(),
            name: o.get("name")?.as_str()?.to_string(),
            anchors: BTreeMap::new(),
            bodies: BTreeMap::new(),
            params: BTreeMap::new(),
            shapes: Vec::new(),
        };
        for (k, f) in o {
            if k == "shapes" {
                if let Some(names) = f.as_array() {
                    item.shapes = names
                        .iter()
                        .filter_map(|n| {
                            let n = n.as_str()?;
                            self.shapes.iter().position(|s| s.name == n)
                        })
                        .collect();
                    continue;
                }
            }
            if ANCHOR_FIELDS.contains(&k.as_str())
                && !(section == "force" && k == "at" && f.is_array())
            {
                if let Some(at) = self.anchor(f, points) {
                    item.anchors.insert(k.clone(), at);
                    continue;
                }
            }
            if BODY_FIELDS.contains(&k.as_str()) {
                if let Some(name) = f.as_str() {
                    let idx = if k == "beam" {
                        self.beam(name).map(|b| b as i64)
                    } else {
                        self.part(name)
                    };
                    if let Some(i) = idx {
                        item.bodies.insert(k.clone(), i);
                    }
                    continue;
                }
            }
            let numeric = f.is_number()
                || f.as_array()
                    .is_some_and(|a| a.len() == 2 && a.iter().all(Value::is_number));
            if numeric || k == "face" {
                item.params.insert(k.clone(), f.clone());
            }
        }
        Some(item)
    }
}

fn values<T: Serialize>(items: &[T]) -> Vec<Value> {
    items
        .iter()
        .filter_map(|i| serde_json::to_value(i).ok())
        .collect()
}

/// `n` points on the arc of radius `r` about `c` from angle `a0` to `a1` (rad), both ends
/// included.
fn arc(c: [f64; 2], r: f64, a0: f64, a1: f64, n: usize) -> Vec<[f64; 2]> {
    let n = n.max(2);
    (0..n)
        .map(|k| {
            let a = a0 + (a1 - a0) * k as f64 / (n - 1) as f64;
            [c[0] + r * a.cos(), c[1] + r * a.sin()]
        })
        .collect()
}

/// The point `p` of a part placed at `pose` [x, y, θ] (m, m, rad).
fn place(pose: [f64; 3], p: [f64; 2]) -> [f64; 2] {
    let (s, c) = pose[2].sin_cos();
    [pose[0] + c * p[0] - s * p[1], pose[1] + s * p[0] + c * p[1]]
}

/// The outline of a clr-contact shape in its own frame (m).
pub fn outlines(shape: &Shape) -> Vec<Outline> {
    let closed = |points| Outline {
        points,
        closed: true,
    };
    match shape {
        Shape::Ball { radius } => {
            let step = std::f64::consts::TAU / CIRCLE_POINTS as f64;
            vec![closed(
                (0..CIRCLE_POINTS)
                    .map(|k| {
                        let a = step * k as f64;
                        [radius * a.cos(), radius * a.sin()]
                    })
                    .collect(),
            )]
        }
        Shape::Capsule {
            half_length,
            radius,
        } => {
            // two half circles of CIRCLE_POINTS/2 + 1 points, counter-clockwise from the
            // lower right
            let half = std::f64::consts::FRAC_PI_2;
            let n = CIRCLE_POINTS / 2 + 1;
            let mut pts = arc([*half_length, 0.0], *radius, -half, half, n);
            pts.extend(arc([-half_length, 0.0], *radius, half, 3.0 * half, n));
            vec![closed(pts)]
        }
        Shape::Cuboid {
            half_extents: [hx, hy],
        } => {
            vec![closed(vec![[-hx, -hy], [*hx, -hy], [*hx, *hy], [-hx, *hy]])]
        }
        Shape::ConvexPolygon { points } => vec![closed(points.clone())],
        Shape::Polyline { points } => vec![Outline {
            points: points.clone(),
            closed: false,
        }],
        Shape::Compound { parts } => {
            let placed: Vec<(Shape, Vec<Outline>)> = parts
                .iter()
                .map(|(pose, part)| {
                    let o = outlines(part)
                        .into_iter()
                        .map(|o| Outline {
                            points: o.points.iter().map(|&p| place(*pose, p)).collect(),
                            closed: o.closed,
                        })
                        .collect();
                    (part.clone(), o)
                })
                .collect();
            let merged = disc_union(parts, &placed);
            merged.unwrap_or_else(|| placed.into_iter().flat_map(|(_, o)| o).collect())
        }
    }
}

/// The one outline of a compound made of a disc and convex polygons that each cross its circle
/// once (the outside vertices of each polygon are one run), with the polygons' outside parts
/// apart from each other around the circle: an involute gear's core and teeth, a disc with a
/// handle. Counter-clockwise: each polygon's outside run from where it leaves the circle to
/// where it enters again, joined by arcs of the circle. None for any other compound (polygons
/// inside the disc are dropped: they do not show).
fn disc_union(
    parts: &[([f64; 3], Shape)],
    placed: &[(Shape, Vec<Outline>)],
) -> Option<Vec<Outline>> {
    use std::f64::consts::TAU;
    let mut discs = parts.iter().filter_map(|(pose, s)| match s {
        Shape::Ball { radius } => Some(([pose[0], pose[1]], *radius)),
        _ => None,
    });
    let (c, r) = discs.next()?;
    if discs.next().is_some() {
        return None;
    }
    let rel = |p: [f64; 2]| [p[0] - c[0], p[1] - c[1]];
    let angle = |p: [f64; 2]| {
        let d = rel(p);
        d[1].atan2(d[0])
    };
    let outside = |p: [f64; 2]| {
        let d = rel(p);
        d[0].hypot(d[1]) > r
    };
    // where the segment from p (inside) to q (outside) crosses the circle
    let cross = |p: [f64; 2], q: [f64; 2]| {
        let (a, b) = (rel(p), [q[0] - p[0], q[1] - p[1]]);
        let bb = b[0] * b[0] + b[1] * b[1];
        let ab = a[0] * b[0] + a[1] * b[1];
        let aa = a[0] * a[0] + a[1] * a[1];
        let s = (-ab + (ab * ab - bb * (aa - r * r)).max(0.0).sqrt()) / bb;
        [p[0] + s * b[0], p[1] + s * b[1]]
    };
    // (angle where the run leaves the circle, its angular span, the run from exit to entry)
    let mut runs: Vec<(f64, f64, Vec<[f64; 2]>)> = Vec::new();
    for (shape, outline) in placed {
        match shape {
            Shape::Ball { .. } => continue,
            Shape::Cuboid { .. } | Shape::ConvexPolygon { .. } => {}
            _ => return None,
        }
        let pts = &outline.first()?.points;
        let n = pts.len();
        let out: Vec<bool> = pts.iter().map(|&p| outside(p)).collect();
        let starts: Vec<usize> = (0..n)
            .filter(|&i| out[i] && !out[(i + n - 1) % n])
            .collect();
        if out.iter().all(|o| !o) {
            continue;
        }
        if starts.len() != 1 {
            return None;
        }
        let first = starts[0];
        let len = (0..n).take_while(|k| out[(first + k) % n]).count();
        let last = (first + len - 1) % n;
        let mut run = vec![cross(pts[(first + n - 1) % n], pts[first])];
        run.extend((0..len).map(|k| pts[(first + k) % n]));
        run.push(cross(pts[(last + 1) % n], pts[last]));
        // counter-clockwise: every point lies within the span from the first to the last
        let a0 = angle(run[0]);
        let span = (angle(run[run.len() - 1]) - a0).rem_euclid(TAU);
        let within = run.iter().all(|&p| {
            let d = (angle(p) - a0).rem_euclid(TAU);
            d <= span + 1e-9 || d >= TAU - 1e-9
        });
        if !(span > 0.0 && span < std::f64::consts::PI && within) {
            return None;
        }
        runs.push((a0, span, run));
    }
    runs.sort_by(|a, b| a.0.total_cmp(&b.0));
    if runs.is_empty() {
        return None;
    }
    let step = TAU / CIRCLE_POINTS as f64;
    let mut pts = Vec::new();
    for (k, (a0, span, run)) in runs.iter().enumerate() {
        // the next run's start, unwrapped past this one's (the first again, one turn on)
        let next = runs.get(k + 1).map_or(runs[0].0 + TAU, |n| n.0);
        let gap = next - (a0 + span);
        if gap < 0.0 {
            // the next run starts before this one ends: they overlap
            return None;
        }
        pts.extend(run.iter().copied());
        let between = (gap / step).ceil() as usize;
        let a1 = a0 + span;
        pts.extend((1..between).map(|i| {
            let a = a1 + gap * i as f64 / between as f64;
            [c[0] + r * a.cos(), c[1] + r * a.sin()]
        }));
    }
    Some(vec![Outline {
        points: pts,
        closed: true,
    }])
}

/// Outlines with at most about `max` points in all: each outline longer than its share keeps
/// evenly spaced points (an open one its two ends), none fewer than 4 (or all it has).
pub fn thin(outlines: Vec<Outline>, max: usize) -> Vec<Outline> {
    let total: usize = outlines.iter().map(|o| o.points.len()).sum();
    if total <= max {
        return outlines;
    }
    outlines
        .into_iter()
        .map(|o| {
            let len = o.points.len();
            let keep = (len * max / total).max(len.min(4));
            if keep >= len {
                return o;
            }
            let points = (0..keep)
                .map(|i| {
                    let j = if o.closed {
                        i * len / keep
                    } else {
                        (i * (len - 1) + (keep - 1) / 2) / (keep - 1)
                    };
                    o.points[j]
                })
                .collect();
            Outline {
                points,
                closed: o.closed,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_outlines_are_thinned_evenly_keeping_the_ends_of_open_ones() {
        let line: Vec<[f64; 2]> = (0..5000).map(|k| [k as f64, 0.0]).collect();
        let square = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let out = thin(
            vec![
                Outline {
                    points: line,
                    closed: false,
                },
                Outline {
                    points: square.clone(),
                    closed: true,
                },
            ],
            2000,
        );
        let pts = &out[0].points;
        assert!(pts.len() <= 2000, "{}", pts.len());
        assert_eq!((pts[0], pts[pts.len() - 1]), ([0.0, 0.0], [4999.0, 0.0]));
        assert!(pts
            .windows(2)
            .all(|w| (2.0..=3.0).contains(&(w[1][0] - w[0][0]))));
        assert_eq!(out[1].points, square, "a short outline is kept whole");
    }

    #[test]
    fn a_compound_that_is_no_disc_with_teeth_keeps_one_outline_per_part() {
        // a housing of four overlapping walls, and a disc crossed right through by a bar
        let wall = |x: f64, y: f64, hx: f64, hy: f64| {
            (
                [x, y, 0.0],
                Shape::Cuboid {
                    half_extents: [hx, hy],
                },
            )
        };
        let housing = Shape::Compound {
            parts: vec![
                wall(0.0, -0.05, 0.1, 0.01),
                wall(0.0, 0.05, 0.1, 0.01),
                wall(-0.1, 0.0, 0.01, 0.06),
                wall(0.1, 0.0, 0.01, 0.06),
            ],
        };
        assert_eq!(outlines(&housing).len(), 4);
        let crossed = Shape::Compound {
            parts: vec![
                ([0.0; 3], Shape::Ball { radius: 0.01 }),
                wall(0.0, 0.0, 0.03, 0.002),
            ],
        };
        assert_eq!(outlines(&crossed).len(), 2);
        // a handle that leaves the disc once: one outline, the disc's arc and the handle's end
        let handle = Shape::Compound {
            parts: vec![
                ([0.0; 3], Shape::Ball { radius: 0.01 }),
                wall(0.015, 0.0, 0.01, 0.002),
            ],
        };
        let one = outlines(&handle);
        assert_eq!(one.len(), 1);
        assert!(one[0].points.contains(&[0.025, 0.002]));
        for p in &one[0].points {
            let r = p[0].hypot(p[1]);
            assert!(p[0] > 0.0099 || (r - 0.01).abs() < 1e-15, "{p:?}");
        }
    }
}
