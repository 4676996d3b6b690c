//! What moves: the recorded states of a run at the frames of the animation (part poses, beam
//! node displacements, clearance contact data), and the figures beside it, taken from the
//! result columns and decimated to a size limit. Numbers are stored as `f32` (7 digits: far
//! below a pixel at any zoom the page offers); displacements are stored relative to the
//! undeformed shape so that their own precision is kept for the magnification controls.

use std::collections::BTreeMap;

use clr_mbd::{Model, Results};
use serde::Serialize;

use super::scene::Scene;

/// Contact columns of a clearance element drawn per frame (`NAME.<column>`), when recorded.
const CONTACT_COLUMNS: &[&str] = &[
    "penetration",
    "normal_force",
    "friction_force",
    "contact",
    "ex",
    "ey",
];

/// The animation frames.
#[derive(Debug, Clone, Serialize)]
pub struct Frames {
    /// Frame times, s.
    pub t: Vec<f64>,
    /// Per part: [x, y, θ] of its centre of mass (m, rad) per frame, flattened.
    pub pose: Vec<Vec<f32>>,
    /// Per beam: the displacement [u, v] (m, world axes) of every node from its undeformed
    /// place (for a flexible body: from the undeformed mesh carried by its frame), per frame,
    /// flattened frame-major.
    pub nodes: Vec<Vec<f32>>,
    /// Per clearance element name: its contact columns per frame.
    pub contact: BTreeMap<String, BTreeMap<String, Vec<f32>>>,
}

/// One line of a figure.
#[derive(Debug, Clone, Serialize)]
pub struct Line {
    /// Legend.
    pub label: String,
    /// Abscissae.
    pub x: Vec<f32>,
    /// Ordinates.
    pub y: Vec<f32>,
}

/// A figure beside the animation; `cursor` says how the current time is marked (`time`: a
/// vertical line at t; `orbit`: a dot at the point of time t on each line).
#[derive(Debug, Clone, Serialize)]
pub struct Plot {
    /// Title.
    pub title: String,
    /// Abscissa label with unit.
    pub x_label: String,
    /// Ordinate label with unit.
    pub y_label: String,
    /// `time` or `orbit`.
    pub cursor: &'static str,
    /// For `orbit` plots: the time of each point of the lines, s.
    pub t: Vec<f32>,
    /// The lines.
    pub lines: Vec<Line>,
    /// True when the axes have equal scales (orbits).
    pub equal: bool,
}

/// Row indices of up to `max` frames at equal time steps over the run (the nearest recorded
/// row to each), every row when there are fewer.
pub fn select(t: &[f64], max: usize) -> Vec<usize> {
    if t.len() <= max || max < 2 {
        return (0..t.len()).collect();
    }
    let (t0, t1) = (t[0], t[t.len() - 1]);
    let mut rows = Vec::with_capacity(max);
    let mut r = 0;
    for k in 0..max {
        let tk = t0 + (t1 - t0) * k as f64 / (max - 1) as f64;
        while r + 1 < t.len() && (t[r + 1] - tk).abs() <= (t[r] - tk).abs() {
            r += 1;
        }
        if rows.last() != Some(&r) {
            rows.push(r);
        }
    }
    rows
}

/// Row indices keeping at most about `max` points of a time history while keeping its peaks:
/// per bucket of rows, the first, the smallest and the largest of `y`.
pub fn decimate(y: &[f64], max: usize) -> Vec<usize> {
    let n = y.len();
    if n <= max || max < 3 {
        return (0..n).collect();
    }
    let buckets = (max / 3).max(1);
    let size = n.div_ceil(buckets);
    let mut rows = Vec::with_capacity(3 * buckets + 1);
    for start in (0..n).step_by(size) {
        let end = (start + size).min(n);
        let (mut lo, mut hi) = (start, start);
        for r in start..end {
            if y[r] < y[lo] {
                lo = r;
            }
            if y[r] > y[hi] {
                hi = r;
            }
        }
        let mut b = [start, lo, hi];
        b.sort_unstable();
        for r in b {
            if rows.last() != Some(&r) {
                rows.push(r);
            }
        }
    }
    if rows.last() != Some(&(n - 1)) {
        rows.push(n - 1);
    }
    rows
}

