//! Unit tests of the per-arc rendezvous on the published arc.
#![allow(
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects
)]

use super::elements::{state_of, Classical};
use super::*;
extern crate std;

const MU: f64 = 398_600.441_8;

fn client(a_km: f64, i_deg: f64, raan_deg: f64, u_deg: f64) -> j2::State {
    state_of(
        MU,
        &Classical {
            a_km,
            e: 0.0,
            i_rad: i_deg.to_radians(),
            raan_rad: raan_deg.to_radians(),
            argp_rad: 0.0,
            nu_rad: u_deg.to_radians(),
        },
    )
    .unwrap()
}

/// The paper's single arc S1 -> S2 (Table 1, three impulses, 83304.4194 s).
pub(crate) fn paper_arc() -> ArcProblem {
    ArcProblem {
        from: client(6778.14, 97.0344, 49.0, 25.0),
        to: client(6878.14, 97.4063, 46.0, 13.0),
        duration_s: 83_304.419_4,
        impulses: 3,
    }
}

#[test]
fn paper_single_arc_is_solved_below_the_published_cost() {
    let sol = solve_arc(&paper_arc(), &Settings::default()).unwrap();
    std::println!("{sol:#?}");
    // The published burns are 149.590 / 234.056 / 53.811 m/s (437.457 m/s, section 3.2) and
    // 418.445 m/s for the same arc in Table 2; this search finds 425.21 m/s (see
    // docs/leo-tour.md): below the first, not yet below the second.
    assert_eq!(sol.status, Status::Solved);
    assert!(sol.miss_m <= 1e-3);
    // Published 437.457 m/s (section 3.2) and 418.445 m/s (Table 2) for this arc.
    assert!(sol.total_dv_mps <= 437.457, "{}", sol.total_dv_mps);
    assert!(
        (sol.total_dv_mps - 425.211).abs() < 0.01,
        "{}",
        sol.total_dv_mps
    );
    // The burns are at free epochs inside the arc, the last at the arrival.
    assert_eq!(sol.impulses, 3);
    assert!(sol.burns[0].epoch_s >= 0.0 && sol.burns[0].epoch_s < sol.burns[1].epoch_s);
    assert!(sol.burns[2].epoch_s.to_bits() == 83_304.419_4f64.to_bits());
    // The plane-change + Hohmann lower bound of the digest: 403.8 m/s.
    assert!(sol.total_dv_mps >= 403.0);
}

#[test]
fn requests_outside_the_limits_are_refused_by_name() {
    let mut p = paper_arc();
    p.impulses = 5;
    let e = solve_arc(&p, &Settings::default()).unwrap_err();
    assert!(matches!(
        e,
        PlanError::OutOfRange {
            field: Field::Impulses,
            ..
        }
    ));
    let mut p = paper_arc();
    p.from[3] = f64::NAN;
    let e = solve_arc(&p, &Settings::default()).unwrap_err();
    assert!(matches!(
        e,
        PlanError::OutOfRange {
            field: Field::From,
            ..
        }
    ));
    let s = Settings {
        step_s: 0.0,
        ..Settings::default()
    };
    let e = solve_arc(&paper_arc(), &s).unwrap_err();
    assert!(matches!(
        e,
        PlanError::OutOfRange {
            field: Field::Step,
            ..
        }
    ));
}

#[test]
fn a_tiny_budget_is_a_named_refusal_not_a_panic() {
    let s = Settings {
        work_budget: 1000,
        ..Settings::default()
    };
    let e = solve_arc(&paper_arc(), &s).unwrap_err();
    assert!(matches!(e, PlanError::BudgetExhausted { .. }), "{e:?}");
}
