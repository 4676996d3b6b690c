//! The compiled form of the measures and their evaluation at one recorded row.

use std::collections::HashSet;

use nalgebra::Vector2;

use crate::error::MbdError;
use crate::results::unit_of;

use crate::runtime::{body_state, frame_rates, perp, rot, Frame, GROUND_ID};

/// Position, velocity or acceleration (of a point, or of a body's angle).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Quantity {
    Position,
    Velocity,
    Acceleration,
}

/// What one measure evaluates.
#[derive(Debug, Clone)]
pub(crate) enum MeasureEl {
    /// A point (frame, arm from the frame's reference point), relative to a body frame (frame,
    /// arm of that frame's drawing origin) or the world.
    Point {
        quantity: Quantity,
        at: (usize, Vector2<f64>),
        frame: Option<(usize, Vector2<f64>)>,
    },
    /// θ_body − θ_relative − offset and its rates.
    Angle {
        quantity: Quantity,
        body: usize,
        relative_to: usize,
        offset: f64,
    },
    /// |r_b − r_a| and its rate.
    Distance {
        a: (usize, Vector2<f64>),
        b: (usize, Vector2<f64>),
    },
    /// Σ m v and Σ (I ω + m (r − about) × v) over the listed rigid bodies (indices, mass,
    /// inertia about the centre of mass), and with `scales` the sums of the magnitudes.
    Momentum {
        bodies: Vec<(usize, f64, f64)>,
        about: Vector2<f64>,
        scales: bool,
    },
    /// Values copied from columns the run writes anyway (source names; their indices in the
    /// row are resolved by [`Measures::resolve`]), the first two rotated into a body frame
    /// when `rotate` is set (reaction forces).
    Copy {
        field: &'static str,
        sources: Vec<String>,
        index: Vec<usize>,
        rotate: Option<usize>,
    },
    /// Σ_k c_k · (|Π x| or Π x) over the terms (sources of each term, their indices in the row
    /// resolved by [`resolve`] among the run's columns and the earlier measures'; factor c_k
    /// and whether to take the absolute value).
    Combination {
        sources: Vec<Vec<String>>,
        index: Vec<Vec<usize>>,
        factors: Vec<(f64, bool)>,
        /// The column's unit is the common unit of the sources ([`resolve`] sets it).
        infer_unit: bool,
    },
}

/// One compiled measure: its columns (name, unit) and what it evaluates.
#[derive(Debug, Clone)]
pub(crate) struct CompiledMeasure {
    pub(crate) name: String,
    pub(crate) columns: Vec<(String, &'static str)>,
    pub(crate) el: MeasureEl,
}

/// Kinematics of one frame at one row: position, angle, velocity, angular velocity,
/// acceleration, angular acceleration (zero for the ground).
#[derive(Debug, Clone, Copy, Default)]
struct FrameKin {
    r: Vector2<f64>,
    th: f64,
    v: Vector2<f64>,
    w: f64,
    a: Vector2<f64>,
    al: f64,
}

/// The state of one recorded row: the frames and q, q̇, q̈.
pub(crate) struct Row<'a> {
    pub(crate) frames: &'a [Frame],
    pub(crate) q: &'a [f64],
    pub(crate) qd: &'a [f64],
    pub(crate) qdd: &'a [f64],
}

impl Row<'_> {
    fn frame(&self, k: usize) -> FrameKin {
        if k == GROUND_ID {
            return FrameKin::default();
        }
        let s = body_state(self.frames, k, self.q, self.qd);
        let (a, al) = frame_rates(self.frames, k, self.qdd);
        FrameKin {
            r: s.position,
            th: s.angle,
            v: s.velocity,
            w: s.angular_velocity,
            a,
            al,
        }
    }

    /// Position, velocity and acceleration of the point at arm `s` of frame `k` (world):
    /// r + R s, v + ω J R s, a + α J R s − ω² R s (J the rotation by +90°).
    fn point(&self, (k, s): (usize, Vector2<f64>)) -> [Vector2<f64>; 3] {
        let f = self.frame(k);
        let d = rot(f.th, s);
        let jd = perp(d);
        [f.r + d, f.v + f.w * jd, f.a + f.al * jd - f.w * f.w * d]
    }
}

