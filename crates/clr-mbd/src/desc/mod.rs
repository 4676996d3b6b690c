//! The model description: plain data (`Clone + Send + Sync`, serde) holding bodies, flexible
//! bodies, joints, drivers, force elements, clearance joints, contact laws and the solver and
//! output settings. A TOML model file is this structure (`docs/model-file.md`);
//! [`ModelDesc::compile`] validates it and builds the runtime [`Model`](crate::Model). One
//! description compiles into any number of independent runs (sweeps clone the description).
//!
//! Rust closures are an explicit opt-in ([`crate::TimeFn::custom`], the `custom` force
//! element): a description holding one still compiles and runs but cannot be written to a file.

pub mod beam;
pub mod laws;
mod settings;

use serde::{Deserialize, Serialize};

pub use beam::{
    BeamMaterial, BeamMesh, MassKindDesc, Reduction, SectionDesc, SupportDesc, SupportKind,
};
pub use laws::{FrictionLawDesc, MaterialDesc, NormalLawDesc};
pub use settings::{OutputSettings, SolverMethod, SolverSettings};

use crate::element::{Clearance, Driver, Force, Joint};

/// A field-level error of a description: the path of the field (`joint[2].axis`) and what to
/// change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("field `{path}`: {message}")]
pub struct FieldError {
    /// Path of the offending field, e.g. `clearance[0].normal.restitution`.
    pub path: String,
    /// What is wrong and what to change.
    pub message: String,
}

impl FieldError {
    /// An error at `path`.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            message: message.into(),
        }
    }
}

/// A whole model as data. Sections in a file: `[model]`, `[[body]]`, `[[point]]`, `[[beam]]`,
/// `[[flexible_body]]`, `[[joint]]`, `[[driver]]`, `[[force]]`, `[[clearance]]`, `[solver]`,
/// `[output]`. Constraint rows follow the order joints, then drivers (then the node ties of
/// floating bodies, first); force elements and contacts keep their section order.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelDesc {
    /// Name, description, gravity, clearance force application.
    #[serde(default)]
    pub model: ModelInfo,
    /// Rigid bodies.
    #[serde(default, rename = "body", skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<Body>,
    /// Named points on bodies or beam nodes.
    #[serde(default, rename = "point", skip_serializing_if = "Vec::is_empty")]
    pub points: Vec<Point>,
    /// Ground-fixed flexible beams.
    #[serde(default, rename = "beam", skip_serializing_if = "Vec::is_empty")]
    pub beams: Vec<crate::element::ground_beam::GroundBeam>,
    /// Floating-frame flexible bodies.
    #[serde(
        default,
        rename = "flexible_body",
        skip_serializing_if = "Vec::is_empty"
    )]
    pub flexible_bodies: Vec<crate::element::floating_body::FlexibleBody>,
    /// Ideal joints.
    #[serde(default, rename = "joint", skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<Joint>,
    /// Drivers (prescribed motions).
    #[serde(default, rename = "driver", skip_serializing_if = "Vec::is_empty")]
    pub drivers: Vec<Driver>,
    /// Force elements.
    #[serde(default, rename = "force", skip_serializing_if = "Vec::is_empty")]
    pub forces: Vec<Force>,
    /// Clearance joints and sliders (contact elements).
    #[serde(default, rename = "clearance", skip_serializing_if = "Vec::is_empty")]
    pub clearances: Vec<Clearance>,
    /// Integrator settings.
    #[serde(default)]
    pub solver: SolverSettings,
    /// Time span and output times.
    #[serde(default)]
    pub output: OutputSettings,
}

/// `[model]`: name, description and model-wide settings.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelInfo {
    /// Model name (used in reports).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// One-line description.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Gravitational acceleration (g_x, g_y), m/s² (default none).
    #[serde(default)]
    pub gravity: [f64; 2],
    /// Where the force pair of every revolute clearance joint acts: `common_point` (default,
    /// collinear action and reaction) or `contact_points` (Flores et al. 2004).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clearance_force_application: Option<ForceApplicationDesc>,
}

/// Where a revolute clearance joint's force pair acts (clr-contact `ForceApplication`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ForceApplicationDesc {
    /// Action and reaction collinear through the journal centre's contact normal.
    CommonPoint,
    /// At the contact points of each body (the published Flores et al. 2004 form).
    ContactPoints,
}

/// A rigid body. Its frame is at `position` with angle `angle`; the centre of mass sits at
/// `centre_of_mass` in that frame (default the frame origin). Anchors and points on the body are
/// given in this frame. The model's coordinates (and result columns) are those of the centre
/// of mass.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// Unique name.
    pub name: String,
    /// Mass, kg (> 0).
    pub mass: f64,
    /// Moment of inertia about the centre of mass, kg·m² (> 0).
    pub inertia: f64,
    /// Initial position of the body frame's origin, m.
    #[serde(default)]
    pub position: [f64; 2],
    /// Initial angle, rad.
    #[serde(default)]
    pub angle: f64,
    /// Initial velocity of the body frame's origin, m/s.
    #[serde(default)]
    pub velocity: [f64; 2],
    /// Initial angular velocity, rad/s.
    #[serde(default)]
    pub angular_velocity: f64,
    /// Centre of mass in the body frame, m (default [0, 0]).
    #[serde(default, skip_serializing_if = "is_zero2")]
    pub centre_of_mass: [f64; 2],
}

fn is_zero2(v: &[f64; 2]) -> bool {
    v[0] == 0.0 && v[1] == 0.0
}

