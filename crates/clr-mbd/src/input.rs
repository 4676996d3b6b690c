//! Named real inputs (`[[input]]`): values a master sets while the model runs (a co-simulation
//! master, a controller in Rust or Python), with a time function as the value when nobody sets
//! one.
//!
//! A force, torque, actuator force or driver motion refers to an input where it takes a time
//! function: `torque = { type = "input", name = "u" }` ([`TimeFn::Input`]). Compiling binds each
//! such reference to the input's [`InputCell`]; the compiled model keeps the cells in an
//! [`InputBank`], and setting a cell changes what every element bound to it sees at the next
//! evaluation. The description stays plain data: the cells live only in the compiled model, one
//! set per compiled model, so parallel runs and FMU instances never share them.
//!
//! What a set value means over time:
//! - a load (force, torque, actuator force) holds it (zero-order hold, derivatives 0);
//! - a driver's motion moves linearly from its value at the time of the call to the set value
//!   at the end of the ramp ([`InputCell::ramp_to`]: the next communication point of an FMU), so
//!   the driven coordinate stays continuous; its rate is the ramp's slope and its acceleration 0.

use std::sync::{Arc, Mutex};

use serde::{Deserialize, Serialize};

use crate::error::MbdError;
use crate::timefn::TimeFn;

/// One `[[input]]` of a description.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputDesc {
    /// Unique name, referred to as `{ type = "input", name = "…" }`.
    pub name: String,
    /// The value while no master sets one, in the unit of what the input drives (N, N·m, m or
    /// rad); constant 0 when absent.
    #[serde(default = "zero", skip_serializing_if = "is_zero")]
    pub default: TimeFn,
    /// A line saying what the input is (written into an FMU's description).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
}

fn zero() -> TimeFn {
    TimeFn::Constant { value: 0.0 }
}

fn is_zero(f: &TimeFn) -> bool {
    *f == zero()
}

/// Where an element takes a time function: the field, its unit and whether it is a driver's
/// motion (set values then ramp instead of being held).
pub struct TimeFnSlot<'a> {
    /// The field of the element (`torque`, `motion`, `fx`).
    pub field: &'static str,
    /// Its unit (N, N·m, m, rad).
    pub unit: &'static str,
    /// True for a driver's prescribed motion.
    pub motion: bool,
    /// The time function itself.
    pub f: &'a mut TimeFn,
}

/// The value an input gives at a time.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Source {
    /// The input's default time function.
    Default,
    /// A value held (loads).
    Held(f64),
    /// A linear move from (t0, v0) to (t1, v1), held at v1 after t1 (motions).
    Ramp { t0: f64, v0: f64, t1: f64, v1: f64 },
}

/// The runtime form of one input: its default, unit and the value set last.
#[derive(Debug)]
pub struct InputCell {
    name: String,
    unit: &'static str,
    motion: bool,
    description: String,
    default: TimeFn,
    source: Mutex<Source>,
}

