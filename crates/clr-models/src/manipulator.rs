//! Dual two-link manipulator on a free-floating spacecraft with revolute clearance joints:
//! Kuang, Bai, Wei, *Aerospace* 13 (2026) 75 (paper-systems.md §2).
//!
//! **Known from the paper:** base 500 kg, 100 kg·m²; four links 1.0 m, 1.09669 kg,
//! 0.094279 kg·m²; drive torques T1 = −0.7 sin(πt), T2 = −0.4 sin(πt), T3 = 0.7 sin(πt),
//! T4 = 0.4 sin(πt) N·m; contact stiffness K = 6.8e7 N/m^1.5, restitution 0.9; friction
//! μ_s = 0.2, μ_d = 0.1, v_s = 0.01 m/s, v_d = 0.1 m/s; the ideal case and cases 1–5
//! ([`ManipulatorParams::case`]).
//!
//! **Reconstructed (documented in docs/models/manipulator.md):** planar, no gravity; mounts of
//! the arms on the base at (±0.5 m, 0); arms stretched along ±x at t = 0 (mirror images, so
//! T3 = −T1 and T4 = −T2 drive mirror-symmetric motions); journal centred in the bearing at
//! t = 0; bearing radius 10 mm; Lankarani–Nikravesh law with K; Bai/Stribeck friction; 2 s.
//!
//! Bodies `base`, `arm1`, `arm2` (manipulator 1), `arm3`, `arm4` (manipulator 2); joints
//! `J1` (base–arm1), `J2` (arm1–arm2), `J3` (base–arm3), `J4` (arm3–arm4), each ideal or a
//! clearance joint (bearing on the inner body); torques `T1`..`T4` in the joints.

use std::path::Path;

use clr_mbd::{Model, ModelBuilder, ModelDesc, Results, RevoluteClearanceSpec, RigidBody, TimeFn};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::common::{
    self, col, non_negative, positive, FrictionParams, PairApplication, Record, Solver,
};
use crate::{Metric, ModelsError, RunOutput, RunSettings};

/// Names of the paper's cases, in order.
pub const CASES: [&str; 6] = ["ideal", "case1", "case2", "case3", "case4", "case5"];

/// Parameters of the dual manipulator (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ManipulatorParams {
    /// Spacecraft (base) mass, kg (paper: 500).
    pub base_mass: f64,
    /// Base inertia, kg·m² (paper: 100).
    pub base_inertia: f64,
    /// Length of each link, m (paper: 1.0).
    pub link_length: f64,
    /// Mass of each link, kg (paper: 1.09669).
    pub link_mass: f64,
    /// Inertia of each link about its centre, kg·m² (paper: 0.094279).
    pub link_inertia: f64,
    /// Distance of each shoulder from the base centre along x, m (reconstruction: 0.5, the
    /// half-width of a square plate of 500 kg with 100 kg·m² is 0.55 m).
    pub mount_offset: f64,
    /// Initial absolute angle of link 1 from +x, rad (reconstruction: 0; link 3 is its mirror
    /// image about the y axis).
    pub shoulder_angle: f64,
    /// Initial elbow angle (link 2 relative to link 1), rad (reconstruction: 0).
    pub elbow_angle: f64,
    /// Torque amplitudes of T1..T4, N·m (paper: −0.7, −0.4, 0.7, 0.4); T_k = a_k sin(ω t).
    pub torque_amplitudes: [f64; 4],
    /// Angular frequency ω of the drive torques, rad/s (paper: π).
    pub torque_frequency: f64,
    /// Radial clearance of joints J1..J4, m; 0 makes the joint ideal (default: case 3).
    pub clearances: [f64; 4],
    /// Bearing radius of a clearance joint, m (reconstruction: 10 mm; the journal radius is
    /// bearing radius − clearance).
    pub bearing_radius: f64,
    /// Contact stiffness K, N/m^1.5 (paper: 6.8e7).
    pub contact_stiffness: f64,
    /// Coefficient of restitution (paper: 0.9), Lankarani–Nikravesh damping.
    pub restitution: f64,
    /// Friction law (paper: Bai/Stribeck μ_s = 0.2, μ_d = 0.1, v_s = 0.01, v_d = 0.1 m/s).
    pub friction: FrictionParams,
    /// Where each clearance joint's force pair acts (default `common_point`, which conserves
    /// angular momentum; `contact_points` is the Flores et al. (2004) form).
    pub force_application: PairApplication,
    /// Simulated time, s (reconstruction: 2, one torque period).
    pub duration: f64,
    /// Relative tolerance (absolute tolerance rtol·1e-3).
    pub rtol: f64,
    /// Integrator.
    pub solver: Solver,
    /// Output interval of the ideal reference run used for the path error, s.
    pub reference_interval: f64,
}

