//! C ABI of the wear of a revolute clearance joint (clr-contact `wear`, docs/wear.md): a worn
//! bearing profile h_w(φ) ≥ 0 (m) at N equally spaced angles of the bearing body frame,
//! Archard's wear law V = K F_N s / H (J.F. Archard, J. Appl. Phys. 24 (1953) 981–988) spreading
//! the load over the Hertz line contact of the journal in the bearing (K.L. Johnson, *Contact
//! Mechanics*, Cambridge University Press 1985, §4.3, pp. 99–104), and the revolute clearance
//! joint on the worn surface ρ(φ) = R_i + h_w(φ).
//!
//! The revolute joint handle of `clr_revolute_joint_new` is immutable after construction (it may
//! be shared between threads), so a worn joint is a new handle,
//! [`clr_revolute_joint_new_worn`], holding a copy of the profile; after accumulating wear,
//! create the joint of the next cycle from the updated profile. A profile handle is modified by
//! [`clr_archard_wear_accumulate`] and must then not be used by another thread during the call.
//! Nothing allocates after construction: the evaluations and the accumulation work in place.

use clr_contact::wear::{ArchardWear, BearingProfile, LineContact, PressureDistribution};
use clr_contact::RevoluteClearance;

use crate::error::{finite, guard, CapiError};
use crate::ffi::{
    body_state, borrow, borrow_mut, fill_buffer, free_handle, new_handle, non_null, out_ptr,
    write_out, ClrBodyState, ClrRevoluteJoint,
};
use crate::ClrStatus;

/// Code of the contact-pressure distribution of `clr_archard_wear_new` (one of the
/// `CLR_PRESSURE_*` constants).
pub type ClrPressureKind = u32;
/// Hertz semi-ellipse p(x) = p₀ √(1 − x²/a²), p₀ = 2F_N/(π a L) (Johnson 1985, §4.3).
pub const CLR_PRESSURE_HERTZ: ClrPressureKind = 0;
/// Uniform mean pressure F_N/(2 a L) over the Hertz half-width a.
pub const CLR_PRESSURE_UNIFORM: ClrPressureKind = 1;

/// Opaque handle of a worn bearing profile: radial wear depth h_w(φ) ≥ 0 (m) at N ≥ 8 equally
/// spaced angles φ_k = 2πk/N (rad) of the bearing body frame, interpolated by a periodic
/// shape-preserving C¹ cubic (docs/wear.md).
pub struct ClrBearingProfile(pub(crate) BearingProfile);

/// Opaque handle of Archard's wear law V = K F_N s / H (Archard 1953) with the Hertz line
/// contact that spreads the load over the bearing (Johnson 1985, §4.3). Immutable: may be shared
/// between threads.
pub struct ClrArchardWear(pub(crate) ArchardWear);

/// Create a bearing profile from the wear depths h_k (m, finite, ≥ 0) at the `n` angles
/// φ_k = 2πk/`n` (rad, k = 0 … n − 1) of the bearing body frame, measured about the bearing
/// centre from the body's x axis, counter-clockwise. `n` must be at least 8 (choose 2π/n well
/// below the contact half-angle a/R_i: typically n = 360 to 3600). The depths are copied. An
/// all-zero profile is the circular (unworn) bearing. On success `*out` receives a handle to
/// free with `clr_bearing_profile_free`.
///
/// # Errors
/// `CLR_STATUS_NULL_POINTER` for a NULL `depths` with `n` > 0 or a NULL `out`;
/// `CLR_STATUS_INVALID_PARAMETER` for `n` < 8 or a negative or non-finite depth.
///
/// # Safety
/// `depths` is NULL or points to `n` readable doubles; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_bearing_profile_new(
    depths: *const f64,
    n: usize,
    out: *mut *mut ClrBearingProfile,
) -> ClrStatus {
    new_handle(out, || {
        let depths = if n == 0 {
            Vec::new()
        } else {
            std::slice::from_raw_parts(non_null("depths", depths)?, n).to_vec()
        };
        Ok(ClrBearingProfile(BearingProfile::new(depths)?))
    })
}

