//! Zero heap allocations during a planner-B solve (fixed points, min fuel, correction, search),
//! counted by a global allocator. Its own test binary, so no other test allocates meanwhile.

use reconfig_core::capacity::MAX_IMPULSES;
use reconfig_core::impulsive::{
    solve, ImpulsePlan, ImpulsePoint, MeanElements, Problem, RelativeElements, Settings, Solution,
    SolveStatus, Workspace,
};
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

fn rel(v: [f64; 6]) -> RelativeElements {
    RelativeElements {
        dsma_km: v[0],
        decc: v[1],
        dinc_rad: v[2].to_radians(),
        draan_rad: v[3].to_radians(),
        dargp_rad: v[4].to_radians(),
        dmean_anomaly_rad: v[5].to_radians(),
    }
}

#[test]
fn solve_does_not_allocate() {
    let mut fixed: heapless::Vec<ImpulsePoint, MAX_IMPULSES> = heapless::Vec::new();
    for (u, n) in [(274.155f64, 2), (238.864, 10), (285.649, 2)] {
        fixed
            .push(ImpulsePoint {
                arg_latitude_rad: u.to_radians(),
                revolutions: n,
            })
            .unwrap();
    }
    let mut problem = Problem {
        chief: MeanElements {
            sma_km: 7178.137,
            ecc: 0.0678,
            inc_rad: 63.4349f64.to_radians(),
            raan_rad: 112f64.to_radians(),
            argp_rad: 0.0,
            mean_anomaly_rad: 0.0,
        },
        initial: rel([
            4.0940e-4, -1.3888e-4, -1.0831e-3, 1.5409e-2, -1.6134e-2, 9.2428e-3,
        ]),
        target: rel([
            -1.6389e-4, 5.5597e-4, 4.3361e-3, 7.1228e-2, -6.3572e-2, 3.1718e-2,
        ]),
        plan: ImpulsePlan::Fixed(fixed),
    };
    let settings = Settings::default();
    let small_search = Settings {
        search_samples: 200,
        search_starts: 4,
        search_max_evaluations: 1000,
        ..settings
    };
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());

    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let fixed_result = solve(&problem, &settings, &mut ws, &mut out);
    let after_fixed = ALLOCATIONS.load(Ordering::SeqCst);
    assert_eq!(after_fixed - before, 0, "fixed-point solve allocated");
    assert!(fixed_result.is_ok());
    assert_eq!(out.info.status, SolveStatus::Solved);

    problem.plan = ImpulsePlan::Search {
        impulses: 3,
        max_revolutions: 14,
    };
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let search_result = solve(&problem, &small_search, &mut ws, &mut out);
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    assert_eq!(after - before, 0, "search allocated");
    assert!(search_result.is_ok());
    assert!(out.info.evaluations > 100);

    // A rejected request does not allocate either.
    problem.chief.ecc = f64::NAN;
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let rejected = solve(&problem, &settings, &mut ws, &mut out);
    assert_eq!(ALLOCATIONS.load(Ordering::SeqCst) - before, 0);
    assert!(rejected.is_err());
}
