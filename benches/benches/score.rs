//! Scoring (argus-score): one hour of 120 aircraft at a 5 s revisit — truth sampled every
//! 5 s, one confirmed track per aircraft 30–150 m off with a row every 5 s and a break in
//! the middle of the hour (a new track takes over), and 10 short false tracks per
//! revolution — scored on the 5 s grid (721 times) with the default parameters.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;

use argus_score::{ScoreConfig, Scorer, TrackHistory, TrackRow, TruthPath, TruthSample};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

const HOUR: f64 = 3600.0;
const REVISIT: f64 = 5.0;

fn scene(aircraft: usize) -> (Vec<TrackHistory>, Vec<TruthPath>) {
    let mut rng = ChaCha8Rng::seed_from_u64(18);
    let steps = (HOUR / REVISIT) as usize;
    let (mut truth, mut tracks) = (Vec::new(), Vec::new());
    for a in 0..aircraft {
        let (x0, y0) = (
            rng.random_range(-1.5e5..1.5e5),
            rng.random_range(-1.5e5..1.5e5),
        );
        let heading: f64 = rng.random_range(0.0..std::f64::consts::TAU);
        let (vx, vy) = (220.0 * heading.cos(), 220.0 * heading.sin());
        let samples: Vec<TruthSample> = (0..=steps)
            .map(|k| {
                let t = k as f64 * REVISIT;
                TruthSample {
                    t,
                    x: x0 + vx * t,
                    vx,
                    y: y0 + vy * t,
                    vy,
                }
            })
            .collect();
        let (ox, oy) = (
            rng.random_range(-100.0..100.0),
            rng.random_range(-100.0..100.0),
        );
        let row = |s: &TruthSample| TrackRow {
            t: s.t,
            confirmed: true,
            x: s.x + ox,
            vx: s.vx + 2.0,
            y: s.y + oy,
            vy: s.vy - 1.0,
        };
        let half = steps / 2;
        tracks.push(
            TrackHistory::new(format!("{a}a"), samples[2..half].iter().map(row).collect()).unwrap(),
        );
        tracks.push(
            TrackHistory::new(
                format!("{a}b"),
                samples[half + 4..].iter().map(row).collect(),
            )
            .unwrap(),
        );
        truth.push(TruthPath::new(a.to_string(), samples).unwrap());
    }
    for k in 0..steps {
        for f in 0..10 {
            let (x, y) = (
                rng.random_range(-1.5e5..1.5e5),
                rng.random_range(-1.5e5..1.5e5),
            );
            let rows = (0..3)
                .map(|i| TrackRow {
                    t: (k + i) as f64 * REVISIT,
                    confirmed: i > 0,
                    x,
                    vx: 0.0,
                    y,
                    vy: 0.0,
                })
                .collect();
            tracks.push(TrackHistory::new(format!("f{k}-{f}"), rows).unwrap());
        }
    }
    (tracks, truth)
}

fn score_hour(c: &mut Criterion) {
    let scorer = Scorer::new(ScoreConfig::default()).unwrap();
    let mut group = c.benchmark_group("score_hour");
    group.sample_size(10);
    for aircraft in [30usize, 120] {
        let (tracks, truth) = scene(aircraft);
        let s = scorer.score(&tracks, &truth).unwrap().summary;
        assert_eq!(s.grid_times, 721);
        assert!(s.completeness.unwrap() > 0.98, "{s:?}");
        group.bench_with_input(
            BenchmarkId::from_parameter(aircraft),
            &(tracks, truth),
            |b, (tk, tr)| {
                b.iter(|| black_box(scorer.score(black_box(tk), black_box(tr)).unwrap()));
            },
        );
    }
    group.finish();
}

criterion_group!(benches, score_hour);
criterion_main!(benches);
