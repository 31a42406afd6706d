//! The hybrid chemical + electric transfer's entry points: `reconfig_hybrid_*` (bodies in
//! [`crate::shell`]).
//!
//! The solve is stack-only: the core's workspace is empty, and the integrator's stages (13 x
//! 210 numbers with the state-transition matrix) and the bang-bang law's event location sit in
//! the solve's frames, about 74 KB on the Cortex-M7 (docs/c-api.md): the calling thread's stack
//! must allow it.

use crate::convert_hybrid::{error_to_c, problem_from_c, refusal_to_c, solution_to_c};
use crate::settings::SettingsMirror;
use crate::shell::{self, not_initialised, Entry, Shell, Slot};
use crate::status::ReconfigError;
use crate::types_hybrid::{ReconfigHybridProblem, ReconfigHybridSettings, ReconfigHybridSolution};
use core::ffi::c_void;
use reconfig_core::hybrid::{Objective, Problem, Settings, Solution, Workspace};
use reconfig_core::wire::{OutcomeRef, Request};

/// The hybrid transfer in the C shell.
pub struct Hybrid;

/// The initial slot (a `static`: see [`Shell::template`]).
static TEMPLATE_HYBRID: Slot<Workspace, Solution> = Slot {
    workspace: Workspace::new(),
    solution: Solution::new(),
};

const EMPTY_PROBLEM: Problem = Problem {
    objective: Objective::MinFuel,
    kappa: 0.0,
    theta_rad: 0.0,
    free_kappa: false,
    free_theta: false,
    duration_days: 0.0,
    thrust_n: 0.0,
    specific_impulse_s: 0.0,
    chemical_specific_impulse_s: 0.0,
    parking_radius_km: 0.0,
    departure_offset: [0.0; 7],
    arrival_r_lu: [0.0; 3],
    arrival_v_vu: [0.0; 3],
    halo_period_tu: 0.0,
    costates: [0.0; 7],
    cost_multiplier: 0.0,
    design_duration_days: 0.0,
    design_thrust_n: 0.0,
};

impl Shell for Hybrid {
    type Slot = Slot<Workspace, Solution>;
    /// "RCFG-HYB" in ASCII.
    const TAG: u64 = 0x5243_4647_2d48_5942;
    fn template() -> &'static Self::Slot {
        &TEMPLATE_HYBRID
    }
    fn empty_request() -> Request {
        Request::Hybrid {
            problem: EMPTY_PROBLEM,
            settings: Settings::DEFAULT,
        }
    }
}

impl Entry for Hybrid {
    type Planner = Self;
    type Problem = ReconfigHybridProblem;
    type Settings = ReconfigHybridSettings;
    type Out = ReconfigHybridSolution;

    fn fill(
        request: &mut Request,
        problem: &ReconfigHybridProblem,
        settings: &ReconfigHybridSettings,
    ) -> Result<(), ReconfigError> {
        let Request::Hybrid {
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
        _problem: &ReconfigHybridProblem,
        out: &mut ReconfigHybridSolution,
    ) -> Result<i32, ReconfigError> {
        match outcome {
            OutcomeRef::Hybrid(solution) => {
                solution_to_c(solution, out);
                Ok(out.status)
            }
            OutcomeRef::HybridRejected(e) => Err(error_to_c(&e)),
            _ => Err(not_initialised()),
        }
    }

    fn refuse(error: ReconfigError, out: &mut ReconfigHybridSolution) -> i32 {
        refusal_to_c(error, out);
        out.status
    }
}

/// Bytes of caller memory one hybrid-transfer workspace needs (the request, the built-in limits
/// and the solution: the planner's own scratch is on the stack, see `reconfig_hybrid_solve`).
#[no_mangle]
pub extern "C" fn reconfig_hybrid_workspace_size() -> usize {
    shell::workspace_size::<Hybrid>()
}

/// Alignment, in bytes, a hybrid-transfer workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_hybrid_workspace_align() -> usize {
    shell::workspace_align::<Hybrid>()
}

/// Initialise a hybrid-transfer workspace in `size` bytes of caller memory at `workspace`.
///
/// Returns 0, or `RECONFIG_ERR_NULL_POINTER`, `RECONFIG_ERR_MISALIGNED` or
/// `RECONFIG_ERR_WORKSPACE_TOO_SMALL`.
///
/// # Safety
/// `workspace` is null or points to `size` writable bytes used by nothing else while the
/// workspace is in use.
#[no_mangle]
pub unsafe extern "C" fn reconfig_hybrid_init(workspace: *mut c_void, size: usize) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { shell::init::<Hybrid>(workspace, size) }
}

/// Write the default settings into `out`. Returns 0, or a null/misaligned refusal.
///
/// # Safety
/// `out` is null or points to writable memory for one `ReconfigHybridSettings`.
#[no_mangle]
pub unsafe extern "C" fn reconfig_hybrid_default_settings(out: *mut ReconfigHybridSettings) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { shell::default_settings(out) }
}

/// Re-converge the transfer `problem` from its design costates with `settings` in the
/// initialised `workspace`; write the result into `out`. The request is answered by the core's
/// request path with the built-in limits (the flight service's): a setting outside them is
/// refused `RECONFIG_ERR_LIMIT_EXCEEDED`, named.
///
/// The solve is stack-only: the integrator's stages with the state-transition matrix need
/// about 74 KB of the calling thread's stack on the Cortex-M7 (docs/c-api.md); call it from a
/// task whose stack allows that.
///
/// Returns the status code (also in `out->status`): `>= 0` a solve status (only
/// `RECONFIG_HYBRID_SOLVED` and `RECONFIG_HYBRID_BUDGET_EXHAUSTED_VERIFIED` may be flown:
/// `usable`), `< 0` a refusal whose field, index, value and limit are in `out->error` (when
/// `out` is usable).
///
/// # Safety
/// Each pointer is null or valid for its type (`workspace`: a block of at least
/// `reconfig_hybrid_workspace_size()` bytes); `workspace` and `out` are used by nothing else
/// during the call.
#[no_mangle]
pub unsafe extern "C" fn reconfig_hybrid_solve(
    workspace: *mut c_void,
    problem: *const ReconfigHybridProblem,
    settings: *const ReconfigHybridSettings,
    out: *mut ReconfigHybridSolution,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { shell::solve::<Hybrid>(workspace, problem, settings, out) }
}
