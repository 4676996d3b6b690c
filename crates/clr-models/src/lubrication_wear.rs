//! Studies of the lubricated and the worn revolute clearance joint (issue 17, item 3):
//!
//! - [`flap_lubricated`]: the rigid flap linkage with 0.1 mm in all four joints, dry against
//!   every joint lubricated (short bearing, ISO VG 46-like oil), under the steady hinge load and
//!   the reversing one (docs/lubrication.md, "Studies");
//! - [`wan_slider_crank_wear`]: the `wan_slider_crank` clearance joint worn by Archard's law
//!   over many crank cycles, one simulated steady-state cycle extrapolated per update
//!   (docs/wear.md, "Studies").

use std::f64::consts::FRAC_PI_2;
use std::path::Path;

use clr_contact::wear::{ArchardWear, BearingProfile, LineContact};
use clr_mbd::element::revolute_clearance::{LubricationDesc, LubricationModel};
use clr_mbd::element::Clearance;
use clr_mbd::{ModelDesc, Results};
use rayon::prelude::*;

use crate::common::{self, col, Record};
use crate::flap::{FlapParams, JOINTS};
use crate::slider_crank::SliderCrankParams;
use crate::{ModelsError, RunSettings};

/// Duration of the flap lubrication runs, s (ramp 0.25 s + 4 actuator periods).
pub const FLAP_LUB_DURATION: f64 = 2.25;
/// Radial clearance of all four flap joints, m (the paper's 0.1 mm).
pub const FLAP_LUB_CLEARANCE: f64 = 0.1e-3;
/// Dynamic viscosity of an ISO VG 46-like oil at 40 °C, Pa·s (typical value).
pub const OIL_VISCOSITY: f64 = 0.04;
/// Film threshold h_t, m (about three combined surface roughnesses; typical value).
pub const FILM_THRESHOLD: f64 = 1e-6;

/// Archard wear coefficient of dry steel on steel (typical value), –.
pub const WEAR_COEFFICIENT: f64 = 1e-5;
/// Hardness of the worn bearing, Pa (typical steel value, 2 GPa).
pub const WEAR_HARDNESS: f64 = 2e9;
/// Number of profile angles of the worn bearing.
pub const WEAR_ANGLES: usize = 360;
/// Largest depth added to any angle by one update, m.
pub const WEAR_DEPTH_PER_UPDATE: f64 = 1e-6;
/// Cycles at which the wear study stops.
pub const WEAR_MAX_CYCLES: f64 = 1e6;
/// Number of wear updates at most.
pub const WEAR_MAX_UPDATES: usize = 16;

/// The lubrication of a flap joint: short bearing, [`OIL_VISCOSITY`], the joint's axial length,
/// [`FILM_THRESHOLD`], dry law from the first touch.
pub fn flap_lubrication(p: &FlapParams, viscosity: f64) -> LubricationDesc {
    LubricationDesc {
        model: LubricationModel::ShortBearing,
        viscosity,
        length: p.axial_length,
        film_threshold: FILM_THRESHOLD,
        dry_threshold: 0.0,
    }
}

/// Set (or remove, with `None`) the lubrication of every revolute clearance joint.
pub fn lubricate_all(d: &mut ModelDesc, lub: Option<&LubricationDesc>) {
    for c in &mut d.clearances {
        if let Clearance::Revolute(r) = c {
            r.lubrication = lub.cloned();
        }
    }
}

/// One run of the flap lubrication study.
#[derive(Debug, Clone)]
pub struct FlapLubCase {
    /// Run name (`dry`, `lubricated`, `reversing_dry`, `reversing_lubricated`).
    pub name: String,
    /// Mean hinge moment, N·m.
    pub hinge_moment: f64,
    /// Lubricant viscosity, Pa·s (0 = dry).
    pub viscosity: f64,
    /// (name, value) metrics.
    pub metrics: Vec<(String, f64)>,
    /// Wall time of the clearance run, s.
    pub wall_s: f64,
}

impl FlapLubCase {
    /// A metric by name (NaN when absent).
    pub fn metric(&self, name: &str) -> f64 {
        self.metrics
            .iter()
            .find(|m| m.0 == name)
            .map_or(f64::NAN, |m| m.1)
    }
}