/// Wear depth h_w(φ) (m) of the interpolated profile at the bearing-frame angle φ (rad, any
/// finite value; periodic with period 2π). Equals h_k at φ_k. Allocates nothing.
///
/// # Safety
/// `profile` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_bearing_profile_depth_at(
    profile: *const ClrBearingProfile,
    phi: f64,
    out: *mut f64,
) -> ClrStatus {
    write_out(out, || {
        let p = borrow("profile", profile)?;
        Ok(p.0.depth_at(finite("phi (rad)", phi)?))
    })
}

/// Largest wear depth max_k h_k (m), also the largest depth of the interpolant.
///
/// # Safety
/// `profile` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_bearing_profile_max_depth(
    profile: *const ClrBearingProfile,
    out: *mut f64,
) -> ClrStatus {
    write_out(out, || Ok(borrow("profile", profile)?.0.max_depth()))
}

/// Worn volume V = L R_i (2π/N) Σ h_k (m³) of a bearing of radius R_i (m) and axial length L
/// (m): the thin-layer volume of the interpolated profile (exact for the interpolant), first
/// order in h/R_i like Archard's law (docs/wear.md).
///
/// # Safety
/// `profile` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_bearing_profile_worn_volume(
    profile: *const ClrBearingProfile,
    bearing_radius: f64,
    length: f64,
    out: *mut f64,
) -> ClrStatus {
    write_out(out, || {
        let p = borrow("profile", profile)?;
        let r = finite("bearing_radius (m)", bearing_radius)?;
        let l = finite("length (m)", length)?;
        Ok(p.0.worn_volume(r, l))
    })
}

/// Copy the N knot depths h_k (m, at φ_k = 2πk/N) into `buf`, which has room for `capacity`
/// doubles, and write N to `*count`. When `capacity` < N nothing is copied, `*count` receives N
/// and the status is `CLR_STATUS_BUFFER_TOO_SMALL`; `buf` may be NULL when `capacity` is 0 (a
/// query of N). Allocates nothing.
///
/// # Safety
/// `profile` is NULL or a live handle; `buf` is NULL or points to `capacity` writable doubles;
/// `count` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_bearing_profile_depths(
    profile: *const ClrBearingProfile,
    buf: *mut f64,
    capacity: usize,
    count: *mut usize,
) -> ClrStatus {
    guard(|| {
        let count = out_ptr("count", count)?;
        let p = borrow("profile", profile)?;
        if capacity > 0 {
            non_null("buf", buf)?;
        }
        let depths = p.0.depths();
        fill_buffer("buf", buf, capacity, count, depths.len(), |b| {
            std::ptr::copy_nonoverlapping(depths.as_ptr(), b, depths.len())
        })
    })
}

/// Free a bearing profile. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `profile` is NULL or a handle from `clr_bearing_profile_new` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_bearing_profile_free(profile: *mut ClrBearingProfile) {
    free_handle(profile)
}

/// Create Archard's wear law V = K F_N s / H (Archard 1953) for the bearing of a revolute
/// clearance joint: wear coefficient K (–, in (0, 1]; typically 1e-6…1e-4 for steel on steel),
/// hardness H of the bearing material (Pa, ≥ 1e6: give Pa, not GPa or HV), and the Hertz line
/// contact of the journal in the bearing that spreads the load (Johnson 1985, §4.3): bearing
/// radius R_i and journal radius R_j (m, R_i > R_j > 0), axial contact length L (m, > 0) and
/// composite modulus E* = 1/(σ_i + σ_j) (Pa, σ_k = (1 − ν_k²)/E_k). `pressure_kind` is
/// `CLR_PRESSURE_HERTZ` (semi-ellipse, half-width a = √(4 F_N R/(π L E*)),
/// R = R_i R_j/(R_i − R_j)) or `CLR_PRESSURE_UNIFORM` (mean pressure F_N/(2aL) over the same
/// width). On success `*out` receives a handle to free with `clr_archard_wear_free`.
///
/// # Errors
/// `CLR_STATUS_INVALID_PARAMETER` for K ∉ (0, 1], H < 1e6 Pa, a non-positive or non-finite
/// length, radius or modulus, or R_j ≥ R_i; `CLR_STATUS_INVALID_ARGUMENT` for an unknown
/// `pressure_kind`.
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn clr_archard_wear_new(
    wear_coefficient: f64,
    hardness: f64,
    bearing_radius: f64,
    journal_radius: f64,
    length: f64,
    composite_modulus: f64,
    pressure_kind: ClrPressureKind,
    out: *mut *mut ClrArchardWear,
) -> ClrStatus {
    new_handle(out, || {
        let distribution = pressure_distribution(pressure_kind)?;
        let contact = LineContact::new(bearing_radius, journal_radius, length, composite_modulus)?;
        let law = ArchardWear::new(wear_coefficient, hardness, contact)?;
        Ok(ClrArchardWear(law.with_distribution(distribution)))
    })
}

