//! Hydrodynamic film of the spatial journal-in-bearing joint ([`crate::journal`]) with
//! misalignment: the short-bearing (Ocvirk) and long-bearing (Sommerfeld, half film) closed forms
//! of [`crate::lubrication`] extended to a journal whose axis is tilted in the bore, so that the
//! film thickness varies along the bearing. Derivations and verification: `docs/lubrication.md`,
//! "Spatial journal: misalignment"; cases `cargo xtask verify lubrication.spatial`.
//!
//! # Geometry
//! Bore (body i) centre O_b, unit axis u_b, radius R_b, length L_b; journal (body j) centre O_j,
//! axis u_j (flipped so that cos γ = u_b·u_j > 0), radius r, length L_j; c = R_b − r. As in
//! [`crate::journal`], the journal axis meets the bore plane at the bore-axial coordinate z in the
//! radial offset e(z) = e₀ + (z − a) t, t = (u_j − cos γ u_b)/cos γ, linear in z. The film is the
//! overlap of the bore [−L_b/2, L_b/2] with the journal's axial span a ± cos γ L_j/2 (the axis end
//! points; the rim of a tilted journal end reaches r sin γ further, neglected), of length 2ℓ and
//! centre z_c; ζ = z − z_c. With a unit n(ψ) ⟂ u_b, the film thickness is
//! h(ψ, ζ) = c − e(ζ)·n(ψ) = h₀(ψ) + h₁(ψ) ζ: the journal's cross-section in the bore plane is
//! taken as the circle of radius r about the axis point; the true section is an ellipse with semi
//! axes r and r/cos γ, which changes h by at most r(1/cos γ − 1) ≈ rγ²/2 (0.15 µm for r = 10 mm,
//! γ = 0.3°, i.e. 0.3 % of c = 50 µm; 6 % at γ = 1°): this *ellipse term* is neglected.
//!
//! # Kinematics of the film
//! With the relative velocity of the journal's axis point X_j(z) = O_j + u_j (z − a)/cos γ,
//! **v**(z) = v_j(X_j) − v_i(O_b + z u_b) (material velocities, the bearing's on its axis as the
//! planar joint takes it) and the axial sliding W(z) = (v_j(X_j) − v_i(X_j))·u_b, the squeeze
//! velocity that enters the Reynolds equation is
//! **V**(z) = (I − u_b u_bᵀ)**v**(z) − k W(z) t, k = 1 for the long bearing (axial flow neglected:
//! only ∂h/∂t at fixed z acts, and a journal sliding along its own axis changes nothing) and
//! k = ½ for the short bearing (the axial Couette term 6μ W ∂h/∂z of the journal's surface moving
//! along a tilted gap: a tilted journal sliding axially builds an axial wedge). Both are linear in
//! z. The spins enter as ω_s = (ω_i + ω_j)·u_b (wedge) and ω_r = (ω_j − ω_i)·u_b (Couette shear);
//! the transverse angular velocities act only through **V**(z) (the tilting squeeze); the
//! circumferential component of a transverse spin on the elliptic section, O(rγ ω_⊥), is
//! neglected with the ellipse term. Without tilt every slice has the planar joint's kinematics.
//!
//! # Long bearing (axial flow neglected)
//! Every slice dz is a slice of an infinitely long bearing: the force per unit length at z is the
//! planar closed form ([`HydrodynamicBearing`], long, moving π-film) at ε(z) = |e(z)|/c,
//! ε̇(z) = **V**·**n**/c and εΩ = (|e| ω_s − 2 **V**·**t**)/c (**n** = e/|e|, **t** = u_b × **n**)
//! divided by L, applied at X_j(z). The force and moment are integrated by Gauss–Legendre in z
//! (order [`AXIAL_ORDER`] on each side of the minimiser of |e(z)|, where ε(z) has its kink). Exact
//! within long-bearing theory up to the ellipse term.
//!
//! # Short bearing (circumferential flow neglected)
//! Per angle ψ, ∂/∂ζ(h³ ∂p/∂ζ) = A + Bζ, A + Bζ = −6μ [ω_s e(ζ)·n′(ψ) + 2 **V**(ζ)·n(ψ)]
//! (n′ = u_b × n; at zero tilt the planar 6μc(εΩ sin ψ − 2ε̇ cos ψ)), p(±ℓ) = 0. Integrated once,
//! h³ p′ = Aζ + Bζ²/2 + C, with C from p(ℓ) = 0; everything reduces to the integrals
//! ∫ζᵏ/(h₀ + h₁ζ)³ dζ, k = 0…4, in closed form (the power series in β = h₁ℓ/h₀ for |β| < 0.3, the
//! partial fractions in u = 1 + βx beyond). The line force ∫p dζ and moment ∫pζ dζ follow by parts
//! (p vanishes at the ends). Gümbel (half-Sommerfeld) cavitation is applied pointwise: p′ has at
//! most two zeros, so a line is either of one sign or changes sign once; the root is found by
//! safeguarded Newton on the closed-form p(ζ) and only the positive part is integrated. The line
//! results are integrated over ψ by Gauss–Legendre (order [`CIRCUMFERENTIAL_ORDER`] on each half
//! of the circle, split where the mid-plane right-hand side A(ψ) changes sign: at zero tilt those
//! are exactly the ends of the π-film, so the reduction to the planar Ocvirk force is exact to
//! rounding; with tilt the lines near those ends are partly cavitated and the ψ-integrand has a
//! kink there: measured accuracy in `docs/lubrication.md`).
//!
//! # Shear, transition, what is not modelled
//! Each slice adds the planar shear torques about u_b (module docs of [`crate::lubrication`]):
//! the Couette (Petroff) torque per unit length −2πμr³ω_r/(c√(1 − ε(z)²)) and the pressure part
//! −½(e(z) × **f**(z))·u_b, as a couple on the journal and its opposite on the bearing. The
//! [`Transition`] freezes the geometry near contact: long bearing per slice at ε_t = 1 − h_t/c
//! (the planar clamp: εΩ scaled by ε_t/ε, ε̇ kept); short bearing per line, by the homothety
//! e(z) → s e(z), s = ε_t c / max|e(z)| when max|e(z)| > ε_t c, with the components of **V**
//! normal to e(z_c) scaled by s and the one along it kept (the planar clamp at zero tilt). The dry
//! law acts only at penetration, where h ≤ 0 ≤ h_d: [`JournalFilm::new`] refuses h_d < 0, so its
//! weight w(h_min) is 1 wherever it acts and the multibody code adds it unweighted. The thrust
//! faces carry no film (dry contact only). Not modelled: the finite-length Reynolds equation
//! (only its two limits), thermal effects and viscosity–pressure dependence, the ellipse term,
//! the film beyond the overlap, the fluid inertia, a film on the thrust faces.
//!
//! All forces are generic over [`Real`] (f64 and the multibody dual numbers) and allocate nothing.

