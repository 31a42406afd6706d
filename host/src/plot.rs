//! Pictures of plans (plotters, SVG).
//!
//! * Planner A: the trajectories in the three plane projections with the LGL nodes and the
//!   Gaussian test points marked; the separation of every pair over time with the keep-out
//!   distance; the controls per axis with the bound.
//! * Planner B: the deputy's relative motion in the chief's local frame (radial / along-track /
//!   normal) under the plan, with the impulses marked and their dv drawn, over the initial and
//!   the target formation; the three components over time.

use anyhow::{anyhow, Result};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use reconfig_core::{impulsive, pseudospectral};
use std::path::Path;

const GOLD: RGBColor = RGBColor(255, 200, 0);

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

fn color(i: usize) -> RGBColor {
    COLORS[i % COLORS.len()]
}

/// Barycentric Lagrange interpolation through the first `n` nodes (Berrut & Trefethen 2004).
pub struct Interpolant {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl Interpolant {
    /// Build from node times.
    pub fn new(nodes: &[f64]) -> Self {
        let weights = nodes
            .iter()
            .enumerate()
            .map(|(j, &xj)| {
                let p: f64 = nodes
                    .iter()
                    .enumerate()
                    .filter(|(k, _)| *k != j)
                    .map(|(_, &xk)| xj - xk)
                    .product();
                1.0 / p
            })
            .collect();
        Self {
            nodes: nodes.to_vec(),
            weights,
        }
    }

