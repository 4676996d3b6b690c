//! The rigid flap linkage written in space (issue 32, study `flap_misalignment`): the same
//! bodies, joints, actuator and hinge load as [`crate::flap`], in the plane z = 0 of a spatial
//! model, with every clearance joint a spatial revolute clearance joint (a bore of the paper's
//! bearing length L = 15 mm, the journal between its thrust collars 0.1 mm longer; clr-mbd
//! `spatial::JournalClearanceDesc`) whose bore axis can be misaligned.
//!
//! **Misalignment.** The bore axis of each clearance joint is turned by α about the bearing
//! body's own x axis (the link's length direction; the world x axis for the ground bearing J2):
//! u_b = (0, sin α, cos α) in the bearing body's frame, while the journal axis stays along z.
//! The journal then lies tilted by α in its bore and touches at the rims (edge loading); with
//! L·tan α below the diametral clearance 2c it still fits (0.2° over 15 mm is 52 µm against
//! 2c = 100–1000 µm in the studies).
//!
//! **Ideal joints in closed loops.** A closed loop of parallel revolute joints is
//! over-constrained in space by three equations (Grübler), which the spatial assembly refuses.
//! Where the ideal joints close a loop, two of them are relaxed so that the loop is statically
//! determinate and nothing else changes in plane motion:
//! - the actuator loop C0–actuator–J1–J2 (J1 and J2 ideal): C0 cylindrical, J1 spherical;
//! - the four-bar J2–J3–J4–O2 (J2, J3, J4 ideal): J3 spherical, J4 cylindrical;
//! - the outer loop C0–actuator–J1–J3–J4–O2 when J2 is the clearance joint (J1, J3, J4 ideal):
//!   J1 spherical, J4 cylindrical.
//!
//! A relaxed joint transmits no moment about the in-plane axes and no force along z; with
//! α = 0 nothing excites out-of-plane motion, so the spatial linkage reproduces the planar one
//! (the study's `alpha0` rows, and `cargo xtask verify models.flap_misalignment`).
//!
//! **Out-of-plane inertia** (reconstruction; the paper gives none): each bar of length l and
//! planar moment I_zz = m l²/12 gets I_xx = m(w² + h²)/12 and I_yy = m(l² + w²)/12 with its
//! width w = 15 mm (the bearing length) and depth h = 25 mm; the cylinder 40 × 40 mm, the
//! piston 20 × 20 mm; the auxiliary lever arm with the flap I_xx = I_yy = I_zz (it turns about
//! the ideal joint O2 only, so these values never enter its motion).
//!
//! **Axial end play** c_a = 0.1 mm per clearance joint (reconstruction), a journal of length
//! L + c_a between its collars (a pin longer than its bore, as in a clevis; a journal exactly as
//! long as its bore would put a kink in the contact energy at zero axial offset), thrust collars
//! of the journal radius, the radial normal law (the flap's preset over L_c = 15 mm) also on the thrust
//! faces, and the flap's Ambrósio friction.

use std::f64::consts::FRAC_PI_2;
use std::path::Path;

use clr_mbd::spatial::{
    ClearanceKind, DriverKind, End, JointKind, JournalClearanceDesc, Orientation, Space,
    SpatialBody, SpatialDesc, SpatialDriver, SpatialForce, SpatialInfo, SpatialJoint, VectorFrame,
};
use clr_mbd::{FrictionLawDesc, NormalLawDesc, TimeFn};

use clr_mbd::Results;

use crate::common::{self, col};
use crate::flap::{FlapParams, JOINTS};
use crate::{Metric, ModelsError, RunOutput, RunSettings};

/// Axial end play of every spatial clearance joint of the flap, m (reconstruction).
pub const AXIAL_CLEARANCE: f64 = 1e-4;

/// Width of the links (z), m: the paper's bearing length.
const LINK_WIDTH: f64 = 0.015;
/// Depth of the links' section, m (the calibrated sections are 22.9–26.6 mm).
const LINK_DEPTH: f64 = 0.025;

/// The axis of the bearing body about which a misaligned bore axis is turned.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TiltAxis {
    /// The bearing body's x axis, along the link (world x for the ground bearing J2): the journal
    /// ends move across the link, u_b = (0, sin α, cos α).
    AlongLink,
    /// The bearing body's y axis, across the link (world y for J2): the journal ends move along
    /// the link, u_b = (sin α, 0, cos α).
    AcrossLink,
}

/// The misalignment of every clearance joint's bore axis.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Misalignment {
    /// Angle α between bore axis and journal axis at the assembly, rad (0 to 1°).
    pub angle: f64,
    /// The axis it is turned about.
    pub about: TiltAxis,
}

