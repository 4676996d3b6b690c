//! Sliding guide of a telescopic mechanism (morphing aircraft; seed 000, paper-systems.md §3):
//! a rigid slider driven along a cantilevered Euler–Bernoulli guide (clr-beam) with clearance to
//! both guide faces, under a lateral load. Multipoint detection (clr-contact), the Flores line law
//! for line contact and the restitution-corrected variable-stiffness area law for area contact
//! (`clr_mbd::FlexibleGuideSpec::area_normal`), Ambrósio friction.
//!
//! Every dimension, material, load and speed is a **reconstruction** (the full text is not
//! available); values and reasons are in docs/models/guide.md. The rigid-guide variant is the
//! same model with every guide node clamped except the tip rotation (identical contact code).

use std::path::Path;

use clr_beam::Face;
use clr_mbd::desc::{BeamMaterial, BeamMesh, SectionDesc, SupportDesc, SupportKind};
use clr_mbd::{FlexibleGuideSpec, Model, ModelBuilder, ModelDesc, Results, RigidBody, TimeFn};
use serde::{Deserialize, Serialize};

use crate::common::{self, col, FrictionParams, Record, Solver};
use crate::{ModelsError, RunOutput, RunSettings};

/// Parameters of the single sliding guide (SI units). Defaults: [`GuideParams::default`]; every
/// value is a reconstruction documented in docs/models/guide.md.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct GuideParams {
    /// Guide (cantilever) length, m.
    pub guide_length: f64,
    /// Guide section width b (out of plane), m.
    pub guide_width: f64,
    /// Guide section depth h (in the bending plane), m.
    pub guide_depth: f64,
    /// Guide Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Guide density, kg/m³.
    pub density: f64,
    /// Poisson ratio of guide and slider, –.
    pub poisson_ratio: f64,
    /// Number of Euler–Bernoulli elements of the guide.
    pub elements: usize,
    /// Mass-proportional Rayleigh coefficient α of the guide, 1/s.
    pub rayleigh_alpha: f64,
    /// `false`: the rigid-guide variant (every guide node clamped except the tip rotation; the
    /// slider must stay off the last element).
    pub elastic_guide: bool,
    /// Slider mass, kg.
    pub slider_mass: f64,
    /// Slider pad length L along the guide, m.
    pub slider_length: f64,
    /// Height of each of the two slider pads (above and below the guide), m.
    pub pad_height: f64,
    /// Clearance between each pad and its guide face (nominal, slider centred), m.
    pub clearance: f64,
    /// Rounding radius of the slider pad edges (line-contact Hertz law), m.
    pub edge_radius: f64,
    /// Depth of the elastic layer of the area law's Winkler term, m.
    pub layer_depth: f64,
    /// Restitution coefficient c_e of both laws, –.
    pub restitution: f64,
    /// Friction law of every contact point.
    pub friction: FrictionParams,
    /// Candidate points per slider face besides the corners.
    pub face_points: usize,
    /// Guide samples of the reverse check.
    pub guide_samples: usize,
    /// Lateral load on the slider (−y, towards the guide's upper face), N.
    pub lateral_load: f64,
    /// Axial offset of the lateral load's point from the slider centre (+ towards the tip), m.
    pub load_offset: f64,
    /// Lateral stiffness of a second load path from the slider centre to the guide axis, N/m
    /// (e.g. an actuator rod or wing skin carrying part of the lateral load): a force
    /// −k·y on the slider. **Not in the paper**: 0 by default; a what-if for the friction
    /// findings (docs/models/guide.md#friction-findings).
    pub lateral_support_stiffness: f64,
    /// Slider start position along the guide (from the root), m.
    pub start: f64,
    /// Slider end position along the guide, m (> start: deployment; < start: retraction).
    pub end: f64,
    /// Actuator speed (constant), m/s.
    pub speed: f64,
    /// Relative tolerance of the integrator.
    pub rtol: f64,
    /// Integrator.
    pub solver: Solver,
}

