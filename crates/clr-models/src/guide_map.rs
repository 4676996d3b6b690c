//! Finding map of the sliding guide (issue 19): over the plausible range of every reconstructed
//! parameter of [`crate::guide`], where do the five friction findings of the paper hold that the
//! default reconstruction does not reproduce (docs/models/guide.md#friction-findings)?
//!
//! Each point of the map is one reconstruction: a [`MapPoint`] (load offset, slider length, pad
//! height, smallest clearance and clearance ratio, guide depth, second-load-path stiffness
//! including 0, speed), turned into the base parameters and the 8 runs of the friction study
//! that the five findings need ([`MapPoint::series`]; run by [`crate::guide::friction_runs`] and
//! [`crate::guide::run_metrics`], the code of `friction_study`). [`PointRuns::margins`] then
//! evaluates the findings with the inequalities and thresholds of `cargo xtask verify
//! models.guide` (xtask/src/verify/models.rs), each margin divided by a positive scale so that
//! all five are relative decreases (sign, hence "holds", unchanged):
//!
//! | finding | verify case | margin (holds when ≥ 0) |
//! |---|---|---|
//! | `clearance_friction` | `models.guide.clearance.friction` | min_k (F̄_k − F̄_{k+1}) / F̄_0 |
//! | `friction_clearance` | `models.guide.friction.clearance` | drop(μ_dep) − 0.01 |
//! | `friction_direction` | `models.guide.friction.direction` | drop(μ_dep) − drop(μ_ret) − 0.01 |
//! | `friction_speed` | `models.guide.friction.speed` | drop(μ_slow) − drop(μ_dep at c₀, c₂) − 0.01 |
//! | `friction_flattening` | `models.guide.friction.flattening` | min(a, a − b)·w₁/μ_0 − 0.01 |
//!
//! with F̄ the time-averaged friction force and μ the equivalent friction coefficient of the
//! deployment at speed v over the four clearances c₀ < c₁ < c₂ < c₃, drop(x) = (x₀ − x_last)/x₀
//! ([`relative_drop`]), a = (μ_0 − μ_1)/w₁ and b = (μ_2 − μ_3)/w₃ the decreases per mm over the
//! first and the last clearance step (widths w₁ = c₁ − c₀, w₃ = c₃ − c₂ in mm). At the verify
//! point (c = 0.25, 0.5, 1, 2 mm) these are verify's values divided by F̄_0, 1, 1, 1 and μ_0/w₁.

use crate::findings::{FindingSpec, Parameter, Scale};
use crate::guide::{self, GuideParams, Stroke, StudyRun, FRICTION_DURATION};
use crate::map_study::MapDef;

/// Name of the study (`clr study guide_findings_map`) and of its output files.
pub const NAME: &str = "guide_findings_map";
/// Points of the map run by the study: a power of two (the design's one-dimensional
/// stratification and the first-order indices assume it), the size issue 19 asks for.
pub const DEFAULT_POINTS: usize = 256;
/// Scramble seed of the design (fixed, so every machine of a sharded run draws the same points;
/// 19 for issue 19, chosen before any run).
pub const SEED: u32 = 19;
/// Simulation runs per point: deployment at v over the 4 clearances, retraction at v over the
/// smallest and largest, deployment at v/4 over c₀ and c₂.
pub const RUNS_PER_POINT: usize = 8;
/// Ratio of the fast to the slow speed of the speed finding: verify's 1 m/s against 0.25 m/s.
pub const SLOW_SPEED_RATIO: f64 = 4.0;
/// Smallest relative decrease of μ_eq that counts (verify's threshold): 1 %, three times the
/// integration sensitivity of μ_eq (0.27 % between rtol 1e-4 and 1e-5, docs/models/guide.md).
pub const MIN_RELATIVE_DECREASE: f64 = 0.01;
/// Values of the parameter `support_log10_stiffness` below this mean no second load path
/// (k = 0); above it k = 10^value N/m.
pub const SUPPORT_OFF_BELOW: f64 = 3.0;
/// Lower end of `support_log10_stiffness`: (3 − 7/3)/(5 − 7/3) = 1/4, so a quarter of the
/// design has k = 0 (exactly 64 of 256 points: each quarter of a coordinate of the Sobol net
/// holds a quarter of the points).
pub const SUPPORT_LOG10_LO: f64 = 7.0 / 3.0;

