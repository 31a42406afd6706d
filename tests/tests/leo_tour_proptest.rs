//! Property tests of the LEO tour's per-arc rendezvous: no input panics, every request is
//! answered by a plan or a named error, and nothing returned is NaN or infinite; the same for
//! one flight in either model (the search model's closed-form J2 theory meets states no
//! request check has seen: the chaser after any burn of the search).

use proptest::prelude::*;
use reconfig_core::leo_tour::flight::Model;
use reconfig_core::leo_tour::j2::State;
use reconfig_core::leo_tour::{solve_arc, ArcProblem, Settings};
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
        let out = solve_arc(&problem, &settings);
        if let Ok(sol) = out {
            let burns = sol.burns.iter().flat_map(|b| {
                [b.epoch_s].into_iter().chain(b.dv_kmps).chain(b.rtn_mps)
            });
            let numbers: Vec<f64> = burns.chain([sol.total_dv_mps, sol.miss_m]).collect();
            prop_assert!(numbers.iter().all(|x| x.is_finite()), "{sol:?}");
            prop_assert!((2..=4).contains(&sol.impulses));
        }
    }
}
