//! The aircraft IMM: mixing across unequal state sizes, mode-matched prediction and
//! (range, azimuth) update, mode probabilities.

use argus_core_math::Vector;
use argus_filters::{GaussianFilter, check_dt};

use super::estimate::{AircraftEstimate, AircraftPrediction};
use super::mixing::{Augmentation, augmented};
use super::radar::AircraftRadar;
use crate::{ImmError, MarkovMatrix, log_sum_exp};

/// Below this a predicted mode probability is recomputed in log space.
const TINY: f64 = 1e-300;

/// An IMM of `C` constant-velocity modes on `[x, vx, y, vy]` (filters `Fcv`) and one
/// coordinated-turn mode with the turn rate as a state, `[x, vx, y, vy, ω]` (filter
/// `Fct`), `R = C + 1` modes in all (CV modes `0..C`, CT mode `C`), updated with
/// (range, azimuth) plots of an [`AircraftRadar`]. See the [module docs](super) for the
/// cycle and the mixing rule.
#[derive(Debug, Clone, PartialEq)]
pub struct AircraftImm<Fcv, Fct, const C: usize, const R: usize> {
    cv: [Fcv; C],
    ct: Fct,
    markov: MarkovMatrix<R>,
    augmentation: Augmentation,
}

/// The result of an update with one plot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AircraftUpdate<const C: usize, const R: usize> {
    /// The posterior.
    pub estimate: AircraftEstimate<C, R>,
    /// `ln Λ = ln Σⱼ μ̄ⱼ Λⱼ`, the plot's log-likelihood under the IMM.
    pub log_likelihood: f64,
    /// `ln Λⱼ` per mode.
    pub mode_log_likelihoods: [f64; R],
}