impl Default for GuideParams {
    fn default() -> Self {
        Self {
            guide_length: 1.0,
            guide_width: 0.02,
            guide_depth: 0.03,
            youngs_modulus: 70e9,
            density: 2700.0,
            poisson_ratio: 0.33,
            elements: 6,
            rayleigh_alpha: 6.0,
            elastic_guide: true,
            slider_mass: 0.5,
            slider_length: 0.06,
            pad_height: 0.01,
            clearance: 0.5e-3,
            edge_radius: 1e-3,
            layer_depth: 5e-3,
            restitution: 0.8,
            friction: FrictionParams::Ambrosio {
                mu: 0.1,
                v0: 1e-4,
                v1: 1e-3,
            },
            face_points: 3,
            guide_samples: 0,
            lateral_load: 50.0,
            load_offset: 0.01,
            lateral_support_stiffness: 0.0,
            start: 0.6,
            end: 0.8,
            speed: 1.0,
            rtol: 1e-4,
            solver: Solver::Dopri5,
        }
    }
}

impl GuideParams {
    /// Check every field; the message names the field to change.
    ///
    /// # Errors
    /// A description of the first invalid field.
    pub fn validate(&self) -> Result<(), String> {
        for (f, v) in [
            ("guide_length", self.guide_length),
            ("guide_width", self.guide_width),
            ("guide_depth", self.guide_depth),
            ("youngs_modulus", self.youngs_modulus),
            ("density", self.density),
            ("slider_mass", self.slider_mass),
            ("slider_length", self.slider_length),
            ("pad_height", self.pad_height),
            ("clearance", self.clearance),
            ("edge_radius", self.edge_radius),
            ("layer_depth", self.layer_depth),
            ("restitution", self.restitution),
            ("speed", self.speed),
            ("rtol", self.rtol),
        ] {
            common::positive(f, v)?;
        }
        common::non_negative("rayleigh_alpha", self.rayleigh_alpha)?;
        common::non_negative("lateral_load", self.lateral_load)?;
        common::non_negative("lateral_support_stiffness", self.lateral_support_stiffness)?;
        if self.elements == 0 {
            return Err("`elements` must be at least 1".into());
        }
        let half = 0.5 * self.slider_length;
        for (f, x) in [("start", self.start), ("end", self.end)] {
            if !(x.is_finite() && x - half >= 0.0 && x + half <= self.guide_length) {
                return Err(format!(
                    "`{f}` = {x} m puts the slider (half length {half} m) off the guide \
                     [0, {}] m",
                    self.guide_length
                ));
            }
        }
        let last = self.guide_length * (1.0 - 1.0 / self.elements as f64);
        if !self.elastic_guide && self.start.max(self.end) + half > last {
            return Err(format!(
                "the rigid-guide variant keeps the last element flexible (its tip rotation is \
                 free): keep `start`/`end` + half the slider length ≤ {last} m"
            ));
        }
        if self.start == self.end {
            return Err("`start` and `end` must differ (the slider must move)".into());
        }
        Ok(())
    }

    /// Run duration |end − start| / speed, s.
    pub fn duration(&self) -> f64 {
        (self.end - self.start).abs() / self.speed
    }

    /// First bending frequency of the clamped-free guide, Hz: f₁ = (β₁L)²/(2π)·√(EI/(ρAL⁴)),
    /// β₁L = 1.875104 (Euler–Bernoulli cantilever; e.g. Rao, *Vibration of Continuous
    /// Systems*, 2007, §11.5).
    pub fn first_frequency(&self) -> f64 {
        let (b, h, l) = (self.guide_width, self.guide_depth, self.guide_length);
        let ei = self.youngs_modulus * b * h.powi(3) / 12.0;
        let rho_a = self.density * b * h;
        1.875_104_f64.powi(2) / (2.0 * std::f64::consts::PI) * (ei / (rho_a * l.powi(4))).sqrt()
    }

