//! Mass properties of common parts from their dimensions and material, as Exudyn's
//! `InertiaCuboid`, `InertiaRodX`, `InertiaCylinder` and `InertiaHollowCylinder`
//! (exudyn.rigidBodyUtilities) give them: the mass m (kg) and the planar moment of inertia
//! I_zz (kg·m²) about the centre of mass and the body z axis (normal to the plane of motion).
//! Every part is homogeneous and its centre of mass is its geometric centre.
//!
//! Formulas (J.L. Meriam, L.G. Kraige, *Engineering Mechanics: Dynamics*, Appendix D, Table D/4
//! "Properties of homogeneous solids"; the same in Exudyn's classes above):
//! - rectangular prism (bar, plate, box) of sides a (body x), b (body y), c (body z):
//!   m = ρabc, I_zz = m(a² + b²)/12;
//! - solid circular cylinder (round rod) of length L along body x and radius r:
//!   m = ρπr²L, I_zz = m(3r² + L²)/12 (transverse axis through the centre);
//! - hollow circular cylinder (tube) of length L along body x, outer radius R, inner radius r:
//!   m = ρπ(R² − r²)L, I_zz = m(3(R² + r²) + L²)/12;
//! - disc of radius r and thickness t, its axis along body z (normal to the plane):
//!   m = ρπr²t, I_zz = m r²/2.
//!
//! A leaf module: it depends only on [`crate::field`], so the description, the element
//! compiler and the Python extension all use the one definition here.

use serde::{Deserialize, Serialize};

/// Mass properties of a part: what a `[[body]]` needs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MassProperties {
    /// Mass m, kg.
    pub mass: f64,
    /// Moment of inertia I_zz about the centre of mass and the body z axis, kg·m².
    pub inertia: f64,
    /// Centre of mass in the part's frame (its geometric centre), m.
    pub centre_of_mass: [f64; 2],
}

/// A dimension or density that cannot describe a part.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct InertiaError {
    /// The field at fault, relative to the part (`length`, `inner_diameter`, `density`,
    /// `material`).
    pub field: &'static str,
    /// What is wrong and what to change.
    pub message: String,
}

impl InertiaError {
    fn new(field: &'static str, message: String) -> Self {
        Self { field, message }
    }
}

/// A named material: its density and where the value comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Name as written in a model file (`material = "steel"`).
    pub name: &'static str,
    /// Density ρ, kg/m³.
    pub density: f64,
    /// The grade the value stands for and its source.
    pub source: &'static str,
}

/// The named materials, with typical room-temperature densities. A real part's alloy may
/// differ by a few per cent; give `density` (kg/m³) for a measured or specified value.
pub const MATERIALS: [Material; 7] = [
    Material {
        name: "steel",
        density: 7850.0,
        source: "structural and carbon steel, EN 1993-1-1 (Eurocode 3) §3.2.6",
    },
    Material {
        name: "stainless steel",
        density: 8000.0,
        source: "austenitic AISI 304 (1.4301), MatWeb/ASM typical value 8.00 g/cm³",
    },
    Material {
        name: "aluminium",
        density: 2700.0,
        source: "wrought aluminium alloys (e.g. 6061-T6), EN 1999-1-1 (Eurocode 9) §3.2.5",
    },
    Material {
        name: "titanium",
        density: 4430.0,
        source: "Ti-6Al-4V (grade 5), MatWeb/ASM typical value 4.43 g/cm³",
    },
    Material {
        name: "brass",
        density: 8500.0,
        source: "free-cutting brass C36000, MatWeb/CDA typical value 8.50 g/cm³",
    },
    Material {
        name: "bronze",
        density: 8930.0,
        source: "bearing bronze C93200 (SAE 660), MatWeb/CDA typical value 8.93 g/cm³",
    },
    Material {
        name: "cast iron",
        density: 7200.0,
        source: "grey cast iron, EN 1561 typical value 7.2 g/cm³",
    },
];

