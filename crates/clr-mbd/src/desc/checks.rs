//! Plausibility checks of a description's values that do not depend on the state (the
//! state-dependent ones are in [`crate::plausible`], which lists every threshold).

use crate::initial_data::Warning;

/// Young's modulus outside [min, max] Pa (soft elastomers ~1 MPa, diamond 1.1e12 Pa; a value in
/// GPa or MPa falls below).
pub const MODULUS_RANGE: (f64, f64) = (1e6, 1.5e12);

fn warn(field: impl Into<String>, message: String) -> Warning {
    Warning {
        field: field.into(),
        message,
    }
}

/// Findings on the values of a description that do not depend on the state: Young's moduli
/// outside [`MODULUS_RANGE`] (a value in GPa or MPa). The description is walked as data, so
/// every material of every law and shape is seen wherever it sits.
pub fn description_warnings(desc: &super::ModelDesc) -> Vec<Warning> {
    let mut out = Vec::new();
    for c in &desc.clearances {
        moduli_warnings(c.name(), c, &mut out);
    }
    out
}

/// The findings of [`description_warnings`] on one item `name` of any description (walked as
/// data).
pub(crate) fn moduli_warnings(name: &str, item: &impl serde::Serialize, out: &mut Vec<Warning>) {
    if let Ok(v) = toml::Value::try_from(item) {
        walk_moduli(name, &v, out);
    }
}

fn walk_moduli(path: &str, v: &toml::Value, out: &mut Vec<Warning>) {
    match v {
        toml::Value::Table(o) => {
            for (k, x) in o {
                let p = format!("{path}.{k}");
                match (k.as_str(), x.as_float()) {
                    ("youngs_modulus", Some(e))
                        if !(MODULUS_RANGE.0..=MODULUS_RANGE.1).contains(&e) =>
                    {
                        out.push(warn(
                            p,
                            format!(
                                "a Young's modulus of {e:e} Pa is outside [{:e}, {:e}] Pa \
                                 (steel 2.07e11, aluminium 7e10, elastomers ~1e6): the unit is \
                                 Pa, so 210 GPa is 2.1e11",
                                MODULUS_RANGE.0, MODULUS_RANGE.1
                            ),
                        ))
                    }
                    _ => walk_moduli(&p, x, out),
                }
            }
        }
        toml::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                walk_moduli(&format!("{path}[{i}]"), x, out);
            }
        }
        _ => {}
    }
}
