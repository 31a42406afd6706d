//! The Cortex-M7 program: answer every baked-in request through the core's one request path
//! (`wire::answer`: the image's limits, then the planner, into the image's static buffers),
//! print results and figures, exit.
//!
//! Output protocol (semihosting stdout, one record per line, `key=value` fields; parsed by
//! `tests/tests/qemu_firmware/`):
//! ```text
//! reconfig-firmware version=0.1.0 fixtures=5
//! binary text_bytes=.. rodata_bytes=.. data_bytes=.. bss_bytes=.. uninit_bytes=.. static_ram_bytes=..
//! planners pseudospectral_workspace_bytes=.. pseudospectral_solution_bytes=.. impulsive_workspace_bytes=.. impulsive_solution_bytes=..
//! planners geo_tour_workspace_bytes=.. geo_tour_solution_bytes=..   (GEO image only)
//! planners leo_workspace_bytes=.. leo_sequence_workspace_bytes=.. leo_arc_solution_bytes=.. leo_sequence_bytes=..   (LEO image only)
//! planners hybrid_workspace_bytes=.. hybrid_solution_bytes=..   (hybrid image only)
//! fixture index=0 name=.. planner=pseudospectral outcome=ok|error stack_bytes=.. systick_instructions=.. work_units=.. (work_units when the planner meters its work)
//! result index=0 hex=..
//! kernel index=0 name=.. units=.. stack_bytes=.. systick_instructions=..   (GEO image only, after the fixtures)
//! done fixtures=5
//! ```
//! One `fixture` line per baked request (`fixtures` counts requests). `planner` is the
//! request's (`contract::PlannerKind::name`); `outcome=ok` when the planner planned (the answer carries
//! a plan, usable or not), `error` when the request was refused or rejected. `hex` is the
//! postcard encoding of the answer's `wire::Outcome`. `stack_bytes` is the stack high-water
//! mark during that request's decode and answer, measured from the top of the stack (so it
//! includes `main`'s own frame and the decoded request): the stack below the current frame is
//! painted before the decode and scanned for the lowest overwritten word after the answer.
//! `systick_instructions` is the answer's SysTick time converted to instructions (40 per
//! tick): meaningful only under `-icount shift=0` (the runner sets it), and accurate to about
//! 40 instructions; the exact count comes from the QEMU plugin.
//!
//! The GEO image then runs each case of `geo_tour::kernels` (one charged kernel on its dearest
//! path: its set-up outside the markers, the kernel between them, measurement `fixtures + index`)
//! and prints a `kernel` line: `units` is what the solve charges for what the case ran
//! (docs/geo-tour.md, "Work budget").

use core::fmt::Write as _;
use core::hint::black_box;

use cortex_m_rt::entry;
use cortex_m_semihosting::debug;

#[path = "../../image_limits.rs"]
mod image_limits;
mod measure;
mod output;
mod runtime;

use measure::{measured, repaint_stack, systick};
use output::{print_result, report, Out};
#[cfg(feature = "geo_tour")]
use reconfig_core::geo_tour;
#[cfg(feature = "hybrid")]
use reconfig_core::hybrid;
#[cfg(feature = "leo_tour")]
use reconfig_core::leo_tour;
use reconfig_core::limits::Limits;
use reconfig_core::wire::{self, Buffers, Request};
use reconfig_core::{impulsive, pseudospectral};

/// A request baked in by `build.rs`: the postcard bytes of a `wire::Request`.
pub struct Fixture {
    /// Its name.
    pub name: &'static str,
    /// postcard encoding of the `wire::Request`.
    pub request: &'static [u8],
}

include!(concat!(env!("OUT_DIR"), "/fixtures.rs"));

/// The image's limits, in flash (`image_limits.rs`).
static LIMITS: Limits = image_limits::IMAGE_LIMITS;

