//! Laws built from a kind (numeric code or name) and a flat parameter list, in SI units.
//!
//! This is the safe Rust layer under the C functions, shared with the Python package
//! (`python/`), so both bindings accept exactly the same kinds, names and parameter orders:
//!
//! | elastic kind | code | name | parameters |
//! |---|---|---|---|
//! | Hertz, given K | 0 | `hertz` | K (N/m^1.5) |
//! | power law K δ^n | 1 | `power` | K (N/m^n), n (–) |
//! | linear spring | 2 | `linear` | k (N/m) |
//! | Hertz sphere–sphere | 3 | `hertz-sphere-sphere` | E₁ (Pa), ν₁, R₁ (m), E₂ (Pa), ν₂, R₂ (m) |
//! | Hertz sphere–plane | 4 | `hertz-sphere-plane` | E_s (Pa), ν_s, R (m), E_p (Pa), ν_p |
//! | Hertz internal cylinder | 5 | `hertz-internal-cylinder` | E_i (Pa), ν_i, R_i (m), E_j (Pa), ν_j, R_j (m) |
//! | Liu conformal cylinder | 6 | `liu` | E* (Pa), ΔR (m), L (m) |
//! | Bai–Zhao (SI numbers) | 7 | `bai-zhao` | E* (Pa), ΔR (m) |
//! | Pereira internal | 8 | `pereira-internal` | E* (Pa), ΔR (m), L (m) |
//! | Pereira external | 9 | `pereira-external` | E* (Pa), R₁ (m), R₂ (m), L (m) |
//! | Johnson cylinder | 10 | `johnson` | E* (Pa), ΔR (m), L (m) |
//!
//! | friction kind | code | name | parameters |
//! |---|---|---|---|
//! | regularized Coulomb | 0 | `coulomb` | μ, v_reg (m/s) |
//! | Ambrósio | 1 | `ambrosio` | μ, v₀ (m/s), v₁ (m/s) |
//! | Threlfall | 2 | `threlfall` | μ, v₀ (m/s) |
//! | Bai/Stribeck (ADAMS STEP) | 3 | `stribeck` | μ_s, μ_d, v_s (m/s), v_d (m/s) |
//!
//! Damping factors are numbered in the order of [`DampingFactor::ALL`] and named by
//! [`DampingFactor::name`]. The formulas and their sources are documented in `clr-contact`
//! ([`clr_contact::elastic`], [`clr_contact::damping`], [`clr_contact::friction`]).

use clr_contact::elastic::Material;
use clr_contact::{DampingFactor, ElasticLaw, FrictionLaw};

use crate::error::CapiError;