/// Relative decrease (x₀ − x_last)/x₀ of a series (verify's `relative_drop`).
pub fn relative_drop(x: &[f64]) -> f64 {
    (x[0] - x[x.len() - 1]) / x[0]
}

/// The smallest decrease x_k − x_{k+1} over consecutive values (≥ 0: non-increasing).
pub fn smallest_decrease(x: &[f64]) -> f64 {
    x.windows(2)
        .map(|w| w[0] - w[1])
        .fold(f64::INFINITY, f64::min)
}

/// The five findings, in the order of the margins.
pub fn findings() -> Vec<FindingSpec> {
    let paper = "sliding-guide paper (seed 000, abstract)";
    vec![
        FindingSpec::new(
            "clearance_friction",
            format!(
                "{paper}, simulation: the time-averaged friction force decreases with clearance \
                 (verify models.guide.clearance.friction: every step of the deployment at v over \
                 the four clearances); margin = smallest decrease / F̄ at c₀"
            ),
        ),
        FindingSpec::new(
            "friction_clearance",
            format!(
                "{paper}, experiment: μ_eq decreases with clearance (verify \
                 models.guide.friction.clearance: relative decrease c₀ → c₃, deployment at v, \
                 ≥ 1 %); margin = decrease − 0.01"
            ),
        ),
        FindingSpec::new(
            "friction_direction",
            format!(
                "{paper}, experiment: the decrease is larger in deployment than in retraction \
                 (verify models.guide.friction.direction: difference of relative decreases c₀ → \
                 c₃ at v ≥ 0.01); margin = difference − 0.01"
            ),
        ),
        FindingSpec::new(
            "friction_speed",
            format!(
                "{paper}, experiment: the decrease is larger at low speed (verify \
                 models.guide.friction.speed: relative decrease c₀ → c₂ at v/4 minus at v ≥ \
                 0.01); margin = difference − 0.01"
            ),
        ),
        FindingSpec::new(
            "friction_flattening",
            format!(
                "{paper}, experiment: the decrease flattens at large clearance (verify \
                 models.guide.friction.flattening: min(a, a − b) ≥ 1 % of μ_0 per first step, a \
                 and b the decreases per mm over the first and last clearance step); margin = \
                 min(a, a − b)·w₁/μ_0 − 0.01"
            ),
        ),
    ]
}

/// The reconstructed parameters with their plausible ranges and reasons, in the order of a
/// point's values ([`MapPoint::from_values`]).
pub fn parameters() -> Vec<Parameter> {
    let p = |name: &str, unit: &str, lo: f64, hi: f64, scale: Scale, reason: &str| {
        Parameter::new(name, unit, lo, hi, scale, reason).expect("valid built-in range")
    };
    vec![
        p(
            "load_offset",
            "m",
            0.0,
            0.1,
            Scale::Linear,
            "axial offset e of the lateral load ahead of the slider centre (GuideParams \
             load_offset; default 0.01): from a load through the centre to a lever of 0.1 m, \
             the e at which the slider was seen to wedge (docs/models/guide.md); spans e < L/2 \
             (one face carries the load) and e > L/2 (both faces) for every slider length",
        ),
        p(
            "slider_length",
            "m",
            0.03,
            0.15,
            Scale::Log,
            "pad length L (slider_length; default 0.06): 1 to 5 guide depths, from a short \
             carriage prone to tilt to the L/D ≥ 1.5–2 of bushings designed against jamming",
        ),
        p(
            "pad_height",
            "m",
            0.005,
            0.02,
            Scale::Linear,
            "height of each pad (pad_height; default 0.01): from the 5 mm elastic layer of the \
             area law to 2/3 of the guide depth; it sets the slider's height and inertia, not \
             where the contact acts",
        ),
        p(
            "clearance_min",
            "m",
            1e-4,
            5e-4,
            Scale::Log,
            "smallest clearance c₀ of the study (clearance; verify 0.25 mm): from a loose \
             running fit of a 30 mm guide (ISO 286 H11/d11, ≈ 0.1–0.3 mm) to the default's \
             \"large clearance\" 0.5 mm",
        ),
        p(
            "clearance_ratio",
            "-",
            4.0,
            16.0,
            Scale::Log,
            "largest over smallest clearance c₃/c₀ (verify 8, clearances c₀·(c₃/c₀)^(k/3), k = \
             0–3): the experiment's decrease saturates, so its clearances span a factor of \
             several; up to 8 mm at c₀ = 0.5 mm",
        ),
        p(
            "guide_depth",
            "m",
            0.02,
            0.045,
            Scale::Log,
            "guide stiffness through the section depth h (guide_depth; default 0.03): EI ∝ h³ \
             from 0.30 to 3.4 times the default (tip stiffness 2.8–32 kN/m, first frequency \
             16–37 Hz), a \"low-stiffness\" aluminium guide of a small morphing wing. Not \
             youngs_modulus: it also sets the contact stiffness",
        ),
        p(
            "support_log10_stiffness",
            "log10(N/m)",
            SUPPORT_LOG10_LO,
            5.0,
            Scale::Linear,
            "second lateral load path k (lateral_support_stiffness; not in the paper, default \
             0): values below 3 mean k = 0 (a quarter of the design, the paper's model), above \
             it k = 10^value, 1e3–1e5 N/m log-uniform: W/k from 50 mm (negligible at these \
             clearances) to 0.5 mm (stiffer than the guide under the slider, ≈ 28 kN/m)",
        ),
        p(
            "speed",
            "m/s",
            0.1,
            1.0,
            Scale::Log,
            "actuator speed v of the deployment and retraction series (speed; verify 1 m/s), \
             the slow series at v/4: from a real morphing actuator (order 0.1 m/s) to verify's \
             1 m/s; every run lasts 0.2 s (≈ 5 periods of the guide's first mode)",
        ),
    ]
}

