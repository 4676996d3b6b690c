//! # clr-ode: stiff and non-stiff integrators with event location and cheap restarts
//!
//! Problems are `M(t, y) y' = f(t, y)` ([`OdeSystem`], or closures through [`OdeFn`]) with an
//! optional analytic Jacobian, an optional mass matrix (constant or state-dependent; a singular
//! M makes an index-1 DAE) and event functions g(t, y) with a crossing [`Direction`] and a
//! terminal flag.
//!
//! Solvers, both configured by [`Options`]:
//! - [`Dopri5`]: Dormand–Prince 5(4), PI step control, 4th-order dense output.
//!
//! A run returns `Result<`[`Solution`]`, `[`OdeError`]`>`; a failure carries the solution
//! computed up to it.
//!
//! ## Solving
//!
//! ```
//! use clr_ode::{Dopri5, OdeFn, Options};
//! // y' = -y, y(0) = 1  →  y(1) = e^-1
//! let mut sys = OdeFn::new(1, |_t, y: &[f64], dy: &mut [f64]| dy[0] = -y[0]);
//! let mut solver = Dopri5::new(Options::default().rtol(1e-9).atol(1e-12));
//! let sol = solver.solve(&mut sys, 0.0, &[1.0], 1.0).unwrap();
//! assert!((sol.y_final[0] - (-1.0f64).exp()).abs() < 1e-8);
//! println!("{} steps, {} f evaluations", sol.stats.accepted, sol.stats.f_evals);
//! ```

// Numerical kernels index several arrays in lock-step; iterator chains would obscure them.
#![allow(clippy::needless_range_loop)]

pub mod dopri5;
pub mod linalg;
pub mod ndf;
pub mod options;
pub mod solution;
pub mod solver;
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
