//! Runs `steps` steps of one IMM-side estimator on the bench's fixed input
//! (`benches/benches/imm.rs`: the paper's CV + 2 CT IMM, a plot 5 s after the start) and
//! prints a checksum, for instruction counting, which does not depend on the machine's load:
//!
//! ```text
//! CARGO_PROFILE_RELEASE_DEBUG=line-tables-only cargo build --release -p argus-imm --example imm_profile
//! valgrind --tool=callgrind target/release/examples/imm_profile multi 20000
//! callgrind_annotate --auto=yes callgrind.out.<pid>
//! ```
//!
//! `<which>` is one of `imm` (one IMM step, conversion included), `multi` (the 5 × 3
//! multi-IMM step), `evidence` (the evidence estimator's step), `variational`, or `none`
//! (set-up only, to subtract). Instructions per step = (total − `none` total) / steps.
//!
//! `track <steps>` instead runs every estimator along a noisy turning track (fixed seed) and
//! prints its final state to 17 digits: a change that is meant to keep the arithmetic can
//! be checked by comparing that output before and after.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use argus_sensors::PolarMeasurement;
use std::hint::black_box;

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::Kf;
use argus_imm::{
    EvidenceEstimate, EvidenceNoiseImm, Imm, ImmEstimate, MarkovMatrix, MultiImm, MultiImmEstimate,
    NoiseGrid, NoiseVariances, PlotConversion, UnbiasedConversion, VariationalEstimate,
    VariationalNoiseImm,
};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};

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

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map_or("multi", String::as_str);
    let steps: usize = args.get(2).map_or(20_000, |s| s.parse().unwrap());

    let imm = paper_imm();
    let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
    let var = NoiseVariances::from_sigmas(70.0, 0.08_f64.to_radians()).unwrap();
    let (x, y) = (-60_000.0 + 450.0_f64, -20_000.0_f64);
    let plot = PolarMeasurement::new(x.hypot(y), y.atan2(x)).unwrap();
    let mut sum = 0.0;
    match which {
        "imm" => {
            let est = start();
            for _ in 0..steps {
                let (m, z) = conv.convert(black_box(&plot), &var).unwrap();
                let u = imm.step(black_box(&est), 5.0, &m, &z).unwrap();
                sum += u.log_likelihood;
            }
        }
        "multi" => {
            let multi =
                MultiImm::new(imm, NoiseGrid::<5>::common(0.1).unwrap(), Some(0.05)).unwrap();
            let est = MultiImmEstimate::new(start(), var);
            for _ in 0..steps {
                let u = multi
                    .step(black_box(&est), 5.0, black_box(&plot), &conv)
                    .unwrap();
                sum += u.log_likelihoods[0];
            }
        }
        "evidence" => {
            let ev = EvidenceNoiseImm::new(imm, 0.2, 1.0, Some(0.05)).unwrap();
            let est = EvidenceEstimate::new(start(), var, 2.0).unwrap();
            for _ in 0..steps {
                let u = ev
                    .step(black_box(&est), 5.0, black_box(&plot), &conv)
                    .unwrap();
                sum += u.anchor().range();
            }
        }
        "variational" => {
            let vb = VariationalNoiseImm::new(imm, 0.995).unwrap();
            let est = VariationalEstimate::new(start(), var, 2.0).unwrap();
            for _ in 0..steps {
                let (_, u) = vb
                    .step(black_box(&est), 5.0, black_box(&plot), &conv)
                    .unwrap();
                sum += u.log_likelihood;
            }
        }
        "track" => track(steps),
        "none" => {}
        other => panic!("unknown estimator {other}"),
    }
    println!("{which} {steps} steps, checksum {sum:.9e}");
}