/// A kind of law selected by a C code (its index in [`ALL`](Kind::ALL)) or a name, with a fixed
/// list of parameters.
pub trait Kind: Copy + PartialEq + 'static {
    /// What the kind selects, for messages.
    const WHAT: &'static str;
    /// Every kind, indexed by its C code.
    const ALL: &'static [Self];

    /// Name used by the Python package.
    fn name(self) -> &'static str;

    /// Names and units of the parameters, in order.
    fn parameters(self) -> &'static [&'static str];

    /// The kind with the C code `code`.
    ///
    /// # Errors
    /// [`CapiError::UnknownCode`] for a code without a kind.
    fn from_code(code: u32) -> Result<Self, CapiError> {
        usize::try_from(code)
            .ok()
            .and_then(|i| Self::ALL.get(i).copied())
            .ok_or(CapiError::UnknownCode {
                what: Self::WHAT,
                code,
                max: Self::ALL.len() - 1,
            })
    }

    /// The kind named `name` (case-insensitive, `_` and spaces count as `-`).
    ///
    /// # Errors
    /// [`CapiError::UnknownName`] listing the valid names.
    fn from_name(name: &str) -> Result<Self, CapiError> {
        let key = name.trim().to_ascii_lowercase().replace(['_', ' '], "-");
        Self::ALL
            .iter()
            .copied()
            .find(|k| k.name() == key)
            .ok_or_else(|| CapiError::UnknownName {
                what: Self::WHAT,
                name: name.to_string(),
                valid: Self::ALL
                    .iter()
                    .map(|k| k.name())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// Check the number of parameters.
    ///
    /// # Errors
    /// [`CapiError::ParameterCount`] naming the expected parameters.
    fn check_count(self, p: &[f64]) -> Result<(), CapiError> {
        let names = self.parameters();
        if p.len() == names.len() {
            Ok(())
        } else {
            Err(CapiError::ParameterCount {
                law: self.name(),
                expected: names.len(),
                names: names.join(", "),
                got: p.len(),
            })
        }
    }
}

/// The elastic parts that can be built from a parameter list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElasticKind {
    /// Hertz F = K δ^{3/2} with a given K.
    Hertz,
    /// General power law K δ^n.
    Power,
    /// Linear (Kelvin–Voigt) spring k δ.
    Linear,
    /// Hertz, two convex spheres, from materials and radii.
    HertzSphereSphere,
    /// Hertz, sphere on a plane.
    HertzSpherePlane,
    /// Hertz, journal in a bearing (the planar revolute clearance joint).
    HertzInternalCylinder,
    /// Liu, Zhang & Yang (2007) conformal cylinder.
    Liu,
    /// Bai & Zhao (2012) hybrid stiffness, SI numbers only.
    BaiZhao,
    /// Pereira, Ramalho & Ambrósio (2011), internal contact.
    PereiraInternal,
    /// Pereira, Ramalho & Ambrósio (2011), external contact.
    PereiraExternal,
    /// Johnson's implicit line contact.
    Johnson,
}

impl Kind for ElasticKind {
    const WHAT: &'static str = "elastic kind";
    const ALL: &'static [Self] = &[
        ElasticKind::Hertz,
        ElasticKind::Power,
        ElasticKind::Linear,
        ElasticKind::HertzSphereSphere,
        ElasticKind::HertzSpherePlane,
        ElasticKind::HertzInternalCylinder,
        ElasticKind::Liu,
        ElasticKind::BaiZhao,
        ElasticKind::PereiraInternal,
        ElasticKind::PereiraExternal,
        ElasticKind::Johnson,
    ];

    fn name(self) -> &'static str {
        match self {
            ElasticKind::Hertz => "hertz",
            ElasticKind::Power => "power",
            ElasticKind::Linear => "linear",
            ElasticKind::HertzSphereSphere => "hertz-sphere-sphere",
            ElasticKind::HertzSpherePlane => "hertz-sphere-plane",
            ElasticKind::HertzInternalCylinder => "hertz-internal-cylinder",
            ElasticKind::Liu => "liu",
            ElasticKind::BaiZhao => "bai-zhao",
            ElasticKind::PereiraInternal => "pereira-internal",
            ElasticKind::PereiraExternal => "pereira-external",
            ElasticKind::Johnson => "johnson",
        }
    }

    fn parameters(self) -> &'static [&'static str] {
        match self {
            ElasticKind::Hertz => &["K (N/m^1.5)"],
            ElasticKind::Power => &["K (N/m^n)", "n (-)"],
            ElasticKind::Linear => &["k (N/m)"],
            ElasticKind::HertzSphereSphere => &[
                "E1 (Pa)", "nu1 (-)", "R1 (m)", "E2 (Pa)", "nu2 (-)", "R2 (m)",
            ],
            ElasticKind::HertzSpherePlane => &[
                "E_sphere (Pa)",
                "nu_sphere (-)",
                "R (m)",
                "E_plane (Pa)",
                "nu_plane (-)",
            ],
            ElasticKind::HertzInternalCylinder => &[
                "E_bearing (Pa)",
                "nu_bearing (-)",
                "R_bearing (m)",
                "E_journal (Pa)",
                "nu_journal (-)",
                "R_journal (m)",
            ],
            ElasticKind::Liu | ElasticKind::PereiraInternal | ElasticKind::Johnson => {
                &["E* (Pa)", "clearance (m)", "length (m)"]
            }
            ElasticKind::BaiZhao => &["E* (Pa)", "clearance (m)"],
            ElasticKind::PereiraExternal => &["E* (Pa)", "R1 (m)", "R2 (m)", "length (m)"],
        }
    }
}

impl ElasticKind {
    /// Build the elastic part from its parameters (SI, in the order of [`parameters`](Self::parameters)).
    ///
    /// # Errors
    /// [`CapiError::ParameterCount`] for a wrong number of parameters, or the validation error of
    /// the law.
    pub fn build(self, p: &[f64]) -> Result<ElasticLaw, CapiError> {
        self.check_count(p)?;
        Ok(match self {
            ElasticKind::Hertz => ElasticLaw::hertz(p[0])?,
            ElasticKind::Power => ElasticLaw::power(p[0], p[1])?,
            ElasticKind::Linear => ElasticLaw::linear(p[0])?,
            ElasticKind::HertzSphereSphere => ElasticLaw::hertz_sphere_sphere(
                &Material::new(p[0], p[1])?,
                p[2],
                &Material::new(p[3], p[4])?,
                p[5],
            )?,
            ElasticKind::HertzSpherePlane => ElasticLaw::hertz_sphere_plane(
                &Material::new(p[0], p[1])?,
                p[2],
                &Material::new(p[3], p[4])?,
            )?,
            ElasticKind::HertzInternalCylinder => ElasticLaw::hertz_internal_cylinder(
                &Material::new(p[0], p[1])?,
                p[2],
                &Material::new(p[3], p[4])?,
                p[5],
            )?,
            ElasticKind::Liu => ElasticLaw::liu(p[0], p[1], p[2])?,
            ElasticKind::BaiZhao => ElasticLaw::bai_zhao(p[0], p[1])?,
            ElasticKind::PereiraInternal => ElasticLaw::pereira_internal(p[0], p[1], p[2])?,
            ElasticKind::PereiraExternal => ElasticLaw::pereira_external(p[0], p[1], p[2], p[3])?,
            ElasticKind::Johnson => ElasticLaw::johnson(p[0], p[1], p[2])?,
        })
    }
}

