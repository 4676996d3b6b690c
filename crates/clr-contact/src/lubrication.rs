//! Lubricated revolute clearance joint: the hydrodynamic force of a dynamically loaded journal
//! bearing from the closed-form solutions of the Reynolds equation (short bearing after Ocvirk,
//! long bearing after Sommerfeld), with squeeze and wedge terms and half-Sommerfeld (Gümbel)
//! cavitation, its exact Jacobian, and the transition to the dry contact law near ε = 1.
//!
//! Theory, derivations and the verification table are in `docs/lubrication.md`; the cases are
//! `cargo xtask verify lubrication`.
//!
//! # Frame and conventions
//!
//! The geometry is that of [`RevoluteClearance`]: bearing (hole, body i) radius R, journal (pin,
//! body j) radius r, radial clearance c = R − r, eccentricity vector **e** = r_j^P − r_i^P
//! (journal centre minus bearing centre), **n** = **e**/e, **t** = k̂ × **n**. Symbols:
//!
//! | symbol | meaning | unit |
//! |---|---|---|
//! | ε = e/c | eccentricity ratio, 0 ≤ ε < 1 | – |
//! | ε̇ = ė·**n**/c | eccentricity-ratio rate (> 0 approaching the wall: squeezing) | 1/s |
//! | γ̇ = (ė·**t**)/e | angular velocity of the line of centres | rad/s |
//! | ω_i, ω_j | bearing and journal angular velocities | rad/s |
//! | Ω = ω_i + ω_j − 2γ̇ | wedge speed | rad/s |
//! | ψ | angle on the circumference from **n** towards **t** | rad |
//! | h = c(1 − ε cos ψ) | film thickness (minimum c(1 − ε) at ψ = 0) | m |
//! | μ, L | dynamic viscosity, axial length | Pa·s, m |
//!
//! With surfaces moving at rω_i and rω_j, the Reynolds equation written in the frame of the line
//! of centres (Frêne et al. 1997, ch. 2; Pinkus & Sternlicht 1961, ch. 3) is
//!
//! (1/r²) ∂/∂ψ(h³ ∂p/∂ψ) + ∂/∂z(h³ ∂p/∂z) = 6μ(ω_i + ω_j) ∂h/∂ψ + 12μ ∂h/∂t
//!                                       = 6μc (εΩ sin ψ − 2ε̇ cos ψ).
//!
//! The film force on the journal, **F** = −∫∫ p (cos ψ **n** + sin ψ **t**) r dψ dz, is returned as
//! its radial component F_r (along **n**, negative when it pushes the journal back towards the
//! bearing centre) and tangential component F_t (along **t**): the sign convention of Flores et
//! al. (2009). In the dry-law convention of
//! [`RevoluteContact`](crate::revolute::RevoluteContact) (**f**_j = −F_N **n** + F_T **t**) that is
//! F_N = −F_r, F_T = F_t.
//!
//! # Closed forms
//!
//! The right-hand side is −12μ **V**·(cos ψ, sin ψ) with the effective squeeze velocity
//! **V** = c(ε̇, −εΩ/2) (Booker 1965): the film is squeezed on the half of the circumference that
//! **V** closes, ψ ∈ (ψ_V − π/2, ψ_V + π/2) with ψ_V = atan2(−εΩ, 2ε̇) (the *π-film*). All forces
//! reduce to the six integrals J_{..} = ∫ (1, cos, sin, cos², sin cos, sin²)(ψ)/(1 − ε cos ψ)³ dψ
//! over the π-film, evaluated in closed form with the Sommerfeld substitution
//! cos χ = (cos ψ − ε)/(1 − ε cos ψ) (Pinkus & Sternlicht 1961, ch. 3), which turns every integrand
//! into a trigonometric polynomial in χ.
//!
//! - **Short bearing** (Ocvirk 1952; Frêne et al. 1997; Flores et al. 2009): the circumferential
//!   flow is neglected, p = (3μ/c²)(z² − L²/4)(εΩ sin ψ − 2ε̇ cos ψ)/(1 − ε cos ψ)³. Its sign
//!   does not depend on z, so setting the negative pressures to zero (Gümbel) keeps exactly the
//!   π-film, and with K_s = μrL³/(2c²):
//!   F_r = K_s (εΩ J_sc − 2ε̇ J_cc), F_t = K_s (εΩ J_ss − 2ε̇ J_sc).
//!   Steady (ε̇ = 0, Ω > 0): F_r = −K_s·2ε²Ω/(1 − ε²)², F_t = K_s·πεΩ/(2(1 − ε²)^{3/2}).
//! - **Long bearing** (Sommerfeld 1904; Pinkus & Sternlicht 1961; Flores et al. 2009): the axial
//!   flow is neglected and the Reynolds equation is integrated over the π-film with ambient
//!   pressure at both ends (the half-Sommerfeld film of the steady bearing), with K_l = 6μr³L/c²:
//!   F_r = K_l (A_n + k J_s), F_t = −K_l (A_t + k J_c), A_n = −εΩ J_sc − 2ε̇ J_ss,
//!   A_t = −εΩ J_cc − 2ε̇ J_sc, k = (εΩ J_c + 2ε̇ J_s)/J_1.
//!   Steady: F_r = −K_l·2ε²Ω/((2 + ε²)(1 − ε²)), F_t = K_l·πεΩ/((2 + ε²)(1 − ε²)^{1/2}).
//!
//! [`PiFilm::Moving`] (the default) places the π-film where **V** closes the gap: for the short
//! bearing this is exactly "pressure set to zero where negative" for any motion. [`PiFilm::Fixed`]
//! keeps it at ψ ∈ (−π, 0) (θ ∈ (0, π) from the maximum film thickness), which reproduces the
//! published closed forms of Flores et al. (2009) term by term, including their squeeze terms
//! (e.g. short bearing F_r = −K_s[2ε²Ω/(1 − ε²)² + πε̇(1 + 2ε²)/(1 − ε²)^{5/2}]); both choices give
//! the same steady force. With a fixed film a pure squeeze produces a tangential force and a
//! reversed wedge speed (Ω < 0) an attracting radial force; the moving film has neither.
//!
//! The radius in the closed forms is the journal radius r (as in the ROSS implementation,
//! petrobras/ross `fluid_flow_coefficients.py`); using R instead changes the forces by O(c/r).
//!
//! # Viscous shear torque (Petroff)
//!
//! The pressure resultant passes through the journal centre; the shear stress of the film on
//! the two surfaces adds a torque on each. With the velocity profile of the Reynolds equation
//! (Couette plus Poiseuille), the shear stress on the journal is
//! τ_j = μ r(ω_i − ω_j)/h − (h/2) ∂p/∂x, on the bearing τ_b = −μ r(ω_i − ω_j)/h − (h/2) ∂p/∂x
//! (along ψ). Integrated over the surfaces (the pressure part by parts, ∂h/∂ψ = cε sin ψ), the
//! torques about each surface's own centre are
//!
//! T_j = T_C − (e/2) F_t,   T_b = −T_C − (e/2) F_t,   T_C = −2πμr³L(ω_j − ω_i)/(c√(1 − ε²)),
//!
//! (Petroff's law at ε = 0, N.P. Petroff 1883; with eccentricity and the pressure-induced term
//! (e/2)·W sin φ = (e/2)·F_t: Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film
//! Lubrication*, 2nd ed. 2004, ch. 10 (journal and bearing friction of the short bearing); Pinkus
//! & Sternlicht 1961, ch. 3). The Couette integral ∫dψ/(1 − ε cos ψ) = 2π/√(1 − ε²) is taken over
//! the whole circumference: the cavitated half carries lubricant streamers that still shear (the
//! usual assumption of these texts); the pressure term is exact for the π-film. The two torques
//! differ by the load × eccentricity term and sum to −e F_t = −(**e** × **F**)·k̂, the moment that
//! balances the pressure pair (F on the journal through its centre, −F on the bearing through
//! its centre): the lubricant, massless, carries no net moment. See
//! [`HydrodynamicBearing::joint_forces`] for how they are applied.
//!
//! # Near contact
//!
//! The closed forms diverge as (1 − ε²)^{−5/2}. A [`Transition`] (film threshold h_t, dry
//! threshold h_d < h_t) evaluates the film force at ε clamped to ε_t = 1 − h_t/c (finite,
//! continuous) and gives a C¹ weight w(h_min) ∈ [0, 1] for the dry law, h_min = c(1 − ε). The
//! multibody code should apply **F** = **F**_film(min(ε, ε_t)) + w(h_min)·**F**_dry; see
//! [`Transition`] for why the film force is kept (not faded out) under the dry force.
//!
//! # Sources
//!
//! - F.W. Ocvirk, *Short-bearing approximation for full journal bearings*, NACA TN 2808 (1952).
//! - A. Sommerfeld, Z. Math. Phys. 50 (1904) 97–155.
//! - O. Pinkus, B. Sternlicht, *Theory of Hydrodynamic Lubrication*, McGraw-Hill (1961), ch. 3.
//! - J.F. Booker, *Dynamically loaded journal bearings: mobility method of solution*, J. Basic
//!   Eng. 87 (1965) 537–546 (π-film located by the squeeze velocity).
//! - J. Frêne, D. Nicolas, B. Degueurce, D. Berthe, M. Godet, *Hydrodynamic Lubrication —
//!   Bearings and Thrust Bearings*, Elsevier (1997).
//! - P. Flores, J. Ambrósio, J.C.P. Claro et al., *Lubricated revolute joints in rigid multibody
//!   systems*, Nonlinear Dyn. 56 (2009) 277–295 (short- and long-bearing forces with squeeze and
//!   wedge terms, switch to the dry law near ε = 1).
//! - G.B. Daniel, T.H. Machado, K.L. Cavalca, Mech. Mach. Theory 99 (2016) 19–36 (time-dependent
//!   integration limits of the short-bearing force: the moving π-film).
//!
//! The equation numbers of these texts could not be checked here; every formula of this module is
//! derived in `docs/lubrication.md` and verified against independent numerical integrations of the
//! pressure field and a finite-difference solution of the finite-length Reynolds equation
//! (`cargo xtask verify lubrication`).

