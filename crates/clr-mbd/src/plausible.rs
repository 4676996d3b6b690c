//! Plausibility checks of a run: the inputs and the assembled initial state before
//! integrating, and the results after. Each finding is a [`Warning`] naming the field or item
//! and what to check (`clr: warning:` on the command line, `warnings` in summary.json,
//! `Result.warnings` in Python); [`SimOptions::strict`](crate::SimOptions) turns them into
//! [`MbdError::Implausible`]. One check refuses outright: a contact element that starts deeper
//! in contact than its own clearance ([`MbdError::InitialPenetration`]).
//!
//! Every threshold is chosen so that no built-in model, example, test model or verify case
//! trips it, with a margin over the largest value they reach (docs/plausibility.md lists each
//! threshold, why it is where it is, and the mistake it catches).

use nalgebra::Vector2;

use crate::clearance::ClearanceKind;
use crate::error::MbdError;
use crate::init::InitialConditions;
use crate::results::Results;
use crate::runtime::{body_state, GROUND_ID};
use crate::system::Model;

/// A contact element refuses to start when its initial penetration exceeds this many
/// clearances (a journal outside its bearing by more than the clearance).
pub const REFUSE_PENETRATION: f64 = 1.0;
/// Given coordinates moved by the assembly by more than this fraction of the mechanism's size
/// (angles: times the body's extent) are reported: a value in degrees or millimetres. Built-ins
/// move nothing; rounding given values to 3 digits moves them by ~1e-3.
pub const CORRECTION_FRACTION: f64 = 0.01;
/// A bearing radius above this fraction of the mechanism's size (radii in mm on a linkage in m).
pub const RADIUS_FRACTION: f64 = 0.5;
/// A radial clearance above this fraction of the bearing radius (typical joints: 1e-3 to 5e-2).
pub const CLEARANCE_FRACTION: f64 = 0.25;
/// Friction coefficients above this (dry metals and polymers stay below 1).
pub const MAX_FRICTION: f64 = 1.0;
/// Peripheral speed ω·extent of a body above this, m/s (an rpm value written as rad/s: 5000
/// rpm on a 0.05 m crank is 26 m/s, 5000 "rad/s" is 250 m/s).
pub const MAX_TIP_SPEED: f64 = 150.0;
/// Radius of gyration √(I/m) above this multiple of the body's extent (its farthest anchor
/// from the centre of mass); a uniform rod has 0.58, a disc pinned at its rim 0.71.
pub const MAX_GYRATION: f64 = 3.0;
/// A contact shape on a body whose bounding radius (the farthest corner of its bounding box
/// from the shape's origin) exceeds this multiple of the body's largest radius of gyration
/// √(I_max/m): for a uniform solid it is a few times that at most (a ball √3 r against
/// √(2/5) r: 2.7; a cube 2.1; a slender rod 1.7), and a contact shape that is a part of a larger
/// body gives less; a radius in millimetres gives ~1000, a mass in grams ~30.
pub const MAX_SHAPE_TO_GYRATION: f64 = 30.0;
/// Viscosities outside [min, max] Pa·s (air 1.8e-5; heavy gear oils ~1 Pa·s at 40 °C; a
/// value in cP or mPa·s is 1000 times too large).
pub const VISCOSITY_RANGE: (f64, f64) = (1e-5, 5.0);
/// Largest L/D of the short-bearing (Ocvirk) film (Frêne et al., *Hydrodynamic Lubrication*,
/// 1997, §4.3: within a few per cent of the finite bearing for L/D ≤ 0.5, 5 times off the long
/// form at L/D = 4); smallest L/D of the long-bearing (Sommerfeld) film.
pub const SHORT_BEARING_MAX_LD: f64 = 0.5;
/// See [`SHORT_BEARING_MAX_LD`].
pub const LONG_BEARING_MIN_LD: f64 = 2.0;
/// Relative difference of the effective restitution from the one asked for (the dual guide's
/// Flores law at 0.8 gives 0.7885, 1.4 %; Lankarani–Nikravesh at 0.8 gives 0.847, 5.9 %).
pub const RESTITUTION_TOLERANCE: f64 = 0.02;
pub use crate::desc::checks::MODULUS_RANGE;
/// Energy-balance error above this fraction of the energy scale (largest of the energy change,
/// the work in, the dissipated energy and the kinetic energy); built-ins reach 2e-3.
pub const BALANCE_FRACTION: f64 = 0.05;
/// Largest penetration of a clearance joint above this fraction of its clearance (the contact
/// laws assume δ ≪ c; the slider–crank at 5000 rpm reaches 0.21).
pub const PENETRATION_FRACTION: f64 = 0.5;
/// Largest penetration of a shape contact above this fraction of the smaller shape's bounding
/// radius (Hertz assumes δ ≪ R; resting contacts reach ~1e-4).
pub const SHAPE_PENETRATION_FRACTION: f64 = 0.1;
/// Initial penetration of a shape contact above this fraction of the smaller shape's bounding
/// radius (a body started inside another).
pub const SHAPE_START_FRACTION: f64 = 0.01;
/// Peak contact force above this multiple of the weight and inertia loads Σ m (|g| + ω² ρ +
/// v²/L) over the run (ρ the body's extent, L the mechanism's size).
pub const FORCE_RATIO: f64 = 1e4;

