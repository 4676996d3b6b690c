//! C ABI of the wear along the axis of the spatial journal joint (clr-contact `journal_wear`,
//! docs/wear.md "Spatial journal: wear along the axis"): the worn bore h_w(φ, z) ≥ 0 (m) on
//! N angles × M axial stations of the bearing body frame, and Archard's law V = K F_N s / H
//! (J.F. Archard, J. Appl. Phys. 24 (1953) 981–988) per section of the journal, the line load
//! spread over the Hertz line-contact half-width (K.L. Johnson, *Contact Mechanics*, 1985, §4.3)
//! around the local contact angle and over each Gauss node's share of the wetted length.
//!
//! A map handle is modified by [`clr_journal_wear_accumulate`] and must then not be used by
//! another thread during the call. The worn map is an output: the joint's contact stays that of
//! the unworn bore. Nothing allocates after construction.

use clr_contact::journal::{JournalFriction, JournalLaws, GROUPS};
use clr_contact::journal_wear::{BearingWearMap, JournalWear, JournalWearError};
use nalgebra::Vector3;

use crate::error::{finite, guard, CapiError};
use crate::ffi::{
    borrow, borrow_mut, fill_buffer, free_handle, new_handle, non_null, out_ptr, write_out,
    ClrNormalLaw,
};
use crate::journal::{journal_state, ClrJournalJoint, ClrJournalState};
use crate::wear::{pressure_distribution, ClrPressureKind};
use crate::ClrStatus;

/// Opaque handle of a worn bore h_w(φ, z) (m): N angles φ_k = 2πk/N about the bore axis from the
/// bearing frame's reference direction, M stations at the cell centres
/// z_m = −L_b/2 + (m + ½) L_b/M; periodic monotone cubic in φ, linear in z between station
/// centres, constant in the rim half cells (docs/wear.md).
pub struct ClrBearingWearMap(pub(crate) BearingWearMap);

/// Opaque handle of Archard's law for a journal joint's bore (K, H, E*, pressure distribution).
/// Immutable: may be shared between threads.
pub struct ClrJournalWear(pub(crate) JournalWear);

/// The readings of a wear map.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ClrWearMapSummary {
    /// Largest knot depth, m.
    pub max_depth: f64,
    /// Mean depth over the bore surface (1/(NM)) Σ h_km, m.
    pub mean_depth: f64,
    /// Worn volume R_b (2π/N) (L_b/M) Σ h_km, m³.
    pub worn_volume: f64,
    /// The larger rim station's largest depth over the mean of all stations' largest depths, –
    /// (1: uniform along the axis; NaN for an unworn map).
    pub edge_concentration: f64,
}

impl From<JournalWearError> for CapiError {
    fn from(e: JournalWearError) -> Self {
        match e {
            JournalWearError::Contact(c) => CapiError::Contact(c),
            other => CapiError::Model(other.to_string()),
        }
    }
}

/// Create a wear map of a bore of radius R_b and length L_b (m) with `angles` = N ≥ 8 angles and
/// `stations` = M ≥ 1 axial stations, from `depths` (m, finite, ≥ 0; N·M values, station by
/// station from z = −L_b/2: h_km at index m·N + k), or the unworn map when `depths` is NULL. On
/// success `*out` receives a handle to free with `clr_bearing_wear_map_free`.
///
/// # Errors
/// `CLR_STATUS_INVALID_PARAMETER` for N < 8, M = 0, a radius or length not positive and finite,
/// or a negative or non-finite depth; `CLR_STATUS_NULL_POINTER` for a NULL `out`.
///
/// # Safety
/// `depths` is NULL or points to N·M readable doubles; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_bearing_wear_map_new(
    angles: usize,
    stations: usize,
    bearing_radius: f64,
    bearing_length: f64,
    depths: *const f64,
    out: *mut *mut ClrBearingWearMap,
) -> ClrStatus {
    new_handle(out, || {
        let knots = angles.checked_mul(stations).ok_or_else(|| {
            CapiError::Model(format!(
                "{angles} angles × {stations} stations overflow: use at most a few thousand each"
            ))
        })?;
        let map = BearingWearMap::zero(angles, stations, bearing_radius, bearing_length)?;
        if depths.is_null() {
            return Ok(ClrBearingWearMap(map));
        }
        let h = std::slice::from_raw_parts(depths, knots);
        let at = |phi: f64, z: f64| {
            let m = ((z + 0.5 * bearing_length) / map.station_step()).floor() as usize;
            let k = (phi / std::f64::consts::TAU * angles as f64).round() as usize;
            h[m.min(stations - 1) * angles + k % angles]
        };
        Ok(ClrBearingWearMap(BearingWearMap::from_fn(
            angles,
            stations,
            bearing_radius,
            bearing_length,
            at,
        )?))
    })
}

/// Wear depth h_w(φ, z) (m) at the bearing-frame angle φ (rad, periodic) and axial position z
/// (m from the bore centre along its axis; 0 outside |z| ≤ L_b/2). Allocates nothing.
///
/// # Safety
/// `map` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_bearing_wear_map_depth_at(
    map: *const ClrBearingWearMap,
    phi: f64,
    z: f64,
    out: *mut f64,
) -> ClrStatus {
    write_out(out, || {
        let m = borrow("map", map)?;
        let phi = finite("phi (rad)", phi)?;
        let z = finite("z (m)", z)?;
        Ok(m.0.depth_at(phi, z))
    })
}

