//! The serde structure of a model file (every value optional here; [`super::ModelSpec`] checks
//! presence, ranges and references so that each error can name its field and line).

use serde::{Deserialize, Serialize};

use super::locate::{closest, line_col, FieldPath};
use super::overrides::{apply_json_override, Assignment};
use super::{Loaded, SpecError};

/// A model file as written (see `docs/model-file.md`).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelFile {
    /// `[model]`: name, description, gravity, or `builtin`.
    pub model: Option<ModelSection>,
    /// `[parameters]` of a built-in model.
    pub parameters: Option<toml::Table>,
    /// `[[body]]` rigid bodies.
    #[serde(default)]
    pub body: Vec<BodyFile>,
    /// `[[point]]` named body-fixed points.
    #[serde(default)]
    pub point: Vec<PointFile>,
    /// `[[joint]]` ideal joints.
    #[serde(default)]
    pub joint: Vec<JointFile>,
    /// `[[driver]]` prescribed motions.
    #[serde(default)]
    pub driver: Vec<DriverFile>,
    /// `[[force]]` force elements.
    #[serde(default)]
    pub force: Vec<ForceFile>,
    /// `[[clearance]]` clearance joints (contact elements).
    #[serde(default)]
    pub clearance: Vec<ClearanceFile>,
    /// `[[beam]]` ground-fixed flexible beams.
    #[serde(default)]
    pub beam: Vec<BeamFile>,
    /// `[solver]` integrator settings.
    pub solver: Option<SolverFile>,
    /// `[output]` duration and output times.
    pub output: Option<OutputFile>,
}

/// `[model]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSection {
    /// Model name (used in reports).
    pub name: Option<String>,
    /// One-line description.
    pub description: Option<String>,
    /// Gravitational acceleration (g_x, g_y), m/s².
    pub gravity: Option<[f64; 2]>,
    /// Name of a built-in model (then only `[parameters]` may follow).
    pub builtin: Option<String>,
}

/// `[[body]]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyFile {
    /// Unique name.
    pub name: Option<String>,
    /// Mass, kg.
    pub mass: Option<f64>,
    /// Moment of inertia about the centre of mass, kg·m².
    pub inertia: Option<f64>,
    /// Initial centre-of-mass position, m.
    pub position: Option<[f64; 2]>,
    /// Initial angle, rad.
    pub angle: Option<f64>,
    /// Initial centre-of-mass velocity, m/s.
    pub velocity: Option<[f64; 2]>,
    /// Initial angular velocity, rad/s.
    pub angular_velocity: Option<f64>,
}

/// `[[point]]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointFile {
    /// Unique name.
    pub name: Option<String>,
    /// Body (or `ground`).
    pub body: Option<String>,
    /// Local coordinates in the body frame (origin at the centre of mass), m.
    pub at: Option<[f64; 2]>,
    /// Beam whose node this point is (instead of `body` and `at`).
    pub beam: Option<String>,
    /// Node index on `beam`.
    pub node: Option<u64>,
}

/// An anchor as written: a point name, or `{ body = "...", at = [x, y] }`.
pub type AnchorFile = toml::Value;

/// `[[joint]]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointFile {
    /// Unique name.
    pub name: Option<String>,
    /// `revolute`, `fixed` or `translational`.
    #[serde(rename = "type")]
    pub kind: Option<String>,
    /// First anchor (on body i).
    pub a: Option<AnchorFile>,
    /// Second anchor (on body j).
    pub b: Option<AnchorFile>,
    /// Sliding axis in body i's frame (translational).
    pub axis: Option<[f64; 2]>,
}

/// `[[driver]]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DriverFile {
    /// Unique name.
    pub name: Option<String>,
    /// `angle`, `relative_angle` or `displacement`.
    #[serde(rename = "type")]
    pub kind: Option<String>,
    /// Driven body (`angle`).
    pub body: Option<String>,
    /// First body (`relative_angle`).
    pub body_i: Option<String>,
    /// Second body (`relative_angle`).
    pub body_j: Option<String>,
    /// First anchor (`displacement`).
    pub a: Option<AnchorFile>,
    /// Second anchor (`displacement`).
    pub b: Option<AnchorFile>,
    /// Axis on body i (`displacement`).
    pub axis: Option<[f64; 2]>,
    /// The prescribed motion.
    pub motion: Option<toml::Table>,
}

