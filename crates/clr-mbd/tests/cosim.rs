//! The co-simulation stepper ([`clr_mbd::cosim::CoSim`]) against closed forms and against one
//! whole run:
//!
//! - a disc under a torque input that a discrete PI-like law sets at every communication point:
//!   with the torque held over each step, the exact discrete recursion θ_{k+1} = θ_k + ω_k h +
//!   u_k h²/(2I), ω_{k+1} = ω_k + u_k h/I is the reference (independent of the integrator);
//! - a disc driven by a motion input set to sin(t_k): the angle reaches each set value at its
//!   point and the rate is the ramp's slope;
//! - the built-in slider–crank's model file (clearance, impacts) stepped at 1 ms against one
//!   `simulate` run recorded at the same times: within the solver's tolerance;
//! - save and restore; the errors a master meets.

use clr_mbd::cosim::CoSim;
use clr_mbd::ModelDesc;

const DISC: &str = r#"
[[point]]
name = "origin"
body = "ground"
at = [0.0, 0.0]

[[body]]
name = "disc"
mass = 2.0
inertia = 0.5
position = [0.0, 0.0]
angle = 0.0
angular_velocity = 0.0

[[joint]]
name = "pin"
type = "revolute"
a = "origin"
b = { body = "disc", at = [0.0, 0.0] }

[[input]]
name = "u"

[[force]]
name = "motor"
type = "torque"
body = "disc"
torque = { type = "input", name = "u" }

[solver]
rtol = 1e-10

[output]
t_end = 1.0
"#;

/// The disc with its angle driven by the input instead of a torque.
fn driven_disc() -> String {
    DISC.replace(
        r#"[[force]]
name = "motor"
type = "torque"
body = "disc"
torque = { type = "input", name = "u" }"#,
        r#"[[driver]]
name = "motor"
type = "angle"
body = "disc"
motion = { type = "input", name = "u" }"#,
    )
}

fn cosim(text: &str) -> CoSim {
    let d = ModelDesc::from_toml_table(text.parse().unwrap()).unwrap();
    CoSim::new(d.compile().unwrap(), &d.sim_options().unwrap()).unwrap()
}

fn col(c: &CoSim, name: &str) -> usize {
    c.columns().iter().position(|n| n == name).unwrap()
}

#[test]
fn held_torque_loop_matches_the_exact_discrete_recursion() {
    let mut c = cosim(DISC);
    let (th, om) = (col(&c, "disc.theta"), col(&c, "disc.omega"));
    let (h, inertia, target) = (0.01, 0.5, 1.0);
    let (mut th_ref, mut om_ref) = (0.0_f64, 0.0_f64);
    for k in 0..200 {
        let u = 4.0 * (target - th_ref) - 1.5 * om_ref;
        c.set_input(0, u).unwrap();
        c.advance_to(h * (k + 1) as f64).unwrap();
        th_ref += om_ref * h + u * h * h / (2.0 * inertia);
        om_ref += u * h / inertia;
        let row = c.outputs().to_vec();
        // tolerance: 1e-8 absolute at rtol 1e-10 over 200 restarts (each held value is a jump)
        assert!(
            (row[th] - th_ref).abs() < 1e-8,
            "θ at step {k}: {} vs {th_ref}",
            row[th]
        );
        assert!(
            (row[om] - om_ref).abs() < 1e-8,
            "ω at step {k}: {} vs {om_ref}",
            row[om]
        );
        assert_eq!(
            row[0],
            h * (k + 1) as f64,
            "the time column is the point itself"
        );
    }
    assert!(
        (th_ref - target).abs() < 0.2,
        "the loop settles towards the target"
    );
}

#[test]
fn motion_input_reaches_each_set_value_at_its_point() {
    let text = driven_disc();
    let mut c = cosim(&text);
    let (th, om) = (col(&c, "disc.theta"), col(&c, "disc.omega"));
    let h = 0.02;
    let mut prev = 0.0_f64;
    for k in 1..=50 {
        let t = h * k as f64;
        c.set_input(0, t.sin()).unwrap();
        c.advance_to(t).unwrap();
        let row = c.outputs().to_vec();
        // the ramp's closed form: θ(t_k) = sin t_k, ω = (sin t_k − sin t_{k−1})/h
        assert!((row[th] - t.sin()).abs() < 1e-9, "θ({t}) = {}", row[th]);
        assert!(
            (row[om] - (t.sin() - prev) / h).abs() < 1e-7,
            "ω({t}) = {}",
            row[om]
        );
        prev = t.sin();
    }
}

