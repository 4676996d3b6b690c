//! A shape against the deformed face of a flexible beam (`[[shape]]` with `geometry = { type =
//! "beam_face", … }` as shape A of a `contact` element): the face is sampled along its
//! undeformed arc length (nodes and points between them), the samples are joined into segments
//! in the world frame at every evaluation, and each segment is queried against shape B with
//! parry (clr-contact `segment_contact_points`, built on the stack). Points whose normal does
//! not leave the face outward are dropped (the solid side is the beam). Then the points are
//! reduced, slotted and loaded as in [`crate::shape_pair`]: f = F_N n + F_T t on B at its
//! contact point, −f on the beam at the contact point's arc coordinate as work-equivalent nodal
//! loads (clr-beam `surface_load_row`; for a floating body through its frame and modes).
//!
//! The face velocity at a point is interpolated linearly between its segment's end samples,
//! like its position. The Newton matrix of this element is by central differences over the
//! beam's and the body's coordinates (the analytic forms cover rigid shapes only).

use clr_beam::{Face, Path};
use clr_contact::{
    segment_contact_points, BodyState, ContactMemory, FrictionLaw, GuideSurface, NormalLaw,
    ShapeContactPoint, ShapeContactWorkspace,
};
use nalgebra::Vector2;

use crate::beam_face::{add_face_load, GuideBeam, GuideRef, Surface};
use crate::contact_report::ContactReport;
use crate::runtime::{cross, perp};
use crate::shape_pair::{assign_slots, point_force, reduce, Kept, PairSettings, Side, SlotKey};

/// The runtime form (module docs); B is on the clearance's frame j.
pub(crate) struct FacePair {
    pub(crate) beam: GuideBeam,
    path: Path,
    face: Face,
    /// Undeformed arc coordinates of the samples, m.
    arcs: Vec<f64>,
    /// World position, velocity and outward normal of each sample at the last update.
    pos: Vec<Vector2<f64>>,
    vel: Vec<Vector2<f64>>,
    nrm: Vec<Vector2<f64>>,
    /// Full-DOF displacement and velocity buffers of the beam.
    qfull: Vec<f64>,
    qdfull: Vec<f64>,
    b: Side,
    pub(crate) settings: PairSettings,
    ws: ShapeContactWorkspace,
    raw: Vec<ShapeContactPoint>,
    kept: Vec<Kept>,
    taken: Vec<bool>,
    /// Committed (arc, 0) on the face, the body-local point on B and the world normal of each
    /// slot.
    keys: Vec<Option<SlotKey>>,
}

/// What a face pair needs from the compiled beam.
#[derive(Clone)]
pub(crate) struct FaceSource {
    pub(crate) beam: GuideBeam,
    pub(crate) path: Path,
    pub(crate) face: Face,
    /// Length of the full-DOF vector of the beam.
    pub(crate) n_full: usize,
    /// Samples per element (≥ 1).
    pub(crate) samples: usize,
}

impl FacePair {
    /// Bounding radius of the rigid shape B, m (the scale of its penetration).
    pub(crate) fn shape_radius(&self) -> f64 {
        self.b.radius
    }

    pub(crate) fn new(src: FaceSource, b: Side, settings: PairSettings) -> Self {
        // `samples` equal arc steps in every element, then the path's end
        let starts = src.path.element_starts();
        let ends = starts.iter().skip(1).copied().chain([src.path.length()]);
        let mut arcs: Vec<f64> = starts
            .iter()
            .zip(ends)
            .flat_map(|(&s0, s1)| {
                (0..src.samples).map(move |i| s0 + (s1 - s0) * i as f64 / src.samples as f64)
            })
            .collect();
        arcs.push(src.path.length());
        let n = arcs.len();
        Self {
            beam: src.beam,
            path: src.path,
            face: src.face,
            pos: vec![Vector2::zeros(); n],
            vel: vec![Vector2::zeros(); n],
            nrm: vec![Vector2::zeros(); n],
            arcs,
            qfull: vec![0.0; src.n_full],
            qdfull: vec![0.0; src.n_full],
            b,
            ws: ShapeContactWorkspace::new(),
            raw: Vec::new(),
            kept: Vec::with_capacity(settings.max_points),
            taken: vec![false; settings.max_points],
            keys: vec![None; settings.max_points],
            settings,
        }
    }

    /// Sample the deformed face at (q, q̇) and detect shape B (body state `bj`) against it.
    pub(crate) fn update(&mut self, guide: GuideRef, q: &[f64], qd: &[f64], bj: &BodyState) {
        let surface = Surface::new(
            guide,
            q,
            qd,
            (&self.path, self.face),
            (&mut self.qfull, &mut self.qdfull),
        );
        for (k, &s) in self.arcs.iter().enumerate() {
            self.pos[k] = surface.point(s);
            self.vel[k] = surface.velocity(s);
            self.nrm[k] = surface.normal(s);
        }
        self.detect(bj);
    }

