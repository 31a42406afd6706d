//! Planner B's entry points: `reconfig_impulsive_*`, the mean-element problem form
//! (`_solve`) and the other input forms (`_solve_form`), in the same workspace (bodies in
//! [`crate::shell`]).

use crate::convert_b::input_form_error_to_c;
use crate::convert_b::{error_to_c, problem_from_c, refusal_to_c, solution_to_c};
use crate::convert_b_form::{end_state_to_c, form_problem_from_c};
use crate::settings::SettingsMirror;
use crate::shell::{self, not_initialised, Entry, Shell, Slot};
use crate::status::ReconfigError;
use crate::types_b::{ReconfigBProblem, ReconfigBSettings, ReconfigBSolution};
use crate::types_b_form::{ReconfigBEndState, ReconfigBFormProblem, ReconfigBFormSolution};
use core::ffi::c_void;
use reconfig_core::impulsive::{
    FormProblem, ImpulsePlan, MeanElements, OrbitForm, PlanError, Problem, RelativeElements,
    RelativeForm, Settings, Solution, Workspace,
};
use reconfig_core::wire::{OutcomeRef, Request};

/// Planner B in the C shell, and its mean-element entry point (`_solve`).
pub struct PlannerB;

/// Planner B's other input forms (`_solve_form`), in planner B's block.
pub struct PlannerBForm;

/// The initial slot (a `static`: see [`Shell::template`]).
static TEMPLATE_B: Slot<Workspace, Solution> = Slot {
    workspace: Workspace::new(),
    solution: Solution::new(),
};

const ZERO_MEAN: MeanElements = MeanElements {
    sma_km: 0.0,
    ecc: 0.0,
    inc_rad: 0.0,
    raan_rad: 0.0,
    argp_rad: 0.0,
    mean_anomaly_rad: 0.0,
};

const ZERO_RELATIVE: RelativeElements = RelativeElements {
    dsma_km: 0.0,
    decc: 0.0,
    dinc_rad: 0.0,
    draan_rad: 0.0,
    dargp_rad: 0.0,
    dmean_anomaly_rad: 0.0,
};

const EMPTY_PROBLEM: Problem = Problem {
    chief: ZERO_MEAN,
    initial: ZERO_RELATIVE,
    target: ZERO_RELATIVE,
    plan: ImpulsePlan::Fixed(heapless::Vec::new()),
};

const EMPTY_FORM: FormProblem = FormProblem {
    chief: OrbitForm::Classical(ZERO_MEAN),
    relative: RelativeForm::Elements {
        initial: ZERO_RELATIVE,
        target: ZERO_RELATIVE,
    },
    plan: ImpulsePlan::Fixed(heapless::Vec::new()),
};

/// Put planner B's empty request of the mean-element form or of the other forms into the
/// block. Out of line, so that the request-sized value it builds lives in this call's frame
/// only (the call returns before the solve), not in the frame under every solve.
#[inline(never)]
fn switch_request(request: &mut Request, form: bool) {
    *request = if form {
        Request::ImpulsiveForm {
            problem: EMPTY_FORM,
            settings: Settings::default(),
        }
    } else {
        PlannerB::empty_request()
    };
}

impl Shell for PlannerB {
    type Slot = Slot<Workspace, Solution>;
    /// "RCFG-IMB" in ASCII.
    const TAG: u64 = 0x5243_4647_2d49_4d42;
    fn template() -> &'static Self::Slot {
        &TEMPLATE_B
    }
    fn empty_request() -> Request {
        Request::Impulsive {
            problem: EMPTY_PROBLEM,
            settings: Settings::default(),
        }
    }
}

impl Entry for PlannerB {
    type Planner = Self;
    type Problem = ReconfigBProblem;
    type Settings = ReconfigBSettings;
    type Out = ReconfigBSolution;

    fn fill(
        request: &mut Request,
        problem: &ReconfigBProblem,
        settings: &ReconfigBSettings,
    ) -> Result<(), ReconfigError> {
        // The block's request may hold the other form (the last solve was `_solve_form`).
        if !matches!(request, Request::Impulsive { .. }) {
            switch_request(request, false);
        }
        let Request::Impulsive {
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
        request: &Request,
        _problem: &ReconfigBProblem,
        out: &mut ReconfigBSolution,
    ) -> Result<i32, ReconfigError> {
        match (outcome, request) {
            (OutcomeRef::Impulsive(solution), _) => {
                *out = solution_to_c(solution);
                Ok(out.status)
            }
            // The value a refusal names is read back from the request as planned.
            (OutcomeRef::ImpulsiveRejected(e), Request::Impulsive { problem, .. }) => {
                Err(error_to_c(&e, problem))
            }
            _ => Err(not_initialised()),
        }
    }

    fn refuse(error: ReconfigError, out: &mut ReconfigBSolution) -> i32 {
        *out = refusal_to_c(error);
        out.status
    }
}

impl Entry for PlannerBForm {
    type Planner = PlannerB;
    type Problem = ReconfigBFormProblem;
    type Settings = ReconfigBSettings;
    type Out = ReconfigBFormSolution;