impl Default for ManipulatorParams {
    fn default() -> Self {
        Self {
            base_mass: 500.0,
            base_inertia: 100.0,
            link_length: 1.0,
            link_mass: 1.09669,
            link_inertia: 0.094279,
            mount_offset: 0.5,
            shoulder_angle: 0.0,
            elbow_angle: 0.0,
            torque_amplitudes: [-0.7, -0.4, 0.7, 0.4],
            torque_frequency: std::f64::consts::PI,
            clearances: [0.0, 0.5e-3, 0.0, 0.5e-3],
            bearing_radius: 10e-3,
            contact_stiffness: 6.8e7,
            restitution: 0.9,
            friction: FrictionParams::Stribeck {
                mu_s: 0.2,
                mu_d: 0.1,
                v_s: 0.01,
                v_d: 0.1,
            },
            force_application: PairApplication::CommonPoint,
            duration: 2.0,
            rtol: 1e-9,
            solver: Solver::Dopri5,
            reference_interval: 1e-4,
        }
    }
}

impl ManipulatorParams {
    /// The paper's cases: `ideal`, `case1` (J2 0.5 mm), `case2` (J1 0.5 mm), `case3` (J2, J4
    /// 0.5 mm), `case4` (J2, J4 0.25 mm), `case5` (J2, J4 1.0 mm); other fields default.
    ///
    /// # Errors
    /// An unknown case name (the message lists the valid ones).
    pub fn case(name: &str) -> Result<Self, String> {
        let c = match name {
            "ideal" => [0.0; 4],
            "case1" => [0.0, 0.5e-3, 0.0, 0.0],
            "case2" => [0.5e-3, 0.0, 0.0, 0.0],
            "case3" => [0.0, 0.5e-3, 0.0, 0.5e-3],
            "case4" => [0.0, 0.25e-3, 0.0, 0.25e-3],
            "case5" => [0.0, 1.0e-3, 0.0, 1.0e-3],
            _ => {
                return Err(format!(
                    "unknown case `{name}`; valid: {}",
                    CASES.join(", ")
                ))
            }
        };
        Ok(Self {
            clearances: c,
            ..Self::default()
        })
    }

    /// Check every value; the message names the field to change.
    ///
    /// # Errors
    /// A message naming the field.
    pub fn validate(&self) -> Result<(), String> {
        for (f, v) in [
            ("base_mass", self.base_mass),
            ("base_inertia", self.base_inertia),
            ("link_length", self.link_length),
            ("link_mass", self.link_mass),
            ("link_inertia", self.link_inertia),
            ("bearing_radius", self.bearing_radius),
            ("contact_stiffness", self.contact_stiffness),
            ("duration", self.duration),
            ("rtol", self.rtol),
            ("reference_interval", self.reference_interval),
        ] {
            positive(f, v)?;
        }
        non_negative("mount_offset", self.mount_offset)?;
        for (k, &c) in self.clearances.iter().enumerate() {
            non_negative(&format!("clearances[{k}]"), c)?;
            if c >= self.bearing_radius {
                return Err(format!(
                    "`clearances[{k}]` = {c} m must be smaller than `bearing_radius` = {} m",
                    self.bearing_radius
                ));
            }
        }
        for (k, &a) in self.torque_amplitudes.iter().enumerate() {
            if !a.is_finite() {
                return Err(format!("`torque_amplitudes[{k}]` = {a} must be finite"));
            }
        }
        for (f, v) in [
            ("shoulder_angle", self.shoulder_angle),
            ("elbow_angle", self.elbow_angle),
            ("torque_frequency", self.torque_frequency),
        ] {
            if !v.is_finite() {
                return Err(format!("`{f}` = {v} must be finite"));
            }
        }
        if self.duration / self.reference_interval > 1e6 {
            return Err(format!(
                "`reference_interval` = {} s gives more than 1e6 reference rows over {} s; \
                 make it larger",
                self.reference_interval, self.duration
            ));
        }
        Ok(())
    }

