//! Impacts of clearance joints as located events.
//!
//! An impact of a clearance joint runs from a located onset (its penetration δ crossing 0
//! upward) to its separation (δ crossing 0 downward). For a translational clearance joint δ is
//! the deepest of its four corners, so an impact of the joint lasts from the first corner
//! closing to the last corner opening, and its normal force is the sum over the loaded corners.
//!
//! The driver feeds [`ImpactTracker::step`] after every accepted step, before the contact memory
//! is committed, so that every probe sees the memory (δ̇⁻) the integrator used inside the step.
//! A joint costs one gap evaluation per step while it is open and not in an impact; on a step
//! with an impact under way the tracker samples the step's dense output at a few points, locates
//! onsets and separations by Illinois (modified regula falsi) on the interpolated penetration,
//! and refines the largest normal force and penetration by Brent's parabolic/golden-section
//! search on the interpolant. Probing evaluates the joint's contact law only (no assembly, no
//! commit), so the integration is untouched. Nothing is allocated per step beyond one
//! [`Impact`] per onset.
//!
//! Not tracked: sliders on flexible guides (their onsets are not located), and a contact already
//! closed at t0 (it has no onset; the tracker waits for it to open).

use crate::runtime::body_state;
use crate::system::Model;

/// One impact of a clearance joint, from its located onset to its separation.
///
/// All times are simulation times in s. Located means found on the integrator's dense output
/// (to about machine precision in time for onset and separation, and to about 1e-7 of a sample
/// interval for the extrema), not read from output rows.
#[derive(Debug, Clone, PartialEq)]
pub struct Impact {
    /// Name of the clearance joint.
    pub joint: String,
    /// Onset time, s: the penetration δ crosses 0 upward (first corner closing for a
    /// translational joint).
    pub onset: f64,
    /// Impact velocity, m/s: the penetration rate δ̇⁻ at the onset (> 0 approaching), as
    /// interpolated there, without the contact memory's floor.
    pub impact_velocity: f64,
    /// Largest normal force during the contact, N (summed over the corners of a translational
    /// joint), located on the dense output.
    pub peak_force: f64,
    /// Time of [`Impact::peak_force`], s.
    pub peak_force_time: f64,
    /// Largest penetration during the contact, m (deepest corner of a translational joint),
    /// located on the dense output.
    pub max_penetration: f64,
    /// Time of [`Impact::max_penetration`], s.
    pub max_penetration_time: f64,
    /// Separation time, s (δ crosses 0 downward; last corner opening); `None` when the joint is
    /// still in contact at the end of the run.
    pub separation: Option<f64>,
    /// Contact duration separation − onset, s; `None` with [`Impact::separation`].
    pub duration: Option<f64>,
}

impl Impact {
    fn begin(joint: &str, onset: f64, impact_velocity: f64) -> Self {
        Self {
            joint: joint.to_string(),
            onset,
            impact_velocity,
            peak_force: 0.0,
            peak_force_time: onset,
            max_penetration: 0.0,
            max_penetration_time: onset,
            separation: None,
            duration: None,
        }
    }
}

/// Contact quantities of one joint at one interpolated state.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Probe {
    /// Largest penetration δ over the joint's points, m.
    pen: f64,
    /// δ̇ of that point, m/s.
    rate: f64,
    /// Normal force summed over the active points, N.
    force: f64,
}

impl Probe {
    /// Penetration δ (m), its rate (m/s) and the normal force (N) of one joint.
    pub(crate) fn new(pen: f64, rate: f64, force: f64) -> Self {
        Self { pen, rate, force }
    }
}

/// What the tracker reads from a model, planar ([`Model`]) or spatial
/// ([`SpatialModel`](crate::spatial::SpatialModel)).
pub(crate) trait ContactProbe {
    /// The joints whose impacts are located: (index in the model, name).
    fn tracked(&self) -> Vec<(usize, String)>;
    /// Largest signed penetration δ of joint `k` at y, m (> 0 in contact).
    fn joint_gap(&mut self, k: usize, y: &[f64]) -> f64;
    /// Penetration, rate and normal force of joint `k` at y with the current contact memory,
    /// without assembling or committing anything.
    fn joint_probe(&mut self, k: usize, y: &[f64]) -> Probe;
}

