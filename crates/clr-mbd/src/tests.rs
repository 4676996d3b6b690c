//! Unit tests: constraint derivatives against finite differences, builder validation, a
//! compound pendulum against its closed-form quarter period, and redundancy detection.

use approx::assert_relative_eq;

use crate::desc::{BeamMaterial, MassKindDesc, SectionDesc, SupportDesc, SupportKind};
use crate::{BeamMesh, MbdError, ModelBuilder, Motion, RigidBody, SimOptions, SolverKind, TimeFn};

/// clr-beam's `Material::steel()` as data (E = 207 GPa, ρ = 7800 kg/m³, ν = 0.3).
fn steel() -> BeamMaterial {
    let m = clr_beam::Material::steel();
    BeamMaterial {
        youngs_modulus: m.youngs_modulus,
        density: m.density,
        poisson_ratio: m.poisson_ratio,
    }
}

/// A straight beam from the origin to (`length`, 0) m of `elements` elements of `material`, with
/// a `width` × `depth` (m) rectangular section, clamped at node 0; no damping, consistent mass.
fn cantilever(
    length: f64,
    elements: usize,
    material: BeamMaterial,
    width: f64,
    depth: f64,
) -> BeamMesh {
    BeamMesh {
        start: [0.0, 0.0],
        end: [length, 0.0],
        elements,
        material,
        section: SectionDesc::Rectangular { width, depth },
        supports: vec![SupportDesc {
            node: 0,
            kind: SupportKind::Clamped,
        }],
        rayleigh: [0.0, 0.0],
        mass: MassKindDesc::Consistent,
    }
}

/// A model exercising every primitive constraint (coincide, angle, project with and without a
/// motion) on bodies away from the origin.
fn all_kinds() -> crate::Model {
    let mut b = ModelBuilder::new();
    b.body("a", RigidBody::new(1.0, 0.1).at(0.3, 0.2, 0.4))
        .body("b", RigidBody::new(2.0, 0.2).at(0.9, -0.1, -0.7))
        .body("c", RigidBody::new(1.5, 0.3).at(-0.4, 0.5, 1.1))
        .revolute("r", ("a", [0.1, 0.05]), ("b", [-0.2, 0.1]))
        .translational("p", ("b", [0.05, -0.02]), ("c", [0.1, 0.2]), [0.6, 0.8])
        .drive_relative_angle("d", "a", "c", Motion::harmonic(0.2, 0.3, 2.0, 0.1))
        .drive_displacement(
            "s",
            ("ground", [0.1, 0.0]),
            ("a", [0.0, 0.1]),
            [1.0, 0.2],
            Motion::harmonic(0.1, 0.05, 3.0, 0.4),
        );
    b.build().unwrap()
}

/// Φ_q against central differences of Φ, and γ against the second time derivative of Φ along
/// q(t) = q0 + q̇ t + ½ q̈ t² (Φ̈ = Φ_q q̈ − γ), for arbitrary (inconsistent) states.
#[test]
fn constraint_derivatives_match_finite_differences() {
    let mut model = all_kinds();
    let (n, m) = (model.n, model.m);
    let q0: Vec<f64> = (0..n).map(|k| 0.3 * (k as f64 * 1.7).sin() + 0.1).collect();
    let qd: Vec<f64> = (0..n).map(|k| 0.8 * (k as f64 * 0.9).cos()).collect();
    let qdd: Vec<f64> = (0..n).map(|k| 0.5 * (k as f64 * 2.3).sin()).collect();
    let t0 = 0.37;
    let phi_at = |model: &mut crate::Model, t: f64, q: &[f64]| -> Vec<f64> {
        model.eval_constraints(t, q, &vec![0.0; n]);
        model.phi.clone()
    };
    model.eval_constraints(t0, &q0, &qd);
    let phiq = model.phiq.clone();
    let phid = model.phid.clone();
    let gamma = model.gamma.clone();
    let h = 1e-6;
    for c in 0..n {
        let mut qp = q0.clone();
        let mut qm = q0.clone();
        qp[c] += h;
        qm[c] -= h;
        let (fp, fm) = (phi_at(&mut model, t0, &qp), phi_at(&mut model, t0, &qm));
        for r in 0..m {
            assert_relative_eq!(phiq[r * n + c], (fp[r] - fm[r]) / (2.0 * h), epsilon = 1e-8);
        }
    }
    let path = |t: f64| -> Vec<f64> {
        let s = t - t0;
        (0..n)
            .map(|k| q0[k] + qd[k] * s + 0.5 * qdd[k] * s * s)
            .collect()
    };
    let h = 1e-4;
    let p0 = phi_at(&mut model, t0, &path(t0));
    let pp = phi_at(&mut model, t0 + h, &path(t0 + h));
    let pm = phi_at(&mut model, t0 - h, &path(t0 - h));
    for r in 0..m {
        let d1 = (pp[r] - pm[r]) / (2.0 * h);
        assert_relative_eq!(phid[r], d1, epsilon = 1e-7);
        let d2 = (pp[r] - 2.0 * p0[r] + pm[r]) / (h * h);
        let pq: f64 = (0..n).map(|c| phiq[r * n + c] * qdd[c]).sum();
        assert_relative_eq!(d2, pq - gamma[r], epsilon = 1e-5);
    }
}

/// Compound pendulum (rod of length L pinned at one end) released horizontally: it reaches the
/// bottom after a quarter period T/4 = K(sin(π/4))·√(I_O/(m g d)) (Landau & Lifshitz,
/// *Mechanics*, §11, with the complete elliptic integral K(1/√2) = 1.854074677301372).
#[test]
fn compound_pendulum_quarter_period() {
    let (m, l, g): (f64, f64, f64) = (2.0, 0.8, 9.81);
    let i_c = m * l * l / 12.0;
    let i_o = i_c + m * (l / 2.0).powi(2);
    let quarter = 1.854_074_677_301_372 * (i_o / (m * g * l / 2.0)).sqrt();
    for solver in [SolverKind::Ndf, SolverKind::Dopri5] {
        let mut b = ModelBuilder::new();
        b.gravity(0.0, -g)
            .body("rod", RigidBody::new(m, i_c).at(l / 2.0, 0.0, 0.0))
            .revolute("pin", ("ground", [0.0, 0.0]), ("rod", [-l / 2.0, 0.0]));
        let mut model = b.build().unwrap();
        let opts = SimOptions {
            t_end: quarter,
            times: vec![0.0, quarter],
            ..Default::default()
        }
        .solver(solver)
        .tolerances(1e-10, 1e-12);
        let res = model.simulate(&opts).unwrap();
        let th = res.column("rod.theta").unwrap();
        assert_relative_eq!(th[1], -std::f64::consts::FRAC_PI_2, epsilon = 1e-6);
        // pin reaction at the bottom: m g + m ω² d with ω² = 2 m g d / I_O (energy)
        let fy = res.column("pin.Fy").unwrap();
        let d = l / 2.0;
        let w2 = 2.0 * m * g * d / i_o;
        assert_relative_eq!(fy[1], m * g + m * w2 * d, max_relative = 1e-6);
    }
}

