//! Planar translational clearance joint: a rectangular slider inside a straight rigid guide.
//!
//! Model of P. Flores, J. Ambrósio, J.C.P. Claro, H.M. Lankarani, "Translational joints with
//! clearance in rigid multibody systems", J. Comput. Nonlinear Dyn. 3 (2008) 011007: the slider
//! (length L, height h) moves between the two parallel guide surfaces a distance W > h apart. The
//! contact is detected at the four slider corners; each corner that crosses a guide surface is a
//! point contact with its own penetration, normal and velocities. Four configurations are
//! possible (paper, Fig. 3): free flight, one corner in contact, two adjacent corners on one
//! surface, and two opposite corners on opposite surfaces ([`Configuration`]).
//!
//! Frames: the guide frame is fixed on the guide body i at local point `guide_origin` with its x
//! axis at angle `guide_angle` (rad) from body i's x axis; the surfaces are the lines y = ±W/2 of
//! that frame (the guide is unbounded along x). The slider frame is the one of its
//! [`SliderShape`] on body j; the corners are (±L/2, ±h/2) in that frame, numbered
//! counter-clockwise from (−L/2, −h/2).
//!
//! Per active corner (conventions of `contact-laws.md` §3.1): the unit normal **n** points from
//! the channel into the wall it penetrates (+y of the guide frame for the upper surface, −y for
//! the lower one), **t** = k̂ × **n**; penetration δ = (distance of the corner beyond the surface);
//! the guide contact point is the corner moved back by δ **n**; v_N = (ṙ_corner − ṙ_guide)·**n** = δ̇
//! (> 0 approaching) and v_T = (ṙ_corner − ṙ_guide)·**t**; the force on the slider is
//! −F_N **n** + F_T **t** at the corner, the opposite force acts on the guide at its contact point.

use nalgebra::Vector2;

use crate::body::{
    check_finite, check_positive, rotate, BodyState, GeneralizedForce, PointContact,
};
use crate::error::ContactError;
use crate::multipoint::SliderShape;

/// Which of Flores et al.'s (2008) slider configurations the corners are in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Configuration {
    /// No corner touches a guide surface.
    FreeFlight,
    /// Exactly one corner penetrates a guide surface.
    OneCorner,
    /// Two corners penetrate the same guide surface (the slider face lies on that surface).
    TwoCornersOneSurface,
    /// Two corners penetrate opposite guide surfaces (the slider is jammed diagonally).
    TwoCornersOppositeSurfaces,
    /// Three or four corners penetrate: only reachable with penetrations comparable to the
    /// clearance, outside the validity of the point-contact model; the contacts are still
    /// reported.
    MoreCorners,
}

/// One of the two guide surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GuideSide {
    /// The surface y = +W/2 of the guide frame.
    Upper,
    /// The surface y = −W/2 of the guide frame.
    Lower,
}

/// An active corner contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerContact {
    /// Corner index 0..4, counter-clockwise from (−L/2, −h/2) of the slider frame.
    pub corner: usize,
    /// Guide surface the corner penetrates.
    pub side: GuideSide,
    /// Penetration, normal, tangent, contact points (the corner on the slider; the corner moved
    /// back by δ **n** on the guide) and relative velocities.
    pub contact: PointContact,
}

/// The corner contacts of a translational clearance joint at one state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TranslationalContact {
    /// Flores et al.'s configuration.
    pub configuration: Configuration,
    /// Contact of each corner (index = corner number), `None` when that corner does not penetrate.
    pub corners: [Option<CornerContact>; 4],
    guide_reference: Vector2<f64>,
    slider_reference: Vector2<f64>,
}

/// Forces of a translational clearance joint on its two bodies.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TranslationalForces {
    /// (F_N, F_T) applied at each corner, N (zero for inactive corners).
    pub corner_forces: [(f64, f64); 4],
    /// (f_x, f_y, m) on the guide body about its reference point.
    pub guide: GeneralizedForce,
    /// (f_x, f_y, m) on the slider body about its reference point.
    pub slider: GeneralizedForce,
}

/// Geometry of a translational clearance joint (module docs for the frames).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TranslationalClearance {
    slider: SliderShape,
    guide_width: f64,
    guide_origin: Vector2<f64>,
    guide_angle: f64,
}