impl Misalignment {
    /// No misalignment.
    pub const NONE: Self = Self {
        angle: 0.0,
        about: TiltAxis::AlongLink,
    };

    /// The bore axis in the bearing body's frame.
    fn bore_axis(self) -> [f64; 3] {
        let (s, c) = self.angle.sin_cos();
        match self.about {
            TiltAxis::AlongLink => [0.0, s, c],
            TiltAxis::AcrossLink => [s, 0.0, c],
        }
    }

    /// A label: `0`, `0.05x` (about the link), `0.05y` (across), in degrees.
    pub fn label(self) -> String {
        if self.angle == 0.0 {
            return "0".into();
        }
        let axis = match self.about {
            TiltAxis::AlongLink => "x",
            TiltAxis::AcrossLink => "y",
        };
        format!("{}{axis}", self.angle.to_degrees())
    }
}

/// How each ideal joint of the linkage is written in space: C0, J1, J2, J3, J4 (O2 and the
/// actuator's prismatic joint are always revolute and prismatic).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IdealKinds {
    /// Actuator cylinder to ground.
    pub c0: JointKind,
    /// J1..J4 when ideal.
    pub joints: [JointKind; 4],
}

/// The ideal joints' kinds for the clearances of J1..J4 (module docs: the relaxed loops).
pub fn ideal_kinds(clearances: &[f64; 4]) -> IdealKinds {
    let ideal = |k: usize| clearances[k] <= 0.0;
    let actuator_loop = ideal(0) && ideal(1);
    let four_bar = ideal(1) && ideal(2) && ideal(3);
    let outer_loop = !ideal(1) && ideal(0) && ideal(2) && ideal(3);
    let pick = |relax: bool, kind: JointKind| {
        if relax {
            kind
        } else {
            JointKind::Revolute
        }
    };
    IdealKinds {
        c0: pick(actuator_loop, JointKind::Cylindrical),
        joints: [
            pick(actuator_loop || outer_loop, JointKind::Spherical),
            JointKind::Revolute,
            pick(four_bar, JointKind::Spherical),
            pick(four_bar || outer_loop, JointKind::Cylindrical),
        ],
    }
}

/// A body in the plane z = 0: position (x, y), angle θ about z, mass, principal moments.
pub(crate) fn planar_body(
    name: &str,
    mass: f64,
    inertia: [f64; 3],
    x: f64,
    y: f64,
    theta: f64,
) -> SpatialBody {
    SpatialBody {
        name: name.into(),
        mass,
        inertia: None,
        principal_inertia: Some(inertia),
        principal_axes: None,
        centre_of_mass: [0.0; 3],
        position: Some([x, y, 0.0]),
        orientation: Some(Orientation::AxisAngle {
            axis: [0.0, 0.0, 1.0],
            angle: theta,
        }),
        velocity: Some([0.0; 3]),
        velocity_frame: Some(VectorFrame::World),
        angular_velocity: Some([0.0; 3]),
        angular_velocity_frame: Some(VectorFrame::World),
    }
}

/// Principal moments of a bar along its x axis: length l, width w (z), depth h (y); I_zz is the
/// planar model's m l²/12.
fn bar_inertia(mass: f64, l: f64, w: f64, h: f64) -> [f64; 3] {
    [
        mass * (w * w + h * h) / 12.0,
        mass * (l * l + w * w) / 12.0,
        mass * l * l / 12.0,
    ]
}

fn end(body: &str, at: [f64; 2], axis: Option<[f64; 3]>) -> End {
    End {
        body: body.into(),
        at: [at[0], at[1], 0.0],
        axis,
    }
}

const Z: Option<[f64; 3]> = Some([0.0, 0.0, 1.0]);

fn joint(name: &str, kind: JointKind, a: End, b: End) -> SpatialJoint {
    // a spherical joint takes no axis; the others take a's, carried to b at the initial poses
    let a = End {
        axis: a.axis.filter(|_| kind != JointKind::Spherical),
        ..a
    };
    SpatialJoint {
        name: name.into(),
        kind,
        a,
        b: End { axis: None, ..b },
    }
}

