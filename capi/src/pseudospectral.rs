//! Planner A's entry points: `reconfig_pseudospectral_*` (bodies in [`crate::shell`]).

use crate::convert_a::{error_to_c, problem_from_c, refusal_to_c, solution_to_c};
use crate::settings::SettingsMirror;
use crate::shell::{self, not_initialised, Entry, Shell, Slot};
use crate::status::ReconfigError;
use crate::types_a::{ReconfigAProblem, ReconfigASettings, ReconfigASolution};
use core::ffi::c_void;
use reconfig_core::pseudospectral::{Problem, Settings, Solution, Workspace};
use reconfig_core::wire::{OutcomeRef, Request};

/// Planner A in the C shell.
pub struct PlannerA;

/// The initial slot (a `static`: see [`Shell::template`]).
static TEMPLATE_A: Slot<Workspace, Solution> = Slot {
    workspace: Workspace::new(),
    solution: Solution::new(),
};

const EMPTY_PROBLEM: Problem = Problem {
    horizon_tu: 0.0,
    max_control_fu: 0.0,
    keep_out_lu: 0.0,
    degree: 0,
    test_points: false,
    spacecraft: heapless::Vec::new(),
};

impl Shell for PlannerA {
    type Slot = Slot<Workspace, Solution>;
    /// "RCFG-PSA" in ASCII.
    const TAG: u64 = 0x5243_4647_2d50_5341;
    fn template() -> &'static Self::Slot {
        &TEMPLATE_A
    }
    fn empty_request() -> Request {
        Request::Pseudospectral {
            problem: EMPTY_PROBLEM,
            settings: Settings::default(),
        }
    }
}

impl Entry for PlannerA {
    type Planner = Self;
    type Problem = ReconfigAProblem;
    type Settings = ReconfigASettings;
    type Out = ReconfigASolution;

    fn fill(
        request: &mut Request,
        problem: &ReconfigAProblem,
        settings: &ReconfigASettings,
    ) -> Result<(), ReconfigError> {
        let Request::Pseudospectral {
            problem: core_problem,
            settings: core_settings,
        } = request
        else {
            return Err(not_initialised());
        };
        settings.to_core(core_settings)?;
        problem_from_c(problem, core_problem)
    }

    fn write(
        outcome: OutcomeRef<'_>,
        _request: &Request,
        problem: &ReconfigAProblem,
        out: &mut ReconfigASolution,
    ) -> Result<i32, ReconfigError> {
        match outcome {
            OutcomeRef::Pseudospectral(solution) => {
                solution_to_c(solution, out);
                Ok(out.status)
            }
            OutcomeRef::PseudospectralRejected(e) => Err(error_to_c(&e, problem)),
            _ => Err(not_initialised()),
        }
    }

    fn refuse(error: ReconfigError, out: &mut ReconfigASolution) -> i32 {
        refusal_to_c(error, out);
        out.status
    }
}

/// Bytes of caller memory one planner-A workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_pseudospectral_workspace_size() -> usize {
    shell::workspace_size::<PlannerA>()
}

/// Alignment, in bytes, a planner-A workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_pseudospectral_workspace_align() -> usize {
    shell::workspace_align::<PlannerA>()
}

/// Initialise a planner-A workspace in `size` bytes of caller memory at `workspace`.
///
/// Returns 0, or `RECONFIG_ERR_NULL_POINTER`, `RECONFIG_ERR_MISALIGNED` or
/// `RECONFIG_ERR_WORKSPACE_TOO_SMALL`.
///
/// # Safety
/// `workspace` is null or points to `size` writable bytes used by nothing else while the
/// workspace is in use.
#[no_mangle]
pub unsafe extern "C" fn reconfig_pseudospectral_init(workspace: *mut c_void, size: usize) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { shell::init::<PlannerA>(workspace, size) }
}

/// Write the default settings into `out`. Returns 0, or a null/misaligned refusal.
///
/// # Safety
/// `out` is null or points to writable memory for one `ReconfigASettings`.
#[no_mangle]
pub unsafe extern "C" fn reconfig_pseudospectral_default_settings(
    out: *mut ReconfigASettings,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { shell::default_settings(out) }
}

/// Plan `problem` with `settings` in the initialised `workspace`; write the result into `out`.
/// The request is answered by the core's request path with the built-in limits (the flight
/// service's): a setting outside them is refused `RECONFIG_ERR_LIMIT_EXCEEDED`, named.
///
/// Returns the status code (also in `out->status`): `>= 0` a solve status, `< 0` a refusal
/// whose field, index, value and limit are in `out->error` (when `out` is usable).
///
/// # Safety
/// Each pointer is null or valid for its type (`workspace`: a block of at least
/// `reconfig_pseudospectral_workspace_size()` bytes); `workspace` and `out` are used by
/// nothing else during the call.
#[no_mangle]
pub unsafe extern "C" fn reconfig_pseudospectral_solve(
    workspace: *mut c_void,
    problem: *const ReconfigAProblem,
    settings: *const ReconfigASettings,
    out: *mut ReconfigASolution,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { shell::solve::<PlannerA>(workspace, problem, settings, out) }
}
