//! `clutter`: tracking in clutter (seed 002). A 2-D constant-velocity target (with
//! white-acceleration process noise, so every filter is matched) in uniform Poisson
//! clutter with Rayleigh amplitudes; Swerling I target amplitudes at two mean SNRs with
//! the threshold set for `P_D = 0.9`. NN, NN with the HYCA gain, SN, PSN and PDA run
//! side by side on the same plots over a sweep of clutter densities. Reported per filter
//! and density: steady-state position RMSE, ANEES with its 95 % interval, track-loss
//! rate, and for NN, NN-HYCA and PDA the off-line predicted RMSE (HYCA in its
//! general-gain form for the plain NN, HYCA for NN-HYCA, the information reduction
//! factor for PDA) next to the Monte Carlo one.
//!
//! Plots are generated here (not by `argus_sim::generate_plots`) because the truth has
//! process noise, which `argus_sim::Trajectory` does not model.

use argus_association::{
    AmplitudeModel, Associator, Candidate, ClutterModel, Gate, LinearSystem, NearestNeighbour, Pda,
    PerformancePredictor, PredictedFilter, PredictionStep, Psn, SteadyState, StrongestNeighbour,
};
use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{CovarianceForm, GaussianFilter, MeasurementPrediction};
use argus_motion_models::{Cv2D, LinearMotionModel, MotionModel};
use argus_sensors::CartesianPosition;
use argus_sim::{ChaCha8Rng, Metrics, RunRecord, SensorSpec, StepRecord, Truth};
use rand_distr::{Distribution, Exp1, Poisson, StandardNormal, Uniform};

use crate::campaign::{Splittable, run_whole};
use crate::context::RunContext;
use crate::error::ScenarioError;
use crate::estimator::{CvKf, cv_kf};
use crate::params::{ParamSpec, Params};
use crate::report::Report;
use crate::scenario::Scenario;

mod report;
mod split;

use report::report;

/// The `clutter` scenario.
pub(crate) struct Clutter;

/// Clutter densities swept (plots per m²).
pub(crate) const DENSITIES: [f64; 6] = [1e-6, 1e-5, 3e-5, 1e-4, 2e-4, 4e-4];
/// Mean SNRs (dB).
pub(crate) const SNRS_DB: [f64; 2] = [10.0, 20.0];
/// Filter names, in run order.
pub(crate) const FILTERS: [&str; 5] = ["NN", "NN-HYCA", "SN", "PSN", "PDA"];

/// Everything one configuration needs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Config {
    /// Steps (scans) per run.
    pub(crate) steps: usize,
    /// Scan period (s).
    pub(crate) period: f64,
    /// Measurement σ per axis (m).
    pub(crate) sigma: f64,
    /// White-acceleration σ of truth and filters (m/s²).
    pub(crate) sigma_a: f64,
    /// Detection probability.
    pub(crate) p_d: f64,
    /// Gate threshold γ.
    pub(crate) gamma: f64,
    /// Clutter density (m⁻²).
    pub(crate) density: f64,
    /// Mean SNR (dB).
    pub(crate) snr_db: f64,
    /// Half-width of the clutter square around the target (m).
    pub(crate) half_width: f64,
    /// A track is lost when its position error exceeds this (m) ...
    pub(crate) loss_bound: f64,
    /// ... for this many consecutive scans.
    pub(crate) loss_scans: usize,
}

/// Per-filter results of one configuration.
#[derive(Debug, Clone)]
pub(crate) struct FilterResult {
    /// Metrics over the runs that kept their track (None if all were lost).
    pub(crate) metrics: Option<Metrics>,
    /// Runs that lost the track.
    pub(crate) lost: usize,
    /// Runs.
    pub(crate) runs: usize,
    /// Time-averaged ANEES over the second half of the steps (kept runs).
    pub(crate) anees: f64,
    /// Steady-state position RMSE over the second half of the steps (kept runs).
    pub(crate) rmse: f64,
    /// 95 % interval of a time-averaged ANEES over this filter's kept runs (4·kept dof,
    /// conservative).
    pub(crate) interval: (f64, f64),
}

/// Results of one configuration.
#[derive(Debug, Clone)]
pub(crate) struct ConfigResult {
    /// One per [`FILTERS`] entry.
    pub(crate) filters: Vec<FilterResult>,
    /// Predicted steady-state position RMSE of the plain NN (general-gain HYCA; None:
    /// the recursion diverges).
    pub(crate) predicted_nn: Option<f64>,
    /// HYCA-predicted steady-state position RMSE of NN-HYCA (None: diverges).
    pub(crate) predicted_hyca: Option<f64>,
    /// PDA-IRF-predicted steady-state position RMSE (None: diverges).
    pub(crate) predicted_pda: Option<f64>,
}

