//! LEO tour plots: Δv per arc (against the published values when the fixture has them) and
//! each arc's relative geometry, the chaser seen from the client it goes to, sampled by flying
//! both through the plan in the core's planning model (`reconfig_core::leo_tour::propagate`,
//! each burn's inertial Δv added at its epoch).

use crate::drivers::leo_tour::{plan, prepare, PlannedArc};
use crate::fixture::leo_tour::LeoTourFixture;
use crate::plot::{chart, range};
use crate::truth::propagate::EciState;
use anyhow::{anyhow, Result};
use plotters::prelude::*;
use reconfig_core::leo_tour::j2::State;
use reconfig_core::leo_tour::{propagate, Settings};
use std::path::Path;

/// The chaser relative to the client at one epoch, in the client's curvilinear frame, km:
/// radial (difference of the radii), along-track (the client's radius times the angle from the
/// client to the chaser's projection on the client's plane, positive ahead), cross-track
/// (the chaser's height above the client's plane).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Relative {
    /// From the arc start, h.
    pub t_h: f64,
    /// Radial, km.
    pub radial_km: f64,
    /// Along-track, km.
    pub along_km: f64,
    /// Cross-track, km.
    pub cross_km: f64,
    /// Whether a burn follows at this epoch (the next point is after it).
    pub before_burn: bool,
}

fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm3(a: &[f64; 3]) -> f64 {
    dot3(a, a).sqrt()
}

/// `chaser` relative to `client` (see [`Relative`]), at `t_h`; the along-track angle is
/// taken in `(-π, π]`, or, given the `previous` point's, the turn closest to it (so that a
/// track stays continuous where the chaser laps the client).
pub fn relative(t_h: f64, chaser: &State, client: &State, previous: Option<&Relative>) -> Relative {
    let rc = [chaser[0], chaser[1], chaser[2]];
    let client = EciState {
        pos_km: [client[0], client[1], client[2]],
        vel_km_s: [client[3], client[4], client[5]],
    };
    let [ir, it, ih] = client.rtn_axes();
    let cross_km = dot3(&rc, &ih);
    let rtn = norm3(&client.pos_km);
    // Signed angle from the client's radial direction to the chaser's projection on the
    // client's plane, about the orbit normal.
    let mut angle = dot3(&rc, &it).atan2(dot3(&rc, &ir));
    if let Some(p) = previous {
        let turns = ((p.along_km / rtn - angle) / std::f64::consts::TAU).round();
        angle += turns * std::f64::consts::TAU;
    }
    Relative {
        t_h,
        radial_km: norm3(&rc) - rtn,
        along_km: rtn * angle,
        cross_km,
        before_burn: false,
    }
}

/// The chaser relative to the client through `arc`'s plan, flown in the planning model of
/// `settings`: `samples` even steps over the arc plus every burn (before and after it).
///
/// # Errors
/// A state the planning model cannot fly.
pub fn arc_geometry(
    arc: &PlannedArc,
    settings: &Settings,
    samples: usize,
) -> Result<Vec<Relative>> {
    let s = &arc.solution;
    let duration = arc.problem.duration_s;
    let n = samples.max(2);
    let mut events: Vec<(f64, Option<[f64; 3]>)> = (0..=n)
        .map(|k| (duration * k as f64 / n as f64, None))
        .collect();
    events.extend(
        s.burns
            .iter()
            .take(usize::from(s.impulses))
            .map(|b| (b.epoch_s, Some(b.dv_km_s))),
    );
    // Burns after the even sample of the same epoch.
    events.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.is_some().cmp(&b.1.is_some())));
    let fly = |x: &State, dt: f64| -> Result<State> {
        if dt <= 0.0 {
            return Ok(*x);
        }
        propagate(settings, x, dt).ok_or_else(|| anyhow!("cannot fly {dt} s from {x:?}"))
    };
    let (mut chaser, mut client) = (arc.problem.from, arc.problem.to);
    let mut t = 0.0;
    // (t, chaser, client, a burn follows), forward in time.
    let mut states = Vec::with_capacity(events.len() + 4);
    for (at, burn) in events {
        chaser = fly(&chaser, at - t)?;
        client = fly(&client, at - t)?;
        t = at;
        states.push((t, chaser, client, burn.is_some()));
        if let Some(dv) = burn {
            for k in 0..3 {
                chaser[3 + k] += dv[k];
            }
            states.push((t, chaser, client, false));
        }
    }
    // Unwrapped from the arrival backwards, so the rendezvous is at along-track 0 even when the
    // chaser laps the client during the arc.
    let mut out: Vec<Relative> = Vec::with_capacity(states.len());
    for (t, chaser, client, before_burn) in states.iter().rev() {
        let here = relative(t / 3600.0, chaser, client, out.last());
        out.push(Relative {
            before_burn: *before_burn,
            ..here
        });
    }
    out.reverse();
    Ok(out)
}

