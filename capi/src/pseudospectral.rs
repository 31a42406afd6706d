//! Planner A's entry points: `reconfig_pseudospectral_*`.

use crate::boundary::{block_mut, check_pointer, init_block, Block};
use crate::convert_a::{
    error_to_c, problem_from_c, refusal_to_c, settings_from_c, settings_to_c, solution_to_c,
};
use crate::status::*;
use crate::types_a::{ReconfigAProblem, ReconfigASettings, ReconfigASolution};
use core::ffi::c_void;
use reconfig_core::pseudospectral::{self, Problem, Settings, Solution, Workspace};

/// Planner A's workspace block.
type BlockA = Block<Workspace, Problem, Solution>;

/// "RCFG-PSA" in ASCII: the tag of an initialised planner-A workspace.
const TAG_A: u64 = 0x5243_4647_2d50_5341;

/// The initial block. A `static`, not a `const`: `_init` copies it from its one place, where
/// `&CONST` compiled a stack temporary of the whole block in the dev profile (the test
/// `init_builds_no_workspace_on_the_stack` caught it).
static TEMPLATE_A: BlockA = Block {
    tag: 0,
    workspace: Workspace::new(),
    problem: Problem {
        horizon_tu: 0.0,
        max_control_fu: 0.0,
        keep_out_lu: 0.0,
        degree: 0,
        test_points: false,
        spacecraft: heapless::Vec::new(),
    },
    solution: Solution::new(),
};

/// Bytes of caller memory one planner-A workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_pseudospectral_workspace_size() -> usize {
    core::mem::size_of::<BlockA>()
}

/// Alignment, in bytes, a planner-A workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_pseudospectral_workspace_align() -> usize {
    core::mem::align_of::<BlockA>()
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
    match unsafe {
        init_block(
            workspace,
            size,
            &TEMPLATE_A,
            TAG_A,
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
/// `out` is null or points to writable memory for one `ReconfigASettings`.
#[no_mangle]
pub unsafe extern "C" fn reconfig_pseudospectral_default_settings(
    out: *mut ReconfigASettings,
) -> i32 {
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
/// `reconfig_pseudospectral_workspace_size()` bytes); `workspace` and `out` are used by
/// nothing else during the call.
#[no_mangle]
pub unsafe extern "C" fn reconfig_pseudospectral_solve(
    workspace: *mut c_void,
    problem: *const ReconfigAProblem,
    settings: *const ReconfigASettings,
    out: *mut ReconfigASolution,
) -> i32 {
    if let Err(e) = check_pointer(out.cast_const(), RECONFIG_FIELD_NONE) {
        return e.code;
    }
    // SAFETY: non-null and aligned (checked); valid and exclusive by the caller's contract;
    // every field is a plain number, valid for any bits.
    let out = unsafe { &mut *out };
    // SAFETY: forwarded caller contract.
    let planned = unsafe { plan(workspace, problem, settings) };
    match planned {
        Ok(block) => {
            solution_to_c(&block.solution, out);
        }
        Err(e) => refusal_to_c(e, out),
    }
    out.status
}

/// The checks and the core solve behind [`reconfig_pseudospectral_solve`].
///
/// # Safety
/// As [`reconfig_pseudospectral_solve`].
unsafe fn plan<'a>(
    workspace: *mut c_void,
    problem: *const ReconfigAProblem,
    settings: *const ReconfigASettings,
) -> Result<&'a BlockA, ReconfigError> {
    // SAFETY: forwarded caller contract.
    let block: &mut BlockA = unsafe { block_mut(workspace, TAG_A, RECONFIG_FIELD_WORKSPACE)? };
    check_pointer(problem, RECONFIG_FIELD_PROBLEM)?;
    check_pointer(settings, RECONFIG_FIELD_SETTINGS_ARG)?;
    // SAFETY: non-null and aligned (checked), valid by the caller's contract; plain numbers.
    let (problem, settings) = unsafe { (&*problem, &*settings) };
    let settings = settings_from_c(settings)?;
    problem_from_c(problem, &mut block.problem)?;
    block.solution.reset();
    pseudospectral::solve(
        &block.problem,
        &settings,
        &mut block.workspace,
        &mut block.solution,
    )
    .map_err(|e| error_to_c(&e, problem))?;
    Ok(block)
}
