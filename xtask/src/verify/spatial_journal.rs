//! `contact.spatial.revolute.*`: the spatial journal-in-bearing clearance joint
//! (`clr_contact::journal`, docs/contact.md "Spatial journal in bearing") against brute-force
//! sampling, the planar revolute joint and closed forms. Sources and tolerances:
//!
//! * `.rim_sampling.*`: the largest radial penetration of each wetted end against 3600 × 401 =
//!   1.4e6 sampled points of the journal surface (end circles included) plus 3600 points on each
//!   of the bore's end planes (the bore's edge on a longer journal). The sampled maximum lies below
//!   the true one by at most R_j(1 − cos(Δθ/2)) + tan γ Δz (the sampling bound, the tolerance);
//!   the deepest point and normal agree within R_j·3Δθ + Δz and 3Δθ. Configurations: one rim, both
//!   rims on the same side, opposite sides, the bore's edge on a longer journal.
//! * `.planar`: no tilt, no axial motion: force, moments and normal force equal the planar
//!   `clr_contact::revolute` joint's (Flores, Ambrósio, Claro & Lankarani, Comput. Struct. 82
//!   (2004) 1359, common-point application) with Hertz, Lankarani–Nikravesh and Ambrósio
//!   friction, 1e-13 relative (rounding of the Gauss sums).
//! * `.moment_tilt.*`: a centred journal loaded by a pure moment M tilts to the root of the closed
//!   form M(γ) derived below ([`closed_moment`]), 1e-10 relative (the quadrature is exact for the
//!   linear law; rounding and the bisections remain); `.moment_tilt.energy` checks that closed
//!   form against −dW/dγ of the closed-form energy, 1e-7 relative (central differences).
//! * `.thrust.*`: an axial load F settles the journal on its thrust face at K δ^n = F
//!   (closed form), 1e-12 relative in δ, for the ring law of the thrust faces.
//! * `.continuity.*`: the largest jump of force and moment through the transitions (located by
//!   bisection, sides ±ε apart): the radial regions opening and merging, and the thrust ring
//!   through zero tilt and as its wetted arc closes to the full ring; 1e-9 of the sweep's force
//!   (moments 1e-9 of force·length). A jump would show at full size; the smooth change over ±ε is
//!   ~1e-12.

use std::f64::consts::TAU;

use clr_contact::body::Vector2;
use clr_contact::journal::{
    JournalClearance, JournalError, JournalFriction, JournalLaws, JournalState, GROUPS, RADIAL_A,
    RADIAL_B, THRUST_MINUS, THRUST_PLUS,
};
use clr_contact::{
    BodyState, DampingFactor, ElasticLaw, ForceApplication, FrictionLaw, Material, NormalLaw,
    RevoluteClearance,
};
use nalgebra::Vector3;

use super::Filter;
use crate::report::Case;

use super::journal_setup::{state, still, tilted, v3, C, L, RB, RJ};

const PREFIX: &str = "contact.spatial.revolute";

type Res<T> = Result<T, JournalError>;
/// A family of cases: computes them all, or fails with the joint's error.
type Family = fn() -> Res<Vec<Case>>;

pub fn cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    let families: [(&str, Family); 5] = [
        ("rim_sampling", rim_sampling),
        ("planar", planar),
        ("moment_tilt", moment_tilt),
        ("thrust", thrust),
        ("continuity", continuity),
    ];
    for (name, run) in families {
        let id = format!("{PREFIX}.{name}");
        if filter.wants(&id) {
            match run() {
                Ok(c) => out.extend(c),
                Err(e) => {
                    out.push(Case::new(&id, name, "-", "module docs").failed(0.0, e.to_string()))
                }
            }
        }
    }
    out
}

fn hertz_ln() -> Res<NormalLaw> {
    let steel = Material::steel();
    Ok(NormalLaw::new(
        ElasticLaw::hertz_internal_cylinder(&steel, RB, &steel, RJ)?,
        DampingFactor::LankaraniNikravesh,
        0.5,
    )?)
}

