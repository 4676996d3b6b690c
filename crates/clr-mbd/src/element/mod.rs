//! Element kinds, one module each: its data (serde, the model-file form), its validation and
//! its compilation into the runtime form. Adding a kind touches its module and one line of
//! registration in a section enum below (see docs/architecture.md, "How to add an element
//! kind").

pub mod actuator;
pub mod anchor;
pub mod applied_force;
pub mod applied_torque;
mod body;
pub mod bushing;
mod compiler;
pub mod custom;
pub mod drive_angle;
pub mod drive_displacement;
pub mod fixed;
pub mod floating_body;
pub mod ground_beam;
pub mod nodal_load;
pub mod revolute;
pub mod revolute_clearance;
pub mod rotational_spring_damper;
pub mod shape;
pub mod shape_contact;
pub mod slider_on_beam;
pub mod spring_damper;
pub mod torque_between;
pub mod translational;
pub mod translational_clearance;

use clr_contact::SliderShape;
use nalgebra::Vector2;
use serde::{Deserialize, Serialize};

pub use anchor::Anchor;
pub(crate) use compiler::{Compiler, Inputs};

use crate::error::MbdError;

/// What every element kind provides to the compiler.
pub(crate) trait Element {
    /// Validate and push the runtime form into the compiler.
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError>;
    /// The anchors it refers to (beam-node anchors get node frames before compilation).
    fn anchors(&self) -> Vec<&Anchor> {
        Vec::new()
    }
    /// True when it is a Rust closure itself (cannot be written to a file; closures inside its
    /// time functions are found through [`Element::time_fns`]).
    fn has_closure(&self) -> bool {
        false
    }
    /// Its time functions, with field, unit and whether each is a driver's motion (to bind
    /// `[[input]]` references).
    fn time_fns(&mut self) -> Vec<crate::input::TimeFnSlot<'_>> {
        Vec::new()
    }
}

