//! IMM smoothing: one mode reduces to the RTS smoother, the smoothed IMM on seed 000's
//! Gimpo trajectory (consistency and RMS position error against the filtered IMM), and
//! the errors of bad sequences.

// A test binary: a panic on an unexpected error is the failure report.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_core_math::{Gaussian, Matrix, Vector, anees_interval};
use argus_filters::{Kf, RtsTrack, SmoothError, two_point_cv2};
use argus_imm::smooth::gibbs::{GibbsChain, GibbsProblem, pooled};
use argus_imm::{
    Imm, ImmEstimate, ImmSmoothError, ImmTrack, MarkovMatrix, NoiseVariances, PairWeights,
    PlotConversion, UnbiasedConversion, unbiased_conversion,
};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use argus_sensors::{CartesianPosition, Measurement, PolarMeasurement};
use argus_sim::{
    KinematicState, Schedule, Segment, SensorId, SensorKind, SensorSpec, Trajectory, Truth,
    generate_plots, run_rng,
};

#[test]
fn one_mode_is_the_rts_smoother() {
    // With R = 1 (π = [1]) the backward mixing is the identity and eqs (5)–(6) are the
    // RTS step: the IMM smoother equals RtsTrack's to round-off (1e-9 relative).
    let kf = Kf::new(Cv2D::discrete(0.7).unwrap());
    let imm = Imm::new([kf], MarkovMatrix::new([[1.0]]).unwrap()).unwrap();
    let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::new(300.0, 40.0, 40.0, 200.0)).unwrap();
    let g = Gaussian::new(
        Vector::<4>::new(0.0, 10.0, 0.0, -5.0),
        Matrix::<4, 4>::identity() * 1e3,
    )
    .unwrap();
    let mut it = ImmTrack::new(*imm.markov(), 0.0, ImmEstimate::new([g], [1.0]).unwrap()).unwrap();
    let mut rt = RtsTrack::new(0.0, g).unwrap();
    for k in 1..=40 {
        let t = 1.5 * f64::from(k) + 0.3 * f64::from(k % 3);
        let z = Vector::<2>::new(
            10.0 * t + 20.0 * (t * 0.3).sin(),
            -5.0 * t + 15.0 * (t * 0.2).cos(),
        );
        it.step(&imm, t, &pos, &z).unwrap();
        rt.step(&kf, t, &pos, &z).unwrap();
    }
    let a = it.smooth().unwrap();
    let b = rt.smooth().unwrap();
    for (k, (a, b)) in a.iter().zip(&b).enumerate() {
        assert!(
            (a.combined.mean() - b.mean()).amax() < 1e-9 * b.mean().amax(),
            "step {k}"
        );
        assert!(
            (a.combined.cov() - b.cov()).amax() < 1e-9 * b.cov().amax(),
            "step {k}"
        );
        assert!((a.mode_probabilities[0] - 1.0).abs() < 1e-12);
    }
}

/// Table 1 of seed 000 (duration s, turn rate deg/s; 0 = CV), as in the gimpo scenario.
const SEGMENTS: [(f64, f64); 10] = [
    (330.0, 0.0),
    (63.0, 1.5),
    (120.0, 0.0),
    (57.0, -0.25),
    (105.0, 0.0),
    (43.0, -2.0),
    (122.0, 0.0),
    (23.0, -2.5),
    (70.0, -0.5),
    (86.0, 0.0),
];

/// The paper's IMM (§3.1): CV σv = 0.1 m/s², CT ±3 deg/s σv = 0.5 m/s², eq (20).
fn paper_imm() -> Imm<Kf<PlanarModel>, 4, 3> {
    let ct = |w: f64| {
        Kf::new(PlanarModel::from(
            CoordinatedTurn::from_degrees_per_second(w, 0.5).unwrap(),
        ))
    };
    let cv = Kf::new(PlanarModel::from(Cv2D::discrete(0.1).unwrap()));
    let pi =
        MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]]).unwrap();
    Imm::new([cv, ct(3.0), ct(-3.0)], pi).unwrap()
}

/// What one campaign measured: smoothed / filtered RMS position error of the IMM
/// smoother, of the RTS smoother on the nearest IMM-mode sequence and on the true model,
/// and the smoothed IMM's ANEES.
struct Campaign {
    ratio: f64,
    nearest_ratio: f64,
    true_model_ratio: f64,
    anees: f64,
}

