//! `[[shape]]`: a contact shape attached to a body, the ground or a beam node (clr-contact
//! [`Shape`] with parry2d-f64 as the geometry engine). Shapes do nothing on their own; a
//! `[[clearance]] type = "contact"` element ([`super::shape_contact`]) puts two of them in
//! contact.

use clr_contact::{ContactShape, InvoluteGear, Shape};
use serde::{Deserialize, Serialize};

use super::{Anchor, Compiler};
use crate::error::MbdError;
use crate::face_pair::FaceSource;
use crate::shape_pair::PlacedShape;

/// `[[shape]]`: a named shape on a body. Its frame sits at `at` turned by `angle` from the body's
/// x axis; the geometry is written in that frame (m, rad).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShapeDesc {
    /// Unique name (contact elements refer to it).
    pub name: String,
    /// Origin of the shape frame: a named point, `{ body, at }` (the ground is `"ground"`) or a
    /// beam node `{ beam, node }` (the shape then moves with the node's small-rotation frame).
    /// Required for every geometry but `beam_face`, which follows its beam and refuses it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<Anchor>,
    /// Angle of the shape frame from the body's x axis, rad.
    #[serde(default)]
    pub angle: f64,
    /// The geometry in the shape frame.
    pub geometry: Geometry,
}

/// The geometry of a shape, tagged by `type` (m, rad).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum Geometry {
    /// A disc centred on the shape origin.
    Ball {
        /// Radius, m.
        radius: f64,
    },
    /// A segment along the shape x axis from −`half_length` to `half_length`, dilated by
    /// `radius` (a stadium).
    Capsule {
        /// Half length of the core segment, m.
        half_length: f64,
        /// Radius, m.
        radius: f64,
    },
    /// A rectangle centred on the shape origin.
    Cuboid {
        /// Half widths along the shape x and y axes, m.
        half_extents: [f64; 2],
    },
    /// A convex polygon, vertices counter-clockwise, m.
    ConvexPolygon {
        /// Vertices, counter-clockwise, first not repeated.
        points: Vec<[f64; 2]>,
    },
    /// An open chain of segments (a cam profile, a wall), m; contact from either side.
    Polyline {
        /// Vertices in order.
        points: Vec<[f64; 2]>,
    },
    /// Convex parts (ball, capsule, cuboid, convex polygon, involute gear teeth excluded) at
    /// poses in the shape frame.
    Compound {
        /// The parts.
        parts: Vec<Part>,
    },
    /// A spur gear with involute teeth (clr-contact [`InvoluteGear`]): a core disc of the root
    /// radius and one convex polygon per tooth, tooth 0 on the shape x axis.
    InvoluteGear {
        /// Module m, m (pitch radius m·z/2).
        module: f64,
        /// Number of teeth z.
        teeth: u32,
        /// Pressure angle α, rad (default 20° = 0.3490659 rad).
        #[serde(default = "default_pressure_angle")]
        pressure_angle: f64,
        /// Circumferential thinning of this gear's tooth at the pitch circle, m (default 0; a pair
        /// with backlash j_t gives each gear j_t/2).
        #[serde(default)]
        backlash: f64,
        /// Addendum coefficient (× module, default 1).
        #[serde(default = "one")]
        addendum: f64,
        /// Dedendum coefficient (× module, default 1.25).
        #[serde(default = "default_dedendum")]
        dedendum: f64,
        /// Vertices per involute flank (default 24; the chord error falls as its square).
        #[serde(default = "default_flank_points")]
        points_per_flank: u32,
    },
    /// A face of a flexible beam (`[[beam]]` or `[[flexible_body]]`) along its deformed shape:
    /// segments through samples of the face, rebuilt at every evaluation. Only as the first
    /// shape (A) of a contact element, against a rigid shape; no `at` or `angle`.
    BeamFace {
        /// The beam's name.
        beam: String,
        /// Which face.
        face: super::slider_on_beam::FaceDesc,
        /// Samples per element (default 4: the segments' chord error falls as its square).
        #[serde(default = "default_face_samples")]
        samples_per_element: usize,
    },
}

fn default_face_samples() -> usize {
    4
}

fn default_pressure_angle() -> f64 {
    20f64.to_radians()
}
fn one() -> f64 {
    1.0
}
fn default_dedendum() -> f64 {
    1.25
}
fn default_flank_points() -> u32 {
    24
}

/// One convex part of a compound shape.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Part {
    /// Origin of the part in the shape frame, m.
    #[serde(default)]
    pub at: [f64; 2],
    /// Angle of the part from the shape x axis, rad.
    #[serde(default)]
    pub angle: f64,
    /// The part's geometry (convex: ball, capsule, cuboid or convex polygon).
    pub geometry: Geometry,
}

