//! Hysteresis damping factors χ(c_e) of the Hunt–Crossley family.
//!
//! Every dissipative normal law of this crate has the form F = F_e(δ)(1 + χ δ̇/δ̇⁻)
//! (contact-laws.md §1.2): the damping factor only chooses the dimensionless χ from the input
//! coefficient of restitution c_e ∈ (0, 1]. Because the restitution a multiplicative law actually
//! produces depends on χ only (§1.3), [`DampingFactor::effective_restitution`] is exact for every
//! elastic part.
//!
//! Status tags (contact-laws.md): \[V\] verified in an independent implementation or by derivation,
//! \[L\] as commonly quoted (primary paper not read), \[?\] not verified.

use crate::error::ContactError;
use crate::restitution::{
    check_restitution, chi_exact, effective_restitution_unchecked as e_of_chi,
};

/// A damping factor χ(c_e) for multiplicative laws F = F_e(δ)(1 + χ δ̇/δ̇⁻).
///
/// χ values at c_e = 0.5 are given for orientation (contact-laws.md §1.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DampingFactor {
    /// No damping, χ = 0: the purely elastic Hertz law (e_eff = 1 whatever c_e).
    None,
    /// Hunt & Crossley, J. Appl. Mech. 42 (1975) 440–445: χ = 3(1 − c_e)/2 (0.75). \[V\]
    /// Intended for c_e → 1.
    HuntCrossley,
    /// Lankarani & Nikravesh, J. Mech. Des. 112 (1990) 369–376: χ = 3(1 − c_e²)/4 (0.5625). \[V\]
    /// Derived for c_e ≈ 1; accurate for c_e ≳ 0.8 only (e_eff = 0.7252 at c_e = 0.5).
    LankaraniNikravesh,
    /// Flores, Machado, Silva, Martins, Multibody Syst. Dyn. 25 (2011) 357–375:
    /// χ = 8(1 − c_e)/(5c_e) (1.6). \[V\] Claimed valid over the whole range, aimed at soft
    /// materials.
    Flores,
    /// Gonthier, McPhee, Lange, Piedbœuf, Multibody Syst. Dyn. 11 (2004) 209–233:
    /// χ = (1 − c_e²)/c_e (1.5). \[L\] Whole range.
    Gonthier,
    /// Zhiying & Qishao, J. Dyn. Control 4 (2006) 294–298: χ = 3(1 − c_e²)e^{2(1−c_e)}/4
    /// (1.5290). \[L\] Whole range.
    ZhiyingQishao,
    /// Hu & Guo, Multibody Syst. Dyn. 35 (2015) 131–151: χ = 3(1 − c_e)/(2c_e) (1.5). \[L\]
    /// (one public code has half this value; the reviews and a two-phase energy balance give
    /// this one, contact-laws.md §1.2).
    HuGuo,
    /// Gharib & Hurmuzlu, J. Appl. Mech. 79 (2012) 064506: χ = (1 − c_e)/c_e (1.0). \[?\]
    /// Recalled from review tables, not verified against the paper. Low c_e.
    GharibHurmuzlu,
    /// Herbert & McWhannell, J. Eng. Ind. 99 (1977) 513–518: χ = 6(1 − c_e)/[(2c_e − 1)² + 3]
    /// (1.0). \[L\] Intended for c_e → 1.
    HerbertMcWhannell,
    /// Lee & Wang, J. Mech. Transm. Autom. Des. 105 (1983) 534–540: χ = 3(1 − c_e)/4 (0.375).
    /// \[L\] Intended for c_e → 1.
    LeeWang,
    /// "HC-exact": χ solved from (1 + c_e)χ = ln[(1 + χ)/(1 − χc_e)] (contact-laws.md §1.3), so
    /// that the law produces exactly c_e with any elastic part (1.432751). \[V\]
    Exact,
}

impl DampingFactor {
    /// Every damping factor, in the order of the docs table.
    pub const ALL: [DampingFactor; 11] = [
        DampingFactor::None,
        DampingFactor::HuntCrossley,
        DampingFactor::LankaraniNikravesh,
        DampingFactor::Flores,
        DampingFactor::Gonthier,
        DampingFactor::ZhiyingQishao,
        DampingFactor::HuGuo,
        DampingFactor::GharibHurmuzlu,
        DampingFactor::HerbertMcWhannell,
        DampingFactor::LeeWang,
        DampingFactor::Exact,
    ];

