//! Slider–crank mechanisms with a revolute clearance joint between the connecting rod and the
//! slider: the Flores-style benchmark of issue 5 (`slider_crank`) and the validation rig of
//! Wan et al., *Machines* 10 (2022) 1098 (`wan_slider_crank`).
//!
//! Geometry and inertia (both models, from the benchmark and Wan's table): crank 0.05 m,
//! 0.343 kg, 0.000216 kg·m²; rod 0.30 m, 1.072 kg, 0.034 kg·m²; slider 0.347 kg, 0.000115 kg·m².
//! The crank turns at constant speed from θ = 0 (all links along +x); the bearing is on the
//! slider at its centre, the journal at the rod end, centred in the bearing at t = 0.

use clr_mbd::{Model, ModelBuilder, ModelDesc, RevoluteClearanceSpec, RigidBody, TimeFn};
use serde::{Deserialize, Serialize};

use crate::common::{self, non_negative, positive, FrictionParams, Record, Solver};
use crate::{ModelsError, RunOutput, RunSettings};

/// Parameters of a clearance slider–crank (SI units).
///
/// Defaults are those of [`SliderCrankParams::flores`] (`slider_crank`);
/// [`SliderCrankParams::wan`] gives the `wan_slider_crank` defaults.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SliderCrankParams {
    /// Crank length, m (0.05).
    pub crank_length: f64,
    /// Connecting-rod length, m (0.30).
    pub rod_length: f64,
    /// Crank mass, kg (0.343).
    pub crank_mass: f64,
    /// Rod mass, kg (1.072).
    pub rod_mass: f64,
    /// Slider mass, kg (0.347).
    pub slider_mass: f64,
    /// Crank inertia about its centre of mass, kg·m² (0.000216).
    pub crank_inertia: f64,
    /// Rod inertia about its centre of mass, kg·m² (0.034; Wan's value is close to mL²/3, which
    /// would be about the rod end: taken about the centre, as in Flores' benchmark).
    pub rod_inertia: f64,
    /// Slider inertia about its centre of mass, kg·m² (0.000115).
    pub slider_inertia: f64,
    /// Crank speed, rpm (constant).
    pub crank_speed_rpm: f64,
    /// Bearing (hole) radius R_i, m.
    pub bearing_radius: f64,
    /// Journal (pin) radius R_j, m (< R_i; clearance c = R_i − R_j).
    pub journal_radius: f64,
    /// Axial length of the joint L, m (used by the `Wang` and `Modified` laws only; refused with the others).
    pub axial_length: f64,
    /// Young's modulus of journal and bearing, Pa (steel 207 GPa).
    pub youngs_modulus: f64,
    /// Poisson's ratio of journal and bearing (0.3).
    pub poisson_ratio: f64,
    /// Normal law: `Hertz`, `LN`, `Gonthier`, `Bai`, `Wang` or `Modified`
    /// (clr_contact `NormalLaw::preset`).
    pub normal_law: String,
    /// Input coefficient of restitution c_e (–).
    pub restitution: f64,
    /// Friction law in the clearance joint.
    pub friction: FrictionParams,
    /// Gravity −9.81 m/s² along y when true.
    pub gravity: bool,
    /// Simulated time, s.
    pub duration: f64,
    /// Crank revolutions excluded from the metrics (start-up transient).
    pub transient_revolutions: f64,
    /// Relative tolerance (absolute tolerance rtol·1e-3).
    pub rtol: f64,
    /// Integrator.
    pub solver: Solver,
}

impl Default for SliderCrankParams {
    fn default() -> Self {
        Self::flores()
    }
}

impl SliderCrankParams {
    /// The benchmark of issue 5 (Flores et al. 2004 style): clearance 0.5 mm (R_i = 10.0 mm,
    /// R_j = 9.5 mm), steel, Hertz internal cylinder with the Lankarani–Nikravesh damping
    /// (`LN`), c_e = 0.9, no friction, crank 5000 rpm, gravity, 0.1 s.
    pub fn flores() -> Self {
        Self {
            crank_length: 0.05,
            rod_length: 0.30,
            crank_mass: 0.343,
            rod_mass: 1.072,
            slider_mass: 0.347,
            crank_inertia: 0.000216,
            rod_inertia: 0.034,
            slider_inertia: 0.000115,
            crank_speed_rpm: 5000.0,
            bearing_radius: 10.0e-3,
            journal_radius: 9.5e-3,
            axial_length: 10e-3,
            youngs_modulus: 207e9,
            poisson_ratio: 0.3,
            normal_law: "LN".into(),
            restitution: 0.9,
            friction: FrictionParams::None,
            gravity: true,
            duration: 0.1,
            transient_revolutions: 1.0,
            rtol: 1e-7,
            solver: Solver::Dopri5,
        }
    }

