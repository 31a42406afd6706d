//! `reconfig solve`'s report of a LEO tour fixture: the tour's requests answered in turn
//! ([`super::leo_tour`]: the order chosen first for a `[sequence]` fixture, the arcs'
//! durations for a `[schedule]` one, then each arc), then every arc flown in the host truth
//! model (J2 alone with the core's constants, and the full model) to report its arrival miss,
//! with its last leg re-planned against the truth model, and the chained multi-round
//! correction after ([`super::leo_truth`]).

use super::answer::{exit_code, report_error};
use super::leo_tour::{plan, prepare, ChosenOrder, ChosenSchedule, PlannedArc};
use super::leo_truth::{multi_round, replan_last_leg, truth_miss_m, Round};
use crate::fixture::leo_tour::LeoTourFixture;
use anyhow::Result;
use reconfig_core::limits::Limits;
use serde_json::json;
use std::process::ExitCode;

/// The truth-model arrival every arc must reach after its last leg's re-plan (issue 13's
/// figure), m: a re-plan or a multi-round correction that fails, or misses by more, makes the
/// tour `TruthMissed` (exit code 1), naming the arc and the miss (issue 31).
pub const TRUTH_ARRIVAL_TOL_M: f64 = 1.0;

/// The first arc the truth model does not confirm: which check, the arc (1-based clients) and
/// its miss after the re-plan, m (NaN when the re-plan or the correction failed outright).
#[derive(Clone, Debug, PartialEq)]
pub struct TruthMiss {
    /// `"re-plan"` (the per-arc re-plan from the planning states) or `"multi-round"` (the
    /// chained correction).
    pub check: &'static str,
    /// The arc, `(from, to)`, 1-based; `None` when the multi-round correction failed before
    /// any arc (a truth-model error).
    pub arc: Option<(usize, usize)>,
    /// The miss after the re-plan, m; NaN when there is none.
    pub miss_m: f64,
}

impl TruthMiss {
    /// `"arc 2 -> 6"`, or `"the tour"` when no arc is named.
    pub fn arc_label(&self) -> String {
        self.arc.map_or("the tour".into(), |(from, to)| {
            format!("arc {from} -> {to}")
        })
    }
}

/// The first failure of the truth checks, or `None`: each per-arc re-plan (arc `(from, to)`,
/// 0-based, its miss after, NaN when it failed) and each multi-round round (`corrected`, its
/// miss after) must arrive within `tol_m`; a multi-round run that failed outright fails.
pub fn truth_verdict(
    replans: &[((usize, usize), f64)],
    rounds: &Result<Vec<Round>>,
    tol_m: f64,
) -> Option<TruthMiss> {
    // A NaN miss (no re-plan) fails too: only a miss known to be within the tolerance passes.
    let within = |miss: f64| miss.partial_cmp(&tol_m).is_some_and(|o| o.is_le());
    let replan = replans
        .iter()
        .find(|(_, miss)| !within(*miss))
        .map(|&((from, to), miss_m)| TruthMiss {
            check: "re-plan",
            arc: Some((from + 1, to + 1)),
            miss_m,
        });
    let round = match rounds {
        Err(_) => Some(TruthMiss {
            check: "multi-round",
            arc: None,
            miss_m: f64::NAN,
        }),
        Ok(rs) => rs
            .iter()
            .find(|r| !(r.corrected && within(r.miss_after_m)))
            .map(|r| TruthMiss {
                check: "multi-round",
                arc: Some((r.arc.from + 1, r.arc.to + 1)),
                miss_m: r.miss_after_m,
            }),
    };
    replan.or(round)
}

/// A LEO tour answered and checked: the tour's requests answered in turn, each arc flown in the
/// truth model, its last leg re-planned there, and the multi-round correction; what
/// `reconfig solve` reports of it, readable or as JSON.
pub struct TourReport {
    prepared: super::leo_tour::Prepared,
    arcs: Vec<PlannedArc>,
    /// Per arc, what the truth model made of its plan.
    misses: Vec<ArcMisses>,
    rounds: Result<Vec<Round>>,
    truth: Option<TruthMiss>,
    status: &'static str,
    usable: bool,
    total: f64,
}

/// One arc's plan in the truth model.
struct ArcMisses {
    /// The arrival miss flown with J2 alone and with the full model, m; absent when the arc
    /// was not flown.
    j2_only_m: Option<f64>,
    full_m: Option<f64>,
    /// After its last leg's re-plan in the truth model: (miss m, the arc's Δv m/s), NaN when
    /// the re-plan failed.
    after_replan: (f64, f64),
}