/// The material named `name`: case-insensitive, `_` and `-` read as spaces, `aluminum` and
/// `ti-6al-4v` accepted as spellings of `aluminium` and `titanium`.
///
/// # Errors
/// [`InertiaError`] at `material` with the closest name ("did you mean") and the list.
pub fn material(name: &str) -> Result<Material, InertiaError> {
    let key = name.trim().to_ascii_lowercase().replace(['_', '-'], " ");
    let key = match key.as_str() {
        "aluminum" => "aluminium",
        "ti 6al 4v" => "titanium",
        k => k,
    };
    if let Some(m) = MATERIALS.iter().find(|m| m.name == key) {
        return Ok(*m);
    }
    let names = MATERIALS.iter().map(|m| m.name);
    let list: Vec<String> = MATERIALS
        .iter()
        .map(|m| format!("{} ({} kg/m³)", m.name, m.density))
        .collect();
    let hint = match crate::field::closest(key, names) {
        Some(c) => format!("did you mean `{c}`? "),
        None => String::new(),
    };
    Err(InertiaError::new(
        "material",
        format!(
            "unknown material `{name}`; {hint}known: {}; or give `density` (kg/m³) instead",
            list.join(", ")
        ),
    ))
}

/// A density ρ (kg/m³) that is positive and finite.
fn check_density(density: f64) -> Result<(), InertiaError> {
    if density.is_finite() && density > 0.0 {
        return Ok(());
    }
    Err(InertiaError::new(
        "density",
        format!(
            "the density {density} kg/m³ must be positive and finite (steel 7850, aluminium \
             2700 kg/m³; a value in g/cm³ is 1000 times too small)"
        ),
    ))
}

/// A dimension (m) that is positive and finite.
fn dimension(field: &'static str, v: f64) -> Result<f64, InertiaError> {
    if v.is_finite() && v > 0.0 {
        return Ok(v);
    }
    Err(InertiaError::new(
        field,
        format!("the {field} {v} m must be positive and finite (a length in m)"),
    ))
}

fn centred(mass: f64, inertia: f64) -> MassProperties {
    MassProperties {
        mass,
        inertia,
        centre_of_mass: [0.0, 0.0],
    }
}

/// A homogeneous rectangular prism of sides `lx` (body x), `ly` (body y), `lz` (body z,
/// normal to the plane), m, and density ρ (kg/m³): m = ρ·lx·ly·lz, I_zz = m(lx² + ly²)/12
/// (Meriam & Kraige Table D/4; Exudyn `InertiaCuboid`).
///
/// # Errors
/// [`InertiaError`] at the first dimension or the density that is not positive and finite.
pub fn cuboid(lx: f64, ly: f64, lz: f64, density: f64) -> Result<MassProperties, InertiaError> {
    cuboid_named(("length", lx), ("width", ly), ("thickness", lz), density)
}

