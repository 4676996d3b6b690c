//! Compile the `[[shape]]`s and the `[[clearance]] type = "contact"` elements of a spatial model
//! into [`ShapeContact3`]s: names resolved (with did-you-mean), geometry validated by
//! clr-contact, laws built, settings defaulted as the planar shape contact's. The body ends and
//! orientations are resolved by the caller's functions (the model compiler's), so that this
//! module depends on nothing above it.

use std::collections::HashMap;

use clr_contact::{ContactShape3, PartPose3, Shape3};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

use super::desc::{
    End, Geometry3, Orientation, ShapeContactDesc3, SpatialClearance, SpatialDesc, SpatialShape,
};
use super::shape_contact::{ShapeContact3, Side3};
use crate::desc::laws::ContactFriction;
use crate::error::MbdError;
use crate::shape_pair::PairSettings;

/// Resolves an end at a path: (body index, point from the centre of mass in the body frame,
/// whether an axis was given).
pub(crate) type ResolveEnd<'a> =
    &'a dyn Fn(&str, &End) -> Result<(usize, Vector3<f64>, bool), MbdError>;
/// Resolves an orientation at a path to its rotation matrix.
pub(crate) type ResolveOrientation<'a> =
    &'a dyn Fn(&str, &Orientation) -> Result<Matrix3<f64>, MbdError>;

fn invalid(path: impl Into<String>, message: impl Into<String>) -> MbdError {
    MbdError::Invalid {
        path: path.into(),
        message: message.into(),
    }
}

/// The shape contacts of `d`, their memory slots from `first_slot` on.
pub(crate) fn contacts(
    end: ResolveEnd<'_>,
    orientation: ResolveOrientation<'_>,
    d: &SpatialDesc,
    first_slot: usize,
) -> Result<Vec<ShapeContact3>, MbdError> {
    let mut shapes = HashMap::new();
    for s in &d.shapes {
        let side = shape(end, orientation, s)?;
        if shapes.insert(s.name.clone(), side).is_some() {
            return Err(MbdError::DuplicateName {
                name: s.name.clone(),
                first: "shape",
                second: "shape",
            });
        }
    }
    let mut out = Vec::new();
    let mut slot = first_slot;
    for c in &d.clearances {
        if let SpatialClearance::Contact(c) = c {
            let contact = contact(&shapes, c, slot)?;
            slot += contact.settings.max_points;
            out.push(contact);
        }
    }
    Ok(out)
}

/// Compile one `[[shape]]`.
fn shape(
    end: ResolveEnd<'_>,
    orientation: ResolveOrientation<'_>,
    s: &SpatialShape,
) -> Result<Side3, MbdError> {
    let name = &s.name;
    let (body, arm, axis) = end(&format!("{name}.at"), &s.at)?;
    if axis {
        return Err(invalid(
            format!("{name}.at.axis"),
            "a shape's place has no axis: turn the shape with `orientation` (its axially \
             symmetric kinds lie along the shape x axis)",
        ));
    }
    let rot = match &s.orientation {
        Some(o) => quaternion(&orientation(&format!("{name}.orientation"), o)?),
        None => UnitQuaternion::identity(),
    };
    let desc = to_shape3(orientation, &format!("{name}.geometry"), &s.geometry)?;
    let shape = ContactShape3::new(desc).map_err(|source| MbdError::Contact {
        item: format!("{name}.geometry"),
        source,
    })?;
    Ok(Side3 {
        name: name.clone(),
        body,
        s: arm,
        rot,
        shape,
    })
}

fn quaternion(a: &Matrix3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*a))
}

/// The clr-contact description of a geometry (compound parts' orientations resolved).
pub(crate) fn to_shape3(
    orientation: ResolveOrientation<'_>,
    path: &str,
    g: &Geometry3,
) -> Result<Shape3, MbdError> {
    Ok(match g {
        Geometry3::Ball { radius } => Shape3::Ball { radius: *radius },
        Geometry3::Capsule {
            half_length,
            radius,
        } => Shape3::Capsule {
            half_length: *half_length,
            radius: *radius,
        },
        Geometry3::Cuboid { half_extents } => Shape3::Cuboid {
            half_extents: *half_extents,
        },
        Geometry3::Cylinder {
            half_length,
            radius,
        } => Shape3::Cylinder {
            half_length: *half_length,
            radius: *radius,
        },
        Geometry3::Cone {
            half_length,
            radius,
        } => Shape3::Cone {
            half_length: *half_length,
            radius: *radius,
        },
        Geometry3::ConvexPolyhedron { points } => Shape3::ConvexPolyhedron {
            points: points.clone(),
        },
        Geometry3::Trimesh { vertices, indices } => Shape3::TriMesh {
            vertices: vertices.clone(),
            indices: indices.clone(),
        },
        Geometry3::Compound { parts } => {
            let mut out = Vec::with_capacity(parts.len());
            for (k, p) in parts.iter().enumerate() {
                let here = format!("{path}.parts[{k}]");
                let rotation = match &p.orientation {
                    Some(o) => quaternion(&orientation(&format!("{here}.orientation"), o)?)
                        .scaled_axis()
                        .into(),
                    None => [0.0; 3],
                };
                let part = to_shape3(orientation, &format!("{here}.geometry"), &p.geometry)?;
                out.push((PartPose3::new(p.at, rotation), part));
            }
            Shape3::Compound { parts: out }
        }
    })
}

