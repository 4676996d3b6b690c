//! Study `journal_wear` (issue 32, point 3): Archard wear along the axis of a spatial revolute
//! clearance joint whose bearing axis is misaligned (docs/wear.md, "Spatial journal: wear along
//! the axis").
//!
//! The mechanism is the Wan slider–crank of the planar wear study
//! ([`crate::lubrication_wear::wan_slider_crank_wear`], [`SliderCrankParams::wan`]: 600 rpm,
//! R_b = 10 mm, c = 0.1 mm, L = 15 mm, Liu law `Modified` c_e = 0.46, Ambrósio friction
//! μ = 0.01) built in the spatial engine, the rod–slider joint B a spatial revolute clearance
//! joint (bore on the slider, 15 mm long; journal on the rod spanning its collars, axial end
//! play 0.1 mm as the spatial flap's). It was chosen over the flap's J4 because it has the planar
//! wear study and the planar engine on the same mechanism to compare with (the aligned case must
//! reproduce the planar wear; `wear.spatial.*` in xtask), its crank turns so that the journal
//! slides continuously, and one steady cycle takes seconds. The slider's bore axis is turned
//! about the slider's y axis (across the guide) by 0, 0.1 and 0.2°: the rod cannot tilt (its
//! revolute joints hold it in the plane), so the journal lies tilted by the misalignment in the
//! bore and is pushed against one rim by the rod force along x.
//!
//! Each case simulates one transient and one steady crank revolution, accumulates the steady
//! revolution's wear map from the history of the joint's states
//! ([`clr_contact::journal_wear::JournalWear::accumulate_history`], K = 1e-5, H = 2 GPa,
//! N = 360 angles × M = 15 stations of 1 mm) and extrapolates it linearly to
//! [`WEAR_CYCLES`] cycles. Unlike the planar study, the worn map is not fed back into the
//! contact (the spatial joint has no worn bore yet): the extrapolation is the first update of
//! the planar study's scheme, exact while the wear stays small against the clearance.

use std::f64::consts::TAU;
use std::path::Path;

use clr_contact::journal::{JournalClearance, JournalFriction, JournalLaws, GROUPS};
use clr_contact::journal_wear::{BearingWearMap, JournalSample, JournalWear};
use clr_contact::{ContactMemory, JournalState};
use clr_mbd::spatial::{
    DriverKind, End, JointKind, JournalClearanceDesc, SpatialBody, SpatialDesc, SpatialDriver,
    SpatialInfo, SpatialJoint,
};
use clr_mbd::{Results, TimeFn};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use rayon::prelude::*;

use crate::common::{self, col};
use crate::lubrication_wear::{
    WEAR_ANGLES, WEAR_COEFFICIENT, WEAR_DEPTH_PER_UPDATE, WEAR_HARDNESS, WEAR_MAX_CYCLES,
};
use crate::slider_crank::SliderCrankParams;

/// Misalignments of the slider's bore axis, rad (0, 0.1°, 0.2°).
pub const MISALIGNMENTS_DEG: [f64; 3] = [0.0, 0.1, 0.2];
/// Axial stations of the wear map (1 mm cells over the 15 mm bore).
pub const WEAR_STATIONS: usize = 15;
/// Cycles the one-cycle wear is extrapolated to (the planar study's end).
pub const WEAR_CYCLES: f64 = WEAR_MAX_CYCLES;
/// Axial end play of the spatial joint, m (the spatial flap's).
pub const AXIAL_CLEARANCE: f64 = crate::flap_spatial::AXIAL_CLEARANCE;
/// Name of the clearance joint.
pub const JOINT: &str = "B";

