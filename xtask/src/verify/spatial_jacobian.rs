//! `mbd.jacobian.spatial.*`: the spatial model's analytic Newton-matrix blocks
//! (`clr_mbd::spatial::SpatialLinearization`: Q_x, Q_v, b_x, b_v, (G a)_x) against central
//! differences of the same quantities (Q, b, G·a), an independent evaluation of the same
//! derivatives, at states with arbitrary velocities: every force element with the gravity and
//! gyroscopic terms of two tumbling bodies, every constraint primitive with Baumgarte terms and
//! time-dependent drivers, the spherical clearance contact in contact, sliding and in the
//! friction's regularization band, and the spatial revolute clearance joint tilted with both
//! radial regions and both thrust faces in contact (journal longer and shorter than the bore),
//! frictionless, sliding and creeping with friction. The models are
//! crates/clr-mbd/tests/data/spatial_*.toml (the first two shared with the whole-run tests of
//! crates/clr-mbd/tests/spatial_jacobian.rs).
//!
//! Positions are varied as the body-frame rotation p → p ⊗ (cos h/2, sin h/2 e) and the
//! translation r → r + h e, the coordinates of the blocks. Value: the largest difference over
//! the elements relative to each block's largest entry. Tolerance 1e-6: the central-difference
//! error (h² times the third derivative plus rounding ε|f|/h) at the steps chosen (1e-6 for
//! forces and constraints; 1e-9 and 1e-8 in the 10 µm deep Hertz contact and the 3–7 µm deep
//! journal contacts, whose curvature scale is the penetration); a wrong term shows as 1e-3 or
//! more. The journal's blocks come from iterated solves (deepest points, region ends, journal
//! ends) differentiated in dual numbers; their stopping tests (steps of 1e-10 rad, 1e-11 and
//! 1e-15 of the lengths) leave derivative errors far below the tolerance (measured 5.8e-8).

use std::time::Instant;

use clr_mbd::spatial::frame::{exp_map, quaternion_of, rotation};
use clr_mbd::spatial::{SpatialDesc, SpatialLinearization, SpatialModel};
use nalgebra::Vector3;

use super::Filter;
use crate::report::Case;

const TWO_BODIES: &str = include_str!("../../../crates/clr-mbd/tests/data/spatial_two_bodies.toml");
const SOCKET: &str = include_str!("../../../crates/clr-mbd/tests/data/spatial_socket.toml");
const JOURNAL: &str = include_str!("../../../crates/clr-mbd/tests/data/spatial_journal.toml");
/// Largest relative difference accepted (module docs).
const TOL: f64 = 1e-6;

/// The model `text` at its consistent initial state, with arbitrary velocities added (the
/// derivatives hold at any state).
fn setup(text: &str, baumgarte: Option<(f64, f64)>) -> Result<(SpatialModel, Vec<f64>), String> {
    let d = SpatialDesc::from_toml_table(text.parse().map_err(|e| format!("{e}"))?)
        .map_err(|e| e.to_string())?;
    let mut m = d.compile().map_err(|e| e.to_string())?;
    if let Some((a, b)) = baumgarte {
        m.set_baumgarte(a, b).map_err(|e| e.to_string())?;
    }
    let (mut y, _) = m.initial_state(0.0).map_err(|e| e.to_string())?;
    let (nq, nv) = (m.n_q(), m.n_v());
    for k in 0..nv {
        y[nq + k] += 0.3 * ((k as f64) * 1.7).sin() + 0.1;
    }
    Ok((m, y))
}

/// y moved by h along column `col` of x (pos) or v.
fn moved(m: &SpatialModel, y: &[f64], col: usize, h: f64, pos: bool) -> Vec<f64> {
    let mut y = y.to_vec();
    let (k, d) = (col / 6, col % 6);
    if !pos {
        y[m.n_q() + col] += h;
    } else if d < 3 {
        y[7 * k + d] += h;
    } else {
        let p = [y[7 * k + 3], y[7 * k + 4], y[7 * k + 5], y[7 * k + 6]];
        let (s, c) = (0.5 * h).sin_cos();
        let mut e = [0.0; 3];
        e[d - 3] = s;
        // p ⊗ (c, e)
        let q = [
            p[0] * c - p[1] * e[0] - p[2] * e[1] - p[3] * e[2],
            p[0] * e[0] + p[1] * c + p[2] * e[2] - p[3] * e[1],
            p[0] * e[1] - p[1] * e[2] + p[2] * c + p[3] * e[0],
            p[0] * e[2] + p[1] * e[1] - p[2] * e[0] + p[3] * c,
        ];
        y[7 * k + 3..7 * k + 7].copy_from_slice(&q);
    }
    y
}

