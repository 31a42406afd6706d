//! Planner A's work units: the cost of each metered step from the transcription's sizes, about
//! one unit per multiply-add of its inner loops, weighted so that no step costs more than
//! [`MAX_INSTRUCTIONS_PER_UNIT`] Cortex-M7 instructions per unit it is charged: every charged
//! step has a case in `kernels.rs` run on its dearest path, and the QEMU test
//! `tests/tests/qemu_firmware/kernels_a_image.rs` fails when a case costs more (the table in
//! `docs/planner-a.md`, "Work budget"). The hooks charge these at their loop heads
//! (`crate::work::Meter`).
//!
//! Sizes: `blocks` = 3 M coefficient blocks of `free` variables, `nodes` = N + 1, `pairs`,
//! `checks` = keep-out rows over all pairs, `k` = rows in the QP's working set.

use super::certificate::POWER_ITERATIONS;
use super::curvature::MAX_ENVELOPES;
use super::kernel::MAX_BLOCKS;
use super::lanczos::LANCZOS_STEPS;
use super::transcription::Transcription;
use crate::capacity::{MAX_ACTIVE, MAX_CHECKS_PER_PAIR, MAX_FREE_PER_AXIS, MAX_NODES};
use crate::work::units;

/// The most Cortex-M7 instructions any charged step may cost per unit it is charged, on every
/// kernel case (`kernels.rs`, checked on the M7 by `tests/tests/qemu_firmware/kernels_a_image.rs`):
/// a solve within `budget` units then runs at most `budget x MAX_INSTRUCTIONS_PER_UNIT`
/// instructions on the paths the cases cover (the default 40 M units: 400 M instructions).
pub const MAX_INSTRUCTIONS_PER_UNIT: u64 = 10;

/// The most Cortex-M7 instructions a planner-A solve within the default budget may run (issue 33
/// item 1): `DEFAULT_WORK_BUDGET x MAX_INSTRUCTIONS_PER_UNIT` must not pass it.
pub const MAX_SOLVE_INSTRUCTIONS: u64 = 400_000_000;

const _: () = assert!(
    super::settings::DEFAULT_WORK_BUDGET.saturating_mul(MAX_INSTRUCTIONS_PER_UNIT)
        <= MAX_SOLVE_INSTRUCTIONS
);

/// A coefficient vector at capacity: the loops clear and copy whole fixed-size arrays, a cost
/// that does not shrink with the problem.
const VECTOR: usize = MAX_BLOCKS * MAX_FREE_PER_AXIS;

struct Size {
    blocks: usize,
    free: usize,
    nodes: usize,
    pairs: usize,
    checks: usize,
}

fn size(tr: &Transcription) -> Size {
    let pairs = tr.pair_count;
    Size {
        blocks: tr.blocks(),
        free: tr.basis.free,
        nodes: tr.grid.nodes(),
        pairs,
        // A saturating fold, not `sum()`: the standard sum carries an overflow check (a panic
        // path in the flight library) the counts' capacities already rule out.
        checks: tr
            .check_count
            .iter()
            .take(pairs)
            .fold(0_usize, |total, &count| total.saturating_add(count)),
    }
}

/// Building the transcription: the analytic guess, LGL nodes and matrices, the Bernstein
/// conversion, the basis (cubic in the nodes), each pair's pruning window and test points
/// ([`SETUP_PAIR`]), the first iterate, and the fixed-size clears ([`SETUP_FIXED`]).
pub(super) fn setup(tr: &Transcription) -> u64 {
    let s = size(tr);
    units(&[8, s.nodes, s.nodes, s.nodes])
        .saturating_add(units(&[s.blocks, s.nodes, s.free]))
        .saturating_add(units(&[SETUP_PAIR, s.pairs]))
        .saturating_add(SETUP_FIXED)
}

/// A pair's part of the set-up (its window, its test points and their rows): measured at most
/// 115 k M7 instructions at N = 10 and 130 k at N = 24 (`kernels.rs`, `setup-*`).
const SETUP_PAIR: usize = 14_000;
/// The set-up's part that does not scale with the sizes (the guess's Newton solves, clears
/// of whole fixed-size arrays).
const SETUP_FIXED: u64 = 12_000;