/// [`cuboid`] with the field names of the dimensions (for the error's place).
pub(crate) fn cuboid_named(
    x: (&'static str, f64),
    y: (&'static str, f64),
    z: (&'static str, f64),
    density: f64,
) -> Result<MassProperties, InertiaError> {
    let (a, b, c) = (
        dimension(x.0, x.1)?,
        dimension(y.0, y.1)?,
        dimension(z.0, z.1)?,
    );
    check_density(density)?;
    let m = density * a * b * c;
    Ok(centred(m, m * (a * a + b * b) / 12.0))
}

/// A homogeneous round rod (solid cylinder) of `length` along body x and `diameter` d, m, and
/// density ρ (kg/m³): m = ρπr²L, I_zz = m(3r² + L²)/12 with r = d/2, about the transverse axis
/// through the centre (Meriam & Kraige Table D/4; Exudyn `InertiaCylinder`).
///
/// # Errors
/// [`InertiaError`] at the first dimension or the density that is not positive and finite.
pub fn rod(length: f64, diameter: f64, density: f64) -> Result<MassProperties, InertiaError> {
    let (l, d) = (
        dimension("length", length)?,
        dimension("diameter", diameter)?,
    );
    check_density(density)?;
    let r = 0.5 * d;
    let m = density * std::f64::consts::PI * r * r * l;
    Ok(centred(m, m * (3.0 * r * r + l * l) / 12.0))
}

/// A homogeneous tube (hollow cylinder) of `length` along body x, `outer_diameter` D and
/// `inner_diameter` d < D, m, and density ρ (kg/m³): m = ρπ(R² − r²)L,
/// I_zz = m(3(R² + r²) + L²)/12 with R = D/2, r = d/2 (Meriam & Kraige Table D/4; Exudyn
/// `InertiaHollowCylinder`).
///
/// # Errors
/// [`InertiaError`] at the first dimension or the density that is not positive and finite,
/// or at `inner_diameter` when it is not below the outer diameter.
pub fn tube(
    length: f64,
    outer_diameter: f64,
    inner_diameter: f64,
    density: f64,
) -> Result<MassProperties, InertiaError> {
    let l = dimension("length", length)?;
    let d_o = dimension("outer_diameter", outer_diameter)?;
    let d_i = dimension("inner_diameter", inner_diameter)?;
    if d_i >= d_o {
        return Err(InertiaError::new(
            "inner_diameter",
            format!(
                "the inner diameter {d_i} m must be smaller than the outer diameter {d_o} m \
                 (a solid bar is a `rod`)"
            ),
        ));
    }
    check_density(density)?;
    let (r_o, r_i) = (0.5 * d_o, 0.5 * d_i);
    let m = density * std::f64::consts::PI * (r_o * r_o - r_i * r_i) * l;
    Ok(centred(
        m,
        m * (3.0 * (r_o * r_o + r_i * r_i) + l * l) / 12.0,
    ))
}

/// A homogeneous disc of `diameter` d and `thickness` t (along body z, so its axis is normal
/// to the plane of motion), m, and density ρ (kg/m³): m = ρπr²t, I_zz = m r²/2 with r = d/2
/// (Meriam & Kraige Table D/4; Exudyn `InertiaCylinder` with the axis along z).
///
/// # Errors
/// [`InertiaError`] at the first dimension or the density that is not positive and finite.
pub fn disc(diameter: f64, thickness: f64, density: f64) -> Result<MassProperties, InertiaError> {
    let (d, t) = (
        dimension("diameter", diameter)?,
        dimension("thickness", thickness)?,
    );
    check_density(density)?;
    let r = 0.5 * d;
    let m = density * std::f64::consts::PI * r * r * t;
    Ok(centred(m, 0.5 * m * r * r))
}

/// `shape = { bar = { ... } }` etc. of a `[[body]]`: a homogeneous part whose mass and inertia
/// the body takes from its dimensions and density; its centre (the centre of mass) is the body
/// frame's origin. A length left out of a bar, plate, rod or tube is the distance of the body's
/// `between` points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Shape {
    /// A rectangular bar: `length` along body x, `width` along body y, `thickness` along z.
    Bar(Prism),
    /// A plate lying in the plane of motion: `length` along body x, `width` along body y,
    /// `thickness` normal to the plane (along z); the same solid as `bar`.
    Plate(Prism),
    /// A box (cuboid): `size = [x, y, z]`, its sides along body x, y and z.
    Box(Cuboid),
    /// A round rod: `length` along body x, `diameter`.
    Rod(Rod),
    /// A tube: `length` along body x, `outer_diameter`, `inner_diameter`.
    Tube(Tube),
    /// A disc with its axis normal to the plane: `diameter`, `thickness` (along z).
    Disc(Disc),
}

/// `bar` and `plate`: sides `length` (body x), `width` (body y), `thickness` (z), m.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Prism {
    /// Length along body x, m (left out: the distance of the body's `between` points).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// Width along body y, m.
    pub width: f64,
    /// Thickness along body z (normal to the plane), m.
    pub thickness: f64,
}

/// `box`: `size = [x, y, z]`, m.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cuboid {
    /// Sides along body x, y and z, m.
    pub size: [f64; 3],
}