/// The spatial Wan slider–crank with the bore axis of joint B turned by `misalignment` (rad)
/// about the slider's y axis, simulated over `duration` s (NDF at the parameters' rtol, every
/// step recorded).
///
/// # Errors
/// Invalid parameters.
pub fn spatial_desc(
    p: &SliderCrankParams,
    misalignment: f64,
    duration: f64,
) -> Result<SpatialDesc, String> {
    p.validate()?;
    let (r, l, w) = (p.crank_length, p.rod_length, p.omega());
    let body = |name: &str, m: f64, i: f64, x: f64, v: [f64; 2], wz: f64| SpatialBody {
        velocity: Some([v[0], v[1], 0.0]),
        angular_velocity: Some([0.0, 0.0, wz]),
        ..crate::flap_spatial::planar_body(name, m, [i; 3], x, 0.0, 0.0)
    };
    let end = |b: &str, x: f64, axis: Option<[f64; 3]>| End {
        body: b.into(),
        at: [x, 0.0, 0.0],
        axis,
    };
    let z = Some([0.0, 0.0, 1.0]);
    let joint = |name: &str, kind, a, b| SpatialJoint {
        name: String::from(name),
        kind,
        a,
        b,
    };
    let mut d = SpatialDesc {
        model: SpatialInfo {
            name: Some("spatial_wan_slider_crank".into()),
            description: Some(format!(
                "Wan slider-crank in space, joint B a spatial revolute clearance joint, bore \
                 misaligned by {:.3}° about the slider's y axis",
                misalignment.to_degrees()
            )),
            space: clr_mbd::spatial::Space::Spatial,
            gravity: if p.gravity {
                [0.0, -9.81, 0.0]
            } else {
                [0.0; 3]
            },
        },
        bodies: vec![
            body(
                "crank",
                p.crank_mass,
                p.crank_inertia,
                r / 2.0,
                [0.0, w * r / 2.0],
                w,
            ),
            body(
                "rod",
                p.rod_mass,
                p.rod_inertia,
                r + l / 2.0,
                [0.0, w * r / 2.0],
                -w * r / l,
            ),
            body(
                "slider",
                p.slider_mass,
                p.slider_inertia,
                r + l,
                [0.0; 2],
                0.0,
            ),
        ],
        joints: vec![
            joint(
                "O",
                JointKind::Revolute,
                end("ground", 0.0, z),
                end("crank", -r / 2.0, None),
            ),
            joint(
                "A",
                JointKind::Revolute,
                end("crank", r / 2.0, z),
                end("rod", -l / 2.0, None),
            ),
            joint(
                "guide",
                JointKind::Prismatic,
                end("ground", 0.0, Some([1.0, 0.0, 0.0])),
                end("slider", 0.0, None),
            ),
        ],
        drivers: vec![SpatialDriver {
            name: "motor".into(),
            kind: DriverKind::RevoluteAngle,
            joint: "O".into(),
            motion: TimeFn::linear(0.0, w),
        }],
        clearances: vec![clearance_desc(p, misalignment).into()],
        ..SpatialDesc::default()
    };
    common::builtin_run(&mut d.solver, &mut d.output, duration, p.rtol, p.solver);
    Ok(d)
}

/// Joint B of [`spatial_desc`]: bore on the slider (axis turned by `misalignment` rad about the
/// slider's y axis), journal on the rod's end, the planar joint's radii, length L, end play
/// [`AXIAL_CLEARANCE`], the Wan normal law (its line laws' length left to the joint: the
/// contact length min(L_b, L_j) = L) on the bore and the thrust faces, Ambrósio friction.
pub fn clearance_desc(p: &SliderCrankParams, misalignment: f64) -> JournalClearanceDesc {
    let normal = common::journal_preset_desc(
        &p.normal_law,
        p.youngs_modulus,
        p.poisson_ratio,
        p.restitution,
    );
    let (s, c) = misalignment.sin_cos();
    let bearing = End {
        body: "slider".into(),
        at: [0.0; 3],
        axis: Some([s, 0.0, c]),
    };
    let journal = End {
        body: "rod".into(),
        at: [p.rod_length / 2.0, 0.0, 0.0],
        axis: Some([0.0, 0.0, 1.0]),
    };
    let radii = [p.bearing_radius, p.journal_radius];
    crate::flap_spatial::revolute_journal(
        JOINT,
        bearing,
        journal,
        radii,
        p.axial_length,
        normal,
        p.friction.desc(),
    )
}

