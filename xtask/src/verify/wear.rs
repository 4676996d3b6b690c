//! Verification cases of the wear of a revolute clearance joint (clr-contact `wear`, worn
//! bearing profile in `revolute`; docs/wear.md).
//!
//! Test rig of the Archard cases: steel journal (R_j = 9.9 mm) in a steel bearing (R_i = 10 mm,
//! E = 207 GPa, ν = 0.3, axial length L = 10 mm), K = 1e-5, H = 2 GPa. The bearing is fixed
//! (ground, angle 0); the journal centre is held at e = c + 1 µm below the bearing centre
//! (direction −y, bearing-frame contact angle φ_c = 3π/2, a knot of the N = 3600 profile) and
//! the journal spins about its centre at ω = 100 rad/s for T = 1 s, pressed by the constant
//! normal load W = 1000 N. The journal's contact point then slides over the fixed bearing at
//! |v_T| = ω R_j, so the sliding distance is s = ω R_j T = 0.99 m. The history (contact angle
//! and v_T from `RevoluteClearance::contact`, F_N = W) is recorded at 1001 times and
//! accumulated with `ArchardWear::accumulate_history`.

use std::f64::consts::{PI, TAU};

use clr_contact::body::{BodyState, Vector2};
use clr_contact::elastic::Material;
use clr_contact::revolute::{RevoluteClearance, RevoluteContact};
use clr_contact::wear::{ArchardWear, BearingProfile, LineContact, PressureDistribution};
use clr_contact::{ContactError, ForceApplication};

use super::Filter;
use crate::report::Case;

const R_I: f64 = 10e-3;
const R_J: f64 = 9.9e-3;
const C: f64 = R_I - R_J;
const LENGTH: f64 = 10e-3;
const K: f64 = 1e-5;
const HARDNESS: f64 = 2e9;
const LOAD: f64 = 1000.0;
const OMEGA: f64 = 100.0;
const T_END: f64 = 1.0;
const N: usize = 3600;

const SRC_ARCHARD: &str = "Archard, J. Appl. Phys. 24 (1953) 981: V = K W s / H";
const SRC_HERTZ: &str = "Archard + Hertz line contact (Johnson 1985 §4.3): h_max = K p0 s / H, \
                         p0 = 2W/(π a L), a = √(4WR/(πLE*)), R = R_i R_j/(R_i − R_j)";

pub fn cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    if filter.wants("wear.archard") {
        out.extend(archard_cases());
    }
    if filter.wants("wear.cycles") {
        out.push(cycles_case());
    }
    if filter.wants("wear.profile") {
        out.extend(profile_cases());
    }
    out
}

fn line_contact() -> Result<LineContact, ContactError> {
    let steel = Material::steel();
    LineContact::new(R_I, R_J, LENGTH, steel.composite_modulus(&steel))
}

/// The journal of the rig: centre at (0, −e), spinning at ω.
fn pressed_journal(e: f64) -> BodyState {
    BodyState::new(Vector2::new(0.0, -e), 0.0, Vector2::zeros(), OMEGA)
}