/// Answer and check a LEO tour fixture under `limits` (see [`TourReport`]).
///
/// # Errors
/// A request refused by the limits or rejected (as `report_error` reports them): nothing more
/// is planned. A truth flight that fails is part of the answer (its miss absent, the tour
/// `TruthMissed` when the re-plan or the correction fails).
pub fn evaluate(f: &LeoTourFixture, limits: &Limits) -> Result<TourReport> {
    let prepared = prepare(f, limits)?;
    let f = &prepared.fixture;
    let arcs = plan(f, limits)?;
    let total: f64 = arcs.iter().map(|a| a.solution.total_dv_mps).sum();
    // The tour's status says no more than its arcs': `Solved` when every arc is, `Usable` when
    // every arc has a plan that arrives but the work budget cut some arc's search.
    let usable = arcs.iter().all(|a| a.solution.info.status.is_usable());
    let solved = arcs
        .iter()
        .all(|a| a.solution.info.status == reconfig_core::leo_tour::SolveStatus::Solved);
    let mut misses = Vec::new();
    for a in &arcs {
        // An arc without a plan is not flown (its misses are absent: null in JSON). A plan the
        // truth model cannot fly uncorrected (it sinks below the model's floor: drag on a low
        // arc) has no miss either; whether the tour holds is the re-plan's and the multi-round
        // correction's verdict below, not a refusal of the input (before, exit 2, no report).
        let (j2_miss, full_miss) = if a.solution.impulses == 0 {
            (None, None)
        } else {
            (truth_miss_m(a, false).ok(), truth_miss_m(a, true).ok())
        };
        // A re-plan that fails is reported as such (NaN: printed as "failed", null in JSON).
        let after = replan_last_leg(a, &f.settings).unwrap_or((f64::NAN, f64::NAN));
        misses.push(ArcMisses {
            j2_only_m: j2_miss,
            full_m: full_miss,
            after_replan: after,
        });
    }
    // The chained multi-round correction in the truth model; an error is reported, not fatal.
    let rounds = multi_round(f, &arcs, limits);
    // Only planned arcs are re-planned: an arc without a plan is already not usable.
    let replans: Vec<_> = arcs
        .iter()
        .zip(&misses)
        .filter(|(a, _)| a.solution.impulses > 0)
        .map(|(a, m)| ((a.from, a.to), m.after_replan.0))
        .collect();
    let truth = usable
        .then(|| truth_verdict(&replans, &rounds, TRUTH_ARRIVAL_TOL_M))
        .flatten();
    let status = match (solved, usable, &truth) {
        (_, false, _) => "NotSolved",
        (_, true, Some(_)) => "TruthMissed",
        (true, true, None) => "Solved",
        (false, true, None) => "Usable",
    };
    Ok(TourReport {
        prepared,
        arcs,
        misses,
        rounds,
        truth,
        status,
        usable,
        total,
    })
}

impl TourReport {
    /// Whether the tour may be flown: every arc's plan usable and confirmed by the truth model.
    pub fn usable(&self) -> bool {
        self.usable && self.truth.is_none()
    }