/// The spatial flap: [`FlapParams`]' linkage in the plane z = 0 with the clearance joints as
/// spatial revolute clearance joints whose bore axes are misaligned by `misalignment` rad
/// (module docs), and its run settings: 0 to `duration` s, NDF at `rtol` (atol = rtol·10⁻³),
/// every step recorded. Bodies `cylinder`, `piston`, `lever_arm`, `aux_rod`, `aux_lever_arm`
/// (with the flap); joints `C0`, `actuator`, `O2`, `J1`..`J4`; driver `x`; torque `hinge` and
/// rotational spring `hinge_stiffness` about O2. Flexible parts are refused (the spatial engine
/// has rigid bodies only).
///
/// # Errors
/// Invalid parameters, a flexible part, or a misalignment outside [0, 1°] or one that does not
/// fit the clearance (L·tan α ≥ 2c).
pub fn spatial_desc(
    p: &FlapParams,
    misalignment: Misalignment,
    model: &str,
) -> Result<SpatialDesc, ModelsError> {
    p.validate().map_err(|m| common::invalid(model, m))?;
    p.friction.law().map_err(|m| common::invalid(model, m))?;
    check_misalignment(p, misalignment.angle).map_err(|m| common::invalid(model, m))?;
    if p.flexible.iter().any(|&f| f) {
        return Err(common::invalid(
            model,
            "flexible = [..] is not available in the spatial flap (the spatial engine has rigid \
             bodies only): set every part rigid",
        ));
    }
    let [c0, o1, o2] = p.ground_points();
    let (a, b, c) = (
        p.lever_arm_actuator_distance,
        p.lever_arm_length,
        p.aux_lever_arm_length,
    );
    let (lr, lc, lp) = (p.aux_rod_length, p.cylinder_length, p.piston_length);
    let (mal, ial, rc) = p.aux_lever_with_flap();
    let bodies = vec![
        planar_body(
            "cylinder",
            p.cylinder_mass,
            bar_inertia(p.cylinder_mass, lc, 0.04, 0.04),
            c0[0] + 0.5 * lc,
            c0[1],
            0.0,
        ),
        planar_body(
            "piston",
            p.piston_mass,
            bar_inertia(p.piston_mass, lp, 0.02, 0.02),
            -0.5 * lp,
            a,
            0.0,
        ),
        planar_body(
            "lever_arm",
            p.lever_arm_mass,
            bar_inertia(p.lever_arm_mass, b, LINK_WIDTH, LINK_DEPTH),
            0.0,
            0.5 * b,
            FRAC_PI_2,
        ),
        planar_body(
            "aux_rod",
            p.aux_rod_mass,
            bar_inertia(p.aux_rod_mass, lr, LINK_WIDTH, LINK_DEPTH),
            0.5 * lr,
            b,
            0.0,
        ),
        // lever frame rotated by π/2: local (u, v) → world (−v, u)
        planar_body(
            "aux_lever_arm",
            mal,
            [ial; 3],
            o2[0] - rc[1],
            o2[1] + rc[0],
            FRAC_PI_2,
        ),
    ];
    let kinds = ideal_kinds(&p.clearances);
    let mut joints = vec![
        joint(
            "C0",
            kinds.c0,
            end("ground", c0, Z),
            end("cylinder", [-0.5 * lc, 0.0], Z),
        ),
        joint(
            "actuator",
            JointKind::Prismatic,
            end("cylinder", [-0.5 * lc, 0.0], Some([1.0, 0.0, 0.0])),
            end("piston", [0.0, 0.0], Some([1.0, 0.0, 0.0])),
        ),
        joint(
            "O2",
            JointKind::Revolute,
            end("ground", o2, Z),
            end("aux_lever_arm", [-rc[0], -rc[1]], Z),
        ),
    ];
    // (name, bearing end, journal end), as the planar flap's J1..J4
    let ends: [(&str, End, End); 4] = [
        (
            "J1",
            end("lever_arm", [a - 0.5 * b, 0.0], Z),
            end("piston", [0.5 * lp, 0.0], Z),
        ),
        (
            "J2",
            end("ground", o1, Z),
            end("lever_arm", [-0.5 * b, 0.0], Z),
        ),
        (
            "J3",
            end("aux_rod", [-0.5 * lr, 0.0], Z),
            end("lever_arm", [0.5 * b, 0.0], Z),
        ),
        (
            "J4",
            end("aux_rod", [0.5 * lr, 0.0], Z),
            end("aux_lever_arm", [c - rc[0], -rc[1]], Z),
        ),
    ];
    let mut clearances = Vec::new();
    for (k, (name, bearing, journal)) in ends.into_iter().enumerate() {
        let cl = p.clearances[k];
        if cl > 0.0 {
            clearances.push(journal_joint(p, name, bearing, journal, cl, misalignment).into());
        } else {
            joints.push(joint(name, kinds.joints[k], bearing, journal));
        }
    }
    let (m0, k) = (p.hinge_moment, p.hinge_stiffness);
    let forces = vec![
        SpatialForce::Torque {
            name: "hinge".into(),
            body: "aux_lever_arm".into(),
            frame: VectorFrame::World,
            mx: TimeFn::constant(0.0),
            my: TimeFn::constant(0.0),
            mz: TimeFn::constant(-m0),
        },
        SpatialForce::RotationalSpringDamper {
            name: "hinge_stiffness".into(),
            joint: "O2".into(),
            stiffness: k,
            damping: 0.0,
            free_angle: 0.0,
        },
    ];
    let mut d = SpatialDesc {
        model: SpatialInfo {
            name: Some(model.into()),
            description: Some(format!(
                "rigid flap linkage in space, bearing axes misaligned by {:.3}° ({:?})",
                misalignment.angle.to_degrees(),
                misalignment.about
            )),
            space: Space::Spatial,
            gravity: if p.gravity {
                [0.0, -9.81, 0.0]
            } else {
                [0.0; 3]
            },
        },
        bodies,
        joints,
        drivers: vec![SpatialDriver {
            name: "x".into(),
            kind: DriverKind::PrismaticDisplacement,
            joint: "actuator".into(),
            motion: p.actuator_motion(0.0),
        }],
        forces,
        clearances,
        ..SpatialDesc::default()
    };
    common::builtin_run(&mut d.solver, &mut d.output, p.duration, p.rtol, p.solver);
    Ok(d)
}

