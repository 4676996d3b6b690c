//! The analytic Jacobians of the contact elements and floating-frame bodies
//! ([`Model::jacobians`]) against central differences of the whole model
//! ([`Model::jacobians_fd_best`]), at states in contact with friction sliding and sticking, for
//! every contact element kind.
//!
//! Comparison: per column c of ∂Q/∂q, ∂Q/∂q̇ and (Φ_q q̇)_q, ‖A_c − F_c‖₂ / max(‖F_c‖₂,
//! 10⁻⁸ max_c′ ‖F_c′‖₂), and the same per row (normwise by column, so that an error in a small
//! column is not hidden by the contact stiffness of another, and by row, so that a row of
//! moments is not hidden by the forces in its columns; the floor keeps rounding noise in
//! near-zero columns out). The largest is the error. The reference is
//! [`Model::jacobians_fd_best`] (per column the best of relative steps 10⁻⁴…10⁻¹⁰).
//! The contact memory is committed at the state first (as the integrator does after an
//! accepted step), so the impact velocity δ̇⁻ is a constant of both forms.
//!
//! Tolerance 1e-6: at these states (penetrations ≥ 1 µm, steps down to 10⁻¹⁰) the reference
//! agrees with the analytic forms to 1e-8–1e-7; the O(δ) terms that distinguish the force
//! application points (δ/R ≈ 10⁻³ of a moment row) or the guide contact point p − δn still
//! give errors near 1e-5 when dropped. Each test runs in milliseconds.

use clr_contact::{DampingFactor, ElasticLaw, FrictionLaw, GuideFace, Material, NormalLaw};
use clr_mbd::desc::beam::{BeamMaterial, MassKindDesc, SectionDesc, SupportDesc, SupportKind};
use clr_mbd::{
    BeamMesh, FlexibleGuideSpec, ForceApplication, Jacobians, Model, ModelBuilder, Reduction,
    RevoluteClearanceSpec, RigidBody, TranslationalClearanceSpec,
};
use clr_ode::OdeSystem;

const TOL: f64 = 1e-6;

/// Largest normwise relative difference of (rows × n) row-major `a` and `f`, by column and by
/// row (a row of small moments next to large forces is compared with its own norm).
fn column_error(a: &[f64], f: &[f64], n: usize) -> f64 {
    let rows = a.len() / n;
    let by = |len: usize, m: usize, at: &dyn Fn(usize, usize) -> usize| {
        let norm = |k: usize, x: &dyn Fn(usize) -> f64| {
            (0..m).map(|i| x(at(k, i)).powi(2)).sum::<f64>().sqrt()
        };
        let big = (0..len).map(|k| norm(k, &|e| f[e])).fold(0.0, f64::max);
        (0..len)
            .map(|k| {
                let scale = norm(k, &|e| f[e]).max(1e-8 * big).max(1e-300);
                norm(k, &|e| a[e] - f[e]) / scale
            })
            .fold(0.0, f64::max)
    };
    let cols = by(n, rows, &|c, r| r * n + c);
    let rws = by(rows, n, &|r, c| r * n + c);
    cols.max(rws)
}

/// Commit the memory at (q, q̇), evaluate there (reports), and return (analytic, FD, error).
fn compare(model: &mut Model, t: f64, q: &[f64], qd: &[f64]) -> (Jacobians, Jacobians, f64) {
    let mut y: Vec<f64> = q.iter().chain(qd).copied().collect();
    y.push(0.0);
    y.resize(model.dim(), 0.0);
    model.commit_contact_memory(&y);
    let mut dy = vec![0.0; model.dim()];
    model.rhs(t, &y, &mut dy);
    let a = model.jacobians(t, q, qd);
    let (f, _) = model.jacobians_fd_best(t, q, qd);
    let n = q.len();
    let err = [
        column_error(&a.dq, &f.dq, n),
        column_error(&a.dv, &f.dv, n),
        column_error(&a.phi_qqd_q, &f.phi_qqd_q, n),
    ]
    .into_iter()
    .fold(0.0, f64::max);
    eprintln!("column error {err:e}");
    (a, f, err)
}