/// A section of the description: an enum of element kinds tagged by `type` in a file, with
/// name, kind and dispatch to the kind's module.
macro_rules! section {
    ($(#[$m:meta])* $enum:ident {
        $($(#[$vm:meta])* $var:ident($ty:ty) = $tag:literal,)*
        $(@code $(#[$cm:meta])* $cvar:ident($cty:ty) = $ctag:literal,)?
    }) => {
        $(#[$m])*
        // element descriptions are few and read once at compile: their size does not matter
        #[allow(clippy::large_enum_variant)]
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
        #[serde(tag = "type")]
        pub enum $enum {
            $($(#[$vm])* #[serde(rename = $tag)] $var($ty),)*
            $($(#[$cm])* #[serde(skip)] $cvar($cty),)?
        }
        impl $enum {
            /// The kinds a file can give as `type`.
            pub const KINDS: &'static [&'static str] = &[$($tag,)*];
            /// The element's name.
            pub fn name(&self) -> &str {
                match self { $(Self::$var(e) => &e.name,)* $(Self::$cvar(e) => &e.name,)? }
            }
            /// The element's kind as written in a file (`type`).
            pub fn kind(&self) -> &'static str {
                match self { $(Self::$var(_) => $tag,)* $(Self::$cvar(_) => $ctag,)? }
            }
            /// True when it holds a Rust closure: a closure element, or a time function that
            /// is one (read on a copy: this is asked once, when a description is written).
            pub fn has_closure(&self) -> bool {
                let own = match self {
                    $(Self::$var(e) => e.has_closure(),)*
                    $(Self::$cvar(e) => e.has_closure(),)?
                };
                own || self.clone().time_fns().iter().any(|s| s.f.has_closure())
            }
            /// Its time functions (field, unit, motion or load), to bind `[[input]]`s.
            pub(crate) fn time_fns(&mut self) -> Vec<crate::input::TimeFnSlot<'_>> {
                match self {
                    $(Self::$var(e) => e.time_fns(),)*
                    $(Self::$cvar(e) => e.time_fns(),)?
                }
            }
            /// Read one item of a file (a table with its `type`), with the path of the
            /// offending field relative to the item on error (`normal.restitution`): serde's
            /// internally tagged enums buffer the item and lose that path.
            ///
            /// # Errors
            /// [`FieldError`](crate::field::FieldError) with the relative path and serde's
            /// message.
            pub fn from_toml(item: toml::Value) -> Result<Self, crate::field::FieldError> {
                let mut table = match item {
                    toml::Value::Table(t) => t,
                    other => {
                        return Err(crate::field::FieldError::new(
                            "",
                            format!("expected a table, got `{other}`"),
                        ))
                    }
                };
                let tag = match table.remove("type") {
                    Some(toml::Value::String(s)) => s,
                    Some(other) => {
                        return Err(crate::field::FieldError::new(
                            "type",
                            format!("expected a string, got `{other}`"),
                        ))
                    }
                    None => return Err(crate::field::FieldError::new("type", "missing field `type`")),
                };
                let body = toml::Value::Table(table);
                let err = |e: serde_path_to_error::Error<toml::de::Error>| {
                    let path = e.path().to_string();
                    let path = if path == "." { String::new() } else { path };
                    crate::field::FieldError::new(path, e.inner().message().to_string())
                };
                match tag.as_str() {
                    $($tag => serde_path_to_error::deserialize::<_, $ty>(body)
                        .map(Self::$var)
                        .map_err(err),)*
                    other => Err(crate::field::FieldError::new(
                        "type",
                        format!("unknown variant `{other}`, expected one of {}",
                            Self::KINDS.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ")),
                    )),
                }
            }
            pub(crate) fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
                match self {
                    $(Self::$var(e) => e.compile(c),)*
                    $(Self::$cvar(e) => e.compile(c),)?
                }
            }
            pub(crate) fn anchors(&self) -> Vec<&Anchor> {
                match self {
                    $(Self::$var(e) => e.anchors(),)*
                    $(Self::$cvar(e) => e.anchors(),)?
                }
            }
        }
        $(impl From<$ty> for $enum {
            fn from(e: $ty) -> Self { Self::$var(e) }
        })*
        $(impl From<$cty> for $enum {
            fn from(e: $cty) -> Self { Self::$cvar(e) }
        })?
    };
}

pub(crate) use section;

section! {
    /// `[[joint]]`: ideal joints (constraint equations).
    Joint {
        /// Revolute joint.
        Revolute(revolute::Revolute) = "revolute",
        /// Fixed joint.
        Fixed(fixed::Fixed) = "fixed",
        /// Translational joint.
        Translational(translational::Translational) = "translational",
    }
}

section! {
    /// `[[driver]]`: prescribed motions (rheonomic constraints).
    Driver {
        /// Absolute angle.
        Angle(drive_angle::DriveAngle) = "angle",
        /// Relative angle.
        RelativeAngle(drive_angle::DriveRelativeAngle) = "relative_angle",
        /// Relative displacement along an axis.
        Displacement(drive_displacement::DriveDisplacement) = "displacement",
    }
}

section! {
    /// `[[force]]`: force elements.
    Force {
        /// Translational spring–damper.
        SpringDamper(spring_damper::SpringDamper) = "spring_damper",
        /// Rotational spring–damper.
        RotationalSpringDamper(rotational_spring_damper::RotationalSpringDamper) = "rotational_spring_damper",
        /// Point-to-point actuator (axial force of time).
        Actuator(actuator::Actuator) = "actuator",
        /// Linear bushing from a ground point to a body point.
        Bushing(bushing::Bushing) = "bushing",
        /// Applied force.
        Force(applied_force::AppliedForce) = "force",
        /// Applied torque.
        Torque(applied_torque::AppliedTorque) = "torque",
        /// Torque between two bodies.
        TorqueBetween(torque_between::TorqueBetween) = "torque_between",
        /// Nodal load on a beam.
        NodalLoad(nodal_load::NodalLoad) = "nodal_load",
        @code
        /// A Rust closure (opt-in; not in files).
        Custom(custom::CustomForce) = "custom",
    }
}

section! {
    /// `[[clearance]]`: contact elements (force elements, no constraint equation).
    Clearance {
        /// Revolute clearance joint.
        Revolute(revolute_clearance::RevoluteClearance) = "revolute",
        /// Translational clearance joint.
        Translational(translational_clearance::TranslationalClearance) = "translational",
        /// Slider on a flexible beam face.
        SliderOnBeam(slider_on_beam::SliderOnBeam) = "slider_on_beam",
        /// Contact between two `[[shape]]`s.
        Contact(shape_contact::ShapeContact) = "contact",
    }
}

impl Clearance {
    /// True for a revolute or translational clearance joint of clearance 0, which compiles as
    /// its ideal joint (its contact laws act on nothing); a slider on a beam or a shape contact
    /// with no gap is touching, not ideal.
    pub fn is_ideal(&self) -> bool {
        match self {
            Clearance::Revolute(r) => r.is_ideal(),
            Clearance::Translational(t) => t.is_ideal(),
            Clearance::SliderOnBeam(_) | Clearance::Contact(_) => false,
        }
    }
}

/// A clr-contact slider rectangle (length, height in m) centred at `centre` on its body.
pub(crate) fn slider_shape(
    item: &str,
    size: [f64; 2],
    centre: Vector2<f64>,
    angle: f64,
) -> Result<SliderShape, MbdError> {
    SliderShape::new(size[0], size[1], centre, angle).map_err(|source| MbdError::Contact {
        item: item.to_string(),
        source,
    })
}

pub(crate) fn ground_load(item: &str) -> MbdError {
    MbdError::InvalidParameter {
        item: item.to_string(),
        what: "body index",
        value: f64::NAN,
        requirement: "a load on the ground does nothing; attach it to a moving body",
    }
}

/// `Ok` when `v` is positive and finite, else an error at the field `{item}.{field}` (m for
/// the lengths this checks).
pub(crate) fn positive_length(item: &str, field: &str, v: f64) -> Result<(), MbdError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(MbdError::Invalid {
            path: format!("{item}.{field}"),
            message: format!("{v} m must be positive and finite"),
        })
    }
}

pub(crate) fn non_negative(item: &str, what: &'static str, v: f64) -> Result<(), MbdError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(MbdError::InvalidParameter {
            item: item.to_string(),
            what,
            value: v,
            requirement: "must be finite and not negative",
        })
    }
}

pub(crate) fn unit_axis(item: &str, axis: [f64; 2]) -> Result<Vector2<f64>, MbdError> {
    let v = Vector2::new(axis[0], axis[1]);
    let n = v.norm();
    if n.is_finite() && n > 0.0 {
        Ok(v / n)
    } else {
        Err(MbdError::InvalidParameter {
            item: item.to_string(),
            what: "axis length (local coordinates)",
            value: n,
            requirement: "the axis must be a finite non-zero vector",
        })
    }
}
