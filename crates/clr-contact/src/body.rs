//! Planar rigid-body state and generalized forces shared by the clearance-joint kinematics.
//!
//! A planar body k has a reference point at `position` r_k (m), an orientation φ_k (rad,
//! counter-clockwise), a velocity ṙ_k (m/s) and an angular velocity ω_k (rad/s). A point fixed on
//! the body with local coordinates s′ sits at r = r_k + A(φ_k) s′ and moves with
//! ṙ = ṙ_k + ω_k k̂ × (r − r_k) (Nikravesh, *Computer-Aided Analysis of Mechanical Systems*,
//! Prentice Hall 1988, ch. 4; Flores et al., *Kinematics and Dynamics of Multibody Systems with
//! Imperfect Joints*, Springer 2008, eqs. 2.1–2.10).

/// Re-export of the planar vector type used throughout the API, so that users need not depend on
/// the same nalgebra version themselves.
pub use nalgebra::Vector2;

/// State of a planar rigid body in absolute coordinates (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyState {
    /// Position of the body's reference point in the world frame, m.
    pub position: Vector2<f64>,
    /// Orientation of the body frame, rad, counter-clockwise from the world x axis.
    pub angle: f64,
    /// Velocity of the reference point, m/s.
    pub velocity: Vector2<f64>,
    /// Angular velocity, rad/s, counter-clockwise positive.
    pub angular_velocity: f64,
}

impl Default for BodyState {
    fn default() -> Self {
        Self::fixed(Vector2::zeros(), 0.0)
    }
}

impl BodyState {
    /// A body at rest at `position` (m) with orientation `angle` (rad) — e.g. the ground.
    pub fn fixed(position: Vector2<f64>, angle: f64) -> Self {
        Self {
            position,
            angle,
            velocity: Vector2::zeros(),
            angular_velocity: 0.0,
        }
    }

    /// A moving body from its four state entries (m, rad, m/s, rad/s).
    pub fn new(
        position: Vector2<f64>,
        angle: f64,
        velocity: Vector2<f64>,
        angular_velocity: f64,
    ) -> Self {
        Self {
            position,
            angle,
            velocity,
            angular_velocity,
        }
    }

    /// A(φ) s′: a body-fixed vector (local coordinates) expressed in the world frame.
    pub fn rotate(&self, local: Vector2<f64>) -> Vector2<f64> {
        rotate(self.angle, local)
    }

    /// World position r_k + A(φ_k) s′ of the body-fixed point with local coordinates `local`, m.
    pub fn point(&self, local: Vector2<f64>) -> Vector2<f64> {
        self.position + self.rotate(local)
    }

    /// Local coordinates Aᵀ(φ_k)(r − r_k) of the world point `world`, m.
    pub fn to_local(&self, world: Vector2<f64>) -> Vector2<f64> {
        rotate(-self.angle, world - self.position)
    }

    /// Velocity ṙ_k + ω_k k̂ × (r − r_k) of the body's material point currently at `world`, m/s.
    pub fn point_velocity(&self, world: Vector2<f64>) -> Vector2<f64> {
        self.velocity + self.angular_velocity * perp(world - self.position)
    }

    /// Generalized force of a force `force` (N) applied at the world point `at` (m), reduced to the
    /// body's reference point: (f, (r − r_k) × f).
    pub fn generalized_force(&self, at: Vector2<f64>, force: Vector2<f64>) -> GeneralizedForce {
        GeneralizedForce::at(self.position, at, force)
    }
}

/// Planar generalized force on a body about its reference point: Q = [f; m].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GeneralizedForce {
    /// Force (f_x, f_y), N.
    pub force: Vector2<f64>,
    /// Moment about the body's reference point, N·m, counter-clockwise positive.
    pub moment: f64,
}

impl GeneralizedForce {
    /// The zero generalized force.
    pub fn zero() -> Self {
        Self::default()
    }

    /// A force `force` (N) applied at the world point `at` (m), reduced to the reference point
    /// `reference` (m): (f, (at − reference) × f).
    pub fn at(reference: Vector2<f64>, at: Vector2<f64>, force: Vector2<f64>) -> Self {
        Self {
            force,
            moment: cross(at - reference, force),
        }
    }

    /// As the array (f_x, f_y, m) in N, N, N·m.
    pub fn as_array(&self) -> [f64; 3] {
        [self.force.x, self.force.y, self.moment]
    }
}