use std::f64::consts::PI;

use crate::error::{positive, ContactError};
use crate::journal::{
    gauss_legendre, Axes, JournalClearance, JournalError, JournalState, Real, MAX_ORDER, V3,
};
use crate::lubrication::{BearingModel, HydrodynamicBearing, Transition};

/// Gauss–Legendre order on each side of the minimiser of |e(z)| (long-bearing slices, Couette
/// torque): relative error below 1e-12 against 2·64 points for the states of the unit tests.
pub const AXIAL_ORDER: usize = 16;

/// Gauss–Legendre order on each half of the circle (short bearing): the planar Ocvirk force to
/// 1e-14 at ε = 0.3 and 2e-10 at ε = 0.8 without tilt; with tilt the measured error is in `docs/lubrication.md`.
pub const CIRCUMFERENTIAL_ORDER: usize = 32;

/// The hydrodynamic film of a spatial journal-in-bearing joint (module docs), validated.
#[derive(Debug, Clone, PartialEq)]
pub struct JournalFilm {
    bearing_length: f64,
    journal_length: f64,
    model: BearingModel,
    transition: Transition,
    /// The planar bearing of unit length (force per unit length of the long-bearing slices); it
    /// holds the radii and the viscosity.
    slice: HydrodynamicBearing,
    z_rule: ([f64; MAX_ORDER], [f64; MAX_ORDER]),
    psi_rule: ([f64; MAX_ORDER], [f64; MAX_ORDER]),
}

