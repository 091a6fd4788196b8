//! Runs the Python `Imm.run` path (python/src/imm_core.rs, `PlainImm::run` on polar plots)
//! over the plots of a CSV written by `argus simulate` (columns `t`, `range`, `azimuth`)
//! `reps` times, for instruction counting (which does not depend on the machine's load):
//! the models and start of python/bench/bench.py item (c) (CV + CT ±3°/s, q = 0.5,
//! σr = 70 m, σθ = 0.08°, `P0 = 10⁴ I`, `t0 = t[0] − 1`).
//!
//! ```text
//! argus simulate gimpo --seed 3 --out /tmp/gimpo.csv
//! CARGO_PROFILE_RELEASE_DEBUG=line-tables-only cargo build --release -p argus-imm --example imm_run_profile
//! valgrind --tool=callgrind target/release/examples/imm_run_profile /tmp/gimpo.csv 100
//! ```
//!
//! Instructions per plot = (total − total with `reps` = 0) / (reps · plots). The printed
//! checksum (the last run's outputs to 17 digits) shows whether a change kept the arithmetic.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use std::hint::black_box;

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::Kf;
use argus_imm::{Imm, ImmEstimate, MarkovMatrix};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use argus_sensors::{CartesianPosition, UnbiasedPolarConversion};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .expect("usage: imm_run_profile <plots.csv> <reps>");
    let reps: usize = args.get(2).map_or(100, |s| s.parse().unwrap());
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    let (ct, cr, ca) = (col("t"), col("range"), col("azimuth"));
    let (mut times, mut plots) = (Vec::new(), Vec::new());
    for line in lines {
        let f: Vec<f64> = line
            .split(',')
            .map(|v| v.parse().unwrap_or(f64::NAN))
            .collect();
        times.push(f[ct]);
        plots.extend([f[cr], f[ca]]);
    }
    let omega = 3.0_f64.to_radians();
    let imm: Imm<Kf<PlanarModel>, 4, 3> = Imm::new(
        [
            Kf::new(PlanarModel::from(Cv2D::discrete(0.5).unwrap())),
            Kf::new(PlanarModel::from(CoordinatedTurn::new(omega, 0.5).unwrap())),
            Kf::new(PlanarModel::from(
                CoordinatedTurn::new(-omega, 0.5).unwrap(),
            )),
        ],
        MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]]).unwrap(),
    )
    .unwrap();
    let mut prev = times[0] - 1.0;
    let dts: Vec<f64> = times
        .iter()
        .map(|&t| {
            let d = t - prev;
            prev = t;
            d
        })
        .collect();
    let x0 = [
        plots[0] * plots[1].cos(),
        0.0,
        plots[0] * plots[1].sin(),
        0.0,
    ];
    let conv = UnbiasedPolarConversion::new(70.0, 0.08_f64.to_radians()).unwrap();
    let origin = Vector::<2>::zeros();
    let mut last = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..reps {
        let start = Gaussian::new(
            Vector::<4>::from_column_slice(&x0),
            Matrix::<4, 4>::identity() * 1e4,
        )
        .unwrap();
        let mut est = ImmEstimate::<4, 3>::from_common(start, [1.0 / 3.0; 3]).unwrap();
        let n = dts.len();
        let (mut xs, mut ps, mut mus) = (
            Vec::with_capacity(4 * n),
            Vec::with_capacity(16 * n),
            Vec::with_capacity(3 * n),
        );
        let plots = black_box(&plots);
        // The loop of `PlainImm::run` (python/src/imm_core.rs), polar plots.
        for (k, dt) in dts.iter().enumerate() {
            let c = conv.convert(plots[2 * k], plots[2 * k + 1]).unwrap();
            let (z, r) = (c.position + origin, c.covariance);
            let meas = CartesianPosition::<4, 2>::cv(r).unwrap();
            if *dt == 0.0 {
                est = imm
                    .update(&est.into_prediction(), &meas, &z)
                    .unwrap()
                    .estimate;
            } else {
                imm.step_in_place(&mut est, *dt, &meas, &z).unwrap();
            }
            let c = est.combined().unwrap();
            xs.extend_from_slice(c.mean().as_slice());
            ps.extend_from_slice(c.cov().transpose().as_slice());
            mus.extend_from_slice(&est.mode_probabilities());
        }
        last = black_box((xs, ps, mus));
    }
    let digest = |v: &[f64]| v.iter().map(|x| format!("{x:.17e}")).collect::<Vec<_>>();
    println!("plots {} reps {reps}", dts.len());
    if let Some(tail) = last.0.len().checked_sub(4) {
        println!("x_last {:?}", digest(&last.0[tail..]));
        println!("p_last {:?}", digest(&last.1[last.1.len() - 16..]));
        println!("mu_last {:?}", digest(&last.2[last.2.len() - 3..]));
        // FNV-1a over every output's bits: equal exactly when all outputs are bit-identical.
        let hash = [&last.0, &last.1, &last.2]
            .iter()
            .flat_map(|v| v.iter())
            .fold(0xcbf2_9ce4_8422_2325_u64, |h, x| {
                (h ^ x.to_bits()).wrapping_mul(0x0100_0000_01b3)
            });
        println!("bits {hash:016x}");
    }
}
