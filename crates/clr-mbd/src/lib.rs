//! Planar constrained multibody dynamics with clearance joints and flexible bodies.
//!
//! **Not implemented yet.** This crate is planned (see `docs/architecture.md`, section clr-mbd)
//! and currently exports nothing. It will combine `clr-ode`, `clr-contact` and `clr-beam`.