#[test]
fn builder_reports_typed_errors() {
    let base = || {
        let mut b = ModelBuilder::new();
        b.body("a", RigidBody::new(1.0, 0.1));
        b
    };
    let mut b = base();
    b.revolute("j", ("a", [0.0, 0.0]), ("nope", [0.0, 0.0]));
    assert!(
        matches!(b.build(), Err(MbdError::UnknownBody { item, body, .. }) if item == "j.b.body" && body == "nope")
    );
    let mut b = base();
    b.body("a", RigidBody::new(1.0, 0.1));
    assert!(matches!(b.build(), Err(MbdError::DuplicateName { name, .. }) if name == "a"));
    let mut b = base();
    b.body("z", RigidBody::new(0.0, 0.1));
    assert!(matches!(b.build(), Err(MbdError::InvalidInertia { body, .. }) if body == "z"));
    let mut b = base();
    b.body("w", RigidBody::new(1.0, -1.0));
    assert!(matches!(b.build(), Err(MbdError::InvalidInertia { body, .. }) if body == "w"));
    let mut b = base();
    b.revolute("self", ("a", [0.0, 0.0]), ("a", [1.0, 0.0]));
    assert!(matches!(b.build(), Err(MbdError::SameBody { item, .. }) if item == "self"));
    let mut b = base();
    b.drive_angle("motor", "ghost", Motion::linear(0.0, 1.0));
    assert!(matches!(b.build(), Err(MbdError::UnknownBody { item, .. }) if item == "motor.body"));
    let mut b = base();
    b.revolute("j", "p", ("a", [0.0, 0.0]));
    assert!(
        matches!(b.build(), Err(MbdError::UnknownPoint { item, point, .. }) if point == "p" && item == "j.a")
    );
    let mut b = base();
    b.translational("t", ("ground", [0.0, 0.0]), ("a", [0.0, 0.0]), [0.0, 0.0]);
    assert!(matches!(b.build(), Err(MbdError::InvalidParameter { item, .. }) if item == "t"));
    let mut b = base();
    b.point("ground", "a", [0.0, 0.0]);
    assert!(matches!(b.build(), Err(MbdError::DuplicateName { .. })));
}

/// A body pinned twice at the same point: the second joint's equations depend on the first.
#[test]
fn redundant_constraints_are_reported_with_their_equations() {
    let mut b = ModelBuilder::new();
    b.body("a", RigidBody::new(1.0, 0.1).at(0.5, 0.0, 0.0))
        .revolute("pin1", ("ground", [0.0, 0.0]), ("a", [-0.5, 0.0]))
        .revolute("pin2", ("ground", [0.0, 0.0]), ("a", [-0.5, 0.0]));
    let mut model = b.build().unwrap();
    match model.initial_state(0.0) {
        Err(MbdError::RedundantConstraints {
            rank,
            rows,
            involved,
        }) => {
            assert_eq!((rank, rows), (2, 4));
            assert!(
                involved.contains("pin2 (x)") && involved.contains("pin1 (x)"),
                "{involved}"
            );
        }
        other => panic!("expected a redundancy error, got {other:?}"),
    }
}

/// Assembly: a rod pinned at the origin given a wrong initial position is moved onto the pin,
/// and its velocity made consistent (the pin point at rest).
#[test]
fn initial_conditions_are_made_consistent() {
    let mut b = ModelBuilder::new();
    b.body(
        "a",
        RigidBody::new(1.0, 0.1)
            .at(0.55, 0.07, 0.1)
            .moving(0.3, 0.2, 1.0),
    )
    .revolute("pin", ("ground", [0.0, 0.0]), ("a", [-0.5, 0.0]));
    let mut model = b.build().unwrap();
    let y = model.initial_state(0.0).unwrap();
    let (pv, vv) = model.violation(0.0, &y);
    assert!(pv < 1e-12 && vv < 1e-12, "{pv} {vv}");
    let p = model.point_position(0, [-0.5, 0.0], &y[..3]);
    assert!(p[0].abs() < 1e-12 && p[1].abs() < 1e-12);
}

/// Ideal slider–crank (crank r, rod l) under a prescribed crank speed: the slider position at
/// interpolated output times against x = r cos θ + √(l² − r² sin² θ), and the CSV writer keeps
/// every column.
#[test]
fn slider_crank_outputs_match_closed_form() {
    let (r, l, omega) = (0.05, 0.3, 100.0);
    let mut b = ModelBuilder::new();
    b.body("crank", RigidBody::new(0.3, 1e-4).at(r / 2.0, 0.0, 0.0))
        .body("rod", RigidBody::new(1.0, 0.03).at(r + l / 2.0, 0.0, 0.0))
        .body("slider", RigidBody::new(0.3, 1e-4).at(r + l, 0.0, 0.0))
        .revolute("O", ("ground", [0.0, 0.0]), ("crank", [-r / 2.0, 0.0]))
        .revolute("A", ("crank", [r / 2.0, 0.0]), ("rod", [-l / 2.0, 0.0]))
        .revolute("B", ("rod", [l / 2.0, 0.0]), ("slider", [0.0, 0.0]))
        .translational(
            "guide",
            ("ground", [0.0, 0.0]),
            ("slider", [0.0, 0.0]),
            [1.0, 0.0],
        )
        .drive_angle("motor", "crank", Motion::linear(0.0, omega));
    let mut model = b.build().unwrap();
    let res = model
        .simulate(&SimOptions::span(0.0, 0.07, 37).tolerances(1e-10, 1e-12))
        .unwrap();
    let (t, x) = (res.column("t").unwrap(), res.column("slider.x").unwrap());
    assert_eq!(t.len(), 38);
    for (ti, xi) in t.iter().zip(x.iter()) {
        let s = r * (omega * ti).sin();
        let exact = r * (omega * ti).cos() + (l * l - s * s).sqrt();
        assert!((xi - exact).abs() < 1e-8, "t = {ti}: {xi} vs {exact}");
    }
    let path = std::env::temp_dir().join(format!("clr_mbd_test_{}.csv", std::process::id()));
    res.write_csv(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let _ = std::fs::remove_file(&path);
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap().split(',').count(), res.columns.len());
    assert_eq!(lines.count(), 38);
}

/// A free 1 kg journal at the centre of a ground-fixed bearing of `jb`, moving at 0.5 m/s along
/// x, held by the revolute clearance joint `gap`.
fn add_thrown_journal(
    b: &mut ModelBuilder,
    jb: &clr_contact::JournalBearing,
    normal: clr_contact::NormalLaw,
    friction: clr_contact::FrictionLaw,
) {
    b.body("journal", RigidBody::new(1.0, 1e-4).moving(0.5, 0.0, 0.0))
        .revolute_clearance(
            "gap",
            ("ground", [0.0, 0.0]),
            ("journal", [0.0, 0.0]),
            crate::RevoluteClearanceSpec {
                bearing_radius: jb.r_bearing,
                journal_radius: jb.r_journal,
                normal: normal.into(),
                friction: friction.into(),
            },
        );
}