    /// The interpolating polynomial of `values` at `x`.
    pub fn eval(&self, values: &[f64], x: f64) -> f64 {
        let mut num = 0.0;
        let mut den = 0.0;
        for ((&xj, &wj), &fj) in self.nodes.iter().zip(&self.weights).zip(values) {
            let d = x - xj;
            if d == 0.0 {
                return fj;
            }
            num += wj / d * fj;
            den += wj / d;
        }
        num / den
    }
}

/// Sampled planner-A trajectories: per spacecraft, (t, [x, y, z], [ux, uy, uz]).
struct Sampled {
    t: Vec<f64>,
    pos: Vec<Vec<[f64; 3]>>,
    ctrl: Vec<Vec<[f64; 3]>>,
}

fn sample(s: &pseudospectral::Solution, samples: usize) -> Sampled {
    let n = usize::from(s.degree) + 1;
    let m = usize::from(s.spacecraft_count);
    let interp = Interpolant::new(&s.node_times_tu[..n]);
    let t: Vec<f64> = (0..=samples)
        .map(|k| s.horizon_tu * k as f64 / samples as f64)
        .collect();
    let series = |f: &dyn Fn(usize) -> f64| -> Vec<f64> { (0..n).map(f).collect() };
    let mut pos = Vec::new();
    let mut ctrl = Vec::new();
    for i in 0..m {
        let axes_p: Vec<Vec<f64>> = (0..3).map(|a| series(&|h| s.states[i][h][a])).collect();
        let axes_u: Vec<Vec<f64>> = (0..3)
            .map(|a| series(&|h| s.controls_fu[i][h][a]))
            .collect();
        pos.push(
            t.iter()
                .map(|&x| {
                    [
                        interp.eval(&axes_p[0], x),
                        interp.eval(&axes_p[1], x),
                        interp.eval(&axes_p[2], x),
                    ]
                })
                .collect(),
        );
        ctrl.push(
            t.iter()
                .map(|&x| {
                    [
                        interp.eval(&axes_u[0], x),
                        interp.eval(&axes_u[1], x),
                        interp.eval(&axes_u[2], x),
                    ]
                })
                .collect(),
        );
    }
    Sampled { t, pos, ctrl }
}

fn range(values: impl Iterator<Item = f64>, pad: f64) -> (f64, f64) {
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

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Draw a planner-A solution of `problem` to an SVG file.
pub fn pseudospectral_svg(
    problem: &pseudospectral::Problem,
    s: &pseudospectral::Solution,
    title: &str,
    out: &Path,
) -> Result<()> {
    let m = usize::from(s.spacecraft_count);
    let n = usize::from(s.degree) + 1;
    if m == 0 || n < 2 {
        return Err(anyhow!("the solution has no trajectories to draw"));
    }
    let sm = sample(s, 400);
    let root = SVGBackend::new(out, (1500, 1000)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let (top, bottom) = root.split_vertically(500);
    let top_panels = top.split_evenly((1, 3));
    let bottom_panels = bottom.split_evenly((1, 4));
    let err = |e: &dyn std::fmt::Display| anyhow!("plot: {e}");

    // Projections with nodes and test points.
    let all = |a: usize| sm.pos.iter().flat_map(move |p| p.iter().map(move |q| q[a]));
    for (panel, (a, b, name)) in
        top_panels
            .iter()
            .zip([(0usize, 1usize, "x-y"), (0, 2, "x-z"), (1, 2, "y-z")])
    {
        let (x0, x1) = range(all(a), 0.08);
        let (y0, y1) = range(all(b), 0.08);
        let axis = ["x (LU)", "y (LU)", "z (LU)"];
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("trajectories, {name} plane"), ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(45)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc(axis[a])
            .y_desc(axis[b])
            .light_line_style(WHITE)
            .draw()
            .map_err(|e| err(&e))?;
        for i in 0..m {
            let c = color(i);
            chart
                .draw_series(LineSeries::new(
                    sm.pos[i].iter().map(|p| (p[a], p[b])),
                    c.stroke_width(2),
                ))
                .map_err(|e| err(&e))?
                .label(format!("sc {}", i + 1))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 15, y)], c.stroke_width(2))
                });
            chart
                .draw_series(
                    (0..n).map(|h| {
                        Circle::new((s.states[i][h][a], s.states[i][h][b]), 3, c.filled())
                    }),
                )
                .map_err(|e| err(&e))?;
            // Start (square) and end (triangle).
            let st = s.states[i][0];
            let en = s.states[i][n - 1];
            chart
                .draw_series([Rectangle::new(
                    [(st[a] - 0.15, st[b] - 0.15), (st[a] + 0.15, st[b] + 0.15)],
                    c.filled(),
                )])
                .map_err(|e| err(&e))?;
            chart
                .draw_series([TriangleMarker::new((en[a], en[b]), 7, c.filled())])
                .map_err(|e| err(&e))?;
        }
        // Test points exist only once a solve has placed them.
        if problem.test_points && s.info.status != pseudospectral::SolveStatus::Unsolved {
            let interp = Interpolant::new(&s.node_times_tu[..n]);
            let mut pair = 0;
            for i in 0..m {
                for j in i + 1..m {
                    for &t in s.test_point_times_tu.get(pair).map_or(&[][..], |v| &v[..]) {
                        for k in [i, j] {
                            let pa: Vec<f64> = (0..n).map(|h| s.states[k][h][a]).collect();
                            let pb: Vec<f64> = (0..n).map(|h| s.states[k][h][b]).collect();
                            let p = (interp.eval(&pa, t), interp.eval(&pb, t));
                            chart
                                .draw_series([Cross::new(p, 4, BLACK.stroke_width(1))])
                                .map_err(|e| err(&e))?;
                        }
                    }
                    pair += 1;
                }
            }
        }
        if a == 0 && b == 1 {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .label_font(("sans-serif", 12))
                .draw()
                .map_err(|e| err(&e))?;
        }
    }

    // Separation of every pair, keep-out line, test points.
    {
        type Curve = Vec<(f64, f64)>;
        let mut seps: Vec<((usize, usize), Curve)> = Vec::new();
        for i in 0..m {
            for j in i + 1..m {
                let v =
                    sm.t.iter()
                        .enumerate()
                        .map(|(k, &t)| (t, dist(sm.pos[i][k], sm.pos[j][k])))
                        .collect();
                seps.push(((i, j), v));
            }
        }
        let (_, y1) = range(
            seps.iter()
                .flat_map(|(_, v)| v.iter().map(|p| p.1))
                .chain([problem.keep_out_lu]),
            0.05,
        );
        let mut chart = ChartBuilder::on(&bottom_panels[0])
            .caption("pair separation", ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(45)
            .build_cartesian_2d(0.0..s.horizon_tu, 0.0..y1)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("t (TU)")
            .y_desc("separation (LU)")
            .light_line_style(WHITE)
            .draw()
            .map_err(|e| err(&e))?;
        for (k, ((i, j), v)) in seps.iter().enumerate() {
            let c = color(k);
            chart
                .draw_series(LineSeries::new(v.iter().copied(), c.stroke_width(2)))
                .map_err(|e| err(&e))?
                .label(format!("{}-{}", i + 1, j + 1))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 15, y)], c.stroke_width(2))
                });
        }
        chart
            .draw_series(LineSeries::new(
                [
                    (0.0, problem.keep_out_lu),
                    (s.horizon_tu, problem.keep_out_lu),
                ],
                RED.stroke_width(2),
            ))
            .map_err(|e| err(&e))?
            .label(format!("keep-out d = {}", problem.keep_out_lu))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], RED.stroke_width(2)));
        // Gaussian test points on each pair's separation curve.
        if problem.test_points && s.info.status != pseudospectral::SolveStatus::Unsolved {
            let interp = Interpolant::new(&s.node_times_tu[..n]);
            for (k, ((i, j), _)) in seps.iter().enumerate() {
                let at = |c: usize, t: f64| -> [f64; 3] {
                    let mut p = [0.0; 3];
                    for (a, v) in p.iter_mut().enumerate() {
                        let vals: Vec<f64> = (0..n).map(|h| s.states[c][h][a]).collect();
                        *v = interp.eval(&vals, t);
                    }
                    p
                };
                let times = s.test_point_times_tu.get(k).map_or(&[][..], |v| &v[..]);
                chart
                    .draw_series(times.iter().map(|&t| {
                        Cross::new((t, dist(at(*i, t), at(*j, t))), 4, BLACK.stroke_width(1))
                    }))
                    .map_err(|e| err(&e))?;
            }
        }
        // Nodes as ticks on the time axis.
        chart
            .draw_series(
                s.node_times_tu[..n]
                    .iter()
                    .map(|&t| Circle::new((t, 0.0), 3, BLACK.filled())),
            )
            .map_err(|e| err(&e))?;
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 11))
            .draw()
            .map_err(|e| err(&e))?;
    }

    // Controls per axis with the bound.
    let umax = problem.max_control_fu;
    for (a, panel) in bottom_panels[1..].iter().enumerate() {
        let (lo, hi) = range(
            sm.ctrl
                .iter()
                .flat_map(|c| c.iter().map(move |u| u[a]))
                .chain([umax, -umax]),
            0.08,
        );
        let mut chart = ChartBuilder::on(panel)
            .caption(
                format!("control u{}", ["x", "y", "z"][a]),
                ("sans-serif", 16),
            )
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(45)
            .build_cartesian_2d(0.0..s.horizon_tu, lo..hi)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("t (TU)")
            .y_desc("force (FU)")
            .light_line_style(WHITE)
            .draw()
            .map_err(|e| err(&e))?;
        for i in 0..m {
            chart
                .draw_series(LineSeries::new(
                    sm.t.iter().zip(&sm.ctrl[i]).map(|(&t, u)| (t, u[a])),
                    color(i).stroke_width(2),
                ))
                .map_err(|e| err(&e))?;
            chart
                .draw_series((0..n).map(|h| {
                    Circle::new(
                        (s.node_times_tu[h], s.controls_fu[i][h][a]),
                        3,
                        color(i).filled(),
                    )
                }))
                .map_err(|e| err(&e))?;
        }
        for bound in [umax, -umax] {
            chart
                .draw_series(LineSeries::new(
                    [(0.0, bound), (s.horizon_tu, bound)],
                    RED.stroke_width(2),
                ))
                .map_err(|e| err(&e))?;
        }
    }
    root.present()?;
    Ok(())
}

