//! Revolute clearance joint: a journal (pin) of radius R_j on body j inside a bearing (hole) of
//! radius R_i on body i; a force element built on clr-contact (no constraint equation). The
//! radii are given once: the normal law takes them from here.

use clr_contact::wear::BearingProfile;
use clr_contact::RevoluteClearance as Geometry;
use serde::{Deserialize, Serialize};

use super::{positive_length, Anchor, Compiler, Element};
use crate::clearance::{Clearance as Runtime, ClearanceKind};
use crate::desc::laws::{FrictionSpec, NormalSpec};
use crate::error::MbdError;
use crate::runtime::Con;

/// `type = "revolute"` (files of older versions without `type` are read as this, with a
/// note).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RevoluteClearance {
    /// Unique name.
    pub name: String,
    /// Bearing centre (on body i).
    pub bearing: Anchor,
    /// Journal centre (on body j).
    pub journal: Anchor,
    /// Bearing radius R_i, m.
    pub bearing_radius: f64,
    /// Journal radius R_j, m (< R_i).
    pub journal_radius: f64,
    /// Normal-force law.
    pub normal: NormalSpec,
    /// Friction law (default none); `lugre` adds one bristle state to the model state.
    #[serde(default)]
    pub friction: FrictionSpec,
    /// Where this joint's force pair acts: `common_point` (both forces at the midpoint of the
    /// two contact points: action and reaction collinear, so the joint conserves the system's
    /// angular momentum, friction included) or `contact_points` (each force at its own body's
    /// contact point, Flores et al. 2004: the friction pair, δ apart along the normal, adds a
    /// moment δ·F_T, so angular momentum drifts by ∫δ·F_T dt). Absent: `[model]
    /// clearance_force_application`, itself `common_point` by default. Energy: both forms
    /// dissipate the same normal-damping and friction power to first order in δ.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub force_application: Option<crate::desc::parts::ForceApplicationDesc>,
    /// A worn bearing: its radial wear depth h_w (m, ≥ 0) at N ≥ 8 equally spaced angles
    /// φ_k = 2πk/N in the bearing body's frame (counter-clockwise from its x axis), the local
    /// bearing radius being R_i + h_w(φ) (clr-contact `BearingProfile`, docs/wear.md). Absent:
    /// a circular bearing; all zeros reproduce it bit for bit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bearing_wear: Option<Vec<f64>>,
    /// An oil film in the joint (a lubricated journal bearing, docs/lubrication.md): the
    /// hydrodynamic force of the Reynolds equation's closed forms acts at every eccentricity,
    /// and the dry `normal`/`friction` laws add to it once the surfaces touch. Absent: dry.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lubrication: Option<LubricationDesc>,
    /// Where the journal centre starts relative to the bearing centre, in the bearing body's
    /// frame: `[e_x, e_y]` (m) or `{ magnitude = e (m), angle = φ (rad, counter-clockwise from
    /// the bearing body's x axis) }`, with e at most the radial clearance. Absent: centred
    /// wherever the assembly solves the journal's place (`[solver] initial_state = "ideal"`,
    /// the default), else where the given coordinates put it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_eccentricity: Option<Eccentricity>,
}

/// An initial eccentricity of a revolute clearance joint (in the bearing body's frame).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Eccentricity {
    /// `[e_x, e_y]`, m.
    Vector([f64; 2]),
    /// `{ magnitude, angle }`: e (m, ≥ 0) at φ (rad) from the bearing body's x axis.
    Polar {
        /// e, m (≥ 0).
        magnitude: f64,
        /// φ, rad.
        angle: f64,
    },
}

impl Eccentricity {
    /// The vector (e_x, e_y) in the bearing body's frame, m.
    pub fn vector(&self) -> [f64; 2] {
        match *self {
            Eccentricity::Vector(v) => v,
            Eccentricity::Polar { magnitude, angle } => {
                [magnitude * angle.cos(), magnitude * angle.sin()]
            }
        }
    }
}

/// `lubrication = { model, viscosity, length, film_threshold, dry_threshold }` of a revolute
/// clearance joint (clr-contact `HydrodynamicBearing` and `Transition`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LubricationDesc {
    /// `short_bearing` (Ocvirk, L/D ≲ 0.5) or `long_bearing` (Sommerfeld with the half-film
    /// condition, L/D ≳ 2).
    pub model: LubricationModel,
    /// Dynamic viscosity μ of the lubricant, Pa·s (e.g. 0.04 for an ISO VG 46 oil at 40 °C).
    pub viscosity: f64,
    /// Axial length L of the bearing, m.
    pub length: f64,
    /// Film threshold h_t, m (> 0): below this minimum film thickness the film force is
    /// frozen at ε_t = 1 − h_t/c (the closed forms grow without bound as ε → 1); typically a
    /// few combined surface roughnesses.
    pub film_threshold: f64,
    /// Dry threshold h_d, m (< h_t, default 0): below it the dry contact law acts with full
    /// weight (at 0: from the first touch); between h_d and h_t it fades in smoothly.
    #[serde(default)]
    pub dry_threshold: f64,
}

/// The closed form of the film force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LubricationModel {
    /// Short bearing (Ocvirk).
    ShortBearing,
    /// Infinitely long bearing (Sommerfeld, Pinkus–Sternlicht).
    LongBearing,
}

