//! A warm start of the per-arc search: a previous plan of the same arc (the multi-round
//! correction re-plans an arc from the states really reached, which differ from the planned
//! ones by kilometres) as the one candidate instead of the grid.

use super::arc::{Ctx, Point};
use super::shoot::{Family, Secant};
use super::types::{ArcSolution, MAX_CANDIDATES, MAX_VARS};

impl Ctx<'_> {
    /// `plan`'s free epochs and free impulse vectors as the one candidate (the cheapest
    /// last-leg family there, aimed with the offset of the client's own orbit), or none when
    /// `plan` does not fit this arc (another impulse count, epochs out of order), written into
    /// `out` (emptied first).
    pub fn warm_candidates(
        &mut self,
        plan: &ArcSolution,
        out: &mut [Option<Point>; MAX_CANDIDATES],
    ) {
        *out = [None; MAX_CANDIDATES];
        if usize::from(plan.impulses) != self.impulses {
            return;
        }
        let free = self.impulses.saturating_sub(1);
        let mut x = [0.0; MAX_VARS];
        for (xi, b) in x.iter_mut().zip(plan.burns.iter()).take(free) {
            *xi = b.epoch_s;
        }
        let vectors = self.impulses.saturating_sub(2);
        if let Some(tail) = x.get_mut(free..) {
            for (slot, b) in tail
                .chunks_exact_mut(3)
                .zip(plan.burns.iter())
                .take(vectors)
            {
                slot.copy_from_slice(&b.dv_km_s);
            }
        }
        let Some(t) = self.epochs(&x) else {
            return;
        };
        let Some(&t_last) = t.get(self.impulses.saturating_sub(2)) else {
            return;
        };
        let Some(off) = self.client_offset(t_last) else {
            return;
        };
        let planned = Family {
            revs: plan.last_leg_revolutions,
            branch: plan.last_leg_branch,
        };
        // The plan's own family first; the cheapest one where that has no Lambert solution.
        let chosen = match self.cost(&x, planned, &off) {
            Some(cost) => Some((planned, cost)),
            None => self.best_family(&x, &off),
        };
        if let (Some(slot), Some((fam, cost))) = (out.first_mut(), chosen) {
            *slot = Some(Point {
                x,
                fam,
                off,
                cost,
                shot: false,
                secant: Secant::default(),
            });
        }
    }
}
