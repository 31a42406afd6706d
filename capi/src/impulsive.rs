//! Planner B's entry points: `reconfig_impulsive_*`, the mean-element problem form
//! (`_solve`) and the other input forms (`_solve_form`), in the same workspace.

use crate::boundary::{block_mut, check_pointer, init_block, Block};
use crate::convert_b::{
    error_to_c, problem_from_c, refusal_to_c, settings_from_c, settings_to_c, solution_to_c,
};
use crate::convert_b_form::{end_state_to_c, form_problem_from_c, input_form_error_to_c};
use crate::status::*;
use crate::types_b::{ReconfigBProblem, ReconfigBSettings, ReconfigBSolution};
use crate::types_b_form::{ReconfigBEndState, ReconfigBFormProblem, ReconfigBFormSolution};
use core::ffi::c_void;
use reconfig_core::impulsive::{
    self, EndState, ImpulsePlan, MeanElements, PlanError, Problem, RelativeElements, Settings,
    Solution, Workspace,
};

/// Planner B's workspace block.
type BlockB = Block<Workspace, Problem, Solution>;

/// "RCFG-IMB" in ASCII: the tag of an initialised planner-B workspace.
const TAG_B: u64 = 0x5243_4647_2d49_4d42;

const ZERO_RELATIVE: RelativeElements = RelativeElements {
    dsma_km: 0.0,
    decc: 0.0,
    dinc_rad: 0.0,
    draan_rad: 0.0,
    dargp_rad: 0.0,
    dmean_anomaly_rad: 0.0,
};

/// The initial block. A `static`, not a `const`: `_init` copies it from its one place, where
/// `&CONST` compiled a stack temporary of the whole block in the dev profile (the test
/// `init_builds_no_workspace_on_the_stack` caught it).
static TEMPLATE_B: BlockB = Block {
    tag: 0,
    workspace: Workspace::new(),
    problem: Problem {
        chief: MeanElements {
            sma_km: 0.0,
            ecc: 0.0,
            inc_rad: 0.0,
            raan_rad: 0.0,
            argp_rad: 0.0,
            mean_anomaly_rad: 0.0,
        },
        initial: ZERO_RELATIVE,
        target: ZERO_RELATIVE,
        plan: ImpulsePlan::Fixed(heapless::Vec::new()),
    },
    solution: Solution::new(),
};

/// Bytes of caller memory one planner-B workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_impulsive_workspace_size() -> usize {
    core::mem::size_of::<BlockB>()
}

/// Alignment, in bytes, a planner-B workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_impulsive_workspace_align() -> usize {
    core::mem::align_of::<BlockB>()
}

/// Initialise a planner-B workspace in `size` bytes of caller memory at `workspace`.
///
/// Returns 0, or `RECONFIG_ERR_NULL_POINTER`, `RECONFIG_ERR_MISALIGNED` or
/// `RECONFIG_ERR_WORKSPACE_TOO_SMALL`.
///
/// # Safety
/// `workspace` is null or points to `size` writable bytes used by nothing else while the
/// workspace is in use.
#[no_mangle]
pub unsafe extern "C" fn reconfig_impulsive_init(workspace: *mut c_void, size: usize) -> i32 {
    // SAFETY: forwarded caller contract.
    match unsafe {
        init_block(
            workspace,
            size,
            &TEMPLATE_B,
            TAG_B,
            RECONFIG_FIELD_WORKSPACE,
        )
    } {
        Ok(()) => 0,
        Err(e) => e.code,
    }
}

/// Write the default settings into `out`. Returns 0, or a null/misaligned refusal.
///
/// # Safety
/// `out` is null or points to writable memory for one `ReconfigBSettings`.
#[no_mangle]
pub unsafe extern "C" fn reconfig_impulsive_default_settings(out: *mut ReconfigBSettings) -> i32 {
    if let Err(e) = check_pointer(out.cast_const(), RECONFIG_FIELD_SETTINGS_ARG) {
        return e.code;
    }
    // SAFETY: non-null and aligned (checked); writable by the caller's contract.
    unsafe { out.write(settings_to_c(&Settings::default())) };
    0
}

/// Plan `problem` with `settings` in the initialised `workspace`; write the result into `out`.
///
/// Returns the status code (also in `out->status`): `>= 0` a solve status, `< 0` a refusal
/// whose field, index, value and limit are in `out->error` (when `out` is usable).
///
/// # Safety
/// Each pointer is null or valid for its type (`workspace`: a block of at least
/// `reconfig_impulsive_workspace_size()` bytes); `workspace` and `out` are used by nothing
/// else during the call.
#[no_mangle]
pub unsafe extern "C" fn reconfig_impulsive_solve(
    workspace: *mut c_void,
    problem: *const ReconfigBProblem,
    settings: *const ReconfigBSettings,
    out: *mut ReconfigBSolution,
) -> i32 {
    if let Err(e) = check_pointer(out.cast_const(), RECONFIG_FIELD_NONE) {
        return e.code;
    }
    // SAFETY: forwarded caller contract.
    let written = match unsafe { plan(workspace, problem, settings) } {
        Ok(block) => solution_to_c(&block.solution),
        Err(e) => refusal_to_c(e),
    };
    // SAFETY: non-null and aligned (checked); writable and exclusive by the caller's contract.
    unsafe { out.write(written) };
    written.status
}