/// What [`tour_svg`] drew: per arc its label, Δv and the published Δv, and its geometry.
pub struct TourPlot {
    /// The fixture as planned (order and durations chosen).
    pub fixture: LeoTourFixture,
    /// The planned arcs.
    pub arcs: Vec<PlannedArc>,
    /// Each arc's relative geometry.
    pub geometry: Vec<Vec<Relative>>,
}

/// One panel of an arc: the relative track projected by `xy`, its burns marked in red.
fn track_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    (x_desc, y_desc): (&str, &str),
    pts: &[Relative],
    xy: impl Fn(&Relative) -> (f64, f64),
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let (x0, x1) = range(pts.iter().map(|p| xy(p).0), 0.05);
    let (y0, y1) = range(pts.iter().map(|p| xy(p).1), 0.05);
    let mut c = chart(
        area,
        Some((caption, 15)),
        (8, 30, 60),
        (x0..x1, y0..y1),
        (x_desc, y_desc),
    )?;
    c.draw_series(LineSeries::new(pts.iter().map(&xy), BLUE.stroke_width(1)))
        .map_err(|e| anyhow!("{e}"))?;
    c.draw_series(
        pts.iter()
            .filter(|p| p.before_burn)
            .map(|p| Circle::new(xy(p), 4, RED.filled())),
    )
    .map_err(|e| anyhow!("{e}"))?;
    Ok(())
}

