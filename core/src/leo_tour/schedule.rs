//! The arcs' durations for a given order, chosen better than the paper's ½ / 1 · Δt_max rule:
//! the cheapest schedule on a grid of `Δt_max / steps` whose arcs add up to at most a tour
//! horizon, each arc between `min_steps` grid units and `Δt_max` (the paper's eq. 9 cap).
//!
//! An arc's problem is fixed by its two clients, its start and its duration (the chaser starts
//! on the client it has just reached), so the cheapest schedule is a shortest path over (arc,
//! start): a forward dynamic programme that plans each (arc, start, duration) of the grid once
//! and is exact for the arc costs given. The rule's durations are on the grid whenever they are
//! ½ or 1 · Δt_max (every arc of Example I), so a horizon equal to the rule's total can only
//! lower the cost the arc planner gives; the rule's closing time `|ΔΩ / ΔΩ̇|` (eq. 10) is not on
//! the grid.
//!
//! Ties keep the earliest start, then the shortest arc: deterministic. Worst case:
//! `arcs × (horizon units + 1) × (steps − min_steps + 1)` arcs planned, at most
//! `7 × 57 × 8 = 3192`; `max_arcs` stops it first.

use super::sequence::MAX_CLIENTS;
use serde::{Deserialize, Serialize};

/// Finest grid: `Δt_max / MAX_STEPS`.
pub const MAX_STEPS: u8 = 8;

/// Most arcs of a tour.
const MAX_ARCS: usize = MAX_CLIENTS - 1;

/// Most grid units in a horizon: every arc `Δt_max` on the finest grid.
const MAX_UNITS: usize = MAX_ARCS * MAX_STEPS as usize;

/// Settings of the schedule.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ScheduleSettings {
    /// `Δt_max = revolutions` periods of the order's first client (the paper's eq. 9, X).
    pub revolutions: f64,
    /// Grid units per `Δt_max`, `1..=MAX_STEPS`.
    pub steps: u8,
    /// Shortest arc, in grid units, `1..=steps`.
    pub min_steps: u8,
    /// The tour's time, s: the arcs add up to at most this (rounded down to the grid).
    pub horizon_s: f64,
    /// Most arcs planned (the callback's calls).
    pub max_arcs: u32,
}

/// What the returned schedule is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum ScheduleStatus {
    /// Every schedule on the grid within the horizon was planned: the cheapest for the arc
    /// costs given.
    Optimal,
    /// `max_arcs` stopped the programme: the cheapest complete schedule planned before, if
    /// any (the arcs are planned arc by arc, so only a stop within the last arc leaves one;
    /// `total_dv_mps` is infinite otherwise).
    ArcLimit,
    /// No complete schedule could be planned (every one has an arc the planner refused).
    NoSchedule,
}

/// The outcome of a schedule.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Schedule {
    /// What the schedule is.
    pub status: ScheduleStatus,
    /// Arcs scheduled (`durations_s` and `starts_s` hold that many).
    pub arcs: u8,
    /// The arcs' start epochs from the tour epoch, s.
    pub starts_s: [f64; MAX_ARCS],
    /// The arcs' durations, s.
    pub durations_s: [f64; MAX_ARCS],
    /// The arcs' durations in grid units.
    pub duration_units: [u8; MAX_ARCS],
    /// The grid unit, `Δt_max / steps`, s.
    pub unit_s: f64,
    /// The schedule's Δv with the arc costs given, m/s (infinite with `NoSchedule`).
    pub total_dv_mps: f64,
    /// Arcs planned (callback calls).
    pub arcs_planned: u32,
}