    /// The guide rail as data: clamped at node 0; for the rigid guide every other node clamped
    /// but the tip node pinned (clr-mbd needs at least one free beam coordinate; the tip rotation
    /// only bends the last element, which the slider never reaches, checked in `validate`).
    pub fn guide_mesh(&self) -> BeamMesh {
        let mut supports = vec![SupportDesc {
            node: 0,
            kind: SupportKind::Clamped,
        }];
        if !self.elastic_guide {
            for n in 1..=self.elements {
                supports.push(SupportDesc {
                    node: n,
                    kind: if n == self.elements {
                        SupportKind::Pinned
                    } else {
                        SupportKind::Clamped
                    },
                });
            }
        }
        BeamMesh {
            start: [0.0, 0.0],
            end: [self.guide_length, 0.0],
            elements: self.elements,
            material: BeamMaterial {
                youngs_modulus: self.youngs_modulus,
                density: self.density,
                poisson_ratio: self.poisson_ratio,
            },
            section: SectionDesc::Rectangular {
                width: self.guide_width,
                depth: self.guide_depth,
            },
            supports,
            rayleigh: [self.rayleigh_alpha, 0.0],
            mass: Default::default(),
        }
    }

    /// The multibody model ([`GuideParams::desc`] compiled).
    ///
    /// # Errors
    /// Invalid parameters or a clr-mbd build error.
    pub fn build(&self, model: &str) -> Result<Model, ModelsError> {
        common::compile(model, &self.desc(model)?)
    }

    /// The multibody model as data, with the run settings of `clr run <model>` (no `--t-end`
    /// or `--rtol`) in `solver` and `output`: the `solver` and `rtol` parameters, atol =
    /// rtol·10⁻³, 0 to [`GuideParams::duration`] s, every accepted step recorded. Guide beam
    /// `guide` (x from 0 at the clamped root), slider `slider` centred on the guide axis,
    /// contact elements `upper` (slider's upper pad on the guide's upper face) and `lower`,
    /// actuator `actuator` (axial displacement driver), lateral load `load`; with
    /// `lateral_support_stiffness` > 0 also the bushing `support` (−k·y on the slider centre).
    /// `model` names the model in errors and in `[model]`.
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn desc(&self, model: &str) -> Result<ModelDesc, ModelsError> {
        self.validate().map_err(|m| common::invalid(model, m))?;
        let inv = |m: String| common::invalid(model, m);
        let beam = self.guide_mesh();
        // built here once for the parameter-level message (the model builds it again)
        beam.build("guide").map_err(|e| inv(e.message))?;
        let (line, area) = common::guide_law_descs(
            self.youngs_modulus,
            self.poisson_ratio,
            self.edge_radius,
            self.guide_width,
            self.layer_depth,
            self.restitution,
        )
        .map_err(inv)?;
        self.friction.law().map_err(inv)?;
        let friction = self.friction.desc();
        let (l, hp, c) = (self.slider_length, self.pad_height, self.clearance);
        let off = 0.5 * self.guide_depth + c + 0.5 * hp;
        let height = 2.0 * off + hp;
        let inertia = self.slider_mass * (l * l + height * height) / 12.0;
        let dir = (self.end - self.start).signum();
        let v = dir * self.speed;
        let spec = |f: Face| FlexibleGuideSpec {
            face: f,
            slider_length: l,
            slider_height: hp,
            slider_angle: 0.0,
            face_points: self.face_points,
            guide_samples: self.guide_samples,
            normal: line.clone().into(),
            area_normal: Some(area.clone().into()),
            friction: friction.clone().into(),
        };
        let load = self.lateral_load;
        let mut b = ModelBuilder::new();
        b.flexible_beam("guide", beam)
            .body(
                "slider",
                RigidBody::new(self.slider_mass, inertia)
                    .at(self.start, 0.0, 0.0)
                    .moving(v, 0.0, 0.0),
            )
            .slider_on_beam("upper", "guide", ("slider", [0.0, off]), spec(Face::Upper))
            .slider_on_beam("lower", "guide", ("slider", [0.0, -off]), spec(Face::Lower))
            .drive_displacement(
                "actuator",
                ("ground", [0.0, 0.0]),
                ("slider", [0.0, 0.0]),
                [1.0, 0.0],
                TimeFn::linear(self.start, v),
            )
            .force(
                "load",
                ("slider", [self.load_offset, 0.0]),
                TimeFn::constant(0.0),
                TimeFn::constant(-load),
            );
        let k = self.lateral_support_stiffness;
        if k > 0.0 {
            // −k·y on the slider centre: a bushing to the guide axis, axially free
            b.bushing(
                "support",
                ("ground", [0.0, 0.0]),
                ("slider", [0.0, 0.0]),
                [0.0, k],
                [0.0, 0.0],
            );
        }
        Ok(common::finish_desc(
            b,
            model,
            self.duration(),
            self.rtol,
            self.solver,
        ))
    }
}

