//! Flap actuation system of Wan, Liu, Liu, Tong, Ma, *Machines* 10 (2022) 1098
//! (paper-systems.md §1) — first part: the flexible parts' section calibration.
//!
//! **Known from the paper:** the first five eigenfrequencies of the auxiliary lever arm
//! (3715.8, 5437.1, 7921.3, 7946.1, 7971.7 Hz), the auxiliary rod (690.40, 1648.66, 1869.88,
//! 2143.10, 3588.54 Hz) and the lever arm (5839.3, 6201.3, 7240.9, 7976.3, 9260.8 Hz).
//!
//! **Reconstructed:** each part is a planar Euler–Bernoulli beam (clr-beam, 20 elements,
//! consistent mass) of steel (207 GPa, 7800 kg/m³), a rectangular section of width 15 mm (the
//! bearing length L of the paper) and a depth calibrated so that the first computed frequency
//! equals the paper's; pinned at one end and on a roller along the axis at the other (the
//! parts are links between two revolute joints); lengths 0.10 m (lever arm), 0.30 m
//! (auxiliary rod), 0.12 m (auxiliary lever arm). A planar beam has only in-plane bending and
//! axial modes: the paper's higher modes of the 3-D parts (out-of-plane bending, torsion) are
//! not reproduced.
//!
//! Second part: the rigid linkage ([`FlapParams`], [`run`], [`study`]) with up to four
//! revolute clearance joints, its closed-form ideal kinematics ([`FlapParams::ideal_flap_angle`])
//! and the clearance studies. With [`FlapParams::flexible`] the lever arm, auxiliary rod and
//! auxiliary lever arm become floating-frame beam bodies of the calibrated sections; the model
//! and the flexible-body studies are in [`crate::flap_flex`] (docs/models/flap.md).

use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

use clr_mbd::{
    Anchor, Model, ModelBuilder, ModelDesc, Results, RevoluteClearanceSpec, RigidBody, TimeFn,
};
use rayon::prelude::*;

use crate::common::{self, col, non_negative, positive, Record};
use crate::{Metric, ModelsError, RunOutput, RunSettings};

pub use crate::flap_params::{Calibration, FlapParams, FlexiblePart, JOINTS, PAPER_FREQUENCIES};

/// A joint of the linkage: (name, bearing anchor, journal anchor).
type JointSpec<'a> = (&'a str, Anchor, Anchor);

/// Smooth step r(t) = 3s² − 2s³, s = t/T (clamped), with r′ and r″.
fn smoothstep(t: f64, ramp: f64) -> [f64; 3] {
    if ramp <= 0.0 || t >= ramp {
        return [1.0, 0.0, 0.0];
    }
    let s = (t / ramp).max(0.0);
    [
        s * s * (3.0 - 2.0 * s),
        6.0 * s * (1.0 - s) / ramp,
        (6.0 - 12.0 * s) / (ramp * ramp),
    ]
}

/// Intersection of the circles |P − a| = ra and |P − b| = rb on the left of a→b (sign +1) or
/// the right (sign −1); `None` when they do not meet.
fn circle_intersection(a: [f64; 2], ra: f64, b: [f64; 2], rb: f64, sign: f64) -> Option<[f64; 2]> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let d = dx.hypot(dy);
    let l = (ra * ra - rb * rb + d * d) / (2.0 * d);
    let h2 = ra * ra - l * l;
    if d.is_nan() || d <= 0.0 || h2 < 0.0 {
        return None;
    }
    let h = h2.sqrt();
    let (ux, uy) = (dx / d, dy / d);
    Some([a[0] + l * ux - sign * h * uy, a[1] + l * uy + sign * h * ux])
}

impl FlapParams {
    /// Actuator extension x(t) = A·r(t)·sin(2πft) with its first two derivatives (m, m/s,
    /// m/s²); r is the smooth-step ramp over `ramp_time`.
    pub fn actuator(&self, t: f64) -> [f64; 3] {
        let w = 2.0 * PI * self.actuator_frequency;
        let (s, c) = (w * t).sin_cos();
        let [r, rd, rdd] = smoothstep(t, self.ramp_time);
        let a = self.actuator_amplitude;
        [
            a * r * s,
            a * (rd * s + r * w * c),
            a * (rdd * s + 2.0 * rd * w * c - r * w * w * s),
        ]
    }

    /// The actuator extension s0 + x(t) as data: a smooth step (fade-in over `ramp_time`) times
    /// a harmonic of amplitude `actuator_amplitude` at `actuator_frequency` (the same function
    /// as [`FlapParams::actuator`]).
    pub fn actuator_motion(&self, s0: f64) -> TimeFn {
        let w = 2.0 * PI * self.actuator_frequency;
        let wave = TimeFn::harmonic(0.0, self.actuator_amplitude, w, 0.0);
        let x = if self.ramp_time > 0.0 {
            TimeFn::Product {
                factors: vec![
                    TimeFn::SmoothStep {
                        from: 0.0,
                        to: 1.0,
                        start: 0.0,
                        duration: self.ramp_time,
                    },
                    wave,
                ],
            }
        } else {
            wave
        };
        TimeFn::Sum {
            terms: vec![TimeFn::constant(s0), x],
        }
    }

    /// Actuator period 1/f, s.
    pub fn period(&self) -> f64 {
        1.0 / self.actuator_frequency
    }

    /// Ground points: actuator pivot C0, lever-arm pivot O1, auxiliary-lever pivot O2 (m).
    pub fn ground_points(&self) -> [[f64; 2]; 3] {
        let a = self.lever_arm_actuator_distance;
        let b = self.lever_arm_length;
        [
            [-self.actuator_length, a],
            [0.0, 0.0],
            [self.aux_rod_length, b - self.aux_lever_arm_length],
        ]
    }

