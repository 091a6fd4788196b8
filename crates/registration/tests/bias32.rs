//! Reduced Monte Carlo of the bias-32 scenario (SPEC §004; full 100 runs via `argus run
//! bias-32`), checked against the *derived* accuracy of the proposed estimator.
//!
//! The proposed estimator is linear in the noise once its gains are fixed, so the first
//! and second moments of its final bias error follow exactly from the gains of a
//! noise-free (nominal) run: [`covariance_analysis`] propagates the mean and covariance of
//! the joint error `[b̂ − b; X̂ᵇ_{s,t} − G_{s,t} β − X_t]` (8 + 2·32·4 = 264 components)
//! through every pseudo-measurement update (eqs (33)–(35), `e_b ← (I − K_b H_b) e_b +
//! K_b (w_i − H Φ e_j)`) and every local update (`e_i ← (I − K_i H) Φ e_i + K_i w_i`), with
//! the plot noise `w_i` shared by both. This is the estimator's true accuracy, unlike its
//! own covariance `Σ`, which ignores the correlation between successive pseudo-measurements.

#![allow(clippy::unwrap_used)] // test code: a failure should panic with its message
#![allow(non_snake_case)] // the papers' matrix names

use argus_core_math::{Gaussian, Matrix, Vector, chi2_quantile};
use argus_registration::simulation::{RunRecord, ScenarioConfig, Summary, run};
use argus_registration::{
    BiasEstimator, BiasedLocalFilter, BiasedTrack, Initiation, Linearization, position_matrix,
    pseudo_measurement,
};
use nalgebra::{DMatrix, DVector};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

fn monte_carlo(cfg: &ScenarioConfig, runs: u64) -> (Vec<RunRecord>, Summary) {
    let recs: Vec<RunRecord> = (0..runs)
        .map(|k| {
            let mut rng = ChaCha8Rng::seed_from_u64(2011 + k);
            run(cfg, &mut || StandardNormal.sample(&mut rng)).unwrap()
        })
        .collect();
    let s = Summary::from_runs(&recs, cfg.sensors.len()).unwrap();
    (recs, s)
}

fn dyn_of(m: argus_core_math::faer::MatRef<'_, f64>) -> DMatrix<f64> {
    DMatrix::from_fn(m.nrows(), m.ncols(), |i, j| m[(i, j)])
}

/// The derived moments of the proposed estimator's final stacked bias error.
struct Moments {
    /// Mean of `b̂ − b` (from the deterministic true bias and the prior mean 0).
    mean: DVector<f64>,
    /// Covariance of `b̂ − b` over the noise and the initial track errors.
    cov: DMatrix<f64>,
    /// The estimator's own final covariance `Σ` on the nominal run.
    claimed: DMatrix<f64>,
    /// Pseudo-measurement updates on the nominal run.
    updates: usize,
}

impl Moments {
    /// Expected squared error of component `k`, averaged over sensors.
    fn mse(&self, k: usize) -> f64 {
        let s = self.mean.len() / 4;
        (0..s)
            .map(|i| self.mean[4 * i + k].powi(2) + self.cov[(4 * i + k, 4 * i + k)])
            .sum::<f64>()
            / s as f64
    }

    /// Standard deviation of the Monte Carlo estimate of [`Self::mse`] over `runs` runs:
    /// `Var(Σ_s e_s²) = Σ_{s,t} (2 C_st² + 4 m_s m_t C_st)` for Gaussian `e`.
    fn mse_sd(&self, k: usize, runs: u64) -> f64 {
        let s = self.mean.len() / 4;
        let mut v = 0.0;
        for a in 0..s {
            for b in 0..s {
                let (i, j) = (4 * a + k, 4 * b + k);
                let c = self.cov[(i, j)];
                v += 2.0 * c * c + 4.0 * self.mean[i] * self.mean[j] * c;
            }
        }
        (v / runs as f64).sqrt() / s as f64
    }
}

