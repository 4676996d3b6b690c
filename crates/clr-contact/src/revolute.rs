//! Planar revolute clearance joint: a journal (pin) of radius R_j inside a bearing (hole) of
//! radius R_i > R_j.
//!
//! Formulas from P. Flores, J. Ambrósio, J.C.P. Claro, H.M. Lankarani, Computers & Structures 82
//! (2004) 1359–1369, and *Kinematics and Dynamics of Multibody Systems with Imperfect Joints*,
//! Springer (2008), ch. 4 (restated in `contact-laws.md` §3.1):
//!
//! - joint centres r_k^P = r_k + A(φ_k) s′_k^P (k = i bearing, j journal);
//! - eccentricity vector **e** = r_j^P − r_i^P, e = |**e**|, normal **n** = **e**/e (bearing centre →
//!   journal centre), tangent **t** = k̂ × **n**;
//! - penetration δ = e − c with the radial clearance c = R_i − R_j (contact when δ > 0);
//! - contact points r_i^Q = r_i^P + R_i **n**, r_j^Q = r_j^P + R_j **n** (they differ by δ **n**);
//! - relative velocity **v** = ṙ_j^Q − ṙ_i^Q, normal velocity v_N = **v**·**n** = δ̇ (> 0
//!   approaching), tangential velocity v_T = **v**·**t**;
//! - force on the journal **f**_j = −F_N **n** + F_T **t** applied at r_j^Q, on the bearing
//!   **f**_i = −**f**_j applied at r_i^Q; moments about each body's reference point
//!   m_k = (r_k^Q − r_k) × **f**_k.
//!
//! Applying each force at its own contact point (the formulation above, [`ForceApplication::ContactPoints`])
//! makes the action–reaction pair non-collinear: the friction pair is offset by δ along **n** and
//! adds a net moment δ·F_T to the system, so a free-floating mechanism with friction in a
//! clearance joint does not conserve angular momentum (a drift of order ∫δ F_T dt).
//! [`ForceApplication::CommonPoint`] applies both forces at the midpoint of the two contact points
//! instead: the moments differ from the Flores form by O(δ/R) and angular momentum is conserved
//! exactly. [`RevoluteContact::generalized_forces`] keeps the published form (the worked example of
//! contact-laws.md §7.7); multibody codes should prefer
//! [`RevoluteContact::generalized_forces_with`]`(.., ForceApplication::CommonPoint)`.
//!
//! When the centres coincide (e → 0) the normal is undefined; the joint is then not in contact
//! (δ = −c < 0) and the x axis of the world frame is reported as the normal, so nothing is NaN.

use nalgebra::Vector2;

use crate::body::{check_finite, check_positive, perp, BodyState, GeneralizedForce};
use crate::error::ContactError;
use crate::friction::FrictionLaw;
use crate::normal::NormalLaw;

/// Geometry of a planar revolute clearance joint: radii and the joint centres on both bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RevoluteClearance {
    bearing_radius: f64,
    journal_radius: f64,
    bearing_centre: Vector2<f64>,
    journal_centre: Vector2<f64>,
}

/// Everything the kinematics of a revolute clearance joint gives at one state (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RevoluteContact {
    /// Eccentricity vector **e** = r_j^P − r_i^P, m.
    pub eccentricity_vector: Vector2<f64>,
    /// Eccentricity e = |**e**|, m.
    pub eccentricity: f64,
    /// Penetration δ = e − c, m (> 0 in contact).
    pub penetration: f64,
    /// Unit normal **n** from the bearing centre to the journal centre (world x axis when e = 0).
    pub normal: Vector2<f64>,
    /// Unit tangent **t** = k̂ × **n**.
    pub tangent: Vector2<f64>,
    /// Contact point on the bearing r_i^Q = r_i^P + R_i **n**, m.
    pub bearing_point: Vector2<f64>,
    /// Contact point on the journal r_j^Q = r_j^P + R_j **n**, m.
    pub journal_point: Vector2<f64>,
    /// Relative normal velocity v_N = (ṙ_j^Q − ṙ_i^Q)·**n** = δ̇, m/s (> 0 approaching).
    pub normal_velocity: f64,
    /// Relative tangential velocity v_T = (ṙ_j^Q − ṙ_i^Q)·**t**, m/s.
    pub tangential_velocity: f64,
    bearing_reference: Vector2<f64>,
    journal_reference: Vector2<f64>,
}

/// Where the contact force pair of a revolute clearance joint is applied.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ForceApplication {
    /// Force on the journal at r_j^Q, on the bearing at r_i^Q (Flores et al. 2004; contact-laws.md
    /// §3.1). The pair is offset by δ**n**, so friction adds a net moment δ·F_T.
    #[default]
    ContactPoints,
    /// Both forces at the midpoint (r_i^Q + r_j^Q)/2: collinear action and reaction, so the joint
    /// conserves the angular momentum of the system exactly.
    CommonPoint,
}

