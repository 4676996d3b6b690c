//! Finding map of the flap linkage with flexible parts (issue 19): over the plausible range of
//! the hinge load, the parts' modal damping, the clearance and the order in which clearance
//! joints are added, where do the flexible-body findings of Wan et al. (2022) hold?
//! (docs/models/flap.md#flexible-body-findings; three of them are known gaps at the default.)
//!
//! Each point runs five configurations of [`flap::run`] (each against its own ideal linkage of
//! the same flexibility), 0.25 s ramp + 2 actuator periods at rtol 1e-8 as the flexible study
//! (`clr study flap_flexible`):
//!
//! | run | flexible parts | clearance joints |
//! |---|---|---|
//! | R1, F1 | none; auxiliary rod | one: J4 (order "J4 first") or J1 (order "J1 first") |
//! | R4, F4 | none; auxiliary rod | J1–J4 |
//! | A4 | all three | J1–J4 |
//!
//! and evaluates the findings with verify's inequalities (xtask/src/verify/models_flap_flex.rs):
//!
//! | finding | verify case | margin (holds when ≥ 0) |
//! |---|---|---|
//! | `suspension` | `.suspension` | 1 − RMS(F1)/RMS(R1) |
//! | `suspension_weakens` | `.suspension_weakens` (order J4 first), `.j1_first` | r(1) − r(4), r(n) = 1 − RMS(Fn)/RMS(Rn) |
//! | `most_irregular_spread` | `.most_irregular` (`.reversing` at zero mean moment) | S(A4) / max S(others) − 1 |
//! | `most_irregular_divergence` | — (the Lyapunov measure) | (λ(A4) − max λ(R4, F4))·T |
//!
//! RMS is the time RMS of the clearance-induced flap acceleration oscillation and S the largest
//! Poincaré-section spread over the clearance joints (the `spread` statistic of [`crate::described_metrics`]).
//!
//! λ is the finite-time divergence rate of twin runs ([`lyapunov::twin_divergence_rate`]). Each
//! four-joint configuration is run a second time with every clearance larger by
//! [`TWIN_PERTURBATION`] (relative), and λ is the slope of ln of the distance between the two
//! runs' journal-eccentricity vectors (all four joints, relative to c, sampled every [`TWIN_DT`]
//! from t = 0) until that distance reaches [`TWIN_SATURATION`]. T is the actuator period, so the
//! margin is a difference in e-folds per period. The comparison set is the other four-joint
//! runs: the finding is about flexibility at equal joints.
//!
//! Rosenstein's estimate from one record ([`lyapunov::largest_exponent`]) is not used. With two
//! actuator periods, state neighbours must lie a period apart, so the estimate follows the
//! difference between the two periods. At the map's first point, runs with Poincaré spreads of
//! 1e-4 (periodic) gave 3–7 1/s.
//!
//! The verify point of `.suspension` uses J4; here the one-joint runs use the point's order, so
//! with "J1 first" the suspension finding is asked of J1.

use crate::common;
use crate::findings::{FindingSpec, Parameter, Scale};
use crate::flap::{self, FlapParams};
use crate::flap_flex::{self, FLAP_FLEX_STUDY_DURATION};
use crate::lyapunov;
use crate::map_study::MapDef;
use crate::RunSettings;
use clr_mbd::Results;

/// Name of the study (`clr study flap_findings_map`) and of its output files.
pub const NAME: &str = "flap_findings_map";
/// Points of the map run by the study.
pub const DEFAULT_POINTS: usize = 256;
/// Scramble seed of the design (fixed before any run).
pub const SEED: u32 = 1922;
/// Runs per point (each with its ideal reference, the three four-joint ones with a twin: 13
/// simulations).
pub const RUNS_PER_POINT: usize = 5;
/// Relative perturbation of every clearance in the twin run of a four-joint configuration.
pub const TWIN_PERTURBATION: f64 = 1e-6;
/// Sampling step of the twin runs' distance, s.
pub const TWIN_DT: f64 = 0.01;
/// Distance (relative to the clearance) at which the twins count as separated: the fit of the
/// divergence rate stops there.
pub const TWIN_SATURATION: f64 = 0.1;

