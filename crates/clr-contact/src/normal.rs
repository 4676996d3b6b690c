//! Normal-force laws: an elastic part combined with a damping factor.
//!
//! F_N = F_e(δ)·(1 + χ δ̇/δ̇⁻), clamped at F_N ≥ 0 and zero for δ ≤ 0 (contact-laws.md §1.2,
//! §1.6), with δ the penetration (m), δ̇ the penetration rate (m/s, > 0 approaching) and δ̇⁻ the
//! penetration rate at the onset of the current contact (m/s), floored at
//! [`NormalLaw::min_impact_velocity`] for resting contact.
//!
//! Named presets reproduce the laws of the papers (see [`NormalLaw::preset`],
//! [`NormalLaw::flores_line`], [`NormalLaw::area`]).

use crate::damping::DampingFactor;
use crate::elastic::{ElasticLaw, Material};
use crate::error::positive;
use crate::error::ContactError;
use crate::restitution::{check_restitution, effective_restitution_unchecked};

/// A dissipative normal-force law F_N = F_e(δ)(1 + χδ̇/δ̇⁻), validated at construction.
///
/// Cheap to copy; [`force`](Self::force) allocates nothing and has no dynamic dispatch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalLaw {
    elastic: ElasticLaw,
    damping: DampingFactor,
    c_e: f64,
    chi: f64,
    min_impact_velocity: f64,
}

/// Geometry and materials of a journal (pin) in a bearing (hole), for the revolute-joint presets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JournalBearing {
    /// Bearing (hole) material.
    pub bearing: Material,
    /// Journal (pin) material.
    pub journal: Material,
    /// Bearing radius R_i (m).
    pub r_bearing: f64,
    /// Journal radius R_j (m), < R_i.
    pub r_journal: f64,
    /// Axial length L (m).
    pub length: f64,
}

impl JournalBearing {
    /// The journal–bearing impact test of the flap paper (Wan et al., Machines 10 (2022) 1098):
    /// steel (207 GPa, 0.3), R_i = 10 mm, R_j = 9.9 mm, L = 15 mm.
    pub fn flap_paper_test() -> Self {
        Self {
            bearing: Material::steel(),
            journal: Material::steel(),
            r_bearing: 10e-3,
            r_journal: 9.9e-3,
            length: 15e-3,
        }
    }

    /// Radial clearance ΔR = R_i − R_j (m).
    pub fn clearance(&self) -> f64 {
        self.r_bearing - self.r_journal
    }

    fn checked(&self) -> Result<(f64, f64), ContactError> {
        const LAW: &str = "journal–bearing";
        let e_star = self.bearing.try_composite_modulus(&self.journal)?;
        positive(LAW, "journal radius R_j (m)", self.r_journal)?;
        positive(LAW, "bearing radius R_i (m)", self.r_bearing)?;
        positive(LAW, "axial length L (m)", self.length)?;
        let c = positive(LAW, "clearance R_i − R_j (m)", self.clearance())?;
        Ok((e_star, c))
    }
}

/// A slider face on a guide, for the sliding-guide presets ([`NormalLaw::flores_line`],
/// [`NormalLaw::area`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuideFace {
    /// Slider material.
    pub slider: Material,
    /// Guide material.
    pub guide: Material,
    /// Rounding radius ρ of the slider edge (corner) that touches the guide in line contact (m).
    pub edge_radius: f64,
    /// Width w of the slider face, out of the plane (m).
    pub width: f64,
    /// Effective depth h of the elastic layer of the Winkler foundation (m).
    pub layer_depth: f64,
}

/// The flap paper's labels accepted by [`NormalLaw::preset`].
pub const FLAP_PRESETS: [&str; 6] = ["Hertz", "LN", "Gonthier", "Bai", "Wang", "Modified"];

/// True for the presets whose elastic part depends on the axial length L (`Wang` and
/// `Modified`, the Liu conformal-cylinder law); the others ignore [`JournalBearing::length`].
pub fn preset_uses_length(name: &str) -> bool {
    matches!(
        name.trim().to_ascii_lowercase().as_str(),
        "wang" | "modified"
    )
}