/// A free 1 kg journal moving radially at 0.5 m/s inside a fixed bearing (the flap paper's
/// journal–bearing test: steel, R_i = 10 mm, R_j = 9.9 mm, L = 15 mm) rebounds with the
/// restitution the law produces in a free impact, which for F_e(δ)(1 + χδ̇/δ̇⁻) depends on χ only
/// (contact-laws.md §1.3; L-N with c_e = 0.5 gives 0.7252, quoted in paper-systems.md §1.1).
/// With and without event-located onsets.
#[test]
fn clearance_joint_free_impact_restitution() {
    use clr_contact::{FrictionLaw, JournalBearing, NormalLaw};
    let jb = JournalBearing::flap_paper_test();
    let law = NormalLaw::preset("LN", &jb, 0.5).unwrap();
    let expected = law.effective_restitution();
    assert!((expected - 0.7252).abs() < 5e-4);
    for events in [true, false] {
        let mut b = ModelBuilder::new();
        add_thrown_journal(&mut b, &jb, law, FrictionLaw::coulomb(0.0, 1.0).unwrap());
        let mut model = b.build().unwrap();
        let mut opts = SimOptions::span(0.0, 4e-4, 4).tolerances(1e-9, 1e-12);
        opts.contact_events = events;
        let res = model.simulate(&opts).unwrap();
        let vx = res.column("journal.vx").unwrap();
        let e = -vx[4] / 0.5;
        assert!(
            (e - expected).abs() < 2e-3,
            "events {events}: e = {e}, expected {expected}"
        );
        assert_eq!(res.onsets, usize::from(events));
        // contact closed again at the end; the integrated dissipation equals the kinetic
        // energy lost, ½ m v² (1 − e²) with the closed-form e
        let pen = res.column("gap.penetration").unwrap();
        assert!(pen[4] < 0.0);
        let ed = res.column("energy.dissipated").unwrap();
        let lost = 0.5 * 0.25 * (1.0 - expected * expected);
        assert!((ed[4] - lost).abs() < 5e-3 * lost, "{} vs {lost}", ed[4]);
    }
}

/// A flat slider block moving across a straight guide (no gravity) hits the lower surface with
/// both lower corners at once and rebounds with the law's free-impact restitution, which depends
/// on χ only (contact-laws.md §1.3), so two equal corner contacts give the same value as one;
/// frictionless, the sliding velocity along the guide is unchanged and the block does not turn.
#[test]
fn translational_clearance_flat_impact_restitution() {
    use clr_contact::{DampingFactor, ElasticLaw, FrictionLaw, NormalLaw};
    let law = NormalLaw::new(
        ElasticLaw::hertz(1e9).unwrap(),
        DampingFactor::LankaraniNikravesh,
        0.8,
    )
    .unwrap();
    let expected = law.effective_restitution();
    for events in [true, false] {
        let mut b = ModelBuilder::new();
        b.body("block", RigidBody::new(1.0, 1e-3).moving(0.2, -0.5, 0.0))
            .translational_clearance(
                "guide",
                ("ground", [0.0, 0.0]),
                ("block", [0.0, 0.0]),
                crate::TranslationalClearanceSpec {
                    guide_width: 0.021,
                    guide_angle: 0.0,
                    slider_length: 0.05,
                    slider_height: 0.02,
                    slider_angle: 0.0,
                    normal: law.into(),
                    friction: FrictionLaw::coulomb(0.0, 1.0).unwrap().into(),
                },
            );
        let mut model = b.build().unwrap();
        let mut opts = SimOptions::span(0.0, 2e-3, 2).tolerances(1e-9, 1e-12);
        opts.contact_events = events;
        let res = model.simulate(&opts).unwrap();
        let (vx, vy, om) = (
            res.column("block.vx").unwrap(),
            res.column("block.vy").unwrap(),
            res.column("block.omega").unwrap(),
        );
        let e = vy[2] / 0.5;
        assert!(
            (e - expected).abs() < 2e-3,
            "events {events}: e = {e}, expected {expected}"
        );
        assert!(
            (vx[2] - 0.2).abs() < 1e-9 && om[2].abs() < 1e-6,
            "{} {}",
            vx[2],
            om[2]
        );
        if events {
            assert!(res.onsets >= 1);
        }
        let ed = res.column("energy.dissipated").unwrap();
        let lost = 0.5 * 0.25 * (1.0 - expected * expected);
        assert!((ed[2] - lost).abs() < 5e-3 * lost, "{} vs {lost}", ed[2]);
    }
}

/// A steel cantilever (clr-beam, 6 elements) under a suddenly applied tip load, integrated as a
/// ground-fixed flexible beam, against undamped modal superposition with every mode of the same
/// discretization: u(t) = Σ φ_k φ_kᵀF (1 − cos ω_k t)/ω_k² (Clough & Penzien, *Dynamics of
/// Structures*, §12-3). Also: without damping, kinetic + elastic energy equals the work of the
/// constant load, F·u(t).
#[test]
fn flexible_beam_step_load_matches_modal_superposition() {
    let sec = clr_beam::Section::rectangular(0.02, 0.01).unwrap();
    let mesh = cantilever(1.0, 6, steel(), 0.02, 0.01);
    let beam = mesh.build("beam").unwrap();
    let p = -100.0;
    let tip = 3 * 6 + 1;
    let modes = beam.modes(18).unwrap();
    let exact = |t: f64| -> f64 {
        (0..modes.omega.len())
            .map(|k| {
                let phi_tip = modes.shapes[(tip, k)];
                let w = modes.omega[k];
                phi_tip * phi_tip * p * (1.0 - (w * t).cos()) / (w * w)
            })
            .sum()
    };
    let u_static = p / (3.0 * 207e9 * sec.second_moment);
    let mut b = ModelBuilder::new();
    b.flexible_beam("beam", mesh).nodal_load(
        "P",
        "beam",
        6,
        [
            TimeFn::constant(0.0),
            TimeFn::constant(p),
            TimeFn::constant(0.0),
        ],
    );
    let mut model = b.build().unwrap();
    assert_eq!(model.n_coordinates(), 18);
    let res = model
        .simulate(&SimOptions::span(0.0, 0.02, 40).tolerances(1e-10, 1e-14))
        .unwrap();
    let (t, v) = (res.column("t").unwrap(), res.column("beam.n6.v").unwrap());
    for (ti, vi) in t.iter().zip(v.iter()) {
        assert!(
            (vi - exact(*ti)).abs() < 1e-6 * u_static.abs(),
            "t = {ti}: {vi} vs {}",
            exact(*ti)
        );
    }
    let e = res.column("energy.total").unwrap();
    for (ei, vi) in e.iter().zip(v.iter()) {
        assert!((ei - p * vi).abs() < 1e-6 * (p * u_static).abs());
    }
}

/// A ground-fixed steel cantilever (0.5 m, 20 × 10 mm, 10 elements) inclined at 30° and
/// released from rest under gravity (0, −9.81 m/s²) with Rayleigh α = 400 s⁻¹, β = 1e-5 s
/// (every mode decays at least as e^{−αt/2}: e^{−60} by 0.3 s; β damps the stiff axial modes)
/// settles on the static deflection under its
/// own weight w = ρAg: tip deflection normal to the axis q L⁴/(8EI) with q = −w cos 30°
/// (Timoshenko & Gere, *Mechanics of Materials*; Roark 8th ed. Table 8.1 case 2a) and axial
/// tip displacement p L²/(2EA) with p = −w sin 30° (a bar under a uniform axial load). The
/// consistent nodal loads make both exact at the nodes (Hermite cubics and linear axial
/// elements), so the tolerance 1e-9 relative covers the integration error only (NDF rtol 1e-8,
/// atol 1e-12 on a settled state: measured 3e-12 transverse, 8e-12 axial).
#[test]
fn beam_self_weight_settles_on_the_static_deflection() {
    let (l, ne, g) = (0.5, 10, 9.81);
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let mut mesh = cantilever(l, ne, steel(), 0.02, 0.01);
    mesh.end = [l * c, l * s];
    mesh.rayleigh = [400.0, 1e-5];
    let sec = clr_beam::Section::rectangular(0.02, 0.01).unwrap();
    let mat = clr_beam::Material::steel();
    let w = mat.density * sec.area * g;
    let (ei, ea) = (
        mat.youngs_modulus * sec.second_moment,
        mat.youngs_modulus * sec.area,
    );
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -g).flexible_beam("beam", mesh);
    let mut model = b.build().unwrap();
    let res = model
        .simulate(&SimOptions::span(0.0, 0.3, 30).tolerances(1e-8, 1e-12))
        .unwrap();
    let last = |name: &str| *res.column(name).unwrap().last().unwrap();
    let (ux, uy) = (
        last(&format!("beam.n{ne}.u")),
        last(&format!("beam.n{ne}.v")),
    );
    let transverse = -ux * s + uy * c;
    let axial = ux * c + uy * s;
    assert_relative_eq!(
        transverse,
        -w * c * l.powi(4) / (8.0 * ei),
        max_relative = 1e-9
    );
    assert_relative_eq!(axial, -w * s * l * l / (2.0 * ea), max_relative = 1e-9);
}

