//! One FMU instance as safe Rust: the FMI 3.0 co-simulation states (instantiated,
//! initialization, step, terminated) and what each call may do in each, over
//! [`clr_mbd::cosim::CoSim`]. The C functions in `lib.rs` only translate to and from this.

use clr_mbd::cosim::{CoSim, CoSimState};
use clr_sim::fmu::FmuConfig;
use clr_sim::spec::{self, Assignment, Loaded};

/// The FMI status of a refused or failed call, with the message to log.
#[derive(Debug, Clone, PartialEq)]
pub struct Refusal {
    /// `true`: fmi3Error (the call failed, the instance can go on or be reset); `false`:
    /// fmi3Discard (a step could not be completed).
    pub error: bool,
    /// What happened and what to change.
    pub message: String,
}

fn error(message: impl Into<String>) -> Refusal {
    Refusal {
        error: true,
        message: message.into(),
    }
}

/// The FMI state of an instance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// After instantiation or reset.
    Instantiated,
    /// Between fmi3EnterInitializationMode and fmi3ExitInitializationMode.
    Initialization,
    /// Stepping.
    Step,
    /// After fmi3Terminate.
    Terminated,
}

/// What a value reference names.
enum Var {
    Time,
    Input(usize),
    Output(usize),
    Parameter(usize),
}

/// A saved moment of an instance (fmi3GetFMUState).
#[derive(Debug, Clone)]
pub struct Saved {
    state: CoSimState,
    inputs: Vec<Option<f64>>,
}

/// One FMU instance.
pub struct Instance {
    config: FmuConfig,
    model_text: String,
    phase: Phase,
    parameters: Vec<f64>,
    inputs: Vec<Option<f64>>,
    dirty: Vec<bool>,
    tolerance: Option<f64>,
    start_time: f64,
    cosim: Option<CoSim>,
    columns: Vec<usize>,
}

impl Instance {
    /// An instance of the model `model_text` with `config` (both from the FMU's resources).
    ///
    /// # Errors
    /// A message when the model does not load or `token` is not the FMU's.
    pub fn new(config: FmuConfig, model_text: String, token: &str) -> Result<Self, Refusal> {
        if token != config.token {
            return Err(error(format!(
                "the instantiation token {token} is not this FMU's ({}): the \
                 modelDescription.xml and the resources belong to different exports",
                config.token
            )));
        }
        let mut inst = Instance {
            parameters: config.parameters.iter().map(|p| p.start).collect(),
            inputs: vec![None; config.inputs.len()],
            dirty: vec![false; config.inputs.len()],
            start_time: config.experiment[0],
            config,
            model_text,
            phase: Phase::Instantiated,
            tolerance: None,
            cosim: None,
            columns: Vec::new(),
        };
        // load once now, so that a broken FMU fails at instantiation with the model's message
        inst.build()?;
        inst.cosim = None;
        Ok(inst)
    }

    /// The current phase.
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// The default experiment's start time, s.
    pub fn start_time(&self) -> f64 {
        self.config.experiment[0]
    }

    /// fmi3EnterInitializationMode.
    ///
    /// # Errors
    /// Out of order, or a tolerance or start time that is not finite and positive.
    pub fn enter_initialization(
        &mut self,
        tolerance: Option<f64>,
        start_time: f64,
    ) -> Result<(), Refusal> {
        self.expect(&[Phase::Instantiated], "fmi3EnterInitializationMode")?;
        if let Some(t) = tolerance {
            if !(t.is_finite() && t > 0.0 && t < 1.0) {
                return Err(error(format!(
                    "the tolerance {t} must be a relative tolerance in (0, 1)"
                )));
            }
        }
        if !start_time.is_finite() {
            return Err(error(format!("the start time {start_time} is not finite")));
        }
        self.tolerance = tolerance;
        self.start_time = start_time;
        self.phase = Phase::Initialization;
        Ok(())
    }

    /// fmi3ExitInitializationMode: compiles the model with the parameters and assembles the
    /// initial state at the start time.
    ///
    /// # Errors
    /// Out of order, or the model's message (a parameter value it refuses, inconsistent initial
    /// conditions).
    pub fn exit_initialization(&mut self) -> Result<(), Refusal> {
        self.expect(&[Phase::Initialization], "fmi3ExitInitializationMode")?;
        if self.cosim.is_none() {
            self.build()?;
        }
        self.phase = Phase::Step;
        Ok(())
    }