/// LGL nodes on [-1, 1]: the ends and the zeros of `L_N'` (Newton on the Chebyshev-Gauss-Lobatto
/// guess; host-side only, for drawing a guess when no solver is at hand).
pub fn lgl_nodes(n: usize) -> Vec<f64> {
    let mut x: Vec<f64> = (0..=n)
        .map(|k| -(std::f64::consts::PI * k as f64 / n as f64).cos())
        .collect();
    for _ in 0..100 {
        let mut change: f64 = 0.0;
        for xk in x.iter_mut() {
            // Legendre recurrences: P_{N-1}, P_N at xk.
            let (mut p0, mut p1) = (1.0, *xk);
            for j in 2..=n {
                let p2 = ((2 * j - 1) as f64 * *xk * p1 - (j - 1) as f64 * p0) / j as f64;
                p0 = p1;
                p1 = p2;
            }
            let step = (*xk * p1 - p0) / ((n + 1) as f64 * p1);
            *xk -= step;
            change = change.max(step.abs());
        }
        if change < 1e-15 {
            break;
        }
    }
    x
}

/// The minimum-energy trajectory without keep-out and without control bounds (a cubic per
/// axis through the boundary states, Huang 2012 eq. 24 with the bound inactive), written as a
/// solution at the LGL nodes of degree `problem.degree`, with its least separation (sampled).
/// Used by `reconfig plot --guess` to draw a problem when no solver result is at hand (the
/// solver may have rejected it); its status stays `Unsolved`.
pub fn unconstrained_guess(problem: &pseudospectral::Problem) -> pseudospectral::Solution {
    let mut s = cubic_at_nodes(problem);
    // Least separation on a fine grid.
    let sm = sample(&s, 2000);
    let mut best = (f64::INFINITY, (0u8, 0u8), 0.0);
    for i in 0..sm.pos.len() {
        for j in i + 1..sm.pos.len() {
            for (k, &t) in sm.t.iter().enumerate() {
                let d = dist(sm.pos[i][k], sm.pos[j][k]);
                if d < best.0 {
                    best = (d, (i as u8, j as u8), t);
                }
            }
        }
    }
    s.min_separation_lu = best.0;
    s.min_separation_pair = best.1;
    s.min_separation_time_tu = best.2;
    s
}

