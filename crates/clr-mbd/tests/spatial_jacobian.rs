//! The spatial model's analytic Newton-matrix blocks (clr_mbd::spatial::SpatialLinearization)
//! against central differences of the same quantities (Q, b, G·a) at states with arbitrary
//! velocities, one model per element kind, and the analytic Newton matrix against the
//! finite-difference one in whole runs.
//!
//! Positions are varied as the body-frame rotation p → p ⊗ (cos h/2, sin h/2 e) and the
//! translation r → r + h e, the coordinates of the blocks. Tolerance of the comparisons: the
//! central-difference error (h² times the third derivative, plus rounding ε|f|/h) at the steps
//! chosen, 1e-6 of the block's largest entry.

use clr_mbd::spatial::frame::{exp_map, rotation};
use clr_mbd::spatial::{SpatialDesc, SpatialLinearization, SpatialModel};
use nalgebra::Vector3;

fn setup(text: &str, baumgarte: Option<(f64, f64)>) -> (SpatialModel, Vec<f64>) {
    let d = SpatialDesc::from_toml_table(text.parse().unwrap()).unwrap();
    let mut m = d.compile().unwrap();
    if let Some((a, b)) = baumgarte {
        m.set_baumgarte(a, b).unwrap();
    }
    let (mut y, _) = m.initial_state(0.0).unwrap();
    // arbitrary velocities (the derivatives hold at any state)
    let (nq, nv) = (m.n_q(), m.n_v());
    for k in 0..nv {
        y[nq + k] += 0.3 * ((k as f64) * 1.7).sin() + 0.1;
    }
    (m, y)
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

/// Compare `a` (rows × nv, row-major) with central differences of `f` along x or v.
fn check(
    what: &str,
    m: &mut SpatialModel,
    y: &[f64],
    a: &[f64],
    pos: bool,
    h: f64,
    f: impl Fn(&SpatialLinearization) -> Vec<f64>,
) {
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
    assert!(
        worst <= 1e-6 * scale.max(1e-12),
        "{what}: largest difference {worst:e}, largest entry {scale:e}"
    );
    assert!(
        scale > 0.0,
        "{what}: the block is zero (the test could not fail)"
    );
    eprintln!("{what:.40}: relative difference {:.1e}", worst / scale);
}

const TWO_BODIES: &str = r#"
[model]
space = "spatial"
gravity = [0.0, 0.0, -9.81]
[[body]]
name = "a"
mass = 2.0
principal_inertia = [0.1, 0.2, 0.3]
principal_axes = [[0.8, 0.6, 0.0], [-0.6, 0.8, 0.0], [0.0, 0.0, 1.0]]
centre_of_mass = [0.05, -0.02, 0.1]
position = [0.0, 0.0, 0.0]
orientation = { axis = [1.0, 1.0, 0.0], angle = 0.3 }
[[body]]
name = "b"
mass = 1.0
principal_inertia = [0.02, 0.03, 0.04]
position = [0.3, 0.1, -0.2]
orientation = { axis = [0.0, 1.0, 1.0], angle = -0.7 }
"#;

/// Q_x and Q_v of each force element (with the gravity and gyroscopic terms of two tumbling
/// bodies) against central differences of Q.
#[test]
fn force_elements_match_central_differences() {
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
        let (mut m, mut y) = setup(&format!("{TWO_BODIES}{el}"), None);
        // move b away from the initial pose (the bushing and the rotational spring unloaded
        // there): turn it and shift it
        y = moved(&m, &y, 9, 0.4, true);
        y = moved(&m, &y, 10, -0.3, true);
        y = moved(&m, &y, 6, 0.05, true);
        let lin = m.linearization(0.1, &y);
        check(el, &mut m, &y, &lin.qx, true, 1e-6, |l| l.q.clone());
        check(el, &mut m, &y, &lin.qv, false, 1e-6, |l| l.q.clone());
    }
}

/// b_x (which holds −β²Φ_x = −β²G: G is checked as the position Jacobian there), b_v and
/// (G a)_x of every constraint primitive
/// (spherical: coincidence; universal and revolute: dot-1; prismatic and cylindrical: dot-2;
/// the angle and displacement drivers with time-dependent motions), with Baumgarte terms on.
#[test]
fn constraint_rows_match_central_differences() {
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
        let (mut m, mut y) = setup(&text, Some((5.0, 7.0)));
        y = moved(&m, &y, 9, 0.02, true);
        let lin = m.linearization(0.1, &y);
        let acc = lin.acc.clone();
        let nv = m.n_v();
        check(j, &mut m, &y, &lin.bx, true, 1e-6, |l| l.b.clone());
        check(j, &mut m, &y, &lin.bv, false, 1e-6, |l| l.b.clone());
        check(j, &mut m, &y, &lin.ga_x, true, 1e-6, |l| {
            (0..l.m)
                .map(|r| (0..nv).map(|c| l.g[r * nv + c] * acc[c]).sum())
                .collect()
        });
    }
}

