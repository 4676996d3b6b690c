//! LuGre friction in clearance joints: the bristle states, their place in the state vector, their
//! forces and their rule at contact loss.
//!
//! # The law
//!
//! clr-contact's [`LuGre`] in friction-coefficient form (C. Canudas de Wit, H. Olsson,
//! K.J. Åström, P. Lischinsky, IEEE Trans. Autom. Control 40 (1995) 419–425): per contact point
//!
//! ```text
//! ż = v_T − σ₀|v_T| z / g(v_T),   g(v) = μ_c + (μ_s − μ_c) e^{−(v/v_s)²},
//! F_T = −(σ₀ z + σ₁ ż + σ₂ v_T) · F_N,
//! ```
//!
//! with v_T the slip velocity of the point along its tangent t (body j relative to body i, the
//! convention of every friction law here) and F_N the point's normal force from the element's
//! normal law. z is a length (m, "m-equivalent": σ₀ z is a friction coefficient, so σ₀·F_N is the
//! pre-sliding stiffness in N/m). Steady sliding gives z_ss = g(v) sgn(v)/σ₀ and
//! F_T = −(g(v) sgn v + σ₂ v) F_N ([`LuGre::steady_state_coefficient`]); a tangential load F
//! below breakaway held at rest gives σ₀ z F_N = F.
//!
//! # State layout
//!
//! y = (q, q̇, E_d, z_1 … z_m): after the n coordinates, the n velocities and the dissipated
//! energy, one bristle deflection per LuGre contact point, element by element in definition
//! order: 1 for a revolute clearance joint, 4 for a translational one (its corners, numbered as
//! clr-contact numbers them). Models without LuGre keep y = (q, q̇, E_d). Every state starts at
//! z = 0 ([`Model::given_state`](crate::Model::given_state)): undeflected bristles.
//!
//! # Contact loss
//!
//! While a point is open (penetration δ ≤ 0) its z is held (ż = 0) and it is set to 0 by the
//! driver at the first accepted step that finds the point open, and at every located contact
//! onset of that point (each reset restarts the integrator, as an onset does). So every contact
//! starts with undeflected bristles. Reason: the bristles of the LuGre model are the asperity
//! junctions of the two surfaces (Canudas de Wit et al. 1995, §II, after the bristle model of
//! D.A. Haessig & B. Friedland, J. Dyn. Syst. Meas. Control 113 (1991) 354–362, in which a
//! junction that breaks re-forms undeflected); when the surfaces separate every junction
//! breaks, and a new contact forms new, undeflected ones. Letting z evolve with the slip of points
//! that do not touch would instead start every new contact at the steady-state friction of the
//! slip it had in flight, without the pre-sliding build-up. With contact events off
//! ([`SimOptions::contact_events`](crate::SimOptions::contact_events)) a separation and a new
//! contact inside one step keep the held z (the onset is not located).
//!
//! # Energy
//!
//! The dissipated power of a LuGre point is −F_T·v_T, as for the stateless laws, so
//! `energy.total + energy.dissipated` stays constant. It includes the power stored in the
//! bristles: for a constant F_N the exact split is −F_T v_T = d/dt(½σ₀F_N z²) +
//! F_N(σ₀²|v|z²/g + σ₁ż v + σ₂v²), but F_N changes in a clearance joint, and then ½σ₀F_N z² is
//! not a potential (the bristle stiffness σ₀F_N changes under a held deflection with no work
//! done by anything), so no exact storage/dissipation split exists. `energy.dissipated` is the
//! work done against friction; it may decrease briefly when loaded bristles spring back.
//!
//! # Jacobians and tolerances
//!
//! clr-ode differences the whole right-hand side, z included. [`Model::jacobians`] gives ∂Q/∂q
//! and ∂Q/∂q̇ at the bristle states of the last evaluation (held fixed); a LuGre clearance is
//! differentiated there by central differences and listed in
//! [`Jacobians::fallback`](crate::Jacobians::fallback). The bristle states get the absolute
//! tolerance min(atol, rtol·z_max), z_max = max(μ_s, μ_c)/σ₀ ([`LuGre::z_max`]), since z is
//! micrometres where q is metres.

use clr_contact::{BodyState, ContactMemory, FrictionLaw, LuGre};

use crate::clearance::{Clearance, ClearanceKind, ContactReport};
use crate::desc::laws::ContactFriction;
use crate::runtime::body_state;
use crate::system::Model;

/// The LuGre law of a clearance joint and where its bristle states sit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LuGreContact {
    pub(crate) law: LuGre,
    /// Index of the element's first bristle state in [`Bristles::z`] (set by
    /// [`Bristles::assign`]).
    pub(crate) first: usize,
}

