//! A planner-A solve performs zero heap allocations (counted by a global allocator).

use reconfig_core::pseudospectral::{self, Settings, Solution, Workspace};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn a_solve_does_not_allocate() {
    let problems: Vec<_> = ["huang2012-three-sats-n10", "crossing-8-sats-n16"]
        .iter()
        .map(|stem| reconfig_tests::pseudospectral_fixture(stem))
        .collect();
    let mut workspace = Box::new(Workspace::new());
    let mut solution = Box::new(Solution::new());
    let settings = Settings::default();
    for problem in &problems {
        let before = ALLOCATIONS.load(Ordering::SeqCst);
        pseudospectral::solve(problem, &settings, &mut workspace, &mut solution).expect("solve");
        let after = ALLOCATIONS.load(Ordering::SeqCst);
        assert_eq!(after - before, 0, "allocations during a solve");
        assert!(solution.info.status.is_usable());
    }
}