/// `rod`: `length` (body x) and `diameter`, m.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rod {
    /// Length along body x, m (left out: the distance of the body's `between` points).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// Diameter, m.
    pub diameter: f64,
}

/// `tube`: `length` (body x), `outer_diameter` and `inner_diameter`, m.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tube {
    /// Length along body x, m (left out: the distance of the body's `between` points).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// Outer diameter, m.
    pub outer_diameter: f64,
    /// Inner diameter, m (< outer).
    pub inner_diameter: f64,
}

/// `disc`: `diameter` and `thickness` (along z), m.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Disc {
    /// Diameter, m.
    pub diameter: f64,
    /// Thickness along body z (normal to the plane), m.
    pub thickness: f64,
}

/// Relative difference between a given length and the distance of the `between` points below
/// which the two are the same number (both written to ~15 digits agree far better).
pub const LENGTH_TOLERANCE: f64 = 1e-9;

/// Largest relative difference between a given length and the distance of the `between`
/// points that is accepted: ends read off a drawing to a few digits differ by 1e-4 or so, and
/// the given length is then used (with a note) while the assembly of the initial conditions
/// corrects the pose. Beyond it the points belong to another link, or the length is wrong.
pub const LENGTH_DRAWING_TOLERANCE: f64 = 0.05;

impl Shape {
    /// The kind as written in a file (`bar`).
    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Bar(_) => "bar",
            Shape::Plate(_) => "plate",
            Shape::Box(_) => "box",
            Shape::Rod(_) => "rod",
            Shape::Tube(_) => "tube",
            Shape::Disc(_) => "disc",
        }
    }

    /// The length field of a bar, plate, rod or tube (`None` when left out or for a box or
    /// disc, which have none); `Err(())` for a box or disc.
    fn length_field(&self) -> Result<Option<f64>, ()> {
        match self {
            Shape::Bar(p) | Shape::Plate(p) => Ok(p.length),
            Shape::Rod(r) => Ok(r.length),
            Shape::Tube(t) => Ok(t.length),
            Shape::Box(_) | Shape::Disc(_) => Err(()),
        }
    }

    /// The length used: the given one, checked against the distance `span` of the `between`
    /// points (m) to [`LENGTH_DRAWING_TOLERANCE`] relative, or `span` when left out. `None`
    /// for a box or disc.
    ///
    /// # Errors
    /// [`InertiaError`] at `length` when it is left out without `between` or disagrees with it.
    pub fn length(&self, span: Option<f64>) -> Result<Option<f64>, InertiaError> {
        let Ok(given) = self.length_field() else {
            return Ok(None);
        };
        match (given, span) {
            (Some(l), Some(d)) if (l - d).abs() > LENGTH_DRAWING_TOLERANCE * d => {
                Err(InertiaError::new(
                    "length",
                    format!(
                        "the length {l} m differs from the distance {d:e} m of the `between` \
                         points by {:.3e} relative (more than {LENGTH_DRAWING_TOLERANCE}): \
                         correct one of them, or leave `length` out to take the distance",
                        (l - d).abs() / d
                    ),
                ))
            }
            (Some(l), _) => Ok(Some(l)),
            (None, Some(d)) => Ok(Some(d)),
            (None, None) => Err(InertiaError::new(
                "length",
                format!(
                    "a {} needs its `length` (m), or the body's `between` points to take it from",
                    self.kind()
                ),
            )),
        }
    }

    /// Mass properties of the part with density ρ (kg/m³); `span` is the distance of the
    /// body's `between` points, m, if any ([`Shape::length`]).
    ///
    /// # Errors
    /// [`InertiaError`] at the field (relative to the shape's kind table) that is invalid.
    pub fn mass_properties(
        &self,
        density: f64,
        span: Option<f64>,
    ) -> Result<MassProperties, InertiaError> {
        let length = self.length(span)?.unwrap_or(f64::NAN);
        match self {
            Shape::Bar(p) | Shape::Plate(p) => cuboid_named(
                ("length", length),
                ("width", p.width),
                ("thickness", p.thickness),
                density,
            ),
            Shape::Box(b) => cuboid_named(
                ("size", b.size[0]),
                ("size", b.size[1]),
                ("size", b.size[2]),
                density,
            ),
            Shape::Rod(r) => rod(length, r.diameter, density),
            Shape::Tube(t) => tube(length, t.outer_diameter, t.inner_diameter, density),
            Shape::Disc(d) => disc(d.diameter, d.thickness, density),
        }
    }
}

