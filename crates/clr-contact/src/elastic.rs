//! Elastic parts F_e(δ) of the normal-force laws.
//!
//! Each law maps the penetration δ (m) to an elastic force (N), is zero for δ ≤ 0, and is
//! built from physical data with the conventions of contact-laws.md §0: compliance
//! σ_k = (1 − ν_k²)/E_k and composite modulus E* = 1/(σ_i + σ_j) (no π in σ). A law is combined
//! with a damping factor in [`crate::normal::NormalLaw`].
//!
//! | constructor | formula | source |
//! |---|---|---|
//! | [`ElasticLaw::hertz_sphere_sphere`], [`hertz_sphere_plane`](ElasticLaw::hertz_sphere_plane), [`hertz_internal_cylinder`](ElasticLaw::hertz_internal_cylinder) | K δ^{3/2}, K = (4/3)E*√R* | Hertz; Lankarani & Nikravesh (1990); Flores et al. (2004) |
//! | [`ElasticLaw::liu`] | (π/2)E* L δ √(δ/(2(ΔR+δ))) | Liu, Zhang, Yang, Mech. Mach. Theory 42 (2007) 183 |
//! | [`ElasticLaw::bai_zhao`] | K_n(δ) δ^{3/2} (SI numbers) | Bai & Zhao, Int. J. Mech. Sci. 54 (2012) 190 |
//! | [`ElasticLaw::pereira_internal`], [`pereira_external`](ElasticLaw::pereira_external) | [(aΔR+b)/ΔR] L E* δ^n (mm, MPa) | Pereira, Ramalho, Ambrósio, Nonlinear Dyn. 63 (2011) 681 |
//! | [`ElasticLaw::johnson`] | δ = F/(πLE*)[ln(4πLE*ΔR/F) − 1] | Johnson, Contact Mechanics (1985) |
//! | [`ElasticLaw::linear`] | k δ | Kelvin–Voigt spring |
//! | [`ElasticLaw::area`] | K_l δ^{n_l} + (E*/h) w l δ | reconstruction (this crate) |

use crate::error::{positive, ContactError};
use crate::restitution::bracketed_newton;

/// An isotropic linear-elastic material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus E (Pa), > 0.
    pub youngs_modulus: f64,
    /// Poisson's ratio ν (–), in (−1, 0.5).
    pub poisson_ratio: f64,
}

impl Material {
    /// A validated material.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for E ≤ 0 or non-finite, or ν outside (−1, 0.5).
    pub fn new(youngs_modulus: f64, poisson_ratio: f64) -> Result<Self, ContactError> {
        let m = Self {
            youngs_modulus,
            poisson_ratio,
        };
        m.validate()?;
        Ok(m)
    }

    /// Structural steel of the contact-laws.md tests: E = 207 GPa, ν = 0.3.
    pub fn steel() -> Self {
        Self {
            youngs_modulus: 207e9,
            poisson_ratio: 0.3,
        }
    }

    fn validate(&self) -> Result<(), ContactError> {
        positive("material", "Young's modulus E (Pa)", self.youngs_modulus)?;
        let nu = self.poisson_ratio;
        if !(nu > -1.0 && nu < 0.5) {
            return Err(ContactError::invalid(
                "material",
                "Poisson ratio ν (-)",
                nu,
                "must be in (−1, 0.5)",
            ));
        }
        Ok(())
    }

    /// Compliance parameter σ = (1 − ν²)/E (1/Pa), without π (contact-laws.md §0).
    pub fn compliance(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus
    }

    /// Composite modulus E* = 1/(σ_self + σ_other) (Pa). For two steels (207 GPa, 0.3):
    /// 1.137363e11 Pa.
    pub fn composite_modulus(&self, other: &Material) -> f64 {
        1.0 / (self.compliance() + other.compliance())
    }

    /// [`composite_modulus`](Self::composite_modulus) after validating both materials.
    ///
    /// # Errors
    /// As [`Material::new`].
    pub fn try_composite_modulus(&self, other: &Material) -> Result<f64, ContactError> {
        self.validate()?;
        other.validate()?;
        Ok(self.composite_modulus(other))
    }
}

