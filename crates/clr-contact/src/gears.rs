//! Contact shape of an external spur gear with involute teeth.
//!
//! [`InvoluteGear`] holds the usual gear data (module m, teeth z, pressure angle α, addendum
//! and dedendum coefficients, backlash thinning) and builds a [`Shape::Compound`] for
//! [`crate::shapes`]: a disc of the root radius plus one convex polygon per tooth.
//!
//! Geometry (Litvin & Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., Cambridge 2004,
//! ch. 10; ISO 21771:2007 for the names and the tooth-thickness formula):
//!
//! - pitch radius r_p = m z/2, base radius r_b = r_p cos α, tip radius r_a = r_p + h_a m,
//!   root radius r_f = r_p − h_f m (ISO 53 basic rack: α = 20°, h_a = 1, h_f = 1.25);
//! - involute function inv φ = tan φ − φ; at radius r ≥ r_b the profile angle α_r satisfies
//!   cos α_r = r_b/r, and the involute's roll angle is t = tan α_r;
//! - arc tooth thickness s(r) = 2r (s_p/(2r_p) + inv α − inv α_r) with s_p = π m/2 − j
//!   (j = this gear's backlash thinning at the pitch circle).
//!
//! Tooth k is centred on the body angle 2πk/z (tooth 0 symmetric about +x). Each flank is the
//! involute of the base circle from max(r_f, r_b) to r_a, sampled uniformly in the roll angle
//! t (the vertices lie exactly on the involute; the chords are the only approximation, see
//! [`InvoluteGear::max_chord_error`]). When r_f < r_b (fewer than 2 h_f/(1 − cos α) ≈ 41.5
//! teeth for the ISO rack) the flank continues radially from the base circle into the core:
//! a real hobbed gear has a trochoidal fillet (or an undercut) there, so the pair check in
//! [`centre_distance`] refuses pairs whose contact would reach below the involute.

use std::f64::consts::PI;

use crate::error::ContactError;
use crate::shapes::Shape;

const LAW: &str = "involute gear";

/// parry's `ConvexPolygon::from_convex_polyline` drops a vertex where the unit normals of the
/// two edges differ by less than acos(1 − √ε) ≈ 1.7e-4 rad, and keeps the first edge's
/// normal for the merged edge (not recomputed). Every vertex of a tooth polygon turns by more
/// than this angle (rad) so that parry keeps all of them and the edge normals stay exact.
const MIN_TURN: f64 = 1e-3;

/// Smallest roll-angle step between flank vertices, rad. Consecutive involute chords turn by
/// about the step; the first chord above the base circle turns by about 2/3 of the step
/// against the radial continuation, hence the factor 1.5.
const MIN_ROLL_STEP: f64 = 1.5 * MIN_TURN;

/// Fewest teeth accepted. Two teeth would each span almost half a turn and the tooth polygon
/// (closed by a chord inside the core disc) degenerates; the real limits (tip not pointed,
/// root radius > 0, teeth not overlapping) are checked one by one in
/// [`InvoluteGear::validate`].
const MIN_TEETH: u32 = 3;

/// Samples of the exact involute per chord when measuring the chord error.
const ERROR_SAMPLES: u32 = 64;

/// Most segments on the tip arc.
const MAX_TIP_SEGMENTS: u32 = 64;

/// inv φ = tan φ − φ, the involute function.
fn inv(phi: f64) -> f64 {
    phi.tan() - phi
}

/// inv α_r written with the roll angle t = tan α_r (better conditioned near the base circle).
fn inv_of_roll(t: f64) -> f64 {
    t - t.atan()
}

/// a (1 − f) + b f, exact at both ends.
fn lerp(a: f64, b: f64, f: f64) -> f64 {
    a * (1.0 - f) + b * f
}

/// Distance from `p` to the segment `[a, b]`, m.
fn distance_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (ab, ap) = ([b[0] - a[0], b[1] - a[1]], [p[0] - a[0], p[1] - a[1]]);
    let f = ((ap[0] * ab[0] + ap[1] * ab[1]) / (ab[0] * ab[0] + ab[1] * ab[1])).clamp(0.0, 1.0);
    (ap[0] - f * ab[0]).hypot(ap[1] - f * ab[1])
}

fn polar(r: f64, angle: f64) -> [f64; 2] {
    [r * angle.cos(), r * angle.sin()]
}

/// An external spur gear with involute teeth (standard, no profile shift), SI units.
///
/// Build it with [`InvoluteGear::new`] and the `with_*` setters, then call
/// [`InvoluteGear::shape`] once when the model is built.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InvoluteGear {
    /// Module m, m (pitch diameter / teeth).
    pub module: f64,
    /// Number of teeth z.
    pub teeth: u32,
    /// Pressure angle α at the pitch circle, rad (default 20°).
    pub pressure_angle: f64,
    /// Addendum coefficient h_a: tip radius = r_p + h_a m (default 1.0).
    pub addendum: f64,
    /// Dedendum coefficient h_f: root radius = r_p − h_f m (default 1.25).
    pub dedendum: f64,
    /// Circumferential thinning of this gear's tooth at the pitch circle, m (default 0). A
    /// pair with circumferential backlash j_t gives each gear j_t/2.
    pub backlash: f64,
    /// Vertices per flank on the involute (default 24, at least 2). Capped so that the roll
    /// step stays ≥ 1.5e-3 rad (see [`InvoluteGear::max_chord_error`]).
    pub points_per_flank: u32,
}

