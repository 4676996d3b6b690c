//! `cargo xtask report-check`: render the run reports (`report.html`) of four models in
//! headless Chromium and check them as a user would see them: the page draws without script
//! errors, the mechanism moves (the drawn journal, or a part, is elsewhere at two times), the
//! contact shapes are drawn and a shape contact's force acts along the right normal, a 10 s
//! run's report stays under 20 MB, and the screenshots go to `docs/figures/` (shown in
//! docs/cli.md). A spatial page (the synthetic spinning top of `clr_sim::report::spatial`) is
//! checked too: WebGL (SwiftShader, software) drew its three.js canvas without a console error,
//! and the ball drawn in its socket is where the recorded eccentricity puts it. Installs Debian's `chromium` with apt-get when missing; never part of `cargo
//! test` (a browser is a large system dependency).

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use serde_json::Value;

use crate::{target_dir, workspace_root};

const HELP: &str = "usage: cargo xtask report-check [spatial]
  Builds clr (release), runs slider_crank, the flap with flexible links, the dual guide and
  models/examples/gear_pair_backlash.toml, opens each report.html in headless Chromium (apt-get
  install chromium when missing) at two times, checks for script errors, that the mechanism
  moved and (gear pair) that the gears' shapes are drawn with the tooth force along the line of
  action, writes the screenshots to docs/figures/report_<model>_<k>.png (the gear pair's first
  to docs/figures/report_shapes.png), and checks that a 10 s run's report is under 20 MB.
  Then writes the 3-D page of a synthetic spatial run (a spinning top, a ball in a socket),
  checks that its WebGL canvas drew with no console error and the ball is where the data puts
  it, and saves docs/figures/report3d.png (`spatial`: only this last check).";

/// The largest report of a 10 s run the issue allows, bytes.
const MAX_REPORT_BYTES: u64 = 20 * 1024 * 1024;

/// One model to render: its name, `clr run` arguments (run in the workspace root: a model file
/// is given relative to it) and the two times of the screenshots.
struct Case {
    name: &'static str,
    args: &'static [&'static str],
    times: [f64; 2],
    /// The file stem of the only screenshot kept (at the first time) in place of both
    /// `report_<name>_<k>`.
    figure: Option<&'static str>,
    /// A shape contact in contact at the first time and its expected normal (world, from
    /// shape A to B): the drawn normal must be within 0.05 (3°) of it.
    contact: Option<(&'static str, [f64; 2])>,
}

/// sin and cos of the 20° pressure angle: the line of action of the example gear pair.
const SIN_20: f64 = 0.3420201433256687;
const COS_20: f64 = 0.9396926207859084;

const CASES: &[Case] = &[
    Case {
        name: "slider_crank",
        args: &["slider_crank", "--t-end", "0.03"],
        times: [0.004, 0.02],
        figure: None,
        contact: None,
    },
    Case {
        name: "flap_flexible",
        args: &[
            "flap",
            "--set",
            "flexible=[true,true,true]",
            "--set",
            "clearances=[0.0001,0.0001,0.0001,0.0001]",
            "--t-end",
            "0.1",
        ],
        times: [0.02, 0.09],
        figure: None,
        contact: None,
    },
    Case {
        name: "dual_guide",
        args: &["dual_guide", "--t-end", "0.1"],
        times: [0.01, 0.09],
        figure: None,
        contact: None,
    },
    // the coast-flank impact after the drive reversal (at about 22 ms, impacts.csv of the
    // example): the tooth force on gear 2 along the line of action, down and to the right
    Case {
        name: "gear_pair",
        args: &["models/examples/gear_pair_backlash.toml"],
        times: [0.02207, 0.08],
        figure: Some("report_shapes"),
        contact: Some(("mesh", [SIN_20, -COS_20])),
    },
];

pub fn run(args: &[String]) -> ExitCode {
    // `report-check spatial`: the 3-D page only (no clr build, no runs)
    if args.len() == 1 && args[0] == "spatial" {
        return crate::command_without_arguments("report-check", HELP, &[], spatial_only);
    }
    crate::command_without_arguments("report-check", HELP, args, run_all)
}