fn simulate_desc(model: &str, d: &ModelDesc) -> Result<Results, String> {
    let (mut m, opts) = common::compile_run(model, d).map_err(|e| e.to_string())?;
    common::simulate(&mut m, &opts, &RunSettings::default(), model).map_err(|e| e.to_string())
}

fn flap_desc(p: &FlapParams, record: Record) -> Result<ModelDesc, String> {
    common::run_desc("flap", &RunSettings::default(), record, || p.desc("flap"))
        .map_err(|e: ModelsError| e.to_string())
}

/// Flap angle (rad, from mid-stroke) and angular acceleration (rad/s²) of the rigid linkage.
fn flap_angle(res: &Results) -> (Vec<f64>, Vec<f64>) {
    let a = col(res, "aux_lever_arm.theta")
        .iter()
        .map(|th| th - FRAC_PI_2)
        .collect();
    (a, col(res, "aux_lever_arm.alpha"))
}

/// Metrics of a flap run against its ideal reference; appends `flap.error` and
/// `flap.alpha_error` to `res`.
fn flap_metrics(p: &FlapParams, res: &mut Results, ideal: &Results) -> Vec<(String, f64)> {
    let t = col(res, "t");
    let ti = col(ideal, "t");
    let (a, al) = flap_angle(res);
    let (ai, ali) = flap_angle(ideal);
    let (err, aerr) = crate::flap::errors_against_ideal(&t, (&a, &al), &ti, (&ai, &ali));
    let t0 = p.transient;
    let mut m = vec![
        (
            "flap_angle_error_max".into(),
            common::peak_abs(&t, &err, t0),
        ),
        (
            "flap_angle_error_rms".into(),
            common::time_rms(&t, &err, t0),
        ),
        (
            "flap_acceleration_oscillation_peak".into(),
            common::peak_abs(&t, &aerr, t0),
        ),
        (
            "flap_acceleration_oscillation_rms".into(),
            common::time_rms(&t, &aerr, t0),
        ),
    ];
    let has_film = res.columns.iter().any(|c| c.ends_with(".film_force"));
    for j in JOINTS {
        let fnn = col(res, &format!("{j}.normal_force"));
        let rows = (common::peak_abs(&t, &fnn, t0), 0.0);
        m.push((
            format!("{j}_peak_normal_force"),
            common::located_peaks(res, j, t0, rows).0,
        ));
        let (ff, hmin) = if has_film {
            let h = col(res, &format!("{j}.film_thickness"));
            let hmin = t
                .iter()
                .zip(&h)
                .filter(|(&ti, _)| ti >= t0)
                .map(|(_, &x)| x)
                .fold(f64::INFINITY, f64::min);
            (
                common::peak_abs(&t, &col(res, &format!("{j}.film_force")), t0),
                hmin,
            )
        } else {
            (0.0, f64::NAN)
        };
        m.push((format!("{j}_peak_film_force"), ff));
        m.push((format!("{j}_min_film_thickness"), hmin));
        m.push((
            format!("{j}_contact_time_fraction"),
            common::time_mean(&t, &col(res, &format!("{j}.contact")), t0),
        ));
        let impacts = res
            .impacts
            .iter()
            .filter(|i| i.joint == j && i.peak_force_time >= t0)
            .count();
        m.push((format!("{j}_impacts"), impacts as f64));
    }
    common::append_columns(
        res,
        vec![
            ("flap.error".into(), err),
            ("flap.alpha_error".into(), aerr),
        ],
    );
    m
}