/// One point of the map in physical terms (SI units); the order of [`parameters`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapPoint {
    /// Axial offset of the lateral load, m.
    pub load_offset: f64,
    /// Slider pad length, m.
    pub slider_length: f64,
    /// Pad height, m.
    pub pad_height: f64,
    /// Smallest clearance c₀, m.
    pub clearance_min: f64,
    /// Largest over smallest clearance, –.
    pub clearance_ratio: f64,
    /// Guide section depth, m.
    pub guide_depth: f64,
    /// log10 of the second load path's stiffness in N/m; below [`SUPPORT_OFF_BELOW`]: k = 0.
    pub support_log10_stiffness: f64,
    /// Speed of the deployment and retraction series, m/s.
    pub speed: f64,
}

impl MapPoint {
    /// The point of a design's values (in the order of [`parameters`]).
    ///
    /// # Errors
    /// A wrong number of values.
    pub fn from_values(x: &[f64]) -> Result<Self, String> {
        match *x {
            [load_offset, slider_length, pad_height, clearance_min, clearance_ratio, guide_depth, support_log10_stiffness, speed] => {
                Ok(Self {
                    load_offset,
                    slider_length,
                    pad_height,
                    clearance_min,
                    clearance_ratio,
                    guide_depth,
                    support_log10_stiffness,
                    speed,
                })
            }
            _ => Err(format!("{} values for 8 parameters", x.len())),
        }
    }

    /// The values in the order of [`parameters`].
    pub fn values(&self) -> Vec<f64> {
        vec![
            self.load_offset,
            self.slider_length,
            self.pad_height,
            self.clearance_min,
            self.clearance_ratio,
            self.guide_depth,
            self.support_log10_stiffness,
            self.speed,
        ]
    }

    /// The point of verify's friction study: the defaults of [`GuideParams`], clearances 0.25,
    /// 0.5, 1, 2 mm, 1 m/s, no second load path (`support_log10_stiffness` at the lower end).
    pub fn verify_point() -> Self {
        let d = GuideParams::default();
        Self {
            load_offset: d.load_offset,
            slider_length: d.slider_length,
            pad_height: d.pad_height,
            clearance_min: 0.25e-3,
            clearance_ratio: 8.0,
            guide_depth: d.guide_depth,
            support_log10_stiffness: SUPPORT_LOG10_LO,
            speed: 1.0,
        }
    }

    /// Stiffness of the second load path, N/m: 0 below [`SUPPORT_OFF_BELOW`], else 10^value.
    pub fn support_stiffness(&self) -> f64 {
        if self.support_log10_stiffness < SUPPORT_OFF_BELOW {
            0.0
        } else {
            10f64.powf(self.support_log10_stiffness)
        }
    }

