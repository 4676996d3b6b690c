//! The report of a sweep: the table of points (varied values, status, wall time, metrics) with
//! a link to each point's own report, and one comparison figure per metric against the first
//! varied parameter (one line per combination of the others).

use std::collections::BTreeMap;

use serde_json::json;

use super::frames::{Line, Plot};
use super::Report;

/// One point of a sweep as its table lists it.
#[derive(Debug, Clone)]
pub struct SweepRow {
    /// Index in the full product.
    pub point: usize,
    /// The varied values as given.
    pub values: Vec<String>,
    /// `ok` or `failed`.
    pub status: String,
    /// Wall time, s.
    pub wall_s: f64,
    /// (name, unit, value) of every metric.
    pub metrics: Vec<(String, String, f64)>,
}

impl SweepRow {
    /// The folder of this point's outputs in the sweep folder.
    pub fn folder(&self) -> String {
        format!("point-{:05}", self.point)
    }
}

/// Metric names and units of a sweep's points, in first-seen order.
pub fn metric_names(rows: &[SweepRow]) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = Vec::new();
    for r in rows {
        for (n, u, _) in &r.metrics {
            if !out.iter().any(|(m, _)| m == n) {
                out.push((n.clone(), u.clone()));
            }
        }
    }
    out
}

impl Report {
    /// The report of a sweep of `target` over the parameters `names`; `links` when every point
    /// wrote its own `report.html`.
    pub fn sweep(target: &str, names: &[String], rows: &[SweepRow], links: bool) -> Self {
        let metrics = metric_names(rows);
        let table: Vec<serde_json::Value> = rows
            .iter()
            .map(|r| {
                let mut o = serde_json::Map::new();
                o.insert("point".into(), json!(r.point));
                for (n, v) in names.iter().zip(&r.values) {
                    o.insert(n.clone(), json!(v));
                }
                o.insert("status".into(), json!(r.status));
                o.insert("wall_s".into(), json!(r.wall_s));
                for (n, u, v) in &r.metrics {
                    o.insert(format!("{n} [{u}]"), json!(v));
                }
                serde_json::Value::Object(o)
            })
            .collect();
        let link_list: Vec<serde_json::Value> = rows
            .iter()
            .filter(|_| links)
            .map(|r| json!({"label": r.folder(), "href": format!("{}/report.html", r.folder())}))
            .collect();
        Report {
            kind: "sweep",
            model: target.to_string(),
            source: target.to_string(),
            description: format!("sweep over {}", names.join(", ")),
            scene: None,
            scene_note: Some("a sweep: open a point's report for its animation".into()),
            frames: None,
            plots: metrics
                .iter()
                .filter_map(|(m, u)| compare(names, rows, m, u))
                .collect(),
            metrics: Vec::new(),
            impacts: Vec::new(),
            notes: Vec::new(),
            initial_conditions: serde_json::Value::Null,
            error: None,
            sweep: Some(json!({"names": names, "table": table, "links": link_list})),
            spatial: None,
        }
    }
}

/// Metric `m` against the first varied parameter (numeric values only), one line per
/// combination of the other parameters.
fn compare(names: &[String], rows: &[SweepRow], m: &str, unit: &str) -> Option<Plot> {
    let first = names.first()?;
    let mut lines: BTreeMap<String, Vec<(f32, f32)>> = BTreeMap::new();
    for r in rows {
        let x: f64 = r.values.first()?.parse().ok()?;
        let Some((_, _, y)) = r.metrics.iter().find(|(n, _, _)| n == m) else {
            continue;
        };
        let label: Vec<String> = names[1..]
            .iter()
            .zip(&r.values[1..])
            .map(|(n, v)| format!("{n}={v}"))
            .collect();
        lines
            .entry(if label.is_empty() {
                m.to_string()
            } else {
                label.join(", ")
            })
            .or_default()
            .push((x as f32, *y as f32));
    }
    if lines.values().all(|l| l.len() < 2) {
        return None;
    }
    Some(Plot {
        title: m.to_string(),
        x_label: first.clone(),
        y_label: format!("{m} [{unit}]"),
        cursor: "none",
        t: Vec::new(),
        lines: lines
            .into_iter()
            .map(|(label, mut pts)| {
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                Line {
                    label,
                    x: pts.iter().map(|p| p.0).collect(),
                    y: pts.iter().map(|p| p.1).collect(),
                }
            })
            .collect(),
        equal: false,
    })
}