/// Seed 000's plot noise: σr = 70 m, σθ = 0.08°.
const SIGMA_R: f64 = 70.0;
const SIGMA_TH_DEG: f64 = 0.08;

/// Seed 000's scene (crates/scenarios/src/gimpo.rs): the Table 1 approach from
/// (−60 km, −20 km) at 90 m/s and a rotating beam of period 5 s at the origin.
fn gimpo_scene() -> (Trajectory, Truth, SensorSpec) {
    let segments = SEGMENTS
        .iter()
        .map(|&(duration, w)| {
            if w == 0.0 {
                Segment::ConstantVelocity { duration }
            } else {
                Segment::Turn {
                    duration,
                    rate: w.to_radians(),
                }
            }
        })
        .collect();
    let traj = Trajectory::new(
        0.0,
        KinematicState::planar(-60_000.0, -20_000.0, 90.0, 0.0),
        segments,
    )
    .unwrap();
    let mut truth = Truth::new();
    truth.add(traj.clone());
    let radar = SensorSpec::new(
        SensorId(1),
        Vector::<3>::zeros(),
        SensorKind::Polar {
            sigma_range: SIGMA_R,
            sigma_azimuth: SIGMA_TH_DEG.to_radians(),
        },
        Schedule::RotatingBeam {
            period: 5.0,
            azimuth_at_zero: 0.0,
        },
    )
    .unwrap();
    (traj, truth, radar)
}

/// Run `run` of campaign seed `seed`: the polar plots in time order (as `argus run gimpo`
/// draws them, from `run_rng(seed, run)`).
fn gimpo_plots(
    truth: &Truth,
    radar: &SensorSpec,
    seed: u64,
    run: u64,
) -> Vec<(f64, PolarMeasurement)> {
    let mut rng = run_rng(seed, run);
    generate_plots(truth, std::slice::from_ref(radar), &mut rng)
        .unwrap()
        .iter()
        .filter_map(|pl| match pl.plot.measurement() {
            Measurement::Polar(m) => PolarMeasurement::new(m.range(), m.azimuth())
                .ok()
                .map(|x| (pl.plot.time(), x)),
            _ => None,
        })
        .collect()
}

/// The two-point start of the IMM track from the first two plots (unbiased conversion,
/// true R, μ₀ uniform): the common start `g` and the track at the second plot's time.
fn two_point_start(
    imm: &Imm<Kf<PlanarModel>, 4, 3>,
    plots: &[(f64, PolarMeasurement)],
    var: &NoiseVariances,
) -> (Gaussian<4>, ImmTrack<4, 3>) {
    let ((t1, p1), (t2, p2)) = (plots[0], plots[1]);
    let (z1, r1) = unbiased_conversion(&p1, var).unwrap();
    let (z2, r2) = unbiased_conversion(&p2, var).unwrap();
    let g = two_point_cv2(&z1, &r1, &z2, &r2, t2 - t1).unwrap();
    let start = ImmEstimate::from_common(g, [1.0 / 3.0; 3]).unwrap();
    (g, ImmTrack::new(*imm.markov(), t2, start).unwrap())
}