/// The joint's geometry and radial law as the spatial engine compiles them from
/// [`clearance_desc`] (clr-mbd spatial compile: a revolute journal joint, the line laws over
/// the contact length L_c = min(L_b, L_j)), and the floor of the impact velocity of its contact
/// memory.
///
/// # Errors
/// Invalid parameters.
pub fn joint_and_laws(
    p: &SliderCrankParams,
) -> Result<(JournalClearance, JournalLaws, f64), String> {
    let d = clearance_desc(p, 0.0);
    let joint = JournalClearance::revolute(
        d.bearing_radius,
        d.bearing_length,
        d.journal_radius,
        d.journal_length,
        AXIAL_CLEARANCE,
        d.thrust_radius,
    )
    .map_err(|e| e.to_string())?;
    let mut normal = d.normal;
    if normal.takes_length() {
        normal.length = Some(joint.contact_length());
    }
    let radial = normal
        .build(
            &format!("{JOINT}.normal"),
            Some((d.bearing_radius, d.journal_radius)),
        )
        .map_err(|e| e.message)?;
    // friction does not enter the wear (the slip does): the laws' normal part is what counts
    let laws =
        JournalLaws::new(radial, radial, JournalFriction::None).map_err(|e| e.to_string())?;
    Ok((joint, laws, radial.min_impact_velocity()))
}

/// The Archard law of the study: K = 1e-5, H = 2 GPa, steel on steel.
///
/// # Errors
/// Invalid moduli.
pub fn archard(p: &SliderCrankParams) -> Result<JournalWear, String> {
    let e_star = p.youngs_modulus / (2.0 * (1.0 - p.poisson_ratio * p.poisson_ratio));
    JournalWear::new(WEAR_COEFFICIENT, WEAR_HARDNESS, e_star).map_err(|e| e.to_string())
}

/// A body's recorded columns (clr-mbd spatial output): origin, quaternion, velocity (world),
/// angular velocity (body frame).
struct BodyColumns([Vec<f64>; 13]);

impl BodyColumns {
    fn new(res: &Results, b: &str) -> Self {
        let names = [
            "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz",
        ];
        Self(names.map(|n| col(res, &format!("{b}.{n}"))))
    }

    /// Origin (m), rotation, velocity (m/s) and angular velocity (rad/s, world) at row k.
    fn at(
        &self,
        k: usize,
    ) -> (
        Vector3<f64>,
        UnitQuaternion<f64>,
        Vector3<f64>,
        Vector3<f64>,
    ) {
        let c = |i: usize| self.0[i].get(k).copied().unwrap_or(f64::NAN);
        let q = UnitQuaternion::from_quaternion(Quaternion::new(c(3), c(4), c(5), c(6)));
        let w_body = Vector3::new(c(10), c(11), c(12));
        (
            Vector3::new(c(0), c(1), c(2)),
            q,
            Vector3::new(c(7), c(8), c(9)),
            q * w_body,
        )
    }
}

