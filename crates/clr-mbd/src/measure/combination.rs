//! `combination`: a sum of terms, each a factor times a column or a product of columns,
//! optionally its absolute value: `<name>.value` = Σ_k c_k · (|x_k,1 · x_k,2 · …| or
//! x_k,1 · x_k,2 · …). It reads columns the run writes at the same row (its own and those of
//! earlier measures), so it costs a few multiplications per row and needs nothing evaluated
//! twice: the total normal force of several contact pads, the friction magnitude summed over
//! them, a generalized coordinate mapped to a displacement (a modal tip deflection Σ T_k q_k), a
//! power F·v, or the moment δ·F_T of a friction pair applied at points δ apart.
//!
//! The column's unit is `unit` when given (one of [`crate::results::UNITS`]), else the common
//! unit of the terms, which must then be single columns of one unit.

use serde::{Deserialize, Serialize};

use super::runtime::{CompiledMeasure, MeasureEl};
use crate::element::{Compiler, Element};
use crate::error::MbdError;
use crate::results::{known_unit, UNITS};

/// One column name or several (a product).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Columns {
    /// One column.
    One(String),
    /// Several columns, multiplied.
    Many(Vec<String>),
}

impl Columns {
    /// The column names.
    pub fn names(&self) -> &[String] {
        match self {
            Columns::One(c) => std::slice::from_ref(c),
            Columns::Many(v) => v,
        }
    }
}

/// One term c · x (or c · |x|), x a column or a product of columns.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Term {
    /// The column, or the columns multiplied.
    pub of: Columns,
    /// The factor c (default 1), in the unit of the measure over that of the columns.
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub factor: f64,
    /// Take the absolute value of the column (or product) before the factor (default false).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub abs: bool,
}

impl Term {
    /// `factor` · x (or · |x| with `abs`) for the single column `of`.
    pub fn column(of: &str, factor: f64, abs: bool) -> Self {
        Term {
            of: Columns::One(of.into()),
            factor,
            abs,
        }
    }
}

fn one() -> f64 {
    1.0
}

fn is_one(x: &f64) -> bool {
    *x == 1.0
}

/// A sum of terms: `<name>.value`, in `unit` or the terms' common unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Combination {
    /// Unique measure name.
    pub name: String,
    /// The terms, summed in order (at least one).
    pub terms: Vec<Term>,
    /// The unit of the column (default: the common unit of single-column terms).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unit: Option<String>,
}

impl Combination {
    /// The `combination` measure `name` of `terms`, in the terms' common unit.
    pub fn measure(name: &str, terms: Vec<Term>) -> super::Measure {
        super::Measure::Combination(Combination {
            name: name.into(),
            terms,
            unit: None,
        })
    }

    fn invalid(&self, field: &str, message: String) -> MbdError {
        MbdError::Invalid {
            path: format!("{}.{field}", self.name),
            message,
        }
    }

    /// The column's unit when given (module docs), else `None` (the common unit of the terms'
    /// columns, found when the columns are: [`super::runtime::resolve`]).
    fn unit(&self) -> Result<Option<&'static str>, MbdError> {
        if let Some(u) = &self.unit {
            return known_unit(u).map(Some).ok_or_else(|| {
                self.invalid(
                    "unit",
                    format!("`{u}` is not a unit clr knows; one of {}", UNITS.join(", ")),
                )
            });
        }
        if self.terms.iter().any(|t| t.of.names().len() > 1) {
            return Err(self.invalid(
                "unit",
                "some terms are products of columns: say the unit of the sum (`unit = \"W\"`, \
                 say)"
                    .into(),
            ));
        }
        Ok(None)
    }
}

impl Element for Combination {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        if self.terms.is_empty() {
            return Err(self.invalid("terms", "give at least one term".into()));
        }
        for (k, t) in self.terms.iter().enumerate() {
            if t.of.names().is_empty() {
                return Err(self.invalid(&format!("terms[{k}].of"), "name a column".into()));
            }
            if !t.factor.is_finite() {
                return Err(self.invalid(
                    &format!("terms[{k}].factor"),
                    format!("{}: the factor must be finite", t.factor),
                ));
            }
        }
        let unit = self.unit()?;
        c.measures.push(CompiledMeasure {
            name: self.name.clone(),
            columns: vec![(format!("{}.value", self.name), unit.unwrap_or("-"))],
            el: MeasureEl::Combination {
                sources: (self.terms.iter()).map(|t| t.of.names().to_vec()).collect(),
                index: Vec::new(),
                factors: self.terms.iter().map(|t| (t.factor, t.abs)).collect(),
                infer_unit: unit.is_none(),
            },
        });
        Ok(())
    }
}
