//! Spatial journal-in-bearing clearance joint (revolute and cylindrical): the geometry of a
//! tilted journal of finite length in a bore of finite length, and its contact forces as a
//! distributed line contact along the overlap (`docs/contact.md`, "Spatial journal in bearing").
//!
//! The contact scenarios are those of Marques, Isaac, Dourado & Flores, Mech. Mach. Theory 116
//! (2017) 123–144 (radial and axial clearance) and Tian, Liu, Machado & Flores, Nonlinear Dyn. 64
//! (2011) 25–47 (cylindrical joints with misalignment); the section-based formulation below is
//! this crate's (derivations in `docs/contact.md`), reducing without tilt to the planar joint of
//! Flores, Ambrósio, Claro & Lankarani, Comput. Struct. 82 (2004) 1359–1369.
//!
//! SI units throughout. Bearing (bore) on body i: centre O_b, unit axis u_b, radius R_b, length
//! L_b; journal on body j: centre O_j, unit axis u_j, radius R_j < R_b, length L_j; radial
//! clearance c = R_b − R_j. The tilt γ is the angle between u_j and u_b (u_j is flipped so that
//! cos γ = u_b·u_j > 0; a cylinder has no preferred end).
//!
//! # Radial contact
//! With d = O_j − O_b, a = d·u_b, e₀ = d − a u_b, w = u_j − cos γ u_b and t = w / cos γ, the
//! journal axis meets the bore plane at the bore-axial coordinate z in the radial offset
//! e(z) = e₀ + (z − a) t (linear in z). The journal's cross-section in that plane is the ellipse
//! X − C(z) = R_j E(m), E(m) = m − (m·u_b)/cos γ · u_j over the unit vectors m ⟂ u_j (semi-axes
//! R_j and R_j / cos γ, the long one along w). The penetration is
//! δ(z) = max_m |e(z) + R_j E(m)| − R_b, the deepest point found by Newton's method on the angle of
//! m, started from the direction of e(z) (at γ = 0 it is |e| + R_j − R_b, the planar e − c). The
//! normal is the bore's radial direction n = r/|r| at the deepest point r, ⟂ u_b. δ(z) is convex
//! (a maximum of convex functions of an affine e(z)), so the wetted set {δ > 0} is the overlap
//! minus one interval: at most a region A at low z and a region B at high z.
//!
//! The overlap runs between the bore's ends z = ±L_b/2 and the journal's ends, where the deepest
//! point of the cross-section lies on the journal's end circle, s = ±L_j/2 along u_j (found by a
//! fixed-point iteration z ← z − cos γ (s(z) − s_end), contraction ≈ R_j γ²/c). The overlap is
//! split at the minimiser of δ (safeguarded secant on δ′ = n·t); the wetted ends are the roots of δ
//! (a safeguarded Newton iteration started from the quadratic |e(z)|² = c²: the ellipse contains
//! the circle of radius R_j, so that start lies on the wetted side).
//!
//! The force per unit length is p(z) = F_N(δ(z), δ̇(z), δ̇⁻)/L_c with L_c = min(L_b, L_j) and δ̇
//! = v·n the approach rate of the deepest points, integrated over each wetted region with a
//! fixed-order Gauss–Legendre rule after the substitution z = z_in + (z_out − z_in)u², which
//! clusters the nodes at the wetted region's inner end, where p ∝ δ^n vanishes like a power: the
//! force is continuous as regions open, shrink to a rim and merge, and without tilt it is F_N(δ)
//! exactly up to rounding (the planar [`crate::revolute`] joint). On the journal the line load is
//! −p n plus friction at the midpoint of the contact pair and the axial part p δ′ u_b at the
//! journal's deepest point: −p (n − δ′ u_b) lies along the journal's surface normal there, and with
//! ∂δ/∂t = n·v − δ′ u_b·v_rel at fixed z it makes the elastic force the gradient of the stored
//! energy W = ∫ Φ(δ) dz / L_c (Φ = ∫ F_e dδ). A wetted region that ends at a journal end adds
//! the generalized force −(±Φ(δ_end)/L_c) ∇z_end (W changes with the end's position z_end): a
//! force pair and moments from the pose gradient of the end, by the implicit-function rule on its
//! defining equation with forward-mode numbers over the scalar type. It cancels the slope term's
//! axial part when the journal slides along a rim (a cylinder sliding in a cylinder stores
//! nothing). So the elastic
//! contact is conservative and the reported dissipation −P − dW/dt is that of damping and
//! friction. Friction acts at every Gauss point in the tangent plane against the slip of the
//! deepest points (rotation and axial sliding), with the magnitude of a [`FrictionLaw`] at |v_t|.
//! The bearing receives the opposite forces at the same points, so the pair conserves angular
//! momentum exactly.
//!
//! # Thrust faces (revolute kind)
//! The journal carries a collar on each side whose face (⟂ u_j, outer radius R_t) sits at
//! s = −k h on the journal axis, h = (L_b + c_a)/2, against the bearing's end face z = −k L_b/2
//! (k = +1 stops motion along +u_b). The deepest point of the tilted collar circle is
//! X_k = O_j − k h u_j + R_t k (u_b − cos γ u_j)/sin γ, and
//! δ_t,k = k a − h cos γ + L_b/2 + R_t sin γ = k a − c_a/2 + h (1 − cos γ) + R_t sin γ (the
//! group's gap). The face is a ring law along the collar circle
//! X(φ) = O_j − k h u_j + R_t (cos φ e₁ + sin φ e₂), e₁ towards the deepest point:
//! δ(φ) = δ₀ + R_t sin γ cos φ with δ₀ = k a − c_a/2 + h (1 − cos γ), force per unit arc
//! F_N(δ(φ))/(2π R_t) along n = k u_b and friction in the face plane, over the analytic wetted
//! arc |φ| < φ_e = acos(−δ₀/(R_t sin γ)) (π for the full ring), each half by the same
//! Gauss–Legendre rule after φ = ±φ_e (1 − u²). Without tilt the total is F_N(δ); force and
//! moment are continuous through γ = 0 and as the arc closes; W = ∫ Φ(δ(φ)) dφ/2π over the
//! ring's material points, so the face is conservative.
//!
//! # Genericity
//! The geometry and forces are written over a scalar type [`Real`] (implemented for f64) so that
//! the same code runs in forward-mode dual numbers for analytic Jacobians; the laws enter through
//! [`NormalLaw::force_with_derivatives`] and [`FrictionLaw::force_with_derivatives`] and
//! [`Real::chain2`]. Nothing here allocates.

use std::ops::{Add, Div, Mul, Neg, Sub};

use nalgebra::Vector3;

use crate::error::ContactError;
use crate::friction::{FrictionLaw, LuGre};
use crate::memory::ContactMemory;
use crate::normal::NormalLaw;

/// Largest Gauss–Legendre order a [`JournalClearance`] accepts.
pub const MAX_ORDER: usize = 32;

/// Default Gauss–Legendre order per wetted region, from the convergence study in
/// `docs/contact.md` (relative error below 1e-8 against a 200-point reference for the laws of the
/// crate, Hertz n = 3/2 included).
pub const DEFAULT_ORDER: usize = 10;

/// Number of contact groups (and contact-memory slots) of a joint: radial A, radial B,
/// thrust −, thrust +.
pub const GROUPS: usize = 4;

/// Index of the radial region at the low-z end of the bore (end A).
pub const RADIAL_A: usize = 0;
/// Index of the radial region at the high-z end of the bore (end B).
pub const RADIAL_B: usize = 1;
/// Index of the thrust face that stops the journal moving along −u_b.
pub const THRUST_MINUS: usize = 2;
/// Index of the thrust face that stops the journal moving along +u_b.
pub const THRUST_PLUS: usize = 3;

/// Largest tilt the joint accepts, rad (cos γ ≥ 1/2): beyond it the journal lies across the bore,
/// which no clearance joint describes.
pub const MAX_TILT: f64 = std::f64::consts::FRAC_PI_3;

/// Errors of the spatial journal-bearing joint.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum JournalError {
    /// A geometric parameter or law is invalid.
    #[error(transparent)]
    Contact(#[from] ContactError),
    /// LuGre friction was asked for: its bristle states are not carried by this joint.
    #[error("spatial journal-bearing joint: LuGre friction is not supported (its bristle state per Gauss point is not carried); use a stateless friction law (coulomb, ambrosio, threlfall, stribeck)")]
    LuGreUnsupported,
    /// The journal axis is tilted too far against the bore axis.
    #[error("spatial journal-bearing joint: the journal axis is tilted by {tilt_deg}° against the bearing axis (at most 60°); check the joint axes of both bodies")]
    Tilt {
        /// The tilt, degrees.
        tilt_deg: f64,
    },
    /// A pose or velocity is not finite.
    #[error("spatial journal-bearing joint: the state has a non-finite {what}")]
    NonFinite {
        /// Which input.
        what: &'static str,
    },
}

