//! The C shell every planner shares, written once: the workspace block in caller memory and the
//! bodies of `_workspace_size`, `_workspace_align`, `_init`, `_default_settings` and `_solve`.
//! Each planner's module keeps only its `extern "C"` one-liners (cbindgen reads them there: it
//! does not expand macros or generics), its [`Shell`] (the core's buffers) and its [`Entry`]
//! (how its C structs fill a `wire::Request` and how an outcome becomes its C solution).
//!
//! Every `_solve` answers through the core's one request path, `wire::answer(request, limits,
//! buffers)`, with the built-in limits (`Limits::default()`, the flight service's): the block
//! holds the request (filled in place from the C structs, so nothing of its size is built on the
//! stack), the limits and the planner's workspace and solution (the block's [`Slot`] is the
//! `wire::Buffers` that carry this one planner).

use crate::boundary::check_pointer;
use crate::settings::SettingsMirror;
use crate::status::{
    limit_violation_to_c, ReconfigError, RECONFIG_ERR_WORKSPACE_NOT_INITIALISED,
    RECONFIG_ERR_WORKSPACE_TOO_SMALL, RECONFIG_FIELD_NONE, RECONFIG_FIELD_PROBLEM,
    RECONFIG_FIELD_SETTINGS_ARG, RECONFIG_FIELD_WORKSPACE,
};
use core::ffi::c_void;
use reconfig_core::limits::Limits;
use reconfig_core::wire::{self, Buffers, Lent, OutcomeRef, Request};
use reconfig_core::{geo_tour, hybrid, impulsive, leo_tour, pseudospectral};

/// A planner's workspace and the solution it writes (the block's `wire::Buffers`).
#[repr(C)]
pub struct Slot<W, S> {
    /// The core's workspace.
    pub workspace: W,
    /// The core's solution.
    pub solution: S,
}

impl Buffers for Slot<pseudospectral::Workspace, pseudospectral::Solution> {
    fn pseudospectral(&mut self) -> Lent<'_, pseudospectral::Workspace, pseudospectral::Solution> {
        Some((&mut self.workspace, &mut self.solution))
    }
}

impl Buffers for Slot<impulsive::Workspace, impulsive::Solution> {
    fn impulsive(&mut self) -> Lent<'_, impulsive::Workspace, impulsive::Solution> {
        Some((&mut self.workspace, &mut self.solution))
    }
}

impl Buffers for Slot<geo_tour::Workspace, geo_tour::Solution> {
    fn geo_tour(&mut self) -> Lent<'_, geo_tour::Workspace, geo_tour::Solution> {
        Some((&mut self.workspace, &mut self.solution))
    }
}

impl Buffers for Slot<leo_tour::Workspace, leo_tour::ArcSolution> {
    fn leo_arc(&mut self) -> Lent<'_, leo_tour::Workspace, leo_tour::ArcSolution> {
        Some((&mut self.workspace, &mut self.solution))
    }
}

impl Buffers for Slot<hybrid::Workspace, hybrid::Solution> {
    fn hybrid(&mut self) -> Lent<'_, hybrid::Workspace, hybrid::Solution> {
        Some((&mut self.workspace, &mut self.solution))
    }
}

/// A planner's workspace block in caller memory: everything a solve needs beyond a few hundred
/// bytes lives here, never on the stack.
#[repr(C)]
pub struct Block<P: Shell> {
    /// Written last by `_init`; `_solve` refuses a block without this planner's tag.
    pub tag: u64,
    /// The built-in limits (`Limits::default()`, the flight service's), written by `_init`.
    pub limits: Limits,
    /// The request, filled in place from the caller's C structs at each solve.
    pub request: Request,
    /// The planner's workspace and solution.
    pub slot: P::Slot,
}

