//! The Cortex-M7 program: run every baked-in fixture, print results and figures, exit.
//!
//! Output protocol (semihosting stdout, one record per line, `key=value` fields; parsed by
//! `tests/tests/qemu_firmware/`):
//! ```text
//! reconfig-firmware version=0.1.0 fixtures=5
//! binary text_bytes=.. rodata_bytes=.. data_bytes=.. bss_bytes=.. uninit_bytes=.. static_ram_bytes=..
//! planners pseudospectral_workspace_bytes=.. pseudospectral_solution_bytes=.. impulsive_workspace_bytes=.. impulsive_solution_bytes=..
//! planners geo_tour_workspace_bytes=.. geo_tour_solution_bytes=..   (GEO image only)
//! planners leo_workspace_bytes=.. leo_sequence_workspace_bytes=.. leo_arc_solution_bytes=.. leo_onboard_plan_bytes=..   (LEO image only)
//! fixture index=0 name=.. planner=pseudospectral outcome=ok|error stack_bytes=.. systick_instructions=.. work_units=.. (no work_units on the GEO image)
//! result index=0 hex=..
//! done fixtures=5
//! ```
//! `hex` is the postcard encoding of `Result<Solution, PlanError>`. `stack_bytes` is the stack
//! high-water mark during that fixture's decode and solve, measured from the top of the stack
//! (so it includes `main`'s own frame): the stack below the current frame is painted before the
//! solve and scanned for the lowest overwritten word after it. `systick_instructions` is the
//! solve's SysTick time converted to instructions (40 per tick): meaningful only under
//! `-icount shift=0` (the runner sets it), and accurate to about 40 instructions; the exact
//! count comes from the QEMU plugin.

use core::fmt::Write as _;
use core::hint::black_box;

use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hio};

mod measure;
mod output;

use measure::{measured, repaint_stack, systick};
use output::{fail, print_result, report, Out};
#[cfg(feature = "geo_tour")]
use reconfig_core::geo_tour;
#[cfg(feature = "leo_tour")]
use reconfig_core::leo_tour;
use reconfig_core::{impulsive, pseudospectral};

/// Which planner a baked-in fixture is for.
#[derive(Clone, Copy)]
#[allow(dead_code)] // a variant is unused while no fixture is for that planner
pub enum Planner {
    /// Planner A.
    Pseudospectral,
    /// Planner B, default settings.
    Impulsive,
    /// Planner B, `Settings::fixed_point_only()`.
    ImpulsiveFixedPoint,
    /// Planner B in other input forms, default settings; its bytes carry an
    /// `impulsive::FormProblem`, converted on board.
    ImpulsiveForm,
    /// Planner B in other input forms, `Settings::fixed_point_only()`.
    ImpulsiveFormFixedPoint,
    /// The GEO servicing tour (the GEO image); its bytes carry `(Problem, Settings)`.
    GeoTour,
    /// One arc of the LEO tour (the LEO image); its bytes carry `(ArcProblem, Settings)`.
    LeoArc,
    /// The LEO tour's on-board part (the LEO image): the order and its arcs; its bytes carry
    /// a `leo_tour::tour_order::OnboardProblem`.
    LeoOnboard,
}

/// A fixture baked in by `build.rs`: the postcard bytes of the planner's `Problem`.
pub struct Fixture {
    /// The fixture's name.
    pub name: &'static str,
    /// Which planner.
    pub planner: Planner,
    /// postcard encoding of the core `Problem`.
    pub problem: &'static [u8],
}