pub(crate) fn pressure_distribution(
    code: ClrPressureKind,
) -> Result<PressureDistribution, CapiError> {
    match code {
        CLR_PRESSURE_HERTZ => Ok(PressureDistribution::Hertz),
        CLR_PRESSURE_UNIFORM => Ok(PressureDistribution::Uniform),
        code => Err(CapiError::UnknownCode {
            what: "pressure distribution",
            code,
            max: 1,
        }),
    }
}

/// Accumulate the wear of one contact into `profile` in place and write the worn volume
/// V = K F_N ds / H (m³) to `*worn_volume`: normal force F_N (N, ≥ 0) sliding over the distance
/// ds = |v_T| dt (m, ≥ 0) at the bearing-frame contact angle φ_c (rad; from
/// `clr_revolute_joint_contact_angle`). V is spread over the profile bins that meet the contact
/// arc |φ − φ_c| ≤ a/R_i in proportion to the exact integral of the pressure over each bin
/// (Δh_k = V w_k/(L R_i Δφ), Σ w_k = 1), so the profile's worn volume
/// (`clr_bearing_profile_worn_volume` with the law's R_i and L) grows by exactly V. Allocates
/// nothing.
///
/// # Errors
/// `CLR_STATUS_NON_FINITE` for a non-finite φ_c, F_N or ds; `CLR_STATUS_INVALID_PARAMETER` for a
/// negative F_N or ds; `CLR_STATUS_OUT_OF_VALIDITY` when the Hertz half-angle a/R_i exceeds π/2.
/// The profile is unchanged on any error.
///
/// # Safety
/// `law` is NULL or a live handle; `profile` is NULL or a live handle not used by another thread
/// during the call; `worn_volume` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_archard_wear_accumulate(
    law: *const ClrArchardWear,
    profile: *mut ClrBearingProfile,
    contact_angle: f64,
    normal_force: f64,
    sliding_distance: f64,
    worn_volume: *mut f64,
) -> ClrStatus {
    write_out(worn_volume, || {
        let law = borrow("law", law)?;
        let profile = borrow_mut("profile", profile)?;
        let phi = finite("contact_angle (rad)", contact_angle)?;
        let f_n = finite("normal_force (N)", normal_force)?;
        let ds = finite("sliding_distance (m)", sliding_distance)?;
        Ok(law.0.accumulate(&mut profile.0, phi, f_n, ds)?)
    })
}

/// Free a wear law. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `law` is NULL or a handle from `clr_archard_wear_new` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_archard_wear_free(law: *mut ClrArchardWear) {
    free_handle(law)
}

