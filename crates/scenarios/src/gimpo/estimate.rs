//! gimpo's estimators and one run: the paper's IMM with fixed R, its multi-IMM noise
//! estimator, and the variational, evidence and difference estimators of `argus-imm`,
//! each from every start factor.

use argus_core_math::{Gaussian, Vector};
use argus_filters::{Kf, two_point_cv2};
use argus_imm::smooth::gibbs::{GibbsConfig, GibbsProblem, gibbs_smooth};
use argus_imm::{
    DifferenceEstimate, DifferenceNoiseImm, EvidenceEstimate, EvidenceNoiseImm, Imm, ImmEstimate,
    ImmTrack, MarkovMatrix, MultiImm, MultiImmEstimate, NoiseGrid, NoiseVariances, PlotConversion,
    UnbiasedConversion, VariationalEstimate, VariationalNoiseImm,
};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use argus_sensors::{Measurement, PolarMeasurement};
use argus_sim::{SensorSpec, Trajectory, Truth, generate_plots};

use crate::error::ScenarioError;
use crate::params::Params;

/// Initial (or fixed) noise factors of the paper: R = f × truth.
pub(super) const STARTS: [f64; 5] = [0.2, 0.5, 1.0, 1.5, 2.0];
/// The paper's IMM: CV and CT ±ω, Kalman filters on the planar models.
pub(super) type PaperImm = Imm<Kf<PlanarModel>, 4, 3>;

/// The paper's IMM (§3.1): CV σv = 0.1 m/s², CT ±ω σv = 0.5 m/s², Markov matrix eq (20).
pub(super) fn paper_imm(omega_deg: f64) -> Result<PaperImm, ScenarioError> {
    let ct = |w: f64| -> Result<Kf<PlanarModel>, ScenarioError> {
        Ok(Kf::new(PlanarModel::from(
            CoordinatedTurn::from_degrees_per_second(w, 0.5)?,
        )))
    };
    let cv = Kf::new(PlanarModel::from(Cv2D::discrete(0.1)?));
    let pi = MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]])?;
    Ok(Imm::new([cv, ct(omega_deg)?, ct(-omega_deg)?], pi)?)
}

/// Everything one run records, per step after the two initialising plots: the per-run
/// record of a split campaign (one JSON line).
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub(crate) struct RunOut {
    /// Squared position error of the fixed-R IMM, per start factor.
    pub(super) fixed_se: [Vec<f64>; 5],
    /// Mode probabilities (CV, CT+, CT−) of the IMM with the true R.
    pub(super) mu: Vec<[f64; 3]>,
    /// Squared position error of the fixed-interval smoothed IMM with the true R
    /// (argus_imm's forward–backward smoother, default pair weights), per step.
    pub(super) smooth_se: Vec<f64>,
    /// Its NEES of `[x, vx, y, vy]` against the truth, per step.
    pub(super) smooth_nees: Vec<f64>,
    /// Squared position error of the same IMM's plots smoothed by the Gibbs smoother
    /// (the jump-Markov model's posterior mean), per step.
    pub(super) gibbs_se: Vec<f64>,
    /// Its NEES against the truth, per step.
    pub(super) gibbs_nees: Vec<f64>,
    /// Paper's multi-IMM: squared error and variance ratio, per start.
    pub(super) multi_se: [Vec<f64>; 5],
    pub(super) multi_ratio: [Vec<f64>; 5],
    /// Variational estimator: squared error and (range, azimuth) ratios, per start.
    pub(super) vb_se: [Vec<f64>; 5],
    pub(super) vb_ratio: [Vec<[f64; 2]>; 5],
    /// Evidence estimator: squared error and (range, azimuth) ratios, per start.
    pub(super) ev_se: [Vec<f64>; 5],
    pub(super) ev_ratio: [Vec<[f64; 2]>; 5],
    /// Difference estimator: squared error and (range, azimuth) ratios, per start.
    pub(super) df_se: [Vec<f64>; 5],
    pub(super) df_ratio: [Vec<[f64; 2]>; 5],
    /// Run 0 only: truth, converted plots and the multi-IMM (start 1) estimate.
    pub(super) track: Vec<[f64; 6]>,
}

/// One run's polar plots in time order.
///
/// # Errors
/// The simulation's error.
pub(super) fn simulate(
    truth: &Truth,
    sensors: &[SensorSpec],
    rng: &mut argus_sim::ChaCha8Rng,
) -> Result<Vec<(f64, PolarMeasurement)>, ScenarioError> {
    Ok(generate_plots(truth, sensors, rng)?
        .iter()
        .filter_map(|pl| match pl.plot.measurement() {
            Measurement::Polar(m) => Some((pl.plot.time(), *m)),
            _ => None,
        })
        .collect())
}

