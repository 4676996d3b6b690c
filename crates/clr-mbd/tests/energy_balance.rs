//! The input work W_in (`energy.work_in`) and the energy balance (`energy.balance` = kinetic +
//! potential + elastic + dissipated − work_in) against independent formulations:
//!
//! - a beam released under its own weight: the balance stays constant with the weight in the
//!   potential energy;
//! - each applied load (torque, force at an offset point, torque between two bodies, actuator
//!   force, nodal load on a beam) at constant magnitude: W_in = load × displacement of its
//!   work-conjugate coordinate, a closed form from the recorded coordinates (1e-8 relative);
//! - a crank driven at constant speed by an angle driver against gravity and a rotational
//!   spring–damper: W_in = ∫ M·ω dt by the trapezoid rule on the recorded driver reaction moment
//!   and crank speed, to the trapezoid rule's own error bound;
//! - a driven slider–crank with a revolute clearance joint (Lankarani–Nikravesh damping) and
//!   Ambrósio friction μ = 0.1: the balance stays constant to 100·rtol = 1e-6 of the largest
//!   kinetic energy at rtol 1e-8 (measured 8.8e-8).
//!
//! Each run takes well under a second in the test profile.

use clr_contact::{FrictionLaw, JournalBearing, Material, NormalLaw};
use clr_mbd::desc::{BeamMaterial, MassKindDesc, SectionDesc, SupportDesc, SupportKind};
use clr_mbd::{
    BeamMesh, ModelBuilder, Results, RevoluteClearanceSpec, RigidBody, SimOptions, SolverKind,
    TimeFn,
};

fn col(r: &Results, name: &str) -> Vec<f64> {
    r.column(name)
        .unwrap_or_else(|| panic!("no column {name} in {:?}", r.columns))
}

