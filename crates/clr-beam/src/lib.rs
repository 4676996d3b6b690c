//! Planar Euler–Bernoulli beam finite elements (being written).
