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

/// The model and run settings that [`run`] simulates: [`ManipulatorParams::desc`] with the end
/// time and tolerance of `settings` (when given) written into `solver` and `output`, and the
/// derived columns and metrics as data ([`derived`]), the ideal-joint reference among them as
/// the description's `[twin]`.
///
/// # Errors
/// Invalid parameters or run settings.
pub fn run_desc(
    model: &str,
    p: &ManipulatorParams,
    settings: &RunSettings,
) -> Result<ModelDesc, ModelsError> {
    let mut d = common::run_desc(model, settings, Record::EveryStep, || p.desc(model))?;
    derived(&mut d, p);
    Ok(d)
}

/// The derived columns as `[[measure]]` items and the ideal reference as `[twin]`: the
/// end-effector positions `ee1.x ee1.y ee2.x ee2.y` (tips of links 2 and 4, m); the system
/// momentum about the origin over the five bodies, `momentum.px momentum.py` (kg·m/s),
/// `momentum.L` (kg·m²/s, L = Σ I_k ω_k + m_k (x_k v_yk − y_k v_xk)) with its scales
/// `momentum.p_scale` = Σ m_k|v_k| and `momentum.L_scale` = Σ (|I_k ω_k| + m_k|r_k × v_k|);
/// `base_displacement.distance` (m), the base centre's distance from the ground origin, where
/// it starts; `friction_offset.value` (N·m), Σ δ·F_T over the clearance joints (the moment of
/// a friction pair applied at contact points δ apart); and the deviations from the ideal-joint
/// twin (the same system with every joint ideal, recorded every `reference_interval` s and
/// interpolated linearly): `ee1.error`, `ee2.error` (end-effector distance from the ideal
/// path, m), `base_position.error` (m) and `base_attitude.error` (rad).
fn derived(d: &mut ModelDesc, p: &ManipulatorParams) {
    use clr_mbd::measure::combination::{Columns, Combination, Term};
    use clr_mbd::measure::deviation::{Deviation, TwinSettings};
    use clr_mbd::measure::{distance::Distance, momentum::Momentum, point::Position};
    use clr_mbd::{Anchor, Measure};
    let local = |body: &str, at: [f64; 2]| Anchor::Local(body.into(), at);
    for (ee, body) in [("ee1", "arm2"), ("ee2", "arm4")] {
        d.measures.push(Measure::Position(Position {
            name: ee.into(),
            at: local(body, [0.5 * p.link_length, 0.0]),
            frame: None,
        }));
    }
    d.measures.push(Measure::Momentum(Momentum {
        name: "momentum".into(),
        bodies: Some(BODIES.map(String::from).to_vec()),
        about: None,
        scales: true,
    }));
    d.measures.push(Measure::Distance(Distance {
        name: "base_displacement".into(),
        a: local(clr_mbd::GROUND, [0.0, 0.0]),
        b: local("base", [0.0, 0.0]),
    }));
    // the moment δ·F_T of the friction pairs, with a clearance joint only (an ideal joint has no
    // contact columns)
    let terms: Vec<Term> = (clearance_joints(p))
        .map(|j| Term {
            of: Columns::Many(vec![
                format!("{j}.penetration"),
                format!("{j}.friction_force"),
            ]),
            factor: 1.0,
            abs: false,
        })
        .collect();
    if !terms.is_empty() {
        d.measures.push(Measure::Combination(Combination {
            name: "friction_offset".into(),
            terms,
            unit: Some("N*m".into()),
        }));
    }
    let deviations = [
        ("ee1", ["ee1.x", "ee1.y"].as_slice()),
        ("ee2", &["ee2.x", "ee2.y"]),
        ("base_position", &["base.x", "base.y"]),
        ("base_attitude", &["base.theta"]),
    ];
    for (name, of) in deviations {
        d.measures.push(Measure::Deviation(Deviation {
            name: name.into(),
            of: of.iter().map(|c| c.to_string()).collect(),
            suffix: None,
        }));
    }
    let t_end = d.output.t_end.unwrap_or(p.duration);
    // as the reference run before: a row every `reference_interval` s
    d.twin = Some(TwinSettings {
        intervals: Some(((t_end / p.reference_interval).round() as usize).max(1)),
    });
    d.metrics = metrics(p);
}

/// The joints J1 … J4 that have a clearance.
fn clearance_joints(p: &ManipulatorParams) -> impl Iterator<Item = &'static str> + '_ {
    (["J1", "J2", "J3", "J4"].into_iter())
        .zip(p.clearances)
        .filter(|(_, c)| *c > 0.0)
        .map(|(j, _)| j)
}