/// The buffers of the planners this image carries (cargo features), each a `static` (in
/// `.bss`, or `.data` when a `new()` is not all zero bits), never on the stack. A planner the
/// image does not carry keeps the trait's default `None`: the request path answers it
/// `Unsupported`, and its solve is not linked in.
struct Image {
    #[cfg(feature = "pseudospectral")]
    pseudospectral: (
        &'static mut pseudospectral::Workspace,
        &'static mut pseudospectral::Solution,
    ),
    #[cfg(feature = "impulsive")]
    impulsive: (
        &'static mut impulsive::Workspace,
        &'static mut impulsive::Solution,
    ),
    #[cfg(feature = "geo_tour")]
    geo_tour: (
        &'static mut geo_tour::Workspace,
        &'static mut geo_tour::Solution,
    ),
    /// The LEO sequencing's workspace (its memos and an arc search's workspace, which the
    /// arc requests use too: a flight computer answers one at a time), an arc's answer and the
    /// sequencing's.
    #[cfg(feature = "leo_tour")]
    leo: (
        &'static mut leo_tour::tour_order::SequenceWorkspace,
        &'static mut leo_tour::ArcSolution,
        &'static mut leo_tour::sequence::Sequence,
    ),
    /// The hybrid transfer's (its workspace is empty: the integrator's stages are on the stack).
    #[cfg(feature = "hybrid")]
    hybrid: (
        &'static mut hybrid::Workspace,
        &'static mut hybrid::Solution,
    ),
}

impl Buffers for Image {
    #[cfg(feature = "pseudospectral")]
    fn pseudospectral(
        &mut self,
    ) -> Option<(
        &mut pseudospectral::Workspace,
        &mut pseudospectral::Solution,
    )> {
        Some((&mut *self.pseudospectral.0, &mut *self.pseudospectral.1))
    }
    #[cfg(feature = "impulsive")]
    fn impulsive(&mut self) -> Option<(&mut impulsive::Workspace, &mut impulsive::Solution)> {
        Some((&mut *self.impulsive.0, &mut *self.impulsive.1))
    }
    #[cfg(feature = "geo_tour")]
    fn geo_tour(&mut self) -> Option<(&mut geo_tour::Workspace, &mut geo_tour::Solution)> {
        Some((&mut *self.geo_tour.0, &mut *self.geo_tour.1))
    }
    #[cfg(feature = "leo_tour")]
    fn leo_arc(&mut self) -> Option<(&mut leo_tour::Workspace, &mut leo_tour::ArcSolution)> {
        Some((&mut self.leo.0.arc, &mut *self.leo.1))
    }
    #[cfg(feature = "leo_tour")]
    fn leo_sequence(
        &mut self,
    ) -> Option<(
        &mut leo_tour::tour_order::SequenceWorkspace,
        &mut leo_tour::sequence::Sequence,
    )> {
        Some((&mut *self.leo.0, &mut *self.leo.2))
    }
    #[cfg(feature = "hybrid")]
    fn hybrid(&mut self) -> Option<(&mut hybrid::Workspace, &mut hybrid::Solution)> {
        Some((&mut *self.hybrid.0, &mut *self.hybrid.1))
    }
}

extern "C" {
    static __stext: u8;
    static __etext: u8;
    static __srodata: u8;
    static __erodata: u8;
    static __sdata: u8;
    static __edata: u8;
    static __sbss: u8;
    static __ebss: u8;
    static __suninit: u8;
    static __euninit: u8;
    /// Lowest address the stack may reach.
    static _stack_end: u8;
    /// Initial stack pointer (the stack grows down from here).
    static _stack_start: u8;
}

fn symbol(s: &u8) -> usize {
    s as *const u8 as usize
}

