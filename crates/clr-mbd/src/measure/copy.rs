//! `reaction`, `contact`, `energy`: quantities every run computes anyway (the joint reaction
//! columns `J.Fx J.Fy J.M`, the contact columns of a clearance joint or slider, the energy
//! columns), taken under the measure's name, a reaction optionally resolved in a body's axes.
//! They make a quantity an output of its own (for a co-simulation interface or a metric) without
//! computing it twice; the sources are looked up when the model is built
//! ([`super::runtime::resolve`]) and an unknown one is refused with the names there are.

use serde::{Deserialize, Serialize};

use super::runtime::{CompiledMeasure, MeasureEl};
use crate::element::{Compiler, Element};
use crate::error::MbdError;
use crate::results::ENERGY_COLUMNS;

/// Reaction of a joint or driver on its second body (on its first when the second is the
/// ground), as the columns `J.Fx J.Fy J.M` (moment about that body's centre of mass): columns
/// `<name>.Fx`, `<name>.Fy` (N) and `<name>.M` (N·m).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Reaction {
    /// Unique measure name.
    pub name: String,
    /// The joint or driver (a clearance joint of clearance 0 counts as a joint).
    pub joint: String,
    /// A body whose axes F_x, F_y are resolved in (default: the world axes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame: Option<String>,
}

impl Element for Reaction {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let rotate = match &self.frame {
            Some(b) => Some(c.body(&self.name, "frame", b)?),
            None => None,
        };
        let (units, suffixes) = (["N", "N", "N*m"], ["Fx", "Fy", "M"]);
        push_copy(
            c,
            (&self.name, "joint"),
            &self.joint,
            &suffixes,
            &units,
            rotate,
        );
        Ok(())
    }
}

/// The quantities of a contact element a `contact` measure can take, with their units.
pub const CONTACT_QUANTITIES: [(&str, &str); 10] = [
    ("penetration", "m"),
    ("rate", "m/s"),
    ("normal_force", "N"),
    ("friction_force", "N"),
    ("contact", "-"),
    ("ex", "m"),
    ("ey", "m"),
    ("lugre_z", "m"),
    ("film_force", "N"),
    ("film_thickness", "m"),
];

/// One quantity of a clearance joint, slider or shape contact (`C.<quantity>`): column
/// `<name>.<quantity>`, unit of [`CONTACT_QUANTITIES`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Contact {
    /// Unique measure name.
    pub name: String,
    /// The contact element (`[[clearance]]` name).
    pub element: String,
    /// One of [`CONTACT_QUANTITIES`].
    pub quantity: String,
}

impl Element for Contact {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let Some(&(q, unit)) = CONTACT_QUANTITIES.iter().find(|(q, _)| *q == self.quantity) else {
            return Err(MbdError::Invalid {
                path: format!("{}.quantity", self.name),
                message: format!(
                    "`{}` is not a contact quantity; one of {}",
                    self.quantity,
                    CONTACT_QUANTITIES.map(|(q, _)| q).join(", ")
                ),
            });
        };
        push_copy(
            c,
            (&self.name, "element"),
            &self.element,
            &[q],
            &[unit],
            None,
        );
        Ok(())
    }
}

/// One energy term (`energy.<term>`, J): column `<name>.energy`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Energy {
    /// Unique measure name.
    pub name: String,
    /// `kinetic`, `potential`, `elastic`, `total`, `dissipated`, `work_in` or `balance`.
    pub term: String,
}

impl Element for Energy {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let terms = ENERGY_COLUMNS.map(|c| c.trim_start_matches("energy."));
        if !terms.contains(&self.term.as_str()) {
            return Err(MbdError::Invalid {
                path: format!("{}.term", self.name),
                message: format!(
                    "`{}` is not an energy term; one of {}",
                    self.term,
                    terms.join(", ")
                ),
            });
        }
        let columns = vec![(format!("{}.energy", self.name), "J")];
        c.measures.push(CompiledMeasure {
            name: self.name.clone(),
            columns,
            el: MeasureEl::Copy {
                field: "term",
                sources: vec![format!("energy.{}", self.term)],
                index: Vec::new(),
                rotate: None,
            },
        });
        Ok(())
    }
}

/// Push a copy of the columns `<source>.<suffix>` as `<name>.<suffix>`.
fn push_copy(
    c: &mut Compiler,
    (name, field): (&str, &'static str),
    source: &str,
    suffixes: &[&str],
    units: &[&'static str],
    rotate: Option<usize>,
) {
    c.measures.push(CompiledMeasure {
        name: name.to_string(),
        columns: suffixes
            .iter()
            .zip(units)
            .map(|(s, u)| (format!("{name}.{s}"), *u))
            .collect(),
        el: MeasureEl::Copy {
            field,
            sources: suffixes.iter().map(|s| format!("{source}.{s}")).collect(),
            index: Vec::new(),
            rotate,
        },
    });
}