use core::f64::consts::PI;
use core::ops::{Add, Div, Mul, Neg, Sub};

use nalgebra::Vector2;

use crate::body::{perp, BodyState, GeneralizedForce};
use crate::error::{positive, ContactError};
use crate::revolute::{CentreLine, RevoluteClearance};

/// Which closed-form solution of the Reynolds equation gives the film force.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BearingModel {
    /// Infinitely short bearing (Ocvirk 1952): circumferential pressure flow neglected; suited to
    /// L/D ≲ 0.5 (the error is a few per cent at L/D = 0.25, see `docs/lubrication.md`).
    ShortBearing,
    /// Infinitely long bearing (Sommerfeld 1904; Pinkus & Sternlicht 1961): axial flow
    /// neglected; suited to L/D ≳ 2 (it overestimates the load of a finite bearing by ~1/(L/D)).
    LongBearing,
}

/// Where the active (pressurised) half of the film lies: the π-film of the half-Sommerfeld
/// (Gümbel) cavitation condition.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PiFilm {
    /// The half of the clearance that the effective squeeze velocity **V** = c(ε̇, −εΩ/2) closes,
    /// ψ ∈ (ψ_V − π/2, ψ_V + π/2), ψ_V = atan2(−εΩ, 2ε̇) (Booker 1965; Daniel et al. 2016). For the
    /// short bearing this is exactly the region of positive pressure for any motion.
    #[default]
    Moving,
    /// The steady-load film ψ ∈ (−π, 0) (θ ∈ (0, π) measured from the maximum film thickness in
    /// the direction of rotation) for every motion: the published closed forms of Flores et al.
    /// (2009). Same force as `Moving` when ε̇ = 0 and Ω > 0.
    Fixed,
}

/// A plain journal bearing filled with a Newtonian lubricant, validated at construction.
///
/// Cheap to copy; [`force_wedge`](Self::force_wedge), [`jacobian`](Self::jacobian) and
/// [`joint_forces`](Self::joint_forces) allocate nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HydrodynamicBearing {
    bearing_radius: f64,
    journal_radius: f64,
    length: f64,
    viscosity: f64,
    model: BearingModel,
    film: PiFilm,
}

/// Film force on the journal in the frame of the line of centres (N).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FilmForce {
    /// F_r, component along **n** (bearing centre → journal centre), N; negative when the film
    /// pushes the journal back towards the bearing centre. The dry-law normal force is F_N = −F_r.
    pub radial: f64,
    /// F_t, component along **t** = k̂ × **n**, N.
    pub tangential: f64,
}

/// Partial derivatives of the film force ([`FilmForce`] components) with respect to the three
/// arguments of [`HydrodynamicBearing::force_wedge`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FilmJacobian {
    /// ∂(F_r, F_t)/∂ε at fixed ε̇ and Ω, N.
    pub d_eccentricity_ratio: FilmForce,
    /// ∂(F_r, F_t)/∂ε̇ at fixed ε and Ω, N·s.
    pub d_eccentricity_rate: FilmForce,
    /// ∂(F_r, F_t)/∂Ω at fixed ε and ε̇, N·s/rad.
    pub d_wedge_speed: FilmForce,
}

/// Hand-over from the film force to the dry contact law near ε = 1.
///
/// - For h_min = c(1 − ε) ≥ h_t the film force is evaluated as it is; below, at ε clamped to
///   ε_t = 1 − h_t/c (ε_t = 0 if h_t ≥ c): finite, continuous, and frozen in ε (its ε̇ and Ω
///   dependence, in particular the squeeze damping at ε_t, stays).
/// - The dry law is weighted by the C¹ cubic w(h_min) = x²(3 − 2x), x = (h_t − h_min)/(h_t − h_d)
///   clamped to [0, 1]: w = 0 for h_min ≥ h_t, w = 1 for h_min ≤ h_d, w′ = 0 at both ends.
///
/// **How to combine** (the multibody code): **F** = **F**_film(min(ε, ε_t)) + w(h_min)·**F**_dry,
/// i.e. F_N = −F_r + w·F_N,dry and F_T = F_t + w·F_T,dry on the journal, with the dry law of
/// [`RevoluteContact`](crate::revolute::RevoluteContact) at δ = e − c (zero while δ ≤ 0).
///
/// Why additive and not (1 − w)**F**_film + w**F**_dry: the film carries load until the surfaces
/// touch, and in mixed lubrication the asperity contact adds to the film pressure instead of
/// replacing it (load sharing of Johnson, Greenwood & Poon, Wear 19 (1972) 91–108, and of Patir &
/// Cheng's average-flow model). A convex blend would remove the film force over (h_d, h_t) while
/// the dry law, which acts only for δ > 0, gives nothing there: the journal would lose its support
/// just before metal contact and hit the wall harder than with either model alone. With the
/// additive form the total force is continuous, never smaller than the film force at ε_t, and
/// the weight only shapes how the dry force comes in: with h_d ≥ 0, w = 1 wherever the dry law is
/// active (plain sum); with h_d < 0 the dry law is faded in over the first |h_d| of penetration.
/// Flores et al. (2009) switch between the two forces at given eccentricity ratios ε0 < ε1 with a
/// transition zone; here the thresholds are film thicknesses, which relate to surface roughness
/// (h_t = k·√(σ_i² + σ_j²), [`Transition::from_roughness`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transition {
    film_threshold: f64,
    dry_threshold: f64,
}

/// Kinematics of a lubricated revolute joint at one state, in the variables of the film force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmKinematics {
    /// Eccentricity vector **e** = r_j^P − r_i^P, m.
    pub eccentricity_vector: Vector2<f64>,
    /// ε = |**e**|/c.
    pub eccentricity_ratio: f64,
    /// ε̇ = ė·**n**/c, 1/s (> 0 approaching the wall).
    pub eccentricity_rate: f64,
    /// γ̇ = (ė·**t**)/e, rad/s (0 when e = 0).
    pub line_of_centres_rate: f64,
    /// ω_i + ω_j, rad/s.
    pub angular_velocity_sum: f64,
    /// ω_j − ω_i, rad/s: the sliding speed of the surfaces over r (Couette shear).
    pub relative_angular_velocity: f64,
    /// Ω = ω_i + ω_j − 2γ̇, rad/s.
    pub wedge_speed: f64,
    /// εΩ = ε(ω_i + ω_j) − 2(ė·**t**)/c, 1/s: the wedge term, regular at e = 0 where Ω is not.
    pub wedge_term: f64,
    /// Unit normal **n** (world x axis when e = 0).
    pub normal: Vector2<f64>,
    /// Unit tangent **t** = k̂ × **n**.
    pub tangent: Vector2<f64>,
    /// Minimum film thickness h_min = c − e, m (negative when the nominal surfaces overlap).
    pub min_film_thickness: f64,
    /// World position of the journal centre r_j^P, m: the film force acts there.
    pub journal_centre: Vector2<f64>,
    bearing_reference: Vector2<f64>,
    journal_reference: Vector2<f64>,
}

/// Film forces of a lubricated revolute joint on its two bodies at one state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmJointForces {
    /// The kinematics the forces were evaluated at.
    pub kinematics: FilmKinematics,
    /// The eccentricity ratio the closed form was evaluated at, min(ε, ε_t).
    pub effective_eccentricity_ratio: f64,
    /// Film force on the journal in the frame of the line of centres, N.
    pub film: FilmForce,
    /// Weight w(h_min) ∈ [0, 1] of the dry contact force ([`Transition`]).
    pub dry_weight: f64,
    /// Viscous shear torques of the film on the journal and on the bearing, each about its own
    /// centre, at min(ε, ε_t), N·m.
    pub torques: FilmTorques,
    /// (f_x, f_y, m) of the film (pressure and shear) on the bearing body about its reference
    /// point.
    pub bearing: GeneralizedForce,
    /// (f_x, f_y, m) of the film (pressure and shear) on the journal body about its reference
    /// point.
    pub journal: GeneralizedForce,
}

/// Viscous shear torques of the film, each about the centre of its surface, N·m
/// (counter-clockwise positive; module docs, *Viscous shear torque*).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FilmTorques {
    /// Couette part on the journal, T_C = −2πμr³L(ω_j − ω_i)/(c√(1 − ε²)) (Petroff at ε = 0); the
    /// bearing's is −T_C.
    pub couette: f64,
    /// On the journal: T_j = T_C − (e/2) F_t.
    pub journal: f64,
    /// On the bearing: T_b = −T_C − (e/2) F_t.
    pub bearing: f64,
}

