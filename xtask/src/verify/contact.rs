//! Verification cases of clr-contact's normal-force laws (contact-laws.md §1.3, §4;
//! paper-systems.md §1.1) and the figures of docs/contact.md.
//!
//! The journal–bearing impact of the flap paper (Wan et al., Machines 10 (2022) 1098) is
//! integrated with clr-ode (Dormand–Prince 5(4), rtol 1e-12): the journal starts concentric and
//! moves radially at 0.5 m/s towards a fixed bearing; a terminal event at δ = 0 captures the
//! impact velocity δ̇⁻, then the contact phase runs to the separation event (δ = 0 falling).
//! The measured restitution is |δ̇ at separation| / δ̇⁻.

use std::path::Path;

use clr_contact::damping::DampingFactor;
use clr_contact::elastic::ElasticLaw;
use clr_contact::normal::{JournalBearing, NormalLaw};
use clr_ode::{Direction, Dopri5, OdeFn, Options, Output};
use clr_plot::{Figure, Style};

use super::Filter;
use crate::report::Case;

/// Journal mass (kg) and initial radial velocity (m/s) of the flap paper's impact test.
const MASS: f64 = 1.0;
const V0: f64 = 0.5;
/// Input coefficient of restitution of the test (paper-systems.md §1.1).
const C_E: f64 = 0.5;

/// What one simulated impact measured.
struct Impact {
    /// Impact velocity δ̇⁻ captured at the onset event (m/s).
    v_in: f64,
    /// Separation velocity (m/s, negative).
    v_out: f64,
    /// Peak penetration (m).
    delta_max: f64,
    /// Peak normal force (N).
    f_max: f64,
    /// Contact time (s).
    t_c: f64,
    /// Time (s) and state [x, ẋ] at separation.
    t_end: f64,
    y_end: [f64; 2],
    /// (δ, F) along the contact, for the hysteresis figure.
    loop_points: Vec<(f64, f64)>,
    /// Accepted steps of both phases.
    steps: usize,
}

impl Impact {
    fn restitution(&self) -> f64 {
        -self.v_out / self.v_in
    }
}

/// Integrate the journal's 1-D radial motion through its first impact with clr-ode.
fn simulate(law: NormalLaw, clearance: f64) -> Result<Impact, String> {
    simulate_from(law, clearance, 1.0, 0.0, [0.0, V0])
}

/// Free flight from (t0, y0 = [x, ẋ]) to the bearing wall on the side `side` = ±1 (x = side·c),
/// then the contact phase to separation. With δ = side·x − c and δ̇ = side·ẋ the journal obeys
/// m ẍ = −side·F(δ, δ̇, δ̇⁻). Velocities in [`Impact`] are δ̇ values.
fn simulate_from(
    law: NormalLaw,
    clearance: f64,
    side: f64,
    t0: f64,
    y0: [f64; 2],
) -> Result<Impact, String> {
    let opts = || Options::default().rtol(1e-12).atol_vec(vec![1e-17, 1e-13]);
    // Phase 1: free flight until δ = side·x − c crosses 0 (terminal event).
    let mut flight = OdeFn::new(2, |_t, y: &[f64], dy: &mut [f64]| {
        dy[0] = y[1];
        dy[1] = 0.0;
    })
    .event(Direction::Rising, true, move |_t, y: &[f64]| {
        side * y[0] - clearance
    });
    let mut solver = Dopri5::new(opts().output(Output::End));
    let sol = solver
        .solve(&mut flight, t0, &y0, t0 + 1.0)
        .map_err(|e| format!("free flight: {e}"))?;
    let onset = sol
        .events
        .first()
        .ok_or("free flight: no contact onset event")?;
    let (t0, y0) = (onset.t, onset.y.clone());
    // δ̇⁻ captured at the onset event and kept for this contact only.
    let v_in = side * y0[1];
    // Phase 2: contact to the separation event; states recorded on a fine grid (2e-9 s) so
    // the peaks are resolved far below the 1e-3 tolerance.
    let mut contact = OdeFn::new(2, move |_t, y: &[f64], dy: &mut [f64]| {
        dy[0] = y[1];
        dy[1] = -side * law.force(side * y[0] - clearance, side * y[1], v_in) / MASS;
    })
    .event(Direction::Falling, true, move |_t, y: &[f64]| {
        side * y[0] - clearance
    });
    let t_end = t0 + 2e-3;
    let grid: Vec<f64> = (1..1_000_000)
        .map(|i| t0 + i as f64 * 2e-9)
        .take_while(|&t| t < t_end)
        .collect();
    let mut solver = Dopri5::new(opts().output(Output::Times(grid)));
    let sol = solver
        .solve(&mut contact, t0, &y0, t_end)
        .map_err(|e| format!("contact phase: {e}"))?;
    let end = sol
        .events
        .first()
        .ok_or("contact phase: no separation within 2 ms")?;
    let mut delta_max = 0.0f64;
    let mut f_max = 0.0f64;
    let mut loop_points = Vec::new();
    for (k, (_, y)) in sol.iter().enumerate() {
        let d = side * y[0] - clearance;
        let f = law.force(d, side * y[1], v_in);
        delta_max = delta_max.max(d);
        f_max = f_max.max(f);
        if k % 200 == 0 {
            loop_points.push((d * 1e6, f));
        }
    }
    Ok(Impact {
        v_in,
        v_out: side * end.y[1],
        delta_max,
        f_max,
        t_c: end.t - t0,
        t_end: end.t,
        y_end: [end.y[0], end.y[1]],
        loop_points,
        steps: sol.stats.accepted,
    })
}

