//! GEO tour plots: the servicer's longitude and radius over the mission (sampled by two-body
//! propagation through the planned burns), and total Δv against mission time.

use crate::drivers::geo_tour::plan;
use crate::fixture::geo_tour::{GeoTourFixture, DAY_S};
use crate::plot::{chart, range};
use anyhow::{anyhow, Result};
use plotters::prelude::*;
use reconfig_core::geo_tour::{rtn_to_inertial, Geo, MethodPolicy, Solution};
use reconfig_core::lambert::propagate;
use std::path::Path;

/// Samples (time d, Earth-fixed longitude deg, radius minus a0 km) of the servicer along the
/// plan, `per_leg` points per leg plus every burn.
pub fn track(s: &Solution, per_leg: usize) -> Vec<(f64, f64, f64)> {
    let g = Geo::standard();
    let mut out = Vec::new();
    let mut unwrap = 0.0f64;
    let mut last: Option<f64> = None;
    let mut push = |t_s: f64, r: &[f64; 3], out: &mut Vec<(f64, f64, f64)>| {
        let lon = (r[1].atan2(r[0]) - g.n0 * t_s).to_degrees();
        let mut l = lon.rem_euclid(360.0) + unwrap;
        if let Some(p) = last {
            while l - p > 180.0 {
                l -= 360.0;
                unwrap -= 360.0;
            }
            while l - p < -180.0 {
                l += 360.0;
                unwrap += 360.0;
            }
        }
        last = Some(l);
        let rn = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        out.push((t_s / DAY_S, l, rn - g.a0));
    };
    for leg in &s.legs {
        let (mut r, mut v) = g.slot_state(leg.from_lon_rad, leg.start_s);
        let mut t = 0.0;
        let mut events: Vec<(f64, Option<[f64; 3]>)> = leg
            .burns
            .iter()
            .map(|b| (b.offset_s, Some(b.dv_rtn_mps)))
            .collect();
        let n = per_leg.max(2);
        for k in 0..=n {
            events.push((leg.duration_s * k as f64 / n as f64, None));
        }
        events.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (at, burn) in events {
            if at > t {
                if let Some((r2, v2)) = propagate(g.mu, &r, &v, at - t, 100) {
                    (r, v) = (r2, v2);
                }
                t = at;
            }
            push(leg.start_s + t, &r, &mut out);
            if let Some(dv) = burn {
                let d = rtn_to_inertial(&r, &v, &dv);
                for k in 0..3 {
                    v[k] += d[k] / 1000.0;
                }
            }
        }
    }
    out
}