/// Why a schedule was refused.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum ScheduleError {
    /// Fewer than one or more than `MAX_CLIENTS - 1` arcs.
    Arcs {
        /// Arcs asked for.
        count: usize,
    },
    /// `revolutions` (or the `Δt_max` it gives) is not finite and positive.
    Revolutions {
        /// The value given.
        value: f64,
    },
    /// `steps` is outside `1..=MAX_STEPS`.
    Steps {
        /// The value given.
        value: u8,
    },
    /// `min_steps` is outside `1..=steps`.
    MinSteps {
        /// The value given.
        value: u8,
        /// `steps`.
        steps: u8,
    },
    /// The horizon is not finite or shorter than every arc at `min_steps`.
    Horizon {
        /// The value given, s.
        value_s: f64,
        /// The shortest horizon that holds the arcs, s.
        min_s: f64,
    },
    /// A client of the order has its osculating perigee below the least altitude
    /// ([`crate::leo_tour::validate::MIN_PERIGEE_ALTITUDE_KM`]), or inside the Earth.
    ClientPerigee(crate::leo_tour::validate::LowPerigee),
}

impl core::fmt::Display for ScheduleError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Self::Arcs { count } => write!(f, "{count} arcs: a schedule takes 1..={MAX_ARCS}"),
            Self::Revolutions { value } => {
                write!(f, "schedule revolutions = {value} is not finite and positive")
            }
            Self::Steps { value } => {
                write!(f, "schedule steps = {value} is outside 1..={MAX_STEPS}")
            }
            Self::MinSteps { value, steps } => {
                write!(f, "schedule min_steps = {value} is outside 1..={steps}")
            }
            Self::Horizon { value_s, min_s } => write!(
                f,
                "schedule horizon_s = {value_s} is not finite or below {min_s} s (every arc at min_steps)"
            ),
            Self::ClientPerigee(low) => write!(f, "{low}"),
        }
    }
}

impl core::error::Error for ScheduleError {}

/// One arc of the grid, as the programme hands it to the arc planner: its place in the order,
/// its start and duration in grid units, and the same in seconds (the epochs the returned
/// [`Schedule`] reports for it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridArc {
    /// Arc `arc` leaves the order's client `arc`.
    pub arc: usize,
    /// Start, grid units from the tour epoch.
    pub start_units: u8,
    /// Duration, grid units.
    pub duration_units: u8,
    /// Start from the tour epoch, s.
    pub start_s: f64,
    /// Duration, s.
    pub duration_s: f64,
}

/// The best way found to reach a start epoch (in grid units) at some arc.
#[derive(Clone, Copy)]
struct Reach {
    /// Δv of the arcs before, m/s.
    cost_mps: f64,
    /// The previous arc's start, units.
    from_units: u8,
    /// The previous arc's duration, units.
    duration_units: u8,
}

