//! Pictures of plans (plotters, SVG), one module per plot.
//!
//! * [`pseudospectral_plot`] — planner A: the trajectories in the three plane projections with
//!   the LGL nodes and the Gaussian test points marked; the separation of every pair over time
//!   with the keep-out distance; the controls per axis with the bound.
//! * [`impulsive_plot`] — planner B: the deputy's relative motion in the chief's local frame
//!   (radial / along-track / normal) under the plan, with the impulses marked and their dv
//!   drawn, over the initial and the target formation; the three components over time. The
//!   orbital model (J2 drift, geometry) is the core's.

use plotters::prelude::*;

pub mod impulsive_plot;
pub mod pseudospectral_plot;

pub use impulsive_plot::{impulsive_svg, impulsive_trajectory};
pub use pseudospectral_plot::{
    cubic_at_nodes, lgl_nodes, pseudospectral_svg, unconstrained_guess, Interpolant,
};

/// Highlight colour (impulses, test points).
pub(crate) const GOLD: RGBColor = RGBColor(255, 200, 0);

const COLORS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// The i-th colour of the palette (cycling).
pub(crate) fn color(i: usize) -> RGBColor {
    COLORS[i % COLORS.len()]
}

/// The finite values' range widened by `pad` of its span on each side (-1..1 when empty).
pub(crate) fn range(values: impl Iterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let span = (hi - lo).max(1e-9);
    (lo - pad * span, hi + pad * span)
}

/// Euclidean distance.
pub(crate) fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
