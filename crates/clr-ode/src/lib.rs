//! # clr-ode: stiff and non-stiff integrators with event location and cheap restarts
//!
//! Problems are `M(t, y) y' = f(t, y)` ([`OdeSystem`], or closures through [`OdeFn`]) with an
//! optional analytic Jacobian (otherwise finite differences), an optional mass matrix
//! ([`MassKind`]: constant or state-dependent; a singular M makes an index-1 DAE) and event
//! functions g(t, y) with a crossing [`Direction`] and a terminal flag.
//!
//! Solvers, both configured by [`Options`] (rtol, scalar or per-component atol, h0 (automatic by
//! default), h_max, h_min floor, max_steps, [`Output`] every step / at given times / end only):
//! - [`Ndf`]: the variable-order (1–5) NDF solver of ode15s (Shampine & Reichelt 1997), or
//!   plain BDF with [`Options::bdf`]; simplified Newton with Jacobian and LU reuse; stiff
//!   problems and index-1 DAEs. For structural models y = (x, ẋ) with undamped stiff modes use
//!   `max_order(2)` and [`Options::h_scaled_error`] on the velocities (docs/ode.md).
//! - [`Dopri5`]: Dormand–Prince 5(4), PI step control, 4th-order dense output; non-stiff.
//!
//! Both locate events on their dense output (Illinois root finding), call an [`Observer`] after
//! each accepted step (it may stop the run), and count [`Stats`]. A run returns
//! `Result<`[`Solution`]`, `[`OdeError`]`>`; every error carries the solution computed up to it.
//! The Test Set problems (HIRES, Robertson ODE/DAE, stiff Van der Pol, OREGO) with references
//! are in [`test_models`].
//!
//! ## Solving
//!
//! ```
//! use clr_ode::{Ndf, OdeFn, Options};
//! // Stiff linear decay y' = -1000 (y - cos t); closure with an analytic Jacobian.
//! let mut sys = OdeFn::new(1, |t, y: &[f64], dy: &mut [f64]| dy[0] = -1000.0 * (y[0] - t.cos()))
//!     .jacobian(|_t, _y: &[f64], j: &mut [f64]| j[0] = -1000.0);
//! let mut solver = Ndf::new(Options::default().rtol(1e-8).atol(1e-10));
//! let sol = solver.solve(&mut sys, 0.0, &[1.0], 2.0).unwrap();
//! // closed form: y → cos t + 1e-3 sin t + O(1e-6)
//! assert!((sol.y_final[0] - (2f64.cos() + 1e-3 * 2f64.sin())).abs() < 1e-5);
//! println!("{} steps, {} LU factorizations", sol.stats.accepted, sol.stats.lu_factorizations);
//! ```
//!
//! ## Events and restarts (the contact pattern)
//!
//! A terminal event stops the run at the located crossing; the caller changes its model (here:
//! the velocity jumps with restitution e = 0.8), then [`Solver::restart`] continues from the new
//! (t, y) with the history reset, reusing every buffer (no reallocation), so thousands of
//! restarts per simulation are cheap.
//!
//! ```
//! use clr_ode::{Direction, Ndf, OdeFn, Options, StopReason};
//! let g = 9.81;
//! let mut ball = OdeFn::new(2, move |_t, y: &[f64], dy: &mut [f64]| {
//!     dy[0] = y[1]; // height (m)
//!     dy[1] = -g;   // velocity (m/s)
//! })
//! .event(Direction::Falling, true, |_t, y: &[f64]| y[0]); // floor contact
//! let mut s = Ndf::new(Options::default().rtol(1e-10).atol(1e-12));
//! s.start(&mut ball, 0.0, &[1.0, 0.0], 5.0).unwrap();
//! let mut impacts = Vec::new();
//! loop {
//!     match s.advance(&mut ball).unwrap() {
//!         StopReason::TerminalEvent(_) => {
//!             let (t, v) = (s.solution().t_final, s.solution().y_final[1]);
//!             impacts.push(t);
//!             if impacts.len() == 3 { break; }
//!             s.restart(&mut ball, t, &[0.0, -0.8 * v]).unwrap();
//!         }
//!         _ => break,
//!     }
//! }
//! // closed form: t1 = sqrt(2 h0 / g), then intervals 2 e^k v0 / g
//! let (t1, v0) = ((2.0 / g).sqrt(), (2.0 * g).sqrt());
//! assert!((impacts[1] - (t1 + 2.0 * 0.8 * v0 / g)).abs() < 1e-8);
//! ```
//!
//! The same loop works with [`Dopri5`]. Output, events and statistics accumulate over restarts
//! in [`Solver::solution`].

// Numerical kernels index several arrays in lock-step; iterator chains would obscure them.
#![allow(clippy::needless_range_loop)]
#![warn(missing_docs)]

pub mod dopri5;
pub mod linalg;
pub mod ndf;
pub mod options;
pub mod solution;
pub mod solver;
pub mod sparse;
pub mod system;
pub mod test_models;

pub use options::{Atol, Formula, Options, Output};
pub use solution::{EventRecord, OdeError, Solution, Stats, StopReason};
pub use solver::{Control, NoObserver, Observer, Solver};
pub use system::{Direction, MassKind, OdeFn, OdeSystem};

/// NDF/BDF solver of the ode15s family (stiff problems and index-1 DAEs).
pub type Ndf = Solver<ndf::NdfMethod>;

/// Dormand–Prince 5(4) solver (non-stiff problems).
pub type Dopri5 = Solver<dopri5::Dopri5Method>;

#[cfg(test)]
mod tests;
