//! Verification cases and the report written by `cargo xtask verify`.
//!
//! Format (architecture.md): `target/verify/report.json` holds
//! `{"cases": [{"id", "quantity", "value", "reference", "tolerance", "unit", "source", "pass"}],
//! "wall_s"}`; each case also carries `comparison` (how value and reference are compared) and an
//! optional `note`. `target/verify/report.md` is the same as a Markdown table.

use std::path::Path;

use serde::Serialize;

/// How a case's value is compared with its reference.
#[derive(Debug, Clone, Copy, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Comparison {
    /// |value − reference| ≤ tolerance · |reference|.
    Relative,
    /// |value − reference| ≤ tolerance.
    Absolute,
    /// value ≥ reference − tolerance.
    AtLeast,
    /// value ≤ reference + tolerance.
    AtMost,
}

impl Comparison {
    fn symbol(self) -> &'static str {
        match self {
            Comparison::Relative => "rel",
            Comparison::Absolute => "abs",
            Comparison::AtLeast => "≥",
            Comparison::AtMost => "≤",
        }
    }
}

/// One verification case: a measured value against a published number, a closed form or an
/// independent formulation.
#[derive(Debug, Clone, Serialize)]
pub struct Case {
    pub id: String,
    pub quantity: String,
    pub value: f64,
    pub reference: f64,
    pub tolerance: f64,
    pub unit: String,
    pub source: String,
    pub pass: bool,
    pub comparison: Comparison,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// A published finding the current reconstruction does not reproduce, known and documented:
    /// still `pass: false` in the report, but listed apart and not a regression (exit code 0).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub known_gap: bool,
}

/// A case under construction: what is measured and where the reference comes from.
pub struct CaseSpec {
    id: String,
    quantity: String,
    unit: String,
    source: String,
}

impl Case {
    /// Start a case: `id` (dotted, e.g. `ode.hires`), the quantity measured, its unit and the
    /// source of the reference.
    // A builder entry point: the case is finished by a comparison (`relative`, `at_least`, …).
    #[allow(clippy::new_ret_no_self)]
    pub fn new(
        id: impl Into<String>,
        quantity: impl Into<String>,
        unit: impl Into<String>,
        source: impl Into<String>,
    ) -> CaseSpec {
        CaseSpec {
            id: id.into(),
            quantity: quantity.into(),
            unit: unit.into(),
            source: source.into(),
        }
    }

    /// Attach a note (measured values of a comparison, solver statistics, caveats).
    pub fn note(mut self, note: impl Into<String>) -> Self {
        self.note = Some(note.into());
        self
    }

    /// Mark a failing case as a known, documented gap (`doc`: where it is explained). A case
    /// that passes is unaffected, so a gap that closes shows up as a pass.
    pub fn known_gap(mut self, doc: &str) -> Self {
        if !self.pass {
            self.known_gap = true;
            let note = self.note.take().unwrap_or_default();
            self.note = Some(format!("known gap, see {doc}; {note}"));
        }
        self
    }
}

impl CaseSpec {
    fn finish(self, value: f64, reference: f64, tolerance: f64, comparison: Comparison) -> Case {
        let pass = value.is_finite()
            && match comparison {
                Comparison::Relative => (value - reference).abs() <= tolerance * reference.abs(),
                Comparison::Absolute => (value - reference).abs() <= tolerance,
                Comparison::AtLeast => value >= reference - tolerance,
                Comparison::AtMost => value <= reference + tolerance,
            };
        Case {
            id: self.id,
            quantity: self.quantity,
            value,
            reference,
            tolerance,
            unit: self.unit,
            source: self.source,
            pass,
            comparison,
            note: None,
            known_gap: false,
        }
    }

    /// Pass when |value − reference| ≤ tol · |reference|.
    pub fn relative(self, value: f64, reference: f64, tol: f64) -> Case {
        self.finish(value, reference, tol, Comparison::Relative)
    }

    /// Pass when |value − reference| ≤ tol.
    pub fn absolute(self, value: f64, reference: f64, tol: f64) -> Case {
        self.finish(value, reference, tol, Comparison::Absolute)
    }

    /// Pass when value ≥ minimum.
    pub fn at_least(self, value: f64, minimum: f64) -> Case {
        self.finish(value, minimum, 0.0, Comparison::AtLeast)
    }

    /// Pass when value ≤ maximum.
    pub fn at_most(self, value: f64, maximum: f64) -> Case {
        self.finish(value, maximum, 0.0, Comparison::AtMost)
    }

    /// The computation itself failed (solver error, invalid model): a failing case that keeps
    /// the reference and says why.
    pub fn failed(self, reference: f64, why: impl Into<String>) -> Case {
        self.finish(f64::NAN, reference, 0.0, Comparison::Absolute)
            .note(why)
    }
}

#[derive(Serialize)]
struct ReportFile<'a> {
    cases: &'a [Case],
    wall_s: f64,
}

fn fmt_num(x: f64) -> String {
    if x.is_nan() {
        "—".into()
    } else if x == 0.0 || (1e-3..1e5).contains(&x.abs()) {
        format!("{x:.6}")
    } else {
        format!("{x:.6e}")
    }
}

/// Print one case as a line of the terminal table.
pub fn print_case(c: &Case) {
    println!(
        "{:4} {:40} {:>14} {:>3} {:>14} (tol {}) {}",
        if c.pass {
            "ok"
        } else if c.known_gap {
            "GAP"
        } else {
            "FAIL"
        },
        c.id,
        fmt_num(c.value),
        c.comparison.symbol(),
        fmt_num(c.reference),
        fmt_num(c.tolerance),
        c.unit
    );
    if !c.pass {
        if let Some(n) = &c.note {
            println!("     note: {n}");
        }
    }
}

/// Write `report.json` and `report.md` into `dir`.
pub fn write(dir: &Path, cases: &[Case], wall_s: f64) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let json = serde_json::to_string_pretty(&ReportFile { cases, wall_s })
        .map_err(std::io::Error::other)?;
    std::fs::write(dir.join("report.json"), json)?;
    let passed = cases.iter().filter(|c| c.pass).count();
    let gaps = cases.iter().filter(|c| c.known_gap).count();
    let mut md = format!(
        "# clr verification report\n\n{passed} of {} cases pass, {gaps} known gaps (published \
         findings the reconstruction does not reproduce, documented); wall time {wall_s:.1} s.\n\n\
         | id | quantity | value | cmp | reference | tolerance | unit | pass | source | note |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
        cases.len()
    );
    for c in cases {
        md.push_str(&format!(
            "| `{}` | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            c.id,
            c.quantity,
            fmt_num(c.value),
            c.comparison.symbol(),
            fmt_num(c.reference),
            fmt_num(c.tolerance),
            c.unit,
            if c.pass {
                "yes"
            } else if c.known_gap {
                "**no** (known gap)"
            } else {
                "**no**"
            },
            c.source,
            c.note.as_deref().unwrap_or("").replace('|', "/")
        ));
    }
    std::fs::write(dir.join("report.md"), md)
}