    /// Flap angle (auxiliary-lever angle minus its initial value π/2, rad) of the ideal
    /// mechanism at actuator extension `x`, with auxiliary rod length `rod_length`, by two
    /// circle intersections (independent of clr-mbd): J1 on the circle of radius a about O1 at
    /// distance s0 + x from C0 gives the lever angle; J4 on the circle of radius c about O2 at
    /// distance `rod_length` from J3 gives the auxiliary-lever angle. `None` when the linkage
    /// cannot be assembled.
    pub fn ideal_flap_angle(&self, x: f64, rod_length: f64) -> Option<f64> {
        let [c0, o1, o2] = self.ground_points();
        let a = self.lever_arm_actuator_distance;
        // J1: |J1 − O1| = a, |J1 − C0| = s0 + x, above the line C0→O1 side (lever up): the
        // lever points up at t = 0, J1 = (0, a), which is on the left of O1→C0? use the branch
        // that contains the assembly configuration
        let j1 = [
            circle_intersection(o1, a, c0, self.actuator_length + x, 1.0)?,
            circle_intersection(o1, a, c0, self.actuator_length + x, -1.0)?,
        ];
        let j1 = if j1[0][1] > j1[1][1] { j1[0] } else { j1[1] };
        let phi = j1[1].atan2(j1[0]);
        let b = self.lever_arm_length;
        let j3 = [o1[0] + b * phi.cos(), o1[1] + b * phi.sin()];
        let cands = [
            circle_intersection(o2, self.aux_lever_arm_length, j3, rod_length, 1.0)?,
            circle_intersection(o2, self.aux_lever_arm_length, j3, rod_length, -1.0)?,
        ];
        let j4 = if cands[0][1] > cands[1][1] {
            cands[0]
        } else {
            cands[1]
        };
        Some((j4[1] - o2[1]).atan2(j4[0] - o2[0]) - FRAC_PI_2)
    }

    /// Combined auxiliary lever arm + flap in the lever frame (origin at O2, x along O2→J4):
    /// (mass, inertia about the combined centre of mass, centre of mass).
    pub(crate) fn aux_lever_with_flap(&self) -> (f64, f64, [f64; 2]) {
        let c = self.aux_lever_arm_length;
        let (ml, mf) = (self.aux_lever_arm_mass, self.flap_mass);
        let rl = [0.5 * c, 0.0];
        // flap chord along world +x when the lever points up (+y): local (0, −d)
        let rf = [0.0, -self.flap_cg_distance];
        let m = ml + mf;
        let rc = [(ml * rl[0] + mf * rf[0]) / m, (ml * rl[1] + mf * rf[1]) / m];
        let d2 = |r: [f64; 2]| (r[0] - rc[0]).powi(2) + (r[1] - rc[1]).powi(2);
        let i = ml * c * c / 12.0 + ml * d2(rl) + self.flap_inertia + mf * d2(rf);
        (m, i, rc)
    }

    /// Parameters these settings do not use, with the reason: the contact-law parameters when no
    /// joint has a clearance, `axial_length` unless the law is `Wang` or `Modified`, and the
    /// flexible-body settings when every part is rigid.
    pub fn unused(&self) -> Vec<(&'static str, String)> {
        let mut v = Vec::new();
        if self.clearances.iter().all(|&c| c <= 0.0) {
            for p in [
                "bearing_radius",
                "axial_length",
                "youngs_modulus",
                "poisson_ratio",
                "normal_law",
                "restitution",
                "friction",
            ] {
                v.push((
                    p,
                    "every joint is ideal (clearances all 0): no contact law".into(),
                ));
            }
        } else if !clr_contact::normal::preset_uses_length(&self.normal_law) {
            v.push((
                "axial_length",
                format!(
                    "normal_law = \"{}\" has no axial length (only Wang and Modified use it)",
                    self.normal_law
                ),
            ));
        }
        if !self.flexible.iter().any(|&f| f) {
            for p in ["flexible_modes", "flexible_damping_ratios"] {
                v.push((
                    p,
                    "every part is rigid (flexible = [false, false, false])".into(),
                ));
            }
        }
        v
    }

