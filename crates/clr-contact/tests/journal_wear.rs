//! Archard wear along the axis of the spatial journal joint (`clr_contact::journal_wear`)
//! against closed forms: the aligned, uniformly loaded spinning journal (the planar Archard
//! depth at every station), the tilted journal loaded at one rim (the linear law's wedge
//! p(z) = k tan γ (z − z₀)/L_c, integrated per station in closed form), and Archard's global law
//! K ∫ p |v_t| dz dt / H against an independent composite-Simpson integral of the sections.
//! Sources and tolerances at each test.

use clr_contact::journal::{JournalClearance, JournalLaws};
use clr_contact::journal_wear::{BearingWearMap, JournalSample, JournalWear, JournalWearError};
use nalgebra::Vector3;

#[path = "support/journal_setup.rs"]
mod journal_setup;
use journal_setup::{L, RB, RJ};
#[path = "support/journal_wear_forms.rs"]
mod journal_wear_forms;
use journal_wear_forms::{aligned_state as aligned, e_star, elastic, hertz_law, DT, K, NO_IMPACT};

fn hertz() -> JournalLaws {
    elastic(hertz_law().unwrap()).unwrap()
}

fn wear() -> JournalWear {
    journal_wear_forms::wear().unwrap()
}

/// An aligned journal pressed by δ₀ along +x, spinning about its axis: the line load F_N(δ₀)/L
/// is uniform along the whole bore and the slip is ω R_j everywhere, so every station must carry
/// the planar Archard profile of F_N over ds = ω R_j dt (clr_contact::wear, docs/wear.md),
/// to rounding (1e-12 relative: the shares of the Gauss weights tile the bore exactly up to
/// rounding, and the angular spreading is the planar law's own).
#[test]
fn aligned_uniform_load_gives_the_planar_depth_at_every_station() {
    let r = journal_wear_forms::aligned_uniform().unwrap();
    assert!(r.planar.max_depth() > 0.0);
    let worst = r.worst_station_error();
    assert!(
        worst <= 1e-12,
        "largest station error {worst:e} of the planar peak"
    );
    // Archard's global law V = K F_N s / H
    for (what, got) in [
        ("returned", r.volume),
        ("map", r.map.worn_volume()),
        ("planar", r.planar_volume),
    ] {
        assert!(
            (got - r.archard).abs() <= 1e-12 * r.archard,
            "{what} volume {got:e} vs Archard {:e}",
            r.archard
        );
    }
    assert!((r.map.edge_concentration() - 1.0).abs() < 1e-12);
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
    let r = journal_wear_forms::rim_wedge().unwrap();
    let (v, total) = (r.volume, r.total);
    assert!((v - total).abs() <= 1e-9 * total, "{v:e} vs {total:e}");
    assert!((r.map.worn_volume() - total).abs() <= 1e-9 * total);
    let dz = r.map.station_step();
    for m in 0..r.areas.len() {
        if -0.5 * L + (m + 1) as f64 * dz <= r.z0 - 0.5 * dz {
            assert_eq!(r.map.worn_area(m), 0.0, "station {m} lies in the dry part");
        }
    }
    let worst = r.worst_station_error();
    assert!(
        worst < 3e-3,
        "worst station error {worst:e} of the rim area"
    );
    // the wear sits at the rim, angle 0 (the offset direction)
    assert!(r.map.edge_concentration() > 2.0);
    let last = r.map.station(r.areas.len() - 1);
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
    let r = journal_wear_forms::global_law().unwrap();
    let (v, archard) = (r.volume, r.simpson);
    assert!((r.map.worn_volume() - v).abs() <= 1e-12 * v);
    assert!(
        (v - archard).abs() <= 1e-6 * archard,
        "{v:e} vs Simpson {archard:e}"
    );
    // the wear lies at the two rims, on opposite sides
    let (a, b) = (r.map.worn_area(0), r.map.worn_area(14));
    assert!(a > 0.0 && b > 0.0 && r.map.worn_area(7) == 0.0);
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
