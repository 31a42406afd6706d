//! The per-arc descent: a bounded quasi-Newton search (BFGS) from the search's best refined
//! point, in the search model, on the cost with the last leg re-shot at every point, with
//! forward-difference gradients.
//!
//! Why: the compass search ([`super::arc`]) keeps the last leg's J2 offset frozen while it
//! moves and re-shoots after each sweep, so it settles where the frozen-offset cost is flat,
//! not the true one: the offset's own dependence on the variables is left out of every
//! comparison. On the held-out arcs 1000-1015 its plans were up to 5.4 % above an optimiser
//! restarted from them (`tests/oracle/leo_arc_optimum.py`), and a work budget 100 times larger
//! moved none of them (`leo_arc_campaign -- 1000 1016 400000000`): the gap was the search's
//! fixed point, not the budget. Re-shot at every point, the gradient is the true one; BFGS
//! then follows the coupled valleys of a three- or four-impulse plan (a burn's epoch and its
//! vector trade against each other) that a search along one variable at a time crawls.
//! In the search model a shooting costs mean-element flights, hundreds of times cheaper than
//! the planning model's RK4 (a descent there cost 3-10 times an arc's budget for little more).
//!
//! Each iteration: the gradient by forward differences (`nvars` evaluations, a backward one
//! where the forward point breaks the epochs' order or has no transfer), the step `-H g` (at most
//! [`MAX_STEP_SCALES`] of the variables' scales long), then a backtracking line search with
//! Armijo's rule (at most [`LINE_SEARCH_HALVINGS`] halvings). Every evaluation is a re-shot
//! point (the plan flown to its last leg, the last leg shot to `arrival_tol_km` from the
//! offset and the quasi-Newton matrix of the point it moves from, the cost). When the
//! quasi-Newton step finds no decrease, the gradient is tried once before the descent stops. Worst case
//! `max_iterations x (nvars + LINE_SEARCH_HALVINGS + 1) + nvars` re-shot evaluations, each
//! at most `shoot_max_iter` aim-point iterations, all charged to the meter, which stops it
//! first when smaller ([`super::work_units::DESCENT_ITERATION`] per iteration for its own
//! arithmetic).

use super::arc::{Ctx, Point};
use super::types::MAX_VARS;
use super::work_units;
use crate::indexed::IndexedExt as _;

/// Iterations of the descent after a search (chosen on the tuning seeds 0-39 of
/// `host/examples/leo_arc_campaign.rs`: 20, 40 and 60 gave the same plans within its share
/// of the budget; docs/leo-tour.md, "The descent").
pub(crate) const DESCENT_MAX_ITERATIONS: u32 = 40;

/// Forward-difference step of an epoch, s: the truncation error of a forward difference,
/// `h f''/2`, is ~0.03 % of the gradient for a cost that swings with the orbit's period, and
/// the shooting's miss tolerance (1 mm) moves the cost by far less than `h` times its slope.
const DIFF_STEP_S: f64 = 0.5;

/// Forward-difference step of a burn component, km/s (1 cm/s).
const DIFF_STEP_KM_S: f64 = 1e-5;

/// Halvings of the line search's step before the iteration gives up.
const LINE_SEARCH_HALVINGS: u32 = 10;

/// Armijo's sufficient-decrease fraction.
const ARMIJO: f64 = 1e-4;

/// The longest step, in scales of the variables (the compass polish's first steps: a
/// sixteenth of `search_step_s` and `search_step_km_s`).
const MAX_STEP_SCALES: f64 = 4.0;

/// A decrease below this, km/s (0.1 mm/s), ends the descent.
const MIN_DECREASE_KM_S: f64 = 1e-7;

/// A vector of the variables (or of a gradient, or a step) in the variables' scales.
type Scaled = [f64; MAX_VARS];

/// A matrix over the scaled variables.
type Matrix = [[f64; MAX_VARS]; MAX_VARS];

