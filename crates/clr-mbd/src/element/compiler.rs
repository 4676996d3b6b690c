//! The compile context: resolves names (bodies, points, beam nodes) into frames and coordinate
//! columns, and collects each element's runtime form. Elements call [`Compiler::anchor`],
//! [`Compiler::body`] and push their runtime forms; [`compile`] drives the sections in order.

use std::collections::HashMap;

use clr_contact::{ContactMemory, ForceApplication};
use nalgebra::Vector2;

use super::anchor::Anchor;
use super::floating_body::FlexibleBody;
use super::ground_beam::GroundBeam;
use crate::beam_face::GuideBeam;
use crate::clearance::Clearance;
use crate::desc::parts::{Body, ForceApplicationDesc, ModelInfo, Point};
use crate::error::MbdError;
use crate::flexible::FlexBeam;
use crate::floating::FloatingBody;
use crate::runtime::{Con, ConKind, ForceEl, Frame, RigidBody, GROUND, GROUND_ID};
use crate::system::{ContactReport, Model, DEFAULT_BAUMGARTE_ALPHA, DEFAULT_BAUMGARTE_BETA};
use crate::timefn::TimeFn;

/// Everything resolved so far, and the runtime forms collected from the elements.
pub(crate) struct Compiler {
    pub(crate) bodies: Vec<(String, RigidBody)>,
    /// Which coordinates (x, y, θ, v_x, v_y, ω) of each rigid body the description fixes.
    fixed: Vec<[bool; 6]>,
    /// Centre of mass of each rigid body in its drawing frame (subtracted from local anchors).
    com: Vec<Vector2<f64>>,
    body_ids: HashMap<String, usize>,
    known: String,
    pub(crate) floating: Vec<FloatingBody>,
    pub(crate) beams: Vec<FlexBeam>,
    pub(crate) frames: Vec<Frame>,
    points: HashMap<String, (usize, Vector2<f64>)>,
    pub(crate) point_list: Vec<(String, usize, Vector2<f64>)>,
    node_points: HashMap<String, usize>,
    float_points: HashMap<String, (usize, Vector2<f64>)>,
    float_nodes: HashMap<(String, usize), (usize, Vector2<f64>)>,
    node_frames: HashMap<(String, usize), usize>,
    ties: Vec<(usize, usize, usize)>,
    /// Next free column of q.
    offset: usize,
    pub(crate) cons: Vec<Con>,
    pub(crate) motions: Vec<TimeFn>,
    pub(crate) forces: Vec<ForceEl>,
    pub(crate) clearances: Vec<Clearance>,
    pub(crate) force_application: ForceApplication,
    /// `[[shape]]` items by name.
    pub(crate) shapes: HashMap<String, crate::element::shape::Placed>,
    /// Initial offsets of contact elements given in the description, by element name (see
    /// [`crate::ideal`]).
    pub(crate) initial_offsets: HashMap<String, Vector2<f64>>,
    /// What compiling computed or decided from the description, in words (mass properties of
    /// shapes, placements from `between`, clearance joints of clearance 0 run as ideal joints),
    /// for the run's notes.
    pub(crate) notes: Vec<String>,
    /// `[[measure]]` items compiled so far.
    pub(crate) measures: Vec<crate::measure::runtime::CompiledMeasure>,
}

/// What the compiler needs of a description before its element sections: `[model]`, bodies,
/// points, beams, floating bodies, and the anchors of every element (beam-node anchors get
/// their node frames first).
pub(crate) struct Inputs<'a> {
    pub(crate) model: &'a ModelInfo,
    pub(crate) bodies: &'a [Body],
    pub(crate) points: &'a [Point],
    pub(crate) beams: &'a [GroundBeam],
    pub(crate) flexible_bodies: &'a [FlexibleBody],
    /// (element name, its anchors) for every element of every section.
    pub(crate) anchors: Vec<(&'a str, Vec<&'a Anchor>)>,
}