pub use crate::initial_data::Warning;

/// A finding on `field`.
pub(crate) fn warn(field: impl Into<String>, message: String) -> Warning {
    Warning {
        field: field.into(),
        message,
    }
}

/// Sizes of the mechanism at one state.
pub(crate) struct Scales {
    /// Diagonal of the bounding box of every anchor, point and centre of mass, m.
    pub(crate) size: f64,
    /// Farthest anchor of each rigid body from its centre of mass, m.
    extent: Vec<f64>,
}

impl Model {
    /// Anchors (frame, local point) of the constraints, contact elements and points.
    fn anchors(&self) -> Vec<(usize, Vector2<f64>)> {
        use crate::runtime::ConKind;
        let mut out: Vec<(usize, Vector2<f64>)> = Vec::new();
        for c in &self.cons {
            match c.kind {
                ConKind::Coincide { i, si, j, sj } | ConKind::Project { i, si, j, sj, .. } => {
                    out.extend([(i, si), (j, sj)]);
                }
                _ => {}
            }
        }
        for c in &self.clearances {
            match &c.kind {
                ClearanceKind::Revolute(g, _) => {
                    out.extend([(c.i, g.bearing_centre()), (c.j, g.journal_centre())]);
                }
                ClearanceKind::Translational {
                    geometry, origin, ..
                } => out.extend([(c.i, *origin), (c.j, geometry.slider().centre())]),
                _ => {}
            }
        }
        out.extend(self.points.iter().map(|(_, f, s)| (*f, *s)));
        out
    }

    /// The mechanism's size and each rigid body's extent at q.
    pub(crate) fn scales(&self, q: &[f64]) -> Scales {
        let zeros = vec![0.0; self.n];
        let mut extent = vec![0.0f64; self.bodies.len()];
        let (mut lo, mut hi) = (
            Vector2::repeat(f64::INFINITY),
            Vector2::repeat(-f64::INFINITY),
        );
        let mut add = |p: Vector2<f64>| {
            if p.iter().all(|x| x.is_finite()) {
                lo = lo.inf(&p);
                hi = hi.sup(&p);
            }
        };
        for (frame, s) in self.anchors() {
            if let Some(e) = extent.get_mut(frame) {
                *e = e.max(s.norm());
            }
            if frame == GROUND_ID {
                add(s);
            } else if frame < self.frames.len() {
                add(body_state(&self.frames, frame, q, &zeros).point(s));
            }
        }
        for k in 0..self.bodies.len() {
            add(Vector2::new(q[3 * k], q[3 * k + 1]));
        }
        // A contact shape reaches beyond its anchor: a gear turning about its centre has all
        // its anchors at the centre, and its extent is its tip radius.
        for c in &self.clearances {
            if let ClearanceKind::Shapes(p) = &c.kind {
                for (frame, side) in [(c.i, &p.a), (c.j, &p.b)] {
                    if let Some(e) = extent.get_mut(frame) {
                        *e = e.max(side.reach);
                    }
                }
            }
        }
        let size = if lo.x.is_finite() {
            (hi - lo).norm()
        } else {
            0.0
        };
        Scales { size, extent }
    }

