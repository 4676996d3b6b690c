//! Largest Lyapunov exponent of a scalar time series, estimated by the method of Rosenstein,
//! Collins & De Luca (1993), *A practical method for calculating largest Lyapunov exponents from
//! small data sets*, Physica D 65:117–134.
//!
//! The series x₀ … x_{N−1} (uniform step Δt) is embedded in m dimensions with delay τ samples,
//! Y_i = (x_i, x_{i+τ}, …, x_{i+(m−1)τ}). For each Y_i the nearest Y_j with |i − j| > P
//! (temporal exclusion: P about one mean period, so that neighbours are close in state, not in
//! time) starts a pair, and d_i(k) = ‖Y_{i+k} − Y_{j+k}‖ follows it for k = 0 … K (eq. 9). The
//! average ⟨ln d_i(k)⟩ over the pairs grows as λ₁·kΔt + const while the separations are small,
//! so λ₁ is the least-squares slope of that curve over the fit range (eq. 10). A periodic
//! signal gives λ₁ ≈ 0, a chaotic one λ₁ > 0.
//!
//! Cost O(M²·m) for M embedded points: meant for series of a few thousand samples.
//!
//! [`twin_divergence_rate`] is the other estimate, from two runs started a tiny perturbation
//! apart; it needs a second run but no long record.

/// Settings of the estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RosensteinSettings {
    /// Embedding dimension m (≥ 1).
    pub dimension: usize,
    /// Embedding delay τ, samples (≥ 1).
    pub delay: usize,
    /// Temporal exclusion P, samples: neighbours must be more than P samples apart.
    pub exclusion: usize,
    /// Steps K the pairs are followed, fitted over k = 0 … K.
    pub steps: usize,
}

/// The estimate and what it rests on.
#[derive(Debug, Clone, PartialEq)]
pub struct LyapunovEstimate {
    /// Largest Lyapunov exponent λ₁, 1/(unit of Δt).
    pub exponent: f64,
    /// Pairs averaged at k = 0.
    pub pairs: usize,
    /// ⟨ln d(k)⟩, k = 0 … K (the divergence curve, for plots and checks of the fit range).
    pub divergence: Vec<f64>,
}

/// Estimate λ₁ of `x` sampled every `dt`. `None` when the series is too short for the settings
/// (fewer than 2 pairs), a setting is 0 where it must not be, or `dt` ≤ 0.
pub fn largest_exponent(x: &[f64], dt: f64, s: RosensteinSettings) -> Option<LyapunovEstimate> {
    if s.dimension == 0 || s.delay == 0 || s.steps == 0 || dt.is_nan() || dt <= 0.0 {
        return None;
    }
    let span = (s.dimension - 1) * s.delay;
    let m = x.len().checked_sub(span)?;
    // only points that can be followed K steps start pairs
    let starts = m.checked_sub(s.steps)?;
    let dist2 = |i: usize, j: usize| -> f64 {
        (0..s.dimension)
            .map(|d| (x[i + d * s.delay] - x[j + d * s.delay]).powi(2))
            .sum()
    };
    let mut sum = vec![0.0; s.steps + 1];
    let mut count = vec![0usize; s.steps + 1];
    for i in 0..starts {
        let nearest = (0..starts)
            .filter(|&j| i.abs_diff(j) > s.exclusion)
            .map(|j| (j, dist2(i, j)))
            .filter(|&(_, d)| d > 0.0)
            .min_by(|a, b| a.1.total_cmp(&b.1));
        let Some((j, _)) = nearest else { continue };
        for k in 0..=s.steps {
            let d = dist2(i + k, j + k);
            if d > 0.0 {
                sum[k] += 0.5 * d.ln();
                count[k] += 1;
            }
        }
    }
    if count.iter().any(|&c| c < 2) {
        return None;
    }
    let y: Vec<f64> = sum.iter().zip(&count).map(|(s, &c)| s / c as f64).collect();
    Some(LyapunovEstimate {
        exponent: slope(y.iter().enumerate().map(|(k, &v)| (k as f64, v)))? / dt,
        pairs: count[0],
        divergence: y,
    })
}

/// Finite-time divergence rate of two runs that start a tiny perturbation apart (the twin-run
/// estimate of the largest Lyapunov exponent, Benettin et al. 1980, *Meccanica* 15:9–20, one
/// renormalisation-free segment): the least-squares slope of ln d(t) over the samples `d`
/// (distances between the runs at times `t`, uniform or not) up to the first one at or above
/// `saturation`, where the separation stops growing exponentially because it has reached the
/// size of the attractor (later samples are left out). A periodic, stable response gives a
/// rate ≤ 0 (the perturbation stays or decays), a chaotic one a positive rate. `None` with
/// fewer than 3 usable samples (positive d before saturation).
pub fn twin_divergence_rate(t: &[f64], d: &[f64], saturation: f64) -> Option<f64> {
    let end = d.iter().position(|&v| v >= saturation).unwrap_or(d.len());
    let pts = t[..end]
        .iter()
        .zip(&d[..end])
        .filter(|(_, &v)| v > 0.0)
        .map(|(&t, &v)| (t, v.ln()));
    if pts.clone().count() < 3 {
        return None;
    }
    slope(pts)
}

