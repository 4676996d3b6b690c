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
//!
//! # Worn bearing
//! [`RevoluteClearance::with_profile`] replaces the circular bearing by the worn surface
//! ρ(φ) = R_i + h_w(φ) of a [`BearingProfile`] (φ in the bearing body frame, about the bearing
//! centre; `docs/wear.md`). The contact is then the point of that surface nearest to the
//! journal centre (the journal is a circle, so its deepest point lies on the surface normal
//! through its centre):
//!
//! - φ_e: direction of **e** in the bearing frame; the contact angle φ_c = φ_e + Δ minimizes
//!   |ρ(φ) **u**(φ) − e **u**(φ_e)|, i.e. solves ρ′(ρ − e cos Δ) + eρ sin Δ = 0
//!   ([`BearingProfile`] search: bounded window, scan, safeguarded Newton);
//! - surface normal of the polar curve **n** = (**u**_c − s **t**_c)/√(1 + s²), s = ρ′/ρ =
//!   (dh_w/dφ)/(R_i + h_w), with **u**_c = **u**(φ_c), **t**_c = k̂ × **u**_c;
//! - penetration along **n**: δ = R_j − (r_i^Q − r_j^P)·**n**
//!   = a e (cos Δ + s sin Δ) − (a ρ − R_j), a = 1/√(1 + s²);
//! - contact points r_i^Q = r_i^P + ρ(φ_c) **u**_c (on the worn surface) and
//!   r_j^Q = r_j^P + R_j **n** (they differ by δ **n**); velocities and forces as above, and
//!   v_N = δ̇ still holds (the surface point nearest to a moving point moves tangentially).
//!
//! Where the bearing is unworn at φ_e, or the profile is flat and symmetric there (uniform wear),
//! Δ = 0 and s = 0 and every quantity is computed by the same floating-point operations as the
//! circular joint with radius R_i + h_w(φ_e): δ = e − ((R_i + h_w) − R_j), **n** = **e**/e,
//! r_i^Q = r_i^P + (R_i + h_w) **n**. The zero profile therefore reproduces the circular joint
//! bit for bit. Only there does the radial formula δ = e − (R_i + h_w(φ_e) − R_j) hold in general:
//! in a conformal joint (e ≈ c ≪ R) a wear slope moves the contact far from φ_e,
//! Δ ≈ −h_w′ R_j/(R_i e), and the radial formula would underestimate δ by about h_w′²/(2e), up
//! to the whole depth h_w(φ_e) (`docs/wear.md`).

use nalgebra::Vector2;

use crate::body::{
    check_finite, check_journal_fits, check_positive, perp, rotate, BodyState, GeneralizedForce,
};
use crate::error::ContactError;
use crate::friction::FrictionLaw;
use crate::normal::NormalLaw;
use crate::wear::{BearingProfile, LineContact};

/// Geometry of a planar revolute clearance joint: radii, the joint centres on both bodies and,
/// optionally, the worn profile of the bearing.
#[derive(Debug, Clone, PartialEq)]
pub struct RevoluteClearance {
    bearing_radius: f64,
    journal_radius: f64,
    bearing_centre: Vector2<f64>,
    journal_centre: Vector2<f64>,
    profile: Option<BearingProfile>,
}

/// The bearing surface at the contact: direction **u**_c from the bearing centre, radius ρ,
/// normal **n**, and the two projections whose difference with R_j is δ.
struct Surface {
    direction: Vector2<f64>,
    radius: f64,
    normal: Vector2<f64>,
    /// e projected on **n**: a e (cos Δ + s sin Δ) (e when Δ = s = 0), m.
    reach: f64,
    /// ρ projected on **n**: a ρ (ρ when s = 0), m.
    projected_radius: f64,
}

/// The line of centres of a revolute joint at one state, shared by the dry
/// ([`RevoluteClearance::contact`]) and the lubricated
/// ([`HydrodynamicBearing::kinematics`](crate::lubrication::HydrodynamicBearing::kinematics))
/// joint.
pub(crate) struct CentreLine {
    /// World position of the bearing centre r_i^P, m.
    pub(crate) bearing_centre: Vector2<f64>,
    /// World position of the journal centre r_j^P, m.
    pub(crate) journal_centre: Vector2<f64>,
    /// Eccentricity vector **e** = r_j^P − r_i^P, m.
    pub(crate) eccentricity_vector: Vector2<f64>,
    /// Eccentricity e = |**e**|, m.
    pub(crate) eccentricity: f64,
    /// True when the centres coincide (e → 0, or e not finite): **n** is undefined there.
    pub(crate) centred: bool,
    /// Unit normal **n** = **e**/e, the world x axis when `centred`.
    pub(crate) normal: Vector2<f64>,
}