impl FilmForce {
    /// Magnitude |**F**| = √(F_r² + F_t²), N: the load capacity in steady operation.
    pub fn magnitude(&self) -> f64 {
        self.radial.hypot(self.tangential)
    }

    /// Attitude angle φ = atan2(F_t, −F_r), rad: the angle between the line of centres **n** and
    /// the external load that this force balances (−**F**). For the steady short bearing
    /// tan φ = π√(1 − ε²)/(4ε), for the long bearing tan φ = π√(1 − ε²)/(2ε).
    pub fn attitude_angle(&self) -> f64 {
        self.tangential.atan2(-self.radial)
    }

    /// The force as a world vector F_r **n** + F_t **t**, N.
    pub fn world(&self, normal: Vector2<f64>) -> Vector2<f64> {
        self.radial * normal + self.tangential * perp(normal)
    }

    fn scaled(self, k: f64) -> Self {
        Self {
            radial: k * self.radial,
            tangential: k * self.tangential,
        }
    }
}

impl HydrodynamicBearing {
    /// A bearing from its radius R (m), the journal radius r (m, 0 < r < R), the axial length
    /// L (m), the dynamic viscosity μ (Pa·s) and the closed-form model; π-film
    /// [`PiFilm::Moving`].
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] when a value is not positive and finite or r ≥ R.
    pub fn new(
        bearing_radius: f64,
        journal_radius: f64,
        length: f64,
        viscosity: f64,
        model: BearingModel,
    ) -> Result<Self, ContactError> {
        const LAW: &str = "hydrodynamic bearing";
        positive(LAW, "bearing radius R (m)", bearing_radius)?;
        positive(LAW, "journal radius r (m)", journal_radius)?;
        positive(LAW, "axial length L (m)", length)?;
        positive(LAW, "dynamic viscosity μ (Pa·s)", viscosity)?;
        if journal_radius >= bearing_radius {
            return Err(ContactError::invalid(
                LAW,
                "journal radius r (m)",
                journal_radius,
                format!(
                    "must be smaller than the bearing radius R = {bearing_radius} m so that the \
                     radial clearance c = R - r is positive"
                ),
            ));
        }
        Ok(Self {
            bearing_radius,
            journal_radius,
            length,
            viscosity,
            model,
            film: PiFilm::Moving,
        })
    }

    /// A bearing with the radii of a [`RevoluteClearance`], the axial length L (m), the viscosity
    /// μ (Pa·s) and the model.
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn for_joint(
        joint: &RevoluteClearance,
        length: f64,
        viscosity: f64,
        model: BearingModel,
    ) -> Result<Self, ContactError> {
        Self::new(
            joint.bearing_radius(),
            joint.journal_radius(),
            length,
            viscosity,
            model,
        )
    }

    /// The same bearing with the π-film placed as `film` says.
    pub fn with_pi_film(mut self, film: PiFilm) -> Self {
        self.film = film;
        self
    }

    /// Bearing radius R, m.
    pub fn bearing_radius(&self) -> f64 {
        self.bearing_radius
    }

    /// Journal radius r, m (the radius used in the closed forms).
    pub fn journal_radius(&self) -> f64 {
        self.journal_radius
    }

    /// Radial clearance c = R − r, m.
    pub fn clearance(&self) -> f64 {
        self.bearing_radius - self.journal_radius
    }

    /// Axial length L, m.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Dynamic viscosity μ, Pa·s.
    pub fn viscosity(&self) -> f64 {
        self.viscosity
    }

    /// The closed-form model.
    pub fn model(&self) -> BearingModel {
        self.model
    }

    /// The π-film placement.
    pub fn pi_film(&self) -> PiFilm {
        self.film
    }

    /// Film force from the eccentricity ratio ε (0 ≤ ε < 1), its rate ε̇ (1/s), the angular
    /// velocity of the line of centres γ̇ (rad/s) and the sum of the bearing and journal angular
    /// velocities ω_i + ω_j (rad/s): [`force_wedge`](Self::force_wedge) with Ω = ω_i + ω_j − 2γ̇.
    pub fn force(
        &self,
        eccentricity_ratio: f64,
        eccentricity_rate: f64,
        line_of_centres_rate: f64,
        angular_velocity_sum: f64,
    ) -> FilmForce {
        self.force_wedge(
            eccentricity_ratio,
            eccentricity_rate,
            angular_velocity_sum - 2.0 * line_of_centres_rate,
        )
    }

    /// Film force from ε (0 ≤ ε < 1; the closed forms diverge at ε = 1, use a [`Transition`]),
    /// ε̇ (1/s) and the wedge speed Ω = ω_i + ω_j − 2γ̇ (rad/s); formulas in the module
    /// documentation.
    pub fn force_wedge(
        &self,
        eccentricity_ratio: f64,
        eccentricity_rate: f64,
        wedge_speed: f64,
    ) -> FilmForce {
        let (fr, ft) = self.evaluate(
            eccentricity_ratio,
            eccentricity_rate,
            eccentricity_ratio * wedge_speed,
            wedge_speed,
        );
        FilmForce {
            radial: fr,
            tangential: ft,
        }
    }

    /// Film force and its exact partial derivatives with respect to ε, ε̇ and Ω at
    /// (ε, ε̇, Ω) (same arguments as [`force_wedge`](Self::force_wedge)).
    ///
    /// The derivatives are those of the closed forms themselves, propagated by forward-mode
    /// differentiation (dual numbers) through the same expressions, so they are exact to
    /// rounding; the film limits of [`PiFilm::Moving`] move with (ε, ε̇, Ω) and are included.
    /// Where the force is not differentiable (ε̇ = εΩ = 0, where the moving film flips) the
    /// derivative of the side the film would take for a small ε > 0 with this Ω is returned.
    ///
    /// For a multibody Jacobian use the chain rule with ε = |**e**|/c, ε̇ = ė·**n**/c,
    /// Ω = ω_i + ω_j − 2(ė·**t**)/|**e**| and **f**_j = F_r **n** + F_t **t**
    /// (∂**n**/∂**e** = **t** **t**ᵀ/|**e**|, ∂**t**/∂**e** = −**n** **t**ᵀ/|**e**|).
    pub fn jacobian(
        &self,
        eccentricity_ratio: f64,
        eccentricity_rate: f64,
        wedge_speed: f64,
    ) -> (FilmForce, FilmJacobian) {
        let eps = eccentricity_ratio;
        let (f, d_eps, d_rate, d_term) =
            self.evaluate_with_derivatives(eps, eccentricity_rate, eps * wedge_speed, wedge_speed);
        (
            f,
            FilmJacobian {
                d_eccentricity_ratio: FilmForce {
                    radial: d_eps.radial + wedge_speed * d_term.radial,
                    tangential: d_eps.tangential + wedge_speed * d_term.tangential,
                },
                d_eccentricity_rate: d_rate,
                d_wedge_speed: d_term.scaled(eps),
            },
        )
    }

    /// Couette (Petroff) shear torque on the journal about its centre, N·m, and its partials
    /// (∂/∂ε in N·m, ∂/∂(ω_j − ω_i) in N·m·s): T_C = −2πμr³L(ω_j − ω_i)/(c√(1 − ε²)) from ε
    /// (0 ≤ ε < 1) and the relative angular velocity ω_j − ω_i (rad/s). Petroff's law at ε = 0
    /// (module docs, *Viscous shear torque*); the bearing carries −T_C.
    pub fn couette_torque(
        &self,
        eccentricity_ratio: f64,
        relative_angular_velocity: f64,
    ) -> (f64, f64, f64) {
        let (r, c) = (self.journal_radius, self.clearance());
        let s = 1.0 - eccentricity_ratio * eccentricity_ratio;
        let k = -2.0 * PI * self.viscosity * r * r * r * self.length / (c * s.sqrt());
        let torque = k * relative_angular_velocity;
        (torque, torque * eccentricity_ratio / s, k)
    }

    /// Shear torques of the film on the journal and the bearing (each about its centre) at ε
    /// (0 ≤ ε < 1), relative angular velocity ω_j − ω_i (rad/s) and with the tangential film
    /// force F_t (N) at that ε: T_j = T_C − (e/2)F_t, T_b = −T_C − (e/2)F_t, e = εc (module docs,
    /// *Viscous shear torque*).
    pub fn shear_torques(
        &self,
        eccentricity_ratio: f64,
        relative_angular_velocity: f64,
        film: FilmForce,
    ) -> FilmTorques {
        let (couette, _, _) = self.couette_torque(eccentricity_ratio, relative_angular_velocity);
        let pressure = 0.5 * eccentricity_ratio * self.clearance() * film.tangential;
        FilmTorques {
            couette,
            journal: couette - pressure,
            bearing: -couette - pressure,
        }
    }

    /// Kinematics of the joint from the local coordinates (m) of the bearing centre on body i
    /// and of the journal centre on body j, and the two body states.
    pub fn kinematics(
        &self,
        bearing_centre: Vector2<f64>,
        journal_centre: Vector2<f64>,
        bearing: &BodyState,
        journal: &BodyState,
    ) -> FilmKinematics {
        let c = self.clearance();
        // The line of centres of RevoluteClearance::contact: the world x axis when the centres
        // coincide; the force stays correct there because it is written with εΩ, not Ω (see
        // wedge_term).
        let line = CentreLine::new(bearing_centre, journal_centre, bearing, journal);
        let (pj, e, normal) = (line.journal_centre, line.eccentricity, line.normal);
        let tangent = perp(normal);
        let e_dot = journal.point_velocity(pj) - bearing.point_velocity(line.bearing_centre);
        let v_t = e_dot.dot(&tangent);
        let omega_sum = bearing.angular_velocity + journal.angular_velocity;
        let gamma_dot = if line.centred { 0.0 } else { v_t / e };
        FilmKinematics {
            eccentricity_vector: line.eccentricity_vector,
            eccentricity_ratio: e / c,
            eccentricity_rate: e_dot.dot(&normal) / c,
            line_of_centres_rate: gamma_dot,
            angular_velocity_sum: omega_sum,
            relative_angular_velocity: journal.angular_velocity - bearing.angular_velocity,
            wedge_speed: omega_sum - 2.0 * gamma_dot,
            wedge_term: (e * omega_sum - 2.0 * v_t) / c,
            normal,
            tangent,
            min_film_thickness: c - e,
            journal_centre: pj,
            bearing_reference: bearing.position,
            journal_reference: journal.position,
        }
    }

    /// Film force at a kinematic state with the [`Transition`] clamp, and its Jacobian with
    /// respect to (ε, ε̇, Ω) (∂/∂ε = 0 beyond ε_t). Also returns min(ε, ε_t).
    pub fn film_force(
        &self,
        kinematics: &FilmKinematics,
        transition: &Transition,
    ) -> (FilmForce, FilmJacobian, f64) {
        let (eps, term) = self.clamped(kinematics, transition);
        let clamped = eps < kinematics.eccentricity_ratio;
        let omega = kinematics.wedge_speed;
        let (f, d_eps, d_rate, d_term) =
            self.evaluate_with_derivatives(eps, kinematics.eccentricity_rate, term, omega);
        let d_eccentricity_ratio = if clamped {
            FilmForce::default()
        } else {
            FilmForce {
                radial: d_eps.radial + omega * d_term.radial,
                tangential: d_eps.tangential + omega * d_term.tangential,
            }
        };
        (
            f,
            FilmJacobian {
                d_eccentricity_ratio,
                d_eccentricity_rate: d_rate,
                d_wedge_speed: d_term.scaled(eps),
            },
            eps,
        )
    }

    /// Generalized film forces on both bodies, with the [`Transition`] clamp and the dry weight;
    /// local centres (m) and body states as in [`kinematics`](Self::kinematics).
    ///
    /// The pressure resultant on the journal passes through the journal centre, so **f**_j =
    /// F_r **n** + F_t **t** is applied at r_j^P; the reaction −**f**_j on the bearing is applied
    /// on the same line (at r_j^P too), so the pair is collinear. The shear torques
    /// ([`FilmTorques`], at min(ε, ε_t)) are added as the couple T_j on the journal and
    /// −T_j = T_b + e F_t on the bearing: with −**f**_j at r_j^P (moment −e F_t about the bearing
    /// centre) the bearing's total moment about its centre is T_b. The added couples are equal
    /// and opposite, so the joint still conserves the angular momentum of the system exactly (as
    /// [`ForceApplication::CommonPoint`](crate::revolute::ForceApplication::CommonPoint) does for
    /// the dry law), and their power −T_j(ω_j − ω_i) counts with the film force's.
    ///
    /// The dry force is not included: add w·(dry generalized forces) as [`Transition`] says, e.g.
    /// `RevoluteClearance::contact(..).forces_from_laws_with(.., ForceApplication::CommonPoint)`
    /// scaled by [`FilmJointForces::dry_weight`].
    pub fn joint_forces(
        &self,
        transition: &Transition,
        bearing_centre: Vector2<f64>,
        journal_centre: Vector2<f64>,
        bearing: &BodyState,
        journal: &BodyState,
    ) -> FilmJointForces {
        let kin = self.kinematics(bearing_centre, journal_centre, bearing, journal);
        let (eps, term) = self.clamped(&kin, transition);
        let (fr, ft) = self.evaluate(eps, kin.eccentricity_rate, term, kin.wedge_speed);
        let film = FilmForce {
            radial: fr,
            tangential: ft,
        };
        let torques = self.shear_torques(eps, kin.relative_angular_velocity, film);
        let (mut on_bearing, mut on_journal) = kin.generalized_forces(film);
        on_journal.moment += torques.journal;
        on_bearing.moment -= torques.journal;
        FilmJointForces {
            kinematics: kin,
            effective_eccentricity_ratio: eps,
            film,
            dry_weight: transition.dry_weight(kin.min_film_thickness),
            torques,
            bearing: on_bearing,
            journal: on_journal,
        }
    }

    /// Closed-form film force (F_r, F_t) (N) at (ε, ε̇ in 1/s, εΩ in 1/s) in any
    /// [`Real`](crate::journal::Real) scalar (f64 or dual numbers), π-film as
    /// [`pi_film`](Self::pi_film) says; `omega` (Ω, rad/s) only decides the film side when
    /// ε̇ = εΩ = 0. The same expressions as [`force_wedge`](Self::force_wedge): the slices of the
    /// spatial long-bearing film ([`crate::journal_film`]).
    pub(crate) fn force_real<S: crate::journal::Real>(
        &self,
        eps: S,
        rate: S,
        term: S,
        omega: f64,
    ) -> (S, S) {
        let (e, v, t) = (RealScalar(eps), RealScalar(rate), RealScalar(term));
        let a = self.film_start(v, t, omega);
        let (fr, ft) = film_force(self.model, self.coefficient(), e, v, t, a);
        (fr.0, ft.0)
    }

    /// (min(ε, ε_t), εΩ at that ε with Ω kept).
    fn clamped(&self, kin: &FilmKinematics, transition: &Transition) -> (f64, f64) {
        let eps_t = transition.eccentricity_threshold(self.clearance());
        let eps = kin.eccentricity_ratio;
        if eps > eps_t {
            (eps_t, kin.wedge_term * (eps_t / eps))
        } else {
            (eps, kin.wedge_term)
        }
    }

    /// Force components at (ε, ε̇, εΩ); `omega` only decides the film side when ε̇ = εΩ = 0.
    fn evaluate(&self, eps: f64, rate: f64, term: f64, omega: f64) -> (f64, f64) {
        let a = self.film_start(rate, term, omega);
        film_force(self.model, self.coefficient(), eps, rate, term, a)
    }

    /// Force and its partial derivatives with respect to ε (at fixed ε̇, εΩ), ε̇ and εΩ.
    fn evaluate_with_derivatives(
        &self,
        eps: f64,
        rate: f64,
        term: f64,
        omega: f64,
    ) -> (FilmForce, FilmForce, FilmForce, FilmForce) {
        let e = Dual::var(eps, 0);
        let v = Dual::var(rate, 1);
        let s = Dual::var(term, 2);
        let a = self.film_start(v, s, omega);
        let (fr, ft) = film_force(self.model, self.coefficient(), e, v, s, a);
        let part = |k: usize| FilmForce {
            radial: fr.d[k],
            tangential: ft.d[k],
        };
        (
            FilmForce {
                radial: fr.v,
                tangential: ft.v,
            },
            part(0),
            part(1),
            part(2),
        )
    }

    /// K_s = μrL³/(2c²) or K_l = 6μr³L/c², N·s.
    fn coefficient(&self) -> f64 {
        let (r, l, c) = (self.journal_radius, self.length, self.clearance());
        match self.model {
            BearingModel::ShortBearing => self.viscosity * r * l * l * l / (2.0 * c * c),
            BearingModel::LongBearing => 6.0 * self.viscosity * r * r * r * l / (c * c),
        }
    }

    /// Start a of the π-film ψ ∈ (a, a + π).
    fn film_start<S: Scalar>(&self, rate: S, term: S, omega: f64) -> S {
        match self.film {
            PiFilm::Fixed => S::cst(-PI),
            PiFilm::Moving => {
                let (x, y) = (2.0 * rate.value(), -term.value());
                if x.hypot(y) > 1e-150 {
                    (-term).atan2(rate * 2.0) - S::cst(0.5 * PI)
                } else if omega != 0.0 {
                    // ε̇ = εΩ = 0: no force; take the side of a small ε > 0 with this Ω so that
                    // the ε-derivative is the one-sided one of the physical branch.
                    S::cst((-omega).atan2(0.0) - 0.5 * PI)
                } else {
                    S::cst(-0.5 * PI)
                }
            }
        }
    }
}

