//! Renders a few figures whose tick labels exercise the formatter.
//! Usage: `cargo run -p clr-plot --example tick_labels -- <out-dir>`.
use clr_plot::Figure;

fn main() {
    let dir = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "target/tick_labels".into());
    let dir = std::path::Path::new(&dir);
    let small: Vec<(f64, f64)> = (0..=100)
        .map(|i| {
            let t = i as f64 * 0.0005;
            (t, 1e-4 * (t * 300.0).sin() - 2e-5)
        })
        .collect();
    Figure::new("small: x 0..0.05 s, y ±1e-4 m")
        .x_label("time (s)")
        .y_label("displacement (m)")
        .line("x", small)
        .save(dir.join("small"))
        .unwrap();
    let large: Vec<(f64, f64)> = (0..=100)
        .map(|i| (i as f64 * 150.0, 12500.0 * (i as f64 * 0.1).cos()))
        .collect();
    Figure::new("large: x 0..15000 rpm, y ±12500 N")
        .x_label("speed (rpm)")
        .y_label("force (N)")
        .points("F", large)
        .save(dir.join("large"))
        .unwrap();
    let log: Vec<(f64, f64)> = (0..=40)
        .map(|i| {
            let h = 10f64.powf(-6.0 + i as f64 * 0.1);
            (h, 3.0 * h * h)
        })
        .collect();
    Figure::new("log axes")
        .x_label("step h (s)")
        .y_label("error")
        .log_x()
        .log_y()
        .line("err", log)
        .save(dir.join("log"))
        .unwrap();
}
