//! LuGre friction in clearance joints (`law = "lugre"`) against the closed forms of the LuGre
//! model (C. Canudas de Wit, H. Olsson, K.J. Åström, P. Lischinsky, IEEE Trans. Autom. Control
//! 40 (1995) 419–425), in clr-contact's friction-coefficient form μ = σ₀z + σ₁ż + σ₂v,
//! ż = v − σ₀|v|z/g(v), F_T = −μF_N:
//!
//! - steady sliding at slip v: ż = 0, z = z_ss = g(v) sgn(v)/σ₀ and
//!   F_T/F_N = −(g(v) sgn v + σ₂v) = −`steady_state_coefficient(v)`, whatever F_N is;
//! - at rest under a tangential load F below breakaway: ż = v = 0, so σ₀·z·F_N = F; a
//!   monotone, quasi-static loading (v ≪ v_s, so g ≈ μ_s) integrates dz/dx = 1 − σ₀z/μ_s into
//!   the pre-sliding displacement x = −(μ_s/σ₀) ln(1 − σ₀z/μ_s) (≈ z = F/(σ₀F_N) for small loads).
//!
//! Each run takes well under a second.

use clr_contact::LuGre;
use clr_mbd::desc::{BeamMaterial, MassKindDesc, SectionDesc, SupportDesc, SupportKind};
use clr_mbd::{
    BeamMesh, FlexibleGuideSpec, FrictionLawDesc, MbdError, ModelBuilder, NormalLawDesc, Results,
    RevoluteClearanceSpec, RigidBody, SimOptions, TimeFn, TranslationalClearanceSpec,
};
use clr_ode::OdeSystem;

const G: f64 = 9.81;
/// Bristle stiffness σ₀ (1/m): 100 /mm, a typical value.
const SIGMA0: f64 = 1e5;
/// Viscous coefficient σ₂ (s/m).
const SIGMA2: f64 = 2.0;
const MU_S: f64 = 0.15;
const MU_C: f64 = 0.10;
/// Stribeck velocity v_s (m/s).
const V_S: f64 = 1e-3;

/// Bristle damping σ₁ (s/m) of the sliding tests. The closed forms of steady sliding do not
/// depend on it; kept small because σ₁ż = σ₁v adds σ₁v·F_N at the start of a slide, before z
/// builds up (20 F_N at 0.05 m/s with the pre-sliding value below).
const SIGMA1: f64 = 1.0;

/// Bristle damping σ₁ (s/m) of the pre-sliding test: the pre-sliding oscillator of the 1 kg
/// block pressed by its own weight (stiffness σ₀mg, damping σ₁mg) gets the damping ratio ζ = 2,
/// σ₁ = 2ζ·sqrt(σ₀/g). Overdamped, so a monotone load gives a monotone displacement (no
/// velocity reversal, whose hysteresis the closed form x(z) does not cover).
fn sigma1_overdamped() -> f64 {
    4.0 * (SIGMA0 / G).sqrt()
}

fn law() -> LuGre {
    LuGre::new(SIGMA0, SIGMA1, SIGMA2, MU_S, MU_C, V_S).unwrap()
}

fn friction() -> FrictionLawDesc {
    FrictionLawDesc::lugre(SIGMA0, SIGMA1, SIGMA2, MU_S, MU_C, V_S)
}

/// Block: 1 kg, 60 mm × 18 mm, in a 20 mm guide fixed to the ground; Hertz corners K = 1e9
/// N/m^1.5 with Flores damping, c_e = 0.5.
const M: f64 = 1.0;
const L: f64 = 0.06;
const H: f64 = 0.018;
const W: f64 = 0.020;
const K: f64 = 1e9;

fn hertz(k: f64) -> NormalLawDesc {
    NormalLawDesc {
        law: "hertz".into(),
        damping: Some("flores".into()),
        restitution: 0.5,
        stiffness: Some(k),
        ..NormalLawDesc::default()
    }
}

fn inertia() -> f64 {
    M * (L * L + H * H) / 12.0
}