fn spatial_only() -> Result<(), String> {
    let chromium = ensure_chromium()?;
    let figures = workspace_root().join("docs").join("figures");
    let out = target_dir().join("report-check").join("spatial");
    check_spatial(&chromium, &out, &figures.join("report3d.png"))
}

fn run_all() -> Result<(), String> {
    let chromium = ensure_chromium()?;
    let clr = crate::system::build_clr()?;
    let out = target_dir().join("report-check");
    let figures = workspace_root().join("docs").join("figures");
    for case in CASES {
        let dir = out.join(case.name);
        run_clr(&clr, case.args, &dir)?;
        let page = dir.join("report.html");
        let states: Vec<Value> = case
            .times
            .iter()
            .enumerate()
            .map(|(k, &t)| {
                let shot = match (case.figure, k) {
                    (Some(stem), 0) => Some(format!("{stem}.png")),
                    (Some(_), _) => None,
                    (None, _) => Some(format!("report_{}_{}.png", case.name, k + 1)),
                };
                if let Some(shot) = shot {
                    screenshot(&chromium, &page, t, &figures.join(shot))?;
                }
                page_state(&chromium, &page, t)
            })
            .collect::<Result<_, String>>()?;
        check_moved(case.name, &states)?;
        if let Some((name, normal)) = case.contact {
            check_shapes(case.name, &states, name, normal)?;
            println!(
                "report-check: {}: shapes drawn, `{name}` in contact along the expected normal",
                case.name
            );
        }
        println!(
            "report-check: {}: no script errors, the mechanism moved",
            case.name
        );
    }
    check_spatial(
        &chromium,
        &out.join("spatial"),
        &figures.join("report3d.png"),
    )?;
    let long = out.join("slider_crank_10s");
    run_clr(&clr, &["slider_crank", "--t-end", "10"], &long)?;
    let bytes = std::fs::metadata(long.join("report.html"))
        .map_err(|e| format!("10 s report: {e}"))?
        .len();
    println!(
        "report-check: report of a 10 s slider_crank run: {:.1} MB (limit {} MB)",
        bytes as f64 / 1e6,
        MAX_REPORT_BYTES / 1024 / 1024
    );
    if bytes > MAX_REPORT_BYTES {
        return Err(format!(
            "the 10 s report is {bytes} bytes, over the 20 MB limit"
        ));
    }
    Ok(())
}

/// `chromium` on the PATH, installed with apt-get when missing.
fn ensure_chromium() -> Result<PathBuf, String> {
    crate::system::apt_install("report-check", &["chromium"], &["chromium"])?;
    crate::system::which("chromium").ok_or_else(|| "chromium not on the PATH".into())
}

/// `clr run ARGS --out OUT` in the workspace root (a model file is given relative to it, and
/// the page shows it so).
fn run_clr(clr: &Path, args: &[&str], out: &Path) -> Result<(), String> {
    let abs = |p: &Path| std::path::absolute(p).map_err(|e| format!("{}: {e}", p.display()));
    let status = Command::new(abs(clr)?)
        .current_dir(workspace_root())
        .arg("run")
        .args(args)
        .arg("--out")
        .arg(abs(out)?)
        .args(["--quiet", "--no-figures"])
        .status()
        .map_err(|e| format!("clr: {e}"))?;
    if !status.success() {
        return Err(format!("clr run {} failed ({status})", args.join(" ")));
    }
    Ok(())
}

/// The page at time `t` (s) as a URL (the page reads `#t=` and stays paused there).
fn url(page: &Path, t: f64) -> Result<String, String> {
    let abs = page
        .canonicalize()
        .map_err(|e| format!("{}: {e}", page.display()))?;
    Ok(format!("file://{}#t={t}", abs.display()))
}

fn headless(chromium: &Path) -> Command {
    let mut c = Command::new(chromium);
    c.args([
        "--headless=new",
        "--no-sandbox",
        "--disable-gpu",
        "--hide-scrollbars",
        "--window-size=1400,860",
        // time for the page to parse its data and draw before the capture
        "--virtual-time-budget=4000",
        // WebGL for the 3-D page without a GPU: ANGLE on SwiftShader (software)
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
    ]);
    c
}