/// The cheapest schedule of `arcs` arcs on the grid `dt_max_s / settings.steps`, each arc
/// planned by `plan_arc(&GridArc)` (its Δv in m/s, or `None` when it cannot be planned).
/// Called in order of arc, then start, then duration.
///
/// # Errors
/// [`ScheduleError`] for settings or an arc count out of range.
pub fn best_schedule<F: FnMut(&GridArc) -> Option<f64>>(
    arcs: usize,
    dt_max_s: f64,
    settings: &ScheduleSettings,
    mut plan_arc: F,
) -> Result<Schedule, ScheduleError> {
    if !(1..=MAX_ARCS).contains(&arcs) {
        return Err(ScheduleError::Arcs { count: arcs });
    }
    if !(dt_max_s.is_finite() && dt_max_s > 0.0) {
        return Err(ScheduleError::Revolutions {
            value: settings.revolutions,
        });
    }
    let steps = settings.steps;
    if !(1..=MAX_STEPS).contains(&steps) {
        return Err(ScheduleError::Steps { value: steps });
    }
    let min = settings.min_steps;
    if !(1..=steps).contains(&min) {
        return Err(ScheduleError::MinSteps { value: min, steps });
    }
    let unit_s = dt_max_s / f64::from(steps);
    // `arcs <= 7` and `steps <= 8`: every count of units below fits a u8.
    let arcs_u8 = u8::try_from(arcs).map_err(|_| ScheduleError::Arcs { count: arcs })?;
    let least = arcs_u8.saturating_mul(min);
    let least_s = f64::from(least) * unit_s;
    // Rounded down to the grid, with a relative slack so that a horizon written as the sum of
    // grid-length intervals keeps its last unit.
    let horizon_units = settings.horizon_s / unit_s * (1.0 + 1e-12);
    if !(horizon_units.is_finite() && horizon_units >= f64::from(least)) {
        return Err(ScheduleError::Horizon {
            value_s: settings.horizon_s,
            min_s: least_s,
        });
    }
    let full = arcs_u8.saturating_mul(steps);
    // Truncation toward zero is the rounding down; the value is in `least..`, below 2^8 after
    // the min.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let horizon = (libm::floor(horizon_units).min(f64::from(full))) as u8;

    let mut reach: [[Option<Reach>; MAX_UNITS + 1]; MAX_ARCS + 1] =
        [[None; MAX_UNITS + 1]; MAX_ARCS + 1];
    if let Some(first) = reach.first_mut().and_then(|r| r.first_mut()) {
        *first = Some(Reach {
            cost_mps: 0.0,
            from_units: 0,
            duration_units: 0,
        });
    }
    let mut arcs_planned = 0_u32;
    let mut stopped = false;
    'arcs: for k in 0..arcs {
        // Units the arcs after this one need at least.
        let later = u8::try_from(arcs.saturating_sub(k).saturating_sub(1))
            .unwrap_or(u8::MAX)
            .saturating_mul(min);
        let (Some(here), Some(next)) = (reach.get(k).copied(), reach.get_mut(k.saturating_add(1)))
        else {
            break;
        };
        for (start, node) in (0..=horizon).zip(here.iter()) {
            let Some(node) = node else { continue };
            for d in min..=steps {
                let end = start.saturating_add(d);
                if end.saturating_add(later) > horizon {
                    break;
                }
                if arcs_planned >= settings.max_arcs {
                    stopped = true;
                    break 'arcs;
                }
                arcs_planned = arcs_planned.saturating_add(1);
                let arc = GridArc {
                    arc: k,
                    start_units: start,
                    duration_units: d,
                    start_s: f64::from(start) * unit_s,
                    duration_s: f64::from(d) * unit_s,
                };
                let Some(dv) = plan_arc(&arc).filter(|dv| dv.is_finite()) else {
                    continue;
                };
                let cost_mps = node.cost_mps + dv;
                let Some(slot) = next.get_mut(usize::from(end)) else {
                    continue;
                };
                if slot.is_none_or(|r| cost_mps < r.cost_mps) {
                    *slot = Some(Reach {
                        cost_mps,
                        from_units: start,
                        duration_units: d,
                    });
                }
            }
        }
    }

    // The cheapest end, ties by the earliest.
    let mut end = None;
    if let Some(last) = reach.get(arcs) {
        for (units, r) in (0..=horizon).zip(last.iter()) {
            if let Some(r) = r {
                if end.is_none_or(|(_, c)| r.cost_mps < c) {
                    end = Some((units, r.cost_mps));
                }
            }
        }
    }
    let mut schedule = Schedule {
        status: if stopped {
            ScheduleStatus::ArcLimit
        } else {
            ScheduleStatus::Optimal
        },
        arcs: arcs_u8,
        starts_s: [0.0; MAX_ARCS],
        durations_s: [0.0; MAX_ARCS],
        duration_units: [0; MAX_ARCS],
        unit_s,
        total_dv_mps: f64::INFINITY,
        arcs_planned,
    };
    let Some((mut at, total)) = end else {
        if !stopped {
            schedule.status = ScheduleStatus::NoSchedule;
        }
        return Ok(schedule);
    };
    schedule.total_dv_mps = total;
    // Back from the end: each arc's start and duration.
    for k in (0..arcs).rev() {
        let Some(r) = reach
            .get(k.saturating_add(1))
            .and_then(|row| row.get(usize::from(at)))
            .copied()
            .flatten()
        else {
            schedule.status = ScheduleStatus::NoSchedule;
            return Ok(schedule);
        };
        if let (Some(s), Some(d), Some(u)) = (
            schedule.starts_s.get_mut(k),
            schedule.durations_s.get_mut(k),
            schedule.duration_units.get_mut(k),
        ) {
            *s = f64::from(r.from_units) * unit_s;
            *d = f64::from(r.duration_units) * unit_s;
            *u = r.duration_units;
        }
        at = r.from_units;
    }
    Ok(schedule)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::vec;
    use std::vec::Vec;

    fn settings(horizon_units: f64) -> ScheduleSettings {
        ScheduleSettings {
            revolutions: 30.0,
            steps: 4,
            min_steps: 1,
            horizon_s: horizon_units * 100.0,
            max_arcs: 10_000,
        }
    }

    /// Every schedule of `arcs` arcs with `1..=steps` units each and at most `horizon` units,
    /// the cheapest by brute force.
    fn brute(
        arcs: usize,
        steps: u8,
        horizon: u8,
        cost: &dyn Fn(usize, u8, u8) -> f64,
    ) -> (f64, Vec<u8>) {
        let mut best = (f64::INFINITY, Vec::new());
        let mut stack = vec![(0_usize, 0_u8, 0.0, Vec::new())];
        while let Some((k, start, c, path)) = stack.pop() {
            if k == arcs {
                if c < best.0 {
                    best = (c, path);
                }
                continue;
            }
            for d in 1..=steps {
                if start + d <= horizon {
                    let mut p = path.clone();
                    p.push(d);
                    stack.push((k + 1, start + d, c + cost(k, start, d), p));
                }
            }
        }
        best
    }

    #[test]
    fn the_programme_finds_the_brute_force_optimum_of_a_start_dependent_cost() {
        // A cost that depends on the arc, its start and its duration, not monotone in any.
        let cost = |k: usize, start: u8, d: u8| {
            let x = f64::from(start) * 0.7 + f64::from(d) * 1.3 + k as f64;
            10.0 + 5.0 * libm::sin(x) + 3.0 * libm::cos(2.1 * x + f64::from(d))
        };
        for (arcs, horizon) in [(1, 4), (3, 7), (4, 14), (4, 16), (5, 11)] {
            let s = settings(f64::from(horizon));
            let got = best_schedule(arcs, 400.0, &s, |a| {
                Some(cost(a.arc, a.start_units, a.duration_units))
            })
            .unwrap();
            let (want, path) = brute(arcs, 4, horizon, &cost);
            assert_eq!(got.status, ScheduleStatus::Optimal);
            assert!((got.total_dv_mps - want).abs() < 1e-12, "{arcs} {horizon}");
            assert_eq!(&got.duration_units[..arcs], &path[..], "{arcs} {horizon}");
            // Starts follow the durations, and the arcs fit the horizon.
            let mut t = 0.0;
            for k in 0..arcs {
                assert!((got.starts_s[k] - t).abs() < 1e-9);
                t += got.durations_s[k];
            }
            assert!(t <= f64::from(horizon) * 100.0 + 1e-9);
        }
    }

    #[test]
    fn refused_arcs_are_avoided_and_a_schedule_with_none_is_named() {
        // Arc 1 cannot be planned at 2 units: the optimum must avoid it.
        let s = settings(8.0);
        let got = best_schedule(2, 400.0, &s, |a| {
            (!(a.arc == 1 && a.duration_units == 2)).then_some(f64::from(a.duration_units))
        })
        .unwrap();
        assert_eq!(got.status, ScheduleStatus::Optimal);
        assert_eq!(&got.duration_units[..2], &[1, 1]);
        let none = best_schedule(2, 400.0, &s, |_| None).unwrap();
        assert_eq!(none.status, ScheduleStatus::NoSchedule);
        assert!(none.total_dv_mps.is_infinite());
        let nan = best_schedule(2, 400.0, &s, |_| Some(f64::NAN)).unwrap();
        assert_eq!(nan.status, ScheduleStatus::NoSchedule);
    }

    #[test]
    fn the_arc_limit_stops_it_and_says_so() {
        let s = ScheduleSettings {
            max_arcs: 5,
            ..settings(16.0)
        };
        let mut calls = 0;
        let got = best_schedule(4, 400.0, &s, |a| {
            calls += 1;
            Some(f64::from(a.duration_units))
        })
        .unwrap();
        assert_eq!(calls, 5);
        assert_eq!(got.arcs_planned, 5);
        assert_eq!(got.status, ScheduleStatus::ArcLimit);
        assert!(got.total_dv_mps.is_infinite());
        // Stopped one arc short of the end: a complete schedule, not necessarily the best.
        let all = best_schedule(4, 400.0, &settings(16.0), |a| {
            Some(f64::from(a.duration_units))
        })
        .unwrap()
        .arcs_planned;
        let short = ScheduleSettings {
            max_arcs: all - 1,
            ..s
        };
        let got = best_schedule(4, 400.0, &short, |a| Some(f64::from(a.duration_units))).unwrap();
        assert_eq!(got.status, ScheduleStatus::ArcLimit);
        assert!((got.total_dv_mps - 4.0).abs() < 1e-12);
    }

    #[test]
    fn the_horizon_is_rounded_down_to_the_grid_and_the_worst_case_is_bounded() {
        // 3.5 grid-lengths of Δt_max written as a sum of intervals keeps its 14 quarter units.
        let dt_max = 166_608.838_7;
        let s = ScheduleSettings {
            revolutions: 30.0,
            steps: 4,
            min_steps: 1,
            horizon_s: 0.5 * dt_max + 3.0 * dt_max,
            max_arcs: 10_000,
        };
        let got = best_schedule(4, dt_max, &s, |a| Some(-f64::from(a.duration_units))).unwrap();
        // The longest arcs are cheapest here: 14 units in all.
        assert_eq!(got.duration_units[..4].iter().sum::<u8>(), 14);
        // The finest grid, every unit: at most 7 × 57 × 8 calls.
        let wide = ScheduleSettings {
            steps: MAX_STEPS,
            min_steps: 1,
            horizon_s: 7.0 * dt_max,
            max_arcs: u32::MAX,
            ..s
        };
        let mut calls = 0_u32;
        best_schedule(7, dt_max, &wide, |_| {
            calls += 1;
            Some(1.0)
        })
        .unwrap();
        assert!(calls <= 7 * 57 * 8, "{calls}");
    }

    #[test]
    fn settings_out_of_range_are_named() {
        let s = settings(8.0);
        let run = |arcs: usize, dt: f64, s: ScheduleSettings| {
            best_schedule(arcs, dt, &s, |_| Some(1.0)).unwrap_err()
        };
        assert_eq!(run(0, 400.0, s), ScheduleError::Arcs { count: 0 });
        assert_eq!(run(8, 400.0, s), ScheduleError::Arcs { count: 8 });
        assert!(matches!(
            run(2, f64::NAN, s),
            ScheduleError::Revolutions { .. }
        ));
        assert_eq!(
            run(2, 400.0, ScheduleSettings { steps: 9, ..s }),
            ScheduleError::Steps { value: 9 }
        );
        assert_eq!(
            run(2, 400.0, ScheduleSettings { min_steps: 5, ..s }),
            ScheduleError::MinSteps { value: 5, steps: 4 }
        );
        let e = run(
            3,
            400.0,
            ScheduleSettings {
                horizon_s: 250.0,
                ..s
            },
        );
        assert_eq!(
            e,
            ScheduleError::Horizon {
                value_s: 250.0,
                min_s: 300.0
            }
        );
        assert!(matches!(
            run(
                3,
                400.0,
                ScheduleSettings {
                    horizon_s: f64::INFINITY,
                    ..s
                }
            ),
            ScheduleError::Horizon { .. }
        ));
    }
}