impl Geometry {
    /// The clr-contact shape description (validated by the constructors).
    ///
    /// # Errors
    /// The clr-contact message saying what to change.
    pub fn to_shape(&self) -> Result<Shape, clr_contact::ContactError> {
        match self {
            Self::Ball { radius } => Shape::ball(*radius),
            Self::Capsule {
                half_length,
                radius,
            } => Shape::capsule(*half_length, *radius),
            Self::Cuboid { half_extents } => Shape::cuboid(half_extents[0], half_extents[1]),
            Self::ConvexPolygon { points } => Shape::convex_polygon(points.clone()),
            Self::Polyline { points } => Shape::polyline(points.clone()),
            Self::Compound { parts } => Shape::compound(
                parts
                    .iter()
                    .map(|p| Ok(([p.at[0], p.at[1], p.angle], p.geometry.to_shape()?)))
                    .collect::<Result<_, clr_contact::ContactError>>()?,
            ),
            Self::InvoluteGear {
                module,
                teeth,
                pressure_angle,
                backlash,
                addendum,
                dedendum,
                points_per_flank,
            } => InvoluteGear {
                module: *module,
                teeth: *teeth,
                pressure_angle: *pressure_angle,
                addendum: *addendum,
                dedendum: *dedendum,
                backlash: *backlash,
                points_per_flank: *points_per_flank,
            }
            .shape(),
            Self::BeamFace { .. } => Err(clr_contact::ContactError::invalid(
                "contact shape",
                "geometry",
                f64::NAN,
                "a beam_face follows its beam's deformed face and has no rigid shape",
            )),
        }
    }
}

/// A compiled `[[shape]]`: rigid, or the face of a flexible beam (with the frame of its beam:
/// the ground or the floating body).
#[derive(Clone)]
pub(crate) enum Placed {
    Rigid(PlacedShape),
    Face(usize, FaceSource),
}

impl ShapeDesc {
    /// Validate and register the shape in the compiler under its name.
    pub(crate) fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        if !self.angle.is_finite() {
            return Err(MbdError::Invalid {
                path: format!("{name}.angle"),
                message: format!("{} rad must be finite", self.angle),
            });
        }
        let placed = match (&self.geometry, &self.at) {
            (Geometry::BeamFace { .. }, Some(_)) => {
                return Err(MbdError::Invalid {
                    path: format!("{name}.at"),
                    message: "a beam_face follows its beam: remove `at`".into(),
                })
            }
            (
                Geometry::BeamFace {
                    beam,
                    face,
                    samples_per_element,
                },
                None,
            ) => self.face(c, beam, *face, *samples_per_element)?,
            (_, None) => {
                return Err(MbdError::Invalid {
                    path: format!("{name}.at"),
                    message: "missing field `at`: where the shape sits, e.g. \
                              { body = \"link\", at = [0.1, 0.0] } (m)"
                        .into(),
                })
            }
            (geometry, Some(at)) => {
                let (frame, arm) = c.anchor(name, "at", at)?;
                let shape = geometry
                    .to_shape()
                    .and_then(ContactShape::new)
                    .map_err(|source| MbdError::Contact {
                        item: format!("{name}.geometry"),
                        source,
                    })?;
                let chord = chord(geometry, shape.desc());
                Placed::Rigid(PlacedShape {
                    frame,
                    arm,
                    angle: self.angle,
                    shape,
                    chord,
                })
            }
        };
        c.shapes.insert(name.clone(), placed);
        Ok(())
    }

    fn face(
        &self,
        c: &Compiler,
        beam: &str,
        face: super::slider_on_beam::FaceDesc,
        samples: usize,
    ) -> Result<Placed, MbdError> {
        let name = &self.name;
        if self.angle != 0.0 {
            return Err(MbdError::Invalid {
                path: format!("{name}.angle"),
                message: "a beam_face has no angle of its own: remove `angle`".into(),
            });
        }
        if !(1..=64).contains(&samples) {
            return Err(MbdError::Invalid {
                path: format!("{name}.geometry.samples_per_element"),
                message: format!("{samples} must be between 1 and 64"),
            });
        }
        let (beam, frame, path, n_full) = c.flexible_face(&format!("{name}.geometry"), beam)?;
        Ok(Placed::Face(
            frame,
            FaceSource {
                beam,
                path,
                face: face.into(),
                n_full,
                samples,
            },
        ))
    }
}

/// [`PlacedShape::chord`] of a geometry built into `shape`.
fn chord(geometry: &Geometry, shape: &Shape) -> f64 {
    let edges = |pts: &[[f64; 2]], closed: bool| -> Vec<f64> {
        let n = pts.len();
        let m = if closed { n } else { n - 1 };
        (0..m)
            .map(|k| {
                let (a, b) = (pts[k], pts[(k + 1) % n]);
                (b[0] - a[0]).hypot(b[1] - a[1])
            })
            .collect()
    };
    match (geometry, shape) {
        (Geometry::Polyline { points }, _) => edges(points, false).into_iter().fold(0.0, f64::max),
        (Geometry::InvoluteGear { .. }, Shape::Compound { parts }) => {
            // most edges of a tooth polygon are flank chords: their median
            let mut all: Vec<f64> = parts
                .iter()
                .filter_map(|(_, p)| match p {
                    Shape::ConvexPolygon { points } => Some(edges(points, true)),
                    _ => None,
                })
                .flatten()
                .collect();
            all.sort_by(f64::total_cmp);
            all.get(all.len() / 2).copied().unwrap_or(0.0)
        }
        _ => 0.0,
    }
}