/// The model and run settings that [`run`] simulates: [`GuideParams::desc`] with the end time
/// and tolerance of `settings` (when given) written into `solver` and `output`.
///
/// # Errors
/// Invalid parameters or run settings.
pub fn run_desc(
    model: &str,
    p: &GuideParams,
    settings: &RunSettings,
) -> Result<ModelDesc, ModelsError> {
    let mut d = common::run_desc(model, settings, Record::EveryStep, || p.desc(model))?;
    derived(&mut d, p);
    Ok(d)
}

/// The guide's metrics as measures and metrics of its description, so that `clr run guide` and
/// its exported file compute them the same way: the guide tip's deflection as a recorded node
/// (`guide.node<E>.uy`, 0 on the rigid guide), the normal and |friction| forces summed over both
/// faces and the drive force along the motion as `combination` measures; the slider's lateral
/// displacement (largest, RMS), the largest face force (located on the dense output), the tip
/// oscillation about its running mean over one first-mode period and its largest deflection,
/// the mean forces, the contact onsets, the actuator's peak, the drive force, the equivalent
/// friction coefficient (drive force / lateral load; without a load it has no meaning and is
/// left out) and the friction-to-normal ratio of the contact.
fn derived(d: &mut ModelDesc, p: &GuideParams) {
    use clr_mbd::desc::metric::{Divisor, MetricDesc, Statistic as S};
    use clr_mbd::desc::NodeSelection;
    use clr_mbd::measure::combination::{Combination, Term};
    let tip = format!("guide.node{}.uy", p.elements);
    d.output
        .nodes
        .insert("guide".into(), NodeSelection::Nodes(vec![p.elements]));
    let term = |of: &str, factor: f64, abs: bool| Term::column(of, factor, abs);
    let sum = Combination::measure;
    let faces = ["upper", "lower"];
    // the actuator's reaction opposes the motion: its mean along the direction of motion is the
    // drive force a test rig measures at constant speed
    let dir = (p.end - p.start).signum();
    d.measures.extend([
        sum(
            "normal_total",
            faces
                .map(|f| term(&format!("{f}.normal_force"), 1.0, false))
                .to_vec(),
        ),
        sum(
            "friction_total",
            faces
                .map(|f| term(&format!("{f}.friction_force"), 1.0, true))
                .to_vec(),
        ),
        sum("drive", vec![term("actuator.Fx", dir, false)]),
    ]);
    let m =
        |name: &str, of: &str, stat, words: &str| MetricDesc::new(name, of, stat).described(words);
    let mut v =
        vec![
        m(
            "max_lateral_displacement",
            "slider.y",
            S::Peak,
            "largest |y| of the slider centre (0 = centred on the undeformed guide)",
        ),
        m(
            "rms_lateral_displacement",
            "slider.y",
            S::Rms,
            "time RMS of the slider centre's y",
        ),
        MetricDesc::of_columns(
            "peak_contact_force",
            &["upper.normal_force", "lower.normal_force"],
            S::Peak,
        )
        .described(
            "largest normal force of either face (sum over that face's points), located on the \
             dense output",
        ),
        MetricDesc {
            window: Some(1.0 / p.first_frequency()),
            ..m(
                "tip_oscillation_amplitude",
                &tip,
                S::Oscillation,
                "largest |tip deflection − its running mean over one first-mode period|",
            )
        },
        m("max_tip_deflection", &tip, S::Peak, "largest |guide-tip deflection|"),
        m(
            "mean_friction_force",
            "friction_total.value",
            S::Mean,
            "time average of |friction| summed over both faces",
        ),
        m(
            "mean_normal_force",
            "normal_total.value",
            S::Mean,
            "time average of the normal force summed over both faces",
        ),
        MetricDesc::of_columns("impacts", &["upper.contact", "lower.contact"], S::Onsets)
            .described("contact onsets of both faces (0→1 transitions over the accepted steps)"),
        m(
            "peak_actuator_force",
            "actuator.Fx",
            S::Peak,
            "largest |axial actuator reaction| (jamming indicator)",
        ),
        m(
            "mean_drive_force",
            "drive.value",
            S::Mean,
            "time average of the actuator force along the direction of motion",
        ),
    ];
    if p.lateral_load > 0.0 {
        v.push(
            m(
                "equivalent_friction_coefficient",
                "drive.value",
                S::Mean,
                "mean drive force / lateral load (the friction coefficient a test rig reads)",
            )
            .per(Divisor::Number(p.lateral_load))
            .in_unit("-"),
        );
    }
    v.push(
        m(
            "contact_friction_ratio",
            "friction_total.value",
            S::Mean,
            "∫Σ|F_T| dt / ∫ΣF_N dt over both faces (the friction law's own ratio)",
        )
        .per(Divisor::Metric("mean_normal_force".into())),
    );
    d.metrics = v;
}

