//! The built-in models, by name.

use crate::common::parse;
use crate::dual_guide::{self, DualGuideParams};
use crate::flap::{self, FlapParams};
use crate::guide::{self, GuideParams};
use crate::manipulator::{self, ManipulatorParams};
use crate::slider_crank::{self, SliderCrankParams};
use crate::{ModelsError, RunOutput, RunSettings};

/// One built-in model.
#[derive(Debug, Clone, Copy)]
pub struct Entry {
    /// Name used on the command line (`clr run <name>`).
    pub name: &'static str,
    /// One-line description.
    pub description: &'static str,
}

/// Every built-in model.
pub fn entries() -> Vec<Entry> {
    vec![
        Entry {
            name: "slider_crank",
            description: "clearance slider-crank benchmark (Flores style): 0.5 mm clearance in \
                          the rod-slider joint, L-N law c_e = 0.9, crank 5000 rpm, 0.1 s",
        },
        Entry {
            name: "wan_slider_crank",
            description: "slider-crank validation rig of Wan et al. (2022), reconstructed: \
                          Modified law c_r = 0.46, Ambrosio friction 0.01, 0.1 mm, 600 rpm",
        },
        Entry {
            name: "flap",
            description: "flap actuation system of Wan et al. (2022), rigid linkage \
                          reconstructed: 0.1 mm clearance in J4 (aux rod-aux lever arm), \
                          Modified law c_r = 0.46, Ambrosio 0.01, actuator 10 mm at 2 Hz, 0.5 s",
        },
        Entry {
            name: "guide",
            description: "sliding guide of a telescopic mechanism (seed 000), reconstructed: \
                          slider with 0.5 mm clearance on a 1 m aluminium cantilever guide, \
                          Flores line / area law, Ambrosio friction, deployment at 1 m/s",
        },
        Entry {
            name: "dual_guide",
            description: "dual-stage dual guide of a telescopic mechanism (seed 000), \
                          reconstructed: stage-1 guides 100 mm apart carrying a carriage with \
                          two flexible (floating-frame) stage-2 guides, 8 pads with 0.5 mm \
                          clearance, both stages deploying at 0.5 m/s, 0.1 s",
        },
        Entry {
            name: "manipulator",
            description: "dual two-link manipulator on a free-floating spacecraft (Kuang, Bai, \
                          Wei 2026), case 3: 0.5 mm clearance in both elbows, 2 s",
        },
    ]
}

fn unknown(name: &str) -> ModelsError {
    ModelsError::UnknownModel {
        name: name.to_string(),
        valid: entries()
            .iter()
            .map(|e| e.name)
            .collect::<Vec<_>>()
            .join(", "),
    }
}

/// The parameters of a built-in model that its other parameters make unused, with the reason
/// (e.g. `axial_length` with the `LN` preset): a front end refuses those the user gave. Models
/// without such dependencies return an empty list.
///
/// # Errors
/// [`ModelsError::UnknownModel`] or [`ModelsError::InvalidParameters`].
pub fn unused_parameters(
    name: &str,
    parameters: &serde_json::Value,
) -> Result<Vec<(&'static str, String)>, ModelsError> {
    let merged = with_defaults(name, parameters)?;
    Ok(match name {
        "slider_crank" | "wan_slider_crank" => parse::<SliderCrankParams>(name, &merged)?.unused(),
        "flap" => parse::<FlapParams>(name, &merged)?.unused(),
        "guide" | "dual_guide" | "manipulator" => Vec::new(),
        _ => return Err(unknown(name)),
    })
}

/// The default parameters of a built-in model as JSON (every field resolved).
pub fn default_parameters(name: &str) -> Result<serde_json::Value, ModelsError> {
    let v = match name {
        "slider_crank" => serde_json::to_value(SliderCrankParams::flores()),
        "wan_slider_crank" => serde_json::to_value(SliderCrankParams::wan()),
        "manipulator" => serde_json::to_value(ManipulatorParams::default()),
        "flap" => serde_json::to_value(FlapParams::default()),
        "guide" => serde_json::to_value(GuideParams::default()),
        "dual_guide" => serde_json::to_value(DualGuideParams::default()),
        _ => return Err(unknown(name)),
    };
    v.map_err(|e| crate::common::invalid(name, e.to_string()))
}

