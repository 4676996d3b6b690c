//! Verification case of the flap's finding map (issue 19, `clr_models::flap_map`): the map's R1
//! run at one point with J4 first (the rigid linkage with J4 the only clearance joint, built by
//! the map's own parameter mapping: load, damping, clearance, flexible study base) against the
//! closed-form kinematic envelope of `models.flap.envelope.J4`: the flap angle lies between the
//! ideal angles for rod lengths l ± (c + δ_max).

use super::Filter;
use crate::report::Case;

/// The point, chosen before any run: inside every range of `flap_map::parameters`, J4 first
/// (joint_order < 0.5), a hinge moment of 10 N·m and a stiffness of 150 N·m/rad (the load
/// stays one-signed, M0 + K·|θ − θ0| with |θ − θ0| ≤ 0.17 rad), 0.3 mm clearance.
fn point() -> clr_models::flap_map::MapPoint {
    clr_models::flap_map::MapPoint {
        hinge_moment: 10.0,
        hinge_stiffness: 150.0,
        modal_damping: 0.05,
        clearance: 0.3e-3,
        joint_order: 0.25,
    }
}

pub fn cases(filter: &Filter) -> Vec<Case> {
    use clr_models::flap::{self, FlapParams};
    use clr_models::RunSettings;
    let id = "models.flap.map.envelope_r1";
    if !filter.wants(id) {
        return Vec::new();
    }
    let p = point();
    let case = Case::new(
        id,
        "largest excursion of the flap angle outside the rod-length envelope, map run R1",
        "rad",
        "closed form: with J4 the only clearance joint, |J4 − J3| stays within l ± (c + δ_max), \
         so the flap angle lies between the ideal angles for those rod lengths (as \
         models.flap.envelope.J4); run R1 of flap_findings_map at M0 = 10 N·m, K = 150 N·m/rad, \
         c = 0.3 mm, J4 first; tolerance 1e-9 rad",
    );
    let (label, flexible, clearances) = p.configurations()[0];
    let q = match p.base() {
        Ok(b) => FlapParams {
            flexible,
            clearances,
            ..b
        },
        Err(e) => return vec![case.failed(0.0, e)],
    };
    if label != "R1" || clearances[3] != p.clearance || flexible != [false; 3] {
        return vec![case.failed(0.0, format!("first configuration is {label}, not R1 at J4"))];
    }
    match flap::run("flap", &q, &RunSettings::default()) {
        Ok(o) => vec![super::models::envelope_case(case, &q, &o)],
        Err(e) => vec![case.failed(0.0, e.to_string())],
    }
}
