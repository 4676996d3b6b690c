//! One fuzz case through the public API of `clr`, as `clr run <file>` does it: parse and
//! validate the model file (`clr_sim::spec::load_str`), build the model, and (when asked) simulate
//! a short span with a step budget (`clr_sim::spec::run::execute` with `--max-steps`-like knobs).
//! A panic is caught and returned as [`Verdict::Panic`]; hangs are the caller's watchdog's.
//!
//! Depends on `clr`, `serde_json`, `toml` and `std` only (all dependencies of `clr`), so that
//! `tests/fuzz_model_files.rs` includes this file as a module (`#[path]`).

#![allow(dead_code)]

use std::panic::{catch_unwind, AssertUnwindSafe};

use clr_sim::spec::run::{execute, Job, RunError};
use clr_sim::spec::{load_str, Loaded, SpecError};

/// How much of a case runs.
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Simulate the accepted model (else parse, validate and build only).
    pub simulate: bool,
    /// Longest simulated span (s).
    pub span: f64,
    /// Step budget of the simulation (accepted steps).
    pub max_steps: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            simulate: false,
            span: 1e-3,
            max_steps: 2000,
        }
    }
}

/// What became of one input.
#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    /// Accepted (and simulated without failure when asked).
    Accepted {
        /// It was simulated.
        simulated: bool,
    },
    /// Rejected with an error placed at a line or a field.
    Rejected,
    /// Rejected with an error that names neither a line nor a field (a finding).
    Unlocated(String),
    /// Accepted, and the simulation failed with an error (fine: a solver failure is reported).
    SolverFailure(String),
    /// Panicked (a finding): the panic message.
    Panic(String),
}

impl Verdict {
    /// True for findings (panics, errors without a place).
    pub fn is_finding(&self) -> bool {
        matches!(self, Verdict::Unlocated(_) | Verdict::Panic(_))
    }
}

/// The file name used in messages.
pub const FILE: &str = "fuzz.toml";

fn spec_verdict(e: &SpecError) -> Verdict {
    if e.line.is_some() || !e.field.is_empty() {
        Verdict::Rejected
    } else {
        Verdict::Unlocated(e.to_string())
    }
}

fn run_verdict(e: &RunError) -> Verdict {
    match e {
        RunError::Spec(s) => spec_verdict(s),
        RunError::Input(m) => Verdict::Unlocated(m.clone()),
    }
}

/// Text of a panic payload.
pub fn panic_message(p: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "(non-text panic payload)".to_string()
    }
}

