//! Flexible lever arm, auxiliary rod and auxiliary lever arm of the flap linkage (Wan et al.,
//! *Machines* 10 (2022) 1098; paper-systems.md §1) as floating-frame beam bodies, and the
//! flexible-body studies ([`crate::flap_flex_study`]).
//!
//! **Model (reconstruction, docs/models/flap.md).** Each flexible part is a clr-mbd
//! [`ModelBuilder::floating_beam`] (planar floating frame of reference, Shabana, *Dynamics of
//! Multibody Systems*, 4th ed. 2020, ch. 5) of the calibrated steel section
//! ([`FlexiblePart::calibrate`]: width 15 mm, depth such that the pinned–roller first frequency
//! is the paper's), [`ELEMENTS`] Euler–Bernoulli elements along the body x axis. Reference
//! conditions: a clamp at node 0, the part's pivot or first joint (lever arm: ground pivot O1;
//! auxiliary rod: J3; auxiliary lever arm: ground pivot O2), so the body frame is tangent to the
//! part there. Reduction: Craig–Bampton (Craig & Bampton, *AIAA J.* 6 (1968) 1313) with the other
//! joints' nodes as interface nodes (lever arm: J1 at node 10 and J3 at node 20; rod and
//! auxiliary lever arm: J4 at node 20) plus `flexible_modes` fixed-interface modes: the joint
//! forces act at those nodes, and the static constraint modes represent the quasi-static
//! deflection under them exactly (modal truncation of cantilever modes would need many modes
//! to do so). Stiffness-proportional Rayleigh damping β = 2ζ/ω1 with ζ at the part's first
//! frequency from `flexible_damping_ratios` (default: Adams/Flex's default modal damping for
//! that frequency, [`adams_default_damping`]). The flap rides on the auxiliary lever arm: when
//! that arm is flexible it is a rigid body fixed to the arm's pivot
//! node.

use std::f64::consts::PI;

use clr_beam::{BeamModel, ReducedModel};
use clr_mbd::desc::{BeamMaterial, BeamMesh, SectionDesc, SupportDesc, SupportKind};
use clr_mbd::{ModelBuilder, Reduction};
use nalgebra::DMatrix;

use crate::flap_params::{Calibration, FlapParams, FlexiblePart};

/// Beam elements per flexible part (the lever arm's actuator joint J1 must fall on a node).
pub const ELEMENTS: usize = 20;

/// Rows kept in the per-case CSV files of [`crate::flap_flex_study::study`] (every k-th recorded step; the metrics use
/// every step). The flexible runs record up to 6e5 steps × 100 columns.
pub const MAX_CSV_ROWS: usize = 20_000;

/// Duration of the flexible flap studies, s (ramp 0.25 s + 2 actuator periods): `clr study
/// flap_flexible` and the flexible flap finding map.
pub const FLAP_FLEX_STUDY_DURATION: f64 = 1.25;

/// Body names of the three parts, in the order of [`FlapParams::flexible`].
pub const PARTS: [&str; 3] = ["lever_arm", "aux_rod", "aux_lever_arm"];

/// A flexible part ready for clr-mbd: the calibration, the clamped beam in its body frame and
/// its Craig–Bampton reduction.
#[derive(Debug, Clone)]
pub struct FlexibleBody {
    /// Part data (length from [`FlapParams`], steel, width 15 mm, paper's first frequency).
    pub part: FlexiblePart,
    /// Calibrated section depth and pinned–roller frequencies.
    pub calibration: Calibration,
    /// The beam as model-file data (the mesh `beam` is built from).
    pub mesh: BeamMesh,
    /// Beam along the body x axis from the reference node 0 (clamped), with Rayleigh damping.
    pub beam: BeamModel,
    /// Craig–Bampton reduction (interface nodes [`FlexibleBody::interface_nodes`]).
    pub reduced: ReducedModel,
    /// Interface (deforming joint) nodes.
    pub interface_nodes: Vec<usize>,
}

impl FlexibleBody {
    /// Mass ρ·b·h·L of the calibrated section, kg.
    pub fn mass(&self) -> f64 {
        self.part.density * self.part.width * self.calibration.depth * self.part.length
    }