/// Squared position error of `[x, vx, y, vy]` against the truth.
fn se(x: &Vector<4>, tr: &Vector<4>) -> f64 {
    (x[0] - tr[0]).powi(2) + (x[2] - tr[2]).powi(2)
}

/// One run's plots and truth, as the estimators read them.
struct RunInput<'a> {
    traj: &'a Trajectory,
    first: &'a (f64, PolarMeasurement),
    second: &'a (f64, PolarMeasurement),
    /// Time of the second plot, where the estimators start.
    t2: f64,
    /// The plots after the two initialising ones.
    rest: &'a [(f64, PolarMeasurement)],
}

/// The modes' prior at the start: equally likely.
const MU0: [f64; 3] = [1.0 / 3.0; 3];

/// Distinguishes the Gibbs smoother's generator from the plots' (`run_rng(seed, run)`).
const GIBBS_SALT: u64 = 0x6769_6262_735f_7331;

/// The Gibbs chain's seed of run `run` in a campaign of seed `seed`: a function of the
/// two only, so that a run smooths the same whatever the threads or shards.
fn gibbs_seed(seed: u64, run: u64) -> u64 {
    use rand::Rng;
    argus_sim::run_rng(seed ^ GIBBS_SALT, run).next_u64()
}

impl RunInput<'_> {
    /// The two-point start (at the second plot) under the noise variances `var`.
    fn start(&self, var: &NoiseVariances) -> Result<Gaussian<4>, ScenarioError> {
        let ((t1, p1), (t2, p2)) = (self.first, self.second);
        let (z1, r1) = argus_imm::unbiased_conversion(p1, var)?;
        let (z2, r2) = argus_imm::unbiased_conversion(p2, var)?;
        Ok(two_point_cv2(&z1, &r1, &z2, &r2, t2 - t1)?)
    }

    /// The two-point start under the noise variances `var`, modes equally likely.
    fn init(&self, var: &NoiseVariances) -> Result<ImmEstimate<4, 3>, ScenarioError> {
        Ok(ImmEstimate::from_common(self.start(var)?, MU0)?)
    }

    /// The true `[x, vx, y, vy]` at `t`.
    fn truth_pos(&self, t: f64) -> Result<Vector<4>, ScenarioError> {
        Ok(self.traj.state_at(t)?.state_2d())
    }

    /// Steps an estimate from `first` (at the second plot) along the plots after the two
    /// initialising ones: `advance(estimate, dt, t, plot)` returns the estimate at the
    /// plot's time `t`, `dt` after the one before, and records what the caller keeps.
    fn walk<E>(
        &self,
        first: E,
        mut advance: impl FnMut(&E, f64, f64, &PolarMeasurement) -> Result<E, ScenarioError>,
    ) -> Result<(), ScenarioError> {
        let mut est = first;
        let mut prev = self.t2;
        for (t, pl) in self.rest {
            est = advance(&est, t - prev, *t, pl)?;
            prev = *t;
        }
        Ok(())
    }
}

/// The estimators of the campaign, built once from the parameters.
pub(crate) struct Estimators {
    true_var: NoiseVariances,
    imm: PaperImm,
    multi: MultiImm<Kf<PlanarModel>, 4, 3, 5>,
    vb: VariationalNoiseImm<Kf<PlanarModel>, 4, 3>,
    ev: EvidenceNoiseImm<Kf<PlanarModel>, 4, 3>,
    df: DifferenceNoiseImm<Kf<PlanarModel>, 4, 3>,
    conv: UnbiasedConversion<4>,
    /// The Gibbs smoother's block, burn-in and recorded sweeps (the seed is the run's).
    gibbs: GibbsConfig,
    /// The multi-IMM's clip of the reference change per step.
    pub(super) clip: Option<f64>,
}