impl RevoluteClearance {
    /// The film of a lubricated joint, validated at `lubrication.<field>`.
    fn film(&self, g: &Geometry) -> Result<Option<crate::clearance::Film>, MbdError> {
        let Some(l) = &self.lubrication else {
            return Ok(None);
        };
        let at = |e: clr_contact::ContactError| MbdError::Invalid {
            path: format!("{}.lubrication", self.name),
            message: e.to_string(),
        };
        let model = match l.model {
            LubricationModel::ShortBearing => clr_contact::lubrication::BearingModel::ShortBearing,
            LubricationModel::LongBearing => clr_contact::lubrication::BearingModel::LongBearing,
        };
        let bearing = clr_contact::lubrication::HydrodynamicBearing::for_joint(
            g,
            l.length,
            l.viscosity,
            model,
        )
        .map_err(at)?;
        let transition =
            clr_contact::lubrication::Transition::new(l.film_threshold, l.dry_threshold)
                .map_err(at)?;
        Ok(Some(crate::clearance::Film {
            bearing,
            transition,
        }))
    }
}

impl RevoluteClearance {
    /// Whether the joint has no clearance (journal_radius = bearing_radius): it is then the
    /// ideal revolute joint ([`RevoluteClearance::compile_ideal`]).
    pub fn is_ideal(&self) -> bool {
        self.journal_radius == self.bearing_radius
    }

    /// A joint of clearance 0 as the ideal revolute joint between the same points, the rule of
    /// the flap built-in (`clr-models` flap.rs: a clearance of 0 makes the joint ideal): the
    /// journal centre on the bearing centre (2 equations, Nikravesh 1988, eq. 5.11), with the
    /// reaction columns `C.Fx`, `C.Fy`, `C.M` of a `[[joint]]`. Its `normal` and `friction`
    /// laws act on nothing (said in the run's notes); the friction law is still checked, and a
    /// film, a worn bearing or an eccentricity, which need a clearance, are refused.
    pub(crate) fn compile_ideal(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        let (i, si) = c.anchor(name, "bearing", &self.bearing)?;
        let (j, sj) = c.anchor(name, "journal", &self.journal)?;
        c.distinct(name, i, j)?;
        positive_length(name, "bearing_radius", self.bearing_radius)?;
        let refuse = |field: &str, what: &str| MbdError::Invalid {
            path: format!("{name}.{field}"),
            message: format!(
                "journal_radius = bearing_radius makes this an ideal revolute joint, which has \
                 no {what}: remove `{field}`, or give the joint a clearance"
            ),
        };
        if self.lubrication.is_some() {
            return Err(refuse("lubrication", "oil film"));
        }
        if self.bearing_wear.is_some() {
            return Err(refuse("bearing_wear", "bearing surface to wear"));
        }
        if let Some(e) = &self.initial_eccentricity {
            if e.vector() != [0.0, 0.0] {
                return Err(refuse("initial_eccentricity", "eccentricity"));
            }
        }
        self.friction.build_contact(&format!("{name}.friction"))?;
        c.cons.push(Con::coincide(name, i, si, j, sj));
        c.notes.push(format!(
            "clearance `{name}` is 0 (journal_radius = bearing_radius = {} m): run as an ideal \
             revolute joint (columns {name}.Fx, {name}.Fy, {name}.M, no contact columns); its \
             normal and friction laws are not used",
            self.bearing_radius
        ));
        Ok(())
    }
}

impl Element for RevoluteClearance {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        let (i, si) = c.anchor(name, "bearing", &self.bearing)?;
        let (j, sj) = c.anchor(name, "journal", &self.journal)?;
        c.distinct(name, i, j)?;
        let (rb, rj) = (self.bearing_radius, self.journal_radius);
        positive_length(name, "bearing_radius", rb)?;
        positive_length(name, "journal_radius", rj)?;
        if rj >= rb {
            return Err(MbdError::Invalid {
                path: format!("{name}.journal_radius"),
                message: format!(
                    "the radial clearance bearing_radius − journal_radius = {:e} m must be \
                     positive: make journal_radius smaller than bearing_radius = {rb} m (or equal \
                     to it for an ideal revolute joint)",
                    rb - rj
                ),
            });
        }
        if let Some(e) = &self.initial_eccentricity {
            let v = e.vector();
            let size = v[0].hypot(v[1]);
            if !size.is_finite() || size > rb - rj {
                return Err(MbdError::Invalid {
                    path: format!("{name}.initial_eccentricity"),
                    message: format!(
                        "the initial eccentricity {size:e} m must be finite and at most the \
                         radial clearance bearing_radius − journal_radius = {:e} m (the journal \
                         would start inside the bearing wall); it is a length in m",
                        rb - rj
                    ),
                });
            }
            c.initial_offsets
                .insert(name.clone(), nalgebra::Vector2::new(v[0], v[1]));
        }
        let mut geometry = Geometry::new(rb, rj, si, sj).map_err(|source| MbdError::Contact {
            item: name.clone(),
            source,
        })?;
        if let Some(depths) = &self.bearing_wear {
            let profile = BearingProfile::new(depths.clone()).map_err(|e| MbdError::Invalid {
                path: format!("{name}.bearing_wear"),
                message: e.to_string(),
            })?;
            geometry = geometry.with_profile(profile);
        }
        let normal = self
            .normal
            .build(&format!("{name}.normal"), Some((rb, rj)))?;
        let film = self.film(&geometry)?;
        let (friction, lugre) = crate::lugre::state::LuGreContact::split(
            self.friction.build_contact(&format!("{name}.friction"))?,
        );
        if film.is_some() && lugre.is_some() {
            return Err(MbdError::Invalid {
                path: format!("{name}.friction"),
                message: "LuGre friction in a lubricated joint is not supported (its bristle \
                          states would slide through the film); use a stateless friction law"
                    .into(),
            });
        }
        c.clearances.push(Runtime {
            name: name.clone(),
            i,
            j,
            kind: ClearanceKind::Revolute(
                geometry,
                match self.force_application {
                    Some(a) => a.into(),
                    None => c.force_application,
                },
            ),
            normal,
            friction,
            mem: 0,
            lugre,
            film,
        });
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.bearing, &self.journal]
    }
}