/// Generalized forces of a revolute clearance joint on its two bodies.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct JointForces {
    /// Normal force F_N ≥ 0 that was applied, N.
    pub normal_force: f64,
    /// Tangential (friction) force F_T on the journal along **t**, N.
    pub tangential_force: f64,
    /// (f_x, f_y, m) on the bearing body about its reference point.
    pub bearing: GeneralizedForce,
    /// (f_x, f_y, m) on the journal body about its reference point.
    pub journal: GeneralizedForce,
}

impl RevoluteClearance {
    /// A clearance joint from the bearing radius R_i and journal radius R_j (m, R_i > R_j > 0) and
    /// the local coordinates (m) of the bearing centre on body i and the journal centre on body j.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] when a radius is not positive and finite, when
    /// R_i ≤ R_j (no clearance), or when a local point is not finite.
    pub fn new(
        bearing_radius: f64,
        journal_radius: f64,
        bearing_centre: Vector2<f64>,
        journal_centre: Vector2<f64>,
    ) -> Result<Self, ContactError> {
        const LAW: &str = "revolute clearance joint";
        check_positive(
            LAW,
            &[
                ("bearing radius R_i (m)", bearing_radius),
                ("journal radius R_j (m)", journal_radius),
            ],
        )?;
        if journal_radius >= bearing_radius {
            return Err(ContactError::invalid(
                LAW,
                "journal radius R_j (m)",
                journal_radius,
                format!("must be smaller than the bearing radius R_i = {bearing_radius} m so that the clearance R_i - R_j is positive"),
            ));
        }
        check_finite(
            LAW,
            &[
                ("bearing centre, local x (m)", bearing_centre.x),
                ("bearing centre, local y (m)", bearing_centre.y),
                ("journal centre, local x (m)", journal_centre.x),
                ("journal centre, local y (m)", journal_centre.y),
            ],
        )?;
        Ok(Self {
            bearing_radius,
            journal_radius,
            bearing_centre,
            journal_centre,
        })
    }

    /// Bearing radius R_i, m.
    pub fn bearing_radius(&self) -> f64 {
        self.bearing_radius
    }

    /// Journal radius R_j, m.
    pub fn journal_radius(&self) -> f64 {
        self.journal_radius
    }

    /// Radial clearance c = R_i − R_j, m.
    pub fn clearance(&self) -> f64 {
        self.bearing_radius - self.journal_radius
    }

    /// Local coordinates of the bearing centre on body i, m.
    pub fn bearing_centre(&self) -> Vector2<f64> {
        self.bearing_centre
    }

    /// Local coordinates of the journal centre on body j, m.
    pub fn journal_centre(&self) -> Vector2<f64> {
        self.journal_centre
    }

    /// All kinematic quantities at once (the cheap way when several are needed).
    pub fn contact(&self, bearing: &BodyState, journal: &BodyState) -> RevoluteContact {
        let pi = bearing.point(self.bearing_centre);
        let pj = journal.point(self.journal_centre);
        let e_vec = pj - pi;
        let e = e_vec.norm();
        // e/e is undefined at e = 0; the normal is irrelevant there (δ = −c < 0, no force) but is
        // kept a unit vector so that downstream code never sees NaN.
        let normal = if e > f64::MIN_POSITIVE && e.is_finite() {
            e_vec / e
        } else {
            Vector2::new(1.0, 0.0)
        };
        let tangent = perp(normal);
        let qi = pi + self.bearing_radius * normal;
        let qj = pj + self.journal_radius * normal;
        let v = journal.point_velocity(qj) - bearing.point_velocity(qi);
        RevoluteContact {
            eccentricity_vector: e_vec,
            eccentricity: e,
            penetration: e - self.clearance(),
            normal,
            tangent,
            bearing_point: qi,
            journal_point: qj,
            normal_velocity: v.dot(&normal),
            tangential_velocity: v.dot(&tangent),
            bearing_reference: bearing.position,
            journal_reference: journal.position,
        }
    }

    /// Eccentricity e = |r_j^P − r_i^P|, m.
    pub fn eccentricity(&self, bearing: &BodyState, journal: &BodyState) -> f64 {
        self.contact(bearing, journal).eccentricity
    }

    /// Penetration δ = e − c, m (> 0 in contact).
    pub fn penetration(&self, bearing: &BodyState, journal: &BodyState) -> f64 {
        self.contact(bearing, journal).penetration
    }