    /// The model with the parameters, tolerance and start time applied, ready to step.
    fn build(&mut self) -> Result<(), Refusal> {
        let mut sets: Vec<Assignment> = (self.config.parameters.iter())
            .zip(&self.parameters)
            .map(|(p, v)| Assignment {
                path: p.path.clone(),
                value: toml::Value::Float(*v),
            })
            .collect();
        if let Some(t) = self.tolerance {
            sets.push(Assignment {
                path: "solver.rtol".into(),
                value: toml::Value::Float(t),
            });
        }
        let spec = match spec::load_str(&self.config.model_name, &self.model_text, &sets) {
            Ok(Loaded::Generic(s)) => s,
            Ok(_) => return Err(error("the FMU's model is not a planar model file")),
            Err(e) => return Err(error(e.to_string())),
        };
        let built = spec.build().map_err(|e| error(e.to_string()))?;
        let mut opts = built.options;
        opts.t0 = self.start_time;
        let cosim = CoSim::new(built.model, &opts).map_err(|e| error(e.to_string()))?;
        let columns = cosim.columns();
        self.columns = (self.config.outputs.iter())
            .map(|o| columns.iter().position(|c| *c == o.name))
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| error("an output of the FMU is not a column of its model"))?;
        self.cosim = Some(cosim);
        self.dirty.iter_mut().for_each(|d| *d = true);
        Ok(())
    }

    /// Notes of the start (corrected initial conditions, warnings), for the log.
    pub fn notes(&self) -> Vec<String> {
        self.cosim
            .as_ref()
            .map(|c| c.notes().to_vec())
            .unwrap_or_default()
    }

    fn var(&self, vr: u32) -> Result<Var, Refusal> {
        let (ni, no, np) = (
            self.config.inputs.len(),
            self.config.outputs.len(),
            self.config.parameters.len(),
        );
        let k = vr as usize;
        Ok(match k {
            0 => Var::Time,
            k if k <= ni => Var::Input(k - 1),
            k if k <= ni + no => Var::Output(k - 1 - ni),
            k if k <= ni + no + np => Var::Parameter(k - 1 - ni - no),
            _ => {
                return Err(error(format!(
                    "value reference {vr} does not exist (this FMU has 0 to {})",
                    ni + no + np
                )))
            }
        })
    }

    /// fmi3GetFloat64 of one value reference.
    ///
    /// # Errors
    /// Unknown references, or calls before instantiation finished.
    pub fn get(&mut self, vr: u32) -> Result<f64, Refusal> {
        if self.phase == Phase::Instantiated {
            if let Ok(Var::Parameter(k)) = self.var(vr) {
                return Ok(self.parameters[k]);
            }
        }
        let var = self.var(vr)?;
        if let Var::Parameter(k) = var {
            return Ok(self.parameters[k]);
        }
        if let Var::Input(k) = var {
            if let Some(v) = self.inputs[k] {
                return Ok(v);
            }
        }
        if self.cosim.is_none() {
            if self.phase != Phase::Initialization {
                return Err(error(format!(
                    "value reference {vr} cannot be read before \
                     fmi3EnterInitializationMode"
                )));
            }
            // outputs asked in initialization mode: the model as initialized so far
            self.build()?;
        }
        let Some(c) = self.cosim.as_mut() else {
            return Err(error("the model is not built"));
        };
        Ok(match var {
            Var::Time => c.time(),
            Var::Input(k) => c.inputs().cells()[k].eval(c.time())[0],
            Var::Output(k) => c.outputs()[self.columns[k]],
            Var::Parameter(k) => self.parameters[k],
        })
    }

    /// fmi3SetFloat64 of one value reference.
    ///
    /// # Errors
    /// A value that is not finite, a reference that cannot be set (time, an output), a
    /// parameter after initialization, or a call after termination.
    pub fn set(&mut self, vr: u32, value: f64) -> Result<(), Refusal> {
        if self.phase == Phase::Terminated {
            return Err(error(
                "no value can be set after fmi3Terminate; call fmi3Reset",
            ));
        }
        let var = self.var(vr)?;
        if !value.is_finite() {
            let name = match var {
                Var::Input(k) => self.config.inputs[k].name.clone(),
                Var::Parameter(k) => self.config.parameters[k].path.clone(),
                _ => format!("value reference {vr}"),
            };
            return Err(error(format!(
                "`{name}` was given {value}: values must be finite; the value is not taken"
            )));
        }
        match var {
            Var::Input(k) => {
                self.inputs[k] = Some(value);
                self.dirty[k] = true;
                Ok(())
            }
            Var::Parameter(k) => {
                if !matches!(self.phase, Phase::Instantiated | Phase::Initialization) {
                    return Err(error(format!(
                        "parameter `{}` is fixed: set it before \
                         fmi3ExitInitializationMode",
                        self.config.parameters[k].path
                    )));
                }
                self.parameters[k] = value;
                self.cosim = None;
                Ok(())
            }
            Var::Time => Err(error("time is set by fmi3DoStep, not by fmi3SetFloat64")),
            Var::Output(k) => Err(error(format!(
                "`{}` is an output; it cannot be set",
                self.config.outputs[k].name
            ))),
        }
    }

    /// fmi3DoStep from `t` over `h`; returns the time reached.
    ///
    /// # Errors
    /// Out of order, a step size that is not positive and finite, a `t` that is not the
    /// instance's time, or the run's failure (the time reached is then the last good one).
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<f64, (Refusal, f64)> {
        let now = self.cosim.as_ref().map_or(self.start_time, |c| c.time());
        self.expect(&[Phase::Step], "fmi3DoStep")
            .map_err(|e| (e, now))?;
        if !(h.is_finite() && h > 0.0) {
            return Err((
                error(format!(
                    "the communication step size {h} s must be positive and finite"
                )),
                now,
            ));
        }
        if !t.is_finite() || (t - now).abs() > 1e-9 * now.abs().max(1.0) {
            return Err((
                error(format!(
                    "currentCommunicationPoint {t} s is not the FMU's time {now} s (restore a \
                     saved state to go back)"
                )),
                now,
            ));
        }
        let Some(c) = self.cosim.as_mut() else {
            return Err((error("the model is not built"), now));
        };
        for (k, v) in self.inputs.iter().enumerate() {
            if let (true, Some(v)) = (self.dirty[k], v) {
                c.set_input(k, *v)
                    .map_err(|e| (error(e.to_string()), now))?;
            }
            self.dirty[k] = false;
        }
        match c.advance_to(now + h) {
            Ok(()) => Ok(c.time()),
            Err(e) => Err((error(e.to_string()), c.time())),
        }
    }

    /// fmi3Terminate.
    ///
    /// # Errors
    /// Before initialization.
    pub fn terminate(&mut self) -> Result<(), Refusal> {
        self.expect(&[Phase::Step, Phase::Initialization], "fmi3Terminate")?;
        self.phase = Phase::Terminated;
        Ok(())
    }

    /// fmi3Reset: back to the state after instantiation (parameters and inputs to their start).
    pub fn reset(&mut self) {
        self.phase = Phase::Instantiated;
        self.parameters = self.config.parameters.iter().map(|p| p.start).collect();
        self.inputs.iter_mut().for_each(|v| *v = None);
        self.tolerance = None;
        self.start_time = self.config.experiment[0];
        self.cosim = None;
    }

    /// fmi3GetFMUState.
    ///
    /// # Errors
    /// Before initialization ended.
    pub fn save(&self) -> Result<Saved, Refusal> {
        match &self.cosim {
            Some(c) if self.phase == Phase::Step => Ok(Saved {
                state: c.save(),
                inputs: self.inputs.clone(),
            }),
            _ => Err(error(
                "the FMU state can be saved after fmi3ExitInitializationMode only",
            )),
        }
    }

    /// fmi3SetFMUState.
    ///
    /// # Errors
    /// Before initialization ended, or a state of another model.
    pub fn restore(&mut self, s: &Saved) -> Result<(), Refusal> {
        let Some(c) = self.cosim.as_mut().filter(|_| self.phase == Phase::Step) else {
            return Err(error(
                "an FMU state can be restored after fmi3ExitInitializationMode only",
            ));
        };
        c.restore(&s.state).map_err(|e| error(e.to_string()))?;
        self.inputs.clone_from(&s.inputs);
        self.dirty.iter_mut().for_each(|d| *d = false);
        Ok(())
    }

    fn expect(&self, phases: &[Phase], call: &str) -> Result<(), Refusal> {
        if phases.contains(&self.phase) {
            Ok(())
        } else {
            Err(error(format!(
                "{call} is not allowed in the {:?} state (allowed in {:?})",
                self.phase, phases
            )))
        }
    }
}

