//! (being written: normal-force and friction laws)