/// The map's readings ([`ClrWearMapSummary`]). Allocates nothing.
///
/// # Safety
/// `map` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_bearing_wear_map_summary(
    map: *const ClrBearingWearMap,
    out: *mut ClrWearMapSummary,
) -> ClrStatus {
    write_out(out, || {
        let m = &borrow("map", map)?.0;
        Ok(ClrWearMapSummary {
            max_depth: m.max_depth(),
            mean_depth: m.mean_depth(),
            worn_volume: m.worn_volume(),
            edge_concentration: m.edge_concentration(),
        })
    })
}

/// Copy the N·M knot depths h_km (m; index m·N + k, station m from z = −L_b/2, angle
/// φ_k = 2πk/N) into `buf` of room `capacity` doubles and write N·M to `*count`. When `capacity`
/// < N·M nothing is copied, `*count` receives N·M and the status is
/// `CLR_STATUS_BUFFER_TOO_SMALL`; `buf` may be NULL when `capacity` is 0. Allocates nothing.
///
/// # Safety
/// `map` is NULL or a live handle; `buf` is NULL or points to `capacity` writable doubles;
/// `count` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_bearing_wear_map_depths(
    map: *const ClrBearingWearMap,
    buf: *mut f64,
    capacity: usize,
    count: *mut usize,
) -> ClrStatus {
    guard(|| {
        let count = out_ptr("count", count)?;
        let m = &borrow("map", map)?.0;
        if capacity > 0 {
            non_null("buf", buf)?;
        }
        let n = m.angles();
        fill_buffer("buf", buf, capacity, count, n * m.station_count(), |b| {
            for (s, station) in m.stations().iter().enumerate() {
                std::ptr::copy_nonoverlapping(station.depths().as_ptr(), b.add(s * n), n);
            }
        })
    })
}

/// Free a wear map. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `map` is NULL or a handle from `clr_bearing_wear_map_new` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_bearing_wear_map_free(map: *mut ClrBearingWearMap) {
    free_handle(map)
}

/// Create Archard's law for a journal joint's bore from the wear coefficient K (–, in (0, 1]),
/// the hardness H of the bore (Pa, ≥ 1 MPa), the composite modulus E* = 1/(σ_b + σ_j) (Pa) and
/// the pressure distribution over the Hertz width (`CLR_PRESSURE_*`). On success `*out` receives
/// a handle to free with `clr_journal_wear_free`.
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_journal_wear_new(
    wear_coefficient: f64,
    hardness: f64,
    composite_modulus: f64,
    pressure_kind: ClrPressureKind,
    out: *mut *mut ClrJournalWear,
) -> ClrStatus {
    new_handle(out, || {
        let d = pressure_distribution(pressure_kind)?;
        let w = JournalWear::new(wear_coefficient, hardness, composite_modulus)?;
        Ok(ClrJournalWear(w.with_distribution(d)))
    })
}

/// Accumulate the wear of one state of `joint` over the sliding interval `dt` (s, ≥ 0) into
/// `map` and write the worn volume K Σ_k w_k p_k |v_t,k| dt / H (m³) to `*worn_volume`: the line
/// loads of the radial law `radial` (and `thrust`, NULL: the radial law, which only decides the
/// thrust faces' contact and wears nothing) at the force evaluation's Gauss nodes, the impact
/// velocities of the four groups (m/s, as for `clr_journal_joint_forces`), and `reference`
/// (3 doubles, world) the direction of the bearing frame's φ = 0. The map must be made for the
/// joint's bore (R_b, L_b). The map is unchanged on any error.
///
/// # Errors
/// `CLR_STATUS_INVALID_PARAMETER` for a map of another bore, a negative `dt`, a reference
/// parallel to the bore axis or a Hertz half-angle over π/2; `CLR_STATUS_NON_FINITE` for a
/// non-finite input; a model error for a state the joint refuses (tilt beyond 60°).
///
/// # Safety
/// `wear`, `joint`, `radial` are NULL or live handles; `thrust` is NULL or a live handle; `map`
/// is NULL or a live handle not used by another thread during the call; `state` is NULL or points
/// to a `ClrJournalState`; `reference` is NULL or points to 3 doubles; `impact_velocities` is NULL
/// or points to 4 doubles; `worn_volume` is NULL or writable.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn clr_journal_wear_accumulate(
    wear: *const ClrJournalWear,
    map: *mut ClrBearingWearMap,
    joint: *const ClrJournalJoint,
    radial: *const ClrNormalLaw,
    thrust: *const ClrNormalLaw,
    state: *const ClrJournalState,
    reference: *const f64,
    impact_velocities: *const f64,
    dt: f64,
    worn_volume: *mut f64,
) -> ClrStatus {
    write_out(worn_volume, || {
        let wear = &borrow("wear", wear)?.0;
        let joint = &borrow("joint", joint)?.0;
        let radial = borrow("radial", radial)?.0;
        let thrust = thrust.as_ref().map_or(radial, |t| t.0);
        let laws = JournalLaws::new(radial, thrust, JournalFriction::None)?;
        let s = borrow("state", state)?;
        let r = *borrow("reference", reference.cast::<[f64; 3]>())?;
        let v0: [f64; GROUPS] = *borrow("impact_velocities", impact_velocities.cast::<[f64; 4]>())?;
        for v in r.iter().chain(&v0) {
            finite("reference or impact_velocities", *v)?;
        }
        let map = &mut borrow_mut("map", map)?.0;
        let state = journal_state(s);
        Ok(wear.accumulate(map, joint, &laws, &state, &Vector3::from(r), &v0, dt)?)
    })
}

/// Free a journal wear law. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `wear` is NULL or a handle from `clr_journal_wear_new` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_journal_wear_free(wear: *mut ClrJournalWear) {
    free_handle(wear)
}
