//! The flexible-body studies of the flap linkage (`clr study flap_flexible`; docs/models/flap.md
//! "Flexible-body studies"): the configurations, their runs with [`crate::flap::run`] and the
//! parts of [`crate::flap_flex`], the summary and the figures.

use std::path::Path;

use clr_mbd::Results;

use crate::common::{self, col};
use crate::flap::{self, StudyCase, JOINTS};
use crate::flap_flex::{with_beam_masses, MAX_CSV_ROWS};
use crate::flap_params::FlapParams;

/// One configuration of the flexible-body studies: (study, label, abscissa, flexible parts,
/// clearances of J1..J4 in m, mean hinge moment in N·m or `None` for the base value).
pub type FlexConfiguration = (String, String, f64, [bool; 3], [f64; 4], Option<f64>);

/// Flexible parts of the `bodies` study with n = 0..3 flexible bodies: the auxiliary rod (the
/// softest) first, then the auxiliary lever arm, then the lever arm.
pub const BODIES_ORDER: [[bool; 3]; 4] = [
    [false, false, false],
    [false, true, false],
    [false, true, true],
    [true, true, true],
];

/// The study configurations (0.1 mm clearances): `bodies` — n = 0..3 flexible bodies
/// ([`BODIES_ORDER`]) with J4 the clearance joint; `joints` — J1..Jn, n = 1..4 (the order of
/// the rigid `number` study), with the auxiliary rod flexible; `joints_j4` — J(5−n)..J4, the
/// same series started from the `bodies` study's joint J4; `joints_rigid`, `joints_j4_rigid`
/// — the same joints, all parts rigid (the references of the reduction); `all` — J1..J4 with
/// the three parts flexible; `reversing` — J1..J4 with 0, 1 (the rod) and 3 flexible parts and a
/// zero mean hinge moment (the load changes sign, the journals cross their clearance: impacts).
pub fn configurations() -> Vec<FlexConfiguration> {
    let c = 0.1e-3;
    let mut v = Vec::new();
    for (n, f) in BODIES_ORDER.iter().enumerate() {
        v.push((
            "bodies".into(),
            format!("f{n}"),
            n as f64,
            *f,
            [0.0, 0.0, 0.0, c],
            None,
        ));
    }
    for n in 1..=4 {
        let mut up = [0.0; 4];
        up.iter_mut().take(n).for_each(|x| *x = c);
        let mut down = [0.0; 4];
        down.iter_mut().rev().take(n).for_each(|x| *x = c);
        for (series, cl) in [("joints", up), ("joints_j4", down)] {
            v.push((
                series.into(),
                format!("n{n}"),
                n as f64,
                [false, true, false],
                cl,
                None,
            ));
            v.push((
                format!("{series}_rigid"),
                format!("n{n}"),
                n as f64,
                [false; 3],
                cl,
                None,
            ));
        }
    }
    v.push(("all".into(), "n4_f3".into(), 4.0, [true; 3], [c; 4], None));
    for (n, f) in [
        (0usize, [false; 3]),
        (1, [false, true, false]),
        (3, [true; 3]),
    ] {
        v.push((
            "reversing".into(),
            format!("n4_f{n}"),
            n as f64,
            f,
            [c; 4],
            Some(0.0),
        ));
    }
    v
}

/// A case of the flexible-body studies.
#[derive(Debug, Clone)]
pub struct FlexStudyCase {
    /// Flexible parts [lever arm, auxiliary rod, auxiliary lever arm].
    pub flexible: [bool; 3],
    /// Study, label, abscissa, clearances, metrics of [`flap::run`] (the ideal reference is the
    /// same flexible configuration with ideal joints), wall time.
    pub case: StudyCase,
}

