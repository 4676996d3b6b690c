//! Validation of a generic model file and its conversion into a clr-mbd model.

use std::collections::HashMap;

use clr_contact::{FrictionLaw, NormalLaw};
use clr_mbd::desc::laws::{FRICTION_LAWS, NORMAL_LAWS};
use clr_mbd::desc::MaterialDesc;
use clr_mbd::{Anchor, Model, ModelBuilder, RevoluteClearanceSpec, RigidBody, SimOptions};
use clr_mbd::{FrictionLawDesc, NormalLawDesc};
use clr_mbd::{SolverKind, TranslationalClearanceSpec, GROUND};

use super::file::{
    BeamFile, ClearanceFile, FrictionFile, MaterialFile, ModelFile, NormalFile, SectionFile,
};
use super::locate::{suggestion, FieldPath};
use super::timefn::{TimeFn, TIME_FN_KINDS};
use super::SpecError;

#[derive(Debug, Clone)]
enum ItemSpec {
    Revolute(String, Anchor, Anchor),
    Fixed(String, Anchor, Anchor),
    Translational(String, Anchor, Anchor, [f64; 2]),
    DriveAngle(String, String, String, TimeFn),
    DriveDisplacement(String, Anchor, Anchor, [f64; 2], TimeFn),
    Spring(String, Anchor, Anchor, [f64; 3]),
    RotSpring(String, String, String, [f64; 3]),
    Force(String, Anchor, TimeFn, TimeFn),
    Torque(String, String, TimeFn),
    PairTorque(String, String, String, TimeFn),
    Clearance(String, Anchor, Anchor, f64, f64, NormalLaw, FrictionLaw),
    /// guide, slider, [guide_width, guide_angle, slider_length, slider_height, slider_angle]
    TransClearance(String, Anchor, Anchor, [f64; 5], NormalLaw, FrictionLaw),
    Beam(String, Box<clr_mbd::BeamMesh>),
    BeamPoint(String, String, usize),
    NodalLoad(String, String, usize, [TimeFn; 3]),
}

/// A validated generic model: everything needed to build a `clr_mbd::Model` and its run
/// settings. Plain data (`Send`), so sweeps can build one model per thread.
#[derive(Debug, Clone)]
pub struct ModelSpec {
    /// File the model came from (for messages).
    pub file: String,
    /// The file's text (for locating build errors).
    src: String,
    /// Model name.
    pub name: String,
    /// Description.
    pub description: String,
    gravity: [f64; 2],
    bodies: Vec<(String, RigidBody)>,
    points: Vec<(String, String, [f64; 2])>,
    items: Vec<ItemSpec>,
    /// Integrator settings (t0, t_end, output times, tolerances, solver, projection, events).
    pub options: SimOptions,
    /// Baumgarte (α, β), 1/s.
    pub baumgarte: (f64, f64),
    /// Each clearance joint by name with its radial clearance c = R_bearing − R_journal (m;
    /// `None` for translational clearances).
    pub clearances: Vec<(String, Option<f64>)>,
    /// The file as validated, with every default filled in (for `summary.json`).
    pub resolved: serde_json::Value,
    /// The model description when the file was read as a `clr_mbd::ModelDesc` (e.g. written
    /// by `clr export`): [`ModelSpec::build`] compiles it instead of the validated items.
    desc: Option<Box<clr_mbd::ModelDesc>>,
}

/// A built model with its run settings.
pub struct Built {
    /// The clr-mbd model (Baumgarte coefficients already set).
    pub model: Model,
    /// Simulation options.
    pub options: SimOptions,
}

struct V<'a> {
    file: &'a str,
    src: &'a str,
}

impl V<'_> {
    fn err(&self, path: &FieldPath, m: impl Into<String>) -> SpecError {
        SpecError::at(self.file, self.src, path, m)
    }
    fn req<T: Clone>(&self, path: &FieldPath, v: &Option<T>, what: &str) -> Result<T, SpecError> {
        v.clone()
            .ok_or_else(|| self.err(path, format!("missing value: give {what}")))
    }
    fn positive(&self, path: &FieldPath, v: f64, unit: &str) -> Result<f64, SpecError> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(
                path,
                format!("must be positive and finite (give a value > 0), got {v} {unit}"),
            ))
        }
    }
    fn non_negative(&self, path: &FieldPath, v: f64, unit: &str) -> Result<f64, SpecError> {
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(self.err(path, format!("must be finite and ≥ 0, got {v} {unit}")))
        }
    }
    fn finite(&self, path: &FieldPath, v: f64) -> Result<f64, SpecError> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(path, format!("{v} must be finite")))
        }
    }
    fn finite2(&self, path: &FieldPath, v: [f64; 2]) -> Result<[f64; 2], SpecError> {
        self.finite(path, v[0])?;
        self.finite(path, v[1])?;
        Ok(v)
    }
    fn kind<'k>(
        &self,
        path: &FieldPath,
        v: &Option<String>,
        valid: &[&'k str],
        what: &str,
    ) -> Result<&'k str, SpecError> {
        let k = self.req(
            path,
            v,
            &format!("the {what} type, one of {}", valid.join(", ")),
        )?;
        let norm = k.trim().to_ascii_lowercase().replace('-', "_");
        valid
            .iter()
            .find(|v| v.replace('-', "_") == norm)
            .copied()
            .ok_or_else(|| {
                self.err(
                    path,
                    format!(
                        "unknown {what} type `{k}`; {}",
                        suggestion(&k, valid.iter().copied())
                    ),
                )
            })
    }
}

struct Names {
    bodies: Vec<String>,
    points: Vec<String>,
    /// Beam names and node counts.
    beams: Vec<(String, usize)>,
}

