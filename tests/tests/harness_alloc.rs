//! After start-up the request path does not allocate: the worker loop (decode, solve, encode,
//! hand back) runs under a counting global allocator over requests of both planners and every
//! fault class, and the count must stay at zero.
//!
//! Start-up includes `warm_up` on each blocking receiver, as the service does: the first
//! blocking receive on a std channel builds that thread's channel context and waker entry.

use reconfig_host::harness::faults;
use reconfig_host::harness::feeder::frame_of;
use reconfig_host::harness::job::Job;
use reconfig_host::harness::service::{warm_up, worker_loop};
use reconfig_host::harness::worker::Worker;
use reconfig_host::scenario;
use reconfig_tests::alloc_count::{allocations, set_counting, CountingAllocator};
use std::sync::mpsc::sync_channel;

// Counts only on threads that opted in: the worker and the feeding side of this test.
#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

#[test]
fn the_worker_loop_allocates_nothing_after_start_up() {
    // Start-up: frames, job buffer, channels, worker (all allocation happens here).
    let mut items = scenario::generate(60, 11);
    items.extend(faults::items(500));
    let frames: Vec<Vec<u8>> = items
        .iter()
        .enumerate()
        .map(|(i, item)| frame_of(item, i as u64 + 1).unwrap())
        .collect();
    let (job_tx, job_rx) = sync_channel::<Box<Job>>(1);
    let (done_tx, done_rx) = sync_channel::<Box<Job>>(1);
    let (ready_tx, ready_rx) = sync_channel::<()>(1);
    warm_up(&done_rx);
    let worker = std::thread::Builder::new()
        .stack_size(reconfig_host::harness::worker::WORKER_STACK_BYTES)
        .spawn(move || {
            let mut worker = Worker::new();
            let mut wakes = 0u64;
            warm_up(&job_rx);
            ready_tx.send(()).unwrap();
            set_counting(true);
            worker_loop(&mut worker, &job_rx, &done_tx, || wakes += 1);
            set_counting(false);
            wakes
        })
        .unwrap();
    ready_rx.recv().unwrap();
    let mut job = Some(Job::boxed(0));
    let mut answered = 0usize;

    set_counting(true);
    for round in 0..3 {
        for frame in &frames {
            let mut j = job.take().unwrap();
            let n = frame.len().min(j.request.len());
            j.request[..n].copy_from_slice(&frame[..n]);
            j.request_len = n;
            job_tx.send(j).unwrap();
            let back = done_rx.recv().unwrap();
            assert!(back.response_len > 0, "round {round}");
            answered += 1;
            job = Some(back);
        }
    }
    set_counting(false);

    drop(job_tx);
    let wakes = worker.join().unwrap();
    assert_eq!(wakes as usize, answered);
    let count = allocations();
    println!("allocations on the request path over {answered} requests: {count}");
    assert_eq!(count, 0, "the request path allocated {count} times");
    reconfig_host::figure_record::hold(
        "heap-allocations",
        &reconfig_host::figure_record::Figure {
            what: "heap allocations on the request path after start-up (every planner, every fault class)".into(),
            target: "0".into(),
            measured: format!("{count} over {answered} requests"),
            met: count == 0,
            doc: "harness".into(),
            command: "cargo test -p reconfig-tests --test harness_alloc".into(),
        },
    )
    .unwrap();
}