/// A planner's buffers in the block.
pub trait Shell: Sized + 'static {
    /// The workspace and solution (`Slot<Workspace, Solution>`).
    type Slot: Buffers + 'static;
    /// The tag `_init` writes ("RCFG-..." in ASCII).
    const TAG: u64;
    /// The initial slot: a `static`, copied from its one place by `_init` (a `&CONST` compiled a
    /// stack temporary of the whole slot in the dev profile; the test
    /// `init_builds_no_workspace_on_the_stack` caught it).
    fn template() -> &'static Self::Slot;
    /// The block's first request (the planner's variant, empty problem, default settings).
    fn empty_request() -> Request;
}

/// One `_solve` entry point: its C structs and how they meet the request path.
pub trait Entry {
    /// The block it solves in.
    type Planner: Shell;
    /// The C problem.
    type Problem;
    /// The C settings.
    type Settings: SettingsMirror;
    /// The C solution.
    type Out;

    /// Fill the block's request from the C structs, in place.
    ///
    /// # Errors
    /// What a C struct can hold and the core's types cannot (a count above its array, a flag
    /// not 0 or 1, a code outside its set).
    fn fill(
        request: &mut Request,
        problem: &Self::Problem,
        settings: &Self::Settings,
    ) -> Result<(), ReconfigError>;

    /// Write the answer into `out` and return its status code, or the refusal the outcome is
    /// (`request` and `problem` as answered: a refusal reads the refused value back).
    ///
    /// # Errors
    /// The planner's refusal, or an outcome this entry cannot write.
    fn write(
        outcome: OutcomeRef<'_>,
        request: &Request,
        problem: &Self::Problem,
        out: &mut Self::Out,
    ) -> Result<i32, ReconfigError>;

    /// Write a refusal into `out` (every other field reset) and return its code.
    fn refuse(error: ReconfigError, out: &mut Self::Out) -> i32;
}

/// The refusal of a block that does not hold this planner's request (never met after this
/// planner's `_init`), or of an outcome an entry cannot write.
pub const fn not_initialised() -> ReconfigError {
    ReconfigError::new(
        RECONFIG_ERR_WORKSPACE_NOT_INITIALISED,
        RECONFIG_FIELD_WORKSPACE,
        0.0,
        0.0,
    )
}

/// Body of `reconfig_<p>_workspace_size`.
pub const fn workspace_size<P: Shell>() -> usize {
    core::mem::size_of::<Block<P>>()
}

/// Body of `reconfig_<p>_workspace_align`.
pub const fn workspace_align<P: Shell>() -> usize {
    core::mem::align_of::<Block<P>>()
}

/// Body of `reconfig_<p>_init`: checks null, alignment and size, copies the planner's slot
/// template (a static, so no stack temporary of the slot's size), writes the built-in limits
/// and the empty request, then the tag.
///
/// # Safety
/// `memory` is null or points to `size` writable bytes that nothing else uses while the block
/// lives.
pub unsafe fn init<P: Shell>(memory: *mut c_void, size: usize) -> i32 {
    let block = memory.cast::<Block<P>>();
    if let Err(e) = check_pointer(block.cast_const(), RECONFIG_FIELD_WORKSPACE) {
        return e.code;
    }
    let needed = core::mem::size_of::<Block<P>>();
    if size < needed {
        return RECONFIG_ERR_WORKSPACE_TOO_SMALL;
    }
    // SAFETY: `block` is non-null, aligned and has `needed <= size` writable bytes (checked
    // above, and the caller's contract), so each field's place is valid for a write; writes
    // through raw field pointers never read the (uninitialised) old contents. `template` is a
    // distinct static of the slot's type, so the copy's regions do not overlap; the slots hold
    // only plain data (no drop glue), so a bitwise copy is a valid value.
    unsafe {
        core::ptr::copy_nonoverlapping(
            core::ptr::from_ref(P::template()),
            core::ptr::addr_of_mut!((*block).slot),
            1,
        );
        core::ptr::addr_of_mut!((*block).limits).write(Limits::default());
        core::ptr::addr_of_mut!((*block).request).write(P::empty_request());
        // Last: the block is whole now.
        core::ptr::addr_of_mut!((*block).tag).write(P::TAG);
    }
    0
}

