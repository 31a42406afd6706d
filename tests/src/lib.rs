//! Helpers shared by the regression tests in `tests/tests/`.

use reconfig_core::pseudospectral::{self, Settings, Solution, Workspace};
use reconfig_host::fixture::{
    self, impulsive::ImpulsiveFixture, pseudospectral::PseudospectralFixture,
};
use std::path::PathBuf;

/// The repository's `fixtures/` folder.
pub fn fixtures_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("fixtures")
}

/// Every fixture file, sorted by name.
pub fn fixture_paths() -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(fixtures_dir())
        .expect("fixtures dir")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    paths.sort();
    paths
}

/// Load a planner-A fixture by file stem.
pub fn pseudospectral_fixture(stem: &str) -> pseudospectral::Problem {
    let path = fixtures_dir().join(format!("{stem}.toml"));
    fixture::load_as::<PseudospectralFixture>(&path)
        .expect("a planner-A fixture")
        .problem
}

/// Solve a planner-A problem in a fresh boxed workspace.
pub fn solve_pseudospectral(
    problem: &pseudospectral::Problem,
    settings: &Settings,
) -> Result<Box<Solution>, pseudospectral::PlanError> {
    let mut workspace = Box::new(Workspace::new());
    let mut solution = Box::new(Solution::new());
    pseudospectral::solve(problem, settings, &mut workspace, &mut solution)?;
    Ok(solution)
}

/// How far below the oracle's cost (relative) our usable answer may be without being wrong: the
/// oracle keeps each pair up to `oracle_margin_rel d` above d, which costs it up to the sum of
/// our keep-out multipliers (dJ/dd per check) times that, plus `below_tolerance_rel`.
pub fn below_oracle_allowance_rel(
    ours: &Solution,
    keep_out_lu: f64,
    oracle_cost: f64,
    below_tolerance_rel: f64,
    oracle_margin_rel: f64,
) -> f64 {
    let keep_out_multipliers: f64 = ours
        .certificate
        .multipliers
        .iter()
        .filter(|m| {
            matches!(
                m.constraint,
                pseudospectral::ActiveConstraint::KeepOut { .. }
            )
        })
        .map(|m| m.value.max(0.0))
        .sum();
    below_tolerance_rel
        + keep_out_multipliers * oracle_margin_rel * keep_out_lu
            / oracle_cost.abs().max(f64::MIN_POSITIVE)
}

/// An order of clients (indices from 0) as the docs write it, numbered from 1: `3 → 4 → 5`.
pub fn order_text(order: &[usize]) -> String {
    order
        .iter()
        .map(|c| (c + 1).to_string())
        .collect::<Vec<_>>()
        .join(" → ")
}

/// The golden value `key` of `name` in `fixtures/golden/FILE`.
pub fn golden(file: &str, name: &str, key: &str) -> f64 {
    let text = std::fs::read_to_string(fixtures_dir().join("golden").join(file)).expect("golden");
    let table: toml::Table = toml::from_str(&text).expect("golden toml");
    table[name][key].as_float().expect("float")
}

/// Load a planner-B fixture by file stem.
pub fn impulsive_fixture(stem: &str) -> reconfig_core::impulsive::Problem {
    let path = fixtures_dir().join(format!("{stem}.toml"));
    fixture::load_as::<ImpulsiveFixture>(&path)
        .expect("a planner-B fixture")
        .problem
}

/// A global allocator that counts the allocations made on threads that opted in, for the
/// zero-allocation tests. Each test binary installs it with
/// `#[global_allocator] static GLOBAL: CountingAllocator = CountingAllocator;`; counting only
/// opted-in threads keeps the harness's other test threads out of the count.
pub mod alloc_count {
    use std::alloc::{GlobalAlloc, Layout, System};
    use std::cell::Cell;
    use std::sync::atomic::{AtomicUsize, Ordering};

    static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

    thread_local! {
        static COUNTING: Cell<bool> = const { Cell::new(false) };
    }

    /// The system allocator with a counter for opted-in threads.
    pub struct CountingAllocator;

    fn note() {
        // `try_with`: no count (and no panic) while a thread's locals are being torn down.
        if COUNTING.try_with(Cell::get).unwrap_or(false) {
            ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        }
    }

    // SAFETY: forwards every call to the system allocator unchanged; only counts.
    unsafe impl GlobalAlloc for CountingAllocator {
        unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
            note();
            unsafe { System.alloc(layout) }
        }
        unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
            unsafe { System.dealloc(ptr, layout) }
        }
        unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
            note();
            unsafe { System.alloc_zeroed(layout) }
        }
        unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
            note();
            unsafe { System.realloc(ptr, layout, new_size) }
        }
    }

    /// Count (or stop counting) this thread's allocations.
    pub fn set_counting(on: bool) {
        COUNTING.with(|c| c.set(on));
    }

    /// Allocations counted so far, over all opted-in threads.
    pub fn allocations() -> usize {
        ALLOCATIONS.load(Ordering::SeqCst)
    }

    /// Run `f` counting this thread's allocations; returns its result and how many it made.
    pub fn count<R>(f: impl FnOnce() -> R) -> (R, usize) {
        let before = allocations();
        set_counting(true);
        let result = f();
        set_counting(false);
        (result, allocations().saturating_sub(before))
    }
}
pub mod doc_blocks;
pub mod golden;
pub mod leo_tables;
pub mod m7_record;
pub mod numbers;
pub mod qemu;
pub mod readme_figures;
