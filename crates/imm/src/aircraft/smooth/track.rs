//! The record of an aircraft-IMM forward pass for smoothing.

use argus_core_math::{Matrix, Vector};
use argus_filters::{SmoothError, SmoothingFilter};

use super::backward::{AircraftSmoothed, aircraft_smooth};
use super::pair::{PairTransition, ct_to_cv_cross};
use super::step::{AircraftStep, AircraftTransition};
use crate::aircraft::mixing::{augmented, kinematic_marginal};
use crate::aircraft::{AircraftEstimate, AircraftImm, AircraftRadar, AircraftUpdate};
use crate::markov::log_sum_exp;
use crate::smooth::Record;
use crate::{ImmError, ImmSmoothError, MarkovMatrix, PairWeights};

/// The transition from the posterior `prev` over `dt` (module docs, forward record):
/// the mixing maps of [`AircraftImm`] (identity, the CT marginal, the augmentation with
/// the IMM's own [`crate::Augmentation`] of `prev`'s CT mode), then each model's
/// [`SmoothingFilter::predict_with_cross`].
///
/// # Errors
/// [`ImmError::Filter`] naming the model whose prediction failed; [`ImmError::Math`]
/// for a mixing map that failed numerically.
pub(super) fn transition<Fcv, Fct, const C: usize, const R: usize>(
    imm: &AircraftImm<Fcv, Fct, C, R>,
    prev: &AircraftEstimate<C, R>,
    dt: f64,
) -> Result<AircraftTransition<C, R>, ImmError>
where
    Fcv: SmoothingFilter<4>,
    Fct: SmoothingFilter<5>,
{
    let filter = |mode: usize| move |source| ImmError::Filter { mode, source };
    let cvf = imm.cv_filters();
    let ctf = imm.ct_filter();
    // CT → CT.
    let tr = ctf.predict_with_cross(&prev.ct, dt).map_err(filter(C))?;
    let ct_ct = PairTransition::new(*tr.predicted(), *tr.cross())?;
    // CT → CV j: the marginal, its cross covariance extended to ω by regression.
    let marginal = kinematic_marginal(&prev.ct)?;
    let mut ct_cv = [PairTransition::new(marginal, Matrix::zeros())?; C];
    for (j, (f, out)) in cvf.iter().zip(ct_cv.iter_mut()).enumerate() {
        let tr = f.predict_with_cross(&marginal, dt).map_err(filter(j))?;
        *out = PairTransition::new(*tr.predicted(), ct_to_cv_cross(&prev.ct, tr.cross())?)?;
    }
    // CV i → CT: [x̂ᵢ; ω̂ᵃ], diag(Pᵢ, σᵃ²); xᵢ is the augmented state's first four
    // components, so Cov(xᵢ, x⁻) is the first four rows of the 5 × 5 cross covariance.
    let (omega, var) = imm.augmentation().turn_rate(&prev.ct);
    let mut cv_ct = [PairTransition::new(*ct_ct.predicted(), Matrix::zeros())?; C];
    for (g, out) in prev.cv.iter().zip(cv_ct.iter_mut()) {
        let aug = augmented(g, omega, var)?;
        let tr = ctf.predict_with_cross(&aug, dt).map_err(filter(C))?;
        let cross: Matrix<4, 5> = tr.cross().fixed_view::<4, 5>(0, 0).into_owned();
        *out = PairTransition::new(*tr.predicted(), cross)?;
    }
    // CV i → CV j: identity.
    let mut cv_cv = [[PairTransition::new(marginal, Matrix::zeros())?; C]; C];
    for (g, row) in prev.cv.iter().zip(cv_cv.iter_mut()) {
        for (j, (f, out)) in cvf.iter().zip(row.iter_mut()).enumerate() {
            let tr = f.predict_with_cross(g, dt).map_err(filter(j))?;
            *out = PairTransition::new(*tr.predicted(), *tr.cross())?;
        }
    }
    // ln μ̄ⱼ = ln Σᵢ πᵢⱼ μᵢ (log-sum-exp over the kept logarithms).
    let log_pi = imm.markov().log_matrix();
    let log_mu = prev.log_mode_probabilities();
    let log_cbar = core::array::from_fn(|j| {
        let terms: [f64; R] = core::array::from_fn(|i| log_pi[(i, j)] + log_mu[i]);
        log_sum_exp(&terms)
    });
    Ok(AircraftTransition {
        cv_cv,
        cv_ct,
        ct_cv,
        ct_ct,
        log_cbar,
    })
}

