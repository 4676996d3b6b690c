//! Archard wear along the axis of the spatial journal joint (`clr_contact::journal_wear`)
//! against closed forms: the aligned, uniformly loaded spinning journal (the planar Archard
//! depth at every station), the tilted journal loaded at one rim (the linear law's wedge
//! p(z) = k tan γ (z − z₀)/L_c, integrated per station in closed form), and Archard's global law
//! K ∫ p |v_t| dz dt / H against an independent composite-Simpson integral of the sections.
//! Sources and tolerances at each test.

use clr_contact::journal::{JournalClearance, JournalFriction, JournalLaws, JournalState, GROUPS};
use clr_contact::journal_wear::{BearingWearMap, JournalSample, JournalWear, JournalWearError};
use clr_contact::wear::{ArchardWear, BearingProfile, LineContact};
use clr_contact::{DampingFactor, ElasticLaw, Material, NormalLaw};
use nalgebra::Vector3;

#[path = "support/journal_setup.rs"]
mod journal_setup;
use journal_setup::{state, tilted, v3, C, L, RB, RJ};

/// Typical dry steel: K = 1e-5, H = 2 GPa (as the planar wear study).
const K: f64 = 1e-5;
const H: f64 = 2e9;
/// Journal spin, rad/s, and the sliding interval, s.
const OMEGA: f64 = 100.0;
const DT: f64 = 1e-3;
const NO_IMPACT: [f64; GROUPS] = [0.0; GROUPS];

fn e_star() -> f64 {
    Material::steel().composite_modulus(&Material::steel())
}

fn elastic(law: ElasticLaw) -> JournalLaws {
    let n = NormalLaw::new(law, DampingFactor::None, 1.0).unwrap();
    JournalLaws::new(n, n, JournalFriction::None).unwrap()
}

fn hertz() -> JournalLaws {
    elastic(
        ElasticLaw::hertz_internal_cylinder(&Material::steel(), RB, &Material::steel(), RJ)
            .unwrap(),
    )
}

/// The aligned journal pressed by δ₀ (m) along +x, spinning at [`OMEGA`] about its axis.
fn aligned(delta0: f64) -> JournalState<f64> {
    state(
        v3(C + delta0, 0.0, 0.0),
        Vector3::z(),
        Vector3::zeros(),
        v3(0.0, 0.0, OMEGA),
    )
}

fn wear() -> JournalWear {
    JournalWear::new(K, H, e_star()).unwrap()
}

/// An aligned journal pressed by δ₀ along +x, spinning about its axis: the line load F_N(δ₀)/L
/// is uniform along the whole bore and the slip is ω R_j everywhere, so every station must carry
/// the planar Archard profile of F_N over ds = ω R_j dt (clr_contact::wear, docs/wear.md),
/// to rounding (1e-12 relative: the shares of the Gauss weights tile the bore exactly up to
/// rounding, and the angular spreading is the planar law's own).
#[test]
fn aligned_uniform_load_gives_the_planar_depth_at_every_station() {
    let joint = JournalClearance::cylindrical(RB, L, RJ, L).unwrap();
    let laws = hertz();
    let delta0 = 2e-6;
    let st = aligned(delta0);
    let mut map = BearingWearMap::zero(360, 12, RB, L).unwrap();
    let v = wear()
        .accumulate(&mut map, &joint, &laws, &st, &Vector3::x(), &NO_IMPACT, DT)
        .unwrap();
    let f_n = joint.geometry(&st).unwrap().forces(&laws, &NO_IMPACT);
    let f_n = f_n.groups[0].normal_force + f_n.groups[1].normal_force;
    let planar = ArchardWear::new(K, H, LineContact::new(RB, RJ, L, e_star()).unwrap()).unwrap();
    let mut profile = BearingProfile::zero(360).unwrap();
    let vp = planar
        .accumulate(&mut profile, 0.0, f_n, OMEGA * RJ * DT)
        .unwrap();
    let peak = profile.max_depth();
    assert!(peak > 0.0);
    for (m, s) in map.stations().iter().enumerate() {
        for (k, (h, hp)) in s.depths().iter().zip(profile.depths()).enumerate() {
            assert!(
                (h - hp).abs() <= 1e-12 * peak,
                "station {m}, angle {k}: {h:e} vs planar {hp:e}"
            );
        }
    }
    // Archard's global law V = K F_N s / H
    let archard = K * f_n * OMEGA * RJ * DT / H;
    for (what, got) in [("returned", v), ("map", map.worn_volume()), ("planar", vp)] {
        assert!(
            (got - archard).abs() <= 1e-12 * archard,
            "{what} volume {got:e} vs Archard {archard:e}"
        );
    }
    assert!((map.edge_concentration() - 1.0).abs() < 1e-12);
}

