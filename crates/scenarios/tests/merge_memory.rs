//! A merge's memory does not grow with the number of runs (issue 22): every scenario's
//! reduce step keeps sums, not the runs' records. For each scenario the records of `4n`
//! runs are computed once; the reduce step's running state after the first `n` of them
//! and after all `4n` is measured in numbers held ([`Footprint`]): the part that does
//! not depend on the runs must not grow (it may shrink: bias-32's series are as long as
//! the shortest run's), and none keeps numbers per run (gimpo's final ratios have one-pass
//! mean and standard deviation accumulators). Reduced run counts and short flights keep
//! each case within seconds.

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use argus_scenarios::{Footprint, NoProgress, Params, find, in_process, run};

/// The footprints after `n` and after `4n` runs of `name` with `settings`.
fn footprints(name: &str, settings: &[&str], n: u64) -> (Footprint, Footprint) {
    let sc = find(name).unwrap();
    let settings: Vec<String> = settings.iter().map(|s| (*s).to_owned()).collect();
    let params = Params::from_settings(&sc.params(), &settings).unwrap();
    let out = run(sc.as_ref(), 0..4 * n, 5, params.clone(), &NoProgress).unwrap();
    let records = out.records.unwrap();
    let sp = sc.splittable().unwrap();
    let at = |k: u64| {
        let recs = &records[..k as usize];
        sp.footprint(&params, k, &mut in_process(recs, &(0..k)))
            .unwrap()
    };
    (at(n), at(4 * n))
}

fn does_not_grow(name: &str, settings: &[&str], n: u64) {
    let (small, large) = footprints(name, settings, n);
    eprintln!("{name}: {n} runs {small:?}, {} runs {large:?}", 4 * n);
    assert!(small.fixed > 0, "{name}: the state holds its sums");
    // Tolerance: none — the sums are sized by the time grid and the configurations.
    assert!(
        large.fixed <= small.fixed,
        "{name}: the state grew from {} to {} numbers between {n} and {} runs",
        small.fixed,
        large.fixed,
        4 * n
    );
    assert_eq!(
        large.per_run,
        0,
        "{name}: numbers kept per run for {} runs",
        4 * n
    );
}

#[test]
fn cv_polar_merge_memory_is_flat() {
    does_not_grow("cv-polar", &["duration=40"], 2);
}

#[test]
fn surveillance_merge_memory_is_flat() {
    does_not_grow("surveillance", &["duration=40", "targets=5"], 1);
}

#[test]
fn gimpo_merge_memory_is_flat() {
    does_not_grow("gimpo", &[], 1);
}

#[test]
fn launch_merge_memory_is_flat() {
    does_not_grow("launch", &["period=2"], 2);
}

#[test]
fn clutter_merge_memory_is_flat() {
    does_not_grow("clutter", &["steps=20"], 2);
}

#[test]
fn rbs_landing_merge_memory_is_flat() {
    does_not_grow("rbs-landing", &[], 1);
}

#[test]
fn maneuver_1d_merge_memory_is_flat() {
    // Detection delays are counted per plot, not kept per run.
    does_not_grow("maneuver-1d", &[], 2);
}

#[test]
fn drag_bearing_merge_memory_is_flat() {
    does_not_grow("drag-bearing", &[], 1);
}

#[test]
fn bias_32_merge_memory_is_flat() {
    does_not_grow("bias-32", &["duration=30"], 1);
}

#[test]
fn bias_32_sweep_merge_memory_is_flat() {
    does_not_grow("bias-32", &["duration=20", "sensors=2,3", "targets=4"], 1);
}

#[test]
fn real_traffic_merge_memory_is_flat() {
    does_not_grow("real-traffic", &["duration=300"], 1);
}
