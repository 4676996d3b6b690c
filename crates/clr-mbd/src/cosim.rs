//! Co-simulation: a planar model advanced by a master from one communication point to the next,
//! with its `[[input]]`s set between points and its output row read at each point. This is
//! what an FMU's `doStep` runs (the `clr-fmu` crate), and what a Rust control loop uses.
//!
//! Between points the integrator runs as in one [`Model::simulate`] run: same solver, located
//! contact onsets and restarts inside a step, and the history kept from one point to the next
//! ([`clr_ode::Solver::extend_to`]); each step is cut to end exactly at the point. It restarts
//! at a point only when a set input jumps there (a load to a different value, a motion's ramp to
//! a different rate), after projecting positions and velocities onto the constraints, and when
//! a saved state is restored.

use clr_ode::OdeSystem;

use crate::driver::{check_options, Stepping};
use crate::error::MbdError;
use crate::guide_exit::GuideExits;
use crate::input::{InputBank, SavedInput};
use crate::options::{InitialConditionsMode, SimOptions};
use crate::plausible::implausible;
use crate::system::Model;

/// A planar model stepped by a master ([module docs](self)).
pub struct CoSim {
    model: Model,
    opts: SimOptions,
    stepping: Stepping<Model>,
    columns: Vec<String>,
    row: Vec<f64>,
    pending: Vec<Option<f64>>,
    notes: Vec<String>,
}

/// A saved moment of a [`CoSim`]: time, state and the inputs' values ([`CoSim::save`]).
#[derive(Debug, Clone)]
pub struct CoSimState {
    t: f64,
    y: Vec<f64>,
    inputs: Vec<SavedInput>,
}

impl CoSimState {
    /// The saved time, s.
    pub fn time(&self) -> f64 {
        self.t
    }

    /// As numbers: t, the state's length and the state, the inputs' count and five numbers
    /// each (to serialize a state, as an FMU does).
    pub fn to_words(&self) -> Vec<f64> {
        let mut w = vec![self.t, self.y.len() as f64];
        w.extend_from_slice(&self.y);
        w.push(self.inputs.len() as f64);
        for s in &self.inputs {
            w.extend_from_slice(&s.to_words());
        }
        w
    }

    /// Read back [`CoSimState::to_words`]; `None` when the numbers are not such a state.
    pub fn from_words(w: &[f64]) -> Option<Self> {
        let count = |x: f64| (x >= 0.0 && x.fract() == 0.0 && x < 1e9).then_some(x as usize);
        let (&t, rest) = w.split_first()?;
        let (&n, rest) = rest.split_first()?;
        let n = count(n)?;
        let y = rest.get(..n)?.to_vec();
        let (&ni, rest) = rest.get(n..)?.split_first()?;
        let ni = count(ni)?;
        if rest.len() != 5 * ni {
            return None;
        }
        let inputs = rest
            .chunks_exact(5)
            .map(|c| SavedInput::from_words([c[0], c[1], c[2], c[3], c[4]]))
            .collect::<Option<Vec<_>>>()?;
        Some(CoSimState { t, y, inputs })
    }
}

/// Position tolerance of the projection after an input jumps, m or rad.
const PROJECTION_TOL: f64 = 1e-12;

impl CoSim {
    /// Assemble the initial state at `opts.t0` as [`Model::simulate`] does (the same initial
    /// conditions, checks and notes) and get ready to step. `opts.t_end` and the output times
    /// are not used: the master says where to go.
    ///
    /// # Errors
    /// As [`Model::simulate`] before its first step: inconsistent `exact` initial conditions,
    /// an implausible start under `strict`, invalid options.
    pub fn new(mut model: Model, opts: &SimOptions) -> Result<Self, MbdError> {
        let mut opts = opts.clone();
        opts.times.clear();
        opts.every_step = false;
        opts.t_end = opts.t_end.max(opts.t0 + 1.0);
        let (y0, ic) = model.assemble_initial_state_with(opts.t0, &opts.initial_setup)?;
        let corrected = ic.corrected();
        if opts.initial_conditions == InitialConditionsMode::Exact && !corrected.is_empty() {
            return Err(crate::sim::inconsistent(&ic, &corrected));
        }
        let start = model.check_start(opts.t0, &y0, &ic)?;
        if opts.strict && !start.is_empty() {
            return Err(implausible(&start, None));
        }
        check_options(&opts, y0.len(), model.dim(), || {
            format!("2n + 2 + m = {}", model.dim())
        })?;
        let (solver, ws) = model.solver(&opts);
        let exits = GuideExits::new(&model);
        let stepping = Stepping::new(&mut model, (opts.t0, &y0), (solver, ws), exits);
        let mut notes = ic.notes();
        notes.extend(start.iter().map(|w| format!("warning: {w}")));
        notes.extend(model.run_notes(&opts));
        Ok(CoSim {
            columns: model.columns(),
            row: Vec::new(),
            pending: vec![None; model.inputs().len()],
            model,
            opts,
            stepping,
            notes,
        })
    }

    /// The current time, s.
    pub fn time(&self) -> f64 {
        self.stepping.state().0
    }