fn gimpo_campaign(weights: PairWeights) -> Campaign {
    // Seed 000's scene (`gimpo_scene`, σr = 70 m, σθ = 0.08°); the paper's IMM with the true R on unbiased converted plots, two-point
    // start, μ₀ uniform. 30 seeded runs.
    let runs = 30_u64;
    let (traj, truth, radar) = gimpo_scene();
    let imm = paper_imm();
    let var = NoiseVariances::from_sigmas(SIGMA_R, SIGMA_TH_DEG.to_radians()).unwrap();
    let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
    // Per step: Σ NEES smoothed, Σ NEES filtered, Σ squared position error smoothed,
    // filtered, and the time.
    let mut acc: Vec<[f64; 9]> = Vec::new();
    for run in 0..runs {
        let plots = gimpo_plots(&truth, &radar, 0, run);
        let (g, mut track) = two_point_start(&imm, &plots, &var);
        track.reserve(plots.len());
        for (t, pl) in &plots[2..] {
            let (m, z) = conv.convert(pl, &var).unwrap();
            track.step(&imm, *t, &m, &z).unwrap();
        }
        let smoothed = track.smooth_with(weights).unwrap();
        let bound_true = rts_on_sequence(&plots, &conv, &var, g, true);
        let bound_near = rts_on_sequence(&plots, &conv, &var, g, false);
        acc.resize(smoothed.len(), [0.0; 9]);
        // The reference smoothers' steps are the track's (both start at the second plot).
        for (((s, st), a), (bt, bn)) in smoothed
            .iter()
            .zip(track.steps())
            .zip(acc.iter_mut())
            .zip(bound_true.iter().zip(&bound_near))
        {
            let x = traj.state_at(st.time()).unwrap().state_2d();
            let f = st.filtered().combined().unwrap();
            let se = |g: &Gaussian<4>| (g.mean()[0] - x[0]).powi(2) + (g.mean()[2] - x[2]).powi(2);
            a[0] += s.combined.mahalanobis_sq(&x);
            a[1] += f.mahalanobis_sq(&x);
            a[2] += se(&s.combined);
            a[3] += se(&f);
            a[4] = st.time();
            a[5] += se(bt);
            a[6] += bt.mahalanobis_sq(&x);
            a[7] += se(bn);
            a[8] += bn.mahalanobis_sq(&x);
            let sum: f64 = s.mode_probabilities.iter().sum();
            assert!(
                (sum - 1.0).abs() < 1e-9,
                "smoothed mode probabilities sum to {sum}"
            );
        }
    }
    let nr = runs as f64;
    // RMS position error over t ≥ 25 % of the track (the scenario's warm-up rule).
    let (t0, t1) = (acc[0][4], acc[acc.len() - 1][4]);
    let tail: Vec<&[f64; 9]> = acc
        .iter()
        .filter(|a| a[4] >= t0 + 0.25 * (t1 - t0))
        .collect();
    let mean = |i: usize| acc.iter().map(|a| a[i] / nr).sum::<f64>() / acc.len() as f64;
    let rms = |i: usize| (tail.iter().map(|a| a[i]).sum::<f64>() / (nr * tail.len() as f64)).sqrt();
    let (rms_s, rms_f) = (rms(2), rms(3));
    eprintln!(
        "bounds: RTS true model RMS {:.2} m (ratio {:.3}), ANEES {:.2}; RTS nearest IMM mode RMS {:.2} m (ratio {:.3}), ANEES {:.2}",
        rms(5),
        rms(5) / rms_f,
        mean(6),
        rms(7),
        rms(7) / rms_f,
        mean(8)
    );
    let ratio = rms_s / rms_f;
    // Per-step ANEES against the two-sided 99 % interval of χ²(4 · runs) / runs.
    let band = anees_interval(4, runs as usize, 0.99).unwrap();
    let inside = |i: usize| {
        acc.iter().filter(|a| band.contains(a[i] / nr)).count() as f64 / acc.len() as f64
    };
    eprintln!(
        "gimpo, {weights:?} ({runs} runs, {} steps): RMS position error smoothed {rms_s:.2} m, filtered {rms_f:.2} m, ratio {ratio:.3}; \
         ANEES mean smoothed {:.2}, filtered {:.2}; steps inside the 99 % band [{:.2}, {:.2}]: smoothed {:.0} %, filtered {:.0} %",
        acc.len(),
        mean(0),
        mean(1),
        band.lower,
        band.upper,
        100.0 * inside(0),
        100.0 * inside(1),
    );
    // ANEES on the straight legs and in the turns (the step's time inside a Table 1 turn).
    let split = |i: usize, turn: bool| {
        let sel: Vec<&[f64; 9]> = acc
            .iter()
            .filter(|a| (true_rate(a[4]) != 0.0) == turn)
            .collect();
        sel.iter().map(|a| a[i] / nr).sum::<f64>() / sel.len() as f64
    };
    eprintln!(
        "  ANEES straight / turns: smoothed {:.2} / {:.2}, filtered {:.2} / {:.2}, RTS nearest mode {:.2} / {:.2}, RTS true model {:.2} / {:.2}",
        split(0, false),
        split(0, true),
        split(1, false),
        split(1, true),
        split(8, false),
        split(8, true),
        split(6, false),
        split(6, true)
    );
    Campaign {
        ratio,
        nearest_ratio: rms(7) / rms_f,
        true_model_ratio: rms(5) / rms_f,
        anees: mean(0),
    }
}