/// Reads one prediction from a configuration's results.
type Predicted = fn(&ConfigResult) -> Option<f64>;

fn assoc(e: argus_association::AssociationError) -> ScenarioError {
    ScenarioError::Association(e)
}

/// A distribution's parameter error.
fn distribution(what: &'static str, e: &dyn std::fmt::Display) -> ScenarioError {
    ScenarioError::Distribution {
        what,
        message: e.to_string(),
    }
}

#[allow(non_snake_case)]
fn system(c: &Config) -> Result<(Matrix<4, 4>, Matrix<4, 4>, LinearSystem<4, 2>), ScenarioError> {
    let model = Cv2D::discrete(c.sigma_a)?;
    let F = model.transition(c.period);
    let Q = model.process_noise(&Vector::<4>::zeros(), c.period);
    let H = Matrix::<2, 4>::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0);
    let R = Matrix::<2, 2>::identity() * (c.sigma * c.sigma);
    Ok((F, Q, LinearSystem::new(F, Q, H, R).map_err(assoc)?))
}

fn initial_cov(c: &Config) -> Matrix<4, 4> {
    let s2 = c.sigma * c.sigma;
    Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(s2, 100.0, s2, 100.0))
}

fn predicted_rmse(
    p: &PerformancePredictor<4, 2>,
    p0: &Matrix<4, 4>,
) -> Result<Option<f64>, ScenarioError> {
    Ok(match p.steady_state(p0, 1e-9, 20_000).map_err(assoc)? {
        SteadyState::Converged { step, .. } => {
            Some((step.posterior[(0, 0)] + step.posterior[(2, 2)]).sqrt())
        }
        SteadyState::Diverged { .. } => None,
    })
}

fn normal2(rng: &mut ChaCha8Rng) -> Vector<2> {
    Vector::<2>::new(StandardNormal.sample(rng), StandardNormal.sample(rng))
}

/// One configuration's filters, predictors and samplers, built once and shared by its
/// runs.
#[allow(non_snake_case)]
pub(crate) struct Prepared {
    c: Config,
    F: Matrix<4, 4>,
    kf: CvKf,
    R: Matrix<2, 2>,
    radar: CartesianPosition<4, 2>,
    nn: NearestNeighbour,
    sn: StrongestNeighbour,
    psn: Psn,
    pda: Pda,
    p0: Matrix<4, 4>,
    hyca: PerformancePredictor<4, 2>,
    pda_pred: PerformancePredictor<4, 2>,
    nn_pred: PerformancePredictor<4, 2>,
    hyca_steps: Vec<PredictionStep<4, 2>>,
    H: Matrix<2, 4>,
    chol_q: Matrix<4, 4>,
    chol_p0: Matrix<4, 4>,
    n_clutter: Poisson<f64>,
    unit: Uniform<f64>,
    d_lin: f64,
    tau2: f64,
}