/// The largest difference of `a` (rows × nv, row-major) from central differences of `f` along
/// x or v, relative to the block's largest entry.
fn check(
    what: &str,
    m: &mut SpatialModel,
    y: &[f64],
    a: &[f64],
    pos: bool,
    h: f64,
    f: impl Fn(&SpatialLinearization) -> Vec<f64>,
) -> Result<f64, String> {
    let nv = m.n_v();
    let rows = a.len() / nv;
    let scale = a.iter().fold(0.0f64, |s, x| s.max(x.abs()));
    let mut worst = 0.0f64;
    for col in 0..nv {
        let yp = moved(m, y, col, h, pos);
        let ym = moved(m, y, col, -h, pos);
        let fp = f(&m.linearization(0.1, &yp));
        let fm = f(&m.linearization(0.1, &ym));
        for r in 0..rows {
            let fd = (fp[r] - fm[r]) / (2.0 * h);
            worst = worst.max((fd - a[r * nv + col]).abs());
        }
    }
    if scale == 0.0 {
        return Err(format!(
            "{what}: the block is zero (the comparison could not fail)"
        ));
    }
    Ok(worst / scale)
}

/// Q_x and Q_v of each force element (with the gravity and gyroscopic terms of two tumbling
/// bodies) against central differences of Q.
fn forces() -> Result<f64, String> {
    let mut worst = 0.0f64;
    let elements = [
        r#"[[force]]
type = "spring_damper"
name = "s"
a = { body = "a", at = [0.1, 0.0, 0.05] }
b = { body = "b", at = [0.0, 0.05, 0.02] }
stiffness = 300.0
damping = 4.0
free_length = 0.2"#,
        r#"[[force]]
type = "actuator"
name = "s"
a = { body = "a", at = [0.1, 0.0, 0.05] }
b = { body = "ground", at = [0.0, 0.5, 0.02] }
force = { type = "linear", initial = 3.0, rate = 1.0 }"#,
        r#"[[force]]
type = "bushing"
name = "s"
a = { body = "a", at = [0.1, 0.0, 0.05] }
b = { body = "b", at = [0.0, 0.05, 0.02] }
stiffness = [100.0, 200.0, 300.0]
damping = [1.0, 2.0, 3.0]
rotational_stiffness = [10.0, 20.0, 30.0]
rotational_damping = [0.1, 0.2, 0.3]"#,
        r#"[[force]]
type = "force"
name = "s"
at = { body = "a", at = [0.1, 0.2, 0.05] }
frame = "body"
fx = { type = "linear", initial = 3.0, rate = 1.0 }
fy = { type = "linear", initial = -1.0, rate = 1.0 }
fz = { type = "linear", initial = 2.0, rate = 1.0 }"#,
        r#"[[force]]
type = "torque"
name = "s"
body = "b"
frame = "world"
mx = { type = "linear", initial = 3.0, rate = 1.0 }
my = { type = "linear", initial = -1.0, rate = 1.0 }
mz = { type = "linear", initial = 2.0, rate = 1.0 }"#,
        r#"[[joint]]
name = "j"
type = "cylindrical"
a = { body = "a", at = [0.1, 0.0, 0.05], axis = [0.0, 0.6, 0.8] }
b = { body = "b", at = [0.0, 0.05, 0.02] }
[[force]]
type = "rotational_spring_damper"
name = "s"
joint = "j"
stiffness = 5.0
damping = 0.3
free_angle = 0.4"#,
    ];
    for el in elements {
        let (mut m, mut y) = setup(&format!("{TWO_BODIES}{el}"), None)?;
        // move b away from the initial pose (the bushing and the rotational spring unloaded
        // there): turn it and shift it
        y = moved(&m, &y, 9, 0.4, true);
        y = moved(&m, &y, 10, -0.3, true);
        y = moved(&m, &y, 6, 0.05, true);
        let lin = m.linearization(0.1, &y);
        worst = worst.max(check(el, &mut m, &y, &lin.qx, true, 1e-6, |l| l.q.clone())?);
        worst = worst.max(check(el, &mut m, &y, &lin.qv, false, 1e-6, |l| {
            l.q.clone()
        })?);
    }
    Ok(worst)
}