/// The unconstrained cubics' states, controls and cost at the LGL nodes of degree
/// `problem.degree` (no separation search). Also the Monte Carlo's unperturbed guess.
pub fn cubic_at_nodes(problem: &pseudospectral::Problem) -> pseudospectral::Solution {
    let mut s = pseudospectral::Solution::new();
    let n = usize::from(problem.degree).clamp(2, reconfig_core::capacity::MAX_DEGREE);
    let t_end = problem.horizon_tu;
    s.degree = n as u16;
    s.spacecraft_count = problem.spacecraft.len() as u8;
    s.horizon_tu = t_end;
    let nodes = lgl_nodes(n);
    for (h, tau) in nodes.iter().enumerate() {
        s.node_times_tu[h] = t_end / 2.0 * (tau + 1.0);
    }
    let mut cost = 0.0;
    for (i, c) in problem.spacecraft.iter().enumerate() {
        for a in 0..3 {
            let (x0, v0) = (c.initial_state[a], c.initial_state[a + 3]);
            let (x1, v1) = (c.final_state[a], c.final_state[a + 3]);
            // x(t) = x0 + v0 t + c2 t^2 + c3 t^3 meeting x1, v1 at T.
            let d = x1 - x0 - v0 * t_end;
            let dv = v1 - v0;
            let c3 = (dv * t_end - 2.0 * d) / t_end.powi(3);
            let c2 = (d - c3 * t_end.powi(3)) / t_end.powi(2);
            for h in 0..=n {
                let t = s.node_times_tu[h];
                s.states[i][h][a] = x0 + v0 * t + c2 * t * t + c3 * t.powi(3);
                s.states[i][h][a + 3] = v0 + 2.0 * c2 * t + 3.0 * c3 * t * t;
                s.controls_fu[i][h][a] = c.mass_mu * (2.0 * c2 + 6.0 * c3 * t);
            }
            // 1/2 int_0^T (m (2 c2 + 6 c3 t))^2 dt
            let m2 = c.mass_mu * c.mass_mu;
            cost += 0.5
                * m2
                * (4.0 * c2 * c2 * t_end
                    + 12.0 * c2 * c3 * t_end * t_end
                    + 12.0 * c3 * c3 * t_end.powi(3));
        }
    }
    s.cost = cost;
    s
}

/// Earth's gravitational parameter, km^3/s^2 (as in SPEC.md).
const EARTH_MU_KM3_S2: f64 = 398_600.441_8;