impl InvoluteGear {
    /// A standard gear of module `module` (m) with `teeth` teeth: α = 20°, h_a = 1,
    /// h_f = 1.25 (ISO 53 basic rack), no backlash, 24 points per flank.
    pub fn new(module: f64, teeth: u32) -> Self {
        Self {
            module,
            teeth,
            pressure_angle: 20f64.to_radians(),
            addendum: 1.0,
            dedendum: 1.25,
            backlash: 0.0,
            points_per_flank: 24,
        }
    }

    /// Set the pressure angle, rad.
    #[must_use]
    pub fn with_pressure_angle(mut self, pressure_angle: f64) -> Self {
        self.pressure_angle = pressure_angle;
        self
    }

    /// Set the addendum coefficient (× module).
    #[must_use]
    pub fn with_addendum(mut self, addendum: f64) -> Self {
        self.addendum = addendum;
        self
    }

    /// Set the dedendum coefficient (× module).
    #[must_use]
    pub fn with_dedendum(mut self, dedendum: f64) -> Self {
        self.dedendum = dedendum;
        self
    }

    /// Set this gear's tooth thinning at the pitch circle, m.
    #[must_use]
    pub fn with_backlash(mut self, backlash: f64) -> Self {
        self.backlash = backlash;
        self
    }

    /// Set the number of vertices per flank.
    #[must_use]
    pub fn with_points_per_flank(mut self, points_per_flank: u32) -> Self {
        self.points_per_flank = points_per_flank;
        self
    }

    /// Pitch radius r_p = m z/2, m.
    pub fn pitch_radius(&self) -> f64 {
        0.5 * self.module * f64::from(self.teeth)
    }

    /// Base radius r_b = r_p cos α, m.
    pub fn base_radius(&self) -> f64 {
        self.pitch_radius() * self.pressure_angle.cos()
    }

    /// Tip (addendum) radius r_a = r_p + h_a m, m.
    pub fn tip_radius(&self) -> f64 {
        self.pitch_radius() + self.addendum * self.module
    }

    /// Root (dedendum) radius r_f = r_p − h_f m, m.
    pub fn root_radius(&self) -> f64 {
        self.pitch_radius() - self.dedendum * self.module
    }

    /// Base pitch p_b = π m cos α, m: the distance between neighbouring flanks along the
    /// line of action.
    pub fn base_pitch(&self) -> f64 {
        PI * self.module * self.pressure_angle.cos()
    }

    /// Arc tooth thickness at the pitch circle s_p = π m/2 − j, m.
    pub fn pitch_thickness(&self) -> f64 {
        0.5 * PI * self.module - self.backlash
    }

    /// Arc tooth thickness at radius `r` (m), in m:
    /// s(r) = 2r (s_p/(2r_p) + inv α − inv α_r), cos α_r = r_b/r.
    ///
    /// For 0 < r < r_b (no involute there) it is 2r (s_p/(2r_p) + inv α), i.e. α_r = 0: the
    /// thickness of the shape's radial flank when r_f < r_b.
    pub fn tooth_thickness_at(&self, r: f64) -> f64 {
        2.0 * r * self.half_angle_of_roll(self.roll_at(r))
    }

    /// Roll angle t = tan α_r of the involute at radius `r`; 0 inside the base circle.
    fn roll_at(&self, r: f64) -> f64 {
        let q = r / self.base_radius();
        if q > 1.0 {
            ((q - 1.0) * (q + 1.0)).sqrt()
        } else {
            0.0
        }
    }

    /// Angle from the tooth centre line to the flank at roll angle `t`, rad.
    fn half_angle_of_roll(&self, t: f64) -> f64 {
        self.pitch_thickness() / (2.0 * self.pitch_radius()) + inv(self.pressure_angle)
            - inv_of_roll(t)
    }

    /// The point of the upper (`side` = 1) or lower (`side` = −1) flank of tooth 0 at roll
    /// angle `t`: exactly on the involute.
    fn flank_point(&self, t: f64, side: f64) -> [f64; 2] {
        polar(
            self.base_radius() * t.hypot(1.0),
            side * self.half_angle_of_roll(t),
        )
    }

    /// Roll angles of the flank vertices, uniform from max(r_f, r_b) to r_a: uniform in t
    /// keeps the chord error ≈ r_b t Δt²/8 nearly even (uniform in r would blow up at r_b,
    /// where the involute's curvature radius r_b t vanishes).
    fn flank_rolls(&self) -> Vec<f64> {
        let (t0, t1) = (
            self.roll_at(self.root_radius()),
            self.roll_at(self.tip_radius()),
        );
        // Saturating float-to-int cast: 0 when the flank is shorter than one step.
        let max_steps = ((t1 - t0) / MIN_ROLL_STEP).floor() as u32;
        let steps = self
            .points_per_flank
            .saturating_sub(1)
            .min(max_steps)
            .max(1);
        (0..=steps)
            .map(|i| lerp(t0, t1, f64::from(i) / f64::from(steps)))
            .collect()
    }

    /// Largest distance between the involute and its chords between `rolls`, m, sampling
    /// the involute at ERROR_SAMPLES points per chord.
    fn flank_chord_error(&self, rolls: &[f64]) -> f64 {
        let chord = |w: &[f64]| {
            let (a, b) = (self.flank_point(w[0], 1.0), self.flank_point(w[1], 1.0));
            (1..ERROR_SAMPLES)
                .map(|i| {
                    let t = lerp(w[0], w[1], f64::from(i) / f64::from(ERROR_SAMPLES));
                    distance_to_segment(self.flank_point(t, 1.0), a, b)
                })
                .fold(0.0, f64::max)
        };
        rolls.windows(2).map(chord).fold(0.0, f64::max)
    }

