//! Contact laws by name with physical parameters, as data (the `normal = { … }` and
//! `friction = { … }` tables of a model file), and their conversion into clr-contact laws.
//!
//! The geometry a law needs (a revolute clearance joint's radii) comes from the joint, so each
//! radius is given once; [`NormalLawDesc::build`] receives it from the element.

use clr_contact::{
    DampingFactor, ElasticLaw, FrictionLaw, GuideFace, JournalBearing, LuGre, Material, NormalLaw,
};
use serde::{Deserialize, Serialize};

use crate::field::{suggestion, FieldError};

/// An isotropic contact material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDesc {
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio, –.
    pub poisson_ratio: f64,
}

/// A normal-force law by name (`law`) with its parameters; unused parameters are refused.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NormalLawDesc {
    /// Elastic law: `hertz`, `power`, `linear` (with `stiffness`), `hertz-internal-cylinder`,
    /// `liu`, `bai-zhao`, `johnson`, `pereira` (materials and `length`; radii from the joint),
    /// `preset` (flap paper label), `flores-line` and `area` (guide face parameters).
    pub law: String,
    /// Damping factor name (clr-contact `DampingFactor::from_name`); fixed by `preset`,
    /// `flores-line` and `area`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<String>,
    /// Input coefficient of restitution c_e ∈ (0, 1].
    pub restitution: f64,
    /// Stiffness K (N/m^n) for `hertz`, `power`, `linear`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// Exponent n for `power`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exponent: Option<f64>,
    /// Axial length L of a journal bearing, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// Bearing material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bearing_material: Option<MaterialDesc>,
    /// Journal material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub journal_material: Option<MaterialDesc>,
    /// Flap-paper label for `law = "preset"` (`Hertz`, `LN`, `Gonthier`, `Bai`, `Wang`,
    /// `Modified`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preset: Option<String>,
    /// Slider material (`flores-line`, `area`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slider_material: Option<MaterialDesc>,
    /// Guide material (`flores-line`, `area`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub guide_material: Option<MaterialDesc>,
    /// Rounding radius of the slider edge, m (`flores-line`, `area`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_radius: Option<f64>,
    /// Width of the slider face out of the plane, m (`flores-line`, `area`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// Depth of the elastic layer of the Winkler foundation, m (`area`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub layer_depth: Option<f64>,
    /// Floor of the impact velocity δ̇⁻, m/s (default 1e-4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_impact_velocity: Option<f64>,
}

/// Normal-law names accepted in `law`.
pub const NORMAL_LAWS: [&str; 11] = [
    "hertz",
    "power",
    "linear",
    "hertz-internal-cylinder",
    "liu",
    "bai-zhao",
    "johnson",
    "pereira",
    "preset",
    "flores-line",
    "area",
];

/// How to write a damping factor given as `law` (`lankarani-nikravesh`, `ln`, `flores`, …): a
/// user reading "Hertz law with Lankarani–Nikravesh damping" in a paper often names the damping
/// as the law, and the list of laws alone does not say where it goes.
fn damping_as_law(law: &str) -> Option<String> {
    let d = DampingFactor::from_name(law).ok()?;
    let name = d.name();
    // the flap paper's presets are the internal-cylinder Hertz law with these dampings
    let preset = match d {
        DampingFactor::LankaraniNikravesh => {
            " (law = \"preset\" with preset = \"LN\" and the \
                                              two materials is the same law)"
        }
        DampingFactor::Gonthier => {
            " (law = \"preset\" with preset = \"Gonthier\" and the two \
                                    materials is the same law)"
        }
        DampingFactor::Flores => {
            " (the rounded-edge law of a slider on a guide face is \
                                  law = \"flores-line\")"
        }
        _ => "",
    };
    Some(format!(
        "`{name}` is a damping factor, not an elastic law: keep an elastic law in `law` and name \
         the damping factor in `damping`, e.g. law = \"hertz\" with stiffness = K (N/m^1.5) and \
         damping = \"{name}\", or law = \"hertz-internal-cylinder\" with bearing_material, \
         journal_material and damping = \"{name}\"{preset}"
    ))
}

