//! Rules of the contact memory (module docs of `clr_contact::memory`), one test per rule, plus an
//! end-to-end check: a free bouncing impact integrated with rejected and accepted steps keeps
//! the closed-form restitution.

use clr_contact::memory::{crossing_rate, crossing_rate_hermite, ContactMemory};

#[test]
fn floor_must_be_positive() {
    assert!(ContactMemory::new(3, 0.0).is_err());
    assert!(ContactMemory::new(3, -1.0).is_err());
    assert!(ContactMemory::new(3, f64::NAN).is_err());
    let m = ContactMemory::new(3, 1e-4).unwrap();
    assert_eq!(m.len(), 3);
    assert!((0..3).all(|k| m.committed(k).is_none()));
}

#[test]
fn trial_states_only_touch_tentative_values() {
    // Rule 2: committed (δ, δ̇) = (−1 µm, 0.5); trial (+1 µm, 0.3) → crossing halfway, δ̇⁻ = 0.4.
    let mut m = ContactMemory::new(1, 1e-4).unwrap();
    m.commit(0, -1e-6, 0.5);
    let v = m.impact_velocity(0, 1e-6, 0.3);
    assert!((v - 0.4).abs() < 1e-15, "{v}");
    assert_eq!(m.tentative(0), Some(v));
    assert_eq!(m.committed(0), None);
}

#[test]
fn rejected_step_restores_committed_state() {
    // Rule 3: after discard, tentative values are gone and the committed memory is unchanged;
    // a retried (smaller) step computes its own onset.
    let mut m = ContactMemory::new(2, 1e-4).unwrap();
    m.commit(0, -1e-6, 0.5);
    m.commit(1, 2e-6, 0.1); // point 1 opens at the first commit with δ̇⁻ = 0.1 (no history)
    let before = m.clone();
    m.impact_velocity(0, 3e-6, 0.2);
    m.impact_velocity(1, 1e-6, -0.3);
    m.discard();
    assert_eq!(m, before);
    let v = m.impact_velocity(0, 1e-6, 0.3);
    assert!((v - 0.4).abs() < 1e-15);
}

#[test]
fn commit_records_onset_keeps_it_and_resets_on_separation() {
    // Rule 4.
    let mut m = ContactMemory::new(1, 1e-4).unwrap();
    m.commit(0, -2e-6, 1.0);
    m.commit(0, 2e-6, 0.8); // onset: θ = 0.5 → 0.9
    assert!((m.committed(0).unwrap() - 0.9).abs() < 1e-15);
    assert_eq!(m.tentative(0), None);
    m.commit(0, 5e-6, 0.1); // stays in contact: unchanged
    assert!((m.committed(0).unwrap() - 0.9).abs() < 1e-15);
    // While open, trial states use the committed value whatever their rate.
    assert_eq!(m.impact_velocity(0, 1e-6, -0.5), 0.9);
    m.commit(0, -1e-7, -0.7); // separated: reset
    assert_eq!(m.committed(0), None);
    m.commit(0, -3e-6, 0.6);
    m.commit(0, 1e-6, 0.2); // new onset: θ = 0.75 → 0.3
    assert!((m.committed(0).unwrap() - 0.3).abs() < 1e-15);
}

#[test]
fn onset_rate_is_floored() {
    // Rule 5: a contact closing at (numerically) zero speed gets the floor.
    let mut m = ContactMemory::new(1, 1e-3).unwrap();
    m.commit(0, -1e-9, 0.0);
    m.commit(0, 1e-9, 0.0);
    assert_eq!(m.committed(0), Some(1e-3));
    let mut m = ContactMemory::new(1, 1e-3).unwrap();
    assert_eq!(m.impact_velocity(0, -1.0, 5.0), 1e-3);
    assert_eq!(m.impact_velocity(0, 1e-6, -5.0), 1e-3);
}