impl LuGreContact {
    /// The stateless law and the LuGre part of a clearance joint's friction: a stateless law
    /// alone, or no stateless friction plus the LuGre law.
    pub(crate) fn split(f: ContactFriction) -> (FrictionLaw, Option<Self>) {
        match f {
            ContactFriction::Static(l) => (l, None),
            ContactFriction::LuGre(law) => (
                FrictionLaw::coulomb(0.0, 1.0).expect("μ = 0 with v_reg = 1 m/s is valid"),
                Some(Self { law, first: 0 }),
            ),
        }
    }
}

/// Bristle states of every LuGre contact point of a model and their rates at the last
/// evaluation.
#[derive(Debug, Clone, Default)]
pub(crate) struct Bristles {
    /// Deflections z (m), loaded from the state before each evaluation.
    pub(crate) z: Vec<f64>,
    /// Rates ż (m/s) of the last evaluation (0 at open points).
    pub(crate) z_dot: Vec<f64>,
    /// Per clearance element: its `lugre_z` output (the F_N-weighted mean deflection of its
    /// loaded points, so that σ₀·mean·ΣF_N = Σσ₀z_kF_N,k; the plain mean when none is loaded), m.
    pub(crate) mean: Vec<f64>,
}

impl Bristles {
    /// Give every LuGre element its slots (one per contact point) and size the storage.
    pub(crate) fn assign(clearances: &mut [Clearance]) -> Self {
        let mut count = 0;
        for c in clearances.iter_mut() {
            let points = c.points();
            if let Some(l) = c.lugre.as_mut() {
                l.first = count;
                count += points;
            }
        }
        Self {
            z: vec![0.0; count],
            z_dot: vec![0.0; count],
            mean: vec![0.0; clearances.len()],
        }
    }

    /// Number of bristle states.
    pub(crate) fn len(&self) -> usize {
        self.z.len()
    }
}

/// ż and F_T of one contact point.
#[inline]
fn bristle(law: &LuGre, v: f64, z: f64, f_n: f64) -> (f64, f64) {
    let z_dot = law.z_dot(v, z);
    (law.force(v, z, z_dot, f_n), z_dot)
}

/// The forces of a LuGre clearance joint (element `k` of the model), added through
/// `add(body, [f_x, f_y, m])`; its bristle rates written to `states`. The geometry, normal law,
/// contact memory and report are those of [`Clearance::apply`], with the LuGre force as the
/// tangential force of each active point.
#[allow(clippy::too_many_arguments)]
pub(crate) fn apply(
    cl: &Clearance,
    lugre: &LuGreContact,
    k: usize,
    bi: &BodyState,
    bj: &BodyState,
    memory: &mut ContactMemory,
    states: &mut Bristles,
    mut add: impl FnMut(usize, [f64; 3]),
) -> ContactReport {
    let mut rep = ContactReport::default();
    let law = &lugre.law;
    let first = lugre.first;
    let Bristles { z, z_dot, mean } = states;
    match &cl.kind {
        ClearanceKind::Revolute(g, application) => {
            let ct = g.contact(bi, bj);
            let local = bi.to_local(bi.position + ct.eccentricity_vector);
            rep.penetration = ct.penetration;
            rep.penetration_rate = ct.normal_velocity;
            rep.eccentricity = [local.x, local.y];
            z_dot[first] = 0.0;
            mean[k] = z[first];
            if ct.in_contact() {
                let vm = memory.impact_velocity(cl.mem, ct.penetration, ct.normal_velocity);
                let f_n = cl.normal.force(ct.penetration, ct.normal_velocity, vm);
                let v = ct.tangential_velocity;
                let (f_t, rate) = bristle(law, v, z[first], f_n);
                z_dot[first] = rate;
                let jf = ct.generalized_forces_with(f_n, f_t, *application);
                add(cl.i, jf.bearing.as_array());
                add(cl.j, jf.journal.as_array());
                rep.active_points = 1;
                rep.normal_force = jf.normal_force;
                rep.friction_force = jf.tangential_force;
                rep.dissipated_power = (jf.normal_force - cl.normal.elastic_force(ct.penetration))
                    * ct.normal_velocity
                    - jf.tangential_force * v;
            }
        }
        ClearanceKind::Translational {
            geometry,
            origin,
            angle,
            ..
        } => {
            let ct = geometry.contact(bi, bj);
            let local = bi.to_local(bj.position);
            let rel = local - *origin;
            let (s, c) = angle.sin_cos();
            rep.eccentricity = [c * rel.x + s * rel.y, -s * rel.x + c * rel.y];
            let zs = &z[first..first + 4];
            let rates = &mut z_dot[first..first + 4];
            rates.fill(0.0);
            let normal = &cl.normal;
            let (mut n_active, mut power, mut zf, mut f_sum) = (0, 0.0, 0.0, 0.0);
            let f = ct.generalized_forces(|corner| {
                let pc = &corner.contact;
                let p = corner.corner;
                let vm = memory.impact_velocity(cl.mem + p, pc.penetration, pc.normal_velocity);
                let f_n = normal.force(pc.penetration, pc.normal_velocity, vm);
                let (f_t, rate) = bristle(law, pc.tangential_velocity, zs[p], f_n);
                rates[p] = rate;
                n_active += 1;
                power += (f_n - normal.elastic_force(pc.penetration)) * pc.normal_velocity
                    - f_t * pc.tangential_velocity;
                if f_n > 0.0 {
                    zf += f_n * zs[p];
                    f_sum += f_n;
                }
                (f_n, f_t)
            });
            mean[k] = if f_sum > 0.0 {
                zf / f_sum
            } else {
                zs.iter().sum::<f64>() / 4.0
            };
            cl.report_corners(bi, bj, &f, (n_active, power), &mut rep, &mut add);
        }
        // refused when the element is compiled (`FrictionSpec::build`): a slider on a flexible
        // guide takes stateless laws only
        ClearanceKind::FlexGuide(_) => {}
    }
    rep
}