const SOCKET: &str = r#"
[model]
space = "spatial"
gravity = [0.0, 0.0, -9.81]
[[body]]
name = "arm"
mass = 1.0
principal_inertia = [0.01, 0.012, 0.004]
centre_of_mass = [0.0, 0.0, -0.2]
position = [0.0, 0.0, 0.0]
orientation = { axis = [1.0, 0.2, 0.0], angle = 0.4 }
[[clearance]]
name = "S"
type = "spherical"
socket = { body = "ground", at = [0.0, 0.0, 0.0] }
ball = { body = "arm", at = [0.0, 0.0, 0.0] }
socket_radius = 0.010
ball_radius = 0.0095
normal = { law = "hertz-internal-sphere", damping = "lankarani-nikravesh", restitution = 0.5, bearing_material = { youngs_modulus = 207e9, poisson_ratio = 0.3 }, journal_material = { youngs_modulus = 207e9, poisson_ratio = 0.3 } }
"#;

/// The spherical clearance contact in contact and sliding, frictionless and with regularized
/// Coulomb friction (in its sliding branch and in its regularization band): Q_x, Q_v against
/// central differences with the impact velocity committed (held fixed, as the integrator).
#[test]
fn sphere_contact_matches_central_differences() {
    for (friction, slip) in [
        ("", 0.3),
        (
            "friction = { law = \"coulomb\", mu = 0.1, v_reg = 1e-3 }\n",
            0.3,
        ),
        (
            "friction = { law = \"coulomb\", mu = 0.1, v_reg = 1e-3 }\n",
            2e-4,
        ),
    ] {
        let (mut m, mut y) = setup(&format!("{SOCKET}{friction}"), None);
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
        let lin = m.linearization(0.1, &y);
        let what = format!("sphere {friction} slip {slip}");
        check(&what, &mut m, &y, &lin.qx, true, 1e-9, |l| l.q.clone());
        check(&what, &mut m, &y, &lin.qv, false, 1e-8, |l| l.q.clone());
    }
}

/// Run `text` with the analytic and the finite-difference Newton matrix: the same results
/// within the integration tolerance (both converge Newton to the same corrector tolerance;
/// the difference is bounded by the local error control, `factor`·rtol of the state's scale),
/// and fewer right-hand-side evaluations with the analytic matrix (no 13n_b + 3 evaluations
/// per Jacobian). Returns the (analytic, finite-difference) statistics.
fn same_run(text: &str, factor: f64) -> (clr_ode::Stats, clr_ode::Stats) {
    let d = SpatialDesc::from_toml_table(text.parse().unwrap()).unwrap();
    let mut o = d.sim_options().unwrap();
    let mut run = |mode| {
        o.jacobian = mode;
        d.compile().unwrap().simulate(&o).unwrap()
    };
    let a = run(clr_mbd::JacobianMode::Analytic);
    let f = run(clr_mbd::JacobianMode::FiniteDifference);
    assert!(
        !a.notes.iter().any(|n| n.contains("finite diff")),
        "{:?}",
        a.notes
    );
    let (ya, yf) = (&a.y_final, &f.y_final);
    let scale = yf.iter().fold(1.0f64, |s, x| s.max(x.abs()));
    let diff = ya
        .iter()
        .zip(yf)
        .fold(0.0f64, |s, (x, y)| s.max((x - y).abs()));
    eprintln!(
        "analytic {:?}\nfinite difference {:?}\nlargest difference of the final states {diff:.2e}",
        a.stats, f.stats
    );
    assert!(
        diff < factor * o.rtol * scale,
        "final states differ by {diff:e}"
    );
    assert!(a.stats.f_evals < f.stats.f_evals);
    (a.stats, f.stats)
}

/// The heavy top (models/examples/heavy_top.toml: one body, a spherical joint, spin 120 rad/s).
#[test]
fn heavy_top_analytic_newton_matrix_matches_finite_differences() {
    same_run(
        include_str!("../../../models/examples/heavy_top.toml"),
        100.0,
    );
}

