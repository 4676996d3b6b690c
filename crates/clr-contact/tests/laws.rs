//! Normal-force, damping, restitution and friction laws against the checklist of
//! contact-laws.md §7.1–7.6 (values recomputed there with numpy/scipy) and closed forms.
//!
//! Printed references are compared to their printed precision: `assert_digits(v, "1.0723158e10")`
//! passes when v rounds to the printed digits (|v − r| ≤ 0.51 unit of the last printed digit).

use clr_contact::damping::DampingFactor;
use clr_contact::elastic::{
    bai_zhao_stiffness, johnson_force_limit, johnson_penetration, ElasticLaw, Material, PereiraFit,
};
use clr_contact::friction::{FrictionLaw, LuGre};
use clr_contact::normal::{GuideFace, JournalBearing, NormalLaw};
use clr_contact::restitution::{chi_exact, effective_restitution, kelvin_voigt_restitution};
use clr_contact::ContactError;
use proptest::prelude::*;

/// Compare with a printed reference to the precision it is printed with.
fn assert_digits(value: f64, reference: &str) {
    let r: f64 = reference.parse().unwrap();
    let mantissa = reference
        .trim_start_matches(['-', '+'])
        .split(['e', 'E'])
        .next()
        .unwrap();
    let exponent: i32 = reference
        .split(['e', 'E'])
        .nth(1)
        .map_or(0, |e| e.parse().unwrap());
    let decimals = mantissa.split('.').nth(1).map_or(0, |d| d.len()) as i32;
    let unit = 10f64.powi(exponent - decimals);
    assert!(
        (value - r).abs() <= 0.51 * unit,
        "value {value:e} does not match the reference {reference} (unit of last digit {unit:e})"
    );
}

fn assert_rel(value: f64, reference: f64, tol: f64) {
    assert!(
        (value - reference).abs() <= tol * reference.abs(),
        "value {value:e} vs reference {reference:e}: relative error {:e} > {tol:e}",
        (value - reference).abs() / reference.abs()
    );
}

const DR: f64 = 1e-4;
const L: f64 = 15e-3;

fn steel() -> Material {
    Material::steel()
}

fn internal_hertz() -> ElasticLaw {
    ElasticLaw::hertz_internal_cylinder(&steel(), 10e-3, &steel(), 9.9e-3).unwrap()
}

fn e_star() -> f64 {
    steel().composite_modulus(&steel())
}

// ---------------------------------------------------------------- §0 and §4 derived quantities

#[test]
fn composite_modulus_and_compliance() {
    // contact-laws.md §4: σ = 4.396135e-12 1/Pa, E* = 1.137363e11 Pa.
    assert_digits(steel().compliance(), "4.396135e-12");
    assert_digits(e_star(), "1.137363e11");
}

// ---------------------------------------------------------------- §7.1 stiffness

#[test]
fn hertz_stiffness_values() {
    let ss = ElasticLaw::hertz_sphere_sphere(&steel(), 10e-3, &steel(), 10e-3).unwrap();
    assert_digits(ss.power_parameters().unwrap().0, "1.0723158e10");
    assert_digits(ss.force(10e-6), "339.0960");
    let sp = ElasticLaw::hertz_sphere_plane(&steel(), 10e-3, &steel()).unwrap();
    assert_digits(sp.power_parameters().unwrap().0, "1.5164835e10");
    let rev = internal_hertz();
    assert_digits(rev.power_parameters().unwrap().0, "1.50888205e11");
    assert_eq!(rev.power_parameters().unwrap().1, 1.5);
    assert_digits(rev.force(10e-6), "4771.5040");
}

#[test]
fn hertz_elastic_journal_peak() {
    // §4: elastic Hertz δ_max = 2.1207e-5 m, F_max = 14735.7 N for m = 1 kg, v0 = 0.5 m/s.
    // Energy balance: m v0²/2 = K δ^{5/2}/(5/2).
    let (k, n) = internal_hertz().power_parameters().unwrap();
    let d_max = (0.5 * 1.0 * 0.25 * (n + 1.0) / k).powf(1.0 / (n + 1.0));
    assert_digits(d_max, "2.1207e-5");
    assert_digits(internal_hertz().force(d_max), "14735.7");
}

#[test]
fn invalid_geometry_is_an_error() {
    assert!(matches!(
        ElasticLaw::hertz_internal_cylinder(&steel(), 9e-3, &steel(), 10e-3),
        Err(ContactError::InvalidParameter { .. })
    ));
    assert!(Material::new(-1.0, 0.3).is_err());
    assert!(Material::new(1e9, 0.5).is_err());
    assert!(ElasticLaw::liu(e_star(), 0.0, L).is_err());
    assert!(ElasticLaw::hertz(f64::NAN).is_err());
}

// ---------------------------------------------------------------- §7.2 dissipative laws