/// The journal tilted by γ in the x–z plane and offset along x so that it touches only towards
/// the rim z = +L/2: the section ellipse's long semi-axis R_j/cos γ lies along the offset, so
/// δ(z) = e₀ + z tan γ + R_j/cos γ − R_b exactly (the far vertex; docs/contact.md), a wedge that
/// opens at z₀; with the linear law F = kδ the line load is p(z) = k tan γ (z − z₀)/L and the
/// slip of the deepest point is ω R_j (spin about u_j, the vertex at R_j/cos γ across u_j).
/// Station m's worn area must be K ω R_j dt ∫_cell p dz /(H Δz) in closed form. Tolerances:
/// the total to 1e-9 (Gauss–Legendre is exact for the linear load after the u² substitution;
/// the root z₀ is solved to 1e-11 L); per station 3e-3 of the rim station's area (each node's
/// share carries its node's load uniformly, so a share that straddles a cell boundary misplaces
/// up to ~p′w²/8 of load, w the share's length: at order 32 and 10 stations, measured 1.8e-3);
/// the stations below z₀ exactly zero.
#[test]
fn rim_loaded_tilted_journal_wears_the_closed_form_wedge() {
    let joint = JournalClearance::cylindrical(RB, L, RJ, 1.2 * L)
        .unwrap()
        .with_quadrature_order(32)
        .unwrap();
    let k = 2e8;
    let laws = elastic(ElasticLaw::linear(k).unwrap());
    let (z0, d_max) = (0.1 * L, 5e-6);
    let tan_g = d_max / (0.5 * L - z0);
    let g = tan_g.atan();
    let e0 = RB - RJ / g.cos() - z0 * tan_g;
    let uj = tilted(g, 0.0);
    let st = state(v3(e0, 0.0, 0.0), uj, Vector3::zeros(), uj * OMEGA);
    let stations = 10;
    let mut map = BearingWearMap::zero(720, stations, RB, L).unwrap();
    let v = wear()
        .accumulate(&mut map, &joint, &laws, &st, &Vector3::x(), &NO_IMPACT, DT)
        .unwrap();
    let c = K * OMEGA * RJ * DT / H * k * tan_g / L;
    let total = c * (0.5 * L - z0).powi(2) / 2.0;
    assert!((v - total).abs() <= 1e-9 * total, "{v:e} vs {total:e}");
    assert!((map.worn_volume() - total).abs() <= 1e-9 * total);
    let dz = map.station_step();
    let rim = c * ((0.5 * L - z0).powi(2) - (0.5 * L - dz - z0).powi(2)) / 2.0 / dz;
    let mut worst = 0.0f64;
    for m in 0..stations {
        let (a, b) = (-0.5 * L + m as f64 * dz, -0.5 * L + (m + 1) as f64 * dz);
        let prim = |z: f64| (z.max(z0) - z0).powi(2) / 2.0;
        let exact = c * (prim(b) - prim(a)) / dz;
        let got = map.worn_area(m);
        if b <= z0 - 0.5 * dz {
            assert_eq!(got, 0.0, "station {m} lies in the dry part");
        }
        worst = worst.max((got - exact).abs() / rim);
    }
    assert!(
        worst < 3e-3,
        "worst station error {worst:e} of the rim area"
    );
    // the wear sits at the rim, angle 0 (the offset direction)
    assert!(map.edge_concentration() > 2.0);
    let last = map.station(stations - 1);
    let k_max = (0..last.len())
        .max_by(|&a, &b| last.depths()[a].total_cmp(&last.depths()[b]))
        .unwrap();
    assert_eq!(k_max, 0);
}