impl ContactProbe for Model {
    fn tracked(&self) -> Vec<(usize, String)> {
        (0..self.clearances.len())
            .filter(|&k| self.clearances[k].event_points() > 0)
            .map(|k| (k, self.clearances[k].name.clone()))
            .collect()
    }
    fn joint_gap(&mut self, k: usize, y: &[f64]) -> f64 {
        Model::joint_gap(self, k, y)
    }
    fn joint_probe(&mut self, k: usize, y: &[f64]) -> Probe {
        Model::joint_probe(self, k, y)
    }
}

/// Sample intervals per step: the step is sampled at SAMPLES + 1 equally spaced times to find
/// crossings and to bracket the extrema (the steps of a resolved contact are short against it).
const SAMPLES: usize = 4;

/// Tracking state of one clearance joint.
struct JointTrack {
    /// Index of the clearance joint in the model.
    clearance: usize,
    /// Its name (copied once, so that probing can borrow the model).
    name: String,
    /// Index in `impacts` of the impact under way.
    open: Option<usize>,
    /// δ at the end of the last step, m.
    last_gap: f64,
}

/// The impacts of one run, built step by step ([module docs](self)).
pub(crate) struct ImpactTracker {
    joints: Vec<JointTrack>,
    impacts: Vec<Impact>,
    /// End of the last accepted step, s.
    t_prev: f64,
}

impl ImpactTracker {
    /// A tracker for the located clearance joints of `model`, starting at (t0, y0).
    pub(crate) fn new(model: &mut impl ContactProbe, t0: f64, y0: &[f64]) -> Self {
        let joints = model
            .tracked()
            .into_iter()
            .map(|(k, name)| JointTrack {
                clearance: k,
                name,
                open: None,
                last_gap: model.joint_gap(k, y0),
            })
            .collect();
        Self {
            joints,
            impacts: Vec::with_capacity(16),
            t_prev: t0,
        }
    }

    /// A tracker of no joint.
    pub(crate) fn empty() -> Self {
        Self {
            joints: Vec::new(),
            impacts: Vec::new(),
            t_prev: 0.0,
        }
    }

    /// The impacts found so far, in onset order.
    pub(crate) fn into_impacts(mut self) -> Vec<Impact> {
        // two joints' onsets in one step were pushed joint by joint
        self.impacts.sort_by(|a, b| a.onset.total_cmp(&b.onset));
        self.impacts
    }

    /// Take the accepted step ending at (tb, yb): `interp(t, out)` is the step's dense output,
    /// `scratch` a buffer of the state's length. Call before the contact memory is committed.
    pub(crate) fn step(
        &mut self,
        model: &mut impl ContactProbe,
        (tb, yb): (f64, &[f64]),
        interp: &dyn Fn(f64, &mut [f64]),
        scratch: &mut [f64],
    ) {
        let ta = self.t_prev;
        self.t_prev = tb;
        #[cfg(test)]
        if brute::tracking_off() {
            return;
        }
        for jt in &mut self.joints {
            let k = jt.clearance;
            let gb = model.joint_gap(k, yb);
            let closing = jt.last_gap <= 0.0 && gb > 0.0;
            jt.last_gap = gb;
            if jt.open.is_none() && !closing || tb <= ta {
                continue;
            }
            let mut probe = |t: f64| {
                interp(t, scratch);
                model.joint_probe(k, scratch)
            };
            track_joint(jt, &mut self.impacts, (ta, tb), &mut probe);
        }
    }
}

/// Samples of one step: times and probes at SAMPLES + 1 equally spaced times over [ta, tb].
struct StepSamples {
    t: [f64; SAMPLES + 1],
    p: [Probe; SAMPLES + 1],
}

impl StepSamples {
    fn take(ta: f64, tb: f64, f: &mut impl FnMut(f64) -> Probe) -> Self {
        let mut s = Self {
            t: [0.0; SAMPLES + 1],
            p: [Probe::default(); SAMPLES + 1],
        };
        for i in 0..=SAMPLES {
            // the last sample exactly at tb: the step end is a sample of the next step too
            s.t[i] = if i == SAMPLES {
                tb
            } else {
                ta + (tb - ta) * i as f64 / SAMPLES as f64
            };
            s.p[i] = f(s.t[i]);
        }
        s
    }
}

/// A contact interval inside one step: from `lo` (onset or step start, s) with the samples
/// `first..end` inside it, to `hi` (separation or step end, s).
#[derive(Clone, Copy)]
struct Segment {
    lo: f64,
    first: usize,
    end: usize,
    hi: f64,
}

