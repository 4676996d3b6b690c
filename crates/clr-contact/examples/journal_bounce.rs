//! A journal bouncing inside a fixed bearing under gravity, with friction, integrated by a
//! hand-written semi-implicit (symplectic) Euler scheme: clr-contact used as an outside code
//! would use it, with no other clr crate.
//!
//! Steel journal (1 kg, R_j = 9.9 mm) in a steel bearing (R_i = 10 mm, L = 15 mm), Hertz +
//! Lankarani–Nikravesh normal law with c_e = 0.5, Ambrósio friction μ = 0.1. The journal starts
//! concentric with a sideways velocity and spin; every impact prints its onset time, the impact
//! velocity δ̇⁻ kept by the contact memory, the peak force and the measured normal restitution.
//!
//! Run: `cargo run -p clr-contact --example journal_bounce --release`

use clr_contact::body::{BodyState, Vector2};
use clr_contact::friction::FrictionLaw;
use clr_contact::memory::ContactMemory;
use clr_contact::normal::{JournalBearing, NormalLaw};
use clr_contact::revolute::RevoluteClearance;
use clr_contact::ContactError;

fn main() -> Result<(), ContactError> {
    let geometry = JournalBearing::flap_paper_test();
    let law = NormalLaw::preset("LN", &geometry, 0.5)?;
    let friction = FrictionLaw::ambrosio(0.1, 1e-4, 1e-3)?;
    let joint = RevoluteClearance::new(
        geometry.r_bearing,
        geometry.r_journal,
        Vector2::zeros(),
        Vector2::zeros(),
    )?;
    let mut memory = ContactMemory::new(1, law.min_impact_velocity())?;

    let mass = 1.0; // kg
    let inertia = 0.5 * mass * geometry.r_journal.powi(2); // solid cylinder, kg·m²
    let gravity = Vector2::new(0.0, -9.81); // m/s²
    let bearing = BodyState::fixed(Vector2::zeros(), 0.0);
    let mut journal = BodyState::new(Vector2::zeros(), 0.0, Vector2::new(0.3, 0.0), 20.0);

    let h = 2e-8; // s, ≈ 1/5000 of the contact time (≈ 1e-4 s)
    let t_end = 20e-3; // s
    let steps = (t_end / h) as usize;
    println!(
        "law: {:?}, effective restitution {:.4}",
        law.damping(),
        law.effective_restitution()
    );
    println!(
        "{:>4} {:>10} {:>12} {:>12} {:>12} {:>8}",
        "#", "t (ms)", "v_in (m/s)", "v_out (m/s)", "F_max (N)", "e"
    );
    let mut impacts = 0;
    let mut peak = 0.0_f64;
    let mut onset: Option<(f64, f64)> = None; // (time, δ̇⁻)
    for step in 0..steps {
        let t = step as f64 * h;
        // Forces at the start of the step (memory gives δ̇⁻, tentative during the step).
        let c = joint.contact(&bearing, &journal);
        let v_minus = memory.impact_velocity(0, c.penetration, c.normal_velocity);
        let f = c.forces_from_laws(&law, &friction, v_minus);
        peak = peak.max(f.normal_force);
        // Semi-implicit Euler: velocities first, then positions with the new velocities.
        journal.velocity += h * (f.journal.force / mass + gravity);
        journal.angular_velocity += h * f.journal.moment / inertia;
        journal.position += h * journal.velocity;
        journal.angle += h * journal.angular_velocity;
        // Accept the step: commit the end state to the memory.
        let end = joint.contact(&bearing, &journal);
        let was_open = memory.committed(0);
        memory.commit(0, end.penetration, end.normal_velocity);
        match (was_open, memory.committed(0)) {
            (None, Some(v_in)) => {
                onset = Some((t + h, v_in));
                peak = 0.0;
            }
            (Some(_), None) => {
                if let Some((t0, v_in)) = onset.take() {
                    impacts += 1;
                    let v_out = end.normal_velocity;
                    println!(
                        "{impacts:>4} {:>10.4} {v_in:>12.5} {v_out:>12.5} {peak:>12.1} {:>8.4}",
                        t0 * 1e3,
                        -v_out / v_in
                    );
                }
            }
            _ => {}
        }
    }
    println!(
        "after {:.1} ms: journal at ({:.4}, {:.4}) mm, speed {:.4} m/s, spin {:.3} rad/s",
        t_end * 1e3,
        journal.position.x * 1e3,
        journal.position.y * 1e3,
        journal.velocity.norm(),
        journal.angular_velocity
    );
    Ok(())
}