impl NormalLaw {
    /// Default floor of δ̇⁻ (m/s): below it the impact velocity is replaced by this value, so a
    /// contact that starts at rest (δ̇⁻ → 0) keeps a finite damping (contact-laws.md §1.6).
    pub const DEFAULT_MIN_IMPACT_VELOCITY: f64 = 1e-4;

    /// Combine an elastic part with a damping factor for the input coefficient of restitution
    /// c_e ∈ (0, 1]. χ is computed once here.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for c_e outside (0, 1].
    pub fn new(
        elastic: ElasticLaw,
        damping: DampingFactor,
        c_e: f64,
    ) -> Result<Self, ContactError> {
        check_restitution("normal law", c_e)?;
        Ok(Self {
            elastic,
            damping,
            c_e,
            chi: damping.chi(c_e)?,
            min_impact_velocity: Self::DEFAULT_MIN_IMPACT_VELOCITY,
        })
    }

    /// The same law with another floor for δ̇⁻ (m/s).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for a floor ≤ 0 or non-finite.
    pub fn with_min_impact_velocity(mut self, v: f64) -> Result<Self, ContactError> {
        self.min_impact_velocity = positive("normal law", "minimum impact velocity (m/s)", v)?;
        Ok(self)
    }

    /// The same law with the contact length l (m) of an area law set (see
    /// [`ElasticLaw::area`]); other laws are unchanged.
    #[inline]
    pub fn with_contact_length(mut self, length: f64) -> Self {
        self.elastic = self.elastic.with_contact_length(length);
        self
    }

    /// Normal force F_N (N) for the penetration δ (m), its rate δ̇ (m/s, > 0 approaching) and
    /// the rate at contact onset δ̇⁻ (m/s, floored at the minimum impact velocity):
    /// F_N = max(0, F_e(δ)(1 + χδ̇/δ̇⁻)); 0 for δ ≤ 0 or NaN.
    #[inline]
    pub fn force(&self, delta: f64, delta_dot: f64, delta_dot_minus: f64) -> f64 {
        let fe = self.elastic.force(delta);
        if fe == 0.0 {
            return 0.0;
        }
        let v0 = delta_dot_minus.max(self.min_impact_velocity);
        let f = fe * (1.0 + self.chi * delta_dot / v0);
        // Clamp at 0 (also maps a NaN rate to 0) and keep the result finite.
        if f > 0.0 {
            f.min(f64::MAX)
        } else {
            0.0
        }
    }

    /// Elastic energy ∫₀^δ F_e(s) ds stored at the penetration δ (m), J: exact for power laws
    /// K δ^{n+1}/(n+1), 16-point Gauss–Legendre quadrature otherwise (Abramowitz & Stegun,
    /// Table 25.4); 0 for δ ≤ 0 or not finite.
    pub fn elastic_energy(&self, delta: f64) -> f64 {
        if delta <= 0.0 || !delta.is_finite() {
            return 0.0;
        }
        if let Some((k, e)) = self.elastic().power_parameters() {
            return k * delta.powf(e + 1.0) / (e + 1.0);
        }
        const X: [f64; 8] = [
            0.095_012_509_837_637_44,
            0.281_603_550_779_258_9,
            0.458_016_777_657_227_4,
            0.617_876_244_402_643_8,
            0.755_404_408_355_003,
            0.865_631_202_387_831_7,
            0.944_575_023_073_232_6,
            0.989_400_934_991_649_9,
        ];
        const W: [f64; 8] = [
            0.189_450_610_455_068_5,
            0.182_603_415_044_923_6,
            0.169_156_519_395_002_5,
            0.149_595_988_816_576_7,
            0.124_628_971_255_533_9,
            0.095_158_511_682_492_8,
            0.062_253_523_938_647_9,
            0.027_152_459_411_754_1,
        ];
        let h = 0.5 * delta;
        let mut s = 0.0;
        for (x, w) in X.iter().zip(W.iter()) {
            s += w * (self.elastic_force(h * (1.0 - x)) + self.elastic_force(h * (1.0 + x)));
        }
        s * h
    }