/// A free body under a constant applied force and torque (no gravity): x = x0 + F t²/(2m),
/// θ = τ t²/(2I) (Newton's second law in closed form).
#[test]
fn applied_force_and_torque_closed_form() {
    let (m, i, f, tau) = (2.0, 0.5, 3.0, 0.7);
    let mut b = ModelBuilder::new();
    b.body("a", RigidBody::new(m, i).at(1.0, 0.0, 0.0))
        .force(
            "F",
            ("a", [0.0, 0.0]),
            TimeFn::constant(f),
            TimeFn::constant(0.0),
        )
        .torque("T", "a", TimeFn::constant(tau));
    let mut model = b.build().unwrap();
    let res = model
        .simulate(&SimOptions::span(0.0, 2.0, 4).tolerances(1e-10, 1e-12))
        .unwrap();
    let (x, th) = (res.column("a.x").unwrap(), res.column("a.theta").unwrap());
    assert_relative_eq!(x[4], 1.0 + f * 4.0 / (2.0 * m), max_relative = 1e-9);
    assert_relative_eq!(th[4], tau * 4.0 / (2.0 * i), max_relative = 1e-9);
}

/// A carriage on a translational joint driven by a harmonic displacement actuator, with a
/// second body welded to it by a fixed joint: the welded body follows x(t) + offset, and the
/// actuator force equals (m_a + m_b)·ẍ(t) = −(m_a + m_b) A ω² sin ωt (closed form).
#[test]
fn displacement_driver_and_fixed_joint() {
    let (ma, mb, amp, w) = (1.5, 0.5, 0.02, 30.0);
    let mut b = ModelBuilder::new();
    b.body("cart", RigidBody::new(ma, 0.01))
        .body("load", RigidBody::new(mb, 0.002).at(0.1, 0.05, 0.0))
        .translational(
            "rail",
            ("ground", [0.0, 0.0]),
            ("cart", [0.0, 0.0]),
            [1.0, 0.0],
        )
        .drive_displacement(
            "act",
            ("ground", [0.0, 0.0]),
            ("cart", [0.0, 0.0]),
            [1.0, 0.0],
            Motion::harmonic(0.0, amp, w, 0.0),
        )
        .fixed("weld", ("cart", [0.1, 0.05]), ("load", [0.0, 0.0]));
    let mut model = b.build().unwrap();
    let res = model
        .simulate(&SimOptions::span(0.0, 0.5, 10).tolerances(1e-11, 1e-13))
        .unwrap();
    let t = res.column("t").unwrap();
    let (xl, yl) = (res.column("load.x").unwrap(), res.column("load.y").unwrap());
    let fx = res.column("act.Fx").unwrap();
    for k in 0..t.len() {
        let x = amp * (w * t[k]).sin();
        assert!((xl[k] - (x + 0.1)).abs() < 1e-9 && (yl[k] - 0.05).abs() < 1e-9);
        // actuator reaction on the cart along +x: the force that accelerates both bodies
        let expected = -(ma + mb) * amp * w * w * (w * t[k]).sin();
        assert!(
            (fx[k] - expected).abs() < 1e-6 * (ma + mb) * amp * w * w,
            "{} {expected}",
            fx[k]
        );
    }
}

/// Coordinate projection: with Baumgarte terms off, a double pendulum drifts off its
/// constraints; projection after accepted steps keeps ‖Φ‖∞ below its threshold at every step.
#[test]
fn projection_keeps_constraints() {
    let build = || {
        let mut b = ModelBuilder::new();
        b.gravity(0.0, -9.81)
            .body("u", RigidBody::new(1.0, 0.08).at(0.5, 0.0, 0.0))
            .body(
                "l",
                RigidBody::new(1.0, 0.08).at(1.0, -0.5, -std::f64::consts::FRAC_PI_2),
            )
            .revolute("s", ("ground", [0.0, 0.0]), ("u", [-0.5, 0.0]))
            .revolute("e", ("u", [0.5, 0.0]), ("l", [-0.5, 0.0]));
        let mut m = b.build().unwrap();
        m.set_baumgarte(0.0, 0.0).unwrap();
        m
    };
    // rows at the accepted steps (where projection acts), not interpolated output times
    let mut opts = SimOptions {
        t_end: 3.0,
        every_step: true,
        ..Default::default()
    }
    .tolerances(1e-5, 1e-7);
    let free = build().simulate(&opts).unwrap();
    opts.projection = Some(1e-9);
    let projected = build().simulate(&opts).unwrap();
    let worst = |r: &crate::Results| {
        r.column("violation.position")
            .unwrap()
            .iter()
            .fold(0.0f64, |a, &v| a.max(v))
    };
    assert!(worst(&free) > 1e-8, "no drift to correct: {}", worst(&free));
    assert!(projected.projections > 0);
    assert!(worst(&projected) <= 1e-9, "{}", worst(&projected));
}

/// Gravity, a 0.5 m steel beam (two elements) clamped at the origin, and a 0.5 kg, 0.2 m bob
/// pinned to its tip.
fn add_pendulum_on_beam(b: &mut ModelBuilder) {
    let beam = cantilever(0.5, 2, steel(), 0.03, 0.02);
    b.gravity(0.0, -9.81)
        .flexible_beam("beam", beam)
        .beam_node_point("tip", "beam", 2)
        .body(
            "bob",
            RigidBody::new(0.5, 0.5 * 0.04 / 12.0).at(0.6, 0.0, 0.0),
        )
        .revolute("pin", "tip", ("bob", [-0.1, 0.0]));
}

/// A rigid pendulum pinned to the tip node of an undamped steel cantilever (joint on a beam
/// node): with gravity on the pendulum and the beam, the total energy (pendulum kinetic and
/// potential, beam kinetic, potential and elastic) is conserved, and the tip stays on the
/// pendulum's pin.
#[test]
fn pendulum_on_flexible_beam_conserves_energy() {
    let mut b = ModelBuilder::new();
    add_pendulum_on_beam(&mut b);
    let mut model = b.build().unwrap();
    let res = model
        .simulate(&SimOptions::span(0.0, 0.15, 30).tolerances(1e-9, 1e-12))
        .unwrap();
    let e = res.column("energy.total").unwrap();
    let k = res.column("energy.kinetic").unwrap();
    let kmax = k.iter().fold(0.0f64, |a, &v| a.max(v));
    let drift = e.iter().map(|v| (v - e[0]).abs()).fold(0.0f64, f64::max);
    assert!(
        kmax > 0.1 && drift < 1e-6 * kmax,
        "drift {drift}, max E_kin {kmax}"
    );
    // the beam tip moved (the pendulum loads it) and the pin holds
    let v4 = res.column("beam.n2.v").unwrap();
    assert!(v4.iter().any(|v| v.abs() > 1e-6));
    let pv = res.column("violation.position").unwrap();
    assert!(pv.iter().all(|v| *v < 1e-8));
}