    /// The current state y = (q, q̇, E_d, W_in, z).
    pub fn state(&self) -> &[f64] {
        self.stepping.state().1
    }

    /// The output column names (those of [`Model::columns`]: `t`, the bodies, contacts,
    /// energies and the `[[measure]]` columns).
    pub fn columns(&self) -> &[String] {
        &self.columns
    }

    /// The output row at the current time, in the order of [`CoSim::columns`] (evaluated from
    /// the state, as a recorded row of a run).
    pub fn outputs(&mut self) -> &[f64] {
        let (t, y) = self.stepping.state();
        self.row.clear();
        self.model.record(t, y, &mut self.row);
        &self.row
    }

    /// The model's inputs, in file order.
    pub fn inputs(&self) -> &InputBank {
        self.model.inputs()
    }

    /// The compiled model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Notes of the start: corrected initial conditions, warnings of the start checks, the
    /// run's notes (a finite-difference Newton matrix, …).
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// Integrator statistics so far (steps, evaluations, …).
    pub fn stats(&self) -> clr_ode::Stats {
        self.stepping.stats()
    }

    /// Set input `k` (file order) for the next [`CoSim::advance_to`]: a load holds `value` from
    /// the current time on; a motion moves linearly to `value` over the next advance.
    ///
    /// # Errors
    /// [`MbdError::Options`] for an index out of range or a value that is not finite.
    pub fn set_input(&mut self, k: usize, value: f64) -> Result<(), MbdError> {
        let n = self.pending.len();
        let Some(slot) = self.pending.get_mut(k) else {
            return Err(MbdError::Options(format!(
                "input index {k} is out of range: the model has {n} inputs"
            )));
        };
        if !value.is_finite() {
            let name = self.model.inputs().cells()[k].name().to_string();
            return Err(MbdError::Options(format!(
                "input `{name}` was given {value}: an input value must be finite"
            )));
        }
        *slot = Some(value);
        Ok(())
    }

    /// Integrate to `t` (s, after the current time), with the inputs set since the last
    /// advance.
    ///
    /// # Errors
    /// [`MbdError::Options`] for a time that is not finite or not after the current one; the
    /// run's errors ([`MbdError::Failed`], [`MbdError::Stopped`]) with their counters. After an
    /// error, [`CoSim::restore`] a saved state to go on.
    pub fn advance_to(&mut self, t: f64) -> Result<(), MbdError> {
        let now = self.time();
        if !t.is_finite() || t <= now {
            return Err(MbdError::Options(format!(
                "the next communication point {t} s must be finite and after the current time \
                 {now} s"
            )));
        }
        if self.apply_inputs(now, t)? {
            let mut y = self.state().to_vec();
            self.model.project(now, &mut y, PROJECTION_TOL)?;
            self.stepping.restart_at(&mut self.model, now, &y);
        }
        self.stepping.advance_to(&mut self.model, &self.opts, t)
    }

    /// Put the pending input values into their cells for the advance [now, t]; true when one
    /// jumps at `now`: a load's value changes, or a motion's rate (a new ramp, or the end of
    /// the last one: a motion without a new value holds where its ramp ended).
    fn apply_inputs(&mut self, now: f64, t: f64) -> Result<bool, MbdError> {
        let mut jumped = false;
        for (k, p) in self.pending.iter_mut().enumerate() {
            let cell = &self.model.inputs().cells()[k];
            let pending = p.take();
            if cell.is_motion() {
                let target = match pending {
                    Some(v) => v,
                    None if cell.is_default() => continue,
                    None => cell.eval(now)[0],
                };
                let before = cell.rate_before(now);
                cell.ramp_to(now, t, target)?;
                jumped |= cell.eval(now)[1] != before;
            } else if let Some(v) = pending {
                let before = cell.eval(now)[0];
                cell.ramp_to(now, t, v)?;
                jumped |= cell.eval(now)[0] != before;
            }
        }
        Ok(jumped)
    }

    /// Save the current moment (time, state, input values) to [`CoSim::restore`] later.
    pub fn save(&self) -> CoSimState {
        CoSimState {
            t: self.time(),
            y: self.state().to_vec(),
            inputs: self.inputs().cells().iter().map(|c| c.saved()).collect(),
        }
    }

    /// Go back to a saved moment. The integrator restarts there with a fresh history, and the
    /// contact memory is rebuilt from the saved state, so a restored run matches the original
    /// within the solver's tolerance, not bit for bit.
    ///
    /// # Errors
    /// [`MbdError::Options`] for a state saved from another model.
    pub fn restore(&mut self, s: &CoSimState) -> Result<(), MbdError> {
        if s.y.len() != self.state().len() || s.inputs.len() != self.pending.len() {
            return Err(MbdError::Options(
                "the saved state belongs to another model (its sizes differ)".into(),
            ));
        }
        for (c, v) in self.model.inputs().cells().iter().zip(&s.inputs) {
            c.restore(*v);
        }
        self.pending.iter_mut().for_each(|p| *p = None);
        self.stepping.restart_at(&mut self.model, s.t, &s.y);
        Ok(())
    }
}