/// A scalar the journal geometry is evaluated in: f64, or a forward-mode dual number that carries
/// derivatives. Only [`value`](Real::value) is used for branching; everything else chains.
pub trait Real:
    Copy
    + std::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// A constant.
    fn from_f64(v: f64) -> Self;
    /// The value (for branching and reports).
    fn value(&self) -> f64;
    /// f(self), given f = f(value) and f′ = df/dx at the value (the chain rule).
    fn chain(self, f: f64, df: f64) -> Self;
    /// f(a, b), given f and its partial derivatives ∂f/∂a, ∂f/∂b at the values: how a law's
    /// `force_with_derivatives` enters the scalar.
    fn chain2(a: Self, b: Self, f: f64, dfa: f64, dfb: f64) -> Self;
    /// √self.
    fn sqrt(self) -> Self {
        let r = self.value().sqrt();
        self.chain(r, 0.5 / r)
    }
    /// sin(self).
    fn sin(self) -> Self {
        let (s, c) = self.value().sin_cos();
        self.chain(s, c)
    }
    /// cos(self).
    fn cos(self) -> Self {
        let (s, c) = self.value().sin_cos();
        self.chain(c, -s)
    }
}

impl Real for f64 {
    #[inline]
    fn from_f64(v: f64) -> Self {
        v
    }
    #[inline]
    fn value(&self) -> f64 {
        *self
    }
    #[inline]
    fn chain(self, f: f64, _df: f64) -> Self {
        f
    }
    #[inline]
    fn chain2(_a: Self, _b: Self, f: f64, _dfa: f64, _dfb: f64) -> Self {
        f
    }
}

/// A 3-vector of [`Real`] scalars (world frame; unit as its contents).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct V3<S>(pub [S; 3]);

impl<S: Real> V3<S> {
    /// From components.
    pub fn new(x: S, y: S, z: S) -> Self {
        Self([x, y, z])
    }
    /// A constant vector.
    pub fn constant(v: &Vector3<f64>) -> Self {
        Self([S::from_f64(v.x), S::from_f64(v.y), S::from_f64(v.z)])
    }
    /// The zero vector.
    pub fn zero() -> Self {
        Self([S::from_f64(0.0); 3])
    }
    /// The value.
    pub fn value(&self) -> Vector3<f64> {
        Vector3::new(self.0[0].value(), self.0[1].value(), self.0[2].value())
    }
    /// Scalar product.
    pub fn dot(&self, o: &Self) -> S {
        self.0[0] * o.0[0] + self.0[1] * o.0[1] + self.0[2] * o.0[2]
    }
    /// Cross product self × o.
    pub fn cross(&self, o: &Self) -> Self {
        let (a, b) = (self.0, o.0);
        Self([
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ])
    }
    /// Euclidean norm.
    pub fn norm(&self) -> S {
        self.dot(self).sqrt()
    }
    /// self · k.
    pub fn scale(&self, k: S) -> Self {
        Self(self.0.map(|c| c * k))
    }
    /// self · k for a constant k.
    pub fn scale_f(&self, k: f64) -> Self {
        self.scale(S::from_f64(k))
    }
}

impl<S: Real> Add for V3<S> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self([self.0[0] + o.0[0], self.0[1] + o.0[1], self.0[2] + o.0[2]])
    }
}
impl<S: Real> Sub for V3<S> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self([self.0[0] - o.0[0], self.0[1] - o.0[1], self.0[2] - o.0[2]])
    }
}
impl<S: Real> Neg for V3<S> {
    type Output = Self;
    fn neg(self) -> Self {
        Self(self.0.map(|c| -c))
    }
}

/// Poses and velocities of the two bodies at the joint, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JournalState<S> {
    /// Bore centre O_b, m.
    pub bearing_centre: V3<S>,
    /// Bore axis u_b (normalized here), –.
    pub bearing_axis: V3<S>,
    /// Velocity of the bearing body's material point at O_b, m/s.
    pub bearing_velocity: V3<S>,
    /// Angular velocity of the bearing body, rad/s.
    pub bearing_angular_velocity: V3<S>,
    /// Journal centre O_j, m.
    pub journal_centre: V3<S>,
    /// Journal axis u_j (normalized here), –.
    pub journal_axis: V3<S>,
    /// Velocity of the journal body's material point at O_j, m/s.
    pub journal_velocity: V3<S>,
    /// Angular velocity of the journal body, rad/s.
    pub journal_angular_velocity: V3<S>,
}

impl JournalState<f64> {
    /// The f64 state from nalgebra vectors: bore centre (m), bore axis, velocity of the bearing
    /// body at O_b (m/s), its angular velocity (rad/s), and the same four for the journal.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        bearing_centre: Vector3<f64>,
        bearing_axis: Vector3<f64>,
        bearing_velocity: Vector3<f64>,
        bearing_angular_velocity: Vector3<f64>,
        journal_centre: Vector3<f64>,
        journal_axis: Vector3<f64>,
        journal_velocity: Vector3<f64>,
        journal_angular_velocity: Vector3<f64>,
    ) -> Self {
        Self {
            bearing_centre: V3::constant(&bearing_centre),
            bearing_axis: V3::constant(&bearing_axis),
            bearing_velocity: V3::constant(&bearing_velocity),
            bearing_angular_velocity: V3::constant(&bearing_angular_velocity),
            journal_centre: V3::constant(&journal_centre),
            journal_axis: V3::constant(&journal_axis),
            journal_velocity: V3::constant(&journal_velocity),
            journal_angular_velocity: V3::constant(&journal_angular_velocity),
        }
    }
}

impl<S: Real> JournalState<S> {
    fn bearing_point_velocity(&self, x: &V3<S>) -> V3<S> {
        self.bearing_velocity
            + self
                .bearing_angular_velocity
                .cross(&(*x - self.bearing_centre))
    }
    fn journal_point_velocity(&self, x: &V3<S>) -> V3<S> {
        self.journal_velocity
            + self
                .journal_angular_velocity
                .cross(&(*x - self.journal_centre))
    }
    /// The unit axes u_b and u_j (u_j flipped so that cos γ = u_b·u_j > 0), cos γ,
    /// w = u_j − cos γ u_b and the tilt γ (rad).
    ///
    /// # Errors
    /// [`JournalError::Tilt`] for a tilt over [`MAX_TILT`].
    pub(crate) fn axes(&self) -> Result<Axes<S>, JournalError> {
        let ub = self
            .bearing_axis
            .scale(S::from_f64(1.0) / self.bearing_axis.norm());
        let mut uj = self
            .journal_axis
            .scale(S::from_f64(1.0) / self.journal_axis.norm());
        if ub.dot(&uj).value() < 0.0 {
            uj = -uj;
        }
        let cg = ub.dot(&uj);
        let w = uj - ub.scale(cg);
        let tilt = w.value().norm().atan2(cg.value());
        if tilt.is_nan() || tilt > MAX_TILT {
            return Err(JournalError::Tilt {
                tilt_deg: tilt.to_degrees(),
            });
        }
        Ok(Axes {
            ub,
            uj,
            cg,
            w,
            tilt,
        })
    }

    pub(crate) fn all_finite(&self) -> Result<(), JournalError> {
        let check = |v: &V3<S>, what| {
            if v.value().iter().all(|c| c.is_finite()) {
                Ok(())
            } else {
                Err(JournalError::NonFinite { what })
            }
        };
        check(&self.bearing_centre, "bearing centre")?;
        check(&self.bearing_axis, "bearing axis")?;
        check(&self.bearing_velocity, "bearing velocity")?;
        check(&self.bearing_angular_velocity, "bearing angular velocity")?;
        check(&self.journal_centre, "journal centre")?;
        check(&self.journal_axis, "journal axis")?;
        check(&self.journal_velocity, "journal velocity")?;
        check(&self.journal_angular_velocity, "journal angular velocity")
    }
}

/// The axes of a state ([`JournalState::axes`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Axes<S> {
    pub ub: V3<S>,
    pub uj: V3<S>,
    pub cg: S,
    pub w: V3<S>,
    pub tilt: f64,
}

/// Thrust faces of the revolute kind.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Thrust {
    /// Total end play c_a, m.
    axial_clearance: f64,
    /// Outer radius R_t of the collar face, m.
    radius: f64,
}

/// Geometry of a spatial journal-in-bearing clearance joint (module docs), validated.
#[derive(Debug, Clone, PartialEq)]
pub struct JournalClearance {
    bearing_radius: f64,
    bearing_length: f64,
    journal_radius: f64,
    journal_length: f64,
    thrust: Option<Thrust>,
    order: usize,
    /// Gauss–Legendre nodes and weights on [0, 1] (the first `order` are used).
    nodes: [f64; MAX_ORDER],
    weights: [f64; MAX_ORDER],
}