/// A misalignment must be finite, in [0, 1°] (a larger value is almost surely degrees), and fit
/// the tightest clearance: L·tan α < 2c.
fn check_misalignment(p: &FlapParams, alpha: f64) -> Result<(), String> {
    if !(alpha.is_finite() && (0.0..=1f64.to_radians()).contains(&alpha)) {
        return Err(format!(
            "misalignment = {alpha} rad must be in [0, 0.01745] rad (0 to 1°); angles are in rad \
             (0.1° = 1.745e-3 rad)"
        ));
    }
    for (k, &c) in p.clearances.iter().enumerate() {
        let across = p.axial_length * alpha.tan();
        if c > 0.0 && across >= 2.0 * c {
            return Err(format!(
                "a bore misaligned by {:.3}° over L = {} m moves the journal ends by {across:.3e} \
                 m, not less than the diametral clearance 2c = {:.3e} m of {}: the journal does \
                 not fit; lower the misalignment or raise the clearance",
                alpha.to_degrees(),
                p.axial_length,
                2.0 * c,
                JOINTS[k]
            ));
        }
    }
    Ok(())
}

/// Joint `name` as a spatial revolute clearance joint of the flap's bearing, its bore axis
/// turned by the misalignment.
fn journal_joint(
    p: &FlapParams,
    name: &str,
    mut bearing: End,
    journal: End,
    clearance: f64,
    misalignment: Misalignment,
) -> JournalClearanceDesc {
    bearing.axis = Some(misalignment.bore_axis());
    let normal = common::journal_preset_desc(
        &p.normal_law,
        p.youngs_modulus,
        p.poisson_ratio,
        p.restitution,
    );
    let radii = [p.bearing_radius, p.bearing_radius - clearance];
    revolute_journal(
        name,
        bearing,
        journal,
        radii,
        p.axial_length,
        normal,
        p.friction.desc(),
    )
}

/// A spatial revolute clearance joint of a planar model's pin joint: bore and journal radii
/// `radii` = [R_b, R_j] (m), bore length `length` = L (m), the journal spanning its collars
/// (L + [`AXIAL_CLEARANCE`]: the pin is longer than its bore, as in a clevis), thrust collars of
/// the journal radius, the radial law `normal` also on the thrust faces, Gauss order by default.
pub(crate) fn revolute_journal(
    name: &str,
    bearing: End,
    journal: End,
    radii: [f64; 2],
    length: f64,
    normal: NormalLawDesc,
    friction: FrictionLawDesc,
) -> JournalClearanceDesc {
    JournalClearanceDesc {
        name: name.into(),
        kind: ClearanceKind::Revolute,
        bearing,
        journal,
        bearing_radius: radii[0],
        bearing_length: length,
        journal_radius: radii[1],
        journal_length: length + AXIAL_CLEARANCE,
        axial_clearance: Some(AXIAL_CLEARANCE),
        thrust_radius: None,
        quadrature_order: None,
        normal,
        thrust_normal: None,
        friction: Some(friction),
        lubrication: None,
    }
}