    /// The tour's status (`Solved`, `Usable`, `TruthMissed`, `NotSolved`).
    pub fn status(&self) -> &'static str {
        self.status
    }

    /// The work units the tour's requests used (the sequencing's and every arc's).
    pub fn work_units(&self) -> u64 {
        let order = self
            .prepared
            .order
            .as_ref()
            .map_or(0, |c| c.sequence.info.work_units);
        self.arcs.iter().fold(order, |sum, a| {
            sum.saturating_add(a.solution.info.work_units)
        })
    }

    /// The total Δv of the tour's arcs, m/s.
    pub fn total_dv_mps(&self) -> f64 {
        self.total
    }

    /// Each arc with what the truth model made of it: (arc, J2-only miss, full miss, the
    /// re-plan's (miss, Δv)), as both reports list them.
    #[allow(clippy::type_complexity)]
    fn rows(&self) -> Vec<(&PlannedArc, &Option<f64>, &Option<f64>, &(f64, f64))> {
        self.arcs
            .iter()
            .zip(&self.misses)
            .map(|(a, m)| (a, &m.j2_only_m, &m.full_m, &m.after_replan))
            .collect()
    }

    /// The JSON object `reconfig solve --json` prints.
    pub fn to_json(&self) -> serde_json::Value {
        let f = &self.prepared.fixture;
        let (status, total, rounds) = (self.status, self.total, &self.rounds);
        let seq_json = self.prepared.order.as_ref().map(sequence_json);
        let schedule_json = self.prepared.schedule.as_ref().map(schedule_json);
        let truth_json = self.truth.as_ref().map(|m| {
            json!({
                "check": m.check,
                "arc": m.arc.map(|(from, to)| format!("{from} -> {to}")),
                "miss_m": m.miss_m.is_finite().then_some(m.miss_m),
                "tolerance_m": TRUTH_ARRIVAL_TOL_M,
            })
        });
        let rows = self.rows();
        let arcs_json: Vec<_> = rows
            .iter()
            .map(|(a, j2m, fm, after)| {
                let s = &a.solution;
                let burns: Vec<_> = s
                    .burns
                    .iter()
                    .take(usize::from(s.impulses))
                    .map(|b| {
                        json!({
                            "epoch_s": a.start_s + b.epoch_s,
                            "dv_rtn_mps": b.rtn_mps,
                            "dv_mps": (b.rtn_mps.iter().map(|x| x * x).sum::<f64>()).sqrt(),
                        })
                    })
                    .collect();
                json!({
                    "from": a.from + 1,
                    "to": a.to + 1,
                    "start_s": a.start_s,
                    "end_s": a.end_s,
                    "status": format!("{:?}", s.info.status),
                    "dv_mps": s.total_dv_mps,
                    "burns": burns,
                    "model_miss_m": s.miss_m,
                    "lowest_altitude_km": s.lowest_altitude_km,
                    "truth_miss_m": { "j2_only": j2m, "full": fm, "after_replanning": after.0.is_finite().then_some(after.0) },
                    "dv_after_replanning_mps": after.1.is_finite().then_some(after.1),
                    "evaluations": s.info.evaluations,
                    "work_units": s.info.work_units,
                    "solve_time_s": a.solve_time_s,
                })
            })
            .collect();
        json!({
            "name": f.name,
            "epoch_jd_utc": f.epoch_jd,
            "status": status,
            "truth_missed": truth_json,
            "order": f.order.iter().map(|k| k + 1).collect::<Vec<_>>(),
            "total_dv_mps": total,
            "sequence": seq_json,
            "schedule": schedule_json,
            "arcs": arcs_json,
            "multi_round": rounds_json(rounds),
            "published": {
                "arc_dv_mps": f.published.arc_dv_mps,
                "total_dv_mps": f.published.total_dv_mps,
            },
        })
    }

    /// Print the readable report.
    fn print(&self) {
        let f = &self.prepared.fixture;
        let (truth, total, rounds) = (&self.truth, self.total, &self.rounds);
        let status = self.status;
        let prepared = &self.prepared;
        let rows = self.rows();
        let order: Vec<String> = f.order.iter().map(|k| (k + 1).to_string()).collect();
        println!("{}: {status}, order {}", f.name, order.join(" -> "));
        if let Some(m) = &truth {
            let miss = if m.miss_m.is_nan() {
                "fails (no re-plan)".to_string()
            } else {
                format!("misses by {:.3e} m", m.miss_m)
            };
            println!(
                "  truth model: the {} of {} {miss} (tolerance {} m)",
                m.check,
                m.arc_label(),
                TRUTH_ARRIVAL_TOL_M
            );
        }
        if let Some(c) = &prepared.order {
            let q = &c.sequence;
            let i = &q.info;
            // Which arc costs ranked the orders: said with the total they sum to.
            let costs = if c.full_plans {
                "ranked by full plans"
            } else {
                "with the sequencing's estimates"
            };
            println!(
                "  sequencing: {:?}, {} m/s {costs}; planned {} of the tree's {} arcs ({:.1} %), {} of {} orders completed, {} bound violations, {} work units, {:.2} s",
                i.status,
                q.total_dv_mps.map_or("no order".into(), |t| format!("{t:.3}")),
                i.arcs_planned,
                i.arcs_in_tree,
                100.0 * f64::from(i.arcs_planned) / f64::from(i.arcs_in_tree.max(1)),
                i.orders_completed,
                i.orders_total,
                i.bound_violations,
                i.work_units,
                c.time_s
            );
        }
        if let Some(c) = &prepared.schedule {
            let q = &c.schedule;
            let n = usize::from(q.arcs);
            let units: Vec<String> = q.duration_units[..n]
                .iter()
                .map(|u| u.to_string())
                .collect();
            println!(
                "  schedule: {:?}, arcs of [{}] x {:.4} s (horizon {:.4} s), {:.3} m/s with the schedule's estimates; {} arcs estimated, {:.2} s",
                q.status,
                units.join(", "),
                q.unit_s,
                c.horizon_s,
                q.total_dv_mps,
                q.arcs_planned,
                c.time_s
            );
        }
        for (n, (a, j2m, fm, after)) in rows.iter().enumerate() {
            let s = &a.solution;
            let published = f
                .published
                .arc_dv_mps
                .get(n)
                .map_or(String::new(), |p| format!(" (published {p:.3})"));
            println!(
                "  arc {} -> {}  [{:.4} s, {:.4} s]  {:?}  dv {:.3} m/s{published}",
                a.from + 1,
                a.to + 1,
                a.start_s,
                a.end_s,
                s.info.status,
                s.total_dv_mps
            );
            for b in s.burns.iter().take(usize::from(s.impulses)) {
                let size = b.rtn_mps.iter().map(|x| x * x).sum::<f64>().sqrt();
                println!(
                    "    burn at {:>12.4} s  RTN [{:>9.3} {:>9.3} {:>9.3}] m/s  |dv| {:.3} m/s",
                    a.start_s + b.epoch_s,
                    b.rtn_mps[0],
                    b.rtn_mps[1],
                    b.rtn_mps[2],
                    size
                );
            }
            let flown = |m: &Option<f64>| {
                m.map_or_else(|| "not flown".to_string(), |m| format!("{m:.3} m"))
            };
            let (j2m, fm) = (flown(j2m), flown(fm));
            let model_miss = s.miss_m.map_or("none".into(), |m| format!("{m:.2e}"));
            println!(
                "    arrival miss: planning model {model_miss} m, truth J2-only {j2m}, truth full {fm}  ({} evaluations, {:.2} s)",
                s.info.evaluations, a.solve_time_s
            );
            println!(
                "    last leg re-planned in the truth model: miss {:.3e} m, arc dv {:.3} m/s",
                after.0, after.1
            );
        }
        let published = f
            .published
            .total_dv_mps
            .map_or(String::new(), |p| format!(" (published {p:.3})"));
        println!("  total {total:.3} m/s{published}");
        print_rounds(rounds);
    }
}