/// The normal and friction laws of a joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JournalLaws {
    radial: NormalLaw,
    thrust: NormalLaw,
    friction: Option<FrictionLaw>,
}

/// The friction a joint is asked to use.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JournalFriction {
    /// Frictionless.
    None,
    /// A stateless law, applied at every Gauss point and at the thrust points.
    Law(FrictionLaw),
    /// LuGre: refused by [`JournalLaws::new`] ([`JournalError::LuGreUnsupported`]).
    LuGre(LuGre),
}

impl JournalLaws {
    /// The laws: `radial` gives the total normal force F_N(δ, δ̇, δ̇⁻) (N) of a journal of the
    /// nominal contact length L_c = min(L_b, L_j) (the force per unit length is F_N/L_c),
    /// `thrust` the point force (N) of a thrust face, `friction` the friction of both.
    ///
    /// # Errors
    /// [`JournalError::LuGreUnsupported`] for LuGre friction.
    pub fn new(
        radial: NormalLaw,
        thrust: NormalLaw,
        friction: JournalFriction,
    ) -> Result<Self, JournalError> {
        let friction = match friction {
            JournalFriction::None => None,
            JournalFriction::Law(f) => Some(f),
            JournalFriction::LuGre(_) => return Err(JournalError::LuGreUnsupported),
        };
        Ok(Self {
            radial,
            thrust,
            friction,
        })
    }
}

/// Gauss–Legendre nodes and weights of order n on [0, 1] (Newton on P_n from the Chebyshev
/// guesses; Press et al., *Numerical Recipes*, 3rd ed., §4.6, `gauleg`).
pub(crate) fn gauss_legendre(n: usize) -> ([f64; MAX_ORDER], [f64; MAX_ORDER]) {
    let (mut x, mut w) = ([0.0; MAX_ORDER], [0.0; MAX_ORDER]);
    let m = n.div_ceil(2);
    for i in 0..m {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p1, mut p2) = (1.0, 0.0);
            for j in 0..n {
                let p3 = p2;
                p2 = p1;
                p1 = ((2 * j + 1) as f64 * z * p2 - j as f64 * p3) / (j + 1) as f64;
            }
            dp = n as f64 * (z * p1 - p2) / (z * z - 1.0);
            let dz = p1 / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        let wi = 1.0 / ((1.0 - z * z) * dp * dp);
        // map [−1, 1] → [0, 1]: x = (1 ± z)/2, weight w/2·2 = 2/((1 − z²)p′²)/2
        x[i] = 0.5 * (1.0 - z);
        x[n - 1 - i] = 0.5 * (1.0 + z);
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    (x, w)
}

impl JournalClearance {
    /// A spatial revolute clearance joint: bore radius and length R_b, L_b, journal radius and
    /// length R_j < R_b, L_j (m), total axial end play c_a (m) between the collars and the
    /// bearing's end faces, collar radius R_t (m; `None`: R_j).
    ///
    /// # Errors
    /// [`JournalError::Contact`] when a dimension is not positive and finite or R_j ≥ R_b.
    pub fn revolute(
        bearing_radius: f64,
        bearing_length: f64,
        journal_radius: f64,
        journal_length: f64,
        axial_clearance: f64,
        thrust_radius: Option<f64>,
    ) -> Result<Self, JournalError> {
        let mut joint = Self::cylindrical(
            bearing_radius,
            bearing_length,
            journal_radius,
            journal_length,
        )?;
        const LAW: &str = "spatial revolute clearance joint";
        let radius = thrust_radius.unwrap_or(journal_radius);
        crate::body::check_positive(
            LAW,
            &[
                ("axial clearance c_a (m)", axial_clearance),
                ("thrust radius R_t (m)", radius),
            ],
        )?;
        joint.thrust = Some(Thrust {
            axial_clearance,
            radius,
        });
        Ok(joint)
    }

    /// A spatial cylindrical clearance joint (no thrust faces): bore radius and length R_b, L_b,
    /// journal radius and length R_j < R_b, L_j (m).
    ///
    /// # Errors
    /// [`JournalError::Contact`] when a dimension is not positive and finite or R_j ≥ R_b.
    pub fn cylindrical(
        bearing_radius: f64,
        bearing_length: f64,
        journal_radius: f64,
        journal_length: f64,
    ) -> Result<Self, JournalError> {
        const LAW: &str = "spatial journal-bearing joint";
        crate::body::check_positive(
            LAW,
            &[
                ("bearing radius R_b (m)", bearing_radius),
                ("bearing length L_b (m)", bearing_length),
                ("journal radius R_j (m)", journal_radius),
                ("journal length L_j (m)", journal_length),
            ],
        )?;
        crate::body::check_journal_fits(LAW, "R_b", bearing_radius, journal_radius)?;
        let (nodes, weights) = gauss_legendre(DEFAULT_ORDER);
        Ok(Self {
            bearing_radius,
            bearing_length,
            journal_radius,
            journal_length,
            thrust: None,
            order: DEFAULT_ORDER,
            nodes,
            weights,
        })
    }

    /// The same joint with another Gauss–Legendre order per wetted region (1..=[`MAX_ORDER`]).
    ///
    /// # Errors
    /// [`JournalError::Contact`] for an order outside 1..=[`MAX_ORDER`].
    pub fn with_quadrature_order(mut self, order: usize) -> Result<Self, JournalError> {
        if !(1..=MAX_ORDER).contains(&order) {
            return Err(ContactError::invalid(
                "spatial journal-bearing joint",
                "quadrature order (-)",
                order as f64,
                format!("must be between 1 and {MAX_ORDER}"),
            )
            .into());
        }
        (self.nodes, self.weights) = gauss_legendre(order);
        self.order = order;
        Ok(self)
    }

    /// Bore radius R_b, m.
    pub fn bearing_radius(&self) -> f64 {
        self.bearing_radius
    }
    /// Bore length L_b, m.
    pub fn bearing_length(&self) -> f64 {
        self.bearing_length
    }
    /// Journal radius R_j, m.
    pub fn journal_radius(&self) -> f64 {
        self.journal_radius
    }
    /// Journal length L_j, m.
    pub fn journal_length(&self) -> f64 {
        self.journal_length
    }
    /// Radial clearance c = R_b − R_j, m.
    pub fn clearance(&self) -> f64 {
        self.bearing_radius - self.journal_radius
    }
    /// Nominal contact length L_c = min(L_b, L_j), m: the force per unit length is F_N/L_c.
    pub fn contact_length(&self) -> f64 {
        self.bearing_length.min(self.journal_length)
    }
    /// Total axial end play c_a (m), `None` for the cylindrical kind.
    pub fn axial_clearance(&self) -> Option<f64> {
        self.thrust.map(|t| t.axial_clearance)
    }
    /// Collar (thrust-face) radius R_t (m), `None` for the cylindrical kind.
    pub fn thrust_radius(&self) -> Option<f64> {
        self.thrust.map(|t| t.radius)
    }
    /// Gauss–Legendre order per wetted region.
    pub fn quadrature_order(&self) -> usize {
        self.order
    }

    /// The geometry at one state: overlap, wetted regions, deepest points at their outer ends
    /// and the thrust points. Allocates nothing.
    ///
    /// # Errors
    /// [`JournalError::NonFinite`] for a non-finite state, [`JournalError::Tilt`] for a tilt over
    /// [`MAX_TILT`].
    pub fn geometry<S: Real>(
        &self,
        state: &JournalState<S>,
    ) -> Result<JournalGeometry<'_, S>, JournalError> {
        state.all_finite()?;
        JournalGeometry::new(self, state)
    }
}

/// The deepest point of the journal's cross-section at one bore-axial coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section<S> {
    /// Bore-axial coordinate z of the section (from O_b along u_b), m.
    pub z: S,
    /// Penetration δ(z) = |r| − R_b, m (> 0 in contact).
    pub penetration: S,
    /// Bore normal n = r/|r| at the deepest point (⟂ u_b, from the bore axis outwards).
    pub normal: V3<S>,
    /// Deepest point on the journal surface, m.
    pub journal_point: V3<S>,
    /// The bore surface point O_b + z u_b + R_b n, m (journal_point − bearing_point = δ n).
    pub bearing_point: V3<S>,
    /// Slope dδ/dz = n·t, – (the envelope derivative).
    pub slope: S,
    /// Journal-axial coordinate s of the deepest point (from O_j along u_j), m.
    pub journal_coordinate: S,
}

impl<S: Real> Section<S> {
    /// Midpoint of the two contact points, where the force pair acts, m.
    pub fn midpoint(&self) -> V3<S> {
        (self.journal_point + self.bearing_point).scale_f(0.5)
    }
}

