//! The FMI 2.0 co-simulation functions over the same [`Instance`] as the FMI 3.0 ones: an FMU
//! written with `clr fmu --fmi-version 2` carries this library and an FMI 2.0 model
//! description. The differences to 3.0 are in the C signatures only (an `fmi2Boolean` is an
//! `int`, the logger is a printf-style callback in a callback struct, the resources come as a
//! `file://` URI, `fmi2SetupExperiment` gives the tolerance and start time).

use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::instance::{Instance, Refusal};

const OK: c_int = 0;
const WARNING: c_int = 1;
const DISCARD: c_int = 2;
const ERROR: c_int = 3;
const FATAL: c_int = 4;

type Logger =
    unsafe extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char, ...);

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct Callbacks {
    logger: Option<Logger>,
    allocate: *const c_void,
    free: *const c_void,
    step_finished: *const c_void,
    env: *mut c_void,
}

struct Fmu2 {
    inst: Instance,
    logger: Option<Logger>,
    env: *mut c_void,
    name: CString,
    logging_on: bool,
    tolerance: Option<f64>,
    start: f64,
}

impl Fmu2 {
    fn log(&self, status: c_int, message: &str) {
        if status == OK && !self.logging_on {
            return;
        }
        log_with(self.logger, self.env, &self.name, status, message);
    }

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

fn log_with(logger: Option<Logger>, env: *mut c_void, name: &CStr, status: c_int, message: &str) {
    let Some(f) = logger else { return };
    let category = match status {
        OK => c"logInfo",
        WARNING => c"logStatusWarning",
        _ => c"logStatusError",
    };
    // the logger formats like printf: a literal % is written %%
    let text = CString::new(message.replace('\0', " ").replace('%', "%%")).unwrap_or_default();
    // SAFETY: the master's logger with NUL-terminated strings that outlive the call
    unsafe { f(env, name.as_ptr(), status, category.as_ptr(), text.as_ptr()) };
}

fn with(ptr: *mut c_void, f: impl FnOnce(&mut Fmu2) -> c_int) -> c_int {
    if ptr.is_null() {
        return ERROR;
    }
    // SAFETY: a non-null component is one fmi2Instantiate returned
    let fmu = unsafe { &mut *ptr.cast::<Fmu2>() };
    let (logger, env, name) = (fmu.logger, fmu.env, fmu.name.clone());
    match catch_unwind(AssertUnwindSafe(|| f(fmu))) {
        Ok(s) => s,
        Err(_) => {
            log_with(
                logger,
                env,
                &name,
                FATAL,
                "internal error (a panic in clr); please report it",
            );
            FATAL
        }
    }
}

/// The directory of a `file://` URI (percent-escapes decoded).
fn uri_to_path(uri: &str) -> String {
    let p = uri
        .strip_prefix("file://localhost")
        .or_else(|| uri.strip_prefix("file://"))
        .or_else(|| uri.strip_prefix("file:"))
        .unwrap_or(uri);
    let b = p.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%' && i + 2 < b.len() {
            if let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2])) {
                out.push((h * 16 + l) as u8);
                i += 3;
                continue;
            }
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: *mut c_void,
    logging_on: c_int,
    _n: usize,
    _categories: *const *const c_char,
) -> c_int {
    with(c, |f| {
        f.logging_on = logging_on != 0;
        OK
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    name: *const c_char,
    fmu_type: c_int,
    guid: *const c_char,
    resources: *const c_char,
    callbacks: *const Callbacks,
    _visible: c_int,
    logging_on: c_int,
) -> *mut c_void {
    // SAFETY: the master's callback struct, read once
    let (logger, env) = if callbacks.is_null() {
        (None, std::ptr::null_mut())
    } else {
        unsafe { ((*callbacks).logger, (*callbacks).env) }
    };
    // SAFETY: strings from the master
    let text = |p: *const c_char| unsafe { crate::str_arg(p) }.map(str::to_string);
    let inst_name = CString::new(text(name).unwrap_or_default()).unwrap_or_default();
    let made = catch_unwind(AssertUnwindSafe(|| {
        if fmu_type != 1 {
            return Err("this FMU is for co-simulation (fmi2CoSimulation) only".to_string());
        }
        let (Some(guid), Some(res)) = (text(guid), text(resources)) else {
            return Err("the GUID and the resource location must be given".into());
        };
        crate::load(&uri_to_path(&res), &guid)
    }));
    match made {
        Ok(Ok(inst)) => {
            let start = inst.start_time();
            let fmu = Fmu2 {
                inst,
                logger,
                env,
                name: inst_name,
                logging_on: logging_on != 0,
                tolerance: None,
                start,
            };
            Box::into_raw(Box::new(fmu)).cast()
        }
        Ok(Err(m)) => {
            log_with(logger, env, &inst_name, ERROR, &m);
            std::ptr::null_mut()
        }
        Err(_) => {
            log_with(
                logger,
                env,
                &inst_name,
                FATAL,
                "internal error while instantiating",
            );
            std::ptr::null_mut()
        }
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: *mut c_void) {
    if !c.is_null() {
        // SAFETY: the component fmi2Instantiate returned, freed once
        drop(unsafe { Box::from_raw(c.cast::<Fmu2>()) });
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: *mut c_void,
    tolerance_defined: c_int,
    tolerance: f64,
    start: f64,
    _stop_defined: c_int,
    _stop: f64,
) -> c_int {
    with(c, |f| {
        f.tolerance = (tolerance_defined != 0).then_some(tolerance);
        f.start = start;
        OK
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: *mut c_void) -> c_int {
    with(c, |f| {
        let r = f.inst.enter_initialization(f.tolerance, f.start);
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: *mut c_void) -> c_int {
    with(c, |f| {
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
pub unsafe extern "C" fn fmi2Terminate(c: *mut c_void) -> c_int {
    with(c, |f| {
        let r = f.inst.terminate();
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: *mut c_void) -> c_int {
    with(c, |f| {
        f.inst.reset();
        OK
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(
    c: *mut c_void,
    vr: *const u32,
    nvr: usize,
    values: *mut f64,
) -> c_int {
    with(c, |f| {
        // SAFETY: the master's arrays, checked inside
        let r = unsafe { crate::values::get(&mut f.inst, vr, nvr, values) };
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetReal(
    c: *mut c_void,
    vr: *const u32,
    nvr: usize,
    values: *const f64,
) -> c_int {
    with(c, |f| {
        // SAFETY: the master's arrays, checked inside
        let r = unsafe { crate::values::set(&mut f.inst, vr, nvr, values) };
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(
    c: *mut c_void,
    current: f64,
    step: f64,
    _no_set_prior: c_int,
) -> c_int {
    with(c, |f| match f.inst.do_step(current, step) {
        Ok(_) => OK,
        Err((e, _)) => f.status::<()>(Err(e)),
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(c: *mut c_void, state: *mut *mut c_void) -> c_int {
    with(c, |f| {
        // SAFETY: the master's arguments, checked inside
        let r = unsafe { crate::state::get(&f.inst, state) };
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: *mut c_void, state: *mut c_void) -> c_int {
    with(c, |f| {
        // SAFETY: the master's arguments, checked inside
        let r = unsafe { crate::state::set(&mut f.inst, state) };
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(c: *mut c_void, state: *mut *mut c_void) -> c_int {
    // SAFETY: the master's arguments, checked inside
    with(c, |_| unsafe {
        crate::state::free(state);
        OK
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: *mut c_void,
    state: *mut c_void,
    size: *mut usize,
) -> c_int {
    with(c, |f| {
        // SAFETY: the master's arguments, checked inside
        let r = unsafe { crate::state::size(state, size) };
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: *mut c_void,
    state: *mut c_void,
    bytes: *mut u8,
    size: usize,
) -> c_int {
    with(c, |f| {
        // SAFETY: the master's arguments, checked inside
        let r = unsafe { crate::state::serialize(state, bytes, size) };
        f.status(r)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: *mut c_void,
    bytes: *const u8,
    size: usize,
    state: *mut *mut c_void,
) -> c_int {
    with(c, |f| {
        // SAFETY: the master's arguments, checked inside
        let r = unsafe { crate::state::deserialize(bytes, size, state) };
        f.status(r)
    })
}

/// Functions of types and interfaces this FMU does not have: fine for zero references (get
/// and set of other types), an error with a message otherwise.
macro_rules! fmi2_not_provided {
    ($($name:ident),* $(,)?) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $name(c: *mut c_void, _a: *const c_void, n: usize) -> c_int {
            with(c, |f| {
                if n == 0 && stringify!($name).contains("Integer")
                    || n == 0 && stringify!($name).contains("Boolean")
                    || n == 0 && stringify!($name).contains("String")
                {
                    return OK;
                }
                f.log(ERROR, concat!(
                    stringify!($name),
                    ": not provided by this co-simulation FMU (Real variables only; no model \
                     exchange, input or output derivatives, asynchronous steps or status queries)"
                ));
                ERROR
            })
        }
    )*};
}

fmi2_not_provided!(
    fmi2GetInteger,
    fmi2GetBoolean,
    fmi2GetString,
    fmi2SetInteger,
    fmi2SetBoolean,
    fmi2SetString,
    fmi2GetDirectionalDerivative,
    fmi2SetRealInputDerivatives,
    fmi2GetRealOutputDerivatives,
    fmi2CancelStep,
    fmi2GetStatus,
    fmi2GetRealStatus,
    fmi2GetIntegerStatus,
    fmi2GetBooleanStatus,
    fmi2GetStringStatus,
    fmi2EnterEventMode,
    fmi2NewDiscreteStates,
    fmi2EnterContinuousTimeMode,
    fmi2CompletedIntegratorStep,
    fmi2SetTime,
    fmi2SetContinuousStates,
    fmi2GetDerivatives,
    fmi2GetEventIndicators,
    fmi2GetContinuousStates,
    fmi2GetNominalsOfContinuousStates,
);

#[cfg(test)]
mod tests {
    #[test]
    fn resource_uris_become_paths() {
        assert_eq!(
            super::uri_to_path("file:///tmp/a%20b/resources"),
            "/tmp/a b/resources"
        );
        assert_eq!(super::uri_to_path("file://localhost/x/"), "/x/");
        assert_eq!(super::uri_to_path("/plain/path"), "/plain/path");
        assert_eq!(super::uri_to_path("file:///x%2"), "/x%2");
    }
}