/// Answer and report a LEO tour fixture under `limits`: exit code 0 when every arc's plan is
/// usable and the truth model confirms each arrival within [`TRUTH_ARRIVAL_TOL_M`] after its
/// re-plan (and in the multi-round correction), 1 when not, 2 when a request was refused by
/// the limits (reported as a refusal, nothing more planned) or rejected.
///
/// # Errors
/// None today: a truth flight that fails is part of the answer; the `Result` is the solve
/// commands' common shape.
pub fn run(f: &LeoTourFixture, limits: &Limits, json_output: bool) -> Result<ExitCode> {
    let report = match evaluate(f, limits) {
        Ok(r) => r,
        Err(e) => return Ok(report_error(&f.name, &e, json_output)),
    };
    if json_output {
        println!("{}", report.to_json());
    } else {
        report.print();
    }
    Ok(exit_code(report.usable()))
}

pub fn sequence_json(c: &ChosenOrder) -> serde_json::Value {
    let q = &c.sequence;
    let n = usize::from(q.len);
    let i = &q.info;
    json!({
        "status": format!("{:?}", i.status),
        "order": q.order[..n].iter().map(|&k| usize::from(k) + 1).collect::<Vec<_>>(),
        "total_dv_mps": q.total_dv_mps,
        "durations_s": q.durations_s[..n.saturating_sub(1)].to_vec(),
        "arcs_planned": i.arcs_planned,
        "arcs_in_tree": i.arcs_in_tree,
        "orders_completed": i.orders_completed,
        "orders_total": i.orders_total,
        "bound_violations": i.bound_violations,
        "work_units": i.work_units,
        "ranked_by": if c.full_plans { "full plans" } else { "estimates" },
        "time_s": c.time_s,
    })
}

pub fn schedule_json(c: &ChosenSchedule) -> serde_json::Value {
    let q = &c.schedule;
    let n = usize::from(q.arcs);
    json!({
        "status": format!("{:?}", q.status),
        "durations_s": q.durations_s[..n].to_vec(),
        "duration_units": q.duration_units[..n].to_vec(),
        "unit_s": q.unit_s,
        "horizon_s": c.horizon_s,
        "total_dv_mps": q.total_dv_mps,
        "arcs_planned": q.arcs_planned,
        "time_s": c.time_s,
    })
}

