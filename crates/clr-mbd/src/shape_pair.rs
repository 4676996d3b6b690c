//! Runtime form of a shape contact pair (`[[clearance]] type = "contact"`): two placed shapes
//! ([`PlacedShape`], the compiled form of a `[[shape]]`), a broad phase on their bounding circles
//! (also tested for every pair at once by the model's
//! [`BroadPhase`](crate::broad_phase::BroadPhase)) and boxes, parry's contact points reduced to one point per contact patch, a
//! stable slot per point for the contact memory, and the step bound that keeps the shapes from
//! passing through each other within a step ([`ShapePair::max_step`]).
//!
//! * **Reduction.** A smooth body pressed into a fine polyline touches several segments, each
//!   with its own point; summing a law over them would count one contact several times. Points
//!   are taken deepest first and a point is dropped when a kept point lies within the merge
//!   distance with a normal within 37° (cos > 0.8: the two sides of a corner stay separate).
//!   Then at most `max_points` points are kept.
//! * **Slots.** Each kept point gets one of `max_points` memory slots: the slot whose point at
//!   the last accepted step lies nearest (on either body, within the match distance) with a
//!   normal within 37°, else a free slot. A contact that slides or rolls keeps its slot and its impact velocity δ̇⁻; the
//!   assignment depends only on the committed keys and the state, as the memory rules need.
//! * **Forces.** At each point with δ > 0: F_N from the normal law with the slot's δ̇⁻, F_T
//!   from the friction law with the slip v_T; f = F_N n + F_T t on B at its contact point and
//!   −f on A at its own (the two points are δ apart along n, so the pair has no moment). With
//!   v = ṙ_B(p_B) − ṙ_A(p_A): δ̇ = −v·n, v_T = v·t, t = k̂ × n. δ̇ is the exact rate of the
//!   signed distance (its first variation with the closest points held, the envelope theorem),
//!   so the pair's power is −F_N δ̇ + F_T v_T and the energy balance closes.

use std::cell::RefCell;

use clr_contact::{
    boxes_gap, boxes_overlap, contact_points, shape_distance, BodyState, ContactMemory,
    ContactShape, FrictionLaw, NormalLaw, ShapeContactPoint, ShapeContactWorkspace,
};
use nalgebra::Vector2;

use crate::contact_report::ContactReport;
use crate::runtime::{cross, perp, GROUND_ID};

/// A compiled shape: the frame it moves with, its origin (arm from the frame's reference point)
/// and angle there, and the parry shape built once.
#[derive(Debug, Clone)]
pub(crate) struct PlacedShape {
    pub(crate) frame: usize,
    pub(crate) arm: Vector2<f64>,
    pub(crate) angle: f64,
    pub(crate) shape: ContactShape,
    /// The spacing of the shape's own discretization, m: the longest polyline segment, the
    /// median flank chord of a gear, 0 for exact shapes (the default merge distance is twice
    /// the larger of a pair's two: one smooth contact drawn as chords is one patch).
    pub(crate) chord: f64,
}

/// One side of a pair: the placed shape.
pub(crate) struct Side {
    /// Origin of the shape frame from the frame's reference point, m (frame coordinates).
    pub(crate) arm: Vector2<f64>,
    /// Angle of the shape frame in the body frame, rad.
    pub(crate) angle: f64,
    pub(crate) shape: ContactShape,
    /// Radius of a circle about the shape origin holding the shape, m.
    pub(crate) radius: f64,
    /// Distance from the frame's reference point to the farthest point of the shape, m.
    pub(crate) reach: f64,
    /// The shape origin in the world when the shape is on the ground (it never moves).
    pub(crate) fixed: Option<Vector2<f64>>,
}

impl Side {
    pub(crate) fn new(p: &PlacedShape) -> Self {
        let radius = p.shape.bounding_radius();
        Self {
            arm: p.arm,
            angle: p.angle,
            shape: p.shape.clone(),
            radius,
            reach: p.arm.norm() + radius,
            fixed: (p.frame == GROUND_ID).then_some(p.arm),
        }
    }

    /// A circle holding the shape for the body at `b`, (centre, radius) in m: about the frame's
    /// reference point (no trigonometry), or the shape's own circle on the ground.
    fn circle(&self, b: &BodyState) -> (Vector2<f64>, f64) {
        match self.fixed {
            Some(c) => (c, self.radius),
            None => (b.position, self.reach),
        }
    }