/// Names of the journal groups' columns (clr-mbd spatial journal: radial regions A and B at
/// the bore's two ends, thrust faces − and +).
const GROUPS: [&str; 4] = ["radial_a", "radial_b", "thrust_minus", "thrust_plus"];

/// Simulate the spatial flap ([`spatial_desc`]) and compare it with the ideal planar linkage
/// `ideal` (a run of [`crate::flap`] with every joint ideal, recorded uniformly; the spatial
/// ideal linkage is the same motion): appends `flap.angle` (rad, from the initial position),
/// `flap.alpha` (rad/s²), `flap.error` and `flap.alpha_error`, and returns the flap's metrics
/// (module docs of [`crate::flap`]: angle error, acceleration oscillation) and per clearance
/// joint J the edge-loading metrics: `J_peak_contact_force` (N, the largest total normal force
/// of the two radial regions and the thrust faces, and the largest located impact peak of any
/// group), `J_peak_penetration` (m, deepest point of any group), `J_max_tilt` (rad, journal
/// axis against bore axis), `J_rim_share` (–, time mean over the contact after the transient of
/// the larger radial region's share of the radial load: 0.5 for a journal loaded evenly along
/// its length, 1 when one rim carries it all) and `J_contact_time_fraction`.
///
/// # Errors
/// Invalid parameters, build or simulation errors.
pub fn run(
    model: &str,
    p: &FlapParams,
    misalignment: Misalignment,
    ideal: &Results,
) -> Result<RunOutput, ModelsError> {
    let d = spatial_desc(p, misalignment, model)?;
    let opts = d
        .sim_options()
        .map_err(|e| common::invalid(model, e.to_string()))?;
    let mut m = d.compile().map_err(|e| common::build_error(model, e))?;
    let mut res = m.simulate(&opts).map_err(|e| common::sim_error(model, e))?;
    let (qw, qz) = (col(&res, "aux_lever_arm.qw"), col(&res, "aux_lever_arm.qz"));
    // O2 is an ideal revolute joint about z: the lever's quaternion is a turn about z
    let angle: Vec<f64> = qw
        .iter()
        .zip(&qz)
        .map(|(w, z)| 2.0 * z.atan2(*w) - FRAC_PI_2)
        .collect();
    let alpha = col(&res, "aux_lever_arm.alphaz");
    let t = col(&res, "t");
    let ti = col(ideal, "t");
    let (err, aerr) = crate::flap::errors_against_ideal(
        &t,
        (&angle, &alpha),
        &ti,
        (&col(ideal, "flap.angle"), &col(ideal, "flap.alpha")),
    );
    let t0 = p.transient;
    let mut metrics = crate::flap::error_metrics(&t, &err, &aerr, t0);
    for (k, j) in JOINTS.iter().enumerate() {
        if p.clearances[k] > 0.0 {
            metrics.extend(joint_metrics(&res, j, &t, t0));
        }
    }
    let peak = metrics
        .iter()
        .filter(|x| x.name.ends_with("_peak_contact_force"))
        .map(|x| x.value)
        .fold(0.0, f64::max);
    metrics.push(Metric::new(
        "peak_contact_force",
        peak,
        "N",
        "largest total normal force over the clearance joints after the transient",
    ));
    let window = crate::output::window_after(t0, "the transient");
    for x in &mut metrics {
        x.window = Some(window.clone());
    }
    common::append_columns(
        &mut res,
        vec![
            ("flap.angle".into(), angle),
            ("flap.alpha".into(), alpha),
            ("flap.error".into(), err),
            ("flap.alpha_error".into(), aerr),
        ],
    );
    let params = serde_json::json!({
        "flap": serde_json::to_value(p).unwrap_or_default(),
        "misalignment": misalignment,
        "axial_clearance_m": AXIAL_CLEARANCE,
    });
    Ok(common::output(model, res, metrics, params))
}

