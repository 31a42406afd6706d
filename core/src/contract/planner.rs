//! The shape of a planner and the vocabulary of its statuses.

/// How a solve ended: the promise the returned plan carries. Every planner's `SolveStatus` is
/// `#[repr(u8)]` with stable codes, defaults to `Unsolved` (code 0: no solve has written the
/// solution) and keeps this vocabulary:
///
/// * `Solved` (code 1): the plan meets every condition the planner's docs list, checked on the
///   returned plan by the code that returns it;
/// * `BudgetExhausted { verified }`: the work budget (`work_budget` setting, [`crate::work`])
///   ran out before the method's own end; the returned plan was checked like any other with
///   the part of the budget kept for the checks, and `verified` says whether it passed them
///   (then it may be flown; a longer solve might find a better plan);
/// * `NumericalFailure(stage)`: a numerical step failed where `stage` says;
/// * every other status says what could be shown instead, never more.
///
/// [`Status::is_usable`] is the one question a flight computer asks: may this plan be flown?
pub trait Status: Copy + Default + PartialEq + core::fmt::Debug {
    /// The plan may be flown: `Solved`, and the statuses the planner's docs call usable (a
    /// verified budget stop, planner A's `Feasible`).
    fn is_usable(&self) -> bool;
    /// The variant's stable code (its `repr(u8)` discriminant; the C interface's status code is
    /// the planner's base plus this).
    fn code(&self) -> u8;
    /// `Some(verified)` when the work budget ended the solve, else `None`.
    fn budget_exhausted(&self) -> Option<bool>;
}

/// A planner: the four objects of the contract and its one solve entry point.
///
/// The caller owns every buffer: the workspace is built once (`Workspace::new()`, a `const fn`
/// that can sit in a `static`), the solution is written in place. A request the planner refuses
/// before planning is an `Err(Error)` naming the field, the value and the limit, and leaves
/// the solution untouched; a plan that ends without a usable transfer is a status in the
/// solution, never an error.
pub trait Planner {
    /// The request's problem.
    type Problem;
    /// The loop bounds, tolerances and work budget (a settings table, `settings_table!`).
    type Settings;
    /// Every scratch buffer of a solve.
    type Workspace;
    /// The answer: the plan, its figures and `info` with the status and counters.
    type Solution;
    /// Why a request is refused before planning.
    type Error;
    /// The status the solution carries.
    type Status: Status;

    /// Which planner, on the wire.
    const KIND: super::PlannerKind;

    /// Plan `problem` with `settings` in `workspace`, writing the answer into `out`.
    ///
    /// # Errors
    /// `Self::Error` when the request is refused before planning; `out` is then untouched.
    fn solve(
        problem: &Self::Problem,
        settings: &Self::Settings,
        workspace: &mut Self::Workspace,
        out: &mut Self::Solution,
    ) -> Result<(), Self::Error>;

    /// The status of an answer.
    fn status(solution: &Self::Solution) -> Self::Status;

    /// Reset `out` to the empty `Unsolved` answer, in place (no large temporary on the stack:
    /// a flight image's stack is measured to the byte).
    fn reset(out: &mut Self::Solution);
}

/// Implement [`Planner`] for a planner's unit struct from its module's items: the problem,
/// settings, workspace, solution, error and status types, the wire kind, the solve function
/// and the in-place reset of a solution (`|out| ...`).
#[macro_export]
macro_rules! impl_planner {
    (
        $Unit:ident: $Problem:ty, $Settings:ty, $Workspace:ty, $Solution:ty, $Error:ty,
        $Status:ty, $kind:ident, $solve:path, reset $reset:expr
    ) => {
        impl $crate::contract::Planner for $Unit {
            type Problem = $Problem;
            type Settings = $Settings;
            type Workspace = $Workspace;
            type Solution = $Solution;
            type Error = $Error;
            type Status = $Status;
            const KIND: $crate::contract::PlannerKind = $crate::contract::PlannerKind::$kind;

            fn solve(
                problem: &$Problem,
                settings: &$Settings,
                workspace: &mut $Workspace,
                out: &mut $Solution,
            ) -> Result<(), $Error> {
                $solve(problem, settings, workspace, out)
            }

            fn status(solution: &$Solution) -> $Status {
                solution.info.status
            }

            fn reset(out: &mut $Solution) {
                let reset: fn(&mut $Solution) = $reset;
                reset(out);
            }
        }
    };
}