    /// Pose of the shape frame (position and angle only) for the body at `b`.
    fn pose(&self, b: &BodyState) -> BodyState {
        BodyState::fixed(b.point(self.arm), b.angle + self.angle)
    }
}

/// Tuning of a pair, m (documented on the model-file element).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairSettings {
    /// Points within this gap are reported (δ ≤ 0) so that their slot and last (δ, δ̇) are
    /// known before they touch.
    pub(crate) prediction: f64,
    /// Points of one patch closer than this are merged.
    pub(crate) merge: f64,
    /// A point keeps its slot when it moved less than this since the last accepted step.
    pub(crate) matching: f64,
    /// Memory slots, the most points kept.
    pub(crate) max_points: usize,
}

/// A kept contact point and its memory slot (planar by default; the spatial shape contact keeps
/// clr-contact's `ShapeContactPoint3`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Kept<P = ShapeContactPoint> {
    pub(crate) point: P,
    pub(crate) slot: usize,
}

/// What the reduction and the slot assignment read of a contact point, in the plane or in space
/// (the rules are the same: [`reduce`], [`assign_slots`]).
pub(crate) trait PatchPoint: Copy {
    /// Penetration δ, m.
    fn depth(&self) -> f64;
    /// Distance between the two points on A (m) and the cosine between their normals.
    fn nearness(&self, other: &Self) -> (f64, f64);
}

impl PatchPoint for ShapeContactPoint {
    fn depth(&self) -> f64 {
        self.depth
    }
    fn nearness(&self, other: &Self) -> (f64, f64) {
        (
            (self.point_a - other.point_a).norm(),
            self.normal.dot(&other.normal),
        )
    }
}

impl PatchPoint for clr_contact::ShapeContactPoint3 {
    fn depth(&self) -> f64 {
        self.depth
    }
    fn nearness(&self, other: &Self) -> (f64, f64) {
        (
            (self.point_a - other.point_a).norm(),
            self.normal.dot(&other.normal),
        )
    }
}

/// A slot key, in the plane ([`SlotKey`]) or in space: where the slot's point was on A and on
/// B and its normal in A's frame.
pub(crate) trait Key: Copy {
    /// The smaller of the distances between the points on A and on B (m), and the cosine
    /// between the normals.
    fn nearness(&self, other: &Self) -> (f64, f64);
}

impl Key for SlotKey {
    fn nearness(&self, other: &Self) -> (f64, f64) {
        let ([la, lb, n], [ka, kb, kn]) = (self, other);
        ((la - ka).norm().min((lb - kb).norm()), n.dot(kn))
    }
}

impl Key for [nalgebra::Vector3<f64>; 3] {
    fn nearness(&self, other: &Self) -> (f64, f64) {
        let ([la, lb, n], [ka, kb, kn]) = (self, other);
        ((la - ka).norm().min((lb - kb).norm()), n.dot(kn))
    }
}

/// Reusable buffers of one detection (interior mutability: detection runs where the model is
/// borrowed immutably, e.g. event functions; the model is used by one thread at a time).
#[derive(Default)]
struct Scratch {
    ws: ShapeContactWorkspace,
    kept: Vec<Kept>,
    taken: Vec<bool>,
}

/// A shape contact pair: shape A on frame `i`, shape B on frame `j` of the clearance.
pub(crate) struct ShapePair {
    pub(crate) a: Side,
    pub(crate) b: Side,
    pub(crate) settings: PairSettings,
    scratch: RefCell<Scratch>,
    /// Body-local contact points (on A's frame, on B's frame) of each slot at the last accepted
    /// step, `None` for a free slot.
    keys: Vec<Option<SlotKey>>,
    /// The last commit found the pair apart (every slot separated, no key).
    committed_apart: bool,
}

impl ShapePair {
    pub(crate) fn new(a: &PlacedShape, b: &PlacedShape, settings: PairSettings) -> Self {
        Self {
            a: Side::new(a),
            b: Side::new(b),
            settings,
            scratch: RefCell::new(Scratch {
                kept: Vec::with_capacity(settings.max_points),
                taken: vec![false; settings.max_points],
                ..Default::default()
            }),
            keys: vec![None; settings.max_points],
            committed_apart: false,
        }
    }