/// A named point: on a body (`body`, `at`) or at a beam node (`beam`, `node`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Point {
    /// Unique name.
    pub name: String,
    /// Body (or `ground`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// Local coordinates in the body frame, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<[f64; 2]>,
    /// Beam (ground-fixed or floating) whose node this point is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beam: Option<String>,
    /// Node index on `beam`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub node: Option<usize>,
}

impl ModelDesc {
    /// Read a description from a parsed TOML document (a model file), with the path of the
    /// offending field on error (`clearance[0].normal.restitution`) and serde's message
    /// (`unknown field`, `missing field`, `invalid type`, `unknown variant`).
    ///
    /// # Errors
    /// [`FieldError`] at the offending field.
    pub fn from_toml_table(table: toml::Table) -> Result<Self, FieldError> {
        let value = toml::Value::Table(table);
        let e = match serde_path_to_error::deserialize::<_, Self>(value.clone()) {
            Ok(d) => return Ok(d),
            Err(e) => e,
        };
        let path = e.path().to_string();
        let fallback = FieldError::new(path.clone(), e.inner().message().to_string());
        // an item of a section tagged by `type`: serde buffers it and loses the inner path,
        // so read that item again on its own
        let Some((section, k)) = section_item(&path) else {
            return Err(fallback);
        };
        let Some(item) = value
            .get(section)
            .and_then(|s| s.as_array())
            .and_then(|a| a.get(k))
            .cloned()
        else {
            return Err(fallback);
        };
        let inner = match section {
            "joint" => Joint::from_toml(item).err(),
            "driver" => Driver::from_toml(item).err(),
            "force" => Force::from_toml(item).err(),
            _ => Clearance::from_toml(item).err(),
        };
        Err(match inner {
            Some(FieldError { path: rel, message }) if rel.is_empty() => {
                FieldError::new(path, message)
            }
            Some(FieldError { path: rel, message }) => {
                FieldError::new(format!("{section}[{k}].{rel}"), message)
            }
            None => fallback,
        })
    }
}

/// `("joint", 2)` for the path `joint[2]` of an item in a section tagged by `type`.
fn section_item(path: &str) -> Option<(&'static str, usize)> {
    let (name, rest) = path.split_once('[')?;
    let section = ["joint", "driver", "force", "clearance"]
        .into_iter()
        .find(|s| *s == name)?;
    let k = rest.strip_suffix(']')?.parse().ok()?;
    Some((section, k))
}

/// Levenshtein edit distance between two strings (characters, not bytes).
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

/// The candidate closest to `name` by edit distance, when it is close enough to be a likely
/// typo (distance ≤ max(2, len/3)) or one contains the other.
pub fn closest<'a, I: IntoIterator<Item = &'a str>>(name: &str, candidates: I) -> Option<&'a str> {
    let lower = name.to_ascii_lowercase();
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        let d = edit_distance(&lower, &c.to_ascii_lowercase());
        if best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, c));
        }
    }
    let (d, c) = best?;
    let limit = (name.chars().count() / 3).max(2);
    let contains = !lower.is_empty()
        && (c.to_ascii_lowercase().contains(&lower) || lower.contains(&c.to_ascii_lowercase()));
    (d <= limit || contains).then_some(c)
}

/// `"; did you mean `x`?"` when a close candidate exists, else the list of valid names.
pub fn suggestion<'a, I>(name: &str, candidates: I) -> String
where
    I: IntoIterator<Item = &'a str> + Clone,
{
    match closest(name, candidates.clone()) {
        Some(c) => format!("did you mean `{c}`?"),
        None => {
            let all: Vec<&str> = candidates.into_iter().collect();
            if all.is_empty() {
                "none is defined".to_string()
            } else {
                format!("valid: {}", all.join(", "))
            }
        }
    }
}

impl ModelDesc {
    /// An empty description (only the ground), no gravity, default settings.
    pub fn new() -> Self {
        Self::default()
    }

    /// Validate every element and build the runtime model (Baumgarte coefficients and contact
    /// events from `solver`).
    ///
    /// # Errors
    /// A typed [`MbdError`](crate::MbdError) naming the item (and for field errors the path).
    pub fn compile(&self) -> Result<crate::Model, crate::MbdError> {
        crate::element::compile(self)
    }

    /// The simulation options of `solver` and `output`.
    ///
    /// # Errors
    /// [`FieldError`] for invalid settings (e.g. `output.t_end` missing or before `t_start`).
    pub fn sim_options(&self) -> Result<crate::SimOptions, FieldError> {
        settings::sim_options(&self.solver, &self.output)
    }

    /// Names of the items holding a Rust closure (they cannot be written to a file).
    pub fn closures(&self) -> Vec<String> {
        let mut out = Vec::new();
        for d in &self.drivers {
            if d.has_closure() {
                out.push(d.name().to_string());
            }
        }
        for f in &self.forces {
            if f.has_closure() {
                out.push(f.name().to_string());
            }
        }
        out
    }

    /// The description as TOML text (a complete model file).
    ///
    /// # Errors
    /// A message naming the items that hold closures, or the serializer's message.
    pub fn to_toml(&self) -> Result<String, String> {
        let c = self.closures();
        if !c.is_empty() {
            return Err(format!(
                "items {} hold Rust closures, which a model file cannot express; replace them \
                 by data (time functions, force elements)",
                c.join(", ")
            ));
        }
        toml::to_string(self).map_err(|e| e.to_string())
    }
}

// Compile-time check that the description is plain data: `Clone + Send + Sync` (the issue's
/// requirement for sweeps that share one description among threads).
const _: () = {
    const fn assert_plain_data<T: Clone + Send + Sync + 'static>() {}
    assert_plain_data::<ModelDesc>();
};