/// Fitted constants of Pereira, Ramalho & Ambrósio (2011) for a given clearance, in the units
/// of the fit (mm, MPa, N).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PereiraFit {
    /// Exponent parameter Y (internal contact only; NaN for external contact).
    pub y: f64,
    /// Exponent n of δ.
    pub exponent: f64,
    /// Generalized stiffness K = [(aΔR + b)/ΔR]·L·E* in N/mm^n.
    pub k_mm: f64,
}

impl PereiraFit {
    /// Smallest radial clearance of the internal fit (m): 0.005 mm.
    pub const MIN_CLEARANCE: f64 = 0.005e-3;
    /// Largest radial clearance of the internal fit (m): 10 mm.
    pub const MAX_CLEARANCE: f64 = 10e-3;

    /// Internal (journal in bearing) fit: a = 0.965, b = 0.0965, n = Y·ΔR^{−0.005} with
    /// Y = 1.51[ln(1000ΔR)]^{−0.151} for 0.005 ≤ ΔR ≤ 0.34954 mm and Y = 0.0151ΔR + 1.151 for
    /// 0.34954 < ΔR ≤ 10 mm (ΔR in mm). Inputs in SI (Pa, m).
    ///
    /// # Errors
    /// [`ContactError::OutOfValidity`] for a clearance outside 0.005–10 mm;
    /// [`ContactError::InvalidParameter`] for non-positive E* or L.
    pub fn internal(e_star: f64, clearance: f64, length: f64) -> Result<Self, ContactError> {
        const LAW: &str = "Pereira internal cylinder";
        positive(LAW, "composite modulus E* (Pa)", e_star)?;
        positive(LAW, "axial length L (m)", length)?;
        if !(Self::MIN_CLEARANCE..=Self::MAX_CLEARANCE).contains(&clearance) {
            return Err(ContactError::OutOfValidity {
                law: LAW,
                quantity: "radial clearance ΔR (m)",
                value: clearance,
                range: "[5e-6, 1e-2] m (0.005–10 mm, the range of the FE fit)".into(),
                advice: "use the Johnson or Liu cylinder law outside this range",
            });
        }
        let dr = clearance * 1e3;
        let y = if dr <= 0.34954 {
            1.51 * (1000.0 * dr).ln().powf(-0.151)
        } else {
            0.0151 * dr + 1.151
        };
        let exponent = y * dr.powf(-0.005);
        let k_mm = (0.965 * dr + 0.0965) / dr * (length * 1e3) * (e_star * 1e-6);
        Ok(Self { y, exponent, k_mm })
    }

    /// External (two convex cylinders) fit with ΔR := R_1 + R_2: a = 0.39, b = 0.85, n = 1.094.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for non-positive E*, radii or L.
    pub fn external(e_star: f64, r1: f64, r2: f64, length: f64) -> Result<Self, ContactError> {
        const LAW: &str = "Pereira external cylinder";
        positive(LAW, "composite modulus E* (Pa)", e_star)?;
        positive(LAW, "radius R_1 (m)", r1)?;
        positive(LAW, "radius R_2 (m)", r2)?;
        positive(LAW, "axial length L (m)", length)?;
        let dr = (r1 + r2) * 1e3;
        let k_mm = (0.39 * dr + 0.85) / dr * (length * 1e3) * (e_star * 1e-6);
        Ok(Self {
            y: f64::NAN,
            exponent: 1.094,
            k_mm,
        })
    }

    /// The same law in SI: K_SI = K_mm·1000^n in N/m^n, so that F = K_SI δ^n with δ in m.
    pub fn k_si(&self) -> f64 {
        self.k_mm * 1000f64.powf(self.exponent)
    }
}

/// Bai–Zhao nonlinear stiffness K_n = (π/8)E*√[2δ(3ΔR + 2δ)²/(ΔR + δ)³] (Pa), "as published,
/// SI only" (Bai & Zhao, Int. J. Mech. Sci. 54 (2012) 190–205). It equals (1/L)·dF_Liu/dδ, the
/// tangent stiffness per unit length of Liu's law (contact-laws.md §1.4), so K_n δ^{3/2} is not
/// dimensionally a force: the published model uses it with numbers in m and Pa. Zero for δ ≤ 0.
pub fn bai_zhao_stiffness(e_star: f64, clearance: f64, delta: f64) -> f64 {
    if delta.is_nan() || delta <= 0.0 {
        return 0.0;
    }
    let a = 3.0 * clearance + 2.0 * delta;
    let b = clearance + delta;
    std::f64::consts::PI / 8.0 * e_star * (2.0 * delta * a * a / (b * b * b)).sqrt()
}