/// Frame quantities of one state (module docs).
#[derive(Debug, Clone, Copy)]
struct Frame<S> {
    ob: V3<S>,
    ub: V3<S>,
    oj: V3<S>,
    uj: V3<S>,
    /// a = (O_j − O_b)·u_b, m.
    a: S,
    /// e₀ = (I − u_b u_bᵀ)(O_j − O_b), m.
    e0: V3<S>,
    /// cos γ.
    cg: S,
    /// w = u_j − cos γ u_b (|w| = sin γ).
    w: V3<S>,
    /// t = w / cos γ = de/dz.
    t: V3<S>,
}

/// One wetted radial region: outer end (an overlap end) and inner end (a root of δ or the split).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Region<S> {
    outer: S,
    inner: S,
    /// The outer end is a journal end (it moves with the journal).
    outer_moves: bool,
}

/// The geometry of a journal-bearing joint at one state ([`JournalClearance::geometry`]).
#[derive(Debug, Clone, Copy)]
pub struct JournalGeometry<'a, S> {
    joint: &'a JournalClearance,
    state: JournalState<S>,
    frame: Frame<S>,
    tilt: f64,
    /// Overlap [z_lo, z_hi] and whether each end is a journal end.
    overlap: Option<(S, S, bool, bool)>,
    /// Deepest points at the overlap ends (lo, hi).
    ends: Option<[Section<S>; 2]>,
    split: f64,
    regions: [Option<Region<S>>; 2],
    thrust: [Option<ThrustPoint<S>>; 2],
}

/// One thrust collar: its deepest point (the group's gap) and the ring it is the deepest point of.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ThrustPoint<S> {
    /// δ_t = δ₀ + R_t sin γ, the deepest point's penetration, m.
    penetration: S,
    /// k u_b.
    normal: V3<S>,
    journal_point: V3<S>,
    bearing_point: V3<S>,
    /// The collar circle's centre O_j − k h u_j, m.
    centre: V3<S>,
    /// Unit radial direction of the collar circle towards its deepest point (any direction ⟂ u_j
    /// without tilt), and u_j × it: X(φ) = centre + R_t (cos φ e₁ + sin φ e₂).
    radial: [V3<S>; 2],
    /// δ₀ = k a − c_a/2 + h (1 − cos γ), the penetration of the circle's centre, m.
    centre_penetration: S,
}

/// Forces, moments and reports of one contact group (radial region or thrust face).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroupForces<S> {
    /// Resultant force on the journal, world, N.
    pub force: V3<S>,
    /// Its moment about O_j, world, N·m.
    pub journal_moment: V3<S>,
    /// Moment of the reaction (−force, at the same points) on the bearing about O_b, N·m.
    pub bearing_moment: V3<S>,
    /// Largest penetration of the group, m: δ at the region's outer end (negative: the gap
    /// there; the event function of contact onset) or δ_t of the thrust face.
    pub penetration: f64,
    /// Its rate (approach rate of the deepest points there), m/s.
    pub rate: f64,
    /// Integrated normal force Σ p, N.
    pub normal_force: f64,
    /// Integrated friction force on the journal, world, N.
    pub friction: Vector3<f64>,
    /// Force-weighted contact point (midpoints of the contact pairs), world, m; the deepest point
    /// at the outer end when the group transmits nothing.
    pub point: Vector3<f64>,
    /// Force-weighted unit normal (bore → journal penetration direction), world.
    pub normal: Vector3<f64>,
    /// Wetted interval (z from, z to) of a radial region, m; `None` when dry or for a thrust face.
    pub wetted: Option<(f64, f64)>,
    /// Power dissipated by contact damping and friction, W: −(power of the pair) − dW/dt.
    pub dissipated: f64,
    /// Elastic energy W = ∫∫ F_e dδ dz / L_c (radial) or ∫F_e dδ (thrust), J.
    pub elastic_energy: f64,
}

impl<S: Real> GroupForces<S> {
    fn open(penetration: f64, rate: f64, point: Vector3<f64>, normal: Vector3<f64>) -> Self {
        Self {
            force: V3::zero(),
            journal_moment: V3::zero(),
            bearing_moment: V3::zero(),
            penetration,
            rate,
            normal_force: 0.0,
            friction: Vector3::zeros(),
            point,
            normal,
            wetted: None,
            dissipated: 0.0,
            elastic_energy: 0.0,
        }
    }
}

/// Forces of the whole joint ([`JournalGeometry::forces`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JournalForces<S> {
    /// Per group: [`RADIAL_A`], [`RADIAL_B`], [`THRUST_MINUS`], [`THRUST_PLUS`].
    pub groups: [GroupForces<S>; GROUPS],
    /// Total force on the journal, world, N.
    pub force: V3<S>,
    /// Total moment on the journal about O_j, N·m.
    pub journal_moment: V3<S>,
    /// Total moment on the bearing about O_b, N·m (its force is −`force`).
    pub bearing_moment: V3<S>,
}

impl<S: Real> JournalForces<S> {
    /// Total dissipated power, W.
    pub fn dissipated(&self) -> f64 {
        self.groups.iter().map(|g| g.dissipated).sum()
    }
    /// Total elastic energy, J.
    pub fn elastic_energy(&self) -> f64 {
        self.groups.iter().map(|g| g.elastic_energy).sum()
    }
}

/// Largest Newton iterations of the inner solves (each converges in a few).
const MAX_ITER: usize = 60;

impl<'a, S: Real> JournalGeometry<'a, S> {
    fn new(joint: &'a JournalClearance, state: &JournalState<S>) -> Result<Self, JournalError> {
        let mut g = Self::bare(joint, state)?;
        g.find_overlap();
        g.find_regions();
        g.find_thrust();
        Ok(g)
    }

    /// The frame quantities only (no overlap, regions or thrust points yet).
    fn bare(joint: &'a JournalClearance, state: &JournalState<S>) -> Result<Self, JournalError> {
        let mut state = *state;
        let Axes {
            ub,
            uj,
            cg,
            w,
            tilt,
        } = state.axes()?;
        state.bearing_axis = ub;
        state.journal_axis = uj;
        let (ob, oj) = (state.bearing_centre, state.journal_centre);
        let d = oj - ob;
        let a = d.dot(&ub);
        let frame = Frame {
            ob,
            ub,
            oj,
            uj,
            a,
            e0: d - ub.scale(a),
            cg,
            w,
            t: w.scale(S::from_f64(1.0) / cg),
        };
        Ok(Self {
            joint,
            state,
            frame,
            tilt,
            overlap: None,
            ends: None,
            split: 0.0,
            regions: [None, None],
            thrust: [None, None],
        })
    }

    /// Gradient of the z of the journal end s_end (±L_j/2, m) over the pose: ∂z_e/∂O_b,
    /// ∂z_e/∂θ_b, ∂z_e/∂O_j, ∂z_e/∂θ_j (θ a world rotation of the body about its centre; – and
    /// m), in the scalar type. The end z_e solves G(z, q) = s(z, q) − s_end = 0, s the journal
    /// coordinate of the section's deepest point, so ∇z_e = −G_q/G_z (the implicit-function
    /// rule), with G_z and each column of G_q from one section evaluated at z_e in [`Rate`]
    /// numbers.
    fn journal_end_gradient(&self, z_end: S) -> [V3<S>; 4] {
        let st = &self.state;
        let (ub, uj) = (st.bearing_axis, st.journal_axis);
        let moving = |x: &V3<S>, dx: V3<S>| {
            V3([0, 1, 2].map(|i| Rate {
                v: x.0[i],
                d: dx.0[i],
            }))
        };
        let still = |x: &V3<S>| moving(x, V3::zero());
        let zero = S::from_f64(0.0);
        let derivative = |dir: &[V3<S>; 4], dz: S| {
            let rate_state = JournalState {
                bearing_centre: moving(&st.bearing_centre, dir[0]),
                bearing_axis: moving(&ub, dir[1].cross(&ub)),
                bearing_velocity: still(&st.bearing_velocity),
                bearing_angular_velocity: still(&st.bearing_angular_velocity),
                journal_centre: moving(&st.journal_centre, dir[2]),
                journal_axis: moving(&uj, dir[3].cross(&uj)),
                journal_velocity: still(&st.journal_velocity),
                journal_angular_velocity: still(&st.journal_angular_velocity),
            };
            JournalGeometry::bare(self.joint, &rate_state).map_or(zero, |geo| {
                geo.section(Rate { v: z_end, d: dz }).journal_coordinate.d
            })
        };
        let g_z = derivative(&[V3::zero(); 4], S::from_f64(1.0));
        let mut grad = [V3::zero(); 4];
        for (k, g) in grad.iter_mut().enumerate() {
            for c in 0..3 {
                let mut dir = [V3::zero(); 4];
                dir[k].0[c] = S::from_f64(1.0);
                g.0[c] = -(derivative(&dir, zero) / g_z);
            }
        }
        grad
    }

    /// Tilt γ between the journal and bore axes, rad.
    pub fn tilt(&self) -> f64 {
        self.tilt
    }

