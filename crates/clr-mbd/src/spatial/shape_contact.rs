//! Shape contact in space (`[[shape]]` and `[[clearance]] type = "contact"` of a spatial model):
//! two shapes on two bodies (or a body and the ground), their contact points from parry3d-f64
//! through clr-contact [`contact_points3`], any clr-contact normal law at each point along its
//! normal and a friction law in its tangent plane. The spatial counterpart of the planar
//! `crate::shape_pair`, whose rules it shares: the reduction to one point per contact patch
//! ([`reduce`]), the memory slots that follow a sliding or rolling point ([`assign_slots`]),
//! the event function (the deepest point) and the conservative step bound.
//!
//! * **Forces.** At each point with δ > 0, with v = ṙ_B(p_B) − ṙ_A(p_A) the relative velocity of
//!   the two contact points as material points of their bodies: δ̇ = −v·n, the slip
//!   v_t = v + δ̇ n (in the tangent plane), F_N = F_N(δ, δ̇, δ̇⁻) with the slot's δ̇⁻ from the contact
//!   memory, F_t = v_t F_T(|v_t|, F_N)/|v_t| (the planar law's magnitude, against the slip, as
//!   the spherical clearance joint). f = F_N n + F_t acts on B at p_B and −f on A at p_A (moments
//!   from the lever arms to each centre of mass). δ̇ is the exact rate of the signed distance
//!   (the closest points held, the envelope theorem), so the pair's power is −F_N δ̇ + F_t·v_t
//!   and the energy balance closes: the dissipated power is (F_N − F_e)δ̇ − F_t·v_t.
//! * **Broad phase.** Bounding spheres about the shape origins, then the axis-aligned boxes grown
//!   by the prediction distance ([`boxes_overlap3`]); a pair far apart costs a distance and a
//!   comparison.
//! * **Step bound.** [`ShapeContact3::max_step`]: conservative advancement (Mirtich 1996, §3.3),
//!   as the planar pairs.

use std::cell::RefCell;

use clr_contact::{
    boxes_gap3, boxes_overlap3, contact_points3, shape_distance3, BodyState3, ContactMemory,
    ContactShape3, FrictionLaw, NormalLaw, ShapeContactPoint3, ShapeContactWorkspace3,
};
use nalgebra::{Rotation3, UnitQuaternion, Vector3};

use super::kin::{add_force, Kin, Kinematics};
use crate::shape_pair::{assign_slots, reduce, Kept, PairSettings};

/// A compiled `[[shape]]`: its body, where its frame sits and how it is turned there.
#[derive(Debug, Clone)]
pub(crate) struct Side3 {
    /// The `[[shape]]`'s name (warnings name its fields).
    pub(crate) name: String,
    /// Body index (or the ground).
    pub(crate) body: usize,
    /// Origin of the shape frame from the centre of mass, body frame, m.
    pub(crate) s: Vector3<f64>,
    /// Rotation shape frame → body frame.
    pub(crate) rot: UnitQuaternion<f64>,
    pub(crate) shape: ContactShape3,
}

impl Side3 {
    /// Pose and twist of the shape frame for the body at `k`.
    fn pose(&self, k: &Kin) -> BodyState3 {
        let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(k.a));
        let o = k.point(&self.s);
        BodyState3::new(o, q * self.rot, k.point_velocity(&o), k.w)
    }

    /// Radius of a sphere about the shape origin holding the shape, m.
    pub(crate) fn radius(&self) -> f64 {
        self.shape.bounding_radius()
    }
}

/// Slot key: the point on A (A's shape frame), the point on B (B's shape frame), the normal in
/// A's shape frame.
type Key3 = [Vector3<f64>; 3];

/// Reusable buffers of one detection (interior mutability: detection also runs where the model
/// is borrowed immutably; the model is used by one thread at a time).
#[derive(Default)]
struct Scratch {
    ws: ShapeContactWorkspace3,
    kept: Vec<Kept<ShapeContactPoint3>>,
    taken: Vec<bool>,
}

/// A compiled spatial shape contact: shape A on body `a.body`, B on `b.body`.
pub(crate) struct ShapeContact3 {
    pub(crate) name: String,
    pub(crate) a: Side3,
    pub(crate) b: Side3,
    pub(crate) law: NormalLaw,
    pub(crate) friction: Option<FrictionLaw>,
    pub(crate) settings: PairSettings,
    /// First of its `max_points` slots in the contact memory.
    pub(crate) memory: usize,
    scratch: RefCell<Scratch>,
    /// Local points and normal of each slot at the last accepted step (`None`: free slot).
    keys: Vec<Option<Key3>>,
    /// The last commit found the pair apart.
    committed_apart: bool,
}