/// The stateless friction laws that can be built from a parameter list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrictionKind {
    /// Coulomb, regularized linearly below v_reg.
    Coulomb,
    /// Ambrósio's modified Coulomb law.
    Ambrosio,
    /// Threlfall's exponential law.
    Threlfall,
    /// Bai & Zhao / ADAMS-STEP Stribeck-type law.
    Stribeck,
}

impl Kind for FrictionKind {
    const WHAT: &'static str = "friction kind";
    const ALL: &'static [Self] = &[
        FrictionKind::Coulomb,
        FrictionKind::Ambrosio,
        FrictionKind::Threlfall,
        FrictionKind::Stribeck,
    ];

    fn name(self) -> &'static str {
        match self {
            FrictionKind::Coulomb => "coulomb",
            FrictionKind::Ambrosio => "ambrosio",
            FrictionKind::Threlfall => "threlfall",
            FrictionKind::Stribeck => "stribeck",
        }
    }

    fn parameters(self) -> &'static [&'static str] {
        match self {
            FrictionKind::Coulomb => &["mu (-)", "v_reg (m/s)"],
            FrictionKind::Ambrosio => &["mu (-)", "v0 (m/s)", "v1 (m/s)"],
            FrictionKind::Threlfall => &["mu (-)", "v0 (m/s)"],
            FrictionKind::Stribeck => &["mu_s (-)", "mu_d (-)", "v_s (m/s)", "v_d (m/s)"],
        }
    }
}

impl FrictionKind {
    /// Build the friction law from its parameters (in the order of [`parameters`](Self::parameters)).
    ///
    /// # Errors
    /// [`CapiError::ParameterCount`] for a wrong number of parameters, or the validation error of
    /// the law.
    pub fn build(self, p: &[f64]) -> Result<FrictionLaw, CapiError> {
        self.check_count(p)?;
        Ok(match self {
            FrictionKind::Coulomb => FrictionLaw::coulomb(p[0], p[1])?,
            FrictionKind::Ambrosio => FrictionLaw::ambrosio(p[0], p[1], p[2])?,
            FrictionKind::Threlfall => FrictionLaw::threlfall(p[0], p[1])?,
            FrictionKind::Stribeck => FrictionLaw::stribeck(p[0], p[1], p[2], p[3])?,
        })
    }
}

/// The damping factor with the C code `code` (the index in [`DampingFactor::ALL`]).
///
/// # Errors
/// [`CapiError::UnknownCode`] for a code without a factor.
pub fn damping_from_code(code: u32) -> Result<DampingFactor, CapiError> {
    usize::try_from(code)
        .ok()
        .and_then(|i| DampingFactor::ALL.get(i).copied())
        .ok_or(CapiError::UnknownCode {
            what: "damping factor",
            code,
            max: DampingFactor::ALL.len() - 1,
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_and_names_round_trip() {
        for (i, &k) in ElasticKind::ALL.iter().enumerate() {
            assert_eq!(ElasticKind::from_code(i as u32).unwrap(), k);
            assert_eq!(ElasticKind::from_name(k.name()).unwrap(), k);
        }
        for (i, &k) in FrictionKind::ALL.iter().enumerate() {
            assert_eq!(FrictionKind::from_code(i as u32).unwrap(), k);
            assert_eq!(
                FrictionKind::from_name(&k.name().to_uppercase()).unwrap(),
                k
            );
        }
        assert!(ElasticKind::from_code(11).is_err());
        assert!(FrictionKind::from_code(u32::MAX).is_err());
        assert!(damping_from_code(11).is_err());
        assert!(ElasticKind::from_name("hertz_internal cylinder").is_ok());
    }

    #[test]
    fn wrong_parameter_count_names_the_parameters() {
        let e = ElasticKind::Liu.build(&[1.0, 2.0]).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("clearance (m)") && msg.contains("got 2"),
            "{msg}"
        );
    }
}
