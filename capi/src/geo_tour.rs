//! The GEO servicing tour's entry points: `reconfig_geo_tour_*`.

use crate::boundary::{block_mut, check_pointer, init_block, Block};
use crate::convert_geo::{
    error_to_c, problem_from_c, refusal_to_c, settings_from_c, settings_to_c, solution_to_c,
};
use crate::status::*;
use crate::types_geo::{ReconfigGeoProblem, ReconfigGeoSettings, ReconfigGeoSolution};
use core::ffi::c_void;
use reconfig_core::geo_tour::{
    self, MethodPolicy, Problem, Settings, Solution, SweepChoice, Workspace,
};

/// The GEO tour's workspace block.
type BlockGeo = Block<Workspace, Problem, Solution>;

/// "RCFG-GEO" in ASCII: the tag of an initialised GEO-tour workspace.
const TAG_GEO: u64 = 0x5243_4647_2d47_454f;

/// The initial block (a `static`, copied from its one place by `_init`; see planner B's).
static TEMPLATE_GEO: BlockGeo = Block {
    tag: 0,
    workspace: Workspace::new(),
    problem: Problem {
        start_lon_rad: 0.0,
        targets_lon_rad: heapless::Vec::new(),
        mission_time_s: 0.0,
        max_burn_mps: 0.0,
        sweep: SweepChoice::Cheaper,
        policy: MethodPolicy::ByCost,
    },
    solution: Solution::new(),
};

/// Bytes of caller memory one GEO-tour workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_geo_tour_workspace_size() -> usize {
    core::mem::size_of::<BlockGeo>()
}

/// Alignment, in bytes, a GEO-tour workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_geo_tour_workspace_align() -> usize {
    core::mem::align_of::<BlockGeo>()
}

/// Initialise a GEO-tour workspace in `size` bytes of caller memory at `workspace`.
///
/// Returns 0, or `RECONFIG_ERR_NULL_POINTER`, `RECONFIG_ERR_MISALIGNED` or
/// `RECONFIG_ERR_WORKSPACE_TOO_SMALL`.
///
/// # Safety
/// `workspace` is null or points to `size` writable bytes used by nothing else while the
/// workspace is in use.
#[no_mangle]
pub unsafe extern "C" fn reconfig_geo_tour_init(workspace: *mut c_void, size: usize) -> i32 {
    // SAFETY: forwarded caller contract.
    match unsafe {
        init_block(
            workspace,
            size,
            &TEMPLATE_GEO,
            TAG_GEO,
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
/// `out` is null or points to writable memory for one `ReconfigGeoSettings`.
#[no_mangle]
pub unsafe extern "C" fn reconfig_geo_tour_default_settings(out: *mut ReconfigGeoSettings) -> i32 {
    if let Err(e) = check_pointer(out.cast_const(), RECONFIG_FIELD_SETTINGS_ARG) {
        return e.code;
    }
    // SAFETY: non-null and aligned (checked); writable by the caller's contract.
    unsafe { out.write(settings_to_c(&Settings::default())) };
    0
}

/// Plan the tour `problem` with `settings` in the initialised `workspace`; write the result
/// into `out`.
///
/// Returns the status code (also in `out->status`): `>= 0` a solve status (only
/// `RECONFIG_GEO_SOLVED` may be flown), `< 0` a refusal whose field, index, value and limit are
/// in `out->error` (when `out` is usable).
///
/// # Safety
/// Each pointer is null or valid for its type (`workspace`: a block of at least
/// `reconfig_geo_tour_workspace_size()` bytes); `workspace` and `out` are used by nothing else
/// during the call.
#[no_mangle]
pub unsafe extern "C" fn reconfig_geo_tour_solve(
    workspace: *mut c_void,
    problem: *const ReconfigGeoProblem,
    settings: *const ReconfigGeoSettings,
    out: *mut ReconfigGeoSolution,
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

/// The checks and the core solve behind [`reconfig_geo_tour_solve`].
///
/// # Safety
/// As [`reconfig_geo_tour_solve`].
unsafe fn plan<'a>(
    workspace: *mut c_void,
    problem: *const ReconfigGeoProblem,
    settings: *const ReconfigGeoSettings,
) -> Result<&'a BlockGeo, ReconfigError> {
    // SAFETY: forwarded caller contract.
    let block: &mut BlockGeo = unsafe { block_mut(workspace, TAG_GEO, RECONFIG_FIELD_WORKSPACE)? };
    check_pointer(problem, RECONFIG_FIELD_PROBLEM)?;
    check_pointer(settings, RECONFIG_FIELD_SETTINGS_ARG)?;
    // SAFETY: non-null and aligned (checked), valid by the caller's contract; plain numbers.
    let (problem, settings) = unsafe { (&*problem, &*settings) };
    let settings = settings_from_c(settings);
    problem_from_c(problem, &mut block.problem)?;
    block.solution = Solution::new();
    geo_tour::solve(
        &block.problem,
        &settings,
        &mut block.workspace,
        &mut block.solution,
    )
    .map_err(|e| error_to_c(&e))?;
    Ok(block)
}