#[test]
fn dissipative_law_values() {
    let cases = [
        (DampingFactor::LankaraniNikravesh, "6113.4895", "3429.5185"),
        (DampingFactor::Flores, "8588.7072", "954.3008"),
        (DampingFactor::HuntCrossley, "6560.8180", "2982.1900"),
        (DampingFactor::Gonthier, "8350.1320", "1192.8760"),
        (DampingFactor::HuGuo, "8350.1320", "1192.8760"),
        (DampingFactor::ZhiyingQishao, "8419.3988", "1123.6092"),
        (DampingFactor::HerbertMcWhannell, "7157.2560", "2385.7520"),
        (DampingFactor::GharibHurmuzlu, "7157.2560", "2385.7520"),
        (DampingFactor::LeeWang, "5666.1610", "3876.8470"),
    ];
    for (d, plus, minus) in cases {
        let law = NormalLaw::new(internal_hertz(), d, 0.5).unwrap();
        assert_digits(law.force(10e-6, 0.25, 0.5), plus);
        assert_digits(law.force(10e-6, -0.25, 0.5), minus);
    }
}

#[test]
fn chi_values_at_half() {
    // §1.2 table, χ at c_e = 0.5.
    let expected = [
        (DampingFactor::None, "0"),
        (DampingFactor::HuntCrossley, "0.75"),
        (DampingFactor::HerbertMcWhannell, "1.0"),
        (DampingFactor::LeeWang, "0.375"),
        (DampingFactor::LankaraniNikravesh, "0.5625"),
        (DampingFactor::Gonthier, "1.5"),
        // The spec prints 1.5290340; 0.5625·e = 1.52903352..., i.e. 1.529034 to its 7 digits.
        (DampingFactor::ZhiyingQishao, "1.529034"),
        (DampingFactor::Flores, "1.6"),
        (DampingFactor::GharibHurmuzlu, "1.0"),
        (DampingFactor::HuGuo, "1.5"),
        (DampingFactor::Exact, "1.432751"),
    ];
    for (d, chi) in expected {
        assert_digits(d.chi(0.5).unwrap(), chi);
    }
}

#[test]
fn force_is_zero_without_penetration_and_clamped() {
    let law = NormalLaw::new(internal_hertz(), DampingFactor::Flores, 0.5).unwrap();
    assert_eq!(law.force(0.0, 1.0, 0.5), 0.0);
    assert_eq!(law.force(-1e-6, 1.0, 0.5), 0.0);
    // 1 + χδ̇/δ̇⁻ = 1 − 1.6·1/0.5 < 0: clamped at 0.
    assert_eq!(law.force(10e-6, -1.0, 0.5), 0.0);
    assert!(law.force(10e-6, -0.3, 0.5) > 0.0);
}

#[test]
fn impact_velocity_floor() {
    let law = NormalLaw::new(internal_hertz(), DampingFactor::LankaraniNikravesh, 0.5).unwrap();
    let v = NormalLaw::DEFAULT_MIN_IMPACT_VELOCITY;
    // δ̇⁻ = 0 (resting contact) behaves as δ̇⁻ = floor.
    assert_eq!(law.force(1e-6, 1e-5, 0.0), law.force(1e-6, 1e-5, v));
    let fe = law.elastic_force(1e-6);
    assert_rel(
        law.force(1e-6, 1e-5, 0.0),
        fe * (1.0 + 0.5625 * 1e-5 / v),
        1e-14,
    );
    let custom = law.with_min_impact_velocity(1e-2).unwrap();
    assert_rel(
        custom.force(1e-6, 1e-5, 0.0),
        fe * (1.0 + 0.5625 * 1e-3),
        1e-14,
    );
    assert!(law.with_min_impact_velocity(0.0).is_err());
}

#[test]
fn restitution_out_of_range_is_an_error() {
    for c in [0.0, -0.1, 1.1, f64::NAN] {
        assert!(matches!(
            DampingFactor::Flores.chi(c),
            Err(ContactError::InvalidParameter { .. })
        ));
        assert!(NormalLaw::new(internal_hertz(), DampingFactor::Gonthier, c).is_err());
    }
    assert_eq!(DampingFactor::Gonthier.chi(1.0).unwrap(), 0.0);
}

#[test]
fn damping_names_round_trip() {
    for d in DampingFactor::ALL {
        assert_eq!(DampingFactor::from_name(d.name()).unwrap(), d);
    }
    assert_eq!(
        DampingFactor::from_name("LN").unwrap(),
        DampingFactor::LankaraniNikravesh
    );
    let err = DampingFactor::from_name("kelvin").unwrap_err().to_string();
    assert!(
        err.contains("lankarani-nikravesh") && err.contains("kelvin"),
        "{err}"
    );
}

// ---------------------------------------------------------------- §7.3 restitution