    /// The clr-mbd model ([`ManipulatorParams::desc`] compiled).
    ///
    /// # Errors
    /// Invalid parameters or a clr-mbd build error.
    pub fn build(&self, model: &str) -> Result<Model, ModelsError> {
        common::compile(model, &self.desc(model)?)
    }

    /// The model as data, with the run settings of the clearance run of `clr run <model>` (no
    /// `--t-end` or `--rtol`) in `solver` and `output`: the `solver` and `rtol` parameters,
    /// atol = rtol·10⁻³, 0 to `duration` s, every accepted step recorded. Bodies `base`,
    /// `arm1` … `arm4`; joints `J1` … `J4` ideal or clearance per
    /// [`ManipulatorParams::clearances`]; joint torques `T1` … `T4`. `model` names the model in
    /// errors and in `[model]`.
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn desc(&self, model: &str) -> Result<ModelDesc, ModelsError> {
        self.validate().map_err(|m| common::invalid(model, m))?;
        // validated here for the parameter-level message; the model gets the laws as data
        common::ln_law(self.contact_stiffness, self.restitution)
            .map_err(|m| common::invalid(model, m))?;
        self.friction.law().map_err(|m| common::invalid(model, m))?;
        let normal = clr_mbd::NormalLawDesc::hertz(self.contact_stiffness, self.restitution);
        let friction = self.friction.desc();
        let (l, a) = (self.link_length, self.mount_offset);
        let mut b = ModelBuilder::new();
        b.clearance_force_application(self.force_application.into());
        b.body(
            "base",
            RigidBody::new(self.base_mass, self.base_inertia).at(0.0, 0.0, 0.0),
        );
        // manipulator 1 to the right (+x), manipulator 2 its mirror image
        let arms = [
            ("arm1", "arm2", 1.0, "J1", "J2", "T1", "T2", 0usize),
            ("arm3", "arm4", -1.0, "J3", "J4", "T3", "T4", 2usize),
        ];
        for (inner, outer, side, j_sh, j_el, t_sh, t_el, k) in arms {
            let mirror = |phi: f64| {
                if side > 0.0 {
                    phi
                } else {
                    std::f64::consts::PI - phi
                }
            };
            let phi1 = mirror(self.shoulder_angle);
            let phi2 = mirror(self.shoulder_angle + self.elbow_angle);
            let shoulder = [side * a, 0.0];
            let c1 = [
                shoulder[0] + 0.5 * l * phi1.cos(),
                shoulder[1] + 0.5 * l * phi1.sin(),
            ];
            let elbow = [c1[0] + 0.5 * l * phi1.cos(), c1[1] + 0.5 * l * phi1.sin()];
            let c2 = [
                elbow[0] + 0.5 * l * phi2.cos(),
                elbow[1] + 0.5 * l * phi2.sin(),
            ];
            b.body(
                inner,
                RigidBody::new(self.link_mass, self.link_inertia).at(c1[0], c1[1], phi1),
            )
            .body(
                outer,
                RigidBody::new(self.link_mass, self.link_inertia).at(c2[0], c2[1], phi2),
            );
            let joints = [
                (j_sh, "base", shoulder, inner, [-0.5 * l, 0.0], k),
                (j_el, inner, [0.5 * l, 0.0], outer, [-0.5 * l, 0.0], k + 1),
            ];
            for (name, bi, si, bj, sj, idx) in joints {
                let c = self.clearances[idx];
                if c > 0.0 {
                    b.revolute_clearance(
                        name,
                        (bi, si),
                        (bj, sj),
                        RevoluteClearanceSpec {
                            bearing_radius: self.bearing_radius,
                            journal_radius: self.bearing_radius - c,
                            normal: normal.clone().into(),
                            friction: friction.clone().into(),
                        },
                    );
                } else {
                    b.revolute(name, (bi, si), (bj, sj));
                }
            }
            let w = self.torque_frequency;
            let (a_sh, a_el) = (self.torque_amplitudes[k], self.torque_amplitudes[k + 1]);
            b.motor_torque(t_sh, "base", inner, TimeFn::harmonic(0.0, a_sh, w, 0.0))
                .motor_torque(t_el, inner, outer, TimeFn::harmonic(0.0, a_el, w, 0.0));
        }
        Ok(common::finish_desc(
            b,
            model,
            self.duration,
            self.rtol,
            self.solver,
        ))
    }
}