/// An aircraft-IMM forward pass recorded for smoothing (the equations: the module docs of
/// `aircraft::smooth`).
///
/// [`AircraftTrack::step`] runs one [`AircraftImm::step`] and records it;
/// [`AircraftTrack::push`] records a posterior the caller computed with the same IMM
/// (plots of one instant applied in turn, coasting via
/// [`crate::AircraftPrediction::into_estimate`], a tracker's track). A failed step is
/// recorded: every later call and [`AircraftTrack::smooth`] return it, naming the step.
#[derive(Debug, Clone, PartialEq)]
pub struct AircraftTrack<const C: usize, const R: usize> {
    markov: MarkovMatrix<R>,
    record: Record<AircraftStep<C, R>>,
}

impl<const C: usize, const R: usize> AircraftTrack<C, R> {
    /// A track of an IMM with transition matrix `markov`, starting at `time` with
    /// `initial` (step 0).
    ///
    /// # Errors
    /// [`SmoothError::TimeNotIncreasing`] for a non-finite `time`.
    pub fn new(
        markov: MarkovMatrix<R>,
        time: f64,
        initial: AircraftEstimate<C, R>,
    ) -> Result<Self, ImmSmoothError> {
        Ok(Self {
            markov,
            record: Record::new(AircraftStep {
                time,
                transition: None,
                filtered: initial,
            })?,
        })
    }

    /// The record of posteriors `estimates[k]` at `times[k]` computed by `imm` (one per
    /// step, in time order).
    ///
    /// # Errors
    /// [`SmoothError::LengthMismatch`] when the two lengths differ,
    /// [`SmoothError::Empty`] when there is none; as [`AircraftTrack::push`].
    pub fn from_posteriors<Fcv, Fct>(
        imm: &AircraftImm<Fcv, Fct, C, R>,
        times: &[f64],
        estimates: &[AircraftEstimate<C, R>],
    ) -> Result<Self, ImmSmoothError>
    where
        Fcv: SmoothingFilter<4>,
        Fct: SmoothingFilter<5>,
    {
        if times.len() != estimates.len() {
            return Err(SmoothError::LengthMismatch {
                what: "aircraft IMM posteriors (against their times)",
                expected: times.len(),
                found: estimates.len(),
            }
            .into());
        }
        let (Some(t0), Some(e0)) = (times.first(), estimates.first()) else {
            return Err(SmoothError::Empty.into());
        };
        let mut track = Self::new(*imm.markov(), *t0, *e0)?;
        track.record.reserve(times.len() - 1);
        for (t, e) in times.iter().zip(estimates).skip(1) {
            track.push(imm, *t, *e)?;
        }
        Ok(track)
    }

    /// Room for `additional` more steps (no reallocation while recording them).
    pub fn reserve(&mut self, additional: usize) {
        self.record.reserve(additional);
    }

    /// The transition matrix.
    #[must_use]
    pub fn markov(&self) -> &MarkovMatrix<R> {
        &self.markov
    }

    /// The recorded steps.
    #[must_use]
    pub fn steps(&self) -> &[AircraftStep<C, R>] {
        self.record.steps()
    }

    /// The latest posterior.
    #[must_use]
    pub fn latest(&self) -> &AircraftEstimate<C, R> {
        &self.record.latest().filtered
    }

    /// The failure recorded, if any.
    #[must_use]
    pub fn failure(&self) -> Option<&ImmSmoothError> {
        self.record.failure()
    }