/// The turn rate (rad/s, 0 = straight) of Table 1 at time `t`.
fn true_rate(t: f64) -> f64 {
    let mut end = 0.0;
    for &(d, w) in &SEGMENTS {
        end += d;
        if t < end {
            return w.to_radians();
        }
    }
    0.0
}

/// The RTS smoother of one Kalman filter whose model over each interval is given by the
/// truth: `exact` = the true turn rate at the interval's midpoint (σv 0.1 m/s²; a
/// smoother that knows the manoeuvres), otherwise the nearest mode of the paper's IMM (CV
/// on the straight legs, CT ±3 deg/s of the turn's sign, σv as the IMM's).
fn rts_on_sequence(
    plots: &[(f64, PolarMeasurement)],
    conv: &UnbiasedConversion<4>,
    var: &NoiseVariances,
    g: Gaussian<4>,
    exact: bool,
) -> Vec<Gaussian<4>> {
    let mut rt = RtsTrack::new(plots[1].0, g).unwrap();
    let mut prev = plots[1].0;
    for (t, pl) in &plots[2..] {
        let w = true_rate(0.5 * (prev + t));
        let model = match (exact, w == 0.0) {
            (_, true) => PlanarModel::from(Cv2D::discrete(0.1).unwrap()),
            (true, false) => PlanarModel::from(CoordinatedTurn::new(w, 0.1).unwrap()),
            (false, false) => PlanarModel::from(
                CoordinatedTurn::from_degrees_per_second(3.0_f64.copysign(w), 0.5).unwrap(),
            ),
        };
        let (m, z) = conv.convert(pl, var).unwrap();
        rt.step(&Kf::new(model), *t, &m, &z).unwrap();
        prev = *t;
    }
    rt.smooth().unwrap()
}

#[test]
fn smoothed_imm_on_the_gimpo_trajectory() {
    let bl = gimpo_campaign(PairWeights::BackwardLikelihood);
    let ec = gimpo_campaign(PairWeights::ExpectationCorrection).ratio;
    let kim = gimpo_campaign(PairWeights::Kim).ratio;
    eprintln!(
        "smoothed / filtered RMS position error: backward likelihood {:.3}, expectation correction {ec:.3}, Kim {kim:.3}; \
         RTS on the nearest IMM-mode sequence {:.3}, RTS on the true model {:.3}",
        bl.ratio, bl.nearest_ratio, bl.true_model_ratio
    );
    // What holds (measured: 0.653 for the backward-likelihood pass, 0.952 expectation
    // correction, 4.12 Kim): the smoothed error is below the filtered one and below the
    // other weightings'. The goal (≤ 0.6) is NOT met, and the smoothed ANEES (7.0)
    // is NOT inside its band; both are reported, not asserted (docs/smoothing.md). An RTS
    // smoother told the true sequence of the IMM's own modes (CV on the legs, CT ±3 deg/s
    // in the turns) reaches 0.643 (measured; asserted: the IMM smoother within 5 % of it,
    // and it above the goal) — one mode history, NOT a bound: the near-exact posterior
    // mean of the same model set reaches 0.596 on these runs
    // (`gibbs_reference_on_gimpo_convergence`). Only the true turn rates give 0.426.
    assert!(bl.ratio < 1.0, "smoothed / filtered RMS {}", bl.ratio);
    assert!(bl.ratio < ec && ec < kim, "{} vs {ec} vs {kim}", bl.ratio);
    assert!(
        bl.ratio < 1.05 * bl.nearest_ratio,
        "{} vs {}",
        bl.ratio,
        bl.nearest_ratio
    );
    assert!(bl.nearest_ratio > 0.6 && bl.true_model_ratio < 0.6);
    assert!(bl.anees.is_finite());
}

/// The Gibbs reference at one number of recorded sweeps: smoothed / filtered-IMM RMS
/// position error (both chains pooled, and each chain alone) and ANEES (all / straight /
/// turns).
#[derive(Debug)]
struct ReferencePoint {
    sweeps: usize,
    ratio: f64,
    chain_ratios: [f64; 2],
    anees: [f64; 3],
}