/// The edge-loading metrics of clearance joint `j` after `t0` ([`run`]).
fn joint_metrics(res: &Results, j: &str, t: &[f64], t0: f64) -> Vec<Metric> {
    let force = |g: &str| col(res, &format!("{j}.{g}.normal_force"));
    let pen = |g: &str| col(res, &format!("{j}.{g}.penetration"));
    let (fa, fb) = (force(GROUPS[0]), force(GROUPS[1]));
    let total: Vec<f64> = (0..t.len())
        .map(|r| GROUPS.iter().map(|g| force(g)[r]).sum())
        .collect();
    let mut peak_f = common::peak_abs(t, &total, t0);
    let mut peak_pen = f64::NEG_INFINITY;
    for g in GROUPS {
        let name = format!("{j}.{g}");
        let (f, d) = common::located_peaks(res, &name, t0, (0.0, common::peak_max(t, &pen(g), t0)));
        peak_f = peak_f.max(f);
        peak_pen = peak_pen.max(d);
    }
    let radial = |r: usize| fa[r] + fb[r];
    let contact: Vec<f64> = (0..t.len()).map(|r| f64::from(radial(r) > 0.0)).collect();
    // the larger region's share, time-weighted over the rows in contact
    let (mut share, mut span) = (0.0, 0.0);
    for r in 1..t.len() {
        if t[r - 1] < t0 || radial(r) <= 0.0 || radial(r - 1) <= 0.0 {
            continue;
        }
        let s = |r: usize| fa[r].max(fb[r]) / radial(r);
        let dt = t[r] - t[r - 1];
        share += 0.5 * (s(r) + s(r - 1)) * dt;
        span += dt;
    }
    vec![
        Metric::new(
            &format!("{j}_peak_contact_force"),
            peak_f,
            "N",
            &format!("largest total normal force in {j} (radial regions and thrust faces)"),
        ),
        Metric::new(
            &format!("{j}_peak_penetration"),
            peak_pen,
            "m",
            &format!("deepest penetration of any contact region of {j}"),
        ),
        Metric::new(
            &format!("{j}_max_tilt"),
            common::peak_abs(t, &col(res, &format!("{j}.tilt")), t0),
            "rad",
            &format!("largest tilt of the {j} journal axis against its bore axis"),
        ),
        Metric::new(
            &format!("{j}_rim_share"),
            if span > 0.0 { share / span } else { f64::NAN },
            "-",
            &format!(
                "time mean over the contact in {j} of the larger radial region's share of the \
                 radial load (0.5 even along the length, 1 one rim)"
            ),
        ),
        Metric::new(
            &format!("{j}_contact_time_fraction"),
            common::time_mean(t, &contact, t0),
            "-",
            &format!("fraction of the time with radial contact in {j}"),
        ),
    ]
}

/// Duration of the misalignment study's runs, s (the 0.25 s ramp and two actuator periods).
pub const STUDY_DURATION: f64 = 1.25;

/// Misalignment angles of the study, degrees.
pub const STUDY_ANGLES_DEG: [f64; 4] = [0.0, 0.05, 0.1, 0.2];

/// One run of the misalignment study.
#[derive(Debug, Clone)]
pub struct MisalignmentCase {
    /// `size` (J4's clearance varied) or `position` (0.1 mm in one joint).
    pub study: String,
    /// Case label (`c0.05mm`, `J2`, …).
    pub label: String,
    /// The study's abscissa: clearance (mm) or joint number.
    pub x: f64,
    /// Clearances of J1..J4, m.
    pub clearances: [f64; 4],
    /// The bore axes' misalignment.
    pub misalignment: Misalignment,
}

/// The study's runs: the clearance-size cases (0.05, 0.1, 0.2, 0.5 mm in J4) and the
/// clearance-position cases (0.1 mm in J1, J2 or J3; J4 is the size case 0.1 mm), each aligned
/// and misaligned by 0.05, 0.1 and 0.2° about and across the link.
pub fn study_cases() -> Vec<MisalignmentCase> {
    let mut configs: Vec<(&str, String, f64, [f64; 4])> = [0.05, 0.1, 0.2, 0.5]
        .iter()
        .map(|&c_mm| {
            (
                "size",
                format!("c{c_mm}mm"),
                c_mm,
                [0.0, 0.0, 0.0, c_mm * 1e-3],
            )
        })
        .collect();
    for k in 0..3 {
        let mut c = [0.0; 4];
        c[k] = 0.1e-3;
        configs.push(("position", JOINTS[k].into(), (k + 1) as f64, c));
    }
    let mut tilts = vec![Misalignment::NONE];
    for about in [TiltAxis::AlongLink, TiltAxis::AcrossLink] {
        for &deg in &STUDY_ANGLES_DEG[1..] {
            tilts.push(Misalignment {
                angle: deg.to_radians(),
                about,
            });
        }
    }
    configs
        .into_iter()
        .flat_map(|(study, label, x, clearances)| {
            tilts.iter().map(move |&misalignment| MisalignmentCase {
                study: study.into(),
                label: label.clone(),
                x,
                clearances,
                misalignment,
            })
        })
        .collect()
}

