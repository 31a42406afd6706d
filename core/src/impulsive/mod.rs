//! Planner B: multi-impulse reconfiguration under J2 at fixed impulse points (Wang et al. 2018).