/// The flap paper's restitution table (paper-systems.md §1.1): preset label, case id suffix,
/// measured restitution.
const FLAP_TABLE: [(&str, &str, f64); 6] = [
    ("Hertz", "hertz", 1.0),
    ("LN", "ln", 0.726),
    ("Gonthier", "gonthier", 0.488),
    ("Bai", "bai", 0.482),
    ("Wang", "wang", 0.482),
    ("Modified", "modified", 0.488),
];

/// One row of contact-laws.md §4: id suffix, law, and reference [e_eff, δ_max, F_max, t_c].
type JournalRow = (&'static str, NormalLaw, [f64; 4]);

/// The eight pairings of contact-laws.md §4: id suffix, elastic part, damping, and the
/// reference e_eff, δ_max (m), F_max (N), t_c (s) (RK45, rtol 1e-11).
fn journal_rows() -> Result<Vec<JournalRow>, String> {
    let jb = JournalBearing::flap_paper_test();
    let e_star = jb.bearing.composite_modulus(&jb.journal);
    let c = jb.clearance();
    let err = |e: clr_contact::ContactError| e.to_string();
    let hertz =
        ElasticLaw::hertz_internal_cylinder(&jb.bearing, jb.r_bearing, &jb.journal, jb.r_journal)
            .map_err(err)?;
    let liu = ElasticLaw::liu(e_star, c, jb.length).map_err(err)?;
    let bai = ElasticLaw::bai_zhao(e_star, c).map_err(err)?;
    let pereira = ElasticLaw::pereira_internal(e_star, c, jb.length).map_err(err)?;
    use DampingFactor as D;
    let rows = [
        (
            "hertz-ln",
            hertz,
            D::LankaraniNikravesh,
            [0.72524, 1.8745e-5, 13343.9, 1.3014e-4],
        ),
        (
            "hertz-hunt-crossley",
            hertz,
            D::HuntCrossley,
            [0.66296, 1.8142e-5, 13311.4, 1.3210e-4],
        ),
        (
            "hertz-flores",
            hertz,
            D::Flores,
            [0.47044, 1.6117e-5, 13847.8, 1.4177e-4],
        ),
        (
            "hertz-hu-guo",
            hertz,
            D::HuGuo,
            [0.48774, 1.6312e-5, 13757.9, 1.4058e-4],
        ),
        (
            "hertz-zhiying-qishao",
            hertz,
            D::ZhiyingQishao,
            [0.48261, 1.6254e-5, 13783.6, 1.4093e-4],
        ),
        (
            "liu-ln",
            liu,
            D::LankaraniNikravesh,
            [0.72524, 1.7518e-5, 13994.3, 1.2229e-4],
        ),
        (
            "bai-zhao-ln",
            bai,
            D::LankaraniNikravesh,
            [0.72524, 2.5584e-5, 11189.0, 1.7106e-4],
        ),
        (
            "pereira-ln",
            pereira,
            D::LankaraniNikravesh,
            [0.72524, 1.2522e-5, 17800.8, 8.9963e-5],
        ),
    ];
    rows.into_iter()
        .map(|(id, e, d, r)| Ok((id, NormalLaw::new(e, d, C_E).map_err(err)?, r)))
        .collect()
}

pub fn cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    let jb = JournalBearing::flap_paper_test();
    let c = jb.clearance();

    // Flap paper restitution table, by integration.
    for (label, id, reference) in FLAP_TABLE {
        let id = format!("contact.restitution.{id}");
        if !filter.wants(&id) {
            continue;
        }
        let spec = Case::new(
            &id,
            format!("measured restitution of the `{label}` law, journal–bearing impact, c_e = 0.5"),
            "-",
            "Wan et al., Machines 10 (2022) 1098, restitution table (paper-systems.md §1.1)",
        );
        let law = match NormalLaw::preset(label, &jb, C_E) {
            Ok(l) => l,
            Err(e) => {
                out.push(spec.failed(reference, e.to_string()));
                continue;
            }
        };
        out.push(match simulate(law, c) {
            Ok(r) => {
                let closed = law.effective_restitution();
                spec.absolute(r.restitution(), reference, 0.002)
                    .note(format!(
                    "{} + {} (χ = {:.6}); closed form (contact-laws.md §1.3) e_eff = {closed:.6}, \
                     integration − closed form = {:.1e}; δ̇⁻ = {:.6} m/s; {} steps",
                    law.elastic().name(),
                    law.damping().name(),
                    law.chi(),
                    r.restitution() - closed,
                    r.v_in,
                    r.steps
                ))
            }
            Err(e) => spec.failed(reference, e),
        });
    }

    // Journal benchmark of contact-laws.md §4.
    if filter.wants("contact.journal") {
        match journal_rows() {
            Ok(rows) => {
                for (id, law, [e_ref, d_ref, f_ref, t_ref]) in rows {
                    let base = format!("contact.journal.{id}");
                    if !filter.wants(&base) {
                        continue;
                    }
                    let src = "contact-laws.md §4 (RK45, rtol 1e-11, numpy/scipy)";
                    let what = format!("{} + {}", law.elastic().name(), law.damping().name());
                    match simulate(law, c) {
                        Ok(r) => {
                            let note = format!(
                                "closed-form e_eff {:.6}; {} steps",
                                law.effective_restitution(),
                                r.steps
                            );
                            out.push(
                                Case::new(
                                    format!("{base}.e_eff"),
                                    format!("e_eff, {what}"),
                                    "-",
                                    src,
                                )
                                .relative(r.restitution(), e_ref, 1.5e-5)
                                .note(note),
                            );
                            out.push(
                                Case::new(
                                    format!("{base}.delta_max"),
                                    format!("peak penetration, {what}"),
                                    "m",
                                    src,
                                )
                                .relative(r.delta_max, d_ref, 1e-3),
                            );
                            out.push(
                                Case::new(
                                    format!("{base}.f_max"),
                                    format!("peak normal force, {what}"),
                                    "N",
                                    src,
                                )
                                .relative(r.f_max, f_ref, 1e-3),
                            );
                            out.push(
                                Case::new(
                                    format!("{base}.t_c"),
                                    format!("contact time, {what}"),
                                    "s",
                                    src,
                                )
                                .relative(r.t_c, t_ref, 1e-3),
                            );
                        }
                        Err(e) => out.push(
                            Case::new(format!("{base}.e_eff"), format!("e_eff, {what}"), "-", src)
                                .failed(e_ref, e),
                        ),
                    }
                }
            }
            Err(e) => out.push(
                Case::new(
                    "contact.journal",
                    "journal benchmark laws",
                    "-",
                    "contact-laws.md §4",
                )
                .failed(f64::NAN, e),
            ),
        }
    }

    // Second rebound off the opposite wall (contact-laws.md §4, step 5): a new δ̇⁻ is recorded
    // for the new contact, so the overall restitution after two impacts is e_eff².
    let id = "contact.restitution.second-impact";
    if filter.wants(id) {
        let spec = Case::new(
            id,
            "ẋ after two impacts / ẋ before, L-N law, c_e = 0.5",
            "-",
            "closed form e_eff² (contact-laws.md §1.3, §4 step 5)",
        );
        let e = DampingFactor::LankaraniNikravesh
            .effective_restitution(C_E)
            .unwrap_or(f64::NAN);
        let run = NormalLaw::preset("LN", &jb, C_E)
            .map_err(|e| e.to_string())
            .and_then(|law| {
                let first = simulate(law, c)?;
                let second = simulate_from(law, c, -1.0, first.t_end, first.y_end)?;
                Ok((first, second))
            });
        out.push(match run {
            Ok((first, second)) => spec
                .relative(second.y_end[1] / V0, e * e, 1e-6)
                .note(format!(
                    "δ̇⁻ first {:.6} m/s, second {:.6} m/s (e·v0 = {:.6})",
                    first.v_in,
                    second.v_in,
                    e * V0
                )),
            Err(err) => spec.failed(e * e, err),
        });
    }

    // Exact damping: the integrated restitution equals the requested one for a non-Hertzian
    // elastic part (Liu), contact-laws.md §1.3.
    let id = "contact.restitution.exact-liu";
    if filter.wants(id) {
        let spec = Case::new(
            id,
            "measured restitution, Liu law + exact damping factor, c_e = 0.5",
            "-",
            "requested c_e (closed form of contact-laws.md §1.3)",
        );
        let law = ElasticLaw::liu(jb.bearing.composite_modulus(&jb.journal), c, jb.length)
            .and_then(|e| NormalLaw::new(e, DampingFactor::Exact, C_E));
        out.push(
            match law.map_err(|e| e.to_string()).and_then(|l| simulate(l, c)) {
                Ok(r) => spec.relative(r.restitution(), C_E, 1e-6),
                Err(e) => spec.failed(C_E, e),
            },
        );
    }
    out
}