const BODIES: [&str; 5] = ["base", "arm1", "arm2", "arm3", "arm4"];

/// The model and run settings of the clearance run of [`run`] (the run it returns; [`run`]
/// also simulates the same system with ideal joints as its reference):
/// [`ManipulatorParams::desc`] with the end time and tolerance of `settings` (when given)
/// written into `solver` and `output`.
///
/// # Errors
/// Invalid parameters or run settings.
pub fn run_desc(
    model: &str,
    p: &ManipulatorParams,
    settings: &RunSettings,
) -> Result<ModelDesc, ModelsError> {
    common::run_desc(model, settings, Record::EveryStep, || p.desc(model))
}

/// Simulate one configuration and append the derived columns: end-effector positions
/// `ee1.x ee1.y ee2.x ee2.y` (tips of links 2 and 4) and the system momentum `momentum.px
/// momentum.py momentum.L` (angular momentum about the origin, L = Σ I_k ω_k + m_k (x_k v_yk −
/// y_k v_xk)). `uniform` records every `reference_interval` instead of every step.
fn simulate(
    model: &str,
    p: &ManipulatorParams,
    settings: &RunSettings,
    uniform: bool,
) -> Result<(Results, [f64; 2]), ModelsError> {
    // the clearance run records every step, the reference run every `reference_interval` s
    let record = if uniform {
        Record::Every(p.reference_interval)
    } else {
        Record::EveryStep
    };
    let desc = common::run_desc(model, settings, record, || p.desc(model))?;
    let (mut m, opts) = common::compile_run(model, &desc)?;
    let mut res = common::simulate(&mut m, &opts, settings, model)?;
    let n = res.len();
    let (mut px, mut py, mut lz) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    // momentum scales: largest Σ m|v| and Σ (|Iω| + m|r × v|) over the run
    let (mut sp, mut sl) = (vec![0.0f64; n], vec![0.0f64; n]);
    for name in BODIES {
        let k = m.body_index(name).unwrap_or(0);
        let (mass, inertia) = m.body_inertia(k);
        let c = |s: &str| col(&res, &format!("{name}.{s}"));
        let (x, y, vx, vy, om) = (c("x"), c("y"), c("vx"), c("vy"), c("omega"));
        for r in 0..n {
            px[r] += mass * vx[r];
            py[r] += mass * vy[r];
            let orb = mass * (x[r] * vy[r] - y[r] * vx[r]);
            lz[r] += inertia * om[r] + orb;
            sp[r] += mass * vx[r].hypot(vy[r]);
            sl[r] += (inertia * om[r]).abs() + orb.abs();
        }
    }
    let scales = [
        sp.iter().cloned().fold(0.0, f64::max),
        sl.iter().cloned().fold(0.0, f64::max),
    ];
    let l = p.link_length;
    let tip = |body: &str| -> (Vec<f64>, Vec<f64>) {
        let (x, y, th) = (
            col(&res, &format!("{body}.x")),
            col(&res, &format!("{body}.y")),
            col(&res, &format!("{body}.theta")),
        );
        let ex = (0..n).map(|r| x[r] + 0.5 * l * th[r].cos()).collect();
        let ey = (0..n).map(|r| y[r] + 0.5 * l * th[r].sin()).collect();
        (ex, ey)
    };
    let (e1x, e1y) = tip("arm2");
    let (e2x, e2y) = tip("arm4");
    common::append_columns(
        &mut res,
        vec![
            ("ee1.x".into(), e1x),
            ("ee1.y".into(), e1y),
            ("ee2.x".into(), e2x),
            ("ee2.y".into(), e2y),
            ("momentum.px".into(), px),
            ("momentum.py".into(), py),
            ("momentum.L".into(), lz),
        ],
    );
    Ok((res, scales))
}