    /// Check every value; the message names the field to change.
    ///
    /// # Errors
    /// A message naming the field.
    pub fn validate(&self) -> Result<(), String> {
        for (f, v) in [
            ("actuator_amplitude", self.actuator_amplitude),
            ("actuator_frequency", self.actuator_frequency),
            ("actuator_length", self.actuator_length),
            ("cylinder_mass", self.cylinder_mass),
            ("cylinder_length", self.cylinder_length),
            ("piston_mass", self.piston_mass),
            ("piston_length", self.piston_length),
            ("lever_arm_length", self.lever_arm_length),
            (
                "lever_arm_actuator_distance",
                self.lever_arm_actuator_distance,
            ),
            ("lever_arm_mass", self.lever_arm_mass),
            ("aux_rod_length", self.aux_rod_length),
            ("aux_rod_mass", self.aux_rod_mass),
            ("aux_lever_arm_length", self.aux_lever_arm_length),
            ("aux_lever_arm_mass", self.aux_lever_arm_mass),
            ("flap_mass", self.flap_mass),
            ("flap_inertia", self.flap_inertia),
            ("bearing_radius", self.bearing_radius),
            ("axial_length", self.axial_length),
            ("youngs_modulus", self.youngs_modulus),
            ("duration", self.duration),
            ("rtol", self.rtol),
            ("reference_interval", self.reference_interval),
        ] {
            positive(f, v)?;
        }
        for (f, v) in [
            ("ramp_time", self.ramp_time),
            ("transient", self.transient),
            ("flap_cg_distance", self.flap_cg_distance),
        ] {
            non_negative(f, v)?;
        }
        for (f, v) in [
            ("hinge_moment", self.hinge_moment),
            ("hinge_stiffness", self.hinge_stiffness),
        ] {
            if !v.is_finite() {
                return Err(format!("`{f}` = {v} must be finite"));
            }
        }
        if self.actuator_amplitude >= 0.5 * self.actuator_length {
            return Err(format!(
                "`actuator_amplitude` = {} m must be below half of `actuator_length` = {} m",
                self.actuator_amplitude, self.actuator_length
            ));
        }
        if self.actuator_amplitude >= 0.5 * self.lever_arm_actuator_distance {
            return Err(format!(
                "`actuator_amplitude` = {} m must be below half of \
                 `lever_arm_actuator_distance` = {} m (the lever would swing past ±30°)",
                self.actuator_amplitude, self.lever_arm_actuator_distance
            ));
        }
        for (k, &c) in self.clearances.iter().enumerate() {
            non_negative(&format!("clearances[{k}]"), c)?;
            if c >= 0.1 * self.bearing_radius {
                return Err(format!(
                    "`clearances[{k}]` = {c} m must be below a tenth of `bearing_radius` = {} m",
                    self.bearing_radius
                ));
            }
        }
        for (k, &z) in self.flexible_damping_ratios.iter().enumerate() {
            if !(z.is_finite() && (0.0..=10.0).contains(&z)) {
                return Err(format!(
                    "`flexible_damping_ratios[{k}]` = {z} must be in [0, 10]"
                ));
            }
        }
        if self.flexible[0] {
            let n = self.lever_arm_actuator_distance / self.lever_arm_length
                * crate::flap_flex::ELEMENTS as f64;
            if (n - n.round()).abs() > 1e-9 || n.round() < 1.0 {
                return Err(format!(
                    "a flexible lever arm needs `lever_arm_actuator_distance` = {} m at a beam \
                     node: a multiple of `lever_arm_length`/{} = {} m",
                    self.lever_arm_actuator_distance,
                    crate::flap_flex::ELEMENTS,
                    self.lever_arm_length / crate::flap_flex::ELEMENTS as f64
                ));
            }
        }
        if self.poincare_phases == 0 {
            return Err("`poincare_phases` must be at least 1".into());
        }
        if self.duration / self.reference_interval > 1e6 {
            return Err(format!(
                "`reference_interval` = {} s gives more than 1e6 reference rows over {} s; \
                 make it larger",
                self.reference_interval, self.duration
            ));
        }
        let x = self.actuator_amplitude;
        for xi in [-x, x] {
            if self.ideal_flap_angle(xi, self.aux_rod_length).is_none() {
                return Err(format!(
                    "the linkage cannot be assembled at actuator extension {xi} m; shorten \
                     `actuator_amplitude` or change the link lengths"
                ));
            }
        }
        Ok(())
    }

    /// The clr-mbd model ([`FlapParams::desc`] compiled).
    ///
    /// # Errors
    /// Invalid parameters or a clr-mbd build error.
    pub fn build(&self, model: &str) -> Result<Model, ModelsError> {
        common::compile(model, &self.desc(model)?)
    }

    /// The model as data, with the run settings of the clearance run of `clr run <model>` (no
    /// `--t-end` or `--rtol`) in `solver` and `output`: the `solver` and `rtol` parameters,
    /// atol = rtol·10⁻³, 0 to `duration` s, every accepted step recorded. Bodies `cylinder`,
    /// `piston`, `lever_arm`, `aux_rod`, `aux_lever_arm` (with the flap; flexible parts per
    /// [`FlapParams::flexible`] are floating-frame bodies of the same names, the flap then a
    /// body `flap`); ideal joints `C0` (ground–cylinder), `actuator` (translational
    /// cylinder–piston), `O2` (ground–auxiliary lever arm); driver `x`; joints `J1`..`J4` ideal
    /// or clearance per [`FlapParams::clearances`]; torque `hinge`. `model` names the model in
    /// errors and in `[model]`.
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn desc(&self, model: &str) -> Result<ModelDesc, ModelsError> {
        self.validate().map_err(|m| common::invalid(model, m))?;
        self.friction.law().map_err(|m| common::invalid(model, m))?;
        let friction = self.friction.desc();
        let [c0, o1, o2] = self.ground_points();
        let (a, b) = (self.lever_arm_actuator_distance, self.lever_arm_length);
        let (lr, lc, lp) = (
            self.aux_rod_length,
            self.cylinder_length,
            self.piston_length,
        );
        let mut m = ModelBuilder::new();
        if self.gravity {
            m.gravity(0.0, -9.81);
        }
        let bar = |mass: f64, len: f64| RigidBody::new(mass, mass * len * len / 12.0);
        m.body(
            "cylinder",
            bar(self.cylinder_mass, lc).at(c0[0] + 0.5 * lc, c0[1], 0.0),
        )
        .body("piston", bar(self.piston_mass, lp).at(-0.5 * lp, a, 0.0));
        let c = self.aux_lever_arm_length;
        let local = |body: &str, x: f64, y: f64| Anchor::Local(body.to_string(), [x, y]);
        let node = |body: &str, n: usize| Anchor::BeamNode(body.to_string(), n);
        let last = crate::flap_flex::ELEMENTS;
        // lever arm: anchors of J1, O1 (J2) and J3
        let lever = if self.flexible[0] {
            crate::flap_flex::add_part(&mut m, self, 0, o1, FRAC_PI_2)
                .map_err(|e| common::invalid(model, e))?;
            let n1 = (a / b * last as f64).round() as usize;
            [
                node("lever_arm", n1),
                node("lever_arm", 0),
                node("lever_arm", last),
            ]
        } else {
            m.body(
                "lever_arm",
                bar(self.lever_arm_mass, b).at(0.0, 0.5 * b, FRAC_PI_2),
            );
            [
                local("lever_arm", a - 0.5 * b, 0.0),
                local("lever_arm", -0.5 * b, 0.0),
                local("lever_arm", 0.5 * b, 0.0),
            ]
        };
        // auxiliary rod: anchors of J3 and J4
        let rod = if self.flexible[1] {
            crate::flap_flex::add_part(&mut m, self, 1, [o1[0], o1[1] + b], 0.0)
                .map_err(|e| common::invalid(model, e))?;
            [node("aux_rod", 0), node("aux_rod", last)]
        } else {
            m.body("aux_rod", bar(self.aux_rod_mass, lr).at(0.5 * lr, b, 0.0));
            [
                local("aux_rod", -0.5 * lr, 0.0),
                local("aux_rod", 0.5 * lr, 0.0),
            ]
        };
        // auxiliary lever arm: anchors of O2 and J4; the body carrying the hinge moment and
        // its angle at t = 0
        let (aux, hinge_body, th0) = if self.flexible[2] {
            crate::flap_flex::add_part(&mut m, self, 2, o2, FRAC_PI_2)
                .map_err(|e| common::invalid(model, e))?;
            // the flap: a rigid body fixed to the arm's reference (pivot) node, chord along +x
            let d = self.flap_cg_distance;
            m.body(
                "flap",
                RigidBody::new(self.flap_mass, self.flap_inertia).at(o2[0] + d, o2[1], 0.0),
            )
            .fixed("flap_mount", node("aux_lever_arm", 0), ("flap", [-d, 0.0]));
            (
                [node("aux_lever_arm", 0), node("aux_lever_arm", last)],
                "flap",
                0.0,
            )
        } else {
            let (mal, ial, rc) = self.aux_lever_with_flap();
            m.body(
                "aux_lever_arm",
                // lever frame rotated by π/2: local (u, v) → world (−v, u)
                RigidBody::new(mal, ial).at(o2[0] - rc[1], o2[1] + rc[0], FRAC_PI_2),
            );
            (
                [
                    local("aux_lever_arm", -rc[0], -rc[1]),
                    local("aux_lever_arm", c - rc[0], -rc[1]),
                ],
                "aux_lever_arm",
                FRAC_PI_2,
            )
        };
        let [l_j1, l_o1, l_j3] = lever;
        let [r_j3, r_j4] = rod;
        let [a_o2, a_j4] = aux;
        // same item order as before the flexible parts existed (identical rigid model)
        m.revolute("C0", ("ground", c0), ("cylinder", [-0.5 * lc, 0.0]))
            .translational(
                "actuator",
                ("cylinder", [-0.5 * lc, 0.0]),
                ("piston", [0.0, 0.0]),
                [1.0, 0.0],
            )
            .revolute("O2", ("ground", o2), a_o2);
        let s0 = self.actuator_length;
        m.drive_displacement(
            "x",
            ("cylinder", [-0.5 * lc, 0.0]),
            ("piston", [0.5 * lp, 0.0]),
            [1.0, 0.0],
            self.actuator_motion(s0),
        );
        // (name, bearing anchor, journal anchor)
        let joints: [JointSpec; 4] = [
            ("J1", l_j1, local("piston", 0.5 * lp, 0.0)),
            ("J2", Anchor::Local("ground".into(), o1), l_o1),
            ("J3", r_j3, l_j3),
            ("J4", r_j4, a_j4),
        ];
        self.add_joints(&mut m, model, joints, &friction)?;
        let (m0, k) = (self.hinge_moment, self.hinge_stiffness);
        // hinge moment −(M0 + k(θ − θ0)): a constant torque plus a rotational spring to ground
        m.torque("hinge", hinge_body, TimeFn::constant(-m0))
            .rotational_spring_damper("hinge_stiffness", "ground", hinge_body, k, 0.0, th0);
        Ok(common::finish_desc(
            m,
            model,
            self.duration,
            self.rtol,
            self.solver,
        ))
    }