impl<Fcv, Fct, const C: usize, const R: usize> AircraftImm<Fcv, Fct, C, R>
where
    Fcv: GaussianFilter<4>,
    Fct: GaussianFilter<5>,
{
    /// An IMM of the CV filters `cv` (modes `0..C`) and the CT filter `ct` (mode `C`) with
    /// the transition matrix `markov` (rows and columns in that order) and the mixing rule
    /// `augmentation`.
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] for an invalid [`Augmentation`]. (`R = C + 1` is
    /// checked at compile time; the Markov matrix was validated by [`MarkovMatrix::new`].)
    pub fn new(
        cv: [Fcv; C],
        ct: Fct,
        markov: MarkovMatrix<R>,
        augmentation: Augmentation,
    ) -> Result<Self, ImmError> {
        let () = AircraftEstimate::<C, R>::MODES;
        augmentation.validate()?;
        Ok(Self {
            cv,
            ct,
            markov,
            augmentation,
        })
    }

    /// The CV filters.
    #[must_use]
    pub fn cv_filters(&self) -> &[Fcv; C] {
        &self.cv
    }

    /// The CT filter.
    #[must_use]
    pub fn ct_filter(&self) -> &Fct {
        &self.ct
    }

    /// The transition matrix.
    #[must_use]
    pub fn markov(&self) -> &MarkovMatrix<R> {
        &self.markov
    }

    /// The mixing rule.
    #[must_use]
    pub fn augmentation(&self) -> Augmentation {
        self.augmentation
    }

    /// Mixing (module docs, eqs M1–M3) of `est` into `out` (which holds `est`); returns
    /// `ln μ̄ⱼ` and leaves it in `out`'s probabilities.
    fn mix_into(
        &self,
        est: &AircraftEstimate<C, R>,
        out: &mut AircraftEstimate<C, R>,
    ) -> Result<(), ImmError> {
        let pi = self.markov.matrix();
        let mu = est.log_mu.map(f64::exp);
        let parts4 = est.kinematic_parts()?;
        let (omega, var) = self.augmentation.turn_rate(&est.ct);
        let mut parts5 = [est.ct; R];
        for (p, g) in parts5.iter_mut().zip(&est.cv) {
            *p = augmented(g, omega, var)?;
        }
        for j in 0..R {
            let mut w = [0.0; R];
            let mut c = 0.0;
            for (i, (wi, m)) in w.iter_mut().zip(&mu).enumerate() {
                *wi = pi[(i, j)] * m;
                c += *wi;
            }
            let log_c = if c >= TINY {
                let inv = 1.0 / c;
                for wi in &mut w {
                    *wi *= inv;
                }
                c.ln()
            } else {
                let lc = self.mixing_in_logs(&est.log_mu, j, &mut w);
                if lc == f64::NEG_INFINITY {
                    // Mode j cannot be reached: probability 0, its own estimate kept.
                    out.log_mu[j] = lc;
                    continue;
                }
                lc
            };
            out.log_mu[j] = log_c;
            if j < C {
                out.cv[j].assign_mixture(&w, &parts4)?;
            } else {
                out.ct.assign_mixture(&w, &parts5)?;
            }
        }
        Ok(())
    }

    /// The rare path of mixing (`μ̄ⱼ` below `1e-300`): `ln μ̄ⱼ` by log-sum-exp and the
    /// weights `μᵢ|ⱼ` into `w` (untouched when `ln μ̄ⱼ = −∞`).
    #[cold]
    #[inline(never)]
    fn mixing_in_logs(&self, log_mu: &[f64; R], j: usize, w: &mut [f64; R]) -> f64 {
        let log_pi = self.markov.log_matrix();
        let mut terms = [f64::NEG_INFINITY; R];
        for (i, t) in terms.iter_mut().enumerate() {
            *t = log_pi[(i, j)] + log_mu[i];
        }
        let lc = log_sum_exp(&terms);
        if lc > f64::NEG_INFINITY {
            *w = terms.map(|t| (t - lc).exp());
        }
        lc
    }

    /// Mixing and prediction of `est` over `dt` into `out` (a copy of `est`).
    fn predict_into(
        &self,
        est: &AircraftEstimate<C, R>,
        dt: f64,
        out: &mut AircraftEstimate<C, R>,
    ) -> Result<(), ImmError> {
        check_dt(dt).map_err(|_| ImmError::InvalidInterval { dt })?;
        self.mix_into(est, out)?;
        for (j, (f, g)) in self.cv.iter().zip(out.cv.iter_mut()).enumerate() {
            if let Err(source) = f.predict_in_place(g, dt) {
                return Err(ImmError::Filter { mode: j, source });
            }
        }
        if let Err(source) = self.ct.predict_in_place(&mut out.ct, dt) {
            return Err(ImmError::Filter { mode: C, source });
        }
        Ok(())
    }

    /// Mixing and mode-matched prediction over `dt` seconds.
    ///
    /// # Errors
    /// [`ImmError::InvalidInterval`] when `dt` is not finite and positive;
    /// [`ImmError::Filter`] naming the mode whose prediction failed; [`ImmError::Math`]
    /// if mixing overflowed. `est` is never modified.
    pub fn predict(
        &self,
        est: &AircraftEstimate<C, R>,
        dt: f64,
    ) -> Result<AircraftPrediction<C, R>, ImmError> {
        let mut predicted = *est;
        self.predict_into(est, dt, &mut predicted)?;
        Ok(AircraftPrediction { predicted })
    }

    /// The update of the predictions held in `est` (with `ln μ̄ⱼ` as its probabilities),
    /// in place; returns `(ln Λ, ln Λⱼ)`. On an error `est` is partly updated: callers
    /// work on a copy.
    fn update_in_place(
        &self,
        est: &mut AircraftEstimate<C, R>,
        radar: &AircraftRadar,
        z: &Vector<2>,
    ) -> Result<(f64, [f64; R]), ImmError> {
        AircraftRadar::check_plot(z)?;
        let mut ll = [f64::NEG_INFINITY; R];
        for (j, (f, g)) in self.cv.iter().zip(est.cv.iter_mut()).enumerate() {
            match f.update_in_place(g, radar.cv(), z) {
                Ok(innov) => ll[j] = innov.log_likelihood(),
                Err(source) => return Err(ImmError::Filter { mode: j, source }),
            }
        }
        match self.ct.update_in_place(&mut est.ct, radar.ct(), z) {
            Ok(innov) => ll[C] = innov.log_likelihood(),
            Err(source) => return Err(ImmError::Filter { mode: C, source }),
        }
        // ln μⱼ = ln μ̄ⱼ + ln Λⱼ − ln Λ, ln Λ = ln Σⱼ exp(ln μ̄ⱼ + ln Λⱼ) (log-sum-exp).
        let mut joint = [f64::NEG_INFINITY; R];
        for ((v, lc), l) in joint.iter_mut().zip(&est.log_mu).zip(&ll) {
            *v = lc + l;
        }
        let total = log_sum_exp(&joint);
        if !total.is_finite() {
            return Err(ImmError::NoLikelihood {
                what: "aircraft IMM modes",
            });
        }
        est.log_mu = joint.map(|v| v - total);
        Ok((total, ll))
    }

    /// Mode-matched updates with the plot `z = [r, θ]` of `radar`, likelihoods and mode
    /// probabilities.
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] for a non-finite plot or a range that is not
    /// positive; [`ImmError::Filter`] naming the mode whose update failed;
    /// [`ImmError::NoLikelihood`] if no mode can explain the plot.
    pub fn update(
        &self,
        pred: &AircraftPrediction<C, R>,
        radar: &AircraftRadar,
        z: &Vector<2>,
    ) -> Result<AircraftUpdate<C, R>, ImmError> {
        let mut estimate = pred.predicted;
        let (log_likelihood, mode_log_likelihoods) =
            self.update_in_place(&mut estimate, radar, z)?;
        Ok(AircraftUpdate {
            estimate,
            log_likelihood,
            mode_log_likelihoods,
        })
    }

    /// One full cycle: [`AircraftImm::predict`] over `dt`, then [`AircraftImm::update`]
    /// with `z`.
    ///
    /// # Errors
    /// As [`AircraftImm::predict`] and [`AircraftImm::update`]; `est` is never modified.
    pub fn step(
        &self,
        est: &AircraftEstimate<C, R>,
        dt: f64,
        radar: &AircraftRadar,
        z: &Vector<2>,
    ) -> Result<AircraftUpdate<C, R>, ImmError> {
        AircraftRadar::check_plot(z)?;
        let mut estimate = *est;
        self.predict_into(est, dt, &mut estimate)?;
        let (log_likelihood, mode_log_likelihoods) =
            self.update_in_place(&mut estimate, radar, z)?;
        Ok(AircraftUpdate {
            estimate,
            log_likelihood,
            mode_log_likelihoods,
        })
    }
}
