//! Dual-stage dual guide of a telescopic mechanism (morphing aircraft; seed 000,
//! paper-systems.md §3, issue 6 §1): two parallel stage-1 cantilever guides at spacing d carry a
//! stage-1 carriage with one slider (two pads with clearance) on each; two stage-2 guides are
//! clamped to that carriage and carry the stage-2 carriage with one slider on each; both stages
//! are driven axially, the stage-2 carriage carries a lateral load.
//!
//! The stage-1 guides are ground-fixed Euler–Bernoulli beams (`ModelBuilder::flexible_beam`),
//! the stage-2 guides moving floating-frame beams (`ModelBuilder::floating_beam`, cantilever
//! modes) clamped to the carriage by fixed joints; every slider pad is a
//! `ModelBuilder::slider_on_beam` contact element with the same laws as the single guide
//! ([`crate::guide`]): Flores line law, restitution-corrected area law, Ambrósio friction.
//! With `dual = false` the model is the **single guide of the same parameters**: one stage-1
//! guide on the axis, one carriage (of the stage-2 carriage's mass, carrying the load), one
//! actuator — the reference of the dual-vs-single comparison.
//!
//! Every dimension, material, load and speed is a **reconstruction** (the paper's abstract gives
//! none); values and reasons are in docs/models/dual_guide.md.

use std::path::Path;

use clr_beam::{BeamModel, Face, ReducedModel};
use clr_mbd::desc::{BeamMaterial, BeamMesh, SectionDesc, SupportDesc, SupportKind};

use clr_mbd::{
    FlexibleGuideSpec, Model, ModelBuilder, ModelDesc, Reduction, Results, RigidBody, TimeFn,
};
use serde::{Deserialize, Serialize};

use crate::common::{self, col, FrictionParams, Record, Solver};
use crate::{ModelsError, RunOutput, RunSettings};

/// Parameters of the dual-stage dual guide (SI units). Defaults: [`DualGuideParams::default`];
/// every value is a reconstruction documented in docs/models/dual_guide.md. Fields that mean the
/// same as in [`crate::guide::GuideParams`] have the same default there (guide section and
/// material, pad geometry, clearance, contact and friction laws, load, rtol, solver).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct DualGuideParams {
    /// `true`: dual-stage dual guide; `false`: the single guide of the same parameters (one
    /// stage-1 guide, one carriage of mass `carriage2_mass` with the load, one actuator).
    pub dual: bool,
    /// Interguide spacing d (y distance between the two guides of a stage), m.
    pub spacing: f64,
    /// Stage-1 guide (cantilever) length, m.
    pub guide1_length: f64,
    /// Stage-2 guide length (root at the stage-1 carriage centre), m.
    pub guide2_length: f64,
    /// Guide section width b (out of plane), both stages, m.
    pub guide_width: f64,
    /// Stage-1 guide section depth h₁ (in the bending plane), m.
    pub guide1_depth: f64,
    /// Stage-2 guide section depth h₂, m.
    pub guide2_depth: f64,
    /// Guide Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Guide density, kg/m³.
    pub density: f64,
    /// Poisson ratio of guides and pads, –.
    pub poisson_ratio: f64,
    /// Euler–Bernoulli elements of each stage-1 guide.
    pub elements1: usize,
    /// Euler–Bernoulli elements of each stage-2 guide (before the modal reduction).
    pub elements2: usize,
    /// Cantilever modes kept for each stage-2 (floating) guide.
    pub modes2: usize,
    /// Mass-proportional Rayleigh coefficient α of every guide, 1/s.
    pub rayleigh_alpha: f64,
    /// Stage-1 carriage mass, kg.
    pub carriage1_mass: f64,
    /// Stage-2 carriage mass (the single guide's carriage in `dual = false`), kg.
    pub carriage2_mass: f64,
    /// Slider pad length L along the guide, m.
    pub slider_length: f64,
    /// Height of each pad (above and below its guide), m.
    pub pad_height: f64,
    /// Clearance between each pad and its guide face (nominal, centred), m.
    pub clearance: f64,
    /// Rounding radius of the pad edges (line-contact Hertz law), m.
    pub edge_radius: f64,
    /// Depth of the elastic layer of the area law's Winkler term, m.
    pub layer_depth: f64,
    /// Restitution coefficient c_e of both laws, –.
    pub restitution: f64,
    /// Friction law of every contact point.
    pub friction: FrictionParams,
    /// Candidate points per pad face besides the corners.
    pub face_points: usize,
    /// Lateral load on the loaded carriage (−y), N.
    pub lateral_load: f64,
    /// Axial offset of the load point from the loaded carriage's centre (+x), m.
    pub load_offset: f64,
    /// Lateral offset of the load point from the carriage centre (+y, towards guide a), m;
    /// with the axial actuator reactions it loads the two guides unequally.
    pub load_lateral_offset: f64,
    /// Out-of-plane twist φ of the stage-1 carriage about the guide axis, rad; 0 (default) is
    /// the planar model. A *reduced model* of the asynchronous deformation of two guides side
    /// by side (issue 19, docs/models/dual_guide.md#twist): a carriage twisted by φ moves the
    /// roots of the two stage-2 guides it carries, a spacing d apart across the twist axis, by
    /// ±φ·d/2 in the load direction, so the stage-2 carriage must take up a mismatch φ·d
    /// between its two sliders. Here the stage-2 guide root of guide a moves by +φ·d/2 and that
    /// of guide b by −φ·d/2 relative to the stage-1 carriage, faded in over `twist_ramp`.
    pub carriage1_twist: f64,
    /// Time over which the twist is faded in from 0 (cubic smooth step), s: the load acts from
    /// t = 0, the ramp avoids starting with the sliders overlapping their guides.
    pub twist_ramp: f64,
    /// Stage-1 carriage start position along the stage-1 guides, m.
    pub start1: f64,
    /// Stage-2 carriage start position along the stage-2 guides (from their root), m.
    pub start2: f64,
    /// Stage-1 actuator speed (constant), m/s.
    pub speed1: f64,
    /// Stage-2 actuator speed relative to the stage-1 carriage, m/s.
    pub speed2: f64,
    /// Stage-1 actuator acceleration (x₁ = start1 + v₁t + ½a₁t²), m/s²; 0 by default.
    pub accel1: f64,
    /// Stage-2 actuator acceleration (relative), m/s²; 0 by default.
    pub accel2: f64,
    /// Simulated time, s.
    pub duration: f64,
    /// Relative tolerance of the integrator.
    pub rtol: f64,
    /// Integrator.
    pub solver: Solver,
}