/// Figures of clr-contact for `docs/figures/` (called by `cargo xtask figures`):
/// `restitution.svg` (effective restitution vs input c_e for every damping factor, closed form
/// of contact-laws.md §1.3) and `hysteresis.svg` (force–penetration loops of the journal impact
/// integrated with clr-ode).
pub fn figures(dir: &Path) -> Result<(), String> {
    let mut fig = Figure::new("Effective restitution of multiplicative damping factors")
        .x_label("input coefficient of restitution c_e")
        .y_label("effective restitution e_eff")
        .size(900, 640);
    let grid: Vec<f64> = (1..=100).map(|i| i as f64 * 0.01).collect();
    let sparse: Vec<f64> = (1..=20).map(|i| i as f64 * 0.05).collect();
    for (k, d) in DampingFactor::ALL.into_iter().enumerate() {
        // The palette has 8 colours: the last factors are drawn with markers to stay distinct.
        let (cs, style) = if k < 8 {
            (&grid, Style::Line)
        } else {
            (&sparse, Style::LinePoints)
        };
        let pts: Vec<(f64, f64)> = cs
            .iter()
            .filter_map(|&c| d.effective_restitution(c).ok().map(|e| (c, e)))
            .collect();
        fig = fig.series(format!("{} χ = {}", d.name(), d.formula()), pts, style);
    }
    fig.save(dir.join("restitution"))
        .map_err(|e| e.to_string())?;

    let jb = JournalBearing::flap_paper_test();
    let mut fig =
        Figure::new("Journal–bearing impact (1 kg, 0.5 m/s, c_e = 0.5): force vs penetration")
            .x_label("penetration δ (µm)")
            .y_label("normal force F_N (N)");
    for label in ["Hertz", "LN", "Gonthier", "Bai", "Wang", "Modified"] {
        let law = NormalLaw::preset(label, &jb, C_E).map_err(|e| e.to_string())?;
        let r = simulate(law, jb.clearance())?;
        fig = fig.line(
            format!("{label} (e = {:.3})", r.restitution()),
            r.loop_points,
        );
    }
    fig.save(dir.join("hysteresis"))
        .map_err(|e| e.to_string())?;
    Ok(())
}