    /// Short name used in files and the CLI (`"lankarani-nikravesh"`, …).
    pub fn name(&self) -> &'static str {
        match self {
            DampingFactor::None => "none",
            DampingFactor::HuntCrossley => "hunt-crossley",
            DampingFactor::LankaraniNikravesh => "lankarani-nikravesh",
            DampingFactor::Flores => "flores",
            DampingFactor::Gonthier => "gonthier",
            DampingFactor::ZhiyingQishao => "zhiying-qishao",
            DampingFactor::HuGuo => "hu-guo",
            DampingFactor::GharibHurmuzlu => "gharib-hurmuzlu",
            DampingFactor::HerbertMcWhannell => "herbert-mcwhannell",
            DampingFactor::LeeWang => "lee-wang",
            DampingFactor::Exact => "exact",
        }
    }

    /// The formula of χ(c_e), as text for docs and reports.
    pub fn formula(&self) -> &'static str {
        match self {
            DampingFactor::None => "0",
            DampingFactor::HuntCrossley => "3(1−c_e)/2",
            DampingFactor::LankaraniNikravesh => "3(1−c_e²)/4",
            DampingFactor::Flores => "8(1−c_e)/(5c_e)",
            DampingFactor::Gonthier => "(1−c_e²)/c_e",
            DampingFactor::ZhiyingQishao => "3(1−c_e²)e^{2(1−c_e)}/4",
            DampingFactor::HuGuo => "3(1−c_e)/(2c_e)",
            DampingFactor::GharibHurmuzlu => "(1−c_e)/c_e",
            DampingFactor::HerbertMcWhannell => "6(1−c_e)/((2c_e−1)²+3)",
            DampingFactor::LeeWang => "3(1−c_e)/4",
            DampingFactor::Exact => "root of (1+c_e)χ = ln((1+χ)/(1−χc_e))",
        }
    }

    /// Status tag of contact-laws.md: `"\[V\]"`, `"\[L\]"` or `"\[?\]"`.
    pub fn status(&self) -> &'static str {
        match self {
            DampingFactor::None
            | DampingFactor::HuntCrossley
            | DampingFactor::LankaraniNikravesh
            | DampingFactor::Flores
            | DampingFactor::Exact => "[V]",
            DampingFactor::GharibHurmuzlu => "[?]",
            _ => "[L]",
        }
    }

    /// Look a damping factor up by its [`name`](Self::name) (case-insensitive; `_` and spaces
    /// count as `-`; `"ln"` and `"hc-exact"` are accepted aliases).
    ///
    /// # Errors
    /// [`ContactError::UnknownName`] listing the valid names.
    pub fn from_name(name: &str) -> Result<Self, ContactError> {
        let key = name.trim().to_ascii_lowercase().replace(['_', ' '], "-");
        let alias = match key.as_str() {
            "ln" | "l-n" => Some(DampingFactor::LankaraniNikravesh),
            "hc-exact" => Some(DampingFactor::Exact),
            "hertz" => Some(DampingFactor::None),
            _ => None,
        };
        alias
            .or_else(|| Self::ALL.into_iter().find(|d| d.name() == key))
            .ok_or_else(|| ContactError::UnknownName {
                kind: "damping factor",
                name: name.to_string(),
                valid: Self::ALL.map(|d| d.name()).join(", "),
            })
    }

    /// The damping factor χ (dimensionless) for the input coefficient of restitution c_e.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] if c_e is not in (0, 1] (the 1/c_e laws diverge at 0).
    pub fn chi(&self, c_e: f64) -> Result<f64, ContactError> {
        check_restitution(self.name(), c_e)?;
        let c = c_e;
        Ok(match self {
            DampingFactor::None => 0.0,
            DampingFactor::HuntCrossley => 1.5 * (1.0 - c),
            DampingFactor::LankaraniNikravesh => 0.75 * (1.0 - c * c),
            DampingFactor::Flores => 8.0 * (1.0 - c) / (5.0 * c),
            DampingFactor::Gonthier => (1.0 - c * c) / c,
            DampingFactor::ZhiyingQishao => 0.75 * (1.0 - c * c) * (2.0 * (1.0 - c)).exp(),
            DampingFactor::HuGuo => 3.0 * (1.0 - c) / (2.0 * c),
            DampingFactor::GharibHurmuzlu => (1.0 - c) / c,
            DampingFactor::HerbertMcWhannell => {
                6.0 * (1.0 - c) / ((2.0 * c - 1.0) * (2.0 * c - 1.0) + 3.0)
            }
            DampingFactor::LeeWang => 0.75 * (1.0 - c),
            DampingFactor::Exact => chi_exact(c)?,
        })
    }

    /// Restitution e_eff that a multiplicative law with this factor actually produces in a free
    /// impact for input c_e, from the exact relation of contact-laws.md §1.3 (independent of the
    /// elastic part, the mass and the impact velocity). Equals c_e for [`DampingFactor::Exact`].
    ///
    /// # Errors
    /// As [`chi`](Self::chi).
    pub fn effective_restitution(&self, c_e: f64) -> Result<f64, ContactError> {
        Ok(e_of_chi(self.chi(c_e)?))
    }
}
