//! The two ways of applying a revolute clearance joint's force pair (`ForceApplication`), checked
//! against the closed-form net moment of the pair about the world origin.
//!
//! Setup: contact-laws.md §7.7 (bearing fixed at the origin, journal centre at (c + δ)·n with
//! n = (0.6, 0.8), c = 0.1 mm, δ = 10 µm, journal reference at its centre).

use clr_contact::{BodyState, ForceApplication, RevoluteClearance};
use nalgebra::Vector2;

fn net_moment_about_origin(
    f: &clr_contact::revolute::JointForces,
    ri: Vector2<f64>,
    rj: Vector2<f64>,
) -> f64 {
    let cross = |a: Vector2<f64>, b: Vector2<f64>| a.x * b.y - a.y * b.x;
    f.bearing.moment + cross(ri, f.bearing.force) + f.journal.moment + cross(rj, f.journal.force)
}

#[test]
fn contact_points_pair_has_moment_delta_times_friction_and_common_point_has_none() {
    let n = Vector2::new(0.6, 0.8);
    let (c, delta) = (0.1e-3, 10e-6);
    let joint = RevoluteClearance::new(10e-3, 9.9e-3, Vector2::zeros(), Vector2::zeros()).unwrap();
    let bearing = BodyState::fixed(Vector2::zeros(), 0.0);
    let rj = (c + delta) * n;
    let journal = BodyState::new(rj, 0.3, Vector2::new(0.3, 0.4), 10.0);
    let contact = joint.contact(&bearing, &journal);
    let (f_n, f_t) = (7455.4750, -745.5475);

    // Flores form: f_j at r_j^Q, f_i = −f_j at r_i^Q = r_j^Q − δ n, so the pair's net moment is
    // (r_j^Q − r_i^Q) × f_j = δ n × (F_T t) = δ·F_T (n × t = 1).
    let flores = contact.generalized_forces_with(f_n, f_t, ForceApplication::ContactPoints);
    assert_eq!(flores, contact.generalized_forces(f_n, f_t));
    let m = net_moment_about_origin(&flores, Vector2::zeros(), rj);
    assert!(
        (m - delta * f_t).abs() < 1e-12 * f_n,
        "net moment {m} vs δ·F_T {}",
        delta * f_t
    );

    // Common point: collinear action and reaction, zero net moment (to round-off).
    let common = contact.generalized_forces_with(f_n, f_t, ForceApplication::CommonPoint);
    let m = net_moment_about_origin(&common, Vector2::zeros(), rj);
    assert!(m.abs() < 1e-12 * f_n, "net moment {m}");
    // Forces are the same in both forms; moments differ by O(δ/R).
    assert_eq!(common.journal.force, flores.journal.force);
    let rel = (common.bearing.moment - flores.bearing.moment).abs() / flores.bearing.moment.abs();
    assert!(rel < 1e-3, "bearing moments differ by {rel}");
}