/// What [`gimpo_reference`] measured: the reference per checkpoint, and the IMM smoother's
/// ratio and ANEES (all / straight / turns) on the same runs.
struct Reference {
    points: Vec<ReferencePoint>,
    imm_ratio: f64,
    imm_anees: [f64; 3],
}

/// The IMM smoother's most probable mode per step, made a sequence of nonzero prior
/// (a CT+ → CT− step, π = 0, becomes CV).
fn imm_mode_sequence(s: &[argus_imm::ImmSmoothed<4, 3>], pi: &[[f64; 3]; 3]) -> Vec<usize> {
    let mut seq: Vec<usize> = s
        .iter()
        .map(|x| {
            (0..3)
                .max_by(|&a, &b| x.mode_probabilities[a].total_cmp(&x.mode_probabilities[b]))
                .unwrap()
        })
        .collect();
    for k in 1..seq.len() {
        if pi[seq[k - 1]][seq[k]] == 0.0 {
            seq[k] = 0;
        }
    }
    seq
}

/// The Gibbs smoother ([`argus_imm::smooth::gibbs`]) of seed 000's jump-Markov model — the paper
/// IMM's three models, Markov matrix, Q, the true R on the unbiased converted plots (the
/// same per-step measurement model the IMM updates with), the two-point start with μ₀
/// uniform — over `runs` runs of campaign seed `seed`; two chains per run (one from the
/// IMM smoother's most probable modes, one from all CV), `burn` sweeps discarded, then
/// estimates at each number of recorded sweeps in `checkpoints` (increasing).
fn gimpo_reference(
    seed: u64,
    runs: u64,
    block: usize,
    burn: usize,
    checkpoints: &[usize],
) -> Reference {
    let (traj, truth, radar) = gimpo_scene();
    let imm = paper_imm();
    let m = imm.markov().matrix();
    let pi: [[f64; 3]; 3] = core::array::from_fn(|i| core::array::from_fn(|j| m[(i, j)]));
    let var = NoiseVariances::from_sigmas(SIGMA_R, SIGMA_TH_DEG.to_radians()).unwrap();
    let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
    // Per step: time, Σ se filtered, Σ se IMM smoothed, Σ NEES IMM smoothed; per
    // checkpoint Σ se pooled, Σ NEES pooled, Σ se chain 0, Σ se chain 1.
    let mut common: Vec<[f64; 4]> = Vec::new();
    let mut per: Vec<Vec<[f64; 4]>> = vec![Vec::new(); checkpoints.len()];
    for run in 0..runs {
        let plots = gimpo_plots(&truth, &radar, seed, run);
        let (g, mut track) = two_point_start(&imm, &plots, &var);
        let (t2, p2) = plots[1];
        let mut times = vec![t2];
        let mut meas = vec![conv.convert(&p2, &var).unwrap()];
        for (t, pl) in &plots[2..] {
            let (mm, z) = conv.convert(pl, &var).unwrap();
            track.step(&imm, *t, &mm, &z).unwrap();
            times.push(*t);
            meas.push((mm, z));
        }
        let smoothed = track.smooth().unwrap();
        let problem = GibbsProblem::new(&imm, [1.0 / 3.0; 3], &g, &times, &meas[1..]).unwrap();
        let init = imm_mode_sequence(&smoothed, &pi);
        let mut chains = [
            GibbsChain::new(&problem, &init, 1000 * run + 1, block).unwrap(),
            GibbsChain::new(&problem, &vec![0; times.len()], 1000 * run + 2, block).unwrap(),
        ];
        let sweep = |c: &mut GibbsChain<'_, 4, 2, 3>, record| c.sweep(block, record).unwrap();
        for _ in 0..burn {
            chains.iter_mut().for_each(|c| sweep(c, false));
        }
        let truth_at: Vec<Vector<4>> = times
            .iter()
            .map(|t| traj.state_at(*t).unwrap().state_2d())
            .collect();
        let se = |g: &Gaussian<4>, x: &Vector<4>| {
            (g.mean()[0] - x[0]).powi(2) + (g.mean()[2] - x[2]).powi(2)
        };
        common.resize(times.len(), [0.0; 4]);
        for (k, (st, sm)) in track.steps().iter().zip(&smoothed).enumerate() {
            let x = &truth_at[k];
            let c = &mut common[k];
            c[0] = st.time();
            c[1] += se(&st.filtered().combined().unwrap(), x);
            c[2] += se(&sm.combined, x);
            c[3] += sm.combined.mahalanobis_sq(x);
        }
        for (ci, &target) in checkpoints.iter().enumerate() {
            while chains[0].sweeps() < target {
                chains.iter_mut().for_each(|c| sweep(c, true));
            }
            let states = |c: &[GibbsChain<'_, 4, 2, 3>]| -> Vec<Gaussian<4>> {
                pooled(c).unwrap().iter().map(|e| e.state).collect()
            };
            let (pooled, a, b) = (states(&chains), states(&chains[..1]), states(&chains[1..]));
            per[ci].resize(times.len(), [0.0; 4]);
            for k in 0..times.len() {
                let x = &truth_at[k];
                let p = &mut per[ci][k];
                p[0] += se(&pooled[k], x);
                p[1] += pooled[k].mahalanobis_sq(x);
                p[2] += se(&a[k], x);
                p[3] += se(&b[k], x);
            }
        }
    }
    let nr = runs as f64;
    let (t0, t1) = (common[0][0], common[common.len() - 1][0]);
    let tail: Vec<usize> = (0..common.len())
        .filter(|&k| common[k][0] >= t0 + 0.25 * (t1 - t0))
        .collect();
    let rms = |f: &dyn Fn(usize) -> f64| {
        (tail.iter().map(|&k| f(k)).sum::<f64>() / (nr * tail.len() as f64)).sqrt()
    };
    let anees = |f: &dyn Fn(usize) -> f64| {
        let part = |turn: Option<bool>| {
            let sel: Vec<usize> = (0..common.len())
                .filter(|&k| turn.is_none_or(|t| (true_rate(common[k][0]) != 0.0) == t))
                .collect();
            sel.iter().map(|&k| f(k) / nr).sum::<f64>() / sel.len() as f64
        };
        [part(None), part(Some(false)), part(Some(true))]
    };
    let rms_f = rms(&|k| common[k][1]);
    let points = checkpoints
        .iter()
        .enumerate()
        .map(|(ci, &sweeps)| ReferencePoint {
            sweeps,
            ratio: rms(&|k| per[ci][k][0]) / rms_f,
            chain_ratios: [
                rms(&|k| per[ci][k][2]) / rms_f,
                rms(&|k| per[ci][k][3]) / rms_f,
            ],
            anees: anees(&|k| per[ci][k][1]),
        })
        .collect::<Vec<_>>();
    let r = Reference {
        imm_ratio: rms(&|k| common[k][2]) / rms_f,
        imm_anees: anees(&|k| common[k][3]),
        points,
    };
    eprintln!(
        "gimpo, seed {seed}, {runs} runs: IMM smoother ratio {:.4}, ANEES {:.2} / {:.2} / {:.2} (all / straight / turns); filtered RMS {rms_f:.2} m",
        r.imm_ratio, r.imm_anees[0], r.imm_anees[1], r.imm_anees[2]
    );
    for p in &r.points {
        eprintln!(
            "  Gibbs reference, blocks of {block}, 2 chains × {} sweeps (burn-in {burn}): ratio {:.4} (chains {:.4} / {:.4}), ANEES {:.2} / {:.2} / {:.2}",
            p.sweeps,
            p.ratio,
            p.chain_ratios[0],
            p.chain_ratios[1],
            p.anees[0],
            p.anees[1],
            p.anees[2]
        );
    }
    r
}