/// One SQP iteration's set-up: scan each pair's checks for near contact (the continuous
/// minima searched are charged per pair as they run, [`pair_search`]), linearise every check
/// (its relative position over the nodes and its row over the free variables), the Anderson
/// step over the coefficients, and the line search's and convergence test's passes over them.
pub(super) fn sqp_iteration(tr: &Transcription) -> u64 {
    let s = size(tr);
    scaled(
        units(&[60, s.pairs, s.nodes])
            .saturating_add(units(&[9, s.checks, s.nodes.saturating_add(s.free)]))
            .saturating_add(units(&[6, s.blocks, s.free]))
            .saturating_add(units(&[12, VECTOR])),
        10,
        23,
    )
}

/// `units x num / den`, saturating: a weight rescaled to the M7's measured cost (each kernel's
/// dearest case at about 9 instructions per unit).
const fn scaled(units: u64, num: u64, den: u64) -> u64 {
    // A zero `den` (none is written) would charge the most, not panic.
    match units.saturating_mul(num).checked_div(den) {
        Some(scaled) => scaled,
        None => u64::MAX,
    }
}

/// One pair's continuous minimum searched by `linearise::follow_minima` (the SQP's moving
/// checks, and the convergence test's search at the answer, which was charged nowhere): the
/// search itself (`pair_minimum`) and the pair's share of the check scan.
pub(super) fn pair_search(tr: &Transcription) -> u64 {
    let s = size(tr);
    scaled(
        pair_minimum(&s).saturating_add(units(&[30, MAX_CHECKS_PER_PAIR])),
        10,
        23,
    )
}

/// The convergence test's search outside its pairs' minima (charged by [`pair_search`]): the
/// node table of the iterate (cleared at capacity) and every pair's check scan.
pub(super) fn convergence_search(tr: &Transcription) -> u64 {
    let s = size(tr);
    scaled(
        units(&[s.blocks, s.nodes, s.free])
            .saturating_add(units(&[MAX_BLOCKS, MAX_NODES]))
            .saturating_add(units(&[30, s.checks])),
        2,
        5,
    )
}

/// The QP's search for the most violated row evaluating `checks` keep-out checks (those of the
/// pairs it does not skip, `qp_scan::ScanBounds`), at its dearest path (no row active, pruned
/// or elastic: every row of those pairs evaluated): every control row (blocks x nodes, a dot
/// product over `free`), the node table (cleared at capacity), every pair's bound test, and
/// each keep-out row evaluated (its relative position from the node table and its normal,
/// about 300 M7 instructions whatever `free`).
pub(super) fn qp_scan(tr: &Transcription, checks: usize) -> u64 {
    let s = size(tr);
    units(&[s.blocks, s.nodes, s.free.saturating_add(2)])
        .saturating_add(units(&[SCAN_CHECK, checks.min(s.checks)]))
        .saturating_add(units(&[SCAN_PAIR, s.pairs]))
        .saturating_add(units(&[MAX_BLOCKS, MAX_NODES]))
}

/// A pair's bound test in the scan (`ScanBounds`: a comparison and a store).
const SCAN_PAIR: usize = 4;

/// A keep-out row's evaluation in the scan: about 300 M7 instructions whatever `free` (fitted
/// to `qp-scan-cap-w0`, `qp-scan-n10-w3` and `qp-scan-small-w1`).
const SCAN_CHECK: usize = 34;

/// The check of the previous QP's `hint` working rows before a scan: each row's view (about
/// 1,000 M7 instructions for a keep-out row whatever `free`) and its product with the iterate
/// (a keep-out row spans six blocks).
pub(super) fn qp_hint(tr: &Transcription, hint: usize) -> u64 {
    let s = size(tr);
    scaled(
        units(&[6, hint, s.free])
            .saturating_add(units(&[150, hint]))
            .saturating_add(100),
        5,
        9,
    )
}