impl Estimators {
    /// The estimators of the parameters `p`.
    ///
    /// # Errors
    /// A parameter the models or estimators refuse.
    pub(super) fn new(p: &Params) -> Result<Self, ScenarioError> {
        let true_var =
            NoiseVariances::from_sigmas(p.get("sigma_r")?, p.get("sigma_az_deg")?.to_radians())?;
        let imm = paper_imm(p.get("omega_deg")?)?;
        let clip = match p.get("clip")? {
            c if c > 0.0 => Some(c),
            _ => None,
        };
        let multi = MultiImm::new(imm.clone(), NoiseGrid::<5>::common(p.get("p")?)?, clip)?;
        let vb = VariationalNoiseImm::new(imm.clone(), p.get("vb_rho")?)?;
        let ev = EvidenceNoiseImm::new(
            imm.clone(),
            p.get("ev_spacing")?,
            p.get("ev_rho")?,
            match p.get("ev_clip")? {
                c if c > 0.0 => Some(c),
                _ => None,
            },
        )?;
        let ev = match p.get("ev_settle")? {
            k if k >= 1.0 => ev.with_post_fit(k.round() as usize),
            _ => ev,
        };
        let ev = if p.get("ev_observed")? >= 0.5 {
            ev.with_observed_information()
        } else {
            ev
        };
        let df = DifferenceNoiseImm::new(imm.clone(), p.get("df_rho")?)?;
        let count = |key: &str| -> Result<usize, ScenarioError> {
            // Declared with integer bounds ≥ 0: the rounded value is the count.
            Ok(p.get(key)?.round() as usize)
        };
        let gibbs = GibbsConfig {
            block: count("gibbs_block")?,
            burn_in: count("gibbs_burn_in")?,
            sweeps: count("gibbs_sweeps")?,
            seed: 0,
        };
        gibbs.validate(3).map_err(|e| ScenarioError::Degenerate {
            scenario: "gimpo",
            message: e.to_string(),
        })?;
        Ok(Self {
            true_var,
            imm,
            multi,
            vb,
            ev,
            df,
            conv: UnbiasedConversion::<4>::new(0, 2)?,
            gibbs,
            clip,
        })
    }

    /// Every estimator from every start over one run's `plots` of the trajectory `traj`
    /// (run `run` of a campaign of seed `seed`).
    ///
    /// # Errors
    /// [`ScenarioError::Degenerate`] for fewer than two plots, else the estimators' errors.
    pub(super) fn run(
        &self,
        traj: &Trajectory,
        seed: u64,
        run: u64,
        plots: &[(f64, PolarMeasurement)],
    ) -> Result<RunOut, ScenarioError> {
        let (Some(first), Some(second)) = (plots.first(), plots.get(1)) else {
            return Err(ScenarioError::Degenerate {
                scenario: "gimpo",
                message: "fewer than two plots".into(),
            });
        };
        let inp = RunInput {
            traj,
            first,
            second,
            t2: second.0,
            rest: plots.get(2..).unwrap_or(&[]),
        };
        let mut out = RunOut::default();
        for (i, f) in STARTS.iter().enumerate() {
            let var0 = NoiseVariances::new(self.true_var.range() * f, self.true_var.azimuth() * f)?;
            self.fixed(&inp, i, var0, &mut out)?;
            if i == 2 {
                self.smoothed(&inp, var0, seed, run, &mut out)?;
            }
            self.multi(&inp, i, var0, run, &mut out)?;
            self.variational(&inp, i, var0, &mut out)?;
            self.evidence(&inp, i, var0, &mut out)?;
            self.difference(&inp, i, var0, &mut out)?;
        }
        Ok(out)
    }

    /// (a) The IMM with R fixed at `var0`.
    fn fixed(
        &self,
        inp: &RunInput<'_>,
        i: usize,
        var0: NoiseVariances,
        out: &mut RunOut,
    ) -> Result<(), ScenarioError> {
        inp.walk(inp.init(&var0)?, |est, dt, t, pl| {
            let (m, z) = self.conv.convert(pl, &var0)?;
            let est = self.imm.step(est, dt, &m, &z)?.estimate;
            let c = est.combined()?;
            out.fixed_se[i].push(se(c.mean(), &inp.truth_pos(t)?));
            if i == 2 {
                out.mu.push(est.mode_probabilities());
            }
            Ok(est)
        })
    }

