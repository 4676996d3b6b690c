//! Exact restitution of multiplicative ("Hunt–Crossley family") damping laws.
//!
//! For a free 1-D impact m δ̈ = −F_e(δ)(1 + χ δ̇/δ̇⁻) with **any** elastic part F_e(δ), separating
//! variables (v dv/(1 + χv/v₀) = −F_e dδ/m) and integrating from δ = 0 back to δ = 0 gives the
//! restitution e actually produced by the law as the root of
//!
//! > (1 + e) χ = ln[(1 + χ)/(1 − χ e)]            (contact-laws.md §1.3)
//!
//! It depends on χ only: not on the stiffness, the exponent, the mass or the impact velocity
//! (see also S. Carvalho, J. Martins, Mech. Mach. Theory 139 (2019) 174–194, for Hunt–Crossley).
//! [`effective_restitution`] solves it for e given χ, [`chi_exact`] for χ given the requested e,
//! which makes any multiplicative law restitution-exact ([`crate::damping::DampingFactor::Exact`]).
//!
//! [`kelvin_voigt_restitution`] gives the restitution of the linear spring–dashpot (which depends
//! on the mass) with the tensile-force cut-off.

use crate::error::{positive, ContactError};

/// Root of a scalar function on a bracket by Newton steps safeguarded with bisection.
///
/// `f` returns (value, derivative). `f(lo)` and `f(hi)` must have opposite signs (or one of them
/// be zero); the returned root lies in [lo, hi]. Converges when the bracket or the Newton step is
/// smaller than `x_tol`·max(1, |x|) or the value is exactly zero. Used by the exact damping factor, the restitution
/// relation and Johnson's implicit cylinder law.
pub(crate) fn bracketed_newton(
    mut f: impl FnMut(f64) -> (f64, f64),
    mut lo: f64,
    mut hi: f64,
    x_tol: f64,
    max_iter: usize,
) -> Option<f64> {
    let (f_lo, _) = f(lo);
    let (f_hi, _) = f(hi);
    if f_lo == 0.0 {
        return Some(lo);
    }
    if f_hi == 0.0 {
        return Some(hi);
    }
    if f_lo.is_nan() || f_hi.is_nan() || f_lo.signum() == f_hi.signum() {
        return None;
    }
    // Orient so that f(lo) < 0 < f(hi).
    let increasing = f_lo < 0.0;
    let mut x = 0.5 * (lo + hi);
    for _ in 0..max_iter {
        let (fx, dfx) = f(x);
        if fx == 0.0 {
            return Some(x);
        }
        if (fx < 0.0) == increasing {
            lo = x;
        } else {
            hi = x;
        }
        let tol = x_tol * x.abs().max(1.0);
        if (hi - lo).abs() <= tol {
            return Some(0.5 * (lo + hi));
        }
        let step = fx / dfx;
        let newton = x - step;
        // Accept the Newton step when it stays strictly inside the bracket; bisect otherwise.
        if newton.is_finite() && newton > lo.min(hi) && newton < lo.max(hi) {
            if step.abs() <= tol {
                return Some(newton);
            }
            x = newton;
        } else {
            x = 0.5 * (lo + hi);
        }
    }
    None
}

/// Below this χ the restitution relation is solved through its power series (no cancellation).
const CHI_SERIES: f64 = 0.5;

/// Series form of the relation for small χ: with
/// ln(1+χ) − ln(1−χe) = Σ_k χ^k [(−1)^{k+1} + e^k]/k, the relation divided by χ² becomes
/// G(e) = Σ_{k≥2} χ^{k−2} (e^k − (−1)^k)/k = 0. Returns (G, dG/de).
fn series_residual(chi: f64, e: f64) -> (f64, f64) {
    let mut g = 0.0;
    let mut dg = 0.0;
    let mut chi_pow = 1.0; // χ^{k-2}
    let mut e_pow = e; // e^{k-1}
    let mut sign = 1.0; // (−1)^k
    for k in 2..200 {
        let kf = k as f64;
        let e_k = e_pow * e;
        let term = chi_pow * (e_k - sign) / kf;
        g += term;
        dg += chi_pow * e_pow;
        if term.abs() <= 1e-18 * g.abs().max(1e-300) && k > 4 {
            break;
        }
        chi_pow *= chi;
        e_pow = e_k;
        sign = -sign;
    }
    (g, dg)
}

/// Effective restitution e_eff produced by the damping factor χ in a free 1-D impact: the root
/// e ∈ (0, 1] of (1 + e)χ = ln[(1 + χ)/(1 − χe)] (contact-laws.md §1.3).
///
/// Valid for every χ ≥ 0, including χ = 0 (e = 1, purely elastic) and χ = +∞ (e = 0). Three
/// well-conditioned forms are used: a power series for χ < 0.5, the relation itself for
/// 0.5 ≤ χ ≤ 1, and for χ > 1 the variable w = ln(1 − χe), in which the relation reads
/// w − e^w + 1 + χ − ln(1 + χ) = 0 (concave and increasing: safeguarded Newton converges), so
/// that the asymptote e → 1/χ is resolved to full precision.
///
/// # Errors
/// [`ContactError::InvalidParameter`] for χ < 0 or NaN.
pub fn effective_restitution(chi: f64) -> Result<f64, ContactError> {
    if chi.is_nan() || chi < 0.0 {
        return Err(ContactError::invalid(
            "restitution relation",
            "damping factor chi (-)",
            chi,
            "must be ≥ 0 (χ = 0 is purely elastic)",
        ));
    }
    Ok(effective_restitution_unchecked(chi))
}

