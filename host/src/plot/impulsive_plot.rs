//! The planner-B plot: the deputy's relative motion in the chief's local frame (radial /
//! along-track / normal) under the plan, with the impulses marked and their dv drawn, over the
//! initial and the target formation; the three components over time. Every position comes
//! from the core (`impulsive::relative_position_rtn_km`, `impulsive::formation_position_rtn_km`).

use super::{arc_color, color, range, GOLD};
use anyhow::{anyhow, Result};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use reconfig_core::impulsive;
use std::path::Path;

/// The chief's Keplerian period, s.
fn chief_period_s(problem: &impulsive::Problem) -> f64 {
    2.0 * std::f64::consts::PI
        * (problem.chief.sma_km.powi(3) / reconfig_core::astro::EARTH_MU_KM3_S2).sqrt()
}

/// One orbit of the formation with relative elements `rel` at `t0_s` (both spacecraft then
/// drifting with their own J2 rates, no impulses), chief's RTN frame, m. The core's model
/// (`impulsive::formation_position_rtn_km`), so the curves agree with the planned trajectory.
fn formation_m(
    problem: &impulsive::Problem,
    settings: &impulsive::Settings,
    rel: &impulsive::RelativeElements,
    t0_s: f64,
    samples: usize,
) -> Result<Vec<[f64; 3]>> {
    let period = chief_period_s(problem);
    (0..=samples)
        .map(|k| {
            let t = t0_s + period * k as f64 / samples as f64;
            impulsive::formation_position_rtn_km(&problem.chief, rel, t0_s, t, settings)
                .map(|p| [p[0] * 1e3, p[1] * 1e3, p[2] * 1e3])
                .map_err(|e| anyhow!("formation at t = {t:.1} s: {e}"))
        })
        .collect()
}

/// The deputy's trajectory under `solution` (the core's nonlinear-check model): times (s) and
/// positions in the chief's RTN frame (m), from the epoch to one chief period after the last
/// impulse, with every impulse time among the samples.
pub fn impulsive_trajectory(
    problem: &impulsive::Problem,
    settings: &impulsive::Settings,
    solution: &impulsive::Solution,
    samples_per_orbit: usize,
) -> Result<Vec<(f64, [f64; 3])>> {
    let period = chief_period_s(problem);
    let t_end = solution.final_time_s + period;
    let n = ((t_end / period) * samples_per_orbit as f64)
        .ceil()
        .max(2.0) as usize;
    let mut times: Vec<f64> = (0..=n).map(|k| t_end * k as f64 / n as f64).collect();
    times.extend(solution.impulses.iter().map(|i| i.time_s));
    times.sort_by(f64::total_cmp);
    times.dedup();
    times
        .into_iter()
        .map(|t| {
            impulsive::relative_position_rtn_km(problem, settings, solution, t)
                .map(|p| (t, [p[0] * 1e3, p[1] * 1e3, p[2] * 1e3]))
                .map_err(|e| anyhow!("trajectory at t = {t:.1} s: {e}"))
        })
        .collect()
}

/// `lo..hi` widened about its middle to `span`.
fn widen(r: (f64, f64), span: f64) -> (f64, f64) {
    let mid = 0.5 * (r.0 + r.1);
    (mid - 0.5 * span, mid + 0.5 * span)
}

/// 1, 2 or 5 times a power of ten, at most `x` (for a readable arrow scale).
fn nice_below(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|v| *v <= x)
        .unwrap_or(p)
}

