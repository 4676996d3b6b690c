//! The data of the flap linkage of Wan, Liu, Liu, Tong, Ma, *Machines* 10 (2022) 1098
//! (paper-systems.md §1, docs/models/flap.md): the flexible parts and their section
//! calibration ([`FlexiblePart`], [`Calibration`]), the joint names and the linkage's parameters
//! ([`FlapParams`] with its reconstructed defaults). The model built from them is in
//! [`crate::flap`] (rigid linkage, studies), [`crate::flap_flex`] (flexible parts) and
//! [`crate::flap_spatial`] (in space); they all depend on this module and it on none of them.

use clr_beam::{BeamModel, Material, Section, Support};
use serde::{Deserialize, Serialize};

use crate::common::{FrictionParams, Solver};

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

/// Names of the four candidate clearance joints, in the order of [`FlapParams::clearances`]:
/// `J1` actuator (piston)–lever arm, `J2` lever-arm ground pivot, `J3` lever arm–auxiliary rod,
/// `J4` auxiliary rod–auxiliary lever arm.
pub const JOINTS: [&str; 4] = ["J1", "J2", "J3", "J4"];

/// Parameters of the rigid flap linkage (SI units). Every value not listed as the paper's is a
/// reconstruction documented in docs/models/flap.md.
///
/// Layout at mid-stroke (t = 0): lever-arm pivot O1 at the origin, lever arm vertical (up);
/// the actuator horizontal, its cylinder pivoted on the ground at distance `actuator_length`
/// to the left of the actuator joint J1 (on the lever arm at `lever_arm_actuator_distance`);
/// the auxiliary rod horizontal from the lever-arm tip J3 to J4; the auxiliary lever arm
/// vertical from its ground pivot O2 up to J4, carrying the flap (chord along +x from O2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FlapParams {
    /// Actuator stroke amplitude, m (paper: x = 10 mm).
    pub actuator_amplitude: f64,
    /// Actuator frequency, Hz (paper: f = 2 Hz).
    pub actuator_frequency: f64,
    /// Smooth-step ramp of the amplitude over this time, s (reconstruction: 0.25 s, half a
    /// period, so the motion starts from rest; 0 = no ramp).
    pub ramp_time: f64,
    /// Pin-to-pin actuator length at mid-stroke, m (reconstruction 0.25).
    pub actuator_length: f64,
    /// Cylinder mass, kg (reconstruction 1.5) and length, m (0.20; centre of mass at mid-length).
    pub cylinder_mass: f64,
    /// Cylinder length, m.
    pub cylinder_length: f64,
    /// Piston (rod) mass, kg (reconstruction 0.5).
    pub piston_mass: f64,
    /// Piston length, m (reconstruction 0.15; its tip is the journal of J1).
    pub piston_length: f64,
    /// Lever arm: pivot O1 to the auxiliary-rod joint J3, m (reconstruction 0.10, the
    /// flexible part's length).
    pub lever_arm_length: f64,
    /// Lever arm: pivot O1 to the actuator joint J1, m (reconstruction 0.05).
    pub lever_arm_actuator_distance: f64,
    /// Lever arm mass, kg (reconstruction 0.29: steel, 15 mm × 25 mm calibrated section).
    pub lever_arm_mass: f64,
    /// Auxiliary rod length J3–J4, m (reconstruction 0.30).
    pub aux_rod_length: f64,
    /// Auxiliary rod mass, kg (reconstruction 0.93: steel, 15 mm × 26.6 mm).
    pub aux_rod_mass: f64,
    /// Auxiliary lever arm: pivot O2 to J4, m (reconstruction 0.12).
    pub aux_lever_arm_length: f64,
    /// Auxiliary lever arm mass, kg (reconstruction 0.32: steel, 15 mm × 22.9 mm).
    pub aux_lever_arm_mass: f64,
    /// Flap mass, kg (reconstruction 4.0).
    pub flap_mass: f64,
    /// Flap inertia about its centre of mass, kg·m² (reconstruction 0.02).
    pub flap_inertia: f64,
    /// Distance of the flap's centre of mass aft of the hinge O2, m (reconstruction 0.10).
    pub flap_cg_distance: f64,
    /// Mean aerodynamic hinge moment, N·m, clockwise on the flap (reconstruction 30).
    pub hinge_moment: f64,
    /// Aerodynamic hinge stiffness, N·m/rad: M = −(M0 + K·(θ − θ0)) (reconstruction 100).
    pub hinge_stiffness: f64,
    /// Gravity −9.81 m/s² along y when true.
    pub gravity: bool,
    /// Radial clearance of J1..J4, m; 0 makes the joint ideal (default: 0.1 mm in J4 only).
    pub clearances: [f64; 4],
    /// Bearing radius of a clearance joint, m (reconstruction 10 mm).
    pub bearing_radius: f64,
    /// Axial (bearing) length L, m (paper: 15 mm).
    pub axial_length: f64,
    /// Young's modulus, Pa (reconstruction: steel 207 GPa).
    pub youngs_modulus: f64,
    /// Poisson's ratio (0.3).
    pub poisson_ratio: f64,
    /// Normal law preset (paper: `Modified`).
    pub normal_law: String,
    /// Restitution coefficient (paper: c_r = 0.46).
    pub restitution: f64,
    /// Friction (paper: Ambrósio c_f = 0.01, v0 = 0.1 mm/s, v1 = 1 mm/s).
    pub friction: FrictionParams,
    /// Simulated time, s.
    pub duration: f64,
    /// Metrics use t ≥ transient, s (reconstruction: 0.25 s, the ramp).
    pub transient: f64,
    /// Number of phases per actuator period at which the Poincaré sections are taken.
    pub poincare_phases: usize,
    /// Relative tolerance (absolute tolerance rtol·1e-3).
    pub rtol: f64,
    /// Integrator (default NDF: the hinge load keeps the journals on the bearing walls, a stiff
    /// persistent contact on light links where DOPRI5 is stability-limited; with J1 and J2
    /// clearance joints DOPRI5 needs 30× more wall time for the same metrics within 1 %).
    pub solver: Solver,
    /// Output interval of the ideal reference run, s.
    pub reference_interval: f64,
    /// Flexible parts: [lever arm, auxiliary rod, auxiliary lever arm]; a flexible part is a
    /// floating-frame beam body of the calibrated section ([`FlexiblePart::calibrate`]) and its
    /// mass is ρ·A·L of that section (the `*_mass` field of the part is then unused). Default:
    /// all rigid. Model in docs/models/flap.md and [`crate::flap_flex`].
    pub flexible: [bool; 3],
    /// Fixed-interface normal modes kept per flexible part in its Craig–Bampton reduction
    /// (reconstruction: 2).
    pub flexible_modes: usize,
    /// Damping ratio ζ of each flexible part [lever arm, auxiliary rod, auxiliary lever arm] at
    /// its calibrated first frequency f1, through stiffness-proportional Rayleigh damping
    /// β = 2ζ/(2πf1) (higher modes more damped). Reconstruction: the default modal damping of
    /// Adams/Flex flexible bodies for f1 (1 % below 100 Hz, 10 % below 1 kHz, critical above;
    /// Adams Solver FLEX_BODY CRATIO): [1.0, 0.1, 1.0] for 5839 / 690 / 3716 Hz.
    pub flexible_damping_ratios: [f64; 3],
}