fn hertz(k: f64) -> NormalLaw {
    NormalLaw::new(
        ElasticLaw::hertz(k).unwrap(),
        DampingFactor::LankaraniNikravesh,
        0.7,
    )
    .unwrap()
}

fn steel_face() -> GuideFace {
    GuideFace {
        slider: Material::steel(),
        guide: Material::new(70e9, 0.33).unwrap(),
        edge_radius: 2e-3,
        width: 0.02,
        layer_depth: 5e-3,
    }
}

/// Revolute clearance between two moving bodies: bearing centre on `a` at (0.2, 0), journal
/// centre on `b` at (−0.3, 0), 10 µm into the wall along direction β; `b` moves with `a`'s rigid
/// motion plus, relative to it, the journal-centre velocity v_n n + v_t t and a spin ω about the
/// journal centre (slip ≈ ω R_j + v_t).
fn revolute_case(friction: FrictionLaw, [v_n, v_t, spin]: [f64; 3], app: ForceApplication) -> f64 {
    let (c, delta, beta) = (0.5e-3, 1e-5, 0.7f64);
    let (ra, tha, va, wa) = ([0.1, -0.05], 0.3f64, [0.4, -0.2], 1.5);
    let rot = |th: f64, v: [f64; 2]| {
        [
            th.cos() * v[0] - th.sin() * v[1],
            th.sin() * v[0] + th.cos() * v[1],
        ]
    };
    let pa = rot(tha, [0.2, 0.0]);
    let (n, t) = ([beta.cos(), beta.sin()], [-beta.sin(), beta.cos()]);
    let pj = [
        ra[0] + pa[0] + (c + delta) * n[0],
        ra[1] + pa[1] + (c + delta) * n[1],
    ];
    let thb = -0.4f64;
    let sb = rot(thb, [-0.3, 0.0]);
    let rb = [pj[0] - sb[0], pj[1] - sb[1]];
    // a's rigid motion at r_b, plus the relative motion about the journal centre
    let vb = [
        va[0] - wa * (rb[1] - ra[1]) + v_n * n[0] + v_t * t[0] - spin * (rb[1] - pj[1]),
        va[1] + wa * (rb[0] - ra[0]) + v_n * n[1] + v_t * t[1] + spin * (rb[0] - pj[0]),
    ];
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -9.81)
        .clearance_force_application(app)
        .body("a", RigidBody::new(2.0, 0.05).at(ra[0], ra[1], tha))
        .body("b", RigidBody::new(1.0, 0.02).at(rb[0], rb[1], thb))
        .revolute_clearance(
            "joint",
            ("a", [0.2, 0.0]),
            ("b", [-0.3, 0.0]),
            RevoluteClearanceSpec {
                bearing_radius: 0.0100,
                journal_radius: 0.0100 - c,
                normal: hertz(2e10).into(),
                friction: friction.into(),
            },
        );
    let mut m = b.build().unwrap();
    let q = [ra[0], ra[1], tha, rb[0], rb[1], thb];
    let qd = [va[0], va[1], wa, vb[0], vb[1], wa + spin];
    let (a, f, err) = compare(&mut m, 0.0, &q, &qd);
    assert!(a.fallback.is_empty(), "{:?}", a.fallback);
    let r = m.contact_reports()[0];
    assert!(
        r.normal_force > 0.0 && f.dq.iter().any(|v| v.abs() > 1e6),
        "{r:?}"
    );
    err
}

#[test]
fn revolute_clearance_sliding_and_sticking() {
    let coulomb = FrictionLaw::coulomb(0.15, 1e-3).unwrap();
    let app = ForceApplication::ContactPoints;
    // sliding: spin 5 rad/s → |v_T| ≈ 5·9.5 mm ≫ v_reg; approaching at 10 mm/s
    let e = revolute_case(coulomb, [0.01, 0.0, 5.0], app);
    assert!(e < TOL, "sliding: {e:e}");
    // sticking: |v_T| ≈ 2e-4 m/s < v_reg (the regularized branch)
    let e = revolute_case(coulomb, [0.01, 2e-4, 0.0], app);
    assert!(e < TOL, "sticking: {e:e}");
    // force pair at the midpoint, Stribeck friction in its static branch and Ambrósio's ramp
    let app = ForceApplication::CommonPoint;
    let stribeck = FrictionLaw::stribeck(0.2, 0.1, 1e-3, 1e-2).unwrap();
    let e = revolute_case(stribeck, [0.01, 3e-4, 0.0], app);
    assert!(e < TOL, "common point, stribeck: {e:e}");
    let ambrosio = FrictionLaw::ambrosio(0.1, 1e-4, 1e-2).unwrap();
    let e = revolute_case(ambrosio, [0.01, 0.0, 0.5], app);
    assert!(e < TOL, "common point, ambrosio ramp: {e:e}");
}

