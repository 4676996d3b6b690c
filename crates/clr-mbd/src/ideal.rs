//! Ideal counterparts of contact elements, used only to assemble the initial state.
//!
//! Published clearance-joint studies start from the state of the ideal mechanism: the journal
//! centred in its bearing (or at a stated eccentricity) and every velocity the ideal joints
//! imply (P. Flores, J. Ambrósio, J.C.P. Claro, H.M. Lankarani, *Kinematics and Dynamics of
//! Multibody Systems with Imperfect Joints*, Springer 2008, §4.6; the built-in models set it by
//! hand). A clearance joint is a force element, so without its counterpart the assembly of
//! initial conditions sees nothing that ties its two bodies together: a rocker connected to the
//! rest only through a clearance joint would keep ω = 0 and the run would start with an impact.
//!
//! During the assembly ([`Model::assemble_initial_state_with`](crate::Model)) each contact
//! element that has an ideal counterpart adds its rows as temporary constraints, in the metric
//! that keeps given coordinates:
//! - revolute clearance joint → revolute joint with the bearing point shifted by the initial
//!   eccentricity e₀ (in the bearing body's frame): two rows (A_i x̂)ᵀd = 0, (A_i ŷ)ᵀd = 0 with
//!   d = r_j + A_j s_j − r_i − A_i (s_i + e₀); written as two projections (not one 2-row
//!   coincidence) so that a redundant direction can be dropped alone;
//! - translational clearance joint → translational joint (slider axis parallel to the guide,
//!   slider centre on the guide's centre line shifted by e₀·ŷ_guide): one angle row and one
//!   normal-offset row;
//! - sliders on flexible guides and shape contacts have none (left as given: "untouched").
//!
//! The rows are removed after the assembly: they never act during the run.

use nalgebra::Vector2;

use crate::clearance::{Clearance, ClearanceKind};
use crate::runtime::{rot, Con};

/// Label suffix of the rows of an ideal counterpart (`J4 (ideal counterpart)`).
pub(crate) const SUFFIX: &str = "ideal counterpart";

/// The constraint rows of the ideal counterpart of contact element `c` with the initial offset
/// `offset` (revolute: the journal centre relative to the bearing centre in the bearing body's
/// frame, m; translational: `offset.y` is the slider centre's offset normal to the guide's
/// centre line, m), or `None` when the element has no ideal counterpart.
pub(crate) fn counterpart(c: &Clearance, offset: Vector2<f64>) -> Option<Vec<Con>> {
    let name = format!("{} ({SUFFIX})", c.name);
    match &c.kind {
        ClearanceKind::Revolute(g, _) => {
            let si = g.bearing_centre() + offset;
            let sj = g.journal_centre();
            Some(
                [Vector2::x(), Vector2::y()]
                    .into_iter()
                    .map(|w| Con::project(&name, c.i, si, c.j, sj, w, None))
                    .collect(),
            )
        }
        ClearanceKind::Translational {
            geometry,
            origin,
            angle,
            ..
        } => {
            let slider = geometry.slider();
            // the guide frame on body i: origin shifted across the guide by the offset
            let normal = rot(*angle, Vector2::y());
            let si = origin + offset.y * normal;
            Some(vec![
                Con::angle(&name, c.i, c.j, angle - slider.angle(), None),
                Con::project(&name, c.i, si, c.j, slider.centre(), normal, None),
            ])
        }
        ClearanceKind::FlexGuide(_) | ClearanceKind::Shapes(_) | ClearanceKind::FacePair(_) => None,
    }
}