/// Journal–bearing geometry a revolute clearance joint gives its law: (R_bearing, R_journal), m.
pub type Radii = Option<(f64, f64)>;

struct Ctx<'a> {
    path: &'a str,
    law: &'a str,
}

impl Ctx<'_> {
    fn err(&self, field: &str, m: impl Into<String>) -> FieldError {
        FieldError::new(format!("{}.{field}", self.path), m)
    }
    fn req<T: Copy>(&self, field: &str, v: Option<T>, what: &str) -> Result<T, FieldError> {
        v.ok_or_else(|| {
            self.err(
                field,
                format!("missing value: the `{}` law needs {what}", self.law),
            )
        })
    }
    fn positive(&self, field: &str, v: Option<f64>, what: &str) -> Result<f64, FieldError> {
        let x = self.req(field, v, what)?;
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(self.err(field, format!("must be positive and finite, got {x}")))
        }
    }
    fn non_negative(&self, field: &str, v: Option<f64>, what: &str) -> Result<f64, FieldError> {
        let x = self.req(field, v, what)?;
        if x.is_finite() && x >= 0.0 {
            Ok(x)
        } else {
            Err(self.err(field, format!("must be ≥ 0 and finite, got {x}")))
        }
    }
    fn material(&self, field: &str, m: Option<MaterialDesc>) -> Result<Material, FieldError> {
        let m = self.req(
            field,
            m,
            "a material { youngs_modulus = 2.07e11, poisson_ratio = 0.3 } (Pa, –)",
        )?;
        Material::new(m.youngs_modulus, m.poisson_ratio).map_err(|e| self.err(field, e.to_string()))
    }
    fn refuse(&self, given: &[(&str, bool)], used: &[&str]) -> Result<(), FieldError> {
        match given.iter().find(|(f, g)| *g && !used.contains(f)) {
            Some((f, _)) => Err(self.err(
                f,
                format!(
                    "the `{}` law does not use `{f}`; remove it (it uses {})",
                    self.law,
                    used.join(", ")
                ),
            )),
            None => Ok(()),
        }
    }
}

impl NormalLawDesc {
    /// A Hertz law F = Kδ^{3/2} with Lankarani–Nikravesh damping (N/m^{3/2}, c_e).
    pub fn hertz(stiffness: f64, restitution: f64) -> Self {
        Self {
            law: "hertz".into(),
            damping: Some("lankarani-nikravesh".into()),
            restitution,
            stiffness: Some(stiffness),
            ..Self::default()
        }
    }

    /// The clr-contact law. `path` names this table in messages (e.g. `clearance[0].normal`),
    /// `radii` is the journal–bearing geometry of a revolute clearance joint (`None` elsewhere).
    ///
    /// # Errors
    /// [`FieldError`] at the offending field, saying what to change.
    pub fn build(&self, path: &str, radii: Radii) -> Result<NormalLaw, FieldError> {
        let norm = self.law.trim().to_ascii_lowercase().replace('_', "-");
        let Some(law) = NORMAL_LAWS.iter().copied().find(|l| *l == norm) else {
            return Err(FieldError::new(
                format!("{path}.law"),
                match damping_as_law(&self.law) {
                    Some(hint) => format!("unknown normal-force law `{}`: {hint}", self.law),
                    None => format!(
                        "unknown normal-force law `{}`; {}",
                        self.law,
                        suggestion(&self.law, NORMAL_LAWS)
                    ),
                },
            ));
        };
        let c = Ctx { path, law };
        let c_e = self.restitution;
        if !(c_e > 0.0 && c_e <= 1.0) {
            return Err(c.err("restitution", format!("c_e = {c_e} must be in (0, 1]")));
        }
        self.refuse_unused(&c)?;
        let out = match law {
            "preset" => self.preset(&c, radii)?,
            "flores-line" | "area" => {
                let face = GuideFace {
                    slider: c.material("slider_material", self.slider_material)?,
                    guide: c.material("guide_material", self.guide_material)?,
                    edge_radius: c.positive(
                        "edge_radius",
                        self.edge_radius,
                        "`edge_radius` in m",
                    )?,
                    width: c.positive("width", self.width, "the face `width` in m")?,
                    layer_depth: if law == "area" {
                        c.positive("layer_depth", self.layer_depth, "`layer_depth` in m")?
                    } else {
                        1.0
                    },
                };
                if law == "area" {
                    NormalLaw::area(&face, c_e, 0.0)
                } else {
                    NormalLaw::flores_line(&face, c_e)
                }
                .map_err(|e| c.err("law", e.to_string()))?
            }
            _ => {
                let elastic = self.elastic(&c, radii)?;
                let dname = c.req(
                    "damping",
                    self.damping.as_deref(),
                    "the damping factor name (e.g. lankarani-nikravesh, flores, gonthier, none)",
                )?;
                let damping = DampingFactor::from_name(dname).map_err(|_| {
                    c.err(
                        "damping",
                        format!(
                            "unknown damping factor `{dname}`; {}",
                            suggestion(dname, DampingFactor::ALL.iter().map(|d| d.name()))
                        ),
                    )
                })?;
                NormalLaw::new(elastic, damping, c_e)
                    .map_err(|e| c.err("restitution", e.to_string()))?
            }
        };
        match self.min_impact_velocity {
            Some(m) => out
                .with_min_impact_velocity(m)
                .map_err(|e| c.err("min_impact_velocity", e.to_string())),
            None => Ok(out),
        }
    }