/// `Anchor::BeamNode` and a named `beam_node_point` attach to the same node frame: identical
/// results, bit for bit.
#[test]
fn beam_node_anchor_forms_agree() {
    let run = |named: bool| {
        let beam = cantilever(0.5, 2, steel(), 0.03, 0.02);
        let mut b = ModelBuilder::new();
        b.gravity(0.0, -9.81)
            .flexible_beam("beam", beam)
            .beam_node_point("tip", "beam", 2)
            .body("bob", RigidBody::new(0.5, 0.002).at(0.6, 0.0, 0.0));
        if named {
            b.revolute("pin", "tip", ("bob", [-0.1, 0.0]));
        } else {
            b.revolute("pin", ("beam", 2usize), ("bob", [-0.1, 0.0]));
        }
        let mut model = b.build().unwrap();
        model
            .simulate(&SimOptions::span(0.0, 0.01, 2).tolerances(1e-8, 1e-11))
            .unwrap()
            .data
    };
    assert_eq!(run(true), run(false));
}

/// A slider dropped at 0.2 m/s on the upper face of an undamped steel cantilever (slider on a
/// flexible guide, elastic contact with no damping or friction, no reverse check): the contact
/// forces are conservative, so slider + beam + contact energy is constant; the beam deflects
/// and the slider rebounds.
#[test]
fn slider_on_flexible_guide_conserves_energy() {
    use clr_beam::Face;
    use clr_contact::{DampingFactor, ElasticLaw, FrictionLaw, NormalLaw};
    let depth = 0.01;
    let beam = cantilever(0.5, 4, steel(), 0.02, depth);
    let law = NormalLaw::new(ElasticLaw::hertz(1e9).unwrap(), DampingFactor::None, 1.0).unwrap();
    let (sl, sh) = (0.04, 0.02);
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -9.81)
        .flexible_beam("beam", beam)
        .body(
            "slider",
            RigidBody::new(0.2, 0.2 * (sl * sl + sh * sh) / 12.0)
                .at(0.35, depth / 2.0 + sh / 2.0 + 1e-4, 0.0)
                .moving(0.0, -0.2, 0.0),
        )
        .slider_on_beam(
            "contact",
            "beam",
            ("slider", [0.0, 0.0]),
            crate::FlexibleGuideSpec {
                face: Face::Upper,
                slider_length: sl,
                slider_height: sh,
                slider_angle: 0.0,
                face_points: 3,
                guide_samples: 0,
                normal: law.into(),
                area_normal: None,
                friction: FrictionLaw::coulomb(0.0, 1.0).unwrap().into(),
            },
        );
    let mut model = b.build().unwrap();
    let res = model
        .simulate(
            &SimOptions::span(0.0, 0.01, 50)
                .tolerances(1e-9, 1e-12)
                .solver(SolverKind::Dopri5),
        )
        .unwrap();
    let e = res.column("energy.total").unwrap();
    let k = res.column("energy.kinetic").unwrap();
    let kmax = k.iter().fold(0.0f64, |a, &v| a.max(v));
    let drift = e.iter().map(|v| (v - e[0]).abs()).fold(0.0f64, f64::max);
    let fmax = res
        .column("contact.normal_force")
        .unwrap()
        .iter()
        .fold(0.0f64, |a, &v| a.max(v));
    let tip = res.column("beam.n4.v").unwrap();
    assert!(fmax > 1.0, "no contact: {fmax}");
    assert!(tip.iter().any(|v| v.abs() > 1e-6), "beam did not deflect");
    assert!(drift < 1e-6 * kmax, "drift {drift}, max E_kin {kmax}");
}

/// The area law of a flexible guide (`FlexibleGuideSpec::area_normal`, applied at every point
/// with its wetted length) with c_e = 1 (χ = 0): a slider dropped flat on a cantilever reaches
/// area contact (all 5 bottom-face points active). The lumped wetted lengths are continuous but
/// not the exact gradient of one potential, so energy is conserved only approximately: measured
/// 1.6e-6 J of 4.0e-3 J (0.041 %). With the earlier switch line → area law at the class change
/// the force jumped and the drift was 8.9e-6 J (0.22 %): the bound 0.1 % of the largest kinetic
/// energy separates the two (a regression check on the continuity, not a closed form).
#[test]
fn slider_on_flexible_guide_area_law_conserves_energy() {
    use clr_beam::Face;
    use clr_contact::{FrictionLaw, GuideFace, NormalLaw};
    let depth = 0.03;
    let beam = cantilever(0.5, 4, steel(), 0.02, depth);
    let steel = clr_contact::Material::new(207e9, 0.3).unwrap();
    let face = GuideFace {
        slider: steel,
        guide: steel,
        edge_radius: 1e-3,
        width: 0.02,
        layer_depth: 0.05,
    };
    let line = NormalLaw::flores_line(&face, 1.0).unwrap();
    let area = NormalLaw::area(&face, 1.0, 0.0).unwrap();
    let (sl, sh) = (0.04, 0.02);
    let mut b = ModelBuilder::new();
    b.flexible_beam("beam", beam)
        .body(
            "slider",
            RigidBody::new(0.2, 0.2 * (sl * sl + sh * sh) / 12.0)
                .at(0.25, depth / 2.0 + sh / 2.0 + 1e-5, 0.0)
                .moving(0.0, -0.2, 0.0),
        )
        .slider_on_beam(
            "contact",
            "beam",
            ("slider", [0.0, 0.0]),
            crate::FlexibleGuideSpec {
                face: Face::Upper,
                slider_length: sl,
                slider_height: sh,
                slider_angle: 0.0,
                face_points: 3,
                guide_samples: 0,
                normal: line.into(),
                area_normal: Some(area.into()),
                friction: FrictionLaw::coulomb(0.0, 1.0).unwrap().into(),
            },
        );
    let mut model = b.build().unwrap();
    let mut opts = SimOptions::span(0.0, 2e-3, 50)
        .tolerances(1e-9, 1e-12)
        .solver(SolverKind::Dopri5);
    opts.every_step = true;
    let res = model.simulate(&opts).unwrap();
    let e = res.column("energy.total").unwrap();
    let k = res.column("energy.kinetic").unwrap();
    let kmax = k.iter().fold(0.0f64, |a, &v| a.max(v));
    let drift = e.iter().map(|v| (v - e[0]).abs()).fold(0.0f64, f64::max);
    let active = res
        .column("contact.contact")
        .unwrap()
        .iter()
        .fold(0.0f64, |a, &v| a.max(v));
    assert!(active >= 5.0, "no area contact: {active} points at most");
    assert!(drift < 1e-3 * kmax, "drift {drift}, max E_kin {kmax}");
}

/// Shared pieces of the floating-guide tests: a steel cantilever (0.5 m, 4 elements, section
/// 0.02 × 0.01 m, clamped at node 0), a flat slider pad and the Flores line law of its edge.
mod floating_guide {
    use super::cantilever;
    use crate::desc::BeamMaterial;
    use crate::{
        BeamMesh, FlexibleGuideSpec, ModelBuilder, Reduction, RigidBody, SimOptions, SolverKind,
        TimeFn,
    };
    use clr_beam::Face;
    use clr_contact::{FrictionLaw, GuideFace, NormalLaw};

