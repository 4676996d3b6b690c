//! The lubricated revolute clearance joint's viscous shear torque in a whole model: a journal
//! driven at a constant speed in a ground-fixed lubricated bearing, with no load and no gravity
//! (so it stays centred, ε = 0), needs the drive torque of Petroff's law,
//! T = 2πμr³Lω/c (N.P. Petroff 1883; Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film
//! Lubrication*, 2nd ed. 2004, ch. 10), and the energy balance closes with the film's power
//! counted as dissipated.

use clr_mbd::ModelDesc;

fn col(r: &clr_mbd::Results, name: &str) -> Vec<f64> {
    r.column(name)
        .unwrap_or_else(|| panic!("no column {name} in {:?}", r.columns))
}

/// tests/data/lubricated_journal.toml: journal r = 9.9 mm in a bearing R = 10 mm (c = 0.1 mm),
/// L = 10 mm, μ = 0.05 Pa·s, driven at ω = 200 rad/s from the centre, NDF rtol 1e-9, 0.3 s.
/// Tolerances: the drive torque (the driver's reaction moment `spin.M`) 1e-9 relative to
/// Petroff's (the journal never leaves the centre, so the only error is the solve's round-off);
/// the input work W_in = Tω·t to 1e-8 relative and the balance drift to 1e-8 of the work done
/// (the integrands are constant: round-off only).
#[test]
fn driven_journal_needs_the_petroff_torque() {
    let (r_b, r_j, l, mu, w) = (0.01f64, 0.0099f64, 0.01f64, 0.05f64, 200.0f64);
    let text = include_str!("../../../tests/data/lubricated_journal.toml");
    let desc = ModelDesc::from_toml_table(text.parse().unwrap()).unwrap();
    let mut m = desc.compile().unwrap();
    let res = m.simulate(&desc.sim_options().unwrap()).unwrap();
    let petroff = 2.0 * std::f64::consts::PI * mu * r_j.powi(3) * l * w / (r_b - r_j);
    let (t, torque) = (col(&res, "t"), col(&res, "spin.M"));
    let worst = torque
        .iter()
        .map(|m| (m / petroff - 1.0).abs())
        .fold(0.0f64, f64::max);
    eprintln!("Petroff {petroff} N·m, drive torque error {worst:e}");
    assert!(
        worst < 1e-9,
        "drive torque vs Petroff {petroff} N·m: {worst:e}"
    );
    let work = col(&res, "energy.work_in");
    let last = t.len() - 1;
    let expected = petroff * w * (t[last] - t[0]);
    let work_err = (work[last] / expected - 1.0).abs();
    let bal = col(&res, "energy.balance");
    let drift = bal
        .iter()
        .map(|b| (b - bal[0]).abs())
        .fold(0.0f64, f64::max);
    eprintln!(
        "W_in error {work_err:e}, balance drift {:e}",
        drift / expected
    );
    assert!(work_err < 1e-8, "W_in {} vs Tωt {expected}", work[last]);
    assert!(
        drift < 1e-8 * expected,
        "balance drift {drift:e} J of {expected} J"
    );
    let ecc = col(&res, "J.ex");
    assert!(
        ecc.iter().all(|e| e.abs() < 1e-12),
        "the journal stays centred"
    );
}
