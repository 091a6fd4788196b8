//! Seed 003: one predict + update step of the conventional decoupled filter (CDKF,
//! both frame handlings), the adaptive one (ADKF) and the coupled 6-state KF on the
//! same converted radar-beacon plot (mid-approach geometry of `rbs-landing`).
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;

use argus_adaptive::{
    AdaptiveDecoupledFilter, AdaptiveRConfig, AdaptiveState, ConvertedPlot, CoupledCvFilter,
    DecoupledEstimate, DecoupledFilter, FrameHandling, REstimate, Warmup, beacon_plot_of,
};
use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::GaussianFilter;
use argus_sensors::SnrNoise;
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};

const DT: f64 = 0.1;

fn rbs_step(c: &mut Criterion) {
    let link = SnrNoise::link_for_range_sigma(149.9, 2.97, 3006.0).unwrap();
    let radar = SnrNoise::new(149.9, 2f64.to_radians(), 2f64.to_radians(), 1.6, link).unwrap();
    let truth = Vector::<3>::new(-3000.0, -100.0, 157.2);
    let sph = beacon_plot_of(&truth).unwrap();
    let plot = ConvertedPlot::from_spherical(&sph, &radar.sigmas_at_range(sph.range())).unwrap();
    let mean = Vector::<6>::new(-3003.5, 35.0, -100.0, 0.0, 157.0, -1.8);
    let block = Matrix::<2, 2>::new(4.0, 0.5, 0.5, 0.4);
    let dec = DecoupledEstimate::new(mean, [block; 3], *plot.frame()).unwrap();
    let g = dec.to_gaussian().unwrap();

    let mut group = c.benchmark_group("rbs_step");
    for (name, handling) in [
        ("cdkf_rotate", FrameHandling::Rotate),
        ("cdkf_fixed", FrameHandling::Fixed),
    ] {
        let f = DecoupledFilter::new(0.05, handling).unwrap();
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                let p = f.predict(black_box(&dec), DT).unwrap();
                black_box(f.update(&p, black_box(&plot)).unwrap())
            });
        });
    }
    let adkf = AdaptiveDecoupledFilter::new(
        DecoupledFilter::new(0.05, FrameHandling::Rotate).unwrap(),
        AdaptiveRConfig::new(20, 1e-6, Warmup::Constant).unwrap(),
    );
    let st = AdaptiveState {
        estimate: dec,
        r: REstimate::new(plot.cartesian_noise()).unwrap(),
    };
    group.bench_function(BenchmarkId::from_parameter("adkf"), |b| {
        b.iter(|| {
            let p = adkf.predict(black_box(&st), DT).unwrap();
            black_box(adkf.update(&p, black_box(&plot)).unwrap())
        });
    });
    let kf = CoupledCvFilter::new(0.05).unwrap();
    group.bench_function(BenchmarkId::from_parameter("kf6"), |b| {
        b.iter(|| {
            let p: Gaussian<6> = kf.predict(black_box(&g), DT).unwrap();
            black_box(kf.update(&p, black_box(&plot), plot.position()).unwrap())
        });
    });
    group.finish();
}

criterion_group!(benches, rbs_step);
criterion_main!(benches);