    const DEPTH: f64 = 0.01;
    const PAD: [f64; 2] = [0.04, 0.01];

    /// The cantilever with Young's modulus `e` (Pa), steel density.
    fn beam(e: f64) -> BeamMesh {
        let mat = BeamMaterial {
            youngs_modulus: e,
            density: 7850.0,
            poisson_ratio: 0.3,
        };
        cantilever(0.5, 4, mat, 0.02, DEPTH)
    }

    /// Hertz law K δ^1.5 (K in N/m^1.5) with a damping factor and restitution c_e.
    fn hertz(k: f64, damping: clr_contact::DampingFactor, c_e: f64) -> NormalLaw {
        NormalLaw::new(clr_contact::ElasticLaw::hertz(k).unwrap(), damping, c_e).unwrap()
    }

    fn law(restitution: f64) -> NormalLaw {
        let steel = clr_contact::Material::new(207e9, 0.3).unwrap();
        let face = GuideFace {
            slider: steel,
            guide: steel,
            edge_radius: 1e-3,
            width: 0.02,
            layer_depth: 0.01,
        };
        NormalLaw::flores_line(&face, restitution).unwrap()
    }

    fn spec(face: Face, normal: NormalLaw, friction: FrictionLaw) -> FlexibleGuideSpec {
        FlexibleGuideSpec {
            face,
            slider_length: PAD[0],
            slider_height: PAD[1],
            slider_angle: 0.0,
            face_points: 3,
            guide_samples: 0,
            normal: normal.into(),
            area_normal: None,
            friction: friction.into(),
        }
    }

    /// DOPRI5 from 0 to `t_end` (s) with `n` outputs, tolerances (rtol, atol), no onset events.
    fn dopri(t_end: f64, n: usize, rtol: f64, atol: f64) -> SimOptions {
        let mut opts = SimOptions::span(0.0, t_end, n)
            .tolerances(rtol, atol)
            .solver(SolverKind::Dopri5);
        opts.contact_events = false;
        opts
    }

    /// A 0.2 kg slider pad `contact` on the guide's upper face, 0.1 mm above it at x (m), tilted
    /// by `angle` (rad), moving at `v` (m/s).
    fn add_slider(
        b: &mut ModelBuilder,
        x: f64,
        angle: f64,
        v: [f64; 2],
        normal: NormalLaw,
        friction: FrictionLaw,
    ) {
        let sy = DEPTH / 2.0 + PAD[1] / 2.0 + 1e-4;
        b.body(
            "slider",
            RigidBody::new(0.2, 0.2 * (PAD[0].powi(2) + PAD[1].powi(2)) / 12.0)
                .at(x, sy, angle)
                .moving(v[0], v[1], 0.0),
        )
        .slider_on_beam(
            "contact",
            "guide",
            ("slider", [0.0, 0.0]),
            spec(Face::Upper, normal, friction),
        );
    }

    /// Independent formulation: the same slider-on-guide problem (a 0.2 kg slider thrown at
    /// 0.5 m/s along and 0.2 m/s onto the upper face of the cantilever and pressed by 20 N, Flores
    /// damping c_e = 0.8, Coulomb friction μ = 0.1) once with the guide as a ground-fixed
    /// `flexible_beam` (nodal coordinates) and once as a `floating_beam` whose frame is clamped to
    /// the ground by a fixed joint, reduced on **all** 12 free modes. The modal truncation error
    /// is then zero (T is square and invertible, M_ff = Tᵀ M T with the same consistent mass,
    /// K_ff = Tᵀ K T), so the two are the same equations in other coordinates and differ only by
    /// the integration error (DOPRI5, rtol 1e-9, atol 1e-12) and the Baumgarte drift of the
    /// clamp. Over the first 2 ms (impact, rebound, second impacts; later the rattling amplifies
    /// any difference) slider y, tip deflection and contact force agree to 1e-4 of their largest
    /// values (measured 1.3e-7, 9.9e-6, 6.6e-5; the impact-force peaks are the most sensitive to
    /// step placement). A truncated reduction (4 modes) is not compared: the impact excites the
    /// dropped modes, so no simple closed-form bound (the static truncation error is 2e-4, the
    /// measured tip difference 0.47) applies.
    #[test]
    fn floating_guide_clamped_matches_ground_fixed_guide() {
        let run = |modes: Option<usize>| {
            // no gravity: clr-mbd's ground-fixed beams carry no weight (floating bodies do), so
            // the slider is pressed by an applied force instead
            let mut b = ModelBuilder::new();
            match modes {
                None => {
                    b.flexible_beam("guide", beam(207e9));
                }
                Some(r) => {
                    let bm = beam(207e9);
                    let red = Reduction::Modal { modes: r };
                    b.floating_beam("guide", bm, red, [0.0; 3], [0.0; 3]).fixed(
                        "clamp",
                        ("ground", [0.0, 0.0]),
                        ("guide", 0usize),
                    );
                }
            }
            add_slider(
                &mut b,
                0.25,
                0.0,
                [0.5, -0.2],
                law(0.8),
                FrictionLaw::coulomb(0.1, 1e-3).unwrap(),
            );
            b.force(
                "press",
                ("slider", [0.0, 0.0]),
                TimeFn::constant(0.0),
                TimeFn::constant(-20.0),
            );
            let mut model = b.build().unwrap();
            let res = model.simulate(&dopri(2e-3, 40, 1e-9, 1e-12)).unwrap();
            let y = res.column("slider.y").unwrap();
            let f = res.column("contact.normal_force").unwrap();
            let tip: Vec<f64> = match modes {
                None => res.column("guide.n4.v").unwrap(),
                Some(_) => (0..res.len())
                    .map(|k| {
                        let q = model.coordinates_from_row(res.row(k)).unwrap();
                        model.floating_node_position("guide", 4, &q).unwrap()[1]
                    })
                    .collect(),
            };
            (y, tip, f)
        };
        let (y0, tip0, f0) = run(None);
        let (y1, tip1, f1) = run(Some(12));
        let scale = |v: &[f64]| v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let diff = |a: &[f64], b: &[f64]| {
            a.iter()
                .zip(b)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        };
        let (ty, tt, tf) = (scale(&y0), scale(&tip0), scale(&f0));
        assert!(tf > 10.0, "contact force {tf} N");
        assert!(tt > 1e-6, "tip deflection {tt} m");
        let (dy, dt, df) = (
            diff(&y0, &y1) / ty,
            diff(&tip0, &tip1) / tt,
            diff(&f0, &f1) / tf,
        );
        eprintln!("all modes: rel. diffs y {dy:.2e}, tip {dt:.2e}, force {df:.2e}");
        assert!(
            dy < 1e-4 && dt < 1e-4 && df < 1e-4,
            "all modes: rel. diffs y {dy:.2e}, tip {dt:.2e}, force {df:.2e}"
        );
    }

