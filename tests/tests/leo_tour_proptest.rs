//! Property tests of the LEO tour's per-arc rendezvous: no input panics, every request is
//! answered by a plan or a named error, and nothing returned is NaN or infinite; the same for
//! one flight in either model (the search model's closed-form J2 theory meets states no
//! request check has seen: the chaser after any burn of the search); and the arcs' schedule
//! with any settings and arc costs.

use proptest::prelude::*;
use reconfig_core::leo_tour::flight::Model;
use reconfig_core::leo_tour::j2::State;
use reconfig_core::leo_tour::{solve_arc, ArcProblem, ArcSolution, Settings, Workspace};
use reconfig_core::work::Meter;

fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -10.0f64..10.0,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(0.0),
        1 => any::<f64>(),
    ]
}

/// A LEO state: mostly a near-circular orbit at any inclination (equatorial and retrograde
/// included), sometimes with one component replaced by a wild value (radial, hyperbolic,
/// inside the Earth, non-finite).
fn leo_state() -> impl Strategy<Value = State> {
    (
        6700.0f64..7400.0,
        0.0f64..180.0,
        0.0f64..360.0,
        0.0f64..360.0,
        -0.05f64..0.05,
        prop::option::weighted(0.2, (0usize..6, any_f64())),
    )
        .prop_map(|(a, i_deg, raan_deg, u_deg, dv, wild)| {
            let v = (398_600.441_8 / a).sqrt() + dv;
            let (si, ci) = i_deg.to_radians().sin_cos();
            let (so, co) = raan_deg.to_radians().sin_cos();
            let (su, cu) = u_deg.to_radians().sin_cos();
            // Position and velocity from the node line and the orbit normal.
            let r = [
                a * (co * cu - so * su * ci),
                a * (so * cu + co * su * ci),
                a * su * si,
            ];
            let w = [-co * su - so * cu * ci, -so * su + co * cu * ci, cu * si];
            let mut s = [r[0], r[1], r[2], v * w[0], v * w[1], v * w[2]];
            if let Some((k, x)) = wild {
                s[k] = 1000.0 * x;
            }
            s
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn a_flight_is_finite_or_refused_in_both_models(s in leo_state(), dt in any_f64()) {
        let settings = Settings { max_steps: 2000, ..Settings::default() };
        for model in [Model::MeanElements, Model::Planning] {
            let mut meter = Meter::new(1_000_000);
            if let Some(out) = settings.flight(model).fly(&s, 1.0e4 * dt, &mut meter) {
                prop_assert!(out.iter().all(|x| x.is_finite()), "{model:?}: {out:?}");
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn an_arc_is_planned_or_refused_by_name_never_nan(
        from in leo_state(),
        to in leo_state(),
        duration in prop_oneof![8 => 5_000.0f64..200_000.0, 1 => any_f64()],
        impulses in prop_oneof![8 => 2u8..=4, 1 => 0u8..8],
    ) {
        // A small budget keeps each case short; the budget is part of the contract too.
        let settings = Settings { work_budget: 3_000_000, ..Settings::default() };
        let problem = ArcProblem {
            from,
            to,
            duration_s: duration,
            impulses,
        };
        let mut sol = ArcSolution::new();
        if solve_arc(&problem, &settings, &mut Box::new(Workspace::new()), &mut sol).is_ok() {
            let burns = sol.burns.iter().flat_map(|b| {
                [b.epoch_s].into_iter().chain(b.dv_km_s).chain(b.rtn_mps)
            });
            let numbers: Vec<f64> = burns.chain([sol.total_dv_mps]).chain(sol.miss_m).collect();
            prop_assert!(numbers.iter().all(|x| x.is_finite()), "{sol:?}");
            // A plan has its burns and its miss; no plan has neither.
            if sol.impulses == 0 {
                prop_assert!(sol.miss_m.is_none() && !sol.info.status.is_usable(), "{sol:?}");
            } else {
                prop_assert!((2..=4).contains(&sol.impulses));
                prop_assert!(sol.miss_m.is_some());
            }
            prop_assert!(sol.info.status != reconfig_core::leo_tour::SolveStatus::Unsolved);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The arcs' schedule (`leo_tour::schedule::best_schedule`) with any settings and any arc
    /// costs (NaN, infinite, refused): a named error or a schedule within its grid and
    /// horizon, never a panic; a returned total is finite exactly when a schedule was found.
    #[test]
    fn any_schedule_request_is_planned_within_its_grid_or_refused_by_name(
        arcs in prop_oneof![4 => 1usize..=7, 1 => 0usize..10],
        dt_max in prop_oneof![4 => 100.0f64..2e5, 1 => any_f64()],
        steps in prop_oneof![4 => 1u8..=8, 1 => 0u8..12],
        min_steps in prop_oneof![4 => 1u8..=4, 1 => 0u8..12],
        // In Δt_max, or any value.
        horizon in prop_oneof![4 => (0.0f64..8.0).prop_map(|h| -h), 1 => any_f64()],
        max_arcs in 0u32..4000,
        costs in prop::collection::vec(prop_oneof![4 => Just(1.0), 1 => any_f64()], 16),
    ) {
        use reconfig_core::leo_tour::schedule::{best_schedule, ScheduleSettings, ScheduleStatus};
        // A negative draw is a multiple of Δt_max (when that is finite and positive).
        let horizon = if horizon <= 0.0 && dt_max.is_finite() { -horizon * dt_max } else { horizon };
        let settings = ScheduleSettings {
            revolutions: 30.0,
            steps,
            min_steps,
            horizon_s: horizon,
            max_arcs,
        };
        let cost = |a: &reconfig_core::leo_tour::schedule::GridArc| -> Option<f64> {
            let (k, start, d) = (a.arc, a.start_units, a.duration_units);
            let c = costs[(k * 7 + usize::from(start) * 3 + usize::from(d)) % costs.len()];
            (c != 0.0).then_some(c.abs() + f64::from(d))
        };
        match best_schedule(arcs, dt_max, &settings, cost) {
            Err(e) => prop_assert!(!e.to_string().is_empty()),
            Ok(s) => {
                prop_assert!(s.arcs_planned <= max_arcs);
                prop_assert!(s.arcs_planned <= 7 * 57 * 8);
                if s.total_dv_mps.is_finite() {
                    let n = usize::from(s.arcs);
                    let units: u32 = s.duration_units[..n].iter().map(|&u| u32::from(u)).sum();
                    prop_assert!(s.duration_units[..n].iter().all(|&u| u >= min_steps && u <= steps));
                    prop_assert!(f64::from(units) * s.unit_s <= horizon * (1.0 + 1e-9));
                    prop_assert!(s.durations_s[..n].iter().all(|d| d.is_finite() && *d > 0.0));
                } else {
                    prop_assert!(s.status != ScheduleStatus::Optimal);
                }
            }
        }
    }
}