/// Draw a planner-B plan: the deputy's relative trajectory in the chief's RTN frame (three
/// projections, one colour per coast arc) from the epoch to one orbit after the last impulse,
/// with the initial and the target formation as thin reference curves, each impulse marked at
/// its position with its dv drawn as an arrow; below, the three RTN components over time.
pub fn impulsive_svg(
    problem: &impulsive::Problem,
    settings: &impulsive::Settings,
    solution: &impulsive::Solution,
    title: &str,
    out: &Path,
) -> Result<()> {
    let period = chief_period_s(problem);
    let traj = impulsive_trajectory(problem, settings, solution, 240)?;
    let initial = formation_m(problem, settings, &problem.initial, 0.0, 600)?;
    let target = formation_m(
        problem,
        settings,
        &problem.target,
        solution.final_time_s,
        600,
    )?;
    let imps = &solution.impulses;
    // Impulse positions on the trajectory.
    let marks: Vec<[f64; 3]> = imps
        .iter()
        .map(|i| {
            impulsive::relative_position_rtn_km(problem, settings, solution, i.time_s)
                .map(|p| [p[0] * 1e3, p[1] * 1e3, p[2] * 1e3])
                .map_err(|e| anyhow!("impulse position: {e}"))
        })
        .collect::<Result<_>>()?;
    // Coast arc of each sample: the number of impulses at or before it.
    let arc = |t: f64| imps.iter().filter(|i| i.time_s <= t).count();
    let dv_norm = |i: &impulsive::Impulse| {
        let d = i.dv_rtn_mps;
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    };
    let max_dv = imps.iter().map(dv_norm).fold(0.0, f64::max);

    let root = SVGBackend::new(out, (1500, 1000)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 20))?;
    let (top, bottom) = root.split_vertically(560);
    let panels = top.split_evenly((1, 3));
    let names = ["radial (m)", "along-track (m)", "normal (m)"];
    let err = |e: &dyn std::fmt::Display| anyhow!("plot: {e}");
    let pairs = [(1usize, 0usize), (1, 2), (0, 2)];

    // Equal scales on both axes of each panel (metres per pixel), the first panel keeping room
    // at the top for the legend.
    let (margin, x_area, y_area, caption) = (10u32, 35u32, 60u32, 24u32);
    let legend_px = 20.0 * (imps.len() as f64 + 4.0);
    let all = || {
        initial
            .iter()
            .chain(&target)
            .chain(traj.iter().map(|p| &p.1))
    };
    let plot_px = |panel: &DrawingArea<SVGBackend, plotters::coord::Shift>| {
        let (w, h) = panel.dim_in_pixel();
        (
            f64::from(w - 2 * margin - y_area),
            f64::from(h - 2 * margin - x_area - caption),
        )
    };
    for (n_panel, (panel, (a, b))) in panels.iter().zip(pairs).enumerate() {
        let rx = range(all().map(|p| p[a]), 0.05);
        let ry = range(all().map(|p| p[b]), 0.05);
        let (w, h) = plot_px(panel);
        let reserve = if n_panel == 0 {
            legend_px.min(0.5 * h)
        } else {
            0.0
        };
        let m_per_px = ((rx.1 - rx.0) / w).max((ry.1 - ry.0) / (h - reserve));
        let (x0, x1) = widen(rx, w * m_per_px);
        let y0 = widen(ry, (h - reserve) * m_per_px).0;
        let y1 = y0 + h * m_per_px;
        // Arrow scale: the largest impulse spans 32 to 80 px.
        let arrow_m_per_mps = if max_dv > 0.0 {
            nice_below(80.0 * m_per_px / max_dv)
        } else {
            1.0
        };
        let mut chart = ChartBuilder::on(panel)
            .caption(
                format!(
                    "{} vs {}; dv arrows 1 m/s = {arrow_m_per_mps} m",
                    names[b], names[a]
                ),
                ("sans-serif", 16),
            )
            .margin(margin)
            .x_label_area_size(x_area)
            .y_label_area_size(y_area)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc(names[a])
            .y_desc(names[b])
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.0}"))
            .light_line_style(WHITE)
            .draw()
            .map_err(|e| err(&e))?;
        for k in 0..=imps.len() {
            let c = arc_color(k);
            // Each arc starts at its impulse, so the curve is continuous.
            let pts: Vec<(f64, f64)> = traj
                .iter()
                .filter(|(t, _)| {
                    let j = arc(*t);
                    j == k || (j == k + 1 && imps.get(k).is_some_and(|i| i.time_s == *t))
                })
                .map(|(_, p)| (p[a], p[b]))
                .collect();
            let what = match k {
                0 => "before impulse 1".to_string(),
                k if k == imps.len() => format!("after impulse {k}"),
                k => format!("impulse {k} to {}", k + 1),
            };
            chart
                .draw_series(LineSeries::new(pts, c.stroke_width(2)))
                .map_err(|e| err(&e))?
                .label(format!("trajectory, {what}"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 15, y)], c.stroke_width(2))
                });
        }
        // The formations on top, thin and dashed: the trajectory should run along them.
        let faint = |c: RGBColor| c.mix(0.9).stroke_width(1);
        for (k, formation, label) in [
            (0, &initial, "initial formation (t = 0)"),
            (1, &target, "target formation (at the last impulse)"),
        ] {
            chart
                .draw_series(DashedLineSeries::new(
                    formation.iter().map(|p| (p[a], p[b])),
                    6,
                    4,
                    faint(color(k)),
                ))
                .map_err(|e| err(&e))?
                .label(label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], faint(color(k))));
        }
        // Impulses: the dv arrows (this panel's two components), labels placed where they
        // hide no marker, arrow or other label, then arrows and markers on top.
        let arrows: Vec<Option<[(f64, f64); 4]>> = imps
            .iter()
            .zip(&marks)
            .map(|(imp, p)| {
                let (px, py) = (p[a], p[b]);
                let (dx, dy) = (
                    imp.dv_rtn_mps[a] * arrow_m_per_mps,
                    imp.dv_rtn_mps[b] * arrow_m_per_mps,
                );
                let len = (dx * dx + dy * dy).sqrt();
                (len > 2.0 * m_per_px).then(|| {
                    let (ux, uy) = (dx / len, dy / len);
                    let head = (8.0 * m_per_px).min(0.5 * len);
                    let tip = (px + dx, py + dy);
                    let side = |s: f64| {
                        (
                            tip.0 - head * (ux * 0.94 - s * uy * 0.34),
                            tip.1 - head * (uy * 0.94 + s * ux * 0.34),
                        )
                    };
                    [(px, py), tip, side(1.0), side(-1.0)]
                })
            })
            .collect();
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let to_px = |x: f64, y: f64| chart.backend_coord(&(x, y));
        type PxBox = (i32, i32, i32, i32);
        let mut taken: Vec<PxBox> = Vec::new();
        for (p, arrow) in marks.iter().zip(&arrows) {
            let (mx, my) = to_px(p[a], p[b]);
            taken.push((mx - 6, my - 6, mx + 6, my + 6));
            if let Some([from, tip, ..]) = arrow {
                for j in 0..=12 {
                    let f = f64::from(j) / 12.0;
                    let (x, y) =
                        to_px(from.0 + f * (tip.0 - from.0), from.1 + f * (tip.1 - from.1));
                    taken.push((x - 3, y - 3, x + 3, y + 3));
                }
            }
        }
        let overlaps = |u: &PxBox, v: &PxBox| u.0 < v.2 && v.0 < u.2 && u.1 < v.3 && v.1 < u.3;
        let mut labels = Vec::new();
        for (k, (imp, p)) in imps.iter().zip(&marks).enumerate() {
            let label = format!("{}: {:.3} m/s", k + 1, dv_norm(imp));
            let (w, h) = (4 + 7 * label.len() as i32, 16);
            let (mx, my) = to_px(p[a], p[b]);
            let candidates = [
                (8, -8),
                (-8 - w, -8),
                (8, -24),
                (8, 8),
                (-8 - w, -24),
                (-8 - w, 8),
                (-w / 2, -28),
                (-w / 2, 12),
            ];
            let fits = |o: &(i32, i32)| {
                let bx = (mx + o.0, my + o.1, mx + o.0 + w, my + o.1 + h);
                bx.0 >= xr.start && bx.2 <= xr.end && bx.1 >= yr.start && bx.3 <= yr.end
            };
            let free = |o: &(i32, i32)| {
                let bx = (mx + o.0, my + o.1, mx + o.0 + w, my + o.1 + h);
                !taken.iter().any(|t| overlaps(t, &bx))
            };
            let o = candidates
                .iter()
                .find(|o| fits(o) && free(o))
                .or_else(|| candidates.iter().find(|o| fits(o)))
                .copied()
                .unwrap_or((8, -8));
            taken.push((mx + o.0, my + o.1, mx + o.0 + w, my + o.1 + h));
            labels.push(
                EmptyElement::at((p[a], p[b]))
                    + Rectangle::new([o, (o.0 + w, o.1 + h)], WHITE.mix(0.75).filled())
                    + Text::new(label, (o.0 + 2, o.1 + 2), ("sans-serif", 13).into_font()),
            );
        }
        chart.draw_series(labels).map_err(|e| err(&e))?;
        let style = BLACK.stroke_width(2);
        for [from, tip, s1, s2] in arrows.iter().flatten() {
            chart
                .draw_series([
                    PathElement::new(vec![*from, *tip], style),
                    PathElement::new(vec![*s1, *tip, *s2], style),
                ])
                .map_err(|e| err(&e))?;
        }
        chart
            .draw_series(marks.iter().map(|p| {
                EmptyElement::at((p[a], p[b]))
                    + Circle::new((0, 0), 5, GOLD.filled())
                    + Circle::new((0, 0), 5, BLACK.stroke_width(1))
            }))
            .map_err(|e| err(&e))?;
        if (a, b) == pairs[0] {
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                .map_err(|e| err(&e))?
                .label("impulse k: |dv|, arrow = dv in this plane (scale in the title)")
                .legend(|(x, y)| {
                    EmptyElement::at((x + 7, y))
                        + Circle::new((0, 0), 4, GOLD.filled())
                        + PathElement::new(vec![(0, 0), (12, 0)], BLACK.stroke_width(2))
                });
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 12))
                .draw()
                .map_err(|e| err(&e))?;
        }
    }

    // The RTN components over time, impulses as vertical lines.
    let orbits = |t: f64| t / period;
    let t_end = traj.last().map_or(period, |p| p.0);
    let (lo, hi) = range(traj.iter().flat_map(|p| p.1), 0.06);
    let mut chart = ChartBuilder::on(&bottom)
        .caption(
            "relative position in the chief's RTN frame over time",
            ("sans-serif", 16),
        )
        .margin(margin)
        .x_label_area_size(x_area)
        .y_label_area_size(y_area)
        .build_cartesian_2d(0.0..orbits(t_end), lo..hi)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc("t (chief orbits)")
        .y_desc("m")
        .y_label_formatter(&|v| format!("{v:.0}"))
        .light_line_style(WHITE)
        .draw()
        .map_err(|e| err(&e))?;
    for (j, name) in ["radial", "along-track", "normal"].iter().enumerate() {
        let c = [color(0), color(1), color(2)][j];
        chart
            .draw_series(LineSeries::new(
                traj.iter().map(|(t, p)| (orbits(*t), p[j])),
                c.stroke_width(2),
            ))
            .map_err(|e| err(&e))?
            .label(*name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], c.stroke_width(2)));
    }
    for (k, imp) in imps.iter().enumerate() {
        let x = orbits(imp.time_s);
        chart
            .draw_series([PathElement::new(vec![(x, lo), (x, hi)], BLACK.mix(0.6))])
            .map_err(|e| err(&e))?;
        let d = imp.dv_rtn_mps;
        let text = format!(
            " {}: dv RTN [{:.2}, {:.2}, {:.2}] m/s ",
            k + 1,
            d[0],
            d[1],
            d[2]
        );
        // Right of the line, or left of it near the right edge; one row per impulse.
        let right = x > 0.75 * orbits(t_end);
        let pos = if right {
            Pos::new(HPos::Right, VPos::Top)
        } else {
            Pos::new(HPos::Left, VPos::Top)
        };
        let row = 2 + 14 * k as i32;
        let width = 4 + 7 * text.len() as i32;
        let bx = if right { -width } else { 0 };
        chart
            .draw_series([EmptyElement::at((x, hi))
                + Rectangle::new([(bx, row), (bx + width, row + 14)], WHITE.mix(0.8).filled())
                + Text::new(
                    text,
                    (0, row + 1),
                    TextStyle::from(("sans-serif", 12).into_font()).pos(pos),
                )])
            .map_err(|e| err(&e))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 12))
        .draw()
        .map_err(|e| err(&e))?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::dist;
    use super::*;

    #[test]
    fn impulsive_trajectory_runs_from_the_initial_to_the_target_formation() -> Result<()> {
        // The core's trajectory and the host's formation curves use one convention: before the
        // first impulse it is on the initial formation, one orbit after the last on the target.
        let p = crate::scenario::wang2018_table2();
        let settings = impulsive::Settings::default();
        let mut ws = Box::new(impulsive::Workspace::new());
        let mut sol = Box::new(impulsive::Solution::new());
        impulsive::solve(&p, &settings, &mut ws, &mut sol).map_err(|e| anyhow!("{e}"))?;
        let traj = impulsive_trajectory(&p, &settings, &sol, 60)?;
        let period = chief_period_s(&p);
        let t1 = sol.impulses[0].time_s;
        let tn = sol.final_time_s;
        assert!((traj.last().map_or(0.0, |p| p.0) - (tn + period)).abs() < 1e-6);
        let mut checked = (0, 0);
        for (t, q) in &traj {
            let formation = if *t < t1 {
                checked.0 += 1;
                impulsive::formation_position_rtn_km(&p.chief, &p.initial, 0.0, *t, &settings)
            } else if *t > tn {
                checked.1 += 1;
                impulsive::formation_position_rtn_km(&p.chief, &p.target, tn, *t, &settings)
            } else {
                continue;
            };
            let want = formation.map_err(|e| anyhow!("{e}"))?;
            let d = dist(*q, [want[0] * 1e3, want[1] * 1e3, want[2] * 1e3]);
            assert!(d < 1e-3, "t = {t}: {d} m off the formation");
        }
        assert!(checked.0 > 50 && checked.1 > 50, "{checked:?}");
        // Every impulse time is a sample.
        for i in &sol.impulses {
            assert!(traj.iter().any(|(t, _)| *t == i.time_s));
        }
        Ok(())
    }
}
