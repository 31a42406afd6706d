//! The tour's order for a fixture with a `[sequence]` table: the core's branch-and-bound
//! (`reconfig_core::leo_tour::sequence`), each arc's cost the core's estimate
//! (`leo_tour::estimate_arc_mps`: the per-arc search in the search model, with the table's
//! faster settings).

use crate::fixture::leo_tour::LeoTourFixture;
use anyhow::{anyhow, Result};
use reconfig_core::leo_tour::bound::plane_of;
use reconfig_core::leo_tour::j2::State;
use reconfig_core::leo_tour::sequence::{best_order, Sequence};
use reconfig_core::leo_tour::{estimate_arc_mps, propagate as core_propagate, ArcProblem};
use serde_json::json;
use std::collections::HashMap;
use std::time::Instant;

/// The order chosen by the core's sequencing for a fixture with a `[sequence]` table.
#[derive(Debug, Clone, Copy)]
pub struct ChosenOrder {
    /// The core's outcome (order, per-arc starts and durations, pruning counts).
    pub sequence: Sequence,
    /// Wall time of the sequencing (every arc it planned), s.
    pub time_s: f64,
}

/// Choose the order of `f`'s tour with the core's branch-and-bound (each arc planned by the
/// core's per-arc rendezvous with the `[sequence]` settings; an arc met twice, with the same
/// clients, start and duration, is planned once), and return the fixture with that order and
/// its intervals.
///
/// # Errors
/// A client without an elliptic plane, or a sequencing request the core refuses.
pub fn choose_order(f: &LeoTourFixture) -> Result<Option<(LeoTourFixture, ChosenOrder)>> {
    let Some(spec) = f.sequence else {
        return Ok(None);
    };
    let g = f.settings.gravity();
    let planes = f
        .clients
        .iter()
        .enumerate()
        .map(|(k, s)| {
            plane_of(&g, s).ok_or_else(|| anyhow!("client {} has no elliptic plane", k + 1))
        })
        .collect::<Result<Vec<_>>>()?;
    let mut states: HashMap<(usize, u64), Option<State>> = HashMap::new();
    let mut arcs: HashMap<(usize, usize, u64, u64), Option<f64>> = HashMap::new();
    let started = Instant::now();
    let sequence = best_order(&g, &planes, &spec.settings, |i, j, t0, dt| {
        if let Some(c) = arcs.get(&(i, j, t0.to_bits(), dt.to_bits())) {
            return *c;
        }
        let mut at = |k: usize| {
            *states
                .entry((k, t0.to_bits()))
                .or_insert_with(|| core_propagate(&f.settings, &f.clients[k], t0))
        };
        let cost = match (at(i), at(j)) {
            (Some(from), Some(to)) => estimate_arc_mps(
                &ArcProblem {
                    from,
                    to,
                    duration_s: dt,
                    impulses: f.impulses,
                },
                &spec.arc_settings,
            )
            .ok(),
            _ => None,
        };
        arcs.insert((i, j, t0.to_bits(), dt.to_bits()), cost);
        cost
    })
    .map_err(|e| anyhow!("sequencing refused: {e:?}"))?;
    let time_s = started.elapsed().as_secs_f64();
    let n = usize::from(sequence.len);
    let mut chosen = f.clone();
    chosen.order = sequence.order[..n]
        .iter()
        .map(|&k| usize::from(k))
        .collect();
    chosen.intervals_s = sequence.durations_s[..n.saturating_sub(1)].to_vec();
    Ok(Some((chosen, ChosenOrder { sequence, time_s })))
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