/// The coordinates p = Rᵀ D of a world vector D(t) in a frame turning at (θ, ω, α), and their
/// derivatives ṗ = Rᵀ(Ḋ − ω J D), p̈ = Rᵀ(D̈ − α J D − 2ω J Ḋ − ω² D) (planar relative
/// kinematics, Nikravesh 1988, §2.6).
fn in_frame(th: f64, w: f64, al: f64, d: [Vector2<f64>; 3]) -> [Vector2<f64>; 3] {
    let back = |v: Vector2<f64>| rot(-th, v);
    [
        back(d[0]),
        back(d[1] - w * perp(d[0])),
        back(d[2] - al * perp(d[0]) - 2.0 * w * perp(d[1]) - w * w * d[0]),
    ]
}

impl CompiledMeasure {
    /// The offset of an angle measure, rad (for the plausibility checks).
    pub(crate) fn angle_offset(&self) -> Option<f64> {
        match self.el {
            MeasureEl::Angle {
                quantity: Quantity::Position,
                offset,
                ..
            } => Some(offset),
            _ => None,
        }
    }

    /// The body points it reads, with their fields (for the plausibility checks).
    pub(crate) fn points(&self) -> Vec<(&'static str, (usize, Vector2<f64>))> {
        match &self.el {
            MeasureEl::Point { at, .. } => vec![("at", *at)],
            MeasureEl::Distance { a, b } => vec![("a", *a), ("b", *b)],
            _ => Vec::new(),
        }
    }

    /// Append this measure's values at `row` to `out`, whose current row (the run's own
    /// columns, from `t` on, which copies read) starts at `row_start`.
    pub(crate) fn write(&self, row: &Row, out: &mut Vec<f64>, row_start: usize) {
        match &self.el {
            MeasureEl::Point {
                quantity,
                at,
                frame,
            } => {
                let mut p = row.point(*at);
                if let Some(f) = frame {
                    let o = row.point(*f);
                    let k = row.frame(f.0);
                    p = in_frame(k.th, k.w, k.al, [p[0] - o[0], p[1] - o[1], p[2] - o[2]]);
                }
                let v = p[*quantity as usize];
                out.extend_from_slice(&[v.x, v.y]);
            }
            MeasureEl::Angle {
                quantity,
                body,
                relative_to,
                offset,
            } => {
                let (b, r) = (row.frame(*body), row.frame(*relative_to));
                out.push(match quantity {
                    Quantity::Position => b.th - r.th - offset,
                    Quantity::Velocity => b.w - r.w,
                    Quantity::Acceleration => b.al - r.al,
                });
            }
            MeasureEl::Distance { a, b } => {
                let (pa, pb) = (row.point(*a), row.point(*b));
                let (d, dv) = (pb[0] - pa[0], pb[1] - pa[1]);
                let l = d.norm();
                out.extend_from_slice(&[l, if l > 0.0 { d.dot(&dv) / l } else { 0.0 }]);
            }
            MeasureEl::Momentum {
                bodies,
                about,
                scales,
            } => {
                let (mut p, mut l) = (Vector2::zeros(), 0.0);
                let (mut sp, mut sl) = (0.0, 0.0);
                for &(k, m, inertia) in bodies {
                    let f = row.frame(k);
                    p += m * f.v;
                    let r = f.r - about;
                    let (spin, orbit) = (inertia * f.w, m * (r.x * f.v.y - r.y * f.v.x));
                    l += spin + orbit;
                    sp += m * f.v.norm();
                    sl += spin.abs() + orbit.abs();
                }
                out.extend_from_slice(&[p.x, p.y, l]);
                if *scales {
                    out.extend_from_slice(&[sp, sl]);
                }
            }
            MeasureEl::Copy { index, rotate, .. } => {
                let start = out.len();
                for &i in index {
                    out.push(out[row_start + i]);
                }
                if let Some(k) = rotate {
                    let f = rot(-row.frame(*k).th, Vector2::new(out[start], out[start + 1]));
                    out[start] = f.x;
                    out[start + 1] = f.y;
                }
            }
            MeasureEl::Combination { index, factors, .. } => {
                let term = |k: usize| {
                    let x = (index[k].iter()).fold(1.0, |p, &i| p * out[row_start + i]);
                    let (c, abs) = factors[k];
                    c * if abs { x.abs() } else { x }
                };
                let sum = (1..index.len()).fold(term(0), |s, k| s + term(k));
                out.push(sum);
            }
        }
    }
}