/// Metrics of a run against the ideal reference, and the path-error columns `ee1.error`,
/// `ee2.error` (distance to the ideal end-effector position at the same time, m; the ideal
/// path is interpolated linearly from its uniform output).
fn compare(
    p: &ManipulatorParams,
    res: &mut Results,
    scales: [f64; 2],
    ideal: &Results,
) -> Vec<Metric> {
    let t = col(res, "t");
    let ti = col(ideal, "t");
    let mut errs = Vec::new();
    let mut metrics = Vec::new();
    for arm in ["ee1", "ee2"] {
        let (x, y) = (col(res, &format!("{arm}.x")), col(res, &format!("{arm}.y")));
        let (xi, yi) = (
            col(ideal, &format!("{arm}.x")),
            col(ideal, &format!("{arm}.y")),
        );
        let e: Vec<f64> = (0..t.len())
            .map(|r| {
                (x[r] - common::interp(&ti, &xi, t[r])).hypot(y[r] - common::interp(&ti, &yi, t[r]))
            })
            .collect();
        errs.push((format!("{arm}.error"), e));
    }
    let emax = |k: usize| common::peak_abs(&t, &errs[k].1, 0.0);
    let erms = |k: usize| common::time_rms(&t, &errs[k].1, 0.0);
    metrics.push(Metric::new(
        "path_error_max",
        emax(0).max(emax(1)),
        "m",
        "largest end-effector distance from the ideal path (both manipulators)",
    ));
    metrics.push(Metric::new(
        "path_error_rms",
        (0.5 * (erms(0).powi(2) + erms(1).powi(2))).sqrt(),
        "m",
        "time RMS of the end-effector distance from the ideal path over both end effectors",
    ));
    for (k, arm) in ["1", "2"].iter().enumerate() {
        metrics.push(Metric::new(
            &format!("path_error_max_arm{arm}"),
            emax(k),
            "m",
            &format!("largest end-effector path error of manipulator {arm}"),
        ));
        metrics.push(Metric::new(
            &format!("path_error_rms_arm{arm}"),
            erms(k),
            "m",
            &format!("time RMS of the end-effector path error of manipulator {arm}"),
        ));
    }
    base_metrics(res, ideal, &mut metrics);
    contact_metrics(p, res, &mut metrics);
    momentum_metrics(p, res, scales, &mut metrics);
    common::append_columns(res, errs);
    metrics
}

/// Base motion and its deviation from the ideal case.
fn base_metrics(res: &Results, ideal: &Results, metrics: &mut Vec<Metric>) {
    let t = col(res, "t");
    let ti = col(ideal, "t");
    // base position and attitude
    let (bx, by, bth) = (
        col(res, "base.x"),
        col(res, "base.y"),
        col(res, "base.theta"),
    );
    let (bxi, byi, bthi) = (
        col(ideal, "base.x"),
        col(ideal, "base.y"),
        col(ideal, "base.theta"),
    );
    let last = t.len().saturating_sub(1);
    metrics.push(Metric::new(
        "base_displacement_max",
        (0..t.len()).map(|r| bx[r].hypot(by[r])).fold(0.0, f64::max),
        "m",
        "largest displacement of the base centre from its initial position",
    ));
    metrics.push(Metric::new(
        "base_attitude_max",
        common::peak_abs(&t, &bth, 0.0),
        "rad",
        "largest |base attitude angle|",
    ));
    let dev_pos = (0..t.len())
        .map(|r| {
            (bx[r] - common::interp(&ti, &bxi, t[r])).hypot(by[r] - common::interp(&ti, &byi, t[r]))
        })
        .fold(0.0, f64::max);
    let dev_att = (0..t.len())
        .map(|r| (bth[r] - common::interp(&ti, &bthi, t[r])).abs())
        .fold(0.0, f64::max);
    metrics.push(Metric::new(
        "base_position_deviation_max",
        dev_pos,
        "m",
        "largest distance of the base centre from its ideal-case position",
    ));
    metrics.push(Metric::new(
        "base_attitude_deviation_max",
        dev_att,
        "rad",
        "largest |base attitude − ideal-case attitude|",
    ));
    metrics.push(Metric::new(
        "base_y_final",
        by.get(last).copied().unwrap_or(f64::NAN),
        "m",
        "base centre y at the end of the run",
    ));
}