    /// Rigid-body motion: a stiff floating guide (E = 2e12 Pa, 4 modes) spun about its clamped root at
    /// ω = 2 rad/s by an angle driver, carrying a slider fixed to its frame at x̄ = 0.3 m whose
    /// two pads are pressed into the two guide faces by the same interference δ₀ = 1e-4 m
    /// (Hertz K = 1e7 N/m^1.5 with Flores damping at c_e = 0.5, so any spurious normal velocity
    /// would add damping force; no friction, see the code). The pad forces on the guide cancel at every arc, so the guide
    /// stays straight and the relative state is the state at rest: each face carries exactly
    /// 5 points (2 corners + 3 face points) × K δ₀^1.5 (closed form of the Hertz term), at every
    /// output time while the guide turns by 0.04 rad. Tolerance 1e-4: the centrifugal axial
    /// vibration couples into bending through the Coriolis term 2θ̇ S̃ q̇_f, bounded by an
    /// elastic deflection of order 1e-9 m (1e-5 δ₀) for this stiffness and speed; a wrong frame
    /// velocity (θ̇ Ĩ A p̄ = 0.6 m/s along the face normal here) or rotation would be off by O(1).
    #[test]
    fn floating_guide_rotating_with_carried_slider_keeps_the_rest_contact_force() {
        let omega = 2.0;
        let delta0 = 1e-4;
        let bm = beam(2e12);
        let red = Reduction::Modal { modes: 4 };
        // a soft Hertz law (K = 1e7 N/m^1.5, 10 N per point) keeps the explicit step large
        let normal = hertz(1e7, clr_contact::DampingFactor::Flores, 0.5);
        // no friction: in a turning frame the pad point and the guide point, δ₀ apart, have the
        // relative tangential velocity ω δ₀, so regularized friction would load the faces
        let friction = FrictionLaw::coulomb(0.0, 1e-3).unwrap();
        let off = DEPTH / 2.0 + PAD[1] / 2.0 - delta0;
        let xs = 0.3;
        let mut b = ModelBuilder::new();
        b.floating_beam("guide", bm, red, [0.0; 3], [0.0, 0.0, omega])
            .revolute("pin", ("ground", [0.0, 0.0]), ("guide", 0usize))
            .drive_angle("spin", "guide", crate::Motion::linear(0.0, omega))
            .body(
                "slider",
                RigidBody::new(0.2, 0.2 * (PAD[0].powi(2) + 0.04f64.powi(2)) / 12.0)
                    .at(xs, 0.0, 0.0)
                    .moving(0.0, xs * omega, omega),
            )
            .fixed("carry", ("guide", [xs, 0.0]), ("slider", [0.0, 0.0]))
            .slider_on_beam(
                "upper",
                "guide",
                ("slider", [0.0, off]),
                spec(Face::Upper, normal, friction),
            )
            .slider_on_beam(
                "lower",
                "guide",
                ("slider", [0.0, -off]),
                spec(Face::Lower, normal, friction),
            );
        let mut model = b.build().unwrap();
        let res = model.simulate(&dopri(0.02, 4, 1e-8, 1e-12)).unwrap();
        let expected = 5.0 * normal.elastic_force(delta0);
        let th = res.column("guide.theta").unwrap();
        assert!((th[4] - 0.04).abs() < 1e-6, "guide angle {}", th[4]);
        for face in ["upper", "lower"] {
            let f = res.column(&format!("{face}.normal_force")).unwrap();
            let n = res.column(&format!("{face}.contact")).unwrap();
            for (k, (fk, nk)) in f.iter().zip(&n).enumerate() {
                assert_eq!(*nk, 5.0, "{face} active points at row {k}");
                assert!(
                    (fk - expected).abs() < 1e-4 * expected,
                    "{face} row {k}: {fk} N vs {expected} N"
                );
            }
        }
    }

    /// Virtual work of the floating-guide forces: a free floating guide (no joints, no gravity,
    /// no beam damping) hit by a slider at 0.3 m/s, obliquely and off-centre, with an undamped
    /// Hertz law and no friction. The contact forces derive from the penetration potential
    /// only if the generalized forces on (R, θ, q_f) are the exact virtual work of the face
    /// kinematics used for the gap, so T + U + contact energy is constant (closed form: the
    /// system is conservative) to the integration error: 1e-6 of the initial kinetic energy.
    /// The guide is set in rigid translation and rotation and deflects (checked).
    #[test]
    fn free_floating_guide_hit_by_slider_conserves_energy() {
        let bm = beam(207e9);
        let red = Reduction::Modal { modes: 4 };
        let normal = hertz(1e9, clr_contact::DampingFactor::None, 1.0);
        let mut b = ModelBuilder::new();
        b.floating_beam("guide", bm, red, [0.0; 3], [0.0; 3]);
        let friction = FrictionLaw::coulomb(0.0, 1.0).unwrap();
        add_slider(&mut b, 0.4, 0.002, [0.1, -0.3], normal, friction);
        let mut model = b.build().unwrap();
        let res = model.simulate(&dopri(4e-3, 80, 1e-10, 1e-13)).unwrap();
        let e = res.column("energy.total").unwrap();
        let fmax = res
            .column("contact.normal_force")
            .unwrap()
            .iter()
            .fold(0.0f64, |a, &v| a.max(v));
        let drift = e.iter().map(|v| (v - e[0]).abs()).fold(0.0f64, f64::max);
        let last = res.len() - 1;
        let w = res.column("guide.theta").unwrap()[last];
        let vy = res.column("guide.y").unwrap()[last];
        let q0 = res.column("guide.q0").unwrap();
        let qmax = q0.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
        eprintln!(
            "drift {drift:e} of {} J, fmax {fmax}, θ {w:e}, y {vy:e}, q0 {qmax:e}",
            e[0]
        );
        assert!(fmax > 1.0, "no contact: {fmax}");
        assert!(
            w.abs() > 1e-6 && vy.abs() > 1e-6 && qmax > 1e-6,
            "guide did not move/deflect"
        );
        assert!(drift < 1e-6 * e[0], "drift {drift} J of {} J", e[0]);
    }
}

/// A model with every kind of output column: a pendulum on a clamped flexible beam (beam nodal
/// columns, joint reactions) and a journal thrown across a revolute clearance (contact columns,
/// contact onsets located as events).
fn every_column_model() -> crate::Model {
    use clr_contact::{FrictionLaw, JournalBearing, NormalLaw};
    let jb = JournalBearing::flap_paper_test();
    let mut b = ModelBuilder::new();
    add_pendulum_on_beam(&mut b);
    add_thrown_journal(
        &mut b,
        &jb,
        NormalLaw::preset("LN", &jb, 0.5).unwrap(),
        FrictionLaw::coulomb(0.1, 1e-3).unwrap(),
    );
    b.build().unwrap()
}

/// A run stopped by its step budget returns, in `MbdError::Failed`, the rows an independent
/// complete run of the same model and settings records first, bit for bit (same columns,
/// including the beam, contact, energy and violation columns), with the statistics up to the
/// failure. Both solvers.
#[test]
fn failed_run_keeps_the_rows_of_the_complete_run() {
    for solver in [SolverKind::Ndf, SolverKind::Dopri5] {
        let mut opts = SimOptions::span(0.0, 1e-3, 20)
            .tolerances(1e-8, 1e-11)
            .solver(solver);
        opts.every_step = true;
        let full = every_column_model().simulate(&opts).unwrap();
        assert!(
            full.onsets >= 1,
            "{solver:?}: the journal must hit the bearing"
        );
        let budget = full.stats.accepted / 2;
        opts.max_steps = budget;
        let err = every_column_model().simulate(&opts).unwrap_err();
        assert!(err.to_string().contains("step budget"), "{err}");
        let part = err
            .partial()
            .expect("a solver failure carries partial results");
        assert_eq!(part.columns, full.columns);
        assert_eq!(part.stats.accepted, budget);
        assert!(part.len() > 1 && part.len() < full.len(), "{solver:?}");
        for r in 0..part.len() {
            assert_eq!(part.row(r), full.row(r), "{solver:?}: row {r}");
        }
        // the last state reached is the state of the last recorded row (every step recorded)
        let t_last = part.row(part.len() - 1)[0];
        let x = part.column("journal.x").unwrap();
        assert_eq!(part.y_final[3], x[x.len() - 1]);
        assert!(
            err.to_string().contains(&format!("t = {t_last} s")),
            "{err}"
        );
        // an integrator that refuses its settings fails before any row: empty partial
        // results with the same columns and no row note in the message
        opts.rtol = -1.0;
        let err = every_column_model().simulate(&opts).unwrap_err();
        let part = err.partial().expect("an integrator failure");
        assert!(part.is_empty() && part.columns == full.columns);
        assert!(!err.to_string().contains("rows recorded"), "{err}");
        // options errors carry no partial results
        opts.t_end = -1.0;
        assert!(every_column_model()
            .simulate(&opts)
            .unwrap_err()
            .partial()
            .is_none());
    }
}