fn max_abs(v: impl IntoIterator<Item = f64>) -> f64 {
    v.into_iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

/// Largest |work_in − expected| relative to the largest |expected|, and the largest change of the
/// balance relative to the same scale.
fn compare(r: &Results, expected: &[f64]) -> (f64, f64) {
    let w = col(r, "energy.work_in");
    let b = col(r, "energy.balance");
    let scale = max_abs(expected.iter().copied());
    assert!(scale > 0.1, "the load does work: {scale} J");
    let err = max_abs(w.iter().zip(expected).map(|(a, e)| a - e)) / scale;
    let drift = max_abs(b.iter().map(|x| x - b[0])) / scale;
    (err, drift)
}

fn tight() -> SimOptions {
    SimOptions::span(0.0, 2.0, 200).tolerances(1e-11, 1e-13)
}

/// A bar pinned to the ground at one end, no gravity, turned by a constant torque τ:
/// W_in = τ(θ(t) − θ0), and the balance (kinetic energy − W_in) stays constant.
#[test]
fn constant_torque_work_is_torque_times_angle() {
    let tau = 0.8;
    let mut b = ModelBuilder::new();
    b.body(
        "bar",
        RigidBody::new(2.0, 0.06)
            .at(0.3, 0.0, 0.0)
            .moving(0.0, 0.3, 1.0),
    )
    .revolute("pin", ("ground", [0.0, 0.0]), ("bar", [-0.3, 0.0]))
    .torque("drive", "bar", TimeFn::constant(tau));
    let mut m = b.build().unwrap();
    let r = m.simulate(&tight()).unwrap();
    let th = col(&r, "bar.theta");
    let expected: Vec<f64> = th.iter().map(|t| tau * (t - th[0])).collect();
    let (err, drift) = compare(&r, &expected);
    eprintln!(
        "torque: W_in = {:.6} J, rel. error {err:.2e}, balance drift {drift:.2e}",
        expected.last().unwrap()
    );
    assert!(err < 1e-8, "W_in vs τΔθ: {err:e}");
    assert!(drift < 1e-8, "balance: {drift:e}");
}

/// A free body (no gravity) pushed by a constant force F at a body-fixed point s off its centre
/// of mass: W_in = F·(P(t) − P(0)) with P = r + A(θ)s (the power F·v_P includes the moment
/// s × F times ω).
#[test]
fn constant_force_work_is_force_times_point_displacement() {
    let (fx, fy, s) = (1.5, -0.5, [0.1, 0.05]);
    let mut b = ModelBuilder::new();
    b.body(
        "a",
        RigidBody::new(1.2, 0.02)
            .at(0.0, 0.0, 0.3)
            .moving(0.2, 0.1, -2.0),
    )
    .force("push", ("a", s), TimeFn::constant(fx), TimeFn::constant(fy));
    let mut m = b.build().unwrap();
    let r = m.simulate(&tight()).unwrap();
    let (x, y, th) = (col(&r, "a.x"), col(&r, "a.y"), col(&r, "a.theta"));
    let p: Vec<[f64; 2]> = (0..x.len())
        .map(|k| {
            let (sn, cs) = th[k].sin_cos();
            [x[k] + cs * s[0] - sn * s[1], y[k] + sn * s[0] + cs * s[1]]
        })
        .collect();
    let expected: Vec<f64> = p
        .iter()
        .map(|pk| fx * (pk[0] - p[0][0]) + fy * (pk[1] - p[0][1]))
        .collect();
    let (err, drift) = compare(&r, &expected);
    eprintln!("force: rel. error {err:.2e}, balance drift {drift:.2e}");
    assert!(err < 1e-8, "W_in vs F·ΔP: {err:e}");
    assert!(drift < 1e-8, "balance: {drift:e}");
}

/// A motor torque τ between two free bodies (+τ on j, −τ on i): W_in = τ(Δθ_j − Δθ_i); and an
/// actuator pushing a free block away from a ground point with a constant force F:
/// W_in = F·(l(t) − l(0)).
#[test]
fn torque_between_and_actuator_work() {
    let tau = 0.3;
    let mut b = ModelBuilder::new();
    b.body("i", RigidBody::new(1.0, 0.01).moving(0.0, 0.0, 0.5))
        .body("j", RigidBody::new(1.0, 0.03).at(1.0, 0.0, 0.0))
        .motor_torque("motor", "i", "j", TimeFn::constant(tau));
    let mut m = b.build().unwrap();
    let r = m.simulate(&tight()).unwrap();
    let (ti, tj) = (col(&r, "i.theta"), col(&r, "j.theta"));
    let expected: Vec<f64> = (0..ti.len())
        .map(|k| tau * ((tj[k] - tj[0]) - (ti[k] - ti[0])))
        .collect();
    let (err, drift) = compare(&r, &expected);
    eprintln!("torque between: rel. error {err:.2e}, balance drift {drift:.2e}");
    assert!(err < 1e-8, "W_in vs τ(Δθ_j − Δθ_i): {err:e}");
    assert!(drift < 1e-8, "balance: {drift:e}");

    let f = 2.0;
    let mut b = ModelBuilder::new();
    b.body(
        "block",
        RigidBody::new(0.5, 0.01)
            .at(0.3, 0.4, 0.0)
            .moving(0.0, -0.2, 0.0),
    )
    .actuator(
        "jack",
        ("ground", [0.0, 0.0]),
        ("block", [0.0, 0.0]),
        TimeFn::constant(f),
        0.0,
    );
    let mut m = b.build().unwrap();
    let r = m.simulate(&tight()).unwrap();
    let (x, y) = (col(&r, "block.x"), col(&r, "block.y"));
    let l: Vec<f64> = x.iter().zip(&y).map(|(x, y)| x.hypot(*y)).collect();
    let expected: Vec<f64> = l.iter().map(|lk| f * (lk - l[0])).collect();
    let (err, drift) = compare(&r, &expected);
    eprintln!("actuator: rel. error {err:.2e}, balance drift {drift:.2e}");
    assert!(err < 1e-8, "W_in vs FΔl: {err:e}");
    assert!(drift < 1e-8, "balance: {drift:e}");
}

/// A steel strip (20 × 5 mm) from `start` to `end` (m), 4 elements, clamped at `start`,
/// undamped, consistent mass.
fn steel_strip(start: [f64; 2], end: [f64; 2]) -> BeamMesh {
    let steel = clr_beam::Material::steel();
    BeamMesh {
        start,
        end,
        elements: 4,
        material: BeamMaterial {
            youngs_modulus: steel.youngs_modulus,
            density: steel.density,
            poisson_ratio: steel.poisson_ratio,
        },
        section: SectionDesc::Rectangular {
            width: 0.02,
            depth: 0.005,
        },
        supports: vec![SupportDesc {
            node: 0,
            kind: SupportKind::Clamped,
        }],
        rayleigh: [0.0, 0.0],
        mass: MassKindDesc::Consistent,
    }
}

/// A steel cantilever (0.5 m, 4 elements, 20 × 5 mm, undamped) with a constant tip load
/// (F_y, M) applied at t = 0: W_in = F_y·v_tip + M·θ_tip (the tip displacements from rest, as
/// recorded), and the balance (beam kinetic + elastic energy − W_in) stays constant. This fails
/// when the nodal loads' power is not accounted.
#[test]
fn nodal_load_work_is_load_times_tip_displacement() {
    let mesh = steel_strip([0.0, 0.0], [0.5, 0.0]);
    let (fy, mz) = (-20.0, 1.5);
    let mut b = ModelBuilder::new();
    b.flexible_beam("beam", mesh).nodal_load(
        "tip",
        "beam",
        4,
        [
            TimeFn::constant(0.0),
            TimeFn::constant(fy),
            TimeFn::constant(mz),
        ],
    );
    let mut m = b.build().unwrap();
    let r = m
        .simulate(&SimOptions::span(0.0, 0.05, 200).tolerances(1e-10, 1e-13))
        .unwrap();
    let (v, th) = (col(&r, "beam.n4.v"), col(&r, "beam.n4.theta"));
    let expected: Vec<f64> = (0..v.len())
        .map(|k| fy * (v[k] - v[0]) + mz * (th[k] - th[0]))
        .collect();
    let (err, drift) = compare(&r, &expected);
    eprintln!(
        "nodal load: max W_in = {:.4} J, rel. error {err:.2e}, balance drift {drift:.2e}",
        max_abs(expected.iter().copied())
    );
    assert!(err < 1e-8, "W_in vs F·Δu: {err:e}");
    assert!(drift < 1e-6, "balance: {drift:e}");
}

/// A steel cantilever (0.5 m, 4 elements, 20 × 5 mm, clamped at (0, 0.2) m, inclined at 30°,
/// Rayleigh α = 50 s⁻¹) released from rest under gravity (0, −9.81 m/s²): its potential energy
/// starts at m g y_c (the centroid's height y_c = 0.2 + 0.25 sin 30° m; closed form, 1e-12), the
/// weight does no input work (W_in = 0: it is in the potential energy) and the balance
/// (kinetic + potential + elastic + dissipated) stays constant to 1e-6 of the largest kinetic
/// energy, the tolerance of the other balance tests at this rtol. This fails when the weight's
/// nodal loads are not the gradient of the beam's potential energy.
#[test]
fn beam_weight_is_in_the_potential_energy() {
    let steel = clr_beam::Material::steel();
    let (l, (c, s), y0) = (
        0.5,
        (30f64.to_radians().cos(), 30f64.to_radians().sin()),
        0.2,
    );
    let (width, depth) = (0.02, 0.005);
    let mesh = BeamMesh {
        rayleigh: [50.0, 0.0],
        ..steel_strip([0.0, y0], [l * c, y0 + l * s])
    };
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -9.81).flexible_beam("beam", mesh);
    let mut m = b.build().unwrap();
    let r = m
        .simulate(&SimOptions::span(0.0, 0.1, 200).tolerances(1e-10, 1e-13))
        .unwrap();
    let mass = steel.density * width * depth * l;
    let pot0 = mass * 9.81 * (y0 + 0.5 * l * s);
    let pot = col(&r, "energy.potential");
    assert!(
        (pot[0] - pot0).abs() < 1e-12 * pot0,
        "E_pot(0) {} vs m g y_c {pot0}",
        pot[0]
    );
    let kmax = max_abs(col(&r, "energy.kinetic"));
    let dissipated = max_abs(col(&r, "energy.dissipated"));
    let bal = col(&r, "energy.balance");
    let drift = max_abs(bal.iter().map(|x| x - bal[0])) / kmax;
    eprintln!(
        "beam weight: max E_kin {kmax:.3e} J, dissipated {dissipated:.3e} J, balance drift \
         {drift:.2e}"
    );
    assert!(dissipated > 0.1 * kmax, "the damping dissipates");
    assert_eq!(max_abs(col(&r, "energy.work_in")), 0.0);
    assert!(drift < 1e-6, "balance: {drift:e}");
}