    /// Refuse a pair parry has no contact query for (one query at the shapes' origins).
    pub(crate) fn check_query(&self) -> Result<(), clr_contact::ContactError> {
        let origin = BodyState::default();
        let mut ws = ShapeContactWorkspace::new();
        contact_points(&self.a.shape, &origin, &self.b.shape, &origin, 0.0, &mut ws).map(|_| ())
    }

    /// Detect, reduce and assign slots at the bodies' states; `f` reads the kept points.
    pub(crate) fn with_points<R>(
        &self,
        bi: &BodyState,
        bj: &BodyState,
        f: impl FnOnce(&[Kept]) -> R,
    ) -> R {
        let mut s = self.scratch.borrow_mut();
        self.detect(bi, bj, &mut s);
        f(&s.kept)
    }

    fn detect(&self, bi: &BodyState, bj: &BodyState, s: &mut Scratch) {
        let Scratch { ws, kept, taken } = s;
        kept.clear();
        let margin = self.settings.prediction;
        // broad phase: bounding circles (no trigonometry), then boxes, so that a pair far
        // apart costs next to nothing
        if self.circle_gap(bi, bj) > margin {
            return;
        }
        let (pa, pb) = (self.a.pose(bi), self.b.pose(bj));
        if !boxes_overlap(&self.a.shape.aabb(&pa), &self.b.shape.aabb(&pb), margin) {
            return;
        }
        // a pose with NaN (a failed step) gives no contact; the integrator rejects that step
        let Ok(points) = contact_points(&self.a.shape, &pa, &self.b.shape, &pb, margin, ws) else {
            return;
        };
        reduce(points, &self.settings, kept);
        self.assign_slots(bi, bj, kept, taken);
    }

    fn assign_slots(&self, bi: &BodyState, bj: &BodyState, kept: &mut [Kept], taken: &mut [bool]) {
        let local = |p: &ShapeContactPoint| key(bi, bj, p);
        assign_slots(&self.keys, self.settings.matching, kept, taken, local);
    }

    /// Gap between the two bounding circles, m: a lower bound of the shapes' distance.
    fn circle_gap(&self, bi: &BodyState, bj: &BodyState) -> f64 {
        let (ca, ra) = self.a.circle(bi);
        let (cb, rb) = self.b.circle(bj);
        (cb - ca).norm() - ra - rb
    }

    /// The pair's event function: the largest signed penetration, m (−prediction when nothing
    /// lies within the prediction distance, continuous with the reported points).
    pub(crate) fn max_depth(&self, bi: &BodyState, bj: &BodyState) -> f64 {
        let floor = -self.settings.prediction;
        self.with_points(bi, bj, |kept| {
            kept.iter().fold(floor, |g, k| g.max(k.point.depth))
        })
    }

