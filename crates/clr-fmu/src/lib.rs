//! The runtime of clr's co-simulation FMUs: the FMI 3.0 C functions over one
//! [`instance::Instance`] per `fmi3InstantiateCoSimulation`, and the FMI 2.0 ones ([`fmi2`])
//! over the same instance.
//!
//! The archive (`clr fmu`, [`clr_sim::fmu`]) carries this library as
//! `binaries/x86_64-linux/clr_fmu.so` and the model file with its configuration under
//! `resources/`. Every function checks its pointers and the instance's state, logs what it
//! refuses through the master's callback (status, category `logStatusError`) and returns an FMI
//! status; a panic inside is caught and reported as `fmi3Fatal`, never unwound into the master.
//! Model exchange, scheduled execution, clocks, event mode and derivatives are not provided:
//! their functions exist (masters bind every symbol) and return `fmi3Error` with a message.

#![allow(clippy::missing_safety_doc)]

pub mod fmi2;
pub mod instance;

use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use clr_sim::fmu::{FmuConfig, CONFIG_RESOURCE, MODEL_RESOURCE};
use instance::{Instance, Refusal};

const OK: c_int = 0;
const WARNING: c_int = 1;
const DISCARD: c_int = 2;
const ERROR: c_int = 3;
const FATAL: c_int = 4;

type LogFn = unsafe extern "C" fn(*mut c_void, c_int, *const c_char, *const c_char);

/// An instance with the master's logger.
struct Fmu {
    inst: Instance,
    log: Option<LogFn>,
    env: *mut c_void,
    logging_on: bool,
}

impl Fmu {
    fn log(&self, status: c_int, message: &str) {
        if status == OK && !self.logging_on {
            return;
        }
        log_with(self.log, self.env, status, message);
    }

    /// The status of `r`, logging a refusal.
    fn status<T>(&self, r: Result<T, Refusal>) -> c_int {
        match r {
            Ok(_) => OK,
            Err(e) => {
                let s = if e.error { ERROR } else { DISCARD };
                self.log(s, &e.message);
                s
            }
        }
    }
}

fn log_with(log: Option<LogFn>, env: *mut c_void, status: c_int, message: &str) {
    let Some(f) = log else { return };
    let category = match status {
        OK => c"logInfo",
        WARNING => c"logStatusWarning",
        _ => c"logStatusError",
    };
    let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
    // SAFETY: the master's callback with NUL-terminated strings that outlive the call
    unsafe { f(env, status, category.as_ptr(), text.as_ptr()) };
}

/// Run `f` on the instance behind `ptr`, catching panics (fmi3Fatal).
fn with(ptr: *mut c_void, f: impl FnOnce(&mut Fmu) -> c_int) -> c_int {
    if ptr.is_null() {
        return ERROR;
    }
    // SAFETY: a non-null instance pointer is one fmi3InstantiateCoSimulation returned
    let fmu = unsafe { &mut *ptr.cast::<Fmu>() };
    let (log, env) = (fmu.log, fmu.env);
    match catch_unwind(AssertUnwindSafe(|| f(fmu))) {
        Ok(s) => s,
        Err(_) => {
            log_with(
                log,
                env,
                FATAL,
                "internal error (a panic in clr); please report it",
            );
            FATAL
        }
    }
}

pub(crate) unsafe fn str_arg<'a>(p: *const c_char) -> Option<&'a str> {
    if p.is_null() {
        None
    } else {
        // SAFETY: the master passes NUL-terminated strings
        unsafe { CStr::from_ptr(p) }.to_str().ok()
    }
}

/// The FMI version string.
#[no_mangle]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    c"3.0".as_ptr()
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetDebugLogging(
    instance: *mut c_void,
    logging_on: bool,
    _n: usize,
    _categories: *const *const c_char,
) -> c_int {
    with(instance, |f| {
        f.logging_on = logging_on;
        OK
    })
}

