//! The deformed face of a flexible beam, ground-fixed (`[[beam]]`) or floating
//! (`[[flexible_body]]`), as a clr-contact guide surface at (q, q̇), and the loads a contact puts
//! on it. Shared by the contact elements that run on a beam face: a rigid slider
//! (`crate::clearance::FlexGuide`) and a shape against the face (`crate::face_pair`).

use clr_beam::{Face, Path};
use clr_contact::GuideSurface;
use nalgebra::Vector2;

use crate::flexible::FlexBeam;
use crate::floating::FloatingBody;
use crate::runtime::{perp, rot};

/// Which flexible body carries a guide face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum GuideBeam {
    /// Index in the model's ground-fixed beams.
    Fixed(usize),
    /// Index in the model's floating-frame bodies.
    Floating(usize),
}

/// The flexible body of a guide, resolved from the model.
#[derive(Clone, Copy)]
pub(crate) enum GuideRef<'a> {
    Fixed(&'a FlexBeam),
    Floating(&'a FloatingBody),
}

/// The deformed beam face as a clr-contact guide surface (s = undeformed arc length).
pub(crate) struct BeamFace<'a> {
    path: &'a Path,
    face: Face,
    q: &'a [f64],
    qd: &'a [f64],
}

impl BeamFace<'_> {
    fn at(&self, s: f64) -> clr_beam::SurfacePoint {
        self.path
            .surface(s, self.face, self.q, self.qd)
            .unwrap_or(clr_beam::SurfacePoint {
                position: [f64::NAN; 2],
                velocity: [f64::NAN; 2],
                normal: [f64::NAN; 2],
                normal_rate: [f64::NAN; 2],
            })
    }
}

impl GuideSurface for BeamFace<'_> {
    fn arc_range(&self) -> (f64, f64) {
        (0.0, self.path.length())
    }
    fn point(&self, s: f64) -> Vector2<f64> {
        let p = self.at(s).position;
        Vector2::new(p[0], p[1])
    }
    fn tangent(&self, s: f64) -> Vector2<f64> {
        // dr/ds direction: the outward normal turned back by ∓90° (upper face: n = k̂ × t)
        let n = self.at(s).normal;
        match self.face {
            Face::Upper => Vector2::new(n[1], -n[0]),
            Face::Lower => Vector2::new(-n[1], n[0]),
        }
    }
    fn normal(&self, s: f64) -> Vector2<f64> {
        let n = self.at(s).normal;
        Vector2::new(n[0], n[1])
    }
    fn velocity(&self, s: f64) -> Vector2<f64> {
        let v = self.at(s).velocity;
        Vector2::new(v[0], v[1])
    }
}

/// The face of a floating-frame beam in world coordinates: the body-frame face point p̄(s),
/// tangent, normal and elastic velocity from the beam interpolation at u = T q_f ([`BeamFace`]),
/// then r = R + A p̄, t = A t̄, n = A n̄, ṙ = Ṙ + θ̇ Ĩ A p̄ + A p̄̇ (Shabana 2020, eq. 5.4 and its
/// time derivative).
pub(crate) struct FloatFace<'a> {
    local: BeamFace<'a>,
    origin: Vector2<f64>,
    angle: f64,
    velocity: Vector2<f64>,
    omega: f64,
}

impl GuideSurface for FloatFace<'_> {
    fn arc_range(&self) -> (f64, f64) {
        self.local.arc_range()
    }
    fn point(&self, s: f64) -> Vector2<f64> {
        self.origin + rot(self.angle, self.local.point(s))
    }
    fn tangent(&self, s: f64) -> Vector2<f64> {
        rot(self.angle, self.local.tangent(s))
    }
    fn normal(&self, s: f64) -> Vector2<f64> {
        rot(self.angle, self.local.normal(s))
    }
    fn velocity(&self, s: f64) -> Vector2<f64> {
        let p = self.local.at(s);
        let arm = rot(self.angle, Vector2::new(p.position[0], p.position[1]));
        self.velocity
            + self.omega * perp(arm)
            + rot(self.angle, Vector2::new(p.velocity[0], p.velocity[1]))
    }
}

/// The deformed face of a ground-fixed or floating beam at (q, q̇), as a clr-contact guide
/// surface ([`BeamFace`], [`FloatFace`]).
pub(crate) enum Surface<'a> {
    Fixed(BeamFace<'a>),
    Floating(FloatFace<'a>),
}

impl<'a> Surface<'a> {
    /// Scatter the beam's coordinates and velocities into the full-DOF buffers `full` and
    /// build the surface of `face` on `path`.
    pub(crate) fn new(
        guide: GuideRef,
        q: &[f64],
        qd: &[f64],
        (path, face): (&'a Path, Face),
        (u, ud): (&'a mut Vec<f64>, &'a mut Vec<f64>),
    ) -> Self {
        match guide {
            GuideRef::Fixed(fb) => {
                u.fill(0.0);
                ud.fill(0.0);
                for (a, &d) in fb.free.iter().enumerate() {
                    u[d] = q[fb.offset + a];
                    ud[d] = qd[fb.offset + a];
                }
                Surface::Fixed(BeamFace {
                    path,
                    face,
                    q: u,
                    qd: ud,
                })
            }
            GuideRef::Floating(fl) => {
                fl.full_displacements(q, qd, u, ud);
                let o = fl.offset;
                Surface::Floating(FloatFace {
                    local: BeamFace {
                        path,
                        face,
                        q: u,
                        qd: ud,
                    },
                    origin: Vector2::new(q[o], q[o + 1]),
                    angle: q[o + 2],
                    velocity: Vector2::new(qd[o], qd[o + 1]),
                    omega: qd[o + 2],
                })
            }
        }
    }

    fn inner(&self) -> &dyn GuideSurface {
        match self {
            Surface::Fixed(f) => f,
            Surface::Floating(f) => f,
        }
    }
}

impl GuideSurface for Surface<'_> {
    fn arc_range(&self) -> (f64, f64) {
        self.inner().arc_range()
    }
    fn point(&self, s: f64) -> Vector2<f64> {
        self.inner().point(s)
    }
    fn tangent(&self, s: f64) -> Vector2<f64> {
        self.inner().tangent(s)
    }
    fn normal(&self, s: f64) -> Vector2<f64> {
        self.inner().normal(s)
    }
    fn velocity(&self, s: f64) -> Vector2<f64> {
        self.inner().velocity(s)
    }
}

/// Add a world force `force` (N) acting on the face `(path, face, u)` of a beam (u: its full-DOF
/// displacements) at arc coordinate s, world point `point`, as work-equivalent nodal loads
/// (clr-beam `surface_load_row`) on a ground-fixed beam's free DOF, or through
/// `FloatingBody::add_point_force` on a floating body's (R, θ, q_f).
pub(crate) fn add_face_load(
    guide: GuideRef,
    (path, face, u): (&Path, Face, &[f64]),
    (s, point): (f64, Vector2<f64>),
    force: Vector2<f64>,
    q: &[f64],
    qf: &mut [f64],
) {
    let Ok(row) = path.surface_load_row(s, face, u) else {
        return;
    };
    match guide {
        GuideRef::Fixed(fb) => {
            for k in 0..6 {
                if let Some(fi) = fb.free_index[row.dofs[k]] {
                    qf[fb.offset + fi] += row.fx[k] * force.x + row.fy[k] * force.y;
                }
            }
        }
        GuideRef::Floating(fl) => fl.add_point_force(q, point, &row, force, qf),
    }
}
