//! The assembly's contact elements ([`Clearance`]), force elements built on clr-contact: a
//! revolute clearance joint (journal in bearing, optionally lubricated), a translational
//! clearance joint (rectangular slider in a straight guide), a slider on a flexible beam face
//! ([`FlexGuide`]), a shape pair and a shape against a beam face. Each holds its laws, its slots
//! in the contact memory and its kind's runtime form, and gives its gaps, forces, memory commits
//! and elastic energy. The runtime forms of the pairs (`crate::shape_pair`, `crate::face_pair`),
//! the beam-face surface (`crate::beam_face`) and [`ContactReport`] sit below this module.

use clr_beam::{Face, Path};
use clr_contact::translational::{TranslationalClearance, TranslationalForces};
use clr_contact::{
    BodyState, ContactMemory, ForceApplication, FrictionLaw, MultipointDetector, NormalLaw,
    RevoluteClearance,
};
use nalgebra::Vector2;

use crate::beam_face::{add_face_load, GuideBeam, GuideRef, Surface};
use crate::contact_report::ContactReport;
use crate::runtime::rot;

/// A slider on a face of a flexible beam (clr-contact multipoint detection over the clr-beam
/// deformed-shape queries), the beam ground-fixed or a floating-frame body.
pub(crate) struct FlexGuide {
    /// The beam carrying the face.
    pub(crate) beam: GuideBeam,
    pub(crate) path: Path,
    pub(crate) face: Face,
    /// Area law applied with each point's wetted length (see `FlexibleGuideSpec::area_normal`).
    pub(crate) area_normal: Option<NormalLaw>,
    pub(crate) detector: MultipointDetector,
    /// Full-DOF displacement and velocity buffers of the beam (scattered from q, q̇).
    pub(crate) qfull: Vec<f64>,
    pub(crate) qdfull: Vec<f64>,
}

/// The dry forces of a lubricated joint weighted by the transition's w(h_min) ∈ [0, 1].
fn scale_joint_forces(jf: &mut clr_contact::revolute::JointForces, w: f64) {
    jf.normal_force *= w;
    jf.tangential_force *= w;
    for g in [&mut jf.bearing, &mut jf.journal] {
        g.force *= w;
        g.moment *= w;
    }
}

/// Geometry of a contact element.
pub(crate) enum ClearanceKind {
    /// Journal (body j) in bearing (body i), with where its force pair acts.
    Revolute(RevoluteClearance, ForceApplication),
    /// Slider (body j) in a guide (body i) whose frame sits at `origin` (local to i) rotated by
    /// `angle`; inner width `width`.
    Translational {
        geometry: TranslationalClearance,
        origin: Vector2<f64>,
        angle: f64,
        width: f64,
    },
    /// Slider (body j) on a flexible beam face; `i` is the ground (ground-fixed beam) or the
    /// floating body's frame.
    FlexGuide(Box<FlexGuide>),
    /// Two shapes in contact: shape A on frame i, shape B on frame j.
    Shapes(Box<crate::shape_pair::ShapePair>),
    /// A rigid shape (frame j) against the deformed face of a flexible beam (frame i: the
    /// ground or the floating body).
    FacePair(Box<crate::face_pair::FacePair>),
}

pub(crate) struct Clearance {
    pub(crate) name: String,
    /// Bearing or guide body.
    pub(crate) i: usize,
    /// Journal or slider body.
    pub(crate) j: usize,
    pub(crate) kind: ClearanceKind,
    pub(crate) normal: NormalLaw,
    pub(crate) friction: FrictionLaw,
    /// First index of this element's contact points in the model's contact memory.
    pub(crate) mem: usize,
    /// LuGre friction with bristle states (then `friction` is frictionless and the element is
    /// evaluated by `crate::lugre::force::apply`, not [`Clearance::apply`]).
    pub(crate) lugre: Option<crate::lugre::state::LuGreContact>,
    /// The oil film of a lubricated revolute joint (else `None`).
    pub(crate) film: Option<Film>,
}

/// The oil film of a lubricated revolute clearance joint: the hydrodynamic force acts at every
/// eccentricity, the dry laws add w(h_min)·F_dry (clr-contact `lubrication`, docs/lubrication.md).
pub(crate) struct Film {
    pub(crate) bearing: clr_contact::lubrication::HydrodynamicBearing,
    pub(crate) transition: clr_contact::lubrication::Transition,
}

