//! Measuring a solve: the instruction-count markers the QEMU plugin watches, SysTick time, and
//! the stack high-water (paint below the current frame, scan after).

use core::arch::asm;
use core::hint::black_box;
use core::ptr::addr_of_mut;

use cortex_m_rt::exception;

use super::{_stack_end, _stack_start, symbol};

/// What cortex-m-rt's `paint-stack` feature writes over the stack at reset (its
/// `STACK_PAINT_VALUE`); repainted below the current frame before each solve.
const STACK_PAINT: u32 = 0xCCCC_CCCC;

/// Written by the markers, so that they have different bodies (identical functions could be
/// merged into one address) and cannot be optimised away.
static mut MEASURE_STARTED: u32 = 0;
static mut MEASURE_STOPPED: u32 = 0;

/// Marks the start of a measured solve for the instruction-counting QEMU plugin.
#[no_mangle]
#[inline(never)]
pub extern "C" fn reconfig_measure_start(index: u32) {
    // SAFETY: single-threaded, no interrupts touch it. The asm is a compiler barrier (it may
    // access memory), so the solve's work cannot move across the marker.
    unsafe {
        addr_of_mut!(MEASURE_STARTED).write_volatile(index);
        asm!("nop");
    }
}

/// Marks the end of a measured solve for the instruction-counting QEMU plugin.
#[no_mangle]
#[inline(never)]
pub extern "C" fn reconfig_measure_stop(index: u32) {
    // SAFETY: as in `reconfig_measure_start`.
    unsafe {
        addr_of_mut!(MEASURE_STOPPED).write_volatile(index);
        asm!("nop", "nop");
    }
}

/// SysTick, free-running over its full 24-bit range; wraps are counted by the SysTick exception.
/// Under the runner's `-icount shift=0` QEMU advances virtual time by 1 ns per instruction and
/// clocks SysTick at the board's 25 MHz, so one tick is 40 instructions.
pub mod systick {
    use core::ptr::{addr_of, addr_of_mut};

    const CSR: *mut u32 = 0xE000_E010 as *mut u32;
    const RVR: *mut u32 = 0xE000_E014 as *mut u32;
    const CVR: *mut u32 = 0xE000_E018 as *mut u32;
    const RELOAD: u32 = 0x00FF_FFFF;
    /// Instructions per SysTick tick under `-icount shift=0` (1 ns each) at 25 MHz.
    pub const INSTRUCTIONS_PER_TICK: u64 = 40;

    static mut WRAPS: u32 = 0;

    /// Start counting: processor clock, exception on wrap.
    pub fn start() {
        // SAFETY: the SysTick registers of every ARMv7-M core; nothing else uses SysTick.
        unsafe {
            RVR.write_volatile(RELOAD);
            CVR.write_volatile(0);
            CSR.write_volatile(0b111);
        }
    }

    /// Called from the SysTick exception.
    pub fn wrapped() {
        // SAFETY: only the exception writes it; readers re-read until it is stable.
        unsafe { addr_of_mut!(WRAPS).write_volatile(addr_of!(WRAPS).read_volatile() + 1) };
    }

    /// Ticks since `start`.
    pub fn now() -> u64 {
        loop {
            // SAFETY: as above; a wrap between the reads shows as a changed count and retries.
            let (before, current, after) = unsafe {
                (
                    addr_of!(WRAPS).read_volatile(),
                    CVR.read_volatile(),
                    addr_of!(WRAPS).read_volatile(),
                )
            };
            if before == after {
                return u64::from(before) * (u64::from(RELOAD) + 1) + u64::from(RELOAD - current);
            }
        }
    }
}

#[exception]
fn SysTick() {
    systick::wrapped();
}

/// Paint the unused stack (from its lowest address up to a margin below the current stack
/// pointer) so that a later scan finds how deep the next code went.
#[inline(never)]
pub fn repaint_stack() {
    let sp: usize;
    // SAFETY: reads the stack pointer only.
    unsafe { asm!("mov {}, sp", out(reg) sp, options(nomem, nostack, preserves_flags)) };
    // SAFETY: linker-script symbols; only their addresses are used.
    let low = unsafe { symbol(&_stack_end) };
    // This function is a leaf that keeps its locals in registers; 64 bytes of margin cover any
    // spill, and lie below the frame of every caller.
    let high = sp.saturating_sub(64) & !3;
    let mut p = low;
    while p < high {
        // SAFETY: [low, high) is stack below the live frames, word aligned, not in use.
        unsafe { (p as *mut u32).write_volatile(STACK_PAINT) };
        p += 4;
    }
}

/// Bytes of stack used since reset or the last repaint: from the initial stack pointer down to
/// the lowest word that no longer holds the paint.
pub fn stack_high_water() -> usize {
    // SAFETY: linker-script symbols; only their addresses are used.
    let (low, top) = unsafe { (symbol(&_stack_end), symbol(&_stack_start)) };
    let mut p = low;
    // SAFETY: [low, top) is the stack region, word aligned and readable.
    while p < top && unsafe { (p as *const u32).read_volatile() } == STACK_PAINT {
        p += 4;
    }
    top - p
}

/// What one measured solve gave: its result, its SysTick time and the stack high-water since
/// the last repaint.
pub struct Measured<R> {
    pub result: R,
    pub ticks: u64,
    pub stack_bytes: usize,
}

/// Runs `solve` between the instruction-count markers. The caller passes the inputs through
/// `black_box` inside `solve` (after the start marker) and the result passes through it before
/// the stop marker, so no part of the solve is folded away or moved out of the measured span.
#[inline(always)]
pub fn measured<R>(marker: u32, solve: impl FnOnce() -> R) -> Measured<R> {
    let ticks_before = systick::now();
    reconfig_measure_start(marker);
    let result = solve();
    black_box(&result);
    reconfig_measure_stop(marker);
    let ticks = systick::now() - ticks_before;
    Measured {
        result,
        ticks,
        stack_bytes: stack_high_water(),
    }
}