    /// Wan et al. (2022) validation rig, reconstructed (paper-systems.md §1.1/§1.2): the
    /// `Modified` law (Liu conformal stiffness with L = 15 mm, Gonthier damping), c_r = 0.46,
    /// Ambrósio friction c_f = 0.01, v0 = 1e-4 m/s, v1 = 1e-3 m/s (the flap study's values),
    /// clearance 0.1 mm (R_i = 10 mm, first row of the table), crank 600 rpm
    /// (reconstruction: not given in the abstract), three revolutions (0.3 s), metrics after
    /// the first revolution.
    pub fn wan() -> Self {
        Self {
            crank_speed_rpm: 600.0,
            bearing_radius: 10.0e-3,
            journal_radius: 9.9e-3,
            axial_length: 15e-3,
            normal_law: "Modified".into(),
            restitution: 0.46,
            friction: FrictionParams::Ambrosio {
                mu: 0.01,
                v0: 1e-4,
                v1: 1e-3,
            },
            duration: 0.3,
            rtol: 1e-8,
            ..Self::flores()
        }
    }

    /// Crank speed ω, rad/s.
    pub fn omega(&self) -> f64 {
        self.crank_speed_rpm * std::f64::consts::PI / 30.0
    }

    /// Parameters these settings do not use, with the reason: `axial_length` is taken only by
    /// the `Wang` and `Modified` presets (the Liu law).
    pub fn unused(&self) -> Vec<(&'static str, String)> {
        if clr_contact::normal::preset_uses_length(&self.normal_law) {
            Vec::new()
        } else {
            vec![(
                "axial_length",
                format!(
                    "normal_law = \"{}\" has no axial length (only Wang and Modified use it)",
                    self.normal_law
                ),
            )]
        }
    }

    /// Check every value; the message says which field to change.
    ///
    /// # Errors
    /// A message naming the field.
    pub fn validate(&self) -> Result<(), String> {
        for (f, v) in [
            ("crank_length", self.crank_length),
            ("rod_length", self.rod_length),
            ("crank_mass", self.crank_mass),
            ("rod_mass", self.rod_mass),
            ("slider_mass", self.slider_mass),
            ("crank_inertia", self.crank_inertia),
            ("rod_inertia", self.rod_inertia),
            ("slider_inertia", self.slider_inertia),
            ("crank_speed_rpm", self.crank_speed_rpm),
            ("bearing_radius", self.bearing_radius),
            ("journal_radius", self.journal_radius),
            ("axial_length", self.axial_length),
            ("duration", self.duration),
            ("rtol", self.rtol),
        ] {
            positive(f, v)?;
        }
        non_negative("transient_revolutions", self.transient_revolutions)?;
        if self.rod_length <= self.crank_length {
            return Err(format!(
                "`rod_length` = {} must exceed `crank_length` = {} for a full-turn crank",
                self.rod_length, self.crank_length
            ));
        }
        if self.journal_radius >= self.bearing_radius {
            return Err(format!(
                "`journal_radius` = {} must be smaller than `bearing_radius` = {} (the clearance \
                 is their difference)",
                self.journal_radius, self.bearing_radius
            ));
        }
        Ok(())
    }

    /// The clr-mbd model ([`SliderCrankParams::desc`] compiled).
    ///
    /// # Errors
    /// Invalid parameters or a clr-mbd build error.
    pub fn build(&self, model: &str) -> Result<Model, ModelsError> {
        common::compile(model, &self.desc(model)?)
    }