include!(concat!(env!("OUT_DIR"), "/fixtures.rs"));

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
    // and output buffers live in static memory (.bss, or .data when a `new()` is not all zero
    // bits), never on the stack.
    // A one-planner image (cargo feature) carries only its planner's statics.
    #[cfg(feature = "pseudospectral")]
    static mut PS_WORKSPACE: pseudospectral::Workspace = pseudospectral::Workspace::new();
    #[cfg(feature = "pseudospectral")]
    static mut PS_SOLUTION: pseudospectral::Solution = pseudospectral::Solution::new();
    #[cfg(feature = "impulsive")]
    static mut IM_WORKSPACE: impulsive::Workspace = impulsive::Workspace::new();
    #[cfg(feature = "impulsive")]
    static mut IM_SOLUTION: impulsive::Solution = impulsive::Solution::new();

    // The GEO image (`cargo firmware-geo`) carries the GEO tour's alone.
    #[cfg(feature = "geo_tour")]
    static mut GEO_WORKSPACE: geo_tour::Workspace = geo_tour::Workspace::new();
    #[cfg(feature = "geo_tour")]
    static mut GEO_SOLUTION: geo_tour::Solution = geo_tour::Solution::new();

    // The LEO image's: the sequencing's workspace (its memos and the arc search's workspace,
    // which the single arcs use too), an arc's answer and the on-board part's.
    #[cfg(feature = "leo_tour")]
    static mut LEO_WORKSPACE: leo_tour::tour_order::SequenceWorkspace =
        leo_tour::tour_order::SequenceWorkspace::new();
    #[cfg(feature = "leo_tour")]
    static mut LEO_ARC_SOLUTION: leo_tour::ArcSolution = leo_tour::ArcSolution::new();
    #[cfg(feature = "leo_tour")]
    static mut LEO_ONBOARD: leo_tour::tour_order::OnboardPlan =
        leo_tour::tour_order::OnboardPlan::new();

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
         leo_arc_solution_bytes={} leo_onboard_plan_bytes={}",
        core::mem::size_of::<leo_tour::Workspace>(),
        core::mem::size_of::<leo_tour::tour_order::SequenceWorkspace>(),
        core::mem::size_of::<leo_tour::ArcSolution>(),
        core::mem::size_of::<leo_tour::tour_order::OnboardPlan>(),
    );

    systick::start();
    #[cfg(feature = "pseudospectral")]
    let ps_settings = pseudospectral::Settings::default();
    #[cfg(feature = "impulsive")]
    let im_settings = impulsive::Settings::default();
    #[cfg(feature = "impulsive")]
    let im_fixed_point_settings = impulsive::Settings::fixed_point_only();
    for (index, fixture) in FIXTURES.iter().enumerate() {
        // The inputs pass through `black_box` after the start marker and the result before the stop
        // marker, so that no part of the solve is folded away or moved out of the measured span.
        let marker = u32::try_from(index).unwrap_or(u32::MAX);
        match fixture.planner {
            #[cfg(feature = "pseudospectral")]
            Planner::Pseudospectral => run_pseudospectral(
                &mut out,
                (index, marker, fixture),
                &ps_settings,
                &mut *PS_WORKSPACE,
                &mut *PS_SOLUTION,
            ),
            #[cfg(feature = "impulsive")]
            Planner::Impulsive | Planner::ImpulsiveFixedPoint => {
                let settings = if matches!(fixture.planner, Planner::ImpulsiveFixedPoint) {
                    &im_fixed_point_settings
                } else {
                    &im_settings
                };
                run_impulsive(
                    &mut out,
                    (index, marker, fixture),
                    settings,
                    &mut *IM_WORKSPACE,
                    &mut *IM_SOLUTION,
                );
            }
            #[cfg(feature = "impulsive")]
            Planner::ImpulsiveForm | Planner::ImpulsiveFormFixedPoint => {
                let settings = if matches!(fixture.planner, Planner::ImpulsiveFormFixedPoint) {
                    &im_fixed_point_settings
                } else {
                    &im_settings
                };
                run_impulsive_form(
                    &mut out,
                    (index, marker, fixture),
                    settings,
                    &mut *IM_WORKSPACE,
                    &mut *IM_SOLUTION,
                );
            }
            #[cfg(feature = "leo_tour")]
            Planner::LeoArc => run_leo_arc(
                &mut out,
                (index, marker, fixture),
                &mut LEO_WORKSPACE.arc,
                &mut *LEO_ARC_SOLUTION,
            ),
            #[cfg(feature = "leo_tour")]
            Planner::LeoOnboard => run_leo_onboard(
                &mut out,
                (index, marker, fixture),
                &mut *LEO_WORKSPACE,
                &mut *LEO_ONBOARD,
            ),
            #[cfg(feature = "geo_tour")]
            Planner::GeoTour => run_geo_tour(
                &mut out,
                (index, marker, fixture),
                &mut *GEO_WORKSPACE,
                &mut *GEO_SOLUTION,
            ),
            // build.rs bakes only the fixtures of the planners this image carries.
            #[allow(unreachable_patterns)]
            _ => panic!(
                "fixture {} is for a planner this image does not carry",
                fixture.name
            ),
        }
    }
    let _ = writeln!(out, "done fixtures={}", FIXTURES.len());
    debug::exit(debug::EXIT_SUCCESS);
    #[allow(clippy::empty_loop)]
    loop {}
}