/// The joint's recorded states for t ≥ `t_from`: poses and velocities of the slider (bore) and
/// the rod (journal) from the result columns, the slider's x axis as the reference of φ, and the
/// impact velocities replayed through a contact memory committed at every recorded (accepted)
/// step, as the simulation's own.
///
/// # Errors
/// Missing columns or a state the joint refuses.
pub fn joint_history(
    res: &Results,
    p: &SliderCrankParams,
    misalignment: f64,
    t_from: f64,
) -> Result<Vec<JournalSample>, String> {
    let (joint, _, min_v) = joint_and_laws(p)?;
    let mut memory = ContactMemory::new(GROUPS, min_v).map_err(|e| e.to_string())?;
    let t = col(res, "t");
    let d = clearance_desc(p, misalignment);
    let bore_axis = Vector3::from(d.bearing.axis.unwrap_or([0.0, 0.0, 1.0]));
    let pin = Vector3::from(d.journal.at);
    let (slider, rod) = (
        BodyColumns::new(res, "slider"),
        BodyColumns::new(res, "rod"),
    );
    let mut out = Vec::new();
    for (k, &tk) in t.iter().enumerate() {
        let (rs, qs, vs, ws) = slider.at(k);
        let (rr, qr, vr, wr) = rod.at(k);
        let oj = rr + qr * pin;
        let state = JournalState::new(
            rs,
            qs * bore_axis,
            vs,
            ws,
            oj,
            qr * Vector3::z(),
            vr + wr.cross(&(oj - rr)),
            wr,
        );
        let geo = joint
            .geometry(&state)
            .map_err(|e| format!("t = {tk} s: {e}"))?;
        let mut vdm = [0.0; GROUPS];
        for (g, v) in vdm.iter_mut().enumerate() {
            let (d, r) = geo.gap(g);
            *v = memory.impact_velocity(g, d, r);
        }
        geo.commit(&mut memory, 0);
        if tk >= t_from {
            out.push(JournalSample {
                time: tk,
                state,
                reference: qs * Vector3::x(),
                impact_velocities: vdm,
            });
        }
    }
    Ok(out)
}

/// One case of the study.
#[derive(Debug, Clone)]
pub struct JournalWearCase {
    /// Misalignment of the bore axis, degrees.
    pub misalignment_deg: f64,
    /// Wear map of one steady revolution.
    pub cycle: BearingWearMap,
    /// Worn volume of one revolution, m³.
    pub volume_per_cycle: f64,
    /// Largest depth of one revolution, m.
    pub depth_per_cycle: f64,
    /// Edge concentration of the map ([`BearingWearMap::edge_concentration`]), –.
    pub edge_concentration: f64,
    /// Largest total radial normal force of the steady revolution, N.
    pub peak_force: f64,
    /// Wall time of the simulation and the wear accumulation, s.
    pub wall_s: f64,
}

/// Simulate one case (one transient and one steady revolution) and accumulate the steady
/// revolution's wear map; the run's results too.
///
/// # Errors
/// Build, simulation or wear errors.
pub fn run_case(
    p: &SliderCrankParams,
    misalignment_deg: f64,
) -> Result<(JournalWearCase, Results), String> {
    let start = std::time::Instant::now();
    let alpha = misalignment_deg.to_radians();
    let period = 60.0 / p.crank_speed_rpm;
    let t_from = p.transient_revolutions * period;
    let d = spatial_desc(p, alpha, t_from + period)?;
    let opts = d.sim_options().map_err(|e| e.to_string())?;
    let mut m = d.compile().map_err(|e| e.to_string())?;
    let res = m.simulate(&opts).map_err(|e| e.to_string())?;
    let samples = joint_history(&res, p, alpha, t_from)?;
    let (joint, laws, _) = joint_and_laws(p)?;
    let mut cycle =
        BearingWearMap::zero(WEAR_ANGLES, WEAR_STATIONS, p.bearing_radius, p.axial_length)
            .map_err(|e| e.to_string())?;
    let volume = archard(p)?
        .accumulate_history(&mut cycle, &joint, &laws, &samples)
        .map_err(|e| e.to_string())?;
    let t = col(&res, "t");
    let total: Vec<f64> = col(&res, &format!("{JOINT}.radial_a.normal_force"))
        .iter()
        .zip(col(&res, &format!("{JOINT}.radial_b.normal_force")))
        .map(|(a, b)| a + b)
        .collect();
    Ok((
        JournalWearCase {
            misalignment_deg,
            volume_per_cycle: volume,
            depth_per_cycle: cycle.max_depth(),
            edge_concentration: cycle.edge_concentration(),
            peak_force: common::peak_abs(&t, &total, t_from),
            cycle,
            wall_s: start.elapsed().as_secs_f64(),
        },
        res,
    ))
}

