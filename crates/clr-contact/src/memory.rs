//! Contact memory: the impact velocity δ̇⁻ of every contact point as explicit state.
//!
//! Hunt–Crossley-type laws F = F_e(δ)(1 + χ δ̇/δ̇⁻) need δ̇⁻, the penetration rate at the onset of
//! the current contact (`contact-laws.md` §1.6). It is not a function of the current state, so an
//! integrator must carry it. [`ContactMemory`] keeps it for a fixed number of contact points with
//! these rules:
//!
//! 1. **Committed values change only in [`ContactMemory::commit`]**, which the caller invokes once
//!    per *accepted* step with the state at the end of the step.
//! 2. During a step, [`ContactMemory::impact_velocity`] gives the δ̇⁻ to use at a trial state
//!    (a Runge–Kutta stage, a Newton iterate). For a contact already open in the committed memory
//!    it is the committed δ̇⁻. For a contact that is closed in the committed memory but penetrates
//!    at the trial state, it is a *tentative* onset value: δ̇ interpolated at the crossing δ = 0
//!    between the last committed (δ, δ̇) and the trial (δ, δ̇) ([`crossing_rate`]). Tentative
//!    values are stored separately and never touch the committed ones.
//! 3. **On a rejected step** call [`ContactMemory::discard`]: the tentative values are dropped and
//!    the committed memory is exactly what it was at the start of the step.
//! 4. At commit, a point with δ ≤ 0 is **reset** (contact closed); a point with δ > 0 that was
//!    closed records a **new onset** δ̇⁻ (the same crossing interpolation); a point that stays in
//!    contact keeps its δ̇⁻ unchanged. A contact that separates and closes again therefore gets a
//!    fresh δ̇⁻.
//! 5. δ̇⁻ is floored at a positive `minimum_impact_velocity` (m/s): laws divide by it, and a
//!    contact that starts at rest (resting contact) would otherwise divide by zero. Chrono's SMC
//!    contact uses the same device ("characteristic velocity").
//!
//! Because the tentative value depends only on the committed memory and the trial state, the
//! contact force is a deterministic function of the state during a step, as an ODE solver needs.
//! Nothing here allocates after [`ContactMemory::new`].

use crate::error::ContactError;

/// Committed state of one contact point.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Point {
    /// δ̇⁻ of the open contact, m/s; `None` while the contact is closed.
    onset: Option<f64>,
    /// (δ, δ̇) at the last commit, `None` before the first commit.
    last: Option<(f64, f64)>,
}

const CLOSED: Point = Point {
    onset: None,
    last: None,
};

/// Per-point storage of the impact velocity δ̇⁻ with commit / discard semantics (module docs).
#[derive(Debug, PartialEq)]
pub struct ContactMemory {
    committed: Vec<Point>,
    tentative: Vec<Option<f64>>,
    minimum_impact_velocity: f64,
}

impl Clone for ContactMemory {
    fn clone(&self) -> Self {
        Self {
            committed: self.committed.clone(),
            tentative: self.tentative.clone(),
            minimum_impact_velocity: self.minimum_impact_velocity,
        }
    }

    /// Copies into the existing buffers: no allocation when the point counts match (saving and
    /// restoring the memory around trial evaluations, e.g. for Jacobians).
    fn clone_from(&mut self, source: &Self) {
        self.committed.clone_from(&source.committed);
        self.tentative.clone_from(&source.tentative);
        self.minimum_impact_velocity = source.minimum_impact_velocity;
    }
}

impl ContactMemory {
    /// Memory for `points` contact points with all contacts closed; δ̇⁻ is floored at
    /// `minimum_impact_velocity` (m/s, > 0; 1e-4 m/s is a common choice).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] when `minimum_impact_velocity` is not positive and finite.
    pub fn new(points: usize, minimum_impact_velocity: f64) -> Result<Self, ContactError> {
        if !(minimum_impact_velocity.is_finite() && minimum_impact_velocity > 0.0) {
            return Err(ContactError::invalid(
                "contact memory",
                "minimum impact velocity (m/s)",
                minimum_impact_velocity,
                "must be positive and finite (for example 1e-4 m/s); the force laws divide by the impact velocity",
            ));
        }
        Ok(Self {
            committed: vec![CLOSED; points],
            tentative: vec![None; points],
            minimum_impact_velocity,
        })
    }