#[test]
fn effective_restitution_table() {
    // contact-laws.md §1.3, e_eff of each χ(c_e), to 4 decimals.
    let ce = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95];
    let table: [(DampingFactor, [&str; 10]); 9] = [
        (
            DampingFactor::HuntCrossley,
            [
                "0.5158", "0.5469", "0.5813", "0.6197", "0.6630", "0.7120", "0.7680", "0.8329",
                "0.9090", "0.9524",
            ],
        ),
        (
            DampingFactor::HerbertMcWhannell,
            [
                "0.4907", "0.5008", "0.5200", "0.5503", "0.5936", "0.6511", "0.7227", "0.8070",
                "0.9009", "0.9501",
            ],
        ),
        (
            DampingFactor::LeeWang,
            [
                "0.6867", "0.7120", "0.7390", "0.7680", "0.7992", "0.8329", "0.8693", "0.9090",
                "0.9524", "0.9756",
            ],
        ),
        (
            DampingFactor::LankaraniNikravesh,
            [
                "0.6653", "0.6723", "0.6842", "0.7016", "0.7252", "0.7561", "0.7960", "0.8471",
                "0.9132", "0.9535",
            ],
        ),
        (
            DampingFactor::Gonthier,
            [
                "0.1010", "0.2046", "0.3042", "0.3978", "0.4877", "0.5773", "0.6696", "0.7680",
                "0.8764", "0.9359",
            ],
        ),
        (
            DampingFactor::ZhiyingQishao,
            [
                "0.2175", "0.2664", "0.3267", "0.3988", "0.4826", "0.5769", "0.6796", "0.7874",
                "0.8959", "0.9489",
            ],
        ),
        (
            DampingFactor::Flores,
            [
                "0.0694", "0.1555", "0.2562", "0.3629", "0.4704", "0.5773", "0.6832", "0.7885",
                "0.8939", "0.9468",
            ],
        ),
        (
            DampingFactor::HuGuo,
            [
                "0.0741", "0.1656", "0.2707", "0.3796", "0.4877", "0.5936", "0.6973", "0.7992",
                "0.8999", "0.9500",
            ],
        ),
        (
            DampingFactor::GharibHurmuzlu,
            [
                "0.1111", "0.2413", "0.3702", "0.4877", "0.5936", "0.6894", "0.7767", "0.8569",
                "0.9310", "0.9661",
            ],
        ),
    ];
    for (d, row) in table {
        for (c, e) in ce.iter().zip(row) {
            assert_digits(d.effective_restitution(*c).unwrap(), e);
        }
    }
    assert_digits(
        DampingFactor::LankaraniNikravesh
            .effective_restitution(0.5)
            .unwrap(),
        "0.725241",
    );
}

#[test]
fn chi_exact_values_and_round_trip() {
    assert_digits(chi_exact(0.5).unwrap(), "1.432751");
    assert_digits(chi_exact(0.9).unwrap(), "0.166482");
    for (c, chi) in [(0.1, "9.9982"), (0.3, "3.0871"), (0.7, "0.6348")] {
        assert_digits(chi_exact(c).unwrap(), chi);
    }
    for c in [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95] {
        let e = effective_restitution(chi_exact(c).unwrap()).unwrap();
        assert_rel(e, c, 1e-12);
        assert_rel(
            DampingFactor::Exact.effective_restitution(c).unwrap(),
            c,
            1e-12,
        );
    }
    assert_eq!(chi_exact(1.0).unwrap(), 0.0);
    assert!(chi_exact(0.0).is_err());
}

#[test]
fn restitution_limits() {
    assert_eq!(effective_restitution(0.0).unwrap(), 1.0);
    assert_eq!(effective_restitution(f64::INFINITY).unwrap(), 0.0);
    assert!(effective_restitution(-1.0).is_err());
    // Small χ: e = 1 − 2χ/3 + O(χ²) (series of the relation, contact-laws.md §1.3).
    let chi = 1e-6;
    assert_rel(
        1.0 - effective_restitution(chi).unwrap(),
        2.0 * chi / 3.0,
        1e-5,
    );
    // Large χ: e → 1/χ (the relation gives 1 − χe = (1+χ)e^{−(1+e)χ}, negligible).
    for chi in [40.0, 1e3, 1e8] {
        assert_rel(effective_restitution(chi).unwrap(), 1.0 / chi, 1e-12);
    }
    // e is decreasing in χ across the three solution branches (series, direct, log form).
    let mut last = 1.0;
    for i in 1..400 {
        let e = effective_restitution(i as f64 * 0.01).unwrap();
        assert!(e < last, "not decreasing at χ = {}", i as f64 * 0.01);
        last = e;
    }
}

/// Independent check: fixed-step RK4 of the linear spring–dashpot until the force vanishes.
#[test]
fn kelvin_voigt_restitution_matches_integration() {
    let (k, c, m) = (1e6, 200.0, 1.0);
    let e = kelvin_voigt_restitution(k, c, m).unwrap();
    let acc = |x: f64, v: f64| -(k * x + c * v) / m;
    let (mut x, mut v, h) = (0.0f64, 1.0f64, 1e-7);
    let mut in_contact = true;
    while in_contact {
        let (k1x, k1v) = (v, acc(x, v));
        let (k2x, k2v) = (v + 0.5 * h * k1v, acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v));
        let (k3x, k3v) = (v + 0.5 * h * k2v, acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v));
        let (k4x, k4v) = (v + h * k3v, acc(x + h * k3x, v + h * k3v));
        x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        in_contact = k * x + c * v > 0.0;
    }
    // The force crosses zero within one step of 1e-7 s, during which v changes by ≤ |a|h.
    assert_rel(-v, e, 1e-4);
    assert!(kelvin_voigt_restitution(k, 2.0 * (k * m).sqrt(), m).is_err());
    assert_eq!(kelvin_voigt_restitution(k, 0.0, m).unwrap(), 1.0);
}