/// b_x (which holds −β²Φ_x = −β²G: G is checked as the position Jacobian there), b_v and
/// (G a)_x of every constraint primitive
/// (spherical: coincidence; universal and revolute: dot-1; prismatic and cylindrical: dot-2;
/// the angle and displacement drivers with time-dependent motions), with Baumgarte terms on.
fn constraints() -> Result<f64, String> {
    let mut worst = 0.0f64;
    // the universal joint's cross: b's body y axis (world) as a's axis, b's x axis as b's
    let (ra, rb) = (
        exp_map(&(Vector3::new(1.0, 1.0, 0.0).normalize() * 0.3)),
        exp_map(&(Vector3::new(0.0, 1.0, 1.0).normalize() * -0.7)),
    );
    let ua = ra.transpose() * rb * Vector3::y();
    let universal = format!(
        "type = \"universal\"\na = {{ body = \"a\", at = [0.1, 0.0, 0.05], axis = [{}, {}, {}] }}\n\
         b = {{ body = \"b\", at = [0.0, 0.05, 0.02], axis = [1.0, 0.0, 0.0] }}",
        ua.x, ua.y, ua.z
    );
    let joints = [
        r#"type = "spherical"
a = { body = "a", at = [0.1, 0.0, 0.05] }
b = { body = "b", at = [0.0, 0.05, 0.02] }"#,
        &universal,
        r#"type = "revolute"
a = { body = "a", at = [0.1, 0.0, 0.05], axis = [0.0, 0.6, 0.8] }
b = { body = "b", at = [0.0, 0.05, 0.02] }
[[driver]]
name = "d"
type = "revolute_angle"
joint = "j"
motion = { type = "linear", initial = 0.0, rate = 2.0 }"#,
        r#"type = "prismatic"
a = { body = "ground", at = [0.1, 0.0, 0.05], axis = [0.0, 0.6, 0.8] }
b = { body = "b", at = [0.0, 0.05, 0.02] }
[[driver]]
name = "d"
type = "prismatic_displacement"
joint = "j"
motion = { type = "linear", initial = 0.0, rate = 0.5 }"#,
        r#"type = "planar"
a = { body = "a", at = [0.1, 0.0, 0.05], axis = [0.0, 0.6, 0.8] }
b = { body = "b", at = [0.0, 0.05, 0.02] }"#,
    ];
    for j in joints {
        let text = format!("{TWO_BODIES}[[joint]]\nname = \"j\"\n{j}\n");
        let (mut m, mut y) = setup(&text, Some((5.0, 7.0)))?;
        y = moved(&m, &y, 9, 0.02, true);
        let lin = m.linearization(0.1, &y);
        let acc = lin.acc.clone();
        let nv = m.n_v();
        worst = worst.max(check(j, &mut m, &y, &lin.bx, true, 1e-6, |l| l.b.clone())?);
        worst = worst.max(check(j, &mut m, &y, &lin.bv, false, 1e-6, |l| l.b.clone())?);
        let ga = |l: &SpatialLinearization| -> Vec<f64> {
            (0..l.m)
                .map(|r| (0..nv).map(|c| l.g[r * nv + c] * acc[c]).sum())
                .collect()
        };
        worst = worst.max(check(j, &mut m, &y, &lin.ga_x, true, 1e-6, ga)?);
    }
    Ok(worst)
}

/// The spherical clearance contact in contact and sliding, frictionless and with regularized
/// Coulomb friction (in its sliding branch and in its regularization band): Q_x, Q_v against
/// central differences with the impact velocity committed (held fixed, as the integrator).
fn sphere(cases: &[(&str, f64)]) -> Result<f64, String> {
    let mut worst = 0.0f64;
    for &(friction, slip) in cases {
        let (mut m, mut y) = setup(&format!("{SOCKET}{friction}"), None)?;
        // ball centre pressed 10 µm into the socket wall along a tilted direction, sliding
        // (ball velocity: approach 0.01 m/s plus a tangential slip), the arm turning
        let n = Vector3::new(0.6, 0.0, -0.8);
        let a = rotation(&y[3..7]);
        let s = a * Vector3::new(0.0, 0.0, 0.2); // ball centre from the centre of mass
        let r = n * (0.0005 + 1e-5) - s;
        let wb = Vector3::new(0.5, -0.3, 0.8);
        let v_ball = Vector3::new(0.8 * slip + 0.006, 0.0, 0.6 * slip - 0.008);
        let v = v_ball - (a * wb).cross(&s);
        let nq = m.n_q();
        y[..3].copy_from_slice(r.as_slice());
        y[nq..nq + 3].copy_from_slice(v.as_slice());
        y[nq + 3..nq + 6].copy_from_slice(wb.as_slice());
        m.commit_contact_memory(&y);
        m.commit_contact_memory(&y);
        let what = format!("sphere {friction} slip {slip}");
        worst = worst.max(contact_blocks(&what, &mut m, &y)?);
    }
    Ok(worst)
}