/// What a shape contact gives at one state (its result columns).
#[derive(Debug, Clone, Copy, Default)]
pub struct ShapeReport3 {
    /// Largest penetration over the tracked points, m (−prediction when none is within it).
    pub penetration: f64,
    /// δ̇ of that point, m/s (> 0 approaching).
    pub rate: f64,
    /// Normal force summed over the active points, N.
    pub normal_force: f64,
    /// Magnitude of the friction force summed over the active points, N.
    pub friction_force: f64,
    /// Number of penetrating points.
    pub active_points: usize,
    /// The deepest tracked point on A (world), m; 0 when none is tracked.
    pub deepest: Vector3<f64>,
    /// Power dissipated by contact damping and friction, W.
    pub dissipated: f64,
    /// Elastic energy ∫F_e dδ summed over the active points, J.
    pub elastic_energy: f64,
}

impl ShapeContact3 {
    pub(crate) fn new(
        name: String,
        (a, b): (Side3, Side3),
        (law, friction): (NormalLaw, Option<FrictionLaw>),
        settings: PairSettings,
        memory: usize,
    ) -> Self {
        Self {
            name,
            a,
            b,
            law,
            friction,
            settings,
            memory,
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
        let origin = BodyState3::default();
        let mut ws = ShapeContactWorkspace3::new();
        contact_points3(&self.a.shape, &origin, &self.b.shape, &origin, 0.0, &mut ws).map(|_| ())
    }

    /// The smaller bounding radius of the two shapes, m (the scale of the depth watch).
    pub(crate) fn size(&self) -> f64 {
        self.a.radius().min(self.b.radius())
    }

    fn poses(&self, kin: &Kinematics) -> (BodyState3, BodyState3) {
        (
            self.a.pose(kin.get(self.a.body)),
            self.b.pose(kin.get(self.b.body)),
        )
    }

    /// Gap between the bounding spheres, m: a lower bound of the shapes' distance.
    fn sphere_gap(&self, pa: &BodyState3, pb: &BodyState3) -> f64 {
        (pb.position - pa.position).norm() - self.a.radius() - self.b.radius()
    }

    fn detect(&self, pa: &BodyState3, pb: &BodyState3, s: &mut Scratch) {
        let Scratch { ws, kept, taken } = s;
        kept.clear();
        let margin = self.settings.prediction;
        if self.sphere_gap(pa, pb) > margin {
            return;
        }
        let (Ok(ba), Ok(bb)) = (self.a.shape.aabb3(pa), self.b.shape.aabb3(pb)) else {
            return;
        };
        if !boxes_overlap3(&ba, &bb, margin) {
            return;
        }
        // a pose with NaN (a failed step) gives no contact; the integrator rejects that step
        let Ok(points) = contact_points3(&self.a.shape, pa, &self.b.shape, pb, margin, ws) else {
            return;
        };
        reduce(points, &self.settings, kept);
        let local = |p: &ShapeContactPoint3| key(pa, pb, p);
        assign_slots(&self.keys, self.settings.matching, kept, taken, local);
    }

    /// The event function: the largest signed penetration, m (−prediction when nothing lies
    /// within the prediction distance).
    pub(crate) fn gap(&self, kin: &Kinematics) -> f64 {
        let (pa, pb) = self.poses(kin);
        let mut s = self.scratch.borrow_mut();
        self.detect(&pa, &pb, &mut s);
        let floor = -self.settings.prediction;
        s.kept.iter().fold(floor, |g, k| g.max(k.point.depth))
    }

    /// Apply the contact forces into Q (when `q` is given) and report.
    pub(crate) fn apply(
        &self,
        kin: &Kinematics,
        memory: &mut ContactMemory,
        mut q: Option<&mut [f64]>,
    ) -> ShapeReport3 {
        let (pa, pb) = self.poses(kin);
        let mut rep = ShapeReport3 {
            penetration: -self.settings.prediction,
            ..Default::default()
        };
        let mut s = self.scratch.borrow_mut();
        self.detect(&pa, &pb, &mut s);
        for k in &s.kept {
            let p = &k.point;
            let v = p.relative_velocity(&pa, &pb);
            let rate = -v.dot(&p.normal);
            if p.depth > rep.penetration {
                rep.penetration = p.depth;
                rep.rate = rate;
                rep.deepest = p.point_a;
            }
            if p.depth <= 0.0 {
                continue;
            }
            let vm = memory.impact_velocity(self.memory + k.slot, p.depth, rate);
            let f_n = self.law.force(p.depth, rate, vm);
            let slip = v + rate * p.normal;
            let speed = slip.norm();
            let f_t = match &self.friction {
                Some(f) if speed > 0.0 => slip * (f.force(speed, f_n) / speed),
                _ => Vector3::zeros(),
            };
            let f = p.normal * f_n + f_t;
            rep.active_points += 1;
            rep.normal_force += f_n;
            rep.friction_force += f_t.norm();
            rep.dissipated += (f_n - self.law.elastic_force(p.depth)) * rate - f_t.dot(&slip);
            rep.elastic_energy += self.law.elastic_energy(p.depth);
            if let Some(q) = q.as_deref_mut() {
                add_force(q, kin, self.b.body, &p.point_b, &f);
                add_force(q, kin, self.a.body, &p.point_a, &(-f));
            }
        }
        rep
    }

    /// Commit the memory at an accepted state: each kept point's (δ, δ̇) into its slot and its
    /// local points as the slot's key; free slots as separated (δ = −1 m marker, δ̇ = 0).
    pub(crate) fn commit(&mut self, kin: &Kinematics, memory: &mut ContactMemory) {
        let (pa, pb) = self.poses(kin);
        if self.sphere_gap(&pa, &pb) > self.settings.prediction {
            // apart: committing (−1, 0) again would change nothing
            if !self.committed_apart {
                for (slot, key) in self.keys.iter_mut().enumerate() {
                    memory.commit(self.memory + slot, -1.0, 0.0);
                    *key = None;
                }
                self.committed_apart = true;
            }
            return;
        }
        self.committed_apart = false;
        let s = self.scratch.get_mut();
        // detected with the previous keys, which are replaced below
        let mut scratch = std::mem::take(s);
        self.detect(&pa, &pb, &mut scratch);
        scratch.taken.fill(false);
        for k in &scratch.kept {
            let rate = -k.point.relative_velocity(&pa, &pb).dot(&k.point.normal);
            memory.commit(self.memory + k.slot, k.point.depth, rate);
            scratch.taken[k.slot] = true;
        }
        for (slot, _) in scratch.taken.iter().enumerate().filter(|(_, t)| !**t) {
            memory.commit(self.memory + slot, -1.0, 0.0);
        }
        self.keys.iter_mut().for_each(|k| *k = None);
        for k in &scratch.kept {
            self.keys[k.slot] = Some(key(&pa, &pb, &k.point));
        }
        *self.scratch.get_mut() = scratch;
    }

    /// The longest next step that cannot carry the shapes through each other, s: with the gap
    /// d between them (the bounding spheres' gap, else the boxes' gap, else parry's distance)
    /// every point of a shape moves relative to the other by at most v·h + a·h²/2, where
    /// v = |v_B − v_A| + |ω_A|R_A + |ω_B|R_B and a = |a_B − a_A| + (|α_A| + |ω_A|²)R_A +
    /// (|α_B| + |ω_B|²)R_B bound the relative speed and acceleration of any point (v, a of the
    /// shape origins, R the bounding radii about them), so h = 2D/(v + √(v² + 2aD)) with
    /// D = d + prediction/2 lets them close the gap and penetrate by at most half the prediction
    /// distance within one step: conservative advancement (Mirtich, *Impulse-based dynamic
    /// simulation of rigid body systems*, PhD thesis, UC Berkeley, 1996, §3.3), as the planar
    /// pairs. `acc` holds each body's (acceleration of the centre of mass, angular
    /// acceleration), world. Unbounded while they touch: the error control follows the contact.
    pub(crate) fn max_step(&self, kin: &Kinematics, acc: [(Vector3<f64>, Vector3<f64>); 2]) -> f64 {
        let (pa, pb) = self.poses(kin);
        let mut gap = self.sphere_gap(&pa, &pb);
        if gap <= 0.0 {
            let (Ok(ba), Ok(bb)) = (self.a.shape.aabb3(&pa), self.b.shape.aabb3(&pb)) else {
                return f64::INFINITY;
            };
            gap = if boxes_overlap3(&ba, &bb, 0.0) {
                shape_distance3(&self.a.shape, &pa, &self.b.shape, &pb).unwrap_or(0.0)
            } else {
                boxes_gap3(&ba, &bb)
            };
        }
        if gap <= 0.0 {
            return f64::INFINITY;
        }
        let d = gap + 0.5 * self.settings.prediction;
        let origin_acc = |side: &Side3, (a, alpha): (Vector3<f64>, Vector3<f64>)| {
            let k = kin.get(side.body);
            let arm = k.a * side.s;
            a + alpha.cross(&arm) + k.w.cross(&k.w.cross(&arm))
        };
        let (ra, rb) = (self.a.radius(), self.b.radius());
        let (wa, wb) = (pa.angular_velocity.norm(), pb.angular_velocity.norm());
        let v = (pb.velocity - pa.velocity).norm() + wa * ra + wb * rb;
        let a = (origin_acc(&self.b, acc[1]) - origin_acc(&self.a, acc[0])).norm()
            + (acc[0].1.norm() + wa * wa) * ra
            + (acc[1].1.norm() + wb * wb) * rb;
        2.0 * d / (v + (v * v + 2.0 * a * d).sqrt())
    }
}

/// The slot key of a point: its points in the two shape frames and its normal in A's.
fn key(pa: &BodyState3, pb: &BodyState3, p: &ShapeContactPoint3) -> Key3 {
    [
        pa.to_local(p.point_a),
        pb.to_local(p.point_b),
        pa.rotation.inverse_transform_vector(&p.normal),
    ]
}
