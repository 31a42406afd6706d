//! Hybrid transfer plots: the trajectory in the rotating frame (x–y and x–z, the Earth, the
//! Moon and the arrival point), and the throttle and the switching function against time, all
//! from the core's own flight of the returned plan (`drivers::hybrid::trajectory`).

use crate::drivers::hybrid::{plan, switch_times_days, trajectory, TRAJECTORY_SAMPLES};
use crate::fixture::hybrid::HybridFixture;
use crate::plot::{chart, range};
use anyhow::{anyhow, Result};
use plotters::prelude::*;
use reconfig_core::hybrid::units::{days, MASS_RATIO};
use reconfig_core::hybrid::Solution;
use reconfig_core::limits::Limits;
use std::path::Path;

/// Draw the fixture's plan (answered under the built-in limits) into `out` (SVG); the plan.
///
/// # Errors
/// The request refused or rejected, a plan that cannot be flown, or a drawing error.
pub fn transfer_svg(f: &HybridFixture, out: &Path) -> Result<Box<Solution>> {
    let s = plan(f, &Limits::default())?;
    let samples = trajectory(f, &s, TRAJECTORY_SAMPLES)?;
    let root = SVGBackend::new(out, (1400, 1000)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let (top, bottom) = root.split_vertically(560);
    let (xy, xz) = top.split_horizontally(700);
    let (throttle_area, switching_area) = bottom.split_vertically(220);
    let title = format!(
        "{}: {:?}, kappa {:.4}, t_f {:.4} d, final mass {}",
        f.name,
        s.info.status,
        s.kappa,
        days(s.duration_tu),
        s.flown
            .map_or_else(|| "-".to_owned(), |p| format!("{:.5}", p.final_mass))
    );
    let earth = (-MASS_RATIO, 0.0);
    let moon = (1.0 - MASS_RATIO, 0.0);
    let target = (f.problem.arrival_r_lu[0], f.problem.arrival_r_lu[1]);
    for (area, caption, pick) in [
        (&xy, Some((title.as_str(), 16)), 1usize),
        (&xz, None, 2usize),
    ] {
        let points: Vec<(f64, f64)> = samples
            .iter()
            .map(|x| (x.state.r_lu[0], x.state.r_lu[pick]))
            .collect();
        let (x0, x1) = range(points.iter().map(|p| p.0).chain([earth.0, moon.0]), 0.05);
        let (y0, y1) = range(points.iter().map(|p| p.1).chain([0.0]), 0.1);
        let y_desc = if pick == 1 { "y [LU]" } else { "z [LU]" };
        let mut c = chart(
            area,
            caption,
            (10, 35, 60),
            (x0..x1, y0..y1),
            ("x [LU]", y_desc),
        )?;
        // Thrust arcs red, coast arcs blue.
        for pair in samples.windows(2) {
            let (a, b) = (&pair[0], &pair[1]);
            let colour = if a.throttle > 0.5 { RED } else { BLUE };
            c.draw_series(LineSeries::new(
                [
                    (a.state.r_lu[0], a.state.r_lu[pick]),
                    (b.state.r_lu[0], b.state.r_lu[pick]),
                ],
                colour.stroke_width(2),
            ))
            .map_err(|e| anyhow!("{e}"))?;
        }
        let target_y = if pick == 1 {
            target.1
        } else {
            f.problem.arrival_r_lu[2]
        };
        c.draw_series([
            Circle::new(earth, 6, GREEN.filled()),
            Circle::new(moon, 4, BLACK.filled()),
            Circle::new((target.0, target_y), 5, MAGENTA.filled()),
        ])
        .map_err(|e| anyhow!("{e}"))?;
    }
    let t: Vec<f64> = samples.iter().map(|x| days(x.time_tu)).collect();
    let (t0, t1) = range(t.iter().copied(), 0.02);
    let mut c = chart(
        &throttle_area,
        None,
        (10, 35, 60),
        (t0..t1, -0.05..1.05),
        ("time [d]", "throttle"),
    )?;
    c.draw_series(LineSeries::new(
        t.iter().zip(&samples).map(|(t, x)| (*t, x.throttle)),
        RED.stroke_width(2),
    ))
    .map_err(|e| anyhow!("{e}"))?;
    let (s0, s1) = range(samples.iter().map(|x| x.switching), 0.05);
    let mut c = chart(
        &switching_area,
        None,
        (10, 35, 60),
        (t0..t1, s0.min(-0.1)..s1.max(0.1)),
        ("time [d]", "switching function S"),
    )?;
    c.draw_series(LineSeries::new(
        t.iter().zip(&samples).map(|(t, x)| (*t, x.switching)),
        BLUE.stroke_width(2),
    ))
    .map_err(|e| anyhow!("{e}"))?;
    c.draw_series(LineSeries::new(
        [(t0, 0.0), (t1, 0.0)],
        BLACK.stroke_width(1),
    ))
    .map_err(|e| anyhow!("{e}"))?;
    c.draw_series(
        switch_times_days(&s)
            .into_iter()
            .map(|d| Circle::new((d, 0.0), 4, MAGENTA.filled())),
    )
    .map_err(|e| anyhow!("{e}"))?;
    root.present().map_err(|e| anyhow!("{e}"))?;
    Ok(s)
}
