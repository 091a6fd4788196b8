//! IMM (CV + 2 CT, seed 000) step, the 5 × 3 multi-IMM step, and the aircraft IMM step
//! (2 CV on 4 states + CT with the turn rate on 5, EKFs, a (range, azimuth) plot).
//!
//! Targets (issue 4): IMM step ≤ 1 µs, multi-IMM step ≤ 5 µs on the project machine.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use argus_sensors::PolarMeasurement;
use std::hint::black_box;

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::Kf;
use argus_imm::{
    AircraftRadar, AircraftTuning, EvidenceEstimate, EvidenceNoiseImm, Imm, ImmEstimate,
    MarkovMatrix, MultiImm, MultiImmEstimate, NoiseGrid, NoiseVariances, PlotConversion,
    UnbiasedConversion, VariationalEstimate, VariationalNoiseImm,
};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use argus_sensors::RadarNoise;
use criterion::{Criterion, criterion_group, criterion_main};

fn paper_imm() -> Imm<Kf<PlanarModel>, 4, 3> {
    Imm::new(
        [
            Kf::new(PlanarModel::from(Cv2D::discrete(0.1).unwrap())),
            Kf::new(PlanarModel::from(
                CoordinatedTurn::from_degrees_per_second(3.0, 0.5).unwrap(),
            )),
            Kf::new(PlanarModel::from(
                CoordinatedTurn::from_degrees_per_second(-3.0, 0.5).unwrap(),
            )),
        ],
        MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]]).unwrap(),
    )
    .unwrap()
}

fn start() -> ImmEstimate<4, 3> {
    let g = Gaussian::new(
        Vector::<4>::new(-60_000.0, 90.0, -20_000.0, 0.0),
        Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(5e3, 400.0, 5e3, 400.0)),
    )
    .unwrap();
    ImmEstimate::from_common(g, [1.0 / 3.0; 3]).unwrap()
}

fn benches(c: &mut Criterion) {
    let imm = paper_imm();
    let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
    let var = NoiseVariances::from_sigmas(70.0, 0.08_f64.to_radians()).unwrap();
    // The target 5 s later, as a plot (noise-free; the cost does not depend on the noise).
    let (x, y) = (-60_000.0 + 450.0_f64, -20_000.0_f64);
    let plot = PolarMeasurement::new(x.hypot(y), y.atan2(x)).unwrap();
    let mut g = c.benchmark_group("imm");

    let est = start();
    g.bench_function("imm_cv_2ct_step", |b| {
        b.iter(|| {
            let (m, z) = conv.convert(black_box(&plot), &var).unwrap();
            imm.step(black_box(&est), 5.0, &m, &z).unwrap()
        });
    });

    // A batch run as the Python `Imm.run` makes it (issue 20 (c)): 204 polar plots of a
    // target at 60 km flying straight, then turning at 3°/s, then straight, one scan every
    // ~5 s with jittered times; each plot converted (unbiased), one IMM cycle, the combined
    // estimate and the mode probabilities written out.
    let scan: Vec<(f64, PolarMeasurement)> = {
        let (mut x, mut y, mut heading) = (-60_000.0_f64, -20_000.0_f64, 0.0_f64);
        (0..204)
            .map(|k| {
                #[allow(clippy::cast_precision_loss)]
                let dt = 5.0 + 1e-3 * ((k * 7919) % 13) as f64;
                let turn = if (70..100).contains(&k) {
                    3.0_f64.to_radians()
                } else {
                    0.0
                };
                heading += turn * dt;
                x += 90.0 * heading.cos() * dt;
                y += 90.0 * heading.sin() * dt;
                (dt, PolarMeasurement::new(x.hypot(y), y.atan2(x)).unwrap())
            })
            .collect()
    };
    let mut out = vec![0.0; scan.len() * (4 + 16 + 3)];
    g.bench_function("imm_cv_2ct_run_204_plots", |b| {
        b.iter(|| {
            let mut e = start();
            for ((dt, plot), o) in scan.iter().zip(out.chunks_exact_mut(23)) {
                let (m, z) = conv.convert(black_box(plot), &var).unwrap();
                e = imm.step(&e, *dt, &m, &z).unwrap().estimate;
                let c = e.combined().unwrap();
                o[..4].copy_from_slice(c.mean().as_slice());
                o[4..20].copy_from_slice(c.cov().as_slice());
                o[20..].copy_from_slice(&e.mode_probabilities());
            }
            black_box(&out);
        });
    });

    let multi = MultiImm::new(
        paper_imm(),
        NoiseGrid::<5>::common(0.1).unwrap(),
        Some(0.05),
    )
    .unwrap();
    let mest = MultiImmEstimate::new(start(), var);
    g.bench_function("multi_imm_5x3_step", |b| {
        b.iter(|| {
            multi
                .step(black_box(&mest), 5.0, black_box(&plot), &conv)
                .unwrap()
        });
    });

    let vb = VariationalNoiseImm::new(paper_imm(), 0.995).unwrap();
    let vest = VariationalEstimate::new(start(), var, 2.0).unwrap();
    g.bench_function("variational_imm_step", |b| {
        b.iter(|| {
            vb.step(black_box(&vest), 5.0, black_box(&plot), &conv)
                .unwrap()
        });
    });

    // The evidence estimator: five IMMs (15 filter cycles), the cost of the 5 × 3 rule.
    let ev = EvidenceNoiseImm::new(paper_imm(), 0.2, 1.0, Some(0.05)).unwrap();
    let eest = EvidenceEstimate::new(start(), var, 2.0).unwrap();
    g.bench_function("evidence_imm_step", |b| {
        b.iter(|| {
            ev.step(black_box(&eest), 5.0, black_box(&plot), &conv)
                .unwrap()
        });
    });

    // The aircraft IMM: mixing across the two state sizes, three EKF predictions and polar
    // updates, from a start after two plots 5 s apart.
    let tuning = AircraftTuning::<2, 3>::default();
    let aircraft = tuning.build().unwrap();
    let radar = AircraftRadar::new(
        [0.0, 0.0],
        RadarNoise::constant(70.0, 0.08_f64.to_radians(), 0.0).unwrap(),
    )
    .unwrap();
    let polar = |x: f64, y: f64| Vector::<2>::new(x.hypot(y), y.atan2(x));
    let aest = tuning
        .start(
            &radar,
            &polar(-60_000.0 - 450.0, -20_000.0),
            &polar(-60_000.0, -20_000.0),
            5.0,
        )
        .unwrap();
    let z = polar(x, y);
    g.bench_function("aircraft_imm_2cv_ct_step", |b| {
        b.iter(|| {
            aircraft
                .step(black_box(&aest), 5.0, &radar, black_box(&z))
                .unwrap()
        });
    });
    g.finish();
}

criterion_group!(imm_benches, benches);
criterion_main!(imm_benches);
