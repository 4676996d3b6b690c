//! The journal wear map through the C ABI against closed forms: an aligned journal pressed into
//! the bore and spinning carries a uniform line load F_N/L and slips at ω R_j, so every station
//! of the map must hold the planar Archard profile of F_N over ds = ω R_j dt (the planar law
//! through the C ABI, `clr_archard_wear_accumulate` with L = the bore length; docs/wear.md), to
//! 1e-12 of the peak, and the worn volume is Archard's K F_N ω R_j dt / H (F_N from
//! `clr_journal_joint_forces`) to 1e-12; a map built from depths reads them back at the knots
//! (to rounding); bad input is a status and leaves the map unchanged.

use std::ptr;

use clr_contact_capi::*;

const RB: f64 = 0.010;
const RJ: f64 = 0.0099;
const L: f64 = 0.015;
const K: f64 = 1e-5;
const H: f64 = 2e9;
const E_STAR: f64 = 207e9 / (2.0 * (1.0 - 0.09));

unsafe fn linear_law() -> *mut ClrNormalLaw {
    let p = [2e8];
    let mut law = ptr::null_mut();
    let s = clr_normal_law_new(
        CLR_ELASTIC_LINEAR,
        p.as_ptr(),
        1,
        CLR_DAMPING_NONE,
        1.0,
        &mut law,
    );
    assert_eq!(s, ClrStatus::Ok);
    law
}

#[test]
fn aligned_spinning_journal_wears_the_planar_profile_at_every_station() {
    let (omega, dt, n, m) = (100.0, 1e-3, 360usize, 6usize);
    unsafe {
        let law = linear_law();
        let mut joint = ptr::null_mut();
        assert_eq!(
            clr_journal_joint_new_cylindrical(RB, L, RJ, L, &mut joint),
            ClrStatus::Ok
        );
        let mut wear = ptr::null_mut();
        assert_eq!(
            clr_journal_wear_new(K, H, E_STAR, CLR_PRESSURE_HERTZ, &mut wear),
            ClrStatus::Ok
        );
        let mut map = ptr::null_mut();
        assert_eq!(
            clr_bearing_wear_map_new(n, m, RB, L, ptr::null(), &mut map),
            ClrStatus::Ok
        );
        // pressed 2 µm towards φ = 40° of the bearing frame (reference x)
        let a = 40f64.to_radians();
        let e = RB - RJ + 2e-6;
        let state = ClrJournalState {
            bearing_axis: [0.0, 0.0, 1.0],
            journal_centre: [e * a.cos(), e * a.sin(), 0.0],
            journal_axis: [0.0, 0.0, 1.0],
            journal_angular_velocity: [0.0, 0.0, omega],
            ..Default::default()
        };
        let v0 = [0.0; 4];
        let mut f = ClrJournalForces::default();
        let s = clr_journal_joint_forces(
            joint,
            law,
            ptr::null(),
            ptr::null(),
            &state,
            v0.as_ptr(),
            &mut f,
        );
        assert_eq!(s, ClrStatus::Ok);
        let f_n = f.normal_force[0] + f.normal_force[1];
        assert!(f_n > 0.0);
        let reference = [1.0, 0.0, 0.0];
        // one state into `map` over `dt`: (status, worn volume)
        let accumulate = |map: *mut ClrBearingWearMap, dt: f64| {
            let mut v = f64::NAN;
            let s = clr_journal_wear_accumulate(
                wear,
                map,
                joint,
                law,
                ptr::null(),
                &state,
                reference.as_ptr(),
                v0.as_ptr(),
                dt,
                &mut v,
            );
            (s, v)
        };
        let (s, v) = accumulate(map, dt);
        assert_eq!(s, ClrStatus::Ok);
        let archard = K * f_n * omega * RJ * dt / H;
        assert!(
            (v - archard).abs() <= 1e-12 * archard,
            "{v:e} vs {archard:e}"
        );
        // the planar law over the bore length, at the same angle and sliding distance
        let mut planar_law = ptr::null_mut();
        assert_eq!(
            clr_archard_wear_new(K, H, RB, RJ, L, E_STAR, CLR_PRESSURE_HERTZ, &mut planar_law),
            ClrStatus::Ok
        );
        let zeros = vec![0.0; n];
        let mut profile = ptr::null_mut();
        assert_eq!(
            clr_bearing_profile_new(zeros.as_ptr(), n, &mut profile),
            ClrStatus::Ok
        );
        let mut vp = 0.0;
        let s = clr_archard_wear_accumulate(planar_law, profile, a, f_n, omega * RJ * dt, &mut vp);
        assert_eq!(s, ClrStatus::Ok);
        let mut planar = vec![0.0; n];
        let mut count = 0;
        let s = clr_bearing_profile_depths(profile, planar.as_mut_ptr(), n, &mut count);
        assert_eq!((s, count), (ClrStatus::Ok, n));
        let mut depths = vec![0.0; n * m];
        let s = clr_bearing_wear_map_depths(map, depths.as_mut_ptr(), n * m, &mut count);
        assert_eq!((s, count), (ClrStatus::Ok, n * m));
        let peak = planar.iter().cloned().fold(0.0, f64::max);
        assert!(peak > 0.0);
        for (i, h) in depths.iter().enumerate() {
            assert!(
                (h - planar[i % n]).abs() <= 1e-12 * peak,
                "knot {i}: {h:e} vs {:e}",
                planar[i % n]
            );
        }
        let mut sum = ClrWearMapSummary::default();
        assert_eq!(clr_bearing_wear_map_summary(map, &mut sum), ClrStatus::Ok);
        assert!((sum.worn_volume - archard).abs() <= 1e-12 * archard);
        assert!((sum.edge_concentration - 1.0).abs() <= 1e-12);
        // a map of another bore is refused and the map is unchanged
        let mut other = ptr::null_mut();
        assert_eq!(
            clr_bearing_wear_map_new(n, m, RB, 2.0 * L, ptr::null(), &mut other),
            ClrStatus::Ok
        );
        let (s, _) = accumulate(other, dt);
        assert_eq!(s, ClrStatus::InvalidParameter);
        let (s, _) = accumulate(map, -1.0);
        assert_eq!(s, ClrStatus::InvalidParameter);
        let mut again = ClrWearMapSummary::default();
        assert_eq!(clr_bearing_wear_map_summary(map, &mut again), ClrStatus::Ok);
        assert_eq!(again, sum);
        let s = clr_bearing_wear_map_depths(map, depths.as_mut_ptr(), 10, &mut count);
        assert_eq!((s, count), (ClrStatus::BufferTooSmall, n * m));
        for h in [map, other] {
            clr_bearing_wear_map_free(h);
        }
        clr_bearing_profile_free(profile);
        clr_archard_wear_free(planar_law);
        clr_journal_wear_free(wear);
        clr_journal_joint_free(joint);
        clr_normal_law_free(law);
    }
}