    /// The four clearances c₀·q^k, q = (c₃/c₀)^(1/3), k = 0–3, m (geometric like verify's
    /// 0.25, 0.5, 1, 2 mm, which they are exactly at [`MapPoint::verify_point`]).
    pub fn clearances(&self) -> [f64; 4] {
        let q = self.clearance_ratio.cbrt();
        [0, 1, 2, 3].map(|k| self.clearance_min * q.powi(k))
    }

    /// The defaults of [`GuideParams`] with this point's values (clearance and speed are set
    /// per run by [`guide::friction_run`]).
    pub fn base(&self) -> GuideParams {
        GuideParams {
            load_offset: self.load_offset,
            slider_length: self.slider_length,
            pad_height: self.pad_height,
            guide_depth: self.guide_depth,
            lateral_support_stiffness: self.support_stiffness(),
            ..GuideParams::default()
        }
    }

    /// The friction-study series the five findings need ([`RUNS_PER_POINT`] runs): deployment
    /// at v over c₀–c₃, retraction at v over c₀ and c₃ (the relative decrease uses only the
    /// ends), deployment at v/4 over c₀ and c₂.
    pub fn series(&self) -> Vec<(Stroke, f64, Vec<f64>)> {
        let c = self.clearances();
        let v = self.speed;
        vec![
            (Stroke::Deployment, v, c.to_vec()),
            (Stroke::Retraction, v, vec![c[0], c[3]]),
            (Stroke::Deployment, v / SLOW_SPEED_RATIO, vec![c[0], c[2]]),
        ]
    }
}

/// The metrics of one point's runs that the findings use.
#[derive(Debug, Clone)]
pub struct PointRuns {
    /// The clearances c₀–c₃, m.
    pub clearances: [f64; 4],
    /// μ_eq of the deployment at v over c₀–c₃.
    pub deploy_mu: [f64; 4],
    /// Time-averaged friction force of the deployment at v over c₀–c₃, N.
    pub deploy_friction: [f64; 4],
    /// μ_eq of the retraction at v at c₀ and c₃.
    pub retract_mu: [f64; 2],
    /// μ_eq of the deployment at v/4 at c₀ and c₂.
    pub slow_mu: [f64; 2],
    /// Every run, in the order of [`MapPoint::series`].
    pub runs: Vec<StudyRun>,
}

impl PointRuns {
    /// One margin per finding of [`findings`], each a relative decrease (see the module docs).
    pub fn margins(&self) -> Vec<f64> {
        let (mu, f) = (&self.deploy_mu, &self.deploy_friction);
        let drop = relative_drop;
        let fast = [mu[0], mu[2]];
        // decreases per mm over the first and last step, as in verify's flattening case
        let w1 = (self.clearances[1] - self.clearances[0]) * 1e3;
        let w3 = (self.clearances[3] - self.clearances[2]) * 1e3;
        let (first, last) = ((mu[0] - mu[1]) / w1, (mu[2] - mu[3]) / w3);
        vec![
            smallest_decrease(f) / f[0],
            drop(mu) - MIN_RELATIVE_DECREASE,
            drop(mu) - drop(&self.retract_mu) - MIN_RELATIVE_DECREASE,
            drop(&self.slow_mu) - drop(&fast) - MIN_RELATIVE_DECREASE,
            first.min(first - last) * w1 / mu[0] - MIN_RELATIVE_DECREASE,
        ]
    }
}

/// Run the [`RUNS_PER_POINT`] friction-study runs of a point (in parallel, nothing written).
///
/// # Errors
/// The first failing run.
pub fn point_runs(p: &MapPoint) -> Result<PointRuns, String> {
    let runs = guide::run_metrics(guide::friction_runs(
        &p.base(),
        &p.series(),
        FRICTION_DURATION,
    ))?;
    let mu = |k: usize| runs[k].metric("equivalent_friction_coefficient");
    Ok(PointRuns {
        clearances: p.clearances(),
        deploy_mu: [mu(0), mu(1), mu(2), mu(3)],
        deploy_friction: [0, 1, 2, 3].map(|k| runs[k].metric("mean_friction_force")),
        retract_mu: [mu(4), mu(5)],
        slow_mu: [mu(6), mu(7)],
        runs,
    })
}