    /// Checks of the inputs and of the assembled initial state y0 (after [`crate::initial`]).
    ///
    /// # Errors
    /// [`MbdError::InitialPenetration`] for a contact element started deeper than its clearance.
    pub(crate) fn check_start(
        &mut self,
        t0: f64,
        y0: &[f64],
        ic: &InitialConditions,
    ) -> Result<Vec<Warning>, MbdError> {
        let n = self.n;
        let sc = self.scales(&y0[..n]);
        let mut out = self.input_warnings.clone();
        self.check_corrections(ic, &sc, &mut out);
        self.check_bodies(y0, &sc, &mut out);
        self.check_contact_inputs(&sc, &mut out);
        self.check_measure_points(&sc, &mut out);
        self.check_initial_contacts(t0, y0, ic, &mut out)?;
        Ok(out)
    }

    /// An angle offset beyond a whole turn (most likely degrees), and a measured point far
    /// outside its body and the mechanism ([`MAX_MEASURE_REACH`] times the
    /// larger of the mechanism's size and the body's radius of gyration) is most likely given in
    /// millimetres: the measure is still written, with a warning at its field.
    fn check_measure_points(&self, sc: &Scales, out: &mut Vec<Warning>) {
        for m in &self.measures {
            if let Some(offset) = m.angle_offset().filter(|o| o.abs() > std::f64::consts::TAU) {
                out.push(warn(
                    format!("{}.offset", m.name),
                    format!(
                        "an angle offset of {offset} rad is more than a whole turn: angles are in \
                         radians ({offset}° would be {:.6} rad)",
                        offset.to_radians()
                    ),
                ));
            }
            for (field, (k, s)) in m.points() {
                let Some(b) = self.bodies.get(k) else {
                    continue;
                };
                let reach = MAX_MEASURE_REACH * sc.size.max((b.inertia / b.mass).sqrt());
                if s.norm() > reach {
                    out.push(warn(
                        format!("{}.{field}", m.name),
                        format!(
                            "the point is {:.3e} m from the centre of mass of `{}`, more than \
                             {MAX_MEASURE_REACH} times the mechanism's size ({:.3e} m) and the \
                             body's radius of gyration: lengths are in metres",
                            s.norm(),
                            self.body_names[k],
                            sc.size
                        ),
                    ));
                }
            }
        }
    }

    fn check_corrections(&self, ic: &InitialConditions, sc: &Scales, out: &mut Vec<Warning>) {
        for b in &ic.bodies {
            let k = self.body_index(&b.body).unwrap_or(0);
            let ext = sc.extent.get(k).copied().unwrap_or(0.0);
            for (c, name) in b.coordinates.iter().zip(crate::COORDINATE_NAMES).take(3) {
                let moved = if name == "theta" {
                    c.correction().abs() * ext
                } else {
                    c.correction().abs()
                };
                if c.is_corrected() && moved > CORRECTION_FRACTION * sc.size {
                    out.push(warn(
                        format!("{}.{name}", b.body),
                        format!(
                            "the assembly changed the given value {:.6e} to {:.6e} {}, which \
                             moves the body by {moved:.3e} m, {:.1} % of the mechanism's size \
                             {:.3e} m: check that angles are in radians and lengths in metres",
                            c.given,
                            c.assembled,
                            crate::initial::unit_of(name),
                            100.0 * moved / sc.size,
                            sc.size
                        ),
                    ));
                }
            }
        }
    }

    fn check_bodies(&self, y0: &[f64], sc: &Scales, out: &mut Vec<Warning>) {
        let n = self.n;
        for (k, b) in self.bodies.iter().enumerate() {
            let name = &self.body_names[k];
            let ext = sc.extent[k];
            let w = y0[n + 3 * k + 2];
            out.extend(tip_speed(format!("{name}.omega"), "ω", w, ext));
            let gyration = (b.inertia / b.mass).sqrt();
            out.extend(gyration_radius(
                name,
                "the radius of gyration √(inertia/mass)",
                gyration,
                ext,
            ));
        }
    }

    fn check_contact_inputs(&self, sc: &Scales, out: &mut Vec<Warning>) {
        for c in &self.clearances {
            let name = &c.name;
            if let ClearanceKind::Revolute(g, _) = &c.kind {
                let (rb, cl) = (g.bearing_radius(), g.clearance());
                let fields = [
                    format!("{name}.bearing_radius"),
                    format!("{name}.journal_radius"),
                ];
                out.extend(joint_radii(fields, "bearing", rb, cl, sc.size));
            }
            out.extend(friction(name, c.friction.mu_max()));
            out.extend(restitution(name, &c.normal));
            if let Some(f) = &c.film {
                check_film(name, &f.bearing, out);
            }
        }
    }

