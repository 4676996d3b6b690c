//! C ABI of the hydrodynamic journal bearing (clr-contact `lubrication`, docs/lubrication.md):
//! the film force of a lubricated revolute clearance joint from the closed-form solutions of
//! the Reynolds equation (short bearing: Ocvirk; long bearing: Sommerfeld with the half-film
//! condition), with its wedge and squeeze terms, for a user's own journal-bearing subroutine.

use clr_contact::lubrication::{BearingModel, HydrodynamicBearing};

use crate::error::{finite, CapiError};
use crate::ffi::{borrow, free_handle, new_handle, write_out};
use crate::ClrStatus;

/// Short bearing (Ocvirk), L/D ≲ 0.5.
pub const CLR_BEARING_SHORT: u32 = 0;
/// Infinitely long bearing (Sommerfeld, Pinkus–Sternlicht), L/D ≳ 2.
pub const CLR_BEARING_LONG: u32 = 1;

/// Opaque handle of a hydrodynamic journal bearing (immutable: may be shared between threads).
pub struct ClrHydrodynamicBearing(HydrodynamicBearing);

/// The film force on the journal in the frame of the line of centres, N.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ClrFilmForce {
    /// Radial component along **n** = **e**/|**e**| (negative: pushes the journal back toward
    /// the bearing centre), N.
    pub radial: f64,
    /// Tangential component along **t** = k̂ × **n**, N.
    pub tangential: f64,
}

/// Create a bearing from the bearing radius R and journal radius r (m, 0 < r < R), the axial
/// length L (m), the dynamic viscosity μ (Pa·s) and the model (`CLR_BEARING_SHORT` or
/// `CLR_BEARING_LONG`). On success `*out` receives a handle to free with
/// `clr_hydrodynamic_bearing_free`.
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_hydrodynamic_bearing_new(
    bearing_radius: f64,
    journal_radius: f64,
    length: f64,
    viscosity: f64,
    model: u32,
    out: *mut *mut ClrHydrodynamicBearing,
) -> ClrStatus {
    new_handle(out, || {
        let model = match model {
            CLR_BEARING_SHORT => BearingModel::ShortBearing,
            CLR_BEARING_LONG => BearingModel::LongBearing,
            code => {
                return Err(CapiError::UnknownCode {
                    what: "bearing model",
                    code,
                    max: 1,
                })
            }
        };
        let b = HydrodynamicBearing::new(bearing_radius, journal_radius, length, viscosity, model)?;
        Ok(ClrHydrodynamicBearing(b))
    })
}

/// The film force on the journal (N, frame of the line of centres) at the eccentricity ratio
/// ε ∈ [0, 1) (–), its rate ε̇ (1/s), the angular velocity of the line of centres γ̇ (rad/s)
/// and the sum of the journal and bearing angular velocities ω_i + ω_j (rad/s); the wedge term
/// depends on ω_i + ω_j − 2γ̇ (Flores, Ambrósio, Claro & Pimenta, Nonlinear Dyn 56 (2009)
/// 277–295; docs/lubrication.md). The force on the bearing is its opposite, on the same line.
///
/// # Safety
/// `bearing` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_hydrodynamic_bearing_force(
    bearing: *const ClrHydrodynamicBearing,
    eccentricity_ratio: f64,
    eccentricity_rate: f64,
    line_of_centres_rate: f64,
    angular_velocity_sum: f64,
    out: *mut ClrFilmForce,
) -> ClrStatus {
    write_out(out, || {
        let b = borrow("bearing", bearing)?;
        let eps = finite("eccentricity_ratio (-)", eccentricity_ratio)?;
        if !(0.0..1.0).contains(&eps) {
            return Err(CapiError::Contact(clr_contact::ContactError::invalid(
                "hydrodynamic bearing",
                "eccentricity ratio ε (-)",
                eps,
                "must be in [0, 1): the journal touches the bearing at ε = 1",
            )));
        }
        let f = b.0.force(
            eps,
            finite("eccentricity_rate (1/s)", eccentricity_rate)?,
            finite("line_of_centres_rate (rad/s)", line_of_centres_rate)?,
            finite("angular_velocity_sum (rad/s)", angular_velocity_sum)?,
        );
        Ok(ClrFilmForce {
            radial: f.radial,
            tangential: f.tangential,
        })
    })
}

/// Free a bearing. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `bearing` is NULL or a handle from `clr_hydrodynamic_bearing_new` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_hydrodynamic_bearing_free(bearing: *mut ClrHydrodynamicBearing) {
    free_handle(bearing)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ABI gives clr-contact's force bit for bit, and refuses bad input with its status.
    #[test]
    fn the_abi_force_is_clr_contact_s_and_bad_input_is_a_status() {
        let direct =
            HydrodynamicBearing::new(0.01, 0.0099, 0.01, 0.05, BearingModel::ShortBearing).unwrap();
        let mut h: *mut ClrHydrodynamicBearing = std::ptr::null_mut();
        unsafe {
            assert_eq!(
                clr_hydrodynamic_bearing_new(0.01, 0.0099, 0.01, 0.05, CLR_BEARING_SHORT, &mut h),
                ClrStatus::Ok
            );
            let mut out = ClrFilmForce::default();
            for (eps, rate, gd, w) in [(0.3, 0.0, 0.0, 200.0), (0.8, 5.0, -3.0, 150.0)] {
                let st = clr_hydrodynamic_bearing_force(h, eps, rate, gd, w, &mut out);
                assert_eq!(st, ClrStatus::Ok);
                let f = direct.force(eps, rate, gd, w);
                assert_eq!(out.radial.to_bits(), f.radial.to_bits());
                assert_eq!(out.tangential.to_bits(), f.tangential.to_bits());
            }
            let before = out;
            assert_eq!(
                clr_hydrodynamic_bearing_force(h, 1.0, 0.0, 0.0, 1.0, &mut out),
                ClrStatus::InvalidParameter
            );
            assert_eq!(
                clr_hydrodynamic_bearing_force(h, f64::NAN, 0.0, 0.0, 1.0, &mut out),
                ClrStatus::NonFinite
            );
            assert_eq!(out, before, "nothing written on failure");
            assert_eq!(
                clr_hydrodynamic_bearing_force(std::ptr::null(), 0.5, 0.0, 0.0, 1.0, &mut out),
                ClrStatus::NullPointer
            );
            let mut bad: *mut ClrHydrodynamicBearing = std::ptr::null_mut();
            assert_eq!(
                clr_hydrodynamic_bearing_new(0.01, 0.02, 0.01, 0.05, CLR_BEARING_LONG, &mut bad),
                ClrStatus::InvalidParameter
            );
            assert_eq!(
                clr_hydrodynamic_bearing_new(0.01, 0.0099, 0.01, 0.05, 7, &mut bad),
                ClrStatus::InvalidArgument
            );
            assert!(bad.is_null());
            clr_hydrodynamic_bearing_free(h);
        }
    }
}
