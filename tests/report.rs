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
        "--keep",
        "all",
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

/// A ball (r = 10 mm) dropping 5 mm onto a ground block, a bracket body carrying a compound of
/// two parts (a turned cuboid and a capsule) and a gear body (an involute gear: core disc and
/// teeth).
const SHAPES_MODEL: &str = r#"
[model]
name = "shapes"
gravity = [0.0, -9.81]

[[body]]
name = "ball"
mass = 0.0327
inertia = 1.308e-6
position = [0.0, 0.015]
angle = 0.0
velocity = [0.0, 0.0]
angular_velocity = 0.0

[[body]]
name = "bracket"
mass = 0.2
inertia = 1e-4
position = [0.3, 0.2]

[[body]]
name = "gear"
mass = 0.1
inertia = 2e-5
position = [-0.2, 0.2]

[[joint]]
name = "bracket_fix"
type = "fixed"
a = { body = "ground", at = [0.3, 0.2] }
b = { body = "bracket", at = [0.0, 0.0] }

[[joint]]
name = "gear_fix"
type = "fixed"
a = { body = "ground", at = [-0.2, 0.2] }
b = { body = "gear", at = [0.0, 0.0] }

[[shape]]
name = "floor"
at = { body = "ground", at = [0.0, -0.05] }
geometry = { type = "cuboid", half_extents = [0.5, 0.05] }

[[shape]]
name = "sphere"
at = { body = "ball", at = [0.0, 0.0] }
geometry = { type = "ball", radius = 0.01 }

[[shape]]
name = "bracket_shape"
at = { body = "bracket", at = [0.01, -0.02] }
angle = 0.2
geometry = { type = "compound", parts = [
    { at = [0.1, 0.0], angle = 0.3, geometry = { type = "cuboid", half_extents = [0.02, 0.01] } },
    { at = [-0.05, 0.02], geometry = { type = "capsule", half_length = 0.03, radius = 0.005 } },
] }

[[shape]]
name = "wheel"
at = { body = "gear", at = [0.0, 0.0] }
geometry = { type = "involute_gear", module = 0.002, teeth = 20 }

[[clearance]]
name = "drop"
type = "contact"
shapes = ["floor", "sphere"]
normal = { law = "hertz", stiffness = 1.5e10, damping = "hc-exact", restitution = 0.8 }

[solver]
rtol = 1e-8
atol = 1e-11

[output]
t_end = 0.05
intervals = 500
"#;

fn vec2(v: &Value) -> [f64; 2] {
    [v[0].as_f64().unwrap(), v[1].as_f64().unwrap()]
}