    /// Number of contact points.
    pub fn len(&self) -> usize {
        self.committed.len()
    }

    /// True when the memory holds no contact point.
    pub fn is_empty(&self) -> bool {
        self.committed.is_empty()
    }

    /// The floor applied to every δ̇⁻, m/s.
    pub fn minimum_impact_velocity(&self) -> f64 {
        self.minimum_impact_velocity
    }

    /// Committed δ̇⁻ of point `k` (m/s), `None` while that contact is closed or `k` is out of range.
    pub fn committed(&self, k: usize) -> Option<f64> {
        self.committed.get(k).and_then(|p| p.onset)
    }

    /// Tentative onset δ̇⁻ of point `k` computed during the current step, if any (m/s).
    pub fn tentative(&self, k: usize) -> Option<f64> {
        self.tentative.get(k).copied().flatten()
    }

    /// The δ̇⁻ (m/s) to use in the force law of point `k` at a trial state with penetration
    /// `delta` (m) and penetration rate `delta_dot` (m/s), following rule 2 of the module docs.
    /// For δ ≤ 0 there is no force; the floor is returned so that callers can still evaluate laws.
    /// An index out of range is treated as a contact without history (δ̇⁻ = max(δ̇, floor)).
    pub fn impact_velocity(&mut self, k: usize, delta: f64, delta_dot: f64) -> f64 {
        let floor = self.minimum_impact_velocity;
        let Some(point) = self.committed.get(k).copied() else {
            return delta_dot.max(floor);
        };
        if let Some(v) = point.onset {
            return v;
        }
        if delta <= 0.0 {
            self.tentative[k] = None;
            return floor;
        }
        let v = onset_rate(point.last, delta, delta_dot).max(floor);
        self.tentative[k] = Some(v);
        v
    }

    /// Accept the end state of a step for point `k`: δ (m) and δ̇ (m/s) there (rules 1 and 4).
    /// Out-of-range indices are ignored. Clears the tentative value of `k`.
    pub fn commit(&mut self, k: usize, delta: f64, delta_dot: f64) {
        let floor = self.minimum_impact_velocity;
        let Some(point) = self.committed.get_mut(k) else {
            return;
        };
        if delta <= 0.0 {
            point.onset = None;
        } else if point.onset.is_none() {
            point.onset = Some(onset_rate(point.last, delta, delta_dot).max(floor));
        }
        point.last = Some((delta, delta_dot));
        self.tentative[k] = None;
    }

    /// Reject the current step: drop every tentative value (rule 3). Committed values are
    /// untouched.
    pub fn discard(&mut self) {
        self.tentative.iter_mut().for_each(|t| *t = None);
    }

    /// Forget everything: all contacts closed, no history (e.g. on a restart from new initial
    /// conditions).
    pub fn reset(&mut self) {
        self.committed.iter_mut().for_each(|p| *p = CLOSED);
        self.discard();
    }
}

/// δ̇ at the onset given the last committed (δ, δ̇) and the current penetrating state.
fn onset_rate(last: Option<(f64, f64)>, delta: f64, delta_dot: f64) -> f64 {
    match last {
        Some((d0, v0)) if d0 <= 0.0 => crossing_rate(d0, v0, delta, delta_dot),
        // No history (contact present at the first state) or the last committed state was already
        // penetrating while the contact was marked closed: the current rate is the best estimate.
        _ => delta_dot,
    }
}