/// A pendulum hanging in a spherical clearance joint with friction, released swinging: up to
/// the end of its second impact (onset, sliding contact, separation), at rtol 1e-9. Later, the
/// two runs' different local errors are amplified impact by impact (at 0.2 s, 9 against 10
/// onsets); the contact blocks themselves are checked against central differences above.
#[test]
fn clearance_pendulum_analytic_newton_matrix_matches_finite_differences() {
    let text = |t_end: f64| {
        format!(
            "{SOCKET}friction = {{ law = \"coulomb\", mu = 0.1, v_reg = 1e-3 }}\n\
             [solver]\nrtol = 1e-9\n[output]\nt_end = {t_end}\nintervals = 20\n"
        )
    };
    let d = SpatialDesc::from_toml_table(text(0.2).parse().unwrap()).unwrap();
    let r = d
        .compile()
        .unwrap()
        .simulate(&d.sim_options().unwrap())
        .unwrap();
    assert!(
        r.impacts.len() >= 2,
        "the pendulum must hit its socket twice"
    );
    let end = r.impacts[1].separation.expect("second impact ends");
    // through impacts the two runs' local errors are amplified (measured: 2.0e-3 at rtol 1e-6,
    // 2.5e-7 at rtol 1e-9, so both converge to one solution): 1e4·rtol at rtol 1e-9
    same_run(&text(end + 1e-3), 1e4);
}

/// The reduced solve (spatial::newton) against the dense first-order matrix I − cJ of central
/// differences of the whole right-hand side (J on y = (q, v, E_d, W_in), the quaternion rows
/// included): the backward error max|(I − cJ)Δy − r|/max|r| over the rows of q and v, for
/// c = 1e-6 … 1e-3 s (the E_d, W_in rows are passive and left out; the quaternion norm term's
/// derivative, which the Newton matrix leaves out, is taken out of the reference). The reduction is exact
/// up to the difference quotients' error (about 1e-9 here), so the bound is 1e-7: measured
/// 1.6e-12 … 1.7e-9 on the heavy top.
#[test]
fn reduced_solve_inverts_the_first_order_newton_matrix() {
    use clr_ode::OdeSystem;
    let top = include_str!("../../../models/examples/heavy_top.toml");
    let rev = format!(
        "{TWO_BODIES}[[joint]]\nname = \"j\"\ntype = \"revolute\"\n\
         a = {{ body = \"ground\", at = [0.0, 0.0, 0.0], axis = [0.0, 0.6, 0.8] }}\n\
         b = {{ body = \"a\", at = [0.0, 0.05, 0.02] }}\n\
         [[force]]\ntype = \"spring_damper\"\nname = \"s\"\n\
         a = {{ body = \"a\", at = [0.1, 0.0, 0.05] }}\nb = {{ body = \"b\", at = [0.0, 0.05, 0.02] }}\n\
         stiffness = 300.0\ndamping = 4.0\nfree_length = 0.2\n"
    );
    for text in [top, rev.as_str()] {
        let (mut m, y) = setup(text, Some((5.0, 7.0)));
        let n = m.dim();
        let t = 0.1;
        let mut jac = vec![0.0; n * n];
        let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
        for c in 0..n {
            let h = 1e-7 * y[c].abs().max(1.0);
            let (mut yp, mut ym) = (y.clone(), y.clone());
            yp[c] += h;
            ym[c] -= h;
            m.rhs(t, &yp, &mut fp);
            m.rhs(t, &ym, &mut fm);
            for r in 0..n {
                jac[r * n + c] = (fp[r] - fm[r]) / (2.0 * h);
            }
        }
        // the Newton matrix leaves out the derivative of the quaternion norm term k(1 − ‖p‖²)p
        // (k = spatial::model::NORM_RATE = 10 1/s): its backward error would be 2ck, which
        // simplified Newton absorbs; take it out of the reference to test the rest exactly
        let k_norm = 10.0;
        for b in 0..m.n_bodies() {
            let o = 7 * b + 3;
            let p = &y[o..o + 4];
            let n2: f64 = p.iter().map(|x| x * x).sum();
            for i in 0..4 {
                for j in 0..4 {
                    let d = if i == j { 1.0 - n2 } else { 0.0 } - 2.0 * p[i] * p[j];
                    jac[(o + i) * n + o + j] -= k_norm * d;
                }
            }
        }
        assert!(m.newton_jacobian(t, &y));
        for c in [1e-6, 1e-5, 1e-4, 1e-3] {
            assert!(m.newton_factor(c));
            let r: Vec<f64> = (0..n).map(|k| ((k as f64) * 0.37).sin()).collect();
            let mut dy = r.clone();
            m.newton_solve(&mut dy);
            let mut worst = 0.0f64;
            // the rows of (q, v); E_d and W_in are passive (ΔE = r_E, ΔW = r_W)
            for i in 0..m.n_q() + m.n_v() {
                let mut acc = dy[i];
                for k in 0..n {
                    acc -= c * jac[i * n + k] * dy[k];
                }
                worst = worst.max((acc - r[i]).abs());
            }
            let rn = r.iter().fold(0.0f64, |s, x| s.max(x.abs()));
            eprintln!("c = {c:e}: backward error {:.1e}", worst / rn);
            assert!(
                worst / rn < 1e-7,
                "c = {c:e}: backward error {:e}",
                worst / rn
            );
        }
    }
}
