//! The drawing of a mechanism, from its plain description (`clr_mbd::ModelDesc`): the parts
//! (rigid bodies and the floating frames of flexible bodies) with the points where elements
//! attach, the beams with their undeformed nodes, and every element with its anchors resolved
//! to a part or a beam node. Element kinds are read generically through their serde form, so a
//! new kind is drawn (as links between its anchors) without a change here; the renderer
//! (`assets/report.js`) gives the known kinds their own symbols.

use std::collections::BTreeMap;

use clr_mbd::desc::SectionDesc;
use clr_mbd::ModelDesc;
use serde::Serialize;
use serde_json::Value;

/// Fields of an element that hold an anchor (a point name, `{body, at}` or `{beam, node}`).
const ANCHOR_FIELDS: &[&str] = &["a", "b", "at", "bearing", "journal", "guide", "slider"];
/// Fields of an element that name a body.
const BODY_FIELDS: &[&str] = &["body", "body_i", "body_j", "beam"];

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
    /// Every point where something attaches, in the part frame (m): the outline is drawn
    /// through them.
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
}

/// The drawable mechanism.
#[derive(Debug, Clone, Serialize)]
pub struct Scene {
    /// Moving frames.
    pub parts: Vec<Part>,
    /// Ground points where something attaches (world, m).
    pub ground: Vec<[f64; 2]>,
    /// Beams.
    pub beams: Vec<Beam>,
    /// Joints, drivers, forces and clearances.
    pub items: Vec<Item>,
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
            gravity: desc.model.gravity,
        };
        for b in &desc.bodies {
            s.parts.push(Part {
                name: b.name.clone(),
                kind: "rigid",
                com: b.centre_of_mass,
                pose0: [
                    b.position.map_or(0.0, |p| p[0]),
                    b.position.map_or(0.0, |p| p[1]),
                    b.angle.unwrap_or(0.0),
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
                pose0: f.pose,
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

    /// Resolve an anchor value (and remember the point on its part's outline).
    fn anchor(&mut self, v: &Value, points: &BTreeMap<String, Value>) -> Option<At> {
        match v {
            Value::String(p) => {
                let p = points.get(p)?.clone();
                self.anchor(&p, points)
            }
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
                let at = at.unwrap_or([0.0, 0.0]);
                if part < 0 {
                    self.ground.push(at);
                } else {
                    self.parts[part as usize].points.push(at);
                }
                Some(At::Part { part, at })
            }
            _ => None,
        }
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
        };
        for (k, f) in o {
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
