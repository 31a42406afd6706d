//! Pictures of plans (plotters, SVG).
//!
//! * Planner A: the trajectories in the three plane projections with the LGL nodes and the
//!   Gaussian test points marked; the separation of every pair over time with the keep-out
//!   distance; the controls per axis with the bound.
//! * Planner B: the relative motion in the chief's local frame (radial / along-track / normal)
//!   of the initial and the target formation, with the impulse points marked.

use anyhow::{anyhow, Result};
use plotters::prelude::*;
use reconfig_core::{impulsive, pseudospectral};
use std::path::Path;

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
/// solution at the LGL nodes of degree `problem.degree`. Used by `reconfig plot --guess` to
/// draw a problem when no solver result is at hand; its status stays `Unsolved`.
pub fn unconstrained_guess(problem: &pseudospectral::Problem) -> pseudospectral::Solution {
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

/// Orbital state of mean elements propagated by `dt_s` seconds with the J2 secular rates
/// (Wang 2018 eq. 4), as an ECI position, km.
/// Earth's gravitational parameter, km^3/s^2 (as in SPEC.md).
const EARTH_MU_KM3_S2: f64 = 398_600.441_8;

fn eci_position_km(el: &impulsive::MeanElements, dt_s: f64) -> [f64; 3] {
    const RE: f64 = 6378.137;
    const J2: f64 = 1.08263e-3;
    let (a, e, i) = (el.sma_km, el.ecc, el.inc_rad);
    let n = (EARTH_MU_KM3_S2 / a.powi(3)).sqrt();
    let eta = (1.0 - e * e).sqrt();
    let c =
        3.0 * J2 * RE * RE / (2.0 * (1.0 - e * e).powi(2)) * (EARTH_MU_KM3_S2 / a.powi(7)).sqrt();
    let raan = el.raan_rad - c * i.cos() * dt_s;
    let argp = el.argp_rad + c / 2.0 * (5.0 * i.cos().powi(2) - 1.0) * dt_s;
    let m = el.mean_anomaly_rad + (n + c / 2.0 * eta * (3.0 * i.cos().powi(2) - 1.0)) * dt_s;
    // Kepler's equation.
    let mut ea = m;
    for _ in 0..30 {
        ea -= (ea - e * ea.sin() - m) / (1.0 - e * ea.cos());
    }
    let f = 2.0 * ((1.0 + e).sqrt() * (ea / 2.0).sin()).atan2((1.0 - e).sqrt() * (ea / 2.0).cos());
    let r = a * (1.0 - e * ea.cos());
    let u = argp + f;
    let (so, co) = raan.sin_cos();
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
fn rtn_km(
    chief: &impulsive::MeanElements,
    deputy: &impulsive::MeanElements,
    dt_s: f64,
) -> [f64; 3] {
    let rc = eci_position_km(chief, dt_s);
    let rd = eci_position_km(deputy, dt_s);
    // Chief velocity direction by a finite difference (the frame needs only directions).
    let rc2 = eci_position_km(chief, dt_s + 1e-3);
    let v = [rc2[0] - rc[0], rc2[1] - rc[1], rc2[2] - rc[2]];
    let norm = |x: [f64; 3]| (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    let unit = |x: [f64; 3]| {
        let n = norm(x);
        [x[0] / n, x[1] / n, x[2] / n]
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let r_hat = unit(rc);
    let n_hat = unit(cross(rc, v));
    let t_hat = cross(n_hat, r_hat);
    let d = [rd[0] - rc[0], rd[1] - rc[1], rd[2] - rc[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    [dot(d, r_hat), dot(d, t_hat), dot(d, n_hat)]
}

/// Draw a planner-B problem: one orbit of the initial and of the target formation in the
/// chief's RTN frame (three projections), with the impulse points of a fixed plan marked on the
/// initial formation's relative orbit at their arguments of latitude.
pub fn impulsive_svg(problem: &impulsive::Problem, title: &str, out: &Path) -> Result<()> {
    let chief = &problem.chief;
    let period = 2.0 * std::f64::consts::PI * (chief.sma_km.powi(3) / EARTH_MU_KM3_S2).sqrt();
    let samples = 600;
    let orbit = |rel: &impulsive::RelativeElements| -> Vec<[f64; 3]> {
        let dep = add(chief, rel);
        (0..=samples)
            .map(|k| rtn_km(chief, &dep, period * k as f64 / samples as f64))
            .map(|p| [p[0] * 1e3, p[1] * 1e3, p[2] * 1e3])
            .collect()
    };
    let initial = orbit(&problem.initial);
    let target = orbit(&problem.target);
    // Impulse points: the time in the first orbit at which the chief's mean argument of
    // latitude equals u_k (the point's revolutions move it by whole orbits only).
    let mut marks = Vec::new();
    if let impulsive::ImpulsePlan::Fixed(points) = &problem.plan {
        let n = (EARTH_MU_KM3_S2 / chief.sma_km.powi(3)).sqrt();
        for p in points {
            let u0 = chief.argp_rad + chief.mean_anomaly_rad;
            let du = (p.arg_latitude_rad - u0).rem_euclid(2.0 * std::f64::consts::PI);
            let dep = add(chief, &problem.initial);
            let q = rtn_km(chief, &dep, du / n);
            marks.push([q[0] * 1e3, q[1] * 1e3, q[2] * 1e3]);
        }
    }
    let root = SVGBackend::new(out, (1500, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let panels = root.split_evenly((1, 3));
    let names = ["radial (m)", "along-track (m)", "normal (m)"];
    let err = |e: &dyn std::fmt::Display| anyhow!("plot: {e}");
    for (panel, (a, b)) in panels.iter().zip([(1usize, 0usize), (1, 2), (0, 2)]) {
        let all = initial.iter().chain(&target).chain(&marks);
        let (x0, x1) = range(all.clone().map(|p| p[a]), 0.08);
        let (y0, y1) = range(all.map(|p| p[b]), 0.08);
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("{} vs {}", names[b], names[a]), ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(55)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc(names[a])
            .y_desc(names[b])
            .light_line_style(WHITE)
            .draw()
            .map_err(|e| err(&e))?;
        chart
            .draw_series(LineSeries::new(
                initial.iter().map(|p| (p[a], p[b])),
                color(0).stroke_width(2),
            ))
            .map_err(|e| err(&e))?
            .label("initial formation")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], color(0).stroke_width(2)));
        chart
            .draw_series(LineSeries::new(
                target.iter().map(|p| (p[a], p[b])),
                color(1).stroke_width(2),
            ))
            .map_err(|e| err(&e))?
            .label("target formation")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], color(1).stroke_width(2)));
        chart
            .draw_series(
                marks
                    .iter()
                    .map(|p| TriangleMarker::new((p[a], p[b]), 8, RED.filled())),
            )
            .map_err(|e| err(&e))?
            .label("impulse points (at u_k)")
            .legend(|(x, y)| TriangleMarker::new((x + 7, y), 6, RED.filled()));
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 12))
            .draw()
            .map_err(|e| err(&e))?;
    }
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

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