#[entry]
fn main() -> ! {
    // cortex-m-rt turns these into `&'static mut` references owned by `main`: the workspaces
    // and output buffers live in static memory, never on the stack. An image carries only its
    // planners' statics (cargo features).
    #[cfg(feature = "pseudospectral")]
    static mut PS_WORKSPACE: pseudospectral::Workspace = pseudospectral::Workspace::new();
    #[cfg(feature = "pseudospectral")]
    static mut PS_SOLUTION: pseudospectral::Solution = pseudospectral::Solution::new();
    #[cfg(feature = "impulsive")]
    static mut IM_WORKSPACE: impulsive::Workspace = impulsive::Workspace::new();
    #[cfg(feature = "impulsive")]
    static mut IM_SOLUTION: impulsive::Solution = impulsive::Solution::new();
    #[cfg(feature = "geo_tour")]
    static mut GEO_WORKSPACE: geo_tour::Workspace = geo_tour::Workspace::new();
    #[cfg(feature = "geo_tour")]
    static mut GEO_SOLUTION: geo_tour::Solution = geo_tour::Solution::new();
    #[cfg(feature = "leo_tour")]
    static mut LEO_WORKSPACE: leo_tour::tour_order::SequenceWorkspace =
        leo_tour::tour_order::SequenceWorkspace::new();
    #[cfg(feature = "leo_tour")]
    static mut LEO_ARC: leo_tour::ArcSolution = leo_tour::ArcSolution::new();
    #[cfg(feature = "leo_tour")]
    static mut LEO_SEQUENCE: leo_tour::sequence::Sequence = leo_tour::sequence::Sequence::new();
    #[cfg(feature = "hybrid")]
    static mut HY_WORKSPACE: hybrid::Workspace = hybrid::Workspace::new();
    #[cfg(feature = "hybrid")]
    static mut HY_SOLUTION: hybrid::Solution = hybrid::Solution::new();

    let mut image = Image {
        #[cfg(feature = "pseudospectral")]
        pseudospectral: (PS_WORKSPACE, PS_SOLUTION),
        #[cfg(feature = "impulsive")]
        impulsive: (IM_WORKSPACE, IM_SOLUTION),
        #[cfg(feature = "geo_tour")]
        geo_tour: (GEO_WORKSPACE, GEO_SOLUTION),
        #[cfg(feature = "leo_tour")]
        leo: (LEO_WORKSPACE, LEO_ARC, LEO_SEQUENCE),
        #[cfg(feature = "hybrid")]
        hybrid: (HY_WORKSPACE, HY_SOLUTION),
    };

    let mut out = Out::new();
    let _ = writeln!(
        out,
        "reconfig-firmware version={} fixtures={}",
        env!("CARGO_PKG_VERSION"),
        FIXTURES.len()
    );
    // SAFETY: linker-script symbols; only their addresses are used.
    unsafe {
        let _ = writeln!(
            out,
            "binary text_bytes={} rodata_bytes={} data_bytes={} bss_bytes={} uninit_bytes={} static_ram_bytes={}",
            symbol(&__etext) - symbol(&__stext),
            symbol(&__erodata) - symbol(&__srodata),
            symbol(&__edata) - symbol(&__sdata),
            symbol(&__ebss) - symbol(&__sbss),
            symbol(&__euninit) - symbol(&__suninit),
            symbol(&__euninit) - symbol(&__sdata),
        );
    }
    // What each planner's static memory costs at the compiled capacities (part of .bss/.data).
    let _ = writeln!(
        out,
        "planners pseudospectral_workspace_bytes={} pseudospectral_solution_bytes={} \
         impulsive_workspace_bytes={} impulsive_solution_bytes={}",
        core::mem::size_of::<pseudospectral::Workspace>(),
        core::mem::size_of::<pseudospectral::Solution>(),
        core::mem::size_of::<impulsive::Workspace>(),
        core::mem::size_of::<impulsive::Solution>(),
    );

    #[cfg(feature = "geo_tour")]
    let _ = writeln!(
        out,
        "planners geo_tour_workspace_bytes={} geo_tour_solution_bytes={}",
        core::mem::size_of::<geo_tour::Workspace>(),
        core::mem::size_of::<geo_tour::Solution>(),
    );

    #[cfg(feature = "leo_tour")]
    let _ = writeln!(
        out,
        "planners leo_workspace_bytes={} leo_sequence_workspace_bytes={} \
         leo_arc_solution_bytes={} leo_sequence_bytes={}",
        core::mem::size_of::<leo_tour::Workspace>(),
        core::mem::size_of::<leo_tour::tour_order::SequenceWorkspace>(),
        core::mem::size_of::<leo_tour::ArcSolution>(),
        core::mem::size_of::<leo_tour::sequence::Sequence>(),
    );

    #[cfg(feature = "hybrid")]
    let _ = writeln!(
        out,
        "planners hybrid_workspace_bytes={} hybrid_solution_bytes={}",
        core::mem::size_of::<hybrid::Workspace>(),
        core::mem::size_of::<hybrid::Solution>(),
    );

    systick::start();
    for (index, fixture) in FIXTURES.iter().enumerate() {
        let marker = u32::try_from(index).unwrap_or(u32::MAX);
        answer(&mut out, (index, marker, fixture), &mut image);
    }
    #[cfg(feature = "geo_tour")]
    run_geo_kernels(&mut out, &mut *image.geo_tour.0);
    let _ = writeln!(out, "done fixtures={}", FIXTURES.len());
    debug::exit(debug::EXIT_SUCCESS);
    #[allow(clippy::empty_loop)]
    loop {}
}