pub(crate) fn load(resource_path: &str, token: &str) -> Result<Instance, String> {
    let dir = Path::new(resource_path);
    let read = |name: &str| {
        std::fs::read_to_string(dir.join(name))
            .map_err(|e| format!("cannot read {}: {e}", dir.join(name).display()))
    };
    let config: FmuConfig = serde_json::from_str(&read(CONFIG_RESOURCE)?)
        .map_err(|e| format!("{CONFIG_RESOURCE} is damaged: {e}"))?;
    Instance::new(config, read(MODEL_RESOURCE)?, token).map_err(|e| e.message)
}

/// A resource path may come as a `file://` URI from masters written for FMI 2.0.
fn resource_dir(p: &str) -> String {
    p.strip_prefix("file://")
        .map_or_else(|| p.to_string(), str::to_string)
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
    _instance_name: *const c_char,
    token: *const c_char,
    resource_path: *const c_char,
    _visible: bool,
    logging_on: bool,
    _event_mode_used: bool,
    _early_return_allowed: bool,
    _required: *const u32,
    _n_required: usize,
    env: *mut c_void,
    log: Option<LogFn>,
    _intermediate_update: *const c_void,
) -> *mut c_void {
    let made = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: strings from the master
        let (token, res) = unsafe { (str_arg(token), str_arg(resource_path)) };
        let (Some(token), Some(res)) = (token, res) else {
            return Err("the instantiation token and the resource path must be given".into());
        };
        load(&resource_dir(res), token)
    }));
    match made {
        Ok(Ok(inst)) => {
            let fmu = Fmu {
                inst,
                log,
                env,
                logging_on,
            };
            Box::into_raw(Box::new(fmu)).cast()
        }
        Ok(Err(m)) => {
            log_with(log, env, ERROR, &m);
            std::ptr::null_mut()
        }
        Err(_) => {
            log_with(
                log,
                env,
                FATAL,
                "internal error while instantiating; please report it",
            );
            std::ptr::null_mut()
        }
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3FreeInstance(instance: *mut c_void) {
    if !instance.is_null() {
        // SAFETY: the pointer fmi3InstantiateCoSimulation returned, freed once
        drop(unsafe { Box::from_raw(instance.cast::<Fmu>()) });
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3EnterInitializationMode(
    instance: *mut c_void,
    tolerance_defined: bool,
    tolerance: f64,
    start_time: f64,
    _stop_time_defined: bool,
    _stop_time: f64,
) -> c_int {
    with(instance, |f| {
        let r = f
            .inst
            .enter_initialization(tolerance_defined.then_some(tolerance), start_time);
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3ExitInitializationMode(instance: *mut c_void) -> c_int {
    with(instance, |f| {
        let r = f.inst.exit_initialization();
        let s = f.status(r);
        if s == OK {
            for n in f.inst.notes() {
                f.log(OK, &n);
            }
        }
        s
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3Terminate(instance: *mut c_void) -> c_int {
    with(instance, |f| {
        let r = f.inst.terminate();
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3Reset(instance: *mut c_void) -> c_int {
    with(instance, |f| {
        f.inst.reset();
        OK
    })
}

/// Get and set arrays of Float64 (FMI 3.0) or Real (FMI 2.0) values.
pub(crate) mod values {
    use crate::instance::{Instance, Refusal};

    fn null() -> Refusal {
        Refusal {
            error: true,
            message: "a null value-reference or value array".into(),
        }
    }

    /// The values of `nvr` references into `out`.
    pub(crate) unsafe fn get(
        inst: &mut Instance,
        vr: *const u32,
        nvr: usize,
        out: *mut f64,
    ) -> Result<(), Refusal> {
        if nvr > 0 && (vr.is_null() || out.is_null()) {
            return Err(null());
        }
        for k in 0..nvr {
            // SAFETY: arrays of nvr entries, checked non-null above
            unsafe { *out.add(k) = inst.get(*vr.add(k))? };
        }
        Ok(())
    }

    /// Set `nvr` references to `values`, stopping at the first refused.
    pub(crate) unsafe fn set(
        inst: &mut Instance,
        vr: *const u32,
        nvr: usize,
        values: *const f64,
    ) -> Result<(), Refusal> {
        if nvr > 0 && (vr.is_null() || values.is_null()) {
            return Err(null());
        }
        for k in 0..nvr {
            // SAFETY: arrays of nvr entries, checked non-null above
            unsafe { inst.set(*vr.add(k), *values.add(k))? };
        }
        Ok(())
    }
}

/// FMI 3.0 passes the number of values as well: one per reference (every variable a scalar).
fn scalars(f: &Fmu, nvr: usize, n: usize) -> bool {
    if n != nvr {
        f.log(
            ERROR,
            &format!("{n} values for {nvr} value references: every variable is a scalar"),
        );
    }
    n == nvr
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetFloat64(
    instance: *mut c_void,
    vr: *const u32,
    nvr: usize,
    values: *mut f64,
    n: usize,
) -> c_int {
    with(instance, |f| {
        if !scalars(f, nvr, n) {
            return ERROR;
        }
        // SAFETY: the master's arrays, checked inside
        let r = unsafe { values::get(&mut f.inst, vr, nvr, values) };
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetFloat64(
    instance: *mut c_void,
    vr: *const u32,
    nvr: usize,
    values: *const f64,
    n: usize,
) -> c_int {
    with(instance, |f| {
        if !scalars(f, nvr, n) {
            return ERROR;
        }
        // SAFETY: the master's arrays, checked inside
        let r = unsafe { values::set(&mut f.inst, vr, nvr, values) };
        f.status(r)
    })
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn fmi3DoStep(
    instance: *mut c_void,
    current: f64,
    step: f64,
    _no_set_prior: bool,
    event_handling_needed: *mut bool,
    terminate: *mut bool,
    early_return: *mut bool,
    last_successful_time: *mut f64,
) -> c_int {
    with(instance, |f| {
        let put = |p: *mut bool| {
            if !p.is_null() {
                // SAFETY: the master's output argument
                unsafe { *p = false };
            }
        };
        put(event_handling_needed);
        put(terminate);
        put(early_return);
        let (s, t) = match f.inst.do_step(current, step) {
            Ok(t) => (OK, t),
            Err((e, t)) => (f.status::<()>(Err(e)), t),
        };
        if !last_successful_time.is_null() {
            // SAFETY: the master's output argument
            unsafe { *last_successful_time = t };
        }
        s
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3EnterStepMode(instance: *mut c_void) -> c_int {
    with(instance, |f| {
        f.log(ERROR, "fmi3EnterStepMode: this FMU has no event mode");
        ERROR
    })
}

/// The FMU-state functions of both FMI versions, over the instance and raw pointers; each
/// refusal says which call and what was wrong.
pub(crate) mod state {
    use std::ffi::c_void;

    use crate::instance::{Instance, Refusal, Saved};

    fn null(call: &str) -> Refusal {
        Refusal {
            error: true,
            message: format!("{call}: a null pointer argument"),
        }
    }

    /// Save the instance into `*state` (a state already there is freed: FMI lets the FMU
    /// reuse it).
    pub(crate) unsafe fn get(inst: &Instance, state: *mut *mut c_void) -> Result<(), Refusal> {
        if state.is_null() {
            return Err(null("get FMU state"));
        }
        let s = inst.save()?;
        // SAFETY: the master's output argument, holding null or a state this FMU made
        unsafe {
            free(state);
            *state = Box::into_raw(Box::new(s)).cast();
        }
        Ok(())
    }

    /// Restore the instance from a state this FMU made.
    pub(crate) unsafe fn set(inst: &mut Instance, state: *mut c_void) -> Result<(), Refusal> {
        if state.is_null() {
            return Err(null("set FMU state"));
        }
        // SAFETY: a state fmi*GetFMUState or fmi*DeserializeFMUState returned
        inst.restore(unsafe { &*state.cast::<Saved>() })
    }

    /// Free `*state` and null it.
    pub(crate) unsafe fn free(state: *mut *mut c_void) {
        if state.is_null() {
            return;
        }
        // SAFETY: the master's pointer to null or a state this FMU made
        unsafe {
            if !(*state).is_null() {
                drop(Box::from_raw((*state).cast::<Saved>()));
            }
            *state = std::ptr::null_mut();
        }
    }

    /// The serialized size of a state.
    pub(crate) unsafe fn size(state: *mut c_void, size: *mut usize) -> Result<(), Refusal> {
        if state.is_null() || size.is_null() {
            return Err(null("serialized FMU state size"));
        }
        // SAFETY: a state this FMU made; the master's output argument
        unsafe { *size = (*state.cast::<Saved>()).to_bytes().len() };
        Ok(())
    }

    /// Write a state into the master's buffer of `size` bytes.
    pub(crate) unsafe fn serialize(
        state: *mut c_void,
        bytes: *mut u8,
        size: usize,
    ) -> Result<(), Refusal> {
        if state.is_null() || bytes.is_null() {
            return Err(null("serialize FMU state"));
        }
        // SAFETY: a state this FMU made
        let b = unsafe { (*state.cast::<Saved>()).to_bytes() };
        if b.len() != size {
            return Err(Refusal {
                error: true,
                message: format!("the buffer holds {size} bytes; the state needs {}", b.len()),
            });
        }
        // SAFETY: the master's buffer of `size` bytes
        unsafe { std::ptr::copy_nonoverlapping(b.as_ptr(), bytes, size) };
        Ok(())
    }

    /// Read a state from `size` bytes into `*state`.
    pub(crate) unsafe fn deserialize(
        bytes: *const u8,
        size: usize,
        state: *mut *mut c_void,
    ) -> Result<(), Refusal> {
        if bytes.is_null() || state.is_null() {
            return Err(null("deserialize FMU state"));
        }
        // SAFETY: the master's buffer of `size` bytes
        let s = Saved::from_bytes(unsafe { std::slice::from_raw_parts(bytes, size) })?;
        // SAFETY: the master's output argument
        unsafe { *state = Box::into_raw(Box::new(s)).cast() };
        Ok(())
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetFMUState(instance: *mut c_void, state: *mut *mut c_void) -> c_int {
    with(instance, |f| {
        // SAFETY: the master's arguments, checked inside
        let r = unsafe { state::get(&f.inst, state) };
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetFMUState(instance: *mut c_void, state: *mut c_void) -> c_int {
    with(instance, |f| {
        // SAFETY: the master's arguments, checked inside
        let r = unsafe { state::set(&mut f.inst, state) };
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3FreeFMUState(instance: *mut c_void, state: *mut *mut c_void) -> c_int {
    // SAFETY: the master's arguments, checked inside
    with(instance, |_| unsafe {
        state::free(state);
        OK
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SerializedFMUStateSize(
    instance: *mut c_void,
    state: *mut c_void,
    size: *mut usize,
) -> c_int {
    with(instance, |f| {
        // SAFETY: the master's arguments, checked inside
        let r = unsafe { state::size(state, size) };
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SerializeFMUState(
    instance: *mut c_void,
    state: *mut c_void,
    bytes: *mut u8,
    size: usize,
) -> c_int {
    with(instance, |f| {
        // SAFETY: the master's arguments, checked inside
        let r = unsafe { state::serialize(state, bytes, size) };
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3DeserializeFMUState(
    instance: *mut c_void,
    bytes: *const u8,
    size: usize,
    state: *mut *mut c_void,
) -> c_int {
    with(instance, |f| {
        // SAFETY: the master's arguments, checked inside
        let r = unsafe { state::deserialize(bytes, size, state) };
        f.status(r)
    })
}

/// Functions of variable types this FMU has none of: fine for zero references, an error else.
macro_rules! no_variables_of_type {
    ($($name:ident),* $(,)?) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            instance: *mut c_void,
            _vr: *const u32,
            nvr: usize,
            _values: *mut c_void,
            _n: usize,
        ) -> c_int {
            with(instance, |f| {
                if nvr == 0 {
                    return OK;
                }
                f.log(ERROR, concat!(stringify!($name), ": this FMU has Float64 variables only"));
                ERROR
            })
        }
    )*};
}

no_variables_of_type!(
    fmi3GetFloat32,
    fmi3GetInt8,
    fmi3GetUInt8,
    fmi3GetInt16,
    fmi3GetUInt16,
    fmi3GetInt32,
    fmi3GetUInt32,
    fmi3GetInt64,
    fmi3GetUInt64,
    fmi3GetBoolean,
    fmi3GetString,
    fmi3SetFloat32,
    fmi3SetInt8,
    fmi3SetUInt8,
    fmi3SetInt16,
    fmi3SetUInt16,
    fmi3SetInt32,
    fmi3SetUInt32,
    fmi3SetInt64,
    fmi3SetUInt64,
    fmi3SetBoolean,
    fmi3SetString,
    fmi3GetClock,
    fmi3SetClock,
);

/// Binary variables carry a size array as well.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetBinary(
    instance: *mut c_void,
    _vr: *const u32,
    nvr: usize,
    _sizes: *mut usize,
    _values: *mut c_void,
    _n: usize,
) -> c_int {
    with(instance, |f| {
        if nvr == 0 {
            return OK;
        }
        f.log(ERROR, "fmi3GetBinary: this FMU has Float64 variables only");
        ERROR
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetBinary(
    instance: *mut c_void,
    _vr: *const u32,
    nvr: usize,
    _sizes: *const usize,
    _values: *const c_void,
    _n: usize,
) -> c_int {
    with(instance, |f| {
        if nvr == 0 {
            return OK;
        }
        f.log(ERROR, "fmi3SetBinary: this FMU has Float64 variables only");
        ERROR
    })
}

/// Functions of interfaces this FMU does not provide: an error with a message. The instance is
/// always the first argument; the others are ignored (the C calling convention lets a callee
/// ignore trailing arguments).
macro_rules! not_provided {
    ($($name:ident),* $(,)?) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $name(instance: *mut c_void) -> c_int {
            with(instance, |f| {
                f.log(ERROR, concat!(
                    stringify!($name),
                    ": not provided by this co-simulation FMU (no model exchange, scheduled \
                     execution, clocks, event mode or derivatives)"
                ));
                ERROR
            })
        }
    )*};
}

not_provided!(
    fmi3EnterEventMode,
    fmi3GetNumberOfVariableDependencies,
    fmi3GetVariableDependencies,
    fmi3GetDirectionalDerivative,
    fmi3GetAdjointDerivative,
    fmi3EnterConfigurationMode,
    fmi3ExitConfigurationMode,
    fmi3GetIntervalDecimal,
    fmi3GetIntervalFraction,
    fmi3GetShiftDecimal,
    fmi3GetShiftFraction,
    fmi3SetIntervalDecimal,
    fmi3SetIntervalFraction,
    fmi3SetShiftDecimal,
    fmi3SetShiftFraction,
    fmi3EvaluateDiscreteStates,
    fmi3UpdateDiscreteStates,
    fmi3EnterContinuousTimeMode,
    fmi3CompletedIntegratorStep,
    fmi3SetTime,
    fmi3SetContinuousStates,
    fmi3GetContinuousStateDerivatives,
    fmi3GetEventIndicators,
    fmi3GetContinuousStates,
    fmi3GetNominalsOfContinuousStates,
    fmi3GetNumberOfEventIndicators,
    fmi3GetNumberOfContinuousStates,
    fmi3GetOutputDerivatives,
    fmi3ActivateModelPartition,
);

/// Other interface types: no instance is made.
#[no_mangle]
pub extern "C" fn fmi3InstantiateModelExchange() -> *mut c_void {
    std::ptr::null_mut()
}

/// Other interface types: no instance is made.
#[no_mangle]
pub extern "C" fn fmi3InstantiateScheduledExecution() -> *mut c_void {
    std::ptr::null_mut()
}