    /// Initial penetration of every contact element at y0: refused beyond its clearance,
    /// reported for shapes started inside each other.
    fn check_initial_contacts(
        &mut self,
        t0: f64,
        y0: &[f64],
        ic: &InitialConditions,
        out: &mut Vec<Warning>,
    ) -> Result<(), MbdError> {
        if self.clearances.is_empty() {
            return Ok(());
        }
        let n = self.n;
        self.load_bristles(y0);
        self.eval_forces(t0, &y0[..n], &y0[n..2 * n]);
        for (k, c) in self.clearances.iter().enumerate() {
            let depth = self.contacts[k].penetration;
            if depth <= 0.0 {
                continue;
            }
            match contact_scale(c) {
                Scale::Clearance(cl, what) if depth > REFUSE_PENETRATION * cl => {
                    let moved: Vec<String> = ic
                        .corrected()
                        .iter()
                        .map(|(b, name, g, a)| format!("{b}.{name} {g:.4e} → {a:.4e}"))
                        .collect();
                    let hint = if moved.is_empty() {
                        String::new()
                    } else {
                        format!(" (the assembly changed {})", moved.join(", "))
                    };
                    return Err(MbdError::InitialPenetration {
                        element: c.name.clone(),
                        what,
                        t: t0,
                        penetration: depth,
                        clearance: cl,
                        ratio: depth / cl,
                        hint,
                    });
                }
                Scale::Size(r) if depth > SHAPE_START_FRACTION * r => out.push(warn(
                    c.name.clone(),
                    format!(
                        "the shapes start {depth:.3e} m inside each other ({:.1} % of the smaller \
                         shape's size {r:.3e} m): the first step pushes them apart with a force \
                         of {:.3e} N; check the initial positions",
                        100.0 * depth / r,
                        self.contacts[k].normal_force
                    ),
                )),
                _ => {}
            }
        }
        Ok(())
    }

    /// Checks of a finished (or failed) run's results.
    pub(crate) fn check_end(&self, r: &Results, sc: &Scales) -> Vec<Warning> {
        let mut out = Vec::new();
        check_energy(r, &mut out);
        for c in &self.clearances {
            let Some(depth) = r.column(&format!("{}.penetration", c.name)) else {
                continue;
            };
            let (fraction, scale, of) = match contact_scale(c) {
                Scale::Clearance(cl, _) => (PENETRATION_FRACTION, cl, "its clearance"),
                Scale::Size(s) => (SHAPE_PENETRATION_FRACTION, s, "the smaller shape's size"),
                Scale::None => continue,
            };
            out.extend(deep(&c.name, &depth, (fraction, scale, of)));
        }
        self.check_peak_forces(r, sc, &mut out);
        out
    }

    fn check_peak_forces(&self, r: &Results, sc: &Scales, out: &mut Vec<Warning>) {
        let size = sc.size;
        let g = self.gravity.norm();
        let mut load = 0.0;
        for (k, b) in self.bodies.iter().enumerate() {
            let name = &self.body_names[k];
            let (Some(w), Some(vx), Some(vy)) = (
                r.column(&format!("{name}.omega")),
                r.column(&format!("{name}.vx")),
                r.column(&format!("{name}.vy")),
            ) else {
                return;
            };
            let ext = sc.extent[k];
            let a = w
                .iter()
                .zip(vx.iter().zip(&vy))
                .map(|(w, (x, y))| {
                    w * w * ext
                        + if size > 0.0 {
                            (x * x + y * y) / size
                        } else {
                            0.0
                        }
                })
                .fold(0.0, f64::max);
            load += b.mass * (g + a);
        }
        if load <= 0.0 {
            return;
        }
        for c in &self.clearances {
            let Some(f) = r.column(&format!("{}.normal_force", c.name)) else {
                continue;
            };
            out.extend(peak_force(&c.name, &f, load));
        }
    }