impl Default for DualGuideParams {
    fn default() -> Self {
        Self {
            dual: true,
            spacing: 0.1,
            guide1_length: 1.0,
            guide2_length: 0.6,
            guide_width: 0.02,
            guide1_depth: 0.03,
            guide2_depth: 0.02,
            youngs_modulus: 70e9,
            density: 2700.0,
            poisson_ratio: 0.33,
            elements1: 4,
            elements2: 4,
            modes2: 3,
            rayleigh_alpha: 6.0,
            carriage1_mass: 1.0,
            carriage2_mass: 0.5,
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
            lateral_load: 50.0,
            load_offset: 0.01,
            load_lateral_offset: 0.02,
            carriage1_twist: 0.0,
            twist_ramp: 0.01,
            start1: 0.5,
            start2: 0.3,
            speed1: 0.5,
            speed2: 0.5,
            accel1: 0.0,
            accel2: 0.0,
            duration: 0.1,
            rtol: 1e-4,
            solver: Solver::Dopri5,
        }
    }
}

/// First bending frequency of a clamped-free Euler–Bernoulli beam, Hz:
/// f₁ = (β₁L)²/(2π)·√(EI/(ρAL⁴)), β₁L = 1.875104 (Rao, *Vibration of Continuous Systems*, 2007,
/// §11.5), for length `l`, section b × h, modulus `e` and density `rho` (SI).
pub fn cantilever_frequency(l: f64, b: f64, h: f64, e: f64, rho: f64) -> f64 {
    let ei = e * b * h.powi(3) / 12.0;
    1.875_104_f64.powi(2) / (2.0 * std::f64::consts::PI) * (ei / (rho * b * h * l.powi(4))).sqrt()
}

