//! Status codes, the thread-local last-error message and the panic guard of the C boundary.

use std::cell::RefCell;
use std::ffi::{c_char, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

use clr_contact::ContactError;

/// Result of every fallible C function. `CLR_STATUS_OK` (0) is success; on any other value the
/// output arguments are left untouched (the one exception: `CLR_STATUS_BUFFER_TOO_SMALL` writes
/// the count needed through the count argument) and `clr_last_error_message()` says what to
/// change.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClrStatus {
    /// Success.
    Ok = 0,
    /// A required pointer argument was NULL.
    NullPointer = 1,
    /// A numeric input (state, velocity, force) was NaN or infinite.
    NonFinite = 2,
    /// A kind code, a parameter count, an array length, a 0/1 flag or a string argument was not
    /// valid.
    InvalidArgument = 3,
    /// A law parameter is out of its admissible range (e.g. c_e outside (0, 1], E ≤ 0).
    InvalidParameter = 4,
    /// A preset, damping factor or kind name is not known.
    UnknownName = 5,
    /// An input lies outside the validity range of an empirical law (Pereira's clearance range).
    OutOfValidity = 6,
    /// An iterative solve inside a law did not converge.
    NoConvergence = 7,
    /// An internal panic was caught at the boundary (a bug: please report the message).
    Panic = 8,
    /// A model file could not be read or built, or a model was used before its first run (the
    /// message gives the line and field).
    ModelError = 9,
    /// The solver failed during `clr_model_run`; the rows recorded up to the failure are kept.
    SimulationFailed = 10,
    /// A caller-supplied output buffer holds fewer entries than the result: nothing was copied
    /// and the count argument received the number of entries needed.
    BufferTooSmall = 11,
}