    /// What the state y at t (the last one an integrator failure reached) shows that likely
    /// caused the failure: the deepest contact against its clearance (or its shapes' size), the
    /// largest contact force against the weight of the mechanism, the fastest body; `""` when
    /// the state is empty. A sentence starting with `; `.
    pub(crate) fn failure_cause(&mut self, t: f64, y: &[f64]) -> String {
        let n = self.n;
        if y.len() < 2 * n || y.iter().any(|v| !v.is_finite()) {
            return "; the state reached is not finite: look for a force that grows without \
                    bound (a penetration deep against the contact's size, a stiffness in the \
                    wrong unit)"
                .into();
        }
        let mut parts = Vec::new();
        if !self.clearances.is_empty() {
            self.load_bristles(y);
            self.eval_forces(t, &y[..n], &y[n..2 * n]);
            let deepest = self
                .clearances
                .iter()
                .zip(&self.contacts)
                .filter_map(|(c, r)| {
                    let scale = match contact_scale(c) {
                        Scale::Clearance(cl, _) => cl,
                        Scale::Size(s) => s,
                        Scale::None => return None,
                    };
                    (r.penetration > 0.0).then_some((c.name.as_str(), r.penetration, scale))
                })
                .max_by(|a, b| (a.1 / a.2).total_cmp(&(b.1 / b.2)));
            if let Some((name, d, s)) = deepest {
                parts.push(format!(
                    "the deepest contact is {name}, {d:.3e} m in ({:.2} of its clearance or size \
                     {s:.3e} m)",
                    d / s
                ));
            }
            let strongest = self
                .clearances
                .iter()
                .zip(&self.contacts)
                .max_by(|a, b| a.1.normal_force.abs().total_cmp(&b.1.normal_force.abs()));
            let weight: f64 = self.bodies.iter().map(|b| b.mass).sum::<f64>() * 9.81;
            if let Some((c, r)) = strongest.filter(|(_, r)| r.normal_force != 0.0) {
                parts.push(format!(
                    "the largest contact force is {:.3e} N in {} ({:.1e} times the mechanism's \
                     weight at 9.81 m/s²)",
                    r.normal_force,
                    c.name,
                    r.normal_force.abs() / weight.max(f64::MIN_POSITIVE)
                ));
            }
        }
        let sc = self.scales(&y[..n]);
        let fastest = (0..self.bodies.len())
            .map(|k| {
                let v =
                    y[n + 3 * k].hypot(y[n + 3 * k + 1]) + y[n + 3 * k + 2].abs() * sc.extent[k];
                (k, v)
            })
            .max_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((k, v)) = fastest.filter(|(_, v)| *v > MAX_TIP_SPEED) {
            parts.push(format!(
                "body {} moves at {v:.3e} m/s (above {MAX_TIP_SPEED} m/s)",
                self.body_names[k]
            ));
        }
        if parts.is_empty() {
            String::new()
        } else {
            format!("; at the last state reached, {}", parts.join("; "))
        }
    }
}