/// Centre height of the block resting on its two lower corners, each carrying mg/2 with the
/// static Hertz penetration (mg/2K)^(2/3).
fn resting_y() -> f64 {
    -(W - H) / 2.0 - (M * G / 2.0 / K).powf(2.0 / 3.0)
}

/// The block `body` in the guide `guide` with LuGre friction `friction`, under gravity.
fn block_with(b: &mut ModelBuilder, body: RigidBody, friction: FrictionLawDesc) {
    b.gravity(0.0, -G)
        .body("block", body)
        .translational_clearance(
            "guide",
            ("ground", [0.0, 0.0]),
            ("block", [0.0, 0.0]),
            TranslationalClearanceSpec {
                guide_width: W,
                guide_angle: 0.0,
                slider_length: L,
                slider_height: H,
                slider_angle: 0.0,
                normal: hertz(K).into(),
                friction: friction.into(),
            },
        );
}

/// [`block_with`] the friction of the sliding tests.
fn block(b: &mut ModelBuilder, body: RigidBody) {
    block_with(b, body, friction());
}

fn last(r: &Results, c: &str) -> f64 {
    *r.column(c).unwrap().last().unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Steady sliding of the block, pulled along the guide at v = v_s (where the Stribeck term is
/// e⁻¹ of its height, so g, its Stribeck part and σ₂ all enter) by a displacement driver at the
/// height of its sliding face (so that the pull and the friction make no moment: pulled at its
/// centre the block would pitch by a few µrad and creep there for ~100 ms through the heavily
/// damped corner contacts, changing the corner slip by ~1e-7 m/s): after 50 ms (the bristle transient decays as exp(−σ₀|v|t/g) ≈ e⁻⁴⁰⁰, the normal and
/// pitch transients through the contact damping), both loaded corners slip at v and
/// −ΣF_T/ΣF_N = steady_state_coefficient(v) with each z = z_ss(v). Tolerance 1e-6 relative:
/// integration error at rtol 1e-8 (the closed form is exact at steady state, independent of
/// how F_N splits between the corners).
#[test]
fn translational_steady_sliding_gives_the_steady_state_coefficient() {
    let v = V_S;
    let mut b = ModelBuilder::new();
    block(
        &mut b,
        RigidBody::new(M, inertia())
            .at(0.0, resting_y(), 0.0)
            .moving(v, 0.0, 0.0),
    );
    b.drive_displacement(
        "pull",
        ("ground", [0.0, 0.0]),
        ("block", [0.0, -H / 2.0]),
        [1.0, 0.0],
        TimeFn::linear(0.0, v),
    );
    let mut m = b.build().unwrap();
    assert_eq!(m.n_bristle_states(), 4);
    assert_eq!(m.dim(), 2 * m.n_coordinates() + 2 + 4);
    let r = m
        .simulate(&SimOptions::span(0.0, 0.05, 10).tolerances(1e-8, 1e-12))
        .unwrap();
    let (f_t, f_n) = (
        last(&r, "guide.friction_force"),
        last(&r, "guide.normal_force"),
    );
    let mu = -f_t / f_n;
    let expect = law().steady_state_coefficient(v);
    let z = last(&r, "guide.lugre_z");
    let z_ss = law().steady_state_z(v);
    eprintln!(
        "translational sliding: μ = {mu:.10} vs {expect:.10} (rel {:.2e}); z = {z:e} vs {z_ss:e} \
         (rel {:.2e}); F_N = {f_n} N",
        rel(mu, expect),
        rel(z, z_ss)
    );
    assert!(rel(mu, expect) < 1e-6, "μ = {mu} vs {expect}");
    assert!(rel(z, z_ss) < 1e-6, "z = {z} vs {z_ss}");
    assert!(rel(f_n, M * G) < 1e-6, "F_N = {f_n}");
    assert_eq!(last(&r, "guide.contact"), 2.0);
    // the final state carries the four corner states: the two loaded ones at z_ss
    let zs = &r.y_final[2 * m.n_coordinates() + 2..];
    assert_eq!(zs.len(), 4);
    assert!(
        zs.iter().filter(|z| rel(**z, z_ss) < 1e-6).count() == 2,
        "{zs:?}"
    );
}

/// Steady sliding in a revolute clearance joint: a journal (1 kg, R_j = 9.9 mm) in a bearing on
/// the ground (R_i = 10 mm) resting on the bottom under its weight, its centre held at x = 0 by
/// a displacement driver and spun at ω by an angle driver, so that the contact point slips at
/// v = ωR_j = 2v_s (g and σ₂v both differ from their values at v_s). After 20 ms (bristle
/// transient exp(−σ₀vt/g) ≈ e⁻⁵⁰⁰), −F_T/F_N = steady_state_coefficient(ωR_j) and z = z_ss.
/// Tolerance 1e-6 relative, integration error at rtol 1e-8.
#[test]
fn revolute_steady_sliding_gives_the_steady_state_coefficient() {
    let (rb, rj) = (0.010, 0.0099);
    let v = 2.0 * V_S;
    let omega = v / rj;
    let k = 1e9;
    let y0 = -(rb - rj) - (M * G / k).powf(2.0 / 3.0);
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -G)
        .body(
            "journal",
            RigidBody::new(M, 5e-5)
                .at(0.0, y0, 0.0)
                .moving(0.0, 0.0, omega),
        )
        .revolute_clearance(
            "bearing",
            ("ground", [0.0, 0.0]),
            ("journal", [0.0, 0.0]),
            RevoluteClearanceSpec {
                bearing_radius: rb,
                journal_radius: rj,
                normal: NormalLawDesc::hertz(k, 0.8).into(),
                friction: friction().into(),
            },
        )
        .drive_displacement(
            "hold_x",
            ("ground", [0.0, 0.0]),
            ("journal", [0.0, 0.0]),
            [1.0, 0.0],
            TimeFn::constant(0.0),
        )
        .drive_angle("spin", "journal", TimeFn::linear(0.0, omega));
    let mut m = b.build().unwrap();
    assert_eq!(m.n_bristle_states(), 1);
    let r = m
        .simulate(&SimOptions::span(0.0, 0.02, 4).tolerances(1e-8, 1e-12))
        .unwrap();
    let (f_t, f_n) = (
        last(&r, "bearing.friction_force"),
        last(&r, "bearing.normal_force"),
    );
    let mu = -f_t / f_n;
    let expect = law().steady_state_coefficient(v);
    let z = last(&r, "bearing.lugre_z");
    let z_ss = law().steady_state_z(v);
    eprintln!(
        "revolute sliding: μ = {mu:.10} vs {expect:.10} (rel {:.2e}); z = {z:e} vs {z_ss:e} \
         (rel {:.2e}); F_N = {f_n} N",
        rel(mu, expect),
        rel(z, z_ss)
    );
    assert!(rel(mu, expect) < 1e-6, "μ = {mu} vs {expect}");
    assert!(rel(z, z_ss) < 1e-6, "z = {z} vs {z_ss}");
    assert_eq!(r.y_final.len(), 2 * m.n_coordinates() + 3);
    assert_eq!(*r.y_final.last().unwrap(), z);
}

/// Pre-sliding: the block resting on the lower face is pushed along the guide by a force that
/// rises smoothly from 0 to F = 0.3·μ_s·mg in 30 ms and is then held (applied at the height of
/// the sliding face, so that it and the friction make no moment and the corners stay equally
/// loaded). At rest (0.1 s; slowest overdamped pole −0.27·sqrt(σ₀g) ≈ −265 /s) the closed forms
/// are
/// - σ₀·z·mg = F, i.e. z = F/(σ₀mg) (exact at rest): tolerance 1e-5 relative (integration);
/// - x = −(μ_s/σ₀) ln(1 − F/(μ_s mg)), 19 % above the linear F/(σ₀mg) at this load: tolerance
///   1e-3 relative, for g(v) ≈ μ_s during the loading (peak v ≈ 7e-5 m/s = 0.07 v_s, so g is
///   below μ_s by (μ_s − μ_c)(v/v_s)² ≲ 2.5e-4, and much less on average).
#[test]
fn pre_sliding_displacement_under_a_small_tangential_load() {
    let f = 0.3 * MU_S * M * G;
    let mut b = ModelBuilder::new();
    let mut friction = friction();
    friction.sigma1 = Some(sigma1_overdamped());
    block_with(
        &mut b,
        RigidBody::new(M, inertia()).at(0.0, resting_y(), 0.0),
        friction,
    );
    b.force(
        "push",
        ("block", [0.0, -H / 2.0]),
        TimeFn::SmoothStep {
            from: 0.0,
            to: f,
            start: 0.0,
            duration: 0.03,
        },
        TimeFn::constant(0.0),
    );
    let mut m = b.build().unwrap();
    let r = m
        .simulate(&SimOptions::span(0.0, 0.1, 10).tolerances(1e-8, 1e-13))
        .unwrap();
    let z = last(&r, "guide.lugre_z");
    let x = last(&r, "block.x");
    let f_n = last(&r, "guide.normal_force");
    let z_closed = f / (SIGMA0 * M * G);
    let x_closed = -(MU_S / SIGMA0) * (1.0 - f / (MU_S * M * G)).ln();
    eprintln!(
        "pre-sliding: z = {z:e} vs F/(σ0 F_N) = {z_closed:e} (rel {:.2e}); x = {x:e} vs {x_closed:e} \
         (rel {:.2e}; linear F/(σ0 F_N) would be off by {:.2e}); vx = {:e}",
        rel(z, z_closed),
        rel(x, x_closed),
        rel(z_closed, x_closed),
        last(&r, "block.vx")
    );
    assert!(rel(f_n, M * G) < 1e-6, "F_N = {f_n}");
    assert!(rel(z, z_closed) < 1e-5, "z = {z} vs {z_closed}");
    assert!(rel(x, x_closed) < 1e-3, "x = {x} vs {x_closed}");
    // the displacement never reversed (the closed form needs a monotone loading)
    let xs = r.column("block.x").unwrap();
    assert!(xs.windows(2).all(|w| w[1] >= w[0] - 1e-12), "{xs:?}");
}

/// Intermittent contact and the energy balance: the block is released in the middle of the guide
/// sliding at 0.05 m/s, falls 1 mm, bounces (c_e = 0.5) and slides on with LuGre friction. The
/// dissipated power is −F_T·v_T as for the stateless laws, so energy.total + energy.dissipated
/// stays at its initial value (tolerance 1e-8 J against 1.1e-2 J of energy in play:
/// integration error at rtol 1e-9; measured 6.5e-10 J). The bristles obey Property 1 of Canudas de Wit et al.:
/// |z| ≤ max(μ_s, μ_c)/σ₀.
#[test]
fn energy_balance_and_bounded_bristles_with_intermittent_contact() {
    let mut b = ModelBuilder::new();
    block(
        &mut b,
        RigidBody::new(M, inertia())
            .at(0.0, 0.0, 0.0)
            .moving(0.05, 0.0, 0.0),
    );
    let mut m = b.build().unwrap();
    let r = m
        .simulate(&SimOptions::span(0.0, 0.06, 300).tolerances(1e-9, 1e-13))
        .unwrap();
    let total = r.column("energy.total").unwrap();
    let diss = r.column("energy.dissipated").unwrap();
    let drift = total
        .iter()
        .zip(&diss)
        .map(|(e, d)| (e + d - total[0]).abs())
        .fold(0.0f64, f64::max);
    let z = r.column("guide.lugre_z").unwrap();
    let zmax = z.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let contact = r.column("guide.contact").unwrap();
    let separations = contact
        .windows(2)
        .filter(|w| w[0] > 0.0 && w[1] == 0.0)
        .count();
    eprintln!(
        "intermittent: drift {drift:e} J, dissipated {:e} J, max |z| {zmax:e} m, {} onsets, \
         {separations} separations seen in the output",
        diss.last().unwrap(),
        r.onsets
    );
    assert!(r.onsets >= 2, "{} onsets", r.onsets);
    assert!(separations >= 1, "no bounce");
    assert!(*diss.last().unwrap() > 1e-3);
    assert!(drift < 1e-8, "energy drift {drift} J");
    assert!(zmax <= law().z_max() * (1.0 + 1e-9), "{zmax}");
}

/// Contact loss: the block slides on the lower face (z at its steady-state value for the slip)
/// until an upward force lifts it off at 20 ms; at 35 ms it is in flight and its four bristle
/// states are exactly 0 (reset at separation, so the next contact starts undeflected). Before
/// the lift-off the loaded corners' z equals z_ss(v) for the block's slip (1e-6 relative).
#[test]
fn bristles_are_undeflected_after_contact_loss() {
    let mut b = ModelBuilder::new();
    block(
        &mut b,
        RigidBody::new(M, inertia())
            .at(0.0, resting_y(), 0.0)
            .moving(0.05, 0.0, 0.0),
    );
    b.force(
        "lift",
        ("block", [0.0, 0.0]),
        TimeFn::constant(0.0),
        TimeFn::SmoothStep {
            from: 0.0,
            to: 2.0 * M * G,
            start: 0.02,
            duration: 1e-3,
        },
    );
    let mut m = b.build().unwrap();
    let opts = SimOptions::span(0.0, 0.035, 35).tolerances(1e-8, 1e-12);
    let r = m.simulate(&opts).unwrap();
    let t = r.column("t").unwrap();
    let k = t.iter().position(|&t| (t - 0.019).abs() < 1e-12).unwrap();
    let vx = r.column("block.vx").unwrap()[k];
    let z = r.column("guide.lugre_z").unwrap()[k];
    let z_ss = law().steady_state_z(vx);
    eprintln!("sliding at vx = {vx}: z = {z:e} vs z_ss = {z_ss:e}");
    assert!(rel(z, z_ss) < 1e-6, "z = {z} vs {z_ss}");
    assert_eq!(last(&r, "guide.contact"), 0.0);
    let n = m.n_coordinates();
    assert_eq!(&r.y_final[2 * n + 2..], &[0.0; 4]);
    assert_eq!(last(&r, "guide.lugre_z"), 0.0);
}

/// Parameters are checked field by field, with the field's path in the error.
#[test]
fn lugre_parameters_are_validated_at_their_field() {
    let build = |f: FrictionLawDesc| {
        let mut b = ModelBuilder::new();
        b.body("j", RigidBody::new(1.0, 1e-4)).revolute_clearance(
            "bearing",
            ("ground", [0.0, 0.0]),
            ("j", [0.0, 0.0]),
            RevoluteClearanceSpec {
                bearing_radius: 0.01,
                journal_radius: 0.0099,
                normal: NormalLawDesc::hertz(1e9, 0.8).into(),
                friction: f.into(),
            },
        );
        b.build().map(|_| ()).map_err(|e| match e {
            MbdError::Invalid { path, message } => (path, message),
            other => panic!("{other}"),
        })
    };
    assert!(build(friction()).is_ok());
    type Change = fn(&mut FrictionLawDesc);
    let cases: [(&str, Change); 7] = [
        ("sigma0", |f| f.sigma0 = Some(-1.0)),
        ("sigma0", |f| f.sigma0 = None),
        ("sigma1", |f| f.sigma1 = Some(f64::NAN)),
        ("sigma2", |f| f.sigma2 = Some(-0.1)),
        ("mu_c", |f| f.mu_c = Some(0.0)),
        ("v_s", |f| f.v_s = None),
        ("mu", |f| f.mu = Some(0.1)),
    ];
    for (field, change) in cases {
        let mut f = friction();
        change(&mut f);
        let (path, message) = build(f).unwrap_err();
        eprintln!("{path}: {message}");
        assert_eq!(path, format!("bearing.friction.{field}"), "{message}");
    }
    // σ₂ defaults to 0
    let mut f = friction();
    f.sigma2 = None;
    assert!(build(f).is_ok());
}

/// A slider on a flexible guide refuses LuGre at its friction law, saying which elements take it.
#[test]
fn slider_on_beam_refuses_lugre() {
    let mesh = BeamMesh {
        start: [0.0, 0.0],
        end: [0.5, 0.0],
        elements: 4,
        material: BeamMaterial {
            youngs_modulus: 207e9,
            density: 7850.0,
            poisson_ratio: 0.3,
        },
        section: SectionDesc::Rectangular {
            width: 0.02,
            depth: 0.01,
        },
        supports: vec![SupportDesc {
            node: 0,
            kind: SupportKind::Clamped,
        }],
        rayleigh: [0.0, 0.0],
        mass: MassKindDesc::Consistent,
    };
    let mut b = ModelBuilder::new();
    b.flexible_beam("guide", mesh)
        .body("pad", RigidBody::new(0.2, 1e-4).at(0.25, 0.0106, 0.0))
        .slider_on_beam(
            "contact",
            "guide",
            ("pad", [0.0, 0.0]),
            FlexibleGuideSpec {
                face: clr_beam::Face::Upper,
                slider_length: 0.04,
                slider_height: 0.01,
                slider_angle: 0.0,
                face_points: 3,
                guide_samples: 0,
                normal: hertz(1e9).into(),
                area_normal: None,
                friction: friction().into(),
            },
        );
    match b.build() {
        Err(MbdError::Invalid { path, message }) => {
            assert_eq!(path, "contact.friction.law");
            assert!(message.contains("revolute and translational"), "{message}");
        }
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("a slider on a beam accepted LuGre friction"),
    }
}

/// The Jacobians of a LuGre clearance stay on the central-difference fallback (listed, never a
/// zero block) and equal central differences of the whole force vector at a loaded, sliding,
/// deflected state (bristle states held at the last evaluation's). Tolerance 1e-6 of the
/// largest entry, central-difference truncation with h = 1e-6·max(1, |x|).
#[test]
fn lugre_clearance_jacobians_fall_back_to_central_differences() {
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -G)
        .body("journal", RigidBody::new(M, 5e-5))
        .revolute_clearance(
            "bearing",
            ("ground", [0.0, 0.0]),
            ("journal", [0.0, 0.0]),
            RevoluteClearanceSpec {
                bearing_radius: 0.010,
                journal_radius: 0.0099,
                normal: NormalLawDesc::hertz(1e9, 0.8).into(),
                friction: friction().into(),
            },
        );
    let mut m = b.build().unwrap();
    // 10 µm into the wall below the centre, approaching it at 0.5 mm/s (so that the damped
    // normal force stays positive), sliding and spinning, bristles half deflected
    let q = [0.0, -0.00011, 0.2];
    let qd = [0.003, -0.0005, 0.5];
    let mut y: Vec<f64> = q.iter().chain(&qd).copied().collect();
    // y = (q, q̇, E_d, W_in, z)
    y.extend([0.0, 0.0]);
    y.push(0.5 * law().z_max());
    let mut dy = vec![0.0; m.dim()];
    m.rhs(0.0, &y, &mut dy);
    assert!(dy[8] != 0.0, "the bristle state does not move");
    let a = m.jacobians(0.0, &q, &qd);
    let f = m.jacobians_fd(0.0, &q, &qd);
    assert!(
        a.fallback.contains(&"bearing".to_string()),
        "{:?}",
        a.fallback
    );
    assert!(
        f.dv.iter().any(|v| v.abs() > 1.0),
        "no friction damping seen"
    );
    for (name, x, y) in [("dQ/dq", &a.dq, &f.dq), ("dQ/dqd", &a.dv, &f.dv)] {
        let scale = y.iter().fold(1e-12_f64, |s, v| s.max(v.abs()));
        for (k, (u, v)) in x.iter().zip(y.iter()).enumerate() {
            assert!((u - v).abs() <= 1e-6 * scale, "{name}[{k}]: {u} vs {v}");
        }
    }
}