/// Where a link placed by its two ends `a` and `b` (world coordinates, m) stands: its body
/// frame at the midpoint (a + b)/2 with the x axis from `a` to `b`, so that in the body frame
/// end `a` is at [−L/2, 0] and end `b` at [L/2, 0] (L = |b − a|), and the centre of a shape is
/// the frame origin.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Placement {
    /// Body frame origin, m: the midpoint (a + b)/2.
    pub position: [f64; 2],
    /// Angle of the body x axis, rad: atan2(b_y − a_y, b_x − a_x).
    pub angle: f64,
    /// Distance L = |b − a|, m.
    pub length: f64,
}

/// The [`Placement`] of a link between `a` and `b` (m).
///
/// # Errors
/// [`InertiaError`] at `between` when a coordinate is not finite or the points coincide.
pub fn between(a: [f64; 2], b: [f64; 2]) -> Result<Placement, InertiaError> {
    if !a.iter().chain(&b).all(|v| v.is_finite()) {
        return Err(InertiaError::new(
            "between",
            format!("the points {a:?} and {b:?} must have finite coordinates (m)"),
        ));
    }
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length = dx.hypot(dy);
    if length == 0.0 {
        return Err(InertiaError::new(
            "between",
            format!(
                "the two points are the same, {a:?}: give the link's two ends, \
                 [[x1, y1], [x2, y2]] in m"
            ),
        ));
    }
    Ok(Placement {
        position: [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])],
        angle: dy.atan2(dx),
        length,
    })
}

#[cfg(test)]
mod tests {
    //! Each closed form against an independent formulation: a midpoint-rule integration of
    //! ∫(x² + y²) dm over the part's volume (the error of the composite midpoint rule is
    //! O(h²): with 400 cells a side, below 1e-5 relative), and the composite of the parallel-
    //! axis theorem (Steiner) for the tube.
    use super::*;