impl Prepared {
    /// Builds configuration `c`.
    ///
    /// # Errors
    /// Invalid parameters.
    #[allow(non_snake_case)]
    pub(crate) fn new(c: &Config) -> Result<Self, ScenarioError> {
        let c = *c;
        let (F, Q, sys) = system(&c)?;
        let kf = cv_kf(c.sigma_a)?;
        let R = Matrix::<2, 2>::identity() * (c.sigma * c.sigma);
        let radar = CartesianPosition::<4, 2>::cv(R)?;
        let gate = Gate::from_threshold(c.gamma, 2).map_err(assoc)?;
        let amp = AmplitudeModel::from_detection_probability(c.snr_db, c.p_d).map_err(assoc)?;
        let nn = NearestNeighbour::new(gate);
        let sn = StrongestNeighbour::new(gate);
        let psn = Psn::new(gate, amp, c.density).map_err(assoc)?;
        let pda =
            Pda::new(gate, c.p_d, ClutterModel::Poisson { density: c.density }).map_err(assoc)?;
        let p0 = initial_cov(&c);
        let hyca = PerformancePredictor::new(
            sys,
            gate,
            c.p_d,
            c.density,
            PredictedFilter::NearestNeighbour,
        )
        .map_err(assoc)?;
        let pda_pred = PerformancePredictor::new(sys, gate, c.p_d, c.density, PredictedFilter::Pda)
            .map_err(assoc)?;
        let nn_pred = PerformancePredictor::new(
            sys,
            gate,
            c.p_d,
            c.density,
            PredictedFilter::NearestNeighbourKalmanGain,
        )
        .map_err(assoc)?;
        // The HYCA gain sequence (deterministic, the same for every run).
        let mut hyca_steps: Vec<PredictionStep<4, 2>> = Vec::with_capacity(c.steps);
        let mut p = p0;
        for _ in 0..c.steps {
            let s = hyca.step(&p).map_err(assoc)?;
            p = s.posterior;
            hyca_steps.push(s);
        }
        let H = Matrix::<2, 4>::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0);
        let chol_q = Q.cholesky().map(|ch| ch.l()).unwrap_or_else(|| {
            // DWNA Q is rank 2 per axis: use the exact square root Γσ.
            let t = c.period;
            let g = Vector::<2>::new(t * t / 2.0, t) * c.sigma_a;
            let mut l = Matrix::<4, 4>::zeros();
            l[(0, 0)] = g[0];
            l[(1, 0)] = g[1];
            l[(2, 2)] = g[0];
            l[(3, 2)] = g[1];
            l
        });
        let chol_p0 = p0
            .cholesky()
            .map(|ch| ch.l())
            .unwrap_or_else(Matrix::<4, 4>::identity);
        let n_clutter = Poisson::new(c.density * 4.0 * c.half_width * c.half_width)
            .map_err(|e| distribution("clutter count", &e))?;
        let unit = Uniform::new(-1.0, 1.0).map_err(|e| distribution("uniform", &e))?;
        let d_lin = amp.snr();
        let tau2 = amp.threshold() * amp.threshold();
        Ok(Self {
            c,
            F,
            kf,
            R,
            radar,
            nn,
            sn,
            psn,
            pda,
            p0,
            hyca,
            pda_pred,
            nn_pred,
            hyca_steps,
            H,
            chol_q,
            chol_p0,
            n_clutter,
            unit,
            d_lin,
            tau2,
        })
    }

    /// One run: the five filters' records on the same plots.
    ///
    /// # Errors
    /// A failed filter step.
    #[allow(non_snake_case)]
    pub(crate) fn one(&self, rng: &mut ChaCha8Rng) -> Result<Vec<RunRecord>, ScenarioError> {
        let Self {
            c,
            F,
            kf,
            R,
            radar,
            nn,
            sn,
            psn,
            pda,
            p0,
            hyca_steps,
            H,
            chol_q,
            chol_p0,
            n_clutter,
            unit,
            d_lin,
            tau2,
            ..
        } = self;
        let (F, R, H, p0, chol_q, chol_p0, d_lin, tau2) =
            (*F, *R, *H, *p0, *chol_q, *chol_p0, *d_lin, *tau2);
        let w4 = Vector::<4>::new(
            StandardNormal.sample(rng),
            StandardNormal.sample(rng),
            StandardNormal.sample(rng),
            StandardNormal.sample(rng),
        );
        let mut x = Vector::<4>::new(0.0, 20.0, 0.0, 10.0);
        let start = Gaussian::new(x + chol_p0 * w4, p0)?;
        let mut est = [start; 5];
        let mut recs: Vec<Vec<StepRecord>> = (0..5).map(|_| Vec::with_capacity(c.steps)).collect();
        let mut over = [0usize; 5];
        let mut lost = [false; 5];
        let mut plots: Vec<Candidate<2>> = Vec::new();
        for (k, hs) in hyca_steps.iter().enumerate() {
            let t = (k + 1) as f64 * c.period;
            let w = Vector::<4>::new(
                StandardNormal.sample(rng),
                StandardNormal.sample(rng),
                StandardNormal.sample(rng),
                StandardNormal.sample(rng),
            );
            x = F * x + chol_q * w;
            let pos = H * x;
            plots.clear();
            let u: f64 = Uniform::new(0.0, 1.0)
                .map_err(|e| distribution("uniform", &e))?
                .sample(rng);
            if u < c.p_d {
                let e: f64 = Exp1.sample(rng);
                let a = (tau2 + 2.0 * (1.0 + d_lin) * e).sqrt();
                plots.push(Candidate::with_amplitude(pos + normal2(rng) * c.sigma, a));
            }
            let m: f64 = n_clutter.sample(rng);
            for _ in 0..m as usize {
                let off = Vector::<2>::new(unit.sample(rng), unit.sample(rng)) * c.half_width;
                let e: f64 = Exp1.sample(rng);
                plots.push(Candidate::with_amplitude(
                    pos + off,
                    (tau2 + 2.0 * e).sqrt(),
                ));
            }
            for (i, e) in est.iter_mut().enumerate() {
                let pred = kf.predict(e, c.period)?;
                let post = if i == 1 {
                    // NN with the HYCA covariance and gain (Li & Bar-Shalom 1996).
                    let mp = MeasurementPrediction::new(
                        H * pred.mean(),
                        hs.s,
                        hs.predicted * H.transpose(),
                        Some(H),
                        R,
                        CovarianceForm::Standard,
                    )?;
                    let out = nn.associate(&pred, &mp, radar, &plots).map_err(assoc)?;
                    Gaussian::from_symmetrized(*out.posterior.mean(), &hs.posterior)?
                } else {
                    let mp = kf.predict_measurement(&pred, radar)?;
                    let out = match i {
                        0 => nn.associate(&pred, &mp, radar, &plots),
                        2 => sn.associate(&pred, &mp, radar, &plots),
                        3 => psn.associate(&pred, &mp, radar, &plots),
                        _ => pda.associate(&pred, &mp, radar, &plots),
                    }
                    .map_err(assoc)?;
                    out.posterior
                };
                *e = post;
                let r = StepRecord::from_estimate_2d(t, e, &x, None);
                if r.pos_err_sq.sqrt() > c.loss_bound {
                    over[i] += 1;
                    if over[i] >= c.loss_scans {
                        lost[i] = true;
                    }
                } else {
                    over[i] = 0;
                }
                if let Some(v) = recs.get_mut(i) {
                    v.push(r);
                }
            }
        }
        Ok(recs
            .into_iter()
            .zip(lost)
            .map(|(steps, lost)| RunRecord { steps, lost })
            .collect())
    }
}