/// The convention on the contact memory: at a tentative onset (closed in the committed memory)
/// the difference quotient also moves the tentative δ̇⁻ with δ̇, the analytic form holds it: the
/// two differ in ∂Q/∂q̇; once committed they agree (the check can fail).
#[test]
fn revolute_clearance_impact_velocity_is_a_constant() {
    let mut b = ModelBuilder::new();
    b.body("rod", RigidBody::new(1.0, 0.08).at(0.5, 0.0, 0.0))
        .revolute_clearance(
            "bearing",
            ("ground", [0.0, 0.0]),
            ("rod", [-0.5, 0.0]),
            RevoluteClearanceSpec {
                bearing_radius: 0.010,
                journal_radius: 0.009,
                normal: hertz(1e9).into(),
                friction: FrictionLaw::coulomb(0.1, 1e-3).unwrap().into(),
            },
        );
    let mut m = b.build().unwrap();
    let q = [0.50101, 0.0, 0.0];
    let qd = [0.05, 0.02, 0.3];
    let a = m.jacobians(0.0, &q, &qd);
    let (f, _) = m.jacobians_fd_best(0.0, &q, &qd);
    assert!(
        column_error(&a.dv, &f.dv, 3) > 1e-2,
        "tentative onset: δ̇⁻ varies in FD"
    );
    let (_, _, err) = compare(&mut m, 0.0, &q, &qd);
    assert!(err < TOL, "committed: {err:e}");
}

#[test]
fn revolute_clearance_without_contact_is_zero() {
    let coulomb = FrictionLaw::coulomb(0.15, 1e-3).unwrap();
    let mut b = ModelBuilder::new();
    b.body("rod", RigidBody::new(1.0, 0.08).at(0.5, 0.0, 0.0))
        .revolute_clearance(
            "bearing",
            ("ground", [0.0, 0.0]),
            ("rod", [-0.5, 0.0]),
            RevoluteClearanceSpec {
                bearing_radius: 0.010,
                journal_radius: 0.009,
                normal: hertz(1e9).into(),
                friction: coulomb.into(),
            },
        );
    let mut m = b.build().unwrap();
    let (q, qd) = ([0.5003, 0.0002, 0.0], [0.5, 0.2, 3.0]);
    let a = m.jacobians(0.0, &q, &qd);
    assert!(a.dq.iter().chain(&a.dv).all(|v| *v == 0.0));
    assert!(a.fallback.is_empty());
}