    /// ∫∫ρ t(x, y)(x² + y²) dx dy and ∫∫ρ t dx dy over [−a/2, a/2] × [−b/2, b/2] by the
    /// midpoint rule with `n` cells a side; `t(x, y)` is the part's extent along z.
    fn integrate(a: f64, b: f64, rho: f64, n: usize, t: impl Fn(f64, f64) -> f64) -> (f64, f64) {
        let (hx, hy) = (a / n as f64, b / n as f64);
        let (mut m, mut i) = (0.0, 0.0);
        for p in 0..n {
            let x = -0.5 * a + (p as f64 + 0.5) * hx;
            for q in 0..n {
                let y = -0.5 * b + (q as f64 + 0.5) * hy;
                let dm = rho * t(x, y) * hx * hy;
                m += dm;
                i += dm * (x * x + y * y);
            }
        }
        (m, i)
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    #[test]
    fn a_bar_agrees_with_integration_over_its_volume() {
        let p = cuboid(0.35, 0.02, 0.01, 7850.0).unwrap();
        let (m, i) = integrate(0.35, 0.02, 7850.0, 400, |_, _| 0.01);
        // the mass sums 160 000 equal cells: rounding grows to ~1e-12 relative
        assert!(close(p.mass, m, 1e-10), "{} vs {m}", p.mass);
        // the midpoint rule's error on x² is −(h²/12)/(L²/12) = −1/n² relative: 6e-6
        assert!(close(p.inertia, i, 1e-5), "{} vs {i}", p.inertia);
        // m = ρ·L·w·t in this order, as tests/data/four_bar_hand.toml writes it
        assert_eq!(p.mass, 7850.0 * 0.35 * 0.02 * 0.01);
    }

    #[test]
    fn a_rod_agrees_with_integration_over_its_volume() {
        // the chord of the circular section at height y is 2√(r² − y²): integrate over x
        // (along the rod) and y, with the extent along z as the thickness; I_zz about the
        // transverse z axis is ∫(x² + y²) dm
        let (l, d, rho) = (0.3, 0.04, 2700.0);
        let r = 0.5 * d;
        let p = rod(l, d, rho).unwrap();
        let (m, i) = integrate(l, d, rho, 2000, |_, y| {
            2.0 * (r * r - y * y).max(0.0).sqrt()
        });
        assert!(close(p.mass, m, 1e-4), "{} vs {m}", p.mass);
        assert!(close(p.inertia, i, 1e-4), "{} vs {i}", p.inertia);
    }

    #[test]
    fn a_tube_is_a_rod_minus_its_bore() {
        let (l, d_o, d_i, rho) = (0.25, 0.03, 0.02, 7850.0);
        let t = tube(l, d_o, d_i, rho).unwrap();
        let (outer, inner) = (rod(l, d_o, rho).unwrap(), rod(l, d_i, rho).unwrap());
        assert!(close(t.mass, outer.mass - inner.mass, 1e-13));
        assert!(close(t.inertia, outer.inertia - inner.inertia, 1e-13));
    }

    #[test]
    fn a_disc_agrees_with_integration_and_a_plate_is_a_bar() {
        let (d, th, rho) = (0.1, 0.01, 7850.0);
        let r = 0.5 * d;
        let p = disc(d, th, rho).unwrap();
        let (m, i) = integrate(d, d, rho, 2000, |x, y| {
            if x * x + y * y <= r * r {
                th
            } else {
                0.0
            }
        });
        assert!(close(p.mass, m, 1e-3), "{} vs {m}", p.mass);
        assert!(close(p.inertia, i, 1e-3), "{} vs {i}", p.inertia);
        // a box of two bars side by side: Steiner on each half (parallel-axis theorem)
        let whole = cuboid(0.2, 0.06, 0.01, rho).unwrap();
        let half = cuboid(0.2, 0.03, 0.01, rho).unwrap();
        let steiner = 2.0 * (half.inertia + half.mass * 0.015 * 0.015);
        assert!(close(whole.inertia, steiner, 1e-13));
    }

    #[test]
    fn bad_dimensions_and_materials_are_refused_at_their_field() {
        assert_eq!(cuboid(0.1, -0.02, 0.01, 7850.0).unwrap_err().field, "width");
        assert_eq!(rod(0.1, 0.01, 0.0).unwrap_err().field, "density");
        assert_eq!(
            tube(0.1, 0.02, 0.03, 7850.0).unwrap_err().field,
            "inner_diameter"
        );
        let e = material("stel").unwrap_err();
        assert!(e.message.contains("did you mean `steel`"), "{e}");
        assert!(e.message.contains("brass (8500 kg/m³)"), "{e}");
        assert_eq!(material("Stainless_Steel").unwrap().density, 8000.0);
        assert_eq!(material("aluminum").unwrap().density, 2700.0);
        assert_eq!(
            between([0.0, 0.0], [0.0, 0.0]).unwrap_err().field,
            "between"
        );
    }

    #[test]
    fn a_link_between_two_points_stands_at_their_midpoint() {
        let p = between([0.0, 0.0], [0.0, 0.1]).unwrap();
        assert_eq!(p.position, [0.0, 0.05]);
        assert_eq!(p.angle, std::f64::consts::FRAC_PI_2);
        assert_eq!(p.length, 0.1);
        let bar = |l: f64| {
            Shape::Bar(Prism {
                length: Some(l),
                width: 0.02,
                thickness: 0.01,
            })
        };
        // ends read off a drawing (within 5 %): the given length is used
        assert_eq!(bar(0.1004).length(Some(0.1)).unwrap(), Some(0.1004));
        // another link's points (6 % off): refused at `length`
        assert_eq!(bar(0.106).length(Some(0.1)).unwrap_err().field, "length");
    }
}