// ---------------------------------------------------------------- §7.4 journal impact

struct Impact {
    e_eff: f64,
    delta_max: f64,
    f_max: f64,
    t_c: f64,
}

/// 1-D free impact m δ̈ = −F(δ, δ̇, v0) from δ = 0, δ̇ = v0, integrated with fixed-step RK4
/// (independent of clr-ode) until δ returns to 0 (linear interpolation of the crossing).
fn impact(law: &NormalLaw, m: f64, v0: f64, h: f64) -> Impact {
    let acc = |d: f64, v: f64| -law.force(d, v, v0) / m;
    let (mut d, mut v, mut t) = (0.0f64, v0, 0.0f64);
    let (mut delta_max, mut f_max) = (0.0f64, 0.0f64);
    loop {
        let (k1d, k1v) = (v, acc(d, v));
        let (k2d, k2v) = (v + 0.5 * h * k1v, acc(d + 0.5 * h * k1d, v + 0.5 * h * k1v));
        let (k3d, k3v) = (v + 0.5 * h * k2v, acc(d + 0.5 * h * k2d, v + 0.5 * h * k2v));
        let (k4d, k4v) = (v + h * k3v, acc(d + h * k3d, v + h * k3v));
        let dn = d + h / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d);
        let vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if dn <= 0.0 {
            let s = d / (d - dn);
            return Impact {
                e_eff: -(v + s * (vn - v)) / v0,
                delta_max,
                f_max,
                t_c: t + s * h,
            };
        }
        d = dn;
        v = vn;
        t += h;
        delta_max = delta_max.max(d);
        f_max = f_max.max(law.force(d, v, v0));
    }
}

#[test]
fn journal_impact_table() {
    // contact-laws.md §4: e_eff, δ_max (m), F_max (N), t_c (s); 1e-3 relative.
    let jb = JournalBearing::flap_paper_test();
    let hertz = internal_hertz();
    let liu = ElasticLaw::liu(e_star(), DR, L).unwrap();
    let bai = ElasticLaw::bai_zhao(e_star(), DR).unwrap();
    let pereira = ElasticLaw::pereira_internal(e_star(), DR, L).unwrap();
    let rows = [
        (
            hertz,
            DampingFactor::LankaraniNikravesh,
            0.72524,
            1.8745e-5,
            13343.9,
            1.3014e-4,
        ),
        (
            hertz,
            DampingFactor::HuntCrossley,
            0.66296,
            1.8142e-5,
            13311.4,
            1.3210e-4,
        ),
        (
            hertz,
            DampingFactor::Flores,
            0.47044,
            1.6117e-5,
            13847.8,
            1.4177e-4,
        ),
        (
            hertz,
            DampingFactor::HuGuo,
            0.48774,
            1.6312e-5,
            13757.9,
            1.4058e-4,
        ),
        (
            hertz,
            DampingFactor::ZhiyingQishao,
            0.48261,
            1.6254e-5,
            13783.6,
            1.4093e-4,
        ),
        (
            liu,
            DampingFactor::LankaraniNikravesh,
            0.72524,
            1.7518e-5,
            13994.3,
            1.2229e-4,
        ),
        (
            bai,
            DampingFactor::LankaraniNikravesh,
            0.72524,
            2.5584e-5,
            11189.0,
            1.7106e-4,
        ),
        (
            pereira,
            DampingFactor::LankaraniNikravesh,
            0.72524,
            1.2522e-5,
            17800.8,
            8.9963e-5,
        ),
    ];
    for (elastic, damping, e, d_max, f_max, t_c) in rows {
        let law = NormalLaw::new(elastic, damping, 0.5).unwrap();
        let r = impact(&law, 1.0, 0.5, 2e-8);
        assert_rel(r.e_eff, e, 2e-5);
        assert_rel(r.e_eff, law.effective_restitution(), 1e-6);
        assert_rel(r.delta_max, d_max, 1e-3);
        assert_rel(r.f_max, f_max, 1e-3);
        assert_rel(r.t_c, t_c, 1e-3);
    }
    // The flap paper's presets give its measured restitution (paper-systems.md §1.1), ±0.002.
    for (name, e) in [
        ("Hertz", 1.0),
        ("LN", 0.726),
        ("Gonthier", 0.488),
        ("Bai", 0.482),
        ("Wang", 0.482),
        ("Modified", 0.488),
    ] {
        let law = NormalLaw::preset(name, &jb, 0.5).unwrap();
        assert!(
            (impact(&law, 1.0, 0.5, 2e-8).e_eff - e).abs() <= 0.002,
            "{name}"
        );
    }
}

#[test]
fn presets_are_the_documented_pairings() {
    let jb = JournalBearing::flap_paper_test();
    let get = |n: &str| NormalLaw::preset(n, &jb, 0.5).unwrap();
    assert_eq!(get("hertz").damping(), DampingFactor::None);
    assert_eq!(get("LN").damping(), DampingFactor::LankaraniNikravesh);
    assert_eq!(get("Gonthier").damping(), DampingFactor::Gonthier);
    assert_eq!(get("Bai").damping(), DampingFactor::ZhiyingQishao);
    assert_eq!(get("Wang").damping(), DampingFactor::ZhiyingQishao);
    assert_eq!(get("Modified").damping(), DampingFactor::Gonthier);
    assert_rel(
        get("Bai").elastic().force(10e-6),
        bai_stiffness_force(10e-6),
        1e-14,
    );
    assert_eq!(get("Wang").elastic(), get("Modified").elastic());
    let err = NormalLaw::preset("Kelvin", &jb, 0.5)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("Hertz, LN, Gonthier, Bai, Wang, Modified"),
        "{err}"
    );
}