impl InputCell {
    /// The input's name.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// The unit of what it drives (N, N·m, m, rad).
    pub fn unit(&self) -> &'static str {
        self.unit
    }
    /// True when it drives a driver's motion (set values ramp).
    pub fn is_motion(&self) -> bool {
        self.motion
    }
    /// The description line of its `[[input]]`.
    pub fn description(&self) -> &str {
        &self.description
    }

    fn source(&self) -> Source {
        // a poisoned lock only means a panic elsewhere; the value itself is always whole
        *self.source.lock().unwrap_or_else(|p| p.into_inner())
    }

    fn put(&self, s: Source) {
        *self.source.lock().unwrap_or_else(|p| p.into_inner()) = s;
    }

    /// [u(t), u′(t), u″(t)] in the input's unit. Allocation-free (an uncontended lock).
    pub fn eval(&self, t: f64) -> [f64; 3] {
        match self.source() {
            Source::Default => self.default.eval(t),
            Source::Held(v) => [v, 0.0, 0.0],
            Source::Ramp { t0, v0, t1, v1 } => {
                if t >= t1 || t1 <= t0 {
                    [v1, 0.0, 0.0]
                } else {
                    let slope = (v1 - v0) / (t1 - t0);
                    let s = (t - t0).max(0.0);
                    [v0 + slope * s, slope, 0.0]
                }
            }
        }
    }

    /// The rate u′ just before `t` (the left limit: a ramp ending at t still has its slope
    /// there), in the input's unit per second.
    pub fn rate_before(&self, t: f64) -> f64 {
        match self.source() {
            Source::Default => self.default.eval(t)[1],
            Source::Held(_) => 0.0,
            Source::Ramp { t0, v0, t1, v1 } => {
                if t > t0 && t <= t1 && t1 > t0 {
                    (v1 - v0) / (t1 - t0)
                } else {
                    0.0
                }
            }
        }
    }

    /// True while the input follows its default function (no value set).
    pub fn is_default(&self) -> bool {
        self.source() == Source::Default
    }

    /// Hold `value` from now on (a load), or for a motion jump to it.
    ///
    /// # Errors
    /// [`MbdError::Options`] for a value that is not finite.
    pub fn set(&self, value: f64) -> Result<(), MbdError> {
        self.finite(value)?;
        self.put(Source::Held(value));
        Ok(())
    }

    /// For a load: hold `value` (as [`InputCell::set`]). For a motion: move linearly from its
    /// value at `t0` to `value` at `t1` (s, t1 > t0), then hold it.
    ///
    /// # Errors
    /// [`MbdError::Options`] for a value that is not finite or t1 ≤ t0.
    pub fn ramp_to(&self, t0: f64, t1: f64, value: f64) -> Result<(), MbdError> {
        self.finite(value)?;
        if !self.motion {
            self.put(Source::Held(value));
            return Ok(());
        }
        if t1 <= t0 || !t0.is_finite() || !t1.is_finite() {
            return Err(MbdError::Options(format!(
                "input `{}`: the ramp must end after it starts (t0 = {t0} s, t1 = {t1} s)",
                self.name
            )));
        }
        let v0 = self.eval(t0)[0];
        self.put(Source::Ramp {
            t0,
            v0,
            t1,
            v1: value,
        });
        Ok(())
    }

    /// Go back to the default time function.
    pub fn reset(&self) {
        self.put(Source::Default);
    }

    /// The value set last as data (to save and restore a state), `None` for the default.
    pub fn saved(&self) -> SavedInput {
        SavedInput(self.source())
    }

    /// Put back a value saved with [`InputCell::saved`].
    pub fn restore(&self, s: SavedInput) {
        self.put(s.0);
    }

    fn finite(&self, value: f64) -> Result<(), MbdError> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(MbdError::Options(format!(
                "input `{}` was given {value}: an input value must be finite ({})",
                self.name, self.unit
            )))
        }
    }
}

/// What an input held at one moment ([`InputCell::saved`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SavedInput(Source);

impl SavedInput {
    /// As five numbers (kind, then the held value or the ramp's t0, v0, t1, v1).
    pub fn to_words(self) -> [f64; 5] {
        match self.0 {
            Source::Default => [0.0; 5],
            Source::Held(v) => [1.0, v, 0.0, 0.0, 0.0],
            Source::Ramp { t0, v0, t1, v1 } => [2.0, t0, v0, t1, v1],
        }
    }
    /// Read back [`SavedInput::to_words`]; `None` for an unknown kind.
    pub fn from_words(w: [f64; 5]) -> Option<Self> {
        // the kinds are the small integers to_words writes, exact in f64
        let kind = w[0] as i64;
        if kind as f64 != w[0] {
            return None;
        }
        Some(SavedInput(match kind {
            0 => Source::Default,
            1 => Source::Held(w[1]),
            2 => Source::Ramp {
                t0: w[1],
                v0: w[2],
                t1: w[3],
                v1: w[4],
            },
            _ => return None,
        }))
    }
}

/// The inputs of a compiled model, in the order of the `[[input]]` sections.
#[derive(Debug, Clone, Default)]
pub struct InputBank {
    cells: Vec<Arc<InputCell>>,
}