/// Q_x and Q_v of a model in contact against central differences of Q, with the contact
/// steps of the module docs (1e-9 in x, 1e-8 in v: the curvature scale is the penetration).
fn contact_blocks(what: &str, m: &mut SpatialModel, y: &[f64]) -> Result<f64, String> {
    let lin = m.linearization(0.1, y);
    let qx = check(what, m, y, &lin.qx, true, 1e-9, |l| l.q.clone())?;
    let qv = check(what, m, y, &lin.qv, false, 1e-8, |l| l.q.clone())?;
    Ok(qx.max(qv))
}

/// One state of the journal checks: the shaft of tests/data/spatial_journal.toml tilted in its
/// bore and shifted along it, with its journal length and axial end play.
struct JournalPose {
    /// Journal length L_j and total axial end play c_a, m.
    length: f64,
    end_play: f64,
    /// Tilt γ of the shaft about the housing's x axis, rad, and axial offset a of the journal
    /// centre along the bore axis, m.
    tilt: f64,
    axial: f64,
}

/// The two tilted poses: a journal longer than the bore (24 mm: the bore's rims press on the
/// journal surface) and a shorter one (16 mm: the journal's end edges press on the bore, the
/// wetted regions end at the moving journal ends), each tilted so that both radial regions
/// touch on opposite sides about 5 µm deep and both collars touch their thrust faces
/// (δ_t = ±a − c_a/2 + h(1 − cos γ) + R_t sin γ ≈ 5 ± 1 µm on partial arcs).
const POSES: [JournalPose; 2] = [
    JournalPose {
        length: 0.024,
        end_play: 2e-4,
        tilt: 0.0105,
        axial: 1e-6,
    },
    JournalPose {
        length: 0.016,
        end_play: 2.5e-4,
        tilt: 0.0131,
        axial: -1e-6,
    },
];

/// Relative motion of the sliding checks: spin of the shaft about its axis relative to the
/// housing (rad/s), axial sliding (m/s) and an approach velocity (m/s, along the housing's y).
type Slip = (f64, f64, f64);

/// The journal model in `pose` (friction text appended) at a state where every contact group
/// of the joint is engaged, with the housing tumbling (the arbitrary velocities of [`setup`])
/// and the shaft either tumbling too (`slip` None) or moving relative to the housing by `slip`;
/// with the four groups' penetrations (m, by clr-contact's geometry at the same pose).
fn journal_state(
    pose: &JournalPose,
    friction: &str,
    slip: Option<Slip>,
) -> Result<(SpatialModel, Vec<f64>, [f64; 4]), String> {
    let text = format!(
        "{JOURNAL}journal_length = {}\naxial_clearance = {}\n{friction}",
        pose.length, pose.end_play
    );
    let (mut m, mut y) = setup(&text, None)?;
    let ah = rotation(&y[3..7]);
    let ub = ah * Vector3::z();
    let a_s = ah * exp_map(&(Vector3::x() * pose.tilt));
    let oj = ub * pose.axial;
    y[7..10].copy_from_slice(oj.as_slice());
    y[10..14].copy_from_slice(&quaternion_of(&a_s));
    let nq = m.n_q();
    if let Some((spin, slide, approach)) = slip {
        let rh = Vector3::new(y[0], y[1], y[2]);
        let vh = Vector3::new(y[nq], y[nq + 1], y[nq + 2]);
        let wh = ah * Vector3::new(y[nq + 3], y[nq + 4], y[nq + 5]);
        let v = vh + wh.cross(&(oj - rh)) + ub * slide + ah * Vector3::y() * approach;
        let w = a_s.transpose() * (wh + a_s * Vector3::z() * spin);
        y[nq + 6..nq + 9].copy_from_slice(v.as_slice());
        y[nq + 9..nq + 12].copy_from_slice(w.as_slice());
    }
    let joint = clr_contact::JournalClearance::revolute(
        0.010,
        0.020,
        0.0099,
        pose.length,
        pose.end_play,
        None,
    )
    .map_err(|e| e.to_string())?;
    let z = Vector3::zeros();
    let state = clr_contact::JournalState::new(z, ub, z, z, oj, a_s * Vector3::z(), z, z);
    let geo = joint.geometry(&state).map_err(|e| e.to_string())?;
    let gaps = [0, 1, 2, 3].map(|g| geo.gap(g).0);
    if gaps.iter().any(|&d| d <= 0.0) {
        return Err(format!(
            "a contact group is open at the check's pose (penetrations {gaps:?} m): the check \
             would not test it"
        ));
    }
    m.commit_contact_memory(&y);
    m.commit_contact_memory(&y);
    Ok((m, y, gaps))
}