/// The progress hook sees strictly increasing times, at most about one per 1 % of the span,
/// ending exactly at t_end; it does not change the results.
#[test]
fn progress_hook_reports_increasing_times_up_to_t_end() {
    let mut opts = SimOptions::span(0.0, 1e-3, 10).tolerances(1e-8, 1e-11);
    opts.every_step = true;
    let plain = every_column_model().simulate(&opts).unwrap();
    let seen = std::cell::RefCell::new(Vec::new());
    let hooked = every_column_model()
        .simulate_with(&opts, &|t| seen.borrow_mut().push(t))
        .unwrap();
    assert_eq!(hooked, plain);
    let seen = seen.into_inner();
    assert!(seen.windows(2).all(|w| w[1] > w[0]), "{seen:?}");
    assert_eq!(seen.last().copied(), Some(opts.t_end));
    // one call per 1 % of the span at most, plus the final one
    assert!(seen.len() >= 2 && seen.len() <= 101, "{} calls", seen.len());
    assert!(seen.windows(2).rev().skip(1).all(|w| w[1] - w[0] >= 1e-5));
    assert!(plain.stats.accepted > seen.len(), "fewer steps than calls");
}

/// A point-to-point actuator pushing a free block along a frictionless guide with a constant
/// force F and damping c: ẍ = (F − c ẋ)/m, closed form x(t) = x0 + (F/c)(t − τ(1 − e^(−t/τ)))
/// with τ = m/c; and its analytic Jacobian (tension turning with the line a–b) equals central
/// differences at an oblique state.
#[test]
fn actuator_pushes_a_block_as_the_closed_form_says() {
    let (m, f, c, x0) = (2.0, 10.0, 4.0, 0.5);
    let mut b = ModelBuilder::new();
    b.body("block", RigidBody::new(m, 0.01).at(x0, 0.0, 0.0))
        .translational(
            "guide",
            ("ground", [0.0, 0.0]),
            ("block", [0.0, 0.0]),
            [1.0, 0.0],
        )
        .actuator(
            "cyl",
            ("ground", [0.0, 0.0]),
            ("block", [0.0, 0.0]),
            Motion::constant(f),
            c,
        );
    let mut model = b.build().unwrap();
    let opts = SimOptions::span(0.0, 1.0, 10).tolerances(1e-10, 1e-12);
    let res = model.simulate(&opts).unwrap();
    let tau = m / c;
    let (t, x) = (res.column("t").unwrap(), res.column("block.x").unwrap());
    for (ti, xi) in t.iter().zip(&x) {
        let exact = x0 + f / c * (ti - tau * (1.0 - (-ti / tau).exp()));
        // integrator tolerance 1e-10 on metres: 1e-8 m leaves room for its global error
        assert!((xi - exact).abs() < 1e-8, "t = {ti}: {xi} vs {exact}");
    }
    // Jacobian of the actuator alone at a state where the line a–b is oblique
    let mut b = ModelBuilder::new();
    b.body("b", RigidBody::new(1.0, 0.1).at(0.4, 0.3, 0.2))
        .actuator(
            "cyl",
            ("ground", [0.0, 0.0]),
            ("b", [0.1, 0.05]),
            Motion::harmonic(5.0, 2.0, 3.0, 0.0),
            0.7,
        );
    let mut model = b.build().unwrap();
    let (q, qd) = ([0.4, 0.3, 0.2], [0.3, -0.2, 0.9]);
    let (a, fd) = (
        model.jacobians(0.2, &q, &qd),
        model.jacobians_fd(0.2, &q, &qd),
    );
    assert!(a.fallback.is_empty(), "{:?}", a.fallback);
    for (x, y) in [(&a.dq, &fd.dq), (&a.dv, &fd.dv)] {
        let scale = y.iter().fold(1e-12_f64, |s, v| s.max(v.abs()));
        for (u, v) in x.iter().zip(y) {
            // central differences with h ~ 1e-6: relative agreement to 1e-6 of the largest entry
            assert!((u - v).abs() <= 1e-6 * scale, "{u} vs {v}");
        }
    }
}

/// A description holding a Rust closure still compiles, but cannot be written to a file:
/// `to_toml` fails and names the item, and says how to make it data.
#[test]
fn a_closure_is_refused_by_to_toml_with_its_name() {
    let mut b = ModelBuilder::new();
    b.body("m", RigidBody::new(1.0, 0.1))
        .applied_force("push", ("m", [0.0, 0.0]), |_, s| {
            nalgebra::Vector2::new(-s.position.x, 0.0)
        });
    let desc = b.desc().clone();
    assert!(desc.compile().is_ok());
    let err = desc.to_toml().unwrap_err();
    assert!(err.contains("push"), "{err}");
}

/// The accelerations and multipliers [q̈; λ] of the range-space solve (`crate::rangespace`)
/// against the augmented matrix G = [M Φ_qᵀ; Φ_q 0] factored densely and sparsely (three
/// independent factorizations of the same equations), at arbitrary inconsistent states: rigid
/// bodies with every primitive constraint, and a pendulum on a clamped beam (banded beam mass,
/// a joint on a beam node) with a journal in a clearance.
#[test]
fn range_space_and_augmented_solves_agree() {
    for (name, mut model) in [("all_kinds", all_kinds()), ("beam", every_column_model())] {
        let n = model.n;
        let q: Vec<f64> = (0..n).map(|k| 0.01 * (k as f64 * 1.7).sin()).collect();
        let qd: Vec<f64> = (0..n).map(|k| 0.3 * (k as f64 * 0.9).cos()).collect();
        let mut y: Vec<f64> = model.given_state();
        for k in 0..n {
            y[k] += q[k];
            y[n + k] += qd[k];
        }
        let (q, qd) = (y[..n].to_vec(), y[n..2 * n].to_vec());
        assert!(model.solve_accelerations(0.1, &q, &qd));
        assert_eq!(model.range_space.applicable, Some(true), "{name}");
        let range = model.sol.clone();
        let mut others = Vec::new();
        for sparse in [false, true] {
            model.g.sparse = sparse;
            model.load_augmented_rhs();
            model.factor_augmented(&q).unwrap();
            let mut sol = model.sol.clone();
            if sparse {
                model.g.growing.solve(&mut sol);
            } else {
                model.g.dense.solve(&mut sol);
            }
            others.push(sol);
        }
        let scale = range.iter().fold(1.0f64, |a, v| a.max(v.abs()));
        for other in &others {
            for (a, b) in range.iter().zip(other) {
                assert!((a - b).abs() <= 1e-11 * scale, "{name}: {a} vs {b}");
            }
        }
    }
}