/// Moments of the final bias error of the proposed method on `cfg` (bias-free starts,
/// linearisation at the prediction), from the gains of a noise-free run (see module docs).
fn covariance_analysis(cfg: &ScenarioConfig) -> Moments {
    assert_eq!(cfg.initiation, Initiation::Given);
    assert_eq!(cfg.linearization, Linearization::AtPrediction);
    let (ns, nt) = (cfg.sensors.len(), cfg.targets.len());
    let nb = 4 * ns;
    let dim = nb + 4 * ns * nt;
    let trk = |s: usize, t: usize| nb + 4 * (t * ns + s);
    let filter = BiasedLocalFilter::new(cfg.q_tilde).unwrap();
    let H = position_matrix();
    let mut est = BiasEstimator::new(ns, &cfg.prior_cov).unwrap();
    let mut tracks: Vec<BiasedTrack> = (0..ns * nt)
        .map(|k| {
            let x = cfg.truth(k % nt, 0.0);
            BiasedTrack::bias_free(Gaussian::new(x, cfg.init_cov).unwrap(), 0.0).unwrap()
        })
        .collect();
    let truth_b = cfg.true_stacked_bias();
    let mut m = DVector::<f64>::zeros(dim);
    for (i, b) in truth_b.iter().enumerate() {
        m[i] = -b;
    }
    let mut c = DMatrix::<f64>::zeros(dim, dim);
    for s in 0..ns {
        for t in 0..nt {
            let o = trk(s, t);
            for a in 0..4 {
                for b in 0..4 {
                    c[(o + a, o + b)] = cfg.init_cov[(a, b)];
                }
            }
        }
    }
    for (time, i) in cfg.events() {
        let setup = &cfg.sensors[i];
        for t in 0..nt {
            let x = cfg.truth(t, time);
            let p = Vector::<2>::new(x[0], x[2]);
            let own = tracks[i * nt + t];
            let pred = filter.predict(&own, time).unwrap();
            let at = H * pred.estimate().mean();
            let plot = setup.sensor.biased_plot(&p, &setup.bias, 0.0, 0.0).unwrap();
            let conv = setup.sensor.convert(time, &plot, Some(&at)).unwrap();
            // The local gain and the actual plot noise (at the true position).
            let P = pred.estimate().cov();
            let S = H * P * H.transpose() + conv.noise();
            let Ki: Matrix<4, 2> = P * H.transpose() * S.try_inverse().unwrap();
            let Fi = (Matrix::<4, 4>::identity() - Ki * H) * filter.transition(time - own.time());
            let w = setup
                .sensor
                .convert(time, &setup.sensor.polar_of(&p).unwrap(), None)
                .unwrap();
            let Rw = *w.noise();
            // The pseudo-measurement against the other sensors' tracks and the bias gain.
            let others: Vec<(usize, &BiasedTrack)> = (0..ns)
                .filter(|&j| j != i)
                .map(|j| (j, &tracks[j * nt + t]))
                .collect();
            let pm = pseudo_measurement(&filter, ns, i, &conv, &others).unwrap();
            let (Hb, Rb, Sig) = (dyn_of(pm.h()), dyn_of(pm.r()), dyn_of(est.covariance()));
            let Kb =
                &Sig * Hb.transpose() * (&Hb * &Sig * Hb.transpose() + Rb).try_inverse().unwrap();
            // T on the changed rows U = [bias, own track] over the columns V = [U, other tracks].
            let mut cols: Vec<usize> = (0..nb).chain(trk(i, t)..trk(i, t) + 4).collect();
            let nu = cols.len();
            for &(j, _) in &others {
                cols.extend(trk(j, t)..trk(j, t) + 4);
            }
            let mut T = DMatrix::<f64>::zeros(nu, cols.len());
            let A = DMatrix::<f64>::identity(nb, nb) - &Kb * &Hb;
            T.view_mut((0, 0), (nb, nb)).copy_from(&A);
            for (k, &(_, tr)) in others.iter().enumerate() {
                let hp = H * filter.transition(time - tr.time());
                let hp = DMatrix::from_fn(2, 4, |a, b| hp[(a, b)]);
                let blk = -Kb.columns(2 * k, 2) * hp;
                T.view_mut((0, nu + 4 * k), (nb, 4)).copy_from(&blk);
            }
            for a in 0..4 {
                for b in 0..4 {
                    T[(nb + a, nb + b)] = Fi[(a, b)];
                }
            }
            // Noise loading of the shared plot noise w_i.
            let mut W = DMatrix::<f64>::zeros(nu, 2);
            for k in 0..others.len() {
                W.view_mut((0, 0), (nb, 2))
                    .add_assign_from(&Kb.columns(2 * k, 2));
            }
            for a in 0..4 {
                for b in 0..2 {
                    W[(nb + a, b)] = Ki[(a, b)];
                }
            }
            let Rw = DMatrix::from_fn(2, 2, |a, b| Rw[(a, b)]);
            // C' = T C Tᵀ + W R Wᵀ on the changed rows; m' = T m.
            let cv = DMatrix::from_fn(cols.len(), dim, |a, b| c[(cols[a], b)]);
            let X = &T * cv; // nu × dim
            let XV = DMatrix::from_fn(nu, cols.len(), |a, b| X[(a, cols[b])]);
            let cuu = &XV * T.transpose() + &W * Rw * W.transpose();
            let mv = DVector::from_fn(cols.len(), |a, _| m[cols[a]]);
            let mu = &T * mv;
            for a in 0..nu {
                for b in 0..dim {
                    c[(cols[a], b)] = X[(a, b)];
                    c[(b, cols[a])] = X[(a, b)];
                }
            }
            for a in 0..nu {
                for b in 0..nu {
                    c[(cols[a], cols[b])] = 0.5 * (cuu[(a, b)] + cuu[(b, a)]);
                }
                m[cols[a]] = mu[a];
            }
            est.update(&pm).unwrap();
            tracks[i * nt + t] = filter.update(&own, &conv).unwrap();
        }
    }
    Moments {
        mean: m.rows(0, nb).into_owned(),
        cov: c.view((0, 0), (nb, nb)).into_owned(),
        claimed: dyn_of(est.covariance()),
        updates: est.updates(),
    }
}

