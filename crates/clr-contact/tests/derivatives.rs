//! Analytic derivatives of every contact and friction law (the Jacobian entries of an implicit
//! integrator) against central finite differences, as property tests over each law's domain.
//!
//! Reference for every property: the central difference (f(x + h) − f(x − h))/(2h) of the law's
//! own force function, with h = 1e-6·max(|x|, scale). It only evaluates the force, so it is
//! independent of the closed-form derivative under test. Its truncation error is O(h²f''') (about
//! 1e-12 relative on a smooth branch) and its rounding error about ε·F_scale/h, where F_scale is
//! the magnitude of the terms summed in the force. Tolerance of every comparison ([`close`]):
//!
//! |analytic − fd| ≤ 1e-5·|fd| + 1e-8·F_scale/x_scale,  x_scale = h/1e-6,
//!
//! i.e. 1e-5 relative, with an absolute floor 1e-8·F_scale/x_scale, about 50 times the rounding
//! error 2.2e-10·F_scale/x_scale of the difference quotient.
//!
//! Documented non-smooth points are excluded by a margin: the stencil never crosses them
//! (|x − x_kink| > 1e-3·|x_kink| for the switch velocities of the piecewise friction laws and for
//! Johnson's δ*; |1 + χδ̇/δ̇⁻| kept away from the clamp; F_N > 0; |v| ≥ 1e-7 m/s > h so the
//! stencil never crosses v = 0; δ ≥ 1e-7 m so it never crosses δ = 0).

use clr_contact::damping::DampingFactor;
use clr_contact::elastic::{ElasticLaw, Material};
use clr_contact::friction::{FrictionLaw, LuGre};
use clr_contact::normal::NormalLaw;
use proptest::prelude::*;

/// Relative tolerance of every comparison.
const REL: f64 = 1e-5;
/// Absolute floor, as a multiple of F_scale/x_scale (see the module docs).
const ABS: f64 = 1e-8;
/// Relative step of the central differences.
const STEP: f64 = 1e-6;
/// Relative margin around documented non-smooth points.
const KINK_MARGIN: f64 = 1e-3;
/// Smallest penetration (m) and |velocity| (m/s) sampled.
const DELTA_MIN: f64 = 1e-7;
const V_MIN: f64 = 1e-7;

/// Central difference of `f` at `x` with h = STEP·max(|x|, scale); returns (fd, x_scale).
fn central(f: impl Fn(f64) -> f64, x: f64, scale: f64) -> (f64, f64) {
    let x_scale = x.abs().max(scale);
    let h = STEP * x_scale;
    ((f(x + h) - f(x - h)) / (2.0 * h), x_scale)
}

/// |analytic − fd| ≤ REL·|fd| + ABS·f_scale/x_scale.
fn close(analytic: f64, fd: f64, f_scale: f64, x_scale: f64) -> bool {
    (analytic - fd).abs() <= REL * fd.abs() + ABS * f_scale / x_scale
}

/// Log-uniform in [lo, hi].
fn log_range(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..=hi.ln()).prop_map(move |x: f64| x.exp().clamp(lo, hi))
}

/// Log-uniform magnitude in [lo, hi] with a random sign.
fn signed_log_range(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (any::<bool>(), log_range(lo, hi)).prop_map(|(neg, x)| if neg { -x } else { x })
}

/// lo·(hi/lo)^t: log-interpolation, t ∈ [0, 1].
fn log_lerp(lo: f64, hi: f64, t: f64) -> f64 {
    (lo * (hi / lo).powf(t)).clamp(lo, hi)
}

// ---------------------------------------------------------------- elastic and normal laws

/// Physical data from which every elastic law is built.
#[derive(Debug, Clone)]
struct Geometry {
    m1: Material,
    m2: Material,
    /// Radii (m).
    r1: f64,
    r2: f64,
    /// Radial clearance ΔR (m), inside Pereira's fit range 0.005–10 mm.
    clearance: f64,
    /// Axial length L (m).
    length: f64,
    /// Power law K (N/m^n) and n.
    k_power: f64,
    n_power: f64,
    /// Linear spring k (N/m).
    k_linear: f64,
    /// Area law: edge radius ρ, face width w, layer depth h, contact length l (m).
    edge_radius: f64,
    width: f64,
    layer: f64,
    contact_length: f64,
}