// Each planner's fixture runs in a function of its own (never inlined), so that `main`'s frame
// does not hold every planner's decoded problem at once: the stack high-water of a fixture in
// the default two-planner image is then that planner's, as in its one-planner image
// (docs/firmware.md, "RAM per image"). The workspace is reused on purpose (no result may depend
// on what an earlier solve left in it); the output buffer is fresh, as the host's is.

/// A baked fixture's bytes decoded as the planner's input (`build.rs` encoded them from this
/// type: a failure is a build fault, fatal).
fn decode<P: serde::de::DeserializeOwned>(fixture: &Fixture) -> P {
    match postcard::from_bytes(fixture.problem) {
        Ok(p) => p,
        Err(_) => panic!("fixture {} does not decode", fixture.name),
    }
}

#[cfg(feature = "pseudospectral")]
#[inline(never)]
fn run_pseudospectral(
    out: &mut Out,
    (index, marker, fixture): (usize, u32, &Fixture),
    settings: &pseudospectral::Settings,
    workspace: &mut pseudospectral::Workspace,
    solution: &mut pseudospectral::Solution,
) {
    *solution = pseudospectral::Solution::new();
    repaint_stack();
    let problem: pseudospectral::Problem = decode(fixture);
    let run = measured(marker, || {
        pseudospectral::solve(
            black_box(&problem),
            black_box(settings),
            black_box(&mut *workspace),
            black_box(&mut *solution),
        )
    });
    let units = Some(solution.info.work_units);
    let figures = (run.ticks, units);
    report(
        out,
        index,
        fixture,
        "pseudospectral",
        run.result.is_ok(),
        run.stack_bytes,
        figures,
    );
    print_result(out, index, &run.result.map(|()| &*solution));
}

#[cfg(feature = "impulsive")]
#[inline(never)]
fn run_impulsive(
    out: &mut Out,
    (index, marker, fixture): (usize, u32, &Fixture),
    settings: &impulsive::Settings,
    workspace: &mut impulsive::Workspace,
    solution: &mut impulsive::Solution,
) {
    *solution = impulsive::Solution::new();
    repaint_stack();
    let problem: impulsive::Problem = decode(fixture);
    let run = measured(marker, || {
        impulsive::solve(
            black_box(&problem),
            black_box(settings),
            black_box(&mut *workspace),
            black_box(&mut *solution),
        )
    });
    let figures = (run.ticks, Some(solution.info.work_units));
    report(
        out,
        index,
        fixture,
        "impulsive",
        run.result.is_ok(),
        run.stack_bytes,
        figures,
    );
    print_result(out, index, &run.result.map(|()| &*solution));
}