    fn detect(&mut self, bj: &BodyState) {
        self.raw.clear();
        self.kept.clear();
        let margin = self.settings.prediction;
        let pose_b = BodyState::fixed(bj.point(self.b.arm), bj.angle + self.b.angle);
        let (centre, reach) = (bj.position, self.b.reach);
        for k in 0..self.pos.len() - 1 {
            let (p0, p1) = (self.pos[k], self.pos[k + 1]);
            // broad phase per segment: B's bounding circle against the segment
            if segment_distance(centre, p0, p1) > reach + margin {
                continue;
            }
            let Ok(points) =
                segment_contact_points([p0, p1], &self.b.shape, &pose_b, margin, &mut self.ws)
            else {
                continue;
            };
            for p in points {
                let (_, n_face) = lerp(&self.nrm, k, param(p0, p1, p.point_a));
                // the beam is solid behind its face: only contacts from outside count
                if p.normal.dot(&n_face) > 0.0 {
                    self.raw.push(ShapeContactPoint {
                        part_a: k as u32,
                        ..*p
                    });
                }
            }
        }
        reduce(&self.raw, &self.settings, &mut self.kept);
        let (pos, arcs) = (&self.pos, &self.arcs);
        let local = |p: &ShapeContactPoint| {
            let s = arc_of(pos, arcs, p);
            [Vector2::new(s, 0.0), bj.to_local(p.point_b), p.normal]
        };
        assign_slots(
            &self.keys,
            self.settings.matching,
            &mut self.kept,
            &mut self.taken,
            local,
        );
    }

    /// (δ̇, v_T) of a kept point, with the face's velocity interpolated along its segment.
    fn rates(&self, p: &ShapeContactPoint, bj: &BodyState) -> (f64, f64) {
        let k = p.part_a as usize;
        let (va, _) = lerp(&self.vel, k, param(self.pos[k], self.pos[k + 1], p.point_a));
        let v = bj.point_velocity(p.point_b) - va;
        (-v.dot(&p.normal), v.dot(&perp(p.normal)))
    }

    /// Forces at the state of the last [`FacePair::update`]: on B through `add_b(qf, [f_x,
    /// f_y, m])`, on the beam into `qf`; returns the report.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn apply(
        &self,
        guide: GuideRef,
        (q, bj): (&[f64], &BodyState),
        (normal, friction): (&NormalLaw, &FrictionLaw),
        mem: usize,
        memory: &mut ContactMemory,
        qf: &mut [f64],
        mut add_b: impl FnMut(&mut [f64], [f64; 3]),
    ) -> ContactReport {
        let mut rep = ContactReport {
            penetration: -self.settings.prediction,
            ..Default::default()
        };
        for k in &self.kept {
            let p = &k.point;
            let (vn, vt) = self.rates(p, bj);
            let laws = (normal, friction);
            let Some(f) = point_force(k, (vn, vt), laws, (mem, &mut *memory), &mut rep) else {
                continue;
            };
            add_b(qf, [f.x, f.y, cross(p.point_b - bj.position, f)]);
            let arc = arc_of(&self.pos, &self.arcs, p);
            let face = (&self.path, self.face, &self.qfull[..]);
            add_face_load(guide, face, (arc, p.point_a), -f, q, qf);
        }
        rep
    }

    /// Commit the memory at the state of the last [`FacePair::update`] (the accepted state).
    pub(crate) fn commit(&mut self, bj: &BodyState, mem: usize, memory: &mut ContactMemory) {
        self.taken.fill(false);
        for k in &self.kept {
            let (vn, _) = self.rates(&k.point, bj);
            memory.commit(mem + k.slot, k.point.depth, vn);
            self.taken[k.slot] = true;
        }
        for (slot, key) in self.keys.iter_mut().enumerate() {
            *key = None;
            if !self.taken[slot] {
                memory.commit(mem + slot, -1.0, 0.0);
            }
        }
        for k in &self.kept {
            let s = arc_of(&self.pos, &self.arcs, &k.point);
            let b = bj.to_local(k.point.point_b);
            self.keys[k.slot] = Some([Vector2::new(s, 0.0), b, k.point.normal]);
        }
    }

    /// Largest signed penetration at the last update, m (−prediction with no point).
    pub(crate) fn max_depth(&self) -> f64 {
        let floor = -self.settings.prediction;
        self.kept.iter().fold(floor, |g, k| g.max(k.point.depth))
    }

    /// Elastic energy over the penetrating points at the last update, J.
    pub(crate) fn elastic_energy(&self, law: impl Fn(f64) -> f64) -> f64 {
        self.kept.iter().map(|k| law(k.point.depth)).sum()
    }
}

/// Parameter t ∈ [0, 1] of the projection of `p` on the segment p0–p1.
fn param(p0: Vector2<f64>, p1: Vector2<f64>, p: Vector2<f64>) -> f64 {
    let d = p1 - p0;
    let l2 = d.norm_squared();
    if l2 > 0.0 {
        ((p - p0).dot(&d) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Linear interpolation of samples `v` at t on segment k, and its normalized direction.
fn lerp(v: &[Vector2<f64>], k: usize, t: f64) -> (Vector2<f64>, Vector2<f64>) {
    let x = v[k] * (1.0 - t) + v[k + 1] * t;
    let n = x.norm();
    (x, if n > 0.0 { x / n } else { x })
}

/// Undeformed arc coordinate of a point on segment `part_a`, m.
fn arc_of(pos: &[Vector2<f64>], arcs: &[f64], p: &ShapeContactPoint) -> f64 {
    let k = p.part_a as usize;
    let t = param(pos[k], pos[k + 1], p.point_a);
    arcs[k] + t * (arcs[k + 1] - arcs[k])
}

/// Distance from `c` to the segment p0–p1, m.
fn segment_distance(c: Vector2<f64>, p0: Vector2<f64>, p1: Vector2<f64>) -> f64 {
    let t = param(p0, p1, c);
    (p0 + (p1 - p0) * t - c).norm()
}