impl DualGuideParams {
    /// Check every field; the message names the field to change.
    ///
    /// # Errors
    /// A description of the first invalid field.
    pub fn validate(&self) -> Result<(), String> {
        for (f, v) in [
            ("spacing", self.spacing),
            ("guide1_length", self.guide1_length),
            ("guide2_length", self.guide2_length),
            ("guide_width", self.guide_width),
            ("guide1_depth", self.guide1_depth),
            ("guide2_depth", self.guide2_depth),
            ("youngs_modulus", self.youngs_modulus),
            ("density", self.density),
            ("carriage1_mass", self.carriage1_mass),
            ("carriage2_mass", self.carriage2_mass),
            ("slider_length", self.slider_length),
            ("pad_height", self.pad_height),
            ("clearance", self.clearance),
            ("edge_radius", self.edge_radius),
            ("layer_depth", self.layer_depth),
            ("restitution", self.restitution),
            ("duration", self.duration),
            ("rtol", self.rtol),
        ] {
            common::positive(f, v)?;
        }
        common::non_negative("rayleigh_alpha", self.rayleigh_alpha)?;
        common::non_negative("lateral_load", self.lateral_load)?;
        common::positive("twist_ramp", self.twist_ramp)?;
        if !self.carriage1_twist.is_finite() || self.carriage1_twist.abs() > 0.1 {
            return Err(format!(
                "`carriage1_twist` = {} rad: give a small angle, |φ| ≤ 0.1 rad (the root shift \
                 ±φ·d/2 is the small-angle form)",
                self.carriage1_twist
            ));
        }
        if self.carriage1_twist != 0.0 && !self.dual {
            return Err(
                "`carriage1_twist` acts on the stage-2 guides: set `dual = true` or \
                        leave it 0"
                    .into(),
            );
        }
        for (f, n) in [
            ("elements1", self.elements1),
            ("elements2", self.elements2),
            ("modes2", self.modes2),
        ] {
            if n == 0 {
                return Err(format!("`{f}` must be at least 1"));
            }
        }
        if self.modes2 > 3 * self.elements2 {
            return Err(format!(
                "`modes2` = {} exceeds the {} free DOF of a stage-2 guide; lower it or raise \
                 `elements2`",
                self.modes2,
                3 * self.elements2
            ));
        }
        let t = self.duration;
        let half = 0.5 * self.slider_length;
        for (what, x0, v, a, len) in [
            (
                "start1/speed1/accel1",
                self.start1,
                self.speed1,
                self.accel1,
                self.guide1_length,
            ),
            (
                "start2/speed2/accel2",
                self.start2,
                self.speed2,
                self.accel2,
                self.guide2_length,
            ),
        ] {
            let x1 = x0 + v * t + 0.5 * a * t * t;
            let (lo, hi) = (x0.min(x1), x0.max(x1));
            if !(lo.is_finite() && hi.is_finite() && lo - half >= 0.0 && hi + half <= len) {
                return Err(format!(
                    "`{what}`: the carriage runs over [{lo}, {hi}] m in `duration` = {t} s, \
                     so its pads (half length {half} m) leave the guide [0, {len}] m"
                ));
            }
        }
        Ok(())
    }

    /// The independent Newton's-law check: no lateral load, both stages starting at rest with
    /// constant accelerations a₁ = 2 m/s², a₂ = 3 m/s² for 0.02 s, DOPRI5 at rtol 1e-8. The
    /// carriages stay centred (no contact) and the actuator reactions are F₂ = m₂ (a₁ + a₂) and
    /// F₁ = (m₁ + 2 m_g2) a₁ + m₂ (a₁ + a₂) = [`Self::newton_stage1_force`].
    pub fn newton_check() -> Self {
        Self {
            lateral_load: 0.0,
            speed1: 0.0,
            speed2: 0.0,
            accel1: 2.0,
            accel2: 3.0,
            duration: 0.02,
            rtol: 1e-8,
            solver: Solver::Dopri5,
            ..Self::default()
        }
    }

    /// Closed-form stage-1 actuator force of the dual guide with no contact, N (Newton's
    /// second law): F₁ = [`Self::stage1_moving_mass`] a₁ + m₂ a₂.
    pub fn newton_stage1_force(&self) -> f64 {
        self.stage1_moving_mass() * self.accel1 + self.carriage2_mass * self.accel2
    }

    /// Total mass carried by the stage-1 actuator in the dual guide: stage-1 carriage, both
    /// stage-2 guides (ρ b h₂ L₂ each) and the stage-2 carriage, kg.
    pub fn stage1_moving_mass(&self) -> f64 {
        self.carriage1_mass
            + 2.0 * self.density * self.guide_width * self.guide2_depth * self.guide2_length
            + self.carriage2_mass
    }

    /// The clamp of stage-2 guide `s` (root at carriage-local (0, y)) to the stage-1 carriage:
    /// a fixed joint, or with a twist a translational joint along the carriage's y plus the
    /// prescribed root shift ±φ·d/2 (sign of y) as a displacement driver.
    fn stage2_root(&self, b: &mut ModelBuilder, s: &str, y: f64) {
        let g = format!("g2{s}");
        let (root, node) = (("carriage1", [0.0, y]), (g.as_str(), 0usize));
        if self.carriage1_twist == 0.0 {
            b.fixed(&format!("root_{s}"), root, node);
            return;
        }
        let shift = 0.5 * self.carriage1_twist * self.spacing * y.signum();
        b.translational(&format!("root_{s}"), root, node, [0.0, 1.0])
            .drive_displacement(
                &format!("twist_{s}"),
                root,
                node,
                [0.0, 1.0],
                TimeFn::SmoothStep {
                    from: 0.0,
                    to: shift,
                    start: 0.0,
                    duration: self.twist_ramp,
                },
            );
    }