impl CentreLine {
    /// From the local coordinates (m) of the bearing centre on body i and of the journal centre
    /// on body j, and the two body states.
    pub(crate) fn new(
        bearing_centre: Vector2<f64>,
        journal_centre: Vector2<f64>,
        bearing: &BodyState,
        journal: &BodyState,
    ) -> Self {
        let pi = bearing.point(bearing_centre);
        let pj = journal.point(journal_centre);
        let e_vec = pj - pi;
        let e = e_vec.norm();
        let centred = !(e > f64::MIN_POSITIVE && e.is_finite());
        // e/e is undefined at e = 0; the normal is irrelevant there (the dry joint has δ = −c < 0
        // and no force; the film force is written with εΩ, not Ω) but is kept a unit vector so
        // that downstream code never sees NaN.
        let normal = if centred {
            Vector2::new(1.0, 0.0)
        } else {
            e_vec / e
        };
        Self {
            bearing_centre: pi,
            journal_centre: pj,
            eccentricity_vector: e_vec,
            eccentricity: e,
            centred,
            normal,
        }
    }
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
    /// Unit vector from the bearing centre to the bearing contact point (world frame).
    contact_direction: Vector2<f64>,
    /// Orientation of the bearing body, rad.
    bearing_angle: f64,
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
        check_journal_fits(LAW, "R_i", bearing_radius, journal_radius)?;
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
            profile: None,
        })
    }

    /// The same joint with a worn bearing: surface ρ(φ) = R_i + h_w(φ), φ in the bearing body
    /// frame about the bearing centre (module docs). A zero profile reproduces the circular
    /// joint bit for bit.
    pub fn with_profile(mut self, profile: BearingProfile) -> Self {
        self.profile = Some(profile);
        self
    }

    /// The worn profile of the bearing (None: circular bearing of radius R_i).
    pub fn profile(&self) -> Option<&BearingProfile> {
        self.profile.as_ref()
    }

    /// Mutable access to the worn profile, e.g. for
    /// [`BearingProfile::add_scaled`] between simulated cycles.
    pub fn profile_mut(&mut self) -> Option<&mut BearingProfile> {
        self.profile.as_mut()
    }

    /// Replace (or, with None, remove) the worn profile.
    pub fn set_profile(&mut self, profile: Option<BearingProfile>) {
        self.profile = profile;
    }

    /// Radial clearance of the worn joint at the bearing-frame angle φ (rad):
    /// R_i + h_w(φ) − R_j, m (c without a profile).
    pub fn clearance_at(&self, angle: f64) -> f64 {
        match &self.profile {
            Some(p) => (self.bearing_radius + p.depth_at(angle)) - self.journal_radius,
            None => self.clearance(),
        }
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
    ///
    /// With a worn profile the contact is the nearest point of the worn surface (module docs);
    /// the circular joint is the case h_w = 0, computed by the same operations. No allocation.
    pub fn contact(&self, bearing: &BodyState, journal: &BodyState) -> RevoluteContact {
        let line = CentreLine::new(self.bearing_centre, self.journal_centre, bearing, journal);
        let (radial, e) = (line.normal, line.eccentricity);
        let surface = match &self.profile {
            None => Surface {
                direction: radial,
                radius: self.bearing_radius,
                normal: radial,
                reach: e,
                projected_radius: self.bearing_radius,
            },
            Some(profile) => self.worn_surface(profile, bearing.angle, radial, e),
        };
        let normal = surface.normal;
        let tangent = perp(normal);
        let qi = line.bearing_centre + surface.radius * surface.direction;
        let qj = line.journal_centre + self.journal_radius * normal;
        let v = journal.point_velocity(qj) - bearing.point_velocity(qi);
        RevoluteContact {
            eccentricity_vector: line.eccentricity_vector,
            eccentricity: e,
            penetration: surface.reach - (surface.projected_radius - self.journal_radius),
            normal,
            tangent,
            bearing_point: qi,
            journal_point: qj,
            normal_velocity: v.dot(&normal),
            tangential_velocity: v.dot(&tangent),
            bearing_reference: bearing.position,
            journal_reference: journal.position,
            contact_direction: surface.direction,
            bearing_angle: bearing.angle,
        }
    }

    /// The worn surface at the contact: nearest point φ_c = φ_e + Δ and the normal of the polar
    /// curve ρ(φ) there. With Δ = 0 and zero slope the circular quantities for the radius
    /// R_i + h_w(φ_e) are returned unchanged (no rotation, no normalization), which keeps the
    /// zero profile bit-identical to the circular joint (adding a zero correction could turn a
    /// −0 component into +0).
    fn worn_surface(
        &self,
        profile: &BearingProfile,
        bearing_angle: f64,
        radial: Vector2<f64>,
        e: f64,
    ) -> Surface {
        let local = rotate(-bearing_angle, radial);
        let phi_e = local.y.atan2(local.x);
        let near = profile.nearest(self.bearing_radius, e, phi_e);
        let rho = self.bearing_radius + near.depth;
        let slope = near.slope / rho;
        if near.offset == 0.0 && slope == 0.0 {
            return Surface {
                direction: radial,
                radius: rho,
                normal: radial,
                reach: e,
                projected_radius: rho,
            };
        }
        let (sin_d, cos_d) = near.offset.sin_cos();
        let direction = cos_d * radial + sin_d * perp(radial);
        let a = 1.0 / (1.0 + slope * slope).sqrt();
        Surface {
            direction,
            radius: rho,
            normal: a * (direction - slope * perp(direction)),
            reach: a * e * (cos_d + slope * sin_d),
            projected_radius: a * rho,
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

    /// Contact angle φ_c in the bearing body frame, rad in [0, 2π): direction of the bearing
    /// contact point r_i^Q from the bearing centre, measured from the bearing body's x axis.
    /// This is the angle to give [`ArchardWear`](crate::wear::ArchardWear) and where the
    /// [`BearingProfile`] is evaluated (φ_e, the direction of **e**, for a circular bearing).
    pub fn contact_angle(&self) -> f64 {
        let local = rotate(-self.bearing_angle, self.contact_direction);
        let angle = local.y.atan2(local.x).rem_euclid(std::f64::consts::TAU);
        // rem_euclid can round a tiny negative angle up to 2π
        if angle >= std::f64::consts::TAU {
            0.0
        } else {
            angle
        }
    }

    /// Every public quantity of the contact as one array, in the order **e** (x, y), e, δ,
    /// **n** (x, y), **t** (x, y), r_i^Q (x, y), r_j^Q (x, y), v_N, v_T and φ_c
    /// ([`contact_angle`](Self::contact_angle)): for comparing two contacts value by value
    /// (e.g. a worn bearing against the circular one).
    pub fn as_array(&self) -> [f64; 15] {
        [
            self.eccentricity_vector.x,
            self.eccentricity_vector.y,
            self.eccentricity,
            self.penetration,
            self.normal.x,
            self.normal.y,
            self.tangent.x,
            self.tangent.y,
            self.bearing_point.x,
            self.bearing_point.y,
            self.journal_point.x,
            self.journal_point.y,
            self.normal_velocity,
            self.tangential_velocity,
            self.contact_angle(),
        ]
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

// `LineContact::for_joint` lives here, not in `wear`, so that `wear` (which the joint's bearing
// profile comes from) does not import the joint back.
impl LineContact {
    /// The contact of `joint`'s radii over the length L (m) between the bearing and journal
    /// materials.
    ///
    /// # Errors
    /// As [`LineContact::new`] for L.
    pub fn for_joint(
        joint: &RevoluteClearance,
        length: f64,
        bearing: &crate::elastic::Material,
        journal: &crate::elastic::Material,
    ) -> Result<Self, ContactError> {
        Self::new(
            joint.bearing_radius(),
            joint.journal_radius(),
            length,
            bearing.try_composite_modulus(journal)?,
        )
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{PI, TAU};

    use super::*;
    use crate::damping::DampingFactor;
    use crate::elastic::{ElasticLaw, Material};
    use crate::wear::test_support::{argmin_on_circle, Rng};

    const RI: f64 = 10e-3;
    const RJ: f64 = 9.9e-3;
    const C: f64 = RI - RJ;

    fn v(x: f64, y: f64) -> Vector2<f64> {
        Vector2::new(x, y)
    }

    /// A random pair of bodies whose joint centres are `ecc` apart in a random direction
    /// (local centres si, sj on the bodies).
    fn random_state(
        rng: &mut Rng,
        si: Vector2<f64>,
        sj: Vector2<f64>,
        ecc: f64,
    ) -> (BodyState, BodyState) {
        let bearing = BodyState::new(
            v(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
            rng.range(-10.0, 10.0),
            v(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)),
            rng.range(-50.0, 50.0),
        );
        let dir = rng.range(0.0, TAU);
        let pj = bearing.point(si) + ecc * v(dir.cos(), dir.sin());
        let angle = rng.range(-10.0, 10.0);
        let journal = BodyState::new(
            pj - crate::body::rotate(angle, sj),
            angle,
            v(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)),
            rng.range(-50.0, 50.0),
        );
        (bearing, journal)
    }

    /// Every f64 of a contact and of the forces derived from it, as bits.
    fn bits(c: &RevoluteContact) -> Vec<u64> {
        let law = NormalLaw::new(
            ElasticLaw::hertz_internal_cylinder(&Material::steel(), RI, &Material::steel(), RJ)
                .unwrap(),
            DampingFactor::LankaraniNikravesh,
            0.5,
        )
        .unwrap();
        let friction = FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap();
        let mut out = c.as_array().to_vec();
        for app in [
            ForceApplication::ContactPoints,
            ForceApplication::CommonPoint,
        ] {
            let f = c.forces_from_laws_with(&law, &friction, 0.5, app);
            out.extend(f.bearing.as_array());
            out.extend(f.journal.as_array());
            out.push(f.normal_force);
            out.push(f.tangential_force);
        }
        out.into_iter().map(f64::to_bits).collect()
    }

    /// The "done when": a worn bearing with zero wear reproduces the circular joint bit
    /// for bit, over 20 000 random states (half in contact, e up to 2c) with off-centre joint
    /// centres, plus degenerate ones (coincident centres, signed zeros).
    #[test]
    fn zero_profile_is_bit_identical_to_circular_joint() {
        let mut rng = Rng(0x5eed);
        for n in [8, 360, 4096] {
            for k in 0..20_000 / 3 {
                let (si, sj) = if k % 2 == 0 {
                    (v(0.0, 0.0), v(0.0, 0.0))
                } else {
                    (
                        v(rng.range(-0.1, 0.1), 0.02),
                        v(-0.05, rng.range(-0.1, 0.1)),
                    )
                };
                let circle = RevoluteClearance::new(RI, RJ, si, sj).unwrap();
                let worn = circle
                    .clone()
                    .with_profile(BearingProfile::zero(n).unwrap());
                let ecc = rng.range(0.0, 2.0 * C);
                let (bi, bj) = random_state(&mut rng, si, sj, ecc);
                let (a, b) = (circle.contact(&bi, &bj), worn.contact(&bi, &bj));
                assert_eq!(bits(&a), bits(&b), "state {k}: {bi:?} {bj:?}");
            }
        }
        // coincident centres and signed zeros
        let circle = RevoluteClearance::new(RI, RJ, v(0.0, 0.0), v(0.0, 0.0)).unwrap();
        let worn = circle
            .clone()
            .with_profile(BearingProfile::zero(16).unwrap());
        for (pi, pj) in [
            (v(0.0, 0.0), v(0.0, 0.0)),
            (v(0.0, 0.0), v(-0.0, 1.2e-4)),
            (v(0.0, -0.0), v(-0.0, -1.0e-4)),
            (v(0.0, 0.0), v(-1.05e-4, -0.0)),
        ] {
            let bi = BodyState::new(pi, 0.0, v(0.1, -0.0), 0.0);
            let bj = BodyState::new(pj, -0.0, v(-0.0, 0.3), -0.0);
            let (a, b) = (circle.contact(&bi, &bj), worn.contact(&bi, &bj));
            assert_eq!(bits(&a), bits(&b), "{pi:?} {pj:?}");
        }
    }

    /// A uniformly worn bearing of depth h is a circular bearing of radius R_i + h (the issue asks
    /// 1e-15 relative; the arithmetic is the same, so the results are identical).
    #[test]
    fn uniform_profile_is_a_larger_circle() {
        let mut rng = Rng(42);
        for h in [1e-9, 3e-6, 2.5e-5] {
            let worn = RevoluteClearance::new(RI, RJ, v(0.0, 0.0), v(0.01, 0.0))
                .unwrap()
                .with_profile(BearingProfile::uniform(720, h).unwrap());
            let circle = RevoluteClearance::new(RI + h, RJ, v(0.0, 0.0), v(0.01, 0.0)).unwrap();
            for _ in 0..5000 {
                let ecc = rng.range(0.0, 2.0 * (C + h));
                let (bi, bj) = random_state(&mut rng, v(0.0, 0.0), v(0.01, 0.0), ecc);
                let (a, b) = (circle.contact(&bi, &bj), worn.contact(&bi, &bj));
                for (x, y) in bits(&a).into_iter().zip(bits(&b)) {
                    let (x, y) = (f64::from_bits(x), f64::from_bits(y));
                    assert!((x - y).abs() <= 1e-15 * x.abs(), "{h}: {x} vs {y}");
                }
            }
            assert_eq!(worn.clearance_at(1.0), circle.clearance());
        }
    }

    /// Where the bearing is unworn in the direction of e, the joint is the circular one exactly
    /// (the nearest surface point is on the unworn circle), wear elsewhere notwithstanding.
    #[test]
    fn unworn_direction_is_circular() {
        let scar = BearingProfile::from_fn(360, |x| {
            let d = (x - 1.5 * PI + PI).rem_euclid(TAU) - PI;
            if d.abs() < 0.3 {
                2e-5 * (1.0 - (d / 0.3).powi(2))
            } else {
                0.0
            }
        })
        .unwrap();
        let circle = RevoluteClearance::new(RI, RJ, v(0.0, 0.0), v(0.0, 0.0)).unwrap();
        let worn = circle.clone().with_profile(scar);
        let mut rng = Rng(9);
        for _ in 0..2000 {
            let dir: f64 = rng.range(-0.5 * PI, 0.5 * PI) * 0.9 + 0.5 * PI; // upper half, unworn
            let bi = BodyState::fixed(v(0.0, 0.0), 0.0);
            let e = rng.range(0.5 * C, 1.2 * C);
            let bj = BodyState::new(e * v(dir.cos(), dir.sin()), 0.3, v(0.2, -0.1), 40.0);
            assert_eq!(
                bits(&circle.contact(&bi, &bj)),
                bits(&worn.contact(&bi, &bj))
            );
        }
    }

    /// Profile h = h0 (1 + cos 2φ) on a rotated, moving bearing: the contact normal against the
    /// closed-form normal of the polar curve ρ = R_i + h (n ∝ ρ u − ρ′ k̂×u at the contact angle),
    /// the bearing point on the curve, r_j^Q − r_i^Q = δ n, and δ against an independent
    /// brute-force distance from the journal centre to the analytic curve (2·10⁵ samples +
    /// golden section). Tolerances from the interpolation error at N = 720 (depth ≈ 1e-7 h0 =
    /// 5e-13 m, slope ≈ 8h0Δφ²/6 = 5e-10 m/rad, so s = ρ′/ρ errs by 5e-8): normal 1e-7, radius
    /// and δ 1e-12 m, δ n closure 1e-14 m. Measured: 4.1e-8, 4.2e-13 m, 4.2e-13 m, 1e-16 m.
    #[test]
    fn cos2_profile_normal_and_penetration_match_closed_form() {
        let h0 = 5e-6;
        let shape = |x: f64| {
            (
                RI + h0 * (1.0 + (2.0 * x).cos()),
                -2.0 * h0 * (2.0 * x).sin(),
            )
        };
        let worn = RevoluteClearance::new(RI, RJ, v(0.01, 0.02), v(0.0, 0.0))
            .unwrap()
            .with_profile(BearingProfile::from_fn(720, |x| shape(x).0 - RI).unwrap());
        let mut rng = Rng(77);
        for _ in 0..40 {
            let ecc = rng.range(0.9, 1.2) * C;
            let (bi, bj) = random_state(&mut rng, v(0.01, 0.02), v(0.0, 0.0), ecc);
            let c = worn.contact(&bi, &bj);
            let phi = c.contact_angle();
            let (rho, drho) = shape(phi);
            let u = bi.rotate(v(phi.cos(), phi.sin()));
            let n_ref = (rho * u - drho * perp(u)).normalize();
            assert!(
                (c.normal - n_ref).norm() < 1e-7,
                "{:?} {:?}",
                c.normal,
                n_ref
            );
            let pi = bi.point(worn.bearing_centre());
            assert!(((c.bearing_point - pi).norm() - rho).abs() < 1e-12);
            let gap = c.journal_point - c.bearing_point - c.penetration * c.normal;
            assert!(gap.norm() < 1e-14, "{gap:?}");
            // brute force: distance from the journal centre to the analytic curve
            let pj = bj.point(worn.journal_centre());
            let d = |x: f64| (pi + bi.rotate(shape(x).0 * v(x.cos(), x.sin())) - pj).norm();
            let delta_ref = RJ - d(argmin_on_circle(d, 200_000));
            assert!(
                (c.penetration - delta_ref).abs() < 1e-12,
                "{} vs {}",
                c.penetration,
                delta_ref
            );
        }
    }

    /// v_N = δ̇ also on a worn surface (the nearest point of a rigidly moving curve to a moving
    /// point moves tangentially): central differences of δ along a smooth trajectory of both
    /// bodies, step 1e-6 s, relative 1e-6 (truncation O(τ² δ⃛) ≈ 1e-8 relative).
    #[test]
    fn normal_velocity_is_penetration_rate_on_worn_surface() {
        let worn = RevoluteClearance::new(RI, RJ, v(0.02, 0.0), v(-0.01, 0.0))
            .unwrap()
            .with_profile(
                BearingProfile::from_fn(720, |x| {
                    4e-6 * (1.0 + (2.0 * x).cos() + 0.5 * (3.0 * x).sin().powi(2))
                })
                .unwrap(),
            );
        let state = |t: f64| {
            let bi = BodyState::new(
                v(0.1 * t, 0.05 * (3.0 * t).sin()),
                0.4 + 2.0 * t,
                v(0.1, 0.15 * (3.0 * t).cos()),
                2.0,
            );
            let psi = 1.0 + 7.0 * t;
            let ecc = C + 1e-5 * (1.0 + (5.0 * t).sin());
            let dpsi = 7.0;
            let decc = 5e-5 * (5.0 * t).cos();
            let th = -0.3 + 30.0 * t;
            let sj = crate::body::rotate(th, v(-0.01, 0.0));
            let ci = bi.point(v(0.02, 0.0));
            let u = v(psi.cos(), psi.sin());
            let centre = ci + ecc * u;
            // velocity of the journal centre: ċ_i + ė u + e ψ̇ k̂×u; reference point = centre − A s′
            let dci = bi.point_velocity(ci);
            let dcentre = dci + decc * u + ecc * dpsi * perp(u);
            let bj = BodyState::new(centre - sj, th, dcentre - 30.0 * perp(sj), 30.0);
            (bi, bj)
        };
        let tau = 1e-6;
        for i in 0..200 {
            let t = 0.013 * i as f64;
            let (bi, bj) = state(t);
            let c = worn.contact(&bi, &bj);
            let (b1, j1) = state(t + tau);
            let (b0, j0) = state(t - tau);
            let rate = (worn.contact(&b1, &j1).penetration - worn.contact(&b0, &j0).penetration)
                / (2.0 * tau);
            assert!(
                (c.normal_velocity - rate).abs() <= 1e-6 * rate.abs().max(1e-4),
                "t = {t}: v_N = {} vs δ̇ = {rate}",
                c.normal_velocity
            );
        }
    }

    #[test]
    fn contact_angle_is_direction_of_e_in_bearing_frame() {
        let joint = RevoluteClearance::new(RI, RJ, v(0.0, 0.0), v(0.0, 0.0)).unwrap();
        let bi = BodyState::fixed(v(1.0, 2.0), 0.5);
        for psi in [0.0f64, 0.3, 2.0, 4.0, 6.2] {
            let bj = BodyState::fixed(v(1.0, 2.0) + 1e-4 * v(psi.cos(), psi.sin()), 0.0);
            let phi = joint.contact(&bi, &bj).contact_angle();
            let expected = (psi - 0.5f64).rem_euclid(TAU);
            assert!((phi - expected).abs() < 1e-12, "{phi} vs {expected}");
            assert!((0.0..TAU).contains(&phi));
        }
    }
}