/// Run the flexible-body studies ([`configurations`]) in parallel (rayon) with `base` (its
/// rigid masses replaced by [`with_beam_masses`]) for every other parameter, writing under
/// `dir`: `<study>_<label>.csv` (at most about [`MAX_CSV_ROWS`] rows), `summary.csv` and
/// figures (`bodies_oscillation`, `joints_oscillation`, `joints_reduction`, `poincare_spread`,
/// `orbits_all`, `poincare_all`).
///
/// # Errors
/// The first failing case, or an output error.
pub fn study(dir: &Path, base: &FlapParams) -> Result<Vec<FlexStudyCase>, String> {
    study_of(dir, base, configurations())
}

/// As [`study`] for the given configurations only (e.g. [`configurations`] without its most
/// expensive cases).
///
/// # Errors
/// As [`study`].
pub fn study_of(
    dir: &Path,
    base: &FlapParams,
    configurations: Vec<FlexConfiguration>,
) -> Result<Vec<FlexStudyCase>, String> {
    let base = with_beam_masses(base)?;
    let configs: Vec<_> = configurations
        .into_iter()
        .map(|(study, label, x, flexible, clearances, hinge)| {
            let p = FlapParams {
                clearances,
                flexible,
                hinge_moment: hinge.unwrap_or(base.hinge_moment),
                ..base.clone()
            };
            (study, label, x, p)
        })
        .collect();
    let flex: Vec<[bool; 3]> = configs.iter().map(|c| c.3.flexible).collect();
    let (cases, results) = flap::run_cases(dir, configs, Some(MAX_CSV_ROWS))?;
    let cases: Vec<FlexStudyCase> = cases
        .into_iter()
        .zip(flex)
        .map(|(case, flexible)| FlexStudyCase { flexible, case })
        .collect();
    write_summary(dir, &cases)?;
    figures(dir, &base, &cases, &results)?;
    Ok(cases)
}

/// The case of `study` with abscissa `x`.
pub fn find<'a>(cases: &'a [FlexStudyCase], study: &str, x: f64) -> Option<&'a FlexStudyCase> {
    cases
        .iter()
        .find(|c| c.case.study == study && c.case.x == x)
}

/// Reduction of the RMS flap acceleration oscillation by the flexible auxiliary rod with n
/// clearance joints of `series` (`joints` or `joints_j4`): 1 − RMS(series, n) /
/// RMS(series`_rigid`, n) (NaN when absent).
pub fn reduction(cases: &[FlexStudyCase], series: &str, n: usize) -> f64 {
    let m = |s: &str| {
        find(cases, s, n as f64).map_or(f64::NAN, |c| {
            c.case.metric("flap_acceleration_oscillation_rms")
        })
    };
    1.0 - m(series) / m(&format!("{series}_rigid"))
}

fn write_summary(dir: &Path, cases: &[FlexStudyCase]) -> Result<(), String> {
    let runs: Vec<_> = cases
        .iter()
        .map(|c| {
            let mut keys = vec![
                c.case.study.clone(),
                c.case.label.clone(),
                format!("{}", c.case.x),
            ];
            keys.extend(c.flexible.iter().map(|f| format!("{}", u8::from(*f))));
            keys.extend(c.case.clearances.iter().map(|v| format!("{v:e}")));
            (keys, c.case.wall_s, c.case.metrics.as_slice())
        })
        .collect();
    common::write_study_summary(
        dir,
        &[
            "study",
            "case",
            "x",
            "flex_lever_arm",
            "flex_aux_rod",
            "flex_aux_lever_arm",
            "c1",
            "c2",
            "c3",
            "c4",
        ],
        &runs,
    )
}

