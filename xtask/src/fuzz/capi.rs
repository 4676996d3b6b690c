//! Fuzzing of the C ABI of `clr-contact-capi`, called from Rust as a C program would: NULL
//! pointers, NaN, ±inf, negative radii, zero or huge parameters, wrong parameter counts,
//! unknown codes and names. Every call must return a status code; [`ClrStatus::Panic`] (a panic
//! caught at the boundary) is a finding, and so is success with a NaN result from finite
//! inputs (an infinite result is IEEE overflow of huge finite inputs, e.g. μ = 1e308, not a
//! finding).

use std::ffi::CString;
use std::ptr::{null, null_mut};

use clr_contact_capi::{
    clr_damping_chi, clr_effective_restitution, clr_friction_law_coefficient,
    clr_friction_law_force, clr_friction_law_free, clr_friction_law_new,
    clr_journal_bearing_flap_paper_test, clr_last_error_message, clr_normal_law_chi,
    clr_normal_law_effective_restitution, clr_normal_law_elastic_force, clr_normal_law_force,
    clr_normal_law_free, clr_normal_law_new, clr_normal_law_preset,
    clr_normal_law_set_min_impact_velocity, clr_revolute_joint_forces, clr_revolute_joint_free,
    clr_revolute_joint_new, ClrBodyState, ClrFrictionLaw, ClrJournalBearing, ClrNormalLaw,
    ClrRevoluteForces, ClrRevoluteJoint, ClrStatus,
};

use super::mutate::{Rng, EXTREMES};

/// Counts of a C ABI run.
#[derive(Debug, Default, Clone)]
pub struct CapiStats {
    /// Calls made.
    pub calls: u64,
    /// Calls that succeeded.
    pub ok: u64,
    /// Calls that returned an error status.
    pub errors: u64,
    /// Findings: (function, inputs, what happened), first few of each kind.
    pub findings: Vec<String>,
    /// Number of findings (all, not only the kept ones).
    pub finding_count: u64,
    /// Successful calls with a NaN result from extreme finite inputs (beyond ±1e6: IEEE
    /// overflow such as r × F with r = 1e30 m), counted, not findings.
    pub overflow: u64,
}

impl CapiStats {
    fn record(&mut self, what: &str, inputs: &str, s: ClrStatus) {
        self.calls += 1;
        match s {
            ClrStatus::Ok => self.ok += 1,
            ClrStatus::Panic => {
                let msg = unsafe { std::ffi::CStr::from_ptr(clr_last_error_message()) }
                    .to_string_lossy()
                    .into_owned();
                self.finding_count += 1;
                self.findings.push(format!(
                    "{what}({inputs}): panic caught at the boundary: {msg}"
                ));
            }
            _ => self.errors += 1,
        }
    }

    fn finding(&mut self, text: String) {
        if EXTREME.with(std::cell::Cell::get) {
            self.overflow += 1;
            return;
        }
        self.finding_count += 1;
        if self.findings.len() < 50 {
            self.findings.push(text);
        }
    }
}