/// Johnson's implicit cylinder law, penetration for a force F (N):
/// δ = (F/(πLE*))·[ln(4πLE*ΔR/F) − 1] (m) (K.L. Johnson, Contact Mechanics, 1985; Pereira et al.
/// 2011). Monotonic only for F < [`johnson_force_limit`]. Zero for F ≤ 0.
pub fn johnson_penetration(e_star: f64, clearance: f64, length: f64, force: f64) -> f64 {
    if force.is_nan() || force <= 0.0 {
        return 0.0;
    }
    let a = std::f64::consts::PI * length * e_star;
    force / a * ((4.0 * a * clearance / force).ln() - 1.0)
}

/// Validity limit of Johnson's law, F* = 4πLE*ΔR/e² (N), where dδ/dF = 0; the matching
/// penetration is δ* = F*/(πLE*) = 4ΔR/e² ≈ 0.541ΔR.
pub fn johnson_force_limit(e_star: f64, clearance: f64, length: f64) -> f64 {
    4.0 * std::f64::consts::PI * length * e_star * clearance / std::f64::consts::E.powi(2)
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// K δ^n.
    Power { k: f64, n: f64, label: &'static str },
    /// Liu conformal cylinder.
    Liu {
        e_star: f64,
        clearance: f64,
        length: f64,
    },
    /// Bai–Zhao K_n δ^{3/2}.
    BaiZhao { e_star: f64, clearance: f64 },
    /// Johnson implicit line contact.
    Johnson {
        /// πLE* (N/m).
        a: f64,
        /// F* (N).
        f_limit: f64,
        /// δ* (m).
        delta_limit: f64,
    },
    /// Edge law plus Winkler foundation over the contact length.
    Area {
        k_line: f64,
        n_line: f64,
        /// Foundation stiffness per unit width and length, E*/h (Pa/m), times the width w (m).
        k_per_length: f64,
        contact_length: f64,
    },
}

/// The elastic part F_e(δ) of a normal-force law (N for δ in m), validated at construction.
///
/// Cheap to copy; evaluation allocates nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticLaw {
    kind: Kind,
}

impl ElasticLaw {
    /// General power law F_e = K δ^n (K in N/m^n).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for K ≤ 0 or n ≤ 0 (or non-finite).
    pub fn power(k: f64, n: f64) -> Result<Self, ContactError> {
        Self::power_labelled(k, n, "power law K δ^n")
    }

    fn power_labelled(k: f64, n: f64, label: &'static str) -> Result<Self, ContactError> {
        positive(label, "stiffness K (N/m^n)", k)?;
        positive(label, "exponent n (-)", n)?;
        Ok(Self {
            kind: Kind::Power { k, n, label },
        })
    }

    /// Hertz law with a given generalized stiffness: F_e = K δ^{3/2} (K in N/m^{1.5}), as used
    /// when a paper states K directly (e.g. K = 6.8e7 N/m^1.5).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for K ≤ 0.
    pub fn hertz(k: f64) -> Result<Self, ContactError> {
        Self::power_labelled(k, 1.5, "Hertz")
    }

    fn hertz_from_radius(e_star: f64, r_eff: f64) -> Result<Self, ContactError> {
        Self::power_labelled(4.0 / 3.0 * e_star * r_eff.sqrt(), 1.5, "Hertz")
    }

    /// Hertz, two convex spheres: K = (4/3)E*√R*, R* = R_1R_2/(R_1 + R_2) (contact-laws.md §1.1).
    /// Steel, R_1 = R_2 = 10 mm: K = 1.0723158e10 N/m^1.5. Radii in m.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for invalid materials or radii ≤ 0.
    pub fn hertz_sphere_sphere(
        m1: &Material,
        r1: f64,
        m2: &Material,
        r2: f64,
    ) -> Result<Self, ContactError> {
        let e_star = m1.try_composite_modulus(m2)?;
        positive("Hertz sphere–sphere", "radius R_1 (m)", r1)?;
        positive("Hertz sphere–sphere", "radius R_2 (m)", r2)?;
        Self::hertz_from_radius(e_star, r1 * r2 / (r1 + r2))
    }