/// Trait shim: `add_assign` on a matrix view from another view.
trait AddAssignFrom {
    fn add_assign_from(&mut self, other: &nalgebra::DMatrixView<'_, f64>);
}
impl AddAssignFrom for nalgebra::DMatrixViewMut<'_, f64> {
    fn add_assign_from(&mut self, other: &nalgebra::DMatrixView<'_, f64>) {
        for i in 0..self.nrows() {
            for j in 0..self.ncols() {
                self[(i, j)] += other[(i, j)];
            }
        }
    }
}

#[test]
fn bias32_matches_its_derived_accuracy() {
    let runs = 20;
    let mut cfg = ScenarioConfig::bias32().unwrap();
    cfg.run_exx = false;
    let mom = covariance_analysis(&cfg);
    let (recs, s) = monte_carlo(&cfg, runs);
    let end = s.times.len() - 1;
    // Every plot of every target is used: 32 targets × (300 + 300) plots (SPEC's schedule:
    // each radar's first plot is its first scan after the start, 1 s and 0.5 s), one
    // pseudo-measurement each (the other sensor's track exists from t = 0).
    assert_eq!(mom.updates, 32 * 600);
    for r in &recs {
        assert_eq!(r.proposed_updates, 32 * 600);
    }
    println!("derived mean of b̂ − b: {:?}", mom.mean.as_slice());
    let names = [
        "range offset",
        "azimuth offset",
        "range scale",
        "azimuth scale",
    ];
    for (k, name) in names.iter().enumerate() {
        let exp = mom.mse(k);
        let sd = mom.mse_sd(k, runs);
        let mc = s.proposed_rmse[end][k].powi(2);
        let claimed = (0..2)
            .map(|i| mom.claimed[(4 * i + k, 4 * i + k)])
            .sum::<f64>()
            / 2.0;
        println!(
            "{name}: Monte Carlo RMSE {:.4e}, derived {:.4e} (sd of MSE {:.1} %), estimator's own {:.4e}",
            mc.sqrt(),
            exp.sqrt(),
            100.0 * sd / exp,
            claimed.sqrt()
        );
        // The Monte Carlo MSE is a weighted sum of (non-central) χ²(1) terms, skewed and
        // ≥ 0, so a Gaussian ±3.5 sd band reaches below zero and cannot fail low (issue
        // 17 §3). Its sampling distribution by moment matching (Satterthwaite): MSE ≈ exp ·
        // χ²(ν)/ν with ν = 2 exp² / sd² (ν ≈ 20–25 here for 20 runs); the two-sided 99.9 %
        // interval [exp·χ²_ν(0.0005)/ν, exp·χ²_ν(0.9995)/ν] is ≈ [0.27, 2.1] × exp, which
        // can fail on both sides. (More runs would narrow it, but 20 runs already take
        // ~15 s in the dev profile; `argus run bias-32` checks 100.)
        let nu = 2.0 * exp * exp / (sd * sd);
        let lo = exp * chi2_quantile(0.0005, nu).unwrap() / nu;
        let hi = exp * chi2_quantile(0.9995, nu).unwrap() / nu;
        println!(
            "{name}: MSE ratio {:.3}, 99.9 % interval [{:.3}, {:.3}] (nu {nu:.1})",
            mc / exp,
            lo / exp,
            hi / exp
        );
        assert!(
            (lo..=hi).contains(&mc),
            "{name}: Monte Carlo MSE {mc:.4e} vs derived {exp:.4e}, 99.9 % interval [{lo:.3e}, {hi:.3e}]"
        );
    }
    // Issue 6's thresholds against the derived values: range offset below 2 m holds with
    // margin; the azimuth offset's derived RMSE is what the 0.2 mrad bound is compared with
    // in docs/papers/004-bias-32.md.
    assert!(mom.mse(0).sqrt() < 2.0);
    assert!(s.proposed_rmse[end][0] < 2.0);
    // The estimator's own Σ is over-confident (ignores the time correlation of the
    // pseudo-measurements): its predicted variance is below the derived one.
    assert!(mom.claimed[(1, 1)] < mom.cov[(1, 1)]);
    // Whole-vector check: the mean NEES of the Monte Carlo errors about the derived mean,
    // with the derived covariance, is χ²(8·runs)/runs: 99.9 % interval for 20 runs
    // [8 − 3.3·sqrt(16/20), 8 + 3.3·sqrt(16/20)] ≈ [5.0, 11.0] (Gaussian approximation).
    let ci = mom.cov.clone().try_inverse().unwrap();
    let anees = recs
        .iter()
        .map(|r| {
            let e =
                DVector::from_iterator(8, r.proposed_final_error.iter().map(|x| -x)) - &mom.mean;
            (e.transpose() * &ci * &e)[(0, 0)]
        })
        .sum::<f64>()
        / runs as f64;
    println!("ANEES about the derived moments: {anees:.2} (8 expected)");
    assert!((5.0..11.0).contains(&anees), "ANEES {anees}");
}

