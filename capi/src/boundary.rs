//! Pointer checks shared by the planners' entry points (the workspace block is
//! [`crate::shell::Block`]).

use crate::status::{ReconfigError, RECONFIG_ERR_MISALIGNED, RECONFIG_ERR_NULL_POINTER};

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