    /// The model as data, with the run settings of `clr run <model>` (no `--t-end` or
    /// `--rtol`) in `solver` and `output`: the `solver` and `rtol` parameters, atol = rtol·10⁻³,
    /// 0 to `duration` s, every accepted step recorded. Bodies `crank`, `rod`, `slider`; joints
    /// `O` (ground–crank), `A` (crank–rod), `guide` (translational), driver `motor`; clearance
    /// joint `B`. `model` names the model in errors and in `[model]`.
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn desc(&self, model: &str) -> Result<ModelDesc, ModelsError> {
        self.validate().map_err(|m| common::invalid(model, m))?;
        // validated here for the parameter-level message; the model gets the law as data
        common::preset_law(
            &self.normal_law,
            self.youngs_modulus,
            self.poisson_ratio,
            self.bearing_radius,
            self.journal_radius,
            self.axial_length,
            self.restitution,
        )
        .map_err(|m| common::invalid(model, m))?;
        self.friction.law().map_err(|m| common::invalid(model, m))?;
        let normal = common::preset_desc(
            &self.normal_law,
            self.youngs_modulus,
            self.poisson_ratio,
            self.axial_length,
            self.restitution,
        )
        .into();
        let friction = self.friction.desc().into();
        let (r, l) = (self.crank_length, self.rod_length);
        let w = self.omega();
        let mut b = ModelBuilder::new();
        if self.gravity {
            b.gravity(0.0, -9.81);
        }
        b.body(
            "crank",
            RigidBody::new(self.crank_mass, self.crank_inertia)
                .at(r / 2.0, 0.0, 0.0)
                .moving(0.0, w * r / 2.0, w),
        )
        .body(
            "rod",
            RigidBody::new(self.rod_mass, self.rod_inertia)
                .at(r + l / 2.0, 0.0, 0.0)
                .moving(0.0, w * r / 2.0, -w * r / l),
        )
        .body(
            "slider",
            RigidBody::new(self.slider_mass, self.slider_inertia).at(r + l, 0.0, 0.0),
        )
        .revolute("O", ("ground", [0.0, 0.0]), ("crank", [-r / 2.0, 0.0]))
        .revolute("A", ("crank", [r / 2.0, 0.0]), ("rod", [-l / 2.0, 0.0]))
        .translational(
            "guide",
            ("ground", [0.0, 0.0]),
            ("slider", [0.0, 0.0]),
            [1.0, 0.0],
        )
        .drive_angle("motor", "crank", TimeFn::linear(0.0, w))
        .revolute_clearance(
            "B",
            ("slider", [0.0, 0.0]),
            ("rod", [l / 2.0, 0.0]),
            RevoluteClearanceSpec {
                bearing_radius: self.bearing_radius,
                journal_radius: self.journal_radius,
                normal,
                friction,
            },
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

/// Closed-form slider position of the ideal slider–crank, x(θ) = r cos θ + √(l² − r² sin² θ)
/// (e.g. Nikravesh 1988, §2), m.
pub fn ideal_slider_position(r: f64, l: f64, theta: f64) -> f64 {
    let s = theta.sin();
    r * theta.cos() + (l * l - r * r * s * s).sqrt()
}

/// Rows per crank revolution of the ideal twin behind `slider.error`: its linear interpolation
/// error h²/8·|ẍ| with |ẍ| ≤ rω²(1 + r/l) is (2π/2000)²/8·r(1 + r/l) = 7e-8 m at r = 0.05 m,
/// l = 0.3 m, against a clearance of 1e-4 to 5e-4 m.
const TWIN_ROWS_PER_REVOLUTION: f64 = 2000.0;

/// The model and run settings that [`run`] simulates: [`SliderCrankParams::desc`] with the end
/// time and tolerance of `settings` (when given) written into `solver` and `output`, and the
/// derived column and metrics as data ([`derived`]).
///
/// # Errors
/// Invalid parameters or run settings.
pub fn run_desc(
    model: &str,
    p: &SliderCrankParams,
    settings: &RunSettings,
) -> Result<ModelDesc, ModelsError> {
    let mut d = common::run_desc(model, settings, Record::EveryStep, || p.desc(model))?;
    derived(&mut d, p);
    Ok(d)
}

/// The slider–crank's derived column and metrics as `[[measure]]`, `[twin]` and `[[metric]]`
/// of its description, so that `clr run <name>` and its exported file compute them the same
/// way: `slider.error` (m), the slider's deviation from the ideal-joint twin (the same
/// mechanism with joint B ideal, whose slider follows x(θ) = r cos θ + √(l² − r² sin² θ)),
/// recorded at [`TWIN_ROWS_PER_REVOLUTION`]; peak contact force, peak slider acceleration,
/// contact-time fraction and largest penetration after `transient_revolutions`, and the
/// largest |slider.error| over the run.
fn derived(d: &mut ModelDesc, p: &SliderCrankParams) {
    use clr_mbd::desc::metric::{MetricDesc, Statistic};
    use clr_mbd::measure::deviation::{Deviation, TwinSettings};
    let t_end = d.output.t_end.unwrap_or(p.duration);
    let revolutions = t_end * p.crank_speed_rpm / 60.0;
    d.measures.push(clr_mbd::Measure::Deviation(Deviation {
        name: "slider".into(),
        of: vec!["slider.x".into()],
        suffix: None,
    }));
    d.twin = Some(TwinSettings {
        intervals: Some(((revolutions * TWIN_ROWS_PER_REVOLUTION).ceil() as usize).max(1000)),
    });
    let t_from = p.transient_revolutions * 60.0 / p.crank_speed_rpm;
    let metric = |name: &str, of: &str, statistic, after_transient: bool, words: &str| MetricDesc {
        t_start: after_transient.then_some(t_from),
        ..MetricDesc::new(name, of, statistic).described(words)
    };
    d.metrics = vec![
        metric(
            "peak_contact_force",
            "B.normal_force",
            Statistic::Peak,
            true,
            "largest normal force in the clearance joint after the transient, located on the \
             dense output",
        ),
        metric(
            "peak_slider_acceleration",
            "slider.ax",
            Statistic::Peak,
            true,
            "largest |slider acceleration| after the transient (every accepted step)",
        ),
        metric(
            "contact_time_fraction",
            "B.contact",
            Statistic::Mean,
            true,
            "fraction of the time after the transient with journal and bearing in contact",
        ),
        metric(
            "max_penetration",
            "B.penetration",
            Statistic::Max,
            true,
            "largest penetration after the transient, located on the dense output",
        ),
        metric(
            "max_slider_deviation",
            "slider.error",
            Statistic::Peak,
            false,
            "largest |x − x_ideal| of the slider over the run, x_ideal from the ideal-joint \
             twin (bounded by clearance + penetration)",
        ),
    ];
}

/// Simulate and compute the derived column and the metrics of [`derived`] from the
/// description, as a run of its exported file does (`clr_mbd::measure::deviation` and
/// [`crate::described_metrics`]).
///
/// # Errors
/// Invalid parameters, build or simulation errors.
pub fn run(
    model: &str,
    p: &SliderCrankParams,
    settings: &RunSettings,
) -> Result<RunOutput, ModelsError> {
    crate::described_metrics::run_output(model, &run_desc(model, p, settings)?, settings, p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn metric(out: &RunOutput, name: &str) -> f64 {
        out.metrics.iter().find(|m| m.name == name).unwrap().value
    }

    #[test]
    fn slider_stays_within_clearance_of_the_ideal_position() {
        // closed-form bound: with the crank and rod ideal, the slider can leave its ideal
        // position x(θ) = r cos θ + √(l² − r² sin² θ) only by the radial play of the clearance
        // joint, c + δ_max (the rod angle change moves it by less than c·(r/l)², negligible)
        let p = SliderCrankParams {
            duration: 0.01,
            transient_revolutions: 0.0,
            ..SliderCrankParams::flores()
        };
        let out = run("slider_crank", &p, &RunSettings::default()).unwrap();
        let c = p.bearing_radius - p.journal_radius;
        let dev = metric(&out, "max_slider_deviation");
        let pen = metric(&out, "max_penetration");
        assert!(
            dev <= (c + pen) * 1.01,
            "deviation {dev} > c + δ = {}",
            c + pen
        );
        // and the journal does travel across the clearance at 5000 rpm (impacts happen)
        assert!(
            dev > 0.5 * c,
            "deviation {dev} should reach the clearance {c}"
        );
        assert!(metric(&out, "peak_contact_force") > 0.0);
        assert_eq!(out.units.len(), out.results.columns.len());
    }

    #[test]
    fn invalid_clearance_is_rejected_with_the_field_name() {
        let p = SliderCrankParams {
            journal_radius: 0.011,
            ..SliderCrankParams::flores()
        };
        let e = run("slider_crank", &p, &RunSettings::default()).unwrap_err();
        assert!(e.to_string().contains("journal_radius"), "{e}");
    }
}
