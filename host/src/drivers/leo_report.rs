//! `reconfig solve` for LEO tour fixtures: each arc of the fixture's order planned by the
//! core's per-arc rendezvous (`reconfig_core::leo_tour::solve_arc`), then flown in the host
//! truth model (J2 alone with the core's constants, and the full model) to report each arc's
//! arrival miss, with each arc's last leg re-planned against the truth model; the order chosen
//! first for a `[sequence]` fixture (`leo_tour_sequence`), and the chained multi-round
//! correction after (`leo_tour_rounds`).

use crate::cli::leo_tour_rounds::{print_rounds, rounds_json};
use crate::cli::leo_tour_sequence::{prepare, schedule_json, sequence_json};
use crate::cli::solve::{report_rejection, EXIT_NOT_USABLE, EXIT_USABLE};
use crate::fixture::leo_tour::LeoTourFixture;
use crate::truth::ephemeris::julian_date;
use crate::truth::integrator::Tolerance;
use crate::truth::plan_check::{full_model, j2_model, TruthSettings};
use crate::truth::propagate::{propagate, Burn, EciState};
use anyhow::{anyhow, Result};
use reconfig_core::leo_tour::flight::Model;
use reconfig_core::leo_tour::j2::State;
use reconfig_core::leo_tour::shoot::{corrected_lambert, shoot_continued, Family, Offset, Secant};
use reconfig_core::leo_tour::{propagate as core_propagate, solve_arc, ArcProblem, ArcSolution};
use reconfig_core::work::Meter;
use serde_json::json;
use std::process::ExitCode;
use std::time::Instant;

/// One planned arc of the tour.
#[derive(Debug, Clone)]
pub struct PlannedArc {
    /// Client index (0-based) the arc leaves.
    pub from: usize,
    /// Client index (0-based) the arc reaches.
    pub to: usize,
    /// Arc start from the tour epoch, s.
    pub start_s: f64,
    /// Arc end from the tour epoch, s.
    pub end_s: f64,
    /// The core's plan (epochs from the arc start).
    pub solution: ArcSolution,
    /// The arc's problem (states at the arc start).
    pub problem: ArcProblem,
    /// Planning time, s.
    pub solve_time_s: f64,
}

/// One arc of the fixture's order as the core's request: (from, to, start from the tour
/// epoch in s, the problem), the clients propagated to the arc start in the planning model.
pub type ArcRequest = (usize, usize, f64, ArcProblem);

/// The arcs of the fixture's order as the core's requests.
///
/// # Errors
/// A client that cannot be propagated to an arc start.
pub fn arc_problems(f: &LeoTourFixture) -> Result<Vec<ArcRequest>> {
    let mut out = Vec::new();
    let mut t0 = 0.0;
    for (pair, &interval) in f.order.windows(2).zip(f.intervals_s.iter()) {
        let (from, to) = (pair[0], pair[1]);
        let at = |k: usize| -> Result<State> {
            core_propagate(&f.settings, &f.clients[k], t0)
                .ok_or_else(|| anyhow!("client {} cannot be propagated to {t0} s", k + 1))
        };
        let problem = ArcProblem {
            from: at(from)?,
            to: at(to)?,
            duration_s: interval,
            impulses: f.impulses,
        };
        out.push((from, to, t0, problem));
        t0 += interval;
    }
    Ok(out)
}

/// Plan every arc of the fixture's order.
///
/// # Errors
/// A client that cannot be propagated to an arc start, or the core's `PlanError` (as text).
pub fn plan(f: &LeoTourFixture) -> Result<Vec<PlannedArc>> {
    let mut arcs = Vec::new();
    for (from, to, start_s, problem) in arc_problems(f)? {
        let started = Instant::now();
        let solution = solve_arc(&problem, &f.settings)
            .map_err(|e| anyhow!("arc {} -> {}: {e}", from + 1, to + 1))?;
        arcs.push(PlannedArc {
            from,
            to,
            start_s,
            end_s: start_s + problem.duration_s,
            solution,
            problem,
            solve_time_s: started.elapsed().as_secs_f64(),
        });
    }
    Ok(arcs)
}

fn eci(s: &State) -> EciState {
    EciState {
        pos_km: [s[0], s[1], s[2]],
        vel_km_s: [s[3], s[4], s[5]],
    }
}