fn bai_stiffness_force(d: f64) -> f64 {
    bai_zhao_stiffness(e_star(), 1e-4, d) * d.powf(1.5)
}

// ---------------------------------------------------------------- §7.5 cylinder laws

#[test]
fn liu_values() {
    let liu = ElasticLaw::liu(e_star(), DR, L).unwrap();
    assert_digits(liu.force(1e-6), "188.55342");
    assert_digits(liu.force(10e-6), "5713.4542");
    assert_digits(liu.force(100e-6), "133992.38");
    // Small-δ asymptote F ≈ (π/2)/√2·E*Lδ^{1.5}/√ΔR = 1.1107·E*Lδ^{1.5}/√ΔR.
    let d: f64 = 1e-10;
    let asym = std::f64::consts::PI / 8f64.sqrt() * e_star() * L * d.powf(1.5) / DR.sqrt();
    assert_rel(liu.force(d), asym, 1e-6);
}

#[test]
fn bai_zhao_values() {
    assert_digits(bai_zhao_stiffness(e_star(), DR, 1e-6), "1.879311e10");
    assert_digits(bai_zhao_stiffness(e_star(), DR, 10e-6), "5.540319e10");
    let bai = ElasticLaw::bai_zhao(e_star(), DR).unwrap();
    assert_digits(bai.force(1e-6), "18.79311");
    assert_digits(bai.force(10e-6), "1752.0028");
    let hybrid = NormalLaw::new(bai, DampingFactor::LankaraniNikravesh, 0.5).unwrap();
    assert_digits(hybrid.force(10e-6, 0.25, 0.5), "2244.7536");
    // K_n = (1/L) dF_Liu/dδ (central difference, truncation error O(h²)).
    let liu = ElasticLaw::liu(e_star(), DR, L).unwrap();
    for d in [1e-6, 10e-6, 50e-6] {
        let h = d * 1e-4;
        let slope = (liu.force(d + h) - liu.force(d - h)) / (2.0 * h) / L;
        assert_rel(bai_zhao_stiffness(e_star(), DR, d), slope, 1e-7);
    }
}

#[test]
fn pereira_values() {
    let fit = PereiraFit::internal(e_star(), DR, L).unwrap();
    assert_digits(fit.y, "1.1990212");
    assert_digits(fit.exponent, "1.2129052");
    assert_digits(fit.k_mm, "3.2926648e6");
    let law = ElasticLaw::pereira_internal(e_star(), DR, L).unwrap();
    assert_digits(law.force(0.001e-3), "756.5402");
    assert_digits(law.force(0.01e-3), "12351.997");
    // Branch continuity at 0.34954 mm: both branches give Y = 1.156278.
    let below = PereiraFit::internal(e_star(), 0.34954e-3, L).unwrap().y;
    let above = PereiraFit::internal(e_star(), 0.34954e-3 * (1.0 + 1e-12), L)
        .unwrap()
        .y;
    assert_digits(below, "1.156278");
    assert_digits(above, "1.156278");
    for bad in [0.004e-3, 11e-3] {
        assert!(matches!(
            ElasticLaw::pereira_internal(e_star(), bad, L),
            Err(ContactError::OutOfValidity { .. })
        ));
    }
    // External, ΔR = R1 + R2 = 15 mm.
    let ext = PereiraFit::external(e_star(), 10e-3, 5e-3, L).unwrap();
    assert_digits(ext.k_mm, "7.6203297e5");
    assert_eq!(ext.exponent, 1.094);
    let law = ElasticLaw::pereira_external(e_star(), 10e-3, 5e-3, L).unwrap();
    assert_digits(law.force(0.001e-3), "398.0831");
    // §1.4 cross-check: Pereira δ at 1 kN = 1.2586 µm.
    let (k, n) = ElasticLaw::pereira_internal(e_star(), DR, L)
        .unwrap()
        .power_parameters()
        .unwrap();
    assert_digits((1000.0 / k).powf(1.0 / n), "1.2586e-6");
}

#[test]
fn johnson_values() {
    assert_digits(johnson_penetration(e_star(), DR, L, 1000.0), "1.2445431e-6");
    let law = ElasticLaw::johnson(e_star(), DR, L).unwrap();
    assert_digits(law.force(1e-6), "773.7539");
    assert_digits(johnson_force_limit(e_star(), DR, L), "2.9014e5");
    // The implicit solve inverts δ(F) over many decades (1e-6 relative, §7).
    for f in [1e-3, 1.0, 1e3, 1e5, 2.9e5] {
        let d = johnson_penetration(e_star(), DR, L, f);
        assert_rel(law.force(d), f, 1e-6);
    }
    let d_lim = 4.0 * DR / std::f64::consts::E.powi(2);
    assert!(law.try_force(0.99 * d_lim).is_ok());
    assert!(matches!(
        law.try_force(1.01 * d_lim),
        Err(ContactError::OutOfValidity { .. })
    ));
    assert!(law.force(1.01 * d_lim).is_finite());
}

