//! The spatial model as the integrator sees it: the right-hand side and events of
//! [`SpatialModel`] and the reduced Newton systems of [`super::newton`] behind clr-ode's
//! [`OdeSystem`] (above both, so that the model and its Newton systems depend one way).

use clr_ode::{Direction, OdeSystem};
use nalgebra::Vector3;

use super::frame::quaternion_rate;
use super::model::SpatialModel;

impl OdeSystem for SpatialModel {
    fn dim(&self) -> usize {
        self.n_q() + self.n_v() + 2 + self.n_bristle
    }

    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let nb = self.bodies.len();
        let (nq, nv) = (7 * nb, 6 * nb);
        self.evaluate(t, y);
        let v = &y[nq..nq + nv];
        self.solve(v);
        for k in 0..nb {
            dydt[7 * k..7 * k + 3].copy_from_slice(&v[6 * k..6 * k + 3]);
            let w = Vector3::new(v[6 * k + 3], v[6 * k + 4], v[6 * k + 5]);
            let p = &y[7 * k + 3..7 * k + 7];
            quaternion_rate(p, &w, &mut dydt[7 * k + 3..7 * k + 7]);
            if self.norm_rate > 0.0 {
                let n2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3];
                for c in 0..4 {
                    dydt[7 * k + 3 + c] += self.norm_rate * (1.0 - n2) * p[c];
                }
            }
        }
        dydt[nq..nq + nv].copy_from_slice(&self.ws.qf);
        dydt[nq + nv] = self.ws.p_diss;
        dydt[nq + nv + 1] = self.ws.p_in + self.driver_power(v);
        let zo = nq + nv + 2;
        dydt[zo..].copy_from_slice(&self.ws.zdot);
    }

    fn has_newton_solver(&self) -> bool {
        self.ws.newton.on
    }
    fn newton_jacobian(&mut self, t: f64, y: &[f64]) -> bool {
        self.reduced_jacobian(t, y)
    }
    fn newton_factor(&mut self, c: f64) -> bool {
        self.reduced_factor(c)
    }
    fn newton_solve(&mut self, b: &mut [f64]) {
        self.reduced_solve(b)
    }

    fn n_events(&self) -> usize {
        if self.events_on {
            self.n_contacts()
        } else {
            0
        }
    }

    /// One event per spherical clearance joint, per contact group of a journal joint and per
    /// shape contact (its deepest point): its penetration δ (m); a rising crossing is a contact
    /// onset.
    fn events(&mut self, _t: f64, y: &[f64], g: &mut [f64]) {
        self.ws.kin.update(self.bodies.len(), y);
        let ns = self.spheres.len();
        let mut gaps = None; // (journal, its groups' gaps): one geometry per journal
        for (k, gk) in g.iter_mut().enumerate().take(self.n_contacts()) {
            *gk = match k.checked_sub(ns).and_then(|p| self.journal_points.get(p)) {
                Some(&(j, group)) => {
                    if gaps.is_none_or(|(at, _)| at != j) {
                        gaps = Some((j, self.journals[j].gaps(&self.ws.kin)));
                    }
                    gaps.map_or(0.0, |(_, d)| d[group].0)
                }
                None => self.contact_gap(k),
            };
        }
    }

    fn event_direction(&self, _i: usize) -> Direction {
        Direction::Rising
    }

    fn event_terminal(&self, _i: usize) -> bool {
        true
    }

    /// The smallest conservative-advancement bound of the shape contacts (none without them):
    /// no step can carry two shapes through each other unseen by the event functions. Costs one
    /// evaluation of the accelerations per step when the model has shape contacts.
    fn max_step(&mut self, t: f64, y: &[f64]) -> f64 {
        if self.shape_contacts.is_empty() {
            return f64::INFINITY;
        }
        let nb = self.bodies.len();
        self.evaluate(t, y);
        self.solve(&y[7 * nb..13 * nb]);
        let acc = |k: usize| {
            if k == super::kin::GROUND {
                return (Vector3::zeros(), Vector3::zeros());
            }
            let a = &self.ws.qf[6 * k..6 * k + 6];
            let alpha_body = Vector3::new(a[3], a[4], a[5]);
            (
                Vector3::new(a[0], a[1], a[2]),
                self.ws.kin.get(k).a * alpha_body,
            )
        };
        self.shape_contacts
            .iter()
            .map(|c| c.max_step(&self.ws.kin, [acc(c.a.body), acc(c.b.body)]))
            .fold(f64::INFINITY, f64::min)
    }
}