#[test]
fn gibbs_reference_on_the_gimpo_trajectory() {
    // The near-exact posterior mean of seed 000's jump-Markov model (the IMM's own three
    // models, π, Q, true R, prior) against the IMM smoother on the same runs; reduced:
    // 10 runs, blocks of 4, 2 chains × 50 sweeps after 20 of burn-in (the full table,
    // 30 / 100 runs and 400–1 600 sweeps, is `gibbs_reference_on_gimpo_convergence`).
    let r = gimpo_reference(0, 10, 4, 20, &[50]);
    let p = &r.points[0];
    // Measured: reference 0.621 (chains 0.6268 / 0.6267), IMM smoother 0.660 on these
    // 10 runs; reference ANEES 7.12, turns 20.9. Asserted: (1) the two chains, started from
    // the IMM smoother's modes and from all CV, agree within 0.01 (single-site sampling
    // fails this: 0.65 against 0.76 after 1 600 sweeps on 30 runs); (2) the reference
    // beats the IMM smoother by more than 0.02 (measured 0.039 here, 0.057 on 30 runs);
    // (3) its ratio in [0.60, 0.64] (measured 0.621; the Monte Carlo spread between
    // chains is 1e-4); (4) its ANEES in the turns above the 99 % band's upper end:
    // the model set's posterior is over-confident there (docs/smoothing.md).
    eprintln!("{p:?}");
    assert!(
        (p.chain_ratios[0] - p.chain_ratios[1]).abs() < 0.01,
        "{:?}",
        p.chain_ratios
    );
    assert!(
        p.ratio < r.imm_ratio - 0.02,
        "{} vs {}",
        p.ratio,
        r.imm_ratio
    );
    assert!((0.60..0.64).contains(&p.ratio), "{}", p.ratio);
    let band = anees_interval(4, 10, 0.99).unwrap();
    assert!(p.anees[2] > band.upper, "{:?} vs {band:?}", p.anees);
}

