//! # reconfig-firmware-kb
//!
//! Planner B's charged steps on the Cortex-M7, one at a time (issue 33 item 1): every case of
//! `reconfig_core::impulsive::kernels`, its set-up outside the instruction markers, its
//! run between them. One line per case:
//! `fixture index=.. name=.. planner=kernels-b stack_bytes=.. systick_instructions=..
//! work_units=.. kepler_solves=.. kepler_steps=..` (the default image's protocol, `work_units`
//! the units the solve charges for the case, then the Kepler solves and Newton steps the case
//! took: the test allows each solve the most steps a request may take); the exact count is the QEMU plugin's (`tools/qemu-insn-plugin`), one
//! `reconfig-insns` line per case in case order. Built and run by the QEMU test
//! `tests/tests/qemu_firmware/kernels_b_image.rs`, which fails when a charged case costs more
//! than `impulsive::work_units::MAX_INSTRUCTIONS_PER_UNIT` instructions per unit (docs/planner-b.md, "Work budget").
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[path = "m7/measure.rs"]
#[allow(dead_code)]
mod measure;

#[cfg(target_os = "none")]
pub use image::{_stack_end, _stack_start, symbol};

#[cfg(target_os = "none")]
mod image {
    use core::fmt::Write as _;
    use core::hint::black_box;

    use cortex_m_rt::{entry, exception, ExceptionFrame};
    use cortex_m_semihosting::{debug, hio};
    use reconfig_core::impulsive::{
        kernels, newton_counts, newton_counts_reset, Solution, Workspace,
    };

    use crate::measure::{measured, systick};

    extern "C" {
        /// Lowest address the stack may reach.
        pub static _stack_end: u8;
        /// Initial stack pointer (the stack grows down from here).
        pub static _stack_start: u8;
    }

    pub fn symbol(s: &u8) -> usize {
        s as *const u8 as usize
    }

    struct Out(hio::HostStream);

    impl core::fmt::Write for Out {
        fn write_str(&mut self, s: &str) -> core::fmt::Result {
            self.0
                .write_all(s.as_bytes())
                .map_err(|()| core::fmt::Error)
        }
    }

    #[entry]
    fn main() -> ! {
        static mut WORKSPACE: Workspace = Workspace::new();
        static mut SOLUTION: Solution = Solution::new();
        let Ok(stream) = hio::hstdout() else {
            debug::exit(debug::EXIT_FAILURE);
            #[allow(clippy::empty_loop)]
            loop {}
        };
        let mut out = Out(stream);
        let _ = writeln!(out, "reconfig-firmware-kb cases={}", kernels::CASES.len());
        systick::start();
        for (index, case) in kernels::CASES.iter().enumerate() {
            let prepared = kernels::prepare(index, WORKSPACE, SOLUTION);
            let marker = u32::try_from(index).unwrap_or(u32::MAX);
            newton_counts_reset();
            let run = measured(marker, || {
                kernels::run(
                    black_box(index),
                    black_box(&mut *WORKSPACE),
                    black_box(&mut *SOLUTION),
                    black_box(&prepared),
                )
            });
            let (solves, steps) = newton_counts();
            let _ = writeln!(
                out,
                "fixture index={index} name={} planner=kernels-b stack_bytes={} \
                 systick_instructions={} work_units={} kepler_solves={solves} kepler_steps={steps}",
                case.name,
                run.stack_bytes,
                run.ticks * systick::INSTRUCTIONS_PER_TICK,
                run.result
            );
        }
        let _ = writeln!(out, "done cases={}", kernels::CASES.len());
        debug::exit(debug::EXIT_SUCCESS);
        #[allow(clippy::empty_loop)]
        loop {}
    }

    #[panic_handler]
    fn panic(info: &core::panic::PanicInfo) -> ! {
        if let Ok(mut stream) = hio::hstdout() {
            let _ = writeln!(stream, "\npanic: {info}");
        }
        debug::exit(debug::EXIT_FAILURE);
        #[allow(clippy::empty_loop)]
        loop {}
    }

    #[exception]
    unsafe fn HardFault(_frame: &ExceptionFrame) -> ! {
        debug::exit(debug::EXIT_FAILURE);
        #[allow(clippy::empty_loop)]
        loop {}
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "reconfig-firmware-kb runs on the emulated Cortex-M7, not on the host (see the module \
         docs of firmware/src/kb_main.rs)."
    );
}