/// Simulate a built-in model with the given parameters (as returned by
/// [`default_parameters`], possibly modified).
///
/// `parameters` is overlaid on [`default_parameters`]: fields it omits keep the model's
/// defaults (a nested object such as `friction` is merged field by field unless it names a new
/// `law`, then it replaces the default whole). Unknown fields are rejected.
///
/// # Errors
/// [`ModelsError::UnknownModel`], [`ModelsError::InvalidParameters`], [`ModelsError::Build`],
/// [`ModelsError::Simulation`].
pub fn run(
    name: &str,
    parameters: &serde_json::Value,
    settings: &RunSettings,
) -> Result<RunOutput, ModelsError> {
    match name {
        "slider_crank" | "wan_slider_crank" => {
            let p: SliderCrankParams = parse(name, &with_defaults(name, parameters)?)?;
            slider_crank::run(name, &p, settings)
        }
        "flap" => {
            let p: FlapParams = parse(name, &with_defaults(name, parameters)?)?;
            flap::run(name, &p, settings)
        }
        "guide" => {
            let p: GuideParams = parse(name, &with_defaults(name, parameters)?)?;
            guide::run(name, &p, settings)
        }
        "dual_guide" => {
            let p: DualGuideParams = parse(name, &with_defaults(name, parameters)?)?;
            dual_guide::run(name, &p, settings)
        }
        "manipulator" => {
            let p: ManipulatorParams = parse(name, &with_defaults(name, parameters)?)?;
            manipulator::run(name, &p, settings)
        }
        _ => Err(unknown(name)),
    }
}

/// The complete model that [`run`] simulates for these parameters and settings, as data: the
/// bodies, joints, drivers, force and contact elements, with the run settings in `solver`
/// (method, rtol, atol = rtol·10⁻³, no step bound, 10⁶ steps, no projection, Baumgarte,
/// contact events) and `output` (0 to the end time in s, every accepted step recorded), and
/// the catalog name and description in `[model]`. Compiling it
/// ([`clr_mbd::ModelDesc::compile`]) and simulating with
/// [`clr_mbd::ModelDesc::sim_options`] gives the time histories of [`run`] bit for bit (its
/// clr-mbd columns; for the slider–cranks and `manipulator` also the derived columns and the
/// metrics, which are `[[measure]]`, `[twin]` and `[[metric]]` items of the description; the
/// other models' [`run`] appends derived columns and computes metrics in Rust, and `flap` also
/// simulates an ideal-joint reference, which this description is not).
/// `parameters` is overlaid on [`default_parameters`] as in [`run`]; `settings.progress` is
/// not used.
///
/// A description holding a Rust closure (`guide` with `lateral_support_stiffness` > 0) is
/// returned, but [`clr_mbd::ModelDesc::to_toml`] refuses it, naming the item.
///
/// # Errors
/// [`ModelsError::UnknownModel`], [`ModelsError::InvalidParameters`].
pub fn export(
    name: &str,
    parameters: &serde_json::Value,
    settings: &RunSettings,
) -> Result<clr_mbd::ModelDesc, ModelsError> {
    let mut d = match name {
        "slider_crank" | "wan_slider_crank" => {
            let p: SliderCrankParams = parse(name, &with_defaults(name, parameters)?)?;
            slider_crank::run_desc(name, &p, settings)
        }
        "flap" => {
            let p: FlapParams = parse(name, &with_defaults(name, parameters)?)?;
            flap::run_desc(name, &p, settings)
        }
        "guide" => {
            let p: GuideParams = parse(name, &with_defaults(name, parameters)?)?;
            guide::run_desc(name, &p, settings)
        }
        "dual_guide" => {
            let p: DualGuideParams = parse(name, &with_defaults(name, parameters)?)?;
            dual_guide::run_desc(name, &p, settings)
        }
        "manipulator" => {
            let p: ManipulatorParams = parse(name, &with_defaults(name, parameters)?)?;
            manipulator::run_desc(name, &p, settings)
        }
        _ => Err(unknown(name)),
    }?;
    d.model.description = entries()
        .iter()
        .find(|e| e.name == name)
        .map(|e| e.description.to_string());
    Ok(d)
}

/// The model's default parameters overlaid with the given (possibly partial) object, so a
/// front end may pass only the fields it changes.
fn with_defaults(
    name: &str,
    parameters: &serde_json::Value,
) -> Result<serde_json::Value, ModelsError> {
    let mut base = default_parameters(name)?;
    merge(&mut base, parameters);
    Ok(base)
}

fn merge(base: &mut serde_json::Value, over: &serde_json::Value) {
    match (base, over) {
        (serde_json::Value::Object(b), serde_json::Value::Object(o)) => {
            for (k, v) in o {
                match b.get_mut(k) {
                    // tagged enums (e.g. friction laws) are replaced whole when the tag changes
                    Some(bv) if bv.is_object() && v.get("law").is_none() => merge(bv, v),
                    _ => {
                        b.insert(k.clone(), v.clone());
                    }
                }
            }
        }
        (b, o) => *b = o.clone(),
    }
}