/// The checks and the core solve behind [`reconfig_impulsive_solve`].
///
/// # Safety
/// As [`reconfig_impulsive_solve`].
unsafe fn plan<'a>(
    workspace: *mut c_void,
    problem: *const ReconfigBProblem,
    settings: *const ReconfigBSettings,
) -> Result<&'a BlockB, ReconfigError> {
    // SAFETY: forwarded caller contract.
    let block: &mut BlockB = unsafe { block_mut(workspace, TAG_B, RECONFIG_FIELD_WORKSPACE)? };
    check_pointer(problem, RECONFIG_FIELD_PROBLEM)?;
    check_pointer(settings, RECONFIG_FIELD_SETTINGS_ARG)?;
    // SAFETY: non-null and aligned (checked), valid by the caller's contract; plain numbers.
    let (problem, settings) = unsafe { (&*problem, &*settings) };
    let settings = settings_from_c(settings)?;
    problem_from_c(problem, &mut block.problem)?;
    block.solution = Solution::new();
    impulsive::solve(
        &block.problem,
        &settings,
        &mut block.workspace,
        &mut block.solution,
    )
    .map_err(|e| error_to_c(&e, &block.problem))?;
    Ok(block)
}

/// Plan a request given in other forms (`problem`: the chief as mean classical or equinoctial
/// elements or an osculating ECI state; the relative state as element differences, ROE or the
/// deputy's own orbits) with `settings` in the initialised planner-B `workspace`; write the plan
/// and its end state, in the form the target was given in, into `out`. The conversion runs on
/// board (the core's `impulsive::solve_form`) and is charged to the same work budget.
///
/// Returns the status code (also in `out->plan.status`): `>= 0` a solve status, `< 0` a
/// refusal whose field, index, value and limit are in `out->plan.error`
/// (`RECONFIG_B_ERR_INPUT_FORM` for a part that cannot be converted).
///
/// # Safety
/// As [`reconfig_impulsive_solve`], with `out` valid for one `ReconfigBFormSolution`.
#[no_mangle]
pub unsafe extern "C" fn reconfig_impulsive_solve_form(
    workspace: *mut c_void,
    problem: *const ReconfigBFormProblem,
    settings: *const ReconfigBSettings,
    out: *mut ReconfigBFormSolution,
) -> i32 {
    if let Err(e) = check_pointer(out.cast_const(), RECONFIG_FIELD_NONE) {
        return e.code;
    }
    // SAFETY: forwarded caller contract.
    let written = match unsafe { plan_form(workspace, problem, settings) } {
        Ok((block, end)) => ReconfigBFormSolution {
            plan: solution_to_c(&block.solution),
            end: end_state_to_c(&end),
        },
        Err(e) => ReconfigBFormSolution {
            plan: refusal_to_c(e),
            end: ReconfigBEndState::default(),
        },
    };
    // SAFETY: non-null and aligned (checked); writable and exclusive by the caller's contract.
    unsafe { out.write(written) };
    written.plan.status
}

/// The checks and the core solve behind [`reconfig_impulsive_solve_form`].
///
/// # Safety
/// As [`reconfig_impulsive_solve_form`].
unsafe fn plan_form<'a>(
    workspace: *mut c_void,
    problem: *const ReconfigBFormProblem,
    settings: *const ReconfigBSettings,
) -> Result<(&'a BlockB, EndState), ReconfigError> {
    // SAFETY: forwarded caller contract.
    let block: &mut BlockB = unsafe { block_mut(workspace, TAG_B, RECONFIG_FIELD_WORKSPACE)? };
    check_pointer(problem, RECONFIG_FIELD_PROBLEM)?;
    check_pointer(settings, RECONFIG_FIELD_SETTINGS_ARG)?;
    // SAFETY: non-null and aligned (checked), valid by the caller's contract; plain numbers.
    let (problem, settings) = unsafe { (&*problem, &*settings) };
    let settings = settings_from_c(settings)?;
    let form = form_problem_from_c(problem)?;
    block.solution = Solution::new();
    let end = impulsive::solve_form(&form, &settings, &mut block.workspace, &mut block.solution)
        .map_err(|e| match e {
            PlanError::InputForm { part, error } => input_form_error_to_c(part, error),
            // The conversion succeeded before the planner refused: convert again (the solve
            // was refused, so the time is there) to read the refused value back as planned.
            other => match form.to_problem(&settings) {
                Ok(converted) => error_to_c(&other, &converted),
                Err((part, error)) => input_form_error_to_c(part, error),
            },
        })?;
    Ok((block, end))
}