    /// A clamped-free straight guide from `a` to `b` of depth `h` and `elements` elements.
    fn guide_beam(&self, a: [f64; 2], b: [f64; 2], h: f64, elements: usize) -> BeamMesh {
        BeamMesh {
            start: a,
            end: b,
            elements,
            material: BeamMaterial {
                youngs_modulus: self.youngs_modulus,
                density: self.density,
                poisson_ratio: self.poisson_ratio,
            },
            section: SectionDesc::Rectangular {
                width: self.guide_width,
                depth: h,
            },
            supports: vec![SupportDesc {
                node: 0,
                kind: SupportKind::Clamped,
            }],
            rayleigh: [self.rayleigh_alpha, 0.0],
            mass: Default::default(),
        }
    }

    /// The stage-2 guide in its own frame (root at the origin, along +x) and its cantilever
    /// modal reduction.
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn stage2_guide(&self, model: &str) -> Result<(BeamModel, ReducedModel), ModelsError> {
        let beam = self
            .stage2_mesh()
            .build("stage-2 guide")
            .map_err(|e| common::invalid(model, e.message))?;
        let red = beam
            .modal_truncation(self.modes2)
            .map_err(|e| common::invalid(model, e.to_string()))?;
        Ok((beam, red))
    }

    /// The stage-2 guide mesh in its own frame (root at the origin, along +x).
    fn stage2_mesh(&self) -> BeamMesh {
        self.guide_beam(
            [0.0, 0.0],
            [self.guide2_length, 0.0],
            self.guide2_depth,
            self.elements2,
        )
    }

    /// y of each guide of a stage: ±d/2 (dual) or 0 (single), with its name suffix.
    fn guide_rows(&self) -> Vec<(&'static str, f64)> {
        if self.dual {
            vec![("a", 0.5 * self.spacing), ("b", -0.5 * self.spacing)]
        } else {
            vec![("a", 0.0)]
        }
    }

    /// Name of the carriage carrying the load and of its actuator.
    pub fn loaded(&self) -> (&'static str, &'static str) {
        if self.dual {
            ("carriage2", "act2")
        } else {
            ("carriage1", "act1")
        }
    }

    /// The multibody model ([`DualGuideParams::desc`] compiled).
    ///
    /// # Errors
    /// Invalid parameters or a clr-mbd build error.
    pub fn build(&self, model: &str) -> Result<Model, ModelsError> {
        common::compile(model, &self.desc(model)?)
    }

