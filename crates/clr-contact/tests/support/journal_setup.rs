//! The journal-in-bearing configurations shared by the journal tests
//! (crates/clr-contact/tests/journal.rs) and the verify cases `contact.spatial.revolute.*`
//! (xtask/src/verify/spatial_journal.rs): the flap paper's bearing (R_b = 10 mm, R_j = 9.9 mm,
//! L = 15 mm) at the origin along z, and journal states around it.

// each includer uses its own subset
#![allow(dead_code)]

use clr_contact::journal::JournalState;
use nalgebra::Vector3;

/// Bore radius, m.
pub const RB: f64 = 10e-3;
/// Journal radius, m.
pub const RJ: f64 = 9.9e-3;
/// Radial clearance, m.
pub const C: f64 = RB - RJ;
/// Bore and journal length, m.
pub const L: f64 = 15e-3;

pub fn v3(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z)
}

/// Unit axis tilted by γ from z towards the azimuth ψ (rad).
pub fn tilted(gamma: f64, psi: f64) -> Vector3<f64> {
    v3(
        gamma.sin() * psi.cos(),
        gamma.sin() * psi.sin(),
        gamma.cos(),
    )
}

/// Bearing at the origin along z, at rest; journal at `oj` along `uj` with the given velocities.
pub fn state(
    oj: Vector3<f64>,
    uj: Vector3<f64>,
    vj: Vector3<f64>,
    wj: Vector3<f64>,
) -> JournalState<f64> {
    let z = Vector3::zeros();
    JournalState::new(z, Vector3::z(), z, z, oj, uj, vj, wj)
}

/// A journal at rest at `oj` along `uj`.
pub fn still(oj: Vector3<f64>, uj: Vector3<f64>) -> JournalState<f64> {
    state(oj, uj, Vector3::zeros(), Vector3::zeros())
}