impl Compiler {
    /// Bodies, flexible bodies, beams, points and the node frames every anchor needs.
    pub(crate) fn new(desc: &Inputs) -> Result<Self, MbdError> {
        let mut c = Compiler {
            bodies: Vec::new(),
            fixed: Vec::new(),
            com: Vec::new(),
            body_ids: HashMap::new(),
            known: desc
                .bodies
                .iter()
                .map(|b| b.name.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            floating: Vec::new(),
            beams: Vec::new(),
            frames: Vec::new(),
            points: HashMap::new(),
            point_list: Vec::new(),
            node_points: HashMap::new(),
            float_points: HashMap::new(),
            float_nodes: HashMap::new(),
            node_frames: HashMap::new(),
            ties: Vec::new(),
            offset: 0,
            cons: Vec::new(),
            motions: Vec::new(),
            forces: Vec::new(),
            clearances: Vec::new(),
            shapes: HashMap::new(),
            initial_offsets: HashMap::new(),
            notes: Vec::new(),
            measures: Vec::new(),
            force_application: match desc.model.clearance_force_application {
                Some(ForceApplicationDesc::ContactPoints) => ForceApplication::ContactPoints,
                _ => ForceApplication::CommonPoint,
            },
        };
        for (k, b) in desc.bodies.iter().enumerate() {
            let (rb, com, note) = crate::element::body::compile(b)?;
            c.notes.extend(note);
            c.body_ids.insert(b.name.clone(), k);
            c.bodies.push((b.name.clone(), rb));
            c.fixed.push(b.fixed_coordinates());
            c.com.push(com);
        }
        // floating bodies: frame index after the rigid bodies, coordinates before the beams
        c.offset = 3 * c.bodies.len();
        for (k, f) in desc.flexible_bodies.iter().enumerate() {
            let mut fb = f.compile(&format!("flexible_body[{k}]"))?;
            fb.offset = c.offset;
            c.offset += fb.n_coords();
            c.body_ids
                .insert(f.name.clone(), c.bodies.len() + c.floating.len());
            c.floating.push(fb);
        }
        for (k, b) in desc.beams.iter().enumerate() {
            let mut fb = b.compile(&format!("beam[{k}]"))?;
            fb.offset = c.offset;
            c.offset += fb.n_free();
            c.beams.push(fb);
        }
        c.frames = (0..c.bodies.len()).map(Frame::rigid).collect();
        let floating_frames: Vec<Frame> = c
            .floating
            .iter()
            .map(|f| Frame {
                cols: [Some(f.offset), Some(f.offset + 1), Some(f.offset + 2)],
                base: Vector2::zeros(),
            })
            .collect();
        c.frames.extend(floating_frames);
        c.body_points(desc)?;
        c.node_frames_of(desc)?;
        Ok(c)
    }

    fn body_points(&mut self, desc: &Inputs) -> Result<(), MbdError> {
        for p in desc.points {
            if p.beam.is_some() || p.node.is_some() {
                if p.body.is_some() || p.at.is_some() {
                    return Err(MbdError::InvalidParameter {
                        item: p.name.clone(),
                        what: "point placement",
                        value: f64::NAN,
                        requirement: "a point is on a body (`body`, `at`) or on a beam node \
                                      (`beam`, `node`), not both",
                    });
                }
                continue;
            }
            let body = p
                .body
                .as_deref()
                .ok_or_else(|| MbdError::InvalidParameter {
                    item: p.name.clone(),
                    what: "point body",
                    value: f64::NAN,
                    requirement: "give `body` and `at` (or `beam` and `node`)",
                })?;
            let at = p.at.unwrap_or([0.0, 0.0]);
            let (id, s) = self.local(&format!("{}.body", p.name), body, at)?;
            self.points.insert(p.name.clone(), (id, s));
            self.point_list.push((p.name.clone(), id, s));
        }
        Ok(())
    }

    /// Node frames for beam points and beam-node anchors, in definition order.
    fn node_frames_of(&mut self, desc: &Inputs) -> Result<(), MbdError> {
        let mut wanted: Vec<(String, String, usize, Option<String>)> = Vec::new();
        for p in desc.points {
            if let (Some(b), Some(n)) = (&p.beam, p.node) {
                wanted.push((p.name.clone(), b.clone(), n, Some(p.name.clone())));
            } else if p.beam.is_some() || p.node.is_some() {
                return Err(MbdError::InvalidParameter {
                    item: p.name.clone(),
                    what: "beam node point",
                    value: f64::NAN,
                    requirement: "give both `beam` and `node`",
                });
            }
        }
        let anchors = desc.anchors.iter().map(|(n, l)| (*n, l.clone()));
        for (name, list) in anchors {
            for a in list {
                if let Anchor::BeamNode(beam, node) = a {
                    wanted.push((name.to_string(), beam.clone(), *node, None));
                }
            }
        }
        for (name, beam, node, point) in &wanted {
            if let Some(f) = self.floating.iter().position(|f| &f.name == beam) {
                self.floating_node(name, f, beam, *node, point)?;
            } else {
                self.beam_node(name, beam, *node, point)?;
            }
        }
        Ok(())
    }

    fn floating_node(
        &mut self,
        name: &str,
        f: usize,
        beam: &str,
        node: usize,
        point: &Option<String>,
    ) -> Result<(), MbdError> {
        let nb = self.bodies.len();
        if node >= self.floating[f].nodes.len() {
            return Err(MbdError::InvalidParameter {
                item: name.to_string(),
                what: "floating-body node index",
                value: node as f64,
                requirement: "must be a node of the floating body's beam model",
            });
        }
        let key = (beam.to_string(), node);
        let a = if let Some(&a) = self.float_nodes.get(&key) {
            a
        } else if self.floating[f].is_reference_node(node) {
            let p = self.floating[f].nodes[node];
            (nb + f, Vector2::new(p[0], p[1]))
        } else {
            // a deforming node: its own frame coordinates tied to the body (3 rows)
            let col = self.offset;
            self.frames.push(Frame {
                cols: [Some(col), Some(col + 1), Some(col + 2)],
                base: Vector2::zeros(),
            });
            let j = self.frames.len() - 1;
            self.cons.push(Con {
                name: format!("{beam}.node{node}"),
                kind: ConKind::FloatNode {
                    f,
                    node,
                    col,
                    i: nb + f,
                    j,
                },
                row: 0,
            });
            self.ties.push((f, node, col));
            self.offset += 3;
            (j, Vector2::zeros())
        };
        self.float_nodes.insert(key, a);
        if let Some(p) = point {
            self.float_points.insert(p.clone(), a);
        }
        Ok(())
    }

    fn beam_node(
        &mut self,
        name: &str,
        beam: &str,
        node: usize,
        point: &Option<String>,
    ) -> Result<(), MbdError> {
        let key = (beam.to_string(), node);
        if let Some(&k) = self.node_frames.get(&key) {
            if let Some(p) = point {
                self.node_points.insert(p.clone(), k);
            }
            return Ok(());
        }
        let Some(fb) = self.beams.iter().find(|b| b.name == beam) else {
            let known: Vec<&str> = (self.beams.iter().map(|b| b.name.as_str()))
                .chain(self.floating.iter().map(|f| f.name.as_str()))
                .collect();
            return Err(MbdError::UnknownBody {
                item: name.to_string(),
                body: beam.to_string(),
                known: known.join(", "),
            });
        };
        if node >= fb.nodes.len() {
            return Err(MbdError::InvalidParameter {
                item: name.to_string(),
                what: "beam node index",
                value: node as f64,
                requirement: "must be a node of the beam model",
            });
        }
        let cols = [0, 1, 2].map(|c| {
            fb.free
                .iter()
                .position(|&d| d == 3 * node + c)
                .map(|k| fb.offset + k)
        });
        let p = fb.nodes[node];
        self.frames.push(Frame {
            cols,
            base: Vector2::new(p[0], p[1]),
        });
        self.node_frames.insert(key, self.frames.len() - 1);
        if let Some(p) = point {
            self.node_points.insert(p.clone(), self.frames.len() - 1);
        }
        Ok(())
    }

    /// The runtime model from everything compiled: floating bodies get their node ties,
    /// constraints their rows, contacts their memory slots, and the model its preallocated
    /// workspace.
    pub(crate) fn finish(mut self, gravity: Vector2<f64>) -> Result<Model, MbdError> {
        for (f, node, col) in std::mem::take(&mut self.ties) {
            self.floating[f].ties.push((node, col));
        }
        for b in self.beams.iter_mut() {
            b.set_gravity([gravity.x, gravity.y]);
        }
        let Compiler {
            bodies,
            fixed,
            beams,
            floating,
            frames,
            point_list: points,
            mut cons,
            motions,
            forces,
            mut clearances,
            initial_offsets,
            notes,
            measures,
            ..
        } = self;
        let mut m = 0;
        for c in cons.iter_mut() {
            c.row = m;
            m += c.rows();
        }
        let n = 3 * bodies.len()
            + beams.iter().map(FlexBeam::n_free).sum::<usize>()
            + floating
                .iter()
                .map(|f| f.n_coords() + 3 * f.ties.len())
                .sum::<usize>();
        if n == 0 {
            return Err(MbdError::InvalidParameter {
                item: "model".into(),
                what: "number of bodies",
                value: 0.0,
                requirement: "define at least one rigid body or flexible beam",
            });
        }
        let mut mem = 0;
        for c in clearances.iter_mut() {
            c.mem = mem;
            mem += c.points();
        }
        let min_v = clearances
            .iter()
            .map(|c| c.normal.min_impact_velocity())
            .fold(
                clr_contact::NormalLaw::DEFAULT_MIN_IMPACT_VELOCITY,
                f64::min,
            );
        let memory = ContactMemory::new(mem, min_v).map_err(|source| MbdError::Contact {
            item: "contact memory".into(),
            source,
        })?;
        let g = crate::linsys::Factorization {
            sparse: crate::LinearSolver::Auto.is_sparse(n + m),
            ..Default::default()
        };
        let (body_names, bodies): (Vec<_>, Vec<_>) = bodies.into_iter().unzip();
        let nc = clearances.len();
        let bristles = crate::lugre::assign_bristles(&mut clearances);
        let broad = crate::broad_phase::BroadPhase::new(&clearances);
        Ok(Model {
            body_names,
            bodies,
            fixed,
            beams,
            floating,
            node_outputs: Vec::new(),
            frames,
            points,
            cons,
            motions,
            forces,
            clearances,
            initial_offsets,
            notes,
            measures,
            input_warnings: Vec::new(),
            inputs: crate::input::InputBank::default(),
            feedback: crate::input::Feedback::default(),
            gravity,
            memory,
            alpha: DEFAULT_BAUMGARTE_ALPHA,
            beta: DEFAULT_BAUMGARTE_BETA,
            events_on: true,
            n,
            m,
            g,
            range_space: Default::default(),
            phi: vec![0.0; m],
            phiq: vec![0.0; m * n],
            phid: vec![0.0; m],
            phit: vec![0.0; m],
            gamma: vec![0.0; m],
            qf: vec![0.0; n],
            sol: vec![0.0; n + m],
            contacts: vec![ContactReport::default(); nc],
            broad,
            solve_ok: true,
            p_diss: 0.0,
            p_loads: 0.0,
            bristles,
        })
    }

    /// Number of rigid bodies.
    pub(crate) fn n_rigid(&self) -> usize {
        self.bodies.len()
    }

    /// Frame index of a body (rigid or floating) by name; the ground is [`GROUND_ID`]. `field`
    /// is the item's field that names it (`body_i`), for the error's path.
    pub(crate) fn body(&self, item: &str, field: &str, name: &str) -> Result<usize, MbdError> {
        self.body_at(&format!("{item}.{field}"), name)
    }

    /// [`Compiler::body`] with the field's whole path (`crank_drive.body`).
    fn body_at(&self, path: &str, name: &str) -> Result<usize, MbdError> {
        if name == GROUND {
            return Ok(GROUND_ID);
        }
        self.body_ids
            .get(name)
            .copied()
            .ok_or_else(|| MbdError::UnknownBody {
                item: path.to_string(),
                body: name.to_string(),
                known: self.known.clone(),
            })
    }

    /// A body-local point in the body's drawing frame → (frame, arm from the centre of mass);
    /// `path` is the field naming the body (`pin.b.body`).
    fn local(
        &self,
        path: &str,
        body: &str,
        l: [f64; 2],
    ) -> Result<(usize, Vector2<f64>), MbdError> {
        if !(l[0].is_finite() && l[1].is_finite()) {
            return Err(MbdError::InvalidParameter {
                item: path.trim_end_matches(".body").to_string(),
                what: "local anchor coordinates (m)",
                value: if l[0].is_finite() { l[1] } else { l[0] },
                requirement: "must be finite",
            });
        }
        let id = self.body_at(path, body)?;
        let com = self.com.get(id).copied().unwrap_or_else(Vector2::zeros);
        Ok((id, Vector2::new(l[0], l[1]) - com))
    }

    /// Resolve an anchor into (frame index, local arm in m from the frame's reference point).
    /// `field` is the item's field holding the anchor (`bearing`), for the error's path.
    pub(crate) fn anchor(
        &self,
        item: &str,
        field: &str,
        a: &Anchor,
    ) -> Result<(usize, Vector2<f64>), MbdError> {
        let path = format!("{item}.{field}");
        match a {
            Anchor::Point(p) => {
                if let Some(&k) = self.node_points.get(p) {
                    return Ok((k, Vector2::zeros()));
                }
                if let Some(&a) = self.float_points.get(p) {
                    return Ok(a);
                }
                self.points
                    .get(p)
                    .copied()
                    .ok_or_else(|| MbdError::UnknownPoint {
                        item: path,
                        point: p.clone(),
                        known: self.point_names(),
                    })
            }
            Anchor::Local(b, l) => self.local(&format!("{path}.body"), b, *l),
            Anchor::BeamNode(b, k) => {
                if let Some(&a) = self.float_nodes.get(&(b.clone(), *k)) {
                    return Ok(a);
                }
                self.node_frames
                    .get(&(b.clone(), *k))
                    .map(|&f| (f, Vector2::zeros()))
                    .ok_or_else(|| MbdError::UnknownBody {
                        item: format!("{path}.beam"),
                        body: b.clone(),
                        known: self.known.clone(),
                    })
            }
        }
    }

    /// A flexible beam by name (a `[[beam]]` or a `[[flexible_body]]`) for an element running on
    /// its face: (which beam, the frame its face moves with — the ground or the floating body —,
    /// its element path, the length of its full-DOF vector). `path` names the field, for errors.
    pub(crate) fn flexible_face(
        &self,
        path: &str,
        beam: &str,
    ) -> Result<(GuideBeam, usize, clr_beam::Path, usize), MbdError> {
        let nb = self.n_rigid();
        let found = match self.beams.iter().position(|fb| fb.name == beam) {
            Some(b) => Some((
                GuideBeam::Fixed(b),
                GROUND_ID,
                self.beams[b].path.clone(),
                self.beams[b].n_dof_full,
            )),
            None => self.floating.iter().position(|f| f.name == beam).map(|f| {
                (
                    GuideBeam::Floating(f),
                    nb + f,
                    self.floating[f].path.clone(),
                    3 * self.floating[f].nodes.len(),
                )
            }),
        };
        let Some((which, frame, p, nfull)) = found else {
            let known: Vec<&str> = (self.beams.iter().map(|b| b.name.as_str()))
                .chain(self.floating.iter().map(|f| f.name.as_str()))
                .collect();
            return Err(MbdError::UnknownBody {
                item: path.to_string(),
                body: beam.to_string(),
                known: known.join(", "),
            });
        };
        let Some(p) = p else {
            return Err(MbdError::Invalid {
                path: path.to_string(),
                message: format!(
                    "the elements of beam `{beam}` must form one chain (as a straight mesh does)"
                ),
            });
        };
        Ok((which, frame, p, nfull))
    }

    /// Every `[[shape]]` name, comma-separated (for messages).
    pub(crate) fn shape_names(&self) -> String {
        let mut all: Vec<&str> = self.shapes.keys().map(String::as_str).collect();
        all.sort_unstable();
        all.join(", ")
    }

    /// Every named point, comma-separated (for messages).
    fn point_names(&self) -> String {
        let mut all: Vec<&str> = self
            .points
            .keys()
            .chain(self.node_points.keys())
            .chain(self.float_points.keys())
            .map(String::as_str)
            .collect();
        all.sort_unstable();
        all.join(", ")
    }

    /// Error when an element connects a frame to itself.
    pub(crate) fn distinct(&self, item: &str, i: usize, j: usize) -> Result<(), MbdError> {
        if i != j {
            return Ok(());
        }
        let body = match self.bodies.get(i) {
            Some(b) => b.0.clone(),
            None if i == GROUND_ID => GROUND.to_string(),
            None => "a beam node".to_string(),
        };
        Err(MbdError::SameBody {
            item: item.to_string(),
            body,
        })
    }

    /// Initial angle of frame `id` (rigid or floating body; 0 for the ground and nodes).
    pub(crate) fn angle0(&self, id: usize) -> f64 {
        let nb = self.bodies.len();
        match self.bodies.get(id) {
            Some(b) => b.1.angle,
            None => self
                .floating
                .get(id.wrapping_sub(nb))
                .map_or(0.0, |f| f.pose[2]),
        }
    }

    /// Register a motion; returns its index.
    pub(crate) fn motion(&mut self, f: &TimeFn) -> usize {
        self.motions.push(f.clone());
        self.motions.len() - 1
    }
}