/// One active-set step with `k` working rows: `k` row products and updates (a keep-out row spans
/// six blocks), two triangular solves of order `k`, and the dense direction.
pub(super) fn qp_step(tr: &Transcription, k: usize) -> u64 {
    let s = size(tr);
    scaled(
        units(&[12, k, s.free])
            .saturating_add(units(&[2, k, k]))
            .saturating_add(units(&[4, s.blocks, s.free]))
            .saturating_add(units(&[2, VECTOR])),
        8,
        11,
    )
}

/// One sweep of the dual coordinate ascent: every control row and every keep-out row, each
/// evaluated and (when it moves) applied.
pub(super) fn dual_sweep(tr: &Transcription) -> u64 {
    let s = size(tr);
    units(&[2, s.blocks, s.nodes, s.free])
        .saturating_add(units(&[s.checks, s.free.saturating_add(DUAL_CHECK)]))
}

/// A keep-out row's evaluation and update in a dual sweep past its `free` products: about 630
/// M7 instructions plus 7 per free variable (fitted to `dual-1-cap-w3` and `dual-4-n10-w3`).
const DUAL_CHECK: usize = 75;

/// One pair's continuous minimum: Bernstein coefficients of the three axes, the squared
/// distance's product coefficients, and the branch-and-bound subdivisions (degree 2N).
fn pair_minimum(s: &Size) -> u64 {
    units(&[40, s.nodes, s.nodes])
}

/// One verification round: every pair's continuous minimum, about `63 nodes^2 + 505 nodes +
/// 3,600` M7 instructions a pair (fitted to `verify-cap-w3`, `verify-n10-w3` and
/// `verify-small-w1`).
pub(super) fn verify_round(tr: &Transcription) -> u64 {
    units(&[size(tr).pairs]).saturating_mul(verify_pair(tr))
}

/// One pair's part of a verification round (also the kept answer's search, `kept.rs`, which
/// pays pair by pair and stops at the first pair that dips).
pub(super) fn verify_pair(tr: &Transcription) -> u64 {
    let s = size(tr);
    units(&[7, s.nodes, s.nodes])
        .saturating_add(units(&[56, s.nodes]))
        .saturating_add(400)
}

/// The checks of a returned iterate every answer gets (`solver::check_answer`): the continuous
/// verification of every pair, the node values of the solution, and its fixed-size part
/// ([`ANSWER_FIXED`]).
pub(super) fn answer_checks(tr: &Transcription) -> u64 {
    let s = size(tr);
    units(&[s.pairs])
        .saturating_mul(pair_minimum(&s))
        .saturating_add(units(&[12, s.blocks, s.nodes, s.free]))
        .saturating_add(ANSWER_FIXED)
}

/// The answer checks' part that does not scale with the sizes (the solution's fixed-size
/// arrays): about 28 k M7 instructions, measured `answer-checks-small-w1` (41 k instructions at
/// N = 4 where the sized part is 1,360 units; 30 per unit before this term, which the power
/// method's slack hid while both were charged as one).
const ANSWER_FIXED: u64 = 3_500;

/// The certificate of a feasible answer at its own QP state (`solver::certify`), with
/// `working` rows in the working set (at most `MAX_ACTIVE` in the reserve): the power method's
/// steps, charged before it runs; the Lanczos steps that precede it are charged after
/// ([`extra_products`]). Per power step: the projection on the working set (row products and
/// updates, two triangular solves), each active keep-out row's curvature (over the nodes), the
/// envelope corrections (at most `MAX_ENVELOPES`, six blocks each way), the dense vector
/// operations.
pub(super) fn certificate(tr: &Transcription, working: usize) -> u64 {
    let s = size(tr);
    projected_curvature(&s, working.min(MAX_ACTIVE)).saturating_mul(units(&[POWER_ITERATIONS]))
}