impl Clearance {
    /// Number of contact-memory slots (1 revolute, 4 corners translational, every detector
    /// candidate for a flexible guide).
    pub(crate) fn points(&self) -> usize {
        match &self.kind {
            ClearanceKind::Revolute(..) => 1,
            ClearanceKind::Translational { .. } => 4,
            ClearanceKind::FlexGuide(g) => g.detector.point_count(),
            ClearanceKind::Shapes(p) => p.settings.max_points,
            ClearanceKind::FacePair(p) => p.settings.max_points,
        }
    }

    /// Number of onset event functions (0 for a flexible guide: its onsets are not located).
    pub(crate) fn event_points(&self) -> usize {
        match &self.kind {
            ClearanceKind::FlexGuide(_) => 0,
            // one per pair: its deepest point (a continuous function of the state)
            ClearanceKind::Shapes(_) | ClearanceKind::FacePair(_) => 1,
            _ => self.points(),
        }
    }

    /// Signed penetration δ (m, > 0 in contact) and its rate δ̇ (m/s) of contact point k.
    pub(crate) fn gap(&self, bi: &BodyState, bj: &BodyState, k: usize) -> (f64, f64) {
        match &self.kind {
            ClearanceKind::Revolute(g, _) => {
                let c = g.contact(bi, bj);
                (c.penetration, c.normal_velocity)
            }
            ClearanceKind::Translational {
                geometry,
                origin,
                angle,
                width,
            } => {
                let o = bi.point(*origin);
                let ay = bi.rotate(Vector2::new(-angle.sin(), angle.cos()));
                let p = geometry.corners(bj)[k];
                let y = (p - o).dot(&ay);
                let n = if y >= 0.0 { ay } else { -ay };
                let v = bj.point_velocity(p) - bi.point_velocity(p);
                (y.abs() - 0.5 * width, v.dot(&n))
            }
            // per-candidate gaps are inside the detector; only active points are known
            ClearanceKind::FlexGuide(_) => (-1.0, 0.0),
            // the pair's deepest point (its rate is in the report)
            ClearanceKind::Shapes(p) => (p.max_depth(bi, bj), 0.0),
            // at the state of its last update (`Model::refresh_face`)
            ClearanceKind::FacePair(p) => (p.max_depth(), 0.0),
        }
    }

