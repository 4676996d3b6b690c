//! Plausibility checks of a spatial run, with the planar engine's thresholds
//! ([`crate::plausible`], docs/plausibility.md): before integrating, the inputs and the
//! assembled initial state (a speed in rpm, a mass or inertia in the wrong unit, a socket
//! radius in millimetres, a clearance of a quarter of the radius, μ > 1, a damping law that
//! misses its restitution, a ball started outside its socket by more than the clearance, which
//! is refused, shapes started inside each other, which is warned); after, the results (the
//! energy balance, penetrations beyond half the clearance or a tenth of a shape's size, peak
//! contact forces far above the weight and inertia loads).

use nalgebra::Vector3;

use super::constraint::PrimKind;
use super::kin::GROUND;
use super::model::SpatialModel;
use crate::desc::laws::ContactFriction;
use crate::error::MbdError;
use crate::plausible::{
    check_energy, deep, friction, gyration_radius, joint_radii, peak_force, restitution, tip_speed,
    warn, Warning, CLEARANCE_FRACTION, MAX_MEASURE_REACH, MAX_SHAPE_TO_GYRATION,
    PENETRATION_FRACTION, REFUSE_PENETRATION, SHAPE_PENETRATION_FRACTION, SHAPE_START_FRACTION,
};
use crate::results::Results;

/// Sizes of a spatial mechanism at one state.
pub(crate) struct Scales3 {
    /// Diagonal of the bounding box of every anchor and centre of mass, m.
    size: f64,
    /// Farthest anchor of each body from its centre of mass, m.
    extent: Vec<f64>,
}

impl super::model::Inertia3 {
    /// The largest radius of gyration √(I_max/m), m.
    fn gyration_radius(&self) -> f64 {
        (self.j.symmetric_eigenvalues().max() / self.mass).sqrt()
    }
}

impl SpatialModel {
    /// Anchors (body, point in the centre-of-mass frame) of the joints and clearance joints.
    fn anchors(&self) -> Vec<(usize, Vector3<f64>)> {
        let mut out = Vec::new();
        for p in &self.prims {
            match p.kind {
                PrimKind::Coincide { si, sj } | PrimKind::Dot2 { si, sj, .. } => {
                    out.extend([(p.i, si), (p.j, sj)]);
                }
                _ => {}
            }
        }
        out.extend(self.spheres.iter().flat_map(|s| [(s.i, s.si), (s.j, s.sj)]));
        out.extend(
            self.journals
                .iter()
                .flat_map(|s| [(s.i, s.si), (s.j, s.sj)]),
        );
        out
    }

    /// The mechanism's size and each body's extent at y.
    pub(crate) fn scales(&mut self, y: &[f64]) -> Scales3 {
        self.ws.kin.update(self.bodies.len(), y);
        let mut extent = vec![0.0f64; self.bodies.len()];
        let (mut lo, mut hi) = (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(-f64::INFINITY),
        );
        let mut add = |p: Vector3<f64>| {
            if p.iter().all(|x| x.is_finite()) {
                lo = lo.inf(&p);
                hi = hi.sup(&p);
            }
        };
        for (k, s) in self.anchors() {
            if k != GROUND {
                extent[k] = extent[k].max(s.norm());
            }
            add(self.ws.kin.get(k).point(&s));
        }
        for k in 0..self.bodies.len() {
            add(self.ws.kin.get(k).r);
        }
        // A contact shape reaches beyond its anchor (as in the planar scales): a wheel's
        // extent is its rim.
        for c in &self.shape_contacts {
            for side in [&c.a, &c.b] {
                if let Some(e) = extent.get_mut(side.body) {
                    *e = e.max(side.s.norm() + side.radius());
                }
            }
        }
        let size = if lo.x.is_finite() {
            (hi - lo).norm()
        } else {
            0.0
        };
        Scales3 { size, extent }
    }