/// What a contact element's penetration is measured against.
enum Scale {
    /// A clearance joint's clearance (m) and what penetrates.
    Clearance(f64, &'static str),
    /// The smaller shape's bounding radius, m.
    Size(f64),
    None,
}

fn contact_scale(c: &crate::clearance::Clearance) -> Scale {
    match &c.kind {
        ClearanceKind::Revolute(g, _) => {
            Scale::Clearance(g.clearance(), "journal into the bearing")
        }
        ClearanceKind::Translational { geometry, .. } => {
            Scale::Clearance(geometry.clearance(), "slider into the guide")
        }
        ClearanceKind::Shapes(p) => Scale::Size(p.a.radius.min(p.b.radius)),
        ClearanceKind::FacePair(p) => Scale::Size(p.shape_radius()),
        ClearanceKind::FlexGuide(_) => Scale::None,
    }
}

/// Warn on a viscosity outside real lubricants and an L/D outside the film form's range.
pub(crate) fn check_film(
    name: &str,
    b: &clr_contact::lubrication::HydrodynamicBearing,
    out: &mut Vec<Warning>,
) {
    use clr_contact::lubrication::BearingModel;
    let mu = b.viscosity();
    if !(VISCOSITY_RANGE.0..=VISCOSITY_RANGE.1).contains(&mu) {
        out.push(warn(
            format!("{name}.lubrication.viscosity"),
            format!(
                "a viscosity of {mu:e} Pa·s is outside the range of real lubricants \
                 [{:e}, {:e}] Pa·s: 1 cP = 1 mPa·s = 1e-3 Pa·s",
                VISCOSITY_RANGE.0, VISCOSITY_RANGE.1
            ),
        ));
    }
    // D is the bore (bearing) diameter, the nominal size of a journal bearing
    let ld = b.length() / (2.0 * b.bearing_radius());
    let (bad, form) = match b.model() {
        BearingModel::ShortBearing => (ld > SHORT_BEARING_MAX_LD, "short-bearing (Ocvirk)"),
        BearingModel::LongBearing => (ld < LONG_BEARING_MIN_LD, "long-bearing (Sommerfeld)"),
    };
    if bad {
        out.push(warn(
            format!("{name}.lubrication.model"),
            format!(
                "L/D = {ld:.3} is outside the range of the {form} film (short: L/D ≤ \
                 {SHORT_BEARING_MAX_LD}, long: L/D ≥ {LONG_BEARING_MIN_LD}): its force is off by \
                 a factor that grows with the distance (5 at L/D = 4 for the short form)"
            ),
        ));
    }
}

/// The energy balance against the run's energy scale ([`BALANCE_FRACTION`]).
pub(crate) fn check_energy(r: &Results, out: &mut Vec<Warning>) {
    let range = |name: &str| -> Option<f64> {
        let c = r.column(name)?;
        let first = *c.first()?;
        Some(c.iter().map(|x| (x - first).abs()).fold(0.0, f64::max))
    };
    let (Some(balance), Some(change)) = (range("energy.balance"), range("energy.total")) else {
        return;
    };
    let scale = [
        change,
        range("energy.work_in").unwrap_or(0.0),
        range("energy.dissipated").unwrap_or(0.0),
        r.column("energy.kinetic")
            .map_or(0.0, |k| k.iter().copied().fold(0.0, f64::max)),
    ]
    .into_iter()
    .fold(0.0, f64::max);
    if balance > BALANCE_FRACTION * scale && balance > 0.0 {
        out.push(warn(
            "energy",
            format!(
                "the energy balance is off by {balance:.3e} J against an energy scale of \
                 {scale:.3e} J (the energy change, the work put in, the energy dissipated): the \
                 run created or lost energy; tighten rtol, check the contact stiffness and the \
                 initial state"
            ),
        ));
    }
}

/// The error of `strict` runs with plausibility findings.
pub(crate) fn implausible(w: &[Warning], partial: Option<Results>) -> MbdError {
    MbdError::Implausible {
        warnings: w
            .iter()
            .map(|w| w.to_string())
            .collect::<Vec<_>>()
            .join("; "),
        count: w.len(),
        partial: partial.map(Box::new),
    }
}

/// A body turning at `w` (rad/s; `symbol` names it in the message) with its farthest anchor at
/// `ext` (m): a finding above [`MAX_TIP_SPEED`], with the value it has if it was in rpm.
pub(crate) fn tip_speed(field: String, symbol: &str, w: f64, ext: f64) -> Option<Warning> {
    let speed = w.abs() * ext;
    (speed > MAX_TIP_SPEED).then(|| {
        warn(
            field,
            format!(
                "{symbol} = {w:.6e} rad/s at t0 gives a peripheral speed of {speed:.3e} m/s at \
                 {ext:.3e} m from the centre of mass (above {MAX_TIP_SPEED} m/s): if it is in \
                 rpm, {symbol} = {:.6e} rad/s",
                w * std::f64::consts::PI / 30.0
            ),
        )
    })
}

/// How far a measured point may lie from its body, in units of the larger of the mechanism's
/// size and the body's radius of gyration, before it is flagged (a point in mm is 1000 times
/// too far; a sensor on a long boom is still well inside).
pub(crate) const MAX_MEASURE_REACH: f64 = 30.0;

/// A radius of gyration `gyration` (m; `what` says which) above [`MAX_GYRATION`] times the
/// body's extent `ext` (m).
pub(crate) fn gyration_radius(name: &str, what: &str, gyration: f64, ext: f64) -> Option<Warning> {
    (ext > 0.0 && gyration > MAX_GYRATION * ext).then(|| {
        warn(
            name,
            format!(
                "{what} = {gyration:.3e} m is {:.1} times the body's extent {ext:.3e} m (its \
                 farthest anchor): check the units of mass (kg) and inertia (kg·m², about the \
                 centre of mass)",
                gyration / ext
            ),
        )
    })
}

/// The outer radius `r` (m) of a clearance joint (a `what`: bearing, socket) against the
/// mechanism's `size` ([`RADIUS_FRACTION`]), and its clearance `cl` against `r`
/// ([`CLEARANCE_FRACTION`]); `fields` name the outer and the inner radius.
pub(crate) fn joint_radii(
    fields: [String; 2],
    what: &str,
    r: f64,
    cl: f64,
    size: f64,
) -> Vec<Warning> {
    let [outer, inner] = fields;
    let mut out = Vec::new();
    if size > 0.0 && r > RADIUS_FRACTION * size {
        out.push(warn(
            outer,
            format!(
                "a {what} radius of {r:.3e} m on a mechanism {size:.3e} m across: radii are in \
                 metres (10 mm is 0.01)"
            ),
        ));
    }
    if cl > CLEARANCE_FRACTION * r {
        out.push(warn(
            inner,
            format!(
                "a radial clearance of {cl:.3e} m is {:.0} % of the {what} radius {r:.3e} m \
                 (joints have 0.1–5 %): check both radii",
                100.0 * cl / r
            ),
        ));
    }
    out
}

/// A friction coefficient above [`MAX_FRICTION`] on element `name`.
pub(crate) fn friction(name: &str, mu: f64) -> Option<Warning> {
    (mu > MAX_FRICTION).then(|| {
        warn(
            format!("{name}.friction"),
            format!(
                "a friction coefficient of {mu} (above {MAX_FRICTION}; dry metals 0.1–0.8): \
                 check the value"
            ),
        )
    })
}

/// A damping law whose effective restitution misses the asked one by more than
/// [`RESTITUTION_TOLERANCE`].
pub(crate) fn restitution(name: &str, law: &clr_contact::NormalLaw) -> Option<Warning> {
    let (asked, effective) = (law.c_e(), law.effective_restitution());
    (asked > 0.0 && ((effective - asked) / asked).abs() > RESTITUTION_TOLERANCE).then(|| {
        warn(
            format!("{name}.normal"),
            format!(
                "the damping law turns the restitution {asked} asked for into an effective \
                 {effective:.4} ({:+.1} %): choose an exact-restitution damping \
                 (docs/contact.md) or adjust the value",
                100.0 * (effective - asked) / asked
            ),
        )
    })
}

/// The largest of a penetration column `depth` (m) above `fraction` of `scale` (m; `of` names
/// it).
pub(crate) fn deep(
    name: &str,
    depth: &[f64],
    (fraction, scale, of): (f64, f64, &str),
) -> Option<Warning> {
    let max = depth.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (max > fraction * scale).then(|| {
        warn(
            name,
            format!(
                "the largest penetration {max:.3e} m is {:.0} % of {of} {scale:.3e} m (above \
                 {:.0} %): the contact stiffness is far too low for the loads (Young's modulus \
                 in Pa, a stiffness in N/m^n, not per mm)",
                100.0 * max / scale,
                100.0 * fraction
            ),
        )
    })
}

/// The peak of a normal-force column `f` (N) above [`FORCE_RATIO`] times the weight and inertia
/// loads `load` (N).
pub(crate) fn peak_force(name: &str, f: &[f64], load: f64) -> Option<Warning> {
    let peak = f.iter().map(|x| x.abs()).fold(0.0, f64::max);
    (peak > FORCE_RATIO * load).then(|| {
        warn(
            name,
            format!(
                "a peak normal force of {peak:.3e} N is {:.1e} times the weight and inertia \
                 loads of the mechanism ({load:.3e} N): check masses (kg), stiffnesses and the \
                 initial state",
                peak / load
            ),
        )
    })
}

/// Finish a run: `report` adds what the model knows of the run (notes, plausibility findings)
/// to its results, also to the partial results of a failed or stopped run; with `strict`, a
/// finding makes the finished run an [`MbdError::Implausible`] carrying its results.
///
/// # Errors
/// The run's own error (with its partial results reported), or [`MbdError::Implausible`].
pub(crate) fn finish<M>(
    model: &M,
    run: Result<Results, MbdError>,
    strict: bool,
    report: impl Fn(&M, Results) -> Results,
) -> Result<Results, MbdError> {
    match run {
        Ok(r) => {
            let r = report(model, r);
            if strict && !r.warnings.is_empty() {
                let w = r.warnings.clone();
                return Err(implausible(&w, Some(r)));
            }
            Ok(r)
        }
        Err(e) => Err(e.map_partial(|r| report(model, r))),
    }
}
