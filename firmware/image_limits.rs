//! The limits every firmware image answers its requests under (`wire::answer` checks each
//! request against them before solving). `no_std` and shared by three includers (`#[path]`):
//! the firmware (a `static` in flash: no RAM), its build script (the host answers a LEO tour's
//! sequencing under them to build the arcs' requests) and the QEMU tests (the host's answer to
//! each baked request, compared byte for byte with the M7's).

use reconfig_core::limits::Limits;

/// The built-in limits, with planner B's nonlinear correction allowed off: every fixed-point
/// planner-B fixture also runs as `<name>+fixed-point`, the fixed-point plan alone
/// (`impulsive::Settings::fixed_point_only()`), the plan the 2 M instruction budget is for
/// (docs/firmware.md). Every other limit is the built-in one.
pub const IMAGE_LIMITS: Limits = {
    let mut limits = Limits::BUILT_IN;
    limits.impulsive.settings.nonlinear_correction = false;
    limits
};