/// Translational clearance joint on a moving guide body, slider tilted so that two opposite
/// corners penetrate (jammed diagonally, 10 µm each), sliding along the guide at 1 m/s
/// (Coulomb, sliding) or moving with the guide (sticking).
fn translational_case(slide: f64) -> f64 {
    let (l, h, w, delta) = (0.1, 0.02, 0.021, 1e-5);
    // vertical extent h cos φ + L sin φ = W + 2δ
    let mut phi: f64 = 0.01;
    for _ in 0..50 {
        let f = h * phi.cos() + l * phi.sin() - (w + 2.0 * delta);
        phi -= f / (-h * phi.sin() + l * phi.cos());
    }
    let (rg, thg, vg, wg) = ([0.0, 0.1], 0.2f64, [0.1, 0.05], 0.3);
    let x = 0.3;
    let rs = [rg[0] + x * thg.cos(), rg[1] + x * thg.sin()];
    let vs = [
        vg[0] - wg * (rs[1] - rg[1]) + slide * thg.cos(),
        vg[1] + wg * (rs[0] - rg[0]) + slide * thg.sin(),
    ];
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -9.81)
        .body("guide", RigidBody::new(5.0, 0.5).at(rg[0], rg[1], thg))
        .body(
            "slider",
            RigidBody::new(0.5, 0.001).at(rs[0], rs[1], thg + phi),
        )
        .translational_clearance(
            "tc",
            ("guide", [0.0, 0.0]),
            ("slider", [0.0, 0.0]),
            TranslationalClearanceSpec {
                guide_width: w,
                guide_angle: 0.0,
                slider_length: l,
                slider_height: h,
                slider_angle: 0.0,
                normal: hertz(5e9).into(),
                friction: FrictionLaw::coulomb(0.2, 1e-3).unwrap().into(),
            },
        );
    let mut m = b.build().unwrap();
    let q = [rg[0], rg[1], thg, rs[0], rs[1], thg + phi];
    let qd = [vg[0], vg[1], wg, vs[0], vs[1], wg + 1e-3];
    let (a, _, err) = compare(&mut m, 0.0, &q, &qd);
    assert!(a.fallback.is_empty(), "{:?}", a.fallback);
    let r = m.contact_reports()[0];
    assert!(
        r.active_points == 2 && r.normal_force > 0.0,
        "two opposite corners: {r:?}"
    );
    err
}

#[test]
fn translational_clearance_sliding_and_sticking() {
    let e = translational_case(1.0);
    assert!(e < TOL, "sliding: {e:e}");
    let e = translational_case(0.0);
    assert!(e < TOL, "sticking: {e:e}");
}

/// A 1 m aluminium cantilever (clamped at node 0, 10 elements, section 20 × 10 mm).
fn cantilever(start: [f64; 2], end: [f64; 2]) -> BeamMesh {
    BeamMesh {
        start,
        end,
        elements: 10,
        material: BeamMaterial {
            youngs_modulus: 70e9,
            density: 2700.0,
            poisson_ratio: 0.33,
        },
        section: SectionDesc::Rectangular {
            width: 0.02,
            depth: 0.01,
        },
        supports: vec![SupportDesc {
            node: 0,
            kind: SupportKind::Clamped,
        }],
        rayleigh: [0.0, 1e-5],
        mass: MassKindDesc::Consistent,
    }
}

fn guide_spec(area: bool, friction: FrictionLaw) -> FlexibleGuideSpec {
    let face = steel_face();
    FlexibleGuideSpec {
        face: clr_beam::Face::Upper,
        slider_length: 0.06,
        slider_height: 0.01,
        slider_angle: 0.0,
        face_points: 3,
        guide_samples: 0,
        normal: NormalLaw::flores_line(&face, 0.8).unwrap().into(),
        area_normal: area.then(|| NormalLaw::area(&face, 0.8, 0.0).unwrap().into()),
        friction: friction.into(),
    }
}