    /// Segments on the tip arc: enough for a sagitta r_a(1 − cos(ψ_a/k)) within `error`,
    /// few enough that each vertex turns by ≥ MIN_TURN (the arc angle per segment).
    fn tip_segments(&self, half_tip: f64, error: f64) -> u32 {
        let step = (1.0 - error / self.tip_radius()).clamp(-1.0, 1.0).acos();
        let wanted = (half_tip / step).ceil().min(f64::from(MAX_TIP_SEGMENTS)) as u32;
        let allowed = (2.0 * half_tip / MIN_TURN).floor() as u32;
        wanted.min(allowed).max(1)
    }

    /// Maximum chord (sagitta) error of the tooth outline, m: the largest distance between
    /// the exact involute flank and the polygon's chords (measured by sampling the involute
    /// at 64 points per chord, so it underestimates the exact maximum by < 0.1 %), or the
    /// sagitta of the tip-arc chords if larger.
    ///
    /// With n = `points_per_flank` vertices uniform in the roll angle t between t_0 (root or
    /// base circle) and t_a = tan α_a (tip), a chord spanning Δt = (t_a − t_0)/(n − 1) near
    /// roll t deviates by ≈ ρ Δt²/8 with the involute's curvature radius ρ = r_b t; the top
    /// chord (mean roll t_a − Δt/2) is the worst, so
    ///
    /// e_max ≈ r_b (t_a − Δt/2) Δt²/8, Δt = (t_a − t_0)/(n − 1),
    ///
    /// e.g. ≈ 1.0 µm for m = 2 mm, z = 20, α = 20°, n = 24; it falls as 1/n². The polygons
    /// lie inside the exact tooth (chords of a convex curve), so the shape's teeth are thinner
    /// than the exact ones by at most e_max per flank along the normal. The tip arc gets just
    /// enough segments for a sagitta ≤ the flank error.
    ///
    /// n is capped so that Δt ≥ 1.5e-3 rad: parry merges polygon edges whose normals differ
    /// by < 1.7e-4 rad, without recomputing the merged normal, so finer chords would break the
    /// exactness; the floor is e_max ≈ r_b t_a (1.5e-3)²/8 (≈ 3 nm for m = 2 mm, z = 20).
    /// Meaningful only for a gear that passes [`InvoluteGear::validate`].
    pub fn max_chord_error(&self) -> f64 {
        let rolls = self.flank_rolls();
        let flank = self.flank_chord_error(&rolls);
        let half_tip = self.half_angle_of_roll(rolls[rolls.len() - 1]);
        let k = self.tip_segments(half_tip, flank);
        let tip = self.tip_radius() * (1.0 - (half_tip / f64::from(k)).cos());
        flank.max(tip)
    }

    /// Vertices of tooth 0 (centred on +x), counter-clockwise, m: lower flank from the core
    /// up to the tip, tip arc, upper flank down, back into the core.
    fn tooth_polygon(&self) -> Vec<[f64; 2]> {
        let rolls = self.flank_rolls();
        let (t0, ta) = (rolls[0], rolls[rolls.len() - 1]);
        // Radial continuation of the flank into the core disc, so that the tooth overlaps
        // it (no crack between tooth and core at the root circle).
        let r_in = self.root_radius() - (0.25 * self.module).min(0.5 * self.root_radius());
        let half_low = self.half_angle_of_roll(t0);
        let half_tip = self.half_angle_of_roll(ta);
        let k = self.tip_segments(half_tip, self.flank_chord_error(&rolls));

        let mut pts = Vec::with_capacity(2 * rolls.len() + k as usize + 1);
        pts.push(polar(r_in, -half_low));
        pts.extend(rolls.iter().map(|&t| self.flank_point(t, -1.0)));
        pts.extend((1..k).map(|i| {
            let f = f64::from(i) / f64::from(k);
            polar(self.tip_radius(), lerp(-half_tip, half_tip, f))
        }));
        pts.extend(rolls.iter().rev().map(|&t| self.flank_point(t, 1.0)));
        pts.push(polar(r_in, half_low));
        pts
    }

    /// The gear's contact shape in its body frame (centre at the origin, m): a
    /// [`Shape::Compound`] of a core [`Shape::Ball`] of the root radius and one convex
    /// polygon per tooth, tooth k at the part pose `[0, 0, 2πk/z]` (tooth 0 symmetric about
    /// +x). Validates the gear first.
    pub fn shape(&self) -> Result<Shape, ContactError> {
        self.validate()?;
        let tooth = Shape::convex_polygon(self.tooth_polygon())?;
        let pitch_angle = 2.0 * PI / f64::from(self.teeth);
        let mut parts = Vec::with_capacity(self.teeth as usize + 1);
        parts.push(([0.0; 3], Shape::ball(self.root_radius())?));
        parts.extend(
            (0..self.teeth).map(|k| ([0.0, 0.0, pitch_angle * f64::from(k)], tooth.clone())),
        );
        Shape::compound(parts)
    }