thread_local! {
    /// Place of the last panic on this thread (set by the [`quiet_panics`] hook).
    static PANIC_AT: std::cell::RefCell<Option<String>> = const { std::cell::RefCell::new(None) };
    /// This thread runs a case.
    static IN_CASE: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Run one input (panics caught; after [`quiet_panics`] the message carries the panic's source
/// location).
pub fn run(text: &str, limits: &Limits) -> Verdict {
    PANIC_AT.with(|p| p.borrow_mut().take());
    IN_CASE.with(|c| c.set(true));
    let r = catch_unwind(AssertUnwindSafe(|| run_inner(text, limits)));
    IN_CASE.with(|c| c.set(false));
    match r {
        Ok(v) => v,
        Err(p) => {
            let at = PANIC_AT.with(|p| p.borrow_mut().take());
            let msg = panic_message(&*p);
            Verdict::Panic(match at {
                Some(at) => format!("{at}: {msg}"),
                None => msg,
            })
        }
    }
}

fn knobs(limits: &Limits) -> clr_sim::models::SolverKnobs {
    clr_sim::models::SolverKnobs {
        max_steps: Some(limits.max_steps),
        ..Default::default()
    }
}

fn run_inner(text: &str, limits: &Limits) -> Verdict {
    let loaded = match load_str(FILE, text, &[]) {
        Ok(l) => l,
        Err(e) => return spec_verdict(&e),
    };
    match loaded {
        Loaded::Generic(spec) => {
            let job = match Job::Generic(spec).with_knobs(knobs(limits)) {
                Ok(j) => j,
                Err(e) => return run_verdict(&e),
            };
            let Job::Generic(mut spec) = job else {
                unreachable!("a generic job stays generic")
            };
            if !limits.simulate {
                return match spec.build() {
                    Ok(_) => Verdict::Accepted { simulated: false },
                    Err(e) => spec_verdict(&e),
                };
            }
            let (t0, t1) = (spec.options.t0, spec.options.t_end);
            let end = t0 + (t1 - t0).min(limits.span);
            if end <= t0 || spec.set_t_end(end).is_err() {
                // the span cannot be shortened (t0 huge): build only
                return match spec.build() {
                    Ok(_) => Verdict::Accepted { simulated: false },
                    Err(e) => spec_verdict(&e),
                };
            }
            match execute(&Job::Generic(spec), None, None, None) {
                Ok(o) => match o.error {
                    None => Verdict::Accepted { simulated: true },
                    Some(m) => Verdict::SolverFailure(m),
                },
                Err(e) => run_verdict(&e),
            }
        }
        Loaded::Spatial(spec) => {
            let job = match Job::Spatial(spec).with_knobs(knobs(limits)) {
                Ok(j) => j,
                Err(e) => return run_verdict(&e),
            };
            let Job::Spatial(mut spec) = job else {
                unreachable!("a spatial job stays spatial")
            };
            let (t0, t1) = (spec.options.t0, spec.options.t_end);
            let end = t0 + (t1 - t0).min(limits.span);
            if !limits.simulate || end <= t0 || spec.set_t_end(end).is_err() {
                return match spec.build() {
                    Ok(_) => Verdict::Accepted { simulated: false },
                    Err(e) => spec_verdict(&e),
                };
            }
            match execute(&Job::Spatial(spec), None, None, None) {
                Ok(o) => match o.error {
                    None => Verdict::Accepted { simulated: true },
                    Some(m) => Verdict::SolverFailure(m),
                },
                Err(e) => run_verdict(&e),
            }
        }
        Loaded::Builtin { name, parameters } => {
            let job = Job::Builtin {
                name,
                parameters,
                knobs: knobs(limits),
            };
            if !limits.simulate {
                return Verdict::Accepted { simulated: false };
            }
            let end = job
                .time_span(None)
                .map_or(limits.span, |(_, t)| t.min(limits.span));
            match execute(&job, Some(end), None, None) {
                Ok(o) => match o.error {
                    None => Verdict::Accepted { simulated: true },
                    Some(m) => Verdict::SolverFailure(m),
                },
                Err(e) => run_verdict(&e),
            }
        }
    }
}

/// Silence the panics of [`run`] (once per process): a panic inside a case only leaves its
/// source location for [`run`]'s verdict; any other panic (a failed assertion) goes to the
/// previous hook as usual.
pub fn quiet_panics() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if IN_CASE.with(std::cell::Cell::get) {
                if let Some(l) = info.location() {
                    let at = format!("{}:{}:{}", l.file(), l.line(), l.column());
                    PANIC_AT.with(|p| *p.borrow_mut() = Some(at));
                }
            } else {
                previous(info);
            }
        }));
    });
}

/// A built-in model file (`[model] builtin = "<name>"` with every `[parameters]` at its catalog
/// default) for each catalog model, as seeds of the built-in form.
pub fn builtin_seeds() -> Vec<(String, String)> {
    clr_sim::models::catalog::entries()
        .iter()
        .filter_map(|e| {
            let params = clr_sim::models::catalog::default_parameters(e.name).ok()?;
            let params: toml::Value = serde_json::from_value(params).ok()?;
            let mut root = toml::Table::new();
            let mut model = toml::Table::new();
            model.insert("builtin".into(), e.name.into());
            root.insert("model".into(), model.into());
            root.insert("parameters".into(), params);
            Some((format!("builtin:{}", e.name), toml::to_string(&root).ok()?))
        })
        .collect()
}