thread_local! {
    /// A value of the current scenario is beyond ±1e6 (SI) or not finite: a NaN result may be
    /// IEEE overflow (∞ − ∞), not a bug.
    static EXTREME: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

fn value(rng: &mut Rng, good: f64) -> f64 {
    let v = match rng.below(6) {
        0 | 1 => good,
        2 => *rng.pick(&EXTREMES),
        3 => -good,
        4 => good * 10f64.powi(rng.below(13) as i32 - 6),
        _ => f64::from_bits(rng.next_u64()),
    };
    if v.is_nan() || v.abs() > 1e6 {
        EXTREME.with(|e| e.set(true));
    }
    v
}

fn geometry(rng: &mut Rng) -> ClrJournalBearing {
    let g = clr_journal_bearing_flap_paper_test();
    let mut g2 = g;
    if rng.chance(0.7) {
        g2.bearing_youngs_modulus = value(rng, g.bearing_youngs_modulus);
        g2.bearing_poisson_ratio = value(rng, g.bearing_poisson_ratio);
        g2.journal_youngs_modulus = value(rng, g.journal_youngs_modulus);
        g2.journal_poisson_ratio = value(rng, g.journal_poisson_ratio);
        g2.bearing_radius = value(rng, g.bearing_radius);
        g2.journal_radius = if rng.chance(0.2) {
            g2.bearing_radius
        } else {
            value(rng, g.journal_radius)
        };
        g2.length = value(rng, g.length);
    }
    g2
}

fn state(rng: &mut Rng) -> ClrBodyState {
    ClrBodyState {
        x: value(rng, 1e-4),
        y: value(rng, -2e-4),
        theta: value(rng, 0.3),
        vx: value(rng, 0.5),
        vy: value(rng, -0.2),
        omega: value(rng, 10.0),
    }
}

fn all_finite(x: &[f64]) -> bool {
    x.iter().all(|v| v.is_finite())
}

/// Make one law of each kind (possibly failing), exercise it, free it.
///
/// # Safety
/// Calls the C ABI with valid or NULL pointers only.
unsafe fn one(rng: &mut Rng, st: &mut CapiStats) {
    // a normal law: by preset name or by kind code
    let mut law: *mut ClrNormalLaw = null_mut();
    let c_e = value(rng, 0.7);
    let out_law = if rng.chance(0.05) {
        null_mut()
    } else {
        &mut law as *mut _
    };
    if rng.chance(0.5) {
        let name = *rng.pick(&[
            "Hertz", "LN", "Gonthier", "Bai", "Wang", "Modified", "ln", "", "nope", "é",
        ]);
        let name = CString::new(name).expect("no NUL");
        let g = geometry(rng);
        let gp: *const ClrJournalBearing = if rng.chance(0.05) { null() } else { &g };
        let np = if rng.chance(0.05) {
            null()
        } else {
            name.as_ptr()
        };
        let s = clr_normal_law_preset(np, gp, c_e, out_law);
        st.record(
            "clr_normal_law_preset",
            &format!("{name:?}, {g:?}, c_e={c_e}"),
            s,
        );
    } else {
        let kind = if rng.chance(0.9) {
            rng.below(11) as u32
        } else {
            rng.next_u64() as u32
        };
        let good: [&[f64]; 11] = [
            &[1e10],
            &[1e10, 1.5],
            &[1e7],
            &[207e9, 0.3, 0.01, 207e9, 0.3, 0.02],
            &[207e9, 0.3, 0.01, 207e9, 0.3],
            &[207e9, 0.3, 0.01, 207e9, 0.3, 0.0099],
            &[1.1e11, 1e-4, 0.015],
            &[1.1e11, 1e-4],
            &[1.1e11, 1e-4, 0.015],
            &[1.1e11, 0.01, 0.02, 0.015],
            &[1.1e11, 1e-4, 0.015],
        ];
        let mut p: Vec<f64> = good[(kind as usize).min(10)]
            .iter()
            .map(|&g| value(rng, g))
            .collect();
        match rng.below(8) {
            0 => {
                p.pop();
            }
            1 => p.push(1.0),
            2 => p.clear(),
            _ => {}
        }
        let damping = if rng.chance(0.9) {
            rng.below(11) as u32
        } else {
            rng.next_u64() as u32
        };
        let pp = if p.is_empty() && rng.chance(0.5) || rng.chance(0.03) {
            null()
        } else {
            p.as_ptr()
        };
        let s = clr_normal_law_new(kind, pp, p.len(), damping, c_e, out_law);
        st.record(
            "clr_normal_law_new",
            &format!("kind={kind}, params={p:?}, damping={damping}, c_e={c_e}"),
            s,
        );
    }
    // evaluate it (or NULL)
    let lp = law as *const ClrNormalLaw;
    let mut out = f64::NAN;
    let d = value(rng, 1e-5);
    let dd = value(rng, 0.3);
    let ddm = value(rng, 0.5);
    let o: *mut f64 = if rng.chance(0.05) {
        null_mut()
    } else {
        &mut out
    };
    let s = clr_normal_law_force(lp, d, dd, ddm, o);
    st.record("clr_normal_law_force", &format!("{d}, {dd}, {ddm}"), s);
    if s == ClrStatus::Ok && all_finite(&[d, dd, ddm]) && out.is_nan() && !law.is_null() {
        st.finding(format!(
            "clr_normal_law_force(δ={d:e}, δ̇={dd:e}, δ̇⁻={ddm:e}) returned OK with NaN (law made with c_e={c_e:e})"
        ));
    }
    let s = clr_normal_law_elastic_force(lp, d, o);
    st.record("clr_normal_law_elastic_force", &format!("{d}"), s);
    let s = clr_normal_law_chi(lp, o);
    st.record("clr_normal_law_chi", "", s);
    let s = clr_normal_law_effective_restitution(lp, o);
    st.record("clr_normal_law_effective_restitution", "", s);
    if rng.chance(0.3) {
        let v = value(rng, 1e-4);
        let s = clr_normal_law_set_min_impact_velocity(law, v);
        st.record("clr_normal_law_set_min_impact_velocity", &format!("{v}"), s);
    }
    // damping factors and restitution alone
    let code = rng.below(13) as u32;
    let s = clr_damping_chi(code, c_e, o);
    st.record("clr_damping_chi", &format!("{code}, {c_e}"), s);
    let chi = value(rng, 0.5);
    let s = clr_effective_restitution(chi, o);
    st.record("clr_effective_restitution", &format!("{chi}"), s);

    // a friction law
    let mut fr: *mut ClrFrictionLaw = null_mut();
    let fk = rng.below(5) as u32;
    let goodf: [&[f64]; 4] = [
        &[0.1, 1e-4],
        &[0.1, 1e-4, 1e-3],
        &[0.1, 1e-4],
        &[0.2, 0.1, 1e-3, 1e-2],
    ];
    let mut fp: Vec<f64> = goodf[(fk as usize).min(3)]
        .iter()
        .map(|&g| value(rng, g))
        .collect();
    if rng.chance(0.1) {
        fp.pop();
    }
    let s = clr_friction_law_new(fk, fp.as_ptr(), fp.len(), &mut fr);
    st.record("clr_friction_law_new", &format!("{fk}, {fp:?}"), s);
    let (vt, fnn) = (value(rng, 0.01), value(rng, 100.0));
    let s = clr_friction_law_force(fr, vt, fnn, o);
    st.record("clr_friction_law_force", &format!("{vt}, {fnn}"), s);
    if s == ClrStatus::Ok && all_finite(&[vt, fnn]) && out.is_nan() {
        st.finding(format!(
            "clr_friction_law_force(kind {fk}, {fp:?}; v_T={vt:e}, F_N={fnn:e}) returned OK with NaN"
        ));
    }
    let s = clr_friction_law_coefficient(fr, vt, o);
    st.record("clr_friction_law_coefficient", &format!("{vt}"), s);

    // a revolute clearance joint
    let mut j: *mut ClrRevoluteJoint = null_mut();
    let (ri, rj) = (value(rng, 0.01), value(rng, 0.0099));
    let (bx, by, jx, jy) = (
        value(rng, 0.0),
        value(rng, 0.0),
        value(rng, 0.1),
        value(rng, 0.0),
    );
    let s = clr_revolute_joint_new(ri, rj, bx, by, jx, jy, &mut j);
    st.record(
        "clr_revolute_joint_new",
        &format!("{ri}, {rj}, {bx}, {by}, {jx}, {jy}"),
        s,
    );
    let (a, b) = (state(rng), state(rng));
    let ap: *const ClrBodyState = if rng.chance(0.05) { null() } else { &a };
    let v0 = value(rng, 0.5);
    let mut rf = ClrRevoluteForces::default();
    let rfp: *mut ClrRevoluteForces = if rng.chance(0.05) {
        null_mut()
    } else {
        &mut rf
    };
    let frp = if rng.chance(0.5) {
        null()
    } else {
        fr as *const _
    };
    let s = clr_revolute_joint_forces(j, lp, frp, ap, &b, v0, rfp);
    st.record(
        "clr_revolute_joint_forces",
        &format!("{a:?}, {b:?}, {v0}"),
        s,
    );
    let outs = [
        rf.penetration,
        rf.normal_x,
        rf.normal_y,
        rf.normal_force,
        rf.tangential_force,
        rf.journal.fx,
        rf.journal.fy,
        rf.journal.moment,
    ];
    if s == ClrStatus::Ok && outs.iter().any(|x| x.is_nan()) {
        st.finding(format!(
            "clr_revolute_joint_forces(R_i={ri:e}, R_j={rj:e}, centres ({bx:e}, {by:e}), ({jx:e}, {jy:e}); {a:?}, {b:?}, δ̇⁻={v0:e}) returned OK with NaN in {rf:?}"
        ));
    }

    clr_revolute_joint_free(j);
    clr_friction_law_free(fr);
    clr_normal_law_free(law);
}

/// Run `n` random scenarios of the C ABI (each a dozen calls).
pub fn run(seed: u64, n: u64) -> CapiStats {
    let mut st = CapiStats::default();
    for i in 0..n {
        let mut rng = Rng::for_case(seed ^ 0xC0FF_EE00, i);
        EXTREME.with(|e| e.set(false));
        // SAFETY: every pointer passed is NULL or points to a live local value or handle.
        unsafe { one(&mut rng, &mut st) };
    }
    st
}