/// [`effective_restitution`] for a χ already known to be ≥ 0.
pub(crate) fn effective_restitution_unchecked(chi: f64) -> f64 {
    if chi == 0.0 {
        return 1.0;
    }
    if chi.is_infinite() {
        return 0.0;
    }
    const TOL: f64 = 1e-15;
    let root = if chi < CHI_SERIES {
        // G(0) < 0 < G(1).
        bracketed_newton(|e| series_residual(chi, e), 0.0, 1.0, TOL, 200)
    } else if chi <= 1.0 {
        // g(e) = (1+e)χ − ln(1+χ) + ln(1−χe): g(0) > 0, g → −∞ or < 0 at e = 1.
        let l1 = chi.ln_1p();
        bracketed_newton(
            |e| {
                let one_m = 1.0 - chi * e;
                ((1.0 + e) * chi - l1 + (-chi * e).ln_1p(), chi - chi / one_m)
            },
            0.0,
            1.0,
            TOL,
            200,
        )
    } else {
        // w = ln(1 − χe) ∈ [ln(1+χ) − χ − 1, ln(1+χ) − χ].
        let c = 1.0 + chi - chi.ln_1p();
        let w = bracketed_newton(
            |w| (w - w.exp() + c, 1.0 - w.exp()),
            -c,
            1.0 - c,
            1e-15,
            200,
        );
        return w.map_or(1.0 / chi, |w| (-w.exp_m1() / chi).clamp(0.0, 1.0));
    };
    // Bisection always converges on a valid bracket; the fallback is never reached in practice.
    root.unwrap_or(1.0).clamp(0.0, 1.0)
}

/// Damping factor χ for which a multiplicative law F_e(δ)(1 + χδ̇/δ̇⁻) produces exactly the
/// restitution `c_e` in a free impact, whatever the elastic part (contact-laws.md §1.3,
/// "HC-exact"): the inverse of [`effective_restitution`].
///
/// χ_exact(0.5) = 1.432751, χ_exact(0.9) = 0.166482 (contact-laws.md §7.3). χ_exact(1) = 0.
/// The root lies in [0, 1/c_e) because e_eff(χ) < 1/χ; the bracket [0, 1/c_e + 1] keeps a
/// strict sign change in floating point.
///
/// # Errors
/// [`ContactError::InvalidParameter`] for c_e outside (0, 1]; [`ContactError::NoConvergence`]
/// if the root solve fails (not expected).
pub fn chi_exact(c_e: f64) -> Result<f64, ContactError> {
    check_restitution("exact damping factor", c_e)?;
    if c_e == 1.0 {
        return Ok(0.0);
    }
    // e(χ) − c_e is decreasing in χ; de/dχ from implicit differentiation of
    // F(e, χ) = (1+e)χ − ln(1+χ) + ln(1−χe): de/dχ = −F_χ/F_e.
    let f = |chi: f64| {
        let e = effective_restitution_unchecked(chi);
        let one_m = 1.0 - chi * e;
        let f_chi = (1.0 + e) - 1.0 / (1.0 + chi) - e / one_m;
        let f_e = -chi * chi * e / one_m;
        let de = if f_e != 0.0 { -f_chi / f_e } else { f64::NAN };
        (e - c_e, de)
    };
    bracketed_newton(f, 0.0, 1.0 / c_e + 1.0, 1e-15, 300).ok_or(ContactError::NoConvergence {
        law: "exact damping factor",
        what: "root of e_eff(chi) = c_e",
        iterations: 300,
    })
}

/// Check that a coefficient of restitution lies in (0, 1].
pub(crate) fn check_restitution(law: &'static str, c_e: f64) -> Result<(), ContactError> {
    if c_e > 0.0 && c_e <= 1.0 {
        Ok(())
    } else {
        Err(ContactError::invalid(
            law,
            "coefficient of restitution c_e (-)",
            c_e,
            "must be in (0, 1]; use a small positive value for a nearly plastic impact",
        ))
    }
}

/// Restitution of a linear Kelvin–Voigt contact F = kδ + cδ̇ between a mass m and a fixed wall,
/// with the contact ending when the force returns to zero (no tensile force), which happens while
/// δ > 0.
///
/// With β = c/(2m), ω₀² = k/m, ω_d = √(ω₀² − β²) (underdamped), the motion in contact is
/// δ = (v₀/ω_d) e^{−βt} sin ω_d t; F = 0 first at θ = ω_d t_s = atan2(2βω_d, 2β² − ω₀²), and
/// e = e^{−βt_s}[(β/ω_d) sin θ − cos θ]. Classical result (e.g. T. Schwager, T. Pöschel,
/// Phys. Rev. E 78 (2008) 051304, for the linear dashpot). Units: k in N/m, c in N·s/m, m in kg.
///
/// # Errors
/// [`ContactError::InvalidParameter`] for k ≤ 0, c < 0, m ≤ 0, or an over-critically damped
/// contact (c ≥ 2√(km)), for which this closed form does not apply.
pub fn kelvin_voigt_restitution(k: f64, c: f64, m: f64) -> Result<f64, ContactError> {
    const LAW: &str = "Kelvin–Voigt restitution";
    positive(LAW, "stiffness k (N/m)", k)?;
    positive(LAW, "mass m (kg)", m)?;
    let critical = 2.0 * (k * m).sqrt();
    if !(c >= 0.0 && c < critical) {
        return Err(ContactError::invalid(
            LAW,
            "damping coefficient c (N·s/m)",
            c,
            format!("must be in [0, 2√(km)) = [0, {critical:e}) (underdamped)"),
        ));
    }
    let beta = c / (2.0 * m);
    let w0sq = k / m;
    let wd = (w0sq - beta * beta).sqrt();
    let theta = (2.0 * beta * wd).atan2(2.0 * beta * beta - w0sq);
    let ts = theta / wd;
    Ok((-beta * ts).exp() * (beta / wd * theta.sin() - theta.cos()))
}
