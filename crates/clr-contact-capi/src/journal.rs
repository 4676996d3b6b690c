//! C ABI of the spatial journal-in-bearing clearance joint (clr-contact `journal`,
//! docs/contact.md "Spatial journal in bearing"): a journal of finite length in a bore of finite
//! length, tilted and sliding axially, with the radial contact distributed along the overlap and
//! point contacts on the thrust faces, for a user's own spatial revolute or cylindrical joint.
//!
//! The caller keeps the impact velocity δ̇⁻ of each of the four contact groups (radial end A,
//! radial end B, thrust −, thrust +; `CLR_JOURNAL_*`): the group's penetration rate at its
//! first evaluation in contact, until it separates (`ClrJournalForces::penetration` and `rate`
//! give both).

use clr_contact::journal::{
    JournalClearance, JournalError, JournalFriction, JournalLaws, JournalState, GROUPS,
};
use nalgebra::Vector3;

use crate::error::{finite, CapiError};
use crate::ffi::{borrow, free_handle, new_handle, write_out, ClrFrictionLaw, ClrNormalLaw};
use crate::ClrStatus;

/// Index of the radial contact at the low-z end of the overlap in the per-group arrays.
pub const CLR_JOURNAL_RADIAL_A: u32 = 0;
/// Index of the radial contact at the high-z end.
pub const CLR_JOURNAL_RADIAL_B: u32 = 1;
/// Index of the thrust face on the −u_b side.
pub const CLR_JOURNAL_THRUST_MINUS: u32 = 2;
/// Index of the thrust face on the +u_b side.
pub const CLR_JOURNAL_THRUST_PLUS: u32 = 3;

/// Opaque handle of a journal-in-bearing joint (immutable: may be shared between threads).
pub struct ClrJournalJoint(pub(crate) JournalClearance);

/// The pose and velocity of both bodies at the joint, world frame, SI units.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ClrJournalState {
    /// Bore centre O_b, m.
    pub bearing_centre: [f64; 3],
    /// Bore axis u_b (any length > 0; normalized).
    pub bearing_axis: [f64; 3],
    /// Velocity of the bearing body's material point at O_b, m/s.
    pub bearing_velocity: [f64; 3],
    /// Angular velocity of the bearing body, rad/s.
    pub bearing_angular_velocity: [f64; 3],
    /// Journal centre O_j, m.
    pub journal_centre: [f64; 3],
    /// Journal axis u_j (normalized).
    pub journal_axis: [f64; 3],
    /// Velocity of the journal body's material point at O_j, m/s.
    pub journal_velocity: [f64; 3],
    /// Angular velocity of the journal body, rad/s.
    pub journal_angular_velocity: [f64; 3],
}

/// What the joint gives at one state: the resultant on the journal (the bearing gets −force and
/// `bearing_moment`) and each contact group's report.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ClrJournalForces {
    /// Force on the journal, N (world).
    pub force: [f64; 3],
    /// Moment on the journal about O_j, N·m.
    pub journal_moment: [f64; 3],
    /// Moment on the bearing about O_b, N·m.
    pub bearing_moment: [f64; 3],
    /// Tilt γ between the journal and bore axes, rad.
    pub tilt: f64,
    /// Largest penetration of each group, m (≤ 0: open).
    pub penetration: [f64; 4],
    /// Its rate, m/s (> 0 approaching).
    pub rate: [f64; 4],
    /// Normal force of each group, N.
    pub normal_force: [f64; 4],
    /// Force-weighted contact point of each group, m (world).
    pub point: [[f64; 3]; 4],
    /// Power dissipated by damping and friction, W.
    pub dissipated: f64,
    /// Elastic energy stored in the contact, J.
    pub elastic_energy: f64,
}

impl From<JournalError> for CapiError {
    fn from(e: JournalError) -> Self {
        match e {
            JournalError::Contact(c) => CapiError::Contact(c),
            other => CapiError::Model(other.to_string()),
        }
    }
}

/// Create a spatial revolute clearance joint: bore radius and length R_b, L_b, journal radius and
/// length R_j < R_b, L_j (m), total axial end play c_a (m) between the thrust faces, thrust
/// (collar) radius R_t (m; ≤ 0: R_j). On success `*out` receives a handle to free with
/// `clr_journal_joint_free`.
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_journal_joint_new_revolute(
    bearing_radius: f64,
    bearing_length: f64,
    journal_radius: f64,
    journal_length: f64,
    axial_clearance: f64,
    thrust_radius: f64,
    out: *mut *mut ClrJournalJoint,
) -> ClrStatus {
    new_handle(out, || {
        let rt = finite("thrust_radius (m)", thrust_radius)?;
        let joint = JournalClearance::revolute(
            finite("bearing_radius (m)", bearing_radius)?,
            finite("bearing_length (m)", bearing_length)?,
            finite("journal_radius (m)", journal_radius)?,
            finite("journal_length (m)", journal_length)?,
            finite("axial_clearance (m)", axial_clearance)?,
            (rt > 0.0).then_some(rt),
        )?;
        Ok(ClrJournalJoint(joint))
    })
}

