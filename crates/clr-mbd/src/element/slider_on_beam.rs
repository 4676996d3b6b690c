//! A rigid rectangular slider on a face of a flexible beam, ground-fixed (`[[beam]]`) or
//! floating (`[[flexible_body]]`): clr-contact's multipoint detection (corners, face points,
//! optional reverse check with guide samples) against the deformed beam surface from clr-beam;
//! the guide reactions become work-equivalent nodal loads of the beam (and, on a floating beam,
//! forces on its frame). Onsets are not located as events for this element.

use serde::{Deserialize, Serialize};

use super::{slider_shape, Anchor, Compiler, Element};
use crate::clearance::{Clearance as Runtime, ClearanceKind, FlexGuide};
use crate::desc::laws::{FrictionSpec, NormalSpec};
use crate::error::MbdError;
use crate::runtime::GROUND_ID;

/// Which face of a beam: `upper` (the +h/2 face on the left of the beam axis) or `lower`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FaceDesc {
    /// +h/2 face.
    Upper,
    /// −h/2 face.
    Lower,
}

impl From<FaceDesc> for clr_beam::Face {
    fn from(f: FaceDesc) -> Self {
        match f {
            FaceDesc::Upper => clr_beam::Face::Upper,
            FaceDesc::Lower => clr_beam::Face::Lower,
        }
    }
}

impl From<clr_beam::Face> for FaceDesc {
    fn from(f: clr_beam::Face) -> Self {
        match f {
            clr_beam::Face::Upper => FaceDesc::Upper,
            clr_beam::Face::Lower => FaceDesc::Lower,
        }
    }
}

/// `type = "slider_on_beam"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SliderOnBeam {
    /// Unique name.
    pub name: String,
    /// The beam carrying the face (a `[[beam]]` or a `[[flexible_body]]`).
    pub beam: String,
    /// Slider centre on a rigid body.
    pub slider: Anchor,
    /// The beam face the slider runs on.
    pub face: FaceDesc,
    /// Slider length L, m.
    pub slider_length: f64,
    /// Slider height h, m.
    pub slider_height: f64,
    /// Angle of the slider axis from its body's x axis, rad.
    #[serde(default)]
    pub slider_angle: f64,
    /// Candidate points on each slider face besides the corners (e.g. 5).
    pub face_points: usize,
    /// Guide samples of the reverse check (0 disables it).
    #[serde(default)]
    pub guide_samples: usize,
    /// Normal-force law of each contact point (the line law, e.g. `flores-line`).
    pub normal: NormalSpec,
    /// Optional area law (e.g. `area`) used instead of `normal` at every contact point, with
    /// the contact length set to the point's wetted length (continuous in the configuration):
    /// an isolated edge gets the line law, a face lying on the guide the area law integrated
    /// over the face.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub area_normal: Option<NormalSpec>,
    /// Friction law of each contact point (default none): a stateless law (`lugre` is refused).
    #[serde(default)]
    pub friction: FrictionSpec,
}

impl Element for SliderOnBeam {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        let (j, sj) = c.anchor(name, "slider", &self.slider)?;
        if j == GROUND_ID || j >= c.n_rigid() {
            return Err(MbdError::InvalidParameter {
                item: name.clone(),
                what: "slider body",
                value: f64::NAN,
                requirement: "the slider must be a rigid body (not the ground or a beam node)",
            });
        }
        let (guide_beam, guide_frame, path, nfull) =
            c.flexible_face(&format!("{name}.beam"), &self.beam)?;
        let shape = slider_shape(
            name,
            [self.slider_length, self.slider_height],
            sj,
            self.slider_angle,
        )?;
        let detector =
            clr_contact::MultipointDetector::new(shape, self.face_points, self.guide_samples)
                .map_err(|source| MbdError::Contact {
                    item: name.clone(),
                    source,
                })?;
        let normal = self.normal.build(&format!("{name}.normal"), None)?;
        let area_normal = match &self.area_normal {
            Some(a) => Some(a.build(&format!("{name}.area_normal"), None)?),
            None => None,
        };
        // stateless laws only: `lugre` is refused at `{name}.friction.law`
        let friction = self.friction.build(&format!("{name}.friction"))?;
        c.clearances.push(Runtime {
            name: name.clone(),
            i: guide_frame,
            j,
            kind: ClearanceKind::FlexGuide(Box::new(FlexGuide {
                beam: guide_beam,
                path,
                face: self.face.into(),
                area_normal,
                detector,
                qfull: vec![0.0; nfull],
                qdfull: vec![0.0; nfull],
            })),
            normal,
            friction,
            mem: 0,
            lugre: None,
            film: None,
        });
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.slider]
    }
}