/// The block behind a `_solve` pointer, refused unless non-null, aligned and tagged by this
/// planner's `_init`.
///
/// # Safety
/// `memory` is null or points to at least `size_of::<Block<P>>()` bytes that this call may use
/// exclusively until the returned reference is dropped; if they carry the tag, they hold a block
/// written by [`init`] (the tag is a best-effort check against uninitialised memory, not a
/// proof).
unsafe fn block_mut<'a, P: Shell>(memory: *mut c_void) -> Result<&'a mut Block<P>, ReconfigError> {
    let block = memory.cast::<Block<P>>();
    check_pointer(block.cast_const(), RECONFIG_FIELD_WORKSPACE)?;
    // SAFETY: non-null and aligned (checked), at least a block's size (caller's contract); the
    // tag is a plain u64, valid for any bit pattern.
    let found = unsafe { core::ptr::addr_of!((*block).tag).read() };
    if found != P::TAG {
        return Err(not_initialised());
    }
    // SAFETY: tagged by `init`, so it holds a valid block; exclusive by the caller's contract
    // (one workspace per task).
    Ok(unsafe { &mut *block })
}

/// Body of `reconfig_<p>_default_settings`: the core's defaults as the C struct.
///
/// # Safety
/// `out` is null or points to writable memory for one `C`.
pub unsafe fn default_settings<C: SettingsMirror>(out: *mut C) -> i32 {
    if let Err(e) = check_pointer(out.cast_const(), RECONFIG_FIELD_SETTINGS_ARG) {
        return e.code;
    }
    // SAFETY: non-null and aligned (checked); writable by the caller's contract.
    unsafe { out.write(C::from_core(&C::Core::default())) };
    0
}

/// Body of every `reconfig_<p>_solve`: the pointer checks, the request filled in the block,
/// `wire::answer` with the block's built-in limits into the block's slot, and the outcome
/// written as the C solution (or refusal). Returns the status code.
///
/// # Safety
/// Each pointer is null or valid for its type (`workspace`: a block of at least
/// `workspace_size::<E::Planner>()` bytes); `workspace` and `out` are used by nothing else
/// during the call.
pub unsafe fn solve<E: Entry>(
    workspace: *mut c_void,
    problem: *const E::Problem,
    settings: *const E::Settings,
    out: *mut E::Out,
) -> i32 {
    if let Err(e) = check_pointer(out.cast_const(), RECONFIG_FIELD_NONE) {
        return e.code;
    }
    // SAFETY: non-null and aligned (checked); valid and exclusive by the caller's contract;
    // every C solution is plain numbers, valid for any bits.
    let out = unsafe { &mut *out };
    // SAFETY: forwarded caller contract.
    let prepared = unsafe { prepare::<E>(workspace, problem, settings) };
    let (block, problem) = match prepared {
        Ok(prepared) => prepared,
        Err(e) => return E::refuse(e, out),
    };
    let Block {
        limits,
        request,
        slot,
        ..
    } = block;
    let written = match wire::answer(request, limits, slot) {
        OutcomeRef::LimitExceeded(violation) => Err(limit_violation_to_c(&violation)),
        outcome => E::write(outcome, request, problem, out),
    };
    match written {
        Ok(status) => status,
        Err(e) => E::refuse(e, out),
    }
}

/// The checks and the request behind [`solve`].
///
/// # Safety
/// As [`solve`].
unsafe fn prepare<'a, E: Entry>(
    workspace: *mut c_void,
    problem: *const E::Problem,
    settings: *const E::Settings,
) -> Result<(&'a mut Block<E::Planner>, &'a E::Problem), ReconfigError> {
    // SAFETY: forwarded caller contract.
    let block = unsafe { block_mut::<E::Planner>(workspace)? };
    check_pointer(problem, RECONFIG_FIELD_PROBLEM)?;
    check_pointer(settings, RECONFIG_FIELD_SETTINGS_ARG)?;
    // SAFETY: non-null and aligned (checked), valid by the caller's contract; plain numbers.
    let (problem, settings) = unsafe { (&*problem, &*settings) };
    E::fill(&mut block.request, problem, settings)?;
    Ok((block, problem))
}
