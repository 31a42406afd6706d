//! A planner-A solve performs zero heap allocations (counted by a global allocator).

use reconfig_core::pseudospectral::{self, Settings, Solution, Workspace};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    // Only the thread under test counts: the harness runs other tests in parallel.
    static COUNTING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

fn count() {
    if COUNTING.with(|c| c.get()) {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
    }
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn a_solve_does_not_allocate() {
    // The counter itself works: a Vec on this thread is counted.
    COUNTING.with(|c| c.set(true));
    let probe = ALLOCATIONS.load(Ordering::SeqCst);
    drop(std::hint::black_box(vec![1u8; 16]));
    assert!(
        ALLOCATIONS.load(Ordering::SeqCst) > probe,
        "counting allocator inactive"
    );
    COUNTING.with(|c| c.set(false));
    let problems: Vec<_> = ["huang2012-three-sats-n10", "crossing-8-sats-n16"]
        .iter()
        .map(|stem| reconfig_tests::pseudospectral_fixture(stem))
        .collect();
    let mut workspace = Box::new(Workspace::new());
    let mut solution = Box::new(Solution::new());
    let settings = Settings::default();
    for problem in &problems {
        let before = ALLOCATIONS.load(Ordering::SeqCst);
        COUNTING.with(|c| c.set(true));
        let result = pseudospectral::solve(problem, &settings, &mut workspace, &mut solution);
        COUNTING.with(|c| c.set(false));
        let after = ALLOCATIONS.load(Ordering::SeqCst);
        result.expect("solve");
        assert_eq!(after - before, 0, "allocations during a solve");
        assert!(solution.info.status.is_usable());
    }
}

#[test]
fn workspace_size_is_reported() {
    // Printed for the README (`cargo test -p reconfig-tests --test pseudospectral_alloc -- --nocapture`).
    let bytes = std::mem::size_of::<Workspace>();
    println!("size_of::<pseudospectral::Workspace>() = {bytes} bytes");
    println!(
        "size_of::<pseudospectral::Solution>() = {} bytes",
        std::mem::size_of::<Solution>()
    );
    // The on-board RAM budget is 256 KiB for static memory plus stack, both planners: both
    // workspaces and solutions must leave 24 KiB for the stack (the M7 high-water is ~20 KiB,
    // measured by the QEMU test, which checks the whole budget on the target itself).
    let statics = bytes
        + std::mem::size_of::<Solution>()
        + std::mem::size_of::<reconfig_core::impulsive::Workspace>()
        + std::mem::size_of::<reconfig_core::impulsive::Solution>();
    assert!(statics + 24 * 1024 <= 256 * 1024, "{statics}");
}