/// The eccentricity e along −y at which the journal penetrates the (possibly worn) bearing by
/// 1 µm (bisection on δ(e); e = c + 1 µm for the circular bearing).
fn pressed_eccentricity(joint: &RevoluteClearance) -> f64 {
    let bearing = BodyState::fixed(Vector2::zeros(), 0.0);
    let delta = |e: f64| joint.contact(&bearing, &pressed_journal(e)).penetration - 1e-6;
    let (mut lo, mut hi) = (
        0.0,
        C + 1e-6 + joint.profile().map_or(0.0, |p| p.max_depth()),
    );
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if delta(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// One simulated "cycle" of the rig on `joint`: the recorded history accumulated into a fresh
/// increment. Returns (increment, worn volume, Σ|v_T| Δt by the trapezoidal rule).
fn run_rig(
    joint: &RevoluteClearance,
    law: &ArchardWear,
) -> Result<(BearingProfile, f64, f64), ContactError> {
    let bearing = BodyState::fixed(Vector2::zeros(), 0.0);
    let e = pressed_eccentricity(joint);
    let m = 1001;
    let mut time = Vec::with_capacity(m);
    let mut angle = Vec::with_capacity(m);
    let mut force = Vec::with_capacity(m);
    let mut slip = Vec::with_capacity(m);
    for i in 0..m {
        let t = T_END * i as f64 / (m - 1) as f64;
        // the journal rotates; its centre stays where it penetrates the bearing by 1 µm
        let mut journal = pressed_journal(e);
        journal.angle = OMEGA * t;
        let c = joint.contact(&bearing, &journal);
        time.push(t);
        angle.push(c.contact_angle());
        force.push(if c.in_contact() { LOAD } else { 0.0 });
        slip.push(c.tangential_velocity);
    }
    let mut inc = BearingProfile::zero(N)?;
    let volume = law.accumulate_history(&mut inc, &time, &angle, &force, &slip)?;
    let s: f64 = (1..m)
        .map(|i| 0.5 * (slip[i].abs() + slip[i - 1].abs()) * (time[i] - time[i - 1]))
        .sum();
    Ok((inc, volume, s))
}

fn archard_cases() -> Vec<Case> {
    let setup = || -> Result<_, ContactError> {
        let contact = line_contact()?;
        let joint = RevoluteClearance::new(R_I, R_J, Vector2::zeros(), Vector2::zeros())?;
        let hertz = ArchardWear::new(K, HARDNESS, contact)?;
        let uniform = hertz.with_distribution(PressureDistribution::Uniform);
        let (inc_h, vol_h, s) = run_rig(&joint, &hertz)?;
        let (inc_u, _, _) = run_rig(&joint, &uniform)?;
        Ok((contact, inc_h, vol_h, s, inc_u))
    };
    let s_ref = OMEGA * R_J * T_END;
    match setup() {
        Ok((contact, inc_h, vol_h, s, inc_u)) => {
            let a = contact.half_width(LOAD);
            let p0 = 2.0 * LOAD / (PI * a * LENGTH);
            let depth_ref = K * p0 * s_ref / HARDNESS;
            // bin averaging: the central bin (width Δφ R_i) gets the mean of the semi-ellipse,
            // relative deficit ξ²/6 + O(ξ⁴), ξ = Δφ R_i/(2a)
            let xi = TAU / N as f64 * R_I / (2.0 * a);
            let k_c = 3 * N / 4;
            let vol_ref = K * LOAD * s_ref / HARDNESS;
            let flat_ref = K * LOAD / (2.0 * a * LENGTH) * s_ref / HARDNESS;
            vec![
                Case::new(
                    "wear.archard.sliding_distance",
                    "sliding distance ∫|v_T| dt of the recorded history",
                    "m",
                    "s = ω R_j T (journal spinning in a fixed bearing)",
                )
                .relative(s, s_ref, 1e-12),
                Case::new(
                    "wear.archard.depth",
                    "maximum wear depth, Hertz pressure",
                    "m",
                    SRC_HERTZ,
                )
                .relative(inc_h.max_depth(), depth_ref, 1e-4)
                .note(format!(
                    "a = {a:.6e} m, p0 = {p0:.6e} Pa, N = {N}; bin-averaging bound ξ²/6 = {:.2e} \
                     (ξ = Δφ R_i/(2a) = {xi:.4e}); maximum at knot {} (φ_c = 3π/2 is knot {k_c})",
                    xi * xi / 6.0,
                    argmax(inc_h.depths())
                )),
                Case::new(
                    "wear.archard.depth.uniform",
                    "wear depth at the contact centre, uniform pressure W/(2aL)",
                    "m",
                    "Archard with p = W/(2aL): h = K W s/(2 a L H)",
                )
                .relative(inc_u.depths()[k_c], flat_ref, 1e-12),
                Case::new(
                    "wear.archard.volume",
                    "worn volume L R_i Δφ Σh_k after the history",
                    "m³",
                    SRC_ARCHARD,
                )
                .relative(inc_h.worn_volume(R_I, LENGTH), vol_ref, 1e-12)
                .note(format!(
                    "returned by accumulate_history: {vol_h:.15e} m³; uniform pressure: {:.15e} \
                     m³",
                    inc_u.worn_volume(R_I, LENGTH)
                )),
            ]
        }
        Err(e) => {
            vec![Case::new("wear.archard", "rig", "-", SRC_ARCHARD).failed(0.0, e.to_string())]
        }
    }
}

fn argmax(v: &[f64]) -> usize {
    v.iter()
        .enumerate()
        .fold(
            (0, f64::NEG_INFINITY),
            |(kb, b), (k, &x)| {
                if x > b {
                    (k, x)
                } else {
                    (kb, b)
                }
            },
        )
        .0
}

/// Multi-cycle scheme (Flores 2009; Mukras et al. 2010): simulate one cycle on the current worn
/// joint (journal placed at 1 µm penetration of the worn surface), accumulate, scale by ΔN = 10,
/// update the profile, repeat five times. With the load prescribed the volume per cycle does
/// not depend on the geometry: total = 5ΔN K W s/H.
fn cycles_case() -> Case {
    let run = || -> Result<(f64, String), ContactError> {
        let law = ArchardWear::new(K, HARDNESS, line_contact()?)?;
        let mut joint = RevoluteClearance::new(R_I, R_J, Vector2::zeros(), Vector2::zeros())?
            .with_profile(BearingProfile::zero(N)?);
        let mut depths = Vec::new();
        for _ in 0..5 {
            let (inc, _, _) = run_rig(&joint, &law)?;
            if let Some(p) = joint.profile_mut() {
                p.add_scaled(&inc, 10.0)?;
                depths.push(p.max_depth());
            }
        }
        let p = joint.profile().expect("profile set above");
        Ok((
            p.worn_volume(R_I, LENGTH),
            format!(
                "max depth after each update (m): {}",
                depths
                    .iter()
                    .map(|d| format!("{d:.4e}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ))
    };
    let reference = 50.0 * K * LOAD * OMEGA * R_J * T_END / HARDNESS;
    let case = Case::new(
        "wear.cycles.volume",
        "worn volume after 5 updates of ΔN = 10 cycles",
        "m³",
        "Archard: 5ΔN K W s / H (Flores 2009, Mukras et al. 2010 update scheme)",
    );
    match run() {
        Ok((v, note)) => case.relative(v, reference, 1e-12).note(note),
        Err(e) => case.failed(reference, e.to_string()),
    }
}

/// A recorded state sequence: a rotating, translating bearing and a journal whose centre
/// orbits it with an eccentricity sweeping 0 … 1.6c (free flight and contact), spinning.
fn state_sequence(extra: f64) -> Vec<(BodyState, BodyState)> {
    let si = Vector2::new(0.02, -0.01);
    let sj = Vector2::new(-0.015, 0.005);
    (0..4000)
        .map(|k| {
            let t = k as f64 * 1e-3;
            let bearing = BodyState::new(
                Vector2::new(0.3 * t, 0.1 * (2.0 * t).sin()),
                0.7 * t + 0.2,
                Vector2::new(0.3, 0.2 * (2.0 * t).cos()),
                0.7,
            );
            let psi = 3.0 * t + 0.5 * (11.0 * t).sin();
            let ecc = (C + extra) * 0.8 * (1.0 + (1.3 * t).sin());
            let centre = bearing.point(si) + ecc * Vector2::new(psi.cos(), psi.sin());
            let th = 40.0 * t;
            let arm = clr_contact::body::rotate(th, sj);
            let journal = BodyState::new(
                centre - arm,
                th,
                Vector2::new(-0.2, 0.4 * (5.0 * t).cos()),
                40.0,
            );
            (bearing, journal)
        })
        .collect()
}

fn joint_with(
    bearing_radius: f64,
    profile: Option<BearingProfile>,
) -> Result<RevoluteClearance, ContactError> {
    let j = RevoluteClearance::new(
        bearing_radius,
        R_J,
        Vector2::new(0.02, -0.01),
        Vector2::new(-0.015, 0.005),
    )?;
    Ok(match profile {
        Some(p) => j.with_profile(p),
        None => j,
    })
}

/// Every f64 of a contact and of its generalized forces (both force applications) for the
/// force pair F_N = 1000 N, F_T = −100 N.
fn values(c: &RevoluteContact) -> Vec<f64> {
    let mut v = c.as_array().to_vec();
    for app in [
        ForceApplication::ContactPoints,
        ForceApplication::CommonPoint,
    ] {
        let f = c.generalized_forces_with(1000.0, -100.0, app);
        v.extend(f.bearing.as_array());
        v.extend(f.journal.as_array());
    }
    v
}

fn profile_cases() -> Vec<Case> {
    let mut out = Vec::new();
    let src_zero = "issue 17 item 2: zero wear reproduces the circular joint bit for bit";
    let zero = || -> Result<(u64, usize, usize), ContactError> {
        let circle = joint_with(R_I, None)?;
        let mut bits = 0u64;
        let mut compared = 0;
        let mut in_contact = 0;
        for n in [8, 360, 3600] {
            let worn = joint_with(R_I, Some(BearingProfile::zero(n)?))?;
            for (bi, bj) in state_sequence(0.0) {
                let (a, b) = (circle.contact(&bi, &bj), worn.contact(&bi, &bj));
                in_contact += usize::from(a.in_contact());
                for (x, y) in values(&a).into_iter().zip(values(&b)) {
                    bits += u64::from((x.to_bits() ^ y.to_bits()).count_ones());
                    compared += 1;
                }
            }
        }
        Ok((bits, compared, in_contact))
    };
    let case = Case::new(
        "wear.profile.zero",
        "mismatching bits, zero profile vs circular joint",
        "bits",
        src_zero,
    );
    out.push(match zero() {
        Ok((bits, compared, in_contact)) => case.absolute(bits as f64, 0.0, 0.0).note(format!(
            "{compared} values compared (3 × 4000 states, N = 8, 360, 3600; {in_contact} \
             state evaluations in contact)"
        )),
        Err(e) => case.failed(0.0, e.to_string()),
    });

    let h = 20e-6;
    let uniform = || -> Result<(f64, usize), ContactError> {
        let circle = joint_with(R_I + h, None)?;
        let worn = joint_with(R_I, Some(BearingProfile::uniform(720, h)?))?;
        let mut worst = 0.0f64;
        let mut count = 0;
        for (bi, bj) in state_sequence(h) {
            let (a, b) = (circle.contact(&bi, &bj), worn.contact(&bi, &bj));
            for (x, y) in values(&a).into_iter().zip(values(&b)) {
                if x != y {
                    worst = worst.max((x - y).abs() / x.abs().max(f64::MIN_POSITIVE));
                }
                count += 1;
            }
        }
        Ok((worst, count))
    };
    let case = Case::new(
        "wear.profile.uniform",
        "max relative difference, uniform wear h = 20 µm vs circle R_i + h",
        "-",
        "uniform wear is a circular bearing of radius R_i + h (exact geometry)",
    );
    out.push(match uniform() {
        Ok((worst, count)) => case
            .absolute(worst, 0.0, 1e-15)
            .note(format!("{count} values compared over 4000 states")),
        Err(e) => case.failed(0.0, e.to_string()),
    });
    out.extend(cos2_cases());
    out
}

/// Profile h = h0 (1 + cos 2φ), h0 = 5 µm, N = 720, on the recorded state sequence (states with
/// e > c/2 only, where the contact is near): against the closed-form normal of the polar curve,
/// an independent brute-force distance to the analytic curve, and v_N against central
/// differences of δ.
fn cos2_cases() -> Vec<Case> {
    let h0 = 5e-6;
    let shape = move |x: f64| {
        (
            R_I + h0 * (1.0 + (2.0 * x).cos()),
            -2.0 * h0 * (2.0 * x).sin(),
        )
    };
    let run = || -> Result<[f64; 3], ContactError> {
        let joint = joint_with(
            R_I,
            Some(BearingProfile::from_fn(720, |x| shape(x).0 - R_I)?),
        )?;
        let states = state_sequence(2.0 * h0);
        let (mut e_n, mut e_d, mut e_v) = (0.0f64, 0.0f64, 0.0f64);
        for k in (1..states.len() - 1).step_by(40) {
            let (bi, bj) = &states[k];
            let c = joint.contact(bi, bj);
            if c.eccentricity < 0.5 * C {
                continue;
            }
            // closed-form normal of ρ(φ) at the contact angle
            let phi = c.contact_angle();
            let (rho, drho) = shape(phi);
            let u = bi.rotate(Vector2::new(phi.cos(), phi.sin()));
            let perp_u = Vector2::new(-u.y, u.x);
            let n_ref = (rho * u - drho * perp_u).normalize();
            e_n = e_n.max((c.normal - n_ref).norm());
            // brute force: min over 2·10⁵ angles of |surface − journal centre|, golden section
            let pi = bi.point(joint.bearing_centre());
            let pj = bj.point(joint.journal_centre());
            let d =
                |x: f64| (pi + bi.rotate(shape(x).0 * Vector2::new(x.cos(), x.sin())) - pj).norm();
            let m = 200_000;
            let mut best = (0.0, f64::INFINITY);
            for i in 0..m {
                let x = TAU * i as f64 / m as f64;
                let dx = d(x);
                if dx < best.1 {
                    best = (x, dx);
                }
            }
            let (mut a, mut b) = (best.0 - TAU / m as f64, best.0 + TAU / m as f64);
            let g = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..80 {
                let (x1, x2) = (b - g * (b - a), a + g * (b - a));
                if d(x1) < d(x2) {
                    b = x2;
                } else {
                    a = x1;
                }
            }
            e_d = e_d.max((c.penetration - (R_J - d(0.5 * (a + b)))).abs());
            // v_N against the central difference of δ: both bodies advanced by ±τ in the rigid
            // motion of constant velocity and angular velocity that their states describe
            let tau = 1e-8;
            let adv = |st: &BodyState, s: f64| {
                let mut b = *st;
                b.position += s * st.velocity;
                b.angle += s * st.angular_velocity;
                b
            };
            let dp = joint.contact(&adv(bi, tau), &adv(bj, tau)).penetration;
            let dm = joint.contact(&adv(bi, -tau), &adv(bj, -tau)).penetration;
            let rate = (dp - dm) / (2.0 * tau);
            e_v = e_v.max((c.normal_velocity - rate).abs() / rate.abs().max(1e-3));
        }
        Ok([e_n, e_d, e_v])
    };
    let src = "closed form / independent formulation: ρ(φ) = R_i + h0 (1 + cos 2φ), h0 = 5 µm";
    match run() {
        Ok([e_n, e_d, e_v]) => vec![
            Case::new(
                "wear.profile.normal",
                "max |n − n_closed-form| at the contact angle (N = 720)",
                "-",
                format!("{src}; n ∝ ρ u − ρ′ k̂×u"),
            )
            .absolute(e_n, 0.0, 1e-7)
            .note("interpolation: slope error ≈ 8h0Δφ²/6 = 5e-10 m/rad, /R_i = 5e-8"),
            Case::new(
                "wear.profile.penetration",
                "max |δ − δ_brute-force| (nearest point of the analytic curve)",
                "m",
                format!("{src}; 2·10⁵ samples + golden section"),
            )
            .absolute(e_d, 0.0, 1e-12)
            .note("interpolation: depth error ≈ 1e-7 h0 = 5e-13 m"),
            Case::new(
                "wear.profile.vn_rate",
                "max relative |v_N − δ̇| (central difference, τ = 1e-8 s)",
                "-",
                "v_N = δ̇ on a worn surface (the nearest point moves tangentially)",
            )
            .absolute(e_v, 0.0, 1e-6)
            .note(
                "the difference falls with τ (2.0e-4, 3.6e-6, 1.3e-7 at τ = 1e-6, 1e-7, 1e-8 s): \
                 O(τ²) plus O(τ) where the contact crosses a knot (the C¹ profile's curvature \
                 jumps there)",
            ),
        ],
        Err(e) => {
            vec![Case::new("wear.profile.normal", "setup", "-", src).failed(0.0, e.to_string())]
        }
    }
}