fn screenshot(chromium: &Path, page: &Path, t: f64, png: &Path) -> Result<(), String> {
    let out = headless(chromium)
        .arg(format!("--screenshot={}", png.display()))
        .arg(url(page, t)?)
        .output()
        .map_err(|e| format!("chromium: {e}"))?;
    if !out.status.success() || !png.exists() {
        return Err(format!(
            "chromium --screenshot failed: {}",
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    Ok(())
}

/// What the page reports of itself after drawing time `t`: the JSON of its
/// `<script id="clr-state">` element (`time`, `journals`, `parts`, `errors`), from the DOM.
fn page_state(chromium: &Path, page: &Path, t: f64) -> Result<Value, String> {
    let out = headless(chromium)
        .arg("--dump-dom")
        .arg(url(page, t)?)
        .output()
        .map_err(|e| format!("chromium: {e}"))?;
    let dom = String::from_utf8_lossy(&out.stdout);
    let start = dom
        .find("<script id=\"clr-state\" type=\"application/json\">")
        .and_then(|i| dom[i..].find('>').map(|j| i + j + 1))
        .ok_or_else(|| {
            format!(
                "{}: the page never drew (no clr-state element)",
                page.display()
            )
        })?;
    let end = dom[start..]
        .find("</script>")
        .ok_or("unterminated clr-state element")?;
    let state: Value = serde_json::from_str(&dom[start..start + end])
        .map_err(|e| format!("clr-state is not JSON: {e}"))?;
    let errors = state["errors"].as_array().cloned().unwrap_or_default();
    if !errors.is_empty() {
        return Err(format!("{}: script errors: {errors:?}", page.display()));
    }
    let drawn = state["time"].as_f64().unwrap_or(f64::NAN);
    if (drawn - t).abs() > 0.01 * t.max(1e-3) + 1e-3 {
        return Err(format!(
            "{}: asked for t = {t} s, the page drew {drawn} s",
            page.display()
        ));
    }
    Ok(state)
}

/// The journals (or, without revolute clearances, the parts) drawn at the two times are not
/// in the same place (or, for parts, not at the same angle).
fn check_moved(name: &str, states: &[Value]) -> Result<(), String> {
    let key = if states[0]["journals"]
        .as_object()
        .is_some_and(|o| !o.is_empty())
    {
        "journals"
    } else {
        "parts"
    };
    let (a, b) = (&states[0][key], &states[1][key]);
    let moved = a.as_object().into_iter().flatten().any(|(k, p)| {
        let q = &b[k];
        let d = |i: usize| p[i].as_f64().unwrap_or(0.0) - q[i].as_f64().unwrap_or(0.0);
        // parts: [x, y, θ]; a part turning in place (a gear) moved too
        d(0).hypot(d(1)) > 1e-6 || d(2).abs() > 1e-6
    });
    if moved {
        Ok(())
    } else {
        Err(format!(
            "{name}: the drawn {key} did not move between the two times: {a} / {b}"
        ))
    }
}

/// Every contact shape is drawn (a frame and at least one outline in the page's state) at both
/// times, and at the first the shape contact `name` is in contact with its drawn normal (unit,
/// world) within 0.05 of `normal`.
fn check_shapes(case: &str, states: &[Value], name: &str, normal: [f64; 2]) -> Result<(), String> {
    for s in states {
        let shapes = s["shapes"].as_object().filter(|o| !o.is_empty());
        let shapes = shapes.ok_or_else(|| format!("{case}: no contact shape drawn"))?;
        for (shape, v) in shapes {
            if v["outlines"].as_u64().unwrap_or(0) == 0 {
                return Err(format!("{case}: shape `{shape}` has no outline: {v}"));
            }
        }
    }
    let c = &states[0]["contacts"][name];
    let n = [c["n"][0].as_f64(), c["n"][1].as_f64()];
    let [Some(nx), Some(ny)] = n else {
        return Err(format!(
            "{case}: `{name}` is not drawn in contact at the first time: {c}"
        ));
    };
    if (nx - normal[0]).hypot(ny - normal[1]) > 0.05 {
        return Err(format!(
            "{case}: the normal drawn for `{name}` is [{nx}, {ny}], expected {normal:?}"
        ));
    }
    Ok(())
}

/// The 3-D page of the synthetic spinning top (`clr_sim::report::spatial::spinning_top`): WebGL
/// drew its canvas (ink in the sample) with no script or console error at two times, the ball
/// drawn in the socket is where the recorded eccentricity puts it, and the screenshot at the
/// first time goes to `png`.
fn check_spatial(chromium: &Path, dir: &Path, png: &Path) -> Result<(), String> {
    use clr_sim::report::{spatial, Input, Limits, Report};
    let (scene, results) = spatial::spinning_top(401);
    let input = Input {
        model: "spinning top (synthetic)",
        source: "cargo xtask report-check",
        description:
            "a top spinning about a tilted axis on a spherical joint; a ball circling in a socket",
        desc: Err("spatial".into()),
        results: &results,
        metrics: &[],
        notes: &[],
        error: None,
    };
    let report =
        Report::spatial("run", &input, scene, Limits::default()).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let page = dir.join("report.html");
    std::fs::write(&page, report.html()).map_err(|e| format!("{}: {e}", page.display()))?;
    let times = [0.3, 0.7];
    screenshot(chromium, &page, times[0], png)?;
    let console = console_messages(chromium, &page, times[0])?;
    if !console.is_empty() {
        return Err(format!("spatial page: console messages: {console:?}"));
    }
    for t in times {
        let state = page_state(chromium, &page, t)?;
        if state["webgl"] != "ok" || state["renders"].as_u64().unwrap_or(0) == 0 {
            return Err(format!(
                "spatial page: WebGL did not draw at t = {t} s: {state}"
            ));
        }
        // ink in at least 1 % of the 64 × 64 samples: the bodies, the socket and the axes
        let ink = state["ink"].as_u64().unwrap_or(0);
        if ink < 41 {
            return Err(format!(
                "spatial page: the canvas is blank at t = {t} s ({ink} samples drawn)"
            ));
        }
        // the ball centre: socket (0.5, 0, 0) + 0.8 mm (sin 2πt, −cos 2πt, 0) (spinning_top);
        // the page holds f32 frames interpolated linearly (401 rows 2.5 ms apart; t on a row):
        // 1e-6 m covers both
        let phi = 2.0 * std::f64::consts::PI * t;
        let want = [0.5 + 0.8e-3 * phi.sin(), -0.8e-3 * phi.cos(), 0.0];
        let got: Vec<f64> = (0..3)
            .map(|k| state["balls"]["cup"][k].as_f64().unwrap_or(f64::NAN))
            .collect();
        // a NaN (no ball drawn) fails too
        let near = (0..3).all(|k| (got[k] - want[k]).abs() < 1e-6);
        if !near {
            return Err(format!(
                "spatial page: ball drawn at {got:?} at t = {t} s, expected {want:?}"
            ));
        }
        println!("report-check: spatial: t = {t} s: WebGL drew ({ink} of 4096 samples inked), no errors, ball where the data puts it");
    }
    Ok(())
}

/// The browser console's messages while the page draws time `t` (Chromium's log on stderr),
/// except the performance note of the page's own pixel sample ("GPU stall due to ReadPixels"):
/// three.js reports WebGL trouble (a failed shader, a lost context) there, and Chromium its
/// deprecation of an implicit software WebGL.
fn console_messages(chromium: &Path, page: &Path, t: f64) -> Result<Vec<String>, String> {
    let out = headless(chromium)
        .args(["--enable-logging=stderr", "--v=0", "--dump-dom"])
        .arg(url(page, t)?)
        .output()
        .map_err(|e| format!("chromium: {e}"))?;
    Ok(String::from_utf8_lossy(&out.stderr)
        .lines()
        .filter(|l| l.contains(":CONSOLE") && !l.contains("GPU stall due to ReadPixels"))
        .map(str::to_string)
        .collect())
}
