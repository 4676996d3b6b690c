//! One row of the ODE benchmark table ([`Row`]) and the timing loop behind its wall time
//! ([`timed`]): shared by the clr-ode runs (`clr.rs`), the peers' rows (`peers.rs`) and the
//! table (`ode.rs`).

use std::time::Instant;

use serde::{Deserialize, Serialize};

/// One row of the benchmark table.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Row {
    pub problem: String,
    pub solver: String,
    pub rtol: f64,
    pub atol: f64,
    /// Median wall time of one solve (s).
    pub wall_s: f64,
    pub f_evals: usize,
    pub steps: usize,
    /// Mixed-error significant correct digits at t_end against the Test Set reference.
    #[serde(default)]
    pub scd: f64,
    /// Number of timed solves behind the median.
    #[serde(default)]
    pub repeats: usize,
}

/// Median of a non-empty sample.
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Repeat `solve` at least 5 times and `min_time` seconds (at most 100 000 times) and return the
/// median wall time with the last result.
pub fn timed<T>(
    min_time: f64,
    mut solve: impl FnMut() -> Result<T, String>,
) -> Result<(f64, usize, T), String> {
    let mut times = Vec::new();
    let mut total = 0.0;
    loop {
        let start = Instant::now();
        let out = solve()?;
        let dt = start.elapsed().as_secs_f64();
        total += dt;
        times.push(dt);
        if times.len() >= 100_000 || (times.len() >= 5 && total >= min_time) {
            let n = times.len();
            return Ok((median(times), n, out));
        }
    }
}