/// The journal joint's Q_x and Q_v at every pose of [`POSES`] against central differences
/// (impact velocities committed, held fixed as the integrator does); (worst, note with the
/// penetrations).
fn journal(friction: &str, slips: &[Option<Slip>]) -> Result<(f64, String), String> {
    let mut worst = 0.0f64;
    let mut depths = Vec::new();
    for pose in &POSES {
        for &slip in slips {
            let (mut m, y, gaps) = journal_state(pose, friction, slip)?;
            let what = format!("journal L_j {} m slip {slip:?}", pose.length);
            worst = worst.max(contact_blocks(&what, &mut m, &y)?);
            depths.push(format!(
                "L_j {:.0} mm: {:.1}/{:.1}/{:.1}/{:.1} µm",
                pose.length * 1e3,
                gaps[0] * 1e6,
                gaps[1] * 1e6,
                gaps[2] * 1e6,
                gaps[3] * 1e6
            ));
        }
    }
    depths.dedup();
    Ok((
        worst,
        format!("penetrations radial A/B, thrust −/+ {}", depths.join(", ")),
    ))
}

/// Regularized Coulomb friction of the contact checks.
const COULOMB: &str = "friction = { law = \"coulomb\", mu = 0.1, v_reg = 1e-3 }\n";

pub fn cases(filter: &Filter) -> Vec<Case> {
    type Check = Box<dyn Fn() -> Result<(f64, String), String>>;
    let plain =
        |f: fn() -> Result<f64, String>| -> Check { Box::new(move || Ok((f()?, String::new()))) };
    let list: [(&str, &str, Check); 6] = [
        (
            "forces",
            "spring–damper, actuator, six-axis bushing, body-frame force, world torque, rotational \
             spring–damper: Q_x, Q_v",
            plain(forces),
        ),
        (
            "constraints",
            "spherical, universal, revolute + angle driver, prismatic + displacement driver, \
             planar: b_x, b_v, (G a)_x with Baumgarte α = 5, β = 7",
            plain(constraints),
        ),
        (
            "sphere_contact",
            "spherical clearance, 10 µm deep, approaching and sliding at 0.3 m/s, frictionless: \
             Q_x, Q_v",
            plain(|| sphere(&[("", 0.3)])),
        ),
        (
            "sphere_sliding",
            "spherical clearance with regularized Coulomb friction (μ 0.1, v_reg 1 mm/s), \
             sliding at 0.3 m/s and inside the regularization band at 0.2 mm/s: Q_x, Q_v",
            plain(|| sphere(&[(COULOMB, 0.3), (COULOMB, 2e-4)])),
        ),
        (
            "revolute_clearance.tilted",
            "spatial revolute clearance joint between two tumbling bodies, frictionless, the \
             journal tilted so that both radial regions (opposite sides) and both thrust faces \
             touch, journal longer than the bore (rims on the journal) and shorter (journal \
             edges on the bore, moving region ends): Q_x, Q_v",
            Box::new(|| journal("", &[None])),
        ),
        (
            "revolute_clearance.sliding",
            "the tilted poses with regularized Coulomb friction (μ 0.1, v_reg 1 mm/s), the shaft \
             spinning in the housing at 30 rad/s (0.3 m/s at the surface) and sliding axially \
             at 0.05 m/s, and creeping inside the regularization band (spin 0.02 rad/s, slide \
             0.1 mm/s): Q_x, Q_v",
            Box::new(|| {
                journal(
                    COULOMB,
                    &[Some((30.0, 0.05, 0.002)), Some((0.02, 1e-4, 1e-4))],
                )
            }),
        ),
    ];
    let mut out = Vec::new();
    for (name, what, run) in list {
        let id = format!("mbd.jacobian.spatial.{name}");
        if !filter.wants(&id) {
            continue;
        }
        let case = Case::new(
            id,
            "largest difference of the analytic block from central differences, relative to \
             the block's largest entry",
            "-",
            "central differences of Q, b and G·a of the same model (an independent evaluation \
             of the same derivatives)",
        );
        let start = Instant::now();
        out.push(match run() {
            Ok((v, extra)) => {
                let sep = if extra.is_empty() { "" } else { "; " };
                case.at_most(v, TOL).note(format!(
                    "{what}{sep}{extra}; {:.1} s",
                    start.elapsed().as_secs_f64()
                ))
            }
            Err(e) => case.failed(TOL, e),
        });
    }
    out
}