/// Everything that can fail at the C boundary.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CapiError {
    /// A law rejected its parameters or inputs.
    #[error(transparent)]
    Contact(#[from] ContactError),
    /// A required pointer was NULL.
    #[error("argument `{0}` is a NULL pointer; pass a valid pointer")]
    Null(&'static str),
    /// A numeric input was NaN or infinite.
    #[error("argument `{name}` = {value} is not finite; pass a finite number")]
    NonFinite {
        /// Argument name with its unit.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A kind code without a kind.
    #[error("unknown {what} code {code}; valid codes are 0..={max} (see clr_contact.h)")]
    UnknownCode {
        /// What the code selects.
        what: &'static str,
        /// The code given.
        code: u32,
        /// Largest valid code.
        max: usize,
    },
    /// A kind name without a kind.
    #[error("unknown {what} `{name}`; valid names: {valid}")]
    UnknownName {
        /// What the name selects.
        what: &'static str,
        /// The name given.
        name: String,
        /// Comma-separated valid names.
        valid: String,
    },
    /// A parameter list of the wrong length.
    #[error("{law} takes {expected} parameter(s) ({names}), got {got}")]
    ParameterCount {
        /// Law name.
        law: &'static str,
        /// Number expected.
        expected: usize,
        /// Parameter names with units, in order.
        names: String,
        /// Number given.
        got: usize,
    },
    /// A C string that is not UTF-8.
    #[error("argument `{0}` is not valid UTF-8; pass an ASCII name such as \"LN\"")]
    Utf8(&'static str),
    /// An input array of the wrong length.
    #[error("argument `{name}` has {got} entries; pass {expected} ({what})")]
    ArrayLength {
        /// Argument name.
        name: &'static str,
        /// What the entries are and where the expected count comes from.
        what: &'static str,
        /// Number of entries expected.
        expected: usize,
        /// Number given.
        got: usize,
    },
    /// A 0/1 flag with another value.
    #[error("argument `{name}` = {value} must be 0 or 1 ({meaning})")]
    Flag {
        /// Argument name.
        name: &'static str,
        /// What 1 means.
        meaning: &'static str,
        /// The value given.
        value: i64,
    },
    /// A caller-supplied output buffer too small for the result.
    #[error(
        "argument `{name}` has room for {capacity} entries but {needed} are needed; nothing was \
         copied: pass a buffer of at least {needed} entries (the count argument holds it)"
    )]
    BufferTooSmall {
        /// Argument name.
        name: &'static str,
        /// Entries needed.
        needed: usize,
        /// Capacity given.
        capacity: usize,
    },
    /// A model file that cannot be loaded, built or run, or a model not run yet.
    #[error("{0}")]
    Model(String),
    /// The solver failed during a model run.
    #[error("simulation failed: {0}")]
    Simulation(String),
    /// A panic caught at the boundary.
    #[error("internal error (caught panic: {0}); please report it with the inputs that caused it")]
    Panic(String),
}

impl CapiError {
    /// The status code of this error.
    pub fn status(&self) -> ClrStatus {
        match self {
            CapiError::Contact(ContactError::InvalidParameter { .. }) => {
                ClrStatus::InvalidParameter
            }
            CapiError::Contact(ContactError::OutOfValidity { .. }) => ClrStatus::OutOfValidity,
            CapiError::Contact(ContactError::NoConvergence { .. }) => ClrStatus::NoConvergence,
            CapiError::Contact(ContactError::UnknownName { .. })
            | CapiError::UnknownName { .. } => ClrStatus::UnknownName,
            CapiError::Null(_) => ClrStatus::NullPointer,
            CapiError::NonFinite { .. } => ClrStatus::NonFinite,
            CapiError::UnknownCode { .. }
            | CapiError::ParameterCount { .. }
            | CapiError::Utf8(_)
            | CapiError::ArrayLength { .. }
            | CapiError::Flag { .. } => ClrStatus::InvalidArgument,
            CapiError::BufferTooSmall { .. } => ClrStatus::BufferTooSmall,
            CapiError::Panic(_) => ClrStatus::Panic,
            CapiError::Model(_) => ClrStatus::ModelError,
            CapiError::Simulation(_) => ClrStatus::SimulationFailed,
        }
    }
}

/// Require a finite input.
pub fn finite(name: &'static str, value: f64) -> Result<f64, CapiError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(CapiError::NonFinite { name, value })
    }
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_last_error(message: &str) {
    let c = CString::new(message.replace('\0', " ")).unwrap_or_default();
    LAST_ERROR.with(|slot| *slot.borrow_mut() = c);
}

/// Run `f` at the C boundary: errors become a status and the thread's last-error message, and a
/// panic is caught (as a last resort) and reported as [`ClrStatus::Panic`].
pub fn guard(f: impl FnOnce() -> Result<(), CapiError>) -> ClrStatus {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(())) => ClrStatus::Ok,
        Ok(Err(e)) => {
            set_last_error(&e.to_string());
            e.status()
        }
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown payload".to_string());
            set_last_error(&CapiError::Panic(what).to_string());
            ClrStatus::Panic
        }
    }
}

/// Pointer to the thread's last error message (UTF-8, NUL-terminated, empty if no call failed
/// yet on this thread). Owned by the library; valid until the next failing call on this thread.
pub fn last_error_ptr() -> *const c_char {
    LAST_ERROR.with(|slot| slot.borrow().as_ptr())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    #[test]
    fn guard_reports_errors_and_panics() {
        assert_eq!(guard(|| Ok(())), ClrStatus::Ok);
        let s = guard(|| Err(CapiError::Null("law")));
        assert_eq!(s, ClrStatus::NullPointer);
        let msg = unsafe { CStr::from_ptr(last_error_ptr()) }
            .to_str()
            .unwrap();
        assert!(msg.contains("`law` is a NULL pointer"), "{msg}");
        let s = guard(|| panic!("boom"));
        assert_eq!(s, ClrStatus::Panic);
        let msg = unsafe { CStr::from_ptr(last_error_ptr()) }
            .to_str()
            .unwrap();
        assert!(msg.contains("boom"), "{msg}");
    }
}