/// Slider on the upper face of a ground-fixed cantilever bent as v = a x², θ = 2ax (moving:
/// v̇ = ȧx²), its bottom face tilted 0.2 mrad against the face so that the corner at the rear
/// is 8 µm deep and the contact a partial wedge (some candidates active, some not: the wetted
/// lengths depend on the neighbours' projections); sliding along the beam at `slide` m/s
/// (Ambrósio friction, sliding) or approaching only (|v_T| in the ramp).
fn fixed_guide_case(area: bool, slide: f64) -> f64 {
    // xc off the nodes: a candidate on a node sits on the kink of the load rows' s-derivative
    // (C¹ Hermite interpolation), where a difference quotient averages the two sides
    let (a, ad, xc, tilt, depth) = (2e-5, 1e-3, 0.5037, 2e-4, 8e-6);
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -9.81)
        .flexible_beam("g", cantilever([0.0, 0.0], [1.0, 0.0]))
        .body("slider", RigidBody::new(0.4, 1e-3))
        .slider_on_beam(
            "pad",
            "g",
            ("slider", [0.0, 0.0]),
            guide_spec(area, FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap()),
        );
    let mut m = b.build().unwrap();
    let n = m.n_coordinates();
    assert_eq!(n, 3 + 30);
    let (mut q, mut qd) = (vec![0.0; n], vec![0.0; n]);
    for k in 1..=10 {
        let x = k as f64 * 0.1;
        let o = 3 + 3 * (k - 1);
        q[o + 1] = a * x * x;
        q[o + 2] = 2.0 * a * x;
        qd[o + 1] = ad * x * x;
        qd[o + 2] = 2.0 * ad * x;
    }
    // rear corner (−L/2, −h/2) 8 µm below the face at x = xc − L/2, the face rising by `tilt`
    // more than the beam's slope there
    let (l, hs, hb) = (0.06, 0.01, 0.01);
    let xr = xc - 0.5 * l;
    let th = 2.0 * a * xc + tilt;
    let face_r = [xr - 0.5 * hb * (2.0 * a * xr), a * xr * xr + 0.5 * hb];
    let corner = [
        -0.5 * l * th.cos() + 0.5 * hs * th.sin(),
        -0.5 * l * th.sin() - 0.5 * hs * th.cos(),
    ];
    q[0] = face_r[0] - corner[0];
    q[1] = face_r[1] - depth - corner[1];
    q[2] = th;
    qd[..3].copy_from_slice(&[slide, -1e-3, 2e-3]);
    let (j, _, err) = compare(&mut m, 0.0, &q, &qd);
    assert!(j.fallback.is_empty(), "{:?}", j.fallback);
    let r = m.contact_reports()[0];
    assert!(r.normal_force > 0.0, "{r:?}");
    assert!((2..16).contains(&r.active_points), "a partial wedge: {r:?}");
    err
}

#[test]
fn slider_on_fixed_beam_line_and_area_laws() {
    for (area, slide) in [(false, 0.5), (true, 0.5), (true, 0.0)] {
        let e = fixed_guide_case(area, slide);
        assert!(e < TOL, "area {area}, slide {slide}: {e:e}");
    }
}

/// Slider on the upper face of a floating-frame cantilever (2 modes) turning at 0.5 rad/s with
/// elastic coordinates and rates; the slider pad 10 µm into the face, sliding along it. The
/// floating body's own terms (inertia coupling, quadratic velocity, elastic and damping forces)
/// are checked with it.
#[test]
fn slider_on_floating_beam_and_floating_terms() {
    let (th, xc, depth) = (0.1f64, 0.5, 1e-5);
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -9.81)
        .floating_beam(
            "g",
            cantilever([0.0, 0.0], [1.0, 0.0]),
            Reduction::Modal { modes: 2 },
            [0.05, -0.02, th],
            [0.1, 0.0, 0.5],
        )
        .body("slider", RigidBody::new(0.4, 1e-3))
        .slider_on_beam(
            "pad",
            "g",
            ("slider", [0.0, 0.0]),
            guide_spec(true, FrictionLaw::coulomb(0.1, 1e-3).unwrap()),
        );
    let mut m = b.build().unwrap();
    let n = m.n_coordinates();
    assert_eq!(n, 3 + 5);
    // q = (slider x, y, θ; frame R_x, R_y, θ; q_0, q_1): rigid bodies come first
    let (mut q, mut qd) = (vec![0.0; n], vec![0.0; n]);
    q[3..6].copy_from_slice(&[0.05, -0.02, th]);
    qd[3..6].copy_from_slice(&[0.1, 0.0, 0.5]);
    // tip deflection of a few µm at most: the face under the slider stays within ~1 µm
    q[6] = 1e-6;
    q[7] = -2e-7;
    qd[6] = 1e-4;
    qd[7] = 3e-5;
    // slider centre above the body-frame point (xc, hb/2 + hs/2 − δ), turned with the frame
    let local = [xc, 0.005 + 0.005 - depth];
    let (s, c) = th.sin_cos();
    q[0] = 0.05 + c * local[0] - s * local[1];
    q[1] = -0.02 + s * local[0] + c * local[1];
    q[2] = th;
    qd[0] = 0.1 - 0.5 * (q[1] + 0.02) + 0.3 * c;
    qd[1] = 0.5 * (q[0] - 0.05) + 0.3 * s;
    qd[2] = 0.5;
    let (j, _, err) = compare(&mut m, 0.0, &q, &qd);
    assert!(j.fallback.is_empty(), "{:?}", j.fallback);
    let r = m.contact_reports()[0];
    assert!(r.active_points >= 2 && r.normal_force > 0.0, "{r:?}");
    assert!(err < TOL, "{err:e}");
}