    /// Unit normal from the bearing centre to the journal centre.
    pub fn normal(&self, bearing: &BodyState, journal: &BodyState) -> Vector2<f64> {
        self.contact(bearing, journal).normal
    }

    /// Unit tangent k̂ × **n**.
    pub fn tangent(&self, bearing: &BodyState, journal: &BodyState) -> Vector2<f64> {
        self.contact(bearing, journal).tangent
    }

    /// Contact points (r_i^Q on the bearing, r_j^Q on the journal), m.
    pub fn contact_points(
        &self,
        bearing: &BodyState,
        journal: &BodyState,
    ) -> (Vector2<f64>, Vector2<f64>) {
        let c = self.contact(bearing, journal);
        (c.bearing_point, c.journal_point)
    }

    /// Relative normal velocity v_N = δ̇, m/s (> 0 approaching).
    pub fn relative_normal_velocity(&self, bearing: &BodyState, journal: &BodyState) -> f64 {
        self.contact(bearing, journal).normal_velocity
    }

    /// Relative tangential velocity v_T of the journal's contact point, m/s.
    pub fn relative_tangential_velocity(&self, bearing: &BodyState, journal: &BodyState) -> f64 {
        self.contact(bearing, journal).tangential_velocity
    }
}

impl RevoluteContact {
    /// True when the journal penetrates the bearing wall (δ > 0).
    pub fn in_contact(&self) -> bool {
        self.penetration > 0.0
    }

    /// Generalized forces on both bodies from a normal force F_N (N, pushes the journal back
    /// toward the bearing centre) and a tangential force F_T (N, on the journal along **t**;
    /// a friction law returns it with the sign opposite to v_T).
    ///
    /// **f**_j = −F_N **n** + F_T **t** at r_j^Q and **f**_i = −**f**_j at r_i^Q (Flores et al.
    /// 2004, eqs. 14–17). Without penetration (δ ≤ 0) the joint transmits nothing and the zero
    /// forces are returned whatever F_N and F_T are.
    pub fn generalized_forces(&self, normal_force: f64, tangential_force: f64) -> JointForces {
        if !self.in_contact() {
            return JointForces::default();
        }
        self.generalized_forces_with(
            normal_force,
            tangential_force,
            ForceApplication::ContactPoints,
        )
    }

    /// As [`generalized_forces`](Self::generalized_forces), with the force pair applied as
    /// `application` says ([`ForceApplication::CommonPoint`] conserves angular momentum).
    pub fn generalized_forces_with(
        &self,
        normal_force: f64,
        tangential_force: f64,
        application: ForceApplication,
    ) -> JointForces {
        if !self.in_contact() {
            return JointForces::default();
        }
        let fj = -normal_force * self.normal + tangential_force * self.tangent;
        let (at_bearing, at_journal) = match application {
            ForceApplication::ContactPoints => (self.bearing_point, self.journal_point),
            ForceApplication::CommonPoint => {
                let mid = 0.5 * (self.bearing_point + self.journal_point);
                (mid, mid)
            }
        };
        JointForces {
            normal_force,
            tangential_force,
            bearing: GeneralizedForce::at(self.bearing_reference, at_bearing, -fj),
            journal: GeneralizedForce::at(self.journal_reference, at_journal, fj),
        }
    }

    /// Generalized forces from a normal law and a friction law: F_N = `normal.force(δ, δ̇, δ̇⁻)`
    /// with δ̇ = v_N and the impact velocity δ̇⁻ (m/s, e.g. from
    /// [`ContactMemory::impact_velocity`](crate::memory::ContactMemory::impact_velocity)), and
    /// F_T = `friction.force(v_T, F_N)`; then as [`generalized_forces`](Self::generalized_forces).
    pub fn forces_from_laws(
        &self,
        normal: &NormalLaw,
        friction: &FrictionLaw,
        impact_velocity: f64,
    ) -> JointForces {
        if !self.in_contact() {
            return JointForces::default();
        }
        self.forces_from_laws_with(
            normal,
            friction,
            impact_velocity,
            ForceApplication::ContactPoints,
        )
    }

    /// As [`forces_from_laws`](Self::forces_from_laws), with the force pair applied as
    /// `application` says.
    pub fn forces_from_laws_with(
        &self,
        normal: &NormalLaw,
        friction: &FrictionLaw,
        impact_velocity: f64,
        application: ForceApplication,
    ) -> JointForces {
        if !self.in_contact() {
            return JointForces::default();
        }
        let f_n = normal.force(self.penetration, self.normal_velocity, impact_velocity);
        let f_t = friction.force(self.tangential_velocity, f_n);
        self.generalized_forces_with(f_n, f_t, application)
    }
}