/// Film forces on the two bodies of the joint, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmLoads<S> {
    /// Resultant film force on the journal, N (the bearing receives −force).
    pub force: V3<S>,
    /// Moment of the film (pressure and shear) on the journal about O_j, N·m.
    pub journal_moment: V3<S>,
    /// Moment of the film on the bearing about O_b, N·m.
    pub bearing_moment: V3<S>,
    /// Minimum film thickness over the film, c − max|e(z)| (ellipse term neglected), m; c when the
    /// journal is out of the bore.
    pub min_film_thickness: f64,
    /// Film length 2ℓ (overlap of journal and bore), m; 0 when the journal is out of the bore.
    pub film_length: f64,
}

/// The film's frame and kinematics at one state (module docs).
#[derive(Debug, Clone, Copy)]
struct Film<S> {
    ub: V3<S>,
    uj: V3<S>,
    cg: S,
    /// Unit vectors ⟂ u_b: along e(z_c) (or any) and u_b × it.
    b1: V3<S>,
    b2: V3<S>,
    /// de/dz.
    t: V3<S>,
    /// Film half length ℓ, m.
    ell: S,
    /// e(z_c), m.
    ec: V3<S>,
    /// X_j(z_c) − O_j and X_j(z_c) − O_b, m.
    arm_j: V3<S>,
    arm_b: V3<S>,
    /// **V**(z_c) (m/s) and d**V**/dz (1/s).
    vc: V3<S>,
    v1: V3<S>,
    omega_sum: S,
    omega_rel: S,
}

impl<S: Real> Film<S> {
    fn e(&self, zeta: S) -> V3<S> {
        self.ec + self.t.scale(zeta)
    }
    fn v(&self, zeta: S) -> V3<S> {
        self.vc + self.v1.scale(zeta)
    }
}

/// Per-line results of the short bearing: ∫p dζ (N/m) and ∫pζ dζ (N).
type Line<S> = (S, S);

impl JournalFilm {
    /// The film of `joint` filled with a lubricant of dynamic viscosity μ (Pa·s), closed form
    /// `model`, and the near-contact `transition` (its dry threshold h_d must be ≥ 0, module docs).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for μ not positive and finite or h_d < 0.
    pub fn new(
        joint: &JournalClearance,
        viscosity: f64,
        model: BearingModel,
        transition: Transition,
    ) -> Result<Self, ContactError> {
        const LAW: &str = "spatial journal film";
        positive(LAW, "dynamic viscosity μ (Pa·s)", viscosity)?;
        if transition.dry_threshold() < 0.0 {
            return Err(ContactError::invalid(
                LAW,
                "dry threshold h_d (m)",
                transition.dry_threshold(),
                "must be >= 0 for the spatial journal: its dry weight w(h_min) is not evaluated \
                 per Gauss point, so the dry law acts with w = 1 where the surfaces overlap; set \
                 h_d = 0 (or between 0 and h_t)",
            ));
        }
        let slice = HydrodynamicBearing::new(
            joint.bearing_radius(),
            joint.journal_radius(),
            1.0,
            viscosity,
            BearingModel::LongBearing,
        )?;
        Ok(Self {
            bearing_length: joint.bearing_length(),
            journal_length: joint.journal_length(),
            model,
            transition,
            slice,
            z_rule: gauss_legendre(AXIAL_ORDER),
            psi_rule: gauss_legendre(CIRCUMFERENTIAL_ORDER),
        })
    }