#[test]
fn early_lead_over_exx_and_compensation() {
    // Seed 004 Figs. 3-6 and 8-11 on 10 runs of 60 s (the claims concern the start and
    // the compensated tracks, which settle within 30 s).
    let mut cfg = ScenarioConfig::bias32().unwrap();
    cfg.duration = 60.0;
    let (_, s) = monte_carlo(&cfg, 10);
    // Bias-free starts: the proposed method is ahead of EXX at 10 s.
    let i = s.index_at(10.0);
    assert!(s.proposed_rmse[i][0] < s.exx_rmse[i][0]);
    assert!(s.proposed_rmse[i][1] < s.exx_rmse[i][1]);
    // Compensation helps the far track 32 more than the near track 1 (mean RMSE, 30-60 s).
    let gain = |k: usize| {
        let tr = &s.tracks[k];
        let n = tr.pos_biased.len();
        let m = |v: &Vec<f64>| v[n / 2..].iter().sum::<f64>() / (n - n / 2) as f64;
        m(&tr.pos_biased) - m(&tr.pos_compensated)
    };
    assert!(
        gain(1) > gain(0),
        "gain track 32 {} vs track 1 {}",
        gain(1),
        gain(0)
    );
}

#[test]
fn linearisation_and_initiation_variants() {
    // SPEC §004 findings of an independent re-implementation, checked on 8 runs of 100 s.
    let runs = 8;
    let mut base_cfg = ScenarioConfig::bias32().unwrap();
    base_cfg.duration = 100.0;
    let (_, base) = monte_carlo(&base_cfg, runs);
    let mut cfg = base_cfg.clone();
    cfg.linearization = Linearization::AtPlot;
    let (_, at_plot) = monte_carlo(&cfg, runs);
    let end = base.times.len() - 1;
    // Linearising at the plot puts its noise into the regressor: the final range-offset
    // RMSE is worse than at the prediction (same seeds).
    assert!(at_plot.proposed_rmse[end][0] > base.proposed_rmse[end][0]);
    assert!(at_plot.exx_rmse[end][0] > base.exx_rmse[end][0]);
    let mut cfg = base_cfg.clone();
    cfg.initiation = Initiation::TwoPoint;
    let (_, two_point) = monte_carlo(&cfg, runs);
    // Two-point initiation from biased plots removes most of the early lead over EXX.
    let i = base.index_at(10.0);
    let lead = |s: &Summary| s.exx_rmse[i][0] / s.proposed_rmse[i][0];
    assert!(
        lead(&two_point) < lead(&base),
        "lead {} vs {}",
        lead(&two_point),
        lead(&base)
    );
    // Sequential least squares ignoring the time correlation of successive
    // pseudo-measurements is over-confident: ANEES far above the 8 degrees of freedom
    // (above the 99.9 % bound of the mean of 8 chi-square(8) draws, ≈ 12.4: 8 + 3.1·sqrt(16/8)).
    assert!(
        base.proposed_anees[end] > 12.4,
        "proposed ANEES {}",
        base.proposed_anees[end]
    );
}
