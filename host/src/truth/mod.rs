//! The truth model: a high-fidelity propagation of inertial states through impulsive burns, to
//! check plans made in the planners' simpler models (planner B's J2 mean-element model).
//!
//! What acts ([`forces::ForceModel`]): the Earth's field JGM-3 to degree and order 8 (vendored
//! coefficients, [`gravity_model`]; Cunningham's recursion, [`gravity`]), drag in Vallado's
//! exponential atmosphere with a stated ballistic coefficient ([`atmosphere`]), and the Sun's and
//! the Moon's tides from Montenbruck & Gill's low-precision series ([`ephemeris`]). Integrator:
//! Dormand-Prince 5(4), relative tolerance 1e-12, absolute 1 micrometre ([`integrator`]).
//! Nothing is read or downloaded at run time: the one data file is compiled in.
//!
//! Why not the `satkit` crate (which the issue prefers): its numerical propagator takes the
//! Sun and Moon from the JPL DE440 file (102 MB, downloaded on first use or installed from the
//! `satkit-data` wheel, 105 MB) and the Earth's orientation and the space weather for drag
//! from CelesTrak files that it refreshes at run time; pinning all of that offline and
//! deterministic in CI was more than this part could carry. See `docs/truth-model.md`.

pub mod atmosphere;
pub mod ephemeris;
pub mod epoch;
pub mod forces;
pub mod gravity;
pub mod gravity_model;
pub mod integrator;
pub mod plan_check;
pub mod propagate;
pub mod record;

#[cfg(test)]
mod validation_tests;

/// Each of `want`'s components matched by `got`'s to within `tol` (absolute).
#[cfg(test)]
fn assert_close(got: &[f64], want: &[f64], tol: f64) {
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!((g - w).abs() < tol, "{i}: {g} vs {w}");
    }
}
