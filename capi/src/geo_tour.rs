//! The GEO servicing tour's entry points: `reconfig_geo_tour_*` (bodies in [`crate::shell`]).

use crate::convert_geo::{error_to_c, problem_from_c, refusal_to_c, solution_to_c};
use crate::settings::SettingsMirror;
use crate::shell::{self, not_initialised, Entry, Shell, Slot};
use crate::status::ReconfigError;
use crate::types_geo::{ReconfigGeoProblem, ReconfigGeoSettings, ReconfigGeoSolution};
use core::ffi::c_void;
use reconfig_core::geo_tour::{MethodPolicy, Problem, Settings, Solution, SweepChoice, Workspace};
use reconfig_core::wire::{OutcomeRef, Request};

/// The GEO tour in the C shell.
pub struct GeoTour;

/// The initial slot (a `static`: see [`Shell::template`]).
static TEMPLATE_GEO: Slot<Workspace, Solution> = Slot {
    workspace: Workspace::new(),
    solution: Solution::new(),
};

const EMPTY_PROBLEM: Problem = Problem {
    start_lon_rad: 0.0,
    targets_lon_rad: heapless::Vec::new(),
    mission_time_s: 0.0,
    max_burn_mps: 0.0,
    sweep: SweepChoice::Cheaper,
    policy: MethodPolicy::ByCost,
};

impl Shell for GeoTour {
    type Slot = Slot<Workspace, Solution>;
    /// "RCFG-GEO" in ASCII.
    const TAG: u64 = 0x5243_4647_2d47_454f;
    fn template() -> &'static Self::Slot {
        &TEMPLATE_GEO
    }
    fn empty_request() -> Request {
        Request::GeoTour {
            problem: EMPTY_PROBLEM,
            settings: Settings::default(),
        }
    }
}

impl Entry for GeoTour {
    type Planner = Self;
    type Problem = ReconfigGeoProblem;
    type Settings = ReconfigGeoSettings;
    type Out = ReconfigGeoSolution;

    fn fill(
        request: &mut Request,
        problem: &ReconfigGeoProblem,
        settings: &ReconfigGeoSettings,
    ) -> Result<(), ReconfigError> {
        let Request::GeoTour {
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
        _problem: &ReconfigGeoProblem,
        out: &mut ReconfigGeoSolution,
    ) -> Result<i32, ReconfigError> {
        match outcome {
            OutcomeRef::GeoTour(solution) => {
                solution_to_c(solution, out);
                Ok(out.status)
            }
            OutcomeRef::GeoTourRejected(e) => Err(error_to_c(&e)),
            _ => Err(not_initialised()),
        }
    }

    fn refuse(error: ReconfigError, out: &mut ReconfigGeoSolution) -> i32 {
        refusal_to_c(error, out);
        out.status
    }
}

/// Bytes of caller memory one GEO-tour workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_geo_tour_workspace_size() -> usize {
    shell::workspace_size::<GeoTour>()
}

/// Alignment, in bytes, a GEO-tour workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_geo_tour_workspace_align() -> usize {
    shell::workspace_align::<GeoTour>()
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
    unsafe { shell::init::<GeoTour>(workspace, size) }
}

/// Write the default settings into `out`. Returns 0, or a null/misaligned refusal.
///
/// # Safety
/// `out` is null or points to writable memory for one `ReconfigGeoSettings`.
#[no_mangle]
pub unsafe extern "C" fn reconfig_geo_tour_default_settings(out: *mut ReconfigGeoSettings) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { shell::default_settings(out) }
}

/// Plan the tour `problem` with `settings` in the initialised `workspace`; write the result
/// into `out`. The request is answered by the core's request path with the built-in limits
/// (the flight service's): a setting outside them is refused `RECONFIG_ERR_LIMIT_EXCEEDED`,
/// named.
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
    // SAFETY: forwarded caller contract.
    unsafe { shell::solve::<GeoTour>(workspace, problem, settings, out) }
}