    /// Radial clearance c, m.
    pub fn clearance(&self) -> f64 {
        self.slice.clearance()
    }

    /// Dynamic viscosity μ, Pa·s.
    pub fn viscosity(&self) -> f64 {
        self.slice.viscosity()
    }

    /// The closed-form model.
    pub fn model(&self) -> BearingModel {
        self.model
    }

    /// The near-contact transition.
    pub fn transition(&self) -> Transition {
        self.transition
    }

    /// Film forces on journal and bearing at `state` (module docs). Allocates nothing.
    ///
    /// # Errors
    /// [`JournalError::NonFinite`] for a non-finite state, [`JournalError::Tilt`] for a tilt over
    /// [`MAX_TILT`](crate::journal::MAX_TILT).
    pub fn loads<S: Real>(&self, state: &JournalState<S>) -> Result<FilmLoads<S>, JournalError> {
        let Some(film) = self.film(state)? else {
            return Ok(FilmLoads {
                force: V3::zero(),
                journal_moment: V3::zero(),
                bearing_moment: V3::zero(),
                min_film_thickness: self.clearance(),
                film_length: 0.0,
            });
        };
        let e_lo = film.e(-film.ell).norm().value();
        let e_hi = film.e(film.ell).norm().value();
        let min_film_thickness = self.clearance() - e_lo.max(e_hi);
        let (force, moment_arm, torque) = match self.model {
            BearingModel::LongBearing => self.long_bearing(&film),
            BearingModel::ShortBearing => self.short_bearing(&film),
        };
        // moment of the slices' forces about the film centre on the journal axis: ∫ζ f dζ along
        // u_j / cos γ (X_j(z) − X_j(z_c) = ζ u_j / cos γ)
        let lever = film.uj.scale(S::from_f64(1.0) / film.cg).cross(&moment_arm);
        let couple = film.ub.scale(torque);
        Ok(FilmLoads {
            force,
            journal_moment: film.arm_j.cross(&force) + lever + couple,
            bearing_moment: -(film.arm_b.cross(&force) + lever + couple),
            min_film_thickness,
            film_length: 2.0 * film.ell.value(),
        })
    }

    /// The frame and kinematics, `None` when the journal is out of the bore.
    fn film<S: Real>(&self, state: &JournalState<S>) -> Result<Option<Film<S>>, JournalError> {
        state.all_finite()?;
        let one = S::from_f64(1.0);
        let Axes { ub, uj, cg, w, .. } = state.axes()?;
        let t = w.scale(one / cg);
        let (ob, oj) = (state.bearing_centre, state.journal_centre);
        let d = oj - ob;
        let a = d.dot(&ub);
        let half_j = cg * S::from_f64(0.5 * self.journal_length);
        let half_b = S::from_f64(0.5 * self.bearing_length);
        let lo = if (a - half_j).value() > -half_b.value() {
            a - half_j
        } else {
            -half_b
        };
        let hi = if (a + half_j).value() < half_b.value() {
            a + half_j
        } else {
            half_b
        };
        if lo.value() >= hi.value() {
            return Ok(None);
        }
        let half = S::from_f64(0.5);
        let (zc, ell) = ((lo + hi) * half, (hi - lo) * half);
        let ec = d - ub.scale(a) + t.scale(zc - a);
        let b1 = if ec.value().norm() > 0.0 {
            ec.scale(one / ec.norm())
        } else {
            let k = if ub.value().x.abs() < 0.9 {
                V3::constant(&nalgebra::Vector3::x())
            } else {
                V3::constant(&nalgebra::Vector3::y())
            };
            let q = k - ub.scale(k.dot(&ub));
            q.scale(one / q.norm())
        };
        let b2 = ub.cross(&b1);
        // kinematics (module docs): v_j at X_j(z), v_i at O_b + z u_b, axial sliding at X_j(z)
        let dxdz = uj.scale(one / cg);
        let arm_j = dxdz.scale(zc - a);
        let arm_b = arm_j + oj - ob;
        let (wi, wj) = (
            state.bearing_angular_velocity,
            state.journal_angular_velocity,
        );
        let vj = state.journal_velocity + wj.cross(&arm_j);
        let rel = vj - (state.bearing_velocity + wi.cross(&ub.scale(zc)));
        let slide = (vj - (state.bearing_velocity + wi.cross(&arm_b))).dot(&ub);
        let d_rel = wj.cross(&dxdz) - wi.cross(&ub);
        let d_slide = (wj - wi).cross(&dxdz).dot(&ub);
        let k = S::from_f64(match self.model {
            BearingModel::LongBearing => 1.0,
            BearingModel::ShortBearing => 0.5,
        });
        let plane = |x: V3<S>| x - ub.scale(x.dot(&ub));
        Ok(Some(Film {
            ub,
            uj,
            cg,
            b1,
            b2,
            t,
            ell,
            ec,
            arm_j,
            arm_b,
            vc: plane(rel) - t.scale(k * slide),
            v1: plane(d_rel) - t.scale(k * d_slide),
            omega_sum: (wi + wj).dot(&ub),
            omega_rel: (wj - wi).dot(&ub),
        }))
    }