    /// Joints J1..J4 (name, bearing anchor, journal anchor): a revolute clearance joint where
    /// [`FlapParams::clearances`] gives a clearance, else an ideal revolute joint.
    fn add_joints(
        &self,
        m: &mut ModelBuilder,
        model: &str,
        joints: [JointSpec; 4],
        friction: &clr_mbd::FrictionLawDesc,
    ) -> Result<(), ModelsError> {
        for (k, (name, bi, bj)) in joints.into_iter().enumerate() {
            let cl = self.clearances[k];
            if cl > 0.0 {
                // validated here for the parameter-level message; the model gets it as data
                common::preset_law(
                    &self.normal_law,
                    self.youngs_modulus,
                    self.poisson_ratio,
                    self.bearing_radius,
                    self.bearing_radius - cl,
                    self.axial_length,
                    self.restitution,
                )
                .map_err(|m| common::invalid(model, m))?;
                let normal = common::preset_desc(
                    &self.normal_law,
                    self.youngs_modulus,
                    self.poisson_ratio,
                    self.axial_length,
                    self.restitution,
                );
                m.revolute_clearance(
                    name,
                    bi,
                    bj,
                    RevoluteClearanceSpec {
                        bearing_radius: self.bearing_radius,
                        journal_radius: self.bearing_radius - cl,
                        normal: normal.into(),
                        friction: friction.clone().into(),
                    },
                );
            } else {
                m.revolute(name, bi, bj);
            }
        }
        Ok(())
    }
}

/// The model and run settings of [`run`]: [`FlapParams::desc`] with the end time and
/// tolerance of `settings` (when given) written into `solver` and `output`, and the flap's
/// derived columns and metrics as its measures, `[twin]` and metrics ([`derived`]).
///
/// # Errors
/// Invalid parameters or run settings.
pub fn run_desc(
    model: &str,
    p: &FlapParams,
    settings: &RunSettings,
) -> Result<ModelDesc, ModelsError> {
    let mut d = common::run_desc(model, settings, Record::EveryStep, || p.desc(model))?;
    derived(&mut d, p);
    Ok(d)
}

/// The flap angle measures: `flap.angle` (rad, from the initial position: the rigid auxiliary
/// lever arm's angle − π/2, or the flap body's when that arm is flexible, the flap then being a
/// rigid body fixed to the arm's pivot node and starting at 0) and `flap.alpha` (rad/s², the
/// flap body's own column when the arm is flexible).
fn angle_measures(d: &mut ModelDesc, p: &FlapParams) {
    use clr_mbd::measure::angle::{Angle, AngularAcceleration};
    use clr_mbd::Measure;
    let (body, offset) = if p.flexible[2] {
        ("flap", 0.0)
    } else {
        ("aux_lever_arm", FRAC_PI_2)
    };
    d.measures.push(Measure::Angle(Angle {
        name: "flap".into(),
        body: body.into(),
        relative_to: None,
        offset,
    }));
    if !p.flexible[2] {
        d.measures
            .push(Measure::AngularAcceleration(AngularAcceleration {
                name: "flap".into(),
                body: body.into(),
                relative_to: None,
            }));
    }
}