    /// The bore-axial overlap [z_lo, z_hi] of journal and bore, m (`None`: the journal is out of
    /// the bore).
    pub fn overlap(&self) -> Option<(f64, f64)> {
        self.overlap.map(|(lo, hi, _, _)| (lo.value(), hi.value()))
    }

    /// The wetted z interval of radial region A (k = 0) or B (k = 1), m, ordered low to high.
    pub fn wetted(&self, k: usize) -> Option<(f64, f64)> {
        self.regions.get(k).copied().flatten().map(|r| {
            let (o, i) = (r.outer.value(), r.inner.value());
            (o.min(i), o.max(i))
        })
    }

    /// Where the overlap is split between regions A and B (the minimiser of δ), m.
    pub fn split(&self) -> f64 {
        self.split
    }

    /// E(m) R_j: the section-ellipse point of the journal direction m, relative to C(z).
    fn ellipse(&self, m: &V3<S>) -> V3<S> {
        let f = &self.frame;
        let r = S::from_f64(self.joint.journal_radius);
        (*m - f.uj.scale(m.dot(&f.ub) / f.cg)).scale(r)
    }

    /// The deepest point of the cross-section at z (module docs): Newton's method on the angle
    /// φ of m = m₀ cos φ + (u_j × m₀) sin φ maximising ½|e(z) + R_j E(m)|², from m₀ along e(z).
    pub fn section(&self, z: S) -> Section<S> {
        let f = &self.frame;
        let e = f.e0 + f.t.scale(z - f.a);
        let len_e = e.norm();
        let ep = e - f.uj.scale(e.dot(&f.uj));
        let len = ep.norm();
        let m0 = if len.value() > 0.0 {
            ep.scale(S::from_f64(1.0) / len)
        } else {
            // e(z) ∥ u_j or 0: no contact here (δ < 0); any direction ⟂ u_j keeps the numbers
            // finite
            let u = f.uj.value();
            let k = if u.x.abs() < 0.9 {
                Vector3::x()
            } else {
                Vector3::y()
            };
            let p = V3::constant(&k);
            let q = p - f.uj.scale(p.dot(&f.uj));
            q.scale(S::from_f64(1.0) / q.norm())
        };
        let e_hat = if len_e.value() > 0.0 {
            e.scale(S::from_f64(1.0) / len_e)
        } else {
            m0
        };
        // Newton's method on the angle φ of m(φ) = m cos φ + (u_j × m) sin φ about the current m
        // (at φ = 0: m′ = u_j × m, m″ = −m), the step taken as m ← (m − Δφ u_j × m)/|·|, which
        // turns by atan Δφ: no trigonometry, and the error it adds, Δφ³/3, is below the quadratic
        // term
        let mut m = m0;
        for _ in 0..MAX_ITER {
            let b = f.uj.cross(&m);
            let em = self.ellipse(&m);
            let r = e + em;
            let r1 = self.ellipse(&b);
            let curvature = r1.dot(&r1) - r.dot(&em);
            if curvature.value() >= 0.0 || curvature.value().is_nan() {
                // a centred circle (every point equally deep) or no maximum near: keep m
                break;
            }
            let step = r.dot(&r1) / curvature;
            let turned = m - b.scale(step);
            m = turned.scale(S::from_f64(1.0) / turned.norm());
            // quadratic convergence: after a step below 1e-10 rad the error is ~ (R_j/e)·1e-20;
            // a tighter test would chase the rounding noise of f′/f″ (~1e-14 rad)
            if step.value().abs() <= 1e-10 {
                break;
            }
        }
        let r = e + self.ellipse(&m);
        let rho = r.norm();
        let n = r.scale(S::from_f64(1.0) / rho);
        let rb = self.joint.bearing_radius;
        let rj = S::from_f64(self.joint.journal_radius);
        // δ = (|e| − c) + Δ with the ellipse excess Δ = |r| − |e| − R_j written in small
        // quantities (no cancellation: at γ = 0 this is the planar e − c bit for bit):
        // |r|² − (|e| + R_j)² = 2R_j(e·E − |e|) + R_j²(|E|² − 1), |E|² − 1 = (m·u_b)²/cos²γ,
        // e·E − |e| = −½|e||ê − m|² − (m·u_b)(e·u_j)/cos γ
        let mb = m.dot(&f.ub) / f.cg;
        let dm = e_hat - m;
        let half = S::from_f64(0.5);
        let num = S::from_f64(2.0) * rj * (-(half * len_e * dm.dot(&dm)) - mb * e.dot(&f.uj))
            + rj * rj * mb * mb;
        let excess = num / (rho + len_e + rj);
        let axis_point = f.ob + f.ub.scale(z);
        Section {
            z,
            penetration: (len_e - S::from_f64(self.joint.clearance())) + excess,
            normal: n,
            journal_point: axis_point + r,
            bearing_point: axis_point + n.scale_f(rb),
            slope: n.dot(&f.t),
            journal_coordinate: (z - f.a - rj * m.dot(&f.ub)) / f.cg,
        }
    }

    /// z of the journal end s_end (±L_j/2): the section whose deepest point lies on the end circle.
    fn journal_end(&self, s_end: f64) -> S {
        let f = &self.frame;
        let mut z = f.a + f.cg * S::from_f64(s_end);
        for _ in 0..MAX_ITER {
            let sec = self.section(z);
            let step = f.cg * (sec.journal_coordinate - S::from_f64(s_end));
            z = z - step;
            // linear convergence (factor ≈ R_j γ²/c): stop at the rounding level of z
            if step.value().abs() <= 1e-15 * self.joint.journal_length {
                break;
            }
        }
        z
    }

    fn find_overlap(&mut self) {
        let (lb, lj) = (self.joint.bearing_length, self.joint.journal_length);
        let (jlo, jhi) = (self.journal_end(-0.5 * lj), self.journal_end(0.5 * lj));
        let (lo, lo_moves) = if jlo.value() > -0.5 * lb {
            (jlo, true)
        } else {
            (S::from_f64(-0.5 * lb), false)
        };
        let (hi, hi_moves) = if jhi.value() < 0.5 * lb {
            (jhi, true)
        } else {
            (S::from_f64(0.5 * lb), false)
        };
        if lo.value() < hi.value() {
            self.overlap = Some((lo, hi, lo_moves, hi_moves));
            self.ends = Some([self.section(lo), self.section(hi)]);
        }
    }

    /// The minimiser of δ on the overlap (values only: the integral does not depend on where a
    /// wetted overlap is split, up to quadrature error): safeguarded secant steps on δ′ = n·t.
    fn find_split(&self, lo: f64, hi: f64, ends: &[Section<S>; 2]) -> f64 {
        let (mut a, fa) = (lo, ends[0].slope.value());
        let (mut b, fb) = (hi, ends[1].slope.value());
        if self.frame.t.value().norm() == 0.0 {
            return 0.5 * (lo + hi);
        }
        if fa >= 0.0 {
            return lo;
        }
        if fb <= 0.0 {
            return hi;
        }
        // secant steps from the minimiser of the circle part |e(z)|² (closed form), kept inside
        // the bracket [a, b] (δ′(a) < 0 < δ′(b)) by bisection
        let fr = &self.frame;
        let (t, e0) = (fr.t.value(), fr.e0.value());
        let start = fr.a.value() - e0.dot(&t) / t.dot(&t);
        let tol = 1e-10 * (hi - lo);
        let mut x0 = start.clamp(a, b);
        let mut f0 = self.section(S::from_f64(x0)).slope.value();
        let probe = 1e-3 * (hi - lo);
        let mut x1 = if x0 + probe < b {
            x0 + probe
        } else {
            x0 - probe
        };
        for _ in 0..MAX_ITER {
            let f1 = self.section(S::from_f64(x1)).slope.value();
            for (x, fx) in [(x0, f0), (x1, f1)] {
                if fx < 0.0 && x > a {
                    a = x;
                } else if fx > 0.0 && x < b {
                    b = x;
                }
            }
            if f1 == 0.0 || b - a <= tol {
                return x1;
            }
            let secant = x1 - f1 * (x1 - x0) / (f1 - f0);
            let next = if secant > a && secant < b {
                secant
            } else {
                0.5 * (a + b)
            };
            if (next - x1).abs() <= tol {
                return next;
            }
            (x0, f0, x1) = (x1, f1, next);
        }
        0.5 * (a + b)
    }