    /// Gauss–Legendre nodes (ζ, weight) over [−ℓ, ℓ] split at the minimiser of |e(ζ)|, where
    /// ε(ζ) has its kink; `f(ζ, weight)` is called for each.
    fn axial_nodes<S: Real>(&self, film: &Film<S>, mut f: impl FnMut(S, S)) {
        let ell = film.ell.value();
        let tt = film.t.dot(&film.t).value();
        let split = if tt > 0.0 {
            (-film.ec.dot(&film.t).value() / tt).clamp(-ell, ell)
        } else {
            0.0
        };
        let (x, w) = &self.z_rule;
        for (from, to) in [(-ell, split), (split, ell)] {
            // the film ends move with the state: ζ = −ℓ + (ℓ_s + ℓ)·u with ℓ_s = split as a value
            // relative to the moving ends keeps the nodes' derivatives (the split itself is a
            // quadrature choice, not a function of the state)
            let (a, b) = (
                film.ell * S::from_f64(from / ell),
                film.ell * S::from_f64(to / ell),
            );
            if to <= from {
                continue;
            }
            for i in 0..AXIAL_ORDER {
                let zeta = a + (b - a) * S::from_f64(x[i]);
                f(zeta, (b - a) * S::from_f64(w[i]));
            }
        }
    }

    /// Long bearing: (∫**f** dζ, ∫ζ**f** dζ, ∫T_j dζ) over the slices (module docs).
    fn long_bearing<S: Real>(&self, film: &Film<S>) -> (V3<S>, V3<S>, S) {
        let c = self.clearance();
        let eps_t = self.transition.eccentricity_threshold(c);
        let (mut force, mut arm, mut torque) = (V3::zero(), V3::zero(), S::from_f64(0.0));
        self.axial_nodes(film, |zeta, weight| {
            let e = film.e(zeta);
            let v = film.v(zeta);
            let len = e.norm();
            let n = if len.value() > 0.0 {
                e.scale(S::from_f64(1.0) / len)
            } else {
                film.b1
            };
            let tn = film.ub.cross(&n);
            let mut eps = len / S::from_f64(c);
            let rate = v.dot(&n) / S::from_f64(c);
            let vt = v.dot(&tn);
            let mut term = (len * film.omega_sum - S::from_f64(2.0) * vt) / S::from_f64(c);
            let omega = if len.value() > 0.0 {
                film.omega_sum.value() - 2.0 * vt.value() / len.value()
            } else {
                film.omega_sum.value()
            };
            if eps.value() > eps_t {
                term = term * (S::from_f64(eps_t) / eps);
                eps = S::from_f64(eps_t);
            }
            let (fr, ft) = self.slice.force_real(eps, rate, term, omega);
            let f = n.scale(fr) + tn.scale(ft);
            let t_j = self.couette(eps, film.omega_rel) - S::from_f64(0.5 * c) * eps * ft;
            force = force + f.scale(weight);
            arm = arm + f.scale(zeta * weight);
            torque = torque + t_j * weight;
        });
        (force, arm, torque)
    }