/// Penetration rate at the crossing δ = 0, interpolated linearly in δ between a state before
/// (δ₀ ≤ 0, δ̇₀) and a state after (δ₁ > 0, δ̇₁) the onset:
/// δ̇* = δ̇₀ + θ (δ̇₁ − δ̇₀) with θ = δ₀/(δ₀ − δ₁) ∈ [0, 1].
///
/// Exact when δ̇ varies linearly with δ across the step (constant acceleration in free flight is
/// not exactly that; the error is O(h²) in the step h). If the states do not bracket the crossing
/// the after-state rate δ̇₁ is returned.
pub fn crossing_rate(delta0: f64, rate0: f64, delta1: f64, rate1: f64) -> f64 {
    if delta0 <= 0.0 && delta1 > 0.0 {
        let theta = delta0 / (delta0 - delta1);
        rate0 + theta * (rate1 - rate0)
    } else {
        rate1
    }
}

/// Penetration rate at the crossing δ = 0 from the cubic Hermite interpolant of one step of
/// length `h` (s) between (δ₀ ≤ 0, δ̇₀) and (δ₁ > 0, δ̇₁), the dense output most integrators
/// provide. The crossing time is found by bisection refined with Newton on the cubic, and δ̇ of
/// the cubic there is returned. Exact when δ(t) is a cubic over the step (e.g. free flight under
/// constant acceleration, a quadratic). Falls back to [`crossing_rate`] when the states do not
/// bracket the crossing or `h` is not positive and finite.
pub fn crossing_rate_hermite(h: f64, delta0: f64, rate0: f64, delta1: f64, rate1: f64) -> f64 {
    if !(delta0 <= 0.0 && delta1 > 0.0 && h.is_finite() && h > 0.0) {
        return crossing_rate(delta0, rate0, delta1, rate1);
    }
    // Cubic in θ ∈ [0, 1]: p(θ) = h00 δ₀ + h10 h δ̇₀ + h01 δ₁ + h11 h δ̇₁.
    let p = |t: f64| {
        let t2 = t * t;
        let t3 = t2 * t;
        (2.0 * t3 - 3.0 * t2 + 1.0) * delta0
            + (t3 - 2.0 * t2 + t) * h * rate0
            + (-2.0 * t3 + 3.0 * t2) * delta1
            + (t3 - t2) * h * rate1
    };
    // dp/dt / h: the rate δ̇ at θ.
    let dp = |t: f64| {
        let t2 = t * t;
        ((6.0 * t2 - 6.0 * t) * delta0
            + (3.0 * t2 - 4.0 * t + 1.0) * h * rate0
            + (-6.0 * t2 + 6.0 * t) * delta1
            + (3.0 * t2 - 2.0 * t) * h * rate1)
            / h
    };
    // Bisection keeps the root bracketed (p(0) ≤ 0 < p(1)); Newton steps accelerate it when they
    // stay inside the bracket. The first crossing is wanted, so bracket from the left.
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    let mut t = crossing_rate(delta0, 0.0, delta1, 1.0); // linear guess θ = δ₀/(δ₀ − δ₁)
    for _ in 0..100 {
        let f = p(t);
        if f <= 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let d = dp(t) * h;
        let newton = if d != 0.0 { t - f / d } else { f64::NAN };
        t = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if hi - lo <= 1e-15 || f == 0.0 {
            break;
        }
    }
    dp(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_crossing_is_exact_for_linear_rate() {
        // δ̇ = 2 − δ (linear in δ): crossing at δ = 0 gives δ̇ = 2 exactly.
        let v = crossing_rate(-0.5, 2.5, 1.0, 1.0);
        assert!((v - 2.0).abs() < 1e-15);
    }

    #[test]
    fn hermite_crossing_is_exact_for_constant_acceleration() {
        // δ(t) = −1e-6 + 0.5 t − 0.5·9.81 t² over h = 1e-5 s: crossing where δ = 0.
        let (a, v0, d0, h) = (-9.81, 0.5, -1e-6, 4e-6);
        let d = |t: f64| d0 + v0 * t + 0.5 * a * t * t;
        let v = |t: f64| v0 + a * t;
        let tc = (-v0 + (v0 * v0 - 2.0 * a * d0).sqrt()) / a;
        let got = crossing_rate_hermite(h, d(0.0), v(0.0), d(h), v(h));
        assert!((got - v(tc)).abs() < 1e-12, "{got} vs {}", v(tc));
    }
}