impl InputBank {
    /// The cells, in file order.
    pub fn cells(&self) -> &[Arc<InputCell>] {
        &self.cells
    }
    /// The cell named `name`.
    pub fn get(&self, name: &str) -> Option<&Arc<InputCell>> {
        self.cells.iter().find(|c| c.name == name)
    }
    /// The number of inputs.
    pub fn len(&self) -> usize {
        self.cells.len()
    }
    /// True without inputs.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }
    /// Every input back to its default.
    pub fn reset(&self) {
        self.cells.iter().for_each(|c| c.reset());
    }
}

/// Bind every `{ type = "input" }` among `slots` (element `owner`) to the cells of `descs`,
/// creating the cells on first use in `bank`: checks that the input is declared, that one input
/// does not drive fields of different units, and that every declared input is used (by the
/// caller, with [`unused`]).
///
/// # Errors
/// [`MbdError::Invalid`] at the element's field.
pub(crate) fn bind(
    owner: &str,
    slots: Vec<TimeFnSlot<'_>>,
    descs: &[InputDesc],
    bank: &mut InputBank,
) -> Result<(), MbdError> {
    for slot in slots {
        let path = format!("{owner}.{}", slot.field);
        bind_fn(slot.f, &path, (slot.unit, slot.motion), descs, bank)?;
    }
    Ok(())
}