/// `clr study flap_misalignment`: every case of [`study_cases`] over [`STUDY_DURATION`] s
/// against the ideal planar linkage, and the planar flap ([`crate::flap::run`]) of each
/// clearance set (the aligned spatial runs reproduce it: `planar_*` columns of the summary),
/// in parallel (rayon). Writes `<study>_<label>_a<misalignment>.csv` (every 10th row),
/// `summary.csv` and the figures `misalignment_size`, `misalignment_position`,
/// `misalignment_penetration` and `misalignment_rim_share` under `dir`.
///
/// # Errors
/// The first failing run, or an output error.
pub fn study(dir: &Path) -> Result<Vec<(MisalignmentCase, Vec<Metric>)>, String> {
    use rayon::prelude::*;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let base = FlapParams {
        duration: STUDY_DURATION,
        ..Default::default()
    };
    let settings = RunSettings::default();
    let ideal =
        crate::flap::run_ideal_reference("flap", &base, &settings).map_err(|e| e.to_string())?;
    let cases = study_cases();
    let runs: Vec<Result<CaseRun, String>> = cases
        .par_iter()
        .map(|c| {
            let start = std::time::Instant::now();
            let p = FlapParams {
                clearances: c.clearances,
                ..base.clone()
            };
            let name = format!("{} {} {}", c.study, c.label, c.misalignment.label());
            let mut o =
                run("flap", &p, c.misalignment, &ideal).map_err(|e| format!("{name}: {e}"))?;
            if c.misalignment.angle == 0.0 {
                let planar = crate::flap::run("flap", &p, &settings)
                    .map_err(|e| format!("{name} (planar): {e}"))?;
                o.metrics.extend(
                    planar
                        .metrics
                        .iter()
                        .filter(|m| PLANAR.contains(&m.name.as_str()))
                        .map(|m| Metric {
                            name: format!("planar_{}", m.name),
                            description: format!("planar flap: {}", m.description),
                            ..m.clone()
                        }),
                );
            }
            Ok((o.metrics, o.results, start.elapsed().as_secs_f64()))
        })
        .collect();
    let mut out = Vec::new();
    let mut rows = Vec::new();
    for (c, r) in cases.into_iter().zip(runs) {
        let (metrics, res, wall) = r?;
        let name = format!("{}_{}_a{}", c.study, c.label, c.misalignment.label());
        common::write_results_csv(&thin(&res, 10), dir, &name)?;
        rows.push((c.clone(), wall, metrics.clone()));
        out.push((c, metrics));
    }
    let table: Vec<_> = rows
        .iter()
        .map(|(c, wall, m)| {
            let mut keys = vec![
                c.study.clone(),
                c.label.clone(),
                format!("{}", c.x),
                format!("{}", c.misalignment.angle.to_degrees()),
                format!("{:?}", c.misalignment.about),
            ];
            keys.extend(c.clearances.iter().map(|v| format!("{v:e}")));
            (keys, *wall, m.as_slice())
        })
        .collect();
    common::write_study_summary(
        dir,
        &[
            "study",
            "case",
            "x",
            "misalignment_deg",
            "about",
            "c1",
            "c2",
            "c3",
            "c4",
        ],
        &table,
    )?;
    figures(dir, &out)?;
    Ok(out)
}

/// One finished case: its metrics, results and wall time (s).
type CaseRun = (Vec<Metric>, Results, f64);

/// The planar flap's metrics set beside the aligned spatial runs.
const PLANAR: [&str; 4] = [
    "flap_angle_error_max",
    "flap_acceleration_oscillation_peak",
    "flap_acceleration_oscillation_rms",
    "peak_contact_force",
];

/// Every `stride`-th row of `res`.
fn thin(res: &Results, stride: usize) -> Results {
    let w = res.columns.len();
    Results {
        data: res
            .data
            .chunks_exact(w)
            .step_by(stride)
            .flatten()
            .copied()
            .collect(),
        ..res.clone()
    }
}

/// Where case `c` is drawn on the figures of `study`: its own abscissa, and the size case of
/// 0.1 mm also as joint 4 of the position figure (it is the position case J4).
fn abscissa(c: &MisalignmentCase, study: &str) -> Option<f64> {
    if c.study == study {
        Some(c.x)
    } else if study == "position" && c.study == "size" && c.label == "c0.1mm" {
        Some(4.0)
    } else {
        None
    }
}

