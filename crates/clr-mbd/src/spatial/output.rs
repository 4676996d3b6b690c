//! Result columns of a spatial run, energies and constraint violations.
//!
//! Columns, in order: `t`; per body `B.x B.y B.z` (centre of mass, world, m), `B.qw B.qx B.qy
//! B.qz` (unit quaternion body → world), `B.vx B.vy B.vz` (m/s, world), `B.wx B.wy B.wz`
//! (angular velocity, rad/s, body frame), `B.ax B.ay B.az` (m/s², world), `B.alphax B.alphay
//! B.alphaz` (rad/s², body frame); per joint or driver `J.Fx J.Fy J.Fz J.Mx J.My J.Mz` (reaction
//! force, N, and moment about the centre of mass, N·m, both world, on its b body, or on its a
//! body when b is the ground); per spherical clearance joint `C.penetration C.rate
//! C.normal_force C.friction_force C.contact C.ex C.ey C.ez C.ftx C.fty C.ftz` (m, m/s, N, N, 1/0,
//! eccentricity in m world, friction force on the ball in N world), then `C.lugre_zx C.lugre_zy
//! C.lugre_zz` with LuGre friction; per revolute or cylindrical clearance joint, per contact
//! group G (`radial_a radial_b`, then `thrust_minus thrust_plus` for the revolute kind)
//! `J.G.penetration J.G.normal_force` (m, N), then `J.Fx J.Fy J.Fz J.Mx J.My J.Mz` (resultant
//! contact force on the journal, N, and its moment about the journal centre, N·m, world),
//! `J.tilt` (rad) and `J.axial_offset` (m, journal centre along the bore axis from the bore
//! centre), then for a lubricated joint `J.film_force J.film_thickness` (magnitude of the film
//! force on the journal, N, not in `J.Fx..`; minimum film thickness, m); per shape contact `C.penetration C.rate C.normal_force C.friction_force C.contact
//! C.ex C.ey C.ez` (deepest tracked point's δ in m, −prediction when none is within it, and δ̇
//! in m/s; normal and friction forces summed over the active points, N; the number of active
//! points; the deepest point on shape A, world, m); `energy.kinetic energy.potential energy.elastic energy.total
//! energy.dissipated energy.work_in energy.balance` (J, as planar runs); `violation.position
//! violation.velocity violation.quaternion` (‖Φ‖∞, ‖Φ̇‖∞ and max |‖p‖ − 1|).

use nalgebra::Vector3;

use clr_ode::OdeSystem;

use super::model::SpatialModel;
use crate::system::Energies;

impl SpatialModel {
    /// Names of the result columns ([module docs](self)).
    pub fn columns(&self) -> Vec<String> {
        let mut c = vec!["t".to_string()];
        for b in &self.names {
            for s in [
                "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz", "ax",
                "ay", "az", "alphax", "alphay", "alphaz",
            ] {
                c.push(format!("{b}.{s}"));
            }
        }
        for o in &self.owners {
            for s in ["Fx", "Fy", "Fz", "Mx", "My", "Mz"] {
                c.push(format!("{}.{s}", o.name));
            }
        }
        for sp in &self.spheres {
            let extra = ["ex", "ey", "ez", "ftx", "fty", "ftz"];
            for s in crate::results::CONTACT_COLUMNS.iter().chain(&extra) {
                c.push(format!("{}.{s}", sp.name));
            }
            if sp.bristle.is_some() {
                for s in ["lugre_zx", "lugre_zy", "lugre_zz"] {
                    c.push(format!("{}.{s}", sp.name));
                }
            }
        }
        for jn in &self.journals {
            for g in &super::journal::GROUP_NAMES[..jn.n_groups()] {
                for s in ["penetration", "normal_force"] {
                    c.push(format!("{}.{g}.{s}", jn.name));
                }
            }
            for s in ["Fx", "Fy", "Fz", "Mx", "My", "Mz", "tilt", "axial_offset"] {
                c.push(format!("{}.{s}", jn.name));
            }
            if jn.film.is_some() {
                for s in ["film_force", "film_thickness"] {
                    c.push(format!("{}.{s}", jn.name));
                }
            }
        }
        for sc in &self.shape_contacts {
            for s in crate::results::CONTACT_COLUMNS
                .iter()
                .chain(&["ex", "ey", "ez"])
            {
                c.push(format!("{}.{s}", sc.name));
            }
        }
        c.extend(crate::results::ENERGY_COLUMNS.map(String::from));
        for s in ["position", "velocity", "quaternion"] {
            c.push(format!("violation.{s}"));
        }
        c
    }

    /// Energies at y (evaluates the model).
    pub fn energies(&mut self, t: f64, y: &[f64]) -> Energies {
        self.evaluate(t, y);
        self.energies_evaluated(y)
    }

    fn energies_evaluated(&self, y: &[f64]) -> Energies {
        let nb = self.bodies.len();
        let mut e = Energies::default();
        for (k, b) in self.bodies.iter().enumerate() {
            let v = &y[7 * nb + 6 * k..7 * nb + 6 * k + 6];
            let w = Vector3::new(v[3], v[4], v[5]);
            e.kinetic +=
                0.5 * b.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 0.5 * w.dot(&(b.j * w));
            let r = Vector3::new(y[7 * k], y[7 * k + 1], y[7 * k + 2]);
            e.potential -= b.mass * self.gravity.dot(&r);
        }
        e.elastic = self
            .forces
            .iter()
            .map(|(_, f)| f.elastic_energy(&self.ws.kin))
            .sum::<f64>()
            + self
                .ws
                .reports
                .iter()
                .map(|r| r.elastic_energy)
                .sum::<f64>()
            + self
                .ws
                .journal_reports
                .iter()
                .map(|r| r.elastic_energy)
                .sum::<f64>()
            + self
                .ws
                .shape_reports
                .iter()
                .map(|r| r.elastic_energy)
                .sum::<f64>();
        e
    }