    /// The IMM with the true R recorded and smoothed over the whole run (issue 19): the
    /// same forward steps as [`Self::fixed`], then the IMM's fixed-interval backward pass,
    /// and the same plots smoothed by the Gibbs smoother of the IMM's jump-Markov model
    /// (its chain started from the IMM smoother's most probable modes, seeded from the
    /// run).
    fn smoothed(
        &self,
        inp: &RunInput<'_>,
        var0: NoiseVariances,
        seed: u64,
        run: u64,
        out: &mut RunOut,
    ) -> Result<(), ScenarioError> {
        let start = inp.start(&var0)?;
        let mut track = ImmTrack::new(
            *self.imm.markov(),
            inp.t2,
            ImmEstimate::from_common(start, MU0)?,
        )?;
        track.reserve(inp.rest.len());
        let mut times = Vec::with_capacity(inp.rest.len() + 1);
        times.push(inp.t2);
        let mut meas = Vec::with_capacity(inp.rest.len());
        for (t, pl) in inp.rest {
            let (m, z) = self.conv.convert(pl, &var0)?;
            track.step(&self.imm, *t, &m, &z)?;
            times.push(*t);
            meas.push((m, z));
        }
        let smoothed = track.smooth()?;
        let truth = times
            .iter()
            .map(|t| inp.truth_pos(*t))
            .collect::<Result<Vec<_>, _>>()?;
        // The first recorded step is the start (at the second plot): skip it, as fixed_se does.
        for (s, tr) in smoothed.iter().zip(&truth).skip(1) {
            out.smooth_se.push(se(s.combined.mean(), tr));
            out.smooth_nees.push(s.combined.mahalanobis_sq(tr));
        }
        let problem = GibbsProblem::new(&self.imm, MU0, &start, &times, &meas)?;
        let init = problem.most_probable_sequence(smoothed.iter().map(|s| s.mode_probabilities))?;
        let config = GibbsConfig {
            seed: gibbs_seed(seed, run),
            ..self.gibbs
        };
        let posterior = gibbs_smooth(&problem, &config, Some(&init))?;
        for (s, tr) in posterior.iter().zip(&truth).skip(1) {
            out.gibbs_se.push(se(s.state.mean(), tr));
            out.gibbs_nees.push(s.state.mahalanobis_sq(tr));
        }
        Ok(())
    }

    /// (b) The paper's multi-IMM from `var0` (run 0, start 1: also the track of Fig. 3).
    fn multi(
        &self,
        inp: &RunInput<'_>,
        i: usize,
        var0: NoiseVariances,
        run: u64,
        out: &mut RunOut,
    ) -> Result<(), ScenarioError> {
        let first = MultiImmEstimate::new(inp.init(&var0)?, var0);
        inp.walk(first, |mest, dt, t, pl| {
            let mest = self.multi.step(mest, dt, pl, &self.conv)?.estimate;
            let c = mest.combined()?;
            let tr = inp.truth_pos(t)?;
            out.multi_se[i].push(se(c.mean(), &tr));
            out.multi_ratio[i].push(mest.reference().range() / self.true_var.range());
            if i == 2 && run == 0 {
                let (z, _) = argus_imm::unbiased_conversion(pl, mest.reference())?;
                out.track
                    .push([tr[0], tr[2], z[0], z[1], c.mean()[0], c.mean()[2]]);
            }
            Ok(mest)
        })
    }

    /// Estimated over true variances: `[range, azimuth]`.
    fn ratios(&self, v: &NoiseVariances) -> [f64; 2] {
        [
            v.range() / self.true_var.range(),
            v.azimuth() / self.true_var.azimuth(),
        ]
    }

    /// The variational estimator from `var0`.
    fn variational(
        &self,
        inp: &RunInput<'_>,
        i: usize,
        var0: NoiseVariances,
        out: &mut RunOut,
    ) -> Result<(), ScenarioError> {
        let first = VariationalEstimate::new(inp.init(&var0)?, var0, 2.0)?;
        inp.walk(first, |vest, dt, t, pl| {
            let vest = self.vb.step(vest, dt, pl, &self.conv)?.0;
            let c = vest.imm().combined()?;
            out.vb_se[i].push(se(c.mean(), &inp.truth_pos(t)?));
            out.vb_ratio[i].push(self.ratios(&vest.variances()?));
            Ok(vest)
        })
    }

    /// The evidence estimator from `var0`.
    fn evidence(
        &self,
        inp: &RunInput<'_>,
        i: usize,
        var0: NoiseVariances,
        out: &mut RunOut,
    ) -> Result<(), ScenarioError> {
        let first = EvidenceEstimate::new(inp.init(&var0)?, var0, 2.0)?;
        inp.walk(first, |eest, dt, t, pl| {
            let eest = self.ev.step(eest, dt, pl, &self.conv)?;
            let c = eest.combined()?;
            out.ev_se[i].push(se(c.mean(), &inp.truth_pos(t)?));
            out.ev_ratio[i].push(self.ratios(eest.variances()));
            Ok(eest)
        })
    }

    /// The difference estimator from `var0`.
    fn difference(
        &self,
        inp: &RunInput<'_>,
        i: usize,
        var0: NoiseVariances,
        out: &mut RunOut,
    ) -> Result<(), ScenarioError> {
        let first = DifferenceEstimate::new(inp.init(&var0)?, var0, 2.0)?;
        inp.walk(first, |dest, dt, t, pl| {
            let dest = self.df.step(dest, dt, pl, &self.conv)?.0;
            let c = dest.imm().combined()?;
            out.df_se[i].push(se(c.mean(), &inp.truth_pos(t)?));
            out.df_ratio[i].push(self.ratios(&dest.variances()?));
            Ok(dest)
        })
    }
}