/// Simulate and compute the metrics (see docs/models/guide.md): slider lateral displacement
/// (max, RMS), peak contact force, guide-tip deflection oscillation amplitude, time-averaged
/// friction force, number of impacts, actuator force peak, equivalent friction coefficient.
///
/// # Errors
/// Invalid parameters, build or simulation errors.
pub fn run(model: &str, p: &GuideParams, settings: &RunSettings) -> Result<RunOutput, ModelsError> {
    crate::described_metrics::run_output(model, &run_desc(model, p, settings)?, settings, p)
}

/// One run of a guide study.
pub type StudyRun = common::StudyRun<GuideParams>;

/// Run named parameter sets in parallel, writing `<name>.csv` and `summary.csv` under `dir`
/// and figures of the slider's y, the tip deflection and the contact force.
///
/// # Errors
/// The first failing run, or an output error.
pub fn study(dir: &Path, runs: Vec<(String, GuideParams)>) -> Result<Vec<StudyRun>, String> {
    let (done, results) = run_all(dir, runs)?;
    figures(dir, &done, &results)?;
    Ok(done)
}

/// Run in parallel, write every run's CSV and `summary.csv`; the runs and their results.
fn run_all(
    dir: &Path,
    runs: Vec<(String, GuideParams)>,
) -> Result<(Vec<StudyRun>, Vec<Results>), String> {
    common::run_study(dir, runs, |p| run("guide", p, &RunSettings::default()))
}

/// Elastic against rigid guide (default parameters otherwise), under `dir`.
///
/// # Errors
/// See [`study`].
pub fn elastic_vs_rigid(dir: &Path) -> Result<Vec<StudyRun>, String> {
    let e = GuideParams::default();
    let r = GuideParams {
        elastic_guide: false,
        ..GuideParams::default()
    };
    study(dir, vec![("elastic".into(), e), ("rigid".into(), r)])
}

/// Clearance study: the default elastic guide at each clearance (m), under `dir`.
///
/// # Errors
/// See [`study`].
pub fn clearance_study(dir: &Path, clearances: &[f64]) -> Result<Vec<StudyRun>, String> {
    let runs = clearances
        .iter()
        .map(|&c| {
            (
                format!("c{:.2}mm", c * 1e3),
                GuideParams {
                    clearance: c,
                    ..GuideParams::default()
                },
            )
        })
        .collect();
    study(dir, runs)
}

/// Direction of the actuator stroke.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stroke {
    /// Towards the guide tip (`end > start`).
    Deployment,
    /// Towards the root (`end < start`).
    Retraction,
}

impl Stroke {
    /// Lower-case name used in run names.
    pub fn name(self) -> &'static str {
        match self {
            Stroke::Deployment => "deploy",
            Stroke::Retraction => "retract",
        }
    }
}

/// Duration of every run of the paper's friction study, s (0.2 m of stroke at 1 m/s).
pub const FRICTION_DURATION: f64 = 0.2;