    /// First frequency (Hz) of the reduced floating body pinned at its reference node and on a
    /// roller along its axis at the last node — the calibration's boundary conditions — from
    /// the linearised floating-frame equations about the undeformed state: coordinates
    /// (θ, q_f), mass [[J₀, cᵀ], [c, M_ff]] (the clr-beam invariants that clr-mbd uses),
    /// stiffness diag(0, K_ff), constraint L·θ + t_v·q_f = 0 (t_v the row of T of the last
    /// node's transverse displacement) eliminated, then the generalized symmetric eigenproblem.
    ///
    /// # Errors
    /// A singular reduced mass matrix.
    pub fn reduced_first_frequency(&self) -> Result<f64, String> {
        let inv = &self.reduced.invariants;
        let t = &self.reduced.transformation;
        let r = t.ncols();
        let l = self.part.length;
        let row = 3 * ELEMENTS + 1;
        // x = (θ, q_f) = G q_f, G = [−t_v / L; I]
        let mut g = DMatrix::<f64>::zeros(r + 1, r);
        for k in 0..r {
            g[(0, k)] = -t[(row, k)] / l;
            g[(k + 1, k)] = 1.0;
        }
        let mut mm = DMatrix::<f64>::zeros(r + 1, r + 1);
        let mut kk = DMatrix::<f64>::zeros(r + 1, r + 1);
        mm[(0, 0)] = inv.polar_inertia;
        for i in 0..r {
            mm[(0, i + 1)] = inv.rotation_coupling[i];
            mm[(i + 1, 0)] = inv.rotation_coupling[i];
            for j in 0..r {
                mm[(i + 1, j + 1)] = inv.modal_mass[(i, j)];
                kk[(i + 1, j + 1)] = self.reduced.stiffness[(i, j)];
            }
        }
        let m = g.transpose() * mm * &g;
        let k = g.transpose() * kk * &g;
        let chol = m.cholesky().ok_or_else(|| {
            format!(
                "{}: reduced mass matrix not positive definite",
                self.part.name
            )
        })?;
        let linv = chol
            .l()
            .try_inverse()
            .ok_or_else(|| format!("{}: singular reduced mass factor", self.part.name))?;
        let a = &linv * k * linv.transpose();
        let a = 0.5 * (&a + a.transpose());
        let lam = a.symmetric_eigen().eigenvalues.min();
        Ok(lam.max(0.0).sqrt() / (2.0 * PI))
    }
}

/// Adams/Flex default modal damping ratio for a mode at `f_hz` (Hz): 0.01 below 100 Hz, 0.1
/// below 1 kHz, 1.0 (critical) above (Adams Solver FLEX_BODY statement, CRATIO default) — the
/// reconstruction behind the default [`FlapParams::flexible_damping_ratios`].
pub fn adams_default_damping(f_hz: f64) -> f64 {
    if f_hz < 100.0 {
        0.01
    } else if f_hz < 1000.0 {
        0.1
    } else {
        1.0
    }
}

/// The flexible part `k` (0 lever arm, 1 auxiliary rod, 2 auxiliary lever arm) of `p`:
/// calibrated, clamped at node 0, damped and reduced.
///
/// # Errors
/// A message naming the field to change (calibration or reduction failure).
pub fn flexible_body(p: &FlapParams, k: usize) -> Result<FlexibleBody, String> {
    let lengths = [p.lever_arm_length, p.aux_rod_length, p.aux_lever_arm_length];
    let mut part = FlexiblePart::paper_parts()
        .into_iter()
        .nth(k)
        .ok_or_else(|| format!("flexible part index {k} must be 0, 1 or 2"))?;
    part.length = lengths[k];
    part.elements = ELEMENTS;
    let calibration = part.calibrate()?;
    // the calibration beam (pinned–roller) re-supported as a cantilever from node 0
    let support = |node, kind| SupportDesc { node, kind };
    let mesh = BeamMesh {
        start: [0.0, 0.0],
        end: [part.length, 0.0],
        elements: part.elements,
        material: BeamMaterial {
            youngs_modulus: part.youngs_modulus,
            density: part.density,
            poisson_ratio: 0.3,
        },
        section: SectionDesc::Rectangular {
            width: part.width,
            depth: calibration.depth,
        },
        supports: vec![
            support(0, SupportKind::Pinned),
            support(part.elements, SupportKind::RollerX),
            support(0, SupportKind::Clamped),
            support(part.elements, SupportKind::Free),
        ],
        rayleigh: [
            0.0,
            2.0 * p.flexible_damping_ratios[k] / (2.0 * PI * part.target_hz),
        ],
        mass: Default::default(),
    };
    let beam = mesh
        .build(PARTS[k])
        .map_err(|e| format!("{}: {}", part.name, e.message))?;
    let interface_nodes = if k == 0 {
        let n1 = (p.lever_arm_actuator_distance / p.lever_arm_length * ELEMENTS as f64).round();
        vec![n1 as usize, ELEMENTS]
    } else {
        vec![ELEMENTS]
    };
    let reduced = beam
        .craig_bampton(&interface_nodes, p.flexible_modes)
        .map_err(|e| format!("{} (change `flexible_modes`): {e}", part.name))?;
    Ok(FlexibleBody {
        part,
        calibration,
        mesh,
        beam,
        reduced,
        interface_nodes,
    })
}