impl core::ops::Add for GeneralizedForce {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        Self {
            force: self.force + rhs.force,
            moment: self.moment + rhs.moment,
        }
    }
}

impl core::ops::AddAssign for GeneralizedForce {
    fn add_assign(&mut self, rhs: Self) {
        self.force += rhs.force;
        self.moment += rhs.moment;
    }
}

/// A(φ) v for the planar rotation matrix A(φ) = [cos φ, −sin φ; sin φ, cos φ].
pub fn rotate(angle: f64, v: Vector2<f64>) -> Vector2<f64> {
    let (s, c) = angle.sin_cos();
    Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// k̂ × v = (−v_y, v_x): `v` turned a quarter turn counter-clockwise.
pub fn perp(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v.y, v.x)
}

/// Planar cross product a × b = a_x b_y − a_y b_x (the k̂ component).
pub fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// A point contact between a slider and a guide surface (translational joint corners and
/// multipoint contacts share it). SI units, world frame.
///
/// Conventions (`contact-laws.md` §3.1): **n** is the direction in which the slider penetrates
/// the guide, **t** = k̂ × **n**, v_N = (ṙ_slider − ṙ_guide)·**n** = δ̇ (> 0 approaching),
/// v_T = (ṙ_slider − ṙ_guide)·**t**; the force on the slider is −F_N **n** + F_T **t**.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointContact {
    /// Penetration δ > 0, m.
    pub penetration: f64,
    /// Unit normal **n**, the direction of penetration of the slider.
    pub normal: Vector2<f64>,
    /// Unit tangent **t** = k̂ × **n**.
    pub tangent: Vector2<f64>,
    /// Contact point on the slider, m.
    pub slider_point: Vector2<f64>,
    /// Contact point on the guide, m.
    pub guide_point: Vector2<f64>,
    /// v_N = δ̇, m/s (> 0 approaching).
    pub normal_velocity: f64,
    /// v_T, m/s.
    pub tangential_velocity: f64,
}

impl PointContact {
    /// Build from δ (m), **n**, the two contact points (m) and the relative velocity
    /// ṙ_slider − ṙ_guide (m/s) of the contact points.
    pub fn new(
        penetration: f64,
        normal: Vector2<f64>,
        slider_point: Vector2<f64>,
        guide_point: Vector2<f64>,
        relative_velocity: Vector2<f64>,
    ) -> Self {
        let tangent = perp(normal);
        Self {
            penetration,
            normal,
            tangent,
            slider_point,
            guide_point,
            normal_velocity: relative_velocity.dot(&normal),
            tangential_velocity: relative_velocity.dot(&tangent),
        }
    }

    /// Force on the slider −F_N **n** + F_T **t** (N) from F_N ≥ 0 and the signed F_T (N).
    pub fn slider_force(&self, normal_force: f64, tangential_force: f64) -> Vector2<f64> {
        -normal_force * self.normal + tangential_force * self.tangent
    }
}

/// Check that every `(name, value)` is finite.
pub(crate) fn check_finite(
    law: &'static str,
    fields: &[(&'static str, f64)],
) -> Result<(), crate::ContactError> {
    match fields.iter().find(|(_, v)| !v.is_finite()) {
        Some(&(name, v)) => Err(crate::ContactError::invalid(law, name, v, "must be finite")),
        None => Ok(()),
    }
}

/// Check that a journal of radius R_j fits its bearing of radius `bearing_radius` (named
/// `bearing_symbol`, e.g. "R_i"), leaving a positive clearance.
pub(crate) fn check_journal_fits(
    law: &'static str,
    bearing_symbol: &str,
    bearing_radius: f64,
    journal_radius: f64,
) -> Result<(), crate::ContactError> {
    if journal_radius >= bearing_radius {
        return Err(crate::ContactError::invalid(
            law,
            "journal radius R_j (m)",
            journal_radius,
            format!("must be smaller than the bearing radius {bearing_symbol} = {bearing_radius} m so that the clearance {bearing_symbol} - R_j is positive"),
        ));
    }
    Ok(())
}

/// Check that every `(name, value)` is positive and finite.
pub(crate) fn check_positive(
    law: &'static str,
    fields: &[(&'static str, f64)],
) -> Result<(), crate::ContactError> {
    fields
        .iter()
        .try_for_each(|&(name, v)| crate::error::positive(law, name, v).map(|_| ()))
}