/// The flap lubrication study: 0.1 mm in all four joints, dry against every joint lubricated
/// (short bearing, μ = [`OIL_VISCOSITY`], L = `axial_length`, h_t = [`FILM_THRESHOLD`]), at the
/// steady hinge moment of the built-in `flap` and at zero mean hinge moment (the joints unload
/// and the journals cross their clearance), each against its ideal reference; 6 simulations of
/// [`FLAP_LUB_DURATION`] s in parallel. Writes `<run>.csv`, `summary.csv` and the figures
/// `oscillation`, `peak_forces`, `alpha_error`, `film_thickness` under `dir`.
///
/// # Errors
/// A failing run or an output error.
pub fn flap_lubricated(dir: &Path) -> Result<Vec<FlapLubCase>, String> {
    let base = FlapParams {
        clearances: [FLAP_LUB_CLEARANCE; 4],
        duration: FLAP_LUB_DURATION,
        ..Default::default()
    };
    let reversing = FlapParams {
        hinge_moment: 0.0,
        ..base.clone()
    };
    // (name, params, viscosity; None = the ideal reference)
    let jobs: Vec<(String, FlapParams, Option<f64>)> = vec![
        ("ideal".into(), base.clone(), None),
        ("dry".into(), base.clone(), Some(0.0)),
        ("lubricated".into(), base.clone(), Some(OIL_VISCOSITY)),
        ("reversing_ideal".into(), reversing.clone(), None),
        ("reversing_dry".into(), reversing.clone(), Some(0.0)),
        (
            "reversing_lubricated".into(),
            reversing.clone(),
            Some(OIL_VISCOSITY),
        ),
    ];
    let done: Vec<Result<(String, Results, f64), String>> = jobs
        .par_iter()
        .map(|(name, p, visc)| {
            let start = std::time::Instant::now();
            let d = match visc {
                None => {
                    let ideal = FlapParams {
                        clearances: [0.0; 4],
                        ..p.clone()
                    };
                    flap_desc(&ideal, Record::Every(ideal.reference_interval))?
                }
                Some(mu) => {
                    let mut d = flap_desc(p, Record::EveryStep)?;
                    let lub = (*mu > 0.0).then(|| flap_lubrication(p, *mu));
                    lubricate_all(&mut d, lub.as_ref());
                    d
                }
            };
            let r = simulate_desc("flap", &d).map_err(|e| format!("{name}: {e}"))?;
            Ok((name.clone(), r, start.elapsed().as_secs_f64()))
        })
        .collect();
    let mut runs = Vec::new();
    for r in done {
        runs.push(r?);
    }
    let ideal_of = |name: &str| -> &Results {
        let key = if name.starts_with("reversing") {
            "reversing_ideal"
        } else {
            "ideal"
        };
        &runs.iter().find(|r| r.0 == key).expect("ideal run").1
    };
    let mut cases = Vec::new();
    let mut results = Vec::new();
    for ((name, p, visc), (_, res, wall)) in jobs.iter().zip(&runs) {
        let Some(mu) = visc else { continue };
        let mut res = res.clone();
        let metrics = flap_metrics(p, &mut res, ideal_of(name));
        common::write_results_csv(&res, dir, name)?;
        cases.push(FlapLubCase {
            name: name.clone(),
            hinge_moment: p.hinge_moment,
            viscosity: *mu,
            metrics,
            wall_s: *wall,
        });
        results.push(res);
    }
    write_flap_summary(dir, &cases)?;
    flap_figures(dir, &cases, &results)?;
    Ok(cases)
}

fn write_flap_summary(dir: &Path, cases: &[FlapLubCase]) -> Result<(), String> {
    let names: Vec<&str> = cases[0].metrics.iter().map(|m| m.0.as_str()).collect();
    let mut header = vec!["run", "hinge_moment_Nm", "viscosity_Pas", "wall_s"];
    header.extend(names.iter().copied());
    let rows: Vec<Vec<String>> = cases
        .iter()
        .map(|c| {
            let mut r = vec![
                c.name.clone(),
                format!("{}", c.hinge_moment),
                format!("{}", c.viscosity),
                format!("{:.3}", c.wall_s),
            ];
            r.extend(names.iter().map(|n| format!("{:e}", c.metric(n))));
            r
        })
        .collect();
    common::write_table_csv(&dir.join("summary.csv"), &header, &rows)
}