/// `[[force]]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceFile {
    /// Unique name.
    pub name: Option<String>,
    /// `spring_damper`, `rotational_spring_damper`, `force`, `torque`, `torque_between`.
    #[serde(rename = "type")]
    pub kind: Option<String>,
    /// First anchor (spring_damper).
    pub a: Option<AnchorFile>,
    /// Second anchor (spring_damper).
    pub b: Option<AnchorFile>,
    /// Anchor of an applied force.
    pub at: Option<AnchorFile>,
    /// Body of an applied torque.
    pub body: Option<String>,
    /// First body (rotational spring, torque_between).
    pub body_i: Option<String>,
    /// Second body (rotational spring, torque_between).
    pub body_j: Option<String>,
    /// Stiffness, N/m or N·m/rad.
    pub stiffness: Option<f64>,
    /// Damping, N·s/m or N·m·s/rad.
    pub damping: Option<f64>,
    /// Free length, m.
    pub free_length: Option<f64>,
    /// Free angle, rad.
    pub free_angle: Option<f64>,
    /// x component of an applied force as a time function, N.
    pub fx: Option<toml::Table>,
    /// y component of an applied force as a time function, N.
    pub fy: Option<toml::Table>,
    /// Torque as a time function, N·m.
    pub torque: Option<toml::Table>,
    /// Beam of a nodal load.
    pub beam: Option<String>,
    /// Node of a nodal load.
    pub node: Option<u64>,
    /// Moment of a nodal load as a time function, N·m.
    pub moment: Option<toml::Table>,
}

/// `[[clearance]]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClearanceFile {
    /// Unique name.
    pub name: Option<String>,
    /// `revolute` (the only kind so far).
    #[serde(rename = "type")]
    pub kind: Option<String>,
    /// Bearing centre anchor.
    pub bearing: Option<AnchorFile>,
    /// Journal centre anchor.
    pub journal: Option<AnchorFile>,
    /// Bearing (hole) radius, m.
    pub bearing_radius: Option<f64>,
    /// Journal (pin) radius, m.
    pub journal_radius: Option<f64>,
    /// Normal-force law.
    pub normal: Option<NormalFile>,
    /// Friction law (absent: frictionless).
    pub friction: Option<FrictionFile>,
    /// Guide frame anchor (translational).
    pub guide: Option<AnchorFile>,
    /// Slider centre anchor (translational).
    pub slider: Option<AnchorFile>,
    /// Inner width of the guide, m (translational).
    pub guide_width: Option<f64>,
    /// Angle of the guide axis in the guide body's frame, rad (translational).
    pub guide_angle: Option<f64>,
    /// Slider length along its axis, m (translational).
    pub slider_length: Option<f64>,
    /// Slider height across the guide, m (translational).
    pub slider_height: Option<f64>,
    /// Angle of the slider axis in the slider body's frame, rad (translational).
    pub slider_angle: Option<f64>,
}

/// `[[beam]]`: a ground-fixed flexible beam of Euler–Bernoulli frame elements (clr-beam).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeamFile {
    /// Unique name.
    pub name: Option<String>,
    /// First end (node 0), m.
    pub start: Option<[f64; 2]>,
    /// Last end (node `elements`), m.
    pub end: Option<[f64; 2]>,
    /// Number of equal elements.
    pub elements: Option<u64>,
    /// Material.
    pub material: Option<BeamMaterialFile>,
    /// Cross-section.
    pub section: Option<SectionFile>,
    /// Supports by node.
    #[serde(default)]
    pub supports: Vec<SupportFile>,
    /// Rayleigh damping [α (1/s), β (s)].
    pub rayleigh: Option<[f64; 2]>,
    /// `consistent` (default) or `lumped` mass.
    pub mass: Option<String>,
}

/// Material of a beam.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeamMaterialFile {
    /// Young's modulus, Pa.
    pub youngs_modulus: Option<f64>,
    /// Density, kg/m³.
    pub density: Option<f64>,
    /// Poisson's ratio (default 0.3).
    pub poisson_ratio: Option<f64>,
}

/// Cross-section of a beam: `shape` and its dimensions.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionFile {
    /// `rectangular`, `circular`, `tube` or `general`.
    pub shape: Option<String>,
    /// Width (rectangular), m.
    pub width: Option<f64>,
    /// Depth in the bending plane (rectangular, general), m.
    pub depth: Option<f64>,
    /// Diameter (circular), m.
    pub diameter: Option<f64>,
    /// Outer diameter (tube), m.
    pub outer_diameter: Option<f64>,
    /// Wall thickness (tube), m.
    pub wall: Option<f64>,
    /// Area (general), m².
    pub area: Option<f64>,
    /// Second moment of area (general), m⁴.
    pub second_moment: Option<f64>,
}

/// A support of a beam node.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SupportFile {
    /// Node index (0 at `start`).
    pub node: Option<u64>,
    /// `clamped`, `pinned`, `roller_x`, `roller_y`.
    #[serde(rename = "type")]
    pub kind: Option<String>,
}

/// An isotropic material.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialFile {
    /// Young's modulus, Pa.
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio, –.
    pub poisson_ratio: Option<f64>,
}