/// Archard's global law with both rims wetted on opposite sides (a crossed journal), Hertz
/// line load, spin and axial sliding: the volume the map gains, the volume returned and
/// K ∫ p |v_t| dz dt / H from an independent composite Simpson rule (4000 intervals per wetted
/// region) on the joint's public sections must agree: map and returned to 1e-12 (the φ and z
/// spreading conserve the volume exactly), against Simpson to 1e-6 (the order-10 Gauss rule on
/// the δ^{3/2} load: docs/contact.md's convergence study gives < 1e-8 on the force; Simpson's own
/// error on the (z − z₀)^{3/2} root is ~1e-7).
#[test]
fn worn_volume_is_archards_global_law() {
    let joint = JournalClearance::cylindrical(RB, L, RJ, L).unwrap();
    let laws = hertz();
    let gamma = 2.0 * (C + 3e-6) / L;
    let uj = tilted(gamma, 0.3);
    let (vj, wj) = (v3(0.0, 0.0, 0.02), uj * OMEGA + v3(0.0, 0.0, 5.0));
    let st = state(Vector3::zeros(), uj, vj, wj);
    let geo = joint.geometry(&st).unwrap();
    assert!(geo.wetted(0).is_some() && geo.wetted(1).is_some());
    let mut map = BearingWearMap::zero(360, 15, RB, L).unwrap();
    let reference = v3(1.0, 1.0, 0.3);
    let v = wear()
        .accumulate(&mut map, &joint, &laws, &st, &reference, &NO_IMPACT, DT)
        .unwrap();
    assert!((map.worn_volume() - v).abs() <= 1e-12 * v);
    let normal = hertz_force();
    let mut integral = 0.0;
    for k in 0..2 {
        let (lo, hi) = geo.wetted(k).unwrap();
        let n = 4000;
        let h = (hi - lo) / n as f64;
        for i in 0..=n {
            let z = lo + i as f64 * h;
            let s = geo.section(z);
            if s.penetration <= 0.0 {
                continue;
            }
            let (xj, nn) = (s.journal_point.value(), s.normal.value());
            // the bearing is at rest: the relative velocity is the journal point's
            let vel = vj + wj.cross(&(xj - st.journal_centre.value()));
            let slip = (vel - nn * vel.dot(&nn)).norm();
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            integral += w * h / 3.0 * normal(s.penetration, vel.dot(&nn)) / L * slip;
        }
    }
    let archard = K * integral * DT / H;
    assert!(
        (v - archard).abs() <= 1e-6 * archard,
        "{v:e} vs Simpson {archard:e}"
    );
    // the wear lies at the two rims, on opposite sides
    let (a, b) = (map.worn_area(0), map.worn_area(14));
    assert!(a > 0.0 && b > 0.0 && map.worn_area(7) == 0.0);
}

/// The radial law of [`hertz`], as a function of (δ, δ̇), N.
fn hertz_force() -> impl Fn(f64, f64) -> f64 {
    let law = NormalLaw::new(
        ElasticLaw::hertz_internal_cylinder(&Material::steel(), RB, &Material::steel(), RJ)
            .unwrap(),
        DampingFactor::None,
        1.0,
    )
    .unwrap();
    move |d, r| law.force(d, r, 0.0)
}

