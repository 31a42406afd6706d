//! Hops of the per-arc search: the best refined plan with its free impulse epochs moved by half
//! a revolution, so the refinement can restart in the basin of the other node.

use super::arc::{period_s, rtn, rtn_axes, Client, Ctx, Point};
use super::j2::State;
use super::shoot::Secant;
use super::types::{MAX_HOPS, MAX_VARS};
use super::work_units;
use crate::indexed::IndexedExt as _;
use crate::vec3::{add, scale, Vec3};

impl Ctx<'_> {
    /// Hops from `p`: its free epochs moved by half a revolution of client A's orbit (each
    /// epoch alone, then all together, both ways), a moved impulse keeping its radial,
    /// along-track and normal components; each with its cheapest last-leg family. A plane
    /// change is cheapest at a node, and the nodes are half a revolution apart: the compass
    /// search cannot cross that far from a basin, a hop can. Written into `out` (emptied
    /// first).
    pub fn hops(&mut self, p: &Point, out: &mut [Option<Point>; MAX_HOPS]) {
        *out = [None; MAX_HOPS];
        let free = self.impulses.saturating_sub(1);
        let Some(s0) = self.client_state(Client::A, 0.0) else {
            return;
        };
        let half = 0.5 * period_s(self.settings.mu_km3_s2, &s0);
        // Moves: epoch k alone for k < free, then every free epoch; each +half and -half.
        let moves = (0..=free).flat_map(|k| [half, -half].map(move |d| (k, d)));
        for (slot, (k, d)) in out.iter_mut().zip(moves) {
            if !self.meter.spend(work_units::HOP) {
                break;
            }
            let mut x = p.x;
            let mut ok = true;
            for (j, xj) in x.iter_mut().take(free).indexed() {
                if j == k || k == free {
                    *xj += d;
                }
            }
            // A moved free impulse keeps its RTN components at its new epoch.
            let vectors = free.min(self.impulses.saturating_sub(2));
            for j in 0..vectors {
                if !(j == k || k == free) {
                    continue;
                }
                let old = self.chaser_state(&p.x, j);
                let new = self.chaser_state(&x, j);
                let (Some(old), Some(new)) = (old, new) else {
                    ok = false;
                    break;
                };
                let lo = free.saturating_add(j.saturating_mul(3));
                let Some(dv) = x.get_mut(lo..lo.saturating_add(3)) else {
                    ok = false;
                    break;
                };
                let [a, b, c] = [dv.first(), dv.get(1), dv.get(2)];
                let (Some(&a), Some(&b), Some(&c)) = (a, b, c) else {
                    ok = false;
                    break;
                };
                let local = rtn(&old, &[a, b, c]);
                let inertial = from_rtn(&new, &local);
                for (o, v) in dv.iter_mut().zip(inertial.iter()) {
                    *o = *v;
                }
            }
            if !ok || self.epochs(&x).is_none() {
                continue;
            }
            if let Some((fam, cost)) = self.best_family(&x, &p.off) {
                *slot = Some(Point {
                    x,
                    fam,
                    off: p.off,
                    cost,
                    shot: false,
                    secant: Secant::default(),
                });
            }
            if self.meter.stage_refused() {
                break;
            }
        }
    }

    /// The chaser's state just before free impulse `j` of the plan `x` (on client A's orbit
    /// for the first, else flown through the earlier free impulses).
    fn chaser_state(&mut self, x: &[f64; MAX_VARS], j: usize) -> Option<State> {
        if j == 0 {
            let t = *x.first()?;
            return self.client_state(Client::A, t);
        }
        let (pre, _, _) = self.fly_to_last_leg(x)?;
        pre.get(j).map(|(s, _)| *s)
    }
}

/// RTN components `local` of `state`'s frame as an inertial vector.
fn from_rtn(state: &State, local: &Vec3) -> Vec3 {
    rtn_axes(state).map_or([0.0; 3], |[ir, it, ih]| {
        add(
            &add(&scale(&ir, local[0]), &scale(&it, local[1])),
            &scale(&ih, local[2]),
        )
    })
}