    fn refuse_unused(&self, c: &Ctx) -> Result<(), FieldError> {
        let given = [
            ("damping", self.damping.is_some()),
            ("stiffness", self.stiffness.is_some()),
            ("exponent", self.exponent.is_some()),
            ("length", self.length.is_some()),
            ("bearing_material", self.bearing_material.is_some()),
            ("journal_material", self.journal_material.is_some()),
            ("preset", self.preset.is_some()),
            ("slider_material", self.slider_material.is_some()),
            ("guide_material", self.guide_material.is_some()),
            ("edge_radius", self.edge_radius.is_some()),
            ("width", self.width.is_some()),
            ("layer_depth", self.layer_depth.is_some()),
        ];
        let used: &[&str] = match c.law {
            "hertz" | "linear" => &["damping", "stiffness"],
            "power" => &["damping", "stiffness", "exponent"],
            "hertz-internal-cylinder" => &["damping", "bearing_material", "journal_material"],
            "bai-zhao" => &["damping", "bearing_material", "journal_material"],
            "liu" | "johnson" | "pereira" => {
                &["damping", "bearing_material", "journal_material", "length"]
            }
            "preset" if self.preset_uses_length() => {
                &["preset", "bearing_material", "journal_material", "length"]
            }
            "preset" => &["preset", "bearing_material", "journal_material"],
            "flores-line" => &["slider_material", "guide_material", "edge_radius", "width"],
            _ => &[
                "slider_material",
                "guide_material",
                "edge_radius",
                "width",
                "layer_depth",
            ],
        };
        c.refuse(&given, used)
    }

    /// Whether the law takes the axial `length` L (liu, johnson, pereira, presets with length).
    pub fn takes_length(&self) -> bool {
        let norm = self.law.trim().to_ascii_lowercase().replace('_', "-");
        matches!(norm.as_str(), "liu" | "johnson" | "pereira")
            || (norm == "preset" && self.preset_uses_length())
    }

    /// `law = "preset"` with a label whose elastic part takes the axial length.
    fn preset_uses_length(&self) -> bool {
        self.preset
            .as_deref()
            .is_some_and(clr_contact::normal::preset_uses_length)
    }

    fn radii(&self, c: &Ctx, radii: Radii) -> Result<(f64, f64), FieldError> {
        radii.ok_or_else(|| {
            c.err(
                "law",
                format!(
                    "the `{}` law needs a journal and a bearing; a translational clearance or a \
                     slider takes `hertz`, `power`, `linear`, `flores-line` or `area`",
                    c.law
                ),
            )
        })
    }