/// The study: the three misalignments in parallel; writes `summary.csv` (per case: worn volume
/// and largest depth of one revolution, the cycles after which the deepest point has worn
/// [`WEAR_DEPTH_PER_UPDATE`] (the planar study's update, the range of the no-feedback
/// extrapolation), largest and mean depth and volume after [`WEAR_CYCLES`], edge
/// concentration), `axial.csv` (per station after [`WEAR_CYCLES`]: worn area per unit length,
/// largest depth over φ, depth at the angle of the deepest point), `map_<deg>.csv` (the wear map
/// of one revolution, φ × z) and the figures `axial_profile` and `rim_profile`.
///
/// # Errors
/// A failing case or an output error.
pub fn study(dir: &Path) -> Result<Vec<JournalWearCase>, String> {
    let p = SliderCrankParams::wan();
    let cases: Vec<JournalWearCase> = MISALIGNMENTS_DEG
        .par_iter()
        .map(|&a| run_case(&p, a).map(|c| c.0))
        .collect::<Result<_, _>>()?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    write_summary(dir, &cases)?;
    write_maps(dir, &cases)?;
    figures(dir, &cases)?;
    Ok(cases)
}

/// The angle (rad) and station of the deepest knot of `map`.
pub fn deepest(map: &BearingWearMap) -> (f64, usize) {
    let (mut best, mut at) = (f64::NEG_INFINITY, (0, 0));
    for (m, s) in map.stations().iter().enumerate() {
        for (k, &h) in s.depths().iter().enumerate() {
            if h > best {
                (best, at) = (h, (k, m));
            }
        }
    }
    (TAU * at.0 as f64 / map.angles() as f64, at.1)
}

fn write_summary(dir: &Path, cases: &[JournalWearCase]) -> Result<(), String> {
    let header = [
        "misalignment_deg",
        "volume_per_cycle_m3",
        "max_depth_per_cycle_m",
        "cycles_to_1um",
        "max_depth_after_cycles_m",
        "mean_depth_after_cycles_m",
        "volume_after_cycles_m3",
        "edge_concentration",
        "deepest_angle_deg",
        "deepest_z_mm",
        "peak_radial_force_N",
        "wall_s",
    ];
    let rows: Vec<Vec<String>> = cases
        .iter()
        .map(|c| {
            let (phi, m) = deepest(&c.cycle);
            vec![
                format!("{}", c.misalignment_deg),
                format!("{:e}", c.volume_per_cycle),
                format!("{:e}", c.depth_per_cycle),
                format!("{:.0}", WEAR_DEPTH_PER_UPDATE / c.depth_per_cycle),
                format!("{:e}", WEAR_CYCLES * c.depth_per_cycle),
                format!("{:e}", WEAR_CYCLES * c.cycle.mean_depth()),
                format!("{:e}", WEAR_CYCLES * c.volume_per_cycle),
                format!("{:.4}", c.edge_concentration),
                format!("{:.1}", phi.to_degrees()),
                format!("{:.1}", c.cycle.station_z(m) * 1e3),
                format!("{:.3}", c.peak_force),
                format!("{:.2}", c.wall_s),
            ]
        })
        .collect();
    common::write_table_csv(&dir.join("summary.csv"), &header, &rows)
}