/// The dearest final checks of one answer with `working` rows: the answer's checks and its
/// certificate with every Lanczos step taken before the power method.
fn finish_bound(tr: &Transcription, working: usize) -> u64 {
    answer_checks(tr)
        .saturating_add(certificate(tr, working))
        .saturating_add(extra_products(tr, working, LANCZOS_STEPS))
}

/// `products` Lanczos steps past the power steps [`certificate`] charges: the certificate's
/// Lanczos steps when the power method ran after them (a reduced Hessian not positive
/// definite), with `working` rows in the working set. A step is a projected curvature product
/// and one more projection (of the Lanczos vector before the curvature acts on it).
pub(super) fn extra_products(tr: &Transcription, working: usize, products: usize) -> u64 {
    let s = size(tr);
    let working = working.min(MAX_ACTIVE);
    projected_curvature(&s, working)
        .saturating_add(projection(&s, working))
        .saturating_mul(units(&[products]))
}

/// The projection on the null space of `working` rows alone (row products and updates, two
/// triangular solves): the part of [`projected_curvature`] a Lanczos step repeats.
fn projection(s: &Size, working: usize) -> u64 {
    units(&[18, working, s.free]).saturating_add(units(&[2, working, working]))
}

/// One product with the Lagrangian's curvature projected on the null space of `working` rows
/// (a power step of the certificate, a conjugate-gradient step of the Newton step): the
/// projection (row products and updates, two triangular solves), each active keep-out row's
/// curvature (over the nodes), the envelope corrections (at most `MAX_ENVELOPES`, six blocks
/// each way), the dense vector operations.
fn projected_curvature(s: &Size, working: usize) -> u64 {
    units(&[18, working, s.free])
        .saturating_add(units(&[6, working, s.nodes]))
        .saturating_add(units(&[2, working, working]))
        .saturating_add(units(&[MAX_ENVELOPES, 12, s.free]))
        .saturating_add(units(&[4, s.blocks, s.free]))
        .saturating_add(units(&[2, VECTOR]))
}

/// The second-order step's set-up (`newton::step`) with `working` rows in the QP's working
/// set: the moving checks' local refinement in time (over the nodes), the unit normals, the
/// Gram refactorisation, the range step and the reduced gradient (two projected curvature
/// products' worth).
pub(super) fn newton_step(tr: &Transcription, working: usize) -> u64 {
    let s = size(tr);
    let working = working.min(MAX_ACTIVE);
    scaled(
        units(&[20, s.checks, s.nodes])
            .saturating_add(units(&[2]).saturating_mul(projected_curvature(&s, working))),
        5,
        6,
    )
}

/// One conjugate-gradient iteration of the second-order step with `working` rows: one
/// projected curvature product. Charged per iteration run (at most `2 curved + 2`), so a step
/// that ends early costs what it did.
pub(super) fn newton_iteration(tr: &Transcription, working: usize) -> u64 {
    let s = size(tr);
    scaled(projected_curvature(&s, working.min(MAX_ACTIVE)), 5, 6)
}

/// Deleting a row from the Gram factor of `k` working rows (`QpState::drop_row`,
/// `packed::delete_row`, at its dearest: the first row deleted): the rows below move up one
/// place (about `k^2 / 2` entries, each copy checked) and the trailing block takes a rank-one
/// update (about `k^2 / 2` entries, a division each, and `k` rotations); no row products, so
/// nothing scales with `free`. Measured on the M7 (kernel cases `drop-row-*`): 112,388
/// instructions at 56 rows, 6,562 at 11.
pub(super) fn drop_row(k: usize) -> u64 {
    let k = k.min(MAX_ACTIVE);
    units(&[4, k, k]).saturating_add(DROP_ROW_FIXED)
}

/// A row deletion's part that does not scale with `k` (the active list's and multipliers'
/// shift, the flags, the rotations' square roots).
const DROP_ROW_FIXED: u64 = 400;