/// Series of the paper's friction study as run by `cargo xtask verify` and `clr study
/// guide_friction`: deployment and retraction at 1 m/s with c = 0.25, 0.5, 1.0, 2.0 mm, and
/// deployment at 0.25 m/s with c = 0.25, 1.0 mm.
pub fn friction_series() -> Vec<(Stroke, f64, Vec<f64>)> {
    let cs = vec![0.25e-3, 0.5e-3, 1.0e-3, 2.0e-3];
    vec![
        (Stroke::Deployment, 1.0, cs.clone()),
        (Stroke::Retraction, 1.0, cs),
        (Stroke::Deployment, 0.25, vec![0.25e-3, 1.0e-3]),
    ]
}

/// Name of a friction-study run: `<deploy|retract>_v<speed m/s>_c<clearance mm>mm`.
pub fn friction_run_name(stroke: Stroke, speed: f64, clearance: f64) -> String {
    format!("{}_v{speed:.2}_c{:.2}mm", stroke.name(), clearance * 1e3)
}

/// Parameters of one friction-study run: `base` with clearance `clearance` (m), driven at
/// `speed` (m/s) for `duration` (s) over the stroke between `base.start` and that position plus
/// `speed·duration`, outwards (deployment) or back (retraction), so every run covers the same
/// time and, per speed, the same stretch of guide in both directions.
pub fn friction_run(
    base: &GuideParams,
    stroke: Stroke,
    speed: f64,
    clearance: f64,
    duration: f64,
) -> GuideParams {
    let d = base.clone();
    let (a, b) = (d.start, d.start + speed * duration);
    let (start, end) = match stroke {
        Stroke::Deployment => (a, b),
        Stroke::Retraction => (b, a),
    };
    GuideParams {
        clearance,
        speed,
        start,
        end,
        ..d
    }
}

/// The named runs of a friction study, in series order: `base` in every `(stroke, speed,
/// clearances)` series at each clearance (m), runs of `duration` s ([`friction_run`], named by
/// [`friction_run_name`]).
pub fn friction_runs(
    base: &GuideParams,
    series: &[(Stroke, f64, Vec<f64>)],
    duration: f64,
) -> Vec<(String, GuideParams)> {
    series
        .iter()
        .flat_map(|(stroke, v, cs)| {
            cs.iter().map(move |&c| {
                (
                    friction_run_name(*stroke, *v, c),
                    friction_run(base, *stroke, *v, c, duration),
                )
            })
        })
        .collect()
}

/// Run named parameter sets in parallel (rayon) and keep only their metrics, in input order;
/// nothing is written (the runs of one point of a finding map, `crate::guide_map`).
///
/// # Errors
/// The first failing run, its message prefixed with its name.
pub fn run_metrics(runs: Vec<(String, GuideParams)>) -> Result<Vec<StudyRun>, String> {
    use rayon::prelude::*;
    runs.into_par_iter()
        .map(|(name, params)| {
            let start = std::time::Instant::now();
            let o = run("guide", &params, &RunSettings::default())
                .map_err(|e| format!("{name}: {e}"))?;
            Ok(StudyRun {
                name,
                params,
                metrics: o.metrics,
                wall_s: start.elapsed().as_secs_f64(),
            })
        })
        .collect()
}

/// Friction study (the paper's experiment, reconstructed; docs/models/guide.md): `base` in every
/// `(stroke, speed, clearances)` series at each clearance (m), runs of `duration` s, under `dir`:
/// CSV per run, `summary.csv`, the figure `friction` (equivalent friction coefficient against
/// clearance, one line per series) and the line figures of the first series.
///
/// # Errors
/// See [`study`].
pub fn friction_study(
    dir: &Path,
    base: &GuideParams,
    series: &[(Stroke, f64, Vec<f64>)],
    duration: f64,
) -> Result<Vec<StudyRun>, String> {
    let (done, results) = run_all(dir, friction_runs(base, series, duration))?;
    let mut fig = clr_plot::Figure::new("Equivalent friction coefficient")
        .x_label("clearance (mm)")
        .y_label("mean drive force / lateral load (-)");
    for (stroke, v, cs) in series {
        let pts: Vec<(f64, f64)> = cs
            .iter()
            .filter_map(|&c| {
                let name = friction_run_name(*stroke, *v, c);
                done.iter()
                    .find(|r| r.name == name)
                    .map(|r| (c * 1e3, r.metric("equivalent_friction_coefficient")))
            })
            .collect();
        fig = fig.line(format!("{} {v} m/s", stroke.name()), pts);
    }
    fig.save(dir.join("friction")).map_err(|e| e.to_string())?;
    if let Some((stroke, v, cs)) = series.first() {
        let names: Vec<String> = cs
            .iter()
            .map(|&c| friction_run_name(*stroke, *v, c))
            .collect();
        let (r, res): (Vec<StudyRun>, Vec<Results>) = done
            .iter()
            .zip(results)
            .filter(|(r, _)| names.contains(&r.name))
            .map(|(r, res)| (r.clone(), res))
            .unzip();
        figures(dir, &r, &res)?;
    }
    Ok(done)
}