/// Decode one baked request and answer it through `wire::answer`, measured, then report it and
/// print its outcome. Never inlined: its frame (the decoded request, the answer) is the part of
/// the stack high-water above the request path, the same for every request. The buffers are
/// reused on purpose (the request path resets a planner's solution before its solve; no answer
/// may depend on what an earlier one left in the workspace).
#[inline(never)]
fn answer(out: &mut Out, (index, marker, fixture): (usize, u32, &Fixture), image: &mut Image) {
    repaint_stack();
    let request = decode(fixture);
    // The inputs pass through `black_box` after the start marker and the result before the stop
    // marker, so that no part of the answer is folded away or moved out of the measured span.
    let run = measured(marker, || {
        wire::answer(
            black_box(&request),
            black_box(&LIMITS),
            black_box(&mut *image),
        )
    });
    report(
        out,
        index,
        fixture,
        request.planner().name(),
        run.result.usable().is_some(),
        run.stack_bytes,
        (run.ticks, run.result.work_units()),
    );
    print_result(out, index, &run.result);
}

/// Every case of `geo_tour::kernels` (the GEO image), after the fixtures: its set-up outside
/// the markers, its run between them (measurement `FIXTURES.len() + index`); one `kernel` line
/// each. Never inlined, as [`answer`].
#[cfg(feature = "geo_tour")]
#[inline(never)]
fn run_geo_kernels(out: &mut Out, workspace: &mut geo_tour::Workspace) {
    use geo_tour::kernels;
    for (index, case) in kernels::CASES.iter().enumerate() {
        let prepared = kernels::prepare(index, workspace);
        repaint_stack();
        let marker = u32::try_from(FIXTURES.len() + index).unwrap_or(u32::MAX);
        let run = measured(marker, || {
            kernels::run(
                black_box(index),
                black_box(&mut *workspace),
                black_box(&prepared),
            )
        });
        let _ = writeln!(
            out,
            "kernel index={index} name={} units={} stack_bytes={} systick_instructions={}",
            case.name,
            run.result,
            run.stack_bytes,
            run.ticks * systick::INSTRUCTIONS_PER_TICK
        );
    }
}

/// A baked request decoded (`build.rs` encoded these bytes from a `wire::Request`: a failure
/// is a build fault, fatal). Never inlined: the decoder's temporaries stay in this frame, below
/// the caller's, and are gone before the answer.
#[inline(never)]
fn decode(fixture: &Fixture) -> Request {
    match postcard::from_bytes(fixture.request) {
        Ok(request) => request,
        Err(_) => panic!("request {} does not decode", fixture.name),
    }
}