/// Compile one `type = "contact"` element; `slot` is its first memory slot.
fn contact(
    shapes: &HashMap<String, Side3>,
    c: &ShapeContactDesc3,
    slot: usize,
) -> Result<ShapeContact3, MbdError> {
    let name = &c.name;
    let side = |k: usize| {
        shapes.get(&c.shapes[k]).cloned().ok_or_else(|| {
            invalid(
                format!("{name}.shapes[{k}]"),
                format!(
                    "no [[shape]] named `{}`; {}",
                    c.shapes[k],
                    crate::field::suggestion(&c.shapes[k], shapes.keys().map(String::as_str))
                ),
            )
        })
    };
    let (a, b) = (side(0)?, side(1)?);
    if a.body == b.body {
        return Err(invalid(
            format!("{name}.shapes"),
            format!(
                "`{}` and `{}` are on the same body: a contact acts between two bodies (or a \
                 body and the ground)",
                c.shapes[0], c.shapes[1]
            ),
        ));
    }
    let law = normal_law(c)?;
    let friction = stateless_friction(
        name,
        c.friction.as_ref(),
        "a shape contact",
        "contact point",
    )?;
    let size = a.shape.bounding_radius().min(b.shape.bounding_radius());
    let settings = settings(c, size)?;
    let contact = ShapeContact3::new(name.clone(), (a, b), (law, friction), settings, slot);
    contact.check_query().map_err(|source| MbdError::Contact {
        item: name.clone(),
        source,
    })?;
    Ok(contact)
}

/// The friction law of element `name` without a bristle state (`None` for none or μ = 0):
/// LuGre is refused, naming the element kind (`what`) and where the state would live (`per`).
pub(crate) fn stateless_friction(
    name: &str,
    f: Option<&crate::desc::FrictionLawDesc>,
    what: &str,
    per: &str,
) -> Result<Option<clr_contact::FrictionLaw>, MbdError> {
    let Some(f) = f else { return Ok(None) };
    match f
        .build_contact(&format!("{name}.friction"))
        .map_err(|e| invalid(e.path, e.message))?
    {
        ContactFriction::Static(l) if l.mu_max() == 0.0 => Ok(None),
        ContactFriction::Static(l) => Ok(Some(l)),
        ContactFriction::LuGre(_) => Err(invalid(
            format!("{name}.friction.law"),
            format!(
                "LuGre friction is not available on {what} (its bristle state per {per} is not \
                 carried): use coulomb, ambrosio, threlfall or stribeck"
            ),
        )),
    }
}

/// The point law: `hertz`, `power` or `linear` with a stiffness (no radii to give).
fn normal_law(c: &ShapeContactDesc3) -> Result<clr_contact::NormalLaw, MbdError> {
    let path = format!("{}.normal", c.name);
    let law = c.normal.law.trim().to_ascii_lowercase().replace('_', "-");
    if !matches!(law.as_str(), "hertz" | "power" | "linear") {
        return Err(invalid(
            format!("{path}.law"),
            format!(
                "`{}` is not available for a shape contact: it gives no radii or lengths to \
                 material-based and line laws; use hertz, power or linear with `stiffness`",
                c.normal.law
            ),
        ));
    }
    c.normal
        .build(&path, None)
        .map_err(|e| invalid(e.path, e.message))
}

/// The pair's settings with the planar shape contact's defaults for shapes of size `size` (the
/// smaller bounding radius, m).
fn settings(c: &ShapeContactDesc3, size: f64) -> Result<PairSettings, MbdError> {
    let name = &c.name;
    let prediction = c.prediction.unwrap_or(0.1 * size);
    let merge = c.merge_distance.unwrap_or(0.0);
    for (f, v) in [("prediction", prediction), ("merge_distance", merge)] {
        if !(v >= 0.0 && v.is_finite()) {
            return Err(invalid(
                format!("{name}.{f}"),
                format!("{v} m must be finite and not negative"),
            ));
        }
    }
    let max_points = c.max_points.unwrap_or(4);
    if !(1..=64).contains(&max_points) {
        return Err(invalid(
            format!("{name}.max_points"),
            format!("{max_points} must be between 1 and 64"),
        ));
    }
    Ok(PairSettings {
        prediction,
        merge,
        // a tenth of the smaller shape: far more than a contact point moves in a step
        matching: merge.max(0.1 * size),
        max_points,
    })
}