fn figures(dir: &Path, cases: &[(MisalignmentCase, Vec<Metric>)]) -> Result<(), String> {
    use clr_plot::Figure;
    let value = |m: &[Metric], name: &str| crate::output::metric_value(m, name);
    // one line per misalignment: (study abscissa, metric), the joint's own metric by name
    let lines =
        |mut f: Figure, study: &str, metric: &dyn Fn(&MisalignmentCase, &[Metric]) -> f64| {
            let mut labels: Vec<(String, Misalignment)> = Vec::new();
            for (c, _) in cases.iter().filter(|(c, _)| c.study == study) {
                let l = c.misalignment.label();
                if !labels.iter().any(|(x, _)| *x == l) {
                    labels.push((l, c.misalignment));
                }
            }
            for (l, mis) in labels {
                let pts: Vec<(f64, f64)> = cases
                    .iter()
                    .filter_map(|(c, m)| {
                        let x = abscissa(c, study)?;
                        (c.misalignment == mis).then(|| (x, metric(c, m)))
                    })
                    .collect();
                let name = if l == "0" {
                    "aligned".to_string()
                } else {
                    format!(
                        "{l}: {:.2}° {}",
                        mis.angle.to_degrees(),
                        if mis.about == TiltAxis::AlongLink {
                            "about the link"
                        } else {
                            "across the link"
                        }
                    )
                };
                f = f.line(&name, pts);
            }
            f
        };
    let joint_of =
        |c: &MisalignmentCase| JOINTS[c.clearances.iter().position(|&x| x > 0.0).unwrap_or(3)];
    let osc = |_: &MisalignmentCase, m: &[Metric]| value(m, "flap_acceleration_oscillation_rms");
    let save = |f: Figure, name: &str| common::save_figure(f, dir, name);
    save(
        lines(
            Figure::new(
                "Clearance size (J4) with misaligned bearings: flap acceleration oscillation",
            )
            .x_label("radial clearance of J4 (mm)")
            .y_label("oscillation RMS (rad/s²)")
            .log_y(),
            "size",
            &osc,
        ),
        "misalignment_size",
    )?;
    save(
        lines(
            Figure::new("Clearance position (0.1 mm) with misaligned bearings: flap acceleration oscillation")
                .x_label("clearance joint (1 actuator, 2 lever pivot, 3 lever-rod, 4 rod-aux lever)")
                .y_label("oscillation RMS (rad/s²)")
                .log_y(),
            "position",
            &osc,
        ),
        "misalignment_position",
    )?;
    save(
        lines(
            Figure::new("Clearance size (J4): deepest penetration with misaligned bearings")
                .x_label("radial clearance of J4 (mm)")
                .y_label("peak penetration (µm)"),
            "size",
            &|c, m| 1e6 * value(m, &format!("{}_peak_penetration", joint_of(c))),
        ),
        "misalignment_penetration",
    )?;
    save(
        lines(
            Figure::new("Clearance size (J4): share of the radial load on the more loaded rim")
                .x_label("radial clearance of J4 (mm)")
                .y_label("rim share (0.5 even, 1 one rim)"),
            "size",
            &|c, m| value(m, &format!("{}_rim_share", joint_of(c))),
        ),
        "misalignment_rim_share",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every study configuration assembles without redundant equations (the spatial assembly
    /// refuses them, naming the loop).
    #[test]
    fn every_clearance_set_of_the_studies_compiles_without_redundancy() {
        for (_, label, _, clearances, _) in crate::flap::study_configurations() {
            let p = FlapParams {
                clearances,
                duration: 1e-3,
                ..Default::default()
            };
            let tilt = Misalignment {
                angle: 0.1f64.to_radians(),
                about: TiltAxis::AcrossLink,
            };
            let d = spatial_desc(&p, tilt, "flap").unwrap();
            let mut m = d.compile().unwrap_or_else(|e| panic!("{label}: {e}"));
            m.simulate(&d.sim_options().unwrap())
                .unwrap_or_else(|e| panic!("{label}: {e}"));
        }
    }

    #[test]
    fn a_misalignment_in_degrees_or_too_large_for_the_clearance_is_refused() {
        let p = FlapParams::default();
        let deg = |angle: f64| Misalignment {
            angle,
            about: TiltAxis::AlongLink,
        };
        let e = spatial_desc(&p, deg(0.2), "flap").unwrap_err().to_string();
        assert!(e.contains("angles are in rad"), "{e}");
        let p = FlapParams {
            clearances: [0.0, 0.0, 0.0, 0.01e-3],
            ..Default::default()
        };
        let e = spatial_desc(&p, deg(0.1f64.to_radians()), "flap")
            .unwrap_err()
            .to_string();
        assert!(e.contains("does not fit") && e.contains("J4"), "{e}");
    }
}