impl Default for FlapParams {
    fn default() -> Self {
        Self {
            actuator_amplitude: 10e-3,
            actuator_frequency: 2.0,
            ramp_time: 0.25,
            actuator_length: 0.25,
            cylinder_mass: 1.5,
            cylinder_length: 0.20,
            piston_mass: 0.5,
            piston_length: 0.15,
            lever_arm_length: 0.10,
            lever_arm_actuator_distance: 0.05,
            lever_arm_mass: 0.29,
            aux_rod_length: 0.30,
            aux_rod_mass: 0.93,
            aux_lever_arm_length: 0.12,
            aux_lever_arm_mass: 0.32,
            flap_mass: 4.0,
            flap_inertia: 0.02,
            flap_cg_distance: 0.10,
            hinge_moment: 30.0,
            hinge_stiffness: 100.0,
            gravity: true,
            clearances: [0.0, 0.0, 0.0, 0.1e-3],
            bearing_radius: 10e-3,
            axial_length: 15e-3,
            youngs_modulus: 207e9,
            poisson_ratio: 0.3,
            normal_law: "Modified".into(),
            restitution: 0.46,
            friction: FrictionParams::Ambrosio {
                mu: 0.01,
                v0: 1e-4,
                v1: 1e-3,
            },
            duration: 0.5,
            transient: 0.25,
            poincare_phases: 20,
            rtol: 1e-8,
            solver: Solver::Ndf,
            reference_interval: 1e-4,
            flexible: [false; 3],
            flexible_modes: 2,
            flexible_damping_ratios: [1.0, 0.1, 1.0],
        }
    }
}