impl FilmKinematics {
    /// Generalized forces (bearing, journal) of the film force `film` on the journal applied at
    /// the journal centre, and of its reaction on the bearing on the same line
    /// (see [`HydrodynamicBearing::joint_forces`]).
    pub fn generalized_forces(&self, film: FilmForce) -> (GeneralizedForce, GeneralizedForce) {
        let f = film.world(self.normal);
        (
            GeneralizedForce::at(self.bearing_reference, self.journal_centre, -f),
            GeneralizedForce::at(self.journal_reference, self.journal_centre, f),
        )
    }
}

impl Transition {
    /// A transition from the film threshold h_t (m, > 0: below it the film force is frozen at
    /// ε_t = 1 − h_t/c) and the dry threshold h_d (m, < h_t: below it the dry law has full weight;
    /// h_d ≤ 0 fades the dry law in over the first |h_d| of penetration).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] when h_t is not positive and finite, h_d is not finite
    /// or h_d ≥ h_t.
    pub fn new(film_threshold: f64, dry_threshold: f64) -> Result<Self, ContactError> {
        const LAW: &str = "lubricated-joint transition";
        positive(LAW, "film threshold h_t (m)", film_threshold)?;
        if !dry_threshold.is_finite() || dry_threshold >= film_threshold {
            return Err(ContactError::invalid(
                LAW,
                "dry threshold h_d (m)",
                dry_threshold,
                format!(
                    "must be finite and smaller than the film threshold h_t = {film_threshold} m"
                ),
            ));
        }
        Ok(Self {
            film_threshold,
            dry_threshold,
        })
    }