fn bind_fn(
    f: &mut TimeFn,
    path: &str,
    (unit, motion): (&'static str, bool),
    descs: &[InputDesc],
    bank: &mut InputBank,
) -> Result<(), MbdError> {
    match f {
        TimeFn::Input { name, cell } => {
            let c: Arc<dyn crate::timefn::InputValue> =
                cell_for(name, path, (unit, motion), descs, bank)?;
            *cell = Some(crate::timefn::BoundInput(c));
            Ok(())
        }
        TimeFn::Sum { terms: v } | TimeFn::Product { factors: v } => v
            .iter_mut()
            .try_for_each(|g| bind_fn(g, path, (unit, motion), descs, bank)),
        _ => Ok(()),
    }
}

fn cell_for(
    name: &str,
    path: &str,
    (unit, motion): (&'static str, bool),
    descs: &[InputDesc],
    bank: &mut InputBank,
) -> Result<Arc<InputCell>, MbdError> {
    let invalid = |message: String| MbdError::Invalid {
        path: path.to_string(),
        message,
    };
    let Some(d) = descs.iter().find(|d| d.name == name) else {
        let names: Vec<&str> = descs.iter().map(|d| d.name.as_str()).collect();
        return Err(invalid(format!(
            "no [[input]] is named `{name}`{}",
            crate::field::suggestion(name, names.iter().copied())
        )));
    };
    if let Some(c) = bank.get(name) {
        if c.unit != unit {
            return Err(invalid(format!(
                "input `{name}` already drives a field in {} and cannot also drive one in \
                 {unit}: declare a second [[input]]",
                c.unit
            )));
        }
        if c.motion != motion {
            return Err(invalid(format!(
                "input `{name}` drives both a driver's motion and a load; declare one input \
                 for each (a motion's set values ramp, a load's are held)"
            )));
        }
        return Ok(Arc::clone(c));
    }
    d.default
        .validate(&format!("input.{name}.default"))
        .map_err(MbdError::from)?;
    if d.default.has_input() {
        return Err(invalid(format!(
            "the default of input `{name}` refers to an input: give it a function of time"
        )));
    }
    let cell = Arc::new(InputCell {
        name: name.to_string(),
        unit,
        motion,
        description: d.description.clone(),
        default: d.default.clone(),
        source: Mutex::new(Source::Default),
    });
    bank.cells.push(Arc::clone(&cell));
    Ok(cell)
}

/// Refuse declared inputs that nothing refers to and repeated names (an unused input would be a
/// co-simulation input that does nothing), then put the cells in file order.
///
/// # Errors
/// [`MbdError::Invalid`] at `input[k]`.
pub(crate) fn finish(descs: &[InputDesc], bank: &mut InputBank) -> Result<(), MbdError> {
    for (k, d) in descs.iter().enumerate() {
        if d.name.trim().is_empty() {
            return Err(MbdError::Invalid {
                path: format!("input[{k}].name"),
                message: "the name is blank: give the name the elements refer to".into(),
            });
        }
        if descs[..k].iter().any(|e| e.name == d.name) {
            return Err(MbdError::Invalid {
                path: format!("input[{k}].name"),
                message: format!("a second [[input]] is named `{}`", d.name),
            });
        }
        if bank.get(&d.name).is_none() {
            return Err(MbdError::Invalid {
                path: format!("input[{k}]"),
                message: format!(
                    "input `{}` is declared but nothing refers to it: use it as \
                     `{{ type = \"input\", name = \"{}\" }}` in a force, torque, actuator or \
                     driver, or remove it",
                    d.name, d.name
                ),
            });
        }
    }
    bank.cells
        .sort_by_key(|c| descs.iter().position(|d| d.name == c.name));
    Ok(())
}

impl crate::timefn::InputValue for InputCell {
    fn value(&self, t: f64) -> [f64; 3] {
        self.eval(t)
    }
}

/// A load's value as a function of time (s) and the feedback measures' values (in the order of
/// [`crate::Model::feedback_columns`]): a controller or a custom force written in Rust or
/// Python ([`crate::Model::set_input_function`]). Called at every evaluation of the forces.
pub type InputFn = Arc<dyn Fn(f64, &[f64]) -> f64 + Send + Sync>;

/// The inputs given as functions of the state, and the position- and velocity-level measures
/// they read.
#[derive(Clone, Default)]
pub(crate) struct Feedback {
    fns: Vec<(usize, InputFn)>,
    measures: Vec<usize>,
    buf: Vec<f64>,
    zeros: Vec<f64>,
}

impl std::fmt::Debug for Feedback {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Feedback({} functions)", self.fns.len())
    }
}

/// Whether a measure can be evaluated inside the right-hand side: positions and velocities of
/// points and angles, distances and their rates (not accelerations, reactions, contact values,
/// energies or momentum, which need the solved accelerations or a whole row).
pub(crate) fn is_feedback(m: &crate::measure::runtime::CompiledMeasure) -> bool {
    use crate::measure::runtime::{MeasureEl as E, Quantity as Q};
    match &m.el {
        E::Point { quantity, .. } | E::Angle { quantity, .. } => *quantity != Q::Acceleration,
        E::Distance { .. } => true,
        _ => false,
    }
}

impl Feedback {
    pub(crate) fn is_empty(&self) -> bool {
        self.fns.is_empty()
    }

    /// The names of the inputs given as functions.
    pub(crate) fn names(&self, bank: &InputBank) -> Vec<String> {
        self.fns
            .iter()
            .map(|(k, _)| bank.cells[*k].name.clone())
            .collect()
    }

    /// Make input `cell` the function `f` of the measures `measures` (indices of the model's
    /// measures, all [`is_feedback`]).
    pub(crate) fn set(&mut self, cell: usize, f: InputFn, measures: Vec<usize>) {
        self.fns.retain(|(k, _)| *k != cell);
        self.fns.push((cell, f));
        self.measures = measures;
    }

    /// Evaluate the feedback measures at (t, q, q̇) and put each function's value into its
    /// input. Allocation-free after the first call.
    pub(crate) fn update(
        &mut self,
        t: f64,
        (frames, q, qd): (&[crate::runtime::Frame], &[f64], &[f64]),
        measures: &[crate::measure::runtime::CompiledMeasure],
        bank: &InputBank,
    ) {
        self.zeros.resize(q.len(), 0.0);
        self.buf.clear();
        let row = crate::measure::runtime::Row {
            frames,
            q,
            qd,
            qdd: &self.zeros,
        };
        for &k in &self.measures {
            measures[k].write(&row, &mut self.buf, 0);
        }
        for (k, f) in &self.fns {
            bank.cells[*k].put(Source::Held(f(t, &self.buf)));
        }
    }
}