/// Runs one configuration over `runs` (seeded per run from `seed`): the tests' entry.
///
/// # Errors
/// Invalid parameters, a failed filter step.
#[cfg(test)]
pub(crate) fn run_config(
    c: &Config,
    seed: u64,
    runs: std::ops::Range<u64>,
    tick: &(dyn Fn() + Sync),
) -> Result<ConfigResult, ScenarioError> {
    let prep = Prepared::new(c)?;
    let all = argus_sim::monte_carlo(seed, runs, |_, rng| prep.one(rng), tick)?;
    let mut sums = split::ConfigSums::new();
    for r in &all {
        sums.add(&prep, r);
    }
    split::result(&prep, &sums)
}

/// The configuration for density `density` and SNR `snr_db` from the parameters.
///
/// # Errors
/// An undeclared parameter.
pub(crate) fn config(p: &Params, density: f64, snr_db: f64) -> Result<Config, ScenarioError> {
    Ok(Config {
        steps: p.get("steps")? as usize,
        period: p.get("period")?,
        sigma: p.get("sigma")?,
        sigma_a: p.get("sigma_a")?,
        p_d: p.get("p_d")?,
        gamma: p.get("gamma")?,
        density,
        snr_db,
        half_width: p.get("half_width")?,
        loss_bound: p.get("loss_bound")?,
        loss_scans: p.get("loss_scans")? as usize,
    })
}