/// A crank (centre of mass 0.05 m from its pin) driven at ω = 10 rad/s by an `angle` driver
/// against gravity and a rotational spring–damper to the ground (k = 2 N·m/rad, c = 0.05
/// N·m·s): W_in against the trapezoid rule on P = M·ω from the recorded driver reaction moment
/// `motor.M` and `crank.omega` at 2001 output times over 1 s. Tolerance: the trapezoid error
/// bound (t_end − t0)·h²/12·max|P''| with P'' from second differences of the samples, times 2,
/// plus 1e-9 of the work for the integrator.
#[test]
fn driver_work_matches_the_integrated_reaction_power() {
    let (w, r_c) = (10.0, 0.05);
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -9.81)
        .body(
            "crank",
            RigidBody::new(0.5, 2e-3)
                .at(r_c, 0.0, 0.0)
                .moving(0.0, w * r_c, w),
        )
        .revolute("O", ("ground", [0.0, 0.0]), ("crank", [-r_c, 0.0]))
        .drive_angle("motor", "crank", TimeFn::linear(0.0, w))
        .rotational_spring_damper("spring", "ground", "crank", 2.0, 0.05, 0.0);
    let mut m = b.build().unwrap();
    let (t_end, n) = (1.0, 2000);
    let r = m
        .simulate(&SimOptions::span(0.0, t_end, n).tolerances(1e-10, 1e-12))
        .unwrap();
    let (t, mm, om) = (col(&r, "t"), col(&r, "motor.M"), col(&r, "crank.omega"));
    let wi = col(&r, "energy.work_in");
    let p: Vec<f64> = mm.iter().zip(&om).map(|(a, b)| a * b).collect();
    let mut trap = vec![0.0; p.len()];
    for k in 1..p.len() {
        trap[k] = trap[k - 1] + 0.5 * (t[k] - t[k - 1]) * (p[k] + p[k - 1]);
    }
    let h = t_end / n as f64;
    let p2 = max_abs((1..p.len() - 1).map(|k| (p[k + 1] - 2.0 * p[k] + p[k - 1]) / (h * h)));
    let bound = 2.0 * t_end * h * h / 12.0 * p2;
    let scale = max_abs(wi.iter().copied());
    let err = max_abs(wi.iter().zip(&trap).map(|(a, b)| a - b));
    let b = col(&r, "energy.balance");
    let drift = max_abs(b.iter().map(|x| x - b[0]));
    eprintln!(
        "driver: W_in = {:.6} J (max {scale:.4} J), |W_in − trapezoid| = {err:.3e} J, bound \
         {bound:.3e} J; balance drift {drift:.3e} J",
        wi.last().unwrap()
    );
    assert!(scale > 0.1, "the driver does work: {scale} J");
    assert!(err <= bound + 1e-9 * scale, "{err:e} > {bound:e}");
    assert!(drift <= 1e-7 * scale, "balance: {drift:e}");
}