    /// Check the data; the error names the offending value and what to change.
    ///
    /// Refused: module not > 0 and finite; fewer than 3 teeth; pressure angle outside
    /// (0, 45°); addendum not > 0; dedendum ≤ addendum (no tip clearance against a mate of
    /// the same proportions); root radius ≤ 0; backlash < 0 or ≥ π m/2; a pointed tooth (arc
    /// thickness at the tip circle ≤ 0); teeth overlapping at the root (no tooth space);
    /// fewer than 2 points per flank. The undercut/interference limit (z ≥ 2 h_a/sin²α ≈ 17
    /// against a rack) depends on the mate: [`centre_distance`] checks it for a pair.
    pub fn validate(&self) -> Result<(), ContactError> {
        self.validate_inputs()?;
        self.validate_geometry()
    }

    fn validate_inputs(&self) -> Result<(), ContactError> {
        let bad = |name, v, why: String| Err(ContactError::invalid(LAW, name, v, why));
        if !(self.module > 0.0 && self.module.is_finite()) {
            return bad("module (m)", self.module, "must be > 0 and finite".into());
        }
        if self.teeth < MIN_TEETH {
            return bad(
                "teeth",
                f64::from(self.teeth),
                format!("must be ≥ {MIN_TEETH}; give more teeth"),
            );
        }
        if !(self.pressure_angle > 0.0 && self.pressure_angle < PI / 4.0) {
            return bad(
                "pressure_angle (rad)",
                self.pressure_angle,
                "must be in (0, π/4) (0° to 45°, exclusive); 20° = 0.349 rad is standard".into(),
            );
        }
        if !(self.addendum > 0.0 && self.addendum.is_finite()) {
            return bad(
                "addendum (× module)",
                self.addendum,
                "must be > 0 and finite; 1.0 is standard".into(),
            );
        }
        if !(self.dedendum > self.addendum && self.dedendum.is_finite()) {
            return bad(
                "dedendum (× module)",
                self.dedendum,
                format!(
                    "must be finite and > the addendum {} so that a mate's tip clears the \
                     root circle; 1.25 is standard",
                    self.addendum
                ),
            );
        }
        if !(self.backlash >= 0.0 && self.backlash < 0.5 * PI * self.module) {
            return bad(
                "backlash (m)",
                self.backlash,
                format!(
                    "must be in [0, π m/2 = {:e} m) (the tooth thinning at the pitch circle)",
                    0.5 * PI * self.module
                ),
            );
        }
        if self.points_per_flank < 2 {
            return bad(
                "points_per_flank",
                f64::from(self.points_per_flank),
                "must be ≥ 2; 24 is the default".into(),
            );
        }
        Ok(())
    }

    fn validate_geometry(&self) -> Result<(), ContactError> {
        let z = f64::from(self.teeth);
        if self.root_radius() <= 0.0 {
            return Err(ContactError::invalid(
                LAW,
                "dedendum (× module)",
                self.dedendum,
                format!(
                    "gives a root radius r_p − h_f m = {:e} m ≤ 0; use a dedendum < z/2 = {} \
                     or more teeth",
                    self.root_radius(),
                    0.5 * z
                ),
            ));
        }
        let s_tip = self.tooth_thickness_at(self.tip_radius());
        if s_tip <= 0.0 {
            return Err(ContactError::invalid(
                LAW,
                "addendum (× module)",
                self.addendum,
                format!(
                    "gives a pointed tooth: arc thickness at the tip circle s_a = {s_tip:e} m \
                     ≤ 0; reduce the addendum, the pressure angle or the backlash, or add teeth"
                ),
            ));
        }
        // The tooth is widest where its involute starts (or on its radial part below r_b).
        let half_low = self.half_angle_of_roll(self.roll_at(self.root_radius()));
        if half_low >= PI / z {
            return Err(ContactError::invalid(
                LAW,
                "pressure_angle (rad)",
                self.pressure_angle,
                format!(
                    "makes neighbouring teeth overlap at the root: the tooth spans ±{half_low} \
                     rad, more than the half pitch π/z = {} rad; reduce the pressure angle or \
                     add teeth",
                    PI / z
                ),
            ));
        }
        Ok(())
    }
}

/// Standard centre distance a = m (z_a + z_b)/2 of an external pair, m.
///
/// Refuses gears that fail [`InvoluteGear::validate`] or cannot mesh as modelled: different
/// modules or pressure angles (relative difference > 1e-12); a tip that reaches the mate's
/// root circle (h_a of one ≥ h_f of the other); involute interference, i.e. a mate's tip
/// circle crossing the line of action below the start of the involute on the other gear's
/// flank (for r_f < r_b the shape's flank is radial there and would jam; a real gear would
/// be undercut; against a rack this needs z ≥ 2 h_a/sin²α ≈ 17.1 at α = 20°).
pub fn centre_distance(a: &InvoluteGear, b: &InvoluteGear) -> Result<f64, ContactError> {
    a.validate()?;
    b.validate()?;
    same("module (m)", a.module, b.module)?;
    same("pressure_angle (rad)", a.pressure_angle, b.pressure_angle)?;
    let dist = 0.5 * a.module * f64::from(a.teeth + b.teeth);
    for (g, mate) in [(a, b), (b, a)] {
        tip_clears_root(g, mate, dist)?;
        no_interference(g, mate, dist)?;
    }
    Ok(dist)
}

fn same(name: &'static str, x: f64, y: f64) -> Result<(), ContactError> {
    if (x - y).abs() <= 1e-12 * x.abs().max(y.abs()) {
        Ok(())
    } else {
        Err(ContactError::invalid(
            LAW,
            name,
            y,
            format!("differs between the two gears ({x} and {y}); a pair needs equal values"),
        ))
    }
}

