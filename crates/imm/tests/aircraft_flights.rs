//! The aircraft IMM on simulated civil flights seen by the seed-000 radar: NEES of the
//! kinematic part against its chi-square band, and position RMSE against seed 000's IMM
//! (CV + CT ±3 °/s fixed-rate modes, converted plots with the true R) on the same plots.
//!
//! Flights (issue 18): straight legs at 120–250 m/s, coordinated turns of 1–3 °/s lasting
//! 30–120 s, speed changes of 0.5–1.5 m/s² along track; a radar at the origin turning at
//! 72 °/s (5-s revisit, a plot when the beam crosses the aircraft), σr = 70 m,
//! σθ = 0.08°, P_D = 1, no clutter; ranges 20–150 km. Fixed seeds, a reduced count.

// A test binary: a panic on an unexpected error is the failure report.
#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use argus_core_math::{ChiSquareInterval, Matrix, Vector, anees_interval};
use argus_filters::{Kf, nees, two_point_cv2};
use argus_imm::{
    AircraftEkf, AircraftRadar, AircraftTuning, Augmentation, Imm, ImmEstimate, MarkovMatrix,
};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use argus_sensors::{CartesianPosition, ConversionMethod, RadarNoise, convert_polar};
use argus_sim::{
    KinematicState, Measurement, Schedule, Segment, SensorId, SensorKind, SensorSpec, Trajectory,
    Truth, generate_plots, run_rng,
};
use rand::RngExt;

const SIGMA_R: f64 = 70.0;
const SIGMA_AZ_DEG: f64 = 0.08;
const PERIOD: f64 = 5.0;
/// Flight length, s.
const DURATION: f64 = 900.0;
/// Steps after the start left out of the averages (the two-point start's transient).
const WARMUP_STEPS: usize = 6;

/// One random flight inside the 20–150 km annulus (drawn again until it stays inside).
fn flight(run: u64) -> Trajectory {
    let mut rng = run_rng(18_002, run);
    loop {
        let r0 = rng.random_range(40e3..120e3);
        let az0 = rng.random_range(0.0..std::f64::consts::TAU);
        let mut speed: f64 = rng.random_range(120.0..250.0);
        let mut heading: f64 = rng.random_range(0.0..std::f64::consts::TAU);
        let start = KinematicState::planar(
            r0 * az0.cos(),
            r0 * az0.sin(),
            speed * heading.cos(),
            speed * heading.sin(),
        );
        let mut segments = Vec::new();
        let mut t = 0.0;
        while t < DURATION {
            let leg = rng.random_range(40.0..150.0);
            segments.push(Segment::ConstantVelocity { duration: leg });
            t += leg;
            if rng.random_range(0.0..1.0) < 0.65 {
                let duration = rng.random_range(30.0..120.0);
                let sign = if rng.random_range(0.0..1.0) < 0.5 {
                    -1.0
                } else {
                    1.0
                };
                let rate = sign * rng.random_range(1.0_f64..3.0).to_radians();
                segments.push(Segment::Turn { duration, rate });
                heading += rate * duration;
                t += duration;
            } else {
                let duration = rng.random_range(20.0..60.0);
                let mut a = rng.random_range(0.5..1.5);
                if speed + a * duration > 250.0
                    || (speed > 185.0 && rng.random_range(0.0..1.0) < 0.5)
                {
                    a = -a;
                }
                if speed + a * duration < 120.0 {
                    a = a.abs();
                }
                let accel = Vector::<3>::new(a * heading.cos(), a * heading.sin(), 0.0);
                segments.push(Segment::Accelerate { duration, accel });
                speed += a * duration;
                t += duration;
            }
        }
        let traj = Trajectory::new(0.0, start, segments).unwrap();
        let inside = (0..=(DURATION / PERIOD) as usize).all(|k| {
            let s = traj.state_at(k as f64 * PERIOD).unwrap();
            (20e3..150e3).contains(&s.position.x.hypot(s.position.y))
        });
        if inside {
            return traj;
        }
    }
}

/// The plots of one flight: `(t, [r, θ])` and the true `[x, vx, y, vy]` at each.
fn plots(traj: &Trajectory, run: u64) -> Vec<(f64, Vector<2>, Vector<4>)> {
    let mut truth = Truth::new();
    truth.add(traj.clone());
    let radar = SensorSpec::new(
        SensorId(1),
        Vector::<3>::zeros(),
        SensorKind::Polar {
            sigma_range: SIGMA_R,
            sigma_azimuth: SIGMA_AZ_DEG.to_radians(),
        },
        Schedule::RotatingBeam {
            period: PERIOD,
            azimuth_at_zero: 0.0,
        },
    )
    .unwrap();
    let mut rng = run_rng(18_003, run);
    generate_plots(&truth, &[radar], &mut rng)
        .unwrap()
        .iter()
        .filter_map(|p| match p.measurement {
            Measurement::Polar { range, azimuth } => Some((
                p.time,
                Vector::<2>::new(range, azimuth),
                traj.state_at(p.time).unwrap().state_2d(),
            )),
            _ => None,
        })
        .collect()
}

type PaperImm = Imm<Kf<PlanarModel>, 4, 3>;

/// Seed 000's IMM (docs/papers/000-gimpo.md): CV σ = 0.1 m/s², CT ±3 °/s σ = 0.5 m/s²,
/// Markov matrix eq (20), μ₀ = ⅓ each.
fn paper_imm() -> PaperImm {
    let ct = |w: f64| {
        Kf::new(PlanarModel::from(
            CoordinatedTurn::from_degrees_per_second(w, 0.5).unwrap(),
        ))
    };
    Imm::new(
        [
            Kf::new(PlanarModel::from(Cv2D::discrete(0.1).unwrap())),
            ct(3.0),
            ct(-3.0),
        ],
        MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]]).unwrap(),
    )
    .unwrap()
}