impl Scenario for Clutter {
    fn name(&self) -> &'static str {
        "clutter"
    }

    fn description(&self) -> &'static str {
        "seed 002: NN, NN-HYCA, SN, PSN, PDA in Poisson clutter with Rayleigh amplitudes; off-line prediction vs Monte Carlo"
    }

    fn default_runs(&self) -> u64 {
        200
    }

    fn params(&self) -> Vec<ParamSpec> {
        vec![
            ParamSpec::new("steps", 100.0, 10.0, 10_000.0, "scans per run"),
            ParamSpec::new("period", 1.0, 1e-3, 100.0, "scan period (s)"),
            ParamSpec::new("sigma", 20.0, 1e-3, 1e4, "position noise σ per axis (m)"),
            ParamSpec::new(
                "sigma_a",
                1.0,
                0.0,
                100.0,
                "white-acceleration σ of truth and filters (m/s²)",
            ),
            ParamSpec::new(
                "p_d",
                0.9,
                0.05,
                1.0,
                "detection probability (sets the threshold per SNR)",
            ),
            ParamSpec::new("gamma", 16.0, 1.0, 40.0, "gate threshold γ on νᵀS⁻¹ν"),
            ParamSpec::new(
                "half_width",
                600.0,
                10.0,
                1e5,
                "half-width of the clutter square around the target (m)",
            ),
            ParamSpec::new(
                "loss_bound",
                150.0,
                1.0,
                1e6,
                "track lost when position error exceeds this (m) ...",
            ),
            ParamSpec::new(
                "loss_scans",
                5.0,
                1.0,
                1000.0,
                "... for this many consecutive scans",
            ),
        ]
    }

    fn scene(&self, _p: &Params) -> Result<(Truth, Vec<SensorSpec>), ScenarioError> {
        Err(ScenarioError::NoScene {
            scenario: "clutter",
            reason: "the truth has process noise and is drawn per run; no fixed scene to export",
        })
    }

    #[allow(clippy::too_many_lines)]
    fn run(&self, ctx: &RunContext<'_>) -> Result<Report, ScenarioError> {
        run_whole(self, ctx)
    }

    fn splittable(&self) -> Option<&dyn Splittable> {
        Some(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use argus_core_math::anees_interval;

    fn reduced(density: f64, snr_db: f64) -> Config {
        Config {
            steps: 60,
            period: 1.0,
            sigma: 20.0,
            sigma_a: 1.0,
            p_d: 0.9,
            gamma: 16.0,
            density,
            snr_db,
            half_width: 600.0,
            loss_bound: 150.0,
            loss_scans: 5,
        }
    }

    #[test]
    fn clutter_claims_on_reduced_runs() {
        // Moderate clutter (λ = 3e-5 m⁻², about one clutter plot per gate), 10 dB,
        // 150 runs × 60 scans, seed 11. Claims of issue 5 / seed 002.
        let r = run_config(&reduced(3e-5, 10.0), 11, 0..150, &|| {}).unwrap();
        let f = |i: usize| r.filters.get(i).unwrap();
        eprintln!(
            "{:?}; pred NN {:?} PDA {:?}",
            r.filters
                .iter()
                .map(|f| (f.rmse, f.anees, f.lost, f.interval))
                .collect::<Vec<_>>(),
            r.predicted_nn,
            r.predicted_pda
        );
        // PDA and PSN consistent: ANEES inside the 95 % interval of their own kept runs.
        let inside = |i: usize| f(i).interval.0 <= f(i).anees && f(i).anees <= f(i).interval.1;
        assert!(inside(4), "PDA ANEES {} in {:?}", f(4).anees, f(4).interval);
        assert!(inside(3), "PSN ANEES {} in {:?}", f(3).anees, f(3).interval);
        // SN over-confident: ANEES above its interval.
        assert!(f(2).anees > f(2).interval.1, "SN ANEES {}", f(2).anees);
        // Each interval is that of the filter's own kept-run count (issue 17 §3).
        for fi in &r.filters {
            let kept = (fi.runs - fi.lost).max(1);
            let iv = anees_interval(4, kept, 0.95).unwrap();
            assert_eq!(fi.interval, (iv.lower, iv.upper));
        }
    }

    #[test]
    fn predicted_rmse_matches_monte_carlo_where_tracks_survive() {
        // λ = 1e-5 m⁻² (≈ 0.3 clutter plots per gate), 10 dB, 150 runs × 60 scans, seed 12:
        // the plain NN (general-gain HYCA with its Kalman gain), NN-HYCA (HYCA, its own
        // gain) and PDA (information reduction factor) predictions within 15 % of the
        // Monte Carlo steady-state RMSE, where fewer than 5 % of tracks are lost (issue 5).
        let r = run_config(&reduced(1e-5, 10.0), 12, 0..150, &|| {}).unwrap();
        let f = |i: usize| r.filters.get(i).unwrap();
        eprintln!(
            "{:?}; pred NN {:?} HYCA {:?} PDA {:?}",
            r.filters
                .iter()
                .map(|f| (f.rmse, f.anees, f.lost))
                .collect::<Vec<_>>(),
            r.predicted_nn,
            r.predicted_hyca,
            r.predicted_pda
        );
        for (i, pred) in [
            (0, r.predicted_nn),
            (1, r.predicted_hyca),
            (4, r.predicted_pda),
        ] {
            assert!(f(i).lost * 20 < f(i).runs, "filter {i} lost {}", f(i).lost);
            let pred = pred.unwrap();
            assert!(
                (pred / f(i).rmse - 1.0).abs() < 0.15,
                "filter {i}: {pred} vs {}",
                f(i).rmse
            );
        }
        // Where the HYCA recursion diverges (λ = 3e-5) it must say so.
        let r = run_config(&reduced(3e-5, 10.0), 13, 0..20, &|| {}).unwrap();
        assert!(r.predicted_hyca.is_none());
    }
}