/// The four findings, in the order of the margins.
pub fn findings() -> Vec<FindingSpec> {
    let paper = "Wan et al. 2022 (abstract), flexible flap linkage";
    vec![
        FindingSpec::new(
            "suspension",
            format!(
                "{paper}: a flexible body lowers the clearance-induced oscillation (verify \
                 models.flap.flex.study.suspension: RMS(flexible rod) ≤ RMS(rigid), one \
                 clearance joint); margin = 1 − RMS(F1)/RMS(R1)"
            ),
        ),
        FindingSpec::new(
            "suspension_weakens",
            format!(
                "{paper}: the suspension effect weakens as clearance joints are added (verify \
                 .suspension_weakens and .j1_first: reduction(4) ≤ reduction(1)); margin = \
                 r(1) − r(4)"
            ),
        ),
        FindingSpec::new(
            "most_irregular_spread",
            format!(
                "{paper}: several flexible bodies with several clearance joints are the most \
                 irregular (verify .most_irregular: Poincaré spread of A4 ≥ every other case); \
                 margin = S(A4)/max S(R1, F1, R4, F4) − 1"
            ),
        ),
        FindingSpec::new(
            "most_irregular_divergence",
            format!(
                "{paper}: the same, measured by the divergence rate λ of twin runs (a \
                 finite-time largest Lyapunov exponent) at four clearance joints; margin = \
                 (λ(A4) − max λ(R4, F4))·T, T the actuator period"
            ),
        ),
    ]
}

/// The parameters with their plausible ranges and reasons, in the order of a point's values.
pub fn parameters() -> Vec<Parameter> {
    let p = |name: &str, unit: &str, lo: f64, hi: f64, scale: Scale, reason: &str| {
        Parameter::new(name, unit, lo, hi, scale, reason).expect("valid built-in range")
    };
    vec![
        p(
            "hinge_moment",
            "N*m",
            0.0,
            60.0,
            Scale::Linear,
            "mean aerodynamic hinge moment M0 (reconstruction 30 N·m; the paper gives none): \
             from 0, a load that changes sign twice per period (the `reversing` study, impacts \
             in every joint), to twice the reconstruction",
        ),
        p(
            "hinge_stiffness",
            "N*m/rad",
            0.0,
            200.0,
            Scale::Linear,
            "aerodynamic hinge stiffness K of M = −(M0 + K(θ − θ0)) (reconstruction 100): \
             from none to twice",
        ),
        p(
            "modal_damping",
            "-",
            0.01,
            1.0,
            Scale::Log,
            "damping ratio ζ of every flexible part at its first frequency (reconstruction: \
             Adams/Flex's defaults 1, 0.1, 1 for the three parts): from 1 % (a bare metal part) \
             to critical",
        ),
        p(
            "clearance",
            "m",
            0.05e-3,
            0.5e-3,
            Scale::Log,
            "radial clearance of every clearance joint (reconstruction 0.1 mm): the range of \
             the rigid flap study's clearance sizes",
        ),
        p(
            "joint_order",
            "-",
            0.0,
            1.0,
            Scale::Linear,
            "order in which clearance joints are added (the paper does not say): below 0.5 J4 \
             first (the one-joint runs have J4), from 0.5 J1 first (they have J1); the \
             four-joint runs do not depend on it",
        ),
    ]
}

/// One point of the map.
#[derive(Debug, Clone, PartialEq)]
pub struct MapPoint {
    /// Mean hinge moment, N·m.
    pub hinge_moment: f64,
    /// Hinge stiffness, N·m/rad.
    pub hinge_stiffness: f64,
    /// Damping ratio of every flexible part.
    pub modal_damping: f64,
    /// Radial clearance, m.
    pub clearance: f64,
    /// Below 0.5: J4 first; else J1 first.
    pub joint_order: f64,
}

impl MapPoint {
    /// From a design point's values (the order of [`parameters`]).
    ///
    /// # Errors
    /// A wrong number of values.
    pub fn from_values(x: &[f64]) -> Result<Self, String> {
        match *x {
            [hinge_moment, hinge_stiffness, modal_damping, clearance, joint_order] => Ok(Self {
                hinge_moment,
                hinge_stiffness,
                modal_damping,
                clearance,
                joint_order,
            }),
            _ => Err(format!("{} values for the 5 parameters", x.len())),
        }
    }

    /// Index of the clearance joint of the one-joint runs: 3 (J4) or 0 (J1).
    pub fn first_joint(&self) -> usize {
        if self.joint_order < 0.5 {
            3
        } else {
            0
        }
    }

