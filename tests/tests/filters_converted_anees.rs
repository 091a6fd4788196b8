//! Cross-crate consistency: a 2-D constant-velocity target seen by a polar radar,
//! tracked by a Kalman filter on unbiased converted measurements, over 200 seeded
//! Monte Carlo runs. The final-time ANEES must lie inside its 95 % chi-square
//! interval (Bar-Shalom, Li & Kirubarajan 2001 §5.4.2; unbiased conversion: Mo et
//! al. 1998, BLK 2001 §10.4.3).

// A test binary: a panic on an unexpected error is the failure report.
#![allow(clippy::unwrap_used)]

use argus_core_math::{Gaussian, Matrix, Vector, anees_interval};
use argus_filters::{ChiSquareAverage, GaussianFilter, Kf, nees, two_point_cv2};
use argus_motion_models::Cv2D;
use argus_sensors::{CartesianPosition, ConversionMethod, convert_polar};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

/// Scenario: radar at the origin, σr = 30 m, σθ = 0.5°; target starting at
/// (15 km, 8 km) with velocity (−120, 60) m/s and DWNA σa = 0.5 m/s² (the filter's
/// model too); a plot every T = 2 s for 60 plots (two for initiation).
const RUNS: usize = 200;
const STEPS: usize = 60;
const T: f64 = 2.0;
const SIGMA_R: f64 = 30.0;
const SIGMA_A: f64 = 0.5;

fn sigma_theta() -> f64 {
    0.5f64.to_radians()
}

fn normal(rng: &mut ChaCha8Rng) -> f64 {
    StandardNormal.sample(rng)
}

/// The truth's DWNA step: `x ← F x + Γ a`, `a ~ N(0, σa² I₂)`.
fn truth_step(x: &Vector<4>, rng: &mut ChaCha8Rng) -> Vector<4> {
    let (ax, ay) = (SIGMA_A * normal(rng), SIGMA_A * normal(rng));
    Vector::<4>::new(
        x[0] + T * x[1] + 0.5 * T * T * ax,
        x[1] + T * ax,
        x[2] + T * x[3] + 0.5 * T * T * ay,
        x[3] + T * ay,
    )
}

/// A converted polar plot of the true position.
fn plot(x: &Vector<4>, rng: &mut ChaCha8Rng) -> (Vector<2>, Matrix<2, 2>) {
    let r = x[0].hypot(x[2]) + SIGMA_R * normal(rng);
    let theta = x[2].atan2(x[0]) + sigma_theta() * normal(rng);
    let c = convert_polar(r, theta, SIGMA_R, sigma_theta(), ConversionMethod::Unbiased).unwrap();
    (c.position, c.covariance)
}

/// One run; returns the NEES after each update from the third plot on.
fn run(seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let kf = Kf::new(Cv2D::discrete(SIGMA_A).unwrap());
    let mut x = Vector::<4>::new(15_000.0, -120.0, 8_000.0, 60.0);
    let (z1, r1) = plot(&x, &mut rng);
    x = truth_step(&x, &mut rng);
    let (z2, r2) = plot(&x, &mut rng);
    let mut est: Gaussian<4> = two_point_cv2(&z1, &r1, &z2, &r2, T).unwrap();
    let mut out = Vec::with_capacity(STEPS);
    for _ in 2..STEPS {
        x = truth_step(&x, &mut rng);
        let (z, r) = plot(&x, &mut rng);
        let meas = CartesianPosition::<4, 2>::cv(r).unwrap();
        let pred = kf.predict(&est, T).unwrap();
        est = kf.update(&pred, &meas, &z).unwrap().0;
        out.push(nees(&est, &x).unwrap());
    }
    out
}

#[test]
fn kf_on_unbiased_converted_plots_is_consistent() {
    let runs: Vec<Vec<f64>> = (0..RUNS as u64).map(|s| run(1000 + s)).collect();
    let last = runs[0].len() - 1;
    let mut final_anees = ChiSquareAverage::new(4).unwrap();
    for r in &runs {
        final_anees.push(r[last]).unwrap();
    }
    let iv = anees_interval(4, RUNS, 0.95).unwrap();
    let a = final_anees.mean().unwrap();
    // Printed for the record (time-averaged values are correlated, not asserted).
    let mut all = ChiSquareAverage::new(4).unwrap();
    for r in &runs {
        for &v in r {
            all.push(v).unwrap();
        }
    }
    eprintln!(
        "final ANEES {a:.3} in [{:.3}, {:.3}]; time-averaged ANEES {:.3}",
        iv.lower,
        iv.upper,
        all.mean().unwrap()
    );
    // 95 % two-sided chi-square interval with 4·200 dof, divided by 200 runs.
    assert!(
        iv.contains(a),
        "ANEES {a} outside [{}, {}]",
        iv.lower,
        iv.upper
    );
    assert!(final_anees.is_consistent(0.95).unwrap());
}