    /// Add the contact forces to `qf` through `add(body, [f_x, f_y, m])` and return the report.
    pub(crate) fn apply(
        &self,
        bi: &BodyState,
        bj: &BodyState,
        memory: &mut ContactMemory,
        mut add: impl FnMut(usize, [f64; 3]),
    ) -> ContactReport {
        let mut rep = ContactReport::default();
        match &self.kind {
            ClearanceKind::Revolute(g, application) => {
                let ct = g.contact(bi, bj);
                let local = bi.to_local(bi.position + ct.eccentricity_vector);
                rep.penetration = ct.penetration;
                rep.penetration_rate = ct.normal_velocity;
                rep.eccentricity = [local.x, local.y];
                let weight = match &self.film {
                    Some(film) => self.apply_film(film, g, bi, bj, &mut rep, &mut add),
                    None => 1.0,
                };
                if ct.in_contact() {
                    let vm = memory.impact_velocity(self.mem, ct.penetration, ct.normal_velocity);
                    let mut jf =
                        ct.forces_from_laws_with(&self.normal, &self.friction, vm, *application);
                    if weight != 1.0 {
                        scale_joint_forces(&mut jf, weight);
                    }
                    add(self.i, jf.bearing.as_array());
                    add(self.j, jf.journal.as_array());
                    rep.active_points = 1;
                    rep.normal_force = jf.normal_force;
                    rep.friction_force = jf.tangential_force;
                    rep.dissipated_power += revolute_dissipated_power(
                        &jf,
                        bi,
                        bj,
                        weight * self.normal.elastic_force(ct.penetration) * ct.normal_velocity,
                    );
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
                let (normal, friction) = (&self.normal, &self.friction);
                let mut n_active = 0;
                let mut power = 0.0;
                let f = ct.generalized_forces(|corner| {
                    let pc = &corner.contact;
                    let vm = memory.impact_velocity(
                        self.mem + corner.corner,
                        pc.penetration,
                        pc.normal_velocity,
                    );
                    let f_n = normal.force(pc.penetration, pc.normal_velocity, vm);
                    let f_t = friction.force(pc.tangential_velocity, f_n);
                    n_active += 1;
                    power += (f_n - normal.elastic_force(pc.penetration)) * pc.normal_velocity
                        - f_t * pc.tangential_velocity;
                    (f_n, f_t)
                });
                self.report_corners(bi, bj, &f, (n_active, power), &mut rep, add);
            }
            // handled by apply_flex (they need the beam coordinates)
            ClearanceKind::FlexGuide(_) | ClearanceKind::FacePair(_) => {}
            ClearanceKind::Shapes(p) => {
                let (i, j) = (self.i, self.j);
                let laws = (&self.normal, &self.friction);
                p.apply([bi, bj], laws, self.mem, memory, &mut rep, |side, g| {
                    add(if side == 0 { i } else { j }, g)
                });
            }
        }
        rep
    }

    /// Add the film force and the film's shear (Petroff) torques of a lubricated revolute joint,
    /// report them (film force and minimum film thickness; their power is all dissipated: a
    /// viscous film stores no energy), and
    /// return the weight w of the dry laws.
    fn apply_film(
        &self,
        film: &Film,
        g: &RevoluteClearance,
        bi: &BodyState,
        bj: &BodyState,
        rep: &mut ContactReport,
        add: &mut impl FnMut(usize, [f64; 3]),
    ) -> f64 {
        let f = film.bearing.joint_forces(
            &film.transition,
            g.bearing_centre(),
            g.journal_centre(),
            bi,
            bj,
        );
        add(self.i, f.bearing.as_array());
        add(self.j, f.journal.as_array());
        rep.film_force = f.film.magnitude();
        rep.film_thickness = f.kinematics.min_film_thickness;
        let power = |gf: &clr_contact::GeneralizedForce, b: &BodyState| {
            gf.force.dot(&b.velocity) + gf.moment * b.angular_velocity
        };
        rep.dissipated_power = -(power(&f.bearing, bi) + power(&f.journal, bj));
        f.dry_weight
    }

    /// Scatter a translational clearance joint's corner forces `f` and fill the report: active
    /// points and dissipated power (`(n_active, power)`, W), summed normal and friction forces,
    /// and the deepest corner's penetration and rate.
    pub(crate) fn report_corners(
        &self,
        bi: &BodyState,
        bj: &BodyState,
        f: &TranslationalForces,
        (n_active, power): (usize, f64),
        rep: &mut ContactReport,
        mut add: impl FnMut(usize, [f64; 3]),
    ) {
        rep.dissipated_power = power;
        if n_active > 0 {
            add(self.i, f.guide.as_array());
            add(self.j, f.slider.as_array());
        }
        rep.active_points = n_active;
        rep.normal_force = f.corner_forces.iter().map(|c| c.0).sum();
        rep.friction_force = f.corner_forces.iter().map(|c| c.1).sum();
        let (mut dmax, mut rate) = (f64::NEG_INFINITY, 0.0);
        for k in 0..4 {
            let (d, r) = self.gap(bi, bj, k);
            if d > dmax {
                dmax = d;
                rate = r;
            }
        }
        rep.penetration = dmax;
        rep.penetration_rate = rate;
    }

    /// The beam of a flexible-guide element.
    pub(crate) fn flex_beam(&self) -> Option<GuideBeam> {
        match &self.kind {
            ClearanceKind::FlexGuide(g) => Some(g.beam),
            ClearanceKind::FacePair(p) => Some(p.beam),
            _ => None,
        }
    }

    /// Sample the face of a beam-face pair at (q, q̇) and detect against it (no-op for other
    /// kinds): the state its gap, energy and report then refer to.
    pub(crate) fn refresh_face(&mut self, guide: GuideRef, q: &[f64], qd: &[f64], bj: &BodyState) {
        if let ClearanceKind::FacePair(p) = &mut self.kind {
            p.update(guide, q, qd, bj);
        }
    }

    /// Detect the slider (state `bj`) against the deformed beam at (q, q̇).
    fn detect_flex(&mut self, guide: GuideRef, q: &[f64], qd: &[f64], bj: &BodyState) {
        let ClearanceKind::FlexGuide(g) = &mut self.kind else {
            return;
        };
        let surface = Surface::new(
            guide,
            q,
            qd,
            (&g.path, g.face),
            (&mut g.qfull, &mut g.qdfull),
        );
        g.detector.detect(&surface, bj);
    }

    /// Forces of a slider on a flexible guide: on the slider through `add_slider(qf, [f_x, f_y,
    /// m])`, on the beam as work-equivalent nodal loads of each point load at its arc coordinate
    /// (clr-beam `surface_load_row`), added to the beam's free DOF in `qf`; for a floating beam
    /// the same rows in the body frame, mapped to (R, θ, q_f) by
    /// `FloatingBody::add_point_force`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn apply_flex(
        &mut self,
        guide: GuideRef,
        q: &[f64],
        qd: &[f64],
        bj: &BodyState,
        memory: &mut ContactMemory,
        qf: &mut [f64],
        mut add_slider: impl FnMut(&mut [f64], [f64; 3]),
    ) -> ContactReport {
        if let ClearanceKind::FacePair(p) = &mut self.kind {
            p.update(guide, q, qd, bj);
            let laws = (&self.normal, &self.friction);
            return p.apply(guide, (q, bj), laws, self.mem, memory, qf, add_slider);
        }
        self.detect_flex(guide, q, qd, bj);
        let (normal, friction, mem) = (&self.normal, &self.friction, self.mem);
        let ClearanceKind::FlexGuide(g) = &mut self.kind else {
            return ContactReport::default();
        };
        let mut rep = ContactReport {
            penetration: f64::NEG_INFINITY,
            ..Default::default()
        };
        // with an area law: every point gets it with its wetted length (continuous in the
        // configuration, so the law passes from line to area contact without a jump; NormalLaw
        // is Copy, so this allocates nothing); without one: the line law, weighted by the
        // fraction of the point's segment over the guide (1 but at a clipped guide end)
        let area = g.area_normal;
        let gf = g.detector.apply_forces(|p| {
            let pc = &p.contact;
            let vm = memory.impact_velocity(mem + p.id, pc.penetration, pc.normal_velocity);
            let (law, w) = point_law(area, *normal, p);
            let f_n = w * law.force(pc.penetration, pc.normal_velocity, vm);
            let f_t = friction.force(pc.tangential_velocity, f_n);
            rep.active_points += 1;
            rep.normal_force += f_n;
            rep.friction_force += f_t;
            rep.dissipated_power += (f_n - w * law.elastic_force(pc.penetration))
                * pc.normal_velocity
                - f_t * pc.tangential_velocity;
            if pc.penetration > rep.penetration {
                rep.penetration = pc.penetration;
                rep.penetration_rate = pc.normal_velocity;
            }
            (f_n, f_t)
        });
        if rep.active_points == 0 {
            rep.penetration = 0.0;
        }
        add_slider(qf, gf.as_array());
        for load in g.detector.loads() {
            let face = (&g.path, g.face, &g.qfull[..]);
            add_face_load(guide, face, (load.arc, load.point), load.force, q, qf);
        }
        // slider reference point in the guide body's frame (the world frame for a fixed beam)
        let local = match guide {
            GuideRef::Fixed(_) => bj.position,
            GuideRef::Floating(fl) => {
                let o = fl.offset;
                rot(-q[o + 2], bj.position - Vector2::new(q[o], q[o + 1]))
            }
        };
        rep.eccentricity = [local.x, local.y];
        rep
    }