/// Create a planar revolute clearance joint with a worn bearing: as `clr_revolute_joint_new`
/// (radii R_i > R_j > 0 in m, local coordinates in m of the bearing centre on body i and of the
/// journal centre on body j), with the bearing surface ρ(φ) = R_i + h_w(φ) of `profile` (φ in
/// the bearing body frame about the bearing centre). The contact is the point of the worn
/// surface nearest to the journal centre (docs/wear.md); an all-zero profile gives the forces of
/// the circular joint bit for bit. The profile is copied: later changes to `profile` do not
/// affect the joint. Evaluate it with `clr_revolute_joint_forces` and free it with
/// `clr_revolute_joint_free`.
///
/// # Safety
/// `profile` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn clr_revolute_joint_new_worn(
    bearing_radius: f64,
    journal_radius: f64,
    bearing_centre_x: f64,
    bearing_centre_y: f64,
    journal_centre_x: f64,
    journal_centre_y: f64,
    profile: *const ClrBearingProfile,
    out: *mut *mut ClrRevoluteJoint,
) -> ClrStatus {
    new_handle(out, || {
        let profile = borrow("profile", profile)?;
        let joint = RevoluteClearance::new(
            bearing_radius,
            journal_radius,
            [bearing_centre_x, bearing_centre_y].into(),
            [journal_centre_x, journal_centre_y].into(),
        )?;
        Ok(ClrRevoluteJoint(joint.with_profile(profile.0.clone())))
    })
}