    /// Root of δ between the wetted `outer` end and the dry `inner` point (safeguarded Newton from
    /// `start`, in the scalar type so that its derivatives follow the implicit-function rule).
    fn root(&self, outer: f64, inner: f64, start: f64) -> S {
        let (mut wet, mut dry) = (outer, inner);
        let inside = |x: f64, wet: f64, dry: f64| (x - wet) * (x - dry) < 0.0;
        let mut z = S::from_f64(if inside(start, wet, dry) {
            start
        } else {
            0.5 * (outer + inner)
        });
        // quadratic convergence: a step below 1e-11 L leaves an error ~ 1e-22 L²·δ″/δ′; a tighter
        // test would chase the rounding noise of δ/δ′
        let tol = 1e-11 * self.joint.bearing_length.max(self.joint.journal_length);
        for _ in 0..MAX_ITER {
            let sec = self.section(z);
            if sec.penetration.value() > 0.0 {
                wet = z.value();
            } else {
                dry = z.value();
            }
            let newton = z - sec.penetration / sec.slope;
            let step = (newton.value() - z.value()).abs();
            z = if inside(newton.value(), wet, dry) || step <= tol {
                newton
            } else {
                S::from_f64(0.5 * (wet + dry))
            };
            if step <= tol || (wet - dry).abs() <= tol {
                break;
            }
        }
        z
    }

    /// Roots of the circle part |e(z)|² = c² (the start of [`root`](Self::root)), low and high.
    fn circle_roots(&self) -> Option<(f64, f64)> {
        let f = &self.frame;
        let (e0, t, a) = (f.e0.value(), f.t.value(), f.a.value());
        let qa = t.dot(&t);
        if qa == 0.0 {
            return None;
        }
        let c = self.joint.clearance();
        let qb = e0.dot(&t);
        let disc = qb * qb - qa * (e0.dot(&e0) - c * c);
        if disc < 0.0 {
            return None;
        }
        let s = disc.sqrt();
        Some((a + (-qb - s) / qa, a + (-qb + s) / qa))
    }

    fn find_regions(&mut self) {
        let (Some((lo, hi, lo_moves, hi_moves)), Some(ends)) = (self.overlap, self.ends) else {
            return;
        };
        let (lo_v, hi_v) = (lo.value(), hi.value());
        let split = self.find_split(lo_v, hi_v, &ends);
        self.split = split;
        let d_split = self.section(S::from_f64(split)).penetration.value();
        let circle = self.circle_roots();
        for (k, (outer, moves, sec)) in [(lo, lo_moves, &ends[0]), (hi, hi_moves, &ends[1])]
            .into_iter()
            .enumerate()
        {
            if sec.penetration.value() <= 0.0 {
                continue;
            }
            let inner = if d_split > 0.0 || split == outer.value() {
                S::from_f64(split)
            } else {
                let start = circle.map_or(split, |(c0, c1)| if k == 0 { c0 } else { c1 });
                self.root(outer.value(), split, start)
            };
            if (inner.value() - outer.value()).abs() > 0.0 {
                self.regions[k] = Some(Region {
                    outer,
                    inner,
                    outer_moves: moves,
                });
            }
        }
    }

    fn find_thrust(&mut self) {
        let Some(th) = self.joint.thrust else {
            return;
        };
        let f = self.frame;
        let h = 0.5 * (self.joint.bearing_length + th.axial_clearance);
        let sin2 = f.w.dot(&f.w);
        let sin_g = if sin2.value() > 0.0 {
            sin2.sqrt()
        } else {
            S::from_f64(0.0)
        };
        // h (1 − cos γ) = h sin²γ / (1 + cos γ): no cancellation at small tilt
        let sag = S::from_f64(h) * sin2 / (S::from_f64(1.0) + f.cg);
        let r_t = S::from_f64(th.radius);
        // without tilt any direction ⟂ u_j serves (the ring is then uniformly loaded); built from
        // the pose so that dual numbers carry the derivatives of the ring's material points
        let fallback = {
            let u = f.uj.value();
            let p = V3::constant(&if u.x.abs() < 0.9 {
                Vector3::x()
            } else {
                Vector3::y()
            });
            let q = p - f.uj.scale(p.dot(&f.uj));
            q.scale(S::from_f64(1.0) / q.norm())
        };
        for (slot, k) in [(0, -1.0), (1, 1.0)] {
            let centre = f.oj - f.uj.scale_f(k * h);
            let e1 = if sin_g.value() > 0.0 {
                let towards = f.ub - f.uj.scale(f.cg);
                towards.scale(S::from_f64(k) / sin_g)
            } else {
                fallback
            };
            let point = if sin_g.value() > 0.0 {
                centre + e1.scale(r_t)
            } else {
                centre
            };
            // δ = k a − h cos γ + L_b/2 + R_t sin γ = k a − c_a/2 + h (1 − cos γ) + R_t sin γ
            let delta0 = f.a * S::from_f64(k) - S::from_f64(0.5 * th.axial_clearance) + sag;
            let delta = delta0 + r_t * sin_g;
            let normal = f.ub.scale_f(k);
            self.thrust[slot] = Some(ThrustPoint {
                penetration: delta,
                normal,
                journal_point: point,
                bearing_point: point - normal.scale(delta),
                centre,
                radial: [e1, f.uj.cross(&e1)],
                centre_penetration: delta0,
            });
        }
    }

    /// Relative velocity of the deepest points (journal − bearing), m/s.
    fn relative_velocity(&self, journal_point: &V3<S>, bearing_point: &V3<S>) -> V3<S> {
        self.state.journal_point_velocity(journal_point)
            - self.state.bearing_point_velocity(bearing_point)
    }

    /// Penetration and its rate (m, m/s) of group `g` (the memory's and the event's inputs):
    /// for a radial group δ and v·n at the region's outer end (−c and 0 when the journal is out
    /// of the bore), for a thrust face δ_t and its rate (−∞ and 0 for the cylindrical kind and
    /// for an index ≥ [`GROUPS`]).
    pub fn gap(&self, g: usize) -> (f64, f64) {
        match g {
            RADIAL_A | RADIAL_B => match self.ends {
                Some(ends) => {
                    let s = &ends[g];
                    let v = self.relative_velocity(&s.journal_point, &s.bearing_point);
                    (s.penetration.value(), v.dot(&s.normal).value())
                }
                None => (-self.joint.clearance(), 0.0),
            },
            THRUST_MINUS | THRUST_PLUS => match &self.thrust[g - THRUST_MINUS] {
                Some(t) => {
                    let v = self.relative_velocity(&t.journal_point, &t.bearing_point);
                    (t.penetration.value(), v.dot(&t.normal).value())
                }
                None => (f64::NEG_INFINITY, 0.0),
            },
            _ => (f64::NEG_INFINITY, 0.0),
        }
    }

    /// Forces with the impact velocities δ̇⁻ (m/s) of the four groups taken from `memory`, slots
    /// `first_slot..first_slot + 4` ([`ContactMemory::impact_velocity`]).
    pub fn forces_with_memory(
        &self,
        laws: &JournalLaws,
        memory: &mut ContactMemory,
        first_slot: usize,
    ) -> JournalForces<S> {
        let mut vdm = [0.0; GROUPS];
        for (g, v) in vdm.iter_mut().enumerate() {
            let (d, r) = self.gap(g);
            *v = memory.impact_velocity(first_slot + g, d, r);
        }
        self.forces(laws, &vdm)
    }

    /// Commit the four groups' (δ, δ̇) to `memory` at an accepted step
    /// ([`ContactMemory::commit`]).
    pub fn commit(&self, memory: &mut ContactMemory, first_slot: usize) {
        for g in 0..GROUPS {
            let (d, r) = self.gap(g);
            memory.commit(first_slot + g, d, r);
        }
    }

    /// Forces of all groups for the impact velocities δ̇⁻ (m/s) of [`RADIAL_A`], [`RADIAL_B`],
    /// [`THRUST_MINUS`], [`THRUST_PLUS`]. Allocates nothing.
    pub fn forces(
        &self,
        laws: &JournalLaws,
        impact_velocities: &[f64; GROUPS],
    ) -> JournalForces<S> {
        let mut groups =
            [GroupForces::open(f64::NEG_INFINITY, 0.0, Vector3::zeros(), Vector3::zeros()); GROUPS];
        for (k, g) in groups.iter_mut().take(2).enumerate() {
            *g = self.radial(k, laws, impact_velocities[k]);
        }
        for k in 0..2 {
            groups[THRUST_MINUS + k] = self.thrust_forces(k, laws, impact_velocities[2 + k]);
        }
        let mut out = JournalForces {
            groups,
            force: V3::zero(),
            journal_moment: V3::zero(),
            bearing_moment: V3::zero(),
        };
        for g in &groups {
            out.force = out.force + g.force;
            out.journal_moment = out.journal_moment + g.journal_moment;
            out.bearing_moment = out.bearing_moment + g.bearing_moment;
        }
        out
    }