    /// Couette torque per unit length on the journal, −2πμr³ω_r/(c√(1 − ε²)), N.
    fn couette<S: Real>(&self, eps: S, omega_rel: S) -> S {
        let r = self.slice.journal_radius();
        let k = -2.0 * PI * self.slice.viscosity() * r * r * r / self.clearance();
        S::from_f64(k) * omega_rel / (S::from_f64(1.0) - eps * eps).sqrt()
    }

    /// Short bearing: (∫**f** dζ, ∫ζ**f** dζ, ∫T_j dζ) (module docs).
    fn short_bearing<S: Real>(&self, film: &Film<S>) -> (V3<S>, V3<S>, S) {
        let c = self.clearance();
        let film = self.frozen(film);
        let mu6 = S::from_f64(6.0 * self.slice.viscosity());
        let two = S::from_f64(2.0);
        // mid-plane right-hand side A(ψ) = α cos ψ + β sin ψ: split the circle at its zeros
        let (ec, vc) = (film.ec, film.vc);
        let alpha = -(mu6 * (film.omega_sum * ec.dot(&film.b2) + two * vc.dot(&film.b1)));
        let beta = -(mu6 * (two * vc.dot(&film.b2) - film.omega_sum * ec.dot(&film.b1)));
        let phi = beta.value().atan2(alpha.value());
        let r = S::from_f64(self.slice.journal_radius());
        let (mut force, mut arm) = (V3::zero(), V3::zero());
        let (x, w) = &self.psi_rule;
        for start in [phi + 0.5 * PI, phi - 0.5 * PI] {
            for i in 0..CIRCUMFERENTIAL_ORDER {
                let psi = start + PI * x[i];
                let (s, co) = psi.sin_cos();
                let n = film.b1.scale_f(co) + film.b2.scale_f(s);
                let np = film.b2.scale_f(co) - film.b1.scale_f(s);
                let (l0, l1) = self.line(&film, &n, &np);
                let k = r * S::from_f64(PI * w[i]);
                force = force - n.scale(l0 * k);
                arm = arm - n.scale(l1 * k);
            }
        }
        // shear: Couette per slice, pressure part −½(∫e × f)·u_b
        let mut couette = S::from_f64(0.0);
        self.axial_nodes(&film, |zeta, weight| {
            let eps = film.e(zeta).norm() / S::from_f64(c);
            couette = couette + self.couette(eps, film.omega_rel) * weight;
        });
        let pressure = (film.ec.cross(&force) + film.t.cross(&arm)).dot(&film.ub);
        (force, arm, couette - pressure * S::from_f64(0.5))
    }

    /// The short-bearing film frozen near contact (module docs, *Shear, transition*).
    fn frozen<S: Real>(&self, film: &Film<S>) -> Film<S> {
        let c = self.clearance();
        let eps_t = self.transition.eccentricity_threshold(c);
        let ends = [film.e(-film.ell).norm(), film.e(film.ell).norm()];
        let deepest = if ends[0].value() > ends[1].value() {
            ends[0]
        } else {
            ends[1]
        };
        if deepest.value() <= eps_t * c {
            return *film;
        }
        let s = S::from_f64(eps_t * c) / deepest;
        // keep the component of V along e(z_c) (b1), scale the rest
        let keep = |v: V3<S>| {
            let along = film.b1.scale(v.dot(&film.b1));
            along + (v - along).scale(s)
        };
        Film {
            ec: film.ec.scale(s),
            t: film.t.scale(s),
            vc: keep(film.vc),
            v1: keep(film.v1),
            ..*film
        }
    }

