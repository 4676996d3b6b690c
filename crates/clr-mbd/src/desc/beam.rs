//! Flexible parts as data: a straight beam mesh (section, material, supports, damping) and its
//! reduction for a floating-frame body.

use clr_beam::{BeamModel, MassKind, Material, ReducedModel, Section, Support};
use serde::{Deserialize, Serialize};

use crate::field::FieldError;

/// A straight beam of `elements` equal Euler–Bernoulli frame elements from `start` to `end`
/// (clr-beam `BeamModel::straight`), with supports, Rayleigh damping and mass kind. Coordinates
/// are world coordinates for a ground-fixed beam and body-frame coordinates for a floating body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeamMesh {
    /// First end (node 0), m.
    pub start: [f64; 2],
    /// Last end (node `elements`), m.
    pub end: [f64; 2],
    /// Number of equal elements (≥ 1).
    pub elements: usize,
    /// Material.
    pub material: BeamMaterial,
    /// Cross-section.
    pub section: SectionDesc,
    /// Supports by node (for a floating body: its reference conditions, e.g. a clamp at node 0).
    #[serde(default)]
    pub supports: Vec<SupportDesc>,
    /// Rayleigh damping [α (1/s), β (s)]: C = αM + βK (default none).
    #[serde(default)]
    pub rayleigh: [f64; 2],
    /// Mass matrix kind (default consistent).
    #[serde(default)]
    pub mass: MassKindDesc,
}

/// Material of a beam.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeamMaterial {
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Density, kg/m³.
    pub density: f64,
    /// Poisson's ratio (default 0.3).
    #[serde(default = "default_poisson")]
    pub poisson_ratio: f64,
}

fn default_poisson() -> f64 {
    0.3
}

/// Cross-section of a beam.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum SectionDesc {
    /// Solid rectangle: width (out of plane) and depth (in the bending plane), m.
    Rectangular {
        /// Width, m.
        width: f64,
        /// Depth in the bending plane, m.
        depth: f64,
    },
    /// Solid circle of diameter d, m.
    Circular {
        /// Diameter, m.
        diameter: f64,
    },
    /// Circular tube, m.
    Tube {
        /// Outer diameter, m.
        outer_diameter: f64,
        /// Wall thickness, m.
        wall: f64,
    },
    /// Area (m²), second moment of area (m⁴) and depth (m) given directly.
    General {
        /// Area, m².
        area: f64,
        /// Second moment of area about the bending axis, m⁴.
        second_moment: f64,
        /// Depth in the bending plane (for the faces), m.
        depth: f64,
    },
}

/// A support of a beam node.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SupportDesc {
    /// Node index (0 at `start`).
    pub node: usize,
    /// Kind of support.
    #[serde(rename = "type")]
    pub kind: SupportKind,
}

/// Kinds of beam supports (clr-beam `Support`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SupportKind {
    /// u = v = θ = 0.
    Clamped,
    /// u = v = 0.
    Pinned,
    /// v = 0 (rolls along x).
    RollerX,
    /// u = 0 (rolls along y).
    RollerY,
    /// No constraint.
    Free,
}

/// Mass matrix kind of a beam.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MassKindDesc {
    /// Consistent mass (default).
    #[default]
    Consistent,
    /// HRZ lumped mass.
    Lumped,
}

/// How a floating-frame body's elastic field is reduced (clr-beam).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum Reduction {
    /// The `modes` lowest modes of the supported beam (e.g. cantilever modes).
    Modal {
        /// Number of modes kept.
        modes: usize,
    },
    /// Craig–Bampton: static constraint modes of the `interface_nodes` plus `modes` fixed-
    /// interface modes.
    CraigBampton {
        /// Interface nodes (where joints attach).
        interface_nodes: Vec<usize>,
        /// Fixed-interface modes kept.
        modes: usize,
    },
}

/// Most elements of one beam (its dense matrices of 3 (n + 1) rows stay below 100 MB).
pub const MAX_ELEMENTS: usize = 1000;

impl BeamMesh {
    /// Build the clr-beam model; `path` names the field in messages.
    ///
    /// # Errors
    /// [`FieldError`] at the offending field, with clr-beam's message.
    pub fn build(&self, path: &str) -> Result<BeamModel, FieldError> {
        let e = |field: &str| {
            let p = format!("{path}.{field}");
            move |e: clr_beam::BeamError| FieldError::new(p.clone(), e.to_string())
        };
        if self.elements == 0 {
            return Err(FieldError::new(
                format!("{path}.elements"),
                "give at least one element",
            ));
        }
        // the beam's matrices are assembled dense (3 DOF per node): a mesh beyond this would
        // ask for gigabytes (found by `cargo xtask fuzz`)
        if self.elements > MAX_ELEMENTS {
            return Err(FieldError::new(
                format!("{path}.elements"),
                format!(
                    "`elements` = {} is more than the {MAX_ELEMENTS} elements a beam may have",
                    self.elements
                ),
            ));
        }
        let m = &self.material;
        let mat =
            Material::new(m.youngs_modulus, m.density, m.poisson_ratio).map_err(e("material"))?;
        let sec = match self.section {
            SectionDesc::Rectangular { width, depth } => Section::rectangular(width, depth),
            SectionDesc::Circular { diameter } => Section::circular(diameter),
            SectionDesc::Tube {
                outer_diameter,
                wall,
            } => Section::tube(outer_diameter, wall),
            SectionDesc::General {
                area,
                second_moment,
                depth,
            } => Section::new(area, second_moment, depth),
        }
        .map_err(e("section"))?;
        let mut model =
            BeamModel::straight(self.start, self.end, self.elements, mat, sec).map_err(e("end"))?;
        for (k, s) in self.supports.iter().enumerate() {
            let kind = match s.kind {
                SupportKind::Clamped => Support::Clamped,
                SupportKind::Pinned => Support::Pinned,
                SupportKind::RollerX => Support::RollerX,
                SupportKind::RollerY => Support::RollerY,
                SupportKind::Free => Support::Free,
            };
            model
                .support(s.node, kind)
                .map_err(e(&format!("supports[{k}].node")))?;
        }
        let [a, b] = self.rayleigh;
        if !(a.is_finite() && a >= 0.0 && b.is_finite() && b >= 0.0) {
            return Err(FieldError::new(
                format!("{path}.rayleigh"),
                format!("Rayleigh [α, β] = [{a}, {b}] must be finite and ≥ 0"),
            ));
        }
        model.set_rayleigh(a, b);
        model.set_mass_kind(match self.mass {
            MassKindDesc::Consistent => MassKind::Consistent,
            MassKindDesc::Lumped => MassKind::Lumped,
        });
        Ok(model)
    }
}

impl Reduction {
    /// Reduce `model`; `path` names the field in messages.
    ///
    /// # Errors
    /// [`FieldError`] with clr-beam's message.
    pub fn reduce(&self, model: &BeamModel, path: &str) -> Result<ReducedModel, FieldError> {
        match self {
            Reduction::Modal { modes } => model.modal_truncation(*modes),
            Reduction::CraigBampton {
                interface_nodes,
                modes,
            } => model.craig_bampton(interface_nodes, *modes),
        }
        .map_err(|e| FieldError::new(path.to_string(), e.to_string()))
    }
}