    /// Hertz, sphere on a plane: K = (4/3)E*√R. Steel, R = 10 mm: K = 1.5164835e10 N/m^1.5.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for invalid materials or R ≤ 0.
    pub fn hertz_sphere_plane(
        sphere: &Material,
        radius: f64,
        plane: &Material,
    ) -> Result<Self, ContactError> {
        let e_star = sphere.try_composite_modulus(plane)?;
        positive("Hertz sphere–plane", "radius R (m)", radius)?;
        Self::hertz_from_radius(e_star, radius)
    }

    /// Hertz, internal contact of a journal (radius R_j) in a bearing (R_i > R_j), the planar
    /// revolute clearance joint of Flores et al. (2004): K = (4/3)E*√(R_iR_j/(R_i − R_j)).
    /// Steel, 10 mm / 9.9 mm: K = 1.50888205e11 N/m^1.5. This is the sphere formula applied to
    /// cylinders (no L, no conformity); prefer [`liu`](Self::liu) for small clearances.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for invalid materials, radii ≤ 0 or R_i ≤ R_j.
    pub fn hertz_internal_cylinder(
        bearing: &Material,
        r_bearing: f64,
        journal: &Material,
        r_journal: f64,
    ) -> Result<Self, ContactError> {
        const LAW: &str = "Hertz internal cylinder";
        let e_star = bearing.try_composite_modulus(journal)?;
        positive(LAW, "bearing radius R_i (m)", r_bearing)?;
        positive(LAW, "journal radius R_j (m)", r_journal)?;
        let c = positive(LAW, "clearance R_i − R_j (m)", r_bearing - r_journal)?;
        Self::hertz_from_radius(e_star, r_bearing * r_journal / c)
    }

    /// Linear spring F_e = k δ (k in N/m), the elastic part of a Kelvin–Voigt contact.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for k ≤ 0.
    pub fn linear(k: f64) -> Result<Self, ContactError> {
        Self::power_labelled(k, 1.0, "linear (Kelvin–Voigt) spring")
    }

    /// Liu's conformal cylinder law (Liu, Zhang, Yang, Mech. Mach. Theory 42 (2007) 183–197):
    /// F_e = (π/2)E* L δ √(δ/(2(ΔR + δ))) — an improved elastic-foundation law, valid for
    /// conformal contact including large contact angles (√(δ/(2(ΔR+δ))) = sin(ε/2), ε the
    /// contact half-angle). E* composite (Pa), ΔR radial clearance (m), L axial length (m).
    /// Status \[L\]; E* is the composite modulus (contact-laws.md §5).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for non-positive inputs.
    pub fn liu(e_star: f64, clearance: f64, length: f64) -> Result<Self, ContactError> {
        const LAW: &str = "Liu conformal cylinder";
        Ok(Self {
            kind: Kind::Liu {
                e_star: positive(LAW, "composite modulus E* (Pa)", e_star)?,
                clearance: positive(LAW, "radial clearance ΔR (m)", clearance)?,
                length: positive(LAW, "axial length L (m)", length)?,
            },
        })
    }

    /// Bai–Zhao hybrid elastic part F_e = K_n(δ)·δ^{3/2} with [`bai_zhao_stiffness`],
    /// **as published, SI only** (numbers in m and Pa; K_n δ^{1.5} is not dimensionally a force,
    /// contact-laws.md §1.4). It does not depend on L.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for non-positive inputs.
    pub fn bai_zhao(e_star: f64, clearance: f64) -> Result<Self, ContactError> {
        const LAW: &str = "Bai–Zhao";
        Ok(Self {
            kind: Kind::BaiZhao {
                e_star: positive(LAW, "composite modulus E* (Pa)", e_star)?,
                clearance: positive(LAW, "radial clearance ΔR (m)", clearance)?,
            },
        })
    }