/// Contact angle φ_c (rad, in [0, 2π)) of a revolute joint in the bearing body frame: the
/// direction of the bearing contact point from the bearing centre, measured from the bearing
/// body's x axis (the direction of the eccentricity for a circular bearing; the nearest point of
/// the worn surface for a joint of `clr_revolute_joint_new_worn`). This is the angle to give
/// `clr_archard_wear_accumulate`. Defined whether or not the joint is in contact. Allocates
/// nothing.
///
/// # Safety
/// `joint` is NULL or a live handle; `bearing`, `journal` are NULL or point to `ClrBodyState`;
/// `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_revolute_joint_contact_angle(
    joint: *const ClrRevoluteJoint,
    bearing: *const ClrBodyState,
    journal: *const ClrBodyState,
    out: *mut f64,
) -> ClrStatus {
    write_out(out, || {
        let joint = borrow("joint", joint)?;
        let i = body_state("bearing state", borrow("bearing", bearing)?)?;
        let j = body_state("journal state", borrow("journal", journal)?)?;
        Ok(joint.0.contact(&i, &j).contact_angle())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ffi::{
        clr_revolute_joint_forces, clr_revolute_joint_free, clr_revolute_joint_new, ClrFrictionLaw,
        ClrNormalLaw, ClrRevoluteForces,
    };
    use clr_contact::{FrictionLaw, JournalBearing, NormalLaw};
    use std::f64::consts::TAU;
    use std::ptr::{null, null_mut};

    const N: usize = 720;
    const RI: f64 = 0.01;
    const RJ: f64 = 0.0099;
    const L: f64 = 0.015;
    const E_STAR: f64 = 1.137e11;
    const K: f64 = 2e-5;
    const H: f64 = 2e9;

    /// A smooth scar h0 (1 + cos 2φ) plus a bump: a non-trivial profile.
    fn shape(x: f64) -> f64 {
        2e-6 * (1.0 + (2.0 * x).cos()) + 1e-6 * (-(x - 1.0) * (x - 1.0) * 20.0).exp()
    }

    fn depths() -> Vec<f64> {
        (0..N).map(|k| shape(TAU * k as f64 / N as f64)).collect()
    }

    fn new_profile(d: &[f64]) -> *mut ClrBearingProfile {
        let mut h = null_mut();
        assert_eq!(
            unsafe { clr_bearing_profile_new(d.as_ptr(), d.len(), &mut h) },
            ClrStatus::Ok
        );
        h
    }

    fn new_law(kind: ClrPressureKind) -> *mut ClrArchardWear {
        let mut h = null_mut();
        assert_eq!(
            unsafe { clr_archard_wear_new(K, H, RI, RJ, L, E_STAR, kind, &mut h) },
            ClrStatus::Ok
        );
        h
    }

    fn direct_law(d: PressureDistribution) -> ArchardWear {
        let c = LineContact::new(RI, RJ, L, E_STAR).unwrap();
        ArchardWear::new(K, H, c).unwrap().with_distribution(d)
    }

    fn copy_depths(p: *const ClrBearingProfile) -> Vec<f64> {
        let mut buf = vec![f64::NAN; N];
        let mut count = 0;
        let s = unsafe { clr_bearing_profile_depths(p, buf.as_mut_ptr(), buf.len(), &mut count) };
        assert_eq!(s, ClrStatus::Ok);
        assert_eq!(count, N);
        buf
    }

    /// The profile functions give clr-contact's values bit for bit.
    #[test]
    fn profile_matches_clr_contact_bit_for_bit() {
        let d = depths();
        let direct = BearingProfile::new(d.clone()).unwrap();
        let p = new_profile(&d);
        for k in 0..2000 {
            let phi = -7.0 + 14.0 * k as f64 / 1999.0;
            let mut h = f64::NAN;
            assert_eq!(
                unsafe { clr_bearing_profile_depth_at(p, phi, &mut h) },
                ClrStatus::Ok
            );
            assert_eq!(h.to_bits(), direct.depth_at(phi).to_bits(), "phi = {phi}");
        }
        let mut m = 0.0;
        assert_eq!(
            unsafe { clr_bearing_profile_max_depth(p, &mut m) },
            ClrStatus::Ok
        );
        assert_eq!(m.to_bits(), direct.max_depth().to_bits());
        let mut v = 0.0;
        assert_eq!(
            unsafe { clr_bearing_profile_worn_volume(p, RI, L, &mut v) },
            ClrStatus::Ok
        );
        assert_eq!(v.to_bits(), direct.worn_volume(RI, L).to_bits());
        let copied = copy_depths(p);
        assert!(copied
            .iter()
            .zip(direct.depths())
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        unsafe { clr_bearing_profile_free(p) };
    }

    /// Accumulation through the ABI changes the profile exactly as clr-contact does, and the
    /// worn volume is Archard's K F_N ds / H (closed form, rel 1e-12), returned and added to the
    /// profile's volume, for both pressure distributions.
    #[test]
    fn accumulation_matches_clr_contact_and_archard_closed_form() {
        for (kind, dist) in [
            (CLR_PRESSURE_HERTZ, PressureDistribution::Hertz),
            (CLR_PRESSURE_UNIFORM, PressureDistribution::Uniform),
        ] {
            let law = new_law(kind);
            let direct = direct_law(dist);
            let d = depths();
            let p = new_profile(&d);
            let mut q = BearingProfile::new(d).unwrap();
            for (phi, f_n, ds) in [
                (0.3, 1000.0, 1e-3),
                (6.2, 250.0, 4e-4),
                (-1.0, 3000.0, 2e-3),
                (2.0, 0.0, 1e-3),
                (4.0, 500.0, 0.0),
            ] {
                let mut v0 = 0.0;
                unsafe { clr_bearing_profile_worn_volume(p, RI, L, &mut v0) };
                let mut v = f64::NAN;
                let s = unsafe { clr_archard_wear_accumulate(law, p, phi, f_n, ds, &mut v) };
                assert_eq!(s, ClrStatus::Ok);
                let vd = direct.accumulate(&mut q, phi, f_n, ds).unwrap();
                assert_eq!(v.to_bits(), vd.to_bits());
                let closed = K * f_n * ds / H;
                assert!((v - closed).abs() <= 1e-12 * closed, "{v} vs {closed}");
                let mut v1 = 0.0;
                unsafe { clr_bearing_profile_worn_volume(p, RI, L, &mut v1) };
                assert!(
                    ((v1 - v0) - closed).abs() <= 1e-12 * closed + 1e-15 * v0,
                    "{} vs {closed}",
                    v1 - v0
                );
                let copied = copy_depths(p);
                assert!(copied
                    .iter()
                    .zip(q.depths())
                    .all(|(a, b)| a.to_bits() == b.to_bits()));
            }
            // Exact closed form on a fresh zero profile (no background volume).
            let z = new_profile(&[0.0; N]);
            let mut v = 0.0;
            let (f_n, ds) = (1234.5, 3.7e-3);
            unsafe {
                assert_eq!(
                    clr_archard_wear_accumulate(law, z, 1.0, f_n, ds, &mut v),
                    ClrStatus::Ok
                );
                let mut vz = 0.0;
                clr_bearing_profile_worn_volume(z, RI, L, &mut vz);
                let closed = K * f_n * ds / H;
                assert!((v - closed).abs() <= 1e-12 * closed);
                assert!((vz - closed).abs() <= 1e-12 * closed, "{vz} vs {closed}");
                clr_bearing_profile_free(z);
                clr_bearing_profile_free(p);
                clr_archard_wear_free(law);
            }
        }
    }

    fn states() -> Vec<(ClrBodyState, ClrBodyState)> {
        let mut v = Vec::new();
        for k in 0..12 {
            let a = TAU * k as f64 / 12.0 + 0.1;
            let e = 1.0e-4 + 2e-6 * (k % 4) as f64; // c = 0.1 mm: some in contact, some not
            let bearing = ClrBodyState {
                x: 0.01,
                y: -0.02,
                theta: 0.3 * k as f64,
                vx: 0.1,
                vy: -0.05,
                omega: 2.0,
            };
            let journal = ClrBodyState {
                x: 0.01 + e * a.cos(),
                y: -0.02 + e * a.sin(),
                theta: -0.2,
                vx: 0.3 * a.cos(),
                vy: 0.3 * a.sin(),
                omega: -5.0,
            };
            v.push((bearing, journal));
        }
        v
    }

    fn forces(j: *const ClrRevoluteJoint, b: &ClrBodyState, s: &ClrBodyState) -> [u64; 13] {
        let jb = JournalBearing::flap_paper_test();
        let normal = ClrNormalLaw(NormalLaw::preset("LN", &jb, 0.5).unwrap());
        let friction = ClrFrictionLaw(FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap());
        let mut o = ClrRevoluteForces::default();
        let st = unsafe { clr_revolute_joint_forces(j, &normal, &friction, b, s, 0.2, &mut o) };
        assert_eq!(st, ClrStatus::Ok);
        [
            o.penetration,
            o.normal_x,
            o.normal_y,
            o.normal_velocity,
            o.tangential_velocity,
            o.normal_force,
            o.tangential_force,
            o.bearing.fx,
            o.bearing.fy,
            o.bearing.moment,
            o.journal.fx,
            o.journal.fy,
            o.journal.moment,
        ]
        .map(f64::to_bits)
    }

    /// A zero profile gives the circular joint's forces and contact angle bit for bit through
    /// the ABI; a worn joint gives clr-contact's worn joint bit for bit.
    #[test]
    fn worn_joint_matches_circular_and_clr_contact() {
        let (bc, jc) = ([0.002, -0.001], [0.0, 0.003]);
        let mut circ = null_mut();
        let mut zero_worn = null_mut();
        let mut worn = null_mut();
        let zero = new_profile(&[0.0; N]);
        let scar = new_profile(&depths());
        unsafe {
            assert_eq!(
                clr_revolute_joint_new(RI, RJ, bc[0], bc[1], jc[0], jc[1], &mut circ),
                ClrStatus::Ok
            );
            assert_eq!(
                clr_revolute_joint_new_worn(
                    RI,
                    RJ,
                    bc[0],
                    bc[1],
                    jc[0],
                    jc[1],
                    zero,
                    &mut zero_worn
                ),
                ClrStatus::Ok
            );
            assert_eq!(
                clr_revolute_joint_new_worn(RI, RJ, bc[0], bc[1], jc[0], jc[1], scar, &mut worn),
                ClrStatus::Ok
            );
            // the joint holds a copy: freeing the profiles does not affect it
            clr_bearing_profile_free(zero);
            clr_bearing_profile_free(scar);
        }
        let direct = RevoluteClearance::new(RI, RJ, bc.into(), jc.into())
            .unwrap()
            .with_profile(BearingProfile::new(depths()).unwrap());
        let direct = ClrRevoluteJoint(direct);
        let mut in_contact = 0;
        for (b, s) in states() {
            let fc = forces(circ, &b, &s);
            assert_eq!(fc, forces(zero_worn, &b, &s));
            assert_eq!(forces(worn, &b, &s), forces(&direct, &b, &s));
            if f64::from_bits(fc[0]) > 0.0 {
                in_contact += 1;
            }
            let (mut a_c, mut a_z, mut a_w) = (f64::NAN, f64::NAN, f64::NAN);
            unsafe {
                assert_eq!(
                    clr_revolute_joint_contact_angle(circ, &b, &s, &mut a_c),
                    ClrStatus::Ok
                );
                clr_revolute_joint_contact_angle(zero_worn, &b, &s, &mut a_z);
                clr_revolute_joint_contact_angle(worn, &b, &s, &mut a_w);
            }
            assert_eq!(a_c.to_bits(), a_z.to_bits());
            let bi = crate::ffi::body_state("b", &b).unwrap();
            let bj = crate::ffi::body_state("j", &s).unwrap();
            assert_eq!(
                a_w.to_bits(),
                direct.0.contact(&bi, &bj).contact_angle().to_bits()
            );
            assert!((0.0..TAU).contains(&a_w));
        }
        assert!(in_contact >= 4, "{in_contact} states in contact");
        unsafe {
            clr_revolute_joint_free(circ);
            clr_revolute_joint_free(zero_worn);
            clr_revolute_joint_free(worn);
        }
    }

    /// NULL, NaN, n < 8, negative depth, buffer too small, bad law parameters: statuses, with
    /// outputs and profile untouched.
    #[test]
    fn bad_input_is_a_status() {
        let d = depths();
        unsafe {
            let mut p = null_mut();
            assert_eq!(
                clr_bearing_profile_new(null(), 10, &mut p),
                ClrStatus::NullPointer
            );
            assert_eq!(
                clr_bearing_profile_new(d.as_ptr(), 7, &mut p),
                ClrStatus::InvalidParameter
            );
            assert_eq!(
                clr_bearing_profile_new(null(), 0, &mut p),
                ClrStatus::InvalidParameter
            );
            let mut neg = d.clone();
            neg[5] = -1e-9;
            assert_eq!(
                clr_bearing_profile_new(neg.as_ptr(), N, &mut p),
                ClrStatus::InvalidParameter
            );
            neg[5] = f64::NAN;
            assert_eq!(
                clr_bearing_profile_new(neg.as_ptr(), N, &mut p),
                ClrStatus::InvalidParameter
            );
            assert!(p.is_null());
            assert_eq!(
                clr_bearing_profile_new(d.as_ptr(), N, null_mut()),
                ClrStatus::NullPointer
            );

            let p = new_profile(&d);
            let mut x = 7.0;
            assert_eq!(
                clr_bearing_profile_depth_at(p, f64::NAN, &mut x),
                ClrStatus::NonFinite
            );
            assert_eq!(
                clr_bearing_profile_depth_at(null(), 0.0, &mut x),
                ClrStatus::NullPointer
            );
            assert_eq!(
                clr_bearing_profile_depth_at(p, 0.0, null_mut()),
                ClrStatus::NullPointer
            );
            assert_eq!(
                clr_bearing_profile_max_depth(null(), &mut x),
                ClrStatus::NullPointer
            );
            assert_eq!(x, 7.0);

            // buffer too small: count needed, nothing copied; NULL buffer with capacity 0 queries
            let mut small = [-1.0; 8];
            let mut count = 0;
            assert_eq!(
                clr_bearing_profile_depths(p, small.as_mut_ptr(), small.len(), &mut count),
                ClrStatus::BufferTooSmall
            );
            assert_eq!(count, N);
            assert_eq!(small, [-1.0; 8]);
            count = 0;
            assert_eq!(
                clr_bearing_profile_depths(p, null_mut(), 0, &mut count),
                ClrStatus::BufferTooSmall
            );
            assert_eq!(count, N);
            assert_eq!(
                clr_bearing_profile_depths(p, null_mut(), N, &mut count),
                ClrStatus::NullPointer
            );
            assert_eq!(
                clr_bearing_profile_depths(p, small.as_mut_ptr(), 8, null_mut()),
                ClrStatus::NullPointer
            );

            // law construction
            let mut law = null_mut();
            for (k, h, ri, rj, l, e) in [
                (0.0, H, RI, RJ, L, E_STAR),
                (2.0, H, RI, RJ, L, E_STAR),
                (K, 2.0, RI, RJ, L, E_STAR),
                (K, H, RI, RI, L, E_STAR),
                (K, H, RI, RJ, -L, E_STAR),
                (K, H, RI, RJ, L, f64::NAN),
            ] {
                assert_eq!(
                    clr_archard_wear_new(k, h, ri, rj, l, e, CLR_PRESSURE_HERTZ, &mut law),
                    ClrStatus::InvalidParameter
                );
            }
            assert_eq!(
                clr_archard_wear_new(K, H, RI, RJ, L, E_STAR, 2, &mut law),
                ClrStatus::InvalidArgument
            );
            assert!(law.is_null());

            // accumulation: profile unchanged and output untouched on every error
            let law = new_law(CLR_PRESSURE_HERTZ);
            let mut v = 7.0;
            for (phi, f_n, ds, want) in [
                (f64::NAN, 100.0, 1e-3, ClrStatus::NonFinite),
                (0.0, f64::INFINITY, 1e-3, ClrStatus::NonFinite),
                (0.0, 100.0, f64::NAN, ClrStatus::NonFinite),
                (0.0, -1.0, 1e-3, ClrStatus::InvalidParameter),
                (0.0, 100.0, -1e-3, ClrStatus::InvalidParameter),
                (0.0, 1e15, 1e-3, ClrStatus::OutOfValidity),
            ] {
                assert_eq!(
                    clr_archard_wear_accumulate(law, p, phi, f_n, ds, &mut v),
                    want,
                    "{phi} {f_n} {ds}"
                );
            }
            assert_eq!(
                clr_archard_wear_accumulate(null(), p, 0.0, 1.0, 1.0, &mut v),
                ClrStatus::NullPointer
            );
            assert_eq!(
                clr_archard_wear_accumulate(law, null_mut(), 0.0, 1.0, 1.0, &mut v),
                ClrStatus::NullPointer
            );
            assert_eq!(
                clr_archard_wear_accumulate(law, p, 0.0, 1.0, 1.0, null_mut()),
                ClrStatus::NullPointer
            );
            assert_eq!(v, 7.0);
            assert!(copy_depths(p)
                .iter()
                .zip(&d)
                .all(|(a, b)| a.to_bits() == b.to_bits()));

            // worn joint
            let mut j = null_mut();
            assert_eq!(
                clr_revolute_joint_new_worn(RI, RJ, 0.0, 0.0, 0.0, 0.0, null(), &mut j),
                ClrStatus::NullPointer
            );
            assert_eq!(
                clr_revolute_joint_new_worn(RJ, RI, 0.0, 0.0, 0.0, 0.0, p, &mut j),
                ClrStatus::InvalidParameter
            );
            assert!(j.is_null());
            let (b, s) = states()[0];
            let nan = ClrBodyState { x: f64::NAN, ..s };
            assert_eq!(
                clr_revolute_joint_contact_angle(null(), &b, &s, &mut v),
                ClrStatus::NullPointer
            );
            let mut circ = null_mut();
            clr_revolute_joint_new(RI, RJ, 0.0, 0.0, 0.0, 0.0, &mut circ);
            assert_eq!(
                clr_revolute_joint_contact_angle(circ, &b, &nan, &mut v),
                ClrStatus::NonFinite
            );
            assert_eq!(
                clr_revolute_joint_contact_angle(circ, null(), &s, &mut v),
                ClrStatus::NullPointer
            );
            assert_eq!(v, 7.0);
            clr_revolute_joint_free(circ);
            clr_archard_wear_free(law);
            clr_bearing_profile_free(p);
            clr_bearing_profile_free(null_mut());
            clr_archard_wear_free(null_mut());
        }
    }
}