fn elastic(law: ElasticLaw) -> Res<NormalLaw> {
    Ok(NormalLaw::new(law, DampingFactor::None, 1.0)?)
}

fn laws(radial: NormalLaw, friction: Option<FrictionLaw>) -> Res<JournalLaws> {
    let f = friction.map_or(JournalFriction::None, JournalFriction::Law);
    JournalLaws::new(radial, radial, f)
}

/// The x in [lo, hi] where the increasing f reaches `target` (200 bisections: to the last bit).
fn solve_increasing(f: &dyn Fn(f64) -> f64, target: f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

// ---------------------------------------------------------------------------------------------
// rim_sampling

/// Largest radial penetration over a sampled journal surface, restricted to the bore's slab and
/// to z below (`side` = 0) or above (1) `split`: (δ, point, normal).
fn brute_force(
    joint: &JournalClearance,
    st: &JournalState<f64>,
    split: f64,
    side: usize,
    (n_theta, n_s): (usize, usize),
) -> (f64, Vector3<f64>, Vector3<f64>) {
    let oj = st.journal_centre.value();
    let uj = st.journal_axis.value().normalize();
    let p = if uj.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let m1 = (p - uj * p.dot(&uj)).normalize();
    let m2 = uj.cross(&m1);
    let (lj, lb) = (joint.journal_length(), joint.bearing_length());
    let mut best = (f64::NEG_INFINITY, Vector3::zeros(), Vector3::zeros());
    let mut consider = |x: Vector3<f64>| {
        if x.z.abs() > 0.5 * lb * (1.0 + 1e-15) || (x.z < split) != (side == 0) {
            return;
        }
        let rho = x.xy().norm();
        if rho - RB > best.0 {
            best = (rho - RB, x, v3(x.x / rho, x.y / rho, 0.0));
        }
    };
    for it in 0..n_theta {
        let th = TAU * it as f64 / n_theta as f64;
        let m = (m1 * th.cos() + m2 * th.sin()) * joint.journal_radius();
        for is in 0..n_s {
            let s = -0.5 * lj + lj * is as f64 / (n_s - 1) as f64;
            consider(oj + uj * s + m);
        }
        // the journal surface's points on the bore's end planes (the bore edge on the journal)
        for zb in [-0.5 * lb, 0.5 * lb] {
            let s = (zb - oj.z - m.z) / uj.z;
            if s.abs() <= 0.5 * lj {
                let mut x = oj + uj * s + m;
                x.z = zb;
                consider(x);
            }
        }
    }
    best
}

fn rim_sampling() -> Res<Vec<Case>> {
    let short = JournalClearance::cylindrical(RB, L, RJ, L)?;
    let long = JournalClearance::cylindrical(RB, L, RJ, 25e-3)?;
    // (joint, centre, axis, label, wetted groups)
    let configurations = [
        (
            &short,
            v3(0.3 * C, 0.05 * C, 1e-4),
            tilted(0.0115, 0.7),
            "one_rim",
            [false, true],
        ),
        (
            &short,
            v3(0.97 * C, 0.0, -2e-4),
            tilted(5e-3, 1.55),
            "same_side",
            [true, true],
        ),
        (
            &short,
            v3(0.1 * C, -0.2 * C, 0.0),
            tilted(0.02, 0.3),
            "opposite_sides",
            [true, true],
        ),
        (
            &long,
            v3(0.1 * C, 0.1 * C, 5e-4),
            tilted(0.016, -0.5),
            "bore_edge",
            [true, true],
        ),
    ];
    let grid = (3600, 401);
    let dtheta = TAU / grid.0 as f64;
    let law = laws(hertz_ln()?, None)?;
    let mut out = Vec::new();
    for (joint, oj, uj, label, wet) in configurations {
        let st = still(oj, uj);
        let g = joint.geometry(&st)?;
        let dz = joint.journal_length() / (grid.1 - 1) as f64;
        let bound = RJ * (1.0 - (0.5 * dtheta).cos()) + g.tilt().tan() * dz;
        let (mut err_d, mut err_n, mut err_x) = (0.0_f64, 0.0_f64, 0.0_f64);
        let mut pattern_ok = true;
        let mut notes = Vec::new();
        let f = g.forces(&law, &[0.1; GROUPS]);
        for k in [RADIAL_A, RADIAL_B] {
            pattern_ok &=
                g.wetted(k).is_some() == wet[k] && (f.groups[k].normal_force > 0.0) == wet[k];
            let (d, _) = g.gap(k);
            let (db, xb, nb) = brute_force(joint, &st, g.split(), k, grid);
            err_d = err_d.max((d - db).abs());
            notes.push(format!(
                "{}: δ = {d:.6e} m, sampled {db:.6e} m",
                ["A", "B"][k]
            ));
            if wet[k] {
                let (lo, hi) = g.overlap().unwrap_or((0.0, 0.0));
                let end = g.section(if k == 0 { lo } else { hi });
                err_n = err_n.max((end.normal.value() - nb).norm());
                err_x = err_x.max((end.journal_point.value() - xb).norm());
            }
        }
        let src = "brute-force sampling of the journal surface (1.4e6 points); tolerance the \
                   sampling bound R_j(1 − cos(Δθ/2)) + tan γ Δz";
        let id = format!("{PREFIX}.rim_sampling.{label}");
        out.push(
            Case::new(&id, "largest |δ − δ_sampled| of the two ends", "m", src)
                .absolute(err_d, 0.0, bound)
                .note(format!(
                    "{}; wetted pattern {}",
                    notes.join("; "),
                    if pattern_ok { "as expected" } else { "WRONG" }
                )),
        );
        if !pattern_ok {
            out.push(
                Case::new(format!("{id}.pattern"), "wetted ends", "-", src)
                    .failed(0.0, "wetted groups differ from the configuration's"),
            );
        }
        out.push(
            Case::new(
                format!("{id}.normal"),
                "|n − n_sampled| at the wetted ends",
                "-",
                "brute-force sampling; tolerance 3Δθ",
            )
            .absolute(err_n, 0.0, 3.0 * dtheta),
        );
        out.push(
            Case::new(
                format!("{id}.point"),
                "|X − X_sampled| of the deepest points",
                "m",
                "brute-force sampling; tolerance 3 R_j Δθ + Δz",
            )
            .absolute(err_x, 0.0, 3.0 * RJ * dtheta + dz),
        );
    }
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// planar

fn planar() -> Res<Vec<Case>> {
    let joint = JournalClearance::revolute(RB, L, RJ, L, 2e-4, None)?;
    let planar = RevoluteClearance::new(RB, RJ, Vector2::zeros(), Vector2::zeros())?;
    let normal = hertz_ln()?;
    let friction = FrictionLaw::ambrosio(0.1, 1e-4, 1e-3)?;
    let laws = laws(normal, Some(friction))?;
    let mut worst = 0.0_f64;
    for (e, psi, v, w) in [
        (1.3 * C, 0.4_f64, Vector2::new(0.01, -0.02), 3.0),
        (1.02 * C, 2.5, Vector2::new(-0.03, 0.005), -20.0),
        (1.1 * C, -1.9, Vector2::new(0.0, 0.0), 0.0),
    ] {
        let oj = v3(e * psi.cos(), e * psi.sin(), 0.0);
        let st = state(oj, Vector3::z(), v3(v.x, v.y, 0.0), v3(0.0, 0.0, w));
        let f = joint.geometry(&st)?.forces(&laws, &[0.3; GROUPS]);
        let c = planar.contact(
            &BodyState::fixed(Vector2::zeros(), 0.0),
            &BodyState::new(oj.xy(), 0.0, v, w),
        );
        let p = c.forces_from_laws_with(&normal, &friction, 0.3, ForceApplication::CommonPoint);
        let scale = p.journal.force.norm();
        let (force, mj, mb) = (
            f.force.value(),
            f.journal_moment.value(),
            f.bearing_moment.value(),
        );
        let fn_sum = f.groups[RADIAL_A].normal_force + f.groups[RADIAL_B].normal_force;
        let thrust = f.groups[THRUST_MINUS].normal_force + f.groups[THRUST_PLUS].normal_force;
        for err in [
            (force.xy() - p.journal.force).norm() / scale,
            force.z.abs() / scale,
            (mj.z - p.journal.moment).abs() / (scale * RB),
            (mb.z - p.bearing.moment).abs() / (scale * RB),
            mj.xy().norm().max(mb.xy().norm()) / (scale * L),
            (fn_sum - p.normal_force).abs() / p.normal_force,
            thrust / scale,
        ] {
            worst = worst.max(err);
        }
    }
    Ok(vec![Case::new(
        format!("{PREFIX}.planar"),
        "largest relative difference of force, moments (about O_j, O_b) and normal force, 3 states",
        "-",
        "clr_contact::revolute (Flores et al. 2004, common point), same Hertz/L-N law and Ambrósio \
         friction; tolerance 1e-13 (rounding of the Gauss sums)",
    )
    .at_most(worst, 1e-13)])
}

// ---------------------------------------------------------------------------------------------
// moment_tilt

/// Restoring moment (N·m) of a centred journal tilted by γ about y, L_j = L_b = L, linear law with
/// force per unit length p = K δ (K in N/m²). Derivation: the cross-section at z is the ellipse of
/// semi-axes R_j/cos γ (along x) and R_j centred at e(z) = z tan γ x̂ on its long axis, so
/// δ(z) = |z| tan γ − c′, c′ = R_b − R_j/cos γ, wetted for z₀ = c′/tan γ < |z| < z_e, where the
/// deepest point (journal direction m = ±(cos γ, 0, −sin γ)) reaches the end circle s = ±L/2:
/// z_e = (L/2) cos γ − R_j sin γ. The two rim wedges push ∓x̂ at ±z, so about O_j
/// M_y = −2 ∫_{z₀}^{z_e} z K (z tan γ − c′) dz = −2K [tan γ (z_e³ − z₀³)/3 − c′ (z_e² − z₀²)/2]
/// from the radial line load, plus the moment of the axial parts: the slope term p δ′ u_b at the
/// journal point x = δ + R_b and the rim term −Φ(δ_e)/L_c u_b at the end (Φ/L_c = K δ_e²/2), per
/// region −K ∫₀^{δ_e} u (u + R_b) du + (δ_e + R_b) K δ_e²/2 = K δ_e³/6, so the restoring moment is
/// 2K [...] − K δ_e³/3 with δ_e = z_e tan γ − c′.
fn closed_moment(k: f64, g: f64) -> f64 {
    let cp = RB - RJ / g.cos();
    let z0 = cp / g.tan();
    let ze = 0.5 * L * g.cos() - RJ * g.sin();
    2.0 * k * (g.tan() * (ze.powi(3) - z0.powi(3)) / 3.0 - cp * (ze * ze - z0 * z0) / 2.0)
        - k * closed_rim_penetration(g).powi(3) / 3.0
}

/// δ_e = z_e tan γ − c′ of [`closed_moment`], m.
fn closed_rim_penetration(g: f64) -> f64 {
    (0.5 * L * g.cos() - RJ * g.sin()) * g.tan() - (RB - RJ / g.cos())
}

/// The stored energy W(γ) = 2 ∫ K δ²/2 dz = K δ_e³/(3 tan γ), J: its −dW/dγ is [`closed_moment`].
fn closed_energy(k: f64, g: f64) -> f64 {
    k * closed_rim_penetration(g).powi(3) / (3.0 * g.tan())
}

fn moment_tilt() -> Res<Vec<Case>> {
    let k = 2e11; // N/m² per unit length
    let joint = JournalClearance::cylindrical(RB, L, RJ, L)?;
    let laws = laws(elastic(ElasticLaw::linear(k * L)?)?, None)?;
    let module = |g: f64| {
        let st = still(Vector3::zeros(), tilted(g, 0.0));
        joint
            .geometry(&st)
            .map(|geo| -geo.forces(&laws, &[1.0; GROUPS]).journal_moment.value().y)
            .unwrap_or(f64::NAN)
    };
    let bisect =
        |f: &dyn Fn(f64) -> f64, m: f64| solve_increasing(f, m, 2.0 * C / L * 1.0001, 0.05);
    let src = "closed form of the two rim wedges, linear law (module docs of \
               xtask/src/verify/spatial_journal.rs); tolerance 1e-10 relative";
    let mut out = Vec::new();
    let mut worst_energy = 0.0_f64;
    for m in [0.5, 5.0, 50.0] {
        let g_closed = bisect(&|g| closed_moment(k, g), m);
        let g_module = bisect(&module, m);
        let st = still(Vector3::zeros(), tilted(g_module, 0.0));
        let f = joint.geometry(&st)?.forces(&laws, &[1.0; GROUPS]);
        let residual = f.force.value().norm() / f.journal_moment.value().norm();
        out.push(
            Case::new(
                format!("{PREFIX}.moment_tilt.m{m}"),
                format!("tilt under a pure moment of {m} N·m"),
                "rad",
                src,
            )
            .relative(g_module, g_closed, 1e-10)
            .note(format!(
                "resultant force / moment {residual:.1e} 1/m (pure moment)"
            )),
        );
        let h = 1e-6 * g_closed;
        let dw = (closed_energy(k, g_closed + h) - closed_energy(k, g_closed - h)) / (2.0 * h);
        worst_energy = worst_energy.max((dw - m).abs() / m);
    }
    out.push(
        Case::new(
            format!("{PREFIX}.moment_tilt.energy"),
            "closed-form moment against dW/dγ of the closed-form energy, largest relative error",
            "-",
            "W = K δ_e³/(3 tan γ), central differences (h = 1e-6 γ); tolerance 1e-7",
        )
        .at_most(worst_energy, 1e-7),
    );
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// thrust

fn thrust() -> Res<Vec<Case>> {
    let (ca, rt) = (2e-4, 12e-3);
    let joint = JournalClearance::revolute(RB, L, RJ, L, ca, Some(rt))?;
    let mut out = Vec::new();
    for (kk, n) in [(1e10, 1.5), (3e8, 1.0)] {
        let law = elastic(ElasticLaw::power(kk, n)?)?;
        let laws = JournalLaws::new(law, law, JournalFriction::None)?;
        for force in [10.0, 1e3] {
            let reaction = |a: f64| {
                joint
                    .geometry(&still(v3(0.0, 0.0, a), Vector3::z()))
                    .map(|g| g.forces(&laws, &[1.0; GROUPS]))
            };
            let axial = |a: f64| reaction(a).map_or(f64::NAN, |f| -f.force.value().z);
            let delta = solve_increasing(&axial, force, 0.5 * ca, ca) - 0.5 * ca;
            let exact = (force / kk).powf(1.0 / n);
            let f = reaction(0.5 * ca + delta)?;
            let g = joint.geometry(&still(v3(0.0, 0.0, 0.5 * ca + delta), Vector3::z()))?;
            let radial = f.groups[RADIAL_A].normal_force + f.groups[RADIAL_B].normal_force;
            out.push(
                Case::new(
                    format!("{PREFIX}.thrust.n{n}.f{force}"),
                    format!("thrust-face penetration under {force} N, K δ^{n}"),
                    "m",
                    "closed form K δ^n = F, δ = a − c_a/2 (docs/contact.md, thrust faces); \
                     tolerance 1e-12 relative",
                )
                .relative(delta, exact, 1e-12)
                .note(format!(
                    "moment {:.1e} of F·R_t (quadrature residual of ∫cos φ around the ring); \
                     radial normal force {radial:e} N; opposite face gap {:.3e} m",
                    f.journal_moment.value().norm() / (force * rt),
                    g.gap(THRUST_MINUS).0
                )),
            );
        }
    }
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// continuity

/// Force and moment at one state of a sweep, and the transition flag.
type SweepPoint = (Vector3<f64>, Vector3<f64>, bool);

/// Locate where the flag of `eval` changes in [lo, hi] by bisection down to `eps` and return the
/// jumps of force and moment between the two sides (±`eps`).
fn jump(eval: &dyn Fn(f64) -> SweepPoint, lo: f64, hi: f64, eps: f64) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (lo, hi);
    let at_lo = eval(lo).2;
    if at_lo == eval(hi).2 {
        return None;
    }
    while hi - lo > 0.01 * eps {
        let mid = 0.5 * (lo + hi);
        // adjacent floating-point numbers: the transition is located to the last bit
        if mid <= lo || mid >= hi {
            break;
        }
        if eval(mid).2 == at_lo {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (a, b) = (eval(lo - eps), eval(hi + eps));
    if a.2 == b.2 {
        return None;
    }
    Some(((a.0 - b.0).norm(), (a.1 - b.1).norm()))
}

/// One continuity case: the relative jump (force / `scale`, moment / (`scale`·`arm`)).
fn continuity_case(
    name: &str,
    what: &str,
    found: Option<(f64, f64)>,
    scale: f64,
    arm: f64,
) -> Case {
    let spec = Case::new(
        format!("{PREFIX}.continuity.{name}"),
        format!("largest relative jump of force and moment, {what}"),
        "-",
        "continuity (a jump shows at full size); tolerance 1e-9 of the sweep's force (moments of \
         force·length)",
    );
    match found {
        Some((df, dm)) => spec
            .at_most((df / scale).max(dm / (scale * arm)), 1e-9)
            .note(format!(
                "ΔF = {df:.2e} N, ΔM = {dm:.2e} N·m, scale {scale:.3e} N"
            )),
        None => spec.failed(0.0, "the sweep does not cross the transition"),
    }
}

fn continuity() -> Res<Vec<Case>> {
    let joint = JournalClearance::cylindrical(RB, L, RJ, L)?;
    let mut out = Vec::new();
    for (label, law) in [
        ("hertz", hertz_ln()?),
        ("linear", elastic(ElasticLaw::linear(2e11 * L)?)?),
    ] {
        let laws = laws(law, Some(FrictionLaw::threlfall(0.1, 1e-2)?))?;
        // (force, moment, opened, merged)
        let point = |oj: Vector3<f64>, uj: Vector3<f64>| {
            let st = state(oj, uj, v3(0.0, 0.0, 1e-3), v3(0.0, 0.0, 5.0));
            let Ok(g) = joint.geometry(&st) else {
                return (Vector3::repeat(f64::NAN), Vector3::zeros(), false, false);
            };
            let f = g.forces(&laws, &[0.1; GROUPS]);
            let (lo, hi) = g.overlap().unwrap_or((0.0, 0.0));
            let wet: f64 = [RADIAL_A, RADIAL_B]
                .iter()
                .filter_map(|&k| g.wetted(k))
                .map(|w| w.1 - w.0)
                .sum();
            let merged = (wet - (hi - lo)).abs() <= 1e-12 * L;
            let opened = g.wetted(RADIAL_A).is_some() || g.wetted(RADIAL_B).is_some();
            (f.force.value(), f.journal_moment.value(), opened, merged)
        };
        let pick = |p: (Vector3<f64>, Vector3<f64>, bool, bool), merged: bool| {
            (p.0, p.1, if merged { p.3 } else { p.2 })
        };
        let across = |e0: f64| {
            point(
                v3(e0, 0.1 * C, 1e-4),
                tilted(6e-3, 0.5 * std::f64::consts::PI),
            )
        };
        let scale = across(1.2 * C).0.norm();
        let open = jump(&|x| pick(across(x), false), 0.0, 1.2 * C, 1e-16);
        let merge = jump(&|x| pick(across(x), true), 0.0, 1.2 * C, 1e-16);
        out.push(continuity_case(
            &format!("{label}.offset_opening"),
            "offset of a tilted journal, the ends open",
            open,
            scale,
            L,
        ));
        out.push(continuity_case(
            &format!("{label}.offset_merging"),
            "offset of a tilted journal, the regions merge",
            merge,
            scale,
            L,
        ));
        let rims = |g: f64| point(v3(0.6 * C, 0.0, 1e-4), tilted(g, 1.2));
        let r = jump(&|x| pick(rims(x), false), 0.0, 0.02, 1e-15);
        out.push(continuity_case(
            &format!("{label}.tilt_rims"),
            "tilt at 0.6c offset, the rims open",
            r,
            rims(0.02).0.norm(),
            L,
        ));
        let split = |g: f64| point(v3(1.02 * C, 0.0, -1e-4), tilted(g, 0.2));
        let s = jump(&|x| pick(split(x), true), 0.0, 0.02, 1e-15);
        out.push(continuity_case(
            &format!("{label}.tilt_split"),
            "tilt at 1.02c offset, a merged contact splits",
            s,
            split(0.0).0.norm(),
            L,
        ));
        // from no tilt to the least tilt (the split jumps from the overlap's middle to an end)
        let (a, b) = (split(0.0), split(1e-15));
        out.push(continuity_case(
            &format!("{label}.zero_tilt"),
            "radial contact from γ = 0 to 1e-15 rad",
            Some(((a.0 - b.0).norm(), (a.1 - b.1).norm())),
            a.0.norm(),
            L,
        ));
    }
    out.extend(thrust_continuity()?);
    Ok(out)
}

/// The thrust ring through zero tilt (the old point law's moment jumped by F·R_t there) and as its
/// wetted arc closes to the full ring (δ₀ = R_t sin γ), Hertz with damping and Threlfall friction,
/// the journal sliding and spinning.
fn thrust_continuity() -> Res<Vec<Case>> {
    let (ca, rt) = (2e-4, 12e-3);
    let joint = JournalClearance::revolute(RB, L, RJ, L, ca, Some(rt))?;
    let laws = laws(hertz_ln()?, Some(FrictionLaw::threlfall(0.1, 1e-2)?))?;
    let eval = |a: f64, uj: Vector3<f64>| {
        let st = state(
            v3(0.2 * C, 0.0, a),
            uj,
            v3(1e-4, 0.0, 1e-3),
            v3(0.0, 0.0, 5.0),
        );
        let Ok(g) = joint.geometry(&st) else {
            return (Vector3::repeat(f64::NAN), Vector3::zeros(), 0.0, 0.0);
        };
        let f = g.forces(&laws, &[0.1; GROUPS]);
        let t = &f.groups[THRUST_PLUS];
        (
            t.force.value(),
            t.journal_moment.value(),
            g.gap(THRUST_PLUS).0,
            g.tilt(),
        )
    };
    let a0 = 0.5 * ca + 2e-6;
    let mut out = Vec::new();
    // through γ = 0 along one line of tilts: γ = ±ε about x
    let mut worst = (0.0_f64, 0.0_f64);
    let scale = eval(a0, Vector3::z()).0.norm();
    for eps in [1e-15, 1e-12] {
        let (p, m) = (
            eval(a0, tilted(eps, 0.3)),
            eval(a0, tilted(eps, 0.3 + std::f64::consts::PI)),
        );
        let z = eval(a0, Vector3::z());
        for (x, y) in [(&p, &m), (&p, &z)] {
            worst.0 = worst.0.max((x.0 - y.0).norm());
            worst.1 = worst.1.max((x.1 - y.1).norm());
        }
    }
    out.push(continuity_case(
        "thrust.zero_tilt",
        "thrust ring from γ = −ε to 0 to ε (ε = 1e-15, 1e-12 rad)",
        Some(worst),
        scale,
        rt,
    ));
    // the wetted arc closing to the full ring: δ_t = δ₀ + R_t sin γ crosses 2 R_t sin γ
    let gamma = 1e-4;
    let uj = tilted(gamma, 0.3);
    let full = |a: f64| {
        let r = eval(a, uj);
        (r.0, r.1, r.2 >= 2.0 * rt * r.3.sin())
    };
    let lo = 0.5 * ca - rt * gamma;
    let found = jump(&full, lo + 1e-3 * rt * gamma, lo + 4.0 * rt * gamma, 1e-18);
    out.push(continuity_case(
        "thrust.full_ring",
        "thrust arc closing to the full ring (γ = 1e-4 rad)",
        found,
        full(lo + 4.0 * rt * gamma).0.norm(),
        rt,
    ));
    Ok(out)
}
