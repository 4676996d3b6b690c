//! `mbd.jacobian.*`: the analytic Jacobians of clr-mbd (`Model::jacobians`: joints, forces,
//! floating-frame bodies, node ties and the contact elements) against central differences of
//! the whole model (`Model::jacobians_fd_best`) on every built-in model of the catalog, at
//! states along a short run, in contact.
//!
//! Each model is compiled from its `desc()` and integrated from its consistent initial state in
//! segments of `dt` (its own solver and tolerances); at the end of each segment (an accepted
//! state: the run commits the contact memory there, so the impact velocities are constants of
//! both forms) the two Jacobians are compared, until `wanted` states with contact forces were
//! seen or `t_max` is reached. Each segment starts a new run, which re-commits the memory at its
//! start (an ongoing contact takes its current δ̇, or the floor 10⁻⁴ m/s when separating, as
//! impact velocity): the derivatives hold for any committed memory, and the floor, which makes
//! ∂F_N/∂δ̇ = F_e χ/δ̇⁻ large, is the harder case for the reference.
//!
//! Value: over the states and over ∂Q/∂q, ∂Q/∂q̇ and (Φ_q q̇)_q, the largest normwise relative
//! error by column and by row, ‖A_k − F_k‖₂ / max(‖F_k‖₂, 10⁻⁶ max_k′ ‖F_k′‖₂, ‖U_k‖₂/TOL)
//! (k a column, then a row). By column so that an error in one body's columns is not hidden by
//! the contact stiffness (10⁸–10¹⁰ N/m) in another's, by row so that a row of moments is not
//! hidden by the forces in its columns. The reference F is `Model::jacobians_fd_best`: per
//! column, the middle of the three neighbouring relative steps of 10⁻⁴…10⁻¹⁰ that agree best,
//! with U the larger of their two differences, its own error estimate. Where U exceeds TOL·‖F_k‖
//! (columns that are zero but for rounding: e.g. ∂Q/∂ω of a journal without friction, where
//! F_e χ/δ̇⁻ ≈ 10⁷ N·s/m turns the rounding of δ̇ (10⁻¹⁵ m/s at 26 m/s) into 10⁻⁸ N of noise),
//! the difference is measured against the reference's uncertainty instead: the check cannot be
//! sharper than its reference. The floor 10⁻⁶ of the largest norm is below what central
//! differences resolve next to it (rounding ε|Q|/h).
//!
//! Tolerance 10⁻⁴: the reference's own error at the contact states of these models
//! (penetrations of 10⁻⁹–10⁻⁵ m, forces up to 10⁵ N) is 10⁻⁸–10⁻⁵ (truncation (h/δ)² on the
//! shallow points, rounding ε|Q|/h on the loaded ones, the kinks of the laws and of the beam's
//! C¹ interpolation at nodes, where a stencil that straddles one averages the two sides). An
//! error in an analytic term shows up as 10⁻³–1 (checked by perturbing the analytic forms: a 10 %
//! error in ∂F_N/∂δ̇ gives 0.1–0.8 on every model). The case fails when a model reaches no state
//! with a contact force: the comparison would not have exercised the contact elements.
//! `CLR_JAC_DEBUG=1` prints the columns over the tolerance.

use std::time::Instant;

use clr_mbd::{ContactReport, Jacobians, Model, ModelDesc, SimOptions};
use clr_ode::OdeSystem;

use super::Filter;
use crate::report::Case;

/// Largest error the case accepts (module docs).
const TOL: f64 = 1e-4;

/// A built-in model and how to sample it.
struct Spec {
    id: &'static str,
    desc: fn() -> Result<ModelDesc, String>,
    /// Segment length, s.
    dt: f64,
    /// Latest time sampled, s.
    t_max: f64,
    /// States with contact force to compare.
    wanted: usize,
}

fn e(r: Result<ModelDesc, clr_models::ModelsError>) -> Result<ModelDesc, String> {
    r.map_err(|e| e.to_string())
}