    /// The multibody model as data, with the run settings of `clr run <model>` (no `--t-end`
    /// or `--rtol`) in `solver` and `output`: the `solver` and `rtol` parameters, atol =
    /// rtol·10⁻³, 0 to `duration` s, every accepted step recorded. `model` names the model in
    /// errors and in `[model]`. Bodies: stage-1 guides `g1a`, `g1b` (flexible beams, x from 0 at
    /// the clamped roots, y = ±d/2), carriage `carriage1` with pads `s1a_up`, `s1a_lo`,
    /// `s1b_up`, `s1b_lo`, actuator `act1` (ground → carriage1, axial); dual only: stage-2
    /// guides `g2a`, `g2b` (floating beams clamped to carriage1 at (0, ±d/2) by `root_a`,
    /// `root_b`), carriage `carriage2` with pads `s2a_up` … `s2b_lo`, actuator `act2`
    /// (carriage1 → carriage2, axial); lateral load `load` on the loaded carriage.
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn desc(&self, model: &str) -> Result<ModelDesc, ModelsError> {
        self.validate().map_err(|m| common::invalid(model, m))?;
        let inv = |m: String| common::invalid(model, m);
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
        let spec = |f: Face| FlexibleGuideSpec {
            face: f,
            slider_length: self.slider_length,
            slider_height: self.pad_height,
            slider_angle: 0.0,
            face_points: self.face_points,
            guide_samples: 0,
            normal: line.clone().into(),
            area_normal: Some(area.clone().into()),
            friction: friction.clone().into(),
        };
        let (c, hp, l) = (self.clearance, self.pad_height, self.slider_length);
        let rows = self.guide_rows();
        let carriage = |mass: f64, h: f64, x: f64, v: f64| {
            let off = 0.5 * h + c + 0.5 * hp;
            let height = if self.dual { self.spacing } else { 0.0 } + 2.0 * off + hp;
            RigidBody::new(mass, mass * (l * l + height * height) / 12.0)
                .at(x, 0.0, 0.0)
                .moving(v, 0.0, 0.0)
        };
        let motion = |x0: f64, v: f64, a: f64| TimeFn::Polynomial {
            coefficients: vec![x0, v, 0.5 * a],
        };
        let pads = |b: &mut ModelBuilder, stage: u8, guide: &str, y: f64, h: f64| {
            let off = 0.5 * h + c + 0.5 * hp;
            let body = format!("carriage{stage}");
            let g = format!("g{stage}{guide}");
            b.slider_on_beam(
                &format!("s{stage}{guide}_up"),
                &g,
                (body.as_str(), [0.0, y + off]),
                spec(Face::Upper),
            )
            .slider_on_beam(
                &format!("s{stage}{guide}_lo"),
                &g,
                (body.as_str(), [0.0, y - off]),
                spec(Face::Lower),
            );
        };
        let mut b = ModelBuilder::new();
        let (m1, v1) = if self.dual {
            (self.carriage1_mass, self.speed1)
        } else {
            (self.carriage2_mass, self.speed1)
        };
        b.body(
            "carriage1",
            carriage(m1, self.guide1_depth, self.start1, v1),
        );
        for &(s, y) in &rows {
            let beam = self.guide_beam(
                [0.0, y],
                [self.guide1_length, y],
                self.guide1_depth,
                self.elements1,
            );
            b.flexible_beam(&format!("g1{s}"), beam);
            pads(&mut b, 1, s, y, self.guide1_depth);
        }
        b.drive_displacement(
            "act1",
            ("ground", [0.0, 0.0]),
            ("carriage1", [0.0, 0.0]),
            [1.0, 0.0],
            motion(self.start1, self.speed1, self.accel1),
        );
        if self.dual {
            b.body(
                "carriage2",
                carriage(
                    self.carriage2_mass,
                    self.guide2_depth,
                    self.start1 + self.start2,
                    self.speed1 + self.speed2,
                ),
            );
            for &(s, y) in &rows {
                let mesh = self.stage2_mesh();
                let g = format!("g2{s}");
                b.floating_beam(
                    &g,
                    mesh,
                    Reduction::Modal { modes: self.modes2 },
                    [self.start1, y, 0.0],
                    [self.speed1, 0.0, 0.0],
                );
                self.stage2_root(&mut b, s, y);
                pads(&mut b, 2, s, y, self.guide2_depth);
            }
            b.drive_displacement(
                "act2",
                ("carriage1", [0.0, 0.0]),
                ("carriage2", [0.0, 0.0]),
                [1.0, 0.0],
                motion(self.start2, self.speed2, self.accel2),
            );
        }
        let load = self.lateral_load;
        b.force(
            "load",
            (
                self.loaded().0,
                [self.load_offset, self.load_lateral_offset],
            ),
            TimeFn::constant(0.0),
            TimeFn::constant(-load),
        );
        Ok(common::finish_desc(
            b,
            model,
            self.duration,
            self.rtol,
            self.solver,
        ))
    }
}

/// The model and run settings that [`run`] simulates: [`DualGuideParams::desc`] with the end
/// time and tolerance of `settings` (when given) written into `solver` and `output`.
///
/// # Errors
/// Invalid parameters or run settings.
pub fn run_desc(
    model: &str,
    p: &DualGuideParams,
    settings: &RunSettings,
) -> Result<ModelDesc, ModelsError> {
    let mut d = common::run_desc(model, settings, Record::EveryStep, || p.desc(model))?;
    derived(&mut d, p);
    Ok(d)
}

/// The names of `v` as `&str`.
fn refs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

