//! The runtime of clr's co-simulation FMUs: the FMI 3.0 C functions over one
//! [`instance::Instance`] per `fmi3InstantiateCoSimulation`.
//!
//! The archive (`clr fmu`, [`clr_sim::fmu`]) carries this library as
//! `binaries/x86_64-linux/clr_fmu.so` and the model file with its configuration under
//! `resources/`. Every function checks its pointers and the instance's state, logs what it
//! refuses through the master's callback (status, category `logStatusError`) and returns an FMI
//! status; a panic inside is caught and reported as `fmi3Fatal`, never unwound into the master.
//! Model exchange, scheduled execution, clocks, event mode and derivatives are not provided:
//! their functions exist (masters bind every symbol) and return `fmi3Error` with a message.

#![allow(clippy::missing_safety_doc)]

pub mod instance;

use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use clr_sim::fmu::{FmuConfig, CONFIG_RESOURCE, MODEL_RESOURCE};
use instance::{Instance, Refusal, Saved};

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

unsafe fn str_arg<'a>(p: *const c_char) -> Option<&'a str> {
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

fn load(resource_path: &str, token: &str) -> Result<Instance, String> {
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

/// Check the array arguments of a get or set call.
fn arrays_ok(f: &Fmu, vr: *const u32, nvr: usize, values: *const c_void, n: usize) -> bool {
    if nvr > 0 && (vr.is_null() || values.is_null()) {
        f.log(ERROR, "null value-reference or value array");
        return false;
    }
    if n != nvr {
        f.log(
            ERROR,
            &format!("{n} values for {nvr} value references: every variable is a scalar"),
        );
        return false;
    }
    true
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
        if !arrays_ok(f, vr, nvr, values.cast(), n) {
            return ERROR;
        }
        for k in 0..nvr {
            // SAFETY: arrays of nvr entries, checked non-null above
            let r = unsafe { *vr.add(k) };
            match f.inst.get(r) {
                Ok(v) => unsafe { *values.add(k) = v },
                Err(e) => return f.status::<()>(Err(e)),
            }
        }
        OK
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
        if !arrays_ok(f, vr, nvr, values.cast(), n) {
            return ERROR;
        }
        for k in 0..nvr {
            // SAFETY: arrays of nvr entries, checked non-null above
            let (r, v) = unsafe { (*vr.add(k), *values.add(k)) };
            let r = f.inst.set(r, v);
            let s = f.status(r);
            if s != OK {
                return s;
            }
        }
        OK
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

#[no_mangle]
pub unsafe extern "C" fn fmi3GetFMUState(instance: *mut c_void, state: *mut *mut c_void) -> c_int {
    with(instance, |f| {
        if state.is_null() {
            f.log(ERROR, "fmi3GetFMUState: null state pointer");
            return ERROR;
        }
        match f.inst.save() {
            Ok(s) => {
                // SAFETY: the master's output argument; a previous state there is replaced
                // (FMI: the FMU may reuse it), so free it first
                unsafe {
                    let old = *state;
                    if !old.is_null() {
                        drop(Box::from_raw(old.cast::<Saved>()));
                    }
                    *state = Box::into_raw(Box::new(s)).cast();
                }
                OK
            }
            Err(e) => f.status::<()>(Err(e)),
        }
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetFMUState(instance: *mut c_void, state: *mut c_void) -> c_int {
    with(instance, |f| {
        if state.is_null() {
            f.log(ERROR, "fmi3SetFMUState: null state");
            return ERROR;
        }
        // SAFETY: a state fmi3GetFMUState or fmi3DeserializeFMUState returned
        let s = unsafe { &*state.cast::<Saved>() };
        let r = f.inst.restore(s);
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3FreeFMUState(instance: *mut c_void, state: *mut *mut c_void) -> c_int {
    with(instance, |_| {
        if !state.is_null() {
            // SAFETY: the master's pointer to a state this FMU made; set to null after
            unsafe {
                if !(*state).is_null() {
                    drop(Box::from_raw((*state).cast::<Saved>()));
                }
                *state = std::ptr::null_mut();
            }
        }
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
        if state.is_null() || size.is_null() {
            f.log(ERROR, "fmi3SerializedFMUStateSize: null argument");
            return ERROR;
        }
        // SAFETY: a state this FMU made; the master's output argument
        unsafe { *size = (*state.cast::<Saved>()).to_bytes().len() };
        OK
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
        if state.is_null() || bytes.is_null() {
            f.log(ERROR, "fmi3SerializeFMUState: null argument");
            return ERROR;
        }
        // SAFETY: a state this FMU made
        let b = unsafe { (*state.cast::<Saved>()).to_bytes() };
        if b.len() != size {
            f.log(
                ERROR,
                &format!("the buffer holds {size} bytes; the state needs {}", b.len()),
            );
            return ERROR;
        }
        // SAFETY: the master's buffer of `size` bytes
        unsafe { std::ptr::copy_nonoverlapping(b.as_ptr(), bytes, size) };
        OK
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
        if bytes.is_null() || state.is_null() {
            f.log(ERROR, "fmi3DeserializeFMUState: null argument");
            return ERROR;
        }
        // SAFETY: the master's buffer of `size` bytes
        let b = unsafe { std::slice::from_raw_parts(bytes, size) };
        match Saved::from_bytes(b) {
            Ok(s) => {
                // SAFETY: the master's output argument
                unsafe { *state = Box::into_raw(Box::new(s)).cast() };
                OK
            }
            Err(e) => f.status::<()>(Err(e)),
        }
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