    /// One line ψ of the short bearing: (∫p⁺ dζ, ∫p⁺ζ dζ) with Gümbel's condition pointwise.
    fn line<S: Real>(&self, film: &Film<S>, n: &V3<S>, np: &V3<S>) -> Line<S> {
        let c = S::from_f64(self.clearance());
        let mu6 = S::from_f64(6.0 * self.slice.viscosity());
        let two = S::from_f64(2.0);
        let zero = S::from_f64(0.0);
        let h0 = c - film.ec.dot(n);
        let h1 = -film.t.dot(n);
        let rhs_a = -(mu6 * (film.omega_sum * film.ec.dot(np) + two * film.vc.dot(n)));
        let rhs_b = -(mu6 * (film.omega_sum * film.t.dot(np) + two * film.v1.dot(n)));
        let ell = film.ell;
        let beta = h1 * ell / h0;
        // in x = ζ/ℓ: h³ dp/dx = ℓ(a x + b x² + C), a = Aℓ, b = Bℓ²/2
        let a = rhs_a * ell;
        let b = rhs_b * ell * ell * S::from_f64(0.5);
        let full = between(beta, -1.0, 1.0);
        let cc = -(a * full[1] + b * full[2]) / full[0];
        let q = |x: f64| a.value() * x + b.value() * x * x + cc.value();
        let scale = ell / (h0 * h0 * h0);
        let (qm, qp) = (q(-1.0), q(1.0));
        // the part [from, to] of the line where p ≥ 0, and whether an end is the interior root
        let (from, to) = if qm >= 0.0 && qp <= 0.0 {
            (-1.0, 1.0)
        } else if qm <= 0.0 && qp >= 0.0 {
            return (zero, zero);
        } else {
            let Some(root) = pressure_root(a.value(), b.value(), cc.value(), beta.value()) else {
                return (zero, zero);
            };
            if qm > 0.0 {
                (-1.0, root)
            } else {
                (root, 1.0)
            }
        };
        let g = between(beta, from, to);
        // ∫p dx = [x p] − ∫x p′ dx, ∫x p dx = [x²p/2] − ½∫x² p′ dx; p = 0 at ±1, and at the root
        // p(root) carries the derivatives of the moving root's value (zero at the value)
        let root = if from > -1.0 { from } else { to };
        let p_root = if root.abs() < 1.0 {
            let g_r = between(beta, -1.0, root);
            scale * (a * g_r[1] + b * g_r[2] + cc * g_r[0])
        } else {
            zero
        };
        let sign = S::from_f64(if from > -1.0 { -1.0 } else { 1.0 });
        let rt = S::from_f64(root);
        let i0 = sign * rt * p_root - scale * (a * g[2] + b * g[3] + cc * g[1]);
        let i1 = sign * rt * rt * p_root * S::from_f64(0.5)
            - scale * (a * g[3] + b * g[4] + cc * g[2]) * S::from_f64(0.5);
        (i0 * ell, i1 * ell * ell)
    }
}

/// ∫_{x₁}^{x₂} xᵏ/(1 + βx)³ dx for k = 0…4 (|β| < 1, −1 ≤ x₁ ≤ x₂ ≤ 1).
fn between<S: Real>(beta: S, x1: f64, x2: f64) -> [S; 5] {
    let (p, q) = (primitives(beta, x2), primitives(beta, x1));
    [0, 1, 2, 3, 4].map(|k| p[k] - q[k])
}

