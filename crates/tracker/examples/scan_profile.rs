//! One tracker scan for instruction counting (issue 9): `scan_profile <targets> [jpda]`
//! builds the bench's scene (targets on a 3 km grid at 150–250 m/s, 10 % uniform
//! clutter, σ = 50 m, 5 s scans), runs 5 scans so every target has a confirmed track,
//! then one more inside `timed_scan`. Count only that scan with
//! `valgrind --tool=callgrind --collect-atstart=no --toggle-collect='*timed_scan*'`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;

use argus_core_math::{Matrix, Vector};
use argus_tracker::{AssociationConfig, Plot, ScanReport, SensorId, Tracker, TrackerConfig};

const T: f64 = 5.0;
const SIGMA: f64 = 50.0;
const SPACING: f64 = 3000.0;

/// SplitMix64, uniform in [0, 1): enough for a profiling scene.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        #[allow(clippy::cast_precision_loss)]
        let u = (z >> 11) as f64 / (1u64 << 53) as f64;
        u
    }

    fn gauss(&mut self) -> f64 {
        let u1 = 1.0 - self.uniform();
        let u2 = self.uniform();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

fn scan(rng: &mut Rng, targets: &[(Vector<2>, Vector<2>)], t: f64, side: f64) -> Vec<Plot> {
    let cov = Matrix::<2, 2>::identity() * (SIGMA * SIGMA);
    let mut plots: Vec<Plot> = targets
        .iter()
        .map(|(p0, v)| {
            Plot::cartesian(
                t,
                SensorId(0),
                p0 + v * t + Vector::<2>::new(SIGMA * rng.gauss(), SIGMA * rng.gauss()),
                cov,
            )
            .unwrap()
        })
        .collect();
    for _ in 0..targets.len() / 10 {
        plots.push(
            Plot::cartesian(
                t,
                SensorId(0),
                Vector::<2>::new(side * rng.uniform(), side * rng.uniform()),
                cov,
            )
            .unwrap(),
        );
    }
    plots
}

#[inline(never)]
fn timed_scan(tracker: &mut Tracker, t: f64, plots: &[Plot]) -> ScanReport {
    tracker.process_scan(t, SensorId(0), plots).unwrap()
}

#[allow(
    clippy::cast_precision_loss,
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss
)]
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1000);
    let jpda = args.get(2).is_some_and(|s| s == "jpda");
    let mut rng = Rng(9);
    let per_side = (n as f64).sqrt().ceil() as usize;
    let side = per_side as f64 * SPACING;
    let targets: Vec<(Vector<2>, Vector<2>)> = (0..n)
        .map(|k| {
            let p0 = Vector::<2>::new(
                (k % per_side) as f64 * SPACING,
                (k / per_side) as f64 * SPACING,
            );
            let speed = 150.0 + 100.0 * rng.uniform();
            let heading = std::f64::consts::TAU * rng.uniform();
            (
                p0,
                Vector::<2>::new(speed * heading.cos(), speed * heading.sin()),
            )
        })
        .collect();
    let mut cfg = TrackerConfig::new(vec![SensorId(0)]);
    if jpda {
        cfg.association = AssociationConfig::Jpda {
            p_detection: 0.99,
            clutter_density: (n / 10).max(1) as f64 / (side * side),
            max_exact_events: 1000,
        };
    }
    let mut tracker = Tracker::new(cfg).unwrap();
    for k in 0..5 {
        let t = T * f64::from(k);
        tracker
            .process_scan(t, SensorId(0), &scan(&mut rng, &targets, t, side))
            .unwrap();
        tracker.take_deleted();
    }
    let t = 5.0 * T;
    let next = scan(&mut rng, &targets, t, side);
    let report = black_box(timed_scan(&mut tracker, t, &next));
    println!(
        "targets {n}: plots {}, assigned {}, initiated {}, confirmed {}, deleted {}, live {}",
        report.plots,
        report.assigned,
        report.initiated.len(),
        report.confirmed.len(),
        report.deleted.len(),
        tracker.tracks().len()
    );
}