    fn fill(
        request: &mut Request,
        problem: &ReconfigBFormProblem,
        settings: &ReconfigBSettings,
    ) -> Result<(), ReconfigError> {
        if !matches!(request, Request::ImpulsiveForm { .. }) {
            switch_request(request, true);
        }
        let Request::ImpulsiveForm {
            problem: core_problem,
            settings: core_settings,
        } = request
        else {
            return Err(not_initialised());
        };
        settings.to_core(core_settings)?;
        *core_problem = form_problem_from_c(problem)?;
        Ok(())
    }

    fn write(
        outcome: OutcomeRef<'_>,
        request: &Request,
        _problem: &ReconfigBFormProblem,
        out: &mut ReconfigBFormSolution,
    ) -> Result<i32, ReconfigError> {
        match (outcome, request) {
            (
                OutcomeRef::ImpulsiveForm {
                    solution,
                    end_state,
                },
                _,
            ) => {
                *out = ReconfigBFormSolution {
                    plan: solution_to_c(solution),
                    end: end_state_to_c(&end_state),
                };
                Ok(out.plan.status)
            }
            (OutcomeRef::ImpulsiveRejected(PlanError::InputForm { part, error }), _) => {
                Err(input_form_error_to_c(part, error))
            }
            // The conversion succeeded before the planner refused: convert again (the solve
            // was refused, so the time is there) to read the refused value back as planned.
            (OutcomeRef::ImpulsiveRejected(e), Request::ImpulsiveForm { problem, settings }) => {
                Err(match problem.to_problem(settings) {
                    Ok(converted) => error_to_c(&e, &converted),
                    Err((part, error)) => input_form_error_to_c(part, error),
                })
            }
            _ => Err(not_initialised()),
        }
    }

    fn refuse(error: ReconfigError, out: &mut ReconfigBFormSolution) -> i32 {
        *out = ReconfigBFormSolution {
            plan: refusal_to_c(error),
            end: ReconfigBEndState::default(),
        };
        out.plan.status
    }
}

/// Bytes of caller memory one planner-B workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_impulsive_workspace_size() -> usize {
    shell::workspace_size::<PlannerB>()
}

/// Alignment, in bytes, a planner-B workspace needs.
#[no_mangle]
pub extern "C" fn reconfig_impulsive_workspace_align() -> usize {
    shell::workspace_align::<PlannerB>()
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
    unsafe { shell::init::<PlannerB>(workspace, size) }
}

/// Write the default settings into `out`. Returns 0, or a null/misaligned refusal.
///
/// # Safety
/// `out` is null or points to writable memory for one `ReconfigBSettings`.
#[no_mangle]
pub unsafe extern "C" fn reconfig_impulsive_default_settings(out: *mut ReconfigBSettings) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { shell::default_settings(out) }
}

/// Plan `problem` with `settings` in the initialised `workspace`; write the result into `out`.
/// The request is answered by the core's request path with the built-in limits (the flight
/// service's): a setting outside them is refused `RECONFIG_ERR_LIMIT_EXCEEDED`, named (the
/// limits require `nonlinear_correction = 1`).
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
    // SAFETY: forwarded caller contract.
    unsafe { shell::solve::<PlannerB>(workspace, problem, settings, out) }
}

/// Plan a request given in other forms (`problem`: the chief as mean classical or equinoctial
/// elements or an osculating ECI state; the relative state as element differences, ROE or the
/// deputy's own orbits) with `settings` in the initialised planner-B `workspace`; write the plan
/// and its end state, in the form the target was given in, into `out`. The conversion runs on
/// board (the core's `impulsive::solve_form`) and is charged to the same work budget; the
/// built-in limits also bound the orbits as given (eccentricity below 1, perigee altitude, the
/// chief's `|sin i|` under ROE: `RECONFIG_ERR_LIMIT_EXCEEDED` with `index` 128 and up).
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
    // SAFETY: forwarded caller contract.
    unsafe { shell::solve::<PlannerBForm>(workspace, problem, settings, out) }
}