impl Names {
    fn body(&self, v: &V, path: &FieldPath, name: &str) -> Result<String, SpecError> {
        if name == GROUND || self.bodies.iter().any(|b| b == name) {
            Ok(name.to_string())
        } else {
            let all: Vec<&str> = std::iter::once(GROUND)
                .chain(self.bodies.iter().map(String::as_str))
                .collect();
            Err(v.err(
                path,
                format!(
                    "unknown body `{name}`; {}",
                    suggestion(name, all.iter().copied())
                ),
            ))
        }
    }
    fn body_opt(
        &self,
        v: &V,
        path: &FieldPath,
        name: &Option<String>,
    ) -> Result<String, SpecError> {
        let n = v.req(path, name, "a body name (or `ground`)")?;
        self.body(v, path, &n)
    }
    fn anchor(
        &self,
        v: &V,
        path: &FieldPath,
        a: &Option<toml::Value>,
    ) -> Result<Anchor, SpecError> {
        let a = v.req(
            path,
            a,
            "an anchor: a point name, or { body = \"name\", at = [x, y] } (m)",
        )?;
        match &a {
            toml::Value::String(p) => {
                if self.points.iter().any(|q| q == p) {
                    Ok(Anchor::Point(p.clone()))
                } else {
                    Err(v.err(
                        path,
                        format!(
                            "unknown point `{p}`; {} (or write {{ body = \"name\", at = [x, y] }})",
                            suggestion(p, self.points.iter().map(String::as_str))
                        ),
                    ))
                }
            }
            toml::Value::Table(t) => {
                for k in t.keys() {
                    if k != "body" && k != "at" {
                        return Err(v.err(
                            &path.key(k),
                            format!(
                                "unknown field `{k}` in an anchor; {}",
                                suggestion(k, ["body", "at"])
                            ),
                        ));
                    }
                }
                let body = match t.get("body") {
                    Some(toml::Value::String(b)) => self.body(v, &path.key("body"), b)?,
                    Some(_) => return Err(v.err(&path.key("body"), "the body must be a name")),
                    None => {
                        return Err(v.err(
                            &path.key("body"),
                            "missing value: give the anchor's body (or `ground`)",
                        ))
                    }
                };
                let at = match t.get("at") {
                    None => [0.0, 0.0],
                    Some(x) => vec2(x).ok_or_else(|| {
                        v.err(&path.key("at"), "expected two numbers [x, y] in m")
                    })?,
                };
                v.finite2(&path.key("at"), at)?;
                Ok(Anchor::Local(body, at))
            }
            _ => Err(v.err(
                path,
                "an anchor is a point name or { body = \"name\", at = [x, y] }",
            )),
        }
    }
}