    /// Thresholds from the RMS roughnesses σ_i, σ_j (m, ≥ 0, not both zero) of the bearing and
    /// journal surfaces: h_t = k_t σ, h_d = k_d σ with σ = √(σ_i² + σ_j²) (e.g. k_t = 3: the film
    /// parameter Λ = h_min/σ below which asperities interact; k_d ≤ 1).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for a negative or non-finite roughness, σ = 0, k_t not
    /// positive and finite, or k_d ≥ k_t.
    pub fn from_roughness(
        film_factor: f64,
        dry_factor: f64,
        bearing_roughness: f64,
        journal_roughness: f64,
    ) -> Result<Self, ContactError> {
        const LAW: &str = "lubricated-joint transition";
        for (name, s) in [
            ("bearing RMS roughness σ_i (m)", bearing_roughness),
            ("journal RMS roughness σ_j (m)", journal_roughness),
        ] {
            if !(s >= 0.0 && s.is_finite()) {
                return Err(ContactError::invalid(
                    LAW,
                    name,
                    s,
                    "must be >= 0 and finite",
                ));
            }
        }
        let sigma = bearing_roughness.hypot(journal_roughness);
        positive(LAW, "composite roughness √(σ_i² + σ_j²) (m)", sigma)?;
        positive(LAW, "film factor k_t (-)", film_factor)?;
        if !dry_factor.is_finite() || dry_factor >= film_factor {
            return Err(ContactError::invalid(
                LAW,
                "dry factor k_d (-)",
                dry_factor,
                format!("must be finite and smaller than the film factor k_t = {film_factor}"),
            ));
        }
        Self::new(film_factor * sigma, dry_factor * sigma)
    }

    /// Film threshold h_t, m.
    pub fn film_threshold(&self) -> f64 {
        self.film_threshold
    }

    /// Dry threshold h_d, m.
    pub fn dry_threshold(&self) -> f64 {
        self.dry_threshold
    }

    /// ε_t = max(1 − h_t/c, 0) for the radial clearance c (m).
    pub fn eccentricity_threshold(&self, clearance: f64) -> f64 {
        (1.0 - self.film_threshold / clearance).max(0.0)
    }

    /// Weight w(h_min) ∈ [0, 1] of the dry force at the minimum film thickness h_min (m).
    pub fn dry_weight(&self, min_film_thickness: f64) -> f64 {
        let x = self.progress(min_film_thickness);
        x * x * (3.0 - 2.0 * x)
    }

    /// dw/dh_min (1/m), ≤ 0, continuous (zero at both thresholds).
    pub fn dry_weight_derivative(&self, min_film_thickness: f64) -> f64 {
        let x = self.progress(min_film_thickness);
        -6.0 * x * (1.0 - x) / (self.film_threshold - self.dry_threshold)
    }

    fn progress(&self, h: f64) -> f64 {
        ((self.film_threshold - h) / (self.film_threshold - self.dry_threshold)).clamp(0.0, 1.0)
    }
}

/// Closed-form film force (F_r, F_t) at (ε, ε̇, εΩ) over the π-film ψ ∈ (a, a + π); generic so
/// that the same expressions give the value (f64) and the exact derivatives ([`Dual`]).
fn film_force<S: Scalar>(model: BearingModel, k: f64, eps: S, rate: S, term: S, a: S) -> (S, S) {
    let one = S::cst(1.0);
    let b2 = one - eps * eps;
    let b = b2.sqrt();
    // Sommerfeld angle χ(ψ), cos χ = (cos ψ − ε)/(1 − ε cos ψ), continuous in ψ (tan(χ/2) =
    // √((1+ε)/(1−ε)) tan(ψ/2) written without the branch cut): χ = ψ + 2 atan2(q sin ψ,
    // 1 − q cos ψ), q = ε/(1 + √(1 − ε²)).
    let q = eps / (one + b);
    let chi = |psi: S| psi + (q * psi.sin()).atan2(one - q * psi.cos()) * 2.0;
    let ends = [chi(a), chi(a + S::cst(PI))];
    let trig = ends.map(|x| (x, x.sin(), x.cos()));
    // [G]_a^b for an antiderivative G(χ, sin χ, cos χ) (static dispatch).
    fn between<S: Scalar>(trig: &[(S, S, S); 2], g: impl Fn(S, S, S) -> S) -> S {
        let ((xa, sa, ca), (xb, sb, cb)) = (trig[0], trig[1]);
        g(xb, sb, cb) - g(xa, sa, ca)
    }
    let ib3 = one / (b2 * b);
    let ib4 = one / (b2 * b2);
    let ib5 = ib4 / b;
    // ∫ sin²ψ/u³ dψ = β⁻³ ∫ sin²χ dχ etc., u = 1 − ε cos ψ, β = √(1 − ε²).
    let jss = ib3 * between(&trig, |x, s, c| (x - s * c) * 0.5);
    let jsc = ib4 * between(&trig, |_, s, c| s * s * 0.5 - eps * c);
    let jcc = ib5
        * between(&trig, |x, s, c| {
            (x + s * c) * 0.5 + eps * s * 2.0 + eps * eps * x
        });
    let two_rate = rate * 2.0;
    match model {
        BearingModel::ShortBearing => (
            (term * jsc - two_rate * jcc) * k,
            (term * jss - two_rate * jsc) * k,
        ),
        BearingModel::LongBearing => {
            let j1 = ib5
                * between(&trig, |x, s, c| {
                    x + eps * s * 2.0 + eps * eps * (x + s * c) * 0.5
                });
            let jc = ib5
                * between(&trig, |x, s, c| {
                    (one + eps * eps) * s + eps * (x * 3.0 + s * c) * 0.5
                });
            let js = ib4 * between(&trig, |_, s, c| eps * s * s * 0.5 - c);
            // r²p′/(6μ... ) ∝ (M + κ)/u³ with M = −εΩ cos ψ − 2ε̇ sin ψ and κ from p(a) = p(a+π).
            let kappa = (term * jc + two_rate * js) / j1;
            let a_n = -(term * jsc) - two_rate * jss;
            let a_t = -(term * jcc) - two_rate * jsc;
            ((a_n + kappa * js) * k, -(a_t + kappa * jc) * k)
        }
    }
}

/// The arithmetic [`film_force`] needs, for f64 and for [`Dual`].
trait Scalar:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Mul<f64, Output = Self>
{
    fn cst(x: f64) -> Self;
    fn value(self) -> f64;
    fn sin(self) -> Self;
    fn cos(self) -> Self;
    fn sqrt(self) -> Self;
    fn atan2(self, x: Self) -> Self;
}

impl Scalar for f64 {
    fn cst(x: f64) -> Self {
        x
    }
    fn value(self) -> f64 {
        self
    }
    fn sin(self) -> Self {
        f64::sin(self)
    }
    fn cos(self) -> Self {
        f64::cos(self)
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    fn atan2(self, x: Self) -> Self {
        f64::atan2(self, x)
    }
}

/// A [`Real`](crate::journal::Real) scalar seen as a [`Scalar`], so that the closed forms run in
/// the spatial journal's scalar types (f64 and the multibody dual numbers).
#[derive(Debug, Clone, Copy)]
struct RealScalar<S>(S);

impl<S: crate::journal::Real> Add for RealScalar<S> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self(self.0 + o.0)
    }
}

impl<S: crate::journal::Real> Sub for RealScalar<S> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self(self.0 - o.0)
    }
}

impl<S: crate::journal::Real> Mul for RealScalar<S> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self(self.0 * o.0)
    }
}

impl<S: crate::journal::Real> Div for RealScalar<S> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        Self(self.0 / o.0)
    }
}

impl<S: crate::journal::Real> Neg for RealScalar<S> {
    type Output = Self;
    fn neg(self) -> Self {
        Self(-self.0)
    }
}

impl<S: crate::journal::Real> Mul<f64> for RealScalar<S> {
    type Output = Self;
    fn mul(self, k: f64) -> Self {
        Self(self.0 * S::from_f64(k))
    }
}

impl<S: crate::journal::Real> Scalar for RealScalar<S> {
    fn cst(x: f64) -> Self {
        Self(S::from_f64(x))
    }
    fn value(self) -> f64 {
        self.0.value()
    }
    fn sin(self) -> Self {
        Self(self.0.sin())
    }
    fn cos(self) -> Self {
        Self(self.0.cos())
    }
    fn sqrt(self) -> Self {
        Self(self.0.sqrt())
    }
    fn atan2(self, x: Self) -> Self {
        let (y, xv) = (self.0.value(), x.0.value());
        let r2 = y * y + xv * xv;
        Self(S::chain2(self.0, x.0, y.atan2(xv), xv / r2, -y / r2))
    }
}

/// Forward-mode dual number with three derivative directions (ε, ε̇, εΩ).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Dual {
    v: f64,
    d: [f64; 3],
}