/// The flap's derived columns and metrics as measures, `[twin]` and metrics of its
/// description, so that `clr run flap` and its exported file compute them the same way:
/// `flap.angle`, `flap.alpha` ([`angle_measures`]); `flap.error` (rad) and `flap.alpha_error`
/// (rad/s²), their deviations from the ideal-joint twin (every clearance joint ideal),
/// recorded every `reference_interval`; after the transient, the error and acceleration
/// oscillation (largest, RMS), the ideal twin's amplitudes, and per clearance joint the peak
/// contact force (located on the dense output), the contact-time fraction and, with two whole
/// periods after the transient, the Poincaré-section spread of its journal centre / clearance;
/// the largest contact force and spread over the joints.
fn derived(d: &mut ModelDesc, p: &FlapParams) {
    use clr_mbd::desc::metric::{Divisor, MetricDesc, Statistic as S};
    use clr_mbd::measure::deviation::{Deviation, TwinSettings};
    angle_measures(d, p);
    for (of, suffix) in [("flap.angle", None), ("flap.alpha", Some("alpha_error"))] {
        d.measures.push(clr_mbd::Measure::Deviation(Deviation {
            name: "flap".into(),
            of: vec![of.into()],
            suffix: suffix.map(str::to_string),
        }));
    }
    let t_end = d.output.t_end.unwrap_or(p.duration);
    d.twin = Some(TwinSettings {
        intervals: Some(((t_end / p.reference_interval).round() as usize).max(1)),
    });
    let t0 = p.transient;
    let m = |name: &str, of: &str, stat, words: &str| {
        MetricDesc::new(name, of, stat).after(t0).described(words)
    };
    let ideal = |name: &str, of: &str, words: &str| MetricDesc {
        twin: true,
        ..m(name, of, S::Peak, words)
    };
    let mut v = vec![
        m(
            "flap_angle_error_max",
            "flap.error",
            S::Peak,
            "largest |flap angle − ideal flap angle| after the transient",
        ),
        m(
            "flap_angle_error_rms",
            "flap.error",
            S::Rms,
            "time RMS of the flap angle error after the transient",
        ),
        m(
            "flap_acceleration_oscillation_peak",
            "flap.alpha_error",
            S::Peak,
            "largest |flap angular acceleration − ideal| after the transient",
        ),
        m(
            "flap_acceleration_oscillation_rms",
            "flap.alpha_error",
            S::Rms,
            "time RMS of the flap angular acceleration − ideal after the transient",
        ),
        ideal(
            "flap_angle_amplitude_ideal",
            "flap.angle",
            "largest |flap angle| of the ideal mechanism after the transient",
        ),
        ideal(
            "flap_acceleration_peak_ideal",
            "flap.alpha",
            "largest |flap angular acceleration| of the ideal mechanism after the transient",
        ),
    ];
    let periods = (t_end - t0) / p.period() + 1e-9;
    let (mut forces, mut spreads) = (Vec::new(), Vec::new());
    for (k, j) in JOINTS.iter().enumerate() {
        let c = p.clearances[k];
        if c <= 0.0 {
            continue;
        }
        forces.push(format!("{j}.normal_force"));
        v.push(m(
            &format!("{j}_peak_contact_force"),
            &format!("{j}.normal_force"),
            S::Peak,
            &format!(
                "largest normal force in clearance joint {j} after the transient, located on \
                 the dense output"
            ),
        ));
        v.push(m(
            &format!("{j}_contact_time_fraction"),
            &format!("{j}.contact"),
            S::Mean,
            &format!("fraction of the time after the transient with contact in {j}"),
        ));
        if periods >= 2.0 {
            let name = format!("{j}_poincare_spread");
            let (ex, ey) = (format!("{j}.ex"), format!("{j}.ey"));
            v.push(MetricDesc {
                period: Some(p.period()),
                phases: Some(p.poincare_phases),
                ..MetricDesc::of_columns(&name, &[&ex, &ey], S::Spread)
                    .after(t0)
                    .per(Divisor::Number(c))
                    .in_unit("-")
                    .described(&format!(
                        "stroboscopic spread of the {j} journal centre over the periods after \
                         the transient, mean over the phases, / clearance"
                    ))
            });
            spreads.push(name);
        }
    }
    if !forces.is_empty() {
        let f: Vec<&str> = forces.iter().map(String::as_str).collect();
        v.push(
            MetricDesc::of_columns("peak_contact_force", &f, S::Peak)
                .after(t0)
                .described("largest normal force over the clearance joints after the transient"),
        );
    }
    if !spreads.is_empty() {
        let s: Vec<&str> = spreads.iter().map(String::as_str).collect();
        v.push(
            MetricDesc::of_metrics("poincare_spread", &s, S::Max).described(
                "largest Poincaré-section spread over the clearance joints (irregularity)",
            ),
        );
    }
    d.metrics = v;
}

/// Simulate one configuration with the flap angle measures `flap.angle` (rad, from the initial
/// position) and `flap.alpha` (rad/s²) and no twin or metric. `uniform` records every
/// `reference_interval` instead of every step.
pub(crate) fn simulate(
    model: &str,
    p: &FlapParams,
    settings: &RunSettings,
    uniform: bool,
) -> Result<Results, ModelsError> {
    // the clearance run records every step, the reference run every `reference_interval` s
    let record = if uniform {
        Record::Every(p.reference_interval)
    } else {
        Record::EveryStep
    };
    let mut desc = common::run_desc(model, settings, record, || p.desc(model))?;
    angle_measures(&mut desc, p);
    let (mut m, opts) = common::compile_run(model, &desc)?;
    common::simulate(&mut m, &opts, settings, model)
}

