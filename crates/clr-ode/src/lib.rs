//! ODE and index-1 DAE integrators for clr (being written).