    /// Checks of the inputs and of the assembled initial state y0 at t0.
    ///
    /// # Errors
    /// [`MbdError::InitialPenetration`] for a ball started outside its socket by more than the
    /// clearance.
    pub(crate) fn check_start(&mut self, t0: f64, y0: &[f64]) -> Result<Vec<Warning>, MbdError> {
        let sc = self.scales(y0);
        let mut out = self.input_warnings.clone();
        self.check_bodies(y0, &sc, &mut out);
        self.check_sockets(&sc, &mut out);
        self.check_initial_depths(t0, y0)?;
        self.check_shape_starts(&mut out);
        self.check_shape_sizes(&mut out);
        self.check_measure_points(&sc, &mut out);
        Ok(out)
    }

    /// A measured point far outside its body and the mechanism ([`MAX_MEASURE_REACH`] times the
    /// larger of the mechanism's size and the body's radius of gyration) is most likely given in
    /// millimetres: the measure is still written, with a warning at its field (as planar
    /// measures, `crate::plausible`).
    fn check_measure_points(&self, sc: &Scales3, out: &mut Vec<Warning>) {
        for (field, k, s) in &self.measure_points {
            let reach = MAX_MEASURE_REACH * sc.size.max(self.bodies[*k].gyration_radius());
            if s.norm() > reach {
                out.push(warn(
                    field.clone(),
                    format!(
                        "the point is {:.3e} m from the centre of mass of `{}`, more than \
                         {MAX_MEASURE_REACH} times the mechanism's size ({:.3e} m) and the body's \
                         radius of gyration: lengths are in metres",
                        s.norm(),
                        self.names[*k],
                        sc.size
                    ),
                ));
            }
        }
    }

    /// A contact shape far larger than the body that carries it ([`MAX_SHAPE_TO_GYRATION`]): a
    /// size in millimetres on a body whose mass and inertia are in SI units.
    fn check_shape_sizes(&self, out: &mut Vec<Warning>) {
        for c in &self.shape_contacts {
            for side in [&c.a, &c.b] {
                let Some(b) = self.bodies.get(side.body) else {
                    continue; // the ground has no size to compare with
                };
                let gyration = b.gyration_radius();
                let r = side.radius();
                if r > MAX_SHAPE_TO_GYRATION * gyration {
                    out.push(warn(
                        format!("{}.geometry", side.name),
                        format!(
                            "the shape's bounding box reaches {r:.3e} m from its origin, {:.0} \
                             times the largest radius of gyration {gyration:.3e} m of body `{}` \
                             that carries it: sizes are in metres (10 mm is 0.01), masses in kg \
                             and inertias in kg·m² (a mass in grams makes the body look small)",
                            r / gyration,
                            self.names[side.body]
                        ),
                    ));
                }
            }
        }
    }

    /// Shapes started inside each other by more than [`SHAPE_START_FRACTION`] of the smaller
    /// shape's size (at the kinematics of `check_initial_depths`): warned, as planar shapes.
    fn check_shape_starts(&self, out: &mut Vec<Warning>) {
        for c in &self.shape_contacts {
            let (depth, r) = (c.gap(&self.ws.kin), c.size());
            if depth > SHAPE_START_FRACTION * r {
                out.push(warn(
                    c.name.clone(),
                    format!(
                        "the shapes start {depth:.3e} m inside each other ({:.1} % of the smaller \
                         shape's size {r:.3e} m): the first step pushes them apart; check the \
                         initial positions",
                        100.0 * depth / r
                    ),
                ));
            }
        }
    }

    fn check_bodies(&self, y0: &[f64], sc: &Scales3, out: &mut Vec<Warning>) {
        let nq = self.n_q();
        for (k, b) in self.bodies.iter().enumerate() {
            let name = &self.names[k];
            let ext = sc.extent[k];
            let w = Vector3::from_column_slice(&y0[nq + 6 * k + 3..nq + 6 * k + 6]).norm();
            out.extend(tip_speed(format!("{name}.angular_velocity"), "|ω|", w, ext));
            let gyration = b.gyration_radius();
            let what = "the largest radius of gyration √(I/m)";
            out.extend(gyration_radius(name, what, gyration, ext));
        }
    }