/// Add flexible part `k` of `p` to `m` as floating body [`PARTS`]`[k]` with its frame origin
/// (reference node 0) at `origin` (m) and its axis at angle `angle` (rad), at rest.
///
/// # Errors
/// As [`flexible_body`].
pub fn add_part(
    m: &mut ModelBuilder,
    p: &FlapParams,
    k: usize,
    origin: [f64; 2],
    angle: f64,
) -> Result<(), String> {
    let fb = flexible_body(p, k)?;
    m.floating_beam(
        PARTS[k],
        fb.mesh,
        Reduction::CraigBampton {
            interface_nodes: fb.interface_nodes,
            modes: p.flexible_modes,
        },
        [origin[0], origin[1], angle],
        [0.0; 3],
    );
    Ok(())
}

/// `p` with the rigid link masses set to ρ·A·L of the calibrated sections, so a rigid and a
/// flexible configuration have the same masses (the defaults 0.29 / 0.93 / 0.32 kg are these
/// values rounded).
///
/// # Errors
/// As [`flexible_body`].
pub fn with_beam_masses(p: &FlapParams) -> Result<FlapParams, String> {
    let m: Vec<f64> = (0..3)
        .map(|k| flexible_body(p, k).map(|b| b.mass()))
        .collect::<Result<_, _>>()?;
    Ok(FlapParams {
        lever_arm_mass: m[0],
        aux_rod_mass: m[1],
        aux_lever_arm_mass: m[2],
        ..p.clone()
    })
}

/// Largest flap-angle deviation (rad) of the flexible linkage with ideal joints from the rigid
/// closed form, estimated from the static deflections under the hinge load (an independent
/// bound for the quasi-static regime, all three parts flexible): with the largest rod force
/// F = M_max / c (c the auxiliary-lever length, M_max the largest hinge + flap-weight moment),
/// the auxiliary lever arm (cantilever from its clamped pivot, tip load F) gives
/// F c²/(3EI), the rod's axial stretch F l/(EA)/c, and the lever arm (clamped at O1, J1 held by
/// the actuator at a = L/2, F at the tip J3) a tip displacement relative to the line O1–J1 of
/// F L³/(12 EI), i.e. /c in flap angle. Sum of the magnitudes.
///
/// # Errors
/// As [`flexible_body`].
pub fn static_deflection_angle(p: &FlapParams) -> Result<f64, String> {
    let swing = p
        .ideal_flap_angle(p.actuator_amplitude, p.aux_rod_length)
        .map(f64::abs)
        .unwrap_or(0.0)
        .max(
            p.ideal_flap_angle(-p.actuator_amplitude, p.aux_rod_length)
                .map(f64::abs)
                .unwrap_or(0.0),
        );
    let g = if p.gravity { 9.81 } else { 0.0 };
    let m_max = p.hinge_moment.abs()
        + p.hinge_stiffness.abs() * swing
        + p.flap_mass * g * p.flap_cg_distance;
    let c = p.aux_lever_arm_length;
    let f = m_max / c;
    let ei = |k: usize| -> Result<(f64, f64), String> {
        let b = flexible_body(p, k)?;
        let (w, h) = (b.part.width, b.calibration.depth);
        Ok((
            b.part.youngs_modulus * w * h * h * h / 12.0,
            b.part.youngs_modulus * w * h,
        ))
    };
    let (ei_l, _) = ei(0)?;
    let (_, ea_r) = ei(1)?;
    let (ei_a, _) = ei(2)?;
    let lever = f * p.lever_arm_length.powi(3) / (12.0 * ei_l) / c;
    let rod = f * p.aux_rod_length / ea_r / c;
    let aux = f * c * c / (3.0 * ei_a);
    Ok(lever + rod + aux)
}