/// The dual guide's metrics as measures and metrics of its description, so that `clr run
/// dual_guide` and its exported file compute them the same way: every guide's tip deflection
/// as a recorded node (`g1<s>.node<E1>.uy` on the ground, `g2<s>.node<E2>.uy` in the stage-2
/// guide's own frame), the normal and |friction| forces summed over the pads and Σ|actuator
/// force| over the stages as `combination` measures; the loaded carriage's lateral displacement
/// (largest, RMS), the largest pad force (located on the dense output), the tip oscillation of
/// each stage about its running mean over that stage's first-mode period and the largest of
/// them, the largest tip deflection, the mean forces, the contact onsets (total and per pad),
/// the actuator forces and the jamming indicators (per μ_max × lateral load).
fn derived(d: &mut ModelDesc, p: &DualGuideParams) {
    use clr_mbd::desc::metric::{Divisor, MetricDesc, Statistic as S};
    use clr_mbd::desc::NodeSelection;
    use clr_mbd::measure::combination::{Combination, Term};
    let pads: Vec<String> = d.clearances.iter().map(|c| c.name().to_string()).collect();
    let (body, act) = p.loaded();
    let rows: Vec<&str> = p.guide_rows().iter().map(|(s, _)| *s).collect();
    let mut tips1 = Vec::new();
    let mut tips2 = Vec::new();
    for s in &rows {
        d.output
            .nodes
            .insert(format!("g1{s}"), NodeSelection::Nodes(vec![p.elements1]));
        tips1.push(format!("g1{s}.node{}.uy", p.elements1));
        if p.dual {
            d.output
                .nodes
                .insert(format!("g2{s}"), NodeSelection::Nodes(vec![p.elements2]));
            tips2.push(format!("g2{s}.node{}.uy", p.elements2));
        }
    }
    let term = |of: String, abs: bool| Term::column(&of, 1.0, abs);
    let sum = Combination::measure;
    // Σ|F_act| over the stages: the stage-1 actuator overcomes the stage-1 friction, the
    // stage-2 actuator the stage-2 friction, so the sum is the total friction of the mechanism
    let mut actuators = vec![term("act1.Fx".into(), true)];
    if p.dual {
        actuators.push(term(format!("{act}.Fx"), true));
    }
    d.measures.extend([
        sum(
            "normal_total",
            pads.iter()
                .map(|c| term(format!("{c}.normal_force"), false))
                .collect(),
        ),
        sum(
            "friction_total",
            pads.iter()
                .map(|c| term(format!("{c}.friction_force"), true))
                .collect(),
        ),
        sum("actuator_sum", actuators),
        sum("loaded_actuator", vec![term(format!("{act}.Fx"), true)]),
    ]);
    let strs = |v: &[String]| -> Vec<String> { v.to_vec() };
    let cols = |v: Vec<String>, suffix: &str| -> Vec<String> {
        v.into_iter().map(|c| format!("{c}.{suffix}")).collect()
    };
    let m =
        |name: &str, of: &str, stat, words: &str| MetricDesc::new(name, of, stat).described(words);
    let osc = |name: &str, tips: &[String], length: f64, depth: f64| MetricDesc {
        window: Some(
            1.0 / cantilever_frequency(length, p.guide_width, depth, p.youngs_modulus, p.density),
        ),
        ..MetricDesc::of_columns(name, &refs(tips), S::Oscillation).described(
            "largest |tip deflection − its running mean over one first-mode period| of the \
             stage's guides",
        )
    };
    let sliding = p.friction.law().map_or(f64::NAN, |l| l.mu_max()) * p.lateral_load;
    let forces = cols(strs(&pads), "normal_force");
    let contacts = cols(strs(&pads), "contact");
    let all_tips: Vec<String> = tips1.iter().chain(&tips2).cloned().collect();
    let mut v =
        vec![
        m(
            "max_lateral_displacement",
            &format!("{body}.y"),
            S::Peak,
            "largest |y| of the loaded carriage's centre (0 = centred on undeformed guides)",
        ),
        m(
            "rms_lateral_displacement",
            &format!("{body}.y"),
            S::Rms,
            "time RMS of the loaded carriage's y",
        ),
        MetricDesc::of_columns("peak_contact_force", &refs(&forces), S::Peak).described(
            "largest normal force of any pad (sum over that pad's points), located on the dense \
             output",
        ),
        osc("tip_oscillation_stage1", &tips1, p.guide1_length, p.guide1_depth),
    ];
    let mut stages = vec!["tip_oscillation_stage1"];
    if p.dual {
        v.push(osc(
            "tip_oscillation_stage2",
            &tips2,
            p.guide2_length,
            p.guide2_depth,
        ));
        stages.push("tip_oscillation_stage2");
    }
    v.extend([
        MetricDesc::of_metrics("tip_oscillation_amplitude", &stages, S::Max).described(
            "largest |tip deflection − its running mean over one first-mode period| of any \
             guide (stage-2 tips in their own frame)",
        ),
        MetricDesc::of_columns("max_tip_deflection", &refs(&all_tips), S::Peak)
            .described("largest |tip deflection| of any guide"),
        m(
            "mean_friction_force",
            "friction_total.value",
            S::Mean,
            "time average of |friction| summed over all pads",
        ),
        m(
            "mean_normal_force",
            "normal_total.value",
            S::Mean,
            "time average of the normal force summed over all pads",
        ),
        MetricDesc::of_columns("impacts", &refs(&contacts), S::Onsets)
            .described("contact onsets of all pads (0→1 transitions over the accepted steps)"),
        MetricDesc::of_columns(
            "peak_actuator_force",
            &if p.dual {
                vec!["act1.Fx", "act2.Fx"]
            } else {
                vec!["act1.Fx"]
            },
            S::Peak,
        )
        .described("largest |axial actuator reaction| of any stage"),
        m(
            "mean_loaded_actuator_force",
            "loaded_actuator.value",
            S::Mean,
            "time average of |axial reaction| of the actuator driving the loaded carriage",
        ),
        m(
            "mean_actuator_force_sum",
            "actuator_sum.value",
            S::Mean,
            "time average of Σ|axial actuator reaction| over the stages",
        ),
        m(
            "jamming_indicator",
            "actuator_sum.value",
            S::Mean,
            "time average of Σ|actuator force| over the stages / (μ_max × lateral load): ≈ 1 \
             for a carriage sliding steadily on one face under the load; > 1 when pinching \
             (the slider tilted between both faces, or between guides deforming differently) \
             raises the normal and friction forces",
        )
        .per(Divisor::Number(sliding))
        .in_unit("-"),
        m(
            "peak_jamming_ratio",
            "actuator_sum.value",
            S::Peak,
            "peak of Σ|actuator force| / (μ_max × lateral load) (dominated by impacts)",
        )
        .per(Divisor::Number(sliding))
        .in_unit("-"),
        MetricDesc::of_columns("impacts_per_pad", &refs(&contacts), S::Onsets)
            .described("contact onsets per pad (the dual guide has 8 pads, the single 2)")
            .per(Divisor::Number(pads.len().max(1) as f64)),
    ]);
    d.metrics = v;
}

