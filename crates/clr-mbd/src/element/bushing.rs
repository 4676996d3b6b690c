//! Linear bushing from a ground point to a body point: a spring–damper with separate
//! stiffness and damping along the world x and y axes, F = −K (r_b − r_a) − C ṙ_b with
//! K = diag(k_x, k_y), C = diag(c_x, c_y) (the planar form of Adams' BUSHING with the ground as
//! the first part). With k_x = 0 it is a lateral support that leaves the axial motion free.

use nalgebra::Vector2;
use serde::{Deserialize, Serialize};

use super::{ground_load, non_negative, Anchor, Compiler, Element};
use crate::error::MbdError;
use crate::runtime::{ForceEl, GROUND_ID};

/// `type = "bushing"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Bushing {
    /// Unique name.
    pub name: String,
    /// Ground point (the bushing's rest position of `b`).
    pub a: Anchor,
    /// Body point.
    pub b: Anchor,
    /// Stiffness [k_x, k_y] along the world axes, N/m (default 0).
    #[serde(default)]
    pub stiffness: [f64; 2],
    /// Damping [c_x, c_y] along the world axes, N·s/m (default 0).
    #[serde(default)]
    pub damping: [f64; 2],
}

impl Element for Bushing {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        let (g, ga) = c.anchor(name, "a", &self.a)?;
        if g != GROUND_ID {
            return Err(MbdError::Invalid {
                path: format!("{name}.a"),
                message: "a bushing's first anchor must be on the ground (`body = \"ground\"` \
                          or a ground point); between two bodies use a spring_damper"
                    .into(),
            });
        }
        let (i, si) = c.anchor(name, "b", &self.b)?;
        if i == GROUND_ID {
            return Err(ground_load(name));
        }
        for (what, v) in [
            ("stiffness k_x (N/m)", self.stiffness[0]),
            ("stiffness k_y (N/m)", self.stiffness[1]),
            ("damping c_x (N·s/m)", self.damping[0]),
            ("damping c_y (N·s/m)", self.damping[1]),
        ] {
            non_negative(name, what, v)?;
        }
        let ([kx, ky], [cx, cy]) = (self.stiffness, self.damping);
        // a state-dependent load: differenced by the Jacobian fallback (state_free: false)
        c.forces.push(ForceEl::Force {
            name: name.clone(),
            i,
            si,
            state_free: false,
            f: std::sync::Arc::new(move |_, s| {
                let arm = s.rotate(si);
                let p = s.position + arm - ga;
                let v = s.point_velocity(s.position + arm);
                Vector2::new(-kx * p.x - cx * v.x, -ky * p.y - cy * v.y)
            }),
        });
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.a, &self.b]
    }
}
