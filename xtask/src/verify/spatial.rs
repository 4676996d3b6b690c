//! Verification cases of the spatial engine (issue 31; docs/verification.md "Spatial engine"):
//! rigid-body motions with closed forms (torque-free body, heavy top, conical pendulum; the
//! references are in [`super::spatial_ref`]), the spherical clearance joint's geometry and
//! static load against closed forms, and two reductions to the planar engine (a clearance
//! pendulum and the clearance slider–crank written as spatial models moving in the x–y plane).

use clr_mbd::spatial::SpatialDesc;
use clr_mbd::{Results, SimOptions, SolverKind};

use super::spatial_ref::{conical_pendulum_rate, HeavyTop, TopState, TorqueFreeBody};
use super::Filter;
use crate::report::Case;

type Mat3 = [[f64; 3]; 3];

fn col(res: &Results, name: &str) -> Vec<f64> {
    res.column(name).unwrap_or_default()
}

/// Compile a spatial model file's text and run it with `opts`.
fn run_spatial(text: &str, opts: &SimOptions) -> Result<Results, String> {
    let table: toml::Table = text.parse().map_err(|e| format!("model text: {e}"))?;
    let desc = SpatialDesc::from_toml_table(table).map_err(|e| e.to_string())?;
    let mut m = desc.compile().map_err(|e| e.to_string())?;
    m.simulate(opts).map_err(|e| e.to_string())
}

/// DOPRI5 over [0, t_end] with `n` output intervals at rtol (atol = rtol · 1e-3).
fn dopri(t_end: f64, n: usize, rtol: f64) -> SimOptions {
    SimOptions::span(0.0, t_end, n)
        .tolerances(rtol, rtol * 1e-3)
        .solver(SolverKind::Dopri5)
}

/// Rotation matrix body → world of the (normalized) quaternion (w, x, y, z) (Haug,
/// *Computer-Aided Kinematics and Dynamics of Mechanical Systems*, eq. 6.3.26).
fn rotation(p: [f64; 4]) -> Mat3 {
    let n = p.iter().map(|v| v * v).sum::<f64>().sqrt();
    let [w, x, y, z] = p.map(|v| v / n);
    [
        [
            w * w + x * x - y * y - z * z,
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            w * w - x * x + y * y - z * z,
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            w * w - x * x - y * y + z * z,
        ],
    ]
}