/// Peak contact force and contact time fraction of each clearance joint.
fn contact_metrics(p: &ManipulatorParams, res: &Results, metrics: &mut Vec<Metric>) {
    let t = col(res, "t");
    // contact forces
    for (k, j) in ["J1", "J2", "J3", "J4"].iter().enumerate() {
        if p.clearances[k] > 0.0 {
            // the located impact peaks (clr-mbd `Results::impacts`), or the rows where larger
            let rows = common::peak_abs(&t, &col(res, &format!("{j}.normal_force")), 0.0);
            let located = res
                .impacts
                .iter()
                .filter(|i| i.joint == *j)
                .fold(rows, |a, i| a.max(i.peak_force));
            metrics.push(Metric::new(
                &format!("{j}_peak_contact_force"),
                located,
                "N",
                &format!(
                    "largest normal force in clearance joint {j}, located on the dense output"
                ),
            ));
            metrics.push(Metric::new(
                &format!("{j}_contact_time_fraction"),
                common::time_mean(&t, &col(res, &format!("{j}.contact")), 0.0),
                "-",
                &format!("fraction of the time with contact in {j}"),
            ));
        }
    }
}

/// Momentum drifts against their scales, and the friction-offset angular impulse.
fn momentum_metrics(
    p: &ManipulatorParams,
    res: &Results,
    scales: [f64; 2],
    metrics: &mut Vec<Metric>,
) {
    let t = col(res, "t");
    let last = t.len().saturating_sub(1);
    // momentum
    let drift = |name: &str| {
        let v = col(res, name);
        v.iter().map(|x| (x - v[0]).abs()).fold(0.0, f64::max)
    };
    let dp = drift("momentum.px").hypot(drift("momentum.py"));
    metrics.push(Metric::new(
        "linear_momentum_drift",
        dp / scales[0].max(f64::MIN_POSITIVE),
        "-",
        "max |p(t) − p(0)| / max Σ m_k|v_k| (zero for exact internal forces)",
    ));
    metrics.push(Metric::new(
        "angular_momentum_drift",
        drift("momentum.L") / scales[1].max(f64::MIN_POSITIVE),
        "-",
        "max |L(t) − L(0)| / max Σ (|I_k ω_k| + m_k|r_k × v_k|) about the origin",
    ));
    // clr-contact applies the contact pair at the two contact points r_i^Q, r_j^Q, which are
    // δ apart along n: the friction pair then has a net torque δ·F_T (n × t = 1), so the
    // angular momentum changes by ∫ Σ δ F_T dt. Reported to compare with the drift.
    let mut impulse = 0.0;
    for (k, j) in ["J1", "J2", "J3", "J4"].iter().enumerate() {
        if p.clearances[k] > 0.0 {
            let d = col(res, &format!("{j}.penetration"));
            let ft = col(res, &format!("{j}.friction_force"));
            let v: Vec<f64> = d.iter().zip(&ft).map(|(d, f)| d.max(0.0) * f).collect();
            impulse += common::time_mean(&t, &v, 0.0) * (t[last] - t[0]);
        }
    }
    let lcol = col(res, "momentum.L");
    metrics.push(Metric::new(
        "angular_momentum_change",
        lcol[last] - lcol[0],
        "kg*m^2/s",
        "L(t_end) − L(0) about the origin",
    ));
    metrics.push(Metric::new(
        "friction_offset_impulse",
        impulse,
        "kg*m^2/s",
        "∫ Σ δ·F_T dt over the clearance joints: the angular impulse of the friction pair \
         applied at contact points δ apart (clr-contact convention)",
    ));
    metrics.push(Metric::new(
        "linear_momentum_scale",
        scales[0],
        "kg*m/s",
        "max over the run of Σ m_k|v_k|",
    ));
    metrics.push(Metric::new(
        "angular_momentum_scale",
        scales[1],
        "kg*m^2/s",
        "max over the run of Σ (|I_k ω_k| + m_k|r_k × v_k|)",
    ));
}

