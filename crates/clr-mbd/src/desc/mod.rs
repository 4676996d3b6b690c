//! The model description: plain data (`Clone + Send + Sync`, serde) holding bodies, flexible
//! bodies, joints, drivers, force elements, clearance joints, contact laws and the solver and
//! output settings. A TOML model file is this structure (`docs/model-file.md`);
//! [`ModelDesc::compile`] validates it and builds the runtime [`Model`](crate::Model). One
//! description compiles into any number of independent runs (sweeps clone the description).
//!
//! Rust closures are an explicit opt-in ([`crate::TimeFn::custom`], the `custom` force
//! element): a description holding one still compiles and runs but cannot be written to a file.

pub mod beam;
pub mod checks;
mod compile;
pub mod inertia;
pub mod laws;
pub mod metric;
pub mod parts;
mod settings;
pub mod twin;

use serde::{Deserialize, Serialize};

pub use beam::{
    BeamMaterial, BeamMesh, MassKindDesc, Reduction, SectionDesc, SupportDesc, SupportKind,
};
pub use laws::{FrictionLawDesc, MaterialDesc, NormalLawDesc};
pub use parts::{Body, ForceApplicationDesc, ModelInfo, Point, ResolvedBody};
pub(crate) use settings::sim_options as sim_options_of;
pub use settings::{
    unused_solver_fields, AllNodes, NodeSelection, OutputSettings, SolverMethod, SolverSettings,
    ATOL_PER_RTOL,
};

pub use crate::field::{closest, edit_distance, suggestion, FieldError};

use crate::element::{Clearance, Driver, Force, Joint};

/// A whole model as data. Sections in a file: `[model]`, `[[body]]`, `[[point]]`, `[[beam]]`,
/// `[[flexible_body]]`, `[[joint]]`, `[[driver]]`, `[[force]]`, `[[shape]]`, `[[clearance]]`,
/// `[[input]]`, `[[measure]]`, `[[metric]]`, `[twin]`, `[solver]`, `[output]`. Constraint rows follow the order joints, then drivers (then the node ties of
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
    /// Contact shapes on bodies (used by `contact` elements).
    #[serde(default, rename = "shape", skip_serializing_if = "Vec::is_empty")]
    pub shapes: Vec<crate::element::shape::ShapeDesc>,
    /// Clearance joints and sliders (contact elements).
    #[serde(default, rename = "clearance", skip_serializing_if = "Vec::is_empty")]
    pub clearances: Vec<Clearance>,
    /// Named real inputs a master can set ([`crate::input`]).
    #[serde(default, rename = "input", skip_serializing_if = "Vec::is_empty")]
    pub inputs: Vec<crate::input::InputDesc>,
    /// Named outputs written as result columns ([`crate::measure`]).
    #[serde(default, rename = "measure", skip_serializing_if = "Vec::is_empty")]
    pub measures: Vec<crate::measure::Measure>,
    /// Numbers taken of columns over time windows ([`metric`]).
    #[serde(default, rename = "metric", skip_serializing_if = "Vec::is_empty")]
    pub metrics: Vec<metric::MetricDesc>,
    /// How the ideal-joint twin of the `deviation` measures records (`[twin]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub twin: Option<crate::measure::deviation::TwinSettings>,
    /// Integrator settings.
    #[serde(default)]
    pub solver: SolverSettings,
    /// Time span and output times.
    #[serde(default)]
    pub output: OutputSettings,
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
            "measure" => crate::measure::Measure::from_toml(item).err(),
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
    let section = ["joint", "driver", "force", "clearance", "measure"]
        .into_iter()
        .find(|s| *s == name)?;
    let k = rest.strip_suffix(']')?.parse().ok()?;
    Some((section, k))
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
        compile::compile(self)
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
