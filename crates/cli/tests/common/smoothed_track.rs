//! Checks of smoothed tracks (tests/smooth_imm_tracks.rs, smooth_aircraft_tracks.rs,
//! smooth_multi_imm_tracks.rs): the tracker's smoothed track row by row against the
//! single-target smoother of the same plots, and a lag as long as the track against the
//! fixed-interval smoother.

// Each test binary uses a part of these helpers.
#![allow(dead_code)]

use std::path::Path;

use super::{Row, num, rows, track};

/// The rows of the scene's one confirmed track (track 0), deleted row excluded; asserts
/// that no other track was confirmed.
pub(crate) fn the_track(csv: &str) -> Vec<Row> {
    let all = rows(csv);
    assert!(
        all.iter()
            .all(|r| r["track"] == "0" || r["status"] != "confirmed")
    );
    all.into_iter()
        .filter(|r| r["track"] == "0" && r["status"] != "deleted")
        .collect()
}

/// Calls `check(tracker row, tracker value, single-target value)` for every row of the
/// tracker's track `multi` and the single-target rows `single` (asserted equal in number
/// and row by row in time), in this order: the columns `same` (one name in both), the
/// smoothed state `xs, vxs, ys, vys`, the tracker's `sigma_xs, sigma_ys` against the
/// square roots of the single-target `var_xs, var_ys`, and `mu_1s … mu_<modes>s`.
pub(crate) fn compare_smoothed(
    multi: &[Row],
    single: &[Row],
    same: &[&str],
    modes: usize,
    mut check: impl FnMut(&Row, f64, f64),
) {
    assert_eq!(multi.len(), single.len());
    for (m, s) in multi.iter().zip(single) {
        assert_eq!(m["t"], s["t"]);
        // The single-target rows have variances; the tracker's σ.
        let s_sigma = |k: &str| num(s, k).sqrt();
        let mut pairs: Vec<(f64, f64)> = same.iter().map(|k| (num(m, k), num(s, k))).collect();
        pairs.extend(["xs", "vxs", "ys", "vys"].map(|k| (num(m, k), num(s, k))));
        pairs.push((num(m, "sigma_xs"), s_sigma("var_xs")));
        pairs.push((num(m, "sigma_ys"), s_sigma("var_ys")));
        pairs.extend((1..=modes).map(|i| {
            let k = format!("mu_{i}s");
            (num(m, &k), num(s, &k))
        }));
        for (a, b) in pairs {
            check(m, a, b);
        }
    }
}

/// `|a − b| / max(1, |b|)`.
pub(crate) fn relative_difference(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1.0)
}

/// The worst [`relative_difference`] over the columns [`compare_smoothed`] pairs,
/// asserting every value finite.
pub(crate) fn worst_difference(multi: &[Row], single: &[Row], same: &[&str], modes: usize) -> f64 {
    let mut worst = 0.0_f64;
    compare_smoothed(multi, single, same, modes, |_, a, b| {
        assert!(a.is_finite() && b.is_finite());
        worst = worst.max(relative_difference(a, b));
    });
    worst
}

/// Runs `argus track` with `config` over `plots` in `dir` with `--smooth` and with
/// `--smooth-lag <lag>` (a lag as long as the track), asserts the second succeeds and
/// writes the same tracks as the first, and returns them.
pub(crate) fn long_lag_is_interval(dir: &Path, config: &str, plots: &Path, lag: &str) -> String {
    let (_, _, interval) = track(dir, config, plots, &["--smooth"]);
    let (code, err, lag) = track(dir, config, plots, &["--smooth-lag", lag]);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(interval, lag);
    interval
}