/// Update the impacts of joint `jt` over the step [ta, tb] (`f`: probe at a time in it).
fn track_joint(
    jt: &mut JointTrack,
    impacts: &mut Vec<Impact>,
    (ta, tb): (f64, f64),
    f: &mut impl FnMut(f64) -> Probe,
) {
    let s = StepSamples::take(ta, tb, f);
    let (mut lo, mut first) = (ta, 0);
    for i in 0..=SAMPLES {
        let inside = s.p[i].pen > 0.0;
        match jt.open {
            // a contact already closed at the step start without an onset (closed at t0) is
            // not an impact: only a crossing inside the step opens one
            None if inside && i > 0 && s.p[i - 1].pen <= 0.0 => {
                let (t_on, p) = crossing(f, (s.t[i - 1], s.p[i - 1]), (s.t[i], s.p[i]));
                impacts.push(Impact::begin(&jt.name, t_on, p.rate));
                jt.open = Some(impacts.len() - 1);
                (lo, first) = (t_on, i);
            }
            // an onset located at the end of the last step can read δ ≤ 0 (by rounding) at
            // the start of this one, whose dense output is another interpolant: when the next
            // sample is inside again the contact did not end there (it would leave an impact
            // of zero duration and zero force followed by the real one)
            Some(_) if !inside && i == 0 && s.p[1].pen > 0.0 => {}
            Some(idx) if !inside => {
                let hi = if i == 0 {
                    ta
                } else {
                    crossing(f, (s.t[i - 1], s.p[i - 1]), (s.t[i], s.p[i])).0
                };
                let seg = Segment {
                    lo,
                    first,
                    end: i,
                    hi,
                };
                refine(&mut impacts[idx], f, &s, seg);
                let imp = &mut impacts[idx];
                imp.separation = Some(hi);
                imp.duration = Some(hi - imp.onset);
                jt.open = None;
            }
            _ => {}
        }
    }
    if let Some(idx) = jt.open {
        let seg = Segment {
            lo,
            first,
            end: SAMPLES + 1,
            hi: tb,
        };
        refine(&mut impacts[idx], f, &s, seg);
    }
}

/// Fold the located extrema of the contact interval `seg` into the impact.
fn refine(imp: &mut Impact, f: &mut impl FnMut(f64) -> Probe, s: &StepSamples, seg: Segment) {
    let best = (imp.peak_force_time, imp.peak_force);
    (imp.peak_force_time, imp.peak_force) = locate_max(f, |p| p.force, s, seg, best);
    let best = (imp.max_penetration_time, imp.max_penetration);
    (imp.max_penetration_time, imp.max_penetration) = locate_max(f, |p| p.pen, s, seg, best);
    #[cfg(test)]
    brute::record(imp, f, seg);
}

/// The larger of `best` (t, value) and the maximum of `key` over `seg`, located by Brent's
/// search around the largest sample. Samples clearly below `best` (the decay after the peak)
/// cost nothing more.
fn locate_max(
    f: &mut impl FnMut(f64) -> Probe,
    key: fn(&Probe) -> f64,
    s: &StepSamples,
    seg: Segment,
    best: (f64, f64),
) -> (f64, f64) {
    let arg = (seg.first..seg.end).max_by(|&a, &b| key(&s.p[a]).total_cmp(&key(&s.p[b])));
    let Some(j) = arg else {
        // onset and separation in one sample interval: no sample inside, search it all
        let x0 = 0.5 * (seg.lo + seg.hi);
        let v0 = key(&f(x0));
        let found = brent_max(&mut |t| key(&f(t)), (seg.lo, seg.hi), (x0, v0));
        return if found.1 > best.1 { found } else { best };
    };
    let (tj, vj) = (s.t[j], key(&s.p[j]));
    if vj < best.1 - 1e-3 * best.1.abs() {
        return best;
    }
    let left = if j > seg.first { s.t[j - 1] } else { seg.lo };
    let right = if j + 1 < seg.end { s.t[j + 1] } else { seg.hi };
    let found = if left == tj || right == tj {
        boundary_max(f, key, (left, right), (tj, vj))
    } else {
        brent_max(&mut |t| key(&f(t)), (left, right), (tj, vj))
    };
    if found.1 > best.1 {
        found
    } else {
        best
    }
}