    /// Commit the memory of a flexible-guide element at an accepted state: active detector
    /// points with their (δ, δ̇), the others as separated (δ = −1 m marker, δ̇ = 0; the next onset
    /// then takes the current δ̇ as impact velocity).
    pub(crate) fn commit_flex(
        &mut self,
        guide: GuideRef,
        q: &[f64],
        qd: &[f64],
        bj: &BodyState,
        memory: &mut ContactMemory,
    ) {
        let mem = self.mem;
        if let ClearanceKind::FacePair(p) = &mut self.kind {
            p.update(guide, q, qd, bj);
            p.commit(bj, mem, memory);
            return;
        }
        self.detect_flex(guide, q, qd, bj);
        let ClearanceKind::FlexGuide(g) = &self.kind else {
            return;
        };
        for id in 0..g.detector.point_count() {
            match g.detector.points().iter().find(|p| p.id == id) {
                Some(p) => {
                    memory.commit(mem + id, p.contact.penetration, p.contact.normal_velocity)
                }
                None => memory.commit(mem + id, -1.0, 0.0),
            }
        }
    }

    /// The report of a shape pair the broad phase found apart.
    pub(crate) fn apart_report(&self) -> ContactReport {
        match &self.kind {
            ClearanceKind::Shapes(p) => p.apart_report(),
            _ => ContactReport::default(),
        }
    }

