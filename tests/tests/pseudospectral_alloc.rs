//! A planner-A solve performs zero heap allocations (counted by a global allocator).

use reconfig_core::pseudospectral::{self, Settings, Solution, Workspace};
use reconfig_tests::alloc_count::{count, CountingAllocator};

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

#[test]
fn a_solve_does_not_allocate() {
    // The counter itself works: a Vec on this thread is counted.
    let ((), probe) = count(|| drop(std::hint::black_box(vec![1u8; 16])));
    assert!(probe > 0, "counting allocator inactive");
    let problems: Vec<_> = ["huang2012-three-sats-n10", "crossing-8-sats-n16"]
        .iter()
        .map(|stem| reconfig_tests::pseudospectral_fixture(stem))
        .collect();
    let mut workspace = Box::new(Workspace::new());
    let mut solution = Box::new(Solution::new());
    let settings = Settings::default();
    for problem in &problems {
        let (result, allocations) =
            count(|| pseudospectral::solve(problem, &settings, &mut workspace, &mut solution));
        result.expect("solve");
        assert_eq!(allocations, 0, "allocations during a solve");
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