// ---------------------------------------------------------------- area law (reconstruction)

fn guide() -> GuideFace {
    GuideFace {
        slider: steel(),
        guide: Material::new(70e9, 0.33).unwrap(),
        edge_radius: 1e-3,
        width: 20e-3,
        layer_depth: 5e-3,
    }
}

#[test]
fn area_law_tends_to_line_law_and_grows_with_length() {
    let g = guide();
    let line = NormalLaw::flores_line(&g, 0.5).unwrap();
    let area = NormalLaw::area(&g, 0.5, 0.0).unwrap();
    for d in [1e-7, 1e-6, 1e-5] {
        // l = 0: exactly the line law's elastic part.
        assert_eq!(area.elastic_force(d), line.elastic_force(d));
        // l → 0: the difference is the Winkler term (E*/h)·w·l·δ → 0.
        let e_star = g.slider.composite_modulus(&g.guide);
        for l in [1e-3, 1e-6, 1e-9] {
            let diff = area.with_contact_length(l).elastic_force(d) - line.elastic_force(d);
            assert_rel(diff, e_star / g.layer_depth * g.width * l * d, 1e-9);
        }
        let mut last = 0.0;
        for i in 0..20 {
            let f = area.with_contact_length(i as f64 * 5e-3).force(d, 0.1, 0.5);
            assert!(f > last);
            last = f;
        }
    }
    // Restitution-corrected: exact c_e whatever the contact length (frozen during the impact).
    for l in [0.0, 0.01, 0.1] {
        let law = area.with_contact_length(l);
        assert_rel(impact(&law, 0.5, 0.2, 1e-8).e_eff, 0.5, 1e-5);
    }
    assert_eq!(line.damping(), DampingFactor::Flores);
    assert_eq!(area.damping(), DampingFactor::Exact);
}

// ---------------------------------------------------------------- §7.6 friction

#[test]
fn coulomb_and_ambrosio_values() {
    let c = FrictionLaw::coulomb(0.1, 1e-4).unwrap();
    assert_digits(c.force(0.02, 1000.0), "-100");
    assert_digits(c.force(-0.02, 1000.0), "100");
    let a = FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap();
    assert_eq!(a.force(5e-5, 1000.0), 0.0);
    assert_digits(a.force(5.5e-4, 1000.0), "-50");
    assert_digits(a.force(-5.5e-4, 1000.0), "50");
    assert_digits(a.force(2e-3, 1000.0), "-100");
    // C¹ variant: equal to the ramp at v0, the midpoint and v1, with zero slope at both ends.
    let sm = FrictionLaw::ambrosio_smooth(0.1, 1e-4, 1e-3).unwrap();
    assert_eq!(sm.force(5e-5, 1000.0), 0.0);
    assert_digits(sm.force(5.5e-4, 1000.0), "-50");
    assert_digits(sm.force(2e-3, 1000.0), "-100");
    for v in [1e-4, 1e-3] {
        let h = 1e-9;
        let slope = (sm.force(v + h, 1000.0) - sm.force(v - h, 1000.0)) / (2.0 * h);
        // The linear ramp has slope μF_N/(v1 − v0) = 1.1e5 N·s/m there; the C¹ law about 0.
        assert!(slope.abs() < 1.0, "slope {slope} at {v}");
    }
    assert!(matches!(
        FrictionLaw::ambrosio(0.1, 1e-3, 1e-4),
        Err(ContactError::InvalidParameter { .. })
    ));
}

#[test]
fn threlfall_values() {
    let t = FrictionLaw::threlfall(0.1, 0.01).unwrap();
    assert_digits(t.force(0.01, 1000.0), "-95.02129");
    assert_digits(t.force(0.001, 1000.0), "-25.91818");
}

#[test]
fn stribeck_values_and_continuity() {
    let s = FrictionLaw::stribeck(0.2, 0.1, 0.01, 0.1).unwrap();
    for (v, mu) in [
        (0.0, "0"),
        (0.005, "-0.1375"),
        (-0.005, "0.1375"),
        (0.01, "-0.2"),
        (0.055, "-0.15"),
        (0.1, "-0.1"),
        (0.2, "-0.1"),
    ] {
        assert_digits(s.signed_coefficient(v), mu);
    }
    for v in [0.01, 0.1, -0.01, -0.1] {
        let below = s.signed_coefficient(v * (1.0 - 1e-12));
        let above = s.signed_coefficient(v * (1.0 + 1e-12));
        assert!(
            (below - above).abs() < 1e-9,
            "jump at {v}: {below} vs {above}"
        );
    }
    assert!(FrictionLaw::stribeck(0.2, 0.1, 0.1, 0.01).is_err());
    assert_eq!(s.mu_max(), 0.2);
}