impl Model {
    /// Number of LuGre bristle states m (0 without LuGre friction): the state is
    /// y = (q, q̇, E_d, z_1 … z_m) of dimension 2n + 1 + m, one z (m) per LuGre contact point,
    /// element by element in definition order (1 per revolute, 4 per translational clearance
    /// joint, corners as clr-contact numbers them), each starting at 0.
    pub fn n_bristle_states(&self) -> usize {
        self.bristles.len()
    }

    /// Copy the bristle states of y = (q, q̇, E_d, z) into the workspace (a shorter y, without
    /// them, leaves the workspace as it is).
    pub(crate) fn load_bristles(&mut self, y: &[f64]) {
        let o = 2 * self.n + 1;
        if let Some(z) = y.get(o..o + self.bristles.len()) {
            self.bristles.z.copy_from_slice(z);
        }
    }

    /// Bristle rates ż of the last evaluation, m/s.
    pub(crate) fn bristle_rates(&self) -> &[f64] {
        &self.bristles.z_dot
    }

    /// The `lugre_z` output of clearance element `k` at the last evaluation (`None` without
    /// LuGre friction), m.
    pub(crate) fn bristle_output(&self, k: usize) -> Option<f64> {
        self.clearances[k]
            .lugre
            .as_ref()
            .map(|_| self.bristles.mean[k])
    }

    /// The contact-loss rule of the module docs at an accepted state y: set z = 0 at every LuGre
    /// point that is open, and at the point whose onset event `onset` (event index of
    /// [`OdeSystem::events`](clr_ode::OdeSystem::events)) stopped the step. Returns true when a
    /// state changed (the integrator must restart).
    pub(crate) fn reset_bristles(&mut self, y: &mut [f64], onset: Option<usize>) -> bool {
        if self.bristles.len() == 0 {
            return false;
        }
        let n = self.n;
        let (q, qd) = (&y[..n], &y[n..2 * n]);
        let mut zero = Vec::new();
        let mut ev = 0;
        for cl in &self.clearances {
            let events = if self.events_on { cl.event_points() } else { 0 };
            if let Some(l) = &cl.lugre {
                let bi = body_state(&self.frames, cl.i, q, qd);
                let bj = body_state(&self.frames, cl.j, q, qd);
                for p in 0..cl.points() {
                    let hit = onset.is_some_and(|e| p < events && e == ev + p);
                    if hit || cl.gap(&bi, &bj, p).0 <= 0.0 {
                        zero.push(l.first + p);
                    }
                }
            }
            ev += events;
        }
        let o = 2 * n + 1;
        let mut changed = false;
        for s in zero {
            if y[o + s] != 0.0 {
                y[o + s] = 0.0;
                changed = true;
            }
        }
        changed
    }

    /// Absolute tolerances of the whole state when the model has bristle states: `atol` for
    /// (q, q̇, E_d), min(atol, rtol·z_max) for each z (`None` without LuGre friction).
    pub(crate) fn bristle_atol(&self, atol: f64, rtol: f64) -> Option<Vec<f64>> {
        if self.bristles.len() == 0 {
            return None;
        }
        let o = 2 * self.n + 1;
        let mut v = vec![atol; o + self.bristles.len()];
        for cl in &self.clearances {
            if let Some(l) = &cl.lugre {
                let a = atol.min(rtol * l.law.z_max());
                v[o + l.first..o + l.first + cl.points()].fill(a);
            }
        }
        Some(v)
    }
}