fn flap_figures(dir: &Path, cases: &[FlapLubCase], results: &[Results]) -> Result<(), String> {
    use clr_plot::Figure;
    const MAX: usize = 3000;
    let joint_x = |k: usize, shift: f64| (k + 1) as f64 + shift;
    let mut forces = Figure::new("Peak forces per joint after the transient (0.1 mm, all joints)")
        .x_label("joint (1 actuator, 2 lever pivot, 3 lever-rod, 4 rod-aux lever)")
        .y_label("peak force (N)");
    for (ci, c) in cases.iter().enumerate() {
        let shift = -0.15 + 0.1 * ci as f64;
        let pts = |what: &str| -> Vec<(f64, f64)> {
            JOINTS
                .iter()
                .enumerate()
                .map(|(k, j)| (joint_x(k, shift), c.metric(&format!("{j}_{what}"))))
                .collect()
        };
        forces = forces.points(
            format!("{}: dry contact force", c.name),
            pts("peak_normal_force"),
        );
        if c.viscosity > 0.0 {
            forces = forces.points(format!("{}: film force", c.name), pts("peak_film_force"));
        }
    }
    common::save_figure(forces, dir, "peak_forces")?;
    let xs: Vec<f64> = (0..cases.len()).map(|k| k as f64).collect();
    let osc = Figure::new(
        "Flap angular-acceleration oscillation (0 dry, 1 lubricated, 2 reversing dry, \
         3 reversing lubricated)",
    )
    .x_label("run")
    .y_label("α − α_ideal (rad/s²)")
    .points(
        "peak",
        xs.iter()
            .zip(cases)
            .map(|(&x, c)| (x, c.metric("flap_acceleration_oscillation_peak")))
            .collect(),
    )
    .points(
        "RMS",
        xs.iter()
            .zip(cases)
            .map(|(&x, c)| (x, c.metric("flap_acceleration_oscillation_rms")))
            .collect(),
    );
    common::save_figure(osc, dir, "oscillation")?;
    let mut aerr = Figure::new("Flap angular acceleration − ideal")
        .x_label("time (s)")
        .y_label("α − α_ideal (rad/s²)");
    let mut film = Figure::new("Minimum film thickness, lubricated runs")
        .x_label("time (s)")
        .y_label("h_min (µm)");
    for (c, r) in cases.iter().zip(results) {
        let t = col(r, "t");
        aerr = aerr.line(
            c.name.clone(),
            common::thin(&t, &col(r, "flap.alpha_error"), MAX),
        );
        if c.viscosity > 0.0 {
            for j in JOINTS {
                let h: Vec<f64> = col(r, &format!("{j}.film_thickness"))
                    .iter()
                    .map(|x| x * 1e6)
                    .collect();
                film = film.line(format!("{} {j}", c.name), common::thin(&t, &h, MAX));
            }
        }
    }
    common::save_figure(aerr, dir, "alpha_error")?;
    common::save_figure(film, dir, "film_thickness")
}

// ---------------------------------------------------------------------------------------------
// Wear of the Wan slider-crank

/// Name of the clearance joint of the slider–crank.
const WEAR_JOINT: &str = "B";

/// The recorded contact history of joint `B` for t ≥ `t_from`: (t, φ_c, F_N, v_T) with the
/// bearing-frame contact angle φ_c = atan2(e_y, e_x) and the sliding speed approximated by the
/// relative rotation of journal (rod) and bearing (slider), v_T ≈ |(ω_rod − ω_slider) R_j|
/// (the joint does not record its sliding speed).
pub fn contact_history(res: &Results, t_from: f64, journal_radius: f64) -> [Vec<f64>; 4] {
    let t = col(res, "t");
    let ex = col(res, &format!("{WEAR_JOINT}.ex"));
    let ey = col(res, &format!("{WEAR_JOINT}.ey"));
    let fnn = col(res, &format!("{WEAR_JOINT}.normal_force"));
    let wj = col(res, "rod.omega");
    let wb = col(res, "slider.omega");
    let mut out: [Vec<f64>; 4] = Default::default();
    for k in 0..t.len() {
        if t[k] < t_from {
            continue;
        }
        out[0].push(t[k]);
        out[1].push(ey[k].atan2(ex[k]));
        out[2].push(fnn[k].max(0.0));
        out[3].push(((wj[k] - wb[k]) * journal_radius).abs());
    }
    out
}