/// `normal = { ... }` of a clearance.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NormalFile {
    /// Elastic law (`hertz`, `power`, `linear`, `hertz-internal-cylinder`, `liu`, `bai-zhao`,
    /// `johnson`, `pereira`) or `preset`.
    pub law: Option<String>,
    /// Damping factor name (clr-contact `DampingFactor::from_name`).
    pub damping: Option<String>,
    /// Input coefficient of restitution c_e ∈ (0, 1].
    pub restitution: Option<f64>,
    /// Stiffness K (N/m^n) for `hertz`, `power`, `linear`.
    pub stiffness: Option<f64>,
    /// Exponent n for `power`.
    pub exponent: Option<f64>,
    /// Axial length L, m.
    pub length: Option<f64>,
    /// Bearing material.
    pub bearing_material: Option<MaterialFile>,
    /// Journal material.
    pub journal_material: Option<MaterialFile>,
    /// Flap-paper label for `law = "preset"` (`Hertz`, `LN`, `Gonthier`, `Bai`, `Wang`,
    /// `Modified`).
    pub preset: Option<String>,
    /// Floor of the impact velocity δ̇⁻, m/s.
    pub min_impact_velocity: Option<f64>,
}

/// `friction = { ... }` of a clearance.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionFile {
    /// `none`, `coulomb`, `ambrosio`, `ambrosio-smooth`, `threlfall`, `stribeck`.
    pub law: Option<String>,
    /// Friction coefficient μ.
    pub mu: Option<f64>,
    /// Regularization velocity (coulomb), m/s.
    pub v_reg: Option<f64>,
    /// Lower velocity v0 (ambrosio, threlfall), m/s.
    pub v0: Option<f64>,
    /// Upper velocity v1 (ambrosio), m/s.
    pub v1: Option<f64>,
    /// Static coefficient (stribeck).
    pub mu_s: Option<f64>,
    /// Dynamic coefficient (stribeck).
    pub mu_d: Option<f64>,
    /// Stiction velocity (stribeck), m/s.
    pub v_s: Option<f64>,
    /// Dynamic velocity (stribeck), m/s.
    pub v_d: Option<f64>,
}

/// `[solver]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverFile {
    /// `ndf` (default) or `dopri5`.
    pub method: Option<String>,
    /// Relative tolerance.
    pub rtol: Option<f64>,
    /// Absolute tolerance.
    pub atol: Option<f64>,
    /// Largest step, s.
    pub h_max: Option<f64>,
    /// Step budget.
    pub max_steps: Option<u64>,
    /// Baumgarte α, 1/s.
    pub baumgarte_alpha: Option<f64>,
    /// Baumgarte β, 1/s.
    pub baumgarte_beta: Option<f64>,
    /// Projection threshold on ‖Φ‖∞ (m or rad); absent: no projection.
    pub projection: Option<f64>,
    /// Locate contact onsets as events (default true).
    pub contact_events: Option<bool>,
}

/// `[output]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputFile {
    /// Start time, s (default 0).
    pub t_start: Option<f64>,
    /// End time, s.
    pub t_end: Option<f64>,
    /// Number of equal output intervals (default 500).
    pub intervals: Option<u64>,
    /// Also record after every accepted step (default false).
    pub every_step: Option<bool>,
}

/// Field names of each section, for suggestions on unknown fields.
pub(crate) fn known_fields(message: &str) -> Vec<String> {
    // serde's message: "unknown field `x`, expected one of `a`, `b`" or "expected `a` or `b`"
    let Some(rest) = message.split("expected").nth(1) else {
        return Vec::new();
    };
    rest.split('`')
        .enumerate()
        .filter(|(i, _)| i % 2 == 1)
        .map(|(_, s)| s.to_string())
        .collect()
}

/// Parse the text into a [`ModelFile`], mapping TOML syntax and schema errors to [`SpecError`].
pub(crate) fn parse(file: &str, src: &str) -> Result<ModelFile, SpecError> {
    toml::from_str::<ModelFile>(src).map_err(|e| de_error(file, src, &e))
}

/// A toml deserialization error as a [`SpecError`] with its line and a suggestion.
pub(crate) fn de_error(file: &str, src: &str, e: &toml::de::Error) -> SpecError {
    let message = e.message().trim().to_string();
    let (line, column) = match e.span() {
        Some(s) => {
            let (l, c) = line_col(src, s.start);
            (Some(l), Some(c))
        }
        None => (None, None),
    };
    let mut field = String::new();
    let mut message = message;
    if let Some(name) = message
        .strip_prefix("unknown field `")
        .and_then(|r| r.split('`').next())
        .map(str::to_string)
    {
        field = name.clone();
        let known = known_fields(&message);
        message = match closest(&name, known.iter().map(String::as_str)) {
            Some(c) => format!("unknown field `{name}`; did you mean `{c}`?"),
            None => format!(
                "unknown field `{name}`; valid fields here: {}",
                known.join(", ")
            ),
        };
    }
    if let (Some(s), true) = (e.span(), field.is_empty()) {
        // the key in front of the offending value, when there is one on that line
        let start = src[..s.start.min(src.len())]
            .rfind('\n')
            .map_or(0, |p| p + 1);
        let line_text = &src[start..s.start.min(src.len())];
        if let Some((k, _)) = line_text.split_once('=') {
            field = k.trim().to_string();
        }
    }
    SpecError {
        file: file.to_string(),
        line,
        column,
        field,
        message,
    }
}