    /// Records `estimate`, the posterior at `time` of `imm` run from the latest step:
    /// forms the transition from the latest posterior (`2 C + C² + 1` predictions).
    ///
    /// # Errors
    /// [`SmoothError::TimeNotIncreasing`] (inside [`ImmSmoothError::Sequence`]) or
    /// [`ImmSmoothError::ForwardFailed`] when a pair's prediction fails; both recorded.
    pub fn push<Fcv, Fct>(
        &mut self,
        imm: &AircraftImm<Fcv, Fct, C, R>,
        time: f64,
        estimate: AircraftEstimate<C, R>,
    ) -> Result<(), ImmSmoothError>
    where
        Fcv: SmoothingFilter<4>,
        Fct: SmoothingFilter<5>,
    {
        let (step, dt) = self.record.next_interval(time)?;
        self.append(imm, step, dt, time, estimate)
    }

    /// Appends `estimate` at `time` as step `step`, `dt` after the latest, with the
    /// transition from the latest posterior.
    fn append<Fcv, Fct>(
        &mut self,
        imm: &AircraftImm<Fcv, Fct, C, R>,
        step: usize,
        dt: f64,
        time: f64,
        estimate: AircraftEstimate<C, R>,
    ) -> Result<(), ImmSmoothError>
    where
        Fcv: SmoothingFilter<4>,
        Fct: SmoothingFilter<5>,
    {
        let tr = transition(imm, self.latest(), dt);
        let tr = self.record.forward(step, tr)?;
        self.record.push(AircraftStep {
            time,
            transition: Some(tr),
            filtered: estimate,
        });
        Ok(())
    }

    /// One [`AircraftImm::step`] from the latest step to `time` with the plot `z` of
    /// `radar`, recorded; returns the IMM's update.
    ///
    /// # Errors
    /// As [`AircraftTrack::push`]; [`ImmSmoothError::ForwardFailed`] when the IMM step
    /// fails (recorded).
    pub fn step<Fcv, Fct>(
        &mut self,
        imm: &AircraftImm<Fcv, Fct, C, R>,
        time: f64,
        radar: &AircraftRadar,
        z: &Vector<2>,
    ) -> Result<AircraftUpdate<C, R>, ImmSmoothError>
    where
        Fcv: SmoothingFilter<4>,
        Fct: SmoothingFilter<5>,
    {
        let (step, dt) = self.record.next_interval(time)?;
        let upd = imm.step(self.latest(), dt, radar, z);
        let upd = self.record.forward(step, upd)?;
        self.append(imm, step, dt, time, upd.estimate)?;
        Ok(upd)
    }

    /// Fixed-interval smoothing of the whole track (default pair weights).
    ///
    /// # Errors
    /// A recorded failure; [`ImmSmoothError::Backward`] for a numerical failure.
    pub fn smooth(&self) -> Result<Vec<AircraftSmoothed<C, R>>, ImmSmoothError> {
        self.smooth_with(PairWeights::default())
    }

    /// [`AircraftTrack::smooth`] with the chosen pair weights.
    ///
    /// # Errors
    /// As [`AircraftTrack::smooth`].
    pub fn smooth_with(
        &self,
        weights: PairWeights,
    ) -> Result<Vec<AircraftSmoothed<C, R>>, ImmSmoothError> {
        aircraft_smooth(&self.markov, weights, self.record.to_smooth()?)
    }

    /// [`AircraftTrack::smooth`] over steps `first ..= last` alone (a fixed-lag smoother's
    /// window: the later plots ignored, `last`'s estimate the filter's).
    ///
    /// # Errors
    /// As [`AircraftTrack::smooth`]; [`SmoothError::LengthMismatch`] for a window that is
    /// empty or reaches past the latest step.
    pub fn smooth_window(
        &self,
        first: usize,
        last: usize,
    ) -> Result<Vec<AircraftSmoothed<C, R>>, ImmSmoothError> {
        aircraft_smooth(
            &self.markov,
            PairWeights::default(),
            self.record.window(first, last)?,
        )
    }
}