/// The Archard law of the Wan joint: K = [`WEAR_COEFFICIENT`], H = [`WEAR_HARDNESS`], Hertz line
/// contact of the joint's radii over its axial length, steel on steel.
///
/// # Errors
/// Invalid radii or moduli.
pub fn wan_archard(p: &SliderCrankParams) -> Result<ArchardWear, String> {
    let e_star = p.youngs_modulus / (2.0 * (1.0 - p.poisson_ratio * p.poisson_ratio));
    let lc = LineContact::new(p.bearing_radius, p.journal_radius, p.axial_length, e_star)
        .map_err(|e| e.to_string())?;
    ArchardWear::new(WEAR_COEFFICIENT, WEAR_HARDNESS, lc).map_err(|e| e.to_string())
}

/// Simulate the slider–crank with the bearing worn as `wear` (m at N angles) over
/// `transient_revolutions` + 1 revolutions; the run's results.
///
/// # Errors
/// Build or simulation errors.
pub fn wear_cycle_run(p: &SliderCrankParams, wear: &[f64]) -> Result<Results, String> {
    let period = 60.0 / p.crank_speed_rpm;
    let q = SliderCrankParams {
        duration: (p.transient_revolutions + 1.0) * period,
        ..p.clone()
    };
    let mut d = q.desc("wan_slider_crank").map_err(|e| e.to_string())?;
    for c in &mut d.clearances {
        if let Clearance::Revolute(r) = c {
            if r.name == WEAR_JOINT {
                r.bearing_wear = Some(wear.to_vec());
            }
        }
    }
    simulate_desc("wan_slider_crank", &d)
}

/// The effective growth of the radial clearance, m: the largest mean wear depth of two opposite
/// angles, max_φ (h(φ) + h(φ + π))/2 (the diametral play along the most worn diameter grows by
/// twice this). N must be even.
pub fn clearance_growth(profile: &BearingProfile) -> f64 {
    let h = profile.depths();
    let n = h.len();
    (0..n / 2)
        .map(|k| 0.5 * (h[k] + h[k + n / 2]))
        .fold(0.0, f64::max)
}

/// One update of the wear study.
#[derive(Debug, Clone)]
pub struct WearUpdate {
    /// Cycles of wear in the bearing profile the cycle was simulated with.
    pub cycles: f64,
    /// Largest and mean wear depth of that profile, m.
    pub max_depth: f64,
    /// Mean wear depth, m.
    pub mean_depth: f64,
    /// Effective clearance growth ([`clearance_growth`]), m.
    pub clearance_growth: f64,
    /// Peak contact force of the simulated steady-state cycle, N.
    pub peak_force: f64,
    /// Number of impacts (located contact onsets) in that cycle.
    pub impacts: usize,
    /// Worn volume per cycle (Archard), m³.
    pub volume_per_cycle: f64,
    /// Largest depth added per cycle, m.
    pub depth_per_cycle: f64,
    /// Cycles extrapolated after this simulation (0 for the last).
    pub delta_cycles: f64,
    /// Wall time of the simulation, s.
    pub wall_s: f64,
}

