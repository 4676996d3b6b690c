use super::*;
use crate::lubrication::HydrodynamicBearing;
use nalgebra::Vector3;

const RB: f64 = 10e-3;
const RJ: f64 = 9.95e-3;
const LB: f64 = 10e-3;
const LJ: f64 = 12e-3;
const MU: f64 = 0.04;

fn film(model: BearingModel) -> JournalFilm {
    let joint = JournalClearance::cylindrical(RB, LB, RJ, LJ).unwrap();
    JournalFilm::new(&joint, MU, model, Transition::new(0.5e-6, 0.0).unwrap()).unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

/// Bearing at rest at the origin, axis z; journal at `centre` with axis `axis`, velocity `v`,
/// angular velocity `w`.
fn state(
    centre: Vector3<f64>,
    axis: Vector3<f64>,
    v: Vector3<f64>,
    w: Vector3<f64>,
    wi: f64,
) -> JournalState<f64> {
    JournalState::new(
        Vector3::zeros(),
        Vector3::z(),
        Vector3::zeros(),
        Vector3::new(0.0, 0.0, wi),
        centre,
        axis,
        v,
        w,
    )
}

/// Without tilt every slice is the planar joint: the force equals the planar closed form
/// ([`HydrodynamicBearing`] of length L_b, the film length) for squeeze, wedge and both, and the
/// moment about u_b equals the planar shear torque T_j; no transverse moment (the film is centred
/// on O_j). Tolerances: long 1e-12 (constant integrand, Gauss exact), short 1e-9 (Gauss–Legendre
/// 32 per half of the π-film on an analytic integrand whose pole nears the real axis as ε → 1:
/// measured 2e-10 at ε = 0.8, 1e-14 at ε = 0.3).
#[test]
fn zero_tilt_reduces_to_the_planar_closed_forms() {
    let c = RB - RJ;
    for model in [BearingModel::ShortBearing, BearingModel::LongBearing] {
        let f = film(model);
        let planar = HydrodynamicBearing::new(RB, RJ, LB, MU, model).unwrap();
        for (eps, dir, v, wj, wi) in [
            (0.3, 0.4, Vector3::new(0.0, 0.0, 0.0), 300.0, 0.0),
            (0.6, -1.2, Vector3::new(0.01, -0.004, 0.0), 0.0, 0.0),
            (0.8, 2.5, Vector3::new(-0.003, 0.002, 0.02), 150.0, -40.0),
            (0.05, 0.0, Vector3::new(0.002, 0.001, 0.0), -80.0, 10.0),
        ] {
            let n = Vector3::new(f64::cos(dir), f64::sin(dir), 0.0);
            let t = Vector3::z().cross(&n);
            let s = state(eps * c * n, Vector3::z(), v, Vector3::new(0.0, 0.0, wj), wi);
            let out = f.loads(&s).unwrap();
            let rate = v.dot(&n) / c;
            let omega = wi + wj - 2.0 * v.dot(&t) / (eps * c);
            let p = planar.force_wedge(eps, rate, omega);
            let expect = p.radial * n + p.tangential * t;
            let tol = if model == BearingModel::LongBearing {
                1e-12
            } else {
                1e-9
            };
            let got = out.force.value();
            assert!(
                (got - expect).norm() <= tol * expect.norm(),
                "{model:?} {eps}: {got:?} vs {expect:?}"
            );
            let torque = planar.shear_torques(eps, wj - wi, p).journal;
            let m = out.journal_moment.value();
            assert!(rel(m.z, torque) < tol, "{model:?} {eps}: {m:?} vs {torque}");
            assert!(m.xy().norm() <= tol * expect.norm() * LB, "{m:?}");
            assert_eq!(out.film_length, LB);
            assert!(rel(out.min_film_thickness, c * (1.0 - eps)) < 1e-12);
        }
    }
}

/// A centred journal tilted by γ about y, spinning at ω about its own axis (no squeeze): long
/// bearing, e(z) = z tan γ x̂, so the slice at z has ε = |z|τ/c (τ = tan γ) and, from the steady
/// half-Sommerfeld force (Pinkus & Sternlicht 1961, ch. 3) per unit length with K′ = 6μr³/c² and
/// Ω = ω cos γ, F_t = K′πεΩ/((2 + ε²)√(1 − ε²)) = K′(π/2)εΩ(1 + O(ε⁴)) and
/// F_r = −2K′ε²Ω/((2 + ε²)(1 − ε²)) = −K′Ω(ε² + ε⁴/2 + O(ε⁶)). With the lever z/cos γ along u_j:
/// M_x = −2∫₀^{L/2} z F_t dz = −K′πΩτL³/(24c) (the cross-coupled moment, linear in e(z)),
/// M_y = 2∫₀^{L/2} z F_r dz = −K′Ω[τ²L⁴/(32c²) + τ⁴L⁶/(384c⁴)] (the restoring moment against
/// the tilt: quadratic in e(z)). At ε_max = 0.01 the neglected terms are ~1e-8 relative: tolerance
/// 1e-7.
#[test]
fn pure_tilt_long_bearing_moment_matches_the_closed_form() {
    let c = RB - RJ;
    let f = film(BearingModel::LongBearing);
    let tau: f64 = 0.01 * c / (0.5 * LB);
    let g = tau.atan();
    let uj = Vector3::new(g.sin(), 0.0, g.cos());
    let w = 250.0;
    let s = state(Vector3::zeros(), uj, Vector3::zeros(), w * uj, 0.0);
    let out = f.loads(&s).unwrap();
    let k = 6.0 * MU * RJ.powi(3) / (c * c);
    let om = w * g.cos();
    let mx = -k * PI * om * tau * LB.powi(3) / (24.0 * c);
    let my = -k
        * om
        * (tau * tau * LB.powi(4) / (32.0 * c * c)
            + tau.powi(4) * LB.powi(6) / (384.0 * c.powi(4)));
    let m = out.journal_moment.value();
    assert!(rel(m.x, mx) < 1e-7, "{m:?} vs {mx}");
    assert!(rel(m.y, my) < 1e-7, "{m:?} vs {my}");
    assert!(
        out.force.value().norm() < 1e-12 * (mx.abs() / LB),
        "{out:?}"
    );
}

/// The same tilted, spinning journal at ε_max = 0.5 against an independent quadrature (20 000
/// midpoints) of the steady closed forms above written out here: the Gauss rule (16 per side of
/// the kink at z = 0) and the slice kinematics. Tolerance 1e-8 (midpoint error ~1e-9).
#[test]
fn tilted_long_bearing_matches_the_integrated_steady_forms() {
    let c = RB - RJ;
    let f = film(BearingModel::LongBearing);
    let tau: f64 = 0.5 * c / (0.5 * LB);
    let g = tau.atan();
    let uj = Vector3::new(g.sin(), 0.0, g.cos());
    let w = 250.0;
    let out = f
        .loads(&state(Vector3::zeros(), uj, Vector3::zeros(), w * uj, 0.0))
        .unwrap();
    let k = 6.0 * MU * RJ.powi(3) / (c * c);
    let om = w * g.cos();
    let (mut mx, mut my) = (0.0, 0.0);
    let n = 20_000;
    let dz = 0.5 * LB / n as f64;
    for i in 0..n {
        let z = (i as f64 + 0.5) * dz;
        let e = z * tau / c;
        let ft = k * PI * e * om / ((2.0 + e * e) * (1.0 - e * e).sqrt());
        let fr = -k * 2.0 * e * e * om / ((2.0 + e * e) * (1.0 - e * e));
        mx -= 2.0 * z * ft * dz;
        my += 2.0 * z * fr * dz;
    }
    let m = out.journal_moment.value();
    assert!(rel(m.x, mx) < 1e-8, "{m:?} vs {mx}");
    assert!(rel(m.y, my) < 1e-8, "{m:?} vs {my}");
}

/// Pure squeeze (no spin about the bore axis) of a tilted journal moving and tilting in random
/// directions, both models: the film only dissipates, power F·v_j + M_j·ω_j ≤ 0 (bearing at
/// rest), and the pair conserves angular momentum (moments about a common point cancel, 1e-12).
#[test]
fn film_is_dissipative_and_balanced() {
    let c = RB - RJ;
    let mut seed = 12345u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    for model in [BearingModel::ShortBearing, BearingModel::LongBearing] {
        let f = film(model);
        for _ in 0..40 {
            let centre = Vector3::new(0.4 * c * rnd(), 0.4 * c * rnd(), 1e-3 * rnd());
            let g = 0.4 * c / (0.5 * LB) * rnd();
            let h = 0.4 * c / (0.5 * LB) * rnd();
            let uj = Vector3::new(g, h, 1.0).normalize();
            let v = 0.01 * Vector3::new(rnd(), rnd(), rnd());
            let mut w = 2.0 * Vector3::new(rnd(), rnd(), 0.0);
            w.z = -(w.x * uj.x + w.y * uj.y) / uj.z; // no spin: ω·u_j = 0
            let s = state(centre, uj, v, w, 0.0);
            let out = f.loads(&s).unwrap();
            let (fv, mj, mb) = (
                out.force.value(),
                out.journal_moment.value(),
                out.bearing_moment.value(),
            );
            let power = fv.dot(&v) + mj.dot(&w);
            let scale = fv.norm() * v.norm() + mj.norm() * w.norm();
            assert!(power <= 1e-12 * scale, "{model:?}: {power} of {scale}");
            let net = mj + mb + centre.cross(&fv);
            assert!(
                net.norm() <= 1e-12 * (mj.norm() + fv.norm() * LB),
                "{net:?}"
            );
        }
    }
}

/// Typed refusals: h_d < 0 (the dry weight is not evaluated per Gauss point), μ ≤ 0, a journal
/// tilted over 60°, a non-finite state.
#[test]
fn refusals_are_typed() {
    let joint = JournalClearance::cylindrical(RB, LB, RJ, LJ).unwrap();
    let m = BearingModel::ShortBearing;
    let e = JournalFilm::new(&joint, MU, m, Transition::new(1e-6, -0.5e-6).unwrap()).unwrap_err();
    assert!(e.to_string().contains("dry threshold"), "{e}");
    assert!(JournalFilm::new(&joint, 0.0, m, Transition::new(1e-6, 0.0).unwrap()).is_err());
    let f = film(m);
    let s = state(
        Vector3::zeros(),
        Vector3::x(),
        Vector3::zeros(),
        Vector3::zeros(),
        0.0,
    );
    assert!(matches!(f.loads(&s), Err(JournalError::Tilt { .. })));
    let s = state(
        Vector3::zeros(),
        Vector3::z(),
        Vector3::new(f64::NAN, 0.0, 0.0),
        Vector3::zeros(),
        0.0,
    );
    assert!(matches!(f.loads(&s), Err(JournalError::NonFinite { .. })));
    // journal out of the bore: no film
    let s = state(
        Vector3::new(0.0, 0.0, 0.1),
        Vector3::z(),
        Vector3::zeros(),
        Vector3::zeros(),
        0.0,
    );
    assert_eq!(f.loads(&s).unwrap().film_length, 0.0);
}

/// The closed-form line integrals ∫xᵏ/(1 + βx)³ against composite Simpson quadrature (200 000
/// intervals, error below 1e-12 for |β| ≤ 0.95), on both sides of the switch between the series
/// and the partial fractions (|β| = 0.3): tolerance 1e-10.
#[test]
fn line_integrals_match_quadrature() {
    for beta in [0.0, 0.1, -0.29, 0.299_999, 0.300_001, -0.6, 0.95] {
        for (x1, x2) in [(-1.0, 1.0), (-1.0, 0.3), (-0.2, 1.0)] {
            let g: [f64; 5] = between(beta, x1, x2);
            let n = 200_000;
            let dx = (x2 - x1) / n as f64;
            for (k, gk) in g.iter().enumerate() {
                let f = |x: f64| x.powi(k as i32) / (1.0 + beta * x).powi(3);
                let mut q = f(x1) + f(x2);
                for i in 1..n {
                    let x = x1 + i as f64 * dx;
                    q += if i % 2 == 1 { 4.0 } else { 2.0 } * f(x);
                }
                q *= dx / 3.0;
                assert!(
                    (gk - q).abs() < 1e-10 * q.abs().max(1.0),
                    "{beta} {k}: {gk} vs {q}"
                );
            }
        }
    }
}