fn figures(dir: &Path, runs: &[StudyRun], results: &[Results]) -> Result<(), String> {
    use clr_plot::Figure;
    const MAX: usize = 3000;
    let mut fy = Figure::new("Slider lateral displacement")
        .x_label("time (s)")
        .y_label("slider y (mm)");
    let mut ftip = Figure::new("Guide-tip deflection")
        .x_label("time (s)")
        .y_label("tip deflection (mm)");
    let mut ff = Figure::new("Contact force (upper face)")
        .x_label("time (s)")
        .y_label("normal force (N)");
    for (r, res) in runs.iter().zip(results) {
        let t = col(res, "t");
        let mm = |v: Vec<f64>| v.iter().map(|x| x * 1e3).collect::<Vec<_>>();
        fy = fy.line(
            r.name.clone(),
            common::thin(&t, &mm(col(res, "slider.y")), MAX),
        );
        let tip = res
            .column(&format!("guide.n{}.v", r.params.elements))
            .unwrap_or_else(|| vec![0.0; t.len()]);
        ftip = ftip.line(r.name.clone(), common::thin(&t, &mm(tip), MAX));
        ff = ff.line(
            r.name.clone(),
            common::thin(&t, &col(res, "upper.normal_force"), MAX),
        );
    }
    for (f, name) in [(fy, "lateral"), (ftip, "tip"), (ff, "contact_force")] {
        common::save_figure(f, dir, name)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_frequency_matches_the_fe_guide() {
        // independent formulation: clr-beam's modal analysis of the same 8-element guide
        let p = GuideParams::default();
        let mat = clr_beam::Material::new(p.youngs_modulus, p.density, p.poisson_ratio).unwrap();
        let sec = clr_beam::Section::rectangular(p.guide_width, p.guide_depth).unwrap();
        let mut beam =
            clr_beam::BeamModel::straight([0.0, 0.0], [p.guide_length, 0.0], p.elements, mat, sec)
                .unwrap();
        beam.support(0, clr_beam::Support::Clamped).unwrap();
        let modes = beam.modes(1).unwrap();
        let f_fe = modes.frequencies_hz()[0];
        assert!(
            (f_fe - p.first_frequency()).abs() < 1e-4 * f_fe,
            "{f_fe} vs {}",
            p.first_frequency()
        );
    }

    #[test]
    fn invalid_position_names_the_field() {
        let p = GuideParams {
            end: 0.99,
            ..GuideParams::default()
        };
        let e = run("guide", &p, &RunSettings::default()).unwrap_err();
        assert!(e.to_string().contains("`end`"), "{e}");
    }

    #[test]
    fn short_run_stays_within_the_clearance_band() {
        // closed-form bound: the slider centre can move laterally by the clearance plus the
        // contact penetration plus the guide's deflection under the slider; with a rigid guide
        // only by c + δ (δ ≪ c here), and it does cross the clearance under the load
        let p = GuideParams {
            elastic_guide: false,
            end: 0.65,
            ..GuideParams::default()
        };
        let out = run("guide", &p, &RunSettings::default()).unwrap();
        let get = |n: &str| out.metrics.iter().find(|m| m.name == n).unwrap().value;
        let y = get("max_lateral_displacement");
        assert!(y < 1.1 * p.clearance, "{y}");
        assert!(y > 0.9 * p.clearance, "{y}");
        assert!(get("peak_contact_force") > p.lateral_load);
    }
}