    /// ‖Φ‖∞ and ‖Φ̇‖∞ at (t, y) (evaluates the model).
    pub fn violation(&mut self, t: f64, y: &[f64]) -> (f64, f64) {
        self.evaluate(t, y);
        self.violation_evaluated(y)
    }

    fn violation_evaluated(&self, y: &[f64]) -> (f64, f64) {
        let nv = self.n_v();
        let v = &y[self.n_q()..self.n_q() + nv];
        let mut pv = 0.0f64;
        let mut vv = 0.0f64;
        for r in 0..self.m {
            pv = pv.max(self.ws.phi[r].abs());
            let gv: f64 = self.ws.g[r * nv..(r + 1) * nv]
                .iter()
                .zip(v)
                .map(|(a, b)| a * b)
                .sum();
            vv = vv.max((gv + self.ws.phit[r]).abs());
        }
        (pv, vv)
    }

    /// Largest |‖p‖ − 1| over the bodies' quaternions in y.
    pub fn quaternion_drift(&self, y: &[f64]) -> f64 {
        (0..self.bodies.len())
            .map(|k| {
                let p = &y[7 * k + 3..7 * k + 7];
                ((p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]).sqrt() - 1.0).abs()
            })
            .fold(0.0, f64::max)
    }

    /// Append the row of (t, y) to `data`.
    pub(crate) fn record(&mut self, t: f64, y: &[f64], data: &mut Vec<f64>) {
        let nb = self.bodies.len();
        let (nq, nv) = (7 * nb, 6 * nb);
        let mut dy = vec![0.0; self.dim()];
        self.rhs(t, y, &mut dy);
        data.push(t);
        for k in 0..nb {
            let qk = &y[7 * k..7 * k + 7];
            let n = (qk[3..7].iter().map(|c| c * c).sum::<f64>()).sqrt();
            data.extend_from_slice(&qk[..3]);
            data.extend(qk[3..7].iter().map(|c| c / n));
            data.extend_from_slice(&y[nq + 6 * k..nq + 6 * k + 6]);
            data.extend_from_slice(&dy[nq + 6 * k..nq + 6 * k + 6]);
        }
        for o in &self.owners {
            let k = if o.j == super::kin::GROUND { o.i } else { o.j };
            let (mut f, mut mb) = (Vector3::zeros(), Vector3::zeros());
            if k != super::kin::GROUND {
                for r in o.rows.0..o.rows.1 {
                    let g = &self.ws.g[r * nv + 6 * k..r * nv + 6 * k + 6];
                    let l = self.ws.lambda[r];
                    f -= Vector3::new(g[0], g[1], g[2]) * l;
                    mb -= Vector3::new(g[3], g[4], g[5]) * l;
                }
            }
            let mw = self.ws.kin.get(k).a * mb;
            data.extend(f.iter().chain(mw.iter()));
        }
        let zoff = nq + nv + 2;
        for (s, sp) in self.spheres.iter().enumerate() {
            let r = &self.ws.reports[s];
            data.extend([
                r.penetration,
                r.rate,
                r.normal_force,
                r.friction.norm(),
                f64::from(u8::from(r.normal_force > 0.0)),
            ]);
            data.extend(r.eccentricity.iter().chain(r.friction.iter()));
            if let Some(o) = sp.bristle {
                data.extend_from_slice(&y[zoff + o..zoff + o + 3]);
            }
        }
        for (k, jn) in self.journals.iter().enumerate() {
            let r = &self.ws.journal_reports[k];
            for g in 0..jn.n_groups() {
                data.extend([r.penetration[g], r.normal_force[g]]);
            }
            data.extend(r.force.iter().chain(r.moment.iter()));
            data.extend([r.tilt, r.axial_offset]);
            if jn.film.is_some() {
                data.extend([r.film_force, r.film_thickness]);
            }
        }
        for r in &self.ws.shape_reports {
            data.extend([
                r.penetration,
                r.rate,
                r.normal_force,
                r.friction_force,
                r.active_points as f64,
            ]);
            data.extend(r.deepest.iter());
        }
        let e = self.energies_evaluated(y);
        let (ed, win) = (y[nq + nv], y[nq + nv + 1]);
        data.extend([
            e.kinetic,
            e.potential,
            e.elastic,
            e.total(),
            ed,
            win,
            e.total() + ed - win,
        ]);
        let (pv, vv) = self.violation_evaluated(y);
        data.extend([pv, vv, self.quaternion_drift(y)]);
    }

    /// Commit the contact memory at the end of an accepted step.
    pub(crate) fn commit_contacts(&mut self, y: &[f64]) {
        self.ws.kin.update(self.bodies.len(), y);
        for s in &self.spheres {
            let (d, r) = s.gap_rate(&self.ws.kin);
            self.memory.commit(s.memory, d, r);
        }
        for jn in &self.journals {
            jn.commit(&self.ws.kin, &mut self.memory);
        }
        for c in &mut self.shape_contacts {
            c.commit(&self.ws.kin, &mut self.memory);
        }
    }
}