prop_compose! {
    fn geometry()(
        e1 in log_range(1e9, 4e11), nu1 in 0.0f64..0.45,
        e2 in log_range(1e9, 4e11), nu2 in 0.0f64..0.45,
        r1 in log_range(1e-3, 0.1), r2 in log_range(1e-3, 0.1),
        clearance in log_range(5e-6, 1e-2), length in log_range(1e-3, 0.1),
        (k_power, n_power) in (log_range(1e4, 1e12), 0.5f64..3.0),
        k_linear in log_range(1e4, 1e10),
        (edge_radius, width, layer, contact_length) in (
            log_range(1e-4, 1e-2), log_range(1e-3, 0.1), log_range(1e-4, 0.1), log_range(1e-4, 0.1),
        ),
    ) -> Geometry {
        Geometry {
            m1: Material::new(e1, nu1).unwrap(),
            m2: Material::new(e2, nu2).unwrap(),
            r1, r2, clearance, length, k_power, n_power, k_linear,
            edge_radius, width, layer, contact_length,
        }
    }
}

/// An elastic law with the penetration interval [lo, hi] (m) it is tested on.
struct Case {
    name: &'static str,
    law: ElasticLaw,
    lo: f64,
    hi: f64,
}

/// Every constructor of `elastic.rs`, each on its domain: from DELTA_MIN to its validity limit.
/// Limits used: δ ≤ 0.1·R* (≤ 1 mm) for Hertz laws with radii (small patch compared with the
/// radii), δ ≤ ΔR (≤ 1 mm) for the conformal cylinder laws, 1 mm for laws without geometry,
/// Johnson up to δ*(1 − 1e-3) and its linear continuation on [δ*(1 + 1e-3), 3δ*].
fn elastic_cases(g: &Geometry) -> Vec<Case> {
    let e_star = g.m1.composite_modulus(&g.m2);
    let r_sphere = g.r1 * g.r2 / (g.r1 + g.r2);
    let (r_journal, r_bearing) = (g.r2, g.r2 + g.clearance);
    let r_internal = r_bearing * r_journal / g.clearance;
    let johnson = ElasticLaw::johnson(e_star, g.clearance, g.length).unwrap();
    let d_star = 4.0 * g.clearance / std::f64::consts::E.powi(2);
    let line = ElasticLaw::hertz_sphere_plane(&g.m1, g.edge_radius, &g.m2).unwrap();
    let area = ElasticLaw::area(line, e_star, g.width, g.layer)
        .unwrap()
        .with_contact_length(g.contact_length);
    let mm = 1e-3;
    let cyl = g.clearance.min(mm);
    vec![
        Case {
            name: "power",
            law: ElasticLaw::power(g.k_power, g.n_power).unwrap(),
            lo: DELTA_MIN,
            hi: mm,
        },
        Case {
            name: "hertz",
            law: ElasticLaw::hertz(g.k_power).unwrap(),
            lo: DELTA_MIN,
            hi: mm,
        },
        Case {
            name: "hertz_sphere_sphere",
            law: ElasticLaw::hertz_sphere_sphere(&g.m1, g.r1, &g.m2, g.r2).unwrap(),
            lo: DELTA_MIN,
            hi: (0.1 * r_sphere).min(mm),
        },
        Case {
            name: "hertz_sphere_plane",
            law: ElasticLaw::hertz_sphere_plane(&g.m1, g.r1, &g.m2).unwrap(),
            lo: DELTA_MIN,
            hi: (0.1 * g.r1).min(mm),
        },
        Case {
            name: "hertz_internal_cylinder",
            law: ElasticLaw::hertz_internal_cylinder(&g.m1, r_bearing, &g.m2, r_journal).unwrap(),
            lo: DELTA_MIN,
            hi: (0.1 * r_internal).min(cyl),
        },
        Case {
            name: "linear",
            law: ElasticLaw::linear(g.k_linear).unwrap(),
            lo: DELTA_MIN,
            hi: mm,
        },
        Case {
            name: "liu",
            law: ElasticLaw::liu(e_star, g.clearance, g.length).unwrap(),
            lo: DELTA_MIN,
            hi: cyl,
        },
        Case {
            name: "bai_zhao",
            law: ElasticLaw::bai_zhao(e_star, g.clearance).unwrap(),
            lo: DELTA_MIN,
            hi: cyl,
        },
        Case {
            name: "pereira_internal",
            law: ElasticLaw::pereira_internal(e_star, g.clearance, g.length).unwrap(),
            lo: DELTA_MIN,
            hi: cyl,
        },
        Case {
            name: "pereira_external",
            law: ElasticLaw::pereira_external(e_star, g.r1, g.r2, g.length).unwrap(),
            lo: DELTA_MIN,
            hi: (0.1 * g.r1.min(g.r2)).min(mm),
        },
        Case {
            name: "johnson",
            law: johnson,
            lo: DELTA_MIN,
            hi: d_star * (1.0 - KINK_MARGIN),
        },
        Case {
            name: "johnson beyond δ*",
            law: johnson,
            lo: d_star * (1.0 + KINK_MARGIN),
            hi: 3.0 * d_star,
        },
        Case {
            name: "area",
            law: area,
            lo: DELTA_MIN,
            hi: (0.1 * g.edge_radius).min(mm),
        },
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// dF_e/dδ = `ElasticLaw::stiffness` for every elastic law over its domain.
    /// Reference: central finite difference of `ElasticLaw::force` in δ, independent of the
    /// closed form; tolerance 1e-5 relative + 1e-8·F_e/δ (module docs).
    #[test]
    fn elastic_stiffness_matches_central_differences(g in geometry(), t in 0.0f64..=1.0) {
        for c in elastic_cases(&g) {
            let d = log_lerp(c.lo, c.hi, t);
            let k = c.law.stiffness(d);
            let (fd, xs) = central(|x| c.law.force(x), d, DELTA_MIN);
            let f = c.law.force(d);
            prop_assert!(k.is_finite() && k >= 0.0, "{}: stiffness {k:e} at δ = {d:e}", c.name);
            prop_assert!(close(k, fd, f, xs),
                "{}: stiffness {k:e} vs central difference {fd:e} at δ = {d:e}", c.name);
        }
    }

    /// ∂F_e/∂l = `ElasticLaw::contact_length_derivative` for the area law (0 for the others).
    /// Reference: central finite difference of `force` in the contact length l (set with
    /// `with_contact_length`), independent of the closed form; tolerance 1e-5 relative +
    /// 1e-8·F_e/l.
    #[test]
    fn area_contact_length_derivative_matches_central_differences(
        g in geometry(), t in 0.0f64..=1.0,
    ) {
        for c in elastic_cases(&g) {
            let d = log_lerp(c.lo, c.hi, t);
            let an = c.law.contact_length_derivative(d);
            let (fd, xs) = central(
                |l| c.law.with_contact_length(l).force(d), g.contact_length, 1e-4);
            prop_assert!(close(an, fd, c.law.force(d), xs),
                "{}: ∂F/∂l {an:e} vs central difference {fd:e} at δ = {d:e}", c.name);
            if c.name != "area" {
                prop_assert_eq!(an, 0.0);
            }
        }
    }

    /// `NormalLaw::force_with_derivatives` for every elastic law × every `DampingFactor::ALL`:
    /// F_N equals `force` bit for bit, ∂F_N/∂δ and ∂F_N/∂δ̇ (δ̇⁻ fixed) and
    /// `contact_length_derivative` (∂F_N/∂l) match the derivatives of `force`.
    /// Reference: central finite differences of `NormalLaw::force` in δ, δ̇ and l, independent of
    /// the closed forms; tolerance 1e-5 relative + 1e-8·F_scale/x_scale with
    /// F_scale = F_e(δ)(1 + χ|δ̇|/δ̇⁻) and x_scale = δ, max(|δ̇|, δ̇⁻) and l. The clamp kink
    /// δ̇ = −δ̇⁻/χ is excluded by |δ̇ + δ̇⁻/χ| > 1e-3·δ̇⁻/χ (the δ̇ stencil never reaches it).
    #[test]
    fn normal_law_derivatives_match_central_differences(
        g in geometry(),
        t in 0.0f64..=1.0,
        c_e in 0.05f64..=1.0,
        rate in signed_log_range(1e-6, 10.0),
        onset in log_range(1e-6, 10.0),
    ) {
        let cases = elastic_cases(&g);
        for damping in DampingFactor::ALL {
            for c in &cases {
                let law = NormalLaw::new(c.law, damping, c_e).unwrap();
                let d = log_lerp(c.lo, c.hi, t);
                let (f, dd, dv) = law.force_with_derivatives(d, rate, onset);
                prop_assert_eq!(f.to_bits(), law.force(d, rate, onset).to_bits(),
                    "{} + {}: F_N differs from force", c.name, damping.name());
                let v0 = onset.max(law.min_impact_velocity());
                let chi = law.chi();
                let f_scale = law.elastic_force(d) * (1.0 + chi * rate.abs() / v0);
                let (fd_d, xs_d) = central(|x| law.force(x, rate, onset), d, DELTA_MIN);
                prop_assert!(close(dd, fd_d, f_scale, xs_d),
                    "{} + {}: ∂F/∂δ {dd:e} vs {fd_d:e} at δ = {d:e}, δ̇ = {rate:e}, δ̇⁻ = {onset:e}",
                    c.name, damping.name());
                let l = g.contact_length;
                let dl = law.contact_length_derivative(d, rate, onset);
                let (fd_l, xs_l) = central(|x| law.with_contact_length(x).force(d, rate, onset), l, 1e-4);
                prop_assert!(close(dl, fd_l, f_scale, xs_l),
                    "{} + {}: ∂F/∂l {dl:e} vs {fd_l:e} at δ = {d:e}, δ̇ = {rate:e}, δ̇⁻ = {onset:e}",
                    c.name, damping.name());
                let kink = -v0 / chi;
                if chi > 0.0 && (rate - kink).abs() <= KINK_MARGIN * kink.abs() {
                    continue;
                }
                let (fd_v, xs_v) = central(|x| law.force(d, x, onset), rate, v0);
                prop_assert!(close(dv, fd_v, f_scale, xs_v),
                    "{} + {}: ∂F/∂δ̇ {dv:e} vs {fd_v:e} at δ = {d:e}, δ̇ = {rate:e}, δ̇⁻ = {onset:e}",
                    c.name, damping.name());
            }
        }
    }
}

// ---------------------------------------------------------------- stateless friction laws

/// A friction law with its switch velocities (the non-smooth or piecewise points of |v_T|).
struct Friction {
    name: &'static str,
    law: FrictionLaw,
    switches: Vec<f64>,
}

/// Parameters of the friction laws: coefficients (–) and characteristic velocities (m/s).
#[derive(Debug, Clone)]
struct FrictionParams {
    mu: f64,
    mu_d: f64,
    /// Regularization / lower velocity (m/s).
    v_a: f64,
    /// v_b/v_a − 1 > 0: ratio of the upper to the lower switch velocity.
    ratio: f64,
    /// Ambrósio with v0 = 0 (friction from zero slip).
    v0_zero: bool,
}

prop_compose! {
    fn friction_params()(
        mu in 0.01f64..1.0, mu_d in 0.0f64..1.0, v_a in log_range(1e-6, 0.1),
        ratio in log_range(1e-2, 1e2), v0_zero in prop::bool::weighted(0.2),
    ) -> FrictionParams {
        FrictionParams { mu, mu_d, v_a, ratio, v0_zero }
    }
}

/// Every friction constructor of `friction.rs`.
fn friction_laws(p: &FrictionParams) -> Vec<Friction> {
    let (va, vb) = (p.v_a, p.v_a * (1.0 + p.ratio));
    let v0 = if p.v0_zero { 0.0 } else { va };
    let ramp_switches = if p.v0_zero { vec![vb] } else { vec![va, vb] };
    vec![
        Friction {
            name: "coulomb",
            law: FrictionLaw::coulomb(p.mu, va).unwrap(),
            switches: vec![va],
        },
        Friction {
            name: "ambrosio",
            law: FrictionLaw::ambrosio(p.mu, v0, vb).unwrap(),
            switches: ramp_switches.clone(),
        },
        Friction {
            name: "ambrosio_smooth",
            law: FrictionLaw::ambrosio_smooth(p.mu, v0, vb).unwrap(),
            switches: ramp_switches,
        },
        Friction {
            name: "threlfall",
            law: FrictionLaw::threlfall(p.mu, va).unwrap(),
            switches: vec![],
        },
        Friction {
            name: "stribeck",
            law: FrictionLaw::stribeck(p.mu, p.mu_d, va, vb).unwrap(),
            switches: vec![va, vb],
        },
    ]
}

/// True if v is farther than the margin from every switch velocity ±s.
fn away_from_switches(v: f64, switches: &[f64]) -> bool {
    switches
        .iter()
        .all(|&s| (v.abs() - s).abs() > KINK_MARGIN * s)
}

/// Check `FrictionLaw::force_with_derivatives` at (v, F_N) against central differences.
fn check_friction(f: &Friction, v: f64, f_n: f64) -> Result<(), TestCaseError> {
    let (ft, d_v, d_n) = f.law.force_with_derivatives(v, f_n);
    prop_assert_eq!(
        ft.to_bits(),
        f.law.force(v, f_n).to_bits(),
        "{}: F_T differs from force",
        f.name
    );
    let f_scale = f.law.mu_max() * f_n;
    if away_from_switches(v, &f.switches) {
        let (fd, xs) = central(|x| f.law.force(x, f_n), v, V_MIN);
        prop_assert!(
            close(d_v, fd, f_scale, xs),
            "{}: ∂F_T/∂v_T {d_v:e} vs {fd:e} at v_T = {v:e}, F_N = {f_n:e}",
            f.name
        );
    }
    let (fd, xs) = central(|x| f.law.force(v, x), f_n, 0.0);
    prop_assert!(
        close(d_n, fd, f_scale, xs),
        "{}: ∂F_T/∂F_N {d_n:e} vs {fd:e} at v_T = {v:e}, F_N = {f_n:e}",
        f.name
    );
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// `FrictionLaw::force_with_derivatives` for coulomb, ambrosio, ambrosio-smooth, threlfall and
    /// stribeck: F_T equals `force` bit for bit; ∂F_T/∂v_T and ∂F_T/∂F_N match.
    /// Reference: central finite differences of `FrictionLaw::force` in v_T and F_N, independent
    /// of the closed forms; tolerance 1e-5 relative + 1e-8·μ_max F_N/x_scale (x_scale = |v_T| or
    /// F_N). Velocities span 1e-7–10 m/s on both sides of zero, plus points within 0.2–30 % of
    /// each switch velocity (both sides); switches are excluded by |(|v| − v_k)| > 1e-3·v_k.
    #[test]
    fn friction_derivatives_match_central_differences(
        p in friction_params(),
        v in signed_log_range(V_MIN, 10.0),
        near in signed_log_range(2e-3, 0.3),
        f_n in log_range(1e-3, 1e6),
    ) {
        for f in friction_laws(&p) {
            check_friction(&f, v, f_n)?;
            for &s in &f.switches {
                let v_near = s * (1.0 + near) * v.signum();
                check_friction(&f, v_near, f_n)?;
            }
        }
    }

    /// Clamp F_N ≤ 0: no force and zero derivatives (the documented choice).
    #[test]
    fn friction_derivatives_vanish_without_normal_force(
        p in friction_params(),
        v in signed_log_range(V_MIN, 10.0),
        f_n in -1e6f64..=0.0,
    ) {
        for f in friction_laws(&p) {
            prop_assert_eq!(f.law.force_with_derivatives(v, f_n), (0.0, 0.0, 0.0));
        }
    }
}

// ---------------------------------------------------------------- LuGre

prop_compose! {
    fn lugre()(
        sigma0 in log_range(1e3, 1e8),
        sigma1 in prop_oneof![Just(0.0), log_range(1e-3, 1e3)],
        sigma2 in prop_oneof![Just(0.0), log_range(1e-3, 10.0)],
        mu_s in 0.01f64..1.0,
        mu_c in 0.01f64..1.0,
        v_s in log_range(1e-5, 1.0),
    ) -> LuGre {
        LuGre::new(sigma0, sigma1, sigma2, mu_s, mu_c, v_s).unwrap()
    }
}

/// Bristle deflection scale (m): the largest steady-state |z|, max(μ_s, μ_c)/σ₀, recovered from
/// the public API (z_ss(v) = g(v)sgn(v)/σ₀ with g(0) = μ_s and g(∞) = μ_c).
fn z_scale(l: &LuGre) -> f64 {
    l.steady_state_z(1e-300)
        .abs()
        .max(l.steady_state_z(1e300).abs())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// `LuGre::z_dot_derivatives`: ż equals `z_dot` bit for bit, ∂ż/∂v and ∂ż/∂z match, with
    /// |v| from 1e-7 to 10 m/s on both sides of zero and |z| up to twice the largest steady
    /// deflection (the kink of |v| at v = 0 is never crossed: h = 1e-6|v|).
    /// Reference: central finite differences of `LuGre::z_dot` in v and z, independent of the
    /// closed forms; tolerance 1e-5 relative + 1e-8·(|v| + σ₀|v||z|/g)/x_scale, the bracket being
    /// the magnitude of the two terms of ż, x_scale = |v| or max(|z|, z_scale).
    #[test]
    fn lugre_z_dot_derivatives_match_central_differences(
        l in lugre(),
        v in signed_log_range(V_MIN, 10.0),
        z_frac in -2.0f64..=2.0,
    ) {
        let zs = z_scale(&l);
        let z = z_frac * zs;
        let (zd, d_v, d_z) = l.z_dot_derivatives(v, z);
        prop_assert_eq!(zd.to_bits(), l.z_dot(v, z).to_bits());
        // σ₀|v||z|/g = |ż − v|.
        let zd_scale = v.abs() + (zd - v).abs();
        let (fd, xs) = central(|x| l.z_dot(x, z), v, V_MIN);
        prop_assert!(close(d_v, fd, zd_scale, xs), "∂ż/∂v {d_v:e} vs {fd:e} at v = {v:e}, z = {z:e}");
        let (fd, xs) = central(|x| l.z_dot(v, x), z, zs);
        prop_assert!(close(d_z, fd, zd_scale, xs), "∂ż/∂z {d_z:e} vs {fd:e} at v = {v:e}, z = {z:e}");
    }

    /// `LuGre::force_with_derivatives`: F_T equals `force` bit for bit and the four partials
    /// (v, z, ż, F_N) match; the total derivatives through ż = ż(v, z) (chain rule with
    /// `z_dot_derivatives`) match the composite F_T(v, z, ż(v, z), F_N), which is what a Jacobian
    /// with z as a state needs.
    /// Reference: central finite differences of `LuGre::force` (and of the composite with
    /// `z_dot`), independent of the closed forms; tolerance 1e-5 relative +
    /// 1e-8·(σ₀|z| + σ₁|ż| + σ₂|v| + σ₁|v| + σ₁σ₀|v||z|/g)·F_N/x_scale (all terms of F_T).
    #[test]
    fn lugre_force_derivatives_match_central_differences(
        l in lugre(),
        v in signed_log_range(V_MIN, 10.0),
        z_frac in -2.0f64..=2.0,
        zd in signed_log_range(1e-7, 10.0),
        f_n in log_range(1e-3, 1e6),
    ) {
        let zs = z_scale(&l);
        let z = z_frac * zs;
        let (ft, d_v, d_z, d_zd, d_n) = l.force_with_derivatives(v, z, zd, f_n);
        prop_assert_eq!(ft.to_bits(), l.force(v, z, zd, f_n).to_bits());
        // Term magnitudes, via the public coefficient: σ₀|z|, σ₁|ż|, σ₂|v|.
        let s0z = l.coefficient(0.0, z, 0.0).abs();
        let s1 = l.coefficient(0.0, 0.0, 1.0);
        let s2v = l.coefficient(v, 0.0, 0.0).abs();
        let f_scale = (s0z + s1 * zd.abs() + s2v) * f_n;
        let (fd, xs) = central(|x| l.force(x, z, zd, f_n), v, V_MIN);
        prop_assert!(close(d_v, fd, f_scale, xs), "∂F/∂v {d_v:e} vs {fd:e}");
        let (fd, xs) = central(|x| l.force(v, x, zd, f_n), z, zs);
        prop_assert!(close(d_z, fd, f_scale, xs), "∂F/∂z {d_z:e} vs {fd:e}");
        let (fd, xs) = central(|x| l.force(v, z, x, f_n), zd, V_MIN);
        prop_assert!(close(d_zd, fd, f_scale, xs), "∂F/∂ż {d_zd:e} vs {fd:e}");
        let (fd, xs) = central(|x| l.force(v, z, zd, x), f_n, 0.0);
        prop_assert!(close(d_n, fd, f_scale, xs), "∂F/∂F_N {d_n:e} vs {fd:e}");

        // Total derivatives with ż = ż(v, z).
        let composite = |v: f64, z: f64| l.force(v, z, l.z_dot(v, z), f_n);
        let (zd_vz, dzd_v, dzd_z) = l.z_dot_derivatives(v, z);
        let (_, p_v, p_z, p_zd, _) = l.force_with_derivatives(v, z, zd_vz, f_n);
        let total_v = p_v + p_zd * dzd_v;
        let total_z = p_z + p_zd * dzd_z;
        let f_scale = (s0z + s1 * (v.abs() + (zd_vz - v).abs()) + s2v) * f_n;
        let (fd, xs) = central(|x| composite(x, z), v, V_MIN);
        prop_assert!(close(total_v, fd, f_scale, xs), "dF/dv {total_v:e} vs {fd:e} at v = {v:e}, z = {z:e}");
        let (fd, xs) = central(|x| composite(v, x), z, zs);
        prop_assert!(close(total_z, fd, f_scale, xs), "dF/dz {total_z:e} vs {fd:e} at v = {v:e}, z = {z:e}");
    }

    /// Clamp F_N ≤ 0: no force and zero derivatives (the documented choice).
    #[test]
    fn lugre_derivatives_vanish_without_normal_force(
        l in lugre(),
        v in signed_log_range(V_MIN, 10.0),
        z_frac in -2.0f64..=2.0,
        f_n in -1e6f64..=0.0,
    ) {
        let z = z_frac * z_scale(&l);
        prop_assert_eq!(
            l.force_with_derivatives(v, z, l.z_dot(v, z), f_n),
            (0.0, 0.0, 0.0, 0.0, 0.0)
        );
    }
}

/// The documented values at the non-smooth points themselves (not covered by the properties).
#[test]
fn derivatives_at_documented_non_smooth_points() {
    // LuGre at v = 0: ∂ż/∂v = 1, the mean of the one-sided values 1 ∓ σ₀z/g(0).
    let l = LuGre::new(1e5, 300.0, 0.0, 0.2, 0.1, 0.01).unwrap();
    let z = 1e-6;
    let (zd, d_v, d_z) = l.z_dot_derivatives(0.0, z);
    assert_eq!((zd, d_v, d_z), (0.0, 1.0, 0.0));
    let h = 1e-9;
    let right = (l.z_dot(h, z) - l.z_dot(0.0, z)) / h;
    let left = (l.z_dot(0.0, z) - l.z_dot(-h, z)) / h;
    assert!((0.5 * (left + right) - d_v).abs() < 1e-6, "{left} {right}");
    // Friction laws at their switch velocities: the branch with the larger |v_T|.
    let coulomb = FrictionLaw::coulomb(0.1, 1e-4).unwrap();
    assert_eq!(coulomb.force_with_derivatives(1e-4, 1000.0).1, 0.0);
    let ambrosio = FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap();
    let ramp = ambrosio.force_with_derivatives(-1e-4, 1000.0).1;
    assert!(
        (ramp / (-0.1 * 1000.0 / 9e-4) - 1.0).abs() < 1e-12,
        "{ramp}"
    );
    assert_eq!(ambrosio.force_with_derivatives(1e-3, 1000.0).1, 0.0);
    // Normal law on the clamp (1 + χδ̇/δ̇⁻ < 0): F = 0 and zero derivatives, also ∂F/∂l.
    let face = clr_contact::normal::GuideFace {
        slider: Material::steel(),
        guide: Material::steel(),
        edge_radius: 1e-3,
        width: 0.02,
        layer_depth: 5e-3,
    };
    let law = NormalLaw::area(&face, 0.5, 0.02).unwrap();
    let v_clamp = -2.0 * 0.5 / law.chi();
    assert_eq!(
        law.force_with_derivatives(1e-6, v_clamp, 0.5),
        (0.0, 0.0, 0.0)
    );
    assert_eq!(law.contact_length_derivative(1e-6, v_clamp, 0.5), 0.0);
    assert!(law.contact_length_derivative(1e-6, 0.1, 0.5) > 0.0);
}