#[test]
fn slider_crank_stepped_matches_one_run_within_tolerance() {
    let text = include_str!("../../../models/slider_crank.toml");
    let d = ModelDesc::from_toml_table(text.parse().unwrap()).unwrap();
    let mut opts = d.sim_options().unwrap();
    // 0.03 s: a crank revolution with the journal's flights and impacts
    let (h, n) = (1e-3, 30);
    opts.t_end = h * n as f64;
    opts.every_step = false;
    opts.times = (0..=n).map(|k| h * k as f64).collect();
    let slider = |mut o: clr_mbd::SimOptions, rtol: f64| {
        o.rtol = rtol;
        let r = d.compile().unwrap().simulate(&o).unwrap();
        r.column("slider.x").unwrap()
    };
    let (run, reference) = (slider(opts.clone(), opts.rtol), slider(opts.clone(), 1e-11));
    let mut c = CoSim::new(d.compile().unwrap(), &opts).unwrap();
    let sx = col(&c, "slider.x");
    let (mut stepped_err, mut run_err) = (0.0_f64, 0.0_f64);
    for k in 1..=n {
        c.advance_to(h * k as f64).unwrap();
        stepped_err = stepped_err.max((c.outputs()[sx] - reference[k]).abs());
        run_err = run_err.max((run[k] - reference[k]).abs());
    }
    eprintln!("stepped {stepped_err:e} m, one run {run_err:e} m against rtol 1e-11");
    // "within the solver's tolerance": the stepped run's error against a run at rtol 1e-11 is of
    // the order of the one run's own error at the same rtol (factor 5 allowed: the cut steps
    // change where the local errors fall, and the impacts amplify them; measured 2.9×)
    assert!(
        stepped_err < 5.0 * run_err.max(1e-9),
        "{stepped_err} vs {run_err}"
    );
}

#[test]
fn save_restore_and_master_mistakes() {
    let mut c = cosim(DISC);
    c.set_input(0, 1.0).unwrap();
    c.advance_to(0.5).unwrap();
    let saved = c.save();
    c.advance_to(1.0).unwrap();
    let first = c.outputs().to_vec();
    c.restore(&saved).unwrap();
    assert_eq!(c.time(), 0.5);
    c.advance_to(1.0).unwrap();
    let again = c.outputs().to_vec();
    // θ(1) = u t²/(2I) = 1 rad under the held torque 1 N·m (closed form); both runs match it
    let th = col(&c, "disc.theta");
    assert!((first[th] - 1.0).abs() < 1e-8 && (again[th] - 1.0).abs() < 1e-8);
    let e = c.advance_to(1.0).unwrap_err().to_string();
    assert!(e.contains("after the current time"), "{e}");
    let e = c.advance_to(f64::NAN).unwrap_err().to_string();
    assert!(e.contains("finite"), "{e}");
    assert!(c
        .set_input(0, f64::NAN)
        .unwrap_err()
        .to_string()
        .contains("`u`"));
    assert!(c
        .set_input(3, 1.0)
        .unwrap_err()
        .to_string()
        .contains("1 inputs"));
}

/// A motion input set once and then left alone: the ramp of the first step ends at the first
/// point and the driver holds there. The rate's jump at that point is a restart with the
/// velocities projected, so the disc stops there (closed form: θ = 0.01 rad, ω = 0 after
/// 0.01 s) instead of being pulled back by the stabilization.
#[test]
fn a_motion_set_once_holds_after_its_ramp() {
    let text = driven_disc();
    let mut c = cosim(&text);
    let (th, om) = (col(&c, "disc.theta"), col(&c, "disc.omega"));
    c.set_input(0, 0.01).unwrap();
    for k in 1..=20 {
        c.advance_to(0.01 * k as f64).unwrap();
        let row = c.outputs().to_vec();
        assert!(
            (row[th] - 0.01).abs() < 1e-9,
            "θ({}) = {}",
            0.01 * k as f64,
            row[th]
        );
        if k > 1 {
            assert!(row[om].abs() < 1e-9, "ω({}) = {}", 0.01 * k as f64, row[om]);
        }
    }
}
