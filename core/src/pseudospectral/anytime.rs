//! Anytime answers (issue 28 item 2): the best iterate of a solve's first run of the iteration
//! whose trajectory keeps the keep-out on the continuous trajectory, kept so that a solve that
//! the work budget (or a QP's iteration limit) ends before a usable answer still returns a plan
//! the flight computer may fly whenever one of its iterates was one.
//!
//! Why it is needed: every accepted QP answer meets its keep-out checks (each linearised check
//! is a tangent half-space inside the feasible set), but between the checks the continuous
//! separation dips while the moving checks chase the minima, and the iteration's verification
//! rounds close those dips only near convergence. Measured before this on the generated sets
//! (docs/planner-a.md, *Anytime answers*): most answers that ended unusable had passed an
//! accepted answer whose continuous separation held, and returned the last iterate instead.
//!
//! The kept iterate lives in `Iterates::saved`, which the saddle escape and the flat probe use
//! only after the first run (their runs keep nothing: the point they leave is usable already).
//! The returned answer's status is decided by `solver::finish` on the kept trajectory itself,
//! never taken from this search.

use super::linearise::{pair_minimum_of, Iterate};
use super::settings::Settings;
use super::work_units;
use super::workspace::Workspace;

/// Once an answer is kept, a later one is searched only where its cost is lower by this
/// fraction: the iteration's costs fall at almost every accepted answer, and a search of every
/// pair at every one would cost about a verification round each; the kept answer is a
/// fallback, whose cost matters less than that there is one.
pub(super) const IMPROVEMENT_REL: f64 = 1e-2;

/// Offer the accepted answer (`Iterates::accepted`, of cost `cost`): where it is worth a search
/// (none kept yet, or cheaper by `IMPROVEMENT_REL`), search the pairs' continuous minima (the
/// last dipping pair first, each paid as a verification round's pair from the budget's loop
/// share, stopping at the first that dips) and keep the answer if every pair keeps
/// `d - verify_tol_lu`, certified. A pair the share cannot pay ends the search unkept, and is
/// not refused: the iteration's own next step decides whether the share is out.
#[inline(never)]
pub(super) fn offer(ws: &mut Workspace, settings: &Settings, cost: f64) {
    let kept = ws.iterates.kept;
    if !kept.worth_searching(cost, IMPROVEMENT_REL) {
        return;
    }
    let pairs = ws.setup.transcription.pair_count;
    let keep_out_lu = ws.setup.transcription.keep_out_lu;
    let units = work_units::verify_pair(&ws.setup.transcription);
    for k in 0..pairs {
        let Some(pair) = kept.dipping_pair().saturating_add(k).checked_rem(pairs) else {
            return;
        };
        if ws.work.remaining() < units || !ws.work.spend(units) {
            return;
        }
        let Some(minimum) = pair_minimum_of(ws, Iterate::Accepted, pair, settings) else {
            return;
        };
        let separation = libm::sqrt(minimum.value_squared.max(0.0));
        if !minimum.certified || separation < keep_out_lu - settings.verify_tol_lu {
            ws.iterates.kept.dipped_at(pair);
            return;
        }
    }
    ws.iterates.saved = ws.iterates.accepted;
    ws.iterates.kept.keep(cost);
}