#[test]
fn map_from_depths_reads_them_back_at_the_knots() {
    let (n, m) = (16usize, 5usize);
    let depths: Vec<f64> = (0..n * m).map(|i| 1e-7 * (1 + i % 7) as f64).collect();
    unsafe {
        let mut map = ptr::null_mut();
        assert_eq!(
            clr_bearing_wear_map_new(n, m, RB, L, depths.as_ptr(), &mut map),
            ClrStatus::Ok
        );
        for s in 0..m {
            let z = -0.5 * L + (s as f64 + 0.5) * L / m as f64;
            for k in 0..n {
                let phi = std::f64::consts::TAU * k as f64 / n as f64;
                let mut h = f64::NAN;
                assert_eq!(
                    clr_bearing_wear_map_depth_at(map, phi, z, &mut h),
                    ClrStatus::Ok
                );
                let want = depths[s * n + k];
                // to rounding: z_m in floating point puts the reading a few ulp off the
                // station centre, towards a neighbour up to 7× deeper
                assert!(
                    (h - want).abs() <= 1e-14 * want,
                    "station {s}, angle {k}: {h:e}"
                );
            }
        }
        clr_bearing_wear_map_free(map);
        let bad = vec![-1e-6; n * m];
        let mut out = ptr::null_mut();
        let s = clr_bearing_wear_map_new(n, m, RB, L, bad.as_ptr(), &mut out);
        assert_eq!(s, ClrStatus::InvalidParameter);
        assert!(out.is_null());
        let s = clr_bearing_wear_map_new(4, m, RB, L, ptr::null(), &mut out);
        assert_eq!(s, ClrStatus::InvalidParameter);
    }
}
