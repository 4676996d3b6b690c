//! Translational clearance joint: a rectangular slider (length L, height h) inside a straight
//! guide of inner width W > h (Flores, Ambrósio, Claro & Lankarani, J. Comput. Nonlinear Dyn. 3
//! (2008) 011007; corners as point contacts, clr-contact `TranslationalClearance`).

use clr_contact::TranslationalClearance as Geometry;
use serde::{Deserialize, Serialize};

use super::{positive_length, slider_shape, Anchor, Compiler, Element};
use crate::clearance::{Clearance as Runtime, ClearanceKind};
use crate::desc::laws::{FrictionSpec, NormalSpec};
use crate::error::MbdError;

/// `type = "translational"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TranslationalClearance {
    /// Unique name.
    pub name: String,
    /// Guide frame origin (on body i): the guide centre line passes through it.
    pub guide: Anchor,
    /// Slider centre (on body j).
    pub slider: Anchor,
    /// Inner width W of the guide, m.
    pub guide_width: f64,
    /// Angle of the guide axis from the guide body's x axis, rad.
    #[serde(default)]
    pub guide_angle: f64,
    /// Slider length L along its axis, m.
    pub slider_length: f64,
    /// Slider height h across the guide, m (< W).
    pub slider_height: f64,
    /// Angle of the slider axis from the slider body's x axis, rad.
    #[serde(default)]
    pub slider_angle: f64,
    /// Normal-force law of each corner contact.
    pub normal: NormalSpec,
    /// Friction law of each corner contact (default none); `lugre` adds four bristle states (one
    /// per corner) to the model state.
    #[serde(default)]
    pub friction: FrictionSpec,
    /// Where the slider centre starts across the guide, m: its distance from the guide's centre
    /// line towards the guide frame's +y surface, at most (W − h)/2 in magnitude. Absent:
    /// centred wherever the assembly solves the slider's place (`[solver] initial_state =
    /// "ideal"`, the default), else where the given coordinates put it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_offset: Option<f64>,
}

impl Element for TranslationalClearance {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        let (i, gi) = c.anchor(name, "guide", &self.guide)?;
        let (j, sj) = c.anchor(name, "slider", &self.slider)?;
        c.distinct(name, i, j)?;
        for (field, v) in [
            ("guide_width", self.guide_width),
            ("slider_length", self.slider_length),
            ("slider_height", self.slider_height),
        ] {
            positive_length(name, field, v)?;
        }
        if let Some(e) = self.initial_offset {
            let half = 0.5 * (self.guide_width - self.slider_height);
            if !(e.is_finite() && e.abs() <= half) {
                return Err(MbdError::Invalid {
                    path: format!("{name}.initial_offset"),
                    message: format!(
                        "the initial offset {e:e} m must be finite and at most half the clearance \
                         (guide_width − slider_height)/2 = {half:e} m in magnitude"
                    ),
                });
            }
            c.initial_offsets
                .insert(name.clone(), nalgebra::Vector2::new(0.0, e));
        }
        if self.slider_height >= self.guide_width {
            return Err(MbdError::Invalid {
                path: format!("{name}.slider_height"),
                message: format!(
                    "the clearance guide_width − slider_height = {:e} m must be positive: make \
                     slider_height smaller than guide_width = {} m",
                    self.guide_width - self.slider_height,
                    self.guide_width
                ),
            });
        }
        let shape = slider_shape(
            name,
            [self.slider_length, self.slider_height],
            sj,
            self.slider_angle,
        )?;
        let geometry =
            Geometry::new(shape, self.guide_width, gi, self.guide_angle).map_err(|source| {
                MbdError::Contact {
                    item: name.clone(),
                    source,
                }
            })?;
        let normal = self.normal.build(&format!("{name}.normal"), None)?;
        let (friction, lugre) = crate::lugre::state::LuGreContact::split(
            self.friction.build_contact(&format!("{name}.friction"))?,
        );
        c.clearances.push(Runtime {
            name: name.clone(),
            i,
            j,
            kind: ClearanceKind::Translational {
                geometry,
                origin: gi,
                angle: self.guide_angle,
                width: self.guide_width,
            },
            normal,
            friction,
            mem: 0,
            lugre,
            film: None,
        });
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.guide, &self.slider]
    }
}
