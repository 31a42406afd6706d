//! Pictures of plans (plotters, SVG), one module per plot.
//!
//! * [`pseudospectral_plot`] — planner A: the trajectories in the three plane projections with
//!   the LGL nodes and the Gaussian test points marked; the separation of every pair over time
//!   with the keep-out distance; the controls per axis with the bound.
//! * [`impulsive_plot`] — planner B: the deputy's relative motion in the chief's local frame
//!   (radial / along-track / normal) under the plan, with the impulses marked and their dv
//!   drawn, over the initial and the target formation; the three components over time. The
//!   orbital model (J2 drift, geometry) is the core's.

use plotters::coord::types::RangedCoordf64 as RangedF64;
use plotters::prelude::*;

pub mod impulsive_plot;
pub mod pseudospectral_plot;

pub use impulsive_plot::{impulsive_svg, impulsive_trajectory};
pub use pseudospectral_plot::{
    cubic_at_nodes, lgl_nodes, pseudospectral_svg, unconstrained_guess, Interpolant,
};

/// Highlight colour (impulses, test points).
pub(crate) const GOLD: RGBColor = RGBColor(255, 200, 0);

/// The palette: [`color`] cycles through its first 8, [`arc_color`] through the 7 after the
/// first two.
const PALETTE: [RGBColor; 9] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
    RGBColor(188, 189, 34),
];

/// The i-th colour of the palette (cycling over 8).
pub(crate) fn color(i: usize) -> RGBColor {
    PALETTE[i % 8]
}

/// The colour of planner B's k-th coast arc (cycling over 7): none of the formations' two
/// (`color(0)`, `color(1)`), at most `MAX_IMPULSES + 1 = 7` arcs.
pub(crate) fn arc_color(k: usize) -> RGBColor {
    PALETTE[2 + k % 7]
}

/// A chart on `area` over `x` × `y`, its mesh drawn with the axes' descriptions: the tours'
/// plots' one style (`(margin, x label area, y label area)` in pixels, an optional caption and
/// its font size).
///
/// # Errors
/// A drawing error.
pub(crate) fn chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, plotters::coord::Shift>,
    caption: Option<(&str, u32)>,
    (margin, x_area, y_area): (u32, u32, u32),
    (x, y): (std::ops::Range<f64>, std::ops::Range<f64>),
    (x_desc, y_desc): (&str, &str),
) -> anyhow::Result<ChartContext<'a, DB, Cartesian2d<RangedF64, RangedF64>>>
where
    DB::ErrorType: 'static,
{
    let mut builder = ChartBuilder::on(area);
    if let Some((text, size)) = caption {
        builder.caption(text, ("sans-serif", size));
    }
    let mut c = builder
        .margin(margin)
        .x_label_area_size(x_area)
        .y_label_area_size(y_area)
        .build_cartesian_2d(x, y)
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    c.configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    Ok(c)
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
