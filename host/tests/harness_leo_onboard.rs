//! The LEO tour's on-board part through the flight service (issue 13): Example I's
//! sequencing request, then the arcs of the order the service answers, sent together; every
//! answer equal to a local solve of the same request. Behaviour only: the time it takes is a
//! figure `reconfig demo` prints, not asserted here.

mod harness_common;

use harness_common::*;
use reconfig_core::limits::Limits;
use reconfig_host::harness::leo_onboard;
use std::path::PathBuf;

#[test]
fn the_on_board_part_goes_through_the_service_and_matches_the_local_solves() {
    let inst = instance("leoonboard");
    let service = serve(&inst, &[]);
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../fixtures");
    let run = leo_onboard::run(&inst, &dir, 1, 1, &Limits::default());
    stop_and_check_clean(service, &inst);
    let run = run.expect("the on-board part through the service");
    // The order of `reconfig solve fixtures/leo-tour-example1-sequence.toml` and its four arcs
    // planned in full (measured 1041.217 m/s), each answer byte-identical to a local solve.
    assert!(run.correct, "{run:?}");
    assert_eq!(run.order, vec![4, 3, 1, 5, 2], "{run:?}");
    assert_eq!(run.arc_solve_ms.len(), 4, "{run:?}");
    assert!((run.total_dv_mps - 1041.217).abs() < 0.01, "{run:?}");
    assert!(run.sequencing_ms > 0.0 && run.arcs_ms > 0.0, "{run:?}");
    assert!(
        (run.total_ms() - run.sequencing_ms - run.arcs_ms).abs() < 1e-9,
        "{run:?}"
    );
}
