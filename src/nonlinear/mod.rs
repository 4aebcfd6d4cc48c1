//! Nonlinear models: equilibria, exact linearisation, simulation (in progress).