    /// [`force`](Self::force) with its partial derivatives, for Jacobians of implicit
    /// integrators: (F_N (N), ∂F_N/∂δ (N/m), ∂F_N/∂δ̇ (N·s/m)), with δ̇⁻ held fixed (it is
    /// contact state, not a function of the current state). Where the clamp F_N = 0 is active the
    /// derivatives are 0. ∂F_N/∂δ = F_e'(δ)(1 + χδ̇/δ̇⁻), ∂F_N/∂δ̇ = F_e(δ)χ/δ̇⁻, with
    /// F_e' = [`ElasticLaw::stiffness`] (contact-laws.md §1.2: the Hunt–Crossley form).
    ///
    /// Non-smooth points: δ = 0 (contact onset, see [`ElasticLaw::stiffness`]), the clamp
    /// 1 + χδ̇/δ̇⁻ = 0, i.e. δ̇ = −δ̇⁻/χ (a kink: the derivatives jump to 0 there), the non-smooth
    /// points of the elastic part (Johnson's δ*), and the floor of δ̇⁻ (a kink in δ̇⁻, which is
    /// held fixed here).
    #[inline]
    pub fn force_with_derivatives(
        &self,
        delta: f64,
        delta_dot: f64,
        delta_dot_minus: f64,
    ) -> (f64, f64, f64) {
        let fe = self.elastic.force(delta);
        if fe == 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let v0 = delta_dot_minus.max(self.min_impact_velocity);
        let factor = 1.0 + self.chi * delta_dot / v0;
        let f = fe * factor;
        if f > 0.0 {
            (
                f.min(f64::MAX),
                self.elastic.stiffness(delta) * factor,
                fe * self.chi / v0,
            )
        } else {
            (0.0, 0.0, 0.0)
        }
    }

    /// Sensitivity ∂F_N/∂l (N/m) of [`force`](Self::force) to the contact length l (m) of an
    /// area law ([`ElasticLaw::area`], [`NormalLaw::area`]), for Jacobians in which l depends on
    /// the state: ∂F_N/∂l = (∂F_e/∂l)(1 + χδ̇/δ̇⁻) with
    /// [`ElasticLaw::contact_length_derivative`]. 0 where the clamp F_N = 0 is active and for
    /// laws without a contact length.
    #[inline]
    pub fn contact_length_derivative(
        &self,
        delta: f64,
        delta_dot: f64,
        delta_dot_minus: f64,
    ) -> f64 {
        let dl = self.elastic.contact_length_derivative(delta);
        if dl == 0.0 || self.force(delta, delta_dot, delta_dot_minus) == 0.0 {
            return 0.0;
        }
        let v0 = delta_dot_minus.max(self.min_impact_velocity);
        dl * (1.0 + self.chi * delta_dot / v0)
    }

    /// Elastic part F_e(δ) (N).
    #[inline]
    pub fn elastic_force(&self, delta: f64) -> f64 {
        self.elastic.force(delta)
    }

    /// Damping factor χ (–).
    pub fn chi(&self) -> f64 {
        self.chi
    }

    /// Input coefficient of restitution c_e (–).
    pub fn c_e(&self) -> f64 {
        self.c_e
    }

    /// The damping factor.
    pub fn damping(&self) -> DampingFactor {
        self.damping
    }

    /// The elastic part.
    pub fn elastic(&self) -> &ElasticLaw {
        &self.elastic
    }

    /// Floor of δ̇⁻ (m/s).
    pub fn min_impact_velocity(&self) -> f64 {
        self.min_impact_velocity
    }

    /// Restitution this law produces in a free impact (exact, contact-laws.md §1.3): depends on
    /// χ only, not on the elastic part, the mass or the impact velocity (provided δ̇⁻ is above
    /// the floor).
    pub fn effective_restitution(&self) -> f64 {
        effective_restitution_unchecked(self.chi)
    }