/// Longitude and radius over time of the fixture's plan.
pub fn tour_svg(f: &GeoTourFixture, out: &Path) -> Result<()> {
    let s = plan(f, None)?;
    let pts = track(&s, 400);
    let root = SVGBackend::new(out, (1400, 900)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let (top, bottom) = root.split_vertically(450);
    let (t0, t1) = range(pts.iter().map(|p| p.0), 0.05);
    let (l0, l1) = range(pts.iter().map(|p| p.1), 0.05);
    let (h0, h1) = range(pts.iter().map(|p| p.2), 0.05);
    let title = format!(
        "{}: {:?}, total dv {:.3} m/s, {:.2} d, largest burn {:.3} m/s",
        f.name,
        s.info.status,
        s.total_dv_mps,
        s.mission_time_s / DAY_S,
        s.max_burn_mps
    );
    let mut c = chart(
        &top,
        Some((&title, 18)),
        (10, 35, 60),
        (t0..t1, l0..l1),
        ("time [d]", "longitude [deg E]"),
    )?;
    c.draw_series(LineSeries::new(
        pts.iter().map(|p| (p.0, p.1)),
        BLUE.stroke_width(2),
    ))
    .map_err(|e| anyhow!("{e}"))?;
    let clients: Vec<(f64, f64)> = s
        .legs
        .iter()
        .map(|l| {
            (
                (l.start_s + l.transfer_s) / DAY_S,
                pts_lon(&pts, (l.start_s + l.transfer_s) / DAY_S),
            )
        })
        .collect();
    c.draw_series(clients.iter().map(|&p| Circle::new(p, 4, RED.filled())))
        .map_err(|e| anyhow!("{e}"))?;
    let mut c = chart(
        &bottom,
        None,
        (10, 35, 60),
        (t0..t1, h0..h1),
        ("time [d]", "radius - GEO [km]"),
    )?;
    c.draw_series(LineSeries::new(
        pts.iter().map(|p| (p.0, p.2)),
        BLUE.stroke_width(1),
    ))
    .map_err(|e| anyhow!("{e}"))?;
    root.present().map_err(|e| anyhow!("{e}"))?;
    Ok(())
}

fn pts_lon(pts: &[(f64, f64, f64)], t_d: f64) -> f64 {
    pts.iter()
        .min_by(|a, b| (a.0 - t_d).abs().total_cmp(&(b.0 - t_d).abs()))
        .map_or(0.0, |p| p.1)
}

/// One point of the Δv-against-time curve: mission days, total by cost, total by the rule
/// (`None`: not solved).
pub type ParetoPoint = (f64, Option<f64>, Option<f64>);

/// Total Δv against mission time (`days`), by cost and by the paper's rule; infeasible points
/// are left out. Returns the curve (days, by cost, by rule) it drew.
pub fn pareto_svg(f: &GeoTourFixture, days: &[f64], out: &Path) -> Result<Vec<ParetoPoint>> {
    let mut curve = Vec::new();
    for &d in days {
        let mut by_rule = f.clone();
        by_rule.problem.policy = MethodPolicy::PaperRule;
        let mut by_cost = f.clone();
        by_cost.problem.policy = MethodPolicy::ByCost;
        let solved = |x: &GeoTourFixture| {
            plan(x, Some(d))
                .ok()
                .filter(|s| s.info.status.is_usable())
                .map(|s| s.total_dv_mps)
        };
        curve.push((d, solved(&by_cost), solved(&by_rule)));
    }
    let root = SVGBackend::new(out, (1000, 650)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let (d0, d1) = range(curve.iter().map(|c| c.0), 0.05);
    let (v0, v1) = range(curve.iter().flat_map(|c| [c.1, c.2]).flatten(), 0.05);
    let caption = format!(
        "{}: total dv against mission time (cap {} m/s)",
        f.name, f.problem.max_burn_mps
    );
    let mut c = chart(
        &root,
        Some((&caption, 18)),
        (10, 35, 60),
        (d0..d1, v0.max(0.0)..v1),
        ("mission time [d]", "total dv [m/s]"),
    )?;
    c.draw_series(LineSeries::new(
        curve.iter().filter_map(|p| p.1.map(|v| (p.0, v))),
        BLUE.stroke_width(2),
    ))
    .map_err(|e| anyhow!("{e}"))?
    .label("methods by cost")
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE));
    c.draw_series(LineSeries::new(
        curve.iter().filter_map(|p| p.2.map(|v| (p.0, v))),
        RED.stroke_width(2),
    ))
    .map_err(|e| anyhow!("{e}"))?
    .label("paper's threshold rule, exact allocation")
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
    let published: Vec<(f64, f64)> = f
        .published
        .sweep_days
        .iter()
        .zip(&f.published.sweep_total_dv_mps)
        .map(|(&d, &v)| (d, v))
        .collect();
    if !published.is_empty() {
        c.draw_series(
            published
                .iter()
                .map(|&p| Cross::new(p, 6, BLACK.stroke_width(2))),
        )
        .map_err(|e| anyhow!("{e}"))?
        .label("published (paper's GA)")
        .legend(|(x, y)| Cross::new((x + 10, y), 6, BLACK));
    }
    c.configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE)
        .draw()
        .map_err(|e| anyhow!("{e}"))?;
    root.present().map_err(|e| anyhow!("{e}"))?;
    Ok(curve)
}
