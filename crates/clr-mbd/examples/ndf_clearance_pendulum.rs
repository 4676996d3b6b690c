//! Reproducer for a clr-ode NDF problem met by clr-mbd: a rod hanging from a frictionless
//! clearance pin (steel Hertz internal cylinder, c = 0.5 mm, no damping), released horizontally.
//! NDF used to stop with "Newton iteration failed 21 times in one step" at h ≈ 1e-9 in free
//! flight (exact predictor, round-off corrections with a ratio ≈ 1 tripping the divergence
//! test); since the ode15s round-off floor in the Newton iteration it integrates every tolerance
//! pair below (energy drift 1.6e-6 at rtol = atol = 1e-9; DOPRI5 gives 1.8e-7, verify case
//! `mbd.energy.clearance`). Run: `cargo run --release -p clr-mbd --example
//! ndf_clearance_pendulum`.

use clr_contact::*;
use clr_mbd::*;
fn main() {
    let jb = JournalBearing {
        bearing: Material::steel(),
        journal: Material::steel(),
        r_bearing: 10e-3,
        r_journal: 9.5e-3,
        length: 0.01,
    };
    for (rtol, atol) in [(1e-9, 1e-8), (1e-9, 1e-9), (1e-10, 1e-10)] {
        let normal = NormalLaw::preset("Hertz", &jb, 1.0).unwrap();
        let mut b = ModelBuilder::new();
        b.gravity(0.0, -9.81)
            .body("rod", RigidBody::new(1.0, 0.16 / 12.0).at(0.2, 0.0, 0.0))
            .revolute_clearance(
                "pin",
                ("ground", [0.0, 0.0]),
                ("rod", [-0.2, 0.0]),
                RevoluteClearanceSpec {
                    bearing_radius: 10e-3,
                    journal_radius: 9.5e-3,
                    normal: normal.into(),
                    friction: FrictionLaw::coulomb(0.0, 1.0).unwrap().into(),
                },
            );
        let mut m = b.build().unwrap();
        let opts = SimOptions::span(0.0, 1.0, 100).tolerances(rtol, atol);
        match m.simulate(&opts) {
            Ok(res) => {
                let e = res.column("energy.total").unwrap();
                let ek = res
                    .column("energy.kinetic")
                    .unwrap()
                    .iter()
                    .cloned()
                    .fold(0.0, f64::max);
                let drift = e.iter().map(|v| (v - e[0]).abs()).fold(0.0, f64::max);
                println!(
                    "{rtol} {atol}: drift {:e} steps {} rej {} onsets {}",
                    drift / ek,
                    res.stats.accepted,
                    res.stats.rejected,
                    res.onsets
                );
            }
            Err(e) => println!("{rtol} {atol}: {e}"),
        }
    }
}