/// The Wan slider–crank wear study: starting from the circular bearing, each update simulates
/// the built-in `wan_slider_crank` for one transient and one steady-state crank revolution with
/// the current wear profile (N = [`WEAR_ANGLES`]), accumulates the Archard wear of the
/// steady-state revolution from its history ([`contact_history`], [`wan_archard`]) and adds it
/// ΔN times, ΔN chosen so that no angle deepens by more than [`WEAR_DEPTH_PER_UPDATE`] (and the
/// total stays ≤ [`WEAR_MAX_CYCLES`]); at most [`WEAR_MAX_UPDATES`] updates. Writes
/// `cycle_<k>.csv` (the simulated revolution of some updates), `profiles.csv`, `summary.csv` and
/// the figures `profiles`, `clearance_growth`, `peak_force`.
///
/// # Errors
/// A failing run or an output error.
pub fn wan_slider_crank_wear(dir: &Path) -> Result<Vec<WearUpdate>, String> {
    let p = SliderCrankParams::wan();
    let law = wan_archard(&p)?;
    let period = 60.0 / p.crank_speed_rpm;
    let t_from = p.transient_revolutions * period;
    let mut profile = BearingProfile::zero(WEAR_ANGLES).map_err(|e| e.to_string())?;
    let mut cycles = 0.0;
    let mut updates: Vec<WearUpdate> = Vec::new();
    let mut snapshots: Vec<(f64, Vec<f64>)> = vec![(0.0, profile.depths().to_vec())];
    for k in 0..=WEAR_MAX_UPDATES {
        let start = std::time::Instant::now();
        let res = wear_cycle_run(&p, profile.depths())?;
        let wall_s = start.elapsed().as_secs_f64();
        let [t, phi, fnn, vt] = contact_history(&res, t_from, p.journal_radius);
        let mut inc = BearingProfile::zero(WEAR_ANGLES).map_err(|e| e.to_string())?;
        let volume = law
            .accumulate_history(&mut inc, &t, &phi, &fnn, &vt)
            .map_err(|e| e.to_string())?;
        let tt = col(&res, "t");
        let rows = (
            common::peak_abs(
                &tt,
                &col(&res, &format!("{WEAR_JOINT}.normal_force")),
                t_from,
            ),
            0.0,
        );
        let peak_force = common::located_peaks(&res, WEAR_JOINT, t_from, rows).0;
        let impacts = res
            .impacts
            .iter()
            .filter(|i| i.joint == WEAR_JOINT && i.peak_force_time >= t_from)
            .count();
        let per_cycle = inc.max_depth();
        let last = k == WEAR_MAX_UPDATES || cycles >= WEAR_MAX_CYCLES;
        let delta = if last || per_cycle <= 0.0 {
            0.0
        } else {
            (WEAR_DEPTH_PER_UPDATE / per_cycle)
                .floor()
                .max(1.0)
                .min(WEAR_MAX_CYCLES - cycles)
        };
        if k % 4 == 0 || last {
            common::write_results_csv(&res, dir, &format!("cycle_{k:02}"))?;
        }
        updates.push(WearUpdate {
            cycles,
            max_depth: profile.max_depth(),
            mean_depth: profile.mean_depth(),
            clearance_growth: clearance_growth(&profile),
            peak_force,
            impacts,
            volume_per_cycle: volume,
            depth_per_cycle: per_cycle,
            delta_cycles: delta,
            wall_s,
        });
        if delta == 0.0 {
            break;
        }
        profile.add_scaled(&inc, delta).map_err(|e| e.to_string())?;
        cycles += delta;
        snapshots.push((cycles, profile.depths().to_vec()));
    }
    write_wear_outputs(dir, &updates, &snapshots)?;
    Ok(updates)
}