/// The map as a study (`clr study guide_findings_map`): design, checkpoint, resume, shards and
/// outputs are [`MapDef`]'s.
pub const MAP: MapDef = MapDef {
    name: NAME,
    seed: SEED,
    default_points: DEFAULT_POINTS,
    runs_per_point: RUNS_PER_POINT,
    parameters,
    findings,
    // the margins of the five findings at a design point's values
    evaluate: |x| point_runs(&MapPoint::from_values(x)?).map(|r| r.margins()),
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verify_point_is_verifys_friction_study() {
        let p = MapPoint::verify_point();
        assert_eq!(p.clearances(), [0.25e-3, 0.5e-3, 1.0e-3, 2.0e-3]);
        assert_eq!(p.base(), GuideParams::default());
        assert_eq!(p.support_stiffness(), 0.0);
        // the series are verify's (guide::friction_series), the retraction and slow ones
        // reduced to the clearances the findings use
        let full = guide::friction_series();
        let mine = p.series();
        assert_eq!(mine[0], full[0]);
        assert_eq!(mine[1].2, [full[1].2[0], full[1].2[3]]);
        assert_eq!((mine[1].0, mine[1].1), (full[1].0, full[1].1));
        assert_eq!(mine[2], full[2]);
        assert_eq!(MapPoint::from_values(&p.values()).unwrap(), p);
        let runs = guide::friction_runs(&p.base(), &mine, FRICTION_DURATION);
        assert_eq!(runs.len(), RUNS_PER_POINT);
        assert!(runs.iter().all(|(_, r)| r.validate().is_ok()));
    }

    // Margins from the μ_eq values of docs/models/guide.md: the default reconstruction (every
    // μ_eq finding fails) and the support what-if (every one holds). The margins have the sign
    // of verify's value − threshold, and at the verify point equal it up to the positive scale.
    #[test]
    fn margins_have_the_sign_of_verifys_inequalities() {
        let runs = |dep: [f64; 4], f: [f64; 4], ret: [f64; 2], slow: [f64; 2]| PointRuns {
            clearances: MapPoint::verify_point().clearances(),
            deploy_mu: dep,
            deploy_friction: f,
            retract_mu: ret,
            slow_mu: slow,
            runs: Vec::new(),
        };
        let default = runs(
            [0.09508, 0.09512, 0.09518, 0.09516],
            [4.962, 4.965, 4.971, 4.975],
            [0.1035, 0.1036],
            [0.09575, 0.09609],
        );
        let m = default.margins();
        assert!(m.iter().all(|&v| v < 0.0), "{m:?}");
        // verify's flattening value min(a, a − b) per mm and threshold 0.01·μ₀/0.25
        let (a, b): (f64, f64) = ((0.09508 - 0.09512) / 0.25, (0.09518 - 0.09516) / 1.0);
        let verify = a.min(a - b) - 0.01 * 0.09508 / 0.25;
        assert!((m[4] - verify * 0.25 / 0.09508).abs() < 1e-12, "{m:?}");
        assert!((m[0] - (-0.006 / 4.962)).abs() < 1e-12, "{m:?}");
        let support = runs(
            [0.05066, 0.04548, 0.03782, 0.03377],
            [2.58, 2.3, 2.0, 1.71],
            [0.05313, 0.03678],
            [0.05775, 0.04058],
        );
        let m = support.margins();
        assert!(m.iter().all(|&v| v > 0.0), "{m:?}");
    }

    // The mixture of the second load path: a quarter of the range means k = 0, so a 256-point
    // Sobol net has exactly 64 points at k = 0 (one point per slice of 1/256).
    #[test]
    fn a_quarter_of_the_design_has_no_second_load_path() {
        let d = MAP.design(DEFAULT_POINTS).unwrap();
        let off = d
            .points()
            .iter()
            .filter(|p| {
                MapPoint::from_values(&p.values)
                    .unwrap()
                    .support_stiffness()
                    == 0.0
            })
            .count();
        assert_eq!(off, 64);
        let params = parameters();
        let k = params
            .iter()
            .position(|p| p.name == "support_log10_stiffness")
            .unwrap();
        assert!((params[k].coordinate_of(SUPPORT_OFF_BELOW) - 0.25).abs() < 1e-12);
        // every point is a valid model
        for p in d.points() {
            let mp = MapPoint::from_values(&p.values).unwrap();
            for (_, r) in guide::friction_runs(&mp.base(), &mp.series(), FRICTION_DURATION) {
                assert!(r.validate().is_ok(), "{mp:?}");
            }
        }
    }
}
