//! [`ModeTrack`] and [`ForwardRecord`]: what code that records a multiple-model
//! estimator's forward pass and smooths it needs of the track, so that it is written once
//! for the IMM ([`crate::ImmTrack`]) and the aircraft IMM ([`crate::AircraftTrack`]) — a
//! tracker's track rows smoothed after the run, a batch of plots smoothed by windows
//! (fixed lag).

use argus_core_math::Gaussian;
use argus_filters::SmoothingFilter;

use super::{ImmSmoothError, ImmSmoothed, ImmTrack};
use crate::{Imm, ImmEstimate};

/// A recorded forward pass of a multiple-model estimator and its smoother, with the
/// combined estimate on `N` states; [`ForwardRecord`] records it.
///
/// Implemented by [`crate::ImmTrack`] (combined on its own `N` states) and
/// [`crate::AircraftTrack`] (combined on `[x, vx, y, vy]`).
///
/// # Example
/// ```
/// use argus_core_math::{Gaussian, Matrix, Vector};
/// use argus_filters::Kf;
/// use argus_imm::{ForwardRecord, Imm, ImmEstimate, ImmTrack, MarkovMatrix, ModeTrack};
/// use argus_motion_models::Cv2D;
///
/// /// The smoothed combined means of posteriors recorded one per time, whatever the track.
/// fn smoothed_means<T: ForwardRecord<M, 4>, M>(
///     imm: &M,
///     posteriors: Vec<(f64, T::Estimate)>,
/// ) -> Result<Vec<Vector<4>>, argus_imm::ImmSmoothError> {
///     let mut rows = posteriors.into_iter();
///     let (t0, e0) = rows.next().expect("one posterior at least");
///     let mut track = T::start(imm, t0, e0)?;
///     track.reserve(rows.len());
///     for (t, e) in rows {
///         track.push(imm, t, e)?;
///     }
///     let last = track.step_count() - 1;
///     Ok(track.smooth_steps(0, last)?.iter().map(|s| *T::combined(s).mean()).collect())
/// }
///
/// let imm = Imm::new(
///     [Kf::new(Cv2D::discrete(0.1)?), Kf::new(Cv2D::discrete(3.0)?)],
///     MarkovMatrix::new([[0.9, 0.1], [0.1, 0.9]])?,
/// )?;
/// let start = Gaussian::new(Vector::<4>::new(0.0, 10.0, 0.0, 0.0), Matrix::<4, 4>::identity())?;
/// let est = ImmEstimate::from_common(start, [0.5, 0.5])?;
/// // The same posterior at three times (no plots): the smoother runs over the record.
/// let means = smoothed_means::<ImmTrack<4, 2>, _>(&imm, vec![(0.0, est), (1.0, est), (2.0, est)])?;
/// assert_eq!(means.len(), 3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub trait ModeTrack<const N: usize>: Sized {
    /// The estimator's posterior at one time.
    type Estimate;
    /// The smoother's estimate at one step.
    type Smoothed: Copy;

    /// Room for `additional` more steps (no reallocation while recording them).
    fn reserve(&mut self, additional: usize);

    /// The number of steps recorded (at least one).
    fn step_count(&self) -> usize;

    /// The latest step's time.
    fn latest_time(&self) -> f64;

    /// The smoother (default pair weights) over steps `first ..= last` alone: one
    /// smoothed estimate per step, `last`'s the filter's. Over `0 ..= step_count() − 1` it
    /// is the fixed-interval smoother; a window ending earlier ignores the later plots
    /// (a fixed-lag smoother's window).
    ///
    /// # Errors
    /// The recorded failure; [`argus_filters::SmoothError::LengthMismatch`] (inside
    /// [`ImmSmoothError::Sequence`]) for a window that is empty or reaches past the latest
    /// step; [`ImmSmoothError::Backward`] for a numerical failure.
    fn smooth_steps(
        &self,
        first: usize,
        last: usize,
    ) -> Result<Vec<Self::Smoothed>, ImmSmoothError>;

    /// A smoothed step's combined estimate.
    fn combined(smoothed: &Self::Smoothed) -> &Gaussian<N>;

    /// A smoothed step's mode probabilities.
    fn mode_probabilities(smoothed: &Self::Smoothed) -> &[f64];
}

/// A [`ModeTrack`] recorded from the forward pass of the estimator `M`: [`crate::ImmTrack`]
/// from an [`crate::Imm`] of smoothing filters, [`crate::AircraftTrack`] from an
/// [`crate::AircraftImm`].
pub trait ForwardRecord<M, const N: usize>: ModeTrack<N> {
    /// A record whose first step (step 0) is `estimate` at `time`, with `imm`'s Markov
    /// matrix.
    ///
    /// # Errors
    /// [`ImmSmoothError`] for a non-finite `time`.
    fn start(imm: &M, time: f64, estimate: Self::Estimate) -> Result<Self, ImmSmoothError>;

    /// Records `estimate`, the posterior of `imm` at `time`, as the next step: its
    /// transition from the latest step is recomputed by `imm`.
    ///
    /// # Errors
    /// [`ImmSmoothError`] for a time not after the latest step or a failed prediction
    /// (both recorded: every later call fails with it).
    fn push(&mut self, imm: &M, time: f64, estimate: Self::Estimate) -> Result<(), ImmSmoothError>;
}

impl<const N: usize, const R: usize> ModeTrack<N> for ImmTrack<N, R> {
    type Estimate = ImmEstimate<N, R>;
    type Smoothed = ImmSmoothed<N, R>;

    fn reserve(&mut self, additional: usize) {
        ImmTrack::reserve(self, additional);
    }

    fn step_count(&self) -> usize {
        self.steps().len()
    }

    fn latest_time(&self) -> f64 {
        self.steps()[self.steps().len() - 1].time()
    }

    fn smooth_steps(
        &self,
        first: usize,
        last: usize,
    ) -> Result<Vec<ImmSmoothed<N, R>>, ImmSmoothError> {
        self.smooth_window(first, last)
    }

    fn combined(smoothed: &ImmSmoothed<N, R>) -> &Gaussian<N> {
        &smoothed.combined
    }

    fn mode_probabilities(smoothed: &ImmSmoothed<N, R>) -> &[f64] {
        &smoothed.mode_probabilities
    }
}

impl<F: SmoothingFilter<N>, const N: usize, const R: usize> ForwardRecord<Imm<F, N, R>, N>
    for ImmTrack<N, R>
{
    fn start(
        imm: &Imm<F, N, R>,
        time: f64,
        estimate: ImmEstimate<N, R>,
    ) -> Result<Self, ImmSmoothError> {
        Self::new(*imm.markov(), time, estimate)
    }

    fn push(
        &mut self,
        imm: &Imm<F, N, R>,
        time: f64,
        estimate: ImmEstimate<N, R>,
    ) -> Result<(), ImmSmoothError> {
        ImmTrack::push(self, imm, time, estimate)
    }
}