    fn preset(&self, c: &Ctx, radii: Radii) -> Result<NormalLaw, FieldError> {
        let (rb, rj) = self.radii(c, radii)?;
        let label = c.req(
            "preset",
            self.preset.as_deref(),
            "the preset label (Hertz, LN, Gonthier, Bai, Wang, Modified)",
        )?;
        if !clr_contact::normal::FLAP_PRESETS
            .iter()
            .any(|p| p.eq_ignore_ascii_case(label))
        {
            return Err(c.err(
                "preset",
                format!(
                    "unknown preset `{label}`; {}",
                    suggestion(label, clr_contact::normal::FLAP_PRESETS)
                ),
            ));
        }
        let length = if self.preset_uses_length() {
            c.positive("length", self.length, "the axial length L in m")?
        } else {
            // the Hertz-type presets have no L (a length given for them is refused above)
            1.0
        };
        let jb = JournalBearing {
            bearing: c.material("bearing_material", self.bearing_material)?,
            journal: c.material("journal_material", self.journal_material)?,
            r_bearing: rb,
            r_journal: rj,
            length,
        };
        NormalLaw::preset(label, &jb, self.restitution).map_err(|e| c.err("preset", e.to_string()))
    }

    fn elastic(&self, c: &Ctx, radii: Radii) -> Result<ElasticLaw, FieldError> {
        let stiff = || c.positive("stiffness", self.stiffness, "the stiffness K in N/m^n");
        let length = || c.positive("length", self.length, "the axial length L in m");
        let mats = || -> Result<(Material, Material), FieldError> {
            Ok((
                c.material("bearing_material", self.bearing_material)?,
                c.material("journal_material", self.journal_material)?,
            ))
        };
        let e_star = || -> Result<f64, FieldError> {
            let (b, j) = mats()?;
            b.try_composite_modulus(&j)
                .map_err(|e| c.err("bearing_material", e.to_string()))
        };
        let r = match c.law {
            "hertz" => ElasticLaw::hertz(stiff()?),
            "linear" => ElasticLaw::linear(stiff()?),
            "power" => ElasticLaw::power(
                stiff()?,
                c.positive("exponent", self.exponent, "the exponent n")?,
            ),
            _ => {
                let (rb, rj) = self.radii(c, radii)?;
                match c.law {
                    "hertz-internal-cylinder" => {
                        let (b, j) = mats()?;
                        ElasticLaw::hertz_internal_cylinder(&b, rb, &j, rj)
                    }
                    "liu" => ElasticLaw::liu(e_star()?, rb - rj, length()?),
                    "bai-zhao" => ElasticLaw::bai_zhao(e_star()?, rb - rj),
                    "johnson" => ElasticLaw::johnson(e_star()?, rb - rj, length()?),
                    _ => ElasticLaw::pereira_internal(e_star()?, rb - rj, length()?),
                }
            }
        };
        r.map_err(|e| c.err("law", e.to_string()))
    }
}

/// A friction law by name with its parameters (absent in a file: frictionless).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionLawDesc {
    /// `none`, `coulomb`, `ambrosio`, `ambrosio-smooth`, `threlfall`, `stribeck`, `lugre`
    /// (dynamic: one bristle state per contact point, revolute and translational clearance
    /// joints only; see the `lugre` fields below).
    pub law: String,
    /// Friction coefficient μ.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mu: Option<f64>,
    /// Regularization velocity (coulomb, default 1e-4), m/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub v_reg: Option<f64>,
    /// Lower velocity v0 (ambrosio, threlfall), m/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub v0: Option<f64>,
    /// Upper velocity v1 (ambrosio), m/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub v1: Option<f64>,
    /// Static coefficient μ_s (stribeck, lugre), –.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mu_s: Option<f64>,
    /// Dynamic coefficient (stribeck).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mu_d: Option<f64>,
    /// Stiction velocity (stribeck), Stribeck velocity v_s of g(v) (lugre), m/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub v_s: Option<f64>,
    /// Dynamic velocity (stribeck), m/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub v_d: Option<f64>,
    /// Bristle stiffness σ₀ (lugre, > 0), 1/m: friction coefficient per metre of bristle
    /// deflection z, so the pre-sliding stiffness of a contact is σ₀·F_N (N/m). Typically
    /// 1e4–1e6 /m (z of a few µm at the breakaway force).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma0: Option<f64>,
    /// Bristle damping σ₁ (lugre, ≥ 0), s/m: the damping of the pre-sliding spring is σ₁·F_N
    /// (N·s/m). σ₁ż also adds up to σ₁|v_T|·F_N at the start of a slide, before z builds up:
    /// keep σ₁|v_T| small against μ_c at the model's sliding speeds.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma1: Option<f64>,
    /// Viscous coefficient σ₂ (lugre, ≥ 0, default 0), s/m: adds σ₂·v_T to the coefficient.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma2: Option<f64>,
    /// Coulomb (sliding) coefficient μ_c of g(v) (lugre, > 0), –.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mu_c: Option<f64>,
}