/// Create a spatial cylindrical clearance joint (no thrust faces): bore radius and length, journal
/// radius and length (m). On success `*out` receives a handle to free with
/// `clr_journal_joint_free`.
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_journal_joint_new_cylindrical(
    bearing_radius: f64,
    bearing_length: f64,
    journal_radius: f64,
    journal_length: f64,
    out: *mut *mut ClrJournalJoint,
) -> ClrStatus {
    new_handle(out, || {
        let joint = JournalClearance::cylindrical(
            finite("bearing_radius (m)", bearing_radius)?,
            finite("bearing_length (m)", bearing_length)?,
            finite("journal_radius (m)", journal_radius)?,
            finite("journal_length (m)", journal_length)?,
        )?;
        Ok(ClrJournalJoint(joint))
    })
}

/// Forces of the joint at `state`: `radial` is the normal law of the whole contact length
/// L_c = min(L_b, L_j) (the force per unit length is F_N/L_c), `thrust` that of a thrust face
/// (NULL: `radial`), `friction` a stateless friction law (NULL: frictionless), and
/// `impact_velocities` the four groups' δ̇⁻ (m/s, kept by the caller; see the module notes).
///
/// # Safety
/// `joint`, `radial` are NULL or live handles; `thrust`, `friction` are NULL or live handles;
/// `state` is NULL or points to a `ClrJournalState`; `impact_velocities` is NULL or points to 4
/// doubles; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_journal_joint_forces(
    joint: *const ClrJournalJoint,
    radial: *const ClrNormalLaw,
    thrust: *const ClrNormalLaw,
    friction: *const ClrFrictionLaw,
    state: *const ClrJournalState,
    impact_velocities: *const f64,
    out: *mut ClrJournalForces,
) -> ClrStatus {
    write_out(out, || {
        let joint = &borrow("joint", joint)?.0;
        let radial = borrow("radial", radial)?.0;
        let thrust = thrust.as_ref().map_or(radial, |t| t.0);
        let friction = friction
            .as_ref()
            .map_or(JournalFriction::None, |f| JournalFriction::Law(f.0));
        let s = borrow("state", state)?;
        let v0: [f64; GROUPS] = *borrow("impact_velocities", impact_velocities.cast::<[f64; 4]>())?;
        for v in v0 {
            finite("impact_velocities (m/s)", v)?;
        }
        let laws = JournalLaws::new(radial, thrust, friction)?;
        journal_forces(joint, &laws, s, &v0)
    })
}

/// The journal joint evaluation shared by the C and Python bindings.
///
/// # Errors
/// A non-finite state or a tilt beyond 60° ([`CapiError::Model`]).
pub fn journal_forces(
    joint: &JournalClearance,
    laws: &JournalLaws,
    s: &ClrJournalState,
    impact_velocities: &[f64; GROUPS],
) -> Result<ClrJournalForces, CapiError> {
    let g = joint.geometry::<f64>(&journal_state(s))?;
    let f = g.forces(laws, impact_velocities);
    let mut out = ClrJournalForces {
        force: f.force.value().into(),
        journal_moment: f.journal_moment.value().into(),
        bearing_moment: f.bearing_moment.value().into(),
        tilt: g.tilt(),
        dissipated: f.dissipated(),
        elastic_energy: f.elastic_energy(),
        ..Default::default()
    };
    for (k, grp) in f.groups.iter().enumerate() {
        out.penetration[k] = grp.penetration;
        out.rate[k] = grp.rate;
        out.normal_force[k] = grp.normal_force;
        out.point[k] = grp.point.into();
    }
    Ok(out)
}

/// The clr-contact state of a C state (shared with the journal wear).
pub(crate) fn journal_state(s: &ClrJournalState) -> JournalState<f64> {
    let v = |a: [f64; 3]| Vector3::from(a);
    JournalState::new(
        v(s.bearing_centre),
        v(s.bearing_axis),
        v(s.bearing_velocity),
        v(s.bearing_angular_velocity),
        v(s.journal_centre),
        v(s.journal_axis),
        v(s.journal_velocity),
        v(s.journal_angular_velocity),
    )
}

/// Free a journal joint. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `joint` is NULL or a handle from `clr_journal_joint_new_*` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_journal_joint_free(joint: *mut ClrJournalJoint) {
    free_handle(joint)
}