    /// Commit the memory of a shape pair the broad phase found apart.
    pub(crate) fn commit_apart(&mut self, memory: &mut ContactMemory) {
        let mem = self.mem;
        if let ClearanceKind::Shapes(p) = &mut self.kind {
            p.commit_apart(mem, memory);
        }
    }

    /// Commit the memory of a shape pair at an accepted state (`false` for other kinds).
    pub(crate) fn commit_shapes(
        &mut self,
        bi: &BodyState,
        bj: &BodyState,
        memory: &mut ContactMemory,
    ) -> bool {
        let mem = self.mem;
        match &mut self.kind {
            ClearanceKind::Shapes(p) => {
                p.commit(bi, bj, mem, memory);
                true
            }
            _ => false,
        }
    }

    /// Elastic energy ∫F_e dδ summed over the contact points, J.
    pub(crate) fn elastic_energy(&self, bi: &BodyState, bj: &BodyState) -> f64 {
        if let ClearanceKind::Shapes(p) = &self.kind {
            return p.elastic_energy(bi, bj, |d| elastic_energy(&self.normal, d));
        }
        if let ClearanceKind::FacePair(p) = &self.kind {
            return p.elastic_energy(|d| elastic_energy(&self.normal, d));
        }
        if let ClearanceKind::FlexGuide(g) = &self.kind {
            let area = g.area_normal;
            return g
                .detector
                .points()
                .iter()
                .map(|p| {
                    let (law, w) = point_law(area, self.normal, p);
                    w * elastic_energy(&law, p.contact.penetration)
                })
                .sum();
        }
        (0..self.points())
            .map(|k| elastic_energy(&self.normal, self.gap(bi, bj, k).0))
            .sum()
    }
}

/// The normal law of a slider-on-beam contact point and the weight of its force: the area law
/// with the point's wetted length (weight 1), or the line law weighted by the fraction of the
/// point's slider segment over the guide (`ContactPoint::over_guide`: below 1 only for a point
/// clipped at an end of the guide, so a slider passing the end leaves it continuously).
pub(crate) fn point_law(
    area: Option<NormalLaw>,
    line: NormalLaw,
    p: &clr_contact::multipoint::ContactPoint,
) -> (NormalLaw, f64) {
    match area {
        Some(a) => (a.with_contact_length(p.tributary_length), 1.0),
        None => (line, p.over_guide),
    }
}

/// Elastic energy ∫₀^δ F_e(s) ds of a normal law (J; [`NormalLaw::elastic_energy`]).
fn elastic_energy(law: &NormalLaw, delta: f64) -> f64 {
    law.elastic_energy(delta)
}

/// Power dissipated by the contact force pair `jf` of a revolute clearance joint, W: minus the
/// power the pair delivers to the bearing body `bi` and the journal body `bj` (g·(v, ω) of each
/// body's generalized force, which is q̇ᵀQ of what is added to Q) minus the elastic storage
/// `elastic_power` = F_e(δ)·δ̇. It equals (F_N − F_e)δ̇ − F_T·v_T with v_T the slip at the points
/// where the pair acts: the contact points ([`ForceApplication::ContactPoints`]) or their
/// midpoint ([`ForceApplication::CommonPoint`], where the slip is v_T − (δ/2)(ω_i + ω_j)); taking
/// it from the applied forces keeps `energy.balance` closed whichever application is chosen.
#[inline]
pub(crate) fn revolute_dissipated_power(
    jf: &clr_contact::revolute::JointForces,
    bi: &BodyState,
    bj: &BodyState,
    elastic_power: f64,
) -> f64 {
    let power = |g: &clr_contact::GeneralizedForce, b: &BodyState| {
        g.force.dot(&b.velocity) + g.moment * b.angular_velocity
    };
    -power(&jf.bearing, bi) - power(&jf.journal, bj) - elastic_power
}
