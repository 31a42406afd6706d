//! Pointer checks and the caller-owned workspace block, shared by the planners' entry points.
//!
//! A workspace block is [`Block`]: a tag written by `_init` (so that `_solve` can refuse memory
//! that was never initialised for this planner), then the core's workspace, the core's problem
//! and the core's solution. Everything a solve needs beyond a few hundred bytes lives there, in
//! the caller's memory, never on the stack.

use crate::status::{
    ReconfigError, RECONFIG_ERR_MISALIGNED, RECONFIG_ERR_NULL_POINTER,
    RECONFIG_ERR_WORKSPACE_NOT_INITIALISED, RECONFIG_ERR_WORKSPACE_TOO_SMALL,
};
use core::ffi::c_void;

/// A planner's workspace block in caller memory.
#[repr(C)]
pub struct Block<W, P, S> {
    /// Written last by `_init`; `_solve` refuses a block without this planner's tag.
    pub tag: u64,
    /// The core's workspace.
    pub workspace: W,
    /// The core's problem, converted from the caller's C struct at each solve.
    pub problem: P,
    /// The core's solution, converted to the caller's C struct at each solve.
    pub solution: S,
}

/// Refuse a null or misaligned pointer to a `T`.
///
/// # Errors
/// `RECONFIG_ERR_NULL_POINTER` or `RECONFIG_ERR_MISALIGNED` (`value` = the address, `limit` =
/// the alignment needed), naming `field`.
pub fn check_pointer<T>(ptr: *const T, field: i32) -> Result<(), ReconfigError> {
    if ptr.is_null() {
        return Err(ReconfigError::new(
            RECONFIG_ERR_NULL_POINTER,
            field,
            0.0,
            0.0,
        ));
    }
    if !ptr.is_aligned() {
        return Err(ReconfigError::new(
            RECONFIG_ERR_MISALIGNED,
            field,
            ptr.addr() as f64,
            core::mem::align_of::<T>() as f64,
        ));
    }
    Ok(())
}

/// Initialise a workspace block of caller memory in place: checks null, alignment and size,
/// copies `template` (a static, so no stack temporary of the block's size), then writes
/// `tag`.
///
/// # Errors
/// Null, misaligned, or `size` below `size_of::<Block>()` (`value` = size, `limit` = needed).
///
/// # Safety
/// `memory` must be null or point to `size` writable bytes that nothing else uses while the
/// block lives.
pub unsafe fn init_block<W, P, S>(
    memory: *mut c_void,
    size: usize,
    template: &Block<W, P, S>,
    tag: u64,
    field: i32,
) -> Result<(), ReconfigError> {
    let block = memory.cast::<Block<W, P, S>>();
    check_pointer(block.cast_const(), field)?;
    let needed = core::mem::size_of::<Block<W, P, S>>();
    if size < needed {
        return Err(ReconfigError::new(
            RECONFIG_ERR_WORKSPACE_TOO_SMALL,
            field,
            size as f64,
            needed as f64,
        ));
    }
    // SAFETY: `block` is non-null, aligned and has `needed <= size` writable bytes (checked
    // above, and the caller's contract); `template` is a distinct, valid value of the same
    // type, so the regions do not overlap. The blocks hold only plain data (no drop glue), so
    // a bitwise copy is a valid value.
    unsafe { core::ptr::copy_nonoverlapping(core::ptr::from_ref(template), block, 1) };
    // SAFETY: `block` now holds a valid block (just written).
    unsafe { (*block).tag = tag };
    Ok(())
}

/// The workspace block behind a `_solve` pointer, refused unless non-null, aligned and tagged
/// by this planner's `_init`.
///
/// # Errors
/// Null, misaligned or not initialised.
///
/// # Safety
/// `memory` must be null or point to at least `size_of::<Block>()` bytes of memory that this
/// call may use exclusively until the returned reference is dropped; if it carries `tag`, they
/// hold a block written by `init_block` (the tag is a best-effort check against uninitialised
/// memory, not a proof).
pub unsafe fn block_mut<'a, W, P, S>(
    memory: *mut c_void,
    tag: u64,
    field: i32,
) -> Result<&'a mut Block<W, P, S>, ReconfigError> {
    let block = memory.cast::<Block<W, P, S>>();
    check_pointer(block.cast_const(), field)?;
    // SAFETY: non-null and aligned (checked), at least a block's size (caller's contract);
    // the tag is a plain u64, valid for any bit pattern.
    let found = unsafe { core::ptr::addr_of!((*block).tag).read() };
    if found != tag {
        return Err(ReconfigError::new(
            RECONFIG_ERR_WORKSPACE_NOT_INITIALISED,
            field,
            0.0,
            0.0,
        ));
    }
    // SAFETY: tagged by `init_block`, so it holds a valid block; exclusive by the caller's
    // contract (one workspace per task).
    Ok(unsafe { &mut *block })
}