    /// Force per unit length (or point force) on the journal at one contact pair, with the
    /// friction of the slip there: (f, p, friction) with p the normal part.
    /// `scale` is 1/L_c for the radial line load, 1 for a thrust point.
    fn pair_force(
        law: &NormalLaw,
        friction: Option<&FrictionLaw>,
        scale: f64,
        (delta, normal, v): (S, &V3<S>, &V3<S>),
        impact_velocity: f64,
    ) -> (V3<S>, S, V3<S>) {
        let rate = v.dot(normal);
        let (f, fd, fr) = law.force_with_derivatives(delta.value(), rate.value(), impact_velocity);
        let p = S::chain2(delta, rate, f * scale, fd * scale, fr * scale);
        let slip = *v - normal.scale(rate);
        let speed = slip.norm();
        let ft = match friction {
            Some(law) if speed.value() > 0.0 && f > 0.0 => {
                let (phi, d_speed, d_fn) = law.force_with_derivatives(speed.value(), p.value());
                let mag = S::chain2(speed, p, phi, d_speed, d_fn);
                slip.scale(mag / speed)
            }
            _ => V3::zero(),
        };
        (ft - normal.scale(p), p, ft)
    }

    fn radial(&self, k: usize, laws: &JournalLaws, impact_velocity: f64) -> GroupForces<S> {
        let (delta0, rate0) = self.gap(k);
        let Some(ends) = self.ends else {
            return GroupForces::open(delta0, rate0, Vector3::zeros(), Vector3::zeros());
        };
        let end = &ends[k];
        let mut out = GroupForces::open(delta0, rate0, end.midpoint().value(), end.normal.value());
        // the overlap's end k: where it is, and whether it is a journal end (it moves with it)
        let Some((lo, hi, lo_moves, hi_moves)) = self.overlap else {
            return out;
        };
        let (end_z, end_moves) = if k == 0 {
            (lo, lo_moves)
        } else {
            (hi, hi_moves)
        };
        let end_term = end_moves && delta0 > 0.0;
        let region = self.regions[k];
        if region.is_none() && !end_term {
            return out;
        }
        let j = self.joint;
        let f = &self.frame;
        let lc = j.contact_length();
        let (mut force, mut mj, mut mb) = (V3::zero(), V3::zero(), V3::zero());
        let (mut fn_sum, mut point, mut normal, mut fric) =
            (0.0, Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
        let (mut power, mut w_rate, mut energy) = (0.0, 0.0, 0.0);
        let ub = f.ub.value();
        // a force pair on the journal (−f on the bearing) at one point: resultant, moments, power
        let mut apply = |fw: V3<S>, at: &V3<S>| {
            force = force + fw;
            mj = mj + (*at - f.oj).cross(&fw);
            mb = mb - (*at - f.ob).cross(&fw);
            let v = self.state.journal_point_velocity(at) - self.state.bearing_point_velocity(at);
            power += fw.value().dot(&v.value());
        };
        let (nodes, span) = match region {
            Some(r) => (j.order, r),
            None => (
                0,
                Region {
                    outer: end_z,
                    inner: end_z,
                    outer_moves: end_moves,
                },
            ),
        };
        let len = if k == 0 {
            span.inner - span.outer
        } else {
            span.outer - span.inner
        };
        for q in 0..nodes {
            let (z, wq) = self.radial_node(&span, len, q);
            let sec = self.section(z);
            if sec.penetration.value() <= 0.0 {
                continue;
            }
            let v = self.relative_velocity(&sec.journal_point, &sec.bearing_point);
            let (fq, p, ft) = Self::pair_force(
                &laws.radial,
                laws.friction.as_ref(),
                1.0 / lc,
                (sec.penetration, &sec.normal, &v),
                impact_velocity,
            );
            // −p n and friction act at the midpoint of the contact pair (the planar joint's common
            // point); the axial part p δ′ u_b, which turns −p n into −p (n − δ′ u_b) along the
            // journal's surface normal and makes the force the gradient of W, acts at the
            // journal's material point, where ∂δ/∂t = n·v − δ′ u_b·v_rel was derived
            let xm = sec.midpoint();
            apply(fq.scale(wq), &xm);
            apply(f.ub.scale(p * sec.slope * wq), &sec.journal_point);
            // reports (values)
            let (wv, pv, xmv, nv) = (wq.value(), p.value(), xm.value(), sec.normal.value());
            fn_sum += wv * pv;
            point += wv * pv * xmv;
            normal += wv * pv * nv;
            fric += wv * ft.value();
            // ∂δ/∂t at fixed z: the approach rate less the slope times the axial sliding of the
            // journal's material point relative to the bore
            let v_rel = (self.state.journal_point_velocity(&sec.journal_point)
                - self.state.bearing_point_velocity(&sec.journal_point))
            .value();
            let d = sec.penetration.value();
            let dt_delta = v.dot(&sec.normal).value() - sec.slope.value() * v_rel.dot(&ub);
            w_rate += wv * laws.radial.elastic_force(d) * dt_delta / lc;
            energy += wv * laws.radial.elastic_energy(d) / lc;
        }
        // a wetted journal end (the overlap's end moves with the journal; it belongs to this group
        // whether or not the split left the group a region of its own): W changes by
        // ±Φ(δ_end)/L_c per unit of end motion, whence the generalized force −(±Φ/L_c)∇z_end,
        // which cancels the axial part of the slope term when the journal slides along a rim (a
        // cylinder sliding in a cylinder stores nothing)
        if end_term {
            let sign = if k == 0 { -1.0 } else { 1.0 };
            let phi = laws.radial.elastic_energy(delta0);
            let phi_s = end
                .penetration
                .chain(phi, laws.radial.elastic_force(delta0));
            // the generalized force −(±Φ/L_c) ∇z_e of the end's motion: a force pair and the
            // moments about O_j and O_b (rigid-motion invariance of z_e makes them balance)
            let c = phi_s * S::from_f64(-sign / lc);
            let grad = self.journal_end_gradient(end_z);
            force = force + grad[2].scale(c);
            mj = mj + grad[3].scale(c);
            mb = mb + grad[1].scale(c);
            let st = &self.state;
            let z_dot = (grad[0].dot(&st.bearing_velocity)
                + grad[1].dot(&st.bearing_angular_velocity)
                + grad[2].dot(&st.journal_velocity)
                + grad[3].dot(&st.journal_angular_velocity))
            .value();
            // its power −c ż_e and the stored energy's rate ±Φ/L_c ż_e cancel in the dissipation
            power += c.value() * z_dot;
            w_rate += sign * phi / lc * z_dot;
        }
        out.force = force;
        out.journal_moment = mj;
        out.bearing_moment = mb;
        out.normal_force = fn_sum;
        out.friction = fric;
        if fn_sum > 0.0 {
            out.point = point / fn_sum;
            out.normal = normal.normalize();
        }
        out.wetted = region.map(|r| {
            let (a, b) = (r.outer.value(), r.inner.value());
            (a.min(b), a.max(b))
        });
        out.dissipated = -power - w_rate;
        out.elastic_energy = energy;
        out
    }

    /// Gauss node `q` of a wetted radial region of length `len` (m): its bore-axial coordinate z
    /// (m) and weight (m), after the substitution z = z_in + (z_out − z_in)u² (module docs).
    fn radial_node(&self, span: &Region<S>, len: S, q: usize) -> (S, S) {
        let j = self.joint;
        let u = j.nodes[q];
        let z = span.inner + (span.outer - span.inner) * S::from_f64(u * u);
        (z, len * S::from_f64(2.0 * u * j.weights[q]))
    }

    /// Half the wetted arc φ_e of a thrust ring (rad): δ(φ) = δ₀ + A cos φ > 0 for |φ| < φ_e,
    /// A = R_t sin γ; π when the whole ring touches, `None` when it is dry. Analytic,
    /// φ_e = acos(−δ₀/A), in the scalar type.
    fn wetted_half_arc(delta0: S, amplitude: S) -> Option<S> {
        let (d, a) = (delta0.value(), amplitude.value());
        if d + a <= 0.0 {
            None
        } else if d - a >= 0.0 {
            Some(S::from_f64(std::f64::consts::PI))
        } else {
            let x = -(delta0 / amplitude);
            let xv = x.value();
            Some(x.chain(xv.acos(), -1.0 / (1.0 - xv * xv).sqrt()))
        }
    }

    /// The thrust face as a ring law: force per unit arc F_N(δ(φ))/(2π R_t) along the collar
    /// circle, integrated over the wetted arc |φ| < φ_e by Gauss–Legendre on each half after the
    /// substitution φ = ±φ_e (1 − u²) (nodes clustered at the arc's ends, where p ∝ δ^n
    /// vanishes). Without tilt δ is uniform and the total is F_N(δ); force and moment are
    /// continuous through γ = 0 and as the arc closes to the full ring.
    fn thrust_forces(&self, k: usize, laws: &JournalLaws, impact_velocity: f64) -> GroupForces<S> {
        let (delta, rate) = self.gap(THRUST_MINUS + k);
        let Some(t) = self.thrust[k] else {
            return GroupForces::open(delta, rate, Vector3::zeros(), Vector3::zeros());
        };
        let xm0 = (t.journal_point + t.bearing_point).scale_f(0.5);
        let mut out = GroupForces::open(delta, rate, xm0.value(), t.normal.value());
        let Some(r_t) = self.joint.thrust.map(|th| th.radius) else {
            return out;
        };
        let amplitude = t.penetration - t.centre_penetration;
        let Some(half) = Self::wetted_half_arc(t.centre_penetration, amplitude) else {
            return out;
        };
        let j = self.joint;
        let f = &self.frame;
        let (mut force, mut mj, mut mb) = (V3::zero(), V3::zero(), V3::zero());
        let (mut fn_sum, mut point, mut fric) = (0.0, Vector3::zeros(), Vector3::zeros());
        let (mut dissipated, mut energy) = (0.0, 0.0);
        for side in [1.0, -1.0] {
            for q in 0..j.order {
                let u = j.nodes[q];
                let phi = half * S::from_f64(side * (1.0 - u * u));
                // dφ/(2π) of the substituted rule
                let wq = half * S::from_f64(u * j.weights[q] / std::f64::consts::PI);
                let arm =
                    (t.radial[0].scale(phi.cos()) + t.radial[1].scale(phi.sin())).scale_f(r_t);
                let xj = t.centre + arm;
                let d = t.centre_penetration + arm.dot(&t.normal);
                if d.value() <= 0.0 {
                    continue;
                }
                let xb = xj - t.normal.scale(d);
                let v = self.relative_velocity(&xj, &xb);
                let (fq, p, ft) = Self::pair_force(
                    &laws.thrust,
                    laws.friction.as_ref(),
                    1.0,
                    (d, &t.normal, &v),
                    impact_velocity,
                );
                let xm = (xj + xb).scale_f(0.5);
                let fw = fq.scale(wq);
                force = force + fw;
                mj = mj + (xm - f.oj).cross(&fw);
                mb = mb - (xm - f.ob).cross(&fw);
                let (wv, pv, dv) = (wq.value(), p.value(), d.value());
                fn_sum += wv * pv;
                point += wv * pv * xm.value();
                fric += wv * ft.value();
                let v_mid = (self.state.journal_point_velocity(&xm)
                    - self.state.bearing_point_velocity(&xm))
                .value();
                dissipated += -fw.value().dot(&v_mid)
                    - wv * laws.thrust.elastic_force(dv) * v.dot(&t.normal).value();
                energy += wv * laws.thrust.elastic_energy(dv);
            }
        }
        out.force = force;
        out.journal_moment = mj;
        out.bearing_moment = mb;
        out.normal_force = fn_sum;
        out.friction = fric;
        if fn_sum > 0.0 {
            out.point = point / fn_sum;
        }
        out.dissipated = dissipated;
        out.elastic_energy = energy;
        out
    }
}

/// One Gauss node of a wetted radial region, as the force evaluation sees it
/// ([`JournalGeometry::visit_radial_nodes`]): the data a distributed law along the contact
/// (wear, heat) needs. World frame, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadialNode {
    /// Radial group ([`RADIAL_A`] or [`RADIAL_B`]).
    pub group: usize,
    /// Bore-axial coordinate z of the node (from O_b along u_b), m.
    pub z: f64,
    /// Quadrature weight, m: Σ weight · line_load is the group's normal force.
    pub weight: f64,
    /// The node's share [z_from, z_to] of the wetted region (m, z_from < z_to): consecutive
    /// nodes' shares tile the region, each share of length `weight` (the partial sums of the
    /// Gauss weights, which interlace the nodes: Szegő, *Orthogonal Polynomials*, Thm. 3.41.1,
    /// the Chebyshev–Markov–Stieltjes separation theorem, carried through the substitution).
    pub share: (f64, f64),
    /// Penetration δ(z), m (> 0).
    pub penetration: f64,
    /// Normal line load p(z) = F_N(δ, δ̇, δ̇⁻)/L_c, N/m (the same value the force uses; may be
    /// negative for a damping law that pulls at separation).
    pub line_load: f64,
    /// Bore normal n at the deepest point (⟂ u_b, outwards).
    pub normal: Vector3<f64>,
    /// Midpoint of the contact pair, where the force acts, m.
    pub point: Vector3<f64>,
    /// Slip velocity (journal − bearing deepest points) in the tangent plane, m/s.
    pub slip: Vector3<f64>,
}