/// Least-squares slope of the points (x, y); `None` when the x do not vary.
fn slope(pts: impl Iterator<Item = (f64, f64)> + Clone) -> Option<f64> {
    let n = pts.clone().count() as f64;
    let (xb, yb) = pts
        .clone()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (num, den) = pts.fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - xb) * (y - yb), b + (x - xb) * (x - xb))
    });
    (den > 0.0).then(|| num / den)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Settings for the two maps: m = 2, τ = 1, fit over k = 0..4 (see each test).
    const MAP_SETTINGS: RosensteinSettings = RosensteinSettings {
        dimension: 2,
        delay: 1,
        exclusion: 1,
        steps: 4,
    };

    // Logistic map x ↦ 4x(1 − x): λ₁ = ln 2 exactly (it is conjugate to the tent map).
    // 2000 iterates, m = 2, τ = 1, fit over k = 0..4 (the separations saturate at the attractor
    // size after about ln(1/d₀)/ln 2 ≈ 9 steps from d₀ ≈ 1e-3). Rosenstein et al. report
    // errors of a few % on 1000-point logistic series; tolerance 10 %.
    #[test]
    fn logistic_map_gives_ln_2() {
        let mut x = vec![0.123_456_7];
        for _ in 1..2000 {
            let v = x[x.len() - 1];
            x.push(4.0 * v * (1.0 - v));
        }
        let e = largest_exponent(&x, 1.0, MAP_SETTINGS).unwrap();
        let ln2 = std::f64::consts::LN_2;
        assert!(
            (e.exponent - ln2).abs() < 0.1 * ln2,
            "λ = {} (ln 2 = {ln2}), {:?}",
            e.exponent,
            e.divergence
        );
    }

    // Hénon map (a = 1.4, b = 0.3): λ₁ = 0.419 per iteration (Sprott 2003, Chaos and
    // Time-Series Analysis, table A.1: 0.41922); Rosenstein et al. (1993, table 2) recover it
    // within a few % from the x series alone with m = 2. Tolerance 10 %.
    #[test]
    fn henon_map_gives_its_exponent() {
        let (mut u, mut v) = (0.1, 0.1);
        let mut x = Vec::new();
        for k in 0..2100 {
            let (un, vn) = (1.0 - 1.4 * u * u + v, 0.3 * u);
            (u, v) = (un, vn);
            if k >= 100 {
                x.push(u);
            }
        }
        let e = largest_exponent(&x, 1.0, MAP_SETTINGS).unwrap();
        assert!(
            (e.exponent - 0.41922).abs() < 0.042,
            "λ = {}, {:?}",
            e.exponent,
            e.divergence
        );
    }

    // Twin runs of the logistic map started 1e-12 apart separate as e^(λk), λ = ln 2 on average
    // (closed form of the map's exponent); the fit stops at the first separation ≥ 0.1, the
    // attractor's size being 1. Tolerance 15 %: a single pair follows the local stretching
    // factors |4 − 8x| along its path, not their long-run mean (20 to 35 steps here).
    // An exponential d = 1e-9·e^(3t) gives exactly 3, and a constant separation 0.
    #[test]
    fn twin_rate_recovers_exponential_growth() {
        let (mut a, mut b) = (0.3_f64, 0.3 + 1e-12);
        let (mut t, mut d) = (Vec::new(), Vec::new());
        for k in 0..60 {
            t.push(k as f64);
            d.push((a - b).abs());
            a = 4.0 * a * (1.0 - a);
            b = 4.0 * b * (1.0 - b);
        }
        let ln2 = std::f64::consts::LN_2;
        let r = twin_divergence_rate(&t, &d, 0.1).unwrap();
        assert!((r - ln2).abs() < 0.15 * ln2, "rate {r}");
        let t: Vec<f64> = (0..50).map(|k| k as f64 * 0.02).collect();
        let d: Vec<f64> = t.iter().map(|&t| 1e-9 * (3.0 * t).exp()).collect();
        assert!((twin_divergence_rate(&t, &d, 1.0).unwrap() - 3.0).abs() < 1e-9);
        assert!(
            twin_divergence_rate(&t, &vec![1e-6; 50], 1.0)
                .unwrap()
                .abs()
                < 1e-9
        );
        assert!(twin_divergence_rate(&t[..2], &d[..2], 1.0).is_none());
    }

    // A periodic signal does not diverge: λ₁ ≈ 0. sin(2πt/T) + 0.3 sin(6πt/T) sampled 100.37
    // times per period (not a whole number, so that neighbours are a fraction of a sample
    // apart, not at rounding level) over 20 periods; |λ₁·T| < 0.05 (e-folds per period; a
    // chaotic response would show order 1).
    #[test]
    fn periodic_signal_gives_zero() {
        let t_per = 0.5;
        let dt = t_per / 100.37;
        let x: Vec<f64> = (0..2000)
            .map(|k| {
                let t = k as f64 * dt;
                let w = 2.0 * std::f64::consts::PI / t_per;
                (w * t).sin() + 0.3 * (3.0 * w * t).sin()
            })
            .collect();
        let s = RosensteinSettings {
            dimension: 3,
            delay: 25,
            exclusion: 50,
            steps: 50,
        };
        let e = largest_exponent(&x, dt, s).unwrap();
        assert!((e.exponent * t_per).abs() < 0.05, "λ = {}", e.exponent);
        assert!(largest_exponent(&x[..10], dt, s).is_none());
    }
}