/// The ideal-joint reference of `p` (every clearance set to 0), recorded every
/// `reference_interval` s with `flap.angle` and `flap.alpha`: what the flap's twin is, for
/// models that simulate the same linkage another way (the spatial flap, [`crate::flap_spatial`]).
///
/// # Errors
/// Invalid parameters or settings, build or simulation errors.
pub fn run_ideal_reference(
    model: &str,
    p: &FlapParams,
    settings: &RunSettings,
) -> Result<Results, ModelsError> {
    let ideal = FlapParams {
        clearances: [0.0; 4],
        ..p.clone()
    };
    simulate(model, &ideal, settings, true)
}

/// The flap angle error and angular-acceleration error (rad, rad/s²) of a run at its output
/// times `t` (s) against the ideal run at `ti` (interpolated linearly).
pub(crate) fn errors_against_ideal(
    t: &[f64],
    (a, al): (&[f64], &[f64]),
    ti: &[f64],
    (ai, ali): (&[f64], &[f64]),
) -> (Vec<f64>, Vec<f64>) {
    let err = (0..t.len())
        .map(|r| a[r] - common::interp(ti, ai, t[r]))
        .collect();
    let aerr = (0..t.len())
        .map(|r| al[r] - common::interp(ti, ali, t[r]))
        .collect();
    (err, aerr)
}

/// The flap angle error (max, RMS) and acceleration oscillation (peak, RMS) after `t0` (s) of
/// the errors `err` (rad) and `aerr` (rad/s²) at times `t` (s).
pub(crate) fn error_metrics(t: &[f64], err: &[f64], aerr: &[f64], t0: f64) -> Vec<Metric> {
    vec![
        Metric::new(
            "flap_angle_error_max",
            common::peak_abs(t, err, t0),
            "rad",
            "largest |flap angle − ideal flap angle| after the transient",
        ),
        Metric::new(
            "flap_angle_error_rms",
            common::time_rms(t, err, t0),
            "rad",
            "time RMS of the flap angle error after the transient",
        ),
        Metric::new(
            "flap_acceleration_oscillation_peak",
            common::peak_abs(t, aerr, t0),
            "rad/s^2",
            "largest |flap angular acceleration − ideal| after the transient",
        ),
        Metric::new(
            "flap_acceleration_oscillation_rms",
            common::time_rms(t, aerr, t0),
            "rad/s^2",
            "time RMS of the flap angular acceleration − ideal after the transient",
        ),
    ]
}

/// Simulate the linkage and its ideal-joint twin (same parameters, all joints ideal) and
/// return the clearance run with the flap-angle error, acceleration oscillation, contact and
/// irregularity metrics of its description ([`run_desc`]).
///
/// # Errors
/// Invalid parameters, build or simulation errors.
pub fn run(model: &str, p: &FlapParams, settings: &RunSettings) -> Result<RunOutput, ModelsError> {
    common::check_settings(model, settings)?;
    p.validate().map_err(|m| common::invalid(model, m))?;
    crate::described_metrics::run_output(model, &run_desc(model, p, settings)?, settings, p)
}

/// One configuration of the flap studies.
#[derive(Debug, Clone)]
pub struct StudyCase {
    /// Study: `size` (clearance of J4), `position` (one clearance joint, 0.1 mm), `number`
    /// (J1..Jn with 0.1 mm), `load` (zero mean hinge moment).
    pub study: String,
    /// Case label (`c0.05mm`, `J2`, `n3`, …).
    pub label: String,
    /// The study's abscissa: clearance (mm), joint number (1–4) or number of clearance joints.
    pub x: f64,
    /// Clearances of J1..J4, m.
    pub clearances: [f64; 4],
    /// Metrics of [`run`].
    pub metrics: Vec<Metric>,
    /// Wall time, s.
    pub wall_s: f64,
}

impl StudyCase {
    /// A metric by name (NaN when absent).
    pub fn metric(&self, name: &str) -> f64 {
        crate::output::metric_value(&self.metrics, name)
    }
}

/// One study configuration: (study, label, abscissa, clearances of J1..J4 in m, mean hinge
/// moment in N·m or `None` for the base value).
pub type StudyConfiguration = (String, String, f64, [f64; 4], Option<f64>);

/// The study configurations. Clearance sizes 0.05, 0.1, 0.2, 0.5 mm in J4; each joint alone
/// with 0.1 mm; J1..Jn with 0.1 mm for n = 1..4; `load`: J1 alone and J1..J4 (0.1 mm) with a
/// zero mean hinge moment (M = −K(θ − θ0) changes sign with the swing, so the joints unload
/// and the journals cross their clearance).
pub fn study_configurations() -> Vec<StudyConfiguration> {
    let mut v = Vec::new();
    for c_mm in [0.05, 0.1, 0.2, 0.5] {
        v.push((
            "size".to_string(),
            format!("c{c_mm}mm"),
            c_mm,
            [0.0, 0.0, 0.0, c_mm * 1e-3],
            None,
        ));
    }
    for k in 0..4 {
        let mut c = [0.0; 4];
        c[k] = 0.1e-3;
        v.push(("position".into(), JOINTS[k].into(), (k + 1) as f64, c, None));
    }
    for n in 1..=4 {
        let mut c = [0.0; 4];
        c.iter_mut().take(n).for_each(|x| *x = 0.1e-3);
        v.push(("number".into(), format!("n{n}"), n as f64, c, None));
    }
    for n in [1usize, 4] {
        let mut c = [0.0; 4];
        c.iter_mut().take(n).for_each(|x| *x = 0.1e-3);
        v.push((
            "load".into(),
            format!("reversing_n{n}"),
            n as f64,
            c,
            Some(0.0),
        ));
    }
    v
}