    /// Add the forces of the penetrating points through `add(frame side, [f_x, f_y, m])`
    /// (side 0 = A on frame i, 1 = B on frame j) and fill the report.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn apply(
        &self,
        [bi, bj]: [&BodyState; 2],
        (normal, friction): (&NormalLaw, &FrictionLaw),
        mem: usize,
        memory: &mut ContactMemory,
        rep: &mut ContactReport,
        mut add: impl FnMut(usize, [f64; 3]),
    ) {
        let floor = -self.settings.prediction;
        rep.penetration = floor;
        rep.eccentricity = [0.0, 0.0];
        self.with_points(bi, bj, |kept| {
            for k in kept {
                let p = &k.point;
                let rates = rates(p, bi, bj);
                if let Some(f) = point_force(k, rates, (normal, friction), (mem, memory), rep) {
                    add(0, [-f.x, -f.y, cross(p.point_a - bi.position, -f)]);
                    add(1, [f.x, f.y, cross(p.point_b - bj.position, f)]);
                }
            }
        });
    }

    /// Commit the memory at an accepted state: each kept point's (δ, δ̇) into its slot and its
    /// body-local points as the slot's key; free slots as separated (δ = −1 m marker, δ̇ = 0).
    pub(crate) fn commit(
        &mut self,
        bi: &BodyState,
        bj: &BodyState,
        mem: usize,
        memory: &mut ContactMemory,
    ) {
        self.committed_apart = false;
        {
            // detected with the previous keys, which are replaced below
            let mut s = self.scratch.borrow_mut();
            self.detect(bi, bj, &mut s);
            let Scratch { kept, taken, .. } = &mut *s;
            taken.fill(false);
            for k in kept.iter() {
                let (vn, _) = rates(&k.point, bi, bj);
                memory.commit(mem + k.slot, k.point.depth, vn);
                taken[k.slot] = true;
            }
            for (slot, _) in taken.iter().enumerate().filter(|(_, t)| !**t) {
                memory.commit(mem + slot, -1.0, 0.0);
            }
        }
        self.keys.iter_mut().for_each(|k| *k = None);
        for k in &self.scratch.get_mut().kept {
            self.keys[k.slot] = Some(key(bi, bj, &k.point));
        }
    }

    /// The longest next step that cannot carry the shapes through each other, s: with the gap
    /// d between them (the boxes' gap when the boxes are apart, parry's distance otherwise),
    /// every point of a shape moves by at most v·h + a·h²/2 relative to the other, where v and a
    /// bound the relative speed and acceleration of any point (reference points plus ω·R and
    /// (|α| + ω²)·R with R the reach of each shape from its frame's reference point), so
    /// h = 2D/(v + √(v² + 2aD)) with D = d + prediction/2 lets them close the gap and penetrate
    /// by at most half the prediction distance within a step — conservative advancement
    /// (Mirtich, *Impulse-based dynamic simulation of rigid body systems*, PhD thesis, UC
    /// Berkeley, 1996, §3.3). `acc` holds each frame's (acceleration, angular acceleration).
    /// Unbounded while they touch: then the error control follows the contact.
    pub(crate) fn max_step(&self, [bi, bj]: [&BodyState; 2], acc: [(Vector2<f64>, f64); 2]) -> f64 {
        // lower bounds of the distance first: circles, then boxes, then parry's distance
        let mut gap = self.circle_gap(bi, bj);
        if gap <= 0.0 {
            let (pa, pb) = (self.a.pose(bi), self.b.pose(bj));
            let (ba, bb) = (self.a.shape.aabb(&pa), self.b.shape.aabb(&pb));
            gap = if boxes_overlap(&ba, &bb, 0.0) {
                shape_distance(&self.a.shape, &pa, &self.b.shape, &pb).unwrap_or(0.0)
            } else {
                boxes_gap(&ba, &bb)
            };
        }
        if gap <= 0.0 {
            return f64::INFINITY;
        }
        let d = gap + 0.5 * self.settings.prediction;
        let (ra, rb) = (self.a.reach, self.b.reach);
        let (wi, wj) = (bi.angular_velocity, bj.angular_velocity);
        let v = (bj.velocity - bi.velocity).norm() + wi.abs() * ra + wj.abs() * rb;
        let a = (acc[1].0 - acc[0].0).norm()
            + (acc[0].1.abs() + wi * wi) * ra
            + (acc[1].1.abs() + wj * wj) * rb;
        2.0 * d / (v + (v * v + 2.0 * a * d).sqrt())
    }

    /// Commit a pair known to be apart (the broad phase): every slot separated.
    pub(crate) fn commit_apart(&mut self, mem: usize, memory: &mut ContactMemory) {
        // committing (−1, 0) again would change nothing: a pair that stays apart costs nothing
        if self.committed_apart {
            return;
        }
        for (slot, key) in self.keys.iter_mut().enumerate() {
            memory.commit(mem + slot, -1.0, 0.0);
            *key = None;
        }
        self.committed_apart = true;
    }

    /// The report of a pair with no point within the prediction distance.
    pub(crate) fn apart_report(&self) -> ContactReport {
        ContactReport {
            penetration: -self.settings.prediction,
            ..Default::default()
        }
    }

    /// Elastic energy ∫F_e dδ over the penetrating points at the bodies' states, J.
    pub(crate) fn elastic_energy(
        &self,
        bi: &BodyState,
        bj: &BodyState,
        law: impl Fn(f64) -> f64,
    ) -> f64 {
        self.with_points(bi, bj, |kept| kept.iter().map(|k| law(k.point.depth)).sum())
    }
}

/// Where a slot's point was at the last accepted step: on A and on B (body-local, or the arc
/// coordinate on a beam face), and the normal in A's frame.
pub(crate) type SlotKey = [Vector2<f64>; 3];

