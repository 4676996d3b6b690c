//! End-to-end tests of the run report (`report.html` of `clr run`, `clr view`, the sweep
//! report): the page's embedded data against independent sources — the model file it was
//! drawn from (the parts, the clearance joint's radii and anchors), the run's own results.csv
//! (the frames are recorded rows, not recomputed), and the closed form of the initial
//! conditions of the slider–crank (ω_rod = −ω_crank·r/L at θ = 0). The browser rendering is
//! checked by `cargo xtask report-check` (headless Chromium), not here.

mod common;

use common::{clr, run_quietly, scratch_in, stderr};
use serde_json::Value;

const SLIDER_CRANK: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/slider_crank.toml");

/// The JSON a page embeds (`<script id="clr-data">`, with "</" written "<\/").
fn page_data(html: &str) -> Value {
    let start = html
        .find(r#"<script id="clr-data" type="application/json">"#)
        .expect("the data element")
        + r#"<script id="clr-data" type="application/json">"#.len();
    let end = start + html[start..].find("</script>").expect("its end");
    serde_json::from_str(&html[start..end].replace("<\\/", "</")).expect("JSON")
}

/// results.csv as (column names, rows).
fn csv(path: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let names = lines
        .next()
        .unwrap()
        .split(',')
        .map(|h| h.rsplit_once(" [").map_or(h, |(n, _)| n).to_string())
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (names, rows)
}

#[test]
fn a_run_report_draws_the_model_file_and_plays_its_recorded_rows() {
    let out = scratch_in("report", "run");
    run_quietly(SLIDER_CRANK, "0.01", &out);
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    // nothing is fetched: no external script, style, image or request
    for net in [
        "src=\"http",
        "href=\"http",
        "url(http",
        "fetch(",
        "XMLHttpRequest",
        "@import",
    ] {
        assert!(!html.contains(net), "the page loads `{net}`");
    }
    let d = page_data(&html);
    let scene = &d["scene"];
    let parts: Vec<&str> = scene["parts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(parts, ["crank", "rod", "slider"]);
    // the clearance joint B of the file: radii and the journal at (0.15, 0) on the rod (part 1)
    let b = scene["items"]
        .as_array()
        .unwrap()
        .iter()
        .find(|i| i["name"] == "B")
        .unwrap();
    assert_eq!(b["section"], "clearance");
    assert_eq!(b["params"]["bearing_radius"], 0.01);
    assert_eq!(b["params"]["journal_radius"], 0.0095);
    assert_eq!(b["anchors"]["journal"]["part"], 1);
    assert_eq!(b["anchors"]["journal"]["at"][0], 0.15);
    // frames are recorded rows: the first and last times, and the rod's pose at each frame
    // equals its row of results.csv (to f32)
    let (names, rows) = csv(&out.join("results.csv"));
    let t: Vec<f64> = d["frames"]["t"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(t[0], 0.0);
    assert_eq!(*t.last().unwrap(), rows.last().unwrap()[0]);
    let col = |n: &str| names.iter().position(|c| c == n).unwrap();
    let pose = d["frames"]["pose"][1].as_array().unwrap();
    for (f, tf) in t.iter().enumerate() {
        // serde_json reads numbers to within an ulp: the recorded row is the nearest one
        let row = rows
            .iter()
            .min_by(|a, b| (a[0] - tf).abs().total_cmp(&(b[0] - tf).abs()))
            .unwrap();
        assert!(
            (row[0] - tf).abs() <= 1e-15 * tf.abs().max(1e-3),
            "frame {f} at {tf} s"
        );
        for (k, c) in ["rod.x", "rod.y", "rod.theta"].iter().enumerate() {
            let drawn = pose[3 * f + k].as_f64().unwrap();
            assert_eq!(drawn as f32, row[col(c)] as f32, "{c} at frame {f}");
        }
    }
    // the figures: orbit of B and its contact force; the impacts of the run
    let titles: Vec<&str> = d["plots"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["title"].as_str().unwrap())
        .collect();
    assert!(titles.iter().any(|t| t.contains("orbit")), "{titles:?}");
    assert!(!d["impacts"].as_array().unwrap().is_empty());
}

#[test]
fn clr_view_draws_the_assembled_initial_state_and_names_what_it_solved() {
    let out = scratch_in("report", "view");
    let text = std::fs::read_to_string(SLIDER_CRANK).unwrap();
    let line = "angular_velocity = -87.26646259971649  # rad/s, −ω r/l\n";
    assert!(text.contains(line));
    let file = out.join("sc.toml");
    std::fs::write(&file, text.replace(line, "")).unwrap();
    let page = out.join("view.html");
    let o = clr(&[
        "view",
        file.to_str().unwrap(),
        "--out",
        page.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // closed form: ω_rod = −ω_crank·r/L = −523.599 · 0.05 / 0.3 at θ = 0
    assert!(
        stderr(&o).contains("rod.omega = -8.726646e1"),
        "{}",
        stderr(&o)
    );
    let d = page_data(&std::fs::read_to_string(&page).unwrap());
    assert_eq!(d["kind"], "view");
    assert_eq!(d["frames"]["t"].as_array().unwrap().len(), 1);
    assert!(d["notes"]
        .as_array()
        .unwrap()
        .iter()
        .any(|n| n.as_str().unwrap().contains("rod.omega")));
    let omega = &d["initial_conditions"]["bodies"]["rod"]["omega"];
    assert_eq!(omega["status"], "solved", "{omega}");
    let w = omega["assembled"].as_f64().unwrap();
    assert!((w + 523.5987755982989 * 0.05 / 0.3).abs() < 1e-9, "{w}");
    // a file that does not read is refused with its field, nothing written
    let bad = out.join("bad.toml");
    std::fs::write(&bad, text.replace("mass = 1.072", "mass = -1.072")).unwrap();
    let o = clr(&[
        "view",
        bad.to_str().unwrap(),
        "--out",
        out.join("bad.html").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("body[1].mass"), "{}", stderr(&o));
    assert!(!out.join("bad.html").exists());
}

#[test]
fn a_sweep_report_links_every_point_report() {
    let out = scratch_in("report", "sweep");
    let o = clr(&[
        "sweep",
        SLIDER_CRANK,
        "--t-end",
        "0.002",
        "--vary",
        "clearance.B.journal_radius=0.0095,0.0098",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--no-figures",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let d = page_data(&std::fs::read_to_string(out.join("report.html")).unwrap());
    assert_eq!(d["kind"], "sweep");
    let links = d["sweep"]["links"].as_array().unwrap();
    assert_eq!(links.len(), 2);
    for l in links {
        assert!(out.join(l["href"].as_str().unwrap()).is_file(), "{l}");
    }
    assert_eq!(d["sweep"]["table"].as_array().unwrap().len(), 2);
    assert!(
        !d["plots"].as_array().unwrap().is_empty(),
        "comparison figures"
    );
}