fn num(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(f) => Some(*f),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

fn vec2(v: &toml::Value) -> Option<[f64; 2]> {
    let a = v.as_array()?;
    if a.len() != 2 {
        return None;
    }
    Some([num(&a[0])?, num(&a[1])?])
}

/// A function of time as written: the clr-mbd `TimeFn` table (`type` and its fields), read by
/// its serde form and checked by `TimeFn::validate`.
fn time_fn(v: &V, path: &FieldPath, t: &Option<toml::Table>) -> Result<TimeFn, SpecError> {
    let t = v.req(
        path,
        t,
        "a function of time, e.g. { type = \"linear\", initial = 0.0, rate = 10.0 }",
    )?;
    if !t.contains_key("type") {
        return Err(v.err(
            &path.key("type"),
            format!(
                "missing value: give the function type, one of {}",
                TIME_FN_KINDS.join(", ")
            ),
        ));
    }
    let f: TimeFn = toml::Value::Table(t)
        .try_into()
        .map_err(|e: toml::de::Error| v.err(path, e.message().trim().to_string()))?;
    f.validate("")
        .map_err(|e| v.err(&sub_path(path, &e.path), e.message))?;
    Ok(f)
}

/// A contact material as written, both fields required when the table is there.
fn material(
    v: &V,
    path: &FieldPath,
    m: &Option<MaterialFile>,
) -> Result<Option<MaterialDesc>, SpecError> {
    let Some(m) = m else { return Ok(None) };
    Ok(Some(MaterialDesc {
        youngs_modulus: v.req(
            &path.key("youngs_modulus"),
            &m.youngs_modulus,
            "Young's modulus in Pa",
        )?,
        poisson_ratio: v.req(
            &path.key("poisson_ratio"),
            &m.poisson_ratio,
            "Poisson's ratio",
        )?,
    }))
}

/// `base` extended by a clr-mbd relative field path (`.bearing_material.youngs_modulus`,
/// `.supports[2].node`).
fn sub_path(base: &FieldPath, rel: &str) -> FieldPath {
    let mut out = base.clone();
    for part in rel.split('.').filter(|p| !p.is_empty()) {
        let mut pieces = part.split('[');
        out = out.key(pieces.next().unwrap_or(""));
        for i in pieces.filter_map(|i| i.trim_end_matches(']').parse().ok()) {
            out = out.index(i);
        }
    }
    out
}

/// The normal-force law of a clearance: the file's table as a clr-mbd `NormalLawDesc`, which
/// checks and builds it (one definition of the laws by name for files and descriptions).
fn normal_law(
    v: &V,
    path: &FieldPath,
    n: &Option<NormalFile>,
    radii: Option<(f64, f64)>,
) -> Result<NormalLaw, SpecError> {
    let n = v.req(
        path,
        n,
        "a normal-force law, e.g. normal = { law = \"hertz\", stiffness = 1e10, damping = \
         \"lankarani-nikravesh\", restitution = 0.9 }",
    )?;
    let desc = NormalLawDesc {
        law: v.req(
            &path.key("law"),
            &n.law,
            &format!("the normal-force law, one of {}", NORMAL_LAWS.join(", ")),
        )?,
        damping: n.damping.clone(),
        restitution: v.req(
            &path.key("restitution"),
            &n.restitution,
            "the coefficient of restitution c_e in (0, 1]",
        )?,
        stiffness: n.stiffness,
        exponent: n.exponent,
        length: n.length,
        bearing_material: material(v, &path.key("bearing_material"), &n.bearing_material)?,
        journal_material: material(v, &path.key("journal_material"), &n.journal_material)?,
        preset: n.preset.clone(),
        min_impact_velocity: n.min_impact_velocity,
        ..NormalLawDesc::default()
    };
    desc.build("", radii)
        .map_err(|e| v.err(&sub_path(path, &e.path), e.message))
}

/// The friction law of a clearance (absent: frictionless), through clr-mbd's
/// `FrictionLawDesc`.
fn friction_law(
    v: &V,
    path: &FieldPath,
    f: &Option<FrictionFile>,
) -> Result<FrictionLaw, SpecError> {
    let desc = match f {
        None => FrictionLawDesc::none(),
        Some(f) => FrictionLawDesc {
            law: v.req(
                &path.key("law"),
                &f.law,
                &format!("the friction law, one of {}", FRICTION_LAWS.join(", ")),
            )?,
            mu: f.mu,
            v_reg: f.v_reg,
            v0: f.v0,
            v1: f.v1,
            mu_s: f.mu_s,
            mu_d: f.mu_d,
            v_s: f.v_s,
            v_d: f.v_d,
        },
    };
    desc.build("")
        .map_err(|e| v.err(&sub_path(path, &e.path), e.message))
}

impl ModelSpec {
    /// Validate a parsed model file; `src` is its text (for line numbers).
    ///
    /// # Errors
    /// The first problem found, as a [`SpecError`] with file, line and field.
    pub fn validate(file: &str, src: &str, m: ModelFile) -> Result<Self, SpecError> {
        let v = V { file, src };
        let root = FieldPath::root();
        let model = m.model.clone().unwrap_or_default();
        let gravity = v.finite2(
            &root.key("model").key("gravity"),
            model.gravity.unwrap_or([0.0, 0.0]),
        )?;
        if m.body.is_empty() && m.beam.is_empty() {
            return Err(v.err(
                &root.key("body"),
                "missing value: a model needs at least one [[body]] (name, mass, inertia) or \
                 [[beam]]",
            ));
        }
        // names: one namespace, `ground` reserved
        let mut seen: HashMap<String, FieldPath> = HashMap::new();
        let mut claim = |path: FieldPath, name: &Option<String>| -> Result<String, SpecError> {
            let p = path.key("name");
            let n = v.req(&p, name, "a unique name")?;
            if n.trim().is_empty() {
                return Err(v.err(&p, "the name is empty"));
            }
            if n == GROUND {
                return Err(v.err(&p, "`ground` is reserved for the fixed frame; rename it"));
            }
            if let Some(first) = seen.get(&n) {
                return Err(v.err(
                    &p,
                    format!("duplicate name `{n}` (first used at `{first}`); rename one"),
                ));
            }
            seen.insert(n.clone(), path);
            Ok(n)
        };
        let mut bodies = Vec::new();
        for (k, b) in m.body.iter().enumerate() {
            let p = root.key("body").index(k);
            let name = claim(p.clone(), &b.name)?;
            let mass = v.req(&p.key("mass"), &b.mass, "the mass in kg")?;
            let mass = v.positive(&p.key("mass"), mass, "kg")?;
            let inertia = v.req(
                &p.key("inertia"),
                &b.inertia,
                "the moment of inertia about the centre of mass in kg·m²",
            )?;
            let inertia = v.positive(&p.key("inertia"), inertia, "kg·m²")?;
            let pos = v.finite2(&p.key("position"), b.position.unwrap_or([0.0; 2]))?;
            let vel = v.finite2(&p.key("velocity"), b.velocity.unwrap_or([0.0; 2]))?;
            let angle = v.finite(&p.key("angle"), b.angle.unwrap_or(0.0))?;
            let omega = v.finite(
                &p.key("angular_velocity"),
                b.angular_velocity.unwrap_or(0.0),
            )?;
            bodies.push((
                name,
                RigidBody::new(mass, inertia)
                    .at(pos[0], pos[1], angle)
                    .moving(vel[0], vel[1], omega),
            ));
        }
        let mut names = Names {
            bodies: bodies.iter().map(|(n, _)| n.clone()).collect(),
            points: Vec::new(),
            beams: Vec::new(),
        };
        let mut items = Vec::new();
        for (k, bm) in m.beam.iter().enumerate() {
            let p = root.key("beam").index(k);
            let name = claim(p.clone(), &bm.name)?;
            let (model, nodes) = beam_model(&v, &p, bm)?;
            names.beams.push((name.clone(), nodes));
            items.push(ItemSpec::Beam(name, Box::new(model)));
        }
        let mut points = Vec::new();
        for (k, pt) in m.point.iter().enumerate() {
            let p = root.key("point").index(k);
            let name = claim(p.clone(), &pt.name)?;
            if pt.beam.is_some() || pt.node.is_some() {
                if pt.body.is_some() || pt.at.is_some() {
                    return Err(v.err(
                        &p.key("beam"),
                        "a point is on a body (`body`, `at`) or on a beam node (`beam`, `node`), \
                         not both",
                    ));
                }
                let (beam, node) = names.beam_node(&v, &p, &pt.beam, pt.node)?;
                names.points.push(name.clone());
                items.push(ItemSpec::BeamPoint(name, beam, node));
                continue;
            }
            let body = names.body_opt(&v, &p.key("body"), &pt.body)?;
            let at = v.finite2(
                &p.key("at"),
                v.req(&p.key("at"), &pt.at, "local coordinates [x, y] in m")?,
            )?;
            names.points.push(name.clone());
            points.push((name, body, at));
        }
        let axis = |p: &FieldPath, a: &Option<[f64; 2]>| -> Result<[f64; 2], SpecError> {
            let a = v.finite2(p, v.req(p, a, "an axis [x, y] (local to body i)")?)?;
            if a[0] == 0.0 && a[1] == 0.0 {
                return Err(v.err(
                    p,
                    "the axis [0, 0] has no direction; give a non-zero vector",
                ));
            }
            Ok(a)
        };
        for (k, j) in m.joint.iter().enumerate() {
            let p = root.key("joint").index(k);
            let name = claim(p.clone(), &j.name)?;
            let kind = v.kind(
                &p.key("type"),
                &j.kind,
                &["revolute", "fixed", "translational"],
                "joint",
            )?;
            let a = names.anchor(&v, &p.key("a"), &j.a)?;
            let b = names.anchor(&v, &p.key("b"), &j.b)?;
            items.push(match kind {
                "revolute" => ItemSpec::Revolute(name, a, b),
                "fixed" => ItemSpec::Fixed(name, a, b),
                _ => ItemSpec::Translational(name, a, b, axis(&p.key("axis"), &j.axis)?),
            });
        }
        for (k, d) in m.driver.iter().enumerate() {
            let p = root.key("driver").index(k);
            let name = claim(p.clone(), &d.name)?;
            let kind = v.kind(
                &p.key("type"),
                &d.kind,
                &["angle", "relative_angle", "displacement"],
                "driver",
            )?;
            let motion = time_fn(&v, &p.key("motion"), &d.motion)?;
            items.push(match kind {
                "angle" => ItemSpec::DriveAngle(
                    name,
                    GROUND.to_string(),
                    names.body_opt(&v, &p.key("body"), &d.body)?,
                    motion,
                ),
                "relative_angle" => ItemSpec::DriveAngle(
                    name,
                    names.body_opt(&v, &p.key("body_i"), &d.body_i)?,
                    names.body_opt(&v, &p.key("body_j"), &d.body_j)?,
                    motion,
                ),
                _ => ItemSpec::DriveDisplacement(
                    name,
                    names.anchor(&v, &p.key("a"), &d.a)?,
                    names.anchor(&v, &p.key("b"), &d.b)?,
                    axis(&p.key("axis"), &d.axis)?,
                    motion,
                ),
            });
        }
        for (k, f) in m.force.iter().enumerate() {
            let p = root.key("force").index(k);
            let name = claim(p.clone(), &f.name)?;
            let kind = v.kind(
                &p.key("type"),
                &f.kind,
                &[
                    "spring_damper",
                    "rotational_spring_damper",
                    "force",
                    "torque",
                    "torque_between",
                    "nodal_load",
                ],
                "force",
            )?;
            let tf = |key: &str, t: &Option<toml::Table>| -> Result<TimeFn, SpecError> {
                match t {
                    Some(_) => time_fn(&v, &p.key(key), t),
                    None => Ok(TimeFn::Constant { value: 0.0 }),
                }
            };
            let nn = |key: &str, x: &Option<f64>, unit: &str| -> Result<f64, SpecError> {
                v.non_negative(&p.key(key), x.unwrap_or(0.0), unit)
            };
            items.push(match kind {
                "spring_damper" => ItemSpec::Spring(
                    name,
                    names.anchor(&v, &p.key("a"), &f.a)?,
                    names.anchor(&v, &p.key("b"), &f.b)?,
                    [
                        nn("stiffness", &f.stiffness, "N/m")?,
                        nn("damping", &f.damping, "N·s/m")?,
                        nn("free_length", &f.free_length, "m")?,
                    ],
                ),
                "rotational_spring_damper" => ItemSpec::RotSpring(
                    name,
                    names.body_opt(&v, &p.key("body_i"), &f.body_i)?,
                    names.body_opt(&v, &p.key("body_j"), &f.body_j)?,
                    [
                        nn("stiffness", &f.stiffness, "N·m/rad")?,
                        nn("damping", &f.damping, "N·m·s/rad")?,
                        v.finite(&p.key("free_angle"), f.free_angle.unwrap_or(0.0))?,
                    ],
                ),
                "nodal_load" => {
                    let (beam, node) = names.beam_node(&v, &p, &f.beam, f.node)?;
                    ItemSpec::NodalLoad(
                        name,
                        beam,
                        node,
                        [tf("fx", &f.fx)?, tf("fy", &f.fy)?, tf("moment", &f.moment)?],
                    )
                }
                "force" => {
                    let fx = tf("fx", &f.fx)?;
                    let fy = tf("fy", &f.fy)?;
                    let at = names.anchor(&v, &p.key("at"), &f.at)?;
                    if anchor_body(&at, &points) == GROUND {
                        return Err(v.err(
                            &p.key("at"),
                            "a force on the ground does nothing; attach it to a moving body",
                        ));
                    }
                    ItemSpec::Force(name, at, fx, fy)
                }
                "torque" => {
                    let b = names.body_opt(&v, &p.key("body"), &f.body)?;
                    if b == GROUND {
                        return Err(v.err(
                            &p.key("body"),
                            "a torque on the ground does nothing; name a moving body",
                        ));
                    }
                    ItemSpec::Torque(name, b, time_fn(&v, &p.key("torque"), &f.torque)?)
                }
                _ => ItemSpec::PairTorque(
                    name,
                    names.body_opt(&v, &p.key("body_i"), &f.body_i)?,
                    names.body_opt(&v, &p.key("body_j"), &f.body_j)?,
                    time_fn(&v, &p.key("torque"), &f.torque)?,
                ),
            });
        }
        let mut clearances = Vec::new();
        for (k, c) in m.clearance.iter().enumerate() {
            let p = root.key("clearance").index(k);
            let name = claim(p.clone(), &c.name)?;
            let ClearanceFile {
                kind,
                bearing,
                journal,
                bearing_radius,
                journal_radius,
                normal,
                friction,
                ..
            } = c;
            let kind = v.kind(
                &p.key("type"),
                &kind.clone().or(Some("revolute".into())),
                &["revolute", "translational"],
                "clearance joint",
            )?;
            if kind == "translational" {
                let (guide, slider, dims) = translational_geometry(&v, &p, &names, c)?;
                let normal = normal_law(&v, &p.key("normal"), normal, None)?;
                let friction = friction_law(&v, &p.key("friction"), friction)?;
                clearances.push((name.clone(), None));
                items.push(ItemSpec::TransClearance(
                    name, guide, slider, dims, normal, friction,
                ));
                continue;
            }
            let bearing = names.anchor(&v, &p.key("bearing"), bearing)?;
            let journal = names.anchor(&v, &p.key("journal"), journal)?;
            let rb = v.req(
                &p.key("bearing_radius"),
                bearing_radius,
                "the bearing radius in m",
            )?;
            let rb = v.positive(&p.key("bearing_radius"), rb, "m")?;
            let rj = v.req(
                &p.key("journal_radius"),
                journal_radius,
                "the journal radius in m",
            )?;
            let rj = v.positive(&p.key("journal_radius"), rj, "m")?;
            if rj >= rb {
                return Err(v.err(
                    &p.key("journal_radius"),
                    format!(
                        "the radial clearance bearing_radius − journal_radius = {:e} m must be \
                         positive: make journal_radius smaller than bearing_radius = {rb} m",
                        rb - rj
                    ),
                ));
            }
            let normal = normal_law(&v, &p.key("normal"), normal, Some((rb, rj)))?;
            let friction = friction_law(&v, &p.key("friction"), friction)?;
            clearances.push((name.clone(), Some(rb - rj)));
            items.push(ItemSpec::Clearance(
                name, bearing, journal, rb, rj, normal, friction,
            ));
        }
        // solver and output
        let s = m.solver.clone().unwrap_or_default();
        let sp = root.key("solver");
        let method = v.kind(
            &sp.key("method"),
            &s.method.clone().or(Some("ndf".into())),
            &["ndf", "dopri5"],
            "solver",
        )?;
        let rtol = v.positive(&sp.key("rtol"), s.rtol.unwrap_or(1e-6), "")?;
        let atol = v.positive(&sp.key("atol"), s.atol.unwrap_or(1e-8), "")?;
        let h_max = s.h_max.unwrap_or(f64::INFINITY);
        if h_max.is_nan() || h_max <= 0.0 {
            return Err(v.err(&sp.key("h_max"), format!("{h_max} s must be > 0")));
        }
        let alpha = v.non_negative(
            &sp.key("baumgarte_alpha"),
            s.baumgarte_alpha
                .unwrap_or(clr_mbd::DEFAULT_BAUMGARTE_ALPHA),
            "1/s",
        )?;
        let beta = v.non_negative(
            &sp.key("baumgarte_beta"),
            s.baumgarte_beta.unwrap_or(clr_mbd::DEFAULT_BAUMGARTE_BETA),
            "1/s",
        )?;
        let projection = match s.projection {
            Some(x) => Some(v.positive(&sp.key("projection"), x, "m or rad")?),
            None => None,
        };
        let o = m.output.clone().unwrap_or_default();
        let op = root.key("output");
        let t0 = v.finite(&op.key("t_start"), o.t_start.unwrap_or(0.0))?;
        let t_end = v.req(&op.key("t_end"), &o.t_end, "the end time t_end in s")?;
        let t_end = v.finite(&op.key("t_end"), t_end)?;
        if t_end <= t0 {
            return Err(v.err(
                &op.key("t_end"),
                format!("t_end = {t_end} s must be after t_start = {t0} s"),
            ));
        }
        let intervals = o.intervals.unwrap_or(500);
        let every_step = o.every_step.unwrap_or(false);
        if (intervals == 0 && !every_step) || intervals > 10_000_000 {
            return Err(v.err(
                &op.key("intervals"),
                "give between 1 and 10 000 000 output intervals (0 only with every_step = true)",
            ));
        }
        let mut options = if intervals == 0 {
            SimOptions {
                t0,
                t_end,
                ..SimOptions::default()
            }
        } else {
            SimOptions::span(t0, t_end, intervals as usize)
        }
        .solver(if method == "ndf" {
            SolverKind::Ndf
        } else {
            SolverKind::Dopri5
        })
        .tolerances(rtol, atol);
        options.h_max = h_max;
        options.max_steps = s.max_steps.unwrap_or(1_000_000) as usize;
        options.every_step = every_step;
        options.projection = projection;
        options.contact_events = s.contact_events.unwrap_or(true);
        let resolved = serde_json::json!({
            "model": {"name": model.name, "description": model.description, "gravity": gravity},
            "body": bodies.iter().map(|(n, b)| serde_json::json!({
                "name": n, "mass": b.mass, "inertia": b.inertia, "position": b.position,
                "angle": b.angle, "velocity": b.velocity, "angular_velocity": b.angular_velocity,
            })).collect::<Vec<_>>(), "point": m.point, "joint": m.joint, "driver": m.driver,
            "force": m.force, "clearance": m.clearance, "beam": m.beam,
            "solver": {"method": method, "rtol": rtol, "atol": atol,
                "h_max": if h_max.is_finite() { Some(h_max) } else { None },
                "max_steps": options.max_steps, "baumgarte_alpha": alpha, "baumgarte_beta": beta,
                "projection": projection, "contact_events": options.contact_events},
            "output": {"t_start": t0, "t_end": t_end, "intervals": intervals,
                "every_step": options.every_step},
        });
        let mut resolved = resolved;
        strip_nulls(&mut resolved);
        Ok(Self {
            file: file.to_string(),
            src: src.to_string(),
            name: model.name.unwrap_or_else(|| {
                std::path::Path::new(file)
                    .file_stem()
                    .map_or("model".into(), |s| s.to_string_lossy().into_owned())
            }),
            description: model.description.unwrap_or_default(),
            gravity,
            bodies,
            points,
            items,
            options,
            baumgarte: (alpha, beta),
            clearances,
            resolved,
            desc: None,
        })
    }

    /// A model from its description (`clr_mbd::ModelDesc`, the TOML form `clr export` writes);
    /// `src` is the file's text (for placing errors). The description is compiled once here to
    /// check it; the run settings come from its `[solver]` and `[output]`
    /// (`ModelDesc::sim_options`), the name from `[model]` or else the file stem.
    ///
    /// # Errors
    /// [`SpecError`] with the item or field named by clr-mbd and its line when found.
    pub fn from_desc(file: &str, src: &str, desc: clr_mbd::ModelDesc) -> Result<Self, SpecError> {
        let mut spec = Self {
            file: file.to_string(),
            src: src.to_string(),
            name: desc.model.name.clone().unwrap_or_else(|| {
                std::path::Path::new(file)
                    .file_stem()
                    .map_or("model".into(), |s| s.to_string_lossy().into_owned())
            }),
            description: desc.model.description.clone().unwrap_or_default(),
            gravity: desc.model.gravity,
            bodies: Vec::new(),
            points: Vec::new(),
            items: Vec::new(),
            options: SimOptions::default(),
            baumgarte: (desc.solver.baumgarte_alpha, desc.solver.baumgarte_beta),
            clearances: desc
                .clearances
                .iter()
                .map(|c| {
                    let radial = match c {
                        clr_mbd::element::Clearance::Revolute(r) => {
                            Some(r.bearing_radius - r.journal_radius)
                        }
                        _ => None,
                    };
                    (c.name().to_string(), radial)
                })
                .collect(),
            resolved: serde_json::Value::Null,
            desc: None,
        };
        spec.options = desc
            .sim_options()
            .map_err(|e| SpecError::at(file, src, &spec.desc_path(&e.path), e.message.clone()))?;
        desc.compile().map_err(|e| spec.model_error(&e))?;
        let mut resolved = serde_json::to_value(&desc).map_err(|e| {
            SpecError::plain(file, "", format!("the model cannot be recorded: {e}"))
        })?;
        strip_nulls(&mut resolved);
        spec.resolved = resolved;
        spec.desc = Some(Box::new(desc));
        Ok(spec)
    }

    /// A field path of a clr-mbd message (`joint[2].axis`, or `crank_drive.motion.rate` with
    /// an item name first) as a path in the file.
    fn desc_path(&self, path: &str) -> FieldPath {
        const SECTIONS: [&str; 11] = [
            "model",
            "body",
            "point",
            "beam",
            "flexible_body",
            "joint",
            "driver",
            "force",
            "clearance",
            "solver",
            "output",
        ];
        let (first, rest) = path.split_once('.').unwrap_or((path, ""));
        if !first.contains('[') && !SECTIONS.contains(&first) {
            // an item name first: its place in its section
            if let Some(item) = self.path_of(first) {
                return sub_path(&item, rest);
            }
        }
        sub_path(&FieldPath::root(), path)
    }

    /// Set the end time (s).
    ///
    /// # Errors
    /// [`SpecError`] when `t_end` is not after the start time.
    pub fn set_t_end(&mut self, t_end: f64) -> Result<(), SpecError> {
        if !(t_end.is_finite() && t_end > self.options.t0) {
            return Err(SpecError::plain(
                "--t-end",
                "",
                format!(
                    "{t_end} s must be finite and after t_start = {} s",
                    self.options.t0
                ),
            ));
        }
        let n = self.options.times.len().saturating_sub(1).max(1);
        let every = self.options.every_step;
        let old = std::mem::take(&mut self.options);
        let times = if old.times.is_empty() {
            Vec::new()
        } else {
            SimOptions::span(old.t0, t_end, n).times
        };
        self.options = SimOptions {
            times,
            t_end,
            every_step: every,
            ..old
        };
        self.resolved["output"]["t_end"] = serde_json::json!(t_end);
        Ok(())
    }

    /// Set the relative tolerance.
    ///
    /// # Errors
    /// [`SpecError`] when `rtol` is not positive.
    pub fn set_rtol(&mut self, rtol: f64) -> Result<(), SpecError> {
        if !(rtol.is_finite() && rtol > 0.0) {
            return Err(SpecError::plain(
                "--rtol",
                "",
                format!("{rtol} must be > 0"),
            ));
        }
        self.options.rtol = rtol;
        self.resolved["solver"]["rtol"] = serde_json::json!(rtol);
        Ok(())
    }

    /// Build the clr-mbd model.
    ///
    /// # Errors
    /// [`SpecError`] from clr-mbd's validation (redundant constraints, assembly, …), placed at
    /// the item it names when possible.
    pub fn build(&self) -> Result<Built, SpecError> {
        if let Some(d) = &self.desc {
            return Ok(Built {
                model: d.compile().map_err(|e| self.model_error(&e))?,
                options: self.options.clone(),
            });
        }
        let mut b = ModelBuilder::new();
        b.gravity(self.gravity[0], self.gravity[1]);
        for (n, body) in &self.bodies {
            b.body(n, *body);
        }
        for (n, body, at) in &self.points {
            b.point(n, body, *at);
        }
        for it in &self.items {
            match it {
                ItemSpec::Beam(n, model) => {
                    b.flexible_beam(n, (**model).clone());
                }
                ItemSpec::BeamPoint(n, beam, node) => {
                    b.beam_node_point(n, beam, *node);
                }
                _ => {}
            }
        }
        let motion = |f: &TimeFn| f.clone();
        for it in &self.items {
            match it {
                ItemSpec::Revolute(n, a, c) => {
                    b.revolute(n, a.clone(), c.clone());
                }
                ItemSpec::Fixed(n, a, c) => {
                    b.fixed(n, a.clone(), c.clone());
                }
                ItemSpec::Translational(n, a, c, ax) => {
                    b.translational(n, a.clone(), c.clone(), *ax);
                }
                ItemSpec::DriveAngle(n, i, j, f) => {
                    b.drive_relative_angle(n, i, j, motion(f));
                }
                ItemSpec::DriveDisplacement(n, a, c, ax, f) => {
                    b.drive_displacement(n, a.clone(), c.clone(), *ax, motion(f));
                }
                ItemSpec::Spring(n, a, c, [k, d, l0]) => {
                    b.spring_damper(n, a.clone(), c.clone(), *k, *d, *l0);
                }
                ItemSpec::RotSpring(n, i, j, [k, d, a0]) => {
                    b.rotational_spring_damper(n, i, j, *k, *d, *a0);
                }
                ItemSpec::Force(n, at, fx, fy) => {
                    b.force(n, at.clone(), fx.clone(), fy.clone());
                }
                ItemSpec::Torque(n, body, f) => {
                    b.torque(n, body, f.clone());
                }
                ItemSpec::PairTorque(n, i, j, f) => {
                    b.motor_torque(n, i, j, f.clone());
                }
                ItemSpec::Beam(..) | ItemSpec::BeamPoint(..) => {}
                ItemSpec::NodalLoad(n, beam, node, [fx, fy, mz]) => {
                    b.nodal_load(n, beam, *node, [fx.clone(), fy.clone(), mz.clone()]);
                }
                ItemSpec::TransClearance(n, guide, slider, d, normal, friction) => {
                    b.translational_clearance(
                        n,
                        guide.clone(),
                        slider.clone(),
                        TranslationalClearanceSpec {
                            guide_width: d[0],
                            guide_angle: d[1],
                            slider_length: d[2],
                            slider_height: d[3],
                            slider_angle: d[4],
                            normal: (*normal).into(),
                            friction: (*friction).into(),
                        },
                    );
                }
                ItemSpec::Clearance(n, bearing, journal, rb, rj, normal, friction) => {
                    b.revolute_clearance(
                        n,
                        bearing.clone(),
                        journal.clone(),
                        RevoluteClearanceSpec {
                            bearing_radius: *rb,
                            journal_radius: *rj,
                            normal: (*normal).into(),
                            friction: (*friction).into(),
                        },
                    );
                }
            }
        }
        let mut model = b.build().map_err(|e| self.model_error(&e))?;
        model
            .set_baumgarte(self.baumgarte.0, self.baumgarte.1)
            .map_err(|e| self.model_error(&e))?;
        Ok(Built {
            model,
            options: self.options.clone(),
        })
    }

    /// A clr-mbd error as a [`SpecError`], placed at the item it names when there is one.
    pub fn model_error(&self, e: &clr_mbd::MbdError) -> SpecError {
        use clr_mbd::MbdError as E;
        let item = match e {
            E::UnknownBody { item, .. }
            | E::UnknownPoint { item, .. }
            | E::SameBody { item, .. }
            | E::InvalidParameter { item, .. }
            | E::Contact { item, .. } => Some(item.clone()),
            E::InvalidInertia { body, .. } => Some(body.clone()),
            E::DuplicateName { name, .. } => Some(name.clone()),
            // labels are `item (equation)`: place the error at the first item named
            E::RedundantConstraints {
                involved: label, ..
            }
            | E::Assembly { worst: label, .. } => {
                label.split(" (").next().map(|s| s.trim().to_string())
            }
            E::Invalid { path, message } => {
                return SpecError::at(
                    &self.file,
                    &self.src,
                    &self.desc_path(path),
                    message.clone(),
                )
            }
            _ => None,
        };
        let path = item
            .and_then(|n| self.path_of(&n))
            .unwrap_or_else(FieldPath::root);
        SpecError::at(&self.file, &self.src, &path, e.to_string())
    }

    fn path_of(&self, name: &str) -> Option<FieldPath> {
        let root: toml::Table = toml::from_str(&self.src).ok()?;
        for sec in [
            "body",
            "beam",
            "flexible_body",
            "point",
            "joint",
            "driver",
            "force",
            "clearance",
        ] {
            if let Some(toml::Value::Array(a)) = root.get(sec) {
                if let Some(k) = a
                    .iter()
                    .position(|i| i.get("name").and_then(|n| n.as_str()) == Some(name))
                {
                    return Some(FieldPath::root().key(sec).index(k));
                }
            }
        }
        None
    }

    /// Names of the rigid bodies, in order.
    pub fn body_names(&self) -> Vec<String> {
        if let Some(d) = &self.desc {
            return d.bodies.iter().map(|b| b.name.clone()).collect();
        }
        self.bodies.iter().map(|(n, _)| n.clone()).collect()
    }
}

fn anchor_body<'a>(a: &'a Anchor, points: &'a [(String, String, [f64; 2])]) -> &'a str {
    match a {
        Anchor::Local(b, _) => b,
        Anchor::Point(p) => points
            .iter()
            .find(|(n, _, _)| n == p)
            .map_or("", |(_, b, _)| b.as_str()),
        // anchors of kinds model files do not write (clr-mbd may add some)
        #[allow(unreachable_patterns)]
        _ => "",
    }
}

impl Names {
    /// A beam name and a node index on it.
    fn beam_node(
        &self,
        v: &V,
        p: &FieldPath,
        beam: &Option<String>,
        node: Option<u64>,
    ) -> Result<(String, usize), SpecError> {
        let b = v.req(&p.key("beam"), beam, "the beam name")?;
        let Some((_, nodes)) = self.beams.iter().find(|(n, _)| *n == b) else {
            return Err(v.err(
                &p.key("beam"),
                format!(
                    "unknown beam `{b}`; {}",
                    suggestion(&b, self.beams.iter().map(|(n, _)| n.as_str()))
                ),
            ));
        };
        let node = v.req(
            &p.key("node"),
            &node,
            "the node index (0 at the beam's start)",
        )?;
        if node as usize >= *nodes {
            return Err(v.err(
                &p.key("node"),
                format!(
                    "beam `{b}` has nodes 0 to {}; node {node} does not exist",
                    nodes - 1
                ),
            ));
        }
        Ok((b, node as usize))
    }
}

/// The clr-beam model of a `[[beam]]` and its node count.
fn beam_model(
    v: &V,
    p: &FieldPath,
    bm: &BeamFile,
) -> Result<(clr_mbd::BeamMesh, usize), SpecError> {
    use clr_mbd::desc::{BeamMaterial, MassKindDesc, SectionDesc, SupportDesc, SupportKind};
    let start = v.finite2(
        &p.key("start"),
        v.req(&p.key("start"), &bm.start, "the first end [x, y] in m")?,
    )?;
    let end = v.finite2(
        &p.key("end"),
        v.req(&p.key("end"), &bm.end, "the last end [x, y] in m")?,
    )?;
    if start == end {
        return Err(v.err(&p.key("end"), "the beam has zero length: give end ≠ start"));
    }
    let n = v.req(&p.key("elements"), &bm.elements, "the number of elements")?;
    if n == 0 || n > 10_000 {
        return Err(v.err(&p.key("elements"), "give between 1 and 10 000 elements"));
    }
    let mp = p.key("material");
    let mf = v.req(
        &mp,
        &bm.material,
        "a material { youngs_modulus = 2.07e11, density = 7850, poisson_ratio = 0.3 }",
    )?;
    let e = v.req(
        &mp.key("youngs_modulus"),
        &mf.youngs_modulus,
        "Young's modulus in Pa",
    )?;
    let e = v.positive(&mp.key("youngs_modulus"), e, "Pa")?;
    let rho = v.req(&mp.key("density"), &mf.density, "the density in kg/m³")?;
    let rho = v.positive(&mp.key("density"), rho, "kg/m³")?;
    let sp = p.key("section");
    let sf: SectionFile = v.req(
        &sp,
        &bm.section,
        "a section, e.g. { shape = \"rectangular\", width = 0.02, depth = 0.005 }",
    )?;
    let shape = v.kind(
        &sp.key("shape"),
        &sf.shape,
        &["rectangular", "circular", "tube", "general"],
        "section shape",
    )?;
    let dim = |k: &str, x: &Option<f64>| -> Result<f64, SpecError> {
        let q = sp.key(k);
        v.positive(
            &q,
            v.req(&q, x, &format!("`{k}` in m for a {shape} section"))?,
            "m",
        )
    };
    let section_desc = match shape {
        "rectangular" => SectionDesc::Rectangular {
            width: dim("width", &sf.width)?,
            depth: dim("depth", &sf.depth)?,
        },
        "circular" => SectionDesc::Circular {
            diameter: dim("diameter", &sf.diameter)?,
        },
        "tube" => SectionDesc::Tube {
            outer_diameter: dim("outer_diameter", &sf.outer_diameter)?,
            wall: dim("wall", &sf.wall)?,
        },
        _ => {
            let a = sp.key("area");
            let i = sp.key("second_moment");
            SectionDesc::General {
                area: v.positive(&a, v.req(&a, &sf.area, "the area in m²")?, "m²")?,
                second_moment: v.positive(
                    &i,
                    v.req(&i, &sf.second_moment, "the second moment in m⁴")?,
                    "m⁴",
                )?,
                depth: dim("depth", &sf.depth)?,
            }
        }
    };
    let mut supports = Vec::new();
    let nodes = n as usize + 1;
    for (k, s) in bm.supports.iter().enumerate() {
        let q = p.key("supports").index(k);
        let node = v.req(&q.key("node"), &s.node, "the node index")?;
        if node as usize >= nodes {
            return Err(v.err(
                &q.key("node"),
                format!(
                    "the beam has nodes 0 to {}; node {node} does not exist",
                    nodes - 1
                ),
            ));
        }
        let kind = v.kind(
            &q.key("type"),
            &s.kind,
            &["clamped", "pinned", "roller_x", "roller_y"],
            "support",
        )?;
        supports.push(SupportDesc {
            node: node as usize,
            kind: match kind {
                "clamped" => SupportKind::Clamped,
                "pinned" => SupportKind::Pinned,
                "roller_x" => SupportKind::RollerX,
                _ => SupportKind::RollerY,
            },
        });
    }
    if let Some([a, b]) = bm.rayleigh {
        let q = p.key("rayleigh");
        v.non_negative(&q, a, "1/s")?;
        v.non_negative(&q, b, "s")?;
    }
    let mass = v.kind(
        &p.key("mass"),
        &bm.mass.clone().or(Some("consistent".into())),
        &["consistent", "lumped"],
        "mass matrix",
    )?;
    let mesh = clr_mbd::BeamMesh {
        start,
        end,
        elements: n as usize,
        material: BeamMaterial {
            youngs_modulus: e,
            density: rho,
            poisson_ratio: mf.poisson_ratio.unwrap_or(0.3),
        },
        section: section_desc,
        supports,
        rayleigh: bm.rayleigh.unwrap_or([0.0, 0.0]),
        mass: if mass == "lumped" {
            MassKindDesc::Lumped
        } else {
            MassKindDesc::Consistent
        },
    };
    // what clr-beam itself refuses (Poisson's ratio, section proportions), at its field
    mesh.build("").map_err(|e| {
        let field = e.path.trim_start_matches('.');
        let at = match field.split(['.', '[']).next().unwrap_or("") {
            "material" => mp.key("poisson_ratio"),
            "section" => sp.clone(),
            "supports" => p.key("supports"),
            "rayleigh" => p.key("rayleigh"),
            _ => p.clone(),
        };
        v.err(&at, e.message)
    })?;
    Ok((mesh, nodes))
}

/// Anchors and dimensions of a translational clearance:
/// [guide_width, guide_angle, slider_length, slider_height, slider_angle].
fn translational_geometry(
    v: &V,
    p: &FieldPath,
    names: &Names,
    c: &ClearanceFile,
) -> Result<(Anchor, Anchor, [f64; 5]), SpecError> {
    for (k, present) in [
        ("bearing", c.bearing.is_some()),
        ("journal", c.journal.is_some()),
        ("bearing_radius", c.bearing_radius.is_some()),
        ("journal_radius", c.journal_radius.is_some()),
    ] {
        if present {
            return Err(v.err(
                &p.key(k),
                format!("`{k}` belongs to revolute clearances; a translational one has guide, slider, guide_width, slider_length, slider_height"),
            ));
        }
    }
    let guide = names.anchor(v, &p.key("guide"), &c.guide)?;
    let slider = names.anchor(v, &p.key("slider"), &c.slider)?;
    let pos = |k: &str, x: &Option<f64>| -> Result<f64, SpecError> {
        let q = p.key(k);
        v.positive(&q, v.req(&q, x, &format!("`{k}` in m"))?, "m")
    };
    let w = pos("guide_width", &c.guide_width)?;
    let l = pos("slider_length", &c.slider_length)?;
    let h = pos("slider_height", &c.slider_height)?;
    if h >= w {
        return Err(v.err(
            &p.key("slider_height"),
            format!(
                "the clearance guide_width − slider_height = {:e} m must be positive: make \
                 slider_height smaller than guide_width = {w} m",
                w - h
            ),
        ));
    }
    let ga = v.finite(&p.key("guide_angle"), c.guide_angle.unwrap_or(0.0))?;
    let sa = v.finite(&p.key("slider_angle"), c.slider_angle.unwrap_or(0.0))?;
    Ok((guide, slider, [w, ga, l, h, sa]))
}

/// Remove absent (null) values from JSON objects, recursively.
fn strip_nulls(v: &mut serde_json::Value) {
    match v {
        serde_json::Value::Object(o) => {
            o.retain(|_, x| !x.is_null());
            o.values_mut().for_each(strip_nulls);
        }
        serde_json::Value::Array(a) => a.iter_mut().for_each(strip_nulls),
        _ => {}
    }
}