/// Run the clearance-size, clearance-position, number-of-joints and load studies in parallel
/// (rayon)
/// with `base` for every other parameter, writing under `dir`: `<study>_<label>.csv` (every
/// column), `summary.csv` (metrics per case) and figures (`size_oscillation`,
/// `size_contact_force`, `position_oscillation`, `number_oscillation`, `number_poincare`,
/// `orbits_size`, `alpha_error_size`, `orbits_n4`, `poincare_n4`, `orbits_reversing_n4`,
/// `poincare_reversing_n4`).
///
/// # Errors
/// The first failing case, or an output error.
pub fn study(dir: &Path, base: &FlapParams) -> Result<Vec<StudyCase>, String> {
    let configs = study_configurations()
        .into_iter()
        .map(|(study, label, x, clearances, hinge)| {
            let p = FlapParams {
                clearances,
                hinge_moment: hinge.unwrap_or(base.hinge_moment),
                ..base.clone()
            };
            (study, label, x, p)
        })
        .collect();
    let (cases, results) = run_cases(dir, configs, None)?;
    write_summary(dir, &cases)?;
    study_figures(dir, base, &cases, &results)?;
    Ok(cases)
}

/// Run the study configurations (study, label, abscissa, parameters) in parallel (rayon) with
/// [`run`], writing `<study>_<label>.csv` under `dir` (every `stride`-th row when
/// `max_rows` is given, so at most about that many rows); cases and results in the given order.
pub(crate) fn run_cases(
    dir: &Path,
    configs: Vec<(String, String, f64, FlapParams)>,
    max_rows: Option<usize>,
) -> Result<(Vec<StudyCase>, Vec<Results>), String> {
    let runs: Vec<Result<(StudyCase, Results), String>> = configs
        .into_par_iter()
        .map(|(study, label, x, p)| {
            let start = std::time::Instant::now();
            let out = run("flap", &p, &RunSettings::default())
                .map_err(|e| format!("{study} {label}: {e}"))?;
            Ok((
                StudyCase {
                    study,
                    label,
                    x,
                    clearances: p.clearances,
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
        let name = format!("{}_{}", c.study, c.label);
        match max_rows {
            Some(n) if res.len() > n => {
                let w = res.columns.len();
                let stride = res.len().div_ceil(n.max(1));
                let mut thin = Results {
                    columns: res.columns.clone(),
                    data: Vec::new(),
                    ..res.clone()
                };
                thin.data = res
                    .data
                    .chunks_exact(w)
                    .step_by(stride)
                    .flatten()
                    .copied()
                    .collect();
                common::write_results_csv(&thin, dir, &name)?;
            }
            _ => common::write_results_csv(&res, dir, &name)?,
        }
        cases.push(c);
        results.push(res);
    }
    Ok((cases, results))
}

fn write_summary(dir: &Path, cases: &[StudyCase]) -> Result<(), String> {
    let runs: Vec<_> = cases
        .iter()
        .map(|c| {
            let mut keys = vec![c.study.clone(), c.label.clone(), format!("{}", c.x)];
            keys.extend(c.clearances.iter().map(|v| format!("{v:e}")));
            (keys, c.wall_s, c.metrics.as_slice())
        })
        .collect();
    common::write_study_summary(dir, &["study", "case", "x", "c1", "c2", "c3", "c4"], &runs)
}

fn study_figures(
    dir: &Path,
    base: &FlapParams,
    cases: &[StudyCase],
    results: &[Results],
) -> Result<(), String> {
    use clr_plot::Figure;
    let save = |f: Figure, name: &str| common::save_figure(f, dir, name);
    const MAX: usize = 3000;
    let series = |study: &str, metric: &str| -> Vec<(f64, f64)> {
        cases
            .iter()
            .filter(|c| c.study == study)
            .map(|c| (c.x, c.metric(metric)))
            .collect()
    };
    let osc = |title: &str, study: &str, xl: &str| {
        Figure::new(title)
            .x_label(xl)
            .y_label("flap angular-acceleration oscillation (rad/s²)")
            .line("peak", series(study, "flap_acceleration_oscillation_peak"))
            .points("peak ", series(study, "flap_acceleration_oscillation_peak"))
            .line("RMS", series(study, "flap_acceleration_oscillation_rms"))
            .points("RMS ", series(study, "flap_acceleration_oscillation_rms"))
    };
    save(
        osc(
            "Clearance size (J4): flap acceleration oscillation",
            "size",
            "radial clearance (mm)",
        ),
        "size_oscillation",
    )?;
    save(
        Figure::new("Clearance size (J4): peak contact force and flap angle error")
            .x_label("radial clearance (mm)")
            .y_label("peak contact force (N)")
            .line("peak contact force", series("size", "peak_contact_force"))
            .points("", series("size", "peak_contact_force")),
        "size_contact_force",
    )?;
    save(
        osc(
            "Clearance-joint position (0.1 mm, one joint): flap acceleration oscillation",
            "position",
            "clearance joint (1 actuator, 2 lever pivot, 3 lever-rod, 4 rod-aux lever)",
        ),
        "position_oscillation",
    )?;
    save(
        osc(
            "Number of clearance joints (J1..Jn, 0.1 mm): flap acceleration oscillation",
            "number",
            "number of clearance joints",
        ),
        "number_oscillation",
    )?;
    save(
        Figure::new("Number of clearance joints: Poincaré-section spread (largest joint)")
            .x_label("number of clearance joints")
            .y_label("spread / clearance (–)")
            .line("spread", series("number", "poincare_spread"))
            .points("", series("number", "poincare_spread")),
        "number_poincare",
    )?;
    let mut orb = Figure::new("Journal-centre orbits in J4 (bearing frame), clearance sizes")
        .x_label("e_x (mm)")
        .y_label("e_y (mm)")
        .equal_aspect();
    let mut aerr = Figure::new("Flap angular acceleration − ideal, clearance sizes (J4)")
        .x_label("time (s)")
        .y_label("α − α_ideal (rad/s²)");
    let mm = |v: Vec<f64>| v.into_iter().map(|x| x * 1e3).collect::<Vec<_>>();
    // orbits and Poincaré sections (once per period, phase 0) of the four-joint cases
    let four_joint = |r: &Results, what: &str| {
        let t = col(r, "t");
        let mut orb = Figure::new(format!(
            "Journal-centre orbits, four clearance joints, {what}"
        ))
        .x_label("e_x (mm)")
        .y_label("e_y (mm)")
        .equal_aspect();
        let mut poin = Figure::new(format!(
            "Poincaré sections (once per period, phase 0), four clearance joints, {what}"
        ))
        .x_label("e_x (mm)")
        .y_label("e_y (mm)")
        .equal_aspect();
        for j in JOINTS {
            let (ex, ey) = (col(r, &format!("{j}.ex")), col(r, &format!("{j}.ey")));
            orb = orb.line(j, common::thin(&mm(ex.clone()), &mm(ey.clone()), MAX));
            let t_end = t.last().copied().unwrap_or(0.0);
            let mut pts = Vec::new();
            let mut ts = base.transient;
            while ts <= t_end {
                pts.push((
                    common::interp(&t, &ex, ts) * 1e3,
                    common::interp(&t, &ey, ts) * 1e3,
                ));
                ts += base.period();
            }
            poin = poin.points(j, pts);
        }
        (orb, poin)
    };
    for (c, r) in cases.iter().zip(results) {
        let t = col(r, "t");
        if c.study == "size" {
            orb = orb.line(
                c.label.clone(),
                common::thin(&mm(col(r, "J4.ex")), &mm(col(r, "J4.ey")), MAX),
            );
            aerr = aerr.line(
                c.label.clone(),
                common::thin(&t, &col(r, "flap.alpha_error"), MAX),
            );
        }
        let tag = match (c.study.as_str(), c.label.as_str()) {
            ("number", "n4") => Some(("n4", "hinge moment 30 N·m")),
            ("load", "reversing_n4") => Some(("reversing_n4", "zero mean hinge moment")),
            _ => None,
        };
        if let Some((tag, what)) = tag {
            let (o, p) = four_joint(r, what);
            save(o, &format!("orbits_{tag}"))?;
            save(p, &format!("poincare_{tag}"))?;
        }
    }
    save(orb, "orbits_size")?;
    save(aerr, "alpha_error_size")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ideal_linkage_follows_the_closed_form_kinematics() {
        // independent formulation: the flap angle of the ideal mechanism from two circle
        // intersections (FlapParams::ideal_flap_angle) at the actuator extension x(t); the
        // multibody solution may differ only by the constraint drift (Baumgarte) and the
        // integration error, far below 1e-7 rad
        let p = FlapParams {
            clearances: [0.0; 4],
            duration: 0.3,
            ..FlapParams::default()
        };
        let res = simulate("flap", &p, &RunSettings::default(), true).unwrap();
        let (t, a) = (col(&res, "t"), col(&res, "flap.angle"));
        let mut worst = 0.0f64;
        for r in 0..t.len() {
            let x = p.actuator(t[r])[0];
            let cf = p.ideal_flap_angle(x, p.aux_rod_length).unwrap();
            worst = worst.max((a[r] - cf).abs());
        }
        assert!(worst < 1e-7, "largest deviation {worst} rad");
        // and the flap does move (amplitude well above the tolerance)
        let amp = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(amp > 0.05, "{amp}");
    }

    #[test]
    fn flap_with_clearance_in_j4_stays_inside_the_rod_length_envelope() {
        // closed-form bound: with only J4 a clearance joint, |J4_aux − J3| lies within
        // l ± (c + δ_max), so the flap angle lies between the ideal angles for those two rod
        // lengths (circle intersections) at every instant
        let p = FlapParams {
            duration: 0.3,
            ..FlapParams::default()
        };
        let out = run("flap", &p, &RunSettings::default()).unwrap();
        let r = &out.results;
        let (t, a) = (col(r, "t"), col(r, "flap.angle"));
        let pen = col(r, "J4.penetration")
            .iter()
            .fold(0.0f64, |m, v| m.max(*v));
        let play = p.clearances[3] + pen;
        let mut worst = f64::NEG_INFINITY;
        for k in 0..t.len() {
            let x = p.actuator(t[k])[0];
            let lo = p.ideal_flap_angle(x, p.aux_rod_length - play).unwrap();
            let hi = p.ideal_flap_angle(x, p.aux_rod_length + play).unwrap();
            let (lo, hi) = (lo.min(hi), lo.max(hi));
            worst = worst.max(lo - a[k]).max(a[k] - hi);
        }
        assert!(worst <= 1e-9, "envelope exceeded by {worst} rad");
        // the error is of the order of the clearance over the lever length
        let e = out
            .metrics
            .iter()
            .find(|m| m.name == "flap_angle_error_max")
            .unwrap()
            .value;
        assert!(e > 0.2 * p.clearances[3] / p.aux_lever_arm_length, "{e}");
        assert_eq!(out.units.len(), out.results.columns.len());
    }

    #[test]
    fn invalid_flap_parameters_name_the_field() {
        let p = FlapParams {
            clearances: [0.0, 0.0, 0.0, 0.005],
            ..FlapParams::default()
        };
        let e = run("flap", &p, &RunSettings::default()).unwrap_err();
        assert!(e.to_string().contains("clearances[3]"), "{e}");
        let p = FlapParams {
            actuator_amplitude: 0.03,
            ..FlapParams::default()
        };
        let e = p.validate().unwrap_err();
        assert!(e.contains("actuator_amplitude"), "{e}");
    }

    #[test]
    fn calibrated_rod_matches_the_paper_and_the_closed_form() {
        let rod = &FlexiblePart::paper_parts()[1];
        let c = rod.calibrate().unwrap();
        // first frequency equal to the paper's 690.40 Hz after calibration
        assert!((c.frequencies_hz[0] / 690.40 - 1.0).abs() < 1e-9);
        // and close to the Euler–Bernoulli closed form at that depth (20 elements)
        let cf = rod.closed_form_f1(c.depth);
        assert!(
            (c.frequencies_hz[0] / cf - 1.0).abs() < 1e-4,
            "{} vs {cf}",
            c.frequencies_hz[0]
        );
    }
}
