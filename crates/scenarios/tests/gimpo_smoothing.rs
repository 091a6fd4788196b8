//! Issue 19 on seed 000's trajectory: `argus run gimpo` reports the smoothed IMM's RMS
//! position error against the filtered IMM's (true R): `smooth_rms_ratio` for the Gibbs
//! smoother (the jump-Markov model's posterior mean), `imm_smooth_rms_ratio` for the IMM
//! smoother, and both smoothers' ANEES with the 99 % band of the run count. That a run's
//! Gibbs chain depends on (seed, run) only is `split_merge.rs`'s gimpo case (shards merged
//! equal the whole run, bit for bit) and `crates/cli/tests/campaign.rs`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use argus_core_math::anees_interval;
use argus_scenarios::{NoProgress, Params, find, run};

#[test]
fn gimpo_meets_the_smoothing_goal_with_the_gibbs_smoother() {
    let s = find("gimpo").unwrap();
    // The CLI's runs and seed (`argus run gimpo --seed 3`: 100 runs) — fewer runs move the
    // ratio by more than its margin (30 runs of seed 0 read 0.595 for the posterior
    // mean) — with half the CLI's recorded sweeps to halve the test's time (100: 0.5848,
    // the CLI's 200: 0.5814, 400: 0.5808; docs/smoothing.md). 10–20 s on 2 cores.
    let params = Params::from_settings(&s.params(), &["gibbs_sweeps=100".to_owned()]).unwrap();
    let out = run(s.as_ref(), 0..100, 3, params, &NoProgress).unwrap();
    let row = |key: &str| {
        out.report
            .rows
            .iter()
            .find(|r| r.key == key)
            .unwrap_or_else(|| panic!("gimpo writes {key}"))
            .ours
    };
    let (gibbs, imm) = (row("smooth_rms_ratio"), row("imm_smooth_rms_ratio"));
    // The goal, ≤ 0.6 (measured 0.5848 at these 100 sweeps; the near-exact
    // reference of docs/smoothing.md, 2 chains × 400 sweeps, 0.5800).
    assert!(gibbs <= 0.6, "smooth_rms_ratio = {gibbs}");
    // The posterior mean beats the IMM smoother by its documented gap (0.05 measured; at
    // least 0.02 asserted, the margin the 10-run library test also asserts), and the IMM
    // smoother still beats the filter (< 1; measured 0.630).
    assert!(gibbs < imm - 0.02 && imm < 1.0, "gibbs {gibbs}, imm {imm}");
    // Lower side: a loose sanity bound, not a derived one — a value under 0.33 would mean
    // the truth leaked into the estimate.
    assert!(gibbs > 0.33, "smooth_rms_ratio = {gibbs}");
    // The band rows are the 99 % interval of χ²(4·100)/100 (derived; round-off only).
    let band = anees_interval(4, 100, 0.99).unwrap();
    assert!((row("smooth_anees_lo") - band.lower).abs() < 1e-12);
    assert!((row("smooth_anees_hi") - band.upper).abs() < 1e-12);
    // Neither smoother is consistent on gimpo (docs/smoothing.md: no ±3 °/s mode fits
    // Table 1's turns, so the model's own posterior is over-confident there): both ANEES
    // above the band (measured 7.14 Gibbs at these sweeps, 6.26 at the CLI's 200, 7.07
    // IMM, against [3.31, 4.77]).
    for key in ["smooth_anees", "imm_smooth_anees"] {
        assert!(row(key) > band.upper, "{key} = {}", row(key));
    }
}