/// The elastic QP's two scans of its held rows after a full scan found no violated row
/// (`qp_scan::most_met_elastic`, then `qp_scan::elastic_slack_left`), with `elastic` rows held:
/// each walks the flag tables and evaluates every held row (its view and its product with the
/// answer, a keep-out row's six blocks at most).
pub(super) fn elastic_scans(tr: &Transcription, elastic: usize) -> u64 {
    let s = size(tr);
    let walk = units(&[s.blocks, s.nodes]).saturating_add(units(&[s.checks]));
    let rows =
        units(&[elastic, 6, s.free]).saturating_add(units(&[elastic]).saturating_mul(ELASTIC_ROW));
    scaled(units(&[2]).saturating_mul(walk.saturating_add(rows)), 7, 10)
}

/// An elastic row's evaluation past its product (its flag, its view and the comparison: about
/// 300 M7 instructions per row and scan at N = 4, measured `elastic-scans-small-w1`).
const ELASTIC_ROW: u64 = 45;

/// Naming the constraints an elastic answer misses (`iteration::name_unmet`), at its dearest
/// path (every row missed, so every row described and offered to the sorted list): every
/// control row's and keep-out row's product with the answer, its description and its place in
/// the list of `MAX_UNMET`.
pub(super) fn name_unmet(tr: &Transcription) -> u64 {
    let s = size(tr);
    let rows = units(&[2, s.blocks, s.nodes]).saturating_add(units(&[s.checks]));
    scaled(
        units(&[2, s.blocks, s.nodes, s.free])
            .saturating_add(units(&[6, s.checks, s.free]))
            .saturating_add(rows.saturating_mul(NAMED_ROW)),
        6,
        7,
    )
}

/// A named row's part past its product: its view, its description (a keep-out check's time)
/// and its place in the sorted list of `MAX_UNMET` entries (about 550 M7 instructions per row
/// at N = 10, measured `name-unmet-n10-w3`).
const NAMED_ROW: u64 = 60;

/// Turning the fallback swerve direction of every pair (`iteration::turn_unmet_pairs`, at its
/// dearest path: an elastic answer naming no keep-out turns every pair): each pair's analytic
/// closest approach (a sampled search of the guess's tracks) and the turn.
pub(super) fn turn_swerves(tr: &Transcription) -> u64 {
    let s = size(tr);
    units(&[s.pairs]).saturating_mul(TURN_PAIR)
}

/// One pair's turn (`swerve::turn_fallback`): the analytic closest approach's 17 samples and up
/// to 60 refinement steps, the relative motion there, and the rotation (37 k M7 instructions
/// per pair measured on the crossing, `turn-swerves-cap-w3`).
const TURN_PAIR: u64 = 4_100;

/// A step off a saddle or along a flat direction (`solver::step_along`): two passes over a
/// coefficient vector at capacity.
pub(super) fn step_along() -> u64 {
    units(&[2, VECTOR])
}

/// How many answers' final checks a stage of a solve keeps in reserve (`reserve`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum FinalChecks {
    /// The first run: its answer's checks and certificate, or, where the answer fails its checks
    /// (no certificate then: it could certify nothing), those checks and the kept answer's
    /// (`solver::answer_or_kept`, whose certificate is not taken either: its QP state is not its
    /// own).
    FirstRun,
    /// A saddle escape or a flat probe: its answer's checks and certificate, and those of the
    /// return to the point it left (`solver::run`).
    EscapeAndReturn,
}

/// What a solve keeps back for the final checks of its stage `checks` with `working` rows in
/// the working set. The final checks run on the last QP's working set, built within the loops'
/// share, so the QP sets the reserve before each step for one row more than it holds
/// (`Meter::reserve`): the reserve is sized by the working set the solve has, not by the
/// capacity (at `MAX_ACTIVE` rows the certificate's power method alone was a third of the
/// default budget) nor by the largest set it once built. A certificate's Lanczos steps are in
/// the bound.
pub(super) fn reserve(tr: &Transcription, working: usize, checks: FinalChecks) -> u64 {
    let one = finish_bound(tr, working);
    match checks {
        FinalChecks::FirstRun => one.max(answer_checks(tr).saturating_mul(2)),
        FinalChecks::EscapeAndReturn => one.saturating_mul(2),
    }
}
