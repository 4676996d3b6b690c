//! Verification cases of clr-contact's geometry and kinematics: the worked examples of
//! contact-laws.md §7.7 (revolute clearance joint) and §7.8 (multipoint detection of a slider on
//! a hogging guide). The references are the spec's hand-computed values (closed forms).

use clr_contact::body::{BodyState, Vector2};
use clr_contact::damping::DampingFactor;
use clr_contact::elastic::{ElasticLaw, Material};
use clr_contact::friction::FrictionLaw;
use clr_contact::multipoint::{ContactClass, MultipointDetector, SineGuide, SliderShape};
use clr_contact::normal::NormalLaw;
use clr_contact::revolute::RevoluteClearance;
use clr_contact::ContactError;

use super::Filter;
use crate::report::Case;

const SRC_77: &str = "contact-laws.md §7.7 (Flores et al., Comput. Struct. 82 (2004) 1359, §3.1)";
const SRC_78: &str = "contact-laws.md §7.8 (A sin(πx) − 39.5 µm, A = 40 µm)";

pub fn cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    if filter.wants("contact.revolute.kinematics") {
        out.extend(revolute_cases());
    }
    if filter.wants("contact.multipoint") {
        out.extend(multipoint_cases());
    }
    out
}

/// (id suffix, quantity, unit, value, reference, relative tolerance)
type Row = (&'static str, &'static str, &'static str, f64, f64, f64);

fn revolute_rows() -> Result<Vec<Row>, ContactError> {
    // Bearing fixed at the origin; journal centre at (c + δ)(0.6, 0.8), c = 0.1 mm, δ = 10 µm,
    // velocity (0.3, 0.4) m/s, ω = 10 rad/s; L-N (c_e = 0.5, δ̇⁻ = 0.5), Ambrósio μ = 0.1.
    let o = Vector2::zeros();
    let joint = RevoluteClearance::new(10e-3, 9.9e-3, o, o)?;
    let bearing = BodyState::fixed(o, 0.0);
    let journal = BodyState::new(
        (0.1e-3 + 10e-6) * Vector2::new(0.6, 0.8),
        0.0,
        Vector2::new(0.3, 0.4),
        10.0,
    );
    let c = joint.contact(&bearing, &journal);
    let steel = Material::steel();
    let elastic = ElasticLaw::hertz_internal_cylinder(&steel, 10e-3, &steel, 9.9e-3)?;
    let law = NormalLaw::new(elastic, DampingFactor::LankaraniNikravesh, 0.5)?;
    let friction = FrictionLaw::ambrosio(0.1, 1e-4, 1e-3)?;
    let f = c.forces_from_laws(&law, &friction, 0.5);
    let vq = journal.point_velocity(c.journal_point);
    Ok(vec![
        (
            "eccentricity",
            "eccentricity e",
            "m",
            c.eccentricity,
            0.11e-3,
            1e-9,
        ),
        (
            "journal_point_x",
            "journal contact point x",
            "m",
            c.journal_point.x,
            6.006e-3,
            1e-9,
        ),
        (
            "journal_point_y",
            "journal contact point y",
            "m",
            c.journal_point.y,
            8.008e-3,
            1e-9,
        ),
        (
            "bearing_point_x",
            "bearing contact point x",
            "m",
            c.bearing_point.x,
            6.000e-3,
            1e-9,
        ),
        (
            "bearing_point_y",
            "bearing contact point y",
            "m",
            c.bearing_point.y,
            8.000e-3,
            1e-9,
        ),
        (
            "point_velocity_x",
            "journal contact point velocity x",
            "m/s",
            vq.x,
            0.2208,
            1e-9,
        ),
        (
            "point_velocity_y",
            "journal contact point velocity y",
            "m/s",
            vq.y,
            0.4594,
            1e-9,
        ),
        (
            "v_n",
            "relative normal velocity v_N",
            "m/s",
            c.normal_velocity,
            0.5,
            1e-9,
        ),
        (
            "v_t",
            "relative tangential velocity v_T",
            "m/s",
            c.tangential_velocity,
            0.099,
            1e-9,
        ),
        (
            "f_n",
            "normal force F_N (L-N)",
            "N",
            f.normal_force,
            7455.4750,
            1e-8,
        ),
        (
            "f_f",
            "friction force |F_T| (Ambrósio)",
            "N",
            -f.tangential_force,
            745.5475,
            1e-8,
        ),
        (
            "fj_x",
            "force on journal x",
            "N",
            f.journal.force.x,
            -3876.8470,
            1e-8,
        ),
        (
            "fj_y",
            "force on journal y",
            "N",
            f.journal.force.y,
            -6411.7085,
            1e-8,
        ),
        (
            "mj",
            "moment on journal",
            "N·m",
            f.journal.moment,
            -7.380920,
            1e-7,
        ),
        (
            "fi_x",
            "force on bearing x",
            "N",
            f.bearing.force.x,
            3876.8470,
            1e-8,
        ),
        (
            "fi_y",
            "force on bearing y",
            "N",
            f.bearing.force.y,
            6411.7085,
            1e-8,
        ),
        (
            "mi",
            "moment on bearing",
            "N·m",
            f.bearing.moment,
            7.455475,
            1e-7,
        ),
    ])
}

fn revolute_cases() -> Vec<Case> {
    match revolute_rows() {
        Ok(rows) => rows
            .into_iter()
            .map(|(id, q, unit, value, reference, tol)| {
                Case::new(format!("contact.revolute.kinematics.{id}"), q, unit, SRC_77)
                    .relative(value, reference, tol)
            })
            .collect(),
        Err(e) => vec![
            Case::new("contact.revolute.kinematics", "worked example", "-", SRC_77)
                .failed(0.11e-3, e.to_string()),
        ],
    }
}

/// Max penetration and class seen by a detector with `face_points` per face and
/// `guide_samples` reverse-check samples on the §7.8 setup; also the penetrations in order.
fn hogging(
    face_points: usize,
    guide_samples: usize,
) -> Result<(Vec<f64>, ContactClass), ContactError> {
    let guide = SineGuide::new(40e-6, 1.0)?;
    let shape = SliderShape::new(0.1, 0.02, Vector2::zeros(), 0.0)?;
    let slider = BodyState::fixed(Vector2::new(0.5, 39.5e-6 + 0.01), 0.0);
    let mut det = MultipointDetector::new(shape, face_points, guide_samples)?;
    let class = det.detect(&guide, &slider);
    Ok((
        det.points().iter().map(|p| p.contact.penetration).collect(),
        class,
    ))
}

fn multipoint_cases() -> Vec<Case> {
    let mut out = Vec::new();
    let expected = [7.534e-9, 3.767e-7, 5.000e-7, 3.767e-7, 7.534e-9];
    let xs = [0.45, 0.475, 0.5, 0.525, 0.55];
    // Corners + 3 points on each face: the candidates sit at the five sample abscissae.
    match hogging(3, 0) {
        Ok((pen, class)) if pen.len() == 5 => {
            for (k, (p, e)) in pen.iter().zip(expected).enumerate() {
                out.push(
                    Case::new(
                        format!("contact.multipoint.penetration.x{}", xs[k]),
                        format!("penetration at x = {} m", xs[k]),
                        "m",
                        SRC_78,
                    )
                    .relative(*p, e, 1e-3)
                    .note("reference given to 4 digits"),
                );
            }
            let (is_area, length) = match class {
                ContactClass::Area { face: 0, length } => (true, length),
                _ => (false, f64::NAN),
            };
            out.push(
                Case::new(
                    "contact.multipoint.area_length",
                    "area contact of the bottom face: contact length",
                    "m",
                    "slider length L = 0.1 m (every bottom candidate penetrates)",
                )
                .relative(length, 0.1, 1e-9)
                .note(format!("classification {class:?}, area = {is_area}")),
            );
        }
        Ok((pen, _)) => out.push(
            Case::new(
                "contact.multipoint.penetration",
                "active points",
                "-",
                SRC_78,
            )
            .failed(5.0, format!("{} active points instead of 5", pen.len())),
        ),
        Err(e) => out.push(
            Case::new("contact.multipoint.penetration", "setup", "-", SRC_78)
                .failed(5.0, e.to_string()),
        ),
    }
    // Corner-only detection misses the mid-face penetration; the reverse check finds it.
    let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    for (id, n, m, reference, what) in [
        (
            "contact.multipoint.corners_only_max",
            0,
            0,
            7.534e-9,
            "max penetration, corner candidates only",
        ),
        (
            "contact.multipoint.reverse_check_max",
            0,
            5,
            5.000e-7,
            "max penetration, corners + reverse check (5 guide samples)",
        ),
    ] {
        let case = Case::new(id, what, "m", SRC_78);
        out.push(match hogging(n, m) {
            Ok((pen, _)) => case
                .relative(max(&pen), reference, 1e-3)
                .note(format!("{} active points", pen.len())),
            Err(e) => case.failed(reference, e.to_string()),
        });
    }
    out
}