fn specs() -> Vec<Spec> {
    use clr_models::dual_guide::DualGuideParams;
    use clr_models::flap::FlapParams;
    use clr_models::guide::GuideParams;
    use clr_models::manipulator::ManipulatorParams;
    use clr_models::slider_crank::SliderCrankParams;
    vec![
        Spec {
            id: "slider_crank",
            desc: || e(SliderCrankParams::flores().desc("slider_crank")),
            dt: 5e-4,
            t_max: 0.02,
            wanted: 6,
        },
        Spec {
            id: "wan_slider_crank",
            desc: || e(SliderCrankParams::wan().desc("wan_slider_crank")),
            dt: 2e-3,
            t_max: 0.1,
            wanted: 6,
        },
        Spec {
            id: "flap",
            desc: || e(FlapParams::default().desc("flap")),
            dt: 5e-3,
            t_max: 0.2,
            wanted: 6,
        },
        Spec {
            id: "flap_flex",
            desc: || {
                let p = FlapParams {
                    flexible: [true; 3],
                    ..FlapParams::default()
                };
                e(p.desc("flap_flex"))
            },
            dt: 5e-3,
            t_max: 0.1,
            wanted: 4,
        },
        Spec {
            id: "guide",
            desc: || e(GuideParams::default().desc("guide")),
            dt: 2e-3,
            t_max: 0.1,
            wanted: 6,
        },
        Spec {
            id: "dual_guide",
            desc: || e(DualGuideParams::default().desc("dual_guide")),
            dt: 2e-3,
            t_max: 0.05,
            wanted: 4,
        },
        Spec {
            id: "manipulator",
            desc: || e(ManipulatorParams::default().desc("manipulator")),
            dt: 0.02,
            t_max: 1.0,
            wanted: 6,
        },
    ]
}

/// The largest of the column- and row-normwise errors of `a` against `f` (rows × n, row-major):
/// ‖a_k − f_k‖₂ / max(‖f_k‖₂, 10⁻⁶ max_k′ ‖f_k′‖₂, ‖u_k‖₂/TOL) over the columns k and over the
/// rows k, with u the reference's error estimate (module docs).
fn column_error(a: &[f64], f: &[f64], u: &[f64], n: usize) -> f64 {
    let rows = a.len() / n.max(1);
    let by = |len: usize, m: usize, at: &dyn Fn(usize, usize) -> usize| {
        let norm = |k: usize, x: &dyn Fn(usize) -> f64| {
            (0..m).map(|i| x(at(k, i)).powi(2)).sum::<f64>().sqrt()
        };
        let big = (0..len).map(|k| norm(k, &|e| f[e])).fold(0.0, f64::max);
        (0..len)
            .map(|k| {
                let scale = norm(k, &|e| f[e])
                    .max(1e-6 * big)
                    .max(norm(k, &|e| u[e]) / TOL);
                norm(k, &|e| a[e] - f[e]) / scale.max(1e-300)
            })
            .fold(0.0, f64::max)
    };
    by(n, rows, &|c, r| r * n + c).max(by(rows, n, &|r, c| r * n + c))
}

fn error(a: &Jacobians, (f, u): &(Jacobians, Jacobians), n: usize) -> f64 {
    [
        column_error(&a.dq, &f.dq, &u.dq, n),
        column_error(&a.dv, &f.dv, &u.dv, n),
        column_error(&a.phi_qqd_q, &f.phi_qqd_q, &u.phi_qqd_q, n),
    ]
    .into_iter()
    .fold(0.0, f64::max)
}

/// What the comparison saw on one model.
#[derive(Default)]
struct Seen {
    worst: f64,
    states: usize,
    in_contact: usize,
    points: usize,
    /// Per state with contact forces: the largest |F_T|/F_N of its loaded elements.
    ratios: Vec<f64>,
    fallback: Vec<String>,
}

impl Seen {
    /// (sliding, sticking) states: at the largest friction ratio seen on the model (μ of the
    /// law's sliding branch) or below it (the regularized, sticking branch); (0, 0) without
    /// friction.
    fn slip(&self) -> (usize, usize) {
        let mu = self.ratios.iter().copied().fold(0.0, f64::max);
        if mu == 0.0 {
            return (0, 0);
        }
        let sliding = self.ratios.iter().filter(|&&r| r >= 0.99 * mu).count();
        (sliding, self.ratios.len() - sliding)
    }
}

/// Compare at the accepted state y (time t) and record.
fn compare(m: &mut Model, t: f64, y: &[f64], seen: &mut Seen) {
    let n = m.n_coordinates();
    let mut dy = vec![0.0; m.dim()];
    m.rhs(t, y, &mut dy);
    let reports = m.contact_reports().to_vec();
    let loaded: Vec<_> = reports.iter().filter(|r| r.normal_force > 0.0).collect();
    let (q, qd) = (&y[..n], &y[n..2 * n]);
    let a = m.jacobians(t, q, qd);
    let f = m.jacobians_fd_best(t, q, qd);
    let err = error(&a, &f, n);
    if err > TOL && std::env::var("CLR_JAC_DEBUG").is_ok() {
        debug(&a, &f, n, t, &reports);
    }
    seen.worst = seen.worst.max(err);
    seen.states += 1;
    seen.fallback = a.fallback;
    if !loaded.is_empty() {
        seen.in_contact += 1;
        seen.points += loaded.iter().map(|r| r.active_points).sum::<usize>();
        let ratio = loaded
            .iter()
            .map(|r| r.friction_force.abs() / r.normal_force)
            .fold(0.0, f64::max);
        seen.ratios.push(ratio);
    }
}