impl JournalGeometry<'_, f64> {
    /// Call `visit` once per Gauss node of each wetted radial region (in order of increasing
    /// u, region A then B) with the node's data as [`forces`](Self::forces) computes them for the
    /// impact velocities δ̇⁻ (m/s) of the four groups: the same nodes, sections and line loads
    /// (dry nodes, δ ≤ 0, are skipped as there). Allocates nothing; does not change what
    /// `forces` returns.
    pub fn visit_radial_nodes(
        &self,
        laws: &JournalLaws,
        impact_velocities: &[f64; GROUPS],
        mut visit: impl FnMut(&RadialNode),
    ) {
        let lc = self.joint.contact_length();
        for (k, region) in self.regions.iter().enumerate() {
            let Some(span) = region else {
                continue;
            };
            let len = if k == 0 {
                span.inner - span.outer
            } else {
                span.outer - span.inner
            };
            // the shares run from the inner end outwards, in the signed direction of the region
            let dir = (span.outer - span.inner).signum();
            let mut from = span.inner;
            for q in 0..self.joint.order {
                let (z, wq) = self.radial_node(span, len, q);
                let to = from + dir * wq;
                let share = (from.min(to), from.max(to));
                from = to;
                let sec = self.section(z);
                if sec.penetration <= 0.0 {
                    continue;
                }
                let v = self.relative_velocity(&sec.journal_point, &sec.bearing_point);
                let (_, p, _) = Self::pair_force(
                    &laws.radial,
                    None,
                    1.0 / lc,
                    (sec.penetration, &sec.normal, &v),
                    impact_velocities[k],
                );
                let (n, v) = (sec.normal.value(), v.value());
                visit(&RadialNode {
                    group: k,
                    z,
                    weight: wq,
                    share,
                    penetration: sec.penetration,
                    line_load: p,
                    normal: n,
                    point: sec.midpoint().value(),
                    slip: v - n * v.dot(&n),
                });
            }
        }
    }
}

/// A scalar and its derivative along one direction of the pose (forward mode over any [`Real`],
/// so that the derivative itself carries the scalar's derivatives): evaluates the journal end's
/// fixed point to get the end's pose gradient. Exact for the arithmetic, √, sin and cos the
/// geometry uses; [`Real::chain`] and [`Real::chain2`] (the laws) are first order in the direction
/// and are not used on it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Rate<S> {
    v: S,
    d: S,
}

impl<S: Real> Add for Rate<S> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            v: self.v + o.v,
            d: self.d + o.d,
        }
    }
}
impl<S: Real> Sub for Rate<S> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self {
            v: self.v - o.v,
            d: self.d - o.d,
        }
    }
}
impl<S: Real> Mul for Rate<S> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self {
            v: self.v * o.v,
            d: self.d * o.v + self.v * o.d,
        }
    }
}
impl<S: Real> Div for Rate<S> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        Self {
            v: self.v / o.v,
            d: (self.d * o.v - self.v * o.d) / (o.v * o.v),
        }
    }
}
impl<S: Real> Neg for Rate<S> {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            v: -self.v,
            d: -self.d,
        }
    }
}
impl<S: Real> Real for Rate<S> {
    fn from_f64(v: f64) -> Self {
        Self {
            v: S::from_f64(v),
            d: S::from_f64(0.0),
        }
    }
    fn value(&self) -> f64 {
        self.v.value()
    }
    fn chain(self, f: f64, df: f64) -> Self {
        Self {
            v: self.v.chain(f, df),
            d: self.d * S::from_f64(df),
        }
    }
    fn chain2(a: Self, b: Self, f: f64, dfa: f64, dfb: f64) -> Self {
        Self {
            v: S::chain2(a.v, b.v, f, dfa, dfb),
            d: a.d * S::from_f64(dfa) + b.d * S::from_f64(dfb),
        }
    }
    fn sqrt(self) -> Self {
        let r = self.v.sqrt();
        Self {
            v: r,
            d: self.d * (S::from_f64(0.5) / r),
        }
    }
    fn sin(self) -> Self {
        Self {
            v: self.v.sin(),
            d: self.d * self.v.cos(),
        }
    }
    fn cos(self) -> Self {
        Self {
            v: self.v.cos(),
            d: -(self.d * self.v.sin()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Gauss–Legendre of order n integrates x^(2n−1) on [0, 1] exactly (1/(2n)).
    #[test]
    fn gauss_legendre_is_exact_for_its_degree() {
        for n in 1..=MAX_ORDER {
            let (x, w) = gauss_legendre(n);
            for p in 0..2 * n {
                let s: f64 = (0..n).map(|i| w[i] * x[i].powi(p as i32)).sum();
                let exact = 1.0 / (p as f64 + 1.0);
                assert!(
                    (s - exact).abs() < 1e-14,
                    "n = {n}, p = {p}: {s} vs {exact}"
                );
            }
        }
    }
}
