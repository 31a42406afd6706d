//! What the kernel images share (`reconfig-firmware-ka`, `-kb`, `-kl`: planner A's, planner
//! B's and the LEO arc's charged steps, one at a time; issue 33): the measurement
//! (`measure.rs`) and the stop handlers (`runtime.rs`, the default image's too), the output
//! stream, and the loop that runs every case of a planner's
//! `kernels` module, its set-up outside the instruction markers and its run between them. One
//! line per case:
//! `fixture index=.. name=.. planner=kernels-.. stack_bytes=.. systick_instructions=..
//! work_units=..` (the default image's protocol, `work_units` the units the solve charges for
//! the case), with `kepler_solves=.. kepler_steps=..` where the planner's flights solve
//! Kepler's equation (the test allows each solve the most Newton steps a request may take).
//! The exact count is the QEMU plugin's (`tools/qemu-insn-plugin`), one `reconfig-insns` line
//! per case in case order. Each image's main names its planner and gives its cases
//! ([`KernelSet`]); the test is `tests/tests/qemu_firmware/kernels_image.rs`.

use core::fmt::Write as _;

use cortex_m_semihosting::{debug, hio};

#[path = "measure.rs"]
#[allow(dead_code)]
mod measure;
#[path = "runtime.rs"]
mod runtime;

use measure::{measured, repaint_stack, systick};
use runtime::fail;

extern "C" {
    /// Lowest address the stack may reach.
    pub static _stack_end: u8;
    /// Initial stack pointer (the stack grows down from here).
    pub static _stack_start: u8;
}

pub fn symbol(s: &u8) -> usize {
    s as *const u8 as usize
}

/// The semihosting output.
pub struct Out(hio::HostStream);

impl core::fmt::Write for Out {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        self.0
            .write_all(s.as_bytes())
            .map_err(|()| core::fmt::Error)
    }
}

/// Kepler's counters: reset them, read them as `(solves, Newton steps)`.
pub type KeplerCounters = (fn(), fn() -> (u32, u32));

/// One planner's kernel cases, over the state `S` they run in (its workspace, its solution),
/// each set up into a `P`.
pub struct KernelSet<S, P> {
    /// The image's name, in its first line.
    pub image: &'static str,
    /// The `planner=` of its lines.
    pub planner: &'static str,
    /// How many cases.
    pub count: usize,
    /// Case `index`'s name.
    pub name: fn(usize) -> &'static str,
    /// A case's set-up (outside the markers).
    pub prepare: fn(usize, &mut S) -> P,
    /// A case's run (between the markers): the units the solve charges for it.
    pub run: fn(usize, &mut S, &P) -> u64,
    /// The Kepler counters (reset, read as `(solves, Newton steps)`), for a planner whose
    /// flights solve Kepler's equation.
    pub kepler: Option<KeplerCounters>,
}

/// Run every case of `set` on `state`, print its line, and exit QEMU.
pub fn run_cases<S, P>(set: &KernelSet<S, P>, state: &mut S) -> ! {
    let Ok(stream) = hio::hstdout() else { fail() };
    let mut out = Out(stream);
    let count = set.count;
    let _ = writeln!(out, "{} cases={count}", set.image);
    systick::start();
    for index in 0..count {
        let name = (set.name)(index);
        let prepared = (set.prepare)(index, state);
        if let Some((reset, _)) = set.kepler {
            reset();
        }
        repaint_stack();
        let marker = u32::try_from(index).unwrap_or(u32::MAX);
        let run = measured(marker, || {
            (set.run)(
                core::hint::black_box(index),
                core::hint::black_box(&mut *state),
                core::hint::black_box(&prepared),
            )
        });
        let _ = write!(
            out,
            "fixture index={index} name={name} planner={} stack_bytes={} \
             systick_instructions={} work_units={}",
            set.planner,
            run.stack_bytes,
            run.ticks * systick::INSTRUCTIONS_PER_TICK,
            run.result
        );
        if let Some((_, counts)) = set.kepler {
            let (solves, steps) = counts();
            let _ = write!(out, " kepler_solves={solves} kepler_steps={steps}");
        }
        let _ = writeln!(out);
    }
    let _ = writeln!(out, "done cases={count}");
    debug::exit(debug::EXIT_SUCCESS);
    #[allow(clippy::empty_loop)]
    loop {}
}