/// [`run_impulsive`] for a fixture in other input forms: the conversion runs inside the
/// measured span, and the result carries the end state in the fixture's form.
#[cfg(feature = "impulsive")]
#[inline(never)]
fn run_impulsive_form(
    out: &mut Out,
    (index, marker, fixture): (usize, u32, &Fixture),
    settings: &impulsive::Settings,
    workspace: &mut impulsive::Workspace,
    solution: &mut impulsive::Solution,
) {
    *solution = impulsive::Solution::new();
    repaint_stack();
    let problem: impulsive::FormProblem = decode(fixture);
    let run = measured(marker, || {
        impulsive::solve_form(
            black_box(&problem),
            black_box(settings),
            black_box(&mut *workspace),
            black_box(&mut *solution),
        )
    });
    let figures = (run.ticks, Some(solution.info.work_units));
    report(
        out,
        index,
        fixture,
        "impulsive",
        run.result.is_ok(),
        run.stack_bytes,
        figures,
    );
    print_result(out, index, &run.result.map(|end| (&*solution, end)));
}

/// The GEO tour's fixture (the GEO image): its bytes carry `(Problem, Settings)`. The GEO tour
/// has no work meter: its line carries no `work_units`.
#[cfg(feature = "geo_tour")]
#[inline(never)]
fn run_geo_tour(
    out: &mut Out,
    (index, marker, fixture): (usize, u32, &Fixture),
    workspace: &mut geo_tour::Workspace,
    solution: &mut geo_tour::Solution,
) {
    *solution = geo_tour::Solution::new();
    repaint_stack();
    let (problem, settings): (geo_tour::Problem, geo_tour::Settings) = decode(fixture);
    let run = measured(marker, || {
        geo_tour::solve(
            black_box(&problem),
            black_box(&settings),
            black_box(&mut *workspace),
            black_box(&mut *solution),
        )
    });
    let figures = (run.ticks, None);
    report(
        out,
        index,
        fixture,
        "geo-tour",
        run.result.is_ok(),
        run.stack_bytes,
        figures,
    );
    print_result(out, index, &run.result.map(|()| &*solution));
}

/// One LEO arc (the LEO image): its bytes carry `(ArcProblem, Settings)`.
#[cfg(feature = "leo_tour")]
#[inline(never)]
fn run_leo_arc(
    out: &mut Out,
    (index, marker, fixture): (usize, u32, &Fixture),
    workspace: &mut leo_tour::Workspace,
    solution: &mut leo_tour::ArcSolution,
) {
    solution.reset();
    repaint_stack();
    let (problem, settings): (leo_tour::ArcProblem, leo_tour::Settings) = decode(fixture);
    let run = measured(marker, || {
        leo_tour::solve_arc(
            black_box(&problem),
            black_box(&settings),
            black_box(&mut *workspace),
            black_box(&mut *solution),
        )
    });
    let units = run.result.is_ok().then_some(solution.info.work_units);
    report(
        out,
        index,
        fixture,
        "leo-tour",
        run.result.is_ok(),
        run.stack_bytes,
        (run.ticks, units),
    );
    print_result(out, index, &run.result.map(|()| &*solution));
}

/// The LEO tour's on-board part (the LEO image): the sequencing and every arc of the order;
/// its bytes carry a `tour_order::OnboardProblem`. Its work units are the arcs' (the
/// sequencing's estimates are not metered in total).
#[cfg(feature = "leo_tour")]
#[inline(never)]
fn run_leo_onboard(
    out: &mut Out,
    (index, marker, fixture): (usize, u32, &Fixture),
    workspace: &mut leo_tour::tour_order::SequenceWorkspace,
    plan: &mut leo_tour::tour_order::OnboardPlan,
) {
    *plan = leo_tour::tour_order::OnboardPlan::new();
    repaint_stack();
    let problem: leo_tour::tour_order::OnboardProblem = decode(fixture);
    let run = measured(marker, || {
        leo_tour::tour_order::plan_onboard(
            black_box(&problem),
            black_box(&mut *workspace),
            black_box(&mut *plan),
        )
    });
    let units = run.result.is_ok().then(|| {
        plan.arcs
            .iter()
            .flatten()
            .flatten()
            .map(|a| a.info.work_units)
            .sum::<u64>()
    });
    report(
        out,
        index,
        fixture,
        "leo-tour",
        run.result.is_ok(),
        run.stack_bytes,
        (run.ticks, units),
    );
    print_result(out, index, &run.result.map(|()| &*plan));
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
