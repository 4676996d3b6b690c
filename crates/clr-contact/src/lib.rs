//! Contact force laws, friction laws, planar clearance-joint kinematics, the spatial
//! journal-in-bearing clearance joint ([`journal`]), and shape contact in the plane ([`shapes`])
//! and in space ([`shapes3d`]).
//!
//! `clr-contact` is meant to be embedded in other codes as much as used inside clr: plain `f64`
//! functions and small validated structs, SI units everywhere, no allocation in force
//! evaluations, and no dependency on the other clr crates.
//!
//! Conventions (see `docs/contact.md`):
//! - δ is the penetration in m, positive in contact;
//! - δ̇ is the penetration rate in m/s, positive while approaching (compression);
//! - δ̇⁻ is δ̇ at the onset of the current contact (stored per contact, see [`memory`]);
//! - σ_k = (1 − ν_k²)/E_k and the composite modulus E* = 1/(σ_i + σ_j), in Pa.

pub mod error;

// Normal-force and friction laws.
pub mod damping;
pub mod elastic;
pub mod friction;
pub mod lubrication;
pub mod normal;
pub mod restitution;

// Geometry, kinematics and contact state.
pub mod body;
pub mod gears;
pub mod journal;
pub mod journal_film;
pub mod journal_wear;
pub mod memory;
pub mod multipoint;
pub mod revolute;
pub mod shapes;
pub mod shapes3d;
pub mod translational;
pub mod wear;

pub use error::ContactError;

pub use body::{BodyState, GeneralizedForce};
pub use gears::InvoluteGear;
pub use journal::{JournalClearance, JournalError, JournalLaws, JournalState};
pub use memory::ContactMemory;
pub use multipoint::{
    ContactClass, GuideSurface, MultipointDetector, SineGuide, SliderShape, StraightGuide,
};
pub use revolute::{ForceApplication, RevoluteClearance, RevoluteContact};
pub use shapes::{
    boxes_gap, boxes_overlap, contact_points, segment_contact_points, shape_distance, ContactShape,
    Feature, Shape, ShapeContactPoint, ShapeContactWorkspace,
};
pub use shapes3d::{
    boxes_gap3, boxes_overlap3, contact_points3, shape_distance3, BodyState3, ContactShape3,
    Feature3, PartPose3, Shape3, ShapeContactPoint3, ShapeContactWorkspace3,
};
pub use translational::{Configuration, TranslationalClearance, TranslationalContact};
pub use wear::{ArchardWear, BearingProfile, LineContact, PressureDistribution};

pub use damping::DampingFactor;
pub use elastic::{ElasticLaw, Material};
pub use friction::{FrictionLaw, LuGre};
pub use lubrication::{BearingModel, HydrodynamicBearing, PiFilm, Transition};
pub use normal::{GuideFace, JournalBearing, NormalLaw};