/// Print the columns over the tolerance (`CLR_JAC_DEBUG=1`).
fn debug(a: &Jacobians, (f, u): &(Jacobians, Jacobians), n: usize, t: f64, r: &[ContactReport]) {
    eprintln!("t = {t}: reports {r:?}");
    for (name, x, z, e) in [
        ("dQ/dq", &a.dq, &f.dq, &u.dq),
        ("dQ/dqd", &a.dv, &f.dv, &u.dv),
        ("(Phi_q qd)_q", &a.phi_qqd_q, &f.phi_qqd_q, &u.phi_qqd_q),
    ] {
        let rows = x.len() / n;
        for c in 0..n {
            let pick = |v: &[f64]| (0..rows).map(|r| v[r * n + c]).collect::<Vec<_>>();
            let err = column_error(&pick(x), &pick(z), &pick(e), 1);
            if err > TOL {
                eprintln!("  {name} column {c}: {err:e}; (analytic, FD, FD error) by row:");
                for row in 0..rows {
                    eprintln!(
                        "    {row}: {:e} {:e} {:e}",
                        x[row * n + c],
                        z[row * n + c],
                        e[row * n + c]
                    );
                }
            }
        }
    }
}

/// Run the model in segments and compare along the way.
fn sample(spec: &Spec) -> Result<Seen, String> {
    let desc = (spec.desc)()?;
    let base = desc.sim_options().map_err(|e| e.to_string())?;
    let mut m = desc.compile().map_err(|e| e.to_string())?;
    let mut t = base.t0;
    let mut y = m.initial_state(t).map_err(|e| e.to_string())?;
    let mut seen = Seen::default();
    while seen.in_contact < spec.wanted && t < spec.t_max - 1e-12 {
        let opts = SimOptions {
            t0: t,
            t_end: t + spec.dt,
            times: Vec::new(),
            every_step: false,
            ..base.clone()
        };
        let res = m.simulate_from(&opts, &y).map_err(|e| e.to_string())?;
        y = res.y_final;
        t += spec.dt;
        compare(&mut m, t, &y, &mut seen);
    }
    Ok(seen)
}

pub fn cases(filter: &Filter) -> Vec<Case> {
    let src = "central differences of the whole model (Model::jacobians_fd_best: per column the \
               best agreeing relative steps of 1e-4…1e-10), an independent formulation of the \
               same derivatives; states along a short run of each built-in model, in contact";
    let mut out = Vec::new();
    for spec in specs() {
        let id = format!("mbd.jacobian.{}", spec.id);
        if !filter.wants(&id) {
            continue;
        }
        let case = Case::new(
            id.clone(),
            "largest column- and row-normwise relative error, analytic vs central-difference \
             Jacobians (∂Q/∂q, ∂Q/∂q̇, (Φ_q q̇)_q) at contact states",
            "-",
            src,
        );
        let start = Instant::now();
        out.push(match sample(&spec) {
            Ok(s) => {
                let value = if s.in_contact == 0 { f64::NAN } else { s.worst };
                let (sliding, sticking) = s.slip();
                let note = format!(
                    "{} states compared to t = {:.3} s, {} with contact forces ({} loaded \
                     points; sliding in {}, sticking in {}); worst error {:.2e}; on the \
                     central-difference fallback: {} element(s){}; {:.1} s",
                    s.states,
                    spec.t_max.min(s.states as f64 * spec.dt),
                    s.in_contact,
                    s.points,
                    sliding,
                    sticking,
                    s.worst,
                    s.fallback.len(),
                    if s.fallback.is_empty() {
                        String::new()
                    } else {
                        format!(" ({})", s.fallback.join(", "))
                    },
                    start.elapsed().as_secs_f64()
                );
                println!("{id}: {note}");
                case.at_most(value, TOL).note(note)
            }
            Err(e) => case.failed(TOL, e),
        });
    }
    out
}