/// Simulate the manipulator and its ideal counterpart (same parameters, all joints ideal) and
/// return the run with path errors, base motion, contact forces and momentum metrics.
///
/// # Errors
/// Invalid parameters, build or simulation errors.
pub fn run(
    model: &str,
    p: &ManipulatorParams,
    settings: &RunSettings,
) -> Result<RunOutput, ModelsError> {
    common::check_settings(model, settings)?;
    p.validate().map_err(|m| common::invalid(model, m))?;
    let ideal_p = ManipulatorParams {
        clearances: [0.0; 4],
        ..p.clone()
    };
    let (ideal, _) = simulate(model, &ideal_p, settings, true)?;
    let (mut res, scales) = simulate(model, p, settings, false)?;
    if let Some(cb) = &settings.progress {
        cb(settings.t_end.unwrap_or(p.duration));
    }
    let metrics = compare(p, &mut res, scales, &ideal);
    let params = serde_json::to_value(p).unwrap_or_default();
    Ok(common::output(model, res, metrics, params))
}

/// One case of the study: its name, metrics and wall time.
#[derive(Debug, Clone)]
pub struct CaseResult {
    /// Case name (`ideal`, `case1`, …).
    pub name: String,
    /// Metrics of [`run`] (path error, base, contact, momentum).
    pub metrics: Vec<Metric>,
    /// Wall time of the case, s.
    pub wall_s: f64,
}

impl CaseResult {
    /// A metric by name (NaN when absent).
    pub fn metric(&self, name: &str) -> f64 {
        crate::output::metric_value(&self.metrics, name)
    }
}

/// The paper's study: the ideal case and cases 1–5, run in parallel. Writes under `dir`:
/// `<case>.csv` (every column), `summary.csv` (metrics per case) and figures
/// (`paths`, `path_error`, `base_attitude`, `base_y`, `contact_force`, `orbits`, `momentum`).
///
/// # Errors
/// The first failing case, or an output error.
pub fn study(dir: &Path, duration: Option<f64>) -> Result<Vec<CaseResult>, String> {
    let settings = || RunSettings {
        t_end: duration,
        ..Default::default()
    };
    let runs: Vec<Result<(CaseResult, Results), String>> = CASES
        .par_iter()
        .map(|&name| {
            let start = std::time::Instant::now();
            let p = ManipulatorParams::case(name)?;
            let out = run("manipulator", &p, &settings()).map_err(|e| format!("{name}: {e}"))?;
            Ok((
                CaseResult {
                    name: name.to_string(),
                    metrics: out.metrics,
                    wall_s: start.elapsed().as_secs_f64(),
                },
                out.results,
            ))
        })
        .collect();
    let mut cases = Vec::new();
    let mut results = Vec::new();
    for r in runs {
        let (c, res) = r?;
        common::write_results_csv(&res, dir, &c.name)?;
        cases.push(c);
        results.push(res);
    }
    write_summary(dir, &cases)?;
    figures(dir, &cases, &results)?;
    Ok(cases)
}

fn write_summary(dir: &Path, cases: &[CaseResult]) -> Result<(), String> {
    let runs: Vec<_> = cases
        .iter()
        .map(|c| (vec![c.name.clone()], c.wall_s, c.metrics.as_slice()))
        .collect();
    common::write_study_summary(dir, &["case"], &runs)
}