    /// The five configurations (label, flexible parts, clearances), in the order R1, F1, R4,
    /// F4, A4.
    pub fn configurations(&self) -> [(&'static str, [bool; 3], [f64; 4]); 5] {
        let c = self.clearance;
        let mut one = [0.0; 4];
        one[self.first_joint()] = c;
        let rod = [false, true, false];
        [
            ("R1", [false; 3], one),
            ("F1", rod, one),
            ("R4", [false; 3], [c; 4]),
            ("F4", rod, [c; 4]),
            ("A4", [true; 3], [c; 4]),
        ]
    }

    /// The flexible study's base ([`flap_flex::with_beam_masses`], duration
    /// [`FLAP_FLEX_STUDY_DURATION`]) with this point's load and damping.
    ///
    /// # Errors
    /// A part that cannot be calibrated.
    pub fn base(&self) -> Result<FlapParams, String> {
        flap_flex::with_beam_masses(&FlapParams {
            duration: FLAP_FLEX_STUDY_DURATION,
            hinge_moment: self.hinge_moment,
            hinge_stiffness: self.hinge_stiffness,
            flexible_damping_ratios: [self.modal_damping; 3],
            ..FlapParams::default()
        })
    }
}

/// The measures of one run that the findings use.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunMeasures {
    /// RMS of the clearance-induced flap acceleration oscillation, rad/s².
    pub oscillation_rms: f64,
    /// Largest Poincaré spread over the clearance joints, –.
    pub spread: f64,
    /// Divergence rate of the twin run, 1/s (four-joint configurations; `None` for the
    /// one-joint ones, which are not twinned).
    pub divergence: Option<f64>,
}

/// Journal eccentricity of every clearance joint relative to its clearance at each of the
/// times `t` (one vector per time). Each column is taken from `res` once: a flexible run has
/// about 10⁵ recorded rows.
fn eccentricities(res: &Results, p: &FlapParams, t: &[f64]) -> Vec<Vec<f64>> {
    let time = res.column("t").unwrap_or_default();
    let mut columns = Vec::new();
    for (k, j) in flap::JOINTS.iter().enumerate() {
        let c = p.clearances[k];
        if c > 0.0 {
            for comp in ["ex", "ey"] {
                columns.push((res.column(&format!("{j}.{comp}")).unwrap_or_default(), c));
            }
        }
    }
    t.iter()
        .map(|&t| {
            columns
                .iter()
                .map(|(v, c)| common::interp(&time, v, t) / c)
                .collect()
        })
        .collect()
}

/// The twin-run divergence rate of `p` against its run `res` (see the module documentation).
///
/// # Errors
/// A failing twin run, or too few samples before the twins separate.
pub fn divergence_rate(p: &FlapParams, res: &Results) -> Result<f64, String> {
    let twin_p = FlapParams {
        clearances: p.clearances.map(|c| c * (1.0 + TWIN_PERTURBATION)),
        ..p.clone()
    };
    let twin = flap::simulate("flap", &twin_p, &RunSettings::default(), false)
        .map_err(|e| format!("twin run: {e}"))?;
    let n = (p.duration / TWIN_DT).floor() as usize + 1;
    let t: Vec<f64> = (0..n).map(|k| k as f64 * TWIN_DT).collect();
    let (ea, eb) = (eccentricities(res, p, &t), eccentricities(&twin, p, &t));
    let d: Vec<f64> = ea
        .iter()
        .zip(&eb)
        .map(|(a, b)| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (x - y).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    lyapunov::twin_divergence_rate(&t, &d, TWIN_SATURATION)
        .ok_or_else(|| "the twin runs separate within 3 samples".into())
}

/// Run one configuration and measure it, with the twin run when `twin`.
///
/// # Errors
/// A failing run or twin.
pub fn measure(p: &FlapParams, twin: bool) -> Result<RunMeasures, String> {
    let o = flap::run("flap", p, &RunSettings::default()).map_err(|e| e.to_string())?;
    let divergence = if twin {
        Some(divergence_rate(p, &o.results)?)
    } else {
        None
    };
    Ok(RunMeasures {
        oscillation_rms: o.metric("flap_acceleration_oscillation_rms"),
        spread: o.metric("poincare_spread"),
        divergence,
    })
}

/// The five runs of a point, R1, F1, R4, F4, A4.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointRuns {
    /// Measures in the order of [`MapPoint::configurations`].
    pub runs: [RunMeasures; 5],
    /// Actuator period, s.
    pub period: f64,
}