impl Ctx<'_> {
    /// The scales of the variables (the compass polish's first steps: an epoch's, a burn
    /// component's), and their forward-difference steps.
    fn descent_scales(&self) -> (Scaled, Scaled) {
        let epochs = self.impulses.saturating_sub(1);
        let (epoch_scale_s, component_scale_km_s) = self.polish_first_steps();
        let mut scales = [component_scale_km_s; MAX_VARS];
        let mut steps = [DIFF_STEP_KM_S; MAX_VARS];
        for (scale, step) in scales.iter_mut().zip(steps.iter_mut()).take(epochs) {
            *scale = epoch_scale_s;
            *step = DIFF_STEP_S;
        }
        (scales, steps)
    }

    /// `p` re-shot, its shooting started from the quasi-Newton matrix of `from`'s converged
    /// shooting (not the context's last one, which a failed shooting nearby may have reset):
    /// each evaluation starts from the same place whatever ran before it.
    fn reshoot_from(&mut self, p: &Point, from: &Point) -> Option<Point> {
        self.secant = from.secant;
        self.reshoot(p)
    }

    /// The gradient of the cost at `p` (the last leg re-shot at every point) in the variables'
    /// scales, or `None` when a variable can be moved neither way.
    fn scaled_gradient(
        &mut self,
        p: &Point,
        n: usize,
        (scales, steps): &(Scaled, Scaled),
    ) -> Option<Scaled> {
        let mut g = [0.0; MAX_VARS];
        let vars = g
            .iter_mut()
            .zip(scales.iter())
            .zip(steps.iter())
            .indexed()
            .take(n);
        for (i, ((gi, scale), h)) in vars {
            let mut forward = *p;
            *forward.x.get_mut(i)? += h;
            let slope = match self.reshoot_from(&forward, p) {
                Some(q) => (q.cost - p.cost) / h,
                None => {
                    let mut backward = *p;
                    *backward.x.get_mut(i)? -= h;
                    (p.cost - self.reshoot_from(&backward, p)?.cost) / h
                }
            };
            *gi = slope * scale;
        }
        g.iter().all(|v| v.is_finite()).then_some(g)
    }

    /// Bounded BFGS descent from `p` (a re-shot point: its cost is a plan that arrives), at most
    /// `max_iterations` iterations: the best re-shot point found (`p` itself when no step pays).
    pub fn descend(&mut self, p: Point, max_iterations: u32) -> Point {
        if !p.shot {
            return p;
        }
        let n = self.nvars().min(MAX_VARS);
        let scales = self.descent_scales();
        let mut best = p;
        let Some(mut g) = self.scaled_gradient(&best, n, &scales) else {
            return best;
        };
        // The inverse Hessian in the variables' scales, the identity at first.
        let mut h = identity();
        let mut first_update = true;
        for _ in 0..max_iterations {
            if !self.meter.spend(work_units::DESCENT_ITERATION) {
                break;
            }
            let mut d = mat_vec(&h, &g, n).map(|v| -v);
            let mut slope = dot_n(&g, &d, n);
            if slope.is_nan() || slope >= 0.0 {
                // Not a descent direction (a curvature pair the rounding spoilt): restart.
                h = identity();
                first_update = true;
                d = g.map(|v| -v);
                slope = dot_n(&g, &d, n);
            }
            let length = libm::sqrt(dot_n(&d, &d, n));
            if !(length > 0.0 && slope < 0.0) {
                break;
            }
            let shrink = (MAX_STEP_SCALES / length).min(1.0);
            d = d.map(|v| v * shrink);
            slope *= shrink;
            let Some((step, q)) = self.line_search(&best, &d, slope, n, &scales.0) else {
                if first_update {
                    break;
                }
                // The quasi-Newton step found no decrease (at the edge of the family's
                // transfers, typically): once more down the gradient before giving up.
                h = identity();
                first_update = true;
                continue;
            };
            let decrease = best.cost - q.cost;
            let Some(g_new) = self.scaled_gradient(&q, n, &scales) else {
                best = q;
                break;
            };
            let mut y = [0.0; MAX_VARS];
            for ((yi, a), b) in y.iter_mut().zip(g_new.iter()).zip(g.iter()).take(n) {
                *yi = a - b;
            }
            if bfgs_update(&mut h, &step, &y, n, first_update) {
                first_update = false;
            }
            best = q;
            g = g_new;
            if decrease < MIN_DECREASE_KM_S {
                break;
            }
        }
        best
    }

    /// Backtracking from the full step `d` (scaled) at `p`: the step taken and the re-shot
    /// point it reaches, or `None` when no halving gives Armijo's decrease.
    fn line_search(
        &mut self,
        p: &Point,
        d: &Scaled,
        slope: f64,
        n: usize,
        scales: &Scaled,
    ) -> Option<(Scaled, Point)> {
        let mut alpha = 1.0;
        for _ in 0..=LINE_SEARCH_HALVINGS {
            let step = d.map(|v| alpha * v);
            let mut moved = *p;
            for ((xi, si), scale) in moved
                .x
                .iter_mut()
                .zip(step.iter())
                .zip(scales.iter())
                .take(n)
            {
                *xi += si * scale;
            }
            if let Some(q) = self.reshoot_from(&moved, p) {
                if q.cost <= p.cost + ARMIJO * alpha * slope {
                    return Some((step, q));
                }
            }
            if self.meter.stage_refused() {
                return None;
            }
            alpha *= 0.5;
        }
        None
    }
}

/// The identity matrix.
fn identity() -> Matrix {
    let mut m = [[0.0; MAX_VARS]; MAX_VARS];
    for (i, row) in m.iter_mut().indexed() {
        if let Some(v) = row.get_mut(i) {
            *v = 1.0;
        }
    }
    m
}

/// `a . b` over the first `n` components.
fn dot_n(a: &Scaled, b: &Scaled, n: usize) -> f64 {
    a.iter()
        .zip(b.iter())
        .take(n)
        .fold(0.0, |acc, (x, y)| acc + x * y)
}

/// `m v` over the first `n` rows and columns (zero below).
fn mat_vec(m: &Matrix, v: &Scaled, n: usize) -> Scaled {
    let mut out = [0.0; MAX_VARS];
    for (o, row) in out.iter_mut().zip(m.iter()).take(n) {
        *o = dot_n(row, v, n);
    }
    out
}