fn tip_clears_root(g: &InvoluteGear, mate: &InvoluteGear, dist: f64) -> Result<(), ContactError> {
    if g.tip_radius() + mate.root_radius() < dist {
        return Ok(());
    }
    Err(ContactError::invalid(
        LAW,
        "addendum (× module)",
        g.addendum,
        format!(
            "the tip of the {}-tooth gear reaches the root circle of the {}-tooth mate; make \
             its addendum smaller than the mate's dedendum {}",
            g.teeth, mate.teeth, mate.dedendum
        ),
    ))
}

/// The mate's tip circle meets the line of action at a distance
/// a sin α − √(r_a,mate² − r_b,mate²) from g's base-tangent point; the involute of g starts at
/// r_b,g t_0 from it (roll angle t_0 of its lowest involute point).
fn no_interference(g: &InvoluteGear, mate: &InvoluteGear, dist: f64) -> Result<(), ContactError> {
    let (ra, rb) = (mate.tip_radius(), mate.base_radius());
    let reach = dist * g.pressure_angle.sin() - ((ra - rb) * (ra + rb)).sqrt();
    let start = g.base_radius() * g.roll_at(g.root_radius());
    if reach >= start {
        return Ok(());
    }
    Err(ContactError::invalid(
        LAW,
        "teeth",
        f64::from(g.teeth),
        format!(
            "involute interference: the tip of the {}-tooth mate reaches {:e} m below the \
             start of the involute on this gear's flank (along the line of action); add teeth \
             to this gear or reduce the mate's addendum",
            mate.teeth,
            start - reach
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::{BodyState, Vector2};
    use crate::shapes::{contact_points, ContactShape, ShapeContactWorkspace};
    use approx::assert_relative_eq;

    const MM: f64 = 1e-3;

    fn gear_20() -> InvoluteGear {
        InvoluteGear::new(2.0 * MM, 20)
    }

    fn tooth_points(g: &InvoluteGear) -> Vec<[f64; 2]> {
        match g.shape().unwrap() {
            Shape::Compound { parts } => match &parts[1].1 {
                Shape::ConvexPolygon { points } => points.clone(),
                other => panic!("tooth is {other:?}"),
            },
            other => panic!("gear is {other:?}"),
        }
    }

    /// Closed forms: r_p = m z/2, r_b = r_p cos α, r_a = r_p + m, r_f = r_p − 1.25 m,
    /// p_b = π m cos α (ISO 21771; Litvin & Fuentes 2004, ch. 10); the literals were
    /// evaluated separately (Python, double precision). Base thickness s_b = cos α (s_p +
    /// m z inv α) is the textbook form of s(r_b) for zero profile shift, a check of the
    /// roll-angle form used by `tooth_thickness_at`. Tolerance: a few f64 roundings.
    #[test]
    fn radii_and_base_pitch_closed_form() {
        let g = gear_20();
        let alpha = 20f64.to_radians();
        assert_relative_eq!(g.pitch_radius(), 0.020, max_relative = 1e-15);
        assert_relative_eq!(g.base_radius(), 0.020 * alpha.cos(), max_relative = 1e-15);
        assert_relative_eq!(
            g.base_radius(),
            0.018_793_852_415_718_17,
            max_relative = 1e-15
        );
        assert_relative_eq!(g.tip_radius(), 0.022, max_relative = 1e-15);
        assert_relative_eq!(g.root_radius(), 0.0175, max_relative = 1e-15);
        assert_relative_eq!(
            g.base_pitch(),
            5.904_262_868_187_099e-3,
            max_relative = 1e-13
        );
        assert_relative_eq!(g.tooth_thickness_at(0.020), PI * MM, max_relative = 1e-14);
        let s_b = alpha.cos() * (PI * MM + 2.0 * MM * 20.0 * inv(alpha));
        assert_relative_eq!(
            g.tooth_thickness_at(g.base_radius()),
            s_b,
            max_relative = 1e-14
        );
        let thin = g.with_backlash(0.05 * MM);
        assert_relative_eq!(thin.tooth_thickness_at(0.020), PI * MM - 0.05 * MM);
    }

    /// Every flank vertex at r ≥ r_b lies on the involute: its polar angle from the tooth
    /// centre line is s(r)/(2r), with s(r) recomputed here from r = |p| through
    /// α_r = acos(r_b/r) (the definition, not the roll form used to build the points).
    /// Tolerance 1e-12 relative: only roundings (the acos is ill-conditioned at r → r_b, but
    /// inv α_r ≈ α_r³/3 absorbs it).
    #[test]
    fn flank_vertices_lie_on_the_involute() {
        for g in [
            gear_20().with_backlash(0.05 * MM),
            InvoluteGear::new(1.0 * MM, 57).with_points_per_flank(7),
            InvoluteGear::new(3.0 * MM, 13).with_pressure_angle(25f64.to_radians()),
        ] {
            let (rb, rp, ra) = (g.base_radius(), g.pitch_radius(), g.tip_radius());
            let half_tip = g.tooth_thickness_at(ra) / (2.0 * ra);
            // The involute starts at the base circle or, if larger, the root circle.
            let r_low = rb.max(g.root_radius());
            let mut on_flank = 0;
            for p in tooth_points(&g) {
                let r = p[0].hypot(p[1]);
                let angle = p[1].atan2(p[0]).abs();
                let tip_arc = r > ra * (1.0 - 1e-12) && angle < half_tip * (1.0 - 1e-9);
                if r < r_low * (1.0 - 1e-12) || tip_arc {
                    continue; // radial continuation, root corner or tip arc
                }
                let alpha_r = (rb / r).min(1.0).acos();
                let half = g.pitch_thickness() / (2.0 * rp) + inv(g.pressure_angle) - inv(alpha_r);
                assert_relative_eq!(angle, half, max_relative = 1e-12);
                on_flank += 1;
            }
            assert!(on_flank >= 2 * 7, "{g:?}: {on_flank} flank vertices");
        }
    }

    /// Angle of the polygon's upper flank where it crosses the circle of radius `r`.
    fn crossing_angle(points: &[[f64; 2]], r: f64) -> f64 {
        for w in points.windows(2) {
            let (a, b) = (w[0], w[1]);
            let (ra, rb) = (a[0].hypot(a[1]), b[0].hypot(b[1]));
            if a[1] > 0.0 && ra >= r && rb <= r {
                // |a + f (b − a)| = r.
                let d = [b[0] - a[0], b[1] - a[1]];
                let (qa, qb, qc) = (
                    d[0] * d[0] + d[1] * d[1],
                    2.0 * (a[0] * d[0] + a[1] * d[1]),
                    ra * ra - r * r,
                );
                let f = (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
                return (a[1] + f * d[1]).atan2(a[0] + f * d[0]);
            }
        }
        panic!("no crossing of r = {r}");
    }

    /// The polygon's arc thickness at the pitch circle, 2 r_p ψ, is π m/2 − j up to the chord
    /// error: the chords lie inside the involute by ≤ e along its normal, which makes an
    /// angle α with the circle's tangent at r_p, so each flank moves in by ≤ e/cos α along
    /// the circle (and never out).
    #[test]
    fn pitch_thickness_on_polygon_within_chord_error() {
        for (g, j) in [
            (gear_20(), 0.0),
            (gear_20().with_backlash(0.05 * MM), 0.05 * MM),
            (gear_20().with_points_per_flank(5), 0.0),
        ] {
            let measured = 2.0 * g.pitch_radius() * crossing_angle(&tooth_points(&g), 0.020);
            let exact = PI * 2.0 * MM / 2.0 - j;
            let tol = 2.0 * g.max_chord_error() / g.pressure_angle.cos();
            let short = exact - measured;
            assert!(
                short >= -1e-15 && short <= tol,
                "{g:?}: thinner by {short:e}, bound {tol:e}"
            );
        }
    }

    /// The measured chord error against the rustdoc's estimate r_b (t_a − Δt/2) Δt²/8 (t_0 = 0
    /// here: r_f < r_b); within 2 % (small-arc sagitta ρΔt²/8 with ρ at the top chord's mean
    /// roll; the curvature varies along the chord: 0.3 % off at n = 6).
    #[test]
    fn chord_error_matches_estimate() {
        for n in [6, 24, 100] {
            let g = gear_20().with_points_per_flank(n);
            let ta = g.roll_at(g.tip_radius());
            let dt = ta / f64::from(n - 1);
            let est = g.base_radius() * (ta - 0.5 * dt) * dt * dt / 8.0;
            let e = g.max_chord_error();
            assert!((e / est - 1.0).abs() < 0.02, "n {n}: {e:e} vs {est:e}");
        }
    }

    /// Turning angle at each vertex of a closed polygon, rad.
    fn turns(p: &[[f64; 2]]) -> impl Iterator<Item = f64> + '_ {
        let n = p.len();
        (0..n).map(move |i| {
            let (o, a, b) = (p[i], p[(i + 1) % n], p[(i + 2) % n]);
            let (e1, e2) = ([a[0] - o[0], a[1] - o[1]], [b[0] - a[0], b[1] - a[1]]);
            (e1[0] * e2[1] - e1[1] * e2[0]).atan2(e1[0] * e2[0] + e1[1] * e2[1])
        })
    }

    /// Gears across the range build shapes that pass `Shape::validate` and parry, and every
    /// tooth vertex turns by more than parry's merge angle acos(1 − √ε) ≈ 1.7e-4 rad (see
    /// MIN_TURN); the base-circle vertex turns by ≈ 2/3 of the roll step, hence the 0.6.
    #[test]
    fn shapes_valid_over_range() {
        let deg = f64::to_radians;
        for (z, alpha, n) in [
            (3, deg(20.0), 24),
            (6, deg(14.5), 2),
            (12, deg(30.0), 24),
            (20, deg(20.0), 5000),
            (41, deg(20.0), 24),
            (42, deg(20.0), 24),
            (200, deg(20.0), 24),
            (1000, deg(20.0), 24),
            (60, deg(30.0), 24),
        ] {
            let g = InvoluteGear::new(1.0 * MM, z)
                .with_pressure_angle(alpha)
                .with_points_per_flank(n);
            let shape = g.shape().unwrap_or_else(|e| panic!("{g:?}: {e}"));
            ContactShape::new(shape).unwrap();
            let pts = tooth_points(&g);
            let min = turns(&pts).fold(f64::INFINITY, f64::min);
            assert!(min > 0.6 * MIN_TURN, "{g:?}: min turn {min:e}");
        }
    }

    /// Maximum penetration (m, negative for a gap) over the contact points and the
    /// deepest point on gear 1 (world, m).
    fn deepest(
        g1: &ContactShape,
        th1: f64,
        g2: &ContactShape,
        a: f64,
        th2: f64,
        ws: &mut ShapeContactWorkspace,
    ) -> (f64, Vector2<f64>) {
        let p1 = BodyState::fixed(Vector2::zeros(), th1);
        let p2 = BodyState::fixed(Vector2::new(a, 0.0), th2);
        // 1 mm prediction: separated flanks are reported with their (negative) gap.
        let pts = contact_points(g1, &p1, g2, &p2, 1e-3, ws).unwrap();
        pts.iter().map(|p| (p.depth, p.point_a)).fold(
            (f64::NEG_INFINITY, Vector2::zeros()),
            |m, q| {
                if q.0 > m.0 {
                    q
                } else {
                    m
                }
            },
        )
    }

    /// Bisection of the sign change of `f` between `gap` (f < 0) and `over` (f > 0); returns
    /// the penetrating end once the bracket is below 1e-15 rad.
    fn bisect(mut f: impl FnMut(f64) -> f64, mut gap: f64, mut over: f64) -> f64 {
        assert!(f(gap) < 0.0 && f(over) > 0.0, "not bracketed");
        while (over - gap).abs() > 1e-15 {
            let mid = 0.5 * (gap + over);
            if f(mid) > 0.0 {
                over = mid;
            } else {
                gap = mid;
            }
        }
        over
    }

    /// Two standard gears (z1 = 20, z2 = 40, m = 2 mm, each thinned by j/2, j = 0.1 mm) at the
    /// standard centre distance. Gear 2's angle is θ2 = π − π/z2 − (z1/z2) θ1 + u (u = 0: a
    /// tooth space of gear 2 centred on the tooth of gear 1 that sits on the line of
    /// centres at θ1 = 0, a mirror-symmetric pose). For gear 1 turning counter-clockwise
    /// and driving, the drive flanks touch at u_d > 0, the coast flanks at u_c < 0.
    ///
    /// Exact involutes (Litvin & Fuentes 2004, ch. 10; ISO 21771): the circumferential
    /// backlash of a standard pair is the sum of the thinnings j, so u_d − u_c = j/r_p2, and
    /// by symmetry u_d = −u_c = j/(2 r_p2) at θ1 = 0; conjugate action keeps u_d constant as
    /// θ1 varies (θ2 advances by exactly −(z1/z2) Δθ1), and the contact point runs on the line
    /// of action (through the pitch point, tangent to both base circles).
    ///
    /// Polygon tolerance: the polygons lie inside the exact teeth and contain every point
    /// farther than e_i (chord error of gear i) from their involute, and a rotation δ of gear
    /// 2 moves its involute by r_b2 δ along the normal, so each touch angle is late by
    /// 0 ≤ Δu ≤ (e1 + e2)/r_b2. Hence (a) play · r_p2 ∈ j + [0, 2(e1 + e2)/cos α],
    /// (b) every u_d ∈ j/(2 r_p2) + [0, (e1 + e2)/r_b2], which bounds the error of the
    /// speed ratio between any two θ1 to (e1 + e2)/r_b2 of gear-2 angle. (c) The polygon
    /// contact point is where the polygons' gap vanishes; the exact gap x²/(2ρ) − δ (x along
    /// the flank from the line of action, 1/ρ = 1/ρ1 + 1/ρ2, exact penetration δ ≤ e1 + e2)
    /// is below it, so |x| ≤ √(2ρ(e1 + e2)) with ρ ≤ a sin α/4 (ρ1 + ρ2 = a sin α): the
    /// contact point slides along a chord, off the line by up to about half a chord, not by
    /// the chord error. 1e-12 m is added for the bisection and parry's roundings.
    #[test]
    fn mesh_backlash_ratio_and_line_of_action() {
        let j = 0.1 * MM;
        let g1 = InvoluteGear::new(2.0 * MM, 20).with_backlash(0.5 * j);
        let g2 = InvoluteGear::new(2.0 * MM, 40).with_backlash(0.5 * j);
        let a = centre_distance(&g1, &g2).unwrap();
        assert_relative_eq!(a, 0.060, max_relative = 1e-15);
        let (s1, s2) = (
            ContactShape::new(g1.shape().unwrap()).unwrap(),
            ContactShape::new(g2.shape().unwrap()).unwrap(),
        );
        let (alpha, rp2, rb2) = (g1.pressure_angle, g2.pitch_radius(), g2.base_radius());
        let e = g1.max_chord_error() + g2.max_chord_error();
        let late = e / rb2 + 1e-12;
        let off_line = (2.0 * (a * alpha.sin() / 4.0) * e).sqrt() + 1e-12;
        let pitch_point = Vector2::new(g1.pitch_radius(), 0.0);
        let mut ws = ShapeContactWorkspace::new();
        let mut drive = Vec::new();
        for frac in [0.0, 0.17, 0.41, 0.66, 0.93, 3.37] {
            let th1 = frac * 2.0 * PI / 20.0;
            let th2 = |u: f64| PI - PI / 40.0 - th1 * 20.0 / 40.0 + u;
            let mut depth = |u: f64| deepest(&s1, th1, &s2, a, th2(u), &mut ws).0;
            let u_d = bisect(&mut depth, 0.0, j / rp2);
            let u_c = bisect(&mut depth, 0.0, -j / rp2);
            drive.push(u_d);
            // (a) Free play at the pitch circle.
            let play = (u_d - u_c) * rp2 - j;
            let play_tol = 2.0 * e / alpha.cos() + 1e-12;
            assert!(
                (-1e-12..=play_tol).contains(&play),
                "θ1 {th1}: play − j = {play:e}"
            );
            // (b) Conjugate action: the same touch angle u on both sides for every θ1.
            for u in [u_d, -u_c] {
                let lag = u - j / (2.0 * rp2);
                assert!((-1e-12..=late).contains(&lag), "θ1 {th1}: lag {lag:e}");
            }
            // (c) Contact points on the lines of action (drive: direction (sin α, cos α)
            // through the pitch point; coast: its mirror about the line of centres).
            for (u, side) in [(u_d, 1.0), (u_c, -1.0)] {
                let (d, p) = deepest(&s1, th1, &s2, a, th2(u), &mut ws);
                assert!((0.0..1e-12).contains(&d), "θ1 {th1}: depth {d:e}");
                let r = p - pitch_point;
                let dist = (r.x * alpha.cos() - r.y * side * alpha.sin()).abs();
                assert!(dist <= off_line, "θ1 {th1}: {dist:e} off the line");
            }
        }
        // (b) restated: between any two θ1 the ratio is −z1/z2 within (e1 + e2)/r_b2.
        let (lo, hi) = drive
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &u| {
                (l.min(u), h.max(u))
            });
        assert!(
            hi - lo <= late,
            "drive touch angles spread by {:e}",
            hi - lo
        );
    }

    #[test]
    fn centre_distance_refusals() {
        let g = gear_20();
        assert_relative_eq!(
            centre_distance(&g, &InvoluteGear::new(2.0 * MM, 33)).unwrap(),
            2.0 * MM * 53.0 / 2.0
        );
        let bad = [
            InvoluteGear::new(2.5 * MM, 40),
            InvoluteGear::new(2.0 * MM, 40).with_pressure_angle(25f64.to_radians()),
            // Tip reaching the 20-tooth gear's root circle (h_a ≥ its h_f = 1.25).
            InvoluteGear::new(2.0 * MM, 40)
                .with_addendum(1.3)
                .with_dedendum(1.6),
            // A mate that fails its own validation.
            InvoluteGear::new(2.0 * MM, 40).with_addendum(f64::NAN),
        ];
        for (i, b) in bad.iter().enumerate() {
            assert!(centre_distance(&g, b).is_err(), "case {i} accepted");
            assert!(centre_distance(b, &g).is_err(), "case {i} swapped accepted");
        }
        // Below the rack undercut limit 2/sin²20° ≈ 17.1 against a large mate: refused.
        let small = InvoluteGear::new(1.0 * MM, 12);
        assert!(centre_distance(&small, &InvoluteGear::new(1.0 * MM, 100)).is_err());
        assert!(centre_distance(
            &InvoluteGear::new(1.0 * MM, 18),
            &InvoluteGear::new(1.0 * MM, 400)
        )
        .is_ok());
    }

    /// Each invalid input is refused by the check meant for it (the error names the
    /// parameter to change).
    #[test]
    fn invalid_gears_refused() {
        let g = gear_20();
        let (module, teeth, alpha) = ("module (m)", "teeth", "pressure_angle (rad)");
        let (ha, hf, j) = ("addendum (× module)", "dedendum (× module)", "backlash (m)");
        let bad = [
            (InvoluteGear::new(0.0, 20), module),
            (InvoluteGear::new(-1.0, 20), module),
            (InvoluteGear::new(f64::NAN, 20), module),
            (InvoluteGear::new(f64::INFINITY, 20), module),
            (InvoluteGear::new(1.0, 2), teeth),
            (g.with_pressure_angle(0.0), alpha),
            (g.with_pressure_angle(PI / 4.0), alpha),
            (g.with_pressure_angle(f64::NAN), alpha),
            (g.with_addendum(0.0), ha),
            (g.with_addendum(f64::NAN), ha),
            (g.with_dedendum(1.0), hf),
            (g.with_dedendum(f64::INFINITY), hf),
            // Root radius ≤ 0: 5 teeth, h_f = 2.6 > z/2.
            (
                InvoluteGear::new(1.0, 5)
                    .with_addendum(0.5)
                    .with_dedendum(2.6),
                hf,
            ),
            (g.with_backlash(-1e-6), j),
            (g.with_backlash(PI * MM), j),
            (g.with_backlash(f64::NAN), j),
            // Pointed tip: s(r_a) ≤ 0 with a long addendum.
            (g.with_addendum(2.0).with_dedendum(2.5), ha),
            // Thinned until the tip vanishes though the pitch thickness stays > 0.
            (g.with_backlash(2.5 * MM), ha),
            // Teeth overlapping below the base circle: at 44.9°, inv α = 0.213 exceeds
            // π/(2z) = 0.196 for 8 teeth (short addendum so the tip is not pointed first).
            (
                InvoluteGear::new(1.0, 8)
                    .with_pressure_angle(44.9f64.to_radians())
                    .with_addendum(0.05),
                alpha,
            ),
            (g.with_points_per_flank(1), "points_per_flank"),
        ];
        for (i, (b, expected)) in bad.iter().enumerate() {
            let e = b
                .validate()
                .expect_err(&format!("case {i} accepted: {b:?}"));
            match &e {
                ContactError::InvalidParameter { name, .. } => {
                    assert_eq!(name, expected, "case {i}: {e}")
                }
                other => panic!("case {i}: {other}"),
            }
            assert!(b.shape().is_err());
        }
        g.validate().unwrap();
    }
}