impl PointRuns {
    /// The margins of the four findings (see the module table).
    pub fn margins(&self) -> Vec<f64> {
        let [r1, f1, r4, f4, a4] = self.runs;
        let red = |f: RunMeasures, r: RunMeasures| 1.0 - f.oscillation_rms / r.oscillation_rms;
        let others = [r1, f1, r4, f4];
        let max = |g: fn(&RunMeasures) -> f64| others.iter().map(g).fold(f64::MIN, f64::max);
        vec![
            red(f1, r1),
            red(f1, r1) - red(f4, r4),
            a4.spread / max(|m| m.spread) - 1.0,
            (a4.divergence.unwrap_or(f64::NAN)
                - r4.divergence
                    .unwrap_or(f64::NAN)
                    .max(f4.divergence.unwrap_or(f64::NAN)))
                * self.period,
        ]
    }
}

/// The five runs of a point (sequential; the map runs points in parallel).
///
/// # Errors
/// The first failing run, named.
pub fn point_runs(p: &MapPoint) -> Result<PointRuns, String> {
    let base = p.base()?;
    let mut runs = Vec::with_capacity(5);
    for (label, flexible, clearances) in p.configurations() {
        let q = FlapParams {
            flexible,
            clearances,
            ..base.clone()
        };
        let twin = clearances.iter().all(|&c| c > 0.0);
        runs.push(measure(&q, twin).map_err(|e| format!("{label}: {e}"))?);
    }
    let runs: [RunMeasures; 5] = runs.try_into().map_err(|_| "five runs".to_string())?;
    Ok(PointRuns {
        runs,
        period: base.period(),
    })
}

/// The map as a study (`clr study flap_findings_map`).
pub const MAP: MapDef = MapDef {
    name: NAME,
    seed: SEED,
    default_points: DEFAULT_POINTS,
    runs_per_point: RUNS_PER_POINT,
    parameters,
    findings,
    // the margins of the four findings at a design point's values
    evaluate: |x| point_runs(&MapPoint::from_values(x)?).map(|r| r.margins()),
};

#[cfg(test)]
mod tests {
    use super::*;

    // Every point is a valid linkage in all five configurations, and half the design adds J4
    // first (each half of a coordinate of the net holds half the points).
    #[test]
    fn every_point_is_valid_and_the_orders_split_evenly() {
        let d = MAP.design(DEFAULT_POINTS).unwrap();
        let mut j4_first = 0;
        for p in d.points() {
            let mp = MapPoint::from_values(&p.values).unwrap();
            j4_first += usize::from(mp.first_joint() == 3);
            let base = mp.base().unwrap();
            for (_, flexible, clearances) in mp.configurations() {
                let q = FlapParams {
                    flexible,
                    clearances,
                    ..base.clone()
                };
                assert!(q.validate().is_ok(), "{mp:?}: {:?}", q.validate());
            }
        }
        assert_eq!(j4_first, 128);
    }

    // The margins have the sign of verify's inequalities, at the study's values
    // (docs/models/flap.md, J4 first: RMS 0.09425 rigid, 0.01971 rod at J4; 0.3231 / 0.1217 at
    // J1–J4; spreads 6.51e-5, 1.25e-6, 1.12e-4, 1.08e-4 and 5.32e-5 for A4): suspension and
    // weakening hold, the spread finding fails, as in verify.
    #[test]
    fn margins_have_the_sign_of_verifys_inequalities() {
        let m = |rms: f64, spread: f64, l: f64| RunMeasures {
            oscillation_rms: rms,
            spread,
            divergence: Some(l),
        };
        let r = PointRuns {
            runs: [
                m(0.09425, 6.51e-5, 0.0),
                m(0.01971, 1.25e-6, 0.0),
                m(0.3231, 1.12e-4, 0.1),
                m(0.1217, 1.08e-4, 0.2),
                m(0.09243, 5.32e-5, 0.5),
            ],
            period: 0.5,
        };
        let g = r.margins();
        assert!((g[0] - (1.0 - 0.01971 / 0.09425)).abs() < 1e-12, "{g:?}");
        let (r1, r4) = (1.0 - 0.01971 / 0.09425, 1.0 - 0.1217 / 0.3231);
        assert!((g[1] - (r1 - r4)).abs() < 1e-12 && g[1] > 0.0, "{g:?}");
        assert!(g[2] < 0.0, "{g:?}");
        // (λ(A4) − max(λ(R4), λ(F4)))·T = (0.5 − 0.2)·0.5; R1's and F1's do not count
        assert!((g[3] - 0.15).abs() < 1e-12, "{g:?}");
    }
}