fn write_wear_outputs(
    dir: &Path,
    updates: &[WearUpdate],
    snapshots: &[(f64, Vec<f64>)],
) -> Result<(), String> {
    use clr_plot::Figure;
    let header = [
        "update",
        "cycles",
        "max_depth_m",
        "mean_depth_m",
        "clearance_growth_m",
        "peak_contact_force_N",
        "impacts",
        "volume_per_cycle_m3",
        "max_depth_per_cycle_m",
        "delta_cycles",
        "wall_s",
    ];
    let rows: Vec<Vec<String>> = updates
        .iter()
        .enumerate()
        .map(|(k, u)| {
            vec![
                k.to_string(),
                format!("{}", u.cycles),
                format!("{:e}", u.max_depth),
                format!("{:e}", u.mean_depth),
                format!("{:e}", u.clearance_growth),
                format!("{:e}", u.peak_force),
                u.impacts.to_string(),
                format!("{:e}", u.volume_per_cycle),
                format!("{:e}", u.depth_per_cycle),
                format!("{}", u.delta_cycles),
                format!("{:.3}", u.wall_s),
            ]
        })
        .collect();
    common::write_table_csv(&dir.join("summary.csv"), &header, &rows)?;
    // profiles.csv: angle (deg), then the depth (m) after each update
    let n = WEAR_ANGLES;
    let mut ph = vec!["angle_deg".to_string()];
    ph.extend(
        snapshots
            .iter()
            .map(|(c, _)| format!("depth_m_after_{c}_cycles")),
    );
    let ph_ref: Vec<&str> = ph.iter().map(String::as_str).collect();
    let prows: Vec<Vec<String>> = (0..n)
        .map(|k| {
            let mut r = vec![format!("{}", 360.0 * k as f64 / n as f64)];
            r.extend(snapshots.iter().map(|(_, h)| format!("{:e}", h[k])));
            r
        })
        .collect();
    common::write_table_csv(&dir.join("profiles.csv"), &ph_ref, &prows)?;
    let mut prof =
        Figure::new("Bearing wear profile of the Wan slider-crank joint (bearing frame)")
            .x_label("angle φ (deg, slider frame)")
            .y_label("wear depth (µm)");
    let m = snapshots.len();
    let picks: Vec<usize> = if m <= 5 {
        (1..m).collect()
    } else {
        vec![1, m / 4, m / 2, 3 * m / 4, m - 1]
    };
    let mut seen = Vec::new();
    for i in picks {
        if i == 0 || seen.contains(&i) {
            continue;
        }
        seen.push(i);
        let (c, h) = &snapshots[i];
        let pts = (0..=n)
            .map(|k| (360.0 * k as f64 / n as f64, h[k % n] * 1e6))
            .collect();
        prof = prof.line(format!("{c:.0} cycles"), pts);
    }
    common::save_figure(prof, dir, "profiles")?;
    let growth: Vec<(f64, f64)> = updates
        .iter()
        .map(|u| (u.cycles, u.clearance_growth * 1e6))
        .collect();
    let maxd: Vec<(f64, f64)> = updates
        .iter()
        .map(|u| (u.cycles, u.max_depth * 1e6))
        .collect();
    common::save_figure(
        Figure::new("Wear of the Wan slider-crank joint (K = 1e-5, H = 2 GPa)")
            .x_label("crank cycles")
            .y_label("µm")
            .line("effective clearance growth", growth.clone())
            .points("", growth)
            .line("max wear depth", maxd.clone())
            .points(" ", maxd),
        dir,
        "clearance_growth",
    )?;
    let pf: Vec<(f64, f64)> = updates.iter().map(|u| (u.cycles, u.peak_force)).collect();
    common::save_figure(
        Figure::new("Peak contact force of the steady-state cycle vs wear")
            .x_label("crank cycles")
            .y_label("peak contact force (N)")
            .line("peak force", pf.clone())
            .points("", pf),
        dir,
        "peak_force",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One wear update on a short run: the profile's worn volume L R_i Δφ Σ h_k equals Archard's
    /// K Σ F_N ds / H summed by hand over the same history (trapezoidal weights), to 1e-9.
    #[test]
    fn wear_update_conserves_the_archard_volume() {
        let p = SliderCrankParams {
            transient_revolutions: 0.0,
            ..SliderCrankParams::wan()
        };
        let q = SliderCrankParams {
            duration: 0.02,
            ..p.clone()
        };
        let d = q.desc("wan_slider_crank").unwrap();
        let res = simulate_desc("wan_slider_crank", &d).unwrap();
        let [t, phi, fnn, vt] = contact_history(&res, 0.0, p.journal_radius);
        let law = wan_archard(&p).unwrap();
        let mut prof = BearingProfile::zero(WEAR_ANGLES).unwrap();
        let v = law
            .accumulate_history(&mut prof, &t, &phi, &fnn, &vt)
            .unwrap();
        let m = t.len();
        let mut by_hand = 0.0;
        for i in 0..m {
            let before = t[i.saturating_sub(1)];
            let after = t[(i + 1).min(m - 1)];
            by_hand += fnn[i] * vt[i] * 0.5 * (after - before);
        }
        by_hand *= WEAR_COEFFICIENT / WEAR_HARDNESS;
        assert!(by_hand > 0.0, "the short run must slide in contact");
        let worn = prof.worn_volume(p.bearing_radius, p.axial_length);
        assert!(
            (worn - by_hand).abs() <= 1e-9 * by_hand,
            "{worn} vs {by_hand}"
        );
        assert!((v - by_hand).abs() <= 1e-9 * by_hand, "{v} vs {by_hand}");
        // the effective clearance growth never exceeds the largest depth
        assert!(clearance_growth(&prof) <= prof.max_depth());
        assert!(phi.iter().all(|a| a.abs() <= std::f64::consts::PI + 1e-12));
    }
}