fn figures(dir: &Path, cases: &[CaseResult], results: &[Results]) -> Result<(), String> {
    use clr_plot::Figure;
    let save = |f: Figure, name: &str| common::save_figure(f, dir, name);
    const MAX: usize = 3000;
    let mut paths = Figure::new("End-effector paths (manipulator 1 right, 2 left)")
        .x_label("x (m)")
        .y_label("y (m)");
    let mut err = Figure::new("End-effector path error against the ideal case (manipulator 1)")
        .x_label("time (s)")
        .y_label("path error (m)");
    let mut att = Figure::new("Base attitude")
        .x_label("time (s)")
        .y_label("base angle (rad)");
    let mut by = Figure::new("Base centre y")
        .x_label("time (s)")
        .y_label("y (m)");
    let mut force = Figure::new("Contact force in joint J2")
        .x_label("time (s)")
        .y_label("normal force (N)");
    let mut orbits = Figure::new("Journal-centre orbits in joint J2 (bearing frame)")
        .x_label("e_x (mm)")
        .y_label("e_y (mm)")
        .equal_aspect();
    let mut mom = Figure::new("Angular momentum about the origin")
        .x_label("time (s)")
        .y_label("L (kg·m²/s)");
    for (c, r) in cases.iter().zip(results) {
        let t = col(r, "t");
        let name = c.name.as_str();
        if name == "ideal" || name == "case5" || name == "case3" {
            paths = paths
                .line(
                    format!("{name} arm 1"),
                    common::thin(&col(r, "ee1.x"), &col(r, "ee1.y"), MAX),
                )
                .line(
                    format!("{name} arm 2"),
                    common::thin(&col(r, "ee2.x"), &col(r, "ee2.y"), MAX),
                );
        }
        att = att.line(name, common::thin(&t, &col(r, "base.theta"), MAX));
        by = by.line(name, common::thin(&t, &col(r, "base.y"), MAX));
        mom = mom.line(name, common::thin(&t, &col(r, "momentum.L"), MAX));
        if name != "ideal" {
            err = err.line(name, common::thin(&t, &col(r, "ee1.error"), MAX));
        }
        if r.index("J2.normal_force").is_some() {
            force = force.line(name, common::thin(&t, &col(r, "J2.normal_force"), MAX));
            let ex: Vec<f64> = col(r, "J2.ex").iter().map(|v| v * 1e3).collect();
            let ey: Vec<f64> = col(r, "J2.ey").iter().map(|v| v * 1e3).collect();
            orbits = orbits.line(name, common::thin(&ex, &ey, MAX));
        }
    }
    save(paths, "paths")?;
    save(err, "path_error")?;
    save(att, "base_attitude")?;
    save(by, "base_y")?;
    save(force, "contact_force")?;
    save(orbits, "orbits")?;
    save(mom, "momentum")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ideal_free_floating_system_conserves_momentum() {
        // closed form: with only internal forces (joint reactions and joint torques) the linear
        // and angular momentum stay at their initial value (zero) — short ideal run
        let p = ManipulatorParams {
            duration: 0.2,
            ..ManipulatorParams::case("ideal").unwrap()
        };
        let out = run("manipulator", &p, &RunSettings::default()).unwrap();
        let m = |n: &str| out.metrics.iter().find(|m| m.name == n).unwrap().value;
        assert!(
            m("linear_momentum_drift") < 1e-10,
            "{}",
            m("linear_momentum_drift")
        );
        assert!(
            m("angular_momentum_drift") < 1e-8,
            "{}",
            m("angular_momentum_drift")
        );
        // the ideal run against itself has no path error (same model, interpolated reference)
        assert!(m("path_error_max") < 1e-6, "{}", m("path_error_max"));
    }

    #[test]
    fn unknown_case_lists_the_valid_ones() {
        let e = ManipulatorParams::case("case9").unwrap_err();
        assert!(e.contains("case5"), "{e}");
    }
}