/// BFGS's update of the inverse Hessian `h` by the step `s` and the gradient change `y`
/// (scaled); skipped when the curvature `s . y` is not clearly positive (the update would
/// lose positive definiteness). The `first` update scales the identity by `s.y / y.y` before
/// it (Nocedal and Wright, eq. 6.20). Whether it updated.
fn bfgs_update(h: &mut Matrix, s: &Scaled, y: &Scaled, n: usize, first: bool) -> bool {
    let sy = dot_n(s, y, n);
    let yy = dot_n(y, y, n);
    let ss = dot_n(s, s, n);
    if !(sy > 1e-12 * libm::sqrt(ss * yy) && sy.is_finite() && yy > 0.0) {
        return false;
    }
    if first {
        let gamma = sy / yy;
        for row in h.iter_mut().take(n) {
            row.iter_mut().take(n).for_each(|v| *v *= gamma);
        }
    }
    let hy = mat_vec(h, y, n);
    let yhy = dot_n(y, &hy, n);
    let rho = 1.0 / sy;
    // H' = H - rho (s hy' + hy s') + (rho^2 y'Hy + rho) s s'.
    let k = rho * rho * yhy + rho;
    for ((row, si), hyi) in h.iter_mut().zip(s.iter()).zip(hy.iter()).take(n) {
        for ((v, sj), hyj) in row.iter_mut().zip(s.iter()).zip(hy.iter()).take(n) {
            *v += -rho * (si * hyj + hyi * sj) + k * si * sj;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    #![allow(
        clippy::unwrap_used,
        clippy::indexing_slicing,
        clippy::arithmetic_side_effects,
        clippy::float_cmp
    )]

    use super::super::flight::Model;
    use super::super::tests::paper_arc;
    use super::super::types::{ArcProblem, Settings};
    use super::super::workspace::Workspace;
    use super::*;
    extern crate std;

    #[test]
    fn the_update_meets_the_secant_equation_and_keeps_the_matrix_symmetric() {
        let n = 3;
        let mut h = identity();
        let mut s = [0.0; MAX_VARS];
        let mut y = [0.0; MAX_VARS];
        s[..3].copy_from_slice(&[0.3, -0.2, 0.5]);
        y[..3].copy_from_slice(&[1.1, -0.1, 0.9]);
        assert!(bfgs_update(&mut h, &s, &y, n, true));
        let hy = mat_vec(&h, &y, n);
        for (i, row) in h.iter().enumerate().take(n) {
            assert!((hy[i] - s[i]).abs() < 1e-12, "{hy:?} vs {s:?}");
            for (j, v) in row.iter().enumerate().take(n) {
                assert!((v - h[j][i]).abs() < 1e-12);
            }
        }
        // Untouched outside the first n rows and columns.
        assert_eq!(h[n][n], 1.0);
        // A pair with negative curvature is skipped.
        let before = h;
        assert!(!bfgs_update(&mut h, &s, &y.map(|v| -v), n, false));
        assert_eq!(h, before);
    }

    /// The paper's arc with `impulses`: the costs (m/s) of the compass search's refinement of
    /// the grid's best candidate in the search model and of the descent from it.
    fn refined(impulses: u8, settings: &Settings, ws: &mut Workspace) -> (f64, f64) {
        let problem = ArcProblem {
            impulses,
            ..paper_arc()
        };
        let Workspace {
            a, b, candidates, ..
        } = ws;
        let mut ctx = super::super::context(&problem, settings, Some((a, b)))
            .ok()
            .unwrap();
        ctx.polish_follows = true;
        // No budget in the way: the test compares the methods' ends.
        ctx.meter = crate::work::Meter::new(u64::MAX);
        ctx.grid(candidates);
        let p = ctx.refine(candidates[0].unwrap());
        assert!(p.shot);
        let q = ctx.descend(p, DESCENT_MAX_ITERATIONS);
        assert!(q.shot, "the descent returns a re-shot point");
        assert_eq!(ctx.flight.model, Model::MeanElements);
        // The descent's point, re-shot from scratch, costs what it says: no frozen offset.
        let again = ctx.reshoot(&q).unwrap();
        assert!(
            (again.cost - q.cost).abs() < 1e-7,
            "{} vs {}",
            again.cost,
            q.cost
        );
        (p.cost * 1e3, q.cost * 1e3)
    }

    #[test]
    fn the_descent_goes_well_below_the_compass_search_on_three_and_four_impulses() {
        let settings = Settings::default();
        let mut ws = std::boxed::Box::new(Workspace::new());
        for impulses in [3, 4] {
            let (compass_mps, descent_mps) = refined(impulses, &settings, &mut ws);
            std::println!(
                "{impulses} impulses: compass {compass_mps:.4}, descent {descent_mps:.4} m/s"
            );
            assert!(
                descent_mps < 0.99 * compass_mps,
                "{impulses} impulses: {descent_mps} vs {compass_mps}"
            );
        }
    }
}