/// A friction law as a contact element uses it: stateless, or LuGre with one bristle state per
/// contact point that the model integrates (see [`Model`](crate::Model)'s state layout).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactFriction {
    /// A stateless law F_T = μ(v_T)·F_N.
    Static(FrictionLaw),
    /// The LuGre law (clr-contact [`LuGre`]).
    LuGre(LuGre),
}

/// Friction-law names accepted in `law`.
pub const FRICTION_LAWS: [&str; 7] = [
    "none",
    "coulomb",
    "ambrosio",
    "ambrosio-smooth",
    "threlfall",
    "stribeck",
    "lugre",
];

impl FrictionLawDesc {
    /// No friction.
    pub fn none() -> Self {
        Self {
            law: "none".into(),
            ..Self::default()
        }
    }

    /// The LuGre law (Canudas de Wit, Olsson, Åström & Lischinsky, IEEE Trans. Autom. Control
    /// 40 (1995) 419–425) in clr-contact's friction-coefficient form μ = σ₀z + σ₁ż + σ₂v_T,
    /// ż = v_T − σ₀|v_T|z/g(v_T), g(v) = μ_c + (μ_s − μ_c)e^{−(v/v_s)²}, F_T = −μF_N: bristle
    /// stiffness σ₀ (1/m), bristle damping σ₁ (s/m), viscous coefficient σ₂ (s/m), static μ_s
    /// and Coulomb μ_c coefficients (–), Stribeck velocity v_s (m/s). Revolute and
    /// translational clearance joints only.
    pub fn lugre(sigma0: f64, sigma1: f64, sigma2: f64, mu_s: f64, mu_c: f64, v_s: f64) -> Self {
        Self {
            law: "lugre".into(),
            sigma0: Some(sigma0),
            sigma1: Some(sigma1),
            sigma2: Some(sigma2),
            mu_s: Some(mu_s),
            mu_c: Some(mu_c),
            v_s: Some(v_s),
            ..Self::default()
        }
    }

    /// The clr-contact stateless law; `path` names this table in messages. A contact element
    /// that can carry bristle states uses [`build_contact`](Self::build_contact) instead.
    ///
    /// # Errors
    /// [`FieldError`] at the offending field; for `lugre` at `law` (it needs a state per
    /// contact point that the caller does not provide).
    pub fn build(&self, path: &str) -> Result<FrictionLaw, FieldError> {
        match self.build_contact(path)? {
            ContactFriction::Static(l) => Ok(l),
            ContactFriction::LuGre(_) => Err(lugre_refused(path)),
        }
    }