    /// Pereira–Ramalho–Ambrósio internal cylinder law F_e = K δ^n with the fit of
    /// [`PereiraFit::internal`] converted from (mm, MPa) to SI.
    ///
    /// # Errors
    /// As [`PereiraFit::internal`] (clearance outside 0.005–10 mm is an error).
    pub fn pereira_internal(
        e_star: f64,
        clearance: f64,
        length: f64,
    ) -> Result<Self, ContactError> {
        let fit = PereiraFit::internal(e_star, clearance, length)?;
        Self::power_labelled(fit.k_si(), fit.exponent, "Pereira internal cylinder")
    }

    /// Pereira–Ramalho–Ambrósio external cylinder law (two convex cylinders R_1, R_2) with
    /// [`PereiraFit::external`], in SI.
    ///
    /// # Errors
    /// As [`PereiraFit::external`].
    pub fn pereira_external(
        e_star: f64,
        r1: f64,
        r2: f64,
        length: f64,
    ) -> Result<Self, ContactError> {
        let fit = PereiraFit::external(e_star, r1, r2, length)?;
        Self::power_labelled(fit.k_si(), fit.exponent, "Pereira external cylinder")
    }

    /// Johnson's implicit cylinder law δ = (F/(πLE*))[ln(4πLE*ΔR/F) − 1], solved for F by a
    /// bracketed Newton iteration in the dimensionless form x(1 − ln x) = δ/δ*, x = F/F*
    /// (F* = [`johnson_force_limit`], δ* = 4ΔR/e²). Valid for δ < δ*; see
    /// [`try_force`](Self::try_force). Steel, ΔR = 0.1 mm, L = 15 mm: F(1 µm) = 773.7539 N.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for non-positive inputs.
    pub fn johnson(e_star: f64, clearance: f64, length: f64) -> Result<Self, ContactError> {
        const LAW: &str = "Johnson cylinder";
        positive(LAW, "composite modulus E* (Pa)", e_star)?;
        positive(LAW, "radial clearance ΔR (m)", clearance)?;
        positive(LAW, "axial length L (m)", length)?;
        let a = std::f64::consts::PI * length * e_star;
        let f_limit = johnson_force_limit(e_star, clearance, length);
        Ok(Self {
            kind: Kind::Johnson {
                a,
                f_limit,
                delta_limit: f_limit / a,
            },
        })
    }

    /// Flat area contact with a variable contact length — a **reconstruction** (no primary source
    /// located, contact-laws.md §1.5):
    ///
    /// F_e(δ; l) = K_l δ^{n_l} + k_f·w·l·δ,
    ///
    /// the line (edge) law `line` (a power law K_l δ^{n_l}, e.g. the Hertz corner law) plus an
    /// elastic-foundation (Winkler) term for a slider face of length l (m, along the guide) and
    /// width w (m, out of plane) pressed flat by δ: pressure p = k_f δ with foundation modulus
    /// k_f = E*/h (Pa/m), h being the effective depth of the deformed layer (m). The law tends to
    /// the line law as l → 0 and increases with l; the contact length starts at 0 and is set per
    /// evaluation with [`with_contact_length`](Self::with_contact_length). With multiplicative
    /// damping χ from [`crate::damping::DampingFactor::Exact`] the restitution is exact while l
    /// stays fixed during an impact (contact-laws.md §1.3).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] if `line` is not a power law, or E*, w or h ≤ 0.
    pub fn area(
        line: ElasticLaw,
        e_star: f64,
        width: f64,
        layer_depth: f64,
    ) -> Result<Self, ContactError> {
        const LAW: &str = "area contact";
        let Kind::Power { k, n, .. } = line.kind else {
            return Err(ContactError::invalid(
                LAW,
                "line law",
                f64::NAN,
                "must be a power law K δ^n (Hertz, linear or Pereira)",
            ));
        };
        positive(LAW, "composite modulus E* (Pa)", e_star)?;
        positive(LAW, "face width w (m)", width)?;
        positive(LAW, "layer depth h (m)", layer_depth)?;
        Ok(Self {
            kind: Kind::Area {
                k_line: k,
                n_line: n,
                k_per_length: e_star / layer_depth * width,
                contact_length: 0.0,
            },
        })
    }

    /// The same law with the contact length l (m) of an area law set; other laws are returned
    /// unchanged. Negative or NaN lengths are treated as 0 (pure line contact).
    pub fn with_contact_length(mut self, length: f64) -> Self {
        if let Kind::Area { contact_length, .. } = &mut self.kind {
            *contact_length = if length > 0.0 { length } else { 0.0 };
        }
        self
    }