    fn check_sockets(&self, sc: &Scales3, out: &mut Vec<Warning>) {
        for s in &self.spheres {
            let name = &s.name;
            let fields = [
                format!("{name}.socket_radius"),
                format!("{name}.ball_radius"),
            ];
            out.extend(joint_radii(
                fields,
                "socket",
                s.r_socket,
                s.clearance(),
                sc.size,
            ));
            let mu = match &s.friction {
                Some(ContactFriction::Static(f)) => f.mu_max(),
                Some(ContactFriction::LuGre(l)) => l.mu_max(0.0),
                None => 0.0,
            };
            out.extend(friction(name, mu));
            out.extend(restitution(name, &s.law));
        }
        for s in &self.journals {
            let name = &s.name;
            let fields = [
                format!("{name}.bearing_radius"),
                format!("{name}.journal_radius"),
            ];
            let (rb, c) = (s.joint.bearing_radius(), s.joint.clearance());
            out.extend(joint_radii(fields, "bearing", rb, c, sc.size));
            let lb = s.joint.bearing_length();
            if let Some(ca) = s
                .joint
                .axial_clearance()
                .filter(|&ca| ca > CLEARANCE_FRACTION * lb)
            {
                out.push(warn(
                    format!("{name}.axial_clearance"),
                    format!(
                        "an axial end play of {ca:.3e} m is {:.0} % of the bearing length \
                         {lb:.3e} m (thrust faces keep a fraction of a millimetre): lengths are \
                         in metres (0.2 mm is 2e-4)",
                        100.0 * ca / lb
                    ),
                ));
            }
            out.extend(equal_lengths(name, lb, s.joint.journal_length()));
            out.extend(friction(name, s.friction.map_or(0.0, |f| f.mu_max())));
            out.extend(restitution(name, &s.radial));
            if s.thrust != s.radial {
                out.extend(restitution(&format!("{name}.thrust_normal"), &s.thrust));
            }
            if let Some(film) = &s.film {
                // the planar checks on the aligned film: length min(L_b, L_j)
                if let Ok(b) = clr_contact::lubrication::HydrodynamicBearing::new(
                    s.joint.bearing_radius(),
                    s.joint.journal_radius(),
                    s.joint.contact_length(),
                    film.viscosity(),
                    film.model(),
                ) {
                    crate::plausible::check_film(name, &b, out);
                }
            }
        }
        for c in &self.shape_contacts {
            out.extend(friction(&c.name, c.friction.map_or(0.0, |f| f.mu_max())));
            out.extend(restitution(&c.name, &c.law));
        }
    }

    /// A ball outside its socket by more than the clearance at t0 is refused: the first step
    /// would fire it back with a force of the law far outside its range.
    fn check_initial_depths(&mut self, t0: f64, y0: &[f64]) -> Result<(), MbdError> {
        self.ws.kin.update(self.bodies.len(), y0);
        for s in &self.spheres {
            let (depth, cl) = (s.gap(&self.ws.kin), s.clearance());
            if depth > REFUSE_PENETRATION * cl {
                return Err(MbdError::InitialPenetration {
                    element: s.name.clone(),
                    what: "ball into the socket",
                    t: t0,
                    penetration: depth,
                    clearance: cl,
                    ratio: depth / cl,
                    hint: String::new(),
                });
            }
        }
        for s in &self.journals {
            for g in 0..s.n_groups() {
                let depth = s.gap(&self.ws.kin, g);
                let cl = match g {
                    0 | 1 => s.joint.clearance(),
                    _ => s.joint.axial_clearance().unwrap_or(f64::INFINITY),
                };
                if depth > REFUSE_PENETRATION * cl {
                    return Err(MbdError::InitialPenetration {
                        element: format!("{}.{}", s.name, super::journal::GROUP_NAMES[g]),
                        what: "journal into the bearing",
                        t: t0,
                        penetration: depth,
                        clearance: cl,
                        ratio: depth / cl,
                        hint: String::new(),
                    });
                }
            }
        }
        Ok(())
    }