fn mul(a: &Mat3, v: [f64; 3]) -> [f64; 3] {
    a.map(|r| r[0] * v[0] + r[1] * v[1] + r[2] * v[2])
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The columns `B.<c>x`, `B.<c>y`, `B.<c>z` of a body, row by row.
fn vec_col(res: &Results, body: &str, c: &str) -> Vec<[f64; 3]> {
    let (x, y, z) = (
        col(res, &format!("{body}.{c}x")),
        col(res, &format!("{body}.{c}y")),
        col(res, &format!("{body}.{c}z")),
    );
    (0..x.len()).map(|k| [x[k], y[k], z[k]]).collect()
}

/// Body → world rotation of a body, row by row.
fn rotations(res: &Results, body: &str) -> Vec<Mat3> {
    let q: Vec<Vec<f64>> = ["qw", "qx", "qy", "qz"]
        .iter()
        .map(|c| col(res, &format!("{body}.{c}")))
        .collect();
    (0..q[0].len())
        .map(|k| rotation([q[0][k], q[1][k], q[2][k], q[3][k]]))
        .collect()
}

fn max_abs(v: impl IntoIterator<Item = f64>) -> f64 {
    v.into_iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

/// The turning points of a sampled signal: (t, value) of each interior local extremum refined by
/// the vertex of the parabola through the three samples around it; `maxima` selects maxima.
fn extrema(t: &[f64], v: &[f64], maxima: bool) -> Vec<(f64, f64)> {
    let s = if maxima { 1.0 } else { -1.0 };
    (1..v.len().saturating_sub(1))
        .filter(|&k| s * v[k] > s * v[k - 1] && s * v[k] >= s * v[k + 1])
        .map(|k| {
            let (a, b, c) = (v[k - 1], v[k], v[k + 1]);
            let h = t[k + 1] - t[k];
            let den = a - 2.0 * b + c;
            let x = 0.5 * (a - c) / den; // vertex offset in steps
            (t[k] + x * h, b - 0.25 * (a - c) * x)
        })
        .collect()
}

/// Downward zero crossings and upward ones of a sampled signal with its derivative, located on
/// the cubic Hermite interpolant between samples (error O(h⁴)) by bisection.
fn zero_crossings(t: &[f64], f: &[f64], d: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    for k in 0..f.len().saturating_sub(1) {
        if f[k] == 0.0 || f[k].signum() == f[k + 1].signum() {
            continue;
        }
        let h = t[k + 1] - t[k];
        let herm = |s: f64| {
            let (s2, s3) = (s * s, s * s * s);
            (2.0 * s3 - 3.0 * s2 + 1.0) * f[k]
                + (s3 - 2.0 * s2 + s) * h * d[k]
                + (-2.0 * s3 + 3.0 * s2) * f[k + 1]
                + (s3 - s2) * h * d[k + 1]
        };
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if herm(mid).signum() == f[k].signum() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        out.push(t[k] + 0.5 * (lo + hi) * h);
    }
    out
}

// ---------------------------------------------------------------------------------------------
// mbd.spatial.torque_free
// ---------------------------------------------------------------------------------------------

/// Principal moments (kg·m²) of the free body.
const TF_INERTIA: [f64; 3] = [0.1, 0.2, 0.3];
/// Its principal axes as rows in the body frame: the rotation of the quaternion (2, 1, 2, 4)/5,
/// exact in decimals, so no axis lies along a body axis.
const TF_AXES: Mat3 = [[-0.6, -0.48, 0.64], [0.8, -0.36, 0.48], [0.0, 0.8, 0.6]];
/// Initial ω along the principal axes, rad/s: close to the intermediate axis (flips).
const TF_OMEGA: [f64; 3] = [0.3, 3.0, 0.36];
const TF_T_END: f64 = 20.0;

fn torque_free_text() -> String {
    let w = (0..3).fold([0.0; 3], |acc, k| {
        [0, 1, 2].map(|i| acc[i] + TF_OMEGA[k] * TF_AXES[k][i])
    });
    format!(
        r#"
[model]
space = "spatial"
[[body]]
name = "b"
mass = 2.0
principal_inertia = {i:?}
principal_axes = {p:?}
centre_of_mass = [0.05, -0.02, 0.1]
position = [0.3, 0.1, -0.2]
orientation = {{ axis = [1.0, 2.0, -0.5], angle = 0.7 }}
velocity = [0.1, -0.05, 0.2]
velocity_frame = "world"
angular_velocity = {w:?}
angular_velocity_frame = "body"
"#,
        i = TF_INERTIA,
        p = TF_AXES,
    )
}

/// Body-frame vectors to principal components.
fn principal(v: [f64; 3]) -> [f64; 3] {
    mul(&TF_AXES, v)
}

/// World angular momentum about the centre of mass: A Pᵀ diag(I) P ω (J built here from the
/// model's own data, independently of the engine's).
fn momentum(a: &Mat3, w_body: [f64; 3]) -> [f64; 3] {
    let wp = principal(w_body);
    let lp = [0, 1, 2].map(|k| TF_INERTIA[k] * wp[k]);
    let l_body = [0, 1, 2].map(|i| (0..3).map(|k| TF_AXES[k][i] * lp[k]).sum());
    mul(a, l_body)
}

fn torque_free_cases(out: &mut Vec<Case>) {
    let ids = [
        "mbd.spatial.torque_free.period",
        "mbd.spatial.torque_free.omega",
        "mbd.spatial.torque_free.energy",
        "mbd.spatial.torque_free.momentum",
    ];
    let src = "Euler's equations of a torque-free body in closed form: ω along the principal \
               axes in Jacobi elliptic functions, period 4K(m)/|λ| (Landau & Lifshitz, \
               Mechanics §37; spatial_ref.rs); E and L conserved exactly";
    let reference = match TorqueFreeBody::new(TF_INERTIA, TF_OMEGA) {
        Ok(r) => r,
        Err(e) => {
            for id in ids {
                out.push(Case::new(id, "torque-free body", "-", src).failed(0.0, e.to_string()));
            }
            return;
        }
    };
    let res = match run_spatial(&torque_free_text(), &dopri(TF_T_END, 20_000, 1e-10)) {
        Ok(r) => r,
        Err(e) => {
            for id in ids {
                let c = Case::new(id, "torque-free body", "-", src);
                out.push(c.failed(reference.period(), e.clone()));
            }
            return;
        }
    };
    let t = col(&res, "t");
    let w: Vec<[f64; 3]> = vec_col(&res, "b", "w").into_iter().map(principal).collect();
    let al: Vec<[f64; 3]> = vec_col(&res, "b", "alpha")
        .into_iter()
        .map(principal)
        .collect();
    // The intermediate component (index 1) reverses every T/2; its crossings give the period.
    let b = reference.axes()[1];
    let (wb, ab): (Vec<f64>, Vec<f64>) = w.iter().zip(&al).map(|(w, a)| (w[b], a[b])).unzip();
    let z = zero_crossings(&t, &wb, &ab);
    let period = if z.len() >= 2 {
        2.0 * (z[z.len() - 1] - z[0]) / (z.len() - 1) as f64
    } else {
        f64::NAN
    };
    let scale = norm(TF_OMEGA);
    let werr = max_abs(t.iter().zip(&w).map(|(&ti, wi)| {
        let r = reference.omega(ti);
        norm(sub(*wi, r)) / scale
    }));
    let e = col(&res, "energy.kinetic");
    let de = max_abs(e.iter().map(|v| (v - e[0]) / e[0]));
    let rot = rotations(&res, "b");
    let l: Vec<[f64; 3]> = rot
        .iter()
        .zip(vec_col(&res, "b", "w"))
        .map(|(a, wb)| momentum(a, wb))
        .collect();
    let dl = max_abs(l.iter().map(|li| norm(sub(*li, l[0])) / norm(l[0])));
    let stats = format!(
        "DOPRI5 rtol 1e-10 over {TF_T_END} s, {} steps; I = {TF_INERTIA:?} along rotated axes, \
         ω₀ = {TF_OMEGA:?} (principal), m = {:.15}",
        res.stats.accepted,
        reference.parameter()
    );
    out.push(
        Case::new(
            ids[0],
            "flip period from the intermediate ω component's zero crossings (Hermite-located)",
            "s",
            format!("{src}; tolerance 1e-8 relative"),
        )
        .relative(period, reference.period(), 1e-8)
        .note(format!(
            "{} crossings at {:?} s; closed form T = {:.12} s; {stats}",
            z.len(),
            z.iter()
                .map(|v| (v * 1e6).round() / 1e6)
                .collect::<Vec<_>>(),
            reference.period()
        )),
    );
    out.push(
        Case::new(
            ids[1],
            "max |ω(t) − ω_ref(t)| / |ω₀| at 20001 outputs (principal axes)",
            "-",
            format!("{src}; tolerance 1e-7 (near-separatrix phase sensitivity)"),
        )
        .at_most(werr, 1e-7)
        .note(stats.clone()),
    );
    out.push(
        Case::new(
            ids[2],
            "max |E(t) − E(0)| / E(0)",
            "-",
            format!("{src}; tolerance 1e-9 relative at rtol 1e-10"),
        )
        .at_most(de, 1e-9)
        .note(stats.clone()),
    );
    out.push(
        Case::new(
            ids[3],
            "max |L(t) − L(0)| / |L(0)|, L = A J ω about the centre of mass (world)",
            "-",
            format!("{src}; tolerance 1e-9 relative at rtol 1e-10"),
        )
        .at_most(dl, 1e-9)
        .note(stats),
    );
}

// ---------------------------------------------------------------------------------------------
// mbd.spatial.heavy_top
// ---------------------------------------------------------------------------------------------

/// The top: mass (kg), pivot–centre-of-mass distance l (m), I1 about the pivot and I3 (kg·m²).
const TOP: (f64, f64, f64, f64) = (1.0, 0.5, 0.5, 0.2);
const G: f64 = 9.81;

/// A symmetric top on a spherical joint at its tip (the body origin), its axis (body z) tilted
/// by θ about world x, with body angular velocity `w`.
fn top_text(theta: f64, w: [f64; 3]) -> String {
    let (m, l, i1, i3) = TOP;
    pivoted_text("top", (m, l, i1, i3), theta, (w, "body"))
}

/// A symmetric body (mass m, centre of mass at l on body z, I1 about the pivot and I3) on a
/// spherical joint at the body origin, tilted by `angle` about world x, with angular velocity
/// `w` in frame `w_frame` (`world` or `body`).
fn pivoted_text(
    name: &str,
    (m, l, i1, i3): (f64, f64, f64, f64),
    angle: f64,
    (w, w_frame): ([f64; 3], &str),
) -> String {
    let it = i1 - m * l * l;
    format!(
        r#"
[model]
space = "spatial"
gravity = [0.0, 0.0, -{G}]
[[body]]
name = "{name}"
mass = {m}
principal_inertia = [{it}, {it}, {i3}]
centre_of_mass = [0.0, 0.0, {l}]
position = [0.0, 0.0, 0.0]
orientation = {{ axis = [1.0, 0.0, 0.0], angle = {angle} }}
velocity = [0.0, 0.0, 0.0]
velocity_frame = "world"
angular_velocity = {w:?}
angular_velocity_frame = "{w_frame}"
[[joint]]
name = "pivot"
type = "spherical"
a = {{ body = "ground", at = [0.0, 0.0, 0.0] }}
b = {{ body = "{name}", at = [0.0, 0.0, 0.0] }}
"#
    )
}

/// θ(t), the angle of the body z axis from the upward vertical: cos θ = A₃₃.
fn nutation_angle(res: &Results, body: &str) -> Vec<f64> {
    rotations(res, body)
        .iter()
        .map(|a| a[2][2].clamp(-1.0, 1.0).acos())
        .collect()
}

/// Unwrapped azimuth of a sequence of horizontal directions (x, y), rad.
fn unwrapped_azimuth(xy: impl Iterator<Item = (f64, f64)>) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    for (x, y) in xy {
        let a = y.atan2(x);
        let v = match out.last() {
            Some(&prev) => {
                let tau = std::f64::consts::TAU;
                a + tau * ((prev - a) / tau).round()
            }
            None => a,
        };
        out.push(v);
    }
    out
}

/// Least-squares slope of v(t), rad/s.
fn slope(t: &[f64], v: &[f64]) -> f64 {
    let n = t.len() as f64;
    let (tm, vm) = (t.iter().sum::<f64>() / n, v.iter().sum::<f64>() / n);
    let num: f64 = t.iter().zip(v).map(|(a, b)| (a - tm) * (b - vm)).sum();
    let den: f64 = t.iter().map(|a| (a - tm) * (a - tm)).sum();
    num / den
}

fn heavy_top_cases(out: &mut Vec<Case>) {
    let src = "heavy symmetric top, Goldstein 3rd ed. §5.7: turning points from the cubic \
               f(u) (eq. 5.66), nutation period 4K/√(β(u₃ − u₁)) (Byrd & Friedman 233.00), \
               steady precession eq. 5.76 (spatial_ref.rs)";
    let (m, l, i1, i3) = TOP;
    let top = match HeavyTop::new(m, l, G, i1, i3) {
        Ok(t) => t,
        Err(e) => {
            out.push(
                Case::new("mbd.spatial.heavy_top", "top", "-", src).failed(0.0, e.to_string()),
            );
            return;
        }
    };
    nutation_cases(&top, src, out);
    precession_case(&top, src, out);
}

/// Released with spin only (θ₀ = 0.5, ψ̇₀ = 20 rad/s): θ between θ_min = θ₀ and θ_max.
fn nutation_cases(top: &HeavyTop, src: &str, out: &mut Vec<Case>) {
    let ids = [
        "mbd.spatial.heavy_top.theta_min",
        "mbd.spatial.heavy_top.theta_max",
        "mbd.spatial.heavy_top.nutation_period",
    ];
    let (theta0, spin) = (0.5, 20.0);
    let state = TopState {
        theta: theta0,
        phi_dot: 0.0,
        theta_dot: 0.0,
        psi_dot: spin,
    };
    let nut = match top.nutation(state) {
        Ok(n) => n,
        Err(e) => {
            for id in ids {
                out.push(Case::new(id, "nutation", "rad", src).failed(0.0, e.to_string()));
            }
            return;
        }
    };
    let refs = [nut.theta_min, nut.theta_max, nut.period];
    let t_end = 2.5;
    let res = match run_spatial(
        &top_text(theta0, [0.0, 0.0, spin]),
        &dopri(t_end, 25_000, 1e-10),
    ) {
        Ok(r) => r,
        Err(e) => {
            for (id, r) in ids.iter().zip(refs) {
                out.push(Case::new(*id, "nutation", "rad", src).failed(r, e.clone()));
            }
            return;
        }
    };
    let t = col(&res, "t");
    let theta = nutation_angle(&res, "top");
    let (mins, maxs) = (extrema(&t, &theta, false), extrema(&t, &theta, true));
    let worst = |ext: &[(f64, f64)], r: f64| {
        ext.iter().map(|e| e.1).fold(f64::NAN, |a, v| {
            if a.is_nan() || (v - r).abs() > (a - r).abs() {
                v
            } else {
                a
            }
        })
    };
    let period = if maxs.len() >= 2 {
        (maxs[maxs.len() - 1].0 - maxs[0].0) / (maxs.len() - 1) as f64
    } else {
        f64::NAN
    };
    let note = format!(
        "θ₀ = {theta0}, ψ̇₀ = {spin} rad/s, φ̇₀ = θ̇₀ = 0; m = {}, l = {}, I1 = {} (pivot), I3 = {}; \
         DOPRI5 rtol 1e-10, {t_end} s, 25001 outputs (extrema by parabolic vertex), {} steps; \
         {} minima, {} maxima; the worst extremum is reported",
        TOP.0,
        TOP.1,
        TOP.2,
        TOP.3,
        res.stats.accepted,
        mins.len(),
        maxs.len()
    );
    let values = [worst(&mins, refs[0]), worst(&maxs, refs[1]), period];
    let what = [
        "θ at the interior minima of θ(t) (the cusps)",
        "θ at the maxima of θ(t)",
        "mean time between maxima of θ(t)",
    ];
    let units = ["rad", "rad", "s"];
    // θ to 1e-8 rad and the period to 1e-8 s: the integration error at rtol 1e-10 over 2.5 s is
    // ~1e-9, the parabolic vertex's ~h³θ''' ~ 1e-11.
    for k in 0..3 {
        out.push(
            Case::new(
                ids[k],
                what[k],
                units[k],
                format!("{src}; tolerance 1e-8 absolute"),
            )
            .absolute(values[k], refs[k], 1e-8)
            .note(format!("error {:.3e}; {note}", values[k] - refs[k])),
        );
    }
}

/// Started at the slow steady precession at θ = 0.8 with ω3 = 15 rad/s: θ stays put and the
/// axis turns about the vertical at φ̇ = the slow root of eq. 5.76.
fn precession_case(top: &HeavyTop, src: &str, out: &mut Vec<Case>) {
    let id = "mbd.spatial.heavy_top.precession";
    let (theta, omega3, t_end) = (0.8f64, 15.0, 3.0);
    let phi_dot = match top.steady_precession(theta, omega3) {
        Ok(p) => p.slow,
        Err(e) => {
            out.push(Case::new(id, "precession", "rad/s", src).failed(0.0, e.to_string()));
            return;
        }
    };
    // ω = φ̇ Z + ψ̇ e₃; in the body frame Z = (0, sin θ, cos θ) and ω3 = ψ̇ + φ̇ cos θ
    let w = [0.0, phi_dot * theta.sin(), omega3];
    let res = match run_spatial(&top_text(theta, w), &dopri(t_end, 3000, 1e-10)) {
        Ok(r) => r,
        Err(e) => {
            out.push(Case::new(id, "precession", "rad/s", src).failed(phi_dot, e));
            return;
        }
    };
    let t = col(&res, "t");
    let rot = rotations(&res, "top");
    let az = unwrapped_azimuth(rot.iter().map(|a| (a[0][2], a[1][2])));
    let rate = slope(&t, &az);
    let dtheta = max_abs(nutation_angle(&res, "top").iter().map(|v| v - theta));
    out.push(
        Case::new(
            id,
            "precession rate φ̇ of the axis (least-squares slope of its azimuth)",
            "rad/s",
            format!("{src}; tolerance 1e-8 relative"),
        )
        .relative(rate, phi_dot, 1e-8)
        .note(format!(
            "θ = {theta}, ω3 = {omega3} rad/s, slow root {phi_dot:.12}; max |θ(t) − θ₀| = \
             {dtheta:.2e} rad over {t_end} s; DOPRI5 rtol 1e-10, {} steps",
            res.stats.accepted
        )),
    );
}

// ---------------------------------------------------------------------------------------------
// mbd.spatial.conical_pendulum
// ---------------------------------------------------------------------------------------------

/// A symmetric body hung from a spherical joint (m = 2 kg, l = 0.7 m, I1 = 1.3 kg·m² about the
/// pivot, I3 = 0.4 kg·m²) turning rigidly about the vertical at the cone angle 0.6 rad from the
/// downward vertical: its rate against Ω² = mgl/((I1 − I3) cos θ) (Goldstein eq. 5.76 with
/// ψ̇ = 0; spatial_ref.rs).
fn conical_case(out: &mut Vec<Case>) {
    let id = "mbd.spatial.conical_pendulum";
    let src = "rigid conical pendulum Ω² = mgl/((I1 − I3) cos θ_cone), the heavy top's steady \
               precession without relative spin (Goldstein 3rd ed. eq. 5.76; spatial_ref.rs); \
               tolerance 1e-8 relative";
    let (m, l, i1, i3, cone, t_end) = (2.0, 0.7, 1.3, 0.4, 0.6f64, 3.0);
    let omega = match HeavyTop::new(m, l, G, i1, i3).and_then(|t| conical_pendulum_rate(&t, cone)) {
        Ok(w) => w,
        Err(e) => {
            out.push(Case::new(id, "rate", "rad/s", src).failed(0.0, e.to_string()));
            return;
        }
    };
    // body z from the pivot to the centre of mass, tilted by π − θ about world x
    let text = pivoted_text(
        "rod",
        (m, l, i1, i3),
        std::f64::consts::PI - cone,
        ([0.0, 0.0, omega], "world"),
    );
    let res = match run_spatial(&text, &dopri(t_end, 3000, 1e-10)) {
        Ok(r) => r,
        Err(e) => {
            out.push(Case::new(id, "rate", "rad/s", src).failed(omega, e));
            return;
        }
    };
    let t = col(&res, "t");
    let (x, y, z) = (col(&res, "rod.x"), col(&res, "rod.y"), col(&res, "rod.z"));
    let az = unwrapped_azimuth(x.iter().zip(&y).map(|(a, b)| (*a, *b)));
    let rate = slope(&t, &az);
    let dz = max_abs(z.iter().map(|v| v + l * cone.cos()));
    out.push(
        Case::new(
            id,
            "turning rate of the centre of mass about the vertical (least-squares slope)",
            "rad/s",
            src,
        )
        .relative(rate, omega, 1e-8)
        .note(format!(
            "closed form Ω = {omega:.12} rad/s; max |z − (−l cos θ)| = {dz:.2e} m over {t_end} s; \
             DOPRI5 rtol 1e-10, {} steps",
            res.stats.accepted
        )),
    );
}

// ---------------------------------------------------------------------------------------------
// contact.spatial.sphere.geometry
// ---------------------------------------------------------------------------------------------

/// The ball's body turns about a tilted revolute axis through P, driven at ω, its centre on a
/// circle of radius ρ that passes in and out of the socket (centred at the origin).
const GEO_P: [f64; 3] = [2e-4, -1e-4, 5e-5];
const GEO_U: [f64; 3] = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
const GEO_R0: [f64; 3] = [4e-4, -4e-4, 2e-4];
const GEO_OMEGA: f64 = 10.0;
const GEO_K: f64 = 1e10;
const GEO_RS: f64 = 0.010;
const GEO_RB: f64 = 0.0095;

fn geometry_text() -> String {
    format!(
        r#"
[model]
space = "spatial"
[[body]]
name = "b"
mass = 0.5
principal_inertia = [1e-4, 2e-4, 2.5e-4]
position = {p:?}
orientation = {{ quaternion = [1.0, 0.0, 0.0, 0.0] }}
velocity = [0.0, 0.0, 0.0]
velocity_frame = "world"
angular_velocity = {w:?}
angular_velocity_frame = "world"
[[joint]]
name = "hinge"
type = "revolute"
a = {{ body = "ground", at = {p:?}, axis = {u:?} }}
b = {{ body = "b", at = [0.0, 0.0, 0.0], axis = {u:?} }}
[[driver]]
name = "motor"
type = "revolute_angle"
joint = "hinge"
motion = {{ type = "linear", initial = 0.0, rate = {GEO_OMEGA} }}
[[clearance]]
name = "S"
type = "spherical"
socket = {{ body = "ground", at = [0.0, 0.0, 0.0] }}
ball = {{ body = "b", at = {r:?} }}
socket_radius = {GEO_RS}
ball_radius = {GEO_RB}
normal = {{ law = "hertz", stiffness = {GEO_K}, damping = "none", restitution = 1.0 }}
"#,
        p = GEO_P,
        u = GEO_U,
        w = GEO_U.map(|c| c * GEO_OMEGA),
        r = GEO_R0,
    )
}

/// Closed form at time t: e = P + R(u, ωt) r₀ (Rodrigues, r₀ ⊥ u), δ = |e| − c, δ̇ = ė·e/|e| with
/// ė = ω u × (e − P), F_N = K δ^{3/2} (δ > 0).
fn geometry_exact(t: f64) -> ([f64; 3], f64, f64, f64) {
    let (s, c) = (GEO_OMEGA * t).sin_cos();
    let uxr = cross(GEO_U, GEO_R0);
    let arm = [0, 1, 2].map(|i| GEO_R0[i] * c + uxr[i] * s);
    let e = [0, 1, 2].map(|i| GEO_P[i] + arm[i]);
    let len = norm(e);
    let de = cross(GEO_U, arm).map(|v| GEO_OMEGA * v);
    let delta = len - (GEO_RS - GEO_RB);
    let f = if delta > 0.0 {
        GEO_K * delta.powf(1.5)
    } else {
        0.0
    };
    (e, delta, dot(de, e) / len, f)
}

fn geometry_cases(out: &mut Vec<Case>) {
    let src = "ball-in-socket geometry in closed form (Flores et al. 2006: e = p_ball − \
               p_socket, δ = |e| − (R_s − R_b), n = e/|e|, δ̇ = ė·n, F_N = Kδ^1.5) along a \
               prescribed motion: the ball's body driven about a tilted revolute axis";
    let ids = [
        (
            "contact.spatial.sphere.geometry.eccentricity",
            "max |e − e_exact| (C.ex, C.ey, C.ez; gives n)",
            "m",
            1e-12,
        ),
        (
            "contact.spatial.sphere.geometry.penetration",
            "max |δ − δ_exact|",
            "m",
            1e-12,
        ),
        (
            "contact.spatial.sphere.geometry.rate",
            "max |δ̇ − δ̇_exact|",
            "m/s",
            1e-10,
        ),
        (
            "contact.spatial.sphere.geometry.normal_force",
            "max |F_N − Kδ^1.5| / max F_N",
            "-",
            1e-8,
        ),
    ];
    let res = match run_spatial(&geometry_text(), &dopri(1.0, 200, 1e-11)) {
        Ok(r) => r,
        Err(e) => {
            for (id, what, unit, tol) in ids {
                out.push(Case::new(id, what, unit, src).failed(tol, e.clone()));
            }
            return;
        }
    };
    let t = col(&res, "t");
    let (ex, ey, ez) = (col(&res, "S.ex"), col(&res, "S.ey"), col(&res, "S.ez"));
    let (pen, rate, fnc) = (
        col(&res, "S.penetration"),
        col(&res, "S.rate"),
        col(&res, "S.normal_force"),
    );
    let exact: Vec<_> = t.iter().map(|&ti| geometry_exact(ti)).collect();
    let fmax = exact.iter().fold(0.0f64, |a, x| a.max(x.3));
    let errs = [
        max_abs((0..t.len()).map(|k| norm(sub([ex[k], ey[k], ez[k]], exact[k].0)))),
        max_abs((0..t.len()).map(|k| pen[k] - exact[k].1)),
        max_abs((0..t.len()).map(|k| rate[k] - exact[k].2)),
        max_abs((0..t.len()).map(|k| fnc[k] - exact[k].3)) / fmax,
    ];
    let in_contact = exact.iter().filter(|x| x.1 > 0.0).count();
    for ((id, what, unit, tol), err) in ids.into_iter().zip(errs) {
        out.push(
            Case::new(id, what, unit, format!("{src}; tolerance {tol:e}"))
                .at_most(err, tol)
                .note(format!(
                    "{} outputs over 1 s ({in_contact} in contact, δ up to {:.3e} m, F_N up to \
                     {fmax:.3e} N); DOPRI5 rtol 1e-11; max constraint violation {:.2e}; the \
                     contact points Q = p + R n are not output: they follow from e",
                    t.len(),
                    exact.iter().fold(f64::MIN, |a, x| a.max(x.1)),
                    res.max_position_violation
                )),
        );
    }
}

// ---------------------------------------------------------------------------------------------
// contact.spatial.sphere.static
// ---------------------------------------------------------------------------------------------

/// A 2 kg ball dropped into its socket (steel, R_s = 10 mm, R_b = 9.5 mm, LN damping c_e = 0.5)
/// settles where K δ^{3/2} = m g, K = (4/3)E*√(R_sR_b/(R_s − R_b)) (Hertz, Johnson, *Contact
/// Mechanics* §4.2, with E* = E/(2(1 − ν²)) for two equal materials).
fn static_case(out: &mut Vec<Case>) {
    let id = "contact.spatial.sphere.static";
    let src = "Hertz static equilibrium K δ^1.5 = m g, K = (4/3)E*√(R_sR_b/(R_s − R_b)) \
               (Johnson, Contact Mechanics §4.2); tolerance 1e-6 relative after 2 s of settling";
    let (m, e, nu, rs, rb) = (2.0f64, 207e9f64, 0.3f64, 0.010f64, 0.0095f64);
    let e_star = e / (2.0 * (1.0 - nu * nu));
    let k = 4.0 / 3.0 * e_star * (rs * rb / (rs - rb)).sqrt();
    let delta = (m * G / k).powf(2.0 / 3.0);
    let text = format!(
        r#"
[model]
space = "spatial"
gravity = [0.0, 0.0, -{G}]
[[body]]
name = "ball"
mass = {m}
principal_inertia = [1e-4, 1e-4, 1e-4]
position = [0.0, 0.0, 0.0]
velocity = [0.0, 0.0, 0.0]
velocity_frame = "world"
[[clearance]]
name = "S"
type = "spherical"
socket = {{ body = "ground", at = [0.0, 0.0, 0.0] }}
ball = {{ body = "ball", at = [0.0, 0.0, 0.0] }}
socket_radius = {rs}
ball_radius = {rb}
normal = {{ law = "hertz-internal-sphere", damping = "lankarani-nikravesh", restitution = 0.5, bearing_material = {{ youngs_modulus = {e}, poisson_ratio = {nu} }}, journal_material = {{ youngs_modulus = {e}, poisson_ratio = {nu} }} }}
"#
    );
    let mut opts = SimOptions::span(0.0, 2.0, 200).tolerances(1e-10, 1e-14);
    opts.solver = SolverKind::Ndf;
    let res = match run_spatial(&text, &opts) {
        Ok(r) => r,
        Err(e) => {
            out.push(Case::new(id, "static penetration", "m", src).failed(delta, e));
            return;
        }
    };
    let pen = col(&res, "S.penetration");
    let f = col(&res, "S.normal_force");
    let n = pen.len();
    let last = pen[n - 1];
    let tail = max_abs(pen[n - 20..].iter().map(|v| v - last));
    out.push(
        Case::new(id, "penetration at rest (C.penetration at 2 s)", "m", src)
            .relative(last, delta, 1e-6)
            .note(format!(
                "Hertz δ = {delta:.6e} m; F_N = {:.9} N vs m g = {:.9} N; variation over the \
                 last 0.2 s {tail:.2e} m; {} impacts; NDF rtol 1e-10, {} steps",
                f[n - 1],
                m * G,
                res.impacts.len(),
                res.stats.accepted
            )),
    );
}

// ---------------------------------------------------------------------------------------------
// Reductions to the planar engine: contact.spatial.sphere.planar, mbd.spatial.planar_reduction
// ---------------------------------------------------------------------------------------------

/// The steel Hertz internal law of the benchmark joint as a spatial `normal` table: the same
/// formula K = (4/3)E*√(R_iR_j/(R_i − R_j)) as the planar `Hertz`/`LN` presets' internal
/// cylinder, with the given damping and c_e.
fn steel_sphere_law(damping: &str, c_e: f64) -> String {
    let mat = "{ youngs_modulus = 207e9, poisson_ratio = 0.3 }";
    format!(
        "{{ law = \"hertz-internal-sphere\", damping = \"{damping}\", restitution = {c_e}, \
         bearing_material = {mat}, journal_material = {mat} }}"
    )
}

/// A spatial body at rest in the x–y plane with in-plane velocity (vx, vy) and ω_z.
fn planar_body(name: &str, m: f64, izz: f64, x: f64, v: [f64; 2], wz: f64) -> String {
    format!(
        r#"
[[body]]
name = "{name}"
mass = {m}
principal_inertia = [{izz}, {izz}, {izz}]
position = [{x}, 0.0, 0.0]
orientation = {{ quaternion = [1.0, 0.0, 0.0, 0.0] }}
velocity = [{}, {}, 0.0]
velocity_frame = "world"
angular_velocity = [0.0, 0.0, {wz}]
angular_velocity_frame = "world"
"#,
        v[0], v[1]
    )
}

/// What two runs of the same mechanism agree on: the largest position difference of the listed
/// columns, and the impacts (count and the largest onset difference).
struct Agreement {
    position: f64,
    onsets: (usize, usize),
    onset: f64,
    out_of_plane: f64,
}

fn agreement(planar: &Results, spatial: &Results, cols: &[&str], z_cols: &[&str]) -> Agreement {
    let position = cols
        .iter()
        .map(|c| {
            max_abs(
                col(planar, c)
                    .iter()
                    .zip(col(spatial, c))
                    .map(|(a, b)| a - b),
            )
        })
        .fold(0.0, f64::max);
    let onset = planar
        .impacts
        .iter()
        .zip(&spatial.impacts)
        .map(|(a, b)| (a.onset - b.onset).abs())
        .fold(0.0, f64::max);
    let out_of_plane = z_cols
        .iter()
        .map(|c| max_abs(col(spatial, c)))
        .fold(0.0, f64::max);
    Agreement {
        position,
        onsets: (planar.impacts.len(), spatial.impacts.len()),
        onset: if planar.impacts.len() == spatial.impacts.len() {
            onset
        } else {
            f64::INFINITY
        },
        out_of_plane,
    }
}

/// Push the position and onset cases of a planar/spatial comparison.
fn agreement_cases(
    out: &mut Vec<Case>,
    (base, src): (&str, &str),
    runs: Result<(Results, Results), String>,
    (pos_tol, rtol): (f64, f64),
    what: &str,
    (cols, z_cols): (&[&str], &[&str]),
    extra: &str,
) {
    let (id_pos, id_onset) = (format!("{base}.position"), format!("{base}.onsets"));
    let src_pos = format!("{src}; tolerance {pos_tol:e} m at rtol {rtol:e}");
    let src_on = format!("{src}; the same impacts, onsets within 1e-9 s at rtol {rtol:e}");
    let (p, s) = match runs {
        Ok(r) => r,
        Err(e) => {
            out.push(Case::new(id_pos, what, "m", src_pos).failed(0.0, e.clone()));
            out.push(Case::new(id_onset, "onset times", "s", src_on).failed(0.0, e));
            return;
        }
    };
    let a = agreement(&p, &s, cols, z_cols);
    let note = format!(
        "{extra}{} outputs; impacts planar {} / spatial {}; steps planar {} / spatial {}; spatial \
         out-of-plane max |z| {:.1e} m; first onsets planar {:?} s; their differences \
         spatial − planar {:?} s",
        p.len(),
        a.onsets.0,
        a.onsets.1,
        p.stats.accepted,
        s.stats.accepted,
        a.out_of_plane,
        p.impacts
            .iter()
            .take(4)
            .map(|i| i.onset)
            .collect::<Vec<_>>(),
        p.impacts
            .iter()
            .zip(&s.impacts)
            .take(6)
            .map(|(a, b)| format!("{:.2e}", b.onset - a.onset))
            .collect::<Vec<_>>()
    );
    out.push(
        Case::new(id_pos, what, "m", src_pos)
            .at_most(a.position, pos_tol)
            .note(note.clone()),
    );
    out.push(
        Case::new(
            id_onset,
            "max |onset_planar − onset_spatial| over the impacts",
            "s",
            src_on,
        )
        .at_most(a.onset, 1e-9)
        .note(note),
    );
}

/// verify/mbd.rs's clearance pendulum (a 1 kg, 0.4 m rod released horizontally on a
/// frictionless steel Hertz pin, c_e = 1) written as a spatial model in the x–y plane.
fn pendulum_text() -> String {
    use crate::minimal_slider_crank::{R_BEARING, R_JOURNAL};
    format!(
        r#"
[model]
space = "spatial"
gravity = [0.0, -{G}, 0.0]
{body}
[[clearance]]
name = "pin"
type = "spherical"
socket = {{ body = "ground", at = [0.0, 0.0, 0.0] }}
ball = {{ body = "rod", at = [-0.2, 0.0, 0.0] }}
socket_radius = {R_BEARING}
ball_radius = {R_JOURNAL}
normal = {law}
"#,
        body = planar_body("rod", 1.0, 0.16 / 12.0, 0.2, [0.0, 0.0], 0.0),
        law = steel_sphere_law("none", 1.0),
    )
}

fn sphere_planar_cases(out: &mut Vec<Case>) {
    let src = "the planar revolute clearance joint (clr-mbd planar engine, verify/mbd.rs \
               clearance_pendulum) on the same mechanism: with the motion in a plane the \
               spherical joint is term by term the revolute one (sphere.rs)";
    // 0.06 s: the first three impacts. Over 0.2 s (19 impacts) the runs part by 4e-6 s in the
    // onsets while the first onset agrees to 1e-17 s: each impact amplifies the two runs'
    // different integration errors (rtol 1e-10, different state vectors and steps).
    let t_end = 0.06;
    let opts = dopri(t_end, 30, 1e-10);
    let runs = (|| {
        let mut planar = super::mbd::clearance_pendulum()?;
        let p = planar.simulate(&opts).map_err(|e| e.to_string())?;
        let s = run_spatial(&pendulum_text(), &opts)?;
        Ok((p, s))
    })();
    agreement_cases(
        out,
        ("contact.spatial.sphere.planar", src),
        runs,
        (1e-9, 1e-10),
        "max |r_planar − r_spatial| of the rod's centre of mass at 31 times over 0.06 s",
        (&["rod.x", "rod.y"], &["rod.z"]),
        "",
    );
}

/// verify/mbd.rs's clearance slider–crank (5000 rpm, LN c_e = 0.9, steel, no friction) as a
/// spatial model: revolute joints about z, a prismatic joint along x for the slider, the
/// clearance joint as a ball (rod end) in a socket (slider).
pub(crate) fn slider_crank_text(omega: f64) -> String {
    use crate::minimal_slider_crank::{
        CRANK, I_CRANK, I_ROD, I_SLIDER, M_CRANK, M_ROD, M_SLIDER, ROD, R_BEARING, R_JOURNAL,
    };
    let z = "axis = [0.0, 0.0, 1.0]";
    format!(
        r#"
[model]
space = "spatial"
gravity = [0.0, -{G}, 0.0]
{crank}{rod}{slider}
[[joint]]
name = "O"
type = "revolute"
a = {{ body = "ground", at = [0.0, 0.0, 0.0], {z} }}
b = {{ body = "crank", at = [{hc}, 0.0, 0.0], {z} }}
[[joint]]
name = "A"
type = "revolute"
a = {{ body = "crank", at = [{c2}, 0.0, 0.0], {z} }}
b = {{ body = "rod", at = [{hr}, 0.0, 0.0], {z} }}
[[joint]]
name = "guide"
type = "prismatic"
a = {{ body = "ground", at = [0.0, 0.0, 0.0], axis = [1.0, 0.0, 0.0] }}
b = {{ body = "slider", at = [0.0, 0.0, 0.0] }}
[[driver]]
name = "motor"
type = "revolute_angle"
joint = "O"
motion = {{ type = "linear", initial = 0.0, rate = {omega} }}
[[clearance]]
name = "B"
type = "spherical"
socket = {{ body = "slider", at = [0.0, 0.0, 0.0] }}
ball = {{ body = "rod", at = [{r2}, 0.0, 0.0] }}
socket_radius = {R_BEARING}
ball_radius = {R_JOURNAL}
normal = {law}
"#,
        crank = planar_body(
            "crank",
            M_CRANK,
            I_CRANK,
            CRANK / 2.0,
            [0.0, omega * CRANK / 2.0],
            omega
        ),
        rod = planar_body(
            "rod",
            M_ROD,
            I_ROD,
            CRANK + ROD / 2.0,
            [0.0, omega * CRANK / 2.0],
            -omega * CRANK / ROD
        ),
        slider = planar_body("slider", M_SLIDER, I_SLIDER, CRANK + ROD, [0.0, 0.0], 0.0),
        hc = -CRANK / 2.0,
        c2 = CRANK / 2.0,
        hr = -ROD / 2.0,
        r2 = ROD / 2.0,
        law = steel_sphere_law("lankarani-nikravesh", 0.9),
    )
}

/// The planar engine's clearance slider–crank of `mbd.clearance_slider_crank` (verify/mbd.rs:
/// steel LN c_e = 0.9 over a 10 mm bearing, no friction) at crank speed `omega` (rad/s), run with
/// `opts`: the reference of the planar reductions.
fn planar_slider_crank(omega: f64, opts: &SimOptions) -> Result<Results, String> {
    let mut planar = planar_slider_crank_model(omega)?;
    planar.simulate(opts).map_err(|e| e.to_string())
}

/// The model of [`planar_slider_crank`] (also `cargo xtask bench spatial`'s planar run).
pub(crate) fn planar_slider_crank_model(omega: f64) -> Result<clr_mbd::Model, String> {
    use crate::minimal_slider_crank::{R_BEARING, R_JOURNAL};
    use clr_contact::{FrictionLaw, JournalBearing, Material, NormalLaw};
    let jb = JournalBearing {
        bearing: Material::steel(),
        journal: Material::steel(),
        r_bearing: R_BEARING,
        r_journal: R_JOURNAL,
        length: 0.01,
    };
    let normal = NormalLaw::preset("LN", &jb, 0.9).map_err(|e| e.to_string())?;
    let friction = FrictionLaw::coulomb(0.0, 1.0).map_err(|e| e.to_string())?;
    super::mbd::clearance_slider_crank(omega, normal, friction, R_BEARING, R_JOURNAL)
}

fn planar_reduction_cases(out: &mut Vec<Case>) {
    let src = "the planar engine on the same mechanism (verify/mbd.rs clearance_slider_crank: \
               5000 rpm, steel LN c_e = 0.9, no friction), the spatial model moving in the x–y \
               plane";
    let omega = 5000.0 * std::f64::consts::PI / 30.0;
    let runs = |rtol: f64| -> Result<(Results, Results), String> {
        let opts = dopri(0.010, 10, rtol);
        let p = planar_slider_crank(omega, &opts)?;
        let s = run_spatial(&slider_crank_text(omega), &opts)?;
        Ok((p, s))
    };
    // rtol 1e-12: at rtol 1e-10 the two engines' different integration errors, amplified by
    // the 14 impacts, part the runs by ~1e-8 m and ~4e-8 s (first onset equal to 1e-17 s);
    // the difference falls ~150-fold at rtol 1e-12, so it is integration error, not a model
    // difference (measured 2026-11-27; the note repeats the rtol 1e-10 figures).
    let loose = loose_note(runs(1e-10));
    agreement_cases(
        out,
        ("mbd.spatial.planar_reduction", src),
        runs(1e-12),
        (1e-9, 1e-12),
        "max |x_planar − x_spatial| of the slider at 1, 2, …, 10 ms",
        (&["slider.x"], &["rod.z", "slider.z"]),
        &loose,
    );
}

/// The note of a planar-reduction case on its runs at the issue's rtol 1e-10: how far the
/// slider and the onsets part there (the case itself runs at 1e-12).
fn loose_note(r: Result<(Results, Results), String>) -> String {
    match r {
        Ok((p, s)) => {
            let a = agreement(&p, &s, &["slider.x"], &[]);
            format!(
                "at rtol 1e-10: position {:.2e} m, onsets {:.2e} s; ",
                a.position, a.onset
            )
        }
        Err(e) => format!("at rtol 1e-10: failed ({e}); "),
    }
}

/// The clearance slider–crank of [`slider_crank_text`] with a spatial revolute clearance joint
/// (bearing in the slider, journal on the rod, both axes along z, 10 mm long, axial end play
/// 0.1 mm) instead of the ball in its socket: nothing excites tilt or axial motion.
pub(crate) fn journal_slider_crank_text(omega: f64) -> String {
    use crate::minimal_slider_crank::{ROD, R_BEARING, R_JOURNAL};
    let text = slider_crank_text(omega);
    let head = &text[..text.find("[[clearance]]").unwrap_or(text.len())];
    let mat = "{ youngs_modulus = 207e9, poisson_ratio = 0.3 }";
    format!(
        r#"{head}[[clearance]]
name = "B"
type = "revolute"
bearing = {{ body = "slider", at = [0.0, 0.0, 0.0], axis = [0.0, 0.0, 1.0] }}
journal = {{ body = "rod", at = [{r2}, 0.0, 0.0], axis = [0.0, 0.0, 1.0] }}
bearing_radius = {R_BEARING}
journal_radius = {R_JOURNAL}
bearing_length = 0.01
journal_length = 0.01
axial_clearance = 1e-4
normal = {{ law = "preset", preset = "LN", restitution = 0.9, bearing_material = {mat}, journal_material = {mat} }}
"#,
        r2 = ROD / 2.0,
    )
}

/// `mbd.spatial.revolute_clearance.planar_reduction`: the spatial revolute clearance joint in
/// the planar clearance slider–crank against the planar engine (issue 32).
fn journal_reduction_cases(out: &mut Vec<Case>) {
    let src = "the planar engine on the same mechanism (verify/mbd.rs clearance_slider_crank: \
               5000 rpm, steel LN c_e = 0.9, no friction), the spatial model with a revolute \
               clearance joint (axes along z, 10 mm long) moving in the x–y plane";
    let omega = 5000.0 * std::f64::consts::PI / 30.0;
    let runs = |rtol: f64| -> Result<(Results, Results), String> {
        let opts = dopri(0.010, 10, rtol);
        let p = planar_slider_crank(omega, &opts)?;
        let mut s = run_spatial(&journal_slider_crank_text(omega), &opts)?;
        // at zero tilt both radial regions open and close together: compare the planar
        // impacts with region A's
        s.impacts.retain(|i| i.joint == "B.radial_a");
        Ok((p, s))
    };
    // rtol 1e-12, as mbd.spatial.planar_reduction (same mechanism, same integrator): at rtol
    // 1e-10 the engines' different integration errors, amplified by the impacts, part the
    // runs by more than 1e-9 m; the note gives the rtol 1e-10 figures
    let loose = loose_note(runs(1e-10));
    agreement_cases(
        out,
        ("mbd.spatial.revolute_clearance.planar_reduction", src),
        runs(1e-12),
        (1e-9, 1e-12),
        "max |x_planar − x_spatial| of the slider at 1, 2, …, 10 ms",
        (
            &["slider.x"],
            &["rod.z", "slider.z", "B.tilt", "B.axial_offset"],
        ),
        &loose,
    );
}

/// A case family: its id prefix and the function pushing its cases.
type Family = (&'static str, fn(&mut Vec<Case>));

const MBD: &[Family] = &[
    ("mbd.spatial.torque_free", torque_free_cases),
    ("mbd.spatial.heavy_top", heavy_top_cases),
    ("mbd.spatial.conical_pendulum", conical_case),
    ("mbd.spatial.planar_reduction", planar_reduction_cases),
    (
        "mbd.spatial.revolute_clearance.planar_reduction",
        journal_reduction_cases,
    ),
];

const CONTACT: &[Family] = &[
    ("contact.spatial.sphere.geometry", geometry_cases),
    ("contact.spatial.sphere.static", static_case),
    ("contact.spatial.sphere.planar", sphere_planar_cases),
];

/// The cases of the requested families.
fn run_families(families: &[Family], filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    for (prefix, run) in families {
        if filter.wants(prefix) {
            run(&mut out);
        }
    }
    out
}

/// The `mbd.spatial.*` cases.
pub fn mbd_cases(filter: &Filter) -> Vec<Case> {
    run_families(MBD, filter)
}

/// The `contact.spatial.*` cases.
pub fn contact_cases(filter: &Filter) -> Vec<Case> {
    run_families(CONTACT, filter)
}