    /// Contact length l (m) of an area law; `None` for other laws.
    pub fn contact_length(&self) -> Option<f64> {
        match self.kind {
            Kind::Area { contact_length, .. } => Some(contact_length),
            _ => None,
        }
    }

    /// The (K, n) of a power law (Hertz, linear, Pereira), in SI; `None` otherwise.
    pub fn power_parameters(&self) -> Option<(f64, f64)> {
        match self.kind {
            Kind::Power { k, n, .. } => Some((k, n)),
            _ => None,
        }
    }

    /// Human-readable name of the law.
    pub fn name(&self) -> &'static str {
        match self.kind {
            Kind::Power { label, .. } => label,
            Kind::Liu { .. } => "Liu conformal cylinder",
            Kind::BaiZhao { .. } => "Bai–Zhao",
            Kind::Johnson { .. } => "Johnson cylinder",
            Kind::Area { .. } => "area contact",
        }
    }

    /// Elastic force F_e(δ) (N) for the penetration δ (m); 0 for δ ≤ 0 or NaN.
    ///
    /// Johnson's law beyond its validity limit δ* continues linearly with the secant stiffness
    /// πLE* (F = F* + πLE*(δ − δ*)), a non-physical continuation that keeps integrators running;
    /// use [`try_force`](Self::try_force) to detect it.
    #[inline]
    pub fn force(&self, delta: f64) -> f64 {
        if delta.is_nan() || delta <= 0.0 {
            return 0.0;
        }
        match self.kind {
            Kind::Power { k, n, .. } => power(k, n, delta),
            Kind::Liu {
                e_star,
                clearance,
                length,
            } => {
                std::f64::consts::FRAC_PI_2
                    * e_star
                    * length
                    * delta
                    * (delta / (2.0 * (clearance + delta))).sqrt()
            }
            Kind::BaiZhao { e_star, clearance } => {
                bai_zhao_stiffness(e_star, clearance, delta) * delta * delta.sqrt()
            }
            Kind::Johnson {
                a,
                f_limit,
                delta_limit,
            } => {
                if delta >= delta_limit {
                    f_limit + a * (delta - delta_limit)
                } else {
                    f_limit * johnson_fraction(delta / delta_limit)
                }
            }
            Kind::Area {
                k_line,
                n_line,
                k_per_length,
                contact_length,
            } => power(k_line, n_line, delta) + k_per_length * contact_length * delta,
        }
    }

    /// Tangent stiffness dF_e/dδ (N/m) at the penetration δ (m), for Jacobians of implicit
    /// integrators; 0 for δ ≤ 0 or NaN. Closed forms: n K δ^{n−1} (power laws);
    /// L·K_n(δ) for Liu (the Bai–Zhao identity, contact-laws.md §1.4);
    /// K_n δ^{3/2}[(1/δ + 4/(3ΔR+2δ) − 3/(ΔR+δ))/2 + 3/(2δ)] for Bai–Zhao;
    /// πLE*/(−ln x) with x = F/F* for Johnson (πLE* beyond δ*); n_l K_l δ^{n_l−1} + (E*/h)wl
    /// for the area law at fixed contact length l (the sensitivity to l is
    /// [`contact_length_derivative`](Self::contact_length_derivative)).
    ///
    /// Non-smooth points:
    /// - δ = 0 for every law (contact onset): the stiffness jumps from 0 to its limit from above,
    ///   which is 0 for exponents n > 1 (Hertz and Liu ~δ^{1/2}, Pereira ~δ^{n−1}, Bai–Zhao ~δ),
    ///   k for the linear spring and (E*/h)wl from the Winkler term of the area law, +∞ for power
    ///   laws with n < 1, and 0 (logarithmically, πLE*/ln(1/x)) for Johnson;
    /// - δ = δ* = 4ΔR/e² for Johnson: the stiffness of the implicit law diverges as δ → δ*
    ///   from below (dδ/dF = 0 at F*), while the linear continuation beyond δ* has πLE*.
    #[inline]
    pub fn stiffness(&self, delta: f64) -> f64 {
        if delta.is_nan() || delta <= 0.0 {
            return 0.0;
        }
        match self.kind {
            Kind::Power { k, n, .. } => n * power(k, n, delta) / delta,
            Kind::Liu {
                e_star,
                clearance,
                length,
            } => length * bai_zhao_stiffness(e_star, clearance, delta),
            Kind::BaiZhao { e_star, clearance } => {
                let f = bai_zhao_stiffness(e_star, clearance, delta) * delta * delta.sqrt();
                let log_kn = 0.5
                    * (1.0 / delta + 4.0 / (3.0 * clearance + 2.0 * delta)
                        - 3.0 / (clearance + delta));
                f * (log_kn + 1.5 / delta)
            }
            Kind::Johnson { a, delta_limit, .. } => {
                if delta >= delta_limit {
                    a
                } else {
                    a / -johnson_fraction(delta / delta_limit).ln()
                }
            }
            Kind::Area {
                k_line,
                n_line,
                k_per_length,
                contact_length,
            } => n_line * power(k_line, n_line, delta) / delta + k_per_length * contact_length,
        }
    }

    /// Sensitivity ∂F_e/∂l (N/m) of the elastic force to the contact length l (m) of an area law
    /// ([`ElasticLaw::area`]), at the penetration δ (m): the Winkler term gives
    /// ∂F_e/∂l = (E*/h)·w·δ, independent of l. 0 for δ ≤ 0 or NaN and for every other law (they
    /// do not depend on l). Needed in a Jacobian when l is itself a function of the state (e.g.
    /// the wetted length of a multipoint contact). At l = 0, where
    /// [`with_contact_length`](Self::with_contact_length) clamps negative lengths to 0, this is
    /// the derivative from above.
    #[inline]
    pub fn contact_length_derivative(&self, delta: f64) -> f64 {
        if delta.is_nan() || delta <= 0.0 {
            return 0.0;
        }
        match self.kind {
            Kind::Area { k_per_length, .. } => k_per_length * delta,
            _ => 0.0,
        }
    }

    /// [`force`](Self::force) that reports Johnson's validity limit as an error.
    ///
    /// # Errors
    /// [`ContactError::OutOfValidity`] for Johnson's law with δ ≥ δ* = 4ΔR/e².
    pub fn try_force(&self, delta: f64) -> Result<f64, ContactError> {
        if let Kind::Johnson { delta_limit, .. } = self.kind {
            if delta >= delta_limit {
                return Err(ContactError::OutOfValidity {
                    law: "Johnson cylinder",
                    quantity: "penetration δ (m)",
                    value: delta,
                    range: format!("[0, {delta_limit:e}) m (δ* = 4ΔR/e², where dδ/dF = 0)"),
                    advice: "use the Liu conformal law for deep conformal contact",
                });
            }
        }
        Ok(self.force(delta))
    }
}