fn pick(v: &[f64], rows: &[usize]) -> Vec<f32> {
    rows.iter().map(|&r| v[r] as f32).collect()
}

impl Frames {
    /// The frames of `results` at `rows` for `scene`; `model` (the compiled description) gives
    /// the deformed nodes of flexible bodies (without it they are drawn undeformed).
    pub fn new(scene: &Scene, results: &Results, rows: &[usize], model: Option<&Model>) -> Self {
        let col = |name: &str| results.column(name);
        let t = col("t").unwrap_or_default();
        let zeros = vec![0.0; t.len()];
        let pose = scene
            .parts
            .iter()
            .map(|p| {
                let [x, y, th] = ["x", "y", "theta"]
                    .map(|c| col(&format!("{}.{c}", p.name)).unwrap_or_else(|| zeros.clone()));
                rows.iter()
                    .flat_map(|&r| [x[r] as f32, y[r] as f32, th[r] as f32])
                    .collect()
            })
            .collect();
        let nodes = scene
            .beams
            .iter()
            .map(|b| beam_displacements(scene, b, results, rows, model))
            .collect();
        let mut contact = BTreeMap::new();
        for item in scene.items.iter().filter(|i| i.section == "clearance") {
            let cols: BTreeMap<String, Vec<f32>> = CONTACT_COLUMNS
                .iter()
                .filter_map(|c| {
                    Some((
                        c.to_string(),
                        pick(&col(&format!("{}.{c}", item.name))?, rows),
                    ))
                })
                .collect();
            contact.insert(item.name.clone(), cols);
        }
        Frames {
            t: rows.iter().map(|&r| t[r]).collect(),
            pose,
            nodes,
            contact,
        }
    }
}

/// Node displacements of one beam at `rows`, flattened frame-major ([u, v] per node).
fn beam_displacements(
    scene: &Scene,
    beam: &super::scene::Beam,
    results: &Results,
    rows: &[usize],
    model: Option<&Model>,
) -> Vec<f32> {
    let nn = beam.nodes.len();
    let mut out = vec![0.0f32; rows.len() * nn * 2];
    if beam.part < 0 {
        // ground-fixed: the free DOF columns are the world displacements (supported DOF are 0)
        for k in 0..nn {
            for (c, dof) in ["u", "v"].iter().enumerate() {
                if let Some(v) = results.column(&format!("{}.n{k}.{dof}", beam.name)) {
                    for (f, &r) in rows.iter().enumerate() {
                        out[(f * nn + k) * 2 + c] = v[r] as f32;
                    }
                }
            }
        }
        return out;
    }
    let Some(model) = model else { return out };
    let part = &scene.parts[beam.part as usize];
    let width = results.columns.len();
    let names = model.columns();
    let index: Vec<Option<usize>> = names.iter().map(|n| results.index(n)).collect();
    for (f, &r) in rows.iter().enumerate() {
        let row = &results.data[r * width..(r + 1) * width];
        let own: Vec<f64> = index.iter().map(|i| i.map_or(0.0, |i| row[i])).collect();
        let Ok(q) = model.coordinates_from_row(&own) else {
            return out;
        };
        let pose = |c: &str| {
            results
                .index(&format!("{}.{c}", part.name))
                .map_or(0.0, |i| row[i])
        };
        let (x, y, th) = (pose("x"), pose("y"), pose("theta"));
        let (s, co) = th.sin_cos();
        for (k, n) in beam.nodes.iter().enumerate() {
            if let Ok(p) = model.floating_node_position(&part.name, k, &q) {
                let rigid = [x + co * n[0] - s * n[1], y + s * n[0] + co * n[1]];
                out[(f * nn + k) * 2] = (p[0] - rigid[0]) as f32;
                out[(f * nn + k) * 2 + 1] = (p[1] - rigid[1]) as f32;
            }
        }
    }
    out
}