/// Simulate and compute the metrics (docs/models/dual_guide.md): lateral displacement of the
/// loaded carriage (max, RMS), peak contact force, guide-tip oscillation, mean friction and
/// normal force, impacts over all pads, actuator forces and the jamming indicators.
///
/// # Errors
/// Invalid parameters, build or simulation errors.
pub fn run(
    model: &str,
    p: &DualGuideParams,
    settings: &RunSettings,
) -> Result<RunOutput, ModelsError> {
    crate::described_metrics::run_output(model, &run_desc(model, p, settings)?, settings, p)
}

/// One run of a dual-guide study.
pub type StudyRun = common::StudyRun<DualGuideParams>;

/// Run named parameter sets in parallel, writing `<name>.csv` and `summary.csv` under `dir`
/// and figures `lateral` (loaded carriage y) and `actuator` (stage-1 actuator force).
///
/// # Errors
/// The first failing run, or an output error.
pub fn study(dir: &Path, runs: Vec<(String, DualGuideParams)>) -> Result<Vec<StudyRun>, String> {
    let (done, results) =
        common::run_study(dir, runs, |p| run("dual_guide", p, &RunSettings::default()))?;
    figures(dir, &done, &results)?;
    Ok(done)
}

/// Single guide against the dual-stage dual guide (default parameters otherwise), under `dir`.
///
/// # Errors
/// See [`study`].
pub fn single_vs_dual(dir: &Path) -> Result<Vec<StudyRun>, String> {
    let dual = DualGuideParams::default();
    let single = DualGuideParams {
        dual: false,
        ..DualGuideParams::default()
    };
    study(dir, vec![("single".into(), single), ("dual".into(), dual)])
}

/// Spacing study: the default dual guide at each interguide spacing d (m), under `dir`.
///
/// # Errors
/// See [`study`].
pub fn spacing_study(dir: &Path, spacings: &[f64]) -> Result<Vec<StudyRun>, String> {
    let runs = spacings
        .iter()
        .map(|&d| {
            (
                format!("d{:.0}mm", d * 1e3),
                DualGuideParams {
                    spacing: d,
                    ..DualGuideParams::default()
                },
            )
        })
        .collect();
    study(dir, runs)
}