    /// The flap paper's laws (Wan et al., Machines 10 (2022) 1098, restitution table) for a
    /// journal in a bearing, by label (case-insensitive):
    ///
    /// | label | elastic part | damping | status |
    /// |---|---|---|---|
    /// | `Hertz` | Hertz internal cylinder | none | as published |
    /// | `LN` | Hertz internal cylinder | Lankarani–Nikravesh | as published |
    /// | `Gonthier` | Hertz internal cylinder | Gonthier | as published |
    /// | `Bai` | Bai–Zhao K_n (SI only) | Zhiying–Qishao | reconstruction |
    /// | `Wang` | Liu conformal cylinder with L | Zhiying–Qishao | reconstruction |
    /// | `Modified` | Liu conformal cylinder with L | Gonthier | reconstruction |
    ///
    /// The reconstructions follow from the paper's measured restitution (paper-systems.md §1.1):
    /// with c_e = 0.5 the Zhiying–Qishao factor gives 0.4826 ("0.482") and the Gonthier factor
    /// 0.4877 ("0.488").
    ///
    /// # Errors
    /// [`ContactError::UnknownName`] (listing the valid labels), or invalid geometry or c_e.
    pub fn preset(name: &str, jb: &JournalBearing, c_e: f64) -> Result<Self, ContactError> {
        let (e_star, c) = jb.checked()?;
        let hertz = || {
            ElasticLaw::hertz_internal_cylinder(
                &jb.bearing,
                jb.r_bearing,
                &jb.journal,
                jb.r_journal,
            )
        };
        let liu = || ElasticLaw::liu(e_star, c, jb.length);
        let (elastic, damping) = match name.trim().to_ascii_lowercase().as_str() {
            "hertz" => (hertz()?, DampingFactor::None),
            "ln" | "l-n" | "lankarani-nikravesh" => (hertz()?, DampingFactor::LankaraniNikravesh),
            "gonthier" => (hertz()?, DampingFactor::Gonthier),
            "bai" => (
                ElasticLaw::bai_zhao(e_star, c)?,
                DampingFactor::ZhiyingQishao,
            ),
            "wang" => (liu()?, DampingFactor::ZhiyingQishao),
            "modified" => (liu()?, DampingFactor::Gonthier),
            _ => {
                return Err(ContactError::UnknownName {
                    kind: "normal-law preset",
                    name: name.to_string(),
                    valid: FLAP_PRESETS.join(", "),
                })
            }
        };
        Self::new(elastic, damping, c_e)
    }

    /// The sliding-guide paper's "Flores" line law for a slider edge on a guide: Hertz
    /// sphere-on-plane stiffness K = (4/3)E*√ρ of the rounded edge (radius ρ) with the Flores
    /// et al. (2011) damping χ = 8(1 − c_e)/(5c_e).
    ///
    /// Why this elastic part: in the planar translational clearance joint of Flores, Ambrósio,
    /// Claro & Lankarani (J. Comput. Nonlinear Dyn. 3 (2008) 011007) each slider corner is a point
    /// contact with a Hertz-type K δ^{3/2} law; the Hertz point law of the rounded corner is the
    /// physical K for that usage and is the same power law on which the area law builds
    /// ([`NormalLaw::area`] tends to it as the contact length goes to 0).
    ///
    /// # Errors
    /// Invalid materials, radius or c_e.
    pub fn flores_line(face: &GuideFace, c_e: f64) -> Result<Self, ContactError> {
        let line = ElasticLaw::hertz_sphere_plane(&face.slider, face.edge_radius, &face.guide)?;
        Self::new(line, DampingFactor::Flores, c_e)
    }

    /// The sliding-guide paper's restitution-corrected variable-stiffness area law — a
    /// **reconstruction** (no primary source located, contact-laws.md §1.5):
    /// F_N = [K_l δ^{3/2} + (E*/h)·w·l·δ]·(1 + χ δ̇/δ̇⁻) with the edge law of
    /// [`flores_line`](Self::flores_line), the Winkler term of [`ElasticLaw::area`] and χ from
    /// [`DampingFactor::Exact`], so the restitution is exactly c_e while the contact length l
    /// stays fixed. l starts at `contact_length` and is updated with
    /// [`with_contact_length`](Self::with_contact_length).
    ///
    /// # Errors
    /// Invalid materials, dimensions or c_e.
    pub fn area(face: &GuideFace, c_e: f64, contact_length: f64) -> Result<Self, ContactError> {
        let line = ElasticLaw::hertz_sphere_plane(&face.slider, face.edge_radius, &face.guide)?;
        let e_star = face.slider.composite_modulus(&face.guide);
        let area = ElasticLaw::area(line, e_star, face.width, face.layer_depth)?
            .with_contact_length(contact_length);
        Self::new(area, DampingFactor::Exact, c_e)
    }
}
