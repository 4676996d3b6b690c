//! The FMU instance's state machine in Rust (what the C functions translate): the calls a
//! master makes in order step the model as `CoSim` does, and every call out of order or with a
//! bad value is refused with a message, leaving the instance usable. The C layer and the
//! archive are checked with FMPy (python/tests/test_fmu.py).

use clr_fmu::instance::{Instance, Phase, Refusal, Saved};
use clr_sim::fmu::{plan, FmuConfig, FmuRequest};

const FLAP: &str = include_str!("../../../models/examples/flap_fmu.toml");

fn instance() -> (Instance, FmuConfig) {
    let req = FmuRequest {
        parameters: vec!["clearance.J4.journal_radius".into()],
        ..Default::default()
    };
    let (config, xml) = plan("flap_fmu.toml", FLAP, &req).unwrap();
    assert!(xml.contains("causality=\"input\"") && xml.contains(&config.token));
    let inst = Instance::new(config.clone(), FLAP.to_string(), &config.token).unwrap();
    (inst, config)
}

fn refused(r: Result<(), Refusal>, what: &str) {
    let m = r.unwrap_err().message;
    assert!(m.contains(what), "{m}");
}

#[test]
fn a_master_steps_the_flap_and_bad_calls_are_refused() {
    let (mut f, c) = instance();
    let (input, angle, radius) = (c.input_vr(0), c.output_vr(0), c.parameter_vr(0));
    // out of order
    let e = f.do_step(0.0, 1e-3).unwrap_err().0;
    assert!(
        e.message.contains("not allowed in the Instantiated state"),
        "{}",
        e.message
    );
    assert!(f.exit_initialization().is_err());
    // the parameter before initialization: J4 made ideal
    assert_eq!(f.get(radius).unwrap(), 0.0099);
    f.set(radius, 0.01).unwrap();
    f.enter_initialization(Some(1e-8), 0.0).unwrap();
    f.exit_initialization().unwrap();
    assert_eq!(f.phase(), Phase::Step);
    // bad values and calls
    refused(f.set(input, f64::NAN), "must be finite");
    refused(f.set(angle, 0.1), "is an output");
    refused(f.set(radius, 0.0099), "set it before");
    refused(f.set(0, 1.0), "time is set by fmi3DoStep");
    assert!(f.get(99).unwrap_err().message.contains("does not exist"));
    let e = f.do_step(0.0, 0.0).unwrap_err().0;
    assert!(e.message.contains("positive and finite"), "{}", e.message);
    let e = f.do_step(0.3, 1e-3).unwrap_err().0;
    assert!(e.message.contains("is not the FMU's time"), "{}", e.message);
    // steps: the motion input ramps the actuator longer, which turns the flap the negative
    // way; the time lands on each communication point
    for k in 0..20 {
        f.set(input, 0.25 + 1e-4 * (k + 1) as f64).unwrap();
        let t = f.do_step(1e-3 * k as f64, 1e-3).unwrap();
        assert!((t - 1e-3 * (k + 1) as f64).abs() < 1e-15);
    }
    let a = f.get(angle).unwrap();
    assert!(a < 0.0 && a > -0.1, "flap angle {a}");
    // save, go on, restore through the serialized form: back at the saved time and angle
    let s = f.save().unwrap();
    f.do_step(0.02, 1e-3).unwrap();
    f.restore(&Saved::from_bytes(&s.to_bytes()).unwrap())
        .unwrap();
    assert!((f.get(0).unwrap() - 0.02).abs() < 1e-15);
    assert_eq!(f.get(angle).unwrap(), a);
    assert!(Saved::from_bytes(&[1, 2, 3]).is_err());
    f.terminate().unwrap();
    assert!(f.do_step(0.02, 1e-3).is_err());
    f.reset();
    assert_eq!(f.phase(), Phase::Instantiated);
    assert_eq!(f.get(radius).unwrap(), 0.0099);
}

#[test]
fn a_foreign_token_and_unknown_outputs_are_refused() {
    let (_, c) = instance();
    let e = Instance::new(c, FLAP.to_string(), "{other}").err().unwrap();
    assert!(e.message.contains("instantiation token"), "{}", e.message);
    let req = FmuRequest {
        outputs: Some(vec!["flap.angel".into()]),
        ..Default::default()
    };
    let e = plan("flap_fmu.toml", FLAP, &req).unwrap_err().to_string();
    assert!(e.contains("flap.angle"), "{e}");
}