/// `axial.csv` and one `map_<deg>.csv` per case.
fn write_maps(dir: &Path, cases: &[JournalWearCase]) -> Result<(), String> {
    let mut header = vec!["z_mm".to_string()];
    for c in cases {
        let a = c.misalignment_deg;
        header.push(format!("worn_area_m2_{a}deg"));
        header.push(format!("max_depth_m_{a}deg"));
        header.push(format!("depth_at_deepest_angle_m_{a}deg"));
    }
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let rows: Vec<Vec<String>> = (0..WEAR_STATIONS)
        .map(|m| {
            let mut r = vec![format!("{:.1}", cases[0].cycle.station_z(m) * 1e3)];
            for c in cases {
                let phi = deepest(&c.cycle).0;
                let s = c.cycle.station(m);
                for v in [c.cycle.worn_area(m), s.max_depth(), s.depth_at(phi)] {
                    r.push(format!("{:e}", WEAR_CYCLES * v));
                }
            }
            r
        })
        .collect();
    common::write_table_csv(&dir.join("axial.csv"), &header, &rows)?;
    for c in cases {
        let map = &c.cycle;
        let n = map.angles();
        let rows: Vec<Vec<String>> = (0..WEAR_STATIONS)
            .flat_map(|m| {
                (0..n).map(move |k| {
                    vec![
                        format!("{}", 360.0 * k as f64 / n as f64),
                        format!("{:.1}", map.station_z(m) * 1e3),
                        format!("{:e}", map.station(m).depths()[k]),
                    ]
                })
            })
            .collect();
        common::write_table_csv(
            &dir.join(format!("map_{}deg.csv", c.misalignment_deg)),
            &["phi_deg", "z_mm", "depth_per_cycle_m"],
            &rows,
        )?;
    }
    Ok(())
}

/// `axial_profile`: the depth along the bore at the angle of the deepest point after
/// [`WEAR_CYCLES`] (and, misaligned, the largest depth over φ per station: the other rim); `rim_profile`: the depth around the bore at the most worn station.
fn figures(dir: &Path, cases: &[JournalWearCase]) -> Result<(), String> {
    use clr_plot::Figure;
    let um = WEAR_CYCLES * 1e6;
    let mut axial = Figure::new(format!(
        "Spatial Wan slider-crank, joint B: wear depth along the bore after {WEAR_CYCLES:.0e} \
         cycles (no feedback)"
    ))
    .x_label("z along the bore (mm)")
    .y_label("wear depth at the angle of the deepest point (µm)");
    let mut rim = Figure::new(format!(
        "Wear depth around the bore at the most worn station after {WEAR_CYCLES:.0e} cycles"
    ))
    .x_label("angle φ (deg, slider frame)")
    .y_label("wear depth (µm)");
    for c in cases {
        let (phi, worn) = deepest(&c.cycle);
        let label = format!(
            "misalignment {}° (φ = {:.0}°)",
            c.misalignment_deg,
            phi.to_degrees()
        );
        let z_mm = |m: usize| c.cycle.station_z(m) * 1e3;
        let pts = (0..WEAR_STATIONS)
            .map(|m| (z_mm(m), um * c.cycle.station(m).depth_at(phi)))
            .collect();
        axial = axial.line(label, pts);
        if c.misalignment_deg > 0.0 {
            // the other rim wears at another angle: the largest depth over φ shows both
            let pts = (0..WEAR_STATIONS)
                .map(|m| (z_mm(m), um * c.cycle.station(m).max_depth()))
                .collect();
            axial = axial.series(
                format!("misalignment {}°, largest over φ", c.misalignment_deg),
                pts,
                clr_plot::Style::Points,
            );
        }
        let s = c.cycle.station(worn);
        let n = s.len();
        let pts = (0..=n)
            .map(|k| (360.0 * k as f64 / n as f64, um * s.depths()[k % n]))
            .collect();
        rim = rim.line(
            format!(
                "misalignment {}°, z = {:.1} mm",
                c.misalignment_deg,
                z_mm(worn)
            ),
            pts,
        );
    }
    common::save_figure(axial, dir, "axial_profile")?;
    common::save_figure(rim, dir, "rim_profile")
}
