//! What a contact element reports at the last evaluated state ([`ContactReport`]): written by
//! every contact element's force evaluation, read by the recorded columns, the energy balance,
//! the plausibility checks and `Model::contact_reports`.

/// Quantities of one contact element at the last evaluated state.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactReport {
    /// Largest penetration over the element's contact points, m (> 0 in contact; the signed
    /// gap when no point is in contact).
    pub penetration: f64,
    /// Penetration rate of the point with the largest penetration, m/s (> 0 approaching).
    pub penetration_rate: f64,
    /// Normal force, summed over the active points, N.
    pub normal_force: f64,
    /// Friction force, summed over the active points, N.
    pub friction_force: f64,
    /// Number of active contact points (0 or 1 for a revolute clearance joint, 0–4 corners for
    /// a translational one).
    pub active_points: usize,
    /// Revolute: journal centre relative to the bearing centre in the bearing body's frame;
    /// translational: slider reference point in the guide frame; shape contact: the deepest
    /// point on shape A within the prediction distance in the world frame (0 when there is
    /// none), m.
    pub eccentricity: [f64; 2],
    /// Resultant of the oil film's pressure on the journal, N (lubricated joints; else 0).
    pub film_force: f64,
    /// Minimum film thickness h_min = c(1 − ε), m (lubricated joints; else 0).
    pub film_thickness: f64,
    /// Power dissipated by contact damping and friction, (F_N − F_e(δ))·δ̇ − F_T·v_T summed over
    /// the active points, W. For a revolute joint it is the power the applied force pair takes
    /// out of the bodies minus the elastic storage F_e·δ̇, so v_T is the slip at the points the
    /// pair is applied to: with the default common-point application it differs from the slip
    /// of the contact points by (δ/2)(ω_i + ω_j).
    pub dissipated_power: f64,
}