fn figures(dir: &Path, runs: &[StudyRun], results: &[Results]) -> Result<(), String> {
    use clr_plot::Figure;
    const MAX: usize = 3000;
    let mut fy = Figure::new("Loaded carriage lateral displacement")
        .x_label("time (s)")
        .y_label("carriage y (mm)");
    let mut fa = Figure::new("Stage-1 actuator force")
        .x_label("time (s)")
        .y_label("axial force (N)");
    for (r, res) in runs.iter().zip(results) {
        let t = col(res, "t");
        let (body, _) = r.params.loaded();
        let y: Vec<f64> = col(res, &format!("{body}.y"))
            .iter()
            .map(|v| v * 1e3)
            .collect();
        fy = fy.line(r.name.clone(), common::thin(&t, &y, MAX));
        fa = fa.line(r.name.clone(), common::thin(&t, &col(res, "act1.Fx"), MAX));
    }
    for (f, name) in [(fy, "lateral"), (fa, "actuator")] {
        common::save_figure(f, dir, name)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cantilever_frequency_matches_the_fe_stage2_guide() {
        // independent formulation: clr-beam's modal analysis of the 4-element stage-2 guide
        // (the reduction's first ω); 4 cubic elements give the first mode to < 1e-4
        let p = DualGuideParams::default();
        let (_, red) = p.stage2_guide("t").unwrap();
        let f_fe = red.mode_omega[0] / (2.0 * std::f64::consts::PI);
        let f = cantilever_frequency(
            p.guide2_length,
            p.guide_width,
            p.guide2_depth,
            p.youngs_modulus,
            p.density,
        );
        assert!((f_fe - f).abs() < 1e-4 * f, "{f_fe} vs {f}");
    }

    #[test]
    fn invalid_travel_names_the_field() {
        let p = DualGuideParams {
            speed2: 5.0,
            ..DualGuideParams::default()
        };
        let e = run("dual_guide", &p, &RunSettings::default()).unwrap_err();
        assert!(e.to_string().contains("start2/speed2/accel2"), "{e}");
    }

    /// Independent check (closed form, Newton's second law): with no lateral load the
    /// carriages stay centred between the pads (no contact), and under constant actuator
    /// accelerations a₁, a₂ the actuator reactions are F₂ = m₂ (a₁ + a₂) on the stage-2
    /// carriage and F₁ = (m₁ + 2 m_g2) a₁ + m₂ (a₁ + a₂) on the stage-1 carriage (it
    /// accelerates itself, the two stage-2 guides through their roots and the stage-2 carriage
    /// through act2). The stage-2 guides only stretch axially (their modes here are bending
    /// modes, so they stay rigid in x), hence a tight relative tolerance 1e-6 (rtol 1e-8).
    #[test]
    fn unloaded_accelerated_stages_follow_newton() {
        let p = DualGuideParams::newton_check();
        let d = common::run_desc(
            "t",
            &RunSettings::default(),
            Record::Every(p.duration / 4.0),
            || p.desc("t"),
        )
        .unwrap();
        let (mut m, opts) = common::compile_run("t", &d).unwrap();
        let res = m.simulate(&opts).unwrap();
        for pad in ["s1a_up", "s1b_lo", "s2a_up", "s2b_lo"] {
            let n = col(&res, &format!("{pad}.contact"));
            assert!(n.iter().all(|&v| v == 0.0), "{pad} touched");
        }
        let f2 = col(&res, "act2.Fx");
        let f1 = col(&res, "act1.Fx");
        let e2 = p.carriage2_mass * (p.accel1 + p.accel2);
        let e1 = p.newton_stage1_force();
        for k in 1..f2.len() {
            assert!((f2[k] - e2).abs() < 1e-6 * e2, "act2 {} vs {e2}", f2[k]);
            assert!((f1[k] - e1).abs() < 1e-6 * e1, "act1 {} vs {e1}", f1[k]);
        }
    }

    // The twist is refused where it has no meaning (the single guide has no stage-2 guides) or
    // leaves the small-angle form, with the field named; with φ = 0 the model keeps the fixed
    // root joints of the planar model, with φ ≠ 0 it has the translational joints and drivers.
    #[test]
    fn twist_is_checked_and_switches_the_root_joints() {
        let single = DualGuideParams {
            dual: false,
            carriage1_twist: 0.01,
            ..DualGuideParams::default()
        };
        assert!(single.validate().unwrap_err().contains("dual = true"));
        let large = DualGuideParams {
            carriage1_twist: 0.2,
            ..DualGuideParams::default()
        };
        assert!(large.validate().unwrap_err().contains("carriage1_twist"));
        let ramp = DualGuideParams {
            carriage1_twist: 0.01,
            twist_ramp: 0.0,
            ..DualGuideParams::default()
        };
        assert!(ramp.validate().unwrap_err().contains("twist_ramp"));
        let names = |p: &DualGuideParams| {
            let d = p.desc("t").unwrap();
            (d.joints.len(), d.drivers.len())
        };
        let planar = names(&DualGuideParams::default());
        let twisted = names(&DualGuideParams {
            carriage1_twist: 0.01,
            ..DualGuideParams::default()
        });
        assert_eq!((twisted.0, twisted.1), (planar.0, planar.1 + 2));
    }
}