#[test]
fn lugre_steady_state() {
    let l = LuGre::new(1e5, 0.0, 0.0, 0.2, 0.1, 0.01).unwrap();
    assert_digits(l.steady_state_coefficient(0.01), "0.13678794");
    assert_digits(l.steady_state_z(0.01), "1.3678794e-6");
    // At the steady state the bristle rate vanishes and the force is −μ_ss F_N.
    let z = l.steady_state_z(0.01);
    assert!(l.z_dot(0.01, z).abs() < 1e-15);
    assert_rel(l.force(0.01, z, 0.0, 1000.0), -136.78794, 1e-7);
    assert!(LuGre::new(0.0, 0.0, 0.0, 0.2, 0.1, 0.01).is_err());
    // μ_s = 0 would make g(0) = 0 and ż = 0/0 at rest
    assert!(LuGre::new(1e5, 0.0, 0.0, 0.0, 0.1, 0.01).is_err());
}

// ---------------------------------------------------------------- properties

fn all_laws(c_e: f64) -> Vec<NormalLaw> {
    let elastic = [
        internal_hertz(),
        ElasticLaw::liu(e_star(), DR, L).unwrap(),
        ElasticLaw::bai_zhao(e_star(), DR).unwrap(),
        ElasticLaw::pereira_internal(e_star(), DR, L).unwrap(),
        ElasticLaw::johnson(e_star(), DR, L).unwrap(),
        ElasticLaw::linear(1e8).unwrap(),
        NormalLaw::area(&guide(), 0.5, 0.02)
            .unwrap()
            .elastic()
            .to_owned(),
    ];
    let mut laws = Vec::new();
    for e in elastic {
        for d in DampingFactor::ALL {
            laws.push(NormalLaw::new(e, d, c_e).unwrap());
        }
    }
    laws
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn force_zero_without_penetration_nonnegative_finite(
        c_e in 0.01f64..=1.0,
        delta in -1e-2f64..1e-3,
        rate in -1e3f64..1e3,
        v0 in -1.0f64..10.0,
    ) {
        for law in all_laws(c_e) {
            let f = law.force(delta, rate, v0);
            prop_assert!(f.is_finite() && f >= 0.0);
            if delta <= 0.0 {
                prop_assert_eq!(f, 0.0);
            }
        }
    }

    #[test]
    fn force_finite_for_extreme_finite_inputs(
        delta in proptest::num::f64::NORMAL,
        rate in proptest::num::f64::NORMAL,
        v0 in proptest::num::f64::NORMAL,
    ) {
        for law in all_laws(0.3) {
            let f = law.force(delta, rate, v0);
            prop_assert!(f.is_finite() && f >= 0.0, "{} {delta} {rate} {v0}: {f}", law.elastic().name());
        }
    }

    #[test]
    fn friction_opposes_slip_and_is_bounded(
        v in -1.0f64..1.0,
        f_n in -10.0f64..1e4,
        mu in 0.0f64..1.0,
        v0 in 1e-6f64..1e-2,
        ratio in 1.01f64..100.0,
    ) {
        let laws = [
            FrictionLaw::coulomb(mu, v0).unwrap(),
            FrictionLaw::ambrosio(mu, v0, v0 * ratio).unwrap(),
            FrictionLaw::ambrosio_smooth(mu, v0, v0 * ratio).unwrap(),
            FrictionLaw::threlfall(mu, v0).unwrap(),
            FrictionLaw::stribeck(mu, 0.5 * mu, v0, v0 * ratio).unwrap(),
            FrictionLaw::stribeck(0.5 * mu, mu, v0, v0 * ratio).unwrap(),
        ];
        for law in laws {
            let ft = law.force(v, f_n);
            prop_assert!(ft * v <= 0.0);
            prop_assert!(ft.abs() <= law.mu_max() * f_n.max(0.0) * (1.0 + 1e-12));
        }
    }

    #[test]
    fn lugre_bristle_state_stays_bounded(
        v in -1.0f64..1.0,
        frac in 1.0f64..3.0,
        sigma0 in 1e3f64..1e7,
    ) {
        // Canudas de Wit et al. (1995), Property 1: |z| ≤ max g/σ0 is invariant, because
        // outside the band g(v)/σ0 the bristle rate points back towards it.
        let l = LuGre::new(sigma0, 300.0, 0.0, 0.2, 0.1, 0.01).unwrap();
        let z = frac * l.g(v) / sigma0 * v.signum();
        if v != 0.0 {
            prop_assert!(l.z_dot(v, z) * z <= 0.0);
        }
        // Steady state: ż = 0 and |μ_ss| ≤ μ_max.
        let zs = l.steady_state_z(v);
        prop_assert!(l.z_dot(v, zs).abs() <= 1e-12 * v.abs().max(1e-300));
        prop_assert!(l.steady_state_coefficient(v).abs() <= l.mu_max(v) * (1.0 + 1e-12));
    }

    #[test]
    fn damping_factors_satisfy_the_restitution_relation(c_e in 0.01f64..=1.0) {
        for d in DampingFactor::ALL {
            let chi = d.chi(c_e).unwrap();
            let e = d.effective_restitution(c_e).unwrap();
            prop_assert!((0.0..=1.0).contains(&e));
            // (1 + e)χ = ln(1 + χ) − ln(1 − χe), checked in a well-conditioned form per range.
            if chi < 1e-3 {
                // Series: e = 1 − 2χ/3 + O(χ²).
                prop_assert!((e - (1.0 - 2.0 * chi / 3.0)).abs() <= chi * chi);
            } else if chi <= 2.0 {
                // The residual is O(χ²) in e (series form G = residual/χ², dG/de ≈ 1).
                let residual = (1.0 + e) * chi - chi.ln_1p() + (-chi * e).ln_1p();
                prop_assert!((residual / (chi * chi)).abs() <= 1e-10, "{d:?}: {residual}");
            } else {
                // Exponential form: 1 − χe = (1 + χ)e^{−(1+e)χ}.
                let residual = (1.0 - chi * e) - (1.0 + chi) * (-(1.0 + e) * chi).exp();
                prop_assert!(residual.abs() <= 1e-13, "{d:?}: {residual}");
            }
        }
        prop_assert!((DampingFactor::Exact.effective_restitution(c_e).unwrap() - c_e).abs() < 1e-12);
    }

    #[test]
    fn restitution_independent_of_stiffness_mass_velocity(
        k in 1e6f64..1e12,
        n in 1.0f64..2.0,
        m in 0.1f64..10.0,
        v0 in 0.01f64..5.0,
        c_e in 0.2f64..0.95,
    ) {
        // §7.4: random K, n, m, v0 give the closed-form e_eff (independent RK4 integration).
        let law = NormalLaw::new(ElasticLaw::power(k, n).unwrap(), DampingFactor::HuntCrossley, c_e).unwrap();
        // Contact-time scale from the elastic peak: δ_m = ((n+1) m v0²/(2K))^{1/(n+1)}, t ~ δ_m/v0.
        let d_m = ((n + 1.0) * m * v0 * v0 / (2.0 * k)).powf(1.0 / (n + 1.0));
        let r = impact(&law, m, v0, d_m / v0 / 4000.0);
        prop_assert!((r.e_eff - law.effective_restitution()).abs() < 2e-5,
            "{} vs {}", r.e_eff, law.effective_restitution());
    }
}