    /// The law of a contact element that can integrate LuGre bristle states (revolute and
    /// translational clearance joints); `path` names this table in messages.
    ///
    /// # Errors
    /// [`FieldError`] at the offending field.
    pub fn build_contact(&self, path: &str) -> Result<ContactFriction, FieldError> {
        let norm = self.law.trim().to_ascii_lowercase().replace('_', "-");
        let Some(law) = FRICTION_LAWS.iter().copied().find(|l| *l == norm) else {
            return Err(FieldError::new(
                format!("{path}.law"),
                format!(
                    "unknown friction law `{}`; {}",
                    self.law,
                    suggestion(&self.law, FRICTION_LAWS)
                ),
            ));
        };
        let c = Ctx { path, law };
        let given = [
            ("mu", self.mu.is_some()),
            ("v_reg", self.v_reg.is_some()),
            ("v0", self.v0.is_some()),
            ("v1", self.v1.is_some()),
            ("mu_s", self.mu_s.is_some()),
            ("mu_d", self.mu_d.is_some()),
            ("v_s", self.v_s.is_some()),
            ("v_d", self.v_d.is_some()),
            ("sigma0", self.sigma0.is_some()),
            ("sigma1", self.sigma1.is_some()),
            ("sigma2", self.sigma2.is_some()),
            ("mu_c", self.mu_c.is_some()),
        ];
        let used: &[&str] = match law {
            "none" => &[],
            "coulomb" => &["mu", "v_reg"],
            "ambrosio" | "ambrosio-smooth" => &["mu", "v0", "v1"],
            "threlfall" => &["mu", "v0"],
            "lugre" => &["sigma0", "sigma1", "sigma2", "mu_s", "mu_c", "v_s"],
            _ => &["mu_s", "mu_d", "v_s", "v_d"],
        };
        c.refuse(&given, used)?;
        if law == "lugre" {
            return self.lugre_law(&c).map(ContactFriction::LuGre);
        }
        let g = |k: &str, x: Option<f64>| c.req(k, x, &format!("`{k}`"));
        let r = match law {
            "none" => FrictionLaw::coulomb(0.0, 1.0),
            "coulomb" => FrictionLaw::coulomb(g("mu", self.mu)?, self.v_reg.unwrap_or(1e-4)),
            "ambrosio" => {
                FrictionLaw::ambrosio(g("mu", self.mu)?, g("v0", self.v0)?, g("v1", self.v1)?)
            }
            "ambrosio-smooth" => FrictionLaw::ambrosio_smooth(
                g("mu", self.mu)?,
                g("v0", self.v0)?,
                g("v1", self.v1)?,
            ),
            "threlfall" => FrictionLaw::threlfall(g("mu", self.mu)?, g("v0", self.v0)?),
            _ => FrictionLaw::stribeck(
                g("mu_s", self.mu_s)?,
                g("mu_d", self.mu_d)?,
                g("v_s", self.v_s)?,
                g("v_d", self.v_d)?,
            ),
        };
        r.map(ContactFriction::Static)
            .map_err(|e| FieldError::new(path.to_string(), e.to_string()))
    }

    /// The LuGre law, each parameter checked at its own field.
    fn lugre_law(&self, c: &Ctx) -> Result<LuGre, FieldError> {
        let sigma0 = c.positive(
            "sigma0",
            self.sigma0,
            "the bristle stiffness `sigma0` in 1/m (e.g. 1e5)",
        )?;
        let sigma1 = c.non_negative(
            "sigma1",
            self.sigma1,
            "the bristle damping `sigma1` in s/m (e.g. 2·sqrt(sigma0·m/F_N) for critical \
             damping of a mass m pressed by F_N)",
        )?;
        let sigma2 = c.non_negative(
            "sigma2",
            Some(self.sigma2.unwrap_or(0.0)),
            "the viscous coefficient `sigma2` in s/m",
        )?;
        let mu_s = c.positive("mu_s", self.mu_s, "the static coefficient `mu_s`")?;
        let mu_c = c.positive("mu_c", self.mu_c, "the Coulomb coefficient `mu_c`")?;
        let v_s = c.positive("v_s", self.v_s, "the Stribeck velocity `v_s` in m/s")?;
        LuGre::new(sigma0, sigma1, sigma2, mu_s, mu_c, v_s)
            .map_err(|e| FieldError::new(c.path.to_string(), e.to_string()))
    }
}

/// The error of a `lugre` law given to a contact element without bristle states.
fn lugre_refused(path: &str) -> FieldError {
    FieldError::new(
        format!("{path}.law"),
        "the `lugre` law carries one bristle state per contact point, which only revolute and \
         translational clearance joints integrate; this contact element (a slider on a flexible \
         guide) takes a stateless law: none, coulomb, ambrosio, ambrosio-smooth, threlfall or \
         stribeck",
    )
}