/// A floating arm pinned to the ground at its clamped node and carrying a bob at its deforming
/// tip (a node tie): Q_v, gravity, elastic and damping terms and (Φ_q q̇)_q of the tie, at a
/// state with elastic coordinates and rates, without contact. Relative step 1e-4: Q is
/// quadratic in q_f and q̇ (exact central differences) and trigonometric in θ (truncation
/// h²/6 ≈ 2e-9), while the elastic forces K q_f ~ 10³ N would give rounding noise
/// ε·10³/h ≈ 2e-7 N per unit at h = 1e-6 against θ-columns of ~10⁻²; tolerance 1e-6.
#[test]
fn floating_body_and_node_tie() {
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -9.81)
        .floating_beam(
            "arm",
            cantilever([0.0, 0.0], [1.0, 0.0]),
            Reduction::Modal { modes: 3 },
            [0.0; 3],
            [0.0; 3],
        )
        .revolute("pin", ("ground", [0.0, 0.0]), ("arm", 0usize))
        .revolute("tip", ("arm", 10usize), ("bob", [-0.25, 0.0]))
        .body("bob", RigidBody::new(0.5, 0.01).at(1.25, 0.0, 0.0));
    let mut m = b.build().unwrap();
    let n = m.n_coordinates();
    let mut y = m.given_state();
    for (k, v) in y.iter_mut().enumerate().take(2 * n) {
        *v += 1e-3 * ((k * 7 % 13) as f64 - 6.0);
    }
    // q = (bob x, y, θ; arm R_x, R_y, θ, q_f (3); tip node frame (3)): the arm turns at 2 rad/s
    y[n + 5] = 2.0;
    let (q, qd) = (y[..n].to_vec(), y[n..2 * n].to_vec());
    let a = m.jacobians(0.0, &q, &qd);
    let f = m.jacobians_fd_step(0.0, &q, &qd, 1e-4);
    assert!(a.fallback.is_empty(), "{:?}", a.fallback);
    assert!(a.phi_qqd_q.iter().any(|v| *v != 0.0));
    for (name, x, y) in [
        ("dQ/dq", &a.dq, &f.dq),
        ("dQ/dqd", &a.dv, &f.dv),
        ("(Phi_q qd)_q", &a.phi_qqd_q, &f.phi_qqd_q),
    ] {
        let e = column_error(x, y, n);
        if e >= 1e-6 {
            for c in 0..n {
                let col: Vec<(f64, f64)> = (0..x.len() / n)
                    .map(|r| (x[r * n + c], y[r * n + c]))
                    .collect();
                eprintln!("col {c}: {col:?}");
            }
        }
        assert!(e < 1e-6, "{name}: {e:e}");
    }
}