/// The maximum near a sample that is also a step boundary (the contact goes on into the
/// neighbouring step): the sample itself when the value falls just inside the step (the next
/// or previous step covers the other side), otherwise Brent's search over the bracket.
fn boundary_max(
    f: &mut impl FnMut(f64) -> Probe,
    key: fn(&Probe) -> f64,
    (left, right): (f64, f64),
    (tj, vj): (f64, f64),
) -> (f64, f64) {
    let inner = if right == tj {
        tj - 1e-3 * (tj - left)
    } else {
        tj + 1e-3 * (right - tj)
    };
    if key(&f(inner)) <= vj {
        return (tj, vj);
    }
    brent_max(&mut |t| key(&f(t)), (left, right), (tj, vj))
}

/// The time (s) where δ crosses 0 between `a` and `b` (δ on opposite sides), with the probe on
/// the contact side (δ > 0): Illinois iteration down to the resolution of t (as clr-ode
/// locates events).
fn crossing(f: &mut impl FnMut(f64) -> Probe, a: (f64, Probe), b: (f64, Probe)) -> (f64, Probe) {
    // orient: `o` out of contact (δ ≤ 0), `c` in contact
    let (mut o, mut c) = if a.1.pen > 0.0 { (b, a) } else { (a, b) };
    let (mut go, mut gc) = (o.1.pen, c.1.pen);
    let mut side = 0i32;
    for _ in 0..200 {
        let tol = 4.0 * f64::EPSILON * o.0.abs().max(c.0.abs()) + f64::MIN_POSITIVE;
        if (c.0 - o.0).abs() <= tol {
            break;
        }
        let mut tm = (o.0 * gc - c.0 * go) / (gc - go);
        let (lo, hi) = (o.0.min(c.0), o.0.max(c.0));
        if !(tm > lo && tm < hi) {
            tm = 0.5 * (lo + hi);
        }
        let pm = f(tm);
        if pm.pen > 0.0 {
            (c, gc) = ((tm, pm), pm.pen);
            if side == 1 {
                go *= 0.5;
            }
            side = 1;
        } else {
            (o, go) = ((tm, pm), pm.pen);
            if side == -1 {
                gc *= 0.5;
            }
            side = -1;
        }
    }
    c
}

