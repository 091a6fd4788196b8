//! Issue 18's break goal (≤ 0.1 per aircraft-hour) against its spurious-time goal
//! (≤ 0.5 % of confirmed-track time) on the quickstart hour (docs/real-traffic.md, "Breaks
//! against spurious time").
//!
//! The derivation. When an aircraft's ADS-B truth ends inside the radar's coverage (the
//! sample's latitude/longitude box ends 108–143 km from the radar, and landings), its plots
//! stop; the tracker sees what it sees after a missed detection: no plot. A tracker that
//! deletes a track at its k-th missed revolution in a row (`max_misses = k`) breaks every
//! aircraft missed k times in a row, `(1 − P_D)^k` per revolution — at P_D 0.9 and 720
//! revolutions per hour 0.72 breaks per aircraft-hour for k = 3 and 0.072 for k = 4, so the
//! break goal needs k ≥ 4. The same track, when the truth ends `τ ∈ [0, T)` after its last
//! plot at `t_L`, stays confirmed until `t_L + k T`: spurious for more than `(k − 1) T`.
//! With `N` such ends and `J` seconds of truth inside the coverage, the spurious fraction is
//! at least `N (k − 1) T / (N (k − 1) T + J)` however good the tracker is otherwise.

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use std::collections::BTreeMap;

use argus_scenarios::{NoProgress, Params, find};
use common::row;

/// The scenario's radar: revolution period (s) and maximum range (m), its defaults.
const PERIOD: f64 = 5.0;
const MAX_RANGE: f64 = 150_000.0;
/// The scorer's `max_truth_gap` (docs/scoring.md): truth samples further apart are not
/// interpolated across, so a gap ends the truth's presence.
const MAX_TRUTH_GAP: f64 = 10.0;

/// Truth ends inside the coverage before the hour's last sample, and the truth's time
/// inside the coverage (s), from the scenario's own truth of seed 1.
fn ends_and_truth_time() -> (usize, f64) {
    let sc = find("real-traffic").unwrap();
    let params = Params::from_settings(&sc.params(), &[]).unwrap();
    let sim = sc.simulated(&params, 1, 0).unwrap().unwrap();
    let mut paths: BTreeMap<&str, Vec<(f64, f64)>> = BTreeMap::new();
    for r in &sim.truth {
        paths
            .entry(r.target.as_str())
            .or_default()
            .push((r.t, r.x.hypot(r.y)));
    }
    let last = sim.truth.iter().map(|r| r.t).fold(f64::MIN, f64::max);
    let (mut ends, mut covered) = (0, 0.0);
    for samples in paths.values() {
        for w in samples.windows(2) {
            let ((t0, r0), (t1, _)) = (w[0], w[1]);
            if t1 - t0 <= MAX_TRUTH_GAP && r0 < MAX_RANGE {
                covered += t1 - t0;
            }
        }
        // Ends of the truth itself (not an exit through the coverage's edge, which a
        // tracker that knows the coverage could act on), inside the coverage, more than
        // four revolutions before the hour ends (a tail needs room to be scored).
        for (i, &(t, r)) in samples.iter().enumerate() {
            let ends_here = samples
                .get(i + 1)
                .is_none_or(|&(next, _)| next - t > MAX_TRUTH_GAP);
            if ends_here && r < MAX_RANGE && t < last - 4.0 * PERIOD {
                ends += 1;
            }
        }
    }
    (ends, covered)
}

fn bound(ends: usize, covered: f64, max_misses: u32) -> f64 {
    let tail = ends as f64 * f64::from(max_misses - 1) * PERIOD;
    tail / (tail + covered)
}

#[test]
fn breaks_and_spurious_time_goals_cannot_both_hold_on_the_quickstart_hour() {
    let (ends, covered) = ends_and_truth_time();
    // Seed 1's truth (docs/real-traffic.md): 118 flight segments, 23.7 aircraft-hours in
    // the coverage; most segments end inside it.
    assert!(ends > 50, "{ends} truth ends inside the coverage");
    assert!(
        (20.0 * 3600.0..30.0 * 3600.0).contains(&covered),
        "{covered} s of truth in the coverage"
    );
    // k = 4, the least that meets the break goal (0.072 per aircraft-hour): the bound
    // alone exceeds the spurious goal of 0.5 % (99 ends, 85 410 s: 1.71 %).
    let at_four = bound(ends, covered, 4);
    assert!(at_four > 0.005, "bound {at_four}");

    let sc = find("real-traffic").unwrap();
    let run = |k: u32| {
        let params = Params::from_settings(&sc.params(), &[format!("max_misses={k}")]).unwrap();
        argus_scenarios::run(sc.as_ref(), 0..1, 1, params, &NoProgress).unwrap()
    };
    let (three, four) = (run(3), run(4));
    for c in ["gnn_aircraft", "gnn_kf"] {
        // k = 3 fails the break goal (derived 0.72 per aircraft-hour; measured 0.84 for
        // gnn_aircraft, seed 1) …
        let breaks = row(&three, &format!("{c}_breaks_per_aircraft_hour"));
        assert!(
            breaks > 0.1,
            "{c}: {breaks} breaks per aircraft-hour at k = 3"
        );
        // … and each configuration's spurious time is above the bound at k = 3 and 4
        // (measured 1.7 % and 2.3 % against 1.16 % and 1.71 %).
        for (k, out) in [(3, &three), (4, &four)] {
            let spurious = row(out, &format!("{c}_spurious_fraction"));
            let b = bound(ends, covered, k);
            assert!(spurious >= b, "{c}, k = {k}: spurious {spurious} below {b}");
            assert!(spurious > 0.005, "{c}, k = {k}: spurious {spurious}");
        }
    }
}