/// Mean elements propagated by `dt_s` seconds with the J2 secular rates (Wang 2018 eq. 4).
fn drifted(el: &impulsive::MeanElements, dt_s: f64) -> impulsive::MeanElements {
    const RE: f64 = 6378.137;
    const J2: f64 = 1.08263e-3;
    let (a, e, i) = (el.sma_km, el.ecc, el.inc_rad);
    let n = (EARTH_MU_KM3_S2 / a.powi(3)).sqrt();
    let eta = (1.0 - e * e).sqrt();
    let c =
        3.0 * J2 * RE * RE / (2.0 * (1.0 - e * e).powi(2)) * (EARTH_MU_KM3_S2 / a.powi(7)).sqrt();
    impulsive::MeanElements {
        raan_rad: el.raan_rad - c * i.cos() * dt_s,
        argp_rad: el.argp_rad + c / 2.0 * (5.0 * i.cos().powi(2) - 1.0) * dt_s,
        mean_anomaly_rad: el.mean_anomaly_rad
            + (n + c / 2.0 * eta * (3.0 * i.cos().powi(2) - 1.0)) * dt_s,
        ..*el
    }
}

/// Orbital state of mean elements propagated by `dt_s` seconds with the J2 secular rates, as an
/// ECI position (the mean elements taken as two-body elements), km.
fn eci_position_km(el: &impulsive::MeanElements, dt_s: f64) -> [f64; 3] {
    let el = drifted(el, dt_s);
    let (e, i, m) = (el.ecc, el.inc_rad, el.mean_anomaly_rad);
    // Kepler's equation.
    let mut ea = m;
    for _ in 0..30 {
        ea -= (ea - e * ea.sin() - m) / (1.0 - e * ea.cos());
    }
    let f = 2.0 * ((1.0 + e).sqrt() * (ea / 2.0).sin()).atan2((1.0 - e).sqrt() * (ea / 2.0).cos());
    let r = el.sma_km * (1.0 - e * ea.cos());
    let u = el.argp_rad + f;
    let (so, co) = el.raan_rad.sin_cos();
    let (su, cu) = u.sin_cos();
    let (si, ci) = i.sin_cos();
    [
        r * (co * cu - so * su * ci),
        r * (so * cu + co * su * ci),
        r * su * si,
    ]
}

fn add(el: &impulsive::MeanElements, d: &impulsive::RelativeElements) -> impulsive::MeanElements {
    impulsive::MeanElements {
        sma_km: el.sma_km + d.dsma_km,
        ecc: el.ecc + d.decc,
        inc_rad: el.inc_rad + d.dinc_rad,
        raan_rad: el.raan_rad + d.draan_rad,
        argp_rad: el.argp_rad + d.dargp_rad,
        mean_anomaly_rad: el.mean_anomaly_rad + d.dmean_anomaly_rad,
    }
}