impl Saved {
    /// The state as bytes (fmi3SerializeFMUState): time, state vector, inputs.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::new();
        let words = self.state.to_words();
        out.extend_from_slice(&(words.len() as u64).to_le_bytes());
        for w in words {
            out.extend_from_slice(&w.to_le_bytes());
        }
        out.extend_from_slice(&(self.inputs.len() as u64).to_le_bytes());
        for v in &self.inputs {
            let (flag, x): (f64, f64) = v.map_or((0.0, 0.0), |x| (1.0, x));
            out.extend_from_slice(&flag.to_le_bytes());
            out.extend_from_slice(&x.to_le_bytes());
        }
        out
    }

    /// A state read back from [`Saved::to_bytes`].
    ///
    /// # Errors
    /// Bytes that are not such a state.
    pub fn from_bytes(b: &[u8]) -> Result<Saved, Refusal> {
        let bad = || error("the serialized FMU state is damaged or from another FMU");
        let mut words = b
            .chunks_exact(8)
            .map(|c| <[u8; 8]>::try_from(c).map_err(|_| bad()));
        let mut next = || words.next().ok_or_else(bad)?;
        let n = u64::from_le_bytes(next()?) as usize;
        let state_words = (0..n)
            .map(|_| next().map(f64::from_le_bytes))
            .collect::<Result<Vec<_>, _>>()?;
        let ni = u64::from_le_bytes(next()?) as usize;
        let mut inputs = Vec::with_capacity(ni.min(1 << 16));
        for _ in 0..ni {
            let flag = f64::from_le_bytes(next()?);
            let x = f64::from_le_bytes(next()?);
            inputs.push((flag != 0.0).then_some(x));
        }
        if b.len() % 8 != 0 {
            return Err(bad());
        }
        let state = CoSimState::from_words(&state_words).ok_or_else(bad)?;
        Ok(Saved { state, inputs })
    }
}