/// Elements without an analytic form stay on the fallback, differenced over their own
/// contribution with the fallback's step 1e-6·max(1, |x|): a LuGre revolute clearance and a
/// slider with reverse-check guide samples. The assembled Jacobians equal central differences
/// of the whole model with that same step ([`Model::jacobians_fd`]; tolerance 1e-6
/// column-normwise: the same stencil, rounding only), and the analytic blocks of the other
/// elements are not replaced.
#[test]
fn lugre_and_guide_samples_are_on_the_fallback() {
    let lugre = clr_contact::LuGre::new(1e5, 30.0, 0.0, 0.15, 0.1, 1e-3).unwrap();
    let mut b = ModelBuilder::new();
    b.body("rod", RigidBody::new(1.0, 0.08).at(0.5, 0.0, 0.0))
        .revolute_clearance(
            "bearing",
            ("ground", [0.0, 0.0]),
            ("rod", [-0.5, 0.0]),
            RevoluteClearanceSpec {
                bearing_radius: 0.010,
                journal_radius: 0.009,
                normal: hertz(1e9).into(),
                friction: lugre.into(),
            },
        );
    let mut m = b.build().unwrap();
    let (q, qd) = ([0.50101, 0.0, 0.0], [0.05, 0.02, 0.3]);
    let (a, _, _) = compare(&mut m, 0.0, &q, &qd);
    let f = m.jacobians_fd(0.0, &q, &qd);
    assert_eq!(a.fallback, vec!["bearing".to_string()]);
    assert!(column_error(&a.dq, &f.dq, 3).max(column_error(&a.dv, &f.dv, 3)) < 1e-6);

    let mut spec = guide_spec(true, FrictionLaw::coulomb(0.1, 1e-3).unwrap());
    spec.guide_samples = 9;
    let mut b = ModelBuilder::new();
    b.flexible_beam("g", cantilever([0.0, 0.0], [1.0, 0.0]))
        .body("slider", RigidBody::new(0.4, 1e-3))
        .slider_on_beam("pad", "g", ("slider", [0.0, 0.0]), spec);
    let mut m = b.build().unwrap();
    let n = m.n_coordinates();
    let mut q = vec![0.0; n];
    q[..3].copy_from_slice(&[0.5037, 0.01 - 5e-6, 1e-4]);
    let mut qd = vec![0.0; n];
    qd[1] = -1e-3;
    let (a, _, _) = compare(&mut m, 0.0, &q, &qd);
    let f = m.jacobians_fd(0.0, &q, &qd);
    assert_eq!(a.fallback, vec!["pad".to_string()]);
    assert!(m.contact_reports()[0].normal_force > 0.0);
    assert!(column_error(&a.dq, &f.dq, n).max(column_error(&a.dv, &f.dv, n)) < 1e-6);
}

/// A lubricated revolute clearance joint (short-bearing film + dry Hertz law): the analytic
/// Newton-matrix block (film force through its exact local partials, chained by dual numbers,
/// and the shear torque; the dry laws weighted by w(h_min)) against central differences of the
/// whole model, in the film regime, beyond the film threshold (force frozen in ε) and in
/// contact.
#[test]
fn lubricated_revolute_jacobians_match_central_differences() {
    let text = r#"
[model]
gravity = [0.0, -9.81]

[[body]]
name = "a"
mass = 2.0
inertia = 0.05

[[body]]
name = "b"
mass = 1.0
inertia = 0.02

[[clearance]]
name = "joint"
type = "revolute"
bearing = { body = "a", at = [0.2, 0.0] }
journal = { body = "b", at = [-0.3, 0.0] }
bearing_radius = 0.01
journal_radius = 0.0095
normal = { law = "hertz", stiffness = 2e10, restitution = 0.8, damping = "lankarani-nikravesh" }
friction = { law = "coulomb", mu = 0.1, v_reg = 1e-3 }
lubrication = { model = "short_bearing", viscosity = 0.05, length = 0.02, film_threshold = 2e-5, dry_threshold = -5e-6 }
"#;
    let table: toml::Table = text.parse().unwrap();
    let desc = clr_mbd::ModelDesc::from_toml_table(table).unwrap();
    let c = 0.5e-3;
    // eccentricities: film regime (ε = 0.6), frozen film (h_min = 1e-5 < h_t), in contact
    // inside the fade-in of the dry law (δ = 2 µm < |h_d|)
    for e in [0.6 * c, c - 1e-5, c + 2e-6] {
        let mut m = desc.compile().unwrap();
        let (ra, tha) = ([0.1, -0.05], 0.3f64);
        let beta = 0.7f64;
        let pa = [ra[0] + 0.2 * tha.cos(), ra[1] + 0.2 * tha.sin()];
        let pj = [pa[0] + e * beta.cos(), pa[1] + e * beta.sin()];
        let thb = -0.4f64;
        let rb = [pj[0] + 0.3 * thb.cos(), pj[1] + 0.3 * thb.sin()];
        let q = [ra[0], ra[1], tha, rb[0], rb[1], thb];
        let qd = [0.4, -0.2, 1.5, 0.3, 0.1, 40.0];
        let (a, _, err) = compare(&mut m, 0.0, &q, &qd);
        assert!(a.fallback.is_empty(), "{:?}", a.fallback);
        assert!(
            err < TOL,
            "e = {e:e} m: analytic vs central differences {err:e}"
        );
    }
}