fn points(outline: &Value) -> Vec<[f64; 2]> {
    outline["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(vec2)
        .collect()
}

/// The point `p` of a compound part at `at` turned by `angle` (the model file's pose).
fn placed(at: [f64; 2], angle: f64, p: [f64; 2]) -> [f64; 2] {
    let (s, c) = angle.sin_cos();
    [at[0] + c * p[0] - s * p[1], at[1] + s * p[0] + c * p[1]]
}

/// The scene lists every `[[shape]]` where the file puts it, with its outline in the shape
/// frame from the file's numbers: the ground block's four corners (counter-clockwise), the
/// ball's points at its radius, each compound part placed by its pose, the gear as one outline
/// between its root and tip circles; the contact element names its two shapes, and a run
/// records its contact point and force for the page.
#[test]
fn the_scene_draws_the_contact_shapes_of_the_model_file() {
    let out = scratch_in("report", "shapes");
    let file = out.join("shapes.toml");
    std::fs::write(&file, SHAPES_MODEL).unwrap();
    let doc: toml::Table = toml::from_str(SHAPES_MODEL).unwrap();
    let shape_doc = |name: &str| {
        doc["shape"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["name"].as_str() == Some(name))
            .unwrap()
            .clone()
    };
    let num = |v: &toml::Value| v.as_float().unwrap();
    let pair = |v: &toml::Value| [num(&v[0]), num(&v[1])];
    let page = out.join("view.html");
    let o = clr(&[
        "view",
        file.to_str().unwrap(),
        "--out",
        page.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let d = page_data(&std::fs::read_to_string(&page).unwrap());
    let scene = &d["scene"];
    let parts: Vec<&str> = scene["parts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    let shapes = scene["shapes"].as_array().unwrap();
    let names: Vec<&str> = shapes.iter().map(|s| s["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["floor", "sphere", "bracket_shape", "wheel"]);
    let shape = |name: &str| shapes.iter().find(|s| s["name"] == name).unwrap();
    let close = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]) <= 1e-12;

    // the ground block: on the ground (part −1) at the file's point, its four corners
    let (floor, floor_doc) = (shape("floor"), shape_doc("floor"));
    assert_eq!(floor["at"]["part"], -1);
    assert_eq!(vec2(&floor["at"]["at"]), pair(&floor_doc["at"]["at"]));
    assert_eq!(floor["angle"], 0.0);
    let [hx, hy] = pair(&floor_doc["geometry"]["half_extents"]);
    let outlines = floor["outlines"].as_array().unwrap();
    assert_eq!(outlines.len(), 1);
    assert_eq!(outlines[0]["closed"], true);
    assert_eq!(
        points(&outlines[0]),
        [[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]]
    );
    // no ground symbol under the block: a shape's origin is not an attachment point
    assert!(scene["ground"]
        .as_array()
        .unwrap()
        .iter()
        .all(|g| vec2(g) != [0.0, -0.05]));

    // the ball: on the body `ball`, every point at the radius, a closed polygon of 48
    let sphere = shape("sphere");
    let ball = parts.iter().position(|&p| p == "ball").unwrap();
    assert_eq!(sphere["at"]["part"], ball);
    assert_eq!(vec2(&sphere["at"]["at"]), [0.0, 0.0]);
    let r = num(&shape_doc("sphere")["geometry"]["radius"]);
    let pts = points(&sphere["outlines"][0]);
    assert_eq!(pts.len(), 48);
    assert_eq!(sphere["outlines"][0]["closed"], true);
    for p in &pts {
        assert!((p[0].hypot(p[1]) - r).abs() <= 1e-15, "{p:?}");
    }

    // the compound: its angle, and each part's outline placed by the part's pose
    let (bracket, bracket_doc) = (shape("bracket_shape"), shape_doc("bracket_shape"));
    let bracket_part = parts.iter().position(|&p| p == "bracket").unwrap();
    assert_eq!(bracket["at"]["part"], bracket_part);
    assert_eq!(vec2(&bracket["at"]["at"]), pair(&bracket_doc["at"]["at"]));
    assert_eq!(bracket["angle"], num(&bracket_doc["angle"]));
    let docs = bracket_doc["geometry"]["parts"].as_array().unwrap();
    let outlines = bracket["outlines"].as_array().unwrap();
    assert_eq!(outlines.len(), 2, "one outline per part");
    // the cuboid part: its corners turned by 0.3 rad about its centre
    let (at, angle) = (pair(&docs[0]["at"]), num(&docs[0]["angle"]));
    let [hx, hy] = pair(&docs[0]["geometry"]["half_extents"]);
    let corners = points(&outlines[0]);
    for (p, q) in corners
        .iter()
        .zip([[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]])
    {
        assert!(close(*p, placed(at, angle, q)), "{p:?} vs {q:?}");
    }
    // the capsule part: every point at its radius from its segment, the segment about its at
    let at = pair(&docs[1]["at"]);
    let (hl, rc) = (
        num(&docs[1]["geometry"]["half_length"]),
        num(&docs[1]["geometry"]["radius"]),
    );
    let stadium = points(&outlines[1]);
    assert!(stadium.len() >= 40);
    for p in &stadium {
        let x = (p[0] - at[0]).clamp(-hl, hl);
        let dist = (p[0] - at[0] - x).hypot(p[1] - at[1]);
        assert!((dist - rc).abs() <= 1e-15, "{p:?}: {dist}");
    }
    for side in [-1.0, 1.0] {
        // the far ends of the stadium
        assert!(stadium
            .iter()
            .any(|p| close(*p, [at[0] + side * (hl + rc), at[1]])));
    }

    // the gear: core and teeth as one outline between the root and tip circles
    let (wheel, wheel_doc) = (shape("wheel"), shape_doc("wheel"));
    assert_eq!(wheel["kind"], "involute_gear");
    let m = num(&wheel_doc["geometry"]["module"]);
    let z = wheel_doc["geometry"]["teeth"].as_integer().unwrap() as f64;
    let (r_tip, r_root) = (m * z / 2.0 + m, m * z / 2.0 - 1.25 * m);
    let outlines = wheel["outlines"].as_array().unwrap();
    assert_eq!(outlines.len(), 1, "merged core and teeth");
    let radii: Vec<f64> = points(&outlines[0])
        .iter()
        .map(|p| p[0].hypot(p[1]))
        .collect();
    assert!(radii.len() <= 4000);
    let (lo, hi) = radii.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &r| {
        (lo.min(r), hi.max(r))
    });
    assert!(
        (hi - r_tip).abs() < 1e-12 && (lo - r_root).abs() < 1e-12,
        "{lo} … {hi}"
    );
    // one tip land per tooth: the runs of points on the tip circle
    let on_tip: Vec<bool> = radii.iter().map(|r| (r - r_tip).abs() < 1e-9).collect();
    let lands = (0..on_tip.len())
        .filter(|&i| on_tip[i] && !on_tip[(i + on_tip.len() - 1) % on_tip.len()])
        .count();
    assert_eq!(lands as f64, z);

    // the contact element names its shapes (A, B) and has no anchors of its own
    let drop = scene["items"]
        .as_array()
        .unwrap()
        .iter()
        .find(|i| i["name"] == "drop")
        .unwrap();
    assert_eq!(drop["kind"], "contact");
    assert_eq!(drop["shapes"], serde_json::json!([0, 1]));

    // a run: the page has the contact point (world) and force of each frame; in contact the
    // point lies on the block's top face under the ball
    let run = out.join("run");
    run_quietly(file.to_str().unwrap(), "0.05", &run);
    let d = page_data(&std::fs::read_to_string(run.join("report.html")).unwrap());
    let c = &d["frames"]["contact"]["drop"];
    let col = |k: &str| -> Vec<f64> {
        c[k].as_array()
            .unwrap_or_else(|| panic!("{k} recorded"))
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    let (on, f, ex, ey) = (col("contact"), col("normal_force"), col("ex"), col("ey"));
    let touching: Vec<usize> = (0..on.len()).filter(|&k| on[k] > 0.0).collect();
    assert!(!touching.is_empty(), "the ball lands within the run");
    for k in touching {
        assert!(f[k] >= 0.0);
        assert!(
            ex[k].abs() < 1e-6 && ey[k].abs() < 1e-6,
            "({}, {})",
            ex[k],
            ey[k]
        );
    }
}