/// The `[model] builtin = ...` form: merge `[parameters]` over the defaults, then the overrides.
pub(crate) fn builtin(
    file: &str,
    src: &str,
    parsed: &ModelFile,
    name: &str,
    overrides: &[Assignment],
) -> Result<Loaded, SpecError> {
    let model_path = FieldPath::root().key("model").key("builtin");
    let names: Vec<&str> = clr_models::catalog::entries()
        .iter()
        .map(|e| e.name)
        .collect();
    let mut params = clr_models::catalog::default_parameters(name).map_err(|_| {
        SpecError::at(
            file,
            src,
            &model_path,
            format!(
                "unknown built-in model `{name}`; {}",
                super::locate::suggestion(name, names.iter().copied())
            ),
        )
    })?;
    let extra = [
        ("body", !parsed.body.is_empty()),
        ("point", !parsed.point.is_empty()),
        ("joint", !parsed.joint.is_empty()),
        ("driver", !parsed.driver.is_empty()),
        ("force", !parsed.force.is_empty()),
        ("clearance", !parsed.clearance.is_empty()),
        ("beam", !parsed.beam.is_empty()),
        ("solver", parsed.solver.is_some()),
        ("output", parsed.output.is_some()),
    ];
    if let Some((sec, _)) = extra.iter().find(|(_, present)| *present) {
        return Err(SpecError::at(
            file,
            src,
            &FieldPath::root().key(sec),
            format!(
                "a built-in model file (`[model] builtin = \"{name}\"`) takes only `[model]` and \
                 `[parameters]`; remove `{sec}` or write a generic model without `builtin`"
            ),
        ));
    }
    if let Some(m) = &parsed.model {
        if m.gravity.is_some() {
            return Err(SpecError::at(
                file,
                src,
                &FieldPath::root().key("model").key("gravity"),
                "a built-in model takes gravity from its `[parameters]`; remove `gravity` here",
            ));
        }
    }
    if let Some(p) = &parsed.parameters {
        let base = FieldPath::root().key("parameters");
        merge_table(file, src, &base, &mut params, p)?;
    }
    for a in overrides {
        apply_json_override(&mut params, a)?;
    }
    Ok(Loaded::Builtin {
        name: name.to_string(),
        parameters: params,
    })
}

/// Merge a TOML table into JSON defaults: every key must exist with the same kind of value.
fn merge_table(
    file: &str,
    src: &str,
    path: &FieldPath,
    target: &mut serde_json::Value,
    table: &toml::Table,
) -> Result<(), SpecError> {
    let serde_json::Value::Object(obj) = target else {
        return Err(SpecError::at(
            file,
            src,
            path,
            "this parameter is a single value, not a table",
        ));
    };
    for (k, v) in table {
        let p = path.key(k);
        let Some(slot) = obj.get_mut(k) else {
            let known: Vec<&str> = obj.keys().map(String::as_str).collect();
            return Err(SpecError::at(
                file,
                src,
                &p,
                format!(
                    "unknown parameter `{k}`; {}",
                    super::locate::suggestion(k, known.iter().copied())
                ),
            ));
        };
        if let toml::Value::Table(t) = v {
            // a table tagged by `law` or `type` that switches variant replaces the default
            // whole (e.g. friction `none` → `coulomb` with its own fields)
            let switches = ["law", "type"].iter().any(|tag| {
                t.get(*tag).and_then(|x| x.as_str()).is_some_and(|new| {
                    slot.get(*tag)
                        .and_then(|x| x.as_str())
                        .is_some_and(|old| old != new)
                })
            });
            if switches {
                *slot = super::overrides::toml_to_json(v)
                    .map_err(|m| SpecError::at(file, src, &p, m))?;
                continue;
            }
            merge_table(file, src, &p, slot, t)?;
        } else {
            let new =
                super::overrides::toml_to_json(v).map_err(|m| SpecError::at(file, src, &p, m))?;
            super::overrides::check_same_kind(slot, &new)
                .map_err(|m| SpecError::at(file, src, &p, m))?;
            *slot = new;
        }
    }
    Ok(())
}