/// The slider–crank of the verify cases (crank 0.05 m, rod 0.3 m, Flores' masses) driven at
/// 5000 rpm, with a 0.5 mm revolute clearance between rod and slider (Lankarani–Nikravesh,
/// c_e = 0.9) and Ambrósio friction μ = 0.1, gravity, 0.03 s: the driver puts work in, contact
/// damping and friction dissipate it, and the balance stays constant to 100·rtol = 1e-6 of the
/// largest kinetic energy at rtol 1e-8 (measured 8.8e-8, 4.9e-5 J of 562 J). Before the
/// dissipated power of the contact pair was taken from the forces as applied (at the common
/// point of the two contact points) the drift was 1.2e-5, whatever the tolerance.
#[test]
fn driven_clearance_slider_crank_with_friction_balances() {
    let (crank, rod) = (0.05, 0.3);
    let omega = 5000.0 * std::f64::consts::PI / 30.0;
    let jb = JournalBearing {
        bearing: Material::steel(),
        journal: Material::steel(),
        r_bearing: 10e-3,
        r_journal: 9.5e-3,
        length: 0.01,
    };
    let normal = NormalLaw::preset("LN", &jb, 0.9).unwrap();
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -9.81)
        .body(
            "crank",
            RigidBody::new(0.343, 0.000216)
                .at(crank / 2.0, 0.0, 0.0)
                .moving(0.0, omega * crank / 2.0, omega),
        )
        .body(
            "rod",
            RigidBody::new(1.072, 0.034)
                .at(crank + rod / 2.0, 0.0, 0.0)
                .moving(0.0, omega * crank / 2.0, -omega * crank / rod),
        )
        .body(
            "slider",
            RigidBody::new(0.347, 0.000115).at(crank + rod, 0.0, 0.0),
        )
        .revolute("O", ("ground", [0.0, 0.0]), ("crank", [-crank / 2.0, 0.0]))
        .revolute(
            "A",
            ("crank", [crank / 2.0, 0.0]),
            ("rod", [-rod / 2.0, 0.0]),
        )
        .translational(
            "guide",
            ("ground", [0.0, 0.0]),
            ("slider", [0.0, 0.0]),
            [1.0, 0.0],
        )
        .drive_angle("motor", "crank", TimeFn::linear(0.0, omega))
        .revolute_clearance(
            "B",
            ("slider", [0.0, 0.0]),
            ("rod", [rod / 2.0, 0.0]),
            RevoluteClearanceSpec {
                bearing_radius: jb.r_bearing,
                journal_radius: jb.r_journal,
                normal: normal.into(),
                friction: FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap().into(),
            },
        );
    let mut m = b.build().unwrap();
    let opts = SimOptions::span(0.0, 0.03, 300)
        .tolerances(1e-8, 1e-11)
        .solver(SolverKind::Dopri5);
    let r = m.simulate(&opts).unwrap();
    let kmax = max_abs(col(&r, "energy.kinetic"));
    let (d, w) = (col(&r, "energy.dissipated"), col(&r, "energy.work_in"));
    let b = col(&r, "energy.balance");
    let drift = max_abs(b.iter().map(|x| x - b[0]));
    eprintln!(
        "slider–crank: max E_kin {kmax:.4} J, work in {:.4e} J (max |W_in| {:.4e} J), \
         dissipated {:.4e} J, balance drift {drift:.3e} J = {:.2e} of max E_kin, {} onsets, {} \
         steps",
        w.last().unwrap(),
        max_abs(w.iter().copied()),
        d.last().unwrap(),
        drift / kmax,
        r.onsets,
        r.stats.accepted
    );
    assert!(
        *d.last().unwrap() > 0.0,
        "contact damping and friction dissipate"
    );
    assert!(r.onsets > 0, "the clearance joint sees impacts");
    assert!(drift <= 100.0 * 1e-8 * kmax, "balance drift {drift:e} J");
}