// ---------------------------------------------------------------- derivatives for Jacobians

#[test]
fn stiffness_matches_central_differences() {
    // Independent check: central difference of the force, truncation error O(h²).
    let laws = [
        internal_hertz(),
        ElasticLaw::liu(e_star(), DR, L).unwrap(),
        ElasticLaw::bai_zhao(e_star(), DR).unwrap(),
        ElasticLaw::pereira_internal(e_star(), DR, L).unwrap(),
        ElasticLaw::johnson(e_star(), DR, L).unwrap(),
        ElasticLaw::linear(1e8).unwrap(),
        NormalLaw::area(&guide(), 0.5, 0.02)
            .unwrap()
            .elastic()
            .to_owned(),
    ];
    for law in laws {
        for d in [1e-8, 1e-6, 1e-5, 3e-5] {
            let h = d * 1e-5;
            let fd = (law.force(d + h) - law.force(d - h)) / (2.0 * h);
            assert_rel(law.stiffness(d), fd, 1e-7);
        }
        assert_eq!(law.stiffness(-1e-6), 0.0);
    }
    let law = NormalLaw::new(internal_hertz(), DampingFactor::Flores, 0.5).unwrap();
    let (f, dd, dv) = law.force_with_derivatives(10e-6, 0.25, 0.5);
    assert_eq!(f, law.force(10e-6, 0.25, 0.5));
    let h = 1e-10;
    let fd_d = (law.force(10e-6 + h, 0.25, 0.5) - law.force(10e-6 - h, 0.25, 0.5)) / (2.0 * h);
    let fd_v = (law.force(10e-6, 0.25 + 1e-6, 0.5) - law.force(10e-6, 0.25 - 1e-6, 0.5)) / 2e-6;
    assert_rel(dd, fd_d, 1e-7);
    assert_rel(dv, fd_v, 1e-9);
    // Clamped: F = 0 with zero derivatives.
    assert_eq!(
        law.force_with_derivatives(10e-6, -1.0, 0.5),
        (0.0, 0.0, 0.0)
    );
}

#[test]
fn friction_derivatives_match_central_differences() {
    let laws = [
        FrictionLaw::coulomb(0.1, 1e-4).unwrap(),
        FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap(),
        FrictionLaw::ambrosio_smooth(0.1, 1e-4, 1e-3).unwrap(),
        FrictionLaw::threlfall(0.1, 0.01).unwrap(),
        FrictionLaw::stribeck(0.2, 0.1, 0.01, 0.1).unwrap(),
    ];
    // Points away from the kinks, on every branch and both signs.
    for law in laws {
        for v in [3e-5f64, 4e-4, 7e-4, 3e-3, 6e-3, 0.03, 0.07, 0.3] {
            for v in [v, -v] {
                let h = v.abs() * 1e-6;
                let fd =
                    (law.signed_coefficient(v + h) - law.signed_coefficient(v - h)) / (2.0 * h);
                let d = law.coefficient_derivative(v);
                assert!(
                    (d - fd).abs() <= 1e-6 * fd.abs().max(1.0),
                    "{law:?} at {v}: {d} vs {fd}"
                );
            }
        }
    }
}
