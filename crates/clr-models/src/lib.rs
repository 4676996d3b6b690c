//! The paper systems of clr: the sliding guide of a telescopic mechanism, the flap actuation
//! system and the dual manipulator on a free-floating spacecraft.
//!
//! **Not implemented yet.** It needs `clr-mbd`; see `docs/models/` for the plan of each system.