/// Maximum of g on [a, b] by Brent's method (Brent, *Algorithms for Minimization without
/// Derivatives*, 1973, ch. 5, `localmin`: parabolic steps safeguarded by golden sections),
/// started from the known point (x0, g(x0)); x to 1e-7 of b − a (the value then to far below
/// 1e-9 relative at a smooth maximum). Returns (t, g(t)) of the best point.
fn brent_max(
    g: &mut impl FnMut(f64) -> f64,
    (mut a, mut b): (f64, f64),
    x0: (f64, f64),
) -> (f64, f64) {
    const C: f64 = 0.381_966_011_250_105_1; // (3 − √5)/2
    let abs_tol = 1e-7 * (b - a) + 4.0 * f64::EPSILON * a.abs().max(b.abs());
    // minimize −g
    let (mut x, mut w, mut v) = (x0.0, x0.0, x0.0);
    let (mut fx, mut fw, mut fv) = (-x0.1, -x0.1, -x0.1);
    let (mut d, mut e) = (0.0f64, 0.0f64);
    for _ in 0..100 {
        let m = 0.5 * (a + b);
        let tol = abs_tol;
        let t2 = 2.0 * tol;
        if (x - m).abs() <= t2 - 0.5 * (b - a) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol {
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            let r = e;
            e = d;
            if p.abs() < (0.5 * q * r).abs() && p > q * (a - x) && p < q * (b - x) {
                d = p / q;
                let u = x + d;
                if u - a < t2 || b - u < t2 {
                    d = if x < m { tol } else { -tol };
                }
                golden = false;
            }
        }
        if golden {
            e = if x < m { b - x } else { a - x };
            d = C * e;
        }
        let u = x + if d.abs() >= tol { d } else { tol.copysign(d) };
        let fu = -g(u);
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    (x, -fx)
}

impl Model {
    /// Largest signed penetration δ over the points of clearance joint `k` at y, m (> 0 in
    /// contact).
    pub(crate) fn joint_gap(&mut self, k: usize, y: &[f64]) -> f64 {
        let (q, qd) = y[..2 * self.n].split_at(self.n);
        self.refresh_face(k, q, qd);
        let cl = &self.clearances[k];
        let bi = body_state(&self.frames, cl.i, q, qd);
        let bj = body_state(&self.frames, cl.j, q, qd);
        (0..cl.event_points()).fold(f64::NEG_INFINITY, |g, p| g.max(cl.gap(&bi, &bj, p).0))
    }

    /// Penetration, its rate and the normal force of clearance joint `k` at y with the contact
    /// memory of the current step (as the `C.*` columns), without assembling or committing
    /// anything: tentative onset values are cleared by the commit that follows.
    pub(crate) fn joint_probe(&mut self, k: usize, y: &[f64]) -> Probe {
        let (q, qd) = y[..2 * self.n].split_at(self.n);
        let bi = body_state(&self.frames, self.clearances[k].i, q, qd);
        let bj = body_state(&self.frames, self.clearances[k].j, q, qd);
        let rep = match self.clearances[k].flex_beam() {
            // a beam-face pair loads the beam: into a scratch copy of the force workspace
            Some(b) => {
                let mut qf = std::mem::take(&mut self.qf);
                let guide = crate::system::guide_ref(&self.beams, &self.floating, b);
                let cl = &mut self.clearances[k];
                let rep = cl.apply_flex(guide, q, qd, &bj, &mut self.memory, &mut qf, |_, _| {});
                self.qf = qf;
                rep
            }
            // LuGre joints carry a frictionless `friction`: the normal force is the same
            None => self.clearances[k].apply(&bi, &bj, &mut self.memory, |_, _| {}),
        };
        Probe {
            pen: rep.penetration,
            rate: rep.penetration_rate,
            force: rep.normal_force,
        }
    }
}

/// Test hook: a brute-force search of every tracked contact interval on the dense output,
/// independent of the located extrema (`brute::enable(samples)` on the test's thread).
#[cfg(test)]
pub(crate) mod brute {
    use std::cell::{Cell, RefCell};

    use super::{Impact, Probe, Segment};

    /// The brute-force maxima of one impact.
    #[derive(Debug, Clone)]
    pub(crate) struct Found {
        pub(crate) joint: String,
        pub(crate) onset: f64,
        /// (t s, largest normal force N).
        pub(crate) force: (f64, f64),
        /// (t s, largest penetration m).
        pub(crate) penetration: (f64, f64),
    }

    thread_local! {
        static OFF: Cell<bool> = const { Cell::new(false) };
        static SAMPLES: Cell<usize> = const { Cell::new(0) };
        static FOUND: RefCell<Vec<Found>> = const { RefCell::new(Vec::new()) };
    }

    /// Switch the tracker off (to compare a run with and without it).
    pub(crate) fn set_tracking_off(off: bool) {
        OFF.with(|o| o.set(off));
    }

    pub(super) fn tracking_off() -> bool {
        OFF.with(Cell::get)
    }

    /// Sample every contact interval at `samples` + 1 equally spaced times from now on.
    pub(crate) fn enable(samples: usize) {
        SAMPLES.with(|s| s.set(samples));
        FOUND.with(|f| f.borrow_mut().clear());
    }

    /// The maxima found per impact, in onset order per joint.
    pub(crate) fn found() -> Vec<Found> {
        FOUND.with(|f| f.borrow().clone())
    }

    pub(super) fn record(imp: &Impact, f: &mut impl FnMut(f64) -> Probe, seg: Segment) {
        let n = SAMPLES.with(Cell::get);
        if n == 0 || seg.hi <= seg.lo {
            return;
        }
        FOUND.with(|found| {
            let mut found = found.borrow_mut();
            let pos = found
                .iter()
                .position(|e| e.joint == imp.joint && e.onset == imp.onset);
            let k = pos.unwrap_or_else(|| {
                found.push(Found {
                    joint: imp.joint.clone(),
                    onset: imp.onset,
                    force: (imp.onset, f64::NEG_INFINITY),
                    penetration: (imp.onset, f64::NEG_INFINITY),
                });
                found.len() - 1
            });
            let e = &mut found[k];
            for i in 0..=n {
                let t = seg.lo + (seg.hi - seg.lo) * i as f64 / n as f64;
                let p = f(t);
                if p.force > e.force.1 {
                    e.force = (t, p.force);
                }
                if p.pen > e.penetration.1 {
                    e.penetration = (t, p.pen);
                }
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use clr_contact::{DampingFactor, ElasticLaw, FrictionLaw, NormalLaw};

    use super::brute;
    use crate::{Impact, ModelBuilder, RigidBody, SimOptions, SolverKind};

    /// Bearing and journal radii (m) of the closed-form tests: radial clearance c = 0.1 mm.
    const R_B: f64 = 0.010;
    const R_J: f64 = 0.0099;
    const V0: f64 = 0.5;

    /// A free 1 kg journal (no gravity) starting at the centre of a ground-fixed bearing and
    /// moving radially at V0 along x: one impact on the bearing wall at t = c / V0, then it
    /// crosses back (the next impact comes after `t_end`).
    fn single_impact(normal: NormalLaw, t_end: f64) -> Vec<Impact> {
        let mut b = ModelBuilder::new();
        b.body("journal", RigidBody::new(1.0, 1e-4).moving(V0, 0.0, 0.0))
            .revolute_clearance(
                "gap",
                ("ground", [0.0, 0.0]),
                ("journal", [0.0, 0.0]),
                crate::RevoluteClearanceSpec {
                    bearing_radius: R_B,
                    journal_radius: R_J,
                    normal: normal.into(),
                    friction: FrictionLaw::coulomb(0.0, 1.0).unwrap().into(),
                },
            );
        let mut model = b.build().unwrap();
        let opts = SimOptions::span(0.0, t_end, 10)
            .tolerances(1e-12, 1e-15)
            .solver(SolverKind::Dopri5);
        let res = model.simulate(&opts).unwrap();
        assert_eq!(res.impacts.len(), 1, "{:?}", res.impacts);
        res.impacts
    }

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    /// Linear law F = K δ without damping: the contact is half a period of an undamped
    /// oscillator, so onset c/v0, impact velocity v0, δ_max = v0 √(m/K), peak force K δ_max and
    /// duration π √(m/K) (closed form). Tolerances: 1e-6 relative on onset, velocity, δ_max and
    /// peak force, 1e-4 on the duration.
    #[test]
    fn linear_impact_is_half_an_undamped_oscillation() {
        let k = 1e7;
        let law = NormalLaw::new(ElasticLaw::linear(k).unwrap(), DampingFactor::None, 1.0).unwrap();
        let imp = &single_impact(law, 1.5e-3)[0];
        let w = (k / 1.0f64).sqrt();
        let d_max = V0 / w;
        let errs = [
            rel(imp.onset, (R_B - R_J) / V0),
            rel(imp.impact_velocity, V0),
            rel(imp.max_penetration, d_max),
            rel(imp.peak_force, k * d_max),
        ];
        let e_dur = rel(imp.duration.unwrap(), std::f64::consts::PI / w);
        eprintln!(
            "linear: errors onset, v, δ_max, F_max {:?}, duration {e_dur:.2e}",
            errs.map(|e| format!("{e:.1e}"))
        );
        assert!(errs.iter().all(|&e| e < 1e-6), "{errs:?} {imp:?}");
        assert!(e_dur < 1e-4, "{e_dur} {imp:?}");
        // the extrema at the middle of the contact
        let mid = imp.onset + 0.5 * std::f64::consts::PI / w;
        assert!(rel(imp.max_penetration_time, mid) < 1e-6);
        assert!(rel(imp.peak_force_time, mid) < 1e-6);
    }

    /// Hertz law F = K δ^1.5 without damping (c_e = 1): δ_max = (5 m v0² / (4K))^(2/5) and the
    /// duration 2 (δ_max / v0) ∫₀¹ (1 − x^{5/2})^{−1/2} dx = 2.943275 δ_max / v0 (energy
    /// integral; Johnson, Contact Mechanics, 1985, §11.4, eq. 11.24 quotes 2.94; the constant
    /// is 2·(2/5)·B(2/5, 1/2) = 0.8 Γ(0.4) Γ(0.5) / Γ(0.9)). Tolerances: 1e-6 relative on onset,
    /// velocity, δ_max and peak force, 1e-4 on the duration.
    #[test]
    fn hertz_impact_matches_the_closed_form() {
        let k = 1e9;
        let law = NormalLaw::new(ElasticLaw::hertz(k).unwrap(), DampingFactor::None, 1.0).unwrap();
        let imp = &single_impact(law, 1.5e-3)[0];
        let d_max = (5.0 * 1.0 * V0 * V0 / (4.0 * k)).powf(0.4);
        let errs = [
            rel(imp.onset, (R_B - R_J) / V0),
            rel(imp.impact_velocity, V0),
            rel(imp.max_penetration, d_max),
            rel(imp.peak_force, k * d_max.powf(1.5)),
        ];
        let e_dur = rel(imp.duration.unwrap(), 2.943_275_184_324_705 * d_max / V0);
        eprintln!(
            "hertz: errors onset, v, δ_max, F_max {:?}, duration {e_dur:.2e}",
            errs.map(|e| format!("{e:.1e}"))
        );
        assert!(errs.iter().all(|&e| e < 1e-6), "{errs:?} {imp:?}");
        assert!(e_dur < 1e-4, "{e_dur} {imp:?}");
    }

    /// The clearance slider–crank of models/slider_crank.toml over its first 0.03 s.
    fn slider_crank() -> (crate::Model, SimOptions) {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../models/slider_crank.toml"
        );
        let text = std::fs::read_to_string(path).unwrap();
        let desc = crate::ModelDesc::from_toml_table(toml::from_str(&text).unwrap()).unwrap();
        let mut opts = desc.sim_options().unwrap();
        opts.t_end = 0.03;
        (desc.compile().unwrap(), opts)
    }

    /// On the clearance slider–crank: every located peak force and penetration is ≥ every row
    /// value of its contact (rows at every step, 1e-12 relative for the step-end rows, which
    /// come from the step's end state rather than its interpolant) and within 1e-9 relative of
    /// a brute-force search of 10 000 samples of the dense output over each contact interval
    /// of each step; every row in contact lies inside an impact.
    #[test]
    fn located_extrema_bound_the_rows_and_match_a_brute_force_search() {
        let (mut model, opts) = slider_crank();
        brute::enable(10_000);
        let res = model.simulate(&opts).unwrap();
        let found = brute::found();
        brute::enable(0);
        assert!(res.impacts.len() >= 3, "{} impacts", res.impacts.len());
        let (t, f, p) = (
            res.column("t").unwrap(),
            res.column("B.normal_force").unwrap(),
            res.column("B.penetration").unwrap(),
        );
        for k in 0..t.len() {
            if p[k] <= 0.0 {
                continue;
            }
            let imp = res
                .impacts
                .iter()
                .find(|i| i.onset <= t[k] && i.separation.is_none_or(|s| t[k] <= s))
                .unwrap_or_else(|| panic!("row t = {} in contact outside every impact", t[k]));
            assert!(f[k] <= imp.peak_force * (1.0 + 1e-12), "{} > {imp:?}", f[k]);
            assert!(
                p[k] <= imp.max_penetration * (1.0 + 1e-12),
                "{} > {imp:?}",
                p[k]
            );
        }
        let (mut worst_f, mut worst_p) = (0.0f64, 0.0f64);
        for imp in &res.impacts {
            let b = found.iter().find(|b| b.onset == imp.onset).unwrap();
            worst_f = worst_f.max(rel(imp.peak_force, b.force.1));
            worst_p = worst_p.max(rel(imp.max_penetration, b.penetration.1));
            assert!(imp.peak_force >= b.force.1 * (1.0 - 1e-12), "{imp:?} {b:?}");
            assert!(
                imp.max_penetration >= b.penetration.1 * (1.0 - 1e-12),
                "{imp:?} {b:?}"
            );
        }
        eprintln!(
            "{} impacts; largest relative difference to brute force: force {worst_f:.2e}, \
             penetration {worst_p:.2e}",
            res.impacts.len()
        );
        assert!(worst_f < 1e-9 && worst_p < 1e-9);
    }

    /// The tracker only reads the dense output: the recorded columns are bit for bit those of
    /// the same run without it.
    #[test]
    fn tracking_impacts_leaves_the_integration_untouched() {
        let (mut model, opts) = slider_crank();
        let with = model.simulate(&opts).unwrap();
        brute::set_tracking_off(true);
        let without = model.simulate(&opts).unwrap();
        brute::set_tracking_off(false);
        assert!(!with.impacts.is_empty() && without.impacts.is_empty());
        assert_eq!(with.data.len(), without.data.len());
        assert!(with
            .data
            .iter()
            .zip(&without.data)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        assert_eq!(with.stats, without.stats);
    }
}