/// The unbiased conversion with the true σ (seed 000 §3.1).
fn converted(z: &Vector<2>) -> (Vector<2>, Matrix<2, 2>) {
    let c = convert_polar(
        z[0],
        z[1],
        SIGMA_R,
        SIGMA_AZ_DEG.to_radians(),
        ConversionMethod::Unbiased,
    )
    .unwrap();
    (c.position, c.covariance)
}

/// Per-run sums after the warm-up.
#[derive(Default)]
struct Sums {
    se_new: f64,
    se_paper: f64,
    n: usize,
}

struct Results {
    /// ANEES per step index (over runs), 4-D kinematic part.
    anees_per_step: Vec<f64>,
    /// Time average of the per-step ANEES.
    anees: f64,
    rmse_new: f64,
    rmse_paper: f64,
    runs: usize,
}

fn evaluate(tuning: &AircraftTuning<2, 3>, runs: u64) -> Results {
    let imm: AircraftEkf<2, 3> = tuning.build().unwrap();
    let paper = paper_imm();
    let radar = AircraftRadar::new(
        [0.0, 0.0],
        RadarNoise::constant(SIGMA_R, SIGMA_AZ_DEG.to_radians(), 0.0).unwrap(),
    )
    .unwrap();
    let mut nees_sum: Vec<f64> = Vec::new();
    let mut nees_n: Vec<usize> = Vec::new();
    let mut sums = Sums::default();
    for run in 0..runs {
        let traj = flight(run);
        let pl = plots(&traj, run);
        let (t1, z1, _) = pl[0];
        let (t2, z2, _) = pl[1];
        let mut est = tuning.start(&radar, &z1, &z2, t2 - t1).unwrap();
        let (c1, r1) = converted(&z1);
        let (c2, r2) = converted(&z2);
        let g = two_point_cv2(&c1, &r1, &c2, &r2, t2 - t1).unwrap();
        let mut pest = ImmEstimate::from_common(g, [1.0 / 3.0; 3]).unwrap();
        let mut prev = t2;
        for (k, (t, z, truth)) in pl[2..].iter().enumerate() {
            let dt = t - prev;
            prev = *t;
            est = imm.step(&est, dt, &radar, z).unwrap().estimate;
            let (c, r) = converted(z);
            let m = CartesianPosition::<4, 2>::cv(r).unwrap();
            pest = paper.step(&pest, dt, &m, &c).unwrap().estimate;
            let comb = est.combined().unwrap();
            if nees_sum.len() <= k {
                nees_sum.push(0.0);
                nees_n.push(0);
            }
            nees_sum[k] += nees(&comb, truth).unwrap();
            nees_n[k] += 1;
            if k >= WARMUP_STEPS {
                let pc = pest.combined().unwrap();
                let se = |x: &Vector<4>| (x[0] - truth[0]).powi(2) + (x[2] - truth[2]).powi(2);
                sums.se_new += se(comb.mean());
                sums.se_paper += se(pc.mean());
                sums.n += 1;
            }
        }
    }
    // Steps seen by every run only (flights have about the same number of plots).
    let full: Vec<f64> = nees_sum
        .iter()
        .zip(&nees_n)
        .filter(|(_, n)| **n == runs as usize)
        .map(|(s, n)| s / *n as f64)
        .collect();
    let tail = &full[WARMUP_STEPS..];
    Results {
        anees: tail.iter().sum::<f64>() / tail.len() as f64,
        anees_per_step: tail.to_vec(),
        rmse_new: (sums.se_new / sums.n as f64).sqrt(),
        rmse_paper: (sums.se_paper / sums.n as f64).sqrt(),
        runs: runs as usize,
    }
}

fn band(runs: usize) -> ChiSquareInterval {
    anees_interval(4, runs, 0.95).unwrap()
}

#[test]
fn sweep() {
    let runs = std::env::var("RUNS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20);
    let base = AircraftTuning::<2, 3>::default();
    let mut cases = vec![("default", base)];
    let mut t = base;
    t.augmentation = Augmentation::Fixed { sigma: 1e-5 };
    cases.push(("zero-pad", t));
    for so in [0.02, 0.05, 0.2, 0.4] {
        let mut t = base;
        t.ct_sigma_omega = f64::to_radians(so);
        cases.push((Box::leak(format!("sw{so}").into_boxed_str()), t));
    }
    for q in [[0.1, 1.0], [0.3, 1.0], [0.5, 3.0], [1.0, 3.0]] {
        let mut t = base;
        t.cv_sigma_a = q;
        cases.push((Box::leak(format!("cv{q:?}").into_boxed_str()), t));
    }
    for q in [0.2, 1.0, 2.0] {
        let mut t = base;
        t.ct_sigma_a = q;
        cases.push((Box::leak(format!("ct{q}").into_boxed_str()), t));
    }
    let b = band(runs as usize);
    for (name, t) in cases {
        let r = evaluate(&t, runs);
        let inside = r.anees_per_step.iter().filter(|v| b.contains(**v)).count() as f64
            / r.anees_per_step.len() as f64;
        println!(
            "{name:>16}: ANEES {:.2} band [{:.2},{:.2}] inside {:.2}  RMSE new {:.1} paper {:.1} ratio {:.3}",
            r.anees,
            b.lower,
            b.upper,
            inside,
            r.rmse_new,
            r.rmse_paper,
            r.rmse_new / r.rmse_paper
        );
    }
}
