//! Materials and cross sections.
//!
//! Section formulas are the standard ones for the second moment of area about the axis normal to
//! the plane of bending (e.g. Roark's Formulas for Stress and Strain, 8th ed., Table A.1).

use crate::error::{positive, BeamError};

/// Linear elastic isotropic material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Density ρ (kg/m³).
    pub density: f64,
    /// Poisson's ratio ν (–); not used by Euler–Bernoulli elements, kept for contact laws.
    pub poisson_ratio: f64,
}

impl Material {
    /// A material from E (Pa), ρ (kg/m³) and ν (–). Errors when E or ρ are not positive or
    /// ν is outside (−1, 0.5).
    pub fn new(youngs_modulus: f64, density: f64, poisson_ratio: f64) -> Result<Self, BeamError> {
        positive("Young's modulus E", youngs_modulus)?;
        positive("density ρ", density)?;
        if !(poisson_ratio > -1.0 && poisson_ratio < 0.5) {
            return Err(BeamError::PoissonRatio(poisson_ratio));
        }
        Ok(Self {
            youngs_modulus,
            density,
            poisson_ratio,
        })
    }

    /// Structural steel: E = 207 GPa, ρ = 7800 kg/m³, ν = 0.3.
    pub fn steel() -> Self {
        Self {
            youngs_modulus: 207e9,
            density: 7800.0,
            poisson_ratio: 0.3,
        }
    }

    /// Aluminium alloy: E = 70 GPa, ρ = 2700 kg/m³, ν = 0.33.
    pub fn aluminium() -> Self {
        Self {
            youngs_modulus: 70e9,
            density: 2700.0,
            poisson_ratio: 0.33,
        }
    }
}

/// Cross section of a planar beam: area, second moment of area about the axis normal to the
/// plane of motion, and depth (extent in the bending plane, used for surface queries).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Area A (m²).
    pub area: f64,
    /// Second moment of area I (m⁴) for in-plane bending.
    pub second_moment: f64,
    /// Depth h (m): distance between the two faces in the bending plane.
    pub depth: f64,
}

impl Section {
    /// A section from its area A (m²), second moment I (m⁴) and depth h (m).
    pub fn new(area: f64, second_moment: f64, depth: f64) -> Result<Self, BeamError> {
        positive("section area A", area)?;
        positive("second moment of area I", second_moment)?;
        positive("section depth h", depth)?;
        Ok(Self {
            area,
            second_moment,
            depth,
        })
    }

    /// Solid rectangle of width b (m, out of plane) and depth h (m, in the bending plane):
    /// A = b h, I = b h³/12.
    pub fn rectangular(width: f64, depth: f64) -> Result<Self, BeamError> {
        positive("section width b", width)?;
        positive("section depth h", depth)?;
        Self::new(width * depth, width * depth.powi(3) / 12.0, depth)
    }

    /// Solid circle of diameter d (m): A = π d²/4, I = π d⁴/64.
    pub fn circular(diameter: f64) -> Result<Self, BeamError> {
        positive("section diameter d", diameter)?;
        let pi = std::f64::consts::PI;
        Self::new(
            pi * diameter.powi(2) / 4.0,
            pi * diameter.powi(4) / 64.0,
            diameter,
        )
    }

    /// Circular tube of outer diameter d (m) and wall thickness t (m), 0 < t ≤ d/2:
    /// A = π(d² − dᵢ²)/4, I = π(d⁴ − dᵢ⁴)/64 with dᵢ = d − 2t.
    pub fn tube(outer_diameter: f64, wall: f64) -> Result<Self, BeamError> {
        positive("tube outer diameter d", outer_diameter)?;
        positive("tube wall thickness t", wall)?;
        if 2.0 * wall > outer_diameter {
            return Err(BeamError::SectionGeometry(format!(
                "tube wall {wall} m is thicker than half the outer diameter {outer_diameter} m; \
                 use t ≤ d/2"
            )));
        }
        let pi = std::f64::consts::PI;
        let di = outer_diameter - 2.0 * wall;
        Self::new(
            pi * (outer_diameter.powi(2) - di.powi(2)) / 4.0,
            pi * (outer_diameter.powi(4) - di.powi(4)) / 64.0,
            outer_diameter,
        )
    }

    /// Symmetric I section bent about its strong axis: flange width b, total depth h, flange
    /// thickness t_f, web thickness t_w (all m). A = 2 b t_f + (h − 2 t_f) t_w,
    /// I = (b h³ − (b − t_w)(h − 2 t_f)³)/12.
    pub fn i_section(
        flange_width: f64,
        depth: f64,
        flange_thickness: f64,
        web_thickness: f64,
    ) -> Result<Self, BeamError> {
        positive("flange width b", flange_width)?;
        positive("section depth h", depth)?;
        positive("flange thickness t_f", flange_thickness)?;
        positive("web thickness t_w", web_thickness)?;
        if 2.0 * flange_thickness >= depth || web_thickness > flange_width {
            return Err(BeamError::SectionGeometry(format!(
                "I section needs 2 t_f < h and t_w ≤ b (got t_f = {flange_thickness}, h = {depth}, \
                 t_w = {web_thickness}, b = {flange_width})"
            )));
        }
        let hw = depth - 2.0 * flange_thickness;
        Self::new(
            2.0 * flange_width * flange_thickness + hw * web_thickness,
            (flange_width * depth.powi(3) - (flange_width - web_thickness) * hw.powi(3)) / 12.0,
            depth,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn sections_against_hand_values() {
        // Rectangle 20 mm × 10 mm: A = 2e-4 m², I = 0.02·0.01³/12 = 1.6667e-9 m⁴.
        let r = Section::rectangular(0.02, 0.01).unwrap();
        assert_relative_eq!(r.area, 2e-4, max_relative = 1e-14);
        assert_relative_eq!(r.second_moment, 0.02 * 1e-6 / 12.0, max_relative = 1e-14);
        // A tube with t = d/2 is a solid circle.
        let t = Section::tube(0.03, 0.015).unwrap();
        let c = Section::circular(0.03).unwrap();
        assert_relative_eq!(t.area, c.area, max_relative = 1e-14);
        assert_relative_eq!(t.second_moment, c.second_moment, max_relative = 1e-14);
        // An I section with t_w = b is a solid rectangle b × h.
        let i = Section::i_section(0.05, 0.1, 0.01, 0.05).unwrap();
        let r = Section::rectangular(0.05, 0.1).unwrap();
        assert_relative_eq!(i.area, r.area, max_relative = 1e-14);
        assert_relative_eq!(i.second_moment, r.second_moment, max_relative = 1e-14);
    }

    #[test]
    fn invalid_inputs_are_errors() {
        assert!(matches!(
            Material::new(-1.0, 7800.0, 0.3),
            Err(BeamError::NonPositive { .. })
        ));
        assert!(matches!(
            Material::new(1.0, 0.0, 0.3),
            Err(BeamError::NonPositive { .. })
        ));
        assert!(matches!(
            Material::new(1.0, 1.0, 0.5),
            Err(BeamError::PoissonRatio(_))
        ));
        assert!(Section::new(1.0, f64::NAN, 1.0).is_err());
        assert!(Section::tube(0.01, 0.006).is_err());
        assert!(Section::rectangular(0.0, 1.0).is_err());
    }
}
