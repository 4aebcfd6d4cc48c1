//! Adaptive Dormand–Prince 5(4) integrator with dense output (in progress).
