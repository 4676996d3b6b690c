//! The spatial journal joint through the C ABI against the planar revolute clearance joint
//! through the C ABI (an independent formulation): a journal with no tilt and no axial motion,
//! its centre off the bore axis by the clearance plus 5 µm and moving in the plane, gives the
//! planar joint's normal force and force on the journal (docs/contact.md: at zero tilt the
//! distributed line contact integrates to F_N(δ) exactly, up to rounding: tolerance 1e-12
//! relative), frictionless and with regularized Coulomb friction; open joints give zero; bad
//! input is a status, not a crash.

use std::ptr;

use clr_contact_capi::*;

unsafe fn normal_law() -> *mut ClrNormalLaw {
    let p = [1.0e10, 1.5];
    let mut law = ptr::null_mut();
    let s = clr_normal_law_new(
        CLR_ELASTIC_POWER,
        p.as_ptr(),
        2,
        CLR_DAMPING_LANKARANI_NIKRAVESH,
        0.9,
        &mut law,
    );
    assert_eq!(s, ClrStatus::Ok);
    law
}

unsafe fn coulomb() -> *mut ClrFrictionLaw {
    let p = [0.1, 1e-3];
    let mut law = ptr::null_mut();
    assert_eq!(
        clr_friction_law_new(CLR_FRICTION_COULOMB, p.as_ptr(), 2, &mut law),
        ClrStatus::Ok
    );
    law
}

#[test]
fn untilted_journal_equals_the_planar_joint() {
    let (rb, rj, l) = (0.010, 0.0095, 0.015);
    unsafe {
        let law = normal_law();
        let fric = coulomb();
        let mut planar = ptr::null_mut();
        assert_eq!(
            clr_revolute_joint_new(rb, rj, 0.0, 0.0, 0.0, 0.0, &mut planar),
            ClrStatus::Ok
        );
        let mut spatial = ptr::null_mut();
        assert_eq!(
            clr_journal_joint_new_revolute(rb, l, rj, l, 1e-4, 0.0, &mut spatial),
            ClrStatus::Ok
        );
        for (friction, depth) in [
            (ptr::null(), 5e-6),
            (fric.cast_const(), 5e-6),
            (ptr::null(), -1e-6),
        ] {
            let a = 0.7f64;
            let e = rb - rj + depth;
            let (x, y) = (e * a.cos(), e * a.sin());
            let (vx, vy, w) = (0.02, -0.05, 3.0);
            let bearing = ClrBodyState::default();
            let journal = ClrBodyState {
                x,
                y,
                theta: 0.2,
                vx,
                vy,
                omega: w,
            };
            let v0 = 0.05;
            let mut p = ClrRevoluteForces::default();
            let s =
                clr_revolute_joint_forces(planar, law, friction, &bearing, &journal, v0, &mut p);
            assert_eq!(s, ClrStatus::Ok);
            let state = ClrJournalState {
                bearing_axis: [0.0, 0.0, 1.0],
                journal_centre: [x, y, 0.0],
                journal_axis: [0.0, 0.0, 1.0],
                journal_velocity: [vx, vy, 0.0],
                journal_angular_velocity: [0.0, 0.0, w],
                ..Default::default()
            };
            let v = [v0; 4];
            let mut f = ClrJournalForces::default();
            let s = clr_journal_joint_forces(
                spatial,
                law,
                ptr::null(),
                friction,
                &state,
                v.as_ptr(),
                &mut f,
            );
            assert_eq!(s, ClrStatus::Ok, "{:?}", last_error());
            let fn_spatial = f.normal_force[0] + f.normal_force[1];
            let scale = p.normal_force.abs().max(1e-300);
            if depth < 0.0 {
                assert_eq!(p.normal_force, 0.0);
                assert_eq!(fn_spatial, 0.0);
                assert_eq!(f.force, [0.0; 3]);
                continue;
            }
            assert!(
                (fn_spatial - p.normal_force).abs() <= 1e-12 * scale,
                "F_N {fn_spatial} against {}",
                p.normal_force
            );
            for (s, q) in [(f.force[0], p.journal.fx), (f.force[1], p.journal.fy)] {
                assert!((s - q).abs() <= 1e-12 * scale, "force {s} against {q}");
            }
            assert_eq!(f.force[2], 0.0, "no axial force without tilt or thrust");
            assert_eq!(f.tilt, 0.0);
        }
        // a NULL state and a non-finite impact velocity are statuses
        let mut f = ClrJournalForces::default();
        let v = [f64::NAN; 4];
        let s = clr_journal_joint_forces(
            spatial,
            law,
            ptr::null(),
            ptr::null(),
            ptr::null(),
            v.as_ptr(),
            &mut f,
        );
        assert_eq!(s, ClrStatus::NullPointer);
        let state = ClrJournalState::default();
        let s = clr_journal_joint_forces(
            spatial,
            law,
            ptr::null(),
            ptr::null(),
            &state,
            v.as_ptr(),
            &mut f,
        );
        assert_eq!(s, ClrStatus::NonFinite);
        // a journal larger than its bore is refused
        let mut bad = ptr::null_mut();
        let s = clr_journal_joint_new_cylindrical(0.01, 0.015, 0.011, 0.015, &mut bad);
        assert_eq!(s, ClrStatus::InvalidParameter);
        assert!(bad.is_null());
        clr_journal_joint_free(spatial);
        clr_revolute_joint_free(planar);
        clr_friction_law_free(fric);
        clr_normal_law_free(law);
    }
}

fn last_error() -> String {
    unsafe {
        std::ffi::CStr::from_ptr(clr_last_error_message())
            .to_string_lossy()
            .into_owned()
    }
}
