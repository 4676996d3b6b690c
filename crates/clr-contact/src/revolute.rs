//! (being written: geometry and contact state)
