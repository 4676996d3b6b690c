//! Translational clearance joint: a rectangular slider (length L, height h) inside a straight
//! guide of inner width W > h (Flores, Ambrósio, Claro & Lankarani, J. Comput. Nonlinear Dyn. 3
//! (2008) 011007; corners as point contacts, clr-contact `TranslationalClearance`).

use clr_contact::TranslationalClearance as Geometry;
use serde::{Deserialize, Serialize};

use super::{positive_length, slider_shape, Anchor, Compiler, Element};
use crate::clearance::{Clearance as Runtime, ClearanceKind};
use crate::desc::laws::{FrictionSpec, NormalSpec};
use crate::error::MbdError;
use crate::runtime::{rot, Con};

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

impl TranslationalClearance {
    /// The guide's and the slider's frame and arm (validated anchors on two bodies), with the
    /// guide width and slider size checked positive.
    fn ends(
        &self,
        c: &Compiler,
    ) -> Result<(usize, nalgebra::Vector2<f64>, usize, nalgebra::Vector2<f64>), MbdError> {
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
        Ok((i, gi, j, sj))
    }

    /// Whether the guide has no clearance (slider_height = guide_width): it is then the ideal
    /// translational joint ([`TranslationalClearance::compile_ideal`]).
    pub fn is_ideal(&self) -> bool {
        self.slider_height == self.guide_width
    }

    /// A guide of clearance 0 as the ideal translational joint, the rule of the flap built-in
    /// for revolute joints (a clearance of 0 makes the joint ideal): the slider centre on the
    /// guide's centre line and the slider axis along the guide axis, θ_j + slider_angle =
    /// θ_i + guide_angle (2 equations, Nikravesh 1988, eq. 5.15; the rows of the assembly's
    /// ideal counterpart, [`crate::ideal`], with no offset). Reaction columns `C.Fx`, `C.Fy`,
    /// `C.M` as a `[[joint]]`; the `normal` and `friction` laws act on nothing (said in the
    /// run's notes); the friction law is still checked and an offset is refused.
    ///
    /// Unlike a `[[joint]]` of type `translational`, which keeps the relative angle the bodies
    /// start with, a guide without clearance holds the slider aligned with it.
    pub(crate) fn compile_ideal(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        let (i, gi, j, sj) = self.ends(c)?;
        for (field, v) in [
            ("guide_angle", self.guide_angle),
            ("slider_angle", self.slider_angle),
        ] {
            if !v.is_finite() {
                return Err(MbdError::Invalid {
                    path: format!("{name}.{field}"),
                    message: format!("the angle {v} rad must be finite"),
                });
            }
        }
        if self.initial_offset.is_some_and(|e| e != 0.0) {
            return Err(MbdError::Invalid {
                path: format!("{name}.initial_offset"),
                message: "slider_height = guide_width makes this an ideal translational joint, \
                          which has no room for an offset: remove `initial_offset`, or give \
                          the guide a clearance"
                    .into(),
            });
        }
        self.friction.build_contact(&format!("{name}.friction"))?;
        let normal = rot(self.guide_angle, nalgebra::Vector2::y());
        c.cons.push(Con::project(name, i, gi, j, sj, normal, None));
        c.cons.push(Con::angle(
            name,
            i,
            j,
            self.guide_angle - self.slider_angle,
            None,
        ));
        c.notes.push(format!(
            "clearance `{name}` is 0 (slider_height = guide_width = {} m): run as an ideal \
             translational joint, the slider aligned with the guide (columns {name}.Fx, \
             {name}.Fy, {name}.M, no contact columns); its normal and friction laws are not used",
            self.guide_width
        ));
        Ok(())
    }
}

impl Element for TranslationalClearance {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        let (i, gi, j, sj) = self.ends(c)?;
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
                     slider_height smaller than guide_width = {} m (or equal to it for an ideal \
                     translational joint)",
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