    /// Checks of a finished (or failed) run's results.
    pub(crate) fn check_end(&self, r: &Results, sc: &Scales3) -> Vec<Warning> {
        let mut out = Vec::new();
        check_energy(r, &mut out);
        for s in &self.spheres {
            if let Some(depth) = r.column(&format!("{}.penetration", s.name)) {
                let scale = (PENETRATION_FRACTION, s.clearance(), "its clearance");
                out.extend(deep(&s.name, &depth, scale));
            }
        }
        for s in &self.journals {
            for (k, g) in super::journal::GROUP_NAMES[..s.n_groups()]
                .iter()
                .enumerate()
            {
                if let Some(depth) = r.column(&format!("{}.{g}.penetration", s.name)) {
                    let scale = match k {
                        0 | 1 => (PENETRATION_FRACTION, s.joint.clearance(), "its clearance"),
                        _ => (
                            PENETRATION_FRACTION,
                            s.joint.axial_clearance().unwrap_or(f64::INFINITY),
                            "its axial clearance",
                        ),
                    };
                    out.extend(deep(&format!("{}.{g}", s.name), &depth, scale));
                }
            }
        }
        for c in &self.shape_contacts {
            if let Some(depth) = r.column(&format!("{}.penetration", c.name)) {
                let scale = (
                    SHAPE_PENETRATION_FRACTION,
                    c.size(),
                    "the smaller shape's size",
                );
                out.extend(deep(&c.name, &depth, scale));
            }
        }
        self.check_peak_forces(r, sc, &mut out);
        out
    }

    /// Peak normal forces against Σ m (|g| + |ω|² ρ + |v|²/L) over the run.
    fn check_peak_forces(&self, r: &Results, sc: &Scales3, out: &mut Vec<Warning>) {
        let g = self.gravity.norm();
        let mut load = 0.0;
        for (k, b) in self.bodies.iter().enumerate() {
            let col = |s: &str| r.column(&format!("{}.{s}", self.names[k]));
            let (Some(wx), Some(wy), Some(wz), Some(vx), Some(vy), Some(vz)) = (
                col("wx"),
                col("wy"),
                col("wz"),
                col("vx"),
                col("vy"),
                col("vz"),
            ) else {
                return;
            };
            let a = (0..wx.len())
                .map(|i| {
                    let w2 = wx[i] * wx[i] + wy[i] * wy[i] + wz[i] * wz[i];
                    let v2 = vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i];
                    w2 * sc.extent[k] + if sc.size > 0.0 { v2 / sc.size } else { 0.0 }
                })
                .fold(0.0, f64::max);
            load += b.mass * (g + a);
        }
        if load <= 0.0 {
            return;
        }
        for s in &self.spheres {
            if let Some(f) = r.column(&format!("{}.normal_force", s.name)) {
                out.extend(peak_force(&s.name, &f, load));
            }
        }
        for s in &self.journals {
            for g in &super::journal::GROUP_NAMES[..s.n_groups()] {
                if let Some(f) = r.column(&format!("{}.{g}.normal_force", s.name)) {
                    out.extend(peak_force(&format!("{}.{g}", s.name), &f, load));
                }
            }
        }
        for c in &self.shape_contacts {
            if let Some(f) = r.column(&format!("{}.normal_force", c.name)) {
                out.extend(peak_force(&c.name, &f, load));
            }
        }
    }
}

/// A journal as long as its bore: the overlap then shortens whichever way the journal slides,
/// so the stored contact energy W = ∫Φ(δ) dz / L_c has a kink at zero axial offset, and the
/// journal-end term pushes a centred journal axially with about Φ(δ)/L_c (measured on the
/// frictionless example: 0.015 N under a 400 N impact, tilt grown from rounding to 1e-3 rad
/// within 40 ms; with a longer journal the motion stays planar to the bit). Real pins are
/// longer than their bores.
fn equal_lengths(name: &str, bearing: f64, journal: f64) -> Option<Warning> {
    ((journal - bearing).abs() <= 1e-9 * bearing).then(|| {
        warn(
            format!("{name}.journal_length"),
            format!(
                "the journal is as long as its bore ({journal:.3e} m): the contact energy then \
                 has a kink at zero axial offset, which pushes a centred journal axially (about \
                 Φ(δ)/L_c) and, without friction, lets rounding grow into tilt; a pin is longer \
                 than its bore (with thrust collars at least bearing_length + axial_clearance): \
                 make journal_length longer"
            ),
        )
    })
}