/// Check the measures' columns against the run's own `columns` (no repeats) and find the
/// sources of the copies there.
pub(crate) fn resolve(
    measures: &mut [CompiledMeasure],
    columns: &[String],
) -> Result<(), MbdError> {
    let mut seen: HashSet<&str> = columns.iter().map(String::as_str).collect();
    for m in measures.iter() {
        for (c, _) in &m.columns {
            if !seen.insert(c) {
                return Err(MbdError::Invalid {
                    path: format!("{}.name", m.name),
                    message: format!(
                        "its column `{c}` is already written (by the model or another \
                         measure): give the measure another name"
                    ),
                });
            }
        }
    }
    let mut known = columns.to_vec();
    let mut units: Vec<&'static str> = columns.iter().map(|c| unit_of(c)).collect();
    for m in measures.iter_mut() {
        let name = &m.name;
        if let MeasureEl::Combination {
            sources,
            index,
            infer_unit,
            ..
        } = &mut m.el
        {
            *index = (sources.iter().enumerate())
                .map(|(k, s)| {
                    (s.iter())
                        .map(|c| {
                            known.iter().position(|x| x == c).ok_or_else(|| MbdError::Invalid {
                                path: format!("{name}.terms[{k}].of"),
                                message: format!(
                                    "the model and the measures before this one write no column                                      `{c}` (a `deviation` column is written after the run and                                      cannot be combined){}",
                                    near(&known, c)
                                ),
                            })
                        })
                        .collect::<Result<Vec<_>, _>>()
                })
                .collect::<Result<_, _>>()?;
            if *infer_unit {
                m.columns[0].1 = common_unit(name, sources, index, &units)?;
            }
        }
        known.extend(m.columns.iter().map(|(c, _)| c.clone()));
        units.extend(m.columns.iter().map(|(_, u)| *u));
        if let MeasureEl::Copy {
            field,
            sources,
            index,
            ..
        } = &mut m.el
        {
            *index = sources
                .iter()
                .map(|s| {
                    columns.iter().position(|c| c == s).ok_or_else(|| {
                        let known = copy_candidates(columns, s);
                        MbdError::Invalid {
                            path: format!("{name}.{field}"),
                            message: format!(
                                "the model writes no column `{s}`{}",
                                if known.is_empty() {
                                    String::new()
                                } else {
                                    format!("; it has {known}")
                                }
                            ),
                        }
                    })
                })
                .collect::<Result<_, _>>()?;
        }
    }
    Ok(())
}

/// The unit shared by the single-column terms of a combination (their columns at `index` in
/// the columns known, whose units are `units`), or the refusal saying to give one.
fn common_unit(
    name: &str,
    sources: &[Vec<String>],
    index: &[Vec<usize>],
    units: &[&'static str],
) -> Result<&'static str, MbdError> {
    let of: Vec<&'static str> = index.iter().flatten().map(|&i| units[i]).collect();
    if of.iter().all(|u| *u == of[0]) {
        return Ok(of[0]);
    }
    let listed: Vec<String> = (sources.iter().flatten().zip(&of))
        .map(|(c, u)| format!("{c} ({u})"))
        .collect();
    Err(MbdError::Invalid {
        path: format!("{name}.unit"),
        message: format!(
            "the terms' columns {} differ in unit: say the unit of the sum (`unit = \"N\"`, say)",
            listed.join(", ")
        ),
    })
}

/// `; similar: …` with up to 8 columns sharing the name's first or last part.
pub(crate) fn near(columns: &[String], of: &str) -> String {
    let head = of.split('.').next().unwrap_or(of);
    let tail = of.rsplit('.').next().unwrap_or(of);
    let near: Vec<&str> = (columns.iter())
        .filter(|c| c.starts_with(&format!("{head}.")) || c.ends_with(&format!(".{tail}")))
        .map(String::as_str)
        .take(8)
        .collect();
    if near.is_empty() {
        String::new()
    } else {
        format!("; similar: {}", near.join(", "))
    }
}

/// The items whose columns end like `source` does (`J.Fx` → `crank_pin, B`), for the error.
fn copy_candidates(columns: &[String], source: &str) -> String {
    let suffix = source.rsplit('.').next().unwrap_or(source);
    columns
        .iter()
        .filter_map(|c| c.strip_suffix(suffix)?.strip_suffix('.'))
        .map(|c| format!("`{c}`"))
        .collect::<Vec<_>>()
        .join(", ")
}