/// The metrics of the columns of [`derived`]: path error, base motion, contact per clearance
/// joint, momentum.
fn metrics(p: &ManipulatorParams) -> Vec<clr_mbd::desc::metric::MetricDesc> {
    use clr_mbd::desc::metric::{MetricDesc, Statistic};
    let m = |name: &str, of: &[&str], stat, words: &str| {
        MetricDesc::of_columns(name, of, stat).described(words)
    };
    let ee = ["ee1.error", "ee2.error"];
    let mut out = vec![
        m(
            "path_error_max",
            &ee,
            Statistic::Peak,
            "largest end-effector distance from the ideal path (both manipulators)",
        ),
        m(
            "path_error_rms",
            &ee,
            Statistic::Rms,
            "time RMS of the end-effector distance from the ideal path over both end effectors",
        ),
    ];
    for (k, arm) in ["1", "2"].iter().enumerate() {
        out.push(m(
            &format!("path_error_max_arm{arm}"),
            &[ee[k]],
            Statistic::Peak,
            &format!("largest end-effector path error of manipulator {arm}"),
        ));
        out.push(m(
            &format!("path_error_rms_arm{arm}"),
            &[ee[k]],
            Statistic::Rms,
            &format!("time RMS of the end-effector path error of manipulator {arm}"),
        ));
    }
    out.extend([
        m(
            "base_displacement_max",
            &["base_displacement.distance"],
            Statistic::Max,
            "largest displacement of the base centre from its initial position",
        ),
        m(
            "base_attitude_max",
            &["base.theta"],
            Statistic::Peak,
            "largest |base attitude angle|",
        ),
        m(
            "base_position_deviation_max",
            &["base_position.error"],
            Statistic::Peak,
            "largest distance of the base centre from its ideal-case position",
        ),
        m(
            "base_attitude_deviation_max",
            &["base_attitude.error"],
            Statistic::Peak,
            "largest |base attitude − ideal-case attitude|",
        ),
        m(
            "base_y_final",
            &["base.y"],
            Statistic::Final,
            "base centre y at the end of the run",
        ),
    ]);
    for j in clearance_joints(p) {
        out.push(m(
            &format!("{j}_peak_contact_force"),
            &[&format!("{j}.normal_force")],
            Statistic::Peak,
            &format!("largest normal force in clearance joint {j}, located on the dense output"),
        ));
        out.push(m(
            &format!("{j}_contact_time_fraction"),
            &[&format!("{j}.contact")],
            Statistic::Mean,
            &format!("fraction of the time with contact in {j}"),
        ));
    }
    out.extend(momentum_metrics(clearance_joints(p).next().is_some()));
    out
}

/// Momentum scales, drifts against them, the change of L and, with a clearance joint, the
/// friction-offset impulse.
fn momentum_metrics(clearance: bool) -> Vec<clr_mbd::desc::metric::MetricDesc> {
    use clr_mbd::desc::metric::{Divisor, MetricDesc, Statistic};
    let m = |name: &str, of: &[&str], stat, words: &str| {
        MetricDesc::of_columns(name, of, stat).described(words)
    };
    let per = |scale: &str| Divisor::Metric(scale.into());
    let mut v = vec![
        // the scales come first: the drifts are divided by them
        m(
            "linear_momentum_scale",
            &["momentum.p_scale"],
            Statistic::Max,
            "max over the run of Σ m_k|v_k|",
        ),
        m(
            "angular_momentum_scale",
            &["momentum.L_scale"],
            Statistic::Max,
            "max over the run of Σ (|I_k ω_k| + m_k|r_k × v_k|)",
        ),
        m(
            "linear_momentum_drift",
            &["momentum.px", "momentum.py"],
            Statistic::Drift,
            "max over the components of max |p_i(t) − p_i(0)|, / max Σ m_k|v_k| (zero for \
             exact internal forces)",
        )
        .per(per("linear_momentum_scale")),
        m(
            "angular_momentum_drift",
            &["momentum.L"],
            Statistic::Drift,
            "max |L(t) − L(0)| / max Σ (|I_k ω_k| + m_k|r_k × v_k|) about the origin",
        )
        .per(per("angular_momentum_scale")),
        m(
            "angular_momentum_change",
            &["momentum.L"],
            Statistic::Change,
            "L(t_end) − L(0) about the origin",
        ),
    ];
    if clearance {
        // clr-contact's `contact_points` form applies the contact pair at the two contact
        // points r_i^Q, r_j^Q, δ apart along n: the friction pair then has a net torque δ·F_T
        // (n × t = 1), so L changes by ∫ Σ δ F_T dt. Reported to compare with the change.
        let impulse = m(
            "friction_offset_impulse",
            &["friction_offset.value"],
            Statistic::Integral,
            "∫ Σ δ·F_T dt over the clearance joints: the angular impulse of the friction pair \
             applied at contact points δ apart (clr-contact convention)",
        )
        .in_unit("kg*m^2/s");
        v.push(impulse);
    }
    v
}

/// Simulate the manipulator and its ideal-joint twin (same parameters, every joint ideal) and
/// compute the derived columns and the metrics of [`derived`] from the description, as a run
/// of its exported file does: path errors, base motion, contact forces and momentum.
///
/// # Errors
/// Invalid parameters, build or simulation errors.
pub fn run(
    model: &str,
    p: &ManipulatorParams,
    settings: &RunSettings,
) -> Result<RunOutput, ModelsError> {
    crate::described_metrics::run_output(model, &run_desc(model, p, settings)?, settings, p)
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