/// Slots by nearness to the committed `keys` (deepest point first): a point keeps a slot when
/// either of its two `local` points moved less than `reach` since the commit and its normal
/// (in A's frame) turned by less than 37° (cos > 0.8, as in [`reduce`]). The normal tells apart
/// two contacts that share a point, e.g. a block's corner on a floor and on a wall: without it
/// both would be at distance 0 of both slots and rounding would pick. Then free slots, then any.
pub(crate) fn assign_slots<P: Copy, K: Key>(
    keys: &[Option<K>],
    reach: f64,
    kept: &mut [Kept<P>],
    taken: &mut [bool],
    local: impl Fn(&P) -> K,
) {
    taken.fill(false);
    for k in kept.iter_mut() {
        let here = local(&k.point);
        let near = keys
            .iter()
            .enumerate()
            .filter(|(s, _)| !taken[*s])
            .filter_map(|(s, key)| {
                let (d, cos) = here.nearness(&(*key)?);
                (d <= reach && cos > 0.8).then_some((s, d))
            });
        let best = near.min_by(|x, y| x.1.total_cmp(&y.1)).map(|(s, _)| s);
        let free = || (0..taken.len()).find(|&s| !taken[s] && keys[s].is_none());
        let any = || (0..taken.len()).find(|&s| !taken[s]);
        // `reduce` keeps at most as many points as there are slots
        k.slot = best.or_else(free).or_else(any).unwrap_or(0);
        taken[k.slot] = true;
    }
}

/// The slot key of a point: its body-local points and its normal in A's frame.
fn key(bi: &BodyState, bj: &BodyState, p: &ShapeContactPoint) -> SlotKey {
    let n = clr_contact::body::rotate(-bi.angle, p.normal);
    [bi.to_local(p.point_a), bj.to_local(p.point_b), n]
}

/// The force f = F_N n + F_T t on B at kept point `k` with rates (δ̇, v_T), `None` when it does
/// not penetrate; the report takes the deepest point's penetration, rate and position on A (as
/// `eccentricity`), and the forces and dissipated power of every penetrating point.
pub(crate) fn point_force(
    k: &Kept,
    (vn, vt): (f64, f64),
    (normal, friction): (&NormalLaw, &FrictionLaw),
    (mem, memory): (usize, &mut ContactMemory),
    rep: &mut ContactReport,
) -> Option<Vector2<f64>> {
    let p = &k.point;
    if p.depth > rep.penetration {
        rep.penetration = p.depth;
        rep.penetration_rate = vn;
        rep.eccentricity = [p.point_a.x, p.point_a.y];
    }
    if p.depth <= 0.0 {
        return None;
    }
    let vm = memory.impact_velocity(mem + k.slot, p.depth, vn);
    let f_n = normal.force(p.depth, vn, vm);
    let f_t = friction.force(vt, f_n);
    rep.active_points += 1;
    rep.normal_force += f_n;
    rep.friction_force += f_t;
    rep.dissipated_power += (f_n - normal.elastic_force(p.depth)) * vn - f_t * vt;
    Some(p.normal * f_n + perp(p.normal) * f_t)
}

/// (δ̇, v_T) of a point: v = ṙ_B(p_B) − ṙ_A(p_A), δ̇ = −v·n, v_T = v·t (module docs).
fn rates(p: &ShapeContactPoint, bi: &BodyState, bj: &BodyState) -> (f64, f64) {
    let v = bj.point_velocity(p.point_b) - bi.point_velocity(p.point_a);
    (-v.dot(&p.normal), v.dot(&perp(p.normal)))
}

/// Deepest first; drop a point near a deeper kept one with a similar normal; at most
/// `max_points` (module docs).
pub(crate) fn reduce<P: PatchPoint>(points: &[P], s: &PairSettings, kept: &mut Vec<Kept<P>>) {
    let near = |a: &P, b: &P| {
        let (d, cos) = a.nearness(b);
        d <= s.merge && cos > 0.8
    };
    for p in points {
        if kept
            .iter()
            .any(|k| near(&k.point, p) && k.point.depth() >= p.depth())
        {
            continue;
        }
        // the near kept points are all shallower than p: p replaces them
        kept.retain(|k| !near(&k.point, p));
        let at = kept.partition_point(|k| k.point.depth() >= p.depth());
        kept.insert(at, Kept { point: *p, slot: 0 });
    }
    kept.truncate(s.max_points);
}