#[test]
fn reset_forgets_everything() {
    let mut m = ContactMemory::new(1, 1e-4).unwrap();
    m.commit(0, 1e-6, 0.5);
    assert!(m.committed(0).is_some());
    m.reset();
    assert_eq!(m, ContactMemory::new(1, 1e-4).unwrap());
}

#[test]
fn crossing_interpolation_helpers() {
    // Linear: exact when δ̇ is linear in δ (δ̇ = 1 − 100 δ here).
    let rate = |d: f64| 1.0 - 100.0 * d;
    assert!((crossing_rate(-3e-3, rate(-3e-3), 1e-3, rate(1e-3)) - 1.0).abs() < 1e-14);
    // No bracket: the after-state rate.
    assert_eq!(crossing_rate(1e-3, 2.0, 2e-3, 3.0), 3.0);
    // Hermite: exact for δ(t) cubic, here δ = −1e-6 + 0.2 t + 3 t² − 40 t³ over h = 1e-5.
    let d = |t: f64| -1e-6 + 0.2 * t + 3.0 * t * t - 40.0 * t * t * t;
    let dd = |t: f64| 0.2 + 6.0 * t - 120.0 * t * t;
    let h = 1e-5;
    let got = crossing_rate_hermite(h, d(0.0), dd(0.0), d(h), dd(h));
    // Crossing time by bisection on the exact cubic (independent root finder).
    let (mut lo, mut hi) = (0.0, h);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if d(mid) <= 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    assert!((got - dd(lo)).abs() < 1e-12, "{got} vs {}", dd(lo));
}

/// End to end: a 1-D Hertz–Lankarani–Nikravesh impact integrated by RK4 with a step-doubling
/// error test that rejects steps; the memory follows the rules above. Reference: the
/// closed-form restitution of the L-N factor at c_e = 0.5, e = 0.725241 (contact-laws.md §1.3,
/// §7.3, given to 6 digits); tolerance 1e-5.
#[test]
fn bouncing_impact_with_rejected_steps_keeps_the_closed_form_restitution() {
    let (k, m_mass, chi) = (1.5e11_f64, 1.0, 0.5625);
    let mut mem = ContactMemory::new(1, 1e-4).unwrap();
    // State (x, v): x is the penetration δ, v = δ̇.
    let rhs = |mem: &mut ContactMemory, x: f64, v: f64| -> (f64, f64) {
        let v0 = mem.impact_velocity(0, x, v);
        let f = if x > 0.0 {
            (k * x.powf(1.5) * (1.0 + chi * v / v0)).max(0.0)
        } else {
            0.0
        };
        (v, -f / m_mass)
    };
    let rk4 = |mem: &mut ContactMemory, x: f64, v: f64, h: f64| {
        let k1 = rhs(mem, x, v);
        let k2 = rhs(mem, x + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
        let k3 = rhs(mem, x + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
        let k4 = rhs(mem, x + h * k3.0, v + h * k3.1);
        (
            x + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
            v + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
        )
    };
    let (mut x, mut v) = (-1e-6, 0.5);
    mem.commit(0, x, v);
    let mut h = 4e-6;
    let mut rejected = 0;
    let mut t = 0.0;
    while t < 1e-3 && !(x < 0.0 && v < 0.0 && t > 1e-5) {
        let full = rk4(&mut mem, x, v, h);
        let half = rk4(&mut mem, x, v, 0.5 * h);
        let two = rk4(&mut mem, half.0, half.1, 0.5 * h);
        let err = (two.1 - full.1).abs();
        if err > 1e-7 {
            mem.discard();
            h *= 0.5;
            rejected += 1;
            continue;
        }
        (x, v) = two;
        t += h;
        mem.commit(0, x, v);
        if err < 1e-9 {
            h = (h * 1.5).min(4e-6);
        }
    }
    assert!(rejected > 0, "the test must exercise rejected steps");
    let e = -v / 0.5;
    assert!((e - 0.725241).abs() < 1e-5, "e = {e}");
}
