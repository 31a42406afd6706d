//! The planner-A plot: trajectories in the three plane projections with the LGL nodes and the
//! Gaussian test points, pair separations over time with the keep-out distance, the controls
//! per axis with the bound; and the initial guesses drawn for comparison.

use super::{color, dist, range};
use anyhow::{anyhow, Result};
use plotters::prelude::*;
use reconfig_core::pseudospectral;
use std::path::Path;

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
        // The three axes' interpolants at every sample time.
        let sampled = |axes: &[Vec<f64>]| -> Vec<[f64; 3]> {
            t.iter()
                .map(|&x| std::array::from_fn(|a| interp.eval(&axes[a], x)))
                .collect()
        };
        pos.push(sampled(&axes_p));
        ctrl.push(sampled(&axes_u));
    }
    Sampled { t, pos, ctrl }
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
    s.min_separation_lu = best.0.is_finite().then_some(best.0);
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