impl TranslationalClearance {
    /// A slider `slider` (length L, height h, frame on body j) in a guide of inner width W > h
    /// (m) whose frame sits on body i at `guide_origin` (local, m) rotated by `guide_angle` (rad).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for a non-positive or non-finite width, for W ≤ h (no
    /// clearance), or for non-finite frame data.
    pub fn new(
        slider: SliderShape,
        guide_width: f64,
        guide_origin: Vector2<f64>,
        guide_angle: f64,
    ) -> Result<Self, ContactError> {
        const LAW: &str = "translational clearance joint";
        check_positive(LAW, &[("guide width W (m)", guide_width)])?;
        let h = slider.height();
        if guide_width <= h {
            return Err(ContactError::invalid(
                LAW,
                "guide width W (m)",
                guide_width,
                format!("must exceed the slider height h = {h} m so that the clearance W - h is positive"),
            ));
        }
        check_finite(
            LAW,
            &[
                ("guide origin, local x (m)", guide_origin.x),
                ("guide origin, local y (m)", guide_origin.y),
                ("guide angle (rad)", guide_angle),
            ],
        )?;
        Ok(Self {
            slider,
            guide_width,
            guide_origin,
            guide_angle,
        })
    }

    /// Total clearance W − h, m.
    pub fn clearance(&self) -> f64 {
        self.guide_width - self.slider.height()
    }

    /// The slider shape (its corners in body j's frame: [`SliderShape::body_corner`]).
    pub fn slider(&self) -> &SliderShape {
        &self.slider
    }

    /// World positions of the four corners, counter-clockwise from (−L/2, −h/2), m.
    pub fn corners(&self, slider: &BodyState) -> [Vector2<f64>; 4] {
        [0, 1, 2, 3].map(|k| self.slider.world_point(slider, self.slider.corner(k)))
    }

    /// Corner contacts and configuration at the given states of the guide body and slider body.
    pub fn contact(&self, guide: &BodyState, slider: &BodyState) -> TranslationalContact {
        let origin = guide.point(self.guide_origin);
        let axis_y = guide.rotate(rotate(self.guide_angle, Vector2::new(0.0, 1.0)));
        let half_w = 0.5 * self.guide_width;
        let mut corners = [None; 4];
        let (mut upper, mut lower) = (0usize, 0usize);
        for (k, p) in self.corners(slider).into_iter().enumerate() {
            let y = (p - origin).dot(&axis_y);
            let (side, penetration, normal) = if y > half_w {
                (GuideSide::Upper, y - half_w, axis_y)
            } else if y < -half_w {
                (GuideSide::Lower, -half_w - y, -axis_y)
            } else {
                continue;
            };
            match side {
                GuideSide::Upper => upper += 1,
                GuideSide::Lower => lower += 1,
            }
            let guide_point = p - penetration * normal;
            let v = slider.point_velocity(p) - guide.point_velocity(guide_point);
            corners[k] = Some(CornerContact {
                corner: k,
                side,
                contact: PointContact::new(penetration, normal, p, guide_point, v),
            });
        }
        let configuration = match (upper + lower, upper.min(lower)) {
            (0, _) => Configuration::FreeFlight,
            (1, _) => Configuration::OneCorner,
            (2, 0) => Configuration::TwoCornersOneSurface,
            (2, _) => Configuration::TwoCornersOppositeSurfaces,
            _ => Configuration::MoreCorners,
        };
        TranslationalContact {
            configuration,
            corners,
            guide_reference: guide.position,
            slider_reference: slider.position,
        }
    }
}

impl TranslationalContact {
    /// The active corner contacts.
    pub fn active(&self) -> impl Iterator<Item = &CornerContact> {
        self.corners.iter().flatten()
    }

    /// Generalized forces on guide and slider from a force rule `force(contact) -> (F_N, F_T)`
    /// (N) called once per active corner: −F_N **n** + F_T **t** on the slider at the corner,
    /// the opposite on the guide at its contact point. Inactive corners transmit nothing.
    pub fn generalized_forces(
        &self,
        mut force: impl FnMut(&CornerContact) -> (f64, f64),
    ) -> TranslationalForces {
        let mut out = TranslationalForces::default();
        for c in self.active() {
            let (f_n, f_t) = force(c);
            let f = c.contact.slider_force(f_n, f_t);
            out.corner_forces[c.corner] = (f_n, f_t);
            out.slider += GeneralizedForce::at(self.slider_reference, c.contact.slider_point, f);
            out.guide += GeneralizedForce::at(self.guide_reference, c.contact.guide_point, -f);
        }
        out
    }
}