/// A normal-force law of a contact element: by name with parameters (data, the file form), or
/// a clr-contact law built in Rust (opt-in; cannot be written to a file, and its geometry is
/// not checked against the element's).
// Boxing the named form would make every file-read law an allocation for no gain: a model holds
// a handful of laws, so the size difference does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum NormalSpec {
    /// By name (see [`NormalLawDesc`]).
    Named(NormalLawDesc),
    /// A prebuilt law.
    Built(NormalLaw),
}

/// A friction law of a contact element: by name (data) or prebuilt (opt-in).
#[derive(Debug, Clone, PartialEq)]
pub enum FrictionSpec {
    /// By name (see [`FrictionLawDesc`]).
    Named(FrictionLawDesc),
    /// A prebuilt law.
    Built(FrictionLaw),
    /// A prebuilt LuGre law (revolute and translational clearance joints only).
    LuGre(LuGre),
}

impl From<NormalLawDesc> for NormalSpec {
    fn from(d: NormalLawDesc) -> Self {
        NormalSpec::Named(d)
    }
}
impl From<NormalLaw> for NormalSpec {
    fn from(l: NormalLaw) -> Self {
        NormalSpec::Built(l)
    }
}
impl From<FrictionLawDesc> for FrictionSpec {
    fn from(d: FrictionLawDesc) -> Self {
        FrictionSpec::Named(d)
    }
}
impl From<FrictionLaw> for FrictionSpec {
    fn from(l: FrictionLaw) -> Self {
        FrictionSpec::Built(l)
    }
}
impl From<LuGre> for FrictionSpec {
    fn from(l: LuGre) -> Self {
        FrictionSpec::LuGre(l)
    }
}
impl Default for FrictionSpec {
    fn default() -> Self {
        FrictionSpec::Named(FrictionLawDesc::none())
    }
}

impl NormalSpec {
    /// The clr-contact law (see [`NormalLawDesc::build`]).
    ///
    /// # Errors
    /// [`FieldError`] of a named law.
    pub fn build(&self, path: &str, radii: Radii) -> Result<NormalLaw, FieldError> {
        match self {
            NormalSpec::Named(d) => d.build(path, radii),
            NormalSpec::Built(l) => Ok(*l),
        }
    }
}

impl FrictionSpec {
    /// The clr-contact law (see [`FrictionLawDesc::build`]).
    ///
    /// # Errors
    /// [`FieldError`] of a named law.
    pub fn build(&self, path: &str) -> Result<FrictionLaw, FieldError> {
        match self {
            FrictionSpec::Named(d) => d.build(path),
            FrictionSpec::Built(l) => Ok(*l),
            FrictionSpec::LuGre(_) => Err(lugre_refused(path)),
        }
    }

    /// The law of a contact element that integrates LuGre bristle states (see
    /// [`FrictionLawDesc::build_contact`]).
    ///
    /// # Errors
    /// [`FieldError`] of a named law.
    pub fn build_contact(&self, path: &str) -> Result<ContactFriction, FieldError> {
        match self {
            FrictionSpec::Named(d) => d.build_contact(path),
            FrictionSpec::Built(l) => Ok(ContactFriction::Static(*l)),
            FrictionSpec::LuGre(l) => Ok(ContactFriction::LuGre(*l)),
        }
    }
}

const BUILT: &str = "a contact law built in Rust cannot be written to a model file; give it by \
                     name (NormalLawDesc / FrictionLawDesc)";

impl Serialize for NormalSpec {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            NormalSpec::Named(d) => d.serialize(s),
            NormalSpec::Built(_) => Err(serde::ser::Error::custom(BUILT)),
        }
    }
}
impl<'de> Deserialize<'de> for NormalSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        NormalLawDesc::deserialize(d).map(NormalSpec::Named)
    }
}
impl Serialize for FrictionSpec {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            FrictionSpec::Named(d) => d.serialize(s),
            FrictionSpec::Built(_) | FrictionSpec::LuGre(_) => {
                Err(serde::ser::Error::custom(BUILT))
            }
        }
    }
}
impl<'de> Deserialize<'de> for FrictionSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        FrictionLawDesc::deserialize(d).map(FrictionSpec::Named)
    }
}