fn figures(
    dir: &Path,
    base: &FlapParams,
    cases: &[FlexStudyCase],
    results: &[Results],
) -> Result<(), String> {
    use clr_plot::Figure;
    let save = |f: Figure, name: &str| common::save_figure(f, dir, name);
    let series = |study: &str, metric: &str| -> Vec<(f64, f64)> {
        cases
            .iter()
            .filter(|c| c.case.study == study)
            .map(|c| (c.case.x, c.case.metric(metric)))
            .collect()
    };
    let (pk, rms) = (
        "flap_acceleration_oscillation_peak",
        "flap_acceleration_oscillation_rms",
    );
    save(
        Figure::new(
            "Number of flexible bodies (J4 clearance 0.1 mm): flap acceleration oscillation",
        )
        .x_label("number of flexible bodies (0; +aux rod; +aux lever arm; +lever arm)")
        .y_label("oscillation vs ideal (rad/s²)")
        .line("peak", series("bodies", pk))
        .points("peak ", series("bodies", pk))
        .line("RMS", series("bodies", rms))
        .points("RMS ", series("bodies", rms)),
        "bodies_oscillation",
    )?;
    let mut osc =
        Figure::new("Number of clearance joints (0.1 mm): RMS flap acceleration oscillation")
            .x_label("number of clearance joints")
            .y_label("RMS oscillation vs ideal (rad/s²)");
    let mut red = Figure::new("Reduction of the RMS oscillation by the flexible auxiliary rod")
        .x_label("number of clearance joints")
        .y_label("1 − RMS(flexible)/RMS(rigid) (–)");
    for (s, what) in [("joints", "J1..Jn"), ("joints_j4", "J(5−n)..J4")] {
        osc = osc
            .line(format!("rigid, {what}"), series(&format!("{s}_rigid"), rms))
            .points(
                format!("rigid, {what} "),
                series(&format!("{s}_rigid"), rms),
            )
            .line(format!("flexible aux rod, {what}"), series(s, rms))
            .points(format!("flexible aux rod, {what} "), series(s, rms));
        let r: Vec<(f64, f64)> = (1..=4)
            .map(|n| (n as f64, reduction(cases, s, n)))
            .collect();
        red = red.line(what, r.clone()).points(format!("{what} "), r);
    }
    save(osc, "joints_oscillation")?;
    save(red, "joints_reduction")?;
    let spread: Vec<(f64, f64)> = cases
        .iter()
        .enumerate()
        .map(|(i, c)| (i as f64, c.case.metric("poincare_spread")))
        .collect();
    save(
        Figure::new("Poincaré-section spread per case (order of summary.csv)")
            .x_label("case index")
            .y_label("spread / clearance (–)")
            .points("spread", spread)
            .log_y(),
        "poincare_spread",
    )?;
    let mm = |v: Vec<f64>| v.into_iter().map(|x| x * 1e3).collect::<Vec<_>>();
    for (c, r) in cases.iter().zip(results) {
        if c.case.study != "all" {
            continue;
        }
        let t = col(r, "t");
        let mut orb =
            Figure::new("Journal-centre orbits, four clearance joints, three flexible bodies")
                .x_label("e_x (mm)")
                .y_label("e_y (mm)")
                .equal_aspect();
        let mut poin = Figure::new(
            "Poincaré sections (phase 0), four clearance joints, three flexible bodies",
        )
        .x_label("e_x (mm)")
        .y_label("e_y (mm)")
        .equal_aspect();
        let t_end = t.last().copied().unwrap_or(0.0);
        for j in JOINTS {
            let (ex, ey) = (col(r, &format!("{j}.ex")), col(r, &format!("{j}.ey")));
            orb = orb.line(j, common::thin(&mm(ex.clone()), &mm(ey.clone()), 3000));
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
        save(orb, "orbits_all")?;
        save(poin, "poincare_all")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flap_flex::{adams_default_damping, flexible_body, static_deflection_angle};
    use crate::RunSettings;

    #[test]
    fn reduced_parts_keep_the_calibrated_first_frequency() {
        // independent check of the reduction and of the floating-frame invariants that clr-mbd
        // uses: the pinned–roller first frequency of the reduced body (frame rotation + CB
        // coordinates) against the full-beam calibration (= the paper's first frequency), 1 %
        let p = FlapParams::default();
        for k in 0..3 {
            let b = flexible_body(&p, k).unwrap();
            let f = b.reduced_first_frequency().unwrap();
            let target = b.calibration.frequencies_hz[0];
            println!(
                "{}: reduced f1 {f:.2} Hz, calibrated {target:.2} Hz, mass {:.4} kg, {} coordinates",
                b.part.name,
                b.mass(),
                b.reduced.stiffness.nrows()
            );
            assert!(
                (f / target - 1.0).abs() < 0.01,
                "{}: reduced {f} Hz vs calibrated {target} Hz",
                b.part.name
            );
            // the default damping is the Adams/Flex band value at the paper's first frequency
            assert_eq!(
                p.flexible_damping_ratios[k],
                adams_default_damping(b.part.target_hz)
            );
            // the beam mass agrees with the rigid default masses (rounded) within 1 %
            let rigid = [p.lever_arm_mass, p.aux_rod_mass, p.aux_lever_arm_mass][k];
            assert!((b.mass() / rigid - 1.0).abs() < 0.01, "{} kg", b.mass());
        }
    }

    /// The `reversing` case with the flexible auxiliary rod (four 0.1 mm clearance joints, zero
    /// mean hinge moment, impacts from the start): NDF used to stop at t = 3.6 ms with 21
    /// Newton failures in one step (its corrections stalled at the rounding noise of the
    /// accelerations, far below the Newton tolerance; clr-ode's `NOISE_FLOOR`). It now runs,
    /// and the flap angle stays within the play of the four joints of the closed-form rigid
    /// angle (each 0.1 mm on levers of 40 mm and more: under 0.01 rad in total).
    #[test]
    fn reversing_load_with_flexible_rod_runs_through_the_impacts() {
        let base = with_beam_masses(&FlapParams::default()).unwrap();
        let p = FlapParams {
            clearances: [0.1e-3; 4],
            flexible: [false, true, false],
            hinge_moment: 0.0,
            duration: 0.01,
            ..base
        };
        let r = &flap::simulate("flap", &p, &RunSettings::default(), false).unwrap();
        let (t, a) = (col(r, "t"), col(r, "flap.angle"));
        assert!(*t.last().unwrap() >= 0.01 - 1e-12);
        for k in 0..t.len() {
            let x = p.actuator(t[k])[0];
            let cf = p.ideal_flap_angle(x, p.aux_rod_length).unwrap();
            assert!((a[k] - cf).abs() < 0.01, "t {}: {} vs {cf}", t[k], a[k]);
        }
    }

    #[test]
    fn flexible_linkage_with_ideal_joints_follows_the_rigid_kinematics() {
        // independent formulation: the closed-form rigid flap angle (circle intersections);
        // the flexible linkage deviates by its quasi-static deflection under the hinge load,
        // bounded by static_deflection_angle (beam formulas). The parts start undeformed under
        // the hinge load (a step load), so the response of this damped linear structure stays
        // below twice the static deflection (the undamped step-response peak).
        let p = FlapParams {
            clearances: [0.0; 4],
            flexible: [true; 3],
            duration: 0.1,
            ..FlapParams::default()
        };
        let bound = static_deflection_angle(&p).unwrap();
        let r = &flap::simulate("flap", &p, &RunSettings::default(), false).unwrap();
        let (t, a) = (col(r, "t"), col(r, "flap.angle"));
        let mut worst = 0.0f64;
        for k in 0..t.len() {
            let x = p.actuator(t[k])[0];
            let cf = p.ideal_flap_angle(x, p.aux_rod_length).unwrap();
            worst = worst.max((a[k] - cf).abs());
        }
        println!(
            "flexible ideal linkage: deviation {worst:.4e} rad, static estimate {bound:.4e} rad"
        );
        assert!(
            worst < 1.5 * bound,
            "deviation {worst} rad, bound {bound} rad"
        );
        // and the flexibility does show: the deviation is of the order of the estimate
        assert!(
            worst > 0.3 * bound,
            "deviation {worst} rad, estimate {bound} rad"
        );
    }
}
