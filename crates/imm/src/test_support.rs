//! Test fixtures: the paper's IMM built from the workspace's Kalman filter and planar models,
//! and the gimpo truth with rotating-beam timing. The library never uses them.
#![allow(clippy::unwrap_used, clippy::expect_used, non_snake_case)]

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_motion_models::{CoordinatedTurn, Cv2D, LinearMotionModel};
use argus_sensors::PolarMeasurement;
use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

use crate::{Imm, ImmEstimate, MarkovMatrix, NoiseVariances, unbiased_conversion};

/// The workspace's Kalman filter (seed 000 eqs (3)–(4)) on the workspace's planar models.
pub(crate) use argus_filters::Kf;
/// CV (eq 15) or fixed-rate CT (eq 16) with `Q = σv² Γ Γᵀ` (eqs 17–18): the motion-models crate's.
pub(crate) use argus_motion_models::PlanarModel as Motion;

/// The CV model with white-acceleration σ `sv` (m/s²).
pub(crate) fn cv(sv: f64) -> Motion {
    Motion::from(Cv2D::discrete(sv).unwrap())
}

/// The fixed-rate coordinated turn at `omega` (rad/s) with σ `sv` (m/s²).
pub(crate) fn ct(omega: f64, sv: f64) -> Motion {
    Motion::from(CoordinatedTurn::new(omega, sv).unwrap())
}

/// The paper's IMM: CV (0.1 m/s²) and CT ±3°/s (0.5 m/s²), eq (20).
pub(crate) fn paper_imm() -> Imm<Kf<Motion>, 4, 3> {
    let w = 3.0_f64.to_radians();
    Imm::new(
        [Kf::new(cv(0.1)), Kf::new(ct(w, 0.5)), Kf::new(ct(-w, 0.5))],
        MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]]).unwrap(),
    )
    .unwrap()
}

/// Table 1 of seed 000: (start, duration, turn rate deg/s).
const SEGMENTS: [(f64, f64, f64); 10] = [
    (0.0, 330.0, 0.0),
    (330.0, 63.0, 1.5),
    (393.0, 120.0, 0.0),
    (513.0, 57.0, -0.25),
    (570.0, 105.0, 0.0),
    (675.0, 43.0, -2.0),
    (718.0, 122.0, 0.0),
    (840.0, 23.0, -2.5),
    (863.0, 70.0, -0.5),
    (933.0, 86.0, 0.0),
];

fn advance(x: Vector<4>, w: f64, t: f64) -> Vector<4> {
    if w.abs() < 1e-12 {
        cv(0.0).transition(t) * x
    } else {
        ct(w, 0.0).transition(t) * x
    }
}

/// The gimpo truth at time `t` (SPEC §000).
pub(crate) fn truth_at(t: f64) -> Vector<4> {
    let mut x = Vector::<4>::new(-60_000.0, 90.0, -20_000.0, 0.0);
    // Exploration only: EV_STRAIGHT=1 removes the turns (a maneuver-free reference).
    let straight = std::env::var("EV_STRAIGHT").is_ok();
    for (start, dur, wdeg) in SEGMENTS {
        let w = if straight { 0.0 } else { wdeg.to_radians() };
        if t <= start + dur {
            return advance(x, w, t - start);
        }
        x = advance(x, w, dur);
    }
    x
}

/// Plot times: the beam (azimuth 0 at t = 0, +72°/s) crosses the target.
pub(crate) fn beam_times() -> Vec<f64> {
    let end = 1019.0;
    let g = |t: f64| {
        let x = truth_at(t);
        let th = x[2].atan2(x[0]).rem_euclid(2.0 * std::f64::consts::PI);
        2.0 * std::f64::consts::PI * t / 5.0 - th
    };
    // g increases by 2π per beam revolution; crossings at g = 2πk (θ in [0, 2π), so k ≥ 0 …).
    let mut times = Vec::new();
    let mut k = (g(0.0) / (2.0 * std::f64::consts::PI)).ceil();
    loop {
        let target = 2.0 * std::f64::consts::PI * k;
        let (mut lo, mut hi) = (0.0_f64.max(5.0 * k - 5.0), 5.0 * k + 5.0);
        if lo > end {
            break;
        }
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if g(mid) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let t = 0.5 * (lo + hi);
        if t > end {
            break;
        }
        times.push(t);
        k += 1.0;
    }
    times
}

/// One run's plots.
pub(crate) fn plots<G: Rng>(times: &[f64], sr: f64, st: f64, rng: &mut G) -> Vec<PolarMeasurement> {
    times
        .iter()
        .map(|&t| {
            let x = truth_at(t);
            let nr: f64 = StandardNormal.sample(rng);
            let nt: f64 = StandardNormal.sample(rng);
            PolarMeasurement::new(x[0].hypot(x[2]) + sr * nr, x[2].atan2(x[0]) + st * nt).unwrap()
        })
        .collect()
}

/// Two-point initialisation (Bar-Shalom et al. 2001 §5.5.3) with the filter's assumed `var`.
pub(crate) fn two_point(
    p1: &PolarMeasurement,
    p2: &PolarMeasurement,
    T: f64,
    var: &NoiseVariances,
) -> ImmEstimate<4, 3> {
    let (z1, R1) = unbiased_conversion(p1, var).unwrap();
    let (z2, R2) = unbiased_conversion(p2, var).unwrap();
    let x = Vector::<4>::new(z2[0], (z2[0] - z1[0]) / T, z2[1], (z2[1] - z1[1]) / T);
    let mut P = Matrix::<4, 4>::zeros();
    for a in 0..2 {
        for b in 0..2 {
            P[(2 * a, 2 * b)] = R2[(a, b)];
            P[(2 * a, 2 * b + 1)] = R2[(a, b)] / T;
            P[(2 * a + 1, 2 * b)] = R2[(a, b)] / T;
            P[(2 * a + 1, 2 * b + 1)] = (R1[(a, b)] + R2[(a, b)]) / (T * T);
        }
    }
    ImmEstimate::from_common(Gaussian::new(x, P).unwrap(), [1.0 / 3.0; 3]).unwrap()
}
