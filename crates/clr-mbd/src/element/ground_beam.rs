//! Ground-fixed flexible beam: the free nodal DOF of a straight clr-beam mesh become
//! coordinates of the model (see the `flexible` module docs); its supports fix it to the
//! ground.

use serde::{Deserialize, Serialize};

use crate::desc::beam::{BeamMaterial, BeamMesh, MassKindDesc, SectionDesc, SupportDesc};
use crate::error::MbdError;
use crate::flexible::FlexBeam;

/// `[[beam]]`: a name and the fields of a [`BeamMesh`], in world coordinates.
///
/// The mesh fields are repeated here rather than `#[serde(flatten)]`ed because serde ignores
/// `deny_unknown_fields` through a flatten, and a misspelt beam field must be refused.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundBeam {
    /// Unique name.
    pub name: String,
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
    /// Supports by node (they fix the beam to the ground).
    #[serde(default)]
    pub supports: Vec<SupportDesc>,
    /// Rayleigh damping [α (1/s), β (s)] (default none).
    #[serde(default)]
    pub rayleigh: [f64; 2],
    /// Mass matrix kind (default consistent).
    #[serde(default)]
    pub mass: MassKindDesc,
}

impl GroundBeam {
    /// A named beam from a mesh.
    pub fn new(name: &str, m: BeamMesh) -> Self {
        Self {
            name: name.to_string(),
            start: m.start,
            end: m.end,
            elements: m.elements,
            material: m.material,
            section: m.section,
            supports: m.supports,
            rayleigh: m.rayleigh,
            mass: m.mass,
        }
    }

    /// The mesh.
    pub fn mesh(&self) -> BeamMesh {
        BeamMesh {
            start: self.start,
            end: self.end,
            elements: self.elements,
            material: self.material,
            section: self.section,
            supports: self.supports.clone(),
            rayleigh: self.rayleigh,
            mass: self.mass,
        }
    }

    /// Build the runtime form; `path` names this entry in messages (e.g. `beam[0]`).
    pub(crate) fn compile(&self, path: &str) -> Result<FlexBeam, MbdError> {
        let model = self.mesh().build(path)?;
        FlexBeam::new(&self.name, &model)
    }
}