/// `multi_round`'s outcome as JSON (an error as `{"error": ...}`).
pub fn rounds_json(rounds: &Result<Vec<Round>>) -> serde_json::Value {
    match rounds {
        Err(e) => json!({ "error": e.to_string() }),
        Ok(rs) => json!({
            "total_dv_after_mps": rs.iter().map(|r| r.dv_after_mps).sum::<f64>(),
            "arcs": rs.iter().map(|r| json!({
                "from": r.arc.from + 1,
                "to": r.arc.to + 1,
                "start_s": r.arc.start_s,
                "end_s": r.arc.end_s,
                "status": format!("{:?}", r.arc.solution.info.status),
                "dv_mps": r.arc.solution.total_dv_mps,
                "dv_after_mps": r.dv_after_mps,
                "corrected": r.corrected,
                "start_offset_m": r.start_offset_m,
                "truth_miss_m": { "before": r.miss_before_m, "after": r.miss_after_m },
            })).collect::<Vec<_>>(),
        }),
    }
}

/// Print `multi_round`'s outcome.
pub fn print_rounds(rounds: &Result<Vec<Round>>) {
    match rounds {
        Err(e) => println!("  multi-round correction in the truth model failed: {e:#}"),
        Ok(rs) => {
            println!("  multi-round correction (each arc planned from the truth state reached, its last leg re-planned in the truth model):");
            for r in rs {
                println!(
                    "    arc {} -> {}  {:?}{}  dv {:.3} m/s planned, {:.3} m/s flown; start offset {:.3e} m; truth miss {:.3} m before, {:.3e} m after",
                    r.arc.from + 1,
                    r.arc.to + 1,
                    r.arc.solution.info.status,
                    if r.corrected { "" } else { " (last leg not re-planned: flown as made)" },
                    r.arc.solution.total_dv_mps,
                    r.dv_after_mps,
                    r.start_offset_m,
                    r.miss_before_m,
                    r.miss_after_m
                );
            }
            let total: f64 = rs.iter().map(|r| r.dv_after_mps).sum();
            println!("    total flown {total:.3} m/s");
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::drivers::leo_tour::PlannedArc;
    use reconfig_core::leo_tour::{ArcProblem, ArcSolution};

    fn round(from: usize, to: usize, corrected: bool, miss_after_m: f64) -> Round {
        Round {
            arc: PlannedArc {
                from,
                to,
                tour_epoch_jd: 2_459_886.5,
                start_s: 0.0,
                end_s: 1.0,
                solution: ArcSolution::new(),
                problem: ArcProblem {
                    from: [7000.0, 0.0, 0.0, 0.0, 7.5, 0.0],
                    to: [7000.0, 0.0, 0.0, 0.0, 7.5, 0.0],
                    duration_s: 1.0,
                    impulses: 2,
                },
                solve_time_s: 0.0,
            },
            miss_before_m: 1e3,
            miss_after_m,
            dv_after_mps: 1.0,
            corrected,
            start_offset_m: 0.0,
        }
    }

    #[test]
    fn a_truth_miss_names_the_first_arc_and_check_that_fails() {
        let good = Ok(vec![round(0, 1, true, 1e-4), round(1, 4, true, 0.5)]);
        assert_eq!(
            truth_verdict(&[((0, 1), 1e-4), ((1, 4), 0.9)], &good, 1.0),
            None
        );
        // A re-plan that misses by more than the tolerance, or failed (NaN), fails first.
        let m = truth_verdict(&[((0, 1), 1e-4), ((1, 4), 3.014e5)], &good, 1.0).unwrap();
        assert_eq!(
            (m.check, m.arc, m.miss_m),
            ("re-plan", Some((2, 5)), 3.014e5)
        );
        let m = truth_verdict(&[((0, 1), f64::NAN)], &good, 1.0).unwrap();
        assert_eq!((m.check, m.arc), ("re-plan", Some((1, 2))));
        // A round that misses, or was not corrected even within the tolerance.
        let missed = Ok(vec![round(0, 1, true, 1e-4), round(1, 4, true, 1973.0)]);
        let m = truth_verdict(&[((0, 1), 1e-4)], &missed, 1.0).unwrap();
        assert_eq!(
            (m.check, m.arc, m.miss_m),
            ("multi-round", Some((2, 5)), 1973.0)
        );
        let uncorrected = Ok(vec![round(2, 0, false, 0.1)]);
        let m = truth_verdict(&[], &uncorrected, 1.0).unwrap();
        assert_eq!((m.arc_label(), m.miss_m), ("arc 3 -> 1".to_string(), 0.1));
        // A correction that failed outright names the tour.
        let failed = Err(anyhow::anyhow!("truth model refused"));
        let m = truth_verdict(&[], &failed, 1.0).unwrap();
        assert_eq!(m.arc_label(), "the tour");
        assert!(m.miss_m.is_nan());
    }
}
