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
use argus_filters::{Ekf, GaussianFilter, Kf, Ukf, UtParams, nees, two_point_cv2};
use argus_imm::{
    AircraftImm, AircraftRadar, AircraftTuning, Augmentation, Imm, ImmEstimate, MarkovMatrix,
};
use argus_motion_models::{CoordinatedTurn, CoordinatedTurnRate, Cv2D, PlanarModel};
use argus_sensors::{CartesianPosition, ConversionMethod, RadarNoise, convert_polar};

mod flights;
use flights::{SIGMA_AZ_DEG, SIGMA_R, WARMUP_STEPS, flight, plots};

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

/// What one estimator gave over the runs.
struct Results {
    /// ANEES of the kinematic part per step index (over runs), after the warm-up.
    anees_per_step: Vec<f64>,
    /// Time average of the per-step ANEES.
    anees: f64,
    /// Position RMSE of the aircraft IMM and of seed 000's IMM, after the warm-up.
    rmse_new: f64,
    rmse_paper: f64,
}

impl Results {
    /// Steps whose ANEES lies below, in and above `band`, and the largest.
    fn split(&self, band: &ChiSquareInterval) -> (usize, usize, usize, f64) {
        let a = &self.anees_per_step;
        let below = a.iter().filter(|v| **v < band.lower).count();
        let above = a.iter().filter(|v| **v > band.upper).count();
        let max = a.iter().copied().fold(0.0, f64::max);
        (below, a.len() - below - above, above, max)
    }
}

/// Runs the aircraft IMM `imm` (started by `tuning`) and seed 000's IMM on `runs` flights.
fn evaluate<Fcv, Fct>(
    imm: &AircraftImm<Fcv, Fct, 2, 3>,
    tuning: &AircraftTuning<2, 3>,
    runs: u64,
) -> Results
where
    Fcv: GaussianFilter<4>,
    Fct: GaussianFilter<5>,
{
    let paper = paper_imm();
    let radar = AircraftRadar::new(
        [0.0, 0.0],
        RadarNoise::constant(SIGMA_R, SIGMA_AZ_DEG.to_radians(), 0.0).unwrap(),
    )
    .unwrap();
    let (mut nees_sum, mut nees_n) = (Vec::<f64>::new(), Vec::<usize>::new());
    let (mut se_new, mut se_paper, mut n) = (0.0, 0.0, 0usize);
    for run in 0..runs {
        let traj = flight(run);
        let pl = plots(&traj, run);
        let ((t1, z1, _), (t2, z2, _)) = (pl[0], pl[1]);
        let mut est = tuning.start(&radar, &z1, &z2, t2 - t1).unwrap();
        let ((c1, r1), (c2, r2)) = (converted(&z1), converted(&z2));
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
                let se = |x: &Vector<4>| (x[0] - truth[0]).powi(2) + (x[2] - truth[2]).powi(2);
                se_new += se(comb.mean());
                se_paper += se(pest.combined().unwrap().mean());
                n += 1;
            }
        }
    }
    // The steps every run reached (the flights have about the same number of plots).
    let per_step: Vec<f64> = nees_sum
        .iter()
        .zip(&nees_n)
        .filter(|(_, c)| **c == runs as usize)
        .map(|(s, c)| s / *c as f64)
        .skip(WARMUP_STEPS)
        .collect();
    Results {
        anees: per_step.iter().sum::<f64>() / per_step.len() as f64,
        anees_per_step: per_step,
        rmse_new: (se_new / n as f64).sqrt(),
        rmse_paper: (se_paper / n as f64).sqrt(),
    }
}

/// Monte Carlo runs (a reduced count: 100 runs give the same numbers within ±0.05 in
/// ANEES and ±0.02 in the RMSE ratio; docs/aircraft-imm.md).
const RUNS: u64 = 40;

#[test]
fn nees_in_band_and_rmse_below_seed_000_on_simulated_flights() {
    let tuning = AircraftTuning::<2, 3>::default();
    let band = anees_interval(4, RUNS as usize, 0.95).unwrap();
    let report = |name: &str, r: &Results| {
        let (below, inside, above, max) = r.split(&band);
        println!(
            "{name}: ANEES {:.2} (95 % band for {RUNS} runs [{:.2}, {:.2}]; steps below / in / \
             above it: {below} / {inside} / {above}, largest {max:.1}); \
             position RMSE {:.1} m vs seed 000's IMM {:.1} m: ratio {:.3}",
            r.anees,
            band.lower,
            band.upper,
            r.rmse_new,
            r.rmse_paper,
            r.rmse_new / r.rmse_paper
        );
    };
    let ekf = evaluate(&tuning.build().unwrap(), &tuning, RUNS);
    report("EKF, unbiased mixing", &ekf);
    // The time-averaged ANEES against the band of one step's average over the runs (the
    // steps of a run are correlated, so the band is indicative; Bar-Shalom, Li &
    // Kirubarajan 2001 §5.4.2). Measured 4.04 with this tuning, which was fixed from the
    // physical reasoning on `AircraftTuning::default` before this test ran.
    assert!(band.contains(ekf.anees), "ANEES {:.2}", ekf.anees);
    // Issue 18's goal on real flights: ≤ 0.8 × seed 000's IMM. Measured 0.70 here.
    assert!(
        ekf.rmse_new < 0.8 * ekf.rmse_paper,
        "{:.1} vs {:.1}",
        ekf.rmse_new,
        ekf.rmse_paper
    );

    // The same with the CT mode run by a UKF (α = 1, β = 2, κ = 0): the turn's
    // nonlinearity over 5 s is mild, so the two agree closely.
    let ukf = AircraftImm::new(
        tuning
            .build()
            .unwrap()
            .cv_filters()
            .map(|f| Ekf::new(*f.model())),
        Ukf::new(
            CoordinatedTurnRate::new(tuning.ct_sigma_a, tuning.ct_sigma_omega).unwrap(),
            UtParams::default(),
        )
        .unwrap(),
        MarkovMatrix::new(tuning.markov).unwrap(),
        tuning.augmentation,
    )
    .unwrap();
    let u = evaluate(&ukf, &tuning, RUNS);
    report("UKF for the CT mode", &u);
    assert!(band.contains(u.anees), "ANEES {:.2}", u.anees);
    // Tolerance: the filters differ by second-order terms of the turn; 5 % of the RMSE.
    assert!((u.rmse_new / ekf.rmse_new - 1.0).abs() < 0.05);

    // Zero padding (Granström et al. 2015's biased reference: the CV modes' missing turn
    // rate is taken as 0 with σ = 1e-5 rad/s) on the same plots: reported for the
    // comparison, and more optimistic than the unbiased rule (its mixed turn rate is
    // pulled towards 0 by the CV modes' weight, so the turn is under-predicted).
    let mut zero = tuning;
    zero.augmentation = Augmentation::Fixed { sigma: 1e-5 };
    let z = evaluate(&zero.build().unwrap(), &zero, RUNS);
    report("EKF, zero padding", &z);
    assert!(z.anees > ekf.anees, "{:.2} vs {:.2}", z.anees, ekf.anees);
}