/// Plan the fixture (its order and durations chosen first when it asks; its requests answered
/// under the built-in limits) and draw Δv per arc and each arc's relative geometry into `out`
/// (SVG).
///
/// # Errors
/// A request refused or rejected, an arc it cannot plan, or a drawing error.
pub fn tour_svg(f: &LeoTourFixture, out: &Path) -> Result<TourPlot> {
    let limits = reconfig_core::limits::Limits::default();
    let fixture = prepare(f, &limits)?.fixture;
    let arcs = plan(&fixture, &limits)?;
    let geometry = arcs
        .iter()
        .map(|a| arc_geometry(a, &fixture.settings, 600))
        .collect::<Result<Vec<_>>>()?;
    let rows = arcs.len();
    let height = 380 + 300 * u32::try_from(rows)?;
    let root = SVGBackend::new(out, (1400, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let (top, rest) = root.split_vertically(380);
    dv_chart(&top, &fixture, &arcs)?;
    for ((area, arc), pts) in rest
        .split_evenly((rows.max(1), 1))
        .iter()
        .zip(&arcs)
        .zip(&geometry)
    {
        let (left, right) = area.split_horizontally(700);
        let label = format!(
            "arc {} -> {}: {:.3} m/s, {:.1} h",
            arc.from + 1,
            arc.to + 1,
            arc.solution.total_dv_mps,
            arc.problem.duration_s / 3600.0
        );
        track_panel(
            &left,
            &format!("{label}: chaser seen from client {}", arc.to + 1),
            ("along-track [km]", "radial [km]"),
            pts,
            |p| (p.along_km, p.radial_km),
        )?;
        track_panel(
            &right,
            "cross-track (burns in red)",
            ("time from the arc start [h]", "cross-track [km]"),
            pts,
            |p| (p.t_h, p.cross_km),
        )?;
    }
    root.present().map_err(|e| anyhow!("{e}"))?;
    Ok(TourPlot {
        fixture,
        arcs,
        geometry,
    })
}

/// Δv per arc, ours beside the published value when the fixture has one.
fn dv_chart(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    f: &LeoTourFixture,
    arcs: &[PlannedArc],
) -> Result<()> {
    let total: f64 = arcs.iter().map(|a| a.solution.total_dv_mps).sum();
    let published = f
        .published
        .total_dv_mps
        .map_or(String::new(), |p| format!(" (published {p:.3})"));
    let order: Vec<String> = f.order.iter().map(|k| (k + 1).to_string()).collect();
    let top = arcs
        .iter()
        .map(|a| a.solution.total_dv_mps)
        .chain(f.published.arc_dv_mps.iter().copied())
        .fold(0.0, f64::max)
        * 1.1;
    let n = arcs.len();
    let mut c = ChartBuilder::on(area)
        .caption(
            format!(
                "{}: order {}, total dv {total:.3} m/s{published}; blue ours, grey published",
                f.name,
                order.join(" -> ")
            ),
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..n as f64, 0.0..top.max(1.0))
        .map_err(|e| anyhow!("{e}"))?;
    c.configure_mesh()
        .disable_x_mesh()
        .x_labels(0)
        .y_desc("dv per arc [m/s]")
        .draw()
        .map_err(|e| anyhow!("{e}"))?;
    c.draw_series(arcs.iter().enumerate().map(|(k, a)| {
        Text::new(
            format!(
                "{} -> {}: {:.3}",
                a.from + 1,
                a.to + 1,
                a.solution.total_dv_mps
            ),
            (k as f64 + 0.1, a.solution.total_dv_mps + 0.02 * top),
            ("sans-serif", 14),
        )
    }))
    .map_err(|e| anyhow!("{e}"))?;
    c.draw_series(arcs.iter().enumerate().map(|(k, a)| {
        let x = k as f64;
        Rectangle::new(
            [(x + 0.1, 0.0), (x + 0.48, a.solution.total_dv_mps)],
            BLUE.filled(),
        )
    }))
    .map_err(|e| anyhow!("{e}"))?;
    c.draw_series(
        f.published
            .arc_dv_mps
            .iter()
            .take(n)
            .enumerate()
            .map(|(k, &p)| {
                let x = k as f64;
                Rectangle::new(
                    [(x + 0.52, 0.0), (x + 0.9, p)],
                    RGBColor(160, 160, 160).filled(),
                )
            }),
    )
    .map_err(|e| anyhow!("{e}"))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_relative_frame_measures_along_track_radial_and_cross_track() {
        // Client on the x axis moving along +y (orbit normal +z).
        let r = 7000.0;
        let client: State = [r, 0.0, 0.0, 0.0, 7.5, 0.0];
        // 0.01 rad ahead, 2 km higher, 3 km above the plane.
        let d = 0.01_f64;
        let chaser: State = [(r + 2.0) * d.cos(), (r + 2.0) * d.sin(), 3.0, 0.0, 7.5, 0.0];
        let p = relative(1.0, &chaser, &client, None);
        let radial = (((r + 2.0) * (r + 2.0)) + 9.0).sqrt() - r;
        assert!((p.radial_km - radial).abs() < 1e-9, "{p:?}");
        assert!((p.along_km - r * d).abs() < 1e-9, "{p:?}");
        assert!((p.cross_km - 3.0).abs() < 1e-12, "{p:?}");
        // Behind is negative; across the far side, the turn nearest the previous point.
        let behind: State = [r * d.cos(), -r * d.sin(), 0.0, 0.0, 7.5, 0.0];
        assert!((relative(0.0, &behind, &client, None).along_km + r * d).abs() < 1e-9);
        let far: State = [-r, -1.0, 0.0, 0.0, 7.5, 0.0];
        let wrapped = relative(0.0, &far, &client, None).along_km;
        assert!(wrapped < -3.0 * r, "{wrapped}");
        let previous = Relative {
            along_km: 3.1 * r,
            ..p
        };
        let unwrapped = relative(0.0, &far, &client, Some(&previous)).along_km;
        assert!((unwrapped - wrapped - std::f64::consts::TAU * r).abs() < 1e-6);
    }
}