impl Dual {
    fn var(v: f64, k: usize) -> Self {
        let mut d = [0.0; 3];
        d[k] = 1.0;
        Self { v, d }
    }

    fn chain(self, v: f64, dv: f64) -> Self {
        Self {
            v,
            d: self.d.map(|x| dv * x),
        }
    }
}

impl Add for Dual {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            v: self.v + o.v,
            d: [self.d[0] + o.d[0], self.d[1] + o.d[1], self.d[2] + o.d[2]],
        }
    }
}

impl Sub for Dual {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self {
            v: self.v - o.v,
            d: [self.d[0] - o.d[0], self.d[1] - o.d[1], self.d[2] - o.d[2]],
        }
    }
}

impl Mul for Dual {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self {
            v: self.v * o.v,
            d: [
                self.d[0] * o.v + self.v * o.d[0],
                self.d[1] * o.v + self.v * o.d[1],
                self.d[2] * o.v + self.v * o.d[2],
            ],
        }
    }
}

impl Div for Dual {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.v;
        let v = self.v * inv;
        Self {
            v,
            d: [
                (self.d[0] - v * o.d[0]) * inv,
                (self.d[1] - v * o.d[1]) * inv,
                (self.d[2] - v * o.d[2]) * inv,
            ],
        }
    }
}

impl Neg for Dual {
    type Output = Self;
    fn neg(self) -> Self {
        self.chain(-self.v, -1.0)
    }
}

impl Mul<f64> for Dual {
    type Output = Self;
    fn mul(self, k: f64) -> Self {
        self.chain(self.v * k, k)
    }
}

