//! What every image does when it stops abnormally: exit QEMU with failure, after printing the
//! panic, the fault's frame or the unexpected exception on semihosting (the tests show it).
//! One copy for the default, GEO and LEO images (`mod.rs`) and the kernel images
//! (`kernel_image.rs`): each binary includes it once.

use core::fmt::Write as _;

use cortex_m_rt::{exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hio};

/// Exit QEMU with failure.
pub fn fail() -> ! {
    debug::exit(debug::EXIT_FAILURE);
    #[allow(clippy::empty_loop)]
    loop {}
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    if let Ok(mut stream) = hio::hstdout() {
        let _ = writeln!(stream, "\npanic: {info}");
    }
    fail()
}

#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    if let Ok(mut stream) = hio::hstdout() {
        let _ = writeln!(stream, "\nHardFault: {frame:?}");
    }
    fail()
}

#[exception]
unsafe fn DefaultHandler(irqn: i16) {
    if let Ok(mut stream) = hio::hstdout() {
        let _ = writeln!(stream, "\nunexpected exception or interrupt {irqn}");
    }
    fail()
}