/// The figures of a run: journal orbits (e/c of every revolute clearance), contact forces of
/// every clearance, and the energy balance, each decimated to about `max` points per line.
pub fn plots(scene: &Scene, results: &Results, max: usize) -> Vec<Plot> {
    let Some(t) = results.column("t") else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut orbit = Plot {
        title: "journal orbits in the clearance".into(),
        x_label: "e_x / c (bearing frame)".into(),
        y_label: "e_y / c (bearing frame)".into(),
        cursor: "orbit",
        t: Vec::new(),
        lines: Vec::new(),
        equal: true,
    };
    let stride = t.len().div_ceil(max.max(1)).max(1);
    let rows: Vec<usize> = (0..t.len()).step_by(stride).collect();
    orbit.t = pick(&t, &rows);
    let mut forces = time_plot("contact forces", "normal force F_N [N]");
    for item in scene.items.iter().filter(|i| i.section == "clearance") {
        let c = (item.params.get("bearing_radius").and_then(|v| v.as_f64()))
            .zip(item.params.get("journal_radius").and_then(|v| v.as_f64()))
            .map(|(b, j)| b - j);
        if let (Some(c), Some(ex), Some(ey)) = (
            c,
            results.column(&format!("{}.ex", item.name)),
            results.column(&format!("{}.ey", item.name)),
        ) {
            orbit.lines.push(Line {
                label: item.name.clone(),
                x: rows.iter().map(|&r| (ex[r] / c) as f32).collect(),
                y: rows.iter().map(|&r| (ey[r] / c) as f32).collect(),
            });
        }
        if let Some(f) = results.column(&format!("{}.normal_force", item.name)) {
            forces.lines.push(time_line(&item.name, &t, &f, max));
        }
    }
    if !orbit.lines.is_empty() {
        out.push(orbit);
    }
    if !forces.lines.is_empty() {
        out.push(forces);
    }
    out.extend(energy_plot(results, &t, max));
    out
}

/// The energy balance figure (total, dissipated, work in, balance), when recorded.
pub(super) fn energy_plot(results: &Results, t: &[f64], max: usize) -> Option<Plot> {
    let mut energy = time_plot("energy balance: total + dissipated − work in", "energy [J]");
    for (name, label) in [
        ("energy.total", "total (kinetic + potential + elastic)"),
        ("energy.dissipated", "dissipated"),
        ("energy.work_in", "work in"),
        ("energy.balance", "balance (should stay constant)"),
    ] {
        if let Some(e) = results.column(name) {
            energy.lines.push(time_line(label, t, &e, max));
        }
    }
    (!energy.lines.is_empty()).then_some(energy)
}

pub(super) fn time_plot(title: &str, y_label: &str) -> Plot {
    Plot {
        title: title.into(),
        x_label: "time [s]".into(),
        y_label: y_label.into(),
        cursor: "time",
        t: Vec::new(),
        lines: Vec::new(),
        equal: false,
    }
}

pub(super) fn time_line(label: &str, t: &[f64], y: &[f64], max: usize) -> Line {
    let rows = decimate(y, max);
    Line {
        label: label.into(),
        x: pick(t, &rows),
        y: pick(y, &rows),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_taken_at_equal_times_from_the_nearest_rows() {
        let t: Vec<f64> = (0..1001).map(|k| (k as f64 / 1000.0).powi(2)).collect();
        let rows = select(&t, 11);
        assert_eq!(rows.len(), 11);
        for (k, &r) in rows.iter().enumerate() {
            let tk = k as f64 / 10.0;
            // nearest row: no other row is closer to tk
            assert!(
                t.iter().all(|&s| (s - tk).abs() >= (t[r] - tk).abs()),
                "{k}"
            );
        }
        assert_eq!(select(&t[..5], 11), vec![0, 1, 2, 3, 4]);
    }

    #[test]
    fn decimation_keeps_every_peak() {
        let y: Vec<f64> = (0..10_000)
            .map(|k| {
                if k % 997 == 0 {
                    1e3
                } else {
                    (k as f64 * 0.01).sin()
                }
            })
            .collect();
        let rows = decimate(&y, 300);
        assert!(rows.len() <= 310, "{}", rows.len());
        let spikes = rows.iter().filter(|&&r| y[r] == 1e3).count();
        assert_eq!(spikes, (0..10_000).filter(|k| k % 997 == 0).count());
        assert!(rows.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(*rows.last().unwrap(), 9_999);
    }
}