#[test]
#[ignore = "the convergence table of docs/smoothing.md: minutes; cargo test --release -- --ignored"]
fn gibbs_reference_on_gimpo_convergence() {
    // GIBBS_GIMPO="seed runs block burn checkpoint…" runs one configuration instead.
    if let Ok(cfg) = std::env::var("GIBBS_GIMPO") {
        let v: Vec<usize> = cfg.split_whitespace().map(|x| x.parse().unwrap()).collect();
        gimpo_reference(v[0] as u64, v[1] as u64, v[2], v[3], &v[4..]);
        return;
    }
    for block in [1, 4] {
        gimpo_reference(0, 30, block, 50, &[25, 100, 400]);
    }
}

#[test]
fn bad_sequences_get_errors_naming_the_step() {
    let imm = paper_imm();
    let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0).unwrap();
    let g = Gaussian::new(Vector::<4>::zeros(), Matrix::<4, 4>::identity() * 1e4).unwrap();
    let start = ImmEstimate::from_common(g, [1.0 / 3.0; 3]).unwrap();
    let mut track = ImmTrack::new(*imm.markov(), 0.0, start).unwrap();
    track
        .step(&imm, 5.0, &pos, &Vector::<2>::new(450.0, 0.0))
        .unwrap();
    track
        .step(&imm, 10.0, &pos, &Vector::<2>::new(900.0, 0.0))
        .unwrap();
    // Time going backwards at step 3.
    let err = track
        .step(&imm, 7.0, &pos, &Vector::<2>::new(1.0, 0.0))
        .unwrap_err();
    assert_eq!(
        err,
        ImmSmoothError::Sequence(SmoothError::TimeNotIncreasing {
            step: 3,
            prev: 10.0,
            now: 7.0
        })
    );
    assert_eq!(track.smooth().unwrap_err(), err);
    assert!(err.to_string().contains("step 3"), "{err}");
    // A failed IMM step (a NaN plot) at step 3 of a fresh track.
    let mut track = ImmTrack::new(*imm.markov(), 0.0, start).unwrap();
    track
        .step(&imm, 5.0, &pos, &Vector::<2>::new(450.0, 0.0))
        .unwrap();
    track
        .step(&imm, 10.0, &pos, &Vector::<2>::new(900.0, 0.0))
        .unwrap();
    let err = track
        .step(&imm, 15.0, &pos, &Vector::<2>::new(f64::NAN, 0.0))
        .unwrap_err();
    assert!(
        matches!(err, ImmSmoothError::ForwardFailed { step: 3, .. }),
        "{err}"
    );
    assert_eq!(track.smooth().unwrap_err(), err);
    assert_eq!(track.steps().len(), 3);
    // An empty sequence.
    assert_eq!(
        argus_imm::imm_smooth::<4, 3>(imm.markov(), PairWeights::Kim, &[]).unwrap_err(),
        ImmSmoothError::Sequence(SmoothError::Empty)
    );
}
