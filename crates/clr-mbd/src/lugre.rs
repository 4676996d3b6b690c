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
//! y = (q, q̇, E_d, W_in, z_1 … z_m): after the n coordinates, the n velocities, the dissipated
//! energy and the input work, one bristle deflection per LuGre contact point, element by element
//! in definition order: 1 for a revolute clearance joint, 4 for a translational one (its
//! corners, numbered as clr-contact numbers them). Models without LuGre keep
//! y = (q, q̇, E_d, W_in). Every state starts at
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

pub(crate) mod force;
pub(crate) mod state;

use crate::clearance::Clearance;
use crate::runtime::body_state;
use crate::system::Model;
use state::Bristles;

/// Give every LuGre element its slots (one per contact point) and size the storage.
pub(crate) fn assign_bristles(clearances: &mut [Clearance]) -> Bristles {
    let mut count = 0;
    for c in clearances.iter_mut() {
        let points = c.points();
        if let Some(l) = c.lugre.as_mut() {
            l.first = count;
            count += points;
        }
    }
    Bristles {
        z: vec![0.0; count],
        z_dot: vec![0.0; count],
        mean: vec![0.0; clearances.len()],
    }
}

impl Model {
    /// Number of LuGre bristle states m (0 without LuGre friction): the state is
    /// y = (q, q̇, E_d, W_in, z_1 … z_m) of dimension 2n + 2 + m, one z (m) per LuGre contact
    /// point, element by element in definition order (1 per revolute, 4 per translational
    /// clearance joint, corners as clr-contact numbers them), each starting at 0.
    pub fn n_bristle_states(&self) -> usize {
        self.bristles.len()
    }

    /// Copy the bristle states of y = (q, q̇, E_d, W_in, z) into the workspace (a shorter y,
    /// without them, leaves the workspace as it is).
    pub(crate) fn load_bristles(&mut self, y: &[f64]) {
        let o = self.bristle_offset();
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
        let o = self.bristle_offset();
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
    /// (q, q̇, E_d, W_in), min(atol, rtol·z_max) for each z (`None` without LuGre friction).
    pub(crate) fn bristle_atol(&self, atol: f64, rtol: f64) -> Option<Vec<f64>> {
        if self.bristles.len() == 0 {
            return None;
        }
        let o = self.bristle_offset();
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