/// Deputy relative position in the chief's RTN frame at `dt_s`, km: (radial, along, normal).
///
/// The frame is the chief's two-body one at that instant (radial unit vector, orbit normal of
/// its drifted elements, along-track = normal x radial), as in the core's
/// `impulsive::relative_position_rtn_km`, so the formation curves and the planned trajectory
/// agree.
fn rtn_km(
    chief: &impulsive::MeanElements,
    deputy: &impulsive::MeanElements,
    dt_s: f64,
) -> [f64; 3] {
    let rc = eci_position_km(chief, dt_s);
    let rd = eci_position_km(deputy, dt_s);
    let c = drifted(chief, dt_s);
    let (so, co) = c.raan_rad.sin_cos();
    let (si, ci) = c.inc_rad.sin_cos();
    let n_hat = [so * si, -co * si, ci];
    let norm = (rc[0] * rc[0] + rc[1] * rc[1] + rc[2] * rc[2]).sqrt();
    let r_hat = [rc[0] / norm, rc[1] / norm, rc[2] / norm];
    let t_hat = [
        n_hat[1] * r_hat[2] - n_hat[2] * r_hat[1],
        n_hat[2] * r_hat[0] - n_hat[0] * r_hat[2],
        n_hat[0] * r_hat[1] - n_hat[1] * r_hat[0],
    ];
    let d = [rd[0] - rc[0], rd[1] - rc[1], rd[2] - rc[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    [dot(d, r_hat), dot(d, t_hat), dot(d, n_hat)]
}

/// The chief's Keplerian period, s.
fn chief_period_s(problem: &impulsive::Problem) -> f64 {
    2.0 * std::f64::consts::PI * (problem.chief.sma_km.powi(3) / EARTH_MU_KM3_S2).sqrt()
}

/// One orbit of the formation with relative elements `rel` at `t0_s` (both spacecraft then
/// drifting with their own J2 rates, no impulses), chief's RTN frame, m.
fn formation_m(
    problem: &impulsive::Problem,
    rel: &impulsive::RelativeElements,
    t0_s: f64,
    samples: usize,
) -> Vec<[f64; 3]> {
    let chief = drifted(&problem.chief, t0_s);
    let dep = add(&chief, rel);
    let period = chief_period_s(problem);
    (0..=samples)
        .map(|k| rtn_km(&chief, &dep, period * k as f64 / samples as f64))
        .map(|p| [p[0] * 1e3, p[1] * 1e3, p[2] * 1e3])
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
    let initial = formation_m(problem, &problem.initial, 0.0, 600);
    let target = formation_m(problem, &problem.target, solution.final_time_s, 600);
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
    // One colour per coast arc (at most MAX_IMPULSES + 1 = 7), none of the formations' two.
    const ARC_COLORS: [RGBColor; 7] = [
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(23, 190, 207),
        RGBColor(188, 189, 34),
    ];
    let arc_color = |k: usize| ARC_COLORS[k % ARC_COLORS.len()];
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
        chart
            .draw_series(DashedLineSeries::new(
                initial.iter().map(|p| (p[a], p[b])),
                6,
                4,
                faint(color(0)),
            ))
            .map_err(|e| err(&e))?
            .label("initial formation (t = 0)")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], faint(color(0))));
        chart
            .draw_series(DashedLineSeries::new(
                target.iter().map(|p| (p[a], p[b])),
                6,
                4,
                faint(color(1)),
            ))
            .map_err(|e| err(&e))?
            .label("target formation (at the last impulse)")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], faint(color(1))));
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
        let initial = add(&p.chief, &p.initial);
        let chief_n = drifted(&p.chief, tn);
        let target = add(&chief_n, &p.target);
        let mut checked = (0, 0);
        for (t, q) in &traj {
            let want = if *t < t1 {
                checked.0 += 1;
                rtn_km(&p.chief, &initial, *t)
            } else if *t > tn {
                checked.1 += 1;
                rtn_km(&chief_n, &target, *t - tn)
            } else {
                continue;
            };
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

    #[test]
    fn lgl_nodes_are_the_known_ones_for_n_4() {
        let x = lgl_nodes(4);
        let r = (3.0f64 / 7.0).sqrt();
        for (a, b) in x.iter().zip([-1.0, -r, 0.0, r, 1.0]) {
            assert!((a - b).abs() < 1e-14, "{a} {b}");
        }
    }

    #[test]
    fn interpolation_reproduces_a_cubic() {
        let nodes = lgl_nodes(6);
        let f = |x: f64| 1.0 - 2.0 * x + 0.5 * x.powi(3);
        let values: Vec<f64> = nodes.iter().map(|&x| f(x)).collect();
        let p = Interpolant::new(&nodes);
        for x in [-0.9, -0.3, 0.2, 0.77] {
            assert!((p.eval(&values, x) - f(x)).abs() < 1e-12);
        }
    }

    #[test]
    fn the_unconstrained_guess_has_the_rest_to_rest_cost() {
        // SPEC: without keep-out the Huang case costs 1/2 sum 12 D^2 / T^3 = 6.336.
        let craft = |a: [f64; 3], b: [f64; 3]| pseudospectral::Spacecraft {
            mass_mu: 1.0,
            initial_state: [a[0], a[1], a[2], 0.0, 0.0, 0.0],
            final_state: [b[0], b[1], b[2], 0.0, 0.0, 0.0],
        };
        let mut spacecraft = heapless::Vec::new();
        let _ = spacecraft.push(craft([0.0, 0.0, 0.0], [12.0, 12.0, 12.0]));
        let _ = spacecraft.push(craft([8.0, 0.0, 0.0], [0.0, 12.0, 12.0]));
        let _ = spacecraft.push(craft([8.0, 0.0, 8.0], [0.0, 12.0, 0.0]));
        let p = pseudospectral::Problem {
            horizon_tu: 10.0,
            max_control_fu: 1.0,
            keep_out_lu: 2.0,
            degree: 10,
            test_points: true,
            spacecraft,
        };
        let s = unconstrained_guess(&p);
        assert!((s.cost - 6.336).abs() < 1e-9, "{}", s.cost);
    }
}
