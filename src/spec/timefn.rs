//! Functions of time as data: the model description's [`TimeFn`] (clr-mbd), re-exported.

pub use clr_mbd::timefn::{TimeFn, TIME_FN_KINDS};
