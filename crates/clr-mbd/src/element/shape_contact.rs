//! Contact between two shapes (`[[clearance]] type = "contact"`): stops, cams and followers,
//! gear teeth, blocks in housings. The geometry comes from parry2d-f64 through clr-contact
//! [`contact_points`](clr_contact::contact_points); any normal and friction law of clr-contact
//! acts at each contact point; onsets are located as events and impacts reported as for the
//! clearance joints. Runtime form and conventions: `crate::shape_pair`.

use serde::{Deserialize, Serialize};

use super::shape::Placed;
use super::{Compiler, Element};
use crate::clearance::{Clearance as Runtime, ClearanceKind};
use crate::desc::laws::{FrictionSpec, NormalSpec};
use crate::error::MbdError;
use crate::face_pair::FacePair;
use crate::shape_pair::{PairSettings, ShapePair, Side};

/// `type = "contact"`: two `[[shape]]`s in contact. The normal points from `shapes[0]` (A) to
/// `shapes[1]` (B).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShapeContact {
    /// Unique name.
    pub name: String,
    /// The two shapes (names of `[[shape]]` items) on different bodies.
    pub shapes: [String; 2],
    /// Normal-force law of each contact point (`hertz`, `power` or `linear` with `stiffness`:
    /// the element gives no radii to material-based laws).
    pub normal: NormalSpec,
    /// Friction law of each contact point (default none; LuGre is refused).
    #[serde(default)]
    pub friction: FrictionSpec,
    /// Gap within which points are tracked before they touch, m (default a tenth of the smaller
    /// shape's bounding radius). Larger than the relative motion of one step near contact.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prediction: Option<f64>,
    /// Points of one contact patch closer than this are merged into the deepest, m (default:
    /// twice the longest segment of a polyline or the median flank chord of a gear in the
    /// pair, else 0: only coincident points).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub merge_distance: Option<f64>,
    /// Most contact points at once (default 4; each has its own impact memory).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_points: Option<usize>,
}

impl Element for ShapeContact {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        let placed = |k: usize| {
            c.shapes
                .get(&self.shapes[k])
                .cloned()
                .ok_or_else(|| MbdError::Invalid {
                    path: format!("{name}.shapes[{k}]"),
                    message: format!(
                        "no [[shape]] named `{}`; known shapes: {}",
                        self.shapes[k],
                        c.shape_names()
                    ),
                })
        };
        let (a, b) = (placed(0)?, placed(1)?);
        let Placed::Rigid(b) = b else {
            return Err(MbdError::Invalid {
                path: format!("{name}.shapes[1]"),
                message: "a beam_face can only be the first shape (A) of a contact, against a \
                          rigid shape: swap the two names (the normal then points from the face \
                          to the other shape)"
                    .into(),
            });
        };
        let normal = self.normal.build(&format!("{name}.normal"), None)?;
        let friction = self.friction.build(&format!("{name}.friction"))?;
        let (i, kind) = match a {
            Placed::Rigid(a) => {
                c.distinct(name, a.frame, b.frame)?;
                let size = a.shape.bounding_radius().min(b.shape.bounding_radius());
                let merge = 2.0 * a.chord.max(b.chord);
                let pair = ShapePair::new(&a, &b, self.settings(size, merge)?);
                pair.check_query().map_err(|source| MbdError::Contact {
                    item: name.clone(),
                    source,
                })?;
                (a.frame, ClearanceKind::Shapes(Box::new(pair)))
            }
            Placed::Face(frame, src) => {
                c.distinct(name, frame, b.frame)?;
                // the face's samples are its natural scale for merging
                let step = face_step(&src);
                let size = b.shape.bounding_radius();
                let side = Side::new(&b);
                let pair = FacePair::new(src, side, self.settings(size, 2.0 * step)?);
                (frame, ClearanceKind::FacePair(Box::new(pair)))
            }
        };
        c.clearances.push(Runtime {
            name: name.clone(),
            i,
            j: b.frame,
            kind,
            normal,
            friction,
            mem: 0,
            lugre: None,
            film: None,
        });
        Ok(())
    }
}

impl ShapeContact {
    /// The pair's settings with the defaults for shapes of size `size` (the smaller bounding
    /// radius, m) and the default merge distance `merge` (m).
    fn settings(&self, size: f64, merge: f64) -> Result<PairSettings, MbdError> {
        let name = &self.name;
        let prediction = self.prediction.unwrap_or(0.1 * size);
        let merge = self.merge_distance.unwrap_or(merge);
        super::non_negative(name, "prediction (m)", prediction)?;
        super::non_negative(name, "merge_distance (m)", merge)?;
        let max_points = self.max_points.unwrap_or(4);
        if !(1..=64).contains(&max_points) {
            return Err(MbdError::Invalid {
                path: format!("{name}.max_points"),
                message: format!("{max_points} must be between 1 and 64"),
            });
        }
        Ok(PairSettings {
            prediction,
            merge,
            // a tenth of the smaller shape: far more than a contact point moves in a step
            matching: merge.max(0.1 * size),
            max_points,
        })
    }
}

/// The longest arc step between the samples of a beam face, m.
fn face_step(src: &crate::face_pair::FaceSource) -> f64 {
    let starts = src.path.element_starts();
    let ends = starts.iter().skip(1).copied().chain([src.path.length()]);
    starts
        .iter()
        .zip(ends)
        .map(|(s0, s1)| (s1 - s0) / src.samples as f64)
        .fold(0.0, f64::max)
}