/// ∫₀ˣ sᵏ/(1 + βs)³ ds for k = 0…4: the power series Σ (n+1)(n+2)/2 (−β)ⁿ x^{n+k+1}/(n+k+1) for
/// |β| < 0.3 (48 terms: remainder below 1e-20), else the partial fractions in u = 1 + βs,
/// β^{−k−1} ∫₁^{1+βx} (u − 1)ᵏ u⁻³ du (cancellation at most 0.3⁻⁵ ≈ 400 ulp).
fn primitives<S: Real>(beta: S, x: f64) -> [S; 5] {
    let zero = S::from_f64(0.0);
    let mut out = [zero; 5];
    if beta.value().abs() < 0.3 {
        let mut bn = S::from_f64(1.0); // (−β)ⁿ
        let mut xn = x; // x^{n+1}
        for n in 0..48 {
            let cn = 0.5 * ((n + 1) * (n + 2)) as f64;
            let mut xm = xn;
            for (k, o) in out.iter_mut().enumerate() {
                *o = *o + bn * S::from_f64(cn * xm / (n + k + 1) as f64);
                xm *= x;
            }
            bn = -(bn * beta);
            xn *= x;
        }
        return out;
    }
    let one = S::from_f64(1.0);
    let u = one + beta * S::from_f64(x);
    let inv = one / u;
    let ln_u = u.chain(u.value().ln(), 1.0 / u.value());
    // U_j(u) − U_j(1), U_j = u^{j−2}/(j − 2) (ln u for j = 2), j = 0…4
    let big_u = [
        (inv * inv - one) * S::from_f64(-0.5),
        -(inv - one),
        ln_u,
        u - one,
        (u * u - one) * S::from_f64(0.5),
    ];
    const BINOMIAL: [[f64; 5]; 5] = [
        [1.0, 0.0, 0.0, 0.0, 0.0],
        [1.0, 1.0, 0.0, 0.0, 0.0],
        [1.0, 2.0, 1.0, 0.0, 0.0],
        [1.0, 3.0, 3.0, 1.0, 0.0],
        [1.0, 4.0, 6.0, 4.0, 1.0],
    ];
    let mut inv_beta = one / beta;
    for (k, o) in out.iter_mut().enumerate() {
        let mut sum = zero;
        for (j, bu) in big_u.iter().enumerate().take(k + 1) {
            let sign = if (k - j) % 2 == 0 { 1.0 } else { -1.0 };
            sum = sum + *bu * S::from_f64(sign * BINOMIAL[k][j]);
        }
        *o = sum * inv_beta;
        inv_beta = inv_beta / beta;
    }
    out
}

/// The interior root of a short-bearing pressure line p(x) = ∫₋₁ˣ q/(1 + βs)³ ds with
/// q = a s + b s² + C, when q(−1) and q(1) have the same sign: p turns twice, at the roots
/// x₁ < x₂ of q, and crosses zero once between them. Safeguarded Newton (bisection when a step leaves the bracket),
/// values only. `None` when q has no two roots in (−1, 1) (a line of one sign up to rounding).
fn pressure_root(a: f64, b: f64, cc: f64, beta: f64) -> Option<f64> {
    let disc = a * a - 4.0 * b * cc;
    if b == 0.0 || disc <= 0.0 {
        return None;
    }
    // stable quadratic roots
    let sq = disc.sqrt();
    let qq = -0.5 * (a + a.signum() * sq);
    let (r1, r2) = (qq / b, if qq != 0.0 { cc / qq } else { -qq / b });
    let (mut lo, mut hi) = (r1.min(r2).max(-1.0), r1.max(r2).min(1.0));
    let p = |x: f64| {
        let g = between(beta, -1.0, x);
        a * g[1] + b * g[2] + cc * g[0]
    };
    let (p_lo, p_hi) = (p(lo), p(hi));
    if p_lo * p_hi > 0.0 {
        return None;
    }
    let rising = p_hi > p_lo;
    let mut x = 0.5 * (lo + hi);
    for _ in 0..100 {
        let px = p(x);
        if (px > 0.0) == rising {
            hi = x;
        } else {
            lo = x;
        }
        let dp = (a * x + b * x * x + cc) / (1.0 + beta * x).powi(3);
        let newton = x - px / dp;
        let next = if newton > lo && newton < hi && dp != 0.0 {
            newton
        } else {
            0.5 * (lo + hi)
        };
        let done = (next - x).abs() <= 1e-15 || hi - lo <= 1e-15;
        x = next;
        if done {
            break;
        }
    }
    Some(x)
}

#[cfg(test)]
mod tests;