/// Arrival miss (m) of `arc`'s plan flown in the truth model `model` (J2 alone or full), the
/// chaser and the client both starting from their planning states at the arc start.
pub fn truth_miss_m(arc: &PlannedArc, full: bool) -> Result<f64> {
    let (chaser, client) = truth_flight(arc, full)?;
    let d: Vec<f64> = (0..3)
        .map(|k| chaser.pos_km[k] - client.pos_km[k])
        .collect();
    Ok((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() * 1e3)
}

/// `arc`'s plan (every burn, the last included) flown in the truth model (J2 alone or full)
/// from the arc's start states: (the chaser's end state, the client's).
///
/// # Errors
/// A truth-model propagation error.
pub fn truth_flight(arc: &PlannedArc, full: bool) -> Result<(EciState, EciState)> {
    let ts = TruthSettings {
        epoch_jd: julian_date(2022, 11, 3, 0, 0, 0.0) + arc.start_s / 86_400.0,
        ..TruthSettings::default_settings()
    };
    let model = if full {
        full_model(&ts, ts.deputy_ballistic_m2_kg)?
    } else {
        j2_model(&ts)?
    };
    let s = &arc.solution;
    let burns: Vec<Burn> = s
        .burns
        .iter()
        .take(usize::from(s.impulses))
        .map(|b| Burn {
            time_s: b.epoch_s,
            dv_rtn_mps: b.rtn_mps,
        })
        .collect();
    let dur = arc.problem.duration_s;
    let chaser = propagate(
        &model,
        &eci(&arc.problem.from),
        &burns,
        dur,
        &Tolerance::TRUTH,
    )?;
    let client = propagate(&model, &eci(&arc.problem.to), &[], dur, &Tolerance::TRUTH)?;
    Ok((chaser.end, client.end))
}

/// The arc's last leg re-planned against the full truth model from the truth state reached at
/// the last leg's departure (the paper's correction, with the core's J2-corrected Lambert leg
/// aimed by the truth model's miss: at most 20 truth flights). Returns (arrival miss m, the
/// arc's Δv m/s after the re-plan).
///
/// # Errors
/// A truth-model propagation error or a Lambert leg that does not solve.
pub fn replan_last_leg(
    arc: &PlannedArc,
    settings: &reconfig_core::leo_tour::Settings,
) -> Result<(f64, f64)> {
    replan_last_leg_states(arc, settings).map(|r| (r.miss_m, r.dv_mps))
}

/// What a last-leg re-plan in the truth model reached.
#[derive(Debug, Clone, Copy)]
pub struct Replanned {
    /// Arrival miss, m.
    pub miss_m: f64,
    /// The arc's Δv after the re-plan, m/s.
    pub dv_mps: f64,
    /// The chaser's truth state at the arrival after the matching burn (the reached position,
    /// the client's velocity).
    pub chaser_end: EciState,
    /// The client's truth state at the arrival.
    pub client_end: EciState,
}

/// [`replan_last_leg`] with the states it reached.
///
/// # Errors
/// As [`replan_last_leg`]; also when no truth flight of the re-planned leg succeeded.
pub fn replan_last_leg_states(
    arc: &PlannedArc,
    settings: &reconfig_core::leo_tour::Settings,
) -> Result<Replanned> {
    let s = &arc.solution;
    let m = usize::from(s.impulses);
    let last = m - 2;
    let t_last = s.burns[last].epoch_s;
    let dur = arc.problem.duration_s;
    let at = |t: f64| TruthSettings {
        epoch_jd: julian_date(2022, 11, 3, 0, 0, 0.0) + (arc.start_s + t) / 86_400.0,
        ..TruthSettings::default_settings()
    };
    let ts0 = at(0.0);
    let model0 = full_model(&ts0, ts0.deputy_ballistic_m2_kg)?;
    let burns: Vec<Burn> = s.burns[..last]
        .iter()
        .map(|b| Burn {
            time_s: b.epoch_s,
            dv_rtn_mps: b.rtn_mps,
        })
        .collect();
    let reached = propagate(
        &model0,
        &eci(&arc.problem.from),
        &burns,
        t_last,
        &Tolerance::TRUTH,
    )?;
    let client = propagate(&model0, &eci(&arc.problem.to), &[], dur, &Tolerance::TRUTH)?;
    let ts1 = at(t_last);
    let model1 = full_model(&ts1, ts1.deputy_ballistic_m2_kg)?;
    let r = reached.end;
    let from: State = [
        r.pos_km[0],
        r.pos_km[1],
        r.pos_km[2],
        r.vel_km_s[0],
        r.vel_km_s[1],
        r.vel_km_s[2],
    ];
    let fam = Family {
        revs: s.last_leg_revolutions,
        branch: s.last_leg_branch,
    };
    // First aim offset as in the core's grid: where the client's own two-body and truth flights
    // over the last leg part (the leg ends on that orbit).
    let client_then = propagate(
        &model0,
        &eci(&arc.problem.to),
        &[],
        t_last,
        &Tolerance::TRUTH,
    )?
    .end;
    let (r_kep, _) = reconfig_core::lambert::propagate(
        settings.mu_km3_s2,
        &client_then.pos_km,
        &client_then.vel_km_s,
        dur - t_last,
        60,
    )
    .ok_or_else(|| anyhow!("two-body flight of the client did not converge"))?;
    let mut off = Offset {
        dr_km: [
            r_kep[0] - client.end.pos_km[0],
            r_kep[1] - client.end.pos_km[1],
            r_kep[2] - client.end.pos_km[2],
        ],
        dv_km_s: [0.0; 3],
    };
    let mut meter = Meter::new(u64::MAX);
    // Then the core's J2 shooting from the reached truth state (the planning model's own
    // correction): the truth iterations start a J2-to-truth difference away, not a
    // two-body-to-truth one, and with the J2 model's Jacobian of the miss in the aim offset
    // (the inverse of the shooting's quasi-Newton matrix), which the truth model's is close
    // to: on 30-revolution legs the identity start diverged (a 11 km miss went to 2500 km).
    let mut secant = Secant::default();
    // Continuation: first the J2 shooting from the plan's own departure state (the planning
    // model's flight of the burns before the last leg, where the core's search converged), then
    // from the truth state with that offset and quasi-Newton matrix. Started from the client's
    // two-body offset directly, the shooting from the truth state could fail on 30-revolution
    // legs (thousands of km of J2 drift) and the truth iterations then diverged.
    let planning_model = settings.flight(Model::Planning);
    let planned_departure = (|| {
        let mut state = arc.problem.from;
        let mut t = 0.0;
        for b in &s.burns[..last] {
            state = core_propagate(settings, &state, b.epoch_s - t)?;
            for k in 0..3 {
                state[3 + k] += b.dv_km_s[k];
            }
            t = b.epoch_s;
        }
        core_propagate(settings, &state, t_last - t)
    })();
    let target = client.end.pos_km;
    let j2_shot = |from: &State, start: &Offset, secant: &mut Secant, meter: &mut Meter| {
        shoot_continued(
            &planning_model,
            settings,
            from,
            &target,
            dur - t_last,
            fam,
            start,
            (8, 1e-3),
            secant,
            meter,
        )
        .filter(|shot| shot.miss_km <= 1.0)
    };
    if let Some(dep) = planned_departure {
        if let Some(shot) = j2_shot(&dep, &off, &mut secant, &mut meter) {
            off = shot.offset;
        }
    }
    // The truth iterations keep the J2 shooting's quasi-Newton matrix as their start: the
    // truth model's Jacobian of the miss in the aim offset is close to the J2 model's.
    if let Some(shot) = j2_shot(&from, &off, &mut secant, &mut meter) {
        off = shot.offset;
    } else {
        secant = Secant::default();
    }
    let mut best = (f64::INFINITY, f64::INFINITY);
    let mut best_end: Option<EciState> = None;
    let mut prev: Option<([f64; 3], [f64; 3])> = None;
    let norm3 = |v: &[f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    for _ in 0..20 {
        // A Lambert leg that does not solve at a moved aim point ends the re-plan with the
        // best flight so far (none at all is an error, below).
        let Some((v_dep, _)) = corrected_lambert(
            settings,
            &from,
            &client.end.pos_km,
            dur - t_last,
            fam,
            &off,
            &mut meter,
        ) else {
            break;
        };
        let start = EciState {
            pos_km: r.pos_km,
            vel_km_s: v_dep,
        };
        // A trial leg that dips into the atmosphere ends the re-plan with the best so far.
        let Ok(flown) = propagate(&model1, &start, &[], dur - t_last, &Tolerance::TRUTH) else {
            break;
        };
        let end = flown.end;
        let miss: Vec<f64> = (0..3)
            .map(|k| end.pos_km[k] - client.end.pos_km[k])
            .collect();
        let miss_m = miss.iter().map(|x| x * x).sum::<f64>().sqrt() * 1e3;
        let dv = |a: &[f64; 3], b: &[f64; 3]| {
            (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt() * 1e3
        };
        let free: f64 = s.burns[..last]
            .iter()
            .map(|b| b.rtn_mps.iter().map(|x| x * x).sum::<f64>().sqrt())
            .sum();
        let total = free + dv(&v_dep, &r.vel_km_s) + dv(&client.end.vel_km_s, &end.vel_km_s);
        if miss_m < best.0 {
            best = (miss_m, total);
            best_end = Some(end);
        }
        if miss_m < 1e-3 {
            break;
        }
        // Broyden's update of the inverse Jacobian (the core's `Secant`, as in its J2
        // shooting; the plain aim-point step contracts only ~0.7 per flight in the full model).
        let m3 = [miss[0], miss[1], miss[2]];
        if let Some((d_prev, m_prev)) = prev {
            let dd: [f64; 3] = std::array::from_fn(|k| off.dr_km[k] - d_prev[k]);
            let dm: [f64; 3] = std::array::from_fn(|k| m3[k] - m_prev[k]);
            secant.update(&dd, &dm);
        }
        prev = Some((off.dr_km, m3));
        // A quasi-Newton step longer than five plain ones is not trusted (the plain step).
        let step = Some(secant.apply(&m3))
            .filter(|st| st.iter().all(|v| v.is_finite()) && norm3(st) <= 5.0 * norm3(&m3))
            .unwrap_or(m3);
        for (o, d) in off.dr_km.iter_mut().zip(&step) {
            *o -= d;
        }
    }
    let end = best_end.ok_or_else(|| {
        anyhow!("the re-planned last leg has no Lambert solution or no truth flight")
    })?;
    Ok(Replanned {
        miss_m: best.0,
        dv_mps: best.1,
        chaser_end: EciState {
            pos_km: end.pos_km,
            vel_km_s: client.end.vel_km_s,
        },
        client_end: client.end,
    })
}

/// Solve and report a LEO tour fixture.
///
/// # Errors
/// A truth-model propagation error.
pub fn run(f: &LeoTourFixture, json_output: bool) -> Result<ExitCode> {
    let prepared = match prepare(f) {
        Ok(p) => p,
        Err(e) => return Ok(report_rejection(&f.name, &e, json_output)),
    };
    let f = &prepared.fixture;
    let seq_json = prepared.order.as_ref().map(sequence_json);
    let schedule_json = prepared.schedule.as_ref().map(schedule_json);
    let arcs = match plan(f) {
        Ok(a) => a,
        Err(e) => return Ok(report_rejection(&f.name, &e, json_output)),
    };
    let total: f64 = arcs.iter().map(|a| a.solution.total_dv_mps).sum();
    let usable = arcs
        .iter()
        .all(|a| a.solution.status == reconfig_core::leo_tour::Status::Solved);
    let status = if usable { "Solved" } else { "NotSolved" };
    let mut rows = Vec::new();
    for a in &arcs {
        let j2_miss = truth_miss_m(a, false)?;
        let full_miss = truth_miss_m(a, true)?;
        // A re-plan that fails is reported as such (NaN: printed as "failed", null in JSON).
        let after = replan_last_leg(a, &f.settings).unwrap_or((f64::NAN, f64::NAN));
        rows.push((a, j2_miss, full_miss, after));
    }
    // The chained multi-round correction in the truth model; an error is reported, not fatal.
    let rounds = crate::cli::leo_tour_rounds::multi_round(f, &arcs);
    if json_output {
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
                    "status": format!("{:?}", s.status),
                    "dv_mps": s.total_dv_mps,
                    "burns": burns,
                    "model_miss_m": s.miss_m,
                    "truth_miss_m": { "j2_only": j2m, "full": fm, "after_replanning": after.0.is_finite().then_some(after.0) },
                    "dv_after_replanning_mps": after.1.is_finite().then_some(after.1),
                    "evaluations": s.evaluations,
                    "work_units": s.work_units,
                    "solve_time_s": a.solve_time_s,
                })
            })
            .collect();
        println!(
            "{}",
            json!({
                "name": f.name,
                "status": status,
                "order": f.order.iter().map(|k| k + 1).collect::<Vec<_>>(),
                "total_dv_mps": total,
                "sequence": seq_json,
                "schedule": schedule_json,
                "arcs": arcs_json,
                "multi_round": rounds_json(&rounds),
                "published": {
                    "arc_dv_mps": f.published.arc_dv_mps,
                    "total_dv_mps": f.published.total_dv_mps,
                },
            })
        );
    } else {
        let order: Vec<String> = f.order.iter().map(|k| (k + 1).to_string()).collect();
        println!("{}: {status}, order {}", f.name, order.join(" -> "));
        if let Some(c) = &prepared.order {
            let q = &c.sequence;
            println!(
                "  sequencing: {:?}, {:.3} m/s with the sequencing search; planned {} of the tree's {} arcs ({:.1} %), {} of {} orders completed, {} bound violations, {:.2} s",
                q.status,
                q.total_dv_mps,
                q.arcs_planned,
                q.arcs_in_tree,
                100.0 * f64::from(q.arcs_planned) / f64::from(q.arcs_in_tree.max(1)),
                q.orders_completed,
                q.orders_total,
                q.bound_violations,
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
                s.status,
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
            println!(
                "    arrival miss: planning model {:.2e} m, truth J2-only {:.3} m, truth full {:.3} m  ({} evaluations, {:.2} s)",
                s.miss_m, j2m, fm, s.evaluations, a.solve_time_s
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
        print_rounds(&rounds);
    }
    Ok(ExitCode::from(if usable {
        EXIT_USABLE
    } else {
        EXIT_NOT_USABLE
    }))
}
