//! The LEO tour's per-arc rendezvous entry points: `reconfig_leo_arc_*` (bodies in
//! [`crate::shell`]).

use crate::convert_leo::{error_to_c, problem_from_c, refusal_to_c, solution_to_c};
use crate::settings::SettingsMirror;
use crate::shell::{self, not_initialised, Entry, Shell, Slot};
use crate::status::ReconfigError;
use crate::types_leo::{ReconfigLeoArcProblem, ReconfigLeoArcSettings, ReconfigLeoArcSolution};
use core::ffi::c_void;
use reconfig_core::leo_tour::{ArcProblem, ArcSolution, Settings, Workspace};
use reconfig_core::wire::{OutcomeRef, Request};

/// The LEO arc in the C shell.
pub struct LeoArc;

/// The initial slot (a `static`: see [`Shell::template`]).
static TEMPLATE_LEO: Slot<Workspace, ArcSolution> = Slot {
    workspace: Workspace::new(),
    solution: ArcSolution::new(),
};

const EMPTY_PROBLEM: ArcProblem = ArcProblem {
    from: [0.0; 6],
    to: [0.0; 6],
    duration_s: 0.0,
    impulses: 0,
};

impl Shell for LeoArc {
    type Slot = Slot<Workspace, ArcSolution>;
    /// "RCFG-LEO" in ASCII.
    const TAG: u64 = 0x5243_4647_2d4c_454f;
    fn template() -> &'static Self::Slot {
        &TEMPLATE_LEO
    }
    fn empty_request() -> Request {
        Request::LeoArc {
            problem: EMPTY_PROBLEM,
            settings: Settings::default(),
        }
    }
}

impl Entry for LeoArc {
    type Planner = Self;
    type Problem = ReconfigLeoArcProblem;
    type Settings = ReconfigLeoArcSettings;
    type Out = ReconfigLeoArcSolution;

    fn fill(
        request: &mut Request,
        problem: &ReconfigLeoArcProblem,
        settings: &ReconfigLeoArcSettings,
    ) -> Result<(), ReconfigError> {
        let Request::LeoArc {
            problem: core_problem,
            settings: core_settings,
        } = request
        else {
            return Err(not_initialised());
        };
        settings.to_core(core_settings)?;
        problem_from_c(problem, core_problem);
        Ok(())
    }

    fn write(
        outcome: OutcomeRef<'_>,
        _request: &Request,
        _problem: &ReconfigLeoArcProblem,
        out: &mut ReconfigLeoArcSolution,
    ) -> Result<i32, ReconfigError> {
        match outcome {
            OutcomeRef::LeoArc(solution) => {
                solution_to_c(solution, out);
                Ok(out.status)
            }
            OutcomeRef::LeoArcRejected(e) => Err(error_to_c(&e)),
            _ => Err(not_initialised()),
        }
    }

    fn refuse(error: ReconfigError, out: &mut ReconfigLeoArcSolution) -> i32 {
        refusal_to_c(error, out);
        out.status
    }
}

/// Bytes of caller memory one LEO-arc workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_leo_arc_workspace_size() -> usize {
    shell::workspace_size::<LeoArc>()
}

/// Alignment, in bytes, a LEO-arc workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_leo_arc_workspace_align() -> usize {
    shell::workspace_align::<LeoArc>()
}

/// Initialise a LEO-arc workspace in `size` bytes of caller memory at `workspace`.
///
/// Returns 0, or `RECONFIG_ERR_NULL_POINTER`, `RECONFIG_ERR_MISALIGNED` or
/// `RECONFIG_ERR_WORKSPACE_TOO_SMALL`.
///
/// # Safety
/// `workspace` is null or points to `size` writable bytes used by nothing else while the
/// workspace is in use.
#[no_mangle]
pub unsafe extern "C" fn reconfig_leo_arc_init(workspace: *mut c_void, size: usize) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { shell::init::<LeoArc>(workspace, size) }
}

/// Write the default settings into `out`. Returns 0, or a null/misaligned refusal.
///
/// # Safety
/// `out` is null or points to writable memory for one `ReconfigLeoArcSettings`.
#[no_mangle]
pub unsafe extern "C" fn reconfig_leo_arc_default_settings(
    out: *mut ReconfigLeoArcSettings,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { shell::default_settings(out) }
}

/// Plan the arc `problem` with `settings` in the initialised `workspace`; write the result into
/// `out`. The request is answered by the core's request path with the built-in limits (the
/// flight service's): a setting outside them is refused `RECONFIG_ERR_LIMIT_EXCEEDED`, named.
///
/// Returns the status code (also in `out->status`): `>= 0` a solve status (only
/// `RECONFIG_LEO_SOLVED` and `RECONFIG_LEO_BUDGET_EXHAUSTED_VERIFIED` may be flown: `usable`),
/// `< 0` a refusal whose field, index, value and limit are in `out->error` (when `out` is
/// usable).
///
/// # Safety
/// Each pointer is null or valid for its type (`workspace`: a block of at least
/// `reconfig_leo_arc_workspace_size()` bytes); `workspace` and `out` are used by nothing else
/// during the call.
#[no_mangle]
pub unsafe extern "C" fn reconfig_leo_arc_solve(
    workspace: *mut c_void,
    problem: *const ReconfigLeoArcProblem,
    settings: *const ReconfigLeoArcSettings,
    out: *mut ReconfigLeoArcSolution,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { shell::solve::<LeoArc>(workspace, problem, settings, out) }
}