/// Every estimator along one noisy track (CV, a 2 °/s turn, CV; a plot every 5 s; σr = 70 m,
/// σθ = 0.08°, each estimator starting from 1.5 × the true variances); prints the final
/// states in full precision.
fn track(steps: usize) {
    let truth = NoiseVariances::from_sigmas(70.0, 0.08_f64.to_radians()).unwrap();
    let start_var = NoiseVariances::new(1.5 * truth.range(), 1.5 * truth.azimuth()).unwrap();
    // IMM_PERTURB=1 moves the range of plot 300 by one ulp: how far round-off alone carries.
    let nudge = std::env::var("IMM_PERTURB").is_ok();
    let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let dt = 5.0;
    let mut x = Vector::<4>::new(-60_000.0, 90.0, -20_000.0, 0.0);
    let mut plots = Vec::with_capacity(steps);
    for k in 0..steps {
        let w = if (60..90).contains(&(k % 200)) {
            2.0_f64.to_radians()
        } else {
            0.0
        };
        let (s, c) = (w * dt).sin_cos();
        x = if w == 0.0 {
            Vector::<4>::new(x[0] + dt * x[1], x[1], x[2] + dt * x[3], x[3])
        } else {
            Vector::<4>::new(
                x[0] + s / w * x[1] - (1.0 - c) / w * x[3],
                c * x[1] - s * x[3],
                x[2] + (1.0 - c) / w * x[1] + s / w * x[3],
                s * x[1] + c * x[3],
            )
        };
        let nr: f64 = StandardNormal.sample(&mut rng);
        let nt: f64 = StandardNormal.sample(&mut rng);
        let ulp = if nudge && k == 300 {
            1.0 + f64::EPSILON
        } else {
            1.0
        };
        plots.push(
            PolarMeasurement::new(
                (x[0].hypot(x[2]) + truth.range().sqrt() * nr) * ulp,
                x[2].atan2(x[0]) + truth.azimuth().sqrt() * nt,
            )
            .unwrap(),
        );
    }
    let show = |name: &str, g: &Gaussian<4>, extra: &[f64]| {
        println!("{name}: mean {:?}", g.mean().as_slice());
        println!("{name}: cov {:?}", g.cov().as_slice());
        println!("{name}: extra {extra:?}");
    };

    let imm = paper_imm();
    let mut est = start();
    let mut ll = 0.0;
    for p in &plots {
        let (m, z) = conv.convert(p, &start_var).unwrap();
        let u = imm.step(&est, dt, &m, &z).unwrap();
        ll += u.log_likelihood;
        est = u.estimate;
    }
    let mut extra = vec![ll];
    extra.extend(est.log_mode_probabilities());
    show("imm", &est.combined().unwrap(), &extra);

    let multi = MultiImm::new(
        paper_imm(),
        NoiseGrid::<5>::common(0.1).unwrap(),
        Some(0.05),
    )
    .unwrap();
    let mut mest = MultiImmEstimate::new(start(), start_var);
    let mut ll = 0.0;
    for (k, p) in plots.iter().enumerate() {
        // Every tenth plot through predict + update, the rest through step.
        let u = if k % 10 == 3 {
            multi
                .update(&multi.predict(&mest, dt).unwrap(), p, &conv)
                .unwrap()
        } else {
            multi.step(&mest, dt, p, &conv).unwrap()
        };
        ll += u.log_likelihoods.iter().sum::<f64>();
        mest = u.estimate;
    }
    let mut extra = vec![ll, mest.reference().range(), mest.reference().azimuth()];
    extra.extend(mest.noise_probabilities());
    extra.extend(mest.mode_probabilities());
    show("multi", &mest.combined().unwrap(), &extra);

    let grid = NoiseGrid::<9>::independent(0.1).unwrap();
    let multi9 = MultiImm::new(paper_imm(), grid, None).unwrap();
    let mut mest = MultiImmEstimate::new(start(), start_var);
    for p in &plots {
        mest = multi9.step(&mest, dt, p, &conv).unwrap().estimate;
    }
    let extra = [mest.reference().range(), mest.reference().azimuth()];
    show("multi9", &mest.combined().unwrap(), &extra);

    let ev = EvidenceNoiseImm::new(paper_imm(), 0.2, 1.0, Some(0.05)).unwrap();
    let mut eest = EvidenceEstimate::new(start(), start_var, 2.0).unwrap();
    for p in &plots {
        eest = ev.step(&eest, dt, p, &conv).unwrap();
    }
    let extra = [eest.variances().range(), eest.variances().azimuth()];
    show("evidence", &eest.combined().unwrap(), &extra);

    let vb = VariationalNoiseImm::new(paper_imm(), 0.995).unwrap();
    let mut vest = VariationalEstimate::new(start(), start_var, 2.0).unwrap();
    for p in &plots {
        vest = vb.step(&vest, dt, p, &conv).unwrap().0;
    }
    let v = vest.variances().unwrap();
    show(
        "variational",
        &vest.imm().combined().unwrap(),
        &[v.range(), v.azimuth()],
    );
}
