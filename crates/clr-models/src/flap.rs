//! Flap actuation system of Wan, Liu, Liu, Tong, Ma, *Machines* 10 (2022) 1098
//! (paper-systems.md §1) — first part: the flexible parts' section calibration.
//!
//! **Known from the paper:** the first five eigenfrequencies of the auxiliary lever arm
//! (3715.8, 5437.1, 7921.3, 7946.1, 7971.7 Hz), the auxiliary rod (690.40, 1648.66, 1869.88,
//! 2143.10, 3588.54 Hz) and the lever arm (5839.3, 6201.3, 7240.9, 7976.3, 9260.8 Hz).
//!
//! **Reconstructed:** each part is a planar Euler–Bernoulli beam (clr-beam, 20 elements,
//! consistent mass) of steel (207 GPa, 7800 kg/m³), a rectangular section of width 15 mm (the
//! bearing length L of the paper) and a depth calibrated so that the first computed frequency
//! equals the paper's; pinned at one end and on a roller along the axis at the other (the
//! parts are links between two revolute joints); lengths 0.10 m (lever arm), 0.30 m
//! (auxiliary rod), 0.12 m (auxiliary lever arm). A planar beam has only in-plane bending and
//! axial modes: the paper's higher modes of the 3-D parts (out-of-plane bending, torsion) are
//! not reproduced.
//!
//! The rigid linkage, its clearance joints and studies, and the floating-frame flexible bodies
//! are not built yet (see docs/models/flap.md).

use clr_beam::{BeamModel, Material, Section, Support};
use serde::{Deserialize, Serialize};

/// The paper's first five eigenfrequencies (Hz) per flexible part.
pub const PAPER_FREQUENCIES: [(&str, [f64; 5]); 3] = [
    ("lever_arm", [5839.3, 6201.3, 7240.9, 7976.3, 9260.8]),
    (
        "auxiliary_rod",
        [690.40, 1648.66, 1869.88, 2143.10, 3588.54],
    ),
    (
        "auxiliary_lever_arm",
        [3715.8, 5437.1, 7921.3, 7946.1, 7971.7],
    ),
];

/// A flexible part of the flap linkage as a planar beam (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlexiblePart {
    /// Part name (`lever_arm`, `auxiliary_rod`, `auxiliary_lever_arm`).
    pub name: String,
    /// Length between the joint centres, m (reconstruction).
    pub length: f64,
    /// Section width out of the plane, m (reconstruction: 15 mm).
    pub width: f64,
    /// Young's modulus, Pa (reconstruction: steel 207 GPa).
    pub youngs_modulus: f64,
    /// Density, kg/m³ (reconstruction: 7800).
    pub density: f64,
    /// Number of beam elements.
    pub elements: usize,
    /// Target first eigenfrequency, Hz (paper).
    pub target_hz: f64,
}

impl FlexiblePart {
    /// The three parts with their reconstructed lengths and the paper's first frequencies.
    pub fn paper_parts() -> Vec<FlexiblePart> {
        let len = [0.10, 0.30, 0.12];
        PAPER_FREQUENCIES
            .iter()
            .zip(len)
            .map(|((name, f), length)| FlexiblePart {
                name: name.to_string(),
                length,
                width: 15e-3,
                youngs_modulus: 207e9,
                density: 7800.0,
                elements: 20,
                target_hz: f[0],
            })
            .collect()
    }

    /// The beam model with section depth `depth` (m): pinned at x = 0, roller along x at
    /// x = length.
    ///
    /// # Errors
    /// The clr-beam message.
    pub fn beam(&self, depth: f64) -> Result<BeamModel, String> {
        let mat =
            Material::new(self.youngs_modulus, self.density, 0.3).map_err(|e| e.to_string())?;
        let sec = Section::rectangular(self.width, depth).map_err(|e| e.to_string())?;
        let mut m = BeamModel::straight([0.0, 0.0], [self.length, 0.0], self.elements, mat, sec)
            .map_err(|e| e.to_string())?;
        m.support(0, Support::Pinned).map_err(|e| e.to_string())?;
        m.support(self.elements, Support::RollerX)
            .map_err(|e| e.to_string())?;
        Ok(m)
    }

    /// Lowest `n` computed frequencies (Hz) with section depth `depth`.
    ///
    /// # Errors
    /// The clr-beam message.
    pub fn frequencies(&self, depth: f64, n: usize) -> Result<Vec<f64>, String> {
        let modes = self.beam(depth)?.modes(n).map_err(|e| e.to_string())?;
        Ok(modes.frequencies_hz())
    }

    /// Euler–Bernoulli closed form of the first bending frequency of a pinned–pinned beam,
    /// f1 = (π/(2L²))·√(EI/(ρA)) with I = b h³/12, A = b h (Hz).
    pub fn closed_form_f1(&self, depth: f64) -> f64 {
        let ei_over_rhoa = self.youngs_modulus * depth * depth / (12.0 * self.density);
        std::f64::consts::PI / (2.0 * self.length * self.length) * ei_over_rhoa.sqrt()
    }

    /// Calibrate the section depth so the first computed frequency equals `target_hz`: start
    /// from the closed form and rescale (f1 ∝ h for a bending mode) until the relative
    /// mismatch is below 1e-10.
    ///
    /// # Errors
    /// The clr-beam message, or no convergence in 20 rescalings.
    pub fn calibrate(&self) -> Result<Calibration, String> {
        let mut h = self.target_hz / self.closed_form_f1(1.0);
        for _ in 0..20 {
            let f = self.frequencies(h, 5)?;
            let r = self.target_hz / f[0];
            if (r - 1.0).abs() < 1e-10 {
                return Ok(Calibration {
                    depth: h,
                    frequencies_hz: f,
                });
            }
            h *= r;
        }
        Err(format!(
            "{}: the section depth did not converge to f1 = {} Hz",
            self.name, self.target_hz
        ))
    }
}

/// A calibrated section.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibration {
    /// Section depth in the plane, m.
    pub depth: f64,
    /// The lowest five computed frequencies, Hz.
    pub frequencies_hz: Vec<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calibrated_rod_matches_the_paper_and_the_closed_form() {
        let rod = &FlexiblePart::paper_parts()[1];
        let c = rod.calibrate().unwrap();
        // first frequency equal to the paper's 690.40 Hz after calibration
        assert!((c.frequencies_hz[0] / 690.40 - 1.0).abs() < 1e-9);
        // and close to the Euler–Bernoulli closed form at that depth (20 elements)
        let cf = rod.closed_form_f1(c.depth);
        assert!(
            (c.frequencies_hz[0] / cf - 1.0).abs() < 1e-4,
            "{} vs {cf}",
            c.frequencies_hz[0]
        );
    }
}