impl Scalar for Dual {
    fn cst(x: f64) -> Self {
        Self { v: x, d: [0.0; 3] }
    }
    fn value(self) -> f64 {
        self.v
    }
    fn sin(self) -> Self {
        let (s, c) = self.v.sin_cos();
        self.chain(s, c)
    }
    fn cos(self) -> Self {
        let (s, c) = self.v.sin_cos();
        self.chain(c, -s)
    }
    fn sqrt(self) -> Self {
        let r = self.v.sqrt();
        self.chain(r, 0.5 / r)
    }
    fn atan2(self, x: Self) -> Self {
        let r2 = self.v * self.v + x.v * x.v;
        let (a, b) = (x.v / r2, -self.v / r2);
        Self {
            v: self.v.atan2(x.v),
            d: [
                a * self.d[0] + b * x.d[0],
                a * self.d[1] + b * x.d[1],
                a * self.d[2] + b * x.d[2],
            ],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// R = 10 mm, r = 9.95 mm (c = 50 µm), L = 10 mm, μ = 0.04 Pa·s.
    fn bearing(model: BearingModel) -> HydrodynamicBearing {
        HydrodynamicBearing::new(10e-3, 9.95e-3, 10e-3, 0.04, model).unwrap()
    }

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs().max(1e-300)
    }

    #[test]
    fn invalid_parameters_are_typed_errors() {
        let m = BearingModel::ShortBearing;
        for (args, name) in [
            ((0.0, 9e-3, 1e-2, 0.04), "bearing radius R (m)"),
            ((1e-2, -1.0, 1e-2, 0.04), "journal radius r (m)"),
            ((1e-2, 9e-3, f64::NAN, 0.04), "axial length L (m)"),
            ((1e-2, 9e-3, 1e-2, 0.0), "dynamic viscosity μ (Pa·s)"),
            ((1e-2, 1e-2, 1e-2, 0.04), "journal radius r (m)"),
        ] {
            match HydrodynamicBearing::new(args.0, args.1, args.2, args.3, m) {
                Err(ContactError::InvalidParameter { name: n, .. }) => assert_eq!(n, name),
                other => panic!("{args:?}: {other:?}"),
            }
        }
        let e = HydrodynamicBearing::new(1e-2, 1e-2, 1e-2, 0.04, m).unwrap_err();
        assert!(
            e.to_string().contains("smaller than the bearing radius"),
            "{e}"
        );
        assert!(Transition::new(0.0, -1.0).is_err());
        assert!(Transition::new(1e-6, 1e-6).is_err());
        assert!(Transition::new(1e-6, f64::NEG_INFINITY).is_err());
        assert!(Transition::from_roughness(3.0, 1.0, 0.0, 0.0).is_err());
        assert!(Transition::from_roughness(3.0, 3.0, 1e-7, 1e-7).is_err());
        assert!(Transition::from_roughness(3.0, 1.0, -1e-7, 1e-7).is_err());
        let t = Transition::from_roughness(3.0, 1.0, 0.3e-6, 0.4e-6).unwrap();
        assert!(rel(t.film_threshold(), 1.5e-6) < 1e-15 && rel(t.dry_threshold(), 0.5e-6) < 1e-15);
    }

    /// Steady short bearing against the Ocvirk relations (Hamrock, Schmid & Jacobson,
    /// *Fundamentals of Fluid Film Lubrication*, 2nd ed. 2004; ROSS fluid_flow_coefficients.py):
    /// W = μUL³ε/(4c²(1−ε²)²)·√(π²(1−ε²) + 16ε²), U = rω, tan φ = π√(1−ε²)/(4ε). Tolerance 1e-12.
    #[test]
    fn short_steady_matches_ocvirk() {
        let b = bearing(BearingModel::ShortBearing);
        let (r, l, c, mu, w): (f64, f64, f64, f64, f64) = (9.95e-3, 10e-3, 50e-6, 0.04, 300.0);
        for film in [PiFilm::Moving, PiFilm::Fixed] {
            let b = b.with_pi_film(film);
            for eps in [0.0, 0.01, 0.2, 0.5, 0.8, 0.95] {
                let f = b.force(eps, 0.0, 0.0, w);
                let e2 = 1.0 - eps * eps;
                let load = mu * r * w * l.powi(3) * eps / (4.0 * c * c * e2 * e2)
                    * (PI * PI * e2 + 16.0 * eps * eps).sqrt();
                assert!(
                    (f.magnitude() - load).abs() <= 1e-12 * load.max(1e-30),
                    "{eps}"
                );
                if eps > 0.0 {
                    let phi = (PI * e2.sqrt() / (4.0 * eps)).atan();
                    assert!((f.attitude_angle() - phi).abs() < 1e-12, "{eps}");
                }
            }
        }
    }

    /// Steady long bearing, half-Sommerfeld: W = 6μUr²Lε√(π²(1−ε²) + 4ε²)/(c²(2+ε²)(1−ε²)),
    /// tan φ = π√(1−ε²)/(2ε) (Pinkus & Sternlicht 1961, ch. 3; ROSS). Tolerance 1e-11.
    #[test]
    fn long_steady_matches_sommerfeld() {
        let b = bearing(BearingModel::LongBearing);
        let (r, l, c, mu, w): (f64, f64, f64, f64, f64) = (9.95e-3, 10e-3, 50e-6, 0.04, 300.0);
        for film in [PiFilm::Moving, PiFilm::Fixed] {
            let b = b.with_pi_film(film);
            for eps in [0.01, 0.2, 0.5, 0.8, 0.95] {
                let f = b.force(eps, 0.0, 0.0, w);
                let e2 = 1.0 - eps * eps;
                let load = 6.0 * mu * w * r.powi(3) * l * eps / (c * c * (2.0 + eps * eps) * e2)
                    * (PI * PI * e2 + 4.0 * eps * eps).sqrt();
                assert!(rel(f.magnitude(), load) < 1e-11, "{eps}: {f:?} {load}");
                let phi = (PI * e2.sqrt() / (2.0 * eps)).atan();
                assert!((f.attitude_angle() - phi).abs() < 1e-11, "{eps}");
            }
        }
    }

    /// The fixed π-film reproduces the dynamic closed forms of Flores et al. (2009) (derived in
    /// docs/lubrication.md §3 from the Reynolds equation on θ ∈ (0, π)).
    #[test]
    fn fixed_film_matches_published_dynamic_forms() {
        let (r, l, c, mu): (f64, f64, f64, f64) = (9.95e-3, 10e-3, 50e-6, 0.04);
        let short = bearing(BearingModel::ShortBearing).with_pi_film(PiFilm::Fixed);
        let long = bearing(BearingModel::LongBearing).with_pi_film(PiFilm::Fixed);
        for (eps, rate, om) in [(0.3, 2.0, 100.0), (0.7, -5.0, 40.0), (0.9, 1.0, -30.0)] {
            let e2: f64 = 1.0 - eps * eps;
            let ks = mu * r * l.powi(3) / (2.0 * c * c);
            let fr = -ks
                * (2.0 * eps * eps * om / (e2 * e2)
                    + PI * rate * (1.0 + 2.0 * eps * eps) / e2.powf(2.5));
            let ft = ks * (PI * eps * om / (2.0 * e2.powf(1.5)) + 4.0 * eps * rate / (e2 * e2));
            let f = short.force_wedge(eps, rate, om);
            assert!(
                rel(f.radial, fr) < 1e-12 && rel(f.tangential, ft) < 1e-12,
                "{eps}"
            );
            let kl = 12.0 * mu * r.powi(3) * l / (c * c);
            let fr = -kl
                * (eps * eps * om / ((2.0 + eps * eps) * e2)
                    + rate / e2.powf(1.5) * (PI / 2.0 - 8.0 / (PI * (2.0 + eps * eps))));
            let ft = kl
                * (PI * eps * om / (2.0 * (2.0 + eps * eps) * e2.sqrt())
                    + 2.0 * eps * rate / ((2.0 + eps * eps) * e2));
            let f = long.force_wedge(eps, rate, om);
            assert!(
                rel(f.radial, fr) < 1e-11 && rel(f.tangential, ft) < 1e-11,
                "{eps}"
            );
        }
    }

    /// Short bearing, moving π-film: against a direct quadrature of the clipped pressure
    /// max(p, 0) of the short-bearing solution (composite Simpson, 20000 intervals in ψ; the z
    /// integral of (z² − L²/4) is exact, −L³/6). Tolerance 1e-7 (quadrature error at the kinks).
    #[test]
    fn short_moving_matches_clipped_pressure() {
        let b = bearing(BearingModel::ShortBearing);
        let (r, l, c, mu): (f64, f64, f64, f64) = (9.95e-3, 10e-3, 50e-6, 0.04);
        for (eps, rate, om) in [(0.4, 3.0, 120.0), (0.6, -8.0, -50.0), (0.0, 2.0, 0.0)] {
            let n = 20000;
            let h = 2.0 * PI / n as f64;
            let (mut fr, mut ft) = (0.0, 0.0);
            for k in 0..=n {
                let psi = -PI + k as f64 * h;
                let w = if k == 0 || k == n {
                    1.0
                } else if k % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                let g = (eps * om * psi.sin() - 2.0 * rate * psi.cos())
                    / (1.0 - eps * psi.cos()).powi(3);
                // p = (3μ/c²)(z² − L²/4) g ≥ 0 where g < 0; ∫p dz = −(μL³/(2c²)) g.
                let pz = (-mu * l.powi(3) / (2.0 * c * c) * g).max(0.0);
                fr -= w * pz * psi.cos() * r * h / 3.0;
                ft -= w * pz * psi.sin() * r * h / 3.0;
            }
            let f = b.force_wedge(eps, rate, om);
            let scale = f.magnitude();
            assert!(
                (f.radial - fr).abs() < 1e-7 * scale,
                "{eps}: {f:?} {fr} {ft}"
            );
            assert!(
                (f.tangential - ft).abs() < 1e-7 * scale,
                "{eps}: {f:?} {fr} {ft}"
            );
        }
    }

    /// Pure squeeze with the moving π-film centred on **n** (docs/lubrication.md §4–5):
    /// short F_r = −(μrL³ε̇/c²)[(1+2ε²)χ₀ + 3ε√(1−ε²)]/(1−ε²)^{5/2}, long
    /// F_r = −(12μr³Lε̇/c²)(χ₀ + ε√(1−ε²))/(1−ε²)^{3/2}, χ₀ = π/2 + asin ε; F_t = 0.
    #[test]
    fn pure_squeeze_closed_forms() {
        let (r, l, c, mu, rate): (f64, f64, f64, f64, f64) = (9.95e-3, 10e-3, 50e-6, 0.04, 3.0);
        for eps in [0.0f64, 0.3, 0.7, 0.9] {
            let b = (1.0 - eps * eps).sqrt();
            let chi0 = 0.5 * PI + eps.asin();
            let short = -(mu * r * l.powi(3) * rate / (c * c))
                * ((1.0 + 2.0 * eps * eps) * chi0 + 3.0 * eps * b)
                / b.powi(5);
            let long = -(12.0 * mu * r.powi(3) * l * rate / (c * c)) * (chi0 + eps * b) / b.powi(3);
            let fs = bearing(BearingModel::ShortBearing).force_wedge(eps, rate, 0.0);
            let fl = bearing(BearingModel::LongBearing).force_wedge(eps, rate, 0.0);
            assert!(rel(fs.radial, short) < 1e-12, "{eps}: {fs:?} {short}");
            assert!(rel(fl.radial, long) < 1e-12, "{eps}: {fl:?} {long}");
            assert!(fs.tangential.abs() < 1e-12 * short.abs());
            assert!(fl.tangential.abs() < 1e-12 * long.abs());
        }
    }

    /// Signs and symmetries of the moving π-film: squeezing pushes the journal back, separating
    /// pulls it towards the wall it leaves (the film on the far side is squeezed), a pure squeeze
    /// has no tangential force, reversing Ω mirrors F_t.
    #[test]
    fn moving_film_signs() {
        for model in [BearingModel::ShortBearing, BearingModel::LongBearing] {
            let b = bearing(model);
            let f = b.force_wedge(0.5, 4.0, 0.0);
            assert!(f.radial < 0.0 && f.tangential.abs() < 1e-12 * f.radial.abs());
            let g = b.force_wedge(0.5, -4.0, 0.0);
            assert!(g.radial > 0.0 && g.tangential.abs() < 1e-12 * g.radial.abs());
            let p = b.force_wedge(0.5, 1.0, 200.0);
            let m = b.force_wedge(0.5, 1.0, -200.0);
            assert!(p.radial < 0.0 && p.tangential > 0.0);
            assert!(rel(m.radial, p.radial) < 1e-12 && rel(-m.tangential, p.tangential) < 1e-12);
            // Homogeneous of degree one in (ε̇, Ω).
            let q = b.force_wedge(0.5, 2.0, 400.0);
            assert!(rel(q.radial, 2.0 * p.radial) < 1e-12);
            assert!(b.force_wedge(0.5, 0.0, 0.0).magnitude() == 0.0);
        }
    }

    /// The Jacobian against central differences, relative 1e-6 of the largest entry.
    #[test]
    fn jacobian_matches_central_differences() {
        let states = [
            (0.3, 2.0, 150.0),
            (0.75, -3.0, 60.0),
            (0.9, 0.5, -80.0),
            (0.05, 4.0, 10.0),
            (0.5, 0.0, 100.0),
            (0.6, 5.0, 0.0),
        ];
        for model in [BearingModel::ShortBearing, BearingModel::LongBearing] {
            for film in [PiFilm::Moving, PiFilm::Fixed] {
                let b = bearing(model).with_pi_film(film);
                for (eps, rate, om) in states {
                    let (f0, j) = b.jacobian(eps, rate, om);
                    let f1 = b.force_wedge(eps, rate, om);
                    assert!((f0.radial - f1.radial).abs() <= 1e-14 * f1.magnitude());
                    assert!((f0.tangential - f1.tangential).abs() <= 1e-14 * f1.magnitude());
                    let fd = |i: usize| {
                        let hx = [1e-6, 1e-5 * rate.abs().max(1.0), 1e-5 * om.abs().max(1.0)][i];
                        let mut x = [eps, rate, om];
                        x[i] += hx;
                        let p = b.force_wedge(x[0], x[1], x[2]);
                        x[i] -= 2.0 * hx;
                        let m = b.force_wedge(x[0], x[1], x[2]);
                        FilmForce {
                            radial: (p.radial - m.radial) / (2.0 * hx),
                            tangential: (p.tangential - m.tangential) / (2.0 * hx),
                        }
                    };
                    for (i, an) in [
                        j.d_eccentricity_ratio,
                        j.d_eccentricity_rate,
                        j.d_wedge_speed,
                    ]
                    .into_iter()
                    .enumerate()
                    {
                        let num = fd(i);
                        let scale = an.magnitude().max(num.magnitude()).max(1e-300);
                        let err = (an.radial - num.radial)
                            .abs()
                            .max((an.tangential - num.tangential).abs());
                        assert!(
                            err <= 1e-6 * scale,
                            "{model:?} {film:?} {eps} {rate} {om} d{i}: {an:?} vs {num:?}"
                        );
                    }
                }
            }
        }
    }

    /// At e = 0 the squeeze force is isotropic: −(πK_s/c)·v for the short bearing whatever the
    /// direction of the journal velocity v (the reported normal is the world x axis there).
    #[test]
    fn centred_journal_squeeze_is_isotropic() {
        let b = bearing(BearingModel::ShortBearing);
        let t = Transition::new(1e-6, 0.0).unwrap();
        let c = b.clearance();
        let ks = 0.04 * 9.95e-3 * 1e-6 / (2.0 * c * c);
        for v in [Vector2::new(0.0, 0.01), Vector2::new(-0.003, 0.004)] {
            let journal = BodyState::new(Vector2::zeros(), 0.0, v, 50.0);
            let out = b.joint_forces(
                &t,
                Vector2::zeros(),
                Vector2::zeros(),
                &BodyState::default(),
                &journal,
            );
            let expect = -(PI * ks / c) * v;
            assert!(
                (out.journal.force - expect).norm() < 1e-12 * expect.norm(),
                "{out:?}"
            );
            // the only moment is Petroff's torque, on the journal spinning at 50 rad/s
            let petroff = 2.0 * PI * 0.04 * 9.95e-3f64.powi(3) * 10e-3 * 50.0 / c;
            assert!(rel(out.journal.moment, -petroff) < 1e-12, "{out:?}");
        }
    }

    /// Petroff's law at ε = 0 (N.P. Petroff 1883; Hamrock, Schmid & Jacobson 2004, ch. 10):
    /// T = 2πμr³Lω/c against the journal's rotation relative to the bearing, equal and opposite
    /// on the bearing, for both models, with the bearing turning too; and T_C(ε) → Petroff as
    /// ε → 0. Tolerance 1e-14 (the same formula evaluated twice, round-off only).
    #[test]
    fn petroff_torque_at_zero_eccentricity() {
        let t = Transition::new(1e-6, 0.0).unwrap();
        let (mu, r, l): (f64, f64, f64) = (0.04, 9.95e-3, 10e-3);
        for model in [BearingModel::ShortBearing, BearingModel::LongBearing] {
            let b = bearing(model);
            let c = b.clearance();
            let (wi, wj) = (-12.0, 300.0);
            let petroff = 2.0 * PI * mu * r.powi(3) * l * (wj - wi) / c;
            let housing = BodyState::new(Vector2::zeros(), 0.0, Vector2::zeros(), wi);
            let journal = BodyState::new(Vector2::zeros(), 0.0, Vector2::zeros(), wj);
            let out = b.joint_forces(&t, Vector2::zeros(), Vector2::zeros(), &housing, &journal);
            assert!(out.journal.force.norm() < 1e-30, "{out:?}");
            assert!(rel(out.journal.moment, -petroff) < 1e-14, "{out:?}");
            assert!(rel(out.bearing.moment, petroff) < 1e-14, "{out:?}");
            assert!(rel(out.torques.couette, -petroff) < 1e-14);
            let (tc, d_eps, d_w) = b.couette_torque(1e-4, wj - wi);
            assert!(
                rel(tc, -petroff) < 1e-8,
                "O(ε²) from Petroff: {tc} vs {petroff}"
            );
            assert!(rel(d_w * (wj - wi), tc) < 1e-14);
            assert!(rel(d_eps, tc * 1e-4 / (1.0 - 1e-8)) < 1e-14);
        }
    }

    /// The shear torques of the short bearing at ε > 0 against an independent quadrature of the
    /// shear stress over the surfaces (module docs, *Viscous shear torque*): the Couette part
    /// μr(ω_i − ω_j)/h over the whole circumference and the Poiseuille part −(h/2)∂p/∂x on the
    /// π-film, with the Ocvirk pressure p = (3μ/c²)(z² − L²/4)(εΩ sin ψ − 2ε̇ cos ψ)/(1 − ε cos ψ)³
    /// differentiated in closed form and ∫(z² − L²/4)dz = −L³/6; 200 000 midpoints in ψ
    /// (periodic or vanishing at the film ends: error far below the tolerance 1e-8). Steady and
    /// squeezing states, both surfaces turning.
    #[test]
    fn short_bearing_shear_torques_match_the_integrated_shear_stress() {
        let b = bearing(BearingModel::ShortBearing);
        let (mu, r, l, c): (f64, f64, f64, f64) = (0.04, 9.95e-3, 10e-3, b.clearance());
        for (eps, rate, wi, wj) in [(0.3, 0.0, 0.0, 300.0), (0.7, 20.0, -40.0, 150.0)] {
            let omega = wi + wj; // γ̇ = 0
            let film = b.force_wedge(eps, rate, omega);
            let tq = b.shear_torques(eps, wj - wi, film);
            let n = 200_000;
            let (mut couette, mut poiseuille) = (0.0, 0.0);
            // π-film start as PiFilm::Moving places it
            let a = (-eps * omega).atan2(2.0 * rate) - 0.5 * PI;
            for k in 0..n {
                let psi = 2.0 * PI * (k as f64 + 0.5) / n as f64;
                let h = c * (1.0 - eps * psi.cos());
                couette += mu * r * (wi - wj) / h * r * (2.0 * PI / n as f64) * l * r;
                let chi = a + PI * (k as f64 + 0.5) / n as f64;
                let (s, co) = chi.sin_cos();
                let den = 1.0 - eps * co;
                let g = eps * omega * s - 2.0 * rate * co;
                let dg = eps * omega * co + 2.0 * rate * s;
                // dP/dψ of P = (3μ/c²) g/den³ (den' = ε sin ψ)
                let dp = 3.0 * mu / (c * c) * (dg / den.powi(3) - 3.0 * g * eps * s / den.powi(4));
                let hf = c * den;
                // −(h/2)(1/r)∂p/∂ψ, times r dψ dz and the arm r; ∫(z² − L²/4)dz = −L³/6
                poiseuille += -0.5 * hf * dp * (-l.powi(3) / 6.0) * r * (PI / n as f64);
            }
            let journal = couette + poiseuille;
            // bearing: Couette reversed, Poiseuille the same
            let bearing_t = -couette + poiseuille;
            assert!(
                rel(tq.journal, journal) < 1e-8,
                "{eps}: {tq:?} vs {journal}"
            );
            assert!(
                rel(tq.bearing, bearing_t) < 1e-8,
                "{eps}: {tq:?} vs {bearing_t}"
            );
            assert!(rel(tq.couette, couette) < 1e-8);
        }
    }

    /// Generalized forces: action–reaction on one line (zero net moment about any point), the
    /// film force of the kinematic state equal to the closed form at (ε, ε̇, Ω), and the clamp.
    #[test]
    fn joint_forces_are_consistent() {
        let b = bearing(BearingModel::LongBearing);
        let c = b.clearance();
        let t = Transition::new(2e-6, 0.5e-6).unwrap();
        let bearing_state =
            BodyState::new(Vector2::new(0.1, -0.2), 0.3, Vector2::new(0.2, 0.1), 3.0);
        let s_i = Vector2::new(0.05, 0.02);
        let s_j = Vector2::new(-0.01, 0.0);
        for (eps, dir) in [(0.4, 0.7), (0.99, -2.0)] {
            let centre = bearing_state.point(s_i);
            let n = Vector2::new(f64::cos(dir), f64::sin(dir));
            let pj = centre + eps * c * n;
            let journal_state = BodyState::new(pj - s_j, 0.0, Vector2::new(-0.3, 0.5), -20.0);
            let out = b.joint_forces(&t, s_i, s_j, &bearing_state, &journal_state);
            let k = out.kinematics;
            assert!((k.eccentricity_ratio - eps).abs() < 1e-9, "{k:?}");
            let total = out.bearing.force + out.journal.force;
            assert!(total.norm() < 1e-12 * out.journal.force.norm());
            // Net moment about the origin: m_k + r_k × f_k.
            let cross = |a: Vector2<f64>, b: Vector2<f64>| a.x * b.y - a.y * b.x;
            let m = out.bearing.moment
                + cross(bearing_state.position, out.bearing.force)
                + out.journal.moment
                + cross(journal_state.position, out.journal.force);
            assert!(m.abs() < 1e-12 * out.journal.force.norm(), "{m}");
            let eps_t = t.eccentricity_threshold(c);
            let e_eff = k.eccentricity_ratio.min(eps_t);
            assert_eq!(out.effective_eccentricity_ratio, e_eff);
            let f = b.force_wedge(e_eff, k.eccentricity_rate, k.wedge_speed);
            assert!(rel(out.film.radial, f.radial) < 1e-12, "{out:?} {f:?}");
            assert!(rel(out.film.tangential, f.tangential) < 1e-12);
            let (g, jac, e2) = b.film_force(&k, &t);
            assert_eq!(e2, e_eff);
            assert!(rel(g.radial, f.radial) < 1e-12);
            if eps > eps_t {
                assert_eq!(jac.d_eccentricity_ratio, FilmForce::default());
                assert!(out.dry_weight > 0.99);
            } else {
                assert_eq!(out.dry_weight, 0.0);
            }
        }
    }

    /// The weight is C¹ with w(h_t) = 0, w(h_d) = 1, and the clamped force is continuous at ε_t.
    #[test]
    fn transition_is_smooth_and_continuous() {
        let t = Transition::new(2e-6, -1e-6).unwrap();
        assert_eq!(t.dry_weight(2e-6), 0.0);
        assert_eq!(t.dry_weight(5e-6), 0.0);
        assert_eq!(t.dry_weight(-1e-6), 1.0);
        assert_eq!(t.dry_weight(-3e-6), 1.0);
        assert!((t.dry_weight(0.5e-6) - 0.5).abs() < 1e-15);
        assert_eq!(t.dry_weight_derivative(2e-6), 0.0);
        assert_eq!(t.dry_weight_derivative(-1e-6), 0.0);
        for h in [1.5e-6, 0.2e-6, -0.7e-6] {
            let d = 1e-12;
            let num = (t.dry_weight(h + d) - t.dry_weight(h - d)) / (2.0 * d);
            assert!((num - t.dry_weight_derivative(h)).abs() < 1e-6 * num.abs());
        }
        let b = bearing(BearingModel::ShortBearing);
        let c = b.clearance();
        let eps_t = t.eccentricity_threshold(c);
        assert!((eps_t - (1.0 - 2e-6 / c)).abs() < 1e-15);
        assert_eq!(
            Transition::new(1.0, 0.0).unwrap().eccentricity_threshold(c),
            0.0
        );
        let journal_at = |eps: f64| {
            BodyState::new(
                Vector2::new(eps * c, 0.0),
                0.0,
                Vector2::new(0.01, 0.02),
                30.0,
            )
        };
        let f = |eps: f64| {
            b.joint_forces(
                &t,
                Vector2::zeros(),
                Vector2::zeros(),
                &BodyState::default(),
                &journal_at(eps),
            )
            .film
        };
        let below = f(eps_t * (1.0 - 1e-12));
        let above = f(eps_t * (1.0 + 1e-12));
        assert!(
            rel(below.radial, above.radial) < 1e-6,
            "{below:?} {above:?}"
        );
        assert!(f(1.5).magnitude().is_finite());
    }
}