/// K δ^n, with the common Hertz exponent 3/2 evaluated as δ√δ.
#[inline]
fn power(k: f64, n: f64, delta: f64) -> f64 {
    if n == 1.5 {
        k * delta * delta.sqrt()
    } else {
        k * delta.powf(n)
    }
}

/// Solve x(1 − ln x) = r for x ∈ (0, 1], r ∈ (0, 1): Johnson's law in dimensionless form.
/// In y = ln x the residual q(y) = y + ln(1 − y) − ln r is concave and increasing on y ≤ 0.
/// Upper bound: x ≤ r/(1 − ln r) (there p(x) ≥ r); the lower bound is found by doubling the
/// distance until q < 0 (q → −∞ as y → −∞).
fn johnson_fraction(r: f64) -> f64 {
    let lr = r.ln();
    let q = |y: f64| (y + (-y).ln_1p() - lr, -y / (1.0 - y));
    let hi = (lr - (-lr).ln_1p()).min(0.0);
    let mut lo = hi - 1.0;
    for _ in 0..64 {
        if q(lo).0 < 0.0 {
            break;
        }
        lo = 2.0 * lo - 1.0;
    }
    match bracketed_newton(q, lo, hi, 1e-15, 200) {
        Some(y) => y.exp(),
        // Not reached for r in (0, 1); the bound x ≤ r keeps the result finite and physical.
        None => r,
    }
}
