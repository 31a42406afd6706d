//! The tour's order for a fixture with a `[sequence]` table: the core's on-board sequencing
//! (`reconfig_core::leo_tour::tour_order`: the branch-and-bound of `leo_tour::sequence`, each
//! arc's cost the core's estimate `leo_tour::estimate_arc_mps`, the per-arc search in the
//! search model with the table's faster settings).

use crate::fixture::leo_tour::LeoTourFixture;
use anyhow::{anyhow, Result};
use reconfig_core::leo_tour::sequence::Sequence;
use reconfig_core::leo_tour::tour_order::{self, OnboardProblem};
use serde_json::json;
use std::time::Instant;

/// The order chosen by the core's sequencing for a fixture with a `[sequence]` table.
#[derive(Debug, Clone, Copy)]
pub struct ChosenOrder {
    /// The core's outcome (order, per-arc starts and durations, pruning counts).
    pub sequence: Sequence,
    /// Wall time of the sequencing (every arc it planned), s.
    pub time_s: f64,
}

/// Choose the order of `f`'s tour with the core's on-board sequencing
/// (`leo_tour::tour_order::choose_order`: branch-and-bound, each arc's cost the per-arc
/// search's estimate with the `[sequence]` settings), and return the fixture with that order
/// and its intervals.
///
/// # Errors
/// A sequencing request the core refuses (too few or many clients, a client without an
/// elliptic plane, intervals out of range).
pub fn choose_order(f: &LeoTourFixture) -> Result<Option<(LeoTourFixture, ChosenOrder)>> {
    let Some(spec) = f.sequence else {
        return Ok(None);
    };
    let started = Instant::now();
    let sequence =
        tour_order::choose_order(&f.clients, f.impulses, &spec.settings, &spec.arc_settings)
            .map_err(|e| anyhow!("sequencing refused: {e:?}"))?;
    let time_s = started.elapsed().as_secs_f64();
    Ok(Some((
        with_order(f, &sequence),
        ChosenOrder { sequence, time_s },
    )))
}

/// The on-board part of a `[sequence]` fixture as one core request
/// (`leo_tour::tour_order::plan_onboard`: the order, then every arc of it).
///
/// # Errors
/// A fixture without a `[sequence]` table, or with more clients than a request carries.
pub fn onboard_problem(f: &LeoTourFixture) -> Result<OnboardProblem> {
    let spec = f
        .sequence
        .ok_or_else(|| anyhow!("{} has no [sequence] table", f.name))?;
    let clients = heapless::Vec::from_slice(&f.clients)
        .map_err(|_| anyhow!("{} has {} clients", f.name, f.clients.len()))?;
    Ok(OnboardProblem {
        clients,
        impulses: f.impulses,
        sequence: spec.settings,
        estimates: spec.arc_settings,
        arcs: f.settings,
    })
}

/// `f` with the order and the arc durations of `sequence` (still with its `[sequence]`
/// table).
pub fn with_order(f: &LeoTourFixture, sequence: &Sequence) -> LeoTourFixture {
    let n = usize::from(sequence.len);
    let mut chosen = f.clone();
    chosen.order = sequence
        .order
        .iter()
        .take(n)
        .map(|&k| usize::from(k))
        .collect();
    chosen.intervals_s = sequence
        .durations_s
        .iter()
        .take(n.saturating_sub(1))
        .copied()
        .collect();
    chosen
}

pub fn sequence_json(c: &ChosenOrder) -> serde_json::Value {
    let q = &c.sequence;
    let n = usize::from(q.len);
    json!({
        "status": format!("{:?}", q.status),
        "order": q.order[..n].iter().map(|&k| usize::from(k) + 1).collect::<Vec<_>>(),
        "total_dv_mps": q.total_dv_mps,
        "durations_s": q.durations_s[..n.saturating_sub(1)].to_vec(),
        "arcs_planned": q.arcs_planned,
        "arcs_in_tree": q.arcs_in_tree,
        "orders_completed": q.orders_completed,
        "orders_total": q.orders_total,
        "bound_violations": q.bound_violations,
        "time_s": c.time_s,
    })
}