/// The trapezoidal rule of a history is exact for a constant state: three samples of the
/// aligned state at t = 0, 1 and 3 ms wear what one state over 3 ms wears (to rounding).
#[test]
fn history_of_a_constant_state_is_the_state_over_the_span() {
    let joint = JournalClearance::cylindrical(RB, L, RJ, L).unwrap();
    let laws = hertz();
    let st = aligned(1e-6);
    let sample = |time| JournalSample {
        time,
        state: st,
        reference: Vector3::x(),
        impact_velocities: NO_IMPACT,
    };
    let mut a = BearingWearMap::zero(90, 4, RB, L).unwrap();
    let va = wear()
        .accumulate_history(
            &mut a,
            &joint,
            &laws,
            &[sample(0.0), sample(1e-3), sample(3e-3)],
        )
        .unwrap();
    let mut b = BearingWearMap::zero(90, 4, RB, L).unwrap();
    let vb = wear()
        .accumulate(&mut b, &joint, &laws, &st, &Vector3::x(), &NO_IMPACT, 3e-3)
        .unwrap();
    assert!((va - vb).abs() <= 1e-13 * vb);
    assert!((a.max_depth() - b.max_depth()).abs() <= 1e-13 * b.max_depth());
}

#[test]
fn bad_input_is_refused_and_leaves_the_map_unchanged() {
    let joint = JournalClearance::cylindrical(RB, L, RJ, L).unwrap();
    let laws = hertz();
    let st = aligned(1e-6);
    let mut map = BearingWearMap::zero(90, 4, RB, L).unwrap();
    let w = wear();
    let e = w
        .accumulate(&mut map, &joint, &laws, &st, &Vector3::z(), &NO_IMPACT, DT)
        .unwrap_err();
    assert!(e.to_string().contains("parallel"), "{e}");
    let e = w
        .accumulate(
            &mut map,
            &joint,
            &laws,
            &st,
            &Vector3::x(),
            &NO_IMPACT,
            -1.0,
        )
        .unwrap_err();
    assert!(e.to_string().contains("dt"), "{e}");
    let mut other = BearingWearMap::zero(90, 4, RB, 2.0 * L).unwrap();
    let e = w
        .accumulate(
            &mut other,
            &joint,
            &laws,
            &st,
            &Vector3::x(),
            &NO_IMPACT,
            DT,
        )
        .unwrap_err();
    assert!(e.to_string().contains("must be made for the joint"), "{e}");
    let bad = JournalSample {
        time: 1.0,
        state: st,
        reference: Vector3::x(),
        impact_velocities: NO_IMPACT,
    };
    let e = w
        .accumulate_history(
            &mut map,
            &joint,
            &laws,
            &[bad, JournalSample { time: 0.5, ..bad }],
        )
        .unwrap_err();
    assert!(matches!(e, JournalWearError::Contact(_)), "{e}");
    assert_eq!(map.worn_volume(), 0.0);
    assert!(BearingWearMap::zero(90, 0, RB, L).is_err());
    assert!(JournalWear::new(K, 2.0, e_star()).is_err());
}

/// The map's reading: linear in z between station centres, constant in the rim half cells, 0
/// outside the bore; its volume the cell sum (a depth linear in z is read back exactly).
#[test]
fn map_reads_linear_along_the_axis() {
    let map = BearingWearMap::from_fn(16, 5, RB, L, |_, z| 1e-6 * (1.0 + z / L)).unwrap();
    let z1 = map.station_z(1);
    let z2 = map.station_z(2);
    let mid = 0.5 * (z1 + z2);
    assert!((map.depth_at(0.3, mid) - 1e-6 * (1.0 + mid / L)).abs() < 1e-18);
    assert_eq!(map.depth_at(0.3, 0.5 * L), map.station(4).depth_at(0.3));
    assert_eq!(map.depth_at(0.3, 0.6 * L), 0.0);
    // ∫∫ h R dφ dz = 2π R ∫ 1e-6 (1 + z/L) dz = 2π R L 1e-6
    let exact = std::f64::consts::TAU * RB * L * 1e-6;
    assert!((map.worn_volume() - exact).abs() < 1e-12 * exact);
}
